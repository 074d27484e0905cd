// What a scene needs (analysis/scene_analysis.hpp). Derivations: docs/reports.md, "Scene analysis".
#include "analysis/scene_analysis.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

#include "analysis/error_stats.hpp"
#include "model/stages/attr.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/input.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/geometry.hpp"

namespace fxr {

namespace {

struct Collect final : FragmentSink {
  std::vector<std::pair<uint64_t, std::pair<uint32_t, uint32_t>>>* all = nullptr;  // pixel → (prim, code)
  uint32_t zmin = UINT32_MAX, zmax = 0;
  uint64_t n = 0;
  int width = 0;
  void emit(const Fragment& f) override {
    ++n;
    zmin = std::min(zmin, f.depth);
    zmax = std::max(zmax, f.depth);
    if (all) all->push_back({(uint64_t)f.y * (uint64_t)width + (uint64_t)f.x, {f.prim, f.depth}});
  }
};

RasterStats run(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris, FragmentSink& s) {
  FrameOutput f;
  frame_begin(cfg, st, f);
  std::vector<SetupTriangle> pieces;
  for (size_t p = 0; p < tris.size(); ++p) {
    ++f.stats.prims_in;
    pieces.clear();
    if (geometry(cfg, st, tris[p], (uint32_t)p, pieces, f.stats) != GeomOutcome::Emitted) continue;
    for (const SetupTriangle& t : pieces) raster_triangle_to(cfg, st, t, f, &s);
  }
  return f.stats;
}

// Smallest e with −2^(e−1) ≤ lo and hi ≤ 2^(e−1) − 1.
int signed_bits(int64_t lo, int64_t hi) {
  int e = 1;
  while (-(int64_t(1) << (e - 1)) > lo || hi > (int64_t(1) << (e - 1)) - 1) ++e;
  return e;
}

}  // namespace

SceneAnalysis analyze_scene(const Scene& sc) {
  SceneAnalysis a;
  const Config& cfg = sc.config;
  const RasterConfig& rc = cfg.raster;
  const DrawState& st = sc.state;
  const int nv = st.num_varyings;
  a.scene = sc.name;
  a.viewport_x = st.viewport_x, a.viewport_y = st.viewport_y, a.viewport_w = st.viewport_w, a.viewport_h = st.viewport_h;
  a.guard_limit_px = guard_limit_px(rc);
  a.texture_w = sc.texture.image.width;
  a.texture_h = sc.texture.image.height;
  a.var_min.assign(nv, INFINITY);
  a.var_max.assign(nv, -INFINITY);
  a.prims = sc.tris.size();
  bool nonfinite_var = false;
  std::vector<double> ratios;
  a.w_min = INFINITY;
  a.w_max = 0;
  const GuardBand gb = guard_band(rc, st);
  for (const ClipTriangle& t : sc.tris) {
    double wlo = INFINITY, whi = 0;
    uint32_t any_out = 0;
    bool all_front = true;
    for (int i = 0; i < 3; ++i) {
      const ClipVertex& v = t.v[i];
      for (int c = 0; c < 4; ++c) a.max_abs_clip[c] = std::max(a.max_abs_clip[c], (double)std::fabs(v.pos[c]));
      const double w = v.pos[3];
      if (w > 0) {
        wlo = std::min(wlo, w), whi = std::max(whi, w);
        a.w_min = std::min(a.w_min, w), a.w_max = std::max(a.w_max, w);
        // Window position of an input vertex in front of the eye (a range figure, double).
        const double xw = (v.pos[0] / w + 1) * st.viewport_w / 2 + st.viewport_x;
        const double yw = (v.pos[1] / w + 1) * st.viewport_h / 2 + st.viewport_y;
        a.input_window_extent_px = std::max({a.input_window_extent_px, std::fabs(xw), std::fabs(yw)});
      } else {
        all_front = false;
      }
      for (int k = 0; k < nv; ++k) {
        if (!std::isfinite(v.var[k])) {
          nonfinite_var = true;
          continue;
        }
        a.var_min[k] = std::min(a.var_min[k], (double)v.var[k]);
        a.var_max[k] = std::max(a.var_max[k], (double)v.var[k]);
      }
      ClipVtx cv;
      bool finite = true;
      for (int c = 0; c < 4; ++c) {
        const F32Decoded d = decode_f32(f32_bits(v.pos[c]));
        finite &= d.cls != F32Class::NaN && d.cls != F32Class::Inf;
        cv.p[c] = d.value;
      }
      if (finite && gb.valid) any_out |= outcode(gb, cv);
    }
    for (int p = 0; p < kNumClipPlanes; ++p) a.plane_clips[p] += (any_out >> p) & 1;
    if (all_front && wlo > 0) ratios.push_back(whi / wlo);
  }
  if (!(a.w_min < INFINITY)) a.w_min = 0;
  std::sort(ratios.begin(), ratios.end());
  if (!ratios.empty()) a.w_ratio_max = ratios.back(), a.w_ratio_p50 = ratios[ratios.size() / 2];
  const int texu = sc.u_varying, texv = sc.v_varying;
  if (texu >= 0 && texu < nv) a.u_outside_unit = a.var_min[texu] < 0 || a.var_max[texu] >= 1;
  if (texv >= 0 && texv < nv) a.v_outside_unit = a.var_min[texv] < 0 || a.var_max[texv] >= 1;

  // The drawn (snapped) triangles: extent, area, block and attribute-coordinate needs.
  a.min_area_px2 = INFINITY;
  int lead_lo = INT_MAX, lead_hi = INT_MIN;  // lead exponents of 1/w of drawn vertices
  {
    RasterStats s;
    std::vector<SetupTriangle> pieces;
    const double sub = std::ldexp(1.0, rc.subpixel_bits);
    for (size_t p = 0; p < sc.tris.size(); ++p) {
      pieces.clear();
      if (geometry(cfg, st, sc.tris[p], (uint32_t)p, pieces, s) != GeomOutcome::Emitted) continue;
      for (const SetupTriangle& t : pieces) {
        TriSetup ts;
        if (setup_triangle(cfg, st, t, ts) != SetupOutcome::Ok) continue;
        const double g = std::ldexp(1.0, 2 * ts.g);
        a.min_area_px2 = std::min(a.min_area_px2, (double)ts.area2 / 2 / g);
        double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
        for (int k = 0; k < 3; ++k) {
          const double x = (double)t.v[k].x / sub, y = (double)t.v[k].y / sub;
          a.window_extent_px = std::max({a.window_extent_px, std::fabs(x), std::fabs(y)});
          xlo = std::min(xlo, x), xhi = std::max(xhi, x), ylo = std::min(ylo, y), yhi = std::max(yhi, y);
          if (!t.v[k].rw.is_zero()) lead_lo = std::min(lead_lo, t.v[k].rw.lead_exp()), lead_hi = std::max(lead_hi, t.v[k].rw.lead_exp());
        }
        a.max_extent_px = std::max({a.max_extent_px, xhi - xlo, yhi - ylo});
        // Block alignment is exact while the lead exponents differ by ≤ ibb − significand bits.
        auto lead_diff = [&](auto get) {
          int lo = INT_MAX, hi = INT_MIN;
          for (int k = 0; k < 3; ++k) {
            const FxFloat f = get(k);
            if (!f.is_zero()) lo = std::min(lo, f.lead_exp()), hi = std::max(hi, f.lead_exp());
          }
          if (hi >= lo) a.max_block_lead_diff = std::max(a.max_block_lead_diff, hi - lo);
        };
        lead_diff([&](int k) { return t.v[k].rw; });
        for (int m = 0; m < nv; ++m) lead_diff([&](int k) { return t.v[k].vw[m]; });
        if (attr_planes(rc)) {
          // attr_setup's need: msb + 3 of the largest relative coordinate (vertices, the candidate
          // rectangle's corner centres, one pixel) at A fraction bits.
          const int A = rc.attr_subpixel_bits;
          u128 M = (u128)1 << A;
          auto grow = [&M](i128 d) { M = std::max(M, (u128)(d < 0 ? -d : d)); };
          const i128 ox = t.v[0].ax, oy = t.v[0].ay, half = (i128)1 << (A - 1);
          for (int k = 1; k < 3; ++k) grow(t.v[k].ax - ox), grow(t.v[k].ay - oy);
          for (int i : {ts.x0, ts.x1}) grow((i128)i * ((i128)1 << A) + half - ox);
          for (int j : {ts.y0, ts.y1}) grow((i128)j * ((i128)1 << A) + half - oy);
          a.max_attr_coord_need = std::max(a.max_attr_coord_need, msb_index(M) + 3);
        }
      }
    }
  }
  if (!(a.min_area_px2 < INFINITY)) a.min_area_px2 = 0;

  // Fragments as drawn (depth range), and every fragment with the depth test off (overlaps).
  std::vector<std::pair<uint64_t, std::pair<uint32_t, uint32_t>>> all;
  {
    Collect c;
    const RasterStats s = run(cfg, st, sc.tris, c);
    a.prims_clipped = s.prims_clipped;
    a.depth_min_code = c.n ? c.zmin : 0;
    a.depth_max_code = c.n ? c.zmax : 0;
    DrawState keep = st;
    keep.depth_test = false;
    Collect k;
    k.all = &all;
    k.width = st.viewport_x + st.viewport_w;
    run(cfg, keep, sc.tris, k);
  }
  std::sort(all.begin(), all.end());
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    std::vector<std::pair<uint32_t, uint32_t>> px;  // (code, prim)
    for (size_t q = i; q < j; ++q) px.push_back({all[q].second.second, all[q].second.first});
    std::sort(px.begin(), px.end());
    bool overlap = false;
    for (size_t q = 0; q + 1 < px.size(); ++q)
      for (size_t r = q + 1; r < px.size(); ++r) {
        if (px[r].second == px[q].second) continue;  // the same primitive (pieces of one clipped polygon)
        overlap = true;
        const int64_t d = (int64_t)px[r].first - (int64_t)px[q].first;
        if (a.min_depth_separation_lsb < 0 || d < a.min_depth_separation_lsb) a.min_depth_separation_lsb = d;
        a.equal_depth_pairs += d == 0;
        break;  // sorted by code: the nearest different primitive above q
      }
    a.overlapping_pixels += overlap;
    i = j;
  }

  // ---- minimal widths (docs/reports.md, "Scene analysis") ----------------------------------
  auto add = [&](const std::string& f, int mn, int cur, const std::string& why) { a.widths.push_back({f, mn, cur, why}); };
  {
    // Window format: the guard band L = 2^(wib−1) − 1 must hold the viewport; holding every
    // input vertex in front of the eye too means no guard-band clipping.
    int wib = 8;
    const int64_t need_vp = std::max<int64_t>({std::abs((int64_t)st.viewport_x), std::abs((int64_t)st.viewport_y),
                                               (int64_t)st.viewport_x + st.viewport_w, (int64_t)st.viewport_y + st.viewport_h});
    while (wib < 20 && (int64_t(1) << (wib - 1)) - kGuardMarginPx < need_vp) ++wib;
    int wib_noclip = wib;
    while (wib_noclip <= 20 && (double)((int64_t(1) << (wib_noclip - 1)) - kGuardMarginPx) < std::ceil(a.input_window_extent_px)) ++wib_noclip;
    std::ostringstream why;
    why << "viewport needs L ≥ " << need_vp << " px: " << wib << " bits; no guard-band clipping needs L ≥ "
        << fmt_num(a.input_window_extent_px) << " px: " << (wib_noclip > 20 ? std::string("beyond 20 bits") : std::to_string(wib_noclip) + " bits");
    add("raster.window_int_bits", wib, rc.window_int_bits, why.str());
  }
  if (attr_planes(rc))
    add("raster.attr_coord_bits", std::max(a.max_attr_coord_need, rc.window_int_bits + 3), rc.attr_coord_bits,
        "no triangle drops attribute fraction bits: msb + 3 of its largest relative coordinate (" +
            std::to_string(a.max_attr_coord_need) + "), and ≥ window_int_bits + 3");
  {
    const int p = attr_planes(rc) ? rc.attr_sig_bits : std::max(cfg.recip.out_sig_bits, rc.varying_sig_bits);
    add("raster.interp_block_bits", p + a.max_block_lead_diff, rc.interp_block_bits,
        "exact alignment: significand bits (" + std::to_string(p) + ") + the largest lead-exponent difference within a triangle (" +
            std::to_string(a.max_block_lead_diff) + ")");
  }
  if (lead_hi >= lead_lo) {
    // 1/w leads in [lead_lo, lead_hi]; w's are −lead − 1 … −lead.
    const int eb = signed_bits(std::min<int64_t>(lead_lo, -lead_hi - 1), std::max<int64_t>(lead_hi, -lead_lo));
    add("recip.exp_bits", std::max(eb, 6), cfg.recip.exp_bits,
        "lead exponents of 1/w (" + std::to_string(lead_lo) + " … " + std::to_string(lead_hi) + ") and of w");
  }
  if (a.texture_w > 0) {
    int sb = 1;
    while ((1 << sb) < std::max(a.texture_w, a.texture_h)) ++sb;
    add("tex_addr.size_bits", sb, cfg.tex_addr.size_bits,
        "texture " + std::to_string(a.texture_w) + " × " + std::to_string(a.texture_h));
  }
  {
    const int db = rc.depth_bits();
    int need = 16;
    std::string why;
    if (a.min_depth_separation_lsb < 0) {
      why = "no overlapping surfaces: the smallest format resolves every pixel";
    } else {
      // Separation s = Δ/(2^db − 1) of the depth range; codes differ at D bits when s·(2^D − 1) ≥ 1.
      const double s = (double)a.min_depth_separation_lsb / (double)((1u << db) - 1);
      if (s * 65535.0 >= 1) need = 16;
      else if (s * 16777215.0 >= 1) need = 24;
      else need = -1;
      why = "smallest separation of overlapping surfaces " + std::to_string(a.min_depth_separation_lsb) + " LSB at D" +
            std::to_string(db) + (need < 0 ? " (intersecting or coplanar surfaces: no format separates them)" : "");
    }
    add("raster.depth_format", need, db, why);
    add("raster.z_frac_bits", db, rc.z_frac_bits, "≥ the depth format's bits on the attribute-position path");
  }
  if (a.prims_clipped == 0)
    add("raster.clip_sig_bits", 16, rc.clip_sig_bits, "no primitive is clipped: the clipper never rounds (range minimum)");
  else
    add("raster.clip_sig_bits", rc.clip_sig_bits, rc.clip_sig_bits,
        std::to_string(a.prims_clipped) + " primitives clipped: an error-target question (fxraster plan / budget)");

  // ---- never exercised -------------------------------------------------------------------
  const char* plane_names[kNumClipPlanes] = {"w_min", "near", "far", "left guard band", "right guard band",
                                             "bottom guard band", "top guard band"};
  if (a.prims_clipped == 0) a.unused.push_back("clipper (stage 2): no primitive is clipped");
  else
    for (int p = 0; p < kNumClipPlanes; ++p)
      if (!a.plane_clips[p]) a.unused.push_back(std::string("clip plane ") + plane_names[p] + ": never crossed");
  if (sc.lines.empty()) a.unused.push_back("line path (stages 1L–7L): no line segments");
  if (!nonfinite_var) a.unused.push_back("non-finite varyings (stage 1 replacement): none");
  if (st.cull == CullMode::None) a.unused.push_back("back-face culling: cull mode none");
  if (st.scissor_w < 0 && st.scissor_h < 0) a.unused.push_back("scissor: off (the viewport)");
  if (!st.depth_test) a.unused.push_back("depth test: off");
  if (nv == 0) a.unused.push_back("interpolators and divider (stages 7 N, D and 9): no varyings");
  if (a.texture_w > 0 && !a.u_outside_unit && !a.v_outside_unit)
    a.unused.push_back("texture wrap modes: u, v stay in [0, 1)");
  if (a.overlapping_pixels == 0) a.unused.push_back("depth test resolution: no pixel is covered by two primitives");
  return a;
}

nlohmann::json analysis_json(const SceneAnalysis& a) {
  nlohmann::json j;
  j["scene"] = a.scene;
  j["viewport"] = {a.viewport_x, a.viewport_y, a.viewport_w, a.viewport_h};
  j["guard_limit_px"] = a.guard_limit_px;
  j["max_abs_clip"] = {a.max_abs_clip[0], a.max_abs_clip[1], a.max_abs_clip[2], a.max_abs_clip[3]};
  j["w"] = {{"min", a.w_min}, {"max", a.w_max}, {"triangle_ratio_max", a.w_ratio_max}, {"triangle_ratio_p50", a.w_ratio_p50}};
  j["window_extent_px"] = {{"drawn", a.window_extent_px}, {"input_in_front", a.input_window_extent_px}};
  j["varyings"] = nlohmann::json::array();
  for (size_t k = 0; k < a.var_min.size(); ++k) j["varyings"].push_back({{"min", a.var_min[k]}, {"max", a.var_max[k]}});
  j["texture"] = {a.texture_w, a.texture_h};
  j["min_triangle_area_px2"] = a.min_area_px2;
  j["max_triangle_extent_px"] = a.max_extent_px;
  j["depth"] = {{"min_code", a.depth_min_code}, {"max_code", a.depth_max_code}, {"overlapping_pixels", a.overlapping_pixels},
                {"min_separation_lsb", a.min_depth_separation_lsb}, {"equal_code_pairs", a.equal_depth_pairs}};
  j["prims"] = a.prims;
  j["prims_clipped"] = a.prims_clipped;
  j["plane_clips"] = nlohmann::json::array();
  for (uint64_t c : a.plane_clips) j["plane_clips"].push_back(c);
  j["max_block_lead_diff"] = a.max_block_lead_diff;
  j["max_attr_coord_need"] = a.max_attr_coord_need;
  for (const MinWidth& w : a.widths) j["min_widths"][w.field] = {{"min", w.min}, {"current", w.current}, {"why", w.why}};
  j["never_exercised"] = a.unused;
  return j;
}

std::string analysis_markdown(const SceneAnalysis& a) {
  std::ostringstream m;
  m << "# Scene analysis: " << a.scene << "\n\nRanges the scene exercises and the minimal widths they require "
       "(derivations: docs/reports.md, \"Scene analysis\").\n\n| range | value |\n|---|---|\n"
    << "| viewport | " << a.viewport_w << " × " << a.viewport_h << " at (" << a.viewport_x << ", " << a.viewport_y << ") |\n"
    << "| guard band L (configuration) | " << a.guard_limit_px << " px |\n"
    << "| input |x_c|, |y_c|, |z_c|, |w_c| max | " << fmt_num(a.max_abs_clip[0]) << ", " << fmt_num(a.max_abs_clip[1]) << ", "
    << fmt_num(a.max_abs_clip[2]) << ", " << fmt_num(a.max_abs_clip[3]) << " |\n"
    << "| w (vertices in front) | " << fmt_num(a.w_min) << " … " << fmt_num(a.w_max) << " |\n"
    << "| w ratio within a triangle, max / median | " << fmt_num(a.w_ratio_max) << " / " << fmt_num(a.w_ratio_p50) << " |\n"
    << "| window extent, drawn vertices / input vertices in front | " << fmt_num(a.window_extent_px) << " / "
    << fmt_num(a.input_window_extent_px) << " px |\n";
  for (size_t k = 0; k < a.var_min.size(); ++k)
    m << "| varying " << k << " | " << fmt_num(a.var_min[k]) << " … " << fmt_num(a.var_max[k]) << " |\n";
  m << "| texture | " << a.texture_w << " × " << a.texture_h << " |\n"
    << "| smallest triangle area / largest extent (drawn) | " << fmt_num(a.min_area_px2) << " px² / " << fmt_num(a.max_extent_px)
    << " px |\n| depth codes written | " << a.depth_min_code << " … " << a.depth_max_code << " |\n"
    << "| pixels covered by ≥ 2 primitives | " << a.overlapping_pixels << " |\n"
    << "| smallest depth separation there (LSB) / equal codes | " << a.min_depth_separation_lsb << " / " << a.equal_depth_pairs
    << " |\n| primitives / clipped | " << a.prims << " / " << a.prims_clipped << " |\n"
    << "| largest lead-exponent difference of 1/w, v/w in a triangle | " << a.max_block_lead_diff << " |\n\n"
    << "## Minimal widths\n\n| field | minimal | configured | from |\n|---|---|---|---|\n";
  for (const MinWidth& w : a.widths)
    m << "| `" << w.field << "` | " << (w.min < 0 ? std::string("none") : std::to_string(w.min)) << " | " << w.current << " | "
      << w.why << " |\n";
  m << "\n## Never exercised\n\n";
  for (const std::string& u : a.unused) m << "- " << u << "\n";
  return m.str();
}

}  // namespace fxr
