// model/config/validate.hpp — every rule a configuration must satisfy, in one place.
//
// A configuration is valid when every parameter lies in the range its unit's visit() declares
// and every cross-field rule of config_rules() holds. validate() checks both and is called by
// every entry point: config_from_json (config files, `fxraster config --emit-*`, scene and
// manifest configurations, `render --config`), frame_begin (every frame of the raster unit,
// including configurations built in code), the vector models and the sweeps (unit by unit).
// The rules, with the bound each one protects, are listed in docs/number-formats.md
// ("Validity rules"); tests/model/validate_test.cpp has one test per rule.
//
// Derived widths are not parameters a user sets independently: derive_widths() computes them
// from the parameter they follow (docs/number-formats.md, "Derived widths").
#pragma once

#include <string>
#include <vector>

#include "model/config/config.hpp"

namespace fxr {

// Which configurations a rule applies to: the whole Config (cross-unit), or one unit on its
// own (also checked when the unit is swept or vectored without the rest of the configuration).
enum class RuleScope { Config, Raster, Recip, Div, TexAddr };

struct ConfigRule {
  const char* id;         // short name, e.g. "recip.nr_frac_bits_above_output"
  RuleScope scope;
  const char* field;      // the field the error names (unit.field), e.g. "recip.nr_frac_bits"
  const char* statement;  // the rule, as docs/number-formats.md lists it
  // "" when the rule holds for cfg; otherwise why not (the values involved), without the field.
  std::string (*check)(const Config& cfg);
};

// Every cross-field rule, in the order they are checked.
const std::vector<ConfigRule>& config_rules();

// A width computed from another parameter instead of being set: unit.field = source_unit.source_field.
struct DerivedParam {
  const char* unit;
  const char* field;
  const char* source_unit;
  const char* source_field;
  const char* why;
};
const std::vector<DerivedParam>& derived_params();

// Sets every derived width from the parameter it follows.
void derive_widths(Config& cfg);

// Throws ConfigError "<where>: field '<unit>.<field>': <problem>" naming every violated range
// and rule (at most kMaxReportedProblems of them, then a count), or returns.
void validate(const Config& cfg, const std::string& where);
// One unit on its own (standalone sweeps and vectors): its ranges and its own-scope rules.
void validate(const RasterConfig& cfg, const std::string& where);
void validate(const RecipConfig& cfg, const std::string& where);
void validate(const DivConfig& cfg, const std::string& where);
void validate(const TexAddrConfig& cfg, const std::string& where);

inline constexpr int kMaxReportedProblems = 8;

}  // namespace fxr
