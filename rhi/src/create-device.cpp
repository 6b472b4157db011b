#include "backend-factory.h"

namespace sp {

Ref<Device> CreateDevice(const DeviceDesc& desc) {
  switch (desc.backend) {
    case Backend::Vulkan: return CreateVulkanDevice(desc);
    case Backend::OpenGL: return CreateGLDevice(desc);
  }
  throw Error(ErrorId::INVALID_ARGUMENT, "CreateDevice", "DeviceDesc", "unknown backend");
}

}  // namespace sp
