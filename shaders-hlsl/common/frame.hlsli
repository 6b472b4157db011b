// Constants shared by the lit pass and the shadow passes.
// Register plan (see docs/porting.md): b0 frame, b1 object, b2..b5 and t0..t15, s0..s3 belong to the
// shadow technique; b6 holds the lit pass's local lights (common/local-lights.hlsli).
#ifndef SP_FRAME_HLSLI
#define SP_FRAME_HLSLI

cbuffer Frame : register(b0) {
  float4x4 viewProj;      // world -> clip of the camera (or of the light in shadow passes)
  float3 cameraPos;
  float ambient;
  float3 toLight;         // unit vector towards the directional light
  float frameTime;
  float3 lightColor;
  float padFrame;
};

cbuffer Object : register(b1) {
  float4x4 world;
  float3 albedo;
  float padObject;
};

#endif
