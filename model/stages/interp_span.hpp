// model/stages/interp_span.hpp — stages 7 (interpolators), 8 (depth test) and 9 (divider) fused
// over one span: the fast path of the stage chain where no tap observes their boundaries
// (FragmentChain::span, model/unit/chain.hpp). docs/speed.md "The fused span".
//
// The same values as InterpStage::step → DepthStage::step → DivideStage::step, computed with the
// work that is constant along a span done once per span or per segment of it:
//   - the depth code stepped in int64_t where depth_step_fits64 proves it (as InterpStage), else
//     one value where the codes at both ends of the span are equal (the code is monotone), else
//     stepped in i128;
//   - the depth function as a 3-bit mask of its answers to <, =, > (from depth_compare itself);
//   - the plane sums D and N_m, affine in x, hence monotone along the span, as sign and magnitude
//     (the magnitude stepped directly: −N by −dN); the span is cut into segments where every
//     sum keeps its sign and binade (its msb), found by testing the segment's last value and, where
//     a sum leaves, by one division for the exact exit pixel; inside a segment each normalisation
//     is NormalizeAtMsb (model/arith/fixed.hpp: one add and one shift, no leading-zero count);
//     in a segment of ≥ kAlignMinPixels pixels where D > 0 and no sum is zero, every sum is
//     stepped left-aligned (its binade's msb at bit 126) and normalised in 64-bit words with
//     constant shifts (rne_high_word, fixed.hpp), the exponents' segment constants folded, a
//     rounding carry-out left to the divider and D's reciprocal computed one pixel ahead;
//   - one reciprocal of D's significand per pixel and per varying one multiply, the rounding
//     decided by the estimate's fraction outside a narrow band, else by the exact remainder
//     (div_sig_recip64_frac_w, model/arith/div.hpp): div_sig_fast64's result;
//   - the default divider widths and 0, 1, 2 varyings as compile-time constants (other widths and
//     counts: the same code with run-time values).
//   - a span of at most kDirectMaxPixels pixels with varyings skips all of the segment machinery:
//     each passing pixel is divided from the cursor's sums by PixelDivide (model/stages/
//     pixel_divide.hpp); the sums' binades are synced at the next longer span.
// Applies where the stage divides with div_sig_fast64 (radix2, W + qb ≤ 63: every default).
// Proven against the staged path: tests/model/interp_span_test.cpp (random triangles and long
// grazing spans under every depth function, both stepper widths, binade exits, sign changes,
// affine mode, default and other widths, 0–4 varyings; every counter below reached).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "model/arith/div.hpp"
#include "model/arith/fixed.hpp"
#include "model/config/config.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/pixel_divide.hpp"
#include "model/unit/fragment_store.hpp"
#include "model/unit/io.hpp"

namespace fxr {

// Bit k of the mask: depth_compare(func, incoming, stored) when incoming is below (k = 0), equal
// to (k = 1) or above (k = 2) the stored code.
inline unsigned depth_func_mask(DepthFunc f) {
  return (depth_compare<uint32_t>(f, 0, 1) ? 1u : 0u) | (depth_compare<uint32_t>(f, 1, 1) ? 2u : 0u) |
         (depth_compare<uint32_t>(f, 1, 0) ? 4u : 0u);
}
// The relation's bit index: 0 (<), 1 (=), 2 (>).
inline unsigned depth_relation(uint32_t incoming, uint32_t stored) {
  return (unsigned)(incoming >= stored) + (unsigned)(incoming > stored);
}

// Stage 8 at one pixel of a span: the test against the stored code (none without a depth
// buffer: codes == nullptr) and the write of a passing code; both pixel loops of FusedSpan.
[[gnu::always_inline]] inline bool depth_pass(uint32_t* codes, int64_t k, uint32_t code, unsigned mask, bool write) {
  if (!codes) return true;
  uint32_t& stored = codes[k];
  const bool pass = (mask >> depth_relation(code, stored)) & 1u;
  if (pass && write) stored = code;
  return pass;
}

// The depth code at pixel (i, j) computed directly (DepthStepper's first division, rounding and
// clamp).
inline uint32_t depth_code_at(const DepthSetup& s, int i, int j) {
  DepthStepperT<i128> z;
  z.den = s.den;
  z.max_code = s.max_code;
  floor_divmod(s.z.at(i, j), s.den, z.q, z.r);
  return z.code();
}
// A depth code that is one value over a span (FusedSpan's range test): nothing to step.
struct DepthConstant {
  uint32_t c = 0;
  void step_x() {}
  uint32_t code() const { return c; }
};

// A copy of `sp` read one 32-bit field at a time. Traversal has just written the fields as
// separate 32-bit stores; GCC read y and x0 as one 64-bit load, which the store buffer cannot
// forward from two stores: the load waits until both have reached the cache (docs/speed.md
// "Session 11: the span"). A volatile access is one access of its own width, never merged with
// a neighbour.
inline Span span_fields(const Span& sp) {
  Span s;
  s.prim = *static_cast<const volatile uint32_t*>(&sp.prim);
  s.y = *static_cast<const volatile int32_t*>(&sp.y);
  s.x0 = *static_cast<const volatile int32_t*>(&sp.x0);
  s.x1 = *static_cast<const volatile int32_t*>(&sp.x1);
  return s;
}

// A 128-bit value read as two 64-bit words (volatile: two loads of their own width, never merged
// into one 16-byte load; as span_fields).
inline u128 u128_words(const u128& v) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the low word first");
  const volatile uint64_t* w = reinterpret_cast<const volatile uint64_t*>(&v);
  const uint64_t lo = w[0], hi = w[1];
  return ((u128)hi << 64) | lo;
}

class FusedSpan {
 public:
  // What the fast path met (the tests check that every case was reached).
  struct Counts {
    uint64_t spans = 0, spans_z128 = 0;  // spans; of them stepped in i128 (else int64_t or constant)
    uint64_t spans_zconst = 0;           // spans not fitting int64_t whose depth code is one value
    uint64_t segments = 0;               // segments (> spans: some sum left its binade)
    uint64_t exits_divided = 0;          // segment ends found by the exit division
    uint64_t sign_changes = 0;           // a sum re-armed with the other sign
    uint64_t segments_high = 0;          // segments normalised in 64-bit words (rne_high_word)
    uint64_t segments_high_low = 0;      // of them with D's significand not above its low word
    // The span start's cursor (begin / run; docs/speed.md "Session 9: the span start"):
    uint64_t cursor_starts = 0;   // first spans of a triangle: the planes and the depth divided
    uint64_t cursor_moves = 0;    // later spans: every value moved from the last span start
    uint64_t spans_z64 = 0;       // spans stepped in int64_t from the depth cursor
    uint64_t z_moves_divided = 0;  // cursor moves of the depth that divided (|Δx| > 1 or Δy > 1)
    uint64_t z_cursor_lost = 0;   // triangles whose depth cursor failed a bound (then per span)
    uint64_t rearmed_moves = 0;   // sums that left their binade or sign between two span starts
    uint64_t rearmed_sign_moves = 0;  // of them with the other sign
    uint64_t sums_fixed = 0;      // sums whose sign and binade hold over a whole triangle
    uint64_t spans_direct = 0;    // short spans divided pixel by pixel (PixelDivide, no segments)
  };
  const Counts& counts() const { return counts_; }

  // True when the divider stage would divide with div_sig_fast64 (the path this one reproduces)
  // and its significands fit the compact record (quot_bits ≤ kStoredSigBits).
  static bool applies(const Config& cfg) { return pixel_divide_applies(cfg.div); }

  // with_varyings false: fragments without varyings, as InterpStage / DivideStage.
  FusedSpan(const Config& cfg, const DrawState& st, DepthBufferView buf, bool with_varyings = true)
      : dc_(cfg.div),
        nv_(with_varyings ? st.num_varyings : 0),
        buf_(buf),
        mask_(depth_func_mask(st.depth_func)),
        test_(st.depth_test),
        write_(st.depth_write),
        widths_(div_widths(cfg.div)),
        default_widths_(is_default_div_widths(widths_)) {}

  // The varyings of each record run() writes (the draw's, or 0 without varyings).
  int num_varyings() const { return nv_; }
  // false: every segment takes the u128 normalisations (the tests run both and compare).
  void set_high_words(bool on) { high_words_ = on; }
  // false: short spans take the segment loop too (the tests run both and compare).
  void set_direct(bool on) { direct_ = on; }

  // True when every exponent this triangle's fragments can have fits the compact record
  // (divide_exponents_fit, model/stages/pixel_divide.hpp); a triangle outside this goes through
  // the staged stages (FragmentChain::span).
  bool fits(const TriangleEquations& t) const { return divide_exponents_fit(t, nv_); }

  // Contract: the spans that follow (run) belong to triangle `t` until the next begin(). run()
  // calls it itself when handed another triangle: another object, or the same object with
  // another serial (SetupStage rewrites one record per triangle and numbers each,
  // TriangleEquations::serial). A caller that edits equations by hand (serial 0, or one kept)
  // must call it per triangle. FragmentChain::run / rows call it per triangle for the depth
  // prefetch below. Cheap: the cursor is set up at the first span.
  void begin(const TriangleEquations& t) {
    pd_.begin(t);
    tri_ = &t;
    serial_ = t.serial;
    started_ = false;
    fits_ = fits(t);
    if (test_) {  // the depth words of the candidate rectangle's first rows: read by the spans soon
      const TriSetup& e = t.edges;
      const int rows = std::min(e.y1 - e.y0 + 1, kPrefetchRows);
      if (rows > 0 && e.x1 >= e.x0) {
        const uint32_t* p = buf_.codes + ((int64_t)e.y0 - buf_.y0) * (int64_t)buf_.width + ((int64_t)e.x0 - buf_.x0);
        const int64_t last = (int64_t)e.x1 - e.x0;
        for (int k = 0; k < rows; ++k, p += buf_.width) {
          __builtin_prefetch(p, 1);
          __builtin_prefetch(p + last, 1);
        }
      }
    }
  }
  // True when `t` is the triangle of the last begin(): the same object with the same serial.
  bool begun(const TriangleEquations& t) const { return &t == tri_ && t.serial == serial_; }
  // fits(t) for the triangle of the last begin(t) (begins it when `t` is another triangle).
  bool fits_begun(const TriangleEquations& t) {
    if (!begun(t)) begin(t);
    return fits_;
  }
  // fits(t) of the last begin(t), for a caller that calls begin() per triangle itself.
  bool fits_of_begun() const { return fits_; }

  // Contract: stages 7–9 on span `sp` of `t` (fits(t); begin(t) called since `t` last changed,
  // see begin()): the same passing pixels, depth-buffer writes and fragment values (x, y, depth,
  // prim, var[0 … nv−1]) as the staged chain, left to right. out != nullptr: each passing
  // pixel's fragment is written to `out` as a compact record of num_varyings() varyings
  // (FragmentStore's layout; room for sp.x1 − sp.x0 + 1 records); nullptr: nothing is written
  // (no sink). Returns the number of passing pixels.
  // The span start: at the triangle's first span the planes are evaluated at (x0, y) and the
  // depth divided (DepthStepper); at later spans a cursor moves every value from the last span
  // start (a plane by Δy·dy + Δx·dx; the sums keep their binade and normaliser unless they left
  // it; the depth quotient by DepthCursor, int64_t where its bound holds).
  uint64_t run(const TriangleEquations& t, const Span& sp, uint8_t* out) {
    if (!begun(t)) begin(t);
    return run_begun(t, sp, out);
  }
  // The same for a caller that calls begin(t) per triangle itself (FragmentChain::run / rows):
  // no identity check per span.
  uint64_t run_begun(const TriangleEquations& t, const Span& span, uint8_t* out) {
    const Span sp = span_fields(span);
    ++counts_.spans;
    const TriSetup& e = t.edges;
    // Every span of traversal lies in the candidate rectangle; what the cursor proves holds there.
    const bool inside = sp.x0 >= e.x0 && sp.x1 <= e.x1 && sp.y >= e.y0 && sp.y <= e.y1;
    if (!started_) {
      started_ = true;
      ++counts_.cursor_starts;
      cx_ = sp.x0, cy_ = sp.y;
      if (nv_ > 0) {
        den_.start(t.interp.den, sp, dc_.den_bits, val_[0], e, inside);
        for (int m = 0; m < nv_; ++m) num_[m].start(t.interp.num[m], sp, dc_.num_bits, val_[1 + m], e, inside);
        counts_.sums_fixed += den_.fixed ? 1 : 0;
        for (int m = 0; m < nv_; ++m) counts_.sums_fixed += num_[m].fixed ? 1 : 0;
      }
      const DepthStepper dz(t.depth, sp.x0, sp.y);
      z_cursor_ = inside && zcur_.start(dz, sp.x0, sp.y, e.x0, e.x1, e.y0, e.y1);
      if (z_cursor_) return run_w(t, sp, zcur_.stepper(), out);
      ++counts_.z_cursor_lost;
      return run_w(t, sp, dz, (int64_t)sp.x1 - sp.x0 + 1, out);
    }
    ++counts_.cursor_moves;
    const int64_t ddx = (int64_t)sp.x0 - cx_, ddy = (int64_t)sp.y - cy_;
    cx_ = sp.x0, cy_ = sp.y;
    if (nv_ > 0) {
      // The common step (the next row, x0 moved by at most one pixel) adds a precomputed delta.
      const int sel = ddy == 1 && ddx >= -1 && ddx <= 1 ? (int)ddx + 1 : -1;
      if (!inside) {  // not proven there: every sum checks its binade from now on
        den_.fixed = false;
        for (int m = 0; m < nv_; ++m) num_[m].fixed = false;
      }
      if (direct_span(sp)) {  // only the cursor: the sums' binades are synced at the next long span
        den_.advance(t.interp.den, sel, ddx, ddy, val_[0]);
        for (int m = 0; m < nv_; ++m) num_[m].advance(t.interp.num[m], sel, ddx, ddy, val_[1 + m]);
      } else {
        den_.move(t.interp.den, sel, ddx, ddy, val_[0], counts_);
        for (int m = 0; m < nv_; ++m) num_[m].move(t.interp.num[m], sel, ddx, ddy, val_[1 + m], counts_);
      }
    }
    if (z_cursor_) {
      const int moved = inside ? zcur_.move(t.depth, sp.x0, sp.y) : 0;
      if (moved) {
        counts_.z_moves_divided += moved == DepthCursor::kMovedDivided ? 1 : 0;
        return run_w(t, sp, zcur_.stepper(), out);
      }
      z_cursor_ = false;
      ++counts_.z_cursor_lost;
    }
    const DepthStepper dz(t.depth, sp.x0, sp.y);
    return run_w(t, sp, dz, (int64_t)sp.x1 - sp.x0 + 1, out);
  }
  // The same handing each passing pixel's Fragment to emit(const Fragment&) (the tests).
  template <class Emit>
  uint64_t run(const TriangleEquations& t, const Span& sp, Emit&& emit) {
    scratch_.resize((size_t)(sp.x1 - sp.x0 + 1) * fragment_record_bytes(nv_));
    const uint64_t pass = run(t, sp, scratch_.data());
    const FragmentRecords b{scratch_.data(), (size_t)pass, nv_};
    for (size_t i = 0; i < b.count; ++i) emit(static_cast<const Fragment&>(b[i]));
    return pass;
  }

 private:
  // The divider's widths (DivWidths, model/stages/pixel_divide.hpp): the configuration's at run
  // time, or the defaults as compile-time constants (DefaultDivWidths: the loop's shifts and
  // masks fold).
  static constexpr int kPrefetchRows = 8;  // begin()'s prefetch: the bunny's rectangles are 1–8 rows

  // The divider widths as compile-time constants where they are the defaults.
  uint64_t run_w(const TriangleEquations& t, const Span& sp, const DepthStepperT<int64_t>& z, uint8_t* out) {
    ++counts_.spans_z64;
    if (default_widths_) return run_nv(t, sp, z, DefaultDivWidths{}, out);
    return run_nv(t, sp, z, widths_, out);
  }
  [[gnu::always_inline]] uint64_t run_w(const TriangleEquations& t, const Span& sp, const DepthStepper& dz, int64_t n, uint8_t* out) {
    if (default_widths_) return run_z(t, sp, dz, n, DefaultDivWidths{}, out);
    return run_z(t, sp, dz, n, widths_, out);
  }

  // The span's depth from a fresh DepthStepper (no cursor): int64_t where the span fits, one
  // value where the code is constant, else i128.
  template <class W>
  uint64_t run_z(const TriangleEquations& t, const Span& sp, const DepthStepper& dz, int64_t n, const W& wd,
                 uint8_t* out) {
    if (depth_step_fits64(dz, n)) {
      const DepthStepperT<int64_t> z = narrow64(dz);
      return run_nv(t, sp, z, wd, out);
    }
    // The range test fitted to the depth plane (docs/speed.md "Session 8: the span path"): along
    // a span Z is affine in x, RNE(Z / den) and the clamp are monotone, so the code is monotone
    // and equal codes at the two ends make it one value over the span — then nothing is stepped.
    // The grazing plane's spans take it (Z constant along a row, den ≈ 2^71–2^75: the int64
    // stepping cannot hold r); a span whose code changes takes the i128 stepper.
    const uint32_t c0 = dz.code();
    if (depth_code_at(t.depth, sp.x1, sp.y) == c0) {
      ++counts_.spans_zconst;
      const DepthConstant z{c0};
      return run_nv(t, sp, z, wd, out);
    }
    ++counts_.spans_z128;
    const DepthStepperT<i128> z = dz;
    return run_nv(t, sp, z, wd, out);
  }
  // The number of varyings as a constant for 0, 1 and 2 (the loop over them unrolled), else nv_;
  // no output (no sink: only the depth test) as a constant too.
  template <class Z, class W>
  uint64_t run_nv(const TriangleEquations& t, const Span& sp, const Z& z, const W& wd, uint8_t* out) {
    if (!out) return loop<0, false>(t, sp, z, wd, out);
    if (direct_span(sp)) {
      ++counts_.spans_direct;
      switch (nv_) {
        case 1: return loop_direct<1>(t, sp, z, wd, out);
        case 2: return loop_direct<2>(t, sp, z, wd, out);
        default: return loop_direct<-1>(t, sp, z, wd, out);
      }
    }
    switch (nv_) {
      case 0: return loop<0, true>(t, sp, z, wd, out);
      case 1: return loop<1, true>(t, sp, z, wd, out);
      case 2: return loop<2, true>(t, sp, z, wd, out);
      default: return loop<-1, true>(t, sp, z, wd, out);
    }
  }

 public:
  // (Public for its tests, SpanSum.* in tests/model/interp_span_test.cpp.)
  // A plane sum along the span as sign and magnitude, the magnitude stepped directly (by −dx for
  // a negative sum, mod 2^128: the signed value is always ±mag exactly), with the normaliser of
  // its binade [lo, lo + width) (zero: [0, 1)). A sum is affine in x, so it leaves its binade a
  // few times per span at most; then arm() re-derives sign, binade and normaliser.
  struct Sum {
    u128 mag = 0, step = 0, lo = 0, width = 1;
    i128 dx = 0;
    u128 row[3] = {};     // the common moves' deltas: dy − dx, dy, dy + dx
    bool fixed = false;   // sign and binade hold over the triangle's candidate rectangle
    bool neg = false;
    int bits = 1;
    NormalizeAtMsb norm;

    // The triangle's first span: the plane evaluated at its start (kept in `v`, the cursor), the
    // deltas of the common move (next row, x0 moved by −1, 0, +1) and whether the sign and binade
    // hold over the whole candidate rectangle `e` (`inside`: the span lies in it). An affine sum
    // takes its extremes on a rectangle at its corners: P(e.x0, e.y0) + min / max(0, (e.x1 − e.x0)·dx)
    // + min / max(0, (e.y1 − e.y0)·dy). When both extremes lie in the binade, every value of
    // every span does, and neither the moves nor run_length test it (`fixed`).
    void start(const Plane& p, const Span& sp, int bits_, u128& v, const TriSetup& e, bool inside) {
      bits = bits_;
      dx = p.dx;
      v = (u128)p.at(sp.x0, sp.y);
      arm((i128)v);
      row[0] = (u128)p.dy - (u128)p.dx, row[1] = (u128)p.dy, row[2] = (u128)p.dy + (u128)p.dx;
      fixed = false;
      if (!inside) return;
      // From the corner (e.x0, e.y0): P there (the plane's constant where it is anchored there, as
      // the attribute planes are) plus the smaller / larger of 0 and (e.x1 − e.x0)·dx, and so in y:
      // two products instead of four.
      const i128 corner = p.i0 == e.x0 && p.j0 == e.y0 ? p.c : p.at(e.x0, e.y0);
      const i128 wx = (i128)((int64_t)e.x1 - e.x0) * p.dx, hy = (i128)((int64_t)e.y1 - e.y0) * p.dy;
      const i128 lowv = corner + std::min<i128>(wx, 0) + std::min<i128>(hy, 0);
      const i128 highv = corner + std::max<i128>(wx, 0) + std::max<i128>(hy, 0);
      fixed = in_binade(lowv) && in_binade(highv);
    }
    // v has the current sign and binade (zero: v = 0 in the zero binade).
    bool in_binade(i128 v) const {
      if (v == 0) return mag == 0;
      if ((v < 0) != neg) return false;
      const u128 m = v < 0 ? (u128)0 - (u128)v : (u128)v;
      return m - lo < width;
    }
    // A later span of the same triangle: the value at its start is the last start's `v` plus
    // Δy·dy + Δx·dx (row[sel] for the common moves; mod 2^128: the true value fits i128, so the
    // sum is exact). The binade and normaliser are kept when the value stayed in them with its
    // sign (set; no test when fixed), else re-armed.
    // (advance: the value alone, for a span that does not read the binade; sync: the binade and
    // normaliser of the value v, from any earlier state.)
    void move(const Plane& p, int sel, int64_t ddx, int64_t ddy, u128& v, Counts& k) {
      advance(p, sel, ddx, ddy, v);
      sync(v, k);
    }
    void advance(const Plane& p, int sel, int64_t ddx, int64_t ddy, u128& v) const {
      v += sel >= 0 ? row[sel] : (u128)p.dy * (u128)ddy + (u128)p.dx * (u128)ddx;
    }
    void sync(u128 v, Counts& k) {
      if (fixed) {
        mag = neg ? (u128)0 - v : v;
        return;
      }
      const bool was = neg;
      if (set((i128)v)) return;
      ++k.rearmed_moves;
      k.rearmed_sign_moves += was != neg ? 1 : 0;
    }
    // Contract: the state arm(v) gives (mag, neg, step, lo, width, norm); true when the binade
    // and normaliser were kept (v has the sign and binade of the current ones), false when
    // re-armed. Tested against arm: SpanSum.* in tests/model/interp_span_test.cpp.
    bool set(i128 v) {
      const bool n = v < 0;
      const u128 m = n ? (u128)0 - (u128)v : (u128)v;
      if (n == neg && m - lo < width) {
        mag = m;
        return true;
      }
      arm(v);
      return false;
    }
    void arm(i128 v) {
      neg = v < 0;
      mag = neg ? (u128)0 - (u128)v : (u128)v;
      step = neg ? (u128)0 - (u128)dx : (u128)dx;
      if (mag == 0) {
        lo = 0, width = 1;
        return;
      }
      const int m = msb_index(mag);
      lo = width = (u128)1 << m;
      norm = NormalizeAtMsb(bits, m);
    }
    // Re-arms when the current value has left the binade (or changed sign), then returns how
    // many pixels from the current one on (at most `limit` ≥ 1) stay in it: the whole rest when
    // its last value is inside (the sum is monotone; a value that crossed zero is ≥ 2^127 mod
    // 2^128, never inside), else the exact exit by one division.
    // The `fixed` test inline (85 % of the bunny's triangles have every sum fixed), the rest out
    // of line (docs/speed.md "Session 11: the span").
    [[gnu::always_inline]] int64_t run_length(int64_t limit, Counts& k) {
      if (fixed) return limit;  // the whole triangle is in this binade (start)
      return run_length_moving(limit, k);
    }
    [[gnu::noinline]] int64_t run_length_moving(int64_t limit, Counts& k) {
      if (mag - lo >= width) {
        const bool was = neg;
        arm(neg ? -(i128)mag : (i128)mag);
        k.sign_changes += was != neg ? 1 : 0;
      }
      if (mag + (u128)(limit - 1) * step - lo < width) return limit;
      ++k.exits_divided;
      const i128 st = (i128)step;  // ≠ 0 here
      u128 q, r;
      if (st > 0) {  // up to lo + width (exclusive): ⌈(lo + width − mag) / st⌉ pixels
        udivmod128(lo + width - mag, (u128)st, q, r);
        return (int64_t)q + (r != 0 ? 1 : 0);
      }
      udivmod128(mag - lo, (u128)0 - step, q, r);  // down to lo (inclusive)
      return (int64_t)q + 1;
    }
    bool zero() const { return width == 1 && lo == 0; }
  };

 private:

  // The msb a sum is aligned to in the 64-bit-word segments: the high word's bit 62 (rne_high_word
  // needs msb ≤ 2·64 − 2); sums up to 2^127 (msb ≤ kAlignMsb, NormalizeAtMsb's range).
  static constexpr int kAlignMsb = kPixelAlignMsb;  // model/stages/pixel_divide.hpp
  // Shorter segments keep the u128 loop: the alignment's shifts and the magnitudes' write-back
  // cost more than they save on the bunny's 2-pixel spans (docs/speed.md "Session 12: the pixel
  // loop").
  static constexpr int64_t kAlignMinPixels = 4;

  // The depth words of span sp (nullptr without a depth test).
  uint32_t* span_codes(const Span& sp) const {
    return test_ ? buf_.codes + ((size_t)(sp.y - buf_.y0) * (size_t)buf_.width + (size_t)((int64_t)sp.x0 - buf_.x0))
                 : nullptr;
  }

  template <int NV, bool kOut, class Z, class W>
  uint64_t loop(const TriangleEquations& t, const Span& sp, const Z& z_start, const W& wd, uint8_t* out) {
    const int nv = kOut ? (NV >= 0 ? NV : nv_) : 0;
    const size_t stride = fragment_record_bytes(nv);
    // Everything the pixel loop reads is a local: the records are written through a byte
    // pointer, which may alias any member or the triangle, so members would be stored and
    // reloaded at every pixel.
    constexpr int kN = NV > 0 ? NV : NV == 0 ? 1 : kMaxVaryings;
    uint32_t* const codes = span_codes(sp);
    const unsigned mask = mask_;
    const bool write = write_;
    const uint32_t prim = t.prim;
    const int32_t y = sp.y;
    const int64_t x0 = sp.x0, x1 = sp.x1;
    const int ed = t.interp.den_exp, qb1 = wd.qb - 1;
    int nexp[kN];
    for (int m = 0; m < nv; ++m) nexp[m] = t.interp.num_exp[m] - qb1;
    Z z = z_start;
    uint8_t* rec = out;
    uint64_t pass_count = 0;
    int64_t i = x0;
    while (i <= x1) {
      // A segment of pixels where every sum keeps its sign and binade.
      int64_t len = x1 - i + 1;
      bool den_pos = true, lane_zero = false;
      if (nv > 0) {
        len = den_.run_length(len, counts_);
        den_pos = !den_.neg && !den_.zero();
        for (int m = 0; m < nv; ++m) {
          len = num_[m].run_length(len, counts_);
          lane_zero = lane_zero || num_[m].zero();
        }
      }
      ++counts_.segments;
      u128 dmag = den_.mag;
      const u128 dstep = den_.step;
      const NormalizeAtMsb& dnorm = den_.norm;
      u128 nmag[kN];
      bool nzero[kN];
      for (int m = 0; m < nv; ++m) {
        nmag[m] = num_[m].mag;
        nzero[m] = lane_zero && num_[m].zero();
      }
      const int64_t end = i + len;
      bool high = kOut && nv > 0 && high_words_ && den_pos && !lane_zero && len >= kAlignMinPixels &&
                  den_.norm.m <= kAlignMsb;
      for (int m = 0; m < nv; ++m) high = high && num_[m].norm.m <= kAlignMsb;
      if (high) {
        // Every sum left-aligned (docs/speed.md "Session 12: the pixel loop"): its value and step
        // times 2^(kAlignMsb − m), m its binade's msb, mod 2^128 — exact at every pixel of the
        // segment, where the value stays in the binade. The significand then lies in the high
        // word at a shift that does not depend on the binade, s = 63 − bits (rne_high_word with
        // constants: no shift or bias per sum and segment, any binade), and each exponent word
        // comes from its segment constant hw[m].
        ++counts_.segments_high;
        const int dm = dnorm.m + ed;
        counts_.segments_high_low += dnorm.shift <= 64 ? 1 : 0;
        // The rounding of a sum aligned at kAlignMsb: NormalizeAtMsb's shift and bias in the high
        // word (constants with the default widths).
        const NormalizeAtMsb dal(wd.db, kAlignMsb), nal(wd.nb, kAlignMsb);
        const int ds = dal.high_shift(), ns = nal.high_shift();
        const uint64_t dhb = dal.high_bias(), nhb = nal.high_bias();
        u128 da = dmag << (kAlignMsb - dnorm.m);
        const u128 dsa = dstep << (kAlignMsb - dnorm.m);
        u128 na[kN], nsa[kN];
        uint32_t hw[kN];
        for (int m = 0; m < nv; ++m) {
          const int sh = kAlignMsb - num_[m].norm.m;
          na[m] = nmag[m] << sh;
          nsa[m] = num_[m].step << sh;
          hw[m] = ((uint32_t)(num_[m].norm.m + nexp[m] - dm) << 1) | (num_[m].neg ? 1u : 0u);
        }
        // D's significand and reciprocal one pixel ahead: the division issues while the
        // previous pixel's quotients are worked on (the next value exists only inside the
        // segment: outside its binade the aligned value is meaningless, and may round to 0).
        uint64_t dn = rne_high_word<uint64_t>((uint64_t)(da >> 64), (uint64_t)da, ds, dhb);
        uint64_t Rn = div_recip64_w(wd.w, wd.db, dn);
        for (; i < end; ++i) {
          const uint32_t code = z.code();
          const bool pass = depth_pass(codes, i - x0, code, mask, write);
          pass_count += pass ? 1 : 0;
          const uint64_t d = dn, R = Rn;
          da += dsa;
          if (i + 1 < end) {
            dn = rne_high_word<uint64_t>((uint64_t)(da >> 64), (uint64_t)da, ds, dhb);
            Rn = div_recip64_w(wd.w, wd.db, dn);
          }
          if (pass) {
            put_fragment_header(rec, prim, (int32_t)i, y, code);
            // The significands as rounded, a carry-out (2^bits) not renormalised: for
            // a ∈ [2^(nb−1), 2^nb], d ∈ [2^(db−1), 2^db] div_sig_recip64_frac_w returns the correctly
            // rounded quotient of those values, i.e. the renormalised operands' result with the
            // exponent moved by the carries — its proof (model/arith/div.hpp) needs only
            // num < 2^(W+qb) and R = ⌊(2^64 − 1)/b⌋, and a quotient of exactly 2^qb (a = 2^nb,
            // d = 2^(db−1)) renormalises in round_increment (tests/model/div_test.cpp
            // DivRecip64Frac.CarryOut*, div_slow_test.cpp).
            for (int m = 0; m < nv; ++m) {
              const uint64_t a = rne_high_word<uint64_t>((uint64_t)(na[m] >> 64), (uint64_t)na[m], ns, nhb);
              const DivSig q = div_sig_recip64_frac_w(wd.w, wd.nb, wd.db, wd.qb, a, d, R);
              // put_fragment_var's words: the exponent word (exp << 1 | neg) from its segment
              // constant hw[m] = eb[m] << 1 | neg plus twice the pixel's part (mod 2^32).
              put_fragment_var_words(rec, m, (uint32_t)q.sig, hw[m] + 2u * (uint32_t)q.exp_adj);
            }
            rec += stride;
          }
          z.step_x();
          for (int m = 0; m < nv; ++m) na[m] += nsa[m];
        }
        // The magnitudes at `end`, the next segment's first pixel (maybe outside the binade: not
        // representable aligned), from the unaligned ones; past the span's end nothing reads them
        // (the next span start sets every sum: Sum::start / move).
        if (end <= x1) {
          dmag += (u128)(uint64_t)len * dstep;
          for (int m = 0; m < nv; ++m) nmag[m] += (u128)(uint64_t)len * num_[m].step;
        }
      }
      for (; i < end; ++i) {
        const uint32_t code = z.code();
        const bool pass = depth_pass(codes, i - x0, code, mask, write);
        pass_count += pass ? 1 : 0;
        if (kOut && pass) {
          put_fragment_header(rec, prim, (int32_t)i, y, code);
          if (nv > 0) {
            if (!den_pos) {  // D ≤ 0: every varying 0 (divide_varying)
              for (int m = 0; m < nv; ++m) put_fragment_var(rec, m, 0, 0, false);
            } else {
              int de;
              const uint64_t d = dnorm.sig_bits(dmag, de, wd.db);
              de += ed;
              const uint64_t R = div_recip64_w(wd.w, wd.db, d);
              for (int m = 0; m < nv; ++m) {
                if (nzero[m]) {
                  put_fragment_var(rec, m, 0, 0, false);
                  continue;
                }
                int ne;
                const uint64_t a = num_[m].norm.sig_bits(nmag[m], ne, wd.nb);
                const DivSig q = div_sig_recip64_frac_w(wd.w, wd.nb, wd.db, wd.qb, a, d, R);
                put_fragment_var(rec, m, q.sig, q.exp_adj + ne + nexp[m] - de, num_[m].neg);
              }
            }
          }
          rec += stride;
        }
        z.step_x();
        if (nv > 0) {
          dmag += dstep;
          for (int m = 0; m < nv; ++m) nmag[m] += num_[m].step;
        }
      }
      if (nv > 0) {
        den_.mag = dmag;
        for (int m = 0; m < nv; ++m) num_[m].mag = nmag[m];
      }
    }
    return pass_count;
  }

  // A span of at most kDirectMaxPixels pixels with varyings: each passing pixel divided directly
  // from the cursor's sums (PixelDivide, model/stages/pixel_divide.hpp), no segment, binade or
  // run_length (docs/speed.md "Session 13: the divider of one pixel").
  static constexpr int64_t kDirectMaxPixels = 4;
  bool direct_span(const Span& sp) const {
    return direct_ && nv_ > 0 && (int64_t)sp.x1 - sp.x0 < kDirectMaxPixels;
  }
  template <int NV, class Z, class W>
  uint64_t loop_direct(const TriangleEquations& t, const Span& sp, const Z& z_start, const W& wd, uint8_t* out) {
    const int nv = NV >= 0 ? NV : nv_;
    const size_t stride = fragment_record_bytes(nv);
    constexpr int kN = NV > 0 ? NV : kMaxVaryings;
    // Locals only (the records are written through a byte pointer that may alias any member).
    const PixelDivide pd = pd_;
    uint32_t* const codes = span_codes(sp);
    const unsigned mask = mask_;
    const bool write = write_;
    const uint32_t prim = t.prim;
    const int32_t y = sp.y;
    const int64_t x0 = sp.x0, x1 = sp.x1;
    // The cursor's sums were just written (run_begun) and the planes' steps by setup, each as two
    // 64-bit stores: read as two words, not as one 16-byte load that waits for both stores to
    // retire (perf: 23 % of this loop's samples on that load).
    u128 s[1 + kN], dx[1 + kN];
    s[0] = u128_words(val_[0]), dx[0] = u128_words((const u128&)t.interp.den.dx);
    for (int m = 0; m < nv; ++m)
      s[1 + m] = u128_words(val_[1 + m]), dx[1 + m] = u128_words((const u128&)t.interp.num[m].dx);
    Z z = z_start;
    uint8_t* rec = out;
    uint64_t pass_count = 0;
    for (int64_t i = x0; i <= x1; ++i) {
      const uint32_t code = z.code();
      const bool pass = depth_pass(codes, i - x0, code, mask, write);
      pass_count += pass ? 1 : 0;
      if (pass) {
        put_fragment_header(rec, prim, (int32_t)i, y, code);
        pd.write_t<NV>(rec, s, wd);
        rec += stride;
      }
      z.step_x();
      for (int k = 0; k <= nv; ++k) s[k] += dx[k];
    }
    return pass_count;
  }

  DivConfig dc_;
  int nv_;
  PixelDivide pd_{dc_, nv_};
  DepthBufferView buf_;
  unsigned mask_;
  bool test_, write_;
  DivWidths widths_;
  bool default_widths_;
  bool high_words_ = true;  // the 64-bit-word segments (the tests turn them off to compare)
  bool direct_ = true;      // short spans through loop_direct (the tests turn it off to compare)
  Sum den_;
  Sum num_[kMaxVaryings];
  // The span-start cursor of the current triangle (begin / run).
  const TriangleEquations* tri_ = nullptr;
  uint64_t serial_ = 0;  // tri_->serial at begin()
  bool started_ = false, fits_ = false, z_cursor_ = false;
  int32_t cx_ = 0, cy_ = 0;            // the last span start
  u128 val_[1 + kMaxVaryings] = {};   // D, N_m at (cx_, cy_) (two's complement)
  DepthCursor zcur_;
  Counts counts_;
  std::vector<uint8_t> scratch_;  // run(…, emit)'s records
};

}  // namespace fxr
