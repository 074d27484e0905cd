// fxr_nr_step: one Newton-Raphson step of the reciprocal core, two register stages; shared by
// fxr_recip and fxr_div_recip_mul. Model: one iteration of fxr::RecipCore::approx
// (model/arith/recip_core.hpp); docs/arith.md "# Shared arithmetic".
//
//   x = x_i * 2^-(XBits-1) in [1, 2)          (msb of x_i set)
//   y = y_i * 2^-YFracBits                   (the seed with its leading one, or the last step's y)
//   stage 1:  p = trunc_F(x*y) (< 2, F+1 bits; precision lost: truncation < 2^-F)
//             t = ~p = 2 - 2^-F - p           (ones' complement: t <= 2 - x*y, so y' <= 1/x)
//   stage 2:  y' = trunc_F(y*t)               (precision lost: truncation < 2^-F)
//   y_o = y' * 2^FracBits, y' in [0, 1), two clocks after x_i / y_i (each clock with en_i high).
// en_i is the caller's pipeline enable (a stalled output holds every stage); act_i says the
// caller's pipeline holds valid data in some stage ('1 where it has no such bit). The step computes
// and loads only then (its registers hold otherwise; nothing reads them without valid data), in
// the clocked processes that load them: a simulator then skips an idle unit's products
// (docs/rtl.md, "Co-simulation speed", session 11). Per-stage valid bits were tried: with the
// recip bench's random input gaps they made the test a mispredicted branch (0.96x that bench).
// In synthesis the blocking variables are the same combinational products, act_i a flip-flop
// enable term.
module fxr_nr_step #(
  parameter int XBits     = 24,
  parameter int YFracBits = 7,
  parameter int FracBits  = 26
) (
  input  logic                 clk_i,
  input  logic                 en_i,
  input  logic                 act_i,
  input  logic [XBits-1:0]     x_i,
  input  logic [YFracBits-1:0] y_i,
  output logic [FracBits-1:0]  y_o
);
  localparam int F  = FracBits;
  localparam int XY = XBits + YFracBits;       // width of the exact product x*y
  localparam int Sh = XBits - 1 + YFracBits - F;  // x*y has XBits-1+YFracBits fraction bits; keep F
  localparam int ShR = Sh >= 0 ? Sh : 0;          // p = x*y >> Sh, or x*y << -Sh
  localparam int ShL = Sh >= 0 ? 0 : -Sh;

  // ---- stage 1: t = ~trunc_F(x*y) ----------------------------------------------------------
  logic [F:0]           t_q;
  logic [YFracBits-1:0] y_q;
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (en_i && act_i) begin
      logic [XY-1:0] xy;
      logic [F:0]    p;
      xy = XY'(x_i) * XY'(y_i);
      p = (F+1)'(xy >> ShR) << ShL;
      t_q <= ~p;
      y_q <= y_i;
    end
  end

  // ---- stage 2: y' = trunc_F(y*t) ----------------------------------------------------------
  // The truncated low bits of y*t are dropped; its top bit is zero (y*t < 1).
  logic [F-1:0] y_next_q;
  always_ff @(posedge clk_i) begin
    if (en_i && act_i) begin
      logic [YFracBits+F:0] yt;
      yt = (YFracBits+F+1)'(y_q) * (YFracBits+F+1)'(t_q);
      y_next_q <= F'(yt >> YFracBits);
    end
  end
  /* verilator lint_on BLKSEQ */
  assign y_o = y_next_q;
endmodule
