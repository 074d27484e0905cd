// Reciprocal unit (stage 3): seed table, Newton-Raphson, remainder correction. docs/arith.md.
#include "model/stages/recip.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "model/arith/fixed.hpp"
#include "model/config/param.hpp"
#include "model/config/validate.hpp"

namespace fxr {

namespace {

// Pipeline stages of rtl/fxr_recip.sv (one register each):
constexpr int kSeedStages = 1;       // table read → y0 register
constexpr int kStagesPerNrStep = 2;  // p = x·y → t register; y·t → y register
constexpr int kRoundStages = 1;      // K = RN(y) (and, without correction, the output register)
constexpr int kCorrectStages = 1;    // m·(2K+1) midpoint test, K or K+1, output register

uint64_t pow2(int e) { return uint64_t{1} << e; }

}  // namespace

bool operator==(const RecipConfig& a, const RecipConfig& b) { return params_equal(a, b); }

void recip_validate(const RecipConfig& c) { validate(c, "recip"); }

std::vector<uint64_t> recip_seed_table(const RecipConfig& c) {
  recip_validate(c);
  return recip_core_seed_table(c.seed_index_bits, c.seed_frac_bits);
}

RecipCoreShape recip_core_shape(const RecipConfig& c) {
  RecipCoreShape s;
  s.x_bits = c.in_sig_bits;
  s.seed_index_bits = c.seed_index_bits;
  s.seed_frac_bits = c.seed_frac_bits;
  s.nr_steps = c.nr_steps;
  s.nr_frac_bits = c.nr_frac_bits;
  return s;
}

RecipUnit::RecipUnit(const RecipConfig& cfg)
    : cfg_((recip_validate(cfg), cfg)), core_(recip_core_shape(cfg)) {
  n_ = cfg.in_sig_bits;
  o_ = cfg.out_sig_bits;
  f_ = cfg.nr_frac_bits;
  narrow_ = n_ + o_ + 1 <= 63;  // m·(2K+1) < 2^(n+o+1) and the constant 2^(n+o)
}

// Contract: y = approx(m) → RecipSig. q = floor(y·2^o) and the rounding bit below it give
// K = q + bit, y rounded to o fraction bits half up (PRECISION LOST), at least 1/2 (1/x > 1/2
// always). Without the correction K is the result (round_increment: K = 2^o is 1.0). With it, K
// is clamped to [2^(o−1), 2^o − 1] (K = 2^o means y ≥ 1 − ½ ulp, so RN(1/x) = 1.0 and the test
// below restores it) and the RNE decision of the exact midpoint test adds one ulp when 1/x lies
// above K + ½: x·(K + ½)·2^−o < 1 ⇔ m·(2K+1) < 2^(n+o). Ties cannot occur (docs/arith.md).
// rtl/fxr_recip.sv computes the same steps (fxr_round for round_increment).
RecipSig RecipUnit::round(uint64_t m, uint64_t y) const {
  const int drop = f_ - o_;  // ≥ 1 (recip_validate)
  const uint64_t lo = pow2(o_ - 1), hi = pow2(o_) - 1;
  const uint64_t q = y >> drop;                    // < 2^o: y < 1
  const bool half = ((y >> (drop - 1)) & 1) != 0;  // the rounding bit (half up)
  if (cfg_.correction != RecipCorrection::Remainder) {
    if (q < lo) return {lo, -1};  // y < 1/2 (inaccurate configurations): max(K, 2^(o−1))
    return round_increment(q, half, o_, -1);
  }
  const uint64_t k = std::clamp<uint64_t>(q + (half ? 1 : 0), lo, hi);
  // Sign of 2^(n+o) − m·(2K+1) = 2·(remainder of 2^(n−1+o) / m against K) − m.
  const int above = narrow_ ? (m * (2 * k + 1) < pow2(n_ + o_) ? 1 : -1)
                            : ((u128)m * (2 * k + 1) < ((u128)1 << (n_ + o_)) ? 1 : -1);
  return round_increment(k, rne_round_up(above, (k & 1) != 0), o_, -1);
}

RecipResult RecipUnit::operator()(const FxFloat& w) const {
  RecipResult r;
  r.value.neg = w.neg;
  const int emin = recip_exp_min(cfg_), emax = recip_exp_max(cfg_);
  auto set = [&](uint64_t sig, int lead) {
    r.value.sig = sig;
    r.value.exp = lead - (o_ - 1);
  };
  const uint64_t largest = pow2(o_) - 1, smallest = pow2(o_ - 1);
  if (w.is_zero()) {
    r.div_by_zero = true;
    set(largest, emax);
    return r;
  }
  // Exact for significands of at most n bits (denormals); wider ones: PRECISION LOST, RNE to n bits.
  const FxFloat x = normalize_fx(w, n_, Round::HalfEven);
  const int e = x.lead_exp();
  if (e < emin || e > emax) {
    r.exp_overflow = true;
    if (e < emin)
      set(largest, emax);
    else
      set(smallest, emin);
    return r;
  }
  const RecipSig q = sig(x.sig);
  const int lead = -e + q.exp_adj;  // ≥ −emax − 1 = emin: no underflow
  if (lead > emax) {                // only w = ±2^emin
    r.exp_overflow = true;
    set(largest, emax);
    return r;
  }
  set(q.sig, lead);
  return r;
}

RecipSig recip_sig(const RecipConfig& cfg, uint64_t m) {
  thread_local std::unique_ptr<RecipUnit> unit;
  if (!unit || unit->config() != cfg) unit = std::make_unique<RecipUnit>(cfg);
  return unit->sig(m);
}

RecipResult recip(const RecipConfig& cfg, const FxFloat& w) {
  thread_local std::unique_ptr<RecipUnit> unit;
  if (!unit || unit->config() != cfg) unit = std::make_unique<RecipUnit>(cfg);
  return (*unit)(w);
}

StageCost recip_cost(const RecipConfig& c) {
  const std::vector<uint64_t> table = recip_seed_table(c);  // validates
  StageCost r;
  const bool corr = c.correction == RecipCorrection::Remainder;
  r.latency = kSeedStages + kStagesPerNrStep * c.nr_steps + kRoundStages + (corr ? kCorrectStages : 0);
  r.ii = 1;
  r.table_bits = (int64_t)table.size() * c.seed_frac_bits;
  r.multipliers = recip_core_multipliers(recip_core_shape(c));
  if (corr) r.multipliers.push_back({c.in_sig_bits, c.out_sig_bits + 1});  // m · (2K+1)
  for (const auto& [a, b] : r.multipliers) r.mult_bits += (int64_t)a * b;
  return r;
}

RecipBound recip_bound(const RecipConfig& c) {
  const std::vector<uint64_t> table = recip_seed_table(c);  // validates
  RecipBound r;
  // Seed error: exact integer endpoint errors, reported as a double.
  const SeedError se = recip_core_seed_error(c.seed_index_bits, c.seed_frac_bits, table);
  r.seed_rel_err = std::ldexp((double)se.num, -se.log2_den);
  // A-priori bound (docs/arith.md): with e = 1 − x·y, one step gives
  //   e' = e² + (1 − e)·δt + x·δy,  0 < δt ≤ 2^−F, 0 ≤ δy < 2^−F, x < 2
  // and the last step 1/x − y' = e'/x ≤ e² + (1 + |e|)·2^−F + 2^−F (x ≥ 1).
  // Doubles with an upward nudge: a report-side bound, not the datapath.
  const double ulp_f = std::ldexp(1.0, -c.nr_frac_bits);
  double e = r.seed_rel_err;
  for (int step = 0; step + 1 < c.nr_steps; ++step) e = e * e + (1 + e) * ulp_f + 2 * ulp_f;
  const double last = e * e + (1 + e) * ulp_f + ulp_f;
  r.error_bound_ulp = std::ldexp(last, c.out_sig_bits) * (1 + 1e-9);
  const bool corr = c.correction == RecipCorrection::Remainder;
  r.valid = corr ? r.error_bound_ulp < 1.0 : r.error_bound_ulp < 0.5;
  return r;
}

}  // namespace fxr
