// Blend-factor adjust unit 153 of US 2004/0207631 (Fenney), FIG. 7, para. 0058-0061, with the
// bypass of para. 0085: the Verilog twin of hdl/units/src/bump/blend_adjust_153.rs (same ports,
// widths, latency and reset).
//
//   u0 = 1/2 + u/2 = {1'b1, u_in}    u1 = u/2 = {1'b0, u_in}    (uQ0.F in, uQ0.(F+1) out)
//   bypass (Blinn): u0 = u1 = {u_in, 1'b0}                      (and the same for v)
//
// REGISTERED = 1: one output register stage (latency 1), synchronous reset clears it; the data
// registers load every cycle, valid or not, as the model's do. REGISTERED = 0: combinational.
module blend_adjust_153 #(
    parameter integer FRAC_BITS = 8,
    parameter integer REGISTERED = 1
) (
    input  wire                 clk,
    input  wire                 rst,
    input  wire                 valid_in,
    input  wire                 bypass,
    input  wire [FRAC_BITS-1:0] u_in,
    input  wire [FRAC_BITS-1:0] v_in,
    output wire                 valid,
    output wire [FRAC_BITS:0]   u0,
    output wire [FRAC_BITS:0]   u1,
    output wire [FRAC_BITS:0]   v0,
    output wire [FRAC_BITS:0]   v1
);
    wire [FRAC_BITS:0] u0_c = bypass ? {u_in, 1'b0} : {1'b1, u_in};
    wire [FRAC_BITS:0] u1_c = bypass ? {u_in, 1'b0} : {1'b0, u_in};
    wire [FRAC_BITS:0] v0_c = bypass ? {v_in, 1'b0} : {1'b1, v_in};
    wire [FRAC_BITS:0] v1_c = bypass ? {v_in, 1'b0} : {1'b0, v_in};

    generate
        if (REGISTERED != 0) begin : g_reg
            reg                 valid_r;
            reg [FRAC_BITS:0]   u0_r, u1_r, v0_r, v1_r;
            always @(posedge clk) begin
                if (rst) begin
                    valid_r <= 1'b0;
                    u0_r    <= {(FRAC_BITS + 1){1'b0}};
                    u1_r    <= {(FRAC_BITS + 1){1'b0}};
                    v0_r    <= {(FRAC_BITS + 1){1'b0}};
                    v1_r    <= {(FRAC_BITS + 1){1'b0}};
                end else begin
                    valid_r <= valid_in;
                    u0_r    <= u0_c;
                    u1_r    <= u1_c;
                    v0_r    <= v0_c;
                    v1_r    <= v1_c;
                end
            end
            assign valid = valid_r;
            assign u0 = u0_r;
            assign u1 = u1_r;
            assign v0 = v0_r;
            assign v1 = v1_r;
        end else begin : g_comb
            // No clock used: the ports stay for a uniform interface.
            wire unused = &{1'b0, clk, rst};
            assign valid = valid_in;
            assign u0 = u0_c;
            assign u1 = u1_c;
            assign v0 = v0_c;
            assign v1 = v1_c;
        end
    endgenerate
endmodule
