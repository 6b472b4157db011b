// Fuzz target: the whole HLSL toolchain on a source that got through the parser: glslang's
// SPIR-V, the SPIR-V edits, spirv-opt's legalisation, spirv-val, reflection and SPIRV-Cross's
// GLSL (sp::hlsl::CompileSource, no cache). Promised error: hlsl::CompileError. Slower per input
// than hlsl-preprocess (glslang's parser runs in a child process, then the optimiser), so its
// inputs are the small shaders of tests/hlsl/data and the target picks its stage from the first
// line (`// ps_5_0`, else ps_5_0).
#include <sp/hlsl/compiler.h>

#include "fuzz-target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text = sp::fuzz::Text(data, size);
  sp::hlsl::CompileOptions options;
  options.target = "ps_5_0";
  for (const char* t : {"vs_5_0", "cs_5_0", "vs_4_0", "ps_4_0"})
    if (text.substr(0, text.find('\n')).find(t) != std::string_view::npos) options.target = t;
  options.entryPoint = "main";
  options.useCache = false;
  try {
    (void)sp::hlsl::CompileSource(text, "fuzz.hlsl", options);
  } catch (const sp::hlsl::CompileError&) {
  }
  return 0;
}
