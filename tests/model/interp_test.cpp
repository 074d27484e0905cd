// Stages 7 and 9 (interpolators and divider): perspective-correct varyings against the exact
// rational value from the SAME quantised per-vertex inputs (GMP), with the error bound derived
// in docs/pipeline.md (stage 9) asserted per fragment, and against the true value from the
// unquantised vertex data; affine mode against its own exact value and the prediction of docs/references.md#seed-000-wrong-image.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "model/stages/interp.hpp"
#include "raster_ref.hpp"

using namespace fxr;
using namespace fxr::ref;

namespace {

int64_t rnd(std::mt19937_64& g, int64_t lo, int64_t hi) { return lo + (int64_t)(g() % (uint64_t)(hi - lo + 1)); }
double urand(std::mt19937_64& g) { return (double)(g() >> 11) * 0x1.0p-53; }

// The 1/w significand the test assumes the reciprocal unit delivers (correctly rounded here).
constexpr int kTestRwBits = 24;

struct VIn {
  int64_t x = 0, y = 0;  // subpixel units
  double w = 1;
  double v[kMaxVaryings] = {};
};

// Quantised setup triangle: rw = RNE(1/w), vw = RNE(v·rw) (perspective) or RNE(v) (affine).
SetupTriangle quantise(const Config& cfg, const VIn in[3], int nv, bool affine) {
  SetupTriangle t;
  for (int k = 0; k < 3; ++k) {
    t.v[k].x = in[k].x;
    t.v[k].y = in[k].y;
    t.v[k].z = 0;
    t.v[k].rw = fx_round(mpq_class(1) / to_mpq(in[k].w), kTestRwBits);
    for (int m = 0; m < nv; ++m)
      t.v[k].vw[m] = fx_round(affine ? to_mpq(in[k].v[m]) : to_mpq(in[k].v[m]) * to_mpq(t.v[k].rw),
                              cfg.raster.varying_sig_bits);
  }
  return t;
}

struct Err {
  long frags = 0, values = 0;
  double max_ulp = 0;          // |model − exact(same inputs)| in ulps of the exact value
  double max_excess = 0;       // max (error − ½ ulp(model)) / ulp: the part beyond the final RNE
  double max_true_ulp = 0;     // |model − exact(unquantised)| in ulps
  long over_bound = 0;
};

// Alignment error bound of one block triple (docs/pipeline.md stage 7): 0 for a value that is
// a multiple of the block ulp 2^(lead_max − (P−1)), else half that ulp.
mpq_class align_err(const FxFloat v[3], int P, int k) {
  int lead = INT32_MIN;
  for (int i = 0; i < 3; ++i)
    if (v[i].sig) lead = std::max(lead, v[i].exp + 63 - __builtin_clzll(v[i].sig));
  if (lead == INT32_MIN || v[k].sig == 0) return 0;
  const int eb = lead - (P - 1);
  const mpq_class q = to_mpq(v[k]) / pow2(eb);
  return q.get_den() == 1 ? mpq_class(0) : mpq_class(pow2(eb) / 2);
}

// Checks every fragment of one triangle; asserts the derived bound per value.
void check_tri(const Config& cfg, const DrawState& st0, const VIn in[3], int nv, Err& e, bool check_true = true) {
  DrawState st = st0;
  st.num_varyings = nv;
  const bool affine = st.interp == InterpMode::Affine;
  const SetupTriangle t = quantise(cfg, in, nv, affine);
  const int s = cfg.raster.subpixel_bits, P = cfg.raster.interp_block_bits;
  const int nb = cfg.div.num_bits, db = cfg.div.den_bits;
  FxFloat rw3[3] = {t.v[0].rw, t.v[1].rw, t.v[2].rw};
  mpq_class rw[3], aR[3], true_rw[3];
  for (int k = 0; k < 3; ++k) {
    rw[k] = affine ? mpq_class(1) : to_mpq(t.v[k].rw);
    aR[k] = affine ? mpq_class(0) : align_err(rw3, P, k);
    true_rw[k] = affine ? mpq_class(1) : mpq_class(mpq_class(1) / to_mpq(in[k].w));
  }
  for (const Fragment& f : all_fragments(cfg, st, t)) {
    ++e.frags;
    const Bary b = bary(t, s, f.x, f.y);
    mpq_class D = 0, aD = 0, Dt = 0;
    for (int k = 0; k < 3; ++k) D += b.e[k] * rw[k], aD += b.e[k] * aR[k], Dt += b.e[k] * true_rw[k];
    for (int m = 0; m < nv; ++m) {
      FxFloat vw3[3] = {t.v[0].vw[m], t.v[1].vw[m], t.v[2].vw[m]};
      mpq_class N = 0, aN = 0, Nt = 0;
      for (int k = 0; k < 3; ++k) {
        N += b.e[k] * to_mpq(vw3[k]);
        aN += b.e[k] * align_err(vw3, P, k);
        Nt += b.e[k] * to_mpq(in[k].v[m]) * true_rw[k];
      }
      const mpq_class exact = N / D, got = to_mpq(f.var[m]);
      // Bound: alignment (aN, aD), RNE of |N| and D to nb / db bits, then ½ ulp of the result.
      const mpq_class an = abs(N);
      static thread_local int cached_nb = -1, cached_db = -1;
      static thread_local mpq_class en, ed;
      if (cached_nb != nb || cached_db != db) en = pow2(-nb), ed = pow2(-db), cached_nb = nb, cached_db = db;
      const mpq_class hi = (an + aN) * (1 + en) / ((D - aD) * (1 - ed));
      mpq_class lo_n = an - aN;
      if (lo_n < 0) lo_n = 0;
      const mpq_class lo = lo_n * (1 - en) / ((D + aD) * (1 + ed));
      const mpq_class dev = std::max(mpq_class(hi - an / D), mpq_class(an / D - lo));
      const mpq_class ulp_got = f.var[m].sig ? pow2(f.var[m].exp) : mpq_class(0);
      const mpq_class err = abs(got - exact);
      ++e.values;
      if (err > ulp_got / 2 + dev) {
        if (++e.over_bound <= 5)
          ADD_FAILURE() << "varying " << m << " at (" << f.x << "," << f.y << ") got " << got.get_d() << " exact "
                        << exact.get_d() << " err " << err.get_d() << " bound " << mpq_class(ulp_got / 2 + dev).get_d();
      }
      if (exact != 0) {
        const mpq_class ulp = pow2(ilog2(exact) - (cfg.raster.varying_out_sig_bits - 1));
        e.max_ulp = std::max(e.max_ulp, mpq_class(err / ulp).get_d());
        e.max_excess = std::max(e.max_excess, mpq_class((err - ulp_got / 2) / ulp).get_d());
      }
      const mpq_class tv = Nt / Dt;
      if (check_true && tv != 0) {
        const mpq_class ulp = pow2(ilog2(tv) - (cfg.raster.varying_out_sig_bits - 1));
        e.max_true_ulp = std::max(e.max_true_ulp, mpq_class(abs(got - tv) / ulp).get_d());
      }
    }
  }
}

DrawState state(int w = 64, int h = 64) {
  DrawState st;
  st.viewport_w = w;
  st.viewport_h = h;
  st.depth_test = false;
  return st;
}

void random_positions(std::mt19937_64& g, VIn in[3], int64_t r_small, int64_t r_big) {
  const int64_t S = 256;
  in[0].x = rnd(g, -8 * S, 72 * S), in[0].y = rnd(g, -8 * S, 72 * S);
  for (int k = 1; k < 3; ++k) {
    const int64_t r = (g() & 1) ? r_small : r_big;
    in[k].x = in[0].x + rnd(g, -r, r), in[k].y = in[0].y + rnd(g, -r, r);
  }
}

void print(const char* what, const Err& e) {
  std::printf("%s: %ld fragments, %ld values, max %.4f ulp vs exact(same inputs) (excess over 0.5: %.2e), "
              "max %.3f ulp vs unquantised\n",
              what, e.frags, e.values, e.max_ulp, e.max_excess, e.max_true_ulp);
}

}  // namespace

TEST(Interp, PlaneSteppingEqualsDirectEvaluation) {
  std::mt19937_64 g(3);
  Config cfg;
  for (int n = 0; n < 200; ++n) {
    SetupTriangle tri;
    for (int k = 0; k < 3; ++k) tri.v[k].x = rnd(g, -4000, 20000), tri.v[k].y = rnd(g, -4000, 20000);
    TriSetup t;
    if (setup_triangle(cfg, state(), tri, t) != SetupOutcome::Ok) continue;
    const int64_t q[3] = {(int64_t)(g() >> 24) - ((int64_t)1 << 39), (int64_t)(g() >> 24), -(int64_t)(g() >> 25)};
    const Plane p = make_plane(t, q);
    for (int j = t.y0; j <= t.y1; ++j) {
      i128 v = p.at(t.x0, j);
      for (int i = t.x0; i <= t.x1; ++i, v += p.dx) {
        // Direct: Σ E_k(centre) q_k from the unbiased edge functions.
        i128 direct = 0;
        for (int k = 0; k < 3; ++k)
          direct += (i128)edge_eval(t.e[k], pixel_centre(i, t.g), pixel_centre(j, t.g)) * q[k];
        ASSERT_TRUE(v == direct) << i << "," << j;
      }
    }
  }
}

TEST(Interp, PerspectiveCorrectWithinDerivedBound) {
  std::mt19937_64 g(101);
  const Config cfg;
  Err pos, mixed;
  for (int n = 0; n < 500; ++n) {
    VIn in[3];
    random_positions(g, in, 6 * 256, 40 * 256);
    for (int k = 0; k < 3; ++k) {
      in[k].w = 0.1 + 100 * urand(g);       // w ratios up to 1000
      in[k].v[0] = urand(g);                // [0, 1): texture coordinate
      in[k].v[1] = 16 * urand(g);           // [0, 16)
      in[k].v[2] = 2 * urand(g) - 1;        // sign change inside: cancellation
    }
    Err* e[2] = {&pos, &mixed};
    check_tri(cfg, state(), in, 2, *e[0]);
    VIn in2[3];
    for (int k = 0; k < 3; ++k) in2[k] = in[k], in2[k].v[0] = in[k].v[2];
    check_tri(cfg, state(), in2, 1, *e[1], false);
  }
  print("perspective, same-sign varyings", pos);
  print("perspective, mixed-sign varyings", mixed);
  EXPECT_GT(pos.frags, 25000);
  EXPECT_EQ(pos.over_bound + mixed.over_bound, 0);
  // Same-sign: the normalisations cost < 2^(qb − nb + 1) ulp (docs/pipeline.md); nothing more.
  EXPECT_LE(pos.max_ulp, 0.5 + 2.0 * std::ldexp(1.0, cfg.raster.varying_out_sig_bits - cfg.div.num_bits + 1));
  // Against the unquantised value: RNE of 1/w and of v/w (2^−24 relative each) and the final
  // rounding: ≤ 3 · 2^−24 relative + ½ ulp + the above, i.e. < 4 ulp (derivation in the docs).
  EXPECT_LT(pos.max_true_ulp, 4.0);
}

TEST(Interp, WRatioOf10000InsideOneTriangle) {
  std::mt19937_64 g(102);
  const Config cfg;
  Err e;
  for (int n = 0; n < 150; ++n) {
    VIn in[3];
    random_positions(g, in, 20 * 256, 60 * 256);
    const double ws[3] = {0.01, 1.0 + urand(g), 100.0 + 1e4 * urand(g)};  // ratios 10^4 … 10^6
    for (int k = 0; k < 3; ++k) {
      in[k].w = ws[(k + n) % 3];
      in[k].v[0] = urand(g);
      in[k].v[1] = 1000 * urand(g);
    }
    check_tri(cfg, state(), in, 2, e);
  }
  print("w ratio >= 1e4", e);
  EXPECT_EQ(e.over_bound, 0);
  EXPECT_GT(e.frags, 10000);
}

TEST(Interp, LargeMagnitudeVaryingsAndLargeRanges) {
  std::mt19937_64 g(103);
  const Config cfg;
  Err big, range;
  for (int n = 0; n < 200; ++n) {
    VIn in[3];
    random_positions(g, in, 6 * 256, 40 * 256);
    for (int k = 0; k < 3; ++k) {
      in[k].w = 0.5 + 50 * urand(g);
      in[k].v[0] = 1e30 * (1 + urand(g));                 // large magnitude, same sign
      in[k].v[1] = 1e-30 * (1 + urand(g));                // tiny magnitude
      in[k].v[2] = (k == 0 ? -1e20 : k == 1 ? 1e20 : 1.0) * urand(g);  // range ±1e20 with a 1
    }
    check_tri(cfg, state(), in, 2, big);
    VIn in2[3];
    for (int k = 0; k < 3; ++k) in2[k] = in[k], in2[k].v[0] = in[k].v[2];
    check_tri(cfg, state(), in2, 1, range, false);
  }
  print("large/tiny magnitudes", big);
  print("range +-1e20", range);
  EXPECT_EQ(big.over_bound + range.over_bound, 0);
  EXPECT_LT(big.max_true_ulp, 4.0);
}

TEST(Interp, SliversOnePixelAndFullScreen) {
  std::mt19937_64 g(104);
  const Config cfg;
  Err sliver, tiny, full;
  for (int n = 0; n < 400; ++n) {
    VIn in[3];
    // Sliver: aspect > 1000 (long edge ~60 px, height a few subpixels).
    in[0].x = rnd(g, 0, 4 * 256), in[0].y = rnd(g, 0, 60 * 256);
    in[1].x = in[0].x + 60 * 256, in[1].y = rnd(g, 0, 60 * 256);
    in[2].x = (in[0].x + in[1].x) / 2 + rnd(g, -2, 2), in[2].y = (in[0].y + in[1].y) / 2 + rnd(g, -3, 3);
    for (int k = 0; k < 3; ++k) in[k].w = 1 + 20 * urand(g), in[k].v[0] = urand(g);
    check_tri(cfg, state(), in, 1, sliver);
    // One-pixel / sub-pixel triangles around a pixel centre.
    in[0].x = rnd(g, 0, 60 * 256), in[0].y = rnd(g, 0, 60 * 256);
    for (int k = 1; k < 3; ++k) in[k].x = in[0].x + rnd(g, -256, 256), in[k].y = in[0].y + rnd(g, -256, 256);
    check_tri(cfg, state(), in, 1, tiny);
  }
  for (int n = 0; n < 3; ++n) {
    VIn in[3];
    in[0].x = -3000 * 256, in[0].y = -2000 * 256;
    in[1].x = 4000 * 256, in[1].y = -2100 * 256;
    in[2].x = -2900 * 256, in[2].y = 5000 * 256;
    for (int k = 0; k < 3; ++k) in[k].w = 0.2 + 30 * urand(g), in[k].v[0] = urand(g) * 8;
    check_tri(cfg, state(), in, 1, full);
  }
  print("slivers", sliver);
  print("1-pixel", tiny);
  print("full-screen", full);
  EXPECT_EQ(sliver.over_bound + tiny.over_bound + full.over_bound, 0);
  EXPECT_GT(full.frags, 3 * 64 * 64 - 1);
}

TEST(Interp, AffineModeIsTheScreenLinearValueAndDiffersAsSeed000Predicts) {
  const Config cfg;
  // A triangle whose screen centroid is the centre of pixel (20, 20): vertices on a grid
  // such that Σ x_k / 3 = 20.5 px exactly.
  VIn in[3];
  in[0].x = (int64_t)(2.5 * 256), in[0].y = (int64_t)(2.5 * 256);
  in[1].x = (int64_t)(50.5 * 256), in[1].y = (int64_t)(8.5 * 256);
  in[2].x = (int64_t)(8.5 * 256), in[2].y = (int64_t)(50.5 * 256);
  in[0].v[0] = 0, in[1].v[0] = 1, in[2].v[0] = 0.5;
  double prev_gap = -1;
  for (double ratio : {1.0, 2.0, 10.0, 100.0, 1e4}) {
    in[0].w = 1, in[1].w = ratio, in[2].w = std::sqrt(ratio);
    Err ea, ep;
    DrawState sa = state(), sp = state();
    sa.interp = InterpMode::Affine;
    check_tri(cfg, sa, in, 1, ea, false);
    check_tri(cfg, sp, in, 1, ep, false);
    EXPECT_EQ(ea.over_bound + ep.over_bound, 0);
    // The value at the centroid pixel.
    auto at = [&](const DrawState& st) {
      DrawState s2 = st;
      s2.num_varyings = 1;
      for (const Fragment& f : all_fragments(cfg, s2, quantise(cfg, in, 1, st.interp == InterpMode::Affine)))
        if (f.x == 20 && f.y == 20) return to_mpq(f.var[0]).get_d();
      return -1.0;
    };
    const double va = at(sa), vp = at(sp);
    // Affine: the average of the corners (docs/references.md#seed-000-wrong-image); perspective: Σ (v/w) / Σ (1/w).
    EXPECT_NEAR(va, 0.5, 1e-7);
    const double want_p = (0 / 1.0 + 1 / ratio + 0.5 / std::sqrt(ratio)) / (1 + 1 / ratio + 1 / std::sqrt(ratio));
    EXPECT_NEAR(vp, want_p, 1e-6);
    const double gap = std::abs(va - vp);
    std::printf("w ratio %g: affine %.6f perspective %.6f gap %.6f\n", ratio, va, vp, gap);
    if (ratio == 1.0) {
      EXPECT_LT(gap, 1e-7);  // equal w: the two modes agree
    }
    EXPECT_GT(gap, prev_gap);                // the error of affine grows with the w ratio
    prev_gap = gap;
  }
}

TEST(Interp, DividerWidthMustMatchOutputWidth) {
  Config cfg;
  cfg.div.quot_bits = cfg.raster.varying_out_sig_bits + 1;
  FrameOutput f;
  EXPECT_THROW(frame_begin(cfg, state(), f), ConfigError);
}

TEST(Interp, NarrowDividerOperandsStayWithinTheirBound) {
  // num_bits / den_bits = quot_bits + 2: the normalisation term of the bound dominates.
  Config cfg;
  cfg.div.num_bits = cfg.div.den_bits = cfg.raster.varying_out_sig_bits + 2;
  std::mt19937_64 g(105);
  Err e;
  for (int n = 0; n < 300; ++n) {
    VIn in[3];
    random_positions(g, in, 6 * 256, 30 * 256);
    for (int k = 0; k < 3; ++k) in[k].w = 0.1 + 10 * urand(g), in[k].v[0] = urand(g);
    check_tri(cfg, state(), in, 1, e, false);
  }
  print("num/den bits = 26", e);
  EXPECT_EQ(e.over_bound, 0);
}

// ---- the depth stepper's int64_t fast path against the i128 one and the direct quotient ------

namespace {

// RNE(z / den) clamped to [0, max_code], written from the definition (no stepping).
uint32_t direct_code(__int128 z, __int128 den, __int128 max_code) {
  __int128 q = z / den, r = z % den;
  if (r < 0) r += den, q -= 1;
  if (2 * r > den || (2 * r == den && (q & 1))) q += 1;
  return (uint32_t)(q < 0 ? 0 : q > max_code ? max_code : q);
}

__int128 rnd_signed(std::mt19937_64& rng, int bits) {
  const __int128 m = ((__int128)1 << bits) - 1;
  const __int128 v = (((__int128)rng() << 64) | rng()) & m;
  return (rng() & 1) ? -v : v;
}

}  // namespace

TEST(DepthStep64, SameCodesAsI128AndTheDirectQuotientWhereTheTestSaysItFits) {
  std::mt19937_64 rng(1414);
  int narrow = 0, wide = 0;
  for (int it = 0; it < 200000; ++it) {
    DepthSetup s;
    const int den_bits = 1 + (int)(rng() % 64);  // up to 2^64: both outcomes of the test
    s.den = 1 + (rnd_signed(rng, den_bits) < 0 ? -rnd_signed(rng, den_bits) : rnd_signed(rng, den_bits));
    if (s.den <= 0) s.den = 1;
    const int zb = (int)(rng() % 90);
    s.z.c = rnd_signed(rng, zb);
    s.z.dx = rnd_signed(rng, (int)(rng() % 90));
    s.max_code = (rng() % 4 == 0) ? (((__int128)1 << (1 + rng() % 62)) - 1) : (((__int128)1 << 32) - 1);
    const int steps = 1 + (int)(rng() % 64);
    DepthStepper wide_z(s, 0, 0);
    if (!depth_step_fits64(wide_z, steps)) {
      ++wide;
      continue;
    }
    ++narrow;
    DepthStepperT<int64_t> nz = narrow64(wide_z);
    for (int k = 0; k < steps; ++k) {
      const uint32_t want = direct_code(s.z.c + (__int128)k * s.z.dx, s.den, s.max_code);
      ASSERT_EQ(wide_z.code(), want) << "it " << it << " k " << k;
      ASSERT_EQ(nz.code(), want) << "it " << it << " k " << k;
      wide_z.step_x();
      nz.step_x();
    }
  }
  EXPECT_GT(narrow, 50000);  // both paths are exercised
  EXPECT_GT(wide, 10000);
}

TEST(DepthStep64, TheRangeTestRejectsAtTheLimit) {
  DepthSetup s;
  s.den = ((__int128)1 << 61) - 1;
  s.z.c = 0;
  s.z.dx = 0;
  EXPECT_TRUE(depth_step_fits64(DepthStepper(s, 0, 0), 1000));
  s.den = (__int128)1 << 61;
  EXPECT_FALSE(depth_step_fits64(DepthStepper(s, 0, 0), 1));
  s.den = 1;  // q = z, dq = dx
  s.z.dx = 1;
  s.z.c = ((__int128)1 << 61) - 1 - 2 * 10;  // |q| + 10·(1 + 1) = 2^61 − 1: fits
  EXPECT_TRUE(depth_step_fits64(DepthStepper(s, 0, 0), 10));
  EXPECT_FALSE(depth_step_fits64(DepthStepper(s, 0, 0), 11));
  s.z.c = -s.z.c;  // the negative side the same
  EXPECT_TRUE(depth_step_fits64(DepthStepper(s, 0, 0), 10));
  EXPECT_FALSE(depth_step_fits64(DepthStepper(s, 0, 0), 11));
  // A long span at the edge, stepped both ways: the same codes (clamped at max_code).
  s.z.c = ((__int128)1 << 61) - 1 - 2 * 1000;
  s.max_code = ((__int128)1 << 60);
  DepthStepper w(s, 0, 0);
  ASSERT_TRUE(depth_step_fits64(w, 1000));
  DepthStepperT<int64_t> n = narrow64(w);
  for (int k = 0; k < 1000; ++k, w.step_x(), n.step_x()) ASSERT_EQ(n.code(), w.code()) << k;
}
