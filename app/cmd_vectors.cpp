// `fxraster vectors`: golden vectors for a unit (hex + JSON manifest, docs/vectors.md),
// `fxraster vectors scene SCENE|--default` to dump a draw at every stage boundary (transaction
// vectors), and `fxraster vectors check FILE|DUMP` to validate a file against its manifest and the
// model, or a scene dump by re-stepping every stage.
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "frontend/scene.hpp"
#include "model/config/config.hpp"
#include "model/config/json_input.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/vectors/scene_dump.hpp"
#include "model/vectors/vectors.hpp"

namespace {

struct Opts {
  std::vector<std::string> args;
  std::string config;
  uint64_t seed = 1;
  uint64_t count = 1000;
  std::string out = ".";
  bool exhaustive = false;
  bool no_recompute = false;
  bool list = false;
  bool use_default = false, no_bunny = false, wireframe = false;
  int width = 0, height = 0;
  uint64_t max_fragments = 0;
  std::string state;                // scene: JSON object of "state" fields replaced
  std::vector<std::string> stages;  // scene: the stages written (default: all)
};

namespace fs = std::filesystem;

// A scene dump: a folder holding scene.json, or scene.json itself.
bool is_scene_dump(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) || fs::path(path).filename() == "scene.json";
}

int run_check_dump(const std::string& path) {
  const std::string dir = fs::is_directory(path) ? path : fs::path(path).parent_path().string();
  const fxr::RestepReport r = fxr::restep_scene_vectors(dir.empty() ? "." : dir);
  for (const auto& l : r.first) std::cout << "MISMATCH " << l << "\n";
  for (const auto& s : r.stages)
    std::cout << dir << ": " << s.stage << ": " << s.in_rows << " in, " << s.out_rows << " out, re-stepped: "
              << s.mismatches << " inputs differ\n";
  std::cout << dir << ": format, manifests and transactions OK; " << r.mismatches() << " mismatches\n";
  return r.mismatches() ? 1 : 0;
}

int run_scene(const Opts& o) {
  const bool has_scene = o.args.size() == 2;
  if (has_scene == o.use_default) throw fxr::ConfigError("vectors scene: give exactly one of SCENE or --default");
  fxr::SceneOptions so;
  so.width = o.width;
  so.height = o.height;
  so.no_optional = o.no_bunny;
  so.wireframe = o.wireframe;
  if (!o.state.empty()) {
    so.state = fxr::parse_json_input(o.state, "--state");
    if (!so.state.is_object()) throw fxr::ConfigError("--state: expected a JSON object of \"state\" fields");
  }
  if (o.wireframe && !o.use_default)
    throw fxr::ConfigError("vectors scene: --wireframe selects the default scene's wireframe variant: give it with "
                           "--default (a scene file gives its own \"lines\" objects or mesh \"wireframe\")");
  fxr::Scene sc = o.use_default ? fxr::default_scene(so) : fxr::load_scene(o.args[1], so);
  if (!o.config.empty()) fxr::apply_config_file(sc, o.config);
  const fxr::SceneDump d =
      fxr::dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, o.out, sc.name, o.stages);
  uint64_t total = 0;
  for (const auto& f : d.files) total += f.rows;
  std::cout << "wrote " << o.out << ": " << d.files.size() << " files, " << total << " transactions ("
            << sc.tris.size() << " triangles, " << sc.lines.size() << " line segments, "
            << d.stats.fragments_depth_pass
            << " fragments) and " << o.out << "/scene.json\n";
  return 0;
}

// `vectors texaddr SCENE|--default`: the texture address unit's vectors from a whole draw — every
// fragment the triangles of the scene produce (what `fxraster render` shades through the unit; line
// fragments are flat-coloured), its texture coordinates on the scene's texture size, under both
// filters and all four wrap modes (docs/texaddr.md).
int run_texaddr_scene(const Opts& o) {
  const bool has_scene = o.args.size() == 2;
  if (has_scene == o.use_default) throw fxr::ConfigError("vectors texaddr: give at most one of SCENE or --default");
  if (o.wireframe) throw fxr::ConfigError("vectors texaddr: --wireframe adds line fragments, which are not textured");
  fxr::SceneOptions so;
  so.width = o.width;
  so.height = o.height;
  so.no_optional = o.no_bunny;
  fxr::Scene sc = o.use_default ? fxr::default_scene(so) : fxr::load_scene(o.args[1], so);
  if (!o.config.empty()) fxr::apply_config_file(sc, o.config);
  if (sc.u_varying < 0 || sc.v_varying < 0)
    throw fxr::ConfigError("vectors texaddr: the scene has no texture coordinates (varyings u / v are -1)");
  const fxr::FrameOutput fo = fxr::run_raster_unit(sc.config, sc.state, sc.tris);
  std::vector<std::array<fxr::FxFloat, 2>> uv;
  uv.reserve(fo.fragments.size());
  // --max-fragments N: every k-th fragment of the draw, k = ceil(n / N) (a bounded run that still
  // spans the whole draw; docs/texaddr.md).
  const size_t n = fo.fragments.size();
  const size_t step = o.max_fragments > 0 && n > o.max_fragments ? (n + o.max_fragments - 1) / o.max_fragments : 1;
  for (size_t i = 0; i < n; i += step) uv.push_back({fo.fragments[i].var[sc.u_varying], fo.fragments[i].var[sc.v_varying]});
  const auto rows = fxr::texaddr_fragment_rows(sc.config, uv, (uint32_t)sc.texture.image.width,
                                               (uint32_t)sc.texture.image.height);
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw fxr::ConfigError(o.out + ": cannot create the folder: " + ec.message());
  const nlohmann::json extra = {{"scene", sc.name},
                                {"fragments", (uint64_t)uv.size()},
                                {"fragments_in_draw", (uint64_t)n},
                                {"fragment_step", (uint64_t)step},
                                {"texture_width", sc.texture.image.width},
                                {"texture_height", sc.texture.image.height},
                                {"row_order", "the draw's fragment order (every fragment_step-th), then filter "
                                              "(nearest, bilinear), then wrap (repeat, mirrored_repeat, "
                                              "clamp_to_edge, clamp_to_border): 8 rows per fragment"}};
  // Filter and wrap are inputs of every row (texture state, ports of fxr_texaddr): the manifest
  // records the configuration with their defaults, as the unit's other vector files do.
  fxr::Config cfg = sc.config;
  cfg.tex_addr.filter = fxr::TexAddrConfig{}.filter;
  cfg.tex_addr.wrap = fxr::TexAddrConfig{}.wrap;
  const auto m = fxr::write_unit_rows("texaddr", cfg, rows, "scene", o.out, extra);
  std::cout << "wrote " << o.out << "/" << m.hex_file << " (" << m.count << " vectors: " << uv.size()
            << " fragments x 2 filters x 4 wraps, texture " << sc.texture.image.width << " x "
            << sc.texture.image.height << ") and " << fxr::vec_manifest_path(o.out + "/" + m.hex_file) << "\n";
  return 0;
}

int run_check(const Opts& o, const std::string& path) {
  if (is_scene_dump(path)) return run_check_dump(path);
  const fxr::Config cfg = o.config.empty() ? fxr::Config{} : fxr::load_config(o.config);
  const fxr::VecFile f = fxr::read_vectors(path, o.config.empty() ? nullptr : &cfg);
  std::cout << path << ": unit " << f.manifest.unit << ", " << f.rows() << " vectors of "
            << f.manifest.layout.size() << " fields (" << f.manifest.layout.word_bits()
            << "-bit words), format and manifest OK\n";
  if (o.no_recompute) return 0;
  std::vector<std::string> first;
  const uint64_t bad = fxr::recheck_vectors(f, &first);
  for (const auto& l : first) std::cout << "STALE " << l << "\n";
  std::cout << path << ": recomputed with the model: " << (f.rows() - bad) << " agree, " << bad
            << " differ\n";
  return bad ? 1 : 0;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  std::string units;
  for (const auto& u : fxr::vector_units()) units += (units.empty() ? "" : ", ") + u.name;
  auto* unit = sub.add_option("unit", o->args,
                               "UNIT (" + units + ") to generate, `scene SCENE|--default` to dump a draw at every stage "
                               "boundary, `texaddr SCENE|--default` for the texture address unit's vectors of a "
                               "scene's fragments, or `check FILE|DUMP` to validate a vector file or a scene dump")
                   ->expected(1, 2);
  auto* list = sub.add_flag("--list", o->list, "print the units that have vectors, one per line, and exit");
  unit->excludes(list);
  sub.add_option("--config", o->config,
                 "configuration JSON (default: built-in defaults; scene, texaddr: its fields override the scene's); with "
                 "check: the manifest must match it");
  sub.add_option("--seed", o->seed, "seed of the random cases (mt19937_64; default 1)");
  sub.add_option("--count", o->count, "number of random cases (after the directed ones; default 1000)");
  sub.add_option("--out", o->out, "output folder (default: the current one): writes OUT/UNIT.hex and OUT/UNIT.json; scene: the dump");
  sub.add_flag("--exhaustive", o->exhaustive, "sweep the whole input domain instead of random cases");
  sub.add_flag("--no-recompute", o->no_recompute, "check: validate the format only, do not rerun the model");
  sub.add_flag("--default", o->use_default, "scene, texaddr: the embedded default scene");
  sub.add_flag("--no-bunny", o->no_bunny, "scene, texaddr: leave out optional meshes (the default scene's bunny)");
  sub.add_option("--max-fragments", o->max_fragments,
                 "texaddr SCENE|--default: at most N fragments, every k-th of the draw (default: all)");
  sub.add_flag("--wireframe", o->wireframe,
               "scene, with --default: the default scene's wireframe variant (the face's edges and the bunny's "
               "silhouette as line segments, as `render --default --wireframe`)");
  sub.add_option("--state", o->state,
                 "scene: a JSON object of draw-state fields replacing the scene's \"state\" ones, e.g. "
                 "'{\"depth_func\": \"greater\", \"cull\": \"front\"}' (docs/scene-format.md)");
  sub.add_option("--stages", o->stages,
                 "scene: write only these stages' files (comma-separated names, e.g. setup,traverse,interp,depth,divide; "
                 "default: every stage)")
      ->delimiter(',');
  sub.add_option("--width", o->width, "scene, texaddr: viewport width (overrides the scene's)")->check(CLI::Range(1, 16384));
  sub.add_option("--height", o->height, "scene, texaddr: viewport height (overrides the scene's)")->check(CLI::Range(1, 16384));
  sub.footer(
      "Directed corner cases come first, then --count random cases or the --exhaustive sweep.\n"
      "Every line is one hex word ($readmemh); the manifest names the fields (docs/vectors.md).\n"
      "`vectors scene` writes OUT/<stage>.in.hex and OUT/<stage>.out.hex for every stage of the\n"
      "unit, the line path's included (transactions: txn / n_out / seq / last) and OUT/scene.json;\n"
      "`vectors check OUT` re-reads the dump and re-steps every stage against it.\n"
      "`vectors texaddr SCENE|--default` writes the texture address unit's vectors of the scene's\n"
      "fragments (both filters, every wrap mode).");
  return [o]() {
    if (o->list) {
      for (const auto& u : fxr::vector_units()) std::cout << u.name << "\n";
      return 0;
    }
    if (o->args.empty()) throw fxr::ConfigError("vectors: missing the UNIT (one of `fxraster vectors --list`) or `check FILE`");
    if (o->args[0] == "scene") return run_scene(*o);
    if (o->args[0] == "texaddr" && (o->args.size() == 2 || o->use_default)) return run_texaddr_scene(*o);
    if (o->args[0] == "check") {
      if (o->args.size() != 2) throw fxr::ConfigError("vectors check: expected one FILE (the .hex)");
      return run_check(*o, o->args[1]);
    }
    if (o->args.size() != 1) throw fxr::ConfigError("vectors: expected one UNIT");
    const fxr::Config cfg = o->config.empty() ? fxr::Config{} : fxr::load_config(o->config);
    std::error_code ec;
    std::filesystem::create_directories(o->out, ec);
    if (ec) throw fxr::ConfigError(o->out + ": cannot create the folder: " + ec.message());
    const auto m = fxr::write_unit_vectors(o->args[0], cfg, o->seed, o->count, o->exhaustive, o->out);
    std::cout << "wrote " << o->out << "/" << m.hex_file << " (" << m.count << " vectors:";
    for (const auto& c : m.cases) std::cout << " " << c.count << " " << c.kind;
    std::cout << ") and " << fxr::vec_manifest_path(o->out + "/" + m.hex_file) << "\n";
    return 0;
  };
}

fxr::app::Registrar reg("vectors",
                        "golden vectors for a unit (hex for $readmemh + JSON manifest), or check a vector file",
                        setup);

}  // namespace
