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

}  // namespace
}  // namespace fxr::fast64
