// An ImGui context for one test, without a window: a fixed display, no ini file, the font atlas
// built (NewFrame needs it), and no anti-aliasing fringe on filled shapes, so their edges are
// exactly the geometric ones.
#pragma once
#include <imgui.h>

namespace sp::test {

class ImGuiTestContext {
 public:
  ImGuiTestContext(int width, int height) : context_(ImGui::CreateContext()) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = 1.0f / 60.0f;
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ImGui::GetStyle().AntiAliasedFill = false;
  }
  ~ImGuiTestContext() { ImGui::DestroyContext(context_); }
  ImGuiTestContext(const ImGuiTestContext&) = delete;
  ImGuiTestContext& operator=(const ImGuiTestContext&) = delete;

 private:
  ImGuiContext* context_;
};

}  // namespace sp::test
