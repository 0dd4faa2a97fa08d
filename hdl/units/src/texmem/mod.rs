//! The texture memory path of Schilling & Knittel's Figure 6, the low-cost texture mapping
//! unit 602, one file per unit: DRAM 604, control unit 607, CCC decode 608/610/612, cache 614,
//! colour extract 618, bilinear interpolator 622; the texture layouts in DRAM; the unit 602
//! that wires them.
//!
//! ## The texture memory path (Schilling & Knittel, Figures 4-7)
//!
//! The low-cost texture mapping unit 602 of their Figure 6, end to end, one file per unit:
//!
//! | Figure 6 unit | model | tests | waveform scope |
//! |---|---|---|---|
//! | DRAM 604 (256K x 16 or 1M x 16, pin level, timing checks) | `hdl/units/src/texmem/dram_604.rs` | `tb/tests/dram.rs` | `texture_unit_602.control_607.dram_604` |
//! | DRAM control unit 607: word reads (open page), block fetch, lookahead queue | `hdl/units/src/texmem/control_607.rs` | `tb/tests/dram.rs`, `tb/tests/texture.rs` | `texture_unit_602.control_607`, `.fill_engine_607`, `.lookahead_queue_607` |
//! | the unit 602: request stage, wiring | `hdl/units/src/texmem/texture_unit_602.rs` | `tb/tests/texture.rs` | `texture_unit_602` |
//! | register 608, multiplexer 610, CLUT 612 | `hdl/units/src/texmem/ccc_decode_608.rs` | in-file, `tb/tests/texture.rs` | `texture_unit_602.ccc_decode_608` |
//! | cache 614 (Figure 7 interleave), lookahead choice | `hdl/units/src/texmem/cache_614.rs` | in-file, `tb/tests/texture.rs` | `texture_unit_602.cache_614.entry_a..d` |
//! | colour extract 618 | `hdl/units/src/texmem/extract_618.rs` | `tb/tests/texture.rs` | `texture_unit_602.extract_618` |
//! | bilinear interpolator 622 | `hdl/units/src/texmem/bilinear_622.rs` | in-file, `tb/tests/texture.rs` (exhaustive over weights) | `texture_unit_602.bilinear_622` |
//! | texture layout in DRAM | `hdl/units/src/texmem/layout.rs` | in-file | - |
//! | CCC encoder (Figure 4, Eq. 1), `.ccc` format | `formats/src/ccc.rs` | in-file, `tb/tests/texture.rs` | - |
//! | golden bilinear filtering | `golden/src/texture.rs` | in-file | `tb.golden.rgb_reference` |
//!
//! **DRAM 604 and 607.** A behavioural page-mode DRAM at pin level (RAS#, CAS#, WE#, OE#, 11
//! multiplexed address pins, 16-bit DQ, one open row in its page register) that checks the
//! timing it is driven with, as a vendor's model does (RAS# precharge, RAS#-to-CAS#, CAS# low and
//! precharge widths, addresses, writes), and the control unit that reads words through it,
//! keeping the page open. Timing in 5 ns controller cycles; defaults reproduce the document:
//! 30 ns per page-mode access, another 30 ns per page fault, hence 33.3 M texels/s peak and
//! 26.7 M with 8 texels and 2 page faults per scanline (both asserted in `cargo test` and
//! `texrtl regress`).
//!
//! **Formats.** Requests `u, v`: `uQ12.F` texel coordinates (F = `--frac-bits`, default 4;
//! integer part below the texture size). DRAM word 0 of a block: CLUT index of colour a (bits
//! 15..8) and b (7..0); word 1: decision bits, bit `4y + x` for texel `(x, y)`, 1 = colour b.
//! Register 608: 32 bits, word 0 high. CLUT 612: 256 x 24-bit RGB. Cache line: colour a (63..40),
//! colour b (39..16), decision bits (15..0). Bilinear 622 per channel: `top = c00 (W - fu) + c10
//! fu` (8 + F bits), `sum = top (W - fv) + bot fv` (8 + 2F bits), exact; one rounding, half up,
//! `(sum + 2^(2F-1)) >> 2F`, which cannot overflow. Addressing clamps to the edge; with clamping,
//! the four blocks of a footprint always have four different (x, y) parities, so the Figure 7
//! interleave never makes them conflict (checked exhaustively).
//!
//! **Timing** (each figure asserted cycle for cycle in `tb/tests/texture.rs`). A request whose
//! blocks are all cached takes one cycle in stage 0 and leaves 622 two cycles later; hits stream
//! at one request per cycle. A miss fills one block at a time: 607 takes word 0 the cycle after the
//! miss, reads both words in page mode (t_cas + t_cp + t_cas = 9 cycles, plus t_rp + t_rcd = 6 on a
//! page fault), multiplexer 610 and CLUT 612 take two cycles, the line is written, the request
//! looks up again: a cold first request takes 23 cycles, each further block of a footprint 13.
//! **Lookahead**: when a request completes (and was not flagged `newline`), up to three
//! neighbouring blocks are queued and preloaded one at a time whenever the fill engine is free and
//! stage 0 needs nothing; a demand miss or a `newline` request empties the queue; a fill in
//! progress is never abandoned. Which neighbours: `quadrant` (the document's scheme and the
//! default: the three adjacent to the point's quadrant, from bit 1 of x and of y) or `direction`
//! (the document's "more sophisticated lookahead": the neighbours in the direction of motion from
//! the scanline's previous point, so the next block is preloaded as soon as the scanline enters a
//! block). **Cache off**: every entry is invalidated when a
//! request completes, so each request fetches all its blocks.
//!
//! **Layouts.** Row-major (block `(bx, by)` at `2 (by bw + bx)`) or tiled: tiles of `tw x th`
//! blocks filling exactly one page (16 x 16 blocks = 64 x 64 texels with 512-word pages), so 2D
//! neighbourhoods share a page. A texture must fit the DRAM: 2048 x 1024 texels (2 M) in the 256K
//! x 16 part, as the document says.
//!
//! **CCC encoder** (`texrtl ccc encode`). Per 4x4 block the tensor of inertia of its colours about
//! their mean (Eq. 1), its eigenvector of least moment (Jacobi rotations), the plane through the
//! mean perpendicular to it splitting the block; colours a and b the cluster means. Then all
//! blocks' colours (weighted by texel counts) are quantised to 256 CLUT entries by median cut
//! (Heckbert), splitting the box of largest weighted squared error at the weighted median of its
//! axis of largest variance; indices are the nearest entries; finally every texel's bit is chosen
//! again against the two quantised colours (never worse). The 256x256 test texture compresses to
//! 33.1 dB PSNR. **`.ccc` format** (little-endian): magic `TEXRTLCC`, version u16 = 1, width u16,
//! height u16, CLUT entries u16 = 256, CLUT 256 x (r, g, b), then the blocks row-major, 4 bytes
//! each (index a, index b, decision bits u16); the size must be exactly `784 + 4 blocks`.
//!
//! **Checks.** `tb/tests/texture.rs`: random textures (1-6 x 1-6 blocks, random CLUTs and blocks)
//! and random requests through every mode (cache + lookahead, cache, no cache) x layout x
//! rasterizer interval (1, 3) x fraction bits (1-6) with 16-word pages, with the schedule check
//! on: every result equal to the integer reference (`tb::texture::reference_filter`: the reference decode and
//! a four-weight sum, written apart from the hardware's two lerps) and within 0.5 LSB of the f64
//! golden model of the decoded texture (derived: exact arithmetic, one round to nearest); reads =
//! 2 x fills; misses = cold + capacity + conflict. The `texture_unit_602` testbench of `texrtl
//! regress` runs a 256x256 synthetic texture (a fixed fixture) on four traces (horizontal
//! scanlines of 32 pixels, the same rotated 30 degrees, random, scanlines of 8 pixels; one
//! configuration each, 2048 requests or `--count`) in the eleven modes of `TB_CONFIGS` each, and
//! a short traced run along the clamped edges; it checks every
//! result against the reference and the golden model, requires all configurations bit-identical,
//! and reports the compression error separately (golden model of the original texture against the
//! hardware: worst 25 levels, mean 4.0). Misses are split into cold, capacity and conflict by a
//! fully-associative LRU shadow cache of four blocks fed the same references (Hakura and Gupta).
//!
//! What the table says (row-major, 512-word pages; all 66 rows in `report.md`):
//!
//! | trace | hit rate, no lookahead | misses cold / capacity / conflict | M pixels/s at 1 request/cycle: quadrant / direction / no lookahead / no cache | at 1 request per 4 cycles, hit rate: none / quadrant / direction | the same, M pixels/s | page faults / scanline (tiled) |
//! |---|---|---|---|---|---|---|
//! | horizontal, 32 px | 82.5 % | 91 / 469 / 0 | 44.5 / 45.3 / 42.4 / 9.1 | 82.5 / 82.5 / 91.9 % | 28.3 / 29.2 / 37.1 | 0.84 (0.02) |
//! | diagonal, 30 degrees | 78.3 % | 98 / 596 / 0 | 32.2 / 31.4 / 34.7 / 9.1 | 78.3 / 78.4 / 81.2 % | 25.0 / 25.2 / 26.2 | 1.94 (2.00) |
//! | random | 0.1 % | 2180 / 1034 / 1 | 5.5 / 5.3 / 7.3 / 7.3 | 0.1 / 0.1 / 0.1 % | 7.3 / 5.5 / 5.3 | 31.8 (31.0) |
//! | 8-pixel scanlines | 77.2 % | 192 / 415 / 190 | 33.2 / 34.7 / 31.9 / 8.4 | 77.2 / 80.4 / 84.1 % | 24.1 / 27.3 / 28.9 | 0.28 (0.06) |
//! | leftward, 32 px | 82.5 % | 91 / 455 / 0 | 44.5 / 47.1 / 43.8 / 9.4 | 82.5 / 82.5 / 92.4 % | 29.0 / 30.9 / 38.1 | 0.50 (2.00) |
//! | upward, 32 px | 81.6 % | 91 / 469 / 0 | 30.7 / 41.4 / 39.1 / 9.4 | 81.6 / 81.6 / 87.9 % | 26.8 / 29.1 / 35.4 | 3.00 (2.00) |
//!
//! The cache is worth 4-5x; the Figure 7 interleave leaves no conflict misses on long scanlines
//! (the short-scanline trace's conflicts come from jumping between lines); tiling removes nearly
//! all page faults of horizontal scanlines (not of these diagonal ones: a 64x64-texel tile is no
//! better than a 16-row page for them). Lookahead depends on the rasterizer's rate: a block fill
//! takes 13 cycles and a scanline crosses a block in about 5 pixels, so at one request per cycle
//! every preload arrives late (counted as `late_prefetches`) and the gain is a few percent; on the
//! diagonal and random traces the extra fills cost more than they save. At one request per 4
//! cycles the direction lookahead preloads in time: the horizontal hit rate rises from 82.5 to
//! 91.9 % and the speed by 31 %, while the quadrant lookahead, which waits for the point to reach
//! the second half of a block and also loads the row above or below, gains 3 %. Scanlines drawn
//! right to left or bottom to top gain as much (92.4 % and 87.9 %): the direction lookahead
//! preloads block `bx - 1`, which shares its cache entry with `bx + 1`, only once the footprint has
//! left `bx + 1` (before that rule, the leftward scan of `tb/tests/texture.rs` missed 10 times
//! with direction lookahead and 4 times without).
//!
//! ## The texture path's contract
//!
//! What an independent reference for `texread` and `ccc` needs, each rule with a worked example
//! (every example is checked by a test or reproduced with the commands above).
//!
//! 1. **Bilinear 622.** `W = 2^F` (`F` = `--frac-bits`, default 4); per channel, with `fu`, `fv`
//!    the fraction bits of `u`, `v` as integers in `0..W`: `top = c00 (W - fu) + c10 fu`,
//!    `bot = c01 (W - fu) + c11 fu`, `sum = top (W - fv) + bot fv` (exact), result
//!    `(sum + 2^(2F-1)) >> 2F`: one rounding, half up, never overflowing 8 bits. Example, `F = 4`,
//!    texels 10, 20 (top row), 30, 40 (bottom row), `fu = 4` (0.25), `fv = 8` (0.5): `top = 200`,
//!    `bot = 520`, `sum = 5760`, `(5760 + 128) >> 8 = 23` (the exact value 22.5 rounds up).
//! 2. **The zero-weight neighbour is fetched.** The footprint is always texels `x0, x1 =
//!    min(x0 + 1, width - 1)` and `y0, y1 = min(y0 + 1, height - 1)`, whatever the weights: `u =
//!    3.0, v = 1.0` (`fu = 0`) references blocks `(0, 0)` and `(1, 0)`: `block_refs` 2 for one
//!    request.
//! 3. **Lookup and fill order.** A footprint's blocks are looked up top row first, left to right
//!    (`(bx0, by0)`, `(bx1, by0)`, `(bx0, by1)`, `(bx1, by1)`, duplicates left out); the first
//!    missing one in that order is filled, then the request looks up again (one fill at a time).
//!    The shadow cache sees the same order, which sets the cold / capacity / conflict split.
//!    Example: a cold request at `(3, 3)` (both weights zero, rule 2) fills `(0, 0)`, `(1, 0)`,
//!    `(0, 1)`, `(1, 1)` in that order: 23 cycles for the first and 13 for each further one
//!    (`miss_penalty_hit_throughput_and_page_faults` in `tb/tests/texture.rs`).
//! 4. **Tiles.** `--layout tiled` uses tiles of `tw x th` blocks filling one page exactly: `tw =
//!    2^ceil(lg/2)`, `th = blocks per page / tw` with `lg = log2(page words / 2)`. With `--dram
//!    256k` (512-word pages, 256 blocks) a tile is 16 x 16 blocks = 64 x 64 texels; with `--dram
//!    1m` (1024-word pages, 512 blocks) 32 x 16 blocks = 128 x 64 texels. Tiles are stored
//!    row-major, `ceil(bw / tw)` per tile row, blocks row-major inside a tile with the tile's
//!    width as stride, so a texture narrower than a tile uses the left part of each tile row and
//!    leaves the rest of the page unused. Example: a 32 x 32 texture (8 x 8 blocks) in 512-word
//!    pages is one tile; block `(bx, by)` is at word `2 (16 by + bx)`, and words `2 (16 by + 8)`
//!    to `2 (16 by + 15) + 1` of each block row are unused.
//! 5. **Which neighbours are preloaded, and when.** Candidates are taken when a request
//!    completes (all its blocks present), never for a request flagged `newline` (the first point
//!    of a scanline); a `newline` request's first lookup and every demand fill empty the queue;
//!    the queue is filled into the fill engine one candidate per free cycle when stage 0 needs
//!    nothing; a candidate the cache holds is dropped (`prefetch_dropped`); a candidate that would
//!    go into the entry of another block of the completing footprint is not queued (a preload
//!    never evicts a block the footprint uses). `quadrant`: from the request's integer texel
//!    `x0 = floor(u)`, `y0 = floor(v)` in block `(bx, by)`: `dx = +1` if bit 1 of `x0` is set, else
//!    `-1`, likewise `dy` from bit 1 of `y0`; candidates `(bx + dx, by)`, `(bx, by + dy)`,
//!    `(bx + dx, by + dy)`, those outside the texture left out. Example: `(5.2, 2.9)`: `x0 = 5`
//!    (bit 1 clear, `dx = -1`), `y0 = 2` (bit 1 set, `dy = +1`), block `(1, 0)`: candidates
//!    `(0, 0)`, `(1, 1)`, `(0, 1)`. `direction`: `dx`, `dy` are the signs of `u - u_prev`,
//!    `v - v_prev` (full `uQ12.F` values) against the previous completed request, whatever its
//!    scanline (after a `newline` request, that request is the previous point); candidates
//!    `(bx + dx, by)` if `dx != 0`, `(bx, by + dy)` if `dy != 0`, the diagonal if both. Example:
//!    `(5.2, 2.9)` then `(6.0, 2.9)`: `dx = +1`, `dy = 0`: candidate `(2, 0)` only.
//! 6. **Inside the texture is checked after rounding.** `u`, `v` are rounded to `uQ12.F` (to
//!    nearest, ties to even) first; the rounded value must satisfy `0 <= u < width`. Example,
//!    16 x 16 texture, `F = 4`: `u = 15.99` rounds to 16.0 and is refused: `r.csv:2: u 15.99
//!    (rounded to 16) outside the texture (0 <= u < 16)`; `u = 15.96` rounds to 15.9375 and is
//!    read.
//! 7. **`scanlines`** counts accepted requests that are the first of the trace or flagged
//!    `newline` (the first request counts once, flagged or not); an empty trace gives 0.
//!    Example: rows `1,1,0`, `2,1,0`, `1,2,1` give 2; rows `1,1,1`, `2,1,0` give 1.
//! 8. **Every `--stats` field** is listed below, with its unit (and in `texrtl texread --help`).
//! 9. **`ccc encode`'s figures.** PSNR over every channel of every texel of the original PPM
//!    against the reference decode: `10 log10(255^2 / MSE)` dB, infinite when they are equal;
//!    "worst texel error" is the largest absolute difference of one channel of one texel, in
//!    levels. Example: a texture whose every block has at most two colours from a small palette
//!    decodes exactly, so PSNR is infinite and the worst error 0 (a property test in
//!    `tb/tests/texture.rs`).
//! 10. **Ties in the encoder.** A texel on the split plane (`|d . e| <= 10^-6` levels) goes to
//!    cluster a (bit 0); a block of one colour has an empty cluster b, so both colours are the
//!    block's colour and every bit is 0; in the final re-choice a texel takes colour b only when
//!    it is strictly nearer to the quantised b (a tie keeps a). Example: a 4 x 4 block of one
//!    grey encodes as `a = b` (same CLUT index) and decision bits `0x0000`.
//! 11. **Option messages name the option.** `--frac-bits 0` is refused with `texrtl:
//!    --frac-bits 0: 1..=8` (before the texture is read).
//!
//! `--stats` JSON of `texrtl texread` (counts of blocks are 4 x 4-texel blocks, two DRAM words
//! each):
//!
//! | field | unit | meaning |
//! |---|---|---|
//! | `requests` | requests | requests accepted from the rasterizer |
//! | `interval` | cycles | cycles between requests the rasterizer offers (`--interval`) |
//! | `cycles` | controller cycles | from the first request offered to the last result out, inclusive |
//! | `cycle_ns` | ns | one controller cycle (5) |
//! | `ns` | ns | `cycles * cycle_ns` |
//! | `pixels_per_second` | 1/s | `requests / ns` |
//! | `layout` | - | `row-major` or `tiled` |
//! | `cache` | bool | cache 614 on |
//! | `lookahead` | - | `quadrant`, `direction` or `off` (`off` whenever the cache is) |
//! | `page_words` | words | DRAM page (row) size |
//! | `block_refs` | blocks | blocks the requests referenced (1, 2 or 4 each), at their first lookup |
//! | `hits` | blocks | of those, found in the cache at the first lookup |
//! | `hit_rate` | fraction | `hits / block_refs` |
//! | `misses` | blocks | `block_refs - hits` |
//! | `misses_cold`, `misses_capacity`, `misses_conflict` | blocks | the misses split by a 4-block fully-associative LRU shadow cache: never seen / evicted there too / held there |
//! | `demand_fills` | blocks | fills started because a request needed the block |
//! | `prefetch_fills` | blocks | fills started from the lookahead queue |
//! | `prefetch_hits` | blocks | hits, at a request's first lookup, on a block a prefetch brought in and no request had used |
//! | `late_prefetches` | blocks | misses, at a request's first lookup, on the block a prefetch fill was fetching |
//! | `prefetch_dropped` | blocks | lookahead candidates taken from the queue and dropped because the cache held them |
//! | `stall_cycles` | cycles | cycles a request sat in stage 0 without completing |
//! | `dram_reads` | words | DRAM word reads (two per fill) |
//! | `page_hits`, `page_faults` | reads | reads in the open row / that opened another row |
//! | `scanlines` | scanlines | see 7 above |
//! | `page_faults_per_scanline` | faults | `page_faults / scanlines` (0 scanlines: divided by 1) |
//! | `violations` | count | timing or protocol violations the DRAM model saw (0) |

pub mod bilinear_622;
pub mod cache_614;
pub mod ccc_decode_608;
pub mod control_607;
pub mod dram_604;
pub mod extract_618;
pub mod layout;
pub mod texture_unit_602;
