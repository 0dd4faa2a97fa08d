// Normal unit 156 of US 2004/0207631 (Fenney), FIG. 7, para. 0076-0080: the Verilog twin of
// hdl/units/src/bump/normal_156.rs (same ports, widths, latency, rounding and reset), around the
// inverse square root of rtl/bump/rsqrt_156.v.
//
//   N = (-du, -dv, 1)
//   s = du^2 + dv^2 + 1                exact, fraction 2 TF
//   s = m 4^k, m in [1, 4)             leading-one detect; m truncated to M_F fraction bits
//   y = rsqrt(m)                       table + ITERATIONS Newton steps (rsqrt_156)
//   n = N y 2^-k                       rounded to OUT_F fraction bits, to nearest with ties to
//                                      even; saturated to sQ2.OUT_F
//
// du, dv: sQ.TF in TAN_W bits, symmetric range (the tangent unit saturates symmetrically, so
// the negation is exact); nx, ny, nz: sQ2.OUT_F. Stages: square/normalise (1), the rsqrt
// (1 + ITERATIONS, with -du, -dv and k carried beside it), multiply (1): latency
// 3 + ITERATIONS. Every register cleared by the synchronous reset.
module normal_156 #(
    parameter integer TAN_W = 32,
    parameter integer TF = 16,
    parameter integer OUT_F = 16,
    parameter integer TABLE_BITS = 8,
    parameter integer ITERATIONS = 1,
    parameter integer M_F = 22,
    parameter integer Y_F = 24
) (
    input  wire               clk,
    input  wire               rst,
    input  wire [TAN_W-1:0]   du,
    input  wire [TAN_W-1:0]   dv,
    output reg  [OUT_F+1:0]   nx,
    output reg  [OUT_F+1:0]   ny,
    output reg  [OUT_F+1:0]   nz
);
    localparam integer SW = 2 * TAN_W + 1;
    localparam integer MW = M_F + 2;
    localparam integer YW = Y_F + 1;
    localparam integer OW = OUT_F + 2;
    localparam integer L = 1 + ITERATIONS;

    // Square stage: s exact, then its leading one.
    wire signed [SW-1:0] dux = {{(SW - TAN_W){du[TAN_W-1]}}, du};
    wire signed [SW-1:0] dvx = {{(SW - TAN_W){dv[TAN_W-1]}}, dv};
    wire [SW-1:0] one = {{(SW - 1){1'b0}}, 1'b1} << (2 * TF);
    wire [SW-1:0] s = dux * dux + dvx * dvx + one;
    integer b, len, kk, sh;
    reg [SW+M_F-1:0] sx;
    reg [MW-1:0] m_n;
    reg [5:0] k_n;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [31:0] k_bits;
    /* verilator lint_on UNUSEDSIGNAL */
    always @* begin
        len = 0;
        for (b = 0; b < SW; b = b + 1) if (s[b]) len = b + 1;
        // s >= 1, so len >= 2 TF + 1.
        kk = (len - 1 - 2 * TF) / 2;
        sh = 2 * TF + 2 * kk - M_F;
        sx = {{M_F{1'b0}}, s};
        if (sh >= 0) sx = sx >> sh;
        else sx = sx << (-sh);
        m_n = sx[MW-1:0];
        k_bits = kk;
        k_n = k_bits[5:0];
    end

    reg [TAN_W-1:0] nx_sq, ny_sq;
    reg [5:0] k_sq;
    reg [MW-1:0] m_sq;
    always @(posedge clk) begin
        if (rst) begin
            nx_sq <= {TAN_W{1'b0}};
            ny_sq <= {TAN_W{1'b0}};
            k_sq <= 6'd0;
            m_sq <= {MW{1'b0}};
        end else begin
            nx_sq <= -du;
            ny_sq <= -dv;
            k_sq <= k_n;
            m_sq <= m_n;
        end
    end

    // The rsqrt stages, and -du, -dv, k carried beside them.
    wire [YW-1:0] y;
    rsqrt_156 #(.TABLE_BITS(TABLE_BITS), .ITERATIONS(ITERATIONS), .M_F(M_F), .Y_F(Y_F)) rsqrt_156 (
        .clk(clk), .rst(rst), .m(m_sq), .y(y)
    );
    reg [TAN_W-1:0] nx_d [0:L-1];
    reg [TAN_W-1:0] ny_d [0:L-1];
    reg [5:0] k_d [0:L-1];
    integer c;
    always @(posedge clk) begin
        for (c = 0; c < L; c = c + 1) begin
            if (rst) begin
                nx_d[c] <= {TAN_W{1'b0}};
                ny_d[c] <= {TAN_W{1'b0}};
                k_d[c] <= 6'd0;
            end else if (c == 0) begin
                nx_d[c] <= nx_sq;
                ny_d[c] <= ny_sq;
                k_d[c] <= k_sq;
            end else begin
                nx_d[c] <= nx_d[c-1];
                ny_d[c] <= ny_d[c-1];
                k_d[c] <= k_d[c-1];
            end
        end
    end

    // Multiply stage.
    wire [TAN_W-1:0] unit_z = {{(TAN_W - 1){1'b0}}, 1'b1} << TF;
    wire [OW-1:0] nx_n, ny_n, nz_n;
    normal_156_scale #(.NW(TAN_W), .YW(YW), .OW(OW), .BASE(TF + Y_F - OUT_F)) u_x (
        .n(nx_d[L-1]), .y(y), .k(k_d[L-1]), .q(nx_n)
    );
    normal_156_scale #(.NW(TAN_W), .YW(YW), .OW(OW), .BASE(TF + Y_F - OUT_F)) u_y (
        .n(ny_d[L-1]), .y(y), .k(k_d[L-1]), .q(ny_n)
    );
    normal_156_scale #(.NW(TAN_W), .YW(YW), .OW(OW), .BASE(TF + Y_F - OUT_F)) u_z (
        .n(unit_z), .y(y), .k(k_d[L-1]), .q(nz_n)
    );
    always @(posedge clk) begin
        if (rst) begin
            nx <= {OW{1'b0}};
            ny <= {OW{1'b0}};
            nz <= {OW{1'b0}};
        end else begin
            nx <= nx_n;
            ny <= ny_n;
            nz <= nz_n;
        end
    end
endmodule

// n (signed NW bits) times y (unsigned YW bits) with BASE + k more fraction bits than the
// output, rounded to nearest with ties to even (shifted left, exactly, when BASE + k <= 0)
// and saturated to OW signed bits.
/* verilator lint_off DECLFILENAME */
module normal_156_scale #(
    parameter integer NW = 32,
    parameter integer YW = 25,
    parameter integer OW = 18,
    parameter integer BASE = 24
) (
    input  wire [NW-1:0] n,
    input  wire [YW-1:0] y,
    input  wire [5:0]    k,
    output wire [OW-1:0] q
);
    localparam integer XW = NW + YW + 1;
    localparam integer LS = (BASE < 0) ? -BASE : 0;
    localparam integer EW0 = XW + LS + 2;
    localparam integer EW = (EW0 > OW + 2) ? EW0 : OW + 2;
    wire signed [EW-1:0] ne = {{(EW - NW){n[NW-1]}}, n};
    wire signed [EW-1:0] ye = $signed({{(EW - YW){1'b0}}, y});
    wire signed [EW-1:0] x = ne * ye;
    wire signed [EW-1:0] hi = $signed(({{(EW - 1){1'b0}}, 1'b1} << (OW - 1)) - 1);
    wire signed [EW-1:0] lo = -hi - 1;
    integer sh;
    reg signed [EW-1:0] fl, rn, sat;
    reg [EW-1:0] mask, rem, half;
    reg up;
    always @* begin
        sh = BASE + {26'd0, k};
        fl = x;
        rem = {EW{1'b0}};
        half = {EW{1'b0}};
        mask = {EW{1'b0}};
        up = 1'b0;
        if (sh > 0) begin
            fl = x >>> sh;
            mask = ~({EW{1'b1}} << sh);
            rem = x & mask;
            half = {{(EW - 1){1'b0}}, 1'b1} << (sh - 1);
            up = (rem > half) || (rem == half && fl[0]);
            rn = fl + {{(EW - 1){1'b0}}, up};
        end else begin
            rn = x <<< (-sh);
        end
        sat = (rn > hi) ? hi : (rn < lo) ? lo : rn;
    end
    /* verilator lint_off UNUSEDSIGNAL */
    wire [EW-1:0] keep = sat;
    /* verilator lint_on UNUSEDSIGNAL */
    assign q = keep[OW-1:0];
endmodule
/* verilator lint_on DECLFILENAME */
