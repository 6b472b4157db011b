// A geometry shader: one triangle in, the same triangle out (its entry is found from
// [maxvertexcount]; the RHI does not create geometry shaders yet, but they compile).
struct GSVertex {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
};

[maxvertexcount(3)]
void ExpandGS(triangle GSVertex input[3], inout TriangleStream<GSVertex> stream) {
  for (int i = 0; i < 3; ++i) stream.Append(input[i]);
  stream.RestartStrip();
}
