// Stage 6: traversal. Contract in model/stages/traverse.hpp.
#include "model/stages/traverse.hpp"

namespace fxr {

StageCost TraverseStage::cost(const Config& cfg) {
  // rtl/fxr_traverse.sv (docs/rtl.md, "fxr_traverse"): one direct evaluation per triangle, then per
  // row an MSB-first search of the three edges' bounds, one offset bit per clock, n = bits of the
  // rectangle width. Latency 2 + n to the first span, a row every n + 1 clocks, a triangle
  // rows·(n + 1) clocks (the next one is accepted in the clock finishing the last row). The
  // figures below are the n = 0 case (1-pixel-wide rectangles): one-row triangles at II 1.
  const RasterConfig& r = cfg.raster;
  const int pb = r.window_int_bits, ab = edge_value_bits(r) + 1, ob = pb + 1;
  StageCost c;
  c.latency = 2;
  c.ii = 1;
  for (int k = 0; k < 3; ++k) {
    c.add_mult(edge_coef_bits(r), pb);  // a_k·x0
    c.add_mult(edge_coef_bits(r), pb);  // b_k·y0
  }
  // Per edge: the evaluation's three adds, the search step, the row step, two bound comparisons.
  c.adder_bits = 3 * (5 * (int64_t)ab + 2 * ob) + 2 * pb + 2 * ob;
  c.ff_bits = 3 * (5 * (int64_t)ab + ob + 2) + kPrimIdBits + 3 * pb + 3 * ob + record_bits<Span>(cfg, 0) + 3;
  return c;
}

}  // namespace fxr
