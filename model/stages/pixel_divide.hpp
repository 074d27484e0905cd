// model/stages/pixel_divide.hpp — stage 9 (divider) at one pixel, direct: from the exact plane
// sums D, N_m of the pixel to the compact record's varying words (model/unit/fragment_store.hpp).
// docs/speed.md "Session 13: the divider of one pixel".
//
// The same words as DivideStage::step (normalize_den + divide_varying on the div_sig_fast64 path,
// model/stages/divide.hpp) followed by put_fragment_var, and as FusedSpan's pixel loops
// (model/stages/interp_span.hpp), with no state carried from one pixel to the next (no binade,
// no segment): a kernel that visits its pixels in any order (a narrow triangle's branchless
// traversal) calls it per passing pixel.
//   D ≤ 0: every varying 0 (sig 0, exp 0, +). N = 0: that varying 0.
//   |N|, D: the msb by a leading-zero count of the 128-bit magnitude, the value shifted so that
//     its msb lies at bit kPixelAlignMsb (126, the high word's bit 62), then rounded (RNE) to
//     num_bits / den_bits in the high word with one shift that does not depend on the msb
//     (rne_high_word, model/arith/fixed.hpp). A rounding carry-out (2^bits) is left to the
//     divider, whose quotient is then the renormalised operands' with the exponent moved
//     (div_sig_recip64_frac_w's contract, model/arith/div.hpp; as FusedSpan's word segments).
//   One reciprocal of D's significand per pixel (div_recip64_w) and per varying one multiply
//     (div_sig_recip64_frac_w): div_sig_fast64's quotient.
//   The exponent: exp_adj + msb(|N|) + num_exp − msb(D) − den_exp − (quot_bits − 1), the
//     triangle's part folded in begin().
// Applies where FusedSpan::applies (radix2, W + qb ≤ 63, quot_bits ≤ kStoredSigBits) and, per
// triangle, where FusedSpan::fits (divide_exponents_fit below: every exponent storable).
// Plane sums lie in (−2^127, 2^127) (normalize()'s range; interp_plane_bits ≤ 127).
// Proven against DivideStage and normalize_den + divide_varying: tests/model/pixel_divide_test.cpp
// (every msb 0 … 126, ties, carry-outs, D ≤ 0, N = 0, signs, default and other widths, nv 0–4),
// 10^8 pixels in tests/model/pixel_divide_slow_test.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "model/arith/div.hpp"
#include "model/arith/fixed.hpp"
#include "model/config/config.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/fragment_store.hpp"

namespace fxr {

// The divider's widths: W = div_align_bits, num_bits, den_bits, quot_bits; a configuration's at
// run time, or the defaults as compile-time constants (the shifts and masks fold).
struct DivWidths {
  int w, nb, db, qb;
};
inline DivWidths div_widths(const DivConfig& c) { return {div_align_bits(c), c.num_bits, c.den_bits, c.quot_bits}; }
struct DefaultDivWidths {
  static constexpr DivConfig kDiv{};
  static constexpr int nb = kDiv.num_bits, db = kDiv.den_bits, qb = kDiv.quot_bits;
  static constexpr int w = nb > db ? nb : db;  // div_align_bits
};
inline bool is_default_div_widths(const DivWidths& w) {
  return w.w == DefaultDivWidths::w && w.nb == DefaultDivWidths::nb && w.db == DefaultDivWidths::db &&
         w.qb == DefaultDivWidths::qb;
}

// True when stage 9 divides with div_sig_fast64 (the path PixelDivide and FusedSpan reproduce)
// and its significands fit the compact record (quot_bits ≤ kStoredSigBits).
inline bool pixel_divide_applies(const DivConfig& c) { return div_fast64_ok(c) && c.quot_bits <= kStoredSigBits; }

// Bound on |exp − num_exp + den_exp|: |exp_adj| + 2·127 + (qb − 1 ≤ 62) < 2^9.
inline constexpr int64_t kDivideExpSlack = int64_t{1} << 9;
// True when every exponent triangle t's fragments can have fits the compact record
// (|exp| ≤ kStoredExpMax): the quotient's exponent is exp_adj + ne + num_exp − de − den_exp −
// (qb − 1) with |exp_adj| ≤ 1 and ne, de ≤ 127, the normalised sums' msb positions. The block
// exponents of any representable scene are far inside; a triangle outside this goes through
// the staged stages (FragmentChain::span).
inline bool divide_exponents_fit(const TriangleEquations& t, int nv) {
  int64_t worst = 0;
  for (int m = 0; m < nv; ++m) worst = std::max<int64_t>(worst, std::abs((int64_t)t.interp.num_exp[m]));
  return worst + std::abs((int64_t)t.interp.den_exp) + kDivideExpSlack <= kStoredExpMax;
}

// The msb a magnitude is shifted to before its rounding: the high word's bit 62 (rne_high_word
// needs msb ≤ 2·64 − 2).
inline constexpr int kPixelAlignMsb = 126;

// Contract: x < 2^127, 4 ≤ bits ≤ 62. Returns RNE(x·2^−(msb − (bits − 1))), msb = msb_index(x),
// in [2^(bits−1), 2^bits] (a carry-out to 2^bits not renormalised), and sets msb; x = 0: returns 0
// (msb then 0; the caller masks). Exact for msb < bits (the shift is then a left shift).
[[gnu::always_inline]] inline uint64_t pixel_sig(u128 x, int bits, int& msb) {
  const uint64_t hi = (uint64_t)(x >> 64), lo = (uint64_t)x;
  // The leading-zero count of the 128-bit value without a branch: of the high word when it is
  // nonzero, else 64 + the low word's (| 1: x = 0 counts 127, its shift is then harmless).
  const int c = hi != 0 ? __builtin_clzll(hi) : 64 + __builtin_clzll(lo | 1);
  msb = 127 - c;
  const u128 a = x << (c - (127 - kPixelAlignMsb));  // msb at kPixelAlignMsb
  // NormalizeAtMsb's rounding of a value whose msb is kPixelAlignMsb, in the high word (constants
  // where `bits` is one).
  const NormalizeAtMsb al(bits, kPixelAlignMsb);
  return rne_high_word<uint64_t>((uint64_t)(a >> 64), (uint64_t)a, al.high_shift(), al.high_bias());
}

class PixelDivide {
 public:
  static bool applies(const Config& cfg) { return pixel_divide_applies(cfg.div); }

  // Per draw: the divider's configuration (applies) and the number of varyings (0 … kMaxVaryings).
  PixelDivide(const DivConfig& dc, int nv)
      : nv_(nv), widths_(div_widths(dc)), default_widths_(is_default_div_widths(widths_)) {}

  int num_varyings() const { return nv_; }
  const DivWidths& widths() const { return widths_; }
  bool default_widths() const { return default_widths_; }

  // Per triangle: the exponents' constant part, num_exp[m] − den_exp − (qb − 1).
  void begin(const TriangleEquations& t) {
    for (int m = 0; m < nv_; ++m) cexp_[m] = t.interp.num_exp[m] - t.interp.den_exp - (widths_.qb - 1);
  }

  // Contract: begin(t) called for the pixel's triangle t (divide_exponents_fit(t, nv)); sums[0] = D,
  // sums[1 + m] = N_m at the pixel (two's complement of Plane::at(i, j), each in (−2^127, 2^127)).
  // Writes varying words 0 … nv − 1 of the record at rec (not its header): the words
  // put_fragment_var writes for DivideStage's var[m].
  void write(uint8_t* rec, const u128* sums) const {
    if (default_widths_) {
      switch (nv_) {
        case 0: return;
        case 1: return write_t<1>(rec, sums, DefaultDivWidths{});
        case 2: return write_t<2>(rec, sums, DefaultDivWidths{});
        default: return write_t<-1>(rec, sums, DefaultDivWidths{});
      }
    }
    write_t<-1>(rec, sums, widths_);
  }
  // The same with the number of varyings (NV ≥ 0; −1: num_varyings()) and the widths (wd:
  // DefaultDivWidths{} when default_widths(), else widths()) as the caller's constants.
  template <int NV, class W>
  [[gnu::always_inline]] void write_t(uint8_t* rec, const u128* sums, const W& wd) const {
    write_t<NV>(rec, sums + 1, den(sums[0], wd), wd);
  }

  // D's part of a pixel: its significand, msb and reciprocal, for a caller that issues the next
  // pixel's division before it writes this one's varyings. D ≤ 0 (pos false): a placeholder
  // divisor (no division by zero, no branch); write_t then writes zeros.
  struct Den {
    uint64_t d = 0, R = 0;
    int msb = 0;
    bool pos = false;
  };
  template <class W>
  [[gnu::always_inline]] static Den den(u128 D, const W& wd) {
    Den r;
    r.pos = (i128)D > 0;
    r.d = pixel_sig(r.pos ? D : 1, wd.db, r.msb);
    r.R = div_recip64_w(wd.w, wd.db, r.d);
    return r;
  }
  // Contract: as write(), with nums[m] = N_m and dn = den(D, wd) of the pixel's D.
  template <int NV, class W>
  [[gnu::always_inline]] void write_t(uint8_t* rec, const u128* nums, const Den& dn, const W& wd) const {
    const int nv = NV >= 0 ? NV : nv_;
    if (__builtin_expect(!dn.pos, 0)) {  // D ≤ 0: every varying 0 (divide_varying)
      for (int m = 0; m < nv; ++m) put_fragment_var_words(rec, m, 0, 0);
      return;
    }
    for (int m = 0; m < nv; ++m) {
      const u128 v = nums[m];
      const uint64_t neg = (uint64_t)(v >> 127);               // 1 for a negative N
      const u128 sm = (u128)0 - (u128)neg;                     // all ones for a negative N
      const u128 mag = (v ^ sm) - sm;                          // |N|
      int nm;
      const uint64_t a = pixel_sig(mag, wd.nb, nm);           // 0 for N = 0
      const DivSig q = div_sig_recip64_frac_w(wd.w, wd.nb, wd.db, wd.qb, a, dn.d, dn.R);  // sig 0 for a = 0
      const uint32_t keep = a != 0 ? ~uint32_t{0} : 0;         // N = 0: the exponent word 0 too
      const uint32_t e = (uint32_t)(q.exp_adj + nm - dn.msb + cexp_[m]);
      put_fragment_var_words(rec, m, (uint32_t)q.sig, ((e << 1) | (uint32_t)neg) & keep);
    }
  }

 private:
  int nv_;
  DivWidths widths_;
  bool default_widths_;
  int cexp_[kMaxVaryings] = {};
};

}  // namespace fxr
