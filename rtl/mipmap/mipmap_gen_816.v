// Real-time mipmap generation for (interlaced) video, unit 816 of Schilling & Knittel's
// TEXRAM (section 12, Figures 14a-b): the Verilog twin of MipmapGen in
// hdl/units/src/mipmap/mipmap_gen_816.rs (same ports, counters, levels, error codes and reset).
//
// The video port delivers one texel per valid cycle (`sof` with a frame's first texel),
// WIDTH x HEIGHT (powers of two up to 1024), SCAN 0 progressive, 1 interlaced with the field
// of even lines first, 2 with the odd field first. Level 1 reads the video (interlaced: only
// in the second field, with the partner line of the first field from shift register 826,
// which the frame store loads at the end of each line); level k reads level k-1's stream
// (level_fig14.v). Every level-0 texel goes to the frame store (store_*, at the edge).
//
// error / err_code: sticky, the first error: a level's FIFO error (1 overflow, 2 underflow)
// over a video sync error (3: sof high other than with a frame's first texel, or low with it).
// frame_done: a frame's mipmap was completed at the last edge (its last level's line written;
// a 1x1 frame by its texel). level_valid / level_texel: each level's texel stream (level k in
// bit k-1 and byte k-1, up to 10 levels).
module mipmap_gen_816 #(
    parameter integer WIDTH = 16,
    parameter integer HEIGHT = 16,
    parameter integer SCAN = 0,
    parameter integer ROUND = 1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        valid,
    input  wire [7:0]  texel,
    input  wire        sof,
    output reg         error,
    output reg  [1:0]  err_code,
    output reg         frame_done,
    // To the frame store (level 0) and from its shift register 826.
    output wire        store_valid,
    output wire [10:0] store_x,
    output wire [10:0] store_y,
    output wire [7:0]  store_texel,
    output wire        sr_load,
    output wire [10:0] sr_row,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [7:0]  sr_texel, // unused by a 1x1 frame
    /* verilator lint_on UNUSEDSIGNAL */
    // The levels' texel streams.
    output wire [9:0]  level_valid,
    output wire [79:0] level_texel
);
    localparam integer INTERLACED = (SCAN != 0) ? 1 : 0;
    localparam integer LPF = (INTERLACED != 0) ? HEIGHT / 2 : HEIGHT;
    localparam integer LW = $clog2(WIDTH);
    localparam integer LH = $clog2(HEIGHT);
    // Levels above 0: down to 1x1.
    localparam integer NL = (LW > LH) ? LW : LH;

    reg [10:0] x0, line0;
    reg field;

    // The frame line arriving as line n of field f.
    function automatic [10:0] frame_line(input f, input [10:0] n);
        frame_line = (SCAN == 0) ? n : (SCAN == 1) ? {n[9:0], f} : {n[9:0], !f};
    endfunction

    // Next arrival position; at a line end in the second field's order, the partner line.
    wire line_end = (x0 + 11'd1 == 11'(WIDTH));
    wire field_end = line_end && (line0 + 11'd1 == 11'(LPF));
    wire [10:0] nx = line_end ? 11'd0 : x0 + 11'd1;
    wire [10:0] nn = field_end ? 11'd0 : line_end ? line0 + 11'd1 : line0;
    wire nf = field_end ? ((INTERLACED != 0) ? !field : 1'b0) : field;
    wire first = (x0 == 0) && (line0 == 0) && !field;
    wire frame_end = field_end && (INTERLACED == 0 || field);

    assign store_valid = valid;
    assign store_x = x0;
    assign store_y = frame_line(field, line0);
    assign store_texel = texel;
    assign sr_load = valid && line_end && (INTERLACED != 0) && nf;
    assign sr_row = frame_line(nf, nn) ^ 11'd1;

    // The levels.
    wire [9:0] lv;
    wire [79:0] lt;
    wire [9:0] drain;
    wire [19:0] lerr;
    genvar k;
    generate
        for (k = 1; k <= NL; k = k + 1) begin : levels
            localparam integer WP = (WIDTH >> (k - 1) > 0) ? WIDTH >> (k - 1) : 1;
            localparam integer HP = (HEIGHT >> (k - 1) > 0) ? HEIGHT >> (k - 1) : 1;
            wire in_v = (k == 1) ? valid && (INTERLACED == 0 || field) : lv[(k == 1) ? 0 : k - 2];
            wire [7:0] in_t = (k == 1) ? texel : lt[8 * ((k == 1) ? 0 : k - 2) +: 8];
            level_fig14 #(
                .WP(WP), .HP(HP), .ROUND(ROUND), .INTERLACED(k == 1 ? INTERLACED : 0)
            ) level (
                .clk(clk), .rst(rst), .in_valid(in_v), .in_texel(in_t), .sr826(sr_texel),
                .out_valid(lv[k - 1]), .out_texel(lt[8 * (k - 1) +: 8]),
                .line_write(drain[k - 1]), .error(lerr[2 * (k - 1) +: 2])
            );
        end
        for (k = NL + 1; k <= 10; k = k + 1) begin : absent
            assign lv[k - 1] = 1'b0;
            assign lt[8 * (k - 1) +: 8] = 8'd0;
            assign drain[k - 1] = 1'b0;
            assign lerr[2 * (k - 1) +: 2] = 2'd0;
        end
    endgenerate
    assign level_valid = lv;
    assign level_texel = lt;

    // The first level (in order) with a FIFO error, over a sync error.
    reg [1:0] code;
    integer j;
    always @* begin
        code = (valid && (sof != first)) ? 2'd3 : 2'd0;
        for (j = 9; j >= 0; j = j - 1)
            if (lerr[2 * j +: 2] != 2'd0) code = lerr[2 * j +: 2];
    end
    wire completes = (NL == 0) ? valid && frame_end : drain[(NL == 0) ? 0 : NL - 1];

    always @(posedge clk) begin
        if (rst) begin
            x0 <= 11'd0;
            line0 <= 11'd0;
            field <= 1'b0;
            error <= 1'b0;
            err_code <= 2'd0;
            frame_done <= 1'b0;
        end else begin
            if (valid) begin
                x0 <= nx;
                line0 <= nn;
                field <= nf;
            end
            if (code != 2'd0 && !error) begin
                error <= 1'b1;
                err_code <= code;
            end
            frame_done <= completes;
        end
    end
endmodule
