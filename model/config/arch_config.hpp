// model/config/arch_config.hpp — the micro-architecture knobs of the raster unit's hardware:
// FIFO depths, divider lanes, setup units, memory latency (issue 12; docs/cycles.md).
//
// These are not number formats: they change how many clocks a draw takes, never a value. They
// are the parameters rtl/fxr_raster_backend.sv is built from (its module parameters, defaults
// equal: tests/sc/cycle_model_test.cpp reads them from the RTL source) and the cycle model
// (sc/, `fxraster cycles`) reads its timing from them plus the stages' cost() functions.
//
// ArchConfig is kept apart from fxr::Config on purpose: Config is embedded in every vector
// manifest and hashed, and a clock-count knob must not make the committed vectors differ.
// A configuration file may carry it as the unit "arch" (load_arch_config strips it before the
// number formats are read); `fxraster config --emit-md` lists it like every unit.
#pragma once

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "model/config/config.hpp"
#include "model/config/param.hpp"

namespace fxr {

struct ArchConfig {
  int tri_fifo_depth = 4;      // fxr_raster_backend TriFifoDepth: equations FIFO (traversal → interp ctx)
  int depth_queue_depth = 8;   // fxr_depth QueueDepth: samples in flight behind the depth memory
  int depth_write_port = 1;    // fxr_depth WritePort: 1 separate write channel, 0 writes share the request port
  int interp_div_steps = 4;    // fxr_interp DivStepsPerClock as the back end instantiates it
  int divide_lanes = 0;        // fxr_divide Lanes: 0 = one lane per varying (the RTL default)
  int setup_units = 1;         // parallel setup pipelines (the RTL has one)
  int mem_latency = 1;         // depth memory read latency in clocks (≥ 1; the testbench's default)
  int link_depth = 1;          // registered entries on a stage-to-stage link (the RTL's valid/ready register)
  int prim_per_clock = 1;      // primitives the source offers per clock (1: one per clock, the testbench)
  int viewport_lanes = 3;      // fxr_raster_unit ViewportLanes (kViewportLanes): fxr_viewport's pipelined dividers

  template <class V>
  void visit(V& v) {
    v.integer("tri_fifo_depth", tri_fifo_depth, 2, 64,
              "triangles between traversal's input and the interpolators (equations FIFO, power of two)");
    v.integer("depth_queue_depth", depth_queue_depth, 1, 64,
              "depth-test samples in flight behind the depth memory (power of two)");
    v.integer("depth_write_port", depth_write_port, 0, 1,
              "1: depth writes on their own channel (dual-port memory); 0: writes share the read port");
    v.integer("interp_div_steps", interp_div_steps, 1, 32,
              "quotient bits per clock of the interpolators' span-start depth divisions");
    v.integer("divide_lanes", divide_lanes, 0, 8, "divider lanes of stage 9 (0: one per varying)");
    v.integer("setup_units", setup_units, 1, 8, "parallel setup pipelines (initiation interval / units)");
    v.integer("mem_latency", mem_latency, 1, 64, "depth memory read latency (clocks from request to response)");
    v.integer("link_depth", link_depth, 1, 16, "registered entries on each stage-to-stage link");
    v.integer("prim_per_clock", prim_per_clock, 1, 1, "primitives offered to the unit per clock");
    v.integer("viewport_lanes", viewport_lanes, 1, 32,
              "pipelined dividers of stage 4 (a triangle's quotients issued this many per clock)");
  }
};

// Cross-field rules (powers of two where the RTL's pointers need them); throws ConfigError
// naming `where` and the field.
void validate_arch(const ArchConfig& a, const std::string& where);

// Divider lanes for a draw of `num_varyings` varyings (divide_lanes 0: one per varying; at
// least 1, at most num_varyings).
int arch_divide_lanes(const ArchConfig& a, int num_varyings);

nlohmann::json arch_to_json(const ArchConfig& a);
// Overrides fields from a JSON object (unknown fields, wrong types, ranges: ConfigError), then
// validates.
ArchConfig arch_from_json(const nlohmann::json& j, const std::string& where);

// A configuration file with an optional "arch" unit: the number formats (config_from_json on
// the rest) and the knobs. Throws ConfigError naming the file and field.
std::pair<Config, ArchConfig> load_config_with_arch(const std::string& path);

// Markdown table of the knobs (the format of emit_md_tables).
void emit_arch_md_table(std::ostream& os, const ArchConfig& a);

}  // namespace fxr
