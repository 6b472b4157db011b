// The `shadowport` command-line program: one function per sub-command.
#pragma once
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sp {
enum class Backend : uint8_t;
}

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
// --backend of a command that renders: vulkan or gl. "null" is refused with the reason (a null
// device draws nothing), anything else naming `valid`, the values the command accepts.
Backend ParseRenderingBackend(const std::string& text, const std::string& valid);
std::map<std::string, std::string> ParseParams(const std::vector<std::string>& params);  // k=v
void WritePng(const std::string& path, uint32_t w, uint32_t h, const uint8_t* rgba);
// "a,b,c"; an empty item is an error naming --option.
std::vector<std::string> SplitList(const std::string& text, const std::string& option);
uint64_t ParseCount(const std::string& text, const std::string& option, uint64_t min, uint64_t max);

// Progress lines on stderr, each stamped with the time since construction ("[ 1:23.4] ..."), so a
// long run shows both what it is doing and how long it has taken.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string prefix = "");
  void operator()(const std::string& line) const;
  double Seconds() const;

 private:
  std::string prefix_;
  std::chrono::steady_clock::time_point start_;
};

// Runs eval/report/report.py on results files; returns its exit status.
int RunReportScript(const std::vector<std::string>& results, const std::string& out, const std::vector<std::string>& extraArgs);

int RunRender(const Args& args);
int RunHlslc(const std::vector<std::string>& argv);
int RunHlslcFx(const std::vector<std::string>& argv);  // hlslc --fx
int RunDemo(const Args& args);
int RunConformance(const Args& args);
int RunBench(const Args& args);
int RunReport(const Args& args);
int RunAdvise(const Args& args);  // cli/advise.cpp
int RunSdsmCost(const Args& args);  // cli/sdsm-cost.cpp

// hlslc --survey DIR (cli/hlslc-survey.cpp): compiles every entry point of a shader tree and
// writes a markdown report. Returns 0 when the survey ran, failures included; throws
// std::invalid_argument for bad usage.
int RunHlslcSurvey(const std::vector<std::string>& argv);
extern const char kSurveyUsage[];  // its lines in `hlslc --help`

}  // namespace sp::cli
