// Error statistics helpers (analysis/error_stats.hpp).
#include "analysis/error_stats.hpp"

#include <cstdio>

namespace fxr {

// ulp of a real value x in a binary format with p significand bits (unbounded exponent):
// 2^(⌊log2 |x|⌋ − (p − 1)). x = 0 has no ulp (returns 0).
double ulp_of(double x, int p) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int e;
  std::frexp(std::abs(x), &e);  // |x| = m · 2^e, m ∈ [0.5, 1)
  return std::ldexp(1.0, e - 1 - (p - 1));
}

// Value of an FxFloat as a double (for error measurement only; exact when sig < 2^53).
double fx_to_double(const FxFloat& f) {
  const double m = std::ldexp((double)f.sig, f.exp);
  return f.neg ? -m : m;
}

std::string fmt_num(double v, int prec) {
  char b[64];
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e6)) std::snprintf(b, sizeof b, "%.*e", prec, v);
  else std::snprintf(b, sizeof b, "%.*f", prec, v);
  return b;
}

}  // namespace fxr
