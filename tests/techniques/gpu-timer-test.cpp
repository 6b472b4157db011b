// GpuTimer: a frame yields the passes techniques and the renderer time plus the frame total, each
// frame is returned once, results are held back at most kMaxFramesInFlight frames, and misuse
// (unbalanced or nested passes, frames) throws instead of measuring nonsense.
#include "backend-test.h"
#include "technique-renderer.h"
#include <sp/tech/renderer.h>

namespace sp::test {
namespace {

class GpuTimerTest : public BackendTest {};

TEST_P(GpuTimerTest, RendererFramesReportShadowLitAndTotal) {
  scene::Scene s = scene::MakeBuiltinScene("default");
  tech::Renderer r(device(), s, MakeConfiguredTechnique(device(), "basic", {{"resolution", "256"}}), 64, 64);
  tech::GpuTimer timer(device());
  r.SetGpuTimer(&timer);
  const int frames = 5;
  size_t early = 0;
  for (int i = 0; i < frames; ++i) {
    r.RenderFrame(s.camera, s.light);
    early += timer.Collect(ctx(), false).size();
  }
  ctx().WaitIdle();
  std::vector<tech::FrameTimes> rest = timer.Collect(ctx(), true);
  EXPECT_EQ(early + rest.size(), size_t(frames)) << "every frame once";
  EXPECT_GE(early, size_t(frames) - tech::GpuTimer::kMaxFramesInFlight) << "at most kMaxFramesInFlight frames held back";
  for (const tech::FrameTimes& f : rest) {
    ASSERT_TRUE(f.count("shadow") && f.count("lit") && f.count("total"));
    EXPECT_GE(f.at("shadow"), 0.0);
    EXPECT_GT(f.at("total"), 0.0);
    EXPECT_GE(f.at("total"), f.at("lit"));
    EXPECT_GE(f.at("total"), f.at("shadow"));
  }
  EXPECT_TRUE(timer.Collect(ctx(), true).empty());
  EXPECT_EQ(timer.DisjointFrames(), 0u);
}

SP_INSTANTIATE_BACKEND_TESTS(GpuTimerTest);

// Misuse refused, no times checked: these run on the null backend too.
class GpuTimerValidationTest : public GpuTimerTest {};

TEST_P(GpuTimerValidationTest, RepeatedPassesSumAndMisuseThrows) {
  tech::GpuTimer timer(device());
  EXPECT_THROW(timer.Begin(ctx(), "shadow"), std::logic_error) << "outside a frame";
  timer.BeginFrame(ctx());
  for (int cascade = 0; cascade < 3; ++cascade) {
    tech::GpuTimer::Scope s(&timer, ctx(), "shadow");
  }
  timer.Begin(ctx(), "blur");
  EXPECT_THROW(timer.Begin(ctx(), "blur"), std::logic_error) << "nested under one name";
  EXPECT_THROW(timer.EndFrame(ctx()), std::logic_error) << "a pass still running";
  timer.End(ctx(), "blur");
  EXPECT_THROW(timer.End(ctx(), "blur"), std::logic_error) << "ended twice";
  EXPECT_THROW(timer.BeginFrame(ctx()), std::logic_error) << "frame not ended";
  timer.EndFrame(ctx());
  std::vector<tech::FrameTimes> t = timer.Collect(ctx(), true);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].size(), 3u) << "shadow (three spans summed), blur, total";
  EXPECT_TRUE(t[0].count("shadow") && t[0].count("blur") && t[0].count("total"));
  // A null timer makes scopes free.
  tech::GpuTimer::Scope none(nullptr, ctx(), "shadow");
}

SP_INSTANTIATE_VALIDATION_TESTS(GpuTimerValidationTest);

}  // namespace
}  // namespace sp::test
