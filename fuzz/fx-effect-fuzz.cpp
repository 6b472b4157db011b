// Fuzz target: FX11 effect files (sp::fx::Effect::LoadFromSource): preprocessing, the effect
// blocks (techniques, passes, state objects) and each pass's shader compile. Promised error:
// sp::Error (hlsl::CompileError with file:line for the source, INVALID_ARGUMENT otherwise).
// Compiled shaders go to a cache folder of this process, not the user's.
#include <filesystem>
#include <sp/fx/effect.h>
#include <string>
#include <unistd.h>

#include "fuzz-target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path cache = std::filesystem::temp_directory_path() / ("sp-fuzz-fx-cache-" + std::to_string(getpid()));
  sp::fx::EffectOptions options;
  options.cacheDir = cache;
  options.failOnCompileError = false;  // as `hlslc --fx`: keep going past a pass that fails
  try {
    std::unique_ptr<sp::fx::Effect> fx = sp::fx::Effect::LoadFromSource(sp::fuzz::Text(data, size), "fuzz.fx", options);
    for (uint32_t t = 0; t < fx->GetTechniqueCount(); ++t) (void)fx->GetTechniqueByIndex(t);
  } catch (const sp::Error&) {
  }
  return 0;
}
