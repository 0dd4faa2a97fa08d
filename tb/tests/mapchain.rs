//! Map linking (section 14) with detail, reflectance and environment maps: the regress
//! testbench, the document's timings, and the detail path's properties.

use tb::mapchain::{expectations, pixels, scene, Maps, Scene, Shape, WalkerTb};
use tb::runs::mapchain::timings;
use units::mapchain::drf_812::{DetailMode, DrfFile, Kind};
use units::mapchain::program::{ChainRequest, Fetch, Program, State};
use units::mapchain::walker_812::walk_pixel;
use units::texram::output_820::mul255;
use units::texram::{Border, TexramAccess};
use verif::{Seed, Stimulus};

fn maps() -> Maps {
    Maps::new(&mut Stimulus::new(Seed(0x15)))
}

/// The colours (and accesses) of `px` through `sc`, access by access on a fresh stub.
fn colours(sc: &Scene, px: &[ChainRequest]) -> Vec<(u8, u32, bool)> {
    colours_of(sc, &sc.file, px)
}

/// The same through DRFs `file` (which may be broken) over `sc`'s maps.
fn colours_of(sc: &Scene, file: &DrfFile, px: &[ChainRequest]) -> Vec<(u8, u32, bool)> {
    let mut stub = sc.stub().unwrap();
    px.iter()
        .map(|q| {
            let r = walk_pixel(file, &mut stub, q).unwrap();
            (r.colour, r.accesses, r.error)
        })
        .collect()
}

/// Every shape, the longest on the chip too, with the schedule check: the walker equal to
/// its micro-program bit for bit (colour, accesses, slots, faults), out at the cycle its
/// slots say, within the golden model's derived bound; every coverage bin hit.
#[test]
fn the_testbench_passes_with_full_coverage() {
    let opts = verif::RunOptions {
        count: Some(160),
        check_schedule: true,
        ..Default::default()
    };
    let r = verif::run_testbench(&WalkerTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?} {:?}", r.failures, r.mismatch_log);
    assert_eq!(r.mismatches, 0);
    assert!(
        r.coverage_percent > 99.0,
        "{} {:?}",
        r.coverage_percent,
        r.unhit
    );
}

/// Section 14: texture + detail about 240 ns a pixel (4 accesses, each faulting), the longest
/// chain about 540 ns (9 accesses): both within 10 %, the faults from the page registers.
#[test]
fn the_documents_timings_from_the_page_registers() {
    let t = timings().unwrap();
    for row in &t {
        eprintln!("{row:?}");
    }
    let [plain, env, detail, longest] = [&t[0], &t[1], &t[2], &t[3]];
    assert_eq!((detail.accesses, detail.faults), (4.0, 4.0));
    assert_eq!((longest.accesses, longest.faults), (9.0, 9.0));
    for row in [detail, longest] {
        let d = row.document_ns.unwrap();
        assert!((row.ns / d - 1.0).abs() <= 0.10, "{row:?}");
    }
    // One access a slot back to back when the texture's rows stay open; a texture and an
    // environment in different rows fault on every access.
    assert!(
        plain.faults < 0.01 && (plain.ns - 30.0).abs() < 0.5,
        "{plain:?}"
    );
    assert_eq!(env.faults, 2.0);
}

/// lambda >= 0 leaves the detail path unused: the detail chains give the texture chain's
/// colour bit for bit, in one access, which is eq. 5 on the plain access.
#[test]
fn above_level_zero_the_detail_path_is_unused() {
    let m = maps();
    let mut stim = Stimulus::new(Seed(1));
    let px: Vec<ChainRequest> = pixels(600, &mut stim)
        .into_iter()
        .map(|mut q| {
            q.lambda = q.lambda.rem_euclid(10 << 8);
            q
        })
        .collect();
    let plain = colours(&scene(Shape::Texture, &m).unwrap(), &px);
    for shape in [Shape::Detail, Shape::DetailMap] {
        assert_eq!(colours(&scene(shape, &m).unwrap(), &px), plain, "{shape:?}");
    }
    let sc = scene(Shape::Texture, &m).unwrap();
    let mut stub = sc.stub().unwrap();
    let tex = sc.file.drfs[0].unwrap();
    for (q, (c, n, _)) in px.iter().zip(&plain) {
        let t = stub
            .access_with(&tex.access(0), q.u, q.v, q.lambda)
            .unwrap();
        assert_eq!((*c, *n), (mul255(q.i_d, t.value), 1));
    }
}

/// The detail map's bilinear at level 0 (lambda -4), from its texels with the tile fold,
/// in plain integers: `round(sum t (256 - a or a)(256 - b or b) / 2^16)`, half up.
fn detail_bilinear(detail: &[u8], side: i64, u: i64, v: i64) -> u8 {
    let axis = |c: i64| {
        let x = c - 128;
        (x.div_euclid(256), (x.rem_euclid(256)) as u64)
    };
    let ((i, a), (j, b)) = (axis(u), axis(v));
    // The tile of the sample point (16 texels), the pair folded into it.
    let tile = |c: i64| c.div_euclid(256).div_euclid(16) * 16;
    let fold = |x: i64, t: i64| (t + (x - t).rem_euclid(16)).rem_euclid(side);
    let (tu, tv) = (tile(u), tile(v));
    let mut sum = 0u64;
    for (dj, wb) in [(0, 256 - b), (1, b)] {
        for (di, wa) in [(0, 256 - a), (1, a)] {
            let t = detail[(fold(j + dj, tv) * side + fold(i + di, tu)) as usize];
            sum += u64::from(t) * wa * wb;
        }
    }
    ((sum + (1 << 15)) >> 16) as u8
}

/// lambda = -4 is the bilinear of level -4 (the detail map's level 0) in the tile the offsets
/// give, the texel's own 16 x 16, exactly; with replace and I_d = 255 that is the colour.
#[test]
fn at_level_minus_four_the_colour_is_the_detail_bilinear() {
    let m = maps();
    let mut sc = scene(Shape::Detail, &m).unwrap();
    sc.file.drfs[2].as_mut().unwrap().detail = DetailMode::Replace;
    let mut stim = Stimulus::new(Seed(2));
    let px: Vec<ChainRequest> = pixels(800, &mut stim)
        .into_iter()
        .map(|mut q| {
            (q.lambda, q.i_d) = (-4 << 8, 255);
            q
        })
        .collect();
    let got = colours(&sc, &px);
    let side = 1i64 << tb::mapchain::DETAIL_LOG2;
    let tex = 1i64 << tb::mapchain::TEX_LOG2;
    for (q, (c, n, err)) in px.iter().zip(got) {
        let (i, j) = (
            (i64::from(q.u) >> 8).rem_euclid(tex),
            (i64::from(q.v) >> 8).rem_euclid(tex),
        );
        let o = |p: usize| i64::from(m.offsets[p][(j * tex + i) as usize]);
        let du = o(0) * 256 + (i64::from(q.u) & 255) * 16;
        let dv = o(1) * 256 + (i64::from(q.v) & 255) * 16;
        assert!(!err);
        assert_eq!(n, 3, "offsets, detail, no texel with replace below -1");
        assert_eq!(c, detail_bilinear(&m.detail, side, du, dv), "{q:?}");
    }
}

/// Continuous in lambda at -1: one step of lambda (1/256) on either side changes the colour
/// by at most 2 LSBs (below: the detail's weight toward level -1 moves by 1/256 of a
/// texel difference, plus roundings; above: the fade's first step).
#[test]
fn the_colour_is_continuous_in_lambda_at_minus_one() {
    let m = maps();
    let mut stim = Stimulus::new(Seed(3));
    let px = pixels(400, &mut stim);
    for shape in [Shape::Detail, Shape::DetailMap, Shape::Longest] {
        let sc = scene(shape, &m).unwrap();
        let at = |l: i32| {
            let p: Vec<ChainRequest> = px
                .iter()
                .map(|q| ChainRequest { lambda: l, ..*q })
                .collect();
            colours(&sc, &p)
        };
        let (below, mid, above) = (at(-257), at(-256), at(-255));
        for k in 0..px.len() {
            for side in [below[k].0, above[k].0] {
                assert!(side.abs_diff(mid[k].0) <= 2, "{shape:?} {:?}", px[k]);
            }
        }
    }
}

/// Eq. 7 with a constant reflectance map k lit by the environment is eq. 6 with k_s = k,
/// bit for bit.
#[test]
fn a_constant_reflectance_is_eq6() {
    let m = maps();
    let mut stim = Stimulus::new(Seed(4));
    let px = pixels(300, &mut stim);
    for k in [0u8, 77, 255] {
        let t = (tb::mapchain::TEX_LOG2, tb::mapchain::TEX_LOG2);
        let mut refl = scene(Shape::Environment, &m).unwrap();
        let r = refl
            .add(
                3,
                Kind::Reflectance,
                t,
                Border::Wrap,
                vec![vec![k; 64 * 64]],
            )
            .unwrap();
        r.link = Some(6);
        refl.file.drfs[0].as_mut().unwrap().link = Some(3);
        let mut env = scene(Shape::Environment, &m).unwrap();
        env.file.drfs[6].as_mut().unwrap().k_s = k;
        let (a, b) = (colours(&refl, &px), colours(&env, &px));
        assert!(a.iter().zip(&b).all(|(x, y)| x.0 == y.0), "k {k}");
        assert!(a.iter().all(|x| x.1 == 3) && b.iter().all(|x| x.1 == 2));
    }
}

/// A link cycle stops after seven DRFs with the error flag (seven accesses made); a detail
/// map reached without offsets and an unset DRF are flagged too.
#[test]
fn chains_that_cannot_end_are_flagged() {
    let m = maps();
    let px = pixels(50, &mut Stimulus::new(Seed(5)));
    for (c, n, err) in colours(&scene(Shape::Cycle, &m).unwrap(), &px) {
        assert_eq!((c, n, err), (0, 7, true));
    }
    let mut sc = scene(Shape::Detail, &m).unwrap();
    sc.file.drfs[0].as_mut().unwrap().link = Some(2);
    for (q, (_, _, err)) in px.iter().zip(colours(&sc, &px)) {
        assert_eq!(err, q.lambda < 0, "{q:?}");
    }
    let q = ChainRequest { drf: 5, ..px[0] };
    assert!(colours(&sc, &[q])[0].2);
    // Offsets that lead nowhere leave the texture's read waiting for a detail (below level
    // 0): flagged, and at level 0 or above (the offsets unused) not.
    let sc = scene(Shape::Detail, &m).unwrap();
    let mut file = sc.file.clone();
    file.drfs[1].as_mut().unwrap().link = None;
    for (q, (_, _, err)) in px.iter().zip(colours_of(&sc, &file, &px)) {
        assert_eq!(err, q.lambda < 0, "{q:?}");
    }
    // A reflectance map lit by the environment with no environment map in the chain.
    let sc = scene(Shape::Reflectance, &m).unwrap();
    assert!(colours(&sc, &px).iter().all(|c| !c.2));
    let mut file = sc.file.clone();
    file.drfs[3].as_mut().unwrap().light_env = true;
    assert!(colours_of(&sc, &file, &px).iter().all(|c| c.2));
}

/// The walker's slot length is 1 to 15 cycles (its 5-bit busy counter spans a faulting
/// access's two slots), both ends taken.
#[test]
fn the_slot_length_is_checked_at_both_ends() {
    use units::mapchain::walker_812::MapChain812;
    let sc = scene(Shape::Texture, &maps()).unwrap();
    for (cycles, ok) in [(0, false), (1, true), (15, true), (16, false)] {
        let r = MapChain812::new(sc.file.clone(), sc.stub().unwrap(), cycles);
        match r {
            Ok(_) => assert!(ok, "{cycles}"),
            Err(e) => assert!(!ok && e == format!("slot_cycles {cycles}: 1..=15"), "{e}"),
        }
    }
}

/// An environment DRF without `new_coords` reads the face the rasterizer gives, at the
/// pixel's own (u, v) and lambda held at 0 or above; a face beyond 5 (the 3-bit field's 6 and
/// 7) ends the walk flagged, with no access.
#[test]
fn a_given_face_is_read_where_the_rasterizer_says() {
    let m = maps();
    let mut sc = scene(Shape::Environment, &m).unwrap();
    sc.file.drfs[6].as_mut().unwrap().new_coords = false;
    let tab = *units::envmap::cube_face::CubeFace::new().table();
    let px = pixels(240, &mut Stimulus::new(Seed(7)));
    for (i, q) in px.iter().enumerate() {
        let q = ChainRequest {
            face: (i % 8) as u8,
            ..*q
        };
        let prog = Program {
            file: &sc.file,
            px: &q,
            tab: &tab,
        };
        let (w, first) = prog.begin();
        assert_eq!((w.state, first.map(|f| f.drf)), (State::Texture, Some(0)));
        let (w, f) = prog.advance(w, 0);
        if q.face > 5 {
            assert_eq!((w.state, f), (State::Error, None), "{q:?}");
        } else {
            let at = Fetch {
                drf: 6,
                plane: q.face,
                u: q.u,
                v: q.v,
                lambda: q.lambda.max(0),
            };
            assert_eq!((w.state, f), (State::Environment, Some(at)), "{q:?}");
        }
        let (_, n, err) = colours(&sc, &[q])[0];
        assert_eq!((n, err), if q.face > 5 { (1, true) } else { (2, false) });
    }
}

/// Eq. 6 with the environment map's `base_texture` off takes I_d for C_d, not the texture's
/// colour: the walk within the golden model's bound of that reading (the texture modulates
/// I_d, so the two readings differ by far more than the bound on most pixels).
#[test]
fn without_base_texture_eq6_takes_the_illumination() {
    let m = maps();
    let mut sc = scene(Shape::Environment, &m).unwrap();
    sc.file.drfs[6].as_mut().unwrap().base_texture = false;
    let px = pixels(300, &mut Stimulus::new(Seed(8)));
    let (mut checked, mut apart) = (0, 0);
    for e in expectations(&sc, &px).unwrap() {
        let g = e.golden.expect("the chain ends");
        if e.ambiguous {
            continue;
        }
        let got = f64::from(e.reference.colour);
        assert!((got - g.x).abs() <= g.e, "{} vs {} +- {}", got, g.x, g.e);
        checked += 1;
        let with_texture = colours(&scene(Shape::Environment, &m).unwrap(), &[e.px])[0].0;
        apart += usize::from((f64::from(with_texture) - g.x).abs() > g.e);
    }
    assert!(checked > 250 && apart > checked / 2, "{checked} {apart}");
}

/// The walker's face is the f64 face unless the two largest components of eq. 4's vector are
/// within 2^-12 of each other.
#[test]
fn the_walker_picks_the_f64_face() {
    let m = maps();
    let sc = scene(Shape::Environment, &m).unwrap();
    let tab = *units::envmap::cube_face::CubeFace::new().table();
    let mut stim = Stimulus::new(Seed(6));
    let mut faces = [0usize; 6];
    for q in pixels(3000, &mut stim) {
        let prog = Program {
            file: &sc.file,
            px: &q,
            tab: &tab,
        };
        let (w, _) = prog.begin();
        let (w, _) = prog.advance(w, 0);
        assert_eq!(w.state, State::EnvCoords);
        let p = tb::mapchain::gpixel(&q);
        let r = golden::envmap::reflect(p.n, p.eye);
        let mut a = r.map(f64::abs);
        a.sort_by(|x, y| y.total_cmp(x));
        if a[0] - a[1] > a[0] * 2f64.powi(-12) {
            assert_eq!(w.face, golden::envmap::face_st(r).0, "{q:?}");
        }
        faces[usize::from(w.face)] += 1;
    }
    assert!(faces.iter().all(|&n| n > 0), "{faces:?}");
}

/// The traced testbench: the walker's scope with its state named by a translate filter
/// (OFFSET_U, DETAIL, ENV_COORDS ...), read back, the view opening it.
#[test]
fn the_waveform_names_the_walkers_state() {
    let dir = std::env::temp_dir().join(format!("texrtl-walker-{}", std::process::id()));
    let opts = verif::RunOptions {
        count: Some(20),
        ..verif::RunOptions::with_waves(&dir)
    };
    let r = verif::run_testbench(&WalkerTb, &opts, &mut |_| {}).unwrap();
    assert!(r.passed, "{:?}", r.failures);
    let vcd = dir.join("walker_812.vcd");
    let rb = waves::check::read_vcd(&vcd).unwrap();
    for v in [
        "state",
        "banks.acc_drf",
        "banks.acc_u",
        "out_colour",
        "banks.rd_slots",
    ] {
        let name = format!("tb.walker_812.{v}");
        assert!(rb.vars.contains_key(&name), "no {name}");
    }
    let filter = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| p.to_string_lossy().contains("walker_812.state"))
        .expect("a translate filter for the state");
    let names = std::fs::read_to_string(filter).unwrap();
    for s in [
        "IDLE",
        "TEXTURE",
        "OFFSET_U",
        "DETAIL_BASE",
        "ENV_COORDS",
        "ERROR",
    ] {
        assert!(names.contains(s), "{s} not in {names}");
    }
    waves::check::check_gtkw(&vcd, &rb).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}
