// The TEXRAM chip 802 of Schilling & Knittel (Figure 8), its rasterizer access path cycle by
// cycle: the Verilog twin of Texram802 in hdl/units/src/texram/texram_802.rs without the
// video port (same ports, registers, children and reset). Requests (DRF number, sQ12.8 u and
// v, sQ5.8 lambda, the illumination for eq. 5) are taken while `req_ready`: the address and
// control unit 812 computes the access into its registers; when the banks are free (or serve
// the last cycle of their slots) it moves into the bank stage 810, the page registers 824
// charge it one slot a round, two when a bank misses its open row; in the last cycle of its
// slots the eight texels (or the border colour) go through CLUT 814 (index maps) and the
// trilinear interpolator 818, and a request's last access through the output stage 820.
// A planar or literal colour request is four component accesses, one after the other.
//
// The DRFs (eight, the eighth 812's working descriptor) are loaded from DRF_FILE, 72 bits
// each as address_812.v describes (bit 69: set); the banks from BANK_FILE, CLUT 814 from
// CLUT_FILE: the host's loads, made before the run as the model's host makes them.
// SLOT_CYCLES clock cycles a slot. Counters since reset (40 bits): slots, faults (banks that
// missed), accesses, fault_slots; 812's conflicts. Synchronous reset.
module texram_802 #(
    parameter integer SLOT_CYCLES = 6,
    parameter integer DEPTH = 2048,
    parameter DRF_FILE = "drfs_802.hex",
    parameter BANK_FILE = "banks_810.hex",
    parameter CLUT_FILE = "clut_814.hex"
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        req_valid,
    input  wire [2:0]  req_drf,
    input  wire [20:0] req_u,
    input  wire [20:0] req_v,
    input  wire [13:0] req_lambda,
    input  wire [31:0] req_illum,
    output wire        req_ready,
    output wire        out_valid,
    output wire [7:0]  out_value,
    output wire [31:0] out_rgba,
    output wire [63:0] out_texels,
    output wire        out_fault,
    output wire [31:0] out_sum,
    output reg  [39:0] slots,
    output reg  [39:0] faults,
    output reg  [39:0] accesses,
    output reg  [39:0] fault_slots,
    output wire [39:0] conflicts
);
    reg [71:0] drfs [0:7];
    initial $readmemh(DRF_FILE, drfs);

    // 812.
    wire a_valid, a_index, a_last;
    wire [31:0] a_read, a_illum;
    wire [8*4*19-1:0] a_words;
    wire [39:0] a_src, a_weights;
    wire [7:0] a_border, a_colour;
    wire [1:0] a_part;
    wire [9:0] a_modulate;
    wire [2:0] held_drf;
    // 810.
    wire b_valid, b_fault, b_index, b_last;
    wire [7:0] b_left;
    wire [39:0] b_weights;
    wire [1:0] b_part;
    wire [31:0] b_illum;
    wire [9:0] b_modulate;
    wire [63:0] texels;
    // 824.
    wire [3:0] cost_slots, cost_fault_slots;
    wire [5:0] missed;

    // The bank stage: the access in 812 moves in when the banks are free or finishing.
    wire busy = b_valid;
    wire finishing = busy && b_left == 8'd1;
    wire waiting = a_valid;
    wire move_on = waiting && (!busy || finishing);
    // A colour request's next component follows its last into 812; a new request is taken
    // only when 812 holds nothing more of the last one.
    wire more = waiting && !a_last;
    assign req_ready = (!waiting || move_on) && !more;
    wire take = req_ready && req_valid;
    wire next_part = !take && move_on && more;
    wire [71:0] drf = drfs[take ? req_drf : held_drf];

    /* verilator lint_off PINCONNECTEMPTY */
    address_812 #(.DRF_BITS(72)) address_812 (
        .clk(clk), .rst(rst), .take(take), .next_part(next_part), .req_drf(req_drf),
        .req_u(req_u), .req_v(req_v), .req_lambda(req_lambda), .req_illum(req_illum), .drf(drf),
        .valid_en(take || move_on), .valid_d(take || more), .valid(a_valid), .read(a_read),
        .words(a_words), .src(a_src), .border(a_border), .weights(a_weights), .colour(a_colour),
        .index(a_index), .part(a_part), .last(a_last), .illum(a_illum), .modulate(a_modulate),
        .held_drf(held_drf), .conflicts(conflicts)
    );
    page_registers_824 page_registers_824 (
        .clk(clk), .rst(rst), .start(move_on), .read(a_read), .words(a_words),
        .slots(cost_slots), .fault_slots(cost_fault_slots), .missed(missed), .open_rows()
    );
    /* verilator lint_on PINCONNECTEMPTY */
    banks_810 #(.DEPTH(DEPTH), .BANK_FILE(BANK_FILE)) banks_810 (
        .clk(clk), .rst(rst), .take(move_on), .finish(finishing), .in_read(a_read),
        .in_words(a_words), .in_src(a_src), .in_border(a_border), .in_weights(a_weights),
        .in_colour(a_colour), .in_index(a_index), .in_part(a_part), .in_last(a_last),
        .in_illum(a_illum), .in_modulate(a_modulate),
        .in_left(8'(cost_slots * 4'(SLOT_CYCLES))), .in_fault(missed != 6'd0),
        .valid(b_valid), .left(b_left), .fault(b_fault), .weights(b_weights), .index(b_index),
        .part(b_part), .last(b_last), .illum(b_illum), .modulate(b_modulate), .texels(texels)
    );

    // 814, 818 and 820 in the access's last cycle.
    wire [255:0] entries;
    wire [31:0] sum, rgba;
    clut_814 #(.CLUT_FILE(CLUT_FILE)) clut_814 (.indices(texels), .entries(entries));
    /* verilator lint_off PINCONNECTEMPTY */
    trilinear_818 trilinear_818 (
        .clk(clk), .rst(rst), .finish(finishing), .texels(texels), .weights(b_weights),
        .index(b_index), .entries(entries), .part(b_part), .last(b_last), .sum(sum),
        .rgba(rgba), .acc_rgba()
    );
    /* verilator lint_on PINCONNECTEMPTY */
    output_820 output_820 (
        .clk(clk), .rst(rst), .finish(finishing && b_last), .modulate(b_modulate),
        .illum(b_illum), .rgba(rgba), .texels(texels), .fault(b_fault), .sum(sum),
        .out_valid(out_valid), .out_value(out_value), .out_rgba(out_rgba),
        .out_texels(out_texels), .out_fault(out_fault), .out_sum(out_sum)
    );

    always @(posedge clk) begin
        if (rst) begin
            slots <= 40'd0;
            faults <= 40'd0;
            accesses <= 40'd0;
            fault_slots <= 40'd0;
        end else if (move_on) begin
            slots <= slots + 40'(cost_slots);
            faults <= faults + 40'(missed);
            accesses <= accesses + 40'd1;
            fault_slots <= fault_slots + 40'(cost_fault_slots);
        end
    end
endmodule
