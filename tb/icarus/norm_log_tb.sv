// Exhaustive bench of rtl/fxr_norm_log.sv under Icarus 11 (ctest NormLog.IcarusExhaustive, label
// rtl): every x of several widths (powers of two and not, a wide msb port) against a reference
// written from the definition — the leading one by a plain loop over the bits, the operand shifted
// by Width - 1 - m — with en_i high, and the outputs 0 with en_i low. Prints PASSED or the first
// MISMATCH lines and FAILED.
module norm_log_check #(
  parameter int Width   = 5,
  parameter int MsbBits = $clog2(Width)
) (
  output int errors_o,
  output int checked_o
);
  logic               en;
  logic [Width-1:0]   x, norm;
  logic [MsbBits-1:0] msb;
  fxr_norm_log #(.Width(Width), .MsbBits(MsbBits)) dut (.en_i(en), .x_i(x), .norm_o(norm), .msb_o(msb));

  initial begin
    int m;
    logic [Width-1:0] want;
    errors_o = 0;
    checked_o = 0;
    for (longint v = 0; v < (longint'(1) << Width); v++) begin
      for (int e = 1; e >= 0; e--) begin
        en = e[0];
        x = Width'(v);
        #1;
        m = 0;
        for (int b = 0; b < Width; b++)
          if (x[b]) m = b;
        want = (en && x != '0) ? x << (Width - 1 - m) : '0;
        if (!en) m = 0;
        checked_o++;
        if (norm !== want || int'(msb) !== m) begin
          errors_o++;
          if (errors_o <= 5)
            $display("MISMATCH Width=%0d en=%0d x=%0h: norm %0h msb %0d, want %0h msb %0d", Width, en, x, norm, msb,
                     want, m);
        end
      end
    end
  end
endmodule

module norm_log_tb;
  int e[6], c[6];
  norm_log_check #(.Width(2))                u2  (.errors_o(e[0]), .checked_o(c[0]));
  norm_log_check #(.Width(5))                u5  (.errors_o(e[1]), .checked_o(c[1]));
  norm_log_check #(.Width(8))                u8  (.errors_o(e[2]), .checked_o(c[2]));
  norm_log_check #(.Width(12))               u12 (.errors_o(e[3]), .checked_o(c[3]));
  norm_log_check #(.Width(13), .MsbBits(8))  u13 (.errors_o(e[4]), .checked_o(c[4]));
  norm_log_check #(.Width(16))               u16 (.errors_o(e[5]), .checked_o(c[5]));
  initial begin
    int errs, n;
    #(2 * (1 << 16) + 10);
    errs = 0;
    n = 0;
    for (int i = 0; i < 6; i++) begin
      errs += e[i];
      n += c[i];
    end
    $display("norm_log: checked=%0d errors=%0d", n, errs);
    if (errs == 0 && n == 2 * ((1 << 2) + (1 << 5) + (1 << 8) + (1 << 12) + (1 << 13) + (1 << 16))) $display("PASSED");
    else $display("FAILED");
    $finish;
  end
endmodule
