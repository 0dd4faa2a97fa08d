// Bench top of the chain walker 812's co-simulation: walker_812 with a stand-in for the banks
// behind its bank port (bank_port_810.rs), the Verilog of tb/src/cosim/mapchain.rs's
// HashBanks. The port makes the access staged on acc_* at the clock edge: an access to an
// unset DRF, or to a plane the DRF does not have, is refused (rd_value 0, one slot, the
// sticky `refused`); any other answers a value and one or two slots (a page fault) from a
// hash of the plane's even base (drfs_812.hex, [35 + 12p +: 12]) and u, v, lambda.
module walker_812_with_banks #(
    parameter SLOT_CYCLES = 6
) (
    input  wire               clk,
    input  wire               rst,
    input  wire               req_valid,
    input  wire        [2:0]  req_drf,
    input  wire signed [20:0] req_u,
    input  wire signed [20:0] req_v,
    input  wire signed [13:0] req_lambda,
    input  wire signed [16:0] req_nx,
    input  wire signed [16:0] req_ny,
    input  wire signed [16:0] req_nz,
    input  wire signed [15:0] req_vx,
    input  wire signed [15:0] req_vy,
    input  wire signed [15:0] req_vz,
    input  wire        [2:0]  req_face,
    input  wire        [7:0]  req_id,
    input  wire        [7:0]  req_is,
    output wire               req_ready,
    output wire               acc_valid,
    output wire        [2:0]  acc_drf,
    output wire        [2:0]  acc_plane,
    output wire        [20:0] acc_u,
    output wire        [20:0] acc_v,
    output wire        [13:0] acc_lambda,
    output reg         [7:0]  rd_value,
    output reg         [1:0]  rd_slots,
    output reg                refused,
    output wire        [3:0]  state,
    output wire               out_valid,
    output wire        [7:0]  out_colour,
    output wire               out_error,
    output wire        [3:0]  out_accesses,
    output wire        [4:0]  out_slots,
    output wire        [3:0]  out_faults
);
    walker_812 #(.SLOT_CYCLES(SLOT_CYCLES)) walker (
        .clk(clk), .rst(rst), .req_valid(req_valid), .req_drf(req_drf), .req_u(req_u),
        .req_v(req_v), .req_lambda(req_lambda), .req_nx(req_nx), .req_ny(req_ny),
        .req_nz(req_nz), .req_vx(req_vx), .req_vy(req_vy), .req_vz(req_vz),
        .req_face(req_face), .req_id(req_id), .req_is(req_is), .req_ready(req_ready),
        .acc_valid(acc_valid), .acc_drf(acc_drf), .acc_plane(acc_plane), .acc_u(acc_u),
        .acc_v(acc_v), .acc_lambda(acc_lambda), .rd_value(rd_value), .rd_slots(rd_slots),
        .state(state), .out_valid(out_valid), .out_colour(out_colour),
        .out_error(out_error), .out_accesses(out_accesses), .out_slots(out_slots),
        .out_faults(out_faults)
    );

    /* verilator lint_off UNUSEDSIGNAL */
    reg [107:0] drfs [0:7];
    /* verilator lint_on UNUSEDSIGNAL */
    initial $readmemh("drfs_812.hex", drfs);

    wire [107:0] d = drfs[acc_drf];
    wire [2:0] planes = d[3:1] == 3'd1 ? 3'd2 : (d[3:1] == 3'd4 ? 3'd6 : 3'd1);
    wire ok = d[0] && acc_plane < planes;
    wire [11:0] base = 12'(d[35 + 12 * acc_plane +: 12]);
    reg [31:0] x;
    always @(*) begin
        x = {20'd0, base} * 32'h9e37_79b9 ^ {11'd0, acc_u} * 32'h85eb_ca6b
            ^ {11'd0, acc_v} * 32'hc2b2_ae35 ^ {18'd0, acc_lambda} * 32'h27d4_eb2f;
        x = x ^ (x >> 15);
        x = x * 32'h2c1b_3c6d;
        x = x ^ (x >> 12);
    end

    always @(posedge clk) begin
        if (rst) begin
            rd_value <= 8'd0;
            rd_slots <= 2'd0;
            refused <= 1'b0;
        end else if (acc_valid) begin
            if (ok) begin
                rd_value <= x[7:0];
                rd_slots <= x[9:8] == 2'd0 ? 2'd2 : 2'd1;
            end else begin
                rd_value <= 8'd0;
                rd_slots <= 2'd1;
                refused <= 1'b1;
            end
        end
    end
endmodule
