// Mipmap generator 816 with the frame store it writes level 0 into and reads shift register
// 826 from (behavioural, rtl/mipmap/frame_store_826.v): the top that `texrtl cosim --unit
// mipmap_gen_816` checks. Besides the generator's ports it brings out each level's texel
// stream (lK_valid, lK_texel for level K; levels the frame does not have stay 0), compared
// every cycle with the model's levels.
module mipmap_gen_816_with_store #(
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
    output wire        error,
    output wire [1:0]  err_code,
    output wire        frame_done,
    output wire        l1_valid,
    output wire [7:0]  l1_texel,
    output wire        l2_valid,
    output wire [7:0]  l2_texel,
    output wire        l3_valid,
    output wire [7:0]  l3_texel,
    output wire        l4_valid,
    output wire [7:0]  l4_texel,
    output wire        l5_valid,
    output wire [7:0]  l5_texel,
    output wire        l6_valid,
    output wire [7:0]  l6_texel,
    output wire        l7_valid,
    output wire [7:0]  l7_texel,
    output wire        l8_valid,
    output wire [7:0]  l8_texel,
    output wire        l9_valid,
    output wire [7:0]  l9_texel,
    output wire        l10_valid,
    output wire [7:0]  l10_texel
);
    wire store_valid, sr_load;
    wire [10:0] store_x, store_y, sr_row;
    wire [7:0] store_texel, sr_texel;
    wire [9:0] level_valid;
    wire [79:0] level_texel;
    mipmap_gen_816 #(.WIDTH(WIDTH), .HEIGHT(HEIGHT), .SCAN(SCAN), .ROUND(ROUND)) mipmap_gen_816 (
        .clk(clk), .rst(rst), .valid(valid), .texel(texel), .sof(sof), .error(error),
        .err_code(err_code), .frame_done(frame_done), .store_valid(store_valid),
        .store_x(store_x), .store_y(store_y), .store_texel(store_texel), .sr_load(sr_load),
        .sr_row(sr_row), .sr_texel(sr_texel), .level_valid(level_valid),
        .level_texel(level_texel)
    );
    frame_store_826 #(.WIDTH(WIDTH), .HEIGHT(HEIGHT)) frame_store_826 (
        .clk(clk), .store_valid(store_valid), .store_x(store_x), .store_y(store_y),
        .store_texel(store_texel), .sr_load(sr_load), .sr_row(sr_row), .sr_x(store_x),
        .sr_texel(sr_texel)
    );
    assign {l1_valid, l1_texel} = {level_valid[0], level_texel[7:0]};
    assign {l2_valid, l2_texel} = {level_valid[1], level_texel[15:8]};
    assign {l3_valid, l3_texel} = {level_valid[2], level_texel[23:16]};
    assign {l4_valid, l4_texel} = {level_valid[3], level_texel[31:24]};
    assign {l5_valid, l5_texel} = {level_valid[4], level_texel[39:32]};
    assign {l6_valid, l6_texel} = {level_valid[5], level_texel[47:40]};
    assign {l7_valid, l7_texel} = {level_valid[6], level_texel[55:48]};
    assign {l8_valid, l8_texel} = {level_valid[7], level_texel[63:56]};
    assign {l9_valid, l9_texel} = {level_valid[8], level_texel[71:64]};
    assign {l10_valid, l10_texel} = {level_valid[9], level_texel[79:72]};
endmodule
