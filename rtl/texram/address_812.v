// The address and control unit 812 of Schilling & Knittel's TEXRAM chip (Figure 8): the
// Verilog twin of Address812 in hdl/units/src/texram/address_812.rs (same registers and
// reset). From a request (or the next component of the colour request it holds) and the
// DRF's descriptor it computes one trilinear access into its registers, for the banks 810.
//
// Descriptor (DRF_BITS = 70, as texram_802.v packs it): width_log2 [3:0], height_log2 [7:4],
// base_even [26:8], base_odd [45:27], border kind [48:46] (0 wrap, 1 clamp, 2 mirror,
// 3 border colour, 4 tile), its colour or tile log2 [56:49], config [58:57] (0 luminance,
// 1 index, 2 planar, 3 literal), modulate [60:59] (0 I_d, 1 k_T, 2 one), k_T [68:61], set [69].
//
// Arithmetic, exact on the raw sQ12.8 u, v and sQ5.8 lambda (every value below an integer):
// levels L = lambda >> 8 held to 0..Lmax (fine L, coarse L + 1, f = lambda & 255; below 0:
// levels 0 and min(1, Lmax), f = 0; at Lmax both Lmax, f = 0); per level k the axis
// x = u - (128 << k), i = x >> (8 + k), a = (x >> k) & 255 (v alike); the pair i, i + 1
// through the border operation (the tile border wraps inside the sample point's 2^(t - k)
// tile, then at the edge); a colour layout's component `part` placed in the DRF's space
// (planar quadrants, literal 2x2 cells) on a map of half the size; texel (x, y) of level k in
// bank 4 (k & 1) + 2 (y & 1) + (x & 1), word base + offset(k) + (y >> 1) ceil(W_k / 2) + (x >> 1).
// A bank asked for several words (the literal layout) reads them in successive rounds
// (`read` bit 4 bank + round, words word[bank][round]); `src` gives each texel's bank and round
// (5 bits each), `border` the texels that are the border colour; `conflicts` counts accesses
// that needed a second round. An unset DRF reads nothing (every texel the colour 0).
// `valid` is the chip's to drive (valid_en, valid_d). Synchronous reset.
module address_812 #(
    parameter integer DRF_BITS = 70
) (
    input  wire                clk,
    input  wire                rst,
    // A request taken (its DRF number, u, v, lambda, illumination), or the held request's
    // next component; `drf` is the descriptor either reads.
    input  wire                take,
    input  wire                next_part,
    input  wire [2:0]          req_drf,
    input  wire [20:0]         req_u,
    input  wire [20:0]         req_v,
    input  wire [13:0]         req_lambda,
    input  wire [31:0]         req_illum,
    // The descriptor; bits 71:70 pad it to whole hex digits.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [DRF_BITS-1:0] drf,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire                valid_en,
    input  wire                valid_d,
    output reg                 valid,
    output reg  [31:0]         read,
    output wire [8*4*19-1:0]   words,
    output reg  [39:0]         src,
    output reg  [7:0]          border,
    output reg  [39:0]         weights,
    output reg  [7:0]          colour,
    output reg                 index,
    output reg  [1:0]          part,
    output reg                 last,
    output reg  [31:0]         illum,
    output reg  [9:0]          modulate,
    output reg  [2:0]          held_drf,
    output reg  [39:0]         conflicts
);
    localparam [2:0] CLAMP = 3'd1, MIRROR = 3'd2, COLOUR = 3'd3, TILE = 3'd4;
    localparam [1:0] INDEX = 2'd1, PLANAR = 2'd2, LITERAL = 2'd3;

    reg [18:0] word [0:31];
    reg [20:0] held_u, held_v;
    reg [13:0] held_lambda;
    genvar g;
    generate
        for (g = 0; g < 32; g = g + 1) begin : g_words
            assign words[19*g +: 19] = word[g];
        end
    endgenerate

    // 2^max(lg - k, 0): a level's side.
    function automatic integer side(input integer lg, input integer k);
        side = (k >= lg) ? 1 : (1 << (lg - k));
    endfunction

    // Index i on an axis of n texels after the border operation: {is the border colour, index}.
    function automatic [32:0] remap(input integer i, input integer n, input [2:0] kind);
        integer m, x;
        begin
            m = i & (2 * n - 1);
            case (kind)
                CLAMP: x = (i < 0) ? 0 : (i > n - 1) ? n - 1 : i;
                MIRROR: x = (m < n) ? m : 2 * n - 1 - m;
                default: x = (kind == COLOUR) ? i : i & (n - 1);
            endcase
            remap = {kind == COLOUR && !(i >= 0 && i < n), x};
        end
    endfunction

    // Texel i + dx of the pair i, i + 1 at level k (weight a toward i + 1), n texels.
    function automatic [32:0] pair(input integer i, input integer a, input integer dx,
                                   input integer n, input integer k, input [2:0] kind,
                                   input integer t);
        integer tile, base;
        begin
            if (kind == TILE) begin
                tile = 1 << ((t > k) ? t - k : 0);
                base = (i + ((a >= 128) ? 1 : 0)) & ~(tile - 1);
                pair = remap(base + ((i + dx - base) & (tile - 1)), n, 3'd0);
            end else begin
                pair = remap(i + dx, n, kind);
            end
        end
    endfunction

    // Words of the levels before k in its bank group.
    function automatic integer offset(input integer wl, input integer hl, input integer k);
        integer j;
        begin
            offset = 0;
            for (j = 0; j < 10; j = j + 1)
                if (j < k && j % 2 == k % 2)
                    offset = offset + ((side(wl, j) + 1) >> 1) * ((side(hl, j) + 1) >> 1);
        end
    endfunction

    // The access: every texel's bank word, round and weight, from part `p` of (u, v, lambda).
    reg [31:0] n_read;
    reg [18:0] n_word [0:31];
    reg [39:0] n_src, n_weights;
    reg [7:0] n_border;
    // Integers of the arithmetic (their upper bits unused where a value is narrower).
    /* verilator lint_off UNUSEDSIGNAL */
    integer u, v, lam, wl, hl, pwl, phl, maxl, fine, coarse, f, lv, w, h, x0, y0;
    integer ii, a, jj, b, t, n, bank, wd, r, rr, gx, gy, rounds, at;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [32:0] xs, ys;
    reg [2:0] kind;
    reg [1:0] cfg, p;
    reg colour_map, placed;
    always @* begin
        u = take ? 32'($signed(req_u)) : 32'($signed(held_u));
        v = take ? 32'($signed(req_v)) : 32'($signed(held_v));
        lam = take ? 32'($signed(req_lambda)) : 32'($signed(held_lambda));
        gx = 0;
        gy = 0;
        bank = 0;
        wd = 0;
        placed = 1'b0;
        rr = 0;
        at = 0;
        p = take ? 2'd0 : part + 2'd1;
        cfg = drf[58:57];
        kind = drf[48:46];
        colour_map = drf[69] && (cfg == PLANAR || cfg == LITERAL);
        wl = 32'(drf[3:0]);
        hl = 32'(drf[7:4]);
        pwl = (colour_map && wl > 0) ? wl - 1 : wl;
        phl = (colour_map && hl > 0) ? hl - 1 : hl;
        maxl = (pwl > phl) ? pwl : phl;
        if ((lam >>> 8) < 0) begin
            fine = 0;
            coarse = (maxl > 0) ? 1 : 0;
            f = 0;
        end else if ((lam >>> 8) >= maxl) begin
            fine = maxl;
            coarse = maxl;
            f = 0;
        end else begin
            fine = lam >>> 8;
            coarse = fine + 1;
            f = lam & 255;
        end
        n_read = 32'd0;
        n_src = 40'd0;
        n_border = 8'd0;
        rounds = 1;
        n_weights = {8'(f), 32'd0};
        for (r = 0; r < 32; r = r + 1) n_word[r] = word[r];
        for (n = 0; n < 2; n = n + 1) begin
            lv = (n == 0) ? fine : coarse;
            w = side(pwl, lv);
            h = side(phl, lv);
            x0 = u - (128 << lv);
            y0 = v - (128 << lv);
            ii = x0 >>> (8 + lv);
            a = (x0 >>> lv) & 255;
            jj = y0 >>> (8 + lv);
            b = (y0 >>> lv) & 255;
            n_weights[16*n +: 16] = {8'(b), 8'(a)};
            for (t = 0; t < 4; t = t + 1) begin
                xs = pair(ii, a, t % 2, w, lv, kind, 32'(drf[56:49]));
                ys = pair(jj, b, t / 2, h, lv, kind, 32'(drf[56:49]));
                if (xs[32] || ys[32]) begin
                    n_border[4*n+t] = 1'b1;
                end else begin
                    gx = $signed(xs[31:0]);
                    gy = $signed(ys[31:0]);
                    if (cfg == PLANAR) begin
                        gx = gx + w * 32'(p[0]);
                        gy = gy + h * 32'(p[1]);
                    end else if (cfg == LITERAL) begin
                        gx = 2 * gx + 32'(p[0]);
                        gy = 2 * gy + 32'(p[1]);
                    end
                    bank = 4 * (lv % 2) + 2 * (gy % 2) + (gx % 2);
                    wd = ((lv % 2 == 1) ? 32'(drf[45:27]) : 32'(drf[26:8])) + offset(wl, hl, lv)
                        + (gy >> 1) * ((side(wl, lv) + 1) >> 1) + (gx >> 1);
                    placed = 1'b0;
                    rr = 0;
                    for (r = 0; r < 4; r = r + 1) begin
                        at = 4 * bank + r;
                        if (!placed && !n_read[at]) begin
                            n_word[at] = 19'(wd);
                            n_read[at] = 1'b1;
                            placed = 1'b1;
                            rr = r;
                        end else if (!placed && n_word[at] == 19'(wd)) begin
                            placed = 1'b1;
                            rr = r;
                        end
                    end
                    if (rr + 1 > rounds) rounds = rr + 1;
                    n_src[5*(4*n+t) +: 5] = 5'(4 * bank + rr);
                end
            end
        end
    end

    integer e;
    always @(posedge clk) begin
        if (rst) begin
            valid <= 1'b0;
            read <= 32'd0;
            for (e = 0; e < 32; e = e + 1) word[e] <= 19'd0;
            src <= 40'd0;
            border <= 8'd0;
            weights <= 40'd0;
            colour <= 8'd0;
            index <= 1'b0;
            part <= 2'd0;
            last <= 1'b0;
            illum <= 32'd0;
            modulate <= 10'd0;
            held_drf <= 3'd0;
            held_u <= 21'd0;
            held_v <= 21'd0;
            held_lambda <= 14'd0;
            conflicts <= 40'd0;
        end else begin
            if (valid_en) valid <= valid_d;
            if (take) begin
                held_drf <= req_drf;
                held_u <= req_u;
                held_v <= req_v;
                held_lambda <= req_lambda;
                illum <= req_illum;
            end
            if (take || next_part) begin
                part <= p;
                last <= !colour_map || p == 2'd3;
                if (!drf[69]) begin
                    read <= 32'd0;
                    border <= 8'hff;
                    colour <= 8'd0;
                end else begin
                    read <= n_read;
                    for (e = 0; e < 32; e = e + 1) word[e] <= n_word[e];
                    src <= n_src;
                    border <= n_border;
                    weights <= n_weights;
                    colour <= (drf[48:46] == COLOUR) ? drf[56:49] : 8'd0;
                    index <= drf[58:57] == INDEX;
                    modulate <= {drf[60:59], (drf[60:59] == 2'd1) ? drf[68:61] : 8'd0};
                    conflicts <= conflicts + 40'(rounds > 1);
                end
            end
        end
    end
endmodule
