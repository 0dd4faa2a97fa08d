// Bilinear interpolator 622 of Schilling & Knittel's TEXRAM (Figure 6): the Verilog twin of
// ColorBilinear in hdl/units/src/texmem/bilinear_622.rs (same ports, registers and reset).
// One 24-bit RGB result from the four texels colour extract 618 registered.
//
// Per channel, unsigned and exact until the one rounding, W = 2^F:
// top = c00 (W - fu) + c10 fu, bot = c01 (W - fu) + c11 fu (8 + F bits);
// sum = top (W - fv) + bot fv (8 + 2F bits); out = (sum + 2^(2F-1)) >> 2F, round half up
// (out <= 255: no overflow). Registered one cycle when `in_valid` (held otherwise; `valid`
// follows `in_valid`), with the exact sums sum_r, sum_g, sum_b. Synchronous reset.
module bilinear_622 #(
    parameter integer F = 4
) (
    input  wire            clk,
    input  wire            rst,
    input  wire            in_valid,
    input  wire [23:0]     c00,
    input  wire [23:0]     c10,
    input  wire [23:0]     c01,
    input  wire [23:0]     c11,
    input  wire [F-1:0]    fu,
    input  wire [F-1:0]    fv,
    output reg             valid,
    output reg  [23:0]     rgb,
    output reg  [7+2*F:0]  sum_r,
    output reg  [7+2*F:0]  sum_g,
    output reg  [7+2*F:0]  sum_b
);
    localparam integer SW = 8 + 2 * F;
    wire [F:0] w = (F+1)'(1) << F;
    // The weights of c00 and c01 (W - fu) and of the top row (W - fv): F + 1 bits.
    wire [F:0] wu = w - {1'b0, fu};
    wire [F:0] wv = w - {1'b0, fv};

    // One channel: c00..c11 = a..d, weights (W - fu, fu) = (w0, w1), (W - fv, fv) = (v0, v1).
    // Every operand is an argument: a continuous assignment of a function call is evaluated
    // again only when its arguments change.
    function automatic [SW-1:0] lerp2(input [7:0] a, input [7:0] b, input [7:0] c,
                                      input [7:0] d, input [F:0] w0, input [F-1:0] w1,
                                      input [F:0] v0, input [F-1:0] v1);
        reg [SW-1:0] top, bot;
        begin
            top = SW'(a) * SW'(w0) + SW'(b) * SW'(w1);
            bot = SW'(c) * SW'(w0) + SW'(d) * SW'(w1);
            lerp2 = top * SW'(v0) + bot * SW'(v1);
        end
    endfunction

    wire [SW-1:0] r = lerp2(c00[23:16], c10[23:16], c01[23:16], c11[23:16], wu, fu, wv, fv);
    wire [SW-1:0] g = lerp2(c00[15:8], c10[15:8], c01[15:8], c11[15:8], wu, fu, wv, fv);
    wire [SW-1:0] b = lerp2(c00[7:0], c10[7:0], c01[7:0], c11[7:0], wu, fu, wv, fv);
    wire [SW-1:0] half = SW'(1) << (2 * F - 1);
    wire [7:0] r_out = 8'((r + half) >> (2 * F));
    wire [7:0] g_out = 8'((g + half) >> (2 * F));
    wire [7:0] b_out = 8'((b + half) >> (2 * F));

    always @(posedge clk) begin
        if (rst) begin
            valid <= 1'b0;
            rgb <= 24'd0;
            sum_r <= {SW{1'b0}};
            sum_g <= {SW{1'b0}};
            sum_b <= {SW{1'b0}};
        end else begin
            valid <= in_valid;
            if (in_valid) begin
                rgb <= {r_out, g_out, b_out};
                sum_r <= r;
                sum_g <= g;
                sum_b <= b;
            end
        end
    end
endmodule
