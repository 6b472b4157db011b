// ClearUnorderedAccessView{Uint,Float} on the formats whose encodings are easy to get wrong
// (packed 10:10:10:2 and 11:11:10, SNORM, 16-bit float), on parts of arrays and on 3D
// textures. Expected bits follow D3D11's conversion rules, written out by hand per case.
#include <limits>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class UavClearTest : public BackendTest {
 protected:
  bool TypedUav(FORMAT f) { return (device().CheckFormatSupport(f) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW) != 0; }
  Ref<UnorderedAccessView> Uav2D(Texture2D* t, FORMAT f) {
    UNORDERED_ACCESS_VIEW_DESC d;
    d.Format = f;
    d.ViewDimension = UAV_DIMENSION_TEXTURE2D;
    d.Texture2D = {0};
    return device().CreateUnorderedAccessView(t, &d);
  }
};

TEST_P(UavClearTest, PackedAndSignedFloatEncodings) {
  struct Case {
    FORMAT format;
    float values[4];
    uint32_t expect;  // the 32-bit texel
  };
  const Case cases[] = {
      // 10-bit: round(0.5 * 1023) = 512 (511.5), 1023, round(0.25 * 1023) = 256 (255.75); 2-bit alpha round(0.7 * 3) = 2.
      {FORMAT_R10G10B10A2_UNORM, {0.5f, 1.0f, 0.25f, 0.7f}, 512u | (1023u << 10) | (256u << 20) | (2u << 30)},
      // 11:11:10 floats (5-bit exponent, bias 15): 1.0 = e15, 2.0 = e16, 0.5 = e14; negatives clamp to 0.
      {FORMAT_R11G11B10_FLOAT, {1.0f, 2.0f, 0.5f, 0.0f}, (15u << 6) | ((16u << 6) << 11) | ((14u << 5) << 22)},
      {FORMAT_R11G11B10_FLOAT, {-3.0f, 0.0f, 1.0f, 0.0f}, 0u | ((15u << 5) << 22)},
      // SNORM: round(v * 127), -1 -> -127 (0x81), -0.25 -> -32 (0xe0), 0.75 -> 95 (0x5f), 2 clamps to 127.
      {FORMAT_R8G8B8A8_SNORM, {-1.0f, -0.25f, 0.75f, 2.0f}, 0x81u | (0xe0u << 8) | (0x5fu << 16) | (0x7fu << 24)},
      // Half floats: 1.5 = 0x3e00, -0.125 = 0xb000.
      {FORMAT_R16G16_FLOAT, {1.5f, -0.125f, 0.0f, 0.0f}, 0x3e00u | (0xb000u << 16)},
  };
  for (const Case& c : cases) {
    if (!TypedUav(c.format)) continue;
    Ref<Texture2D> tex = MakeTexture2D(device(), 4, 2, c.format, BIND_UNORDERED_ACCESS);
    ctx().ClearUnorderedAccessViewFloat(Uav2D(tex.get(), c.format).get(), c.values);
    for (uint32_t v : ReadTextureAs<uint32_t>(device(), ctx(), tex.get())) ASSERT_EQ(v, c.expect) << FormatName(c.format);
  }
}

// A TYPELESS texture cleared through a float view of another member of its family.
TEST_P(UavClearTest, TypelessTextureThroughFloatView) {
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_TYPELESS, BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE);
  const float v[4] = {0.2f, 0.4f, 0.6f, 1.0f};
  ctx().ClearUnorderedAccessViewFloat(Uav2D(tex.get(), FORMAT_R8G8B8A8_UNORM).get(), v);
  // round(0.2 * 255) = 51, round(0.4 * 255) = 102, round(0.6 * 255) = 153.
  for (uint32_t t : ReadTextureAs<uint32_t>(device(), ctx(), tex.get())) EXPECT_EQ(t, 51u | (102u << 8) | (153u << 16) | (255u << 24));
  const uint32_t u[4] = {0x101, 0x202, 0x303, 0x404};  // low 8 bits per channel
  ctx().ClearUnorderedAccessViewUint(Uav2D(tex.get(), FORMAT_R8G8B8A8_UINT).get(), u);
  for (uint32_t t : ReadTextureAs<uint32_t>(device(), ctx(), tex.get())) EXPECT_EQ(t, 0x04030201u);
}

// Clearing slices 1..2 of a four-slice array leaves slices 0 and 3 alone.
TEST_P(UavClearTest, ArraySliceRange) {
  std::vector<uint32_t> init(4 * 4 * 4, 7);
  TEXTURE2D_DESC d;
  d.Width = d.Height = 4;
  d.ArraySize = 4;
  d.Format = FORMAT_R32_UINT;
  d.BindFlags = BIND_UNORDERED_ACCESS;
  std::vector<SUBRESOURCE_DATA> sd(4, SUBRESOURCE_DATA{nullptr, 16, 0});
  for (uint32_t i = 0; i < 4; ++i) sd[i].pSysMem = init.data() + i * 16;
  Ref<Texture2D> tex = device().CreateTexture2D(d, sd.data());
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_R32_UINT;
  ud.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
  ud.Texture2DArray = {0, 1, 2};
  Ref<UnorderedAccessView> uav = device().CreateUnorderedAccessView(tex.get(), &ud);
  const uint32_t v[4] = {42, 0, 0, 0};
  ctx().ClearUnorderedAccessViewUint(uav.get(), v);
  for (uint32_t slice = 0; slice < 4; ++slice)
    for (uint32_t t : ReadTextureAs<uint32_t>(device(), ctx(), tex.get(), slice)) EXPECT_EQ(t, slice == 1 || slice == 2 ? 42u : 7u) << slice;
}

// A whole mip of a Texture3D, read back through a compute shader.
TEST_P(UavClearTest, Texture3DMip) {
  TEXTURE3D_DESC d;
  d.Width = d.Height = d.Depth = 4;
  d.MipLevels = 2;
  d.Format = FORMAT_R32_FLOAT;
  d.BindFlags = BIND_UNORDERED_ACCESS | BIND_SHADER_RESOURCE;
  Ref<Texture3D> tex = device().CreateTexture3D(d);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.Format = FORMAT_R32_FLOAT;
  ud.ViewDimension = UAV_DIMENSION_TEXTURE3D;
  ud.Texture3D = {1, 0, 2};
  Ref<UnorderedAccessView> mip1 = device().CreateUnorderedAccessView(tex.get(), &ud);
  ud.Texture3D = {0, 0, 4};
  Ref<UnorderedAccessView> mip0 = device().CreateUnorderedAccessView(tex.get(), &ud);
  const float a[4] = {2.5f, 0, 0, 0}, b[4] = {-1.0f, 0, 0, 0};
  ctx().ClearUnorderedAccessViewFloat(mip0.get(), a);
  ctx().ClearUnorderedAccessViewFloat(mip1.get(), b);
  const char* cs = R"(
Texture3D<float> tex : register(t0);
RWStructuredBuffer<float> output : register(u0);
[numthreads(1, 1, 1)] void main() {
  float sum0 = 0, sum1 = 0;
  for (int z = 0; z < 4; ++z) for (int y = 0; y < 4; ++y) for (int x = 0; x < 4; ++x) sum0 += tex.Load(int4(x, y, z, 0));
  for (int z = 0; z < 2; ++z) for (int y = 0; y < 2; ++y) for (int x = 0; x < 2; ++x) sum1 += tex.Load(int4(x, y, z, 1));
  output[0] = sum0; output[1] = sum1;
}
)";
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  UavBuffer out = MakeUavBuffer(device(), 2, 4);
  ctx().CSSetShader(shader.get());
  ctx().CSSetShaderResources(0, {srv.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<float>(device(), ctx(), out.buffer.get()), (std::vector<float>{2.5f * 64, -1.0f * 8}));
}

// Typed buffer views with 4-byte and 16-byte elements, and a raw view (values[0] per word).
TEST_P(UavClearTest, TypedAndRawBufferViews) {
  BUFFER_DESC bd;
  bd.ByteWidth = 128;
  bd.BindFlags = BIND_UNORDERED_ACCESS;
  bd.MiscFlags = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS;
  Ref<Buffer> buf = device().CreateBuffer(bd);
  UNORDERED_ACCESS_VIEW_DESC ud;
  ud.ViewDimension = UAV_DIMENSION_BUFFER;
  ud.Format = FORMAT_R8G8B8A8_UINT;
  ud.Buffer = {0, 8, 0};  // bytes 0..31
  Ref<UnorderedAccessView> rgba8 = device().CreateUnorderedAccessView(buf.get(), &ud);
  ud.Format = FORMAT_R32G32B32A32_UINT;
  ud.Buffer = {2, 2, 0};  // bytes 32..63
  Ref<UnorderedAccessView> rgba32 = device().CreateUnorderedAccessView(buf.get(), &ud);
  ud.Format = FORMAT_R32_TYPELESS;
  ud.Buffer = {16, 8, BUFFER_UAV_FLAG_RAW};  // bytes 64..95
  Ref<UnorderedAccessView> raw = device().CreateUnorderedAccessView(buf.get(), &ud);
  const uint32_t a[4] = {0x1ff, 2, 3, 4}, b[4] = {10, 20, 30, 40}, c[4] = {0xcafef00du, 1, 1, 1};
  ctx().ClearUnorderedAccessViewUint(rgba8.get(), a);
  ctx().ClearUnorderedAccessViewUint(rgba32.get(), b);
  ctx().ClearUnorderedAccessViewUint(raw.get(), c);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device(), ctx(), buf.get());
  for (uint32_t i = 0; i < 32; ++i) {
    uint32_t expect = i < 8 ? 0x040302ffu : i < 16 ? b[i % 4] : i < 24 ? 0xcafef00du : 0u;
    EXPECT_EQ(got[i], expect) << "word " << i;
  }
}

// Where the backends once converted differently (Vulkan packed on the CPU rounding to nearest, GL
// let the driver convert): D3D11 rounds toward zero into 16-bit and 11/10-bit floats, turns NaN
// into 0 for UNORM, and rounds UNORM to nearest. Texture and typed-buffer views get the same bits.
TEST_P(UavClearTest, FloatConversionsFollowD3D11) {
  const float halfUlp = 1.0f / 1024, f11Ulp = 1.0f / 64, f10Ulp = 1.0f / 32;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  struct Case {
    FORMAT format;
    float values[4];
    uint32_t expect[2];  // the texel's words (8-byte formats use both)
  };
  const Case cases[] = {
      // 1 + 3/4 ulp rounds down to 1.0 (0x3c00), -(1 + 3/4 ulp) to -1.0 (0xbc00); round-to-nearest would add 1.
      {FORMAT_R16G16_FLOAT, {1.0f + 0.75f * halfUlp, -(1.0f + 0.75f * halfUlp), 0, 0}, {0x3c00u | (0xbc00u << 16), 0}},
      // 11-bit and 10-bit floats: 1.0 is exponent 15, mantissa 0, whatever 3/4 of an ulp is added.
      {FORMAT_R11G11B10_FLOAT, {1.0f + 0.75f * f11Ulp, 2.0f + 1.5f * f11Ulp, 1.0f + 0.75f * f10Ulp, 0}, {(15u << 6) | ((16u << 6) << 11) | ((15u << 5) << 22), 0}},
      // NaN -> 0, 0.5 * 255 = 127.5 -> 128, -INF -> 0, +INF -> 255.
      {FORMAT_R8G8B8A8_UNORM, {nan, 0.5f, -inf, inf}, {0u | (128u << 8) | (0u << 16) | (255u << 24), 0}},
      // 0.5 * 65535 = 32767.5 -> 32768; 1/3 * 65535 = 21845.
      {FORMAT_R16G16_UNORM, {0.5f, 1.0f / 3.0f, 0, 0}, {32768u | (21845u << 16), 0}},
      // Four halves: 1 + 3/4 ulp -> 0x3c00, 0.5 -> 0x3800, NaN stays NaN (exponent all ones, mantissa non-zero), 65520 -> the largest finite 0x7bff.
      {FORMAT_R16G16B16A16_FLOAT, {1.0f + 0.75f * halfUlp, 0.5f, nan, 65520.0f}, {0x3c00u | (0x3800u << 16), 0x7e00u | (0x7bffu << 16)}},
  };
  // A NaN may come back with another payload: D3D11 only keeps it a NaN.
  auto same = [](const Case& c, uint32_t word, uint32_t got) {
    if (c.format != FORMAT_R16G16B16A16_FLOAT || word != 1) return got == c.expect[word];
    return (got >> 16) == (c.expect[1] >> 16) && (got & 0x7c00u) == 0x7c00u && (got & 0x3ffu) != 0;
  };
  uint32_t checked = 0;
  for (const Case& c : cases) {
    if (!TypedUav(c.format)) continue;
    const uint32_t words = GetFormatInfo(c.format).bytesPerElement / 4;
    Ref<Texture2D> tex = MakeTexture2D(device(), 4, 2, c.format, BIND_UNORDERED_ACCESS);
    ctx().ClearUnorderedAccessViewFloat(Uav2D(tex.get(), c.format).get(), c.values);
    std::vector<uint32_t> got = ReadTextureAs<uint32_t>(device(), ctx(), tex.get());
    for (size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same(c, i % words, got[i])) << FormatName(c.format) << " texture word " << i << ": " << std::hex << got[i];
    // The same clear through a typed buffer view.
    BUFFER_DESC bd;
    bd.ByteWidth = 64;
    bd.BindFlags = BIND_UNORDERED_ACCESS;
    Ref<Buffer> buf = device().CreateBuffer(bd);
    UNORDERED_ACCESS_VIEW_DESC ud;
    ud.ViewDimension = UAV_DIMENSION_BUFFER;
    ud.Format = c.format;
    ud.Buffer = {0, 64 / (4 * words), 0};
    Ref<UnorderedAccessView> uav;
    try {
      uav = device().CreateUnorderedAccessView(buf.get(), &ud);
    } catch (const Error&) {
      continue;  // not a typed-buffer UAV format on this device
    }
    ctx().ClearUnorderedAccessViewFloat(uav.get(), c.values);
    got = ReadBufferAs<uint32_t>(device(), ctx(), buf.get());
    for (size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(same(c, i % words, got[i])) << FormatName(c.format) << " buffer word " << i << ": " << std::hex << got[i];
    ++checked;
  }
  EXPECT_GE(checked, 3u);
}

// ClearUnorderedAccessViewUint on float formats copies the low bits of each value, unconverted.
TEST_P(UavClearTest, UintClearOfFloatFormatsCopiesLowBits) {
  struct Case {
    FORMAT format;
    uint32_t values[4];
    uint32_t expect;
  };
  const Case cases[] = {
      {FORMAT_R16G16_FLOAT, {0x13c00u, 0xfffbc00u, 7, 7}, 0x3c00u | (0xbc00u << 16)},
      // 1.0, 2.03125 and the largest finite float10 (GL's readback flushes denormals and canonicalises NaNs of this format).
      {FORMAT_R11G11B10_FLOAT, {0xfbc0u, 0xc01u, 0x3dfu, 0}, 0x3c0u | (0x401u << 11) | (0x3dfu << 22)},
      {FORMAT_R32_FLOAT, {0x7fc00001u, 0, 0, 0}, 0x7fc00001u},  // a NaN payload survives: the bits are copied
  };
  for (const Case& c : cases) {
    if (!TypedUav(c.format)) continue;
    Ref<Texture2D> tex = MakeTexture2D(device(), 4, 2, c.format, BIND_UNORDERED_ACCESS);
    ctx().ClearUnorderedAccessViewUint(Uav2D(tex.get(), c.format).get(), c.values);
    for (uint32_t v : ReadTextureAs<uint32_t>(device(), ctx(), tex.get())) ASSERT_EQ(v, c.expect) << FormatName(c.format);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(UavClearTest);

}  // namespace
}  // namespace sp::test
