//! Co-simulation adapter of the TEXRAM chip 802 (Schilling & Knittel Figure 8): the chip's
//! model, its twin in `rtl/texram/`, the DRFs, maps and CLUT both are loaded with, and the
//! stimulus.

use super::twin;
use hdl::kernel::Signal;
use std::path::PathBuf;
use units::texram::banks_810::{bank_words, group_words, store_level, BANKS};
use units::texram::clut_814::Clut;
use units::texram::output_820::Modulate;
use units::texram::texram_802::{Texram802, TexramParams};
use units::texram::{load_levels, Border, Config, Drf, DRFS};
use verif::cosim::{field, CosimModel, CosimUnit, ModelSim, Port};

/// The chip against `rtl/texram/texram_802.v` (812, 824, 810, 814, 818, 820; no video port),
/// `slot_cycles` clock cycles a slot, holding [`TexramCosim::drfs`]: a map in every border
/// operation and configuration, each level 0 pseudo-random, and a scattered CLUT. Compared
/// besides the request port: the output stage's registers, the counters and 812's conflicts.
pub struct TexramCosim {
    pub slot_cycles: u32,
}

/// Words a bank of the twin holds (the maps below fit; the model's banks are full size).
pub const TWIN_BANK_WORDS: u32 = 2048;

impl TexramCosim {
    /// The DRFs 0-5 (DRF 6 and 812's working descriptor unset: an access reads the colour 0):
    /// 64x64 luminance wrapped (rows 0-2 of the even banks: page faults); 32x16 clamped; 16x16
    /// index mirrored; 16x16 planar colour with border colour 77 and eq. 5 on I_d; 8x8 literal
    /// colour with k_T = 200; 1x32 luminance in tiles of 8.
    pub fn drfs() -> Vec<Drf> {
        let d = |wl, hl, border, config, (be, bo), modulate| Drf {
            config,
            base_even: be,
            base_odd: bo,
            modulate,
            ..Drf::new(wl, hl, border)
        };
        let one = Modulate::One;
        vec![
            d(6, 6, Border::Wrap, Config::Luminance, (0, 0), one),
            d(5, 4, Border::Clamp, Config::Luminance, (1200, 300), one),
            d(4, 4, Border::Mirror, Config::Index, (1400, 400), one),
            d(
                4,
                4,
                Border::Colour(77),
                Config::Planar,
                (1500, 500),
                Modulate::Illumination,
            ),
            d(
                3,
                3,
                Border::Wrap,
                Config::Literal,
                (1800, 600),
                Modulate::Constant(200),
            ),
            d(0, 5, Border::Tile(3), Config::Luminance, (1900, 700), one),
        ]
    }

    /// CLUT 814: entry i a multiplicative hash of i.
    pub fn clut() -> Clut {
        Clut {
            entries: std::array::from_fn(|i| (i as u32).wrapping_mul(0x9e37_79b9) ^ 0x5a5a_5a5a),
        }
    }

    /// Level 0 of DRF `k`'s map (its whole space for the colour layouts).
    fn level0(k: usize, d: &Drf) -> Vec<u8> {
        let n = 1usize << (d.width_log2 + d.height_log2);
        (0..n)
            .map(|i| ((i as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15 + k as u64) >> 56) as u8)
            .collect()
    }

    /// The chip as the co-simulation starts it: the DRFs set, their maps and the CLUT loaded.
    pub fn chip(&self) -> Result<Texram802, String> {
        Self::check_fits()?;
        let mut chip = Texram802::new(TexramParams {
            slot_cycles: self.slot_cycles,
        })?;
        for (k, d) in Self::drfs().iter().enumerate() {
            chip.set_drf(k, *d)?;
            chip.load(k, &Self::level0(k, d))?;
        }
        chip.set_clut(Self::clut());
        Ok(chip)
    }

    /// The banks as both sides hold them after the host's loads.
    fn banks() -> Result<Vec<Vec<u8>>, String> {
        Self::check_fits()?;
        let mut banks: Vec<Vec<u8>> = (0..BANKS)
            .map(|b| vec![0; bank_words(b) as usize])
            .collect();
        for (k, d) in Self::drfs().iter().enumerate() {
            load_levels(d, &Self::level0(k, d), |lv, t| {
                store_level(&mut banks, d, lv, t)
            })?;
        }
        Ok(banks)
    }

    /// Every DRF's map within the twin's banks.
    fn check_fits() -> Result<(), String> {
        for (k, d) in Self::drfs().iter().enumerate() {
            for g in 0..2 {
                let base = if g == 0 { d.base_even } else { d.base_odd };
                if base + group_words(d, g) > TWIN_BANK_WORDS {
                    return Err(format!("texram_802: DRF {k} beyond the twin's banks"));
                }
            }
        }
        Ok(())
    }
}

/// A DRF as the twin's DRF_FILE holds it (72 bits, see `rtl/texram/address_812.v`).
fn packed(d: Option<&Drf>) -> u128 {
    let Some(d) = d else { return 0 };
    let (kind, param) = match d.border {
        Border::Wrap => (0, 0),
        Border::Clamp => (1, 0),
        Border::Mirror => (2, 0),
        Border::Colour(c) => (3, c),
        Border::Tile(t) => (4, t),
    };
    let config = match d.config {
        Config::Luminance => 0,
        Config::Index => 1,
        Config::Planar => 2,
        Config::Literal => 3,
    };
    let (m, k) = match d.modulate {
        Modulate::Illumination => (0, 0),
        Modulate::Constant(k) => (1, k),
        Modulate::One => (2, 0),
    };
    let f = |x: u32, at: u32| u128::from(x) << at;
    f(d.width_log2, 0)
        | f(d.height_log2, 4)
        | f(d.base_even, 8)
        | f(d.base_odd, 27)
        | f(kind, 46)
        | f(param.into(), 49)
        | f(config, 57)
        | f(m, 59)
        | f(k.into(), 61)
        | 1 << 69
}

/// The output stage's registers, the counters and the conflicts.
fn texram_probes() -> Vec<Port> {
    [
        ("out_valid", 1),
        ("out_value", 8),
        ("out_rgba", 32),
        ("out_texels", 64),
        ("out_fault", 1),
        ("out_sum", 32),
        ("slots", 40),
        ("faults", 40),
        ("accesses", 40),
        ("fault_slots", 40),
        ("conflicts", 40),
    ]
    .into_iter()
    .map(|(n, w)| Port::uint(n, w))
    .collect()
}

/// Drives the chip's request port from one cycle of [`TexramCosim`]'s stimulus.
#[inline]
pub fn drive_texram(d: &mut Texram802, v: &[u64]) {
    let ins = [
        &mut d.req_valid,
        &mut d.req_drf,
        &mut d.req_u,
        &mut d.req_v,
        &mut d.req_lambda,
        &mut d.req_illum,
    ];
    Signal::set_row(ins, v);
}

impl CosimUnit for TexramCosim {
    fn name(&self) -> &str {
        "texram_802"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec![
            "texram/texram_802.v",
            "texram/address_812.v",
            "texram/page_registers_824.v",
            "texram/banks_810.v",
            "texram/clut_814.v",
            "texram/trilinear_818.v",
            "texram/output_820.v",
        ])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![
            ("SLOT_CYCLES", self.slot_cycles.into()),
            ("DEPTH", TWIN_BANK_WORDS.into()),
        ]
    }
    fn memories(&self) -> Vec<(String, String)> {
        let drfs = Self::drfs();
        let drf_text = (0..8)
            .map(|k| format!("{:018x}\n", packed(drfs.get(k))))
            .collect();
        // A DRF beyond the twin's banks fails `model` first, so no empty image is used.
        let banks = Self::banks().unwrap_or_default();
        let bank_text = banks
            .iter()
            .flat_map(|b| b[..TWIN_BANK_WORDS as usize].iter())
            .map(|t| format!("{t:02x}\n"))
            .collect();
        let clut_text = Self::clut()
            .entries
            .iter()
            .map(|c| format!("{c:08x}\n"))
            .collect();
        vec![
            ("drfs_802.hex".into(), drf_text),
            ("banks_810.hex".into(), bank_text),
            ("clut_814.hex".into(), clut_text),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        let m = ModelSim::new(self.chip()?, drive_texram);
        Ok(Box::new(m.probes(texram_probes(), |d: &Texram802| {
            let o = &d.output;
            vec![
                o.out_valid.q().bits(),
                o.out_value.q().bits(),
                o.out_rgba.q().bits(),
                o.out_texels.q().bits(),
                o.out_fault.q().bits(),
                o.out_sum.q().bits(),
                d.slots.q().bits(),
                d.faults.q().bits(),
                d.accesses.q().bits(),
                d.fault_slots.q().bits(),
                d.address.conflicts.q().bits(),
            ]
        })))
    }
    /// Requests three cycles in four: a DRF (the unset ones one time in eight), u and v over
    /// the map and two maps' widths beyond either edge (anywhere in sQ12.8 one time in
    /// sixteen), lambda over -4.0 ..= 10.0 (anywhere in its 14 bits one time in sixteen), any
    /// illumination.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::prelude::*;
        let drfs = Self::drfs();
        let mut st = verif::Stimulus::new(seed);
        let coord = |lg: u32| {
            let n = 256i64 << lg;
            prop_oneof![15 => -2 * n..3 * n, 1 => -(1i64 << 20)..(1i64 << 20)]
        };
        (0..cycles)
            .map(|_| {
                let (valid, pick) = st.draw(&(0u32..4, 0usize..8 * drfs.len()));
                let k = if pick < 7 * drfs.len() {
                    pick % drfs.len()
                } else {
                    DRFS - 1 + pick % 2
                };
                let (wl, hl) = drfs
                    .get(k)
                    .map_or((4, 4), |d| (d.width_log2, d.height_log2));
                let (u, v) = st.draw(&(coord(wl), coord(hl)));
                let lambda = st.draw(&prop_oneof![15 => -1024i64..=2560, 1 => -8192i64..8192]);
                let illum = st.draw(&field(32));
                let raw = |x: i64, bits: u32| (x as u64) & ((1 << bits) - 1);
                vec![
                    u64::from(valid != 0),
                    k as u64,
                    raw(u, 21),
                    raw(v, 21),
                    raw(lambda, 14),
                    illum,
                ]
            })
            .collect()
    }
    fn history(&self) -> usize {
        12
    }
}
