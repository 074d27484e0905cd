// `fxraster vectors`: golden vectors for a unit (hex + JSON manifest, docs/vectors.md), and
// `fxraster vectors check FILE` to validate a file against its manifest and the model.
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "model/config/config.hpp"
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
};

int run_check(const Opts& o, const std::string& path) {
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
                               "UNIT (" + units + ") to generate, or `check FILE` to validate a vector file")
                   ->expected(1, 2);
  auto* list = sub.add_flag("--list", o->list, "print the units that have vectors, one per line, and exit");
  unit->excludes(list);
  sub.add_option("--config", o->config,
                 "configuration JSON (default: built-in defaults); with check: the manifest must match it");
  sub.add_option("--seed", o->seed, "seed of the random cases (mt19937_64)");
  sub.add_option("--count", o->count, "number of random cases (after the directed ones)");
  sub.add_option("--out", o->out, "output folder: writes OUT/UNIT.hex and OUT/UNIT.json");
  sub.add_flag("--exhaustive", o->exhaustive, "sweep the whole input domain instead of random cases");
  sub.add_flag("--no-recompute", o->no_recompute, "check: validate the format only, do not rerun the model");
  sub.footer(
      "Directed corner cases come first, then --count random cases or the --exhaustive sweep.\n"
      "Every line is one hex word ($readmemh); the manifest names the fields (docs/vectors.md).");
  return [o]() {
    if (o->list) {
      for (const auto& u : fxr::vector_units()) std::cout << u.name << "\n";
      return 0;
    }
    if (o->args.empty()) throw fxr::ConfigError("vectors: missing the UNIT (one of `fxraster vectors --list`) or `check FILE`");
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
