//! Co-simulation adapter of the map chain walker 812 (section 14): the walker's model over a
//! stand-in for the banks ([`HashBanks`]), its twin `rtl/mapchain/walker_812.v` in the bench
//! top `walker_812_with_banks.v` (the same stand-in in Verilog), the DRFs both load, and the
//! stimulus.

use super::twin;
use hdl::kernel::Signal;
use std::path::PathBuf;
use units::mapchain::drf_812::{ChainDrf, DetailMode, DrfFile, Kind};
use units::mapchain::walker_812::{MapChain812, Pixel};
use units::texram::output_820::Modulate;
use units::texram::{Border, Drf, TexramAccess, TexramReply};
use verif::cosim::{Compare, CosimModel, CosimUnit, ModelSim, Port};

/// Banks that answer an access from a hash of its map plane's even base and its u, v and
/// lambda: a value and one slot, or two (a page fault) one time in four. The walker's
/// behaviour depends on the values and slots it gets, not on where they come from, so a
/// stand-in both sides compute alike exercises every state without the banks' Verilog.
#[derive(Clone, Debug, Default)]
pub struct HashBanks {
    slots: u64,
}

impl HashBanks {
    /// The hash (32-bit wrapping arithmetic, as `walker_812_with_banks.v` computes it).
    pub fn mix(base: u32, u: i32, v: i32, lambda: i32) -> u32 {
        let field = |x: i32, bits: u32| (x as u32) & ((1 << bits) - 1);
        let mut x = (base & 0xfff).wrapping_mul(0x9e37_79b9)
            ^ field(u, 21).wrapping_mul(0x85eb_ca6b)
            ^ field(v, 21).wrapping_mul(0xc2b2_ae35)
            ^ field(lambda, 14).wrapping_mul(0x27d4_eb2f);
        x ^= x >> 15;
        x = x.wrapping_mul(0x2c1b_3c6d);
        x ^ (x >> 12)
    }
}

impl TexramAccess for HashBanks {
    fn set_drf(&mut self, _: usize, _: Drf) -> Result<(), String> {
        Ok(())
    }
    fn access(&mut self, _: units::texram::TexramRequest) -> Result<TexramReply, String> {
        Err("the hash banks answer the walker's working descriptor only".into())
    }
    fn slots(&self) -> u64 {
        self.slots
    }
    fn load_map(&mut self, _: &Drf, _: &[u8]) -> Result<(), String> {
        Ok(())
    }
    fn access_with(
        &mut self,
        drf: &Drf,
        u: i32,
        v: i32,
        lambda: i32,
    ) -> Result<TexramReply, String> {
        let x = Self::mix(drf.base_even, u, v, lambda);
        let slots = if (x >> 8) & 3 == 0 { 2 } else { 1 };
        self.slots += u64::from(slots);
        Ok(TexramReply {
            fine: 0,
            coarse: 0,
            texels: [0; 8],
            a: [0; 2],
            b: [0; 2],
            f: 0,
            value: x as u8,
            rgba: [x as u8; 4],
            slots,
            faults: slots - 1,
        })
    }
}

/// The walker against `rtl/mapchain/walker_812.v`, `slot_cycles` clock cycles a slot, over
/// [`HashBanks`], with the DRFs of [`WalkerCosim::file`]. Compared besides the pixel port's
/// ready: the access port (when it is valid), the banks' answer, the state, the result and
/// its counts.
pub struct WalkerCosim {
    pub slot_cycles: u32,
}

impl WalkerCosim {
    /// Seven DRFs: texture 0 (eq. 5 on I_d) -> offsets 1 -> detail 2 (add-signed) ->
    /// reflectance 3 (lit by the environment) -> environment 4 (eq. 4's coordinates);
    /// environment 5 at the rasterizer's face and coordinates, on to 0; texture 6 (eq. 5 on
    /// k_T = 180) on to detail 2, which ends its chain in an error below level 0 (no offsets).
    pub fn file() -> DrfFile {
        let map = |side: u32, base: u32| Drf {
            base_even: base,
            base_odd: base + 1,
            ..Drf::new(side, side, Border::Wrap)
        };
        let d = |kind, side, base, link: Option<u8>| ChainDrf {
            link,
            planes: std::array::from_fn(|p| (base + 40 * (p as u32 + 1), 0)),
            ..ChainDrf::new(kind, map(side, base))
        };
        let mut file = DrfFile::default();
        let mut tex = d(Kind::Texture, 6, 100, Some(1));
        tex.map.modulate = Modulate::Illumination;
        let mut detail = d(Kind::Detail, 8, 700, Some(3));
        detail.detail = DetailMode::AddSigned;
        let mut refl = d(Kind::Reflectance, 5, 1000, Some(4));
        refl.light_env = true;
        let mut env = d(Kind::Environment, 4, 1500, None);
        env.k_s = 100;
        let mut env_face = d(Kind::Environment, 5, 2000, Some(0));
        env_face.new_coords = false;
        env_face.k_s = 200;
        env_face.base_texture = false;
        let mut tex_k = d(Kind::Texture, 4, 3000, Some(2));
        tex_k.map.modulate = Modulate::Constant(180);
        let offsets = d(Kind::Offset, 6, 400, Some(2));
        file.drfs = [tex, offsets, detail, refl, env, env_face, tex_k].map(Some);
        file
    }

    /// The DRF image `walker_812.v` loads (its header gives the layout).
    pub fn image() -> String {
        let file = Self::file();
        (0..8u8)
            .map(|k| format!("{:027x}\n", file.get(k).map_or(0, packed)))
            .collect()
    }
}

/// A DRF as `walker_812.v` reads it.
fn packed(d: &ChainDrf) -> u128 {
    let kind = Kind::ALL.iter().position(|k| *k == d.kind).unwrap_or(0) as u128;
    let mode = match d.detail {
        DetailMode::Replace => 0,
        DetailMode::Multiply => 1,
        DetailMode::AddSigned => 2,
    };
    let (factor, k_t) = match d.map.modulate {
        Modulate::Illumination => (0, 0),
        Modulate::Constant(k) => (1, k),
        Modulate::One => (2, 0),
    };
    let mut x = 1
        | kind << 1
        | u128::from(d.link.is_some()) << 4
        | u128::from(d.link.unwrap_or(0)) << 5
        | u128::from(d.new_coords) << 8
        | u128::from(d.k_s) << 9
        | mode << 17
        | u128::from(d.base_texture) << 19
        | u128::from(d.light_env) << 20
        | u128::from(d.map.width_log2) << 21
        | factor << 25
        | u128::from(k_t) << 27;
    for p in 0..d.plane_count() {
        x |= u128::from(d.plane(p).base_even & 0xfff) << (35 + 12 * p);
    }
    x
}

/// The walker's model over the hash banks.
type Walker = MapChain812<HashBanks>;

/// Drives the pixel port from one cycle of [`WalkerCosim`]'s stimulus.
#[inline]
pub fn drive_walker(d: &mut Walker, v: &[u64]) {
    d.req.valid.set_bits(v[0]);
    Signal::set_row(d.req.payload.each_mut(), &v[1..]);
}

/// What is compared besides the port's ready, in the twin's port order.
fn walker_probes() -> Vec<Port> {
    let p = Port::uint;
    vec![
        p("acc_valid", 1),
        p("acc_drf", 3),
        p("acc_plane", 3),
        p("acc_u", 21),
        p("acc_v", 21),
        p("acc_lambda", 14),
        p("rd_value", 8),
        p("rd_slots", 2),
        p("refused", 1),
        p("state", 4),
        p("out_valid", 1),
        p("out_colour", 8),
        p("out_error", 1),
        p("out_accesses", 4),
        p("out_slots", 5),
        p("out_faults", 4),
    ]
}

impl CosimUnit for WalkerCosim {
    fn name(&self) -> &str {
        "walker_812"
    }
    fn top(&self) -> &str {
        "walker_812_with_banks"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec!["mapchain/walker_812.v"])
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        twin(vec!["mapchain/walker_812_with_banks.v"])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        vec![("SLOT_CYCLES", self.slot_cycles.into())]
    }
    fn memories(&self) -> Vec<(String, String)> {
        vec![("drfs_812.hex".into(), Self::image())]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        let dut = MapChain812::new(Self::file(), HashBanks::default(), self.slot_cycles)?;
        let m = ModelSim::new(dut, drive_walker);
        Ok(Box::new(m.probes(walker_probes(), |d: &Walker| {
            let (a, b) = (&d.banks.acc, &d.banks);
            let r = d.result();
            let mut v: Vec<u64> = [&a.valid, &a.drf, &a.plane, &a.u, &a.v, &a.lambda]
                .map(|s| s.bits())
                .to_vec();
            v.extend([&b.rd_value, &b.rd_slots, &b.refused].map(|r| r.q().bits()));
            v.push(d.state().bits());
            v.extend([&d.out_valid, &d.out_colour, &d.out_error].map(|r| r.q().bits()));
            v.extend([r.accesses, r.slots, r.faults].map(u64::from));
            v
        })))
    }
    /// The access port's fields only with `acc_valid` (the model keeps their last values).
    fn compare(&self) -> Vec<Compare> {
        ["acc_drf", "acc_plane", "acc_u", "acc_v", "acc_lambda"]
            .map(|p| Compare::when(p, "acc_valid"))
            .to_vec()
    }
    /// A pixel offered three cycles in four: a leading DRF (the unset 7 one time in sixteen);
    /// u and v within 16 texels of the origin (anywhere in sQ12.8 one time in eight); lambda
    /// over -4.7 ..= 3.5 (anywhere in sQ5.8 one time in eight); any normal and eye vector
    /// (eq. 4 saturates on the long ones); a face 0 ..= 5 (6 or 7 one time in eight); any
    /// illumination and specular term.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::prelude::*;
        let mut st = verif::Stimulus::new(seed);
        let fields = Pixel::fields();
        let coord = prop_oneof![7 => -4096i64..4096, 1 => -(1i64 << 20)..(1i64 << 20)];
        let lambda = prop_oneof![7 => -1200i64..=900, 1 => -(1i64 << 13)..(1i64 << 13)];
        let vec3 = |bits: u32| [(); 3].map(|_| -(1i64 << (bits - 1))..(1i64 << (bits - 1)));
        let head = (0u32..4, 0u64..16, coord.clone(), coord, lambda);
        let tail = (
            vec3(17),
            vec3(16),
            prop_oneof![7 => 0u64..6, 1 => 6u64..8],
            0u64..256,
            0u64..256,
        );
        st.draw_n(&(head, tail), cycles)
            .into_iter()
            .map(|((valid, drf, u, v, l), (n, e, face, id, is))| {
                let drf = if drf < 15 { drf % 7 } else { 7 };
                let raw = [drf as i64, u, v, l, n[0], n[1], n[2], e[0], e[1], e[2]];
                let mut row = vec![u64::from(valid != 0)];
                let widths = fields.each().map(|f| f.fmt.width());
                row.extend(
                    raw.iter()
                        .zip(widths)
                        .map(|(x, w)| (*x as u64) & ((1 << w) - 1)),
                );
                row.extend([face, id, is]);
                row
            })
            .collect()
    }
    fn history(&self) -> usize {
        8
    }
}
