// `shadowport render`: one frame of a scene with a technique, on one backend.
#include <chrono>
#include <cstdio>

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
  job.backend = ParseRenderingBackend(a.get("backend", "vulkan"), "vulkan or gl");
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

}  // namespace sp::cli
