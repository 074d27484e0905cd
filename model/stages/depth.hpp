// model/stages/depth.hpp — stage 8 (depth test). The depth code of a pixel is interpolated in
// stage 7 (model/stages/interp.hpp: DepthStepper); its derivation:
// docs/pipeline.md, stage 8.
//
// z is affine in window space (D3D, Vulkan): z = Σ E_k·z_k / 2A with z_k the per-vertex
// z_c/w_c (raster.z_frac_bits fraction bits). The unorm code is ONE rounding of the exact
// rational value: code = RNE(z · (2^depth_bits − 1)) = RNE(Z / Qd) with the integer plane
// Z = Σ E_k·(z_k·(2^depth_bits − 1)) and Qd = 2A·2^z_frac_bits. The quotient and remainder are
// stepped exactly along a span (a Bresenham-style DDA), so the per-pixel cost is two adds and
// a compare. Inside a triangle z is a convex combination of z_k ∈ [0, 1], so the code is in
// [0, 2^depth_bits − 1] without clamping.
#pragma once

#include <cstdint>

#include "model/stages/interp.hpp"

namespace fxr {

// ---- the stage ------------------------------------------------------------------------------

// The depth buffer a DepthStage tests against: w × h codes, row 0 at the bottom, indexed from
// the viewport origin (FrameOutput::depth).
struct DepthBufferView {
  uint32_t* codes = nullptr;
  int width = 0;
  int x0 = 0, y0 = 0;  // window coordinates of codes[0]
};

// Samples in flight in rtl/fxr_depth.sv (its parameter QueueDepth: a micro-architecture choice,
// docs/rtl.md).
inline constexpr int kDepthQueueDepth = 8;

class DepthStage {
 public:
  static constexpr const char* kName = "depth";
  using In = PlaneSample;
  using Out = PlaneSample;

  DepthStage(const Config&, const DrawState& st, DepthBufferView buf)
      : buf_(buf), func_(st.depth_func), test_(st.depth_test), write_(st.depth_write) {}

  // 1 → 0..1: the sample passes on unchanged when it passes the test (st.depth_test false:
  // always passes and never writes, as in GL); a passing sample is written when
  // st.depth_write. State: the depth buffer (the only state of the unit). Returns pass.
  template <class Emit>
  bool step(const In& in, Emit&& emit) {
    bool pass = true;
    if (test_) {
      uint32_t& stored = buf_.codes[(size_t)(in.y - buf_.y0) * (size_t)buf_.width + (size_t)(in.x - buf_.x0)];
      pass = depth_compare(func_, in.depth, stored);
      if (pass && write_) stored = in.depth;
    }
    if (pass) emit(in);
    return pass;
  }

  // rtl/fxr_depth.sv: one depth_bits comparator, an in-order queue of kDepthQueueDepth samples
  // behind the buffer's memory port (depth.cpp; docs/rtl.md, "fxr_depth").
  static StageCost cost(const Config& cfg);

  // The memory-dependent timing of rtl/fxr_depth.sv (the cycle model, docs/cycles.md), for a
  // memory answering `mem_latency` clocks after a read request (cost()'s figures: 1):
  // a sample's read is issued in its input clock, its entry reaches the queue head and leaves
  // `head_clocks` later (response, compare), a passing one is out of the 2-entry output FIFO a
  // clock after that (latency = head_clocks + 1). Read-after-write hazard (write mask on): a
  // sample whose pixel is in the queue waits at the input until that entry has left and is taken
  // the clock after. One read per clock; with the request port shared (no write channel) a
  // passing sample's write takes a port slot too. One sample per clock while
  // queue depth ≥ head_clocks + 1.
  static int head_clocks(int mem_latency) { return mem_latency + 1; }
  static int latency(int mem_latency) { return head_clocks(mem_latency) + 1; }

 private:
  DepthBufferView buf_;
  DepthFunc func_;
  bool test_, write_;
};

}  // namespace fxr
