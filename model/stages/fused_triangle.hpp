// model/stages/fused_triangle.hpp — stages 6–9 of a narrow triangle without varyings in one
// branchless loop: traversal, the depth code, the depth test and the records, pixel by pixel over
// the candidate rectangle, without Span records or a call per span (FragmentChain, model/unit/
// chain.hpp). docs/speed.md "Session 13: the small-triangle kernel".
//
// Applies to a set-up triangle whose candidate rectangle is narrow (x1 − x0 < kScanMaxWidth: the
// rectangles traversal scans pixel by pixel, model/stages/traverse.hpp) and whose fragments carry
// no varyings. The same values as traverse → InterpStage → DepthStage (→ DivideStage with 0
// varyings), computed so:
//   - per triangle: the depth quotient at the rectangle's corner (x0, y_lo), (q, r) =
//     floor_divmod(Z, den), and the steps (qx, rx), (qy, ry) = floor_divmod(z_dx or z_dy, den)
//     (DepthSteps below), with DepthCursor's bound proven once for the whole rectangle (model/
//     stages/depth.hpp: every quotient of the rectangle, one step past its right column included,
//     below 2^61); the remainders in int64_t where den < 2^61, else in i128 (the attribute
//     planes' den = 2A'·2^(z_frac_bits − depth_bits) reaches 2^61 at ≈ 16 px² of area); where
//     the bound fails, run() answers false and the caller takes its span path for the triangle;
//   - per row (bottom to top): the edge values and the row's depth quotient stepped (one
//     conditional subtract of den: r + ry < 2den);
//   - per candidate pixel, without a branch: covered = (E0|E1|E2) ≥ 0, the code (RNE and clamp as
//     DepthStepperT::code), the test against the stored word (the depth function as
//     depth_func_mask), the stored word rewritten (with itself where the pixel does not pass),
//     the record written and the output pointer advanced by `pass`.
// Rewriting a stored word with itself is safe in the threaded unit: a row belongs to one thread
// (docs/speed.md "Deterministic threads": interleaved row bands; a split step cuts a triangle by
// rows), and the words written are those of the rows run() was given, inside the candidate
// rectangle, which lies in the viewport (TriSetup: bbox ∩ viewport ∩ scissor).
// Proven against the staged chain: tests/model/fused_triangle_test.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "model/stages/depth.hpp"
#include "model/stages/interp_span.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/fragment_store.hpp"

namespace fxr {

// The depth quotient of a rectangle [x0, x0 + W] × [y0, y0 + H] (W, H ≥ 0) from its corner:
// (q, r) = floor_divmod(Z(x0, y0), den), (qx, rx) and (qy, ry) = floor_divmod(z_dx, z_dy by den).
// start() proves, as DepthCursor (model/stages/depth.hpp) does for its rectangle, that every
// quotient floor(Z(i, j)/den) with x0 ≤ i ≤ x0 + W + 1 and y0 ≤ j ≤ y0 + H lies below
//   B = |q| + 2 + (W + 1)·(|qx| + 1) + H·(|qy| + 1) < 2^kLimitBits
// in magnitude (Z(i, j)/den = q + r/den + Δi·(qx + rx/den) + Δj·(qy + ry/den), fractions in
// [0, 1)), so q steps in int64_t; r, rx, ry < den and den < 2^kDenBits keep r + rx, r + ry and 2r
// below 2^127 in i128, and below 2^62 in int64_t where den < 2^kLimitBits (narrow64()).
struct DepthSteps {
  static constexpr int kLimitBits = 61;   // |q| and den for the int64_t stepping (DepthCursor's)
  static constexpr int kDenBits = 125;    // den for the i128 remainders
  int64_t q = 0, qx = 0, qy = 0, max_code = 0;
  i128 r = 0, rx = 0, ry = 0, den = 1;

  bool start(const DepthSetup& s, int x0, int y0, int W, int H) {
    const i128 lim = (i128)1 << kLimitBits;
    if (s.den <= 0 || s.den >= ((i128)1 << kDenBits) || s.max_code < 0 || s.max_code >= lim) return false;
    i128 q0, qx0, qy0 = 0;
    floor_divmod(s.z.at(x0, y0), s.den, q0, r);
    floor_divmod(s.z.dx, s.den, qx0, rx);
    ry = 0;
    if (H > 0) floor_divmod(s.z.dy, s.den, qy0, ry);
    const auto mag = [](i128 v) { return v < 0 ? -v : v; };
    const i128 aq = mag(q0), aqx = mag(qx0), aqy = mag(qy0);
    if (aq >= lim || aqx >= lim || aqy >= lim) return false;
    if (aq + 2 + ((i128)W + 1) * (aqx + 1) + (i128)H * (aqy + 1) >= lim) return false;
    q = (int64_t)q0, qx = (int64_t)qx0, qy = (int64_t)qy0;
    den = s.den, max_code = (int64_t)s.max_code;
    return true;
  }
  bool narrow64() const { return den < ((i128)1 << kLimitBits); }
};

class FusedTriangle {
 public:
  // What the kernel met (the tests check that every case was reached).
  struct Counts {
    uint64_t triangles = 0;  // triangles run
    uint64_t rows = 0;       // candidate rows run
    uint64_t wide_den = 0;   // triangles whose remainders were stepped in i128 (den ≥ 2^61)
    uint64_t fallbacks = 0;  // triangles whose depth bound failed (run() answered false)
  };
  const Counts& counts() const { return counts_; }

  FusedTriangle(const Config& cfg, const DrawState& st, DepthBufferView buf)
      : buf_(buf),
        mask_(depth_func_mask(st.depth_func)),
        test_(st.depth_test),
        write_(st.depth_write),
        rows_(st.viewport_h),
        sb_(cfg.raster.subpixel_bits) {}

  // A hint, before setup: the depth words of the first rows of `tri`'s pixel bounding box (from
  // its snapped vertices, within the buffer), read by run() after setup has run. No effect on
  // any output.
  void prefetch(const SetupTriangle& tri) const {
    if (!test_) return;
    int64_t x0 = tri.v[0].x, x1 = x0, y0 = tri.v[0].y, y1 = y0;
    for (int k = 1; k < 3; ++k) {
      x0 = std::min(x0, tri.v[k].x), x1 = std::max(x1, tri.v[k].x);
      y0 = std::min(y0, tri.v[k].y), y1 = std::max(y1, tri.v[k].y);
    }
    x0 = std::max<int64_t>(x0 >> sb_, buf_.x0), x1 = std::min<int64_t>(x1 >> sb_, (int64_t)buf_.x0 + buf_.width - 1);
    y0 = std::max<int64_t>(y0 >> sb_, buf_.y0), y1 = std::min<int64_t>(y1 >> sb_, (int64_t)buf_.y0 + rows_ - 1);
    if (x1 < x0 || y1 < y0) return;
    const int n = (int)std::min<int64_t>(y1 - y0 + 1, kPrefetchRows);
    const uint32_t* p = buf_.codes + (y0 - buf_.y0) * (int64_t)buf_.width + (x0 - buf_.x0);
    for (int k = 0; k < n; ++k, p += buf_.width) {
      __builtin_prefetch(p, 1);
      __builtin_prefetch(p + (x1 - x0), 1);
    }
  }

  // The rectangles the kernel takes: narrow ones (traverse's pixel scan).
  static bool narrow(const TriSetup& e) { return (int64_t)e.x1 - e.x0 < kScanMaxWidth; }

  // Records run() may write for `t` restricted to rows [ya, yb]: one per candidate pixel.
  static size_t room(const TriSetup& e, int ya, int yb) {
    const int64_t rows = (int64_t)std::min(e.y1, yb) - std::max(e.y0, ya) + 1, w = (int64_t)e.x1 - e.x0 + 1;
    return rows > 0 && w > 0 ? (size_t)(rows * w) : 0;
  }

  // The fragment counters of one run.
  struct Result {
    uint64_t generated = 0, passed = 0;
  };

  // Contract: for a narrow(t.edges) triangle, stages 6–9 on its rows y with ya ≤ y ≤ yb, with 0
  // varyings: the same covered pixels, depth-buffer writes and fragments (x, y, depth, prim) as
  // traverse → InterpStage → DepthStage, rows bottom to top, pixels left to right. out != nullptr:
  // each passing pixel's record (FragmentStore's layout, 0 varyings) written from `out` on (room
  // for room(t.edges, ya, yb) records); row_done(first, count) is called after each row with its
  // records (count may be 0). nullptr: no record (no sink), and no depth code is computed unless
  // the test needs it. Returns false, having done nothing, when the depth code's int64_t bound
  // fails for the rectangle (then the caller takes the span path).
  template <class RowDone>
  bool run(const TriangleEquations& t, int ya, int yb, uint8_t* out, Result& res, RowDone&& row_done) {
    const TriSetup& e = t.edges;
    const int y_lo = std::max(e.y0, ya), y_hi = std::min(e.y1, yb);
    if (y_lo > y_hi || e.x1 < e.x0) return true;  // no candidate pixel: traversal emits nothing
    const bool need_code = test_ || out != nullptr;
    if (test_) prefetch_rows(e, y_lo, y_hi);
    DepthSteps z;
    if (need_code && !z.start(t.depth, e.x0, y_lo, e.x1 - e.x0, y_hi - y_lo)) {
      ++counts_.fallbacks;
      return false;
    }
    ++counts_.triangles;
    counts_.rows += (uint64_t)(y_hi - y_lo + 1);
    if (!need_code) {
      rows<false, false, int64_t>(t, y_lo, y_hi, z, out, res, row_done);
    } else if (z.narrow64()) {
      by_output<int64_t>(t, y_lo, y_hi, z, out, res, row_done);
    } else {
      ++counts_.wide_den;
      by_output<i128>(t, y_lo, y_hi, z, out, res, row_done);
    }
    return true;
  }

 private:
  static constexpr int kPrefetchRows = 8;  // as FusedSpan::begin: the bunny's rectangles are 1–8 rows

  // The depth words of the rectangle's first rows, read soon (the divisions run meanwhile).
  void prefetch_rows(const TriSetup& e, int y_lo, int y_hi) const {
    const int n = std::min(y_hi - y_lo + 1, kPrefetchRows);
    const uint32_t* p = buf_.codes + ((int64_t)y_lo - buf_.y0) * (int64_t)buf_.width + ((int64_t)e.x0 - buf_.x0);
    const int64_t last = (int64_t)e.x1 - e.x0;
    for (int k = 0; k < n; ++k, p += buf_.width) {
      __builtin_prefetch(p, 1);
      __builtin_prefetch(p + last, 1);
    }
  }

  template <class R, class RowDone>
  void by_output(const TriangleEquations& t, int y_lo, int y_hi, const DepthSteps& z, uint8_t* out, Result& res,
                 RowDone& row_done) {
    if (!test_) return rows<false, true, R>(t, y_lo, y_hi, z, out, res, row_done);  // out: need_code
    if (out) return rows<true, true, R>(t, y_lo, y_hi, z, out, res, row_done);
    rows<true, false, R>(t, y_lo, y_hi, z, out, res, row_done);
  }

  // The rows; R: the type of the remainders (int64_t where den < 2^61, else i128).
  template <bool kTest, bool kOut, class R, class RowDone>
  void rows(const TriangleEquations& t, int y_lo, int y_hi, const DepthSteps& zc, uint8_t* out, Result& res,
            RowDone& row_done) {
    constexpr bool kCode = kTest || kOut;  // the depth code is computed
    const TriSetup& e = t.edges;
    constexpr size_t kStride = fragment_record_bytes(0);
    static_assert(kStride == 2 * sizeof(uint64_t), "a record of 0 varyings is its header: two 64-bit words");
    static_assert(kScanMaxWidth <= 32, "the row mask is 32 bits");
    const int w = e.x1 - e.x0;  // last offset in a row (< kScanMaxWidth)
    // Everything the loops read is a local (the records are written through a byte pointer).
    const R den = (R)zc.den, rx = (R)zc.rx, ry = (R)zc.ry;
    const int64_t max_code = zc.max_code, qx = zc.qx, qy = zc.qy;
    const unsigned mask = mask_;
    const uint32_t write = write_ ? ~0u : 0u;  // ANDed into the rewrite of a stored word
    const int64_t width = buf_.width;
    uint32_t* codes = kTest ? buf_.codes + ((int64_t)y_lo - buf_.y0) * width + ((int64_t)e.x0 - buf_.x0) : nullptr;
    // The depth quotient's move from a row's first pixel to offset o: o·(qx + rx/den) as
    // (oq[o], orr[o]), orr[o] ∈ [0, den) (DepthStepperT::step_x o times).
    int64_t oq[kScanMaxWidth];
    R orr[kScanMaxWidth];
    if (kCode) {
      oq[0] = 0, orr[0] = 0;
      for (int o = 1; o <= w; ++o) {
        R rr = orr[o - 1] + rx;
        const bool carry = rr >= den;
        orr[o] = carry ? rr - den : rr;
        oq[o] = oq[o - 1] + qx + (carry ? 1 : 0);
      }
    }
    int64_t q = zc.q;
    R r = (R)zc.r;
    EdgeStepper row(e, e.x0, y_lo);
    const int64_t ex0 = row.dx[0], ex1 = row.dx[1], ex2 = row.dx[2];
    // The header's words 0–1 (prim, x) at the row's first pixel (x in the high half, one per
    // pixel: x_step); words 2–3 (y, depth) per pixel.
    const uint64_t h01 = fragment_word_pair(t.prim, (uint32_t)e.x0), x_step = fragment_word_pair(0, 1);
    uint8_t* rec = out;
    uint64_t gen = 0, passed = 0;
    for (int32_t j = y_lo; j <= y_hi; ++j) {
      // The row's covered pixels as traverse finds them: every pixel tested into a bit mask (the
      // same w + 1 steps on every row), the covered ones one interval [lowest, highest bit].
      uint32_t m = 0;
      {
        int64_t v0 = row.v[0], v1 = row.v[1], v2 = row.v[2];
        for (int o = 0; o <= w; ++o) {
          m |= (uint32_t)((v0 | v1 | v2) >= 0) << o;
          v0 += ex0, v1 += ex1, v2 += ex2;
        }
      }
      if (m != 0) {
        const int ob = __builtin_ctz(m), oe = 31 - __builtin_clz(m);
        gen += (uint64_t)(oe - ob + 1);
        if (kCode) {
          // The depth at the interval's first pixel, then stepped along it.
          int64_t zq = q + oq[ob];
          R zr = r + orr[ob];
          {
            const bool carry = zr >= den;
            zr -= den & (R)(0 - (R)carry);
            zq += (int64_t)carry;
          }
          uint64_t h = h01 + (uint64_t)ob * x_step;
          uint8_t* const first = rec;
          for (int o = ob; o <= oe; ++o) {
            // DepthStepperT::code: RNE (rne_round_up), then the clamp to [0, max_code].
            const R r2 = zr + zr;
            const int64_t up = (int64_t)(r2 > den) | ((int64_t)(r2 == den) & zq);
            int64_t c = zq + (up & 1);
            c = c < 0 ? 0 : c;
            c = c > max_code ? max_code : c;
            const uint32_t code = (uint32_t)c;
            uint32_t pass = 1;
            if (kTest) {
              const uint32_t stored = codes[o];
              pass = (mask >> depth_relation(code, stored)) & 1u;
              codes[o] = stored ^ ((stored ^ code) & write & (0u - pass));  // itself unless written
            }
            if (kOut) {
              const uint64_t h23 = fragment_word_pair((uint32_t)j, code);
              std::memcpy(rec, &h, sizeof h);
              std::memcpy(rec + sizeof h, &h23, sizeof h23);
              rec += (size_t)pass * kStride;
              h += x_step;
            } else {
              passed += pass;
            }
            // DepthStepperT::step_x (r + rx < 2den)
            zq += qx, zr += rx;
            const bool carry = zr >= den;
            zr -= den & (R)(0 - (R)carry);
            zq += (int64_t)carry;
          }
          if (kOut) row_done(first, (size_t)(rec - first) / kStride);
        }
      }
      row.step_y();
      if (kCode) {  // the next row's start (r + ry < 2den)
        q += qy, r += ry;
        const bool carry = r >= den;
        r -= den & (R)(0 - (R)carry);
        q += (int64_t)carry;
      }
      if (kTest) codes += width;
    }
    passed = kOut ? (uint64_t)(rec - out) / kStride : kTest ? passed : gen;
    res.generated += gen;
    res.passed += passed;
  }

  DepthBufferView buf_;
  unsigned mask_;
  bool test_, write_;
  int rows_;  // of the depth buffer (the viewport's height)
  int sb_;    // raster.subpixel_bits of the snapped vertices
  Counts counts_;
};

}  // namespace fxr
