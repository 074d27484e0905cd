// model/config/config.hpp — the one configuration of the raster unit.
//
// Every number format and algorithm choice of every stage is a named parameter of a unit's
// config struct (declared in that unit's header, listed once in its visit()). This struct
// aggregates them; JSON files, the generated SystemVerilog package (fxr_config_pkg.sv), the
// docs tables and the vector manifests are all produced from it.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "model/arith/div.hpp"
#include "model/config/param.hpp"
#include "model/config/raster_config.hpp"
#include "model/stages/line.hpp"
#include "model/stages/recip.hpp"
#include "model/stages/texaddr.hpp"

namespace fxr {

// Version of the configuration JSON format (field "version").
inline constexpr int kConfigFormatVersion = 1;

struct Config {
  // Units: name used in JSON and as the SV prefix, and its config.
  // (Members are added here as units land; for_each_unit lists each once.)
  RasterConfig raster;
  DivConfig div;
  RecipConfig recip;
  TexAddrConfig tex_addr;
  LineConfig line;  // line rasterisation rule (model/stages/line.hpp, docs/lines.md)

  template <class F>
  void for_each_unit(F&& f) {
    f("raster", raster);
    f("div", div);
    f("recip", recip);
    f("tex_addr", tex_addr);
    f("line", line);
  }
  template <class F>
  void for_each_unit(F&& f) const {
    const_cast<Config*>(this)->for_each_unit(f);
  }
};

// Equality from visit(): every parameter of every unit (model/config/param.hpp).
bool operator==(const Config& a, const Config& b);
inline bool operator!=(const Config& a, const Config& b) { return !(a == b); }
inline bool operator==(const RasterConfig& a, const RasterConfig& b) { return params_equal(a, b); }
inline bool operator!=(const RasterConfig& a, const RasterConfig& b) { return !(a == b); }
inline bool operator==(const DivConfig& a, const DivConfig& b) { return params_equal(a, b); }
inline bool operator!=(const DivConfig& a, const DivConfig& b) { return !(a == b); }
// Hash of every parameter of every unit (deterministic FNV-1a; ParamsHash for one unit).
uint64_t config_hash(const Config& cfg);

// JSON: {"version": 1, "<unit>": {<param>: value, ...}, ...}; missing fields keep defaults.
// Derived widths (model/config/validate.hpp) are not written: they follow their source.
nlohmann::json config_to_json(const Config& cfg);
// Reads, derives the derived widths and validates (model/config/validate.hpp): throws
// ConfigError naming `where` (file name) and the field on any problem. A derived width may
// appear in j (older files) only with the value it derives to.
Config config_from_json(const nlohmann::json& j, const std::string& where);
// Types and per-field ranges only, no derivation and no cross-field rules: for a partial file
// that overrides another configuration (render --config), validated once merged.
Config config_fields_from_json(const nlohmann::json& j, const std::string& where);
Config load_config(const std::string& path);  // throws ConfigError (file, field)

// The SystemVerilog package fxr_config_pkg with one localparam per parameter (derived widths
// included: the RTL reads DivQuotBits), named <UnitPrefix><ParamName>, e.g. RecipSeedIndexBits.
// Validates cfg first (throws ConfigError): no package the model would reject is written.
void emit_sv_package(std::ostream& os, const Config& cfg);
// Markdown tables, one per unit.
void emit_md_tables(std::ostream& os, const Config& cfg);

}  // namespace fxr
