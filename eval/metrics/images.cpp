// The lab's pictures: error and texel-density heat maps with a legend drawn into the image (the
// report shows them without captions of their own), and the reference image.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "metrics.h"

// Static, so this copy of stb's writer does not collide with another in the same program.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace sp::eval {

namespace {

using Rgb = std::array<uint8_t, 3>;

// A 5x7 font (columns, bit 0 at the top) for the characters legends use.
struct Glyph {
  char c;
  uint8_t col[5];
};
const Glyph kFont[] = {
    {' ', {0x00, 0x00, 0x00, 0x00, 0x00}}, {'(', {0x00, 0x1C, 0x22, 0x41, 0x00}}, {')', {0x00, 0x41, 0x22, 0x1C, 0x00}},
    {'-', {0x08, 0x08, 0x08, 0x08, 0x08}}, {'.', {0x00, 0x60, 0x60, 0x00, 0x00}}, {'/', {0x20, 0x10, 0x08, 0x04, 0x02}},
    {':', {0x00, 0x36, 0x36, 0x00, 0x00}}, {'<', {0x08, 0x14, 0x22, 0x41, 0x00}}, {'=', {0x14, 0x14, 0x14, 0x14, 0x14}},
    {'>', {0x00, 0x41, 0x22, 0x14, 0x08}}, {',', {0x00, 0x50, 0x30, 0x00, 0x00}}, {'0', {0x3E, 0x51, 0x49, 0x45, 0x3E}},
    {'1', {0x00, 0x42, 0x7F, 0x40, 0x00}}, {'2', {0x42, 0x61, 0x51, 0x49, 0x46}}, {'3', {0x21, 0x41, 0x45, 0x4B, 0x31}},
    {'4', {0x18, 0x14, 0x12, 0x7F, 0x10}}, {'5', {0x27, 0x45, 0x45, 0x45, 0x39}}, {'6', {0x3C, 0x4A, 0x49, 0x49, 0x30}},
    {'7', {0x01, 0x71, 0x09, 0x05, 0x03}}, {'8', {0x36, 0x49, 0x49, 0x49, 0x36}}, {'9', {0x06, 0x49, 0x49, 0x29, 0x1E}},
    {'A', {0x7E, 0x11, 0x11, 0x11, 0x7E}}, {'B', {0x7F, 0x49, 0x49, 0x49, 0x36}}, {'C', {0x3E, 0x41, 0x41, 0x41, 0x22}},
    {'D', {0x7F, 0x41, 0x41, 0x22, 0x1C}}, {'E', {0x7F, 0x49, 0x49, 0x49, 0x41}}, {'F', {0x7F, 0x09, 0x09, 0x09, 0x01}},
    {'G', {0x3E, 0x41, 0x49, 0x49, 0x7A}}, {'H', {0x7F, 0x08, 0x08, 0x08, 0x7F}}, {'I', {0x00, 0x41, 0x7F, 0x41, 0x00}},
    {'J', {0x20, 0x40, 0x41, 0x3F, 0x01}}, {'K', {0x7F, 0x08, 0x14, 0x22, 0x41}}, {'L', {0x7F, 0x40, 0x40, 0x40, 0x40}},
    {'M', {0x7F, 0x02, 0x0C, 0x02, 0x7F}}, {'N', {0x7F, 0x04, 0x08, 0x10, 0x7F}}, {'O', {0x3E, 0x41, 0x41, 0x41, 0x3E}},
    {'P', {0x7F, 0x09, 0x09, 0x09, 0x06}}, {'Q', {0x3E, 0x41, 0x51, 0x21, 0x5E}}, {'R', {0x7F, 0x09, 0x19, 0x29, 0x46}},
    {'S', {0x46, 0x49, 0x49, 0x49, 0x31}}, {'T', {0x01, 0x01, 0x7F, 0x01, 0x01}}, {'U', {0x3F, 0x40, 0x40, 0x40, 0x3F}},
    {'V', {0x1F, 0x20, 0x40, 0x20, 0x1F}}, {'W', {0x3F, 0x40, 0x38, 0x40, 0x3F}}, {'X', {0x63, 0x14, 0x08, 0x14, 0x63}},
    {'Y', {0x07, 0x08, 0x70, 0x08, 0x07}}, {'Z', {0x61, 0x51, 0x49, 0x45, 0x43}},
};

class Canvas {
 public:
  Canvas(uint32_t w, uint32_t h) : w_(w), h_(h), px_(size_t(w) * h * 4, 255) {}
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= int(w_) || y >= int(h_)) return;
    uint8_t* p = &px_[(size_t(y) * w_ + size_t(x)) * 4];
    p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
  }
  void fill(int x0, int y0, int w, int h, Rgb c) {
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) set(x, y, c);
  }
  // Draws upper-cased text; returns the x after it.
  int text(int x, int y, const std::string& s, int scale, Rgb c) {
    for (char ch : s) {
      char u = char(std::toupper(static_cast<unsigned char>(ch)));
      const Glyph* g = nullptr;
      for (const Glyph& k : kFont)
        if (k.c == u) g = &k;
      if (g)
        for (int cx = 0; cx < 5; ++cx)
          for (int cy = 0; cy < 7; ++cy)
            if (g->col[cx] >> cy & 1) fill(x + cx * scale, y + cy * scale, scale, scale, c);
      x += 6 * scale;
    }
    return x;
  }
  static int textWidth(const std::string& s, int scale) { return int(s.size()) * 6 * scale; }
  std::vector<uint8_t> take() { return std::move(px_); }
  uint32_t width() const { return w_; }

 private:
  uint32_t w_, h_;
  std::vector<uint8_t> px_;
};

// Legend entries: a swatch (or none) and a label, laid out left to right, wrapping to new lines.
struct LegendItem {
  bool swatch;
  Rgb color;
  std::string label;
};

int LegendScale(uint32_t width) { return width >= 480 ? 2 : 1; }

// Height the legend needs at this width (so the canvas can be sized before drawing).
int LayoutLegend(const std::vector<LegendItem>& items, uint32_t width, Canvas* canvas, int top) {
  int s = LegendScale(width), line = 10 * s, pad = 3 * s;
  int x = pad, y = top + pad;
  for (const LegendItem& it : items) {
    int need = (it.swatch ? 9 * s : 0) + Canvas::textWidth(it.label, s) + 4 * s;
    if (x > pad && x + need > int(width)) {
      x = pad;
      y += line;
    }
    if (canvas) {
      if (it.swatch) {
        canvas->fill(x, y, 7 * s, 7 * s, {40, 40, 40});
        canvas->fill(x + s, y + s, 5 * s, 5 * s, it.color);
      }
      canvas->text(x + (it.swatch ? 9 * s : 0), y, it.label, s, {20, 20, 20});
    }
    x += need + 2 * s;
  }
  return y + line + pad - top;
}

uint8_t LinearToSrgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  double s = c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return uint8_t(std::lround(s * 255.0));
}

// The colour image as grey (sRGB luma), scaled: the backdrop heat maps paint over.
uint8_t Grey(const tech::LabBuffers& lab, size_t i, double scale) {
  const uint8_t* c = &lab.color[i * 4];
  return uint8_t(std::clamp((0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) * scale, 0.0, 255.0));
}

Rgb Mix(Rgb a, Rgb b, double t) {
  Rgb r;
  for (int k = 0; k < 3; ++k) r[k] = uint8_t(std::lround(a[k] + (b[k] - a[k]) * std::clamp(t, 0.0, 1.0)));
  return r;
}

// Draws `pixel(i)` for every pixel, then the legend under it.
template <class F>
std::vector<uint8_t> Compose(const tech::LabBuffers& lab, const std::vector<LegendItem>& legend, uint32_t* imageHeight, F pixel) {
  int legendHeight = LayoutLegend(legend, lab.width, nullptr, 0);
  Canvas canvas(lab.width, lab.height + uint32_t(legendHeight));
  for (uint32_t y = 0; y < lab.height; ++y)
    for (uint32_t x = 0; x < lab.width; ++x) canvas.set(int(x), int(y), pixel(size_t(y) * lab.width + x));
  LayoutLegend(legend, lab.width, &canvas, int(lab.height));
  *imageHeight = lab.height + uint32_t(legendHeight);
  return canvas.take();
}

const Rgb kFalseLit{235, 45, 35}, kFalseShadow{30, 110, 255};

// ColorBrewer RdBu, 11 classes, reversed: dark red = undersampled, white = 1, dark blue = oversampled.
const Rgb kDensityBands[11] = {{103, 0, 31},    {178, 24, 43},   {214, 96, 77},  {244, 165, 130}, {253, 219, 199}, {247, 247, 247},
                               {209, 229, 240}, {146, 197, 222}, {67, 147, 195}, {33, 102, 172},  {5, 48, 97}};

}  // namespace

std::vector<uint8_t> ErrorHeatMap(const tech::LabBuffers& lab, const uint8_t* reference, uint32_t* imageHeight) {
  return ErrorHeatMap(lab, ReferenceAsFloat(lab, reference).data(), imageHeight);
}

std::vector<uint8_t> ErrorHeatMap(const tech::LabBuffers& lab, const float* reference, uint32_t* imageHeight) {
  std::vector<LegendItem> legend = {{true, kFalseLit, "false lit (leak)"},
                                    {true, kFalseShadow, "false shadow (acne)"},
                                    {true, {150, 150, 150}, "correct"},
                                    {true, {45, 45, 45}, "not judged"}};
  return Compose(lab, legend, imageHeight, [&](size_t i) -> Rgb {
    if (!lab.receiving(i)) {
      uint8_t g = Grey(lab, i, 0.3);
      return {g, g, g};
    }
    uint8_t g = uint8_t(40 + Grey(lab, i, 0.75));  // keeps the shadows readable under the colours
    Rgb grey{g, g, g};
    double err = double(lab.visibility[i]) - double(reference[i]);
    bool wrong = (lab.visibility[i] >= kLitThreshold) != (reference[i] >= kLitThreshold);
    // Misclassified pixels at full strength; a filtered technique's partial errors as a tint.
    return Mix(grey, err > 0 ? kFalseLit : kFalseShadow, wrong ? 1.0 : std::abs(err));
  });
}

std::array<uint8_t, 3> TexelDensityColor(float tpp) {
  int band = int(std::lround(std::log2(std::max(double(tpp), 1e-30)))) + 5;
  return kDensityBands[std::clamp(band, 0, 10)];
}

std::vector<uint8_t> TexelDensityHeatMap(const tech::LabBuffers& lab, uint32_t* imageHeight) {
  std::vector<LegendItem> legend;
  legend.push_back({false, {}, "texels/pixel:"});
  const char* labels[11] = {"<1/32", "1/16", "1/8", "1/4", "1/2", "1", "2", "4", "8", "16", ">32"};
  for (int b = 0; b < 11; ++b) legend.push_back({true, kDensityBands[b], labels[b]});
  legend.push_back({false, {}, "(red: undersampled)"});
  return Compose(lab, legend, imageHeight, [&](size_t i) -> Rgb {
    if (!lab.receiving(i) || lab.lookup[i].x < 0.0f) {
      uint8_t g = Grey(lab, i, 0.3);
      return {g, g, g};
    }
    // Shade the band colour lightly with the image so the scene stays recognisable.
    Rgb c = TexelDensityColor(lab.lookup[i].w);
    double k = 0.7 + 0.3 * Grey(lab, i, 1.0) / 255.0;
    return {uint8_t(c[0] * k), uint8_t(c[1] * k), uint8_t(c[2] * k)};
  });
}

namespace {

// What common/local-lights.hlsli adds for one local light at a surface point, before albedo:
// color * N.L * saturate(1 - (d / range)^4) / d^2 * spot cone factor.
glm::dvec3 LocalLightAt(const tech::LocalLight& l, const glm::vec3& p, const glm::vec3& n) {
  glm::dvec3 v = glm::dvec3(l.position) - glm::dvec3(p);
  double d = glm::length(v);
  if (!(d > 0.0)) return glm::dvec3(0.0);
  glm::dvec3 toLight = v / d;
  double q = d / double(l.range), q2 = q * q;
  double falloff = std::clamp(1.0 - q2 * q2, 0.0, 1.0) / std::max(d * d, 1e-8);
  double spot = 1.0;
  if (l.type == tech::LocalLight::Spot) {
    double t = std::clamp((glm::dot(glm::dvec3(l.direction), -toLight) - double(l.cosOuter)) / std::max(1e-3, double(l.cosInner - l.cosOuter)), 0.0, 1.0);
    spot = t * t;
  }
  double ndotl = std::max(0.0, glm::dot(glm::dvec3(n), toLight));
  return glm::dvec3(l.color) * (ndotl * falloff * spot);
}

}  // namespace

std::vector<uint8_t> ReferenceImage(const tech::LabBuffers& lab, const uint8_t* reference, const scene::DirectionalLight& light,
                                    const std::vector<tech::LocalLight>& localLights, int judgedLocalLight) {
  return ReferenceImage(lab, ReferenceAsFloat(lab, reference).data(), light, localLights, judgedLocalLight);
}

std::vector<uint8_t> ReferenceImage(const tech::LabBuffers& lab, const float* reference, const scene::DirectionalLight& light,
                                    const std::vector<tech::LocalLight>& localLights, int judgedLocalLight) {
  if (judgedLocalLight >= int(localLights.size()))
    throw std::invalid_argument("reference image: judged local light " + std::to_string(judgedLocalLight) + " but " +
                                std::to_string(localLights.size()) + " local lights given");
  std::vector<uint8_t> out(lab.size() * 4, 255);
  const double sky[3] = {0.55, 0.68, 0.85};  // the lit pass's clear colour
  const glm::dvec3 toSun(light.towardsLight());
  for (size_t i = 0; i < lab.size(); ++i) {
    glm::dvec3 v(sky[0], sky[1], sky[2]);
    if (lab.drawn(i)) {
      double vis = lab.receiving(i) ? double(reference[i]) : 0.0;
      glm::dvec3 albedo(lab.albedo[i * 4] / 255.0, lab.albedo[i * 4 + 1] / 255.0, lab.albedo[i * 4 + 2] / 255.0);
      glm::dvec3 lit(light.ambient);
      if (judgedLocalLight < 0) {
        // As lit.hlsl: albedo * (ambient + lightColor * N.L * visibility), here with the reference's.
        lit += glm::dvec3(light.color) * (lab.normal[i].w * vis);
      } else {
        // As lit.hlsl draws a local-light technique's frame: the judged light with the reference's
        // visibility; the directional light and the other local lights unshadowed, as a technique
        // that shadows one local light leaves them (LocalShadowVisibility and ShadowVisibility 1).
        glm::vec3 p(lab.position[i]), n(lab.normal[i]);
        lit += glm::dvec3(light.color) * std::max(0.0, glm::dot(glm::dvec3(n), toSun));
        for (size_t k = 0; k < localLights.size(); ++k)
          lit += LocalLightAt(localLights[k], p, n) * (int(k) == judgedLocalLight ? vis : 1.0);
      }
      v = albedo * lit;
    }
    for (int k = 0; k < 3; ++k) out[i * 4 + k] = LinearToSrgb(v[k]);
  }
  return out;
}

ImageDiff DiffImages(uint32_t w, uint32_t h, const uint8_t* a, const uint8_t* b) {
  std::vector<LegendItem> legend = {{true, {255, 40, 40}, "differs (brighter: larger)"}, {true, {60, 60, 60}, "identical"}};
  int legendHeight = LayoutLegend(legend, w, nullptr, 0);
  Canvas canvas(w, h + uint32_t(legendHeight));
  ImageDiff d;
  d.pixels = uint64_t(w) * h;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      int m = 0;
      for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a[i * 4 + c]) - int(b[i * 4 + c])));
      d.maxDifference = std::max(d.maxDifference, m);
      d.differingPixels += m != 0;
      // Even a difference of one step must stand out against the dimmed picture.
      uint8_t g = uint8_t((a[i * 4] + a[i * 4 + 1] + a[i * 4 + 2]) / 9);
      canvas.set(int(x), int(y), m ? Rgb{uint8_t(std::min(255, 150 + m * 8)), 30, 30} : Rgb{g, g, g});
    }
  LayoutLegend(legend, w, &canvas, int(h));
  d.imageHeight = h + uint32_t(legendHeight);
  d.heatmap = canvas.take();
  return d;
}

void WritePng(const std::filesystem::path& path, uint32_t w, uint32_t h, const uint8_t* rgba) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  if (!stbi_write_png(path.string().c_str(), int(w), int(h), 4, rgba, int(w * 4)))
    throw std::runtime_error("cannot write " + path.string());
}

}  // namespace sp::eval
