// `fxraster sweep --out` never leaves stale output (issue 9): the sweep writes into a temporary
// folder beside the target and renames it at the end; a failed run leaves no partial output and
// removes the previous run's files (they must not pass for this run's); a folder holding other
// files is never replaced; the synthesis cache survives both.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

namespace fs = std::filesystem;

const std::string kQuick = "sweep div --count 200 --no-timing ";

void expect_no_partial(const std::string& d) {
  for (const auto& e : fs::directory_iterator(d))
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
}

TEST(SweepOutput, SuccessfulRunReplacesThePreviousOne) {
  const std::string d = scratch();
  ASSERT_EQ(run_cli(d, kQuick + "--out '" + d + "/out'").exit, 0);
  ASSERT_TRUE(fs::exists(d + "/out/sweep.csv"));
  ASSERT_TRUE(fs::exists(d + "/out/error_vs_latency.png")) << "matplotlib missing?";
  // Second run without plots: its files only, none of the first run's.
  const CliResult r = run_cli(d, kQuick + "--no-plots --out '" + d + "/out/'");
  ASSERT_EQ(r.exit, 0) << r.err;
  EXPECT_TRUE(fs::exists(d + "/out/sweep.csv"));
  EXPECT_TRUE(fs::exists(d + "/out/report.md"));
  EXPECT_FALSE(fs::exists(d + "/out/error_vs_latency.png")) << "a file of the previous run survived";
  EXPECT_NE(r.out.find(d + "/out/sweep.csv"), std::string::npos) << r.out;  // the final path, not the temporary one
  expect_no_partial(d);
}

// A run that fails after it has written files (synthesis without yosys on the PATH: the sweep,
// the package and the configuration list are written before synth_cost.py fails).
TEST(SweepOutput, FailedRunLeavesNoPartialOutputAndRemovesThePreviousRun) {
  const std::string d = scratch();
  ASSERT_EQ(run_cli(d, kQuick + "--no-plots --out '" + d + "/out'").exit, 0);
  ASSERT_TRUE(fs::exists(d + "/out/sweep.csv"));
  const std::string cmd = "PATH=/nonexistent '" + fxraster() + "' " + kQuick + "--no-plots --synth --out '" + d +
                          "/out' > '" + d + "/fail.out' 2> '" + d + "/fail.err'";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 2) << read_file(d + "/fail.err");
  EXPECT_NE(read_file(d + "/fail.err").find("synth_cost.py failed"), std::string::npos) << read_file(d + "/fail.err");
  EXPECT_FALSE(fs::exists(d + "/out/sweep.csv")) << "the previous run's sweep.csv is still there";
  EXPECT_FALSE(fs::exists(d + "/out")) << "partial or previous output left";
  expect_no_partial(d);
}

// The synthesis cache is not output: a failed run puts it back, a successful one carries it on.
TEST(SweepOutput, SynthesisCacheSurvivesFailedAndSuccessfulRuns) {
  const std::string d = scratch();
  write_file(d + "/out/synth_cache/entry.json", "{}");
  const std::string cmd = "PATH=/nonexistent '" + fxraster() + "' " + kQuick + "--no-plots --synth --out '" + d +
                          "/out' > /dev/null 2>&1";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 2);
  EXPECT_EQ(read_file(d + "/out/synth_cache/entry.json"), "{}");
  EXPECT_FALSE(fs::exists(d + "/out/sweep.csv"));
  ASSERT_EQ(run_cli(d, kQuick + "--no-plots --out '" + d + "/out'").exit, 0);
  EXPECT_EQ(read_file(d + "/out/synth_cache/entry.json"), "{}");
  EXPECT_TRUE(fs::exists(d + "/out/sweep.csv"));
  expect_no_partial(d);
}

TEST(SweepOutput, FolderWithOtherFilesIsNeverReplaced) {
  const std::string d = scratch();
  write_file(d + "/mine/notes.txt", "keep me");
  const CliResult r = run_cli(d, kQuick + "--no-plots --out '" + d + "/mine'");
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("notes.txt"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(d + "/mine/notes.txt"), "keep me");
  write_file(d + "/afile", "x");
  EXPECT_EQ(run_cli(d, kQuick + "--no-plots --out '" + d + "/afile'").exit, 2);
  EXPECT_EQ(read_file(d + "/afile"), "x");
  expect_no_partial(d);
}

}  // namespace
}  // namespace fxr::test
