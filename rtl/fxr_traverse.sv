// fxr_traverse: stage 6, traversal (issue 10). One triangle's equations in, one span per covered
// row out, rows bottom to top. Model: fxr::TraverseStage (model/stages/traverse.hpp); algorithm
// and figures: docs/rtl.md, "fxr_traverse"; vectors: the transaction dumps' traverse.in /
// traverse.out (docs/vectors.md, "Transaction vectors"; tb/traverse_txn_test.cpp).
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::triangle_equations_t (TriangleEquations::visit(); only
//                                 prim, the edges and the candidate rectangle are used here)
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::span_t: prim, row y, covered pixels x0 ≤ i ≤ x1
//
// Algorithm (exact, the same spans as the model's wide path). Per row j the biased edge values
// at the rectangle's left pixel centre, e_k = E_k(x0, j) + bias_k, are stepped by b_k·2^g from
// row to row (one direct evaluation per triangle, at (x0, y0)). Along the row e_k + o·d_k,
// d_k = a_k·2^g, is monotone in the offset o, so each edge bounds the covered offsets on one
// side: the bound is the largest o in [0, 2^n) with e_k + o·d_k < 0 (d_k > 0: the pixels left
// of the edge, lo_k = that + 1) or ≥ 0 (d_k < 0: hi_k = that), found MSB first, one bit per
// clock for the three edges at once (a restoring division's shift-and-add), n = bits of the
// width w = x1 − x0. Then lo = max lo_k, hi = min(hi_k, w), and the row's span is
// [x0 + lo, x0 + hi] when lo ≤ hi. So a row costs n + 1 clocks whatever its uncovered part
// (1 clock for 1-pixel-wide rectangles, 10 for 512 pixels).
//
// Timing (TraverseStage::cost()): the first span is valid n + 2 clocks after the input transfer;
// rows take n + 1 clocks each; a triangle occupies the unit for rows·(n + 1) clocks (the next
// one is accepted in the clock that finishes the last row; an empty rectangle takes one clock).
// out_ready_i low holds a found span and stops the walk; no span is lost or duplicated.
module fxr_traverse #(
  parameter int SubpixelBits  = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  // derived (model/stages/setup.hpp)
  localparam int G   = SubpixelBits > 0 ? SubpixelBits : 1,  // grid_bits
  localparam int CB  = WindowIntBits + G,                     // coord_bits
  localparam int ECB = CB + 1,                                // edge_coef_bits
  localparam int EVB = 2 * CB + 2,                            // edge_value_bits
  localparam int PB  = WindowIntBits,                         // pixel index (signed)
  // Search values e_k + o·d_k for o < 2^n ≤ 2^PB: |e_k| ≤ 2^(EVB−1) (bias included) and
  // |o·d_k| < 2^(PB + ECB − 1 + G) ≤ 2^(EVB−2), so EVB + 1 signed bits hold every one.
  localparam int AB  = EVB + 1,
  localparam int OB  = PB + 1,                                // offsets 0 … 2^PB (unsigned)
  localparam int NB  = $clog2(PB + 1)                         // n = 0 … PB
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic                             in_valid_i,
  output logic                             in_ready_o,
  /* verilator lint_off UNUSEDSIGNAL */
  input  fxr_rec_pkg::triangle_equations_t in_i,  // depth / varying planes: not used here
  /* verilator lint_on UNUSEDSIGNAL */
  output logic                             out_valid_o,
  input  logic                             out_ready_i,
  output fxr_rec_pkg::span_t               out_o
);

  typedef enum logic [1:0] {StIdle, StSearch, StFin} state_e;

  // ---- input decode -------------------------------------------------------------------------
  logic signed [ECB-1:0] in_a [3], in_b [3];
  logic signed [EVB-1:0] in_c [3];
  logic                  in_bias [3];  // 1: bias −1
  always_comb begin
    in_a[0] = $signed(in_i.e0_a); in_b[0] = $signed(in_i.e0_b); in_c[0] = $signed(in_i.e0_c);
    in_a[1] = $signed(in_i.e1_a); in_b[1] = $signed(in_i.e1_b); in_c[1] = $signed(in_i.e1_c);
    in_a[2] = $signed(in_i.e2_a); in_b[2] = $signed(in_i.e2_b); in_c[2] = $signed(in_i.e2_c);
    in_bias[0] = in_i.e0_bias; in_bias[1] = in_i.e1_bias; in_bias[2] = in_i.e2_bias;
  end
  logic signed [PB-1:0] in_x0, in_x1, in_y0, in_y1;
  assign in_x0 = $signed(in_i.x0);
  assign in_x1 = $signed(in_i.x1);
  assign in_y0 = $signed(in_i.y0);
  assign in_y1 = $signed(in_i.y1);

  // Width w = x1 − x0 (PB + 1 signed bits), empty rectangle, n = bits of w.
  logic signed [PB:0] in_w;
  logic               in_empty;
  logic [NB-1:0]      in_n;
  assign in_w     = {in_x1[PB-1], in_x1} - {in_x0[PB-1], in_x0};
  assign in_empty = in_w[PB] | (in_y1 < in_y0);
  always_comb begin
    in_n = '0;
    for (int i = 0; i < PB; i++)
      if (in_w[i]) in_n = NB'(i + 1);
  end

  // Biased edge values at the centre of pixel (x0, y0): X = x0·2^g + 2^(g−1), so
  // a·X + b·Y + c = (a·x0 + b·y0)·2^g + (a + b)·2^(g−1) + c.
  // The products at their own width (ECB + PB signed bits hold them), then widened.
  logic signed [ECB+PB-1:0] in_ax [3], in_by [3];
  logic signed [AB-1:0] in_v [3];
  logic signed [AB-1:0] in_ds0 [3];  // d_k·2^(n−1): the first search step
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      in_ax[k] = in_a[k] * in_x0;
      in_by[k] = in_b[k] * in_y0;
      in_v[k] = ((AB'(in_ax[k]) + AB'(in_by[k])) <<< G)
              + ((AB'(in_a[k]) + AB'(in_b[k])) <<< (G - 1)) + AB'(in_c[k]) - AB'(in_bias[k]);
      in_ds0[k] = in_n == '0 ? '0 : (AB'(in_a[k]) <<< G) <<< (in_n - NB'(1));
    end
  end

  // ---- state --------------------------------------------------------------------------------
  state_e               state_q;
  logic [31:0]          prim_q;
  logic signed [PB-1:0] x0_q, y_q, y1_q;
  logic [OB-1:0]        w_q;          // x1 − x0 ≥ 0
  logic [OB-1:0]        tb0_q, tb_q;  // one-hot search bit: 2^(n−1) (0 when n = 0), shifted right
  logic signed [AB-1:0] dy_q [3];     // b_k·2^g
  logic                 dpos_q [3], dneg_q [3];  // sign of d_k = a_k·2^g
  logic signed [AB-1:0] ds0_q [3], ds_q [3];     // d_k·2^(n−1), shifted right with tb_q
  logic signed [AB-1:0] v_q [3];      // e_k of the current row
  logic signed [AB-1:0] acc_q [3];    // e_k + t_k·d_k
  logic [OB-1:0]        t_q [3];      // search result so far

  logic                 out_valid_q;
  fxr_rec_pkg::span_t   out_q;

  // ---- search step (StSearch) ---------------------------------------------------------------
  logic signed [AB-1:0] try_v [3];
  logic                 take [3];
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      try_v[k] = acc_q[k] + ds_q[k];
      // d > 0: the largest offset still outside (value < 0); d < 0: the largest still inside.
      take[k] = dpos_q[k] ? try_v[k][AB-1] : (dneg_q[k] & ~try_v[k][AB-1]);
    end
  end

  // ---- row result (StFin) -------------------------------------------------------------------
  logic [OB-1:0] lo, hi;
  logic          row_empty;
  always_comb begin
    lo = '0;
    hi = w_q;
    row_empty = 1'b0;
    for (int k = 0; k < 3; k++) begin
      if (dpos_q[k]) begin
        if (v_q[k][AB-1] && t_q[k] + OB'(1) > lo) lo = t_q[k] + OB'(1);
      end else if (dneg_q[k]) begin
        if (v_q[k][AB-1]) row_empty = 1'b1;
        else if (t_q[k] < hi) hi = t_q[k];
      end else if (v_q[k][AB-1]) begin
        row_empty = 1'b1;
      end
    end
    if (lo > hi) row_empty = 1'b1;
  end

  // The next triangle is accepted while idle or in the clock that finishes the last row.
  logic fin_stall, last_row, accept;
  assign fin_stall   = ~row_empty & out_valid_q & ~out_ready_i;
  assign last_row    = y_q == y1_q;
  assign in_ready_o  = state_q == StIdle || (state_q == StFin && last_row && !fin_stall);
  assign accept      = in_valid_i & in_ready_o;
  assign out_valid_o = out_valid_q;
  assign out_o       = out_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q     <= StIdle;
      out_valid_q <= 1'b0;
    end else begin
      if (out_valid_q && out_ready_i) out_valid_q <= 1'b0;
      unique case (state_q)
        StIdle: if (accept && !in_empty) state_q <= in_n == '0 ? StFin : StSearch;
        StSearch: if (tb_q[0]) state_q <= StFin;
        StFin: if (!fin_stall) begin
          if (!row_empty) out_valid_q <= 1'b1;
          if (!last_row) state_q <= tb0_q == '0 ? StFin : StSearch;
          else if (accept && !in_empty) state_q <= in_n == '0 ? StFin : StSearch;
          else state_q <= StIdle;
        end
        default: state_q <= StIdle;
      endcase
    end
  end

  // Datapath registers (no reset: qualified by state_q / out_valid_q).
  always_ff @(posedge clk_i) begin
    if (state_q == StFin && !fin_stall && !row_empty) begin
      out_q.prim <= prim_q;
      out_q.y    <= y_q;
      out_q.x0   <= x0_q + PB'(lo);
      out_q.x1   <= x0_q + PB'(hi);
    end
    if (accept) begin
      prim_q <= in_i.prim;
      x0_q   <= in_x0;
      y_q    <= in_y0;
      y1_q   <= in_y1;
      w_q    <= in_w[OB-1:0];
      tb0_q  <= in_n == '0 ? '0 : OB'(1) << (in_n - NB'(1));
      tb_q   <= in_n == '0 ? '0 : OB'(1) << (in_n - NB'(1));
      for (int k = 0; k < 3; k++) begin
        dy_q[k]   <= AB'(in_b[k]) <<< G;
        dpos_q[k] <= in_a[k] > 0;
        dneg_q[k] <= in_a[k] < 0;
        ds0_q[k]  <= in_ds0[k];
        ds_q[k]   <= in_ds0[k];
        v_q[k]    <= in_v[k];
        acc_q[k]  <= in_v[k];
        t_q[k]    <= '0;
      end
    end else if (state_q == StSearch) begin
      tb_q <= tb_q >> 1;
      for (int k = 0; k < 3; k++) begin
        ds_q[k] <= ds_q[k] >>> 1;
        if (take[k]) begin
          acc_q[k] <= try_v[k];
          t_q[k]   <= t_q[k] | tb_q;
        end
      end
    end else if (state_q == StFin && !fin_stall) begin
      y_q  <= y_q + PB'(1);
      tb_q <= tb0_q;
      for (int k = 0; k < 3; k++) begin
        v_q[k]   <= v_q[k] + dy_q[k];
        acc_q[k] <= v_q[k] + dy_q[k];
        ds_q[k]  <= ds0_q[k];
        t_q[k]   <= '0;
      end
    end
  end

endmodule
