// clip_txn_tb: plain SystemVerilog testbench of the clipper (rtl/fxr_clip_core.sv, the flat-port
// core of fxr_clip: Icarus 11 aborts on fxr_rec_pkg's packed-struct ports) driven by a transaction
// dump's clip.in.hex and checked against its clip.out.hex with $readmemh (docs/vectors.md,
// "Transaction vectors"; docs/rtl.md, "fxr_clip"; the Verilator test is tb/txn/clip_txn_test.cpp).
// A hex line is the record's fields each padded to whole hex digits after the header (in: txn,
// n_out; out: txn, seq, last); the bench repacks them into the flat record (first field most
// significant), so the layout comes from fxr_rec_pkg's constants, none is written here.
//
// Rows of clip.in are offered in order with random input gaps; outputs see random back-pressure
// and must equal the rows of clip.out in order (record and last), never before the input they
// belong to was accepted, none missing, none extra. +corrupt=N flips the lowest significand bit
// of v1_x in expected row N (from 1): the bench must then report exactly that MISMATCH and FAILED.
//
// Run by hand (absolute paths: $readmemh resolves relative ones against the working directory):
//   iverilog -g2012 -s clip_txn_tb -o clip.vvp build/gen/fxr_config_pkg.sv build/gen/fxr_rec_pkg.sv \
//     rtl/fxr_clip_core.sv tb/icarus/clip_txn_tb.sv
//   vvp -n clip.vvp +in=$PWD/vectors/scenes/transactions/clip.in.hex \
//     +out=$PWD/vectors/scenes/transactions/clip.out.hex +nin=6 +nout=6 +vx=0 +vy=0 +vw=24 +vh=16
`timescale 1ns / 1ps
module clip_txn_tb;
  parameter int MaxIn         = 1 << 12;
  parameter int MaxOut        = 1 << 13;
  parameter int GapPct        = 25;
  parameter int StallPct      = 25;
  parameter int TimeoutCycles = 100000;

  localparam int PB = fxr_config_pkg::RasterWindowIntBits;
  localparam int NV = fxr_rec_pkg::NumVaryings;
  localparam int SB = fxr_rec_pkg::ClipVertexSigBits;
  localparam int EB = fxr_rec_pkg::FxExpBits;
  localparam int VB = 1 + SB + EB;
  localparam int IdBits = 32;  // txn, n_out, seq (model/vectors/scene_dump.hpp)
  localparam int PrimBits = fxr_rec_pkg::PrimIdBits;
  localparam int NIn = 3 * (4 + NV);
  localparam int NOut = 3 * (4 + fxr_rec_pkg::ClipVertexHasWa + NV);
  // a field padded to whole hex digits
  function automatic int pad(input int w);
    pad = ((w + 3) / 4) * 4;
  endfunction
  localparam int PadVal = pad(1) + pad(SB) + pad(EB);
  localparam int InWordBits = 2 * IdBits + PrimBits + NIn * PadVal;
  localparam int OutWordBits = 2 * IdBits + pad(1) + PrimBits + NOut * PadVal;
  localparam int InBits = fxr_rec_pkg::ExactTriangleBits;
  localparam int OutBits = fxr_rec_pkg::ClippedTriangleBits;

  logic [InWordBits-1:0] in_mem [MaxIn];
  logic [OutWordBits-1:0] out_mem [MaxOut];
  logic clk = 1'b0, rst_n = 1'b0, in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0, out_last;
  logic done;
  logic [fxr_rec_pkg::ClipOutcomeBits-1:0] done_outcome;
  logic [$clog2(fxr_rec_pkg::ClipMaxPolyVerts * fxr_rec_pkg::ClipNumPlanes + 1)-1:0] done_created;
  logic [InBits-1:0] in_rec;
  logic [OutBits-1:0] out_rec;
  logic [PB-1:0] vx, vy;
  logic [PB:0] vw, vh;

  fxr_clip_core dut (
    .clk_i(clk), .rst_ni(rst_n), .viewport_x_i(vx), .viewport_y_i(vy), .viewport_w_i(vw), .viewport_h_i(vh),
    .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_rec),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_rec), .out_last_o(out_last),
    .done_o(done), .done_outcome_o(done_outcome), .done_created_o(done_created));

  always #5 clk = ~clk;

  // The record of a hex line: prim, then n values (neg, sig, exp), from bit `top` down.
  function automatic logic [OutBits-1:0] repack(input logic [OutWordBits-1:0] w, input int top, input int n);
    logic [OutBits-1:0] r;
    int at, o;
    r = '0;
    o = PrimBits + n * VB;
    r[o - 1 -: PrimBits] = w[top - 1 -: PrimBits];
    at = top - PrimBits;
    o = o - PrimBits;
    for (int k = 0; k < n; k++) begin
      r[o - 1] = w[at - pad(1)];
      r[o - 2 -: SB] = w[at - pad(1) - 1 -: SB];
      r[o - 1 - SB - 1 -: EB] = w[at - pad(1) - pad(SB) - 1 -: EB];
      at = at - PadVal;
      o = o - VB;
    end
    repack = r;
  endfunction

  string fin, fout;
  int nin, nout, seed, corrupt, ivx, ivy, ivw, ivh;
  int n_in, n_out, errors, idle, cycles;
  logic [OutBits-1:0] want;
  logic [IdBits-1:0] want_txn;
  logic want_last;

  initial begin
    if (!$value$plusargs("in=%s", fin) || !$value$plusargs("out=%s", fout) || !$value$plusargs("nin=%d", nin) ||
        !$value$plusargs("nout=%d", nout) || !$value$plusargs("vx=%d", ivx) || !$value$plusargs("vy=%d", ivy) ||
        !$value$plusargs("vw=%d", ivw) || !$value$plusargs("vh=%d", ivh)) begin
      $display("FAILED: plusargs +in= +out= +nin= +nout= +vx= +vy= +vw= +vh= required");
      $finish;
    end
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("corrupt=%d", corrupt)) corrupt = 0;
    $readmemh(fin, in_mem, 0, nin - 1);
    if (nout > 0) $readmemh(fout, out_mem, 0, nout - 1);
    if (corrupt > 0) begin  // v1_x_sig's lowest bit: the first value of vertex 1
      logic [OutWordBits-1:0] row;
      row = out_mem[corrupt - 1];
      row[OutWordBits - 2 * IdBits - pad(1) - PrimBits - (4 + fxr_rec_pkg::ClipVertexHasWa + NV) * PadVal - pad(1) - SB] =
          ~row[OutWordBits - 2 * IdBits - pad(1) - PrimBits - (4 + fxr_rec_pkg::ClipVertexHasWa + NV) * PadVal - pad(1) - SB];
      out_mem[corrupt - 1] = row;
    end
    vx = PB'(ivx);
    vy = PB'(ivy);
    vw = (PB + 1)'(ivw);
    vh = (PB + 1)'(ivh);
    n_in = 0;
    n_out = 0;
    errors = 0;
    idle = 0;
    cycles = 0;
    repeat (4) @(posedge clk);
    rst_n = 1'b1;
    while (n_out < nout || n_in < nin) begin
      @(negedge clk);
      if (!in_valid && n_in < nin && ($urandom(seed) % 100) >= GapPct) begin
        in_valid = 1'b1;
        in_rec = InBits'(repack(OutWordBits'(in_mem[n_in]), InWordBits - 2 * IdBits, NIn));
      end
      out_ready = ($urandom(seed) % 100) >= StallPct;
      @(posedge clk);
      cycles++;
      if (out_valid && out_ready) begin
        if (n_out >= nout) begin
          $display("MISMATCH clip row=%0d: output beyond the %0d rows", n_out + 1, nout);
          errors++;
        end else begin
          want = repack(out_mem[n_out], OutWordBits - 2 * IdBits - pad(1), NOut);
          want_txn = out_mem[n_out][OutWordBits - 1 -: IdBits];
          want_last = out_mem[n_out][OutWordBits - 2 * IdBits - pad(1)];
          if (out_rec !== want || out_last !== want_last || want_txn >= IdBits'(n_in)) begin
            $display("MISMATCH clip row=%0d txn=%0d: got %h last %b, exp %h last %b", n_out + 1, want_txn, out_rec,
                     out_last, want, want_last);
            errors++;
          end
        end
        n_out++;
        idle = 0;
      end
      if (in_valid && in_ready) begin
        n_in++;
        in_valid = 1'b0;
      end
      idle++;
      if (idle > TimeoutCycles) begin
        $display("MISMATCH clip row=%0d: no output within %0d cycles", n_out + 1, TimeoutCycles);
        errors++;
        n_in = nin;  // end the run
        nout = n_out;
      end
    end
    $display("clip: inputs=%0d outputs=%0d (file %0d) errors=%0d cycles=%0d", n_in, n_out, nout, errors, cycles);
    if (errors == 0) $display("PASSED");
    else $display("FAILED");
    $finish;
  end
endmodule
