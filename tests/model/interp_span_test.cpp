// The fused stages 7–9 (FusedSpan, model/stages/interp_span.hpp) against the staged chain
// (InterpStage → DepthStage → DivideStage, the reference path every other model test checks
// against the exact references): every fragment field, every depth-buffer word and the pass /
// fail counts equal, span by span, on random triangles (overlapping, under every depth
// function, depth test and write on / off), long grazing spans whose plane sums cross binades
// and zero, affine mode, the default divider widths (compile-time constants) and other widths
// (run-time), 0–4 varyings. Each test also checks that the cases it is about were reached
// (FusedSpan::Counts), and the whole chain (FragmentChain picks the fused path only without taps).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <type_traits>
#include <string>
#include <vector>

#include "model/config/validate.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/interp_span.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/fragment_store.hpp"
#include "model/unit/geometry.hpp"
#include "tests/model/geom_ref.hpp"
#include "tests/model/random_tris.hpp"

using namespace fxr;

namespace {

constexpr int kW = 160, kH = 120;

bool same_fragment(const Fragment& a, const Fragment& b, int nv) {
  bool same = a.prim == b.prim && a.x == b.x && a.y == b.y && a.depth == b.depth;
  for (int k = 0; k < nv; ++k)
    same = same && a.var[k].neg == b.var[k].neg && a.var[k].sig == b.var[k].sig && a.var[k].exp == b.var[k].exp;
  return same;
}

DrawState viewport_state(int nv) {
  DrawState st;
  st.viewport_x = 2, st.viewport_y = -3, st.viewport_w = kW, st.viewport_h = kH;
  st.num_varyings = nv;
  return st;
}

// Small triangles (1–8 pixels across, the bunny's size) at random places, overlapping in depth.
std::vector<ClipTriangle> small_tris(uint64_t seed, int n, int nv) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> centre(-0.95f, 0.95f), size(0.01f, 0.1f), zf(0.0f, 1.0f), wf(0.2f, 4.0f),
      var(-5.0f, 5.0f), unit(-1.0f, 1.0f);
  std::vector<ClipTriangle> v;
  for (int t = 0; t < n; ++t) {
    ClipTriangle tri;
    const float cx = centre(rng), cy = centre(rng), sz = size(rng);
    for (auto& x : tri.v) {
      const float w = wf(rng);
      x.pos[0] = (cx + sz * unit(rng)) * w, x.pos[1] = (cy + sz * unit(rng)) * w, x.pos[2] = zf(rng) * w, x.pos[3] = w;
      for (int k = 0; k < nv; ++k) x.var[k] = var(rng);
    }
    v.push_back(tri);
  }
  return v;
}

// A grazing plane as two triangles (w from near to far: the sums change binade along a row)
// with varyings crossing zero in the middle of the screen.
std::vector<ClipTriangle> grazing_plane(int nv, float w_far) {
  ClipVertex a, b, c, d;
  const float wn = 0.3f;
  auto set = [&](ClipVertex& v, float x, float y, float w, float u) {
    v.pos[0] = x * w, v.pos[1] = y * w, v.pos[2] = 0.5f * w, v.pos[3] = w;
    for (int k = 0; k < nv; ++k) v.var[k] = k % 2 ? u * (float)(k + 1) : -u + 0.25f * (float)k;
  };
  set(a, -1.1f, -1.1f, wn, -3.0f), set(b, 1.1f, -1.1f, w_far, 2.0f), set(c, 1.1f, 1.1f, w_far, 5.0f),
      set(d, -1.1f, 1.1f, wn, -1.0f);
  ClipTriangle t0, t1;
  t0.v[0] = a, t0.v[1] = b, t0.v[2] = c;
  t1.v[0] = a, t1.v[1] = c, t1.v[2] = d;
  return {t0, t1};
}

// Stages 5–9 of every triangle, each span through the staged stages (interp → depth → divide,
// as FragmentChain composes them) on one depth buffer and through FusedSpan on another; every
// emitted fragment and both buffers compared. Returns the fused path's counts.
// scramble: each triangle's spans in a shuffled order, some repeated, some cut to a part (the
// span-start cursor then moves left, right, down and by several rows, and to the same start).
// call_begin false: FusedSpan::begin is never called; run() must tell each triangle setup
// writes into its one record from the last by the record's serial.
FusedSpan::Counts compare(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                          const std::string& what, bool scramble = false, bool call_begin = true) {
  const size_t words = (size_t)(st.viewport_w) * (size_t)st.viewport_h;
  std::vector<uint32_t> buf_staged(words, (1u << cfg.raster.depth_bits()) - 1), buf_fused = buf_staged,
                                                                                buf_u128 = buf_staged,
                                                                                buf_direct = buf_staged;
  const DepthBufferView vs{buf_staged.data(), st.viewport_w, st.viewport_x, st.viewport_y};
  const DepthBufferView vf{buf_fused.data(), st.viewport_w, st.viewport_x, st.viewport_y};
  const DepthBufferView vu{buf_u128.data(), st.viewport_w, st.viewport_x, st.viewport_y};
  const DepthBufferView vd{buf_direct.data(), st.viewport_w, st.viewport_x, st.viewport_y};
  SetupStage setup(cfg, st, true);
  TraverseStage traverse(cfg, st);
  InterpStage interp(cfg, st, true);
  DepthStage depth(cfg, st, vs);
  DivideStage divide(cfg, st, true);
  FusedSpan fused(cfg, st, vf, true);
  fused.set_direct(false);  // every span through the segments (the counts below are theirs)
  // The same with every segment's normalisations in u128 (no 64-bit-word segments): both loops
  // against the staged path.
  FusedSpan fused_u128(cfg, st, vu, true);
  fused_u128.set_high_words(false);
  fused_u128.set_direct(false);
  // The default: spans of ≤ kDirectMaxPixels pixels divided pixel by pixel (PixelDivide).
  FusedSpan fused_direct(cfg, st, vd, true);
  RasterStats gs;
  std::vector<SetupTriangle> pieces;
  // Both buffers first hold the nearest codes of the odd-numbered triangles (a staged "less"
  // pass), so that every depth function both passes and fails.
  {
    DrawState pre = st;
    pre.depth_test = true, pre.depth_write = true, pre.depth_func = DepthFunc::Less;
    SetupStage setup_pre(cfg, pre, false);
    InterpStage interp_pre(cfg, pre, false);
    DepthStage depth_pre(cfg, pre, vs);
    for (size_t p = 1; p < tris.size(); p += 2) {
      pieces.clear();
      geometry(cfg, pre, tris[p], (uint32_t)p, pieces, gs);
      for (const SetupTriangle& tri : pieces)
        setup_pre.step(tri, [&](const TriangleEquations& eq) {
          traverse.step(eq, [&](const Span& sp) {
            interp_pre.step(eq, sp, [&](const PlaneSample& ps) { depth_pre.step(ps, [](const PlaneSample&) {}); });
          });
        });
    }
    buf_fused = buf_staged;
    buf_u128 = buf_staged;
    buf_direct = buf_staged;
  }
  uint64_t frags = 0, bad = 0, fails = 0;
  std::mt19937_64 rng(tris.size());
  for (size_t p = 0; p < tris.size(); ++p) {
    pieces.clear();
    geometry(cfg, st, tris[p], (uint32_t)p, pieces, gs);
    for (const SetupTriangle& tri : pieces)
      setup.step(tri, [&](const TriangleEquations& eq) {
        if (call_begin) {  // setup rewrites one record per triangle
          fused.begin(eq);
          fused_u128.begin(eq);
          fused_direct.begin(eq);
        }
        auto check = [&](const Span& sp) {
          std::vector<Fragment> want, got;
          uint64_t pass_staged = 0;
          interp.step(eq, sp, [&](const PlaneSample& ps) {
            if (depth.step(ps, [&](const PlaneSample& q) { divide.step(q, [&](const Fragment& f) { want.push_back(f); }); }))
              ++pass_staged;
          });
          frags += want.size();
          fails += (uint64_t)(sp.x1 - sp.x0 + 1) - pass_staged;
          for (FusedSpan* fs : {&fused, &fused_u128, &fused_direct}) {
            got.clear();
            const uint64_t pass_fused = fs->run(eq, sp, [&](const Fragment& f) { got.push_back(f); });
            const char* path = fs == &fused ? "" : fs == &fused_u128 ? " (u128 segments)" : " (direct short spans)";
            if (pass_fused != pass_staged || want.size() != got.size()) {
              if (++bad <= 3) ADD_FAILURE() << what << path << ": span y " << sp.y << " x " << sp.x0 << ".." << sp.x1 << " passes " << pass_staged << " vs " << pass_fused;
              continue;
            }
            for (size_t i = 0; i < want.size(); ++i) {
              if (!same_fragment(want[i], got[i], st.num_varyings) && ++bad <= 3)
                ADD_FAILURE() << what << path << ": fragment (" << want[i].x << ", " << want[i].y << ") prim " << want[i].prim;
            }
          }
        };
        if (!scramble) {
          traverse.step(eq, check);
          return;
        }
        std::vector<Span> spans;
        traverse.step(eq, [&](const Span& sp) { spans.push_back(sp); });
        const size_t n = spans.size();
        for (size_t k = 0; k < n; ++k) {
          Span part = spans[k];
          if (rng() % 3 == 0) spans.push_back(part);  // the same start again
          if (part.x1 > part.x0 && rng() % 2 == 0) {  // a later part of the span
            part.x0 += 1 + (int)(rng() % (uint64_t)(part.x1 - part.x0));
            spans.push_back(part);
          }
        }
        std::shuffle(spans.begin(), spans.end(), rng);
        for (const Span& sp : spans) check(sp);
      });
  }
  EXPECT_EQ(bad, 0u) << what;
  EXPECT_TRUE(buf_staged == buf_fused) << what << ": depth buffers differ";
  EXPECT_TRUE(buf_staged == buf_u128) << what << ": depth buffers differ (u128 segments)";
  EXPECT_TRUE(buf_staged == buf_direct) << what << ": depth buffers differ (direct short spans)";
  EXPECT_EQ(fused_u128.counts().segments_high, 0u) << what;
  if (st.depth_func != DepthFunc::Never) {
    EXPECT_GT(frags, 0u) << what << ": nothing drawn (the test would be vacuous)";
  }
  if (st.depth_test && st.depth_func != DepthFunc::Never && st.depth_func != DepthFunc::Always) {
    EXPECT_GT(fails, 0u) << what << ": nothing failed the depth test";
  }
  FusedSpan::Counts c = fused.counts();
  c.spans_direct = fused_direct.counts().spans_direct;
  EXPECT_EQ(fused.counts().spans_direct + fused_u128.counts().spans_direct, 0u) << what;
  return c;
}

Config widths_config(int nb, int db, int qb) {
  Config c;
  c.div.num_bits = nb, c.div.den_bits = db, c.div.quot_bits = qb;
  c.raster.varying_out_sig_bits = qb;
  derive_widths(c);
  return c;
}

void add(FusedSpan::Counts& a, const FusedSpan::Counts& b) {
  a.spans += b.spans, a.spans_z128 += b.spans_z128, a.spans_zconst += b.spans_zconst, a.segments += b.segments;
  a.exits_divided += b.exits_divided, a.sign_changes += b.sign_changes, a.segments_high += b.segments_high;
  a.segments_high_low += b.segments_high_low;
  a.cursor_starts += b.cursor_starts, a.cursor_moves += b.cursor_moves, a.spans_z64 += b.spans_z64;
  a.z_moves_divided += b.z_moves_divided, a.z_cursor_lost += b.z_cursor_lost, a.rearmed_moves += b.rearmed_moves;
  a.sums_fixed += b.sums_fixed, a.rearmed_sign_moves += b.rearmed_sign_moves;
  a.spans_direct += b.spans_direct;
}

// A tap (any tap type but NoTaps makes FragmentChain take the staged stages).
struct Observe {
  uint64_t samples = 0;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out&) {
    if (std::is_same<S, InterpStage>::value) ++samples;
  }
};

}  // namespace

TEST(FusedSpan, AppliesWhereTheStageDividesWithTheFast64Path) {
  EXPECT_TRUE(FusedSpan::applies(Config{}));
  EXPECT_TRUE(FusedSpan::applies(widths_config(39, 39, 24)));   // W + qb = 63
  EXPECT_FALSE(FusedSpan::applies(widths_config(40, 40, 24)));  // 64: the staged u128 path
  Config rm;
  rm.div.algorithm = DivAlgorithm::RecipMul;
  EXPECT_FALSE(FusedSpan::applies(rm));
  Config sr;
  sr.div.algorithm = DivAlgorithm::SharedRecip;
  EXPECT_FALSE(FusedSpan::applies(sr));
}

TEST(FusedSpan, DepthFunctionMaskIsTheComparison) {
  for (DepthFunc f : {DepthFunc::Never, DepthFunc::Less, DepthFunc::Equal, DepthFunc::LessEqual, DepthFunc::Greater,
                      DepthFunc::NotEqual, DepthFunc::GreaterEqual, DepthFunc::Always}) {
    const unsigned mask = depth_func_mask(f);
    for (uint32_t a : {0u, 1u, 7u, 0xFFFFFFu, 0xFFFFFFFFu})
      for (uint32_t b : {0u, 1u, 7u, 0xFFFFFFu, 0xFFFFFFFFu})
        EXPECT_EQ(((mask >> depth_relation(a, b)) & 1u) != 0, depth_compare(f, a, b)) << (int)f << " " << a << " " << b;
  }
}

TEST(FusedSpan, RandomTrianglesUnderEveryDepthStateEqualTheStagedPath) {
  const DepthFunc funcs[] = {DepthFunc::Less, DepthFunc::Equal, DepthFunc::LessEqual, DepthFunc::Greater,
                             DepthFunc::NotEqual, DepthFunc::GreaterEqual, DepthFunc::Always, DepthFunc::Never};
  FusedSpan::Counts total;
  int i = 0;
  for (DepthFunc fn : funcs) {
    for (int nv : {0, 1, 2, 4}) {
      DrawState st = viewport_state(nv);
      st.depth_func = fn;
      st.depth_write = i % 3 != 2;
      st.depth_test = i % 5 != 4;
      const std::string what = "func " + std::to_string((int)fn) + " nv " + std::to_string(nv) + " test " +
                               std::to_string(st.depth_test) + " write " + std::to_string(st.depth_write);
      add(total, compare(Config{}, st, random_tris(500 + i, 40, nv), what));
      ++i;
    }
  }
  EXPECT_GT(total.spans, 1000u);
  EXPECT_GT(total.segments, total.spans);  // sums left their binade inside spans
  EXPECT_GT(total.exits_divided, 0u);
  EXPECT_GT(total.sign_changes, 0u);       // and crossed zero
  EXPECT_GT(total.segments_high, 100u);    // both loops
  EXPECT_GT(total.segments - total.segments_high, 100u);
  // The word segments also where D's significand reaches into the low word (the sums aligned,
  // docs/speed.md "Session 12: the pixel loop").
  EXPECT_GT(total.segments_high_low, 10u);
  // Short spans with varyings divided pixel by pixel (the default path, compared as well).
  EXPECT_GT(total.spans_direct, 1000u);
}

TEST(FusedSpan, GrazingPlanesAcrossBinadesAndZeroEqualTheStagedPath) {
  FusedSpan::Counts total;
  for (float w_far : {1.0f, 8.0f, 200.0f, 3000.0f})
    for (int nv : {1, 2, 3, 4}) {
      const DrawState st = viewport_state(nv);
      add(total, compare(Config{}, st, grazing_plane(nv, w_far), "plane w_far " + std::to_string(w_far) + " nv " + std::to_string(nv)));
    }
  EXPECT_GT(total.segments, 2 * total.spans);
  EXPECT_GT(total.sign_changes, 0u);
  // Both loops of the fused path: segments in 64-bit words and in u128 (a sum at zero, D ≤ 0, a
  // binade at or below 2^95).
  EXPECT_GT(total.segments_high, 100u);
  EXPECT_GT(total.segments - total.segments_high, 100u);
}

TEST(FusedSpan, OtherDividerWidthsAndAffineModeEqualTheStagedPath) {
  FusedSpan::Counts total;
  // Run-time widths (not the compile-time default shape), at the fast path's limit too.
  for (const Config& cfg : {widths_config(28, 30, 20), widths_config(39, 39, 24), widths_config(32, 24, 16)}) {
    ASSERT_NO_THROW(validate(cfg, "interp_span_test"));
    for (int nv : {1, 2, 3}) {
      DrawState st = viewport_state(nv);
      const std::string what = "widths " + std::to_string(cfg.div.num_bits) + "/" + std::to_string(cfg.div.den_bits) +
                               "/" + std::to_string(cfg.div.quot_bits) + " nv " + std::to_string(nv);
      add(total, compare(cfg, st, random_tris(900 + nv, 30, nv), what));
      add(total, compare(cfg, st, grazing_plane(nv, 50.0f), what + " plane"));
    }
  }
  for (int nv : {1, 2}) {
    DrawState st = viewport_state(nv);
    st.interp = InterpMode::Affine;
    add(total, compare(Config{}, st, random_tris(950 + nv, 30, nv), "affine nv " + std::to_string(nv)));
  }
  EXPECT_GT(total.segments, total.spans);
}

TEST(FusedSpan, BothDepthStepperWidthsAreReached) {
  // Large and tiny w give depth planes whose stepping does not fit int64_t (depth_step_fits64).
  FusedSpan::Counts total;
  for (uint64_t seed : {1u, 2u, 3u}) {
    std::vector<ClipTriangle> tris = random_tris(seed, 40, 2);
    for (size_t t = 0; t < tris.size(); t += 2)
      for (auto& v : tris[t].v)
        for (int c = 0; c < 4; ++c) v.pos[c] *= 1e-30f;
    add(total, compare(Config{}, viewport_state(2), tris, "scaled seed " + std::to_string(seed)));
  }
  EXPECT_GT(total.spans_z128, 0u);
  EXPECT_LT(total.spans_z128, total.spans);
}

TEST(FusedSpan, TheChainTakesItOnlyWithoutTapsAndGivesTheSameFrame) {
  // FragmentChain with NoTaps (fused) against the same chain observed by a tap (staged).
  struct Keep : FragmentSink {
    FragmentStore s;
    void draw_state(const DrawState& st) override { s.widen(st.num_varyings); }
    void emit(const Fragment& f) override { s.push_back(f); }
  };
  for (int nv : {0, 2, 3}) {
    const DrawState st = viewport_state(nv);
    std::vector<ClipTriangle> tris = random_tris(77 + nv, 50, nv);
    for (const ClipTriangle& t : grazing_plane(nv, 40.0f)) tris.push_back(t);
    Config cfg;
    FrameOutput fa, fb;
    Keep ka, kb;
    ka.s.shape(nv), kb.s.shape(nv);
    NoTaps none;
    Observe obs;
    run_raster_unit_to(cfg, st, tris, fa, &ka, none);
    run_raster_unit_to(cfg, st, tris, fb, &kb, obs);
    EXPECT_GT(obs.samples, 0u);  // the observed chain ran the staged stages
    ASSERT_EQ(ka.s.size(), kb.s.size()) << nv;
    ASSERT_GT(ka.s.size(), 0u);
    uint64_t bad = 0;
    for (size_t i = 0; i < ka.s.size(); ++i) bad += same_fragment(ka.s[i], kb.s[i], nv) ? 0 : 1;
    EXPECT_EQ(bad, 0u) << nv;
    EXPECT_TRUE(fa.depth == fb.depth) << nv;
    EXPECT_EQ(fa.stats.fragments_depth_pass, fb.stats.fragments_depth_pass) << nv;
    EXPECT_EQ(fa.stats.fragments_depth_fail, fb.stats.fragments_depth_fail) << nv;
    EXPECT_EQ(fa.stats.fragments_generated, fb.stats.fragments_generated) << nv;
  }
}

TEST(FusedSpan, SpanRecordsReachEverySinkAsTheSameFragments) {
  // The fused chain hands a span's passing fragments to FragmentSink::emit_span as compact
  // records: KeepFragments appends them in one copy (or widens each when its store has more
  // varyings), a sink without emit_span gets them one by one (the default). Each must hold the
  // fragments of the staged chain (observed by a tap: emit per fragment), in order.
  struct Spans : FragmentSink {  // KeepFragments' bulk append, counting the blocks
    FragmentStore s;
    uint64_t blocks = 0, records = 0;
    void draw_state(const DrawState& st) override { s.widen(st.num_varyings); }
    void emit(const Fragment& f) override { s.push_back(f); }
    void emit_span(const FragmentRecords& b) override {
      ++blocks, records += b.count;
      s.append(b);
    }
  };
  // Lends memory of its own (span_space / span_done, offered: asked per span); the same without
  // offering it (never asked: emit_span's copy).
  struct Lends : FragmentSink {
    FragmentStore s;
    uint64_t lent = 0, copied = 0;
    explicit Lends(bool offer) {
      if (offer) offer_span_space();
    }
    void draw_state(const DrawState& st) override { s.widen(st.num_varyings); }
    void emit(const Fragment& f) override { s.push_back(f); }
    void emit_span(const FragmentRecords& b) override {
      ++copied;
      s.append(b);
    }
    uint8_t* span_space(size_t n, int nv) override { return nv == s.num_varyings() ? s.append_space(n) : nullptr; }
    void span_done(size_t count) override {
      ++lent;
      s.append_commit(count);
    }
  };
  struct OneByOne : FragmentSink {  // only emit: the default emit_span decodes
    FragmentStore s;
    void draw_state(const DrawState& st) override { s.widen(st.num_varyings); }
    void emit(const Fragment& f) override { s.push_back(f); }
  };
  for (int nv : {0, 1, 2, 3}) {
    const DrawState st = viewport_state(nv);
    std::vector<ClipTriangle> tris = random_tris(177 + nv, 60, nv);
    for (const ClipTriangle& t : grazing_plane(nv, 30.0f)) tris.push_back(t);
    Config cfg;
    FrameOutput f_staged, f_spans, f_one, f_wide, f_keep;
    Spans staged, spans, wide;
    OneByOne one;
    FragmentStore kept, kept_wide;
    KeepFragments keep(kept), keep_wide(kept_wide);  // its memory lent / not (another shape)
    FrameOutput f_keep_wide, f_lends, f_asked_not;
    Lends lends(true), not_offered(false);
    lends.s.shape(nv), not_offered.s.shape(nv);
    kept_wide.shape(nv + 1);
    staged.s.shape(nv), spans.s.shape(nv), one.s.shape(nv), kept.shape(nv);
    wide.s.shape(nv + 1);  // more varyings than the draw: each record widened
    NoTaps none;
    Observe obs;
    run_raster_unit_to(cfg, st, tris, f_staged, &staged, obs);
    run_raster_unit_to(cfg, st, tris, f_spans, &spans, none);
    run_raster_unit_to(cfg, st, tris, f_one, &one, none);
    run_raster_unit_to(cfg, st, tris, f_wide, &wide, none);
    run_raster_unit_to(cfg, st, tris, f_keep, &keep, none);
    run_raster_unit_to(cfg, st, tris, f_keep_wide, &keep_wide, none);
    run_raster_unit_to(cfg, st, tris, f_lends, &lends, none);
    run_raster_unit_to(cfg, st, tris, f_asked_not, &not_offered, none);
    EXPECT_GT(lends.lent, 100u) << nv;  // every fused span in its memory
    EXPECT_EQ(lends.copied, 0u) << nv;
    EXPECT_EQ(not_offered.lent, 0u) << nv;  // not offered: never asked
    EXPECT_GT(not_offered.copied, 100u) << nv;
    EXPECT_EQ(kept_wide.num_varyings(), nv + 1);
    EXPECT_EQ(staged.blocks, 0u);       // the staged chain emits one at a time
    EXPECT_GT(spans.blocks, 100u) << nv;  // the fused chain per span
    EXPECT_EQ(spans.records, spans.s.size());
    ASSERT_GT(staged.s.size(), 1000u) << nv;
    for (const FragmentStore* got : {&spans.s, &one.s, &wide.s, &kept, &kept_wide, &lends.s, &not_offered.s}) {
      ASSERT_EQ(got->size(), staged.s.size()) << nv;
      uint64_t bad = 0;
      for (size_t i = 0; i < got->size(); ++i) {
        const Fragment a = staged.s[i], b = (*got)[i];
        bad += same_fragment(a, b, nv) ? 0 : 1;
        if (got == &wide.s || got == &kept_wide) bad += b.var[nv].sig == 0 && b.var[nv].exp == 0 && !b.var[nv].neg ? 0 : 1;
      }
      EXPECT_EQ(bad, 0u) << nv;
    }
    EXPECT_EQ(wide.s.num_varyings(), nv + 1);
    for (const FrameOutput* f : {&f_spans, &f_one, &f_wide, &f_keep, &f_keep_wide, &f_lends, &f_asked_not}) {
      EXPECT_TRUE(f->depth == f_staged.depth) << nv;
      EXPECT_EQ(f->stats.fragments_depth_pass, f_staged.stats.fragments_depth_pass) << nv;
      EXPECT_EQ(f->stats.fragments_depth_fail, f_staged.stats.fragments_depth_fail) << nv;
    }
  }
}

TEST(FusedSpan, RecordsWithMoreVaryingsThanTheStoreAreRefused) {
  FragmentStore s(1);
  uint8_t rec[fragment_record_bytes(2)] = {};
  EXPECT_THROW(s.append(FragmentRecords{rec, 1, 2}), std::logic_error);
  EXPECT_NO_THROW(s.append(FragmentRecords{rec, 1, 1}));
  EXPECT_NO_THROW(s.append(FragmentRecords{rec, 1, 0}));
  EXPECT_EQ(s.size(), 2u);
}

namespace {

mpz_class mpz_of(i128 v) {
  const bool neg = v < 0;
  const u128 m = neg ? (u128)0 - (u128)v : (u128)v;
  mpz_class z = mpz_class((unsigned long)(uint64_t)(m >> 64));
  z <<= 64;
  z += mpz_class((unsigned long)(uint64_t)m);
  return neg ? mpz_class(-z) : z;
}

// The code at (i, j) from its definition, in GMP: clamp(RNE(Z(i, j) / den), 0, max_code).
uint32_t ref_code(const DepthSetup& s, int i, int j) {
  const mpz_class z = mpz_of(s.z.c) + mpz_class(i - s.z.i0) * mpz_of(s.z.dx) + mpz_class(j - s.z.j0) * mpz_of(s.z.dy);
  mpq_class q(z, mpz_of(s.den));
  q.canonicalize();
  mpz_class c = georef::rne_int(q);
  if (c < 0) c = 0;
  if (c > mpz_of(s.max_code)) c = mpz_of(s.max_code);
  return (uint32_t)c.get_ui();
}

// A nearly level plane: z/w varies by `slope` across the screen in x, so the code is one value
// over many spans and changes inside others.
std::vector<ClipTriangle> level_plane(int nv, float slope) {
  std::vector<ClipTriangle> v = grazing_plane(nv, 20.0f);
  for (ClipTriangle& t : v)
    for (ClipVertex& c : t.v) c.pos[2] = (0.5f + slope * c.pos[0] / c.pos[3]) * c.pos[3];
  return v;
}

}  // namespace

TEST(FusedSpan, EqualEndCodesMeanOneCodeOverTheSpan) {
  // The range test of the wide depth path: the codes at both ends of a span equal ⇒ every code
  // of the span equals them (the code is monotone along x). Random depth planes with den of
  // 2^40–2^100 and slopes giving 0 to a few code changes per span, each span's every code from
  // the definition (GMP); then directed ties at the span end (Z/den = c + ½ exactly: c even
  // rounds down — one code; c odd rounds up — two), and the clamps at 0 and max_code.
  std::mt19937_64 rng(2026);
  uint64_t one = 0, several = 0;
  auto check = [&](const DepthSetup& s, int x0, int x1, int y) {
    const DepthStepper dz(s, x0, y);
    const uint32_t c0 = dz.code();
    ASSERT_EQ(c0, ref_code(s, x0, y));
    ASSERT_EQ(depth_code_at(s, x1, y), ref_code(s, x1, y));
    const bool constant = depth_code_at(s, x1, y) == c0;
    bool all_equal = true;
    for (int i = x0; i <= x1; ++i) all_equal = all_equal && ref_code(s, i, y) == c0;
    EXPECT_EQ(constant, all_equal) << "den 2^" << msb_index((u128)s.den) << " x " << x0 << ".." << x1;
    (constant ? one : several) += 1;
  };
  for (int k = 0; k < 3000; ++k) {
    DepthSetup s;
    const int db = 40 + (int)(rng() % 61);
    s.den = ((i128)1 << db) + (i128)(rng() >> 4);
    s.max_code = (1 << 24) - 1;
    const int n = 1 + (int)(rng() % 300), x0 = (int)(rng() % 500) - 100, y = (int)(rng() % 300);
    const i128 code0 = (i128)(rng() % (1u << 24));
    s.z.c = code0 * s.den + (i128)(rng() % (uint64_t)1e18) * (s.den >> 60 > 0 ? s.den >> 60 : 1);
    // 0 to ~3 code changes over the span, either direction.
    const int64_t changes = (int64_t)(rng() % 4);
    const i128 slope = changes == 0 ? 0 : (s.den * changes) / (i128)(n * (1 + (int)(rng() % 3)));
    s.z.dx = rng() % 2 ? slope : -slope;
    s.z.dy = (i128)(rng() >> 8);
    s.z.c -= (i128)x0 * s.z.dx + (i128)y * s.z.dy;  // the code near code0 at the span start
    check(s, x0, x0 + n - 1, y);
  }
  EXPECT_GT(one, 500u);
  EXPECT_GT(several, 500u);
  // Ties at the span's end: Z(x1)/den = c + ½ with c even (RNE keeps c) and odd (c + 1).
  for (int c : {1000, 1001, 0, 1}) {
    DepthSetup s;
    s.den = (i128)1 << 80;
    s.max_code = (1 << 24) - 1;
    const int n = 64;
    s.z.dx = s.den / (4 * (n - 1));                          // about ¼ code over the span
    s.z.c = (i128)c * s.den + s.den / 2 - (n - 1) * s.z.dx;  // from ≈ c + ¼ up to c + ½ exactly
    ASSERT_EQ(s.z.at(n - 1, 0), (i128)c * s.den + s.den / 2);
    check(s, 0, n - 1, 0);
    const bool constant = depth_code_at(s, n - 1, 0) == DepthStepper(s, 0, 0).code();
    EXPECT_EQ(constant, c % 2 == 0) << c;
  }
  // Clamps: both ends beyond max_code (or below 0) with different unclamped values.
  for (int side : {-1, 1}) {
    DepthSetup s;
    s.den = (i128)1 << 90;
    s.max_code = (1 << 24) - 1;
    s.z.c = side > 0 ? (s.max_code + 5) * s.den : -5 * s.den;
    s.z.dx = side * s.den;  // one code per pixel, away from the range
    check(s, 0, 40, 0);
    EXPECT_EQ(depth_code_at(s, 40, 0), side > 0 ? (uint32_t)s.max_code : 0u);
  }
}

TEST(FusedSpan, WideDepthSpansWithOneCodeOrSteppedEqualTheStagedPath) {
  // Nearly level planes: the depth plane's den is beyond int64 stepping, the code is one value
  // over some spans (no stepping) and changes inside others (the i128 stepper); both against
  // the staged stages, with 0 and 2 varyings, under two depth functions.
  FusedSpan::Counts total;
  for (float slope : {0.0f, 1e-7f, 3e-6f, 1e-4f})
    for (int nv : {0, 2})
      for (DepthFunc fn : {DepthFunc::Less, DepthFunc::GreaterEqual}) {
        DrawState st = viewport_state(nv);
        st.depth_func = fn;
        std::vector<ClipTriangle> tris = level_plane(nv, slope);
        for (const ClipTriangle& t : level_plane(nv, -slope)) tris.push_back(t);
        add(total, compare(Config{}, st, tris, "level plane slope " + std::to_string(slope)));
      }
  EXPECT_GT(total.spans_zconst, 100u);
  EXPECT_GT(total.spans_z128, 10u);
}

// The significands' rounding carry-outs inside the 64-bit-word segments, directed: D and the
// numerators set (on a real triangle's equations) to planes in the binade [2^100, 2^101) that
// step by 2^60 through 2^101 − 2^68 — the value whose top 32 bits round up to 2^32 (a tie
// rounding to even there: the kept part is odd) — and on to just below 2^101, so that D's and
// each numerator's normalisation carries out (d = 2^31, exponent + 1) on some pixels and not on
// the others; both signs of N. Every fragment against the staged stages, with and without the
// word segments.
TEST(FusedSpan, SignificandCarryOutsInTheWordSegmentsEqualTheStagedPath) {
  const int nv = 2;
  DrawState st = viewport_state(nv);
  st.depth_test = false;
  const Config cfg;
  std::vector<uint32_t> buf((size_t)kW * kH, 0);
  const DepthBufferView view{buf.data(), st.viewport_w, st.viewport_x, st.viewport_y};
  SetupStage setup(cfg, st, true);
  std::vector<SetupTriangle> pieces;
  RasterStats gs;
  geometry(cfg, st, grazing_plane(nv, 8.0f)[0], 0, pieces, gs);
  ASSERT_FALSE(pieces.empty());
  TriangleEquations eq;
  bool got_eq = false;
  setup.step(pieces[0], [&](const TriangleEquations& e) { eq = e, got_eq = true; });
  ASSERT_TRUE(got_eq);
  const i128 top = (i128)1 << 101, cut = top - ((i128)1 << 68), step = (i128)1 << 60;
  const int x0 = 10, y = 20;
  uint64_t frags = 0, bad = 0;
  FusedSpan::Counts counts;
  for (int variant = 0; variant < 4; ++variant) {
    Plane p;
    p.dx = step, p.dy = 0, p.i0 = x0, p.j0 = y;
    p.c = cut - (i128)(3 + variant) * step;  // the carry-out starts at pixel 3 + variant
    eq.interp.den = p;
    eq.interp.num[0] = p;
    eq.interp.num[0].c -= (i128)variant * step;  // a numerator whose carry-out starts later
    eq.interp.num[1] = p;
    eq.interp.num[1].c = -(cut - (i128)(5 - variant) * step), eq.interp.num[1].dx = -step;  // negative
    eq.interp.n = nv;
    Span sp;
    sp.y = y, sp.x0 = x0, sp.x1 = x0 + 15;
    ASSERT_LT(eq.interp.den.at(sp.x1, y), top);  // one binade over the span
    std::vector<Fragment> want;
    InterpStage interp(cfg, st, true);
    DepthStage depth(cfg, st, view);
    DivideStage divide(cfg, st, true);
    interp.step(eq, sp, [&](const PlaneSample& ps) {
      depth.step(ps, [&](const PlaneSample& q) { divide.step(q, [&](const Fragment& f) { want.push_back(f); }); });
    });
    ASSERT_EQ(want.size(), 16u);
    for (bool high : {true, false}) {
      FusedSpan fused(cfg, st, view, true);
      fused.set_high_words(high);
      std::vector<Fragment> got;
      fused.run(eq, sp, [&](const Fragment& f) { got.push_back(f); });
      ASSERT_EQ(got.size(), want.size());
      for (size_t i = 0; i < want.size(); ++i) bad += same_fragment(want[i], got[i], nv) ? 0 : 1;
      frags += got.size();
      if (high) add(counts, fused.counts());
    }
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(frags, 4u * 2u * 16u);
  EXPECT_GE(counts.segments_high, 4u);  // the word segments ran these spans
}

TEST(FusedSpan, SpansInAnyOrderWithinATriangleEqualTheStagedPath) {
  // The span-start cursor (FusedSpan::run after the first span of a triangle) moves every
  // value from the last span start: here it moves by several rows, down, left and right, to the
  // same start and to a later part of a span; the triangles have many rows (the big ones of
  // random_tris, the grazing planes), sums leave their binade and sign between rows, tiny w
  // gives depth planes the int64 cursor refuses. Every fragment and buffer word as the staged
  // path in the same order, and every counter of the cursor reached.
  FusedSpan::Counts total, small;
  for (int nv : {0, 1, 2, 3}) {
    DrawState st = viewport_state(nv);
    for (bool scramble : {false, true}) {
      const std::string what = "nv " + std::to_string(nv) + (scramble ? " scrambled" : "");
      add(small, compare(Config{}, st, small_tris(290 + nv, 400, nv), what + " small", scramble));
      add(total, compare(Config{}, st, random_tris(300 + nv, 60, nv), what, scramble));
      add(total, compare(Config{}, st, grazing_plane(nv, 300.0f), what + " plane", scramble));
      std::vector<ClipTriangle> tiny = random_tris(310 + nv, 30, nv);
      for (ClipTriangle& t : tiny)
        for (auto& v : t.v)
          for (int c = 0; c < 4; ++c) v.pos[c] *= 1e-30f;
      add(total, compare(Config{}, st, tiny, what + " tiny w", scramble));
      add(total, compare(widths_config(28, 30, 20), st, random_tris(320 + nv, 30, nv), what + " widths", scramble));
    }
  }
  std::printf("small triangles: %llu spans, %llu from the int64 cursor, %llu sums fixed per triangle of %llu starts\n",
              (unsigned long long)small.spans, (unsigned long long)small.spans_z64, (unsigned long long)small.sums_fixed,
              (unsigned long long)small.cursor_starts);
  // The bunny's case: small triangles take the int64 cursor and keep their binades.
  EXPECT_GT(small.spans_z64, small.spans / 2);
  EXPECT_GT(small.sums_fixed, 200u);
  EXPECT_GT(small.cursor_moves, small.cursor_starts);
  add(total, small);
  std::printf("cursor: %llu starts, %llu moves, %llu spans int64 from the cursor, %llu depth moves divided, %llu "
              "cursors lost, %llu sums re-armed (%llu with the other sign), %llu sums fixed per triangle\n",
              (unsigned long long)total.cursor_starts, (unsigned long long)total.cursor_moves,
              (unsigned long long)total.spans_z64, (unsigned long long)total.z_moves_divided,
              (unsigned long long)total.z_cursor_lost, (unsigned long long)total.rearmed_moves,
              (unsigned long long)total.rearmed_sign_moves, (unsigned long long)total.sums_fixed);
  EXPECT_GT(total.cursor_starts, 1000u);
  EXPECT_GT(total.cursor_moves, 10 * total.cursor_starts);
  EXPECT_GT(total.spans_z64, 1000u);
  EXPECT_GT(total.spans_z128, 0u);
  EXPECT_GT(total.spans_zconst, 0u);
  EXPECT_GT(total.z_moves_divided, 100u);
  EXPECT_GT(total.z_cursor_lost, 10u);
  EXPECT_GT(total.rearmed_moves, 100u);
  EXPECT_GT(total.rearmed_sign_moves, 10u);
  EXPECT_GT(total.spans_direct, 1000u);  // between them: the sums synced lazily at a long span
  EXPECT_GT(total.sums_fixed, 100u);
  EXPECT_GT(total.segments, total.spans);
  EXPECT_GT(total.sign_changes, 0u);
}

TEST(FusedSpan, ARewrittenTriangleRecordStartsItsCursorWithoutBegin) {
  // SetupStage writes every triangle into one TriangleEquations object. Without begin() per
  // triangle the span-start cursor used to move from the last triangle's state (the same object
  // address); run() now compares the record's serial too. Every fragment and buffer word as the
  // staged path, each triangle's first span counted as a cursor start.
  for (int nv : {0, 1, 2}) {
    const DrawState st = viewport_state(nv);
    const std::string what = "nv " + std::to_string(nv) + " without begin";
    const std::vector<ClipTriangle> tris = small_tris(330 + nv, 400, nv);
    const FusedSpan::Counts with = compare(Config{}, st, tris, what + " (begin)");
    const FusedSpan::Counts without = compare(Config{}, st, tris, what, false, false);
    EXPECT_EQ(without.cursor_starts, with.cursor_starts) << what;
    EXPECT_GT(without.cursor_starts, 100u) << what;
    EXPECT_GT(without.cursor_moves, without.cursor_starts) << what;
  }
  // Numbered apart: two stages, and one stage's successive triangles.
  Config cfg;
  const DrawState st = viewport_state(1);
  SetupStage a(cfg, st), b(cfg, st);
  RasterStats gs;
  std::vector<SetupTriangle> pieces;
  for (const ClipTriangle& t : small_tris(340, 20, 1)) geometry(cfg, st, t, 0, pieces, gs);
  ASSERT_GE(pieces.size(), 2u);
  uint64_t sa0 = 0, sa1 = 0, sb0 = 0;
  a.step(pieces[0], [&](const TriangleEquations& eq) { sa0 = eq.serial; });
  a.step(pieces[1], [&](const TriangleEquations& eq) { sa1 = eq.serial; });
  b.step(pieces[0], [&](const TriangleEquations& eq) { sb0 = eq.serial; });
  EXPECT_NE(sa0, 0u);
  EXPECT_NE(sa0, sa1);
  EXPECT_NE(sa0, sb0);
  EXPECT_NE(sa1, sb0);
}

namespace {

// The state arm(v) gives, field by field (norm only where the sum is not zero).
bool same_sum(const FusedSpan::Sum& a, const FusedSpan::Sum& b) {
  bool same = a.mag == b.mag && a.neg == b.neg && a.step == b.step && a.lo == b.lo && a.width == b.width;
  if (a.mag != 0)
    same = same && a.norm.bits == b.norm.bits && a.norm.m == b.norm.m && a.norm.shift == b.norm.shift &&
           a.norm.bias == b.norm.bias;
  return same;
}
int msb_or_minus(i128 v) { return v == 0 ? -1 : msb_index(v < 0 ? (u128)0 - (u128)v : (u128)v); }

}  // namespace

TEST(SpanSum, SetGivesArmsStateAndKeepsTheNormaliserExactlyWithinTheBinade) {
  // Exhaustive on small values (every pair in [−600, 600], 4-bit significands), then values of
  // every binade up to 2^126 at its edges: set(v) after arm(u) leaves the state arm(v) gives,
  // and answers "kept" exactly when u and v share sign and msb (or are both 0).
  auto check = [](i128 u, i128 v, int bits, i128 dx) {
    FusedSpan::Sum a, b;
    a.bits = b.bits = bits;
    a.dx = b.dx = dx;
    a.arm(u);
    const bool kept = a.set(v);
    b.arm(v);
    const bool want_kept = (u < 0) == (v < 0) && msb_or_minus(u) == msb_or_minus(v);
    return same_sum(a, b) && kept == want_kept;
  };
  uint64_t bad = 0, n = 0;
  for (int u = -600; u <= 600; ++u)
    for (int v = -600; v <= 600; ++v, ++n) bad += check(u, v, 4, (u + v) % 7 - 3) ? 0 : 1;
  std::mt19937_64 g(5);
  for (int k = 0; k < 1000000; ++k, ++n) {
    const int e = (int)(g() % 126);
    auto edge = [&](int ee) {
      const i128 p = (i128)1 << ee;
      const i128 off = (i128)(g() % 5) - 2;  // 2^e − 2 … 2^e + 2
      i128 x = p + off;
      if (x < 0) x = 0;
      return g() % 2 ? -x : x;
    };
    const i128 u = edge(e), v = g() % 3 == 0 ? edge(e) : edge((int)(g() % 126));
    bad += check(u, v, 1 + (int)(g() % 40), (i128)(g() >> 1)) ? 0 : 1;
  }
  EXPECT_EQ(bad, 0u) << "of " << n;
}

TEST(SpanSum, TheRectangleTestHoldsExactlyWhenEveryPixelIsInTheBinade) {
  // start()'s `fixed`: true exactly when every pixel of the candidate rectangle has the start
  // value's sign and binade (brute force over the rectangle). Exhaustive on small planes (value
  // at the start −40 … 40, steps −6 … 6, every start pixel of a 4 × 3 rectangle), then random
  // planes of 2^40–2^110 near binade edges; where fixed, move() to any pixel leaves the state
  // arm(the plane's value there) gives.
  uint64_t bad = 0, fixed = 0, not_fixed = 0, at_corner = 0;
  std::mt19937_64 g(9);
  auto check = [&](const Plane& p, const TriSetup& e, int a, int b, int bits) {
    at_corner += p.i0 == e.x0 && p.j0 == e.y0 ? 1 : 0;  // start() takes p.c as the corner's value
    FusedSpan::Sum s;
    FusedSpan::Counts k;
    Span sp;
    sp.y = b, sp.x0 = a, sp.x1 = a;
    u128 v;
    s.start(p, sp, bits, v, e, true);
    const i128 v0 = p.at(a, b);
    bool all = true;
    for (int i = e.x0; i <= e.x1; ++i)
      for (int j = e.y0; j <= e.y1; ++j) {
        const i128 w = p.at(i, j);
        all = all && (w < 0) == (v0 < 0) && msb_or_minus(w) == msb_or_minus(v0);
      }
    if (s.fixed != all) ++bad;
    (s.fixed ? fixed : not_fixed) += 1;
    // Moves from the start through every pixel, in an order with steps of every kind (the
    // common ones: next row and x by −1, 0, +1; others) (fixed: no test; else set()).
    std::vector<std::pair<int, int>> order;
    for (int j = e.y0; j <= e.y1; ++j)
      for (int i = e.x0; i <= e.x1; ++i) order.emplace_back((j - e.y0) % 2 ? e.x1 - (i - e.x0) : i, j);
    for (int j = e.y0; j <= e.y1; ++j)
      for (int i = e.x0; i <= e.x1; ++i) order.emplace_back(i, j);
    std::shuffle(order.begin() + order.size() / 2, order.end(), g);
    int ci = a, cj = b;
    for (const auto& [i, j] : order) {
        const int64_t ddx = i - ci, ddy = j - cj;
        const int sel = ddy == 1 && ddx >= -1 && ddx <= 1 ? (int)ddx + 1 : -1;
        s.move(p, sel, ddx, ddy, v, k);
        ci = i, cj = j;
        FusedSpan::Sum want;
        want.bits = bits;
        want.dx = p.dx;
        want.arm(p.at(i, j));
        if (!same_sum(s, want) || (i128)v != p.at(i, j)) ++bad;
      }
  };
  TriSetup e;
  e.x0 = 0, e.x1 = 3, e.y0 = 0, e.y1 = 2;
  for (int c = -40; c <= 40; ++c)
    for (int dx = -6; dx <= 6; ++dx)
      for (int dy = -6; dy <= 6; ++dy)
        for (int a = e.x0; a <= e.x1; ++a)
          for (int b = e.y0; b <= e.y1; ++b) {
            Plane p;
            p.dx = dx, p.dy = dy, p.i0 = a, p.j0 = b, p.c = c;
            check(p, e, a, b, 4);
          }
  for (int k = 0; k < 200000; ++k) {
    TriSetup r;
    r.x0 = (int)(g() % 2000) - 1000, r.y0 = (int)(g() % 2000) - 1000;
    r.x1 = r.x0 + (int)(g() % 6), r.y1 = r.y0 + (int)(g() % 6);
    const int a = r.x0 + (int)(g() % (uint64_t)(r.x1 - r.x0 + 1)), b = r.y0 + (int)(g() % (uint64_t)(r.y1 - r.y0 + 1));
    const int eb = 40 + (int)(g() % 70), sb = eb - 1 - (int)(g() % 20);
    Plane p;
    p.i0 = a, p.j0 = b;
    p.c = ((i128)1 << eb) + (i128)(g() % 7) - 3 - (i128)(g() % 4) * ((i128)1 << sb);  // near a binade edge
    if (g() % 2) p.c = -p.c;
    p.dx = ((i128)(g() >> 1) << (sb - 62 > 0 ? sb - 62 : 0)) * (g() % 2 ? 1 : -1);
    p.dy = ((i128)(g() >> 1) << (sb - 62 > 0 ? sb - 62 : 0)) * (g() % 2 ? 1 : -1);
    check(p, r, a, b, 32);
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(fixed, 10000u);
  EXPECT_GT(not_fixed, 10000u);
  EXPECT_GT(at_corner, 10000u);                       // planes anchored at the rectangle's corner
  EXPECT_GT(fixed + not_fixed - at_corner, 10000u);  // and elsewhere (Plane::at)
}
