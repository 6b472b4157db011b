// Renders one frame of a scene with a technique on both backends (validation on, no messages
// allowed), for the techniques' cross-backend image tests.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "backend-test.h"
#include <sp/tech/renderer.h>

namespace sp::test {

struct CrossBackendFrame {
  std::vector<uint8_t> images[2];  // RGBA8 colour: Vulkan, OpenGL
  // Both backends run on Mesa's shared rasterizer (llvmpipe/lavapipe), where the images must be
  // identical; other drivers may differ in sub-pixel precision and filter weights at shadow edges.
  bool mesa = false;
};

inline CrossBackendFrame RenderOnBothBackends(const std::string& technique, const std::map<std::string, std::string>& params,
                                              const scene::Scene& s, uint32_t w, uint32_t h) {
  CrossBackendFrame f;
  bool llvmpipe[2] = {false, false};
  const Backend backends[2] = {Backend::Vulkan, Backend::OpenGL};
  for (int i = 0; i < 2; ++i) {
    DeviceDesc dd;
    dd.backend = backends[i];
    Ref<Device> dev = CreateDevice(dd);
    llvmpipe[i] = dev->Info().deviceName.find("llvmpipe") != std::string::npos;
    std::unique_ptr<tech::Technique> t = tech::CreateTechnique(technique);
    t->Configure(*dev, tech::ParamValues::Parse(technique, t->Params(), params));
    tech::Renderer r(*dev, s, std::move(t), w, h);
    r.RenderFrame(s.camera, s.light);
    f.images[i] = r.ReadColor();
    EXPECT_EQ(dev->ValidationErrorCount(), 0u) << BackendName(backends[i]) << ": " << dev->LastValidationError();
  }
  f.mesa = llvmpipe[0] && llvmpipe[1];
  return f;
}

}  // namespace sp::test
