// The viewer's panel without a window: synthetic mouse input (io.MousePos, io.MouseDown) clicks
// its widgets where the panel says it drew them, and the panel reports exactly the change made:
// a toggle, a technique, a parameter choice, a slider's value, saving a recorded path (refused
// below two keys); frames without input, or with clicks outside the panel, report nothing.
#include <gtest/gtest.h>

#include "imgui-test-context.h"
#include "panel.h"

namespace sp::test {
namespace {

using viewer::PanelChanges;
using viewer::PanelLayout;
using viewer::PanelState;

PanelState State() {
  PanelState s;
  s.techniques = {"basic", "csm", "sdsm"};
  s.technique = 0;
  s.params = {{tech::ParamSpec::Int, "resolution", "shadow map size", "2048", 16, 4096, {}},
              {tech::ParamSpec::Choice, "filter", "shadow filter", "pcf", 0, 0, {"none", "pcf", "gauss"}},
              {tech::ParamSpec::Float, "slope_bias", "slope-scaled bias", "2", 0, 10, {}},
              {tech::ParamSpec::Text, "splits", "cascade splits", "", 0, 0, {}}};
  s.values = {{"resolution", "1024"}, {"filter", "pcf"}, {"slope_bias", "2"}, {"splits", "0.1:0.3"}};
  s.gpuMs = {{"shadow", 0.75}, {"lit", 1.5}, {"total", 2.25}};
  return s;
}

class PanelTest : public ::testing::Test {
 protected:
  // One frame with the mouse at `pos`, the left button down or not; changes are merged over frames.
  PanelChanges Frame(const PanelState& s, ImVec2 pos, bool down) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = pos;
    io.MouseDown[0] = down;
    ImGui::NewFrame();
    layout_.clear();
    PanelChanges c = viewer::DrawPanel(s, &layout_);
    ImGui::Render();
    return c;
  }
  static void Merge(PanelChanges& into, const PanelChanges& c) {
    if (c.technique) into.technique = c.technique;
    for (const auto& [k, v] : c.params) into.params[k] = v;
    if (c.cascadeColours) into.cascadeColours = c.cascadeColours;
    if (c.texelDensity) into.texelDensity = c.texelDensity;
    if (c.showShadowMap) into.showShadowMap = c.showShadowMap;
    if (c.errorHeatMap) into.errorHeatMap = c.errorHeatMap;
    if (c.recordingPath) into.recordingPath = c.recordingPath;
    into.savePath |= c.savePath;
  }
  // Moves there, presses and releases the button (as a user would over three frames).
  PanelChanges ClickAt(const PanelState& s, ImVec2 p) {
    PanelChanges all;
    for (bool down : {false, true, false}) Merge(all, Frame(s, p, down));
    return all;
  }
  ImVec2 Where(const std::string& label, float fx = 0.5f) {
    auto it = layout_.find(label);
    EXPECT_NE(it, layout_.end()) << "the panel drew no '" << label << "'";
    if (it == layout_.end()) return ImVec2(-100, -100);
    const auto& [lo, hi] = it->second;
    return ImVec2(lo.x + (hi.x - lo.x) * fx, (lo.y + hi.y) * 0.5f);
  }
  PanelChanges Click(const PanelState& s, const std::string& label, float fx = 0.5f) { return ClickAt(s, Where(label, fx)); }
  // Opens a combo's list: a popup is laid out for real from its second frame (ImGui measures it
  // hidden on the first), so one more frame before its items' places are read.
  PanelChanges Open(const PanelState& s, const std::string& label) {
    ImVec2 p = Where(label);
    PanelChanges c = ClickAt(s, p);
    Merge(c, Frame(s, p, false));
    return c;
  }

  ImGuiTestContext imgui_{800, 600};
  PanelLayout layout_;
};

TEST_F(PanelTest, NoInputChangesNothing) {
  PanelState s = State();
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(Frame(s, ImVec2(-1, -1), false).any()) << "frame " << i;
  // A click far from the panel is the viewer's, not the panel's.
  EXPECT_FALSE(ClickAt(s, ImVec2(700, 550)).any());
  for (const char* w : {"technique", "resolution", "filter", "slope_bias", "splits", "cascade colours", "show shadow map",
                        "texel density", "error heat map (traces the reference)", "record camera path", "save path"})
    EXPECT_TRUE(layout_.count(w)) << w;
}

TEST_F(PanelTest, ClickingAToggleReportsItAlone) {
  PanelState s = State();
  Frame(s, ImVec2(-1, -1), false);
  PanelChanges c = Click(s, "cascade colours", 0.05f);
  ASSERT_TRUE(c.cascadeColours.has_value());
  EXPECT_TRUE(*c.cascadeColours);
  EXPECT_FALSE(c.showShadowMap || c.texelDensity || c.errorHeatMap || c.technique || c.recordingPath || c.savePath);
  EXPECT_TRUE(c.params.empty());
  // The viewer applied it: clicking again turns it off.
  s.cascadeColours = true;
  c = Click(s, "cascade colours", 0.05f);
  ASSERT_TRUE(c.cascadeColours.has_value());
  EXPECT_FALSE(*c.cascadeColours);
  c = Click(s, "error heat map (traces the reference)", 0.05f);
  EXPECT_EQ(c.errorHeatMap, std::optional<bool>(true));
  EXPECT_FALSE(c.cascadeColours.has_value());
}

// An overlay the viewer cannot show is named with its reason instead of a toggle that does nothing.
TEST_F(PanelTest, UnavailableOverlaysAreNotOffered) {
  PanelState s = State();
  s.noShadowMap = "psm exposes no shadow-map texture";
  s.noHeatMaps = "built without the lab";
  Frame(s, ImVec2(-1, -1), false);
  EXPECT_TRUE(layout_.count("cascade colours"));
  for (const char* w : {"show shadow map", "texel density", "error heat map (traces the reference)"}) EXPECT_FALSE(layout_.count(w)) << w;
  s = State();
  Frame(s, ImVec2(-1, -1), false);
  PanelChanges c = Click(s, "texel density", 0.05f);
  EXPECT_EQ(c.texelDensity, std::optional<bool>(true));
  EXPECT_FALSE(c.cascadeColours || c.showShadowMap || c.errorHeatMap);
}

TEST_F(PanelTest, PickingATechniqueAndAChoiceReportsThem) {
  PanelState s = State();
  Frame(s, ImVec2(-1, -1), false);
  EXPECT_FALSE(Open(s, "technique").any()) << "opening the list changes nothing";
  PanelChanges c = Click(s, "technique/sdsm");
  EXPECT_EQ(c.technique, std::optional<int>(2));
  EXPECT_TRUE(c.params.empty());

  Frame(s, ImVec2(-1, -1), false);
  Open(s, "filter");
  c = Click(s, "filter/gauss");
  EXPECT_FALSE(c.technique.has_value());
  ASSERT_EQ(c.params.size(), 1u);
  EXPECT_EQ(c.params["filter"], "gauss");
}

TEST_F(PanelTest, SlidersReportValuesInTheirRange) {
  PanelState s = State();
  Frame(s, ImVec2(-1, -1), false);
  // The slider's right end is its maximum, its left end its minimum (AlwaysClamp).
  PanelChanges c = Click(s, "resolution", 0.999f);
  EXPECT_EQ(c.params["resolution"], "4096");
  c = Click(s, "slope_bias", 0.001f);
  EXPECT_EQ(c.params["slope_bias"], "0");
}

TEST_F(PanelTest, SavingAPathNeedsTwoKeys) {
  PanelState s = State();
  s.recordingPath = true;
  s.recordedKeys = 1;
  Frame(s, ImVec2(-1, -1), false);
  EXPECT_FALSE(Click(s, "save path").savePath) << "one key is no path";
  s.recordedKeys = 120;
  Frame(s, ImVec2(-1, -1), false);
  PanelChanges c = Click(s, "save path");
  EXPECT_TRUE(c.savePath);
  EXPECT_FALSE(c.recordingPath.has_value());
  c = Click(s, "record camera path", 0.05f);
  EXPECT_EQ(c.recordingPath, std::optional<bool>(false));
}

}  // namespace
}  // namespace sp::test
