// ps_5_0
struct V { float4 p; float2 uv; };
static const V verts[2] = { -1, -1, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1 };
float4x4 m;
float4 main() : SV_Target {
  float3 t = m._41_42_43;
  for (int i = 0; i < 2; ++i) t += verts[i].p.xyz;
  return float4(t * i, 1);
}
