#include "backend-factory.h"
namespace sp {
Ref<Device> CreateVulkanDevice(const DeviceDesc&) { throw Error(ErrorId::DEVICE_CREATION_FAILED, "CreateDevice", "vulkan", "backend under construction"); }
}  // namespace sp
