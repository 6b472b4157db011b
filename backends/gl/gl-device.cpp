#include "backend-factory.h"
namespace sp {
Ref<Device> CreateGLDevice(const DeviceDesc&) { throw Error(ErrorId::DEVICE_CREATION_FAILED, "CreateDevice", "gl", "backend under construction"); }
}  // namespace sp
