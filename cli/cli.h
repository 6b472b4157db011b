// The `shadowport` command-line program: one function per sub-command.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace sp::cli {

// Minimal argument reader: `--name value`, `--name=value`, repeated options, positionals.
class Args {
 public:
  Args(std::vector<std::string> args, const std::vector<std::string>& flagsWithoutValue = {});
  bool has(const std::string& name) const;
  std::string get(const std::string& name, const std::string& fallback = "") const;
  std::vector<std::string> getAll(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // Throws for options not in `known`, naming the bad option and the valid ones.
  void expectOnly(const std::vector<std::string>& known) const;

 private:
  std::multimap<std::string, std::string> options_;
  std::vector<std::string> positionals_;
};

void ParseSize(const std::string& text, uint32_t* w, uint32_t* h);  // "1280x720"
std::map<std::string, std::string> ParseParams(const std::vector<std::string>& params);  // k=v
void WritePng(const std::string& path, uint32_t w, uint32_t h, const uint8_t* rgba);

int RunRender(const Args& args);
int RunHlslc(const std::vector<std::string>& argv);
int RunDemo(const Args& args);
int RunConformance(const Args& args);
int RunBench(const Args& args);
int RunReport(const Args& args);

}  // namespace sp::cli
