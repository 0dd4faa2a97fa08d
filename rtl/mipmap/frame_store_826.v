// The frame store's level 0 and shift register 826 as mipmap generator 816 uses them
// (Schilling & Knittel, section 12): a behavioural model for testbenches (the TEXRAM's banks
// are the chip's memory, not the unit's), the counterpart of the buffers and `sr` of
// hdl/units/src/mipmap/mipmap_gen_816.rs.
//
// At each edge: the video texel (store_*) is written, then, on sr_load, line sr_row is copied
// into the shift register (with the texel written at the same edge). sr_texel is the shift
// register's texel at the arrival column sr_x (a serial shift register clocked by the valid
// texels gives the same texel).
module frame_store_826 #(
    parameter integer WIDTH = 16,
    parameter integer HEIGHT = 16
) (
    input  wire        clk,
    input  wire        store_valid,
    input  wire [10:0] store_x,
    input  wire [10:0] store_y,
    input  wire [7:0]  store_texel,
    input  wire        sr_load,
    input  wire [10:0] sr_row,
    input  wire [10:0] sr_x,
    output wire [7:0]  sr_texel
);
    // Behavioural: indices in integer arithmetic, widths left to the simulator.
    /* verilator lint_off WIDTH */
    /* verilator lint_off UNUSEDSIGNAL */
    reg [7:0] mem [0:WIDTH*HEIGHT-1];
    reg [8*WIDTH-1:0] sr, sr_next;
    integer i;
    initial begin
        for (i = 0; i < WIDTH * HEIGHT; i = i + 1) mem[i] = 8'd0;
        sr = {(8 * WIDTH){1'b0}};
    end
    assign sr_texel = sr[8 * sr_x +: 8];
    /* verilator lint_off BLKSEQ */
    always @(posedge clk) begin
        if (store_valid) mem[store_y * WIDTH + store_x] <= store_texel;
        if (sr_load) begin
            for (i = 0; i < WIDTH; i = i + 1)
                sr_next[8 * i +: 8] = (store_valid && store_y == sr_row && store_x == i)
                                    ? store_texel : mem[sr_row * WIDTH + i];
            sr <= sr_next;
        end
    end
    /* verilator lint_on BLKSEQ */
    /* verilator lint_on UNUSEDSIGNAL */
    /* verilator lint_on WIDTH */
endmodule
