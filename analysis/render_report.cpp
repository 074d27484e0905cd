// The render report (analysis/render_report.hpp).
#include "analysis/render_report.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "analysis/line_analysis.hpp"
#include "analysis/render_images.hpp"
#include "analysis/texel_errors.hpp"
#include "model/stages/texfilter.hpp"
#include "model/unit/threads.hpp"

namespace fxr {

using json = nlohmann::json;

namespace {
// Every stream is checked: a file that cannot be written fails the command (never exit 0).
void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw std::runtime_error(path + ": cannot write");
}
}  // namespace

RenderSummary render_with_report(const Scene& sc, const RenderOptions& o) {
  {
    // The texture address unit takes sizes in [1, 2^tex_addr.size_bits] (model/stages/texaddr.hpp).
    const int64_t most = int64_t{1} << sc.config.tex_addr.size_bits;
    const Image& t = sc.texture.image;
    if (t.width < 1 || t.height < 1 || t.width > most || t.height > most)
      throw ConfigError(sc.source + ": texture " + sc.texture.description + ": " + std::to_string(t.width) + "x" +
                        std::to_string(t.height) + " texels is outside the texture address unit's sizes 1 … " +
                        std::to_string(most) + " (field 'tex_addr.size_bits' = " +
                        std::to_string(sc.config.tex_addr.size_bits) + ")");
  }
  std::filesystem::create_directories(o.out);
  using clk = std::chrono::steady_clock;
  auto t0 = clk::now();
  ThreadOptions to;
  to.threads = o.threads;
  const FrameOutput fo = run_raster_unit(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, to);
  auto t1 = clk::now();
  const RefFrame rf = run_reference(sc.state, sc.tris);
  auto t2 = clk::now();

  // Images.
  const Image img = shade_model(sc, fo);
  write_png(o.out + "/image.png", img);
  write_png(o.out + "/reference.png", shade_reference(sc, rf));
  const uint32_t clear_code = (uint32_t)((1ull << sc.config.raster.depth_bits()) - 1);
  uint32_t dlo = 0, dhi = 0;
  write_png(o.out + "/depth.png", depth_image(fo, clear_code, &dlo, &dhi));
  json other_mode;
  if (!o.no_affine_image) {
    DrawState st2 = sc.state;
    st2.interp = o.affine ? InterpMode::Perspective : InterpMode::Affine;
    Scene sc2 = sc;
    sc2.state = st2;
    sc2.line_state.interp = st2.interp;
    const FrameOutput fo2 = run_raster_unit(sc.config, st2, sc.tris, sc2.line_state, sc.lines, to);
    const Image img2 = shade_model(sc2, fo2);
    const std::string name = o.affine ? "image_perspective.png" : "image_affine.png";
    write_png(o.out + "/" + name, img2);
    write_png(o.out + "/side_by_side.png", o.affine ? side_by_side(img2, img) : side_by_side(img, img2));
    const RenderErrors e2 = compare_to_reference(sc2, fo2);
    other_mode = {{"image", name}, {"interp", o.affine ? "perspective" : "affine"}, {"fragments", fo2.fragments.size()}};
    if (sc.u_varying >= 0)
      other_mode["u_error_vs_perspective_reference_texels"] = e2.var_texel[sc.u_varying].to_json();
  }
  write_fragment_dump(o.out, sc, fo);

  // Coverage: both pipelines with the depth test off.
  DrawState nod = sc.state;
  nod.depth_test = false;
  const FrameOutput fo_cov = run_raster_unit(sc.config, nod, sc.tris, to);
  const RefFrame rf_cov = run_reference(nod, sc.tris);
  const CoverageDiff cov = compare_coverage(fo_cov.fragments, rf_cov.fragments);
  const RenderErrors err = compare_to_reference(sc, fo);
  if (sc.u_varying >= 0) write_png(o.out + "/error_heatmap.png", heat_image(err.heat, sc.state.viewport_w, sc.state.viewport_h));
  const SpotChecks spot = exact_spot_checks(sc, fo, o.spot_checks);
  const ErrStat snap = snap_errors(sc);
  const TexelErrors texel = texel_errors(sc, fo, spot);

  // Final images: pixels that differ in colour.
  const Image rimg = shade_reference(sc, rf);
  uint64_t pix_diff = 0;
  uint32_t pix_max_levels = 0;  // largest channel difference of a pixel
  for (size_t i = 0; i < img.rgba.size(); ++i) {
    pix_diff += img.rgba[i] != rimg.rgba[i];
    for (int k = 0; k < kTexChannels; ++k) {
      const int a = (img.rgba[i] >> (kTexChannelBits * k)) & 0xff, b = (rimg.rgba[i] >> (kTexChannelBits * k)) & 0xff;
      pix_max_levels = std::max(pix_max_levels, (uint32_t)std::abs(a - b));
    }
  }

  // Accounting: every input primitive is drawn, culled (with the reason) or rejected.
  const RasterStats& s = fo.stats;
  const uint64_t accounted = s.prims_drawn + s.prims_culled_outside + s.prims_culled_zero_area +
                             s.prims_culled_backface + s.prims_culled_no_samples + s.prims_rejected_nan +
                             s.prims_rejected_inf + s.prims_rejected_range;
  const LineStats& ls = s.lines;
  const bool lines_accounted = ls.accounted() == ls.in && ls.in == sc.lines.size();
  uint64_t line_frags_written = 0;
  for (const Fragment& f : fo.fragments) line_frags_written += f.prim >= sc.tris.size();
  const LineChecks lck = sc.lines.empty() ? LineChecks{} : line_checks(sc, fo, o.spot_checks);

  json stats = {{"scene", sc.name}, {"source", sc.source}, {"viewport", {sc.state.viewport_w, sc.state.viewport_h}},
                {"interp", sc.state.interp == InterpMode::Affine ? "affine" : "perspective"},
                {"triangles", sc.tris.size()}, {"model", stats_json(s)}, {"reference", ref_stats_json(rf.stats)},
                {"all_primitives_accounted", accounted == s.prims_in && s.prims_in == sc.tris.size() && lines_accounted}};
  if (!sc.lines.empty()) stats["lines"] = sc.lines.size();
  write_text(o.out + "/stats.json", stats.dump(2) + "\n");

  const int nv = sc.state.num_varyings;
  json rep = {{"scene", sc.name}, {"source", sc.source}, {"notes", sc.notes}, {"config", config_to_json(sc.config)},
              {"stats", stats}, {"texture", sc.texture.description}};
  json vars = json::array();
  for (int k = 0; k < nv; ++k)
    vars.push_back({{"varying", k}, {"ulp", err.var_ulp[k].to_json()}, {"abs", err.var_abs[k].to_json()},
                    {"texels", err.var_texel[k].to_json()}, {"texel_differs", err.texel_diff[k]},
                    {"exact_spot_ulp", spot.var_ulp[k].to_json()},
                    {"exact_ideal_ulp", spot.ideal_var_ulp[k].to_json()}});
  rep["errors_vs_double_reference"] = {{"varyings", vars}, {"depth_lsb", err.depth_lsb.to_json()},
                                       {"fragments_reference_undefined", err.ref_invalid},
                                       {"varying_reference_zero", err.var_zero_ref}, {"worst", err.worst}};
  rep["vertex_snap_px"] = snap.to_json();
  rep["exact_spot_checks"] = {{"checked", spot.checked}, {"not_covered_exactly", spot.not_covered_exactly},
                              {"depth_lsb", spot.depth_lsb.to_json()}};
  rep["exact_ideal_checks"] = {{"checked", spot.ideal_checked}, {"ideal_undefined", spot.ideal_undefined},
                               {"depth_lsb", spot.ideal_depth_lsb.to_json()}};
  rep["coverage_depth_test_off"] = {{"model", cov.model}, {"reference", cov.ref}, {"common", cov.common},
                                    {"model_only", cov.model_only}, {"reference_only", cov.ref_only},
                                    {"examples", cov.examples}};
  if (!sc.lines.empty()) {
    json lv = json::array();
    for (int k = 0; k < (int)lck.var_ulp.size(); ++k)
      lv.push_back({{"varying", k}, {"exact_own_ulp", lck.var_ulp[k].to_json()}, {"exact_ideal_ulp", lck.ideal_var_ulp[k].to_json()}});
    rep["lines"] = {{"segments", sc.lines.size()}, {"stats", stats["model"]["lines"]}, {"fragments_written", line_frags_written},
                    {"checked_own", lck.checked}, {"checked_ideal", lck.ideal_checked}, {"ideal_undefined", lck.ideal_undefined},
                    {"depth_lsb_own", lck.depth_lsb.to_json()}, {"depth_lsb_ideal", lck.ideal_depth_lsb.to_json()},
                    {"varyings", lv}};
  }
  rep["image_pixels_differing_from_reference"] = pix_diff;
  rep["image_max_channel_difference_levels"] = pix_max_levels;
  rep["texture_filter"] = sc.config.tex_addr.filter == TexFilter::Bilinear ? "bilinear" : "nearest";
  rep["texel_errors"] = texel.to_json();
  rep["other_interp_mode"] = other_mode;
  rep["depth_image_range"] = dlo <= dhi ? json{dlo, dhi} : json(nullptr);
  write_text(o.out + "/report.json", rep.dump(2) + "\n");

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
    md << "| " << other_mode["interp"].get<std::string>() << " interpolation (docs/references.md#seed-000: "
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
  md << "| rejected: NaN / Inf in a position / range | " << s.prims_rejected_nan << " / " << s.prims_rejected_inf << " / "
     << s.prims_rejected_range << " | " << rf.stats.prims_rejected_nonfinite << " (non-finite) |\n";
  md << "| of those in: NaN / ±Inf varying replaced by 0 / ±FLT_MAX (docs/pipeline.md, stage 1) | "
     << s.prims_varying_nonfinite << " | " << rf.stats.prims_varying_nonfinite << " |\n";
  md << "| fragments generated | " << s.fragments_generated << " | " << rf.stats.fragments_generated << " |\n";
  md << "| fragments passing depth | " << s.fragments_depth_pass << " | " << rf.stats.fragments_depth_pass << " |\n\n";
  if (!sc.lines.empty()) {
    md << "## Lines\n\n" << sc.lines.size() << " segments drawn after the triangles (rule `"
       << (sc.config.line.rule == LineRule::Midpoint ? "midpoint" : "diamond_exit") << "`"
       << (sc.config.line.rule == LineRule::Midpoint
               ? std::string(", endpoints `") + (sc.config.line.endpoints == LineEndpoints::HalfOpen ? "half_open" : "closed") + "`"
               : std::string())
       << "; depth test " << (sc.line_state.depth_test ? "on" : "off") << "; docs/lines.md), primitives "
       << sc.tris.size() << "…" << sc.tris.size() + sc.lines.size() - 1 << " in the fragment dump.\n\n"
       << "| | triangles | lines |\n|---|---|---|\n"
       << "| in | " << s.prims_in << " | " << ls.in << " |\n"
       << "| drawn | " << s.prims_drawn << " | " << ls.drawn << " |\n"
       << "| trivially accepted / clipped | " << s.prims_trivial_accept << " / " << s.prims_clipped << " | "
       << ls.trivial_accept << " / " << ls.clipped << " |\n"
       << "| clip vertices created | " << s.clip_vertices_created << " | " << ls.clip_vertices_created << " |\n"
       << "| culled: outside | " << s.prims_culled_outside << " | " << ls.culled_outside << " |\n"
       << "| culled: no samples / no pixels | " << s.prims_culled_no_samples << " | " << ls.culled_no_pixels << " |\n"
       << "| rejected: NaN / Inf / range | " << s.prims_rejected_nan << " / " << s.prims_rejected_inf << " / "
       << s.prims_rejected_range << " | " << ls.rejected_nan << " / " << ls.rejected_inf << " / " << ls.rejected_range << " |\n"
       << "| fragments generated | " << s.fragments_generated - ls.fragments_generated << " | " << ls.fragments_generated << " |\n"
       << "| fragments written (passed depth) | " << fo.fragments.size() - line_frags_written << " | " << line_frags_written << " |\n\n"
       << "Every segment accounted for (drawn + culled + rejected = in): **" << (lines_accounted ? "yes" : "NO")
       << "**.\n\nExact checks (GMP) of " << lck.checked << " line fragments (evenly spaced, of " << lck.fragments
       << "): against the **ideal** (GL's t, depth and perspective-correct varyings from the unsnapped float32 "
          "endpoints; " << lck.ideal_undefined << " fragments of segments with an endpoint at w ≤ 0 skipped) and "
          "against the model's **own quantised segment** (the positions, z, 1/w and v/w its line setup sees). "
          "The error tables further down are the triangles'.\n\n"
       << "| output | vs ideal: max | mean | vs own segment: max | mean |\n|---|---|---|---|---|\n";
    for (int k = 0; k < (int)lck.var_ulp.size(); ++k)
      md << "| varying " << k << " (ulp) | " << fmt_num(lck.ideal_var_ulp[k].max) << " | " << fmt_num(lck.ideal_var_ulp[k].mean())
         << " | " << fmt_num(lck.var_ulp[k].max) << " | " << fmt_num(lck.var_ulp[k].mean()) << " |\n";
    md << "| depth (LSB) | " << fmt_num(lck.ideal_depth_lsb.max) << " | " << fmt_num(lck.ideal_depth_lsb.mean()) << " | "
       << fmt_num(lck.depth_lsb.max) << " | " << fmt_num(lck.depth_lsb.mean()) << " |\n\n";
  }
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
    md << "| " << name << " | " << unit << " | " << fmt_num(e.max) << " | " << fmt_num(e.mean()) << " | " << fmt_num(e.rms())
       << " | " << fmt_num(e.pct(0.5)) << " | " << fmt_num(e.pct(0.99)) << " | " << fmt_num(e.pct(0.999)) << " | " << extra << " |\n";
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
     << img.rgba.size() << " (largest channel difference " << pix_max_levels << " levels of 255).\n\n";
  if (texel.textured) {
    const int fb = texel.weight_frac_bits;
    md << "## Texel error: the texture address unit, both filters\n\n"
          "The shaded image uses the **" << rep["texture_filter"].get<std::string>() << "** filter (`tex_addr.filter`, "
          "`render --filter`), wrap `" << texel.wrap << "`, bilinear weights with " << fb << " fraction bits "
          "(docs/texaddr.md). Both filters are measured here whatever the image uses. Each fragment's u, v codes go "
          "through the texture address unit and the texel filter (integer), and are compared with: the exact address "
          "of the **same** codes (GMP: how well the unit rounds; every fragment), the exact address of the **ideal** "
          "u, v (the exact spot-check sample above: what a user sees), and the same rules on the **double reference**'s "
          "u, v (every fragment). Same texels: every index and border flag of both axes equal; weight error: "
          "|unit weight − exact fraction · 2^" << fb << "| in LSBs, on fragments with the same texels (both axes); "
          "colour error: largest channel difference between the unit's colour and the unrounded blend at the "
          "reference's address, in 8-bit levels.\n\n"
          "| filter | against | fragments | same texels | weight error max (LSB) | mean | colour error max (levels) | mean | p99 |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (const TexelFilterErrors& fe : texel.filters) {
      const bool bil = fe.filter == "bilinear";
      auto lrow = [&](const char* against, const TexelLevel& l) {
        md << "| " << fe.filter << " | " << against << " | " << l.checked << " | " << l.same_texels << " ("
           << fmt_num(l.checked ? 100.0 * (double)l.same_texels / (double)l.checked : 0.0, 4) << " %) | "
           << (bil ? fmt_num(l.weight_lsb.max) : std::string("—")) << " | "
           << (bil ? fmt_num(l.weight_lsb.mean()) : std::string("—")) << " | " << fmt_num(l.colour.max) << " | "
           << fmt_num(l.colour.mean()) << " | " << fmt_num(l.colour.pct(0.99)) << " |\n";
      };
      lrow("exact, own coordinates", fe.own);
      lrow("exact, ideal", fe.ideal);
      lrow("double reference", fe.ref);
    }
    md << "\n";
    if (texel.coords_exp_outside)
      md << "**" << texel.coords_exp_outside << " u, v codes have an exponent outside the unit's "
         << "tex_addr.exp_bits field** (the model's result is exact; the RTL would read a different value).\n\n";
  }
  md << "## Exact spot checks (GMP): against the ideal and against the model's own triangle\n\n"
     << spot.checked << " fragments (evenly spaced in draw order) re-evaluated exactly at two levels: against the "
        "**ideal** (the exact solve of the unsnapped float32 input at the pixel centre, `fxr::IdealJudge`: what a "
        "user sees) and against exact arithmetic on the model's **own quantised triangle** (the setup triangles of "
        "`fxr::geometry`, with the positions the planes are set up from: raster.attr_subpixel_bits = "
     << rc.attr_subpixel_bits << (rc.attr_subpixel_bits > rc.subpixel_bits ? " (attribute positions)" : " (the snapped positions)")
     << "; how well each rounding is done). docs/pipeline.md, \"Accuracy against the ideal\".\n\n"
        "| output | vs ideal: max | mean | vs own triangle: max | mean |\n|---|---|---|---|---|\n";
  for (int k = 0; k < nv; ++k)
    md << "| varying " << k << " (ulp) | " << fmt_num(spot.ideal_var_ulp[k].max) << " | "
       << fmt_num(spot.ideal_var_ulp[k].mean()) << " | " << fmt_num(spot.var_ulp[k].max) << " | "
       << fmt_num(spot.var_ulp[k].mean()) << " |\n";
  md << "| depth (LSB) | " << fmt_num(spot.ideal_depth_lsb.max) << " | " << fmt_num(spot.ideal_depth_lsb.mean())
     << " | " << fmt_num(spot.depth_lsb.max) << " | " << fmt_num(spot.depth_lsb.mean()) << " |\n\n";
  if (spot.ideal_undefined) md << spot.ideal_undefined << " checked fragments where the ideal is undefined (edge-on) were skipped.\n\n";
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
       << "u error against the perspective-correct reference, in texels: max " << fmt_num(a["max"].get<double>())
       << ", mean " << fmt_num(a["mean"].get<double>()) << " (" << other_mode["fragments"].get<uint64_t>() << " fragments).\n";
  }
  md.close();
  if (!md) throw std::runtime_error(o.out + "/report.md: cannot write");

  RenderSummary r;
  r.fragments = fo.fragments.size();
  r.model_seconds = std::chrono::duration<double>(t1 - t0).count();
  r.reference_seconds = std::chrono::duration<double>(t2 - t1).count();
  r.err = err;
  r.spot = spot;
  r.cov = cov;
  r.all_accounted = accounted == s.prims_in && s.prims_in == sc.tris.size() && lines_accounted;
  return r;
}


}  // namespace fxr
