// Page registers 824 of Schilling & Knittel's TEXRAM chip (Figure 8) as the chip uses them:
// the Verilog twin of PageRegisters824 in hdl/units/src/pages/page_registers_824.rs (same
// registers and reset), with the chip's rounds. One open row per bank (`open` holds the row
// plus one, 0 while closed; a row is 512 words). An access reads in up to four rounds (bit
// 4 bank + round of `read`, its word in `words`); round 0 always counts, a later round only
// when it reads a bank. A round costs one slot, two when any bank it reads misses its open
// row (which it then holds, for the next round too). When `start` (the access moves into the
// banks) the rows it leaves open are registered. Outputs, for this cycle's access: `slots`,
// `fault_slots` (the slots misses added) and `missed` (banks that missed). Synchronous reset.
module page_registers_824 #(
    parameter integer ROW_BITS = 11
) (
    input  wire                    clk,
    input  wire                    rst,
    input  wire                    start,
    input  wire [31:0]             read,
    input  wire [8*4*19-1:0]       words,
    output reg  [3:0]              slots,
    output reg  [3:0]              fault_slots,
    output reg  [5:0]              missed,
    output wire [8*ROW_BITS-1:0]   open_rows
);
    reg [ROW_BITS-1:0] open [0:7];
    reg [ROW_BITS-1:0] rows [0:7];
    genvar g;
    generate
        for (g = 0; g < 8; g = g + 1) begin : g_open
            assign open_rows[ROW_BITS*g +: ROW_BITS] = open[g];
        end
    endgenerate

    integer r, b;
    reg [3:0] faults;
    reg [ROW_BITS-1:0] row;
    always @* begin
        for (b = 0; b < 8; b = b + 1) rows[b] = open[b];
        slots = 4'd0;
        fault_slots = 4'd0;
        missed = 6'd0;
        for (r = 0; r < 4; r = r + 1) begin
            faults = 4'd0;
            for (b = 0; b < 8; b = b + 1) begin
                row = ROW_BITS'(words[19*(4*b+r) + 9 +: 10]) + 1'b1;
                if (read[4*b+r] && rows[b] != row) begin
                    faults = faults + 4'd1;
                    rows[b] = row;
                end
            end
            if (r == 0 || read[r] || read[4+r] || read[8+r] || read[12+r] || read[16+r]
                    || read[20+r] || read[24+r] || read[28+r]) begin
                slots = slots + ((faults != 4'd0) ? 4'd2 : 4'd1);
                fault_slots = fault_slots + ((faults != 4'd0) ? 4'd1 : 4'd0);
                missed = missed + 6'(faults);
            end
        end
    end

    always @(posedge clk) begin
        if (rst) begin
            for (b = 0; b < 8; b = b + 1) open[b] <= {ROW_BITS{1'b0}};
        end else if (start) begin
            for (b = 0; b < 8; b = b + 1) open[b] <= rows[b];
        end
    end
endmodule
