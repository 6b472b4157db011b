// Shadow pass of the paraboloid technique: one hemisphere per draw. Frame.viewProj is the
// hemisphere's frame (world -> light-relative, axis along z), not a projection: the paraboloid
// mapping (x, y) / (1 + z) of the unit direction is not a linear map of homogeneous coordinates,
// so the vertex shader applies it per vertex and writes w = 1. The rasterizer then interpolates
// screen position, depth and everything else linearly across the triangle in paraboloid space,
// while the true mapping of a straight edge or a flat face is curved: a large triangle's edges and
// depth are wrong between its vertices. That is the technique's known failure, kept as it is.
//
// Vertices behind the hemisphere (z < 0) map outside the unit disk, towards infinity near z = -1;
// a triangle with such a vertex would smear across the map. The pixel shader drops fragments
// whose interpolated z is below parabDiscardZ (slightly negative, so the rim is drawn a few texels
// wide for the filter), as Brabec et al. do; a triangle wholly behind is dropped exactly, since
// its interpolated z stays below the threshold. SV_ClipDistance would do it before rasterizing,
// but needs GL_CLIP_DISTANCEi and Vulkan's shaderClipDistance, which the RHI does not expose.
//
// SP_PARABOLOID_EXACT=1 (depth=exact): the pixel shader writes SV_Depth, the distance along the
// texel centre's own direction to the triangle's plane, so only the silhouette error (which
// texels a triangle covers) remains, separated from the depth interpolation error. The
// rasterizer bias does not reach a written depth, so the shader adds its own: parabExactBias in world
// units plus slope_bias times the depth's larger screen derivative, as D3D11's slope term.
//! vs_5_0 VSMain
//! ps_5_0 PSMain
#include "common/frame.hlsli"
#include "paraboloid/constants.hlsli"

#ifndef SP_PARABOLOID_EXACT
#define SP_PARABOLOID_EXACT 0
#endif

struct VSOut {
  float4 pos : SV_Position;
  float3 rel : LIGHTREL;  // light-relative position in the hemisphere frame
  float frameZ : FRAMEZ;  // z of the unit direction
};

VSOut VSMain(float3 pos : POSITION) {
  VSOut o;
  float3 d = mul(viewProj, mul(world, float4(pos, 1.0))).xyz;
  float L = length(d);
  float3 n = L > 0.0 ? d / L : float3(0.0, 0.0, 1.0);
  // Bounded near z = -1 (the dropped side): a finite position keeps the interpolation defined.
  o.pos = float4(n.xy / max(1.0 + n.z, 1e-3), ParaboloidDepth(L), 1.0);
  o.rel = d;
  o.frameZ = n.z;
  return o;
}

#if SP_PARABOLOID_EXACT
float PSMain(VSOut i) : SV_Depth {
  // The interpolated position lies on the triangle's plane, but not on the ray of this pixel: the
  // interpolation is linear in paraboloid space. Its screen derivatives are constant across the
  // triangle and span the plane, so the plane is known exactly; intersect it with the direction
  // this texel's centre stands for (the inverse mapping) for the true distance. Where the ray
  // grazes the plane or misses it, the interpolated point's distance stands in.
  float3 plane = cross(ddx(i.rel), ddy(i.rel));
  float2 ndc = float2(i.pos.x, parabMapSize - i.pos.y) * (2.0 / parabMapSize) - 1.0;
  float q = dot(ndc, ndc);
  float3 ray = float3(2.0 * ndc, 1.0 - q) / (1.0 + q);
  float along = dot(plane, ray);
  float t = abs(along) > 1e-4 * length(plane) ? dot(plane, i.rel) / along : -1.0;
  float z = ParaboloidDepth(t > 0.0 ? t : length(i.rel));
  // D3D11's slope term, on the written depth (derivatives before the clip).
  float slope = max(abs(ddx(z)), abs(ddy(z)));
  clip(i.frameZ - parabDiscardZ);
  return saturate(z + parabExactBias / (parabRange - parabNear) + parabExactSlope * slope);
}
#else
void PSMain(VSOut i) { clip(i.frameZ - parabDiscardZ); }
#endif
