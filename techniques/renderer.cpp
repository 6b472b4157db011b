#include <sp/tech/renderer.h>

#include "local-lights.h"

#include <cstring>
#include <stdexcept>

namespace sp::tech {

namespace {

// Lab targets after the colour (SV_Target0), in SV_Target order.
struct LabTargetSpec {
  FORMAT format;
  const char* name;
  float clear[4];
};
const LabTargetSpec kLabTargets[5] = {
    {FORMAT_R32G32B32A32_FLOAT, "lab world position", {0, 0, 0, 0}},  // w = 0: nothing drawn
    {FORMAT_R32G32B32A32_FLOAT, "lab normal and N.L", {0, 0, 0, 0}},
    {FORMAT_R32_FLOAT, "lab visibility", {0, 0, 0, 0}},
    {FORMAT_R32G32B32A32_FLOAT, "lab shadow lookup", {-1, 0, 0, 0}},  // layer -1: no map read
    {FORMAT_R8G8B8A8_UNORM, "lab albedo", {0, 0, 0, 0}},
};

Ref<Texture2D> StagingFor(Device& device, Texture2D* t) {
  TEXTURE2D_DESC sd = t->GetDesc();
  sd.BindFlags = 0;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ;
  return device.CreateTexture2D(sd);
}

// Copies a mapped texture's rows (bytesPerPixel each) into `out`, dropping the row padding.
template <class T>
void ReadRows(DeviceContext& ctx, Texture2D* texture, Texture2D* staging, uint32_t w, uint32_t h, std::vector<T>& out, size_t perPixel) {
  ctx.CopyResource(staging, texture);
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging, 0, MAP_READ, 0, &m);
  out.resize(size_t(w) * h * perPixel);
  size_t rowBytes = size_t(w) * perPixel * sizeof(T);
  for (uint32_t y = 0; y < h; ++y)
    std::memcpy(reinterpret_cast<uint8_t*>(out.data()) + y * rowBytes, static_cast<const uint8_t*>(m.pData) + size_t(y) * m.RowPitch, rowBytes);
  ctx.Unmap(staging, 0);
}

}  // namespace

std::pair<ShaderBytecode, ShaderBytecode> Renderer::CompileLitShaders(const Technique& technique, LitPass pass, const scene::Scene* labScene) {
  // The lit pass is compiled after the technique's include, which defines ShadowVisibility().
  // The wrapper lives (virtually) in shaders-hlsl/ so relative includes resolve there.
  std::string source = "#include \"" + technique.LightingInclude() + "\"\n#include \"lit.hlsl\"\n";
  std::string name = (ShaderDirectory() / ("lit+" + technique.Name() + ".hlsl")).string();
  hlsl::CompileOptions o;
  o.defines = technique.LightingDefines();
  if (pass == LitPass::Lab) o.defines.push_back({"SP_LAB", "1"});
  if (pass == LitPass::Lab && labScene && technique.LabLocalLight(*labScene) >= 0)
    o.defines.push_back({"SP_LAB_LOCAL_LIGHT", std::to_string(technique.LabLocalLight(*labScene))});
  o.includeDirs = {ShaderDirectory()};
  o.target = "vs_5_0";
  o.entryPoint = "VSMain";
  ShaderBytecode vs = hlsl::CompileSource(source, name, o);
  o.target = "ps_5_0";
  o.entryPoint = "PSMain";
  ShaderBytecode ps = hlsl::CompileSource(source, name, o);
  return {std::move(vs), std::move(ps)};
}

Renderer::Renderer(Device& device, const scene::Scene& scene, std::unique_ptr<Technique> technique, uint32_t width, uint32_t height,
                   const RendererOptions& options)
    : device_(device), technique_(std::move(technique)), width_(width), height_(height) {
  CheckLocalLights(scene);
  gpu_ = std::make_unique<scene::GpuScene>(device, scene);
  localLights_ = MakeConstantBuffer(device, sizeof(LocalLightConstants), "LocalLights constants");
  drawer_ = std::make_unique<SceneDrawer>(device, *gpu_);

  TEXTURE2D_DESC cd;
  cd.Width = width;
  cd.Height = height;
  cd.Format = FORMAT_R8G8B8A8_UNORM_SRGB;
  cd.BindFlags = BIND_RENDER_TARGET | BIND_SHADER_RESOURCE;
  color_ = device.CreateTexture2D(cd);
  color_->SetDebugName("lit colour");
  colorRtv_ = device.CreateRenderTargetView(color_.get());
  TEXTURE2D_DESC dd = cd;
  dd.Format = FORMAT_D32_FLOAT;
  dd.BindFlags = BIND_DEPTH_STENCIL;
  depth_ = device.CreateTexture2D(dd);
  depth_->SetDebugName("lit depth");
  depthDsv_ = device.CreateDepthStencilView(depth_.get());

  auto [vs, ps] = CompileLitShaders(*technique_);
  litVs_ = device.CreateVertexShader(vs);
  litPs_ = device.CreatePixelShader(ps);
  uint32_t n;
  const INPUT_ELEMENT_DESC* el = scene::GpuScene::InputElements(&n);
  litLayout_ = device.CreateInputLayout(el, n, vs);
  RASTERIZER_DESC rd;
  // Scenes follow glTF: right-handed, front faces counter-clockwise as seen by the viewer. D3D11
  // judges winding as it appears on the render target, so such content needs
  // FrontCounterClockwise (D3D11's default, clockwise, belongs to left-handed content).
  rd.FrontCounterClockwise = true;
  litRasterizer_ = device.CreateRasterizerState(rd);

  if (options.lab) {
    // The lab variant shares the vertex shader: VSMain does not depend on SP_LAB.
    labPs_ = device.CreatePixelShader(CompileLitShaders(*technique_, LitPass::Lab, &scene).second);
    CreateLabTargets();
  }
}

void Renderer::CreateLabTargets() {
  for (int i = 0; i < 5; ++i) {
    TEXTURE2D_DESC d;
    d.Width = width_;
    d.Height = height_;
    d.Format = kLabTargets[i].format;
    d.BindFlags = BIND_RENDER_TARGET;
    lab_[i].texture = device_.CreateTexture2D(d);
    lab_[i].texture->SetDebugName(kLabTargets[i].name);
    lab_[i].rtv = device_.CreateRenderTargetView(lab_[i].texture.get());
    lab_[i].staging = StagingFor(device_, lab_[i].texture.get());
  }
  colorStaging_ = StagingFor(device_, color_.get());
}

FrameInputs Renderer::MakeFrame(const scene::Camera& camera, const scene::DirectionalLight& light) const {
  FrameInputs f;
  f.scene = &gpu_->scene();
  f.camera = camera;
  f.light = light;
  f.width = width_;
  f.height = height_;
  f.cameraView = camera.view();
  f.cameraProj = camera.projection(float(width_) / float(height_));
  f.timer = timer_;
  f.localLights = LocalLightsOf(gpu_->scene());
  return f;
}

void Renderer::RenderFrame(const scene::Camera& camera, const scene::DirectionalLight& light, LitPass pass) {
  DeviceContext& ctx = *device_.GetImmediateContext();
  FrameInputs f = MakeFrame(camera, light);
  if (timer_) timer_->BeginFrame(ctx);
  technique_->RenderShadows(ctx, *drawer_, f);
  {
    GpuTimer::Scope timed(timer_, ctx, "lit");
    LitPassInternal(ctx, f, pass);
  }
  if (timer_) timer_->EndFrame(ctx);
}

void Renderer::RenderLitPass(const scene::Camera& camera, const scene::DirectionalLight& light, LitPass pass) {
  DeviceContext& ctx = *device_.GetImmediateContext();
  FrameInputs f = MakeFrame(camera, light);
  f.timer = nullptr;  // not a frame of its own
  LitPassInternal(ctx, f, pass);
}

void Renderer::LitPassInternal(DeviceContext& ctx, const FrameInputs& f, LitPass pass) {
  if (pass == LitPass::Lab && !labPs_) throw std::logic_error("Renderer: the lab lit pass needs RendererOptions::lab");
  const float sky[4] = {0.55f, 0.68f, 0.85f, 1.0f};
  if (pass == LitPass::Lab) {
    RenderTargetView* rtvs[6] = {colorRtv_.get()};
    for (int i = 0; i < 5; ++i) rtvs[i + 1] = lab_[i].rtv.get();
    ctx.OMSetRenderTargets(6, rtvs, depthDsv_.get());
    for (int i = 0; i < 5; ++i) ctx.ClearRenderTargetView(lab_[i].rtv.get(), kLabTargets[i].clear);
    labViewProj_ = f.cameraProj * f.cameraView;
    labCameraPosition_ = f.camera.position;
  } else {
    RenderTargetView* rtvs[] = {colorRtv_.get()};
    ctx.OMSetRenderTargets(1, rtvs, depthDsv_.get());
  }
  ctx.OMSetDepthStencilState(nullptr, 0);
  ctx.OMSetBlendState(nullptr, nullptr, 0xffffffff);
  ctx.ClearRenderTargetView(colorRtv_.get(), sky);
  ctx.ClearDepthStencilView(depthDsv_.get(), CLEAR_DEPTH, 1.0f, 0);
  VIEWPORT vp{0, 0, float(width_), float(height_), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.RSSetState(litRasterizer_.get());

  drawer_->SetFrame(ctx, f.cameraProj * f.cameraView, &f);
  LocalLightConstants local = PackLocalLights(f.localLights);
  ctx.UpdateSubresource(localLights_.get(), 0, nullptr, &local, 0, 0);
  gpu_->BindGeometry(ctx);
  ctx.IASetInputLayout(litLayout_.get());
  ctx.VSSetShader(litVs_.get());
  ctx.PSSetShader(pass == LitPass::Lab ? labPs_.get() : litPs_.get());
  drawer_->BindConstants(ctx, ShaderStage::Vertex);
  drawer_->BindConstants(ctx, ShaderStage::Pixel);
  ctx.PSSetConstantBuffers(6, {localLights_.get()});
  technique_->BindLighting(ctx);
  for (const scene::DrawItem& d : gpu_->draws()) {
    drawer_->SetObject(ctx, d.instance);
    ctx.DrawIndexed(d.indexCount, d.firstIndex, d.baseVertex);
  }
}

std::vector<uint8_t> Renderer::ReadColor() {
  DeviceContext& ctx = *device_.GetImmediateContext();
  Ref<Texture2D> staging = colorStaging_ ? colorStaging_ : StagingFor(device_, color_.get());
  std::vector<uint8_t> out;
  ReadRows(ctx, color_.get(), staging.get(), width_, height_, out, 4);
  return out;
}

LabBuffers Renderer::ReadLab() {
  if (!labPs_) throw std::logic_error("Renderer::ReadLab needs RendererOptions::lab");
  DeviceContext& ctx = *device_.GetImmediateContext();
  LabBuffers b;
  b.width = width_;
  b.height = height_;
  b.viewProj = labViewProj_;
  b.cameraPosition = labCameraPosition_;
  b.color = ReadColor();
  ReadRows(ctx, lab_[0].texture.get(), lab_[0].staging.get(), width_, height_, b.position, 1);
  ReadRows(ctx, lab_[1].texture.get(), lab_[1].staging.get(), width_, height_, b.normal, 1);
  ReadRows(ctx, lab_[2].texture.get(), lab_[2].staging.get(), width_, height_, b.visibility, 1);
  ReadRows(ctx, lab_[3].texture.get(), lab_[3].staging.get(), width_, height_, b.lookup, 1);
  ReadRows(ctx, lab_[4].texture.get(), lab_[4].staging.get(), width_, height_, b.albedo, 4);
  return b;
}

}  // namespace sp::tech
