// Control unit 607 driving the behavioural DRAM 604, as the model's DramCtrl holds its DRAM:
// the top that `texrtl cosim --unit control_607` checks. Besides the controller's ports it
// brings out the DRAM's pins (compared every cycle with the model's) and the DRAM's count of
// timing violations (the model's DRAM counts them too).
module control_607_with_dram #(
    parameter integer ROWS = 512,
    parameter integer COLS = 512,
    parameter integer T_RP = 3,
    parameter integer T_RCD = 3,
    parameter integer T_CAS = 3,
    parameter integer T_CP = 3
) (
    input  wire                           clk,
    input  wire                           rst,
    input  wire                           req_valid,
    input  wire [$clog2(ROWS * COLS)-1:0] req_addr,
    output wire                           ready,
    output wire                           resp_valid,
    output wire [15:0]                    resp_data,
    output wire                           ras_n,
    output wire                           cas_n,
    output wire                           oe_n,
    output wire [10:0]                    addr,
    output wire [31:0]                    violations
);
    wire we_n, dq_valid;
    wire [15:0] dq;
    control_607 #(
        .ROWS(ROWS), .COLS(COLS), .T_RP(T_RP), .T_RCD(T_RCD), .T_CAS(T_CAS), .T_CP(T_CP)
    ) control_607 (
        .clk(clk), .rst(rst), .req_valid(req_valid), .req_addr(req_addr), .ready(ready),
        .resp_valid(resp_valid), .resp_data(resp_data), .ras_n(ras_n), .cas_n(cas_n),
        .we_n(we_n), .oe_n(oe_n), .dram_addr(addr), .dq(dq), .dq_valid(dq_valid)
    );
    dram_604 #(
        .ROWS(ROWS), .COLS(COLS), .T_RP(T_RP), .T_RCD(T_RCD), .T_CAS(T_CAS), .T_CP(T_CP)
    ) dram_604 (
        .clk(clk), .rst(rst), .ras_n(ras_n), .cas_n(cas_n), .we_n(we_n), .oe_n(oe_n),
        .addr(addr), .dq(dq), .dq_valid(dq_valid), .violations(violations)
    );
endmodule
