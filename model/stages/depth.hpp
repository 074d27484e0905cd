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

// ---- the depth quotient at a moving span start (FusedSpan, model/stages/interp_span.hpp) ------
//
// DepthStepper divides twice at every span start: Z(x0, y) / den and dx / den. Within one
// triangle the spans come row after row with nearby starts, so the cursor keeps
// (q, r) = floor_divmod(Z(i, j), den) at the last span start and moves it to the next one,
// (i', j') = (i + Δi, j + Δj), without a division: with (qx, rx) = floor_divmod(dx, den) and
// (qy, ry) = floor_divmod(dy, den), computed once per triangle,
//   Z(i', j') = (q + Δj·qy + Δi·qx)·den + t,   t = r + Δj·ry + Δi·rx,
// so q' = q + Δj·qy + Δi·qx + floor(t / den) and r' = t mod den. For Δj ∈ {0, 1} and |Δi| ≤ 1
// (97 % of the bunny's row steps, docs/speed.md "Session 9: the span start") t ∈ (−den, 3den):
// one conditional add and two conditional subtracts of den; other steps divide t once.
//
// Everything is int64_t, which start() and the first row step prove for the whole candidate
// rectangle [x0, x1] × [y0, y1] of the triangle (every span lies in it): den, max_code < 2^61
// and, for every pixel (i, j) with x0 ≤ i ≤ x1 + 1 (the stepper's last step) and y0 ≤ j ≤ y1,
//   |floor(Z(i, j) / den)| ≤ B = |q_s| + 2 + (W + 1)·(|qx| + 1) + H·(|qy| + 1) < 2^61
// (q_s at the start pixel (a, b), W = x1 − x0, H = y1 − y0: Z(i, j)/den = q_s + r_s/den +
// (i − a)·(qx + rx/den) + (j − b)·(qy + ry/den) with the fractions in [0, 1), |i − a| ≤ W + 1,
// |j − b| ≤ H). Then t ∈ (−den, 3den) and q + |qy| + |qx| stay below 3·2^61 < 2^63, and the
// span's DepthStepperT<int64_t> (stepper()) is exact: r + dr < 2den < 2^62, |q| + |dq| + 1 < 2^63.
// The y part of B needs qy: it is added at the first step to another row. Where a bound fails
// (or a span leaves the rectangle) the cursor answers false and the caller divides per span as
// before. Proof: tests/model/depth_test.cpp DepthCursor.* (every move against floor_divmod).
struct DepthCursor {
  static constexpr int kLimitBits = 61;
  int64_t q = 0, r = 0, qx = 0, rx = 0, qy = 0, ry = 0, den = 1, max_code = 0;
  int32_t i = 0, j = 0;                  // the pixel (q, r) belongs to
  int32_t x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // the candidate rectangle
  bool have_y = false;                   // qy, ry computed and the bound's y part added
  i128 bound = 0;                        // B so far (without the y part until have_y)

  // Contract: the cursor at pixel (i, j) of rectangle `rect` from dz = DepthStepper(s, i, j)
  // (its q, r at (i, j) and dq, dr = floor_divmod(s.z.dx, s.den)). False when the int64_t
  // bounds above fail or (i, j) is outside the rectangle (the cursor is then unusable).
  bool start(const DepthStepperT<i128>& dz, int i_, int j_, int rx0, int rx1, int ry0, int ry1) {
    const i128 lim = (i128)1 << kLimitBits;
    if (rx1 < rx0 || ry1 < ry0 || i_ < rx0 || i_ > rx1 || j_ < ry0 || j_ > ry1) return false;
    if (dz.den >= lim || dz.max_code >= lim || dz.den <= 0 || dz.max_code < 0) return false;
    const i128 aq = dz.q < 0 ? -dz.q : dz.q, aqx = dz.dq < 0 ? -dz.dq : dz.dq;
    if (aq >= lim || aqx >= lim) return false;
    bound = aq + 2 + ((i128)rx1 - rx0 + 1) * (aqx + 1);
    if (bound >= lim) return false;
    q = (int64_t)dz.q, r = (int64_t)dz.r, qx = (int64_t)dz.dq, rx = (int64_t)dz.dr;
    den = (int64_t)dz.den, max_code = (int64_t)dz.max_code;
    i = i_, j = j_, x0 = rx0, x1 = rx1, y0 = ry0, y1 = ry1;
    have_y = false;
    return true;
  }

  // Contract: after a true start() for the same plane s, moves to pixel (i2, j2):
  // (q, r) = floor_divmod(Z(i2, j2), den) exactly; returns kMoved, or kMovedDivided when it took
  // the division. kLost (0) when (i2, j2) is outside the rectangle or the bound's y part fails
  // (the cursor is then unusable: the caller divides from then on).
  static constexpr int kLost = 0, kMoved = 1, kMovedDivided = 2;
  int move(const DepthSetup& s, int i2, int j2) {
    if (i2 < x0 || i2 > x1 || j2 < y0 || j2 > y1) return kLost;
    const int64_t di = (int64_t)i2 - i, dj = (int64_t)j2 - j;
    if (dj != 0 && !have_y) {
      i128 q128, r128;
      floor_divmod(s.z.dy, s.den, q128, r128);
      const i128 lim = (i128)1 << kLimitBits, aqy = q128 < 0 ? -q128 : q128;
      if (aqy >= lim) return kLost;
      bound += ((i128)y1 - y0) * (aqy + 1);
      if (bound >= lim) return kLost;
      qy = (int64_t)q128, ry = (int64_t)r128;
      have_y = true;
    }
    i = i2, j = j2;
    if ((dj == 0 || dj == 1) && di >= -1 && di <= 1) {  // t ∈ (−den, 3den)
      int64_t t = r, nq = q;
      if (dj) t += ry, nq += qy;
      if (di > 0) t += rx, nq += qx;
      else if (di < 0) t -= rx, nq -= qx;
      if (t < 0) t += den, nq -= 1;
      if (t >= den) t -= den, nq += 1;
      if (t >= den) t -= den, nq += 1;
      q = nq, r = t;
      return kMoved;
    }
    // In i128: |Δ|·|rx| may exceed int64_t; the quotient and q' are bounded by B.
    const i128 t = (i128)r + (i128)dj * ry + (i128)di * rx;
    i128 k, rr;
    floor_divmod(t, (i128)den, k, rr);
    q = (int64_t)((i128)q + (i128)dj * qy + (i128)di * qx + k);
    r = (int64_t)rr;
    return kMovedDivided;
  }

  // The span's stepper from the current pixel (DepthStepperT<int64_t>, exact by the bound).
  DepthStepperT<int64_t> stepper() const {
    DepthStepperT<int64_t> z;
    z.q = q, z.r = r, z.dq = qx, z.dr = rx, z.den = den, z.max_code = max_code;
    return z;
  }
};

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
