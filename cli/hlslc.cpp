// `shadowport hlslc`: fxc-style front end to the HLSL toolchain, for checking what of an existing
// D3D11 shader ports:  shadowport hlslc shadow.hlsl /T ps_4_0 /E PSMain /D PCF=1 /I inc /Zpr /Fo out
// Options take fxc's spellings with '-' or '/'; values follow attached (-Tps_5_0) or separately.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sp/hlsl/compiler.h>
#include <stdexcept>

#include "cli.h"
#include "hlslc-args.h"

namespace sp::cli {
namespace {

void Usage() {
  std::fprintf(stderr,
               "usage: shadowport hlslc <file.hlsl> -T <target> [-E entry] [-D NAME[=VALUE]]... [-I dir]... [-Fo out] [fxc flags]\n"
               "targets: %s\n"
               "options: %s\n"
               "writes out.spv (SPIR-V for Vulkan), out.glsl (GLSL 4.50 for OpenGL) and out.json (reflection);\n"
               "with -P out.hlsl, writes instead what glslang parses: the preprocessed source after the D3D11\n"
               "compatibility rewrites (-T optional), and names the rewrites that changed it\n",
               hlsl::ValidTargets(), HlslcValidOptions().c_str());
  std::fputs(kSurveyUsage, stderr);
}

// fxc's -P: the preprocessed source, here also after the compatibility rewrites.
int WritePreprocessed(HlslcCommand& c) {
  std::ifstream in(c.file, std::ios::binary);
  if (!in) throw std::invalid_argument(c.file + ": cannot open the file");
  std::string source((std::istreambuf_iterator<char>(in)), {});
  c.opt.target = c.target;
  c.opt.entryPoint = c.entry;
  std::vector<std::string> applied;
  std::string text = hlsl::Preprocess(source, c.file, c.opt, &applied);
  std::ofstream out(c.preprocessOut, std::ios::binary);
  if (!(out << text)) throw std::runtime_error(c.preprocessOut + ": cannot write the file");
  std::string names;
  for (const std::string& a : applied) names += (names.empty() ? "" : ", ") + a;
  std::printf("%s -> %s (rewrites: %s)\n", c.file.c_str(), c.preprocessOut.c_str(), names.empty() ? "none" : names.c_str());
  return 0;
}

}  // namespace

int RunHlslc(const std::vector<std::string>& argv) {
  if (std::find(argv.begin(), argv.end(), "--fx") != argv.end()) return RunHlslcFx(argv);  // cli/hlslc-fx.cpp
  if (std::find(argv.begin(), argv.end(), "--survey") != argv.end()) return RunHlslcSurvey(argv);  // cli/hlslc-survey.cpp
  HlslcCommand c = ParseHlslcArguments(argv);
  if (c.help) {
    Usage();
    return 0;
  }
  if (!c.file.empty() && !c.preprocessOut.empty()) return WritePreprocessed(c);
  if (c.file.empty() || c.target.empty()) {
    Usage();
    throw std::invalid_argument("an input file and -T are required");
  }
  c.opt.target = c.target;
  c.opt.entryPoint = c.entry;
  std::filesystem::path base = c.out.empty() ? std::filesystem::path(c.file).replace_extension("") : std::filesystem::path(c.out);
  std::string ext = base.extension().string();
  if (ext == ".cso" || ext == ".spv" || ext == ".fxo" || ext == ".bin") base.replace_extension("");
  std::vector<hlsl::Diagnostic> warnings;
  ShaderBytecode b = hlsl::CompileFile(c.file, c.opt, &warnings);
  if (!warnings.empty()) std::fprintf(stderr, "%s\n", hlsl::FormatDiagnostics(warnings, "warning").c_str());
  hlsl::WriteCompiledFiles(base, b);
  std::printf("%s: %s %s -> %s.spv (%zu words), %s.glsl, %s.json (%zu cbuffers, %zu resources)\n", c.file.c_str(), c.target.c_str(),
              c.entry.c_str(), base.string().c_str(), b.spirv.size(), base.string().c_str(), base.string().c_str(),
              b.reflection.cbuffers.size(), b.reflection.resources.size());
  return 0;
}

}  // namespace sp::cli
