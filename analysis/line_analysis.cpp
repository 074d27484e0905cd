// Line fragments against exact arithmetic (analysis/line_analysis.hpp).
#include "analysis/line_analysis.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>

#include "analysis/ideal.hpp"
#include "model/unit/line_chain.hpp"
#include "reference/reference.hpp"

namespace fxr {

namespace {

mpq_class pow2q(int e) {
  return e >= 0 ? mpq_class(mpz_class(1) << e) : mpq_class(mpz_class(1), mpz_class(1) << -e);
}

// Keeps the snapped segment of every primitive the line chain sets up.
struct SetupTap {
  std::map<uint32_t, SetupLine> setup;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same_v<S, LineViewportStage>) setup[o.prim] = o;
  }
};

mpq_class clampq(const mpq_class& t) { return t < 0 ? mpq_class(0) : t > 1 ? mpq_class(1) : t; }

}  // namespace

LineChecks line_checks(const Scene& sc, const FrameOutput& fo, int n) {
  LineChecks c;
  const int nv = sc.line_state.num_varyings;
  c.var_ulp.resize(nv);
  c.ideal_var_ulp.resize(nv);
  const uint32_t ntris = (uint32_t)sc.tris.size();
  std::vector<Fragment> frags;  // the line fragments (decoded records: few beside the triangles')
  for (const Fragment& f : fo.fragments)
    if (f.prim >= ntris) frags.push_back(f);
  c.fragments = frags.size();
  if (frags.empty() || n <= 0) return c;

  // The model's own segments: the line chain once more, up to the snap (no fragments kept).
  const Config& cfg = sc.config;
  const RasterConfig& rc = cfg.raster;
  SetupTap tap;
  {
    FrameOutput scratch;
    DrawState st = sc.line_state;
    st.depth_test = false;
    frame_begin(cfg, st, scratch);
    LineChain<SetupTap> chain(cfg, st, scratch, nullptr, tap);
    for (size_t k = 0; k < sc.lines.size(); ++k) chain.draw(sc.lines[k], ntris + (uint32_t)k);
  }
  const bool attr = attr_planes(rc);
  const int A = attr ? rc.attr_subpixel_bits : rc.subpixel_bits;
  const int db = rc.depth_bits(), p = rc.varying_out_sig_bits;
  const mpq_class M = mpq_class((mpz_class(1) << db) - 1);
  const bool affine = sc.line_state.interp == InterpMode::Affine;
  const DrawState& st = sc.line_state;

  const size_t step = std::max<size_t>(1, frags.size() / (size_t)n);
  for (size_t i = 0; i < frags.size(); i += step) {
    const Fragment& f = frags[i];
    const mpq_class cx = mpq_class(2 * (long)f.x + 1, 2), cy = mpq_class(2 * (long)f.y + 1, 2);
    const mpq_class got_z = mpq_class(mpz_class((unsigned long)f.depth), mpz_class(M.get_num()));
    // Level 1: the own segment.
    const auto it = tap.setup.find(f.prim);
    if (it != tap.setup.end()) {
      const SetupLine& s = it->second;
      mpq_class px[2], py[2], z[2], rw[2], vw[2][kMaxVaryings];
      for (int e = 0; e < 2; ++e) {
        px[e] = mpq_class(mpz_class((long)s.v[e].ax)) / pow2q(A);
        py[e] = mpq_class(mpz_class((long)s.v[e].ay)) / pow2q(A);
        z[e] = mpq_class(mpz_class((unsigned long)s.v[e].z)) / pow2q(rc.z_frac_bits);
        rw[e] = affine ? mpq_class(1) : to_mpq(s.v[e].rw);
        for (int k = 0; k < nv; ++k) vw[e][k] = to_mpq(s.v[e].vw[k]);
      }
      const mpq_class dx = px[1] - px[0], dy = py[1] - py[0], L2 = dx * dx + dy * dy;
      const mpq_class t = L2 == 0 ? mpq_class(0) : clampq(((cx - px[0]) * dx + (cy - py[0]) * dy) / L2);
      ++c.checked;
      c.depth_lsb.add(depth_err_lsb(got_z, (1 - t) * z[0] + t * z[1], db));
      const mpq_class D = (1 - t) * rw[0] + t * rw[1];
      for (int k = 0; k < nv; ++k) {
        const double e = ulp_err(to_mpq(f.var[k]), ((1 - t) * vw[0][k] + t * vw[1][k]) / D, p);
        if (e >= 0) c.var_ulp[k].add(e);
      }
    }
    // Level 2: the ideal of the unsnapped input.
    const ClipLine& l = sc.lines[f.prim - ntris];
    mpq_class w[2], wx[2], wy[2], zn[2];
    bool ok = true;
    for (int e = 0; e < 2; ++e) {
      w[e] = to_mpq_float(l.v[e].pos[3]);
      if (!(std::isfinite(l.v[e].pos[0]) && std::isfinite(l.v[e].pos[1]) && std::isfinite(l.v[e].pos[2]) &&
            std::isfinite(l.v[e].pos[3])) || sgn(w[e]) <= 0) {
        ok = false;
        break;
      }
      wx[e] = (to_mpq_float(l.v[e].pos[0]) / w[e] + 1) * mpq_class(st.viewport_w, 2) + st.viewport_x;
      wy[e] = (to_mpq_float(l.v[e].pos[1]) / w[e] + 1) * mpq_class(st.viewport_h, 2) + st.viewport_y;
      zn[e] = to_mpq_float(l.v[e].pos[2]) / w[e];
    }
    if (!ok) {
      ++c.ideal_undefined;
      continue;
    }
    const mpq_class dx = wx[1] - wx[0], dy = wy[1] - wy[0], L2 = dx * dx + dy * dy;
    const mpq_class t = L2 == 0 ? mpq_class(0) : clampq(((cx - wx[0]) * dx + (cy - wy[0]) * dy) / L2);
    ++c.ideal_checked;
    mpq_class zi = (1 - t) * zn[0] + t * zn[1];
    if (zi < 0) zi = 0;
    if (zi > 1) zi = 1;
    c.ideal_depth_lsb.add(depth_err_lsb(got_z, zi, db));
    const mpq_class R0 = affine ? mpq_class(1) : mpq_class(1 / w[0]), R1 = affine ? mpq_class(1) : mpq_class(1 / w[1]);
    const mpq_class D = (1 - t) * R0 + t * R1;
    for (int k = 0; k < nv; ++k) {
      const mpq_class v0 = to_mpq_float(l.v[0].var[k]) * R0, v1 = to_mpq_float(l.v[1].var[k]) * R1;
      const double e = ulp_err(to_mpq(f.var[k]), ((1 - t) * v0 + t * v1) / D, p);
      if (e >= 0) c.ideal_var_ulp[k].add(e);
    }
  }
  return c;
}

}  // namespace fxr
