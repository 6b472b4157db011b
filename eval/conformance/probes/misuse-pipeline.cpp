// Misuse of shaders, bindings and draws: compile errors, stage and interface mismatches, slots
// out of range, registers the shader reads left unbound or bound to the wrong kind of view,
// inconsistent output-merger bindings, incomplete draw state and features ShadowPort does not
// offer. Each must throw sp::Error with the documented id naming the call and the object.
#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Misuse";

ShaderBytecode Compile(const char* src, const char* target, const char* entry) {
  return gpu::CompileInline(src, "conformance/misuse.hlsl", target, entry);
}

// A 4 x 4 render target with a viewport and triangle-list topology: everything a draw needs but
// the shaders and their resources.
struct DrawSetup {
  Ref<Texture2D> texture;
  Ref<RenderTargetView> rtv;
  explicit DrawSetup(Device& dev, FORMAT format = FORMAT_R8G8B8A8_UNORM) {
    DeviceContext& ctx = *dev.GetImmediateContext();
    texture = gpu::MakeTexture2D(dev, 4, 4, format, BIND_RENDER_TARGET);
    rtv = dev.CreateRenderTargetView(texture.get());
    RenderTargetView* rtvs[] = {rtv.get()};
    ctx.OMSetRenderTargets(1, rtvs, nullptr);
    VIEWPORT vp{0, 0, 4, 4, 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  }
};

const char* kShaders = R"(
Texture2D<float4> albedo : register(t3);
SamplerState smp : register(s1);
cbuffer Material : register(b2) { float4 tint; };
struct VOut { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
VOut VSMain(uint id : SV_VertexID) { VOut o; o.pos = float4(0, 0, 0, 1); o.uv = 0; return o; }
float4 VSPositionOnly(uint id : SV_VertexID) : SV_Position { return float4(0, 0, 0, 1); }
float4 VSWithInput(float3 p : POSITION) : SV_Position { return float4(p, 1); }
float4 VSOtherInput(float2 q : NORMAL) : SV_Position { return float4(q, 0, 1); }
float4 PSTextured(VOut v) : SV_Target { return albedo.Sample(smp, v.uv) * tint; }
float4 PSReadsTexcoord3(float4 p : SV_Position, float2 t : TEXCOORD3) : SV_Target { return t.xyxy; }
float4 PSWhite(float4 p : SV_Position) : SV_Target { return 1; }
RWStructuredBuffer<uint> results : register(u2);
[numthreads(1, 1, 1)] void CSWrite() { results[0] = 1; }
AppendStructuredBuffer<uint> list : register(u0);
[numthreads(1, 1, 1)] void CSAppend() { list.Append(7); }
StructuredBuffer<float2> pairs : register(t0);
[numthreads(1, 1, 1)] void CSPairs() { results[0] = uint(pairs[0].x); }
RWBuffer<float> vsOut : register(u1);
float4 VSWritesUav(uint id : SV_VertexID) : SV_Position { vsOut[id] = 1; return float4(0, 0, 0, 1); }
)";

}  // namespace

SP_PROBE(kGroup, "SP_SHADER_COMPILE_FAILED: HLSL the toolchain cannot compile", "errors name the file and line; the stage that failed is the call") {
  const char* bad = "float4 main() : SV_Target {\n  float4 c = 1;\n  return undeclared + c;\n}\n";
  hlsl::CompileOptions o;
  o.target = "ps_5_0";
  o.entryPoint = "main";
  o.useCache = false;
  hlsl::CompileOptions wrongTarget = o;
  wrongTarget.target = "ps_4_1x";
  return ExpectErrors(
      ErrorId::SHADER_COMPILE_FAILED,
      {{"glslang",
        "conformance/misuse-bad.hlsl:main",
        {"misuse-bad.hlsl:3", "undeclared"},
        [&] { hlsl::CompileSource(bad, "conformance/misuse-bad.hlsl", o); }},
       {"Compile", "conformance/misuse-bad.hlsl:main", {"ps_4_1x"}, [&] { hlsl::CompileSource(bad, "conformance/misuse-bad.hlsl", wrongTarget); }}});
}

SP_PROBE(kGroup, "SP_SHADER_STAGE_MISMATCH: bytecode of another stage",
         "pixel bytecode to CreateVertexShader or CreateInputLayout, vertex bytecode to CreateComputeShader") {
  ShaderBytecode ps = Compile(kShaders, "ps_5_0", "PSWhite"), vs = Compile(kShaders, "vs_5_0", "VSPositionOnly");
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  return ExpectErrors(
      ErrorId::SHADER_STAGE_MISMATCH,
      {{"CreateVertexShader", "misuse.hlsl:PSWhite", {"pixel shader, not a vertex shader"}, [&] { device.CreateVertexShader(ps); }},
       {"CreateComputeShader", "misuse.hlsl:VSPositionOnly", {"vertex shader, not a compute shader"}, [&] { device.CreateComputeShader(vs); }},
       {"CreateInputLayout", "misuse.hlsl:PSWhite", {"not a vertex shader"}, [&] { device.CreateInputLayout(&el, 1, ps); }}});
}

SP_PROBE(kGroup, "SP_INPUT_LAYOUT_MISMATCH: an input layout that does not feed the vertex shader",
         "a missing semantic, a format of another type, a layout made for another shader at draw time") {
  DeviceContext& ctx = *device.GetImmediateContext();
  const char* vsSrc = "float4 main(float3 p : POSITION, float2 uv : TEXCOORD1) : SV_Position { return float4(p + uv.x, 1); }";
  ShaderBytecode vs = gpu::CompileInline(vsSrc, "conformance/misuse-layout.hlsl", "vs_5_0", "main");
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  INPUT_ELEMENT_DESC wrongType[] = {{"POSITION", 0, FORMAT_R32G32B32_UINT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                                    {"TEXCOORD", 1, FORMAT_R32G32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0}};
  DrawSetup setup(device);
  ShaderBytecode withInput = Compile(kShaders, "vs_5_0", "VSWithInput"), other = Compile(kShaders, "vs_5_0", "VSOtherInput");
  INPUT_ELEMENT_DESC normal{"NORMAL", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0};
  Ref<InputLayout> otherLayout = device.CreateInputLayout(&normal, 1, other);
  otherLayout->SetDebugName("normals layout");
  Ref<VertexShader> shader = device.CreateVertexShader(withInput);
  Ref<PixelShader> ps = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSWhite"));
  Ref<Buffer> vb = gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 64);
  Buffer* vbs[] = {vb.get()};
  uint32_t stride = 8, offset = 0;
  return ExpectErrors(ErrorId::INPUT_LAYOUT_MISMATCH,
                      {{"CreateInputLayout", "misuse-layout.hlsl:main", {"TEXCOORD1"}, [&] { device.CreateInputLayout(&el, 1, vs); }},
                       {"CreateInputLayout", "misuse-layout.hlsl:main", {"R32G32B32_UINT"}, [&] { device.CreateInputLayout(wrongType, 2, vs); }},
                       {"Draw", "normals layout", {"POSITION0", "another shader"}, [&] {
                          ctx.VSSetShader(shader.get());
                          ctx.PSSetShader(ps.get());
                          ctx.IASetInputLayout(otherLayout.get());
                          ctx.IASetVertexBuffers(0, 1, vbs, &stride, &offset);
                          ctx.Draw(3, 0);
                        }}});
}

SP_PROBE(kGroup, "SP_SHADER_INTERFACE_MISMATCH: the pixel shader reads what the vertex shader does not write",
         "a PS input semantic missing from the VS outputs fails the draw") {
  DeviceContext& ctx = *device.GetImmediateContext();
  DrawSetup setup(device);
  Ref<VertexShader> vs = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSReadsTexcoord3"));
  ps->SetDebugName("reads TEXCOORD3");
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  return ExpectErrors(ErrorId::SHADER_INTERFACE_MISMATCH, {{"Draw", "reads TEXCOORD3", {"TEXCOORD3"}, [&] { ctx.Draw(3, 0); }}});
}

SP_PROBE(kGroup, "SP_SLOT_OUT_OF_RANGE: StartSlot + count beyond D3D11's slot counts",
         "t0-t127, u0-u7, b0-b13, s0-s15, 32 vertex buffers, InputSlot < 32") {
  DeviceContext& ctx = *device.GetImmediateContext();
  ShaderBytecode vs = Compile(kShaders, "vs_5_0", "VSWithInput");
  INPUT_ELEMENT_DESC el{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 32, 0, INPUT_PER_VERTEX_DATA, 0};
  Buffer* vbs[2] = {nullptr, nullptr};
  uint32_t strides[2] = {0, 0}, offsets[2] = {0, 0};
  return ExpectErrors(ErrorId::SLOT_OUT_OF_RANGE,
                      {{"PSSetShaderResources",
                        "shader resource slots",
                        {"128"},
                        [&] {
                          ctx.PSSetShaderResources(127, {nullptr, nullptr});
                        }},
                       {"CSSetUnorderedAccessViews",
                        "UAV slots",
                        {"[7, 9)"},
                        [&] {
                          ctx.CSSetUnorderedAccessViews(7, {nullptr, nullptr});
                        }},
                       {"VSSetConstantBuffers", "constant buffer slots", {"14"}, [&] { ctx.VSSetConstantBuffers(14, {nullptr}); }},
                       {"PSSetSamplers", "sampler slots", {"16"}, [&] { ctx.PSSetSamplers(16, {nullptr}); }},
                       {"IASetVertexBuffers", "vertex buffer slots", {"32"}, [&] { ctx.IASetVertexBuffers(31, 2, vbs, strides, offsets); }},
                       {"CreateInputLayout", "misuse.hlsl:VSWithInput", {"InputSlot"}, [&] { device.CreateInputLayout(&el, 1, vs); }}});
}

// The SP_UNBOUND_RESOURCE cases, on a strict device.
static Result UnboundResourceCases(Device& device) {
  DeviceContext& ctx = *device.GetImmediateContext();
  DrawSetup setup(device);
  Ref<VertexShader> vs = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSTextured"));
  Ref<ComputeShader> cs = device.CreateComputeShader(Compile(kShaders, "cs_5_0", "CSWrite"));
  ps->SetDebugName("textured");
  cs->SetDebugName("writer");
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());
  Ref<SamplerState> linear = device.CreateSamplerState(SAMPLER_DESC{});
  Ref<Buffer> tint = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, 16);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ctx.CSSetShader(cs.get());
  Result r = ExpectErrors(ErrorId::UNBOUND_RESOURCE, {{"Draw", "textured", {"PS slot b2", "Material"}, [&] { ctx.Draw(3, 0); }},
                                                      {"Draw",
                                                       "textured",
                                                       {"PS slot t3", "albedo"},
                                                       [&] {
                                                         ctx.PSSetConstantBuffers(2, {tint.get()});
                                                         ctx.Draw(3, 0);
                                                       }},
                                                      {"Draw",
                                                       "textured",
                                                       {"PS slot s1", "smp"},
                                                       [&] {
                                                         ctx.PSSetShaderResources(3, {srv.get()});
                                                         ctx.Draw(3, 0);
                                                       }},
                                                      {"Dispatch", "writer", {"CS slot u2", "results"}, [&] { ctx.Dispatch(1, 1, 1); }}});
  // With everything bound the draw goes through; a throw fails the probe.
  ctx.PSSetSamplers(1, {linear.get()});
  ctx.Draw(3, 0);
  return r;
}

SP_PROBE(kGroup, "SP_UNBOUND_RESOURCE: a register the shader reads has nothing bound",
         "on a device created with strictUnboundResources (by default such registers read zeros, as in D3D11): textures, "
         "samplers, cbuffers and UAVs read by the bound shaders, named by stage, register and HLSL name") {
  DeviceDesc strictDesc;
  strictDesc.backend = device.GetBackend();
  strictDesc.debug = device.Info().validationEnabled;
  strictDesc.strictUnboundResources = true;
  // Driver messages of the strict device count on the probe's device, which the suite checks.
  strictDesc.messageCallback = [&device](MessageSeverity s, std::string_view t) { device.Message(s, t); };
  Ref<Device> strictDevice = CreateDevice(strictDesc);
  return UnboundResourceCases(*strictDevice);
}

SP_PROBE(kGroup, "SP_RESOURCE_TYPE_MISMATCH: a bound view or sampler of another kind than the shader declares",
         "comparison vs plain samplers, array vs 2D views, uint vs float views, structured strides, counters, render-target types") {
  DeviceContext& ctx = *device.GetImmediateContext();
  DrawSetup setup(device, FORMAT_R32_UINT);
  Ref<VertexShader> vs = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSMain"));
  Ref<PixelShader> ps = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSTextured"));
  Ref<PixelShader> white = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSWhite"));
  Ref<ComputeShader> append = device.CreateComputeShader(Compile(kShaders, "cs_5_0", "CSAppend"));
  Ref<ComputeShader> pairs = device.CreateComputeShader(Compile(kShaders, "cs_5_0", "CSPairs"));
  ps->SetDebugName("textured");
  white->SetDebugName("white");
  append->SetDebugName("appender");
  pairs->SetDebugName("pairs reader");
  SAMPLER_DESC cd;
  cd.Filter = FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
  cd.ComparisonFunc = COMPARISON_LESS;
  Ref<SamplerState> cmp = device.CreateSamplerState(cd), linear = device.CreateSamplerState(SAMPLER_DESC{});
  Ref<Texture2D> arr = gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, nullptr, 1, 2);
  Ref<Texture2D> flat = gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<Texture2D> uintTex = gpu::MakeTexture2D(device, 4, 4, FORMAT_R32_UINT, BIND_SHADER_RESOURCE);
  Ref<ShaderResourceView> arrSrv = device.CreateShaderResourceView(arr.get()), flatSrv = device.CreateShaderResourceView(flat.get()),
                          uintSrv = device.CreateShaderResourceView(uintTex.get());
  Ref<Buffer> tint = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, 16);
  BufferViews plain = MakeStructured(device, 4, 4), results = MakeStructured(device, 4, 4), wide = MakeStructured(device, 4, 16);
  ctx.VSSetShader(vs.get());
  ctx.PSSetConstantBuffers(2, {tint.get()});
  return ExpectErrors(ErrorId::RESOURCE_TYPE_MISMATCH, {{"Draw",
                                                         "textured",
                                                         {"PS slot s1", "SamplerState"},
                                                         [&] {
                                                           ctx.PSSetShader(ps.get());
                                                           ctx.PSSetShaderResources(3, {flatSrv.get()});
                                                           ctx.PSSetSamplers(1, {cmp.get()});
                                                           ctx.Draw(3, 0);
                                                         }},
                                                        {"Draw",
                                                         "textured",
                                                         {"declared Texture2D", "Texture2DArray"},
                                                         [&] {
                                                           ctx.PSSetSamplers(1, {linear.get()});
                                                           ctx.PSSetShaderResources(3, {arrSrv.get()});
                                                           ctx.Draw(3, 0);
                                                         }},
                                                        {"Draw",
                                                         "textured",
                                                         {"returns float", "R32_UINT"},
                                                         [&] {
                                                           ctx.PSSetShaderResources(3, {uintSrv.get()});
                                                           ctx.Draw(3, 0);
                                                         }},
                                                        {"Draw",
                                                         "white",
                                                         {"SV_Target0 is float", "R32_UINT"},
                                                         [&] {
                                                           ctx.PSSetShader(white.get());
                                                           ctx.Draw(3, 0);
                                                         }},
                                                        {"Dispatch",
                                                         "appender",
                                                         {"BUFFER_UAV_FLAG_APPEND"},
                                                         [&] {
                                                           ctx.CSSetShader(append.get());
                                                           ctx.CSSetUnorderedAccessViews(0, {plain.uav.get()});
                                                           ctx.Dispatch(1, 1, 1);
                                                         }},
                                                        {"Dispatch", "pairs reader", {"stride of 8 bytes", "StructureByteStride is 16"}, [&] {
                                                           ctx.CSSetShader(pairs.get());
                                                           ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr, results.uav.get()});
                                                           ctx.CSSetShaderResources(0, {wide.srv.get()});
                                                           ctx.Dispatch(1, 1, 1);
                                                         }}});
}

SP_PROBE(kGroup, "SP_SAMPLE_COUNT_MISMATCH: render targets, depth buffers or copies of different sample counts",
         "a 4x target with a 1x depth buffer, resolving a single-sampled source, copying between sample counts") {
  if (device.CheckMultisampleQualityLevels(FORMAT_R8G8B8A8_UNORM, 4) == 0) return Unsupported("no 4x MSAA for R8G8B8A8_UNORM");
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> color = gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET, nullptr, 1, 1, 4);
  Ref<Texture2D> single = gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<Texture2D> depth = gpu::MakeTexture2D(device, 8, 8, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL);
  depth->SetDebugName("single-sampled depth");
  single->SetDebugName("resolved");
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(color.get());
  Ref<DepthStencilView> dsv = device.CreateDepthStencilView(depth.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  return ExpectErrors(
      ErrorId::SAMPLE_COUNT_MISMATCH,
      {{"OMSetRenderTargets", "single-sampled depth", {"4x"}, [&] { ctx.OMSetRenderTargets(1, rtvs, dsv.get()); }},
       {"ResolveSubresource", "resolved", {"multisampled"}, [&] { ctx.ResolveSubresource(color.get(), 0, single.get(), 0, FORMAT_R8G8B8A8_UNORM); }},
       {"CopyResource", "resolved", {"sample count"}, [&] { ctx.CopyResource(single.get(), color.get()); }}});
}

SP_PROBE(kGroup, "SP_OUTPUT_MISMATCH: output-merger bindings that do not fit together",
         "render targets of different sizes, one subresource bound twice, UAV slots overlapping render targets") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> a = gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<Texture2D> b = gpu::MakeTexture2D(device, 4, 8, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  b->SetDebugName("half width");
  Ref<RenderTargetView> ra = device.CreateRenderTargetView(a.get()), rb = device.CreateRenderTargetView(b.get()),
                        ra2 = device.CreateRenderTargetView(a.get());
  ra2->SetDebugName("second view of a");
  BufferViews u = MakeStructured(device, 4, 4);
  RenderTargetView* sizes[] = {ra.get(), rb.get()};
  RenderTargetView* twice[] = {ra.get(), ra2.get()};
  RenderTargetView* one[] = {ra.get()};
  UnorderedAccessView* uavs[] = {u.uav.get()};
  return ExpectErrors(ErrorId::OUTPUT_MISMATCH,
                      {{"OMSetRenderTargets", "half width", {"does not match"}, [&] { ctx.OMSetRenderTargets(2, sizes, nullptr); }},
                       {"OMSetRenderTargets", "second view of a", {"render targets 0 and 1"}, [&] { ctx.OMSetRenderTargets(2, twice, nullptr); }},
                       {"OMSetRenderTargetsAndUnorderedAccessViews", "UAVs", {"UAVStartSlot"}, [&] {
                          ctx.OMSetRenderTargetsAndUnorderedAccessViews(1, one, nullptr, 0, 1, uavs, nullptr);
                        }}});
}

SP_PROBE(kGroup, "SP_DRAW_STATE_INVALID: a draw or dispatch without the state it needs",
         "no vertex or compute shader, no topology, no viewport, no input layout, no index buffer") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<VertexShader> vs = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSPositionOnly"));
  Ref<VertexShader> withInput = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSWithInput"));
  withInput->SetDebugName("needs POSITION");
  Ref<Texture2D> rt = gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(rt.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, 4, 4, 0, 1};
  return ExpectErrors(ErrorId::DRAW_STATE_INVALID, {{"Draw", "pipeline", {"VSSetShader"}, [&] { ctx.Draw(3, 0); }},
                                                    {"Draw",
                                                     "pipeline",
                                                     {"IASetPrimitiveTopology"},
                                                     [&] {
                                                       ctx.VSSetShader(vs.get());
                                                       ctx.Draw(3, 0);
                                                     }},
                                                    {"Draw",
                                                     "pipeline",
                                                     {"RSSetViewports"},
                                                     [&] {
                                                       ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
                                                       ctx.Draw(3, 0);
                                                     }},
                                                    {"DrawIndexed",
                                                     "pipeline",
                                                     {"IASetIndexBuffer"},
                                                     [&] {
                                                       ctx.RSSetViewports(1, &vp);
                                                       ctx.DrawIndexed(3, 0, 0);
                                                     }},
                                                    {"Draw",
                                                     "needs POSITION",
                                                     {"IASetInputLayout"},
                                                     [&] {
                                                       ctx.VSSetShader(withInput.get());
                                                       ctx.Draw(3, 0);
                                                     }},
                                                    {"Dispatch", "pipeline", {"CSSetShader"}, [&] { ctx.Dispatch(1, 1, 1); }}});
}

SP_PROBE(kGroup, "SP_NOT_SUPPORTED: valid D3D11 that ShadowPort does not offer",
         "geometry shaders, stream output, other query types and topologies, UAVs in vertex shaders, depth resolves") {
  DeviceContext& ctx = *device.GetImmediateContext();
  DrawSetup setup(device);
  Ref<VertexShader> vs = device.CreateVertexShader(Compile(kShaders, "vs_5_0", "VSWritesUav"));
  vs->SetDebugName("vertex UAV writer");
  Ref<PixelShader> ps = device.CreatePixelShader(Compile(kShaders, "ps_5_0", "PSWhite"));
  ShaderBytecode vsb = Compile(kShaders, "vs_5_0", "VSPositionOnly");
  return ExpectErrors(ErrorId::NOT_SUPPORTED,
                      {{"CreateGeometryShader", "misuse.hlsl:VSPositionOnly", {"geometry shaders"}, [&] { device.CreateGeometryShader(vsb); }},
                       {"CreateBuffer", "BIND_STREAM_OUTPUT", {"stream output"}, [&] { gpu::MakeBuffer(device, BIND_STREAM_OUTPUT, nullptr, 64); }},
                       {"CreateQuery",
                        "Query",
                        {"query type 4"},
                        [&] {
                          QUERY_DESC q;
                          q.Query = QUERY(4);
                          device.CreateQuery(q);
                        }},
                       {"IASetPrimitiveTopology", "topology 33", {"TRIANGLESTRIP"}, [&] { ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY(33)); }},
                       {"Draw", "vertex UAV writer", {"pixel and compute shaders"}, [&] {
                          ctx.VSSetShader(vs.get());
                          ctx.PSSetShader(ps.get());
                          ctx.Draw(3, 0);
                        }}});
}

}  // namespace sp::conformance
