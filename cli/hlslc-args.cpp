// `shadowport hlslc` argument handling; see hlslc-args.h.
#include "hlslc-args.h"

#include <filesystem>
#include <stdexcept>

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

}  // namespace

std::string HlslcValidOptions() {
  std::string s = "-T <target>, -E <entry>, -D <name>[=<value>], -I <dir>, -Fo <out>, -P <out.hlsl>, -nologo";
  for (const FlagSwitch& f : kFlagSwitches) s += std::string(", -") + f.name;
  return s + ", --no-cache, --help (each also as /option)";
}

namespace {

// Applies the option `body` (the argument without its '-' or '/'); returns false when it is not
// an option hlslc knows.
bool ApplyOption(const std::vector<std::string>& argv, size_t& i, const std::string& body, HlslcCommand& c) {
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

}  // namespace

HlslcCommand ParseHlslcArguments(const std::vector<std::string>& argv) {
  HlslcCommand c;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    bool dash = a.size() > 1 && a[0] == '-';
    // "/Zpr" is an option; "/home/me/shader.hlsl" (an existing path, or anything unknown with a
    // second '/') is the input file. The non-throwing query: a name the file system cannot even
    // look up (longer than NAME_MAX, found by fuzzing) is not an existing path, not a crash.
    std::error_code ignored;
    bool slash = a.size() > 1 && a[0] == '/' && !std::filesystem::exists(a, ignored);
    if (dash || slash) {
      if (ApplyOption(argv, i, a.substr(1), c)) continue;
      if (dash || a.find('/', 1) == std::string::npos) throw std::invalid_argument("unknown option " + a + " (valid: " + HlslcValidOptions() + ")");
    }
    if (!c.file.empty()) throw std::invalid_argument("more than one input file (" + c.file + ", " + a + ")");
    c.file = a;
  }
  return c;
}

}  // namespace sp::cli
