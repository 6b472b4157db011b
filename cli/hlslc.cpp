// `shadowport hlslc`: fxc/dxc-style front end to the HLSL toolchain, for checking what of an
// existing D3D11 shader ports:  shadowport hlslc shadow.hlsl -T ps_5_0 -E PSMain -D PCF=1 -I inc -Fo out
#include <cstdio>
#include <filesystem>
#include <sp/hlsl/compiler.h>
#include <stdexcept>

#include "cli.h"

namespace sp::cli {

static void Usage() {
  std::fprintf(stderr,
               "usage: shadowport hlslc <file.hlsl> -T vs_5_0|ps_5_0|cs_5_0 [-E entry] [-D NAME[=VALUE]]... [-I dir]... "
               "[-Fo out] [--no-cache]\n"
               "writes out.spv (SPIR-V for Vulkan), out.glsl (GLSL 4.50 for OpenGL) and out.json (reflection)\n");
}

int RunHlslc(const std::vector<std::string>& argv) {
  std::string file, entry = "main", target, out;
  hlsl::CompileOptions opt;
  auto value = [&](size_t& i, const std::string& flag) -> std::string {
    const std::string& a = argv[i];
    if (a.size() > flag.size()) return a.substr(flag.size());  // -DNAME, -Idir
    if (i + 1 >= argv.size()) throw std::invalid_argument(flag + " needs a value");
    return argv[++i];
  };
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "-h" || a == "--help") {
      Usage();
      return 0;
    } else if (a.rfind("-T", 0) == 0) {
      target = value(i, "-T");
    } else if (a.rfind("-E", 0) == 0) {
      entry = value(i, "-E");
    } else if (a.rfind("-Fo", 0) == 0) {
      out = value(i, "-Fo");
    } else if (a.rfind("-D", 0) == 0) {
      std::string d = value(i, "-D");
      size_t eq = d.find('=');
      opt.defines.push_back({d.substr(0, eq), eq == std::string::npos ? "" : d.substr(eq + 1)});
    } else if (a.rfind("-I", 0) == 0) {
      opt.includeDirs.push_back(value(i, "-I"));
    } else if (a == "--no-cache") {
      opt.useCache = false;
    } else if (!a.empty() && a[0] == '-') {
      Usage();
      throw std::invalid_argument("unknown option " + a);
    } else if (file.empty()) {
      file = a;
    } else {
      throw std::invalid_argument("more than one input file (" + file + ", " + a + ")");
    }
  }
  if (file.empty() || target.empty()) {
    Usage();
    throw std::invalid_argument("an input file and -T are required");
  }
  opt.target = target;
  opt.entryPoint = entry;
  std::filesystem::path base = out.empty() ? std::filesystem::path(file).replace_extension("") : std::filesystem::path(out);
  std::string ext = base.extension().string();
  if (ext == ".cso" || ext == ".spv" || ext == ".fxo" || ext == ".bin") base.replace_extension("");
  ShaderBytecode b = hlsl::CompileFile(file, opt);
  hlsl::WriteCompiledFiles(base, b);
  std::printf("%s: %s %s -> %s.spv (%zu words), %s.glsl, %s.json (%zu cbuffers, %zu resources)\n", file.c_str(), target.c_str(), entry.c_str(),
              base.string().c_str(), b.spirv.size(), base.string().c_str(), base.string().c_str(), b.reflection.cbuffers.size(),
              b.reflection.resources.size());
  return 0;
}

}  // namespace sp::cli
