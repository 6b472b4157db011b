// shadowport: render, demo, hlslc, conformance, and the lab's bench and report.
#include <cstdio>
#include <exception>
#include <sp/rhi/common.h>
#include <string>
#include <vector>

#include "cli.h"

namespace {

void Help() {
  std::printf(
      "usage: shadowport <command> [options]\n\n"
      "commands:\n"
      "  render  --backend vulkan|gl --technique NAME --scene NAME --size WxH --out file.png [--param k=v]... [--validate]\n"
      "          renders one frame of a scene with a shadow technique\n"
      "  demo    [--out dir] [--size WxH] [--scene NAME] [--technique T[,T...]] [--frames N] [--param k=v]...\n"
      "          a small lab run (about two minutes): basic, csm, csm with 5x5 Gaussian PCF, csm with MSM and\n"
      "          sdsm on ShadowColumns (a built-in scene if ../shared/scenes is missing) at 960x540, 8 frames,\n"
      "          both backends with validation on, against the ray-traced reference; prints a table and writes\n"
      "          out/demo/index.html. A technique may carry parameters (csm:filter=gauss:kernel=5); a --param\n"
      "          applies to every listed technique that has it\n"
      "  bench   --scene S[,S...] --technique T[,T...] --backend vulkan|gl|both --size WxH --frames N\n"
      "          [--param k=v[,v...]]... [--triangles N] [--path NAME|FILE.json] [--out results.json] [--reference-cache dir] [--validate]\n"
      "          [--light-gamma DEG[,DEG...]] [--light-size S] [--light-samples N]\n"
      "          measures techniques against the ray-traced reference along a camera path (default slow-pan);\n"
      "          writes {\"runs\": [...]} and pictures beside it; a --param with several values sweeps them;\n"
      "          a technique may carry fixed parameters (csm:filter=gauss:kernel=5); the reference cache is\n"
      "          --reference-cache, else $SHADOWPORT_REFERENCE_CACHE, else reference-cache/ beside the results;\n"
      "          --light-gamma runs each scene with its light at these angles to the view (0 from behind the\n"
      "          viewer, 90 across, 180 towards it: duelling frusta), as scenes named <scene>-gamma<DEG>;\n"
      "          --light-size sets every light's size (the sun's angular diameter in degrees, local lights'\n"
      "          radius in world units; 0 hard) for techniques (and their light_size parameter, e.g. pcss)\n"
      "          and the area-light reference, which casts --light-samples rays per pixel (default 256)\n"
      "  report  results.json... --out dir [--title text]\n"
      "          charts and an HTML page from bench results (eval/report/report.py)\n"
      "  advise  --scene S --budget METRIC=V [--budget ...] [--backend vulkan|gl] [--size WxH] [--frames N] [--path NAME|FILE.json]\n"
      "          [--techniques T[,T...]] [--minimize ms|memory] [--axes P[,P...]] [--noise F] [--max-runs N] [--max-resolution N] [--confirm N] [--exhaustive]\n"
      "          [--cache dir] [--no-report] --out dir\n"
      "          the cheapest configuration meeting every budget (metrics: misclassified, false_lit, false_shadow,\n"
      "          mean_abs_error, flicker, ms, memory): a coarse sweep of each technique's resolution, cascades,\n"
      "          filter, kernel and bias, refined around the Pareto front; measurements are cached (rerun to resume);\n"
      "          prints the front, the --technique line and C++, writes dir/index.html\n"
      "  conformance [--backend vulkan|gl|both] [--out dir] [--filter text] [--verbose]\n"
      "          runs the D3D11 conformance probes; prints the feature x backend table, writes Markdown and JSON\n"
      "  sdsm-cost [--backend vulkan|gl|both] [--size WxH[,WxH...]] [--frames N] [--warmup N] [--validate]\n"
      "          times each SDSM analysis pass on a synthetic depth buffer against a pass that reads it once\n"
      "          (medians of N frames, default 20, after warm-up; first frame apart); prints Markdown tables\n"
      "  hlslc   file.hlsl -T vs_5_0|ps_5_0|cs_5_0 [-E entry] [-D NAME[=VALUE]] [-I dir] [-Fo out]\n"
      "          compiles HLSL like fxc: writes out.spv, out.glsl and out.json (reflection)\n"
      "  hlslc   --fx file.fx [-D NAME[=VALUE]] [-I dir]\n"
      "          lists an FX11 effect's techniques, passes (each stage compiled) and state objects\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    Help();
    return args.empty() ? 2 : 0;
  }
  std::string cmd = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (cmd == "render") return sp::cli::RunRender(sp::cli::Args(rest, {"validate"}));
    if (cmd == "demo") return sp::cli::RunDemo(sp::cli::Args(rest));
    if (cmd == "hlslc") return sp::cli::RunHlslc(rest);
    if (cmd == "bench") return sp::cli::RunBench(sp::cli::Args(rest, {"validate"}));
    if (cmd == "report") return sp::cli::RunReport(sp::cli::Args(rest));
    if (cmd == "advise") return sp::cli::RunAdvise(sp::cli::Args(rest, {"exhaustive", "no-report"}));
    if (cmd == "sdsm-cost") return sp::cli::RunSdsmCost(sp::cli::Args(rest, {"validate"}));
    if (cmd == "conformance") return sp::cli::RunConformance(sp::cli::Args(rest, {"verbose"}));
    std::fprintf(stderr, "shadowport: unknown command '%s'\n", cmd.c_str());
    Help();
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadowport %s: error: %s\n", cmd.c_str(), e.what());
    return 1;
  }
}
