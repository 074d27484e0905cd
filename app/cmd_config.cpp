// `fxraster config`: print or export the configuration (JSON, SystemVerilog package, Markdown).
#include <fstream>
#include <iostream>
#include <sstream>

#include "command.hpp"
#include "model/config/arch_config.hpp"
#include "model/config/config.hpp"

namespace {

struct Opts {
  std::string in, sv, md, json;
};

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  sub.add_option("--config", o->in, "configuration JSON to read (default: built-in defaults)");
  sub.add_option("--emit-sv", o->sv, "write the SystemVerilog package fxr_config_pkg to this file");
  sub.add_option("--emit-md", o->md, "write the Markdown parameter tables to this file");
  sub.add_option("--emit-json", o->json, "write the full configuration JSON to this file ('-' = stdout)");
  return [o]() {
    const fxr::Config cfg = o->in.empty() ? fxr::Config{} : fxr::load_config(o->in);
    auto open = [](const std::string& path) {
      std::ofstream f(path);
      if (!f) throw std::runtime_error(path + ": cannot write");
      return f;
    };
    if (!o->sv.empty()) {
      std::ostringstream os;
      fxr::emit_sv_package(os, cfg);
      fxr::app::write_file_if_changed(o->sv, os.str());  // unchanged: no re-verilation
    }
    if (!o->md.empty()) {
      auto f = open(o->md);
      fxr::emit_md_tables(f, cfg);
      fxr::emit_arch_md_table(f, fxr::ArchConfig{});  // the cycle model's knobs (docs/cycles.md)
    }
    if (o->json == "-" || (o->sv.empty() && o->md.empty() && o->json.empty())) {
      std::cout << fxr::config_to_json(cfg).dump(2) << "\n";
    } else if (!o->json.empty()) {
      auto f = open(o->json);
      f << fxr::config_to_json(cfg).dump(2) << "\n";
    }
    return 0;
  };
}

fxr::app::Registrar reg("config", "print the configuration, or export it as JSON, SystemVerilog or Markdown", setup);

}  // namespace
