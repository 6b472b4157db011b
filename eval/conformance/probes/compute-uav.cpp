// Unordered access from compute shaders: typed stores to RWTexture2D, RWTexture2DArray and
// RWBuffer (with the view's FirstArraySlice / FirstElement applied), the tightly packed layout of
// RWStructuredBuffer elements, RWByteAddressBuffer loads and stores at any 4-byte offset, typed
// UAV loads of the three formats D3D11.0 allows (R32_FLOAT/UINT/SINT), and groupshared memory
// with GroupMemoryBarrierWithGroupSync. Every expected value is computed on the CPU from the
// shader's formula and compared exactly.
#include <cmath>
#include <functional>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Compute";

uint32_t FloatBits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// D3D11 float -> UNORM8: clamp, scale by 255, round to nearest.
uint8_t ToUnorm8(float f) { return uint8_t(std::floor(std::clamp(f, 0.0f, 1.0f) * 255.0f + 0.5f)); }

Result RequireTypedUav(Device& device, std::initializer_list<FORMAT> formats) {
  for (FORMAT f : formats)
    if (!(device.CheckFormatSupport(f) & FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW))
      return Unsupported(std::string(FormatName(f)) + " has no typed UAV support on this device");
  return Pass();
}

}  // namespace

SP_PROBE(kGroup, "RWTexture2D stores: float4, uint, int, unorm float4",
         "typed stores land at [x, y] of the UAV; UNORM converts with round-to-nearest") {
  Result support = RequireTypedUav(device, {FORMAT_R32G32B32A32_FLOAT, FORMAT_R32_UINT, FORMAT_R32_SINT, FORMAT_R8G8B8A8_UNORM});
  if (support.status != Status::Pass) return support;
  const char* cs = R"(
RWTexture2D<float4> f4 : register(u0);
RWTexture2D<uint> u1 : register(u1);
RWTexture2D<int> i1 : register(u2);
RWTexture2D<unorm float4> n4 : register(u3);
[numthreads(8, 4, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint k = id.x + id.y * 16;
  f4[id.xy] = float4(id.x, id.y, k * 0.25, -1.5 * k);
  u1[id.xy] = k * 2654435761u;
  i1[id.xy] = -int(k) * 1000 + 7;
  n4[id.xy] = float4(k, 255 - k, (k * 3) % 256, 128) / 255.0;
}
)";
  constexpr uint32_t W = 16, H = 8;
  DeviceContext& ctx = *device.GetImmediateContext();
  TextureViews f4 = MakeUavTexture(device, W, H, FORMAT_R32G32B32A32_FLOAT), u1 = MakeUavTexture(device, W, H, FORMAT_R32_UINT),
               i1 = MakeUavTexture(device, W, H, FORMAT_R32_SINT), n4 = MakeUavTexture(device, W, H, FORMAT_R8G8B8A8_UNORM);
  Ref<ComputeShader> shader = MakeCS(device, cs, "rwtexture2d-stores");
  ctx.CSSetShader(shader.get());
  ctx.CSSetUnorderedAccessViews(0, {f4.uav.get(), u1.uav.get(), i1.uav.get(), n4.uav.get()});
  ctx.Dispatch(W / 8, H / 4, 1);
  std::vector<float> gf = ReadTextureAs<float>(device, f4.texture.get());
  std::vector<uint32_t> gu = ReadTextureAs<uint32_t>(device, u1.texture.get());
  std::vector<int32_t> gi = ReadTextureAs<int32_t>(device, i1.texture.get());
  std::vector<uint8_t> gn = ReadTextureAs<uint8_t>(device, n4.texture.get());
  Mismatches m("texels");
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t k = x + y * 16, p = y * W + x;
      std::string at = "(" + std::to_string(x) + "," + std::to_string(y) + ")";
      float ef[4] = {float(x), float(y), float(k) * 0.25f, -1.5f * float(k)};
      for (int c = 0; c < 4; ++c) m.Check(gf[p * 4 + c], ef[c], "float4 " + at + "." + "xyzw"[c]);
      m.Check(gu[p], k * 2654435761u, "uint " + at);
      m.Check(gi[p], -int32_t(k) * 1000 + 7, "int " + at);
      float en[4] = {float(k), float(255 - k), float((k * 3) % 256), 128.0f};
      for (int c = 0; c < 4; ++c) m.Check(int(gn[p * 4 + c]), int(ToUnorm8(en[c] / 255.0f)), "unorm " + at + "." + "xyzw"[c]);
    }
  return m.Finish();
}

SP_PROBE(kGroup, "RWTexture2DArray: every slice, and a view of a slice range",
         "[x, y, s] addresses slice FirstArraySlice + s of the view; slices outside it are untouched") {
  const char* cs = R"(
RWTexture2DArray<uint> target : register(u0);
cbuffer Base : register(b0) { uint base; uint3 pad; };
[numthreads(8, 8, 1)] void main(uint3 id : SV_DispatchThreadID) { target[id] = base + id.x + 8 * id.y + 100 * id.z; }
)";
  constexpr uint32_t W = 8, S = 4;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> init(W * W * S, 0xdeadbeefu);
  TextureViews all = MakeUavTexture(device, W, W, FORMAT_R32_UINT, S, init.data());
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_R32_UINT;
  d.ViewDimension = UAV_DIMENSION_TEXTURE2DARRAY;
  d.Texture2DArray = {0, 1, 2};  // slices 1 and 2
  Ref<UnorderedAccessView> middle = device.CreateUnorderedAccessView(all.texture.get(), &d);
  TextureViews second = MakeUavTexture(device, W, W, FORMAT_R32_UINT, S, init.data());
  Ref<ComputeShader> shader = MakeCS(device, cs, "rwtexture2darray");
  uint32_t c0[4] = {1000, 0, 0, 0}, c1[4] = {5000, 0, 0, 0};
  Ref<Buffer> cb0 = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, c0, 16), cb1 = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, c1, 16);
  ctx.CSSetShader(shader.get());
  ctx.CSSetConstantBuffers(0, {cb0.get()});
  ctx.CSSetUnorderedAccessViews(0, {middle.get()});
  ctx.Dispatch(1, 1, 2);
  ctx.CSSetConstantBuffers(0, {cb1.get()});
  ctx.CSSetUnorderedAccessViews(0, {second.uav.get()});
  ctx.Dispatch(1, 1, S);
  Mismatches m("texels");
  for (uint32_t s = 0; s < S; ++s) {
    std::vector<uint32_t> a = ReadTextureAs<uint32_t>(device, all.texture.get(), s), b = ReadTextureAs<uint32_t>(device, second.texture.get(), s);
    for (uint32_t i = 0; i < W * W; ++i) {
      uint32_t local = (i % W) + 8 * (i / W);
      m.Check(a[i], s == 1 || s == 2 ? 1000 + local + 100 * (s - 1) : 0xdeadbeefu,
              "range view, slice " + std::to_string(s) + " texel " + std::to_string(i));
      m.Check(b[i], 5000 + local + 100 * s, "whole view, slice " + std::to_string(s) + " texel " + std::to_string(i));
    }
  }
  return m.Finish();
}

SP_PROBE(kGroup, "RWBuffer<T> typed stores with FirstElement",
         "element i of the view is element FirstElement + i of the buffer, converted to the view's format") {
  Result support = RequireTypedUav(device, {FORMAT_R32G32B32A32_FLOAT, FORMAT_R32_UINT, FORMAT_R32_SINT, FORMAT_R8G8B8A8_UINT});
  if (support.status != Status::Pass) return support;
  const char* cs = R"(
RWBuffer<float4> f4 : register(u0);
RWBuffer<uint> u1 : register(u1);
RWBuffer<int> i1 : register(u2);
RWBuffer<uint4> b4 : register(u3);
[numthreads(8, 1, 1)] void main(uint i : SV_DispatchThreadID) {
  f4[i] = float4(i, i * 2, -float(i), 0.5);
  u1[i] = 0x80000000u | (i * 77);
  i1[i] = int(i) * -123456;
  b4[i] = uint4(i, 255 - i, i * 16, 200);
}
)";
  constexpr uint32_t N = 16, First = 4, Num = 8;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> init(N * 4, 0x7f7f7f7fu);
  BufferViews f4 = MakeTyped(device, FORMAT_R32G32B32A32_FLOAT, N, init.data(), First, Num);
  BufferViews u1 = MakeTyped(device, FORMAT_R32_UINT, N, init.data(), First, Num);
  BufferViews i1 = MakeTyped(device, FORMAT_R32_SINT, N, init.data(), First, Num);
  BufferViews b4 = MakeTyped(device, FORMAT_R8G8B8A8_UINT, N, init.data(), First, Num);
  Ref<ComputeShader> shader = MakeCS(device, cs, "rwbuffer-stores");
  ctx.CSSetShader(shader.get());
  ctx.CSSetUnorderedAccessViews(0, {f4.uav.get(), u1.uav.get(), i1.uav.get(), b4.uav.get()});
  ctx.Dispatch(1, 1, 1);
  std::vector<uint32_t> gf = ReadBufferAs<uint32_t>(device, f4.buffer.get()), gu = ReadBufferAs<uint32_t>(device, u1.buffer.get());
  std::vector<uint32_t> gi = ReadBufferAs<uint32_t>(device, i1.buffer.get());
  std::vector<uint8_t> gb = ReadBufferAs<uint8_t>(device, b4.buffer.get());
  Mismatches m("elements");
  for (uint32_t e = 0; e < N; ++e) {
    bool in = e >= First && e < First + Num;
    uint32_t i = e - First;
    std::string at = "element " + std::to_string(e);
    float ef[4] = {float(i), float(i * 2), -float(i), 0.5f};
    for (int c = 0; c < 4; ++c) m.Check(gf[e * 4 + c], in ? FloatBits(ef[c]) : 0x7f7f7f7fu, "float4 " + at);
    m.Check(gu[e], in ? 0x80000000u | (i * 77) : 0x7f7f7f7fu, "uint " + at);
    m.Check(gi[e], in ? uint32_t(int32_t(i) * -123456) : 0x7f7f7f7fu, "int " + at);
    uint8_t eb[4] = {uint8_t(i), uint8_t(255 - i), uint8_t(i * 16), 200};
    for (int c = 0; c < 4; ++c) m.Check(int(gb[e * 4 + c]), in ? int(eb[c]) : 0x7f, "R8G8B8A8_UINT " + at);
  }
  return m.Finish();
}

namespace {

// Writes `Item` elements through a RWStructuredBuffer (whole struct, then one member) and checks
// every word of the buffer against the D3D11 layout: members 4-byte aligned, no padding.
Result CheckStructured(Device& device, const char* name, const char* itemDecl, uint32_t strideWords,
                       const std::function<std::vector<uint32_t>(uint32_t)>& expect) {
  std::string cs = std::string(itemDecl) + R"(
RWStructuredBuffer<Item> items : register(u0);
[numthreads(16, 1, 1)] void main(uint i : SV_DispatchThreadID) {
  Item it;
  Fill(it, i);
  items[i] = it;
  items[i].c.y = i * 1000;
}
)";
  constexpr uint32_t N = 16;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> poison(N * strideWords, 0x5a5a5a5au);
  BufferViews items = MakeStructured(device, N, strideWords * 4, poison.data());
  Ref<ComputeShader> shader = MakeCS(device, cs, name);
  ctx.CSSetShader(shader.get());
  ctx.CSSetUnorderedAccessViews(0, {items.uav.get()});
  ctx.Dispatch(1, 1, 1);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device, items.buffer.get());
  Mismatches m("words");
  for (uint32_t i = 0; i < N; ++i) {
    std::vector<uint32_t> e = expect(i);
    for (uint32_t w = 0; w < strideWords; ++w)
      m.Check(got[i * strideWords + w], e[w], "element " + std::to_string(i) + " byte " + std::to_string(w * 4));
  }
  return m.Finish();
}

}  // namespace

SP_PROBE(kGroup, "RWStructuredBuffer: struct elements, naturally aligned members",
         "whole-struct and member writes land at the members' offsets (float3 0, uint 12, float2 16, int2 24, float4 32; stride 48)") {
  const char* item = R"(
struct Item { float3 c; uint d; float2 b; int2 e; float4 g; };
void Fill(inout Item it, uint i) {
  it.c = float3(i, i + 100, i + 200); it.d = i * 3 + 1; it.b = float2(i * 2, -1.0 * i); it.e = int2(-int(i), i * 5);
  it.g = float4(i + 0.5, 0.25, i * 8, -2);
}
)";
  return CheckStructured(device, "structured-aligned", item, 12, [](uint32_t i) {
    return std::vector<uint32_t>{FloatBits(float(i)),       FloatBits(float(i * 1000)),
                                 FloatBits(float(i + 200)), i * 3 + 1,
                                 FloatBits(float(i * 2)),   FloatBits(-1.0f * float(i)),
                                 uint32_t(-int32_t(i)),     i * 5,
                                 FloatBits(i + 0.5f),       FloatBits(0.25f),
                                 FloatBits(float(i * 8)),   FloatBits(-2.0f)};
  });
}

// D3D11 packs structured-buffer members at 4-byte alignment: here b at 4, c at 12 (straddling a
// 16-byte boundary), d at 24; stride 28. glslang lays structured buffers out with the cbuffer
// rule (c moves to 16) and GLSL's std430 cannot express b at 4, so the toolchain rejects the
// shader with a message naming the buffer. The probe checks that rejection (never a silently
// different layout) and reports the layout as unsupported.
SP_PROBE(kGroup, "RWStructuredBuffer: members packed at 4-byte alignment",
         "members of a structured-buffer element are 4-byte aligned with no 16-byte rule (float2 at 4, float3 at 12; stride 28)") {
  const char* item = R"(
struct Item { float a; float2 b; float3 c; uint d; };
void Fill(inout Item it, uint i) { it.a = i + 0.5; it.b = float2(i * 2, -1.0 * i); it.c = float3(i, i + 100, i + 200); it.d = i * 3 + 1; }
)";
  try {
    return CheckStructured(device, "structured-packed", item, 7, [](uint32_t i) {
      return std::vector<uint32_t>{FloatBits(i + 0.5f),
                                   FloatBits(float(i * 2)),
                                   FloatBits(-1.0f * float(i)),
                                   FloatBits(float(i)),
                                   FloatBits(float(i * 1000)),
                                   FloatBits(float(i + 200)),
                                   i * 3 + 1};
    });
  } catch (const Error& e) {
    if (std::string(e.what()).find("4-byte packed") == std::string::npos) throw;
    return Unsupported("the toolchain rejects structured-buffer elements whose members D3D11 packs at 4 bytes across a 16-byte boundary "
                       "(SP_SHADER_COMPILE_FAILED names the buffer; reorder or pad members)");
  }
}

SP_PROBE(kGroup, "RWByteAddressBuffer: Load/Store 1-4 words at 4-byte offsets",
         "Store/Store2/Store3/Store4 and Load/Load2/Load3/Load4 address bytes, at any multiple of 4") {
  const char* cs = R"(
RWByteAddressBuffer raw : register(u0);
RWByteAddressBuffer src : register(u1);
[numthreads(8, 1, 1)] void Stores(uint i : SV_DispatchThreadID) {
  uint base = i * 40 + 4;
  raw.Store(base, i + 1);
  raw.Store2(base + 4, uint2(i * 10, i * 11));
  raw.Store3(base + 12, uint3(i << 8, i << 16, i << 24));
  raw.Store4(base + 24, uint4(~i, i ^ 0x5555u, 7, 0xffffffffu - i));
}
[numthreads(8, 1, 1)] void Loads(uint i : SV_DispatchThreadID) {
  uint base = i * 12 + 4;
  uint4 a = src.Load4(base);
  uint3 b = src.Load3(base + 8);
  uint2 c = src.Load2(base + 4);
  uint d = src.Load(base + 12);
  raw.Store4(i * 16, uint4(a.x + a.w, b.x ^ b.z, c.y * 3, d + a.y));
}
)";
  constexpr uint32_t N = 8, Bytes = 8 * 40 + 8;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> fill(Bytes / 4, 0x11111111u), input(Bytes / 4);
  for (uint32_t w = 0; w < input.size(); ++w) input[w] = w * 0x01010101u + 3;
  BufferViews raw = MakeRaw(device, Bytes, fill.data()), out = MakeRaw(device, Bytes, fill.data()), src = MakeRaw(device, Bytes, input.data());
  Ref<ComputeShader> stores = MakeCS(device, cs, "raw-load-store", "Stores"), loads = MakeCS(device, cs, "raw-load-store", "Loads");
  ctx.CSSetShader(stores.get());
  ctx.CSSetUnorderedAccessViews(0, {raw.uav.get(), src.uav.get()});
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetShader(loads.get());
  ctx.CSSetUnorderedAccessViews(0, {out.uav.get(), src.uav.get()});
  ctx.Dispatch(1, 1, 1);
  std::vector<uint32_t> expect = fill, expectOut = fill;
  for (uint32_t i = 0; i < N; ++i) {
    uint32_t b = (i * 40 + 4) / 4;
    uint32_t v[10] = {i + 1, i * 10, i * 11, i << 8, i << 16, i << 24, ~i, i ^ 0x5555u, 7, 0xffffffffu - i};
    for (uint32_t k = 0; k < 10; ++k) expect[b + k] = v[k];
    uint32_t s = (i * 12 + 4) / 4;
    const uint32_t* in = input.data();
    uint32_t r[4] = {in[s] + in[s + 3], in[s + 2] ^ in[s + 4], in[s + 2] * 3, in[s + 3] + in[s + 1]};
    for (uint32_t k = 0; k < 4; ++k) expectOut[i * 4 + k] = r[k];
  }
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device, raw.buffer.get()), gotOut = ReadBufferAs<uint32_t>(device, out.buffer.get());
  Mismatches m("words");
  for (uint32_t w = 0; w < expect.size(); ++w) {
    m.Check(got[w], expect[w], "after stores, byte " + std::to_string(w * 4));
    m.Check(gotOut[w], expectOut[w], "after loads, byte " + std::to_string(w * 4));
  }
  return m.Finish();
}

SP_PROBE(kGroup, "typed UAV loads: R32_FLOAT, R32_UINT, R32_SINT textures and buffers",
         "D3D11.0 reads typed UAVs of the three single-channel 32-bit formats (read-modify-write)") {
  const char* cs = R"(
RWTexture2D<float> tf : register(u0);
RWTexture2D<uint> tu : register(u1);
RWTexture2D<int> ti : register(u2);
RWBuffer<float> bf : register(u3);
RWBuffer<uint> bu : register(u4);
RWBuffer<int> bi : register(u5);
[numthreads(16, 4, 1)] void main(uint3 id : SV_DispatchThreadID) {
  uint i = id.x + id.y * 16;
  tf[id.xy] = tf[id.xy] * 2 + 0.5;
  tu[id.xy] = tu[id.xy] ^ 0xa5a5a5a5u;
  ti[id.xy] = ti[id.xy] * -3;
  bf[i] = bf[i] - 0.25;
  bu[i] = bu[i] + 0x10000u;
  bi[i] = bi[i] - 17;
}
)";
  constexpr uint32_t W = 16, H = 4, N = W * H;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<float> f(N);
  std::vector<uint32_t> u(N);
  std::vector<int32_t> s(N);
  for (uint32_t i = 0; i < N; ++i) {
    f[i] = float(i) * 0.75f - 20.0f;
    u[i] = i * 0x01020304u;
    s[i] = int32_t(i * 1000) - 31000;
  }
  TextureViews tf = MakeUavTexture(device, W, H, FORMAT_R32_FLOAT, 1, f.data()), tu = MakeUavTexture(device, W, H, FORMAT_R32_UINT, 1, u.data()),
               ti = MakeUavTexture(device, W, H, FORMAT_R32_SINT, 1, s.data());
  BufferViews bf = MakeTyped(device, FORMAT_R32_FLOAT, N, f.data(), 0, N), bu = MakeTyped(device, FORMAT_R32_UINT, N, u.data(), 0, N),
              bi = MakeTyped(device, FORMAT_R32_SINT, N, s.data(), 0, N);
  Ref<ComputeShader> shader = MakeCS(device, cs, "typed-uav-loads");
  ctx.CSSetShader(shader.get());
  ctx.CSSetUnorderedAccessViews(0, {tf.uav.get(), tu.uav.get(), ti.uav.get(), bf.uav.get(), bu.uav.get(), bi.uav.get()});
  ctx.Dispatch(1, 1, 1);
  std::vector<float> gtf = ReadTextureAs<float>(device, tf.texture.get()), gbf = ReadBufferAs<float>(device, bf.buffer.get());
  std::vector<uint32_t> gtu = ReadTextureAs<uint32_t>(device, tu.texture.get()), gbu = ReadBufferAs<uint32_t>(device, bu.buffer.get());
  std::vector<int32_t> gti = ReadTextureAs<int32_t>(device, ti.texture.get()), gbi = ReadBufferAs<int32_t>(device, bi.buffer.get());
  Mismatches m("values");
  for (uint32_t i = 0; i < N; ++i) {
    std::string at = " " + std::to_string(i);
    m.Check(gtf[i], f[i] * 2 + 0.5f, "R32_FLOAT texel" + at);
    m.Check(gtu[i], u[i] ^ 0xa5a5a5a5u, "R32_UINT texel" + at);
    m.Check(gti[i], s[i] * -3, "R32_SINT texel" + at);
    m.Check(gbf[i], f[i] - 0.25f, "R32_FLOAT element" + at);
    m.Check(gbu[i], u[i] + 0x10000u, "R32_UINT element" + at);
    m.Check(gbi[i], s[i] - 17, "R32_SINT element" + at);
  }
  return m.Finish();
}

SP_PROBE(kGroup, "groupshared memory with GroupMemoryBarrierWithGroupSync",
         "after the barrier every thread sees every other thread's groupshared writes: exact permutation and tree reduction") {
  const char* cs = R"(
#define N 256
StructuredBuffer<uint> input : register(t0);
RWStructuredBuffer<uint> permuted : register(u0);
RWStructuredBuffer<uint> sums : register(u1);
groupshared uint values[N];
groupshared uint partial[N];
[numthreads(N, 1, 1)] void main(uint i : SV_GroupIndex, uint3 g : SV_GroupID) {
  uint v = input[g.x * N + i];
  values[i] = v;
  partial[i] = v;
  GroupMemoryBarrierWithGroupSync();
  permuted[g.x * N + i] = values[(i * 37 + 11) % N];
  for (uint stride = N / 2; stride > 0; stride >>= 1) {
    if (i < stride) partial[i] += partial[i + stride];
    GroupMemoryBarrierWithGroupSync();
  }
  if (i == 0) sums[g.x] = partial[0];
}
)";
  constexpr uint32_t N = 256, G = 4;
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> input(N * G);
  for (uint32_t i = 0; i < input.size(); ++i) input[i] = (i * 2654435761u) >> 8;
  Ref<Buffer> in = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, input.data(), N * G * 4, RESOURCE_MISC_BUFFER_STRUCTURED, 4);
  Ref<ShaderResourceView> inSrv = device.CreateShaderResourceView(in.get());
  BufferViews permuted = MakeStructured(device, N * G, 4), sums = MakeStructured(device, G, 4);
  Ref<ComputeShader> shader = MakeCS(device, cs, "groupshared-barrier");
  ctx.CSSetShader(shader.get());
  ctx.CSSetShaderResources(0, {inSrv.get()});
  ctx.CSSetUnorderedAccessViews(0, {permuted.uav.get(), sums.uav.get()});
  ctx.Dispatch(G, 1, 1);
  std::vector<uint32_t> gp = ReadBufferAs<uint32_t>(device, permuted.buffer.get()), gs = ReadBufferAs<uint32_t>(device, sums.buffer.get());
  Mismatches m("values");
  for (uint32_t g = 0; g < G; ++g) {
    uint32_t sum = 0;
    for (uint32_t i = 0; i < N; ++i) {
      sum += input[g * N + i];
      m.Check(gp[g * N + i], input[g * N + (i * 37 + 11) % N],
              "group " + std::to_string(g) + " thread " + std::to_string(i) + " read of another thread's write");
    }
    m.Check(gs[g], sum, "group " + std::to_string(g) + " reduction");
  }
  return m.Finish();
}

}  // namespace sp::conformance
