// Fuzz target: the glTF loader (scene::LoadGltf), .gltf JSON or .glb by the input's first bytes.
// Promised error: std::runtime_error whose message names the file. The input is written to a
// file of its own per process because the loader reads files (external buffers resolve next to
// it, as for a user's scene).
#include <filesystem>
#include <fstream>
#include <sp/scene/scene.h>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "fuzz-target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("sp-fuzz-gltf-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const bool binary = size >= 4 && sp::fuzz::Text(data, 4) == "glTF";
  const std::filesystem::path file = dir / (binary ? "input.glb" : "input.gltf");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    sp::scene::Scene s = sp::scene::LoadGltf(file);
    (void)s.triangleCount();
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find(file.filename().string()) == std::string::npos) {
      std::fprintf(stderr, "error message does not name the file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
