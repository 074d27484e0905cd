// fxr_setup_attr: the edge functions the depth and varying planes are built from, four register
// stages, instantiated by fxr_setup after fxr_setup_edges. Model: fxr::attr_setup and
// make_attr_plane (model/stages/attr.cpp), make_plane (model/stages/setup.cpp); rules:
// docs/pipeline.md, "Attribute positions".
//
// Attribute triangle (Attr: AttrSubpixelBits > SubpixelBits), relative to vertex 0:
//   A1  M = max(2^A, |ax_k - ax_0|, |ay_k - ay_0|, |i*2^A + 2^(A-1) - ax_0| for i in {x0, x1},
//       likewise rows) as the OR of the magnitudes (same leading one), drop = max(0, msb(M) + 3 - W)
//   A2  X_k = RNE(ax_k / 2^drop) (F = A - drop fraction bits), x_k = X_k - X_0 (likewise y)
//   A3  a_k = y_{k+1} - y_{k+2}, b_k = x_{k+2} - x_{k+1}; c_0 = x_1*y_2 - x_2*y_1 (c_1 = c_2 = 0:
//       vertex 0 is the origin); the anchor, the candidate rectangle's corner pixel centre,
//       X0 = x0*2^F + 2^(F-1) - X_0, Y0 likewise
//   A4  2A' = c_0; zero: the planes fall back to the snapped triangle; negative: a, b, c negated;
//       per edge C_k = a_k*X0 + b_k*Y0 + c_k (the edge function at the anchor)
// Outputs per edge k: a_k, b_k, C_k and the step shift s, so that a plane with vertex values q_k
// is c = sum C_k q_k, dx = (sum a_k q_k) * 2^s, dy = (sum b_k q_k) * 2^s: s = F and the anchor
// (x0, y0) on the attribute triangle; on the snapped triangle (fallback, or not Attr) the
// coverage edges with C_k = (a_k + b_k) * 2^(G-1) + c_k (the edge function at pixel (0, 0)),
// s = G and the anchor (0, 0).
module fxr_setup_attr #(
  parameter int SubpixelBits     = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits    = fxr_config_pkg::RasterWindowIntBits,
  parameter int AttrSubpixelBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int AttrCoordBits    = fxr_config_pkg::RasterAttrCoordBits,
  // derived
  localparam bit Attr = AttrSubpixelBits > SubpixelBits,
  localparam int G    = SubpixelBits > 0 ? SubpixelBits : 1,
  localparam int A    = Attr ? AttrSubpixelBits : G,           // (A is unused without Attr)
  localparam int W    = AttrCoordBits,
  localparam int AXB  = WindowIntBits + AttrSubpixelBits,       // attribute position port
  localparam int PB   = WindowIntBits,                          // pixel index
  localparam int CB   = WindowIntBits + G,
  localparam int ECB  = CB + 1,                                 // coverage edge coefficient
  localparam int EVB  = 2 * CB + 2,                             // coverage edge value
  localparam int AB   = (W + 2 > ECB ? W + 2 : ECB),            // plane edge coefficient a, b
  localparam int CWB  = (2 * W + 2 > EVB ? 2 * W + 2 : EVB),    // plane edge value C
  localparam int SHB  = $clog2((A > G ? A : G) + 1)             // step shift
) (
  input  logic                clk_i,
  input  logic                en_i,
  input  logic [3:0]          v_i,        // v_i[s]: stage s's input is valid (else skipped)
  input  logic [3*AXB-1:0]    ax_i,       // signed, AttrSubpixelBits fraction bits
  input  logic [3*AXB-1:0]    ay_i,
  input  logic [PB-1:0]       x0_i,       // candidate rectangle (signed)
  input  logic [PB-1:0]       x1_i,
  input  logic [PB-1:0]       y0_i,
  input  logic [PB-1:0]       y1_i,
  input  logic [3*ECB-1:0]    ea_i,       // coverage edges, counter-clockwise normalised
  input  logic [3*ECB-1:0]    eb_i,
  input  logic [3*EVB-1:0]    ec_i,
  // after four enabled clocks:
  output logic                attr_o,     // the planes are on the attribute triangle
  output logic [3*AB-1:0]     a_o,        // signed
  output logic [3*AB-1:0]     b_o,
  output logic [3*CWB-1:0]    c_o,
  output logic [SHB-1:0]      shift_o,
  output logic [PB-1:0]       i0_o,       // anchor (0 on the snapped triangle)
  output logic [PB-1:0]       j0_o,
  output logic [CWB-1:0]      area2_o     // 2A' (> 0) when attr_o
);
  localparam int MB      = AXB + 2;                        // relative magnitudes at A bits
  localparam int DropMax = (MB + 2 > W) ? MB + 2 - W : 0;  // msb(M) <= MB - 1
  localparam int DRB     = $clog2(DropMax + 1) > 0 ? $clog2(DropMax + 1) : 1;
  localparam int RW      = W + 1;                          // relative coordinate (fits W bits)
  localparam int XW      = W + 2;                          // anchor offset X0 (fits W bits)
  localparam int PW      = 2 * W + 4;                      // products and C before truncation

  // ---- A1: how many fraction bits the triangle keeps ---------------------------------------
  logic signed [MB-1:0] ox, oy, rel, cnr;
  logic [MB-1:0]        orm;
  logic [DRB-1:0]       drop_d;
  int                   msb;
  always_comb begin
    ox = '0;
    oy = '0;
    rel = '0;
    cnr = '0;
    orm = '0;
    drop_d = '0;
    msb = 0;
    if (v_i[0]) begin
      ox  = MB'($signed(ax_i[0 +: AXB]));
      oy  = MB'($signed(ay_i[0 +: AXB]));
      orm = MB'(1) << A;
      for (int k = 1; k < 3; k++) begin
        rel = MB'($signed(ax_i[k*AXB +: AXB])) - ox;
        orm |= rel < 0 ? MB'(-rel) : MB'(rel);
        rel = MB'($signed(ay_i[k*AXB +: AXB])) - oy;
        orm |= rel < 0 ? MB'(-rel) : MB'(rel);
      end
      cnr = (MB'($signed(x0_i)) <<< A) + (MB'(1) <<< (A - 1)) - ox;
      orm |= cnr < 0 ? MB'(-cnr) : MB'(cnr);
      cnr = (MB'($signed(x1_i)) <<< A) + (MB'(1) <<< (A - 1)) - ox;
      orm |= cnr < 0 ? MB'(-cnr) : MB'(cnr);
      cnr = (MB'($signed(y0_i)) <<< A) + (MB'(1) <<< (A - 1)) - oy;
      orm |= cnr < 0 ? MB'(-cnr) : MB'(cnr);
      cnr = (MB'($signed(y1_i)) <<< A) + (MB'(1) <<< (A - 1)) - oy;
      orm |= cnr < 0 ? MB'(-cnr) : MB'(cnr);
      msb = 0;
      for (int b = 0; b < MB; b++) if (orm[b]) msb = b;
      drop_d = (msb + 3 > W) ? DRB'(msb + 3 - W) : '0;
    end
  end

  logic [3*AXB-1:0] a1_ax_q, a1_ay_q;
  logic [DRB-1:0]   a1_drop_q;
  logic [PB-1:0]    a1_x0_q, a1_y0_q;
  logic [3*ECB-1:0] a1_ea_q, a1_eb_q;
  logic [3*EVB-1:0] a1_ec_q;
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[0]) begin
      a1_ax_q   <= ax_i;
      a1_ay_q   <= ay_i;
      a1_drop_q <= drop_d;
      a1_x0_q   <= x0_i;
      a1_y0_q   <= y0_i;
      a1_ea_q   <= ea_i;
      a1_eb_q   <= eb_i;
      a1_ec_q   <= ec_i;
    end
  end

  // ---- A2: positions at F bits (RNE), relative to vertex 0 ---------------------------------
  logic signed [AXB-1:0] px [3], py [3];
  logic signed [AXB:0]   wide;
  logic [2*RW-1:0]       rx_d, ry_d;  // vertices 1 and 2
  function automatic logic signed [AXB-1:0] rne_drop(logic signed [AXB-1:0] v, logic [DRB-1:0] s);
    logic signed [AXB-1:0] fl;
    logic [AXB-1:0]        rem, half;
    fl   = v >>> s;
    rem  = AXB'(v) & ((AXB'(1) << s) - AXB'(1));
    half = (AXB'(1) << s) >> 1;
    // RNE: up when the dropped part exceeds one half, or equals it and the floor is odd
    if (s != '0 && (rem > half || (rem == half && fl[0]))) fl = fl + AXB'(1);
    rne_drop = fl;
  endfunction
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      px[k] = '0;
      py[k] = '0;
    end
    wide = '0;
    rx_d = '0;
    ry_d = '0;
    if (v_i[1]) begin
      for (int k = 0; k < 3; k++) begin
        px[k] = rne_drop($signed(a1_ax_q[k*AXB +: AXB]), a1_drop_q);
        py[k] = rne_drop($signed(a1_ay_q[k*AXB +: AXB]), a1_drop_q);
      end
      for (int k = 1; k < 3; k++) begin
        wide = (AXB+1)'(px[k]) - (AXB+1)'(px[0]);
        rx_d[(k-1)*RW +: RW] = RW'(wide);
        wide = (AXB+1)'(py[k]) - (AXB+1)'(py[0]);
        ry_d[(k-1)*RW +: RW] = RW'(wide);
      end
    end
  end

  logic [2*RW-1:0]  a2_rx_q, a2_ry_q;
  logic [AXB-1:0]   a2_ox_q, a2_oy_q;
  logic [SHB-1:0]   a2_f_q;
  logic [PB-1:0]    a2_x0_q, a2_y0_q;
  logic [3*ECB-1:0] a2_ea_q, a2_eb_q;
  logic [3*EVB-1:0] a2_ec_q;
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[1]) begin
      a2_rx_q <= rx_d;
      a2_ry_q <= ry_d;
      a2_ox_q <= px[0];
      a2_oy_q <= py[0];
      a2_f_q  <= SHB'(A) - SHB'(a1_drop_q);
      a2_x0_q <= a1_x0_q;
      a2_y0_q <= a1_y0_q;
      a2_ea_q <= a1_ea_q;
      a2_eb_q <= a1_eb_q;
      a2_ec_q <= a1_ec_q;
    end
  end

  // ---- A3: edge coefficients, 2A', anchor ----------------------------------------------------
  logic signed [RW-1:0]  vx [3], vy [3];
  logic [3*AB-1:0]       ta_d, tb_d;
  logic signed [PW-1:0]  c0_d;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [AXB+2:0] anc;  // exact; the anchor offset fits XW bits (docs/pipeline.md)
  /* verilator lint_on UNUSEDSIGNAL */
  logic [XW-1:0]         ax0_d, ay0_d;
  always_comb begin
    for (int k = 0; k < 3; k++) begin
      vx[k] = '0;
      vy[k] = '0;
    end
    ta_d = '0;
    tb_d = '0;
    c0_d = '0;
    anc = '0;
    ax0_d = '0;
    ay0_d = '0;
    if (v_i[2]) begin
      vx[0] = '0;
      vy[0] = '0;
      for (int k = 1; k < 3; k++) begin
        vx[k] = $signed(a2_rx_q[(k-1)*RW +: RW]);
        vy[k] = $signed(a2_ry_q[(k-1)*RW +: RW]);
      end
      for (int k = 0; k < 3; k++) begin
        ta_d[k*AB +: AB] = AB'(vy[(k + 1) % 3]) - AB'(vy[(k + 2) % 3]);
        tb_d[k*AB +: AB] = AB'(vx[(k + 2) % 3]) - AB'(vx[(k + 1) % 3]);
      end
      c0_d = PW'(vx[1]) * PW'(vy[2]) - PW'(vx[2]) * PW'(vy[1]);
      anc = ((AXB+3)'($signed(a2_x0_q)) <<< a2_f_q) + ((AXB+3)'(1) <<< (a2_f_q - SHB'(1))) - (AXB+3)'($signed(a2_ox_q));
      ax0_d = XW'(anc);
      anc = ((AXB+3)'($signed(a2_y0_q)) <<< a2_f_q) + ((AXB+3)'(1) <<< (a2_f_q - SHB'(1))) - (AXB+3)'($signed(a2_oy_q));
      ay0_d = XW'(anc);
    end
  end

  logic [3*AB-1:0]  a3_a_q, a3_b_q;
  logic [PW-1:0]    a3_c0_q;
  logic [XW-1:0]    a3_ax0_q, a3_ay0_q;
  logic [SHB-1:0]   a3_f_q;
  logic [PB-1:0]    a3_x0_q, a3_y0_q;
  logic [3*ECB-1:0] a3_ea_q, a3_eb_q;
  logic [3*EVB-1:0] a3_ec_q;
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[2]) begin
      a3_a_q   <= ta_d;
      a3_b_q   <= tb_d;
      a3_c0_q  <= c0_d;
      a3_ax0_q <= ax0_d;
      a3_ay0_q <= ay0_d;
      a3_f_q   <= a2_f_q;
      a3_x0_q  <= a2_x0_q;
      a3_y0_q  <= a2_y0_q;
      a3_ea_q  <= a2_ea_q;
      a3_eb_q  <= a2_eb_q;
      a3_ec_q  <= a2_ec_q;
    end
  end

  // ---- A4: orientation, the edge functions at the anchor, or the snapped triangle's ----------
  logic                 use_attr, flip;
  logic signed [AB-1:0] na, nb;
  logic signed [PW-1:0] nc;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [PW-1:0] cc;  // exact; the edge value at the anchor fits CWB bits
  /* verilator lint_on UNUSEDSIGNAL */
  logic [3*AB-1:0]      a_d, b_d;
  logic [3*CWB-1:0]     c_d;
  always_comb begin
    na = '0;
    nb = '0;
    nc = '0;
    cc = '0;
    a_d = '0;
    b_d = '0;
    c_d = '0;
    use_attr = 1'b0;
    flip = 1'b0;
    if (v_i[3]) begin
      use_attr = Attr && a3_c0_q != '0;
      flip     = a3_c0_q[PW-1];
      for (int k = 0; k < 3; k++) begin
        if (use_attr) begin
          na = $signed(a3_a_q[k*AB +: AB]);
          nb = $signed(a3_b_q[k*AB +: AB]);
          nc = (k == 0) ? $signed(a3_c0_q) : '0;
          if (flip) begin
            na = -na;
            nb = -nb;
            nc = -nc;
          end
          cc = PW'(na) * PW'($signed(a3_ax0_q)) + PW'(nb) * PW'($signed(a3_ay0_q)) + nc;
        end else begin
          na = AB'($signed(a3_ea_q[k*ECB +: ECB]));
          nb = AB'($signed(a3_eb_q[k*ECB +: ECB]));
          cc = ((PW'(na) + PW'(nb)) <<< (G - 1)) + PW'($signed(a3_ec_q[k*EVB +: EVB]));
        end
        a_d[k*AB +: AB]    = na;
        b_d[k*AB +: AB]    = nb;
        c_d[k*CWB +: CWB]  = CWB'(cc);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i && v_i[3]) begin
      attr_o  <= use_attr;
      a_o     <= a_d;
      b_o     <= b_d;
      c_o     <= c_d;
      shift_o <= use_attr ? a3_f_q : SHB'(G);
      i0_o    <= use_attr ? a3_x0_q : '0;
      j0_o    <= use_attr ? a3_y0_q : '0;
      area2_o <= CWB'(flip ? -a3_c0_q : a3_c0_q);
    end
  end
endmodule
