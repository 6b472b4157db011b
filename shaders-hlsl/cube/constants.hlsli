// cbuffer CubeShadow of the cube technique (techniques/cube/cube-technique.cpp, Constants), read by
// its lighting include and by the radial-distance shadow pass.
#ifndef SP_CUBE_CONSTANTS_HLSLI
#define SP_CUBE_CONSTANTS_HLSLI

// One shadowed point light: its cube is CubeShadowMap<k> (t<k>) for slot k.
struct CubeSlot {
  float3 lightPos;
  float depthA;    // storage=depth: window z = depthA + depthB / major axis
  float depthB;
  float faceSize;  // texels
  uint light;      // local light index; 0xffffffff for an unused slot
  float range;
};

#define SP_CUBE_MAX_SLOTS 8

cbuffer CubeShadow : register(b2) {
  float3 cubePassLightPos;  // the light whose faces are being rendered (the radial pass)
  float cubeRadialBias;     // storage=radial: constant bias, world units
  float cubeRadialSlope;    // storage=radial: times the receiver's distance change across a texel
  uint cubeLabSlot;         // the slot of the light the lab judges; SP_CUBE_MAX_SLOTS for none
  float2 padCubeShadow;
  CubeSlot cubeSlots[SP_CUBE_MAX_SLOTS];
  float4 cubePcss;  // filter=pcss: the light sphere's radius (world units), search taps, max kernel, unused
};

#endif
