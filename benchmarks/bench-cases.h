// The three implementations of every case: through sp::, and by hand on Vulkan and on GL.
#pragma once
#include <memory>

#include "bench-common.h"

namespace spbench {

std::unique_ptr<Case> MakeSpCase(CaseId id, sp::Device& dev);

class RawVulkan;
class RawGL;
std::unique_ptr<Case> MakeRawVulkanCase(CaseId id, RawVulkan& vk);
std::unique_ptr<Case> MakeRawGLCase(CaseId id, RawGL& gl);

}  // namespace spbench
