// Include-only: declarations the entry points share, no entry point of its own.
cbuffer Frame : register(b0) {
  float4x4 viewProj;
  float4 tint;
};

struct VSOut {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
};
