// Shared pieces of the compute, constant-buffer, query and misuse probes: buffers with their
// views, shader creation from inline HLSL, typed readback, exact comparison of integer results,
// query polling and a draw target.
#pragma once
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "probe-helpers.h"

namespace sp::conformance {

// A buffer and the views the probes need of it (null where not requested).
struct BufferViews {
  Ref<Buffer> buffer;
  Ref<UnorderedAccessView> uav;
  Ref<ShaderResourceView> srv;
};

// Structured buffer of `count` elements of `stride` bytes with a UAV (uavFlags: APPEND/COUNTER)
// and, when `withSrv`, an SRV.
BufferViews MakeStructured(Device& dev, uint32_t count, uint32_t stride, const void* init = nullptr, uint32_t uavFlags = 0, bool withSrv = true);
// Raw (byte-address) buffer with a raw UAV; extraBind/extraMisc add e.g. vertex or indirect use.
BufferViews MakeRaw(Device& dev, uint32_t bytes, const void* init = nullptr, uint32_t extraBind = 0, uint32_t extraMisc = 0);
// Typed buffer of `count` elements with a typed UAV of `uavFormat` over [first, first + num).
BufferViews MakeTyped(Device& dev, FORMAT format, uint32_t count, const void* init, uint32_t first, uint32_t num, uint32_t extraBind = 0,
                      uint32_t extraMisc = 0);
// Texture2D (array) with a UAV over every slice.
struct TextureViews {
  Ref<Texture2D> texture;
  Ref<UnorderedAccessView> uav;
  Ref<ShaderResourceView> srv;
};
TextureViews MakeUavTexture(Device& dev, uint32_t w, uint32_t h, FORMAT format, uint32_t slices = 1, const void* init = nullptr,
                            bool withSrv = false);

Ref<ComputeShader> MakeCS(Device& dev, const std::string& source, const std::string& name, const std::string& entry = "main",
                          const std::vector<hlsl::Define>& defines = {});
Ref<VertexShader> MakeVS(Device& dev, const std::string& source, const std::string& name, const std::string& entry = "main",
                         const std::vector<hlsl::Define>& defines = {});
Ref<PixelShader> MakePS(Device& dev, const std::string& source, const std::string& name, const std::string& entry = "main",
                        const std::vector<hlsl::Define>& defines = {});

template <class T>
std::vector<T> ReadBufferAs(Device& dev, Buffer* b) {
  return gpu::ReadAs<T>(gpu::ReadBuffer(dev, *dev.GetImmediateContext(), b));
}
template <class T>
std::vector<T> ReadTextureAs(Device& dev, Texture2D* t, uint32_t subresource = 0) {
  return gpu::ReadAs<T>(gpu::ReadTexture(dev, *dev.GetImmediateContext(), t, subresource));
}

// A render target with its view, bound with a full viewport by Bind().
struct DrawTarget {
  Ref<Texture2D> texture;
  Ref<RenderTargetView> rtv;
  uint32_t width = 0, height = 0;
  void Clear(DeviceContext& ctx, float value) const;
  void Bind(DeviceContext& ctx) const;
};
DrawTarget MakeDrawTarget(Device& dev, uint32_t w, uint32_t h, FORMAT format);

using gpu::RectDrawer;

// Accumulates exact comparisons; the result's error is the number of wrong values.
class Mismatches {
 public:
  explicit Mismatches(std::string what) : what_(std::move(what)) {}
  template <class T>
  void Check(const T& got, const T& expected, const std::string& where) {
    if (got == expected) return;
    if (count_++ == 0) first_ = where + ": got " + ToString(got) + ", D3D11 " + ToString(expected);
  }
  // A condition that must hold, with its explanation.
  void Expect(bool ok, const std::string& why) {
    if (!ok && count_++ == 0) first_ = why;
  }
  size_t count() const { return count_; }
  // Pass with 0 "values" when nothing differed, else a Fail naming the first difference.
  Result Finish(const std::string& unit = "values") const;

 private:
  template <class T>
  static std::string ToString(const T& v) {
    if constexpr (std::is_floating_point_v<T>)
      return std::to_string(v);
    else if constexpr (std::is_integral_v<T>)
      return std::to_string(v);
    else
      return v;
  }
  std::string what_, first_;
  size_t count_ = 0;
};

// Polls GetData until the query's data is available (as D3D11 applications do), up to ~10 s.
bool WaitForQuery(DeviceContext& ctx, Query* q, void* data, uint32_t size);

// Runs `f`, which must throw sp::Error `id` from `call` naming an object that contains `object`
// and a message containing every string in `mentions`. Returns "" when it did, else what went
// wrong; `message` receives what() of the error.
std::string ExpectError(ErrorId id, const std::string& call, const std::string& object, const std::vector<std::string>& mentions,
                        const std::function<void()>& f, std::string* message = nullptr);

// Runs a list of ExpectError cases for one error id: Pass (with the first message as detail)
// when every case raised it correctly, else Fail naming the first case that did not.
struct MisuseCase {
  std::string call, object;
  std::vector<std::string> mentions;
  std::function<void()> f;
};
Result ExpectErrors(ErrorId id, const std::vector<MisuseCase>& cases);

}  // namespace sp::conformance
