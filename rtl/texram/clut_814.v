// The colour look-up table 814 of Schilling & Knittel's TEXRAM chip (section 6): the Verilog
// twin of Clut814 in hdl/units/src/texram/clut_814.rs. 256 entries of 32 bits (R in bits
// 31..24, G, B, alpha in 7..0) loaded from CLUT_FILE with $readmemh (read-only here, as the
// model's host loads it before a run), eight read ports: entry t of `entries` is the colour
// of index byte t of `indices`.
module clut_814 #(
    parameter CLUT_FILE = "clut_814.hex"
) (
    input  wire [63:0]  indices,
    output wire [255:0] entries
);
    reg [31:0] table_814 [0:255];
    initial $readmemh(CLUT_FILE, table_814);
    genvar t;
    generate
        for (t = 0; t < 8; t = t + 1) begin : g_port
            assign entries[32*t +: 32] = table_814[indices[8*t +: 8]];
        end
    endgenerate
endmodule
