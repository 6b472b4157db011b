// Shader resource views and samplers: array-slice and mip ranges, cube maps and cube arrays,
// typeless reinterpretation, min/max reduction filters, and typed, structured and raw buffer views
// with element offsets. Depth and stencil read through R24G8_TYPELESS views are a conformance
// probe (eval/conformance/probes/resource-depth-views.cpp), and so are comparison sampling,
// address modes with border colours and LOD clamps (eval/conformance/probes/sampling-*.cpp).
#include <algorithm>
#include <cmath>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

class ViewTest : public BackendTest {
 protected:
  // Runs a compute shader writing `count` float4 into u0 and returns them.
  std::vector<float> RunCompute(const std::string& src, uint32_t count, const std::vector<ShaderResourceView*>& srvs,
                                const std::vector<SamplerState*>& samplers = {}) {
    Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(src, "cs_5_0", "main"));
    UavBuffer out = MakeUavBuffer(device(), count, 16);
    ctx().CSSetShader(cs.get());
    if (!srvs.empty()) ctx().CSSetShaderResources(0, uint32_t(srvs.size()), srvs.data());
    if (!samplers.empty()) ctx().CSSetSamplers(0, uint32_t(samplers.size()), samplers.data());
    ctx().CSSetUnorderedAccessViews(0, {out.uav.get()});
    ctx().Dispatch(1, 1, 1);
    ctx().CSSetUnorderedAccessViews(0, {nullptr});
    return ReadBufferAs<float>(device(), ctx(), out.buffer.get());
  }

  Ref<SamplerState> Sampler(FILTER filter, TEXTURE_ADDRESS_MODE address = TEXTURE_ADDRESS_CLAMP) {
    SAMPLER_DESC d;
    d.Filter = filter;
    d.AddressU = d.AddressV = d.AddressW = address;
    return device().CreateSamplerState(d);
  }
};

// A 2x2 texture array with 4 slices and 2 mips, texel value = slice * 10 + mip.
TEST_P(ViewTest, ArraySliceAndMipRanges) {
  std::vector<std::vector<float>> data;
  std::vector<SUBRESOURCE_DATA> init;
  for (uint32_t s = 0; s < 4; ++s)
    for (uint32_t m = 0; m < 2; ++m) data.push_back(std::vector<float>(4 >> (2 * m), float(s * 10 + m)));
  for (uint32_t i = 0; i < data.size(); ++i) init.push_back({data[i].data(), (2u >> (i % 2)) * 4, 0});
  TEXTURE2D_DESC td;
  td.Width = td.Height = 2;
  td.MipLevels = 2;
  td.ArraySize = 4;
  td.Format = FORMAT_R32_FLOAT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture2D> tex = device().CreateTexture2D(td, init.data());
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {1, 1, 2, 2};  // mip 1 only, slices 2..3
  Ref<ShaderResourceView> range = device().CreateShaderResourceView(tex.get(), &sd);
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};  // a 2D view of an array texture sees slice 0
  Ref<ShaderResourceView> single = device().CreateShaderResourceView(tex.get(), &sd);
  const char* src = R"(
Texture2DArray<float> range : register(t0);
Texture2D<float> single : register(t1);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(1, 1, 1)] void main() {
  uint w, h, elements, levels;
  range.GetDimensions(0, w, h, elements, levels);
  output[0] = float4(range.Load(int4(0, 0, 0, 0)), range.Load(int4(0, 0, 1, 0)), w, elements);
  output[1] = float4(levels, single.Load(int3(1, 1, 0)), 0, 0);
}
)";
  std::vector<float> r = RunCompute(src, 2, {range.get(), single.get()});
  EXPECT_EQ(r[0], 21.0f);
  EXPECT_EQ(r[1], 31.0f);
  EXPECT_EQ(r[2], 1.0f);  // mip 1 of a 2x2 texture
  EXPECT_EQ(r[3], 2.0f);
  EXPECT_EQ(r[4], 1.0f);
  EXPECT_EQ(r[5], 0.0f);
}

// Faces +X, -X, +Y, -Y, +Z, -Z of each cube in D3D's order; sampled at their centres.
TEST_P(ViewTest, CubeMapsAndCubeArrays) {
  const uint32_t S = 4, Cubes = 2;
  std::vector<std::vector<float>> faces;
  std::vector<SUBRESOURCE_DATA> init;
  for (uint32_t f = 0; f < 6 * Cubes; ++f) faces.push_back(std::vector<float>(S * S, float(f + 1)));
  for (auto& f : faces) init.push_back({f.data(), S * 4, 0});
  TEXTURE2D_DESC td;
  td.Width = td.Height = S;
  td.ArraySize = 6 * Cubes;
  td.Format = FORMAT_R32_FLOAT;
  td.BindFlags = BIND_SHADER_RESOURCE;
  td.MiscFlags = RESOURCE_MISC_TEXTURECUBE;
  Ref<Texture2D> tex = device().CreateTexture2D(td, init.data());
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
  sd.TextureCube = {0, 1};
  Ref<ShaderResourceView> cube = device().CreateShaderResourceView(tex.get(), &sd);
  Ref<ShaderResourceView> array = device().CreateShaderResourceView(tex.get());  // TEXTURECUBEARRAY by default
  Ref<SamplerState> point = Sampler(FILTER_MIN_MAG_MIP_POINT);
  const char* src = R"(
TextureCube<float> cube : register(t0);
TextureCubeArray<float> cubes : register(t1);
SamplerState smp : register(s0);
RWStructuredBuffer<float4> output : register(u0);
static const float3 dirs[6] = {float3(1, 0.1, 0.2), float3(-1, 0.1, 0.2), float3(0.1, 1, 0.2), float3(0.1, -1, 0.2), float3(0.1, 0.2, 1), float3(0.1, 0.2, -1)};
[numthreads(6, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  output[i.x] = float4(cube.SampleLevel(smp, dirs[i.x], 0), cubes.SampleLevel(smp, float4(dirs[i.x], 1), 0), 0, 0);
}
)";
  std::vector<float> r = RunCompute(src, 6, {cube.get(), array.get()}, {point.get()});
  for (uint32_t f = 0; f < 6; ++f) {
    EXPECT_EQ(r[f * 4 + 0], float(f + 1)) << "face " << f;
    EXPECT_EQ(r[f * 4 + 1], float(f + 7)) << "cube 1 face " << f;
  }
}

// One R8G8B8A8_TYPELESS texture read as UNORM, UINT and SNORM at the same time.
TEST_P(ViewTest, TypelessReinterpretation) {
  const uint8_t texel[4] = {255, 128, 1, 0x81};
  Ref<Texture2D> tex = MakeTexture2D(device(), 1, 1, FORMAT_R8G8B8A8_TYPELESS, BIND_SHADER_RESOURCE, texel);
  auto view = [&](FORMAT f) {
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = f;
    sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
    sd.Texture2D = {0, 1};
    return device().CreateShaderResourceView(tex.get(), &sd);
  };
  Ref<ShaderResourceView> unorm = view(FORMAT_R8G8B8A8_UNORM), uint = view(FORMAT_R8G8B8A8_UINT), snorm = view(FORMAT_R8G8B8A8_SNORM);
  const char* src = R"(
Texture2D<float4> asUnorm : register(t0);
Texture2D<uint4> asUint : register(t1);
Texture2D<float4> asSnorm : register(t2);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(1, 1, 1)] void main() {
  output[0] = asUnorm.Load(int3(0, 0, 0));
  output[1] = float4(asUint.Load(int3(0, 0, 0)));
  output[2] = asSnorm.Load(int3(0, 0, 0));
}
)";
  std::vector<float> r = RunCompute(src, 3, {unorm.get(), uint.get(), snorm.get()});
  for (int c = 0; c < 4; ++c) {
    EXPECT_FLOAT_EQ(r[c], texel[c] / 255.0f) << c;
    EXPECT_EQ(r[4 + c], float(texel[c])) << c;
    int8_t s = int8_t(texel[c]);
    EXPECT_FLOAT_EQ(r[8 + c], std::max(-1.0f, s / 127.0f)) << c;
  }
}

// MINIMUM/MAXIMUM filters reduce the texels of the footprint instead of weighting them (where
// the device offers them; elsewhere creating the sampler fails cleanly).
TEST_P(ViewTest, MinMaxReductionFilters) {
  const float row[2] = {1.0f, 3.0f};
  Ref<Texture2D> tex = MakeTexture2D(device(), 2, 1, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE, row);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  Ref<SamplerState> mn, mx;
  try {
    mn = Sampler(FILTER_MINIMUM_MIN_MAG_MIP_LINEAR);
    mx = Sampler(FILTER_MAXIMUM_MIN_MAG_MIP_LINEAR);
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED) << e.what();
    GTEST_SKIP() << "min/max filtering is not supported here";
  }
  Ref<SamplerState> linear = Sampler(FILTER_MIN_MAG_MIP_LINEAR);
  const char* src = R"(
Texture2D<float> tex : register(t0);
SamplerState mn : register(s0);
SamplerState mx : register(s1);
SamplerState lin : register(s2);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(1, 1, 1)] void main() {
  float2 uv = float2(0.5, 0.5);
  output[0] = float4(tex.SampleLevel(mn, uv, 0), tex.SampleLevel(mx, uv, 0), tex.SampleLevel(lin, uv, 0), 0);
}
)";
  std::vector<float> r = RunCompute(src, 1, {srv.get()}, {mn.get(), mx.get(), linear.get()});
  EXPECT_EQ(r[0], 1.0f);
  EXPECT_EQ(r[1], 3.0f);
  EXPECT_EQ(r[2], 2.0f);
}

// Buffer views start at FirstElement: typed (Buffer<float4>), structured and raw.
TEST_P(ViewTest, BufferViewsWithElementOffsets) {
  std::vector<float> data(64);
  for (uint32_t i = 0; i < data.size(); ++i) data[i] = float(i);
  Ref<Buffer> typed = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), 256);
  Ref<Buffer> structured = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), 256, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<Buffer> raw = MakeBuffer(device(), BIND_SHADER_RESOURCE, data.data(), 256, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  SHADER_RESOURCE_VIEW_DESC td;
  td.Format = FORMAT_R32G32B32A32_FLOAT;
  td.ViewDimension = SRV_DIMENSION_BUFFER;
  td.Buffer = {2, 8};
  Ref<ShaderResourceView> typedView = device().CreateShaderResourceView(typed.get(), &td);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_UNKNOWN;
  sd.ViewDimension = SRV_DIMENSION_BUFFER;
  sd.Buffer = {3, 4};
  Ref<ShaderResourceView> structuredView = device().CreateShaderResourceView(structured.get(), &sd);
  SHADER_RESOURCE_VIEW_DESC rd;
  rd.Format = FORMAT_R32_TYPELESS;
  rd.ViewDimension = SRV_DIMENSION_BUFFEREX;
  rd.BufferEx = {16, 32, BUFFEREX_SRV_FLAG_RAW};
  Ref<ShaderResourceView> rawView = device().CreateShaderResourceView(raw.get(), &rd);
  const char* src = R"(
Buffer<float4> typed : register(t0);
struct S { float a, b, c, d; };
StructuredBuffer<S> structured : register(t1);
ByteAddressBuffer raw : register(t2);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(1, 1, 1)] void main() {
  uint n, stride;
  structured.GetDimensions(n, stride);
  output[0] = typed.Load(1);
  output[1] = float4(structured[1].b, n, stride, asfloat(raw.Load(8)));
}
)";
  std::vector<float> r = RunCompute(src, 2, {typedView.get(), structuredView.get(), rawView.get()});
  EXPECT_EQ(r[0], 12.0f);  // element 3 of the buffer = floats 12..15
  EXPECT_EQ(r[3], 15.0f);
  EXPECT_EQ(r[4], 17.0f);  // structured element 4, member b
  EXPECT_EQ(r[5], 4.0f);
  EXPECT_EQ(r[6], 16.0f);
  EXPECT_EQ(r[7], 18.0f);  // raw view from byte 64, +8 bytes
}

SP_INSTANTIATE_BACKEND_TESTS(ViewTest);

}  // namespace
}  // namespace sp::test
