// fxr_div_align: exact operand alignment shared by both divider algorithms (combinational).
// Mirrors align() in model/arith/div.cpp: a = num << (AlignBits - NumBits),
// b = den << (AlignBits - DenBits), AlignBits = max(NumBits, DenBits). No bits are lost.
module fxr_div_align #(
  parameter int NumBits   = 32,
  parameter int DenBits   = 32,
  parameter int AlignBits = (NumBits > DenBits) ? NumBits : DenBits
) (
  input  logic [NumBits-1:0]   num_i,
  input  logic [DenBits-1:0]   den_i,
  output logic [AlignBits-1:0] a_o,
  output logic [AlignBits-1:0] b_o
);
  if (AlignBits > NumBits) begin : gen_pad_num
    assign a_o = {num_i, {(AlignBits - NumBits){1'b0}}};
  end else begin : gen_num
    assign a_o = num_i;
  end
  if (AlignBits > DenBits) begin : gen_pad_den
    assign b_o = {den_i, {(AlignBits - DenBits){1'b0}}};
  end else begin : gen_den
    assign b_o = den_i;
  end
endmodule
