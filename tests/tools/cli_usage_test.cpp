// The command line's usage errors: exit status 2 with the offending option or subcommand named on
// stderr (README "The command line"), --help / --version exit 0. CLI11 alone would exit with its
// own codes (105, 106, 109 …), which a script cannot tell apart from a crash.
#include <gtest/gtest.h>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

TEST(CliUsage, UsageErrorsExit2NamingTheOption) {
  const std::string d = scratch();
  struct Case {
    const char* args;
    const char* named;  // what stderr must name
  };
  const Case cases[] = {
      {"render --default", "--out"},                             // a required option missing
      {"render --default --out x --no-such-flag", "--no-such-flag"},  // an unknown option
      {"render --default --out x --width 0", "--width"},        // a value out of range
      {"render --default --out x --threads many", "--threads"},  // not a number
      {"render --out x", "--default"},                            // neither SCENE nor --default
      {"render s.json --default --out x", "--default"},           // both
      {"analyze", "--default"},                                   // the same check in every
      {"budget --out x", "--default"},                            // subcommand reading a scene
      {"cycles --out x", "--default"},                            // (app/scene_input.hpp)
      {"cycles --default --out x --width 0", "--width"},         // the same ranges too
      {"no-such-command", "no-such-command"},                    // an unknown subcommand
      {"", "subcommand"},                                        // no subcommand
  };
  for (const Case& c : cases) {
    const CliResult r = run_cli(d, c.args);
    EXPECT_EQ(r.exit, 2) << "fxraster " << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.named), std::string::npos) << "fxraster " << c.args << "\n" << r.err;
  }
}

TEST(CliUsage, HelpAndVersionExit0) {
  const std::string d = scratch();
  for (const char* args : {"--help", "render --help", "--version"}) {
    const CliResult r = run_cli(d, args);
    EXPECT_EQ(r.exit, 0) << "fxraster " << args << "\n" << r.err;
    EXPECT_FALSE(r.out.empty()) << "fxraster " << args;
  }
}

}  // namespace
}  // namespace fxr::test
