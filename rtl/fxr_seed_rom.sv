// fxr_seed_rom: the seed table of the reciprocal core (combinational ROM), shared by fxr_recip
// and fxr_div_recip_mul. Model: fxr::recip_core_seed_table (model/arith/recip_core.cpp);
// docs/arith.md "# Shared arithmetic". The table is computed at elaboration by seed_entry(), the
// same minimax rule in the same exact integer arithmetic as the model; tb/seed_rom_test.cpp
// reads every address of the verilated ROM and compares it with the model's table.
//
// Entry i covers x in [1 + i*2^-SeedIndexBits, 1 + (i+1)*2^-SeedIndexBits) and holds the
// SeedFracBits bits after the leading one of y0 = (2^SeedFracBits + entry) * 2^-(SeedFracBits+1)
// in [1/2, 1): the grid value minimising the largest |1 - x*y0| over the segment; candidates
// floor / floor+1 of 2^(s+k+2) / (2a+1) (the reciprocal of the segment midpoint), clamped to
// [1/2, 1); ties keep the smaller. The caller adds the leading one back.
// Exact integer arithmetic in 64 bits: products below 2^(2*SeedIndexBits+SeedFracBits+3) <= 2^51
// (parameter ranges 14 and 20).
module fxr_seed_rom #(
  parameter int SeedIndexBits = 6,
  parameter int SeedFracBits  = 6
) (
  input  logic [SeedIndexBits-1:0] idx_i,
  output logic [SeedFracBits-1:0]  seed_o
);
  localparam int Entries = 1 << SeedIndexBits;

  // Largest relative endpoint error of candidate y (units 2^-(SeedIndexBits+SeedFracBits+1)) on
  // the segment [a, a+1) * 2^-SeedIndexBits.
  function automatic logic signed [63:0] seed_cost(input logic signed [63:0] a,
                                                   input logic signed [63:0] y);
    logic signed [63:0] d, ea, eb;
    d  = 64'sd1 <<< (SeedIndexBits + SeedFracBits + 1);
    ea = d - a * y;
    eb = d - (a + 64'sd1) * y;
    if (ea < 0) ea = -ea;
    if (eb < 0) eb = -eb;
    seed_cost = (ea > eb) ? ea : eb;
  endfunction

  function automatic logic [SeedFracBits-1:0] seed_entry(input int i);
    logic signed [63:0] a, y_lo, y_hi, y_floor, best, up;
    a       = (64'sd1 <<< SeedIndexBits) + 64'(i);
    y_lo    = 64'sd1 <<< SeedFracBits;
    y_hi    = (64'sd1 <<< (SeedFracBits + 1)) - 64'sd1;
    y_floor = (64'sd1 <<< (SeedIndexBits + SeedFracBits + 2)) / (64'sd2 * a + 64'sd1);
    best    = (y_floor < y_lo) ? y_lo : ((y_floor > y_hi) ? y_hi : y_floor);
    up      = (y_floor + 64'sd1 < y_lo) ? y_lo :
              ((y_floor + 64'sd1 > y_hi) ? y_hi : y_floor + 64'sd1);
    if (seed_cost(a, up) < seed_cost(a, best)) best = up;
    seed_entry = SeedFracBits'(best - y_lo);  // (Yosys 0.23 does not parse `return`)
  endfunction

  // Two nested loops of at most 2^7 iterations each (Verilator refuses loops above 1024).
  localparam int InnerBits = (SeedIndexBits > 7) ? 7 : SeedIndexBits;
  localparam int Inner     = 1 << InnerBits;
  localparam int Outer     = Entries / Inner;

  logic [Entries*SeedFracBits-1:0] rom;
  for (genvar o = 0; o < Outer; o++) begin : gen_outer
    for (genvar n = 0; n < Inner; n++) begin : gen_entry
      localparam int                      I     = o * Inner + n;  // localparams: Icarus 11
      localparam int                      Lo    = I * SeedFracBits;
      localparam logic [SeedFracBits-1:0] Entry = seed_entry(I);
      assign rom[Lo +: SeedFracBits] = Entry;
    end
  end

  assign seed_o = rom[idx_i * SeedFracBits +: SeedFracBits];
endmodule
