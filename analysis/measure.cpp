// Error measurement and sweep lists of the arithmetic units (analysis/measure.hpp).
#include "analysis/measure.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <random>
#include <thread>

namespace fxr {

namespace {

using u128 = unsigned __int128;
using i128 = __int128;

uint64_t pow2(int e) { return uint64_t{1} << e; }

// Number of fixed chunks a measurement splits its inputs into. Statistics are combined chunk by
// chunk in index order, so the result does not depend on how many threads ran them.
constexpr uint64_t kMeasureChunks = 64;

// Per-chunk statistics, combined in chunk order.
struct Accum {
  double max = 0, max_before = 0, sum = 0, sum2 = 0;
  uint64_t count = 0, correct = 0;
  void add(double e, bool cr) {
    max = std::max(max, e);
    sum += e;
    sum2 += e * e;
    ++count;
    correct += cr ? 1 : 0;
  }
  void merge(const Accum& o) {
    max = std::max(max, o.max);
    max_before = std::max(max_before, o.max_before);
    sum += o.sum;
    sum2 += o.sum2;
    count += o.count;
    correct += o.correct;
  }
  ErrorStats stats() const {
    ErrorStats st;
    st.count = count;
    st.max_err_ulp = max;
    st.max_err_ulp_before_round = max_before;
    st.mean_err_ulp = count ? sum / (double)count : 0;
    st.rms_err_ulp = count ? std::sqrt(sum2 / (double)count) : 0;
    st.correctly_rounded_share = count ? (double)correct / (double)count : 0;
    st.correctly_rounded = correct == count;
    st.faithful = max < 1.0;
    return st;
  }
};

// Runs fn(chunk, accum) for every chunk on the machine's threads, then merges in chunk order.
Accum run_chunks(uint64_t chunks, const std::function<void(uint64_t, Accum&)>& fn) {
  std::vector<Accum> parts(chunks);
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned nthreads = (unsigned)std::min<uint64_t>(hw, chunks);
  std::atomic<uint64_t> next{0};
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < nthreads; ++t)
    pool.emplace_back([&] {
      for (uint64_t ci; (ci = next.fetch_add(1)) < chunks;) fn(ci, parts[ci]);
    });
  for (auto& t : pool) t.join();
  Accum all;
  for (const Accum& p : parts) all.merge(p);  // fixed order: thread-count independent
  return all;
}

// ---- reciprocal unit ----------------------------------------------------------------------

// Exact error of the unit at significand m, in ulps of the exact result's binade (2^−o below
// 1, 2^−(o−1) for 1/x = 1, m = 2^(n−1)); before-rounding error of y likewise.
void recip_account(const RecipUnit& unit, uint64_t m, Accum& p) {
  const RecipConfig& c = unit.config();
  const int n = c.in_sig_bits, o = c.out_sig_bits, f = c.nr_frac_bits;
  const uint64_t first = pow2(n - 1);
  const i128 one_y = (i128)1 << (n - 1 + f);  // 1/x · m · 2^F  (exact numerator for y)
  const i128 one_q = (i128)1 << (n - 1 + o);  // 1/x · m · 2^o  (exact numerator for the result)
  const uint64_t y = unit.approx(m);
  const RecipSig q = unit.round(m, y);
  const double scale = (m == first ? 0.5 : 1.0) / (double)m;
  const i128 nb = one_y - (i128)((u128)y * m);
  p.max_before = std::max(p.max_before, (double)(nb < 0 ? -nb : nb) * std::ldexp(1.0, o - f) * scale);
  const uint64_t rq = q.exp_adj == 0 ? q.sig << 1 : q.sig;  // result · 2^o
  const i128 nq = (i128)((u128)rq * m) - one_q;
  const i128 aq = nq < 0 ? -nq : nq;
  // Correctly rounded ⇔ error < ½ ulp (ties are impossible), in exact integers.
  p.add((double)aq * scale, 2 * aq * (m == first ? 1 : 2) < (i128)m * 2);
}

}  // namespace

ErrorStats measure(const RecipConfig& c, const MeasureOptions& opt) {
  const RecipUnit unit(c);
  const uint64_t first = pow2(c.in_sig_bits - 1), total = pow2(c.in_sig_bits - 1);
  if (opt.exhaustive) {
    const uint64_t chunks = std::min<uint64_t>(kMeasureChunks, total);
    return run_chunks(chunks, [&](uint64_t ci, Accum& p) {
             const uint64_t lo = first + total * ci / chunks, hi = first + total * (ci + 1) / chunks;
             for (uint64_t m = lo; m < hi; ++m) recip_account(unit, m, p);
           }).stats();
  }
  Accum p;
  std::mt19937_64 rng(opt.seed);
  for (uint64_t i = 0; i < opt.count; ++i) recip_account(unit, first + rng() % total, p);
  return p.stats();
}

// ---- divider ------------------------------------------------------------------------------

namespace {

// Exact error of s against n/d in ulps of the exact quotient's binade, written from the div_sig
// contract: with a = n·2^(W−nb), b = d·2^(W−db) (exact), k = [a < b], ulp = 2^(−k−(qb−1)),
//   |sig·2^exp_adj·2^−(qb−1) − a/b| / ulp = |sig·2^(exp_adj+k)·b − a·2^(qb−1+k)| / b.
double div_err_ulp(const DivConfig& c, const DivSig& s, uint64_t n, uint64_t d) {
  const int w = div_align_bits(c);
  const uint64_t a = n << (w - c.num_bits), b = d << (w - c.den_bits);
  const int k = a < b ? 1 : 0;
  const int sh = s.exp_adj + k;  // ∈ {0, 1} by the div_sig contract
  const u128 got = ((u128)s.sig * b) << (sh < 0 ? 0 : sh);
  const u128 want = (u128)a << (c.quot_bits - 1 + k);
  const u128 diff = got > want ? got - want : want - got;
  return (double)diff / (double)b;  // double only for the statistic
}

void div_account(const DivConfig& c, uint64_t n, uint64_t d, Accum& acc) {
  const DivSig got = div_sig(c, n, d);
  acc.add(div_err_ulp(c, got, n, d), got == div_sig_exact(c, n, d));
}

}  // namespace

ErrorStats measure(const DivConfig& c, const MeasureOptions& opt) {
  const int nb = c.num_bits, db = c.den_bits, qb = c.quot_bits, w = div_align_bits(c);
  const uint64_t nlo = pow2(nb - 1), nhi = pow2(nb) - 1;
  const uint64_t dlo = pow2(db - 1), dhi = pow2(db) - 1;
  if (opt.exhaustive) {
    const uint64_t chunks = std::min<uint64_t>(kMeasureChunks, dhi - dlo + 1);
    const uint64_t span = dhi - dlo + 1;
    return run_chunks(chunks, [&](uint64_t ci, Accum& p) {
             for (uint64_t d = dlo + span * ci / chunks; d < dlo + span * (ci + 1) / chunks; ++d)
               for (uint64_t n = nlo; n <= nhi; ++n) div_account(c, n, d, p);
           }).stats();
  }
  Accum acc;
  std::mt19937_64 rng(opt.seed);
  auto rand_in = [&](uint64_t lo, uint64_t hi) { return lo + rng() % (hi - lo + 1); };
  // Directed: range ends.
  for (uint64_t n : {nlo, nlo + 1, nhi - 1, nhi})
    for (uint64_t d : {dlo, dlo + 1, dhi - 1, dhi}) div_account(c, n, d, acc);
  // Directed: n equal (after alignment) to d and its neighbours; divisors on seed-interval edges.
  for (int i = 0; i < 256; ++i) {
    const uint64_t d = rand_in(dlo, dhi);
    const uint64_t a = (nb >= db) ? d << (nb - db) : d >> (db - nb);
    for (int64_t delta : {-1, 0, 1}) {
      const uint64_t n = a + delta;
      if (n >= nlo && n <= nhi) div_account(c, n, d, acc);
    }
    const int si = c.seed_index_bits < db - 1 ? c.seed_index_bits : db - 1;
    const uint64_t edge = dlo + (rand_in(0, pow2(si) - 1) << (db - 1 - si));
    for (int64_t delta : {-1, 0, 1}) {
      const uint64_t dd = edge + delta;
      if (dd >= dlo && dd <= dhi) div_account(c, rand_in(nlo, nhi), dd, acc);
    }
  }
  // Directed: exact rounding ties X = q + ½ and their neighbours n ± 1. a'·2^qb = (2q+1)·b
  // needs b = m·2^qb (possible when W − 1 ≥ qb); then a' = (2q+1)·m, a = a' (if < 2^W) or a'/2.
  if (w - 1 >= qb) {
    for (int i = 0, made = 0; i < 8000 && made < 2000; ++i) {
      const uint64_t m = rand_in(pow2(w - 1 - qb), pow2(w - qb) - 1);
      const uint64_t b = m << qb;
      const uint64_t q = rand_in(pow2(qb - 1), pow2(qb) - 1);
      const u128 a1 = (u128)(2 * q + 1) * m;
      if (a1 >= ((u128)1 << w) && (a1 & 1)) continue;  // k = 1 needs an even a'
      const uint64_t a = (uint64_t)(a1 >= ((u128)1 << w) ? a1 >> 1 : a1);
      if ((a & (pow2(w - nb) - 1)) || (b & (pow2(w - db) - 1))) continue;
      const uint64_t n = a >> (w - nb), d = b >> (w - db);
      for (int64_t delta : {-1, 0, 1}) {
        const uint64_t nn = n + delta;
        if (nn >= nlo && nn <= nhi) div_account(c, nn, d, acc);
      }
      ++made;
    }
  }
  for (uint64_t i = 0; i < opt.count; ++i) {
    const uint64_t n = rand_in(nlo, nhi), d = rand_in(dlo, dhi);
    div_account(c, n, d, acc);
  }
  return acc.stats();
}

// ---- sweeps and labels --------------------------------------------------------------------

std::string recip_label(const RecipConfig& c) {
  return std::to_string(pow2(c.seed_index_bits)) + "x" + std::to_string(c.seed_frac_bits) + "+" +
         std::to_string(c.nr_steps) + "NR f" + std::to_string(c.nr_frac_bits) +
         (c.correction == RecipCorrection::Remainder ? " rem" : " none");
}

std::vector<RecipConfig> recip_sweep_configs() {
  std::vector<RecipConfig> out;
  // (seed index bits, seed frac bits, NR steps, datapath fraction bits), each with and without
  // the correction.
  const int rows[][4] = {
      // The anchor designs of docs/arith.md with a near-ideal 40-bit datapath (reproduces them).
      {5, 7, 2, 40}, {6, 8, 2, 40}, {8, 8, 2, 40}, {12, 14, 1, 40}, {13, 15, 1, 40},
      // Two NR steps around the default (64×6, F = 26): table size, entry width, datapath width.
      {5, 7, 2, 28}, {5, 8, 2, 30}, {6, 5, 2, 27}, {6, 6, 2, 25}, {6, 6, 2, 26}, {6, 6, 2, 27},
      {6, 7, 2, 26}, {6, 8, 2, 26}, {6, 8, 2, 27}, {7, 7, 2, 26}, {8, 8, 2, 26},
      // One NR step: large tables, fewer multipliers, lower latency.
      {11, 13, 1, 27}, {12, 13, 1, 27}, {12, 14, 1, 27}, {13, 15, 1, 27},
      // Three NR steps: tiny tables, more multipliers and latency.
      {2, 4, 3, 27}, {3, 4, 3, 27}, {4, 5, 3, 26}};
  for (const auto& p : rows)
    for (RecipCorrection corr : {RecipCorrection::None, RecipCorrection::Remainder}) {
      RecipConfig c;
      c.seed_index_bits = p[0];
      c.seed_frac_bits = p[1];
      c.nr_steps = p[2];
      c.nr_frac_bits = p[3];
      c.correction = corr;
      out.push_back(c);
    }
  return out;
}

std::vector<DivConfig> div_sweep_configs() {
  std::vector<DivConfig> v;
  const DivConfig base;
  for (DivSchedule sch : {DivSchedule::Pipelined, DivSchedule::Iterative})
    for (int k : {1, 2, 4}) {
      DivConfig c = base;
      c.algorithm = DivAlgorithm::Radix2;
      c.schedule = sch;
      c.bits_per_stage = k;
      v.push_back(c);
    }
  // recip_mul: (seed index bits, seed bits, NR steps, iterate fraction bits), including the
  // anchor designs of docs/arith.md and ones too coarse for the ±1 correction.
  const int rm[][4] = {{5, 7, 2, 28},  {6, 8, 2, 28},  {8, 8, 2, 28},  {8, 8, 2, 26},
                       {8, 8, 2, 25},  {12, 14, 1, 28}, {13, 15, 1, 28}, {8, 8, 1, 28},
                       {10, 10, 1, 28}, {6, 8, 1, 28},  {4, 4, 2, 28},  {4, 4, 3, 28}};
  for (const auto& p : rm) {
    DivConfig c = base;
    c.algorithm = DivAlgorithm::RecipMul;
    c.seed_index_bits = p[0];
    c.seed_bits = p[1];
    c.nr_steps = p[2];
    c.nr_frac_bits = p[3];
    v.push_back(c);
  }
  // shared_recip (one reciprocal per pixel, one multiply per varying, rounded once): the same
  // reciprocal core shapes, and wider iterates (the error bound is 0.5 + 2^qb·δ).
  const int sr[][4] = {{8, 8, 2, 28}, {8, 8, 2, 26}, {8, 8, 2, 30}, {8, 8, 2, 32}, {6, 8, 2, 28},
                       {5, 7, 2, 28}, {12, 14, 1, 28}, {13, 15, 1, 30}, {8, 8, 1, 28}, {4, 4, 3, 30}};
  for (const auto& p : sr) {
    DivConfig c = base;
    c.algorithm = DivAlgorithm::SharedRecip;
    c.seed_index_bits = p[0];
    c.seed_bits = p[1];
    c.nr_steps = p[2];
    c.nr_frac_bits = p[3];
    v.push_back(c);
  }
  return v;
}

std::string div_label(const DivConfig& c) {
  if (c.algorithm == DivAlgorithm::Radix2)
    return "radix2 k=" + std::to_string(c.bits_per_stage) +
           (c.schedule == DivSchedule::Iterative ? " iter" : " pipe");
  return std::string(c.algorithm == DivAlgorithm::SharedRecip ? "shared_recip " : "recip_mul ") +
         std::to_string(1 << c.seed_index_bits) + "x" + std::to_string(c.seed_bits) +
         " nr" + std::to_string(c.nr_steps) + " f" + std::to_string(c.nr_frac_bits);
}

}  // namespace fxr
