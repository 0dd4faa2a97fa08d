// Bilinear unit, one of 65-68 of US 2004/0207631 (Fenney), FIG. 7: the Verilog twin of
// hdl/src/bump/bilinear_65_68.rs (same ports, widths, latency, rounding and reset).
//
//   q = lerp(lerp(p00, p10, s), lerp(p01, p11, s), t),   lerp(a, b, x) = a + x (b - a)
//
// Both blends are exact (fraction TEXEL_F + 2 BLEND_W); the result is rounded to OUT_F
// fraction bits, to nearest with ties to even, and saturated to OUT_W bits (it cannot exceed
// the largest texel). With OUT_F = TEXEL_F + 2 BLEND_W (the default) nothing is rounded.
// p00..p11: uQ.TEXEL_F (replicate unit 152's outputs); s, t: uQ0.BLEND_W; q: uQ.OUT_F.
// One register stage (latency 1), cleared by the synchronous reset.
module bilinear_65_68 #(
    parameter integer TEXEL_W = 10,
    parameter integer TEXEL_F = 4,
    parameter integer BLEND_W = 9,
    parameter integer OUT_W = 28,
    parameter integer OUT_F = 22
) (
    input  wire               clk,
    input  wire               rst,
    input  wire [TEXEL_W-1:0] p00,
    input  wire [TEXEL_W-1:0] p10,
    input  wire [TEXEL_W-1:0] p01,
    input  wire [TEXEL_W-1:0] p11,
    input  wire [BLEND_W-1:0] s,
    input  wire [BLEND_W-1:0] t,
    output reg  [OUT_W-1:0]   q
);
    localparam integer EXACT_F = TEXEL_F + 2 * BLEND_W;
    localparam integer SH = EXACT_F - OUT_F;
    // The exact blend fits 48 bits (texels up to 14 bits, factors up to 17); it is computed
    // in 64-bit signed arithmetic, whose upper bits are zero by construction.
    /* verilator lint_off UNUSEDSIGNAL */
    wire signed [63:0] a00 = {{(64 - TEXEL_W){1'b0}}, p00};
    wire signed [63:0] a10 = {{(64 - TEXEL_W){1'b0}}, p10};
    wire signed [63:0] a01 = {{(64 - TEXEL_W){1'b0}}, p01};
    wire signed [63:0] a11 = {{(64 - TEXEL_W){1'b0}}, p11};
    wire signed [63:0] sx = {{(64 - BLEND_W){1'b0}}, s};
    wire signed [63:0] tx = {{(64 - BLEND_W){1'b0}}, t};
    wire signed [63:0] r0 = (a00 <<< BLEND_W) + sx * (a10 - a00);
    wire signed [63:0] r1 = (a01 <<< BLEND_W) + sx * (a11 - a01);
    wire signed [63:0] x = (r0 <<< BLEND_W) + tx * (r1 - r0);
    wire [63:0] qn;
    generate
        if (SH == 0) begin : g_exact
            assign qn = x;
        end else begin : g_round
            // Round half to even on the SH dropped bits, then saturate to OUT_W bits.
            wire [63:0] fl = x >>> SH;
            wire [63:0] rem = x & ((64'd1 << SH) - 64'd1);
            wire [63:0] half = 64'd1 << (SH - 1);
            wire up = (rem > half) || (rem == half && fl[0]);
            wire [63:0] rn = fl + {63'd0, up};
            wire [63:0] max = (64'd1 << OUT_W) - 64'd1;
            assign qn = (rn > max) ? max : rn;
        end
    endgenerate
    /* verilator lint_on UNUSEDSIGNAL */

    always @(posedge clk) begin
        if (rst) q <= {OUT_W{1'b0}};
        else q <= qn[OUT_W-1:0];
    end
endmodule
