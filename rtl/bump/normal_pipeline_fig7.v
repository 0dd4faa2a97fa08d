// The normal-generation pipeline of FIG. 7 of US 2004/0207631 (Fenney), para. 0050-0087: the
// Verilog twin of hdl/units/src/bump/normal_pipeline_fig7.rs, built from the units' twins (same
// ports, widths, latency, instance names and reset).
//
//   (u,v) -> address 150 -> texel fetch 151 -> replicate 152 -> bilinear 65..68 -> tangent 155 -> normal 156
//                        \-> blend adjust 153 -----------------^ (factors)     ^ (tu, tv, scale, lod carried)
//
// Stages (one register each): address; texel fetch with blend adjust beside it; bilinear
// units; tangent unit; normal unit (3 + ITERATIONS). Latency 7 + ITERATIONS, one sample per
// clock. TRILINEAR = 1: a second address unit, fetch, adjust, replicate and four bilinear
// units work on the next MIP level (HEIGHT_FILE_L1) at (u/2, v/2), the same bits with one
// more fraction bit (para. 0081).
//
// FILTER: 0 B-spline (unit 153 active), 1 Bezier (153 bypassed, 152 makes Equation 1's
// points), 2 Blinn (153 bypassed, tangents G - R and B - R). BORDER as texel_fetch_151.
// u, v: sQ<POS_INT>.<POS_FRAC>; scale: uQ.SCALE_F in SCALE_W bits; lod: uQ0.F; nx, ny, nz:
// sQ2.OUT_F; height: uQ.TAN_F in H_W bits. The bilinear outputs are BL_W bits, BL_F fraction.
module normal_pipeline_fig7 #(
    parameter integer POS_INT = 16,
    parameter integer POS_FRAC = 8,
    parameter integer F = 8,
    parameter integer TEXEL_BITS = 8,
    parameter integer FILTER = 0,
    parameter integer BORDER = 0,
    parameter integer BORDER_VALUE = 0,
    parameter integer MAP_W = 16,
    parameter integer MAP_H = 16,
    parameter integer TRILINEAR = 0,
    parameter integer MAP1_W = 8,
    parameter integer MAP1_H = 8,
    parameter integer BL_W = 28,
    parameter integer BL_F = 22,
    parameter integer SCALE_W = 16,
    parameter integer SCALE_F = 8,
    parameter integer TAN_W = 32,
    parameter integer H_W = 30,
    parameter integer TAN_F = 16,
    parameter integer OUT_F = 16,
    parameter integer TABLE_BITS = 8,
    parameter integer ITERATIONS = 1,
    parameter integer M_F = 22,
    parameter integer Y_F = 24,
    parameter HEIGHT_FILE = "height_151.hex",
    parameter HEIGHT_FILE_L1 = "height_151_l1.hex"
) (
    input  wire                        clk,
    input  wire                        rst,
    input  wire                        valid_in,
    input  wire [POS_INT+POS_FRAC-1:0] u,
    input  wire [POS_INT+POS_FRAC-1:0] v,
    input  wire [SCALE_W-1:0]          scale,
    input  wire [F-1:0]                lod,
    output wire                        valid,
    output wire [OUT_F+1:0]            nx,
    output wire [OUT_F+1:0]            ny,
    output wire [OUT_F+1:0]            nz,
    output wire [H_W-1:0]              height
);
    localparam integer CW = POS_INT + 1;
    localparam integer TW = TEXEL_BITS + 2;
    localparam integer TF = TEXEL_BITS / 4 + 2;
    localparam integer NORMAL_LATENCY = 3 + ITERATIONS;
    localparam integer BYPASS = (FILTER != 0) ? 1 : 0;
    localparam integer BEZIER = (FILTER == 1) ? 1 : 0;
    localparam integer BLINN = (FILTER == 2) ? 1 : 0;

    // Level 0: address, fetch with blend adjust beside it, replicate, bilinear units 65-68.
    wire [CW-1:0] ui, vj;
    wire [F-1:0] ub, vb;
    address_150 #(.POS_INT(POS_INT), .POS_FRAC(POS_FRAC), .BLEND_BITS(F)) address_150 (
        .clk(clk), .rst(rst), .u(u), .v(v), .colour(1'b0), .ui(ui), .vj(vj), .ub(ub), .vb(vb)
    );
    wire [TEXEL_BITS-1:0] t [0:8];
    texel_fetch_151 #(
        .COORD_W(CW), .TEXEL_W(TEXEL_BITS), .MAP_W(MAP_W), .MAP_H(MAP_H), .BORDER(BORDER),
        .BORDER_VALUE(BORDER_VALUE), .HEIGHT_FILE(HEIGHT_FILE)
    ) texel_fetch_151 (
        .clk(clk), .rst(rst), .ui(ui), .vj(vj), .a(t[0]), .b(t[1]), .c(t[2]), .d(t[3]),
        .e(t[4]), .f(t[5]), .g(t[6]), .h(t[7]), .k(t[8])
    );
    wire [F:0] u0, u1, v0, v1;
    /* verilator lint_off PINCONNECTEMPTY */
    blend_adjust_153 #(.FRAC_BITS(F), .REGISTERED(1)) blend_adjust_153 (
        .clk(clk), .rst(rst), .valid_in(1'b1), .bypass(BYPASS[0]), .u_in(ub), .v_in(vb),
        .valid(), .u0(u0), .u1(u1), .v0(v0), .v1(v1)
    );
    /* verilator lint_on PINCONNECTEMPTY */
    wire [TW-1:0] w [0:15];
    replicate_152 #(.TEXEL_BITS(TEXEL_BITS), .BEZIER(BEZIER)) replicate_152 (
        .a(t[0]), .b(t[1]), .c(t[2]), .d(t[3]), .e(t[4]), .f(t[5]), .g(t[6]), .h(t[7]), .k(t[8]),
        .r00(w[0]), .r10(w[1]), .r01(w[2]), .r11(w[3]), .g00(w[4]), .g10(w[5]), .g01(w[6]),
        .g11(w[7]), .b00(w[8]), .b10(w[9]), .b01(w[10]), .b11(w[11]), .a00(w[12]), .a10(w[13]),
        .a01(w[14]), .a11(w[15])
    );
    // Red (U0, V0), green (U1, V0), blue (U0, V1), alpha (U1, V1): para. 0060.
    wire [BL_W-1:0] rgba [0:7];
    `define TEXRTL_BILINEAR(NAME, W, K, S, T, Q) \
        bilinear_65_68 #(.TEXEL_W(TW), .TEXEL_F(TF), .BLEND_W(F + 1), .OUT_W(BL_W), \
            .OUT_F(BL_F)) NAME (.clk(clk), .rst(rst), .p00(W[4*K]), .p10(W[4*K+1]), \
            .p01(W[4*K+2]), .p11(W[4*K+3]), .s(S), .t(T), .q(Q));
    `TEXRTL_BILINEAR(bilinear_65_red, w, 0, u0, v0, rgba[0])
    `TEXRTL_BILINEAR(bilinear_66_green, w, 1, u1, v0, rgba[1])
    `TEXRTL_BILINEAR(bilinear_67_blue, w, 2, u0, v1, rgba[2])
    `TEXRTL_BILINEAR(bilinear_68_alpha, w, 3, u1, v1, rgba[3])

    // Level 1 (trilinear): the same units on the coarser map at (u/2, v/2).
    wire [F-1:0] ub1, vb1;
    generate
        if (TRILINEAR != 0) begin : g_l1
            wire [CW-1:0] ui1, vj1;
            address_150 #(.POS_INT(POS_INT), .POS_FRAC(POS_FRAC + 1), .BLEND_BITS(F))
                address_150_l1 (
                .clk(clk), .rst(rst), .u({u[POS_INT+POS_FRAC-1], u}),
                .v({v[POS_INT+POS_FRAC-1], v}), .colour(1'b0), .ui(ui1), .vj(vj1), .ub(ub1),
                .vb(vb1)
            );
            wire [TEXEL_BITS-1:0] t1 [0:8];
            texel_fetch_151 #(
                .COORD_W(CW), .TEXEL_W(TEXEL_BITS), .MAP_W(MAP1_W), .MAP_H(MAP1_H),
                .BORDER(BORDER), .BORDER_VALUE(BORDER_VALUE), .HEIGHT_FILE(HEIGHT_FILE_L1)
            ) texel_fetch_151_l1 (
                .clk(clk), .rst(rst), .ui(ui1), .vj(vj1), .a(t1[0]), .b(t1[1]), .c(t1[2]),
                .d(t1[3]), .e(t1[4]), .f(t1[5]), .g(t1[6]), .h(t1[7]), .k(t1[8])
            );
            wire [F:0] u0_1, u1_1, v0_1, v1_1;
            /* verilator lint_off PINCONNECTEMPTY */
            blend_adjust_153 #(.FRAC_BITS(F), .REGISTERED(1)) blend_adjust_153_l1 (
                .clk(clk), .rst(rst), .valid_in(1'b1), .bypass(BYPASS[0]), .u_in(ub1),
                .v_in(vb1), .valid(), .u0(u0_1), .u1(u1_1), .v0(v0_1), .v1(v1_1)
            );
            /* verilator lint_on PINCONNECTEMPTY */
            wire [TW-1:0] w1 [0:15];
            replicate_152 #(.TEXEL_BITS(TEXEL_BITS), .BEZIER(BEZIER)) replicate_152_l1 (
                .a(t1[0]), .b(t1[1]), .c(t1[2]), .d(t1[3]), .e(t1[4]), .f(t1[5]), .g(t1[6]),
                .h(t1[7]), .k(t1[8]), .r00(w1[0]), .r10(w1[1]), .r01(w1[2]), .r11(w1[3]),
                .g00(w1[4]), .g10(w1[5]), .g01(w1[6]), .g11(w1[7]), .b00(w1[8]), .b10(w1[9]),
                .b01(w1[10]), .b11(w1[11]), .a00(w1[12]), .a10(w1[13]), .a01(w1[14]),
                .a11(w1[15])
            );
            `TEXRTL_BILINEAR(bilinear_65_red_l1, w1, 0, u0_1, v0_1, rgba[4])
            `TEXRTL_BILINEAR(bilinear_66_green_l1, w1, 1, u1_1, v0_1, rgba[5])
            `TEXRTL_BILINEAR(bilinear_67_blue_l1, w1, 2, u0_1, v1_1, rgba[6])
            `TEXRTL_BILINEAR(bilinear_68_alpha_l1, w1, 3, u1_1, v1_1, rgba[7])
        end else begin : g_single
            assign ub1 = {F{1'b0}};
            assign vb1 = {F{1'b0}};
            assign rgba[4] = {BL_W{1'b0}};
            assign rgba[5] = {BL_W{1'b0}};
            assign rgba[6] = {BL_W{1'b0}};
            assign rgba[7] = {BL_W{1'b0}};
        end
    endgenerate
    `undef TEXRTL_BILINEAR

    // Blend factors (2 stages) and the side inputs (3 stages) carried to the tangent unit.
    wire [F-1:0] tu, tv, tu1, tv1, lod_d;
    wire [SCALE_W-1:0] scale_d;
    normal_pipeline_fig7_delay #(.W(4 * F), .DEPTH(2)) blend_carry (
        .clk(clk), .rst(rst), .i({ub, vb, ub1, vb1}), .o({tu, tv, tu1, tv1})
    );
    normal_pipeline_fig7_delay #(.W(SCALE_W + F), .DEPTH(3)) side_carry (
        .clk(clk), .rst(rst), .i({scale, lod}), .o({scale_d, lod_d})
    );

    wire [TAN_W-1:0] du, dv;
    wire [H_W-1:0] h;
    tangent_155 #(
        .BL_W(BL_W), .BL_F(BL_F), .F(F), .SCALE_W(SCALE_W), .SCALE_F(SCALE_F), .TAN_W(TAN_W),
        .H_W(H_W), .TAN_F(TAN_F), .BLINN(BLINN), .TRILINEAR(TRILINEAR)
    ) tangent_155 (
        .clk(clk), .rst(rst), .r(rgba[0]), .g(rgba[1]), .b(rgba[2]), .a(rgba[3]), .r1(rgba[4]),
        .g1(rgba[5]), .b1(rgba[6]), .a1(rgba[7]), .tu(tu), .tv(tv), .scale(scale_d), .tu1(tu1),
        .tv1(tv1), .lod(lod_d), .du(du), .dv(dv), .height(h)
    );

    normal_156 #(
        .TAN_W(TAN_W), .TF(TAN_F), .OUT_F(OUT_F), .TABLE_BITS(TABLE_BITS),
        .ITERATIONS(ITERATIONS), .M_F(M_F), .Y_F(Y_F)
    ) normal_156 (.clk(clk), .rst(rst), .du(du), .dv(dv), .nx(nx), .ny(ny), .nz(nz));
    normal_pipeline_fig7_delay #(.W(H_W), .DEPTH(NORMAL_LATENCY)) height_carry (
        .clk(clk), .rst(rst), .i(h), .o(height)
    );
    normal_pipeline_fig7_delay #(.W(1), .DEPTH(4 + NORMAL_LATENCY)) valid_carry (
        .clk(clk), .rst(rst), .i(valid_in), .o(valid)
    );
endmodule

// A delay line of DEPTH >= 1 register stages of W bits, every stage cleared by the
// synchronous reset (the model's Delay).
/* verilator lint_off DECLFILENAME */
module normal_pipeline_fig7_delay #(
    parameter integer W = 8,
    parameter integer DEPTH = 2
) (
    input  wire         clk,
    input  wire         rst,
    input  wire [W-1:0] i,
    output wire [W-1:0] o
);
    reg [W-1:0] stage [0:DEPTH-1];
    integer n;
    always @(posedge clk) begin
        if (rst) begin
            for (n = 0; n < DEPTH; n = n + 1) stage[n] <= {W{1'b0}};
        end else begin
            stage[0] <= i;
            for (n = 1; n < DEPTH; n = n + 1) stage[n] <= stage[n - 1];
        end
    end
    assign o = stage[DEPTH-1];
endmodule
/* verilator lint_on DECLFILENAME */
