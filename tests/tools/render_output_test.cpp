// `fxraster render` never leaves stale output (issue 9): a run writes into a temporary folder and
// renames it at the end; a failed run removes the previous run's files; a folder holding other
// files is never replaced; image sizes beyond the PNG writer are refused before any work.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

namespace fs = std::filesystem;

const std::string kSmall = "render --default --no-bunny --quiet --width 24 --height 16 --spot-checks 10 ";

TEST(RenderOutput, FailedRunLeavesNoPreviousRunsFiles) {
  const std::string d = scratch();
  ASSERT_EQ(run_cli(d, kSmall + "--out '" + d + "/out'").exit, 0);
  ASSERT_TRUE(fs::exists(d + "/out/stats.json"));
  write_file(d + "/bad.json", R"({"version": 1, "viewport": {"width": 8, "height": 1e400}, "objects": []})");
  const CliResult r = run_cli(d, "render '" + d + "/bad.json' --quiet --out '" + d + "/out'");
  EXPECT_EQ(r.exit, 2) << r.err;
  EXPECT_FALSE(fs::exists(d + "/out/stats.json")) << "the previous run's stats.json is still there";
  EXPECT_FALSE(fs::exists(d + "/out"));
  for (const auto& e : fs::directory_iterator(d))  // no temporary folder left either
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
}

TEST(RenderOutput, SuccessfulRunReplacesThePreviousOne) {
  const std::string d = scratch();
  ASSERT_EQ(run_cli(d, kSmall + "--out '" + d + "/out'").exit, 0);
  ASSERT_TRUE(fs::exists(d + "/out/image_affine.png"));
  // Second run without the affine image: its files only, none of the first run's.
  ASSERT_EQ(run_cli(d, kSmall + "--no-affine-image --out '" + d + "/out/'").exit, 0);
  EXPECT_TRUE(fs::exists(d + "/out/stats.json"));
  EXPECT_FALSE(fs::exists(d + "/out/image_affine.png")) << "a file of the previous run survived";
}

TEST(RenderOutput, FolderWithOtherFilesIsNeverReplaced) {
  const std::string d = scratch();
  write_file(d + "/mine/notes.txt", "keep me");
  const CliResult r = run_cli(d, kSmall + "--out '" + d + "/mine'");
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("notes.txt"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(d + "/mine/notes.txt"), "keep me");
  write_file(d + "/afile", "x");
  EXPECT_EQ(run_cli(d, kSmall + "--out '" + d + "/afile'").exit, 2);
  EXPECT_EQ(read_file(d + "/afile"), "x");
}

TEST(RenderOutput, OversizedImagesAreRefusedBeforeAnyWork) {
  const std::string d = scratch();
  const auto t0 = std::chrono::steady_clock::now();
  const CliResult r = run_cli(d, "render --default --quiet --width 16384 --height 16384 --out '" + d + "/out'");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.exit, 2) << r.err;
  EXPECT_NE(r.err.find("16384x16384"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-affine-image"), std::string::npos) << r.err;
  EXPECT_LT(s, 20.0) << "refused only after rendering";  // the render itself took 113 s
  EXPECT_FALSE(fs::exists(d + "/out"));
}

TEST(RenderOutput, FilterOptionShadesBilinearAndTheReportMeasuresBothFilters) {
  const std::string d = scratch();
  ASSERT_EQ(run_cli(d, kSmall + "--filter bilinear --out '" + d + "/bil'").exit, 0);
  ASSERT_EQ(run_cli(d, kSmall + "--out '" + d + "/near'").exit, 0);
  const nlohmann::json b = nlohmann::json::parse(read_file(d + "/bil/report.json"));
  const nlohmann::json n = nlohmann::json::parse(read_file(d + "/near/report.json"));
  EXPECT_EQ(b["texture_filter"], "bilinear");
  EXPECT_EQ(n["texture_filter"], "nearest");  // the configuration's default
  for (const char* f : {"nearest", "bilinear"}) {
    const auto& own = b["texel_errors"]["filters"][f]["vs_exact_own_coordinates"];
    EXPECT_GT(own["checked"].get<uint64_t>(), 0u) << f;
    EXPECT_EQ(own["same_texels"], own["checked"]) << f;  // the unit is exact on its own coordinates
    EXPECT_LE(own["weight_error_lsb"]["max"].get<double>(), 0.5) << f;
    EXPECT_GT(b["texel_errors"]["filters"][f]["vs_exact_ideal"]["checked"].get<uint64_t>(), 0u) << f;
  }
  EXPECT_NE(read_file(d + "/bil/image.png"), read_file(d + "/near/image.png")) << "bilinear shades differently";
  EXPECT_NE(read_file(d + "/bil/report.md").find("## Texel error"), std::string::npos);
  const CliResult bad = run_cli(d, kSmall + "--filter trilinear --out '" + d + "/bad'");
  EXPECT_NE(bad.exit, 0);
  EXPECT_NE(bad.err.find("--filter"), std::string::npos) << bad.err;
}

TEST(RenderOutput, TextureLargerThanTheAddressUnitIsRefusedNamingTheField) {
  const std::string d = scratch();
  write_file(d + "/cfg.json", R"({"version": 1, "tex_addr": {"size_bits": 5}})");  // 32 < the 64-texel checker
  const CliResult r = run_cli(d, kSmall + "--config '" + d + "/cfg.json' --out '" + d + "/out'");
  EXPECT_EQ(r.exit, 2) << r.err;
  EXPECT_NE(r.err.find("tex_addr.size_bits"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d + "/out"));
}

// A NaN / Inf varying (docs/pipeline.md, stage 1): the triangle is drawn, with as many fragments
// as the same triangle with finite varyings, and stats.json and report.md count it.
TEST(RenderOutput, NonFiniteVaryingIsDrawnAndCounted) {
  const std::string d = scratch();
  const auto scene = [](const std::string& a, const std::string& b) {
    return R"({"version": 1, "viewport": {"width": 32, "height": 32}, "objects": [{"type": "clip", "triangles": [[)"
           R"({"pos": [-0.9, -0.9, 0.5, 1], "var": [)" + a + R"(, 0]}, {"pos": [0.9, -0.8, 0.5, 1], "var": [1, )" + b +
           R"(]}, {"pos": [0, 0.9, 0.5, 1], "var": [0, 1]}]]}]})";
  };
  write_file(d + "/nan.json", scene("\"nan\"", "\"-inf\""));
  write_file(d + "/fin.json", scene("0", "1"));
  for (const char* n : {"nan", "fin"}) {
    const CliResult r = run_cli(d, std::string("render '") + d + "/" + n + ".json' --quiet --out '" + d + "/" + n + "'");
    ASSERT_EQ(r.exit, 0) << r.err;
  }
  const std::string sn = read_file(d + "/nan/stats.json"), sf = read_file(d + "/fin/stats.json");
  EXPECT_NE(sn.find("\"prims_varying_nonfinite\": 1"), std::string::npos) << sn;
  EXPECT_NE(sn.find("\"prims_drawn\": 1"), std::string::npos) << sn;
  EXPECT_NE(sf.find("\"prims_varying_nonfinite\": 0"), std::string::npos) << sf;
  const auto field = [](const std::string& j, const std::string& k) {  // first occurrence: the model's
    const size_t p = j.find("\"" + k + "\": ");
    return p == std::string::npos ? std::string() : j.substr(p, j.find('\n', p) - p);
  };
  EXPECT_EQ(field(sn, "fragments_generated"), field(sf, "fragments_generated"));
  EXPECT_NE(field(sf, "fragments_generated"), "\"fragments_generated\": 0,");
  const std::string md = read_file(d + "/nan/report.md");
  EXPECT_NE(md.find("NaN / ±Inf varying replaced by 0 / ±FLT_MAX (docs/pipeline.md, stage 1) | 1 | 1 |"), std::string::npos)
      << md;
}

TEST(VectorsOutput, FinishedFilesOnlyAndThePreviousPairReplaced) {
  const std::string d = scratch();
  for (int count : {40, 3}) {
    ASSERT_EQ(run_cli(d, "vectors div --count " + std::to_string(count) + " --seed 9 --out '" + d + "/v'").exit, 0);
    for (const auto& e : fs::directory_iterator(d + "/v"))
      EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
  }
  const CliResult r = run_cli(d, "vectors check '" + d + "/v/div.hex'");  // the second run's pair
  EXPECT_EQ(r.exit, 0) << r.err;
  EXPECT_NE(r.out.find("77 vectors"), std::string::npos) << r.out;  // 74 directed + 3 random
}

}  // namespace
}  // namespace fxr::test
