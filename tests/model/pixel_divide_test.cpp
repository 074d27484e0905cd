// PixelDivide (model/stages/pixel_divide.hpp), stage 9 at one pixel, against the staged divider:
// DivideStage::step's Fragment (and normalize_den + divide_varying) written by put_fragment_var
// must give the same record words. Plane sums of every magnitude (msb 0 … 126) and sign, exact
// RNE ties and near-ties at num_bits / den_bits, the rounding carry-out (a significand rounding
// up to 2^bits), D ≤ 0, N = 0, default and other widths, 0–4 varyings; the planes of random
// set-up triangles at every pixel of their spans. Deliberate breakages of the reference (one
// case handled wrongly each) must be told apart on their case family, so each family reaches
// its case. 10^8 pixels: pixel_divide_slow_test.cpp.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "model/stages/divide.hpp"
#include "model/stages/pixel_divide.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/geometry.hpp"
#include "tests/model/random_tris.hpp"
#include "tests/model/pixel_divide_cases.hpp"

using namespace fxr;
using namespace fxr::pixel_divide_cases;

namespace {

// The staged divider's fragment for one pixel (a fresh DivideStage: no affine memo).
void staged_words(const Config& cfg, const PixelCase& p, int nv, uint8_t* rec) {
  DrawState st;
  st.num_varyings = nv;
  DivideStage ds(cfg, st, true);
  ds.step(p.sample(nv), [&](const Fragment& f) {
    for (int m = 0; m < nv; ++m) {
      ASSERT_TRUE(fragment_var_storable(f.var[m].sig, f.var[m].exp));
      put_fragment_var(rec, m, f.var[m].sig, f.var[m].exp, f.var[m].neg);
    }
  });
}

// Mismatches of PixelDivide against `ref` (record words of one pixel) over the cases; both
// records start as the same non-zero filler, so words PixelDivide fails to write show.
// report false: counted only (a deliberately broken reference is expected to differ).
uint64_t mismatches(const Config& cfg, int nv, const std::vector<PixelCase>& cases, const RefWriter& ref,
                    const std::string& what, bool report = true) {
  PixelDivide pd(cfg.div, nv);
  uint64_t bad = 0;
  const size_t bytes = fragment_record_bytes(kMaxVaryings);
  std::vector<uint8_t> want(bytes), got(bytes);
  for (const PixelCase& p : cases) {
    std::memset(want.data(), 0xA5, bytes);
    std::memset(got.data(), 0xA5, bytes);
    ref(cfg, p, nv, want.data());
    pd.begin(p.tri(nv));
    pd.write(got.data(), p.sums);
    if (want != got && ++bad <= 3 && report)
      ADD_FAILURE() << what << ": nv " << nv << " " << p.describe(nv) << " want " << words(want.data(), nv)
                    << " got " << words(got.data(), nv);
  }
  return bad;
}

const std::vector<DivConfig>& shapes() {
  static const std::vector<DivConfig> s = {div_shape(32, 32, 24), div_shape(24, 24, 16), div_shape(20, 39, 24),
                                           div_shape(39, 20, 24), div_shape(32, 32, 31), div_shape(8, 8, 6),
                                           div_shape(12, 12, 12), div_shape(4, 4, 4)};
  return s;
}

// The pixels of every span of `n` random triangles (tests/model/random_tris.hpp) as set up by
// the model: D and N_m = Plane::at(i, j) there.
std::vector<PixelCase> triangle_cases(const Config& cfg, int nv, int n, uint64_t seed, uint64_t& pixels) {
  DrawState st;
  st.viewport_x = 0, st.viewport_y = 0, st.viewport_w = 160, st.viewport_h = 120;
  st.num_varyings = nv;
  SetupStage setup(cfg, st, true);
  TraverseStage traverse(cfg, st);
  RasterStats gs;
  std::vector<SetupTriangle> pieces;
  std::vector<PixelCase> out;
  const std::vector<ClipTriangle> tris = random_tris(seed, n, nv);
  for (int t = 0; t < n; ++t) {
    const ClipTriangle& tri = tris[t];
    pieces.clear();
    geometry(cfg, st, tri, (uint32_t)t, pieces, gs);
    for (const SetupTriangle& s : pieces)
      setup.step(s, [&](const TriangleEquations& eq) {
        if (!divide_exponents_fit(eq, nv)) return;
        traverse.step(eq, [&](const Span& sp) {
          for (int i = sp.x0; i <= sp.x1; ++i) {
            PixelCase p;
            p.den_exp = eq.interp.den_exp;
            p.sums[0] = (u128)eq.interp.den.at(i, sp.y);
            for (int m = 0; m < nv; ++m) {
              p.num_exp[m] = eq.interp.num_exp[m];
              p.sums[1 + m] = (u128)eq.interp.num[m].at(i, sp.y);
            }
            out.push_back(p);
            ++pixels;
          }
        });
      });
  }
  return out;
}

Config with_div(const DivConfig& dc) {
  Config c;
  c.div = dc;
  return c;
}

}  // namespace

TEST(PixelDivide, AppliesWhereTheFusedSpanDoes) {
  EXPECT_TRUE(PixelDivide::applies(Config{}));
  DivConfig dc;
  dc.algorithm = DivAlgorithm::SharedRecip;
  EXPECT_FALSE(pixel_divide_applies(dc));
  EXPECT_FALSE(pixel_divide_applies(div_shape(40, 40, 24)));  // W + qb = 64
  EXPECT_TRUE(pixel_divide_applies(div_shape(39, 39, 24)));
  for (const DivConfig& s : shapes()) EXPECT_TRUE(pixel_divide_applies(s));
  EXPECT_TRUE(PixelDivide(DivConfig{}, 2).default_widths());
  EXPECT_FALSE(PixelDivide(div_shape(24, 24, 16), 2).default_widths());
}

// pixel_sig against normalize() (the staged normaliser) at every msb, with ties and carry-outs.
TEST(PixelDivide, PixelSigIsNormalizeAtEveryMsb) {
  std::mt19937_64 rng(7);
  for (int bits : {4, 8, 12, 20, 24, 31, 32, 39, 59, 62}) {
    uint64_t bad = 0, carries = 0, ties = 0;
    for (int msb = -1; msb <= 126; ++msb) {
      for (int k = 0; k < 200; ++k) {
        const u128 x = k < 100 ? random_at_msb(rng, msb) : k < 150 ? tie_at_msb(rng, msb, bits, k % 2 == 0)
                                                                   : carry_at_msb(rng, msb, bits, k % 3);
        int e;
        const uint64_t s = pixel_sig(x, bits, e);
        const Normalized n = normalize(x, bits, Round::HalfEven);
        // pixel_sig leaves a carry-out (2^bits, exponent of the msb) to its caller; normalize
        // renormalises it (2^(bits−1), exponent + 1).
        const bool carry = s == (uint64_t{1} << bits);
        carries += carry ? 1 : 0;
        ties += msb >= bits && k >= 100 && k < 150 ? 1 : 0;
        const uint64_t s_norm = carry ? s >> 1 : s;
        const int e_norm = carry ? e + 1 : e;
        if (x == 0) {
          if (s != 0 && ++bad <= 3) ADD_FAILURE() << "zero: " << s;
          continue;
        }
        if ((s_norm != n.sig || e_norm != n.exp) && ++bad <= 3)
          ADD_FAILURE() << "bits " << bits << " msb " << msb << ": " << s << "·2^" << e << " vs " << n.sig << "·2^" << n.exp;
      }
    }
    EXPECT_EQ(bad, 0u) << bits;
    EXPECT_GT(carries, 0u) << bits;
    EXPECT_GT(ties, 0u) << bits;
  }
}

TEST(PixelDivide, EqualsTheStagedDividerOnEveryMagnitudeAndSign) {
  for (const DivConfig& dc : shapes()) {
    const Config cfg = with_div(dc);
    for (int nv = 0; nv <= kMaxVaryings; ++nv) {
      if (nv > 4 && nv != kMaxVaryings) continue;
      const std::vector<PixelCase> cases = random_cases(dc, nv, 20000, 11 + nv, Family::Random);
      EXPECT_EQ(mismatches(cfg, nv, cases, staged_words, "random"), 0u) << shape_name(dc);
    }
  }
}

TEST(PixelDivide, EqualsTheStagedDividerOnTiesAndCarryOuts) {
  for (const DivConfig& dc : shapes()) {
    const Config cfg = with_div(dc);
    for (int nv : {1, 2, 4}) {
      for (Family f : {Family::Ties, Family::CarryOut}) {
        const std::vector<PixelCase> cases = random_cases(dc, nv, 20000, 23 + nv, f);
        EXPECT_EQ(mismatches(cfg, nv, cases, staged_words, family_name(f)), 0u) << shape_name(dc);
      }
    }
  }
}

TEST(PixelDivide, EqualsTheStagedDividerOnZerosAndNonPositiveDenominators) {
  for (const DivConfig& dc : shapes()) {
    const Config cfg = with_div(dc);
    for (int nv : {1, 2, 3, 4}) {
      for (Family f : {Family::ZeroN, Family::DenNotPositive, Family::Negative}) {
        const std::vector<PixelCase> cases = random_cases(dc, nv, 5000, 31 + nv, f);
        EXPECT_EQ(mismatches(cfg, nv, cases, staged_words, family_name(f)), 0u) << shape_name(dc);
      }
    }
  }
}

// normalize_den + divide_varying (the functions DivideStage calls) agree as well: the second
// reference, also the one the slow test uses.
TEST(PixelDivide, EqualsNormalizeDenAndDivideVarying) {
  for (const DivConfig& dc : shapes()) {
    const Config cfg = with_div(dc);
    for (Family f : kAllFamilies) {
      const std::vector<PixelCase> cases = random_cases(dc, 4, 5000, 41, f);
      EXPECT_EQ(mismatches(cfg, 4, cases, reference_words, family_name(f)), 0u) << shape_name(dc);
    }
  }
}

// nv = 0: nothing written (the record's varying bytes keep their filler).
TEST(PixelDivide, WritesNothingWithoutVaryings) {
  const std::vector<PixelCase> cases = random_cases(DivConfig{}, 0, 100, 5, Family::Random);
  PixelDivide pd(DivConfig{}, 0);
  std::vector<uint8_t> rec(fragment_record_bytes(kMaxVaryings), 0x5A), before = rec;
  for (const PixelCase& p : cases) {
    pd.begin(p.tri(0));
    pd.write(rec.data(), p.sums);
  }
  EXPECT_TRUE(rec == before);
}

// The compile-time paths (write_t with NV and the default widths as constants) and the run-time
// ones write the same words.
TEST(PixelDivide, TemplatePathsAgree) {
  const DivConfig dc;
  for (int nv = 1; nv <= 4; ++nv) {
    const std::vector<PixelCase> cases = random_cases(dc, nv, 20000, 51 + nv, Family::Random);
    PixelDivide pd(dc, nv);
    const size_t bytes = fragment_record_bytes(kMaxVaryings);
    std::vector<uint8_t> a(bytes, 0), b(bytes, 0), c(bytes, 0);
    uint64_t bad = 0;
    for (const PixelCase& p : cases) {
      pd.begin(p.tri(nv));
      pd.write(a.data(), p.sums);
      pd.write_t<-1>(b.data(), p.sums, pd.widths());
      switch (nv) {
        case 1: pd.write_t<1>(c.data(), p.sums, DefaultDivWidths{}); break;
        case 2: pd.write_t<2>(c.data(), p.sums, DefaultDivWidths{}); break;
        default: pd.write_t<-1>(c.data(), p.sums, DefaultDivWidths{}); break;
      }
      bad += a != b || a != c ? 1 : 0;
    }
    EXPECT_EQ(bad, 0u) << nv;
  }
}

// The divisor's part taken ahead (den() of the next pixel before this one's write, as a kernel
// hides the division's latency) writes the same words; D ≤ 0 gives a placeholder, not positive.
TEST(PixelDivide, DenAheadWritesTheSameWords) {
  for (const DivConfig& dc : {div_shape(32, 32, 24), div_shape(20, 39, 24)}) {
    const int nv = 3;
    std::vector<PixelCase> cases = random_cases(dc, nv, 5000, 81, Family::Random);
    const std::vector<PixelCase> more = random_cases(dc, nv, 5000, 82, Family::DenNotPositive);
    cases.insert(cases.end(), more.begin(), more.end());
    PixelDivide pd(dc, nv);
    const size_t bytes = fragment_record_bytes(kMaxVaryings);
    std::vector<uint8_t> a(bytes, 0), b(bytes, 0);
    uint64_t bad = 0, nonpos = 0;
    PixelDivide::Den next = PixelDivide::den(cases[0].sums[0], pd.widths());
    for (size_t k = 0; k < cases.size(); ++k) {
      const PixelDivide::Den cur = next;
      if (k + 1 < cases.size()) next = PixelDivide::den(cases[k + 1].sums[0], pd.widths());
      nonpos += cur.pos ? 0 : 1;
      bad += cur.pos != ((i128)cases[k].sums[0] > 0) ? 1 : 0;
      pd.begin(cases[k].tri(nv));
      pd.write(a.data(), cases[k].sums);
      pd.write_t<-1>(b.data(), cases[k].sums + 1, cur, pd.widths());
      bad += a != b ? 1 : 0;
    }
    EXPECT_EQ(bad, 0u) << shape_name(dc);
    EXPECT_EQ(nonpos, 5000u);
  }
}

// The planes of set-up triangles (small and large, perspective, some clipped), every pixel of every span.
TEST(PixelDivide, EqualsTheStagedDividerOnTrianglePlanes) {
  for (const DivConfig& dc : {div_shape(32, 32, 24), div_shape(24, 24, 16), div_shape(20, 39, 24)}) {
    const Config cfg = with_div(dc);
    for (int nv : {1, 2, 4}) {
      uint64_t pixels = 0;
      const std::vector<PixelCase> cases = triangle_cases(cfg, nv, 40, 61 + nv, pixels);
      EXPECT_GT(pixels, 10000u);
      EXPECT_EQ(mismatches(cfg, nv, cases, staged_words, "triangles"), 0u) << shape_name(dc);
    }
  }
}

// Deliberate breakages: a reference that handles one case wrongly must differ from PixelDivide
// on the case family made for it (so a PixelDivide with that bug would fail the tests above),
// while the true reference does not.
TEST(PixelDivide, BreakagesAreCaught) {
  struct B {
    Breakage b;
    Family f;
  };
  const B all[] = {B{Breakage::TiesHalfUp, Family::Ties}, B{Breakage::CarryExponentLost, Family::CarryOut},
                   B{Breakage::SignLost, Family::Negative}, B{Breakage::DenMagnitude, Family::DenNotPositive},
                   B{Breakage::ZeroExponent, Family::ZeroN}, B{Breakage::MsbOffByOne, Family::Random},
                   B{Breakage::TruncateDen, Family::Random}};
  uint64_t total[16] = {};
  // The pre-roundings (ties, truncation) move the quotient by ≤ 2^(qb−nb) ulp: visible at the
  // default widths only rarely, always where nb ≈ qb; counted over the three shapes.
  for (const DivConfig& dc : {div_shape(32, 32, 24), div_shape(12, 12, 12), div_shape(8, 8, 6)}) {
    const Config cfg = with_div(dc);
    for (const B& k : all) {
      const std::vector<PixelCase> cases = random_cases(dc, 2, 4000, 71, k.f);
      const RefWriter broken = [&](const Config& c, const PixelCase& p, int nv, uint8_t* rec) {
        broken_reference_words(c, p, nv, rec, k.b);
      };
      total[(int)k.b] += mismatches(cfg, 2, cases, broken, breakage_name(k.b), false);
      EXPECT_EQ(mismatches(cfg, 2, cases, reference_words, "reference"), 0u) << shape_name(dc);
    }
  }
  for (const B& k : all) EXPECT_GT(total[(int)k.b], 0u) << breakage_name(k.b);
}
