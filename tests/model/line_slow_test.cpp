// The big line run (label slow; docs/lines.md quotes its counts): 10^5 segments per rule at the
// default configuration, every pixel against the exact references of tests/model/line_ref.hpp.
// Run: ctest --test-dir build -R LineSlow
#include <gtest/gtest.h>

#include <cstdio>

#include "line_check.hpp"

using namespace fxr;

TEST(LineSlow, HundredThousandSegmentsPerRuleMatchTheExactReferences) {
  const RasterConfig r;
  for (int rule = 0; rule < 3; ++rule) {
    LineConfig c;
    c.rule = rule == 2 ? LineRule::DiamondExit : LineRule::Midpoint;
    c.endpoints = rule == 1 ? LineEndpoints::Closed : LineEndpoints::HalfOpen;
    // 6 classes × 15,000 + 1,500 guard-band-long = 91,500 per seed; two seeds.
    line_check::Counts total;
    for (uint64_t seed : {11u, 12u}) {
      const line_check::Counts k = line_check::check(r, c, seed, 15000);
      total.segments += k.segments, total.pixels += k.pixels;
      total.mismatched_segments += k.mismatched_segments, total.reverse_mismatches += k.reverse_mismatches;
      if (total.first.empty()) total.first = k.first;
    }
    std::printf("line rule %d: segments=%llu pixels=%llu mismatched=%llu reversed-mismatched=%llu\n", rule,
                (unsigned long long)total.segments, (unsigned long long)total.pixels,
                (unsigned long long)total.mismatched_segments, (unsigned long long)total.reverse_mismatches);
    EXPECT_GE(total.segments, 100000u);
    EXPECT_EQ(total.mismatched_segments, 0u) << total.first;
    EXPECT_EQ(total.reverse_mismatches, 0u);
  }
}
