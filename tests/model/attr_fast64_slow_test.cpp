// 10^8 random cases of each 64-bit path of stage 4's per-vertex arithmetic against its i128
// reference (slow label; docs/speed.md "Session 9: per triangle" gives the run's figures). The
// model-label proof with the exhaustive and directed cases is attr_fast64_test.cpp.
#include <cstdio>

#include "tests/model/attr_fast64_cases.hpp"

namespace fxr::fast64 {
namespace {

TEST(AttrFast64Slow, HundredMillionRandomCasesOfEachPathEqualTheReference) {
  const RandomRounds r = run_random_rounds(0xA77F64, 100000000);
  const Tally &rqp = r.rqp, &quot = r.quot, &rss = r.rss, &composed = r.composed, &align = r.align;
  std::printf("rne_quotient_plus64 %llu cases, %.1f %% fast; attr_quotient64 %llu, %.1f %%; round_scaled_sum64 %llu, "
              "%.1f %%; align_block %llu, %.1f %%; composed %llu; mismatches %llu\n",
              (unsigned long long)rqp.cases, 100.0 * (double)rqp.fast / (double)rqp.cases,
              (unsigned long long)quot.cases, 100.0 * (double)quot.fast / (double)quot.cases,
              (unsigned long long)rss.cases, 100.0 * (double)rss.fast / (double)rss.cases,
              (unsigned long long)align.cases, 100.0 * (double)align.fast / (double)align.cases,
              (unsigned long long)composed.cases,
              (unsigned long long)(rqp.mismatches + quot.mismatches + rss.mismatches + composed.mismatches +
                                   align.mismatches));
}

// attr_depth_q (its branchless int64 rounding, docs/speed.md "Session 12: per triangle"):
// 10^8 random z ≤ 2^40 of random magnitude per depth format against depth_q_reference.
TEST(AttrFast64Slow, AttrDepthQHundredMillionRandomCasesPerFormatEqualTheReference) {
  std::mt19937_64 g(0xD3B7510);
  uint64_t mismatches = 0;
  for (const DepthFormat f : {DepthFormat::D16, DepthFormat::D24}) {
    RasterConfig rc;
    rc.depth_format = f;
    const int db = rc.depth_bits();
    for (long i = 0; i < 100000000; ++i) {
      const uint64_t z = g() >> 24 >> (g() % 41);
      if (attr_depth_q(rc, z) != depth_q_reference(db, z)) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace fxr::fast64
