// Copies and updates with D3D11's addressing: regions between mips and array slices, 3D boxes
// with padded pitches, 1D arrays, staging uploads and staging-to-staging copies, depth formats'
// staging layouts (D24S8: depth in the low 24 bits, stencil in the top 8), buffer regions
// (including into a constant buffer that shaders then read) and BGRA memory order. GenerateMips is
// a conformance probe (eval/conformance/probes/sampling-mips.cpp).
#include <algorithm>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class CopyTest : public BackendTest {};

uint32_t Pattern(uint32_t sub, uint32_t x, uint32_t y, uint32_t z = 0) { return sub << 24 | z << 16 | y << 8 | x; }

TEST_P(CopyTest, RegionsBetweenMipsAndSlices) {
  const uint32_t W = 16, H = 8, Mips = 3, Slices = 2;
  std::vector<std::vector<uint32_t>> data;
  std::vector<SUBRESOURCE_DATA> init;
  for (uint32_t s = 0; s < Slices; ++s)
    for (uint32_t m = 0; m < Mips; ++m) {
      uint32_t w = W >> m, h = H >> m, sub = CalcSubresource(m, s, Mips);
      std::vector<uint32_t> d(w * h);
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) d[y * w + x] = Pattern(sub, x, y);
      data.push_back(std::move(d));
    }
  for (uint32_t i = 0; i < data.size(); ++i) init.push_back({data[i].data(), (W >> (i % Mips)) * 4, 0});
  TEXTURE2D_DESC td;
  td.Width = W;
  td.Height = H;
  td.MipLevels = Mips;
  td.ArraySize = Slices;
  td.Format = FORMAT_R32_UINT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture2D> src = device().CreateTexture2D(td, init.data());
  Ref<Texture2D> dst = device().CreateTexture2D(td, init.data());
  // Slice 1 mip 1 (8x4): box x 2..6, y 1..3 -> slice 0 mip 0 at (9, 4).
  BOX box{2, 1, 0, 6, 3, 1};
  ctx().CopySubresourceRegion(dst.get(), CalcSubresource(0, 0, Mips), 9, 4, 0, src.get(), CalcSubresource(1, 1, Mips), &box);
  std::vector<uint32_t> got = ReadTextureAs<uint32_t>(device(), ctx(), dst.get(), 0);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t expect = Pattern(0, x, y);
      if (x >= 9 && x < 13 && y >= 4 && y < 6) expect = Pattern(CalcSubresource(1, 1, Mips), x - 9 + 2, y - 4 + 1);
      ASSERT_EQ(got[y * W + x], expect) << x << "," << y;
    }
  // The other subresources are untouched.
  std::vector<uint32_t> other = ReadTextureAs<uint32_t>(device(), ctx(), dst.get(), CalcSubresource(1, 1, Mips));
  EXPECT_EQ(other, data[CalcSubresource(1, 1, Mips)]);
}

// A 3D texture: UpdateSubresource of a box from padded rows and slices, a region copy to another
// 3D texture, and a readback through a 3D staging texture's RowPitch and DepthPitch.
TEST_P(CopyTest, Texture3DBoxesAndPitches) {
  const uint32_t W = 8, H = 4, D = 4;
  TEXTURE3D_DESC td;
  td.Width = W;
  td.Height = H;
  td.Depth = D;
  td.Format = FORMAT_R32_UINT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture3D> a = device().CreateTexture3D(td), b = device().CreateTexture3D(td);
  // Box x 1..5, y 1..3, z 1..3 with 8 bytes of row padding and one spare row per slice.
  const uint32_t rowPitch = 4 * 4 + 8, depthPitch = rowPitch * 3;
  std::vector<uint8_t> src(depthPitch * 2, 0xee);
  for (uint32_t z = 0; z < 2; ++z)
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 4; ++x) {
        uint32_t v = Pattern(1, x + 1, y + 1, z + 1);
        std::memcpy(src.data() + z * depthPitch + y * rowPitch + x * 4, &v, 4);
      }
  BOX ub{1, 1, 1, 5, 3, 3};
  ctx().UpdateSubresource(a.get(), 0, &ub, src.data(), rowPitch, depthPitch);
  BOX cb{1, 1, 1, 5, 3, 3};
  ctx().CopySubresourceRegion(b.get(), 0, 3, 2, 0, a.get(), 0, &cb);  // to x 3..7, y 2..4, z 0..2
  td.BindFlags = 0;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture3D> staging = device().CreateTexture3D(td);
  ctx().CopyResource(staging.get(), b.get());
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx().Map(staging.get(), 0, MAP_READ, 0, &m));
  for (uint32_t z = 0; z < D; ++z)
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        uint32_t v;
        std::memcpy(&v, static_cast<const uint8_t*>(m.pData) + z * m.DepthPitch + y * m.RowPitch + x * 4, 4);
        bool in = x >= 3 && x < 7 && y >= 2 && y < 4 && z < 2;
        ASSERT_EQ(v, in ? Pattern(1, x - 2, y - 1, z + 1) : 0u) << x << "," << y << "," << z;
      }
  ctx().Unmap(staging.get(), 0);
}

// 1D texture arrays keep their slices apart through update, copy and readback.
TEST_P(CopyTest, Texture1DArrays) {
  const uint32_t W = 8, S = 3;
  TEXTURE1D_DESC td;
  td.Width = W;
  td.ArraySize = S;
  td.Format = FORMAT_R32_UINT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture1D> tex = device().CreateTexture1D(td);
  for (uint32_t s = 0; s < S; ++s) {
    std::vector<uint32_t> row(W);
    for (uint32_t x = 0; x < W; ++x) row[x] = Pattern(s, x, 0);
    ctx().UpdateSubresource(tex.get(), s, nullptr, row.data(), 0, 0);
  }
  BOX box{2, 0, 0, 5, 1, 1};
  ctx().CopySubresourceRegion(tex.get(), 2, 0, 0, 0, tex.get(), 0, &box);
  td.BindFlags = 0;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture1D> staging = device().CreateTexture1D(td);
  ctx().CopyResource(staging.get(), tex.get());
  for (uint32_t s = 0; s < S; ++s) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(staging.get(), s, MAP_READ, 0, &m));
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t v = static_cast<const uint32_t*>(m.pData)[x];
      uint32_t expect = (s == 2 && x < 3) ? Pattern(0, x + 2, 0) : Pattern(s, x, 0);
      EXPECT_EQ(v, expect) << "slice " << s << " x " << x;
    }
    ctx().Unmap(staging.get(), s);
  }
}

// Staging textures written by the CPU feed GPU textures and other staging textures.
TEST_P(CopyTest, StagingUploadAndStagingToStaging) {
  const uint32_t W = 8, H = 4;
  TEXTURE2D_DESC sd;
  sd.Width = W;
  sd.Height = H;
  sd.Format = FORMAT_R16G16_UINT;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
  Ref<Texture2D> up = device().CreateTexture2D(sd), down = device().CreateTexture2D(sd);
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx().Map(up.get(), 0, MAP_WRITE, 0, &m));
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint16_t v[2] = {uint16_t(x * 100 + y), uint16_t(0xf000 | y)};
      std::memcpy(static_cast<uint8_t*>(m.pData) + y * m.RowPitch + x * 4, v, 4);
    }
  ctx().Unmap(up.get(), 0);
  Ref<Texture2D> gpu = MakeTexture2D(device(), W, H, FORMAT_R16G16_TYPELESS, BIND_SHADER_RESOURCE);
  ctx().CopyResource(gpu.get(), up.get());
  BOX box{1, 1, 0, 4, 3, 1};
  ctx().CopySubresourceRegion(down.get(), 0, 4, 0, 0, up.get(), 0, &box);
  std::vector<uint16_t> g = ReadTextureAs<uint16_t>(device(), ctx(), gpu.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      EXPECT_EQ(g[(y * W + x) * 2], x * 100 + y);
      EXPECT_EQ(g[(y * W + x) * 2 + 1], 0xf000 | y);
    }
  ASSERT_TRUE(ctx().Map(down.get(), 0, MAP_READ, 0, &m));
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 3; ++x) {
      uint16_t v[2];
      std::memcpy(v, static_cast<const uint8_t*>(m.pData) + y * m.RowPitch + (x + 4) * 4, 4);
      EXPECT_EQ(v[0], (x + 1) * 100 + y + 1);
      EXPECT_EQ(v[1], 0xf000 | (y + 1));
    }
  ctx().Unmap(down.get(), 0);
}

// Depth formats read back in D3D's layouts, and a staging copy written back into a depth texture
// reproduces it.
TEST_P(CopyTest, DepthStagingLayoutsRoundTrip) {
  const uint32_t W = 4, H = 2;
  struct Case {
    FORMAT texture, dsv;
    uint32_t bytes;
  };
  const Case cases[] = {{FORMAT_R16_TYPELESS, FORMAT_D16_UNORM, 2},
                        {FORMAT_R24G8_TYPELESS, FORMAT_D24_UNORM_S8_UINT, 4},
                        {FORMAT_R32_TYPELESS, FORMAT_D32_FLOAT, 4},
                        {FORMAT_R32G8X24_TYPELESS, FORMAT_D32_FLOAT_S8X24_UINT, 8}};
  for (const Case& c : cases) {
    if (!(device().CheckFormatSupport(c.dsv) & FORMAT_SUPPORT_DEPTH_STENCIL)) continue;
    Ref<Texture2D> depth = MakeTexture2D(device(), W, H, c.texture, BIND_DEPTH_STENCIL);
    DEPTH_STENCIL_VIEW_DESC dd;
    dd.Format = c.dsv;
    dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
    Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get(), &dd);
    ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH | CLEAR_STENCIL, 0.25f, 0x5a);
    std::vector<uint8_t> raw = ReadTexture(device(), ctx(), depth.get());
    ASSERT_EQ(raw.size(), W * H * c.bytes);
    for (uint32_t i = 0; i < W * H; ++i) {
      const uint8_t* p = &raw[i * c.bytes];
      if (c.dsv == FORMAT_D16_UNORM) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        EXPECT_EQ(v, 16384);  // round(0.25 * 65535)
      } else if (c.dsv == FORMAT_D24_UNORM_S8_UINT) {
        uint32_t v;
        std::memcpy(&v, p, 4);
        EXPECT_EQ(v & 0xffffff, 0x400000u) << FormatName(c.dsv);  // round(0.25 * (2^24 - 1))
        EXPECT_EQ(v >> 24, 0x5au) << FormatName(c.dsv);
      } else {
        float v;
        std::memcpy(&v, p, 4);
        EXPECT_EQ(v, 0.25f) << FormatName(c.dsv);
        if (c.bytes == 8) {
          EXPECT_EQ(p[4], 0x5a) << FormatName(c.dsv);
        }
      }
    }
    // Staging -> depth texture -> staging gives the same bytes.
    TEXTURE2D_DESC sd = depth->GetDesc();
    sd.BindFlags = 0;
    sd.Usage = USAGE_STAGING;
    sd.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
    Ref<Texture2D> staging = device().CreateTexture2D(sd);
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(staging.get(), 0, MAP_WRITE, 0, &m));
    for (uint32_t y = 0; y < H; ++y) std::memcpy(static_cast<uint8_t*>(m.pData) + y * m.RowPitch, &raw[y * W * c.bytes], W * c.bytes);
    // Change the first texel: a distinct depth and stencil survive the round trip.
    if (c.dsv == FORMAT_D24_UNORM_S8_UINT) {
      uint32_t v = 0x3c123456u;
      std::memcpy(m.pData, &v, 4);
    }
    ctx().Unmap(staging.get(), 0);
    Ref<Texture2D> copy = MakeTexture2D(device(), W, H, c.texture, BIND_DEPTH_STENCIL);
    ctx().CopyResource(copy.get(), staging.get());
    std::vector<uint8_t> back = ReadTexture(device(), ctx(), copy.get());
    if (c.dsv == FORMAT_D24_UNORM_S8_UINT) {
      uint32_t v;
      std::memcpy(&v, back.data(), 4);
      EXPECT_EQ(v, 0x3c123456u);
      std::memcpy(back.data(), raw.data(), 4);
    }
    if (c.bytes == 8) {
      // Only the depth and the stencil byte carry data; the 24 bits after stencil are undefined.
      for (uint32_t i = 0; i < W * H; ++i) {
        EXPECT_EQ(std::memcmp(&back[i * 8], &raw[i * 8], 5), 0) << FormatName(c.dsv);
      }
    } else {
      EXPECT_EQ(back, raw) << FormatName(c.dsv);
    }
  }
}

// Buffer regions, including a copy into a constant buffer whose packing needs a std140 copy on
// some backends: the shader must see the copied bytes.
TEST_P(CopyTest, BufferRegionsAndConstantBufferDestination) {
  std::vector<uint32_t> a(16), b(16, 0);
  for (uint32_t i = 0; i < 16; ++i) a[i] = i + 1;
  Ref<Buffer> src = MakeBuffer(device(), BIND_SHADER_RESOURCE, a.data(), 64, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  Ref<Buffer> dst = MakeBuffer(device(), BIND_SHADER_RESOURCE, b.data(), 64, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  BOX box{8, 0, 0, 24, 1, 1};
  ctx().CopySubresourceRegion(dst.get(), 0, 36, 0, 0, src.get(), 0, &box);
  uint32_t patch[2] = {77, 78};
  BOX ub{4, 0, 0, 12, 1, 1};
  ctx().UpdateSubresource(dst.get(), 0, &ub, patch, 0, 0);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device(), ctx(), dst.get());
  for (uint32_t i = 0; i < 16; ++i) {
    uint32_t expect = 0;
    if (i >= 9 && i < 13) expect = a[i - 9 + 2];
    if (i == 1 || i == 2) expect = patch[i - 1];
    EXPECT_EQ(got[i], expect) << i;
  }

  const char* cs = R"(
cbuffer Packed : register(b0) { float f; float3 v; float g; };
RWStructuredBuffer<float> output : register(u0);
[numthreads(1, 1, 1)] void main() { output[0] = f; output[1] = v.x; output[2] = v.z; output[3] = g; }
)";
  float values[8] = {1, 2, 3, 4, 5, 0, 0, 0};
  Ref<Buffer> constants = MakeBuffer(device(), BIND_CONSTANT_BUFFER, values, 32);
  float other[8] = {10, 20, 30, 40, 50, 0, 0, 0};
  Ref<Buffer> source = MakeBuffer(device(), BIND_CONSTANT_BUFFER, other, 32);
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  UavBuffer out = MakeUavBuffer(device(), 4, 4);
  ctx().CSSetShader(shader.get());
  ctx().CSSetConstantBuffers(0, {constants.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<float>(device(), ctx(), out.buffer.get()), (std::vector<float>{1, 2, 4, 5}));
  ctx().CopyResource(constants.get(), source.get());
  ctx().Dispatch(1, 1, 1);
  EXPECT_EQ(ReadBufferAs<float>(device(), ctx(), out.buffer.get()), (std::vector<float>{10, 20, 40, 50}));
}

// B8G8R8A8: bytes in memory are B, G, R, A; shaders see (R, G, B, A).
TEST_P(CopyTest, BgraMemoryOrder) {
  const uint8_t bgra[4] = {10, 20, 30, 40};
  Ref<Texture2D> tex = MakeTexture2D(device(), 1, 1, FORMAT_B8G8R8A8_UNORM, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET, bgra);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  const char* cs = R"(
Texture2D<float4> tex : register(t0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(1, 1, 1)] void main() { output[0] = tex.Load(int3(0, 0, 0)) * 255; }
)";
  Ref<ComputeShader> shader = device().CreateComputeShader(CompileHlsl(cs, "cs_5_0", "main"));
  UavBuffer out = MakeUavBuffer(device(), 1, 16);
  ctx().CSSetShader(shader.get());
  ctx().CSSetShaderResources(0, {srv.get()});
  ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx().Dispatch(1, 1, 1);
  std::vector<float> v = ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  EXPECT_FLOAT_EQ(v[0], 30);
  EXPECT_FLOAT_EQ(v[1], 20);
  EXPECT_FLOAT_EQ(v[2], 10);
  EXPECT_FLOAT_EQ(v[3], 40);
  // A clear to (R, G, B, A) = (1, 0.5, 0, 1) lands in memory as B, G, R, A.
  ctx().CSSetShaderResources(0, {nullptr});
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(tex.get());
  const float c[4] = {1.0f, 0.5f, 0.0f, 1.0f};
  ctx().ClearRenderTargetView(rtv.get(), c);
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), tex.get());
  EXPECT_EQ(px, (std::vector<uint8_t>{0, 128, 255, 255}));
}

SP_INSTANTIATE_BACKEND_TESTS(CopyTest);

}  // namespace
}  // namespace sp::test
