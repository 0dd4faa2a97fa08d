//! Footprint assembly on the FIG. 7 height-map pipeline (US 2004/0207631 para. 0081, "improved
//! anisotropic filtering"): the sample generator of section 10 in front of the pipeline, whose
//! tangent average (`bump/tangent_average_0081.rs`) adds up the tangents of a pixel's N
//! samples and normalises their mean once.
//!
//! The generator takes a pixel (`u`, `v` in the pipeline's position format, the setup unit's
//! step and N, the height scale) when it has at most one sample of the last left, and feeds
//! the pipeline one sample a clock (the pipeline has no backpressure): points exact in sQ.15
//! as on the TEXRAM (`p - (N-1) dr/2`, then `+ dr`), rounded half up to the position's
//! fraction bits. A pixel takes N clocks; its normal comes out with its last sample's, after
//! the pipeline's latency. Trilinear pipelines are not driven here (\[C\]: level 0 only, as the
//! FIG. 7 pipeline's default).

use super::assembly_fig12::POINT_FRAC;
use super::setup_fig12::STEP_FRAC;
use crate::bump::normal_pipeline_fig7::NormalPipeline;
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};

/// A point (sQ.15) in a position format with `frac` fraction bits: rounded half up below 15
/// bits, exact above, held to the format's range.
pub fn to_position(p: i64, fmt: Format) -> i64 {
    let frac = fmt.frac() as u32;
    let q = if frac < POINT_FRAC {
        let sh = POINT_FRAC - frac;
        (p + (1 << (sh - 1))) >> sh
    } else {
        p << (frac - POINT_FRAC)
    };
    q.clamp(fmt.min_raw() as i64, fmt.max_raw() as i64)
}

/// A position (raw, `frac` fraction bits) as a point in sQ.15 (exact for `frac <= 15`).
pub fn from_position(x: i64, frac: u32) -> i64 {
    if frac <= POINT_FRAC {
        x << (POINT_FRAC - frac)
    } else {
        x >> (frac - POINT_FRAC)
    }
}

/// The sample generator's state: the samples left of the pixel, the current one's index and
/// point, the step between samples, the pixel's `log2_n` and scale. Its next state is the
/// owner's [`FootprintNormals::eval`], which drives the pipeline from it.
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_generator")]
struct Generator {
    #[instance]
    name: &'static str,
    #[reg]
    left: Reg,
    #[reg]
    index: Reg,
    #[reg]
    log2_n: Reg,
    #[reg]
    pu: Reg,
    #[reg]
    pv: Reg,
    #[reg]
    du: Reg,
    #[reg]
    dv: Reg,
    #[reg]
    scale: Reg,
}

impl Generator {
    /// Registers only: [`FootprintNormals::eval`] sets their next values.
    fn eval(&mut self) {}
}

/// The generator with the FIG. 7 pipeline (with its tangent average) behind it.
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_normals_0081")]
pub struct FootprintNormals {
    #[input]
    pub px_valid: Signal,
    #[output]
    pub px_ready: Signal,
    #[input]
    pub px_u: Signal,
    #[input]
    pub px_v: Signal,
    #[input]
    pub px_du: Signal,
    #[input]
    pub px_dv: Signal,
    #[input]
    pub px_log2_n: Signal,
    #[input]
    pub px_scale: Signal,
    #[child]
    gen: Generator,
    #[child]
    pub pipe: NormalPipeline,
}

impl FootprintNormals {
    /// `pipe` gets its tangent average here.
    pub fn new(pipe: NormalPipeline) -> FootprintNormals {
        let pipe = pipe.with_tangent_average();
        let (pos, scale) = (pipe.u.fmt(), pipe.scale.fmt());
        let point = |n| Reg::new(n, Format::signed(40, POINT_FRAC as i32));
        FootprintNormals {
            px_valid: Signal::bit("px_valid"),
            px_ready: Signal::bit("px_ready"),
            px_u: Signal::new("px_u", pos),
            px_v: Signal::new("px_v", pos),
            px_du: Signal::new("px_du", Format::signed(26, STEP_FRAC as i32)),
            px_dv: Signal::new("px_dv", Format::signed(26, STEP_FRAC as i32)),
            px_log2_n: Signal::new("px_log2_n", Format::uint(3)),
            px_scale: Signal::new("px_scale", scale),
            gen: Generator {
                name: "generator",
                left: Reg::new("left", Format::uint(7)),
                index: Reg::new("index", Format::uint(7)),
                log2_n: Reg::new("log2_n", Format::uint(3)),
                pu: point("pu"),
                pv: point("pv"),
                du: point("step_u"),
                dv: point("step_v"),
                scale: Reg::new("scale", scale),
            },
            pipe,
        }
    }

    /// The current sample into the pipeline, and the generator's next state.
    fn generate(&mut self) {
        let left = self.gen.left.q().bits();
        let pos = self.pipe.u.fmt();
        let p = &mut self.pipe;
        p.valid_in.set_bool(left > 0);
        p.u.set_raw(to_position(self.gen.pu.q().raw(), pos));
        p.v.set_raw(to_position(self.gen.pv.q().raw(), pos));
        p.scale.follow(self.gen.scale.q());
        let fa = p.fa.as_mut().expect("the pipeline has the tangent average");
        fa.first.set_bool(self.gen.index.q().bits() == 0);
        fa.last.set_bool(left == 1);
        fa.log2_n.follow(self.gen.log2_n.q());
        if left > 0 {
            self.gen.left.set_next_bits(left - 1);
            self.gen.index.set_next_bits(self.gen.index.q().bits() + 1);
            self.gen
                .pu
                .set_next_raw(self.gen.pu.q().raw() + self.gen.du.q().raw());
            self.gen
                .pv
                .set_next_raw(self.gen.pv.q().raw() + self.gen.dv.q().raw());
        }
        // The next pixel is taken as the last sample of this one goes in.
        let ready = left <= 1;
        self.px_ready.set_bool(ready);
        if ready && self.px_valid.is_high() {
            let k = self.px_log2_n.bits() as u32;
            let n1 = (1i64 << k) - 1;
            let frac = pos.frac() as u32;
            let (du, dv) = (self.px_du.raw(), self.px_dv.raw());
            self.gen
                .pu
                .set_next_raw(from_position(self.px_u.raw(), frac) - n1 * du);
            self.gen
                .pv
                .set_next_raw(from_position(self.px_v.raw(), frac) - n1 * dv);
            self.gen.du.set_next_raw(2 * du);
            self.gen.dv.set_next_raw(2 * dv);
            self.gen.left.set_next_bits(1 << k);
            self.gen.index.set_next_bits(0);
            self.gen.log2_n.set_next_bits(u64::from(k));
            self.gen.scale.set_next_raw(self.px_scale.raw());
        }
    }
}

impl FootprintNormals {
    /// The generator's samples into the pipeline, and the pipeline.
    pub fn eval(&mut self) {
        self.generate();
        self.pipe.eval();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_round_half_up_into_the_format_and_back_exactly() {
        let f8 = Format::signed(24, 8);
        assert_eq!(to_position(64, f8), 1);
        assert_eq!(to_position(63, f8), 0);
        assert_eq!(to_position(-64, f8), 0);
        assert_eq!(to_position(-65, f8), -1);
        assert_eq!(to_position(1 << 40, f8), (1 << 23) - 1);
        let f20 = Format::signed(36, 20);
        assert_eq!(to_position(3, f20), 3 << 5);
        for x in [-1000i64, 0, 77, 1 << 20] {
            assert_eq!(to_position(from_position(x, 8), f8), x);
            assert_eq!(from_position(x << 5, 20), x);
        }
        // At the point's own 15 fraction bits both ways are the identity (no rounding).
        let f15 = Format::signed(30, 15);
        for x in [-12345i64, -1, 0, 1, (1 << 29) - 1] {
            assert_eq!((to_position(x, f15), from_position(x, 15)), (x, x));
        }
    }
}
