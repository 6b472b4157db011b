// Renders one frame of a scene with a shadow technique: the technique's shadow passes, then the
// lit pass into an sRGB colour target with a D32 depth buffer.
#pragma once
#include "technique.h"

namespace sp::tech {

class Renderer {
 public:
  Renderer(Device& device, const scene::Scene& scene, std::unique_ptr<Technique> technique, uint32_t width, uint32_t height);

  void RenderFrame(const scene::Camera& camera, const scene::DirectionalLight& light);
  // The colour target as RGBA8 rows (sRGB-encoded, top row first).
  std::vector<uint8_t> ReadColor();

  Technique& technique() { return *technique_; }
  Texture2D* colorTarget() { return color_.get(); }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // The lit pass's shaders for a technique (what RenderFrame uses); exposed for tests.
  static std::pair<ShaderBytecode, ShaderBytecode> CompileLitShaders(const Technique& technique);

 private:
  Device& device_;
  std::unique_ptr<scene::GpuScene> gpu_;
  std::unique_ptr<SceneDrawer> drawer_;
  std::unique_ptr<Technique> technique_;
  uint32_t width_, height_;
  Ref<Texture2D> color_, depth_;
  Ref<RenderTargetView> colorRtv_;
  Ref<DepthStencilView> depthDsv_;
  Ref<VertexShader> litVs_;
  Ref<PixelShader> litPs_;
  Ref<InputLayout> litLayout_;
  Ref<RasterizerState> litRasterizer_;
};

}  // namespace sp::tech
