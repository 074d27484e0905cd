// Stage 9 at one pixel (PixelDivide, model/stages/pixel_divide.hpp) against the fused span's
// per-pixel cost (FusedSpan, model/stages/interp_span.hpp) on spans of 1, 2 and 4 pixels with
// two varyings at the default widths (docs/speed.md "Session 13: the divider of one pixel").
//   BM_PixelDivide_Write       the divider alone: the sums of each pixel precomputed
//   BM_PixelDivide_AtWrite     the sums from Plane::at (D, N_0, N_1), the record's header and
//                              the divider: what a kernel visiting pixels in any order pays
//   BM_FusedSpan/L             FusedSpan::run on spans of L pixels (no depth test): the span
//                              start (cursor move) and the segment loop, per pixel
// items = pixels; compare items_per_second in one run, never pass/fail on time.
#include <benchmark/benchmark.h>

#include <cstring>
#include <vector>

#include "model/stages/interp_span.hpp"
#include "model/stages/pixel_divide.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/geometry.hpp"

using namespace fxr;

namespace {

constexpr int kNv = 2;

struct Scene {
  Config cfg;
  DrawState st;
  TriangleEquations eq;
  std::vector<Span> spans[5];  // spans[L]: parts of L pixels of the triangle's spans (L = 1, 2, 4)
};

// One perspective triangle over most of a 256 × 256 viewport (its spans long enough to cut).
const Scene& scene() {
  static const Scene s = [] {
    Scene sc;
    sc.st.num_varyings = kNv;
    sc.st.depth_test = false, sc.st.depth_write = false;
    ClipTriangle tri;
    const float p[3][4] = {{-0.9f, -0.9f, 0.2f, 1.0f}, {3.5f, -1.0f, 1.5f, 4.0f}, {-0.5f, 1.6f, 0.9f, 2.0f}};
    const float v[3][2] = {{-2.0f, 0.5f}, {3.0f, -1.5f}, {0.25f, 4.0f}};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 4; ++c) tri.v[k].pos[c] = p[k][c];
      for (int m = 0; m < kNv; ++m) tri.v[k].var[m] = v[k][m];
    }
    std::vector<SetupTriangle> pieces;
    RasterStats gs;
    geometry(sc.cfg, sc.st, tri, 1, pieces, gs);
    SetupStage setup(sc.cfg, sc.st, true);
    TraverseStage traverse(sc.cfg, sc.st);
    setup.step(pieces.at(0), [&](const TriangleEquations& eq) {
      sc.eq = eq;
      traverse.step(eq, [&](const Span& sp) {
        for (int len : {1, 2, 4})
          for (int x = sp.x0; x + len - 1 <= sp.x1; x += 7) sc.spans[len].push_back(Span{sp.prim, sp.y, x, x + len - 1});
      });
    });
    return sc;
  }();
  return s;
}

void BM_PixelDivide_Write(benchmark::State& state) {
  const Scene& sc = scene();
  const std::vector<Span>& spans = sc.spans[4];
  std::vector<u128> sums;
  for (const Span& sp : spans)
    for (int i = sp.x0; i <= sp.x1; ++i) {
      sums.push_back((u128)sc.eq.interp.den.at(i, sp.y));
      for (int m = 0; m < kNv; ++m) sums.push_back((u128)sc.eq.interp.num[m].at(i, sp.y));
    }
  PixelDivide pd(sc.cfg.div, kNv);
  pd.begin(sc.eq);
  std::vector<uint8_t> rec(fragment_record_bytes(kNv) * 64);
  const size_t pixels = sums.size() / (1 + kNv);
  size_t k = 0;
  for (auto _ : state) {
    pd.write_t<kNv>(rec.data() + (k & 63) * fragment_record_bytes(kNv), &sums[k * (1 + kNv)], DefaultDivWidths{});
    benchmark::ClobberMemory();
    k = k + 1 == pixels ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_PixelDivide_AtWrite(benchmark::State& state) {
  const Scene& sc = scene();
  const std::vector<Span>& spans = sc.spans[state.range(0)];
  PixelDivide pd(sc.cfg.div, kNv);
  pd.begin(sc.eq);
  std::vector<uint8_t> rec(fragment_record_bytes(kNv) * 4 * 64);
  const TriangleEquations& eq = sc.eq;
  size_t k = 0, pixels = 0;
  for (auto _ : state) {
    const Span& sp = spans[k];
    uint8_t* out = rec.data() + (k & 63) * 4 * fragment_record_bytes(kNv);
    for (int i = sp.x0; i <= sp.x1; ++i, out += fragment_record_bytes(kNv)) {
      const u128 sums[1 + kNv] = {(u128)eq.interp.den.at(i, sp.y), (u128)eq.interp.num[0].at(i, sp.y),
                                  (u128)eq.interp.num[1].at(i, sp.y)};
      put_fragment_header(out, eq.prim, i, sp.y, 0);
      pd.write_t<kNv>(out, sums, DefaultDivWidths{});
    }
    benchmark::ClobberMemory();
    pixels += (size_t)(sp.x1 - sp.x0 + 1);
    k = k + 1 == spans.size() ? 0 : k + 1;
  }
  state.SetItemsProcessed((int64_t)pixels);
}

void BM_FusedSpan(benchmark::State& state) {
  const Scene& sc = scene();
  const std::vector<Span>& spans = sc.spans[state.range(0)];
  FusedSpan fs(sc.cfg, sc.st, DepthBufferView{}, true);
  fs.begin(sc.eq);
  std::vector<uint8_t> rec(fragment_record_bytes(kNv) * 4 * 64);
  size_t k = 0, pixels = 0;
  for (auto _ : state) {
    const Span& sp = spans[k];
    pixels += fs.run_begun(sc.eq, sp, rec.data() + (k & 63) * 4 * fragment_record_bytes(kNv));
    benchmark::ClobberMemory();
    k = k + 1 == spans.size() ? 0 : k + 1;
  }
  state.SetItemsProcessed((int64_t)pixels);
}

}  // namespace

BENCHMARK(BM_PixelDivide_Write);
BENCHMARK(BM_PixelDivide_AtWrite)->Arg(1)->Arg(2)->Arg(4);
BENCHMARK(BM_FusedSpan)->Arg(1)->Arg(2)->Arg(4);
