// Shared by recip_test.cpp and recip_slow_test.cpp: independent exact-integer checks of the
// reciprocal unit (nothing here calls the measurement (analysis/measure.hpp) or reuses the unit's rounding code).
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "model/stages/recip.hpp"

namespace fxr::recip_check {


inline uint64_t pow2(int e) { return uint64_t{1} << e; }

// Reference: 1/x for x = m·2^−(n−1) ∈ [1, 2) rounded to nearest at o significand bits, by exact
// integer division. Returns the result in units of 2^−o (1.0 = 2^o).
inline uint64_t ref_round_q(int n, int o, uint64_t m) {
  const uint64_t num = pow2(n - 1 + o);  // n − 1 + o ≤ 63 at the widths tested here
  uint64_t q = num / m;
  const uint64_t r = num % m;
  if (2 * r > m) ++q;  // 2r == m is impossible (1/x is never a midpoint)
  return q;
}

// The unit's significand result in units of 2^−o.
inline uint64_t as_q(const RecipSig& s) { return s.exp_adj == 0 ? s.sig << 1 : s.sig; }

struct Exhaustive {
  uint64_t count = 0, correctly_rounded = 0, unfaithful = 0, malformed = 0;
};

// Runs every significand of cfg through recip_sig and checks it against exact integer products:
// with d = q·m − 2^(n−1+o) (q the result in units of 2^−o) the error is |d|/m units of 2^−o, and
// ulp = 2 units when 1/x = 1 (m = 2^(n−1)), else 1.
//   correctly rounded ⇔ 2|d| < m·ulp (ties cannot occur); faithful ⇔ |d| < m·ulp.
// stride > 1 checks every stride-th significand (a fast subset). Threads only split a count: results cannot depend on their number.
inline Exhaustive check_all(const RecipConfig& cfg, uint64_t stride = 1) {
  const RecipUnit unit(cfg);
  const int n = cfg.in_sig_bits, o = cfg.out_sig_bits;
  const uint64_t first = pow2(n - 1), total = pow2(n - 1);
  const i128 one = (i128)1 << (n - 1 + o);
  std::atomic<uint64_t> cr{0}, unf{0}, bad{0};
  const unsigned nt = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < nt; ++t)
    pool.emplace_back([&, t] {
      uint64_t c = 0, u = 0, b = 0;
      for (uint64_t m = first + t * stride; m < first + total; m += nt * stride) {
        const RecipSig s = unit.sig(m);
        if (s.sig < pow2(o - 1) || s.sig >= pow2(o) || (s.exp_adj != 0 && s.exp_adj != -1)) ++b;
        const i128 d = (i128)((u128)as_q(s) * m) - one;
        const i128 ad = d < 0 ? -d : d, mu = (i128)m * (m == first ? 2 : 1);
        c += 2 * ad < mu;
        u += ad >= mu;
      }
      cr += c;
      unf += u;
      bad += b;
    });
  for (auto& th : pool) th.join();
  return {(total + stride - 1) / stride, cr.load(), unf.load(), bad.load()};
}

inline RecipConfig small_config(int n, int o, int s, int k, int nr, int f, RecipCorrection c) {
  RecipConfig cfg;
  cfg.in_sig_bits = n;
  cfg.out_sig_bits = o;
  cfg.seed_index_bits = s;
  cfg.seed_frac_bits = k;
  cfg.nr_steps = nr;
  cfg.nr_frac_bits = f;
  cfg.correction = c;
  return cfg;
}


}  // namespace fxr::recip_check
