// The threaded raster unit (model/unit/threads.hpp) against the sequential chain: for every
// thread count, band height, batch size and raster step size the fragment stream (every field
// of every fragment, in order), the depth buffer and every statistic equal those of
// run_raster_unit on one thread (the reference: the chain of model/unit/chain.hpp, tested on its own against
// the exact references in the other model tests). Scenes: the committed example scenes
// (clipping, the near plane, the guard band, the depth functions, lines), the default scene,
// random overlapping triangles under every depth function, scissors and culling. Also the
// compact fragment records (model/unit/fragment_store.hpp): round trip of extreme values.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "frontend/scene.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/unit/threads.hpp"
#include "stats_fields.hpp"

using namespace fxr;

namespace {

std::string source_dir() {
  const char* d = std::getenv("FXR_SOURCE_DIR");
  return d ? d : ".";  // ctest sets it; the working directory is the source tree
}

// Every field of two frames; `what` names the run.
void expect_same_frame(const FrameOutput& want, const FrameOutput& got, int nv, const std::string& what) {
  ASSERT_EQ(want.width, got.width) << what;
  ASSERT_EQ(want.height, got.height) << what;
  EXPECT_EQ(stats_fields(want.stats), stats_fields(got.stats)) << what;
  ASSERT_EQ(want.depth.size(), got.depth.size()) << what;
  size_t depth_diff = 0;
  for (size_t i = 0; i < want.depth.size(); ++i) depth_diff += want.depth[i] != got.depth[i];
  EXPECT_EQ(depth_diff, 0u) << what << ": depth-buffer words differ";
  ASSERT_EQ(want.fragments.size(), got.fragments.size()) << what;
  size_t first_diff = want.fragments.size(), diffs = 0;
  for (size_t i = 0; i < want.fragments.size(); ++i) {
    const Fragment a = want.fragments[i], b = got.fragments[i];
    bool same = a.prim == b.prim && a.x == b.x && a.y == b.y && a.depth == b.depth;
    for (int k = 0; k < nv; ++k)
      same = same && a.var[k].neg == b.var[k].neg && a.var[k].sig == b.var[k].sig && a.var[k].exp == b.var[k].exp;
    if (!same) {
      ++diffs;
      if (first_diff == want.fragments.size()) first_diff = i;
    }
  }
  EXPECT_EQ(diffs, 0u) << what << ": first differing fragment " << first_diff;
}

struct Case {
  std::string name;
  Config cfg;
  DrawState st, line_st;
  std::vector<ClipTriangle> tris;
  std::vector<ClipLine> lines;
};

Case scene_case(const std::string& file, int w = 0, int h = 0) {
  SceneOptions o;
  o.width = w, o.height = h;
  const Scene sc = file.empty() ? default_scene(o) : load_scene(source_dir() + "/scenes/" + file, o);
  return {file.empty() ? "default" : file, sc.config, sc.state, sc.line_state, sc.tris, sc.lines};
}

// Random triangles over a 120 × 90 viewport at depths that overlap, some crossing the near plane
// and the guard band, with nv varyings.
Case random_case(uint64_t seed, int n, int nv) {
  Case c;
  c.name = "random" + std::to_string(seed);
  c.st.viewport_x = 3, c.st.viewport_y = -2, c.st.viewport_w = 120, c.st.viewport_h = 90;
  c.st.num_varyings = nv;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> pos(-1.4f, 1.4f), zf(-0.3f, 1.1f), wf(0.2f, 4.0f), var(-10.0f, 10.0f);
  for (int t = 0; t < n; ++t) {
    ClipTriangle tri;
    const float big = (t % 7 == 0) ? 3.0f : 1.0f;  // some large triangles spanning many bands
    for (auto& v : tri.v) {
      const float wv = wf(rng);
      v.pos[0] = pos(rng) * wv * big, v.pos[1] = pos(rng) * wv * big, v.pos[2] = zf(rng) * wv, v.pos[3] = wv;
      for (int k = 0; k < nv; ++k) v.var[k] = var(rng);
    }
    c.tris.push_back(tri);
  }
  return c;
}

// The sequential unit against the threaded one at several thread counts, band heights and batch
// sizes; the fragments kept, streamed to a sink, and not produced at all.
void check_case(const Case& c, const std::vector<ThreadOptions>& opts) {
  const FrameOutput want = run_raster_unit(c.cfg, c.st, c.tris, c.line_st, c.lines);
  const int nv = std::max(c.st.num_varyings, c.lines.empty() ? 0 : c.line_st.num_varyings);
  for (const ThreadOptions& o : opts) {
    const std::string what = c.name + " threads " + std::to_string(o.threads) + " band_rows " +
                             std::to_string(o.band_rows) + " batch_prims " + std::to_string(o.batch_prims) +
                             " step_pixels " + std::to_string(o.step_pixels);
    expect_same_frame(want, run_raster_unit(c.cfg, c.st, c.tris, c.line_st, c.lines, o), nv, what);
  }
  // A sink receives the same stream; without one the depth buffer and the counters still agree.
  struct Record : FragmentSink {
    FragmentStore s;
    void draw_state(const DrawState& st) override { s.widen(st.num_varyings); }
    void emit(const Fragment& f) override { s.push_back(f); }
  };
  FrameOutput seq_tris;
  {
    Record r;
    r.s.shape(c.st.num_varyings);
    NoTaps taps;
    run_raster_unit_to(c.cfg, c.st, c.tris, seq_tris, &r, taps);
    seq_tris.fragments = r.s;
  }
  for (int threads : {2, 3}) {
    ThreadOptions o;
    o.threads = threads, o.band_rows = 2, o.batch_prims = 5, o.step_pixels = threads == 2 ? 40 : kThreadStepPixels;
    Record r;
    r.s.shape(c.st.num_varyings);
    FrameOutput f;
    run_raster_unit_threads(c.cfg, c.st, c.tris, f, nullptr, &r, o);
    f.fragments = r.s;
    expect_same_frame(seq_tris, f, c.st.num_varyings, c.name + " sink, threads " + std::to_string(threads));
    FrameOutput none_seq, none_par;
    NoTaps taps;
    run_raster_unit_to(c.cfg, c.st, c.tris, none_seq, nullptr, taps);
    run_raster_unit_threads(c.cfg, c.st, c.tris, none_par, nullptr, nullptr, o);
    EXPECT_EQ(none_par.fragments.size(), 0u);
    expect_same_frame(none_seq, none_par, 0, c.name + " no fragments, threads " + std::to_string(threads));
  }
}

// Step sizes: one pixel (every row of a triangle its own raster item, most steps cut bands),
// a few rows of a small triangle, and the default.
std::vector<ThreadOptions> option_grid() {
  std::vector<ThreadOptions> v;
  const int steps[] = {1, 37, kThreadStepPixels};
  int i = 0;
  for (int t : {1, 2, 3, 7})
    for (int rows : {1, 3, kThreadBandRows})
      for (int batch : {1, 7, kThreadBatchPrims}) {
        ThreadOptions o;
        o.threads = t, o.band_rows = rows, o.batch_prims = batch, o.step_pixels = steps[i++ % 3];
        v.push_back(o);
      }
  return v;
}

}  // namespace

TEST(Threads, ExampleScenesAreBitIdenticalForEveryThreadCount) {
  for (const char* f : {"clip_triangles.json", "near_plane.json", "guard_band.json", "backend_state.json",
                        "lines.json", "checker_quad.json", "texture_border.json"})
    check_case(scene_case(f), option_grid());
}

TEST(Threads, DefaultSceneIsBitIdenticalForEveryThreadCount) {
  // At a reduced size (the bunny's 69,666 triangles, when installed, are all set up; fewer pixels).
  Case c = scene_case("", 200, 150);
  std::vector<ThreadOptions> opts;
  for (int t : {1, 2, 3, 7}) {
    ThreadOptions o;
    o.threads = t;
    opts.push_back(o);
    o.band_rows = 1, o.batch_prims = 333;
    opts.push_back(o);
  }
  check_case(c, opts);
}

TEST(Threads, RandomOverlapsUnderEveryDepthFunctionScissorAndCulling) {
  const DepthFunc funcs[] = {DepthFunc::Less, DepthFunc::Equal, DepthFunc::LessEqual, DepthFunc::Greater,
                             DepthFunc::NotEqual, DepthFunc::GreaterEqual, DepthFunc::Always, DepthFunc::Never};
  int i = 0;
  for (DepthFunc fn : funcs) {
    Case c = random_case(100 + i, 60, i % 4);
    c.st.depth_func = fn;
    c.st.depth_write = i % 3 != 2;
    c.st.depth_test = i != 7;
    c.st.cull = i % 2 ? CullMode::Back : CullMode::None;
    if (i % 3 == 1) c.st.scissor_x = 20, c.st.scissor_y = 5, c.st.scissor_w = 70, c.st.scissor_h = 61;
    c.name += " func " + std::to_string((int)fn);
    std::vector<ThreadOptions> opts;
    for (int t : {2, 3, 7})
      for (int rows : {1, 4}) {
        ThreadOptions o;
        o.threads = t, o.band_rows = rows, o.batch_prims = 9;
        opts.push_back(o);
      }
    check_case(c, opts);
    ++i;
  }
}

TEST(Threads, InvalidOptionsAreRejected) {
  const Case c = random_case(1, 3, 0);
  for (ThreadOptions o : {ThreadOptions{0, 8, 10}, ThreadOptions{2, 0, 10}, ThreadOptions{2, 8, 0},
                          ThreadOptions{2, 8, 10, 0}})
    EXPECT_THROW(run_raster_unit(c.cfg, c.st, c.tris, o), std::invalid_argument);
}

TEST(Threads, LargeTrianglesCutIntoRowChunksAtEveryStepSize) {
  // Large overlapping triangles (each weighs far more than a small step): a triangle's rows are
  // split over several raster steps, steps cut bands in the middle, and the records of one
  // triangle are copied into the frame by several threads in several steps.
  Case c = random_case(7, 24, 2);
  for (ClipTriangle& t : c.tris)
    for (ClipVertex& v : t.v) v.pos[0] *= 2.5f, v.pos[1] *= 2.5f;
  std::vector<ThreadOptions> opts;
  for (int t : {2, 3, 5})
    for (int step : {1, 2, 7, 100, 999, kThreadStepPixels}) {
      ThreadOptions o;
      o.threads = t, o.band_rows = 1 + step % 6, o.batch_prims = 1 + step % 10, o.step_pixels = step;
      opts.push_back(o);
    }
  check_case(c, opts);
}

TEST(Threads, AReusedFrameIsClearedByTheThreadsAndEqualsANewOne) {
  // A FrameOutput of the viewport's size is cleared by the threads in their own bands (and its
  // stores keep their memory); one of another size is allocated anew. Each frame equals the
  // sequential unit's whatever the frame before it left.
  Case a = random_case(11, 40, 1), b = random_case(12, 40, 1);
  b.st.depth_func = DepthFunc::Greater;  // b's passing fragments need a depth buffer cleared to the maximum
  Case small = random_case(13, 10, 1);
  small.st.viewport_w = 31, small.st.viewport_h = 17;
  for (int t : {2, 3}) {
    ThreadOptions o;
    o.threads = t, o.band_rows = 3, o.batch_prims = 6, o.step_pixels = 50;
    FrameOutput f;
    for (const Case* c : {&a, &b, &a, &small, &b}) {
      run_raster_unit_threads(c->cfg, c->st, c->tris, f, &f.fragments, nullptr, o);
      expect_same_frame(run_raster_unit(c->cfg, c->st, c->tris), f, c->st.num_varyings,
                        c->name + " reused frame, threads " + std::to_string(t));
    }
  }
}

TEST(FragmentStore, RoundTripsTheExtremesOfEveryField) {
  FragmentStore s(kMaxVaryings);
  std::vector<Fragment> in;
  std::mt19937_64 rng(5);
  for (int i = 0; i < 200; ++i) {
    Fragment f;
    f.prim = i == 0 ? 0xffffffffu : (uint32_t)rng();
    f.x = i == 1 ? INT32_MIN : (int32_t)rng();
    f.y = i == 2 ? INT32_MAX : (int32_t)rng();
    f.depth = (uint32_t)rng();
    for (int k = 0; k < kMaxVaryings; ++k) {
      f.var[k].neg = rng() & 1;
      f.var[k].sig = i == 3 ? 0xffffffffu : (uint32_t)rng();
      f.var[k].exp = i == 4 ? (1 << 30) - 1 : i == 5 ? -(1 << 30) : (int)(rng() % 2001) - 1000;
    }
    in.push_back(f);
    s.push_back(f);
  }
  ASSERT_EQ(s.size(), in.size());
  EXPECT_EQ(s.record_bytes(), (size_t)kFragmentHeaderBytes + (size_t)kMaxVaryings * kFragmentVaryingBytes);
  for (size_t i = 0; i < in.size(); ++i) {
    const Fragment g = s[i];
    EXPECT_EQ(g.prim, in[i].prim);
    EXPECT_EQ(g.x, in[i].x);
    EXPECT_EQ(g.y, in[i].y);
    EXPECT_EQ(g.depth, in[i].depth);
    for (int k = 0; k < kMaxVaryings; ++k) {
      EXPECT_EQ(g.var[k].neg, in[i].var[k].neg) << i << " " << k;
      EXPECT_EQ(g.var[k].sig, in[i].var[k].sig) << i << " " << k;
      EXPECT_EQ(g.var[k].exp, in[i].var[k].exp) << i << " " << k;
    }
  }
  // Values the record cannot hold are refused, not truncated.
  Fragment wide;
  wide.var[0].sig = (uint64_t)1 << kStoredSigBits;
  EXPECT_THROW(s.push_back(wide), std::logic_error);
  Fragment far;
  far.var[3].exp = 1 << 30;
  EXPECT_THROW(s.push_back(far), std::logic_error);
  // Widening keeps the records and adds zero varyings.
  FragmentStore n(1);
  n.push_back(in[7]);
  n.widen(3);
  EXPECT_EQ(n.num_varyings(), 3);
  EXPECT_EQ(n[0].var[0].sig, in[7].var[0].sig);
  EXPECT_EQ(n[0].var[2].sig, 0u);
  EXPECT_EQ(n[0].prim, in[7].prim);
}
