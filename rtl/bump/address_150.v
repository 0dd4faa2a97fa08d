// Address unit 150 of US 2004/0207631 (Fenney), FIG. 7, para. 0052: the Verilog twin of
// hdl/units/src/bump/address_150.rs (same ports, widths, latency and reset).
//
//   U' = U - 1/2 in colour mode (step 51), U' = U otherwise; Ui = floor(U'),
//   Ublend = U' - Ui truncated to BLEND_BITS fraction bits; the same for V.
//
// u, v: sQ<POS_INT>.<POS_FRAC> (two's complement, POS_INT + POS_FRAC bits); ui, vj: signed
// POS_INT + 1 bits (U - 1/2 can fall below the position's minimum); ub, vb: uQ0.BLEND_BITS.
// One register stage (latency 1), cleared by the synchronous reset.
module address_150 #(
    parameter integer POS_INT = 16,
    parameter integer POS_FRAC = 8,
    parameter integer BLEND_BITS = 8
) (
    input  wire                        clk,
    input  wire                        rst,
    input  wire [POS_INT+POS_FRAC-1:0] u,
    input  wire [POS_INT+POS_FRAC-1:0] v,
    input  wire                        colour,
    output reg  [POS_INT:0]            ui,
    output reg  [POS_INT:0]            vj,
    output reg  [BLEND_BITS-1:0]       ub,
    output reg  [BLEND_BITS-1:0]       vb
);
    localparam integer W = POS_INT + POS_FRAC;
    // Half a texel in the position's fraction, one bit wider than the position.
    wire [W:0] half = colour ? ({{W{1'b0}}, 1'b1} << (POS_FRAC - 1)) : {(W + 1){1'b0}};
    // Sign-extended by one bit, so U - 1/2 cannot wrap. The fraction bits below the blend
    // factor's (POS_FRAC > BLEND_BITS) are truncated, by design: unused.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [W:0] up = {u[W-1], u} - half;
    wire [W:0] vp = {v[W-1], v} - half;
    /* verilator lint_on UNUSEDSIGNAL */

    always @(posedge clk) begin
        if (rst) begin
            ui <= {(POS_INT + 1){1'b0}};
            vj <= {(POS_INT + 1){1'b0}};
            ub <= {BLEND_BITS{1'b0}};
            vb <= {BLEND_BITS{1'b0}};
        end else begin
            // floor(U'): the integer bits of the two's complement value.
            ui <= up[W:POS_FRAC];
            vj <= vp[W:POS_FRAC];
            // The BLEND_BITS fraction bits below the binary point; the rest is dropped.
            ub <= up[POS_FRAC-1 -: BLEND_BITS];
            vb <= vp[POS_FRAC-1 -: BLEND_BITS];
        end
    end
endmodule
