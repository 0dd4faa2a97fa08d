// Page-mode DRAM 604 of Schilling & Knittel's TEXRAM (Figure 6, section 5): a behavioural
// model for testbenches, like a vendor's (not synthesizable), the twin of Dram in
// hdl/units/src/texmem/dram_604.rs.
//
// ROWS x COLS words of 16 bits behind RAS#, CAS#, WE#, OE# and 11 multiplexed address pins.
// The falling edge of RAS# latches the row into the page register (page_row, the open row);
// each falling edge of CAS# latches a column; from the second CAS# low cycle, once CAS# has
// been low T_CAS cycles counting this one, the word is on DQ (with OE# low); DQ keeps its last
// word otherwise. Contents at power-up: word a holds bits 63..48 of a * 0x9e3779b97f4a7c15
// (the model's pattern), so reads are checked without loading anything.
//
// Timing checks, in clock cycles, counted in `violations` (the first ones printed): RAS#
// precharge T_RP, RAS#-to-CAS# T_RCD, CAS# low T_CAS, CAS# precharge T_CP, a row or column
// beyond the array, CAS# with RAS# high, any write (WE# low: the texture DRAM is only read).
module dram_604 #(
    parameter integer ROWS = 512,
    parameter integer COLS = 512,
    parameter integer T_RP = 3,
    parameter integer T_RCD = 3,
    parameter integer T_CAS = 3,
    parameter integer T_CP = 3
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        ras_n,
    input  wire        cas_n,
    input  wire        we_n,
    input  wire        oe_n,
    input  wire [10:0] addr,
    output wire [15:0] dq,
    output wire        dq_valid,
    output reg  [31:0] violations
);
    localparam integer RB = (ROWS > 1) ? $clog2(ROWS) : 1;
    localparam integer CB = (COLS > 1) ? $clog2(COLS) : 1;

    reg [15:0] mem [0:ROWS*COLS-1];
    reg [RB-1:0] page_row;
    reg [CB-1:0] col;
    reg last_ras, last_cas;
    integer ras_level_for, cas_level_for, since_ras_fall;
    integer cycle;
    reg [15:0] dq_hold;

    integer w;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [63:0] x;
    /* verilator lint_on UNUSEDSIGNAL */
    initial begin
        for (w = 0; w < ROWS * COLS; w = w + 1) begin
            x = 64'(w) * 64'h9e3779b97f4a7c15;
            mem[w] = x[63:48];
        end
        page_row = {RB{1'b0}};
        col = {CB{1'b0}};
        dq_hold = 16'd0;
        violations = 32'd0;
        cycle = 0;
        since_ras_fall = 0;
        last_ras = 1'b1;
        last_cas = 1'b1;
        ras_level_for = 1000;
        cas_level_for = 1000;
    end

    assign dq_valid = !ras_n && !cas_n && !oe_n && !last_cas && (cas_level_for + 1 >= T_CAS);
    wire [31:0] a32 = {21'd0, addr};
    /* verilator lint_off UNUSEDSIGNAL */
    wire [31:0] word_index = 32'(page_row) * 32'(COLS) + 32'(col);
    /* verilator lint_on UNUSEDSIGNAL */
    assign dq = dq_valid ? mem[word_index[RB+CB-1:0]] : dq_hold;

    // This cycle's edges, the checks they fail (counted, the first 20 printed).
    wire ras_fall = last_ras && !ras_n;
    wire cas_fall = last_cas && !cas_n;
    wire cas_rise = !last_cas && cas_n;
    wire [31:0] rcd = ras_fall ? 32'd0 : since_ras_fall;
    wire [7:0] fails = {
        !we_n,
        ras_fall && ras_level_for < T_RP,
        ras_fall && a32 >= ROWS,
        cas_fall && ras_n,
        cas_fall && rcd < T_RCD,
        cas_fall && cas_level_for < T_CP,
        cas_fall && a32 >= COLS,
        cas_rise && cas_level_for < T_CAS
    };
    wire [3:0] n_fails = 4'(fails[0]) + 4'(fails[1]) + 4'(fails[2]) + 4'(fails[3])
                       + 4'(fails[4]) + 4'(fails[5]) + 4'(fails[6]) + 4'(fails[7]);
    always @(posedge clk) begin
        cycle <= cycle + 1;
        dq_hold <= dq;
        if (rst) begin
            last_ras <= 1'b1;
            last_cas <= 1'b1;
            ras_level_for <= 1000;
            cas_level_for <= 1000;
        end else begin
            violations <= violations + 32'(n_fails);
            if (n_fails != 0 && violations < 20)
                $display("dram_604: cycle %0d: timing or protocol violation %b (WE#, t_rp, row, RAS#, t_rcd, t_cp, column, t_cas)",
                         cycle, fails);
            if (ras_fall) page_row <= RB'(a32 % ROWS);
            if (cas_fall) col <= CB'(a32 % COLS);
            ras_level_for <= (last_ras == ras_n) ? ras_level_for + 1 : 1;
            cas_level_for <= (last_cas == cas_n) ? cas_level_for + 1 : 1;
            since_ras_fall <= (ras_fall ? 0 : since_ras_fall) + 1;
            last_ras <= ras_n;
            last_cas <= cas_n;
        end
    end
endmodule
