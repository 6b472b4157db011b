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

}  // namespace sp
