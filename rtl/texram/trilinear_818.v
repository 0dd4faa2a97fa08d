// The trilinear interpolator 818 of Schilling & Knittel's TEXRAM chip: the Verilog twin of
// Trilinear818 and the arithmetic of hdl/units/src/texram/trilinear_818.rs. The eight texels
// (fine 2x2 then coarse 2x2, byte t of `texels`), each weighed by w_a w_b w_f with 8-bit
// weights 256 - a and a (`weights`: a0, b0, a1, b1, f in bytes 0-4), summed exactly (`sum`,
// the value times 2^24) and rounded once, half up: (sum + 2^23) >> 24. An index access's
// texels are CLUT 814 colours (`entries`), each component filtered; otherwise the value is
// component `part` of the colour collected in `acc_rgba` (R top byte), all four for a
// luminance access (part 0 and last). `rgba` is the colour so far; registered in acc_rgba
// when `finish`. Synchronous reset.
module trilinear_818 (
    input  wire         clk,
    input  wire         rst,
    input  wire         finish,
    input  wire [63:0]  texels,
    input  wire [39:0]  weights,
    input  wire         index,
    input  wire [255:0] entries,
    input  wire [1:0]   part,
    input  wire         last,
    output wire [31:0]  sum,
    output wire [31:0]  rgba,
    output reg  [31:0]  acc_rgba
);
    // The exact weighted sum of eight bytes.
    function automatic [39:0] weighted(input [63:0] tx, input [39:0] w);
        integer n, t;
        reg [39:0] wa, wb, wf;
        begin
            weighted = 40'd0;
            for (n = 0; n < 2; n = n + 1) begin
                wf = (n == 0) ? 40'd256 - 40'(w[39:32]) : 40'(w[39:32]);
                for (t = 0; t < 4; t = t + 1) begin
                    wa = (t % 2 == 1) ? 40'(w[16*n +: 8]) : 40'd256 - 40'(w[16*n +: 8]);
                    wb = (t / 2 == 1) ? 40'(w[16*n+8 +: 8]) : 40'd256 - 40'(w[16*n+8 +: 8]);
                    weighted = weighted + 40'(tx[8*(4*n+t) +: 8]) * wa * wb * wf;
                end
            end
        end
    endfunction

    // One component (byte c from the top) of the eight CLUT colours.
    function automatic [63:0] component(input [255:0] e, input integer c);
        integer t;
        begin
            for (t = 0; t < 8; t = t + 1) component[8*t +: 8] = e[32*t + 24 - 8*c +: 8];
        end
    endfunction

    wire [39:0] exact = weighted(texels, weights);
    assign sum = exact[31:0];
    wire [7:0] value = 8'((exact + 40'h80_0000) >> 24);
    wire [7:0] lut [0:3];
    genvar c;
    generate
        for (c = 0; c < 4; c = c + 1) begin : g_component
            assign lut[c] = 8'((weighted(component(entries, c), weights) + 40'h80_0000) >> 24);
        end
    endgenerate
    wire [4:0] shift = 5'(8 * (3 - 32'(part)));
    wire [31:0] collected = (last && part == 2'd0) ? {4{value}}
        : (acc_rgba & ~(32'hff << shift)) | (32'(value) << shift);
    assign rgba = index ? {lut[0], lut[1], lut[2], lut[3]} : collected;

    always @(posedge clk) begin
        if (rst) acc_rgba <= 32'd0;
        else if (finish) acc_rgba <= rgba;
    end
endmodule
