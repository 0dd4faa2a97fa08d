//! The TEXRAM access (`hdl::texram`, its behavioural stub for now) against the integer
//! reference of `tb::texram` (bit-exact on 10^6 random requests over square, rectangular and
//! 1-wide maps and every border operation) and the f64 golden model of `golden::texram`
//! (within half an LSB with the chip's truncated weights; inside the min/max of the eight
//! texels; integer lambda is the bilinear of that level). Seeds are printed; replay with
//! `TEXRTL_SEED`.

use hdl::texram::stub::TexramStub;
use hdl::texram::{Border, Drf, TexramAccess, TexramRequest};
use proptest::prelude::*;
use tb::texram::{RefBorder, RefMipmap};

const MAPS: [(u32, u32); 5] = [(6, 6), (7, 3), (0, 5), (4, 0), (2, 2)];

fn borders() -> [(Border, RefBorder, golden::texram::Border); 4] {
    use golden::texram::Border as G;
    [
        (Border::Wrap, RefBorder::Wrap, G::Wrap),
        (Border::Clamp, RefBorder::Clamp, G::Clamp),
        (Border::Mirror, RefBorder::Mirror, G::Mirror),
        (Border::Colour(77), RefBorder::Colour(77), G::Colour(77.0)),
    ]
}

/// A chip with `map` loaded in DRF 0, and the reference's mipmap of the same level 0.
fn setup(wl: u32, hl: u32, border: Border, seed: u64) -> (TexramStub, RefMipmap) {
    let (w, h) = (1u32 << wl, 1u32 << hl);
    let level0: Vec<u8> = (0..w * h)
        .map(|k| ((u64::from(k) * 0x9e37_79b9 + seed) >> 13) as u8)
        .collect();
    let mut chip = TexramStub::new();
    chip.set_drf(0, Drf::new(wl, hl, border)).unwrap();
    chip.load(0, &level0).unwrap();
    (chip, RefMipmap::build(w, h, &level0))
}

/// Requests over the map and two texels beyond its edges, every lambda.
fn requests(wl: u32, hl: u32) -> impl Strategy<Value = (i32, i32, i32)> {
    let (w, h) = ((1i32 << wl) << 8, (1i32 << hl) << 8);
    (-512..w + 512, -512..h + 512, -4 * 256..=10 * 256)
}

#[test]
fn the_access_is_bit_exact_against_the_integer_reference() {
    let mut stim = verif::seeded_stimulus("texram bit-exact");
    let per = 1_000_000 / (MAPS.len() * 4);
    for (wl, hl) in MAPS {
        for (border, rb, _) in borders() {
            let (mut chip, reference) = setup(wl, hl, border, stim.seed().0);
            for (u, v, lambda) in stim.draw_n(&requests(wl, hl), per) {
                let r = chip
                    .access(TexramRequest {
                        drf: 0,
                        u,
                        v,
                        lambda,
                    })
                    .unwrap();
                let (texels, value) = reference.access(u, v, lambda, rb);
                assert_eq!(
                    (r.texels, r.value),
                    (texels, value),
                    "map {wl},{hl} {border:?} u {u} v {v} lambda {lambda}"
                );
            }
        }
    }
}

#[test]
fn the_access_is_within_half_an_lsb_of_golden_and_within_its_texels() {
    let mut stim = verif::seeded_stimulus("texram golden");
    let mut worst: f64 = 0.0;
    for (wl, hl) in MAPS {
        for (border, rb, gb) in borders() {
            let (mut chip, reference) = setup(wl, hl, border, stim.seed().0);
            let g = golden::texram::Mipmap {
                width: 1 << wl,
                height: 1 << hl,
                levels: &reference.levels,
                border: gb,
            };
            let lmax = reference.levels.len() - 1;
            for (u, v, lambda) in stim.draw_n(&requests(wl, hl), 20_000) {
                let r = chip
                    .access(TexramRequest {
                        drf: 0,
                        u,
                        v,
                        lambda,
                    })
                    .unwrap();
                let (fu, fv, fl) = (
                    f64::from(u) / 256.0,
                    f64::from(v) / 256.0,
                    f64::from(lambda) / 256.0,
                );
                let want = golden::texram::trilinear(
                    &g,
                    &golden::texram::Weights::truncated(fu, fv, fl, lmax),
                );
                let err = (f64::from(r.value) - want).abs();
                worst = worst.max(err);
                assert!(
                    err <= golden::texram::ERROR_BOUND_LSB,
                    "{wl},{hl} {rb:?} ({u},{v},{lambda}): {} vs {want}",
                    r.value
                );
                let (lo, hi) = (
                    r.texels.iter().min().unwrap(),
                    r.texels.iter().max().unwrap(),
                );
                assert!((lo..=hi).contains(&&r.value));
                if lambda % 256 == 0 || lambda < 0 {
                    // Integer (or negative) lambda: the coarser level has no weight.
                    assert_eq!(r.f, 0);
                }
            }
        }
    }
    eprintln!("texram against golden (truncated weights): worst error {worst:.4} LSB");
}

#[test]
fn integer_lambda_is_exactly_the_bilinear_of_its_level() {
    let (mut chip, reference) = setup(5, 4, Border::Wrap, 1);
    let g = golden::texram::Mipmap {
        width: 32,
        height: 16,
        levels: &reference.levels,
        border: golden::texram::Border::Wrap,
    };
    for l in 0..=5 {
        for (u, v) in [(300, 900), (2000, 17), (8191, 4095)] {
            let r = chip
                .access(TexramRequest {
                    drf: 0,
                    u,
                    v,
                    lambda: l << 8,
                })
                .unwrap();
            let w = golden::texram::Weights::truncated(
                f64::from(u) / 256.0,
                f64::from(v) / 256.0,
                f64::from(l),
                5,
            );
            let bil = golden::texram::trilinear(&g, &golden::texram::Weights { f: 0.0, ..w });
            assert!((f64::from(r.value) - bil).abs() <= 0.5 + 1e-9, "level {l}");
            assert_eq!(r.fine, l as u32);
        }
    }
}
