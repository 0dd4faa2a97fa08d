//! Footprint assembly (Schilling & Knittel section 10, Figures 12 and 13): anisotropic
//! filtering by N trilinear accesses along the longer edge of the pixel's footprint.
//!
//! * [`setup_fig12`](crate::footprint::setup_fig12): the rasterizer-side setup unit (eqs 19-21): N, the step and the level
//!   of detail from the screen derivatives, with no square root or division;
//! * [`assembly_fig12`](crate::footprint::assembly_fig12): the chip-side sample generator (eq. 22) and accumulator in front of
//!   the TEXRAM chip 802: N accesses a pixel, the exact sum of their trilinear sums, one
//!   rounding of the mean, and the same at transaction level over any `TexramAccess`;
//! * [`footprint_fig12`](crate::footprint::footprint_fig12): the two together in front of the chip;
//! * [`normals_0081`](crate::footprint::normals_0081): the generator in front of the FIG. 7 height-map pipeline, whose
//!   tangents are averaged over the samples and normalised once (Fenney para. 0081).
//!
//! ## Footprint assembly (Schilling & Knittel, section 10, Figures 12-13)
//!
//! Anisotropic filtering by N trilinear accesses along the longer edge of the pixel's
//! footprint. `hdl/units/src/footprint/`: the **setup unit** on the rasterizer side
//! (`setup_fig12.rs`), the **sample generator and accumulator** on the chip side
//! (`assembly_fig12.rs`, in front of the TEXRAM chip 802) and the two together
//! (`footprint_fig12.rs`); golden `golden/src/footprint.rs`; testbench `footprint_fig12`
//! (`tb/src/footprint.rs`), tests `tb/tests/footprint.rs`, command `texrtl footprint`.
//!
//! The pages defining d1, d2 and lambda are missing from the seed; the readings are the notes'
//! (\[C\], `../shared/notes/seed-systems.md` section 2):
//!
//! | step | what the model does |
//! |---|---|
//! | eq. 19 | `q = min(\|r1\|, \|r2\|, d1, d2)` with the diagonals `d1 = \|r1 + r2\|`, `d2 = \|r1 - r2\|` \[C\]; squared lengths only (no square root), exact: r1, r2 sQ11.8, squares uQ25.16 |
//! | eq. 20 | `N = max(\|r1\|, \|r2\|) / q` to the nearest power of two in the log domain (the least k with `m^2 < q^2 2^(2k+1)`, exact compares), or in the linear domain (`--rounding linear`: `4 m^2 < 9 q^2 4^k`); at most 16 (`--max-n`, up to 64); no footprint gives 1, a collapsed one the most |
//! | eq. 21 | `dr = r / N` along the longer edge (r1 on a tie): `r << (6 - k)`, exact in sQ11.14 |
//! | lambda | `log2 q` \[C\] = `1/2 log2 q^2`: leading one of `q^2`, the six bits after it (truncated) into a 64-entry table of `log2(1 + i/64)` in Q.8 (made by integer squaring), halved half up, held to -4..10; exact at powers of two, within 0.0141 levels (derived; measured 0.0113) |
//! | eq. 22 | `p_n = p + (n/2) dr` for `n = -(N-1), -(N-3), ..., N-1` (the printed `n = +-1, +-3, ...` gives even N only; N = 1 samples p): `p_0 = p - (N-1) dr/2`, then `+ dr`, exact in sQ16.15; each rounded half up to the chip's sQ12.8 |
//! | accumulator | the N accesses' exact trilinear sums (818's `out_sum`, before its rounding) added in uQ14.24, one rounding of the mean: `(S + 2^(23+k)) >> (24+k)` |
//!
//! Timing: the setup unit is one register stage with ready/valid; the generator takes a pixel
//! when free and offers a sample a cycle to the chip, which takes one a slot; the accumulator
//! counts results against the N of the pixels in flight (at most six; the generator waits for
//! room), so the setup of pixel i+1 overlaps the assembly of pixel i and the chip never waits.
//! Luminance maps on the TEXRAM \[C\] (818's exact sum is the luminance one).
//!
//! **On Figure 6's texture unit 602** (the document's low-cost system, "bilinear interpolation,
//! CCC and footprint assembly", section 4): the same setup, generator and accumulator drive the
//! texture unit through the `SampleTarget` trait (`FootprintFig12<TextureUnit>`): each sample
//! point less half a texel (the unit samples texel x at x), rounded half up to its F fraction
//! bits and held inside the texture (the unit clamps to the edge); the accumulator adds 622's
//! exact sums (now on its registers `sum_r`, `sum_g`, `sum_b`, 2F fraction bits) per channel
//! and rounds each mean once. There is no mipmap, so lambda is unused and a square wider than a
//! texel is point-sampled by the bilinear filter: the low-cost system's quality limit.
//!
//! **Checks.** The setup unit against the f64 setup (real square roots and logarithms) on
//! 200,000 random derivative pairs in each rounding mode: the same N except within 2^-20 of a
//! threshold (7 of 100,000 in the log domain, all at a threshold; 0 in the linear), the same
//! step, lambda within its bound. The sample offsets sum to exactly zero for every N. An
//! isotropic footprint gives N = 1 and exactly the trilinear access. The transaction-level
//! assembly on the stub and on the cycle-accurate chip are equal pixel by pixel and slot by slot,
//! bit-exact against an integer reference (its own setup, sample points and sums over
//! `RefMipmap`; on the texture unit over the CCC reference's exact bilinear sums), on the
//! TEXRAM each result inside the min/max of the texels read. The regress testbench (`footprint_fig12`, six
//! configurations: on the TEXRAM 64x64 wrap, 256x256 mirror, 64x32 clamp with N <= 64 and
//! linear rounding, 32x8 border colour with N <= 4; on the texture unit 64x64 CCC with F = 4 and
//! its cache, 32x16 with F = 8 and no cache, N <= 64) drives random pixels (footprints from
//! 1/16 to 64 texels, anisotropy 1 to 32, any direction, sheared) with random gaps through the
//! setup unit, scores each against the reference (value and N) and the f64 mean of the chip's
//! accesses (bound 0.5 LSB, measured 0.500), and covers N x lambda class (magnified, between
//! levels, last level), N x unit, borders and rounding.
//!
//! **The quality claim, measured** (regress report, `footprint_quality.png`): a 1024x1024 checker
//! with lines of text-like one-texel strokes on a plane seen at 0, 60, 75 and 85 degrees, 64x64
//! pixels (those whose footprint is at most 128 texels long), both filters on the TEXRAM stub,
//! against the mean of level 0 over each pixel's exact parallelogram (stratified bilinear
//! samples, at least two a texel along each edge):
//!
//! | plane tilt | pixels | RMSE trilinear (LSB) | RMSE footprint assembly (LSB) | mean N | slots | bank faults | M pixels/s |
//! |---|---|---|---|---|---|---|---|
//! | 0 | 4096 | 7.82 | 7.82 | 1.00 | 4160 | 244 | 32.82 |
//! | 60 | 4096 | 11.96 | 4.38 | 2.00 | 16256 | 25106 | 8.40 |
//! | 75 | 4096 | 16.52 | 5.24 | 3.29 | 26654 | 52744 | 5.12 |
//! | 85 | 3968 | 14.72 | 2.60 | 8.19 | 60921 | 99982 | 2.17 |
//!
//! Footprint assembly beats isotropic trilinear at every tilt but 0 (where both are one access
//! and equal), by 3x at 75 degrees and 5.7x at 85. The rate is not 33.3 M / mean N: the samples
//! step along the plane's depth, across texture rows, so nearly every access opens new rows
//! (`the number of page faults per scanline will increase`, section 5): at 60 degrees two
//! accesses a pixel take 3.97 slots, 8.4 M pixels/s instead of 16.7 M. This is the row layout's
//! cost (a row holds two level-0 lines of a 1024-wide map); a tiled row layout would recover
//! some of it (not modelled).
//!
//! Bit-accuracy vectors (`golden/vectors/footprint_fig12.json`, checked by every regress): 256
//! hashed pixels through the setup unit and the generator and accumulator on the TEXRAM chip
//! (wrap and mirror) and on the texture unit 602: `(config, u, v, r1, r2) -> N, R, G, B`.
//!
//! `texrtl footprint --texture T --requests R.csv --out O.csv \[--unit texram|texture\] \[--max-n
//! N\] \[--rounding log|linear\] \[--border ...\] \[--stats S.json\] \[--vcd W.vcd\]`: T is a PGM
//! (texram) or a PPM or .ccc (texture); R has `u,v,dudx,dvdx,dudy,dvdy`; O gets those (as
//! quantised) and `n,lambda` and `value` (texram) or `r,g,b` (texture); every pixel is checked
//! against the integer reference before it is written (a difference is exit 1). S holds
//! `pixels`, `accesses`, `mean_n`, `page_faults`, `cycles`, `ns`, `pixels_per_second`, and on
//! the TEXRAM `slots` and `bank_misses`.
//!
//! **On the FIG. 7 height-map pipeline** (Fenney para. 0081, "improved anisotropic filtering";
//! `footprint/normals_0081.rs`, `bump/tangent_average_0081.rs`): the same generator feeds the
//! pipeline one sample a clock (it has no backpressure; a pixel of N samples takes N clocks, the
//! next pixel taken as the last sample goes in), and a tangent-average stage between tangent
//! unit 155 and normal unit 156 adds up each pixel's `du`, `dv` and height (six more integer
//! bits) and hands 156 their mean with the pixel's last sample, `(sum + 2^(k-1)) >> k` (round
//! half up), in the tangent format: one normalisation a pixel \[C\]. The pipeline without the
//! stage is unchanged (its Verilog twin still matches). Checked: the average is, bit for bit,
//! the integer mean of the plain pipeline's tangents at the reference's own sample points (400
//! random pixels and their N = 1 versions); with N = 1 the normals are the plain pipeline's,
//! bit for bit; the regress testbench `footprint_normals_0081` (B-spline, Blinn and Bezier
//! filters over four borders, random pixels with random gaps) scores every normal within normal
//! unit 156's derived tolerance (0.89 LSB; measured at most 0.75) of the f64 normal of the
//! averaged tangents, and the height equal to the averaged height; coverage N x filter,
//! borders. Level 0 only (the trilinear variant is not driven) \[C\].

pub mod assembly_fig12;
pub mod footprint_fig12;
pub mod normals_0081;
pub mod setup_fig12;
