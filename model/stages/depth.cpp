// Stage 8: depth test. Contract in model/stages/depth.hpp.
#include "model/stages/depth.hpp"

namespace fxr {

StageCost DepthStage::cost(const Config& cfg) {
  StageCost c;
  c.latency = 2;  // buffer read, compare + write
  c.ii = 1;
  c.adder_bits = cfg.raster.depth_bits();  // one comparator
  c.ff_bits = c.latency * record_bits<PlaneSample>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr
