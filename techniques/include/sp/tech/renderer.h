// Renders one frame of a scene with a shadow technique: the technique's shadow passes, then the
// lit pass into an sRGB colour target with a D32 depth buffer. The lit pass shades the scene's
// directional light and its local lights (FrameInputs::localLights, at most kMaxLocalLights; the
// constructor throws std::invalid_argument for more or for a light it cannot shade).
//
// For the lab (RendererOptions::lab) the renderer also builds a variant of the lit pass
// (shaders-hlsl/lit.hlsl compiled with SP_LAB=1) that writes, beside the same colour, the world
// position, normal and N.L, the technique's visibility, its shadow lookup and the albedo, one
// render target each, read back with ReadLab(). The normal lit pass is unchanged by it.
#pragma once
#include <sp/tech/technique.h>

namespace sp::tech {

struct RendererOptions {
  bool lab = false;  // build the lab's lit pass (LitPass::Lab, ReadLab)
};

enum class LitPass { Normal, Lab };

// What the lab's lit pass wrote, row by row from the top, width * height entries each.
struct LabBuffers {
  uint32_t width = 0, height = 0;
  glm::mat4 viewProj{1.0f};          // the camera's world -> clip for this frame
  glm::vec3 cameraPosition{0.0f};
  std::vector<glm::vec4> position;   // world position; w = 1 where geometry was drawn, 0 for sky
  std::vector<glm::vec4> normal;     // unit world normal; w = N.L (saturated)
  std::vector<float> visibility;     // the technique's ShadowVisibility, for every drawn pixel
  std::vector<glm::vec4> lookup;     // layer (-1: no map read), texel x, texel y, texels per pixel
  std::vector<uint8_t> color;        // RGBA8, sRGB-encoded (what the normal lit pass shows)
  std::vector<uint8_t> albedo;       // RGBA8, linear

  size_t size() const { return size_t(width) * height; }
  bool drawn(size_t i) const { return position[i].w > 0.0f; }
  // The pixels the lab judges: surfaces facing the light, where shading uses the shadow term.
  bool receiving(size_t i) const { return drawn(i) && normal[i].w > 0.0f; }
};

class Renderer {
 public:
  Renderer(Device& device, const scene::Scene& scene, std::unique_ptr<Technique> technique, uint32_t width, uint32_t height,
           const RendererOptions& options = {});

  // The technique's shadow passes, then the lit pass.
  void RenderFrame(const scene::Camera& camera, const scene::DirectionalLight& light, LitPass pass = LitPass::Normal);
  // The lit pass alone, with the shadow state the last RenderFrame left: what the previous frame's
  // shadows give at this camera's surface points (the lab's temporal metric).
  void RenderLitPass(const scene::Camera& camera, const scene::DirectionalLight& light, LitPass pass = LitPass::Normal);
  // The colour target as RGBA8 rows (sRGB-encoded, top row first).
  std::vector<uint8_t> ReadColor();
  // The lab targets of the last lab lit pass (staging copy + Map READ; waits for the GPU).
  LabBuffers ReadLab();

  // Measures GPU time per pass from the next frame on (null: stop): each RenderFrame becomes one
  // timer frame, the technique gets the timer in FrameInputs and the lit pass is timed as "lit".
  void SetGpuTimer(GpuTimer* timer) { timer_ = timer; }

  Technique& technique() { return *technique_; }
  Texture2D* colorTarget() { return color_.get(); }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // The lit pass's shaders for a technique (what RenderFrame uses); exposed for tests. The lab
  // variant judges the light Technique::LabLocalLight(*labScene) names (none: the directional one).
  static std::pair<ShaderBytecode, ShaderBytecode> CompileLitShaders(const Technique& technique, LitPass pass = LitPass::Normal,
                                                                     const scene::Scene* labScene = nullptr);

 private:
  struct LabTarget {
    Ref<Texture2D> texture, staging;
    Ref<RenderTargetView> rtv;
  };
  FrameInputs MakeFrame(const scene::Camera& camera, const scene::DirectionalLight& light) const;
  void LitPassInternal(DeviceContext& ctx, const FrameInputs& f, LitPass pass);
  void CreateLabTargets();

  Device& device_;
  std::unique_ptr<scene::GpuScene> gpu_;
  std::unique_ptr<SceneDrawer> drawer_;
  std::unique_ptr<Technique> technique_;
  uint32_t width_, height_;
  Ref<Texture2D> color_, depth_;
  Ref<RenderTargetView> colorRtv_;
  Ref<DepthStencilView> depthDsv_;
  Ref<VertexShader> litVs_;
  Ref<PixelShader> litPs_, labPs_;
  Ref<InputLayout> litLayout_;
  Ref<RasterizerState> litRasterizer_;
  Ref<Buffer> localLights_;  // cbuffer LocalLights (b6) of the lit pass
  // Lab: position, normal, visibility, lookup, albedo (SV_Target1..5), and the colour's staging copy.
  LabTarget lab_[5];
  Ref<Texture2D> colorStaging_;
  glm::mat4 labViewProj_{1.0f};
  glm::vec3 labCameraPosition_{0.0f};
  GpuTimer* timer_ = nullptr;
};

}  // namespace sp::tech
