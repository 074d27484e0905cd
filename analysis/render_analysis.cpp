// Error analysis of a rendered frame (analysis/render_analysis.hpp).
#include "analysis/render_analysis.hpp"

#include "analysis/ideal.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <tuple>

#include "frontend/texture.hpp"
#include "model/stages/texaddr.hpp"
#include "reference/texture_ref.hpp"
#include "model/unit/geometry.hpp"

namespace fxr {

using json = nlohmann::json;

void write_fragment_dump(const std::string& dir, const Scene& sc, const FrameOutput& fo) {
  const int nv = sc.state.num_varyings;
  const auto& rc = sc.config.raster;
  {
    std::ofstream f(dir + "/fragments.csv");
    f << "# fxraster fragment dump: one fragment per line, in draw order, that passed the depth test.\n"
         "# Integer codes only; fragments.json declares every column. x, y: pixel (row 0 at the bottom);\n"
         "# depth: D" << rc.depth_bits() << " unorm code (z = depth / (2^" << rc.depth_bits() << " - 1));\n"
         "# prim: input primitive index; vK_neg, vK_sig, vK_exp: varying K = (-1)^neg * sig * 2^exp,\n"
         "# sig has " << rc.varying_out_sig_bits << " bits with its msb set (sig = 0: zero).\n";
    f << "x,y,depth,prim";
    for (int k = 0; k < nv; ++k) f << ",v" << k << "_neg,v" << k << "_sig,v" << k << "_exp";
    f << "\n";
    std::string line;
    for (const auto& fr : fo.fragments) {
      line = std::to_string(fr.x) + "," + std::to_string(fr.y) + "," + std::to_string(fr.depth) + "," +
             std::to_string(fr.prim);
      for (int k = 0; k < nv; ++k)
        line += "," + std::to_string((int)fr.var[k].neg) + "," + std::to_string(fr.var[k].sig) + "," +
                std::to_string(fr.var[k].exp);
      f << line << "\n";
    }
    f.close();
    if (!f) throw std::runtime_error(dir + "/fragments.csv: cannot write");  // checked: never a silent 0 exit
  }
  json cols = json::array();
  cols.push_back({{"name", "x"}, {"type", "int32"}, {"meaning", "pixel column (window x), 0 at the left"}});
  cols.push_back({{"name", "y"}, {"type", "int32"}, {"meaning", "pixel row (window y), 0 at the bottom"}});
  cols.push_back({{"name", "depth"}, {"type", "uint" + std::to_string(rc.depth_bits())},
                  {"meaning", "unorm depth code: z = depth / (2^" + std::to_string(rc.depth_bits()) + " - 1)"}});
  cols.push_back({{"name", "prim"}, {"type", "uint32"}, {"meaning", "index of the input primitive (scene order)"}});
  for (int k = 0; k < nv; ++k) {
    const std::string p = "v" + std::to_string(k);
    cols.push_back({{"name", p + "_neg"}, {"type", "bit"}, {"meaning", "sign of varying " + std::to_string(k)}});
    cols.push_back({{"name", p + "_sig"}, {"type", "uint" + std::to_string(rc.varying_out_sig_bits)},
                    {"meaning", "significand, msb set unless the value is zero"}});
    cols.push_back({{"name", p + "_exp"}, {"type", "int"},
                    {"meaning", "exponent of the significand's lsb: value = (-1)^neg * sig * 2^exp"}});
  }
  json side = {{"format", "fxraster fragment dump"}, {"version", 1}, {"file", "fragments.csv"},
               {"comment_prefix", "#"}, {"header_row", true}, {"columns", cols},
               {"varying_meaning", {{"u", sc.u_varying}, {"v", sc.v_varying}}},
               {"config", config_to_json(sc.config)}, {"rows", fo.fragments.size()}};
  std::ofstream fj(dir + "/fragments.json");
  fj << side.dump(2) << "\n";
  fj.close();
  if (!fj) throw std::runtime_error(dir + "/fragments.json: cannot write");
}

json stats_json(RasterStats s) {
  json j = json::object();
  auto v = [&](const char* name, uint64_t value) { j[name] = value; };
  s.visit(v);
  if (s.lines.in > 0) {  // only a draw with lines has them (the JSON of others is unchanged)
    json l = json::object();
    auto lv = [&](const char* name, uint64_t value) { l[name] = value; };
    s.lines.visit(lv);
    j["lines"] = l;
  }
  return j;
}

json ref_stats_json(const RefStats& s) {
  return {{"prims_in", s.prims_in}, {"prims_drawn", s.prims_drawn}, {"prims_culled_outside", s.prims_culled_outside},
          {"prims_culled_zero_area", s.prims_culled_zero_area}, {"prims_culled_backface", s.prims_culled_backface},
          {"prims_culled_no_samples", s.prims_culled_no_samples},
          {"prims_rejected_nonfinite", s.prims_rejected_nonfinite},
          {"prims_varying_nonfinite", s.prims_varying_nonfinite}, {"fragments_generated", s.fragments_generated},
          {"fragments_depth_pass", s.fragments_depth_pass}, {"fragments_depth_fail", s.fragments_depth_fail}};
}


RenderErrors compare_to_reference(const Scene& sc, const FrameOutput& fo) {
  const int nv = sc.state.num_varyings;
  const int p = sc.config.raster.varying_out_sig_bits;
  const double dmax = std::ldexp(1.0, sc.config.raster.depth_bits()) - 1;
  RenderErrors e;
  e.var_ulp.resize(nv), e.var_abs.resize(nv), e.var_texel.resize(nv), e.texel_diff.assign(nv, 0);
  e.heat.assign((size_t)sc.state.viewport_w * sc.state.viewport_h, -1.0);
  for (const auto& f : fo.fragments) {
    const int hx = f.x - sc.state.viewport_x, hy = f.y - sc.state.viewport_y;
    double* heat = hx >= 0 && hy >= 0 && hx < sc.state.viewport_w && hy < sc.state.viewport_h
                       ? &e.heat[(size_t)hy * sc.state.viewport_w + hx] : nullptr;
    if (heat) *heat = 0;
    if (f.prim >= sc.tris.size()) continue;
    const RefSample r = reference_at_pixel(sc.state, sc.tris[f.prim], nv, f.x + 0.5, f.y + 0.5);
    if (!r.valid) {
      ++e.ref_invalid;
      continue;
    }
    const double derr = std::abs((double)f.depth - r.depth * dmax);
    if (derr > e.depth_lsb.max)
      e.worst["depth"] = {{"x", f.x}, {"y", f.y}, {"prim", f.prim}, {"model_code", f.depth}, {"ref_code", r.depth * dmax}};
    e.depth_lsb.add(derr);
    for (int k = 0; k < nv; ++k) {
      const double m = fx_to_double(f.var[k]), ref = r.var[k];
      const double err = std::abs(m - ref);
      e.var_abs[k].add(err);
      const double u = ulp_of(ref, p);
      if (u > 0) {
        if (err / u > e.var_ulp[k].max)
          e.worst["v" + std::to_string(k)] = {{"x", f.x}, {"y", f.y}, {"prim", f.prim}, {"model", m}, {"ref", ref}, {"ulp", err / u}};
        e.var_ulp[k].add(err / u);
      } else {
        ++e.var_zero_ref;
      }
      int size = 0;
      if (k == sc.u_varying) size = sc.texture.image.width;
      if (k == sc.v_varying) size = sc.texture.image.height;
      if (size) {
        e.var_texel[k].add(err * size);
        if (heat) *heat = std::max(*heat, err * size);
        // The nearest texel along this axis: the texture address unit against the same rule on
        // the double reference value.
        TexAddrConfig nearest = sc.config.tex_addr;
        nearest.filter = TexFilter::Nearest;
        if (texaddr_axis(nearest, f.var[k], (uint32_t)size).i0 != ref_tex_axis(TexFilter::Nearest, nearest.wrap, ref, (uint32_t)size).i0)
          ++e.texel_diff[k];
      }
    }
  }
  return e;
}


// Coverage with the depth test off: the sets of (prim, x, y) of the model and the reference.
CoverageDiff compare_coverage(const FragmentStore& mf, const std::vector<RefFragment>& rf) {
  CoverageDiff c;
  std::vector<std::tuple<uint32_t, int, int>> a, b;
  a.reserve(mf.size());
  b.reserve(rf.size());
  for (size_t i = 0; i < mf.size(); ++i) a.emplace_back(mf.prim(i), mf.y(i), mf.x(i));
  for (const auto& f : rf) b.emplace_back(f.prim, f.y, f.x);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  c.model = a.size();
  c.ref = b.size();
  size_t i = 0, j = 0;
  auto note = [&](const std::tuple<uint32_t, int, int>& t, const char* who) {
    if (c.examples.size() < 20)
      c.examples.push_back({{"prim", std::get<0>(t)}, {"x", std::get<2>(t)}, {"y", std::get<1>(t)}, {"only_in", who}});
  };
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i] < b[j])) {
      ++c.model_only;
      note(a[i++], "model");
    } else if (i == a.size() || b[j] < a[i]) {
      ++c.ref_only;
      note(b[j++], "reference");
    } else {
      ++c.common;
      ++i, ++j;
    }
  }
  return c;
}

SpotChecks exact_spot_checks(const Scene& sc, const FrameOutput& fo, int n) {
  SpotChecks s;
  const int nv = sc.state.num_varyings;
  s.var_ulp.resize(nv);
  s.ideal_var_ulp.resize(nv);
  if (fo.fragments.empty() || n <= 0) return s;
  const int p = sc.config.raster.varying_out_sig_bits;
  const int db = sc.config.raster.depth_bits();
  const mpq_class dmax = mpq_class(mpz_class(1) << db) - 1;
  const size_t step = std::max<size_t>(1, fo.fragments.size() / (size_t)n);
  const IdealJudge judge(sc.state, sc.tris);
  for (size_t i = 0; i < fo.fragments.size(); i += step) {
    const Fragment& f = fo.fragments[i];
    if (f.prim >= sc.tris.size()) continue;  // line fragments: checked by tests/model/line_path_test
    // Level 1: exact on the model's own quantised triangle (analysis/ideal.hpp, snapped_at).
    const IdealValue own = snapped_at(sc.config, sc.state, sc.tris[f.prim], f.x, f.y);
    if (!own.valid) {
      ++s.not_covered_exactly;
    } else {
      ++s.checked;
      const mpq_class dz = mpq_class(f.depth) - own.z * dmax;
      s.depth_lsb.add(std::abs(dz.get_d()));
      for (int k = 0; k < nv; ++k) {
        const double u = ulp_of(own.v[k].get_d(), p);
        if (u > 0) s.var_ulp[k].add(std::abs(mpq_class(to_mpq(f.var[k]) - own.v[k]).get_d()) / u);
      }
    }
    // Level 2: exact ideal of the unsnapped input.
    const IdealValue id = judge.at(f.prim, f.x, f.y);
    if (!id.valid) {
      ++s.ideal_undefined;
      continue;
    }
    ++s.ideal_checked;
    if (sc.u_varying >= 0 && sc.v_varying >= 0) s.ideal_uv.push_back({i, id.v[sc.u_varying], id.v[sc.v_varying]});
    s.ideal_depth_lsb.add(depth_err_lsb(mpq_class(mpz_class(f.depth), mpz_class(dmax)), id.z, db));
    for (int k = 0; k < nv; ++k) {
      const double e = ulp_err(to_mpq(f.var[k]), id.v[k], p);
      if (e >= 0) s.ideal_var_ulp[k].add(e);
    }
  }
  return s;
}

// Vertex snapping, stage 4: for every primitive the geometry stages pass unclipped (one setup
// triangle out), each snapped window x, y against the double window position of the nearest
// input vertex; error in pixels (and in subpixel ulps = pixels · 2^subpixel_bits).
ErrStat snap_errors(const Scene& sc) {
  ErrStat e;
  const auto& st = sc.state;
  const double sub = std::ldexp(1.0, sc.config.raster.subpixel_bits);
  std::vector<SetupTriangle> out;
  for (size_t p = 0; p < sc.tris.size(); ++p) {
    out.clear();
    RasterStats scratch;
    if (geometry(sc.config, st, sc.tris[p], (uint32_t)p, out, scratch) != GeomOutcome::Emitted ||
        out.size() != 1 || scratch.prims_clipped != 0)
      continue;
    double rx[3], ry[3];
    for (int k = 0; k < 3; ++k) {
      const float* c = sc.tris[p].v[k].pos;
      rx[k] = st.viewport_x + ((double)c[0] / c[3] + 1) * 0.5 * st.viewport_w;
      ry[k] = st.viewport_y + ((double)c[1] / c[3] + 1) * 0.5 * st.viewport_h;
    }
    for (const auto& v : out[0].v) {
      const double mx = v.x / sub, my = v.y / sub;
      double best = INFINITY;
      for (int k = 0; k < 3; ++k) best = std::min(best, std::max(std::abs(mx - rx[k]), std::abs(my - ry[k])));
      e.add(best);
    }
  }
  return e;
}

}  // namespace fxr
