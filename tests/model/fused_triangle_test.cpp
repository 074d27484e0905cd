// The small-triangle kernel (FusedTriangle, model/stages/fused_triangle.hpp; FragmentChain's
// triangle()) against the staged chain (a tap on the chain: traverse → interp → depth → divide,
// no fused code): on random narrow triangles (1–16 pixels wide, 1–40 tall, slivers, triangles
// with no covered pixel, some across the viewport's edges) drawn whole (run) and in row bands
// (rows: the threaded unit's calls), under every depth function, the depth test / write off,
// without a sink and with each way a sink takes records (its store, emit_span, one by one, lent
// memory), the default, D16, deep (z_frac_bits 38) and snapped-plane configurations, and with
// planes where the kernel's bounds fail (its fallback, counted): every fragment in order, every
// depth-buffer word and every counter equal. Then the default scene (the bunny) through the whole
// unit with the kernel and with the staged chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "frontend/scene.hpp"
#include "model/config/validate.hpp"
#include "model/stages/fused_triangle.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/fragment_store.hpp"
#include "stats_fields.hpp"

using namespace fxr;

namespace {

constexpr int kW = 160, kH = 120;

// Observes nothing, but is not NoTaps: the chain takes its staged path.
struct StagedTap {
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out&) {}
};

bool same_fragment(const Fragment& a, const Fragment& b) {
  return a.prim == b.prim && a.x == b.x && a.y == b.y && a.depth == b.depth;
}

DrawState viewport_state() {
  DrawState st;
  st.viewport_x = 2, st.viewport_y = -3, st.viewport_w = kW, st.viewport_h = kH;
  st.num_varyings = 0;
  return st;
}

// Narrow triangles in window pixels: a box 1–16 wide (a few 17–20: the span path) and 1–40
// tall, vertices anywhere in it (some slivers: the third vertex near the line of the other two;
// some tiny, between pixel centres), 1 in 8 across the viewport's edges, depths overlapping.
std::vector<ClipTriangle> narrow_tris(uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ClipTriangle> v;
  const DrawState st = viewport_state();
  for (int t = 0; t < n; ++t) {
    const double bw = t % 13 == 0 ? 16 + 4 * u(rng) : t % 7 == 0 ? 0.3 + u(rng) : 1 + 15 * u(rng);
    const double bh = t % 11 == 0 ? 0.4 * u(rng) : 1 + 39 * u(rng);
    const bool edge = t % 8 == 0;
    const double x = edge ? -bw / 2 + (t % 16 == 0 ? kW : 0) : (kW - bw) * u(rng);
    const double y = edge ? (kH - bh) * u(rng) : (kH - bh) * u(rng);
    double px[3], py[3];
    for (int k = 0; k < 3; ++k) px[k] = x + bw * u(rng), py[k] = y + bh * u(rng);
    if (t % 5 == 0) {  // a sliver
      const double s = u(rng);
      px[2] = px[0] + s * (px[1] - px[0]) + 0.05 * (u(rng) - 0.5);
      py[2] = py[0] + s * (py[1] - py[0]) + 0.05 * (u(rng) - 0.5);
    }
    ClipTriangle tri;
    for (int k = 0; k < 3; ++k) {
      const double w = 0.3 + 3 * u(rng), z = 0.2 + 0.6 * u(rng) + 0.01 * k;
      tri.v[k].pos[0] = (float)((2 * px[k] / st.viewport_w - 1) * w);
      tri.v[k].pos[1] = (float)((2 * py[k] / st.viewport_h - 1) * w);
      tri.v[k].pos[2] = (float)(z * w);
      tri.v[k].pos[3] = (float)w;
    }
    v.push_back(tri);
  }
  return v;
}

// The sinks: records per call (emit_span; each call must be one row, x increasing), the store of
// KeepFragments (records appended in place), emit only (the default emit_span), lent memory.
struct Blocks : FragmentSink {
  FragmentStore s;
  uint64_t blocks = 0, not_one_row = 0;
  Blocks() { s.shape(0); }
  void emit(const Fragment& f) override { s.push_back(f); }
  void emit_span(const FragmentRecords& b) override {
    ++blocks;
    for (size_t i = 1; i < b.count; ++i) not_one_row += b.y(i) != b.y(0) || b.x(i) <= b.x(i - 1) ? 1 : 0;
    s.append(b);
  }
};
struct OneByOne : FragmentSink {
  FragmentStore s;
  OneByOne() { s.shape(0); }
  void emit(const Fragment& f) override { s.push_back(f); }
};
struct Lends : FragmentSink {
  FragmentStore s;
  uint64_t lent = 0;
  Lends() {
    s.shape(0);
    offer_span_space();
  }
  void emit(const Fragment& f) override { s.push_back(f); }
  void emit_span(const FragmentRecords& b) override { s.append(b); }
  uint8_t* span_space(size_t n, int nv) override { return nv == 0 ? s.append_space(n) : nullptr; }
  void span_done(size_t count) override {
    ++lent;
    s.append_commit(count);
  }
};

enum class SinkKind { None, Store, Blocks, OneByOne, Lends };
const SinkKind kSinks[] = {SinkKind::None, SinkKind::Store, SinkKind::Blocks, SinkKind::OneByOne, SinkKind::Lends};

// One chain's frame: its depth buffer, counters and fragments.
struct Frame {
  std::vector<uint32_t> depth;
  RasterStats stats;
  FragmentStore kept;
  KeepFragments keep{kept};
  Blocks blocks;
  OneByOne one;
  Lends lends;
  explicit Frame(const std::vector<uint32_t>& d) : depth(d) { kept.shape(0); }
  FragmentSink* sink(SinkKind k) {
    switch (k) {
      case SinkKind::None: return nullptr;
      case SinkKind::Store: return &keep;
      case SinkKind::Blocks: return &blocks;
      case SinkKind::OneByOne: return &one;
      case SinkKind::Lends: return &lends;
    }
    return nullptr;
  }
  const FragmentStore* fragments(SinkKind k) const {
    switch (k) {
      case SinkKind::None: return nullptr;
      case SinkKind::Store: return &kept;
      case SinkKind::Blocks: return &blocks.s;
      case SinkKind::OneByOne: return &one.s;
      case SinkKind::Lends: return &lends.s;
    }
    return nullptr;
  }
};

// Every triangle of `tris` set up once (the setup stage with varyings, as a chain with a sink
// builds it) and drawn by both chains: whole (run) when bands is false, else cut into random
// row bands given to rows() in order (some empty, some beyond the rectangle). Returns the
// kernel's counts; every mismatch is an assertion failure naming `what`.
FusedTriangle::Counts compare(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                              SinkKind kind, bool bands, uint64_t seed, const std::string& what,
                              void (*edit)(TriangleEquations&) = nullptr) {
  std::mt19937_64 rng(seed);
  // Random stored codes, then the nearest codes of every third triangle (a staged "less" pass),
  // so that every depth function both passes and fails (equal: where that triangle comes again).
  std::vector<uint32_t> init((size_t)kW * kH);
  const uint32_t max_code = (uint32_t)depth_max_code(cfg.raster);
  for (uint32_t& c : init) c = (uint32_t)(rng() % ((uint64_t)max_code + 1));
  NoTaps nt;
  StagedTap tap;
  {
    DrawState pre = st;
    pre.depth_test = true, pre.depth_write = true, pre.depth_func = DepthFunc::Less;
    RasterStats ps;
    FragmentChain<StagedTap> first(cfg, pre, ps, init.data(), kW, nullptr, tap);
    GeometryChain<NoTaps> g(cfg, pre, nt);
    std::vector<SetupTriangle> out;
    for (size_t i = 0; i < tris.size(); i += 3) {
      InputTriangle in;
      in.prim = (uint32_t)i;
      in.tri = tris[i];
      out.clear();
      g.run_stages(in, out, ps);
      for (const SetupTriangle& p : out) first.run(p);
    }
  }
  Frame fk(init), fs(init);
  FragmentChain<NoTaps> kernel(cfg, st, fk.stats, fk.depth.data(), kW, fk.sink(kind), nt);
  FragmentChain<StagedTap> staged(cfg, st, fs.stats, fs.depth.data(), kW, fs.sink(kind), tap);
  GeometryChain<NoTaps> geom(cfg, st, nt);
  SetupStage setup(cfg, st, kind != SinkKind::None);
  std::vector<SetupTriangle> pieces;
  RasterStats gs;
  uint32_t prim = 0;
  for (const ClipTriangle& c : tris) {
    InputTriangle in;
    in.prim = prim++;
    in.tri = c;
    pieces.clear();
    geom.run_stages(in, pieces, gs);
    for (const SetupTriangle& p : pieces) {
      if (!bands && !edit) {
        const SetupOutcome a = kernel.run(p), b = staged.run(p);
        EXPECT_EQ(a, b) << what;
        continue;
      }
      setup.step(p, [&](const TriangleEquations& eq0) {
        TriangleEquations eq = eq0;
        if (edit) edit(eq);
        if (!bands) {
          kernel.rows(eq, eq.edges.y0, eq.edges.y1);
          staged.rows(eq, eq.edges.y0, eq.edges.y1);
          return;
        }
        int y = eq.edges.y0 - (int)(rng() % 3);
        while (y <= eq.edges.y1 + 1) {
          const int n = (int)(rng() % 9);  // 0: an empty band
          kernel.rows(eq, y, y + n - 1);
          staged.rows(eq, y, y + n - 1);
          y += n;
        }
      });
    }
  }
  EXPECT_EQ(stats_fields(fk.stats), stats_fields(fs.stats)) << what;
  EXPECT_TRUE(fk.depth == fs.depth) << what;
  EXPECT_GT(fk.stats.fragments_depth_pass, 0u) << what;
  if (st.depth_test && st.depth_func != DepthFunc::Always) {
    EXPECT_GT(fk.stats.fragments_depth_fail, 0u) << what;
  }
  if (const FragmentStore* a = fk.fragments(kind)) {
    const FragmentStore* b = fs.fragments(kind);
    EXPECT_EQ(a->size(), fk.stats.fragments_depth_pass) << what;
    EXPECT_EQ(a->size(), b->size()) << what;
    uint64_t bad = 0;
    for (size_t i = 0; i < std::min(a->size(), b->size()); ++i) bad += same_fragment((*a)[i], (*b)[i]) ? 0 : 1;
    EXPECT_EQ(bad, 0u) << what;
  }
  EXPECT_EQ(fk.blocks.not_one_row, 0u) << what;  // emit_span: one row per call
  if (kind == SinkKind::Blocks) {
    EXPECT_GT(fk.blocks.blocks, 0u) << what;
  }
  return kernel.triangle_counts();
}

Config config_named(const std::string& name) {
  Config c;
  if (name == "d16") c.raster.depth_format = DepthFormat::D16;
  if (name == "deep") c.raster.z_frac_bits = 38;  // the most with D24 (z·(2^24 − 1) in 63 bits)
  if (name == "snapped") c.raster.attr_subpixel_bits = c.raster.subpixel_bits;
  derive_widths(c);
  validate(c, name);
  return c;
}

}  // namespace

TEST(FusedTriangle, ChainTakesItOnlyWithoutTapsAndVaryings) {
  const Config cfg;
  DrawState st = viewport_state();
  std::vector<uint32_t> d((size_t)kW * kH, 0);
  RasterStats s;
  NoTaps nt;
  StagedTap tap;
  const std::vector<ClipTriangle> tris = narrow_tris(1, 200);
  FragmentChain<StagedTap> staged(cfg, st, s, d.data(), kW, nullptr, tap);
  st.num_varyings = 2;
  OneByOne one;
  FragmentChain<NoTaps> with_varyings(cfg, st, s, d.data(), kW, &one, nt);
  GeometryChain<NoTaps> geom(cfg, st, nt);
  std::vector<SetupTriangle> pieces;
  for (const ClipTriangle& c : tris) {
    InputTriangle in;
    in.tri = c;
    geom.run_stages(in, pieces, s);
  }
  ASSERT_GT(pieces.size(), 100u);
  for (const SetupTriangle& p : pieces) staged.run(p), with_varyings.run(p);
  EXPECT_EQ(staged.triangle_counts().triangles, 0u);
  EXPECT_EQ(with_varyings.triangle_counts().triangles, 0u);
}

TEST(FusedTriangle, NarrowTrianglesUnderEveryDepthStateAndSinkEqualTheStagedChain) {
  const std::vector<ClipTriangle> tris = narrow_tris(0x7213, 400);
  FusedTriangle::Counts total;
  uint64_t cases = 0;
  for (const DepthFunc f : {DepthFunc::Never, DepthFunc::Less, DepthFunc::Equal, DepthFunc::LessEqual,
                            DepthFunc::Greater, DepthFunc::NotEqual, DepthFunc::GreaterEqual, DepthFunc::Always}) {
    for (const int mode : {0, 1, 2}) {  // test and write; test, no write; no test
      for (const SinkKind kind : kSinks) {
        for (const bool bands : {false, true}) {
          DrawState st = viewport_state();
          st.depth_func = f;
          st.depth_test = mode != 2;
          st.depth_write = mode == 0;
          if (f == DepthFunc::Never && st.depth_test) continue;  // nothing passes: checked below
          const std::string what = "func " + std::to_string((int)f) + " mode " + std::to_string(mode) + " sink " +
                                   std::to_string((int)kind) + (bands ? " bands" : " whole");
          const FusedTriangle::Counts c = compare(Config{}, st, tris, kind, bands, 11 * cases + 5, what);
          total.triangles += c.triangles, total.rows += c.rows, total.wide_den += c.wide_den;
          total.fallbacks += c.fallbacks;
          if (kind == SinkKind::Lends) {
            EXPECT_EQ(c.triangles, 0u) << what;  // lent memory: the span path
          } else {
            EXPECT_GT(c.triangles, 100u) << what;
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_GT(total.wide_den, 1000u);                       // remainders in i128 (den ≥ 2^61)
  EXPECT_GT(total.triangles - total.wide_den, 1000u);     // and in int64_t
  EXPECT_EQ(total.fallbacks, 0u);                          // the scene's planes all fit
}

TEST(FusedTriangle, DepthFuncNeverPassesNothingAsTheStagedChain) {
  // (compare() expects passing fragments; here none pass, and nothing is written.)
  DrawState st = viewport_state();
  st.depth_func = DepthFunc::Never;
  const Config cfg;
  std::vector<uint32_t> dk((size_t)kW * kH, 7), ds = dk;
  RasterStats sk, ss;
  NoTaps nt;
  StagedTap tap;
  Blocks bk, bs;
  FragmentChain<NoTaps> kernel(cfg, st, sk, dk.data(), kW, &bk, nt);
  FragmentChain<StagedTap> staged(cfg, st, ss, ds.data(), kW, &bs, tap);
  GeometryChain<NoTaps> geom(cfg, st, nt);
  std::vector<SetupTriangle> pieces;
  RasterStats gs;
  for (const ClipTriangle& c : narrow_tris(3, 200)) {
    InputTriangle in;
    in.tri = c;
    geom.run_stages(in, pieces, gs);
  }
  for (const SetupTriangle& p : pieces) kernel.run(p), staged.run(p);
  EXPECT_GT(kernel.triangle_counts().triangles, 100u);
  EXPECT_EQ(stats_fields(sk), stats_fields(ss));
  EXPECT_GT(sk.fragments_depth_fail, 1000u);
  EXPECT_EQ(sk.fragments_depth_pass, 0u);
  EXPECT_EQ(bk.s.size(), 0u);
  EXPECT_EQ(bk.blocks, 0u);  // no empty emit_span
  EXPECT_TRUE(dk == ds);
}

TEST(FusedTriangle, OtherDepthFormatsAndPlanesEqualTheStagedChain) {
  const std::vector<ClipTriangle> tris = narrow_tris(0x1613, 300);
  for (const std::string name : {"d16", "deep", "snapped"}) {
    const Config cfg = config_named(name);
    for (const SinkKind kind : {SinkKind::None, SinkKind::Store, SinkKind::Blocks}) {
      for (const bool bands : {false, true}) {
        const FusedTriangle::Counts c =
            compare(cfg, viewport_state(), tris, kind, bands, 99, name + " sink " + std::to_string((int)kind));
        EXPECT_GT(c.triangles, 100u) << name;
        if (name == "deep") {
          EXPECT_GT(c.wide_den, c.triangles / 2) << name;  // den = 2A'·2^14: mostly i128
        }
        if (name == "snapped") {
          EXPECT_EQ(c.wide_den, 0u) << name;  // den = 2A·2^32 < 2^61
        }
      }
    }
  }
}

// Planes the kernel cannot step: a depth quotient beyond its int64_t bound (the code clamps to
// max_code), a denominator beyond 2^125 (every code 0). The kernel answers false for them and the
// chain takes the span path: still the staged chain's frame.
TEST(FusedTriangle, PlanesBeyondTheBoundsFallBackToTheSpanPath) {
  const std::vector<ClipTriangle> tris = narrow_tris(0xfa11, 200);
  const auto huge_z = [](TriangleEquations& eq) {
    if (eq.prim % 2 == 0 && eq.depth.den < ((i128)1 << 64)) eq.depth.z.c += eq.depth.den << 62;  // quotients ≈ 2^62
  };
  const auto huge_den = [](TriangleEquations& eq) {
    if (eq.prim % 3 == 0) eq.depth.den = (i128)1 << 126;
  };
  const auto huge_step = [](TriangleEquations& eq) {  // the corner fits, the y step does not
    if (eq.prim % 2 == 1 && eq.depth.den < ((i128)1 << 64)) eq.depth.z.dy = eq.depth.den << 60;
  };
  for (void (*edit)(TriangleEquations&) : {+huge_z, +huge_den, +huge_step}) {
    for (const SinkKind kind : {SinkKind::None, SinkKind::Store, SinkKind::Blocks}) {
      for (const bool bands : {false, true}) {
        const FusedTriangle::Counts e =
            compare(Config{}, viewport_state(), tris, kind, bands, 5, "fallback edited", edit);
        EXPECT_GT(e.fallbacks, 20u);
        EXPECT_GT(e.triangles, 20u);
      }
    }
  }
}

// The default scene (the bunny) through the whole unit: the kernel (NoTaps, no varyings) against
// the staged chain (a tap), with a store sink and without a sink, depth test on and off.
TEST(FusedTriangle, DefaultSceneThroughTheUnitEqualsTheStagedChain) {
  SceneOptions o;
  o.width = 256, o.height = 192;
  const Scene sc = default_scene(o);
  ASSERT_GT(sc.tris.size(), 10000u);
  for (const bool test : {true, false}) {
    for (const bool with_sink : {true, false}) {
      DrawState st = sc.state;
      st.num_varyings = 0;
      st.depth_test = test;
      FrameOutput fast, full;
      FragmentStore a, b;
      a.shape(0), b.shape(0);
      KeepFragments ka(a), kb(b);
      NoTaps nt;
      StagedTap ft;
      run_raster_unit_to(sc.config, st, sc.tris, fast, with_sink ? &ka : nullptr, nt);
      run_raster_unit_to(sc.config, st, sc.tris, full, with_sink ? &kb : nullptr, ft);
      EXPECT_EQ(stats_fields(fast.stats), stats_fields(full.stats));
      EXPECT_EQ(fast.depth, full.depth);
      EXPECT_GT(fast.stats.fragments_depth_pass, 10000u);
      ASSERT_EQ(a.size(), b.size());
      for (size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(same_fragment(a[i], b[i])) << "fragment " << i;
    }
  }
}

// Hand-made depth planes the scene's triangles rarely give: every pixel a tie (Z odd, den 2:
// RNE to even at every pixel, int64_t and i128 remainders), and codes crossing 0 and max_code
// within a row (the clamp at both ends).
TEST(FusedTriangle, TiesAndClampsOfHandMadePlanesEqualTheStagedChain) {
  const std::vector<ClipTriangle> tris = narrow_tris(0x7135, 200);
  const auto ties = [](TriangleEquations& eq) {
    eq.depth.den = 2, eq.depth.z.c = 2 * 100001 + 1, eq.depth.z.dx = 2 * (int64_t)(eq.prim % 7) - 6,
    eq.depth.z.dy = 4;
  };
  const auto ties_wide = [](TriangleEquations& eq) {  // the same at den = 2^70 (i128 remainders)
    const i128 half = (i128)1 << 69;
    eq.depth.den = half * 2, eq.depth.z.c = (2 * (i128)100001 + 1) * half,
    eq.depth.z.dx = (2 * (i128)(eq.prim % 7) - 6) * half * 2, eq.depth.z.dy = 4 * half * 2;
  };
  const auto clamps = [](TriangleEquations& eq) {  // 2^22 codes per pixel, from −2^23 at the anchor
    const i128 den = 1024 + eq.prim % 5;
    eq.depth.den = den, eq.depth.z.dx = den << 22, eq.depth.z.dy = (den << 20) * (eq.prim % 2 ? 1 : -1);
    eq.depth.z.c = -(den << 23) + 7;  // at the anchor (i0, j0), a vertex of the triangle
  };
  for (void (*edit)(TriangleEquations&) : {+ties, +ties_wide, +clamps}) {
    for (const SinkKind kind : {SinkKind::None, SinkKind::Store, SinkKind::Blocks}) {
      for (const bool bands : {false, true}) {
        for (const DepthFunc f : {DepthFunc::LessEqual, DepthFunc::Greater}) {  // codes at 0, at max_code pass
          DrawState st = viewport_state();
          st.depth_func = f;
          const FusedTriangle::Counts c = compare(Config{}, st, tris, kind, bands, 17, "hand-made plane", edit);
          EXPECT_GT(c.triangles, 100u);
          EXPECT_EQ(c.fallbacks, 0u);
        }
      }
    }
  }
}
