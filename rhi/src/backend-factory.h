// Entry points of the two backends (backends/vulkan, backends/gl).
#pragma once
#include <sp/rhi/device.h>

namespace sp {

Ref<Device> CreateVulkanDevice(const DeviceDesc& desc);
Ref<Device> CreateGLDevice(const DeviceDesc& desc);

}  // namespace sp
