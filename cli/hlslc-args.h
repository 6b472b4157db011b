// The argument handling of `shadowport hlslc` (fxc spellings), apart from the compiling so it can
// be tested and fuzzed without touching files.
#pragma once
#include <sp/hlsl/compiler.h>
#include <string>
#include <vector>

namespace sp::cli {

struct HlslcCommand {
  std::string file, entry = "main", target, out, preprocessOut;
  hlsl::CompileOptions opt;
  bool help = false;
};

// Throws std::invalid_argument naming the bad argument (unknown option, a value missing, two
// input files). Reads no file; only asks whether a "/..." argument is an existing path.
HlslcCommand ParseHlslcArguments(const std::vector<std::string>& argv);

// "-T <target>, -E <entry>, ...": every option, for messages and the usage text.
std::string HlslcValidOptions();

}  // namespace sp::cli
