// `shadowport hlslc` argument handling (cli/hlslc-args.cpp) on input found by fuzzing
// (fuzz/corpus/cli-arguments/regression-*): a bad argument is std::invalid_argument naming it.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "../../cli/hlslc-args.h"

namespace sp::test {
namespace {

// "/Zpr" followed by 300 bytes: asking the file system whether it exists threw
// std::filesystem::filesystem_error ("File name too long"), which nothing caught.
TEST(HlslcArguments, AnOptionTooLongForAFileNameIsAnUnknownOption) {
  const std::string arg = "/Zpr" + std::string(300, 'x');
  try {
    (void)cli::ParseHlslcArguments({"-T", "ps_5_0", arg});
    FAIL() << "accepted " << arg.size() << " bytes as an option";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown option /Zpr"), std::string::npos) << e.what();
  }
}

// A long absolute path with a second '/' is still the input file: only the compile reads it.
TEST(HlslcArguments, ALongPathIsTheInputFile) {
  const std::string path = "/no-such-dir/" + std::string(300, 'y') + ".hlsl";
  cli::HlslcCommand c = cli::ParseHlslcArguments({"-T", "ps_5_0", path});
  EXPECT_EQ(c.file, path);
  EXPECT_EQ(c.target, "ps_5_0");
}

}  // namespace
}  // namespace sp::test
