// cbuffer ParaboloidShadow of the paraboloid technique (techniques/paraboloid/paraboloid-technique.cpp,
// Constants), read by its shadow pass and its lighting include.
#ifndef SP_PARABOLOID_CONSTANTS_HLSLI
#define SP_PARABOLOID_CONSTANTS_HLSLI

cbuffer ParaboloidShadow : register(b2) {
  // World -> front hemisphere frame: rows of the rotation, translation in w. The back hemisphere
  // is the same frame with z negated.
  float4 parabFrame[3];
  float parabNear;
  float parabRange;       // the light's range: depth 1
  float parabMapSize;     // texels per hemisphere side
  uint parabLightIndex;   // the local light this map shadows
  float parabDiscardZ;    // shadow pass: frame z (unit direction) below which a fragment is dropped
  float parabExactBias;   // depth=exact: world units added to the distance written
  float parabExactSlope;  // depth=exact: times the written depth's larger screen derivative
  float padParaboloidShadow;
};

// Depth of a point at `distance` from the light: linear, the same in both hemispheres.
float ParaboloidDepth(float distance) { return (distance - parabNear) / (parabRange - parabNear); }

#endif
