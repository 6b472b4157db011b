// Where the techniques' HLSL lives at run time (see ShaderDirectory() in technique.h).
#include <cstdlib>
#include <mutex>
#include <sp/tech/technique.h>
#include <stdexcept>

namespace sp::tech {
namespace {

// Function-local: RegisterPackageShaderDirectory runs during the static initialisation of the
// program's own translation units, possibly before this file's globals would be constructed.
struct Choices {
  std::mutex mutex;
  std::filesystem::path explicitDir;  // SetShaderDirectory
  std::filesystem::path packageDir;   // RegisterPackageShaderDirectory
};
Choices& Get() {
  static Choices choices;
  return choices;
}

// A folder holds the shaders when the file every technique needs is there.
bool HoldsShaders(const std::filesystem::path& dir) {
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_regular_file(dir / "common" / "depth-only.hlsl", ec);
}

}  // namespace

void SetShaderDirectory(const std::filesystem::path& directory) {
  std::lock_guard lock(Get().mutex);
  Get().explicitDir = directory;
}

bool RegisterPackageShaderDirectory(const char* directory) {
  std::lock_guard lock(Get().mutex);
  Get().packageDir = directory ? directory : "";
  return true;
}

std::filesystem::path ShaderDirectory() {
  Choices& c = Get();
  std::lock_guard lock(c.mutex);
  // An explicit choice is used as given, so a wrong one fails loudly at the first compile
  // (naming the missing file) instead of silently falling back to other shaders.
  if (!c.explicitDir.empty()) return c.explicitDir;
  if (const char* e = std::getenv("SHADOWPORT_SHADER_DIR"); e && *e) return e;
  const std::filesystem::path candidates[] = {c.packageDir, SHADOWPORT_SHADER_DIR, SHADOWPORT_INSTALLED_SHADER_DIR};
  std::string tried;
  for (const auto& dir : candidates) {
    if (HoldsShaders(dir)) return dir;
    if (!dir.empty()) tried += "\n  " + dir.string();
  }
  throw std::runtime_error("ShadowPort's technique shaders (shaders-hlsl/) were not found; looked in:" + tried +
                           "\nset SHADOWPORT_SHADER_DIR or call sp::tech::SetShaderDirectory()");
}

}  // namespace sp::tech
