// One bench run: the timing phase, then the measured frames (see bench.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bench.h"
#include <sp/tech/hpsm-counters.h>

namespace sp::bench {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The frames after warm-up; all of them when there are too few to drop any.
template <class T>
std::vector<T> AfterWarmup(const std::vector<T>& v) {
  if (v.size() <= kWarmupFrames) return v;
  return std::vector<T>(v.begin() + kWarmupFrames, v.end());
}

std::string Describe(const RunSpec& s) {
  std::string t = s.scene->name + " / " + (s.technique.empty() ? std::string("(custom)") : s.technique);
  for (const auto& [k, v] : s.params) t += " " + k + "=" + v;
  return t + " / " + BackendName(s.backend);
}

// The reference for one lab frame: the fraction of the light visible per pixel (receiving pixels
// only; 0 or 1 for a hard light).
std::vector<float> Reference(eval::ReferenceCache& cache, const tech::LabBuffers& lab, const eval::ReferenceLight& light, bool* cached) {
  eval::LabSurfacePoints p = eval::SurfacePointsOf(lab);
  std::vector<float> out(p.size(), 0.0f);
  *cached = cache.Visibility(p.position.data(), p.normal.data(), p.valid.data(), p.size(), light, out.data());
  return out;
}

}  // namespace

RunResult RunOne(const RunSpec& spec, eval::ReferenceCache& reference, const Progress& progress) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  const scene::Scene& scene = *spec.scene;
  std::unique_ptr<tech::Technique> technique = spec.make ? spec.make() : tech::CreateTechnique(spec.technique);
  tech::ParamValues params = tech::ParamValues::Parse(technique->Name(), technique->Params(), spec.params);

  RunResult r;
  r.scene = scene.name;
  r.technique = technique->Name();
  r.backend = BackendName(spec.backend);
  r.params = params.all();
  r.paramsGiven = spec.params;
  r.width = spec.width;
  r.height = spec.height;
  r.frames = spec.frames;
  r.path = spec.path ? spec.path->name : "static";
  r.sceneTriangles = scene.triangleCount();
  r.light = scene.light;

  DeviceDesc dd;
  dd.backend = spec.backend;
  dd.debug = spec.validate;  // off for speed unless asked
  Ref<Device> device = CreateDevice(dd);
  DeviceContext& ctx = *device->GetImmediateContext();
  r.device = device->Info().deviceName;
  try {
    technique->Configure(*device, params);
  } catch (...) {
    // A refusal can come after the technique made some of its objects: they belong to the device
    // and go first (otherwise the device reports them as outliving it).
    technique.reset();
    throw;
  }
  tech::RendererOptions ro;
  ro.lab = true;
  tech::Renderer renderer(*device, scene, std::move(technique), spec.width, spec.height, ro);
  tech::Technique& tech = renderer.technique();

  auto cameraAt = [&](uint32_t i) {
    if (!spec.path) return scene.camera;
    return spec.path->at(spec.frames > 1 ? double(i) / double(spec.frames - 1) : 0.0);
  };
  // A path recorded with the sun's direction (a sun turning) moves the scene's light with it.
  auto lightAt = [&](uint32_t i) {
    scene::DirectionalLight l = scene.light;
    if (spec.path)
      if (std::optional<glm::vec3> d = spec.path->lightAt(spec.frames > 1 ? double(i) / double(spec.frames - 1) : 0.0)) l.direction = *d;
    return l;
  };
  std::string what = Describe(spec);

  // --- 1. Timing: the normal lit pass, nothing read back.
  say(what + ": timing " + std::to_string(spec.frames) + " frames");
  tech::GpuTimer timer(*device);
  renderer.SetGpuTimer(&timer);
  std::vector<double> triangles, layers;
  for (uint32_t i = 0; i < spec.frames; ++i) {
    // One frame at a time: the GPU is idle when a frame starts, so its CPU time holds no wait for
    // (and, on a software device, no competition with) the previous frame's GPU work.
    ctx.WaitIdle();
    auto t0 = std::chrono::steady_clock::now();
    renderer.RenderFrame(cameraAt(i), lightAt(i));
    ctx.Flush();  // what Present would do: submission is part of a frame's CPU cost
    r.cpuSeries.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    triangles.push_back(double(tech.Stats().trianglesSubmitted));
    layers.push_back(double(tech.Stats().layersRendered));
    if (auto* refinement = dynamic_cast<const tech::AsmCounterSource*>(&tech)) r.asmRefinement.push_back(refinement->AsmFrameCounters());
  }
  if (auto* refinement = dynamic_cast<const tech::AsmCounterSource*>(&tech))
    for (uint32_t key : refinement->AsmResidentPages()) {
      uint32_t level = key >> 28;
      if (r.asmPagesByLevel.size() <= level) r.asmPagesByLevel.resize(level + 1, 0);
      ++r.asmPagesByLevel[level];
    }
  std::vector<tech::FrameTimes> times = timer.Collect(ctx, true);
  renderer.SetGpuTimer(nullptr);
  r.disjointFrames = timer.DisjointFrames();
  for (const tech::FrameTimes& t : times) r.gpuTotalSeries.push_back(t.at("total"));
  std::map<std::string, std::vector<double>> perPass;
  for (const tech::FrameTimes& t : AfterWarmup(times))
    for (const auto& [pass, ms] : t) perPass[pass].push_back(ms);
  for (const auto& [pass, v] : perPass) r.gpuMs[pass] = Median(v);
  r.cpuMs = Median(AfterWarmup(r.cpuSeries));
  r.shadowTriangles = uint64_t(Median(AfterWarmup(triangles)));
  r.shadowLayersRendered = uint64_t(Median(AfterWarmup(layers)));
  r.shadowMemoryBytes = tech.Stats().memoryBytes;
  if (auto* source = dynamic_cast<const tech::HpsmCounterSource*>(&tech)) {
    tech::HpsmCounts c = source->HpsmDecisions();  // counted since the last frame's shadow pass
    if (c.total()) r.hpsmDecisions = {{"minmax", c.minMaxFraction()}, {"plane", c.planeFraction()}, {"filtered", c.filteredFraction()}};
  }

  // --- 2. Measurement: the lab's lit pass, read back and judged.
  // The directional light, or the local light a local-light technique is judged on.
  eval::ReferenceLight light = eval::ReferenceLight::FromScene(scene.light);
  bool judgePointLight = false;
  if (int k = tech.LabLocalLight(scene); k >= 0) {
    std::vector<tech::LocalLight> local = tech::LocalLightsOf(scene);
    if (size_t(k) >= local.size())
      throw std::invalid_argument(r.technique + " is judged on local light " + std::to_string(k) + " but scene '" + scene.name + "' has " +
                                  std::to_string(local.size()));
    const tech::LocalLight& l = local[k];
    r.judgedLocalLight = k;
    judgePointLight = l.type == tech::LocalLight::Point;
    // LocalLightsOf lists the point lights, then the spot lights; their radius is the scene's.
    float radius = size_t(k) < scene.pointLights.size() ? scene.pointLights[k].radius : scene.spotLights[k - scene.pointLights.size()].radius;
    light = l.type == tech::LocalLight::Spot ? eval::ReferenceLight::MakeSpot(l.position, l.direction, l.cosOuter, radius)
                                             : eval::ReferenceLight::MakePoint(l.position, radius);
  }
  r.lightSize = light.size;
  if (light.IsArea()) r.lightSamples = reference.Options().lightSamples;
  // The cache's tracer uses the default options (bench.cpp), so its resolution is known without
  // building a tracer when every frame comes from the cache.
  r.referenceEpsilon = eval::ReferenceOptions{}.relativeEpsilon * eval::ReferenceSceneScale(scene);
  eval::LogHistogram density;
  std::array<eval::LogHistogram, 6> densityByFace;
  double utilizationSum = 0;
  tech::LabBuffers prev;
  std::vector<float> prevReference;
  uint32_t frame = 0;
  reference.SetBeforeTracing([&](size_t pixels) {
    say(what + ": frame " + std::to_string(frame + 1) + "/" + std::to_string(spec.frames) + ": tracing the reference (" +
        std::to_string(pixels) + " pixels, Embree)");
  });
  struct Unset {
    eval::ReferenceCache& cache;
    ~Unset() { cache.SetBeforeTracing({}); }
  } unset{reference};
  for (uint32_t i = 0; i < spec.frames; ++i) {
    frame = i;
    scene::Camera cam = cameraAt(i);
    tech::LabBuffers before;
    if (i > 0) {
      renderer.RenderLitPass(cam, lightAt(i), tech::LitPass::Lab);
      before = renderer.ReadLab();
    }
    renderer.RenderFrame(cam, lightAt(i), tech::LitPass::Lab);
    if (r.judgedLocalLight < 0) light = eval::ReferenceLight::FromScene(lightAt(i));
    tech::LabBuffers now = renderer.ReadLab();
    auto t0 = std::chrono::steady_clock::now();
    bool cached = false;
    std::vector<float> ref = Reference(reference, now, light, &cached);
    double traceMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    eval::Accuracy a = eval::MeasureAccuracy(now, ref.data());
    r.accuracy.add(a);
    r.regions.resize(scene.regions.size());
    for (size_t k = 0; k < scene.regions.size(); ++k) {
      r.regions[k].first = scene.regions[k].name;
      r.regions[k].second.add(eval::MeasureRegionAccuracy(now, ref.data(), scene.regions[k]));
    }
    if (judgePointLight) {
      // Two texels of the faces this frame rendered (their resolution may follow the light's
      // size on screen); a technique whose layers are not six equal square faces (not a cube map)
      // is measured with the band of `cube`'s default 512.
      std::vector<tech::ShadowLayer> layers = tech.Layers();
      bool cubeFaces = layers.size() == 6 && std::all_of(layers.begin(), layers.end(), [&](const tech::ShadowLayer& f) {
        return f.width == layers[0].width && f.height == layers[0].width && f.width > 2;
      });
      float band = eval::SeamBandFor(cubeFaces ? layers[0].width : 512u);
      if (i == 0) r.seamBand = band;
      eval::SeamAccuracy seam = eval::MeasureSeamAccuracy(now, ref.data(), light.position, band);
      r.seam.band.add(seam.band);
      r.seam.elsewhere.add(seam.elsewhere);
      eval::AddTexelDensityByFace(now, light.position, densityByFace);
    }
    r.misclassifiedSeries.push_back(a.misclassifiedPct());
    eval::AddTexelDensity(now, density);
    eval::LogHistogram frameDensity;
    eval::AddTexelDensity(now, frameDensity);
    if (frameDensity.count()) {
      double error = 1.0 / frameDensity.percentile(0.001);
      if (error > r.maxAliasingError) {
        uint64_t texels = 0;
        for (const tech::ShadowLayer& l : tech.Layers()) texels += uint64_t(l.width) * l.height;
        r.maxAliasingError = error;
        r.storageFactor = double(texels) * error * error / (double(spec.width) * spec.height);
      }
    }
    utilizationSum += eval::MeasureUtilization(now, tech.Layers());
    std::ostringstream line;
    line << std::fixed << std::setprecision(3) << what << ": frame " << (i + 1) << "/" << spec.frames << " measured, misclassified "
         << a.misclassifiedPct() << " %, mean |error| " << a.meanAbsError() << ", reference " << (cached ? "from the cache" : "traced in " + std::to_string(int(traceMs)) + " ms");
    if (i > 0) {
      eval::Flicker f = eval::MeasureFlicker(now, before);
      r.flicker.add(f);
      r.flickerSeries.push_back(f.mean());
      r.flickerReprojected.add(eval::MeasureReprojectedFlicker(prev, prev.visibility.data(), now, now.visibility.data()));
      r.flickerReprojectedReference.add(eval::MeasureReprojectedFlicker(prev, prevReference.data(), now, ref.data()));
      line << std::defaultfloat << std::setprecision(2) << ", flicker " << f.mean();
    }
    say(line.str());
    if (i == 0) {
      r.firstFrame = now;
      r.firstReference = ref;
    }
    prev = std::move(now);
    prevReference = std::move(ref);
  }
  r.texelsPerPixelMedian = density.percentile(0.5);
  r.texelsPerPixelP05 = density.percentile(0.05);
  r.densitySamples = density.count();
  for (int f = 0; f < 6; ++f) r.texelsPerPixelMedianByFace[f] = densityByFace[f].percentile(0.5);
  r.utilization = spec.frames ? utilizationSum / spec.frames : 0.0;
  ctx.ClearState();
  ctx.WaitIdle();
  r.validationErrors = device->ValidationErrorCount();
  r.validationEnabled = device->Info().validationEnabled;
  if (r.validationErrors) r.lastValidationError = device->LastValidationError();
  return r;
}

}  // namespace sp::bench
