//! The chip side of footprint assembly (section 10, eq. 22): the rasterizer sends `u, v,
//! lambda` and then `dr = (du, dv)` and `N` (the setup unit's); the sample generator makes the
//! N sample points `p_n = p + (n/2) dr` for `n = -(N-1), -(N-3), ..., N-1` (eq. 22 prints only
//! the odd `n` of an even N; N = 1 is `p` itself), one trilinear access of the TEXRAM chip
//! each, and the accumulator adds the accesses' exact trilinear sums (818 before its
//! rounding) and rounds their mean once: `(S + 2^(23+k)) >> (24+k)` for `N = 2^k`.
//!
//! # Formats
//! | value | format |
//! |---|---|
//! | `u`, `v` | sQ12.8 (the chip's) |
//! | `du`, `dv` | sQ11.14 (the setup unit's) |
//! | sample points `p_n` | sQ16.15: `p_0 = p - (N-1) dr/2`, then `+ dr`; exact (dr/2 is sQ11.15) |
//! | the access's `u`, `v` | `p_n` rounded half up to sQ12.8, held to its range \[C\] |
//! | accumulator | uQ14.24 (38 bits): up to 64 sums of at most `255 * 2^24` |
//! | result | u8, one rounding of the mean, half up |
//!
//! Luminance maps only on the TEXRAM chip \[C\] (818's exact sum is the luminance one).
//!
//! The same generator and accumulator drive Figure 6's texture unit 602 (bilinear on CCC
//! textures, RGB: the document's low-cost system, "bilinear interpolation, CCC and footprint
//! assembly", section 4) through [`SampleTarget`]: each point less half a texel, rounded half
//! up to the unit's `F` fraction bits and held inside the texture; the accumulator adds 622's
//! exact sums per channel (`2F` fraction bits) and rounds each mean once. There is no mipmap:
//! lambda is not used.
//!
//! # Timing
//! The generator takes a pixel when it holds none (`px_ready`), offers one sample a cycle to
//! the chip's request port and moves on when the chip takes it (one a slot, when no page
//! faults); it takes the next pixel in the cycle after its last sample went. The accumulator
//! counts the chip's results against the N of the pixels in flight (in order, at most four)
//! and outputs a pixel with its last sample's result: setup of pixel i+1 and assembly of pixel
//! i overlap, and the chip never waits for the generator.

use super::setup_fig12::{Setup, STEP_FRAC};
use crate::fx::Format;
use crate::kernel::{Module, Reg, Signal};
use crate::texram::texram_802::Texram802;
use crate::texram::trilinear_818::trilinear_sum;
use crate::texram::{TexramAccess, TexramRequest, FRAC, UV_BITS};

/// Fraction bits of the sample points: the step's plus one (for `dr / 2`).
pub const POINT_FRAC: u32 = STEP_FRAC + 1;
/// Pixels the accumulator counts at most (the chip holds two accesses, the texture unit three;
/// the generator one pixel): the generator waits for room.
const IN_FLIGHT: u64 = 6;

/// The first sample point and the step, raw sQ.15: `p - (N-1) dr / 2` and `dr`.
pub fn first_point(u: i32, du: i32, log2_n: u32) -> (i64, i64) {
    let n1 = (1i64 << log2_n) - 1;
    let p = i64::from(u) << (POINT_FRAC - FRAC);
    // dr in sQ.15 is 2 du (du is sQ.14); (N-1) dr / 2 is (N-1) du.
    (p - n1 * i64::from(du), 2 * i64::from(du))
}

/// A sample point rounded half up to the chip's sQ12.8, held to its range.
pub fn access_coord(p: i64) -> i32 {
    let half = 1i64 << (POINT_FRAC - FRAC - 1);
    let lim = 1i64 << (UV_BITS - 1);
    ((p + half) >> (POINT_FRAC - FRAC)).clamp(-lim, lim - 1) as i32
}

/// The mean of `2^log2_n` exact trilinear sums, rounded once, half up.
pub fn mean(sum: u64, log2_n: u32) -> u8 {
    mean_of(sum, log2_n, 24)
}

/// One assembled pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Assembled {
    pub value: u8,
    /// Samples (accesses), and the slots and bank faults they took.
    pub n: u32,
    pub slots: u32,
    pub faults: u32,
}

/// The generator and accumulator at transaction level over any [`TexramAccess`] (the stub,
/// the chip behind `Texram802Access`): what [`FootprintAssembly`] does, access by access.
pub fn assemble(
    chip: &mut dyn TexramAccess,
    drf: u8,
    (u, v): (i32, i32),
    s: &Setup,
) -> Result<Assembled, String> {
    let (mut pu, du) = first_point(u, s.du, s.log2_n);
    let (mut pv, dv) = first_point(v, s.dv, s.log2_n);
    let (mut sum, mut slots, mut faults) = (0u64, 0, 0);
    for _ in 0..1u32 << s.log2_n {
        let r = chip.access(TexramRequest {
            drf,
            u: access_coord(pu),
            v: access_coord(pv),
            lambda: s.lambda,
        })?;
        sum += trilinear_sum(&r.texels, r.a, r.b, r.f);
        slots += r.slots;
        faults += r.faults;
        pu += du;
        pv += dv;
    }
    Ok(Assembled {
        value: mean(sum, s.log2_n),
        n: 1 << s.log2_n,
        slots,
        faults,
    })
}

/// What the generator drives and the accumulator reads: the TEXRAM chip 802 (trilinear,
/// luminance) or the Figure 6 texture unit 602 (bilinear, RGB; the document's low-cost
/// system, section 4).
pub trait SampleTarget: Module {
    /// Channels of a result (1 luminance, 3 RGB) and the fraction bits of its exact sums.
    fn channels(&self) -> usize;
    fn sum_frac(&self) -> u32;
    /// Offers (or not) a sample at the point `p` (sQ.15, texel centres at k + 1/2).
    fn present(&mut self, valid: bool, drf: u64, p: (i64, i64), lambda: i64);
    /// After `eval`: the sample offered was taken.
    fn taken(&self) -> bool;
    /// After `eval`: a sample's exact sums, one a channel, in the order samples were taken.
    fn result(&self) -> Option<[u64; 3]>;
}

impl SampleTarget for Texram802 {
    fn channels(&self) -> usize {
        1
    }
    fn sum_frac(&self) -> u32 {
        24
    }
    fn present(&mut self, valid: bool, drf: u64, p: (i64, i64), lambda: i64) {
        self.req_valid.set_bool(valid);
        self.req_drf.set_bits(drf);
        self.req_u.set_raw(i64::from(access_coord(p.0)));
        self.req_v.set_raw(i64::from(access_coord(p.1)));
        self.req_lambda.set_raw(lambda);
    }
    fn taken(&self) -> bool {
        self.req_valid.is_high() && self.req_ready.is_high()
    }
    fn result(&self) -> Option<[u64; 3]> {
        self.output
            .out_valid
            .q()
            .is_high()
            .then(|| [self.output.out_sum.q().bits(), 0, 0])
    }
}

/// A sample point as the texture unit 602 takes it: texel `(x, y)` at integer coordinates
/// (the point less half a texel), `F` fraction bits rounded half up, held inside the texture
/// (`0 ..= size * 2^F - 1`: the unit clamps its footprint to the edge).
pub fn unit_coord(p: i64, frac_bits: u32, size: u32) -> u32 {
    let shift = POINT_FRAC - frac_bits;
    let half = 1i64 << (shift - 1);
    let q = (p - (1i64 << (POINT_FRAC - 1)) + half) >> shift;
    q.clamp(0, (i64::from(size) << frac_bits) - 1) as u32
}

impl SampleTarget for crate::texmem::texture_unit_602::TextureUnit {
    fn channels(&self) -> usize {
        3
    }
    fn sum_frac(&self) -> u32 {
        2 * self.params().frac_bits
    }
    fn present(&mut self, valid: bool, _drf: u64, p: (i64, i64), _lambda: i64) {
        let tp = *self.params();
        self.in_valid.set_bool(valid);
        self.in_u
            .set_bits(u64::from(unit_coord(p.0, tp.frac_bits, tp.width)));
        self.in_v
            .set_bits(u64::from(unit_coord(p.1, tp.frac_bits, tp.height)));
        self.in_newline.set_bool(false);
    }
    fn taken(&self) -> bool {
        self.in_valid.is_high() && self.in_ready.is_high()
    }
    fn result(&self) -> Option<[u64; 3]> {
        let b = &self.bilinear;
        self.out_valid
            .is_high()
            .then(|| b.sums.each_ref().map(|s| s.q().bits()))
    }
}

/// The sample generator's state: samples still to send, the point, the step, the pixel's DRF
/// and lambda (its next state is [`FootprintAssembly::eval`]'s).
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_generator")]
struct Generator {
    #[instance]
    name: &'static str,
    #[reg]
    left: Reg,
    #[reg]
    pu: Reg,
    #[reg]
    pv: Reg,
    #[reg]
    du: Reg,
    #[reg]
    dv: Reg,
    #[reg]
    drf: Reg,
    #[reg]
    lambda: Reg,
}

impl Generator {
    /// Registers only: [`FootprintAssembly::eval`] sets their next values.
    fn eval(&mut self) {}
}

/// The accumulator's state: the pixels in flight (3 bits of log2 N each, oldest lowest), their
/// count, the results counted for the oldest, the sums (one a channel), and the result.
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_accumulator")]
pub struct Accumulator {
    #[instance]
    name: &'static str,
    #[reg]
    pend: Reg,
    #[reg]
    pend_n: Reg,
    #[reg]
    count: Reg,
    #[reg]
    sums: Vec<Reg>,
    #[reg]
    pub out_valid: Reg,
    /// The first channel (luminance), and R, G, B (luminance three times).
    #[reg]
    pub out_value: Reg,
    #[reg]
    pub out_rgb: Reg,
    #[reg]
    pub out_n: Reg,
    #[reg]
    pub pixels: Reg,
}

impl Accumulator {
    /// Registers only: [`FootprintAssembly::eval`] sets their next values.
    fn eval(&mut self) {}
}

/// The sample generator and accumulator with the chip (or unit) behind them.
#[derive(Clone, Debug, Module)]
#[module(kind = "footprint_assembly")]
pub struct FootprintAssembly<T: SampleTarget = Texram802> {
    #[input]
    pub px_valid: Signal,
    #[output]
    pub px_ready: Signal,
    #[input]
    pub px_drf: Signal,
    #[input]
    pub px_u: Signal,
    #[input]
    pub px_v: Signal,
    #[input]
    pub px_lambda: Signal,
    #[input]
    pub px_du: Signal,
    #[input]
    pub px_dv: Signal,
    #[input]
    pub px_log2_n: Signal,
    #[child]
    gen: Generator,
    /// The result: `out_valid`, `out_value`, `out_rgb`, `out_n`, and the pixels counted.
    #[child]
    pub acc: Accumulator,
    #[child]
    pub chip: T,
}

impl<T: SampleTarget> FootprintAssembly<T> {
    pub fn new(chip: T) -> FootprintAssembly<T> {
        let point = |n| Reg::new(n, Format::signed(32, POINT_FRAC as i32));
        let frac = chip.sum_frac();
        // Up to 64 sums of at most 255 * 2^frac.
        let sum = |n| Reg::new(n, Format::unsigned(frac + 14, frac as i32));
        FootprintAssembly {
            px_valid: Signal::bit("px_valid"),
            px_ready: Signal::bit("px_ready"),
            px_drf: Signal::new("px_drf", Format::uint(3)),
            px_u: Signal::new("px_u", Format::signed(UV_BITS, FRAC as i32)),
            px_v: Signal::new("px_v", Format::signed(UV_BITS, FRAC as i32)),
            px_lambda: Signal::new("px_lambda", Format::signed(14, 8)),
            px_du: Signal::new("px_du", Format::signed(26, STEP_FRAC as i32)),
            px_dv: Signal::new("px_dv", Format::signed(26, STEP_FRAC as i32)),
            px_log2_n: Signal::new("px_log2_n", Format::uint(3)),
            gen: Generator {
                name: "generator",
                left: Reg::new("left", Format::uint(7)),
                pu: point("pu"),
                pv: point("pv"),
                du: point("step_u"),
                dv: point("step_v"),
                drf: Reg::new("drf", Format::uint(3)),
                lambda: Reg::new("lambda", Format::signed(14, 8)),
            },
            acc: Accumulator {
                name: "accumulator",
                pend: Reg::new("pend", Format::uint(3 * IN_FLIGHT as u32)),
                pend_n: Reg::new("pend_n", Format::uint(4)),
                count: Reg::new("count", Format::uint(7)),
                sums: ["sum0", "sum1", "sum2"][..chip.channels()]
                    .iter()
                    .map(|n| sum(n))
                    .collect(),
                out_valid: Reg::new("out_valid", Format::uint(1)),
                out_value: Reg::new("out_value", Format::uint(8)),
                out_rgb: Reg::new("out_rgb", Format::uint(24)),
                out_n: Reg::new("out_n", Format::uint(7)),
                pixels: Reg::new("pixels", Format::uint(40)),
            },
            chip,
        }
    }

    /// The generator: a pixel taken (its log2 N), or the current sample offered.
    fn generate(&mut self) -> Option<u64> {
        let left = self.gen.left.q().bits();
        // A pixel is taken when the last has all its samples out and the accumulator has
        // room to count it.
        let ready = left == 0 && self.acc.pend_n.q().bits() < IN_FLIGHT;
        self.px_ready.set_bool(ready);
        let p = (self.gen.pu.q().raw(), self.gen.pv.q().raw());
        let (drf, lambda) = (self.gen.drf.q().bits(), self.gen.lambda.q().raw());
        self.chip.present(left > 0, drf, p, lambda);
        if ready && self.px_valid.is_high() {
            let k = self.px_log2_n.bits() as u32;
            let (pu, du) = first_point(self.px_u.raw() as i32, self.px_du.raw() as i32, k);
            let (pv, dv) = first_point(self.px_v.raw() as i32, self.px_dv.raw() as i32, k);
            self.gen.left.set_next_bits(1 << k);
            for (r, x) in [
                (&mut self.gen.pu, pu),
                (&mut self.gen.pv, pv),
                (&mut self.gen.du, du),
                (&mut self.gen.dv, dv),
            ] {
                r.set_next_raw(x);
            }
            self.gen.drf.set_next_bits(self.px_drf.bits());
            self.gen.lambda.set_next_raw(self.px_lambda.raw());
            return Some(u64::from(k));
        }
        None
    }

    /// After the chip settled: the sample taken moves the generator on.
    fn advance(&mut self) {
        if self.gen.left.q().bits() > 0 && self.chip.taken() {
            self.gen.left.set_next_bits(self.gen.left.q().bits() - 1);
            let pu = self.gen.pu.q().raw() + self.gen.du.q().raw();
            let pv = self.gen.pv.q().raw() + self.gen.dv.q().raw();
            self.gen.pu.set_next_raw(pu);
            self.gen.pv.set_next_raw(pv);
        }
    }

    /// The oldest pixel complete with `sums`: its result into the output registers.
    fn emit(&mut self, sums: [u64; 3], k: u32, count: u64) {
        let frac = self.chip.sum_frac();
        let ch = sums.map(|s| u64::from(mean_of(s, k, frac)));
        let rgb = if self.chip.channels() == 1 {
            ch[0] * 0x01_01_01
        } else {
            ch[0] << 16 | ch[1] << 8 | ch[2]
        };
        self.acc.out_valid.set_next_bool(true);
        self.acc.out_value.set_next_bits(ch[0]);
        self.acc.out_rgb.set_next_bits(rgb);
        self.acc.out_n.set_next_bits(count);
        self.acc
            .pixels
            .set_next_bits(self.acc.pixels.q().bits() + 1);
    }

    /// The accumulator: the chip's result added; the oldest pixel out with its last one;
    /// `taken` the log2 N of a pixel the generator took this cycle.
    fn accumulate(&mut self, taken: Option<u64>) {
        let (mut pend, mut n) = (self.acc.pend.q().bits(), self.acc.pend_n.q().bits());
        self.acc.out_valid.set_next_bool(false);
        if let Some(r) = self.chip.result().filter(|_| n > 0) {
            let k = (pend & 7) as u32;
            let sums: [u64; 3] =
                std::array::from_fn(|c| self.acc.sums.get(c).map_or(0, |s| s.q().bits()) + r[c]);
            let count = self.acc.count.q().bits() + 1;
            if count == 1 << k {
                self.emit(sums, k, count);
                for s in &mut self.acc.sums {
                    s.set_next_bits(0);
                }
                self.acc.count.set_next_bits(0);
                pend >>= 3;
                n -= 1;
            } else {
                for (reg, s) in self.acc.sums.iter_mut().zip(sums) {
                    reg.set_next_bits(s);
                }
                self.acc.count.set_next_bits(count);
            }
        }
        if let Some(k) = taken {
            pend |= k << (3 * n);
            n += 1;
        }
        self.acc.pend.set_next_bits(pend);
        self.acc.pend_n.set_next_bits(n);
    }
}

/// The mean of `2^k` exact sums with `frac` fraction bits, rounded once, half up.
pub fn mean_of(sum: u64, k: u32, frac: u32) -> u8 {
    ((sum + (1u64 << (frac - 1 + k))) >> (frac + k)) as u8
}

impl<T: SampleTarget> FootprintAssembly<T> {
    /// The generator's sample to the chip, the chip, and its result into the accumulator.
    pub fn eval(&mut self) {
        let taken = self.generate();
        self.chip.eval();
        self.advance();
        self.accumulate(taken);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_points_round_half_up_to_the_chips_grid_and_hold_to_its_range() {
        // sQ.15 to sQ.8: 128 raw units an LSB, 64 the half.
        assert_eq!(access_coord(0), 0);
        assert_eq!(access_coord(63), 0);
        assert_eq!(access_coord(64), 1);
        assert_eq!(access_coord(-64), 0);
        assert_eq!(access_coord(-65), -1);
        assert_eq!(access_coord(128 * 5 + 64), 6);
        let lim = 1i64 << 20;
        assert_eq!(access_coord(lim << 7), (lim - 1) as i32);
        assert_eq!(access_coord(-(lim << 7) - 1000), -lim as i32);
    }

    #[test]
    fn the_mean_rounds_once_half_up() {
        let one = 1u64 << 24;
        assert_eq!(mean(0, 0), 0);
        assert_eq!(mean(255 * one, 0), 255);
        // (3 + 4) / 2 = 3.5 -> 4; (3 + 3 + 3 + 4) / 4 = 3.25 -> 3.
        assert_eq!(mean(7 * one, 1), 4);
        assert_eq!(mean(13 * one, 2), 3);
        assert_eq!(mean(7 * one - 1, 1), 3);
        assert_eq!(mean(64 * 255 * one, 6), 255);
    }

    #[test]
    fn the_first_point_is_half_the_span_back() {
        // N = 4, step 1 texel (sQ.14: 16384): p - 1.5 texels, step 1 texel in sQ.15.
        assert_eq!(first_point(256, 16384, 2), ((256 << 7) - 3 * 16384, 32768));
        assert_eq!(first_point(-5, -3, 0), (-5 << 7, -6));
    }
}
