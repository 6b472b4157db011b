// FX11 effect files (sp/fx/effect.h): the descs read from the blocks (D3D11's defaults plus the
// fields set), errors at the user's file:line, the effect-blocks rewrite that lets glslang
// compile the shader code of an .fx, and passes applied and drawn on both backends.
#include <sp/fx/effect.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "../rhi/rhi-test-util.h"

namespace sp::test {
namespace {

namespace fs = std::filesystem;

// tests/hlsl/data/fx in the source tree (SHADOWPORT_SHADER_DIR is <source>/shaders-hlsl).
fs::path FxDir() { return fs::path(SHADOWPORT_SHADER_DIR).parent_path() / "tests" / "hlsl" / "data" / "fx"; }

fx::EffectOptions Options() {
  fx::EffectOptions o;
  o.cacheDir = TestShaderCacheDir();
  return o;
}

std::string ReadFileText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// Field by field: the descs have padding after their bools.
bool Same(const DEPTH_STENCILOP_DESC& a, const DEPTH_STENCILOP_DESC& b) {
  return a.StencilFailOp == b.StencilFailOp && a.StencilDepthFailOp == b.StencilDepthFailOp && a.StencilPassOp == b.StencilPassOp &&
         a.StencilFunc == b.StencilFunc;
}
bool Same(const DEPTH_STENCIL_DESC& a, const DEPTH_STENCIL_DESC& b) {
  return a.DepthEnable == b.DepthEnable && a.DepthWriteMask == b.DepthWriteMask && a.DepthFunc == b.DepthFunc &&
         a.StencilEnable == b.StencilEnable && a.StencilReadMask == b.StencilReadMask && a.StencilWriteMask == b.StencilWriteMask &&
         Same(a.FrontFace, b.FrontFace) && Same(a.BackFace, b.BackFace);
}
bool Same(const BLEND_DESC& a, const BLEND_DESC& b) {
  if (a.AlphaToCoverageEnable != b.AlphaToCoverageEnable || a.IndependentBlendEnable != b.IndependentBlendEnable) return false;
  for (uint32_t i = 0; i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i) {
    const RENDER_TARGET_BLEND_DESC &x = a.RenderTarget[i], &y = b.RenderTarget[i];
    if (x.BlendEnable != y.BlendEnable || x.SrcBlend != y.SrcBlend || x.DestBlend != y.DestBlend || x.BlendOp != y.BlendOp ||
        x.SrcBlendAlpha != y.SrcBlendAlpha || x.DestBlendAlpha != y.DestBlendAlpha || x.BlendOpAlpha != y.BlendOpAlpha ||
        x.RenderTargetWriteMask != y.RenderTargetWriteMask)
      return false;
  }
  return true;
}
bool Same(const SAMPLER_DESC& a, const SAMPLER_DESC& b) {  // no padding: all 4-byte fields
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool StartsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// The diagnostic of a failing LoadFromSource, as "file:line: message".
std::string LoadError(const std::string& source) {
  try {
    fx::Effect::LoadFromSource(source, "inline.fx", Options());
  } catch (const hlsl::CompileError& e) {
    if (e.diagnostics().empty()) return e.what();
    const hlsl::Diagnostic& d = e.diagnostics()[0];
    return d.file + ":" + std::to_string(d.line) + ": " + d.message;
  }
  return "(no error)";
}

TEST(EffectParse, StatesAreD3D11DefaultsPlusTheFieldsSet) {
  fx::EffectOptions opt = Options();
  opt.defines = {{"SCALE", "2"}};
  auto effect = fx::Effect::Load(FxDir() / "states.fx", opt);

  const fx::StateObjectDesc* rs = effect->FindState("rsWire");
  ASSERT_TRUE(rs);
  EXPECT_EQ(rs->type, fx::StateType::Rasterizer);
  RASTERIZER_DESC r;
  r.FillMode = FILL_WIREFRAME;
  r.CullMode = CULL_NONE;
  r.FrontCounterClockwise = true;
  r.DepthBias = -5;
  r.DepthBiasClamp = 0.25f;
  r.SlopeScaledDepthBias = 2.0f;
  r.DepthClipEnable = false;
  r.ScissorEnable = true;
  r.MultisampleEnable = true;
  r.AntialiasedLineEnable = true;
  EXPECT_EQ(rs->rasterizer.FillMode, r.FillMode);
  EXPECT_EQ(rs->rasterizer.CullMode, r.CullMode);
  EXPECT_EQ(rs->rasterizer.FrontCounterClockwise, r.FrontCounterClockwise);
  EXPECT_EQ(rs->rasterizer.DepthBias, r.DepthBias);
  EXPECT_EQ(rs->rasterizer.DepthBiasClamp, r.DepthBiasClamp);
  EXPECT_EQ(rs->rasterizer.SlopeScaledDepthBias, r.SlopeScaledDepthBias);
  EXPECT_EQ(rs->rasterizer.DepthClipEnable, r.DepthClipEnable);
  EXPECT_EQ(rs->rasterizer.ScissorEnable, r.ScissorEnable);
  EXPECT_EQ(rs->rasterizer.MultisampleEnable, r.MultisampleEnable);
  EXPECT_EQ(rs->rasterizer.AntialiasedLineEnable, r.AntialiasedLineEnable);
  EXPECT_EQ(rs->setFields.size(), 10u);
  EXPECT_EQ(rs->setFields[0], "FillMode = WIREFRAME");
  EXPECT_EQ(rs->location.line, 19);

  const fx::StateObjectDesc* ds = effect->FindState("dsStencil");
  ASSERT_TRUE(ds);
  DEPTH_STENCIL_DESC d;
  d.DepthFunc = COMPARISON_GREATER_EQUAL;
  d.StencilEnable = true;
  d.StencilReadMask = 0x0F;
  d.StencilWriteMask = 0xF0;
  d.FrontFace = {STENCIL_OP_KEEP, STENCIL_OP_INCR_SAT, STENCIL_OP_REPLACE, COMPARISON_EQUAL};
  d.BackFace = {STENCIL_OP_ZERO, STENCIL_OP_DECR, STENCIL_OP_INVERT, COMPARISON_NOT_EQUAL};
  EXPECT_TRUE(Same(ds->depthStencil, d));

  const fx::StateObjectDesc* bs = effect->FindState("bsAlpha");
  ASSERT_TRUE(bs);
  // Unindexed render-target fields set every target; BlendEnable[0] and the write mask [0] only
  // the first, so the targets differ and blending is independent.
  BLEND_DESC b;
  for (RENDER_TARGET_BLEND_DESC& rt : b.RenderTarget) {
    rt.SrcBlend = BLEND_SRC_ALPHA;
    rt.DestBlend = BLEND_INV_SRC_ALPHA;
    rt.BlendOp = BLEND_OP_REV_SUBTRACT;
    rt.SrcBlendAlpha = BLEND_ZERO;
    rt.DestBlendAlpha = BLEND_INV_DEST_ALPHA;
    rt.BlendOpAlpha = BLEND_OP_MAX;
  }
  b.RenderTarget[0].BlendEnable = true;
  b.RenderTarget[0].RenderTargetWriteMask = 0x07;
  b.IndependentBlendEnable = true;
  EXPECT_TRUE(Same(bs->blend, b));

  const fx::StateObjectDesc* bsDefault = effect->FindState("bsDefault");
  ASSERT_TRUE(bsDefault);
  BLEND_DESC defaults;
  EXPECT_TRUE(Same(bsDefault->blend, defaults));
  EXPECT_TRUE(bsDefault->setFields.empty());

  const fx::StateObjectDesc* shadow = effect->FindState("samShadow");
  ASSERT_TRUE(shadow);
  EXPECT_EQ(shadow->type, fx::StateType::SamplerComparison);
  SAMPLER_DESC s;
  s.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  s.AddressU = s.AddressV = TEXTURE_ADDRESS_BORDER;
  s.AddressW = TEXTURE_ADDRESS_CLAMP;
  s.ComparisonFunc = COMPARISON_LESS_EQUAL;
  s.BorderColor[0] = 1, s.BorderColor[1] = 0.5f, s.BorderColor[2] = 0.25f, s.BorderColor[3] = 0;
  s.MaxAnisotropy = 4;
  s.MipLODBias = -1.5f;
  s.MinLOD = 0;
  s.MaxLOD = 3;
  EXPECT_TRUE(Same(shadow->sampler, s));

  // From the included file, at its own line.
  const fx::StateObjectDesc* lin = effect->FindState("samLinear");
  ASSERT_TRUE(lin);
  EXPECT_EQ(lin->sampler.Filter, FILTER_ANISOTROPIC);
  EXPECT_EQ(lin->sampler.AddressU, TEXTURE_ADDRESS_MIRROR_ONCE);
  EXPECT_EQ(lin->sampler.AddressV, TEXTURE_ADDRESS_MIRROR);
  EXPECT_EQ(lin->sampler.AddressW, TEXTURE_ADDRESS_CLAMP);
  EXPECT_NE(lin->location.file.find("states-common.fxh"), std::string::npos) << lin->location.file;
  EXPECT_EQ(lin->location.line, 6);
  ASSERT_TRUE(effect->FindState("samDefault"));
  SAMPLER_DESC sd;
  EXPECT_TRUE(Same(effect->FindState("samDefault")->sampler, sd));
}

TEST(EffectParse, TechniquesPassesAndShaders) {
  auto effect = fx::Effect::Load(FxDir() / "states.fx", Options());
  ASSERT_EQ(effect->GetTechniqueCount(), 3u);
  fx::EffectTechnique* lit = effect->GetTechniqueByName("Lit");
  EXPECT_EQ(lit->Group(), "Lighting");
  ASSERT_EQ(lit->GetPassCount(), 2u);
  const fx::PassDesc& p0 = lit->GetPassByName("P0")->GetDesc();
  ASSERT_TRUE(p0.shaders[0] && p0.shaders[1]);
  EXPECT_FALSE(p0.shaders[2] || p0.shaders[3]);
  EXPECT_EQ(p0.shaders[0]->variable, "vsMain");
  EXPECT_EQ(p0.shaders[0]->target, "vs_4_0");
  EXPECT_EQ(p0.shaders[0]->entryPoint, "VS");
  EXPECT_FALSE(p0.shaders[0]->bytecode.empty());
  EXPECT_EQ(p0.shaders[1]->function, "PS");
  EXPECT_EQ(p0.shaders[1]->arguments, (std::vector<std::string>{"true", "2.0"}));
  EXPECT_NE(p0.shaders[1]->entryPoint, "PS");  // a generated wrapper passes the uniforms
  EXPECT_EQ(p0.shaders[1]->bytecode.stage, ShaderStage::Pixel);
  EXPECT_EQ(p0.rasterizerState, "rsWire");
  EXPECT_EQ(p0.depthStencilState, "dsStencil");
  EXPECT_EQ(p0.stencilRef, 0x80u);
  EXPECT_EQ(p0.blendState, "bsAlpha");
  EXPECT_EQ(p0.blendFactor, (std::array<float, 4>{0.5f, 0.25f, 1, 0}));
  EXPECT_EQ(p0.sampleMask, 0xFu);
  // samLinear at the register glslang gave it in the pixel shader (s0: the first free one).
  ASSERT_EQ(p0.samplers.size(), 1u);
  EXPECT_EQ(p0.samplers[0].sampler, "samLinear");
  EXPECT_EQ(p0.samplers[0].stage, ShaderStage::Pixel);
  EXPECT_EQ(p0.samplers[0].slot, 0u);
  const fx::PassDesc& shadowPass = effect->GetTechniqueByName("Shadow")->GetPassByIndex(0)->GetDesc();
  ASSERT_EQ(shadowPass.samplers.size(), 1u);
  EXPECT_EQ(shadowPass.samplers[0].sampler, "samShadow");
  EXPECT_EQ(shadowPass.samplers[0].slot, 2u);  // register(s2)
  const fx::PassDesc& p1 = lit->GetPassByIndex(1)->GetDesc();
  ASSERT_TRUE(p1.shaders[1]);
  EXPECT_TRUE(p1.shaders[1]->isNull);
  EXPECT_FALSE(p1.shaders[0]);
  EXPECT_FALSE(p1.rasterizerState);

  fx::EffectTechnique* shadow = effect->GetTechniqueByIndex(1);
  EXPECT_EQ(shadow->Name(), "Shadow");
  EXPECT_EQ(shadow->Location().line, 98);
  EXPECT_EQ(shadow->GetPassByIndex(0)->GetDesc().shaders[1]->target, "ps_4_0");
  const fx::PassDesc& cs = effect->GetTechniqueByName("Compute")->GetPassByName("Main")->GetDesc();
  ASSERT_TRUE(cs.shaders[3]);
  EXPECT_EQ(cs.shaders[3]->bytecode.reflection.threadGroupSize[0], 8u);

  try {
    effect->GetTechniqueByName("Missing");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no technique 'Missing' (the effect has: Lit, Shadow, Compute)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("states.fx"), std::string::npos) << e.what();
  }
  EXPECT_THROW(lit->GetPassByName("P9"), Error);
  EXPECT_THROW(lit->GetPassByIndex(2), Error);
  EXPECT_EQ(effect->FindTechnique("Missing"), nullptr);
}

// Several samplers in one declaration, and shader code that only looks like effect syntax.
TEST(EffectParse, SamplerDeclaratorListsAndLookalikes) {
  auto e = fx::Effect::LoadFromSource(
      "SamplerState a : register(s0) { Filter = MIN_MAG_MIP_POINT; }, b : register(s1);\n"
      "SamplerState Pick(bool x) { return a; }\n"
      "struct S { BlendState notOurs; };\n",
      "inline.fx", Options());
  ASSERT_EQ(e->States().size(), 2u);
  ASSERT_TRUE(e->FindState("a") && e->FindState("b"));
  EXPECT_EQ(e->FindState("a")->sampler.Filter, FILTER_MIN_MAG_MIP_POINT);
  EXPECT_EQ(e->FindState("b")->sampler.Filter, FILTER_MIN_MAG_MIP_LINEAR);
  EXPECT_EQ(e->GetTechniqueCount(), 0u);
}

// The shader code of an effect compiles as any HLSL file: the blocks are hidden, sampler states
// keep their declaration, and lines stay where they were.
TEST(EffectParse, ShaderCodeOfAnEffectCompilesWithTheBlocksHidden) {
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.entryPoint = "PSWrap";
  o.cacheDir = TestShaderCacheDir();
  ShaderBytecode b = hlsl::CompileFile(FxDir() / "two-techniques.fx", o);
  const ShaderResourceBinding* sam = b.reflection.FindResource(RegisterClass::Sampler, 0);
  ASSERT_TRUE(sam);
  EXPECT_EQ(sam->name, "samWrap");
  std::vector<std::string> applied;
  std::string text = hlsl::Preprocess(ReadFileText(FxDir() / "two-techniques.fx"), (FxDir() / "two-techniques.fx").string(), {}, &applied);
  // PS's `uniform bool` parameter (given by CompileShader's argument) is not the entry's here.
  EXPECT_EQ(applied, (std::vector<std::string>{"effect-blocks", "uniform-parameter"}));
  EXPECT_EQ(text.find("technique11"), std::string::npos);
  EXPECT_EQ(text.find("CullMode"), std::string::npos);
  EXPECT_NE(text.find("SamplerState samWrap : register(s0)"), std::string::npos) << text;
  // An error in the shader code still names its line in the .fx.
  std::string bad = "technique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }\n"
                    "float4 PS() : SV_Target { return undeclared; }\n";
  try {
    hlsl::CompileSource(bad, "inline.fx", o);
    FAIL() << "no error";
  } catch (const hlsl::CompileError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_EQ(e.diagnostics()[0].line, 2) << e.what();
  }
}

TEST(EffectParse, IncludeInsideAPassKeepsLineNumbers) {
  fx::EffectOptions opt = Options();
  opt.failOnCompileError = false;  // PSBroken fails every compile of the file
  auto effect = fx::Effect::Load(FxDir() / "include-in-pass.fx", opt);
  const fx::PassDesc& p = effect->GetTechniqueByIndex(0)->GetPassByIndex(0)->GetDesc();
  ASSERT_TRUE(p.shaders[1]);
  EXPECT_NE(p.shaders[1]->error.find("include-in-pass.fx:10: error: 'undeclared'"), std::string::npos) << p.shaders[1]->error;
  EXPECT_EQ(p.shaders[1]->function, "PS");
  EXPECT_NE(p.shaders[1]->location.file.find("pass-body.fxh"), std::string::npos) << p.shaders[1]->location.file;
  EXPECT_EQ(p.shaders[1]->location.line, 2);
  EXPECT_EQ(p.rasterizerState, "");
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.entryPoint = "PSBroken";
  o.useCache = false;
  try {
    hlsl::CompileFile(FxDir() / "include-in-pass.fx", o);
    FAIL() << "no error";
  } catch (const hlsl::CompileError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_EQ(e.diagnostics()[0].line, 10) << e.what();
  }
}

TEST(EffectParse, ErrorsNameFileAndLine) {
  EXPECT_EQ(LoadError("\nRasterizerState rs {\n  CullMode = SIDEWAYS;\n};\n"),
            "inline.fx:3: unknown value 'SIDEWAYS' for effect state field 'CullMode' (valid: NONE, FRONT, BACK, or a number)");
  EXPECT_PRED2(StartsWith, LoadError("BlendState bs {\n  Colour = 1;\n};\n"), "inline.fx:2: unknown field 'Colour' in BlendState");
  EXPECT_EQ(LoadError("float4 PS() : SV_Target { return 1; }\ntechnique11 T {\n pass P {\n  SetPixelShader(CompileShader(ps_5_0, PS()));\n"
                      "  SetRasterizerState(rsMissing);\n }\n}\n"),
            "inline.fx:5: unknown RasterizerState 'rsMissing' (declare it before the technique)");
  EXPECT_PRED2(StartsWith, LoadError("technique11 T {\n pass P {\n  SetPixelShader(CompileShader(ps_3_0, PS()));\n }\n}\n"),
            "inline.fx:3: CompileShader: unknown target 'ps_3_0'");
  EXPECT_EQ(LoadError("technique11 T {\n pass P {\n  SetVertexShader(CompileShader(ps_5_0, PS()));\n }\n}\n"),
            "inline.fx:3: CompileShader: target ps_5_0 is not a VertexShader target");
  EXPECT_EQ(LoadError("technique11 T {\n pass P {\n  SetPixelShader(CompileShader(ps_5_0, Missing(1)));\n }\n}\n"),
            "inline.fx:3: CompileShader: no function 'Missing' is defined");
  EXPECT_EQ(LoadError("float4 PS(uniform float a) : SV_Target { return a; }\ntechnique11 T {\n pass P {\n"
                      "  SetPixelShader(CompileShader(ps_5_0, PS(1, 2)));\n }\n}\n"),
            "inline.fx:4: CompileShader: PS has 1 uniform parameter, given 2 arguments");
  EXPECT_PRED2(StartsWith, LoadError("technique11 T {\n pass P {\n  VertexShader = compile vs_2_0 VS();\n }\n}\n"),
            "inline.fx:3: 'VertexShader = ...' in a pass is Direct3D 9 effect syntax");
  EXPECT_PRED2(StartsWith, LoadError("technique11 T {\n pass P {\n  SetStreamOutput(x);\n }\n}\n"),
            "inline.fx:3: unknown pass statement 'SetStreamOutput' ");
  EXPECT_PRED2(StartsWith, LoadError("SamplerState s {\n  Texture = <g_tex>;\n};\n"), "inline.fx:2: 'Texture' in a sampler state is Direct3D 9 effect syntax");
  // A shader that does not compile fails Load with glslang's message at the user's line.
  EXPECT_PRED2(StartsWith, LoadError("float4 PS() : SV_Target {\n  return undeclared;\n}\ntechnique11 T { pass P { SetPixelShader(CompileShader(ps_5_0, PS())); } }\n")
                ,
            "inline.fx:2:");
  // The same errors come from the compatibility pass when the .fx is compiled as a shader.
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.entryPoint = "PS";
  o.useCache = false;
  try {
    hlsl::CompileSource("float4 PS() : SV_Target { return 1; }\nRasterizerState rs {\n  FillMode = DOTTED;\n};\n", "inline.fx", o);
    FAIL() << "no error";
  } catch (const hlsl::CompileError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_EQ(e.diagnostics()[0].line, 3) << e.what();
  }
}

// Two techniques drawn into an 8x8 float target through Pass::Apply, compared with D3D11's rules
// computed here: "Add" blends ONE + ONE (twice over a clear colour); "CullWrap" culls front
// (clockwise) faces and samples a 4x4 texture with a point, wrapping sampler at uv = pixel / 4.
class EffectDrawTest : public BackendTest {};

TEST_P(EffectDrawTest, PassesApplyShadersStatesAndSamplers) {
  const uint32_t W = 8, H = 8;
  auto effect = fx::Effect::Load(FxDir() / "two-techniques.fx", Options());
  effect->CreateObjects(device());
  Target t = MakeTarget(device(), W, H, FORMAT_R32G32B32A32_FLOAT);
  RenderTargetView* rtvs[] = {t.rtv.get()};
  ctx().OMSetRenderTargets(1, rtvs, nullptr);
  SetViewport(ctx(), W, H);
  ctx().IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);

  // --- Add: dst = clear + 2 * color * 0.5 (PSColor's uniform scale).
  const float clear[4] = {0.125f, 0.25f, 0.375f, 0.0625f};
  const float color[4] = {0.25f, 0.5f, 0.0625f, 0.5f};
  Ref<Buffer> cb = MakeBuffer(device(), BIND_CONSTANT_BUFFER, color, 16);
  ctx().PSSetConstantBuffers(0, {cb.get()});
  ctx().ClearRenderTargetView(t.rtv.get(), clear);
  effect->GetTechniqueByName("Add")->GetPassByIndex(0)->Apply(ctx());
  ctx().Draw(3, 0);
  ctx().Draw(3, 0);
  std::vector<float> px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < W * H; ++i)
    for (int c = 0; c < 4; ++c) {
      float expect = clear[c] * 1 + color[c] * 0.5f;  // first draw: src * ONE + dst * ONE
      expect = expect * 1 + color[c] * 0.5f;           // second draw
      ASSERT_NEAR(px[i * 4 + c], expect, 1e-6) << "pixel " << i << " channel " << c;
    }

  // --- CullWrap.
  uint8_t texels[4 * 4 * 4];
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      uint8_t* p = texels + (y * 4 + x) * 4;
      p[0] = uint8_t(x * 64 + 17), p[1] = uint8_t(y * 64 + 5), p[2] = uint8_t(x * 16 + y), p[3] = 255;
    }
  Ref<Texture2D> tex = MakeTexture2D(device(), 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, texels);
  Ref<ShaderResourceView> srv = device().CreateShaderResourceView(tex.get());
  ctx().PSSetShaderResources(0, {srv.get()});
  const float zero[4] = {0, 0, 0, 0};
  ctx().ClearRenderTargetView(t.rtv.get(), zero);
  fx::EffectTechnique* cw = effect->GetTechniqueByName("CullWrap");
  // Front: the clockwise triangle is a front face, culled; the blend state goes back to the default.
  cw->GetPassByName("Front")->Apply(ctx());
  ctx().Draw(3, 0);
  px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t i = 0; i < W * H * 4; ++i) ASSERT_EQ(px[i], 0.0f) << "front face drawn at " << i / 4;
  // Back: the counter-clockwise triangle through the vsBack shader variable is drawn.
  cw->GetPassByName("Back")->Apply(ctx());
  ctx().Draw(3, 0);
  px = ReadTextureAs<float>(device(), ctx(), t.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const uint8_t* texel = texels + ((y % 4) * 4 + (x % 4)) * 4;
      for (int c = 0; c < 4; ++c)
        ASSERT_NEAR(px[(y * W + x) * 4 + c], texel[c] / 255.0f, 1e-6) << "pixel " << x << "," << y << " channel " << c;
    }
  EXPECT_TRUE(validationMessages.empty());
}

// What Apply binds and leaves, read back through the context's Get calls: NULL unbinds, states a
// pass does not name stay, the stencil reference, blend factor and sample mask go with their state.
TEST_P(EffectDrawTest, ApplyBindsWhatThePassNamesAndLeavesTheRest) {
  auto effect = fx::Effect::Load(FxDir() / "states.fx", Options());
  fx::EffectTechnique* lit = effect->GetTechniqueByName("Lit");
  EXPECT_THROW(lit->GetPassByIndex(0)->Apply(ctx()), Error);  // no objects yet
  effect->CreateObjects(device());
  lit->GetPassByIndex(0)->Apply(ctx());
  Ref<PixelShader> ps;
  Ref<RasterizerState> rs;
  Ref<DepthStencilState> ds;
  Ref<BlendState> bs;
  Ref<SamplerState> sam;
  uint32_t ref = 0, mask = 0;
  float factor[4] = {};
  ctx().PSGetShader(&ps);
  EXPECT_TRUE(ps);
  ctx().RSGetState(&rs);
  ASSERT_TRUE(rs);
  EXPECT_EQ(rs->GetDesc().FillMode, FILL_WIREFRAME);
  ctx().OMGetDepthStencilState(&ds, &ref);
  ASSERT_TRUE(ds);
  EXPECT_EQ(ds->GetDesc().DepthFunc, COMPARISON_GREATER_EQUAL);
  EXPECT_EQ(ref, 0x80u);
  ctx().OMGetBlendState(&bs, factor, &mask);
  ASSERT_TRUE(bs);
  EXPECT_EQ(bs->GetDesc().RenderTarget[0].SrcBlend, BLEND_SRC_ALPHA);
  EXPECT_EQ(factor[1], 0.25f);
  EXPECT_EQ(mask, 0xFu);
  ctx().PSGetSamplers(0, 1, &sam);
  ASSERT_TRUE(sam);
  EXPECT_EQ(sam->GetDesc().Filter, FILTER_ANISOTROPIC);  // samLinear at s0

  lit->GetPassByIndex(1)->Apply(ctx());
  ctx().PSGetShader(&ps);
  EXPECT_FALSE(ps);  // SetPixelShader(psNone), psNone = NULL
  ctx().RSGetState(&rs);
  ASSERT_TRUE(rs);
  EXPECT_EQ(rs->GetDesc().FillMode, FILL_WIREFRAME);  // P1 does not name a rasterizer state
  ctx().OMGetBlendState(&bs, factor, &mask);
  ASSERT_TRUE(bs);
  EXPECT_FALSE(bs->GetDesc().RenderTarget[0].BlendEnable);
  EXPECT_EQ(mask, 0xFFFFFFFFu);
}

// A pass whose shader did not compile (kept by failOnCompileError = false) stops CreateObjects.
TEST_P(EffectDrawTest, CreateObjectsRefusesAPassThatDidNotCompile) {
  fx::EffectOptions opt = Options();
  opt.failOnCompileError = false;
  auto effect = fx::Effect::Load(FxDir() / "include-in-pass.fx", opt);
  try {
    effect->CreateObjects(device());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("technique T, pass P: the pixel shader did not compile"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(effect->HasObjects());
}

SP_INSTANTIATE_BACKEND_TESTS(EffectDrawTest);

}  // namespace
}  // namespace sp::test
