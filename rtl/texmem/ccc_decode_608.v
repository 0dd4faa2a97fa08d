// CCC decode of Schilling & Knittel's TEXRAM (Figures 4-6): register 608, multiplexer 610 and
// colour look-up table 612, the Verilog twin of CccDecode in
// hdl/units/src/texmem/ccc_decode_608.rs (same ports, registers, states and reset). Turns the
// two DRAM words of one 4x4 block into a 64-bit line of cache 614.
//
// Word 0: CLUT indices of colour a (bits 15..8) and b (7..0); word 1: the decision bits.
// Register 608 holds word 0 in bits 31..16 and word 1 in 15..0, filled one word per
// `word_valid`. After the second word: state LUT_A (multiplexer 610 on colour a, its CLUT
// entry registered in color_a), then LUT_B (610 on colour b): `line_valid` high and `line` =
// {colour a, colour b, decision bits} (24 + 24 + 16 bits). CLUT 612: 256 entries of 24-bit RGB,
// loaded from CLUT_FILE with $readmemh (read-only here, as in the model). States (state):
// 0 LOAD, 1 LUT_A, 2 LUT_B. Synchronous reset.
module ccc_decode_608 #(
    parameter CLUT_FILE = "clut_612.hex"
) (
    input  wire        clk,
    input  wire        rst,
    input  wire        word_valid,
    input  wire [15:0] word,
    output wire        line_valid,
    output wire [63:0] line,
    output reg  [1:0]  state
);
    localparam [1:0] LOAD = 2'd0, LUT_A = 2'd1, LUT_B = 2'd2;

    reg [23:0] clut_612 [0:255];
    initial $readmemh(CLUT_FILE, clut_612);

    reg [31:0] reg_608;
    reg words_in;
    reg [23:0] color_a;

    wire mux_610_sel = (state == LUT_B);
    wire [7:0] clut_612_addr = mux_610_sel ? reg_608[23:16] : reg_608[31:24];
    wire [23:0] clut_612_data = clut_612[clut_612_addr];

    assign line_valid = mux_610_sel;
    assign line = {color_a, clut_612_data, reg_608[15:0]};

    always @(posedge clk) begin
        if (rst) begin
            state <= LOAD;
            reg_608 <= 32'd0;
            words_in <= 1'b0;
            color_a <= 24'd0;
        end else begin
            case (state)
                LUT_A: begin
                    color_a <= clut_612_data;
                    state <= LUT_B;
                end
                LUT_B: state <= LOAD;
                default: if (word_valid) begin
                    if (words_in) begin
                        reg_608[15:0] <= word;
                        words_in <= 1'b0;
                        state <= LUT_A;
                    end else begin
                        reg_608[31:16] <= word;
                        words_in <= 1'b1;
                    end
                end
            endcase
        end
    end
endmodule
