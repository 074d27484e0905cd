// fxr_texaddr: texture address unit (issue 15): u, v (FxFloat codes) and the texture size to
// texel indices, border flags and bilinear weights. Model: fxr::texaddr (model/stages/texaddr.hpp);
// rules, special values and measurements: docs/texaddr.md.
//
// Ports:
//   clk_i, rst_ni                     clock, active-low asynchronous reset
//   in_valid_i / in_ready_o           input handshake (transfer when both are high)
//   filter_i                          fxr_config_pkg::tex_addr_filter_e (nearest, bilinear)
//   wrap_i [2]                        fxr_config_pkg::tex_addr_wrap_e
//   u_neg_i, u_exp_i, u_sig_i         u = (-1)^neg * sig * 2^exp (exp signed, lsb exponent)
//   v_neg_i, v_exp_i, v_sig_i         v alike
//   width_i, height_i [SizeBits+1]    texture size, each in [1, 2^SizeBits]
//   out_valid_o / out_ready_i         output handshake
//   s_i0_o, s_i1_o, s_b0_o, s_b1_o, s_w_o   along u: texel indices, border flags, weight of i1
//   t_i0_o, t_i1_o, t_b0_o, t_b1_o, t_w_o   along v
// Latency 1 (the output register, = fxr::texaddr_cost().latency), initiation interval 1;
// in_ready_o = out_ready_i | ~out_valid_o: a stalled output holds, nothing is lost.
module fxr_texaddr #(
  parameter int SigBits  = fxr_config_pkg::TexAddrSigBits,
  parameter int ExpBits  = fxr_config_pkg::TexAddrExpBits,
  parameter int SizeBits = fxr_config_pkg::TexAddrSizeBits,
  parameter int FracBits = fxr_config_pkg::TexAddrWeightFracBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic                filter_i,
  input  logic [1:0]          wrap_i,
  input  logic                u_neg_i,
  input  logic [ExpBits-1:0]  u_exp_i,
  input  logic [SigBits-1:0]  u_sig_i,
  input  logic                v_neg_i,
  input  logic [ExpBits-1:0]  v_exp_i,
  input  logic [SigBits-1:0]  v_sig_i,
  input  logic [SizeBits:0]   width_i,
  input  logic [SizeBits:0]   height_i,
  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [SizeBits-1:0] s_i0_o,
  output logic [SizeBits-1:0] s_i1_o,
  output logic                s_b0_o,
  output logic                s_b1_o,
  output logic [FracBits-1:0] s_w_o,
  output logic [SizeBits-1:0] t_i0_o,
  output logic [SizeBits-1:0] t_i1_o,
  output logic                t_b0_o,
  output logic                t_b1_o,
  output logic [FracBits-1:0] t_w_o
);
  localparam int AxisBits = 2 * SizeBits + 2 + FracBits;  // {i0, i1, b0, b1, w}

  logic bilinear;
  assign bilinear = filter_i == 1'(fxr_config_pkg::TexAddrFilterBilinear);  // tex_addr_filter_e

  logic [AxisBits-1:0] s_d, t_d, s_q, t_q;

  fxr_texaddr_axis #(
    .SigBits (SigBits),
    .ExpBits (ExpBits),
    .SizeBits(SizeBits),
    .FracBits(FracBits)
  ) u_axis_s (
    .bilinear_i(bilinear),
    .wrap_i    (wrap_i),
    .neg_i     (u_neg_i),
    .exp_i     (u_exp_i),
    .sig_i     (u_sig_i),
    .size_i    (width_i),
    .i0_o      (s_d[AxisBits-1 -: SizeBits]),
    .i1_o      (s_d[AxisBits-SizeBits-1 -: SizeBits]),
    .b0_o      (s_d[FracBits+1]),
    .b1_o      (s_d[FracBits]),
    .w_o       (s_d[FracBits-1:0])
  );

  fxr_texaddr_axis #(
    .SigBits (SigBits),
    .ExpBits (ExpBits),
    .SizeBits(SizeBits),
    .FracBits(FracBits)
  ) u_axis_t (
    .bilinear_i(bilinear),
    .wrap_i    (wrap_i),
    .neg_i     (v_neg_i),
    .exp_i     (v_exp_i),
    .sig_i     (v_sig_i),
    .size_i    (height_i),
    .i0_o      (t_d[AxisBits-1 -: SizeBits]),
    .i1_o      (t_d[AxisBits-SizeBits-1 -: SizeBits]),
    .b0_o      (t_d[FracBits+1]),
    .b1_o      (t_d[FracBits]),
    .w_o       (t_d[FracBits-1:0])
  );

  // ---- handshake: one output register ----------------------------------------------------
  logic valid_q, advance;
  assign advance     = out_ready_i | ~valid_q;
  assign in_ready_o  = advance;
  assign out_valid_o = valid_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (advance) begin
      valid_q <= in_valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance && in_valid_i) begin
      s_q <= s_d;
      t_q <= t_d;
    end
  end

  assign {s_i0_o, s_i1_o, s_b0_o, s_b1_o, s_w_o} = s_q;
  assign {t_i0_o, t_i1_o, t_b0_o, t_b1_o, t_w_o} = t_q;
endmodule
