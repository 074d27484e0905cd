// model/config/config.hpp — the one configuration of the raster unit.
//
// Every number format and algorithm choice of every stage is a named parameter of a unit's
// config struct (declared in that unit's header, listed once in its visit()). This struct
// aggregates them; JSON files, the generated SystemVerilog package (fxr_config_pkg.sv), the
// docs tables and the vector manifests are all produced from it.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "model/arith/div.hpp"
#include "model/config/param.hpp"
#include "model/config/raster_config.hpp"
#include "model/stages/recip.hpp"

namespace fxr {

// Version of the configuration JSON format (field "version").
inline constexpr int kConfigFormatVersion = 1;

struct Config {
  // Units: name used in JSON and as the SV prefix, and its config.
  // (Members are added here as units land; for_each_unit lists each once.)
  RasterConfig raster;
  DivConfig div;
  RecipConfig recip;

  template <class F>
  void for_each_unit(F&& f) {
    f("raster", raster);
    f("div", div);
    f("recip", recip);
  }
  template <class F>
  void for_each_unit(F&& f) const {
    const_cast<Config*>(this)->for_each_unit(f);
  }
};

// JSON: {"version": 1, "<unit>": {<param>: value, ...}, ...}; missing fields keep defaults.
nlohmann::json config_to_json(const Config& cfg);
// Throws ConfigError naming `where` (file name) and the field on any problem.
Config config_from_json(const nlohmann::json& j, const std::string& where);
Config load_config(const std::string& path);  // throws ConfigError (file, field)

// The SystemVerilog package fxr_config_pkg with one localparam per parameter,
// named <UnitPrefix><ParamName>, e.g. RecipSeedIndexBits.
void emit_sv_package(std::ostream& os, const Config& cfg);
// Markdown tables, one per unit.
void emit_md_tables(std::ostream& os, const Config& cfg);

}  // namespace fxr
