// Speed of the fixed-point primitives against SystemC's fixed-point types, same operation
// sequence: a Q16.16 multiply-accumulate chain over an array,
//     acc = round_half_even(a[i] · b[i] + acc) saturated to Q16.16 (s15.16, 32 bits),
// done four ways in one run:
//   Mac_HandInt64     — hand-written int64 (the floor: what a careful C programmer writes)
//   Mac_Fxr           — fxr::mac with a runtime FxFormat (what the model uses)
//   Mac_ScFixed       — sc_fixed<32,16,SC_RND_CONV,SC_SAT>  (the bit-exact oracle)
//   Mac_ScFixedFast   — sc_fixed_fast<32,16,SC_RND_CONV,SC_SAT> (double-based; 53-bit mantissa)
// After the runs a table prints each time per element as a ratio to Mac_Fxr, and whether the
// final accumulators agree (sc_fixed_fast may not: a·b needs 64 bits, a double keeps 53).
// Timings are on a shared machine: read the ratios, not the absolute figures.
#define SC_INCLUDE_FX
#include <systemc.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "model/arith/fixed.hpp"

int sc_main(int, char*[]) { return 0; }  // libsystemc's main() wants it; ours is below

namespace {

// The benchmarked format: Q16.16 = 32 bits, 16 fraction bits, signed.
constexpr int kQWidth = 32;
constexpr int kQFrac = 16;
constexpr int kQInt = kQWidth - kQFrac;  // sc_fixed's iwl
// Array length: long enough to amortise the loop, short enough to stay in L1/L2.
constexpr int kLen = 4096;
// Operand magnitude: |a|, |b| < 2^kOperandIntBits, so products reach 2^(2·7) and the
// accumulator's random walk saturates now and then (the saturation branch is exercised).
constexpr int kOperandIntBits = 6;

const fxr::FxFormat kQ16{kQWidth, kQFrac, true, fxr::Round::HalfEven, fxr::Overflow::Saturate};

struct Data {
  std::vector<int32_t> a, b;
  Data() {
    std::mt19937_64 rng(42);
    const int64_t span = int64_t(1) << (kOperandIntBits + kQFrac);
    for (int i = 0; i < kLen; ++i) {
      a.push_back((int32_t)((int64_t)(rng() % (2 * span)) - span));
      b.push_back((int32_t)((int64_t)(rng() % (2 * span)) - span));
    }
  }
};
const Data& data() {
  static const Data d;
  return d;
}

std::map<std::string, int64_t> g_final;  // final accumulator code per variant

// Hand-written: Q32.32 product + aligned acc, round half to even at bit kQFrac, clamp.
int64_t mac_hand(int32_t a, int32_t b, int64_t acc) {
  const int64_t wide = (int64_t)a * b + (acc << kQFrac);  // |·| < 2^63: exact
  int64_t q = wide >> kQFrac;                              // floor
  const int64_t rem = wide & ((int64_t(1) << kQFrac) - 1);
  const int64_t half = int64_t(1) << (kQFrac - 1);
  if (rem > half || (rem == half && (q & 1))) ++q;
  const int64_t hi = (int64_t(1) << (kQWidth - 1)) - 1, lo = -(int64_t(1) << (kQWidth - 1));
  return q > hi ? hi : (q < lo ? lo : q);
}

void Mac_HandInt64(benchmark::State& st) {
  const Data& d = data();
  int64_t acc = 0;
  for (auto _ : st) {
    acc = 0;
    for (int i = 0; i < kLen; ++i) acc = mac_hand(d.a[i], d.b[i], acc);
    benchmark::DoNotOptimize(acc);
  }
  g_final["Mac_HandInt64"] = acc;
  st.SetItemsProcessed(st.iterations() * kLen);
}

void Mac_Fxr(benchmark::State& st) {
  const Data& d = data();
  int64_t acc = 0;
  for (auto _ : st) {
    acc = 0;
    for (int i = 0; i < kLen; ++i) acc = fxr::mac(d.a[i], kQFrac, d.b[i], kQFrac, acc, kQFrac, kQ16);
    benchmark::DoNotOptimize(acc);
  }
  g_final["Mac_Fxr"] = acc;
  st.SetItemsProcessed(st.iterations() * kLen);
}

// Raw code of a SystemC fixed-point value with kQFrac fraction bits.
template <class T>
int64_t code_of(const T& x) {
  return (int64_t)(x.to_double() * (double)(int64_t(1) << kQFrac));  // exact: 32-bit code
}

template <class Acc, class Op>
void run_sc(benchmark::State& st, const char* name) {
  const Data& d = data();
  // Operands converted to the SystemC type once, outside the timed loop (as the fxr
  // variants get them as ready codes).
  std::vector<Op> a(kLen), b(kLen);
  for (int i = 0; i < kLen; ++i) {
    a[i] = (double)d.a[i] / (double)(int64_t(1) << kQFrac);  // exact: 32-bit code in a double
    b[i] = (double)d.b[i] / (double)(int64_t(1) << kQFrac);
  }
  Acc acc;
  for (auto _ : st) {
    acc = 0;
    for (int i = 0; i < kLen; ++i) acc = a[i] * b[i] + acc;
    benchmark::DoNotOptimize(acc);
  }
  g_final[name] = code_of(acc);
  st.SetItemsProcessed(st.iterations() * kLen);
}

using ScQ16 = sc_dt::sc_fixed<kQWidth, kQInt, sc_dt::SC_RND_CONV, sc_dt::SC_SAT>;
using ScQ16Fast = sc_dt::sc_fixed_fast<kQWidth, kQInt, sc_dt::SC_RND_CONV, sc_dt::SC_SAT>;

void Mac_ScFixed(benchmark::State& st) { run_sc<ScQ16, ScQ16>(st, "Mac_ScFixed"); }
void Mac_ScFixedFast(benchmark::State& st) { run_sc<ScQ16Fast, ScQ16Fast>(st, "Mac_ScFixedFast"); }

BENCHMARK(Mac_HandInt64);
BENCHMARK(Mac_Fxr);
BENCHMARK(Mac_ScFixed);
BENCHMARK(Mac_ScFixedFast);

// Keeps the console output and remembers the CPU time per element of each run.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> ns_per_item;
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs)
      if (r.run_type == Run::RT_Iteration && r.iterations > 0)
        // GetAdjustedCPUTime: CPU time per iteration in r.time_unit; one iteration = kLen macs.
        ns_per_item[r.benchmark_name()] =
            r.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(r.time_unit) * 1e9 / kLen;
  }
};

// Untimed check of every step of the chain: each variant's accumulator code after each
// element against sc_fixed's (the oracle). Returns the number of differing steps.
template <class F>
int steps_differing_from_sc_fixed(F&& step) {
  const Data& d = data();
  ScQ16 sacc = 0;
  int64_t acc = 0;
  int bad = 0;
  for (int i = 0; i < kLen; ++i) {
    ScQ16 sa, sb;
    sa = (double)d.a[i] / (double)(int64_t(1) << kQFrac);
    sb = (double)d.b[i] / (double)(int64_t(1) << kQFrac);
    sacc = sa * sb + sacc;
    acc = step(i, acc);
    bad += acc != code_of(sacc);
  }
  return bad;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  benchmark::Shutdown();
  const Data& d = data();
  int saturated = 0;
  for (int i = 0, acc = 0; i < kLen; ++i) {
    acc = (int)fxr::mac(d.a[i], kQFrac, d.b[i], kQFrac, acc, kQFrac, kQ16);
    saturated += acc == kQ16.max_code() || acc == kQ16.min_code();
  }
  std::printf("\nchain steps at a saturation limit: %d of %d\n", saturated, kLen);
  std::printf("steps differing from sc_fixed: Mac_Fxr %d, Mac_HandInt64 %d, Mac_ScFixedFast %d\n",
              steps_differing_from_sc_fixed([&](int i, int64_t acc) {
                return fxr::mac(d.a[i], kQFrac, d.b[i], kQFrac, acc, kQFrac, kQ16);
              }),
              steps_differing_from_sc_fixed([&](int i, int64_t acc) { return mac_hand(d.a[i], d.b[i], acc); }),
              [&] {
                ScQ16Fast f = 0;
                return steps_differing_from_sc_fixed([&](int i, int64_t) {
                  ScQ16Fast fa, fb;
                  fa = (double)d.a[i] / (double)(int64_t(1) << kQFrac);
                  fb = (double)d.b[i] / (double)(int64_t(1) << kQFrac);
                  f = fa * fb + f;
                  return code_of(f);
                });
              }());
  const auto base = rep.ns_per_item.find("Mac_Fxr");
  if (base == rep.ns_per_item.end()) return 0;
  std::printf("\nQ16.16 mac, round half even, saturate; %d elements; ratios to Mac_Fxr (same run):\n", kLen);
  std::printf("  %-18s %10s %8s  %s\n", "variant", "ns/elem", "ratio", "final acc (bit-exact?)");
  const int64_t want = g_final.count("Mac_Fxr") ? g_final["Mac_Fxr"] : 0;
  for (const auto& [name, ns] : rep.ns_per_item) {
    const bool have = g_final.count(name) != 0;
    std::printf("  %-18s %10.2f %7.1fx  %lld %s\n", name.c_str(), ns, ns / base->second,
                have ? (long long)g_final[name] : 0LL, !have ? "" : (g_final[name] == want ? "same" : "DIFFERS"));
  }
  return 0;
}
