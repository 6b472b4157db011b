// cbuffer CubeShadow of the cube technique (techniques/cube/cube-technique.cpp, Constants), read by
// its lighting include and by the radial-distance shadow pass.
#ifndef SP_CUBE_CONSTANTS_HLSLI
#define SP_CUBE_CONSTANTS_HLSLI

cbuffer CubeShadow : register(b2) {
  float3 cubeLightPos;
  float cubeDepthA;       // storage=depth: window z = cubeDepthA + cubeDepthB / major axis
  float cubeDepthB;
  float cubeFaceSize;     // texels
  uint cubeLightIndex;    // the local light this map shadows
  float cubeRange;
  float cubeRadialBias;   // storage=radial: constant bias, world units
  float cubeRadialSlope;  // storage=radial: times the receiver's distance change across a texel
  float2 padCubeShadow;
};

#endif
