// The viewer's on-screen panel: technique and parameter choice, what to overlay, per-pass GPU
// times, path recording. It holds no state of its own: the viewer describes what is (PanelState),
// the panel draws ImGui widgets for it between ImGui::NewFrame and ImGui::Render, and reports what
// the user changed (PanelChanges), which the viewer applies. That keeps it testable without a
// window: feed ImGui synthetic mouse input and read the changes.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <imgui.h>
#include <sp/tech/technique.h>

namespace sp::viewer {

struct PanelState {
  std::vector<std::string> techniques;  // registry names
  int technique = 0;                    // index into techniques
  // The current technique's parameters as it declares them, and their current values (text, as
  // tech::ParamValues::all() gives them).
  std::vector<tech::ParamSpec> params;
  std::map<std::string, std::string> values;
  std::vector<std::pair<std::string, double>> gpuMs;  // pass -> ms, in the order to show
  // Whether the viewer can do the overlays below: the toggles are drawn only when it can, so the
  // panel shows no button that does nothing. (The panel's tests draw them all.)
  bool offerOverlays = true;
  // Overlays this build or technique cannot show are named with the reason instead of a toggle:
  // the shadow-map view needs Technique::ShadowMapTexture(), the heat maps need the lab (eval/).
  std::string noShadowMap, noHeatMaps;  // empty: offered
  bool cascadeColours = false;
  bool texelDensity = false;
  bool showShadowMap = false;
  bool errorHeatMap = false;  // traces the reference for the current frame: slow, on demand
  std::string overlayNote;    // what the overlay shows now (trace time, misclassified, stale)
  bool recordingPath = false;
  size_t recordedKeys = 0;
};

struct PanelChanges {
  std::optional<int> technique;
  std::map<std::string, std::string> params;  // name -> new value text, only those changed
  std::optional<bool> cascadeColours, texelDensity, showShadowMap, errorHeatMap, recordingPath;
  bool savePath = false;  // "save path" was pressed

  bool any() const {
    return technique || !params.empty() || cascadeColours || texelDensity || showShadowMap || errorHeatMap || recordingPath || savePath;
  }
};

// Where each widget was drawn (screen pixels), by its label: "technique", a parameter's name, a
// choice as "<combo label>/<choice>" while its list is open, "cascade colours", ... For tests
// (where to click) and for the viewer to keep its mouse away from the panel.
using PanelLayout = std::map<std::string, std::pair<ImVec2, ImVec2>>;

// Draws the panel window (at `pos`, the first time) and returns the user's changes this frame.
PanelChanges DrawPanel(const PanelState& state, PanelLayout* layout = nullptr, ImVec2 pos = ImVec2(8, 8));

}  // namespace sp::viewer
