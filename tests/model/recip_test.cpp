// Reciprocal unit (stage 3) against exact arithmetic. Every expected value comes from an
// independent integer division (or GMP rationals) written here, never from the measurement (analysis/measure.hpp).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "model/config/config.hpp"
#include "analysis/measure.hpp"
#include "model/stages/recip.hpp"
#include "recip_check.hpp"

using namespace fxr;
using namespace fxr::recip_check;


TEST(Recip, CorrectlyRoundedForAllMantissas) {
  // The default, every one of the 2^23 significands, through the public recip_sig, against
  // round-to-nearest of an exact integer division.
  const RecipConfig cfg;
  const int n = cfg.in_sig_bits, o = cfg.out_sig_bits;
  uint64_t wrong = 0, first_wrong = 0;
  for (uint64_t m = pow2(n - 1); m < pow2(n); ++m) {
    if (as_q(recip_sig(cfg, m)) != ref_round_q(n, o, m) && wrong++ == 0) first_wrong = m;
  }
  EXPECT_EQ(wrong, 0u) << "first at m=" << std::hex << first_wrong;
  // The same through the product-based check (also counts malformed significands).
  const Exhaustive r = check_all(cfg);
  EXPECT_EQ(r.count, pow2(n - 1));
  EXPECT_EQ(r.malformed, 0u);
  EXPECT_EQ(r.correctly_rounded, r.count);
  EXPECT_EQ(r.unfaithful, 0u);
}

TEST(Recip, MeasureReportsTheDefaultAsCorrectlyRounded) {
  const RecipConfig cfg;
  const ErrorStats st = measure(cfg);
  EXPECT_EQ(st.count, pow2(cfg.in_sig_bits - 1));
  EXPECT_EQ(st.correctly_rounded_share, 1.0);
  EXPECT_LE(st.max_err_ulp, 0.5);
  EXPECT_TRUE(st.faithful);
  // The proof behind the default: the a-priori bound covers the measured error and is below 1 ulp.
  const RecipBound cost = recip_bound(cfg);
  EXPECT_TRUE(cost.valid);
  EXPECT_LT(cost.error_bound_ulp, 1.0);
  EXPECT_LE(st.max_err_ulp_before_round, cost.error_bound_ulp);
}

TEST(Recip, SweepContainsTheDefault) {
  const auto configs = recip_sweep_configs();
  EXPECT_NE(std::find(configs.begin(), configs.end(), RecipConfig{}), configs.end());
}

// Every 61st significand here; recip_slow_test.cpp checks all of them.
TEST(Recip, ValidSweepConfigsAreFaithfulAndCorrectedOnesCorrectlyRoundedOnASubset) {
  int valid = 0;
  for (const RecipConfig& cfg : recip_sweep_configs()) {
    const RecipBound cost = recip_bound(cfg);
    if (!cost.valid) continue;
    ++valid;
    const Exhaustive r = check_all(cfg, 61);
    EXPECT_EQ(r.unfaithful, 0u) << recip_label(cfg);
    EXPECT_EQ(r.malformed, 0u) << recip_label(cfg);
    if (cfg.correction == RecipCorrection::Remainder) {
      EXPECT_EQ(r.correctly_rounded, r.count) << recip_label(cfg);
    }
  }
  EXPECT_GT(valid, 4);
}

TEST(Recip, ValidSmallConfigsAreCorrectlyRoundedAtOtherWidths) {
  // Narrow and asymmetric widths (o < n rounds some x slightly above 1 up to 1.0).
  for (const RecipConfig& cfg :
       {small_config(16, 16, 5, 6, 2, 19, RecipCorrection::Remainder),
        small_config(16, 10, 4, 5, 2, 14, RecipCorrection::Remainder),
        small_config(12, 18, 3, 5, 3, 22, RecipCorrection::Remainder),
        small_config(14, 14, 8, 9, 1, 17, RecipCorrection::Remainder),
        small_config(16, 10, 5, 6, 2, 16, RecipCorrection::None)}) {
    const RecipBound cost = recip_bound(cfg);
    ASSERT_TRUE(cost.valid) << recip_label(cfg) << " bound " << cost.error_bound_ulp;
    const Exhaustive r = check_all(cfg);
    EXPECT_EQ(r.malformed, 0u) << recip_label(cfg);
    EXPECT_EQ(r.unfaithful, 0u) << recip_label(cfg);
    if (cfg.correction == RecipCorrection::Remainder) {
      EXPECT_EQ(r.correctly_rounded, r.count) << recip_label(cfg);
    }
  }
}

TEST(Recip, MeasureAgreesWithIndependentCountOnANonFaithfulDesign) {
  // 32×7 seed + 2 NR without correction (docs/references.md#recip-designs: 94.5 % correctly rounded), a 30-bit datapath.
  const RecipConfig cfg = small_config(24, 24, 5, 7, 2, 30, RecipCorrection::None);
  const Exhaustive r = check_all(cfg);
  const ErrorStats st = measure(cfg);
  EXPECT_EQ(st.correctly_rounded_share, (double)r.correctly_rounded / (double)r.count);
  EXPECT_EQ(st.faithful, r.unfaithful == 0);
  EXPECT_FALSE(st.faithful);
  EXPECT_FALSE(recip_bound(cfg).valid);
}

TEST(Recip, SeedTableIsMinimaxOnItsGrid) {
  // GMP rationals: no neighbouring grid value has a smaller largest endpoint error.
  for (const auto& sk : {std::pair{6, 6}, std::pair{5, 7}, std::pair{3, 4}, std::pair{8, 8}}) {
    // Plain variables, not a structured binding: C++17 lambdas cannot capture those (clang).
    const int s = sk.first, k = sk.second;
    RecipConfig cfg;
    cfg.seed_index_bits = s;
    cfg.seed_frac_bits = k;
    const auto table = recip_seed_table(cfg);
    ASSERT_EQ(table.size(), pow2(s));
    for (uint64_t i = 0; i < table.size(); ++i) {
      ASSERT_LT(table[i], pow2(k));
      const mpq_class a(mpz_class((unsigned long)(pow2(s) + i)), mpz_class((unsigned long)pow2(s)));
      const mpq_class b(mpz_class((unsigned long)(pow2(s) + i + 1)), mpz_class((unsigned long)pow2(s)));
      auto worst = [&](int64_t grid) {
        const mpq_class y(mpz_class((long)grid), mpz_class((unsigned long)pow2(k + 1)));
        mpq_class ea = 1 - a * y, eb = 1 - b * y;
        ea.canonicalize();
        eb.canonicalize();
        return std::max(mpq_class(abs(ea)), mpq_class(abs(eb)));
      };
      const int64_t g = (int64_t)(pow2(k) + table[i]);
      const mpq_class w = worst(g);
      if (g > (int64_t)pow2(k)) {
        EXPECT_LE(w, worst(g - 1)) << "s=" << s << " i=" << i;
      }
      if (g + 1 < (int64_t)pow2(k + 1)) {
        EXPECT_LE(w, worst(g + 1)) << "s=" << s << " i=" << i;
      }
    }
  }
}

TEST(Recip, ZeroGivesDivByZeroAndSaturatedValueWithSign) {
  const RecipConfig cfg;
  for (bool neg : {false, true}) {
    FxFloat z;
    z.neg = neg;
    const RecipResult r = recip(cfg, z);
    EXPECT_TRUE(r.div_by_zero);
    EXPECT_FALSE(r.exp_overflow);
    EXPECT_EQ(r.value.neg, neg);
    EXPECT_EQ(r.value.sig, pow2(cfg.out_sig_bits) - 1);
    EXPECT_EQ(r.value.lead_exp(), recip_exp_max(cfg));
  }
}

TEST(Recip, NegativeInputNegatesTheResult) {
  const RecipConfig cfg;
  for (uint64_t m : {pow2(23), pow2(23) + 1, (pow2(24) - 1), uint64_t{0xABCDEF}}) {
    const FxFloat pos{false, m, -30}, neg{true, m, -30};
    const RecipResult a = recip(cfg, pos), b = recip(cfg, neg);
    EXPECT_FALSE(a.value.neg);
    EXPECT_TRUE(b.value.neg);
    EXPECT_EQ(a.value.sig, b.value.sig);
    EXPECT_EQ(a.value.exp, b.value.exp);
  }
}

TEST(Recip, PowersOfTwoAndNeighboursAreCorrectlyRounded) {
  const RecipConfig cfg;
  const int n = cfg.in_sig_bits, o = cfg.out_sig_bits;
  for (int e : {-100, -1, 0, 1, 37, recip_exp_max(cfg)}) {
    // w = 2^e exactly → 1/w = 2^−e exactly.
    const RecipResult r = recip(cfg, FxFloat{false, 1, e});
    EXPECT_FALSE(r.exp_overflow);
    EXPECT_EQ(r.value.sig, pow2(o - 1));
    EXPECT_EQ(r.value.lead_exp(), -e);
    // Neighbours: (1 + 2^−(n−1))·2^e and (2 − 2^−(n−1))·2^(e−1) (just above and below 2^e).
    for (uint64_t m : {pow2(n - 1) + 1, pow2(n) - 1}) {
      const int lead = m == pow2(n - 1) + 1 ? e : e - 1;
      const RecipResult q = recip(cfg, FxFloat{false, m, lead - (n - 1)});
      const uint64_t ref = ref_round_q(n, o, m);  // units of 2^−o, in (1/2, 1)
      EXPECT_EQ(q.value.sig, ref);
      EXPECT_EQ(q.value.lead_exp(), -lead - 1);
    }
  }
}

TEST(Recip, ExponentRangeEndsAndOverflowFlag) {
  const RecipConfig cfg;
  const int emin = recip_exp_min(cfg), emax = recip_exp_max(cfg), o = cfg.out_sig_bits;
  // w = 2^emin: 1/w = 2^−emin = 2^(emax+1) does not fit: flagged, saturated.
  RecipResult r = recip(cfg, FxFloat{false, 1, emin});
  EXPECT_TRUE(r.exp_overflow);
  EXPECT_FALSE(r.div_by_zero);
  EXPECT_EQ(r.value.sig, pow2(o) - 1);
  EXPECT_EQ(r.value.lead_exp(), emax);
  // w = 1.5·2^emin: 1/w = (4/3)·2^(emax) fits.
  r = recip(cfg, FxFloat{false, 3, emin - 1});
  EXPECT_FALSE(r.exp_overflow);
  EXPECT_EQ(r.value.lead_exp(), emax);
  // Largest w (lead exponent emax, all-ones significand): 1/w ∈ [2^emin, …) without underflow.
  r = recip(cfg, FxFloat{false, pow2(cfg.in_sig_bits) - 1, emax - (cfg.in_sig_bits - 1)});
  EXPECT_FALSE(r.exp_overflow);
  EXPECT_EQ(r.value.lead_exp(), emin);
  // Inputs outside the I/O exponent range are flagged.
  r = recip(cfg, FxFloat{false, 1, emax + 1});
  EXPECT_TRUE(r.exp_overflow);
  EXPECT_EQ(r.value.sig, pow2(o - 1));
  EXPECT_EQ(r.value.lead_exp(), emin);
  r = recip(cfg, FxFloat{false, 1, emin - 1});
  EXPECT_TRUE(r.exp_overflow);
  EXPECT_EQ(r.value.lead_exp(), emax);
}

TEST(Recip, DenormalFloat32InputsAreNormalisedExactly) {
  const RecipConfig cfg;
  const int n = cfg.in_sig_bits, o = cfg.out_sig_bits;
  for (uint32_t bits : {0x00000001u, 0x00000003u, 0x00400000u, 0x007FFFFFu, 0x00012345u}) {
    const F32Decoded d = decode_f32(bits);
    ASSERT_EQ(d.cls, F32Class::Denormal);
    const RecipResult r = recip(cfg, d.value);
    EXPECT_FALSE(r.exp_overflow);
    // Independent normalisation: frac · 2^−149 = m · 2^(lead − (n−1)).
    const int msb = 31 - __builtin_clz(bits);
    const uint64_t m = (uint64_t)bits << (n - 1 - msb);
    const int lead = -149 + msb;
    const uint64_t q = ref_round_q(n, o, m);
    if (q == pow2(o)) {
      EXPECT_EQ(r.value.sig, pow2(o - 1));
      EXPECT_EQ(r.value.lead_exp(), -lead);
    } else {
      EXPECT_EQ(r.value.sig, q) << std::hex << bits;
      EXPECT_EQ(r.value.lead_exp(), -lead - 1);
    }
  }
}

TEST(Recip, WideSignificandsAreRoundedToTheInputWidthFirst) {
  const RecipConfig cfg;
  const uint64_t m = 0xC00001;  // 24 bits
  const RecipResult exact = recip(cfg, FxFloat{false, m, 0});
  // Same value with 6 more zero bits: identical result.
  const RecipResult wide = recip(cfg, FxFloat{false, m << 6, -6});
  EXPECT_EQ(wide.value.sig, exact.value.sig);
  EXPECT_EQ(wide.value.exp, exact.value.exp);
  // m + ¼ ulp rounds down to m (RNE), m + ¾ ulp rounds up to m + 1.
  EXPECT_EQ(recip(cfg, FxFloat{false, (m << 2) | 1, -2}).value.sig, exact.value.sig);
  EXPECT_EQ(recip(cfg, FxFloat{false, (m << 2) | 3, -2}).value.sig,
            recip(cfg, FxFloat{false, m + 1, 0}).value.sig);
}

TEST(Recip, CostFieldsAreConsistent) {
  for (const RecipConfig& cfg : recip_sweep_configs()) {
    const StageCost c = recip_cost(cfg);
    const bool corr = cfg.correction == RecipCorrection::Remainder;
    // StageCost has no entries / width fields: the table is 2^s entries of k bits.
    const int64_t table_entries = (int64_t)pow2(cfg.seed_index_bits);
    EXPECT_EQ(c.table_bits, table_entries * cfg.seed_frac_bits);
    EXPECT_EQ((int64_t)recip_seed_table(cfg).size(), table_entries);
    EXPECT_EQ(c.ii, 1);
    // Seed register, two stages per NR step, rounding, and the correction stage.
    EXPECT_EQ(c.latency, 1 + 2 * cfg.nr_steps + 1 + (corr ? 1 : 0));
    EXPECT_EQ((int)c.multipliers.size(), 2 * cfg.nr_steps + (corr ? 1 : 0));
    int64_t bits = 0;
    for (const auto& [a, b] : c.multipliers) {
      EXPECT_GT(a, 0);
      EXPECT_GT(b, 0);
      bits += (int64_t)a * b;
    }
    EXPECT_EQ(c.mult_bits, bits);
    EXPECT_EQ(c.area_proxy(), c.table_bits + c.mult_bits);
  }
}

TEST(Recip, InconsistentConfigurationIsRejectedNamingTheField) {
  RecipConfig cfg;
  cfg.nr_frac_bits = cfg.out_sig_bits;
  try {
    recip_cost(cfg);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("nr_frac_bits"), std::string::npos) << e.what();
  }
  cfg = RecipConfig{};
  cfg.nr_steps = 7;
  EXPECT_THROW(recip_seed_table(cfg), ConfigError);
}

TEST(Recip, ConfigurationIsPartOfTheGlobalConfig) {
  const Config cfg;
  const nlohmann::json j = config_to_json(cfg);
  ASSERT_TRUE(j.contains("recip"));
  EXPECT_EQ(j["recip"]["seed_index_bits"], RecipConfig{}.seed_index_bits);
  EXPECT_EQ(j["recip"]["correction"], "remainder");
}
