// Texture mapping unit 602 of Schilling & Knittel's TEXRAM (Figure 6), end to end: the
// Verilog twin of TextureUnit in hdl/units/src/texmem/texture_unit_602.rs (same ports,
// registers, children and reset). Requests from the rasterizer; block fetch and lookahead
// queue of control unit 607 with its word controller driving DRAM 604's pins; CCC decode
// 608/610/612; cache 614; colour extract 618; bilinear interpolator 622. One 24-bit RGB
// result per request, in request order.
//
// Requests: in_u, in_v unsigned uQ12.F (the integer part the texel x0 < W, y0 < H; the
// fraction the weight of x0 + 1), in_newline the scanline-change flag, taken when in_ready.
// Stage 0 (req_* registers) looks the request's 1, 2 or 4 blocks up in cache 614 (x1 =
// min(x0 + 1, W - 1), likewise y1; block (bx, by) in entry {by[0], bx[0]}, hit when valid and
// tagged (bx >> 1, by >> 1)): need_mask and hit_mask by entry. All present: the footprint
// goes to 618 and the next request is taken. The first missing block (in the order (x0, y0),
// (x1, y0), (x0, y1), (x1, y1)) starts a demand fill when the engine is idle, which empties
// the lookahead queue (as a newline request's first lookup does); otherwise an idle engine
// takes the queue's first candidate, dropped when the cache already holds it. A completed
// request offers its neighbours to the queue (CACHE = 1 and MODE != 0) or invalidates the
// whole cache (CACHE = 0). 618 and 622 register one cycle each: a hit is answered two cycles
// after its lookup. Parameters: the texture (W x H texels, multiples of 4; F fraction bits;
// LAYOUT and BASE in DRAM), CACHE, MODE (0 off, 1 quadrant, 2 direction), the DRAM's
// geometry and timing, CLUT_FILE (CLUT 612's contents). Synchronous reset.
module texture_unit_602 #(
    parameter integer W = 64,
    parameter integer H = 64,
    parameter integer F = 4,
    parameter integer LAYOUT = 0,
    parameter integer BASE = 0,
    parameter integer CACHE = 1,
    parameter integer MODE = 1,
    parameter integer ROWS = 512,
    parameter integer COLS = 512,
    parameter integer T_RP = 3,
    parameter integer T_RCD = 3,
    parameter integer T_CAS = 3,
    parameter integer T_CP = 3,
    parameter CLUT_FILE = "clut_612.hex"
) (
    input  wire          clk,
    input  wire          rst,
    input  wire          in_valid,
    input  wire [11+F:0] in_u,
    input  wire [11+F:0] in_v,
    input  wire          in_newline,
    output wire          in_ready,
    output wire          out_valid,
    output wire [23:0]   out_rgb,
    output wire [3:0]    need_mask,
    output wire [3:0]    hit_mask,
    // DRAM 604's pins.
    output wire          ras_n,
    output wire          cas_n,
    output wire          we_n,
    output wire          oe_n,
    output wire [10:0]   dram_addr,
    input  wire [15:0]   dq,
    input  wire          dq_valid
);
    localparam integer UW = 12 + F;
    localparam integer BB = 10;
    localparam integer AB = $clog2(ROWS * COLS);
    localparam integer LOOK = (CACHE != 0) ? MODE : 0;

    // Stage 0.
    reg req_valid, req_newline, req_seen;
    reg [UW-1:0] req_u, req_v;

    // The children's outputs.
    wire [1:0] fill_state;
    wire [BB-1:0] fill_bx, fill_by;
    wire fill_prefetch, word_req;
    wire [AB-1:0] word_addr;
    wire take;
    wire [BB-1:0] take_bx, take_by;
    wire mem_ready, resp_valid;
    wire [15:0] resp_data;
    wire line_valid;
    wire [63:0] line;
    wire [3:0] valid;
    // Seen in the waveform only.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [2:0] queue_mask;
    wire [1:0] decode_state;
    wire [3:0] prefetched;
    /* verilator lint_on UNUSEDSIGNAL */
    wire [BB-2:0] tag_x [0:3];
    wire [BB-2:0] tag_y [0:3];
    wire [63:0] line_a, line_b, line_c, line_d;
    wire ex_valid;
    wire [23:0] c00, c10, c01, c11;
    wire [F-1:0] ex_fu, ex_fv;


    // The footprint: its texels, its 1, 2 or 4 blocks, which it needs and which hit (block
    // (bx, by) is held when entry {by[0], bx[0]} is valid and tagged (bx >> 1, by >> 1)).
    wire [11:0] x0 = req_u[UW-1:F], y0 = req_v[UW-1:F];
    wire [11:0] x1 = ({1'b0, x0} + 13'd1 > 13'(W - 1)) ? 12'(W - 1) : x0 + 12'd1;
    wire [11:0] y1 = ({1'b0, y0} + 13'd1 > 13'(H - 1)) ? 12'(H - 1) : y0 + 12'd1;
    wire [BB-1:0] bxs [0:3];
    wire [BB-1:0] bys [0:3];
    assign bxs[0] = x0[11:2];
    assign bxs[1] = x1[11:2];
    assign bxs[2] = x0[11:2];
    assign bxs[3] = x1[11:2];
    assign bys[0] = y0[11:2];
    assign bys[1] = y0[11:2];
    assign bys[2] = y1[11:2];
    assign bys[3] = y1[11:2];
    wire two_x = x0[11:2] != x1[11:2], two_y = y0[11:2] != y1[11:2];
    wire [3:0] used = {two_x && two_y, two_y, two_x, 1'b1};
    wire [3:0] present;
    wire [3:0] entry_bit [0:3];
    genvar k;
    generate
        for (k = 0; k < 4; k = k + 1) begin : g_block
            wire [1:0] e = {bys[k][0], bxs[k][0]};
            assign present[k] = valid[e] && tag_x[e] == bxs[k][BB-1:1]
                && tag_y[e] == bys[k][BB-1:1];
            assign entry_bit[k] = used[k] ? 4'b0001 << {bys[k][0], bxs[k][0]} : 4'b0000;
        end
    endgenerate
    wire busy = req_valid;
    wire [3:0] missing = busy ? used & ~present : 4'b0000;
    wire [1:0] miss_k = missing[0] ? 2'd0 : missing[1] ? 2'd1 : missing[2] ? 2'd2 : 2'd3;
    wire missing_any = missing != 4'b0000;
    wire done = busy && !missing_any;
    wire first = !req_seen;
    wire newline_now = busy && first && req_newline;
    wire [3:0] need = entry_bit[0] | entry_bit[1] | entry_bit[2] | entry_bit[3];
    wire [3:0] hit = (present[0] ? entry_bit[0] : 4'b0000) | (present[1] ? entry_bit[1] : 4'b0000)
        | (present[2] ? entry_bit[2] : 4'b0000) | (present[3] ? entry_bit[3] : 4'b0000);
    assign need_mask = busy ? need : 4'b0000;
    assign hit_mask = busy ? hit : 4'b0000;

    // Starting a fill: a demand miss first, else the lookahead queue's candidate.
    wire free = (fill_state == 2'd0);
    wire demand = missing_any && free;
    wire [1:0] take_e = {take_by[0], take_bx[0]};
    wire take_held = valid[take_e] && tag_x[take_e] == take_bx[BB-1:1]
        && tag_y[take_e] == take_by[BB-1:1];
    wire preload = !demand && take && !take_held;
    wire start = demand || preload;
    wire [BB-1:0] start_bx = demand ? bxs[miss_k] : preload ? take_bx : {BB{1'b0}};
    wire [BB-1:0] start_by = demand ? bys[miss_k] : preload ? take_by : {BB{1'b0}};

    // The rasterizer handshake.
    assign in_ready = !busy || done;
    wire accept = in_ready && in_valid;

    always @(posedge clk) begin
        if (rst) begin
            req_valid <= 1'b0;
            req_u <= {UW{1'b0}};
            req_v <= {UW{1'b0}};
            req_newline <= 1'b0;
            req_seen <= 1'b0;
        end else begin
            if (busy && first) req_seen <= 1'b1;
            if (accept) begin
                req_valid <= 1'b1;
                req_u <= in_u;
                req_v <= in_v;
                req_newline <= in_newline;
                req_seen <= 1'b0;
            end else if (done) begin
                req_valid <= 1'b0;
            end
        end
    end

    fill_engine_607 #(
        .LAYOUT(LAYOUT), .BW(W / 4), .PAGE_WORDS(COLS), .BASE(BASE), .BB(BB), .AB(AB)
    ) fill (
        .clk(clk), .rst(rst), .start(start), .start_bx(start_bx), .start_by(start_by),
        .start_prefetch(preload), .word_ready(mem_ready), .word_resp(resp_valid),
        .line_done(line_valid), .word_req(word_req), .word_addr(word_addr), .state(fill_state),
        .bx(fill_bx), .by(fill_by), .prefetch(fill_prefetch)
    );
    lookahead_queue_607 #(.MODE(LOOK), .BW(W / 4), .BH(H / 4), .F(F), .BB(BB)) queue (
        .clk(clk), .rst(rst), .complete(done && LOOK != 0), .u(req_u), .v(req_v),
        .newline(req_newline), .flush(demand || newline_now), .engine_free(free),
        .stage0_missing(missing_any), .take(take), .take_bx(take_bx), .take_by(take_by),
        .mask(queue_mask)
    );
    control_607 #(
        .ROWS(ROWS), .COLS(COLS), .T_RP(T_RP), .T_RCD(T_RCD), .T_CAS(T_CAS), .T_CP(T_CP)
    ) mem (
        .clk(clk), .rst(rst), .req_valid(word_req), .req_addr(word_addr), .ready(mem_ready),
        .resp_valid(resp_valid), .resp_data(resp_data), .ras_n(ras_n), .cas_n(cas_n),
        .we_n(we_n), .oe_n(oe_n), .dram_addr(dram_addr), .dq(dq), .dq_valid(dq_valid)
    );
    ccc_decode_608 #(.CLUT_FILE(CLUT_FILE)) decode (
        .clk(clk), .rst(rst), .word_valid(resp_valid), .word(resp_data),
        .line_valid(line_valid), .line(line), .state(decode_state)
    );
    cache_614 #(.TAG_BITS(BB - 1)) cache (
        .clk(clk), .rst(rst), .touch(hit_mask), .invalidate(done && CACHE == 0),
        .write(line_valid), .write_bx(fill_bx), .write_by(fill_by), .write_data(line),
        .write_prefetched(fill_prefetch), .valid(valid), .prefetched(prefetched),
        .tag_x_a(tag_x[0]), .tag_x_b(tag_x[1]), .tag_x_c(tag_x[2]), .tag_x_d(tag_x[3]),
        .tag_y_a(tag_y[0]), .tag_y_b(tag_y[1]), .tag_y_c(tag_y[2]), .tag_y_d(tag_y[3]),
        .line_a(line_a), .line_b(line_b), .line_c(line_c), .line_d(line_d)
    );
    extract_618 #(.COORD_BITS(12), .F(F)) extract (
        .clk(clk), .rst(rst), .in_valid(done), .x0(x0), .x1(x1), .y0(y0), .y1(y1),
        .in_fu(req_u[F-1:0]), .in_fv(req_v[F-1:0]), .line_a(line_a), .line_b(line_b),
        .line_c(line_c), .line_d(line_d), .valid(ex_valid), .c00(c00), .c10(c10), .c01(c01),
        .c11(c11), .fu(ex_fu), .fv(ex_fv)
    );
    /* verilator lint_off PINCONNECTEMPTY */
    bilinear_622 #(.F(F)) bilinear (
        .clk(clk), .rst(rst), .in_valid(ex_valid), .c00(c00), .c10(c10), .c01(c01), .c11(c11),
        .fu(ex_fu), .fv(ex_fv), .valid(out_valid), .rgb(out_rgb), .sum_r(), .sum_g(), .sum_b()
    );
    /* verilator lint_on PINCONNECTEMPTY */
endmodule
