//! Co-simulation adapter of the FIG. 14 mipmap generator 816 (Schilling & Knittel, section
//! 12): the model, its twin in `rtl/mipmap/` with the behavioural frame store, the twin's
//! parameters and video stimulus.

use super::twin;
use hdl::kernel::Signal;
use std::path::PathBuf;
use units::mipmap::mipmap_gen_816::{MipmapGen, MipmapParams, Rounding, Scan};
use verif::cosim::{CosimModel, CosimUnit, ModelSim, Port, Unmodelled};

/// Mipmap generator 816 against `rtl/mipmap/mipmap_gen_816.v` (with `level_fig14.v`,
/// `fifo_fig14.v`) writing the behavioural `frame_store_826.v`. Compared besides its ports:
/// every level's texel stream (`lK_valid`, `lK_texel`), which fixes every texel of every
/// level the frame store receives. With `sync_error_at`, the `sof` of that video texel is
/// inverted (the sticky sync error, code 3).
pub struct MipmapCosim {
    pub params: MipmapParams,
    /// Of eight cycles, how many carry a video texel (8: back to back, as the video port).
    pub rate: u32,
    pub sync_error_at: Option<usize>,
}

impl MipmapCosim {
    pub fn new(params: MipmapParams) -> MipmapCosim {
        MipmapCosim {
            params,
            rate: 8,
            sync_error_at: None,
        }
    }
}

impl CosimUnit for MipmapCosim {
    fn name(&self) -> &str {
        "mipmap_gen_816"
    }
    fn top(&self) -> &str {
        "mipmap_gen_816_with_store"
    }
    fn rtl(&self) -> Vec<PathBuf> {
        twin(vec![
            "mipmap/mipmap_gen_816.v",
            "mipmap/level_fig14.v",
            "mipmap/fifo_fig14.v",
        ])
    }
    fn bench_rtl(&self) -> Vec<PathBuf> {
        twin(vec![
            "mipmap/mipmap_gen_816_with_store.v",
            "mipmap/frame_store_826.v",
        ])
    }
    fn parameters(&self) -> Vec<(&'static str, i64)> {
        let p = &self.params;
        let scan = match p.scan {
            Scan::Progressive => 0,
            Scan::InterlacedTop => 1,
            Scan::InterlacedBottom => 2,
        };
        vec![
            ("WIDTH", p.width.into()),
            ("HEIGHT", p.height.into()),
            ("SCAN", scan),
            ("ROUND", i64::from(p.rounding == Rounding::Round)),
        ]
    }
    fn model(&self) -> Result<Box<dyn CosimModel>, String> {
        if !(1..=8).contains(&self.rate) {
            return Err(format!("mipmap_gen_816: rate {}: 1..=8", self.rate));
        }
        let dut = MipmapGen::new(self.name(), self.params)?;
        let probes: Vec<Port> = (1..dut.dims().len())
            .flat_map(|k| {
                [
                    Port::uint(format!("l{k}_valid"), 1),
                    Port::uint(format!("l{k}_texel"), 8),
                ]
            })
            .collect();
        let m = ModelSim::new(dut, |d: &mut MipmapGen, v: &[u64]| {
            Signal::set_row([&mut d.valid, &mut d.texel, &mut d.sof], v);
        });
        Ok(Box::new(m.probes(probes, |d: &MipmapGen| {
            d.levels
                .iter()
                .flat_map(|l| [l.out_valid.bits(), l.out_texel.bits()])
                .collect()
        })))
    }
    /// The levels the wrapper has (ten) beyond the frame's: open.
    fn unmodelled(&self) -> Vec<Unmodelled> {
        (self.params.levels().len()..=10)
            .flat_map(|k| ["valid", "texel"].map(|f| Unmodelled::Open(format!("l{k}_{f}"))))
            .collect()
    }
    /// Frames of texels (0 and 255 an eighth of the time each, otherwise any), `rate` of
    /// eight cycles carrying one (blanking in between at random), `sof` with each frame's
    /// first texel.
    fn stimulus(&self, seed: verif::Seed, cycles: usize) -> Vec<Vec<u64>> {
        use proptest::strategy::Just;
        let frame = u64::from(self.params.width) * u64::from(self.params.height);
        let texel = proptest::prop_oneof![1 => Just(0u64), 1 => Just(255u64), 6 => 0u64..256];
        let mut st = verif::Stimulus::new(seed);
        let mut sent = 0u64;
        (0..cycles)
            .map(|c| {
                let (slot, t) = st.draw(&(0u32..8, texel.clone()));
                // No texel during reset: the first frame starts after it.
                if c < verif::cosim::RESET_CYCLES || slot >= self.rate {
                    return vec![0, 0, 0];
                }
                let mut sof = sent.is_multiple_of(frame);
                if self.sync_error_at == Some(sent as usize) {
                    sof = !sof;
                }
                sent += 1;
                vec![1, t, u64::from(sof)]
            })
            .collect()
    }
}
