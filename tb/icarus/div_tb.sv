// div_tb: plain Verilog testbench of fxr_div driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus: iverilog -g2012).
//
//   iverilog -g2012 -s div_tb -y rtl -Y .sv build/gen/fxr_config_pkg.sv rtl/fxr_div.sv tb/icarus/div_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/div/div.hex +count=<manifest count> [+seed=N]
//
// $readmemh resolves a relative path against the simulator's working directory: pass an
// absolute one. Each line is one word: the fields concatenated msb first, each padded to whole
// hex digits; field f = word[offset_f +: width_f] with the offsets of the manifest, recomputed
// here from the package widths by the same rule (the last field at bit 0).
`timescale 1ns / 1ps
module div_tb;
  import fxr_config_pkg::*;

  // ---- layout (vectors/div/div.json): in_num, in_den, out_sig, out_exp_adj, out_dbz
  function automatic int pad(input int w);  // bits a field occupies: whole hex digits
    return 4 * ((w + 3) / 4);
  endfunction
  localparam int ExpAdjBits  = 2;
  localparam int OffDbz      = 0;
  localparam int OffExpAdj   = OffDbz + pad(1);
  localparam int OffSig      = OffExpAdj + pad(ExpAdjBits);
  localparam int OffDen      = OffSig + pad(DivQuotBits);
  localparam int OffNum      = OffDen + pad(DivDenBits);
  localparam int WordBits    = OffNum + pad(DivNumBits);
  parameter int MaxVecs      = 1 << 16;
  parameter int GapPct       = 25;  // chance (%) that a new input waits one more cycle
  parameter int StallPct     = 25;  // chance (%) that out_ready is low
  parameter int TimeoutCycles = 2000;

  logic [WordBits-1:0] mem [MaxVecs];

  logic clk = 1'b0, rst_n = 1'b0;
  logic in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0;
  logic [WordBits-1:0] cur = '0;
  logic [DivQuotBits-1:0] out_sig;
  logic [ExpAdjBits-1:0] out_exp_adj;
  logic out_dbz;

  fxr_div dut (
    .clk_i        (clk),
    .rst_ni       (rst_n),
    .in_valid_i   (in_valid),
    .in_ready_o   (in_ready),
    .in_num_i     (cur[OffNum +: DivNumBits]),
    .in_den_i     (cur[OffDen +: DivDenBits]),
    .out_valid_o  (out_valid),
    .out_ready_i  (out_ready),
    .out_sig_o    (out_sig),
    .out_exp_adj_o(out_exp_adj),
    .out_dbz_o    (out_dbz)
  );

  always #5 clk = ~clk;

  // The output digits of a line (bits [OffNum-… : 0] hold the outputs, padding included) and
  // the DUT's outputs packed the same way, so got / exp print like the vector file.
  localparam int OutWordBits = OffDen;
  localparam int InWordBits  = WordBits - OffDen;
  logic [OutWordBits-1:0] got;
  always_comb begin
    got = '0;
    got[OffSig +: DivQuotBits]   = out_sig;
    got[OffExpAdj +: ExpAdjBits] = out_exp_adj;
    got[OffDbz]                  = out_dbz;
  end

  string file;
  int count, loaded, seed, n_in, n_out, errors, idle, offered, r;

  initial begin
    if (!$value$plusargs("vectors=%s", file)) $fatal(1, "div_tb: pass +vectors=<absolute path of div.hex>");
    if (!$value$plusargs("count=%d", count)) count = 0;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (count > MaxVecs) $fatal(1, "div_tb: %0d vectors, MaxVecs is %0d", count, MaxVecs);
    if (count > 0) $readmemh(file, mem, 0, count - 1);
    else $readmemh(file, mem);
    loaded = 0;
    while (loaded < MaxVecs && !$isunknown(mem[loaded])) loaded++;
    $display("div_tb: %0d vectors of %0d bits from %s", loaded, WordBits, file);
    if (count > 0 && loaded != count) begin
      $display("div_tb: %0d words loaded, the manifest says %0d (truncated file?)", loaded, count);
      $display("FAILED");
      $finish;
    end
    r = $urandom(seed);
    n_in = 0; n_out = 0; errors = 0; idle = 0; offered = -1;
    repeat (4) @(posedge clk);
    @(negedge clk) rst_n = 1'b1;
    wait (n_out == loaded || idle > TimeoutCycles);
    repeat (50) @(posedge clk);  // outputs beyond the last vector are counted as errors
    if (idle > TimeoutCycles) begin
      $display("div_tb: TIMEOUT, %0d outputs missing", loaded - n_out);
      errors += loaded - n_out;
    end
    $display("div: checked=%0d errors=%0d", n_out, errors);
    if (errors == 0 && n_out == loaded) $display("PASSED");
    else $display("FAILED");
    $finish;
  end

  // Transfers happen at the rising edge; the values were settled at the falling edge.
  always @(posedge clk) if (rst_n) begin
    idle++;
    if (in_valid && in_ready) n_in++;
    if (out_valid && out_ready) begin
      if (n_out >= loaded) begin
        errors++;
        $display("MISMATCH div vec=%0d got=%h (extra output)", n_out, got);
      end else if (got !== mem[n_out][OutWordBits-1:0]) begin
        errors++;
        if (errors <= 20)
          $display("MISMATCH div vec=%0d in=%h got=%h exp=%h", n_out, mem[n_out][WordBits-1:OffDen], got,
                   mem[n_out][OutWordBits-1:0]);
      end
      n_out++;
      idle = 0;
    end
  end

  // Next inputs at the falling edge: valid stays up until accepted; random gaps and stalls.
  always @(negedge clk) if (rst_n) begin
    if (in_valid && n_in > offered) in_valid = 1'b0;  // accepted at the last rising edge
    if (!in_valid && n_in < loaded && ($urandom % 100) >= GapPct) begin
      offered = n_in;
      cur = mem[n_in];
      in_valid = 1'b1;
    end
    out_ready = ($urandom % 100) >= StallPct;
  end
endmodule
