// The guide's blend under the name of its raw-integer model (bench/src/styles.rs).
module blend_raw (
    input  wire       clk,
    input  wire       rst,
    input  wire       valid_in,
    input  wire [7:0] a,
    input  wire [7:0] b,
    input  wire [7:0] alpha,
    output wire       out_valid,
    output wire [7:0] out
);
    blend u (.clk(clk), .rst(rst), .valid_in(valid_in), .a(a), .b(b), .alpha(alpha),
             .out_valid(out_valid), .out(out));
endmodule
