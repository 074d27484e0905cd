// The pixels of PixelDivide's tests (tests/model/pixel_divide_test.cpp, pixel_divide_slow_test.cpp):
// plane sums D, N_m by case family (every msb, RNE ties, carry-outs, zeros, D ≤ 0, negative N),
// the references (normalize_den + divide_varying, model/stages/divide.hpp, written with
// put_fragment_var) and deliberately broken references.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "model/arith/div.hpp"
#include "model/arith/fixed.hpp"
#include "model/config/config.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/fragment_store.hpp"

namespace fxr::pixel_divide_cases {

inline DivConfig div_shape(int nb, int db, int qb) {
  DivConfig c;
  c.num_bits = nb, c.den_bits = db, c.quot_bits = qb;
  return c;
}
inline std::string shape_name(const DivConfig& c) {
  return std::to_string(c.num_bits) + "/" + std::to_string(c.den_bits) + "/" + std::to_string(c.quot_bits);
}

inline u128 random128(std::mt19937_64& rng) { return ((u128)rng() << 64) | rng(); }
inline u128 below(int msb) { return msb <= 0 ? 0 : ((u128)1 << msb) - 1; }  // the bits under msb

// A magnitude with its msb at `msb` (−1: zero): random low bits, or the binade's ends.
inline u128 random_at_msb(std::mt19937_64& rng, int msb) {
  if (msb < 0) return 0;
  const u128 top = (u128)1 << msb;
  switch (rng() % 4) {
    case 0: return top;                 // a power of two
    case 1: return top | below(msb);    // the binade's last value
    default: return top | (random128(rng) & below(msb));
  }
}
// An exact tie of the RNE to `bits` bits at msb (sig · 2^s + 2^(s−1), s = msb − bits + 1 ≥ 1) of a
// significand of the given parity (even: rounds down, odd: up), or a random value where msb < bits.
inline u128 tie_at_msb(std::mt19937_64& rng, int msb, int bits, bool even) {
  const int s = msb - (bits - 1);
  if (s < 1) return random_at_msb(rng, msb);
  uint64_t sig = (uint64_t{1} << (bits - 1)) | (rng() & ((uint64_t{1} << (bits - 1)) - 1));
  sig = (sig & ~uint64_t{1}) | (even ? 0 : 1);
  return ((u128)sig << s) | ((u128)1 << (s - 1));
}
// A value whose RNE to `bits` bits carries out (rounds up to 2^bits): (2^bits − 1)·2^s plus a
// tie (variant 0), a random part above the tie (1) or all ones (2); s = msb − bits + 1 ≥ 1.
inline u128 carry_at_msb(std::mt19937_64& rng, int msb, int bits, int variant) {
  const int s = msb - (bits - 1);
  if (s < 1) return random_at_msb(rng, msb);
  const u128 hi = (u128)((uint64_t{1} << bits) - 1) << s, half = (u128)1 << (s - 1);
  switch (variant) {
    case 0: return hi | half;
    case 1: return hi | half | (random128(rng) & below(s - 1));
    default: return hi | below(s);
  }
}

// One pixel: D and N_m (two's complement) with the triangle's exponents.
struct PixelCase {
  u128 sums[1 + kMaxVaryings] = {};
  int den_exp = 0;
  int num_exp[kMaxVaryings] = {};

  PlaneSample sample(int nv) const {
    PlaneSample s;
    s.den = (i128)sums[0], s.den_exp = den_exp;
    for (int m = 0; m < nv; ++m) s.num[m] = (i128)sums[1 + m], s.num_exp[m] = num_exp[m];
    return s;
  }
  TriangleEquations tri(int nv) const {
    TriangleEquations t;
    t.interp.n = nv, t.interp.den_exp = den_exp;
    for (int m = 0; m < nv; ++m) t.interp.num_exp[m] = num_exp[m];
    return t;
  }
  std::string describe(int nv) const {
    std::ostringstream o;
    o << "D msb " << msb_of((i128)sums[0]) << " exp " << den_exp;
    for (int m = 0; m < nv; ++m) o << ", N" << m << " msb " << msb_of((i128)sums[1 + m]) << " exp " << num_exp[m];
    return o.str();
  }
  // The msb of |v| with its sign (0 for zero: "-0" never shows, "+0" is zero).
  static std::string msb_of(i128 v) {
    if (v == 0) return "zero";
    const u128 m = v < 0 ? (u128)0 - (u128)v : (u128)v;
    return (v < 0 ? "-" : "+") + std::to_string(msb_index(m));
  }
};

inline std::string words(const uint8_t* rec, int nv) {
  std::ostringstream o;
  for (int m = 0; m < nv; ++m) {
    const FxFloat v = get_fragment_var(rec, m);
    o << (m ? " " : "") << (v.neg ? "-" : "+") << v.sig << "e" << v.exp;
  }
  return o.str();
}

enum class Family { Random, Ties, CarryOut, ZeroN, DenNotPositive, Negative };
inline constexpr Family kAllFamilies[] = {Family::Random, Family::Ties, Family::CarryOut,
                                          Family::ZeroN, Family::DenNotPositive, Family::Negative};
inline const char* family_name(Family f) {
  switch (f) {
    case Family::Random: return "random";
    case Family::Ties: return "ties";
    case Family::CarryOut: return "carry-out";
    case Family::ZeroN: return "N = 0";
    case Family::DenNotPositive: return "D <= 0";
    case Family::Negative: return "negative N";
  }
  return "?";
}

inline u128 with_sign(u128 mag, bool neg) { return neg ? (u128)0 - mag : mag; }

// `count` pixels of family f for the divider shape dc (nv varyings; exponents in ±300).
inline std::vector<PixelCase> random_cases(const DivConfig& dc, int nv, size_t count, uint64_t seed, Family f) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + (uint64_t)f);
  const int nb = dc.num_bits, db = dc.den_bits;
  auto msb_any = [&] { return (int)(rng() % 127); };                      // 0 … 126
  auto msb_rounded = [&](int bits) { return bits + (int)(rng() % (uint64_t)(127 - bits)); };  // bits … 126
  auto exp_any = [&] { return (int)(rng() % 601) - 300; };
  std::vector<PixelCase> v(count);
  for (size_t i = 0; i < count; ++i) {
    PixelCase& p = v[i];
    p.den_exp = exp_any();
    for (int m = 0; m < kMaxVaryings; ++m) p.num_exp[m] = exp_any();
    u128 D = random_at_msb(rng, msb_any());
    for (int m = 0; m < nv; ++m) {
      const int k = (int)(rng() % 3);
      u128 N = random_at_msb(rng, rng() % 64 == 0 ? -1 : msb_any());
      bool neg = rng() % 2 == 0;
      switch (f) {
        case Family::Random: break;
        case Family::Ties:  // exact ties and their neighbours
          N = tie_at_msb(rng, msb_rounded(nb), nb, rng() % 2 == 0);
          if (k == 0) N -= 1;
          if (k == 2) N += 1;
          break;
        case Family::CarryOut:
          if (rng() % 3 != 0) N = carry_at_msb(rng, msb_rounded(nb), nb, (int)(rng() % 3));
          break;
        case Family::ZeroN:
          if (rng() % 2 == 0) N = 0;
          break;
        case Family::DenNotPositive: break;
        case Family::Negative:
          neg = true;
          if (rng() % 4 == 0) N = tie_at_msb(rng, msb_rounded(nb), nb, rng() % 2 == 0);
          if (rng() % 8 == 0) N = ((u128)1 << 127) - 1;  // the most negative sum in range
          if (rng() % 8 == 0) N = 1;
          break;
      }
      p.sums[1 + m] = with_sign(N, neg);
    }
    switch (f) {
      case Family::Ties: D = tie_at_msb(rng, msb_rounded(db), db, rng() % 2 == 0); break;
      case Family::CarryOut:
        if (rng() % 3 != 1) D = carry_at_msb(rng, msb_rounded(db), db, (int)(rng() % 3));
        break;
      default: break;
    }
    if (f == Family::DenNotPositive) {
      p.sums[0] = rng() % 4 == 0 ? 0 : with_sign(D == 0 ? 1 : D, true);
    } else {
      p.sums[0] = D == 0 ? 1 : D;  // D > 0
    }
  }
  return v;
}

// A reference writes the record words of one pixel (varyings 0 … nv − 1).
using RefWriter = std::function<void(const Config&, const PixelCase&, int, uint8_t*)>;

// The one reference (unbroken) and its deliberate breakages, each one case handled wrongly.
enum class Breakage {
  None,
  TiesHalfUp,         // N and D rounded half up (a tie of an even significand rounds up)
  CarryExponentLost,  // N's rounding carry-out renormalised without its exponent step
  SignLost,           // the quotient always positive
  DenMagnitude,       // D < 0 divided as |D| (instead of every varying 0)
  ZeroExponent,       // N = 0 written with the triangle's exponent instead of exponent 0
  MsbOffByOne,        // the exponent of N one too high where |N| ≥ 2^64
  TruncateDen,        // D truncated to den_bits instead of RNE
};
inline const char* breakage_name(Breakage b) {
  switch (b) {
    case Breakage::None: return "none";
    case Breakage::TiesHalfUp: return "ties half up";
    case Breakage::CarryExponentLost: return "carry exponent lost";
    case Breakage::SignLost: return "sign lost";
    case Breakage::DenMagnitude: return "D < 0 as |D|";
    case Breakage::ZeroExponent: return "N = 0 with an exponent";
    case Breakage::MsbOffByOne: return "msb off by one above 2^64";
    case Breakage::TruncateDen: return "D truncated";
  }
  return "?";
}

// normalize_den + divide_varying (DivideStage::step's functions) with breakage b, the varyings
// written with put_fragment_var.
inline void broken_reference_words(const Config& cfg, const PixelCase& p, int nv, uint8_t* rec, Breakage b) {
  const DivConfig& dc = cfg.div;
  const Round r = b == Breakage::TiesHalfUp ? Round::HalfUp : Round::HalfEven;
  i128 D = (i128)p.sums[0];
  if (b == Breakage::DenMagnitude && D < 0) D = -D;
  DenNorm dn = normalize_den(dc, D, p.den_exp);
  if (D > 0 && (b == Breakage::TiesHalfUp || b == Breakage::TruncateDen)) {
    const Normalized nd = normalize((u128)D, dc.den_bits, b == Breakage::TruncateDen ? Round::TruncZero : r);
    dn.d = nd.sig, dn.e = nd.exp + p.den_exp;
  }
  for (int m = 0; m < nv; ++m) {
    const i128 N = (i128)p.sums[1 + m];
    FxFloat out = divide_varying(dc, N, p.num_exp[m], dn);
    if (b != Breakage::None && N != 0 && dn.d != 0) {
      const u128 mag = N < 0 ? (u128)0 - (u128)N : (u128)N;
      Normalized nn = normalize(mag, dc.num_bits, r);
      if (b == Breakage::CarryExponentLost && nn.exp > msb_index(mag)) nn.exp -= 1;
      const DivSig q = div_sig_fast64(dc, nn.sig, dn.d);
      out.sig = q.sig;
      out.exp = q.exp_adj + (nn.exp + p.num_exp[m]) - dn.e - (dc.quot_bits - 1);
      if (b == Breakage::MsbOffByOne && msb_index(mag) >= 64) out.exp += 1;
      if (b == Breakage::SignLost) out.neg = false;
    }
    if (b == Breakage::ZeroExponent && N == 0 && dn.d != 0) out.exp = p.num_exp[m] - dn.e;
    put_fragment_var(rec, m, out.sig, out.exp, out.neg);
  }
}
inline void reference_words(const Config& cfg, const PixelCase& p, int nv, uint8_t* rec) {
  broken_reference_words(cfg, p, nv, rec, Breakage::None);
}

}  // namespace fxr::pixel_divide_cases
