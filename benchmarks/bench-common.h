// What both sides of every RHI benchmark share: the shaders (compiled once by the project's HLSL
// toolchain; sp:: takes the bytecode, raw Vulkan its SPIR-V, raw GL its GLSL), the mesh, the
// per-draw constants and the sizes of each case, so that sp:: and raw record the same work.
#pragma once
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <vector>
#include <sp/rhi/rhi.h>

namespace spbench {

// Tiny targets: llvmpipe/lavapipe rasterise on the CPU too, and the cost measured here is the
// recording, not the pixels.
inline constexpr uint32_t kTargetSize = 64;

inline constexpr uint32_t kDraws = 2000;        // cases cbuffer, texture, state
inline constexpr uint32_t kDispatches = 2000;   // case compute
inline constexpr uint32_t kShadowDraws = 3000;  // case shadow
inline constexpr uint32_t kShadowInstanceEvery = 4, kShadowInstances = 8;  // every 4th draw instanced
inline constexpr uint32_t kShadowMeshRun = 50;  // the shadow pass switches mesh every 50 draws

inline constexpr uint32_t kTextures = 8, kSamplers = 2;        // cycled by the texture case
inline constexpr uint32_t kRasterStates = 4, kDepthStates = 3, kBlendStates = 3;  // state case
inline constexpr uint32_t kUavs = 4;                          // compute case: UAV cycled
inline constexpr uint32_t kUavElements = 64;                  // one group of 64 threads

enum class CaseId { CBuffer, Texture, State, Compute, Shadow };
inline constexpr CaseId kCases[] = {CaseId::CBuffer, CaseId::Texture, CaseId::State, CaseId::Compute, CaseId::Shadow};
const char* CaseName(CaseId id);  // "cbuffer", "texture", "state", "compute", "shadow"
uint32_t CaseDraws(CaseId id);    // draws (or dispatches) per iteration

// The state case's objects, as D3D11 descs; the raw sides set the same states by hand.
//   raster: 0 cull back, 1 cull front, 2 cull none, 3 cull back + depth bias 100 / slope 1.5
//   depth:  0 less + write, 1 less-equal without write, 2 off
//   blend:  0 opaque, 1 alpha blending, 2 additive
sp::RASTERIZER_DESC RasterDesc(uint32_t i);
sp::DEPTH_STENCIL_DESC DepthDesc(uint32_t i);
sp::BLEND_DESC BlendDesc(uint32_t i);
// The shadow pass's rasterizer: cull back with depth bias 100 / slope 1.5.
inline constexpr int32_t kShadowDepthBias = 100;
inline constexpr float kShadowSlopeBias = 1.5f;

struct Shaders {
  sp::ShaderBytecode vs;       // cbuffer b0 (world, colour), POSITION, SV_InstanceID
  sp::ShaderBytecode psColor;  // cbuffer b0
  sp::ShaderBytecode psTex;    // cbuffer b0, t0, s0
  sp::ShaderBytecode cs;       // cbuffer b0 (base), u0 (RWStructuredBuffer<uint>)
};
const Shaders& GetShaders();

// 80 bytes: float4x4 world (row_major) + float4 colour, as VSMain/PSColor declare it.
struct DrawConstants {
  float world[16];
  float color[4];
};
DrawConstants MakeConstants(uint32_t draw);
struct DispatchConstants {
  uint32_t base, pad[3];
};

struct Mesh {
  std::vector<float> positions;   // float3
  std::vector<uint16_t> indices;  // triangle list
};
// A cube (mesh 0) and a slightly smaller one (mesh 1): the shadow pass alternates between them.
const Mesh& GetMesh(uint32_t which);
inline constexpr uint32_t kMeshIndices = 36;

std::vector<uint32_t> TextureTexels(uint32_t which);  // 4x4 RGBA8

// A side of one case: Record() records and submits one iteration (what is timed), Wait() waits
// for the GPU (not timed: lavapipe and llvmpipe execute on CPU threads, and that is the driver's
// rasterising, not the cost of the API layer).
class Case {
 public:
  virtual ~Case() = default;
  virtual void Record() = 0;
  virtual void Wait() = 0;
};

// Times Record(); the first iteration is recorded outside the timing, so pipelines, descriptor
// layouts and framebuffers that are created on first use on either side are not counted.
void RunCase(benchmark::State& state, Case& c, uint32_t draws);

}  // namespace spbench
