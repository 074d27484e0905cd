// Stage 8: depth test. Contract in model/stages/depth.hpp.
#include "model/stages/depth.hpp"

namespace fxr {

StageCost DepthStage::cost(const Config& cfg) {
  // rtl/fxr_depth.sv (docs/rtl.md, "fxr_depth"): an in-order queue of kDepthQueueDepth samples
  // behind the buffer's memory port, a 2-entry output FIFO. Latency with a memory answering in
  // the next clock: read request in the input's clock, response, compare at the queue head, out
  // of the FIFO: 3 clocks. One sample per clock while reads alone use the port; a passing
  // sample's write takes one more port slot (measured figures in docs/rtl.md).
  const RasterConfig& r = cfg.raster;
  const int pb = r.window_int_bits, ab = 2 * pb, db = r.depth_bits();
  int qb = 0;  // pointer bits: log2 kDepthQueueDepth
  while ((1 << qb) < kDepthQueueDepth) ++qb;
  StageCost c;
  c.latency = 3;
  c.ii = 1;
  c.add_mult(pb + 1, pb + 1);  // (y − viewport_y)·viewport_w
  // Offsets and index, the comparator, the hazard compares (one per queue entry), pointers.
  c.adder_bits = 2 * (pb + 1) + ab + db + (int64_t)kDepthQueueDepth * ab + 4 * (qb + 1);
  c.ff_bits = (int64_t)(kDepthQueueDepth + 2) * record_bits<PlaneSample>(cfg, kMaxVaryings) +
              (int64_t)kDepthQueueDepth * (ab + 2 * db + 2) + 4 * (qb + 1);
  return c;
}

}  // namespace fxr
