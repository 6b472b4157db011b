// D3D11's input/output hazard rules for bindings: binding a resource for output unbinds it from
// input slots and binding it for input while it is bound for output binds NULL, each with the
// debug layer's warning. (Misuse that D3D11 fails, sp::Error with its id naming the call and the
// object, is checked by the conformance probes in eval/conformance/probes/misuse-*.cpp.)
#include "backend-test.h"

namespace sp::test {
namespace {

class MisuseTest : public BackendTest {};

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
  auto boundAt = [&](uint32_t slot) {
    Ref<ShaderResourceView> v;
    ctx().PSGetShaderResources(slot, 1, &v);
    return v;
  };
  ctx().PSSetShaderResources(2, {srv.get()});
  ASSERT_EQ(boundAt(2), srv);
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  EXPECT_EQ(boundAt(2), nullptr);
  ctx().PSSetShaderResources(2, {srv.get()});
  EXPECT_EQ(boundAt(2), nullptr);
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
  EXPECT_EQ(boundAt(0), dsrv);
}

// A raw buffer may be a vertex buffer, an index buffer and a shader resource at once: binding it
// as a compute UAV unbinds it from each of those slots, with a warning naming each.
TEST_P(MisuseTest, BindingABufferAsUavUnbindsItsVertexIndexAndShaderResourceSlots) {
  std::vector<std::string> warnings;
  device().SetMessageCallback([&](MessageSeverity s, std::string_view t) {
    if (s == MessageSeverity::Warning) warnings.emplace_back(t);
    if (s == MessageSeverity::Error) validationMessages.emplace_back(t);
  });
  Ref<Buffer> buf = MakeBuffer(device(), BIND_VERTEX_BUFFER | BIND_INDEX_BUFFER | BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS, nullptr, 64,
                               RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  const CSHADER_RESOURCE_VIEW_DESC sd(buf.get(), FORMAT_R32_TYPELESS, 0, 16, BUFFEREX_SRV_FLAG_RAW);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(buf.get(), &sd);
  const CUNORDERED_ACCESS_VIEW_DESC ud(buf.get(), FORMAT_R32_TYPELESS, 0, 16, BUFFER_UAV_FLAG_RAW);
  Ref<UnorderedAccessView> uav = device().CreateUnorderedAccessView(buf.get(), &ud);
  Buffer* vbs[] = {buf.get()};
  uint32_t stride = 16, offset = 0;
  ctx().IASetVertexBuffers(3, 1, vbs, &stride, &offset);
  ctx().IASetIndexBuffer(buf.get(), FORMAT_R32_UINT, 0);
  ctx().VSSetShaderResources(5, {srv.get()});
  ctx().CSSetUnorderedAccessViews(0, {uav.get()});
  Ref<Buffer> vb, ib;
  Ref<ShaderResourceView> view;
  uint32_t gotStride = 0, gotOffset = 0, gotIndexOffset = 0;
  FORMAT format = FORMAT_UNKNOWN;
  ctx().IAGetVertexBuffers(3, 1, &vb, &gotStride, &gotOffset);
  ctx().IAGetIndexBuffer(&ib, &format, &gotIndexOffset);
  ctx().VSGetShaderResources(5, 1, &view);
  EXPECT_EQ(vb, nullptr);
  EXPECT_EQ(ib, nullptr);
  EXPECT_EQ(view, nullptr);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(warnings[0].find("VS slot t5"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("vertex buffer slot 3"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[2].find("the index buffer"), std::string::npos) << warnings[2];
}

SP_INSTANTIATE_VALIDATION_TESTS(MisuseTest);

}  // namespace
}  // namespace sp::test
