// The lookahead queue of DRAM control unit 607 (Schilling & Knittel, Figure 6, section 5):
// the Verilog twin of LookaheadQueue in hdl/units/src/texmem/control_607.rs (same ports, widths,
// registers and reset). Up to three neighbouring blocks to preload into cache 614, chosen when
// a request completes, offered to the fill engine one at a time.
//
// MODE 1 (quadrant, the document's scheme): for the point (x, y) = (u, v) >> F in block
// (bx, by) = (x, y) >> 2, dx = +1 if bit 1 of x is set else -1, likewise dy. MODE 2
// (direction): dx, dy are the signs of the motion from the previous completed point of the
// scanline (prev_u, prev_v, fractions included). MODE 0: none. The neighbours are (bx + dx, by),
// (bx, by + dy) and (bx + dx, by + dy), those outside the BW x BH blocks or with a zero step
// left out, packed into the slots in that order; one that would go into the cache entry
// (Figure 7: {by[0], bx[0]}) of another block of the request's 2x2 footprint (clamped at the
// texture's edge) is dropped. Nothing for a `newline` request.
//
// Each cycle: on `complete` the candidates replace the slots; `flush` empties the queue;
// otherwise, when `engine_free` and not `stage0_missing`, the lowest live slot is taken
// (take, take_bx, take_by) and cleared. mask: the live slots (registered). u, v: uQ12.F;
// blocks: BB bits. Synchronous reset.
module lookahead_queue_607 #(
    parameter integer MODE = 1,
    parameter integer BW = 16,
    parameter integer BH = 16,
    parameter integer F = 4,
    parameter integer BB = 10
) (
    input  wire            clk,
    input  wire            rst,
    input  wire            complete,
    input  wire [11+F:0]   u,
    input  wire [11+F:0]   v,
    input  wire            newline,
    input  wire            flush,
    input  wire            engine_free,
    input  wire            stage0_missing,
    output wire            take,
    output wire [BB-1:0]   take_bx,
    output wire [BB-1:0]   take_by,
    output reg  [2:0]      mask
);
    localparam integer UW = 12 + F;

    reg [BB-1:0] slot_bx [0:2];
    reg [BB-1:0] slot_by [0:2];
    reg prev_valid;
    reg [UW-1:0] prev_u, prev_v;

    // The point, its footprint's far corner (clamped) and their blocks.
    wire [12:0] x0 = {1'b0, u[UW-1:F]};
    wire [12:0] y0 = {1'b0, v[UW-1:F]};
    wire [12:0] x_max = 13'(4 * BW - 1);
    wire [12:0] y_max = 13'(4 * BH - 1);
    wire [12:0] x1 = (x0 + 13'd1 > x_max) ? x_max : x0 + 13'd1;
    wire [12:0] y1 = (y0 + 13'd1 > y_max) ? y_max : y0 + 13'd1;
    wire [BB-1:0] bx = BB'(x0 >> 2), by = BB'(y0 >> 2);
    wire [BB-1:0] fx1 = BB'(x1 >> 2), fy1 = BB'(y1 >> 2);

    // Direction of the neighbours: -1, 0, +1 as (step, up).
    wire quadrant = (MODE == 1);
    wire direction = (MODE == 2) && prev_valid;
    wire x_step = quadrant || (direction && u != prev_u);
    wire x_up = quadrant ? x0[1] : (u > prev_u);
    wire y_step = quadrant || (direction && v != prev_v);
    wire y_up = quadrant ? y0[1] : (v > prev_v);
    wire nx_ok = !newline && x_step && (x_up ? ({1'b0, bx} + 1 < (BB + 1)'(BW)) : (bx != 0));
    wire ny_ok = !newline && y_step && (y_up ? ({1'b0, by} + 1 < (BB + 1)'(BH)) : (by != 0));
    wire [BB-1:0] nx = x_up ? bx + 1'b1 : bx - 1'b1;
    wire [BB-1:0] ny = y_up ? by + 1'b1 : by - 1'b1;

    // The neighbours packed in order, and whether each may be preloaded.
    wire [BB-1:0] c_bx [0:2];
    wire [BB-1:0] c_by [0:2];
    wire [2:0] present = {nx_ok && ny_ok, nx_ok && ny_ok, nx_ok || ny_ok};
    assign c_bx[0] = nx_ok ? nx : bx;
    assign c_by[0] = nx_ok ? by : ny;
    assign c_bx[1] = bx;
    assign c_by[1] = ny;
    assign c_bx[2] = nx;
    assign c_by[2] = ny;
    wire [2:0] live;
    genvar k;
    generate
        for (k = 0; k < 3; k = k + 1) begin : g_slot
            wire evicts_k;
            lookahead_queue_607_evicts #(.BB(BB)) u_evicts (
                .bx(c_bx[k]), .by(c_by[k]), .x0(bx), .y0(by), .x1(fx1), .y1(fy1),
                .evicts(evicts_k)
            );
            assign live[k] = present[k] && !evicts_k;
        end
    endgenerate

    // This cycle's queue: the new candidates, or the registered slots.
    wire [2:0] m = complete ? live : mask;
    wire [BB-1:0] q_bx [0:2];
    wire [BB-1:0] q_by [0:2];
    generate
        for (k = 0; k < 3; k = k + 1) begin : g_queue
            assign q_bx[k] = complete ? (live[k] ? c_bx[k] : {BB{1'b0}}) : slot_bx[k];
            assign q_by[k] = complete ? (live[k] ? c_by[k] : {BB{1'b0}}) : slot_by[k];
        end
    endgenerate
    assign take = !flush && engine_free && (m != 3'b000) && !stage0_missing;
    wire [1:0] first = m[0] ? 2'd0 : m[1] ? 2'd1 : 2'd2;
    assign take_bx = take ? q_bx[first] : {BB{1'b0}};
    assign take_by = take ? q_by[first] : {BB{1'b0}};
    wire [2:0] m_next = flush ? 3'b000 : take ? (m & ~(3'b001 << first)) : m;

    integer n;
    always @(posedge clk) begin
        if (rst) begin
            mask <= 3'b000;
            prev_valid <= 1'b0;
            prev_u <= {UW{1'b0}};
            prev_v <= {UW{1'b0}};
            for (n = 0; n < 3; n = n + 1) begin
                slot_bx[n] <= {BB{1'b0}};
                slot_by[n] <= {BB{1'b0}};
            end
        end else begin
            mask <= m_next;
            if (complete) begin
                for (n = 0; n < 3; n = n + 1) begin
                    slot_bx[n] <= q_bx[n];
                    slot_by[n] <= q_by[n];
                end
                if (MODE == 2) begin
                    prev_valid <= 1'b1;
                    prev_u <= u;
                    prev_v <= v;
                end
            end
        end
    end
endmodule

// Whether preloading block (bx, by) would evict another block of the footprint whose blocks
// are (x0, y0), (x1, y0), (x0, y1), (x1, y1): one that differs from it but has its cache
// entry, {by[0], bx[0]} (Figure 7).
/* verilator lint_off DECLFILENAME */
module lookahead_queue_607_evicts #(
    parameter integer BB = 10
) (
    input  wire [BB-1:0] bx,
    input  wire [BB-1:0] by,
    input  wire [BB-1:0] x0,
    input  wire [BB-1:0] y0,
    input  wire [BB-1:0] x1,
    input  wire [BB-1:0] y1,
    output wire          evicts
);
    function automatic clash(input [BB-1:0] fx, input [BB-1:0] fy, input [BB-1:0] ax,
                             input [BB-1:0] ay);
        clash = !(fx == ax && fy == ay) && fx[0] == ax[0] && fy[0] == ay[0];
    endfunction
    assign evicts = clash(x0, y0, bx, by) || clash(x1, y0, bx, by) || clash(x0, y1, bx, by)
                 || clash(x1, y1, bx, by);
endmodule
/* verilator lint_on DECLFILENAME */
