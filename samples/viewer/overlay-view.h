// The viewer's overlays at run time (docs/viewer.md, "Overlays"): after the renderer's frame has
// been copied into the back buffer, the chosen overlay's picture replaces it (UpdateSubresource of
// the back buffer), so the panel still draws on top. Every picture is made on the CPU from what
// the GPU wrote, read back that frame:
//  - layers, density: the lab lit pass (the renderer built with RendererOptions::lab) and
//    Renderer::ReadLab every frame: live, at the cost of a full read-back per frame;
//  - error: on demand only. The frame is traced (eval/reference, Embree) once when asked, and the
//    picture is shown until the view changes (camera, light, technique, parameters, size), then
//    dropped with a message;
//  - shadowmap: the technique's ShadowMapTexture() copied to a staging texture each frame.
// density and error need the lab (eval/), present when the viewer is built inside the ShadowPort
// tree (SP_VIEWER_LAB); a viewer built against the installed package offers layers and shadowmap.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <sp/rhi/rhi.h>
#include <sp/scene/scene.h>
#include <sp/tech/renderer.h>

#include "overlay.h"

namespace sp::viewer {

class OverlayView {
 public:
  OverlayView(Device& device, const scene::Scene& scene);
  ~OverlayView();

  Overlay overlay() const { return overlay_; }
  // Switches to `o` (Off: the plain frame; "None" would clash with X11's macro). Error asks for a
  // trace of the next frame; a reason it cannot be shown (this build has no lab) goes to note()
  // and the overlay stays off.
  void Set(Overlay o);
  // Whether the renderer must be built with RendererOptions::lab for the current overlay, and
  // whether this frame's lit pass must be the lab one.
  bool NeedsLabRenderer() const;
  bool NeedsLabPass() const;
  // Writes the overlay's picture over `target` (the back buffer, renderer-sized, sRGB bytes).
  // `viewKey` names everything the picture depends on; a traced heat map is dropped when it changes.
  void Draw(DeviceContext& ctx, tech::Renderer& renderer, Texture2D* target, const scene::DirectionalLight& light,
            const std::string& viewKey);

  // What the panel says about the overlay now ("" for none), and why one cannot be offered
  // ("" when it can): the shadow-map view for this technique, the heat maps in this build.
  const std::string& note() const { return note_; }
  static std::string NoShadowMap(const tech::Technique& technique);
  static std::string NoHeatMaps();
  // The lab buffers of the last frame that read them (null before), for --dump-lab.
  const tech::LabBuffers* lastLab() const { return lab_ ? &*lab_ : nullptr; }

 private:
  void Upload(DeviceContext& ctx, Texture2D* target, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h);
  bool ReadMap(DeviceContext& ctx, Texture2D* map, MapImage* out);
  void Trace(const scene::DirectionalLight& light, const tech::Technique& technique);

  Device& device_;
  const scene::Scene& scene_;
  Overlay overlay_ = Overlay::Off;
  std::string note_;
  std::optional<tech::LabBuffers> lab_;
  // error: the traced picture, the view it shows, and whether a trace is wanted.
  bool tracePending_ = false;
  std::vector<uint8_t> heatMap_;
  std::string tracedKey_;
  // shadowmap: the staging copy of the map, remade when the map changes.
  Ref<Texture2D> mapStaging_;
  Texture2D* mapSource_ = nullptr;
  struct Lab;  // the tracer (eval/reference) where the lab is built in
  std::unique_ptr<Lab> labImpl_;
};

}  // namespace sp::viewer
