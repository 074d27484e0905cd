// Stages 3 and 4: reciprocal + perspective divide, viewport + snap. Contracts in model/stages/viewport.hpp.
#include "model/stages/viewport.hpp"

#include "model/stages/attr.hpp"

#include "model/stages/recip.hpp"

#include "model/arith/round_flat.hpp"

namespace fxr {

namespace {
// Largest |m·2^e| round_scaled_sum accepts (bits), so that (q + c) · 4 stays inside an i128.
constexpr int kSnapSumMaxBits = 120;
// Beyond this right shift, m·2^e (|m| < 2^122) is below ¼ and only its sign matters.
constexpr int kSnapCollapseShift = 124;

// Contract: p with its significand cut to ≤ kSnapProdMaxBits bits by jamming (dropped bits
// OR-ed into the lowest kept bit). A later RNE to ≤ kSnapProdMaxBits − 2 significant bits of
// the sum with a coarser integer is then the same as from the exact p.
FxProd jam(FxProd p) {
  const int over = msb_index(p.sig) + 1 - kSnapProdMaxBits;
  if (over <= 0) return p;
  const bool sticky = low_bits(p.sig, over) != 0;
  p.sig = (p.sig >> over) | (sticky ? 1 : 0);
  p.exp += over;
  return p;
}
}  // namespace

FxProd mul_exact(const FxFloat& a, const FxFloat& b) {
  FxProd p;
  p.neg = a.neg != b.neg;
  p.sig = (u128)a.sig * b.sig;
  p.exp = a.exp + b.exp;
  return p;
}

i128 round_scaled_sum(i128 m, int e, i128 c, int sh, bool* range) {
  if (m == 0) return shift_round(c, sh, Round::HalfEven);
  const u128 mag = m < 0 ? -(u128)m : (u128)m;
  if (e >= 0) {
    if (msb_index(mag) + e > kSnapSumMaxBits) {
      *range = true;
      return 0;
    }
    return shift_round(m * ((i128)1 << e) + c, sh, Round::HalfEven);  // m may be < 0: no <<
  }
  const int k = -e;
  i128 q;
  bool g, s;
  if (k >= kSnapCollapseShift) {  // |m·2^e| < ¼: floor is 0 or −1, fraction (0,¼) or (¾,1)
    q = m < 0 ? -1 : 0;
    g = m < 0;
    s = true;
  } else {
    q = m >> k;                                   // floor
    const u128 r = (u128)(m - q * ((i128)1 << k));  // [0, 2^k); q may be < 0: no <<
    g = (r >> (k - 1)) & 1;                       // the ½ bit
    s = low_bits(r, k - 1) != 0;                  // anything below it
  }
  // X/4 = q + c + (g/2 + s/4) rounds like the exact q + c + r/2^k at any step ≥ 1.
  const i128 x = (q + c) * 4 + ((i128)g << 1) + (i128)s;  // (q + c)·4 | g·2 | s without a negative <<
  return shift_round(x, sh + 2, Round::HalfEven);
}

bool round_scaled_sum64(int64_t m, int e, int64_t c, int sh, int64_t* out) {
  // Range: |m| < 2^kSnapFast64Bits, |c| < 2^(kSnapFast64Bits − 1), sh + 2 ≤ kInt64ShiftMax, and for e ≥ 0
  // |m·2^e| < 2^(kSnapFast64Bits − 1) (so m·2^e + c fits), for e < 0 a shift −e ≤ kSnapFast64Bits
  // (so q, r and (q + c)·4 fit: |q + c| < 2^kSnapFast64Bits). Then the i128 path's steps in int64.
  constexpr int64_t kM = (int64_t)1 << kSnapFast64Bits, kC = (int64_t)1 << (kSnapFast64Bits - 1);
  if (m >= kM || m <= -kM || c >= kC || c <= -kC || sh < 0 || sh + 2 > kInt64ShiftMax) return false;
  // The rounding without a branch on the dropped bits (data-dependent: mispredicted about 1.4
  // times a call; docs/speed.md "Session 13: per vertex and per triangle").
  const auto rne = [](int64_t x, int s) {
    return s == 0 ? x : detail::shift_round_right_rne_flat<int64_t, uint64_t>(x, s);
  };
  if (m == 0) {
    *out = rne(c, sh);
    return true;
  }
  if (e >= 0) {
    const uint64_t mag = m < 0 ? (uint64_t)0 - (uint64_t)m : (uint64_t)m;
    if (msb64(mag) + e >= kSnapFast64Bits - 1) return false;
    *out = rne(m * ((int64_t)1 << e) + c, sh);  // m may be < 0: no <<
    return true;
  }
  const int k = -e;
  if (k > kSnapFast64Bits) return false;
  const int64_t q = m >> k;                                     // floor
  const uint64_t r = (uint64_t)(m - q * ((int64_t)1 << k));    // [0, 2^k)
  const bool g = (r >> (k - 1)) & 1;
  const bool s = (r & ((((uint64_t)1) << (k - 1)) - 1)) != 0;
  const int64_t x = (q + c) * 4 + ((int64_t)g << 1) + (int64_t)s;
  *out = rne(x, sh + 2);
  return true;
}

namespace {
// ±mag (mag < 2^63) by masks: a branch on the sign, data-dependent, was mispredicted (docs/speed.md
// "Session 13: per vertex and per triangle").
inline int64_t signed_by(uint64_t mag, bool neg) {
  const uint64_t m = (uint64_t)0 - (uint64_t)neg;
  return (int64_t)((mag ^ m) - m);
}
// snap_window's range check of a code.
int64_t window_code(i128 code, bool r, const RasterConfig& rc, bool* range) {
  const int code_bits = rc.window_int_bits + rc.subpixel_bits;  // signed
  const i128 hi = (((i128)1) << (code_bits - 1)) - 1, lo = -(((i128)1) << (code_bits - 1));
  if (r || code > hi || code < lo) {
    *range = true;
    return 0;
  }
  return (int64_t)code;
}
}  // namespace

int64_t snap_window(const FxProd& n, int64_t size, int64_t origin, const RasterConfig& rc, bool* range) {
  // snap_window_wide in 64-bit words when m = n.sig·size and c fit round_scaled_sum64 (n.sig
  // below 2^64 is below kSnapProdMaxBits: jam leaves it unchanged).
  const int s = rc.subpixel_bits;
  uint64_t mag;
  int64_t c, code;
  if ((n.sig >> 64) == 0 && size > 0 && s >= 0 && s < kInt64ShiftMax &&
      !__builtin_mul_overflow((uint64_t)n.sig, (uint64_t)size, &mag) && mag < ((uint64_t)1 << kSnapFast64Bits) &&
      !__builtin_mul_overflow(size + 2 * origin, (int64_t)1 << s, &c) &&
      round_scaled_sum64(signed_by(mag, n.neg), n.exp + s, c, 1, &code))
    return window_code(code, false, rc, range);
  return snap_window_wide(n, size, origin, rc, range);
}

int64_t snap_window_wide(const FxProd& n0, int64_t size, int64_t origin, const RasterConfig& rc, bool* range) {
  const FxProd n = jam(n0);
  const int s = rc.subpixel_bits;
  // 2·code = n·size·2^s + (size + 2·origin)·2^s, then one RNE halving.
  const i128 m = (i128)(n.sig * (u128)size);      // < 2^(100 + 21)
  const i128 c = (i128)(size + 2 * origin) * ((i128)1 << s);  // origin may be < 0: no <<
  bool r = false;
  const i128 code = round_scaled_sum(n.neg ? -m : m, n.exp + s, c, 1, &r);
  return window_code(code, r, rc, range);
}

uint64_t snap_depth(const FxProd& zn0, const RasterConfig& rc) {
  const FxProd zn = jam(zn0);
  if (zn.sig == 0 || zn.neg) return 0;  // z_n ≤ 0 saturates to 0
  const i128 one = ((i128)1) << rc.z_frac_bits;
  bool r = false;
  const i128 code = round_scaled_sum((i128)zn.sig, zn.exp + rc.z_frac_bits, 0, 0, &r);
  if (r || code > one) return (uint64_t)one;  // z_n > 1 saturates to 1 (precision: ½ LSB RNE)
  return (uint64_t)code;
}

FxFloat round_prod(const FxProd& p, int bits) {
  FxFloat f;
  f.neg = p.neg;
  if (p.sig == 0) return f;
  const Normalized nm = normalize(p.sig, bits, Round::HalfEven);  // precision lost: ½ ulp
  f.sig = nm.sig;
  f.exp = p.exp + nm.exp - (bits - 1);
  return f;
}

ProjectStatus project_vertex(const Config& cfg, const DrawState& st, const ClipVtx& v, SetupVertex& out) {
  // Stage 3: the reciprocal unit. w is exact at in_sig_bits (float32: 24 bits; the clipper
  // rounds its w to exactly this width), so this normalisation never rounds.
  FxFloat r;
  if (!recip_vertex(cfg.recip, v, r)) return ProjectStatus::RecipError;
  return snap_vertex(cfg, st, v, r, out);
}

ProjectStatus snap_vertex(const Config& cfg, const DrawState& st, const ClipVtx& v, const FxFloat& r,
                          SetupVertex& out) {
  const ProjectStatus s = snap_vertex_active(cfg, st, v, r, out);
  if (s == ProjectStatus::Ok)
    for (int k = std::max(st.num_varyings, 0); k < kMaxVaryings; ++k) out.vw[k] = FxFloat{};
  return s;
}

ProjectStatus snap_vertex_active(const Config& cfg, const DrawState& st, const ClipVtx& v, const FxFloat& r,
                                 SetupVertex& out, bool rw_unread) {
  const RasterConfig& rc = cfg.raster;
  // Perspective divide as exact products (no rounding here).
  const FxProd xn = mul_exact(v.p[0], r), yn = mul_exact(v.p[1], r), zn = mul_exact(v.p[2], r);
  // Stage 4: viewport + snap, one RNE each.
  bool range = false;
  out.x = snap_window(xn, st.viewport_w, st.viewport_x, rc, &range);
  out.y = snap_window(yn, st.viewport_h, st.viewport_y, rc, &range);
  if (range) return ProjectStatus::Range;
  if (attr_separate(rc)) {
    // Separate attribute positions (model/stages/attr.hpp): x_c/w_c, y_c/w_c, z_c/w_c, 1/w_c and
    // v_k/w_c as exact quotients, each rounded once; r is used for the snap only. w_c is the
    // attribute w: exact (float32) or the clipper's rounding to raster.clip_sig_bits.
    const FxFloat& w = v.attr_w();
    out.ax = attr_window(v.p[0], w, st.viewport_w, st.viewport_x, rc, &range);
    out.ay = attr_window(v.p[1], w, st.viewport_h, st.viewport_y, rc, &range);
    if (range) return ProjectStatus::Range;
    out.z = attr_depth(v.p[2], w, rc);
    static const FxFloat kOne{false, 1, 0};
    // attr_quotient written in place (its result returned through the stack and copied stalled
    // on store forwarding: a quarter of snap_vertex's samples).
    const auto quotient = [&](const FxFloat& n, FxFloat& q) {
      if (!attr_quotient64(n, w, rc.attr_sig_bits, &q)) q = attr_quotient_wide(n, w, rc.attr_sig_bits);
    };
    if (rw_unread) out.rw = FxFloat{};
    else quotient(kOne, out.rw);
    for (int k = 0; k < st.num_varyings; ++k) {
      if (st.interp == InterpMode::Affine) out.vw[k] = normalize_fx(v.v[k], rc.attr_sig_bits, Round::HalfEven);
      else quotient(v.v[k], out.vw[k]);
    }
    return ProjectStatus::Ok;
  }
  out.ax = out.x;
  out.ay = out.y;
  out.z = snap_depth(zn, rc);
  out.rw = r;
  for (int k = 0; k < st.num_varyings; ++k) {
    if (st.interp == InterpMode::Affine) {
      // Affine (the wrong image of docs/references.md#seed-000-wrong-image): v itself, at the same width (exact for float32 inputs
      // when varying_sig_bits ≥ 24).
      out.vw[k] = v.v[k].sig ? normalize_fx(v.v[k], rc.varying_sig_bits, Round::HalfEven) : v.v[k];
    } else {
      out.vw[k] = round_prod(mul_exact(v.v[k], r), rc.varying_sig_bits);
    }
  }
  return ProjectStatus::Ok;
}

StageCost ViewportStage::cost(const Config& cfg, int num_varyings, int lanes) {
  const RasterConfig& r = cfg.raster;
  const int sb = clip_vertex_sig_bits(cfg), rb = cfg.recip.out_sig_bits;
  StageCost c;
  // Per vertex: x, y, z and every varying times 1/w, then x and y times the viewport size.
  for (int v = 0; v < 3; ++v) {
    for (int k = 0; k < 3 + kMaxVaryings; ++k) c.add_mult(sb, rb);
    c.add_mult(sb + rb, r.window_int_bits + 1);
    c.add_mult(sb + rb, r.window_int_bits + 1);
  }
  c.latency = 3;  // products, scale + offset, rounding (the products-only path has no RTL)
  c.ii = 1;
  c.adder_bits = 3 * (int64_t)(3 + kMaxVaryings) * (sb + rb);
  if (attr_separate(r)) {
    // Attribute path (model/stages/attr.hpp): per vertex the exact quotients x_c/w_c, y_c/w_c
    // (window_int_bits + A + 1 quotient bits), z_c/w_c (z_frac_bits + 2), 1/w_c and every v/w_c
    // (attr_sig_bits + 2, with guard and sticky), each a correctly rounded division: counted as
    // a restoring divider's subtractor bits (quotient bits × divisor bits, divisor
    // recip.in_sig_bits), plus the viewport scale products of x and y. The v·(1/w) products
    // above are then unused for the planes (kept: the snap still uses x·r, y·r). The divisor is
    // the attribute w (clip_vertex_sig_bits: the clipper's new w at raster.clip_sig_bits).
    const int wb = sb;
    const int q_xy = r.window_int_bits + r.attr_subpixel_bits + 1, q_z = r.z_frac_bits + 2, q_v = r.attr_sig_bits + 2;
    for (int v = 0; v < 3; ++v) {
      c.adder_bits += (int64_t)(2 * q_xy + q_z + (1 + kMaxVaryings) * q_v) * wb;
      c.add_mult(sb, r.window_int_bits + 1);
      c.add_mult(sb, r.window_int_bits + 1);
    }
    // The RTL (rtl/fxr_viewport_core.sv): J quotient jobs issued `lanes` per clock over
    // ⌈J / lanes⌉ slots (the initiation interval), each through viewport_quot_bits pipeline
    // stages, plus the input register, the result alignment and the output register.
    const int jobs = 3 * (4 + std::max(num_varyings, 0));
    c.ii = (jobs + std::max(lanes, 1) - 1) / std::max(lanes, 1);
    c.latency = c.ii + viewport_quot_bits(r) + 3;
  }
  c.ff_bits = c.latency * record_bits<SetupTriangle>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr
