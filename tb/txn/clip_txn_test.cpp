// Co-simulation of rtl/fxr_clip.sv (stage 2, the model's "clip") on transaction dumps
// (tb/txn_harness.hpp): the committed dump of scenes/transactions.json, the default scene and
// scenes/clip_triangles.json, near_plane.json, guard_band.json dumped at build time, directed rows
// (near-plane and guard-band crossings, w at the w_min plane, triangles behind the eye, vertices
// on a plane, the float32 limits) and random clip-space triangles that need clipping, every output
// bit-identical and in order with the model's clip.out under random input gaps and output
// back-pressure; the done pulses' outcomes and created-vertex counts equal to the model's (and
// to the dumps' statistics); and, checked here without the model, every output vertex inside the
// clip volume (exactly, GMP, up to one ulp of the rounded components it is made of) and at most
// 3 + planes - 2 triangles per input. The clocks a clipped triangle costs are measured and must
// equal ClipStage::rtl_cycles() (the cost model the SystemC model reads). docs/rtl.md, "fxr_clip".
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "Vfxr_clip.h"
#include "draw_state_ports.hpp"
#include "model/stages/clip.hpp"
#include "model/vectors/codegen.hpp"
#include "model/vectors/record_vectors.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::ClipOutcome;
using fxr::DrawState;
using fxr::SceneStageVectors;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kBin = std::string(FXR_BINARY_DIR) + "/vectors/";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  TxnOptions o;
  o.unit = "clip";
  o.run_name = run;
  o.seed = seed;
  o.in_gap_pct = gap;
  o.out_stall_pct = stall;
  o.drain_cycles = 40000;  // a triangle clipped away ends without an output: wait for its done
  return o;
}

// The viewport on the DUT's ports; the done pulses counted by outcome; the clocks each primitive
// occupied the stage (input transfer to done, inclusive) by outcome.
struct Obs {
  DrawState st;
  int wib = 16;
  uint64_t count[6] = {};
  uint64_t created = 0;
  uint64_t cycle = 0, take_cycle = 0;
  std::vector<uint64_t> clip_cycles;  // Clipped / ClippedAway, in input order
  TxnHook<Vfxr_clip> hook() {
    TxnHook<Vfxr_clip> h;
    h.reset = [this] {
      for (auto& c : count) c = 0;
      created = cycle = take_cycle = 0;
      clip_cycles.clear();
    };
    h.drive = [this](Vfxr_clip& d) {
      d.viewport_x_i = fxr::tb::state_bits(st.viewport_x, wib);
      d.viewport_y_i = fxr::tb::state_bits(st.viewport_y, wib);
      d.viewport_w_i = fxr::tb::state_bits(st.viewport_w, wib + 1);
      d.viewport_h_i = fxr::tb::state_bits(st.viewport_h, wib + 1);
    };
    h.observe = [this](Vfxr_clip& d) {
      // done_o is registered: it pulses the clock after the decision (the stage's last busy clock)
      if (d.done_o) {
        const int o = d.done_outcome_o;
        if (o < 6) ++count[o];
        created += d.done_created_o;
        if (o == (int)ClipOutcome::Clipped || o == (int)ClipOutcome::ClippedAway) clip_cycles.push_back(cycle - take_cycle);
      }
      if (d.in_valid_i && d.in_ready_o) take_cycle = cycle;
      ++cycle;
    };
    return h;
  }
};

nlohmann::json dump_stats(const std::string& dir) {
  std::ifstream f(dir + "/scene.json");
  return nlohmann::json::parse(f).at("stats");
}

struct CycleStats {
  uint64_t n = 0, min = 0, max = 0, sum = 0;
  void add(uint64_t c) {
    min = n == 0 ? c : std::min(min, c);
    max = std::max(max, c);
    sum += c;
    ++n;
  }
  double mean() const { return n ? (double)sum / (double)n : 0.0; }
};

// The model's clip_cycles() of every input that went through the iterative clipper, in order.
std::vector<uint64_t> model_clip_cycles(const SceneStageVectors& v, const DrawState& st) {
  std::vector<uint64_t> r;
  const fxr::RecordShape shape{v.cfg, v.num_varyings};
  fxr::ClipStage stage(v.cfg, st);
  for (uint64_t row = 0; row < v.in.rows; ++row) {
    fxr::ExactTriangle t;
    fxr::unpack_record(t, shape, v.in.row(row), v.in.header);
    fxr::restore_record(t, shape);
    const fxr::ClipReport rep = stage.step(t, [](const fxr::ClippedTriangle&) {});
    if (rep.outcome == ClipOutcome::Clipped || rep.outcome == ClipOutcome::ClippedAway) r.push_back((uint64_t)stage.rtl_cycles());
  }
  return r;
}

// Runs v (no gaps / stalls, then two randomised handshakes); checks outputs, outcomes and cycles.
// Runs: no gaps / stalls (the clocks per clipped triangle are measured there), then randomised
// handshakes (`quick`: one, 25 % / 25 %; else two, also 60 % / 70 %).
CycleStats run_vectors(const SceneStageVectors& v, const DrawState& st, const std::string& name,
                       const uint64_t* want_count = nullptr, const uint64_t* want_created = nullptr, bool quick = false) {
  CycleStats cs;
  const std::vector<uint64_t> want_cycles = model_clip_cycles(v, st);
  std::vector<std::tuple<unsigned, unsigned, unsigned>> runs = {{1u, 0u, 0u}, {2u, 25u, 25u}};
  if (!quick) runs.emplace_back(3u, 60u, 70u);
  for (auto [seed, gap, stall] : runs) {
    Obs ob;
    ob.st = st;
    ob.wib = v.cfg.raster.window_int_bits;
    const TxnHook<Vfxr_clip> h = ob.hook();
    const TxnResult r = fxr::tb::run_txn<Vfxr_clip>(v, nullptr, opts(name + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << name << " seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
    uint64_t done = 0;
    for (uint64_t c : ob.count) done += c;
    EXPECT_EQ(done, v.in.rows) << "one done pulse per input";
    if (want_count) {
      for (int o = 0; o < 6; ++o) EXPECT_EQ(ob.count[o], want_count[o]) << name << " outcome " << o;
    }
    if (want_created) {
      EXPECT_EQ(ob.created, *want_created) << name;
    }
    if (seed == 1 && want_cycles.empty() && v.out.rows > 0) {
      // only trivial cases: ClipStage::cost()'s initiation interval and latency
      const fxr::StageCost c = fxr::ClipStage::cost(v.cfg);
      EXPECT_LE(r.last_out_cycle - r.first_in_cycle, (v.in.rows - 1) * (uint64_t)c.ii + (uint64_t)c.latency) << name;
    }
    if (seed == 1) {
      EXPECT_EQ(ob.clip_cycles, want_cycles) << name << ": measured clocks per clipped triangle != ClipStage::rtl_cycles()";
      for (uint64_t c : ob.clip_cycles) cs.add(c);
      std::printf("clip %s: %llu inputs, %llu outputs, %llu clipped: clocks per clipped triangle min %llu mean %.1f max %llu; "
                  "%llu cycles, %.0f cycles/s\n",
                  name.c_str(), (unsigned long long)v.in.rows, (unsigned long long)v.out.rows, (unsigned long long)cs.n,
                  (unsigned long long)cs.min, cs.mean(), (unsigned long long)cs.max, (unsigned long long)r.cycles,
                  r.seconds > 0 ? (double)r.cycles / r.seconds : 0.0);
    }
  }
  return cs;
}

void run_dump(const std::string& dir, const std::string& name, uint64_t min_rows) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "clip");
  ASSERT_GE(v.in.rows, min_rows);
  const DrawState st = fxr::tb::read_dump_draw_state(dir);
  const nlohmann::json s = dump_stats(dir);
  // The model's outcomes of the dump's inputs (the dump's statistics hold their sums).
  uint64_t want[6] = {}, created = 0;
  {
    const fxr::RecordShape shape{v.cfg, v.num_varyings};
    fxr::ClipStage stage(v.cfg, st);
    for (uint64_t row = 0; row < v.in.rows; ++row) {
      fxr::ExactTriangle t;
      fxr::unpack_record(t, shape, v.in.row(row), v.in.header);
      fxr::restore_record(t, shape);
      const fxr::ClipReport rep = stage.step(t, [](const fxr::ClippedTriangle&) {});
      ++want[(int)rep.outcome];
      if (rep.outcome == ClipOutcome::Clipped || rep.outcome == ClipOutcome::ClippedAway ||
          rep.outcome == ClipOutcome::RejectedOverflow)
        created += (uint64_t)rep.vertices_created;
    }
  }
  EXPECT_EQ(want[(int)ClipOutcome::Accepted], s.at("prims_trivial_accept").get<uint64_t>());
  EXPECT_EQ(want[(int)ClipOutcome::Clipped] + want[(int)ClipOutcome::ClippedAway] + want[(int)ClipOutcome::RejectedOverflow],
            s.at("prims_clipped").get<uint64_t>());
  EXPECT_EQ(created, s.at("clip_vertices_created").get<uint64_t>());
  run_vectors(v, st, name, want, &created);
}

TEST(ClipTxn, CommittedDumpMatchesTheModel) { run_dump(kCommitted, "clip_committed_", 5); }
TEST(ClipTxn, DefaultSceneMatchesTheModel) { run_dump(kBin + "scene_default", "clip_default_", 1000); }
TEST(ClipTxn, NearPlaneSceneMatchesTheModel) { run_dump(kBin + "scene_near_plane", "clip_near_plane_", 1); }
TEST(ClipTxn, GuardBandSceneMatchesTheModel) { run_dump(kBin + "scene_guard_band", "clip_guard_band_", 1); }

// ---- generated rows ---------------------------------------------------------------------------

fxr::FxFloat fx_of(float f) {
  bool nan = false, inf = false;
  return fxr::convert_input(f, nan, inf);
}

fxr::ExactTriangle tri_of(const float p[3][4], const float var[3][fxr::kMaxVaryings], int nv, uint32_t prim) {
  fxr::ExactTriangle t;
  t.prim = prim;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 4; ++c) t.v[i].p[c] = fx_of(p[i][c]);
    for (int k = 0; k < nv; ++k) t.v[i].v[k] = fx_of(var[i][k]);
    t.v[i].wa = t.v[i].p[3];
  }
  return t;
}

mpq_class q_of(const fxr::FxFloat& f) {
  mpz_class m(std::to_string(f.sig));
  mpq_class q(m);
  if (f.exp >= 0) q *= mpq_class(mpz_class(1) << f.exp);
  else q /= mpq_class(mpz_class(1) << -f.exp);
  return f.neg ? mpq_class(-q) : q;
}
mpq_class pow2(int e) {
  return e >= 0 ? mpq_class(mpz_class(1) << e) : mpq_class(mpz_class(1), mpz_class(1) << -e);
}

// Independent check of one output vertex: inside every plane of the clip volume, exactly for
// w_min and for an input vertex; a new vertex up to the rounding of the vertices it was made
// from: a plane distance a*c + b*w >= -2^-kRoundRelExp * (|a*c| + |b*w|) (each new component is
// within 2^-(bits-1) relative of its exact value, bits >= 24, and a vertex is made from at most
// kNumClipPlanes roundings in a row: 7 * 2^-23 < 2^-20; e.g. z/w of a far-plane vertex exceeds 1
// by up to an ulp, docs/pipeline.md stage 2). The planes are written here from docs/pipeline.md's
// table, not from the model's plane_eq().
constexpr int kRoundRelExp = 20;
std::string inside_violation(const fxr::ClipVtx& v, bool is_input, const DrawState& st, int wib) {
  const mpq_class x = q_of(v.p[0]), y = q_of(v.p[1]), z = q_of(v.p[2]), w = q_of(v.p[3]);
  if (w < pow2(fxr::kWMinExp)) return "w below 2^kWMinExp";
  const int64_t lim = (int64_t(1) << (wib - 1)) - fxr::kGuardMarginPx;
  const int64_t W = st.viewport_w, H = st.viewport_h, X0 = st.viewport_x, Y0 = st.viewport_y;
  const mpq_class rel = is_input ? mpq_class(0) : pow2(-kRoundRelExp);
  auto tol = [&](const mpq_class& a, const mpq_class& c, const mpq_class& b) -> mpq_class {
    return rel * (abs(a * c) + abs(b * w));
  };
  if (z < -tol(1, z, 0)) return "near";
  if (w - z < -tol(1, z, 1)) return "far";
  // x_w = (x/w + 1)·W/2 + X0 in [−lim, lim]  ⇔  (2(−lim − X0) − W)·w ≤ W·x ≤ (2(lim − X0) − W)·w
  const mpq_class nl(2 * (-lim - X0) - W), nr(2 * (lim - X0) - W), nb(2 * (-lim - Y0) - H), nt(2 * (lim - Y0) - H);
  if (mpq_class(W) * x - nl * w < -tol(W, x, nl)) return "left";
  if (nr * w - mpq_class(W) * x < -tol(W, x, nr)) return "right";
  if (mpq_class(H) * y - nb * w < -tol(H, y, nb)) return "bottom";
  if (nt * w - mpq_class(H) * y < -tol(H, y, nt)) return "top";
  return "";
}

// Builds vectors from triangles with the model's outputs; checks the invariants of the outputs.
SceneStageVectors make_vectors(const std::vector<fxr::ExactTriangle>& tris, const DrawState& st, uint64_t* clipped,
                               uint64_t want[6], uint64_t* created) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "clip");
  const fxr::RecordShape shape{v.cfg, v.num_varyings};
  const size_t ni = v.in.lay.size(), no = v.out.lay.size();
  v.in.data.clear();
  v.out.data.clear();
  v.in.rows = v.out.rows = 0;
  fxr::ClipStage stage(v.cfg, st);
  const int max_fan = 3 + fxr::kNumClipPlanes - 2;
  int worst_fan = 0;
  uint64_t violations = 0;
  for (size_t t = 0; t < tris.size(); ++t) {
    std::vector<fxr::ClippedTriangle> outs;
    const fxr::ClipReport rep = stage.step(tris[t], [&](const fxr::ClippedTriangle& o) { outs.push_back(o); });
    ++want[(int)rep.outcome];
    if (rep.outcome == ClipOutcome::Clipped || rep.outcome == ClipOutcome::ClippedAway) ++*clipped;
    if (rep.outcome == ClipOutcome::Clipped || rep.outcome == ClipOutcome::ClippedAway || rep.outcome == ClipOutcome::RejectedOverflow)
      *created += (uint64_t)rep.vertices_created;
    worst_fan = std::max(worst_fan, (int)outs.size());
    fxr::VecRow in(ni, 0);
    in[0] = t;
    in[1] = outs.size();
    fxr::pack_record(tris[t], shape, in, v.in.header, "clip directed row " + std::to_string(t));
    v.in.data.insert(v.in.data.end(), in.begin(), in.end());
    ++v.in.rows;
    for (size_t k = 0; k < outs.size(); ++k) {
      for (int i = 0; i < 3; ++i) {
        bool is_input = false;
        for (int j = 0; j < 3; ++j) {
          bool same = true;
          for (int c = 0; c < 4; ++c)
            same = same && outs[k].v[i].p[c].sig == tris[t].v[j].p[c].sig && outs[k].v[i].p[c].exp == tris[t].v[j].p[c].exp &&
                   outs[k].v[i].p[c].neg == tris[t].v[j].p[c].neg;
          is_input = is_input || same;
        }
        const std::string bad = inside_violation(outs[k].v[i], is_input, st, v.cfg.raster.window_int_bits);
        if (!bad.empty() && ++violations <= 10) ADD_FAILURE() << "row " << t << " output " << k << " vertex " << i << ": outside " << bad;
      }
      fxr::VecRow out(no, 0);
      out[0] = t;
      out[1] = k;
      out[2] = k + 1 == outs.size() ? 1 : 0;
      fxr::pack_record(outs[k], shape, out, v.out.header, "clip directed output " + std::to_string(t));
      v.out.data.insert(v.out.data.end(), out.begin(), out.end());
      ++v.out.rows;
    }
  }
  EXPECT_EQ(violations, 0u);
  EXPECT_LE(worst_fan, max_fan) << "triangles from one input beyond 3 + planes - 2";
  return v;
}

constexpr float kMax = 3.40282347e38f, kMinDen = 1.4e-45f;

DrawState state(int x, int y, int w, int h) {
  DrawState st;
  st.viewport_x = x;
  st.viewport_y = y;
  st.viewport_w = w;
  st.viewport_h = h;
  st.num_varyings = fxr::kRecordPackageVaryings;
  return st;
}

CycleStats run_generated(const std::vector<fxr::ExactTriangle>& tris, const DrawState& st, const std::string& name,
                         uint64_t min_clipped, bool quick = false) {
  uint64_t clipped = 0, want[6] = {}, created = 0;
  const SceneStageVectors v = make_vectors(tris, st, &clipped, want, &created);
  EXPECT_GE(clipped, min_clipped);
  return run_vectors(v, st, name, want, &created, quick);
}

// scenes/clip_triangles.json declares 3 varyings, the record package (and so the DUT) has
// kRecordPackageVaryings: its triangles are driven with their first varyings, the expectation
// computed for them (each component is clipped on its own: positions and those varyings are
// exactly the dump's).
TEST(ClipTxn, ClipTrianglesSceneMatchesTheModel) {
  const std::string dir = kBin + "scene_clip_triangles";
  const SceneStageVectors d = fxr::load_scene_stage(dir, "clip");
  ASSERT_GE(d.in.rows, 1u);
  const fxr::RecordShape shape{d.cfg, d.num_varyings};
  std::vector<fxr::ExactTriangle> tris;
  for (uint64_t r = 0; r < d.in.rows; ++r) {
    fxr::ExactTriangle t;
    fxr::unpack_record(t, shape, d.in.row(r), d.in.header);
    fxr::restore_record(t, shape);
    tris.push_back(t);
  }
  DrawState st = fxr::tb::read_dump_draw_state(dir);
  st.num_varyings = std::min(st.num_varyings, fxr::kRecordPackageVaryings);
  run_generated(tris, st, "clip_clip_triangles_", 0);
}

TEST(ClipTxn, DirectedRowsMatchTheModel) {
  const int nv = fxr::kRecordPackageVaryings;
  std::vector<fxr::ExactTriangle> tris;
  const float va[3][fxr::kMaxVaryings] = {{0.25f, -3.0f}, {1e-20f, 7.5f}, {-kMax, kMinDen}};
  auto add = [&](std::initializer_list<std::initializer_list<float>> vs) {
    float p[3][4];
    int i = 0;
    for (auto& v : vs) {
      int c = 0;
      for (float f : v) p[i][c++] = f;
      ++i;
    }
    tris.push_back(tri_of(p, va, nv, 500 + (uint32_t)tris.size()));
  };
  // Viewport 16 x 16 at the origin: lim 32767, n_right = 65518, the band's NDC x extent 4094.875.
  const float band = 4094.875f;
  add({{0, 0, -0.5f, 1}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}});          // near plane: one vertex behind
  add({{0, 0, -0.5f, 1}, {1, 0, -0.5f, 1}, {0, 1, 0.5f, 1}});         // near plane: two behind
  add({{0, 0, 0.5f, 1}, {1, 0, 1.5f, 1}, {0, 1, 0.5f, 1}});           // far plane
  add({{0, 0, 0.5f, 1}, {1e5f, 0, 0.5f, 1}, {0, 1, 0.5f, 1}});        // guard band right
  add({{-1e5f, -1e5f, 0.5f, 1}, {1e5f, -1e5f, 0.5f, 1}, {0, 1e5f, 0.5f, 1}});  // the band's corners
  add({{0, 0, 0.5f, -1}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}});          // w < 0: new vertices at w = 2^-160
  add({{0, 0, 0, -1}, {1, 0, 0.5f, 1}, {0, 1, 0.25f, 2}});            // w_min then near
  add({{0, 0, 0.5f, 0}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}});           // w = 0 exactly
  add({{0, 0, 0, kMinDen}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}});        // w the smallest subnormal
  add({{0, 0, 0.5f, -1}, {1, 0, 0.5f, -2}, {0, 1, 0.5f, -0.5f}});     // behind the eye: trivial reject
  add({{0, 0, -0.5f, -1}, {1, 0, 0.5f, -2}, {0, 1, 0.5f, 1}});        // two behind the eye
  add({{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0.5f, 1}});                 // two vertices on the near plane
  add({{0, 0, 0, 1}, {1, 0, -1, 1}, {0, 1, 0.5f, 1}});                // one on the near plane, one behind
  add({{0, 0, 1, 1}, {1, 0, 2, 1}, {0, 1, 0.5f, 1}});                 // one on the far plane, one beyond
  add({{band, 0, 0.5f, 1}, {band * 2, 0, 0.5f, 1}, {0, 1, 0.5f, 1}}); // a vertex on the right plane
  add({{-band, -band, 0.5f, 1}, {band, band, 0.5f, 1}, {band, -band * 2, 0.5f, 1}});  // on the corners
  add({{kMax, 0, 0.5f, 1}, {0, kMax, 0.5f, 1}, {0, 0, 0.5f, 1}});    // FLT_MAX coordinates
  add({{-kMax, -kMax, -kMax, kMax}, {kMax, 0, kMax, kMax}, {0, kMax, 0, kMax}});  // FLT_MAX everywhere
  add({{kMinDen, 0, -kMinDen, kMinDen}, {0, kMinDen, kMinDen, kMinDen}, {kMinDen, kMinDen, 0, kMinDen}});  // subnormals
  add({{1e-30f, 0, -1e-30f, 1e30f}, {1e30f, 0, 1e-30f, 1}, {0, 1, 0.5f, 1e-30f}});  // exponents far apart
  add({{1e30f, 1e30f, -1e30f, 1e-30f}, {-1e30f, 1e30f, 1e30f, 1e-30f}, {0, -1e30f, 1e-30f, 1e30f}});
  add({{0, 0, -kMax, kMax}, {0, 1, kMax, kMax}, {1, 0, 0.5f, kMinDen}});
  add({{1e-38f, 2e-38f, -1e-38f, 3e-38f}, {5e-38f, -1e-38f, 1e-38f, 1e-38f}, {0, 0, 1e-38f, -1e-38f}});
  add({{3, 3, 0.5f, 0.001f}, {-3, 3, 0.5f, 0.001f}, {0, -3, 0.5f, 0.001f}});  // every guard plane crossed
  add({{1e4f, 1e4f, -2, 1}, {-1e4f, 1e4f, 3, 1}, {0, -1e4f, 0.5f, -1}});     // all seven planes
  for (const DrawState& st : {state(0, 0, 16, 16), state(-1000, 37, 300, 200), state(-32767, -32767, 65534, 65534)})
    run_generated(tris, st, "clip_directed_" + std::to_string(st.viewport_x) + "_", 10);
}

TEST(ClipTxn, InvalidViewportRejectsEveryPrimitive) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "clip");
  const fxr::RecordShape shape{base.cfg, base.num_varyings};
  std::vector<fxr::ExactTriangle> tris;
  for (uint64_t r = 0; r < base.in.rows; ++r) {
    fxr::ExactTriangle t;
    fxr::unpack_record(t, shape, base.in.row(r), base.in.header);
    fxr::restore_record(t, shape);
    tris.push_back(t);
  }
  for (const DrawState& st : {state(0, 0, 0, 16), state(0, 0, 16, -3), state(32000, 0, 1000, 10)}) {
    uint64_t clipped = 0, want[6] = {}, created = 0;
    const SceneStageVectors v = make_vectors(tris, st, &clipped, want, &created);
    ASSERT_EQ(want[(int)ClipOutcome::RejectedViewport], tris.size());
    run_vectors(v, st, "clip_badviewport_", want, &created);
  }
}

// Random clip-space triangles, each needing the iterative clipper (trivially accepted and
// rejected ones are drawn again): magnitudes from 2^-40 to 2^40 per triangle, w of both signs,
// z across both depth planes, x, y across the guard band; varyings of any exponent.
std::vector<fxr::ExactTriangle> random_clipped(uint64_t seed, size_t count, const DrawState& st) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "clip");
  fxr::ClipStage stage(base.cfg, st);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const int nv = fxr::kRecordPackageVaryings;
  std::vector<fxr::ExactTriangle> r;
  while (r.size() < count) {
    const double s = std::ldexp(1.0, (int)(rng() % 81) - 40);
    const double band = (rng() % 2) ? 8000.0 : 3.0;
    float p[3][4], va[3][fxr::kMaxVaryings];
    int vexp[fxr::kMaxVaryings];
    for (int k = 0; k < nv; ++k) vexp[k] = (int)(rng() % 41) - 20;
    for (int i = 0; i < 3; ++i) {
      const double w = (rng() % 5 == 0 ? u(rng) : 0.2 + std::fabs(u(rng))) * s;
      p[i][3] = (float)w;
      p[i][0] = (float)(u(rng) * band * std::fabs(w));
      p[i][1] = (float)(u(rng) * band * std::fabs(w));
      p[i][2] = (float)((u(rng) * 1.5 + 0.5) * std::fabs(w));
      // varyings: mostly of one magnitude per triangle, one in eight of any exponent
      for (int k = 0; k < nv; ++k)
        va[i][k] = (float)std::ldexp(u(rng), rng() % 8 == 0 ? (int)(rng() % 200) - 100 : vexp[k] + (int)(rng() % 5));
    }
    const fxr::ExactTriangle t = tri_of(p, va, nv, (uint32_t)r.size());
    const fxr::ClipReport rep = stage.step(t, [](const fxr::ClippedTriangle&) {});
    if (rep.outcome == ClipOutcome::Clipped || rep.outcome == ClipOutcome::ClippedAway) r.push_back(t);
  }
  return r;
}

TEST(ClipTxn, RandomClippedTrianglesMatchTheModel) {
  const DrawState a = state(0, 0, 16, 16), b = state(-1000, 37, 300, 200);
  CycleStats ca = run_generated(random_clipped(21, 6000, a), a, "clip_random_a_", 6000, true);
  CycleStats cb = run_generated(random_clipped(22, 4000, b), b, "clip_random_b_", 4000, true);
  EXPECT_EQ(ca.n + cb.n, 10000u);
}

// The checker can fail: one bit of a new vertex's significand in the expectation flipped.
TEST(ClipTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "clip");
  const DrawState st = fxr::tb::read_dump_draw_state(kCommitted);
  size_t col = 0, row = v.out.rows;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "v1_x_sig") col = f;
  for (uint64_t r = 0; r < v.out.rows && row == v.out.rows; ++r)
    if (v.out.row(r)[1] != 0 || v.out.row(r)[2] == 0) row = r;  // a piece of a clipped triangle
  ASSERT_GT(col, 0u);
  ASSERT_LT(row, v.out.rows);
  v.out.data[row * v.out.lay.size() + col] ^= 1;
  Obs ob;
  ob.st = st;
  const TxnHook<Vfxr_clip> h = ob.hook();
  TxnOptions o = opts("clip_corrupt", 2, 25, 25);
  o.write_wave = false;
  const TxnResult r = fxr::tb::run_txn<Vfxr_clip>(v, nullptr, o, &h);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, row);
  EXPECT_EQ(r.mismatches[0].cls, "v1_x_sig");
}

}  // namespace
