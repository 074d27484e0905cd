// Stage 2: the clipper. See model/stages/clip.hpp for the contracts and docs/pipeline.md (stage 2) for
// the derivations. Integer arithmetic only.
#include "model/stages/clip.hpp"

#include <algorithm>
#include <cstdlib>

namespace fxr {

const char* to_string(ClipPlane p) {
  switch (p) {
    case kPlaneWMin: return "w_min";
    case kPlaneNear: return "near";
    case kPlaneFar: return "far";
    case kPlaneLeft: return "left";
    case kPlaneRight: return "right";
    case kPlaneBottom: return "bottom";
    case kPlaneTop: return "top";
    default: return "?";
  }
}

GuardBand guard_band(const RasterConfig& rc, const DrawState& st) {
  GuardBand g;
  const int64_t lim = guard_limit_px(rc);
  const int64_t x0 = st.viewport_x, y0 = st.viewport_y, w = st.viewport_w, h = st.viewport_h;
  if (w < 1 || h < 1) return g;
  if (x0 < -lim || y0 < -lim || x0 + w > lim || y0 + h > lim) return g;
  g.valid = true;
  g.w = w;
  g.h = h;
  // x_n = (2(x_w − X0) − W)/W at x_w = ∓L. |n| ≤ 4L + W < 2^(window_int_bits+2): fits easily.
  g.n_left = 2 * (-lim - x0) - w;
  g.n_right = 2 * (lim - x0) - w;
  g.n_bottom = 2 * (-lim - y0) - h;
  g.n_top = 2 * (lim - y0) - h;
  return g;
}

PlaneEq plane_eq(const GuardBand& gb, ClipPlane p) {
  PlaneEq e;
  switch (p) {
    case kPlaneWMin: e.b = 1; e.wmin = true; break;                      // w − 2^kWMinExp
    case kPlaneNear: e.comp = 2; e.a = 1; break;                         // z
    case kPlaneFar: e.comp = 2; e.a = -1; e.b = 1; break;                // w − z
    case kPlaneLeft: e.comp = 0; e.a = gb.w; e.b = -gb.n_left; break;   // W·x − n_left·w
    case kPlaneRight: e.comp = 0; e.a = -gb.w; e.b = gb.n_right; break; // n_right·w − W·x
    case kPlaneBottom: e.comp = 1; e.a = gb.h; e.b = -gb.n_bottom; break;
    case kPlaneTop: e.comp = 1; e.a = -gb.h; e.b = gb.n_top; break;
    default: break;
  }
  return e;
}

namespace {

// A signed term k·sig·2^exp with |k·sig| < 2^127.
struct Term {
  bool neg = false;
  u128 mag = 0;
  int exp = 0;
  int lead() const { return exp + msb_index(mag); }
};

Term term(int64_t k, const FxFloat& f) {
  Term t;
  if (k == 0 || f.sig == 0) return t;
  t.neg = (k < 0) != f.neg;
  t.mag = (u128)(k < 0 ? -(u128)k : (u128)k) * f.sig;  // |k| < 2^23, sig < 2^64: < 2^87
  t.exp = f.exp;
  return t;
}

int sign_of(const Term& t) { return t.mag == 0 ? 0 : (t.neg ? -1 : 1); }

// Exact sign of t1 + t2. If the leading ones differ the larger term decides; otherwise both
// align within 88 bits of the common leading one, so the i128 sum is exact.
int sign_of_sum(const Term& t1, const Term& t2) {
  if (t1.mag == 0) return sign_of(t2);
  if (t2.mag == 0) return sign_of(t1);
  const int l1 = t1.lead(), l2 = t2.lead();
  if (l1 != l2) return l1 > l2 ? sign_of(t1) : sign_of(t2);
  const int e = std::min(t1.exp, t2.exp);
  const i128 a = (i128)(t1.mag << (t1.exp - e)), b = (i128)(t2.mag << (t2.exp - e));
  const i128 s = (t1.neg ? -a : a) + (t2.neg ? -b : b);
  return s > 0 ? 1 : (s < 0 ? -1 : 0);
}

// The same sign in 64-bit words (docs/speed.md "Trivial accept in 64 bits"): |k|·sig computed
// with an overflow check; when both products are below 2^62 the leading ones are compared from
// 64-bit leading-zero counts and, when they coincide, the aligned magnitudes (shift ≤ 61, so
// each stays below 2^62) are summed in int64. Returns 2 when a product is too wide (the caller
// then takes the u128 path). Equal to sign_of_sum(term(ka, a), term(kb, b))
// (Clip.PlaneSide64EqualsTheU128Path in tests/model/clip_test.cpp).
int sign_of_sum64(int64_t ka, const FxFloat& a, int64_t kb, const FxFloat& b) {
  uint64_t ma = 0, mb = 0;
  const uint64_t lim = uint64_t{1} << 62;
  if (ka != 0 && a.sig != 0 &&
      (__builtin_mul_overflow(ka < 0 ? (uint64_t)0 - (uint64_t)ka : (uint64_t)ka, a.sig, &ma) || ma >= lim))
    return 2;
  if (kb != 0 && b.sig != 0 &&
      (__builtin_mul_overflow(kb < 0 ? (uint64_t)0 - (uint64_t)kb : (uint64_t)kb, b.sig, &mb) || mb >= lim))
    return 2;
  const bool na = (ka < 0) != a.neg, nb = (kb < 0) != b.neg;
  if (ma == 0) return mb == 0 ? 0 : (nb ? -1 : 1);
  if (mb == 0) return na ? -1 : 1;
  const int la = a.exp + 63 - __builtin_clzll(ma), lb = b.exp + 63 - __builtin_clzll(mb);
  if (la != lb) return la > lb ? (na ? -1 : 1) : (nb ? -1 : 1);
  const int e = std::min(a.exp, b.exp);
  const int64_t x = (int64_t)(ma << (a.exp - e)), y = (int64_t)(mb << (b.exp - e));  // < 2^62
  const int64_t sum = (na ? -x : x) + (nb ? -y : y);
  return sum > 0 ? 1 : (sum < 0 ? -1 : 0);
}

}  // namespace

int plane_side(const PlaneEq& pl, const ClipVtx& v) {
  const FxFloat& w = v.p[3];
  if (pl.wmin) {  // sign of w − 2^kWMinExp
    if (w.sig == 0 || w.neg) return -1;
    const int l = w.lead_exp();
    if (l != kWMinExp) return l > kWMinExp ? 1 : -1;
    return (w.sig & (w.sig - 1)) == 0 ? 0 : 1;  // w = 2^kWMinExp exactly iff sig is a power of 2
  }
  static const FxFloat kZero{};
  const int s64 = sign_of_sum64(pl.comp >= 0 ? pl.a : 0, pl.comp >= 0 ? v.p[pl.comp] : kZero, pl.b, w);
  if (s64 != 2) return s64;
  return plane_side_u128(pl, v);
}

int plane_side_u128(const PlaneEq& pl, const ClipVtx& v) {
  const Term ta = pl.comp >= 0 ? term(pl.a, v.p[pl.comp]) : Term{};
  return sign_of_sum(ta, term(pl.b, v.p[3]));
}

uint32_t outcode(const GuardBand& gb, const ClipVtx& v) {
  uint32_t oc = 0;
  // Unrolled: each plane's equation a constant pattern, not plane_eq's jump table per plane
  // (docs/speed.md "Session 10: per triangle").
#pragma GCC unroll 8
  for (int p = 0; p < kNumClipPlanes; ++p)
    if (plane_side(plane_eq(gb, (ClipPlane)p), v) < 0) oc |= 1u << p;
  return oc;
}

ClipWidths clip_widths(const Config& cfg, int num_varyings) {
  ClipWidths cw;
  cw.pos_sig_bits = cfg.raster.clip_sig_bits;
  cw.w_sig_bits = cfg.recip.in_sig_bits;
  cw.num_varyings = num_varyings;
  cw.rtl_record_sig_bits = clip_vertex_sig_bits(cfg);
  cw.rtl_with_wa = clip_vertex_has_wa(cfg);
  return cw;
}

// ---- exact multi-word arithmetic for the intersections ----------------------------------------
//
// Bound: every clipper operand has its leading one in [2^kClipFlushLeadExp, 2^129) and a
// significand of ≤ 64 bits, so its lowest bit is ≥ 2^(kClipFlushLeadExp − 63) = 2^−255. Plane
// distances (× |a|, |b| < 2^23) span ≤ 129 + 255 + 23 + 1 = 408 bits; the numerators
// c_e·d_s − c_s·d_e span ≤ 2·(129 + 255) + 23 + 2 ≈ 793 bits, the shifted operands of the
// division ≤ 793 + 64 + 3. kBigLimbs · 64 = 1024 bits covers it; an excess sets `overflow`.
namespace {

constexpr int kBigLimbs = 16;
constexpr int kLimbBits = 64;

struct BigU {
  uint64_t l[kBigLimbs] = {};
  int n = 0;  // limbs in use (l[n−1] ≠ 0), 0 for zero
  void trim() {
    while (n > 0 && l[n - 1] == 0) --n;
  }
};

BigU big_from(u128 x) {
  BigU b;
  b.l[0] = (uint64_t)x;
  b.l[1] = (uint64_t)(x >> kLimbBits);
  b.n = 2;
  b.trim();
  return b;
}

int big_msb(const BigU& a) {
  return a.n == 0 ? -1 : (a.n - 1) * kLimbBits + msb_index(a.l[a.n - 1]);
}

int big_cmp(const BigU& a, const BigU& b) {
  if (a.n != b.n) return a.n > b.n ? 1 : -1;
  for (int i = a.n - 1; i >= 0; --i)
    if (a.l[i] != b.l[i]) return a.l[i] > b.l[i] ? 1 : -1;
  return 0;
}

BigU big_shl(const BigU& a, int s, bool* of) {
  if (a.n == 0 || s == 0) return a;
  if (big_msb(a) + s >= kBigLimbs * kLimbBits) {
    *of = true;
    return BigU{};
  }
  BigU r;
  const int w = s / kLimbBits, b = s % kLimbBits;
  for (int i = a.n - 1; i >= 0; --i) {
    r.l[i + w] |= b ? (a.l[i] << b) : a.l[i];
    if (b && i + w + 1 < kBigLimbs) r.l[i + w + 1] |= a.l[i] >> (kLimbBits - b);
  }
  r.n = std::min(kBigLimbs, a.n + w + 1);
  r.trim();
  return r;
}

// Number of trailing zero bits (a ≠ 0).
int big_ctz(const BigU& a) {
  int i = 0;
  while (a.l[i] == 0) ++i;
  return i * kLimbBits + __builtin_ctzll(a.l[i]);
}

// a >> s, dropping the low bits (callers shift out zeros only).
BigU big_shr(const BigU& a, int s) {
  BigU r;
  const int w = s / kLimbBits, b = s % kLimbBits;
  for (int i = w; i < a.n; ++i) {
    r.l[i - w] = b ? (a.l[i] >> b) : a.l[i];
    if (b && i + 1 < a.n) r.l[i - w] |= a.l[i + 1] << (kLimbBits - b);
  }
  r.n = std::max(0, a.n - w);
  r.trim();
  return r;
}

u128 big_to_u128(const BigU& a) { return ((u128)a.l[1] << kLimbBits) | a.l[0]; }

void big_shr1(BigU& a) {
  for (int i = 0; i < a.n; ++i) a.l[i] = (a.l[i] >> 1) | (i + 1 < a.n ? a.l[i + 1] << (kLimbBits - 1) : 0);
  a.trim();
}

BigU big_add(const BigU& a, const BigU& b, bool* of) {
  BigU r;
  const int n = std::max(a.n, b.n);
  u128 carry = 0;
  for (int i = 0; i < n; ++i) {
    carry += (u128)a.l[i] + b.l[i];
    r.l[i] = (uint64_t)carry;
    carry >>= kLimbBits;
  }
  r.n = n;
  if (carry) {
    if (n == kBigLimbs) *of = true;
    else r.l[r.n++] = 1;
  }
  r.trim();
  return r;
}

// a − b, requires a ≥ b.
BigU big_sub(const BigU& a, const BigU& b) {
  BigU r;
  uint64_t borrow = 0;
  for (int i = 0; i < a.n; ++i) {
    const u128 sub = (u128)b.l[i] + borrow;
    r.l[i] = a.l[i] - (uint64_t)sub;
    borrow = (u128)a.l[i] < sub ? 1 : 0;
  }
  r.n = a.n;
  r.trim();
  return r;
}

BigU big_mul(const BigU& a, const BigU& b, bool* of) {
  BigU r;
  if (a.n == 0 || b.n == 0) return r;
  if (a.n + b.n > kBigLimbs + 1 || big_msb(a) + big_msb(b) + 2 > kBigLimbs * kLimbBits) {
    *of = true;
    return r;
  }
  for (int i = 0; i < a.n; ++i) {
    u128 carry = 0;
    for (int j = 0; j < b.n && i + j < kBigLimbs; ++j) {
      carry += (u128)a.l[i] * b.l[j] + r.l[i + j];
      r.l[i + j] = (uint64_t)carry;
      carry >>= kLimbBits;
    }
    if (i + b.n < kBigLimbs) r.l[i + b.n] = (uint64_t)carry;
  }
  r.n = std::min(kBigLimbs, a.n + b.n);
  r.trim();
  return r;
}

// Signed dyadic ±m·2^e.
struct Dy {
  bool neg = false;
  BigU m;
  int e = 0;
};

Dy dy_from(const FxFloat& f) {
  Dy d;
  d.neg = f.neg;
  d.m = big_from(f.sig);
  d.e = f.exp;
  return d;
}

Dy dy_int(int64_t k) {
  Dy d;
  d.neg = k < 0;
  d.m = big_from(k < 0 ? -(u128)k : (u128)k);
  return d;
}

Dy dy_mul(const Dy& a, const Dy& b, bool* of) {
  Dy r;
  r.m = big_mul(a.m, b.m, of);
  r.neg = a.neg != b.neg;
  r.e = a.e + b.e;
  return r;
}

// Exact a + b: both aligned to the lower exponent (a left shift, no bits dropped).
Dy dy_add(const Dy& a, const Dy& b, bool* of) {
  if (a.m.n == 0) return b;
  if (b.m.n == 0) return a;
  const int e = std::min(a.e, b.e);
  const BigU am = big_shl(a.m, a.e - e, of), bm = big_shl(b.m, b.e - e, of);
  Dy r;
  r.e = e;
  if (a.neg == b.neg) {
    r.neg = a.neg;
    r.m = big_add(am, bm, of);
  } else if (big_cmp(am, bm) >= 0) {
    r.neg = a.neg;
    r.m = big_sub(am, bm);
  } else {
    r.neg = b.neg;
    r.m = big_sub(bm, am);
  }
  return r;
}

Dy dy_neg(Dy a) {
  a.neg = !a.neg;
  return a;
}

// Exact plane distance d = a·p[comp] + b·w − (wmin ? 2^kWMinExp : 0).
Dy plane_distance(const PlaneEq& pl, const ClipVtx& v, bool* of) {
  Dy d = dy_mul(dy_int(pl.b), dy_from(v.p[3]), of);
  if (pl.comp >= 0) d = dy_add(d, dy_mul(dy_int(pl.a), dy_from(v.p[pl.comp]), of), of);
  if (pl.wmin) {
    Dy c;
    c.neg = true;
    c.m = big_from(1);
    c.e = kWMinExp;
    d = dy_add(d, c, of);
  }
  return d;
}

// Contract: RNE(p / q) as a normalised FxFloat of `bits` (≤ 62) significand bits; q > 0.
// An exact zero is +0. Quotient of bits + 2 or bits + 3 bits by restoring division, then a sticky bit from the
// remainder: one correct rounding. Results with leading one below 2^kClipFlushLeadExp → ±0.
FxFloat div_round(const Dy& p, const Dy& q, int bits, bool* of) {
  FxFloat r;
  if (p.m.n == 0) return r;  // exact zero: +0 whatever the edge direction
  r.neg = p.neg;
  const int mp = big_msb(p.m), mq = big_msb(q.m);
  // Scale so that quotient = a / b ∈ [2^(bits+1), 2^(bits+3)).
  const int k = bits + 2 - (mp - mq);
  BigU a = k > 0 ? big_shl(p.m, k, of) : p.m;
  BigU b = k < 0 ? big_shl(q.m, -k, of) : q.m;
  // Common trailing zeros change neither the quotient nor whether the remainder is zero.
  const int tz = std::min(big_ctz(a), big_ctz(b));
  a = big_shr(a, tz);
  b = big_shr(b, tz);
  u128 quo = 0;
  bool sticky;
  if (a.n <= 2 && b.n <= 2) {  // fast path: both fit 128 bits
    const u128 a2 = big_to_u128(a), b2 = big_to_u128(b);
    quo = a2 / b2;
    sticky = a2 % b2 != 0;
  } else {  // restoring division, one quotient bit per step
    const int qbits = bits + 3;
    b = big_shl(b, qbits - 1, of);
    for (int i = qbits - 1; i >= 0; --i) {
      if (big_cmp(a, b) >= 0) {
        a = big_sub(a, b);
        quo |= ((u128)1) << i;
      }
      big_shr1(b);
    }
    sticky = a.n != 0;
  }
  // value = (quo + rem/b)·2^(p.e − q.e − k); (quo << 1 | sticky) keeps a sticky bit below the
  // guard bits, so rounding it to `bits` is the correct RNE of the exact quotient.
  const Normalized nm = normalize((quo << 1) | (sticky ? 1 : 0), bits, Round::HalfEven);
  const int exp = p.e - q.e - k - 1 + nm.exp - (bits - 1);  // precision lost: ≤ ½ ulp (RNE)
  if (exp + bits - 1 < kClipFlushLeadExp) return r;       // flush to ±0 (documented)
  r.sig = nm.sig;
  r.exp = exp;
  return r;
}

}  // namespace

ClipVtx clip_intersect(const ClipWidths& cw, const PlaneEq& pl, const ClipVtx& s, const ClipVtx& e,
                       bool* overflow, int64_t* rtl_cycles) {
  bool of = false;
  Dy ds = plane_distance(pl, s, &of), de = plane_distance(pl, e, &of);
  // q = d_s − d_e ≠ 0 (strictly opposite signs); make it positive by negating both distances
  // (value unchanged): c = (c_e·d_s − c_s·d_e)/(d_s − d_e).
  Dy q = dy_add(ds, dy_neg(de), &of);
  if (q.neg) {
    ds = dy_neg(ds);
    de = dy_neg(de);
    q.neg = false;
  }
  auto component = [&](const FxFloat& cs, const FxFloat& ce, int bits) {
    const Dy num = dy_add(dy_mul(dy_from(ce), ds, &of), dy_neg(dy_mul(dy_from(cs), de, &of)), &of);
    if (rtl_cycles) {
      // rtl/fxr_clip.sv: set-up, the shift-and-add over the record's significand plus the
      // exponent distance (a zero takes the other value's exponent), normalise, the restoring
      // division (skipped for an exact zero), round.
      const int xs = cs.sig ? cs.exp : ce.exp, xe = ce.sig ? ce.exp : xs;
      *rtl_cycles += 1 + cw.rtl_record_sig_bits + std::abs(xs - xe) + 1 + (num.m.n == 0 ? 0 : bits + 3) + 1;
    }
    return div_round(num, q, bits, &of);
  };
  ClipVtx r;
  for (int c = 0; c < 3; ++c) r.p[c] = component(s.p[c], e.p[c], cw.pos_sig_bits);
  r.p[3] = component(s.p[3], e.p[3], cw.w_sig_bits);
  // The attribute path's w: the same exact intersection of the endpoints' attribute w, rounded
  // to the position width (where p[3] is rounded to the reciprocal unit's input width).
  if (rtl_cycles) *rtl_cycles += kClipRtlDistClocks;
  {
    int64_t* const all = rtl_cycles;  // the RTL makes the attribute w only when the record has it
    if (!cw.rtl_with_wa) rtl_cycles = nullptr;
    r.wa = component(s.attr_w(), e.attr_w(), cw.pos_sig_bits);
    rtl_cycles = all;
  }
  for (int k = 0; k < cw.num_varyings; ++k) r.v[k] = component(s.v[k], e.v[k], cw.pos_sig_bits);
  if (of) *overflow = true;
  return r;
}

ClipPolygon clip_triangle(const GuardBand& gb, const ClipWidths& cw, const ClipVtx in[3]) {
  ClipPolygon poly;
  poly.rtl_cycles = 1;  // the input transfer
  poly.n = 3;
  for (int i = 0; i < 3; ++i) poly.v[i] = in[i];
  ClipVtx next[kClipMaxPolyVerts];
  int side[kClipMaxPolyVerts];
  for (int p = 0; p < kNumClipPlanes && poly.n > 0; ++p) {
    const PlaneEq pl = plane_eq(gb, (ClipPlane)p);
    bool any_out = false;
    for (int i = 0; i < poly.n; ++i) {
      side[i] = plane_side(pl, poly.v[i]);
      any_out |= side[i] < 0;
    }
    poly.rtl_cycles += poly.n + 1;  // one side per clock, one to decide
    if (!any_out) continue;  // no edge crosses: the pass would return its input
    int m = 0;
    poly.rtl_cycles += 1;  // the end of the pass
    for (int i = 0; i < poly.n; ++i) {
      const int j = (i + 1) % poly.n;  // edge v[i] → v[j]
      poly.rtl_cycles += 1;  // one clock per edge (copy)
      if (m + 2 > kClipMaxPolyVerts) {  // cannot happen for a convex polygon (m ≤ n + 1)
        poly.overflow = true;
        break;
      }
      if (side[i] >= 0) next[m++] = poly.v[i];
      if ((side[i] > 0 && side[j] < 0) || (side[i] < 0 && side[j] > 0)) {
        next[m++] = clip_intersect(cw, pl, poly.v[i], poly.v[j], &poly.overflow, &poly.rtl_cycles);
        ++poly.created;
      }
    }
    poly.n = m < 3 ? 0 : m;
    for (int i = 0; i < poly.n; ++i) poly.v[i] = next[i];
  }
  // The fan, one triangle per clock; nothing to emit (clipped away, overflow): one clock.
  poly.rtl_cycles += (!poly.overflow && poly.n >= 3) ? poly.n - 2 : 1;
  return poly;
}

StageCost ClipStage::cost(const Config& cfg) {
  const int sb = clip_vertex_sig_bits(cfg);
  const int coef = cfg.raster.window_int_bits + 2;  // guard-band plane coefficients n_left … n_top
  StageCost c;
  // Outcodes: per vertex and guard-band plane a·p + b·w (2 products); one intersection unit:
  // 2 products per component (c_e·d_s, c_s·d_e) and a divider, iterated over the components.
  for (int v = 0; v < 3; ++v)
    for (int p = 0; p < 4; ++p) c.add_mult(sb, coef), c.add_mult(sb, coef);
  c.add_mult(sb, 2 * sb + coef);
  c.add_mult(sb, 2 * sb + coef);
  c.latency = 1;  // rtl/fxr_clip.sv: trivially accepted triangles leave from the output register
  c.ii = 1;       // one per clock; a clipped triangle occupies the stage ClipStage::rtl_cycles()
  c.adder_bits = 3 * (int64_t)kNumClipPlanes * (sb + coef);
  c.ff_bits = record_bits<ClippedTriangle>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr
