// A compute shader; TILE is set by the build (the manifest passes it), with a default here.
#ifndef TILE
#define TILE 8
#endif
Texture2D<float4> input : register(t0);
RWTexture2D<float4> output : register(u0);

[numthreads(TILE, TILE, 1)]
void BlurCS(uint3 id : SV_DispatchThreadID) {
  output[id.xy] = 0.25 * (input[id.xy] + input[id.xy + uint2(1, 0)] + input[id.xy + uint2(0, 1)] + input[id.xy + uint2(1, 1)]);
}
