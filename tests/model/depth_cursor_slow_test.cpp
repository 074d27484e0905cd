// DepthCursor (model/stages/depth.hpp) on 10^8 random cases (label slow; the 10^6 of the model
// label and the exhaustive small planes are in depth_cursor_test.cpp; the cases in
// depth_cursor_cases.hpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "tests/model/depth_cursor_cases.hpp"

using namespace fxr::cursor_cases;

TEST(DepthCursorSlow, HundredMillionRandomCasesEqualTheDirectQuotient) {
  std::mt19937_64 g(20261124);
  Tally t;
  for (uint64_t k = 0; k < 100000000ull; ++k) run_case(g, t);
  std::printf("cursor: %llu cases, %llu started, %llu refused, %llu moves (%llu divided), %llu lost, %llu codes, %llu bad\n",
              (unsigned long long)t.cases, (unsigned long long)t.started, (unsigned long long)t.refused,
              (unsigned long long)t.moves, (unsigned long long)t.divided, (unsigned long long)t.lost,
              (unsigned long long)t.codes, (unsigned long long)t.bad);
  EXPECT_EQ(t.bad, 0u);
  EXPECT_GT(t.started, t.cases / 10);
  EXPECT_GT(t.divided, t.moves / 20);
}
