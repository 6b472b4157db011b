#include "warp-fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "csm/cascade-fit.h"

namespace sp::tech::warps {

namespace {

using glm::dmat4;
using glm::dvec3;
using glm::dvec4;

const double kDegrees = 180.0 / 3.14159265358979323846;
const double kInf = std::numeric_limits<double>::infinity();

double Smoothstep(double a, double b, double x) {
  double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A row acting on homogeneous world points (X, 1).
double Apply(const dvec4& row, const dvec3& p) { return glm::dot(dvec3(row), p) + row.w; }

dmat4 FromRows(const dvec4& r0, const dvec4& r1, const dvec4& r2, const dvec4& r3) {
  return glm::transpose(dmat4(r0, r1, r2, r3));  // dmat4 takes columns
}

// The light view: origin at the camera, -z along the light, +y along the view direction's part
// perpendicular to the light (the camera's up where there is none).
struct Frame {
  dvec3 camera, forward, light;  // light: unit travel direction
  dvec4 x, y, z;                 // light-view rows
  dvec4 dist;                    // distance along the light from the camera's plane: -z
  double gamma = 0;              // radians
  double sinGamma = 0;
};

Frame MakeFrame(const scene::Camera& cam, const glm::vec3& lightDirection) {
  Frame f;
  f.camera = dvec3(cam.position);
  dvec3 fwd = dvec3(cam.target) - dvec3(cam.position), dir(lightDirection);
  f.forward = glm::length(fwd) > 1e-12 ? glm::normalize(fwd) : dvec3(0, 0, -1);
  dvec3 L = glm::length(dir) > 1e-12 ? glm::normalize(dir) : dvec3(0, -1, 0);
  f.light = L;
  double c = std::clamp(glm::dot(f.forward, L), -1.0, 1.0);
  f.gamma = std::acos(c);
  dvec3 y = f.forward - c * L;
  f.sinGamma = glm::length(y);
  if (f.sinGamma < 1e-9) {
    y = dvec3(cam.up) - glm::dot(dvec3(cam.up), L) * L;
    if (glm::length(y) < 1e-9) y = std::abs(L.x) < 0.9 ? glm::cross(L, dvec3(1, 0, 0)) : glm::cross(L, dvec3(0, 1, 0));
  }
  y = glm::normalize(y);
  dvec3 z = -L, x = glm::cross(y, z);
  f.x = dvec4(x, -glm::dot(x, f.camera));
  f.y = dvec4(y, -glm::dot(y, f.camera));
  f.z = dvec4(z, -glm::dot(z, f.camera));
  f.dist = -f.z;
  return f;
}

// The casters that can shadow B: B's light-view x/y box extruded towards the light, clipped to the
// caster bounds; the vertices of that solid.
std::vector<dvec3> CasterPoints(const Frame& f, const std::vector<dvec3>& body, const scene::Bounds& casters) {
  std::vector<dvec3> out;
  if (casters.empty() || body.empty()) return out;
  dvec3 lo(1e300), hi(-1e300);
  for (const dvec3& p : body) {
    dvec3 l(Apply(f.x, p), Apply(f.y, p), Apply(f.z, p));
    lo = glm::min(lo, l), hi = glm::max(hi, l);
  }
  glm::vec3 bc[8];
  casters.corners(bc);
  double top = hi.z;
  for (const glm::vec3& c : bc) top = std::max(top, Apply(f.z, dvec3(c)));
  top += 1.0 + 1e-3 * (top - lo.z);
  dvec3 ax(f.x), ay(f.y), az(f.z);
  glm::vec3 prism[8];
  for (int k = 0; k < 8; ++k) {
    // bit 0 right, bit 1 up, bit 2 far (away from the light), as SliceCorners.
    double lx = k & 1 ? hi.x : lo.x, ly = k & 2 ? hi.y : lo.y, lz = k & 4 ? lo.z : top;
    prism[k] = glm::vec3(f.camera + ax * lx + ay * ly + az * lz);
  }
  for (const glm::vec3& p : csm::SliceBoxIntersection(prism, casters)) out.push_back(dvec3(p));
  return out;
}

// The ortho fit after the warp (rows u, v, w on world points): B's rectangle of (u/w, v/w) to
// [-1, 1] (its smallest v, the near side, at the top), depth (dist / w) from B's casters to B's
// far side onto [0, 1]; rows scaled so w averages 1 over B. Returns false where w <= 0 somewhere.
bool FitRows(const dvec4& u, const dvec4& v, const dvec4& w, const dvec4& dist, const std::vector<dvec3>& body,
             const std::vector<dvec3>& casters, dmat4* out) {
  double umin = kInf, umax = -kInf, vmin = kInf, vmax = -kInf, tn = kInf, tf = -kInf, wsum = 0;
  for (const dvec3& p : body) {
    double ww = Apply(w, p);
    if (!(ww > 0.0)) return false;
    double a = Apply(u, p) / ww, b = Apply(v, p) / ww, t = Apply(dist, p) / ww;
    umin = std::min(umin, a), umax = std::max(umax, a);
    vmin = std::min(vmin, b), vmax = std::max(vmax, b);
    tn = std::min(tn, t), tf = std::max(tf, t);
    wsum += ww;
  }
  for (const dvec3& p : casters) {
    double ww = Apply(w, p);
    if (!(ww > 0.0)) return false;
    tn = std::min(tn, Apply(dist, p) / ww);
  }
  if (body.empty()) return false;
  // Slack so B's extreme points do not land exactly on the edges (and a flat B has a range).
  auto widen = [](double& lo, double& hi) {
    double m = std::max((hi - lo) * 1e-4, 1e-9 * std::max({std::abs(lo), std::abs(hi), 1e-3}));
    lo -= m, hi += m;
  };
  widen(umin, umax), widen(vmin, vmax), widen(tn, tf);
  dvec4 x = (2.0 * u - (umax + umin) * w) / (umax - umin);
  dvec4 y = -(2.0 * v - (vmax + vmin) * w) / (vmax - vmin);
  dvec4 z = (dist - tn * w) / (tf - tn);
  double s = double(body.size()) / wsum;
  *out = FromRows(x * s, y * s, z * s, w * s);
  return true;
}

bool Finite(const dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The rows of the LiSPSM / TSM family: perspective from (0, y0 - 1/k) along the warp axis.
dvec4 WarpW(const Frame& f, double y0, double k) { return dvec4(0, 0, 0, 1) + k * (f.y - dvec4(0, 0, 0, y0)); }

// PSM's w row (world): the depth of the light camera in the virtual camera's post-projective
// space, or false where there is no valid light camera. cmin: the least cosine between the light
// camera's axis and a ray to a point of B or its casters.
bool PsmW(const WarpInput& in, const Frame& f, const std::vector<dvec3>& body, const std::vector<dvec3>& casters, double zn, double zf,
          double extra, dvec4* w, double* cmin, double* slide) {
  double minDepth = kInf;
  for (const auto* set : {&body, &casters})
    for (const dvec3& p : *set) minDepth = std::min(minDepth, glm::dot(f.forward, p - f.camera));
  double s = std::max(0.0, 0.5 * zn - minDepth) + extra * (zf - zn);
  *slide = s;
  dvec3 eye = f.camera - f.forward * s;
  double nearV = minDepth + s;
  dvec3 right = glm::cross(f.forward, dvec3(in.camera.up));
  if (glm::length(right) < 1e-9) right = glm::cross(f.forward, std::abs(f.forward.y) < 0.9 ? dvec3(0, 1, 0) : dvec3(1, 0, 0));
  right = glm::normalize(right);
  dvec3 up = glm::cross(right, f.forward);
  double ty = std::tan(double(in.camera.fovY) * 0.5), tx = ty * double(in.aspect);
  // Virtual camera, D3D depth, far plane at infinity: x/tx, y/ty, z_v - n, z_v.
  dmat4 pv = FromRows(dvec4(right / tx, -glm::dot(right, eye) / tx), dvec4(up / ty, -glm::dot(up, eye) / ty),
                      dvec4(f.forward, -glm::dot(f.forward, eye) - nearV), dvec4(f.forward, -glm::dot(f.forward, eye)));
  dvec4 lh = pv * dvec4(-f.light, 0.0);
  dvec3 l(lh);
  double lw = lh.w;
  auto post = [&](const dvec3& p) {
    dvec4 q = pv * dvec4(p, 1.0);
    return dvec3(q) / q.w;
  };
  dvec3 lo(kInf), hi(-kInf);
  for (const dvec3& p : body) {
    dvec3 q = post(p);
    lo = glm::min(lo, q), hi = glm::max(hi, q);
  }
  dvec3 c = (lo + hi) * 0.5;
  dvec3 axis = lw * c - l;
  if (!(glm::length(axis) > 1e-12)) return false;
  axis = glm::normalize(axis);
  *cmin = 1.0;
  for (const auto* set : {&body, &casters})
    for (const dvec3& p : *set) {
      dvec3 d = lw * post(p) - l;
      double len = glm::length(d);
      if (len > 0) *cmin = std::min(*cmin, glm::dot(axis, d) / len);
    }
  // a . D(Q) on post-projective (x, w), pulled back to world (row vector times matrix).
  *w = dvec4(lw * axis, -glm::dot(axis, l)) * pv;
  return true;
}

}  // namespace

WarpInput MakeWarpInput(const scene::Camera& camera, float aspect, const glm::vec3& lightDirection, const scene::Bounds& sceneBounds,
                        float d0, float d1) {
  WarpInput in;
  in.camera = camera;
  in.aspect = aspect;
  in.lightDirection = lightDirection;
  in.casters = sceneBounds;
  glm::vec3 corners[8];
  csm::SliceCorners(camera, aspect, d0, d1, corners);
  in.body = csm::SliceBoxIntersection(corners, sceneBounds);
  if (in.body.empty()) in.body.assign(corners, corners + 8);
  return in;
}

WarpFit FitWarp(const WarpInput& in, Warp warp, const WarpParams& params) {
  WarpFit fit;
  fit.warp = warp;
  Frame f = MakeFrame(in.camera, in.lightDirection);
  fit.gamma = float(f.gamma * kDegrees);
  fit.lightView = glm::mat4(FromRows(f.x, f.y, f.z, dvec4(0, 0, 0, 1)));
  fit.n = std::numeric_limits<float>::infinity();

  std::vector<dvec3> body;
  for (const glm::vec3& p : in.body)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) body.push_back(dvec3(p));
  if (body.empty()) body.push_back(f.camera + f.forward * double(std::max(in.camera.nearZ, 1e-3f)));
  std::vector<dvec3> casters = CasterPoints(f, body, in.casters);

  // B's extent along the warp axis and its view-depth range.
  double y0 = kInf, y1 = -kInf, zn = kInf, zf = -kInf;
  for (const dvec3& p : body) {
    double y = Apply(f.y, p), z = glm::dot(f.forward, p - f.camera);
    y0 = std::min(y0, y), y1 = std::max(y1, y);
    zn = std::min(zn, z), zf = std::max(zf, z);
  }
  zn = std::max(zn, std::max(double(in.camera.nearZ), 1e-6));
  zf = std::max(zf, zn);

  // Light-space linear depth over B and its casters.
  {
    double dn = kInf, df = -kInf;
    for (const dvec3& p : body) dn = std::min(dn, Apply(f.dist, p)), df = std::max(df, Apply(f.dist, p));
    for (const dvec3& p : casters) dn = std::min(dn, Apply(f.dist, p));
    double m = std::max((df - dn) * 1e-4, 1e-6);
    dn -= m, df += m;
    fit.linearDepth = glm::vec4((f.dist - dvec4(0, 0, 0, dn)) / (df - dn));
  }

  dmat4 uniform;
  FitRows(f.x, f.y, dvec4(0, 0, 0, 1), f.dist, body, casters, &uniform);
  dmat4 result = uniform;
  double blend = 0.0;
  const double gammaEdge = std::min(f.gamma, 3.14159265358979323846 - f.gamma) * kDegrees;
  const double fade = Smoothstep(5.0, 20.0, gammaEdge);
  const double d = y1 - y0;

  auto perspectiveFamily = [&](double k) {
    dmat4 m;
    if (k > 0.0 && std::isfinite(k) && FitRows(f.x, f.y - dvec4(0, 0, 0, y0), WarpW(f, y0, k), f.dist, body, casters, &m) && Finite(m)) {
      result = m;
      fit.n = float(1.0 / k);
      return true;
    }
    return false;
  };

  switch (warp) {
    case Warp::None: break;
    case Warp::Lispsm: {
      double scale = std::max(double(params.lispsmScale), 1e-3);
      if (std::isfinite(scale) && f.sinGamma > 1e-9 && zf - zn > 1e-9 * zf && d > 1e-9 * (zf + 1.0)) {
        double nOpt = d / (zf - zn) * (zn + std::sqrt(zn * zf)) / f.sinGamma;
        if (perspectiveFamily(1.0 / (scale * nOpt))) blend = std::min(f.sinGamma, 1.0);
      }
      break;
    }
    case Warp::Tsm: {
      fit.preferLinearDepth = true;
      double xi = std::clamp(double(params.tsmFocus), 0.0, 0.999);
      if (d > 1e-9 * (zf + 1.0) && fade > 0.0) {
        dvec3 focus = f.camera + f.forward * (zn + double(std::clamp(params.tsmFocusDepth, 0.0f, 1.0f)) * (zf - zn));
        double delta = std::clamp(Apply(f.y, focus) - y0, 1e-6 * d, d);
        double k = std::max(0.0, (xi - delta / d) / (delta * (1.0 - xi)));
        if (perspectiveFamily(k * fade)) blend = fade;
      }
      break;
    }
    case Warp::Psm: {
      double extra = std::max(double(params.psmSlideBack), 0.0);
      dvec4 w;
      double cmin = -1, slide = 0;
      if (std::isfinite(extra) && fade > 0.0 && PsmW(in, f, body, casters, zn, zf, extra, &w, &cmin, &slide)) {
        fit.slideBack = float(slide);
        // The image rows: u = X / w, v = (Y - y0) / w, as the LiSPSM family (any two rows without
        // a component along L give the same image up to an affine map; these keep the map aligned
        // with the uniform one). They are independent of w while w(P0) > 0 at P0 = (0, y0).
        // The 2D map is singular where w(P0) = 0; P0 inside B's footprint has w(P0) >= min w over B.
        double w0 = Apply(w, f.camera + dvec3(f.y) * y0), wmin = kInf;
        for (const dvec3& p : body) wmin = std::min(wmin, Apply(w, p));
        double b = fade * Smoothstep(0.05, 0.4, cmin) * (wmin > 0 ? Smoothstep(0.1, 0.5, w0 / wmin) : 0.0);
        dmat4 m;
        if (b > 0.0 && FitRows(f.x, f.y - dvec4(0, 0, 0, y0), w, f.dist, body, casters, &m) && Finite(m)) {
          result = (1.0 - b) * uniform + b * m;
          blend = b;
        }
      }
      break;
    }
  }
  fit.blend = float(blend);
  fit.fellBack = warp != Warp::None && blend == 0.0;
  if (blend == 0.0) result = uniform, fit.n = std::numeric_limits<float>::infinity();
  fit.viewProj = glm::mat4(result);

  // The map's corners in the light view: invert the 2D homography (x, y, w rows on X, Y, 1).
  dmat4 toWorld = glm::inverse(FromRows(f.x, f.y, f.z, dvec4(0, 0, 0, 1)));
  dmat4 onLight = result * toWorld;
  glm::dmat3 h;
  for (int r = 0, out = 0; r < 4; ++r) {
    if (r == 2) continue;
    h[0][out] = onLight[0][r], h[1][out] = onLight[1][r], h[2][out] = onLight[3][r];
    ++out;
  }
  glm::dmat3 hi = glm::inverse(h);
  const glm::dvec2 ndc[4] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
  for (int i = 0; i < 4; ++i) {
    // q = (X, Y, 1) / w of the corner's preimage.
    glm::dvec3 q = hi * glm::dvec3(ndc[i], 1.0);
    fit.trapezoid[i] = glm::vec2(glm::dvec2(q) / q.z);
    fit.trapezoidBounded = fit.trapezoidBounded && q.z > 0.0;
  }
  return fit;
}

bool MayCastInto(const WarpFit& fit, const scene::Bounds& worldBounds) {
  if (worldBounds.empty()) return false;
  glm::vec3 corners[8];
  worldBounds.corners(corners);
  float nearest = 3e38f;
  for (const glm::vec3& c : corners) nearest = std::min(nearest, LinearDepth(fit, c));
  if (nearest > 1.0f) return false;
  if (!fit.trapezoidBounded) return true;
  // Separating axes of a rectangle and a convex quadrilateral in the plane: the rectangle's two
  // and the quadrilateral's four edge normals.
  const scene::Bounds lv = worldBounds.transformed(fit.lightView);
  const glm::vec2 rect[4] = {{lv.min.x, lv.min.y}, {lv.max.x, lv.min.y}, {lv.max.x, lv.max.y}, {lv.min.x, lv.max.y}};
  auto separated = [&](glm::vec2 axis) {
    float r0 = 3e38f, r1 = -3e38f, q0 = 3e38f, q1 = -3e38f;
    for (int i = 0; i < 4; ++i) {
      float a = glm::dot(axis, rect[i]), b = glm::dot(axis, fit.trapezoid[i]);
      r0 = std::min(r0, a), r1 = std::max(r1, a), q0 = std::min(q0, b), q1 = std::max(q1, b);
    }
    return r1 < q0 || q1 < r0;
  };
  if (separated({1, 0}) || separated({0, 1})) return false;
  for (int i = 0; i < 4; ++i) {
    glm::vec2 e = fit.trapezoid[(i + 1) % 4] - fit.trapezoid[i];
    if (separated({-e.y, e.x})) return false;
  }
  return true;
}

glm::vec3 ToTexel(const WarpFit& fit, const glm::vec3& world, float resolution) {
  glm::vec4 p = fit.viewProj * glm::vec4(world, 1.0f);
  glm::vec3 c = glm::vec3(p) / p.w;
  return {(c.x * 0.5f + 0.5f) * resolution, (0.5f - c.y * 0.5f) * resolution, c.z};
}

float LinearDepth(const WarpFit& fit, const glm::vec3& world) { return glm::dot(fit.linearDepth, glm::vec4(world, 1.0f)); }

float TexelsPerUnit(const WarpFit& fit, const glm::vec3& world, const glm::vec3& along, float resolution, float h) {
  glm::vec3 dir = glm::normalize(along);
  glm::vec3 a = ToTexel(fit, world + dir * h, resolution), b = ToTexel(fit, world - dir * h, resolution);
  return glm::length(glm::vec2(a - b)) / (2.0f * h);
}

}  // namespace sp::tech::warps
