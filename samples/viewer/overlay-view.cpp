// The viewer's overlays at run time (overlay-view.h).
#include "overlay-view.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <glm/gtc/packing.hpp>

#ifdef SP_VIEWER_LAB
#include <metrics.h>
#include <reference.h>
#endif

namespace sp::viewer {

struct OverlayView::Lab {
#ifdef SP_VIEWER_LAB
  std::unique_ptr<eval::ReferenceTracer> tracer;  // built on the first trace, kept for the scene
#endif
};

OverlayView::OverlayView(Device& device, const scene::Scene& scene) : device_(device), scene_(scene), labImpl_(std::make_unique<Lab>()) {}
OverlayView::~OverlayView() = default;

std::string OverlayView::NoHeatMaps() {
#ifdef SP_VIEWER_LAB
  return "";
#else
  return "this viewer was built without the lab (eval/): build it inside the ShadowPort tree";
#endif
}

std::string OverlayView::NoShadowMap(const tech::Technique& technique) {
  Texture2D* map = technique.ShadowMapTexture();
  if (!map) return technique.Name() + " exposes no shadow-map texture";
  if (map->GetDesc().SampleDesc.Count > 1) return "its map is multisampled";
  return "";
}

void OverlayView::Set(Overlay o) {
  note_.clear();
  heatMap_.clear();
  tracePending_ = false;
  if ((o == Overlay::Density || o == Overlay::Error) && !NoHeatMaps().empty()) {
    note_ = NoHeatMaps();
    std::printf("viewer: no %s overlay: %s\n", OverlayName(o), note_.c_str());
    o = Overlay::Off;
  }
  overlay_ = o;
  tracePending_ = o == Overlay::Error;
  if (o != Overlay::ShadowMap) mapStaging_ = nullptr, mapSource_ = nullptr;
}

bool OverlayView::NeedsLabRenderer() const {
  return overlay_ == Overlay::Layers || overlay_ == Overlay::Density || overlay_ == Overlay::Error;
}
bool OverlayView::NeedsLabPass() const {
  return overlay_ == Overlay::Layers || overlay_ == Overlay::Density || (overlay_ == Overlay::Error && tracePending_);
}

void OverlayView::Upload(DeviceContext& ctx, Texture2D* target, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h) {
  const TEXTURE2D_DESC& d = target->GetDesc();
  if (d.Width != w || d.Height != h || rgba.size() < size_t(w) * h * 4)
    throw std::logic_error("viewer overlay: a " + std::to_string(w) + "x" + std::to_string(h) + " picture for a " + std::to_string(d.Width) +
                           "x" + std::to_string(d.Height) + " back buffer");
  ctx.UpdateSubresource(target, 0, nullptr, rgba.data(), w * 4, 0);
}

void OverlayView::Draw(DeviceContext& ctx, tech::Renderer& renderer, Texture2D* target, const scene::DirectionalLight& light,
                       const std::string& viewKey) {
  const uint32_t w = renderer.width(), h = renderer.height();
  switch (overlay_) {
    case Overlay::Off: return;
    case Overlay::Layers:
      note_ = "layer colours: the layer each pixel read, 0 red, 1 green, 2 blue, 3 yellow, 4 magenta, 5 cyan, 6 orange, 7 violet "
              "(then again); untinted: no map read (" + std::to_string(renderer.technique().Layers().size()) + " layer(s))";
      lab_ = renderer.ReadLab();
      Upload(ctx, target, ComposeLayerColours(*lab_), w, h);
      return;
    case Overlay::Density: {
#ifdef SP_VIEWER_LAB
      note_ = "texels per pixel: dark red <= 1/32 (undersampled) ... white 1 ... dark blue >= 32 (oversampled), one band per "
              "octave; grey: not judged";
      lab_ = renderer.ReadLab();
      uint32_t imageHeight = 0;
      // The picture's first h rows; the legend strip under it is described in the panel instead.
      Upload(ctx, target, eval::TexelDensityHeatMap(*lab_, &imageHeight), w, h);
#endif
      return;
    }
    case Overlay::Error: {
      if (tracePending_) {
        lab_ = renderer.ReadLab();
        Trace(light, renderer.technique());
        tracedKey_ = viewKey;
        tracePending_ = false;
      } else if (viewKey != tracedKey_) {
        // The picture judged another frame: showing it over this one would be wrong.
        note_ = "error heat map dropped: the view changed since the trace (H or the panel traces again)";
        std::printf("viewer: %s\n", note_.c_str());
        std::fflush(stdout);
        heatMap_.clear();
        overlay_ = Overlay::Off;
        return;
      }
      if (!heatMap_.empty()) Upload(ctx, target, heatMap_, w, h);
      return;
    }
    case Overlay::ShadowMap: {
      std::string why = NoShadowMap(renderer.technique());
      MapImage map;
      if (why.empty() && ReadMap(ctx, renderer.technique().ShadowMapTexture(), &map)) {
        note_ = std::to_string(map.layers) + " layer(s) of " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                (map.depth ? ", grey = depth, scaled per layer from its nearest to its farthest drawn texel (white: nothing drawn)"
                           : ", grey = the first channel (a moment map's first moment), scaled per layer over its range");
        Upload(ctx, target, TileShadowMap(map, w, h), w, h);
      } else {
        std::string note = "no map view: " + (why.empty() ? std::string("its map's format is not one the view reads") : why);
        if (note != note_) std::printf("viewer: %s\n", note.c_str());  // once, not every frame
        note_ = note;
      }
      return;
    }
  }
}

bool OverlayView::ReadMap(DeviceContext& ctx, Texture2D* map, MapImage* out) {
  const TEXTURE2D_DESC d = map->GetDesc();
  // Bytes per texel and how to read the first channel.
  enum { F32, U16, F16 } kind;
  uint32_t stride = 0;
  switch (d.Format) {
    case FORMAT_R32_TYPELESS: case FORMAT_R32_FLOAT: case FORMAT_D32_FLOAT: kind = F32, stride = 4; break;
    case FORMAT_R32G32_TYPELESS: case FORMAT_R32G32_FLOAT: kind = F32, stride = 8; break;
    case FORMAT_R32G32B32A32_TYPELESS: case FORMAT_R32G32B32A32_FLOAT: kind = F32, stride = 16; break;
    case FORMAT_R16_TYPELESS: case FORMAT_R16_UNORM: case FORMAT_D16_UNORM: kind = U16, stride = 2; break;
    case FORMAT_R16G16_UNORM: kind = U16, stride = 4; break;
    case FORMAT_R16G16B16A16_UNORM: kind = U16, stride = 8; break;
    case FORMAT_R16_FLOAT: kind = F16, stride = 2; break;
    case FORMAT_R16G16_FLOAT: kind = F16, stride = 4; break;
    case FORMAT_R16G16B16A16_FLOAT: kind = F16, stride = 8; break;
    default: return false;
  }
  const TEXTURE2D_DESC old = mapStaging_ ? mapStaging_->GetDesc() : TEXTURE2D_DESC{};
  if (!mapStaging_ || mapSource_ != map || old.Width != d.Width || old.Height != d.Height || old.ArraySize != d.ArraySize ||
      old.MipLevels != d.MipLevels || old.Format != d.Format) {
    TEXTURE2D_DESC sd = d;
    sd.Usage = USAGE_STAGING;
    sd.BindFlags = 0;
    sd.CPUAccessFlags = CPU_ACCESS_READ;
    sd.MiscFlags = 0;  // a cube's faces are read as its six slices
    mapStaging_ = device_.CreateTexture2D(sd);
    mapSource_ = map;
  }
  ctx.CopyResource(mapStaging_.get(), map);
  out->width = d.Width, out->height = d.Height, out->layers = d.ArraySize;
  out->depth = (d.BindFlags & BIND_DEPTH_STENCIL) != 0;
  out->values.resize(size_t(d.Width) * d.Height * d.ArraySize);
  float* o = out->values.data();
  for (uint32_t s = 0; s < d.ArraySize; ++s) {
    const uint32_t sub = s * d.MipLevels;  // mip 0 of slice s
    MAPPED_SUBRESOURCE m;
    ctx.Map(mapStaging_.get(), sub, MAP_READ, 0, &m);
    for (uint32_t y = 0; y < d.Height; ++y) {
      const uint8_t* row = static_cast<const uint8_t*>(m.pData) + size_t(y) * m.RowPitch;
      for (uint32_t x = 0; x < d.Width; ++x, ++o) {
        const uint8_t* t = row + size_t(x) * stride;
        if (kind == F32) {
          std::memcpy(o, t, 4);
        } else {
          uint16_t v;
          std::memcpy(&v, t, 2);
          *o = kind == U16 ? float(v) / 65535.0f : glm::unpackHalf1x16(v);
        }
      }
    }
    ctx.Unmap(mapStaging_.get(), sub);
  }
  return true;
}

void OverlayView::Trace(const scene::DirectionalLight& light, const tech::Technique& technique) {
#ifdef SP_VIEWER_LAB
  using Clock = std::chrono::steady_clock;
  // The light the lab judges this technique on (as eval/bench does): the sun, or its local light.
  eval::ReferenceLight ref = eval::ReferenceLight::FromScene(light);
  if (int k = technique.LabLocalLight(scene_); k >= 0) {
    std::vector<tech::LocalLight> local = tech::LocalLightsOf(scene_);
    if (size_t(k) >= local.size()) {
      note_ = "no error heat map: " + technique.Name() + " is judged on local light " + std::to_string(k) + ", which this scene lacks";
      std::printf("viewer: %s\n", note_.c_str());
      heatMap_.clear();
      return;
    }
    const tech::LocalLight& l = local[size_t(k)];
    float radius = size_t(k) < scene_.pointLights.size() ? scene_.pointLights[size_t(k)].radius
                                                         : scene_.spotLights[size_t(k) - scene_.pointLights.size()].radius;
    ref = l.type == tech::LocalLight::Spot ? eval::ReferenceLight::MakeSpot(l.position, l.direction, l.cosOuter, radius)
                                           : eval::ReferenceLight::MakePoint(l.position, radius);
  }
  double buildS = 0;
  if (!labImpl_->tracer) {
    auto t0 = Clock::now();
    labImpl_->tracer = std::make_unique<eval::ReferenceTracer>(scene_);
    buildS = std::chrono::duration<double>(Clock::now() - t0).count();
  }
  const tech::LabBuffers& lab = *lab_;
  eval::LabSurfacePoints points = eval::SurfacePointsOf(lab);
  std::vector<float> reference(lab.size(), 0.0f);
  auto t0 = Clock::now();
  labImpl_->tracer->Visibility(points.position.data(), points.normal.data(), points.valid.data(), points.size(), ref, reference.data());
  double traceS = std::chrono::duration<double>(Clock::now() - t0).count();
  eval::Accuracy a = eval::MeasureAccuracy(lab, reference.data());
  uint32_t imageHeight = 0;
  heatMap_ = eval::ErrorHeatMap(lab, reference.data(), &imageHeight);  // its first rows are the frame
  char text[320];
  std::snprintf(text, sizeof text,
                "error heat map: %llu pixels judged, traced in %.3f s (%u threads%s), misclassified %.2f %% (false lit %.2f %%, "
                "false shadow %.2f %%); red = false lit, blue = false shadow, grey = correct",
                static_cast<unsigned long long>(a.receiving), traceS, std::thread::hardware_concurrency(),
                buildS > 0 ? (", BVH built in " + std::to_string(buildS).substr(0, 5) + " s").c_str() : "", a.misclassifiedPct(),
                a.falseLitPct(), a.falseShadowPct());
  note_ = text;
  std::printf("viewer: %s\n", text);
  std::fflush(stdout);
#else
  (void)light, (void)technique;
#endif
}

}  // namespace sp::viewer
