// `shadowport hlslc --survey`: compiles every entry point of a shader tree and writes a markdown
// report of what ports and what does not, for users sizing a port before starting it.
#pragma once
#include <string>
#include <vector>

namespace sp::cli {

// The survey's lines in `hlslc --help`.
extern const char kSurveyUsage[];

// `argv`: hlslc's arguments, `--survey DIR` among them. Returns 0 when the survey ran (failures
// are the report's content, not an error); throws std::invalid_argument for bad usage.
int RunHlslcSurvey(const std::vector<std::string>& argv);

}  // namespace sp::cli
