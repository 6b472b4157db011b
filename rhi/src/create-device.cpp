// Device creation: the one place that knows both backends, and the start-up order the core
// depends on.
#include "backend.h"

namespace sp {

namespace detail {

DeviceBackend::DeviceBackend(Device& core) : core_(core), info_(core.info_) {}

void DeviceBackend::Message(MessageSeverity severity, std::string_view text) const { core_.Message(severity, text); }

}  // namespace detail

Ref<Device> CreateDevice(const DeviceDesc& desc) {
  if (desc.backend != Backend::Vulkan && desc.backend != Backend::OpenGL)
    throw Error(ErrorId::INVALID_ARGUMENT, "CreateDevice", "DeviceDesc", "unknown backend");
  // From here on a throw destroys `device`, whose destructor releases what exists in order
  // (context, objects' backend data, backend).
  Ref<Device> device(new Device(desc));
  device->backend_ = desc.backend == Backend::Vulkan ? detail::CreateVulkanBackend(*device, desc) : detail::CreateGLBackend(*device, desc);
  device->context_.reset(new DeviceContext(device.get(), device->backend_->CreateContextBackend()));
  // Calibration draws through the public API, so it needs the context.
  device->CalibrateDepthBias();
  return device;
}

}  // namespace sp
