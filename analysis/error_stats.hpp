// analysis/error_stats.hpp — error statistics of a set of fragments (max, mean, RMS,
// nearest-rank percentiles) and the unit conversions every report uses. Double precision:
// analysis only, never the model (docs/reports.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/arith/fxfloat.hpp"

namespace fxr {

// Non-finite samples are ignored (counted nowhere): callers count undefined references apart.
struct ErrStat {
  uint64_t n = 0;
  double max = 0, sum = 0, sum2 = 0;
  std::vector<double> all;  // for percentiles
  void add(double e) {
    if (!std::isfinite(e)) return;
    ++n;
    max = std::max(max, e);
    sum += e;
    sum2 += e * e;
    all.push_back(e);
  }
  double mean() const { return n ? sum / n : 0; }
  double rms() const { return n ? std::sqrt(sum2 / n) : 0; }
  // Nearest-rank percentile (q ∈ [0, 1]); deterministic.
  double pct(double q) const {
    if (all.empty()) return 0;
    std::vector<double> v = all;
    const size_t k = std::min(v.size() - 1, (size_t)std::ceil(q * v.size()) - (q > 0 ? 1 : 0));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[k];
  }
  nlohmann::json to_json() const {
    return {{"count", n}, {"max", max}, {"mean", mean()}, {"rms", rms()}, {"p50", pct(0.5)}, {"p99", pct(0.99)}, {"p999", pct(0.999)}};
  }
};


// ulp of a real value x in a binary format with p significand bits (unbounded exponent):
// 2^(⌊log2 |x|⌋ − (p − 1)). x = 0 or non-finite has no ulp (returns 0).
double ulp_of(double x, int p);

// Value of an FxFloat as a double (for error measurement only; exact when sig < 2^53 and the
// exponent is in double's range).
double fx_to_double(const FxFloat& f);

// A number for a report: fixed with `prec` decimals, scientific when tiny or huge.
std::string fmt_num(double v, int prec = 3);

}  // namespace fxr
