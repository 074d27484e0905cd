// 10^8 random cases of the attribute planes' fast path against the reference make_attr_plane
// (attr_plane_cases.hpp; the directed cases and 10^6 random are in attr_plane_test.cpp). Slow
// label: ≈ 2–3 CPU minutes (750 s wall at nice 19, load 12).
#include <gtest/gtest.h>

#include <cstdio>

#include "attr_plane_cases.hpp"

using namespace fxr;
using namespace fxr::attr_cases;

TEST(AttrPlaneSlow, HundredMillionRandomCasesEqualTheReference) {
  const uint64_t n = 100000000;
  const uint64_t fits = check_random(0xa77e5, n, [](const PlaneCase&, uint64_t) {});
  std::printf("fast path taken in %llu of %llu cases\n", (unsigned long long)fits, (unsigned long long)n);
}

TEST(AttrTerms64Slow, HundredMillionRandomTrianglesEqualTheReference) {
  const uint64_t n = 100000000;
  const uint64_t done = check_random_terms(0x7e6405, n);
  std::printf("64-bit edge terms in %llu of %llu cases\n", (unsigned long long)done, (unsigned long long)n);
}
