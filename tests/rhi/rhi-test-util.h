// Small helpers shared by the RHI tests (render targets, rectangles drawn from SV_VertexID,
// readback as typed values). Everything goes through the public D3D11-style API.
#pragma once
#include <cstring>
#include <string>
#include <vector>

#include "backend-test.h"

namespace sp::test {

// A render target with its view.
struct Target {
  Ref<Texture2D> texture;
  Ref<RenderTargetView> rtv;
};

inline Target MakeTarget(Device& dev, uint32_t w, uint32_t h, FORMAT fmt, uint32_t extraBind = 0) {
  Target t;
  t.texture = MakeTexture2D(dev, w, h, fmt, BIND_RENDER_TARGET | extraBind);
  t.rtv = dev.CreateRenderTargetView(t.texture.get());
  return t;
}

// Vertex shader drawing the rectangle `rect` (x0, y0, x1, y1 in pixels, y down) of a
// `size`-pixel target as two triangles from SV_VertexID, at depth `depth`.
inline const char* kRectVS = R"(
cbuffer Rect : register(b13) { float4 rect; float2 size; float depth; float pad; };
float4 main(uint id : SV_VertexID) : SV_Position {
  float2 corner = float2((id == 1 || id == 2 || id == 4) ? 1 : 0, (id == 2 || id == 4 || id == 5) ? 1 : 0);
  float2 p = lerp(rect.xy, rect.zw, corner);
  return float4(p.x / size.x * 2 - 1, 1 - p.y / size.y * 2, depth, 1);
}
)";

struct RectConstants {
  float rect[4];
  float size[2];
  float depth;
  float pad;
};

// Binds the rect VS and draws 6 vertices covering `rect` (pixels) at `depth`.
class RectDrawer {
 public:
  explicit RectDrawer(Device& dev) : dev_(dev) {
    vs_ = dev.CreateVertexShader(CompileHlsl(kRectVS, "vs_5_0", "main"));
    constants_ = MakeBuffer(dev, BIND_CONSTANT_BUFFER, nullptr, sizeof(RectConstants));
  }
  void Draw(DeviceContext& ctx, float x0, float y0, float x1, float y1, float w, float h, float depth = 0.5f) {
    RectConstants c{{x0, y0, x1, y1}, {w, h}, depth, 0};
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
    ctx.VSSetShader(vs_.get());
    ctx.VSSetConstantBuffers(13, {constants_.get()});
    ctx.IASetInputLayout(nullptr);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.Draw(6, 0);
  }
  VertexShader* vs() const { return vs_.get(); }

 private:
  Device& dev_;
  Ref<VertexShader> vs_;
  Ref<Buffer> constants_;
};

inline void SetViewport(DeviceContext& ctx, float w, float h, float minDepth = 0, float maxDepth = 1) {
  VIEWPORT vp{0, 0, w, h, minDepth, maxDepth};
  ctx.RSSetViewports(1, &vp);
}

template <class T>
std::vector<T> ReadTextureAs(Device& dev, DeviceContext& ctx, Texture2D* tex, uint32_t sub = 0) {
  return ReadAs<T>(ReadTexture(dev, ctx, tex, sub));
}

template <class T>
std::vector<T> ReadBufferAs(Device& dev, DeviceContext& ctx, Buffer* buf) {
  return ReadAs<T>(ReadBuffer(dev, ctx, buf));
}

// A structured UAV buffer of `count` elements of `stride` bytes and its UAV.
struct UavBuffer {
  Ref<Buffer> buffer;
  Ref<UnorderedAccessView> uav;
};

inline UavBuffer MakeUavBuffer(Device& dev, uint32_t count, uint32_t stride, uint32_t uavFlags = 0) {
  UavBuffer u;
  u.buffer = MakeBuffer(dev, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE, nullptr, count * stride, RESOURCE_MISC_BUFFER_STRUCTURED, stride);
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_UNKNOWN;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {0, count, uavFlags};
  u.uav = dev.CreateUnorderedAccessView(u.buffer.get(), &d);
  return u;
}

}  // namespace sp::test
