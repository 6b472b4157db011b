// The top-left fill rule: a pixel is covered when its centre is inside the triangle, or on an edge
// that is a top edge (horizontal, the other vertex below) or a left edge (D3D11 functional spec,
// "Triangle Rasterization Rules"). Meshes whose triangles share edges through pixel centres must
// cover every pixel exactly once, and exactly the pixels the rule predicts. Hits are counted with
// additive blending into R32_FLOAT, so a pixel drawn twice reads 2 and a dropped one 0; the
// expectation is the sum of D3DCovers over the triangles. Coverage is exact in D3D11 (vertices on
// the 1/256 grid are not moved by the 8-bit sub-pixel snapping), so the tolerance is 0 pixels.
#include <cmath>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Rasterization";
constexpr uint32_t W = 32, H = 32;

using Tri = std::array<PixelVertex, 3>;

Result CheckMesh(Device& device, const std::vector<Tri>& tris, const std::string& what, uint32_t w = W, uint32_t h = H) {
  std::vector<PixelVertex> flat;
  for (const Tri& t : tris) flat.insert(flat.end(), t.begin(), t.end());
  std::vector<float> got = CountHits(device, w, h, flat);
  std::vector<float> expected(size_t(w) * h, 0.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (const Tri& t : tris)
        if (D3DCovers({t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}, x + 0.5, y + 0.5)) expected[y * w + x] += 1;
  std::string detail;
  int wrong = CountMismatches(got, expected, w, &detail, "hit");
  if (wrong) return Fail(what + ": " + std::to_string(wrong) + " pixels covered a different number of times than D3D11's rule says; " + detail, wrong,
                         "pixels", 0);
  return Pass(0, "pixels", 0);
}

// Two triangles of the axis-aligned rectangle (x0,y0)-(x1,y1), split along one diagonal.
void Rect(std::vector<Tri>& out, double x0, double y0, double x1, double y1, bool otherDiagonal = false) {
  if (!otherDiagonal) {
    out.push_back({{{x0, y0}, {x1, y0}, {x0, y1}}});
    out.push_back({{{x1, y0}, {x1, y1}, {x0, y1}}});
  } else {
    out.push_back({{{x0, y0}, {x1, y0}, {x1, y1}}});
    out.push_back({{{x0, y0}, {x1, y1}, {x0, y1}}});
  }
}

}  // namespace

SP_PROBE(kGroup, "fill rule: horizontal shared edges through pixel centres",
         "strips stacked along edges y = k + 0.5 cover every pixel once (top edges are in, bottom edges out)") {
  // Strips of height 1, 2, 3 and 5 pixels between rows on pixel centres; the outer left and right
  // edges also run through centres.
  std::vector<Tri> tris;
  double y = 1.5;
  bool flip = false;
  for (double hgt : {1.0, 2.0, 3.0, 5.0, 1.0, 4.0, 2.0, 7.0}) {
    Rect(tris, 2.5, y, 29.5, y + hgt, flip);
    flip = !flip;
    y += hgt;
  }
  return CheckMesh(device, tris, "horizontal strips");
}

SP_PROBE(kGroup, "fill rule: vertical shared edges through pixel centres",
         "columns side by side along edges x = k + 0.5 cover every pixel once (left edges are in, right edges out)") {
  std::vector<Tri> tris;
  double x = 1.5;
  bool flip = false;
  for (double wid : {1.0, 2.0, 3.0, 5.0, 1.0, 4.0, 2.0, 7.0}) {
    Rect(tris, x, 2.5, x + wid, 29.5, flip);
    flip = !flip;
    x += wid;
  }
  return CheckMesh(device, tris, "vertical columns");
}

SP_PROBE(kGroup, "fill rule: diagonal shared edges through pixel centres",
         "triangles sharing edges of slope +-1, +-2 and +-1/2 that pass through pixel centres cover every pixel once") {
  // A band of triangles between two polylines whose vertices are all pixel centres, so every
  // shared edge (slopes 1, -1, 2, 1/2) crosses further pixel centres.
  std::vector<Tri> tris;
  const double top[] = {2.5, 4.5, 2.5, 6.5, 3.5, 3.5, 5.5, 2.5};
  const double bottom[] = {14.5, 12.5, 16.5, 13.5, 15.5, 17.5, 14.5, 16.5};
  for (int i = 0; i < 7; ++i) {
    double xa = 1.5 + 4 * i, xb = xa + 4;
    tris.push_back({{{xa, top[i]}, {xb, top[i + 1]}, {xa, bottom[i]}}});
    tris.push_back({{{xb, top[i + 1]}, {xb, bottom[i + 1]}, {xa, bottom[i]}}});
  }
  // A diamond of four triangles around (16.5, 24.5) with 45-degree outer edges.
  PixelVertex c{16.5, 24.5}, n{16.5, 19.5}, e{21.5, 24.5}, s{16.5, 29.5}, wv{11.5, 24.5};
  tris.push_back({{c, n, e}});
  tris.push_back({{c, e, s}});
  tris.push_back({{c, s, wv}});
  tris.push_back({{c, wv, n}});
  return CheckMesh(device, tris, "diagonal band and diamond");
}

SP_PROBE(kGroup, "fill rule: fans around a vertex on a pixel centre",
         "16 triangles around a shared vertex on a pixel centre cover that pixel and every other exactly once") {
  std::vector<Tri> tris;
  // Spokes to the border of a square, at axis-aligned, 45-degree and 1/2-slope directions, so
  // most shared edges pass through pixel centres besides the hub.
  auto fan = [&](PixelVertex hub, double r, bool reverse) {
    std::vector<PixelVertex> ring;
    for (double t : {-1.0, -0.5, 0.0, 0.5}) ring.push_back({hub.x + t * r, hub.y - r});
    for (double t : {-1.0, -0.5, 0.0, 0.5}) ring.push_back({hub.x + r, hub.y + t * r});
    for (double t : {1.0, 0.5, 0.0, -0.5}) ring.push_back({hub.x + t * r, hub.y + r});
    for (double t : {1.0, 0.5, 0.0, -0.5}) ring.push_back({hub.x - r, hub.y + t * r});
    for (size_t i = 0; i < ring.size(); ++i) {
      PixelVertex a = ring[i], b = ring[(i + 1) % ring.size()];
      if (reverse) tris.push_back({{hub, b, a}});
      else tris.push_back({{hub, a, b}});
    }
  };
  fan({8.5, 8.5}, 6, false);
  fan({23.5, 8.5}, 6, true);  // the other winding: coverage must not depend on it
  fan({15.5, 23.5}, 7, false);
  return CheckMesh(device, tris, "fans");
}

SP_PROBE(kGroup, "fill rule: a quad split along either diagonal",
         "a quadrilateral with corners on pixel centres covers the same pixels, once each, whichever diagonal splits it") {
  const PixelVertex a{4.5, 3.5}, b{27.5, 6.5}, c{24.5, 28.5}, d{3.5, 22.5};
  std::vector<Tri> one = {{{a, b, c}}, {{a, c, d}}};
  std::vector<Tri> two = {{{a, b, d}}, {{b, c, d}}};
  Result r1 = CheckMesh(device, one, "split along AC");
  if (r1.status != Status::Pass) return r1;
  Result r2 = CheckMesh(device, two, "split along BD");
  if (r2.status != Status::Pass) return r2;
  // An axis-aligned quad split both ways, drawn together: exactly two hits per pixel inside.
  std::vector<Tri> both;
  Rect(both, 6.5, 9.5, 25.5, 20.5, false);
  Rect(both, 6.5, 9.5, 25.5, 20.5, true);
  return CheckMesh(device, both, "axis-aligned quad split both ways");
}

SP_PROBE(kGroup, "fill rule: triangles in general position",
         "edges through pixel centres and arbitrary sub-pixel vertices cover exactly the D3D11 pixels") {
  std::vector<Tri> tris = {
      {{{2.5, 2.5}, {12.5, 2.5}, {2.5, 12.5}}},      // top and left edges on centres
      {{{12.5, 2.5}, {12.5, 12.5}, {2.5, 12.5}}},    // shares the diagonal with the first
      {{{16.0, 4.0}, {30.25, 9.5}, {18.75, 27.5}}},  // general position
      {{{20.5, 28.5}, {29.5, 28.5}, {29.5, 31.5}}},  // horizontal top edge
      {{{1.125, 17.0625}, {13.9375, 19.25}, {6.0, 30.75}}},
  };
  return CheckMesh(device, tris, "general triangles");
}

SP_PROBE(kGroup, "fill rule: 8-bit sub-pixel precision",
         "edges 1/256 pixel beside a pixel centre are resolved as D3D11's 16.8 fixed-point vertices say") {
  // Vertical and horizontal edges 1/256 pixel left/right of (or above/below) pixel centres: with
  // D3D11's 8 fractional bits they stay off the centre, so the centre is inside or outside by the
  // edge function alone, not by the tie rule. A rasterizer with fewer sub-pixel bits snaps them
  // onto the centre and gets some of them wrong.
  const double e = 1.0 / 256;
  std::vector<Tri> tris;
  Rect(tris, 2.5 + e, 2.5, 9.5 - e, 12.5);
  Rect(tris, 12.5 - e, 2.5, 19.5 + e, 12.5);
  Rect(tris, 2.5, 15.5 + e, 12.5, 22.5 - e);
  Rect(tris, 16.5, 15.5 - e, 26.5, 22.5 + e);
  tris.push_back({{{22.5 + e, 2.5}, {30.5, 10.5 - e}, {22.5, 10.5}}});  // a diagonal edge just off the centres
  return CheckMesh(device, tris, "edges 1/256 pixel off the centres");
}

}  // namespace sp::conformance
