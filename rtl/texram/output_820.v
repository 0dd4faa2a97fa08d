// The output and combination stage 820 of Schilling & Knittel's TEXRAM chip (eq. 5): the
// Verilog twin of Output820 in hdl/units/src/texram/output_820.rs (same registers and reset).
// C_d = (I_d | k_T | 1) . T on R, G and B, `x . y = round(x y / 255)` exactly as
// t = x y + 128, (t + (t >> 8)) >> 8; alpha the texture's. `modulate`: {0, -} I_d (the
// request's illumination, R top byte), {1, k_T}, {2, -} one. When `finish` the result is
// registered (out_value its top byte, out_rgba, the eight texels, the fault, 818's exact sum)
// with out_valid high for one cycle. Synchronous reset.
module output_820 (
    input  wire        clk,
    input  wire        rst,
    input  wire        finish,
    input  wire [9:0]  modulate,
    // R, G, B of the illumination (its alpha, bits 7..0, unused: eq. 5 leaves alpha).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [31:0] illum,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0] rgba,
    input  wire [63:0] texels,
    input  wire        fault,
    input  wire [31:0] sum,
    output reg         out_valid,
    output reg  [7:0]  out_value,
    output reg  [31:0] out_rgba,
    output reg  [63:0] out_texels,
    output reg         out_fault,
    output reg  [31:0] out_sum
);
    function automatic [7:0] mul255(input [7:0] x, input [7:0] y);
        reg [15:0] t;
        begin
            t = 16'(x) * 16'(y) + 16'd128;
            mul255 = 8'((t + (t >> 8)) >> 8);
        end
    endfunction

    wire [7:0] factor [0:2];
    wire [7:0] shaded [0:2];
    genvar c;
    generate
        for (c = 0; c < 3; c = c + 1) begin : g_rgb
            assign factor[c] = (modulate[9:8] == 2'd0) ? illum[24-8*c +: 8]
                : (modulate[9:8] == 2'd1) ? modulate[7:0] : 8'd255;
            assign shaded[c] = mul255(factor[c], rgba[24-8*c +: 8]);
        end
    endgenerate

    always @(posedge clk) begin
        if (rst) begin
            out_valid <= 1'b0;
            out_value <= 8'd0;
            out_rgba <= 32'd0;
            out_texels <= 64'd0;
            out_fault <= 1'b0;
            out_sum <= 32'd0;
        end else begin
            out_valid <= finish;
            if (finish) begin
                out_value <= shaded[0];
                out_rgba <= {shaded[0], shaded[1], shaded[2], rgba[7:0]};
                out_texels <= texels;
                out_fault <= fault;
                out_sum <= sum;
            end
        end
    end
endmodule
