// `fxraster cycles SCENE|--default [--config F] --out DIR`: the cycle-approximate SystemC model
// (sc/cycle_model.hpp, docs/cycles.md) on a scene: clocks per frame, triangles and fragments per
// clock, per-stage busy / stalled / starved clocks, the bottleneck stage, a timeline of stage
// occupancy (timeline.csv; timeline.png by scripts/plot_cycles.py) and a small sweep over the
// architecture knobs (ArchConfig, the unit "arch" of a configuration file).
//
// Writes DIR/cycles.json, DIR/report.md, DIR/timeline.csv, DIR/sweep.csv and DIR/timeline.png.
// --rtl: the same scene through the RTL unit too (`fxraster cosim` into DIR/rtl: the whole unit
// under Verilator, every stage boundary compared with the model), its clocks and wall clock
// beside the model's — the deviation and the speed ratio measured in the same run.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <sys/wait.h>

#include "command.hpp"
#include "scene_input.hpp"
#include "frontend/scene.hpp"
#include "model/config/arch_config.hpp"
#include "model/config/json_input.hpp"
#include "sc/cycle_model.hpp"

namespace {

namespace fs = std::filesystem;
using fxr::cyc::CycleRun;

struct Opts {
  fxr::app::SceneInput in;  // its --config also sets the architecture knobs (apply_config below)
  std::string out;
  bool no_sweep = false, no_plot = false, quiet = false, rtl = false;
  int bins = 200;
};

using fxr::app::quote;

// The scene's configuration with the fields of F (the model's number formats, unit by unit,
// as `render --config`), and the knobs of F's unit "arch".
fxr::ArchConfig apply_config(fxr::Scene& sc, const std::string& path) {
  nlohmann::json j = fxr::read_json_file(path, "configuration file");
  fxr::ArchConfig arch;
  if (j.is_object() && j.contains("arch")) {
    arch = fxr::arch_from_json(j.at("arch"), path);
    j.erase("arch");
  }
  fxr::config_fields_from_json(j, path);
  nlohmann::json merged = fxr::config_to_json(sc.config);
  merged.merge_patch(j);
  sc.config = fxr::config_from_json(merged, path);
  return arch;
}

double per(uint64_t a, uint64_t b) { return b ? (double)a / (double)b : 0.0; }

nlohmann::json run_json(const CycleRun& r) {
  nlohmann::json j;
  j["clocks"] = r.clocks;
  j["primitives"] = r.primitives;
  j["triangles"] = r.triangles;
  j["triangles_drawn"] = r.drawn;
  j["spans"] = r.spans;
  j["fragments_generated"] = r.samples;
  j["fragments_passed"] = r.passed;
  j["triangles_per_clock"] = per(r.triangles, r.clocks);
  j["fragments_per_clock"] = per(r.samples, r.clocks);
  j["bottleneck"] = fxr::cyc::stage_name(r.bottleneck());
  j["sim_seconds"] = r.seconds;
  nlohmann::json st = nlohmann::json::object();
  for (int s = 0; s < fxr::cyc::kNumStages; ++s) {
    const fxr::cyc::StageClocks& c = r.stage[(size_t)s];
    st[fxr::cyc::stage_name(s)] = {{"in", c.in}, {"out", c.out}, {"busy", c.busy}, {"stalled", c.stalled}, {"starved", c.starved}};
  }
  j["stages"] = st;
  return j;
}

// Occupancy per bin of the frame: the fraction of the bin's clocks each stage was busy.
void write_timeline(const CycleRun& r, int bins, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot write");
  const uint64_t t0 = r.first_in, len = std::max<uint64_t>(1, r.clocks);
  const uint64_t w = std::max<uint64_t>(1, (len + (uint64_t)bins - 1) / (uint64_t)bins);
  const size_t nb = (size_t)((len + w - 1) / w);
  std::vector<std::vector<uint64_t>> busy(fxr::cyc::kNumStages, std::vector<uint64_t>(nb, 0));
  for (int s = 0; s < fxr::cyc::kNumStages; ++s)
    for (const auto& iv : r.busy[(size_t)s]) {
      uint64_t b = std::max(iv.first, t0) - t0, e = std::min(iv.second, t0 + len) - t0;
      while (b < e) {
        const size_t k = (size_t)(b / w);
        const uint64_t end = std::min(e, (uint64_t)(k + 1) * w);
        busy[(size_t)s][k] += end - b;
        b = end;
      }
    }
  f << "clock";
  for (int s = 0; s < fxr::cyc::kNumStages; ++s) f << "," << fxr::cyc::stage_name(s);
  f << "\n";
  for (size_t k = 0; k < nb; ++k) {
    f << k * w;
    for (int s = 0; s < fxr::cyc::kNumStages; ++s) f << "," << std::setprecision(4) << per(busy[(size_t)s][k], w);
    f << "\n";
  }
}

struct Variant {
  std::string label;
  fxr::ArchConfig arch;
};

std::vector<Variant> sweep_variants(const fxr::ArchConfig& base) {
  std::vector<Variant> v;
  auto add = [&](const std::string& label, auto&& edit) {
    fxr::ArchConfig a = base;
    edit(a);
    v.push_back({label, a});
  };
  add("baseline", [](fxr::ArchConfig&) {});
  add("interp_div_steps 8", [](fxr::ArchConfig& a) { a.interp_div_steps = 8; });
  add("interp_div_steps 16", [](fxr::ArchConfig& a) { a.interp_div_steps = 16; });
  add("interp_div_steps 2", [](fxr::ArchConfig& a) { a.interp_div_steps = 2; });
  add("tri_fifo_depth 16", [](fxr::ArchConfig& a) { a.tri_fifo_depth = 16; });
  add("link_depth 4", [](fxr::ArchConfig& a) { a.link_depth = 4; });
  add("divide_lanes 1", [](fxr::ArchConfig& a) { a.divide_lanes = 1; });
  add("setup_units 2", [](fxr::ArchConfig& a) { a.setup_units = 2; });
  add("mem_latency 8", [](fxr::ArchConfig& a) { a.mem_latency = 8; });
  add("mem_latency 8, depth_queue_depth 16", [](fxr::ArchConfig& a) {
    a.mem_latency = 8;
    a.depth_queue_depth = 16;
  });
  add("depth_write_port 0", [](fxr::ArchConfig& a) { a.depth_write_port = 0; });
  add("viewport_lanes 6", [](fxr::ArchConfig& a) { a.viewport_lanes = 6; });
  add("interp_div_steps 8, viewport_lanes 6", [](fxr::ArchConfig& a) {
    a.interp_div_steps = 8;
    a.viewport_lanes = 6;
  });
  return v;
}

int run(const Opts& o) {
  fxr::app::check_scene_source(o.in, "cycles");
  if (o.bins < 1 || o.bins > 100000) throw fxr::ConfigError("cycles: --bins: " + std::to_string(o.bins) + " is not in 1 … 100000");
  // The RTL runs at its own parameters on the scene as it is: nothing that changes them.
  if (o.rtl && (!o.in.config.empty() || o.in.width || o.in.height || o.in.no_bunny))
    throw fxr::ConfigError("cycles: --rtl runs the scene as fxraster cosim does: not with --config, --width, --height or --no-bunny");
  fxr::app::SceneInput scene_only = o.in;
  scene_only.config.clear();  // applied below with its unit "arch"
  fxr::Scene sc = fxr::app::load_scene_input(scene_only, "cycles");
  fxr::ArchConfig arch;
  if (!o.in.config.empty()) arch = apply_config(sc, o.in.config);
  fs::create_directories(o.out);

  fxr::cyc::CycleOptions opt;
  opt.timeline = true;
  fxr::FrameOutput f;
  const CycleRun r = fxr::cyc::run_unit_cycles(sc.config, arch, sc.state, sc.tris, f, nullptr, opt);
  write_timeline(r, o.bins, o.out + "/timeline.csv");

  // The RTL on the same scene (fxraster cosim: exit 0 match, 1 mismatch, 2 bad input).
  nlohmann::json rtl;
  if (o.rtl) {
    const std::string dir = o.out + "/rtl";
    std::vector<std::string> args = {o.in.use_default ? std::string("--default") : o.in.scene, "--out", dir};
    const int rc = fxr::app::run_cosim(args);
    if (rc != 0) throw std::runtime_error("cycles --rtl: fxraster cosim exited " + std::to_string(rc) + " (" + dir + "/report.md)");
    const nlohmann::json rep = fxr::read_json_file(dir + "/report.json", "cosim report");
    const nlohmann::json sp = fxr::read_json_file(dir + "/speed.json", "cosim speed");
    const uint64_t clocks = rep.at("cycles").at("first_input_to_last_output").get<uint64_t>();
    const double secs = sp.at("rtl_seconds").get<double>();
    rtl = {{"clocks", clocks},
           {"seconds", secs},
           {"deviation", clocks ? ((double)r.clocks - (double)clocks) / (double)clocks : 0.0},
           {"systemc_seconds", r.seconds},
           {"speed_ratio", r.seconds > 0 ? secs / r.seconds : 0.0},
           {"report", "rtl/report.md"}};
  }

  std::vector<std::pair<Variant, CycleRun>> sweep;
  if (!o.no_sweep)
    for (const Variant& v : sweep_variants(arch)) {
      fxr::FrameOutput g;
      sweep.emplace_back(v, v.label == "baseline" ? r : fxr::cyc::run_unit_cycles(sc.config, v.arch, sc.state, sc.tris, g, nullptr));
    }

  nlohmann::json j;
  j["scene"] = sc.source;
  j["arch"] = fxr::arch_to_json(arch);
  j["run"] = run_json(r);
  if (o.rtl) j["rtl"] = rtl;
  nlohmann::json sj = nlohmann::json::array();
  for (const auto& [v, s] : sweep)
    sj.push_back({{"variant", v.label}, {"arch", fxr::arch_to_json(v.arch)}, {"clocks", s.clocks},
                  {"speedup", per(r.clocks, s.clocks)}, {"bottleneck", fxr::cyc::stage_name(s.bottleneck())}});
  j["sweep"] = sj;
  {
    std::ofstream jf(o.out + "/cycles.json");
    jf << j.dump(2) << "\n";
    std::ofstream cf(o.out + "/sweep.csv");
    cf << "variant,clocks,speedup,bottleneck\n";
    for (const auto& [v, s] : sweep)
      cf << "\"" << v.label << "\"," << s.clocks << "," << per(r.clocks, s.clocks) << "," << fxr::cyc::stage_name(s.bottleneck()) << "\n";
  }

  // The plot.
  std::string plot_note;
  if (!o.no_plot) {
    const std::string script = std::string(FXR_SOURCE_DIR) + "/scripts/plot_cycles.py";
    const std::string cmd = quote(FXR_PYTHON) + " " + quote(script) + " --csv " + quote(o.out + "/timeline.csv") +
                            " --out " + quote(o.out + "/timeline.png") + " --title " + quote("stage occupancy: " + sc.source);
    const int st = std::system(cmd.c_str());
    const int rc = st == -1 ? -1 : WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    if (rc == 3) plot_note = "timeline.png skipped: matplotlib is not installed for " + std::string(FXR_PYTHON);
    else if (rc != 0) throw std::runtime_error("plot_cycles.py failed (exit " + std::to_string(rc) + "): " + cmd);
  }

  std::ostringstream md;
  md << "# Cycles: " << sc.source << "\n\n"
     << "The cycle-approximate SystemC model (docs/cycles.md) of the raster unit on this scene: input, clip, recip "
        "and viewport (stages 1–4), then setup, traversal, the interpolators (front: span start; back: one sample per clock), "
        "depth and divide, one triangle offered per clock. Clocks from the first primitive in to the last fragment "
        "out.\n\n"
     << "| | value |\n|---|---|\n"
     << "| primitives | " << r.primitives << " |\n| setup triangles (drawn) | " << r.triangles << " (" << r.drawn << ") |\n"
     << "| spans | " << r.spans << " |\n| fragments generated / passed | " << r.samples << " / " << r.passed << " |\n"
     << "| **clocks** | **" << r.clocks << "** |\n"
     << std::fixed << std::setprecision(4) << "| triangles per clock | " << per(r.triangles, r.clocks) << " |\n"
     << "| fragments per clock (generated) | " << per(r.samples, r.clocks) << " |\n"
     << "| bottleneck (most busy clocks) | **" << fxr::cyc::stage_name(r.bottleneck()) << "** |\n"
     << std::setprecision(3) << "| simulation wall clock | " << r.seconds << " s |\n";
  if (o.rtl)
    md << "| RTL clocks (fxraster cosim, the unit under Verilator: `rtl/report.md`) | " << rtl["clocks"].get<uint64_t>()
       << " |\n| deviation SystemC − RTL | " << std::showpos << std::setprecision(2)
       << 100.0 * rtl["deviation"].get<double>() << std::noshowpos << " % |\n| RTL wall clock (stage taps compared) | "
       << std::setprecision(3) << rtl["seconds"].get<double>() << " s |\n| **speed ratio RTL / SystemC** | **"
       << std::setprecision(1) << rtl["speed_ratio"].get<double>() << "×** |\n";
  md << "\n"
     << "## Stages\n\nbusy: working on a transaction; stalled: holding a result the next stage does not take; "
        "starved: waiting for input (the rest of the frame).\n\n"
     << "| stage | in | out | busy | stalled | starved | busy % |\n|---|---|---|---|---|---|---|\n";
  for (int s = 0; s < fxr::cyc::kNumStages; ++s) {
    const fxr::cyc::StageClocks& c = r.stage[(size_t)s];
    md << "| " << fxr::cyc::stage_name(s) << " | " << c.in << " | " << c.out << " | " << c.busy << " | " << c.stalled
       << " | " << c.starved << " | " << std::setprecision(1) << 100.0 * per(c.busy, r.clocks) << " |\n";
  }
  md << "\n## Timeline\n\n";
  if (plot_note.empty() && !o.no_plot) md << "![stage occupancy](timeline.png)\n\n";
  else if (!plot_note.empty()) md << "**" << plot_note << "**\n\n";
  md << "Busy fraction of every stage per bin of the frame: `timeline.csv`.\n\n";
  if (!sweep.empty()) {
    md << "## Architecture sweep\n\nOne knob of the configuration's `arch` unit moved at a time (the rest as run above).\n\n"
       << "| variant | clocks | speed-up | bottleneck |\n|---|---|---|---|\n";
    for (const auto& [v, s] : sweep)
      md << "| " << v.label << " | " << s.clocks << " | " << std::setprecision(3) << per(r.clocks, s.clocks) << " | "
         << fxr::cyc::stage_name(s.bottleneck()) << " |\n";
    md << "\n";
  }
  md << "Knobs of this run: `" << fxr::arch_to_json(arch).dump() << "`.\n";
  std::ofstream(o.out + "/report.md") << md.str();
  if (!o.quiet)
    std::cout << "cycles " << sc.source << ": " << r.clocks << " clocks, " << std::setprecision(4)
              << per(r.samples, r.clocks) << " fragments/clock, " << per(r.triangles, r.clocks)
              << " triangles/clock, bottleneck " << fxr::cyc::stage_name(r.bottleneck()) << "; report " << o.out
              << "/report.md\n";
  if (o.rtl && !o.quiet)
    std::cout << "cycles " << sc.source << ": RTL " << rtl["clocks"].get<uint64_t>() << " clocks (deviation "
              << std::showpos << std::setprecision(3) << 100.0 * rtl["deviation"].get<double>() << std::noshowpos
              << " %), RTL " << rtl["seconds"].get<double>() << " s, SystemC " << r.seconds << " s: speed ratio "
              << rtl["speed_ratio"].get<double>() << "\n";
  return 0;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  fxr::app::add_scene_source(sub, o->in, "the embedded default scene");
  sub.get_option("--config")
      ->description("configuration JSON: fields override the scene's; its unit \"arch\" sets the knobs (docs/cycles.md)");
  sub.add_option("--out", o->out, "output directory")->required();
  fxr::app::add_scene_overrides(sub, o->in);
  sub.add_option("--bins", o->bins, "timeline bins (default 200)");
  sub.add_flag("--no-sweep", o->no_sweep, "skip the architecture sweep");
  sub.add_flag("--no-plot", o->no_plot, "do not call scripts/plot_cycles.py");
  sub.add_flag("--quiet", o->quiet, "no summary line");
  sub.add_flag("--rtl", o->rtl,
               "the scene through the RTL unit too (fxraster cosim into OUT/rtl): its clocks, the deviation and the "
               "speed ratio RTL / SystemC of this run");
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("cycles", "clocks per frame, stage occupancy and bottleneck from the cycle-approximate SystemC model",
                        setup);

}  // namespace
