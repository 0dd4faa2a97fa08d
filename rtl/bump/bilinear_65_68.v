// Bilinear unit, one of 65-68 of US 2004/0207631 (Fenney), FIG. 7: the Verilog twin of
// hdl/units/src/bump/bilinear_65_68.rs (same ports, widths, latency, rounding and reset).
//
//   q = lerp(lerp(p00, p10, s), lerp(p01, p11, s), t),   lerp(a, b, x) = a + x (b - a)
//
// Both blends are exact (fraction TEXEL_F + 2 BLEND_W); the result is rounded to OUT_F
// fraction bits, to nearest with ties to even, and saturated to OUT_W bits (it cannot exceed
// the largest texel). With OUT_F = TEXEL_F + 2 BLEND_W (the default) nothing is rounded.
// p00..p11: uQ.TEXEL_F (replicate unit 152's outputs); s, t: uQ0.BLEND_W; q: uQ.OUT_F.
// Every intermediate is as wide as its range needs (no wider). One register stage (latency
// 1), cleared by the synchronous reset.
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
    // Widths as the arithmetic needs them: the first blends lie in [0, 2^(TEXEL_W+BLEND_W))
    // and their differences in magnitude below that; one sign bit and one bit of headroom.
    localparam integer RW = TEXEL_W + BLEND_W + 2;
    localparam integer XW = RW + BLEND_W + 1;
    wire signed [RW-1:0] a00 = $signed({{(RW - TEXEL_W){1'b0}}, p00});
    wire signed [RW-1:0] a10 = $signed({{(RW - TEXEL_W){1'b0}}, p10});
    wire signed [RW-1:0] a01 = $signed({{(RW - TEXEL_W){1'b0}}, p01});
    wire signed [RW-1:0] a11 = $signed({{(RW - TEXEL_W){1'b0}}, p11});
    wire signed [RW-1:0] sx = $signed({{(RW - BLEND_W){1'b0}}, s});
    // lerp(a, b, s) = a 2^BLEND_W + s (b - a), exact.
    wire signed [RW-1:0] r0 = (a00 <<< BLEND_W) + sx * (a10 - a00);
    wire signed [RW-1:0] r1 = (a01 <<< BLEND_W) + sx * (a11 - a01);
    wire signed [XW-1:0] r0x = {{(XW - RW){r0[RW-1]}}, r0};
    wire signed [XW-1:0] r1x = {{(XW - RW){r1[RW-1]}}, r1};
    wire signed [XW-1:0] tx = $signed({{(XW - BLEND_W){1'b0}}, t});
    wire signed [XW-1:0] x = (r0x <<< BLEND_W) + tx * (r1x - r0x);
    wire [OUT_W-1:0] qn;
    generate
        if (SH == 0) begin : g_exact
            // The exact result is below 2^OUT_W: the bits above are zero.
            /* verilator lint_off UNUSEDSIGNAL */
            wire [XW-1:0] xu = x;
            /* verilator lint_on UNUSEDSIGNAL */
            assign qn = xu[OUT_W-1:0];
        end else begin : g_round
            // Round half to even on the SH dropped bits, then saturate to OUT_W bits.
            wire [XW-1:0] xu = x;
            wire [XW-1:0] fl = xu >> SH;
            wire [SH-1:0] rem = xu[SH-1:0];
            wire [SH-1:0] half = {1'b1, {(SH - 1){1'b0}}};
            wire up = (rem > half) || (rem == half && fl[0]);
            wire [XW-1:0] rn = fl + {{(XW - 1){1'b0}}, up};
            wire [XW-1:0] max = {{(XW - OUT_W){1'b0}}, {OUT_W{1'b1}}};
            wire [XW-1:0] sat = (rn > max) ? max : rn;
            /* verilator lint_off UNUSEDSIGNAL */
            wire [XW-1:0] keep = sat;
            /* verilator lint_on UNUSEDSIGNAL */
            assign qn = keep[OUT_W-1:0];
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) q <= {OUT_W{1'b0}};
        else q <= qn;
    end
endmodule
