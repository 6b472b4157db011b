// Fuzz target: the HLSL front end up to glslang's parser: glslang's preprocessor and the D3D11
// compatibility rewrites (sp::hlsl::Preprocess, what `shadowport hlslc -P` runs). Promised error:
// hlsl::CompileError (file:line messages). The source is named fuzz.hlsl in the working folder,
// so its #includes resolve there.
#include <sp/hlsl/compiler.h>

#include "fuzz-target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sp::hlsl::CompileOptions options;
  options.target = "ps_5_0";
  options.entryPoint = "main";
  options.useCache = false;
  try {
    std::vector<std::string> applied;
    (void)sp::hlsl::Preprocess(sp::fuzz::Text(data, size), "fuzz.hlsl", options, &applied);
  } catch (const sp::hlsl::CompileError&) {
  }
  return 0;
}
