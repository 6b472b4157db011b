// Constant-buffer contents per draw: D3D11 gives every draw and dispatch the data the buffer held
// when it was issued, however often the buffer is rewritten in between: Map(WRITE_DISCARD) on a
// dynamic buffer (the runtime renames it) and UpdateSubresource on a default one (ordered with
// the draws). Each draw writes one pixel (each dispatch one element) from its own constants.
// D3D11.1's partial constant-buffer updates (UpdateSubresource1 with a box, *SetConstantBuffers1
// offsets) are not part of D3D11.0 and not probed.
#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Constant buffers";

// The layout is one std140 cannot express (a float3 right after a uint, an array of floats), so
// the GL backend's repacked copy of the buffer is exercised as well. D3D11 offsets: value 0,
// tint 4, pixel 16, scale 24, weights 32/48/64, last 68.
const char* kSource = R"(
cbuffer PerDraw : register(b0) { uint value; float3 tint; uint2 pixel; float scale; float weights[3]; float last; };
float4 VSMain(uint id : SV_VertexID) : SV_Position {
  return float4((pixel.x + 0.5) / 32 * 2 - 1, 1 - (pixel.y + 0.5) / 8 * 2, 0.5, 1);
}
uint PSMain(float4 p : SV_Position) : SV_Target { return value ^ asuint(weights[2]) ^ asuint(tint.z) ^ (uint(p.x) << 24); }
RWStructuredBuffer<uint> results : register(u0);
[numthreads(1, 1, 1)] void CSMain() { results[pixel.x + pixel.y * 32] = value ^ asuint(last) ^ asuint(scale); }
)";

constexpr uint32_t W = 32, H = 8;

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// The constants of draw/dispatch `i` writing pixel or element `slot`, as D3D11 lays them out.
struct PerDraw {
  uint32_t words[20] = {};
  uint32_t Value() const { return words[0]; }
  uint32_t PixelX() const { return words[4]; }
  uint32_t PixelY() const { return words[5]; }
};
// Words: value 0, tint 1-3, pixel 4-5, scale 6, weights 8/12/16, last 17; the padding holds a
// value no member has.
PerDraw Constants(uint32_t i, uint32_t slot) {
  PerDraw c;
  for (uint32_t& w : c.words) w = 0x7f7f0000u + i;
  c.words[0] = i * 2654435761u + 1;
  for (uint32_t k = 0; k < 3; ++k) c.words[1 + k] = Bits(float(i) + 0.25f * float(k));
  c.words[4] = slot % W;
  c.words[5] = slot / W;
  c.words[6] = Bits(float(i) * 3.0f);
  for (uint32_t k = 0; k < 3; ++k) c.words[8 + 4 * k] = Bits(float(i) * 0.5f + float(k) * 1000.0f);
  c.words[17] = Bits(-float(i));
  return c;
}
uint32_t PixelValue(const PerDraw& c) { return c.words[0] ^ c.words[16] ^ c.words[3] ^ (c.PixelX() << 24); }
uint32_t DispatchValue(const PerDraw& c) { return c.words[0] ^ c.words[17] ^ c.words[6]; }

struct Pipeline {
  Ref<VertexShader> vs;
  Ref<PixelShader> ps;
  Ref<ComputeShader> cs;
  DrawTarget target;
  BufferViews results;
};
Pipeline Setup(Device& device, Buffer* cb, uint32_t dispatches) {
  DeviceContext& ctx = *device.GetImmediateContext();
  Pipeline p;
  p.vs = MakeVS(device, kSource, "cbuffer-per-draw", "VSMain");
  p.ps = MakePS(device, kSource, "cbuffer-per-draw", "PSMain");
  p.cs = MakeCS(device, kSource, "cbuffer-per-draw", "CSMain");
  p.target = MakeDrawTarget(device, W, H, FORMAT_R32_UINT);
  p.target.Clear(ctx, 0);
  p.target.Bind(ctx);
  std::vector<uint32_t> zero(dispatches, 0);
  p.results = MakeStructured(device, dispatches, 4, zero.data());
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
  ctx.VSSetShader(p.vs.get());
  ctx.PSSetShader(p.ps.get());
  ctx.CSSetShader(p.cs.get());
  ctx.VSSetConstantBuffers(0, {cb});
  ctx.PSSetConstantBuffers(0, {cb});
  ctx.CSSetConstantBuffers(0, {cb});
  ctx.CSSetUnorderedAccessViews(0, {p.results.uav.get()});
  return p;
}

Result Check(Device& device, Pipeline& p, const std::vector<uint32_t>& pixels, const std::vector<uint32_t>& results) {
  std::vector<uint32_t> px = ReadTextureAs<uint32_t>(device, p.target.texture.get());
  std::vector<uint32_t> r = ReadBufferAs<uint32_t>(device, p.results.buffer.get());
  Mismatches m("draws");
  for (uint32_t i = 0; i < W * H; ++i) m.Check(px[i], pixels[i], "pixel " + std::to_string(i) + " (written by the draw for it)");
  for (uint32_t i = 0; i < results.size(); ++i) m.Check(r[i], results[i], "dispatch " + std::to_string(i));
  return m.Finish("draws");
}

}  // namespace

SP_PROBE(kGroup, "Map(WRITE_DISCARD) before each of 256 draws and 64 dispatches",
         "every draw and dispatch sees the constants mapped before it, not later ones") {
  DeviceContext& ctx = *device.GetImmediateContext();
  BUFFER_DESC d;
  d.ByteWidth = sizeof(PerDraw);
  d.Usage = USAGE_DYNAMIC;
  d.BindFlags = BIND_CONSTANT_BUFFER;
  d.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> cb = device.CreateBuffer(d);
  constexpr uint32_t Dispatches = 64;
  Pipeline p = Setup(device, cb.get(), Dispatches);
  std::vector<uint32_t> pixels(W * H, 0), results(Dispatches, 0);
  auto map = [&](const PerDraw& c) {
    MAPPED_SUBRESOURCE ms;
    ctx.Map(cb.get(), 0, MAP_WRITE_DISCARD, 0, &ms);
    std::memcpy(ms.pData, &c, sizeof(c));
    ctx.Unmap(cb.get(), 0);
  };
  for (uint32_t i = 0; i < W * H; ++i) {
    PerDraw c = Constants(i, i);
    map(c);
    ctx.Draw(1, 0);
    pixels[i] = PixelValue(c);
  }
  for (uint32_t i = 0; i < Dispatches; ++i) {
    PerDraw c = Constants(i + 1000, i);
    map(c);
    ctx.Dispatch(1, 1, 1);
    results[i] = DispatchValue(c);
  }
  return Check(device, p, pixels, results);
}

SP_PROBE(kGroup, "UpdateSubresource on a constant buffer between draws and dispatches",
         "each draw and dispatch sees the whole-buffer update issued before it (interleaved draws and dispatches)") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, sizeof(PerDraw));
  constexpr uint32_t Dispatches = 64;
  Pipeline p = Setup(device, cb.get(), Dispatches);
  std::vector<uint32_t> pixels(W * H, 0), results(Dispatches, 0);
  for (uint32_t i = 0; i < W * H; ++i) {
    PerDraw c = Constants(i, (i * 37) % (W * H));
    ctx.UpdateSubresource(cb.get(), 0, nullptr, &c, 0, 0);
    ctx.Draw(1, 0);
    pixels[c.PixelY() * W + c.PixelX()] = PixelValue(c);
    if (i % 4 == 3) {
      PerDraw k = Constants(i + 5000, i / 4);
      ctx.UpdateSubresource(cb.get(), 0, nullptr, &k, 0, 0);
      ctx.Dispatch(1, 1, 1);
      results[i / 4] = DispatchValue(k);
    }
  }
  return Check(device, p, pixels, results);
}

}  // namespace sp::conformance
