// UAV clears: ClearUnorderedAccessViewFloat converts to the view's format and
// ClearUnorderedAccessViewUint writes raw low bits, on textures, structured and typed buffers.
// (The D3D11 behaviour of compute shaders, append/consume counters, indirect arguments and UAV
// visibility is checked by the conformance probes in eval/conformance/probes/compute-*.cpp.)
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class ComputeTest : public BackendTest {};

Ref<UnorderedAccessView> TextureUav(Device& dev, Texture2D* tex, FORMAT fmt) {
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = fmt;
  d.ViewDimension = UAV_DIMENSION_TEXTURE2D;
  return dev.CreateUnorderedAccessView(tex, &d);
}

// ClearUnorderedAccessViewFloat converts; ClearUnorderedAccessViewUint writes raw low bits.
TEST_P(ComputeTest, UavClears) {
  Ref<Texture2D> f = MakeTexture2D(device(), 4, 4, FORMAT_R16G16B16A16_FLOAT, BIND_UNORDERED_ACCESS);
  Ref<Texture2D> u = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_UNORDERED_ACCESS);
  Ref<Texture2D> r = MakeTexture2D(device(), 4, 4, FORMAT_R32_FLOAT, BIND_UNORDERED_ACCESS);
  const float fv[4] = {0.5f, -2.0f, 1024.0f, 0.25f};
  ctx().ClearUnorderedAccessViewFloat(TextureUav(device(), f.get(), FORMAT_R16G16B16A16_FLOAT).get(), fv);
  const float uf[4] = {0.5f, 2.0f, -1.0f, 0.2f};
  ctx().ClearUnorderedAccessViewFloat(TextureUav(device(), u.get(), FORMAT_R8G8B8A8_UNORM).get(), uf);
  const uint32_t bits[4] = {0x3f800000u, 7, 8, 9};  // R32_FLOAT: the bits of 1.0f
  ctx().ClearUnorderedAccessViewUint(TextureUav(device(), r.get(), FORMAT_R32_FLOAT).get(), bits);
  std::vector<uint16_t> hf = ReadTextureAs<uint16_t>(device(), ctx(), f.get());
  EXPECT_EQ(hf[0], 0x3800);  // 0.5 as half
  EXPECT_EQ(hf[1], 0xc000);  // -2
  EXPECT_EQ(hf[2], 0x6400);  // 1024
  EXPECT_EQ(hf[3], 0x3400);  // 0.25
  std::vector<uint8_t> ub = ReadTexture(device(), ctx(), u.get());
  EXPECT_EQ(ub[0], 128);
  EXPECT_EQ(ub[1], 255);
  EXPECT_EQ(ub[2], 0);
  EXPECT_EQ(ub[3], 51);
  std::vector<float> rf = ReadTextureAs<float>(device(), ctx(), r.get());
  for (float v : rf) EXPECT_EQ(v, 1.0f);
  const uint32_t raw[4] = {0x12345678u, 0x11, 0x22, 0x33};
  ctx().ClearUnorderedAccessViewUint(TextureUav(device(), u.get(), FORMAT_R8G8B8A8_UNORM).get(), raw);
  ub = ReadTexture(device(), ctx(), u.get());
  EXPECT_EQ(ub[0], 0x78);  // low 8 bits of each value
  EXPECT_EQ(ub[1], 0x11);
  EXPECT_EQ(ub[2], 0x22);
  EXPECT_EQ(ub[3], 0x33);

  // Structured: every element gets values[0]. Typed buffer: per-channel low bits.
  UavBuffer s = MakeUavBuffer(device(), 8, 8);
  const uint32_t sv[4] = {0xdeadbeefu, 1, 2, 3};
  ctx().ClearUnorderedAccessViewUint(s.uav.get(), sv);
  for (uint32_t v : ReadBufferAs<uint32_t>(device(), ctx(), s.buffer.get())) EXPECT_EQ(v, 0xdeadbeefu);
  Ref<Buffer> typed = MakeBuffer(device(), BIND_UNORDERED_ACCESS, nullptr, 64);
  UNORDERED_ACCESS_VIEW_DESC td;
  td.Format = FORMAT_R16G16_UINT;
  td.ViewDimension = UAV_DIMENSION_BUFFER;
  td.Buffer = {4, 8, 0};
  Ref<UnorderedAccessView> typedUav = device().CreateUnorderedAccessView(typed.get(), &td);
  const uint32_t tv[4] = {0x10005, 0x20007, 0, 0};
  ctx().ClearUnorderedAccessViewUint(typedUav.get(), tv);
  std::vector<uint16_t> tb = ReadBufferAs<uint16_t>(device(), ctx(), typed.get());
  for (uint32_t i = 0; i < 16; ++i) {
    bool inView = i >= 4 && i < 12;
    EXPECT_EQ(tb[i * 2], inView ? 5 : 0) << i;
    EXPECT_EQ(tb[i * 2 + 1], inView ? 7 : 0) << i;
  }
}

SP_INSTANTIATE_BACKEND_TESTS(ComputeTest);

}  // namespace
}  // namespace sp::test
