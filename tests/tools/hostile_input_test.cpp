// Hostile input (issue 9): every case ends in exit status 2 with a message that names the file
// and the field (JSON path, or file:line), is bounded in length, and leaves no output behind.
// The expected pieces come from the formats' documentation (docs/scene-format.md,
// docs/vectors.md, docs/number-formats.md "Reading input"), not from the code.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Longest error message accepted (the issue measured 10 MB for one input).
constexpr size_t kMaxMessageBytes = 1024;
// Nesting that overflowed the stack before the limit (the issue used ~60 k levels).
constexpr int kDeep = 100000;

std::string nest(int depth) { return std::string((size_t)depth, '[') + std::string((size_t)depth, ']'); }

std::string scene_with(const std::string& name_value, const std::string& version = "1",
                       const std::string& viewport = R"({"width": 8, "height": 8})",
                       const std::string& objects = "[]", const std::string& extra = "") {
  return "{\"version\": " + version + ", \"name\": " + name_value + ", \"viewport\": " + viewport +
         ", \"objects\": " + objects + extra + "}";
}

std::string clip_scene(const std::string& pos0) {
  return scene_with("\"t\"", "1", R"({"width": 8, "height": 8})",
                    R"([{"type": "clip", "triangles": [[{"pos": [)" + pos0 +
                        R"(, 0, 0.5, 1], "var": [0, 0]}, {"pos": [1, 0, 0.5, 1], "var": [0, 0]}, {"pos": [0, 1, 0.5, 1], "var": [0, 0]}]]}])");
}

struct Case {
  std::string name;
  std::string scene;               // written to <dir>/in.json
  std::string args;                // after the command; {in} and {dir} are replaced
  std::vector<std::string> want;   // pieces the message must contain
  std::string obj = "";            // optional: written to <dir>/m.obj
};

std::string expand(std::string s, const std::string& dir) {
  for (size_t p; (p = s.find("{dir}")) != std::string::npos;) s.replace(p, 5, dir);
  for (size_t p; (p = s.find("{in}")) != std::string::npos;) s.replace(p, 4, dir + "/in.json");
  return s;
}

std::string cut_for_log(const std::string& s) { return s.size() > 2000 ? s.substr(0, 2000) + "..." : s; }

// Runs every case: exit 2, the pieces, a bounded message, no output folder content.
void run_cases(const std::vector<Case>& cases, int* tried) {
  const std::string d = scratch();
  for (const Case& c : cases) {
    fs::remove_all(d + "/out");
    write_file(d + "/in.json", c.scene);
    if (!c.obj.empty()) write_file(d + "/m.obj", c.obj);
    const CliResult r = run_cli(d, expand(c.args, d));
    ++*tried;
    EXPECT_EQ(r.exit, 2) << c.name << "\n" << cut_for_log(r.err);
    for (const auto& w : c.want) EXPECT_NE(r.err.find(expand(w, d)), std::string::npos) << c.name << ": no '" << w << "' in\n" << cut_for_log(r.err);
    EXPECT_LE(r.err.size(), kMaxMessageBytes) << c.name;
    EXPECT_FALSE(fs::exists(d + "/out/stats.json")) << c.name << ": output written";
  }
}

const std::string kRender = "render {in} --quiet --no-affine-image --spot-checks 10 --out {dir}/out";

TEST(HostileInput, SceneNestingNumbersAndNarrowing) {
  const std::vector<Case> cases = {
      {"deep name", scene_with(nest(kDeep)), kRender, {"in.json: /name/0/0", "nesting deeper than 64"}},
      {"deep version", scene_with("\"x\"", nest(kDeep)), kRender, {"in.json: /version/0", "nesting"}},
      {"deep objects", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", nest(kDeep)), kRender,
       {"in.json: /objects/0", "nesting"}},
      {"1e400 in viewport", scene_with("\"x\"", "1", R"({"width": 8, "height": 1e400})"), kRender,
       {"in.json: /viewport/height", "1e400", "outside the range of a double"}},
      {"1e400 in clip pos", clip_scene("1e400"), kRender, {"in.json: /objects/0/triangles/0/0/pos/0", "1e400"}},
      {"1e39 in clip pos", clip_scene("1e39"), kRender, {"in.json: /objects/0/triangles/0/0/pos/0", "overflows float32"}},
      {"\"1e400\" in clip pos", clip_scene("\"1e400\""), kRender, {"/objects/0/triangles/0/0/pos/0", "overflows float32"}},
      {"\"1e5000\" in clip pos", clip_scene("\"1e5000\""), kRender, {"/objects/0/triangles/0/0/pos/0", "overflows float32"}},
      {"\"infinity\" spelling", clip_scene("\"Infinity\""), kRender, {"/objects/0/triangles/0/0/pos/0", "bad number"}},
      {"bits negative", clip_scene("\"bits:-0000001\""), kRender, {"/pos/0", "bad bit pattern"}},
      {"bits space", clip_scene("\"bits: 7fc0000\""), kRender, {"/pos/0", "bad bit pattern"}},
      {"bits 0x", clip_scene("\"bits:0x7fc000\""), kRender, {"/pos/0", "bad bit pattern"}},
      {"bits uppercase", clip_scene("\"bits:7FC00000\""), kRender, {"/pos/0", "lowercase"}},
      {"version 2^32+1", scene_with("\"x\"", "4294967297"), kRender, {"in.json: /version", "4294967297", "not supported"}},
      {"version 1.0", scene_with("\"x\"", "1.0"), kRender, {"in.json: /version", "expected an integer"}},
      {"squares 0 (fuzz finding: division by zero)", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                                              R"(, "texture": {"kind": "checker", "size": 64, "squares": 0})"),
       kRender, {"in.json: /texture/squares", "0 is outside [1, 4096]"}},
      {"width 0", scene_with("\"x\"", "1", R"({"width": 0, "height": 8})"), kRender, {"in.json: /viewport/width", "0 is outside"}},
      {"width 2^32+1", scene_with("\"x\"", "1", R"({"width": 4294967297, "height": 8})"), kRender,
       {"in.json: /viewport/width", "4294967297 is outside"}},
      {"width 2^64-1", scene_with("\"x\"", "1", R"({"width": 18446744073709551615, "height": 8})"), kRender,
       {"in.json: /viewport/width", "18446744073709551615 is outside"}},
      {"width 1e20", scene_with("\"x\"", "1", R"({"width": 99999999999999999999, "height": 8})"), kRender,
       {"in.json: /viewport/width", "expected an integer"}},
      {"2M-element array", scene_with("\"x\"", "1", "{\"width\": [" + [] {
                                        std::string s = "\"x\"";
                                        for (int i = 1; i < 2000000; ++i) s += ",\"x\"";
                                        return s;
                                      }() + "], \"height\": 8}"),
       kRender, {"in.json: /viewport/width", "array of 2000000 elements"}},
      {"huge unknown key", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                      ", \"" + std::string(1000000, 'k') + "\": 1"),
       kRender, {"in.json: /kkkk", "unknown field"}},
      {"up parallel (given)", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                         R"(, "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 0, 1], "fovy_deg": 45, "near": 1, "far": 6})"),
       kRender, {"in.json: /camera/up", "parallel to the view direction"}},
      {"up parallel (default)", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                           R"(, "camera": {"eye": [0, 3, 0], "target": [0, 0, 0], "fovy_deg": 45, "near": 1, "far": 6})"),
       kRender, {"in.json: /camera/up", "default up (0, 1, 0) is parallel"}},
      {"eye == target", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                   R"(, "camera": {"eye": [1, 1, 1], "target": [1, 1, 1], "fovy_deg": 45, "near": 1, "far": 6})"),
       kRender, {"in.json: /camera/target", "equals 'eye'"}},
      {"varyings count 0, default u/v", scene_with("\"x\"", "1", R"({"width": 8, "height": 8})", "[]",
                                                   R"(, "varyings": {"count": 0})"),
       kRender, {"in.json: /varyings/count", "texture coordinate 'u'"}},
  };
  int tried = 0;
  run_cases(cases, &tried);
  std::printf("hostile scenes tried: %d\n", tried);
}

TEST(HostileInput, ObjIndicesAreChecked) {
  const std::string mesh = R"(, "objects": [{"type": "mesh", "obj": "m.obj"}])";
  const std::string s = "{\"version\": 1, \"viewport\": {\"width\": 8, \"height\": 8}" + mesh + "}";
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<Case> cases = {
      {"huge index", s, kRender, {"in.json: /objects/0/obj", "m.obj:4: face vertex index '99999999999999999999'", "no such vertex"},
       v3 + "f 1 2 99999999999999999999\n"},
      {"index 0", s, kRender, {"m.obj:4: face vertex index '0'"}, v3 + "f 0 1 2\n"},
      {"index 4 of 3", s, kRender, {"m.obj:4", "the file has 3"}, v3 + "f 1 2 4\n"},
      {"relative index before the start", s, kRender, {"m.obj:4", "'-4'"}, v3 + "f -1 -2 -4\n"},
      {"vt out of range", s, kRender, {"m.obj:5: face texcoord index '7'", "no such texcoord"},
       v3 + "vt 0 0\nf 1/1 2/7 3/1\n"},
      {"index not a number", s, kRender, {"m.obj:4", "not an integer"}, v3 + "f 1 2 x\n"},
  };
  int tried = 0;
  run_cases(cases, &tried);
  std::printf("hostile OBJ files tried: %d\n", tried);
}

TEST(HostileInput, ConfigurationFiles) {
  const std::string cfg = "config --config {in} --emit-sv {dir}/out/pkg.sv";
  const std::vector<Case> cases = {
      {"deep field", "{\"version\": 1, \"recip\": {\"nr_steps\": " + nest(kDeep) + "}}", cfg, {"in.json: /recip/nr_steps/0", "nesting"}},
      {"1e400", R"({"version": 1, "recip": {"nr_steps": 1e400}})", cfg, {"in.json: /recip/nr_steps", "1e400"}},
      {"width 2^32+1", R"({"version": 1, "recip": {"nr_steps": 4294967297}})", cfg, {"in.json", "nr_steps", "4294967297 is outside"}},
      {"width 2^64-1", R"({"version": 1, "recip": {"nr_steps": 18446744073709551615}})", cfg,
       {"in.json", "nr_steps", "18446744073709551615 is outside"}},
      {"fraction", R"({"version": 1, "recip": {"nr_steps": 2.5}})", cfg, {"in.json", "nr_steps", "expected an integer"}},
      {"version 2^32+1", R"({"version": 4294967297})", cfg, {"in.json", "'version'", "not supported"}},
      {"truncated", R"({"version": 1, "recip": {)", cfg, {"in.json:1:", "parse error"}},
      {"render --config deep", "{\"version\": 1, \"div\": " + nest(kDeep) + "}",
       "render --default --no-bunny --quiet --config {in} --out {dir}/out", {"in.json: /div/0", "nesting"}},
      {"render --config 1e400", R"({"version": 1, "raster": {"subpixel_bits": -1e400}})",
       "render --default --no-bunny --quiet --config {in} --out {dir}/out", {"in.json: /raster/subpixel_bits", "-1e400"}},
  };
  int tried = 0;
  run_cases(cases, &tried);
  EXPECT_FALSE(fs::exists(binary_dir() + "/test_cli/HostileInput.ConfigurationFiles/out/pkg.sv"));
  std::printf("hostile configuration files tried: %d\n", tried);
}

// Vector manifests and hex files: each case edits a freshly generated div vector set.
TEST(HostileInput, VectorManifestsAndHexFiles) {
  const std::string d = scratch();
  const std::string gen = "vectors div --count 4 --seed 3 --out '" + d + "/v'";
  struct VCase {
    std::string name;
    std::function<void(json&)> manifest;            // edits the manifest (or null)
    std::function<void(std::string&)> hex;          // edits the hex text (or null)
    std::string raw_manifest;                       // replaces the manifest text when non-empty
    std::vector<std::string> want;
  };
  const std::vector<VCase> cases = {
      {"format_version 1.9", [](json& m) { m["format_version"] = 1.9; }, nullptr, "", {"div.json", "'format_version'", "expected an integer"}},
      {"format_version 2^32+1", [](json& m) { m["format_version"] = 4294967297ull; }, nullptr, "",
       {"div.json", "'format_version'", "4294967297 is outside"}},
      {"seed 2.25e59", [](json& m) { m["seed"] = 2.25e59; }, nullptr, "", {"div.json", "'seed'", "expected an integer"}},
      {"seed negative", [](json& m) { m["seed"] = -1; }, nullptr, "", {"div.json", "'seed'", "-1 is outside"}},
      {"cases wrap uint64", [](json& m) {
         // 74 directed, then 2^64 − 1 and 5: the sum wraps to the 78 lines of 'count'.
         m["cases"][1]["count"] = 18446744073709551615ull;
         m["cases"][2] = {{"kind", "x"}, {"first_line", 74}, {"count", 5}};
       }, nullptr, "", {"div.json", "'cases'", "runs past"}},
      {"first_line 0", [](json& m) { m["cases"][0]["first_line"] = 0; }, nullptr, "", {"div.json", "'cases'"}},
      {"deep seed", nullptr, nullptr, "DEEP", {"div.json: /seed/0", "nesting"}},
      {"1e400 seed", nullptr, nullptr, "E400", {"div.json: /seed", "1e400"}},
      {"uppercase hex", nullptr, [](std::string& h) {
         const size_t p = h.find_first_of("abcdef");
         h[p] = (char)(h[p] - 'a' + 'A');
       }, "", {"div.hex:", "uppercase"}},
      {"denominator without msb", nullptr, [](std::string& h) {
         // Line 1: in_num (8 digits) in_den (8 digits) ...: clear the denominator's msb.
         h.replace(8, 8, "00000001");
       }, "", {"div.hex:1", "input domain"}},
  };
  int tried = 0;
  for (const VCase& c : cases) {
    fs::remove_all(d + "/v");
    ASSERT_EQ(run_cli(d, gen).exit, 0);
    const std::string mp = d + "/v/div.json", hp = d + "/v/div.hex";
    if (c.manifest) {
      json m = json::parse(read_file(mp));
      c.manifest(m);
      write_file(mp, m.dump(2));
    }
    if (c.raw_manifest == "DEEP") {
      std::string t = read_file(mp);
      const size_t p = t.find("\"seed\": ") + 8;
      t.replace(p, t.find_first_of(",\n}", p) - p, nest(kDeep));
      write_file(mp, t);
    } else if (c.raw_manifest == "E400") {
      std::string t = read_file(mp);
      const size_t p = t.find("\"seed\": ") + 8;
      t.replace(p, t.find_first_of(",\n}", p) - p, "1e400");
      write_file(mp, t);
    }
    if (c.hex) {
      std::string h = read_file(hp);
      c.hex(h);
      write_file(hp, h);
    }
    const CliResult r = run_cli(d, "vectors check '" + hp + "'");
    ++tried;
    EXPECT_EQ(r.exit, 2) << c.name << "\n" << cut_for_log(r.err + r.out);
    for (const auto& w : c.want) EXPECT_NE(r.err.find(w), std::string::npos) << c.name << ": no '" << w << "' in\n" << cut_for_log(r.err);
    EXPECT_LE(r.err.size(), kMaxMessageBytes) << c.name;
  }
  std::printf("hostile vector files tried: %d\n", tried);
}

}  // namespace
}  // namespace fxr::test
