// Misuse of the API gives an sp::Error with a stable id whose message names the call and the
// object, on both backends, and never a crash or a silently wrong image.
#include "backend-test.h"

namespace sp::test {
namespace {

class MisuseTest : public BackendTest {};

// Runs `f`, expects an sp::Error with `id` whose message contains every string in `mentions`.
template <class F>
void ExpectError(ErrorId id, std::initializer_list<const char*> mentions, F&& f) {
  try {
    f();
    ADD_FAILURE() << "expected SP_" << ErrorIdName(id);
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), id) << e.what();
    for (const char* m : mentions) EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << "'" << m << "' missing in: " << e.what();
  }
}

TEST_P(MisuseTest, WrongBindFlags) {
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  tex->SetDebugName("albedo");
  ExpectError(ErrorId::BIND_FLAGS_INVALID, {"CreateRenderTargetView", "albedo", "BIND_RENDER_TARGET"},
              [&] { device().CreateRenderTargetView(tex.get()); });
  Ref<Buffer> vb = MakeBuffer(device(), BIND_VERTEX_BUFFER, nullptr, 64);
  vb->SetDebugName("verts");
  ExpectError(ErrorId::BIND_FLAGS_INVALID, {"PSSetConstantBuffers", "verts"}, [&] { ctx().PSSetConstantBuffers(0, {vb.get()}); });
  ExpectError(ErrorId::BIND_FLAGS_INVALID, {"CreateBuffer", "BIND_CONSTANT_BUFFER"},
              [&] { MakeBuffer(device(), BIND_CONSTANT_BUFFER | BIND_SHADER_RESOURCE, nullptr, 64); });
  ExpectError(ErrorId::BIND_FLAGS_INVALID, {"CreateTexture2D", "TYPELESS"},
              [&] { MakeTexture2D(device(), 4, 4, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE); });
}

TEST_P(MisuseTest, IncompatibleViewFormats) {
  Ref<Texture2D> depth = MakeTexture2D(device(), 4, 4, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  depth->SetDebugName("shadow map");
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R16G16_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  ExpectError(ErrorId::VIEW_FORMAT_INCOMPATIBLE, {"CreateShaderResourceView", "shadow map", "R16G16_FLOAT"},
              [&] { device().CreateShaderResourceView(depth.get(), &sd); });
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D16_UNORM;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  ExpectError(ErrorId::VIEW_FORMAT_INCOMPATIBLE, {"CreateDepthStencilView", "D32_FLOAT"}, [&] { device().CreateDepthStencilView(depth.get(), &dd); });
  // A TYPELESS texture without a desc: the view format is ambiguous.
  ExpectError(ErrorId::VIEW_FORMAT_INCOMPATIBLE, {"CreateShaderResourceView", "TYPELESS"}, [&] { device().CreateShaderResourceView(depth.get()); });
  // The valid pair works.
  sd.Format = FORMAT_R32_FLOAT;
  EXPECT_NO_THROW(device().CreateShaderResourceView(depth.get(), &sd));
  dd.Format = FORMAT_D32_FLOAT;
  EXPECT_NO_THROW(device().CreateDepthStencilView(depth.get(), &dd));
}

TEST_P(MisuseTest, OutOfRangeSizesAndSubresources) {
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, {"CreateTexture2D", "16384"}, [&] { MakeTexture2D(device(), 20000, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE); });
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, {"CreateBuffer", "ByteWidth"}, [&] { MakeBuffer(device(), BIND_VERTEX_BUFFER, nullptr, 0); });
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, {"CreateBuffer", "multiple of 16"}, [&] { MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 20); });
  ExpectError(ErrorId::SIZE_OUT_OF_RANGE, {"CreateTexture2D", "MipLevels"},
              [&] { MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, nullptr, 5); });
  Ref<Texture2D> tex = MakeTexture2D(device(), 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, nullptr, 2, 3);
  tex->SetDebugName("array");
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R8G8B8A8_UNORM;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {0, 1, 2, 2};
  ExpectError(ErrorId::SUBRESOURCE_OUT_OF_RANGE, {"CreateShaderResourceView", "array", "array slices"},
              [&] { device().CreateShaderResourceView(tex.get(), &sd); });
  std::vector<uint8_t> data(64 * 4);
  ExpectError(ErrorId::SUBRESOURCE_OUT_OF_RANGE, {"UpdateSubresource", "array", "subresource 6"},
              [&] { ctx().UpdateSubresource(tex.get(), 6, nullptr, data.data(), 32, 0); });
  BOX box{0, 0, 0, 9, 8, 1};
  Ref<Texture2D> dst = MakeTexture2D(device(), 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  ExpectError(ErrorId::SUBRESOURCE_OUT_OF_RANGE, {"CopySubresourceRegion", "pSrcBox"},
              [&] { ctx().CopySubresourceRegion(dst.get(), 0, 0, 0, 0, tex.get(), 0, &box); });
  ExpectError(ErrorId::SLOT_OUT_OF_RANGE, {"PSSetShaderResources"}, [&] { ctx().PSSetShaderResources(127, {nullptr, nullptr}); });
}

TEST_P(MisuseTest, SampleCountMismatch) {
  if (device().CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 4) == 0) GTEST_SKIP() << "no 4x MSAA";
  Ref<Texture2D> color = MakeTexture2D(device(), 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET, nullptr, 1, 1, 4);
  Ref<Texture2D> depth = MakeTexture2D(device(), 8, 8, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  depth->SetDebugName("single-sampled depth");
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(color.get());
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ExpectError(ErrorId::SAMPLE_COUNT_MISMATCH, {"OMSetRenderTargets", "single-sampled depth", "4x"},
              [&] { ctx().OMSetRenderTargets(1, rtvs, dsv.get()); });
  ExpectError(ErrorId::SAMPLE_COUNT_MISMATCH, {"ResolveSubresource", "multisampled"},
              [&] { ctx().ResolveSubresource(color.get(), 0, depth.get(), 0, FORMAT_R8G8B8A8_UNORM); });
}

TEST_P(MisuseTest, SlotTheShaderReadsLeftUnbound) {
  const char* src = R"(
Texture2D<float4> albedo : register(t3);
SamplerState smp : register(s1);
float4 VSMain(uint id : SV_VertexID) : SV_Position { return float4(0, 0, 0, 1); }
float4 PSMain(float4 p : SV_Position) : SV_Target { return albedo.Sample(smp, p.xy); }
)";
  Ref<VertexShader> vs = device().CreateVertexShader(CompileHlsl(src, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device().CreatePixelShader(CompileHlsl(src, "ps_5_0", "PSMain"));
  ps->SetDebugName("textured");
  Ref<Texture2D> rt = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(rt.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, 4, 4, 0, 1};
  ctx().RSSetViewports(1, &vp);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx().VSSetShader(vs.get());
  ctx().PSSetShader(ps.get());
  ExpectError(ErrorId::UNBOUND_RESOURCE, {"Draw", "textured", "PS slot t3", "albedo"}, [&] { ctx().Draw(3, 0); });
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  ctx().PSSetShaderResources(3, {srv.get()});
  ExpectError(ErrorId::UNBOUND_RESOURCE, {"Draw", "PS slot s1", "smp"}, [&] { ctx().Draw(3, 0); });
  // A comparison sampler where the shader declares SamplerState is a type mismatch.
  SAMPLER_DESC cmp;
  cmp.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  cmp.ComparisonFunc = COMPARISON_LESS;
  Ref<SamplerState> cmpSampler = device().CreateSamplerState(cmp);
  ctx().PSSetSamplers(1, {cmpSampler.get()});
  ExpectError(ErrorId::RESOURCE_TYPE_MISMATCH, {"Draw", "SamplerState"}, [&] { ctx().Draw(3, 0); });
  Ref<SamplerState> linear = device().CreateSamplerState(SAMPLER_DESC{});
  ctx().PSSetSamplers(1, {linear.get()});
  EXPECT_NO_THROW(ctx().Draw(3, 0));
}

TEST_P(MisuseTest, MapMisuse) {
  Ref<Buffer> def = MakeBuffer(device(), BIND_VERTEX_BUFFER, nullptr, 64);
  def->SetDebugName("default vb");
  MAPPED_SUBRESOURCE m;
  ExpectError(ErrorId::MAP_INVALID, {"Map", "default vb", "USAGE_DYNAMIC"}, [&] { ctx().Map(def.get(), 0, MAP_WRITE_DISCARD, 0, &m); });
  ExpectError(ErrorId::MAP_INVALID, {"Unmap", "not mapped"}, [&] { ctx().Unmap(def.get(), 0); });
  BUFFER_DESC d;
  d.ByteWidth = 64;
  d.Usage = USAGE_DYNAMIC;
  d.BindFlags = BIND_CONSTANT_BUFFER;
  ExpectError(ErrorId::USAGE_INVALID, {"CreateBuffer", "CPU_ACCESS_WRITE"}, [&] { device().CreateBuffer(d); });
}

TEST_P(MisuseTest, HazardUnbindsInputWhenBoundForOutput) {
  // D3D11 semantics: binding a texture as a render target unbinds its SRV (with a warning), and
  // binding the SRV while the RTV is bound binds NULL instead.
  std::vector<std::string> warnings;
  device().SetMessageCallback([&](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Warning) warnings.emplace_back(t);
    if (s == MessageSeverity::Error) validationMessages.emplace_back(t);
  });
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(tex.get());
  ctx().PSSetShaderResources(2, {srv.get()});
  ASSERT_EQ(ctx().State().stage(ShaderStage::Pixel).shaderResources[2].get(), srv.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  EXPECT_EQ(ctx().State().stage(ShaderStage::Pixel).shaderResources[2], nullptr);
  ctx().PSSetShaderResources(2, {srv.get()});
  EXPECT_EQ(ctx().State().stage(ShaderStage::Pixel).shaderResources[2], nullptr);
  EXPECT_EQ(warnings.size(), 2u);
  // A read-only DSV does not conflict with a depth SRV.
  Ref<Texture2D> depth = MakeTexture2D(device(), 4, 4, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE);
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  dd.Flags = DSV_READ_ONLY_DEPTH;
  Ref<DepthStencilView> ro = device().CreateDepthStencilView(depth.get(), &dd);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R32_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  Ref<ShaderResourceView> dsrv = device().CreateShaderResourceView(depth.get(), &sd);
  ctx().OMSetRenderTargets(0, nullptr, ro.get());
  ctx().PSSetShaderResources(0, {dsrv.get()});
  EXPECT_EQ(ctx().State().stage(ShaderStage::Pixel).shaderResources[0].get(), dsrv.get());
}

TEST_P(MisuseTest, ShaderErrors) {
  const char* src = "float4 main() : SV_Target { return 1; }";
  ShaderBytecode ps = CompileHlsl(src, "ps_5_0", "main");
  ExpectError(ErrorId::SHADER_STAGE_MISMATCH, {"CreateVertexShader", "pixel shader"}, [&] { device().CreateVertexShader(ps); });
  std::vector<uint8_t> junk(64, 7);
  ExpectError(ErrorId::INVALID_ARGUMENT, {"Deserialize", "bad magic"}, [&] { device().CreatePixelShader(junk.data(), junk.size()); });
  const char* vsSrc = "float4 main(float3 p : POSITION, float2 uv : TEXCOORD1) : SV_Position { return float4(p + uv.x, 1); }";
  ShaderBytecode vs = CompileHlsl(vsSrc, "vs_5_0", "main");
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  ExpectError(ErrorId::INPUT_LAYOUT_MISMATCH, {"CreateInputLayout", "TEXCOORD1"}, [&] { device().CreateInputLayout(&el, 1, vs); });
  INPUT_ELEMENT_DESC wrongType[] = {{"POSITION", 0, FORMAT_R32G32B32_UINT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                                    {"TEXCOORD", 1, FORMAT_R32G32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0}};
  ExpectError(ErrorId::INPUT_LAYOUT_MISMATCH, {"CreateInputLayout", "R32G32B32_UINT"}, [&] { device().CreateInputLayout(wrongType, 2, vs); });
}

SP_INSTANTIATE_BACKEND_TESTS(MisuseTest);

}  // namespace
}  // namespace sp::test
