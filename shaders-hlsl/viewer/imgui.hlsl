// Dear ImGui's draw lists through the RHI (samples/viewer/ui/imgui-renderer.cpp): vertices in
// pixels of the display, a colour per vertex (R8G8B8A8_UNORM, what ImDrawVert holds) times one
// texture (the font atlas, or a picture the panel shows), blended SrcAlpha / InvSrcAlpha by the
// pipeline.
//! vs_5_0 VSMain
//! ps_5_0 PSMain

cbuffer ImGuiFrame : register(b0) {
  // clip.xy = pixel * scale + offset: maps ImDrawData's DisplayPos..DisplayPos+DisplaySize onto
  // [-1, 1] with y pointing down the screen, as ImGui's pixels do.
  float2 scale;
  float2 offset;
};

Texture2D picture : register(t0);
SamplerState linearSampler : register(s0);

struct VSIn {
  float2 pos : POSITION;
  float2 uv : TEXCOORD0;
  float4 color : COLOR0;
};

struct PSIn {
  float4 pos : SV_Position;
  float4 color : COLOR0;
  float2 uv : TEXCOORD0;
};

PSIn VSMain(VSIn v) {
  PSIn o;
  o.pos = float4(v.pos * scale + offset, 0.0, 1.0);
  o.color = v.color;
  o.uv = v.uv;
  return o;
}

#ifndef SRGB_TARGET
#define SRGB_TARGET 0
#endif

float3 SrgbToLinear(float3 c) {
  return lerp(pow((c + 0.055) / 1.055, 2.4), c / 12.92, step(c, 0.04045));
}

float4 PSMain(PSIn i) : SV_Target {
  float4 c = i.color * picture.Sample(linearSampler, i.uv);
#if SRGB_TARGET
  // ImGui's colours are sRGB-encoded values meant to land in the back buffer as they are; an sRGB
  // target encodes what the shader writes, so decode first (blending then happens on linear values).
  c.rgb = SrgbToLinear(c.rgb);
#endif
  return c;
}
