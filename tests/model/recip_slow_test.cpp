// Exhaustive check of every configuration the sweep marks valid (a few seconds of CPU: label slow).
// The a-priori bound (recip_bound().valid) claims: remainder → correctly rounded, none → faithful.
#include <gtest/gtest.h>

#include "analysis/measure.hpp"
#include "model/stages/recip.hpp"
#include "recip_check.hpp"

using namespace fxr;
using namespace fxr::recip_check;

TEST(RecipSlow, ValidSweepConfigsAreFaithfulAndCorrectedOnesCorrectlyRoundedForAllMantissas) {
  int valid = 0;
  for (const RecipConfig& cfg : recip_sweep_configs()) {
    if (!recip_bound(cfg).valid) continue;
    ++valid;
    const Exhaustive r = check_all(cfg);
    EXPECT_EQ(r.count, pow2(cfg.in_sig_bits - 1));
    EXPECT_EQ(r.unfaithful, 0u) << recip_label(cfg);
    EXPECT_EQ(r.malformed, 0u) << recip_label(cfg);
    if (cfg.correction == RecipCorrection::Remainder) {
      EXPECT_EQ(r.correctly_rounded, r.count) << recip_label(cfg);
    }
  }
  EXPECT_GT(valid, 4);
}
