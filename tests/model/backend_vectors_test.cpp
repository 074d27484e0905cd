// The committed back-end stage vectors (docs/vectors.md, "Committed back-end vectors"):
// vectors/scenes/backend_directed/ (scenes/backend_directed.json: the geometric cases) and
// vectors/scenes/backend_state/<depth func>/ (scenes/backend_state.json dumped once per depth
// function, the cull mode, front face and interpolation mode varying with it). Each is what the
// generator writes today, and each reaches the cases it is committed for — checked against
// expectations computed here from the scene's float vertices in double precision (signed areas,
// pixel-centre bounding boxes, point-in-triangle coverage, a depth buffer of z values), not from
// the model's output.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "frontend/scene.hpp"
#include "model/vectors/scene_dump.hpp"

using namespace fxr;
namespace fs = std::filesystem;

namespace {

fs::path source_dir() {
  const char* d = std::getenv("FXR_SOURCE_DIR");
  return fs::path(d ? d : ".");
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The committed sets: folder, scene, --state override, stages written.
const std::vector<std::string> kGeometryStages = {"convert", "clip",     "recip", "viewport", "setup",
                                                  "traverse", "interp", "depth", "divide"};
const std::vector<std::string> kBackendStages = {"setup", "traverse", "interp", "depth", "divide"};
const char* const kFuncNames[8] = {"never", "less", "equal", "lequal", "greater", "notequal", "gequal", "always"};
const char* const kCullNames[3] = {"none", "back", "front"};

// Depth function f's dump: cull f mod 3, front face ccw for even f, affine interpolation for f = 4
// (greater), perspective otherwise: each cull mode meets both front faces.
nlohmann::json state_of(int f) {
  return {{"depth_func", kFuncNames[f]},
          {"cull", kCullNames[f % 3]},
          {"front_face", f % 2 == 0 ? "ccw" : "cw"},
          {"interp", f == 4 ? "affine" : "perspective"}};
}

struct CommittedSet {
  std::string dir;  // under vectors/scenes/
  std::string scene;
  nlohmann::json state;
  std::vector<std::string> stages;
};
std::vector<CommittedSet> committed_sets() {
  std::vector<CommittedSet> v = {{"backend_directed", "backend_directed.json", nlohmann::json::object(), kGeometryStages}};
  for (int f = 0; f < 8; ++f)
    v.push_back({std::string("backend_state/") + kFuncNames[f], "backend_state.json", state_of(f), kBackendStages});
  return v;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

Scene load(const CommittedSet& c) {
  SceneOptions so;
  so.state = c.state;
  return load_scene((source_dir() / "scenes" / c.scene).string(), so);
}

// ---- the independent expectations --------------------------------------------------------------

// A triangle in window coordinates (y up), from the float clip coordinates in double.
struct Win {
  double x[3], y[3];
  double area2() const { return (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]); }
};
Win window(const ClipTriangle& t, const DrawState& st) {
  Win w;
  for (int i = 0; i < 3; ++i) {
    const double iw = 1.0 / (double)t.v[i].pos[3];
    w.x[i] = st.viewport_x + ((double)t.v[i].pos[0] * iw + 1.0) * 0.5 * st.viewport_w;
    w.y[i] = st.viewport_y + ((double)t.v[i].pos[1] * iw + 1.0) * 0.5 * st.viewport_h;
  }
  return w;
}

// Pixel centres of the viewport inside the triangle (every edge value > 0 by a margin), and how
// many are within the margin of an edge (there the top-left rule decides: not predicted here).
struct Coverage {
  std::set<std::pair<int, int>> in;
  int on_edge = 0;
};
Coverage coverage(const Win& w, const DrawState& st) {
  Coverage c;
  const double a = w.area2();
  if (a == 0) return c;
  for (int j = 0; j < st.viewport_h; ++j)
    for (int i = 0; i < st.viewport_w; ++i) {
      const double px = st.viewport_x + i + 0.5, py = st.viewport_y + j + 0.5;
      bool inside = true, near = false;
      for (int k = 0; k < 3; ++k) {
        const int l = (k + 1) % 3;
        const double dx = w.x[l] - w.x[k], dy = w.y[l] - w.y[k];
        const double e = (dx * (py - w.y[k]) - dy * (px - w.x[k])) * (a > 0 ? 1 : -1) / std::hypot(dx, dy);
        if (e <= 1e-4) inside = false;
        if (std::fabs(e) <= 1e-4) near = true;
        if (e < -1e-4) near = false, k = 3;  // clearly outside this edge
      }
      if (inside) c.in.insert({i, j});
      else if (near) ++c.on_edge;
    }
  return c;
}

// Does the triangle's bounding box hold a pixel centre of the viewport (setup's candidate
// rectangle, closed)?
bool box_has_centre(const Win& w, const DrawState& st) {
  const double x0 = std::max(*std::min_element(w.x, w.x + 3), (double)st.viewport_x);
  const double x1 = std::min(*std::max_element(w.x, w.x + 3), (double)st.viewport_x + st.viewport_w);
  const double y0 = std::max(*std::min_element(w.y, w.y + 3), (double)st.viewport_y);
  const double y1 = std::min(*std::max_element(w.y, w.y + 3), (double)st.viewport_y + st.viewport_h);
  return std::ceil(x0 - 0.5) <= std::floor(x1 - 0.5) && std::ceil(y0 - 0.5) <= std::floor(y1 - 0.5) &&
         std::floor(x1 - 0.5) >= st.viewport_x && std::floor(y1 - 0.5) >= st.viewport_y;
}

enum Outcome { kDrawn, kZeroArea, kBackface, kNoSamples };
Outcome outcome(const Win& w, const DrawState& st) {
  const double a = w.area2();
  if (a == 0) return kZeroArea;
  const bool front = (a > 0) == st.front_ccw;
  if ((st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front)) return kBackface;
  if (!box_has_centre(w, st)) return kNoSamples;
  return kDrawn;
}

// The dump's fragments per primitive (interp.out: generated) with their pixels.
std::map<uint32_t, std::vector<std::pair<int, int>>> fragments_by_prim(const std::string& dir, const char* stage,
                                                                       bool out_side) {
  const SceneStageVectors v = load_scene_stage(dir, stage);
  const SceneStageFile& f = out_side ? v.out : v.in;
  size_t cp = 0, cx = 0, cy = 0;
  for (size_t i = 0; i < f.lay.size(); ++i) {
    if (f.lay[i].name == "prim") cp = i;
    if (f.lay[i].name == "x") cx = i;
    if (f.lay[i].name == "y") cy = i;
  }
  std::map<uint32_t, std::vector<std::pair<int, int>>> m;
  for (uint64_t r = 0; r < f.rows; ++r) {
    const VecRow row = f.row(r);
    m[(uint32_t)row[cp]].push_back({(int)(int16_t)row[cx], (int)(int16_t)row[cy]});
  }
  return m;
}

nlohmann::json scene_stats(const std::string& dir) {
  std::ifstream in(dir + "/scene.json");
  return nlohmann::json::parse(in).at("stats");
}

// ---- the files are current -----------------------------------------------------------------------

TEST(BackendVectorsCommitted, RegeneratingGivesIdenticalFiles) {
  for (const CommittedSet& c : committed_sets()) {
    const fs::path committed = source_dir() / "vectors" / "scenes" / c.dir;
    ASSERT_TRUE(fs::is_directory(committed)) << committed;
    const Scene sc = load(c);
    const fs::path dir = fs::temp_directory_path() / ("fxr_backend_vectors_" + std::to_string(::getpid()));
    const SceneDump d = dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name,
                                           c.stages);
    std::vector<std::string> names = {"scene.json"};
    for (const auto& f : d.files) {
      names.push_back(f.hex);
      names.push_back(fs::path(f.hex).replace_extension(".json").string());
    }
    EXPECT_EQ(names.size(), 1 + 4 * c.stages.size()) << c.dir;
    size_t in_folder = 0;
    for (const auto& e : fs::directory_iterator(committed)) (void)e, ++in_folder;
    EXPECT_EQ(in_folder, names.size()) << committed << " holds other files";
    for (const auto& n : names)
      EXPECT_EQ(slurp(dir / n), slurp(committed / n))
          << c.dir << "/" << n << " is stale; regenerate with: build/app/fxraster vectors scene scenes/" << c.scene
          << (c.state.empty() ? "" : " --state '" + c.state.dump() + "'") << " --stages " << join(c.stages)
          << " --out vectors/scenes/" << c.dir;
    fs::remove_all(dir);
  }
}

// A stage subset: only those files, re-stepped alone; a missing prerequisite, an unknown or a
// repeated stage, and a stage the dump does not hold are errors. The state override: the scene's
// fields replaced, a bad value named by its field.
TEST(BackendVectors, StageSubsetsAndStateOverride) {
  SceneOptions so;
  so.state = {{"depth_func", "gequal"}, {"cull", "front"}};
  const Scene sc = load_scene((source_dir() / "scenes" / "backend_state.json").string(), so);
  EXPECT_EQ(sc.state.depth_func, DepthFunc::GreaterEqual);
  EXPECT_EQ(sc.state.cull, CullMode::Front);
  EXPECT_EQ(sc.line_state.depth_func, DepthFunc::GreaterEqual);
  so.state = {{"depth_func", "bogus"}};
  try {
    load_scene((source_dir() / "scenes" / "backend_state.json").string(), so);
    ADD_FAILURE() << "a bad depth_func was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/state/depth_func"), std::string::npos) << e.what();
  }
  const fs::path dir = fs::temp_directory_path() / ("fxr_backend_subset_" + std::to_string(::getpid()));
  const SceneDump d =
      dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name, {"depth", "divide"});
  EXPECT_EQ(d.files.size(), 4u);
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) (void)e, ++n;
  EXPECT_EQ(n, 9u);  // 4 hex, 4 manifests, scene.json
  EXPECT_EQ(scene_dump_stages_present(dir.string()), (std::vector<std::string>{"depth", "divide"}));
  const RestepReport r = restep_scene_vectors(dir.string());
  ASSERT_EQ(r.stages.size(), 2u);
  EXPECT_EQ(r.stages[0].stage, "depth");
  EXPECT_GT(r.stages[0].in_rows, 0u);
  EXPECT_EQ(r.mismatches(), 0u);
  EXPECT_THROW(load_scene_stage(dir.string(), "setup"), ConfigError);
  EXPECT_NO_THROW(load_scene_stage(dir.string(), "divide"));
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"interp"}, {"line_interp"}, {"line_depth"}, {"setup", "setup"}, {"sideways"}})
    EXPECT_THROW(
        dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name, bad),
        ConfigError)
        << join(bad);
  fs::remove_all(dir);
}

// ---- the geometric cases are reached ---------------------------------------------------------------

// Primitive ids of scenes/backend_directed.json (its "name" lists them).
constexpr uint32_t kTieEdges[2] = {0, 1}, kTieCentres[2] = {2, 3}, kFan[4] = {4, 5, 6, 7};
constexpr uint32_t kOnePixel = 8, kSubPixelEmpty = 9, kSubPixelCentre = 10, kSliver = 11, kWRatio = 14, kGuardBand = 15,
                   kFullViewport = 16;

TEST(BackendVectors, DirectedCasesAreReached) {
  const CommittedSet c = committed_sets()[0];
  const std::string dir = (source_dir() / "vectors" / "scenes" / c.dir).string();
  const Scene sc = load(c);
  const DrawState& st = sc.state;
  ASSERT_EQ(sc.tris.size(), 18u);
  const auto gen = fragments_by_prim(dir, "interp", true);  // generated fragments per primitive
  std::array<uint64_t, 4> oc{};
  uint64_t cw = 0, ccw = 0;
  for (uint32_t p = 0; p < sc.tris.size(); ++p) {
    const Win w = window(sc.tris[p], st);
    const Outcome o = outcome(w, st);
    ++oc[o];
    if (o != kZeroArea) ++(w.area2() > 0 ? ccw : cw);
    const Coverage cv = coverage(w, st);
    const size_t got = gen.count(p) ? gen.at(p).size() : 0;
    if (o != kDrawn) EXPECT_EQ(got, 0u) << "primitive " << p << " is culled";
    else if (cv.on_edge == 0) EXPECT_EQ(got, cv.in.size()) << "primitive " << p << ": fragments";
    else EXPECT_GE(got, cv.in.size()) << "primitive " << p << ": at least the centres strictly inside";
  }
  // Setup's outcomes (scene.json stats) equal the counts found here.
  const nlohmann::json s = scene_stats(dir);
  EXPECT_EQ(s.at("prims_culled_zero_area"), oc[kZeroArea]);
  EXPECT_EQ(s.at("prims_culled_backface"), oc[kBackface]);
  EXPECT_EQ(s.at("prims_culled_no_samples"), oc[kNoSamples]);
  EXPECT_EQ(s.at("prims_drawn"), oc[kDrawn]);
  EXPECT_EQ(oc[kZeroArea], 2u);
  EXPECT_EQ(oc[kNoSamples], 1u);
  EXPECT_GE(cw, 2u);  // both windings drawn (cull none)
  EXPECT_GE(ccw, 2u);
  // Top-left ties: a square split along its diagonal (vertices on pixel edges; on pixel centres,
  // with horizontal and vertical edges through centres) and a fan of four around a vertex on a
  // pixel centre: every pixel of the square once, none twice, 4 x 4 in all — while the centres
  // on the shared edges are many (counted here).
  auto tie = [&](const uint32_t* ids, size_t n, const char* what) {
    std::set<std::pair<int, int>> u;
    size_t total = 0;
    int shared = 0;
    for (size_t k = 0; k < n; ++k) {
      ASSERT_TRUE(gen.count(ids[k])) << what;
      for (const auto& px : gen.at(ids[k])) u.insert(px), ++total;
      shared += coverage(window(sc.tris[ids[k]], st), st).on_edge;
    }
    EXPECT_EQ(total, 16u) << what;
    EXPECT_EQ(u.size(), 16u) << what << ": a pixel drawn twice";
    EXPECT_GE(shared, 8) << what << ": centres on the edges";
  };
  tie(kTieEdges, 2, "pixel-edge square");
  tie(kTieCentres, 2, "pixel-centre square");
  tie(kFan, 4, "fan");
  {  // the pixel-centre square has a vertex exactly on a centre and horizontal / vertical edges
    const Win w = window(sc.tris[kTieCentres[0]], st);
    EXPECT_EQ(w.x[0] - std::floor(w.x[0]), 0.5);
    EXPECT_EQ(w.y[0], w.y[1]);  // horizontal
    EXPECT_EQ(w.x[0], w.x[2]);  // vertical
  }
  // 1-pixel and sub-pixel triangles.
  EXPECT_LT(std::fabs(window(sc.tris[kOnePixel], st).area2()), 2.0);
  EXPECT_EQ(gen.count(kOnePixel) ? gen.at(kOnePixel).size() : 0, 1u);
  EXPECT_LT(std::fabs(window(sc.tris[kSubPixelCentre], st).area2()), 0.1);
  EXPECT_EQ(gen.count(kSubPixelCentre) ? gen.at(kSubPixelCentre).size() : 0, 1u);
  EXPECT_EQ(outcome(window(sc.tris[kSubPixelEmpty], st), st), kNoSamples);
  {  // a sliver: long (> 15 px) and thin (at most 0.6 px across)
    const Win w = window(sc.tris[kSliver], st);
    const double len = std::hypot(w.x[1] - w.x[0], w.y[1] - w.y[0]);
    EXPECT_GT(len, 15.0);
    EXPECT_LT(std::fabs(w.area2()) / len, 0.6);
    EXPECT_GT(gen.at(kSliver).size(), 2u);
  }
  // w ratio 10^6 inside one triangle.
  {
    const auto& t = sc.tris[kWRatio];
    const double w0 = std::min({t.v[0].pos[3], t.v[1].pos[3], t.v[2].pos[3]});
    const double w1 = std::max({t.v[0].pos[3], t.v[1].pos[3], t.v[2].pos[3]});
    EXPECT_GE(w1 / w0, 0.999e6);
    EXPECT_GT(gen.at(kWRatio).size(), 10u);
  }
  {  // guard-band-sized: vertices 1000 viewports out, not clipped (prims_clipped 0)
    const Win w = window(sc.tris[kGuardBand], st);
    EXPECT_GE(std::max({std::fabs(w.x[1]), std::fabs(w.y[1]), std::fabs(w.x[2])}), 1000.0 * st.viewport_w);
    EXPECT_EQ(s.at("prims_clipped"), 0u);
  }
  // The full viewport: every pixel generated once.
  EXPECT_EQ(gen.at(kFullViewport).size(), (size_t)st.viewport_w * (size_t)st.viewport_h);
  // Both depth outcomes.
  EXPECT_GT(s.at("fragments_depth_fail").get<uint64_t>(), 0u);
  EXPECT_GT(s.at("fragments_depth_pass").get<uint64_t>(), 0u);
}

// ---- every depth function, cull mode and front face --------------------------------------------

// The depth test of one function on z values (each triangle of backend_state.json has one z, so
// its fragments share one depth code and codes order as z does; z = 1 is the far plane, the
// maximum code, which the cleared buffer holds).
bool passes(DepthFunc f, double in, double stored) {
  switch (f) {
    case DepthFunc::Never: return false;
    case DepthFunc::Less: return in < stored;
    case DepthFunc::Equal: return in == stored;
    case DepthFunc::LessEqual: return in <= stored;
    case DepthFunc::Greater: return in > stored;
    case DepthFunc::NotEqual: return in != stored;
    case DepthFunc::GreaterEqual: return in >= stored;
    case DepthFunc::Always: return true;
  }
  return false;
}

TEST(BackendVectors, EveryDepthFunctionCullModeAndFrontFaceIsReached) {
  const auto sets = committed_sets();
  std::set<int> funcs;
  std::set<std::pair<int, bool>> cull_faces;
  std::set<int> interps;
  for (size_t i = 1; i < sets.size(); ++i) {
    const CommittedSet& c = sets[i];
    const std::string dir = (source_dir() / "vectors" / "scenes" / c.dir).string();
    const Scene sc = load(c);
    const DrawState st = load_scene_draw_state(dir);
    EXPECT_EQ(st.depth_func, sc.state.depth_func) << c.dir;
    EXPECT_EQ(st.cull, sc.state.cull) << c.dir;
    funcs.insert((int)st.depth_func);
    cull_faces.insert({(int)st.cull, st.front_ccw});
    interps.insert((int)st.interp);
    // The draw, simulated here: outcome, coverage (no centre near an edge), z per triangle.
    std::vector<double> buf((size_t)st.viewport_w * (size_t)st.viewport_h, 1.0);
    uint64_t backface = 0, drawn = 0, pass = 0, fail = 0;
    for (const ClipTriangle& t : sc.tris) {
      const Win w = window(t, st);
      const Outcome o = outcome(w, st);
      backface += o == kBackface;
      if (o != kDrawn) continue;
      ++drawn;
      const double z = (double)t.v[0].pos[2] / (double)t.v[0].pos[3];
      for (int k = 1; k < 3; ++k) ASSERT_EQ((double)t.v[k].pos[2] / (double)t.v[k].pos[3], z) << "one z per triangle";
      const Coverage cv = coverage(w, st);
      ASSERT_EQ(cv.on_edge, 0) << c.dir << ": a centre on an edge (the expectation would need the top-left rule)";
      for (const auto& [x, y] : cv.in) {
        double& b = buf[(size_t)y * (size_t)st.viewport_w + (size_t)x];
        if (passes(st.depth_func, z, b)) {
          ++pass;
          if (st.depth_write) b = z;
        } else {
          ++fail;
        }
      }
    }
    const nlohmann::json s = scene_stats(dir);
    EXPECT_EQ(s.at("prims_culled_backface"), backface) << c.dir;
    EXPECT_EQ(s.at("prims_drawn"), drawn) << c.dir;
    EXPECT_EQ(s.at("fragments_depth_pass"), pass) << c.dir;
    EXPECT_EQ(s.at("fragments_depth_fail"), fail) << c.dir;
    EXPECT_EQ(load_scene_stage(dir, "divide").out.rows, pass) << c.dir;
    // Each function decides both ways where it can against the cleared buffer: never passes
    // nothing, always fails nothing, greater cannot pass the cleared maximum code (docs/vectors.md).
    if (st.depth_func != DepthFunc::Never && st.depth_func != DepthFunc::Greater) {
      EXPECT_GT(pass, 0u) << c.dir;
    }
    if (st.depth_func != DepthFunc::Always) {
      EXPECT_GT(fail, 0u) << c.dir;
    }
    if (st.cull != CullMode::None) {
      EXPECT_GT(backface, 0u) << c.dir;
    }
    std::printf("%s: cull %s, front %s, interp %d: %llu drawn, %llu culled by facing, %llu fragments pass, %llu fail\n",
                c.dir.c_str(), kCullNames[(int)st.cull], st.front_ccw ? "ccw" : "cw", (int)st.interp,
                (unsigned long long)drawn, (unsigned long long)backface, (unsigned long long)pass,
                (unsigned long long)fail);
  }
  EXPECT_EQ(funcs.size(), 8u);
  EXPECT_EQ(cull_faces.size(), 6u);  // each cull mode with both front faces
  EXPECT_EQ(interps.size(), 2u);
}

}  // namespace
