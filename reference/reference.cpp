// The double-precision reference pipeline and the exact GMP helpers (reference/reference.hpp).
// Floating point is intended here: this is the yardstick, not the model.
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "model/stages/setup.hpp"

namespace fxr {

namespace {

struct DVert {
  double p[4];                 // clip x, y, z, w
  double v[kMaxVaryings];
};

DVert lerp(const DVert& a, const DVert& b, double t, int nv) {
  DVert r;
  for (int i = 0; i < 4; ++i) r.p[i] = a.p[i] + t * (b.p[i] - a.p[i]);
  for (int i = 0; i < nv; ++i) r.v[i] = a.v[i] + t * (b.v[i] - a.v[i]);
  return r;
}

// Sutherland–Hodgman against one plane d(v) ≥ 0, d linear in clip space.
template <class D>
std::vector<DVert> clip_plane(const std::vector<DVert>& in, int nv, D dist) {
  std::vector<DVert> out;
  for (size_t i = 0; i < in.size(); ++i) {
    const DVert& a = in[i];
    const DVert& b = in[(i + 1) % in.size()];
    const double da = dist(a), db = dist(b);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(lerp(a, b, da / (da - db), nv));
  }
  return out;
}

struct Win {
  double x, y, z, rw;           // window x, y (pixels), window z, 1/w
  double vw[kMaxVaryings];      // v/w (perspective) or v (affine)
};

double edge(const Win& a, const Win& b, double x, double y) {
  return (a.y - b.y) * x + (b.x - a.x) * y + a.x * b.y - b.x * a.y;
}

}  // namespace

RefFrame run_reference(const DrawState& st, const std::vector<ClipTriangle>& tris) {
  RefFrame f;
  f.width = st.viewport_w;
  f.height = st.viewport_h;
  f.depth.assign((size_t)f.width * f.height, 1.0);
  const int nv = st.num_varyings;
  const bool affine = st.interp == InterpMode::Affine;
  // Sample rectangle [x0, x1) × [y0, y1): the viewport ∩ scissor, in window pixels. The model's
  // draw_rect (inclusive bounds) is the draw state's meaning, shared: the reference checks the
  // arithmetic, not how a scissor is read.
  const int vx = st.viewport_x, vy = st.viewport_y;
  const PixelRect dr = draw_rect(st);
  const int x0 = dr.x0, y0 = dr.y0, x1 = dr.x1 + 1, y1 = dr.y1 + 1;
  for (size_t prim = 0; prim < tris.size(); ++prim) {
    ++f.stats.prims_in;
    std::vector<DVert> poly(3);
    bool finite = true, replaced = false;
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 4; ++i) finite &= std::isfinite(poly[k].p[i] = tris[prim].v[k].pos[i]);
      for (int i = 0; i < nv; ++i) poly[k].v[i] = ref_varying_input(tris[prim].v[k].var[i], &replaced);
    }
    if (!finite) {
      ++f.stats.prims_rejected_nonfinite;
      continue;
    }
    if (replaced) ++f.stats.prims_varying_nonfinite;
    // Clip volume 0 ≤ z_c ≤ w_c (implies w_c ≥ 0); x, y need no clipping in double.
    poly = clip_plane(poly, nv, [](const DVert& v) { return v.p[2]; });
    if (poly.size() >= 3) poly = clip_plane(poly, nv, [](const DVert& v) { return v.p[3] - v.p[2]; });
    std::vector<Win> wv;
    for (const DVert& v : poly) {
      if (!(v.p[3] > 0)) continue;  // w = 0 only at a degenerate corner z = w = 0
      Win w;
      w.rw = 1.0 / v.p[3];
      w.x = vx + (v.p[0] * w.rw + 1) * 0.5 * f.width;
      w.y = vy + (v.p[1] * w.rw + 1) * 0.5 * f.height;
      w.z = v.p[2] * w.rw;
      for (int i = 0; i < nv; ++i) w.vw[i] = affine ? v.v[i] : v.v[i] * w.rw;
      wv.push_back(w);
    }
    if (wv.size() < 3) {
      ++f.stats.prims_culled_outside;
      continue;
    }
    // Orientation of the whole (planar, convex) polygon: twice its signed area.
    double area2 = 0;
    for (size_t i = 0; i < wv.size(); ++i) {
      const Win& a = wv[i];
      const Win& b = wv[(i + 1) % wv.size()];
      area2 += a.x * b.y - b.x * a.y;
    }
    if (area2 == 0) {
      ++f.stats.prims_culled_zero_area;
      continue;
    }
    const bool ccw = area2 > 0;
    const bool front = ccw == st.front_ccw;
    if ((st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front)) {
      ++f.stats.prims_culled_backface;
      continue;
    }
    uint64_t covered = 0;
    for (size_t i = 1; i + 1 < wv.size(); ++i) {
      Win t[3] = {wv[0], wv[i], wv[i + 1]};
      if (!ccw) std::swap(t[1], t[2]);
      const double area = edge(t[0], t[1], t[2].x, t[2].y);
      if (!(area > 0)) continue;
      // Bounding box, clamped to the sample rectangle before any conversion to int.
      auto clampd = [](double v, int lo, int hi) { return std::min<double>(std::max<double>(v, lo - 1), hi + 1); };
      const double bx0 = clampd(std::min({t[0].x, t[1].x, t[2].x}), x0, x1);
      const double bx1 = clampd(std::max({t[0].x, t[1].x, t[2].x}), x0, x1);
      const double by0 = clampd(std::min({t[0].y, t[1].y, t[2].y}), y0, y1);
      const double by1 = clampd(std::max({t[0].y, t[1].y, t[2].y}), y0, y1);
      const int px0 = std::max(x0, (int)std::floor(bx0 - 0.5)), px1 = std::min(x1 - 1, (int)std::ceil(bx1));
      const int py0 = std::max(y0, (int)std::floor(by0 - 0.5)), py1 = std::min(y1 - 1, (int)std::ceil(by1));
      bool tl[3];
      for (int e = 0; e < 3; ++e) {
        const Win& a = t[(e + 1) % 3];
        const Win& b = t[(e + 2) % 3];
        tl[e] = top_left_edge(b.x - a.x, b.y - a.y);
      }
      for (int py = py0; py <= py1; ++py)
        for (int px = px0; px <= px1; ++px) {
          const double cx = px + 0.5, cy = py + 0.5;
          double lam[3];
          bool in = true;
          for (int e = 0; e < 3 && in; ++e) {
            // λ_e: edge opposite vertex e.
            lam[e] = edge(t[(e + 1) % 3], t[(e + 2) % 3], cx, cy);
            in = lam[e] > 0 || (lam[e] == 0 && tl[e]);
          }
          if (!in) continue;
          ++covered;
          ++f.stats.fragments_generated;
          RefFragment fr;
          fr.x = px;
          fr.y = py;
          fr.prim = (uint32_t)prim;
          const double s = lam[0] + lam[1] + lam[2];
          for (double& l : lam) l /= s;
          fr.depth = lam[0] * t[0].z + lam[1] * t[1].z + lam[2] * t[2].z;
          const double rw = lam[0] * t[0].rw + lam[1] * t[1].rw + lam[2] * t[2].rw;
          for (int k = 0; k < nv; ++k) {
            const double num = lam[0] * t[0].vw[k] + lam[1] * t[1].vw[k] + lam[2] * t[2].vw[k];
            fr.var[k] = affine ? num : num / rw;
          }
          double& buf = f.depth[(size_t)(py - vy) * f.width + (px - vx)];
          if (!st.depth_test || depth_compare(st.depth_func, fr.depth, buf)) {
            ++f.stats.fragments_depth_pass;
            if (st.depth_test && st.depth_write) buf = fr.depth;
            f.fragments.push_back(fr);
          } else {
            ++f.stats.fragments_depth_fail;
          }
        }
    }
    if (covered) ++f.stats.prims_drawn;
    else ++f.stats.prims_culled_no_samples;
  }
  return f;
}

RefSample reference_at_pixel(const DrawState& st, const ClipTriangle& tri, int num_varyings, double wx, double wy) {
  RefSample r;
  // Window point → NDC.
  const double xn = 2.0 * (wx - st.viewport_x) / st.viewport_w - 1.0, yn = 2.0 * (wy - st.viewport_y) / st.viewport_h - 1.0;
  // Rows: Σ b_i (x_i − xn w_i) = 0, Σ b_i (y_i − yn w_i) = 0, Σ b_i = 1 (GLM is column-major:
  // m[col][row]).
  glm::dmat3 m;
  for (int i = 0; i < 3; ++i) {
    const float* p = tri.v[i].pos;
    m[i][0] = (double)p[0] - xn * p[3];
    m[i][1] = (double)p[1] - yn * p[3];
    m[i][2] = 1.0;
  }
  const double det = glm::determinant(m);
  if (!(std::abs(det) > 0) || !std::isfinite(det)) return r;
  const glm::dvec3 b = glm::inverse(m) * glm::dvec3(0, 0, 1);
  double w = 0, z = 0;
  for (int i = 0; i < 3; ++i) {
    w += b[i] * tri.v[i].pos[3];
    z += b[i] * tri.v[i].pos[2];
  }
  if (!(w > 0)) return r;
  r.valid = true;
  r.w = w;
  r.depth = z / w;
  bool replaced = false;
  for (int k = 0; k < num_varyings; ++k)
    r.var[k] = b[0] * ref_varying_input(tri.v[0].var[k], &replaced) + b[1] * ref_varying_input(tri.v[1].var[k], &replaced) +
               b[2] * ref_varying_input(tri.v[2].var[k], &replaced);
  return r;
}

double ref_varying_input(float f, bool* replaced) {
  if (std::isfinite(f)) return f;
  *replaced = true;
  return std::isnan(f) ? 0.0 : std::copysign((double)std::numeric_limits<float>::max(), (double)f);
}

// ---- exact ------------------------------------------------------------------------------------

mpq_class to_mpq(const FxFloat& f) {
  mpz_class s;
  mpz_import(s.get_mpz_t(), 1, 1, sizeof f.sig, 0, 0, &f.sig);
  mpq_class q(s);
  if (f.exp >= 0) {
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 2, (unsigned long)f.exp);
    q *= p;
  } else {
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 2, (unsigned long)(-f.exp));
    q /= p;
  }
  q.canonicalize();
  return f.neg ? mpq_class(-q) : q;
}

static mpq_class pow2q(int e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 2, (unsigned long)std::abs(e));
  return e >= 0 ? mpq_class(p) : mpq_class(mpz_class(1), p);
}

ExactVertex exact_vertex(const RasterConfig& rc, const SetupVertex& v, int var) {
  ExactVertex e;
  const mpq_class sub = pow2q(-rc.subpixel_bits);
  e.x = mpq_class(mpz_class(std::to_string(v.x))) * sub;
  e.y = mpq_class(mpz_class(std::to_string(v.y))) * sub;
  e.z = mpq_class(mpz_class(std::to_string(v.z))) * pow2q(-rc.z_frac_bits);
  e.rw = to_mpq(v.rw);
  e.vw = var >= 0 ? to_mpq(v.vw[var]) : mpq_class(0);
  return e;
}

ExactSample exact_at_pixel(const ExactVertex v[3], int px, int py, bool affine) {
  ExactSample s;
  const mpq_class cx = mpq_class(2 * (long)px + 1, 2), cy = mpq_class(2 * (long)py + 1, 2);
  auto edge_q = [&](const ExactVertex& a, const ExactVertex& b) {
    return mpq_class((a.y - b.y) * cx + (b.x - a.x) * cy + a.x * b.y - b.x * a.y);
  };
  mpq_class lam[3];
  for (int e = 0; e < 3; ++e) lam[e] = edge_q(v[(e + 1) % 3], v[(e + 2) % 3]);
  const mpq_class area = lam[0] + lam[1] + lam[2];  // = 2·signed area, at every point
  if (sgn(area) == 0) return s;
  const int orient = sgn(area);
  bool in = true;
  for (int e = 0; e < 3; ++e) {
    const ExactVertex& a = v[(e + 1) % 3];
    const ExactVertex& b = v[(e + 2) % 3];
    const int sg = sgn(lam[e]) * orient;
    // For a clockwise triangle the edge runs the other way in its CCW order.
    const mpq_class dx = orient > 0 ? mpq_class(b.x - a.x) : mpq_class(a.x - b.x);
    const mpq_class dy = orient > 0 ? mpq_class(b.y - a.y) : mpq_class(a.y - b.y);
    in &= sg > 0 || (sg == 0 && top_left_edge(sgn(dx), sgn(dy)));
  }
  s.inside = in;
  for (auto& l : lam) l /= area;
  s.z = lam[0] * v[0].z + lam[1] * v[1].z + lam[2] * v[2].z;
  const mpq_class num = lam[0] * v[0].vw + lam[1] * v[1].vw + lam[2] * v[2].vw;
  if (affine) {
    s.v = num;
  } else {
    const mpq_class den = lam[0] * v[0].rw + lam[1] * v[1].rw + lam[2] * v[2].rw;
    s.v = sgn(den) ? mpq_class(num / den) : mpq_class(0);
  }
  return s;
}

}  // namespace fxr
