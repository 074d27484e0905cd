// 10^8 random cases of each 64-bit path of stage 4's per-vertex arithmetic against its i128
// reference (slow label; docs/speed.md "Session 9: per triangle" gives the run's figures). The
// model-label proof with the exhaustive and directed cases is attr_fast64_test.cpp.
#include <cstdio>

#include "tests/model/attr_fast64_cases.hpp"

namespace fxr::fast64 {
namespace {

TEST(AttrFast64Slow, HundredMillionRandomCasesOfEachPathEqualTheReference) {
  std::mt19937_64 g(0xA77F64);
  Tally rqp, quot, rss, composed, align;
  for (long i = 0; i < 100000000; ++i) random_round(g, rqp, quot, rss, composed, align);
  expect_clean(rqp, "rne_quotient_plus64");
  expect_clean(quot, "attr_quotient64");
  expect_clean(rss, "round_scaled_sum64");
  expect_clean(composed, "attr_window / attr_depth / snap_window");
  expect_clean(align, "align_block");
  for (const Tally* t : {&rqp, &quot, &rss, &align}) {
    EXPECT_GT(t->fast, t->cases / 10);
    EXPECT_LT(t->fast, t->cases - t->cases / 10);
  }
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
