// The technique registry: adding a technique is one line here.
#include <functional>
#include <stdexcept>

#include <sp/tech/technique.h>

namespace sp::tech {

std::unique_ptr<Technique> MakeBasicTechnique();
std::unique_ptr<Technique> MakeCsmTechnique();
std::unique_ptr<Technique> MakeSdsmTechnique();
std::unique_ptr<Technique> MakePsmTechnique();
std::unique_ptr<Technique> MakeLispsmTechnique();
std::unique_ptr<Technique> MakeTsmTechnique();
std::unique_ptr<Technique> MakeCubeTechnique();
std::unique_ptr<Technique> MakeSpotTechnique();
std::unique_ptr<Technique> MakeVsdctTechnique();
std::unique_ptr<Technique> MakeParaboloidTechnique();
std::unique_ptr<Technique> MakeAsmTechnique();

namespace {
struct Entry {
  const char* name;
  std::unique_ptr<Technique> (*make)();
};

const Entry kTechniques[] = {
    {"basic", MakeBasicTechnique},
    {"csm", MakeCsmTechnique},
    {"sdsm", MakeSdsmTechnique},
    {"psm", MakePsmTechnique},
    {"lispsm", MakeLispsmTechnique},
    {"tsm", MakeTsmTechnique},
    {"cube", MakeCubeTechnique},
    {"spot", MakeSpotTechnique},
    {"vsdct", MakeVsdctTechnique},
    {"paraboloid", MakeParaboloidTechnique},
    {"asm", MakeAsmTechnique},
};
}  // namespace

std::vector<std::string> TechniqueNames() {
  std::vector<std::string> names;
  for (const Entry& e : kTechniques) names.push_back(e.name);
  return names;
}

std::unique_ptr<Technique> CreateTechnique(const std::string& name) {
  for (const Entry& e : kTechniques)
    if (name == e.name) return e.make();
  std::string list;
  for (const Entry& e : kTechniques) list += (list.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown technique '" + name + "' (available: " + list + ")");
}

}  // namespace sp::tech
