// `fxraster layout`: the code generated from the vector layouts (model/vectors/codegen.hpp):
// the SystemVerilog package fxr_vec_pkg (field offsets, widths and packed structs of every
// unit's vector lines) and the Verilator port adapters of the testbenches. The build runs it;
// a user runs it to bind the vectors to their own testbench. docs/vectors.md.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "command.hpp"
#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "model/vectors/codegen.hpp"
#include "model/vectors/vectors.hpp"

namespace {

struct Opts {
  std::string config, sv, ports_dir, rec_sv;
  int varyings = fxr::kRecordPackageVaryings;
};

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  sub.add_option("--config", o->config, "configuration JSON (default: built-in defaults)");
  sub.add_option("--emit-sv", o->sv, "write the SystemVerilog package fxr_vec_pkg to this file");
  sub.add_option("--emit-ports", o->ports_dir,
                 "write <unit>_ports_gen.hpp (Verilator port adapters) for every unit into this folder");
  sub.add_option("--emit-records-sv", o->rec_sv,
                 "write the SystemVerilog package fxr_rec_pkg (a packed struct per back-end stage record)");
  sub.add_option("--varyings", o->varyings, "varyings of the records of --emit-records-sv (default " + std::to_string(fxr::kRecordPackageVaryings) + ")")
      ->check(CLI::Range(0, fxr::kMaxVaryings));
  return [o]() {
    if (o->sv.empty() && o->ports_dir.empty() && o->rec_sv.empty())
      throw fxr::ConfigError("layout: give --emit-sv, --emit-ports and/or --emit-records-sv");
    const fxr::Config cfg = o->config.empty() ? fxr::Config{} : fxr::load_config(o->config);
    if (!o->sv.empty()) {
      std::ostringstream os;
      fxr::emit_sv_vector_package(os, cfg);
      fxr::app::write_file_if_changed(o->sv, os.str());
    }
    if (!o->rec_sv.empty()) {
      std::ostringstream os;
      fxr::emit_sv_record_package(os, cfg, o->varyings);
      fxr::app::write_file_if_changed(o->rec_sv, os.str());
    }
    if (!o->ports_dir.empty()) {
      std::filesystem::create_directories(o->ports_dir);
      for (const auto& u : fxr::vector_units()) {
        std::ostringstream os;
        fxr::emit_verilator_ports(os, u.name, u.make(cfg)->layout());
        fxr::app::write_file_if_changed(o->ports_dir + "/" + u.name + "_ports_gen.hpp", os.str());
      }
    }
    return 0;
  };
}

fxr::app::Registrar reg("layout",
                        "generated vector layouts: the SystemVerilog package fxr_vec_pkg and Verilator port adapters",
                        setup);

}  // namespace
