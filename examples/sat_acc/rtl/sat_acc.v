// sat_acc: acc <= sat(acc + x), x sQ4.4, acc sQ6.4; out_valid one cycle after valid_in.
module sat_acc (
    input  wire              clk,
    input  wire              rst,
    input  wire              valid_in,
    input  wire signed [7:0] x,
    output wire              out_valid,
    output wire signed [9:0] acc
);
    reg signed [9:0] acc_r;
    reg valid_r;
    wire signed [10:0] sum = acc_r + x;  // full precision, one bit wider
    wire signed [9:0] sat = (sum > 11'sd511) ? 10'sd511 : (sum < -11'sd512) ? -10'sd512 : sum[9:0];
    always @(posedge clk) begin
        if (rst) begin
            acc_r <= 10'sd0;
            valid_r <= 1'b0;
        end else begin
            valid_r <= valid_in;
            if (valid_in) acc_r <= sat;
        end
    end
    assign out_valid = valid_r;
    assign acc = acc_r;
endmodule
