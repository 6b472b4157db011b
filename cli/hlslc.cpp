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

namespace sp::cli {
namespace {

// fxc switches that only set a COMPILE_* bit (see sp/hlsl/compiler.h for what each one does).
struct FlagSwitch {
  const char* name;
  uint32_t bits;
};
constexpr FlagSwitch kFlagSwitches[] = {
    {"Zi", hlsl::COMPILE_DEBUG},
    {"Vd", hlsl::COMPILE_SKIP_VALIDATION},
    {"Od", hlsl::COMPILE_SKIP_OPTIMIZATION},
    {"Zpr", hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR},
    {"Zpc", hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR},
    {"Gpp", hlsl::COMPILE_PARTIAL_PRECISION},
    {"Op", hlsl::COMPILE_NO_PRESHADER},
    {"Gfa", hlsl::COMPILE_AVOID_FLOW_CONTROL},
    {"Gfp", hlsl::COMPILE_PREFER_FLOW_CONTROL},
    {"Ges", hlsl::COMPILE_ENABLE_STRICTNESS},
    {"Gec", hlsl::COMPILE_ENABLE_BACKWARDS_COMPATIBILITY},
    {"Gis", hlsl::COMPILE_IEEE_STRICTNESS},
    {"O0", hlsl::COMPILE_OPTIMIZATION_LEVEL0},
    {"O1", hlsl::COMPILE_OPTIMIZATION_LEVEL1},
    {"O2", hlsl::COMPILE_OPTIMIZATION_LEVEL2},
    {"O3", hlsl::COMPILE_OPTIMIZATION_LEVEL3},
    {"WX", hlsl::COMPILE_WARNINGS_ARE_ERRORS},
    {"res_may_alias", hlsl::COMPILE_RESOURCES_MAY_ALIAS},
    {"all_resources_bound", hlsl::COMPILE_ALL_RESOURCES_BOUND},
    {"enable_unbounded_descriptor_tables", hlsl::COMPILE_ENABLE_UNBOUNDED_DESCRIPTOR_TABLES},
};
constexpr uint32_t kOptimizationLevelBits = hlsl::COMPILE_OPTIMIZATION_LEVEL2;  // both level bits
const char* const kValueOptions[] = {"Fo", "E", "T", "D", "I", "P"};

std::string ValidOptions() {
  std::string s = "-T <target>, -E <entry>, -D <name>[=<value>], -I <dir>, -Fo <out>, -P <out.hlsl>, -nologo";
  for (const FlagSwitch& f : kFlagSwitches) s += std::string(", -") + f.name;
  return s + ", --no-cache, --help (each also as /option)";
}

void Usage() {
  std::fprintf(stderr,
               "usage: shadowport hlslc <file.hlsl> -T <target> [-E entry] [-D NAME[=VALUE]]... [-I dir]... [-Fo out] [fxc flags]\n"
               "targets: %s\n"
               "options: %s\n"
               "writes out.spv (SPIR-V for Vulkan), out.glsl (GLSL 4.50 for OpenGL) and out.json (reflection);\n"
               "with -P out.hlsl, writes instead what glslang parses: the preprocessed source after the D3D11\n"
               "compatibility rewrites (-T optional), and names the rewrites that changed it\n",
               hlsl::ValidTargets(), ValidOptions().c_str());
  std::fputs(kSurveyUsage, stderr);
}

struct Command {
  std::string file, entry = "main", target, out, preprocessOut;
  hlsl::CompileOptions opt;
  bool help = false;
};

// Applies the option `body` (the argument without its '-' or '/'); returns false when it is not
// an option hlslc knows.
bool ApplyOption(const std::vector<std::string>& argv, size_t& i, const std::string& body, Command& c) {
  if (body == "nologo") return true;  // hlslc prints no banner anyway
  if (body == "no-cache" || body == "-no-cache") {
    c.opt.useCache = false;
    return true;
  }
  if (body == "h" || body == "-help" || body == "?") {
    c.help = true;
    return true;
  }
  for (const FlagSwitch& f : kFlagSwitches) {
    if (body != f.name) continue;
    if (f.bits == 0 || (f.bits & kOptimizationLevelBits) == f.bits) c.opt.flags1 &= ~kOptimizationLevelBits;  // the last -O wins
    c.opt.flags1 |= f.bits;
    return true;
  }
  for (const char* v : kValueOptions) {
    std::string flag = v;
    if (body.rfind(flag, 0) != 0) continue;
    std::string value;
    if (body.size() > flag.size()) {
      value = body.substr(flag.size());  // -DNAME, -Idir
    } else {
      if (i + 1 >= argv.size()) throw std::invalid_argument("-" + flag + " needs a value");
      value = argv[++i];
    }
    if (flag == "T") c.target = value;
    else if (flag == "E") c.entry = value;
    else if (flag == "Fo") c.out = value;
    else if (flag == "P") c.preprocessOut = value;
    else if (flag == "I") c.opt.includeDirs.push_back(value);
    else {
      size_t eq = value.find('=');
      c.opt.defines.push_back({value.substr(0, eq), eq == std::string::npos ? "" : value.substr(eq + 1)});
    }
    return true;
  }
  return false;
}

Command Parse(const std::vector<std::string>& argv) {
  Command c;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    bool dash = a.size() > 1 && a[0] == '-';
    // "/Zpr" is an option; "/home/me/shader.hlsl" (an existing path, or anything unknown with a
    // second '/') is the input file.
    bool slash = a.size() > 1 && a[0] == '/' && !std::filesystem::exists(a);
    if (dash || slash) {
      if (ApplyOption(argv, i, a.substr(1), c)) continue;
      if (dash || a.find('/', 1) == std::string::npos) throw std::invalid_argument("unknown option " + a + " (valid: " + ValidOptions() + ")");
    }
    if (!c.file.empty()) throw std::invalid_argument("more than one input file (" + c.file + ", " + a + ")");
    c.file = a;
  }
  return c;
}

// fxc's -P: the preprocessed source, here also after the compatibility rewrites.
int WritePreprocessed(Command& c) {
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
  Command c = Parse(argv);
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
