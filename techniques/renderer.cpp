#include "renderer.h"

#include <cstring>

namespace sp::tech {

std::pair<ShaderBytecode, ShaderBytecode> Renderer::CompileLitShaders(const Technique& technique) {
  // The lit pass is compiled after the technique's include, which defines ShadowVisibility().
  // The wrapper lives (virtually) in shaders-hlsl/ so relative includes resolve there.
  std::string source = "#include \"" + technique.LightingInclude() + "\"\n#include \"lit.hlsl\"\n";
  std::string name = (ShaderDirectory() / ("lit+" + technique.Name() + ".hlsl")).string();
  hlsl::CompileOptions o;
  o.defines = technique.LightingDefines();
  o.includeDirs = {ShaderDirectory()};
  o.target = "vs_5_0";
  o.entryPoint = "VSMain";
  ShaderBytecode vs = hlsl::CompileSource(source, name, o);
  o.target = "ps_5_0";
  o.entryPoint = "PSMain";
  ShaderBytecode ps = hlsl::CompileSource(source, name, o);
  return {std::move(vs), std::move(ps)};
}

Renderer::Renderer(Device& device, const scene::Scene& scene, std::unique_ptr<Technique> technique, uint32_t width, uint32_t height)
    : device_(device), technique_(std::move(technique)), width_(width), height_(height) {
  gpu_ = std::make_unique<scene::GpuScene>(device, scene);
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
}

void Renderer::RenderFrame(const scene::Camera& camera, const scene::DirectionalLight& light) {
  DeviceContext& ctx = *device_.GetImmediateContext();
  FrameInputs f;
  f.scene = &gpu_->scene();
  f.camera = camera;
  f.light = light;
  f.width = width_;
  f.height = height_;
  f.cameraView = camera.view();
  f.cameraProj = camera.projection(float(width_) / float(height_));

  technique_->RenderShadows(ctx, *drawer_, f);

  RenderTargetView* rtvs[] = {colorRtv_.get()};
  ctx.OMSetRenderTargets(1, rtvs, depthDsv_.get());
  ctx.OMSetDepthStencilState(nullptr, 0);
  ctx.OMSetBlendState(nullptr, nullptr, 0xffffffff);
  const float sky[4] = {0.55f, 0.68f, 0.85f, 1.0f};
  ctx.ClearRenderTargetView(colorRtv_.get(), sky);
  ctx.ClearDepthStencilView(depthDsv_.get(), CLEAR_DEPTH, 1.0f, 0);
  VIEWPORT vp{0, 0, float(width_), float(height_), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.RSSetState(litRasterizer_.get());

  drawer_->SetFrame(ctx, f.cameraProj * f.cameraView, &f);
  gpu_->BindGeometry(ctx);
  ctx.IASetInputLayout(litLayout_.get());
  ctx.VSSetShader(litVs_.get());
  ctx.PSSetShader(litPs_.get());
  drawer_->BindConstants(ctx, ShaderStage::Vertex);
  drawer_->BindConstants(ctx, ShaderStage::Pixel);
  technique_->BindLighting(ctx);
  for (const scene::DrawItem& d : gpu_->draws()) {
    drawer_->SetObject(ctx, d.instance);
    ctx.DrawIndexed(d.indexCount, d.firstIndex, d.baseVertex);
  }
}

std::vector<uint8_t> Renderer::ReadColor() {
  DeviceContext& ctx = *device_.GetImmediateContext();
  TEXTURE2D_DESC sd = color_->GetDesc();
  sd.BindFlags = 0;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_READ;
  Ref<Texture2D> staging = device_.CreateTexture2D(sd);
  ctx.CopyResource(staging.get(), color_.get());
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging.get(), 0, MAP_READ, 0, &m);
  std::vector<uint8_t> out(size_t(width_) * height_ * 4);
  for (uint32_t y = 0; y < height_; ++y)
    std::memcpy(out.data() + size_t(y) * width_ * 4, static_cast<const uint8_t*>(m.pData) + size_t(y) * m.RowPitch, width_ * 4);
  ctx.Unmap(staging.get(), 0);
  return out;
}

}  // namespace sp::tech
