// analysis/measure.hpp — error measurement of the arithmetic units against exact arithmetic,
// one signature for every unit, and the configurations a sweep covers (docs/arith.md).
//
// Errors are exact integers (numerators against the exact quotient); double is used only for
// the statistics. Multi-threaded over fixed chunks combined in index order: the results do not
// depend on the thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/arith/div.hpp"
#include "model/stages/recip.hpp"

namespace fxr {

struct MeasureOptions {
  bool exhaustive = true;  // every input of the domain (recip: all 2^(n−1) significands;
                           // div: all operand pairs, only sensible at narrow widths)
  uint64_t count = 0;      // otherwise: directed cases (div) plus `count` uniform random inputs
  uint64_t seed = 1;       // of mt19937_64(seed)
};

struct ErrorStats {
  double max_err_ulp = 0;             // max |result − exact|, ulps of the exact result's binade
  double mean_err_ulp = 0;
  double rms_err_ulp = 0;
  double correctly_rounded_share = 0; // result == the correctly rounded (RNE) value
  bool correctly_rounded = false;     // every input measured is correctly rounded
  bool faithful = false;              // max_err_ulp < 1
  double max_err_ulp_before_round = 0;  // recip: max |1/x − y|, y the NR result before rounding
                                        // (div: not measured, 0)
  uint64_t count = 0;                 // inputs measured
};

// Reciprocal unit, significand core (RecipUnit::approx / round) against 1/x.
ErrorStats measure(const RecipConfig& cfg, const MeasureOptions& opt = {});
// Divider, div_sig against the exact quotient. Not exhaustive: range ends, n = d ± 1, divisors
// on seed-interval edges, exact rounding ties and their neighbours, then `count` random pairs.
ErrorStats measure(const DivConfig& cfg, const MeasureOptions& opt);

// The configurations a sweep covers; the default configuration is among them.
// recip: the anchor designs of docs/arith.md with a near-ideal 40-bit datapath and the
// neighbourhood of the default, each with and without correction.
std::vector<RecipConfig> recip_sweep_configs();
// div: radix2 schedules and digits per stage; recip_mul seeds including ones too coarse;
// shared_recip on the same reciprocal shapes and wider iterates.
std::vector<DivConfig> div_sweep_configs();

// Short labels for reports, e.g. "64x6+2NR f26 rem", "radix2 k=1 pipe", "recip_mul 256x8 nr2 f28".
std::string recip_label(const RecipConfig& cfg);
std::string div_label(const DivConfig& cfg);
inline std::string label(const RecipConfig& cfg) { return recip_label(cfg); }
inline std::string label(const DivConfig& cfg) { return div_label(cfg); }

}  // namespace fxr
