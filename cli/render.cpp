// `shadowport render` and `shadowport demo`.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli.h"
#include "render-job.h"

namespace sp::cli {

RenderResult RenderOnce(const RenderJob& job) {
  DeviceDesc dd;
  dd.backend = job.backend;
  dd.debug = job.debug;
  Ref<Device> device = CreateDevice(dd);
  scene::Scene scene = scene::LoadScene(job.scene);
  std::unique_ptr<tech::Technique> technique = tech::CreateTechnique(job.technique);
  tech::ParamValues params = tech::ParamValues::Parse(job.technique, technique->Params(), job.params);
  technique->Configure(*device, params);
  tech::Renderer renderer(*device, scene, std::move(technique), job.width, job.height);

  auto t0 = std::chrono::steady_clock::now();
  renderer.RenderFrame(scene.camera, scene.light);
  RenderResult r;
  r.rgba = renderer.ReadColor();
  r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.info = device->Info();
  r.stats = renderer.technique().Stats();
  r.params = params.all();
  r.validationErrors = device->ValidationErrorCount();
  r.triangles = scene.triangleCount();
  return r;
}

static RenderJob JobFromArgs(const Args& a) {
  RenderJob job;
  if (!ParseBackend(a.get("backend", "vulkan"), &job.backend))
    throw std::invalid_argument("--backend must be vulkan or gl (got '" + a.get("backend") + "')");
  job.technique = a.get("technique", "basic");
  job.scene = a.get("scene", "default");
  ParseSize(a.get("size", "1280x720"), &job.width, &job.height);
  job.params = ParseParams(a.getAll("param"));
  job.debug = a.has("validate");
  return job;
}

int RunRender(const Args& a) {
  a.expectOnly({"backend", "technique", "scene", "size", "out", "param", "validate"});
  RenderJob job = JobFromArgs(a);
  std::string out = a.get("out", "out/render.png");
  RenderResult r = RenderOnce(job);
  WritePng(out, job.width, job.height, r.rgba.data());
  std::printf("%s: %s, technique %s, scene %s, %ux%u, frame %.1f ms -> %s\n", BackendName(job.backend), r.info.deviceName.c_str(),
              job.technique.c_str(), job.scene.c_str(), job.width, job.height, r.milliseconds, out.c_str());
  return r.validationErrors ? 1 : 0;
}

int RunDemo(const Args& a) {
  a.expectOnly({"out", "size", "technique", "scene", "param"});
  namespace fs = std::filesystem;
  fs::path dir = a.get("out", "out/demo");
  fs::create_directories(dir);
  RenderJob job;
  job.technique = a.get("technique", "basic");
  job.scene = a.get("scene", "default");
  ParseSize(a.get("size", "1280x720"), &job.width, &job.height);
  job.params = ParseParams(a.getAll("param"));
  job.debug = true;  // the demo doubles as a smoke test: validation on

  RenderResult results[2];
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  std::string files[2];
  for (int i = 0; i < 2; ++i) {
    job.backend = backends[i];
    std::fprintf(stderr, "rendering %s / %s on %s...\n", job.scene.c_str(), job.technique.c_str(), BackendName(job.backend));
    results[i] = RenderOnce(job);
    files[i] = (dir / (job.scene + "-" + job.technique + "-" + BackendName(job.backend) + ".png")).string();
    WritePng(files[i], job.width, job.height, results[i].rgba.data());
  }
  ImageDiff diff = DiffImages(job.width, job.height, results[0].rgba, results[1].rgba);
  std::string diffFile = (dir / (job.scene + "-" + job.technique + "-diff.png")).string();
  WritePng(diffFile, job.width, job.height, diff.heatmap.data());

  std::ofstream md(dir / "summary.md");
  md << "# ShadowPort demo\n\n";
  md << "Scene `" << job.scene << "` (" << results[0].triangles << " triangles), technique `" << job.technique << "`, " << job.width << "x"
     << job.height << ".\n\n";
  md << "| | Vulkan | OpenGL |\n|---|---|---|\n";
  md << "| device | " << results[0].info.deviceName << " | " << results[1].info.deviceName << " |\n";
  md << "| API | " << results[0].info.apiVersion << " | " << results[1].info.apiVersion << " |\n";
  md << "| image | " << fs::path(files[0]).filename().string() << " | " << fs::path(files[1]).filename().string() << " |\n";
  md << "| frame time (first frame, ms, includes pipeline creation) | " << results[0].milliseconds << " | " << results[1].milliseconds << " |\n";
  md << "| shadow map memory (bytes) | " << results[0].stats.memoryBytes << " | " << results[1].stats.memoryBytes << " |\n";
  md << "| triangles in shadow pass | " << results[0].stats.trianglesSubmitted << " | " << results[1].stats.trianglesSubmitted << " |\n";
  md << "| depth-bias scale D16 / D24 / D32 (measured) | " << results[0].info.depthBiasScaleD16 << " / " << results[0].info.depthBiasScaleD24
     << " / " << results[0].info.depthBiasScaleD32 << " | " << results[1].info.depthBiasScaleD16 << " / " << results[1].info.depthBiasScaleD24
     << " / " << results[1].info.depthBiasScaleD32 << " |\n";
  md << "| validation errors | " << results[0].validationErrors << " | " << results[1].validationErrors << " |\n\n";
  md << "Parameters:";
  for (const auto& [k, v] : results[0].params) md << " `" << k << "=" << v << "`";
  md << "\n\nCross-backend comparison: " << diff.differingPixels << " of " << size_t(job.width) * job.height
     << " pixels differ (largest channel difference " << diff.maxDifference << "); heat map: " << fs::path(diffFile).filename().string()
     << ".\n";

  std::printf("demo images:\n  %s\n  %s\n  %s (difference heat map)\nsummary: %s\n", files[0].c_str(), files[1].c_str(), diffFile.c_str(),
              (dir / "summary.md").string().c_str());
  std::printf("cross-backend: %zu differing pixels (max channel difference %d)\n", diff.differingPixels, diff.maxDifference);
  return (results[0].validationErrors || results[1].validationErrors) ? 1 : 0;
}

ImageDiff DiffImages(uint32_t w, uint32_t h, const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  ImageDiff d;
  d.heatmap.resize(size_t(w) * h * 4);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    int m = 0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a[i * 4 + c]) - int(b[i * 4 + c])));
    d.maxDifference = std::max(d.maxDifference, m);
    if (m) ++d.differingPixels;
    // Grey copy of the image with differences in red, so they can be located.
    uint8_t g = uint8_t((a[i * 4] + a[i * 4 + 1] + a[i * 4 + 2]) / 12);
    d.heatmap[i * 4 + 0] = m ? uint8_t(std::min(255, 128 + m * 16)) : g;
    d.heatmap[i * 4 + 1] = m ? 0 : g;
    d.heatmap[i * 4 + 2] = m ? 0 : g;
    d.heatmap[i * 4 + 3] = 255;
  }
  return d;
}

}  // namespace sp::cli
