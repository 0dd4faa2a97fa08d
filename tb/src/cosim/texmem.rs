//! Co-simulation adapters of the Figure 6 memory path (Schilling & Knittel): each unit's
//! model, its twin in `rtl/texmem/`, the twin's parameters from the model's and the stimulus.

use super::twin;
use hdl::fx::Format;
use hdl::kernel::Signal;
use std::path::PathBuf;
use units::texmem::cache_614::{Lookahead, TextureCache};
use units::texmem::control_607::{DramCtrl, FillEngine, LookaheadQueue};
use units::texmem::dram_604::DramParams;
use units::texmem::layout::{BlockMap, Layout};
use verif::cosim::{field, CosimModel, CosimUnit, ModelSim, Port};

/// Control unit 607 (word reads, with its page register) driving DRAM 604, against
/// `rtl/texmem/control_607.v` driving the behavioural `rtl/texmem/dram_604.v`. Compared
/// besides the controller's ports: the DRAM pins RAS#, CAS#, OE# and the address every cycle,
/// and the DRAM's count of timing violations (both DRAM models check the same timing).
pub struct ControlCosim(pub DramParams);

/// The DRAM's [`dram_probes`] in the model.
fn dram_probe_values(r: &units::texmem::dram_604::Dram) -> Vec<u64> {
    vec![
        r.ras_n.bits(),
        r.cas_n.bits(),
        r.oe_n.bits(),
        r.addr.bits(),
        r.violations() & 0xffff_ffff,
    ]
}

/// The DRAM's geometry and timing as the twins' Verilog parameters.
fn dram_parameters(p: &DramParams) -> Vec<(&'static str, i64)> {
    vec![
        ("ROWS", p.rows.into()),
        ("COLS", p.cols.into()),
        ("T_RP", p.t_rp.into()),
        ("T_RCD", p.t_rcd.into()),
        ("T_CAS", p.t_cas.into()),
        ("T_CP", p.t_cp.into()),
    ]
}

/// The pins and the violation count, compared after the controller's ports.
fn dram_probes() -> Vec<Port> {
    let p = Port::uint;
    vec![
        p("ras_n", 1),
        p("cas_n", 1),
        p("oe_n", 1),
        p("addr", 11),
        p("violations", 32),
    ]
}

impl CosimUnit for ControlCosim {
    fn name(&self) -> &str {
        "control_607"
    }
    fn top(&self) -> &str {
        "control_607_with_dram"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["texmem/control_607.v"])
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        twin(vec!["texmem/control_607_with_dram.v", "texmem/dram_604.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        dram_parameters(&self.0)
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        let dut = DramCtrl::new(self.name(), self.0)?;
        let m = ModelSim::new(dut, |d: &mut DramCtrl, v: &[u64]| {
            Signal::set_row([&mut d.req_valid, &mut d.req_addr], v);
        });
        Ok(Box::new(m.probes(dram_probes(), |d: &DramCtrl| {
            dram_probe_values(&d.dram)
        })))
    }
    /// Requests three times in four; addresses in one of four rows three times in four (page
    /// hits and faults in page mode), anywhere otherwise, corners included.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Strategy;
        let p = self.0;
        let ab = 64 - (p.words() - 1).leading_zeros();
        let mut st = verif::Stimulus::new(seed);
        let rows = st.draw_n(&(0..u64::from(p.rows)), 4);
        let cols = u64::from(p.cols);
        let near = (0..4usize, 0..cols).prop_map(move |(r, c)| rows[r] * cols + c);
        let addr = proptest::prop_oneof![1 => field(ab), 3 => near];
        let valid = proptest::prop_oneof![1 => proptest::strategy::Just(0u64), 3 => proptest::strategy::Just(1u64)];
        st.draw_n(&(valid, addr), cycles)
            .into_iter()
            .map(|(v, a)| vec![v, a])
            .collect()
    }
}

/// Drives the lookahead queue's inputs from one cycle of [`LookaheadCosim`]'s stimulus.
#[inline]
pub fn drive_lookahead(d: &mut LookaheadQueue, v: &[u64]) {
    let ins = [
        &mut d.complete,
        &mut d.u,
        &mut d.v,
        &mut d.newline,
        &mut d.flush,
        &mut d.engine_free,
        &mut d.stage0_missing,
    ];
    Signal::set_row(ins, v);
}

/// Drives the block fetch's inputs from one cycle of [`FillCosim`]'s stimulus.
#[inline]
pub fn drive_fill(d: &mut FillEngine, v: &[u64]) {
    let ins = [
        &mut d.start,
        &mut d.start_bx,
        &mut d.start_by,
        &mut d.start_prefetch,
        &mut d.word_ready,
        &mut d.word_resp,
        &mut d.line_done,
    ];
    Signal::set_row(ins, v);
}

/// The lookahead queue of control unit 607 against `rtl/texmem/lookahead_queue_607.v`, for a
/// texture of `blocks` (width, height) 4x4 blocks, coordinates `uQ12.<frac_bits>` and the
/// unit's 10-bit block coordinates. Compared besides its ports: the live-slot mask.
pub struct LookaheadCosim {
    pub mode: Lookahead,
    pub blocks: (u32, u32),
    pub frac_bits: u32,
}

/// The lookahead mode as the twins' `MODE`.
fn mode_code(m: Lookahead) -> i64 {
    match m {
        Lookahead::Off => 0,
        Lookahead::Quadrant => 1,
        Lookahead::Direction => 2,
    }
}

/// Block coordinates of texture unit 602 (12-bit texel coordinates, 4x4 blocks).
const BLOCK_BITS: u32 = 10;

impl CosimUnit for LookaheadCosim {
    fn name(&self) -> &str {
        "lookahead_queue_607"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["texmem/lookahead_queue_607.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("MODE", mode_code(self.mode)),
            ("BW", self.blocks.0.into()),
            ("BH", self.blocks.1.into()),
            ("F", self.frac_bits.into()),
            ("BB", BLOCK_BITS.into()),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        let uq = Format::unsigned(12 + self.frac_bits, self.frac_bits as i32);
        let dut = LookaheadQueue::new(self.mode, self.blocks, uq, BLOCK_BITS);
        let m = ModelSim::new(dut, drive_lookahead);
        let mask = Port::uint("mask", 3);
        Ok(Box::new(m.probes(vec![mask], |d: &LookaheadQueue| {
            vec![d.mask.q().bits()]
        })))
    }
    /// A point that walks like a rasterizer (small steps in any direction, across block
    /// edges) three times in four and jumps anywhere in the texture otherwise (beyond it one
    /// time in sixteen); completions half the time, a new scanline or a flush now and then, the
    /// fill engine free and stage 0 missing at random.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let f = self.frac_bits;
        let w = 12 + f;
        let (tw, th) = (
            u64::from(4 * self.blocks.0) << f,
            u64::from(4 * self.blocks.1) << f,
        );
        let mut st = verif::Stimulus::new(seed);
        let (mut u, mut v) = (0u64, 0u64);
        let step = 1i64 << f;
        (0..cycles)
            .map(|_| {
                let kind = st.draw(&(0u32..16));
                if kind < 12 {
                    let (du, dv) = st.draw(&(-step..=step, -step / 2..=step / 2));
                    u = (u as i64 + du).clamp(0, tw as i64 - 1) as u64;
                    v = (v as i64 + dv).clamp(0, th as i64 - 1) as u64;
                } else if kind < 15 {
                    (u, v) = st.draw(&(0..tw, 0..th));
                } else {
                    (u, v) = st.draw(&(field(w), field(w)));
                }
                let (complete, newline, flush, free, missing) =
                    st.draw(&(0u64..2, 0u64..8, 0u64..16, 0u64..2, 0u64..4));
                vec![
                    complete,
                    u,
                    v,
                    u64::from(newline == 0),
                    u64::from(flush == 0),
                    free,
                    u64::from(missing == 0),
                ]
            })
            .collect()
    }
}

/// Cache 614 against `rtl/texmem/cache_614.v`, tags of `tag_bits` bits per coordinate. Its
/// registered state is compared every cycle: valid and prefetched by entry, tags and lines
/// (what the model's `holds`, `line` and `prefetched` read).
pub struct CacheCosim {
    pub tag_bits: u32,
}

/// The cache's state as ports, after the model's (it has no outputs of its own).
fn cache_probes(tag_bits: u32) -> Vec<Port> {
    let p = Port::uint;
    let mut v = vec![p("valid", 4), p("prefetched", 4)];
    for (field, w) in [("tag_x", tag_bits), ("tag_y", tag_bits), ("line", 64)] {
        v.extend(["a", "b", "c", "d"].map(|e| Port::uint(format!("{field}_{e}"), w)));
    }
    v
}

impl CosimUnit for CacheCosim {
    fn name(&self) -> &str {
        "cache_614"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["texmem/cache_614.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![("TAG_BITS", self.tag_bits.into())]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        if !(1..=31).contains(&self.tag_bits) {
            return Err(format!("cache_614: tag_bits {}: 1..=31", self.tag_bits));
        }
        let dut = TextureCache::new(self.name(), self.tag_bits);
        let m = ModelSim::new(dut, |d: &mut TextureCache, v: &[u64]| {
            let ins: [&mut Signal; 7] = [
                &mut d.touch,
                &mut d.invalidate,
                &mut d.write,
                &mut d.write_bx,
                &mut d.write_by,
                &mut d.write_data,
                &mut d.write_prefetched,
            ];
            Signal::set_row(ins, v);
        });
        Ok(Box::new(m.probes(
            cache_probes(self.tag_bits),
            |d: &TextureCache| {
                let e = &d.entries;
                let bits =
                    |f: &dyn Fn(usize) -> bool| (0..4).fold(0, |m, k| m | u64::from(f(k)) << k);
                let mut v = vec![
                    bits(&|k| e[k].valid.q().is_high()),
                    bits(&|k| e[k].prefetched.q().is_high()),
                ];
                v.extend(e.iter().map(|x| x.tag_x.q().bits()));
                v.extend(e.iter().map(|x| x.tag_y.q().bits()));
                v.extend(e.iter().map(|x| x.data.q().bits()));
                v
            },
        )))
    }
    /// Writes half the time, of blocks from a set of eight three times in four (tags that
    /// repeat and entries that conflict) and anywhere otherwise; any line, touches at random,
    /// an invalidation one cycle in eight.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Strategy;
        let b = self.tag_bits + 1;
        let mut st = verif::Stimulus::new(seed);
        let blocks = st.draw_n(&(field(b), field(b)), 8);
        let near = (0..8usize).prop_map(move |k| blocks[k]);
        let block = proptest::prop_oneof![3 => near, 1 => (field(b), field(b))];
        let s = (0u64..16, 0u64..8, 0u64..2, block, field(64), 0u64..2);
        st.draw_n(&s, cycles)
            .into_iter()
            .map(|(touch, inval, write, (bx, by), data, pre)| {
                vec![touch, u64::from(inval == 0), write, bx, by, data, pre]
            })
            .collect()
    }
}

/// The block fetch of control unit 607 against `rtl/texmem/fill_engine_607.v`: a texture of
/// `blocks` 4x4 blocks from DRAM word `base` in `layout`, on `dram`'s pages and addresses.
/// Compared besides its ports: its state and the block it fills (coordinates, prefetch flag).
pub struct FillCosim {
    pub layout: Layout,
    pub blocks: (u32, u32),
    pub base: u64,
    pub dram: DramParams,
}

impl FillCosim {
    fn map(&self) -> BlockMap {
        let (bw, bh) = self.blocks;
        BlockMap::new(self.layout, bw, bh, self.dram.cols, self.base)
    }
    fn addr_bits(&self) -> u32 {
        64 - (self.dram.words() - 1).leading_zeros()
    }
}

impl CosimUnit for FillCosim {
    fn name(&self) -> &str {
        "fill_engine_607"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["texmem/fill_engine_607.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("LAYOUT", i64::from(self.layout == Layout::Tiled)),
            ("BW", self.blocks.0.into()),
            ("PAGE_WORDS", self.dram.cols.into()),
            ("BASE", self.base as i64),
            ("BB", BLOCK_BITS.into()),
            ("AB", self.addr_bits().into()),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        self.dram.validate()?;
        let map = self.map();
        if self.base + map.words() > self.dram.words() {
            return Err("fill_engine_607: the texture does not fit the DRAM".into());
        }
        let dut = FillEngine::new(map, BLOCK_BITS, Format::uint(self.addr_bits()));
        let m = ModelSim::new(dut, drive_fill);
        let p = Port::uint;
        Ok(Box::new(m.probes(
            vec![
                p("state", 2),
                p("bx", BLOCK_BITS),
                p("by", BLOCK_BITS),
                p("prefetch", 1),
            ],
            |d: &FillEngine| {
                let (bx, by, pre) = d.block();
                vec![d.state.q().bits(), bx.into(), by.into(), pre.into()]
            },
        )))
    }
    /// Blocks anywhere in the texture (its corners a quarter of the time); starts, grants and
    /// responses at random, the decoder done one cycle in four.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Just;
        let (bw, bh) = (u64::from(self.blocks.0), u64::from(self.blocks.1));
        let coord = |n: u64| proptest::prop_oneof![1 => Just(0), 1 => Just(n - 1), 6 => 0..n];
        let s = (
            (0u64..2, coord(bw), coord(bh), 0u64..2),
            (0u64..2, 0u64..2, 0u64..4),
        );
        let mut st = verif::Stimulus::new(seed);
        st.draw_n(&s, cycles)
            .into_iter()
            .map(|((go, bx, by, pre), (ready, resp, done))| {
                vec![go, bx, by, pre, ready, resp, u64::from(done == 0)]
            })
            .collect()
    }
}

/// Drives texture unit 602's request port from one cycle of [`TextureCosim`]'s stimulus.
#[inline]
pub fn drive_texture(d: &mut units::texmem::texture_unit_602::TextureUnit, v: &[u64]) {
    Signal::set_row(
        [&mut d.in_valid, &mut d.in_u, &mut d.in_v, &mut d.in_newline],
        v,
    );
}

/// Texture mapping unit 602 end to end against `rtl/texmem/texture_unit_602.v` and its
/// children's twins (control 607's block fetch, lookahead queue and word controller, CCC
/// decode 608-612, cache 614, extract 618, bilinear 622), driving the behavioural
/// `rtl/texmem/dram_604.v`. The texture is the DRAM's power-up pattern (both DRAM models hold
/// it), read through [`TextureCosim::clut`]. Compared besides the unit's ports: the stage-0
/// need and hit masks, the DRAM pins and its count of timing violations.
pub struct TextureCosim(pub units::texmem::texture_unit_602::TexParams);

impl TextureCosim {
    /// CLUT 612 of the co-simulation: 256 scattered 24-bit colours (a multiplicative hash of
    /// the index), so every index and every channel is told apart.
    pub fn clut() -> Vec<u32> {
        (0..256u32)
            .map(|i| (i.wrapping_mul(0x9e37_79b9) >> 8) & 0xff_ffff)
            .collect()
    }
}

impl CosimUnit for TextureCosim {
    fn name(&self) -> &str {
        "texture_unit_602"
    }
    fn top(&self) -> &str {
        "texture_unit_602_with_dram"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec![
            "texmem/texture_unit_602.v",
            "texmem/fill_engine_607.v",
            "texmem/lookahead_queue_607.v",
            "texmem/control_607.v",
            "texmem/ccc_decode_608.v",
            "texmem/cache_614.v",
            "texmem/extract_618.v",
            "texmem/bilinear_622.v",
        ])
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        twin(vec![
            "texmem/texture_unit_602_with_dram.v",
            "texmem/dram_604.v",
        ])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = &self.0;
        let mut v = vec![
            ("W", p.width.into()),
            ("H", p.height.into()),
            ("F", p.frac_bits.into()),
            ("LAYOUT", i64::from(p.layout == Layout::Tiled)),
            ("BASE", p.base as i64),
            ("CACHE", i64::from(p.cache)),
            ("MODE", mode_code(p.lookahead)),
        ];
        v.extend(dram_parameters(&p.dram));
        v
    }
    fn memories(&self) -> Vec<(String, String)> {
        let text = Self::clut().iter().map(|c| format!("{c:06x}\n")).collect();
        vec![("clut_612.hex".into(), text)]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        use units::texmem::texture_unit_602::TextureUnit;
        let dut = TextureUnit::new(self.name(), self.0, &Self::clut(), &[])?;
        let m = ModelSim::new(dut, drive_texture);
        let mut ports = vec![Port::uint("need_mask", 4), Port::uint("hit_mask", 4)];
        ports.extend(dram_probes());
        Ok(Box::new(m.probes(ports, |d: &TextureUnit| {
            let mut v = vec![d.need_mask.bits(), d.hit_mask.bits()];
            v.extend(dram_probe_values(&d.mem.dram));
            v
        })))
    }
    /// A rasterizer's walk, one point a cycle whether or not the unit took the last (so steps
    /// are small: a sixteenth to a quarter of a texel at `F = 4`, either way): scanlines of 16
    /// to 256 points flagged `newline` at their first, a jump anywhere in the texture one
    /// point in 64 (its far corner included); a request seven cycles in eight.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        let f = self.0.frac_bits;
        let (tw, th) = (i64::from(self.0.width) << f, i64::from(self.0.height) << f);
        let one = 1i64 << f;
        let mut st = verif::Stimulus::new(seed);
        let (mut u, mut v, mut du, mut left) = (0i64, 0i64, one, 0u32);
        (0..cycles)
            .map(|_| {
                let (valid, kind) = st.draw(&(0u32..8, 0u32..64));
                let mut newline = false;
                if kind == 0 {
                    (u, v) = st.draw(&(
                        proptest::prop_oneof![0..tw, proptest::strategy::Just(tw - 1)],
                        proptest::prop_oneof![0..th, proptest::strategy::Just(th - 1)],
                    ));
                } else if left == 0 {
                    let (len, step, back, dv) = st.draw(&(
                        16u32..256,
                        1.max(one / 16)..=1.max(one / 4),
                        proptest::bool::ANY,
                        0..=one,
                    ));
                    (left, du, newline) = (len, if back { -step } else { step }, true);
                    v = (v + dv) % th;
                    u = st.draw(&(0..tw));
                } else {
                    u = (u + du).clamp(0, tw - 1);
                    left -= 1;
                }
                vec![
                    u64::from(valid != 0),
                    u as u64,
                    v as u64,
                    u64::from(newline),
                ]
            })
            .collect()
    }
    fn history(&self) -> usize {
        8
    }
}
