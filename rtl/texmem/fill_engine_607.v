// The block fetch of DRAM control unit 607 (Schilling & Knittel, Figure 6, section 5): the
// Verilog twin of FillEngine in hdl/units/src/texmem/control_607.rs (same ports, registers, states
// and reset). Reads a CCC block's two DRAM words (word 0, then word 1, through the word
// controller, in page mode when the row is open) into register 608, then waits while 610/612
// decode it until the line is written to cache 614. One fill at a time, never abandoned.
//
// `start` (with start_bx, start_by, start_prefetch) is taken only when idle; a word is asked
// for (word_req, word_addr: Moore outputs) while fetching and fewer than two were accepted
// (`word_ready`); the second response (`word_resp`) moves to DECODE; `line_done` back to
// IDLE. The block being filled (bx, by) and its prefetch flag are registered outputs: they
// address the line's write into cache 614. Block addresses (the layout of
// hdl/units/src/texmem/layout.rs): LAYOUT 0 row-major, block (bx, by) at BASE + 2 (by BW + bx);
// LAYOUT 1 tiled, TW x TH blocks to a DRAM page of PAGE_WORDS words (TW x TH = PAGE_WORDS / 2,
// TW = 2^ceil(lg / 2)), tiles row-major, blocks row-major inside a tile. States (state):
// 0 IDLE, 1 FETCH, 2 DECODE. Synchronous reset.
module fill_engine_607 #(
    parameter integer LAYOUT = 0,
    parameter integer BW = 16,
    parameter integer PAGE_WORDS = 512,
    parameter integer BASE = 0,
    parameter integer BB = 10,
    parameter integer AB = 18
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          start,
    input  wire [BB-1:0] start_bx,
    input  wire [BB-1:0] start_by,
    input  wire          start_prefetch,
    input  wire          word_ready,
    input  wire          word_resp,
    input  wire          line_done,
    output wire          word_req,
    output wire [AB-1:0] word_addr,
    output reg  [1:0]    state,
    output reg  [BB-1:0] bx,
    output reg  [BB-1:0] by,
    output reg           prefetch
);
    localparam [1:0] IDLE = 2'd0, FETCH = 2'd1, DECODE = 2'd2;
    // The tile: PAGE_WORDS / 2 blocks (at least one), TW = 2^ceil(lg / 2) wide.
    localparam integer BLOCKS = (PAGE_WORDS / 2 > 1) ? PAGE_WORDS / 2 : 1;
    localparam integer LG = $clog2(BLOCKS);
    localparam integer LGW = (LG + 1) / 2;
    localparam integer LGH = LG - LGW;
    localparam integer TILES_X = (BW + (1 << LGW) - 1) >> LGW;

    reg [1:0] words_issued;

    // Word 0 of block (bx, by).
    wire [AB-1:0] row_major = AB'(BASE) + (AB'(by) * AB'(BW) + AB'(bx) << 1);
    wire [AB-1:0] tx = AB'(bx) >> LGW, ty = AB'(by) >> LGH;
    wire [AB-1:0] inner = (AB'(by) & AB'((1 << LGH) - 1)) << LGW | (AB'(bx) & AB'((1 << LGW) - 1));
    wire [AB-1:0] tiled = AB'(BASE) + AB'(PAGE_WORDS) * (ty * AB'(TILES_X) + tx) + (inner << 1);
    wire [AB-1:0] block_addr = (LAYOUT == 1) ? tiled : row_major;

    assign word_req = (state == FETCH) && (words_issued < 2'd2);
    assign word_addr = word_req ? block_addr + AB'(words_issued) : {AB{1'b0}};

    always @(posedge clk) begin
        if (rst) begin
            state <= IDLE;
            bx <= {BB{1'b0}};
            by <= {BB{1'b0}};
            prefetch <= 1'b0;
            words_issued <= 2'd0;
        end else if (start && state == IDLE) begin
            state <= FETCH;
            bx <= start_bx;
            by <= start_by;
            prefetch <= start_prefetch;
            words_issued <= 2'd0;
        end else begin
            if (word_req && word_ready) words_issued <= words_issued + 2'd1;
            if (line_done) state <= IDLE;
            else if (word_resp && words_issued == 2'd2 && state == FETCH) state <= DECODE;
        end
    end
endmodule
