// blend: out = b + alpha (a - b), a, b, alpha and out uQ0.8; two stages, latency 2.
// Stage 1 registers the exact product (sQ1.16) and b; stage 2 adds them and rounds half to
// even to uQ0.8, saturating (a blend lies between a and b: never reached).
module blend (
    input  wire       clk,
    input  wire       rst,
    input  wire       valid_in,
    input  wire [7:0] a,
    input  wire [7:0] b,
    input  wire [7:0] alpha,
    output wire       out_valid,
    output wire [7:0] out
);
    wire signed [9:0]  diff = $signed({2'b00, a}) - $signed({2'b00, b});
    wire signed [18:0] full = $signed({1'b0, alpha}) * diff;
    wire signed [17:0] product = full[17:0];
    reg  signed [17:0] product_r;
    reg  [7:0] b_r, out_r;
    reg  valid1_r, valid2_r;
    // b in sQ2.16 beside the product; the sum is exact.
    wire signed [19:0] sum = $signed({4'b0000, b_r, 8'b0}) + product_r;
    wire [11:0] kept = sum[19:8];
    wire [7:0]  dropped = sum[7:0];
    wire up = dropped[7] && (dropped[6:0] != 7'd0 || kept[0]);
    wire signed [12:0] rounded = $signed({1'b0, kept}) + $signed({12'd0, up});
    wire [7:0] sat = rounded < 0 ? 8'd0 : rounded > 13'sd255 ? 8'd255 : rounded[7:0];
    always @(posedge clk) begin
        if (rst) begin
            product_r <= 18'sd0;
            b_r <= 8'd0;
            valid1_r <= 1'b0;
            out_r <= 8'd0;
            valid2_r <= 1'b0;
        end else begin
            valid2_r <= valid1_r;
            if (valid1_r) out_r <= sat;
            valid1_r <= valid_in;
            if (valid_in) begin
                product_r <= product;
                b_r <= b;
            end
        end
    end
    assign out_valid = valid2_r;
    assign out = out_r;
endmodule
