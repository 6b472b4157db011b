// The viewer's panel (panel.h). Values are shown from PanelState every frame and a change is
// reported the frame it happens (a slider while it is dragged too): the viewer decides when to
// reconfigure.
#include "panel.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace sp::viewer {
namespace {

class Drawer {
 public:
  explicit Drawer(PanelLayout* layout) : layout_(layout) {}

  // framed: a widget with its label beside it (combo, slider, field), whose rectangle would take
  // the label in; noted is the frame alone, so its fractions are the slider's.
  void note(const std::string& label, bool framed = false) {
    if (!layout_) return;
    ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    if (framed) hi.x = std::min(hi.x, lo.x + ImGui::CalcItemWidth());
    (*layout_)[label] = {lo, hi};
  }
  static void help(const std::string& text) {
    if (!text.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
  }
  // A combo over `choices`; returns the index picked this frame, if any.
  std::optional<int> combo(const std::string& label, const std::vector<std::string>& choices, int current) {
    std::optional<int> picked;
    const char* preview = current >= 0 && size_t(current) < choices.size() ? choices[size_t(current)].c_str() : "";
    bool open = ImGui::BeginCombo(label.c_str(), preview);
    note(label, true);
    if (!open) return picked;
    for (size_t i = 0; i < choices.size(); ++i) {
      ImGui::PushID(int(i));
      if (ImGui::Selectable(choices[i].c_str(), int(i) == current) && int(i) != current) picked = int(i);
      note(label + "/" + choices[i]);
      ImGui::PopID();
    }
    ImGui::EndCombo();
    return picked;
  }
  std::optional<bool> checkbox(const char* label, bool value) {
    bool v = value;
    bool changed = ImGui::Checkbox(label, &v);
    note(label);
    return changed ? std::optional<bool>(v) : std::nullopt;
  }

 private:
  PanelLayout* layout_;
};

// One parameter's widget; returns the new value text when the user changed it.
std::optional<std::string> ParamWidget(Drawer& d, const tech::ParamSpec& p, const std::string& value) {
  const char* label = p.name.c_str();
  std::optional<std::string> out;
  switch (p.kind) {
    case tech::ParamSpec::Choice: {
      int current = -1;
      for (size_t i = 0; i < p.choices.size(); ++i)
        if (p.choices[i] == value) current = int(i);
      if (std::optional<int> i = d.combo(p.name, p.choices, current)) out = p.choices[size_t(*i)];
      Drawer::help(p.help);
      return out;
    }
    case tech::ParamSpec::Int: {
      int v = std::atoi(value.c_str());
      bool changed = p.max > p.min ? ImGui::SliderInt(label, &v, int(p.min), int(p.max), "%d", ImGuiSliderFlags_AlwaysClamp)
                                   : ImGui::InputInt(label, &v);
      if (changed) out = std::to_string(v);
      break;
    }
    case tech::ParamSpec::Float: {
      float v = float(std::atof(value.c_str()));
      bool changed = p.max > p.min ? ImGui::SliderFloat(label, &v, float(p.min), float(p.max), "%.4g", ImGuiSliderFlags_AlwaysClamp)
                                   : ImGui::InputFloat(label, &v, 0.0f, 0.0f, "%.4g");
      if (changed) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", double(v));
        out = text;
      }
      break;
    }
    case tech::ParamSpec::Text: {
      // Applied on Enter: a half-typed list (splits=0.1:0.) is not a value to configure with.
      char text[256];
      std::snprintf(text, sizeof text, "%s", value.c_str());
      if (ImGui::InputText(label, text, sizeof text, ImGuiInputTextFlags_EnterReturnsTrue)) out = std::string(text);
      break;
    }
  }
  d.note(p.name, true);
  Drawer::help(p.help);
  return out;
}

}  // namespace

PanelChanges DrawPanel(const PanelState& s, PanelLayout* layout, ImVec2 pos) {
  PanelChanges c;
  Drawer d(layout);
  ImGui::SetNextWindowPos(pos, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("ShadowPort")) {
    ImGui::End();
    return c;
  }
  c.technique = d.combo("technique", s.techniques, s.technique);

  if (!s.params.empty() && ImGui::CollapsingHeader("parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const tech::ParamSpec& p : s.params) {
      auto it = s.values.find(p.name);
      ImGui::PushID(p.name.c_str());
      if (std::optional<std::string> v = ParamWidget(d, p, it != s.values.end() ? it->second : p.defaultValue)) c.params[p.name] = *v;
      ImGui::PopID();
    }
  }

  if (s.offerOverlays && ImGui::CollapsingHeader("show", ImGuiTreeNodeFlags_DefaultOpen)) {
    c.cascadeColours = d.checkbox("cascade colours", s.cascadeColours);
    if (s.noShadowMap.empty())
      c.showShadowMap = d.checkbox("show shadow map", s.showShadowMap);
    else
      ImGui::TextDisabled("no map view: %s", s.noShadowMap.c_str());
    if (s.noHeatMaps.empty()) {
      c.texelDensity = d.checkbox("texel density", s.texelDensity);
      c.errorHeatMap = d.checkbox("error heat map (traces the reference)", s.errorHeatMap);
    } else {
      ImGui::TextDisabled("no heat maps: %s", s.noHeatMaps.c_str());
    }
    if (!s.overlayNote.empty()) ImGui::TextWrapped("%s", s.overlayNote.c_str());
  }

  if (!s.gpuMs.empty() && ImGui::CollapsingHeader("GPU time per pass", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const auto& [pass, ms] : s.gpuMs) ImGui::Text("%-12s %8.3f ms", pass.c_str(), ms);
  }

  if (ImGui::CollapsingHeader("camera path", ImGuiTreeNodeFlags_DefaultOpen)) {
    c.recordingPath = d.checkbox("record camera path", s.recordingPath);
    ImGui::Text("%zu keys", s.recordedKeys);
    // A path needs two keys (scene::CameraPathRecorder::path).
    ImGui::BeginDisabled(s.recordedKeys < 2);
    c.savePath = ImGui::Button("save path");
    d.note("save path");
    ImGui::EndDisabled();
  }
  ImGui::End();
  return c;
}

}  // namespace sp::viewer
