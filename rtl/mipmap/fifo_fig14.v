// A synchronous FIFO of DEPTH entries of W bits that reports overflow and underflow instead
// of wrapping: FIFOs 1408 and 1412 of the mipmap generator (Schilling & Knittel, Figure 14),
// the Verilog twin of Fifo in hdl/units/src/mipmap/fifo.rs.
//
// The clock edge applies clear (a parallel transfer of the FIFO's line), then pop, then push;
// a pop from an empty FIFO or a push into a full one is dropped. `error` reports this cycle's
// inputs against the stored state: 0 none, 1 overflow, 2 underflow (checked in that order of
// operations). `occupancy` and `front` (the oldest entry, 0 when empty) are the stored state.
// Synchronous reset empties it.
module fifo_fig14 #(
    parameter integer DEPTH = 4,
    parameter integer W = 9
) (
    input  wire                       clk,
    input  wire                       rst,
    input  wire                       push,
    input  wire [W-1:0]               push_data,
    input  wire                       pop,
    input  wire                       clear,
    output wire [$clog2(DEPTH+1)-1:0] occupancy,
    output wire [1:0]                 error,
    output wire [W-1:0]               front,
    output wire                       full
);
    localparam integer OB = $clog2(DEPTH + 1);
    localparam integer HB = (DEPTH > 1) ? $clog2(DEPTH) : 1;
    reg [W-1:0] mem [0:DEPTH-1];
    reg [HB-1:0] head;
    reg [OB-1:0] len;

    assign occupancy = len;
    assign full = (len == OB'(DEPTH));
    assign front = (len != 0) ? mem[head] : {W{1'b0}};

    wire [OB-1:0] len_c = clear ? {OB{1'b0}} : len;
    wire underflow = pop && (len_c == 0);
    wire overflow = !underflow && push && (len_c - OB'(pop) == OB'(DEPTH));
    assign error = underflow ? 2'd2 : overflow ? 2'd1 : 2'd0;

    // After clear and pop: the head and the count the push sees.
    wire do_pop = pop && (len_c != 0);
    wire [HB-1:0] head_c = clear ? {HB{1'b0}} : head;
    wire [HB-1:0] head_p = do_pop ? ((head_c == HB'(DEPTH - 1)) ? {HB{1'b0}} : head_c + 1'b1) : head_c;
    wire [OB-1:0] len_p = len_c - OB'(do_pop);
    wire do_push = push && (len_p < OB'(DEPTH));
    // The tail, (head + len) mod DEPTH, in one more bit.
    wire [HB:0] tail_w = {1'b0, head_p} + (HB + 1)'(len_p);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [HB:0] tail = (tail_w >= (HB + 1)'(DEPTH)) ? tail_w - (HB + 1)'(DEPTH) : tail_w;
    /* verilator lint_on UNUSEDSIGNAL */

    always @(posedge clk) begin
        if (rst) begin
            head <= {HB{1'b0}};
            len <= {OB{1'b0}};
        end else begin
            head <= head_p;
            len <= len_p + OB'(do_push);
            if (do_push) mem[tail[HB-1:0]] <= push_data;
        end
    end
endmodule
