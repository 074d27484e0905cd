// The threaded raster unit (model/unit/threads.hpp) against the sequential chain: for every
// thread count, band height, batch size and raster step size the fragment stream (every field
// of every fragment, in order), the depth buffer and every statistic equal those of
// run_raster_unit on one thread (the reference: the chain of model/unit/chain.hpp, tested on its own against
// the exact references in the other model tests). Scenes: the committed example scenes
// (clipping, the near plane, the guard band, the depth functions, lines), the default scene,
// random overlapping triangles under every depth function, scissors and culling. Also the
// compact fragment records (model/unit/fragment_store.hpp): round trip of extreme values.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "frontend/scene.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/unit/threads.hpp"
#include "model/unit/vertex_cache.hpp"
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
                             " step_pixels " + std::to_string(o.step_pixels) + " setup_chunk_prims " +
                             std::to_string(o.setup_chunk_prims);
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
    o.setup_chunk_prims = threads == 2 ? 2 : kThreadSetupChunkPrims;
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
// a few rows of a small triangle, and the default. Setup chunks of one primitive (a batch of
// many chunks, claimed by the threads in turn), of three (a batch of 7 ends in a short chunk)
// and the default.
std::vector<ThreadOptions> option_grid() {
  std::vector<ThreadOptions> v;
  const int steps[] = {1, 37, kThreadStepPixels};
  const int chunks[] = {1, 3, kThreadSetupChunkPrims, 3};
  int i = 0, j = 0;
  for (int t : {1, 2, 3, 7})
    for (int rows : {1, 3, kThreadBandRows})
      for (int batch : {1, 7, kThreadBatchPrims}) {
        ThreadOptions o;
        o.threads = t, o.band_rows = rows, o.batch_prims = batch, o.step_pixels = steps[i++ % 3];
        o.setup_chunk_prims = chunks[j++ % 4];
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
    o.band_rows = 1, o.batch_prims = 333, o.setup_chunk_prims = 5;
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
        o.threads = t, o.band_rows = rows, o.batch_prims = 9, o.setup_chunk_prims = rows == 4 ? 2 : kThreadSetupChunkPrims;
        opts.push_back(o);
      }
    check_case(c, opts);
    ++i;
  }
}

namespace {

// The band heights the batches of a frame were rasterised in (ThreadObserver::batch_bands).
class BandCounter final : public ThreadObserver {
 public:
  void phase(int, ThreadPhase) override {}
  void batch_bands(int64_t, int band_rows) override { ++seen[band_rows]; }
  std::map<int, int> seen;
};

}  // namespace

// Batches of tall triangles and batches of triangles a few pixels high in one frame: a batch is
// rasterised in the band map chosen from the batch before it (fine bands after tall triangles,
// coarse after small ones; the first batch from its own), its triangles routed in that map only,
// so the same depth words change owner between steps and the first small batch is rasterised in
// fine bands (its map chosen from the last tall one); every frame equals the sequential unit's.
TEST(Threads, EachBatchChoosesItsBandMap) {
  Case c = random_case(11, 60, 2);
  c.name = "tall then small";
  for (size_t t = 30; t < c.tris.size(); ++t) {  // the second half shrunk about its centre (NDC)
    float cx = 0, cy = 0;
    for (const ClipVertex& v : c.tris[t].v) cx += v.pos[0] / v.pos[3] / 3, cy += v.pos[1] / v.pos[3] / 3;
    for (ClipVertex& v : c.tris[t].v) {
      const float w = v.pos[3];
      v.pos[0] = (cx + (v.pos[0] / w - cx) * 0.05f) * w, v.pos[1] = (cy + (v.pos[1] / w - cy) * 0.05f) * w;
    }
  }
  const FrameOutput want = run_raster_unit(c.cfg, c.st, c.tris);
  for (int t : {2, 3})
    for (int rows : {kThreadBandRows, 16})
      for (int step : {37, kThreadStepPixels}) {
        BandCounter bands;
        ThreadOptions o;
        o.threads = t, o.band_rows = rows, o.batch_prims = 10, o.step_pixels = step, o.setup_chunk_prims = 3;
        o.observer = &bands;
        const std::string what = "threads " + std::to_string(t) + " band_rows " + std::to_string(rows) +
                                 " step_pixels " + std::to_string(step);
        expect_same_frame(want, run_raster_unit(c.cfg, c.st, c.tris, o), 2, what);
        EXPECT_GT(bands.seen[rows], 0) << what;                      // the small triangles' batches
        EXPECT_GT(bands.seen[kThreadFineBandRows], 0) << what;       // the tall ones'
        EXPECT_EQ(bands.seen.size(), 2u) << what;
      }
}

TEST(Threads, InvalidOptionsAreRejected) {
  const Case c = random_case(1, 3, 0);
  for (ThreadOptions o : {ThreadOptions{0, 8, 10}, ThreadOptions{2, 0, 10}, ThreadOptions{2, 8, 0},
                          ThreadOptions{2, 8, 10, 0}, ThreadOptions{2, 8, 10, 100, 0}})
    EXPECT_THROW(run_raster_unit(c.cfg, c.st, c.tris, o), std::invalid_argument);
}

// The waiting threads' polling time (next_poll_state; docs/speed.md "Session 13: threads"). Waits
// of a few tens of microseconds — a barrier between two raster steps on an idle machine — keep it
// long enough to end them by polling, whatever it started at; waits longer than kThreadPollMax
// bring it down to kThreadPollMin, and so do short waits that keep outlasting it after it was
// raised for them (a partner descheduled on a loaded machine); it stays within its bounds. The
// rule the threads used before session 13 (halve after any rest) fails the first part: from a
// polling time below the waits, every wait rests and the time only falls; raising it after
// every short rest (no cooldown) fails the third.
TEST(Threads, PollingTimeFollowsTheWaitsItCouldEnd) {
  using ns = std::chrono::nanoseconds;
  for (const ns need : {ns{3000}, ns{45000}, kThreadPollMax}) {
    for (const ns from : {kThreadPollMin, ns{20000}, kThreadPollMax}) {
      PollState s{from, false, 0};
      int rests = 0;
      for (int i = 0; i < 20; ++i) {
        const bool rested = need > s.poll;  // a wait outlasting the polling rests
        rests += rested;
        s = next_poll_state(s, need, rested);
        EXPECT_GE(s.poll, kThreadPollMin);
        EXPECT_LE(s.poll, kThreadPollMax);
      }
      EXPECT_GE(s.poll, need) << need.count() << " ns waits";  // the next such wait ends while polling
      EXPECT_LE(rests, 1) << need.count() << " ns waits";      // at most the first rests
    }
  }
  PollState s;
  for (int i = 0; i < 20; ++i) s = next_poll_state(s, ns{5000000}, true);
  EXPECT_EQ(s.poll, kThreadPollMin);
  // Short waits that rest whatever the polling time (the thread waited for runs late each time):
  // raised once per cooldown at most, polling mostly short.
  s = PollState{ns{20000}, false, 0};
  int raises = 0;
  ns total{0};
  const int n = 4 * kThreadPollCooldown;
  for (int i = 0; i < n; ++i) {
    total += s.poll;
    const PollState next = next_poll_state(s, ns{50000}, true);
    raises += next.raised;
    s = next;
  }
  EXPECT_LE(raises, n / kThreadPollCooldown + 1);
  EXPECT_LE(total / n, ns{20000});
  // A wait ended while polling doubles it (up to the bound) and ends a cooldown.
  EXPECT_EQ(next_poll_state(PollState{ns{4000}, true, 5}, ns{0}, false).poll, ns{8000});
  EXPECT_EQ(next_poll_state(PollState{ns{4000}, true, 5}, ns{0}, false).cooldown, 0);
  EXPECT_EQ(next_poll_state(PollState{ns{80000}, false, 0}, ns{0}, false).poll, kThreadPollMax);
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
      o.setup_chunk_prims = 1 + step % 4;
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

// The threads' shared vertex cache table (model/unit/vertex_cache.hpp, SharedVertexTable).
namespace {

DrawState vertex_state(int vx, int vy, int nv) {
  DrawState st;
  st.viewport_x = vx, st.viewport_y = vy, st.viewport_w = 200, st.viewport_h = 150;
  st.num_varyings = nv;
  return st;
}

// `n` distinct vertices, inside the view, with a few outside a clip plane (not accepted).
std::vector<ClipVertex> some_vertices(std::mt19937_64& rng, int n, int nv) {
  std::uniform_real_distribution<float> u(-0.9f, 0.9f), wf(0.5f, 3.0f), var(-50.0f, 50.0f);
  std::vector<ClipVertex> vs((size_t)n);
  for (size_t i = 0; i < vs.size(); ++i) {
    ClipVertex& v = vs[i];
    const float w = wf(rng);
    v.pos[0] = u(rng) * w, v.pos[1] = u(rng) * w, v.pos[2] = (0.5f + 0.4f * u(rng)) * w, v.pos[3] = w;
    if (i % 5 == 4) v.pos[2] = 1.5f * w;  // beyond the far plane
    for (int k = 0; k < nv; ++k) v.var[k] = var(rng);
  }
  return vs;
}

// What the cache must answer for a vertex: accepted_vertex itself (the stages 1–4 functions).
struct VertexAnswer {
  bool ok = false;
  SetupVertex v;
};
std::vector<VertexAnswer> answers(const Config& cfg, const DrawState& st, const std::vector<ClipVertex>& vs) {
  const GuardBand gb = guard_band(cfg.raster, st);
  std::vector<VertexAnswer> a(vs.size());
  for (size_t i = 0; i < vs.size(); ++i) a[i].ok = accepted_vertex(cfg, st, gb, vs[i], a[i].v);
  return a;
}

bool same_vertex(const SetupVertex& a, const SetupVertex& b, int nv) {
  bool same = a.x == b.x && a.y == b.y && a.ax == b.ax && a.ay == b.ay && a.z == b.z && a.rw.neg == b.rw.neg &&
              a.rw.sig == b.rw.sig && a.rw.exp == b.rw.exp;
  for (int k = 0; k < nv; ++k)
    same = same && a.vw[k].neg == b.vw[k].neg && a.vw[k].sig == b.vw[k].sig && a.vw[k].exp == b.vw[k].exp;
  return same;
}

// Looks up `count` random triangles of `vs` in `cache`; returns the answers that differ from `want`.
uint64_t wrong_answers(VertexCache& cache, uint64_t seed, int count, const std::vector<ClipVertex>& vs,
                       const std::vector<VertexAnswer>& want, int nv) {
  std::mt19937_64 rng(seed);
  uint64_t wrong = 0;
  for (int p = 0; p < count; ++p) {
    size_t idx[3];
    InputTriangle in;
    in.prim = (uint32_t)p;
    for (int i = 0; i < 3; ++i) idx[i] = rng() % vs.size(), in.tri.v[i] = vs[idx[i]];
    SetupTriangle got;
    const bool ok = cache.triangle(in, got);
    bool expect_ok = true;
    for (size_t i : idx) expect_ok = expect_ok && want[i].ok;
    if (ok != expect_ok) {
      ++wrong;
      continue;
    }
    if (!ok) continue;
    bool same = got.prim == in.prim;
    for (int i = 0; i < 3; ++i) same = same && same_vertex(got.v[i], want[idx[i]].v, nv);
    wrong += !same;
  }
  return wrong;
}

}  // namespace

// Three threads look up and fill one shared slot (every vertex maps to it) at the same time:
// slots are read while another thread rewrites them, yet every answer is accepted_vertex's for
// the vertex looked up (a torn read answered would give another vertex's fields), and the slot
// keeps being found (a sequence number left odd would make every lookup a miss). A tear needs a
// reader and a writer within the same few nanoseconds: this run cannot force one, only never
// answer wrongly while they interleave.
TEST(Threads, SharedVertexTableUnderContentionAnswersAsTheStages) {
  const Config cfg;
  const int nv = 3;
  const DrawState st = vertex_state(0, 0, nv);
  std::mt19937_64 rng(0x7ab1e);
  const std::vector<ClipVertex> vs = some_vertices(rng, 6, nv);
  const std::vector<VertexAnswer> want = answers(cfg, st, vs);
  SharedVertexTable table;
  table.begin(nv);
  constexpr int kThreads = 3, kCount = 60000;
  std::vector<std::unique_ptr<VertexCache>> caches;
  std::vector<uint64_t> wrong(kThreads);
  for (int t = 0; t < kThreads; ++t) {
    caches.emplace_back(new VertexCache(cfg, st, 0, 0));  // one slot, from the first primitive
    caches.back()->share(table);
  }
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] { wrong[(size_t)t] = wrong_answers(*caches[(size_t)t], 100 + t, kCount, vs, want, nv); });
  for (std::thread& th : threads) th.join();
  uint64_t hits = 0, misses = 0;
  for (int t = 0; t < kThreads; ++t) {
    EXPECT_EQ(wrong[(size_t)t], 0u) << "thread " << t;
    hits += caches[(size_t)t]->hits(), misses += caches[(size_t)t]->misses();
  }
  EXPECT_GT(hits, (uint64_t)kCount / 10);  // both outcomes, many times
  EXPECT_GT(misses, (uint64_t)kCount / 10);
}

// A table filled through one cache answers another sharing it; the next draw (begin) finds it
// empty — its own draw state's answers, never the last draw's — also when the varying count
// changes the slot layout; a cache of another varying count than the table's keeps its own.
// (A direct-mapped table: a second pass over the same lookups misses only where a later vertex
// took the slot, and a third pass, through another cache, exactly as often.)
TEST(Threads, SharedVertexTableIsSharedWithinADrawAndEmptiedForTheNext) {
  const Config cfg;
  std::mt19937_64 rng(0x7ab1f);
  const std::vector<ClipVertex> vs = some_vertices(rng, 400, 2);
  SharedVertexTable table;
  const DrawState a = vertex_state(0, 0, 2), moved = vertex_state(-37, 11, 2), none = vertex_state(0, 0, 0);
  const int count = 3000;
  for (int round = 0; round < 2; ++round) {
    for (const DrawState* st : {&a, &moved, &none, &a}) {
      const int nv = st->num_varyings;
      const std::vector<VertexAnswer> want = answers(cfg, *st, vs);
      table.begin(nv);
      VertexCache fresh(cfg, *st, kVertexCacheMaxSlotBits, 0);  // a table of its own
      VertexCache first(cfg, *st, kVertexCacheMaxSlotBits, 0), second(cfg, *st, kVertexCacheMaxSlotBits, 0);
      first.share(table);
      second.share(table);
      EXPECT_EQ(wrong_answers(fresh, 1, count, vs, want, nv), 0u);
      EXPECT_EQ(wrong_answers(first, 1, count, vs, want, nv), 0u);
      const uint64_t m1 = first.misses();
      EXPECT_EQ(m1, fresh.misses()) << "round " << round;  // as empty as a new table
      EXPECT_EQ(wrong_answers(first, 1, count, vs, want, nv), 0u);
      const uint64_t m2 = first.misses() - m1;
      EXPECT_LT(m2, m1 / 4);
      EXPECT_EQ(wrong_answers(second, 1, count, vs, want, nv), 0u);
      EXPECT_EQ(second.misses(), m2) << "round " << round;  // the other cache's vertices found
    }
    // A cache with 1 varying and the table begun for 2: not shared (its own table).
    const DrawState one = vertex_state(0, 0, 1);
    table.begin(2);
    VertexCache other(cfg, one, kVertexCacheMaxSlotBits, 0);
    other.share(table);
    EXPECT_EQ(wrong_answers(other, 2, count, vs, answers(cfg, one, vs), 1), 0u);
  }
}

// Meshes with shared vertices, large enough for the threads' shared vertex cache, drawn one
// after the other through the same pool with other draw states (the viewport moved, the
// varying count changed): each frame equals the sequential unit's.
TEST(Threads, MeshesThroughTheSharedVertexCacheEqualTheSequentialUnit) {
  std::mt19937_64 rng(0x7ab20);
  Case c;
  c.name = "mesh";
  const int n = 40;  // (n − 1)² · 2 = 3,042 triangles, each vertex in up to 6
  std::vector<ClipVertex> grid = some_vertices(rng, n * n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {  // a regular grid, jittered depths and w
      ClipVertex& v = grid[(size_t)j * n + i];
      const float w = v.pos[3];
      v.pos[0] = (-1.1f + 2.2f * (float)i / (n - 1)) * w, v.pos[1] = (-1.1f + 2.2f * (float)j / (n - 1)) * w;
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const ClipVertex &p = grid[(size_t)j * n + i], &q = grid[(size_t)j * n + i + 1], &r = grid[(size_t)(j + 1) * n + i],
                       &s = grid[(size_t)(j + 1) * n + i + 1];
      c.tris.push_back(ClipTriangle{{p, q, s}});
      c.tris.push_back(ClipTriangle{{p, s, r}});
    }
  // One thread count after the other: the draws of one count run on the same pool, whose table
  // the next draw finds filled by the last (with the draw state it had).
  for (int t : {2, 3}) {
    ThreadOptions o;
    o.threads = t, o.batch_prims = t == 2 ? 500 : kThreadBatchPrims, o.setup_chunk_prims = t == 2 ? 7 : 64;
    // (0 varyings first: the pool's batch buffers then hold no planes when a draw with 2 comes.)
    for (const DrawState& st : {vertex_state(0, 0, 0), vertex_state(0, 0, 2), vertex_state(-23, 9, 2),
                                vertex_state(0, 0, 0), vertex_state(0, 0, 2)}) {
      c.st = st;
      expect_same_frame(run_raster_unit(c.cfg, c.st, c.tris), run_raster_unit(c.cfg, c.st, c.tris, o), 2,
                        "mesh, threads " + std::to_string(t) + ", viewport " + std::to_string(st.viewport_x) +
                            ", varyings " + std::to_string(st.num_varyings));
    }
  }
  check_case(c, {});  // (the sink and no-fragment paths)
}

namespace {

// Counts the split steps' direct rows (ThreadPhase::Direct) on thread 0 and on the others (parts
// written in place), thread 0's fills of a new depth buffer within a step (ThreadPhase::Clear;
// on another thread: `elsewhere`) and the gaps closed between a split step's parts (Compact).
class DirectCounter final : public ThreadObserver {
 public:
  void phase(int thread, ThreadPhase p) override {
    if (p == ThreadPhase::Direct) ++(thread == 0 ? on_0 : in_place);
    if (p == ThreadPhase::Clear) ++(thread == 0 ? clear : elsewhere);
    if (p == ThreadPhase::Compact) ++compact;
  }
  std::atomic<int> on_0{0}, in_place{0}, elsewhere{0}, clear{0}, compact{0};
};

ClipVertex plane_vertex(float x, float y, float z, float w, float a, float b) {
  ClipVertex v;
  v.pos[0] = x * w, v.pos[1] = y * w, v.pos[2] = z * w, v.pos[3] = w, v.var[0] = a, v.var[1] = b;
  return v;
}

// A grazing-plane-like quad (two triangles sharing an edge) over a 150 × 110 viewport, 2 varyings.
Case quad_case() {
  Case c;
  c.name = "split";
  c.st.viewport_x = -5, c.st.viewport_y = 4, c.st.viewport_w = 150, c.st.viewport_h = 110;
  c.st.num_varyings = 2;
  const ClipVertex p = plane_vertex(-0.95f, -0.9f, 0.2f, 1.0f, 0, 0), q = plane_vertex(0.97f, -0.93f, 0.3f, 1.3f, 5, 0),
                   r = plane_vertex(0.6f, 0.95f, 0.9f, 3.5f, 5, 7), s = plane_vertex(-0.7f, 0.9f, 0.8f, 3.0f, 0, 7);
  c.tris = {ClipTriangle{{p, q, r}}, ClipTriangle{{p, r, s}}};
  return c;
}

}  // namespace

TEST(Threads, SplitStepsWriteThreadZerosRowsStraightIntoTheFrame) {
  // Two large overlapping triangles (a grazing-plane-like quad and one in front of half of it):
  // steps of one triangle's rows are split steps (contiguous parts, thread 0's records written
  // straight into the frame's store), steps holding two triangles' items use the bands. The frame
  // equals the sequential unit's at every thread count and step size, on a new frame (whose
  // store first has no room: bands until it has grown; its depth buffer filled by thread 0 in
  // the first raster step, whose rows the threads claim) and on a reused one; a sink gets the
  // same stream without any split step.
  Case c = quad_case();
  c.tris.push_back(ClipTriangle{{plane_vertex(-0.3f, -0.8f, 0.1f, 1.0f, 1, 2), plane_vertex(0.9f, 0.1f, 0.1f, 1.0f, 3, 4),
                                 plane_vertex(-0.5f, 0.7f, 0.5f, 2.0f, 5, 6)}});
  const FrameOutput want = run_raster_unit(c.cfg, c.st, c.tris);
  ASSERT_GT(want.fragments.size(), 10000u);
  int split_frames = 0;
  for (int t : {2, 3, 5})
    for (int step : {40, 150, 1000, 4000, kThreadStepPixels})
      for (int rows : {1, 8}) {
        DirectCounter n;
        ThreadOptions o;
        o.threads = t, o.band_rows = rows, o.step_pixels = step, o.observer = &n;
        const std::string what = "threads " + std::to_string(t) + " step " + std::to_string(step) + " rows " +
                                 std::to_string(rows);
        FrameOutput f;
        for (int frame = 0; frame < 2; ++frame) {  // a new frame, then the same one reused
          n.clear = 0;
          // The split steps counted on the reused frame (a new frame's fill step may be one of
          // kThreadFillStepFactor steps: EachFillStepsPiecesGoInPlace).
          if (frame == 1) n.on_0 = 0, n.in_place = 0;
          run_raster_unit_threads(c.cfg, c.st, c.tris, f, &f.fragments, nullptr, o);
          expect_same_frame(want, f, 2, what + (frame ? " reused" : " new"));
          EXPECT_EQ(n.clear.load(), frame ? 0 : 1) << what << ": a new depth buffer filled within a step";
        }
        EXPECT_EQ(n.elsewhere.load(), 0) << what;
        // Split steps where a step holds at least a row per thread of one triangle: not at step 40
        // (items of one row, ≈ 140 pixels wide: a row a step), at 150 only on 2 threads (two rows a
        // step), nor at the default (whole triangles, several a step).
        const bool split = step > 40 && step < kThreadStepPixels && (step > 150 || t == 2);
        EXPECT_EQ(n.on_0.load() > 0, split) << what << ": split steps " << n.on_0.load();
        if (!split) {
          EXPECT_EQ(n.in_place.load(), 0) << what << ": parts in place without a split step";
        }
        split_frames += split;
        DirectCounter none;
        o.observer = &none;
        struct Record : FragmentSink {
          FragmentStore s{2};
          void emit(const Fragment& fr) override { s.push_back(fr); }
        } sink;
        FrameOutput g;
        run_raster_unit_threads(c.cfg, c.st, c.tris, g, nullptr, &sink, o);
        g.fragments = sink.s;
        expect_same_frame(want, g, 2, what + " sink");
        EXPECT_EQ(none.on_0.load() + none.in_place.load() + none.elsewhere.load(), 0)
            << what << ": a split step without a kept store";
      }
  EXPECT_EQ(split_frames, 14);
  // No triangle: no raster step; the new depth buffer is still filled (after the steps).
  ThreadOptions o;
  o.threads = 2;
  expect_same_frame(run_raster_unit(c.cfg, c.st, {}), run_raster_unit(c.cfg, c.st, {}, o), 2, "no triangle");
}

// A new frame's fill step (thread 0 fills the depth buffer while the rows are claimed in pieces)
// made of kThreadFillStepFactor steps when that makes a split step, each claimed piece written
// straight into the frame's store after the fragments the pieces before it generate. At 3
// threads and steps of 150 pixels only the fill step is a split step (a normal step holds one
// row of the quad, the fill step four). New frames one after the other through one pool (the
// store then has room, as in threads_bench), each equal to the sequential unit's.
TEST(Threads, FillStepsPiecesGoInPlace) {
  // The fill step is the frame's first raster step: a fragment fails its depth test there only
  // where it is at the cleared code itself. The quad fails none (Less); with Never every piece
  // keeps none of what it generates; with Equal on the far plane a few fragments pass.
  Case quad = quad_case(), never = quad_case(), far = quad_case();
  never.name = "never", far.name = "far";
  never.st.depth_func = DepthFunc::Never;
  for (ClipTriangle& t : far.tris)
    for (ClipVertex& v : t.v) v.pos[1] = -v.pos[1], v.pos[2] = v.pos[3] * (v.pos[0] < 0 ? 1.0f : 0.9999f);
  far.st.depth_func = DepthFunc::Equal;
  for (const Case* c : {&quad, &never, &far}) {
    const FrameOutput want = run_raster_unit(c->cfg, c->st, c->tris);
    ASSERT_EQ(want.stats.fragments_depth_fail > 0, c != &quad) << c->name;
    int direct = 0, compact = 0;
    for (int rows : {1, 8}) {
      DirectCounter n;
      ThreadOptions o;
      o.threads = 3, o.band_rows = rows, o.step_pixels = 150, o.observer = &n;
      for (int frame = 0; frame < 3; ++frame) {
        FrameOutput f;  // new each time
        run_raster_unit_threads(c->cfg, c->st, c->tris, f, &f.fragments, nullptr, o);
        expect_same_frame(want, f, 2, c->name + " rows " + std::to_string(rows) + " frame " + std::to_string(frame));
      }
      EXPECT_EQ(n.elsewhere.load(), 0);
      direct += n.on_0.load() + n.in_place.load(), compact += n.compact.load();
    }
    EXPECT_GT(direct, 0) << c->name << ": no piece written in place";
    if (c == &quad) {
      EXPECT_EQ(compact, 0) << "a gap where no fragment failed";
    }
  }
  // Without the fill step's in-place pieces, the same options make no split step at all.
  DirectCounter n;
  ThreadOptions o;
  o.threads = 3, o.step_pixels = 150, o.observer = &n;
  FrameOutput f;
  for (int frame = 0; frame < 2; ++frame) run_raster_unit_threads(quad.cfg, quad.st, quad.tris, f, &f.fragments, nullptr, o);
  n.on_0 = 0, n.in_place = 0;
  run_raster_unit_threads(quad.cfg, quad.st, quad.tris, f, &f.fragments, nullptr, o);  // reused: no fill step
  EXPECT_EQ(n.on_0.load() + n.in_place.load(), 0);
}

TEST(Threads, SplitStepsWriteEveryPartInPlaceAndCloseTheGapsOfDepthFailures) {
  // A split step's parts ≥ 1 written straight into the frame's store after the fragments the
  // parts before them generate. The quad alone fails no depth test: every part lands where the
  // sequential stream puts it (no gap closed: a miscounted part would leave one). Behind an
  // occluder drawn first, a part keeps fewer records than it generates: the gaps are closed
  // between the steps. Each frame (new, then reused) equals the sequential unit's.
  Case quad = quad_case(), hidden = quad_case();
  hidden.name = "occluded split";
  hidden.tris.insert(hidden.tris.begin(),
                     ClipTriangle{{plane_vertex(-0.8f, -0.7f, 0.05f, 1.0f, 1, 2), plane_vertex(0.7f, -0.2f, 0.05f, 1.0f, 3, 4),
                                   plane_vertex(-0.2f, 0.8f, 0.05f, 1.0f, 5, 6)}});
  for (const Case* c : {&quad, &hidden}) {
    const FrameOutput want = run_raster_unit(c->cfg, c->st, c->tris);
    const bool fails = c == &hidden;
    ASSERT_EQ(want.stats.fragments_depth_fail > 0, fails) << c->name;
    int in_place = 0, compact = 0;
    for (int t : {2, 3, 5})
      for (int step : {1000, 4000})
        for (int rows : {1, 8}) {
          DirectCounter n;
          ThreadOptions o;
          o.threads = t, o.band_rows = rows, o.step_pixels = step, o.observer = &n;
          const std::string what = c->name + " threads " + std::to_string(t) + " step " + std::to_string(step) +
                                   " rows " + std::to_string(rows);
          FrameOutput f;
          for (int frame = 0; frame < 2; ++frame) {
            run_raster_unit_threads(c->cfg, c->st, c->tris, f, &f.fragments, nullptr, o);
            expect_same_frame(want, f, 2, what + (frame ? " reused" : " new"));
          }
          EXPECT_GT(n.on_0.load(), 0) << what << ": no split step";
          if (!fails) {
            EXPECT_EQ(n.compact.load(), 0) << what << ": a gap where no fragment failed";
          }
          in_place += n.in_place.load(), compact += n.compact.load();
        }
    EXPECT_GT(in_place, 0) << c->name << ": no part ≥ 1 written in place";
    if (fails) {
      EXPECT_GT(compact, 0) << c->name << ": no gap closed";
    }
  }
}
