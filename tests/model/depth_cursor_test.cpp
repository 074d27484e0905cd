// DepthCursor (model/stages/depth.hpp): the depth quotient and remainder at a span start moved
// from the last span start of the same triangle without a division (docs/speed.md "Session 9:
// the span start"). Every (q, r) it reaches is checked against floor(Z / den) from the
// definition (i128 `/` and `%`, tests/model/depth_cursor_cases.hpp), every code of the span's
// int64_t stepper against the RNE of that quotient: exhaustively on small planes (every den
// 1–6, every x and y step in [−3den, 3den], every start value in [−2den, 2den], every start and
// target pixel of a 4 × 3 rectangle: both move paths), 10^6 random cases up to den < 2^62 and
// quotients past the int64 bound, and the bound's edges directed. 10^8 random cases:
// depth_cursor_slow_test.cpp (label slow).
#include <gtest/gtest.h>

#include <random>

#include "model/stages/depth.hpp"
#include "tests/model/depth_cursor_cases.hpp"

using namespace fxr;
using namespace fxr::cursor_cases;

TEST(DepthCursor, EveryMoveOnSmallPlanesEqualsTheDirectQuotient) {
  const int x0 = 0, x1 = 3, y0 = 0, y1 = 2;
  uint64_t moves = 0, divided = 0, common = 0, bad = 0;
  for (int64_t den = 1; den <= 6; ++den)
    for (int64_t dx = -3 * den; dx <= 3 * den; ++dx)
      for (int64_t dy = -3 * den; dy <= 3 * den; ++dy)
        for (int64_t z0 = -2 * den; z0 <= 2 * den; ++z0) {
          DepthSetup s;
          s.den = den;
          s.max_code = 7;
          s.z.dx = dx, s.z.dy = dy, s.z.c = z0;  // anchor (0, 0)
          for (int a = x0; a <= x1; ++a)
            for (int b = y0; b <= y1; ++b) {
              DepthCursor c0;
              ASSERT_TRUE(c0.start(DepthStepper(s, a, b), a, b, x0, x1, y0, y1));
              DepthCursor chain = c0;  // also moved through every pixel in turn
              for (int i = x0; i <= x1; ++i)
                for (int j = y0; j <= y1; ++j) {
                  for (DepthCursor* c : {&c0, &chain}) {
                    DepthCursor from = *c;
                    const int m = from.move(s, i, j);
                    ++moves;
                    divided += m == DepthCursor::kMovedDivided;
                    common += m == DepthCursor::kMoved;
                    i128 q, r;
                    ref_divmod(ref_z(s, i, j), s.den, q, r);
                    if ((m == DepthCursor::kLost || (i128)from.q != q || (i128)from.r != r) && ++bad <= 5)
                      ADD_FAILURE() << "den " << (int)den << " dx " << (int)dx << " dy " << (int)dy << " z0 "
                                    << (int)z0 << " (" << a << "," << b << ") -> (" << i << "," << j << ")";
                    // The stepper from the new pixel to the rectangle's end.
                    DepthStepperT<int64_t> z = from.stepper();
                    for (int p = i; p <= x1; ++p, z.step_x()) {
                      ref_divmod(ref_z(s, p, j), s.den, q, r);
                      if (z.code() != ref_code(q, r, s.den, s.max_code) && ++bad <= 5) ADD_FAILURE() << "code";
                    }
                    if (c == &chain) chain = from;
                  }
                }
            }
        }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(divided, moves / 10);  // both paths of move() reached
  EXPECT_GT(common, moves / 10);
}

TEST(DepthCursor, RandomPlanesUpToTheInt64BoundEqualTheDirectQuotient) {
  std::mt19937_64 g(14);
  Tally t;
  for (int k = 0; k < 1000000; ++k) run_case(g, t);
  std::printf("cursor: %llu cases, %llu started, %llu refused, %llu moves (%llu divided), %llu lost, %llu codes\n",
              (unsigned long long)t.cases, (unsigned long long)t.started, (unsigned long long)t.refused,
              (unsigned long long)t.moves, (unsigned long long)t.divided, (unsigned long long)t.lost,
              (unsigned long long)t.codes);
  EXPECT_EQ(t.bad, 0u);
  // Every outcome reached often.
  EXPECT_GT(t.started, t.cases / 10);
  EXPECT_GT(t.refused, t.cases / 10);
  EXPECT_GT(t.divided, t.moves / 20);
  EXPECT_GT(t.moves - t.divided, t.moves / 2);
  EXPECT_GT(t.lost, 1000u);
}

TEST(DepthCursor, TheBoundIsTakenUpToItsLimitAndRefusedAtIt) {
  const i128 lim = (i128)1 << DepthCursor::kLimitBits;
  // den and max_code: 2^61 − 1 taken, 2^61 refused.
  for (i128 den : {lim - 1, lim}) {
    DepthSetup s;
    s.den = den;
    s.z.c = 5 * den + 3;
    s.z.dx = den + 1;
    s.z.dy = 2 * den - 1;
    DepthCursor c;
    EXPECT_EQ(c.start(DepthStepper(s, 0, 0), 0, 0, 0, 3, 0, 3), den < lim);
  }
  for (i128 mc : {lim - 1, lim}) {
    DepthSetup s;
    s.den = 1000;
    s.max_code = mc;
    DepthCursor c;
    EXPECT_EQ(c.start(DepthStepper(s, 0, 0), 0, 0, 0, 3, 0, 3), mc < lim);
  }
  // The x part: |q_s| + 2 + (W + 1)·(|qx| + 1) = 2^61 − 1 taken, 2^61 refused; both signs of q.
  for (int sign : {1, -1})
    for (i128 extra : {0, 1}) {
      const int W = 7;  // x0 = 0, x1 = 7: W + 1 = 8 steps of |qx| + 1
      const i128 qx = 1000, aq = lim - 1 - 2 - (W + 1) * (qx + 1) + extra;
      DepthSetup s;
      s.den = 12345;
      s.max_code = lim - 1;
      s.z.c = sign * aq * s.den + (sign > 0 ? 17 : 0);  // q = sign·aq exactly
      s.z.dx = -sign * qx * s.den;                     // towards 0 from the start: the bound is conservative
      DepthCursor c;
      const bool ok = c.start(DepthStepper(s, 0, 0), 0, 0, 0, W, 0, 0);
      EXPECT_EQ(ok, extra == 0) << sign;
      if (!ok) continue;
      // The whole span stepped in int64_t at the limit: every code equals the direct one.
      DepthStepperT<int64_t> z = c.stepper();
      for (int i = 0; i <= W; ++i, z.step_x()) {
        i128 q, r;
        ref_divmod(ref_z(s, i, 0), s.den, q, r);
        EXPECT_EQ(z.code(), ref_code(q, r, s.den, s.max_code)) << i;
        EXPECT_EQ((i128)z.q, q);
      }
    }
  // The y part, added at the first move to another row: H·(|qy| + 1) taking B to 2^61 − 1
  // keeps the cursor, to 2^61 loses it (the caller divides per span from then on).
  for (i128 extra : {0, 1}) {
    const int H = 3;
    DepthSetup s;
    s.den = 999;
    s.z.c = 10 * s.den;                    // q_s = 10
    s.z.dx = 3 * s.den + 5;                // qx = 3
    const i128 bx = 10 + 2 + (0 + 1) * (3 + 1);  // W = 0
    const i128 qy = (lim - 1 - bx) / H - 1 + extra * 2;
    s.z.dy = qy * s.den + 7;
    DepthCursor c;
    ASSERT_TRUE(c.start(DepthStepper(s, 0, 0), 0, 0, 0, 0, 0, H));
    const bool within = bx + H * (qy + 1) < lim;
    const int m = c.move(s, 0, 1);
    EXPECT_EQ(m != DepthCursor::kLost, within) << (int)extra;
    if (m != DepthCursor::kLost) {
      i128 q, r;
      ref_divmod(ref_z(s, 0, 1), s.den, q, r);
      EXPECT_EQ((i128)c.q, q);
      EXPECT_EQ((i128)c.r, r);
    }
  }
  // Outside the rectangle: refused at the start, lost on a move.
  DepthSetup s;
  s.den = 10;
  DepthCursor c;
  EXPECT_FALSE(c.start(DepthStepper(s, 4, 0), 4, 0, 0, 3, 0, 3));
  ASSERT_TRUE(c.start(DepthStepper(s, 3, 0), 3, 0, 0, 3, 0, 3));
  EXPECT_EQ(c.move(s, 4, 1), DepthCursor::kLost);
}
