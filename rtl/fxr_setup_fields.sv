// fxr_setup_fields: stage 5, triangle setup (issue 10), with one port per vector field (the setup
// vector unit's layout; rtl/fxr_setup.sv wraps it with the record ports of fxr_rec_pkg). One
// snapped triangle and the draw state in, its equations out: edge functions, top-left bias, 2A, culling, the candidate rectangle and the
// depth, 1/w and v/w planes. Model: fxr::SetupStage (model/stages/setup.hpp, setup.cpp,
// attr.cpp); rules and figures: docs/pipeline.md, stage 5 and "Attribute positions"; vectors:
// vectors/setup/ (model/vectors/setup_vectors.hpp: the port list is the vector layout, the
// fields with _i / _o).
//
// Ports:
//   clk_i, rst_ni                      clock, active-low asynchronous reset
//   in_valid_i / in_ready_o            input handshake (transfer when both are high)
//   prim_i                             primitive index (passes through to out_prim_o)
//   v<k>_x_i, v<k>_y_i [XB]            snapped window position, signed, SubpixelBits fraction bits
//   v<k>_ax_i, v<k>_ay_i [AXB]         attribute position, signed, AttrSubpixelBits fraction bits
//                                      (unused when AttrSubpixelBits <= SubpixelBits)
//   v<k>_z_i [ZB]                      z/w, ZFracBits fraction bits (more than 1: range)
//   v<k>_rw_*, v<k>_vw<m>_*            1/w and v_m/w: sign, significand (msb set, or 0), exponent
//                                      of the significand's lsb
//   viewport_*_i, scissor_*_i          draw rectangle (pixels, signed); no scissor when a scissor
//                                      size is negative
//   cull_i (cull_e of fxr_setup_edges), front_ccw_i, interp_i (1 = affine: 1/w plane of ones)
//   out_valid_o / out_ready_i          output handshake
//   outcome_o                          ok, zero area, back face, no samples, range (the model's
//                                      precedence); when not ok every other output is 0
//   out_prim_o                         prim_i of the triangle
//   e<k>_a_o, e<k>_b_o, e<k>_c_o       edge function k (opposite vertex k) on the sample grid,
//                                      counter-clockwise normalised (E_k >= 0 inside)
//   e<k>_bias_o                        top-left bias (1 = -1: not a top or left edge)
//   area2_o, front_o                   2A (> 0), front-facing
//   x0_o, x1_o, y0_o, y1_o             candidate pixels (inclusive): bounding box ∩ viewport ∩
//                                      scissor ∩ window range
//   z_*_o, z_den_o                     depth plane (c at the anchor (i0, j0), dx, dy) and divisor
//   den_*_o, den_exp_o                 1/w plane and its block exponent
//   num<m>_*_o, num<m>_exp_o           v_m/w planes and their block exponents
//
// Latency (cycles from the input transfer to out_valid_o, = SetupStage::cost().latency): 9 =
// 3 (fxr_setup_edges) + 4 (fxr_setup_attr) + 2 (fxr_setup_plane). Initiation interval 1.
// out_ready_i low stalls every stage (in_ready_o = out_ready_i | ~out_valid_o); no result is
// lost or duplicated. Two varyings (kSetupVecVaryings): each more is one more fxr_setup_align
// and fxr_setup_plane.
module fxr_setup_fields #(
  parameter int SubpixelBits     = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits    = fxr_config_pkg::RasterWindowIntBits,
  parameter int ZFracBits        = fxr_config_pkg::RasterZFracBits,
  parameter int DepthFormat      = fxr_config_pkg::RasterDepthFormat,  // raster_depth_format_e
  parameter int InterpBlockBits  = fxr_config_pkg::RasterInterpBlockBits,
  parameter int AttrSubpixelBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int AttrCoordBits    = fxr_config_pkg::RasterAttrCoordBits,
  parameter int AttrSigBits      = fxr_config_pkg::RasterAttrSigBits,
  parameter int VaryingSigBits   = fxr_config_pkg::RasterVaryingSigBits,
  parameter int RecipOutSigBits  = fxr_config_pkg::RecipOutSigBits,
  parameter int RecipExpBits     = fxr_config_pkg::RecipExpBits,
  // derived (model/stages/setup.hpp, model/unit/record.hpp)
  localparam bit Attr       = AttrSubpixelBits > SubpixelBits,   // attr_planes
  localparam int G          = SubpixelBits > 0 ? SubpixelBits : 1,
  localparam int XB         = WindowIntBits + SubpixelBits,      // snapped position
  localparam int AXB        = WindowIntBits + AttrSubpixelBits,  // attribute position
  localparam int ZB         = ZFracBits + 1,
  localparam int CB         = WindowIntBits + G,                 // coord_bits
  localparam int ECB        = CB + 1,                            // edge_coef_bits
  localparam int EVB        = 2 * CB + 2,                        // edge_value_bits
  localparam int Db         = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PEB        = Attr ? 2 * AttrCoordBits + 2 : EVB,                 // plane_edge_bits
  localparam int IPB        = PEB + InterpBlockBits + 1 + 2,                      // interp_plane_bits
  localparam int ZPB        = PEB + ZFracBits + 1 + (Attr ? 0 : Db) + 2,          // depth_plane_bits
  localparam int ZDB        = PEB - 1 + ZFracBits - (Attr ? Db : 0),              // depth_den_bits
  localparam int RwSigBits  = Attr ? AttrSigBits : RecipOutSigBits,
  localparam int VwSigBits  = Attr ? AttrSigBits : VaryingSigBits,
  // fx_exp_field_bits: max(recip.exp_bits, float32 exponent bits + 1) + 2
  localparam int F32ExpBits = 8,
  localparam int EB         = (RecipExpBits > F32ExpBits + 1 ? RecipExpBits : F32ExpBits + 1) + 2,
  localparam int PrimBits   = 32,                                // kPrimIdBits
  localparam int PB         = WindowIntBits                      // pixel index
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          in_valid_i,
  output logic                          in_ready_o,
  input  logic [PrimBits-1:0]           prim_i,
  input  logic [XB-1:0]                 v0_x_i,
  input  logic [XB-1:0]                 v0_y_i,
  input  logic [AXB-1:0]                v0_ax_i,
  input  logic [AXB-1:0]                v0_ay_i,
  input  logic [ZB-1:0]                 v0_z_i,
  input  logic                          v0_rw_neg_i,
  input  logic [RwSigBits-1:0]          v0_rw_sig_i,
  input  logic [EB-1:0]                 v0_rw_exp_i,
  input  logic                          v0_vw0_neg_i,
  input  logic [VwSigBits-1:0]          v0_vw0_sig_i,
  input  logic [EB-1:0]                 v0_vw0_exp_i,
  input  logic                          v0_vw1_neg_i,
  input  logic [VwSigBits-1:0]          v0_vw1_sig_i,
  input  logic [EB-1:0]                 v0_vw1_exp_i,
  input  logic [XB-1:0]                 v1_x_i,
  input  logic [XB-1:0]                 v1_y_i,
  input  logic [AXB-1:0]                v1_ax_i,
  input  logic [AXB-1:0]                v1_ay_i,
  input  logic [ZB-1:0]                 v1_z_i,
  input  logic                          v1_rw_neg_i,
  input  logic [RwSigBits-1:0]          v1_rw_sig_i,
  input  logic [EB-1:0]                 v1_rw_exp_i,
  input  logic                          v1_vw0_neg_i,
  input  logic [VwSigBits-1:0]          v1_vw0_sig_i,
  input  logic [EB-1:0]                 v1_vw0_exp_i,
  input  logic                          v1_vw1_neg_i,
  input  logic [VwSigBits-1:0]          v1_vw1_sig_i,
  input  logic [EB-1:0]                 v1_vw1_exp_i,
  input  logic [XB-1:0]                 v2_x_i,
  input  logic [XB-1:0]                 v2_y_i,
  input  logic [AXB-1:0]                v2_ax_i,
  input  logic [AXB-1:0]                v2_ay_i,
  input  logic [ZB-1:0]                 v2_z_i,
  input  logic                          v2_rw_neg_i,
  input  logic [RwSigBits-1:0]          v2_rw_sig_i,
  input  logic [EB-1:0]                 v2_rw_exp_i,
  input  logic                          v2_vw0_neg_i,
  input  logic [VwSigBits-1:0]          v2_vw0_sig_i,
  input  logic [EB-1:0]                 v2_vw0_exp_i,
  input  logic                          v2_vw1_neg_i,
  input  logic [VwSigBits-1:0]          v2_vw1_sig_i,
  input  logic [EB-1:0]                 v2_vw1_exp_i,
  input  logic [WindowIntBits-1:0]      viewport_x_i,
  input  logic [WindowIntBits-1:0]      viewport_y_i,
  input  logic [WindowIntBits:0]        viewport_w_i,
  input  logic [WindowIntBits:0]        viewport_h_i,
  input  logic [WindowIntBits-1:0]      scissor_x_i,
  input  logic [WindowIntBits-1:0]      scissor_y_i,
  input  logic [WindowIntBits:0]        scissor_w_i,
  input  logic [WindowIntBits:0]        scissor_h_i,
  input  logic [1:0]                    cull_i,
  input  logic                          front_ccw_i,
  input  logic                          interp_i,
  output logic                          out_valid_o,
  input  logic                          out_ready_i,
  output logic [2:0]                    outcome_o,
  output logic [PrimBits-1:0]           out_prim_o,
  output logic [ECB-1:0]                e0_a_o,
  output logic [ECB-1:0]                e0_b_o,
  output logic [EVB-1:0]                e0_c_o,
  output logic                          e0_bias_o,
  output logic [ECB-1:0]                e1_a_o,
  output logic [ECB-1:0]                e1_b_o,
  output logic [EVB-1:0]                e1_c_o,
  output logic                          e1_bias_o,
  output logic [ECB-1:0]                e2_a_o,
  output logic [ECB-1:0]                e2_b_o,
  output logic [EVB-1:0]                e2_c_o,
  output logic                          e2_bias_o,
  output logic [EVB-1:0]                area2_o,
  output logic                          front_o,
  output logic [PB-1:0]                 x0_o,
  output logic [PB-1:0]                 x1_o,
  output logic [PB-1:0]                 y0_o,
  output logic [PB-1:0]                 y1_o,
  output logic [ZPB-1:0]            z_c_o,
  output logic [ZPB-1:0]            z_dx_o,
  output logic [ZPB-1:0]            z_dy_o,
  output logic [PB-1:0]             z_i0_o,
  output logic [PB-1:0]             z_j0_o,
  output logic [ZDB-1:0]            z_den_o,
  output logic [IPB-1:0]            den_c_o,
  output logic [IPB-1:0]            den_dx_o,
  output logic [IPB-1:0]            den_dy_o,
  output logic [PB-1:0]             den_i0_o,
  output logic [PB-1:0]             den_j0_o,
  output logic [EB-1:0]             den_exp_o,
  output logic [IPB-1:0]            num0_c_o,
  output logic [IPB-1:0]            num0_dx_o,
  output logic [IPB-1:0]            num0_dy_o,
  output logic [PB-1:0]             num0_i0_o,
  output logic [PB-1:0]             num0_j0_o,
  output logic [EB-1:0]             num0_exp_o,
  output logic [IPB-1:0]            num1_c_o,
  output logic [IPB-1:0]            num1_dx_o,
  output logic [IPB-1:0]            num1_dy_o,
  output logic [PB-1:0]             num1_i0_o,
  output logic [PB-1:0]             num1_j0_o,
  output logic [EB-1:0]             num1_exp_o
);
  localparam int EdgeStages  = 3;  // fxr_setup_edges
  localparam int AttrStages  = 4;  // fxr_setup_attr
  localparam int PlaneStages = 2;  // fxr_setup_plane
  localparam int Latency     = EdgeStages + AttrStages + PlaneStages;
  localparam int Last        = Latency - 1;
  localparam int QB          = InterpBlockBits + 2;  // block-aligned vertex values (fxr_setup_align)
  localparam int ZQB         = ZB + 1;               // depth vertex values, signed
  localparam int W           = AttrCoordBits;
  localparam int AB          = (W + 2 > ECB ? W + 2 : ECB);          // as fxr_setup_attr
  localparam int CWB         = (2 * W + 2 > EVB ? 2 * W + 2 : EVB);
  localparam int SHB         = $clog2(((Attr ? AttrSubpixelBits : G) > G ? AttrSubpixelBits : G) + 1);
  localparam int NV          = 2;                    // varyings (kSetupVecVaryings)

  // ---- handshake: one global enable, the pipeline holds while the output is stalled --------
  logic [Latency-1:0] valid_q;
  logic               advance;
  assign advance     = out_ready_i | ~valid_q[Last];
  assign in_ready_o  = advance;
  assign out_valid_o = valid_q[Last];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else if (advance) begin
      valid_q <= {valid_q[Last-1:0], in_valid_i};
    end
  end
  // vs[c]: the data c registers after the input is valid. Each register stage loads, and each
  // combinational stage computes, only for valid data (held / 0 otherwise: nothing reads it), so
  // that the simulator skips an idle setup's wide products (docs/rtl.md, "Co-simulation speed").
  // Combinational logic reads valid_q only (vs[c] = valid_q[c-1] for c >= 1): in
  // fxr_raster_backend in_valid_i is a top-level input, and Verilator evaluates combinational
  // logic on one in both eval()s of a clock (docs/rtl.md, "Co-simulation speed", session 9); vs
  // (with in_valid_i) goes only to clocked processes (fxr_setup_edges, fxr_pipe).
  logic [Latency:0] vs;
  assign vs = {valid_q, in_valid_i};

  // ---- coverage: edges, 2A, culling, candidate rectangle (cycles 1-3) -----------------------
  logic [2:0]       outcome;
  logic [3*ECB-1:0] ea, eb;
  logic [3*EVB-1:0] ec;
  logic [2:0]       ebias;
  logic [EVB-1:0]   area2;
  logic             front;
  logic [PB-1:0]    bx0, bx1, by0, by1;

  fxr_setup_edges #(
    .SubpixelBits (SubpixelBits),
    .WindowIntBits(WindowIntBits),
    .ZFracBits    (ZFracBits)
  ) u_edges (
    .clk_i       (clk_i),
    .en_i        (advance),
    .v_i         (vs[EdgeStages-1:0]),
    .x_i         ({v2_x_i, v1_x_i, v0_x_i}),
    .y_i         ({v2_y_i, v1_y_i, v0_y_i}),
    .z_i         ({v2_z_i, v1_z_i, v0_z_i}),
    .viewport_x_i(viewport_x_i),
    .viewport_y_i(viewport_y_i),
    .viewport_w_i(viewport_w_i),
    .viewport_h_i(viewport_h_i),
    .scissor_x_i (scissor_x_i),
    .scissor_y_i (scissor_y_i),
    .scissor_w_i (scissor_w_i),
    .scissor_h_i (scissor_h_i),
    .cull_i      (cull_i),
    .front_ccw_i (front_ccw_i),
    .outcome_o   (outcome),
    .a_o         (ea),
    .b_o         (eb),
    .c_o         (ec),
    .bias_o      (ebias),
    .area2_o     (area2),
    .front_o     (front),
    .x0_o        (bx0),
    .x1_o        (bx1),
    .y0_o        (by0),
    .y1_o        (by1)
  );

  // ---- the planes' edge functions: attribute triangle or snapped (cycles 4-7) ---------------
  logic [3*AXB-1:0] ax_e, ay_e;  // attribute positions at cycle 3
  fxr_pipe #(.Width(6 * AXB), .Stages(EdgeStages)) u_pipe_axy (
    .clk_i(clk_i), .en_i(advance), .v_i(vs[EdgeStages-1:0]),
    .d_i  ({v2_ax_i, v1_ax_i, v0_ax_i, v2_ay_i, v1_ay_i, v0_ay_i}),
    .q_o  ({ax_e, ay_e})
  );

  logic             use_attr;
  logic [3*AB-1:0]  pa, pb;
  logic [3*CWB-1:0] pc;
  logic [SHB-1:0]   pshift;
  logic [PB-1:0]    pi0, pj0;
  logic [CWB-1:0]   area2_attr;

  fxr_setup_attr #(
    .SubpixelBits    (SubpixelBits),
    .WindowIntBits   (WindowIntBits),
    .AttrSubpixelBits(AttrSubpixelBits),
    .AttrCoordBits   (AttrCoordBits)
  ) u_attr (
    .clk_i  (clk_i),
    .en_i   (advance),
    .v_i    (valid_q[EdgeStages-1 +: AttrStages]),
    .ax_i   (ax_e),
    .ay_i   (ay_e),
    .x0_i   (bx0),
    .x1_i   (bx1),
    .y0_i   (by0),
    .y1_i   (by1),
    .ea_i   (ea),
    .eb_i   (eb),
    .ec_i   (ec),
    .attr_o (use_attr),
    .a_o    (pa),
    .b_o    (pb),
    .c_o    (pc),
    .shift_o(pshift),
    .i0_o   (pi0),
    .j0_o   (pj0),
    .area2_o(area2_attr)
  );

  // ---- vertex values: registered as they come (cycle 1), block-aligned there, delayed to the
  // planes (cycle 7). The alignment reads the register, not the input ports: in
  // fxr_raster_backend these are top-level ports, and Verilator evaluates combinational logic on
  // top-level inputs in both eval()s of a clock (docs/rtl.md, "Co-simulation speed", session 9).
  localparam int RwRaw = 3 * (1 + RwSigBits + EB);  // {neg, sig, exp} of the three vertices
  localparam int VwRaw = 3 * (1 + VwSigBits + EB);
  logic [RwRaw-1:0] raw_rw;
  logic [VwRaw-1:0] raw_vw0, raw_vw1;
  logic             interp_q;  // interp_i of the triangle (the vector unit changes it per triangle)
  always_ff @(posedge clk_i) begin
    if (advance && in_valid_i) begin
      interp_q  <= interp_i;
      raw_rw    <= {v2_rw_neg_i, v1_rw_neg_i, v0_rw_neg_i, v2_rw_sig_i, v1_rw_sig_i, v0_rw_sig_i,
                    v2_rw_exp_i, v1_rw_exp_i, v0_rw_exp_i};
      raw_vw0   <= {v2_vw0_neg_i, v1_vw0_neg_i, v0_vw0_neg_i, v2_vw0_sig_i, v1_vw0_sig_i, v0_vw0_sig_i,
                    v2_vw0_exp_i, v1_vw0_exp_i, v0_vw0_exp_i};
      raw_vw1   <= {v2_vw1_neg_i, v1_vw1_neg_i, v0_vw1_neg_i, v2_vw1_sig_i, v1_vw1_sig_i, v0_vw1_sig_i,
                    v2_vw1_exp_i, v1_vw1_exp_i, v0_vw1_exp_i};
    end
  end

  logic [3*QB-1:0] q_den, q_num [NV];
  logic [EB-1:0]   exp_den, exp_num [NV];
  logic [3*QB-1:0] q_rw;
  logic [EB-1:0]   exp_rw;

  fxr_setup_align #(.SigBits(RwSigBits), .ExpBits(EB), .Bits(InterpBlockBits)) u_align_rw (
    .en_i (valid_q[0]),
    .neg_i(raw_rw[RwRaw-1 -: 3]),
    .sig_i(raw_rw[3*EB +: 3*RwSigBits]),
    .exp_i(raw_rw[0 +: 3*EB]),
    .q_o  (q_rw),
    .exp_o(exp_rw)
  );
  // Affine: the denominator's vertex values are 1 (D = 2A), its exponent 0.
  assign q_den   = interp_q ? {QB'(1), QB'(1), QB'(1)} : q_rw;
  assign exp_den = interp_q ? '0 : exp_rw;

  fxr_setup_align #(.SigBits(VwSigBits), .ExpBits(EB), .Bits(InterpBlockBits)) u_align_vw0 (
    .en_i (valid_q[0]),
    .neg_i(raw_vw0[VwRaw-1 -: 3]),
    .sig_i(raw_vw0[3*EB +: 3*VwSigBits]),
    .exp_i(raw_vw0[0 +: 3*EB]),
    .q_o  (q_num[0]),
    .exp_o(exp_num[0])
  );
  fxr_setup_align #(.SigBits(VwSigBits), .ExpBits(EB), .Bits(InterpBlockBits)) u_align_vw1 (
    .en_i (valid_q[0]),
    .neg_i(raw_vw1[VwRaw-1 -: 3]),
    .sig_i(raw_vw1[3*EB +: 3*VwSigBits]),
    .exp_i(raw_vw1[0 +: 3*EB]),
    .q_o  (q_num[1]),
    .exp_o(exp_num[1])
  );

  localparam int PlaneIn = EdgeStages + AttrStages;  // cycle at which the planes start
  logic [3*QB-1:0] q_den_p, q_num_p [NV];
  logic [3*ZB-1:0] z_p;
  fxr_pipe #(.Width(3 * ZB), .Stages(PlaneIn)) u_pipe_z (
    .clk_i(clk_i), .en_i(advance), .v_i(vs[PlaneIn-1:0]),
    .d_i  ({v2_z_i, v1_z_i, v0_z_i}),
    .q_o  (z_p)
  );
  fxr_pipe #(.Width(3 * QB), .Stages(PlaneIn - 1)) u_pipe_qden (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-2:0]), .d_i(q_den), .q_o(q_den_p)
  );
  for (genvar m = 0; m < NV; m++) begin : g_qnum
    fxr_pipe #(.Width(3 * QB), .Stages(PlaneIn - 1)) u_pipe_qnum (
      .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-2:0]), .d_i(q_num[m]), .q_o(q_num_p[m])
    );
  end

  // Depth vertex values: on the attribute triangle RNE(z*(2^Db - 1) / 2^Db) = z - RNE(z / 2^Db)
  // (attr_depth_q; RNE is odd-symmetric), on the snapped triangle z itself and the plane is
  // multiplied by 2^Db - 1 afterwards (fxr_setup_plane's post_m_i).
  logic [3*ZQB-1:0] q_z;
  logic [ZB-1:0]    zk, zr;
  logic             zup;
  always_comb begin
    zk  = '0;
    zup = 1'b0;
    zr  = '0;
    q_z = '0;
    if (valid_q[PlaneIn-1]) begin
      for (int k = 0; k < 3; k++) begin
        zk  = z_p[k*ZB +: ZB];
        zup = zk[Db-1] & ((|zk[Db-2:0]) | zk[Db]);
        zr  = (zk >> Db) + ZB'(zup);
        q_z[k*ZQB +: ZQB] = use_attr ? ZQB'(zk) - ZQB'(zr) : ZQB'(zk);
      end
    end
  end

  // ---- planes (cycles 8-9) -------------------------------------------------------------------
  logic [ZPB-1:0] zc, zdx, zdy;
  fxr_setup_plane #(.AB(AB), .CWB(CWB), .SHB(SHB), .QB(ZQB), .PostBits(Db), .OutBits(ZPB)) u_plane_z (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-1 +: PlaneStages]), .a_i(pa), .b_i(pb), .c_i(pc), .shift_i(pshift), .q_i(q_z),
    .post_m_i(!use_attr), .c_o(zc), .dx_o(zdx), .dy_o(zdy)
  );
  logic [IPB-1:0] dc, ddx, ddy;
  fxr_setup_plane #(.AB(AB), .CWB(CWB), .SHB(SHB), .QB(QB), .PostBits(0), .OutBits(IPB)) u_plane_den (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-1 +: PlaneStages]), .a_i(pa), .b_i(pb), .c_i(pc), .shift_i(pshift), .q_i(q_den_p),
    .post_m_i(1'b0), .c_o(dc), .dx_o(ddx), .dy_o(ddy)
  );
  logic [IPB-1:0] nc [NV], ndx [NV], ndy [NV];
  for (genvar m = 0; m < NV; m++) begin : g_plane_num
    fxr_setup_plane #(.AB(AB), .CWB(CWB), .SHB(SHB), .QB(QB), .PostBits(0), .OutBits(IPB)) u_plane_num (
      .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-1 +: PlaneStages]), .a_i(pa), .b_i(pb), .c_i(pc), .shift_i(pshift), .q_i(q_num_p[m]),
      .post_m_i(1'b0), .c_o(nc[m]), .dx_o(ndx[m]), .dy_o(ndy[m])
    );
  end

  // Depth divisor: 2A' * 2^(ZFracBits - Db) on the attribute triangle, 2A * 2^ZFracBits on the
  // snapped one (cycle 7), then beside the planes.
  logic [EVB-1:0] area2_p;
  fxr_pipe #(.Width(EVB), .Stages(AttrStages)) u_pipe_area2 (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[EdgeStages-1 +: AttrStages]), .d_i(area2), .q_o(area2_p)
  );
  logic [ZDB-1:0] zden_d, zden;
  always_comb begin
    zden_d = '0;
    if (valid_q[PlaneIn-1]) zden_d = use_attr ? ZDB'(area2_attr) << (ZFracBits - Db) : ZDB'(area2_p) << ZFracBits;
  end
  logic [2*PB-1:0] anchor;
  fxr_pipe #(.Width(ZDB + 2 * PB), .Stages(PlaneStages)) u_pipe_zden (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[PlaneIn-1 +: PlaneStages]), .d_i({zden_d, pi0, pj0}), .q_o({zden, anchor})
  );

  // ---- everything else beside the stages to the output (cycle 9) ----------------------------
  localparam int EdgeOut = 3 + 3 * ECB * 2 + 3 * EVB + 3 + EVB + 1 + 4 * PB;
  logic [2:0]       outcome_o_q;
  logic [3*ECB-1:0] ea_o, eb_o;
  logic [3*EVB-1:0] ec_o;
  logic [2:0]       ebias_o;
  logic [EVB-1:0]   area2_o_q;
  logic             front_o_q;
  logic [PB-1:0]    bx0_o, bx1_o, by0_o, by1_o;
  fxr_pipe #(.Width(EdgeOut), .Stages(AttrStages + PlaneStages)) u_pipe_edges (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[EdgeStages-1 +: AttrStages + PlaneStages]),
    .d_i  ({outcome, ea, eb, ec, ebias, area2, front, bx0, bx1, by0, by1}),
    .q_o  ({outcome_o_q, ea_o, eb_o, ec_o, ebias_o, area2_o_q, front_o_q, bx0_o, bx1_o, by0_o, by1_o})
  );
  logic [PrimBits-1:0] prim_o_q;
  logic [EB-1:0]       exp_den_o, exp_num_o [NV];
  fxr_pipe #(.Width(PrimBits), .Stages(Latency)) u_pipe_prim (
    .clk_i(clk_i), .en_i(advance), .v_i(vs[Latency-1:0]), .d_i(prim_i), .q_o(prim_o_q)
  );
  fxr_pipe #(.Width((1 + NV) * EB), .Stages(Latency - 1)) u_pipe_exp (
    .clk_i(clk_i), .en_i(advance), .v_i(valid_q[Latency-2:0]),
    .d_i  ({exp_den, exp_num[0], exp_num[1]}),
    .q_o  ({exp_den_o, exp_num_o[0], exp_num_o[1]})
  );

  // ---- outputs: 0 unless the triangle is drawn ----------------------------------------------
  // Assembled only with a drawn triangle in the last stage (0 otherwise: the port rule, and what an
  // empty stage gives), so that a simulator does not select ~2,200 bits on every idle clock
  // (docs/rtl.md, "Co-simulation speed", session 11). out_valid_o qualifies them as before.
  logic ok, drawn;
  assign ok         = outcome_o_q == 3'd0;  // fxr_setup_edges::OutcomeOk
  assign drawn      = valid_q[Last] & ok;
  assign outcome_o  = outcome_o_q;
  always_comb begin
    out_prim_o = '0;
    e0_a_o     = '0;
    e0_b_o     = '0;
    e0_c_o     = '0;
    e0_bias_o  = '0;
    e1_a_o     = '0;
    e1_b_o     = '0;
    e1_c_o     = '0;
    e1_bias_o  = '0;
    e2_a_o     = '0;
    e2_b_o     = '0;
    e2_c_o     = '0;
    e2_bias_o  = '0;
    area2_o    = '0;
    front_o    = '0;
    x0_o       = '0;
    x1_o       = '0;
    y0_o       = '0;
    y1_o       = '0;
    z_c_o      = '0;
    z_dx_o     = '0;
    z_dy_o     = '0;
    z_i0_o     = '0;
    z_j0_o     = '0;
    z_den_o    = '0;
    den_c_o    = '0;
    den_dx_o   = '0;
    den_dy_o   = '0;
    den_i0_o   = '0;
    den_j0_o   = '0;
    den_exp_o  = '0;
    num0_c_o   = '0;
    num0_dx_o  = '0;
    num0_dy_o  = '0;
    num0_i0_o  = '0;
    num0_j0_o  = '0;
    num0_exp_o = '0;
    num1_c_o   = '0;
    num1_dx_o  = '0;
    num1_dy_o  = '0;
    num1_i0_o  = '0;
    num1_j0_o  = '0;
    num1_exp_o = '0;
    if (drawn) begin
      out_prim_o = prim_o_q;
      e0_a_o     = ea_o[0*ECB +: ECB];
      e0_b_o     = eb_o[0*ECB +: ECB];
      e0_c_o     = ec_o[0*EVB +: EVB];
      e0_bias_o  = ebias_o[0];
      e1_a_o     = ea_o[1*ECB +: ECB];
      e1_b_o     = eb_o[1*ECB +: ECB];
      e1_c_o     = ec_o[1*EVB +: EVB];
      e1_bias_o  = ebias_o[1];
      e2_a_o     = ea_o[2*ECB +: ECB];
      e2_b_o     = eb_o[2*ECB +: ECB];
      e2_c_o     = ec_o[2*EVB +: EVB];
      e2_bias_o  = ebias_o[2];
      area2_o    = area2_o_q;
      front_o    = front_o_q;
      x0_o       = bx0_o;
      x1_o       = bx1_o;
      y0_o       = by0_o;
      y1_o       = by1_o;
      z_c_o      = zc;
      z_dx_o     = zdx;
      z_dy_o     = zdy;
      z_i0_o     = anchor[PB +: PB];
      z_j0_o     = anchor[0 +: PB];
      z_den_o    = zden;
      den_c_o    = dc;
      den_dx_o   = ddx;
      den_dy_o   = ddy;
      den_i0_o   = anchor[PB +: PB];
      den_j0_o   = anchor[0 +: PB];
      den_exp_o  = exp_den_o;
      num0_c_o   = nc[0];
      num0_dx_o  = ndx[0];
      num0_dy_o  = ndy[0];
      num0_i0_o  = anchor[PB +: PB];
      num0_j0_o  = anchor[0 +: PB];
      num0_exp_o = exp_num_o[0];
      num1_c_o   = nc[1];
      num1_dx_o  = ndx[1];
      num1_dy_o  = ndy[1];
      num1_i0_o  = anchor[PB +: PB];
      num1_j0_o  = anchor[0 +: PB];
      num1_exp_o = exp_num_o[1];
    end
  end
endmodule
