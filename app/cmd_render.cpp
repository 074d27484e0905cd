// `fxraster render`: a scene through the bit-accurate raster unit and through the double
// reference; writes the shaded image, the depth image, the fragment dump, statistics and an
// error report (report.md / report.json). Deterministic: no timings in the files.
// The work is analysis/render_report.hpp's; this file parses options and prints a summary.
#include <climits>
#include <filesystem>
#include <fstream>
#include <iostream>


#include "analysis/render_report.hpp"
#include "command.hpp"
#include "frontend/scene.hpp"
#include "out_folder.hpp"
#include "scene_input.hpp"
#include "model/config/config.hpp"
#include "model/config/json_input.hpp"

namespace {

using nlohmann::json;

struct Opts {
  fxr::app::SceneInput in;
  std::string out;
  bool wireframe = false, affine = false, no_affine_image = false, quiet = false;
  int spot_checks = 2000, threads = 1;
  std::string filter;  // "" (the configuration's tex_addr.filter), nearest, bilinear
};

namespace fs = std::filesystem;

// ---- the output folder ---------------------------------------------------------------------------
// Written beside --out and renamed at the end; a failed run removes the previous run's files; a
// folder holding other files is never replaced (app/out_folder.hpp; docs/reports.md, "Render output").

// Every file render_with_report writes (analysis/render_report.cpp).
const char* const kRenderFiles[] = {"image.png",         "reference.png",  "depth.png",      "image_affine.png",
                                    "image_perspective.png", "side_by_side.png", "error_heatmap.png", "fragments.csv",
                                    "fragments.json",    "stats.json",     "report.md",      "report.json"};

bool is_render_file(const std::string& name) {
  for (const char* f : kRenderFiles)
    if (name == f) return true;
  return false;
}

// PNGs are written by stb_image_write, whose sizes are C ints: the largest image (side by side:
// 2W + 8 gap pixels wide, RGBA) must stay below INT_MAX bytes. Checked before any work.
constexpr int64_t kRgbaBytes = 4;
constexpr int64_t kSideBySideGap = 8;
void check_image_sizes(const fxr::Scene& sc, bool no_affine_image, const std::string& where) {
  const int64_t w = sc.state.viewport_w, h = sc.state.viewport_h;
  const int64_t widest = no_affine_image ? w : 2 * w + kSideBySideGap;
  if (widest * h * kRgbaBytes > INT_MAX)
    throw fxr::ConfigError(where + ": viewport " + std::to_string(w) + "x" + std::to_string(h) + ": the " +
                           (no_affine_image ? "image" : "side-by-side image") + " (" + std::to_string(widest) + "x" +
                           std::to_string(h) + " RGBA) exceeds the PNG writer's 2 GiB limit" +
                           (no_affine_image ? "" : "; --no-affine-image drops it") + " (or use --width / --height)");
}

// ---- the command --------------------------------------------------------------------------------

int run_into(const Opts& o, const fs::path& out);

int run(const Opts& o) {
  fxr::app::check_scene_source(o.in, "render");  // a usage error: the previous output stays
  return fxr::app::write_out_folder({"render", is_render_file, ""}, fxr::app::out_path(o.out),
                                    [&](const fs::path& tmp) { return run_into(o, tmp); });
}

int run_into(const Opts& o, const fs::path& tmp) {
  if (o.wireframe && !o.in.use_default)
    throw fxr::ConfigError("--wireframe selects the default scene's wireframe variant: give it with --default "
                           "(a scene file gives its own \"lines\" objects or mesh \"wireframe\")");
  fxr::Scene sc = fxr::app::load_scene_input(o.in, "render", o.wireframe);
  if (o.affine) sc.state.interp = sc.line_state.interp = fxr::InterpMode::Affine;
  // --filter: the texture filter of the shaded images (tex_addr.filter, docs/texaddr.md).
  if (!o.filter.empty())
    sc.config.tex_addr.filter = o.filter == "bilinear" ? fxr::TexFilter::Bilinear : fxr::TexFilter::Nearest;
  check_image_sizes(sc, o.no_affine_image, o.in.use_default ? "<default scene>" : o.in.scene);
  for (const auto& n : sc.notes) std::cerr << "fxraster render: note: " << n << "\n";

  fxr::RenderOptions ro;
  ro.out = tmp.string();
  ro.affine = o.affine;
  ro.no_affine_image = o.no_affine_image;
  ro.spot_checks = o.spot_checks;
  ro.threads = o.threads;
  const fxr::RenderSummary r = fxr::render_with_report(sc, ro);
  const int nv = sc.state.num_varyings;
  if (!o.quiet) {
    std::cout << "fxraster render: " << sc.name << "\n  " << sc.tris.size() << " triangles, "
              << (sc.lines.empty() ? std::string() : std::to_string(sc.lines.size()) + " lines, ")
              << r.fragments << " fragments written; model " << r.model_seconds
              << " s, reference " << r.reference_seconds << " s\n";
    for (int k = 0; k < nv; ++k)
      std::cout << "  varying " << k << ": max " << fxr::fmt_num(r.err.var_ulp[k].max) << " ulp vs double reference, "
                << fxr::fmt_num(r.spot.var_ulp[k].max) << " ulp vs exact (snapped)\n";
    std::cout << "  depth: max " << fxr::fmt_num(r.err.depth_lsb.max) << " LSB vs double reference, " << fxr::fmt_num(r.spot.depth_lsb.max)
              << " LSB vs exact (snapped)\n  coverage: " << r.cov.model_only << " model-only, " << r.cov.ref_only
              << " reference-only (of " << r.cov.common << " common)\n  wrote " << o.out << "/report.md\n";
  }
  return r.all_accounted ? 0 : 3;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  fxr::app::add_scene_source(sub, o->in,
                             "render the embedded default scene (a checkerboard face at an angle, "
                             "docs/references.md#seed-000, + the glmark2 bunny)");
  sub.add_option("--out", o->out, "output directory (created; replaced only when it holds nothing but render's "
                                  "files): image.png, reference.png, depth.png, image_affine.png (with --affine: "
                                  "image_perspective.png), side_by_side.png, error_heatmap.png, fragments.csv/.json, "
                                  "stats.json, report.md/.json")
      ->required();
  sub.add_flag("--wireframe", o->wireframe,
               "with --default: add the wireframe of the checkerboard face and the bunny's silhouette edges as "
               "line segments (docs/lines.md)");
  sub.add_flag("--affine", o->affine, "interpolate varyings affinely in screen space (the wrong image of docs/references.md#seed-000) "
                                      "for the main image; the extra image is then the perspective one");
  sub.add_option("--filter", o->filter,
                 "texture filter of the shaded images: nearest or bilinear (default: the configuration's "
                 "tex_addr.filter; docs/texaddr.md); the report measures both")
      ->check(CLI::IsMember({"nearest", "bilinear"}));
  sub.add_flag("--no-affine-image", o->no_affine_image, "do not render the second image in the other interpolation mode");
  fxr::app::add_scene_overrides(sub, o->in);
  sub.add_option("--spot-checks", o->spot_checks, "fragments re-evaluated exactly with GMP (default 2000)")
      ->check(CLI::Range(0, 1000000));
  sub.add_option("--threads", o->threads,
                 "model threads (default 1; the output is bit-identical for every count, docs/speed.md)")
      ->check(CLI::Range(1, 256));
  sub.add_flag("--quiet", o->quiet, "print nothing on success");
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("render",
                        "render a scene through the model and the double reference: images, fragment dump, "
                        "statistics and an error report",
                        setup);

}  // namespace
