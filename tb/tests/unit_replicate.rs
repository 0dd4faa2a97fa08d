//! Replicate unit 152: windows of para. 0056-0057 and Equation 1's Bezier points, computed here
//! as the matrix product the patent writes.

use hdl::fx::Format;
use hdl::kernel::Sim;
use units::bump::replicate_152::Replicate;
use verif::{Seed, Stimulus};

fn matmul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

#[test]
fn windows_and_bezier_points() {
    let texel = Format::unsigned(8, 2);
    let mut stim = Stimulus::new(Seed(152));
    let left = [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.5, 0.5]];
    let right = [[0.5, 0.0, 0.0], [0.5, 1.0, 0.5], [0.0, 0.0, 0.5]];
    for bezier in [false, true] {
        let mut sim = Sim::new(Replicate::new("rep", texel, bezier)).check_schedule(true);
        for _ in 0..2000 {
            let g: [u8; 9] = stim.draw(&proptest::array::uniform9(proptest::num::u8::ANY));
            for (h, g) in sim.dut.h.iter_mut().zip(g) {
                h.set_bits(u64::from(g));
            }
            sim.eval();
            let grid = [[g[0], g[1], g[2]], [g[3], g[4], g[5]], [g[6], g[7], g[8]]]
                .map(|r| r.map(|x| f64::from(x) / 4.0));
            let pts = if bezier {
                matmul(matmul(left, grid), right)
            } else {
                grid
            };
            // Red top-left, green top-right, blue bottom-left, alpha bottom-right windows.
            for (w, (r0, c0)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
                for (k, (dr, dc)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
                    let got = sim.dut.w[w][k].fx().to_f64();
                    assert_eq!(
                        got,
                        pts[r0 + dr][c0 + dc],
                        "bezier={bezier} window {w} point {k}"
                    );
                }
            }
            sim.tick();
        }
    }
}
