// The CPU math of perspective shadow-map warps (issue 12, first step): PSM, LiSPSM and TSM for a
// directional light, and the uniform focused map every one of them degrades to. Pure math on a
// camera, a light direction and the body of interest, so tests and the lab can check it without
// a device.
//
// Spaces and conventions
//   World -> light view: right-handed, looking down -z along the light's travel direction L (as
//   csm's SharedLightView), but with its origin at the camera and its y axis the view direction's
//   component perpendicular to L (the "warp axis"; the camera's up vector where the view is
//   parallel to L). In light view the viewer sits at the origin and looks towards +y; X is a
//   light-view x, Y a light-view y.
//   Clip: D3D11, x and y in [-1, 1] after the divide, z in [0, 1]; texture row 0 at the top. The
//   near side of the body (small Y, where the camera is) is mapped to the top rows.
//   The body of interest B: the view-frustum slice [d0, d1] clipped to the scene bounds (csm's
//   SliceCorners / SliceBoxIntersection, see MakeWarpInput). The casters that matter: the part of
//   the caster bounds inside B's light-view x/y box, extruded towards the light.
//
// Everything is computed in double and rounded to float once, in the result. One structure for
// every warp: a shadow map of a directional light whose matrix is a 4x4 sends every light ray to
// one texel, so its x, y and w rows have no component along L: they are a 2D homography H of the
// light-view plane (X, Y). The warps differ only in H:
//   none    H = identity (orthographic)                         u = X, v = Y, w = 1
//   LiSPSM  perspective along the warp axis, centre n before B   u = X, v = Y - y0, w = 1 + k (Y - y0)
//   TSM     the same family, k from the trapezoid's focus line  (the 2DH maps its trapezoid to the square)
//   PSM     H induced by the camera's post-projective space, see below
// followed by the same fit (FitRows): the bounding rectangle of u/w, v/w over B maps to [-1, 1]
// (unit-cube clipping), and the depth row. Depth: t = (distance along L) / w; far = max over B,
// near = min over B and its casters. So viewProj's depth is post-projective (what a depth buffer
// stores when viewProj is used as is, not linear in light space for a warp); WarpFit::linearDepth
// is the light-space linear alternative (its own row, not divided by w: the TSM paper handles z
// separately, the shader writes linearDepth * w to clip z, or stores it in an R32 target).
// Casters between B and the light land in [0, 1] (the near plane is at the nearest of them);
// anything else nearer the light than that lands in front of the near plane (z < 0: clamped by
// depth clamping, pancaked, as in csm).
//
// LiSPSM (Wimmer, Scherzer, Purgathofer 2004). The perspective P has its eye on the line through
// the camera (X = 0) parallel to the warp axis, at distance n before B's near side y0 = min Y
// over B; with k = 1/n, w = 1 + k (Y - y0) is P's homogeneous w (Y - y0 + n) divided by n, so k = 0 is exactly
// the uniform map. The paper's optimum n_opt = (z_n + sqrt(z_n z_f)) / sin(gamma) is written in
// view depths; it comes from equalising the perspective error y^2 / z at both ends of B when view
// depth z grows linearly along the warp axis (y = n + (z - z_n) d / (z_f - z_n)): that gives
// n = d sqrt(z_n) / (sqrt(z_f) - sqrt(z_n)) = d (z_n + sqrt(z_n z_f)) / (z_f - z_n). We use
//   n_opt = d / (z_f - z_n) * (z_n + sqrt(z_n z_f)) / sin(gamma),
// d = B's extent along the warp axis (light-space units), z_n, z_f = B's nearest and farthest view
// depths: the paper's formula in light-space units (identical to it for the whole frustum at
// gamma = 90 degrees, where d = z_f - z_n), with its 1/sin(gamma) that weakens the warp as the
// light turns parallel to the view. n = lispsmScale * n_opt. Fallback rule: k = sin(gamma) /
// (lispsmScale * ...) goes to 0 continuously as gamma -> 0 or 180 degrees, so the map tends to the
// uniform one with no threshold and no pop; k = 0 exactly at gamma = 0, 180, for a flat body or
// lispsmScale = +inf. At k = 1/n_opt and gamma = 90 the texel density along the view is
// z_f / z_n times higher at B's near end than at its far end (sqrt(z_f / z_n) across it), the
// ratio of the screen's own densities: equal perspective error at both ends, the paper's point.
//
// TSM (Martin and Tan 2004). In the light's post-perspective space (for a directional light the
// orthographic light view), B projects to a 2D point set; the centre line is the projection of the
// camera's axis (through the near and far centres), here the warp axis through the camera. The
// top and base lines are perpendicular to it and touch B's 2D convex hull at Y = y0 and Y = y1
// (lambda = y1 - y0). The apex q lies on the centre line at distance eta before the top line, the
// sides pass through q and touch the hull, and the 2D homography (2DH) maps this trapezoid to the
// square. The 2DH is the perspective from q along the centre line followed by a scale, i.e. the
// LiSPSM family above with k = 1/eta; the hull is implicit (the extremes of u/w and v/w over B are
// attained at hull vertices), and WarpFit::trapezoid gives its corners. The 80 % rule: the focus
// line, perpendicular to the centre line through the camera axis at view depth
// z_n + tsmFocusDepth (z_f - z_n), at distance delta from the top, maps to v = tsmFocus (0.8):
// with v(t) = t (1 + k lambda) / (lambda (1 + k t)), t = Y - y0, v(delta) = xi gives
//   k = (xi - delta / lambda) / (delta (1 - xi)),
// which is 1 / eta for the paper's eta = lambda delta (1 + xi_p) / (lambda - 2 delta - lambda xi_p)
// written in its [-1, 1] terms, xi_p = 1 - 2 xi (-0.6 for 80 %),
// clamped at 0 (a focus line already at or beyond xi needs no warp: uniform). Fallback rule: the
// centre line degenerates as the light turns parallel to the view, so k is multiplied by
// fade(gamma') = smoothstep(5, 20 degrees, gamma'), gamma' = min(gamma, 180 - gamma).
// Depth: TSM's paper keeps z linear in light space; its fit sets preferLinearDepth.
//
// PSM (Stamminger and Drettakis 2002, with Kozlov's fixes, GPU Gems ch. 14). The shadow map is
// rendered in the post-projective space of a virtual camera: the real one slid back along its
// axis by s = s_min + psmSlideBack (z_f - z_n), s_min the least that puts B and its casters at
// least z_n / 2 in front of it (Kozlov's virtual slide-back: nothing crosses the camera plane),
// with the near plane at the nearest of them and the far plane at infinity (Z-infinity: the
// light's post-projective image then lies on z = 1, never inside B). The directional light
// becomes the homogeneous point Lh = PV' (-L, 0) = (l, lw): a point light at l / lw when lw > 0
// (light in front of the viewer), a point "beyond infinity" when lw < 0 (light behind the viewer:
// Kozlov's inverted projection, the rays converge behind the scene and depth order along them is
// reversed), a direction when lw = 0 (light parallel to the view plane). One formula covers all
// three: ray directions D(Q) = lw Q - l for post-projective points Q, the light camera's axis
// a = normalize(lw c - l) (c = centre of B's post-projective bounding box: the light looks at
// B), and its homogeneous depth w = a . D(Q), smooth through lw = 0. Pulled back to the world, w
// has no component along L (a . D(Lh) = 0), so PSM is again a 2D homography of the light view;
// its image rows are taken as u = X, v = Y - y0 (any two such rows give the same image up to an
// affine map; these keep the map aligned with the uniform one and are independent of w while
// w(P0) > 0 at P0 = (X, Y) = (0, y0)). psmSlideBack is Kozlov's near-plane / Z-infinity knob:
// more slide-back moves the virtual near plane away relative to the far, a milder warp (near/far
// density (z_f + s)^2 / (z_n + s)^2 on the ground at gamma = 90); +inf is the uniform map. The
// default 0.3: with the least slide-back the post-projective light sits against B's far face
// for most lights not perpendicular to the view, and PSM would fall back over most of the sweep.
// Fallback rule: PSM is degenerate when a point of B or its casters is (nearly) behind the light
// camera's plane through its centre (duelling frusta, light near the view axis) or the 2D map
// is near singular. With cmin = min over those points of a . D / |D| (cosine of the angle from
// the axis) and r = w(P0) / min over B of w, the PSM matrix W is blended with the uniform matrix
// U as (1 - b) U + b W, b = fade(gamma') * smoothstep(0.05, 0.4, cmin) * smoothstep(0.1, 0.5, r),
// W scaled so its w averages 1 over B. The blend is a valid map for every b: a point with w > 0
// in both lands on a convex combination of its positions in U and W (weights 1 - b and b w_W),
// so B stays inside [0, 1]^3, and rows without a component along L stay so.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include <sp/scene/scene.h>

namespace sp::tech::warps {

enum class Warp { None, Psm, Lispsm, Tsm };

struct WarpParams {
  // PSM: extra virtual slide-back beyond the least one, in multiples of B's view-depth range
  // (z_f - z_n). 0 = the strongest warp (and the most fallbacks); more = weaker (less
  // over-sampling near the viewer); +inf = uniform.
  float psmSlideBack = 0.3f;
  // LiSPSM: n = lispsmScale * n_opt. < 1 warps more, > 1 less, +inf = uniform.
  float lispsmScale = 1.0f;
  // TSM: the fraction of the map (v from the top) the focus line maps to (the 80 % rule); 0 =
  // uniform (as any value at or below the focus line's own fraction).
  float tsmFocus = 0.8f;
  // TSM: where the focus line is: view depth z_n + tsmFocusDepth (z_f - z_n) on the camera axis.
  float tsmFocusDepth = 0.5f;
};

struct WarpInput {
  scene::Camera camera;
  float aspect = 1.0f;
  glm::vec3 lightDirection{0, -1, 0};  // the way the light travels
  std::vector<glm::vec3> body;         // world points; B is their convex hull
  scene::Bounds casters;               // world bounds of what may cast (the scene's bounds)
};

// B = the slice [d0, d1] of the camera's frustum clipped to `sceneBounds` (the slice itself where
// they do not meet); casters = sceneBounds.
WarpInput MakeWarpInput(const scene::Camera& camera, float aspect, const glm::vec3& lightDirection,
                        const scene::Bounds& sceneBounds, float d0, float d1);

struct WarpFit {
  Warp warp = Warp::None;
  glm::mat4 viewProj{1.0f};     // world -> clip, z in [0, 1]; perspective (w != 1) for a warp
  glm::mat4 lightView{1.0f};    // world -> light view (origin at the camera, looking down -z, +y along the view)
  glm::vec4 linearDepth{0.0f};  // dot(linearDepth, (world, 1)): light-space linear depth in [0, 1] over B and its casters
  bool preferLinearDepth = false;  // TSM: store linearDepth, as its paper does
  float gamma = 0.0f;           // angle between view and light direction, degrees (0: light from behind the viewer)
  bool fellBack = false;        // the result is the uniform map (blend == 0)
  // 0 = uniform, 1 = the full warp: PSM's b, TSM's fade(gamma'), LiSPSM's sin(gamma) (its warp
  // strength 1/n relative to the same body lit at 90 degrees).
  float blend = 0.0f;
  float n = 0.0f;               // LiSPSM / TSM: distance of the perspective's eye before B (1/k); +inf when uniform
  float slideBack = 0.0f;       // PSM: the virtual camera's slide-back, world units
  // Light-view x/y of the map's corners (TSM's trapezoid; a rectangle when uniform): top-left,
  // top-right, bottom-right, bottom-left (top = row 0 = B's near side).
  glm::vec2 trapezoid[4]{};
  // Whether the trapezoid is the map's whole region: every corner of the square has a preimage
  // with w > 0. Where one has not (PSM's blend can put the line w = 0 through the square), the
  // region in the light view is unbounded and the corners above mean nothing.
  bool trapezoidBounded = true;
};

WarpFit FitWarp(const WarpInput& input, Warp warp, const WarpParams& params = {});

// Whether an object with these world bounds may cast a shadow into the fit's map: its shadow
// footprint (the bounds' light-view x/y rectangle, conservative) meets the map's region in the
// light view (the trapezoid: the 2D homography's preimage of the square), and its side nearest the
// light is not beyond B's far side (linear depth <= 1). Conservative: false only for objects that
// draw no texel the lookup of B can read.
bool MayCastInto(const WarpFit& fit, const scene::Bounds& worldBounds);

// World point -> texel coordinates (x right, y down, row 0 at the top) for a map `resolution`
// texels wide and high, and the depth viewProj gives, after the divide by w.
glm::vec3 ToTexel(const WarpFit& fit, const glm::vec3& world, float resolution);

// Light-space linear depth (WarpFit::linearDepth) of a world point.
float LinearDepth(const WarpFit& fit, const glm::vec3& world);

// Texels per world unit at `world` along the world direction `along` (central difference of
// ToTexel over +-h world units).
float TexelsPerUnit(const WarpFit& fit, const glm::vec3& world, const glm::vec3& along, float resolution, float h);

}  // namespace sp::tech::warps
