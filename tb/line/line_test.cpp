// tb/line/line_test.cpp — co-simulation of rtl/fxr_line.sv (a segment in, a pixel stream out, 1 → n)
// against fxr::line_pixels (model/stages/line.hpp) on the segment classes of the model test
// (tests/model/line_ref.hpp), with random input gaps and output back-pressure. Not a vector-file
// unit (the vector format is one output line per input line); compiled once per configuration:
// FXR_LINE_HEADER / FXR_LINE_DUT (the verilated model), FXR_LINE_CONFIG ("" = default),
// FXR_LINE_SUITE. docs/lines.md quotes the counts.
#include <gtest/gtest.h>

#include <cstdio>
#include <deque>
#include <memory>
#include <random>
#include <string>

#include <verilated.h>

#include FXR_LINE_HEADER
#include "model/config/config.hpp"
#include "model/stages/line.hpp"
#include "tests/model/line_ref.hpp"

using namespace fxr;

namespace {

struct CosimRun {
  uint64_t segments = 0, pixels = 0, errors = 0, cycles = 0;
};

CosimRun cosim(const Config& cfg, uint64_t seed, int per_class, unsigned gap_pct, unsigned stall_pct) {
  auto ctx = std::make_unique<VerilatedContext>();
  ctx->fatalOnError(false);
  auto dut = std::make_unique<FXR_LINE_DUT>(ctx.get());
  std::mt19937_64 hs(seed * 7919u);
  auto pct = [&](unsigned p) { return (hs() % 100) < p; };

  // The segments, and the expected pixel stream (all segments concatenated, model order).
  std::vector<LineIn> segs;
  line_ref::SegmentGen gen(cfg.raster, seed);
  for (int cls = 0; cls < (int)line_ref::SegClass::kCount; ++cls) {
    const int n = cls == (int)line_ref::SegClass::GuardBandLong ? std::max(1, per_class / 50) : per_class;
    for (int t = 0; t < n; ++t) segs.push_back(gen.next((line_ref::SegClass)cls));
  }
  std::shuffle(segs.begin(), segs.end(), hs);
  std::deque<LinePixel> exp;
  CosimRun r;
  for (const LineIn& s : segs)
    for (const LinePixel& p : line_pixels(cfg.raster, cfg.line, s)) exp.push_back(p);
  r.pixels = exp.size();

  auto tick = [&]() {
    dut->clk_i = 0;
    dut->eval();
    dut->clk_i = 1;
    dut->eval();
    ++r.cycles;
  };
  dut->rst_ni = 0;
  dut->in_valid_i = 0;
  dut->out_ready_i = 0;
  dut->clk_i = 0;
  dut->eval();
  tick();
  dut->rst_ni = 1;
  dut->eval();

  const int cb = cfg.raster.window_int_bits + cfg.raster.subpixel_bits;
  const uint32_t mask = (uint32_t)((1ull << cb) - 1);
  const int wb = cfg.raster.window_int_bits;
  auto sx = [&](uint32_t v) { return (int32_t)(v << (32 - wb)) >> (32 - wb); };
  size_t next = 0;
  uint64_t idle = 0;
  while (next < segs.size() || !exp.empty()) {
    // Drive (values settle before the edge).
    const bool offer = next < segs.size() && !pct(gap_pct);
    dut->in_valid_i = offer;
    if (offer) {
      dut->in_x0_i = (uint32_t)segs[next].x0 & mask;
      dut->in_y0_i = (uint32_t)segs[next].y0 & mask;
      dut->in_x1_i = (uint32_t)segs[next].x1 & mask;
      dut->in_y1_i = (uint32_t)segs[next].y1 & mask;
    }
    dut->out_ready_i = !pct(stall_pct);
    dut->eval();
    const bool in_fire = dut->in_valid_i && dut->in_ready_o;
    const bool out_fire = dut->out_valid_o && dut->out_ready_i;
    if (out_fire) {
      const LinePixel got{sx(dut->out_x_o), sx(dut->out_y_o)};
      if (exp.empty()) {
        if (r.errors++ < 20) std::printf("MISMATCH line extra pixel (%d,%d)\n", got.x, got.y);
      } else {
        if (!(got == exp.front()) && r.errors++ < 20)
          std::printf("MISMATCH line pixel=%llu got=(%d,%d) exp=(%d,%d)\n",
                      (unsigned long long)(r.pixels - exp.size()), got.x, got.y, exp.front().x, exp.front().y);
        exp.pop_front();
      }
      idle = 0;
    }
    if (in_fire) ++next, ++r.segments;
    tick();
    if (++idle > 200000) {
      std::printf("MISMATCH line: %zu pixels never came out\n", exp.size());
      r.errors += exp.size();
      break;
    }
  }
  // Drain: nothing more may come out.
  dut->in_valid_i = 0;
  dut->out_ready_i = 1;
  for (int k = 0; k < 8; ++k) {
    dut->eval();
    if (dut->out_valid_o && r.errors++ < 20) std::printf("MISMATCH line extra pixel at drain\n");
    tick();
  }
  EXPECT_FALSE(ctx->gotError());
  std::printf("line: segments=%llu checked=%llu errors=%llu cycles=%llu\n%s\n", (unsigned long long)r.segments,
              (unsigned long long)r.pixels, (unsigned long long)r.errors, (unsigned long long)r.cycles,
              r.errors ? "FAILED" : "PASSED");
  return r;
}

Config config() {
  const std::string path = FXR_LINE_CONFIG;
  return path.empty() ? Config{} : load_config(path);
}

}  // namespace

// Back-to-back: no gaps, no stalls; the unit takes a step per clock.
TEST(FXR_LINE_SUITE, MatchesModelOneStepPerClock) {
  const CosimRun r = cosim(config(), 3, 1500, 0, 0);
  EXPECT_EQ(r.errors, 0u);
  EXPECT_GT(r.pixels, r.segments);
}

TEST(FXR_LINE_SUITE, MatchesModelUnderGapsAndStalls) {
  const CosimRun r = cosim(config(), 4, 1500, 25, 25);
  EXPECT_EQ(r.errors, 0u);
}
