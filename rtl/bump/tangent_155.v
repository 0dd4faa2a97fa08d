// Tangent unit 155 of US 2004/0207631 (Fenney), FIG. 7: the Verilog twin of
// hdl/units/src/bump/tangent_155.rs (same ports, widths, latency, rounding and reset).
//
//   B-spline / Bezier:  du = 2 lerp(tv, G - R, A - B)     dv = 2 lerp(tu, B - R, A - G)
//                       h  = lerp(tv, lerp(tu, R, G), lerp(tu, B, A))
//   Blinn (BLINN = 1):  du = G - R    dv = B - R    h = R
//   Trilinear (TRILINEAR = 1, para. 0081): the same for the coarser MIP level (r1, g1, b1,
//   a1 with tu1, tv1), then du = lerp(lod, du0, du1 / 2) (its texels are twice as wide),
//   h = lerp(lod, h0, h1);
//   then du, dv and h times the height scale.
//
// lerp(x, y, t) = x 2^F + t (y - x) is exact; the factor 2 is one fraction bit less. Each
// output is rounded once, to nearest with ties to even, to TAN_F fraction bits; du and dv
// saturate symmetrically to TAN_W bits (so normal unit 156 may negate them), h to H_W bits.
// r, g, b, a: uQ.BL_F (bilinear units 65-68), tu, tv, lod: uQ0.F, scale: uQ.SCALE_F,
// du, dv: sQ.TAN_F, height: uQ.TAN_F. One register stage (latency 1), synchronous reset.
// Without TRILINEAR the second level's ports are unused (the model has none).
module tangent_155 #(
    parameter integer BL_W = 28,
    parameter integer BL_F = 22,
    parameter integer F = 8,
    parameter integer SCALE_W = 16,
    parameter integer SCALE_F = 8,
    parameter integer TAN_W = 32,
    parameter integer H_W = 30,
    parameter integer TAN_F = 16,
    parameter integer BLINN = 0,
    parameter integer TRILINEAR = 0
) (
    input  wire               clk,
    input  wire               rst,
    input  wire [BL_W-1:0]    r,
    input  wire [BL_W-1:0]    g,
    input  wire [BL_W-1:0]    b,
    input  wire [BL_W-1:0]    a,
    input  wire [BL_W-1:0]    r1,
    input  wire [BL_W-1:0]    g1,
    input  wire [BL_W-1:0]    b1,
    input  wire [BL_W-1:0]    a1,
    input  wire [F-1:0]       tu,
    input  wire [F-1:0]       tv,
    input  wire [SCALE_W-1:0] scale,
    input  wire [F-1:0]       tu1,
    input  wire [F-1:0]       tv1,
    input  wire [F-1:0]       lod,
    output reg  [TAN_W-1:0]   du,
    output reg  [TAN_W-1:0]   dv,
    output reg  [H_W-1:0]     height
);
    // One level: slopes in DW bits, the height in HW bits (see tangent_155_level).
    localparam integer DW = BL_W + F + 2;
    localparam integer HW = BL_W + 2 * F + 2;
    // After the trilinear blend: 2 du0 2^F + lod (du1 - 2 du0), h0 2^F + lod (h1 - h0).
    localparam integer TD = (TRILINEAR != 0) ? DW + F + 3 : DW;
    localparam integer TH = (TRILINEAR != 0) ? HW + F + 2 : HW;
    localparam integer SW = SCALE_W + 1;
    localparam integer DPW = TD + SW;
    localparam integer HPW = TH + SW;
    // Fraction bits of the exact products.
    localparam integer LD_F = (BLINN != 0) ? BL_F : BL_F + F - 1;
    localparam integer LH_F = (BLINN != 0) ? BL_F : BL_F + 2 * F;
    localparam integer DU_F = ((TRILINEAR != 0) ? LD_F + 1 + F : LD_F) + SCALE_F;
    localparam integer H_F = ((TRILINEAR != 0) ? LH_F + F : LH_F) + SCALE_F;

    wire signed [DW-1:0] du0;
    wire signed [DW-1:0] dv0;
    wire signed [HW-1:0] h0;
    tangent_155_level #(.BL_W(BL_W), .F(F), .BLINN(BLINN)) level0 (
        .r(r), .g(g), .b(b), .a(a), .tu(tu), .tv(tv), .du(du0), .dv(dv0), .h(h0)
    );
    wire signed [TD-1:0] x_du;
    wire signed [TD-1:0] x_dv;
    wire signed [TH-1:0] x_h;
    generate
        if (TRILINEAR != 0) begin : g_trilinear
            wire signed [DW-1:0] du1;
            wire signed [DW-1:0] dv1;
            wire signed [HW-1:0] h1;
            tangent_155_level #(.BL_W(BL_W), .F(F), .BLINN(BLINN)) level1 (
                .r(r1), .g(g1), .b(b1), .a(a1), .tu(tu1), .tv(tv1), .du(du1), .dv(dv1), .h(h1)
            );
            wire signed [TD-1:0] lodd = $signed({{(TD - F){1'b0}}, lod});
            wire signed [TH-1:0] lodh = $signed({{(TH - F){1'b0}}, lod});
            // The coarser level's slopes are halved: the finer one's doubled instead.
            wire signed [TD-1:0] du2 = {{(TD - DW){du0[DW-1]}}, du0} <<< 1;
            wire signed [TD-1:0] dv2 = {{(TD - DW){dv0[DW-1]}}, dv0} <<< 1;
            wire signed [TD-1:0] du1x = {{(TD - DW){du1[DW-1]}}, du1};
            wire signed [TD-1:0] dv1x = {{(TD - DW){dv1[DW-1]}}, dv1};
            wire signed [TH-1:0] h0x = {{(TH - HW){h0[HW-1]}}, h0};
            wire signed [TH-1:0] h1x = {{(TH - HW){h1[HW-1]}}, h1};
            assign x_du = (du2 <<< F) + lodd * (du1x - du2);
            assign x_dv = (dv2 <<< F) + lodd * (dv1x - dv2);
            assign x_h = (h0x <<< F) + lodh * (h1x - h0x);
        end else begin : g_single
            /* verilator lint_off UNUSEDSIGNAL */
            wire [4*BL_W+3*F-1:0] unused_l1 = {r1, g1, b1, a1, tu1, tv1, lod};
            /* verilator lint_on UNUSEDSIGNAL */
            assign x_du = du0;
            assign x_dv = dv0;
            assign x_h = h0;
        end
    endgenerate

    wire signed [SW-1:0] ss = $signed({1'b0, scale});
    wire signed [DPW-1:0] p_du = {{SW{x_du[TD-1]}}, x_du} * {{TD{1'b0}}, ss};
    wire signed [DPW-1:0] p_dv = {{SW{x_dv[TD-1]}}, x_dv} * {{TD{1'b0}}, ss};
    wire signed [HPW-1:0] p_h = {{SW{x_h[TH-1]}}, x_h} * {{TH{1'b0}}, ss};

    wire [TAN_W-1:0] du_n;
    wire [TAN_W-1:0] dv_n;
    wire [H_W-1:0] h_n;
    tangent_155_narrow #(.IW(DPW), .SH(DU_F - TAN_F), .OW(TAN_W), .SIGNED(1)) u_du (p_du, du_n);
    tangent_155_narrow #(.IW(DPW), .SH(DU_F - TAN_F), .OW(TAN_W), .SIGNED(1)) u_dv (p_dv, dv_n);
    tangent_155_narrow #(.IW(HPW), .SH(H_F - TAN_F), .OW(H_W), .SIGNED(0)) u_h (p_h, h_n);

    always @(posedge clk) begin
        if (rst) begin
            du <= {TAN_W{1'b0}};
            dv <= {TAN_W{1'b0}};
            height <= {H_W{1'b0}};
        end else begin
            du <= du_n;
            dv <= dv_n;
            height <= h_n;
        end
    end
endmodule

// One MIP level of unit 155, exact: du and dv in DW = BL_W + F + 2 bits (fraction BL_F + F - 1,
// or BL_F for Blinn), h in HW = BL_W + 2F + 2 bits (fraction BL_F + 2F, or BL_F for Blinn).
// The differences lie in (-2^BL_W, 2^BL_W), their blend in (-2^(BL_W+F), 2^(BL_W+F)); the
// inner height blends in [0, 2^(BL_W+F)), the outer in [0, 2^(BL_W+2F)).
/* verilator lint_off DECLFILENAME */
module tangent_155_level #(
    parameter integer BL_W = 28,
    parameter integer F = 8,
    parameter integer BLINN = 0
) (
    input  wire [BL_W-1:0]                  r,
    input  wire [BL_W-1:0]                  g,
    input  wire [BL_W-1:0]                  b,
    input  wire [BL_W-1:0]                  a,
    input  wire [F-1:0]                     tu,
    input  wire [F-1:0]                     tv,
    output wire signed [BL_W+F+1:0]         du,
    output wire signed [BL_W+F+1:0]         dv,
    output wire signed [BL_W+2*F+1:0]       h
);
    localparam integer DW = BL_W + F + 2;
    localparam integer HW = BL_W + 2 * F + 2;
    wire signed [DW-1:0] rx = $signed({{(DW - BL_W){1'b0}}, r});
    wire signed [DW-1:0] gx = $signed({{(DW - BL_W){1'b0}}, g});
    wire signed [DW-1:0] bx = $signed({{(DW - BL_W){1'b0}}, b});
    wire signed [DW-1:0] gr = gx - rx;
    wire signed [DW-1:0] br = bx - rx;
    generate
        if (BLINN != 0) begin : g_blinn
            // Blinn's height ignores A and the blend factors (three bilinear units); the
            // ports stay, as in the model.
            /* verilator lint_off UNUSEDSIGNAL */
            wire [BL_W+2*F-1:0] unused_ta = {a, tu, tv};
            /* verilator lint_on UNUSEDSIGNAL */
            assign du = gr;
            assign dv = br;
            assign h = {{(HW - DW){rx[DW-1]}}, rx};
        end else begin : g_quadratic
            wire signed [DW-1:0] tus = $signed({{(DW - F){1'b0}}, tu});
            wire signed [DW-1:0] tvs = $signed({{(DW - F){1'b0}}, tv});
            wire signed [HW-1:0] tvh = $signed({{(HW - F){1'b0}}, tv});
            wire signed [DW-1:0] ax = $signed({{(DW - BL_W){1'b0}}, a});
            wire signed [DW-1:0] ab = ax - bx;
            wire signed [DW-1:0] ag = ax - gx;
            assign du = (gr <<< F) + tvs * (ab - gr);
            assign dv = (br <<< F) + tus * (ag - br);
            wire signed [DW-1:0] h0 = (rx <<< F) + tus * (gx - rx);
            wire signed [DW-1:0] h1 = (bx <<< F) + tus * (ax - bx);
            wire signed [HW-1:0] h0x = {{(HW - DW){h0[DW-1]}}, h0};
            wire signed [HW-1:0] h1x = {{(HW - DW){h1[DW-1]}}, h1};
            assign h = (h0x <<< F) + tvh * (h1x - h0x);
        end
    endgenerate
endmodule
/* verilator lint_on DECLFILENAME */

// One narrowing of unit 155: the signed IW-bit x with SH more fraction bits than the output
// (SH may be zero or negative: then nothing is rounded) rounded to nearest, ties to even,
// and saturated to OW bits: symmetrically, [-(2^(OW-1) - 1), 2^(OW-1) - 1], when SIGNED,
// else to [0, 2^OW - 1].
/* verilator lint_off DECLFILENAME */
module tangent_155_narrow #(
    parameter integer IW = 8,
    parameter integer SH = 1,
    parameter integer OW = 8,
    parameter integer SIGNED = 1
) (
    input  wire signed [IW-1:0] x,
    output wire        [OW-1:0] y
);
    localparam integer LS = (SH < 0) ? -SH : 0;
    localparam integer RS = (SH > 0) ? SH : 0;
    // Wide enough for x shifted left, the rounding carry and both bounds.
    localparam integer EW0 = IW + LS + 1;
    localparam integer EW = (EW0 > OW + 2) ? EW0 : OW + 2;
    wire signed [EW-1:0] xe = {{(EW - IW){x[IW-1]}}, x};
    wire signed [EW-1:0] rn;
    generate
        if (RS == 0) begin : g_exact
            assign rn = xe <<< LS;
        end else begin : g_round
            wire signed [EW-1:0] fl = xe >>> RS;
            // The dropped bits and one half, one bit wider so that RS = 1 needs no
            // zero-width replication.
            wire [RS:0] rem = {xe[RS-1:0], 1'b0};
            wire [RS:0] half = {1'b1, {RS{1'b0}}};
            wire up = (rem > half) || (rem == half && fl[0]);
            assign rn = fl + {{(EW - 1){1'b0}}, up};
        end
    endgenerate
    localparam integer TOP = (SIGNED != 0) ? OW - 1 : OW;
    wire signed [EW-1:0] hi = (({{(EW - 1){1'b0}}, 1'b1}) <<< TOP) - 1;
    wire signed [EW-1:0] lo = (SIGNED != 0) ? -hi : {EW{1'b0}};
    wire signed [EW-1:0] sat = (rn > hi) ? hi : (rn < lo) ? lo : rn;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [EW-1:0] keep = sat;
    /* verilator lint_on UNUSEDSIGNAL */
    assign y = keep[OW-1:0];
endmodule
/* verilator lint_on DECLFILENAME */
