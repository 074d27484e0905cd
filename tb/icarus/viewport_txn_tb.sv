// viewport_txn_tb: plain Verilog testbench of fxr_viewport_core (stage 4 on flat record vectors)
// driven by a transaction dump's viewport.in.hex and checked against its viewport.out.hex
// (docs/vectors.md, "Transaction vectors"; docs/rtl.md, "fxr_viewport"), for Icarus 11, which aborts
// on fxr_rec_pkg's struct ports (fxr_viewport is fxr_viewport_core behind them; its Verilator test:
// tb/txn/viewport_txn_test.cpp). The ctest driver tb/icarus/run_viewport_txn.cmake reads the two
// manifests and writes `viewport_fields.svh` (functions in_off / in_w / out_off / out_w: the
// offset and width of every field, a field being word[offset +: width], the manifests' rule) and
// passes the draw state of scene.json as plusargs, so no layout is written here. The record is the
// fields after the header (txn, n_out / txn, seq, last), first field most significant.
//
// Rows are offered in order with random input gaps; outputs see random back-pressure and must equal
// the rows of viewport.out in order (the whole record), never before their input (txn) was
// accepted, none missing, none extra; rej_range_o must pulse once per input with n_out = 0.
// +corrupt=N flips the lowest bit of expected row N (from 1): the bench must then report exactly
// that MISMATCH and FAILED.
//
// Plusargs: +in=<abs path> +out=<abs path> +nin=<rows> +nout=<rows> [+seed=N] [+corrupt=N]
//           +vx= +vy= +vw= +vh= +interp= (the draw state)
`timescale 1ns / 1ps
module viewport_txn_tb;
  parameter int InWordBits    = 1;
  parameter int OutWordBits   = 1;
  parameter int MaxIn         = 1 << 12;
  parameter int MaxOut        = 1 << 12;
  parameter int GapPct        = 25;
  parameter int StallPct      = 25;
  parameter int TimeoutCycles = 20000;

  localparam int InBits = fxr_rec_pkg::RecipTriangleBits;
  localparam int OutBits = fxr_rec_pkg::SetupTriangleBits;
  localparam int Wib = fxr_config_pkg::RasterWindowIntBits;
  localparam int IdBits = 32;  // transaction ids (model/vectors/scene_dump.hpp kTxnIdBits)

`include "viewport_fields.svh"

  logic [InWordBits-1:0] in_mem [MaxIn];
  logic [OutWordBits-1:0] out_mem [MaxOut];
  logic clk = 1'b0, rst_n = 1'b0, in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0, rej;
  logic [InBits-1:0] in_rec;
  logic [OutBits-1:0] out_rec, want;
  logic signed [Wib-1:0] vx, vy;
  logic signed [Wib:0] vw, vh;
  logic interp;

  fxr_viewport_core dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_rec),
    .viewport_x_i(vx), .viewport_y_i(vy), .viewport_w_i(vw), .viewport_h_i(vh), .interp_i(interp),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_rec), .rej_range_o(rej)
  );

  always #5 clk = ~clk;

  // The record of row `r` of viewport.in / viewport.out: fields first..last, first most significant.
  function automatic logic [InBits-1:0] in_record(input int r);
    logic [InBits-1:0] v;
    v = '0;
    for (int f = InHeader; f < InFields; f++)
      for (int b = in_w(f) - 1; b >= 0; b--) v = {v[InBits-2:0], in_mem[r][in_off(f) + b]};
    return v;
  endfunction
  function automatic logic [OutBits-1:0] out_record(input int r);
    logic [OutBits-1:0] v;
    v = '0;
    for (int f = OutHeader; f < OutFields; f++)
      for (int b = out_w(f) - 1; b >= 0; b--) v = {v[OutBits-2:0], out_mem[r][out_off(f) + b]};
    return v;
  endfunction
  function automatic logic [IdBits-1:0] field(input logic [InWordBits-1:0] w, input int off);
    logic [IdBits-1:0] v;
    for (int b = 0; b < IdBits; b++) v[b] = w[off + b];
    return v;
  endfunction
  function automatic logic [IdBits-1:0] out_txn(input int r);
    logic [IdBits-1:0] v;
    for (int b = 0; b < IdBits; b++) v[b] = out_mem[r][out_off(0) + b];
    return v;
  endfunction

  function automatic int need(input string name);
    int v;
    if (!$value$plusargs({name, "=%d"}, v)) $fatal(1, "viewport_txn_tb: +%s missing", name);
    return v;
  endfunction

  string fin, fout;
  int nin, nout, seed, corrupt, scratch, n_in, n_out, errors, idle, want_drops, rejected;
  logic in_fire, lost;

  initial begin
    if (!$value$plusargs("in=%s", fin)) $fatal(1, "viewport_txn_tb: +in=<absolute path of viewport.in.hex> missing");
    if (!$value$plusargs("out=%s", fout)) $fatal(1, "viewport_txn_tb: +out=<absolute path of viewport.out.hex> missing");
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("corrupt=%d", corrupt)) corrupt = 0;
    nin = need("nin");
    nout = need("nout");
    vx = Wib'(need("vx"));
    vy = Wib'(need("vy"));
    vw = (Wib + 1)'(need("vw"));
    vh = (Wib + 1)'(need("vh"));
    interp = need("interp") != 0;
    if (nin > MaxIn || nout > MaxOut) $fatal(1, "viewport_txn_tb: %0d / %0d rows, the bench holds %0d / %0d", nin, nout, MaxIn, MaxOut);
    $readmemh(fin, in_mem, 0, nin - 1);
    $readmemh(fout, out_mem, 0, nout - 1);
    want_drops = 0;
    for (int r = 0; r < nin; r++) if (field(in_mem[r], in_off(1)) == 0) want_drops++;
    scratch = $urandom(seed);
    n_in = 0; n_out = 0; errors = 0; idle = 0; rejected = 0;
    repeat (4) @(posedge clk);
    rst_n = 1'b1;
    // Everything the bench drives changes at the falling edge; the handshakes are sampled 1 ns
    // later, before the rising edge that performs them.
    in_fire = 1'b0;
    lost = 1'b0;
    while (!lost && (n_out < nout || n_in < nin || in_fire)) begin
      @(negedge clk);
      if (in_fire) begin
        in_valid = 1'b0;
        n_in++;
      end
      if (!in_valid && n_in < nin && ($urandom % 100) >= GapPct) begin
        in_valid = 1'b1;
        in_rec = in_record(n_in);
      end
      out_ready = ($urandom % 100) >= StallPct;
      #1;
      in_fire = in_valid && in_ready;
      if (rej) rejected++;
      if (out_valid && out_ready) begin
        idle = 0;
        if (n_out >= nout) begin
          errors++;
          $display("MISMATCH viewport row=%0d extra output", n_out + 1);
        end else begin
          want = out_record(n_out);
          if (corrupt == n_out + 1) want[0] = ~want[0];
          if (out_txn(n_out) >= n_in) begin
            errors++;
            $display("MISMATCH viewport row=%0d early: before its input (txn %0d) was accepted", n_out + 1, out_txn(n_out));
          end else if (out_rec !== want) begin
            errors++;
            $display("MISMATCH viewport row=%0d got=%h exp=%h", n_out + 1, out_rec, want);
          end
        end
        n_out++;
      end else begin
        idle++;
      end
      if (idle > TimeoutCycles) begin
        errors++;
        $display("MISMATCH viewport row=%0d lost: no output within %0d cycles", n_out + 1, TimeoutCycles);
        lost = 1'b1;  // (Icarus 11 has no break)
      end
    end
    out_ready = 1'b1;
    repeat (100) begin
      @(negedge clk);
      #1;
      if (rej) rejected++;
      if (out_valid && out_ready) begin
        errors++;
        $display("MISMATCH viewport row=%0d extra output", n_out + 1);
      end
    end
    if (rejected != want_drops) begin
      errors++;
      $display("MISMATCH viewport rej_range_o pulsed %0d times, %0d inputs without output", rejected, want_drops);
    end
    $display("viewport: inputs=%0d outputs=%0d (file %0d) dropped=%0d errors=%0d", n_in, n_out, nout, rejected, errors);
    if (errors == 0) $display("PASSED");
    else $display("FAILED");
    $finish;
  end
endmodule
