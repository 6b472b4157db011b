// The same HLSL arithmetic gives bit-identical results on both backends. Mesa lowers dot and
// matrix products and lerp differently from SPIR-V and from GLSL; the toolchain rewrites them into
// one fixed order of multiplies and adds, which this test holds it to on random inputs.
#include <gtest/gtest.h>

#include <random>

#include "backend-test.h"

namespace sp::test {
namespace {

const char* kShader = R"(
cbuffer Matrices : register(b0) { float4x4 M; row_major float4x4 R; float3x3 N; };
StructuredBuffer<float4> input : register(t0);
RWStructuredBuffer<float4> output : register(u0);
RWStructuredBuffer<float4> lerps : register(u1);
[numthreads(64, 1, 1)] void main(uint3 id : SV_DispatchThreadID) {
  float4 v = input[id.x], w = input[id.x + 1];
  // A constant endpoint is where Mesa's two paths differed (mix with a literal).
  lerps[id.x] = float4(lerp(v.x, 0.4075, frac(w.x)), lerp(v.yz, w.yz, frac(w.zw)), lerp(v.w, w.w, 0.3));
  float4 r = mul(M, v) + mul(v, R);
  r.xyz += mul(N, w.xyz) + normalize(w.xyz) * length(v.xyz) + distance(v.xy, w.xy);
  r.w += dot(v, w) + dot(v.xyz, w.zyx);
  output[id.x] = r;
}
)";

std::vector<float> RunOn(Backend backend, const std::vector<float>& in, const std::vector<float>& matrices) {
  DeviceDesc dd;
  dd.backend = backend;
  Ref<Device> dev = CreateDevice(dd);
  DeviceContext& ctx = *dev->GetImmediateContext();
  Ref<ComputeShader> cs = dev->CreateComputeShader(CompileHlsl(kShader, "cs_5_0", "main"));
  Ref<Buffer> cb = MakeBuffer(*dev, BIND_CONSTANT_BUFFER, matrices.data(), uint32_t(matrices.size() * 4));
  Ref<Buffer> src = MakeBuffer(*dev, BIND_SHADER_RESOURCE, in.data(), uint32_t(in.size() * 4), RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<Buffer> dst = MakeBuffer(*dev, BIND_UNORDERED_ACCESS, nullptr, uint32_t((in.size() - 4) * 4), RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> srv = dev->CreateShaderResourceView(src.get());
  Ref<Buffer> lerps = MakeBuffer(*dev, BIND_UNORDERED_ACCESS, nullptr, uint32_t((in.size() - 4) * 4), RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<UnorderedAccessView> uav = dev->CreateUnorderedAccessView(dst.get()), lerpUav = dev->CreateUnorderedAccessView(lerps.get());
  ctx.CSSetShader(cs.get());
  ctx.CSSetConstantBuffers(0, {cb.get()});
  ctx.CSSetShaderResources(0, {srv.get()});
  ctx.CSSetUnorderedAccessViews(0, {uav.get(), lerpUav.get()});
  ctx.Dispatch(uint32_t((in.size() / 4 - 1) / 64), 1, 1);
  EXPECT_EQ(dev->ValidationErrorCount(), 0u) << dev->LastValidationError();
  std::vector<float> out = ReadAs<float>(ReadBuffer(*dev, ctx, dst.get()));
  std::vector<float> l = ReadAs<float>(ReadBuffer(*dev, ctx, lerps.get()));
  out.insert(out.end(), l.begin(), l.end());
  return out;
}

TEST(CrossBackendArithmetic, DotMatrixProductsAndLerpAreBitIdentical) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  std::vector<float> in(4 * (64 * 16 + 1)), matrices(16 + 16 + 12);
  for (float& f : in) f = u(rng);
  for (float& f : matrices) f = u(rng) * 0.1f;
  std::vector<float> vk = RunOn(Backend::Vulkan, in, matrices), gl = RunOn(Backend::OpenGL, in, matrices);
  ASSERT_EQ(vk.size(), gl.size());
  size_t differing = 0;
  for (size_t i = 0; i < vk.size(); ++i) differing += std::memcmp(&vk[i], &gl[i], 4) != 0;
  EXPECT_EQ(differing, 0u) << "of " << vk.size() << " results";
}

}  // namespace
}  // namespace sp::test
