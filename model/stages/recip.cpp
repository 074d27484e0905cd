// Reciprocal unit (stage 3): seed table, Newton-Raphson, remainder correction. docs/arith.md.
#include "model/stages/recip.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <thread>

#include "model/arith/fixed.hpp"
#include "model/config/param.hpp"
#include "model/config/validate.hpp"

namespace fxr {

namespace {

// Number of fixed chunks recip_measure splits the significands into. Statistics are combined
// chunk by chunk in index order, so the result does not depend on how many threads ran them.
constexpr int kMeasureChunks = 64;

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
  const int s = c.seed_index_bits, k = c.seed_frac_bits;
  // Segment i: x ∈ [A, B) · 2^−s with A = 2^s + i, B = A + 1; y0 = Y · 2^−(k+1).
  // Relative error at an endpoint X: 1 − X·Y·2^−(s+k+1) = (D − X·Y) / D, D = 2^(s+k+1).
  // It is linear in x, so the extremes over the segment are at its two ends.
  const i128 d = (i128)1 << (s + k + 1);
  const i128 y_lo = (i128)1 << k, y_hi = ((i128)1 << (k + 1)) - 1;  // y0 ∈ [1/2, 1)
  std::vector<uint64_t> table(pow2(s));
  for (uint64_t i = 0; i < table.size(); ++i) {
    const i128 a = (i128)pow2(s) + i, b = a + 1;
    auto cost = [&](i128 y) {
      const i128 ea = d - a * y, eb = d - b * y;
      return std::max(ea < 0 ? -ea : ea, eb < 0 ? -eb : eb);
    };
    // The real minimax value 2/(a+b) · 2^(s+k)... as a grid index: floor(2^(s+k+2) / (2a + 1)).
    const i128 y_floor = (((i128)1 << (s + k + 2)) / (2 * a + 1));
    i128 best = std::clamp(y_floor, y_lo, y_hi);
    const i128 up = std::clamp(y_floor + 1, y_lo, y_hi);
    if (cost(up) < cost(best)) best = up;  // ties keep the smaller y0
    table[i] = (uint64_t)(best - y_lo);    // k bits after the implied leading one
  }
  return table;
}

RecipUnit::RecipUnit(const RecipConfig& cfg) : cfg_(cfg) {
  const std::vector<uint64_t> t = recip_seed_table(cfg);  // validates
  n_ = cfg.in_sig_bits;
  o_ = cfg.out_sig_bits;
  s_ = cfg.seed_index_bits;
  k_ = cfg.seed_frac_bits;
  f_ = cfg.nr_frac_bits;
  // Widest products: x·y (n + F bits, y0 narrower), y·t (F + F + 1), m·(2K+1) (n + o + 1); the
  // comparison constant 2^(n+o) must also fit.
  narrow_ = n_ + f_ <= 64 && 2 * f_ + 1 <= 64 && n_ + o_ + 1 <= 63;
  seed_.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i) seed_[i] = (uint32_t)(pow2(k_) + t[i]);
}

// Contract: m ∈ [2^(n−1), 2^n) → Y with y = Y·2^−F ∈ [0, 1), 0 ≤ 1/x − y (one-sided, see header).
// W is the product type: uint64_t when every product fits 64 bits (the default: x·y 50 bits,
// y·t 53 bits), else u128. Both give identical results; W only changes the speed.
template <class W>
uint64_t RecipUnit::approx_w(uint64_t m) const {
  // Seed: index = the s fraction bits below the leading one of m.
  const uint64_t idx = (m >> (n_ - 1 - s_)) & (pow2(s_) - 1);
  uint64_t y = seed_[idx];  // y0 = y · 2^−(k+1)
  int fy = k_ + 1;          // fraction bits of y (F after the first step)
  const uint64_t ones = pow2(f_ + 1) - 1;  // all ones of t's F+1 bits (one integer bit)
  for (int step = 0; step < cfg_.nr_steps; ++step) {
    // p = x·y has (n−1) + fy fraction bits exactly; keep F. PRECISION LOST: truncation < 2^−F.
    const W xy = (W)m * y;
    const int sh = n_ - 1 + fy - f_;
    const uint64_t p = (uint64_t)(sh >= 0 ? xy >> sh : xy << -sh);  // p < 2 (x·y ≤ 1 + seed error)
    // t = 2 − 2^−F − p: the ones' complement of p; never above 2 − x·y, so y stays ≤ 1/x.
    const uint64_t t = ones - p;
    // y·t has fy + F fraction bits; keep F. PRECISION LOST: truncation < 2^−F.
    y = (uint64_t)(((W)y * t) >> fy);
    fy = f_;
  }
  return y;
}

uint64_t RecipUnit::approx(uint64_t m) const {
  return narrow_ ? approx_w<uint64_t>(m) : approx_w<u128>(m);
}

// Contract: y = approx(m) → RecipSig. Rounds y to o fraction bits (half up; PRECISION LOST), clamps
// below at 1/2 (1/x > 1/2 always), then with the remainder correction adds one ulp when the
// exact 1/x lies above the midpoint K + ½: x·(K + ½)·2^−o < 1 ⇔ m·(2K+1) < 2^(n+o), exact.
RecipSig RecipUnit::round(uint64_t m, uint64_t y) const {
  const int drop = f_ - o_;  // ≥ 1 (recip_validate)
  uint64_t k = (y + pow2(drop - 1)) >> drop;
  k = std::max(k, pow2(o_ - 1));
  if (cfg_.correction == RecipCorrection::Remainder) {
    if (narrow_ ? m * (2 * k + 1) < pow2(n_ + o_) : (u128)m * (2 * k + 1) < ((u128)1 << (n_ + o_)))
      k += 1;
  }
  RecipSig r;
  if (k >= pow2(o_)) {  // 1.0: the next binade
    r.sig = pow2(o_ - 1);
    r.exp_adj = 0;
  } else {
    r.sig = k;
    r.exp_adj = -1;
  }
  return r;
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

RecipCost recip_cost(const RecipConfig& c) {
  const std::vector<uint64_t> table = recip_seed_table(c);  // validates
  RecipCost r;
  const int n = c.in_sig_bits, o = c.out_sig_bits, s = c.seed_index_bits, k = c.seed_frac_bits,
            f = c.nr_frac_bits;
  const bool corr = c.correction == RecipCorrection::Remainder;
  r.latency = kSeedStages + kStagesPerNrStep * c.nr_steps + kRoundStages + (corr ? kCorrectStages : 0);
  r.ii = 1;
  r.table_entries = (int64_t)table.size();
  r.table_width = k;
  r.table_bits = r.table_entries * r.table_width;
  // Multipliers: per step x·y (n × width of y) and y·t (width of y × F+1); y0 has k+1 bits.
  for (int step = 0; step < c.nr_steps; ++step) {
    const int wy = step == 0 ? k + 1 : f;
    r.multipliers.push_back({n, wy});
    r.multipliers.push_back({wy, f + 1});
  }
  if (corr) r.multipliers.push_back({n, o + 1});  // m · (2K+1)
  for (const auto& [a, b] : r.multipliers) r.mult_bits += (int64_t)a * b;
  r.area_proxy = r.table_bits + r.mult_bits;

  // Seed error: exact integer endpoint errors (as in recip_seed_table), reported as a double.
  const i128 d = (i128)1 << (s + k + 1);
  i128 worst = 0;
  for (uint64_t i = 0; i < table.size(); ++i) {
    const i128 a = (i128)pow2(s) + i, y = (i128)(pow2(k) + table[i]);
    for (i128 xx : {a, a + 1}) {
      const i128 e = d - xx * y;
      worst = std::max(worst, e < 0 ? -e : e);
    }
  }
  r.seed_rel_err = (double)worst / (double)d;
  // A-priori bound (docs/arith.md): with e = 1 − x·y, one step gives
  //   e' = e² + (1 − e)·δt + x·δy,  0 < δt ≤ 2^−F, 0 ≤ δy < 2^−F, x < 2
  // and the last step 1/x − y' = e'/x ≤ e² + (1 + |e|)·2^−F + 2^−F (x ≥ 1).
  // Doubles with an upward nudge: a report-side bound, not the datapath.
  const double ulp_f = std::ldexp(1.0, -f);
  double e = r.seed_rel_err;
  for (int step = 0; step + 1 < c.nr_steps; ++step) e = e * e + (1 + e) * ulp_f + 2 * ulp_f;
  const double last = e * e + (1 + e) * ulp_f + ulp_f;
  r.error_bound_ulp = std::ldexp(last, o) * (1 + 1e-9);
  r.valid = corr ? r.error_bound_ulp < 1.0 : r.error_bound_ulp < 0.5;
  return r;
}

RecipErrorStats recip_measure(const RecipConfig& c) {
  const RecipUnit unit(c);
  const int n = c.in_sig_bits, o = c.out_sig_bits, f = c.nr_frac_bits;
  const uint64_t first = pow2(n - 1), total = pow2(n - 1);
  const uint64_t chunks = std::min<uint64_t>(kMeasureChunks, total);
  struct Part {
    double max_b = 0, max_e = 0, sum = 0, sum2 = 0;
    uint64_t cr = 0;
  };
  std::vector<Part> parts(chunks);
  const i128 one_y = (i128)1 << (n - 1 + f);  // 1/x · m · 2^F  (exact numerator for y)
  const i128 one_q = (i128)1 << (n - 1 + o);  // 1/x · m · 2^o  (exact numerator for the result)
  const double y_to_ulp = std::ldexp(1.0, o - f);
  auto run = [&](uint64_t ci) {
    Part p;
    const uint64_t lo = first + total * ci / chunks, hi = first + total * (ci + 1) / chunks;
    for (uint64_t m = lo; m < hi; ++m) {
      const uint64_t y = unit.approx(m);
      const RecipSig q = unit.round(m, y);
      // ulp of the exact result's binade: 2^−o below 1, 2^−(o−1) for 1/x = 1 (m = 2^(n−1)).
      const double scale = (m == first ? 0.5 : 1.0) / (double)m;
      const i128 nb = one_y - (i128)((u128)y * m);
      const double eb = (double)(nb < 0 ? -nb : nb) * y_to_ulp * scale;
      const uint64_t rq = q.exp_adj == 0 ? q.sig << 1 : q.sig;  // result · 2^o
      const i128 nq = (i128)((u128)rq * m) - one_q;
      const i128 aq = nq < 0 ? -nq : nq;
      const double eq = (double)aq * scale;
      p.max_b = std::max(p.max_b, eb);
      p.max_e = std::max(p.max_e, eq);
      p.sum += eq;
      p.sum2 += eq * eq;
      // Correctly rounded ⇔ error < ½ ulp (ties are impossible), in exact integers.
      p.cr += (2 * aq * (m == first ? 1 : 2) < (i128)m * 2) ? 1 : 0;
    }
    parts[ci] = p;
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned nthreads = (unsigned)std::min<uint64_t>(hw, chunks);
  std::atomic<uint64_t> next{0};
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < nthreads; ++t)
    pool.emplace_back([&] {
      for (uint64_t ci; (ci = next.fetch_add(1)) < chunks;) run(ci);
    });
  for (auto& t : pool) t.join();

  RecipErrorStats st;
  double sum = 0, sum2 = 0;
  uint64_t cr = 0;
  for (const Part& p : parts) {  // fixed order: thread-count independent
    st.max_err_ulp_before_round = std::max(st.max_err_ulp_before_round, p.max_b);
    st.max_err_ulp = std::max(st.max_err_ulp, p.max_e);
    sum += p.sum;
    sum2 += p.sum2;
    cr += p.cr;
  }
  st.count = total;
  st.mean_err_ulp = sum / (double)total;
  st.rms_err_ulp = std::sqrt(sum2 / (double)total);
  st.correctly_rounded_share = (double)cr / (double)total;
  st.faithful = st.max_err_ulp < 1.0;
  return st;
}

std::string recip_label(const RecipConfig& c) {
  return std::to_string(pow2(c.seed_index_bits)) + "x" + std::to_string(c.seed_frac_bits) + "+" +
         std::to_string(c.nr_steps) + "NR f" + std::to_string(c.nr_frac_bits) +
         (c.correction == RecipCorrection::Remainder ? " rem" : " none");
}

std::vector<RecipConfig> recip_sweep_configs() {
  std::vector<RecipConfig> out;
  auto add = [&](int s, int k, int nr, int f) {
    for (RecipCorrection corr : {RecipCorrection::None, RecipCorrection::Remainder}) {
      RecipConfig c;
      c.seed_index_bits = s;
      c.seed_frac_bits = k;
      c.nr_steps = nr;
      c.nr_frac_bits = f;
      c.correction = corr;
      out.push_back(c);
    }
  };
  // The anchor designs of ANCHORS.md with a near-ideal 40-bit datapath (reproduces its table).
  add(5, 7, 2, 40);
  add(6, 8, 2, 40);
  add(8, 8, 2, 40);
  add(12, 14, 1, 40);
  add(13, 15, 1, 40);
  // Two NR steps around the default (64×6, F = 26): table size, entry width, datapath width.
  add(5, 7, 2, 28);
  add(5, 8, 2, 30);
  add(6, 5, 2, 27);
  add(6, 6, 2, 25);
  add(6, 6, 2, 26);
  add(6, 6, 2, 27);
  add(6, 7, 2, 26);
  add(6, 8, 2, 26);
  add(6, 8, 2, 27);
  add(7, 7, 2, 26);
  add(8, 8, 2, 26);
  // One NR step: large tables, fewer multipliers, lower latency.
  add(11, 13, 1, 27);
  add(12, 13, 1, 27);
  add(12, 14, 1, 27);
  add(13, 15, 1, 27);
  // Three NR steps: tiny tables, more multipliers and latency.
  add(2, 4, 3, 27);
  add(3, 4, 3, 27);
  add(4, 5, 3, 26);
  return out;
}

}  // namespace fxr
