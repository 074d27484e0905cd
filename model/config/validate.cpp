// Every validity rule of the configuration (contracts in model/config/validate.hpp; the rules and
// the bounds they protect are listed in docs/number-formats.md, "Validity rules").
#include "model/config/validate.hpp"

#include <string>

#include "model/stages/setup.hpp"

namespace fxr {

namespace {

// Interpolator and depth sums are held in i128: 127 value bits plus the sign (setup.cpp).
constexpr int kI128ValueBits = 127;
// The three-term plane sums Σ E_k·Q_k add 2 bits to one product (docs/pipeline.md, stage 7).
constexpr int kThreeTermSumBits = 2;
// A signed block-aligned value carries one sign bit beyond its magnitude bits.
constexpr int kSignBits = 1;

std::string str(int v) { return std::to_string(v); }

// Bits of the interpolator sums Σ E_k·Q_k: edge value × (interp_block_bits + sign) + 2.
int interp_sum_bits(const RasterConfig& r) {
  return edge_value_bits(r) + r.interp_block_bits + kSignBits + kThreeTermSumBits;
}
// Bits of the per-vertex depth product z·(2^depth_bits − 1) (z ∈ [0, 1] with z_frac_bits).
int depth_product_bits(const RasterConfig& r) { return r.z_frac_bits + kSignBits + r.depth_bits(); }
// Bits of the depth plane sums: edge value × depth product + 2.
int depth_sum_bits(const RasterConfig& r) { return edge_value_bits(r) + depth_product_bits(r) + kThreeTermSumBits; }

const std::vector<ConfigRule> kRules = {
    {"raster.edge_values_fit_int64", RuleScope::Raster, "raster.window_int_bits",
     "edge values need 2·(window_int_bits + max(subpixel_bits, 1)) + 2 ≤ 63 bits (held in int64)",
     [](const Config& c) -> std::string {
       const RasterConfig& r = c.raster;
       if (edge_value_bits(r) <= kEdgeValueMaxBits) return "";
       return "window_int_bits (" + str(r.window_int_bits) + ") + max(subpixel_bits, 1) (" + str(grid_bits(r)) +
              ") gives edge values of " + str(edge_value_bits(r)) + " bits, more than the " +
              str(kEdgeValueMaxBits) + " an int64 holds (needs window_int_bits + max(subpixel_bits, 1) <= 30)";
     }},
    {"raster.interp_sums_fit_int128", RuleScope::Raster, "raster.interp_block_bits",
     "interpolator sums need edge value bits + interp_block_bits + 3 ≤ 127 bits (held in i128)",
     [](const Config& c) -> std::string {
       const RasterConfig& r = c.raster;
       if (interp_sum_bits(r) <= kI128ValueBits) return "";
       return str(r.interp_block_bits) + ": interpolator sums need " + str(interp_sum_bits(r)) +
              " bits (edge values " + str(edge_value_bits(r)) + " + interp_block_bits + 3), more than " +
              str(kI128ValueBits);
     }},
    {"raster.depth_products_fit_int64", RuleScope::Raster, "raster.z_frac_bits",
     "z·(2^depth_bits − 1) needs z_frac_bits + 1 + depth_bits ≤ 63 bits (held in int64)",
     [](const Config& c) -> std::string {
       const RasterConfig& r = c.raster;
       if (depth_product_bits(r) <= kEdgeValueMaxBits) return "";
       return str(r.z_frac_bits) + ": z·(2^depth_bits − 1) needs " + str(depth_product_bits(r)) +
              " bits (z_frac_bits + 1 + depth_bits " + str(r.depth_bits()) + "), more than " +
              str(kEdgeValueMaxBits);
     }},
    {"raster.depth_sums_fit_int128", RuleScope::Raster, "raster.z_frac_bits",
     "depth plane sums need edge value bits + z_frac_bits + 1 + depth_bits + 2 ≤ 127 bits (held in i128)",
     [](const Config& c) -> std::string {
       const RasterConfig& r = c.raster;
       if (depth_sum_bits(r) <= kI128ValueBits) return "";
       return str(r.z_frac_bits) + ": depth sums need " + str(depth_sum_bits(r)) + " bits, more than " +
              str(kI128ValueBits);
     }},
    {"raster.attr_plane_sums_fit_int128", RuleScope::Raster, "raster.attr_coord_bits",
     "attribute-plane 1/w and v/w sums need 2·attr_coord_bits + interp_block_bits + 5 ≤ 127 bits (held in i128)",
     [](const Config& c) -> std::string {
       const RasterConfig& r = c.raster;
       // Attribute-plane edge values take 2·attr_coord_bits + 2 bits (raster_config.hpp, issue 8);
       // times a block-aligned value (interp_block_bits + sign) summed over three vertices (+2).
       const int bits = 2 * r.attr_coord_bits + 2 + r.interp_block_bits + kSignBits + kThreeTermSumBits;
       if (bits <= kI128ValueBits) return "";
       return str(r.attr_coord_bits) + ": attribute-plane sums need " + str(bits) +
              " bits (2·attr_coord_bits + interp_block_bits (" + str(r.interp_block_bits) + ") + 5), more than " +
              str(kI128ValueBits);
     }},
    {"recip.nr_frac_bits_above_output", RuleScope::Recip, "recip.nr_frac_bits",
     "nr_frac_bits > out_sig_bits (the final rounding needs a bit below the output lsb)",
     [](const Config& c) -> std::string {
       if (c.recip.nr_frac_bits > c.recip.out_sig_bits) return "";
       return str(c.recip.nr_frac_bits) + " must exceed recip.out_sig_bits (" + str(c.recip.out_sig_bits) +
              "): the final rounding needs a bit below the output lsb";
     }},
    {"recip.seed_index_within_input", RuleScope::Recip, "recip.seed_index_bits",
     "seed_index_bits < in_sig_bits (the table index is taken from the fraction bits of w)",
     [](const Config& c) -> std::string {
       if (c.recip.seed_index_bits < c.recip.in_sig_bits) return "";
       return str(c.recip.seed_index_bits) + " must be below recip.in_sig_bits (" + str(c.recip.in_sig_bits) +
              "): the table index is taken from the fraction bits of w";
     }},
    {"div.iterative_needs_radix2", RuleScope::Div, "div.schedule",
     "schedule = iterative only with algorithm = radix2 (recip_mul is always pipelined)",
     [](const Config& c) -> std::string {
       if (c.div.schedule != DivSchedule::Iterative || c.div.algorithm == DivAlgorithm::Radix2) return "";
       return "'iterative' needs algorithm 'radix2' (recip_mul is always pipelined, II 1)";
     }},
    {"div.quot_bits_derived", RuleScope::Config, "div.quot_bits",
     "div.quot_bits = raster.varying_out_sig_bits (derived: the divider produces the output varyings)",
     [](const Config& c) -> std::string {
       if (c.div.quot_bits == c.raster.varying_out_sig_bits) return "";
       return str(c.div.quot_bits) + " differs from raster.varying_out_sig_bits (" +
              str(c.raster.varying_out_sig_bits) +
              "), from which it is derived (the divider produces the output varyings): leave it out of the "
              "configuration, or call derive_widths() after setting raster.varying_out_sig_bits";
     }},
    {"tex_addr.sig_bits_derived", RuleScope::Config, "tex_addr.sig_bits",
     "tex_addr.sig_bits = raster.varying_out_sig_bits (derived: the texture address unit reads the output varyings)",
     [](const Config& c) -> std::string {
       if (c.tex_addr.sig_bits == c.raster.varying_out_sig_bits) return "";
       return str(c.tex_addr.sig_bits) + " differs from raster.varying_out_sig_bits (" +
              str(c.raster.varying_out_sig_bits) +
              "), from which it is derived (the texture address unit reads the output varyings u, v): leave it out "
              "of the configuration, or call derive_widths() after setting raster.varying_out_sig_bits";
     }},
};

const std::vector<DerivedParam> kDerived = {
    {"div", "quot_bits", "raster", "varying_out_sig_bits", "the divider produces the output varyings"},
    {"tex_addr", "sig_bits", "raster", "varying_out_sig_bits", "the texture address unit reads the output varyings u, v"},
};

// Collects range violations of one unit: "field 'unit.name': v is outside [lo, hi]".
struct RangeCheck {
  std::string unit;
  std::vector<std::string>& problems;
  void integer(const char* name, int& value, int lo, int hi, const char*) {
    if (value < lo || value > hi)
      problems.push_back("field '" + unit + "." + name + "': " + str(value) + " is outside [" + str(lo) + ", " +
                         str(hi) + "]");
  }
  template <class E>
  void choice(const char* name, E& value, std::initializer_list<const char*> names, const char*) {
    const int i = static_cast<int>(value);
    if (i < 0 || i >= (int)names.size())
      problems.push_back("field '" + unit + "." + name + "': choice index " + str(i) + " is not one of the " +
                         str((int)names.size()) + " choices");
  }
};

template <class Cfg>
void check_ranges(const char* unit, const Cfg& cfg, std::vector<std::string>& problems) {
  RangeCheck rc{unit, problems};
  const_cast<Cfg&>(cfg).visit(rc);  // visit does not modify through RangeCheck
}

void check_rules(const Config& cfg, bool all_scopes, RuleScope only, std::vector<std::string>& problems) {
  for (const ConfigRule& r : kRules) {
    if (!all_scopes && r.scope != only) continue;
    const std::string why = r.check(cfg);
    if (!why.empty()) problems.push_back("field '" + std::string(r.field) + "': " + why);
  }
}

void throw_if_any(const std::string& where, const std::vector<std::string>& problems) {
  if (problems.empty()) return;
  std::string msg = where + ": " + problems[0];
  const int shown = (int)problems.size() < kMaxReportedProblems ? (int)problems.size() : kMaxReportedProblems;
  for (int i = 1; i < shown; ++i) msg += "; " + problems[(size_t)i];
  if ((int)problems.size() > shown) msg += "; and " + str((int)problems.size() - shown) + " more";
  throw ConfigError(msg);
}

}  // namespace

const std::vector<ConfigRule>& config_rules() { return kRules; }
const std::vector<DerivedParam>& derived_params() { return kDerived; }

void derive_widths(Config& cfg) {
  cfg.div.quot_bits = cfg.raster.varying_out_sig_bits;
  cfg.tex_addr.sig_bits = cfg.raster.varying_out_sig_bits;
}

void validate(const Config& cfg, const std::string& where) {
  std::vector<std::string> problems;
  cfg.for_each_unit([&](const char* unit, const auto& u) { check_ranges(unit, u, problems); });
  // Cross-field rules read the fields: only meaningful once every field is in range.
  if (problems.empty()) check_rules(cfg, true, RuleScope::Config, problems);
  throw_if_any(where, problems);
}

namespace {
template <class Unit>
void validate_unit(const char* name, RuleScope scope, const Unit& u, Config& wrap, const std::string& where) {
  std::vector<std::string> problems;
  check_ranges(name, u, problems);
  if (problems.empty()) check_rules(wrap, false, scope, problems);
  throw_if_any(where, problems);
}
}  // namespace

void validate(const RasterConfig& c, const std::string& where) {
  Config w;
  w.raster = c;
  validate_unit("raster", RuleScope::Raster, c, w, where);
}
void validate(const RecipConfig& c, const std::string& where) {
  Config w;
  w.recip = c;
  validate_unit("recip", RuleScope::Recip, c, w, where);
}
void validate(const DivConfig& c, const std::string& where) {
  Config w;
  w.div = c;
  validate_unit("div", RuleScope::Div, c, w, where);
}
void validate(const TexAddrConfig& c, const std::string& where) {
  Config w;
  w.tex_addr = c;
  validate_unit("tex_addr", RuleScope::TexAddr, c, w, where);
}

}  // namespace fxr
