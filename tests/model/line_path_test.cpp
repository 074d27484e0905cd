// The line path of the unit (model/unit/line_chain.hpp, docs/lines.md "The line path") against
// independent references:
//   geometry  — a GMP segment clipper written from the specification (the same planes, order and
//               inside rules as the triangle clipper, each new component the exact rational
//               intersection rounded once) and georef::ref_project (stage 3 + 4 per vertex); every
//               field of the snapped segment must agree exactly;
//   coverage  — line_ref.hpp's exact rule references on the reference's snapped endpoints,
//               restricted to viewport ∩ scissor: the same pixel set;
//   depth     — GL's parameter t = clamp((c − p_a)·(p_b − p_a) / |p_b − p_a|², 0, 1) in rationals
//               from the reference's positions, code = RNE(((1 − t)·zq_a + t·zq_b) / 2^zs): equal;
//   varyings  — ((1 − t)·vw_a + t·vw_b) / ((1 − t)·rw_a + t·rw_b) exactly; the model within the
//               bound of its documented roundings (block alignment, divider normalisation, ½ ulp);
//   statistics — every segment drawn, culled or rejected exactly once.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>

#include <algorithm>
#include <cstdio>
#include <random>
#include <type_traits>

#include "geom_ref.hpp"
#include "line_ref.hpp"
#include "model/unit/line_chain.hpp"
#include "model/unit/raster_unit.hpp"

using namespace fxr;
using namespace georef;

namespace {

int ilog2q(const mpq_class& x) {  // floor(log2 |x|), x ≠ 0
  const mpq_class a = abs(x);
  int e = (int)mpz_sizeinbase(a.get_num_mpz_t(), 2) - (int)mpz_sizeinbase(a.get_den_mpz_t(), 2);
  if (a < pow2(e)) --e;
  if (a >= pow2(e + 1)) ++e;
  return e;
}

// Records the snapped segment leaving stage 4 and every fragment.
struct Recorder {
  std::vector<SetupLine> setup;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same_v<S, LineViewportStage>) setup.push_back(o);
  }
};
struct Collect final : FragmentSink {
  std::vector<Fragment> f;
  void emit(const Fragment& x) override { f.push_back(x); }
};

enum class RefOutcome { Drawn, Culled, RejectedNaN, RejectedInf, RejectedRange };
struct RefLine {
  RefOutcome outcome = RefOutcome::Drawn;
  RSetup v[2];
  int created = 0;
};

// The varying rule of docs/pipeline.md stage 1, from its statement: NaN → +0, ±Inf → ±FLT_MAX.
float ref_varying(float f) {
  if (std::isnan(f)) return 0.0f;
  if (std::isinf(f)) return std::copysign(FLT_MAX, f);
  return f;
}

// The segment clipper from its specification, on rationals.
RefLine ref_line(const Config& cfg, const DrawState& st, const ClipLine& l) {
  RefLine r;
  const int nv = st.num_varyings;
  bool nan = false, inf = false;
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 4; ++c) nan |= is_nan_f(l.v[i].pos[c]), inf |= is_inf_f(l.v[i].pos[c]);
  }
  if (nan) return r.outcome = RefOutcome::RejectedNaN, r;
  if (inf) return r.outcome = RefOutcome::RejectedInf, r;
  const RBand b = ref_band(cfg.raster, st);
  RVtx v[2];
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 4; ++c) v[i].p[c] = q_of_float(l.v[i].pos[c]);
    for (int k = 0; k < nv; ++k) v[i].v[k] = q_of_float(ref_varying(l.v[i].var[k]));
  }
  for (int p = 0; p < 7; ++p)
    if (sgn(ref_dist(b, p, v[0])) < 0 && sgn(ref_dist(b, p, v[1])) < 0) return r.outcome = RefOutcome::Culled, r;
  for (int p = 0; p < 7; ++p) {
    const mpq_class d0 = ref_dist(b, p, v[0]), d1 = ref_dist(b, p, v[1]);
    if (sgn(d0) >= 0 && sgn(d1) >= 0) continue;
    if (sgn(d0) < 0 && sgn(d1) < 0) return r.outcome = RefOutcome::Culled, r;
    const int o = sgn(d0) < 0 ? 0 : 1;
    if (sgn(o == 0 ? d1 : d0) == 0) {
      v[o] = v[1 - o];
      continue;
    }
    const mpq_class t = d0 / (d0 - d1);
    RVtx x;
    for (int c = 0; c < 4; ++c)
      x.p[c] = ref_round_clip(v[0].p[c] + t * (v[1].p[c] - v[0].p[c]),
                              c == 3 ? cfg.recip.in_sig_bits : cfg.raster.clip_sig_bits);
    for (int k = 0; k < nv; ++k) x.v[k] = ref_round_clip(v[0].v[k] + t * (v[1].v[k] - v[0].v[k]), cfg.raster.clip_sig_bits);
    ref_set_attr_w(x, v[0], v[1], t, cfg);
    v[o] = x;
    ++r.created;
  }
  const long lim = 1L << (cfg.raster.window_int_bits + cfg.raster.subpixel_bits - 1);
  for (int i = 0; i < 2; ++i) {
    r.v[i] = ref_project(cfg, st, v[i]);
    if (r.v[i].x <= -lim || r.v[i].x >= lim || r.v[i].y <= -lim || r.v[i].y >= lim)
      return r.outcome = RefOutcome::RejectedRange, r;
  }
  return r;
}

// Half a block ulp when v[k] is not a multiple of the block ulp of the pair (align_block).
mpq_class align_err2(const FxFloat& a, const FxFloat& b, int P, int k) {
  int lead = INT32_MIN;
  for (const FxFloat* f : {&a, &b})
    if (f->sig) lead = std::max(lead, f->exp + 63 - __builtin_clzll(f->sig));
  const FxFloat& x = k == 0 ? a : b;
  if (lead == INT32_MIN || x.sig == 0) return 0;
  const int eb = lead - (P - 1);
  const mpq_class q = q_of(x) / pow2(eb);
  return q.get_den() == 1 ? mpq_class(0) : mpq_class(pow2(eb) / 2);
}

struct Tally {
  long segments = 0, drawn = 0, clipped = 0, culled = 0, fragments = 0, values = 0;
  long setup_diffs = 0, pixel_diffs = 0, depth_diffs = 0, over_bound = 0;
  double max_ulp = 0;
};

float rnd_f(std::mt19937_64& g, double lo, double hi) {
  return (float)std::uniform_real_distribution<double>(lo, hi)(g);
}

// A clip-space vertex: w in (0.2, 4) (sometimes ≤ 0 or tiny), x, y mostly inside the viewport's
// NDC range, sometimes far outside (guard band), z sometimes outside [0, w].
ClipVertex rnd_vertex(std::mt19937_64& g, int nv) {
  ClipVertex v;
  const int kind = (int)(g() % 8);
  const float w = kind == 0 ? rnd_f(g, -1.0, 0.3) : rnd_f(g, 0.2, 4.0);
  const double s = kind == 1 ? 3000.0 : kind == 2 ? 1.6 : 1.1;
  v.pos[0] = rnd_f(g, -s, s) * w;
  v.pos[1] = rnd_f(g, -s, s) * w;
  v.pos[2] = kind == 3 ? rnd_f(g, -1.0, 2.0) * w : rnd_f(g, 0.0, 1.0) * w;
  v.pos[3] = w;
  for (int k = 0; k < nv; ++k) v.var[k] = rnd_f(g, -2.0, 3.0);
  return v;
}

void check_lines(const Config& cfg, const DrawState& st0, const std::vector<ClipLine>& lines, Tally& t) {
  DrawState st = st0;
  st.depth_test = false;  // every fragment comes out
  const int nv = st.num_varyings;
  const RasterConfig& rc = cfg.raster;
  const bool attr = attr_planes(rc);
  ASSERT_EQ(line_param_frac_bits(rc), attr ? rc.attr_subpixel_bits : grid_bits(rc))
      << "this test assumes no dropped parameter bits";
  const PixelRect dr = draw_rect(st);
  const int64_t M = (1LL << rc.depth_bits()) - 1;
  const int zs = attr ? rc.z_frac_bits - rc.depth_bits() : rc.z_frac_bits;
  const int A = attr ? rc.attr_subpixel_bits : rc.subpixel_bits;
  const int P = rc.interp_block_bits, nb = cfg.div.num_bits, db = cfg.div.den_bits;
  for (const ClipLine& l : lines) {
    ++t.segments;
    FrameOutput f;
    frame_begin(cfg, st, f);
    Recorder rec;
    Collect col;
    LineChain<Recorder> chain(cfg, st, f, &col, rec);
    chain.draw(l, 3);
    const LineStats& s = f.stats.lines;
    ASSERT_EQ(s.in, 1u);
    ASSERT_EQ(s.accounted(), 1u);
    const RefLine r = ref_line(cfg, st, l);
    t.clipped += (long)s.clipped;
    if (r.outcome == RefOutcome::RejectedNaN) { EXPECT_EQ(s.rejected_nan, 1u); continue; }
    if (r.outcome == RefOutcome::RejectedInf) { EXPECT_EQ(s.rejected_inf, 1u); continue; }
    if (r.outcome == RefOutcome::RejectedRange) { EXPECT_EQ(s.rejected_range, 1u); continue; }
    if (r.outcome == RefOutcome::Culled) {
      EXPECT_EQ(s.culled_outside, 1u);
      ++t.culled;
      continue;
    }
    EXPECT_EQ(s.clip_vertices_created, (uint64_t)r.created);
    ASSERT_EQ(rec.setup.size(), 1u);
    const SetupLine& m = rec.setup[0];
    const int d = diff_count(m.v[0], r.v[0], nv) + diff_count(m.v[1], r.v[1], nv);
    t.setup_diffs += d > 0;
    if (d) {
      ADD_FAILURE() << "snapped segment differs from the reference in " << d << " fields";
      continue;
    }
    // Coverage.
    const LineIn seg{r.v[0].x.get_si(), r.v[0].y.get_si(), r.v[1].x.get_si(), r.v[1].y.get_si()};
    std::vector<LinePixel> exp;
    for (const LinePixel& p : line_ref::reference(rc, cfg.line, seg))
      if (p.x >= dr.x0 && p.x <= dr.x1 && p.y >= dr.y0 && p.y <= dr.y1) exp.push_back(p);
    std::vector<LinePixel> got;
    for (const Fragment& fr : col.f) got.push_back({fr.x, fr.y});
    std::sort(got.begin(), got.end());
    t.pixel_diffs += got != exp;
    EXPECT_EQ(got.size(), exp.size());
    if (got != exp) continue;
    EXPECT_EQ(s.drawn + s.culled_no_pixels, 1u);
    EXPECT_EQ(s.drawn, exp.empty() ? 0u : 1u);
    t.drawn += !exp.empty();
    // Parameter t and the values.
    const mpq_class ax = mpq_class(r.v[0].ax) / pow2(A), ay = mpq_class(r.v[0].ay) / pow2(A);
    const mpq_class bx = mpq_class(r.v[1].ax) / pow2(A), by = mpq_class(r.v[1].ay) / pow2(A);
    const mpq_class L2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
    mpq_class zq[2];
    for (int i = 0; i < 2; ++i)
      zq[i] = attr ? mpq_class(rne_int(mpq_class(r.v[i].z * M) / pow2(rc.depth_bits()))) : mpq_class(r.v[i].z * M);
    for (const Fragment& fr : col.f) {
      ++t.fragments;
      EXPECT_EQ(fr.prim, 3u);
      const mpq_class cx = mpq_class(2 * fr.x + 1, 2), cy = mpq_class(2 * fr.y + 1, 2);
      mpq_class tt = L2 == 0 ? mpq_class(0) : mpq_class(((cx - ax) * (bx - ax) + (cy - ay) * (by - ay)) / L2);
      if (tt < 0) tt = 0;
      if (tt > 1) tt = 1;
      const mpq_class w0 = 1 - tt, w1 = tt;
      mpz_class code = rne_int((w0 * zq[0] + w1 * zq[1]) / pow2(zs));
      if (code < 0) code = 0;
      if (code > M) code = M;
      if (mpz_class((unsigned long)fr.depth) != code) {
        if (++t.depth_diffs <= 5)
          ADD_FAILURE() << "depth at (" << fr.x << "," << fr.y << "): " << fr.depth << " expected " << code.get_str();
      }
      const bool affine = st.interp == InterpMode::Affine;
      const FxFloat& ra = m.v[0].rw;
      const FxFloat& rb = m.v[1].rw;
      const mpq_class R0 = affine ? mpq_class(1) : r.v[0].rw, R1 = affine ? mpq_class(1) : r.v[1].rw;
      const mpq_class D = w0 * R0 + w1 * R1;
      const mpq_class aD = affine ? mpq_class(0) : mpq_class(w0 * align_err2(ra, rb, P, 0) + w1 * align_err2(ra, rb, P, 1));
      for (int k = 0; k < nv; ++k) {
        ++t.values;
        const mpq_class N = w0 * r.v[0].vw[k] + w1 * r.v[1].vw[k];
        const mpq_class aN = w0 * align_err2(m.v[0].vw[k], m.v[1].vw[k], P, 0) + w1 * align_err2(m.v[0].vw[k], m.v[1].vw[k], P, 1);
        const mpq_class exact = N / D, got_v = q_of(fr.var[k]);
        const mpq_class an = abs(N);
        const mpq_class hi = (an + aN) * (1 + pow2(-nb)) / ((D - aD) * (1 - pow2(-db)));
        mpq_class lo_n = an - aN;
        if (lo_n < 0) lo_n = 0;
        const mpq_class lo = lo_n * (1 - pow2(-nb)) / ((D + aD) * (1 + pow2(-db)));
        const mpq_class dev = std::max(mpq_class(hi - an / D), mpq_class(an / D - lo));
        const mpq_class ulp_got = fr.var[k].sig ? pow2(fr.var[k].exp) : mpq_class(0);
        const mpq_class err = abs(got_v - exact);
        if (err > ulp_got / 2 + dev && ++t.over_bound <= 5)
          ADD_FAILURE() << "varying " << k << " at (" << fr.x << "," << fr.y << "): got " << got_v.get_d() << " exact "
                        << exact.get_d();
        if (exact != 0)
          t.max_ulp = std::max(t.max_ulp, mpq_class(err / pow2(ilog2q(exact) - (rc.varying_out_sig_bits - 1))).get_d());
      }
    }
  }
}

std::vector<ClipLine> random_lines(uint64_t seed, int n, int nv) {
  std::mt19937_64 g(seed);
  std::vector<ClipLine> v(n);
  for (auto& l : v) {
    l.v[0] = rnd_vertex(g, nv);
    l.v[1] = (g() % 6 == 0) ? l.v[0] : rnd_vertex(g, nv);  // some zero-length ones
    if (g() % 5 == 0) {  // short: a few pixels at most
      for (int c = 0; c < 4; ++c) l.v[1].pos[c] = l.v[0].pos[c] * (float)(1.0 + 0.02 * ((double)(g() % 100) / 100.0 - 0.5));
    }
  }
  return v;
}

void run_config(const Config& cfg, InterpMode mode, const char* what, uint64_t seed) {
  DrawState st = georef::state(96, 64, 8, -4, 2);
  st.scissor_x = 10, st.scissor_y = 0, st.scissor_w = 80, st.scissor_h = 50;
  st.interp = mode;
  Tally t;
  check_lines(cfg, st, random_lines(seed, 1500, 2), t);
  std::printf("%s: %ld segments (%ld clipped, %ld culled, %ld drawn), %ld fragments, %ld varying values; "
              "setup diffs %ld, pixel-set diffs %ld, depth diffs %ld, over bound %ld; max %.3f ulp vs exact\n",
              what, t.segments, t.clipped, t.culled, t.drawn, t.fragments, t.values, t.setup_diffs, t.pixel_diffs,
              t.depth_diffs, t.over_bound, t.max_ulp);
  EXPECT_GT(t.drawn, 300);
  EXPECT_GT(t.clipped, 100);
  EXPECT_EQ(t.setup_diffs, 0);
  EXPECT_EQ(t.pixel_diffs, 0);
  EXPECT_EQ(t.depth_diffs, 0);
  EXPECT_EQ(t.over_bound, 0);
}

}  // namespace

TEST(LinePath, DefaultConfigMatchesExactReferencePerspective) { run_config(Config{}, InterpMode::Perspective, "default", 11); }

TEST(LinePath, DefaultConfigMatchesExactReferenceAffine) { run_config(Config{}, InterpMode::Affine, "affine", 12); }

TEST(LinePath, SnappedPlanesDiamondExitMatchExactReference) {
  Config cfg;
  cfg.raster.attr_subpixel_bits = cfg.raster.subpixel_bits;  // planes from the snapped positions
  cfg.line.rule = LineRule::DiamondExit;
  run_config(cfg, InterpMode::Perspective, "snapped planes, diamond exit", 13);
}

TEST(LinePath, ClosedEndpointsCoarseGrid) {
  Config cfg;
  cfg.raster.subpixel_bits = 4;
  cfg.line.endpoints = LineEndpoints::Closed;
  run_config(cfg, InterpMode::Perspective, "S=4, closed", 14);
}

// Midpoint rule: both directions of a segment give the same fragments, values included
// (t from p_b is exactly 1 − t from p_a; the clipper is direction-independent).
TEST(LinePath, ReversedSegmentGivesIdenticalFragments) {
  const Config cfg;
  DrawState st = georef::state(96, 64, 0, 0, 2);
  st.depth_test = false;
  long compared = 0;
  for (const ClipLine& l : random_lines(21, 800, 2)) {
    ClipLine rv;
    rv.v[0] = l.v[1], rv.v[1] = l.v[0];
    const FrameOutput a = run_raster_unit(cfg, st, {}, st, {l});
    const FrameOutput b = run_raster_unit(cfg, st, {}, st, {rv});
    auto key = [](std::vector<Fragment> v) {
      std::sort(v.begin(), v.end(), [](const Fragment& p, const Fragment& q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
      return v;
    };
    const auto fa = key(a.fragments.to_vector()), fb = key(b.fragments.to_vector());
    ASSERT_EQ(fa.size(), fb.size());
    for (size_t i = 0; i < fa.size(); ++i) {
      ++compared;
      EXPECT_EQ(fa[i].x, fb[i].x);
      EXPECT_EQ(fa[i].y, fb[i].y);
      EXPECT_EQ(fa[i].depth, fb[i].depth);
      for (int k = 0; k < 2; ++k) EXPECT_TRUE(fa[i].var[k].neg == fb[i].var[k].neg && fa[i].var[k].sig == fb[i].var[k].sig && fa[i].var[k].exp == fb[i].var[k].exp) << "varying " << k;
    }
  }
  EXPECT_GT(compared, 1000);
}

// Lines share the frame's depth buffer with the triangles drawn before them.
TEST(LinePath, LinesAreDepthTestedAgainstTriangles) {
  const Config cfg;
  DrawState st = georef::state(32, 32, 0, 0, 0);
  ClipTriangle near_quad[2];
  const float q[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < 3; ++i) {
      ClipVertex& v = near_quad[t].v[i];
      v.pos[0] = q[idx[t][i]][0], v.pos[1] = q[idx[t][i]][1], v.pos[2] = 0.25f, v.pos[3] = 1;
    }
  ClipLine front, behind;
  for (int i = 0; i < 2; ++i) {
    front.v[i].pos[0] = behind.v[i].pos[0] = i ? 0.8f : -0.8f;
    front.v[i].pos[1] = behind.v[i].pos[1] = 0.1f;
    front.v[i].pos[2] = 0.125f, behind.v[i].pos[2] = 0.5f;
  }
  const FrameOutput f = run_raster_unit(cfg, st, {near_quad[0], near_quad[1]}, st, {front, behind});
  EXPECT_EQ(f.stats.prims_in, 2u);
  EXPECT_EQ(f.stats.lines.in, 2u);
  EXPECT_EQ(f.stats.lines.drawn, 2u);
  uint64_t front_frags = 0, behind_frags = 0;
  for (const Fragment& fr : f.fragments) front_frags += fr.prim == 2, behind_frags += fr.prim == 3;
  EXPECT_EQ(front_frags, f.stats.lines.fragments_generated / 2);  // 26 pixels each, same columns
  EXPECT_GT(front_frags, 20u);
  EXPECT_EQ(behind_frags, 0u);
}

// The varying rule of stage 1 on segments: a NaN / ±Inf varying is replaced (NaN → +0, ±Inf →
// ±FLT_MAX) and the segment is drawn as the reference draws it with those values; a NaN / Inf
// position still rejects it. Counted in lines.varying_nonfinite.
TEST(LinePath, NonFiniteVaryingsAreReplacedNotRejected) {
  DrawState st = georef::state(96, 64, 8, -4, 2);
  std::vector<ClipLine> lines = random_lines(21, 300, 2);
  const float kNaN = std::numeric_limits<float>::quiet_NaN(), kInf = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < lines.size(); ++i) {
    lines[i].v[i % 2].var[0] = i % 3 == 0 ? kNaN : (i % 3 == 1 ? kInf : -kInf);
  }
  Tally t;
  check_lines(Config{}, st, lines, t);
  EXPECT_GT(t.drawn, 50);
  EXPECT_EQ(t.setup_diffs, 0);
  EXPECT_EQ(t.pixel_diffs, 0);
  EXPECT_EQ(t.depth_diffs, 0);
  EXPECT_EQ(t.over_bound, 0);
  // Counted once per segment that reached the clipper; a NaN position still rejects.
  const Config cfg;
  FrameOutput f;
  frame_begin(cfg, st, f);
  NoTaps taps;
  LineChain<NoTaps> c2(cfg, st, f, nullptr, taps);
  for (uint32_t i = 0; i < lines.size(); ++i) c2.draw(lines[i], i);
  EXPECT_EQ(f.stats.lines.varying_nonfinite, lines.size());
  EXPECT_EQ(f.stats.lines.rejected_nan + f.stats.lines.rejected_inf, 0u);
  ClipLine bad = lines[0];
  bad.v[1].pos[0] = kNaN;
  c2.draw(bad, 0);
  EXPECT_EQ(f.stats.lines.rejected_nan, 1u);
}
