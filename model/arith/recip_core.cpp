// The one reciprocal core (model/arith/recip_core.hpp has the contracts; docs/arith.md).
#include "model/arith/recip_core.hpp"

#include <algorithm>

namespace fxr {

namespace {

using i128 = __int128;

i128 abs128(i128 v) { return v < 0 ? -v : v; }

// Largest endpoint error of the grid value Y (y0 = Y·2^−(k+1)) on segment [A, A+1)·2^−s, in units
// of 2^−(s+k+1): |1 − X·y0| = |D − X·Y| / D with D = 2^(s+k+1). Linear in x: the extremes are at
// the two ends.
i128 segment_error(int s, int k, i128 a, i128 y) {
  const i128 d = (i128)1 << (s + k + 1);
  return std::max(abs128(d - a * y), abs128(d - (a + 1) * y));
}

}  // namespace

std::vector<uint64_t> recip_core_seed_table(int s, int k) {
  const i128 y_lo = (i128)1 << k, y_hi = ((i128)1 << (k + 1)) - 1;  // y0 ∈ [1/2, 1)
  std::vector<uint64_t> table(size_t{1} << s);
  for (uint64_t i = 0; i < table.size(); ++i) {
    const i128 a = ((i128)1 << s) + i;
    // The real minimax value is the reciprocal of the segment midpoint, 2/(a+b); as a grid index
    // floor(2^(s+k+2) / (2a + 1)). Candidates: it and the next grid value, clamped.
    const i128 y_floor = ((i128)1 << (s + k + 2)) / (2 * a + 1);
    i128 best = std::clamp(y_floor, y_lo, y_hi);
    const i128 up = std::clamp(y_floor + 1, y_lo, y_hi);
    if (segment_error(s, k, a, up) < segment_error(s, k, a, best)) best = up;  // ties: smaller y0
    table[i] = (uint64_t)(best - y_lo);  // k bits after the implied leading one
  }
  return table;
}

SeedError recip_core_seed_error(int s, int k, const std::vector<uint64_t>& table) {
  SeedError e;
  e.log2_den = s + k + 1;
  for (uint64_t i = 0; i < table.size(); ++i)
    e.num = std::max(e.num, segment_error(s, k, ((i128)1 << s) + i, ((i128)1 << k) + table[i]));
  return e;
}

std::vector<std::pair<int, int>> recip_core_multipliers(const RecipCoreShape& s) {
  std::vector<std::pair<int, int>> m;
  for (int step = 0; step < s.nr_steps; ++step) {
    const int wy = step == 0 ? s.seed_frac_bits + 1 : s.nr_frac_bits;
    m.push_back({s.x_bits, wy});             // x·y
    m.push_back({wy, s.nr_frac_bits + 1});   // y·t
  }
  return m;
}

RecipCore::RecipCore(const RecipCoreShape& s) : s_(s) {
  const std::vector<uint64_t> t = recip_core_seed_table(s.seed_index_bits, s.seed_frac_bits);
  seed_.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i) seed_[i] = (uint64_t{1} << s.seed_frac_bits) + t[i];
  idx_mask_ = (uint64_t{1} << s.seed_index_bits) - 1;
  // Widest products: x·y (xb + max(k+1, F) bits) and y·t (max(k+1, F) + F + 1 bits).
  const int wy = std::max(s.seed_frac_bits + 1, s.nr_frac_bits);
  narrow_ = s.x_bits + wy <= 64 && wy + s.nr_frac_bits + 1 <= 64;
}

}  // namespace fxr
