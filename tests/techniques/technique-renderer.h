// A technique's renderer made the way the CLI makes one (created by name, its parameters parsed
// against its ParamSpecs, configured on the test's device), and the error a configuration is
// refused with: the steps every technique test repeats, so a change to how techniques are
// configured is made once.
#pragma once
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include <sp/rhi/rhi.h>
#include <sp/tech/renderer.h>

namespace sp::test {

using TechniqueParams = std::map<std::string, std::string>;

inline std::unique_ptr<tech::Technique> MakeConfiguredTechnique(Device& device, const std::string& name, const TechniqueParams& params) {
  std::unique_ptr<tech::Technique> t = tech::CreateTechnique(name);
  t->Configure(device, tech::ParamValues::Parse(name, t->Params(), params));
  return t;
}

inline std::unique_ptr<tech::Renderer> MakeTechniqueRenderer(Device& device, const std::string& name, const scene::Scene& s, uint32_t w, uint32_t h,
                                                             const TechniqueParams& params = {}, const tech::RendererOptions& options = {}) {
  return std::make_unique<tech::Renderer>(device, s, MakeConfiguredTechnique(device, name, params), w, h, options);
}

inline tech::RendererOptions LabOptions(bool lab) {
  tech::RendererOptions o;
  o.lab = lab;
  return o;
}

// The message Configure refuses `params` with (std::invalid_argument, the techniques' promise for
// a bad parameter), or "(accepted)" so a test's substring check fails with a readable value.
inline std::string ConfigureError(Device& device, const std::string& name, const TechniqueParams& params) {
  try {
    MakeConfiguredTechnique(device, name, params);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

// Configure must refuse `params` with a message that contains `what` (a parameter's name, a reason).
inline void ExpectConfigureRefused(Device& device, const std::string& name, const TechniqueParams& params, const std::string& what) {
  std::string error = ConfigureError(device, name, params);
  EXPECT_NE(error.find(what), std::string::npos) << name << ": expected a refusal naming \"" << what << "\", got: " << error;
}

}  // namespace sp::test
