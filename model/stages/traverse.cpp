// Stage 6: traversal. Contract in model/stages/traverse.hpp.
#include "model/stages/traverse.hpp"

namespace fxr {

StageCost TraverseStage::cost(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  StageCost c;
  c.latency = 2;  // row start step, interval ends (estimate until rtl/ has the stage)
  c.ii = 1;       // one span per clock
  // Three edge steppers in x and y, and the interval-end divisions of wide rows (3 dividers of
  // edge_value_bits by edge_coef_bits, counted as their adder width).
  c.adder_bits = 3 * 2 * (int64_t)edge_value_bits(r) + 3 * (int64_t)edge_value_bits(r) * edge_coef_bits(r);
  c.ff_bits = c.latency * record_bits<Span>(cfg, 0);
  return c;
}

}  // namespace fxr
