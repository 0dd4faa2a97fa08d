//! Schilling & Knittel's TEXRAM chip (Figure 8): eight banks 810 holding a mipmap in the
//! two-level layout, so that the eight texels of any trilinear footprint (a 2x2 at level L and
//! a 2x2 at level L+1) are read in one access slot of 30 ns.
//!
//! The chip's transaction-level interface, the arithmetic its units share, the cycle-accurate
//! chip built on them and a behavioural stub:
//!
//! * [`TexramAccess`](crate::texram::TexramAccess): one access, `(DRF, u, v, lambda) -> 8 texels, weights, slots, faults`,
//!   the interface the footprint assembly, the volume stepper and the map chain are written
//!   against;
//! * [`address_812`](crate::texram::address_812): the address and control unit's arithmetic: level, weights and the
//!   border operations (wrap, clamp, mirror, border colour) of one access;
//! * [`banks_810`](crate::texram::banks_810): the two-level layout, texel `(level, x, y)` to bank and word (the bank
//!   address decoders 822), proved conflict-free by exhaustive tests;
//! * [`page_registers_824`](crate::pages::page_registers_824) (shared with the units that read banks like these): one open row per bank; an access costs one slot, two if any bank
//!   it reads misses its open row;
//! * [`trilinear_818`](crate::texram::trilinear_818): the trilinear interpolator, one rounding of the exact weighted sum;
//! * [`clut_814`](crate::texram::clut_814): the colour look-up table of the index configuration, filtered after look-up;
//! * [`output_820`](crate::texram::output_820): the output stage's eq. 5, `C_d = (I_d | k_T | 1) . T`;
//! * [`video_port_808`](crate::texram::video_port_808): the video port with the mipmap generator 816 on the banks and the
//!   shift registers 826, stealing slots from the rasterizer;
//! * [`texram_802`](crate::texram::texram_802): the chip cycle by cycle (request port, 812, 824, 810, 818, 820, the video
//!   port), and `Texram802Access`, the chip behind [`TexramAccess`](crate::texram::TexramAccess);
//! * [`lockstep`](crate::texram::lockstep): one colour component per chip, four chips in lock-step;
//! * [`stub`](crate::texram::stub): [`stub::TexramStub`](crate::texram::stub::TexramStub), a behavioural model of the chip made of the above, exact
//!   in its texels, weights, result and slot count but not cycle by cycle (every
//!   configuration; the video port as single row transfers).
//!
//! ## The TEXRAM chip (Schilling & Knittel, Figure 8)
//!
//! `hdl/units/src/texram/` holds the chip's access path cycle by cycle, its configurations, and the
//! interface footprint assembly, volume rendering and the map chain are written against. Formats and choices (\[C\]: the document is silent; see
//! `../shared/notes/seed-systems.md` section 1):
//!
//! | value | format | note |
//! |---|---|---|
//! | u, v | sQ12.8 | level-0 texel units (texel centres at k + 0.5) \[C\] |
//! | lambda | sQ5.8, -4.0 ..= 10.0 | L = floor, held to 0 ..= Lmax; f = fraction (0 below 0 and at Lmax) |
//! | a, b, f | u8, truncated | `u_k = u 2^-k - 1/2`: i its floor, a its fraction's top 8 bits \[C\] |
//! | texel, result | u8 | 818: `(sum + 2^23) >> 24` of the exact weighted sum, one rounding \[C\] |
//! | eq. 5 (820) | u8 | `x . y = round(x y / 255)` exact: `t = xy + 128; (t + (t >> 8)) >> 8` \[C\] |
//! | bank word | 19 bits | banks 0-3: 547 rows of 512 words, banks 4-7: 137 rows (one 1024x1024 mipmap) \[C\] |
//!
//! * **Layout** (`banks_810.rs`): texel (x, y) of level L in bank `4 (L & 1) + 2 (y & 1) + (x & 1)`,
//!   word `base + offset(L) + (y >> 1) ceil(W_L / 2) + (x >> 1)`; even levels in banks 0-3, odd in
//!   4-7 \[C: the only reading with a trilinear pair for every L\]. A test proves for every
//!   2x2 position (inside the map and two texels beyond), every level, every border operation
//!   (wrap, clamp, mirror, border colour) of 64x64, 1x32, 32x1, 8x2, 2x16 and 1x1 maps that no bank
//!   is asked for two words in one access, and that no two texels share a bank word.
//! * **Timing** (`texram_802.rs`): 5 ns clock, a 30 ns slot is 6 cycles; 812 takes a request while
//!   the banks serve the previous one; an access takes one slot, two when any bank it reads misses
//!   its open row (page registers 824; reads never modify a row, so no precharge is waited for).
//! * **Configurations** (section 6): luminance; index (CLUT 814, 256 x 32 bits, eight ports, each
//!   component filtered after the look-up); planar colour \[C, the default colour reading\]: four
//!   component planes in the quadrants of a square space, four accesses a pixel, conflict-free;
//!   the literal colour layout as printed (R, G, B, alpha in a 2x2 cell): a component's 2x2 lies
//!   in one bank, read in up to four rounds, counted as conflicts (and the generator's 2x2 average
//!   mixes the components at the upper levels: the document's error, visible in the results);
//!   one component per chip: four chips 802 in lock-step (`lockstep.rs`), one pixel a slot.
//!   Planar, lock-step and per-plane luminance agree component by component; literal agrees at
//!   level 0; index with the identity table equals luminance.
//! * **`TexramAccess`** (`mod.rs`): `(DRF, u, v, lambda) -> 8 texels, weights, value, rgba,
//!   slots, faults`; implemented by `stub::TexramStub`, a behavioural model of the same
//!   arithmetic (all configurations, and the video port's row transfers), and by
//!   `texram_802::Texram802Access`, the cycle-accurate chip clocked per access: code written
//!   against the interface runs on either, and a test holds them equal access by access.
//! * **Checks** (`tb/tests/texram.rs`, testbench `texram_802` in regress): bit-exact against an
//!   integer reference with its own addressing (plain loops over levels) on 10^6 random requests
//!   over five map shapes and four border operations; within 0.5 LSB of the f64 golden model with
//!   the truncated weights (measured: 0.5000 LSB, half-way cases); inside the min/max of its eight
//!   texels; integer lambda gives the bilinear of that level; the cycle-accurate chip equals the
//!   stub texel for texel and slot for slot in every configuration, one result per slot (two after
//!   a fault). The testbench (11 configurations: four borders, five map shapes down to 1x32,
//!   index, planar and literal colour) drives directed requests (every lambda class and level
//!   range, inside and beyond the map, a page hit) then random ones with random gaps through the
//!   chip's `req_ready`, scores each result, and covers border x lambda class, levels, positions
//!   beyond the edges, page faults and configurations; bit-accuracy vectors
//!   (`golden/vectors/texram_802.json`, 1,280 requests) are checked by every regress.
//! * **Video** (sections 11-12): see "Video on the chip" below: cycle by cycle, interlaced
//!   1024x512 at 25 frames a second costs the rasterizer 0.144 % of its accesses; at stub level,
//!   768x576 (each row transfer a slot of its own) 0.51 %.
//! * **The document's rates, from the page registers** (regress report, measured on the chip):
//!
//! | stream | pixels | slots | M pixels/s | document |
//! |---|---|---|---|---|
//! | one access per pixel, no page fault | 1000 | 1001 | 33.30 | 33.3 |
//! | 8 pixels and 2 page faults per scanline | 1600 | 2000 | 26.67 | about 27 |
//! | 2 accesses per pixel (texture + environment), no fault | 1000 | 2001 | 16.66 | 16.7 |
//! | 4 accesses per pixel (all colours on one chip) | 1000 | 4001 | 8.33 | 8.3 |
//! | texture + environment maps in different rows of the same banks | 1000 | 4000 | 8.33 | - |
//!
//!   The last row is a finding of the page-register model: the document's 16.7 M for texture +
//!   environment holds only when both maps' accesses hit the open rows; two maps in different
//!   rows of the same banks reopen them on every access, which halves the rate again. The same
//!   holds for colour on one chip: the 8.3 M (four accesses a pixel) needs the four component
//!   accesses in open rows, but the planar layout's top and bottom quadrants lie in different
//!   rows, so a pixel's R, G, B, alpha switch rows twice: 6 slots a pixel, 5.6 M pixels/s
//!   (`texram_slots.svg` in the report; the literal layout 17 slots a pixel). An order that
//!   alternates R G B A with A B G R from pixel to pixel would save one switch; left open.
//!
//! `texrtl texram --texture T.pgm|T.ppm --requests R.csv --out O.csv \[--config luminance|index|
//! planar|truecolor\] \[--border wrap|clamp|mirror|border:N\] \[--stats S.json\] \[--vcd W.vcd\]`: R has
//! `u,v,lambda`; O gets `u,v,lambda,r,g,b,a` in request order (luminance in all four); S holds
//! `requests`, `accesses`, `slots`, `page_faults` (the slots they added), `bank_misses`,
//! `bank_conflicts`, `video_slots`, `cycles`, `ns`, `pixels_per_second`. Every result is checked
//! against the integer reference (luminance) or the stub (colour) before it is written. Index
//! mode \[C\]: a PPM of at most 256 colours, its palette (first appearance) in the CLUT; the upper
//! levels are made by the host, each texel the palette entry nearest the rounded mean colour of
//! the 2x2 below it (the generator 816 averages values, which means nothing for indices).
//!
//! Eq. 5 (`output_820.rs`) is in the chip's output stage: the DRF's `modulate` (I_d, k_T or 1)
//! times R, G, B, with the rasterizer's `req_illum`; alpha passes \[C\].
//!
//! ### Video on the chip: port 808, generator 816 on the banks, shift registers 826
//!
//! `Texram802::attach_video(VideoParams)` gives the chip its video port (`video_port_808.rs`,
//! scope `texram_802.video_port_808`): texels enter at the serial port, the generator 816 of
//! FIG. 14 (the unit of `mipmap/`, unchanged but for its frame store, which is now the chip's
//! banks) makes the upper levels, and every line reaches its banks through the shift registers
//! 826 and page registers 824 in slots taken from the rasterizer. The model (\[C\], the document
//! gives the data path only):
//!
//! * A line of level k goes to the two banks of its row parity, even columns to one, odd to the
//!   other: two **row segments**, each split where it would cross a DRAM row. Level 0 is
//!   collected in the shift registers as it arrives; an upper level's line comes out of its
//!   FIFO 1412 when complete.
//! * A finished segment is loaded in parallel into one of `queue` **row buffers** (default 32:
//!   at the end of a frame a line of every level finishes within a few cycles, 24 segments for
//!   1024x1024; `max_buffered` records the most a run used). A **bank round** takes the oldest
//!   waiting segment of every bank, in one 30 ns slot, two when one of those banks has another
//!   row open; the page register then holds the written row, so the rasterizer's next access
//!   there faults. The port goes first at a slot boundary (video cannot wait); a waiting
//!   rasterizer access is held (`req_ready` low).
//! * Interlaced video: before each line of the second field, the partner line of the first field
//!   is read from the banks into the shift register (two read segments through the same
//!   buffers). The source must leave the line blanking this needs: typically 2-4 slots, at worst
//!   about 72 cycles (360 ns; PAL's blanking is 12 us). A second-field texel before its partner
//!   line is in is an **underrun** (sticky `err_code` 2, a test shows it with no blanking; a
//!   partner read asked for while the last is still waiting is one too); a segment with every
//!   buffer full an **overrun** (1), and so is a line of frame f written while frame f - 2, in
//!   the same map, is not ready yet: the banks are taken each in its own order, so with frames
//!   very short (one texel wide, a cycle of line blanking) the last segments of frame f - 2 can
//!   still be waiting when frame f starts to overwrite them.
//! * Frames go alternately into the maps of two DRFs (`drfs`, default 0 and 1), so the rasterizer
//!   reads a complete mipmap while the next is made; a frame is **ready** (`frames_ready`) when
//!   every segment up to its last is in the banks.
//! * Counted on the chip: `video_port_808.shift_registers_826.transfers` (segments) and
//!   `video_slots` (the slots stolen from the rasterizer), which are also in the chip's `slots`
//!   (`slots = accesses + fault_slots + video_slots`, checked).
//!
//! Checks (`tb/tests/texram_video.rs`; testbench `video_port_808` in regress, six configurations:
//! 32x16 interlaced both field orders, 16x16 progressive, 64x2 interlaced, 1x8 progressive,
//! 128x64 interlaced with map 1 placed off a row boundary so that lines split; three frames each,
//! so both frame buffers and a reuse): each frame's mipmap read back from the banks when the chip
//! reports it ready equals the integer reference (`RefMipmap`, its own loops) level by level; the
//! rasterizer's results while the video runs (2,000 random requests to a third map, random gaps)
//! equal the stub's; the slots add up; the row transfers are exactly the segments the frames'
//! lines and partner reads make (counted from the layout, bank and row per texel); no error.
//! Coverage: scan order, frames ready in either map, segments per round (1, 2, 3-8), rounds with
//! and without a page fault. Underrun without blanking and overrun with one buffer are tests, as
//! are a frame overtaking the one two before it (1x8 video with one cycle of line blanking: until
//! 2026-11-26 this was reported ready holding the next frame's texels, without an error) and
//! overlapping partner reads (1x8 interlaced, four cycles of blanking: until then the count of
//! read segments wrapped, a panic), and the same overtaking after a reset (a reset now clears the
//! record of ready frames, whose numbers start again at 0 with the generator's).
//!
//! **What video costs the rasterizer**, cycle by cycle (`tb::texram_video::video_cost`, a test):
//! interlaced video at 25 frames a second, the texels spread over 80 % of each line time, written
//! into map 0 while the rasterizer reads the last frame (map 1) at full rate along a span. The
//! frame is 1024x512: the generator takes power-of-two frames, and 1024x512 is the largest at
//! least 768 wide whose two frame buffers fit the chip (768x576 has 64 more lines, each two or
//! three more transfers: about 12 % more than below).
//!
//! | interlaced 1024x512, 25 frames/s, one frame time (40 ms, 8,000,000 cycles) | value |
//! |---|---|
//! | source timing | a texel every 12 cycles, 3,337 cycles of blanking a line |
//! | row transfers (segments) a frame | 2,559 (level 0: 1,024; partner reads: 512; levels 1-10: 1,023) |
//! | slots they took (rounds of several banks) | 1,409 |
//! | row buffers used at most | 21 of 32 |
//! | rasterizer accesses in the frame time, without video | 1,326,698 |
//! | with video | 1,324,788 |
//! | rasterizer fault slots, without / with video | 6,634 / 7,135 |
//! | **accesses lost to the video** | **0.144 %** (1,409 stolen slots and 501 extra fault slots) |
//!
//! Under 1 %, as the document's "without slowing down" needs. The stub-level figure above
//! (0.51 % for 768x576) charges every row transfer a slot of its own and counts the rows of a
//! different rasterizer span; the chip's rounds write up to eight banks at once.

pub mod address_812;
pub mod banks_810;
pub mod clut_814;
pub mod lockstep;
pub mod output_820;
pub mod stub;
pub mod texram_802;
pub mod trilinear_818;
pub mod video_port_808;

pub use address_812::{Border, Footprint};

/// Fraction bits of u, v and lambda.
pub const FRAC: u32 = 8;
/// u and v: sQ12.8, `-2^20 ..= 2^20 - 1` raw.
pub const UV_BITS: u32 = 21;
/// lambda: sQ5.8 raw, limited to `-4.0 ..= 10.0`.
pub const LAMBDA_MIN: i32 = -4 << FRAC;
pub const LAMBDA_MAX: i32 = 10 << FRAC;
/// Description register files: seven (DRF 7 holds the cube faces of an environment map).
pub const DRFS: usize = 7;

/// A description register file (DRF) as far as one texture access needs it: where the map
/// is, its size and its border operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drf {
    /// log2 of the level-0 width and height (0 ..= 10: up to 1024 x 1024).
    pub width_log2: u32,
    pub height_log2: u32,
    /// First word of the even levels (banks 0-3) and of the odd levels (banks 4-7).
    pub base_even: u32,
    pub base_odd: u32,
    pub border: Border,
    /// How the stored texels are read (section 6).
    pub config: Config,
    /// Eq. 5 in the output stage 820: what multiplies the texture colour.
    pub modulate: output_820::Modulate,
}

/// The configurations of section 6 modelled so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Config {
    /// 8-bit luminance: the result in all four components.
    #[default]
    Luminance,
    /// 8-bit indices into the CLUT 814, filtered per component after the look-up.
    Index,
    /// True colour, \[C\] the conflict-free reading: the DRF's space holds four component
    /// planes of half its width and height in its quadrants (R top left, G top right, B
    /// bottom left, alpha bottom right); four accesses per pixel.
    Planar,
    /// True colour as section 6 prints it: R, G, B, alpha of a texel in one 2x2 cell, so the
    /// neighbours of a component sit in the same bank: every access conflicts (reported).
    Literal,
}

impl Config {
    /// Where texel (x, y) of level `k` of component `c`'s map (`plane`) is stored, in the
    /// level-k coordinates of the DRF's whole space.
    pub fn place(self, plane: &Drf, c: u32, k: u32, x: u32, y: u32) -> (u32, u32) {
        let (w, h) = plane.level_size(k);
        match self {
            Config::Luminance | Config::Index => (x, y),
            Config::Planar => (x + w * (c & 1), y + h * (c >> 1)),
            Config::Literal => (2 * x + (c & 1), 2 * y + (c >> 1)),
        }
    }
}

impl Drf {
    /// The map of one colour component (planar, literal): half the width and height.
    pub fn component_map(&self) -> Drf {
        Drf {
            width_log2: self.width_log2.saturating_sub(1),
            height_log2: self.height_log2.saturating_sub(1),
            config: Config::Luminance,
            ..*self
        }
    }
}

impl Drf {
    /// A map of `2^w x 2^h` texels at word 0 of both bank groups.
    pub fn new(width_log2: u32, height_log2: u32, border: Border) -> Drf {
        Drf {
            width_log2,
            height_log2,
            base_even: 0,
            base_odd: 0,
            border,
            config: Config::Luminance,
            modulate: output_820::Modulate::One,
        }
    }

    /// The coarsest level: the chain ends at 1 x 1.
    pub fn max_level(&self) -> u32 {
        self.width_log2.max(self.height_log2)
    }

    /// Width and height of level `k` (each at least 1).
    pub fn level_size(&self, k: u32) -> (u32, u32) {
        (
            1 << self.width_log2.saturating_sub(k),
            1 << self.height_log2.saturating_sub(k),
        )
    }

    pub fn validate(&self) -> Result<(), String> {
        let colour = matches!(self.config, Config::Planar | Config::Literal);
        // [C] Square: a component's levels then stay apart down to 1 x 1 (a rectangular
        // space's smaller side would reach 1 while the planes still need two rows).
        if colour && (self.width_log2 == 0 || self.width_log2 != self.height_log2) {
            return Err(format!(
                "map {}x{}: a planar or literal colour space is square, at least 2 x 2",
                1u64 << self.width_log2,
                1u64 << self.height_log2
            ));
        }
        if self.width_log2 > 10 || self.height_log2 > 10 {
            return Err(format!(
                "map {}x{}: at most 1024 x 1024 per chip",
                1u64 << self.width_log2,
                1u64 << self.height_log2
            ));
        }
        Ok(())
    }
}

/// One texture access as the rasterizer (or the footprint generator) sends it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexramRequest {
    /// Which DRF (0 .. [`DRFS`]).
    pub drf: u8,
    /// sQ12.8 raw, level-0 texel units.
    pub u: i32,
    pub v: i32,
    /// sQ5.8 raw.
    pub lambda: i32,
}

impl TexramRequest {
    /// Checks the fields against their formats.
    pub fn validate(&self) -> Result<(), String> {
        let lim = 1i32 << (UV_BITS - 1);
        if usize::from(self.drf) >= DRFS {
            return Err(format!("drf {}: 0..{DRFS}", self.drf));
        }
        for (n, x) in [("u", self.u), ("v", self.v)] {
            if !(-lim..lim).contains(&x) {
                return Err(format!("{n} raw {x}: outside sQ12.8"));
            }
        }
        if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&self.lambda) {
            return Err(format!("lambda raw {}: outside -4.0 ..= 10.0", self.lambda));
        }
        Ok(())
    }
}

/// What one access gives back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexramReply {
    /// The two levels read (`fine + 1 == coarse`, or both the last level).
    pub fine: u32,
    pub coarse: u32,
    /// Texels: the fine 2x2 as (i, j), (i+1, j), (i, j+1), (i+1, j+1), then the coarse 2x2.
    /// A border-colour texel holds the DRF's border colour.
    pub texels: [u8; 8],
    /// Weights of the fine and coarse levels (a along u, b along v) and between them (f).
    pub a: [u8; 2],
    pub b: [u8; 2],
    pub f: u8,
    /// The trilinear interpolator 818's result (luminance; R in index mode).
    pub value: u8,
    /// The result's R, G, B and alpha (luminance: the value four times).
    pub rgba: [u8; 4],
    /// Access slots taken (1, or 2 after a page fault).
    pub slots: u32,
    /// Banks whose open row missed.
    pub faults: u32,
}

/// The chip seen from outside: one trilinear access per call.
pub trait TexramAccess {
    /// Sets DRF `k`; the map it describes must then be loaded.
    fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String>;
    /// One access; `Err` names the field that is out of its format or an unset DRF.
    fn access(&mut self, req: TexramRequest) -> Result<TexramReply, String>;
    /// Slots taken since the start (accesses, their faults and anything else the chip did).
    fn slots(&self) -> u64;
    /// Writes the map `drf` describes (level 0 given, the levels above made as
    /// [`stub::next_level`] makes them) wherever its bases say, with or without a DRF
    /// pointing at it (an offset map's second plane, a cube face).
    fn load_map(&mut self, drf: &Drf, level0: &[u8]) -> Result<(), String>;
    /// One access through 812's working descriptor [`WORKING`]: the map the chain walker
    /// selected (a cube face, an offset plane, a detail map) loaded for this access only.
    fn access_with(
        &mut self,
        drf: &Drf,
        u: i32,
        v: i32,
        lambda: i32,
    ) -> Result<TexramReply, String>;
    /// The state accesses leave (open rows, counters, the chip's registers), for the
    /// waveform of a module that holds the banks; nothing by default.
    fn visit(&self, _v: &mut dyn crate::kernel::Visitor) {}
}

/// The request pointer of 812's working descriptor: the DRF the chain walker fills for one
/// access. The rasterizer's requests name DRFs `0 .. DRFS` only.
pub const WORKING: u8 = DRFS as u8;

/// Writes every level of `drf`'s map, from level 0 up, with `store`.
pub fn load_levels(
    drf: &Drf,
    level0: &[u8],
    mut store: impl FnMut(u32, &[u8]) -> Result<(), String>,
) -> Result<(), String> {
    drf.validate()?;
    // Each level's size is checked where it is stored (`banks_810::store_level`).
    let mut level = level0.to_vec();
    for k in 0..=drf.max_level() {
        store(k, &level)?;
        let (w, h) = drf.level_size(k);
        level = stub::next_level(w, h, &level);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_maps_are_square_and_their_components_luminance() {
        for config in [Config::Planar, Config::Literal] {
            let mut d = Drf::new(3, 3, Border::Wrap);
            d.config = config;
            assert!(d.validate().is_ok());
            let c = d.component_map();
            assert_eq!(
                (c.width_log2, c.height_log2, c.config),
                (2, 2, Config::Luminance)
            );
            for (w, h) in [(0, 0), (3, 2), (2, 3), (0, 3)] {
                let e = Drf {
                    width_log2: w,
                    height_log2: h,
                    ..d
                };
                assert!(e.validate().unwrap_err().contains("square"), "{w} {h}");
            }
        }
        // Luminance maps may be rectangular and 1 x 1; nothing past 1024.
        assert!(Drf::new(0, 0, Border::Wrap).validate().is_ok());
        assert!(Drf::new(10, 2, Border::Wrap).validate().is_ok());
        assert!(Drf::new(11, 2, Border::Wrap).validate().is_err());
    }

    #[test]
    fn requests_are_checked_against_their_formats() {
        let ok = TexramRequest {
            drf: 6,
            u: (1 << 20) - 1,
            v: -(1 << 20),
            lambda: LAMBDA_MAX,
        };
        assert!(ok.validate().is_ok());
        let bad = [
            TexramRequest { drf: 7, ..ok },
            TexramRequest { u: 1 << 20, ..ok },
            TexramRequest {
                v: -(1 << 20) - 1,
                ..ok
            },
            TexramRequest {
                lambda: LAMBDA_MAX + 1,
                ..ok
            },
            TexramRequest {
                lambda: LAMBDA_MIN - 1,
                ..ok
            },
        ];
        for r in bad {
            assert!(r.validate().is_err(), "{r:?}");
        }
        assert!(TexramRequest {
            lambda: LAMBDA_MIN,
            ..ok
        }
        .validate()
        .is_ok());
    }

    #[test]
    fn the_slot_is_one_to_fifteen_cycles() {
        use texram_802::TexramParams;
        for (c, ok) in [(0, false), (1, true), (6, true), (15, true), (16, false)] {
            let p = TexramParams { slot_cycles: c };
            assert_eq!(p.validate().is_ok(), ok, "{c}");
            assert_eq!(texram_802::Texram802::new(p).is_ok(), ok, "{c}");
        }
    }

    #[test]
    fn level_sizes_stop_at_one() {
        let d = Drf::new(4, 1, Border::Wrap);
        assert_eq!(d.max_level(), 4);
        assert_eq!(d.level_size(0), (16, 2));
        assert_eq!(d.level_size(1), (8, 1));
        assert_eq!(d.level_size(4), (1, 1));
    }
}
