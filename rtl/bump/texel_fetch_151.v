// Texel fetch unit 151 of US 2004/0207631 (Fenney), FIG. 7, para. 0053: the Verilog twin of
// hdl/units/src/bump/texel_fetch_151.rs (same ports, widths, latency, border modes and reset).
//
// The 3x3 height texels around (ui, vj), a..k row by row:
//   a = (ui-1, vj-1)  b = (ui, vj-1)  c = (ui+1, vj-1)
//   d = (ui-1, vj  )  e = (ui, vj  )  f = (ui+1, vj  )
//   g = (ui-1, vj+1)  h = (ui, vj+1)  k = (ui+1, vj+1)
// Border modes (BORDER): 0 wrap (i mod n), 1 clamp (0..n-1), 2 mirror (mirrored repeat of
// period 2n: ..., 1, 0, 0, 1, ..., n-1, n-1, ...), 3 constant (BORDER_VALUE outside the map).
//
// ui, vj: signed COORD_W bits (address unit 150); texels: TEXEL_W bits (uQ6.2 or uQ3.1).
// The height map is a MAP_W x MAP_H ROM, row-major, loaded from HEIGHT_FILE with $readmemh
// (one texel per line, in hex). One register stage (latency 1), synchronous reset.
module texel_fetch_151 #(
    parameter integer COORD_W = 17,
    parameter integer TEXEL_W = 8,
    parameter integer MAP_W = 16,
    parameter integer MAP_H = 16,
    parameter integer BORDER = 0,
    parameter integer BORDER_VALUE = 0,
    parameter HEIGHT_FILE = "height_151.hex"
) (
    input  wire               clk,
    input  wire               rst,
    input  wire [COORD_W-1:0] ui,
    input  wire [COORD_W-1:0] vj,
    output reg  [TEXEL_W-1:0] a,
    output reg  [TEXEL_W-1:0] b,
    output reg  [TEXEL_W-1:0] c,
    output reg  [TEXEL_W-1:0] d,
    output reg  [TEXEL_W-1:0] e,
    output reg  [TEXEL_W-1:0] f,
    output reg  [TEXEL_W-1:0] g,
    output reg  [TEXEL_W-1:0] h,
    output reg  [TEXEL_W-1:0] k
);
    localparam integer XW = $clog2(MAP_W);
    localparam integer YW = $clog2(MAP_H);
    localparam integer AW = $clog2(MAP_W * MAP_H);

    reg [TEXEL_W-1:0] mem [0:MAP_W*MAP_H-1];
    initial $readmemh(HEIGHT_FILE, mem);

    // Column and row indices of the three neighbours along each axis, and whether each lies
    // inside the map (only the constant border uses it).
    wire [XW-1:0] x [0:2];
    wire [YW-1:0] y [0:2];
    wire [2:0] xin;
    wire [2:0] yin;
    genvar n;
    generate
        for (n = 0; n < 3; n = n + 1) begin : g_axis
            texel_fetch_151_axis #(.CW(COORD_W), .N(MAP_W), .IW(XW), .BORDER(BORDER), .D(n - 1))
                u_x (.i(ui), .idx(x[n]), .in_map(xin[n]));
            texel_fetch_151_axis #(.CW(COORD_W), .N(MAP_H), .IW(YW), .BORDER(BORDER), .D(n - 1))
                u_y (.i(vj), .idx(y[n]), .in_map(yin[n]));
        end
    endgenerate

    // The nine reads, row by row (a b c / d e f / g h k).
    wire [TEXEL_W-1:0] t [0:8];
    generate
        for (n = 0; n < 9; n = n + 1) begin : g_read
            wire [AW-1:0] addr = AW'(y[n / 3]) * AW'(MAP_W) + AW'(x[n % 3]);
            wire outside = (BORDER == 3) && !(xin[n % 3] && yin[n / 3]);
            assign t[n] = outside ? TEXEL_W'(BORDER_VALUE) : mem[addr];
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) begin
            {a, b, c, d, e, f, g, h, k} <= {(9 * TEXEL_W){1'b0}};
        end else begin
            {a, b, c, d, e, f, g, h, k} <= {t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]};
        end
    end
endmodule

// One axis of unit 151: the index of coordinate i + D (D in -1..1) in a map side of N texels
// under the border mode, and whether i + D lies inside 0..N-1. Computed in JW signed bits,
// wide enough for i + D and for 2N, so nothing wraps.
/* verilator lint_off DECLFILENAME */
module texel_fetch_151_axis #(
    parameter integer CW = 17,
    parameter integer N = 16,
    parameter integer IW = 4,
    parameter integer BORDER = 0,
    parameter integer D = 0
) (
    input  wire [CW-1:0] i,
    output wire [IW-1:0] idx,
    output wire          in_map
);
    localparam integer NW = $clog2(2 * N) + 2;
    localparam integer JW = (CW + 1 > NW) ? CW + 1 : NW;
    localparam signed [JW-1:0] SN = JW'(N);
    wire signed [JW-1:0] j = $signed({{(JW - CW){i[CW-1]}}, i}) + JW'(D);
    assign in_map = (j >= 0) && (j < SN);
    // Euclidean remainders: Verilog's % takes the dividend's sign.
    wire signed [JW-1:0] rn = j % SN;
    wire signed [JW-1:0] wrap = (rn < 0) ? rn + SN : rn;
    wire signed [JW-1:0] r2 = j % (SN <<< 1);
    wire signed [JW-1:0] m2 = (r2 < 0) ? r2 + (SN <<< 1) : r2;
    wire signed [JW-1:0] mirror = (m2 < SN) ? m2 : (SN <<< 1) - 1 - m2;
    wire signed [JW-1:0] clamp = (j < 0) ? 0 : (j >= SN) ? SN - 1 : j;
    wire signed [JW-1:0] sel = (BORDER == 0) ? wrap : (BORDER == 1) ? clamp
                             : (BORDER == 2) ? mirror : j;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [JW-1:0] keep = sel;
    /* verilator lint_on UNUSEDSIGNAL */
    // Outside the map (constant border) the index is unused; inside it is below N.
    assign idx = keep[IW-1:0];
endmodule
/* verilator lint_on DECLFILENAME */
