// Inverse square root inside normal unit 156 of US 2004/0207631 (Fenney), FIG. 7, para. 0080:
// the Verilog twin of hdl/units/src/bump/rsqrt_156.rs (same ports, widths, latency, rounding, reset).
//
// m: uQ2.M_F in [1, 4) (below 1, never produced by unit 156, gives 0); y ~ 1/sqrt(m): uQ1.Y_F.
// Stage 0 reads a ROM of 2^TABLE_BITS first approximations, indexed by the bit telling [1,2)
// from [2,4) and the next TABLE_BITS - 1 bits below the leading one; each entry is 1/sqrt of
// its interval's midpoint rounded to nearest (computed at elaboration with integer division
// and an integer square root, as the model does at construction). Each of the ITERATIONS
// further stages is one Newton-Raphson step, products exact before rounding:
//
//   t  = m y^2 rounded to Y_F + 2 fraction bits (to nearest, ties to even), saturated to
//        uQ2.(Y_F+2)
//   y' = y (3 - t) / 2 rounded to Y_F fraction bits (ties to even), saturated to uQ1.Y_F
//
// Latency 1 + ITERATIONS; every register cleared by the synchronous reset.
module rsqrt_156 #(
    parameter integer TABLE_BITS = 8,
    parameter integer ITERATIONS = 1,
    parameter integer M_F = 22,
    parameter integer Y_F = 24
) (
    input  wire           clk,
    input  wire           rst,
    input  wire [M_F+1:0] m,
    output wire [Y_F:0]   y
);
    localparam integer MW = M_F + 2;
    localparam integer YW = Y_F + 1;
    localparam integer LO = TABLE_BITS - 1;
    localparam integer N = 1 << TABLE_BITS;

    // floor(sqrt(x)), digit by digit.
    function automatic [127:0] isqrt(input [127:0] x);
        reg [127:0] rest, root, trial;
        integer k;
        begin
            rest = x;
            root = 128'd0;
            for (k = 63; k >= 0; k = k - 1) begin
                trial = root | (128'd1 << (2 * k));
                if (rest >= trial) begin
                    rest = rest - trial;
                    root = (root >> 1) | (128'd1 << (2 * k));
                end else begin
                    root = root >> 1;
                end
            end
            isqrt = root;
        end
    endfunction

    // Entry `idx`: y = sqrt(2^(2 Y_F + M_F + 1) / mid2) with mid2 the interval's midpoint in
    // units of 2^-(M_F+1); z = floor(2 y); the entry is (z + 1) / 2.
    function automatic [Y_F:0] entry(input integer idx);
        reg [127:0] lo, start, mid2, z;
        /* verilator lint_off UNUSEDSIGNAL */
        reg [127:0] r;
        /* verilator lint_on UNUSEDSIGNAL */
        integer hi, shift;
        begin
            hi = idx >> LO;
            shift = M_F + hi - LO;
            lo = {96'd0, idx};
            lo = lo & ((128'd1 << LO) - 128'd1);
            start = ((128'd1 << LO) | lo) << shift;
            mid2 = 2 * start + (128'd1 << shift);
            z = isqrt((128'd1 << (2 * Y_F + M_F + 3)) / mid2);
            r = (z + 1) >> 1;
            entry = r[Y_F:0];
        end
    endfunction

    reg [Y_F:0] rom [0:N-1];
    integer i;
    initial begin
        for (i = 0; i < N; i = i + 1) rom[i] = entry(i);
    end

    // Stage 0: the table.
    wire hi_bit = m[M_F+1];
    wire [LO-1:0] lo_bits = hi_bit ? m[M_F-:LO] : m[M_F-1-:LO];
    wire [TABLE_BITS-1:0] idx = {hi_bit, lo_bits};
    wire below_one = (m[M_F+1:M_F] == 2'b00);
    // Per stage k: the mantissa carried along and the current approximation; yn[k] is
    // stage k's Newton step on stage k - 1 (yn[0] is not a step: the table feeds stage 0).
    reg [MW-1:0] m_r [0:ITERATIONS];
    reg [YW-1:0] y_r [0:ITERATIONS];
    /* verilator lint_off UNUSEDSIGNAL */
    wire [YW-1:0] yn [0:ITERATIONS];
    /* verilator lint_on UNUSEDSIGNAL */
    assign yn[0] = {YW{1'b0}};
    genvar s;
    generate
        for (s = 1; s <= ITERATIONS; s = s + 1) begin : g_newton
            rsqrt_156_newton #(.M_F(M_F), .Y_F(Y_F)) u_step (
                .m(m_r[s-1]), .y(y_r[s-1]), .y_next(yn[s])
            );
        end
    endgenerate
    integer k;
    always @(posedge clk) begin
        if (rst) begin
            for (k = 0; k <= ITERATIONS; k = k + 1) begin
                m_r[k] <= {MW{1'b0}};
                y_r[k] <= {YW{1'b0}};
            end
        end else begin
            m_r[0] <= m;
            y_r[0] <= below_one ? {YW{1'b0}} : rom[idx];
            for (k = 1; k <= ITERATIONS; k = k + 1) begin
                m_r[k] <= m_r[k-1];
                y_r[k] <= (m_r[k-1][M_F+1:M_F] == 2'b00) ? {YW{1'b0}} : yn[k];
            end
        end
    end
    assign y = y_r[ITERATIONS];
    // The last stage's mantissa is carried as the model carries it, and not read.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [MW-1:0] m_last = m_r[ITERATIONS];
    /* verilator lint_on UNUSEDSIGNAL */
endmodule

// One Newton-Raphson step of unit 156: y' = y (3 - m y^2) / 2, rounded as the header says.
/* verilator lint_off DECLFILENAME */
module rsqrt_156_newton #(
    parameter integer M_F = 22,
    parameter integer Y_F = 24
) (
    input  wire [M_F+1:0] m,
    input  wire [Y_F:0]   y,
    output wire [Y_F:0]   y_next
);
    localparam integer MW = M_F + 2;
    localparam integer YW = Y_F + 1;
    // m y^2: MW + 2 YW bits, fraction M_F + 2 Y_F; rounded to Y_F + 2: SH1 bits dropped.
    localparam integer PW = MW + 2 * YW;
    localparam integer SH1 = M_F + Y_F - 2;
    localparam integer TW = Y_F + 4;
    wire [PW-1:0] prod = {{(2 * YW){1'b0}}, m} * {{(MW + YW){1'b0}}, y} * {{(MW + YW){1'b0}}, y};
    wire [PW-1:0] fl1 = prod >> SH1;
    wire [SH1:0] rem1 = {prod[SH1-1:0], 1'b0};
    wire [SH1:0] half1 = {1'b1, {SH1{1'b0}}};
    wire up1 = (rem1 > half1) || (rem1 == half1 && fl1[0]);
    wire [PW-1:0] r1 = fl1 + {{(PW - 1){1'b0}}, up1};
    wire [PW-1:0] tmax = {{(PW - TW){1'b0}}, {TW{1'b1}}};
    wire [PW-1:0] t_wide = (r1 > tmax) ? tmax : r1;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [PW-1:0] t_keep = t_wide;
    /* verilator lint_on UNUSEDSIGNAL */
    wire [TW-1:0] t = t_keep[TW-1:0];
    // e = 3 - t in sQ3.(Y_F+2); y e: fraction 2 Y_F + 2, and the halving makes it 2 Y_F + 3.
    localparam integer EW = TW + 1;
    localparam integer QW = YW + EW + 1;
    localparam integer SH2 = Y_F + 3;
    wire signed [EW-1:0] three = $signed({3'b011, {(Y_F + 2){1'b0}}});
    wire signed [EW-1:0] e = three - $signed({1'b0, t});
    wire signed [QW-1:0] q = $signed({{(QW - YW){1'b0}}, y}) * $signed({{(QW - EW){e[EW-1]}}, e});
    wire signed [QW-1:0] fl2 = q >>> SH2;
    wire [SH2:0] rem2 = {q[SH2-1:0], 1'b0};
    wire [SH2:0] half2 = {1'b1, {SH2{1'b0}}};
    wire up2 = (rem2 > half2) || (rem2 == half2 && fl2[0]);
    wire signed [QW-1:0] r2 = fl2 + {{(QW - 1){1'b0}}, up2};
    wire signed [QW-1:0] ymax = $signed({{(QW - YW){1'b0}}, {YW{1'b1}}});
    wire signed [QW-1:0] ysat = r2[QW-1] ? {QW{1'b0}} : (r2 > ymax) ? ymax : r2;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [QW-1:0] y_keep = ysat;
    /* verilator lint_on UNUSEDSIGNAL */
    assign y_next = y_keep[YW-1:0];
endmodule
/* verilator lint_on DECLFILENAME */
