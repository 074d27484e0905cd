// tests/model/attr_fast64_cases.hpp — the 64-bit paths of a vertex's stage-4 arithmetic against
// their i128 references (docs/speed.md "Session 9: per triangle"): rne_quotient_plus64 (attr_window,
// attr_depth), attr_quotient64 (1/w, v/w) and round_scaled_sum64 (snap_window). Each check runs
// both paths on one case and counts whether the 64-bit path answered; shared by
// attr_fast64_test.cpp (model label) and attr_fast64_slow_test.cpp (slow label).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <random>
#include <string>

#include "model/stages/attr.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/viewport.hpp"

namespace fxr::fast64 {

// Outcome counts of one kernel over many cases.
struct Tally {
  uint64_t cases = 0, fast = 0, mismatches = 0;
  std::string first;  // the first mismatch, described
  // `what()` describes the case; called for the first mismatch only.
  template <class What>
  void note(bool took_fast, bool same, What&& what) {
    ++cases;
    fast += took_fast;
    if (!same) {
      if (mismatches == 0) first = what();
      ++mismatches;
    }
  }
};

inline std::string str(i128 v) {
  const bool neg = v < 0;
  u128 m = neg ? (u128)0 - (u128)v : (u128)v;
  std::string s;
  do {
    s.insert(s.begin(), (char)('0' + (int)(m % 10)));
    m /= 10;
  } while (m);
  return neg ? "-" + s : s;
}

// rne_quotient_plus64 against rne_quotient_plus: where the 64-bit path answers, the same value
// and the reference reports no overflow.
inline void check_rqp(Tally& t, bool neg, uint64_t N, int k, uint64_t D, int64_t C) {
  bool ovf = false;
  const i128 ref = rne_quotient_plus(neg, N, k, D, C, &ovf);
  int64_t v = 0;
  const bool fast = rne_quotient_plus64(neg, N, k, D, C, &v);
  const bool same = !fast || (!ovf && (i128)v == ref);
  t.note(fast, same, [&] { return "neg " + std::to_string(neg) + " N " + std::to_string(N) + " k " + std::to_string(k) + " D " +
             std::to_string(D) + " C " + std::to_string(C) + ": fast " + std::to_string(v) + " ref " + str(ref) +
             (ovf ? " (ovf)" : ""); });
}

// attr_quotient (which takes attr_quotient64 where it answers) against attr_quotient_wide.
inline void check_quot(Tally& t, const FxFloat& n, const FxFloat& w, int bits) {
  const FxFloat ref = attr_quotient_wide(n, w, bits);
  FxFloat f;
  const bool fast = attr_quotient64(n, w, bits, &f);
  const FxFloat d = attr_quotient(n, w, bits);
  const auto eq = [](const FxFloat& a, const FxFloat& b) { return a.neg == b.neg && a.sig == b.sig && a.exp == b.exp; };
  const bool same = eq(d, ref) && (!fast || eq(f, ref));
  t.note(fast, same, [&] { return "n " + std::to_string(n.neg) + "/" + std::to_string(n.sig) + "/" + std::to_string(n.exp) + " w " +
             std::to_string(w.sig) + "/" + std::to_string(w.exp) + " bits " + std::to_string(bits) + ": fast " +
             std::to_string(f.sig) + "·2^" + std::to_string(f.exp) + " ref " + std::to_string(ref.sig) + "·2^" +
             std::to_string(ref.exp); });
}

// round_scaled_sum64 against round_scaled_sum (which must not report range where it answers).
inline void check_rss(Tally& t, int64_t m, int e, int64_t c, int sh) {
  bool range = false;
  const i128 ref = round_scaled_sum(m, e, c, sh, &range);
  int64_t v = 0;
  const bool fast = round_scaled_sum64(m, e, c, sh, &v);
  const bool same = !fast || (!range && (i128)v == ref);
  t.note(fast, same, [&] { return "m " + std::to_string(m) + " e " + std::to_string(e) + " c " + std::to_string(c) + " sh " +
             std::to_string(sh) + ": fast " + std::to_string(v) + " ref " + str(ref); });
}

// The composed stage-4 functions against their i128 references, range flags included.
inline void check_window(Tally& t, const FxFloat& c, const FxFloat& w, int64_t size, int64_t origin,
                         const RasterConfig& rc) {
  bool r1 = false, r2 = false;
  const int64_t a = attr_window(c, w, size, origin, rc, &r1), b = attr_window_wide(c, w, size, origin, rc, &r2);
  t.note(true, a == b && r1 == r2, [&] { return "attr_window c " + std::to_string(c.neg) + "/" + std::to_string(c.sig) + "/" + std::to_string(c.exp) + " w " +
             std::to_string(w.sig) + "/" + std::to_string(w.exp) + " size " + std::to_string(size) + " origin " +
             std::to_string(origin) + ": " + std::to_string(a) + " vs " + std::to_string(b); });
}
inline void check_depth(Tally& t, const FxFloat& z, const FxFloat& w, const RasterConfig& rc) {
  const uint64_t a = attr_depth(z, w, rc), b = attr_depth_wide(z, w, rc);
  t.note(true, a == b, [&] { return "attr_depth z " + std::to_string(z.sig) + "/" + std::to_string(z.exp) + " w " + std::to_string(w.sig) + "/" +
             std::to_string(w.exp) + ": " + std::to_string(a) + " vs " + std::to_string(b); });
}
inline void check_snap(Tally& t, const FxProd& n, int64_t size, int64_t origin, const RasterConfig& rc) {
  bool r1 = false, r2 = false;
  const int64_t a = snap_window(n, size, origin, rc, &r1), b = snap_window_wide(n, size, origin, rc, &r2);
  t.note(true, a == b && r1 == r2, [&] { return "snap_window n " + std::to_string(n.neg) + "/" + str((i128)n.sig) + "/" + std::to_string(n.exp) + " size " +
             std::to_string(size) + " origin " + std::to_string(origin) + ": " + std::to_string(a) + " vs " +
             std::to_string(b); });
}

// align_block against align_block_wide; fast: every value on the int64 path (no value wider
// than 63 bits, no right shift past 62).
inline void check_align(Tally& t, const FxFloat v[3], int bits) {
  const Block3 a = align_block(v, bits), b = align_block_wide(v, bits);
  int lead = INT_MIN;
  for (int k = 0; k < 3; ++k)
    if (v[k].sig) lead = std::max(lead, v[k].lead_exp());
  bool fast = true;
  for (int k = 0; k < 3; ++k)
    if (v[k].sig && ((v[k].sig >> 63) || lead - (bits - 1) - v[k].exp > 62)) fast = false;
  const bool same = a.exp == b.exp && a.q[0] == b.q[0] && a.q[1] == b.q[1] && a.q[2] == b.q[2];
  t.note(fast, same, [&] {
    std::string d = "align_block bits " + std::to_string(bits);
    for (int k = 0; k < 3; ++k)
      d += " " + std::string(v[k].neg ? "-" : "") + std::to_string(v[k].sig) + "·2^" + std::to_string(v[k].exp);
    for (int k = 0; k < 3; ++k) d += " | " + std::to_string(a.q[k]) + " vs " + std::to_string(b.q[k]);
    return d;
  });
}

// ---- random cases ---------------------------------------------------------------------------

// A value of a random width 0 … max_bits (leading one at the top of that width), so that every
// magnitude, and both sides of each range test, is reached.
// attr_depth_q's reference: RNE(z·M / 2^db), M = 2^db − 1, from the exact i128 product by
// floor, remainder and a compare with the half (not shift_round: docs/speed.md "Session 12: per
// triangle"). z < 2^64.
inline int64_t depth_q_reference(int db, uint64_t z) {
  const i128 p = (i128)z * (((i128)1 << db) - 1);
  const i128 q = p >> db, r = p - (q << db), half = (i128)1 << (db - 1);
  return (int64_t)((r > half || (r == half && (q & 1))) ? q + 1 : q);
}

inline uint64_t random_width(std::mt19937_64& g, int max_bits) {
  const int b = (int)(g() % (uint64_t)(max_bits + 1));
  if (b == 0) return 0;
  const uint64_t top = (uint64_t)1 << (b - 1);
  return top | (g() & (top - 1));
}
inline int64_t random_signed(std::mt19937_64& g, int max_bits) {
  const int64_t m = (int64_t)random_width(g, max_bits);
  return (g() & 1) ? -m : m;
}
inline int random_in(std::mt19937_64& g, int lo, int hi) { return lo + (int)(g() % (uint64_t)(hi - lo + 1)); }

// A float32-like FxFloat (24-bit significand, normalised or a denormal) or a wider one.
inline FxFloat random_fx(std::mt19937_64& g, bool positive) {
  FxFloat f;
  f.neg = positive ? false : (g() & 1);
  const int kind = (int)(g() % 4);
  if (kind == 0) f.sig = random_width(g, 64);
  else f.sig = random_width(g, 24) | (kind == 1 ? 0 : (uint64_t)1 << 23);  // float32: a 24-bit significand
  if (positive && f.sig == 0) f.sig = 1;
  f.exp = random_in(g, -60, 20);
  return f;
}

// The configurations the composed functions are checked under: the default, a narrow one and
// A = 40 with window_int_bits 20 (positions near the int64 bound).
inline RasterConfig raster_config(int which) {
  RasterConfig rc;
  if (which == 1) rc.attr_subpixel_bits = 12, rc.z_frac_bits = 24, rc.attr_coord_bits = 24;
  if (which == 2) rc.attr_subpixel_bits = 40, rc.window_int_bits = 20, rc.z_frac_bits = 48;
  return rc;
}

// One random case of each kernel and composed function.
inline void random_round(std::mt19937_64& g, Tally& rqp, Tally& quot, Tally& rss, Tally& composed, Tally& align) {
  check_rqp(rqp, g() & 1, random_width(g, 64), random_in(g, -70, 70), random_width(g, 64) | 1,
            random_signed(g, 63));
  const FxFloat n = random_fx(g, false), w = random_fx(g, true);
  check_quot(quot, n, w, random_in(g, 2, 62));
  check_rss(rss, random_signed(g, 63), random_in(g, -70, 70), random_signed(g, 62), random_in(g, 0, 4));
  const RasterConfig rc = raster_config((int)(g() % 3));
  const int64_t size = (int64_t)random_width(g, rc.window_int_bits) + 1;
  const int64_t origin = random_signed(g, rc.window_int_bits - 1);
  check_window(composed, n, w, size, origin, rc);
  check_depth(composed, n, w, rc);
  FxProd p;
  p.neg = g() & 1;
  p.sig = (u128)random_width(g, 64) * (g() % 4 == 0 ? random_width(g, 36) : 1);  // past 2^64 at times
  p.exp = random_in(g, -110, 10);
  check_snap(composed, p, size, origin, rc);
  // Three attribute values (32-bit significands as the default attr_sig_bits, or up to 64 bits)
  // with exponents up to 80 apart; bits 2 … 62.
  FxFloat v[3];
  const int e0 = random_in(g, -40, 40), wide = (int)(g() % 4);
  for (FxFloat& x : v) {
    x.neg = g() & 1;
    x.sig = random_width(g, wide == 0 ? 64 : 32);
    x.exp = e0 + random_in(g, -(10 << wide), 10 << wide);
  }
  check_align(align, v, random_in(g, 2, 62));
}

inline void expect_clean(const Tally& t, const char* what) {
  EXPECT_EQ(t.mismatches, 0u) << what << ": " << t.mismatches << " of " << t.cases << ", first: " << t.first;
}

// `rounds` random rounds of every path (seeded), each checked clean and each range test's two
// outcomes both reached in more than a tenth of the cases: the CI test (10^6) and the slow one
// (10^8) differ only in the count.
struct RandomRounds {
  Tally rqp, quot, rss, composed, align;
};
inline RandomRounds run_random_rounds(uint64_t seed, long rounds) {
  std::mt19937_64 g(seed);
  RandomRounds r;
  for (long i = 0; i < rounds; ++i) random_round(g, r.rqp, r.quot, r.rss, r.composed, r.align);
  expect_clean(r.rqp, "rne_quotient_plus64");
  expect_clean(r.quot, "attr_quotient64");
  expect_clean(r.rss, "round_scaled_sum64");
  expect_clean(r.composed, "attr_window / attr_depth / snap_window");
  expect_clean(r.align, "align_block");
  for (const Tally* t : {&r.rqp, &r.quot, &r.rss, &r.align}) {
    EXPECT_GT(t->fast, t->cases / 10);
    EXPECT_LT(t->fast, t->cases - t->cases / 10);
  }
  return r;
}

}  // namespace fxr::fast64
