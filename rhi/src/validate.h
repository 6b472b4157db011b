// Helpers shared by the core's validation code.
#pragma once
#include <sp/rhi/context.h>

#include <string>

#include "backend.h"

namespace sp {

[[noreturn]] inline void Fail(ErrorId id, const char* call, const std::string& object, const std::string& detail) {
  throw Error(id, call, object, detail);
}

inline std::string Describe(const Object* o) { return o ? o->Describe() : std::string("null"); }

inline bool IsDepthFormat(FORMAT f) {
  FormatKind k = GetFormatInfo(f).kind;
  return k == FormatKind::Depth || k == FormatKind::DepthStencil;
}

// Number of mips of a full chain for the largest dimension.
inline uint32_t FullMipCount(uint32_t w, uint32_t h, uint32_t d) {
  uint32_t m = w > h ? w : h;
  if (d > m) m = d;
  uint32_t n = 1;
  while (m > 1) {
    m >>= 1;
    ++n;
  }
  return n;
}

// Texture (or null) behind a resource pointer.
inline const Texture* AsTexture(const Resource* r) {
  return r && r->GetType() != RESOURCE_DIMENSION_BUFFER ? static_cast<const Texture*>(r) : nullptr;
}
inline const Buffer* AsBuffer(const Resource* r) {
  return r && r->GetType() == RESOURCE_DIMENSION_BUFFER ? static_cast<const Buffer*>(r) : nullptr;
}

// The array-index output a vertex shader writes ("SV_RenderTargetArrayIndex" or
// "SV_ViewportArrayIndex", the first found), or null.
inline const char* ArrayIndexOutput(const ShaderReflection& r) {
  for (const SignatureElement& o : r.outputs) {
    if (o.semanticName == "SV_RENDERTARGETARRAYINDEX") return "SV_RenderTargetArrayIndex";
    if (o.semanticName == "SV_VIEWPORTARRAYINDEX") return "SV_ViewportArrayIndex";
  }
  return nullptr;
}

std::string BindFlagsToString(uint32_t flags);
std::string UsageName(USAGE usage);
// HLSL's name of a resource dimension ("Texture2DArray", "Buffer"; "raw buffer" for BUFFEREX).
const char* SrvDimensionName(SRV_DIMENSION d);

}  // namespace sp
