// Throughput of the reciprocal unit's significand core (recip_sig) at the default configuration,
// beside baselines measured in the same run: exact integer division with round to nearest (the
// reference the tests use) and float 1.0f / x (hardware, not bit-exact to anything here).
// Each benchmark reports items_per_second (= ops/s); BM_RecipSigVsBaselines also reports the
// ratios, timed back to back in one loop so machine noise hits both alike. No pass/fail on time.
#include <benchmark/benchmark.h>

#include <chrono>

#include "model/stages/recip.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// A sweep over consecutive significands (as the exhaustive test does), wrapping in the range.
struct Sigs {
  uint64_t first, mask, i = 0;
  explicit Sigs(int n) : first(uint64_t{1} << (n - 1)), mask((uint64_t{1} << (n - 1)) - 1) {}
  uint64_t next() { return first | (i++ & mask); }
};

uint64_t int_div_rn(int n, int o, uint64_t m) {
  const uint64_t num = uint64_t{1} << (n - 1 + o);
  const uint64_t q = num / m, r = num % m;
  return q + (2 * r > m);
}

void BM_RecipSig(benchmark::State& state) {
  const fxr::RecipConfig cfg;
  Sigs s(cfg.in_sig_bits);
  for (auto _ : state) benchmark::DoNotOptimize(fxr::recip_sig(cfg, s.next()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RecipSig);

void BM_RecipUnitSig(benchmark::State& state) {
  const fxr::RecipUnit unit{fxr::RecipConfig{}};
  Sigs s(unit.config().in_sig_bits);
  for (auto _ : state) benchmark::DoNotOptimize(unit.sig(s.next()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RecipUnitSig);

void BM_IntDivideBaseline(benchmark::State& state) {
  const fxr::RecipConfig cfg;
  Sigs s(cfg.in_sig_bits);
  for (auto _ : state) benchmark::DoNotOptimize(int_div_rn(cfg.in_sig_bits, cfg.out_sig_bits, s.next()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IntDivideBaseline);

void BM_FloatRecipBaseline(benchmark::State& state) {
  float x = 1.0f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(1.0f / x);
    x = x < 2.0f ? x + 1.1920929e-7f : 1.0f;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FloatRecipBaseline);

// recip_sig, integer division and 1.0f/x over the same 2^16 significands, alternating per block.
void BM_RecipSigVsBaselines(benchmark::State& state) {
  const fxr::RecipConfig cfg;
  const int n = cfg.in_sig_bits, o = cfg.out_sig_bits;
  constexpr uint64_t kBlock = 1 << 16;
  double t_recip = 0, t_div = 0, t_float = 0;
  uint64_t sink = 0, base = uint64_t{1} << (n - 1);
  float fsink = 0;
  for (auto _ : state) {
    auto t0 = Clock::now();
    for (uint64_t m = base; m < base + kBlock; ++m) sink += fxr::recip_sig(cfg, m).sig;
    auto t1 = Clock::now();
    for (uint64_t m = base; m < base + kBlock; ++m) sink += int_div_rn(n, o, m);
    auto t2 = Clock::now();
    for (uint64_t m = base; m < base + kBlock; ++m) fsink += 1.0f / (float)m;
    auto t3 = Clock::now();
    t_recip += std::chrono::duration<double>(t1 - t0).count();
    t_div += std::chrono::duration<double>(t2 - t1).count();
    t_float += std::chrono::duration<double>(t3 - t2).count();
    base = (uint64_t{1} << (n - 1)) | ((base + kBlock) & ((uint64_t{1} << (n - 1)) - 1));
  }
  benchmark::DoNotOptimize(sink);
  benchmark::DoNotOptimize(fsink);
  const double ops = (double)state.iterations() * kBlock;
  state.counters["recip_Mops"] = ops / t_recip / 1e6;
  state.counters["intdiv_Mops"] = ops / t_div / 1e6;
  state.counters["float_Mops"] = ops / t_float / 1e6;
  state.counters["recip_vs_intdiv"] = t_div / t_recip;     // > 1: recip_sig is faster
  state.counters["recip_vs_float"] = t_float / t_recip;
}
BENCHMARK(BM_RecipSigVsBaselines)->Unit(benchmark::kMillisecond);

}  // namespace
