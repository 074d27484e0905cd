// Stage 1: input conversion. Contract in model/stages/input.hpp.
#include "model/stages/input.hpp"

namespace fxr {

StageCost ConvertStage::cost(const Config& cfg) {
  StageCost c;
  c.latency = 1;  // one register stage
  c.ii = 1;
  // Per float32 (3 vertices × (4 + kMaxVaryings)): an all-ones and an all-zeros exponent detect.
  c.adder_bits = 3 * (4 + kMaxVaryings) * 2 * (int64_t)kF32ExpBits;
  c.ff_bits = record_bits<ExactTriangle>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr
