// `shadowport hlslc --fx effect.fx [-D NAME[=VALUE]] [-I dir]`: what of an FX11 effect file
// ports: its techniques and passes (each stage's target, entry and whether it compiles) and its
// state objects with the fields they set (the rest are D3D11's defaults).
#include <cstdio>
#include <sp/fx/effect.h>
#include <stdexcept>

#include "cli.h"

namespace sp::cli {
namespace {

const char* const kStagePrefixes[] = {"VS", "PS", "GS", "CS"};

std::string ShaderLine(const fx::ShaderDesc& s) {
  if (s.isNull) return "NULL";
  std::string call = s.function + "(";
  for (size_t i = 0; i < s.arguments.size(); ++i) call += (i ? ", " : "") + s.arguments[i];
  call += ")";
  std::string line = s.target + " " + call;
  if (!s.variable.empty()) line += " (via " + s.variable + ")";
  if (s.entryPoint != s.function) line += " as " + s.entryPoint;
  return line + (s.error.empty() ? ": ok" : ": error\n        " + s.error);
}

std::string Name(const std::string& s) { return s.empty() ? "NULL" : s; }

}  // namespace

int RunHlslcFx(const std::vector<std::string>& argv) {
  std::string file;
  fx::EffectOptions opt;
  opt.failOnCompileError = false;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    auto value = [&](const std::string& flag) {
      if (a.size() > flag.size()) return a.substr(flag.size());
      if (i + 1 >= argv.size()) throw std::invalid_argument(flag + " needs a value");
      return argv[++i];
    };
    if (a == "--fx") {
      file = value("--fx");
    } else if (a.rfind("-D", 0) == 0 || a.rfind("/D", 0) == 0) {
      std::string v = value(a.substr(0, 2));
      size_t eq = v.find('=');
      opt.defines.push_back({v.substr(0, eq), eq == std::string::npos ? "" : v.substr(eq + 1)});
    } else if (a.rfind("-I", 0) == 0 || a.rfind("/I", 0) == 0) {
      opt.includeDirs.push_back(value(a.substr(0, 2)));
    } else if (a == "--no-cache" || a == "-nologo" || a == "/nologo") {
      // The effect's shaders use the default cache rule; -nologo is accepted as elsewhere.
    } else {
      throw std::invalid_argument("hlslc --fx: unknown option " + a + " (valid: --fx <file.fx>, -D NAME[=VALUE], -I <dir>, -nologo)");
    }
  }
  if (file.empty()) throw std::invalid_argument("hlslc --fx needs an effect file: shadowport hlslc --fx file.fx [-D ..] [-I ..]");
  std::unique_ptr<fx::Effect> effect = fx::Effect::Load(file, opt);
  int errors = 0;
  std::printf("%s: %u technique%s, %zu state object%s\n", file.c_str(), effect->GetTechniqueCount(),
              effect->GetTechniqueCount() == 1 ? "" : "s", effect->States().size(), effect->States().size() == 1 ? "" : "s");
  for (uint32_t t = 0; t < effect->GetTechniqueCount(); ++t) {
    const fx::EffectTechnique& tech = *effect->GetTechniqueByIndex(t);
    std::printf("technique %s%s (%s)\n", tech.Name().c_str(), tech.Group().empty() ? "" : (" in fxgroup " + tech.Group()).c_str(),
                tech.Location().ToString().c_str());
    for (uint32_t p = 0; p < tech.GetPassCount(); ++p) {
      const fx::PassDesc& d = tech.GetPassByIndex(p)->GetDesc();
      std::printf("  pass %s (%s)\n", d.name.empty() ? ("#" + std::to_string(p)).c_str() : d.name.c_str(), d.location.ToString().c_str());
      for (size_t s = 0; s < SHADER_STAGE_COUNT; ++s) {
        if (!d.shaders[s]) continue;
        errors += !d.shaders[s]->error.empty();
        std::printf("    %s %s\n", kStagePrefixes[s], ShaderLine(*d.shaders[s]).c_str());
      }
      if (d.rasterizerState) std::printf("    RasterizerState %s\n", Name(*d.rasterizerState).c_str());
      if (d.depthStencilState) std::printf("    DepthStencilState %s, stencil ref %u\n", Name(*d.depthStencilState).c_str(), d.stencilRef);
      if (d.blendState)
        std::printf("    BlendState %s, factor (%g, %g, %g, %g), sample mask 0x%08x\n", Name(*d.blendState).c_str(), d.blendFactor[0],
                    d.blendFactor[1], d.blendFactor[2], d.blendFactor[3], d.sampleMask);
      for (const fx::SamplerBindingDesc& b : d.samplers)
        std::printf("    %s sampler s%u: %s\n", kStagePrefixes[size_t(b.stage)], b.slot, b.sampler.c_str());
    }
  }
  for (const fx::StateObjectDesc& s : effect->States()) {
    std::printf("%s %s (%s)", fx::StateTypeName(s.type), s.name.c_str(), s.location.ToString().c_str());
    if (s.setFields.empty()) std::printf(": D3D11 defaults\n");
    else std::printf("\n");
    for (const std::string& f : s.setFields) std::printf("    %s\n", f.c_str());
  }
  std::fflush(stdout);  // the summary comes after the listing, also when both go to one terminal
  if (errors) std::fprintf(stderr, "%s: %d shader%s did not compile\n", file.c_str(), errors, errors == 1 ? "" : "s");
  return errors ? 1 : 0;
}

}  // namespace sp::cli
