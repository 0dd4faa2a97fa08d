// Replicate unit 152 of US 2004/0207631 (Fenney), FIG. 7, para. 0056-0057, and its Bezier form
// (Equation 1, para. 0083): the Verilog twin of hdl/units/src/bump/replicate_152.rs.
//
// The 3x3 grid a..k (texels of TEXEL_BITS bits) goes to the four bilinear units as the
// overlapping 2x2 windows red [a b; d e], green [b c; e f], blue [d e; g h], alpha [e f; h k]
// (outputs xy: x right, y down). Every output has two more fraction bits than a texel: the
// texel times 4, or with BEZIER = 1 Equation 1's Bezier points times 4:
//   a' = a+b+d+e, b' = 2(b+e), c' = b+c+e+f, d' = 2(d+e), e' = 4e, f' = 2(e+f),
//   g' = d+e+g+h, h' = 2(e+h), k' = e+f+h+k.
// Combinational (latency 0): no clock.
module replicate_152 #(
    parameter integer TEXEL_BITS = 8,
    parameter integer BEZIER = 0
) (
    input  wire [TEXEL_BITS-1:0] a, b, c, d, e, f, g, h, k,
    output wire [TEXEL_BITS+1:0] r00, r10, r01, r11,
    output wire [TEXEL_BITS+1:0] g00, g10, g01, g11,
    output wire [TEXEL_BITS+1:0] b00, b10, b01, b11,
    output wire [TEXEL_BITS+1:0] a00, a10, a01, a11
);
    localparam integer O = TEXEL_BITS + 2;
    // Zero-extended texels, so the sums of four cannot overflow.
    wire [O-1:0] xa = {2'b00, a}, xb = {2'b00, b}, xc = {2'b00, c}, xd = {2'b00, d};
    wire [O-1:0] xe = {2'b00, e}, xf = {2'b00, f}, xg = {2'b00, g}, xh = {2'b00, h};
    wire [O-1:0] xk = {2'b00, k};
    wire [O-1:0] pa, pb, pc, pd, pe, pf, pg, ph, pk;
    generate
        if (BEZIER != 0) begin : g_bezier
            assign pa = xa + xb + xd + xe;
            assign pb = (xb + xe) << 1;
            assign pc = xb + xc + xe + xf;
            assign pd = (xd + xe) << 1;
            assign pe = xe << 2;
            assign pf = (xe + xf) << 1;
            assign pg = xd + xe + xg + xh;
            assign ph = (xe + xh) << 1;
            assign pk = xe + xf + xh + xk;
        end else begin : g_bspline
            assign pa = xa << 2;
            assign pb = xb << 2;
            assign pc = xc << 2;
            assign pd = xd << 2;
            assign pe = xe << 2;
            assign pf = xf << 2;
            assign pg = xg << 2;
            assign ph = xh << 2;
            assign pk = xk << 2;
        end
    endgenerate
    assign r00 = pa; assign r10 = pb; assign r01 = pd; assign r11 = pe;
    assign g00 = pb; assign g10 = pc; assign g01 = pe; assign g11 = pf;
    assign b00 = pd; assign b10 = pe; assign b01 = pg; assign b11 = ph;
    assign a00 = pe; assign a10 = pf; assign a01 = ph; assign a11 = pk;
endmodule
