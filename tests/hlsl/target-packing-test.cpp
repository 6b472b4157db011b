// The per-target products of a compiled shader (rhi/src/hlsl/target-*.cpp), without a device:
// both targets repack a tricky cbuffer from the same D3D11 offsets (one rule,
// target-cbuffer.cpp), GL to std140 offsets computed here by hand; pixel shaders writing
// SV_Target1 come with their dual-source variants for both targets.
#include <gtest/gtest.h>

#include <map>

#include "backend-test.h"
// The products are internal to the library (rhi/src).
#include "shader-bindings.h"

namespace sp::test {
namespace {

// Every kind of member D3D11 packs differently from std140 and from SPIR-V block rules.
const char* kTricky = R"(
struct Light { float3 dir; float power; float2 uv; };
cbuffer Tricky : register(b2) {
  float3 a;
  float b;       // fills a's register
  float c[3];    // each element starts a register
  float d;       // in the tail of c's last register
  float3x3 m;    // column_major: one register per column
  float e;       // in the tail of m's last register
  Light l;       // a struct starts a register
  float f;       // in the tail of l's last register
  float2 g;      // would straddle: next register
};
float4 main() : SV_Target {
  return float4(a * b + c[0] + c[1] + c[2] + d + mul(a, m) * e, 1) + float4(l.dir * l.power, f) + float4(l.uv, g);
}
)";

// D3D11 packing by hand: 16-byte registers, no member straddles one, arrays of 16-byte elements,
// the next member may use the tail of an array's, matrix's or struct's last register.
struct Field {
  const char* what;
  uint32_t d3d, std140, size;  // byte offsets in each layout, bytes
};
const Field kFields[] = {
    {"a", 0, 0, 12},          {"b", 12, 12, 4},
    {"c[0]", 16, 16, 4},      {"c[1]", 32, 32, 4},      {"c[2]", 48, 48, 4},
    {"d", 52, 64, 4},
    {"m col 0", 64, 80, 12},  {"m col 1", 80, 96, 12},  {"m col 2", 96, 112, 12},
    {"e", 108, 128, 4},
    {"l.dir", 112, 144, 12},  {"l.power", 124, 156, 4}, {"l.uv", 128, 160, 8},
    {"f", 136, 176, 4},       {"g", 144, 184, 8},
};

// Where each source byte of the D3D-packed buffer lands in the target's layout.
std::map<uint32_t, uint32_t> Destinations(const std::vector<CBufferCopyRange>& ranges) {
  std::map<uint32_t, uint32_t> out;
  for (const CBufferCopyRange& r : ranges)
    for (uint32_t i = 0; i < r.size; ++i) out[r.src + i] = r.dst + i;
  return out;
}

std::map<uint32_t, uint32_t> ExpectedBytes(bool std140) {
  std::map<uint32_t, uint32_t> out;
  for (const Field& f : kFields)
    for (uint32_t i = 0; i < f.size; ++i) out[f.d3d + i] = std140 ? f.std140 + i : f.d3d + i;
  return out;
}

TEST(TargetPacking, BothTargetsRepackFromD3D11Offsets) {
  ShaderBytecode ps = CompileHlsl(kTricky, "ps_5_0", "main");
  ASSERT_EQ(ps.reflection.cbuffers.size(), 1u);
  const CBufferInfo& cb = ps.reflection.cbuffers[0];
  EXPECT_EQ(cb.size, 160u);  // g ends at 152
  ASSERT_EQ(cb.members.size(), 9u);
  const uint32_t memberOffsets[] = {0, 12, 16, 52, 64, 108, 112, 136, 144};
  for (size_t i = 0; i < 9; ++i) EXPECT_EQ(cb.members[i].offset, memberOffsets[i]) << cb.members[i].name;

  // GL: the std140 block and the copies into it.
  const GlBinding* ubo = nullptr;
  for (const GlBinding& g : detail::GlBindingsOf(ps))
    if (g.kind == GlBindingKind::UniformBlock && g.registerIndex == 2) ubo = &g;
  ASSERT_NE(ubo, nullptr);
  EXPECT_EQ(ubo->glBlockSize, 192u);
  std::map<uint32_t, uint32_t> gl = Destinations(ubo->repack), glExpected = ExpectedBytes(true);
  EXPECT_EQ(gl, glExpected);

  // Vulkan: the same source bytes, each to where glslang's block puts it (not computed here: the
  // rendering tests check those); the order of members is kept.
  const detail::SpirvProducts& vk = detail::TargetsOf(ps).spirv;
  ASSERT_EQ(vk.repacks.size(), 1u);
  EXPECT_EQ(vk.repacks[0].reg, 2u);
  std::map<uint32_t, uint32_t> vkDst = Destinations(vk.repacks[0].ranges);
  std::vector<uint32_t> vkSources, expectedSources;
  for (const auto& [src, dst] : vkDst) vkSources.push_back(src);
  for (const auto& [src, dst] : glExpected) expectedSources.push_back(src);
  EXPECT_EQ(vkSources, expectedSources);
  uint32_t last = 0;
  for (const Field& f : kFields) {
    ASSERT_TRUE(vkDst.count(f.d3d)) << f.what;
    EXPECT_GE(vkDst[f.d3d], last) << f.what;
    last = vkDst[f.d3d] + f.size;
    EXPECT_LE(last, vk.repacks[0].size) << f.what;
  }

  // One rule: the products survive the blob (and so the cache) unchanged.
  std::vector<uint8_t> blob = ps.Serialize();
  ShaderBytecode back = ShaderBytecode::Deserialize(blob.data(), blob.size());
  EXPECT_EQ(Destinations(detail::TargetsOf(back).spirv.repacks.at(0).ranges), vkDst);
}

TEST(TargetPacking, DualSourceVariantsMadeAtCompileTime) {
  const char* src = R"(
struct Out { float4 c0 : SV_Target0; float4 c1 : SV_Target1; };
Out main(float4 p : SV_Position) { Out o; o.c0 = float4(0.5, 0, 0, 1); o.c1 = float4(0.25, 0, 0, 1); return o; }
float4 single(float4 p : SV_Position) : SV_Target { return p; }
)";
  ShaderBytecode dual = CompileHlsl(src, "ps_5_0", "main");
  const detail::TargetProducts& t = detail::TargetsOf(dual);
  EXPECT_NE(t.gl.dualSourceGlsl.find("layout(location = 0, index = 1) out "), std::string::npos) << t.gl.dualSourceGlsl;
  EXPECT_EQ(dual.glsl.find("index = 1"), std::string::npos) << dual.glsl;
  EXPECT_FALSE(t.spirv.dualSource.empty());
  EXPECT_EQ(detail::SpirvFor(dual, {false, false, true}), t.spirv.dualSource);
  EXPECT_EQ(detail::SpirvFor(dual, {}), dual.spirv);

  ShaderBytecode single = CompileHlsl(src, "ps_5_0", "single");
  EXPECT_TRUE(detail::TargetsOf(single).gl.dualSourceGlsl.empty());
  EXPECT_TRUE(detail::TargetsOf(single).spirv.dualSource.empty());
}

}  // namespace
}  // namespace sp::test
