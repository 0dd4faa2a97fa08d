//! Traces a real module, reads the VCD back with wellen and checks hierarchy, widths, values,
//! companions, probes, filters, windows and the save file.

use hdl::kernel::Sim;
use std::path::{Path, PathBuf};
use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use waves::check::{check_gtkw, read_vcd, Value};
use waves::{TraceConfig, VcdTracer};

/// A scratch folder, removed when the test ends.
fn tmpdir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("texrtl-waves-{name}-"))
        .tempdir()
        .unwrap()
}

/// A file's path in a scratch folder of its own, removed with the folder when the test ends.
struct Scratch {
    _dir: tempfile::TempDir,
    path: PathBuf,
}

impl Scratch {
    fn new(name: &str, file: &str) -> Scratch {
        let dir = tmpdir(name);
        let path = dir.path().join(file);
        Scratch { _dir: dir, path }
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// Two cycles of reset, then 20 with u = 10 * cycle; `settled` sees each cycle before its edge.
fn drive<T: hdl::kernel::Trace>(
    sim: &mut Sim<BlendAdjust, T>,
    mut settled: impl FnMut(&mut Sim<BlendAdjust, T>),
) {
    sim.reset(2);
    for c in 0..20u64 {
        sim.dut.i.valid_in.set_bool(true);
        sim.dut.i.u_in.set_bits(10 * c);
        sim.eval();
        settled(sim);
        sim.tick();
    }
}

/// Runs the blend adjust unit for 20 cycles with u = 10 * cycle, traced by `cfg`.
fn run(name: &str, cfg: TraceConfig, finish: bool) -> Scratch {
    let path = Scratch::new(name, "ba.vcd");
    let mut t = VcdTracer::create(&path, "blend adjust", cfg).unwrap();
    assert_eq!(t.gtkw_path(), path.with_extension("gtkw"));
    let gold = t.probe_real("u0", Some("tb.blend_adjust_153.u0"));
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    let mut sim = Sim::traced(dut, t).unwrap();
    drive(&mut sim, |sim| {
        let u = sim.dut.o.u0.fx().to_f64();
        sim.trace_mut().unwrap().set_real(gold, u);
    });
    if finish {
        sim.finish().unwrap();
    }
    path
}

#[test]
fn full_trace_reads_back() {
    let path = run("full", TraceConfig::default(), true);
    let rb = read_vcd(&path).unwrap();
    assert_eq!(rb.timescale_exp, Some(-12));
    // The design's variables, as the header scan counts them: all but clk, rst and probes.
    let design = rb
        .vars
        .keys()
        .filter(|k| k.starts_with("tb.blend_adjust_153."));
    assert_eq!(waves::design_variables(&path).unwrap(), design.count());
    assert!(
        rb.scopes.contains(&"tb.blend_adjust_153".to_string()),
        "{:?}",
        rb.scopes
    );
    let w = |n: &str| rb.vars[n].width;
    assert_eq!(w("tb.clk"), Some(1));
    assert_eq!(w("tb.blend_adjust_153.u_in"), Some(8));
    assert_eq!(w("tb.blend_adjust_153.u0"), Some(9));
    assert_eq!(w("tb.blend_adjust_153.u0_r"), Some(9));
    assert_eq!(w("tb.blend_adjust_153.u0_real"), None, "companion is real");
    assert_eq!(w("tb.golden.u0"), None);
    // Cycle 2 + c is sampled at (2 + c) * 10 ns; the registered output shows input c - 1.
    let t = |c: u64| (2 + c) * 10_000;
    assert_eq!(
        rb.value_at("tb.blend_adjust_153.u_in", t(5))
            .unwrap()
            .as_u64(),
        Some(50)
    );
    assert_eq!(
        rb.value_at("tb.blend_adjust_153.u0", t(5))
            .unwrap()
            .as_u64(),
        Some(0x100 + 40)
    );
    let r = rb
        .value_at("tb.blend_adjust_153.u0_real", t(5))
        .unwrap()
        .as_f64()
        .unwrap();
    assert_eq!(r, (256.0 + 40.0) / 512.0);
    let g = rb.value_at("tb.golden.u0", t(5)).unwrap().as_f64().unwrap();
    assert_eq!(g, r, "golden probe beside the DUT value");
    assert_eq!(rb.value_at("tb.rst", 0), Some(&Value::Bits("1".into())));
    assert_eq!(rb.value_at("tb.rst", t(0)), Some(&Value::Bits("0".into())));
    // The clock toggles every half period; the trace ends at the last cycle's end.
    assert_eq!(rb.vars["tb.clk"].changes.len(), 44);
    assert_eq!(*rb.times.last().unwrap(), 22 * 10_000);
    // Only changes are written: u_in changes once per cycle after reset, never more.
    assert_eq!(rb.vars["tb.blend_adjust_153.u_in"].changes.len(), 20);
    let n = check_gtkw(&path, &rb).unwrap();
    assert!(n >= 20, "{n} traces");
    let g = std::fs::read_to_string(path.with_extension("gtkw")).unwrap();
    let i_u0 = g.find("tb.blend_adjust_153.u0[8:0]").unwrap();
    let i_gold = g.find("tb.golden.u0").unwrap();
    assert!(
        i_gold > i_u0 && !g[i_u0..i_gold].contains("tb.blend_adjust_153.u1"),
        "golden beside u0"
    );
    assert!(
        g.contains("-blend_adjust_153\n"),
        "the group is named after the unit: {g}"
    );
}

#[test]
fn depth_filter_window() {
    let d0 = run(
        "depth0",
        TraceConfig {
            max_depth: Some(0),
            ..Default::default()
        },
        true,
    );
    let rb = read_vcd(&d0).unwrap();
    assert!(
        rb.vars
            .keys()
            .all(|k| !k.starts_with("tb.blend_adjust_153.")),
        "{:?}",
        rb.vars.keys()
    );
    assert!(rb.vars.contains_key("tb.clk"));
    check_gtkw(&d0, &rb).unwrap();
    assert_eq!(waves::design_variables(&d0).unwrap(), 0);
    // A filter without the `tb.` its names start with matches nothing of the design.
    let none = TraceConfig {
        filters: vec!["blend_adjust_153.*".into()],
        ..Default::default()
    };
    assert_eq!(
        waves::design_variables(&run("none", none, true)).unwrap(),
        0
    );

    let f = run(
        "filter",
        TraceConfig {
            filters: vec!["tb.blend_adjust_153.u0*".into()],
            companions: false,
            ..Default::default()
        },
        true,
    );
    let rb = read_vcd(&f).unwrap();
    let dut: Vec<_> = rb
        .vars
        .keys()
        .filter(|k| k.starts_with("tb.blend_adjust_153."))
        .cloned()
        .collect();
    assert_eq!(dut, ["tb.blend_adjust_153.u0", "tb.blend_adjust_153.u0_r"]);
    assert_eq!(waves::design_variables(&f).unwrap(), 2);
    check_gtkw(&f, &rb).unwrap();

    let w = run(
        "window",
        TraceConfig {
            window: Some((5, 9)),
            ..Default::default()
        },
        true,
    );
    let rb = read_vcd(&w).unwrap();
    assert_eq!(rb.times.first(), Some(&50_000));
    assert_eq!(rb.times.last(), Some(&90_000));
    // Initial values at the window's start: cycle 5 is input c = 3.
    assert_eq!(
        rb.value_at("tb.blend_adjust_153.u_in", 50_000)
            .unwrap()
            .as_u64(),
        Some(30)
    );
}

#[test]
fn abandoned_trace_leaves_no_file() {
    let p = run("abandon", TraceConfig::default(), false);
    assert!(!p.exists());
    let mut partial = p.to_path_buf().into_os_string();
    partial.push(".partial");
    assert!(!PathBuf::from(partial).exists());
    assert!(!p.with_extension("gtkw").exists());
}

/// A cycle sampled before `start` (the tracer has not seen the design) is an error naming the
/// file, not a panic.
#[test]
fn a_cycle_before_the_start_is_refused() {
    use hdl::kernel::Trace;
    let path = Scratch::new("early", "e.vcd");
    let mut t = VcdTracer::create(&path, "early", TraceConfig::default()).unwrap();
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    let e = t.sample(0, true, &dut).unwrap_err().to_string();
    assert!(
        e.contains("e.vcd") && e.contains("before the trace started"),
        "{e}"
    );
}

#[test]
fn bad_configs_are_refused() {
    let dir = tmpdir("bad");
    let e = VcdTracer::create(
        dir.path().join("x.vcd"),
        "x",
        TraceConfig {
            window: Some((4, 4)),
            ..Default::default()
        },
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("x.vcd"), "{e}");
    assert!(VcdTracer::create(
        dir.path().join("no/such/dir/x.vcd"),
        "x",
        TraceConfig::default()
    )
    .is_err());
}

#[test]
fn fst_holds_what_the_vcd_holds() {
    let path = run("fst", TraceConfig::default(), true);
    let fst = path.with_extension("fst");
    waves::fst::vcd_to_fst(&path, &fst).unwrap();
    let a = read_vcd(&path).unwrap();
    let b = waves::check::read_fst(&fst).unwrap();
    assert_eq!(
        a.vars.keys().collect::<Vec<_>>(),
        b.vars.keys().collect::<Vec<_>>()
    );
    for (name, va) in &a.vars {
        let vb = &b.vars[name];
        assert_eq!(va.width, vb.width, "{name}");
        assert_eq!(va.changes, vb.changes, "{name}");
    }
    assert_eq!(a.times, b.times);
}

#[test]
fn fst_of_a_windowed_trace() {
    let path = run(
        "fstw",
        TraceConfig {
            window: Some((5, 9)),
            ..Default::default()
        },
        true,
    );
    let fst = path.with_extension("fst");
    waves::fst::vcd_to_fst(&path, &fst).unwrap();
    let a = read_vcd(&path).unwrap();
    let b = waves::check::read_fst(&fst).unwrap();
    assert_eq!(fst_header(&fst).2, 0, "no time offset");
    // fst-writer always starts its time table at 0: the FST has one extra leading timestamp
    // before the window, and from the window on every value is the VCD's.
    assert!(
        waves::fst::same_values(&a, &b).is_ok(),
        "{:?}",
        waves::fst::same_values(&a, &b)
    );
}

/// The blend adjust unit's run of [`run`] traced directly to FST (no companions, no probes),
/// with the writer's section and batch sizes `limits` when given.
fn run_fst(name: &str, cfg: TraceConfig, limits: Option<(usize, usize)>) -> Scratch {
    let path = Scratch::new(name, "ba.fst");
    let mut t = waves::FstTracer::create(&path, cfg).unwrap();
    if let Some((flush, batch)) = limits {
        t = t.with_limits(flush, batch);
    }
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    let mut sim = Sim::traced(dut, t).unwrap();
    drive(&mut sim, |_| {});
    sim.finish().unwrap();
    path
}

/// The FST written while simulating holds what the VCD of the same run holds (without the
/// VCD's `real` companions and probes): every variable, width and value at every VCD time,
/// whole and windowed, in one section and batch or across many (tiny limits: a section every
/// few hundred bytes, a batch every 7 records, so every boundary falls somewhere new).
#[test]
fn direct_fst_holds_the_vcds_values() {
    for (name, window, limits) in [
        ("direct", None, None),
        ("directw", Some((5, 9)), None),
        ("directs", None, Some((300, 7))),
        ("directsw", Some((5, 9)), Some((1, 1))),
    ] {
        let cfg = TraceConfig {
            companions: false,
            window,
            ..Default::default()
        };
        let vcd = run(&format!("{name}-vcd"), cfg.clone(), true);
        let fst = run_fst(name, cfg, limits);
        let mut a = read_vcd(&vcd).unwrap();
        a.vars.retain(|n, _| !n.starts_with("tb.golden"));
        let b = waves::check::read_fst(&fst).unwrap();
        let r = waves::fst::same_values(&a, &b);
        assert!(r.is_ok(), "{name}: {r:?}");
        assert!(!b.vars.is_empty());
        let end = window.map_or(22, |(_, b)| b) * 10_000;
        assert_eq!(
            fst_header(&fst),
            (0, end, 0),
            "{name}: from 0, no time offset"
        );
    }
}

/// The FST header's start and end times (fst-reader, wellen's reader) and its time zero, an
/// offset GTKWave adds to every time it shows (read from the header block's last eight bytes:
/// one byte of block type, then 321 bytes of fields before it, big-endian).
fn fst_header(fst: &std::path::Path) -> (u64, u64, u64) {
    let file = std::io::BufReader::new(std::fs::File::open(fst).unwrap());
    let h = fst_reader::FstReader::open(file).unwrap().get_header();
    let bytes = std::fs::read(fst).unwrap();
    let zero = u64::from_be_bytes(bytes[322..330].try_into().unwrap());
    (h.start_time, h.end_time, zero)
}

/// A long run through both writer threads: many VCD batches and 256 KB chunks, many FST
/// batches and sections (tiny limits). The two files, written by independent paths, hold the
/// same values at every time, and the VCD's values are the model's (checked at sampled
/// cycles against what the design held).
#[test]
fn long_runs_cross_every_batch_and_chunk_boundary() {
    // 8-bit texels, and 62-bit ones (64-bit windows: the longest change lines) across the
    // chunk boundaries.
    for (bits, cycles) in [(8, 6000), (62, 4000)] {
        long_run(bits, cycles);
    }
}

fn long_run(bits: u32, cycles: u64) {
    use hdl::fx::Format;
    use units::bump::replicate_152::Replicate;
    let cfg = TraceConfig {
        companions: false,
        ..Default::default()
    };
    let dir = tmpdir(&format!("long{bits}"));
    let (vcd, fst) = (dir.path().join("r.vcd"), dir.path().join("r.fst"));
    let unit = || Replicate::new("replicate_152", Format::unsigned(bits, 2), false);
    let mut a = Sim::traced(
        unit(),
        VcdTracer::create(&vcd, "long", cfg.clone()).unwrap(),
    )
    .unwrap();
    let fst_tracer = waves::FstTracer::create(&fst, cfg)
        .unwrap()
        .with_limits(4096, 1000);
    let mut b = Sim::traced(unit(), fst_tracer).unwrap();
    let mut seen = Vec::new();
    let mut most = 0;
    let mut x: u64 = 7;
    for c in 0..cycles {
        for k in 0..9 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            a.dut.h[k].set_bits(x >> (64 - bits));
            b.dut.h[k].set_bits(x >> (64 - bits));
        }
        a.eval();
        b.eval();
        if c % 997 == 0 {
            seen.push((c, a.dut.w[3][2].bits()));
        }
        a.tick();
        b.tick();
        let pending = b.trace_mut().unwrap().pending();
        assert!(pending < 1000, "cycle {c}: {pending} records held back");
        most = most.max(pending);
    }
    assert!(
        most > 900,
        "records are held until a batch is full: at most {most}"
    );
    assert!(
        a.trace_mut().unwrap().changes() > 100_000,
        "several VCD batches"
    );
    let a_name = a.dut.w[3][2].name();
    let (na, nb) = (
        a.trace_mut().unwrap().changes(),
        b.trace_mut().unwrap().changes(),
    );
    a.finish().unwrap();
    b.finish().unwrap();
    let rv = read_vcd(&vcd).unwrap();
    // Both writers count the same changes; the file holds them and the clock's falls.
    assert_eq!(na, nb);
    assert_eq!(rv.total_changes() as u64, na + cycles);
    let rf = waves::check::read_fst(&fst).unwrap();
    waves::fst::same_values(&rv, &rf).unwrap();
    let var = format!("tb.replicate_152.{}", a_name);
    for (c, bits) in seen {
        assert_eq!(
            rv.value_at(&var, c * 10_000).and_then(Value::as_u64),
            Some(bits),
            "{var} at cycle {c}"
        );
    }
}

/// A trace to a full device: the writer's error comes back from `finish` naming the file,
/// with no panic, and the device is not replaced (it is written through).
#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_an_error_naming_it() {
    use hdl::fx::Format;
    use units::bump::replicate_152::Replicate;
    let cfg = TraceConfig {
        companions: false,
        ..Default::default()
    };
    let unit = || Replicate::new("replicate_152", Format::unsigned(8, 2), false);
    let full = std::path::Path::new("/dev/full");
    let vcd = VcdTracer::create(full, "full", cfg.clone()).unwrap();
    let fst = waves::FstTracer::create(full, cfg)
        .unwrap()
        .with_limits(4096, 1000);
    let mut a = Sim::traced(unit(), vcd).unwrap();
    let mut x: u64 = 3;
    for _ in 0..6000u64 {
        for k in 0..9 {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            a.dut.h[k].set_bits(x >> 56);
        }
        a.eval();
        a.tick();
    }
    // The FST tracer writes its header out when the hierarchy is declared: the error comes
    // there.
    let e = Sim::traced(unit(), fst)
        .err()
        .expect("the FST header cannot be written");
    for e in [a.finish().unwrap_err(), e] {
        assert!(e.to_string().starts_with("/dev/full: No space left"), "{e}");
    }
    assert!(!std::path::Path::new("/dev/full.gtkw").exists());
    assert!(!std::path::Path::new("/dev/full.partial").exists());
}

/// The flags line (`@...`) in effect for trace line `name` of a save file.
fn flags_of<'a>(gtkw: &'a str, name: &str) -> Option<&'a str> {
    let mut flags = None;
    for l in gtkw.lines() {
        if let Some(f) = l.strip_prefix('@') {
            flags = Some(f);
        } else if l == name {
            return flags;
        }
    }
    None
}

/// Bit probes of one and eight bits: declared with their widths and listed in the save file
/// as GTKWave names them (a vector with its range, a bit without), as are the design's.
#[test]
fn probes_and_single_bits_are_named_as_gtkwave_names_them() {
    let path = Scratch::new("probes", "p.vcd");
    let mut t = VcdTracer::create(&path, "probes", TraceConfig::default()).unwrap();
    let f = t.probe_bits("f", 1, None);
    let b = t.probe_bits("b", 8, None);
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    let mut sim = Sim::traced(dut, t).unwrap();
    drive(&mut sim, |sim| {
        let t = sim.trace_mut().unwrap();
        t.set_bits(f, 1);
        t.set_bits(b, 200);
    });
    sim.finish().unwrap();
    let rb = read_vcd(&path).unwrap();
    assert_eq!(rb.vars["tb.golden.f"].width, Some(1));
    assert_eq!(rb.vars["tb.golden.b"].width, Some(8));
    assert_eq!(
        rb.value_at("tb.golden.b", 50_000).unwrap().as_u64(),
        Some(200)
    );
    check_gtkw(&path, &rb).unwrap();
    // Declared as GTKWave then names them: a range only on a vector.
    let vcd = std::fs::read_to_string(&path).unwrap();
    let declared = |name: &str| {
        vcd.lines()
            .find(|l| l.starts_with("$var") && l.split(' ').nth(4) == Some(name))
            .map(|l| l.split(' ').skip(5).collect::<Vec<_>>().join(" "))
    };
    assert_eq!(declared("f").as_deref(), Some("$end"));
    assert_eq!(declared("b").as_deref(), Some("[7:0] $end"));
    assert_eq!(declared("valid_in").as_deref(), Some("$end"));
    assert_eq!(declared("u_in").as_deref(), Some("[7:0] $end"));
    let g = std::fs::read_to_string(path.with_extension("gtkw")).unwrap();
    for (name, flags) in [
        ("tb.golden.f", "28"),
        ("tb.golden.b[7:0]", "24"),
        ("tb.blend_adjust_153.valid_in", "28"),
        ("tb.blend_adjust_153.u_in[7:0]", "24"),
    ] {
        assert_eq!(flags_of(&g, name), Some(flags), "{name} in\n{g}");
    }
}

/// A window no cycle of the run reaches: a valid dump of unknowns at the window's start.
#[test]
fn a_window_past_the_run_dumps_unknowns_at_its_start() {
    let path = run(
        "late",
        TraceConfig {
            window: Some((100, 110)),
            ..Default::default()
        },
        true,
    );
    let rb = read_vcd(&path).unwrap();
    assert_eq!(rb.times, [1_000_000]);
    let at = |v: &str| rb.value_at(v, 1_000_000).cloned();
    assert_eq!(at("tb.clk"), Some(Value::Bits("x".into())));
    assert_eq!(
        at("tb.blend_adjust_153.u_in"),
        Some(Value::Bits("x".repeat(8)))
    );
    assert_eq!(at("tb.blend_adjust_153.u0_real"), Some(Value::Real(0.0)));
    assert_eq!(at("tb.golden.u0"), Some(Value::Real(0.0)));
    check_gtkw(&path, &rb).unwrap();
}

/// The FST written beside the VCD (`fst` on) holds the VCD's values.
#[test]
fn an_fst_beside_the_vcd_holds_its_values() {
    let cfg = TraceConfig {
        fst: true,
        companions: false,
        ..Default::default()
    };
    let vcd = run("beside", cfg, true);
    let mut a = read_vcd(&vcd).unwrap();
    a.vars.retain(|n, _| !n.starts_with("tb.golden"));
    let b = waves::check::read_fst(&vcd.with_extension("fst")).unwrap();
    waves::fst::same_values(&a, &b).unwrap();
}

/// A tracer driven out of order (a cycle again, or an earlier one) is an error naming the
/// file, not a dump whose time goes backwards.
#[test]
fn time_never_goes_backwards() {
    use hdl::kernel::Trace;
    let path = Scratch::new("order", "o.vcd");
    let mut t = VcdTracer::create(&path, "order", TraceConfig::default()).unwrap();
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    t.start(&dut).unwrap();
    t.sample(3, false, &dut).unwrap();
    for again in [3, 2] {
        let e = t.sample(again, false, &dut).unwrap_err().to_string();
        assert!(
            e.contains("o.vcd") && e.contains("timestamps must increase"),
            "{e}"
        );
    }
}

/// A hand-written dump: timescale 10 ps, a bit `tb.a` (0, then 1 at time 3) and a vector
/// `tb.v` numbered 8..1 (5).
fn written_vcd(name: &str) -> Scratch {
    let vcd = Scratch::new("written", &format!("{name}.vcd"));
    let text = "$timescale 10 ps $end\n$scope module tb $end\n$var wire 1 ! a $end\n\
                $var wire 8 \" v [8:1] $end\n$upscope $end\n$enddefinitions $end\n\
                #0\n$dumpvars\n0!\nb101 \"\n$end\n#3\n1!\n";
    std::fs::write(&vcd, text).unwrap();
    vcd
}

/// A VCD converts to a FST of the same timescale and values; the comparison used for that
/// finds each kind of difference.
#[test]
fn a_vcd_converts_with_its_timescale_and_differences_are_found() {
    use waves::fst::same_values;
    let vcd = written_vcd("convert");
    let fst = vcd.with_extension("fst");
    waves::fst::vcd_to_fst(&vcd, &fst).unwrap();
    let (a, b) = (
        read_vcd(&vcd).unwrap(),
        waves::check::read_fst(&fst).unwrap(),
    );
    assert_eq!(b.timescale_exp, Some(-11));
    assert_eq!(same_values(&a, &b), Ok(()));
    let changed = |f: fn(&mut waves::check::Readback)| {
        let mut c = b.clone();
        f(&mut c);
        same_values(&a, &c).unwrap_err()
    };
    let e = changed(|c| drop(c.vars.get_mut("tb.a").unwrap().changes.pop()));
    assert_eq!(e, "tb.a differs at time 3");
    let e = changed(|c| c.vars.get_mut("tb.v").unwrap().width = Some(7));
    assert_eq!(e, "tb.v: width Some(8) vs Some(7)");
    assert_eq!(
        changed(|c| drop(c.vars.remove("tb.a"))),
        "different variables"
    );
    assert!(changed(|c| c.times.push(9)).starts_with("the VCD ends at Some(3)"));
    // A dump that states no timescale is taken as 1 ps, the tracers' own.
    let bare = vcd.with_file_name("bare.vcd");
    let text = std::fs::read_to_string(&vcd).unwrap();
    std::fs::write(&bare, text.replace("$timescale 10 ps $end\n", "")).unwrap();
    waves::fst::vcd_to_fst(&bare, &fst).unwrap();
    let b = waves::check::read_fst(&fst).unwrap();
    assert_eq!(b.timescale_exp, Some(-12));
}

/// A hand-written dump (timescale 10 ps, a vector numbered 8..1) and a save file for it with
/// `lines` after its `[dumpfile]` line: what `check_gtkw` says.
fn check_written(name: &str, lines: &str) -> Result<usize, String> {
    let vcd = written_vcd(name);
    let rb = read_vcd(&vcd).unwrap();
    assert_eq!(rb.timescale_exp, Some(-11), "10 ps");
    assert_eq!(rb.times, [0, 3]);
    let default = "[*] dump 0 3 ps, clock period 1 ps\n[timestart] 0\n*-1.0 -1\n";
    let view = if lines.contains("[*] dump") {
        ""
    } else {
        default
    };
    let gtkw = format!("[dumpfile] \"{}\"\n{view}{lines}", vcd.display());
    std::fs::write(vcd.with_extension("gtkw"), gtkw).unwrap();
    check_gtkw(&vcd, &rb)
}

/// What `check_gtkw` refuses in a save file: ranges that do not give the dump's width, and
/// translate filter files that are missing or not `value name` lines.
#[test]
fn save_files_are_checked_line_by_line() {
    let dir = tmpdir("written");
    let filter = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    let good = filter("good.txt", "# states\n\n0 idle\n1 busy\n");
    assert_eq!(check_written("ok", "@28\ntb.a\n@22\ntb.v[8:1]\n"), Ok(2));
    assert_eq!(
        check_written("f", &format!("@2024\n^1 {good}\ntb.a\n")),
        Ok(1)
    );
    for (name, lines, says) in [
        (
            "narrow",
            "tb.v[7:1]\n".to_string(),
            "the dump says Some(8) bits",
        ),
        ("upside", "tb.v[1:8]\n".into(), "bad range in tb.v[1:8]"),
        ("huge", "tb.v[4294967295:0]\n".into(), "bad range"),
        ("gone", "tb.w\n".into(), "trace tb.w is not in the dump"),
        ("slot", format!("^x {good}\n"), "bad filter slot"),
        (
            "nofile",
            "^1 /no/such/filter.txt\n".into(),
            "filter file /no/such",
        ),
        (
            "noname",
            format!("^1 {}\n", filter("n.txt", "0 idle\n1\n")),
            "'1' is not 'value name'",
        ),
        (
            "hex",
            format!("^1 {}\n", filter("h.txt", "0x1 idle\n")),
            "'0x1' is not a decimal value",
        ),
        ("groups", "@800200\n-g\n".into(), "unbalanced groups"),
        (
            "marker",
            "[*] dump 0 3 ps, clock period 1 ps\n[timestart] 0\n*-1.0 7 7\n".into(),
            "marker at 7 outside the dump",
        ),
        (
            "late",
            "[*] dump 0 3 ps, clock period 1 ps\n[timestart] 5\n*-1.0 -1\n".into(),
            "the view 5..15 leaves the dump 0..3",
        ),
        ("closed", "@1000200\n-g\n".into(), "group closed twice"),
    ] {
        let e = check_written(name, &lines).unwrap_err();
        assert!(e.contains(says), "{name}: {e}");
    }
}

/// The co-simulation comparison waveform: model and RTL side by side with a mismatch flag per
/// port, unknown RTL values as `x`, only changes written, and a save file that opens it with
/// each port's three traces grouped.
#[test]
fn a_comparison_waveform_shows_model_rtl_and_mismatch() {
    let path = Scratch::new("compare", "c.vcd");
    let ports = [("ok", 1, false), ("u", 8, false)];
    let model = vec![vec![1, 5], vec![1, 6], vec![0, 6], vec![0, 7]];
    let rtl = vec![
        vec![Some(1), Some(5)],
        vec![Some(1), Some(9)],
        vec![None, Some(6)],
        vec![Some(0), None],
    ];
    let differs = |c: usize, k: usize| rtl[c][k] != Some(model[c][k]);
    let stim = vec![vec![1, 3], vec![0, 3], vec![0, 4], vec![0, 4]];
    let inputs = [("rst", 1, false), ("a", 4, true)];
    let shown = [waves::compare::Shown {
        scope: "inputs",
        signals: &inputs,
        values: waves::compare::Values::Every(&stim),
        states: &[],
    }];
    waves::compare::write(&path, "unit", &ports, &model, &rtl, &differs, &shown).unwrap();
    let rb = read_vcd(&path).unwrap();
    assert_eq!(rb.times.last(), Some(&40_000), "four cycles of 10 ns");
    let w = |n: &str| rb.vars[n].width;
    assert_eq!(
        (w("tb.model.u"), w("tb.rtl.u"), w("tb.mismatch.u")),
        (Some(8), Some(8), Some(1))
    );
    assert_eq!(w("tb.rtl.ok"), Some(1));
    let at = |n: &str, c: u64| match rb.value_at(n, c * 10_000) {
        Some(Value::Bits(b)) => b.trim_start_matches('0').to_string(),
        v => panic!("{n}: {v:?}"),
    };
    let column = |n: &str| (0..4).map(|c| at(n, c)).collect::<Vec<_>>();
    assert_eq!(column("tb.model.u"), ["101", "110", "110", "111"]);
    assert_eq!(column("tb.rtl.u"), ["101", "1001", "110", "xxxxxxxx"]);
    assert_eq!(column("tb.mismatch.u"), ["", "1", "", "1"]);
    assert_eq!(column("tb.rtl.ok"), ["1", "1", "x", ""]);
    assert_eq!(column("tb.mismatch.ok"), ["", "", "1", ""]);
    // Only changes: the model's `ok` changes once after its initial value.
    assert_eq!(rb.vars["tb.model.ok"].changes.len(), 2);
    assert_eq!(rb.vars["tb.model.u"].changes.len(), 3);
    // One `$dumpvars` block, the first cycle's; a bit declared without a range.
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.matches("$dumpvars").count(), 1);
    let (_, after) = text.split_once("#0\n$dumpvars\n").unwrap();
    assert!(after.split_once("#10000").unwrap().0.ends_with("$end\n"));
    let body = text.split_once("$enddefinitions $end\n").unwrap().1;
    assert_eq!(
        body.lines().filter(|l| *l == "$end").count(),
        1,
        "one block closed"
    );
    assert!(text
        .lines()
        .any(|l| l.starts_with("$var wire 1 ") && l.ends_with(" ok $end")));
    assert!(text
        .lines()
        .any(|l| l.starts_with("$var wire 8 ") && l.ends_with(" u [7:0] $end")));
    // The inputs beside the comparison, only their changes, in a group of their own first.
    assert_eq!(column("tb.inputs.a"), ["11", "11", "100", "100"]);
    assert_eq!(column("tb.inputs.rst"), ["1", "", "", ""]);
    assert_eq!(rb.vars["tb.inputs.a"].changes.len(), 2);
    assert_eq!(check_gtkw(&path, &rb), Ok(8));
    let g = std::fs::read_to_string(path.with_extension("gtkw")).unwrap();
    assert!(
        g.find("tb.inputs.a[3:0]") < g.find("tb.model.ok"),
        "inputs first:\n{g}"
    );
    for (name, flags) in [
        ("+{ok model} tb.model.ok", "28"),
        ("+{u RTL} tb.rtl.u[7:0]", "24"),
        ("+{u mismatch} tb.mismatch.u", "28"),
        ("tb.inputs.a[3:0]", "424"),
    ] {
        assert_eq!(flags_of(&g, name), Some(flags), "{name} in\n{g}");
    }
    assert!(g.contains("@800200\n-u\n"), "a group per port");
    assert!(
        g.contains(
            "[timestart] 0\n[size] 1600 900\n[pos] -1 -1\n*-13.036174 15000 15000\n\
                    [markername] Afirst mismatch\n"
        ),
        "zoomed to the four cycles, marker A on the first mismatch (cycle 1):\n{g}"
    );
}

/// A window of an RTL's internals (cycles 1..3 of 5) beside a comparison: its values there,
/// x where unknown, z where not recorded; a dotted name in a scope of its own, in the tree and
/// not in the view; the window's group below the ports; the ports that never differ closed.
#[test]
fn a_window_of_internals_is_recorded_where_it_was_dumped() {
    use waves::compare::{Shown, Values};
    let path = Scratch::new("compare", "w.vcd");
    let ports = [("ok", 1, false), ("u", 8, false)];
    let model = vec![vec![1, 5]; 5];
    let mut rtl = vec![vec![Some(1), Some(5)]; 5];
    rtl[2][1] = Some(6);
    let differs = |c: usize, k: usize| rtl[c][k] != Some(model[c][k]);
    let inner = [("acc", 4, false), ("u_sat.hit", 1, false)];
    let window = vec![vec![Some(3), Some(0)], vec![None, Some(1)]];
    let fsm = [("state", 2, false)];
    let states = vec![vec![Some(1)], vec![Some(2)]];
    let names: &[&str] = &["IDLE", "RUN", "DONE"];
    let shown = [
        Shown {
            scope: "rtl_internals",
            signals: &inner,
            values: Values::From(1, &window),
            states: &[],
        },
        Shown {
            scope: "model_internals",
            signals: &fsm,
            values: Values::From(1, &states),
            states: &[(0, names)],
        },
    ];
    waves::compare::write(&path, "unit", &ports, &model, &rtl, &differs, &shown).unwrap();
    let rb = read_vcd(&path).unwrap();
    let at = |n: &str, c: u64| match rb.value_at(n, c * 10_000) {
        Some(Value::Bits(b)) => b.clone(),
        v => panic!("{n}: {v:?}"),
    };
    let column = |n: &str| (0..5).map(|c| at(n, c)).collect::<Vec<_>>();
    assert_eq!(
        column("tb.rtl_internals.acc"),
        ["zzzz", "0011", "xxxx", "zzzz", "zzzz"]
    );
    assert_eq!(
        column("tb.rtl_internals.u_sat.hit"),
        ["z", "0", "1", "z", "z"]
    );
    assert!(rb.scopes.iter().any(|s| s == "tb.rtl_internals.u_sat"));
    assert_eq!(check_gtkw(&path, &rb), Ok(8));
    // A signal with named values: by name, through a filter file beside the dump.
    let filter = path.with_file_name("w.model_internals.state.txt");
    let text = std::fs::read_to_string(&filter).unwrap();
    assert!(text.contains("\n1 RUN\n2 DONE\n"), "{text}");
    let g = std::fs::read_to_string(path.with_extension("gtkw")).unwrap();
    assert!(
        g.find("tb.rtl.u[7:0]") < g.find("tb.rtl_internals.acc"),
        "{g}"
    );
    assert!(!g.contains("u_sat"), "nested signals are in the tree:\n{g}");
    assert!(
        g.contains("^1 w.model_internals.state.txt\ntb.model_internals.state[1:0]"),
        "{g}"
    );
    assert!(
        g.contains("@c00200\n-ok\n") && g.contains("@1401200\n-ok\n"),
        "{g}"
    );
    assert!(
        g.contains("@800200\n-u\n"),
        "the port that differs is open:\n{g}"
    );
}

/// A state machine of kind `kind`: one enumerated output.
struct Fsm {
    name: &'static str,
    kind: &'static str,
    state: hdl::kernel::Signal,
}

impl hdl::kernel::Module for Fsm {
    fn instance(&self) -> &str {
        self.name
    }
    fn kind(&self) -> &'static str {
        self.kind
    }
    fn eval(&mut self) {}
    fn tick(&mut self, _: bool) {}
    fn visit(&self, v: &mut dyn hdl::kernel::Visitor) {
        v.enter(self.name, self.kind);
        v.signal(hdl::kernel::Dir::Output, &self.state);
        v.leave();
    }
}

/// Two machines of one kind and one of another under a top module.
struct Machines(Vec<Fsm>);

impl hdl::kernel::Module for Machines {
    fn kind(&self) -> &'static str {
        "machines"
    }
    fn eval(&mut self) {}
    fn tick(&mut self, _: bool) {}
    fn visit(&self, v: &mut dyn hdl::kernel::Visitor) {
        v.enter("machines", "machines");
        for m in &self.0 {
            m.visit(v);
        }
        v.leave();
    }
}

/// State names go to one translate filter file per kind and signal, shared by a kind's
/// instances; every file is written and named in the save file.
#[test]
fn each_kind_of_state_machine_has_its_filter_file() {
    use hdl::fx::Format;
    let fsm = |name, kind, names: &'static [&'static str]| Fsm {
        name,
        kind,
        state: hdl::kernel::Signal::new("state", Format::uint(2)).with_states(names),
    };
    let dut = Machines(vec![
        fsm("a0", "ctl", &["IDLE", "RUN"]),
        fsm("a1", "ctl", &["IDLE", "RUN"]),
        fsm("b0", "fill", &["WAIT", "LOAD", "DONE"]),
    ]);
    let path = Scratch::new("fsm", "m.vcd");
    let t = VcdTracer::create(&path, "machines", TraceConfig::default()).unwrap();
    let mut sim = Sim::traced(dut, t).unwrap();
    sim.reset(1);
    sim.tick();
    sim.finish().unwrap();
    let dir = path.parent().unwrap();
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    let head = "# texrtl: state names, value in decimal\n";
    assert_eq!(read("m.ctl.state.txt"), format!("{head}0 IDLE\n1 RUN\n"));
    assert_eq!(
        read("m.fill.state.txt"),
        format!("{head}0 WAIT\n1 LOAD\n2 DONE\n")
    );
    let rb = read_vcd(&path).unwrap();
    assert_eq!(check_gtkw(&path, &rb), Ok(2 + 3));
    let g = read("m.gtkw");
    let slots: Vec<&str> = g.lines().filter(|l| l.starts_with('^')).collect();
    assert_eq!(slots.len(), 3, "{g}");
    assert_eq!(
        slots[0], "^1 m.ctl.state.txt",
        "beside the save file: by name"
    );
    assert_eq!(slots[1], slots[0], "a kind's instances share their file");
    assert_eq!(slots[2], "^2 m.fill.state.txt");
    // A copy of the folder, the original gone: its save file still finds its filters.
    let copy = tmpdir("fsm-copy");
    for f in ["m.vcd", "m.gtkw", "m.ctl.state.txt", "m.fill.state.txt"] {
        std::fs::copy(dir.join(f), copy.path().join(f)).unwrap();
    }
    std::fs::remove_dir_all(dir).unwrap();
    let moved = copy.path().join("m.vcd");
    assert_eq!(check_gtkw(&moved, &read_vcd(&moved).unwrap()), Ok(2 + 3));
}

/// Integer registers of both signs, one-bit flags and a hex-shown address, counting from
/// the first cycle out of reset.
struct Counters {
    count: hdl::kernel::Signal,
    delta: hdl::kernel::Signal,
    addr: hdl::kernel::Signal,
    odd: hdl::kernel::Signal,
    n: u64,
}

impl hdl::kernel::Module for Counters {
    fn kind(&self) -> &'static str {
        "counters"
    }
    fn eval(&mut self) {}
    fn tick(&mut self, reset: bool) {
        self.n = if reset { 0 } else { self.n + 1 };
        self.count.set_bits(self.n & 0xff);
        self.delta.set_bits((self.n.wrapping_neg()) & 0x3f);
        self.addr.set_bits(0x1000 + self.n);
        self.odd.set_bits(self.n & 1);
    }
    fn visit(&self, v: &mut dyn hdl::kernel::Visitor) {
        v.enter("c", "counters");
        for s in [&self.count, &self.delta, &self.addr, &self.odd] {
            v.signal(hdl::kernel::Dir::Output, s);
        }
        v.leave();
    }
}

/// The radix follows the format (decimal unsigned, signed decimal, binary bits, hex where a
/// pattern asks), integer vectors have `real` companions in the dump, and the view opens on
/// the first cycles out of reset, [`waves::gtkw::OPENING_CYCLES`] of them.
#[test]
fn radix_companions_and_the_opening_view_follow_the_formats() {
    use hdl::fx::Format;
    let sig = |n, f| hdl::kernel::Signal::new(n, f);
    let dut = Counters {
        count: sig("count", Format::uint(8)),
        delta: sig("delta", Format::sint(6)),
        addr: sig("addr", Format::uint(16)),
        odd: sig("odd", Format::uint(1)),
        n: 0,
    };
    let path = Scratch::new("radix", "c.vcd");
    let cfg = TraceConfig {
        hex: vec!["*.addr".into()],
        ..TraceConfig::default()
    };
    let mut sim = Sim::traced(dut, VcdTracer::create(&path, "counters", cfg).unwrap()).unwrap();
    sim.reset(300);
    for _ in 0..1000 {
        sim.eval();
        sim.tick();
    }
    sim.finish().unwrap();
    let rb = read_vcd(&path).unwrap();
    check_gtkw(&path, &rb).unwrap();
    let g = std::fs::read_to_string(path.with_extension("gtkw")).unwrap();
    for (name, flags) in [
        ("tb.c.count[7:0]", "24"),
        ("tb.c.delta[5:0]", "424"),
        ("tb.c.addr[15:0]", "22"),
        ("tb.c.odd", "28"),
    ] {
        assert_eq!(flags_of(&g, name), Some(flags), "{name} in\n{g}");
    }
    let t = 310 * 10_000;
    assert_eq!(rb.value_at("tb.c.count_real", t), Some(&Value::Real(10.0)));
    assert_eq!(rb.value_at("tb.c.delta_real", t), Some(&Value::Real(-10.0)));
    assert!(
        !rb.vars.contains_key("tb.c.odd_real"),
        "no companion for a bit"
    );
    assert!(
        !g.contains("count_real"),
        "integer companions stay out of the view"
    );
    let v = waves::gtkw::View::parse(&g).unwrap();
    assert_eq!(
        v.window.0,
        298 * 10_000,
        "two cycles before the reset falls"
    );
    let span = v.window.1 - v.window.0;
    assert!(
        span.abs_diff(waves::gtkw::OPENING_CYCLES * 10_000) <= 10,
        "{v:?}"
    );
    assert_eq!(v.marker, None);
}

/// The tracer's change count is what the file holds: every change but the clock's falls,
/// companions and probes included.
#[test]
fn the_change_count_is_what_the_file_holds() {
    let path = Scratch::new("count", "c.vcd");
    let mut t = VcdTracer::create(&path, "count", TraceConfig::default()).unwrap();
    let gold = t.probe_real("u0", None);
    let dut = BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap();
    let mut sim = Sim::traced(dut, t).unwrap();
    drive(&mut sim, |sim| {
        let u = sim.dut.o.u0.fx().to_f64();
        sim.trace_mut().unwrap().set_real(gold, u);
    });
    let n = sim.trace_mut().unwrap().changes();
    sim.finish().unwrap();
    let rb = read_vcd(&path).unwrap();
    assert!(
        rb.vars.contains_key("tb.blend_adjust_153.u0_real"),
        "companions on"
    );
    assert_eq!(rb.total_changes() as u64, n + 22, "and 22 clock falls");
}
