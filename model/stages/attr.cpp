// Attribute positions and attribute planes (issue 8). Contracts in model/stages/attr.hpp;
// derivations in docs/pipeline.md, "Attribute positions".
#include "model/stages/attr.hpp"

#include <algorithm>
#include <climits>
#include <string>

#include "model/arith/round_flat.hpp"

namespace fxr {

namespace {

// Values held in i128 (127 value bits).
constexpr int kI128Bits = 127;
// Largest msb an intermediate shifted numerator or denominator may have in the exact division.
constexpr int kDivMaxMsb = 125;

}  // namespace

i128 rne_quotient_plus(bool neg, u128 N, int k, u128 D, i128 C, bool* overflow) {
  if (N == 0) return C;
  u128 num = N, den = D;
  if (k >= 0) {
    if (msb_index(N) + k > kDivMaxMsb) {
      *overflow = true;
      return 0;
    }
    num = N << k;
  } else {
    if (msb_index(D) - k > kDivMaxMsb) return C;  // |quotient| < 2^−24: rounds to C either way
    den = D << (-k);
  }
  u128 q, r;
  udivmod128(num, den, q, r);
  if (q >> 120) {
    *overflow = true;
    return 0;
  }
  i128 fl;
  u128 frac_num;  // fraction = frac_num / den ∈ [0, 1)
  if (!neg) {
    fl = C + (i128)q;
    frac_num = r;
  } else if (r == 0) {
    return C - (i128)q;
  } else {
    fl = C - (i128)q - 1;
    frac_num = den - r;
  }
  // Round half to even: 2·frac vs 1 (den < 2^126, so 2·frac_num does not overflow u128).
  const u128 twice = frac_num << 1;
  if (twice > den || (twice == den && (fl & 1))) fl += 1;
  return fl;
}

namespace {

// FxFloat with a zero-exponent-safe view: sig as u128.
inline u128 sig128(const FxFloat& f) { return (u128)f.sig; }

}  // namespace

// ---- 64-bit paths (docs/speed.md "Session 9: per triangle") ------------------------------------
//
// Each runs rne_quotient_plus / attr_quotient's steps in 64-bit words when its range test shows
// every intermediate fits (float32 inputs have 24-bit significands: the shifted numerators reach
// ≈ 2^56 at the default widths), else answers false and the caller takes the i128 path.

bool rne_quotient_plus64(bool neg, uint64_t N, int k, uint64_t D, int64_t C, int64_t* out) {
  // Range: both operands after the shift and |C| below 2^kAttrFast64Bits (61), so the quotient is below
  // 2^61, C ± q − 1 fits int64 and 2·frac_num < 2·den < 2^62. D > 0.
  if (D == 0 || C >= ((int64_t)1 << kAttrFast64Bits) || C <= -((int64_t)1 << kAttrFast64Bits)) return false;
  if (N == 0) {
    *out = C;
    return true;
  }
  uint64_t num = N, den = D;
  if (k >= 0) {
    if (msb64(N) + k >= kAttrFast64Bits || msb64(D) >= kAttrFast64Bits) return false;
    num = N << k;
  } else {
    if (msb64(D) - k >= kAttrFast64Bits || msb64(N) >= kAttrFast64Bits) return false;  // (the i128 path's
                                                                                      // |q| < 2^−24 cut-off is past this)
    den = D << (-k);
  }
  const uint64_t q = num / den, r = num % den;
  // ±num/den = qf + frac_num/den with qf = floor: q, r when positive; −q − 1, den − r when
  // negative with r ≠ 0; −q, 0 when negative with r = 0 (the i128 path's three cases). Formed
  // with masks, not branches: the sign is data-dependent (half of a mesh's x_c and y_c are
  // negative) and the branch on it, with the rounding's on 2·frac_num > den, was mispredicted
  // about 1.4 times a call (callgrind --branch-sim; docs/speed.md "Session 13: per vertex and per
  // triangle"). Wrapping uint64 arithmetic: C ± q − 1 fits int64 (the range test above).
  const uint64_t neg_mask = (uint64_t)0 - (uint64_t)neg;               // all ones when negative
  const uint64_t r_zero = (uint64_t)(r == 0);
  const uint64_t qf = (q ^ neg_mask) + (neg_mask & r_zero);           // ~q = −q − 1
  const uint64_t flip = neg_mask & (r_zero - 1);                       // negative and r ≠ 0
  const uint64_t frac_num = r ^ ((r ^ (den - r)) & flip);
  const int64_t fl = (int64_t)((uint64_t)C + qf);
  *out = fl + (int64_t)rne_round_up_flat<uint64_t>((uint64_t)fl, frac_num, den);
  return true;
}

bool attr_quotient64(const FxFloat& n, const FxFloat& w, int bits, FxFloat* out) {
  // Range: bits ≤ 61 (q < 2^(bits+2) ≤ 2^63) and the shifted operand below 2^63; w > 0.
  if (w.sig == 0 || bits > kAttrFast64Bits) return false;
  FxFloat f;
  f.neg = n.neg;
  if (n.sig == 0) {
    *out = f;
    return true;
  }
  const int s = bits + 1 + msb64(w.sig) - msb64(n.sig);
  uint64_t num = n.sig, den = w.sig;
  if (s >= 0) {
    if (msb64(n.sig) + s > kInt64ShiftMax) return false;
    num <<= s;
  } else {
    if (msb64(w.sig) - s > kInt64ShiftMax) return false;
    den <<= -s;
  }
  const uint64_t q = num / den, r = num % den;
  const bool rem = r != 0;
  const int extra = msb64(q) - (bits - 1);  // 1 or 2
  uint64_t sig = q >> extra;
  const bool guard = (q >> (extra - 1)) & 1;
  const bool sticky = rem || (q & ((((uint64_t)1) << (extra - 1)) - 1)) != 0;
  // The rounding from flags, without a branch (data-dependent; docs/speed.md "Session 13: per
  // vertex and per triangle").
  sig += (uint64_t)(guard & (sticky | ((sig & 1) != 0)));
  int e = extra;
  if (sig >> bits) sig >>= 1, e += 1;
  f.sig = sig;
  f.exp = n.exp - s - w.exp + e;
  *out = f;
  return true;
}

void check_attr_widths(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  if (!attr_separate(r)) return;  // attr_subpixel_bits ≤ subpixel_bits: planes on the snapped triangle
  if (attr_position_bits(r) > kInt64ShiftMax)
    throw ConfigError("raster: fields 'window_int_bits' + 'attr_subpixel_bits' = " +
                      std::to_string(attr_position_bits(r)) + " bits: attribute positions are held in int64 (<= " +
                      std::to_string(kInt64ShiftMax) + ")");
  if (r.attr_coord_bits < r.window_int_bits + 3)
    throw ConfigError("raster: field 'attr_coord_bits' (" + std::to_string(r.attr_coord_bits) +
                      ") must be >= window_int_bits + 3 so that every triangle keeps a fraction bit");
  if (r.z_frac_bits < r.depth_bits())
    throw ConfigError("raster: field 'z_frac_bits' must be >= the depth format's bits on the attribute path");
  const int depth_sum = attr_edge_value_bits(r) + r.z_frac_bits + 1 + 2;
  const int interp_sum = attr_edge_value_bits(r) + r.interp_block_bits + 1 + 2;
  if (depth_sum > kI128Bits || interp_sum > kI128Bits)
    throw ConfigError("raster: field 'attr_coord_bits' (" + std::to_string(r.attr_coord_bits) +
                      "): attribute plane sums need " + std::to_string(std::max(depth_sum, interp_sum)) +
                      " bits, more than " + std::to_string(kI128Bits));
}

int64_t attr_window(const FxFloat& c, const FxFloat& w, int64_t size, int64_t origin, const RasterConfig& rc,
                    bool* range) {
  // attr_window_wide's quotient in 64-bit words when it fits (rne_quotient_plus64's range test).
  const int A = rc.attr_subpixel_bits;
  int64_t C, v;
  uint64_t N;
  if (size > 0 && A >= 1 && A - 1 < kAttrFast64Bits && attr_position_bits(rc) <= kInt64ShiftMax &&
      !__builtin_mul_overflow(size + 2 * origin, (int64_t)1 << (A - 1), &C) &&
      !__builtin_mul_overflow(c.sig, (uint64_t)size, &N) &&
      rne_quotient_plus64(c.neg, N, c.exp - w.exp + A - 1, w.sig, C, &v)) {
    const int64_t lim = (int64_t)1 << (attr_position_bits(rc) - 1);
    if (v >= lim || v < -lim) {
      *range = true;
      return 0;
    }
    return v;
  }
  return attr_window_wide(c, w, size, origin, rc, range);
}

int64_t attr_window_wide(const FxFloat& c, const FxFloat& w, int64_t size, int64_t origin, const RasterConfig& rc,
                         bool* range) {
  const int A = rc.attr_subpixel_bits;  // ≥ 1 (attr_separate: A > subpixel_bits ≥ 0)
  // x·2^A = ±m_c·size·2^(e_c − e_w + A − 1) / m_w + (size + 2·origin)·2^(A − 1)
  const i128 C = (i128)(size + 2 * origin) * ((i128)1 << (A - 1));  // no left shift of a negative value
  bool ovf = false;
  const i128 v = c.sig == 0 ? C
                            : rne_quotient_plus(c.neg, sig128(c) * (u128)size, c.exp - w.exp + A - 1, sig128(w), C, &ovf);
  const i128 lim = (i128)1 << (attr_position_bits(rc) - 1);
  if (ovf || v >= lim || v < -lim) {
    *range = true;
    return 0;
  }
  return (int64_t)v;
}

uint64_t attr_depth(const FxFloat& z, const FxFloat& w, const RasterConfig& rc) {
  if (z.sig == 0 || z.neg) return 0;
  int64_t v;
  if (rc.z_frac_bits < kAttrFast64Bits && rne_quotient_plus64(false, z.sig, z.exp - w.exp + rc.z_frac_bits, w.sig, 0, &v)) {
    const int64_t one = (int64_t)1 << rc.z_frac_bits;
    return (uint64_t)(v > one ? one : v);  // (v ≥ 0: a non-negative quotient)
  }
  return attr_depth_wide(z, w, rc);
}

uint64_t attr_depth_wide(const FxFloat& z, const FxFloat& w, const RasterConfig& rc) {
  if (z.sig == 0 || z.neg) return 0;  // z ≤ 0 saturates to 0
  const i128 one = (i128)1 << rc.z_frac_bits;
  bool ovf = false;
  const i128 v = rne_quotient_plus(false, sig128(z), z.exp - w.exp + rc.z_frac_bits, sig128(w), 0, &ovf);
  if (ovf || v > one) return (uint64_t)one;  // z > w saturates to 1
  return (uint64_t)v;
}

FxFloat attr_quotient(const FxFloat& n, const FxFloat& w, int bits) {
  FxFloat out;
  if (!attr_quotient64(n, w, bits, &out)) out = attr_quotient_wide(n, w, bits);
  return out;
}

FxFloat attr_quotient_wide(const FxFloat& n, const FxFloat& w, int bits) {
  FxFloat out;
  out.neg = n.neg;
  if (n.sig == 0) return out;
  // q = n.sig·2^s / w.sig with s chosen so that q ∈ [2^bits, 2^(bits+2)): at least one guard bit.
  const int s = bits + 1 + msb_index((u128)w.sig) - msb_index((u128)n.sig);
  u128 num = (u128)n.sig, den = (u128)w.sig;
  if (s >= 0) num <<= s;
  else den <<= -s;
  u128 q, r;
  udivmod128(num, den, q, r);
  const bool rem = r != 0;
  const int extra = msb_index(q) - (bits - 1);  // 1 or 2
  u128 sig = q >> extra;
  const bool guard = (q >> (extra - 1)) & 1;
  const bool sticky = rem || low_bits(q, extra - 1) != 0;
  if (guard && (sticky || (sig & 1))) sig += 1;  // round half to even — the one rounding
  int e = extra;
  if (sig >> bits) sig >>= 1, e += 1;            // carry to 2^bits (exact: the low bit is 0)
  out.sig = (uint64_t)sig;
  out.exp = n.exp - s - w.exp + e;
  return out;
}

AttrSetup attr_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t) {
  const RasterConfig& rc = cfg.raster;
  const int A = rc.attr_subpixel_bits;
  AttrSetup s;
  // Magnitude of the relative coordinates at A bits: vertices, the candidate rectangle's corner
  // pixel centres, and one pixel (so that the per-pixel step 2^F stays within the width too).
  const i128 ox = tri.v[0].ax, oy = tri.v[0].ay;
  u128 M = (u128)1 << A;
  auto grow = [&M](i128 d) { M = std::max(M, (u128)(d < 0 ? -d : d)); };
  for (int k = 1; k < 3; ++k) grow(tri.v[k].ax - ox), grow(tri.v[k].ay - oy);
  const i128 half = (i128)1 << (A - 1);
  for (int i : {t.x0, t.x1}) grow((i128)i * ((i128)1 << A) + half - ox);
  for (int j : {t.y0, t.y1}) grow((i128)j * ((i128)1 << A) + half - oy);
  // Signed bits the relative values need, with one more for the rounding below: msb + 3.
  const int need = msb_index(M) + 3;
  const int drop = std::max(0, need - rc.attr_coord_bits);  // PRECISION IS LOST HERE when > 0 (RNE)
  s.F = A - drop;
  int64_t X[3], Y[3];
  for (int k = 0; k < 3; ++k) {
    X[k] = (int64_t)shift_round((i128)tri.v[k].ax, drop, Round::HalfEven);
    Y[k] = (int64_t)shift_round((i128)tri.v[k].ay, drop, Round::HalfEven);
  }
  s.ox = X[0];
  s.oy = Y[0];
  for (int k = 0; k < 3; ++k) s.x[k] = X[k] - s.ox, s.y[k] = Y[k] - s.oy;
  // Edge k from v_{k+1} to v_{k+2} in relative coordinates (exact in i128: < 2^(2·acb+1)).
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    s.a[k] = (i128)s.y[a] - s.y[b];
    s.b[k] = (i128)s.x[b] - s.x[a];
    s.c[k] = (i128)s.x[a] * s.y[b] - (i128)s.x[b] * s.y[a];
  }
  s.area2 = s.c[0];  // E'_0 at vertex 0, which is the origin
  if (s.area2 == 0) return s;  // ok = false
  if (s.area2 < 0) {
    for (int k = 0; k < 3; ++k) s.a[k] = -s.a[k], s.b[k] = -s.b[k], s.c[k] = -s.c[k];
    s.area2 = -s.area2;
  }
  s.i0 = t.x0;
  s.j0 = t.y0;
  s.ok = true;
  return s;
}

Plane make_attr_plane(const AttrSetup& s, const int64_t q[3]) {
  // E'_k(centre(i, j)) = a_k·((2i + 1)·2^(F−1) − ox) + b_k·((2j + 1)·2^(F−1) − oy) + c_k, anchored at (i0, j0).
  const i128 h = (i128)1 << (s.F - 1);
  const i128 unit = (i128)1 << s.F;  // one pixel; products, not shifts, of signed values
  const i128 X0 = (i128)s.i0 * unit + h - s.ox, Y0 = (i128)s.j0 * unit + h - s.oy;
  Plane p;
  p.i0 = s.i0;
  p.j0 = s.j0;
  for (int k = 0; k < 3; ++k) {
    p.dx += s.a[k] * unit * q[k];
    p.dy += s.b[k] * unit * q[k];
    p.c += (s.a[k] * X0 + s.b[k] * Y0 + s.c[k]) * q[k];
  }
  return p;
}

AttrEdgeTerms attr_edge_terms(const AttrSetup& s) {
  // As make_attr_plane: E'_k(centre(i, j)) = a_k·X + b_k·Y + c_k with X = (2i + 1)·2^(F−1) − ox.
  const i128 h = (i128)1 << (s.F - 1);
  const i128 unit = (i128)1 << s.F;
  const i128 X0 = (i128)s.i0 * unit + h - s.ox, Y0 = (i128)s.j0 * unit + h - s.oy;
  AttrEdgeTerms t;
  t.i0 = s.i0;
  t.j0 = s.j0;
  t.fits64 = true;
  const auto fits = [](i128 v) { return v >= (i128)INT64_MIN && v <= (i128)INT64_MAX; };
  for (int k = 0; k < 3; ++k) {
    t.dx[k] = s.a[k] * unit;
    t.dy[k] = s.b[k] * unit;
    t.e0[k] = s.a[k] * X0 + s.b[k] * Y0 + s.c[k];
    t.fits64 = t.fits64 && fits(t.dx[k]) && fits(t.dy[k]) && fits(t.e0[k]);
  }
  if (t.fits64)
    for (int k = 0; k < 3; ++k) t.dx64[k] = (int64_t)t.dx[k], t.dy64[k] = (int64_t)t.dy[k], t.e064[k] = (int64_t)t.e0[k];
  return t;
}

namespace {
// attr_edge_terms64 with 2A' as the int64 it is computed in (attr_plane_setup: an i128 written
// through a pointer as two words and read back by one 16-byte load stalled on store forwarding,
// a sixth of attr_plane_setup's samples; docs/speed.md "Session 10: per triangle").
AttrTerms64 attr_edge_terms64_int(const Config& cfg, const SetupTriangle& tri, const TriSetup& t, AttrEdgeTerms& out,
                                  int64_t* area2);
}  // namespace

AttrTerms64 attr_edge_terms64(const Config& cfg, const SetupTriangle& tri, const TriSetup& t, AttrEdgeTerms& out,
                              i128* area2) {
  int64_t a = 0;
  const AttrTerms64 r = attr_edge_terms64_int(cfg, tri, t, out, &a);
  if (r == AttrTerms64::Done) *area2 = a;
  return r;
}

namespace {
AttrTerms64 attr_edge_terms64_int(const Config& cfg, const SetupTriangle& tri, const TriSetup& t, AttrEdgeTerms& out,
                                  int64_t* area2) {
  const RasterConfig& rc = cfg.raster;
  if (attr_position_bits(rc) > kInt64ShiftMax) return AttrTerms64::Wide;  // check_attr_widths refuses it
  const int A = rc.attr_subpixel_bits;
  // attr_setup's M. No overflow: positions and i·2^A (|i| ≤ 2^(window_int_bits − 1)) are below
  // 2^(attr_position_bits − 1) ≤ 2^61, so every difference is below 2^62.
  const int64_t ox = tri.v[0].ax, oy = tri.v[0].ay;
  uint64_t M = (uint64_t)1 << A;
  const auto grow = [&M](int64_t d) { M = std::max(M, d < 0 ? (uint64_t)0 - (uint64_t)d : (uint64_t)d); };
  for (int k = 1; k < 3; ++k) grow(tri.v[k].ax - ox), grow(tri.v[k].ay - oy);
  const int64_t unitA = (int64_t)1 << A, halfA = (int64_t)1 << (A - 1);
  grow((int64_t)t.x0 * unitA + halfA - ox), grow((int64_t)t.x1 * unitA + halfA - ox);
  grow((int64_t)t.y0 * unitA + halfA - oy), grow((int64_t)t.y1 * unitA + halfA - oy);
  const int need = msb_index((u128)M) + 3;
  const int drop = std::max(0, need - rc.attr_coord_bits);
  const int F = A - drop;
  const auto rne = [drop](int64_t v) {
    return drop == 0 ? v : detail::shift_round_right<int64_t, uint64_t>(v, drop, Round::HalfEven);
  };
  int64_t x[3], y[3];
  const int64_t X0v = rne(tri.v[0].ax), Y0v = rne(tri.v[0].ay);
  x[0] = y[0] = 0;
  for (int k = 1; k < 3; ++k) x[k] = rne(tri.v[k].ax) - X0v, y[k] = rne(tri.v[k].ay) - Y0v;
  // Edge k from v_{k+1} to v_{k+2}; the cross products may leave int64.
  int64_t a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    a[k] = y[i] - y[j];  // |relative| < 2^(attr_coord_bits − 2) + 1: no overflow
    b[k] = x[j] - x[i];
    int64_t p, q;
    if (__builtin_mul_overflow(x[i], y[j], &p) || __builtin_mul_overflow(x[j], y[i], &q) ||
        __builtin_sub_overflow(p, q, &c[k]))
      return AttrTerms64::Wide;
  }
  if (c[0] == 0) return AttrTerms64::ZeroArea;
  // The clockwise triangle negated by a mask (x ^ m) − m, m = −1 when c[0] < 0: a branch on the
  // winding was mispredicted (docs/speed.md "Session 13: per vertex and per triangle"). Only
  // c = −2^63 has no int64 negation (|a|, |b| are small): Wide, as the overflow check answered.
  const int64_t m = c[0] >> 63;
  if (m != 0 && (c[0] == INT64_MIN || c[1] == INT64_MIN || c[2] == INT64_MIN)) return AttrTerms64::Wide;
  for (int k = 0; k < 3; ++k) {
    a[k] = (a[k] ^ m) - m, b[k] = (b[k] ^ m) - m;
    c[k] = (int64_t)(((uint64_t)c[k] ^ (uint64_t)m) - (uint64_t)m);
  }
  // attr_edge_terms at the anchor (t.x0, t.y0): X0 = i0·2^F + 2^(F−1) − ox at F bits (< 2^62).
  const int64_t unit = (int64_t)1 << F, h = (int64_t)1 << (F - 1);
  const int64_t XA = (int64_t)t.x0 * unit + h - X0v, YA = (int64_t)t.y0 * unit + h - Y0v;
  for (int k = 0; k < 3; ++k) {
    int64_t ax, by, e;
    if (__builtin_mul_overflow(a[k], unit, &out.dx64[k]) || __builtin_mul_overflow(b[k], unit, &out.dy64[k]) ||
        __builtin_mul_overflow(a[k], XA, &ax) || __builtin_mul_overflow(b[k], YA, &by) ||
        __builtin_add_overflow(ax, by, &e) || __builtin_add_overflow(e, c[k], &out.e064[k]))
      return AttrTerms64::Wide;
    out.dx[k] = out.dx64[k], out.dy[k] = out.dy64[k], out.e0[k] = out.e064[k];
  }
  out.fits64 = true;
  out.i0 = t.x0;
  out.j0 = t.y0;
  *area2 = c[0];
  return AttrTerms64::Done;
}
}  // namespace

void attr_plane_to(const AttrEdgeTerms& t, const int64_t q[3], Plane& out) {
  // Summed in locals and stored once (a Plane returned through the stack, written as 8-byte
  // words and read back by 16-byte loads, stalled on store forwarding: nearly half of
  // build_interp_planes' samples, docs/speed.md "Session 12: per triangle").
  i128 c = 0, dx = 0, dy = 0;
  if (t.fits64) {
    for (int k = 0; k < 3; ++k) {  // int64 × int64: GCC's one widening imul
      dx += (i128)t.dx64[k] * q[k];
      dy += (i128)t.dy64[k] * q[k];
      c += (i128)t.e064[k] * q[k];
    }
  } else {
    for (int k = 0; k < 3; ++k) {
      dx += t.dx[k] * q[k];
      dy += t.dy[k] * q[k];
      c += t.e0[k] * q[k];
    }
  }
  out.c = c;
  out.dx = dx;
  out.dy = dy;
  out.i0 = t.i0;
  out.j0 = t.j0;
}

Plane attr_plane(const AttrEdgeTerms& t, const int64_t q[3]) {
  Plane p;
  attr_plane_to(t, q, p);
  return p;
}

namespace {
// The depth plane written into `d` (attr_plane_setup: into the triangle's record; a DepthSetup
// returned and copied stalled on store forwarding, docs/speed.md "Session 12: per triangle").
void attr_depth_setup_terms(const Config& cfg, const SetupTriangle& tri, i128 area2, const AttrEdgeTerms& t,
                            DepthSetup& d) {
  // Vertex values z_k·(2^db − 1) kept to the absolute precision of z_k itself: z_frac_bits − db
  // fraction bits of an LSB (PRECISION IS LOST HERE: ≤ 2^−(z_frac_bits − db + 1) LSB, RNE, the
  // same as the rounding of z_k; 2^−9 LSB at D24). z_frac_bits + 1 signed bits.
  const RasterConfig& rc = cfg.raster;
  int64_t q[3];
  for (int k = 0; k < 3; ++k) q[k] = attr_depth_q(rc, tri.v[k].z);
  attr_plane_to(t, q, d.z);
  d.den = area2 << (rc.z_frac_bits - rc.depth_bits());
  d.max_code = (int64_t)depth_max_code(rc);
}
void attr_interp_setup_terms(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const AttrEdgeTerms& t,
                             InterpSetup& out) {
  build_interp_planes(cfg, st, tri, out, [&](const int64_t q[3], Plane& p) { attr_plane_to(t, q, p); });
}
}  // namespace

DepthSetup attr_depth_setup(const Config& cfg, const SetupTriangle& tri, const AttrSetup& a) {
  DepthSetup d;
  attr_depth_setup_terms(cfg, tri, a.area2, attr_edge_terms(a), d);
  return d;
}

bool attr_plane_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, bool varyings,
                      TriangleEquations& eq) {
  // The edge terms once for every plane of the triangle: in 64-bit words where they fit.
  AttrEdgeTerms t{AttrEdgeTerms::Unset{}};  // Done writes every member; Wide assigns t whole
  i128 area2 = 0;
  int64_t area64 = 0;
  switch (attr_edge_terms64_int(cfg, tri, eq.edges, t, &area64)) {
    case AttrTerms64::Done: area2 = area64; break;
    case AttrTerms64::ZeroArea: return false;
    case AttrTerms64::Wide: {
      const AttrSetup a = attr_setup(cfg, tri, eq.edges);
      if (!a.ok) return false;
      t = attr_edge_terms(a);
      area2 = a.area2;
      break;
    }
  }
  attr_depth_setup_terms(cfg, tri, area2, t, eq.depth);
  if (varyings) attr_interp_setup_terms(cfg, st, tri, t, eq.interp);
  else eq.interp.n = 0;
  return true;
}

void attr_interp_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const AttrSetup& a,
                       InterpSetup& out) {
  attr_interp_setup_terms(cfg, st, tri, attr_edge_terms(a), out);
}

}  // namespace fxr
