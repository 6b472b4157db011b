// Small helpers for programs that check GPU results on the CPU (conformance probes, tests):
// creating resources tersely, reading them back the D3D11 way (staging copy + Map READ), and
// compiling inline HLSL with the project's include path and cache.
#pragma once
#include <cstring>
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

namespace sp::gpu {

std::vector<uint8_t> ReadTexture(Device& dev, DeviceContext& ctx, Texture2D* tex, uint32_t subresource = 0);
std::vector<uint8_t> ReadBuffer(Device& dev, DeviceContext& ctx, Buffer* buf);
template <class T>
std::vector<T> ReadAs(const std::vector<uint8_t>& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

Ref<Buffer> MakeBuffer(Device& dev, uint32_t bind, const void* data, uint32_t size, uint32_t misc = 0, uint32_t stride = 0);
Ref<Texture2D> MakeTexture2D(Device& dev, uint32_t w, uint32_t h, FORMAT fmt, uint32_t bind, const void* data = nullptr,
                             uint32_t mips = 1, uint32_t arraySize = 1, uint32_t samples = 1, uint32_t misc = 0);

// Compiles inline HLSL; `name` appears in error messages ("conformance/depth-bias.hlsl").
ShaderBytecode CompileInline(const std::string& source, const std::string& name, const std::string& target,
                             const std::string& entry, const std::vector<hlsl::Define>& defines = {});

// A vertex shader drawing a full-viewport triangle from SV_VertexID (no vertex buffers).
extern const char* const kFullscreenVS;

// Draws the rectangle (x0, y0)-(x1, y1), in pixels from the top left, of a w x h target at
// `depth` as two triangles from SV_VertexID; its constants use VS slot b13.
class RectDrawer {
 public:
  explicit RectDrawer(Device& dev);
  // Binds the vertex shader, its constants and the topology (no input layout), then draws.
  void Draw(DeviceContext& ctx, float x0, float y0, float x1, float y1, float w, float h, float depth = 0.5f);
  VertexShader* vs() const { return vs_.get(); }

 private:
  Ref<VertexShader> vs_;
  Ref<Buffer> constants_;
};

}  // namespace sp::gpu
