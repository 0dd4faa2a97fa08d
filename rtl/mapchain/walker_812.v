// The chain walker of Schilling & Knittel's address and control unit 812 (section 14,
// Fig. 16): the Verilog twin of MapChain812 in hdl/units/src/mapchain/walker_812.rs and its
// micro-program hdl/units/src/mapchain/program.rs (same states, registers, reset, timing).
//
// A pixel is taken when req_ready (idle, the cycle a result is out, or the last cycle of a
// pixel's last access when the next pixel's first DRF reads the banks). Each state that reads
// the banks issues one access on acc_* (the banks answer at the clock edge on rd_value and
// rd_slots) and stays for rd_slots x SLOT_CYCLES cycles; ENV_COORDS (eq. 4 and the cube face)
// takes one cycle; going to a linked DRF none. At the chain's end the output stage 820's
// eqs 5-7 give out_colour, with the pixel's access, slot and fault counts (out_error on a
// chain of more than seven DRFs, a detail without offsets, an unset DRF, a face above 5, a
// reflectance lit by an environment the chain does not read, a texel still waiting).
//
// The seven DRFs are the host's load (the adapter writes drfs_812.hex from the model's DRF
// file); word k, k = 0..7 (7 is never set), bit 0 up:
//   [0] set, [3:1] kind (0 texture, 1 offset, 2 detail, 3 reflectance, 4 environment),
//   [4] link valid, [7:5] link, [8] new_coords, [16:9] k_s, [18:17] detail mode (0 replace,
//   1 multiply, 2 add-signed), [19] base_texture, [20] light_env, [24:21] width_log2,
//   [26:25] eq. 5's factor (0 I_d, 1 k_T, 2 one), [34:27] k_T, then plane p's even base at
//   [35 + 12p +: 12] (read by the banks' stand-in, not here).
// Formats: req_u, req_v sQ12.8; req_lambda sQ5.8; req_n* sQ2.14; req_v* sQ1.14 (the eye
// vector); acc_u, acc_v sQ12.8, acc_lambda sQ5.8; colours u8.
module walker_812 #(
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
    output reg                req_ready,
    output reg                acc_valid,
    output reg         [2:0]  acc_drf,
    output reg         [2:0]  acc_plane,
    output reg         [20:0] acc_u,
    output reg         [20:0] acc_v,
    output reg         [13:0] acc_lambda,
    input  wire        [7:0]  rd_value,
    input  wire        [1:0]  rd_slots,
    output wire        [3:0]  state,
    output reg                out_valid,
    output reg         [7:0]  out_colour,
    output reg                out_error,
    output reg         [3:0]  out_accesses,
    output reg         [4:0]  out_slots,
    output reg         [3:0]  out_faults
);
    localparam [3:0] IDLE = 4'd0, TEXTURE = 4'd1, OFFSET_U = 4'd2, OFFSET_V = 4'd3,
        DETAIL = 4'd4, DETAIL_BASE = 4'd5, REFLECTANCE = 4'd6, ENV_COORDS = 4'd7,
        ENVIRONMENT = 4'd8, COMBINE = 4'd9, ERROR = 4'd10;
    localparam [2:0] KTEX = 3'd0, KOFF = 3'd1, KDET = 3'd2, KREFL = 3'd3, KENV = 3'd4;
    localparam [2:0] NONE = 3'd7;

    /* verilator lint_off UNUSEDSIGNAL */
    reg [107:0] drfs [0:7];
    /* verilator lint_on UNUSEDSIGNAL */
    initial $readmemh("drfs_812.hex", drfs);

    // Cube-face reciprocal table: round(2^32 / mid) for the midpoints of [1, 2)'s 64 steps.
    reg [31:0] tab [0:63];
    integer ti;
    reg [63:0] tmid;
    initial begin
        for (ti = 0; ti < 64; ti = ti + 1) begin
            tmid = 64'd131072 + ((64'd2 * ti + 64'd1) << 10);
            tab[ti] = 32'((((64'd1 << 34) / tmid) + 64'd1) >> 1);
        end
    end

    // round(x y / 255), half up: t = x y + 128, (t + (t >> 8)) >> 8.
    function automatic [7:0] mul255(input [7:0] x, input [7:0] y);
        reg [15:0] t;
        begin
            t = 16'(x) * 16'(y) + 16'd128;
            mul255 = 8'((t + (t >> 8)) >> 8);
        end
    endfunction

    function automatic [7:0] add_sat(input [7:0] a, input [7:0] b);
        reg [8:0] s;
        begin
            s = {1'b0, a} + {1'b0, b};
            add_sat = s[8] ? 8'd255 : s[7:0];
        end
    endfunction

    // x / 2^sh rounded to nearest, ties to even (sh >= 1).
    function automatic [63:0] round_even(input [63:0] x, input integer sh);
        reg [63:0] q, rem, half;
        begin
            q = x >> sh;
            rem = x & ((64'd1 << sh) - 64'd1);
            half = 64'd1 << (sh - 1);
            round_even = (rem > half || (rem == half && q[0])) ? q + 64'd1 : q;
        end
    endfunction

    // Eq. 4: w = 2 n (n . v) - v (n . n), exact in units of 2^-42, each component rounded to
    // sQ3.16 (ties to even) and held at its ends.
    function automatic [59:0] reflect4(
        input signed [16:0] nx, input signed [16:0] ny, input signed [16:0] nz,
        input signed [15:0] vx, input signed [15:0] vy, input signed [15:0] vz);
        reg signed [63:0] n [0:2];
        reg signed [63:0] v [0:2];
        reg signed [63:0] d, nn, x, q;
        reg [25:0] rem;
        integer c;
        begin
            n[0] = 64'(nx); n[1] = 64'(ny); n[2] = 64'(nz);
            v[0] = 64'(vx); v[1] = 64'(vy); v[2] = 64'(vz);
            d = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
            nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            reflect4 = 60'd0;
            for (c = 0; c < 3; c = c + 1) begin
                x = 64'sd2 * n[c] * d - v[c] * nn;
                q = x >>> 26;
                rem = x[25:0];
                if (rem > 26'h2000000 || (rem == 26'h2000000 && q[0])) q = q + 64'sd1;
                if (q > 64'sd524287) q = 64'sd524287;
                if (q < -64'sd524288) q = -64'sd524288;
                reflect4[40 - 20 * c +: 20] = q[19:0];
            end
        end
    endfunction

    // The face of w's major axis (ties to x, then y) and s, t in uQ0.12 (cube_face.rs).
    function automatic [26:0] face_st(input [59:0] w);
        reg signed [63:0] c [0:2];
        reg [63:0] a [0:2];
        reg signed [63:0] sc, tc, p, scaled, vv;
        reg [63:0] ma, m, r0, mr, r1, st [0:1];
        integer axis, lead, e, i, k;
        reg neg;
        begin
            for (i = 0; i < 3; i = i + 1) begin
                c[i] = 64'($signed(w[40 - 20 * i +: 20]));
                a[i] = c[i] < 0 ? 64'(-c[i]) : 64'(c[i]);
            end
            axis = (a[0] >= a[1] && a[0] >= a[2]) ? 0 : (a[1] >= a[2]) ? 1 : 2;
            ma = a[axis];
            if (ma == 64'd0) begin
                face_st = {3'd4, 12'd2048, 12'd2048};
            end else begin
                neg = c[axis] < 0;
                case ({axis[1:0], neg})
                    3'b000: begin sc = -c[2]; tc = -c[1]; end
                    3'b001: begin sc = c[2]; tc = -c[1]; end
                    3'b010: begin sc = c[0]; tc = c[2]; end
                    3'b011: begin sc = c[0]; tc = -c[2]; end
                    3'b100: begin sc = c[0]; tc = -c[1]; end
                    default: begin sc = -c[0]; tc = -c[1]; end
                endcase
                lead = 0;
                for (i = 0; i < 20; i = i + 1) if (ma[i]) lead = i;
                m = lead >= 16 ? ma >> (lead - 16) : ma << (16 - lead);
                e = lead - 16;
                r0 = 64'(tab[m[15:10]]);
                mr = round_even(m * r0, 16);
                r1 = round_even(r0 * ((64'd2 << 16) - mr), 16);
                for (k = 0; k < 2; k = k + 1) begin
                    p = (k == 0 ? sc : tc) * $signed(r1);
                    scaled = e >= 0 ? p >>> e : p <<< (-e);
                    vv = scaled + (64'sd1 << 32);
                    if (vv < 0) vv = 0;
                    if (vv > (64'sd1 << 33) - (64'sd1 << 21)) vv = (64'sd1 << 33) - (64'sd1 << 21);
                    st[k] = round_even(64'(vv), 21);
                end
                face_st = {3'(2 * axis) + {2'd0, neg}, st[0][11:0], st[1][11:0]};
            end
        end
    endfunction

    // Section 9's detail path (detail_fig9.rs).
    /* verilator lint_off UNUSEDSIGNAL */
    function automatic [20:0] offset_point(input [20:0] c);
        offset_point = {c[20:8], 8'h80};
    endfunction
    /* verilator lint_on UNUSEDSIGNAL */

    function automatic [20:0] detail_coord(input [7:0] o, input [7:0] frac);
        detail_coord = {5'd0, o, 8'd0} + {9'd0, frac, 4'd0};
    endfunction

    function automatic [13:0] detail_lambda(input signed [13:0] l);
        reg signed [13:0] k;
        begin
            k = l < -14'sd1024 ? -14'sd1024 : (l > -14'sd256 ? -14'sd256 : l);
            detail_lambda = k + 14'sd1024;
        end
    endfunction

    function automatic [13:0] max0(input signed [13:0] l);
        max0 = l[13] ? 14'd0 : l;
    endfunction

    function automatic needs_texel(input [1:0] mode, input signed [13:0] l);
        needs_texel = mode != 2'd0 || l > -14'sd256;
    endfunction

    function automatic [7:0] step_912(input [1:0] mode, input signed [13:0] l, input [7:0] d,
                                      input [7:0] t);
        reg [7:0] x;
        reg signed [9:0] s;
        reg [8:0] f;
        reg [17:0] mix;  // < 2^16
        begin
            case (mode)
                2'd0: x = d;
                2'd1: x = mul255(t, d);
                default: begin
                    s = $signed({2'b0, t}) + $signed({2'b0, d}) - 10'sd128;
                    x = s < 0 ? 8'd0 : (s > 10'sd255 ? 8'd255 : s[7:0]);
                end
            endcase
            if (l <= -14'sd256) begin
                step_912 = x;
            end else begin
                f = 9'(l + 14'sd256);
                mix = 18'(x) * (18'd256 - 18'(f)) + 18'(t) * 18'(f) + 18'd128;
                step_912 = 8'(mix >> 8);
            end
        end
    endfunction

    // A state that waits for an access to the banks.
    function automatic reads(input [3:0] s);
        reads = !(s == IDLE || s == ENV_COORDS || s == COMBINE || s == ERROR);
    endfunction

    // The walk's registers (Walk in program.rs) and the pixel held (its leading DRF is used
    // only when it is taken).
    reg [3:0] w_state, w_steps;
    reg [2:0] w_drf, w_tex_drf, w_refl_drf, w_env_drf, w_face;
    reg w_deferred, w_to_refl, w_offsets;
    reg [7:0] w_tex, w_refl, w_env, w_ou, w_ov, w_detail;
    reg [11:0] w_s, w_t;
    reg [2:0] h_face;
    reg signed [20:0] h_u, h_v;
    reg signed [13:0] h_lambda;
    reg signed [16:0] h_nx, h_ny, h_nz;
    reg signed [15:0] h_vx, h_vy, h_vz;
    reg [7:0] h_id, h_is;
    reg [4:0] busy;
    reg [3:0] px_accesses, px_faults;
    reg [4:0] px_slots;
    assign state = w_state;

    // The walk being computed (ws_*), its access (f_*), the pixel it is for (p_*), and every
    // register's next value (*_n).
    reg [3:0] ws_state, ws_steps;
    reg [2:0] ws_drf, ws_tex_drf, ws_refl_drf, ws_env_drf, ws_face;
    reg ws_deferred, ws_to_refl, ws_offsets;
    reg [7:0] ws_tex, ws_refl, ws_env, ws_ou, ws_ov, ws_detail;
    reg [11:0] ws_s, ws_t;
    reg f_valid;
    reg [2:0] f_drf, f_plane;
    reg [20:0] f_u, f_v;
    reg [13:0] f_lambda;
    reg [2:0] p_face;
    reg signed [20:0] p_u, p_v;
    reg signed [13:0] p_lambda;
    reg [26:0] p_fst;
    reg [7:0] p_id, p_is;
    reg [2:0] r_drf, r_face;
    reg signed [20:0] r_u, r_v;
    reg signed [13:0] r_lambda;
    reg [26:0] r_fst;
    reg [7:0] r_id, r_is;
    // Eq. 4 and the cube face of the pixel held and of the port's: one each, read by the
    // environment state of whichever pixel is walked.
    wire [26:0] fst_held = face_st(reflect4(h_nx, h_ny, h_nz, h_vx, h_vy, h_vz));
    wire [26:0] fst_port = face_st(reflect4(req_nx, req_ny, req_nz, req_vx, req_vy, req_vz));
    reg [3:0] w_state_n, w_steps_n;
    reg [2:0] w_drf_n, w_tex_drf_n, w_refl_drf_n, w_env_drf_n, w_face_n;
    reg w_deferred_n, w_to_refl_n, w_offsets_n;
    reg [7:0] w_tex_n, w_refl_n, w_env_n, w_ou_n, w_ov_n, w_detail_n;
    reg [11:0] w_s_n, w_t_n;
    reg hold_n;
    reg [4:0] busy_n;
    reg [3:0] px_accesses_n, px_faults_n;
    reg [4:0] px_slots_n;
    reg out_valid_n, out_error_n;
    reg [7:0] out_colour_n;
    reg [3:0] out_accesses_n, out_faults_n;
    reg [4:0] out_slots_n;
    reg [3:0] c_acc, c_faults;
    reg [4:0] c_slots;
    reg [5:0] busy1;
    reg stall;

    // DRF fields (a word of an unset DRF is all zeros).
    function automatic d_set(input [2:0] k);
        d_set = drfs[k][0];
    endfunction
    function automatic [2:0] d_kind(input [2:0] k);
        d_kind = drfs[k][3:1];
    endfunction
    function automatic d_linked(input [2:0] k);
        d_linked = drfs[k][0] && drfs[k][4];
    endfunction
    function automatic [2:0] d_link(input [2:0] k);
        d_link = drfs[k][7:5];
    endfunction
    function automatic [1:0] d_mode(input [2:0] k);
        d_mode = drfs[k][0] ? drfs[k][18:17] : 2'd0;
    endfunction

    task automatic fetch(input [2:0] k, input [2:0] plane, input [20:0] u, input [20:0] v,
                         input [13:0] l);
        begin
            f_valid = 1'b1; f_drf = k; f_plane = plane; f_u = u; f_v = v; f_lambda = l;
        end
    endtask

    task automatic clear_walk;
        begin
            f_valid = 1'b0; f_drf = 3'd0; f_plane = 3'd0; f_u = 21'd0; f_v = 21'd0;
            f_lambda = 14'd0;
        end
    endtask

    // The chain's end: the output stage next, or an error.
    task automatic do_finish;
        begin
            ws_state = ((d_set(ws_refl_drf) && drfs[ws_refl_drf][20] && ws_env_drf == NONE)
                        || ws_deferred) ? ERROR : COMBINE;
        end
    endtask

    // To DRF k and on along its links until an access or the chain's end.
    task automatic do_visit(input [2:0] k0);
        reg [2:0] k;
        reg done, refl, below0;
        integer i;
        begin
            k = k0;
            done = 1'b0;
            below0 = p_lambda[13];
            for (i = 0; i < 8; i = i + 1) begin
                if (!done) begin
                    ws_steps = ws_steps + 4'd1;
                    if (!d_set(k) || ws_steps > 4'd7) begin
                        ws_state = ERROR;
                        done = 1'b1;
                    end else begin
                        ws_drf = k;
                        case (d_kind(k))
                            KTEX, KREFL: begin
                                refl = d_kind(k) == KREFL;
                                ws_to_refl = refl;
                                if (refl) ws_refl_drf = k; else ws_tex_drf = k;
                                ws_deferred = below0 && d_linked(k) && d_set(d_link(k))
                                    && d_kind(d_link(k)) == KOFF;
                                if (!ws_deferred) begin
                                    ws_state = refl ? REFLECTANCE : TEXTURE;
                                    fetch(k, 3'd0, p_u, p_v, p_lambda);
                                    done = 1'b1;
                                end
                            end
                            KOFF: if (below0) begin
                                ws_state = OFFSET_U;
                                fetch(k, 3'd0, offset_point(p_u), offset_point(p_v), 14'd0);
                                done = 1'b1;
                            end
                            KDET: if (below0) begin
                                if (!ws_offsets) begin
                                    ws_state = ERROR;
                                end else begin
                                    ws_state = DETAIL;
                                    fetch(k, 3'd0, detail_coord(ws_ou, p_u[7:0]),
                                          detail_coord(ws_ov, p_v[7:0]), detail_lambda(p_lambda));
                                end
                                done = 1'b1;
                            end
                            KENV: begin
                                ws_env_drf = k;
                                if (drfs[k][8]) begin
                                    {ws_face, ws_s, ws_t} = p_fst;
                                    ws_state = ENV_COORDS;
                                end else if (p_face > 3'd5) begin
                                    ws_state = ERROR;
                                end else begin
                                    ws_state = ENVIRONMENT;
                                    fetch(k, p_face, p_u, p_v, max0(p_lambda));
                                end
                                done = 1'b1;
                            end
                            default: ;
                        endcase
                        if (!done) begin
                            if (d_linked(k)) begin
                                k = d_link(k);
                            end else begin
                                do_finish();
                                done = 1'b1;
                            end
                        end
                    end
                end
            end
        end
    endtask

    // A new pixel from the port: its walk from the first DRF (held if it is taken).
    task automatic take_port;
        begin
            p_u = r_u; p_v = r_v; p_lambda = r_lambda; p_fst = r_fst; p_face = r_face;
            p_id = r_id; p_is = r_is;
            ws_state = IDLE; ws_drf = NONE; ws_steps = 4'd0; ws_deferred = 1'b0;
            ws_to_refl = 1'b0; ws_tex = 8'd0; ws_refl = 8'd0; ws_env = 8'd0; ws_ou = 8'd0;
            ws_ov = 8'd0; ws_offsets = 1'b0; ws_detail = 8'd0; ws_tex_drf = NONE;
            ws_refl_drf = NONE; ws_env_drf = NONE; ws_face = 3'd0; ws_s = 12'd0;
            ws_t = 12'd0;
            clear_walk();
            do_visit(r_drf);
            hold_n = 1'b1;
        end
    endtask

    // Step 912 into the detail's target; the detail used up with its offsets.
    task automatic apply_detail(input [7:0] d, input [7:0] t);
        reg [7:0] x;
        begin
            x = step_912(d_mode(ws_drf), p_lambda, d, t);
            if (ws_to_refl) ws_refl = x; else ws_tex = x;
            ws_offsets = 1'b0;
            ws_deferred = 1'b0;
        end
    endtask

    // The walk after its state's access gave `value`.
    task automatic do_advance(input [7:0] value);
        reg cont;
        reg [31:0] lg;
        begin
            cont = 1'b1;
            case (ws_state)
                TEXTURE: ws_tex = value;
                REFLECTANCE: ws_refl = value;
                OFFSET_U: begin
                    ws_ou = value;
                    ws_state = OFFSET_V;
                    fetch(ws_drf, 3'd1, offset_point(p_u), offset_point(p_v), 14'd0);
                    cont = 1'b0;
                end
                OFFSET_V: begin
                    ws_ov = value;
                    ws_offsets = 1'b1;
                end
                DETAIL: begin
                    ws_detail = value;
                    if (ws_deferred && needs_texel(d_mode(ws_drf), p_lambda)) begin
                        ws_state = DETAIL_BASE;
                        fetch(ws_to_refl ? ws_refl_drf : ws_tex_drf, 3'd0, p_u, p_v, p_lambda);
                        cont = 1'b0;
                    end else begin
                        apply_detail(value, ws_to_refl ? ws_refl : ws_tex);
                    end
                end
                DETAIL_BASE: apply_detail(ws_detail, value);
                ENV_COORDS: begin
                    ws_state = ENVIRONMENT;
                    lg = d_set(ws_drf) ? {28'd0, drfs[ws_drf][24:21]} : 32'd4;
                    fetch(ws_drf, ws_face, 21'(({20'd0, ws_s} << lg) >> 4),
                          21'(({20'd0, ws_t} << lg) >> 4), max0(p_lambda));
                    cont = 1'b0;
                end
                ENVIRONMENT: ws_env = value;
                default: cont = 1'b0;
            endcase
            if (cont) begin
                if (d_linked(ws_drf)) do_visit(d_link(ws_drf));
                else do_finish();
            end
        end
    endtask

    // The output stage 820 on the walk computed (ws_*) for a pixel lit by I_d = id and
    // I_s = is: eq. 5, then eq. 6 or 7.
    function automatic [7:0] colour(input [7:0] id, input [7:0] is);
        reg [7:0] cd, factor, light, base;
        reg [2:0] k;
        begin
            case (drfs[ws_tex_drf][26:25])
                2'd0: factor = id;
                2'd1: factor = drfs[ws_tex_drf][34:27];
                default: factor = 8'd255;
            endcase
            cd = d_set(ws_tex_drf) ? mul255(factor, ws_tex) : id;
            k = d_set(ws_refl_drf) ? ws_refl_drf : ws_env_drf;
            base = (d_set(k) && !drfs[k][19]) ? id : cd;
            light = drfs[ws_refl_drf][20] ? ws_env : is;
            if (d_set(ws_refl_drf)) colour = add_sat(base, mul255(ws_refl, light));
            else if (d_set(ws_env_drf)) colour = add_sat(base, mul255(drfs[ws_env_drf][16:9], ws_env));
            else colour = cd;
        end
    endfunction

    // The walk into the registers, its access issued, the result out at the chain's end.
    task automatic apply_walk(input [3:0] acc, input [4:0] slots, input [3:0] faults);
        reg [3:0] a;
        begin
            w_state_n = ws_state; w_steps_n = ws_steps; w_drf_n = ws_drf;
            w_tex_drf_n = ws_tex_drf; w_refl_drf_n = ws_refl_drf; w_env_drf_n = ws_env_drf;
            w_face_n = ws_face; w_deferred_n = ws_deferred; w_to_refl_n = ws_to_refl;
            w_offsets_n = ws_offsets; w_tex_n = ws_tex; w_refl_n = ws_refl; w_env_n = ws_env;
            w_ou_n = ws_ou; w_ov_n = ws_ov; w_detail_n = ws_detail; w_s_n = ws_s;
            w_t_n = ws_t;
            busy_n = 5'd0;
            a = acc;
            if (f_valid) begin
                a = a + 4'd1;
                acc_valid = 1'b1; acc_drf = f_drf; acc_plane = f_plane; acc_u = f_u;
                acc_v = f_v; acc_lambda = f_lambda;
            end
            px_accesses_n = a; px_slots_n = slots; px_faults_n = faults;
            if (ws_state == ERROR || ws_state == COMBINE) begin
                out_valid_n = 1'b1;
                out_error_n = ws_state == ERROR;
                out_colour_n = ws_state == COMBINE ? colour(p_id, p_is) : 8'd0;
                out_accesses_n = a; out_slots_n = slots; out_faults_n = faults;
            end
        end
    endtask

    always @(*) begin
        w_state_n = w_state; w_steps_n = w_steps; w_drf_n = w_drf;
        w_tex_drf_n = w_tex_drf; w_refl_drf_n = w_refl_drf; w_env_drf_n = w_env_drf;
        w_face_n = w_face; w_deferred_n = w_deferred; w_to_refl_n = w_to_refl;
        w_offsets_n = w_offsets; w_tex_n = w_tex; w_refl_n = w_refl; w_env_n = w_env;
        w_ou_n = w_ou; w_ov_n = w_ov; w_detail_n = w_detail; w_s_n = w_s; w_t_n = w_t;
        hold_n = 1'b0; busy_n = busy;
        px_accesses_n = px_accesses; px_slots_n = px_slots; px_faults_n = px_faults;
        out_valid_n = 1'b0; out_error_n = out_error; out_colour_n = out_colour;
        out_accesses_n = out_accesses; out_slots_n = out_slots; out_faults_n = out_faults;
        acc_valid = 1'b0; acc_drf = 3'd0; acc_plane = 3'd0; acc_u = 21'd0; acc_v = 21'd0;
        acc_lambda = 14'd0;
        stall = 1'b0; busy1 = 6'd0;
        c_acc = px_accesses; c_slots = px_slots; c_faults = px_faults;
        req_ready = (w_state == IDLE) || (w_state == COMBINE) || (w_state == ERROR);
        clear_walk();
        // The pixel held, the walk's registers and the port's pixel, read here: Icarus's
        // sensitivity covers what the block itself reads, not what its tasks read.
        p_u = h_u; p_v = h_v; p_lambda = h_lambda; p_fst = fst_held; p_face = h_face;
        p_id = h_id; p_is = h_is;
        ws_state = w_state; ws_steps = w_steps; ws_drf = w_drf; ws_tex_drf = w_tex_drf;
        ws_refl_drf = w_refl_drf; ws_env_drf = w_env_drf; ws_face = w_face;
        ws_deferred = w_deferred; ws_to_refl = w_to_refl; ws_offsets = w_offsets;
        ws_tex = w_tex; ws_refl = w_refl; ws_env = w_env; ws_ou = w_ou; ws_ov = w_ov;
        ws_detail = w_detail; ws_s = w_s; ws_t = w_t;
        r_drf = req_drf; r_u = req_u; r_v = req_v; r_lambda = req_lambda; r_fst = fst_port;
        r_face = req_face; r_id = req_id; r_is = req_is;
        if (req_ready) begin
            if (req_valid) begin
                take_port();
                apply_walk(4'd0, 5'd0, 4'd0);
            end else begin
                w_state_n = IDLE;
            end
        end else begin
            if (reads(w_state)) begin
                busy1 = {1'b0, busy} + 6'd1;
                if ({26'd0, busy1} < {30'd0, rd_slots} * SLOT_CYCLES) begin
                    busy_n = busy1[4:0];
                    stall = 1'b1;
                end else begin
                    c_slots = c_slots + {3'd0, rd_slots};
                    c_faults = c_faults + {3'd0, rd_slots > 2'd1};
                end
            end
            if (!stall) begin
                do_advance(rd_value);
                apply_walk(c_acc, c_slots, c_faults);
                if ((ws_state == COMBINE || ws_state == ERROR) && req_valid) begin
                    take_port();
                    if (f_valid) begin
                        req_ready = 1'b1;
                        apply_walk(4'd0, 5'd0, 4'd0);
                    end else begin
                        hold_n = 1'b0;
                    end
                end
            end
        end
    end

    always @(posedge clk) begin
        if (rst) begin
            w_state <= IDLE; w_steps <= 4'd0; w_drf <= 3'd0; w_tex_drf <= 3'd0;
            w_refl_drf <= 3'd0; w_env_drf <= 3'd0; w_face <= 3'd0; w_deferred <= 1'b0;
            w_to_refl <= 1'b0; w_offsets <= 1'b0; w_tex <= 8'd0; w_refl <= 8'd0;
            w_env <= 8'd0; w_ou <= 8'd0; w_ov <= 8'd0; w_detail <= 8'd0; w_s <= 12'd0;
            w_t <= 12'd0;
            h_u <= 21'sd0; h_v <= 21'sd0; h_lambda <= 14'sd0;
            h_nx <= 17'sd0; h_ny <= 17'sd0; h_nz <= 17'sd0; h_vx <= 16'sd0; h_vy <= 16'sd0;
            h_vz <= 16'sd0; h_face <= 3'd0; h_id <= 8'd0; h_is <= 8'd0;
            busy <= 5'd0; px_accesses <= 4'd0; px_slots <= 5'd0; px_faults <= 4'd0;
            out_valid <= 1'b0; out_colour <= 8'd0; out_error <= 1'b0;
            out_accesses <= 4'd0; out_slots <= 5'd0; out_faults <= 4'd0;
        end else begin
            w_state <= w_state_n; w_steps <= w_steps_n; w_drf <= w_drf_n;
            w_tex_drf <= w_tex_drf_n; w_refl_drf <= w_refl_drf_n; w_env_drf <= w_env_drf_n;
            w_face <= w_face_n; w_deferred <= w_deferred_n; w_to_refl <= w_to_refl_n;
            w_offsets <= w_offsets_n; w_tex <= w_tex_n; w_refl <= w_refl_n; w_env <= w_env_n;
            w_ou <= w_ou_n; w_ov <= w_ov_n; w_detail <= w_detail_n; w_s <= w_s_n;
            w_t <= w_t_n;
            if (hold_n) begin
                h_u <= req_u; h_v <= req_v; h_lambda <= req_lambda;
                h_nx <= req_nx; h_ny <= req_ny; h_nz <= req_nz; h_vx <= req_vx;
                h_vy <= req_vy; h_vz <= req_vz; h_face <= req_face; h_id <= req_id;
                h_is <= req_is;
            end
            busy <= busy_n; px_accesses <= px_accesses_n; px_slots <= px_slots_n;
            px_faults <= px_faults_n;
            out_valid <= out_valid_n; out_colour <= out_colour_n; out_error <= out_error_n;
            out_accesses <= out_accesses_n; out_slots <= out_slots_n;
            out_faults <= out_faults_n;
        end
    end
endmodule
