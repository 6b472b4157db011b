// The null device: what Direct3D 11 feature level 11_0 guarantees, and nothing a driver adds.
#include <algorithm>
#include <cstring>

#include "null-internal.h"

namespace sp::null {
namespace {

bool IsInteger(const FormatInfo& fi) { return fi.kind == FormatKind::UInt || fi.kind == FormatKind::SInt; }

// CheckFormatSupport of a feature level 11_0 device, from D3D11's "required format support"
// tables, in the rules those tables follow: every colour format is a buffer, a 1D/2D/3D/cube
// texture, loadable and mipmapped; non-integer ones are sampled and blended; all are render
// targets, multisampled and typed UAVs (except sRGB and BGRA, which 11_0 leaves optional for
// UAVs); the depth formats are depth-stencil targets whose R* views sample and compare. What
// 11_0 leaves optional is reported absent, so code validated on a null device asks nothing of a
// real one beyond the feature level. One exception narrows it further: 96-bit R32G32B32 formats
// are buffer and vertex formats only, because ShadowPort's Vulkan and GL backends cannot store
// them as textures (Vulkan makes them optional and Mesa offers none), and a null device must not
// accept what every real one refuses.
uint32_t RequiredSupport(FORMAT format) {
  const FormatInfo& fi = GetFormatInfo(format);
  if (fi.format == FORMAT_UNKNOWN) return 0;
  const uint32_t textures = FORMAT_SUPPORT_TEXTURE1D | FORMAT_SUPPORT_TEXTURE2D | FORMAT_SUPPORT_TEXTURECUBE | FORMAT_SUPPORT_MIP;
  const uint32_t msaa = FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET | FORMAT_SUPPORT_MULTISAMPLE_LOAD;
  if (fi.kind == FormatKind::Typeless) {
    // A typeless resource is a texture of its family; what it can do depends on the view.
    // The packed depth-stencil families (R24G8, R32G8X24) have no colour members.
    return fi.stencilBits ? textures : textures | FORMAT_SUPPORT_TEXTURE3D | FORMAT_SUPPORT_BUFFER;
  }
  if (fi.isDepthView) return textures | FORMAT_SUPPORT_DEPTH_STENCIL | msaa;
  uint32_t out = 0;
  if (fi.readsDepth) {
    out |= textures | FORMAT_SUPPORT_SHADER_LOAD | FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON |
           FORMAT_SUPPORT_SHADER_GATHER | FORMAT_SUPPORT_SHADER_GATHER_COMPARISON | FORMAT_SUPPORT_MULTISAMPLE_LOAD;
  }
  if (fi.readsStencil) out |= textures | FORMAT_SUPPORT_SHADER_LOAD | FORMAT_SUPPORT_MULTISAMPLE_LOAD;
  // R24_UNORM_X8 and friends exist only as views of a depth-stencil texture; R16_UNORM and
  // R32_FLOAT read depth too but are colour formats as well, and go on below.
  if (fi.stencilBits) return out;
  const bool srgb = fi.kind == FormatKind::UNormSRGB;
  const bool bgra = format == FORMAT_B8G8R8A8_UNORM || format == FORMAT_B8G8R8A8_UNORM_SRGB || format == FORMAT_B8G8R8A8_TYPELESS;
  const bool wide = fi.bytesPerElement == 12;  // R32G32B32: see above
  out |= FORMAT_SUPPORT_SHADER_LOAD;
  if (!wide) out |= textures | FORMAT_SUPPORT_TEXTURE3D;
  if (!srgb) out |= FORMAT_SUPPORT_BUFFER | FORMAT_SUPPORT_IA_VERTEX_BUFFER;
  if (format == FORMAT_R16_UINT || format == FORMAT_R32_UINT) out |= FORMAT_SUPPORT_IA_INDEX_BUFFER;
  if (!IsInteger(fi)) out |= FORMAT_SUPPORT_SHADER_SAMPLE | FORMAT_SUPPORT_SHADER_GATHER;
  if (!wide) {
    out |= FORMAT_SUPPORT_RENDER_TARGET | msaa;
    if (!IsInteger(fi)) out |= FORMAT_SUPPORT_BLENDABLE | FORMAT_SUPPORT_MULTISAMPLE_RESOLVE;
    if (!srgb && !bgra) out |= FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW;
  }
  return out;
}

class NullDevice final : public detail::DeviceBackend {
 public:
  NullDevice(Device& core, const DeviceDesc& desc) : DeviceBackend(core) {
    info_.backend = Backend::Null;
    info_.apiVersion = "none (null backend: validation only, no rendering)";
    info_.deviceName = "null device (Direct3D 11 feature level 11_0 limits)";
    info_.driverName = "none";
    // No GPU clock exists: timestamps read 0, in nanosecond ticks as on GL.
    info_.timestampFrequency = 1000000000ull;
    info_.maxMsaaSamples = std::min(MaxSampleCountBackend(FORMAT_R8G8B8A8_UNORM), MaxSampleCountBackend(FORMAT_D32_FLOAT));
    // D3D11 clamps depth bias on every feature level. The array index from the vertex shader is
    // D3D11.3's optional feature, claimed so that the core's checks around it can be exercised;
    // the Disable* flags turn both off as on a real device.
    info_.depthBiasClamp = !desc.disableDepthBiasClamp;
    info_.vsRenderTargetArrayIndex = !desc.disableVsRenderTargetArrayIndex;
  }

  std::unique_ptr<detail::BackendObject> CreateBufferBackend(Buffer& buffer, const SUBRESOURCE_DATA* init) override {
    const BUFFER_DESC& d = buffer.GetDesc();
    if (d.Usage != USAGE_DYNAMIC && d.Usage != USAGE_STAGING) return nullptr;
    auto r = std::make_unique<NullResource>();
    r->subresources.resize(1);
    if (init) {
      const uint8_t* p = static_cast<const uint8_t*>(init->pSysMem);
      r->subresources[0].assign(p, p + d.ByteWidth);
    }
    return r;
  }

  std::unique_ptr<detail::BackendObject> CreateTextureBackend(Texture& texture, const SUBRESOURCE_DATA* init) override {
    const TextureShape& s = texture.Shape();
    if (s.usage != USAGE_DYNAMIC && s.usage != USAGE_STAGING) return nullptr;
    auto r = std::make_unique<NullResource>();
    r->subresources.resize(s.subresourceCount());
    if (init) {
      const uint32_t bpe = GetFormatInfo(s.format).bytesPerElement;
      for (uint32_t sub = 0; sub < s.subresourceCount(); ++sub) {
        const detail::Subresource at = detail::SubresourceOf(s, sub);
        const uint32_t row = at.width * bpe, h = at.height, d = at.depth;
        std::vector<uint8_t>& block = r->subresources[sub];
        block.resize(size_t(row) * h * d);
        for (uint32_t z = 0; z < d; ++z)
          for (uint32_t y = 0; y < h; ++y)
            std::memcpy(block.data() + (size_t(z) * h + y) * row,
                        static_cast<const uint8_t*>(init[sub].pSysMem) + size_t(z) * init[sub].SysMemSlicePitch + size_t(y) * init[sub].SysMemPitch, row);
      }
    }
    return r;
  }

  // Views, samplers, shaders and queries need no backend data: nothing is ever drawn with them.
  std::unique_ptr<detail::BackendObject> CreateViewBackend(View&) override { return nullptr; }
  std::unique_ptr<detail::BackendObject> CreateSamplerBackend(SamplerState&) override { return nullptr; }
  std::unique_ptr<detail::BackendObject> CreateShaderBackend(Shader&) override { return nullptr; }
  std::unique_ptr<detail::BackendObject> CreateQueryBackend(Query&) override { return nullptr; }
  std::unique_ptr<detail::ContextBackend> CreateContextBackend() override { return CreateNullContext(); }

  uint32_t FormatSupportBackend(FORMAT format) const override { return RequiredSupport(format); }

  // 11_0 requires 4x for every render-target and depth format and 8x for all but the 128-bit
  // ones; 2x is offered by every 11_0 part and accepted here too.
  uint32_t MaxSampleCountBackend(FORMAT format) const override {
    if (!(RequiredSupport(format) & FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET)) return 1;
    return GetFormatInfo(format).bytesPerElement == 16 ? 4 : 8;
  }
  bool SampleCountSupportedBackend(FORMAT format, uint32_t count) const override {
    return count && (count & (count - 1)) == 0 && count <= MaxSampleCountBackend(format);
  }
};

}  // namespace
}  // namespace sp::null

namespace sp::detail {
std::unique_ptr<DeviceBackend> CreateNullBackend(Device& core, const DeviceDesc& desc) { return std::make_unique<null::NullDevice>(core, desc); }
}  // namespace sp::detail
