// Included by states.fx: a sampler state in an include file.
#ifndef SCALE
#define SCALE 1
#endif
Texture2D g_tex : register(t1);
SamplerState samLinear { Filter = ANISOTROPIC; AddressU = MIRROR_ONCE; AddressV = Mirror; };
