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

// Draws a rectangle in pixels at a depth (eval/conformance/gpu-util.h).
using gpu::RectDrawer;

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
