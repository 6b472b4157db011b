// The D3D11 call shapes a port writes unchanged: descs by pointer, out-pointers (COM-style T**
// and Ref<T>*), HRESULT results. Success must give what the throwing API gives; failure must give
// D3D11's code, a null *out and the sp::Error's message through the callback as a validation
// error; a null out-pointer only validates (S_FALSE).
#include <cstring>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

const char* kShaders = R"(
struct VOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
VOut VSMain(float3 p : POSITION, float2 uv : TEXCOORD0) { VOut o; o.pos = float4(p, 1); o.uv = uv; return o; }
float4 PSMain(VOut v) : SV_Target { return float4(v.uv, 0, 1); }
RWStructuredBuffer<uint> outBuf : register(u0);
[numthreads(1, 1, 1)] void CSMain() { outBuf[0] = 5; }
)";

// Descs made of 32-bit fields only, compared byte for byte (those with bools are compared by field).
// A non-null out value the failing calls must overwrite with null.
template <class T>
T* Bogus() {
  return reinterpret_cast<T*>(uintptr_t(0x10));
}

template <class T>
bool SameBytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

class D3D11ShapesTest : public BackendTest {
 protected:
  // Errors go to `errors` (the fixture would fail the test on them).
  void CaptureErrors() {
    expectValidationErrors = true;
    device().SetMessageCallback([this](MessageSeverity s, std::string_view t) {
      if (s == MessageSeverity::Error) errors.emplace_back(t);
    });
  }
  // The message the throwing call gives for the same arguments.
  template <class Fn>
  std::string ThrownMessage(Fn&& fn) {
    try {
      fn();
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "the throwing call did not throw";
    return {};
  }
  // Checks one failing HRESULT call: the code, a null out-pointer, one error message equal to the
  // sp::Error's, counted as a validation error.
  template <class P>
  void ExpectFailure(HRESULT got, HRESULT want, const P& out, const std::string& thrown) {
    EXPECT_EQ(got, want);
    EXPECT_EQ(out, nullptr);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0], thrown);
    EXPECT_EQ(device().LastValidationError(), thrown);
    errors.clear();
  }
  std::vector<std::string> errors;
};

TEST_P(D3D11ShapesTest, ResourcesAndViewsMatchTheThrowingCalls) {
  TEXTURE2D_DESC td;
  td.Width = 8;
  td.Height = 4;
  td.Format = FORMAT_R32_TYPELESS;
  td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
  Ref<Texture2D> expected = device().CreateTexture2D(td);
  Texture2D* tex = nullptr;  // COM-style, as CascadedShadowMaps11 keeps it
  ASSERT_EQ(device().CreateTexture2D(&td, NULL, &tex), S_OK);
  ASSERT_NE(tex, nullptr);
  EXPECT_TRUE(SameBytes(expected->GetDesc(), tex->GetDesc()));

  DEPTH_STENCIL_VIEW_DESC dsvd;
  dsvd.Format = FORMAT_D32_FLOAT;
  dsvd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  DepthStencilView* dsv = nullptr;
  ASSERT_EQ(device().CreateDepthStencilView(tex, &dsvd, &dsv), S_OK);
  EXPECT_EQ(dsv->ViewFormat(), device().CreateDepthStencilView(expected.get(), &dsvd)->ViewFormat());
  EXPECT_EQ(dsv->GetResource(), tex);

  SHADER_RESOURCE_VIEW_DESC srvd;
  srvd.Format = FORMAT_R32_FLOAT;
  srvd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srvd.Texture2D = {0, 1};
  Ref<ShaderResourceView> srv;  // the Ref<T>* form
  ASSERT_EQ(device().CreateShaderResourceView(tex, &srvd, &srv), S_OK);
  Ref<ShaderResourceView> srvExpected = device().CreateShaderResourceView(expected.get(), &srvd);
  EXPECT_TRUE(SameBytes(srv->GetDesc(), srvExpected->GetDesc()));
  EXPECT_EQ(srv->Range().mipCount, srvExpected->Range().mipCount);

  Ref<Texture2D> color = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET | BIND_UNORDERED_ACCESS);
  RenderTargetView* rtv = nullptr;
  ASSERT_EQ(device().CreateRenderTargetView(color.get(), NULL, &rtv), S_OK);
  EXPECT_EQ(rtv->ViewFormat(), FORMAT_R8G8B8A8_UNORM);
  UnorderedAccessView* uav = nullptr;
  ASSERT_EQ(device().CreateUnorderedAccessView(color.get(), nullptr, &uav), S_OK);
  EXPECT_EQ(uav->GetDesc().ViewDimension, device().CreateUnorderedAccessView(color.get())->GetDesc().ViewDimension);

  BUFFER_DESC bd;
  bd.ByteWidth = 64;
  bd.Usage = USAGE_DYNAMIC;
  bd.BindFlags = BIND_CONSTANT_BUFFER;
  bd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Buffer* cb = nullptr;
  ASSERT_EQ(device().CreateBuffer(&bd, NULL, &cb), S_OK);
  EXPECT_TRUE(SameBytes(cb->GetDesc(), device().CreateBuffer(bd)->GetDesc()));

  TEXTURE1D_DESC t1;
  t1.Width = 16;
  t1.Format = FORMAT_R8G8B8A8_UNORM;
  t1.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture1D> tex1;
  ASSERT_EQ(device().CreateTexture1D(&t1, nullptr, &tex1), S_OK);
  EXPECT_EQ(tex1->GetDesc().Width, device().CreateTexture1D(t1)->GetDesc().Width);
  TEXTURE3D_DESC t3;
  t3.Width = t3.Height = t3.Depth = 4;
  t3.Format = FORMAT_R16_FLOAT;
  t3.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture3D> tex3;
  ASSERT_EQ(device().CreateTexture3D(&t3, nullptr, &tex3), S_OK);
  EXPECT_TRUE(SameBytes(tex3->GetDesc(), device().CreateTexture3D(t3)->GetDesc()));

  // The COM references this test took; the views keep their resources alive on their own.
  for (Object* o : std::initializer_list<Object*>{uav, rtv, cb, dsv}) EXPECT_EQ(o->Release(), 0u);
  EXPECT_EQ(tex->Release(), 0u);
}

TEST_P(D3D11ShapesTest, StatesShadersLayoutsAndQueriesMatchTheThrowingCalls) {
  SAMPLER_DESC sd;
  sd.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  sd.ComparisonFunc = COMPARISON_LESS;
  Ref<SamplerState> s;
  ASSERT_EQ(device().CreateSamplerState(&sd, &s), S_OK);
  EXPECT_TRUE(SameBytes(s->GetDesc(), device().CreateSamplerState(sd)->GetDesc()));
  RASTERIZER_DESC rd;
  rd.DepthBias = 100;
  rd.SlopeScaledDepthBias = 2;
  Ref<RasterizerState> rs;
  ASSERT_EQ(device().CreateRasterizerState(&rd, &rs), S_OK);
  Ref<RasterizerState> rsExpected = device().CreateRasterizerState(rd);
  EXPECT_EQ(rs->GetDesc().DepthBias, rsExpected->GetDesc().DepthBias);
  EXPECT_EQ(rs->GetDesc().SlopeScaledDepthBias, rsExpected->GetDesc().SlopeScaledDepthBias);
  EXPECT_EQ(rs->GetDesc().CullMode, rsExpected->GetDesc().CullMode);
  EXPECT_EQ(rs->GetDesc().DepthClipEnable, rsExpected->GetDesc().DepthClipEnable);
  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_GREATER_EQUAL;
  Ref<DepthStencilState> ds;
  ASSERT_EQ(device().CreateDepthStencilState(&dd, &ds), S_OK);
  Ref<DepthStencilState> dsExpected = device().CreateDepthStencilState(dd);
  EXPECT_EQ(ds->GetDesc().DepthFunc, dsExpected->GetDesc().DepthFunc);
  EXPECT_EQ(ds->GetDesc().DepthEnable, dsExpected->GetDesc().DepthEnable);
  EXPECT_EQ(ds->GetDesc().DepthWriteMask, dsExpected->GetDesc().DepthWriteMask);
  BLEND_DESC bd;
  bd.RenderTarget[0].BlendEnable = true;
  bd.RenderTarget[0].SrcBlend = BLEND_SRC_ALPHA;
  bd.RenderTarget[0].DestBlend = BLEND_INV_SRC_ALPHA;
  Ref<BlendState> bs;
  ASSERT_EQ(device().CreateBlendState(&bd, &bs), S_OK);
  Ref<BlendState> bsExpected = device().CreateBlendState(bd);
  EXPECT_EQ(bs->GetDesc().RenderTarget[0].BlendEnable, bsExpected->GetDesc().RenderTarget[0].BlendEnable);
  EXPECT_EQ(bs->GetDesc().RenderTarget[0].SrcBlend, bsExpected->GetDesc().RenderTarget[0].SrcBlend);
  EXPECT_EQ(bs->GetDesc().RenderTarget[0].DestBlend, bsExpected->GetDesc().RenderTarget[0].DestBlend);
  QUERY_DESC qd;
  qd.Query = QUERY_OCCLUSION;
  Query* q = nullptr;
  ASSERT_EQ(device().CreateQuery(&qd, &q), S_OK);
  EXPECT_EQ(q->GetDesc().Query, device().CreateQuery(qd)->GetDesc().Query);
  EXPECT_EQ(q->Release(), 0u);

  // Blobs as D3DCompile's ID3DBlob gives them: GetBufferPointer(), GetBufferSize().
  ShaderBytecode vsCode = CompileHlsl(kShaders, "vs_5_0", "VSMain");
  std::vector<uint8_t> vsBlob = vsCode.Serialize(), psBlob = CompileHlsl(kShaders, "ps_5_0", "PSMain").Serialize();
  std::vector<uint8_t> csBlob = CompileHlsl(kShaders, "cs_5_0", "CSMain").Serialize();
  VertexShader* vs = nullptr;
  PixelShader* ps = nullptr;
  Ref<ComputeShader> cs;
  ASSERT_EQ(device().CreateVertexShader(vsBlob.data(), vsBlob.size(), NULL, &vs), S_OK);
  ASSERT_EQ(device().CreatePixelShader(psBlob.data(), psBlob.size(), NULL, &ps), S_OK);
  ASSERT_EQ(device().CreateComputeShader(csBlob.data(), csBlob.size(), nullptr, &cs), S_OK);
  EXPECT_EQ(vs->Bytecode().spirv, device().CreateVertexShader(vsBlob.data(), vsBlob.size())->Bytecode().spirv);
  EXPECT_EQ(ps->Stage(), ShaderStage::Pixel);
  EXPECT_EQ(cs->Reflection().threadGroupSize, (std::array<uint32_t, 3>{1, 1, 1}));
  const INPUT_ELEMENT_DESC layout[] = {{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                                       {"TEXCOORD", 0, FORMAT_R32G32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0}};
  InputLayout* il = nullptr;
  ASSERT_EQ(device().CreateInputLayout(layout, 2, vsBlob.data(), vsBlob.size(), &il), S_OK);
  Ref<InputLayout> ilExpected = device().CreateInputLayout(layout, 2, vsCode);
  ASSERT_EQ(il->Attributes().size(), ilExpected->Attributes().size());
  for (size_t i = 0; i < il->Attributes().size(); ++i) {
    EXPECT_EQ(il->Attributes()[i].location, ilExpected->Attributes()[i].location);
    EXPECT_EQ(il->Attributes()[i].offset, ilExpected->Attributes()[i].offset);
  }
  // The shapes D3D11 code binds with: raw pointers and NULL class instances.
  ctx().VSSetShader(vs, NULL, 0);
  ctx().PSSetShader(ps, NULL, 0);
  ctx().CSSetShader(cs.get(), nullptr, 0);
  ctx().GSSetShader(NULL, NULL, 0);
  ctx().IASetInputLayout(il);
  EXPECT_EQ(il->Release(), 0u);
  EXPECT_EQ(vs->Release(), 0u);
  EXPECT_EQ(ps->Release(), 0u);
  // Still bound, so still alive.
  VertexShader* bound = nullptr;
  ctx().VSGetShader(&bound, NULL, NULL);
  ASSERT_NE(bound, nullptr);
  EXPECT_EQ(bound->Bytecode().sourceName, vsCode.sourceName);
  EXPECT_EQ(bound->Release(), 0u);
}

TEST_P(D3D11ShapesTest, FailuresReturnD3D11CodesAndReportTheError) {
  CaptureErrors();
  TEXTURE2D_DESC td;
  td.Width = 0;  // invalid
  td.Height = 4;
  td.Format = FORMAT_R8G8B8A8_UNORM;
  td.BindFlags = BIND_SHADER_RESOURCE;
  Texture2D* tex = Bogus<Texture2D>();  // must be overwritten with null
  HRESULT hr = device().CreateTexture2D(&td, NULL, &tex);
  ExpectFailure(hr, E_INVALIDARG, tex, ThrownMessage([&] { device().CreateTexture2D(td); }));
  EXPECT_EQ(device().ValidationErrorCount(), 1u);

  Ref<Texture2D> ref = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<Texture2D> refOut = ref;  // the Ref<T>* form is reset too
  hr = device().CreateTexture2D(&td, nullptr, &refOut);
  ExpectFailure(hr, E_INVALIDARG, refOut, ThrownMessage([&] { device().CreateTexture2D(td); }));

  // NOT_SUPPORTED and FORMAT_UNSUPPORTED give DXGI_ERROR_UNSUPPORTED.
  td.Width = 4;
  td.Format = FORMAT_R32G32B32_FLOAT;
  tex = Bogus<Texture2D>();
  ExpectFailure(device().CreateTexture2D(&td, NULL, &tex), DXGI_ERROR_UNSUPPORTED, tex, ThrownMessage([&] { device().CreateTexture2D(td); }));
  BUFFER_DESC bd;
  bd.ByteWidth = 16;
  bd.BindFlags = BIND_STREAM_OUTPUT;
  Buffer* buf = Bogus<Buffer>();
  ExpectFailure(device().CreateBuffer(&bd, NULL, &buf), DXGI_ERROR_UNSUPPORTED, buf, ThrownMessage([&] { device().CreateBuffer(bd); }));
  std::vector<uint8_t> vsBlob = CompileHlsl(kShaders, "vs_5_0", "VSMain").Serialize();
  GeometryShader* gs = Bogus<GeometryShader>();
  ExpectFailure(device().CreateGeometryShader(vsBlob.data(), vsBlob.size(), NULL, &gs), DXGI_ERROR_UNSUPPORTED, gs,
                ThrownMessage([&] { device().CreateGeometryShader(ShaderBytecode::Deserialize(vsBlob.data(), vsBlob.size())); }));

  // Class linkage is refused with a message saying so.
  ClassLinkage* linkage = reinterpret_cast<ClassLinkage*>(&bd);
  VertexShader* vs = Bogus<VertexShader>();
  EXPECT_EQ(device().CreateVertexShader(vsBlob.data(), vsBlob.size(), linkage, &vs), DXGI_ERROR_UNSUPPORTED);
  EXPECT_EQ(vs, nullptr);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("class linkage"), std::string::npos) << errors[0];
  errors.clear();

  // Stage mismatch, a bad blob, null descs: E_INVALIDARG.
  PixelShader* ps = Bogus<PixelShader>();
  ExpectFailure(device().CreatePixelShader(vsBlob.data(), vsBlob.size(), NULL, &ps), E_INVALIDARG, ps,
                ThrownMessage([&] { device().CreatePixelShader(vsBlob.data(), vsBlob.size()); }));
  const uint8_t junk[16] = {1, 2, 3};
  ComputeShader* cs = Bogus<ComputeShader>();
  ExpectFailure(device().CreateComputeShader(junk, sizeof(junk), NULL, &cs), E_INVALIDARG, cs,
                ThrownMessage([&] { device().CreateComputeShader(junk, sizeof(junk)); }));
  SamplerState* smp = Bogus<SamplerState>();
  EXPECT_EQ(device().CreateSamplerState(nullptr, &smp), E_INVALIDARG);
  EXPECT_EQ(smp, nullptr);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("pDesc is null"), std::string::npos) << errors[0];
  errors.clear();
  const INPUT_ELEMENT_DESC wrong[] = {{"POSITION", 0, FORMAT_R32G32B32_UINT, 0, 0, INPUT_PER_VERTEX_DATA, 0}};
  InputLayout* il = Bogus<InputLayout>();
  ExpectFailure(device().CreateInputLayout(wrong, 1, vsBlob.data(), vsBlob.size(), &il), E_INVALIDARG, il,
                ThrownMessage([&] { device().CreateInputLayout(wrong, 1, ShaderBytecode::Deserialize(vsBlob.data(), vsBlob.size())); }));
  QUERY_DESC qd;
  qd.MiscFlags = 1;
  Query* q = Bogus<Query>();
  ExpectFailure(device().CreateQuery(&qd, &q), E_INVALIDARG, q, ThrownMessage([&] { device().CreateQuery(qd); }));
  SHADER_RESOURCE_VIEW_DESC srvd;
  srvd.Format = FORMAT_R16G16_FLOAT;
  srvd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  srvd.Texture2D = {0, 1};
  ShaderResourceView* srv = Bogus<ShaderResourceView>();
  ExpectFailure(device().CreateShaderResourceView(ref.get(), &srvd, &srv), E_INVALIDARG, srv,
                ThrownMessage([&] { device().CreateShaderResourceView(ref.get(), &srvd); }));
  RASTERIZER_DESC rd;
  rd.CullMode = CULL_MODE(9);
  RasterizerState* rs = Bogus<RasterizerState>();
  ExpectFailure(device().CreateRasterizerState(&rd, &rs), E_INVALIDARG, rs, ThrownMessage([&] { device().CreateRasterizerState(rd); }));

  // Each failure counted once (the throwing calls above did not report).
  EXPECT_EQ(device().ValidationErrorCount(), 13u);
}

// The remaining Create* shapes fail the same way.
TEST_P(D3D11ShapesTest, EveryCreateShapeReportsFailure) {
  CaptureErrors();
  TEXTURE1D_DESC t1;
  t1.Width = 0;
  t1.Format = FORMAT_R8G8B8A8_UNORM;
  Texture1D* tex1 = Bogus<Texture1D>();
  ExpectFailure(device().CreateTexture1D(&t1, NULL, &tex1), E_INVALIDARG, tex1, ThrownMessage([&] { device().CreateTexture1D(t1); }));
  TEXTURE3D_DESC t3;
  t3.Width = t3.Height = 4;
  t3.Depth = 0;
  t3.Format = FORMAT_R8G8B8A8_UNORM;
  TEXTURE3D_DESC valid = t3;
  valid.Depth = 4;
  valid.BindFlags = BIND_SHADER_RESOURCE;
  Ref<Texture3D> tex3 = device().CreateTexture3D(valid);  // the Ref<T>* form is reset on failure
  ExpectFailure(device().CreateTexture3D(&t3, NULL, &tex3), E_INVALIDARG, tex3, ThrownMessage([&] { device().CreateTexture3D(t3); }));

  // Views of a texture that lacks the bind flag they need.
  Ref<Texture2D> plain = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  RenderTargetView* rtv = Bogus<RenderTargetView>();
  ExpectFailure(device().CreateRenderTargetView(plain.get(), NULL, &rtv), E_INVALIDARG, rtv,
                ThrownMessage([&] { device().CreateRenderTargetView(plain.get()); }));
  DepthStencilView* dsv = Bogus<DepthStencilView>();
  ExpectFailure(device().CreateDepthStencilView(plain.get(), NULL, &dsv), E_INVALIDARG, dsv,
                ThrownMessage([&] { device().CreateDepthStencilView(plain.get()); }));
  UnorderedAccessView* uav = Bogus<UnorderedAccessView>();
  ExpectFailure(device().CreateUnorderedAccessView(plain.get(), NULL, &uav), E_INVALIDARG, uav,
                ThrownMessage([&] { device().CreateUnorderedAccessView(plain.get()); }));

  DEPTH_STENCIL_DESC dd;
  dd.DepthFunc = COMPARISON_FUNC(0);
  DepthStencilState* ds = Bogus<DepthStencilState>();
  ExpectFailure(device().CreateDepthStencilState(&dd, &ds), E_INVALIDARG, ds, ThrownMessage([&] { device().CreateDepthStencilState(dd); }));
  BLEND_DESC bd;
  bd.RenderTarget[0].BlendEnable = true;
  bd.RenderTarget[0].BlendOp = BLEND_OP(0);
  BlendState* bs = Bogus<BlendState>();
  ExpectFailure(device().CreateBlendState(&bd, &bs), E_INVALIDARG, bs, ThrownMessage([&] { device().CreateBlendState(bd); }));

  VertexShader* vs = Bogus<VertexShader>();
  EXPECT_EQ(device().CreateVertexShader(nullptr, 0, NULL, &vs), E_INVALIDARG);
  EXPECT_EQ(vs, nullptr);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("pShaderBytecode is null"), std::string::npos) << errors[0];
  EXPECT_EQ(device().ValidationErrorCount(), 8u);
}

TEST_P(D3D11ShapesTest, FormatSupportHresultForms) {
  uint32_t support = 0;
  EXPECT_EQ(device().CheckFormatSupport(FORMAT_R8G8B8A8_UNORM, &support), S_OK);
  EXPECT_EQ(support, device().CheckFormatSupport(FORMAT_R8G8B8A8_UNORM));
  EXPECT_NE(support & FORMAT_SUPPORT_TEXTURE2D, 0u);
  support = 1;
  EXPECT_EQ(device().CheckFormatSupport(FORMAT_UNKNOWN, &support), E_FAIL);
  EXPECT_EQ(support, 0u);
  uint32_t levels = 7;
  EXPECT_EQ(device().CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 1, &levels), S_OK);
  EXPECT_EQ(levels, 1u);
  EXPECT_EQ(device().CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 3, &levels), S_OK);
  EXPECT_EQ(levels, 0u);  // not a power of two
  EXPECT_EQ(device().CheckFormatSupport(FORMAT_R8G8B8A8_UNORM, nullptr), E_INVALIDARG);
}

TEST_P(D3D11ShapesTest, NullOutPointerOnlyValidates) {
  CaptureErrors();
  TEXTURE2D_DESC td;
  td.Width = td.Height = 4;
  td.Format = FORMAT_R8G8B8A8_UNORM;
  td.BindFlags = BIND_SHADER_RESOURCE;
  EXPECT_EQ(device().CreateTexture2D(&td, NULL, NULL), S_FALSE);
  EXPECT_EQ(device().CreateTexture2D(&td, nullptr, nullptr), S_FALSE);
  SAMPLER_DESC sd;
  EXPECT_EQ(device().CreateSamplerState(&sd, NULL), S_FALSE);
  EXPECT_TRUE(errors.empty());
  td.Width = 0;
  EXPECT_EQ(device().CreateTexture2D(&td, NULL, NULL), E_INVALIDARG);
  EXPECT_EQ(errors.size(), 1u);
}

TEST_P(D3D11ShapesTest, ComReferencesAndRefsShareOneLifetime) {
  TEXTURE2D_DESC td;
  td.Width = td.Height = 4;
  td.Format = FORMAT_R8G8B8A8_UNORM;
  td.BindFlags = BIND_SHADER_RESOURCE;

  // COM only: destroyed by the last Release.
  Texture2D* tex = nullptr;
  ASSERT_EQ(device().CreateTexture2D(&td, NULL, &tex), S_OK);
  std::weak_ptr<Object> alive = tex->weak_from_this();
  EXPECT_EQ(tex->AddRef(), 2u);
  EXPECT_EQ(tex->Release(), 1u);
  EXPECT_FALSE(alive.expired());
  EXPECT_EQ(tex->Release(), 0u);
  EXPECT_TRUE(alive.expired());

  // COM then Ref: the object lives until the last of both goes, whichever order.
  ASSERT_EQ(device().CreateTexture2D(&td, NULL, &tex), S_OK);
  alive = tex->weak_from_this();
  Ref<Texture2D> ref = std::static_pointer_cast<Texture2D>(tex->shared_from_this());
  EXPECT_EQ(tex->Release(), 0u);
  EXPECT_FALSE(alive.expired());
  ref.reset();
  EXPECT_TRUE(alive.expired());

  Ref<Texture2D> owner = device().CreateTexture2D(td);
  alive = owner;
  Texture2D* raw = owner.get();
  EXPECT_EQ(raw->AddRef(), 1u);
  owner.reset();
  EXPECT_FALSE(alive.expired());
  EXPECT_EQ(raw->Release(), 0u);
  EXPECT_TRUE(alive.expired());

  // Releasing a reference never taken is an error, not a double free.
  Ref<Texture2D> plain = device().CreateTexture2D(td);
  EXPECT_THROW(plain->Release(), Error);

  // Raw pointers in the T* const* binding calls keep working: the context holds its own
  // reference, and the *Get* calls hand out COM references.
  ShaderResourceView* srv = nullptr;
  ASSERT_EQ(device().CreateShaderResourceView(device().CreateTexture2D(td).get(), NULL, &srv), S_OK);
  std::weak_ptr<Object> srvAlive = srv->weak_from_this();
  std::weak_ptr<Object> texAlive = srv->GetResource()->weak_from_this();
  ctx().PSSetShaderResources(3, 1, &srv);
  EXPECT_EQ(srv->Release(), 0u);
  EXPECT_FALSE(srvAlive.expired());
  ShaderResourceView* got[2] = {nullptr, reinterpret_cast<ShaderResourceView*>(uintptr_t(1))};
  ctx().PSGetShaderResources(3, 2, got);
  ASSERT_EQ(got[0], srv);
  EXPECT_EQ(got[1], nullptr);
  ctx().ClearState();
  EXPECT_FALSE(srvAlive.expired());  // the Get's reference
  EXPECT_EQ(got[0]->Release(), 0u);
  EXPECT_TRUE(srvAlive.expired());
  EXPECT_TRUE(texAlive.expired());
}

TEST_P(D3D11ShapesTest, GettersGiveTheBoundState) {
  Ref<Texture2D> color = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(color.get());
  Ref<Texture2D> depth = MakeTexture2D(device(), 4, 4, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(depth.get());
  Ref<SamplerState> smp = device().CreateSamplerState(SAMPLER_DESC{});
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, nullptr, 16);
  Ref<Buffer> vb = MakeBuffer(device(), BIND_VERTEX_BUFFER, nullptr, 64);
  Ref<Buffer> ib = MakeBuffer(device(), BIND_INDEX_BUFFER, nullptr, 64);
  UavBuffer uav = MakeUavBuffer(device(), 4, 4);
  Ref<RasterizerState> rs = device().CreateRasterizerState(RASTERIZER_DESC{});
  Ref<BlendState> bs = device().CreateBlendState(BLEND_DESC{});
  Ref<DepthStencilState> ds = device().CreateDepthStencilState(DEPTH_STENCIL_DESC{});
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kShaders, "cs_5_0", "CSMain"));

  RenderTargetView* rtvs[] = {rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, dsv.get());
  ctx().PSSetSamplers(2, {smp.get()});
  ctx().VSSetConstantBuffers(1, {cb.get()});
  ctx().CSSetUnorderedAccessViews(0, {uav.uav.get()});
  ctx().CSSetShader(cs.get());
  const uint32_t stride = 16, offset = 8;
  Buffer* vbs[] = {vb.get()};
  ctx().IASetVertexBuffers(2, 1, vbs, &stride, &offset);
  ctx().IASetIndexBuffer(ib.get(), FORMAT_R16_UINT, 4);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_LINESTRIP);
  ctx().RSSetState(rs.get());
  const VIEWPORT vps[2] = {{0, 0, 4, 4, 0, 1}, {1, 1, 2, 2, 0.25f, 0.5f}};
  ctx().RSSetViewports(2, vps);
  const float factor[4] = {0.5f, 0.25f, 1, 0};
  ctx().OMSetBlendState(bs.get(), factor, 0xf0u);
  ctx().OMSetDepthStencilState(ds.get(), 7);

  Ref<RenderTargetView> gotRtv[2];
  Ref<DepthStencilView> gotDsv;
  ctx().OMGetRenderTargets(2, gotRtv, &gotDsv);
  EXPECT_EQ(gotRtv[0], rtv);
  EXPECT_EQ(gotRtv[1], nullptr);
  EXPECT_EQ(gotDsv, dsv);
  SamplerState* gotSmp = nullptr;
  ctx().PSGetSamplers(2, 1, &gotSmp);
  EXPECT_EQ(gotSmp, smp.get());
  gotSmp->Release();
  Ref<Buffer> gotCb;
  ctx().VSGetConstantBuffers(1, 1, &gotCb);
  EXPECT_EQ(gotCb, cb);
  ctx().PSGetConstantBuffers(1, 1, &gotCb);
  EXPECT_EQ(gotCb, nullptr);
  Ref<UnorderedAccessView> gotUav;
  ctx().CSGetUnorderedAccessViews(0, 1, &gotUav);
  EXPECT_EQ(gotUav, uav.uav);
  Ref<ComputeShader> gotCs;
  uint32_t numInstances = 5;
  ctx().CSGetShader(&gotCs, nullptr, &numInstances);
  EXPECT_EQ(gotCs, cs);
  EXPECT_EQ(numInstances, 0u);
  Ref<Buffer> gotVb;
  uint32_t gotStride = 0, gotOffset = 0;
  ctx().IAGetVertexBuffers(2, 1, &gotVb, &gotStride, &gotOffset);
  EXPECT_EQ(gotVb, vb);
  EXPECT_EQ(gotStride, stride);
  EXPECT_EQ(gotOffset, offset);
  Ref<Buffer> gotIb;
  FORMAT ibFormat = FORMAT_UNKNOWN;
  uint32_t ibOffset = 0;
  ctx().IAGetIndexBuffer(&gotIb, &ibFormat, &ibOffset);
  EXPECT_EQ(gotIb, ib);
  EXPECT_EQ(ibFormat, FORMAT_R16_UINT);
  EXPECT_EQ(ibOffset, 4u);
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_UNDEFINED;
  ctx().IAGetPrimitiveTopology(&topology);
  EXPECT_EQ(topology, PRIMITIVE_TOPOLOGY_LINESTRIP);
  Ref<RasterizerState> gotRs;
  ctx().RSGetState(&gotRs);
  EXPECT_EQ(gotRs, rs);
  uint32_t numVps = 0;
  ctx().RSGetViewports(&numVps, nullptr);
  ASSERT_EQ(numVps, 2u);
  VIEWPORT gotVps[3];
  numVps = 3;
  ctx().RSGetViewports(&numVps, gotVps);
  EXPECT_EQ(gotVps[1].TopLeftX, 1.0f);
  EXPECT_EQ(gotVps[1].MaxDepth, 0.5f);
  EXPECT_EQ(gotVps[2].Width, 0.0f);
  Ref<BlendState> gotBs;
  float gotFactor[4] = {};
  uint32_t mask = 0;
  ctx().OMGetBlendState(&gotBs, gotFactor, &mask);
  EXPECT_EQ(gotBs, bs);
  EXPECT_EQ(gotFactor[1], 0.25f);
  EXPECT_EQ(mask, 0xf0u);
  Ref<DepthStencilState> gotDs;
  uint32_t stencilRef = 0;
  ctx().OMGetDepthStencilState(&gotDs, &stencilRef);
  EXPECT_EQ(gotDs, ds);
  EXPECT_EQ(stencilRef, 7u);

  ctx().ClearState();
  ctx().OMGetRenderTargets(1, gotRtv, &gotDsv);
  EXPECT_EQ(gotRtv[0], nullptr);
  EXPECT_EQ(gotDsv, nullptr);
  EXPECT_THROW(ctx().PSGetShaderResources(127, 2, static_cast<ShaderResourceView**>(nullptr)), Error);
}

TEST_P(D3D11ShapesTest, ClassInstancesAreRefused) {
  Ref<ComputeShader> cs = device().CreateComputeShader(CompileHlsl(kShaders, "cs_5_0", "CSMain"));
  ClassInstance* instance = reinterpret_cast<ClassInstance*>(cs.get());
  try {
    ctx().CSSetShader(cs.get(), &instance, 1);
    FAIL() << "class instances were accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::NOT_SUPPORTED);
    EXPECT_EQ(e.call(), "CSSetShader");
    EXPECT_NE(std::string(e.what()).find("class linkage"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ctx().VSSetShader(nullptr, nullptr, 1), Error);
}

TEST_P(D3D11ShapesTest, MapAndGetDataReadAsBoolAndAsHRESULT) {
  BUFFER_DESC bd;
  bd.ByteWidth = 16;
  bd.Usage = USAGE_STAGING;
  bd.CPUAccessFlags = CPU_ACCESS_READ | CPU_ACCESS_WRITE;
  Ref<Buffer> buf = device().CreateBuffer(bd);
  MAPPED_SUBRESOURCE m;
  HRESULT hr = ctx().Map(buf.get(), 0, MAP_WRITE, 0, &m);  // as `V(ctx->Map(...))` uses it
  EXPECT_EQ(hr, S_OK);
  EXPECT_TRUE(SUCCEEDED(hr));
  ctx().Unmap(buf.get(), 0);
  EXPECT_TRUE(ctx().Map(buf.get(), 0, MAP_READ, 0, &m));  // as existing `if (!ctx->Map(...))` uses it
  ctx().Unmap(buf.get(), 0);

  QUERY_DESC qd;
  qd.Query = QUERY_EVENT;
  Ref<Query> q = device().CreateQuery(qd);
  ctx().End(q.get());
  ctx().WaitIdle();
  uint32_t done = 0;
  EXPECT_EQ(ctx().GetData(q.get(), &done, sizeof(done), 0), S_OK);  // `while (S_OK != ctx->GetData(...))`
  EXPECT_TRUE(ctx().GetData(q.get(), &done, sizeof(done), 0));
  EXPECT_EQ(done, 1u);
}

TEST_P(D3D11ShapesTest, PrivateDataNamesObjects) {
  Ref<Buffer> b = MakeBuffer(device(), BIND_VERTEX_BUFFER, nullptr, 16);
  const char name[] = "CSM vertex buffer";
  EXPECT_EQ(b->SetPrivateData(WKPDID_D3DDebugObjectName, sizeof(name) - 1, name), S_OK);
  EXPECT_EQ(b->GetDebugName(), "CSM vertex buffer");
  EXPECT_NE(b->Describe().find("'CSM vertex buffer'"), std::string::npos);
  uint32_t size = 0;
  EXPECT_EQ(b->GetPrivateData(WKPDID_D3DDebugObjectName, &size, nullptr), S_OK);
  EXPECT_EQ(size, sizeof(name) - 1);
  char small[4];
  size = sizeof(small);
  EXPECT_EQ(b->GetPrivateData(WKPDID_D3DDebugObjectName, &size, small), DXGI_ERROR_MORE_DATA);

  const GUID mine{0x12345678, 0x1, 0x2, {1, 2, 3, 4, 5, 6, 7, 8}};
  const uint32_t value = 42;
  EXPECT_EQ(b->SetPrivateData(mine, sizeof(value), &value), S_OK);
  uint32_t back = 0;
  size = sizeof(back);
  EXPECT_EQ(b->GetPrivateData(mine, &size, &back), S_OK);
  EXPECT_EQ(back, 42u);
  EXPECT_EQ(b->SetPrivateData(mine, 0, nullptr), S_OK);
  EXPECT_EQ(b->GetPrivateData(mine, &size, &back), DXGI_ERROR_NOT_FOUND);
  EXPECT_EQ(size, 0u);
}

// tex->GetDesc(&desc), view->GetDesc(&desc), state->GetDesc(&desc), view->GetResource(&res).
TEST_P(D3D11ShapesTest, GetDescAndGetResourceTakeOutPointers) {
  TEXTURE2D_DESC td = {64, 32, 1, 2, FORMAT_R32_TYPELESS, 1, 0, USAGE_DEFAULT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  Texture2D* tex = nullptr;
  ASSERT_EQ(device().CreateTexture2D(&td, nullptr, &tex), S_OK);
  TEXTURE2D_DESC back{};
  tex->GetDesc(&back);
  EXPECT_TRUE(SameBytes(back, td));
  SHADER_RESOURCE_VIEW_DESC sd = {FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DARRAY};
  sd.Texture2DArray = {0, 1, 1, 1};
  ShaderResourceView* srv = nullptr;
  ASSERT_EQ(device().CreateShaderResourceView(tex, &sd, &srv), S_OK);
  SHADER_RESOURCE_VIEW_DESC sdBack;
  srv->GetDesc(&sdBack);
  EXPECT_EQ(sdBack.Format, FORMAT_R32_FLOAT);
  EXPECT_EQ(sdBack.ViewDimension, SRV_DIMENSION_TEXTURE2DARRAY);
  EXPECT_EQ(sdBack.Texture2DArray.FirstArraySlice, 1u);
  // GetResource hands out a COM reference: the texture outlives our own Release.
  Resource* res = nullptr;
  srv->GetResource(&res);
  EXPECT_EQ(res, static_cast<Resource*>(tex));
  EXPECT_EQ(tex->Release(), 1u);
  EXPECT_EQ(res->Release(), 0u);  // the view still holds the texture alive through its Ref
  RASTERIZER_DESC rd;
  rd.DepthBias = 7;
  RasterizerState* rs = nullptr;
  ASSERT_EQ(device().CreateRasterizerState(&rd, &rs), S_OK);
  RASTERIZER_DESC rdBack;
  rs->GetDesc(&rdBack);
  EXPECT_EQ(rdBack.DepthBias, 7);
  BUFFER_DESC bd = {256, USAGE_DEFAULT, BIND_CONSTANT_BUFFER, 0, 0, 0};
  Buffer* cb = nullptr;
  ASSERT_EQ(device().CreateBuffer(&bd, nullptr, &cb), S_OK);
  BUFFER_DESC bdBack{};
  cb->GetDesc(&bdBack);
  EXPECT_TRUE(SameBytes(bdBack, bd));
  EXPECT_EQ(cb->Release(), 0u);
  EXPECT_EQ(rs->Release(), 0u);
  EXPECT_EQ(srv->Release(), 0u);
}

TEST_P(D3D11ShapesTest, ImmediateContextThroughAnOutPointer) {
  DeviceContext* context = nullptr;
  device().GetImmediateContext(&context);
  EXPECT_EQ(context, &ctx());
  DeviceContext* again = nullptr;
  device().GetImmediateContext(&again);
  EXPECT_EQ(context->Release(), 1u);
  EXPECT_EQ(again->Release(), 0u);
  try {
    context->Release();
    ADD_FAILURE() << "a Release too many must be reported";
  } catch (const Error& e) {
    EXPECT_EQ(e.id(), ErrorId::INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("once too often"), std::string::npos) << e.what();
  }
}

SP_INSTANTIATE_VALIDATION_TESTS(D3D11ShapesTest);

}  // namespace
}  // namespace sp::test
