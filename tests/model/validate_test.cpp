// Configuration validity in one place (model/config/validate.hpp): one test per cross-field rule
// (it rejects a violating configuration and accepts the boundary), derived widths, and
// equality / hashing from visit(). The bounds are recomputed here from the formats the rules
// protect (docs/number-formats.md, "Validity rules"), not taken from the code under test.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include "model/config/config.hpp"
#include "model/config/validate.hpp"
#include "model/unit/backend.hpp"

namespace fxr {
namespace {

// Storage limits the rules protect: int64 and i128 value bits (sign excluded).
constexpr int kInt64ValueBits = 63;
constexpr int kInt128ValueBits = 127;

// Independent restatement of the widths (docs/pipeline.md, stages 5 and 7).
int coord_bits_of(const RasterConfig& r) { return r.window_int_bits + (r.subpixel_bits > 0 ? r.subpixel_bits : 1); }
int edge_bits_of(const RasterConfig& r) { return 2 * coord_bits_of(r) + 2; }
int depth_code_bits_of(const RasterConfig& r) { return r.depth_format == DepthFormat::D16 ? 16 : 24; }

const ConfigRule& rule(const std::string& id) {
  for (const ConfigRule& r : config_rules())
    if (r.id == id) return r;
  throw std::runtime_error("no rule " + id);
}

// validate() must throw naming `where` and `field`; returns the message.
std::string rejection(const Config& c, const std::string& field) {
  try {
    validate(c, "cfg.json");
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("cfg.json: ", 0), 0u) << m;
    EXPECT_NE(m.find("field '" + field + "'"), std::string::npos) << m;
    return m;
  }
  ADD_FAILURE() << "validate accepted a configuration violating " << field;
  return "";
}

// Asserts: the rule flags `bad`, validate() rejects it naming the rule's field; the rule passes
// `boundary` and validate() accepts it.
void expect_rule(const std::string& id, const Config& bad, const Config& boundary) {
  const ConfigRule& r = rule(id);
  EXPECT_FALSE(r.check(bad).empty()) << id;
  rejection(bad, r.field);
  EXPECT_EQ(r.check(boundary), "") << id;
  EXPECT_NO_THROW(validate(boundary, "cfg.json")) << id;
}

TEST(Validate, DefaultConfigurationIsValid) { EXPECT_NO_THROW(validate(Config{}, "defaults")); }

TEST(Validate, EveryRuleHasATestBelow) {
  // The ids tested in this file; a new rule must add its test (and this list).
  const std::set<std::string> tested = {"raster.edge_values_fit_int64", "raster.interp_sums_fit_int128",
                                        "raster.depth_products_fit_int64", "raster.depth_sums_fit_int128",
                                        "raster.attr_plane_sums_fit_int128",
                                        "recip.nr_frac_bits_above_output", "recip.seed_index_within_input",
                                        "div.iterative_needs_radix2",     "div.quot_bits_derived",
                                        "tex_addr.sig_bits_derived"};
  std::set<std::string> ids;
  for (const ConfigRule& r : config_rules()) {
    EXPECT_TRUE(ids.insert(r.id).second) << "duplicate rule id " << r.id;
    EXPECT_TRUE(tested.count(r.id)) << "rule without a test: " << r.id;
  }
  EXPECT_EQ(ids.size(), tested.size());
}

TEST(Validate, EdgeValuesMustFitInt64) {
  Config bad, edge;
  bad.raster.window_int_bits = 20, bad.raster.subpixel_bits = 11;  // coordinates of 31 bits
  edge.raster.window_int_bits = 20, edge.raster.subpixel_bits = 10;  // 30 bits
  ASSERT_GT(edge_bits_of(bad.raster), kInt64ValueBits);
  ASSERT_LE(edge_bits_of(edge.raster), kInt64ValueBits);
  expect_rule("raster.edge_values_fit_int64", bad, edge);
}

TEST(Validate, InterpolatorSumsMustFitInt128) {
  // Σ E·Q with Q of interp_block_bits + sign bits, three terms (+2 bits).
  Config bad, edge;
  bad.raster.window_int_bits = 20, bad.raster.subpixel_bits = 11, bad.raster.interp_block_bits = 62;
  edge.raster.window_int_bits = 20, edge.raster.subpixel_bits = 10, edge.raster.interp_block_bits = 62;
  edge.raster.attr_coord_bits = 30;  // the attribute planes' own i128 rule: 2·30 + 62 + 5 = 127
  ASSERT_GT(edge_bits_of(bad.raster) + 62 + 1 + 2, kInt128ValueBits);
  ASSERT_EQ(edge_bits_of(edge.raster) + 62 + 1 + 2, kInt128ValueBits);  // exactly at the limit
  const ConfigRule& r = rule("raster.interp_sums_fit_int128");
  EXPECT_FALSE(r.check(bad).empty());
  rejection(bad, r.field);
  EXPECT_EQ(r.check(edge), "");
  EXPECT_NO_THROW(validate(edge, "cfg.json"));
}

TEST(Validate, DepthProductsMustFitInt64) {
  Config bad, edge;
  bad.raster.z_frac_bits = 39;   // 39 + 1 + 24 = 64
  edge.raster.z_frac_bits = 38;  // 63
  ASSERT_GT(bad.raster.z_frac_bits + 1 + depth_code_bits_of(bad.raster), kInt64ValueBits);
  ASSERT_EQ(edge.raster.z_frac_bits + 1 + depth_code_bits_of(edge.raster), kInt64ValueBits);
  expect_rule("raster.depth_products_fit_int64", bad, edge);
  // The same z width is fine with a 16-bit depth buffer.
  Config d16 = bad;
  d16.raster.depth_format = DepthFormat::D16;
  EXPECT_NO_THROW(validate(d16, "cfg.json"));
}

TEST(Validate, DepthSumsMustFitInt128) {
  Config bad, edge;
  bad.raster.window_int_bits = 20, bad.raster.subpixel_bits = 11, bad.raster.z_frac_bits = 38;
  edge.raster.window_int_bits = 20, edge.raster.subpixel_bits = 10, edge.raster.z_frac_bits = 38;
  ASSERT_GT(edge_bits_of(bad.raster) + 38 + 1 + 24 + 2, kInt128ValueBits);
  ASSERT_EQ(edge_bits_of(edge.raster) + 38 + 1 + 24 + 2, kInt128ValueBits);
  expect_rule("raster.depth_sums_fit_int128", bad, edge);
}

TEST(Validate, AttributePlaneSumsMustFitInt128) {
  // raster_config.hpp: attribute-plane 1/w, v/w sums take 2·attr_coord_bits + interp_block_bits + 5.
  Config bad, edge;
  bad.raster.attr_coord_bits = 40, bad.raster.interp_block_bits = 43;   // 128 bits
  edge.raster.attr_coord_bits = 40, edge.raster.interp_block_bits = 42;  // 127
  ASSERT_GT(2 * 40 + 43 + 5, kInt128ValueBits);
  ASSERT_EQ(2 * 40 + 42 + 5, kInt128ValueBits);
  expect_rule("raster.attr_plane_sums_fit_int128", bad, edge);
  EXPECT_NO_THROW(validate(Config{}, "defaults"));  // 2·40 + 40 + 5 = 125
}

TEST(Validate, RecipNeedsAFractionBitBelowTheOutput) {
  Config bad, edge;
  bad.recip.nr_frac_bits = bad.recip.out_sig_bits;
  edge.recip.nr_frac_bits = edge.recip.out_sig_bits + 1;
  expect_rule("recip.nr_frac_bits_above_output", bad, edge);
  EXPECT_THROW(validate(bad.recip, "recip"), ConfigError);  // also on its own (sweeps)
}

TEST(Validate, RecipSeedIndexComesFromTheInputFraction) {
  Config bad, edge;
  bad.recip.in_sig_bits = 8, bad.recip.seed_index_bits = 8;
  edge.recip.in_sig_bits = 8, edge.recip.seed_index_bits = 7;
  expect_rule("recip.seed_index_within_input", bad, edge);
}

TEST(Validate, IterativeScheduleNeedsRadix2) {
  Config bad, edge;
  bad.div.algorithm = DivAlgorithm::RecipMul, bad.div.schedule = DivSchedule::Iterative;
  edge.div.algorithm = DivAlgorithm::Radix2, edge.div.schedule = DivSchedule::Iterative;
  expect_rule("div.iterative_needs_radix2", bad, edge);
  Config pipelined = bad;
  pipelined.div.schedule = DivSchedule::Pipelined;
  EXPECT_NO_THROW(validate(pipelined, "cfg.json"));
  EXPECT_THROW(validate(bad.div, "div"), ConfigError);  // also on its own (sweeps)
}

TEST(Validate, QuotientWidthIsDerivedFromTheOutputVaryings) {
  Config bad, edge;
  bad.div.quot_bits = bad.raster.varying_out_sig_bits + 1;
  expect_rule("div.quot_bits_derived", bad, edge);
  // Derived, not set: derive_widths makes any raster.varying_out_sig_bits consistent.
  for (int bits : {8, 20, 24, 32}) {
    Config c;
    c.raster.varying_out_sig_bits = bits;
    if (bits != c.div.quot_bits) {
      EXPECT_THROW(validate(c, "x"), ConfigError) << bits;  // not yet derived
    }
    derive_widths(c);
    EXPECT_EQ(c.div.quot_bits, bits);
    EXPECT_NO_THROW(validate(c, "x"));
  }
}

TEST(Validate, TexAddrSignificandIsDerivedFromTheOutputVaryings) {
  Config bad, edge;
  bad.tex_addr.sig_bits = bad.raster.varying_out_sig_bits - 1;
  expect_rule("tex_addr.sig_bits_derived", bad, edge);
  for (int bits : {8, 20, 32}) {
    Config c;
    c.raster.varying_out_sig_bits = bits;
    EXPECT_THROW(validate(c, "x"), ConfigError) << bits;  // not yet derived
    derive_widths(c);
    EXPECT_EQ(c.tex_addr.sig_bits, bits);
    EXPECT_NO_THROW(validate(c, "x"));
  }
  EXPECT_NO_THROW(validate(bad.tex_addr, "tex_addr"));  // the standalone unit keeps its own width
}

TEST(Validate, JsonDerivesTheQuotientWidth) {
  const Config c = config_from_json(R"({"version": 1, "raster": {"varying_out_sig_bits": 20}})"_json, "c.json");
  EXPECT_EQ(c.div.quot_bits, 20);
  // Written without the derived field; reads back equal.
  const nlohmann::json j = config_to_json(c);
  EXPECT_FALSE(j.at("div").contains("quot_bits")) << j.dump();
  EXPECT_TRUE(config_from_json(j, "back") == c);
  // Older files that carry the derived value stay readable; a different value is refused.
  EXPECT_NO_THROW(config_from_json(R"({"version": 1, "div": {"quot_bits": 24}})"_json, "old.json"));
  try {
    config_from_json(R"({"version": 1, "div": {"quot_bits": 20}})"_json, "c.json");
    FAIL() << "accepted div.quot_bits != raster.varying_out_sig_bits";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("c.json"), std::string::npos) << m;
    EXPECT_NE(m.find("div.quot_bits"), std::string::npos) << m;
    EXPECT_NE(m.find("raster.varying_out_sig_bits"), std::string::npos) << m;
  }
}

TEST(Validate, JsonLoadingAppliesTheRulesNamingFileAndField) {
  // The issue's example: exits 0 before validation was in one place.
  const auto j = R"({"version": 1, "recip": {"nr_frac_bits": 20}, "div": {"quot_bits": 20}})"_json;
  EXPECT_THROW(config_from_json(j, "x.json"), ConfigError);
  try {
    config_from_json(R"({"version": 1, "recip": {"nr_frac_bits": 20}})"_json, "x.json");
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("x.json: ", 0), 0u) << m;
    EXPECT_NE(m.find("recip.nr_frac_bits"), std::string::npos) << m;
  }
  // Fields only (an override file validated after merging): accepted on its own.
  EXPECT_NO_THROW(config_fields_from_json(R"({"version": 1, "recip": {"nr_frac_bits": 20}})"_json, "x.json"));
}

TEST(Validate, EveryEntryPointOfTheModelRefuses) {
  Config bad;
  bad.recip.nr_frac_bits = bad.recip.out_sig_bits;
  FrameOutput f;
  DrawState st;
  st.viewport_w = st.viewport_h = 8;
  EXPECT_THROW(frame_begin(bad, st, f), ConfigError);
  std::ostringstream sv;
  EXPECT_THROW(emit_sv_package(sv, bad), ConfigError);
  EXPECT_THROW(recip_seed_table(bad.recip), ConfigError);
}

TEST(Validate, ErrorListsEveryProblemUpToABound) {
  Config c;
  // Every integer parameter out of range: more problems than the message lists.
  c.raster.subpixel_bits = 99, c.raster.window_int_bits = 99, c.raster.clip_sig_bits = 99;
  c.raster.z_frac_bits = 99, c.raster.varying_sig_bits = 99, c.raster.varying_out_sig_bits = 99;
  c.raster.interp_block_bits = 99, c.recip.in_sig_bits = 99, c.recip.out_sig_bits = 99;
  c.recip.exp_bits = 99;
  try {
    validate(c, "many.json");
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("raster.subpixel_bits"), std::string::npos) << m;
    EXPECT_NE(m.find("and 2 more"), std::string::npos) << m;  // 10 problems, 8 shown
    EXPECT_EQ(m.find("recip.exp_bits"), std::string::npos) << m;
  }
}

// ---- equality and hashing from visit() -----------------------------------------------------

// Sets parameter `index` (visit order) to another value within its range.
struct Perturb {
  int index, at = 0;
  void integer(const char*, int& v, int lo, int hi, const char*) {
    if (at++ == index) v = v < hi ? v + 1 : lo;
  }
  template <class E>
  void choice(const char*, E& v, std::initializer_list<const char*> names, const char*) {
    if (at++ == index) v = static_cast<E>((static_cast<int>(v) + 1) % (int)names.size());
  }
};

template <class Cfg>
void expect_every_parameter_compared_and_hashed(const Cfg& base) {
  const int n = param_values(base).n;
  ASSERT_GT(n, 0);
  Cfg copy = base;
  EXPECT_TRUE(params_equal(copy, base));
  EXPECT_EQ(params_hash(copy), params_hash(base));
  for (int i = 0; i < n; ++i) {
    Cfg c = base;
    Perturb p{i};
    c.visit(p);
    EXPECT_FALSE(params_equal(c, base)) << "parameter " << i;
    EXPECT_NE(params_hash(c), params_hash(base)) << "parameter " << i;
  }
}

TEST(ConfigEquality, EveryParameterOfEveryUnitIsComparedAndHashed) {
  expect_every_parameter_compared_and_hashed(RasterConfig{});
  expect_every_parameter_compared_and_hashed(RecipConfig{});
  expect_every_parameter_compared_and_hashed(DivConfig{});
}

TEST(ConfigEquality, OperatorsFollowVisit) {
  RecipConfig a, b;
  EXPECT_TRUE(a == b);
  b.correction = RecipCorrection::None;  // the last parameter visit() lists
  EXPECT_TRUE(a != b);
  Config x, y;
  EXPECT_TRUE(x == y);
  EXPECT_EQ(config_hash(x), config_hash(y));
  y.div.bits_per_stage = 2;
  EXPECT_TRUE(x != y);
  EXPECT_NE(config_hash(x), config_hash(y));
  // The same values in a different unit are a different configuration.
  Config z;
  z.raster.subpixel_bits = 4;
  EXPECT_NE(config_hash(z), config_hash(x));
  EXPECT_EQ(ParamsHash{}(a), (size_t)params_hash(a));
}

}  // namespace
}  // namespace fxr
