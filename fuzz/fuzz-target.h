// What every fuzz target shares: libFuzzer's entry point and the rule for a finding.
//
// A target feeds the bytes to one parser of user input and catches the errors that parser
// promises (each target names them). Anything else is a finding: a crash, a sanitizer report, a
// hang or runaway allocation (libFuzzer's -timeout and -rss_limit_mb), or an exception of a type
// the parser does not promise, which reaches std::terminate. Built with clang and
// -DSHADOWPORT_FUZZ=ON the targets link libFuzzer; otherwise replay-main.cpp drives them over
// their seed corpus and a few thousand deterministic mutations (the `fuzz.*` tests).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace sp::fuzz {

inline std::string_view Text(const uint8_t* data, size_t size) { return {reinterpret_cast<const char*>(data), size}; }

// The input cut at '\n' (several short strings from one input: arguments, names, values).
inline std::vector<std::string> Lines(std::string_view text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    out.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

}  // namespace sp::fuzz
