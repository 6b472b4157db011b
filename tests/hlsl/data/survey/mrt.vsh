// A vertex shader whose position is an out parameter.
cbuffer Object : register(b1) {
  float4x4 world;
};

void FullscreenVS(uint id : SV_VertexID, out float4 pos : SV_Position, out float2 uv : TEXCOORD0) {
  uv = float2((id << 1) & 2, id & 2);
  pos = mul(world, float4(uv * 2.0 - 1.0, 0.0, 1.0));
}
