//! Volume rendering on the TEXRAM chip (Schilling & Knittel section 13, Figure 15): "only
//! the four larger memory arrays in the TEXRAM holding level 0" (banks 810, 0-3) as a voxel
//! store, a 3-D sample stepper (the footprint generator of section 10 in three dimensions)
//! and the trilinear interpolator, reading the eight voxels round a resample point in two
//! accesses ("value mode"), or the 32 voxels its central-difference gradient needs in eight
//! ("gradient mode"). Compositing is off-chip (the golden model has one).
//!
//! * [`layout`](crate::volume::layout): voxel `(x, y, z)` to bank and word, the border operation, the accesses of a
//!   resample point in each mode (each reads four voxels from four different banks: proved
//!   exhaustively in its tests);
//! * [`interp`](crate::volume::interp): the value and gradient arithmetic of one resample point;
//! * [`ray_caster_fig15`](crate::volume::ray_caster_fig15): the cycle-accurate ray caster: ray port, stepper, accesses through
//!   the page registers, interpolation, sample port;
//! * [`lockstep`](crate::volume::lockstep): pre-classified RGBA on four chips in lock-step.
//!
//! The document gives the data path and two timings; the rest is \[C\] (see
//! `../shared/notes/seed-systems.md` section 3, and below).
//!
//! ## Volume rendering (Schilling & Knittel, section 13, Figure 15)
//!
//! "Using the memory arrays and the hardware units for footprint assembly and mipmapping
//! differently, the TEXRAM turns into a complete ray-casting machine": `hdl/units/src/volume/`
//! (`layout.rs` the voxel store and the accesses, `interp.rs` the arithmetic,
//! `ray_caster_fig15.rs` the cycle-accurate caster, `lockstep.rs` RGBA on four chips); golden
//! `golden/src/volume.rs` (f64 trilinear, the central-difference field, a front-to-back
//! compositor, which the document leaves to the host); testbench `ray_caster_fig15`
//! (`tb/src/volume.rs`), tests `tb/tests/volume.rs`, command `texrtl volume`. The document gives
//! the data path and two timings; the rest is \[C\]:
//!
//! | value | format / rule |
//! |---|---|
//! | voxel store | banks 0-3 (level 0's), 8-bit voxels, voxel (x, y, z) in bank `2 (y & 1) + (x & 1)`; words column-major `((y >> 1)(X/2) + (x >> 1)) Z + z` (default) or slice-major `z (X/2)(Y/2) + ...` (as level 0 stores a texture); X, Y even <= 256, Z <= 256, at most 280,064 words a bank |
//! | borders | indices reflected without repeating the edge voxel (`-1 -> 1`): a reflection keeps parity, so every access reads four different banks at every position (the notes' clamp would read -1 and 2 from one bank at the edge) |
//! | positions | sQ9.12, voxel i at i; the stepper adds the step exactly (sQ19.12 registers) |
//! | weights | the fractions truncated to 8 bits, as the texture path's |
//! | value mode | 2 accesses: the 2x2 at slices k and k+1; the exact sum rounded once half up to u8 |
//! | gradient mode | 8 accesses: also columns i-1, i+2 (rows j, j+1) and rows j-1, j+2 (columns i, i+1) at k and k+1, and the 2x2 at k-1 and k+2; central differences without the 1/2 at the eight corners, the same weights, rounded once to sQ9.4 |
//! | access order | gradient mode alternates `1 2 7 8 3 4 5 6` and `5 6 3 4 7 8 1 2` from sample to sample, so consecutive samples meet in the same rows: one row switch a sample instead of two |
//! | timing | one access a 30 ns slot, two when a bank has another row open (page registers 824, rows of 512 words by default); a sample's result the cycle after its last access |
//!
//! **Checks.** Exhaustively on four small volumes (down to 2x2x1), both word orders: every
//! access of every resample point, inside and one voxel beyond every face, reads four different
//! banks, and no two voxels share a word. The ray caster against an integer reference (plain
//! loops, its own reflection and weights) bit for bit, value within 0.5 LSB of the f64 trilinear
//! at the weight-quantised point (measured 0.500), and its slots equal to the page-register
//! model's count; a linear field gives the value within 0.5 LSB and the gradient exactly (2a, 2b,
//! 2c) wherever the neighbours are inside. The testbench (five configurations: both orders,
//! both modes, rows of 16 to 512 words, volumes down to 2x2x1) drives random rays (in, through
//! and beside the volume, steps up to 1.5 voxels) with random gaps and covers mode x position
//! (interior, at a face, outside), word order and page faults. Four chips in lock-step on a
//! classified built-in volume (`volume_render.png` in the report, composited by the golden
//! model): every sample's four components equal the reference of their planes. Bit-accuracy
//! vectors: `golden/vectors/ray_caster_fig15.json` (586 samples in both modes).
//!
//! **The document's timings, from the page registers** (regress report): one resample per voxel
//! at the voxel centres shifted by half a voxel, rays along x, the rays in y-then-z order:
//!
//! | figure | samples | accesses | slots | time | document |
//! |---|---|---|---|---|---|
//! | RGBA 64x128x128, four chips in lock-step (one component each, the same slots), value mode | 1,048,576 | 2,097,152 | 2,342,912 | 70.3 ms | about 70 ms |
//! | 256x128x128 with gradients, four chips in parallel, each a slab of 64 (+2 overlap) x 128 x 128 | 1,048,576 | 8,388,608 | 10,423,168 | 312.7 ms | about 0.28 s |
//!
//! Both within 15 % with **column-major voxel words, 512-word rows and rays along x**: the value
//! mode's 11.7 % extra slots are the row changes every eight samples along x (the document's
//! 62.9 ms ideal and 70 ms imply 11.3 %); gradient mode's 24 % are one row switch a sample to
//! the y neighbours' columns (with the alternating order; 36 % without it) and the row changes.
//! The sweep behind the choice (release build; value ms, gradient ms):
//!
//! | words | rows | rays along x | along y | along z |
//! |---|---|---|---|---|
//! | slice-major | any of 256-2048 | 125.8, 502.7 (every access faults: a sample's two slices are in different rows) | 125.8, 502.7 | 94.6, 502.9 |
//! | column-major | 256 | 78.2, 334.2 | 94.1, 341.7 | 63.0, 310.6 |
//! | column-major | 512 | **70.3, 312.7** | 94.1, 329.9 | 63.0, 298.8 |
//! | column-major | 1024 | 66.4, 298.1 | 94.1, 322.1 | 62.9, 290.9 |
//! | column-major | 2048 | 64.4, 290.9 | 94.1, 318.2 | 62.9, 287.0 |
//!
//! Rays along z with column-major words never leave a row in value mode (0.1 %): the document's
//! 11 % says its rays did cross rows, as rays along x do. Splitting the original data into four
//! slabs along x costs two voxel planes of overlap a chip (3 % of each chip's capacity).
//!
//! `texrtl volume --volume V.raw --dims X,Y,Z --rays R.csv --out O.csv \[--gradient\] \[--order
//! column|slice\] \[--row-words N\] \[--stats S.json\] \[--vcd W.vcd\]`: V is X*Y*Z raw bytes (x
//! fastest); R has `x0,y0,z0,dx,dy,dz,steps`; O gets `ray,k,x,y,z,value` (+ `gx,gy,gz`) per
//! sample, each checked against the integer reference before it is written; S holds `rays`,
//! `samples`, `accesses`, `slots`, `fault_slots`, `bank_misses`, `cycles`, `ns`,
//! `samples_per_second`.

pub mod interp;
pub mod layout;
pub mod lockstep;
pub mod ray_caster_fig15;
