// One rendered frame, as `render` produces it.
#pragma once
#include <map>
#include <string>
#include <vector>

#include <sp/tech/renderer.h>

namespace sp::cli {

struct RenderJob {
  Backend backend = Backend::Vulkan;
  std::string technique = "basic";
  std::string scene = "default";
  uint32_t width = 1280, height = 720;
  std::map<std::string, std::string> params;
  bool debug = false;
};

struct RenderResult {
  std::vector<uint8_t> rgba;
  double milliseconds = 0;
  DeviceInfo info;
  tech::ShadowStats stats;
  std::map<std::string, std::string> params;
  uint64_t validationErrors = 0;
  size_t triangles = 0;
};

RenderResult RenderOnce(const RenderJob& job);

}  // namespace sp::cli
