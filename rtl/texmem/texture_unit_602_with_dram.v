// Texture mapping unit 602 driving the behavioural DRAM 604, as the model's unit holds its
// DRAM: the top that `texrtl cosim --unit texture_unit_602` checks. Besides the unit's ports
// it brings out the DRAM's pins and its count of timing violations (compared every cycle with
// the model's). The texture is the DRAM's power-up contents (see dram_604.v), the CLUT is
// CLUT_FILE.
module texture_unit_602_with_dram #(
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
    output wire          ras_n,
    output wire          cas_n,
    output wire          oe_n,
    output wire [10:0]   addr,
    output wire [31:0]   violations
);
    wire we_n, dq_valid;
    wire [15:0] dq;
    texture_unit_602 #(
        .W(W), .H(H), .F(F), .LAYOUT(LAYOUT), .BASE(BASE), .CACHE(CACHE), .MODE(MODE),
        .ROWS(ROWS), .COLS(COLS), .T_RP(T_RP), .T_RCD(T_RCD), .T_CAS(T_CAS), .T_CP(T_CP),
        .CLUT_FILE(CLUT_FILE)
    ) texture_unit_602 (
        .clk(clk), .rst(rst), .in_valid(in_valid), .in_u(in_u), .in_v(in_v),
        .in_newline(in_newline), .in_ready(in_ready), .out_valid(out_valid), .out_rgb(out_rgb),
        .need_mask(need_mask), .hit_mask(hit_mask), .ras_n(ras_n), .cas_n(cas_n), .we_n(we_n),
        .oe_n(oe_n), .dram_addr(addr), .dq(dq), .dq_valid(dq_valid)
    );
    dram_604 #(
        .ROWS(ROWS), .COLS(COLS), .T_RP(T_RP), .T_RCD(T_RCD), .T_CAS(T_CAS), .T_CP(T_CP)
    ) dram_604 (
        .clk(clk), .rst(rst), .ras_n(ras_n), .cas_n(cas_n), .we_n(we_n), .oe_n(oe_n),
        .addr(addr), .dq(dq), .dq_valid(dq_valid), .violations(violations)
    );
endmodule
