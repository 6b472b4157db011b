// Map/Unmap with D3D11's semantics: WRITE_DISCARD gives every draw the data written before it,
// NO_OVERWRITE appends without disturbing earlier draws, staging maps see exactly what the GPU
// wrote, several subresources of one staging texture can be mapped at once, and dynamic
// textures are uploaded on Unmap.
#include "rhi-test-util.h"

namespace sp::test {
namespace {

class MapTest : public BackendTest {};

const char* kColorPS = R"(
cbuffer Color : register(b0) { float4 color; };
float4 main(float4 p : SV_Position) : SV_Target { return color; }
)";

Ref<Buffer> DynamicBuffer(Device& dev, uint32_t size, uint32_t bind) {
  BUFFER_DESC d;
  d.ByteWidth = size;
  d.Usage = USAGE_DYNAMIC;
  d.BindFlags = bind;
  d.CPUAccessFlags = CPU_ACCESS_WRITE;
  return dev.CreateBuffer(d);
}

// Eight draws, each preceded by Map(WRITE_DISCARD) of the same constant buffer with a different
// colour: D3D11 renames the buffer, so every strip keeps the colour written before its draw.
TEST_P(MapTest, WriteDiscardRenamesConstantBufferBetweenDraws) {
  const uint32_t W = 32, H = 8;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  RectDrawer rect(device());
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kColorPS, "ps_5_0", "main"));
  Ref<Buffer> cb = DynamicBuffer(device(), 16, BIND_CONSTANT_BUFFER);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(ps.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  for (uint32_t i = 0; i < 8; ++i) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(cb.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    float c[4] = {float(i), float(i * 10), 1.0f, 0.5f};
    std::memcpy(m.pData, c, sizeof(c));
    ctx().Unmap(cb.get(), 0);
    rect.Draw(ctx(), float(i * 4), 0, float(i * 4 + 4), float(H), W, H);
  }
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const float* p = &px[(y * W + x) * 4];
      uint32_t i = x / 4;
      ASSERT_EQ(p[0], float(i)) << x << "," << y;
      ASSERT_EQ(p[1], float(i * 10)) << x << "," << y;
      ASSERT_EQ(p[2], 1.0f);
      ASSERT_EQ(p[3], 0.5f);
    }
}

// The same through a default-usage constant buffer written by UpdateSubresource.
TEST_P(MapTest, UpdateSubresourceBetweenDrawsIsOrdered) {
  const uint32_t W = 16, H = 4;
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  RectDrawer rect(device());
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(kColorPS, "ps_5_0", "main"));
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().PSSetShader(ps.get());
  ctx().PSSetConstantBuffers(0, {cb.get()});
  for (uint32_t i = 0; i < 4; ++i) {
    float c[4] = {float(i + 1), 0, 0, 1};
    ctx().UpdateSubresource(cb.get(), 0, nullptr, c, 0, 0);
    rect.Draw(ctx(), float(i * 4), 0, float(i * 4 + 4), float(H), W, H);
  }
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(px[x * 4], float(x / 4 + 1)) << x;
}

// A dynamic vertex buffer filled in pieces with NO_OVERWRITE after a first DISCARD: every draw
// reads the vertices appended for it, earlier draws are not disturbed.
TEST_P(MapTest, NoOverwriteAppendsVertices) {
  const char* src = R"(
struct V { float4 pos : SV_Position; float4 color : COLOR; };
V VSMain(float2 p : POSITION, float4 c : COLOR) { V v; v.pos = float4(p, 0, 1); v.color = c; return v; }
float4 PSMain(V v) : SV_Target { return v.color; }
)";
  const uint32_t W = 16, H = 4;
  ShaderBytecode vsb = CompileHlsl(src, "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device().CreateVertexShader(vsb);
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "PSMain"));
  INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                             {"COLOR", 0, FORMAT_R8G8B8A8_UNORM, 0, 8, INPUT_PER_VERTEX_DATA, 0}};
  Ref<InputLayout> layout = device().CreateInputLayout(el, 2, vsb);
  struct Vertex {
    float x, y;
    uint8_t rgba[4];
  };
  Ref<Buffer> vb = DynamicBuffer(device(), 4 * 6 * sizeof(Vertex), BIND_VERTEX_BUFFER);
  Target t = MakeTarget(device(), W, H, FORMAT_R8G8B8A8_UNORM);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ctx().IASetInputLayout(layout.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  uint32_t stride = sizeof(Vertex), offset = 0;
  Buffer* vbs[] = {vb.get()};
  ctx().IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  for (uint32_t i = 0; i < 4; ++i) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(vb.get(), 0, i == 0 ? MAP_WRITE_DISCARD : MAP_WRITE_NO_OVERWRITE, 0, &m));
    Vertex* v = static_cast<Vertex*>(m.pData) + i * 6;
    float x0 = -1 + i * 0.5f, x1 = x0 + 0.5f;
    uint8_t c = uint8_t(50 * (i + 1));
    Vertex quad[6] = {{x0, 1, {c, 0, 0, 255}}, {x1, 1, {c, 0, 0, 255}}, {x1, -1, {c, 0, 0, 255}},
                      {x0, 1, {c, 0, 0, 255}}, {x1, -1, {c, 0, 0, 255}}, {x0, -1, {c, 0, 0, 255}}};
    std::memcpy(v, quad, sizeof(quad));
    ctx().Unmap(vb.get(), 0);
    ctx().Draw(6, i * 6);
  }
  std::vector<uint8_t> px = ReadTexture(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(px[(y * W + x) * 4], 50 * (x / 4 + 1)) << x << "," << y;
}

// Staging buffers: CPU writes reach the GPU, GPU copies reach the CPU, and DO_NOT_WAIT either
// succeeds or reports the resource busy, never returns stale data.
TEST_P(MapTest, StagingBufferRoundTrip) {
  BUFFER_DESC d;
  d.ByteWidth = 256;
  d.Usage = USAGE_STAGING;
  d.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
  Ref<Buffer> up = device().CreateBuffer(d);
  Ref<Buffer> down = device().CreateBuffer(d);
  Ref<Buffer> gpu = MakeBuffer(device(), BIND_SHADER_RESOURCE, nullptr, 256, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  MAPPED_SUBRESOURCE m;
  ASSERT_TRUE(ctx().Map(up.get(), 0, MAP_WRITE, 0, &m));
  for (uint32_t i = 0; i < 64; ++i) static_cast<uint32_t*>(m.pData)[i] = i * 7 + 3;
  ctx().Unmap(up.get(), 0);
  ctx().CopyResource(gpu.get(), up.get());
  BOX box{64, 0, 0, 192, 1, 1};
  ctx().CopySubresourceRegion(down.get(), 0, 16, 0, 0, gpu.get(), 0, &box);
  while (!ctx().Map(down.get(), 0, MAP_READ, MAP_FLAG_DO_NOT_WAIT, &m)) {
  }
  const uint8_t* bytes = static_cast<const uint8_t*>(m.pData);
  for (uint32_t i = 0; i < 32; ++i) {
    uint32_t v;
    std::memcpy(&v, bytes + 16 + i * 4, 4);
    EXPECT_EQ(v, (i + 16) * 7 + 3) << i;
  }
  ctx().Unmap(down.get(), 0);
}

// D3D11 lets every subresource of a staging texture be mapped at the same time, each with its
// own RowPitch; the contents are those of the copied mips.
TEST_P(MapTest, StagingTextureSubresourcesMapTogether) {
  const uint32_t W = 8, H = 8;
  std::vector<std::vector<uint32_t>> levels;
  std::vector<SUBRESOURCE_DATA> init;
  for (uint32_t slice = 0; slice < 2; ++slice)
    for (uint32_t mip = 0; mip < 4; ++mip) {
      uint32_t w = W >> mip, h = H >> mip;
      std::vector<uint32_t> l(w * h);
      for (uint32_t i = 0; i < l.size(); ++i) l[i] = slice << 24 | mip << 16 | i;
      levels.push_back(std::move(l));
    }
  for (uint32_t i = 0; i < levels.size(); ++i) init.push_back({levels[i].data(), (W >> (i % 4)) * 4, 0});
  TEXTURE2D_DESC td;
  td.Width = W;
  td.Height = H;
  td.MipLevels = 4;
  td.ArraySize = 2;
  td.Format = FORMAT_R8G8B8A8_UINT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture2D> tex = device().CreateTexture2D(td, init.data());
  td.BindFlags = 0;
  td.Usage = USAGE_STAGING;
  td.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture2D> staging = device().CreateTexture2D(td);
  ctx().CopyResource(staging.get(), tex.get());
  std::vector<MAPPED_SUBRESOURCE> maps(8);
  for (uint32_t i = 0; i < 8; ++i) ASSERT_TRUE(ctx().Map(staging.get(), i, MAP_READ, 0, &maps[i]));
  for (uint32_t i = 0; i < 8; ++i) {
    uint32_t w = W >> (i % 4), h = H >> (i % 4);
    ASSERT_GE(maps[i].RowPitch, w * 4);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        uint32_t v;
        std::memcpy(&v, static_cast<const uint8_t*>(maps[i].pData) + y * maps[i].RowPitch + x * 4, 4);
        ASSERT_EQ(v, levels[i][y * w + x]) << "subresource " << i << " at " << x << "," << y;
      }
  }
  for (uint32_t i = 0; i < 8; ++i) ctx().Unmap(staging.get(), i);
}

// Staging textures smaller than a word (1x1 R8 and R16) map with and without initial data and
// return exactly the bytes they were created with. The GL backend rounds such a texture's buffer up to 4 bytes; it once
// copied those 4 bytes out of a 1- or 2-byte initial image (found by ASan in the whole suite;
// `./shadowport test --sanitize --core` runs this test under it).
TEST_P(MapTest, TinyStagingTexturesKeepTheirBytes) {
  for (FORMAT f : {FORMAT_R8_UNORM, FORMAT_R16_UNORM})
    for (bool withData : {false, true}) {
      SCOPED_TRACE(std::string(FormatName(f)) + (withData ? " with initial data" : " empty"));
      const uint16_t value = 0xA55A;
      const uint32_t bytes = f == FORMAT_R8_UNORM ? 1 : 2;
      TEXTURE2D_DESC td;
      td.Width = td.Height = 1;
      td.Format = f;
      td.Usage = USAGE_STAGING;
      td.BindFlags = 0;
      td.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
      std::vector<uint8_t> init(bytes);
      std::memcpy(init.data(), &value, bytes);
      SUBRESOURCE_DATA d{init.data(), bytes, 0};
      Ref<Texture2D> t = device().CreateTexture2D(td, withData ? &d : nullptr);
      MAPPED_SUBRESOURCE m;
      ASSERT_TRUE(ctx().Map(t.get(), 0, MAP_READ, 0, &m));
      std::vector<uint8_t> got(static_cast<const uint8_t*>(m.pData), static_cast<const uint8_t*>(m.pData) + bytes);
      ctx().Unmap(t.get(), 0);
      if (withData) EXPECT_EQ(got, init);  // without data D3D11 leaves the contents undefined
    }
}

// A dynamic texture written with WRITE_DISCARD (honouring RowPitch) and then sampled.
TEST_P(MapTest, DynamicTextureUploadsOnUnmap) {
  const uint32_t W = 8, H = 4;
  TEXTURE2D_DESC td;
  td.Width = W;
  td.Height = H;
  td.Format = FORMAT_R32_UINT;
  td.Usage = USAGE_DYNAMIC;
  td.BindFlags = BIND_SHADER_RESOURCE;
  td.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Texture2D> tex = device().CreateTexture2D(td);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  const char* ps = R"(
Texture2D<uint> input : register(t0);
uint main(float4 p : SV_Position) : SV_Target { return input.Load(int3(p.xy, 0)) + 1; }
)";
  Ref<PixelShader> shader = device().CreatePixelShader(CompileHlsl(ps, "ps_5_0", "main"));
  Target t = MakeTarget(device(), W, H, FORMAT_R32_UINT);
  RectDrawer rect(device());
  for (uint32_t round = 0; round < 2; ++round) {
    MAPPED_SUBRESOURCE m;
    ASSERT_TRUE(ctx().Map(tex.get(), 0, MAP_WRITE_DISCARD, 0, &m));
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        uint32_t v = round * 1000 + y * 16 + x;
        std::memcpy(static_cast<uint8_t*>(m.pData) + y * m.RowPitch + x * 4, &v, 4);
      }
    ctx().Unmap(tex.get(), 0);
    RenderTargetView* rtvs[] = {t.rtv.get()};
    ctx().OMSetRenderTargets(1, rtvs, nullptr);
    SetViewport(ctx(), W, H);
    ctx().PSSetShader(shader.get());
    ctx().PSSetShaderResources(0, {srv.get()});
    rect.Draw(ctx(), 0, 0, W, H, W, H);
    std::vector<uint32_t> px = ReadTextureAs<uint32_t>(device(), ctx(), t.texture.get());
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) EXPECT_EQ(px[y * W + x], round * 1000 + y * 16 + x + 1);
  }
}

SP_INSTANTIATE_BACKEND_TESTS(MapTest);

}  // namespace
}  // namespace sp::test
