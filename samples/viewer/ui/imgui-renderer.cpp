// ImGui's draw data through sp:: (see imgui-renderer.h): all command lists of a frame go into one
// dynamic vertex and index buffer (mapped WRITE_DISCARD, grown when a frame needs more), one
// DrawIndexed per command with its clip rectangle as the scissor.
#include "imgui-renderer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <sp/tech/technique.h>

namespace sp::viewer {
namespace {

struct FrameConstants {
  float scale[2];
  float offset[2];
};

// D3D11's rule for what an _SRGB view writes: the shader's value is encoded (imgui.hlsl decodes).
bool IsSrgb(FORMAT f) { return GetFormatInfo(f).kind == FormatKind::UNormSRGB; }

}  // namespace

ImGuiRenderer::ImGuiRenderer(Device& device, FORMAT rtvFormat) : device_(device), format_(rtvFormat) {
  if (!ImGui::GetCurrentContext()) throw std::logic_error("ImGuiRenderer: no current ImGui context (call ImGui::CreateContext first)");
  const FormatInfo& info = GetFormatInfo(rtvFormat);
  if (!(info.kind == FormatKind::UNorm || info.kind == FormatKind::UNormSRGB) || info.components != 4)
    throw std::invalid_argument("ImGuiRenderer: rtvFormat " + std::string(FormatName(rtvFormat)) +
                                " is not a 4-component UNORM or UNORM_SRGB format");
  static_assert(sizeof(ImDrawIdx) == 2, "the index buffer is FORMAT_R16_UINT: build ImGui with 16-bit ImDrawIdx");
  static_assert(sizeof(ImDrawVert) == 20, "the input layout below is ImDrawVert's default layout");

  const char* file = "viewer/imgui.hlsl";
  ShaderBytecode vsCode = tech::CompileTechniqueShader(file, "vs_5_0", "VSMain");
  vs_ = device.CreateVertexShader(vsCode);
  ps_ = device.CreatePixelShader(tech::CompileTechniqueShader(file, "ps_5_0", "PSMain", {{"SRGB_TARGET", IsSrgb(rtvFormat) ? "1" : "0"}}));
  const INPUT_ELEMENT_DESC elements[] = {
      {"POSITION", 0, FORMAT_R32G32_FLOAT, 0, uint32_t(offsetof(ImDrawVert, pos)), INPUT_PER_VERTEX_DATA, 0},
      {"TEXCOORD", 0, FORMAT_R32G32_FLOAT, 0, uint32_t(offsetof(ImDrawVert, uv)), INPUT_PER_VERTEX_DATA, 0},
      {"COLOR", 0, FORMAT_R8G8B8A8_UNORM, 0, uint32_t(offsetof(ImDrawVert, col)), INPUT_PER_VERTEX_DATA, 0},
  };
  layout_ = device.CreateInputLayout(elements, 3, vsCode);

  constants_ = tech::MakeConstantBuffer(device, sizeof(FrameConstants), "imgui frame constants");

  // What ImGui's own backends set: straight (not premultiplied) alpha for colour, and the
  // destination's alpha kept meaningful for a target that is later composed.
  BLEND_DESC bd;
  RENDER_TARGET_BLEND_DESC& rt = bd.RenderTarget[0];
  rt.BlendEnable = true;
  rt.SrcBlend = BLEND_SRC_ALPHA;
  rt.DestBlend = BLEND_INV_SRC_ALPHA;
  rt.BlendOp = BLEND_OP_ADD;
  rt.SrcBlendAlpha = BLEND_ONE;
  rt.DestBlendAlpha = BLEND_INV_SRC_ALPHA;
  rt.BlendOpAlpha = BLEND_OP_ADD;
  blend_ = device.CreateBlendState(bd);

  RASTERIZER_DESC rd;
  rd.CullMode = CULL_NONE;  // ImGui emits both windings
  rd.ScissorEnable = true;
  rasterizer_ = device.CreateRasterizerState(rd);

  DEPTH_STENCIL_DESC dd;
  dd.DepthEnable = false;
  dd.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  depth_ = device.CreateDepthStencilState(dd);

  SAMPLER_DESC sd;
  sd.Filter = FILTER_MIN_MAG_MIP_LINEAR;
  sd.AddressU = sd.AddressV = sd.AddressW = TEXTURE_ADDRESS_CLAMP;
  sampler_ = device.CreateSamplerState(sd);

  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  TEXTURE2D_DESC td;
  td.Width = uint32_t(w);
  td.Height = uint32_t(h);
  td.Format = FORMAT_R8G8B8A8_UNORM;
  td.Usage = USAGE_IMMUTABLE;
  td.BindFlags = BIND_SHADER_RESOURCE;
  SUBRESOURCE_DATA init{pixels, uint32_t(w) * 4, 0};
  font_ = device.CreateTexture2D(td, &init);
  font_->SetDebugName("imgui font atlas");
  fontSrv_ = device.CreateShaderResourceView(font_.get());
  io.Fonts->SetTexID(TextureId(fontSrv_.get()));
  io.BackendRendererName = "shadowport-rhi";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // DrawIndexed's base vertex
}

ImGuiRenderer::~ImGuiRenderer() {
  // The atlas may outlive this renderer (the context does); it must not point at a freed view.
  if (ImGui::GetCurrentContext() && ImGui::GetIO().Fonts->TexID == TextureId(fontSrv_.get())) ImGui::GetIO().Fonts->SetTexID(nullptr);
}

void ImGuiRenderer::Reserve(uint32_t vertices, uint32_t indices) {
  // Grow with headroom so a panel that opens one more widget does not reallocate every frame.
  if (vertices > vertexCapacity_) {
    vertexCapacity_ = std::max(vertices + vertices / 2, 4096u);
    vb_ = tech::MakeDynamicBuffer(device_, vertexCapacity_ * uint32_t(sizeof(ImDrawVert)), BIND_VERTEX_BUFFER, "imgui vertices");
  }
  if (indices > indexCapacity_) {
    indexCapacity_ = std::max(indices + indices / 2, 8192u);
    ib_ = tech::MakeDynamicBuffer(device_, indexCapacity_ * uint32_t(sizeof(ImDrawIdx)), BIND_INDEX_BUFFER, "imgui indices");
  }
}

void ImGuiRenderer::Render(DeviceContext& ctx, RenderTargetView* rtv, const ImDrawData* dd) {
  if (!rtv) throw std::invalid_argument("ImGuiRenderer::Render: no render target view");
  if (rtv->ViewFormat() != format_)
    throw std::invalid_argument("ImGuiRenderer::Render: the render target view is " + std::string(FormatName(rtv->ViewFormat())) +
                                " but the renderer was made for " + std::string(FormatName(format_)));
  if (!dd || dd->TotalVtxCount == 0 || dd->CmdListsCount == 0) return;
  const float fbW = dd->DisplaySize.x * dd->FramebufferScale.x, fbH = dd->DisplaySize.y * dd->FramebufferScale.y;
  if (fbW <= 0.0f || fbH <= 0.0f) return;

  Reserve(uint32_t(dd->TotalVtxCount), uint32_t(dd->TotalIdxCount));
  MAPPED_SUBRESOURCE mv, mi;
  ctx.Map(vb_.get(), 0, MAP_WRITE_DISCARD, 0, &mv);
  ctx.Map(ib_.get(), 0, MAP_WRITE_DISCARD, 0, &mi);
  auto* vdst = static_cast<ImDrawVert*>(mv.pData);
  auto* idst = static_cast<ImDrawIdx*>(mi.pData);
  for (int n = 0; n < dd->CmdListsCount; ++n) {
    const ImDrawList* list = dd->CmdLists[n];
    std::memcpy(vdst, list->VtxBuffer.Data, size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    std::memcpy(idst, list->IdxBuffer.Data, size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
    vdst += list->VtxBuffer.Size;
    idst += list->IdxBuffer.Size;
  }
  ctx.Unmap(vb_.get(), 0);
  ctx.Unmap(ib_.get(), 0);

  // Pixels of the display (DisplayPos at the top left) to clip space, y down the screen.
  const float L = dd->DisplayPos.x, T = dd->DisplayPos.y, W = dd->DisplaySize.x, H = dd->DisplaySize.y;
  FrameConstants c{{2.0f / W, -2.0f / H}, {-1.0f - 2.0f * L / W, 1.0f + 2.0f * T / H}};
  ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

  auto setupState = [&] {
    VIEWPORT vp{0, 0, fbW, fbH, 0, 1};
    ctx.RSSetViewports(1, &vp);
    ctx.OMSetRenderTargets(1, &rtv, nullptr);
    const uint32_t stride = sizeof(ImDrawVert), offset = 0;
    Buffer* vb = vb_.get();
    ctx.IASetInputLayout(layout_.get());
    ctx.IASetVertexBuffers(0, 1, &vb, &stride, &offset);
    ctx.IASetIndexBuffer(ib_.get(), FORMAT_R16_UINT, 0);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.VSSetShader(vs_.get());
    ctx.VSSetConstantBuffers(0, {constants_.get()});
    ctx.PSSetShader(ps_.get());
    ctx.PSSetSamplers(0, {sampler_.get()});
    ctx.GSSetShader(nullptr);
    const float blendFactor[4] = {0, 0, 0, 0};
    ctx.OMSetBlendState(blend_.get(), blendFactor, 0xffffffffu);
    ctx.OMSetDepthStencilState(depth_.get(), 0);
    ctx.RSSetState(rasterizer_.get());
  };
  setupState();

  int32_t vtxBase = 0;
  uint32_t idxBase = 0;
  const ImVec2 clipOff = dd->DisplayPos, clipScale = dd->FramebufferScale;
  for (int n = 0; n < dd->CmdListsCount; ++n) {
    const ImDrawList* list = dd->CmdLists[n];
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      if (cmd.UserCallback) {
        if (cmd.UserCallback == ImDrawCallback_ResetRenderState) setupState();
        else cmd.UserCallback(list, &cmd);
        continue;
      }
      // The clip rectangle in target pixels, clamped to the target (a scissor outside it is
      // invalid on Vulkan); nothing to draw when it is empty.
      float x0 = std::max((cmd.ClipRect.x - clipOff.x) * clipScale.x, 0.0f), y0 = std::max((cmd.ClipRect.y - clipOff.y) * clipScale.y, 0.0f);
      float x1 = std::min((cmd.ClipRect.z - clipOff.x) * clipScale.x, fbW), y1 = std::min((cmd.ClipRect.w - clipOff.y) * clipScale.y, fbH);
      if (x1 <= x0 || y1 <= y0) continue;
      RECT r{int32_t(x0), int32_t(y0), int32_t(x1), int32_t(y1)};
      ctx.RSSetScissorRects(1, &r);
      ShaderResourceView* srv = static_cast<ShaderResourceView*>(cmd.GetTexID());
      if (!srv) srv = fontSrv_.get();
      ctx.PSSetShaderResources(0, {srv});
      ctx.DrawIndexed(cmd.ElemCount, cmd.IdxOffset + idxBase, int32_t(cmd.VtxOffset) + vtxBase);
    }
    idxBase += uint32_t(list->IdxBuffer.Size);
    vtxBase += list->VtxBuffer.Size;
  }
}

}  // namespace sp::viewer
