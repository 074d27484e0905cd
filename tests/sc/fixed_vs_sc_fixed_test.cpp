// model/arith/fixed.hpp against SystemC's own fixed-point types (the oracle): conversion between
// formats (fxr::convert), multiply (mul_wide + convert) and multiply-accumulate (fxr::mac)
// must give bit-identical codes to sc_fix / sc_ufix / sc_fixed / sc_ufixed for every
// quantisation mode (SC_TRN, SC_TRN_ZERO, SC_RND, SC_RND_CONV, SC_RND_INF) and overflow mode
// (SC_WRAP, SC_SAT), on directed edge values and on 10^6+ random values spread over formats
// of width 1..63 with the binary point anywhere (frac < 0 and frac > width included).
//
// How a code crosses into SystemC and back (kept independent of the code under test):
//   in:  sc_fxval(int64 hi)·2^64 + sc_fxval(uint64 lo), then >> frac — exact in sc_fxval;
//   out: the raw bits of the sc_fxnum read one by one with operator[] (bit 0 = LSB of the
//        wl-bit word), sign-extended for signed formats. (sc_fxval::to_int64() is not used:
//        in SystemC 2.3.4 it returns 0 for −2^63.)
#define SC_INCLUDE_FX
#include <systemc.h>

#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <vector>

#include "model/arith/fixed.hpp"

// libsystemc.so defines main() and calls sc_main(); these tests use the fixed-point library
// only, from GoogleTest's main, so sc_main just has to exist for the link.
int sc_main(int, char*[]) { return 0; }

using namespace fxr;

namespace {

constexpr Round kRounds[] = {Round::Trunc, Round::TruncZero, Round::HalfUp, Round::HalfEven,
                             Round::HalfAway};
constexpr Overflow kOverflows[] = {Overflow::Wrap, Overflow::Saturate};

// Widest format exercised (the brief: widths 1..63, so every code fits int64 either way).
constexpr int kMaxTestWidth = 63;
// How far the binary point may sit outside the word in random formats: frac in
// [−kFracOutside, width + kFracOutside].
constexpr int kFracOutside = 12;

sc_q_mode to_sc(Round r) {
  switch (r) {
    case Round::Trunc: return SC_TRN;
    case Round::TruncZero: return SC_TRN_ZERO;
    case Round::HalfUp: return SC_RND;
    case Round::HalfEven: return SC_RND_CONV;
    case Round::HalfAway: return SC_RND_INF;
  }
  return SC_TRN;
}
sc_o_mode to_sc(Overflow o) { return o == Overflow::Wrap ? SC_WRAP : SC_SAT; }

sc_fxtype_params sc_params(const FxFormat& f) {
  return sc_fxtype_params(f.width, f.width - f.frac, to_sc(f.round), to_sc(f.overflow));
}

// Exact value code · 2^−frac as an sc_fxval.
sc_fxval to_fxval(i128 code, int frac) {
  const int64 hi = (int64)(code >> 64);
  const uint64 lo = (uint64)(u128)code;
  sc_fxval v = (sc_fxval(hi) << 64) + sc_fxval(lo);
  return frac >= 0 ? (v >> frac) : (v << -frac);
}

// The raw code of an sc_fxnum, read bit by bit.
int64_t raw_code(const sc_fxnum& x, int width, bool is_signed) {
  uint64_t u = 0;
  for (int i = 0; i < width; ++i)
    if (x[i]) u |= uint64_t(1) << i;
  if (is_signed && width < 64 && ((u >> (width - 1)) & 1)) u |= ~uint64_t(0) << width;
  return (int64_t)u;
}

// The sc_fix (signed) or sc_ufix (unsigned) of format f holding value v, quantised by
// SystemC; `body` sees it as an sc_fxnum.
template <class Body>
void with_sc_num(const FxFormat& f, Body&& body) {
  if (f.is_signed) {
    sc_fix x(sc_params(f));
    body(static_cast<sc_fxnum&>(x));
  } else {
    sc_ufix x(sc_params(f));
    body(static_cast<sc_fxnum&>(x));
  }
}

// SystemC's answer for: assign the exact value `v` to a variable of format `dst`.
int64_t sc_assign(const sc_fxval& v, const FxFormat& dst) {
  int64_t out = 0;
  with_sc_num(dst, [&](sc_fxnum& x) {
    x = v;
    out = raw_code(x, dst.width, dst.is_signed);
  });
  return out;
}

// An operand held in SystemC in its own format (checks the code survives the trip: the
// operand is representable, so SystemC must keep it exactly).
struct ScOperand {
  FxFormat fmt;
  int64_t code;
};

std::string fmt_name(const FxFormat& f) {
  std::ostringstream os;
  os << (f.is_signed ? "sc_fix<" : "sc_ufix<") << f.width << "," << f.width - f.frac << ","
     << to_string(f.round) << "," << to_string(f.overflow) << "> (frac " << f.frac << ")";
  return os.str();
}

std::string i128_str(i128 v) {
  if (v == 0) return "0";
  const bool neg = v < 0;
  u128 m = neg ? (u128)0 - (u128)v : (u128)v;
  std::string s;
  while (m) {
    s.insert(s.begin(), char('0' + (int)(m % 10)));
    m /= 10;
  }
  return neg ? "-" + s : s;
}

// A random code of format f, biased towards the ends of the range and small values.
int64_t random_code(std::mt19937_64& rng, const FxFormat& f) {
  const uint64_t r = rng();
  const int width_used = 1 + (int)(rng() % f.width);  // spread magnitudes over all scales
  uint64_t u = f.width >= 64 ? r : (r & ((uint64_t(1) << f.width) - 1));
  switch (rng() % 8) {
    case 0: return std::max(f.min_code(), f.max_code() - (int64_t)(rng() % 3));
    case 1: return std::min(f.max_code(), f.min_code() + (int64_t)(rng() % 3));
    case 2: u &= (width_used >= 64 ? ~uint64_t(0) : ((uint64_t(1) << width_used) - 1)); break;
    default: break;
  }
  if (f.is_signed && f.width < 64 && ((u >> (f.width - 1)) & 1)) u |= ~uint64_t(0) << f.width;
  if (!f.is_signed) return (int64_t)u;
  if (rng() % 4 == 0 && width_used < f.width) {  // small negative / positive values
    const int64_t m = (int64_t)(u & ((uint64_t(1) << width_used) - 1));
    return (rng() & 1) ? -m : m;
  }
  return (int64_t)u;
}

FxFormat random_format(std::mt19937_64& rng, int max_width = kMaxTestWidth) {
  FxFormat f;
  f.width = 1 + (int)(rng() % max_width);
  f.frac = -kFracOutside + (int)(rng() % (f.width + 2 * kFracOutside + 1));
  f.is_signed = rng() % 4 != 0;
  f.round = kRounds[rng() % 5];
  f.overflow = kOverflows[rng() % 2];
  return f;
}

// Conversion: a source code with frac `sf` into dst, ours against SystemC.
void expect_convert(i128 src, int sf, const FxFormat& dst) {
  const int64_t ours = convert(src, sf, dst);
  const int64_t theirs = sc_assign(to_fxval(src, sf), dst);
  ASSERT_EQ(ours, theirs) << "convert src=" << i128_str(src) << "·2^-" << sf << " into "
                          << fmt_name(dst);
}

// Multiply: a·b (exact) assigned to dst.
void expect_mul(const ScOperand& a, const ScOperand& b, const FxFormat& dst) {
  const int64_t ours = convert(mul_wide(a.code, b.code), a.fmt.frac + b.fmt.frac, dst);
  int64_t theirs = 0;
  with_sc_num(a.fmt, [&](sc_fxnum& sa) {
    sa = to_fxval(a.code, a.fmt.frac);
    ASSERT_EQ(raw_code(sa, a.fmt.width, a.fmt.is_signed), a.code) << "operand a " << fmt_name(a.fmt);
    with_sc_num(b.fmt, [&](sc_fxnum& sb) {
      sb = to_fxval(b.code, b.fmt.frac);
      ASSERT_EQ(raw_code(sb, b.fmt.width, b.fmt.is_signed), b.code) << "operand b " << fmt_name(b.fmt);
      theirs = sc_assign(sa * sb, dst);
    });
  });
  ASSERT_EQ(ours, theirs) << "mul a=" << a.code << " (" << fmt_name(a.fmt) << ") b=" << b.code << " ("
                          << fmt_name(b.fmt) << ") into " << fmt_name(dst);
}

// Multiply-accumulate: a·b + c assigned to dst (one quantisation, as `dst = a * b + c`).
void expect_mac(const ScOperand& a, const ScOperand& b, const ScOperand& c, const FxFormat& dst) {
  const int64_t ours = mac(a.code, a.fmt.frac, b.code, b.fmt.frac, c.code, c.fmt.frac, dst);
  int64_t theirs = 0;
  with_sc_num(a.fmt, [&](sc_fxnum& sa) {
    sa = to_fxval(a.code, a.fmt.frac);
    ASSERT_EQ(raw_code(sa, a.fmt.width, a.fmt.is_signed), a.code) << "operand a " << fmt_name(a.fmt);
    with_sc_num(b.fmt, [&](sc_fxnum& sb) {
      sb = to_fxval(b.code, b.fmt.frac);
      ASSERT_EQ(raw_code(sb, b.fmt.width, b.fmt.is_signed), b.code) << "operand b " << fmt_name(b.fmt);
      with_sc_num(c.fmt, [&](sc_fxnum& sc) {
        sc = to_fxval(c.code, c.fmt.frac);
        ASSERT_EQ(raw_code(sc, c.fmt.width, c.fmt.is_signed), c.code) << "operand c " << fmt_name(c.fmt);
        theirs = sc_assign(sa * sb + sc, dst);
      });
    });
  });
  ASSERT_EQ(ours, theirs) << "mac a=" << a.code << " (" << fmt_name(a.fmt) << ") b=" << b.code << " ("
                          << fmt_name(b.fmt) << ") c=" << c.code << " (" << fmt_name(c.fmt) << ") into "
                          << fmt_name(dst);
}

// Directed sources around one destination format: its extreme codes, one past them, zero,
// ±1, each shifted up by k extra fraction bits and offset by the tie (half an ulp of dst),
// the tie ± 1 source ulp, and ± one source ulp.
std::vector<i128> edge_sources(const FxFormat& dst, int k) {
  const i128 one = ((i128)1) << k;
  const i128 half = k > 0 ? ((i128)1) << (k - 1) : 0;
  const i128 bases[] = {dst.max_code(), (i128)dst.max_code() + 1, dst.min_code(), (i128)dst.min_code() - 1,
                        0, 1, -1, 2, -2, (i128)dst.max_code() / 2, (i128)dst.min_code() / 2};
  std::vector<i128> out;
  for (i128 b : bases) {
    const i128 s = b * one;
    out.push_back(s);
    if (k > 0) {
      for (i128 off : {half, -half, half + 1, half - 1, -half + 1, -half - 1, (i128)1, (i128)-1})
        out.push_back(s + off);
    }
  }
  return out;
}

}  // namespace

TEST(FixedVsScFixed, ConvertMatchesOnEdgeValuesOfEveryWidthAndMode) {
  // Every width 1..63; the binary point inside, left of and right of the word; every mode;
  // sources 0, 1, 2, 5, 30 bits finer than the destination (0: exact, overflow only).
  int64_t checked = 0;
  for (int w = 1; w <= kMaxTestWidth; ++w) {
    for (int frac : {0, w / 2, w, -3, w + 5}) {
      for (bool s : {true, false}) {
        for (Round r : kRounds) {
          for (Overflow o : kOverflows) {
            const FxFormat dst{w, frac, s, r, o};
            for (int k : {0, 1, 2, 5, 30}) {
              for (i128 src : edge_sources(dst, k)) {
                expect_convert(src, frac + k, dst);
                if (HasFatalFailure()) return;
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  RecordProperty("checked", (int)checked);
}

TEST(FixedVsScFixed, ConvertMatchesOnRandomValuesAcrossFormats) {
  std::mt19937_64 rng(20240601);
  constexpr int kCount = 1000000;
  for (int i = 0; i < kCount; ++i) {
    const FxFormat dst = random_format(rng);
    // Source: up to 120 significant bits with its point 0..60 bits finer or up to 8 coarser
    // than the destination.
    const int sf = dst.frac - 8 + (int)(rng() % 69);
    const int src_bits = 1 + (int)(rng() % 120);
    i128 src = (i128)(((unsigned __int128)rng() << 64) | rng());  // same bits, no negative left shift
    src >>= (128 - src_bits);  // arithmetic: signed value of src_bits bits
    expect_convert(src, sf, dst);
    if (HasFatalFailure()) return;
  }
}

TEST(FixedVsScFixed, MultiplyMatchesOnRandomValuesAcrossFormats) {
  std::mt19937_64 rng(7);
  constexpr int kCount = 300000;
  for (int i = 0; i < kCount; ++i) {
    const FxFormat fa = random_format(rng), fb = random_format(rng), dst = random_format(rng);
    expect_mul({fa, random_code(rng, fa)}, {fb, random_code(rng, fb)}, dst);
    if (HasFatalFailure()) return;
  }
}

TEST(FixedVsScFixed, MacMatchesOnRandomValuesAcrossFormats) {
  std::mt19937_64 rng(8);
  constexpr int kCount = 300000;
  for (int i = 0; i < kCount; ++i) {
    const FxFormat fa = random_format(rng), fb = random_format(rng), dst = random_format(rng);
    // fxr::mac's contract: c's fraction ≤ fa + fb (c aligns by a left shift), and the aligned
    // c must fit the i128 accumulator: width_c + (fa + fb − fc) ≤ 125.
    FxFormat fc = random_format(rng);
    const int fp = fa.frac + fb.frac;
    fc.frac = fp - (int)(rng() % std::min(40, 126 - fc.width));
    expect_mac({fa, random_code(rng, fa)}, {fb, random_code(rng, fb)}, {fc, random_code(rng, fc)}, dst);
    if (HasFatalFailure()) return;
  }
}

TEST(FixedVsScFixed, MultiplyAndMacMatchOnExtremeOperands) {
  // Products of the extreme codes of a format with itself and with ±1 ulp, into destinations
  // that keep all bits, drop half of them (ties appear) or overflow; every mode.
  std::vector<int64_t> picks;
  for (int w = 1; w <= kMaxTestWidth; w += (w < 8 ? 1 : 5)) {
    for (bool s : {true, false}) {
      const FxFormat f{w, w / 2, s, Round::Trunc, Overflow::Wrap};
      picks.clear();
      for (int64_t c : {f.max_code(), f.min_code(), int64_t(0), int64_t(1), int64_t(-1), f.max_code() - 1,
                        f.min_code() + 1})
        if (c >= f.min_code() && c <= f.max_code()) picks.push_back(c);
      for (Round r : kRounds) {
        for (Overflow o : kOverflows) {
          const FxFormat dsts[] = {{std::min(63, 2 * w), 2 * (w / 2), s, r, o},
                                   {w, w / 2, s, r, o},
                                   {std::max(1, w / 2), w / 2, s, r, o},
                                   {w, w + 3, s, r, o}};
          for (const FxFormat& dst : dsts) {
            for (int64_t a : picks) {
              for (int64_t b : picks) {
                expect_mul({f, a}, {f, b}, dst);
                for (int64_t c : picks) expect_mac({f, a}, {f, b}, {f, c}, dst);
                if (HasFatalFailure()) return;
              }
            }
          }
        }
      }
    }
  }
}

// ---- the templated sc_fixed / sc_ufixed types themselves (compile-time formats) ----------

namespace {

// One templated format W (word length), I (integer bits), signedness, with all modes:
// convert random sources, multiply and multiply-accumulate Q16.16-style operands into it.
template <int W, int I, bool S, sc_q_mode Q, sc_o_mode O>
struct Tfmt {
  using type = std::conditional_t<S, sc_fixed<W, I, Q, O>, sc_ufixed<W, I, Q, O>>;
};

Round from_sc(sc_q_mode q) {
  switch (q) {
    case SC_TRN: return Round::Trunc;
    case SC_TRN_ZERO: return Round::TruncZero;
    case SC_RND: return Round::HalfUp;
    case SC_RND_CONV: return Round::HalfEven;
    default: return Round::HalfAway;
  }
}

template <int W, int I, bool S, sc_q_mode Q, sc_o_mode O>
void check_templated(std::mt19937_64& rng, int count) {
  using T = typename Tfmt<W, I, S, Q, O>::type;
  const FxFormat dst{W, W - I, S, from_sc(Q), O == SC_WRAP ? Overflow::Wrap : Overflow::Saturate};
  // Operands: sc_fixed<32,16> (Q16.16, the bench's format) with a fixed rounding.
  const FxFormat q16{32, 16, true, Round::Trunc, Overflow::Wrap};
  for (int i = 0; i < count; ++i) {
    // conversion of an exact value with 0..40 extra fraction bits
    const int sf = dst.frac + (int)(rng() % 41) - 4;
    const i128 src = (i128)(int64_t)rng() >> (rng() % 64);
    T t;
    t = to_fxval(src, sf);
    ASSERT_EQ(convert(src, sf, dst), raw_code(t, W, S))
        << "sc_fixed<" << W << "," << I << "> convert " << i128_str(src) << "·2^-" << sf;
    const int64_t a = random_code(rng, q16), b = random_code(rng, q16), c = random_code(rng, q16);
    sc_fixed<32, 16, SC_TRN, SC_WRAP> sa, sb, sc;
    sa = to_fxval(a, 16);
    sb = to_fxval(b, 16);
    sc = to_fxval(c, 16);
    T p = sa * sb;
    ASSERT_EQ(convert(mul_wide(a, b), 32, dst), raw_code(p, W, S)) << "sc_fixed<" << W << "," << I << "> mul";
    T m = sa * sb + sc;
    ASSERT_EQ(mac(a, 16, b, 16, c, 16, dst), raw_code(m, W, S)) << "sc_fixed<" << W << "," << I << "> mac";
  }
}

template <int W, int I, bool S>
void check_templated_all_modes(std::mt19937_64& rng, int count) {
  check_templated<W, I, S, SC_TRN, SC_WRAP>(rng, count);
  check_templated<W, I, S, SC_TRN, SC_SAT>(rng, count);
  check_templated<W, I, S, SC_TRN_ZERO, SC_WRAP>(rng, count);
  check_templated<W, I, S, SC_TRN_ZERO, SC_SAT>(rng, count);
  check_templated<W, I, S, SC_RND, SC_WRAP>(rng, count);
  check_templated<W, I, S, SC_RND, SC_SAT>(rng, count);
  check_templated<W, I, S, SC_RND_CONV, SC_WRAP>(rng, count);
  check_templated<W, I, S, SC_RND_CONV, SC_SAT>(rng, count);
  check_templated<W, I, S, SC_RND_INF, SC_WRAP>(rng, count);
  check_templated<W, I, S, SC_RND_INF, SC_SAT>(rng, count);
}

}  // namespace

TEST(FixedVsScFixed, TemplatedScFixedFormatsMatchInEveryMode) {
  std::mt19937_64 rng(99);
  constexpr int kPerMode = 3000;
  check_templated_all_modes<32, 16, true>(rng, kPerMode);   // Q16.16
  check_templated_all_modes<24, 1, false>(rng, kPerMode);   // u1.23 significand-like
  check_templated_all_modes<16, 8, true>(rng, kPerMode);    // narrow: the mac overflows
  check_templated_all_modes<1, 1, true>(rng, kPerMode);     // one bit: values −1, 0
  check_templated_all_modes<1, 0, false>(rng, kPerMode);    // one bit: values 0, 1/2
  check_templated_all_modes<12, 20, true>(rng, kPerMode);   // frac −8 < 0: lsb is 256
  check_templated_all_modes<10, -6, false>(rng, kPerMode);  // frac 16 > width
  check_templated_all_modes<63, 31, true>(rng, kPerMode);   // widest tested
  check_templated_all_modes<63, 1, false>(rng, kPerMode);
  if (HasFatalFailure()) return;
}
