// fxr_input: stage 1 of the raster unit (the model's "convert" stage, issue 11). One primitive's
// float32 clip-space words in, the same primitive as exact (neg, sig, exp) values out, or nothing
// when a position word is NaN / Inf. Model: fxr::ConvertStage (model/stages/input.hpp); vectors:
// the transaction dumps' convert.in / convert.out (docs/vectors.md, "Transaction vectors";
// tb/txn/convert_txn_test.cpp); docs/rtl.md, "fxr_input".
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::input_triangle_t (InputTriangle::visit(): prim, then
//                                 per vertex x, y, z, w and the NumVaryings varyings, float32 bits)
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::exact_triangle_t (ExactTriangle::visit(): prim, then
//                                 per value _neg, _sig, _exp in the same order)
//   rej_nan_o, rej_inf_o          the primitive transferred in this clock is rejected: a NaN in a
//                                 position (takes precedence), else an infinity in a position
//   var_replaced_o                the primitive transferred in this clock is emitted and one of its
//                                 varyings was NaN / ±Inf and replaced (prims_varying_nonfinite)
//   var_zero_i                    bit k set: varying k of every vertex enters as +0 (the unit's
//                                 number of varyings; a forced varying is neither replaced nor
//                                 counted). 0 (every varying as given) where unconnected.
//   The three pulses are combinational on the input transfer (in_valid_i && in_ready_o), so a
//   counter adds them in the clock the primitive is taken.
//
// Function (docs/pipeline.md, stage 1): per float32 word the exponent all-ones / all-zeros detect
// and the hidden-bit insert: normal E: sig = 2^FracBits | frac, exp = E − bias − FracBits;
// E = 0 (zero and denormals, nothing flushed): sig = frac, exp = 1 − bias − FracBits; the sign
// kept (−0 stays −0). A varying word with E all ones is first replaced: NaN → +0, ±Inf → ±FLT_MAX
// (one multiplexer onto a constant). A rejected primitive produces no output (n_out = 0 in the
// dump: the 1 → 0 convention of every stage). The model's RejectedRange (more than kMaxVaryings
// varyings asked for) cannot occur: the number of varyings is the record's, fixed at elaboration.
//
// Both records are handled as flat bit vectors (first field most significant, as fxr_rec_pkg
// packs them), so the module follows NumVaryings without naming the per-vertex members.
//
// Timing: one register stage, initiation interval 1 (in_ready_o = !out_valid_o || out_ready_i).
module fxr_input (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic                         in_valid_i,
  output logic                         in_ready_o,
  input  fxr_rec_pkg::input_triangle_t in_i,
  output logic                         out_valid_o,
  input  logic                         out_ready_i,
  output fxr_rec_pkg::exact_triangle_t out_o,
  output logic                         rej_nan_o,
  output logic                         rej_inf_o,
  output logic                         var_replaced_o,
  input  logic [fxr_rec_pkg::NumVaryings-1:0] var_zero_i
);
  // IEEE-754 binary32: the word width comes from the record package, the exponent width and
  // bias are the format's (docs/references.md, IEEE 754). The widths are fxr_rec_pkg's
  // constants, not $bits() of struct members (Yosys 0.23 gives the whole struct's width).
  localparam int F32Bits = fxr_rec_pkg::F32Bits;
  localparam int F32ExpBits = 8;
  localparam int F32FracBits = F32Bits - 1 - F32ExpBits;
  localparam int F32ExpBias = (1 << (F32ExpBits - 1)) - 1;
  localparam int NumVaryings = fxr_rec_pkg::NumVaryings;
  localparam int WordsPerVertex = 4 + NumVaryings;  // x, y, z, w, varyings
  localparam int NumWords = 3 * WordsPerVertex;
  localparam int PrimBits = fxr_rec_pkg::PrimIdBits;
  localparam int SigBits = fxr_rec_pkg::ClipVertexSigBits;
  localparam int ExpBits = fxr_rec_pkg::FxExpBits;
  localparam int ValBits = 1 + SigBits + ExpBits;  // _neg, _sig, _exp
  localparam int InBits = fxr_rec_pkg::InputTriangleBits;
  localparam int OutBits = fxr_rec_pkg::ExactTriangleBits;

  // The exponent of a zero / denormal word and the offset of a normal one.
  localparam logic signed [ExpBits-1:0] ExpSub = ExpBits'(1 - F32ExpBias - F32FracBits);
  localparam logic signed [ExpBits-1:0] ExpOffset = ExpBits'(F32ExpBias + F32FracBits);
  // FLT_MAX without its sign: exponent all ones − 1, fraction all ones.
  localparam logic [F32Bits-2:0] MaxFinite = {{(F32ExpBits - 1){1'b1}}, 1'b0, {F32FracBits{1'b1}}};

  logic [InBits-1:0]  in_flat;
  logic any_nan, any_inf, any_repl, take;
  assign in_flat = in_i;

  // The word j of the input record (prim first).
  function automatic logic [F32Bits-1:0] word(input logic [InBits-1:0] x, input int j);
    word = x[InBits-PrimBits-1-F32Bits*j -: F32Bits];
  endfunction

  // The classes of the position words and of the varyings (those not forced to +0), evaluated only
  // with an input offered: in_i is the unit's top-level input, and a simulator evaluates the logic
  // that depends on it in every evaluation (docs/rtl.md, "Co-simulation speed", session 10).
  logic [NumWords-1:0] w_nan, w_inf, pos_mask, var_on;
  always_comb begin
    /* verilator lint_off UNUSEDSIGNAL */
    logic [F32Bits-1:0] w;  // (its sign bit is not read)
    /* verilator lint_on UNUSEDSIGNAL */
    w = '0;
    w_nan = '0;
    w_inf = '0;
    if (in_valid_i) begin
      for (int j = 0; j < NumWords; j++) begin
        w = word(in_flat, j);
        w_nan[j] = (&w[F32Bits-2 -: F32ExpBits]) && (|w[F32FracBits-1:0]);
        w_inf[j] = (&w[F32Bits-2 -: F32ExpBits]) && !(|w[F32FracBits-1:0]);
      end
    end
  end
  for (genvar j = 0; j < NumWords; j++) begin : g_mask
    assign pos_mask[j] = (j % WordsPerVertex) < 4;
    if ((j % WordsPerVertex) < 4) begin : g_pos
      assign var_on[j] = 1'b0;
    end else begin : g_var
      assign var_on[j] = !var_zero_i[(j % WordsPerVertex) - 4];
    end
  end
  assign any_nan = |(w_nan & pos_mask);
  assign any_inf = |(w_inf & pos_mask);
  assign any_repl = |((w_nan | w_inf) & var_on);

  assign in_ready_o = !out_valid_o || out_ready_i;
  assign take = in_valid_i && in_ready_o;
  assign rej_nan_o = take && any_nan;
  assign rej_inf_o = take && !any_nan && any_inf;
  assign var_replaced_o = take && !any_nan && !any_inf && any_repl;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_o <= 1'b0;
    end else if (in_ready_o) begin
      out_valid_o <= in_valid_i && !any_nan && !any_inf;
    end
  end
  // The conversion, in the process that loads the output register (blocking variables read
  // nowhere else: combinational logic in synthesis), evaluated only on an input transfer.
  logic [OutBits-1:0] out_q;
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (take) begin
      logic [F32Bits-1:0] bits;
      logic [F32ExpBits-1:0] e;
      logic e_zero;
      out_q[OutBits-1 -: PrimBits] <= in_flat[InBits-1 -: PrimBits];
      for (int j = 0; j < NumWords; j++) begin
        bits = word(in_flat, j);
        if ((j % WordsPerVertex) >= 4) begin
          // The varying rule: NaN → +0, ±Inf → ±FLT_MAX, finite words unchanged; a varying
          // forced to +0 (var_zero_i) enters as +0.
          if (var_zero_i[(j % WordsPerVertex) - 4]) bits = '0;
          else if (&bits[F32Bits-2 -: F32ExpBits]) bits = (|bits[F32FracBits-1:0]) ? '0 : {bits[F32Bits-1], MaxFinite};
        end  // a position word that is NaN / Inf rejects the primitive: its value is unused
        e = bits[F32Bits-2 -: F32ExpBits];
        e_zero = ~|e;
        out_q[OutBits-PrimBits-1-ValBits*j -: ValBits] <=
            {bits[F32Bits-1], SigBits'({!e_zero, bits[F32FracBits-1:0]}),
             e_zero ? ExpSub : $signed(ExpBits'(e)) - ExpOffset};
      end
    end
  end
  /* verilator lint_on BLKSEQ */
  assign out_o = out_q;
endmodule
