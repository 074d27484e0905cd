// model/vectors/codegen.hpp — code generated from a vector layout, so that no field layout is
// written twice (docs/vectors.md, "Generated layouts"):
//   * the SystemVerilog package fxr_vec_pkg: per unit, the bit offset and width of every field
//     of a vector line as localparams, and packed structs of the whole line and of its output
//     part, which plain-Verilog testbenches (tb/icarus/) overlay on a $readmemh word;
//   * a C++ port adapter per unit for the Verilator testbenches (tb/): the vector fields in
//     file order, input fields driven onto the ports <field>_i and output ports <field>_o
//     sampled into the fields.
// Names: unit "recip", field "in_sig" → RecipVecInSigOff / RecipVecInSigBits (localparams),
// recip_vec_t / recip_vec_out_t (structs), fxr::tb::gen::RecipPortsGen<Dut> (C++).
#pragma once

#include <ostream>
#include <string>

#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {

// The localparams and packed structs of one unit's layout (no package wrapper).
void emit_sv_vector_layout(std::ostream& os, const std::string& unit, const VecLayout& l);

// The package fxr_vec_pkg with the layouts of every unit of vector_units() at `cfg`.
void emit_sv_vector_package(std::ostream& os, const Config& cfg);

// A self-contained C++ header with fxr::tb::gen::<Unit>PortsGen<Dut>: fields(), drive(), sample().
// Ports up to 64 bits are Verilator scalars, wider ones (up to kVecMaxFieldBits) VlWide<N>.
void emit_verilator_ports(std::ostream& os, const std::string& unit, const VecLayout& l);

// The package fxr_rec_pkg: one packed struct per stage record of the back end (TriangleEquations
// as triangle_equations_t, Span as span_t, PlaneSample as plane_sample_t, Fragment as fragment_t;
// the line path's LineEquations as line_equations_t, LineFragment as line_fragment_t), members in the order
// and with the widths of the record's visit() at (cfg, num_varyings): the first field is the most
// significant. The transaction testbench (tb/txn_harness.hpp) binds a port of such a struct to
// the same fields of a transaction vector row (docs/rtl.md, "Record ports").
void emit_sv_record_package(std::ostream& os, const Config& cfg, int num_varyings);
// kRecordPackageVaryings (the varyings of the generated record package): model/unit/io.hpp.

}  // namespace fxr
