// model/arith/recip_core.hpp — the one reciprocal core: seed table + Newton–Raphson iterate,
// shared by the reciprocal unit (stages/recip.hpp) and the recip_mul divider (arith/div.hpp).
// docs/arith.md "# Shared arithmetic" derives it and gives the figure that chose the seed rule.
//
// Operand: x = X · 2^−(xb−1) ∈ [1, 2), X an xb-bit integer with its msb set (xb = x_bits:
// in_sig_bits for the reciprocal unit, the aligned divisor width for the divider).
// Seed: y0 = (2^k + table[i]) · 2^−(k+1) ∈ [1/2, 1), i = the s fraction bits of x below its
//   leading one, zero-extended when s > xb − 1 (s = seed_index_bits, k = seed_frac_bits); k bits stored per entry.
//   Rule (minimax on the grid): the entry minimises max |1 − x·y0| over its segment of x, ties to
//   the smaller y0; exact integer arithmetic (rtl/fxr_seed_rom.sv computes the same table).
// Newton–Raphson, nr_steps times (F = nr_frac_bits; y has k+1 fraction bits before step 1,
//   F after):
//     p = trunc_F(x·y)              truncation (precision lost, < 2^−F)
//     t = ~p = 2 − 2^−F − p         ones' complement: t ≤ 2 − x·y, never above
//     y = trunc_F(y·t)              truncation (precision lost, < 2^−F)
//   → 0 ≤ 1/x − y after every step (one-sided; docs/arith.md proves it). nr_steps = 0 returns
//   y0 at F fraction bits (truncated when k + 1 > F: precision lost).
// Result: Y with y = Y · 2^−F ∈ [0, 1). No overflow: p < 2 whenever the seed error is below 1
// (every table), so t ≥ 0; products fit 2·max(xb, F) + 2 ≤ 128 bits (xb, F ≤ 62).
// The RTL twin: rtl/fxr_seed_rom.sv (the table) and rtl/fxr_nr_step.sv (one step).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace fxr {

struct RecipCoreShape {
  int x_bits = 24;           // xb: operand significand width incl. the leading one
  int seed_index_bits = 6;   // s
  int seed_frac_bits = 6;    // k
  int nr_steps = 2;          // 0.. (the reciprocal unit needs ≥ 1, the divider allows 0)
  int nr_frac_bits = 26;     // F

  bool operator==(const RecipCoreShape& o) const {
    return x_bits == o.x_bits && seed_index_bits == o.seed_index_bits &&
           seed_frac_bits == o.seed_frac_bits && nr_steps == o.nr_steps && nr_frac_bits == o.nr_frac_bits;
  }
  bool operator!=(const RecipCoreShape& o) const { return !(*this == o); }
};

// The seed table (k bits after the implied leading one per entry), by the minimax rule above.
// Needs s + k + 3 ≤ 126 (exact in i128).
std::vector<uint64_t> recip_core_seed_table(int seed_index_bits, int seed_frac_bits);

// Largest relative seed error max |1 − x·y0| over the table (exact endpoints; the numerator
// over the denominator 2^(s+k+1)): the figure the NR error bound starts from.
struct SeedError {
  __int128 num = 0;
  int log2_den = 0;
};
SeedError recip_core_seed_error(int seed_index_bits, int seed_frac_bits,
                                const std::vector<uint64_t>& table);

// Operand widths (a, b) of the core's multipliers, in order: per step x·y (xb × width of y)
// and y·t (width of y × F+1), y being k+1 bits wide before the first step, F after.
std::vector<std::pair<int, int>> recip_core_multipliers(const RecipCoreShape& s);

// Prepared core: the table with its leading ones, built once; approx() is the hot path.
class RecipCore {
 public:
  explicit RecipCore(const RecipCoreShape& s);
  const RecipCoreShape& shape() const { return s_; }
  // y0 with k + 1 fraction bits (leading one included) for an xb-bit X.
  uint64_t seed(uint64_t x) const {
    // s > xb − 1 (possible for the divider's narrow operands) zero-extends the fraction.
    const int sh = s_.x_bits - 1 - s_.seed_index_bits;
    return seed_[(sh >= 0 ? x >> sh : x << -sh) & idx_mask_];
  }
  // Y = the NR result at F fraction bits (see the header contract).
  uint64_t approx(uint64_t x) const { return narrow_ ? approx_w<uint64_t>(x) : approx_w<unsigned __int128>(x); }

 private:
  template <class W>
  uint64_t approx_w(uint64_t x) const;

  RecipCoreShape s_;
  std::vector<uint64_t> seed_;  // 2^k + entry
  uint64_t idx_mask_ = 0;
  bool narrow_ = false;  // every product fits 64 bits: uint64_t arithmetic (same results, faster)
};

template <class W>
uint64_t RecipCore::approx_w(uint64_t x) const {
  const int xf = s_.x_bits - 1, f = s_.nr_frac_bits;
  uint64_t y = seed(x);
  int fy = s_.seed_frac_bits + 1;  // fraction bits of y (F after the first step)
  if (s_.nr_steps == 0) return fy <= f ? y << (f - fy) : y >> (fy - f);  // precision lost if fy > F
  const W ones = (((W)1) << (f + 1)) - 1;  // all ones of t's F+1 bits (one integer bit)
  for (int step = 0; step < s_.nr_steps; ++step) {
    // p = x·y has xf + fy fraction bits exactly; keep F. PRECISION LOST: truncation < 2^−F.
    const W xy = (W)x * y;
    const int sh = xf + fy - f;
    const W p = sh >= 0 ? xy >> sh : xy << -sh;  // p < 2
    // t = 2 − 2^−F − p: the ones' complement of p; never above 2 − x·y, so y stays ≤ 1/x.
    const W t = ones - p;
    // y·t has fy + F fraction bits; keep F. PRECISION LOST: truncation < 2^−F.
    y = (uint64_t)(((W)y * t) >> fy);
    fy = f;
  }
  return y;
}

}  // namespace fxr
