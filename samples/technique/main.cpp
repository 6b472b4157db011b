// samples/technique: shadows on your own glTF scene from ShadowPort's technique library, on
// Vulkan or OpenGL. The library does the passes; this program picks the technique and its
// parameters, frames the camera and writes the picture.
//
//   technique scene.gltf [--technique csm] [--param name=value]... [--backend vulkan|gl]
//             [--size N] [--out technique.png] [--eye x,y,z] [--target x,y,z] [--light x,y,z]
//
// Without --eye/--target/--light the loader's framing is used (the whole scene from above one
// corner, a low sun). --light is the direction the light travels. `--technique list` prints the
// techniques and their parameters.
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

#include <sp/rhi/rhi.h>
#include <sp/scene/scene.h>
#include <sp/tech/renderer.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace {

glm::vec3 ParseVec3(const std::string& text) {
  glm::vec3 v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',')
    throw std::invalid_argument("expected x,y,z, got '" + text + "'");
  return v;
}

void ListTechniques() {
  for (const std::string& name : sp::tech::TechniqueNames()) {
    std::printf("%s\n", name.c_str());
    for (const sp::tech::ParamSpec& p : sp::tech::CreateTechnique(name)->Params())
      std::printf("  %-22s %s (default %s)\n", p.name.c_str(), p.help.c_str(), p.defaultValue.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: technique scene.gltf [--technique NAME|list] [--param k=v]... [--backend vulkan|gl] "
                         "[--size N] [--out file.png] [--eye x,y,z] [--target x,y,z] [--light x,y,z]\n");
    return 2;
  }
  try {
    std::string gltf = argv[1], techniqueName = "csm", out = "technique.png";
    std::map<std::string, std::string> params;
    sp::DeviceDesc dd;
    uint32_t size = 512;
    sp::scene::Scene scene;
    std::map<std::string, std::string> options;
    for (int i = 2; i < argc; i += 2) {
      std::string k = argv[i], v = i + 1 < argc ? argv[i + 1] : "";
      if (i + 1 == argc) throw std::invalid_argument(k + " needs a value");
      if (k == "--param") {
        size_t eq = v.find('=');
        if (eq == std::string::npos) throw std::invalid_argument("--param takes name=value, got '" + v + "'");
        params[v.substr(0, eq)] = v.substr(eq + 1);
      } else if (k == "--backend") {
        if (!sp::ParseBackend(v, &dd.backend)) throw std::invalid_argument("--backend takes vulkan or gl");
      } else if (k == "--technique" || k == "--size" || k == "--out" || k == "--eye" || k == "--target" || k == "--light") {
        options[k] = v;
      } else {
        throw std::invalid_argument("unknown option " + k);
      }
    }
    if (options.count("--technique")) techniqueName = options["--technique"];
    if (techniqueName == "list") {
      ListTechniques();
      return 0;
    }
    if (options.count("--size")) size = uint32_t(std::stoul(options["--size"]));
    if (options.count("--out")) out = options["--out"];

    // The scene, and where it is seen from and lit from.
    scene = sp::scene::LoadGltf(gltf);
    if (options.count("--eye")) scene.camera.position = ParseVec3(options["--eye"]);
    if (options.count("--target")) scene.camera.target = ParseVec3(options["--target"]);
    if (options.count("--light")) scene.light.direction = glm::normalize(ParseVec3(options["--light"]));

    // The technique, configured: unknown parameters or values out of range are errors that list
    // what is valid.
    sp::Ref<sp::Device> device = sp::CreateDevice(dd);
    std::unique_ptr<sp::tech::Technique> technique = sp::tech::CreateTechnique(techniqueName);
    technique->Configure(*device, sp::tech::ParamValues::Parse(techniqueName, technique->Params(), params));

    // One frame: the technique's shadow passes, then the lit pass into an sRGB target.
    sp::tech::Renderer renderer(*device, scene, std::move(technique), size, size);
    renderer.RenderFrame(scene.camera, scene.light);
    std::vector<uint8_t> rgba = renderer.ReadColor();
    if (!stbi_write_png(out.c_str(), int(size), int(size), 4, rgba.data(), int(size * 4))) {
      std::fprintf(stderr, "technique: cannot write %s\n", out.c_str());
      return 1;
    }
    sp::tech::ShadowStats stats = renderer.technique().Stats();
    std::printf("technique: %s on %s, %zu triangles, %.1f MiB of shadow maps, wrote %s\n", techniqueName.c_str(),
                device->Info().deviceName.c_str(), scene.triangleCount(), stats.memoryBytes / 1048576.0, out.c_str());
    if (device->ValidationErrorCount() > 0) {
      std::fprintf(stderr, "technique: %llu validation errors, last: %s\n",
                   (unsigned long long)device->ValidationErrorCount(), device->LastValidationError().c_str());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "technique: %s\n", e.what());
    return 1;
  }
}
