#include <sp/rhi/common.h>

namespace sp {

std::string_view ErrorIdName(ErrorId id) {
  switch (id) {
#define SP_X(name) \
  case ErrorId::name: return #name;
    SP_ERROR_IDS(SP_X)
#undef SP_X
  }
  return "UNKNOWN_ERROR";
}

static std::string FormatError(ErrorId id, const std::string& call, const std::string& object, const std::string& detail) {
  std::string s = "[SP_";
  s += ErrorIdName(id);
  s += "] ";
  s += call;
  s += "(";
  s += object;
  s += "): ";
  s += detail;
  return s;
}

Error::Error(ErrorId id, std::string call, std::string object, std::string detail)
    : std::runtime_error(FormatError(id, call, object, detail)),
      id_(id),
      call_(std::move(call)),
      object_(std::move(object)),
      detail_(std::move(detail)) {}

HRESULT HResultFromErrorId(ErrorId id) {
  switch (id) {
    case ErrorId::NOT_SUPPORTED:
    case ErrorId::FORMAT_UNSUPPORTED: return DXGI_ERROR_UNSUPPORTED;
    case ErrorId::OUT_OF_MEMORY: return E_OUTOFMEMORY;
    // Failures of the driver or the platform, not of the arguments.
    case ErrorId::DEVICE_CREATION_FAILED:
    case ErrorId::DEVICE_API_ERROR:
    case ErrorId::SHADER_COMPILE_FAILED: return E_FAIL;
    default: return E_INVALIDARG;
  }
}

}  // namespace sp
