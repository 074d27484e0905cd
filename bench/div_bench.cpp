// div_sig throughput per algorithm at the default widths (32 / 32 → 24), with baselines in
// the same run: plain double division and plain __int128 division of the same operands.
// Report ratios (items_per_second of a case / of BM_Baseline_Double); never pass/fail on time.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "model/arith/div.hpp"

using namespace fxr;

namespace {

struct Operands {
  std::vector<uint64_t> n, d;
};

// 4096 random normalised operand pairs at the default widths (fixed seed).
const Operands& operands() {
  static const Operands ops = [] {
    Operands o;
    const DivConfig c;
    std::mt19937_64 rng(1);
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    for (int i = 0; i < 4096; ++i) {
      o.n.push_back(nlo + rng() % nlo);
      o.d.push_back(dlo + rng() % dlo);
    }
    return o;
  }();
  return ops;
}

template <class F>
void run(benchmark::State& st, F&& f) {
  const Operands& o = operands();
  const size_t m = o.n.size();
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(f(o.n[i], o.d[i]));
    i = (i + 1) & (m - 1);
  }
  st.SetItemsProcessed(st.iterations());
}

DivConfig with(DivAlgorithm a) {
  DivConfig c;
  c.algorithm = a;
  return c;
}

}  // namespace

// Baselines: what the same quotient costs without any bit-accuracy (double), and an exact
// truncated integer division of the same width (no rounding step).
static void BM_Baseline_Double(benchmark::State& st) {
  run(st, [](uint64_t n, uint64_t d) { return (double)n / (double)d; });
}
static void BM_Baseline_Int128Div(benchmark::State& st) {
  run(st, [](uint64_t n, uint64_t d) { return ((u128)n << 23) / (u128)d; });
}
// The pipeline's entry point per algorithm.
static void BM_DivSig_Radix2(benchmark::State& st) {
  const DivConfig c = with(DivAlgorithm::Radix2);
  run(st, [&](uint64_t n, uint64_t d) { return div_sig(c, n, d).sig; });
}
static void BM_DivSig_RecipMul(benchmark::State& st) {
  const DivConfig c = with(DivAlgorithm::RecipMul);
  run(st, [&](uint64_t n, uint64_t d) { return div_sig(c, n, d).sig; });
}
// The step-by-step radix-2 model (what div_sig would cost without the proven-equal fast path).
static void BM_DivSigRadix2Steps(benchmark::State& st) {
  const DivConfig c = with(DivAlgorithm::Radix2);
  run(st, [&](uint64_t n, uint64_t d) { return div_sig_radix2_steps(c, n, d).sig; });
}

BENCHMARK(BM_Baseline_Double);
BENCHMARK(BM_Baseline_Int128Div);
BENCHMARK(BM_DivSig_Radix2);
BENCHMARK(BM_DivSig_RecipMul);
BENCHMARK(BM_DivSigRadix2Steps);
