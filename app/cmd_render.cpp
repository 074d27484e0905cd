// `fxraster render`: a scene through the bit-accurate raster unit and through the double
// reference; writes the shaded image, the depth image, the fragment dump, statistics and an
// error report (report.md / report.json). Deterministic: no timings in the files.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "command.hpp"
#include "model/config/config.hpp"
#include "model/unit/geometry.hpp"
#include "model/unit/raster_unit.hpp"
#include "reference/reference.hpp"
#include "frontend/scene.hpp"
#include "frontend/texture.hpp"

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Opts {
  std::string scene, out, config;
  bool use_default = false, affine = false, no_bunny = false, no_affine_image = false, quiet = false;
  int width = 0, height = 0, spot_checks = 2000;
};

// ---- error statistics ---------------------------------------------------------------------------

struct ErrStat {
  uint64_t n = 0;
  double max = 0, sum = 0, sum2 = 0;
  std::vector<double> all;  // for percentiles
  void add(double e) {
    if (!std::isfinite(e)) return;
    ++n;
    max = std::max(max, e);
    sum += e;
    sum2 += e * e;
    all.push_back(e);
  }
  double mean() const { return n ? sum / n : 0; }
  double rms() const { return n ? std::sqrt(sum2 / n) : 0; }
  // Nearest-rank percentile (q ∈ [0, 1]); deterministic.
  double pct(double q) const {
    if (all.empty()) return 0;
    std::vector<double> v = all;
    const size_t k = std::min(v.size() - 1, (size_t)std::ceil(q * v.size()) - (q > 0 ? 1 : 0));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[k];
  }
  json to_json() const {
    return {{"count", n}, {"max", max}, {"mean", mean()}, {"rms", rms()}, {"p50", pct(0.5)}, {"p99", pct(0.99)}, {"p999", pct(0.999)}};
  }
};

// ulp of a real value x in a binary format with p significand bits (unbounded exponent):
// 2^(⌊log2 |x|⌋ − (p − 1)). x = 0 has no ulp (returns 0).
double ulp_of(double x, int p) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int e;
  std::frexp(std::abs(x), &e);  // |x| = m · 2^e, m ∈ [0.5, 1)
  return std::ldexp(1.0, e - 1 - (p - 1));
}

// Value of an FxFloat as a double (for error measurement only; exact when sig < 2^53).
double fx_to_double(const fxr::FxFloat& f) {
  const double m = std::ldexp((double)f.sig, f.exp);
  return f.neg ? -m : m;
}

// ---- images -----------------------------------------------------------------------------------

// Paints fragments in draw order (the last one that passed the depth test wins). `texel(f, k,
// size)` gives the texel index of varying k of fragment f along an axis of `size` texels.
template <class Frag, class Texel>
fxr::Image paint(const fxr::Scene& sc, const std::vector<Frag>& frags, Texel texel) {
  const fxr::DrawState& st = sc.state;
  fxr::Image img(st.viewport_w, st.viewport_h, sc.background);
  const auto& tex = sc.texture;
  for (const auto& f : frags) {
    const int x = f.x - st.viewport_x, y = f.y - st.viewport_y;
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
    img.at(x, y) = sc.u_varying < 0 || sc.v_varying < 0
                       ? fxr::pack_rgba(192, 192, 192)  // no texture coordinates: flat grey
                       : fxr::texture_fetch(tex, texel(f, sc.u_varying, tex.image.width),
                                            texel(f, sc.v_varying, tex.image.height));
  }
  return img;
}

// The texture address unit on the model's fragments: exact floor(u·W) on the FxFloat codes.
fxr::Image shade_model(const fxr::Scene& sc, const fxr::FrameOutput& fo) {
  return paint(sc, fo.fragments, [&](const fxr::Fragment& f, int k, int size) {
    return fxr::texel_index(f.var[k], size, sc.texture.wrap);
  });
}

fxr::Image shade_reference(const fxr::Scene& sc, const fxr::RefFrame& rf) {
  return paint(sc, rf.fragments, [&](const fxr::RefFragment& f, int k, int size) {
    return fxr::texel_index_ref(f.var[k], size, sc.texture.wrap);
  });
}

// Depth codes → grey, normalised to the range of written codes (nearest = brightest, 255;
// farthest written = 48); never-written pixels (the cleared maximum code) are black.
fxr::Image depth_image(const fxr::FrameOutput& fo, uint32_t clear_code, uint32_t* lo_out, uint32_t* hi_out) {
  fxr::Image img(fo.width, fo.height, fxr::pack_rgba(0, 0, 0));
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t c : fo.depth)
    if (c != clear_code) lo = std::min(lo, c), hi = std::max(hi, c);
  *lo_out = lo;
  *hi_out = hi;
  for (int y = 0; y < fo.height; ++y)
    for (int x = 0; x < fo.width; ++x) {
      const uint32_t c = fo.depth[(size_t)y * fo.width + x];
      if (c == clear_code) continue;
      const double t = hi > lo ? (double)(hi - c) / (double)(hi - lo) : 1.0;
      const uint32_t g = 48 + (uint32_t)std::lround(t * 207);
      img.at(x, y) = fxr::pack_rgba(g, g, g);
    }
  return img;
}

// Error heat map: log10 of the texel error of the visible fragment, 10^-6 (dark blue) …
// 1 texel (red) and beyond (white); no fragment: black.
fxr::Image heat_image(const std::vector<double>& heat, int w, int h) {
  fxr::Image img(w, h, fxr::pack_rgba(0, 0, 0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double e = heat[(size_t)y * w + x];
      if (e < 0) continue;
      if (e >= 1) {
        img.at(x, y) = fxr::pack_rgba(255, 255, 255);
        continue;
      }
      const double t = std::clamp((std::log10(std::max(e, 1e-12)) + 6.0) / 6.0, 0.0, 1.0);  // 0 … 1
      // blue → cyan → green → yellow → red
      const double r = std::clamp(4 * t - 2, 0.0, 1.0), g = t < 0.75 ? std::clamp(4 * t - 0.5, 0.0, 1.0) : 4 - 4 * t,
                   b = std::clamp(1.5 - 4 * t, 0.0, 1.0);
      img.at(x, y) = fxr::pack_rgba((uint32_t)std::lround(40 + 215 * r), (uint32_t)std::lround(40 + 215 * g),
                                    (uint32_t)std::lround(60 + 195 * b));
    }
  return img;
}

fxr::Image side_by_side(const fxr::Image& a, const fxr::Image& b) {
  const int gap = 8;
  fxr::Image img(a.width + gap + b.width, std::max(a.height, b.height), fxr::pack_rgba(255, 255, 255));
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) img.at(x, y) = a.at(x, y);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) img.at(a.width + gap + x, y) = b.at(x, y);
  return img;
}

// ---- fragment dump ------------------------------------------------------------------------------

void write_fragments(const std::string& dir, const fxr::Scene& sc, const fxr::FrameOutput& fo) {
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
               {"config", fxr::config_to_json(sc.config)}, {"rows", fo.fragments.size()}};
  std::ofstream(dir + "/fragments.json") << side.dump(2) << "\n";
}

json stats_json(fxr::RasterStats s) {
  json j = json::object();
  auto v = [&](const char* name, uint64_t value) { j[name] = value; };
  s.visit(v);
  return j;
}

json ref_stats_json(const fxr::RefStats& s) {
  return {{"prims_in", s.prims_in}, {"prims_drawn", s.prims_drawn}, {"prims_culled_outside", s.prims_culled_outside},
          {"prims_culled_zero_area", s.prims_culled_zero_area}, {"prims_culled_backface", s.prims_culled_backface},
          {"prims_culled_no_samples", s.prims_culled_no_samples},
          {"prims_rejected_nonfinite", s.prims_rejected_nonfinite}, {"fragments_generated", s.fragments_generated},
          {"fragments_depth_pass", s.fragments_depth_pass}, {"fragments_depth_fail", s.fragments_depth_fail}};
}

// ---- the comparison ---------------------------------------------------------------------------

struct Errors {
  std::vector<ErrStat> var_ulp, var_abs, var_texel;  // per varying
  std::vector<uint64_t> texel_diff;                  // nearest texel differs from the reference's
  ErrStat depth_lsb;
  uint64_t ref_invalid = 0;                          // reference undefined at the fragment
  uint64_t var_zero_ref = 0;                         // reference value 0: no ulp
  json worst = json::object();
  std::vector<double> heat;                          // per pixel: error of the visible fragment (texels; −1: none)
};

Errors compare_values(const fxr::Scene& sc, const fxr::FrameOutput& fo) {
  const int nv = sc.state.num_varyings;
  const int p = sc.config.raster.varying_out_sig_bits;
  const double dmax = std::ldexp(1.0, sc.config.raster.depth_bits()) - 1;
  Errors e;
  e.var_ulp.resize(nv), e.var_abs.resize(nv), e.var_texel.resize(nv), e.texel_diff.assign(nv, 0);
  e.heat.assign((size_t)sc.state.viewport_w * sc.state.viewport_h, -1.0);
  for (const auto& f : fo.fragments) {
    const int hx = f.x - sc.state.viewport_x, hy = f.y - sc.state.viewport_y;
    double* heat = hx >= 0 && hy >= 0 && hx < sc.state.viewport_w && hy < sc.state.viewport_h
                       ? &e.heat[(size_t)hy * sc.state.viewport_w + hx] : nullptr;
    if (heat) *heat = 0;
    if (f.prim >= sc.tris.size()) continue;
    const fxr::RefSample r = fxr::reference_at_pixel(sc.state, sc.tris[f.prim], nv, f.x + 0.5, f.y + 0.5);
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
        if (fxr::texel_index(f.var[k], size, sc.texture.wrap) != fxr::texel_index_ref(ref, size, sc.texture.wrap))
          ++e.texel_diff[k];
      }
    }
  }
  return e;
}

struct Coverage {
  uint64_t model = 0, ref = 0, common = 0, model_only = 0, ref_only = 0;
  json examples = json::array();
};

// Coverage with the depth test off: the sets of (prim, x, y) of the model and the reference.
Coverage compare_coverage(const std::vector<fxr::Fragment>& mf, const std::vector<fxr::RefFragment>& rf) {
  Coverage c;
  std::vector<std::tuple<uint32_t, int, int>> a, b;
  a.reserve(mf.size());
  b.reserve(rf.size());
  for (const auto& f : mf) a.emplace_back(f.prim, f.y, f.x);
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

// Exact spot checks: for up to n fragments (evenly spaced in draw order), rebuild the snapped
// setup triangles of the fragment's primitive with fxr::geometry, and compare the model's depth
// and varyings with the exact rational values (GMP) from those snapped vertices.
struct Spot {
  uint64_t checked = 0, not_covered_exactly = 0;
  ErrStat depth_lsb;
  std::vector<ErrStat> var_ulp;
};

Spot spot_checks(const fxr::Scene& sc, const fxr::FrameOutput& fo, int n) {
  Spot s;
  const int nv = sc.state.num_varyings;
  s.var_ulp.resize(nv);
  if (fo.fragments.empty() || n <= 0) return s;
  const int p = sc.config.raster.varying_out_sig_bits;
  const mpq_class dmax = mpq_class(mpz_class(1) << sc.config.raster.depth_bits()) - 1;
  const bool affine = sc.state.interp == fxr::InterpMode::Affine;
  const size_t step = std::max<size_t>(1, fo.fragments.size() / (size_t)n);
  for (size_t i = 0; i < fo.fragments.size(); i += step) {
    const fxr::Fragment& f = fo.fragments[i];
    std::vector<fxr::SetupTriangle> st;
    fxr::RasterStats scratch;
    fxr::geometry(sc.config, sc.state, sc.tris[f.prim], f.prim, st, scratch);
    bool found = false;
    for (const auto& t : st) {
      fxr::ExactVertex ev[3];
      for (int k = 0; k < 3; ++k) ev[k] = fxr::exact_vertex(sc.config.raster, t.v[k], -1);
      const fxr::ExactSample es = fxr::exact_at_pixel(ev, f.x, f.y, affine);
      if (!es.inside) continue;
      found = true;
      ++s.checked;
      const mpq_class dz = mpq_class(f.depth) - es.z * dmax;
      s.depth_lsb.add(std::abs(dz.get_d()));
      for (int k = 0; k < nv; ++k) {
        for (int j = 0; j < 3; ++j) ev[j] = fxr::exact_vertex(sc.config.raster, t.v[j], k);
        const fxr::ExactSample ek = fxr::exact_at_pixel(ev, f.x, f.y, affine);
        const double ex = ek.v.get_d();
        const double u = ulp_of(ex, p);
        if (u > 0) s.var_ulp[k].add(std::abs(mpq_class(fxr::to_mpq(f.var[k]) - ek.v).get_d()) / u);
      }
      break;
    }
    if (!found) ++s.not_covered_exactly;
  }
  return s;
}

// Vertex snapping, stage 4: for every primitive the geometry stages pass unclipped (one setup
// triangle out), each snapped window x, y against the double window position of the nearest
// input vertex; error in pixels (and in subpixel ulps = pixels · 2^subpixel_bits).
ErrStat snap_errors(const fxr::Scene& sc) {
  ErrStat e;
  const auto& st = sc.state;
  const double sub = std::ldexp(1.0, sc.config.raster.subpixel_bits);
  std::vector<fxr::SetupTriangle> out;
  for (size_t p = 0; p < sc.tris.size(); ++p) {
    out.clear();
    fxr::RasterStats scratch;
    if (fxr::geometry(sc.config, st, sc.tris[p], (uint32_t)p, out, scratch) != fxr::GeomOutcome::Emitted ||
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

std::string fmt(double v, int prec = 3) {
  char b[64];
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e6)) std::snprintf(b, sizeof b, "%.*e", prec, v);
  else std::snprintf(b, sizeof b, "%.*f", prec, v);
  return b;
}

// ---- the command --------------------------------------------------------------------------------

int run(const Opts& o) {
  if (o.scene.empty() == !o.use_default)
    throw std::runtime_error("give exactly one of SCENE or --default");
  fxr::SceneOptions so;
  so.width = o.width;
  so.height = o.height;
  so.no_optional = o.no_bunny;
  fxr::Scene sc = o.use_default ? fxr::default_scene(so) : fxr::load_scene(o.scene, so);
  if (!o.config.empty()) {
    // --config F: its fields override the scene's configuration (unit by unit, field by field).
    std::ifstream in(o.config);
    if (!in) throw fxr::ConfigError(o.config + ": cannot open the configuration file");
    json cj;
    try {
      cj = json::parse(in);
    } catch (const json::parse_error& e) {
      throw fxr::ConfigError(o.config + ": not valid JSON: " + e.what());
    }
    fxr::config_from_json(cj, o.config);  // validates the file on its own (fields named)
    json merged = fxr::config_to_json(sc.config);
    merged.merge_patch(cj);
    sc.config = fxr::config_from_json(merged, o.config);
  }
  if (o.affine) sc.state.interp = fxr::InterpMode::Affine;
  fs::create_directories(o.out);
  for (const auto& n : sc.notes) std::cerr << "fxraster render: note: " << n << "\n";

  using clk = std::chrono::steady_clock;
  auto t0 = clk::now();
  const fxr::FrameOutput fo = fxr::run_raster_unit(sc.config, sc.state, sc.tris);
  auto t1 = clk::now();
  const fxr::RefFrame rf = fxr::run_reference(sc.state, sc.tris);
  auto t2 = clk::now();

  // Images.
  const fxr::Image img = shade_model(sc, fo);
  fxr::write_png(o.out + "/image.png", img);
  fxr::write_png(o.out + "/reference.png", shade_reference(sc, rf));
  const uint32_t clear_code = (uint32_t)((1ull << sc.config.raster.depth_bits()) - 1);
  uint32_t dlo = 0, dhi = 0;
  fxr::write_png(o.out + "/depth.png", depth_image(fo, clear_code, &dlo, &dhi));
  json other_mode;
  if (!o.no_affine_image) {
    fxr::DrawState st2 = sc.state;
    st2.interp = o.affine ? fxr::InterpMode::Perspective : fxr::InterpMode::Affine;
    fxr::Scene sc2 = sc;
    sc2.state = st2;
    const fxr::FrameOutput fo2 = fxr::run_raster_unit(sc.config, st2, sc.tris);
    const fxr::Image img2 = shade_model(sc2, fo2);
    const std::string name = o.affine ? "image_perspective.png" : "image_affine.png";
    fxr::write_png(o.out + "/" + name, img2);
    fxr::write_png(o.out + "/side_by_side.png", o.affine ? side_by_side(img2, img) : side_by_side(img, img2));
    const Errors e2 = compare_values(sc2, fo2);
    other_mode = {{"image", name}, {"interp", o.affine ? "perspective" : "affine"}, {"fragments", fo2.fragments.size()}};
    if (sc.u_varying >= 0)
      other_mode["u_error_vs_perspective_reference_texels"] = e2.var_texel[sc.u_varying].to_json();
  }
  write_fragments(o.out, sc, fo);

  // Coverage: both pipelines with the depth test off.
  fxr::DrawState nod = sc.state;
  nod.depth_test = false;
  const fxr::FrameOutput fo_cov = fxr::run_raster_unit(sc.config, nod, sc.tris);
  const fxr::RefFrame rf_cov = fxr::run_reference(nod, sc.tris);
  const Coverage cov = compare_coverage(fo_cov.fragments, rf_cov.fragments);
  const Errors err = compare_values(sc, fo);
  if (sc.u_varying >= 0) fxr::write_png(o.out + "/error_heatmap.png", heat_image(err.heat, sc.state.viewport_w, sc.state.viewport_h));
  const Spot spot = spot_checks(sc, fo, o.spot_checks);
  const ErrStat snap = snap_errors(sc);

  // Final images: pixels that differ in colour.
  const fxr::Image rimg = shade_reference(sc, rf);
  uint64_t pix_diff = 0;
  for (size_t i = 0; i < img.rgba.size(); ++i) pix_diff += img.rgba[i] != rimg.rgba[i];

  // Accounting: every input primitive is drawn, culled (with the reason) or rejected.
  const fxr::RasterStats& s = fo.stats;
  const uint64_t accounted = s.prims_drawn + s.prims_culled_outside + s.prims_culled_zero_area +
                             s.prims_culled_backface + s.prims_culled_no_samples + s.prims_rejected_nan +
                             s.prims_rejected_inf + s.prims_rejected_range;

  json stats = {{"scene", sc.name}, {"source", sc.source}, {"viewport", {sc.state.viewport_w, sc.state.viewport_h}},
                {"interp", sc.state.interp == fxr::InterpMode::Affine ? "affine" : "perspective"},
                {"triangles", sc.tris.size()}, {"model", stats_json(s)}, {"reference", ref_stats_json(rf.stats)},
                {"all_primitives_accounted", accounted == s.prims_in && s.prims_in == sc.tris.size()}};
  std::ofstream(o.out + "/stats.json") << stats.dump(2) << "\n";

  const int nv = sc.state.num_varyings;
  json rep = {{"scene", sc.name}, {"source", sc.source}, {"notes", sc.notes}, {"config", fxr::config_to_json(sc.config)},
              {"stats", stats}, {"texture", sc.texture.description}};
  json vars = json::array();
  for (int k = 0; k < nv; ++k)
    vars.push_back({{"varying", k}, {"ulp", err.var_ulp[k].to_json()}, {"abs", err.var_abs[k].to_json()},
                    {"texels", err.var_texel[k].to_json()}, {"texel_differs", err.texel_diff[k]},
                    {"exact_spot_ulp", spot.var_ulp[k].to_json()}});
  rep["errors_vs_double_reference"] = {{"varyings", vars}, {"depth_lsb", err.depth_lsb.to_json()},
                                       {"fragments_reference_undefined", err.ref_invalid},
                                       {"varying_reference_zero", err.var_zero_ref}, {"worst", err.worst}};
  rep["vertex_snap_px"] = snap.to_json();
  rep["exact_spot_checks"] = {{"checked", spot.checked}, {"not_covered_exactly", spot.not_covered_exactly},
                              {"depth_lsb", spot.depth_lsb.to_json()}};
  rep["coverage_depth_test_off"] = {{"model", cov.model}, {"reference", cov.ref}, {"common", cov.common},
                                    {"model_only", cov.model_only}, {"reference_only", cov.ref_only},
                                    {"examples", cov.examples}};
  rep["image_pixels_differing_from_reference"] = pix_diff;
  rep["other_interp_mode"] = other_mode;
  rep["depth_image_range"] = dlo <= dhi ? json{dlo, dhi} : json(nullptr);
  std::ofstream(o.out + "/report.json") << rep.dump(2) << "\n";

  // report.md
  std::ofstream md(o.out + "/report.md");
  const auto& rc = sc.config.raster;
  md << "# fxraster render: " << sc.name << "\n\n";
  md << "Source: `" << sc.source << "`; viewport " << sc.state.viewport_w << " × " << sc.state.viewport_h << "; "
     << sc.tris.size() << " triangles; " << nv << " varyings (u = v" << sc.u_varying << ", v = v" << sc.v_varying
     << "); interpolation " << stats["interp"].get<std::string>() << "; texture " << sc.texture.description << ".\n\n";
  for (const auto& n : sc.notes) md << "> **Note:** " << n << "\n\n";
  md << "| image | file |\n|---|---|\n| shaded (model) | [image.png](image.png) |\n| shaded (double reference) | "
        "[reference.png](reference.png) |\n| depth (D" << rc.depth_bits() << " codes "
     << (dlo <= dhi ? std::to_string(dlo) + "…" + std::to_string(dhi) : std::string("none written"))
     << " → grey, near = bright) | [depth.png](depth.png) |\n";
  if (!o.no_affine_image)
    md << "| " << other_mode["interp"].get<std::string>() << " interpolation (seed 000: "
       << (o.affine ? "the right image" : "the wrong image") << ") | [" << other_mode["image"].get<std::string>() << "]("
       << other_mode["image"].get<std::string>() << ") |\n| perspective ‖ affine | [side_by_side.png](side_by_side.png) |\n";
  if (sc.u_varying >= 0)
    md << "| texel error of u, v vs the double reference (log scale: dark blue 1e-6 … red 1 texel, white ≥ 1) | "
          "[error_heatmap.png](error_heatmap.png) |\n";
  md << "\nFragment dump: [fragments.csv](fragments.csv) (columns declared in [fragments.json](fragments.json)); "
        "statistics: [stats.json](stats.json); this report as JSON: [report.json](report.json).\n\n";
  md << "## Primitives\n\n| counter | model | double reference |\n|---|---|---|\n";
  md << "| primitives in | " << s.prims_in << " | " << rf.stats.prims_in << " |\n";
  md << "| drawn (model: rasterised; reference: ≥ 1 sample) | " << s.prims_drawn << " | " << rf.stats.prims_drawn << " |\n";
  md << "| trivially accepted / clipped | " << s.prims_trivial_accept << " / " << s.prims_clipped << " | |\n";
  md << "| culled: outside | " << s.prims_culled_outside << " | " << rf.stats.prims_culled_outside << " |\n";
  md << "| culled: zero area | " << s.prims_culled_zero_area << " | " << rf.stats.prims_culled_zero_area << " |\n";
  md << "| culled: back face | " << s.prims_culled_backface << " | " << rf.stats.prims_culled_backface << " |\n";
  md << "| culled: no samples (model: empty box; reference: no sample) | " << s.prims_culled_no_samples << " | " << rf.stats.prims_culled_no_samples << " |\n";
  md << "| rejected: NaN / Inf / range | " << s.prims_rejected_nan << " / " << s.prims_rejected_inf << " / "
     << s.prims_rejected_range << " | " << rf.stats.prims_rejected_nonfinite << " (non-finite) |\n";
  md << "| fragments generated | " << s.fragments_generated << " | " << rf.stats.fragments_generated << " |\n";
  md << "| fragments passing depth | " << s.fragments_depth_pass << " | " << rf.stats.fragments_depth_pass << " |\n\n";
  md << "Every primitive accounted for (drawn + culled + rejected = in): **"
     << (stats["all_primitives_accounted"].get<bool>() ? "yes" : "NO") << "** (" << accounted << " of " << s.prims_in << ").\n\n";
  md << "## Error against the double reference\n\n"
        "Per fragment of the model, the reference value is the ideal one at the pixel centre for the "
        "input primitive (unsnapped, unclipped clip-space solve, `fxr::reference_at_pixel`). ulp = ulp of the "
        "reference value in the output format (" << rc.varying_out_sig_bits << "-bit significand); depth in LSBs of D"
     << rc.depth_bits() << ". The reference is not snapped, so these figures include the snapping of the vertices "
        "to 1/" << (1 << rc.subpixel_bits) << " px; the exact spot checks below do not.\n\n";
  md << "| output | unit | max | mean | RMS | p50 | p99 | p99.9 | nearest texel differs |\n|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const std::string& name, const std::string& unit, const ErrStat& e, const std::string& extra) {
    md << "| " << name << " | " << unit << " | " << fmt(e.max) << " | " << fmt(e.mean()) << " | " << fmt(e.rms())
       << " | " << fmt(e.pct(0.5)) << " | " << fmt(e.pct(0.99)) << " | " << fmt(e.pct(0.999)) << " | " << extra << " |\n";
  };
  for (int k = 0; k < nv; ++k) {
    const bool tex = k == sc.u_varying || k == sc.v_varying;
    const std::string name = "varying " + std::to_string(k) + (k == sc.u_varying ? " (u)" : k == sc.v_varying ? " (v)" : "");
    row(name, "ulp", err.var_ulp[k], "");
    if (tex)
      row(name, "texels", err.var_texel[k], std::to_string(err.texel_diff[k]) + " of " + std::to_string(err.var_texel[k].n));
    else
      row(name, "absolute", err.var_abs[k], "—");
  }
  row("depth", "LSB (= ulp)", err.depth_lsb, "—");
  {
    ErrStat snap_ulp;
    for (double v : snap.all) snap_ulp.add(v * (1 << rc.subpixel_bits));
    row("vertex window x, y (snap, unclipped primitives)", "pixels", snap, "");
    row("vertex window x, y (snap, unclipped primitives)", "subpixel ulp", snap_ulp, "");
  }
  md << "\nulp figures of values near zero are large by construction (the ulp of a tiny reference value is "
        "tiny while the snapping error is not); the texel column is the one that shows on screen.\n\n";
  if (err.ref_invalid) md << err.ref_invalid << " fragments where the reference is undefined (edge-on) were skipped.\n\n";
  md << "Pixels of the shaded image that differ from the reference image: " << pix_diff << " of "
     << img.rgba.size() << ".\n\n";
  md << "## Exact spot checks (GMP, from the model's own snapped vertices)\n\n"
     << spot.checked << " fragments (evenly spaced in draw order) re-evaluated exactly from the snapped setup "
        "triangles of `fxr::geometry`: exact depth and exact perspective-correct varyings at the pixel centre.\n\n"
        "| output | max | mean |\n|---|---|---|\n";
  for (int k = 0; k < nv; ++k)
    md << "| varying " << k << " (ulp) | " << fmt(spot.var_ulp[k].max) << " | " << fmt(spot.var_ulp[k].mean()) << " |\n";
  md << "| depth (LSB) | " << fmt(spot.depth_lsb.max) << " | " << fmt(spot.depth_lsb.mean()) << " |\n\n";
  if (spot.not_covered_exactly)
    md << "**" << spot.not_covered_exactly << " checked fragments are not covered by any snapped piece under exact "
          "arithmetic** (a coverage error of the model).\n\n";
  md << "## Coverage (depth test off)\n\nSets of (primitive, pixel): model " << cov.model << ", reference "
     << cov.ref << ", common " << cov.common << ", model only " << cov.model_only << ", reference only "
     << cov.ref_only << ". The reference is unsnapped: differences along edges are expected "
        "(a vertex moves by up to half a subpixel), not failures. Exact coverage of the snapped triangles "
        "is checked by the raster unit's own tests.\n\n";
  if (!o.no_affine_image && sc.u_varying >= 0) {
    const auto& a = other_mode["u_error_vs_perspective_reference_texels"];
    md << "## " << other_mode["interp"].get<std::string>() << " interpolation\n\n"
       << "u error against the perspective-correct reference, in texels: max " << fmt(a["max"].get<double>())
       << ", mean " << fmt(a["mean"].get<double>()) << " (" << other_mode["fragments"].get<uint64_t>() << " fragments).\n";
  }
  md.close();

  if (!o.quiet) {
    std::cout << "fxraster render: " << sc.name << "\n  " << sc.tris.size() << " triangles, "
              << fo.fragments.size() << " fragments written; model " << std::chrono::duration<double>(t1 - t0).count()
              << " s, reference " << std::chrono::duration<double>(t2 - t1).count() << " s\n";
    for (int k = 0; k < nv; ++k)
      std::cout << "  varying " << k << ": max " << fmt(err.var_ulp[k].max) << " ulp vs double reference, "
                << fmt(spot.var_ulp[k].max) << " ulp vs exact (snapped)\n";
    std::cout << "  depth: max " << fmt(err.depth_lsb.max) << " LSB vs double reference, " << fmt(spot.depth_lsb.max)
              << " LSB vs exact (snapped)\n  coverage: " << cov.model_only << " model-only, " << cov.ref_only
              << " reference-only (of " << cov.common << " common)\n  wrote " << o.out << "/report.md\n";
  }
  return accounted == s.prims_in ? 0 : 3;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  sub.add_option("scene", o->scene, "scene JSON file (docs/scene-format.md)");
  sub.add_flag("--default", o->use_default,
               "render the embedded default scene (seed 000's checkerboard face at an angle + the glmark2 bunny)");
  sub.add_option("--out", o->out, "output directory (created): image.png, reference.png, depth.png, "
                                  "image_affine.png, side_by_side.png, fragments.csv/.json, stats.json, "
                                  "report.md/.json")
      ->required();
  sub.add_option("--config", o->config, "configuration JSON whose fields override the scene's configuration");
  sub.add_flag("--affine", o->affine, "interpolate varyings affinely in screen space (seed 000's wrong image) "
                                      "for the main image; the extra image is then the perspective one");
  sub.add_flag("--no-bunny", o->no_bunny, "leave out optional meshes (the default scene's bunny)");
  sub.add_flag("--no-affine-image", o->no_affine_image, "do not render the second image in the other interpolation mode");
  sub.add_option("--width", o->width, "override the viewport width (pixels)")->check(CLI::Range(1, 16384));
  sub.add_option("--height", o->height, "override the viewport height (pixels)")->check(CLI::Range(1, 16384));
  sub.add_option("--spot-checks", o->spot_checks, "fragments re-evaluated exactly with GMP (default 2000)")
      ->check(CLI::Range(0, 1000000));
  sub.add_flag("--quiet", o->quiet, "print nothing on success");
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("render",
                        "render a scene through the model and the double reference: images, fragment dump, "
                        "statistics and an error report",
                        setup);

}  // namespace
