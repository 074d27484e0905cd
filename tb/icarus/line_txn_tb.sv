// line_txn_tb: plain Verilog testbench of fxr_line (the line walk) driven by a transaction dump's
// line.in.hex and checked against its line.out.hex (docs/vectors.md, "Transaction vectors";
// docs/lines.md, "RTL"), for Icarus 11. Icarus 11 aborts on the packed-struct ports of
// fxr_rec_pkg ("elab_type.cc:86: failed assertion scope"), so this bench drives fxr_line's plain
// ports and does what fxr_line_rec adds around it (its Verilator test: tb/txn/line_txn_test.cpp)
// itself: it keeps the segment's prim and draw rectangle and drops the pixels outside the
// rectangle before comparing, and lets a new segment in only once the previous one's last pixel
// has left (or leaves in that clock). The ctest driver
// tb/icarus/run_line_txn.cmake reads the two manifests and passes the word widths (parameters),
// the row counts and the bit offsets of the fields used here (plusargs), so no layout is written
// here: a field is word[offset +: width], the manifests' rule.
//
// Rows of line.in are offered in order with random input gaps; outputs see random back-pressure
// and must equal the rows of line.out in order (prim, x, y), never before the input they belong
// to (their txn) was accepted, none missing, none extra. +corrupt=N flips the lowest bit of x in
// expected row N (from 1): the bench must then report exactly that MISMATCH and FAILED.
//
// Plusargs: +in=<abs path> +out=<abs path> +nin=<rows> +nout=<rows> [+seed=N] [+corrupt=N]
//   +in_prim= +in_x0= +in_y0= +in_x1= +in_y1= +in_rx0= +in_rx1= +in_ry0= +in_ry1= (offsets in line.in)
//   +out_txn= +out_prim= +out_x= +out_y= (offsets in line.out)
`timescale 1ns / 1ps
module line_txn_tb;
  parameter int InWordBits    = 1;
  parameter int OutWordBits   = 1;
  parameter int MaxIn         = 1 << 14;
  parameter int MaxOut        = 1 << 15;
  parameter int GapPct        = 25;
  parameter int StallPct      = 25;
  parameter int TimeoutCycles = 20000;

  localparam int PrimBits  = 32;  // prim ids (model/unit/record.hpp kPrimIdBits)
  localparam int CoordBits = fxr_config_pkg::RasterWindowIntBits + fxr_config_pkg::RasterSubpixelBits;
  localparam int PixBits   = fxr_config_pkg::RasterWindowIntBits;
  localparam int IdBits    = 32;  // transaction ids (model/vectors/scene_dump.hpp kTxnIdBits)

  logic [InWordBits-1:0] in_mem [MaxIn];
  logic [OutWordBits-1:0] out_mem [MaxOut];
  logic clk = 1'b0, rst_n = 1'b0, in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0;
  logic signed [CoordBits-1:0] x0, y0, x1, y1;
  logic signed [PixBits-1:0] out_x, out_y, rx0, rx1, ry0, ry1;
  logic [PrimBits-1:0] prim;

  // A segment goes in only while no pixel waits, or the waiting one leaves in this clock (its
  // segment's prim and rectangle are still the latched ones), as fxr_line_rec does.
  wire in_rect;
  wire dut_in_valid = in_valid && (!out_valid || out_ready || !in_rect);
  wire accepted = dut_in_valid && in_ready;
  fxr_line dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(dut_in_valid), .in_ready_o(in_ready),
    .in_x0_i(x0), .in_y0_i(y0), .in_x1_i(x1), .in_y1_i(y1),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_x_o(out_x), .out_y_o(out_y)
  );
  assign in_rect = out_x >= rx0 && out_x <= rx1 && out_y >= ry0 && out_y <= ry1;

  always #5 clk = ~clk;

  string fin, fout;
  int nin, nout, seed, corrupt, scratch;
  int o_prim, o_x0, o_y0, o_x1, o_y1, o_rx0, o_rx1, o_ry0, o_ry1, e_txn, e_prim, e_x, e_y;
  int n_in, n_out, errors, idle, offered, dropped;
  logic [PrimBits-1:0] want_prim;
  logic [PixBits-1:0] want_x, want_y;
  logic [IdBits-1:0] want_txn;

  function automatic int need(input string name);
    int v;
    if (!$value$plusargs({name, "=%d"}, v)) $fatal(1, "line_txn_tb: +%s missing", name);
    return v;
  endfunction

  initial begin
    if (!$value$plusargs("in=%s", fin)) $fatal(1, "line_txn_tb: +in=<absolute path of line.in.hex> missing");
    if (!$value$plusargs("out=%s", fout)) $fatal(1, "line_txn_tb: +out=<absolute path of line.out.hex> missing");
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("corrupt=%d", corrupt)) corrupt = 0;
    nin = need("nin"); nout = need("nout");
    o_prim = need("in_prim"); o_x0 = need("in_x0"); o_y0 = need("in_y0"); o_x1 = need("in_x1"); o_y1 = need("in_y1");
    o_rx0 = need("in_rx0"); o_rx1 = need("in_rx1"); o_ry0 = need("in_ry0"); o_ry1 = need("in_ry1");
    e_txn = need("out_txn"); e_prim = need("out_prim"); e_x = need("out_x"); e_y = need("out_y");
    if (nin > MaxIn || nout > MaxOut) $fatal(1, "line_txn_tb: %0d / %0d rows, the bench holds %0d / %0d", nin, nout, MaxIn, MaxOut);
    if (nin > 0) $readmemh(fin, in_mem, 0, nin - 1);
    if (nout > 0) $readmemh(fout, out_mem, 0, nout - 1);
    // (^word is x when a bit is x or z: Icarus 11's $isunknown misreads these wide words)
    if ((nin > 0 && (^in_mem[nin - 1]) === 1'bx) || (nout > 0 && (^out_mem[nout - 1]) === 1'bx)) begin
      $display("line_txn_tb: fewer rows than the manifests say (truncated file?)");
      $display("FAILED");
      $finish;
    end
    if (corrupt > 0) out_mem[corrupt - 1][e_x] = ~out_mem[corrupt - 1][e_x];
    $display("line_txn_tb: %0d segments from %s, %0d pixels from %s", nin, fin, nout, fout);
    scratch = $urandom(seed);
    n_in = 0; n_out = 0; errors = 0; idle = 0; offered = -1; dropped = 0;
    x0 = '0; y0 = '0; x1 = '0; y1 = '0;
    repeat (4) @(posedge clk);
    @(negedge clk) rst_n = 1'b1;
    wait ((n_out == nout && n_in == nin) || idle > TimeoutCycles);
    repeat (200) @(posedge clk);  // an output beyond the last row is an error
    if (n_out < nout || n_in < nin) begin
      $display("line_txn_tb: TIMEOUT, %0d inputs not accepted, %0d outputs missing", nin - n_in, nout - n_out);
      errors += nout - n_out + (n_in < nin ? 1 : 0);
    end
    $display("line: segments=%0d checked=%0d (dropped outside the rectangle: %0d) errors=%0d", n_in, n_out, dropped,
             errors);
    if (errors == 0 && n_out == nout) $display("PASSED");
    else $display("FAILED");
    $finish;
  end

  always @(posedge clk) if (rst_n) begin
    idle++;
    if (out_valid && out_ready && !in_rect) dropped++;
    if (out_valid && out_ready && in_rect) begin
      if (n_out >= nout) begin
        errors++;
        $display("MISMATCH line row=%0d got prim=%0d x=%0d y=%0d (extra output)", n_out + 1, prim, out_x, out_y);
      end else begin
        want_txn = out_mem[n_out][e_txn +: IdBits];
        want_prim = out_mem[n_out][e_prim +: PrimBits];
        want_x = out_mem[n_out][e_x +: PixBits];
        want_y = out_mem[n_out][e_y +: PixBits];
        if (want_txn >= n_in) begin  // n_in: inputs accepted before this edge
          errors++;
          $display("MISMATCH line row=%0d early: txn %0d not accepted yet", n_out + 1, want_txn);
        end
        if (prim !== want_prim || out_x !== want_x || out_y !== want_y) begin
          errors++;
          if (errors <= 20)
            $display("MISMATCH line row=%0d txn=%0d got prim=%0d x=%0d y=%0d exp prim=%0d x=%0d y=%0d", n_out + 1,
                     want_txn, prim, out_x, out_y, want_prim, $signed(want_x), $signed(want_y));
        end
      end
      n_out++;
      idle = 0;
    end
    if (accepted) begin  // the segment's prim and rectangle, for its pixels
      prim <= in_mem[n_in][o_prim +: PrimBits];
      rx0 <= in_mem[n_in][o_rx0 +: PixBits];
      rx1 <= in_mem[n_in][o_rx1 +: PixBits];
      ry0 <= in_mem[n_in][o_ry0 +: PixBits];
      ry1 <= in_mem[n_in][o_ry1 +: PixBits];
      n_in++;
    end
  end

  // Next inputs at the falling edge: valid stays up until accepted; random gaps and stalls.
  always @(negedge clk) if (rst_n) begin
    if (in_valid && n_in > offered) in_valid = 1'b0;  // accepted at the last rising edge
    if (!in_valid && n_in < nin && ($urandom % 100) >= GapPct) begin
      offered = n_in;
      x0 = in_mem[n_in][o_x0 +: CoordBits];
      y0 = in_mem[n_in][o_y0 +: CoordBits];
      x1 = in_mem[n_in][o_x1 +: CoordBits];
      y1 = in_mem[n_in][o_y1 +: CoordBits];
      in_valid = 1'b1;
    end
    out_ready = ($urandom % 100) >= StallPct;
  end
endmodule
