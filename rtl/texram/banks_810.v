// Banks 810 of Schilling & Knittel's TEXRAM chip (Figure 8) and their address decoders 822:
// the Verilog twin of Banks810 in hdl/units/src/texram/banks_810.rs (same registers and
// reset). The bank stage holds the access being served (copied from 812 when it moves in,
// `take`), the cycles left of its slots and whether it faulted; it reads its eight texels
// from the banks (or the border colour) for the interpolator. The banks are DEPTH words of
// 8 bits each, bank b at b DEPTH in BANK_FILE ($readmemh: the host's load, as the model's).
// `take` loads the access, `left` (slots x slot cycles) and `fault`; `finish` clears `valid`;
// otherwise a busy stage counts `left` down. Synchronous reset (the banks' contents stay).
module banks_810 #(
    parameter integer DEPTH = 2048,
    parameter BANK_FILE = "banks_810.hex"
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              take,
    input  wire              finish,
    input  wire [31:0]       in_read,
    input  wire [8*4*19-1:0] in_words,
    input  wire [39:0]       in_src,
    input  wire [7:0]        in_border,
    input  wire [39:0]       in_weights,
    input  wire [7:0]        in_colour,
    input  wire              in_index,
    input  wire [1:0]        in_part,
    input  wire              in_last,
    input  wire [31:0]       in_illum,
    input  wire [9:0]        in_modulate,
    input  wire [7:0]        in_left,
    input  wire              in_fault,
    output reg               valid,
    output reg  [7:0]        left,
    output reg               fault,
    output reg  [39:0]       weights,
    output reg               index,
    output reg  [1:0]        part,
    output reg               last,
    output reg  [31:0]       illum,
    output reg  [9:0]        modulate,
    output wire [63:0]       texels
);
    localparam integer AW = $clog2(8 * DEPTH);
    reg [7:0] mem [0:8*DEPTH-1];
    initial $readmemh(BANK_FILE, mem);

    // The address decoders 822: the access's bank words (`read`, which of them it reads, is
    // for the waveform: the texels name their words through `src`).
    /* verilator lint_off UNUSEDSIGNAL */
    reg [31:0] read;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [8*4*19-1:0] words;
    reg [39:0] src;
    reg [7:0] border, colour;

    // A word beyond DEPTH is not held (the adapter keeps every map inside).
    /* verilator lint_off UNUSEDSIGNAL */
    genvar t;
    generate
        for (t = 0; t < 8; t = t + 1) begin : g_texel
            wire [4:0] at = src[5*t +: 5];
            wire [18:0] word = words[19*at +: 19];
            wire [AW-1:0] addr = AW'(at[4:2]) * AW'(DEPTH) + AW'(word);
            assign texels[8*t +: 8] = border[t] ? colour : mem[addr];
        end
    endgenerate
    /* verilator lint_on UNUSEDSIGNAL */

    always @(posedge clk) begin
        if (rst) begin
            valid <= 1'b0;
            left <= 8'd0;
            fault <= 1'b0;
            read <= 32'd0;
            words <= {8*4*19{1'b0}};
            src <= 40'd0;
            border <= 8'd0;
            weights <= 40'd0;
            colour <= 8'd0;
            index <= 1'b0;
            part <= 2'd0;
            last <= 1'b0;
            illum <= 32'd0;
            modulate <= 10'd0;
        end else if (take) begin
            valid <= 1'b1;
            left <= in_left;
            fault <= in_fault;
            read <= in_read;
            words <= in_words;
            src <= in_src;
            border <= in_border;
            weights <= in_weights;
            colour <= in_colour;
            index <= in_index;
            part <= in_part;
            last <= in_last;
            illum <= in_illum;
            modulate <= in_modulate;
        end else if (finish) begin
            valid <= 1'b0;
        end else if (valid) begin
            left <= left - 8'd1;
        end
    end
endmodule
