// Cache 614 of Schilling & Knittel's TEXRAM (Figures 6 and 7): the Verilog twin of
// TextureCache in hdl/units/src/texmem/cache_614.rs (same ports, registers and reset). Four entries
// A-D, each a decoded 4x4 block (a 64-bit line), direct mapped with Figure 7's interleave:
// block (bx, by) lives only in entry {by[0], bx[0]}, tagged (bx >> 1, by >> 1), TAG_BITS bits
// each (block coordinates have one more).
//
// Each cycle, in this order: `touch` clears the `prefetched` bits of the entries a request
// used; `invalidate` clears every entry's `valid` (the cache-off mode); `write` fills the
// entry of (write_bx, write_by) with write_data, valid, its tag and write_prefetched (a write
// wins over the others for its entry). Everything takes effect at the clock edge. The
// registered state is the output (the lines go to colour extract 618; valid and the tags to
// the unit's hit logic): valid and prefetched by entry (bit 0 = A), the tags and lines of
// A..D. Synchronous reset clears everything.
module cache_614 #(
    parameter integer TAG_BITS = 9
) (
    input  wire                clk,
    input  wire                rst,
    input  wire [3:0]          touch,
    input  wire                invalidate,
    input  wire                write,
    input  wire [TAG_BITS:0]   write_bx,
    input  wire [TAG_BITS:0]   write_by,
    input  wire [63:0]         write_data,
    input  wire                write_prefetched,
    output reg  [3:0]          valid,
    output reg  [3:0]          prefetched,
    output wire [TAG_BITS-1:0] tag_x_a,
    output wire [TAG_BITS-1:0] tag_x_b,
    output wire [TAG_BITS-1:0] tag_x_c,
    output wire [TAG_BITS-1:0] tag_x_d,
    output wire [TAG_BITS-1:0] tag_y_a,
    output wire [TAG_BITS-1:0] tag_y_b,
    output wire [TAG_BITS-1:0] tag_y_c,
    output wire [TAG_BITS-1:0] tag_y_d,
    output wire [63:0]         line_a,
    output wire [63:0]         line_b,
    output wire [63:0]         line_c,
    output wire [63:0]         line_d
);
    reg [TAG_BITS-1:0] tag_x [0:3];
    reg [TAG_BITS-1:0] tag_y [0:3];
    reg [63:0] data [0:3];
    wire [1:0] entry = {write_by[0], write_bx[0]};

    integer k;
    always @(posedge clk) begin
        if (rst) begin
            valid <= 4'b0000;
            prefetched <= 4'b0000;
            for (k = 0; k < 4; k = k + 1) begin
                tag_x[k] <= {TAG_BITS{1'b0}};
                tag_y[k] <= {TAG_BITS{1'b0}};
                data[k] <= 64'd0;
            end
        end else begin
            for (k = 0; k < 4; k = k + 1) begin
                if (write && entry == 2'(k)) begin
                    valid[k] <= 1'b1;
                    prefetched[k] <= write_prefetched;
                    tag_x[k] <= write_bx[TAG_BITS:1];
                    tag_y[k] <= write_by[TAG_BITS:1];
                    data[k] <= write_data;
                end else begin
                    if (invalidate) valid[k] <= 1'b0;
                    if (touch[k]) prefetched[k] <= 1'b0;
                end
            end
        end
    end
    assign {tag_x_d, tag_x_c, tag_x_b, tag_x_a} = {tag_x[3], tag_x[2], tag_x[1], tag_x[0]};
    assign {tag_y_d, tag_y_c, tag_y_b, tag_y_a} = {tag_y[3], tag_y[2], tag_y[1], tag_y[0]};
    assign {line_d, line_c, line_b, line_a} = {data[3], data[2], data[1], data[0]};
endmodule
