// One level of Figure 14 (Schilling & Knittel, TEXRAM, section 12): level k of the mipmap from
// the texel stream of level k-1 (WP x HP texels), the Verilog twin of Level in
// hdl/units/src/mipmap/level_fig14.rs (same ports, registers, FIFOs and reset).
//
// Progressive (Figure 14a/b): adder 1402 adds horizontal neighbours, the even column held in
// register 1404; on even lines the sums go into FIFO 1408 (a line buffer), on odd lines adder
// 1410 adds them to its oldest entry and the sum of four is divided by four. A side of 1 pairs
// along the other side only (divided by two). INTERLACED (level 1 of interlaced video): adder
// 1402 adds the texel to the partner line's texel from shift register 826 (sr_texel), FIFO
// 1408 holds the even column's sum, adder 1410 adds the odd one.
// Division: ROUND 1 rounds half up ((sum + n/2) / n), 0 truncates. Every result goes out
// (out_valid, out_texel: registered, one cycle later) and into FIFO 1412, whose full line goes
// to the frame store at the next edge (line_write: the FIFO is cleared).
// Formats: texels u8, adder 1402 u9, adder 1410 u10, FIFO 1408 u9, FIFO 1412 u8. `error`:
// sticky, the first FIFO error (1 overflow, 2 underflow; the larger code when both).
module level_fig14 #(
    parameter integer WP = 8,
    parameter integer HP = 8,
    parameter integer ROUND = 1,
    parameter integer INTERLACED = 0
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       in_valid,
    input  wire [7:0] in_texel,
    input  wire [7:0] sr826,
    output reg        out_valid,
    output reg  [7:0] out_texel,
    output wire       line_write,
    output reg  [1:0] error
);
    localparam integer WK = (WP / 2 > 1) ? WP / 2 : 1;
    localparam integer PAIR_X = (WP > 1) ? 1 : 0;
    localparam integer PAIR_Y = (HP > 1) ? 1 : 0;
    localparam [8:0] HALF2 = (ROUND != 0) ? 9'd1 : 9'd0;
    localparam [9:0] HALF4 = (ROUND != 0) ? 10'd2 : 10'd0;

    reg [10:0] x, y;
    reg [7:0] r1404;
    wire [8:0] front_1408;
    wire full_1412;
    wire [1:0] err_1408, err_1412;

    // Adders 1402 and 1410, and the divisions.
    wire x_odd = x[0];
    wire y_odd = y[0];
    wire [8:0] t9 = {1'b0, in_texel};
    wire [8:0] sum1402 = (INTERLACED != 0) ? t9 + {1'b0, sr826}
                       : (PAIR_X != 0) ? {1'b0, r1404} + t9
                       : front_1408 + t9;
    wire [9:0] sum1410 = {1'b0, front_1408} + {1'b0, sum1402};
    wire [7:0] half_of_sum = 8'((sum1402 + HALF2) >> 1);
    wire [7:0] quarter_of_sum = 8'((sum1410 + HALF4) >> 2);

    // What this texel does: the result (if any) and the FIFO 1408 operations.
    reg produce, push_1408, pop_1408;
    reg [7:0] result;
    reg [8:0] push_data;
    always @* begin
        produce = 1'b0;
        push_1408 = 1'b0;
        pop_1408 = 1'b0;
        result = quarter_of_sum;
        push_data = sum1402;
        if (INTERLACED != 0) begin
            if (PAIR_X == 0) begin
                produce = 1'b1;
                result = half_of_sum;
            end else if (!x_odd) begin
                push_1408 = 1'b1;
            end else begin
                produce = 1'b1;
                pop_1408 = 1'b1;
            end
        end else if (PAIR_X != 0) begin
            if (x_odd) begin
                if (PAIR_Y == 0) begin
                    produce = 1'b1;
                    result = half_of_sum;
                end else if (!y_odd) begin
                    push_1408 = 1'b1;
                end else begin
                    produce = 1'b1;
                    pop_1408 = 1'b1;
                end
            end
        end else if (!y_odd) begin
            push_1408 = 1'b1;
            push_data = t9;
        end else begin
            produce = 1'b1;
            pop_1408 = 1'b1;
            result = half_of_sum;
        end
    end
    wire go = in_valid;
    // A full FIFO 1412 holds a line: it goes to the frame store at this edge.
    assign line_write = full_1412;

    /* verilator lint_off PINCONNECTEMPTY */
    fifo_fig14 #(.DEPTH(WK), .W(9)) fifo_1408 (
        .clk(clk), .rst(rst), .push(go && push_1408), .push_data(push_data),
        .pop(go && pop_1408), .clear(1'b0), .occupancy(), .error(err_1408), .front(front_1408),
        .full()
    );
    fifo_fig14 #(.DEPTH(WK), .W(8)) fifo_1412 (
        .clk(clk), .rst(rst), .push(go && produce), .push_data(result), .pop(1'b0),
        .clear(full_1412), .occupancy(), .error(err_1412), .front(), .full(full_1412)
    );
    /* verilator lint_on PINCONNECTEMPTY */

    wire [10:0] nx = (x + 11'd1 == 11'(WP)) ? 11'd0 : x + 11'd1;
    wire [10:0] ny = (y + 11'd1 == 11'(HP)) ? 11'd0 : y + 11'd1;
    wire [1:0] fifo_err = (err_1408 > err_1412) ? err_1408 : err_1412;

    always @(posedge clk) begin
        if (rst) begin
            x <= 11'd0;
            y <= 11'd0;
            r1404 <= 8'd0;
            out_valid <= 1'b0;
            out_texel <= 8'd0;
            error <= 2'd0;
        end else begin
            out_valid <= go && produce;
            if (go) begin
                x <= nx;
                if (nx == 0 && INTERLACED == 0) y <= ny;
                if (INTERLACED == 0 && PAIR_X != 0 && !x_odd) r1404 <= in_texel;
                if (produce) out_texel <= result;
            end
            if (fifo_err != 0 && error == 0) error <= fifo_err;
        end
    end
endmodule
