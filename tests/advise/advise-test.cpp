// shadowport advise without a GPU: budgets, the search space from ParamSpecs, the Pareto front and
// the choice under timing noise, on synthetic measurements.
#include <gtest/gtest.h>

#include "advise.h"

namespace sp::advise {
namespace {

Measurement M(const std::string& tech, const std::string& res, double ms, double mib, double mis, double flicker = 0) {
  Measurement m;
  m.config = {tech, {{"resolution", res}}};
  m.metrics = {{"ms", ms}, {"memory", mib}, {"misclassified", mis}, {"false_lit", mis / 2}, {"false_shadow", mis / 2},
               {"mean_abs_error", mis / 100}, {"flicker", flicker}};
  return m;
}

SelectOptions Opts(double budget, Minimize min = Minimize::Ms, double noise = 0.15) {
  SelectOptions o;
  o.budgets = {{"misclassified", budget}};
  o.minimize = min;
  o.noise = noise;
  return o;
}

TEST(AdviseBudget, ParsesMetricAndValue) {
  Budget b = ParseBudget("misclassified=0.2");
  EXPECT_EQ(b.metric, "misclassified");
  EXPECT_DOUBLE_EQ(b.limit, 0.2);
  EXPECT_DOUBLE_EQ(ParseBudget("flicker=1e-4").limit, 1e-4);
  EXPECT_DOUBLE_EQ(ParseBudget("ms=30").limit, 30.0);
}

TEST(AdviseBudget, RejectsMalformedAndUnknownNamingThem) {
  auto message = [](const std::string& text) {
    try {
      ParseBudget(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message("misclassified").find("is not metric=value"), std::string::npos);
  EXPECT_NE(message("=3").find("is not metric=value"), std::string::npos);
  EXPECT_NE(message("misclassified=").find("is not metric=value"), std::string::npos);
  EXPECT_NE(message("acne=1").find("unknown metric 'acne' (valid: misclassified, false_lit"), std::string::npos);
  EXPECT_NE(message("misclassified=abc").find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(message("misclassified=0.2x").find("'0.2x' is not a number"), std::string::npos);
  EXPECT_NE(message("misclassified=-1").find("is not a number >= 0"), std::string::npos);
}

TEST(AdviseSelect, CheapestMeetingTheBudgetUnderMemory) {
  std::vector<Measurement> all = {M("a", "512", 5, 1, 2.0), M("a", "1024", 6, 4, 0.8), M("a", "2048", 9, 16, 0.3),
                                  M("b", "1024", 20, 8, 0.25), M("b", "4096", 40, 64, 0.1)};
  Selection s = Select(all, Opts(0.5, Minimize::Memory));
  ASSERT_TRUE(s.best);
  EXPECT_EQ(*s.best, 3u);  // 8 MiB at 0.25 %: b beats a's 16 MiB
  ASSERT_TRUE(s.cheaperMiss);
  EXPECT_EQ(*s.cheaperMiss, 1u);  // 4 MiB, 0.8 %: the dearest that is cheaper and misses
  std::vector<size_t> front = ParetoFront(all, Opts(0.5, Minimize::Memory));
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3, 4}));  // 2048 (16 MiB, 0.3) is dominated by b 1024
}

TEST(AdviseSelect, TimingsWithinTheNoiseMarginAreTiesWonByLessMemory) {
  std::vector<Measurement> all = {M("a", "2048", 10.0, 16, 0.3), M("a", "1024", 11.0, 4, 0.4), M("a", "512", 14.0, 1, 0.45)};
  Selection s = Select(all, Opts(0.5, Minimize::Ms, 0.15));
  ASSERT_TRUE(s.best);
  EXPECT_EQ(*s.best, 1u);  // 11 ms is within 15 % of 10 ms: a tie, 4 MiB beats 16
  s = Select(all, Opts(0.5, Minimize::Ms, 0.0));
  EXPECT_EQ(*s.best, 0u);  // no margin: the fastest
  EXPECT_TRUE(Cheaper(all[0], all[2], Opts(0.5)));
  EXPECT_FALSE(Cheaper(all[0], all[1], Opts(0.5)));
}

TEST(AdviseSelect, EveryBudgetMustHold) {
  std::vector<Measurement> all = {M("a", "512", 5, 1, 0.1, 0.01), M("a", "1024", 8, 4, 0.2, 0.0)};
  SelectOptions o = Opts(0.5);
  o.budgets.push_back({"flicker", 1e-3});
  Selection s = Select(all, o);
  ASSERT_TRUE(s.best);
  EXPECT_EQ(*s.best, 1u);
}

TEST(AdviseSelect, ImpossibleBudgetGivesTheClosest) {
  std::vector<Measurement> all = {M("a", "512", 5, 1, 2.0), M("a", "1024", 6, 4, 0.8), M("a", "2048", 9, 16, 0.6), M("a", "4096", 20, 64, 3)};
  Selection s = Select(all, Opts(0.1));
  EXPECT_FALSE(s.best);
  EXPECT_FALSE(s.cheaperMiss);
  EXPECT_EQ(s.closest, (std::vector<size_t>{2, 1, 0}));
}

TEST(AdviseSelect, AConfigurationThatRenderedTheSameAsAnEarlierOneIsLeftOut) {
  std::vector<Measurement> all = {M("a", "1024", 30, 4, 0.2), M("a", "1024k5", 12, 4, 0.2), M("a", "2048", 25, 16, 0.1)};
  all[1].sameAs = 0;  // e.g. kernel=5 under the hardware 2x2 filter: only noise makes it "faster"
  Selection s = Select(all, Opts(0.5));
  ASSERT_TRUE(s.best);
  EXPECT_EQ(*s.best, 2u);  // not the duplicate's 12 ms; 30 ms is beyond 15 % of 25 ms
  EXPECT_EQ(ParetoFront(all, Opts(0.5)), (std::vector<size_t>{2}));
  all[1].sameAs.reset();
  EXPECT_EQ(*Select(all, Opts(0.5)).best, 1u);
}

TEST(AdviseSelect, DeterministicOnExactTies) {
  std::vector<Measurement> all = {M("b", "512", 5, 1, 0.1), M("a", "512", 5, 1, 0.1)};
  Selection s = Select(all, Opts(0.5, Minimize::Memory));
  EXPECT_EQ(*s.best, 1u);  // same cost and error: the config text decides
}

std::vector<tech::ParamSpec> Specs() {
  using P = tech::ParamSpec;
  return {
      {P::Int, "cascades", "", "4", 1, 8, {}},
      {P::Choice, "filter", "", "hw2x2", 0, 0, {"hw2x2", "box", "gauss"}},
      {P::Int, "resolution", "", "1024", 16, 2048, {}},
      {P::Int, "depth_bias", "", "100", -1e7, 1e7, {}},
      {P::Text, "splits", "", "", 0, 0, {}},
  };
}

TEST(AdviseSpace, AxesComeFromTheParamSpecs) {
  std::vector<Axis> axes = AxesFor("t", Specs(), {"resolution", "cascades", "filter", "kernel", "depth_bias"});
  ASSERT_EQ(axes.size(), 4u);  // no kernel declared
  EXPECT_EQ(axes[0].name, "resolution");
  EXPECT_EQ(axes[0].values, (std::vector<std::string>{"256", "384", "512", "768", "1024", "1536", "2048"}));  // capped by max
  EXPECT_EQ(axes[0].coarse, (std::vector<std::string>{"512", "1024", "2048"}));
  EXPECT_EQ(axes[1].values, (std::vector<std::string>{"1", "2", "3", "4"}));
  EXPECT_EQ(axes[1].coarse, (std::vector<std::string>{"1", "2", "4"}));
  EXPECT_EQ(axes[2].values, (std::vector<std::string>{"hw2x2", "box", "gauss"}));
  EXPECT_EQ(axes[2].coarse, (std::vector<std::string>{"hw2x2"}));
  EXPECT_EQ(axes[3].values, (std::vector<std::string>{"25", "50", "100", "200", "400"}));
  EXPECT_THROW(AxesFor("t", Specs(), {"splits"}), std::invalid_argument);
  EXPECT_EQ(CoarseGrid("t", axes).size(), 3u * 3u);
  EXPECT_EQ(FullGrid("t", axes).size(), 7u * 4u * 3u * 5u);
}

TEST(AdviseSpace, NeighboursAreOneLatticeStepAlongOneAxis) {
  std::vector<Axis> axes = AxesFor("t", Specs(), {"resolution", "filter"});
  Config c{"t", {{"resolution", "1024"}, {"filter", "hw2x2"}}};
  std::vector<Config> n = Neighbours(c, axes);
  ASSERT_EQ(n.size(), 4u);  // 768, 1536; filter names have no order: every other one
  EXPECT_EQ(n[0].params.at("resolution"), "768");
  EXPECT_EQ(n[1].params.at("resolution"), "1536");
  EXPECT_EQ(n[2].params.at("filter"), "box");
  EXPECT_EQ(n[3].params.at("filter"), "gauss");
  using P = tech::ParamSpec;
  std::vector<Axis> kernel = AxesFor("t", {{P::Choice, "kernel", "", "5", 0, 0, {"3", "5", "7", "9"}}}, {"kernel"});
  EXPECT_TRUE(kernel[0].ordered);
  EXPECT_FALSE(axes[1].ordered);
  std::vector<Config> k = Neighbours(Config{"t", {{"kernel", "5"}}}, kernel);
  ASSERT_EQ(k.size(), 2u);  // numbers: the next width either side
  EXPECT_EQ(k[0].params.at("kernel"), "3");
  EXPECT_EQ(k[1].params.at("kernel"), "7");
}

TEST(AdviseOutput, TechniqueLineAndCpp) {
  Config c{"csm", {{"cascades", "2"}, {"resolution", "768"}}};
  EXPECT_EQ(ConfigText(c), "csm:cascades=2:resolution=768");
  std::string cpp = CppSnippet(c);
  EXPECT_NE(cpp.find("sp::tech::CreateTechnique(\"csm\")"), std::string::npos);
  EXPECT_NE(cpp.find("{\"cascades\", \"2\"}, {\"resolution\", \"768\"}"), std::string::npos);
  EXPECT_NE(cpp.find("sp::tech::ParamValues::Parse(\"csm\", technique->Params(), given)"), std::string::npos);
}

}  // namespace
}  // namespace sp::advise
