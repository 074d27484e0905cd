// The analysis path with every rounding point a knob (analysis/budget_path.hpp). GMP rationals
// throughout; the model is called only to find which of its fan triangles drew a pixel and its
// candidate rectangle (setup), and for the divider of a non-correctly-rounded algorithm.
#include "analysis/budget_path.hpp"

#include <algorithm>
#include <climits>

#include "analysis/ideal.hpp"
#include "model/stages/attr.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/divide.hpp"
#include "model/unit/geometry.hpp"
#include "reference/reference.hpp"

namespace fxr {

namespace {

const RoundPointInfo kInfo[kNumRoundPoints] = {
    {"coverage_snap", "raster.subpixel_bits", "stage 4: snap of x, y (coverage only)"},
    {"clip", "raster.clip_sig_bits, recip.in_sig_bits", "stage 2: clipper-made vertices"},
    {"attr_position", "raster.attr_subpixel_bits", "stage 4: attribute positions ax, ay"},
    {"attr_coord", "raster.attr_coord_bits", "stage 5: drop to F fraction bits of large triangles"},
    {"depth_vertex", "raster.z_frac_bits", "stage 4/5: z/w and the depth plane's vertex values"},
    {"recip", "raster.attr_sig_bits", "stage 4: 1/w per vertex"},
    {"v_over_w", "raster.attr_sig_bits", "stage 4: v/w per vertex"},
    {"block_align", "raster.interp_block_bits", "stage 5: block alignment of 1/w and v/w"},
    {"normalise", "div.num_bits, div.den_bits", "stage 9: N, D to the divider's operand widths"},
    {"divider", "div.quot_bits, div.algorithm", "stage 9: the quotient"},
    {"depth_code", "raster.depth_format", "stage 8: the depth code"},
};

mpq_class pow2(long e) {
  return e >= 0 ? mpq_class(mpz_class(1) << (unsigned long)e) : mpq_class(mpz_class(1), mpz_class(1) << (unsigned long)-e);
}

// ⌊log2 |x|⌋, x ≠ 0, exact.
long floor_log2(const mpq_class& x) {
  const mpq_class a = abs(x);
  long e = (long)mpz_sizeinbase(a.get_num_mpz_t(), 2) - (long)mpz_sizeinbase(a.get_den_mpz_t(), 2);
  while (pow2(e) > a) --e;
  while (pow2(e + 1) <= a) ++e;
  return e;
}

// Round to the nearest integer, ties to even.
mpz_class rne_int(const mpq_class& x) {
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  const int c = cmp(mpq_class(x - fl), mpq_class(1, 2));
  if (c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t()))) fl += 1;
  return fl;
}

// RNE of x onto the grid 2^e.
mpq_class rne_grid(const mpq_class& x, long e) { return mpq_class(rne_int(x / pow2(e))) * pow2(e); }

// RNE of x to a normalised `bits`-bit significand (sign-magnitude, symmetric).
mpq_class rne_sig(const mpq_class& x, int bits) {
  if (sgn(x) == 0) return x;
  return rne_grid(x, floor_log2(x) - (bits - 1));
}

// a / b as a canonical rational (GMP's arithmetic needs canonical operands).
mpq_class qfrac(long a, long b) {
  mpq_class q(a, b);
  q.canonicalize();
  return q;
}

mpq_class clamp_q(const mpq_class& x, const mpq_class& lo, const mpq_class& hi) { return x < lo ? lo : x > hi ? hi : x; }

// The dyadic x = ±sig·2^e with sig odd or zero, for feeding the model's divider.
void dyadic_parts(const mpq_class& x, mpz_class& sig, long& e) {
  sig = abs(x.get_num());
  e = -(long)(mpz_sizeinbase(x.get_den_mpz_t(), 2) - 1);  // canonical dyadic: den = 2^k
}

}  // namespace

const RoundPointInfo& round_point_info(RoundPoint p) { return kInfo[(int)p]; }

bool round_point_from_name(const std::string& name, RoundPoint* out) {
  for (int p = 0; p < kNumRoundPoints; ++p)
    if (name == kInfo[p].name) return *out = (RoundPoint)p, true;
  return false;
}

std::string round_point_width(const Config& cfg, RoundPoint p) {
  const RasterConfig& r = cfg.raster;
  auto n = [](int v) { return std::to_string(v); };
  switch (p) {
    case RoundPoint::CoverageSnap: return "subpixel_bits " + n(r.subpixel_bits);
    case RoundPoint::Clip: return "clip_sig_bits " + n(r.clip_sig_bits) + ", w in_sig_bits " + n(cfg.recip.in_sig_bits);
    case RoundPoint::AttrPosition: return "attr_subpixel_bits " + n(r.attr_subpixel_bits);
    case RoundPoint::AttrCoord: return "attr_coord_bits " + n(r.attr_coord_bits);
    case RoundPoint::DepthVertex: return "z_frac_bits " + n(r.z_frac_bits);
    case RoundPoint::Recip: return "attr_sig_bits " + n(r.attr_sig_bits);
    case RoundPoint::VaryingW: return "attr_sig_bits " + n(r.attr_sig_bits);
    case RoundPoint::BlockAlign: return "interp_block_bits " + n(r.interp_block_bits);
    case RoundPoint::Normalise: return "num_bits " + n(cfg.div.num_bits) + ", den_bits " + n(cfg.div.den_bits);
    case RoundPoint::Divider:
      return "quot_bits " + n(cfg.div.quot_bits) + ", " + (cfg.div.algorithm == DivAlgorithm::Radix2 ? "radix2"
                                                          : cfg.div.algorithm == DivAlgorithm::SharedRecip ? "shared_recip"
                                                                                                            : "recip_mul");
    case RoundPoint::DepthCode: return std::string(r.depth_format == DepthFormat::D16 ? "d16" : "d24");
  }
  return "";
}

BudgetPath::BudgetPath(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris)
    : cfg_(cfg), st_(st), tris_(tris) {
  if (!attr_planes(cfg.raster))
    throw ConfigError("budget: the analysis path models the attribute-position path only (raster.attr_subpixel_bits "
                      "must exceed raster.subpixel_bits; docs/reports.md, \"Error budget\")");
  if (st.interp != InterpMode::Perspective)
    throw ConfigError("budget: the analysis path models perspective interpolation only (interp: affine given)");
}

void BudgetPath::load_prim(uint32_t prim) {
  if (prim == cached_prim_) return;
  cached_prim_ = prim;
  model_pieces_.clear();
  model_setup_.clear();
  model_ok_.clear();
  poly_.clear();
  pieces_.clear();
  piece_store_.clear();
  RasterStats scratch;
  if (geometry(cfg_, st_, tris_[prim], prim, model_pieces_, scratch) != GeomOutcome::Emitted) model_pieces_.clear();
  model_setup_.resize(model_pieces_.size());
  for (size_t i = 0; i < model_pieces_.size(); ++i)
    model_ok_.push_back(setup_triangle(cfg_, st_, model_pieces_[i], model_setup_[i]) == SetupOutcome::Ok);
}

// Stage 2 in rationals: Sutherland–Hodgman with the model's planes (model/stages/clip.hpp:
// the same order, inside on d ≥ 0, a plane skipped when no current vertex is strictly
// outside it), new components rounded (clip active) or exact.
const std::vector<BudgetPath::Vtx>& BudgetPath::polygon(ExactMask m) {
  auto it = poly_.find(m & exact_bit(RoundPoint::Clip));
  if (it != poly_.end()) return it->second;
  const bool exact = m & exact_bit(RoundPoint::Clip);
  const RasterConfig& rc = cfg_.raster;
  const int nv = st_.num_varyings;
  std::vector<Vtx> poly(3);
  const ClipTriangle& t = tris_[cached_prim_];
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 4; ++c) poly[i].p[c] = to_mpq_float(t.v[i].pos[c]);
    for (int k = 0; k < nv; ++k) {
      bool replaced = false;  // NaN / ±Inf varyings: the unit's rule (docs/pipeline.md, stage 1)
      poly[i].v[k] = to_mpq_float((float)ref_varying_input(t.v[i].var[k], &replaced));
    }
    poly[i].wa = poly[i].p[3];
  }
  const GuardBand gb = guard_band(rc, st_);
  auto dist = [&](ClipPlane pl, const Vtx& v) {
    const PlaneEq e = plane_eq(gb, pl);
    mpq_class d = mpq_class(mpz_class(std::to_string(e.b))) * v.p[3];
    if (e.comp >= 0) d += mpq_class(mpz_class(std::to_string(e.a))) * v.p[e.comp];
    if (e.wmin) d -= pow2(kWMinExp);
    return d;
  };
  auto round_clip = [&](const mpq_class& x, int bits) {
    if (exact) return x;
    const mpq_class r = rne_sig(x, bits);
    if (sgn(r) != 0 && abs(r) < pow2(kClipFlushLeadExp)) return mpq_class(0);
    return r;
  };
  for (int pl = 0; pl < kNumClipPlanes && poly.size() >= 3; ++pl) {
    std::vector<mpq_class> d;
    bool out = false;
    for (const Vtx& v : poly) d.push_back(dist((ClipPlane)pl, v)), out |= sgn(d.back()) < 0;
    if (!out) continue;
    std::vector<Vtx> next;
    for (size_t i = 0; i < poly.size(); ++i) {
      const size_t j = (i + 1) % poly.size();
      if (sgn(d[i]) >= 0) next.push_back(poly[i]);
      if (sgn(d[i]) * sgn(d[j]) < 0) {
        const mpq_class tt = d[i] / (d[i] - d[j]);
        Vtx r;
        for (int c = 0; c < 4; ++c)
          r.p[c] = round_clip(poly[i].p[c] + tt * (poly[j].p[c] - poly[i].p[c]),
                              c == 3 ? cfg_.recip.in_sig_bits : rc.clip_sig_bits);
        for (int k = 0; k < nv; ++k)
          r.v[k] = round_clip(poly[i].v[k] + tt * (poly[j].v[k] - poly[i].v[k]), rc.clip_sig_bits);
        r.wa = round_clip(poly[i].wa + tt * (poly[j].wa - poly[i].wa), rc.clip_sig_bits);
        next.push_back(r);
      }
    }
    poly = next.size() < 3 ? std::vector<Vtx>{} : next;
  }
  return poly_[m & exact_bit(RoundPoint::Clip)] = poly;
}

const BudgetPath::Piece& BudgetPath::piece(ExactMask m, int fan, int model_fan) {
  const auto key = std::make_tuple(m, fan, model_fan);
  if (auto it = pieces_.find(key); it != pieces_.end()) return *it->second;
  piece_store_.push_back(std::make_unique<Piece>());
  Piece& P = *piece_store_.back();
  pieces_[key] = &P;
  const std::vector<Vtx>& poly = polygon(m);
  const RasterConfig& rc = cfg_.raster;
  const int nv = st_.num_varyings;
  const int A = rc.attr_subpixel_bits, db = rc.depth_bits();
  const mpq_class M = mpq_class((mpz_class(1) << (unsigned long)db) - 1);
  const int idx[3] = {0, fan + 1, fan + 2};
  auto on = [&](RoundPoint p) { return !(m & exact_bit(p)); };
  mpq_class ax[3], ay[3];
  for (int k = 0; k < 3; ++k) {
    const Vtx& v = poly[idx[k]];
    // Stage 4, attribute path (model/stages/attr.hpp): every quotient exact, rounded once.
    const mpq_class xw = (v.p[0] / v.wa + 1) * qfrac(st_.viewport_w, 2) + st_.viewport_x;
    const mpq_class yw = (v.p[1] / v.wa + 1) * qfrac(st_.viewport_h, 2) + st_.viewport_y;
    ax[k] = on(RoundPoint::AttrPosition) ? rne_grid(xw, -A) : xw;
    ay[k] = on(RoundPoint::AttrPosition) ? rne_grid(yw, -A) : yw;
    const mpq_class zr = v.p[2] / v.wa;
    if (on(RoundPoint::DepthVertex)) {
      const mpq_class z = clamp_q(rne_grid(zr, -rc.z_frac_bits), 0, 1);
      P.zq[k] = rne_grid(z * M, -(rc.z_frac_bits - db));  // attr_depth_q
    } else {
      P.zq[k] = clamp_q(zr, 0, 1) * M;  // the saturation belongs to the clipper's rounding (z ≤ w exact)
    }
    P.rw[k] = on(RoundPoint::Recip) ? rne_sig(mpq_class(1 / v.wa), rc.attr_sig_bits) : mpq_class(1 / v.wa);
    P.vw[k].resize(nv);
    for (int j = 0; j < nv; ++j) {
      const mpq_class q = v.v[j] / v.wa;
      P.vw[k][j] = on(RoundPoint::VaryingW) ? rne_sig(q, rc.attr_sig_bits) : q;
    }
  }
  // Stage 5: the drop to F fraction bits (attr_setup): relative magnitudes at A bits of the
  // vertices, the candidate rectangle's corner pixel centres and one pixel.
  if (on(RoundPoint::AttrCoord) && model_fan >= 0) {
    const TriSetup& ts = model_setup_[model_fan];
    const mpq_class sA = pow2(A);
    mpz_class Mg = mpz_class(1) << (unsigned long)A;
    auto grow = [&](const mpq_class& d) {
      mpz_class f;
      const mpq_class a = abs(d);
      mpz_fdiv_q(f.get_mpz_t(), a.get_num_mpz_t(), a.get_den_mpz_t());
      if (f > Mg) Mg = f;
    };
    for (int k = 1; k < 3; ++k) grow((ax[k] - ax[0]) * sA), grow((ay[k] - ay[0]) * sA);
    for (int i : {ts.x0, ts.x1}) grow((mpq_class(i) + mpq_class(1, 2) - ax[0]) * sA);
    for (int j : {ts.y0, ts.y1}) grow((mpq_class(j) + mpq_class(1, 2) - ay[0]) * sA);
    const int need = (int)mpz_sizeinbase(Mg.get_mpz_t(), 2) - 1 + 3;
    const int drop = std::max(0, need - rc.attr_coord_bits);
    if (drop > 0)  // otherwise the model keeps the positions as they are (exact ones too)
      for (int k = 0; k < 3; ++k) ax[k] = rne_grid(ax[k], -(A - drop)), ay[k] = rne_grid(ay[k], -(A - drop));
  }
  for (int k = 0; k < 3; ++k) P.x[k] = ax[k], P.y[k] = ay[k];
  // Block alignment (align_block): the largest lead exponent gets its msb at bit bits − 1.
  auto align = [&](mpq_class* q3) {
    if (!on(RoundPoint::BlockAlign)) return;
    long lead = LONG_MIN;
    for (int k = 0; k < 3; ++k)
      if (sgn(q3[k]) != 0) lead = std::max(lead, floor_log2(q3[k]));
    if (lead == LONG_MIN) return;
    for (int k = 0; k < 3; ++k) q3[k] = rne_grid(q3[k], lead - (rc.interp_block_bits - 1));
  };
  align(P.rw);
  for (int j = 0; j < nv; ++j) {
    mpq_class q3[3] = {P.vw[0][j], P.vw[1][j], P.vw[2][j]};
    align(q3);
    for (int k = 0; k < 3; ++k) P.vw[k][j] = q3[k];
  }
  P.ok = true;
  return P;
}

namespace {
// Edge functions E_k(p) = cross(b − a, p − a), edge k from vertex k+1 to k+2; λ_k = E_k / ΣE.
bool barycentric(const mpq_class x[3], const mpq_class y[3], const mpq_class& px, const mpq_class& py,
                 mpq_class E[3], mpq_class& sum) {
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    E[k] = (x[b] - x[a]) * (py - y[a]) - (y[b] - y[a]) * (px - x[a]);
  }
  sum = E[0] + E[1] + E[2];
  return sgn(sum) != 0;
}
}  // namespace

PathValue BudgetPath::eval(uint32_t prim, int px, int py, ExactMask m) {
  PathValue r;
  if (prim >= tris_.size()) return r;
  load_prim(prim);
  // The model's fan triangle that drew the pixel (coverage: the snapped triangle, top-left rule).
  int model_fan = -1;
  for (size_t i = 0; i < model_pieces_.size() && model_fan < 0; ++i) {
    if (!model_ok_[i]) continue;
    const TriSetup& t = model_setup_[i];
    const int64_t X = pixel_centre(px, t.g), Y = pixel_centre(py, t.g);
    bool in = true;
    for (int k = 0; k < 3; ++k) in &= edge_eval(t.e[k], X, Y) + t.e[k].bias >= 0;
    if (in) model_fan = (int)i;
  }
  const std::vector<Vtx>& poly = polygon(m);
  if (poly.size() < 3) return r;
  const int nfan = (int)poly.size() - 2;
  const mpq_class cx = qfrac(2L * px + 1, 2), cy = qfrac(2L * py + 1, 2);
  // The fan triangle at this mask: the model's when the polygon has the model's vertex count,
  // else the one containing the pixel centre (every piece lies on the same plane).
  int fan = -1;
  if (model_fan >= 0 && nfan == (int)model_pieces_.size()) fan = model_fan;
  mpq_class E[3], sum;
  for (int f = 0; f < nfan && fan < 0; ++f) {
    const Piece& P = piece(m, f, model_fan);
    if (barycentric(P.x, P.y, cx, cy, E, sum) && sgn(E[0]) * sgn(sum) >= 0 && sgn(E[1]) * sgn(sum) >= 0 &&
        sgn(E[2]) * sgn(sum) >= 0)
      fan = f;
  }
  if (fan < 0) fan = 0;
  const Piece& P = piece(m, fan, model_fan);
  if (!barycentric(P.x, P.y, cx, cy, E, sum)) return r;  // zero-area attribute triangle (the model falls back)
  if (m == kAllExact) {
    // Exact coverage: the centre inside (or on the boundary of) the exact clipped polygon.
    for (int f = 0; f < nfan && !r.exact_covered; ++f) {
      const Piece& Q = piece(m, f, model_fan);
      mpq_class e[3], s;
      if (barycentric(Q.x, Q.y, cx, cy, e, s))
        r.exact_covered = sgn(e[0]) * sgn(s) >= 0 && sgn(e[1]) * sgn(s) >= 0 && sgn(e[2]) * sgn(s) >= 0;
    }
  }
  auto on = [&](RoundPoint p) { return !(m & exact_bit(p)); };
  const RasterConfig& rc = cfg_.raster;
  const mpq_class Mc = mpq_class((mpz_class(1) << (unsigned long)rc.depth_bits()) - 1);
  // Stage 8: the depth plane Σ λ_k·Q_k, its code RNE and clamped (DepthStepper).
  mpq_class z = (E[0] * P.zq[0] + E[1] * P.zq[1] + E[2] * P.zq[2]) / sum;
  r.depth = on(RoundPoint::DepthCode) ? clamp_q(mpq_class(rne_int(z)), 0, Mc) : z;
  // Stages 7, 9: D = Σ E_k·R_k, N = Σ E_k·V_k (the orientation's sign cancels in N / D).
  const DivConfig& dc = cfg_.div;
  const int sg = sgn(sum);
  mpq_class D = E[0] * P.rw[0] + E[1] * P.rw[1] + E[2] * P.rw[2];
  if (sg < 0) D = -D;
  if (on(RoundPoint::Normalise)) D = rne_sig(D, dc.den_bits);
  r.valid = true;
  for (int j = 0; j < st_.num_varyings; ++j) {
    mpq_class N = E[0] * P.vw[0][j] + E[1] * P.vw[1][j] + E[2] * P.vw[2][j];
    if (sg < 0) N = -N;
    if (sgn(N) == 0 || sgn(D) <= 0) {
      r.var[j] = 0;  // divide_varying: N = 0 or D ≤ 0 gives zero
      continue;
    }
    if (on(RoundPoint::Normalise)) N = rne_sig(N, dc.num_bits);
    if (!on(RoundPoint::Divider)) {
      r.var[j] = N / D;
    } else if (on(RoundPoint::Normalise) && dc.algorithm != DivAlgorithm::Radix2) {
      // The model's divider on the dyadic operands (significands of num_bits / den_bits bits).
      mpz_class ns, ds;
      long en, ed;
      dyadic_parts(N, ns, en);
      dyadic_parts(D, ds, ed);
      const i128 n128 = (i128)ns.get_ui() * (sgn(N) < 0 ? -1 : 1);
      const FxFloat q = divide_varying(dc, n128, (int)en, normalize_den(dc, (i128)ds.get_ui(), (int)ed));
      r.var[j] = to_mpq(q);
    } else {
      r.var[j] = rne_sig(mpq_class(N / D), dc.quot_bits);  // radix2: correctly rounded
    }
  }
  return r;
}

}  // namespace fxr
