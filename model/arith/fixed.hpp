// model/arith/fixed.hpp — bit-exact fixed-point primitives: quantisation (rounding, overflow)
// of integer codes whose format an FxFormat carries, as sc_fixed defines them.
//
// The stages use the normalisation and rounding here (normalize_fx in fxfloat.hpp, the RNE of
// round.hpp through shift_round); convert / mac are the general sc_fixed-compatible operations
// the benchmarks and tests compare against SystemC. Every round-to-nearest-even decision is
// round.hpp's rne_round_up.
//
// Values are plain two's-complement integers (int64_t, or i128 where a product needs more
// than 64 bits) whose meaning — width, binary point, signedness — is carried by an FxFormat.
// Nothing here uses floating point. The operations mirror SystemC's sc_fixed quantisation
// (SC_TRN, SC_TRN_ZERO, SC_RND, SC_RND_CONV, SC_RND_INF) and overflow (SC_WRAP, SC_SAT)
// modes bit for bit; tests/sc/fixed_vs_sc_fixed_test.cpp proves it.
#pragma once

#include <cstdint>
#include <string>

#include "model/arith/round.hpp"

namespace fxr {

using i128 = __int128;
using u128 = unsigned __int128;

// Largest width any FxFormat may have: results are held in int64_t.
inline constexpr int kMaxFormatBits = 64;

// Quantisation (rounding) applied when low-order bits are dropped.
enum class Round : uint8_t {
  Trunc,        // toward −∞ (drop bits).                          sc: SC_TRN
  TruncZero,    // toward 0.                                        sc: SC_TRN_ZERO
  HalfUp,       // to nearest, ties toward +∞.                      sc: SC_RND
  HalfEven,     // to nearest, ties to even (IEEE default).         sc: SC_RND_CONV
  HalfAway,     // to nearest, ties away from 0.                    sc: SC_RND_INF
};

// What happens when a value does not fit the destination width.
enum class Overflow : uint8_t {
  Wrap,      // keep the low bits (two's complement wrap).          sc: SC_WRAP
  Saturate,  // clamp to the most positive / most negative code.    sc: SC_SAT
};

const char* to_string(Round r);
const char* to_string(Overflow o);

// A fixed-point format: `width` bits in all, `frac` of them after the binary point
// (frac may be negative or exceed width, as in sc_fixed), two's complement if is_signed.
// The represented value of code c is c · 2^−frac.
struct FxFormat {
  int width = 32;
  int frac = 16;
  bool is_signed = true;
  Round round = Round::HalfEven;
  Overflow overflow = Overflow::Saturate;

  int int_bits() const { return width - frac; }  // sc_fixed's iwl
  int64_t max_code() const {
    return is_signed ? (int64_t)((((u128)1) << (width - 1)) - 1) : (int64_t)((((u128)1) << width) - 1);
  }
  int64_t min_code() const { return is_signed ? -(int64_t)((((u128)1) << (width - 1))) : 0; }
  std::string describe() const;  // e.g. "s8.16 RNE sat"
};

// ---- bit utilities -------------------------------------------------------------------------

// The int64 range proofs' bound (docs/speed.md "Session 9: per triangle"): a value whose msb
// index is at most kInt64ShiftMax is below 2^63 (fits int64, and uint64 with a spare bit for a
// doubling), and shift_round_right<int64_t> takes right shifts up to it (64 − 2).
inline constexpr int kInt64ShiftMax = 62;

// Number of leading zeros of a 64-bit value; clz64(0) == 64.
inline int clz64(uint64_t x) { return x ? __builtin_clzll(x) : 64; }

// Number of leading zeros of a 128-bit value; clz128(0) == 128.
inline int clz128(u128 x) {
  const uint64_t hi = (uint64_t)(x >> 64);
  return hi ? __builtin_clzll(hi) : 64 + clz64((uint64_t)x);
}

// Position of the most significant set bit (0-based); -1 for 0.
inline int msb_index(u128 x) { return 127 - clz128(x); }
inline int msb64(uint64_t x) { return 63 - clz64(x); }

// Low `width` bits of x, as unsigned.
inline u128 low_bits(u128 x, int width) {
  return width >= 128 ? x : (x & ((((u128)1) << width) - 1));
}

// ---- integer division with remainder ----------------------------------------------------------

// Contract: q = floor(a / d), r = a − q·d ∈ [0, d), for any a and d > 0 (u128). Exact.
//   When d < 2^64 and the quotient fits 64 bits (a / 2^64 < d) on x86-64 it is the one hardware
//   128-by-64-bit division (divq), else the compiler's u128 division (docs/speed.md "Wide
//   divisions with a narrow quotient"); the same q and r (DivMod128.* in tests/model/fixed_test.cpp).
inline void udivmod128(u128 a, u128 d, u128& q, u128& r) {
#if defined(__x86_64__) && defined(__GNUC__)
  const uint64_t hi = (uint64_t)(a >> 64), d64 = (uint64_t)d;
  if ((d >> 64) == 0 && hi < d64) {  // hi < d: the quotient fits 64 bits (no #DE)
    uint64_t q64, r64;
    __asm__("divq %4" : "=a"(q64), "=d"(r64) : "a"((uint64_t)a), "d"(hi), "rm"(d64) : "cc");
    q = q64;
    r = r64;
    return;
  }
#endif
  q = a / d;
  r = a % d;
}

// Contract: q = floor(a / d), r = a − q·d ∈ [0, d), for any a and d > 0 (i128). Exact.
inline void floor_divmod(i128 a, i128 d, i128& q, i128& r) {
  const u128 ud = (u128)d;
  u128 uq, ur;
  if (a >= 0) {
    udivmod128((u128)a, ud, uq, ur);
    q = (i128)uq, r = (i128)ur;
    return;
  }
  udivmod128((u128)0 - (u128)a, ud, uq, ur);  // |a| (also for a = −2^127)
  if (ur == 0) {
    q = -(i128)uq, r = 0;
  } else {
    q = -(i128)uq - 1, r = (i128)(ud - ur);
  }
}

// ---- rounding shift ------------------------------------------------------------------------

namespace detail {

// x · 2^−shift rounded by r, for 1 ≤ shift ≤ bits(S) − 2; S is int64_t or i128 and U its
// unsigned twin. Shared by the i128 path and the int64 fast path, so both round alike.
template <class S, class U>
inline S shift_round_right(S x, int shift, Round r) {
  const S floor_q = x >> shift;  // arithmetic shift: floor
  const U rem = (U)x & ((((U)1) << shift) - 1);  // x − floor_q·2^shift, in [0, 2^shift)
  if (rem == 0) return floor_q;
  const U half = ((U)1) << (shift - 1);
  switch (r) {
    case Round::Trunc: return floor_q;
    case Round::TruncZero: return x < 0 ? floor_q + 1 : floor_q;
    case Round::HalfUp: return rem >= half ? floor_q + 1 : floor_q;
    case Round::HalfEven:  // 2·rem < 2^(shift+1) fits U (shift ≤ bits(S) − 2)
      return rne_round_up<U>((U)floor_q, rem, half << 1) ? floor_q + 1 : floor_q;
    case Round::HalfAway:
      if (rem > half) return floor_q + 1;
      if (rem < half) return floor_q;
      return x < 0 ? floor_q : floor_q + 1;  // tie: away from zero
  }
  return floor_q;  // floor_q + 1 above always fits S: |floor_q| ≤ |x| / 2
}

}  // namespace detail

// Contract: returns x · 2^−shift rounded to an integer by `r`.
//   x: any i128; shift: ≥ 0 (shift ≤ 0 is an exact left shift by −shift, caller ensures fit).
//   Exact: no overflow is possible for shift ≥ 0 (the magnitude only shrinks, +1 at most
//   when rounding up, which fits because |x| < 2^127).
//   Special cases: shift ≥ 127 returns the rounding of a value in (−1, 1) — 0, or ±1 when
//   the mode rounds away from zero there.
inline i128 shift_round(i128 x, int shift, Round r) {
  if (shift <= 0) return x * (((i128)1) << (-shift));
  if (shift >= 127) {
    // |x · 2^−shift| < 1/2 for every x here except x = −2^127 (never produced by callers):
    // nearest modes give 0; truncation toward −∞ gives −1 for negative x.
    if (r == Round::Trunc && x < 0) return -1;
    return 0;
  }
  return detail::shift_round_right<i128, u128>(x, shift, r);
}

// ---- overflow handling ---------------------------------------------------------------------

// Contract: fits integer code x into `width` bits (signed or unsigned).
//   Saturate: clamps to [min_code, max_code]. Wrap: keeps the low `width` bits and
//   reinterprets them (sign-extends when signed). *overflowed (if given) is set when x
//   was out of range, else left unchanged. 1 ≤ width ≤ 64.
inline int64_t fit_width(i128 x, int width, bool is_signed, Overflow o, bool* overflowed = nullptr) {
  const i128 maxv = is_signed ? ((((i128)1) << (width - 1)) - 1) : ((((i128)1) << width) - 1);
  const i128 minv = is_signed ? -(((i128)1) << (width - 1)) : 0;
  if (x >= minv && x <= maxv) return (int64_t)x;
  if (overflowed) *overflowed = true;
  if (o == Overflow::Saturate) return (int64_t)(x > maxv ? maxv : minv);
  u128 low = low_bits((u128)x, width);
  if (is_signed && width < 128 && ((low >> (width - 1)) & 1)) low |= ~((((u128)1) << width) - 1);
  return (int64_t)(i128)low;
}

namespace detail {

// Widest destination the int64 fast path handles (its max code must fit int64_t).
inline constexpr int kFastMaxWidth = 63;
// Largest right shift the int64 fast path handles (shift_round_right needs ≤ bits − 2).
inline constexpr int kFastMaxShift = kInt64ShiftMax;

// convert() for an int64 x, 0 ≤ shift ≤ kFastMaxShift, dst.width ≤ kFastMaxWidth: the same
// rounding and overflow as the i128 path, in 64-bit arithmetic (the common case: 3× faster).
inline int64_t convert_fast(int64_t x, int shift, const FxFormat& dst, bool* overflowed) {
  const int64_t q = shift == 0 ? x : shift_round_right<int64_t, uint64_t>(x, shift, dst.round);
  const int64_t maxv = dst.max_code(), minv = dst.min_code();
  if (q >= minv && q <= maxv) return q;
  if (overflowed) *overflowed = true;
  if (dst.overflow == Overflow::Saturate) return q > maxv ? maxv : minv;
  uint64_t low = (uint64_t)q & (((uint64_t)1 << dst.width) - 1);
  if (dst.is_signed && ((low >> (dst.width - 1)) & 1)) low |= ~(((uint64_t)1 << dst.width) - 1);
  return (int64_t)low;
}

}  // namespace detail

// Contract: converts a code with `src_frac` fraction bits into format `dst`:
//   value = x · 2^−src_frac; result = fit(round(value · 2^dst.frac)).
//   Rounding by dst.round, overflow by dst.overflow; exact when no bits are dropped and the
//   result fits. This is sc_fixed's assignment from a wider fixed-point value.
//   Any x and any frac difference: when the destination has more fraction bits than the
//   source by so much that x · 2^(dst.frac − src_frac) leaves i128, the value certainly
//   leaves the ≤ 64-bit destination too: Saturate clamps by sign, Wrap keeps the low bits
//   (computed modulo 2^128, which preserves them).
inline int64_t convert(i128 x, int src_frac, const FxFormat& dst, bool* overflowed = nullptr) {
  const int shift = src_frac - dst.frac;
  if (x == (i128)(int64_t)x && shift >= 0 && shift <= detail::kFastMaxShift &&
      dst.width <= detail::kFastMaxWidth)
    return detail::convert_fast((int64_t)x, shift, dst, overflowed);
  if (shift < 0 && x != 0) {
    const int up = -shift;
    const int headroom = clz128((u128)(x < 0 ? ~x : x)) - 1;  // redundant sign bits of x
    if (up > headroom) {  // |x · 2^up| ≥ 2^126: out of every destination range
      if (overflowed) *overflowed = true;
      if (dst.overflow == Overflow::Saturate) return x < 0 ? dst.min_code() : dst.max_code();
      const u128 low = up >= 128 ? 0 : ((u128)x << up);
      return fit_width((i128)low_bits(low, dst.width), dst.width, dst.is_signed, Overflow::Wrap);
    }
  }
  const i128 q = shift_round(x, shift, dst.round);
  return fit_width(q, dst.width, dst.is_signed, dst.overflow, overflowed);
}

// Contract: product of two codes, a (frac fa) · b (frac fb), exact, frac fa + fb.
//   Needs |a|,|b| < 2^63: the product always fits i128.
inline i128 mul_wide(int64_t a, int64_t b) { return (i128)a * (i128)b; }

// Contract: a·b + c quantised into dst; a has frac fa, b frac fb, c frac fc (fc ≤ fa + fb,
//   and c aligned exactly by a left shift; the aligned c and the sum must fit i128).
//   One rounding, one overflow step, as sc_fixed computes `dst = a * b + c` with
//   full-precision intermediates. Fast path: when product, aligned c and sum fit int64
//   (checked), the whole computation stays in 64 bits with identical results.
inline int64_t mac(int64_t a, int fa, int64_t b, int fb, int64_t c, int fc, const FxFormat& dst,
                   bool* overflowed = nullptr) {
  const int fp = fa + fb;
  const int align = fp - fc;  // ≥ 0 by contract
  const int shift = fp - dst.frac;
  int64_t p, sum;
  const int64_t c_aligned = align < 63 ? (int64_t)((uint64_t)c << align) : 0;  // checked below
  if (align < 63 && shift >= 0 && shift <= detail::kFastMaxShift && dst.width <= detail::kFastMaxWidth &&
      (c_aligned >> align) == c && !__builtin_mul_overflow(a, b, &p) &&
      !__builtin_add_overflow(p, c_aligned, &sum))
    return detail::convert_fast(sum, shift, dst, overflowed);
  const i128 acc = mul_wide(a, b) + (i128)c * ((i128)1 << align);  // c may be < 0: no <<
  return convert(acc, fp, dst, overflowed);
}

// ---- normalisation -------------------------------------------------------------------------

// Result of normalising a positive integer into a significand with a leading one.
struct Normalized {
  uint64_t sig = 0;  // in [2^(bits−1), 2^bits), or 0 for input 0
  int exp = 0;       // input ≈ sig · 2^(exp − (bits − 1)), i.e. exp = msb index of the input
  bool inexact = false;  // bits were dropped (only when the input had more than `bits` bits)
};

namespace detail {

// normalize() for Round::HalfEven and 1 ≤ bits ≤ 63 in 64-bit words (docs/speed.md "The
// normalisation in 64-bit words"): the leading-zero count of the high (or, when it is 0, the low)
// word places the significand; the dropped bits are compared with a half in at most two words;
// the rounded significand is one 64-bit add. The same result as the generic u128 path below for
// every x < 2^127 (Normalize64.* in tests/model/fixed_test.cpp).
inline Normalized normalize_rne64(u128 x, int bits) {
  Normalized n;
  const uint64_t hi = (uint64_t)(x >> 64), lo = (uint64_t)x;
  uint64_t q;
  int cmp;  // dropped bits vs half an ulp of q: < 0, == 0 (a tie), > 0
  if (hi == 0) {
    if (lo == 0) return n;
    const int m = 63 - __builtin_clzll(lo);
    n.exp = m;
    const int shift = m - (bits - 1);
    if (shift <= 0) {
      n.sig = lo << (-shift);
      return n;
    }
    q = lo >> shift;  // 1 ≤ shift ≤ 63
    const uint64_t rem = lo & ((uint64_t{1} << shift) - 1), half = uint64_t{1} << (shift - 1);
    n.inexact = rem != 0;
    cmp = rem > half ? 1 : rem == half ? 0 : -1;
  } else {
    const int mh = 63 - __builtin_clzll(hi);
    n.exp = 64 + mh;
    const int shift = n.exp - (bits - 1);  // ≥ 2 (bits ≤ 63)
    if (shift >= 64) {                     // the significand lies in hi
      const int s = shift - 64;
      if (s == 0) {
        q = hi;
        n.inexact = lo != 0;
        const uint64_t half = uint64_t{1} << 63;
        cmp = lo > half ? 1 : lo == half ? 0 : -1;
      } else {
        q = hi >> s;
        const uint64_t rem = hi & ((uint64_t{1} << s) - 1), half = uint64_t{1} << (s - 1);
        n.inexact = rem != 0 || lo != 0;
        cmp = rem > half ? 1 : rem < half ? -1 : lo != 0 ? 1 : 0;
      }
    } else {  // 2 ≤ shift ≤ 63: q takes bits of both words
      q = (hi << (64 - shift)) | (lo >> shift);
      const uint64_t rem = lo & ((uint64_t{1} << shift) - 1), half = uint64_t{1} << (shift - 1);
      n.inexact = rem != 0;
      cmp = rem > half ? 1 : rem == half ? 0 : -1;
    }
  }
  q += rne_round_up(cmp, (q & 1) != 0) ? 1 : 0;
  if (q >> bits) {  // carry out of rounding: 1.111… → 10.000…
    q >>= 1;
    n.exp += 1;
  }
  n.sig = q;
  return n;
}

// The generic path of normalize() (any rounding mode, bits ≤ 64, x < 2^127).
inline Normalized normalize_u128(u128 x, int bits, Round r) {
  Normalized n;
  if (x == 0) return n;
  const int m = msb_index(x);
  n.exp = m;
  const int shift = m - (bits - 1);
  if (shift <= 0) {
    n.sig = (uint64_t)(x << (-shift));
    return n;
  }
  n.inexact = low_bits(x, shift) != 0;
  u128 s = (u128)shift_round((i128)x, shift, r);
  if (s >> bits) {  // carry out of rounding: 1.111… → 10.000…
    s >>= 1;
    n.exp += 1;
  }
  n.sig = (uint64_t)s;
  return n;
}

}  // namespace detail

// normalize(x, bits, Round::HalfEven) for values whose msb index m is known in advance — set up
// once where m is constant (the plane sums along a span: docs/speed.md "The fused span"), then
// each value is one add and one shift, no leading-zero count and no branch:
//   shift = m − (bits − 1) > 0: RNE(x·2^−shift) = (x + 2^(shift−1) − 1 + bit0(x >> shift)) >> shift
//   (below half: no carry into bit `shift`; above: one; exactly half: one iff the kept part is
//   odd), a carry-out to 2^bits renormalises (sig 2^(bits−1), exp m + 1);
//   shift ≤ 0: the exact left shift.
// Contract: 1 ≤ bits ≤ 63, 0 ≤ m ≤ 126; sig(x, e) needs msb(x) == m (x < 2^127) and returns
// normalize(x, bits, HalfEven).sig, e = its exp (Normalize64.AtKnownMsb* in tests/model/fixed_test.cpp).
struct NormalizeAtMsb {
  int bits = 1, m = 0, shift = 0;
  u128 bias = 0;  // 2^(shift−1) − 1 (shift > 0)
  NormalizeAtMsb() = default;
  NormalizeAtMsb(int bits_, int m_) : bits(bits_), m(m_), shift(m_ - (bits_ - 1)) {
    if (shift > 0) bias = ((u128)1 << (shift - 1)) - 1;
  }
  uint64_t sig(u128 x, int& e) const { return sig_bits(x, e, bits); }
  // The same with `bits` passed in (== this->bits): a constant where the caller knows it.
  // Always inlined: out of line it is a call per normalisation in the fused span's loop
  // (GCC's heuristics kept it out of line there, 6 % of the grazing plane's samples).
  [[gnu::always_inline]] uint64_t sig_bits(u128 x, int& e, int bits_) const {
    uint64_t q;
    if (shift >= 64) {  // the significand lies in the high word: 64-bit shifts only
      const int s = shift - 64;
      const uint64_t odd = ((uint64_t)(x >> 64) >> s) & 1;
      q = (uint64_t)((x + bias + odd) >> 64) >> s;
    } else if (shift > 0) {
      const uint64_t odd = (uint64_t)(x >> shift) & 1;
      q = (uint64_t)((x + bias + odd) >> shift);
    } else {
      e = m;
      return (uint64_t)x << (-shift);
    }
    const int carry = (int)(q >> bits_);  // 0 or 1
    q >>= carry;
    e = m + carry;
    return q;
  }
  // True when the significand lies above the low 64-bit word (shift > 64): rne_high_word applies
  // with high_shift() and high_bias().
  bool high_word() const { return shift > 64; }
  int high_shift() const { return shift - 64; }
  uint64_t high_bias() const { return (uint64_t)(bias >> 64); }
};

// NormalizeAtMsb's rounding in words only, for a shift above one word (docs/speed.md "Session 9:
// the pixel loop"): x = hi·2^W + lo (W = the Word's bits), shift = W + s with s ≥ 1. The bias
// 2^(shift−1) − 1 is hb·2^W + (2^W − 1) with hb = 2^(s−1) − 1, so in x + bias + bit_shift(x)
// the low word carries into the high one exactly when lo ≠ 0 or the odd bit (bit s of hi) is
// set, and what is left of the low word is shifted out:
//   (x + bias + odd) >> shift = (hi + hb + [lo ≠ 0 ∨ odd]) >> s.
// Contract: 1 ≤ s ≤ W − 2, hb = 2^(s−1) − 1, hi < 2^(W−1) (msb(x) ≤ 2W − 2: no overflow,
// hi + hb + 1 < 2^(W−1) + 2^(W−3)); returns RNE(x·2^−shift) before the carry-out
// renormalisation (2^bits possible), the value NormalizeAtMsb::sig_bits shifts back.
// tests/model/fixed_test.cpp: every x of two 8-bit words exhaustively, the 64-bit words at every
// msb × width with the directed ties (against GMP), 10^6 random; fixed_slow_test.cpp 10^8.
template <class Word>
constexpr Word rne_high_word(Word hi, Word lo, int s, Word hb) {
  const Word odd = (Word)((Word)(hi >> s) & 1u);
  const Word c = (Word)((lo | odd) != 0 ? 1 : 0);
  return (Word)((Word)(hi + hb + c) >> s);
}

// Contract: normalises x > 0 (x < 2^127) to a `bits`-bit significand with its msb set
//   (1 ≤ bits ≤ 64). Drops low bits by rounding mode r; if rounding carries out (sig == 2^bits),
//   renormalises (sig = 2^(bits−1), exp + 1). x == 0 gives sig 0, exp 0. Round::HalfEven with
//   bits ≤ 63 (every stage's use) takes the 64-bit-word path, the same results.
inline Normalized normalize(u128 x, int bits, Round r) {
  if (r == Round::HalfEven && bits <= 63) return detail::normalize_rne64(x, bits);
  return detail::normalize_u128(x, bits, r);
}

}  // namespace fxr
