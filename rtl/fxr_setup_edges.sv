// fxr_setup_edges: coverage part of stage 5 (triangle setup), three register stages, instantiated
// by fxr_setup. Model: fxr::setup_triangle (model/stages/setup.cpp); rules: docs/pipeline.md,
// stage 5.
//
//   stage 1  vertices on the sample grid (x << Up), edge coefficients a_k = y_a - y_b,
//            b_k = x_b - x_a, the 6 coordinate products of the edge constants, the vertex
//            bounding box, z > 1 (range), the draw rectangle viewport ∩ scissor ∩ window range
//   stage 2  c_k = x_a*y_b - x_b*y_a, 2A = c_0 + c_1 + c_2 (E_0 + E_1 + E_2 = 2A at every point,
//            here at the origin: no further products), the candidate pixels
//            ceil((min - h) / 2^G) .. floor((max - h) / 2^G) ∩ draw rectangle
//   stage 3  outcome (range, zero area, back face, no samples: the model's precedence), winding
//            normalisation (negate a, b, c, 2A of a clockwise triangle), the top-left bias
//            (0 when a > 0 or a = 0 and b < 0, else -1), front face
// Vertex x, y ports are exactly the coordinate range (signed WindowIntBits + SubpixelBits bits,
// ±2^(WindowIntBits-1) px), so a vertex cannot leave it: only z > 1 is a range outcome.
// Registers advance when en_i is high (the enclosing pipeline's advance); no reset (the
// enclosing module's valid bits qualify the data).
module fxr_setup_edges #(
  parameter int SubpixelBits  = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  parameter int ZFracBits     = fxr_config_pkg::RasterZFracBits,
  // derived (docs/pipeline.md, stage 5 widths)
  localparam int G   = SubpixelBits > 0 ? SubpixelBits : 1,  // grid_bits
  localparam int XB  = WindowIntBits + SubpixelBits,         // vertex port width
  localparam int CB  = WindowIntBits + G,                    // coord_bits
  localparam int ECB = CB + 1,                               // edge_coef_bits
  localparam int EVB = 2 * CB + 2,                           // edge_value_bits
  localparam int ZB  = ZFracBits + 1,                        // z port width
  localparam int PB  = WindowIntBits                         // pixel index width
) (
  input  logic                     clk_i,
  input  logic                     en_i,
  input  logic [2:0]               v_i,           // v_i[s]: stage s's input is valid (else skipped)
  input  logic [3*XB-1:0]       x_i,           // signed, subpixel units
  input  logic [3*XB-1:0]       y_i,
  input  logic [3*ZB-1:0]       z_i,           // unsigned, ZFracBits fraction bits
  input  logic [WindowIntBits-1:0] viewport_x_i,  // signed
  input  logic [WindowIntBits-1:0] viewport_y_i,  // signed
  input  logic [WindowIntBits:0]   viewport_w_i,  // signed
  input  logic [WindowIntBits:0]   viewport_h_i,  // signed
  input  logic [WindowIntBits-1:0] scissor_x_i,   // signed
  input  logic [WindowIntBits-1:0] scissor_y_i,   // signed
  input  logic [WindowIntBits:0]   scissor_w_i,   // signed; negative: no scissor
  input  logic [WindowIntBits:0]   scissor_h_i,   // signed; negative: no scissor
  input  logic [1:0]               cull_i,        // cull_e
  input  logic                     front_ccw_i,
  // after three enabled clocks:
  output logic [2:0]               outcome_o,     // outcome_e
  output logic [3*ECB-1:0]      a_o,           // signed, counter-clockwise normalised
  output logic [3*ECB-1:0]      b_o,
  output logic [3*EVB-1:0]      c_o,
  output logic [2:0]               bias_o,        // 1: bias -1
  output logic [EVB-1:0]           area2_o,       // > 0
  output logic                     front_o,
  output logic [PB-1:0]            x0_o,          // candidate pixels, inclusive, signed
  output logic [PB-1:0]            x1_o,
  output logic [PB-1:0]            y0_o,
  output logic [PB-1:0]            y1_o
);
  localparam int Up = G - SubpixelBits;  // 1 when SubpixelBits = 0: vertices doubled (exact)
  localparam int RB = WindowIntBits + 3;  // signed rectangle arithmetic: vx + vw - 1, sx + sw - 1
  localparam int HalfPx = 1 << (G - 1);  // h: half a pixel on the sample grid

  typedef enum logic [1:0] {
    CullNone  = 2'd0,
    CullBack  = 2'd1,
    CullFront = 2'd2
  } cull_e;
  typedef enum logic [2:0] {
    OutcomeOk        = 3'd0,
    OutcomeZeroArea  = 3'd1,
    OutcomeBackface  = 3'd2,
    OutcomeNoSamples = 3'd3,
    OutcomeRange     = 3'd4
  } outcome_e;

  // ---- stage 1 ------------------------------------------------------------------------------
  logic signed [CB-1:0]  gx [3], gy [3];
  logic signed [CB-1:0]  xmin, xmax, ymin, ymax;
  logic [3*ECB-1:0]   a_d, b_d;
  logic [6*CB-1:0]  p_d, q_d;  // x_a*y_b, x_b*y_a
  logic                  range_d;
  logic signed [RB-1:0]  rx0_d, rx1_d, ry0_d, ry1_d;
  logic signed [RB-1:0]  vx, vy, sx, sy, t;
  logic                  scissor;
  logic [3*ECB-1:0]  s1_a_q, s1_b_q;
  logic [6*CB-1:0] s1_p_q, s1_q_q;
  logic [CB-1:0]        s1_xmin_q, s1_xmax_q, s1_ymin_q, s1_ymax_q;
  logic [RB-1:0]        s1_rx0_q, s1_rx1_q, s1_ry0_q, s1_ry1_q;
  logic                 s1_range_q, s1_front_ccw_q;
  logic [1:0]           s1_cull_q;
  // Stage 1's logic is computed in the clocked process that loads its registers: it reads the
  // module's inputs, which in fxr_raster_backend are top-level ports, and Verilator evaluates
  // combinational logic on top-level inputs in both eval()s of a clock (the input region); here
  // it runs once, at the edge that loads it (docs/rtl.md, "Co-simulation speed", session 9).
  // The variables above are read nowhere else (blocking: combinational in synthesis).
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[0]) begin
      for (int k = 0; k < 3; k++) begin
        gx[k] = CB'($signed(x_i[k*XB +: XB])) <<< Up;
        gy[k] = CB'($signed(y_i[k*XB +: XB])) <<< Up;
      end
      range_d = 1'b0;
      for (int k = 0; k < 3; k++) range_d |= z_i[k*ZB +: ZB] > ZB'(1) << ZFracBits;  // z/w > 1
      for (int k = 0; k < 3; k++) begin
        a_d[k*ECB +: ECB] = ECB'(gy[(k + 1) % 3]) - ECB'(gy[(k + 2) % 3]);
        b_d[k*ECB +: ECB] = ECB'(gx[(k + 2) % 3]) - ECB'(gx[(k + 1) % 3]);
        p_d[k*(2*CB) +: 2*CB] = (2*CB)'(gx[(k + 1) % 3] * gy[(k + 2) % 3]);
        q_d[k*(2*CB) +: 2*CB] = (2*CB)'(gx[(k + 2) % 3] * gy[(k + 1) % 3]);
      end
      xmin = gx[0];
      xmax = gx[0];
      ymin = gy[0];
      ymax = gy[0];
      for (int k = 1; k < 3; k++) begin
        if (gx[k] < xmin) xmin = gx[k];
        if (gx[k] > xmax) xmax = gx[k];
        if (gy[k] < ymin) ymin = gy[k];
        if (gy[k] > ymax) ymax = gy[k];
      end
      // draw_rect: viewport ∩ scissor (both sizes non-negative), then the window range.
      vx = RB'($signed(viewport_x_i));
      vy = RB'($signed(viewport_y_i));
      sx = RB'($signed(scissor_x_i));
      sy = RB'($signed(scissor_y_i));
      t = '0;
      scissor = !scissor_w_i[WindowIntBits] && !scissor_h_i[WindowIntBits];
      rx0_d = vx;
      ry0_d = vy;
      rx1_d = vx + RB'($signed(viewport_w_i)) - RB'(1);
      ry1_d = vy + RB'($signed(viewport_h_i)) - RB'(1);
      if (scissor) begin
        if (sx > rx0_d) rx0_d = sx;
        if (sy > ry0_d) ry0_d = sy;
        t = sx + RB'($signed(scissor_w_i)) - RB'(1);
        if (t < rx1_d) rx1_d = t;
        t = sy + RB'($signed(scissor_h_i)) - RB'(1);
        if (t < ry1_d) ry1_d = t;
      end
      if (rx0_d < -(RB'(1) <<< (WindowIntBits - 1))) rx0_d = -(RB'(1) <<< (WindowIntBits - 1));
      if (ry0_d < -(RB'(1) <<< (WindowIntBits - 1))) ry0_d = -(RB'(1) <<< (WindowIntBits - 1));
      if (rx1_d > (RB'(1) <<< (WindowIntBits - 1)) - RB'(1)) rx1_d = (RB'(1) <<< (WindowIntBits - 1)) - RB'(1);
      if (ry1_d > (RB'(1) <<< (WindowIntBits - 1)) - RB'(1)) ry1_d = (RB'(1) <<< (WindowIntBits - 1)) - RB'(1);
      s1_a_q         <= a_d;
      s1_b_q         <= b_d;
      s1_p_q         <= p_d;
      s1_q_q         <= q_d;
      s1_xmin_q      <= xmin;
      s1_xmax_q      <= xmax;
      s1_ymin_q      <= ymin;
      s1_ymax_q      <= ymax;
      s1_rx0_q       <= rx0_d;
      s1_rx1_q       <= rx1_d;
      s1_ry0_q       <= ry0_d;
      s1_ry1_q       <= ry1_d;
      s1_range_q     <= range_d;
      s1_front_ccw_q <= front_ccw_i;
      s1_cull_q      <= cull_i;
    end
  end
  /* verilator lint_on BLKSEQ */

  // ---- stage 2 ------------------------------------------------------------------------------
  // (computed in the process that loads it, as stage 1: no combinational logic in this module
  // reads v_i, whose bit 0 is fxr_raster_backend's top-level input valid)
  logic [3*EVB-1:0]   c_d;
  logic signed [EVB-1:0] area2_d;
  logic signed [RB-1:0]  bx0_d, bx1_d, by0_d, by1_d;
  logic signed [CB+1:0]  lo_x, lo_y, hi_x, hi_y;
  logic [3*ECB-1:0] s2_a_q, s2_b_q;
  logic [3*EVB-1:0] s2_c_q;
  logic [EVB-1:0]      s2_area2_q;
  logic [RB-1:0]       s2_bx0_q, s2_bx1_q, s2_by0_q, s2_by1_q;
  logic                s2_range_q, s2_front_ccw_q;
  logic [1:0]          s2_cull_q;
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[1]) begin
      area2_d = '0;
      for (int k = 0; k < 3; k++) begin
        c_d[k*EVB +: EVB]  = EVB'($signed(s1_p_q[k*(2*CB) +: 2*CB])) - EVB'($signed(s1_q_q[k*(2*CB) +: 2*CB]));
        area2_d = area2_d + $signed(c_d[k*EVB +: EVB]);
      end
      // ceil((min - h) / 2^G) = floor((min - h + 2^G - 1) / 2^G); floor((max - h) / 2^G)
      lo_x = (CB+2)'($signed(s1_xmin_q)) + (CB+2)'(HalfPx - 1);
      lo_y = (CB+2)'($signed(s1_ymin_q)) + (CB+2)'(HalfPx - 1);
      hi_x = (CB+2)'($signed(s1_xmax_q)) - (CB+2)'(HalfPx);
      hi_y = (CB+2)'($signed(s1_ymax_q)) - (CB+2)'(HalfPx);
      bx0_d = RB'(lo_x >>> G);
      by0_d = RB'(lo_y >>> G);
      bx1_d = RB'(hi_x >>> G);
      by1_d = RB'(hi_y >>> G);
      if ($signed(s1_rx0_q) > bx0_d) bx0_d = $signed(s1_rx0_q);
      if ($signed(s1_ry0_q) > by0_d) by0_d = $signed(s1_ry0_q);
      if ($signed(s1_rx1_q) < bx1_d) bx1_d = $signed(s1_rx1_q);
      if ($signed(s1_ry1_q) < by1_d) by1_d = $signed(s1_ry1_q);
      s2_a_q         <= s1_a_q;
      s2_b_q         <= s1_b_q;
      s2_c_q         <= c_d;
      s2_area2_q     <= area2_d;
      s2_bx0_q       <= bx0_d;
      s2_bx1_q       <= bx1_d;
      s2_by0_q       <= by0_d;
      s2_by1_q       <= by1_d;
      s2_range_q     <= s1_range_q;
      s2_front_ccw_q <= s1_front_ccw_q;
      s2_cull_q      <= s1_cull_q;
    end
  end
  /* verilator lint_on BLKSEQ */

  // ---- stage 3 ------------------------------------------------------------------------------
  logic                  ccw, front, back, empty;
  outcome_e              outcome_d;
  logic [3*ECB-1:0]   a_n, b_n;
  logic [3*EVB-1:0]   c_n;
  logic [2:0]            bias_d;
  logic [EVB-1:0]        area2_n;
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[2]) begin
      ccw   = $signed(s2_area2_q) > 0;
      front = ccw == s2_front_ccw_q;
      back  = (s2_cull_q == CullBack && !front) || (s2_cull_q == CullFront && front);
      empty = $signed(s2_bx0_q) > $signed(s2_bx1_q) || $signed(s2_by0_q) > $signed(s2_by1_q);
      if (s2_range_q)            outcome_d = OutcomeRange;
      else if (s2_area2_q == '0) outcome_d = OutcomeZeroArea;
      else if (back)             outcome_d = OutcomeBackface;
      else if (empty)            outcome_d = OutcomeNoSamples;
      else                       outcome_d = OutcomeOk;
      for (int k = 0; k < 3; k++) begin
        a_n[k*ECB +: ECB] = ccw ? s2_a_q[k*ECB +: ECB] : -s2_a_q[k*ECB +: ECB];
        b_n[k*ECB +: ECB] = ccw ? s2_b_q[k*ECB +: ECB] : -s2_b_q[k*ECB +: ECB];
        c_n[k*EVB +: EVB] = ccw ? s2_c_q[k*EVB +: EVB] : -s2_c_q[k*EVB +: EVB];
        // left: a > 0; top: a = 0 and b < 0 (the gradient (a, b) points inside)
        bias_d[k] = !(($signed(a_n[k*ECB +: ECB]) > 0) || (a_n[k*ECB +: ECB] == '0 && $signed(b_n[k*ECB +: ECB]) < 0));
      end
      area2_n = ccw ? s2_area2_q : -s2_area2_q;
      outcome_o <= outcome_d;
      a_o       <= a_n;
      b_o       <= b_n;
      c_o       <= c_n;
      bias_o    <= bias_d;
      area2_o   <= area2_n;
      front_o   <= front;
      x0_o      <= PB'(s2_bx0_q);
      x1_o      <= PB'(s2_bx1_q);
      y0_o      <= PB'(s2_by0_q);
      y1_o      <= PB'(s2_by1_q);
    end
  end
  /* verilator lint_on BLKSEQ */
endmodule
