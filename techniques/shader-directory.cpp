// Where the techniques' HLSL lives at run time (see ShaderDirectory() in technique.h).
#include <cstdlib>
#include <mutex>
#include <sp/tech/technique.h>
#include <stdexcept>

namespace sp::tech {
namespace {

std::mutex gMutex;
std::filesystem::path gExplicit;  // SetShaderDirectory
std::filesystem::path gPackage;   // RegisterPackageShaderDirectory

// A folder holds the shaders when the file every technique needs is there.
bool HoldsShaders(const std::filesystem::path& dir) {
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_regular_file(dir / "common" / "depth-only.hlsl", ec);
}

}  // namespace

void SetShaderDirectory(const std::filesystem::path& directory) {
  std::lock_guard lock(gMutex);
  gExplicit = directory;
}

bool RegisterPackageShaderDirectory(const char* directory) {
  std::lock_guard lock(gMutex);
  gPackage = directory ? directory : "";
  return true;
}

std::filesystem::path ShaderDirectory() {
  std::lock_guard lock(gMutex);
  // An explicit choice is used as given, so a wrong one fails loudly at the first compile
  // (naming the missing file) instead of silently falling back to other shaders.
  if (!gExplicit.empty()) return gExplicit;
  if (const char* e = std::getenv("SHADOWPORT_SHADER_DIR"); e && *e) return e;
  const std::filesystem::path candidates[] = {gPackage, SHADOWPORT_SHADER_DIR, SHADOWPORT_INSTALLED_SHADER_DIR};
  std::string tried;
  for (const auto& c : candidates) {
    if (HoldsShaders(c)) return c;
    if (!c.empty()) tried += "\n  " + c.string();
  }
  throw std::runtime_error("ShadowPort's technique shaders (shaders-hlsl/) were not found; looked in:" + tried +
                           "\nset SHADOWPORT_SHADER_DIR or call sp::tech::SetShaderDirectory()");
}

}  // namespace sp::tech
