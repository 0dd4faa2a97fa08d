// Colour extract unit 618 of Schilling & Knittel's TEXRAM (Figure 6): the Verilog twin of
// ColorExtract in hdl/units/src/texmem/extract_618.rs (same ports, registers and reset). From
// the four cache lines (entries A-D of cache 614) it picks the 2x2 texels of the bilinear
// footprint and registers them with the blend weights, for interpolator 622.
//
// Texel (x, y) lives in the line of entry {y[2], x[2]} (Figure 7: block (x >> 2, y >> 2) in
// entry {by[0], bx[0]}); its decision bit 4 (y & 3) + (x & 3) selects colour b (line bits
// 39..16) when set, colour a (63..40) otherwise. Outputs, registered one cycle when `in_valid`
// (held otherwise; `valid` follows `in_valid`): c00, c10, c01, c11 (24-bit RGB of (x0, y0),
// (x1, y0), (x0, y1), (x1, y1)), fu, fv. Pure selection. Synchronous reset.
module extract_618 #(
    parameter integer COORD_BITS = 12,
    parameter integer F = 4
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire                  in_valid,
    // Whole texel coordinates, as the model's ports; the selection reads bits 2..0.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [COORD_BITS-1:0] x0,
    input  wire [COORD_BITS-1:0] x1,
    input  wire [COORD_BITS-1:0] y0,
    input  wire [COORD_BITS-1:0] y1,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [F-1:0]          in_fu,
    input  wire [F-1:0]          in_fv,
    input  wire [63:0]           line_a,
    input  wire [63:0]           line_b,
    input  wire [63:0]           line_c,
    input  wire [63:0]           line_d,
    output reg                   valid,
    output reg  [23:0]           c00,
    output reg  [23:0]           c10,
    output reg  [23:0]           c01,
    output reg  [23:0]           c11,
    output reg  [F-1:0]          fu,
    output reg  [F-1:0]          fv
);
    wire [63:0] lines [0:3];
    assign lines[0] = line_a;
    assign lines[1] = line_b;
    assign lines[2] = line_c;
    assign lines[3] = line_d;

    // The texel at (x, y) from the low three bits of its coordinates.
    function automatic [23:0] texel(input [2:0] x, input [2:0] y);
        reg [63:0] l;
        begin
            l = lines[{y[2], x[2]}];
            texel = l[{2'b00, y[1:0], x[1:0]}] ? l[39:16] : l[63:40];
        end
    endfunction

    always @(posedge clk) begin
        if (rst) begin
            valid <= 1'b0;
            c00 <= 24'd0;
            c10 <= 24'd0;
            c01 <= 24'd0;
            c11 <= 24'd0;
            fu <= {F{1'b0}};
            fv <= {F{1'b0}};
        end else begin
            valid <= in_valid;
            if (in_valid) begin
                c00 <= texel(x0[2:0], y0[2:0]);
                c10 <= texel(x1[2:0], y0[2:0]);
                c01 <= texel(x0[2:0], y1[2:0]);
                c11 <= texel(x1[2:0], y1[2:0]);
                fu <= in_fu;
                fv <= in_fv;
            end
        end
    end
endmodule
