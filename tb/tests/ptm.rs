//! PTM micro-occlusion (001): the testbenches, the seed's misprints each against a test
//! that fails on the printed form, and the fit's quality.

use golden::ptm::dome;
use tb::ptm::{golden_fit, host_pinv, ref_fit, PtmFitterTb, PtmShaderTb, Swatch};
use tb::runs::ptm::{fit_swatch, quality};
use units::ptm::shader_608::occlusion_at;
use units::ptm::texture_612::PtmFormat;

#[test]
fn the_testbenches_pass_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(64),
        check_schedule: true,
        ..Default::default()
    };
    for tb in [&PtmFitterTb as &dyn verif::Testbench, &PtmShaderTb] {
        let r = verif::run_testbench(tb, &opts, &mut |_| {}).unwrap();
        assert!(
            r.passed,
            "{}: {:?} {:?}",
            r.name, r.failures, r.mismatch_log
        );
        assert!(
            r.coverage_percent > 99.0,
            "{} {:?}",
            r.coverage_percent,
            r.unhit
        );
    }
}

/// \[0036\] says K = 0 is unoccluded; the sample images are white where lit \[0044\]. A texel
/// lit from every light must fit to K = 0 (visibility 255) and one dark from every light to
/// K = 1; taking the samples as K, as printed, gives the reverse.
#[test]
fn a_lit_texel_fits_to_no_occlusion() {
    let lights = dome(3, 8);
    let p = host_pinv(&lights).unwrap();
    let fmt = PtmFormat::for_pinv(&p, 16).unwrap();
    let (lit, dark) = (vec![255u8; lights.len()], vec![0u8; lights.len()]);
    for l in &lights {
        let (u, v) = l.uv();
        let (u, v) = ((u * 16384.0) as i64, (v * 16384.0) as i64);
        assert_eq!(occlusion_at(&fmt, &ref_fit(&p, &fmt, &lit), u, v), 0);
        assert_eq!(occlusion_at(&fmt, &ref_fit(&p, &fmt, &dark), u, v), 255);
    }
    // The printed polarity, K_i = sample_i / 255: the lit texel fits to K = 1, fully
    // occluded, against [0036]'s K = 0 for no occlusion.
    let rows = golden::ptm::Basis::Quadratic.rows(&lights);
    let printed: Vec<f64> = lit.iter().map(|&x| f64::from(x) / 255.0).collect();
    let c = golden::ptm::fit(&rows, &printed).unwrap();
    let (u, v) = lights[0].uv();
    let k = golden::ptm::evaluate(&[c[0], c[1], c[2], c[3], c[4], c[5]], u, v);
    assert!(
        (k - 1.0).abs() < 1e-9,
        "the printed polarity calls a lit texel occluded"
    );
    let (ours, _) = golden_fit(&lights, &p, &fmt, &lit);
    assert!(golden::ptm::evaluate(&ours, u, v).abs() < 1e-9);
}

/// One ring of lights (one elevation) is refused with the reason; two rings are not.
#[test]
fn one_ring_of_lights_is_refused() {
    let e = host_pinv(&dome(1, 16)).unwrap_err();
    assert!(e.contains("one elevation"), "{e}");
    assert!(host_pinv(&dome(2, 8)).is_ok());
    assert!(host_pinv(&dome(3, 1)).unwrap_err().contains("at least 6"));
}

/// Occlusions made by the basis itself (grey samples of a quadratic) are fitted back: the
/// fitter's coefficients within their derived bound of the basis's (the f64 fit recovers
/// them to rounding, `golden::ptm`'s tests).
#[test]
fn a_quadratic_occlusion_is_recovered() {
    let lights = dome(4, 12);
    let p = host_pinv(&lights).unwrap();
    let fmt = PtmFormat::for_pinv(&p, 16).unwrap();
    let c = [0.2, -0.1, 0.15, 0.05, 0.1, 0.4];
    let s: Vec<u8> = lights
        .iter()
        .map(|l| {
            let (u, v) = l.uv();
            let k = golden::ptm::evaluate(&c, u, v);
            (255.0 * (1.0 - k)).round() as u8
        })
        .collect();
    let q = ref_fit(&p, &fmt, &s);
    let (g, bound) = golden_fit(&lights, &p, &fmt, &s);
    for j in 0..6 {
        let got = fmt.coefficient(j, q[j]) as f64 * 2f64.powi(-20);
        assert!(
            (got - g[j]).abs() <= bound[j],
            "{j}: {got} {} {}",
            g[j],
            bound[j]
        );
        // The samples' own rounding (half of 1/255 a light) moves the fit little.
        assert!(
            (got - c[j]).abs() < 0.02 + bound[j],
            "{j}: {got} vs {}",
            c[j]
        );
    }
}

/// The fit of a woven cloth: each texel's RMS error over its lights is below that of the
/// best constant (its own mean occlusion), which a PTM holds as A6 alone.
#[test]
fn the_fit_beats_a_constant_occlusion() {
    let side = 16;
    let sw = Swatch::new(side, golden::ptm::woven(side, 2.5), dome(4, 12));
    let (q, fmt) = fit_swatch(&sw, 16).unwrap();
    let qual = quality(&sw, &q, &fmt);
    let mut constant = 0.0;
    for t in 0..side * side {
        let k: Vec<f64> = sw
            .texel_samples(t)
            .iter()
            .map(|&x| 1.0 - f64::from(x) / 255.0)
            .collect();
        let m = k.iter().sum::<f64>() / k.len() as f64;
        constant += (k.iter().map(|x| (x - m).powi(2)).sum::<f64>() / k.len() as f64).sqrt();
    }
    constant /= (side * side) as f64;
    eprintln!("{qual:?}, constant {constant:.3}");
    assert!(
        qual.rmse_mean < constant,
        "{} vs {constant}",
        qual.rmse_mean
    );
    assert_eq!(qual.ptm_bytes, 6 * 2 * 256);
    assert!(qual.ptm_bytes < qual.shadow_map_bytes);
}
