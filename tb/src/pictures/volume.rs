//! The ray-cast volume of the report: a classified built-in volume on four chips of Figure 15
//! in lock-step, every sample checked against the reference of its plane.

use crate::volume::ref_sample;
use hdl::kernel::Sim;
use units::volume::layout::{Mode, VolumeParams, POS_FRAC};

/// A built-in volume: two nested shells and a bar, values 0..=255.
pub fn builtin_volume(n: u32) -> Vec<u8> {
    let c = f64::from(n) / 2.0;
    (0..n * n * n)
        .map(|k| {
            let (x, y, z) = (k % n, k / n % n, k / (n * n));
            let d = [x, y, z].map(|a| f64::from(a) + 0.5 - c);
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / c;
            let shell = |r0: f64, w: f64| (1.0 - ((r - r0) / w).abs()).max(0.0);
            let bar = if d[0].abs() < c / 6.0 && d[1].abs() < c / 6.0 {
                0.6
            } else {
                0.0
            };
            let v = (shell(0.85, 0.12) + 0.8 * shell(0.45, 0.15)).max(bar);
            (255.0 * v.min(1.0)).round() as u8
        })
        .collect()
}

/// The host's classification (a transfer function): a value's R, G, B, alpha planes.
pub fn classify(v: &[u8]) -> [Vec<u8>; 4] {
    let f = |t: fn(u8) -> u8| v.iter().map(|&x| t(x)).collect::<Vec<u8>>();
    [
        f(|x| x),
        f(|x| (255 - x) / 2 + 64),
        f(|x| if x > 150 { 40 } else { 200 }),
        f(|x| (u32::from(x.saturating_sub(40)) * 60 / 215) as u8),
    ]
}

/// The picture: `side x side` rays through the built-in volume (`n^3`, classified) on four
/// chips in lock-step, each sample checked against the reference of its plane, composited
/// front to back by the golden compositor. Returns the RGB pixels and the samples.
pub fn render(n: u32, side: u32) -> Result<(Vec<[u8; 3]>, u64), String> {
    use units::volume::lockstep::VolumeLockstep;
    let planes = classify(&builtin_volume(n));
    let p = VolumeParams::new(n, n, n);
    let mut sim = Sim::new(VolumeLockstep::new(p, &planes)?);
    sim.reset(2);
    let one = 1i64 << POS_FRAC;
    let steps = 2 * n as u16;
    let ray = |px: u32, py: u32| -> [i64; 6] {
        // Slightly oblique rays that stay inside the volume from front to back.
        let s = |a: u32| (i64::from(a) * (i64::from(n) - 3) * one) / i64::from(side);
        [s(px), s(py), -one, one / 32, one / 64, one / 2]
    };
    let (mut next, mut samples, mut pixels) = (0u32, Vec::new(), Vec::new());
    let total = side * side;
    let mut guard = 0u64;
    while pixels.len() < total as usize {
        guard += 1;
        if guard > u64::from(total) * u64::from(steps) * 20 {
            return Err("the lock-step chips stalled".into());
        }
        let d = &mut sim.dut;
        d.port.valid.set_bool(next < total);
        let r = ray(next % side, next / side);
        for c in 0..3 {
            d.port.p[c].set_raw(r[c]);
            d.port.d[c].set_raw(r[3 + c]);
        }
        d.port.steps.set_bits(u64::from(steps));
        sim.eval();
        let d = &sim.dut;
        next += u32::from(d.port.valid.is_high() && d.ready.is_high());
        if d.out_valid.is_high() {
            let c = &d.chips[0];
            let pt = c.out.p.each_ref().map(|r| r.q().raw());
            let rgba = (d.out_rgba.bits() as u32).to_be_bytes();
            for (plane, got) in planes.iter().zip(rgba) {
                let (want, _) = ref_sample(plane, p.dims, pt, Mode::Value);
                if want != got {
                    return Err(format!("sample at {pt:?}: chip {got}, reference {want}"));
                }
            }
            samples.push(rgba.map(|x| f64::from(x) / 255.0));
            if samples.len() == usize::from(steps) {
                let c = golden::volume::composite(&samples);
                pixels.push([0, 1, 2].map(|k| (255.0 * c[k]).round().min(255.0) as u8));
                samples.clear();
            }
        }
        sim.tick();
    }
    if sim.dut.out_of_step.q().is_high() {
        return Err("the four chips fell out of step".into());
    }
    Ok((pixels, u64::from(total) * u64::from(steps)))
}
