// model/stages/recip.hpp — stage 3: the reciprocal unit, 1/w for every vertex (docs/arith.md).
//
// Input: a normalised FxFloat w = (−1)^neg · m · 2^(e − (n−1)), m ∈ [2^(n−1), 2^n) (n = in_sig_bits,
// e = the exponent of the leading one, a signed exp_bits field), or zero. Output: 1/w in the same
// form with an o-bit significand (o = out_sig_bits), rounded to nearest even when the remainder
// correction is on (exact ties cannot occur: 1/x is never a midpoint, docs/arith.md).
//
// Significand datapath (the pipelined RTL rtl/fxr_recip.sv computes exactly this):
//   x = m · 2^−(n−1) ∈ [1, 2)
//   y = the reciprocal core (model/arith/recip_core.hpp): minimax seed table, nr_steps one-sided
//       Newton–Raphson steps at F = nr_frac_bits → 0 ≤ 1/x − y
//   K = round_half_up_o(y)                        rounding to o fraction bits (precision lost)
//   correction = remainder: K = min(K, 2^o − 1), then the RNE decision (model/arith/round.hpp) of
//       the exact midpoint test: up when m · (2K+1) < 2^(n+o) (1/x above K + ½ ulp; never equal)
//   K (+ up) = 2^o → 1.0 (exp_adj 0), else K · 2^−o (exp_adj −1)
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "model/arith/fxfloat.hpp"
#include "model/arith/recip_core.hpp"
#include "model/arith/round.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

enum class RecipCorrection : uint8_t { None, Remainder };

struct RecipConfig {
  int in_sig_bits = 24;     // significand of w incl. leading one (float32: 24)
  int out_sig_bits = 24;    // significand of 1/w incl. leading one
  int exp_bits = 10;        // signed exponent of the leading one, I/O of the unit (float32 denormals
                            // need ±149 → 9 bits; 10 leaves room for the clipper's w)
  int seed_index_bits = 6;  // table has 2^seed_index_bits entries (docs/arith.md: chosen default)
  int seed_frac_bits = 6;   // entry width: bits after the leading one
  int nr_steps = 2;         // Newton-Raphson iterations
  int nr_frac_bits = 26;    // NR datapath fraction bits (y, p, t)
  RecipCorrection correction = RecipCorrection::Remainder;

  template <class V>
  void visit(V& v) {
    v.integer("in_sig_bits", in_sig_bits, 8, 32, "significand bits of w incl. the leading one");
    v.integer("out_sig_bits", out_sig_bits, 8, 32, "significand bits of 1/w incl. the leading one");
    v.integer("exp_bits", exp_bits, 6, 16, "signed exponent bits (exponent of the leading one) of the unit's I/O");
    v.integer("seed_index_bits", seed_index_bits, 2, 14, "log2 of the seed table entries");
    v.integer("seed_frac_bits", seed_frac_bits, 2, 20, "seed table entry width: bits after the leading one");
    v.integer("nr_steps", nr_steps, 1, 3, "Newton-Raphson iterations");
    v.integer("nr_frac_bits", nr_frac_bits, 9, 48, "fraction bits of the Newton-Raphson datapath");
    v.choice("correction", correction, {"none", "remainder"},
             "final rounding: none = round y to nearest; remainder = back-multiply midpoint test (RNE)");
  }
};

bool operator==(const RecipConfig& a, const RecipConfig& b);
inline bool operator!=(const RecipConfig& a, const RecipConfig& b) { return !(a == b); }

// Equality from visit() (params_equal, model/config/param.hpp): keys the per-thread table cache.
// recip_validate: validate(cfg, "recip") (model/config/validate.hpp): the per-field ranges and
// the recip rules (nr_frac_bits > out_sig_bits, seed_index_bits < in_sig_bits); throws
// ConfigError naming the field. (The widest product, y · t, has 2·nr_frac_bits + 1 ≤ 97 bits.)
void recip_validate(const RecipConfig& cfg);

// I/O exponent range (exponent of the leading one): [−2^(exp_bits−1), 2^(exp_bits−1) − 1].
inline int recip_exp_min(const RecipConfig& c) { return -(1 << (c.exp_bits - 1)); }
inline int recip_exp_max(const RecipConfig& c) { return (1 << (c.exp_bits - 1)) - 1; }

// Significand core. Contract:
//   in:  m ∈ [2^(n−1), 2^n) (n = in_sig_bits), i.e. x = m · 2^−(n−1) ∈ [1, 2); cfg valid.
//   out: 1/x ≈ sig · 2^−(o−1) · 2^exp_adj, sig ∈ [2^(o−1), 2^o) (o = out_sig_bits), exp_adj ∈ {0, −1}
//        (0 only when the result is exactly 1.0, i.e. x = 1 or rounding up to 1.0).
//   rounding: correction = remainder → round to nearest (even; ties never occur) when the NR error
//   is below 1 ulp (valid configurations: proven by recip_bound().error_bound_ulp, checked
//   exhaustively); correction = none → round to nearest (half up) of the NR result y ≤ 1/x.
//   No overflow is possible. m outside the range: undefined (the caller normalises).
using RecipSig = RoundedSig;
RecipSig recip_sig(const RecipConfig& cfg, uint64_t m);  // caches the table of the last cfg per thread

struct RecipResult {
  FxFloat value;             // normalised: sig ∈ [2^(o−1), 2^o), exp = lead exponent − (o−1)
  bool div_by_zero = false;  // w == 0
  bool exp_overflow = false; // 1/|w| ≥ 2^(exp_max+1), or the lead exponent of w was outside the I/O range
};

// Full unit. Contract:
//   w: any FxFloat. Significands of up to n bits are normalised exactly (denormal float32 inputs
//   from decode_f32 included); wider ones are first rounded to n bits, RNE (precision lost).
//   sign: passes through (1/(−w) = −(1/w); the clipper guarantees w > 0 where it matters).
//   w == 0 (either sign): div_by_zero, value = ±(largest: sig 2^o − 1, lead exponent exp_max).
//   lead exponent of w below exp_min: exp_overflow, value = ±largest (as for zero, no div_by_zero).
//   lead exponent of w above exp_max: exp_overflow, value = ±smallest (sig 2^(o−1), exp_min).
//   1/|w| ≥ 2^(exp_max+1) (only w = ±2^exp_min exactly): exp_overflow, value = ±largest.
//   1/|w| never falls below 2^exp_min for an in-range w (−(exp_max) − 1 = exp_min), no underflow.
RecipResult recip(const RecipConfig& cfg, const FxFloat& w);

// Seed table (k = seed_frac_bits bits per entry after the implied leading one): the reciprocal
// core's minimax table, recip_core_seed_table (model/arith/recip_core.hpp). Validates cfg.
std::vector<uint64_t> recip_seed_table(const RecipConfig& cfg);

// The reciprocal core's shape for this unit (x_bits = in_sig_bits).
RecipCoreShape recip_core_shape(const RecipConfig& cfg);

// Prepared unit: the core and derived widths computed once; sig() is the hot path.
class RecipUnit {
 public:
  explicit RecipUnit(const RecipConfig& cfg);
  const RecipConfig& config() const { return cfg_; }
  // y = NR result before the final rounding, as an integer with nr_frac_bits fraction bits.
  uint64_t approx(uint64_t m) const { return core_.approx(m); }
  RecipSig round(uint64_t m, uint64_t y) const;  // final rounding (+ correction) of approx(m)
  RecipSig sig(uint64_t m) const { return round(m, approx(m)); }
  RecipResult operator()(const FxFloat& w) const;

 private:
  RecipConfig cfg_;
  RecipCore core_;
  int n_, o_, f_;
  bool narrow_;  // the back-multiply m·(2K+1) and 2^(n+o) fit 64 bits
};

// Cost of rtl/fxr_recip.sv (the one StageCost shape, model/unit/stage.hpp):
//   latency = 1 (seed table) + 2·nr_steps (x·y → t, y·t → y) + 1 (round) + 1 if corrected;
//   ii = 1; table_bits = 2^s · k; multipliers: the core's (per step x·y and y·t) and, corrected,
//   the back-multiply n × (o+1); adder_bits and ff_bits are not estimated for this unit (0).
StageCost recip_cost(const RecipConfig& cfg);
inline StageCost cost(const RecipConfig& cfg) { return recip_cost(cfg); }  // the uniform name

// The a-priori error analysis of a configuration (docs/arith.md), apart from its cost.
struct RecipBound {
  double seed_rel_err = 0;     // max |1 − x·y0| over the table (exact endpoints)
  double error_bound_ulp = 0;  // a-priori bound on 1/x − y (before rounding), ulps of the output
  bool valid = false;          // bound proves: remainder → correctly rounded; none → faithful
};
RecipBound recip_bound(const RecipConfig& cfg);

}  // namespace fxr
