// A shared include as D3D-era libraries wrote it: a quad table with each member braced and no
// braces per element (fxc accepts it; glslang alone rejects every shader that includes it).
struct QuadVertex { float4 pos; float2 uv; };
static const QuadVertex kQuad[6] = {
  { -1, -1, 0, 1 }, { 0, 1 },  { -1, 1, 0, 1 }, { 0, 0 },  { 1, 1, 0, 1 }, { 1, 0 },
  { -1, -1, 0, 1 }, { 0, 1 },  { 1, 1, 0, 1 }, { 1, 0 },   { 1, -1, 0, 1 }, { 1, 1 } };
