// Independent reference for the geometry stages (1–4), in GMP rationals.
//
// Input values come from the float32 through mpq_set_d (exact, not through decode_f32). The
// clipper is re-implemented from its specification (docs/pipeline.md, stage 2): the same plane
// order and inside rules, each new component the rational (c_e·d_s − c_s·d_e)/(d_s − d_e)
// rounded to nearest even at the documented width; snapping is the RNE of the exact rational
// window coordinate. The reciprocal unit (a separate unit with its own tests) is the one call
// shared with the model: its output r is an input of stage 3.
#pragma once

#include <gmpxx.h>

#include <vector>

#include "model/stages/clip.hpp"
#include "model/unit/geometry.hpp"
#include "model/stages/recip.hpp"

namespace georef {

using namespace fxr;

// A draw state with the given viewport and varying count (test helper).
inline DrawState state(int w, int h, int x0 = 0, int y0 = 0, int nv = 0) {
  DrawState st;
  st.viewport_x = x0;
  st.viewport_y = y0;
  st.viewport_w = w;
  st.viewport_h = h;
  st.num_varyings = nv;
  return st;
}

inline mpq_class q_of(const FxFloat& f) {
  mpz_class s;
  mpz_import(s.get_mpz_t(), 1, 1, sizeof f.sig, 0, 0, &f.sig);
  mpq_class v(s);
  if (f.exp >= 0) v *= mpq_class(mpz_class(1) << f.exp);
  else v /= mpq_class(mpz_class(1) << -f.exp);
  return f.neg ? mpq_class(-v) : v;
}

// a / b as a canonical rational.
inline mpq_class frac(long a, long b) {
  mpq_class q{mpz_class(a), mpz_class(b)};
  q.canonicalize();
  return q;
}

inline mpq_class pow2(int e) {
  return e >= 0 ? mpq_class(mpz_class(1) << e) : mpq_class(mpz_class(1), mpz_class(1) << -e);
}

// Round to nearest integer, ties to even.
inline mpz_class rne_int(const mpq_class& x) {
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  const mpq_class frac = x - fl;
  const int c = cmp(frac, mpq_class(1, 2));
  if (c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t()))) fl += 1;
  return fl;
}

// RNE of x to a normalised `bits`-bit significand; returns the exact rational of the result.
inline mpq_class rne_sig(const mpq_class& x, int bits) {
  if (x == 0) return x;
  mpq_class a = abs(x);
  // e with 2^(bits−1) ≤ a / 2^e < 2^bits
  int e = (int)mpz_sizeinbase(a.get_num_mpz_t(), 2) - (int)mpz_sizeinbase(a.get_den_mpz_t(), 2) - bits;
  while (a / pow2(e) >= pow2(bits)) ++e;
  while (a / pow2(e) < pow2(bits - 1)) --e;
  const mpq_class r = mpq_class(rne_int(a / pow2(e))) * pow2(e);
  return x < 0 ? mpq_class(-r) : r;
}

inline mpq_class q_of_float(float f) { return mpq_class((double)f); }  // exact

struct RVtx {
  mpq_class p[4];
  mpq_class v[kMaxVaryings];
  // The attribute w (docs/pipeline.md, stage 2): a new vertex's w rounded to clip_sig_bits;
  // an input vertex's is its w.
  bool has_wa = false;
  mpq_class wa;
  const mpq_class& attr_w() const { return has_wa ? wa : p[3]; }
};

// A new vertex's attribute w: the intersection of the endpoints' attribute w at parameter t.
inline void ref_set_attr_w(RVtx& r, const RVtx& a, const RVtx& b, const mpq_class& t, const Config& cfg);

// Guard band from its definition: window x = ±L with L = 2^(window_int_bits−1) − 1 px.
struct RBand {
  bool valid = false;
  mpq_class xlo, xhi, ylo, yhi;  // NDC extents
};
inline RBand ref_band(const RasterConfig& rc, const DrawState& st) {
  RBand b;
  const long L = (1L << (rc.window_int_bits - 1)) - 1;
  if (st.viewport_w < 1 || st.viewport_h < 1) return b;
  if (st.viewport_x < -L || st.viewport_y < -L || st.viewport_x + st.viewport_w > L ||
      st.viewport_y + st.viewport_h > L)
    return b;
  b.valid = true;
  // x_w = (x_n + 1)·W/2 + X0  ⇒  x_n = (x_w − X0)·2/W − 1
  auto ndc = [](long xw, long x0, long w) -> mpq_class { return frac(2 * (xw - x0), w) - 1; };
  b.xlo = ndc(-L, st.viewport_x, st.viewport_w);
  b.xhi = ndc(L, st.viewport_x, st.viewport_w);
  b.ylo = ndc(-L, st.viewport_y, st.viewport_h);
  b.yhi = ndc(L, st.viewport_y, st.viewport_h);
  return b;
}

// Plane distance (any positive multiple of it gives the same signs and the same intersection).
inline mpq_class ref_dist(const RBand& b, int plane, const RVtx& v) {
  const mpq_class &x = v.p[0], &y = v.p[1], &z = v.p[2], &w = v.p[3];
  switch (plane) {
    case 0: return w - pow2(kWMinExp);
    case 1: return z;
    case 2: return w - z;
    case 3: return x - b.xlo * w;
    case 4: return b.xhi * w - x;
    case 5: return y - b.ylo * w;
    default: return b.yhi * w - y;
  }
}

inline mpq_class ref_round_clip(const mpq_class& x, int bits) {
  const mpq_class r = rne_sig(x, bits);
  if (r != 0 && abs(r) < pow2(kClipFlushLeadExp)) return mpq_class(0);
  return r;
}

inline void ref_set_attr_w(RVtx& r, const RVtx& a, const RVtx& b, const mpq_class& t, const Config& cfg) {
  r.has_wa = true;
  r.wa = ref_round_clip(a.attr_w() + t * (b.attr_w() - a.attr_w()), cfg.raster.clip_sig_bits);
}

// Sutherland–Hodgman on rationals, rounding new components as specified. Returns the polygon.
inline std::vector<RVtx> ref_clip(const RBand& b, const Config& cfg, int nv, std::vector<RVtx> poly,
                                  int* created) {
  for (int p = 0; p < 7 && !poly.empty(); ++p) {
    std::vector<mpq_class> d;
    bool out = false;
    for (auto& v : poly) {
      d.push_back(ref_dist(b, p, v));
      out |= sgn(d.back()) < 0;
    }
    if (!out) continue;
    std::vector<RVtx> next;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n;
      if (sgn(d[i]) >= 0) next.push_back(poly[i]);
      if (sgn(d[i]) * sgn(d[j]) < 0) {
        const mpq_class t = d[i] / (d[i] - d[j]);
        RVtx r;
        for (int c = 0; c < 4; ++c)
          r.p[c] = ref_round_clip(poly[i].p[c] + t * (poly[j].p[c] - poly[i].p[c]),
                                  c == 3 ? cfg.recip.in_sig_bits : cfg.raster.clip_sig_bits);
        for (int k = 0; k < nv; ++k)
          r.v[k] = ref_round_clip(poly[i].v[k] + t * (poly[j].v[k] - poly[i].v[k]), cfg.raster.clip_sig_bits);
        ref_set_attr_w(r, poly[i], poly[j], t, cfg);
        next.push_back(r);
        ++*created;
      }
    }
    poly = next.size() < 3 ? std::vector<RVtx>{} : next;
  }
  return poly;
}

// FxFloat of an exact dyadic rational (for feeding the reciprocal unit).
inline FxFloat fx_of_q(const mpq_class& x) {
  FxFloat f;
  if (x == 0) return f;
  mpq_class a = abs(x);
  int e = 0;
  while (a.get_den() != 1) {
    a *= 2;
    --e;
  }
  mpz_class n = a.get_num();
  while (mpz_even_p(n.get_mpz_t())) {
    n /= 2;
    ++e;
  }
  f.neg = x < 0;
  f.sig = 0;
  mpz_export(&f.sig, nullptr, -1, sizeof f.sig, 0, 0, n.get_mpz_t());
  f.exp = e;
  return f;
}

struct RSetup {
  mpz_class x, y, z;
  mpz_class ax, ay;  // attribute positions (= x, y when the planes use the snapped ones)
  mpq_class rw;
  mpq_class vw[kMaxVaryings];
};

// Stage 3 + 4 reference for one vertex.
inline RSetup ref_project(const Config& cfg, const DrawState& st, const RVtx& v) {
  RSetup o;
  const RecipResult rr = recip(cfg.recip, fx_of_q(v.p[3]));
  const mpq_class r = q_of(rr.value);
  const int s = cfg.raster.subpixel_bits;
  auto win = [&](const mpq_class& c, long size, long org) -> mpz_class {
    return rne_int(((c * r + 1) * frac(size, 2) + org) * pow2(s));
  };
  o.x = win(v.p[0], st.viewport_w, st.viewport_x);
  o.y = win(v.p[1], st.viewport_h, st.viewport_y);
  mpz_class z = rne_int(v.p[2] * r * pow2(cfg.raster.z_frac_bits));
  const mpz_class one = mpz_class(1) << cfg.raster.z_frac_bits;
  o.z = z < 0 ? mpz_class(0) : (z > one ? one : z);
  o.rw = r;
  for (int k = 0; k < st.num_varyings; ++k)
    o.vw[k] = rne_sig(st.interp == InterpMode::Affine ? v.v[k] : mpq_class(v.v[k] * r),
                      cfg.raster.varying_sig_bits);
  o.ax = o.x;
  o.ay = o.y;
  const RasterConfig& rc = cfg.raster;
  if (rc.attr_subpixel_bits > rc.subpixel_bits) {
    // Attribute path (model/stages/attr.hpp): every per-vertex quotient exact, rounded once.
    const mpq_class w = v.attr_w();
    auto awin = [&](const mpq_class& c, long size, long org) -> mpz_class {
      return rne_int(((c / w + 1) * frac(size, 2) + org) * pow2(rc.attr_subpixel_bits));
    };
    o.ax = awin(v.p[0], st.viewport_w, st.viewport_x);
    o.ay = awin(v.p[1], st.viewport_h, st.viewport_y);
    mpz_class za = rne_int(v.p[2] / w * pow2(rc.z_frac_bits));
    o.z = za < 0 ? mpz_class(0) : (za > one ? one : za);
    o.rw = rne_sig(mpq_class(1 / w), rc.attr_sig_bits);
    for (int k = 0; k < st.num_varyings; ++k)
      o.vw[k] = rne_sig(st.interp == InterpMode::Affine ? v.v[k] : mpq_class(v.v[k] / w), rc.attr_sig_bits);
  }
  return o;
}

struct RResult {
  GeomOutcome outcome = GeomOutcome::Emitted;
  std::vector<RSetup> poly;  // fan (0, i, i+1)
  int created = 0;
};

inline bool is_nan_f(float f) { return f != f; }
inline bool is_inf_f(float f) { return f == f && (f - f) != (f - f); }

inline RResult ref_geometry(const Config& cfg, const DrawState& st, const ClipTriangle& tri) {
  RResult res;
  const int nv = st.num_varyings;
  bool nan = false, inf = false;
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) nan |= is_nan_f(tri.v[i].pos[c]), inf |= is_inf_f(tri.v[i].pos[c]);
  // Varyings: NaN → 0, ±Inf → ±(2^24 − 1)·2^104 (= ±FLT_MAX), docs/pipeline.md stage 1.
  const auto var_q = [](float f) -> mpq_class {
    if (is_nan_f(f)) return 0;
    if (is_inf_f(f)) return mpq_class(mpq_class(f < 0 ? -1 : 1) * mpq_class((mpz_class(1) << 24) - 1) * pow2(104));
    return q_of_float(f);
  };
  if (nan) return res.outcome = GeomOutcome::RejectedNaN, res;
  if (inf) return res.outcome = GeomOutcome::RejectedInf, res;
  const RBand b = ref_band(cfg.raster, st);
  if (!b.valid) return res.outcome = GeomOutcome::RejectedRange, res;
  std::vector<RVtx> poly(3);
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 4; ++c) poly[i].p[c] = q_of_float(tri.v[i].pos[c]);
    for (int k = 0; k < nv; ++k) poly[i].v[k] = var_q(tri.v[i].var[k]);
  }
  for (int p = 0; p < 7; ++p) {  // trivial reject
    bool all_out = true;
    for (auto& v : poly) all_out &= sgn(ref_dist(b, p, v)) < 0;
    if (all_out) return res.outcome = GeomOutcome::CulledOutside, res;
  }
  poly = ref_clip(b, cfg, nv, poly, &res.created);
  if (poly.empty()) return res.outcome = GeomOutcome::CulledOutside, res;
  const long lim = 1L << (cfg.raster.window_int_bits + cfg.raster.subpixel_bits - 1);
  for (auto& v : poly) {
    res.poly.push_back(ref_project(cfg, st, v));
    const RSetup& o = res.poly.back();
    if (o.x < -lim || o.x >= lim || o.y < -lim || o.y >= lim) return res.outcome = GeomOutcome::RejectedRange, res;
  }
  return res;
}

// Number of differing fields between a model setup vertex and the reference.
inline int diff_count(const SetupVertex& m, const RSetup& r, int nv) {
  int d = 0;
  d += mpz_class((long)m.x) != r.x;
  d += mpz_class((long)m.y) != r.y;
  d += mpz_class((long)m.ax) != r.ax;
  d += mpz_class((long)m.ay) != r.ay;
  d += mpz_class((unsigned long)m.z) != r.z;
  d += q_of(m.rw) != r.rw;
  for (int k = 0; k < nv; ++k) d += q_of(m.vw[k]) != r.vw[k];
  return d;
}

// Model vs reference for one triangle: 0 when the outcome and every emitted field agree.
inline int compare_with_reference(const Config& cfg, const DrawState& st, const ClipTriangle& tri,
                                  GeomOutcome* model_outcome = nullptr) {
  std::vector<SetupTriangle> out;
  RasterStats stats;
  const GeomOutcome o = geometry(cfg, st, tri, 7, out, stats);
  if (model_outcome) *model_outcome = o;
  const RResult r = ref_geometry(cfg, st, tri);
  if (o != r.outcome) return 1000;
  if (o != GeomOutcome::Emitted) return out.empty() ? 0 : 1000;
  const size_t n = r.poly.size();
  if (out.size() != n - 2) return 1000;
  int d = 0;
  for (size_t i = 1; i + 1 < n; ++i) {
    const SetupTriangle& t = out[i - 1];
    d += t.prim != 7;
    d += diff_count(t.v[0], r.poly[0], st.num_varyings);
    d += diff_count(t.v[1], r.poly[i], st.num_varyings);
    d += diff_count(t.v[2], r.poly[i + 1], st.num_varyings);
  }
  if (stats.clip_vertices_created != (uint64_t)r.created) d += 100;
  return d;
}

}  // namespace georef
