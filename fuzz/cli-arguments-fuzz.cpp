// Fuzz target: the command line's parsers of user text. The first line picks the parser, the
// rest are its arguments: --size, --param lists, counts, comma lists, technique specs with their
// parameters validated against the technique's ParamSpecs, built-in scene names with a triangle
// target, and hlslc's fxc-style arguments. Promised error: std::invalid_argument naming the
// option or value.
#include <cstring>
#include <sp/scene/scene.h>
#include <sp/tech/technique.h>
#include <stdexcept>

#include "../cli/cli.h"
#include "../cli/hlslc-args.h"
#include "../eval/bench/bench.h"
#include "fuzz-target.h"

namespace {

void Run(const std::vector<std::string>& lines) {
  const std::string& which = lines[0];
  const std::vector<std::string> args(lines.begin() + 1, lines.end());
  const std::string first = args.empty() ? std::string() : args[0];
  if (which == "size") {
    uint32_t w = 0, h = 0;
    sp::cli::ParseSize(first, &w, &h);
    if (w < 1 || h < 1 || w > 16384 || h > 16384) std::abort();
  } else if (which == "params") {
    (void)sp::cli::ParseParams(args);
  } else if (which == "count") {
    (void)sp::cli::ParseCount(first, "frames", 1, 100000);
  } else if (which == "list") {
    (void)sp::cli::SplitList(first, "scene");
  } else if (which == "technique") {
    sp::bench::TechniqueSpec spec = sp::bench::ParseTechniqueSpec(first);
    std::unique_ptr<sp::tech::Technique> t = sp::tech::CreateTechnique(spec.name);
    (void)sp::tech::ParamValues::Parse(spec.name, t->Params(), spec.params);
  } else if (which == "scene") {
    sp::scene::SceneOptions options;
    options.targetTriangles = args.size() > 1 ? sp::cli::ParseCount(args[1], "triangles", 0, UINT64_MAX) : 0;
    // Building a scene of millions of triangles takes seconds: a fuzzer would time out on the
    // sizes, not find anything. Targets up to 2e5, and everything past the limit (which throws).
    if (options.targetTriangles > 200000 && options.targetTriangles <= sp::scene::kMaxTargetTriangles) return;
    (void)sp::scene::MakeBuiltinScene(first, options);
  } else if (which == "hlslc") {
    (void)sp::cli::ParseHlslcArguments(args);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return 0;  // arguments, not files
  std::vector<std::string> lines = sp::fuzz::Lines(sp::fuzz::Text(data, size));
  try {
    Run(lines);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
