// D3D11's helper classes (CD3D11_* -> sp::C*), its default constants and D3D11-style aggregate
// initialisation of the description structs. Expected values are D3D11's documented defaults,
// written out here rather than taken from the code under test.
#include <cfloat>
#include <type_traits>

#include "rhi-test-util.h"

namespace sp::test {
namespace {

// ---- layout: positional initialisation lands in D3D11's field order ----------------------------

// Sizes of the descs whose fields are all 32-bit in D3D11 too (BOOL descs differ: bool is 1 byte).
static_assert(sizeof(BUFFER_DESC) == 24);
static_assert(sizeof(TEXTURE1D_DESC) == 32);
static_assert(sizeof(TEXTURE2D_DESC) == 44);
static_assert(sizeof(TEXTURE3D_DESC) == 36);
static_assert(sizeof(SAMPLER_DESC) == 52);
static_assert(sizeof(SHADER_RESOURCE_VIEW_DESC) == 24);
static_assert(sizeof(RENDER_TARGET_VIEW_DESC) == 20);
static_assert(sizeof(DEPTH_STENCIL_VIEW_DESC) == 24);
static_assert(sizeof(UNORDERED_ACCESS_VIEW_DESC) == 20);
static_assert(sizeof(VIEWPORT) == 24 && sizeof(RECT) == 16 && sizeof(BOX) == 24 && sizeof(QUERY_DESC) == 8);
static_assert(std::is_aggregate_v<SHADER_RESOURCE_VIEW_DESC> && std::is_aggregate_v<RENDER_TARGET_VIEW_DESC> &&
              std::is_aggregate_v<DEPTH_STENCIL_VIEW_DESC> && std::is_aggregate_v<UNORDERED_ACCESS_VIEW_DESC>);

TEST(DescLayout, PositionalInitialisationFollowsD3D11FieldOrder) {
  BUFFER_DESC b = {64, USAGE_DYNAMIC, BIND_CONSTANT_BUFFER, CPU_ACCESS_WRITE, 0x40, 16};
  EXPECT_EQ(b.ByteWidth, 64u);
  EXPECT_EQ(b.Usage, USAGE_DYNAMIC);
  EXPECT_EQ(b.BindFlags, uint32_t(BIND_CONSTANT_BUFFER));
  EXPECT_EQ(b.CPUAccessFlags, uint32_t(CPU_ACCESS_WRITE));
  EXPECT_EQ(b.MiscFlags, 0x40u);
  EXPECT_EQ(b.StructureByteStride, 16u);

  TEXTURE1D_DESC t1 = {8, 2, 3, FORMAT_R8_UNORM, USAGE_STAGING, 0, CPU_ACCESS_READ, 0};
  EXPECT_EQ(t1.Width, 8u);
  EXPECT_EQ(t1.MipLevels, 2u);
  EXPECT_EQ(t1.ArraySize, 3u);
  EXPECT_EQ(t1.Format, FORMAT_R8_UNORM);
  EXPECT_EQ(t1.Usage, USAGE_STAGING);
  EXPECT_EQ(t1.CPUAccessFlags, uint32_t(CPU_ACCESS_READ));

  // The CascadedShadowMaps11 shadow map, with SampleDesc brace-elided as D3D samples write it.
  uint32_t w = 32, h = 16;
  TEXTURE2D_DESC t2 = {w, h, 1, 1, FORMAT_R32_TYPELESS, 1, 0, USAGE_DEFAULT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  EXPECT_EQ(t2.Width, 32u);
  EXPECT_EQ(t2.Height, 16u);
  EXPECT_EQ(t2.MipLevels, 1u);
  EXPECT_EQ(t2.ArraySize, 1u);
  EXPECT_EQ(t2.Format, FORMAT_R32_TYPELESS);
  EXPECT_EQ(t2.SampleDesc.Count, 1u);
  EXPECT_EQ(t2.SampleDesc.Quality, 0u);
  EXPECT_EQ(t2.BindFlags, uint32_t(BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE));
  TEXTURE2D_DESC t2b = {w, h, 3, 6, FORMAT_R8G8B8A8_UNORM, {4, 0}, USAGE_IMMUTABLE, BIND_SHADER_RESOURCE, 0, RESOURCE_MISC_TEXTURECUBE};
  EXPECT_EQ(t2b.MipLevels, 3u);
  EXPECT_EQ(t2b.ArraySize, 6u);
  EXPECT_EQ(t2b.SampleDesc.Count, 4u);
  EXPECT_EQ(t2b.Usage, USAGE_IMMUTABLE);
  EXPECT_EQ(t2b.MiscFlags, uint32_t(RESOURCE_MISC_TEXTURECUBE));

  TEXTURE3D_DESC t3 = {4, 5, 6, 2, FORMAT_R16_FLOAT, USAGE_DEFAULT, BIND_UNORDERED_ACCESS, 0, 0};
  EXPECT_EQ(t3.Depth, 6u);
  EXPECT_EQ(t3.MipLevels, 2u);
  EXPECT_EQ(t3.Format, FORMAT_R16_FLOAT);
  EXPECT_EQ(t3.BindFlags, uint32_t(BIND_UNORDERED_ACCESS));

  SAMPLER_DESC s = {FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT, TEXTURE_ADDRESS_BORDER, TEXTURE_ADDRESS_MIRROR, TEXTURE_ADDRESS_WRAP,
                    0.5f, 4, COMPARISON_LESS, {0.1f, 0.2f, 0.3f, 0.4f}, 1.0f, FLOAT32_MAX};
  EXPECT_EQ(s.Filter, FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT);
  EXPECT_EQ(s.AddressU, TEXTURE_ADDRESS_BORDER);
  EXPECT_EQ(s.AddressV, TEXTURE_ADDRESS_MIRROR);
  EXPECT_EQ(s.AddressW, TEXTURE_ADDRESS_WRAP);
  EXPECT_EQ(s.MipLODBias, 0.5f);
  EXPECT_EQ(s.MaxAnisotropy, 4u);
  EXPECT_EQ(s.ComparisonFunc, COMPARISON_LESS);
  EXPECT_EQ(s.BorderColor[2], 0.3f);
  EXPECT_EQ(s.MinLOD, 1.0f);
  EXPECT_EQ(s.MaxLOD, FLT_MAX);

  RASTERIZER_DESC r = {FILL_WIREFRAME, CULL_FRONT, true, -3, 0.25f, 1.5f, false, true, true, true};
  EXPECT_EQ(r.FillMode, FILL_WIREFRAME);
  EXPECT_EQ(r.CullMode, CULL_FRONT);
  EXPECT_TRUE(r.FrontCounterClockwise);
  EXPECT_EQ(r.DepthBias, -3);
  EXPECT_EQ(r.DepthBiasClamp, 0.25f);
  EXPECT_EQ(r.SlopeScaledDepthBias, 1.5f);
  EXPECT_FALSE(r.DepthClipEnable);
  EXPECT_TRUE(r.ScissorEnable && r.MultisampleEnable && r.AntialiasedLineEnable);

  DEPTH_STENCIL_DESC d = {false, DEPTH_WRITE_MASK_ZERO, COMPARISON_GREATER, true, 0x0f, 0xf0,
                          {STENCIL_OP_ZERO, STENCIL_OP_REPLACE, STENCIL_OP_INCR, COMPARISON_EQUAL},
                          {STENCIL_OP_DECR, STENCIL_OP_INVERT, STENCIL_OP_INCR_SAT, COMPARISON_NOT_EQUAL}};
  EXPECT_FALSE(d.DepthEnable);
  EXPECT_EQ(d.DepthWriteMask, DEPTH_WRITE_MASK_ZERO);
  EXPECT_EQ(d.DepthFunc, COMPARISON_GREATER);
  EXPECT_TRUE(d.StencilEnable);
  EXPECT_EQ(d.StencilReadMask, 0x0f);
  EXPECT_EQ(d.StencilWriteMask, 0xf0);
  EXPECT_EQ(d.FrontFace.StencilFailOp, STENCIL_OP_ZERO);
  EXPECT_EQ(d.FrontFace.StencilDepthFailOp, STENCIL_OP_REPLACE);
  EXPECT_EQ(d.FrontFace.StencilPassOp, STENCIL_OP_INCR);
  EXPECT_EQ(d.FrontFace.StencilFunc, COMPARISON_EQUAL);
  EXPECT_EQ(d.BackFace.StencilFunc, COMPARISON_NOT_EQUAL);

  RENDER_TARGET_BLEND_DESC rt = {true, BLEND_SRC_ALPHA, BLEND_INV_SRC_ALPHA, BLEND_OP_SUBTRACT, BLEND_ONE, BLEND_ZERO, BLEND_OP_MAX, 0x7};
  EXPECT_TRUE(rt.BlendEnable);
  EXPECT_EQ(rt.SrcBlend, BLEND_SRC_ALPHA);
  EXPECT_EQ(rt.DestBlend, BLEND_INV_SRC_ALPHA);
  EXPECT_EQ(rt.BlendOp, BLEND_OP_SUBTRACT);
  EXPECT_EQ(rt.BlendOpAlpha, BLEND_OP_MAX);
  EXPECT_EQ(rt.RenderTargetWriteMask, 0x7);
  BLEND_DESC bd = {true, true, {rt}};
  EXPECT_TRUE(bd.AlphaToCoverageEnable && bd.IndependentBlendEnable);
  EXPECT_EQ(bd.RenderTarget[0].SrcBlend, BLEND_SRC_ALPHA);

  INPUT_ELEMENT_DESC layout[] = {
      {"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"TEXCOORD", 1, FORMAT_R32G32_FLOAT, 2, 12, INPUT_PER_INSTANCE_DATA, 3},
  };
  EXPECT_STREQ(layout[1].SemanticName, "TEXCOORD");
  EXPECT_EQ(layout[1].SemanticIndex, 1u);
  EXPECT_EQ(layout[1].Format, FORMAT_R32G32_FLOAT);
  EXPECT_EQ(layout[1].InputSlot, 2u);
  EXPECT_EQ(layout[1].AlignedByteOffset, 12u);
  EXPECT_EQ(layout[1].InputSlotClass, INPUT_PER_INSTANCE_DATA);
  EXPECT_EQ(layout[1].InstanceDataStepRate, 3u);

  VIEWPORT vp = {1, 2, 3, 4, 0.25f, 0.75f};
  EXPECT_EQ(vp.TopLeftY, 2.0f);
  EXPECT_EQ(vp.Height, 4.0f);
  EXPECT_EQ(vp.MaxDepth, 0.75f);
  BOX box = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(box.front, 3u);
  EXPECT_EQ(box.right, 4u);
  RECT rc = {1, 2, 3, 4};
  EXPECT_EQ(rc.top, 2);
  EXPECT_EQ(rc.right, 3);
  QUERY_DESC q = {QUERY_OCCLUSION, 0};
  EXPECT_EQ(q.Query, QUERY_OCCLUSION);
  SUBRESOURCE_DATA init = {&b, 16, 32};
  EXPECT_EQ(init.SysMemPitch, 16u);
  EXPECT_EQ(init.SysMemSlicePitch, 32u);
}

// The view descs' union starts with Buffer in D3D11: brace initialisation lands there and aliases
// Texture2D.MostDetailedMip/MipLevels; everything not given is zero.
TEST(DescLayout, ViewDescBraceInitialisationFillsTheUnionAsD3D11) {
  SHADER_RESOURCE_VIEW_DESC srv = {FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2D, 0, 1};
  EXPECT_EQ(srv.Format, FORMAT_R32_FLOAT);
  EXPECT_EQ(srv.ViewDimension, SRV_DIMENSION_TEXTURE2D);
  EXPECT_EQ(srv.Texture2D.MostDetailedMip, 0u);
  EXPECT_EQ(srv.Texture2D.MipLevels, 1u);
  EXPECT_EQ(srv.Buffer.FirstElement, 0u);
  EXPECT_EQ(srv.Buffer.NumElements, 1u);
  EXPECT_EQ(srv.Buffer.ElementWidth, 1u);
  EXPECT_EQ(srv.Texture2DArray.FirstArraySlice, 0u);
  EXPECT_EQ(srv.Texture2DArray.ArraySize, 0u);
  SHADER_RESOURCE_VIEW_DESC srv2 = {FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DARRAY, 2};
  EXPECT_EQ(srv2.Texture2DArray.MostDetailedMip, 2u);
  EXPECT_EQ(srv2.Texture2DArray.MipLevels, 0u);
  EXPECT_EQ(srv2.Texture2DArray.ArraySize, 0u);

  DEPTH_STENCIL_VIEW_DESC dsv = {FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2D, 0};
  EXPECT_EQ(dsv.Format, FORMAT_D32_FLOAT);
  EXPECT_EQ(dsv.ViewDimension, DSV_DIMENSION_TEXTURE2D);
  EXPECT_EQ(dsv.Flags, 0u);
  EXPECT_EQ(dsv.Texture2D.MipSlice, 0u);
  DEPTH_STENCIL_VIEW_DESC dsv2 = {FORMAT_D24_UNORM_S8_UINT, DSV_DIMENSION_TEXTURE2DARRAY, DSV_READ_ONLY_DEPTH, 1};
  EXPECT_EQ(dsv2.Flags, uint32_t(DSV_READ_ONLY_DEPTH));
  EXPECT_EQ(dsv2.Texture2DArray.MipSlice, 1u);
  EXPECT_EQ(dsv2.Texture2DArray.ArraySize, 0u);

  RENDER_TARGET_VIEW_DESC rtv = {FORMAT_R8G8B8A8_UNORM, RTV_DIMENSION_TEXTURE2D};
  EXPECT_EQ(rtv.Texture2D.MipSlice, 0u);
  UNORDERED_ACCESS_VIEW_DESC uav = {FORMAT_UNKNOWN, UAV_DIMENSION_BUFFER, 0, 8};
  EXPECT_EQ(uav.Buffer.FirstElement, 0u);
  EXPECT_EQ(uav.Buffer.NumElements, 8u);
  EXPECT_EQ(uav.Buffer.Flags, 0u);

  // Default construction still means "unknown format and dimension, all zero" (the meaning
  // Create*View's callers rely on when they set only some union fields).
  SHADER_RESOURCE_VIEW_DESC def;
  def.ViewDimension = SRV_DIMENSION_TEXTURECUBEARRAY;
  EXPECT_EQ(def.Format, FORMAT_UNKNOWN);
  EXPECT_EQ(def.TextureCubeArray.MostDetailedMip, 0u);
  EXPECT_EQ(def.TextureCubeArray.MipLevels, 0u);
  EXPECT_EQ(def.TextureCubeArray.First2DArrayFace, 0u);
  EXPECT_EQ(def.TextureCubeArray.NumCubes, 0u);
  DEPTH_STENCIL_VIEW_DESC defDsv;
  EXPECT_EQ(defDsv.ViewDimension, DSV_DIMENSION_UNKNOWN);
  EXPECT_EQ(defDsv.Texture2DArray.ArraySize, 0u);
  UNORDERED_ACCESS_VIEW_DESC defUav;
  EXPECT_EQ(defUav.Texture3D.WSize, 0u);
  RENDER_TARGET_VIEW_DESC defRtv;
  EXPECT_EQ(defRtv.Texture2DArray.ArraySize, 0u);
}

// ---- constants and helpers against D3D11's documented values ---------------------------------

TEST(D3D11Helpers, ConstantsHaveD3D11Values) {
  EXPECT_EQ(FLOAT32_MAX, 3.402823466e+38f);
  EXPECT_EQ(FLOAT32_MAX, FLT_MAX);
  EXPECT_EQ(DEFAULT_DEPTH_BIAS, 0);
  EXPECT_EQ(DEFAULT_DEPTH_BIAS_CLAMP, 0.0f);
  EXPECT_EQ(DEFAULT_SLOPE_SCALED_DEPTH_BIAS, 0.0f);
  EXPECT_EQ(DEFAULT_SAMPLE_MASK, 0xffffffffu);
  EXPECT_EQ(DEFAULT_STENCIL_READ_MASK, 0xffu);
  EXPECT_EQ(DEFAULT_STENCIL_WRITE_MASK, 0xffu);
  EXPECT_EQ(DEFAULT_STENCIL_REFERENCE, 0u);
  EXPECT_EQ(DEFAULT_BLEND_FACTOR_RED, 1.0f);
  EXPECT_EQ(DEFAULT_BLEND_FACTOR_GREEN, 1.0f);
  EXPECT_EQ(DEFAULT_BLEND_FACTOR_BLUE, 1.0f);
  EXPECT_EQ(DEFAULT_BLEND_FACTOR_ALPHA, 1.0f);
  EXPECT_EQ(DEFAULT_BORDER_COLOR_COMPONENT, 0.0f);
  EXPECT_EQ(DEFAULT_MAX_ANISOTROPY, 16u);
  EXPECT_EQ(DEFAULT_MIP_LOD_BIAS, 0.0f);
  EXPECT_EQ(DEFAULT_RENDER_TARGET_ARRAY_INDEX, 0u);
  EXPECT_EQ(DEFAULT_VIEWPORT_AND_SCISSORRECT_INDEX, 0u);
  EXPECT_EQ(DEFAULT_VIEWPORT_TOPLEFTX + DEFAULT_VIEWPORT_TOPLEFTY + DEFAULT_VIEWPORT_WIDTH + DEFAULT_VIEWPORT_HEIGHT, 0u);
  EXPECT_EQ(DEFAULT_VIEWPORT_MIN_DEPTH, 0.0f);
  EXPECT_EQ(DEFAULT_VIEWPORT_MAX_DEPTH, 0.0f);
  EXPECT_EQ(DEFAULT_SCISSOR_STARTX + DEFAULT_SCISSOR_STARTY + DEFAULT_SCISSOR_ENDX + DEFAULT_SCISSOR_ENDY, 0u);
  EXPECT_EQ(MIN_DEPTH, 0.0f);
  EXPECT_EQ(MAX_DEPTH, 1.0f);
  EXPECT_EQ(COLOR_WRITE_ENABLE_ALL, 15);
  EXPECT_EQ(SIMULTANEOUS_RENDER_TARGET_COUNT, 8u);
  EXPECT_EQ(MAX_MAXANISOTROPY, 16u);
  EXPECT_EQ(CS_THREAD_GROUP_MAX_THREADS_PER_GROUP, 1024u);
  EXPECT_EQ(CS_THREAD_GROUP_MAX_Z, 64u);
}

TEST(D3D11Helpers, StateDefaultsAreD3D11s) {
  CRASTERIZER_DESC r(DEFAULT);
  EXPECT_EQ(r.FillMode, FILL_SOLID);
  EXPECT_EQ(r.CullMode, CULL_BACK);
  EXPECT_FALSE(r.FrontCounterClockwise);
  EXPECT_EQ(r.DepthBias, 0);
  EXPECT_EQ(r.DepthBiasClamp, 0.0f);
  EXPECT_EQ(r.SlopeScaledDepthBias, 0.0f);
  EXPECT_TRUE(r.DepthClipEnable);
  EXPECT_FALSE(r.ScissorEnable);
  EXPECT_FALSE(r.MultisampleEnable);
  EXPECT_FALSE(r.AntialiasedLineEnable);
  CRASTERIZER_DESC r2(FILL_WIREFRAME, CULL_NONE, true, 10, 0.5f, 2.0f, false, true, true, true);
  EXPECT_EQ(r2.FillMode, FILL_WIREFRAME);
  EXPECT_EQ(r2.CullMode, CULL_NONE);
  EXPECT_TRUE(r2.FrontCounterClockwise);
  EXPECT_EQ(r2.DepthBias, 10);
  EXPECT_EQ(r2.DepthBiasClamp, 0.5f);
  EXPECT_EQ(r2.SlopeScaledDepthBias, 2.0f);
  EXPECT_FALSE(r2.DepthClipEnable);
  EXPECT_TRUE(r2.ScissorEnable && r2.MultisampleEnable && r2.AntialiasedLineEnable);
  RASTERIZER_DESC base = r2;
  base.DepthBias = 3;
  EXPECT_EQ(CRASTERIZER_DESC(base).DepthBias, 3);

  CSAMPLER_DESC s(DEFAULT);
  EXPECT_EQ(s.Filter, FILTER_MIN_MAG_MIP_LINEAR);
  EXPECT_EQ(s.AddressU, TEXTURE_ADDRESS_CLAMP);
  EXPECT_EQ(s.AddressV, TEXTURE_ADDRESS_CLAMP);
  EXPECT_EQ(s.AddressW, TEXTURE_ADDRESS_CLAMP);
  EXPECT_EQ(s.MipLODBias, 0.0f);
  EXPECT_EQ(s.MaxAnisotropy, 1u);
  EXPECT_EQ(s.ComparisonFunc, COMPARISON_NEVER);
  for (float c : s.BorderColor) EXPECT_EQ(c, 1.0f);
  EXPECT_EQ(s.MinLOD, -FLT_MAX);
  EXPECT_EQ(s.MaxLOD, FLT_MAX);
  const float border[4] = {0.0f, 0.25f, 0.5f, 0.75f};
  CSAMPLER_DESC s2(FILTER_ANISOTROPIC, TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_MIRROR, TEXTURE_ADDRESS_BORDER, -1.0f, 8,
                   COMPARISON_GREATER, border, 2.0f, 5.0f);
  EXPECT_EQ(s2.Filter, FILTER_ANISOTROPIC);
  EXPECT_EQ(s2.AddressV, TEXTURE_ADDRESS_MIRROR);
  EXPECT_EQ(s2.AddressW, TEXTURE_ADDRESS_BORDER);
  EXPECT_EQ(s2.MipLODBias, -1.0f);
  EXPECT_EQ(s2.MaxAnisotropy, 8u);
  EXPECT_EQ(s2.ComparisonFunc, COMPARISON_GREATER);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(s2.BorderColor[i], border[i]);
  EXPECT_EQ(s2.MinLOD, 2.0f);
  EXPECT_EQ(s2.MaxLOD, 5.0f);
  CSAMPLER_DESC s3(FILTER_MIN_MAG_MIP_POINT, TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_WRAP, TEXTURE_ADDRESS_WRAP, 0, 1, COMPARISON_NEVER,
                   nullptr, 0, 0);
  for (float c : s3.BorderColor) EXPECT_EQ(c, 1.0f);  // null border: opaque white

  CDEPTH_STENCIL_DESC d(DEFAULT);
  EXPECT_TRUE(d.DepthEnable);
  EXPECT_EQ(d.DepthWriteMask, DEPTH_WRITE_MASK_ALL);
  EXPECT_EQ(d.DepthFunc, COMPARISON_LESS);
  EXPECT_FALSE(d.StencilEnable);
  EXPECT_EQ(d.StencilReadMask, 0xff);
  EXPECT_EQ(d.StencilWriteMask, 0xff);
  for (const DEPTH_STENCILOP_DESC* f : {&d.FrontFace, &d.BackFace}) {
    EXPECT_EQ(f->StencilFailOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f->StencilDepthFailOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f->StencilPassOp, STENCIL_OP_KEEP);
    EXPECT_EQ(f->StencilFunc, COMPARISON_ALWAYS);
  }
  CDEPTH_STENCIL_DESC d2(false, DEPTH_WRITE_MASK_ZERO, COMPARISON_GREATER_EQUAL, true, 0x3, 0xc, STENCIL_OP_ZERO, STENCIL_OP_REPLACE,
                         STENCIL_OP_INCR_SAT, COMPARISON_EQUAL, STENCIL_OP_DECR_SAT, STENCIL_OP_INVERT, STENCIL_OP_INCR, COMPARISON_LESS);
  EXPECT_FALSE(d2.DepthEnable);
  EXPECT_EQ(d2.DepthWriteMask, DEPTH_WRITE_MASK_ZERO);
  EXPECT_EQ(d2.DepthFunc, COMPARISON_GREATER_EQUAL);
  EXPECT_TRUE(d2.StencilEnable);
  EXPECT_EQ(d2.StencilReadMask, 0x3);
  EXPECT_EQ(d2.StencilWriteMask, 0xc);
  EXPECT_EQ(d2.FrontFace.StencilFailOp, STENCIL_OP_ZERO);
  EXPECT_EQ(d2.FrontFace.StencilDepthFailOp, STENCIL_OP_REPLACE);
  EXPECT_EQ(d2.FrontFace.StencilPassOp, STENCIL_OP_INCR_SAT);
  EXPECT_EQ(d2.FrontFace.StencilFunc, COMPARISON_EQUAL);
  EXPECT_EQ(d2.BackFace.StencilFailOp, STENCIL_OP_DECR_SAT);
  EXPECT_EQ(d2.BackFace.StencilDepthFailOp, STENCIL_OP_INVERT);
  EXPECT_EQ(d2.BackFace.StencilPassOp, STENCIL_OP_INCR);
  EXPECT_EQ(d2.BackFace.StencilFunc, COMPARISON_LESS);

  CBLEND_DESC b(DEFAULT);
  EXPECT_FALSE(b.AlphaToCoverageEnable);
  EXPECT_FALSE(b.IndependentBlendEnable);
  for (const RENDER_TARGET_BLEND_DESC& rt : b.RenderTarget) {
    EXPECT_FALSE(rt.BlendEnable);
    EXPECT_EQ(rt.SrcBlend, BLEND_ONE);
    EXPECT_EQ(rt.DestBlend, BLEND_ZERO);
    EXPECT_EQ(rt.BlendOp, BLEND_OP_ADD);
    EXPECT_EQ(rt.SrcBlendAlpha, BLEND_ONE);
    EXPECT_EQ(rt.DestBlendAlpha, BLEND_ZERO);
    EXPECT_EQ(rt.BlendOpAlpha, BLEND_OP_ADD);
    EXPECT_EQ(rt.RenderTargetWriteMask, COLOR_WRITE_ENABLE_ALL);
  }

  CQUERY_DESC q(QUERY_TIMESTAMP);
  EXPECT_EQ(q.Query, QUERY_TIMESTAMP);
  EXPECT_EQ(q.MiscFlags, 0u);
  CRECT rc(1, 2, 30, 40);
  EXPECT_EQ(rc.left, 1);
  EXPECT_EQ(rc.top, 2);
  EXPECT_EQ(rc.right, 30);
  EXPECT_EQ(rc.bottom, 40);
  CBOX box(1, 2, 3, 4, 5, 6);
  EXPECT_EQ(box.left, 1u);
  EXPECT_EQ(box.top, 2u);
  EXPECT_EQ(box.front, 3u);
  EXPECT_EQ(box.right, 4u);
  EXPECT_EQ(box.bottom, 5u);
  EXPECT_EQ(box.back, 6u);
  CVIEWPORT vp(10, 20, 300, 200);
  EXPECT_EQ(vp.TopLeftX, 10.0f);
  EXPECT_EQ(vp.TopLeftY, 20.0f);
  EXPECT_EQ(vp.Width, 300.0f);
  EXPECT_EQ(vp.Height, 200.0f);
  EXPECT_EQ(vp.MinDepth, 0.0f);  // D3D11_MIN_DEPTH
  EXPECT_EQ(vp.MaxDepth, 1.0f);  // D3D11_MAX_DEPTH
}

TEST(D3D11Helpers, ResourceDescDefaultsAreD3D11s) {
  CBUFFER_DESC b(256, BIND_CONSTANT_BUFFER);
  EXPECT_EQ(b.ByteWidth, 256u);
  EXPECT_EQ(b.BindFlags, uint32_t(BIND_CONSTANT_BUFFER));
  EXPECT_EQ(b.Usage, USAGE_DEFAULT);
  EXPECT_EQ(b.CPUAccessFlags, 0u);
  EXPECT_EQ(b.MiscFlags, 0u);
  EXPECT_EQ(b.StructureByteStride, 0u);
  CBUFFER_DESC b2(64, BIND_SHADER_RESOURCE, USAGE_DYNAMIC, CPU_ACCESS_WRITE, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  EXPECT_EQ(b2.Usage, USAGE_DYNAMIC);
  EXPECT_EQ(b2.CPUAccessFlags, uint32_t(CPU_ACCESS_WRITE));
  EXPECT_EQ(b2.MiscFlags, uint32_t(RESOURCE_MISC_BUFFER_STRUCTURED));
  EXPECT_EQ(b2.StructureByteStride, 16u);

  CTEXTURE1D_DESC t1(FORMAT_R8_UNORM, 64);
  EXPECT_EQ(t1.Width, 64u);
  EXPECT_EQ(t1.ArraySize, 1u);
  EXPECT_EQ(t1.MipLevels, 0u);  // full chain
  EXPECT_EQ(t1.BindFlags, uint32_t(BIND_SHADER_RESOURCE));
  EXPECT_EQ(t1.Usage, USAGE_DEFAULT);
  EXPECT_EQ(t1.CPUAccessFlags, 0u);
  EXPECT_EQ(t1.MiscFlags, 0u);

  CTEXTURE2D_DESC t2(FORMAT_R32_TYPELESS, 1024, 512);
  EXPECT_EQ(t2.Format, FORMAT_R32_TYPELESS);
  EXPECT_EQ(t2.Width, 1024u);
  EXPECT_EQ(t2.Height, 512u);
  EXPECT_EQ(t2.ArraySize, 1u);
  EXPECT_EQ(t2.MipLevels, 0u);
  EXPECT_EQ(t2.BindFlags, uint32_t(BIND_SHADER_RESOURCE));
  EXPECT_EQ(t2.Usage, USAGE_DEFAULT);
  EXPECT_EQ(t2.CPUAccessFlags, 0u);
  EXPECT_EQ(t2.SampleDesc.Count, 1u);
  EXPECT_EQ(t2.SampleDesc.Quality, 0u);
  EXPECT_EQ(t2.MiscFlags, 0u);
  CTEXTURE2D_DESC t2b(FORMAT_R8G8B8A8_UNORM, 8, 4, 6, 3, BIND_RENDER_TARGET, USAGE_DEFAULT, 0, 4, 1, RESOURCE_MISC_TEXTURECUBE);
  EXPECT_EQ(t2b.ArraySize, 6u);
  EXPECT_EQ(t2b.MipLevels, 3u);
  EXPECT_EQ(t2b.BindFlags, uint32_t(BIND_RENDER_TARGET));
  EXPECT_EQ(t2b.SampleDesc.Count, 4u);
  EXPECT_EQ(t2b.SampleDesc.Quality, 1u);
  EXPECT_EQ(t2b.MiscFlags, uint32_t(RESOURCE_MISC_TEXTURECUBE));

  CTEXTURE3D_DESC t3(FORMAT_R16_FLOAT, 8, 4, 2);
  EXPECT_EQ(t3.Depth, 2u);
  EXPECT_EQ(t3.MipLevels, 0u);
  EXPECT_EQ(t3.BindFlags, uint32_t(BIND_SHADER_RESOURCE));
  EXPECT_EQ(t3.Usage, USAGE_DEFAULT);
}

TEST(D3D11Helpers, ViewDescsFromADimensionUseD3D11sMeanings) {
  CSHADER_RESOURCE_VIEW_DESC s(SRV_DIMENSION_TEXTURE2D);
  EXPECT_EQ(s.Format, FORMAT_UNKNOWN);
  EXPECT_EQ(s.Texture2D.MostDetailedMip, 0u);
  EXPECT_EQ(s.Texture2D.MipLevels, uint32_t(-1));
  CSHADER_RESOURCE_VIEW_DESC sa(SRV_DIMENSION_TEXTURE2DARRAY, FORMAT_R32_FLOAT, 1, 2, 3, 4);
  EXPECT_EQ(sa.Format, FORMAT_R32_FLOAT);
  EXPECT_EQ(sa.Texture2DArray.MostDetailedMip, 1u);
  EXPECT_EQ(sa.Texture2DArray.MipLevels, 2u);
  EXPECT_EQ(sa.Texture2DArray.FirstArraySlice, 3u);
  EXPECT_EQ(sa.Texture2DArray.ArraySize, 4u);
  CSHADER_RESOURCE_VIEW_DESC sb(SRV_DIMENSION_BUFFER, FORMAT_R32_UINT, 5, 6);
  EXPECT_EQ(sb.Buffer.FirstElement, 5u);
  EXPECT_EQ(sb.Buffer.NumElements, 6u);
  CSHADER_RESOURCE_VIEW_DESC sc(SRV_DIMENSION_TEXTURECUBEARRAY, FORMAT_R8G8B8A8_UNORM, 0, 1, 6, 2);
  EXPECT_EQ(sc.TextureCubeArray.First2DArrayFace, 6u);
  EXPECT_EQ(sc.TextureCubeArray.NumCubes, 2u);
  CSHADER_RESOURCE_VIEW_DESC sx(SRV_DIMENSION_BUFFEREX, FORMAT_R32_TYPELESS, 2, 8, 0, 0, BUFFEREX_SRV_FLAG_RAW);
  EXPECT_EQ(sx.BufferEx.FirstElement, 2u);
  EXPECT_EQ(sx.BufferEx.NumElements, 8u);
  EXPECT_EQ(sx.BufferEx.Flags, uint32_t(BUFFEREX_SRV_FLAG_RAW));
  CSHADER_RESOURCE_VIEW_DESC sbuf(static_cast<Buffer*>(nullptr), FORMAT_R32_FLOAT, 4, 12);
  EXPECT_EQ(sbuf.ViewDimension, SRV_DIMENSION_BUFFEREX);
  EXPECT_EQ(sbuf.BufferEx.FirstElement, 4u);
  EXPECT_EQ(sbuf.BufferEx.NumElements, 12u);
  EXPECT_EQ(sbuf.BufferEx.Flags, 0u);

  CRENDER_TARGET_VIEW_DESC r(RTV_DIMENSION_TEXTURE2DARRAY, FORMAT_R8G8B8A8_UNORM, 1, 2);
  EXPECT_EQ(r.Texture2DArray.MipSlice, 1u);
  EXPECT_EQ(r.Texture2DArray.FirstArraySlice, 2u);
  EXPECT_EQ(r.Texture2DArray.ArraySize, uint32_t(-1));
  CRENDER_TARGET_VIEW_DESC r3(RTV_DIMENSION_TEXTURE3D, FORMAT_R8G8B8A8_UNORM, 1, 2, 3);
  EXPECT_EQ(r3.Texture3D.MipSlice, 1u);
  EXPECT_EQ(r3.Texture3D.FirstWSlice, 2u);
  EXPECT_EQ(r3.Texture3D.WSize, 3u);
  CRENDER_TARGET_VIEW_DESC rb(RTV_DIMENSION_BUFFER, FORMAT_R32_FLOAT, 7, 9);
  EXPECT_EQ(rb.Buffer.FirstElement, 7u);
  EXPECT_EQ(rb.Buffer.NumElements, 9u);

  CDEPTH_STENCIL_VIEW_DESC d(DSV_DIMENSION_TEXTURE2D, FORMAT_D32_FLOAT);
  EXPECT_EQ(d.Format, FORMAT_D32_FLOAT);
  EXPECT_EQ(d.Flags, 0u);
  EXPECT_EQ(d.Texture2D.MipSlice, 0u);
  CDEPTH_STENCIL_VIEW_DESC da(DSV_DIMENSION_TEXTURE2DARRAY, FORMAT_D16_UNORM, 1, 2, 3, DSV_READ_ONLY_DEPTH);
  EXPECT_EQ(da.Texture2DArray.MipSlice, 1u);
  EXPECT_EQ(da.Texture2DArray.FirstArraySlice, 2u);
  EXPECT_EQ(da.Texture2DArray.ArraySize, 3u);
  EXPECT_EQ(da.Flags, uint32_t(DSV_READ_ONLY_DEPTH));

  CUNORDERED_ACCESS_VIEW_DESC u(UAV_DIMENSION_BUFFER, FORMAT_UNKNOWN, 1, 16, 0, BUFFER_UAV_FLAG_APPEND);
  EXPECT_EQ(u.Buffer.FirstElement, 1u);
  EXPECT_EQ(u.Buffer.NumElements, 16u);
  EXPECT_EQ(u.Buffer.Flags, uint32_t(BUFFER_UAV_FLAG_APPEND));
  CUNORDERED_ACCESS_VIEW_DESC u3(UAV_DIMENSION_TEXTURE3D, FORMAT_R32_FLOAT, 1, 2);
  EXPECT_EQ(u3.Texture3D.MipSlice, 1u);
  EXPECT_EQ(u3.Texture3D.FirstWSlice, 2u);
  EXPECT_EQ(u3.Texture3D.WSize, uint32_t(-1));
}

// ---- on a device: the resource forms of the helpers, and D3D11-style set-up that draws ------

class D3D11HelpersTest : public BackendTest {};

TEST_P(D3D11HelpersTest, ViewDescsFromAResourceFillTheRestFromIt) {
  Ref<Texture2D> arr = device().CreateTexture2D(
      CTEXTURE2D_DESC(FORMAT_R8G8B8A8_UNORM, 16, 8, 3, 0, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET | BIND_UNORDERED_ACCESS));
  EXPECT_EQ(arr->GetDesc().MipLevels, 5u);  // 16x8: full chain
  CSHADER_RESOURCE_VIEW_DESC s(arr, SRV_DIMENSION_TEXTURE2DARRAY, FORMAT_UNKNOWN, 1, uint32_t(-1), 1);
  EXPECT_EQ(s.Format, FORMAT_R8G8B8A8_UNORM);
  EXPECT_EQ(s.Texture2DArray.MostDetailedMip, 1u);
  EXPECT_EQ(s.Texture2DArray.MipLevels, 4u);
  EXPECT_EQ(s.Texture2DArray.FirstArraySlice, 1u);
  EXPECT_EQ(s.Texture2DArray.ArraySize, 2u);
  EXPECT_NE(device().CreateShaderResourceView(arr.get(), &s), nullptr);
  CRENDER_TARGET_VIEW_DESC r(arr.get(), RTV_DIMENSION_TEXTURE2DARRAY, FORMAT_UNKNOWN, 1, 2);
  EXPECT_EQ(r.Format, FORMAT_R8G8B8A8_UNORM);
  EXPECT_EQ(r.Texture2DArray.ArraySize, 1u);
  Ref<RenderTargetView> rtv = device().CreateRenderTargetView(arr.get(), &r);
  CUNORDERED_ACCESS_VIEW_DESC u(arr, UAV_DIMENSION_TEXTURE2DARRAY);
  EXPECT_EQ(u.Texture2DArray.ArraySize, 3u);
  EXPECT_NE(device().CreateUnorderedAccessView(arr.get(), &u), nullptr);
  // The viewport of the RTV's mip level: 16x8 at mip 1 is 8x4.
  CVIEWPORT vp(arr, rtv, 2.0f, 1.0f);
  EXPECT_EQ(vp.TopLeftX, 2.0f);
  EXPECT_EQ(vp.TopLeftY, 1.0f);
  EXPECT_EQ(vp.Width, 6.0f);
  EXPECT_EQ(vp.Height, 3.0f);
  EXPECT_EQ(vp.MaxDepth, 1.0f);

  Ref<Texture2D> cubes = device().CreateTexture2D(
      CTEXTURE2D_DESC(FORMAT_R8G8B8A8_UNORM, 4, 4, 12, 1, BIND_SHADER_RESOURCE, USAGE_DEFAULT, 0, 1, 0, RESOURCE_MISC_TEXTURECUBE));
  CSHADER_RESOURCE_VIEW_DESC c(cubes, SRV_DIMENSION_TEXTURECUBEARRAY);
  EXPECT_EQ(c.TextureCubeArray.MipLevels, 1u);
  EXPECT_EQ(c.TextureCubeArray.NumCubes, 2u);  // 12 faces
  EXPECT_NE(device().CreateShaderResourceView(cubes.get(), &c), nullptr);

  Ref<Texture2D> depth = device().CreateTexture2D(CTEXTURE2D_DESC(FORMAT_R32_TYPELESS, 8, 8, 2, 1, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE));
  CDEPTH_STENCIL_VIEW_DESC d(depth, DSV_DIMENSION_TEXTURE2DARRAY, FORMAT_D32_FLOAT, 0, 1);
  EXPECT_EQ(d.Texture2DArray.ArraySize, 1u);
  EXPECT_NE(device().CreateDepthStencilView(depth.get(), &d), nullptr);

  Ref<Texture3D> vol = device().CreateTexture3D(CTEXTURE3D_DESC(FORMAT_R32_FLOAT, 8, 8, 4, 2, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET));
  CSHADER_RESOURCE_VIEW_DESC s3(vol);
  EXPECT_EQ(s3.ViewDimension, SRV_DIMENSION_TEXTURE3D);
  EXPECT_EQ(s3.Format, FORMAT_R32_FLOAT);
  EXPECT_EQ(s3.Texture3D.MipLevels, 2u);
  EXPECT_NE(device().CreateShaderResourceView(vol.get(), &s3), nullptr);
  CRENDER_TARGET_VIEW_DESC r3(vol, FORMAT_UNKNOWN, 0, 1);
  EXPECT_EQ(r3.Texture3D.FirstWSlice, 1u);
  EXPECT_EQ(r3.Texture3D.WSize, 3u);
  // OpenGL attaches one W slice or all of them (SP_NOT_SUPPORTED otherwise): create the last one.
  CRENDER_TARGET_VIEW_DESC r3last(vol, FORMAT_UNKNOWN, 0, 3);
  EXPECT_EQ(r3last.Texture3D.WSize, 1u);
  EXPECT_NE(device().CreateRenderTargetView(vol.get(), &r3last), nullptr);

  Ref<Buffer> buf = device().CreateBuffer(CBUFFER_DESC(64, BIND_SHADER_RESOURCE | BIND_UNORDERED_ACCESS));
  // Vulkan needs typed buffer views at 16-byte offsets (minTexelBufferOffsetAlignment on lavapipe).
  CSHADER_RESOURCE_VIEW_DESC sb(buf, FORMAT_R32_FLOAT, 4, 8);
  EXPECT_EQ(sb.BufferEx.FirstElement, 4u);
  EXPECT_EQ(sb.BufferEx.NumElements, 8u);
  EXPECT_NE(device().CreateShaderResourceView(buf.get(), &sb), nullptr);
  CUNORDERED_ACCESS_VIEW_DESC ub(buf, FORMAT_R32_UINT, 0, 16);
  EXPECT_NE(device().CreateUnorderedAccessView(buf.get(), &ub), nullptr);
}

// CascadedShadowMaps11's shadow-map set-up, written with D3D11's aggregate initialisers and
// field-by-field descs: a depth-only pass through an input layout into an R32_TYPELESS map, then
// a compute pass that reads it through the SRV with a comparison sampler.
TEST_P(D3D11HelpersTest, D3D11StyleSetUpRendersAShadowMap) {
  const char* vs = R"(
struct VSIn { float3 pos : POSITION; float2 uv : TEXCOORD0; };
float4 main(VSIn i) : SV_Position { return float4(i.pos.xy, i.pos.z + i.uv.x * 0.0, 1); }
)";
  const char* cs = R"(
cbuffer Refs : register(b0) { float lower; float higher; };
Texture2D<float> shadowMap : register(t0);
SamplerComparisonState shadowSampler : register(s0);
RWStructuredBuffer<float4> result : register(u0);
[numthreads(1, 1, 1)] void main() {
  float2 uv = float2(0.5, 0.5);
  result[0] = float4(shadowMap.Load(int3(4, 4, 0)), shadowMap.SampleCmpLevelZero(shadowSampler, uv, lower),
                     shadowMap.SampleCmpLevelZero(shadowSampler, uv, higher), 1);
}
)";
  const uint32_t size = 8;
  TEXTURE2D_DESC dtd = {size, size, 1, 1, FORMAT_R32_TYPELESS, 1, 0, USAGE_DEFAULT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, 0, 0};
  Ref<Texture2D> shadowMap = device().CreateTexture2D(dtd);
  DEPTH_STENCIL_VIEW_DESC dsvd = {FORMAT_D32_FLOAT, DSV_DIMENSION_TEXTURE2D, 0};
  Ref<DepthStencilView> dsv = device().CreateDepthStencilView(shadowMap.get(), &dsvd);
  SHADER_RESOURCE_VIEW_DESC srvd = {FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2D, 0, 1};
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(shadowMap.get(), &srvd);

  ShaderBytecode vsCode = CompileHlsl(vs, "vs_4_0", "main");
  Ref<VertexShader> vsObj = device().CreateVertexShader(vsCode);
  INPUT_ELEMENT_DESC layout[] = {
      {"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"TEXCOORD", 0, FORMAT_R32G32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
  };
  Ref<InputLayout> il = device().CreateInputLayout(layout, 2, vsCode);
  // A full-viewport quad at depth 0.5 (two triangles).
  const float verts[] = {-1, -1, 0.5f, 0, 0, -1, 1, 0.5f, 0, 0, 1, -1, 0.5f, 0, 0,
                         1, -1, 0.5f, 0, 0, -1, 1, 0.5f, 0, 0, 1, 1, 0.5f, 0, 0};
  BUFFER_DESC bd;
  bd.ByteWidth = sizeof verts;
  bd.Usage = USAGE_IMMUTABLE;
  bd.BindFlags = BIND_VERTEX_BUFFER;
  bd.CPUAccessFlags = 0;
  bd.MiscFlags = 0;
  SUBRESOURCE_DATA init = {verts, 0, 0};
  Ref<Buffer> vb = device().CreateBuffer(bd, &init);

  CRASTERIZER_DESC rs(DEFAULT);
  rs.CullMode = CULL_NONE;
  Ref<RasterizerState> rsObj = device().CreateRasterizerState(rs);
  Ref<DepthStencilState> dsObj = device().CreateDepthStencilState(CDEPTH_STENCIL_DESC(DEFAULT));
  CVIEWPORT vp(0.0f, 0.0f, float(size), float(size));

  ctx().ClearDepthStencilView(dsv.get(), CLEAR_DEPTH, 1.0f, 0);
  ctx().OMSetRenderTargets(0, nullptr, dsv.get());
  ctx().OMSetDepthStencilState(dsObj.get(), DEFAULT_STENCIL_REFERENCE);
  ctx().RSSetState(rsObj.get());
  ctx().RSSetViewports(1, &vp);
  ctx().IASetInputLayout(il.get());
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  Buffer* vbs[] = {vb.get()};
  const uint32_t strides[] = {20}, offsets[] = {0};
  ctx().IASetVertexBuffers(0, 1, vbs, strides, offsets);
  ctx().VSSetShader(vsObj.get());
  ctx().PSSetShader(nullptr);
  ctx().Draw(6, 0);
  ctx().OMSetRenderTargets(0, nullptr, nullptr);

  // The sample's comparison sampler, set field by field.
  SAMPLER_DESC sd;
  sd.Filter = FILTER_COMPARISON_MIN_MAG_MIP_POINT;
  sd.AddressU = sd.AddressV = sd.AddressW = TEXTURE_ADDRESS_BORDER;
  sd.MipLODBias = 0.0f;
  sd.MaxAnisotropy = 0;
  sd.ComparisonFunc = COMPARISON_LESS_EQUAL;
  sd.BorderColor[0] = sd.BorderColor[1] = sd.BorderColor[2] = sd.BorderColor[3] = 0.0f;
  sd.MinLOD = 0.0f;
  sd.MaxLOD = FLOAT32_MAX;
  Ref<SamplerState> smp = device().CreateSamplerState(sd);
  BUFFER_DESC cbd;
  cbd.ByteWidth = 16;
  cbd.Usage = USAGE_DYNAMIC;
  cbd.BindFlags = BIND_CONSTANT_BUFFER;
  cbd.CPUAccessFlags = CPU_ACCESS_WRITE;
  cbd.MiscFlags = 0;
  Ref<Buffer> cb = device().CreateBuffer(cbd);
  MAPPED_SUBRESOURCE mapped;
  ASSERT_TRUE(ctx().Map(cb.get(), 0, MAP_WRITE_DISCARD, 0, &mapped));
  const float refs[4] = {0.25f, 0.75f, 0, 0};
  std::memcpy(mapped.pData, refs, sizeof refs);
  ctx().Unmap(cb.get(), 0);

  Ref<Buffer> out = device().CreateBuffer(CBUFFER_DESC(16, BIND_UNORDERED_ACCESS, USAGE_DEFAULT, 0, RESOURCE_MISC_BUFFER_STRUCTURED, 16));
  CUNORDERED_ACCESS_VIEW_DESC uavd(out, FORMAT_UNKNOWN, 0, 1);
  Ref<UnorderedAccessView> uav = device().CreateUnorderedAccessView(out.get(), &uavd);
  Ref<ComputeShader> csObj = device().CreateComputeShader(CompileHlsl(cs, "cs_4_0", "main"));
  ctx().CSSetShader(csObj.get());
  ctx().CSSetConstantBuffers(0, {cb.get()});
  ctx().CSSetShaderResources(0, {srv.get()});
  ctx().CSSetSamplers(0, {smp.get()});
  ctx().CSSetUnorderedAccessViews(0, {uav.get()});
  ctx().Dispatch(1, 1, 1);
  ctx().CSSetUnorderedAccessViews(0, {nullptr});
  std::vector<float> got = ReadBufferAs<float>(device(), ctx(), out.get());
  // D3D11: the stored depth is 0.5; SampleCmp returns (reference <= texel) per D3D's rule.
  EXPECT_EQ(got, (std::vector<float>{0.5f, 0.25f <= 0.5f ? 1.0f : 0.0f, 0.75f <= 0.5f ? 1.0f : 0.0f, 1.0f}));
}

SP_INSTANTIATE_BACKEND_TESTS(D3D11HelpersTest);

}  // namespace
}  // namespace sp::test
