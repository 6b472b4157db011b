#include "bench-common.h"

#include <cmath>
#include <sp/hlsl/compiler.h>

namespace spbench {
namespace {

const char* kGraphicsHlsl = R"(
cbuffer PerDraw : register(b0) { row_major float4x4 world; float4 color; };
float4 VSMain(float3 pos : POSITION, uint inst : SV_InstanceID) : SV_Position {
  float4 p = mul(float4(pos, 1), world);
  p.x += inst * 0.01;
  return p;
}
float4 PSColor(float4 p : SV_Position) : SV_Target { return color; }
Texture2D tex : register(t0);
SamplerState smp : register(s0);
float4 PSTex(float4 p : SV_Position) : SV_Target { return tex.Sample(smp, p.xy / 64) * color; }
)";

const char* kComputeHlsl = R"(
cbuffer Dispatch : register(b0) { uint base; };
RWStructuredBuffer<uint> outBuf : register(u0);
[numthreads(64, 1, 1)] void CSMain(uint3 id : SV_DispatchThreadID) { outBuf[id.x] = id.x + base; }
)";

sp::ShaderBytecode Compile(const char* src, const char* name, const char* target, const char* entry) {
  sp::hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  return sp::hlsl::CompileSource(src, name, o);
}

Mesh MakeCube(float h) {
  Mesh m;
  for (int i = 0; i < 8; ++i) {
    m.positions.push_back(i & 1 ? h : -h);
    m.positions.push_back(i & 2 ? h : -h);
    m.positions.push_back(i & 4 ? h : -h);
  }
  const uint16_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    for (uint16_t k : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.indices.push_back(k);
  return m;
}

}  // namespace

const char* CaseName(CaseId id) {
  switch (id) {
    case CaseId::CBuffer: return "cbuffer";
    case CaseId::Texture: return "texture";
    case CaseId::State: return "state";
    case CaseId::Compute: return "compute";
    default: return "shadow";
  }
}

uint32_t CaseDraws(CaseId id) {
  switch (id) {
    case CaseId::Compute: return kDispatches;
    case CaseId::Shadow: return kShadowDraws;
    default: return kDraws;
  }
}

sp::RASTERIZER_DESC RasterDesc(uint32_t i) {
  sp::RASTERIZER_DESC d;
  d.CullMode = i == 1 ? sp::CULL_FRONT : i == 2 ? sp::CULL_NONE : sp::CULL_BACK;
  if (i == 3) {
    d.DepthBias = kShadowDepthBias;
    d.SlopeScaledDepthBias = kShadowSlopeBias;
  }
  return d;
}

sp::DEPTH_STENCIL_DESC DepthDesc(uint32_t i) {
  sp::DEPTH_STENCIL_DESC d;
  if (i == 1) {
    d.DepthFunc = sp::COMPARISON_LESS_EQUAL;
    d.DepthWriteMask = sp::DEPTH_WRITE_MASK_ZERO;
  }
  if (i == 2) d.DepthEnable = false;
  return d;
}

sp::BLEND_DESC BlendDesc(uint32_t i) {
  sp::BLEND_DESC d;
  sp::RENDER_TARGET_BLEND_DESC& t = d.RenderTarget[0];
  if (i == 1) {
    t.BlendEnable = true;
    t.SrcBlend = sp::BLEND_SRC_ALPHA;
    t.DestBlend = sp::BLEND_INV_SRC_ALPHA;
  } else if (i == 2) {
    t.BlendEnable = true;
    t.DestBlend = sp::BLEND_ONE;
  }
  return d;
}

const Shaders& GetShaders() {
  static const Shaders s = [] {
    Shaders r;
    r.vs = Compile(kGraphicsHlsl, "bench-graphics.hlsl", "vs_5_0", "VSMain");
    r.psColor = Compile(kGraphicsHlsl, "bench-graphics.hlsl", "ps_5_0", "PSColor");
    r.psTex = Compile(kGraphicsHlsl, "bench-graphics.hlsl", "ps_5_0", "PSTex");
    r.cs = Compile(kComputeHlsl, "bench-compute.hlsl", "cs_5_0", "CSMain");
    return r;
  }();
  return s;
}

DrawConstants MakeConstants(uint32_t draw) {
  // Small cubes scattered over the target (depth in [0.2, 0.8]).
  DrawConstants c{};
  float s = 0.15f;
  float x = std::fmod(draw * 0.37f, 1.6f) - 0.8f, y = std::fmod(draw * 0.23f, 1.6f) - 0.8f;
  float z = 0.5f + 0.3f * std::sin(float(draw));
  float w[16] = {s, 0, 0, 0, 0, s, 0, 0, 0, 0, s * 0.5f, 0, x, y, z, 1};
  for (int i = 0; i < 16; ++i) c.world[i] = w[i];
  c.color[0] = float(draw % 7) / 7.0f;
  c.color[1] = float(draw % 5) / 5.0f;
  c.color[2] = 0.5f;
  c.color[3] = 0.5f;
  return c;
}

const Mesh& GetMesh(uint32_t which) {
  static const Mesh m[2] = {MakeCube(1.0f), MakeCube(0.7f)};
  return m[which & 1];
}

std::vector<uint32_t> TextureTexels(uint32_t which) {
  std::vector<uint32_t> t(16);
  for (uint32_t i = 0; i < 16; ++i) t[i] = 0xff000000u | ((which * 0x203040u) ^ (i * 0x010101u));
  return t;
}

void RunCase(benchmark::State& state, Case& c, uint32_t draws) {
  c.Record();
  c.Wait();
  for (auto _ : state) {
    c.Record();
    state.PauseTiming();
    c.Wait();
    state.ResumeTiming();
  }
  state.counters["draws"] = draws;
  state.counters["per_draw"] =
      benchmark::Counter(double(draws), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace spbench
