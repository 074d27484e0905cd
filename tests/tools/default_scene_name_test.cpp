// The default scene's name says what was drawn (frontend/scene_default.cpp): `--no-bunny` (render,
// cosim, vectors scene, …) must not name a bunny that is not in the image. The name is checked
// against what the run reports it drew, not against the code's own string: the triangle count
// (the face alone is 2 triangles, docs/references.md#seed-000) and the skipped-mesh note.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

namespace fs = std::filesystem;

const std::string kBunnyObj = "/usr/share/glmark2/models/bunny.obj";  // the default scene's optional mesh
constexpr size_t kFaceTriangles = 2;  // the checkerboard face: two triangles
const std::string kSmall = "--width 32 --height 24 ";

// The first line of `fxraster render` names the scene: "fxraster render: NAME".
std::string printed_name(const std::string& out) {
  const std::string head = "fxraster render: ";
  if (out.rfind(head, 0) != 0) return "";
  return out.substr(head.size(), out.find('\n') - head.size());
}

// Renders the default scene into d/out with `flags`; returns report.json.
nlohmann::json render_default(const std::string& d, const std::string& flags, std::string* stdout_text) {
  const CliResult r = run_cli(d, "render --default " + kSmall + "--no-affine-image --spot-checks 10 " + flags +
                                     " --out '" + d + "/out'");
  EXPECT_EQ(r.exit, 0) << r.err;
  *stdout_text = r.out;
  return nlohmann::json::parse(read_file(d + "/out/report.json"));
}

TEST(DefaultSceneName, WithoutTheBunnyTheNameSaysSo) {
  const std::string d = scratch();
  std::string out;
  const nlohmann::json rep = render_default(d, "--no-bunny", &out);
  const std::string name = rep["scene"].get<std::string>();
  EXPECT_EQ(rep["stats"]["triangles"].get<size_t>(), kFaceTriangles) << "the face alone";
  EXPECT_EQ(name.find("+ bunny"), std::string::npos) << name;
  EXPECT_NE(name.find("without the bunny (--no-bunny)"), std::string::npos) << name;
  EXPECT_EQ(printed_name(out), name) << out;
  EXPECT_EQ(read_file(d + "/out/report.md").rfind("# fxraster render: " + name + "\n", 0), 0u);
  // The wireframe variant draws the face's edges only: no bunny silhouette named either.
  const nlohmann::json w = render_default(d, "--no-bunny --wireframe", &out);
  const std::string wn = w["scene"].get<std::string>();
  EXPECT_EQ(wn.find("silhouette"), std::string::npos) << wn;
  EXPECT_NE(wn.find("without the bunny (--no-bunny), wireframe (face edges)"), std::string::npos) << wn;
}

TEST(DefaultSceneName, WithTheBunnyTheNameSaysSo) {
  if (!fs::exists(kBunnyObj)) GTEST_SKIP() << kBunnyObj << " not installed (glmark2-data)";
  const std::string d = scratch();
  std::string out;
  const nlohmann::json rep = render_default(d, "", &out);
  const std::string name = rep["scene"].get<std::string>();
  EXPECT_GT(rep["stats"]["triangles"].get<size_t>(), kFaceTriangles) << "the bunny's triangles too";
  EXPECT_TRUE(rep["notes"].empty()) << rep["notes"];
  EXPECT_NE(name.find("+ bunny (glmark2-data)"), std::string::npos) << name;
  EXPECT_EQ(name.find("without"), std::string::npos) << name;
  EXPECT_EQ(printed_name(out), name) << out;
}

// `fxraster cosim --no-bunny` (the co-simulation executable reads the same default scene).
TEST(DefaultSceneName, CosimWithoutTheBunnyTheNameSaysSo) {
  const std::string cosim = env_or("FXRASTER_COSIM", binary_dir() + "/tb/fxraster-cosim");
  if (!fs::exists(cosim)) GTEST_SKIP() << cosim << " not built (FXR_RTL off)";
  const std::string d = scratch();
  const CliResult r = run_cli(d, "cosim --default --no-bunny " + kSmall + "--out '" + d + "/cosim'");
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  const nlohmann::json rep = nlohmann::json::parse(read_file(d + "/cosim/report.json"));
  const std::string name = rep["scene"]["name"].get<std::string>();
  EXPECT_EQ(rep["scene"]["triangles"].get<size_t>(), kFaceTriangles) << "the face alone";
  EXPECT_EQ(name.find("+ bunny"), std::string::npos) << name;
  EXPECT_NE(name.find("without the bunny (--no-bunny)"), std::string::npos) << name;
  EXPECT_EQ(read_file(d + "/cosim/report.md").rfind("# fxraster cosim: " + name + "\n", 0), 0u);
}

}  // namespace
}  // namespace fxr::test
