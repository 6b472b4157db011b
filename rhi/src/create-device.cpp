// Device creation: the one place that knows every backend, and the start-up order the core
// depends on.
#include "backend.h"

namespace sp {

namespace detail {

DeviceBackend::DeviceBackend(Device& core) : core_(core), info_(core.info_) {}

void DeviceBackend::Message(MessageSeverity severity, std::string_view text) const { core_.Message(severity, text); }

}  // namespace detail

Ref<Device> CreateDevice(const DeviceDesc& desc) {
  if (desc.backend != Backend::Vulkan && desc.backend != Backend::OpenGL && desc.backend != Backend::Null)
    throw Error(ErrorId::INVALID_ARGUMENT, "CreateDevice", "DeviceDesc", "unknown backend");
  // From here on a throw destroys `device`, whose destructor releases what exists in order
  // (context, objects' backend data, backend).
  Ref<Device> device(new Device(desc));
  switch (desc.backend) {
    case Backend::Vulkan: device->backend_ = detail::CreateVulkanBackend(*device, desc); break;
    case Backend::OpenGL: device->backend_ = detail::CreateGLBackend(*device, desc); break;
    case Backend::Null: device->backend_ = detail::CreateNullBackend(*device, desc); break;
  }
  device->context_.reset(new DeviceContext(device.get(), device->backend_->CreateContextBackend()));
  // Calibration draws through the public API, so it needs the context. A null device draws
  // nothing to measure; its scales stay 1, D3D11's own units.
  if (desc.backend != Backend::Null) device->CalibrateDepthBias();
  return device;
}

}  // namespace sp
