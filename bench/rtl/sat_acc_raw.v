// The example's accumulator under the name of its raw-integer model (bench/src/styles.rs).
module sat_acc_raw (
    input  wire              clk,
    input  wire              rst,
    input  wire              valid_in,
    input  wire signed [7:0] x,
    output wire              out_valid,
    output wire signed [9:0] acc
);
    sat_acc u (.clk(clk), .rst(rst), .valid_in(valid_in), .x(x), .out_valid(out_valid), .acc(acc));
endmodule
