// Dear ImGui drawn through the RHI: one renderer for both backends (no imgui_impl_vulkan or
// imgui_impl_opengl3), so the panel is drawn by the same sp:: calls as the rest of the viewer and
// the tests can check its pixels on Vulkan and on OpenGL alike.
//
// Colours: ImGui's are sRGB-encoded values meant to reach the screen as they are. On a UNORM
// target they are written unchanged; on an _SRGB target the pixel shader decodes them first, so
// the target's encoding gives the same bytes back (blending then happens on linear values).
#pragma once
#include <imgui.h>
#include <sp/rhi/rhi.h>

namespace sp::viewer {

class ImGuiRenderer {
 public:
  // Needs a current ImGui context: builds its font atlas into a texture and sets the atlas's
  // TexID. rtvFormat: the format of the views Render draws into (UNORM or UNORM_SRGB, 8 bits).
  ImGuiRenderer(Device& device, FORMAT rtvFormat);
  ~ImGuiRenderer();
  ImGuiRenderer(const ImGuiRenderer&) = delete;
  ImGuiRenderer& operator=(const ImGuiRenderer&) = delete;

  // Draws ImGui::GetDrawData() (after ImGui::Render()) over what `rtv` holds. A draw command's
  // ImTextureID is a ShaderResourceView* (a Texture2D the panel shows, e.g. a shadow map) or the
  // font atlas's; TextureId() converts. Binds its own state and leaves it bound. Throws
  // std::invalid_argument when rtv's format is not the one given to the constructor.
  void Render(DeviceContext& ctx, RenderTargetView* rtv, const ImDrawData* drawData);

  static ImTextureID TextureId(ShaderResourceView* srv) { return static_cast<ImTextureID>(srv); }
  ShaderResourceView* FontAtlas() const { return fontSrv_.get(); }
  // Vertex and index capacity of the dynamic buffers (they grow, never shrink).
  uint32_t VertexCapacity() const { return vertexCapacity_; }
  uint32_t IndexCapacity() const { return indexCapacity_; }

 private:
  void Reserve(uint32_t vertices, uint32_t indices);

  Device& device_;
  FORMAT format_;
  Ref<VertexShader> vs_;
  Ref<PixelShader> ps_;
  Ref<InputLayout> layout_;
  Ref<Buffer> constants_, vb_, ib_;
  uint32_t vertexCapacity_ = 0, indexCapacity_ = 0;
  Ref<BlendState> blend_;
  Ref<RasterizerState> rasterizer_;
  Ref<DepthStencilState> depth_;
  Ref<SamplerState> sampler_;
  Ref<Texture2D> font_;
  Ref<ShaderResourceView> fontSrv_;
};

}  // namespace sp::viewer
