// DRAM control unit 607 of Schilling & Knittel's TEXRAM (Figure 6, section 5), its word-read
// controller: the Verilog twin of DramCtrl in hdl/units/src/texmem/control_607.rs (same ports,
// widths, states, pin timing and reset), with the page register: the open row.
//
// Takes a word read (req_valid + req_addr, accepted while `ready`), keeps the open page and
// drives the DRAM's pins: on a page hit straight to the CAS# cycle; on a fault RAS# high for
// T_RP cycles, RAS# low with the new row for T_RCD, then the CAS# cycle (CAS# low T_CAS
// cycles, the word returned in the last of them, then CAS# high T_CP). A new request is taken
// when idle or in the last cycle of CAS# precharge, so page-mode reads follow each other every
// T_CAS + T_CP cycles (30 ns at 5 ns a cycle by default, a fault another T_RP + T_RCD).
//
// req_addr: word address, row-major (row = addr / COLS); dram_addr: the 11 multiplexed
// address pins (row in PRECHARGE and ROW_OPEN, column otherwise); resp_data: the word read,
// held until the next one. Synchronous reset. States (state): 0 IDLE, 1 PRECHARGE,
// 2 ROW_OPEN, 3 CAS_LOW, 4 CAS_HIGH; count: cycles in the state.
module control_607 #(
    parameter integer ROWS = 512,
    parameter integer COLS = 512,
    parameter integer T_RP = 3,
    parameter integer T_RCD = 3,
    parameter integer T_CAS = 3,
    parameter integer T_CP = 3
) (
    input  wire                               clk,
    input  wire                               rst,
    input  wire                               req_valid,
    input  wire [$clog2(ROWS * COLS)-1:0]     req_addr,
    output wire                               ready,
    output wire                               resp_valid,
    output wire [15:0]                        resp_data,
    // DRAM 604's pins.
    output wire                               ras_n,
    output wire                               cas_n,
    output wire                               we_n,
    output wire                               oe_n,
    output wire [10:0]                        dram_addr,
    input  wire [15:0]                        dq,
    input  wire                               dq_valid
);
    localparam integer AB = $clog2(ROWS * COLS);
    localparam integer CB = $clog2(COLS);
    localparam [2:0] IDLE = 3'd0, PRECHARGE = 3'd1, ROW_OPEN = 3'd2, CAS_LOW = 3'd3,
        CAS_HIGH = 3'd4;

    reg [2:0] state;
    reg [10:0] count;
    reg [10:0] open_row;
    reg row_open;
    reg [AB-1:0] addr_r;
    reg [15:0] resp_hold;

    wire last_cp = (state == CAS_HIGH) && (count >= 11'(T_CP));
    wire free = (state == IDLE) || last_cp;
    wire accept = free && req_valid;
    wire [AB-1:0] addr = accept ? req_addr : addr_r;
    // The address in at least 11 bits (the pins'), split into row and column.
    localparam integer XW = (AB > 11) ? AB : 11;
    wire [XW-1:0] ax = XW'(addr);
    wire [10:0] row = 11'(ax >> CB);
    wire [10:0] col = 11'(ax & XW'(COLS - 1));
    wire open = row_open && (open_row == row);
    assign ready = free;

    // Pins from the state (the column of a request accepted this cycle already on the bus).
    assign ras_n = (state == PRECHARGE) || ((state == IDLE || state == CAS_HIGH) && !row_open);
    assign cas_n = (state != CAS_LOW);
    assign oe_n = cas_n;
    assign we_n = 1'b1;
    assign dram_addr = (state == PRECHARGE || state == ROW_OPEN) ? row : col;

    // The word, in the last CAS# low cycle; held until the next.
    wire word = (state == CAS_LOW) && (count >= 11'(T_CAS));
    assign resp_valid = word && dq_valid;
    assign resp_data = word ? dq : resp_hold;

    reg [2:0] state_n;
    reg [10:0] count_n;
    always @* begin
        state_n = state;
        count_n = count + 11'd1;
        if (accept) begin
            state_n = open ? CAS_LOW : PRECHARGE;
            count_n = 11'd1;
        end else begin
            case (state)
                IDLE: count_n = 11'd0;
                PRECHARGE: if (count >= 11'(T_RP)) begin
                    state_n = ROW_OPEN;
                    count_n = 11'd1;
                end
                ROW_OPEN: if (count >= 11'(T_RCD)) begin
                    state_n = CAS_LOW;
                    count_n = 11'd1;
                end
                CAS_LOW: if (word) begin
                    state_n = CAS_HIGH;
                    count_n = 11'd1;
                end
                default: if (last_cp) begin
                    state_n = IDLE;
                    count_n = 11'd0;
                end
            endcase
        end
    end

    always @(posedge clk) begin
        if (rst) begin
            state <= IDLE;
            count <= 11'd0;
            open_row <= 11'd0;
            row_open <= 1'b0;
            addr_r <= {AB{1'b0}};
            resp_hold <= 16'd0;
        end else begin
            state <= state_n;
            count <= count_n;
            resp_hold <= resp_data;
            if (accept) begin
                addr_r <= addr;
                open_row <= row;
                row_open <= 1'b1;
            end
        end
    end
endmodule
