// fxr_line: line rasterisation, a snapped segment in, a stream of covered pixels out, one major-axis
// step per clock. Model: fxr::line_pixels / fxr::line_setup (model/stages/line.hpp); docs/lines.md.
//
// Function (bit-exact to the model, pixels in the model's order):
//   Rule = LineRuleMidpoint: in every major-axis pixel whose centre lies in the segment's major range
//     ([min, max) with Endpoints = LineEndpointsHalfOpen, [min, max] with LineEndpointsClosed), the
//     pixel whose minor interval holds the line's exact minor coordinate; ties to the smaller one.
//   Rule = LineRuleDiamondExit: the GL diamond-exit rule (open diamonds, p_b's diamond excluded).
//   Walk in the canonical frame (major axis A increasing, minor axis B reflected when it decreases),
//   doubled coordinates (pixel centres i*U + H), decision variable D = db*(A_c - A0) - da*((r+1)*U - B0).
//
// Ports:
//   clk_i, rst_ni                  clock, active-low asynchronous reset
//   in_valid_i / in_ready_o        segment handshake; in_ready_o is high only while idle
//   in_x0_i, in_y0_i, in_x1_i, in_y1_i [CoordBits]  signed endpoints, SubpixelBits fraction bits
//                                  (p0 first: p_a of the diamond-exit rule)
//   out_valid_o / out_ready_i      pixel handshake
//   out_x_o, out_y_o [WindowIntBits]  signed pixel indices (centre at index + 1/2)
//
// Timing: one set-up cycle after the input transfer, then one major-axis step per clock while the
// output is not stalled (a step the diamond-exit rule drops emits nothing), plus one step for a
// diamond-exit start pixel beyond the walk. A segment of n steps occupies the unit n + 2 cycles
// (n + 3 with that start pixel); in_ready_o rises again when the last step has been taken.
module fxr_line #(
  parameter int SubpixelBits  = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  parameter int Rule          = fxr_config_pkg::LineRule,       // fxr_config_pkg::line_rule_e
  parameter int Endpoints     = fxr_config_pkg::LineEndpoints,  // fxr_config_pkg::line_endpoints_e
  localparam int CoordBits    = WindowIntBits + SubpixelBits
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic                            in_valid_i,
  output logic                            in_ready_o,
  input  logic signed [CoordBits-1:0]     in_x0_i,
  input  logic signed [CoordBits-1:0]     in_y0_i,
  input  logic signed [CoordBits-1:0]     in_x1_i,
  input  logic signed [CoordBits-1:0]     in_y1_i,
  output logic                            out_valid_o,
  input  logic                            out_ready_i,
  output logic signed [WindowIntBits-1:0] out_x_o,
  output logic signed [WindowIntBits-1:0] out_y_o
);
  // ---- widths ---------------------------------------------------------------------------------
  // Doubled coordinates and their differences: |2x| < 2^(CoordBits), differences < 2^(CoordBits+1).
  // D and the set-up products: |D| < 2^(W + 2S + 3) (model/stages/line.hpp, line_decision_bits).
  // One wide signed type for all of it (W + 2S + 8 bits); synthesis trims the unused top bits.
  localparam int WW = WindowIntBits + 2 * SubpixelBits + 8;
  localparam int Sh = SubpixelBits + 1;  // log2 of U, one pixel in doubled units
  typedef logic signed [WW-1:0] wide_t;
  localparam logic signed [WW-1:0] H = WW'(1) <<< SubpixelBits;
  localparam bit Midpoint = Rule == fxr_config_pkg::LineRuleMidpoint;
  localparam bit HalfOpen = Endpoints == fxr_config_pkg::LineEndpointsHalfOpen;

  function automatic signed [WW-1:0] absw(input signed [WW-1:0] v);
    absw = v < 0 ? -v : v;
  endfunction
  function automatic signed [WW-1:0] floor_u(input signed [WW-1:0] v);  // floor(v / U)
    floor_u = v >>> Sh;
  endfunction
  function automatic signed [WW-1:0] ceil_u(input signed [WW-1:0] v);   // ceil(v / U)
    ceil_u = -((-v) >>> Sh);
  endfunction

  typedef enum logic [2:0] {StIdle, StSetup, StPre, StWalk, StPost} state_e;
  state_e state_q, state_d;

  // ---- input registers ------------------------------------------------------------------------
  logic signed [CoordBits-1:0] x0_q, y0_q, x1_q, y1_q;

  // ---- set-up (combinational from the input registers, registered into the walk state) -------
  wide_t X0, Y0, X1, Y1, a0, b0, a1, b1, pa_a, pa_b, pb_a, pb_b, da, db;
  wide_t first, last, cnt, row0, d0, ei, er, ecentre;
  logic  y_major, swapped, reflect, bias, extra, extra_before;

  always_comb begin
    X0 = WW'(x0_q) <<< 1;
    Y0 = WW'(y0_q) <<< 1;
    X1 = WW'(x1_q) <<< 1;
    Y1 = WW'(y1_q) <<< 1;
    y_major = absw(Y1 - Y0) > absw(X1 - X0);
    a0 = y_major ? Y0 : X0;
    b0 = y_major ? X0 : Y0;
    a1 = y_major ? Y1 : X1;
    b1 = y_major ? X1 : Y1;
    swapped = a1 < a0;
    if (swapped) begin
      {a0, a1} = {a1, a0};
      {b0, b1} = {b1, b0};
    end
    reflect = b1 < b0;
    if (reflect) begin
      b0 = -b0;
      b1 = -b1;
    end
    pa_a = swapped ? a1 : a0;
    pa_b = swapped ? b1 : b0;
    pb_a = swapped ? a0 : a1;
    pb_b = swapped ? b0 : b1;
    da = a1 - a0;
    db = b1 - b0;
    first = ceil_u(a0 - H);
    last = (Midpoint && HalfOpen) ? ceil_u(a1 - H) - 1 : floor_u(a1 - H);
    cnt = last >= first ? last - first + 1 : '0;
    // Ties to the smaller original minor coordinate: a bias of 1 in a reflected frame (midpoint).
    bias = Midpoint && reflect;
    row0 = floor_u(bias ? b0 : b0 - 1);
    // Both products have factors of at most one pixel (U): exact, within WW bits.
    d0 = db * ((first <<< Sh) + H - a0) - da * (((row0 + 1) <<< Sh) - b0);
    // Diamond exit: p_a inside a diamond whose centre lies beyond [a0, a1] along the major axis.
    ei = floor_u(pa_a);
    er = floor_u(pa_b);
    ecentre = (ei <<< Sh) + H;
    extra = !Midpoint && (ecentre < a0 || ecentre > a1) &&
            (absw(pa_a - ecentre) + absw(pa_b - ((er <<< Sh) + H)) < H) &&
            !(absw(pb_a - ecentre) + absw(pb_b - ((er <<< Sh) + H)) < H);
    extra_before = ecentre < a0;
  end

  // ---- walk state -------------------------------------------------------------------------------
  wide_t d_q, row_q, i_q, cnt_q, da_u_q, db_u_q, pb_a_q, pb_b_q, ei_q, er_q;
  logic  y_major_q, reflect_q, bias_q, extra_q, extra_before_q;

  // One step: the row correction, the pixel, the diamond-exit drop.
  wide_t d_corr, row_corr, minor, step_major, step_row;
  logic  inc, emit, pb_in, stepping, advance;
  always_comb begin
    inc = bias_q ? d_q >= 0 : d_q > 0;  // at most once per column: db <= da
    row_corr = inc ? row_q + 1 : row_q;
    d_corr = inc ? d_q - da_u_q : d_q;
    pb_in = absw(pb_a_q - ((i_q <<< Sh) + H)) + absw(pb_b_q - ((row_corr <<< Sh) + H)) < H;
    // D = 0 after the correction: the line crosses the centre line on two diamonds' corners.
    emit = Midpoint || (d_corr != 0 && !pb_in);
    step_major = i_q;
    step_row = row_corr;
    if (state_q != StWalk) begin  // StPre / StPost: the diamond-exit start pixel
      step_major = ei_q;
      step_row = er_q;
      emit = 1'b1;
    end
    minor = reflect_q ? -1 - step_row : step_row;
  end

  assign advance = out_ready_i | ~out_valid_o;
  assign stepping = advance && (state_q == StPre || state_q == StWalk || state_q == StPost);

  always_comb begin
    state_d = state_q;
    unique case (state_q)
      StIdle:  if (in_valid_i) state_d = StSetup;
      // (if / else rather than conditional expressions: Icarus 11 rejects an enum assigned from one)
      StSetup:
        if (extra && extra_before) state_d = StPre;
        else if (cnt > 0) state_d = StWalk;
        else if (extra) state_d = StPost;
        else state_d = StIdle;
      StPre:
        if (advance) begin
          if (cnt_q > 0) state_d = StWalk;
          else state_d = StIdle;
        end
      StWalk:
        if (advance && cnt_q == 1) begin
          if (extra_q && !extra_before_q) state_d = StPost;
          else state_d = StIdle;
        end
      StPost:  if (advance) state_d = StIdle;
      default: state_d = StIdle;
    endcase
  end

  assign in_ready_o = state_q == StIdle;

  logic                            out_valid_q;
  logic signed [WindowIntBits-1:0] out_x_q, out_y_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= StIdle;
      out_valid_q <= 1'b0;
    end else begin
      state_q <= state_d;
      if (advance) out_valid_q <= stepping && emit;
    end
  end

  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) begin
      x0_q <= in_x0_i;
      y0_q <= in_y0_i;
      x1_q <= in_x1_i;
      y1_q <= in_y1_i;
    end
    if (state_q == StSetup) begin
      d_q <= d0;
      row_q <= row0;
      i_q <= first;
      cnt_q <= cnt;
      da_u_q <= da <<< Sh;
      db_u_q <= db <<< Sh;
      pb_a_q <= pb_a;
      pb_b_q <= pb_b;
      ei_q <= ei;
      er_q <= er;
      y_major_q <= y_major;
      reflect_q <= reflect;
      bias_q <= bias;
      extra_q <= extra;
      extra_before_q <= extra_before;
    end else if (state_q == StWalk && advance) begin
      row_q <= row_corr;
      d_q <= d_corr + db_u_q;
      i_q <= i_q + 1;
      cnt_q <= cnt_q - 1;
    end
    if (stepping) begin
      out_x_q <= y_major_q ? minor[WindowIntBits-1:0] : step_major[WindowIntBits-1:0];
      out_y_q <= y_major_q ? step_major[WindowIntBits-1:0] : minor[WindowIntBits-1:0];
    end
  end

  // Pixel indices fit WindowIntBits (|x| < 2^(W-1) px); the top bits of the wide type are unused.
  logic unused_hi;
  assign unused_hi = ^{minor[WW-1:WindowIntBits], step_major[WW-1:WindowIntBits]};

  assign out_valid_o = out_valid_q;
  assign out_x_o = out_x_q;
  assign out_y_o = out_y_q;

endmodule
