//! Co-simulation of the Verilog twins against their models, in Verilator and Icarus, and
//! proof that the harness fails: one-bit bugs injected into a twin are reported with the
//! right cycle and port. Without a simulator the tests say so in one line and pass, unless
//! `TEXRTL_REQUIRE_COSIM=1` (which `.ci/run` sets).

use std::path::PathBuf;
use tb::cosim::{
    AddressCosim, BilinearCosim, BlendAdjustCosim, CacheCosim, ControlCosim, FillCosim,
    LookaheadCosim, MipmapCosim, NormalCosim, PipelineCosim, ReplicateCosim, RsqrtCosim,
    TangentCosim, TexelFetchCosim, TexramCosim, TextureCosim, WalkerCosim,
};
use units::bump::blend_adjust_153::BlendAdjustParams;
use units::bump::params::{Border, BumpParams, Filter, HeightTexel, RsqrtParams};
use units::mipmap::mipmap_gen_816::{MipmapParams, Rounding, Scan};
use units::texmem::cache_614::Lookahead;
use units::texmem::dram_604::DramParams;
use units::texmem::layout::Layout;
use units::texmem::texture_unit_602::TexParams;
use verif::cosim::{run, CosimUnit, Simulator};
use verif::Seed;

/// Whether `sim` can run; without it, fails only when co-simulation is required.
fn available(sim: Simulator) -> bool {
    match sim.check_installed() {
        Ok(()) => true,
        Err(e) if std::env::var("TEXRTL_REQUIRE_COSIM").as_deref() == Ok("1") => {
            panic!("TEXRTL_REQUIRE_COSIM=1 but {e}")
        }
        Err(e) => {
            println!("co-simulation skipped: {e}");
            false
        }
    }
}

/// A fresh folder of its own for each call: the quick check and the full sweep run the same
/// configurations, at once under `--include-ignored`.
fn dir(name: &str) -> PathBuf {
    static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("texrtl-cosim-{}-{n}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn params(frac_bits: u32, registered: bool) -> BlendAdjustParams {
    BlendAdjustParams {
        frac_bits,
        registered,
    }
}

/// A configuration of a twin: its label and the unit.
type Twin = (String, Box<dyn CosimUnit>);

/// Every twin in every configuration the tests cover.
fn twins() -> Vec<Twin> {
    let mut v = fig7_twins();
    v.extend(memory_twins());
    for (label, u) in mipmap_configs() {
        v.push((format!("mipmap_gen_816 {label}"), Box::new(u)));
    }
    v
}

/// The FIG. 7 units and their pipeline.
fn fig7_twins() -> Vec<Twin> {
    let mut v: Vec<Twin> = Vec::new();
    for (f, reg) in [(8, true), (4, false), (16, true)] {
        v.push((
            format!("blend_adjust_153 F={f} registered={reg}"),
            Box::new(BlendAdjustCosim(params(f, reg))),
        ));
    }
    for (i, fr, b) in [(16, 8, 8), (4, 16, 12), (24, 4, 4)] {
        let u = AddressCosim {
            pos_int: i,
            pos_frac: fr,
            blend_bits: b,
        };
        v.push((format!("address_150 sQ{i}.{fr} F={b}"), Box::new(u)));
    }
    for (t, bez) in [(8, false), (8, true), (4, true)] {
        let u = ReplicateCosim {
            texel_bits: t,
            bezier: bez,
        };
        v.push((format!("replicate_152 {t}-bit bezier={bez}"), Box::new(u)));
    }
    // Exact (the default), rounded to 12 fraction bits, 4-bit texels with F = 16 rounded to 8.
    for (t, f, frac) in [(8, 8, None), (8, 8, Some(12)), (4, 16, Some(8))] {
        let u = BilinearCosim {
            texel_bits: t,
            blend_bits: f,
            bilinear_frac: frac,
        };
        v.push((
            format!("bilinear_65_68 {t}-bit F={f} frac={frac:?}"),
            Box::new(u),
        ));
    }
    for (label, p) in tangent_configs() {
        v.push((format!("tangent_155 {label}"), Box::new(TangentCosim(p))));
    }
    // The default; the table alone (4 bits); the widest mantissa and iterate with the
    // smallest table and the most iterations; the largest table with short iterates.
    for (table_bits, iterations, mant_frac, y_frac) in [
        (8, 1, 22, 24),
        (4, 0, 8, 8),
        (3, 3, 40, 40),
        (14, 2, 30, 12),
    ] {
        let p = RsqrtParams {
            table_bits,
            iterations,
            mant_frac,
            y_frac,
        };
        v.push((
            format!("rsqrt_156 table={table_bits} iter={iterations} uQ2.{mant_frac} uQ1.{y_frac}"),
            Box::new(RsqrtCosim(p)),
        ));
    }
    for (label, u) in texel_fetch_configs() {
        v.push((format!("texel_fetch_151 {label}"), Box::new(u)));
    }
    for (label, p) in normal_configs() {
        v.push((format!("normal_156 {label}"), Box::new(NormalCosim(p))));
    }
    for (label, u) in pipeline_configs() {
        v.push((format!("normal_pipeline_fig7 {label}"), Box::new(u)));
    }
    v
}

/// Figure 6: control unit 607's word controller, lookahead queue and block fetch, cache 614.
fn memory_twins() -> Vec<Twin> {
    let mut v: Vec<Twin> = Vec::new();
    for (label, p) in control_configs() {
        v.push((format!("control_607 {label}"), Box::new(ControlCosim(p))));
    }
    for (mode, blocks, frac_bits) in [
        (Lookahead::Quadrant, (16, 16), 4),
        (Lookahead::Direction, (16, 16), 4),
        (Lookahead::Direction, (5, 3), 8),
        (Lookahead::Quadrant, (1, 1), 1),
        (Lookahead::Off, (16, 16), 4),
    ] {
        let u = LookaheadCosim {
            mode,
            blocks,
            frac_bits,
        };
        let label = format!(
            "lookahead_queue_607 {} {}x{} blocks F={frac_bits}",
            mode.name(),
            blocks.0,
            blocks.1
        );
        v.push((label, Box::new(u)));
    }
    for tag_bits in [9, 1, 12] {
        v.push((
            format!("cache_614 tags of {tag_bits} bits"),
            Box::new(CacheCosim { tag_bits }),
        ));
    }
    for (label, u) in fill_configs() {
        v.push((format!("fill_engine_607 {label}"), Box::new(u)));
    }
    for slot_cycles in [6, 1, 15] {
        v.push((
            format!("texram_802 slots of {slot_cycles} cycles"),
            Box::new(TexramCosim { slot_cycles }),
        ));
    }
    for (label, p) in texture_configs() {
        v.push((
            format!("texture_unit_602 {label}"),
            Box::new(TextureCosim(p)),
        ));
    }
    for slot_cycles in [6, 1, 15] {
        v.push((
            format!("walker_812 slots of {slot_cycles} cycles"),
            Box::new(WalkerCosim { slot_cycles }),
        ));
    }
    v
}

/// Texture unit 602: 64x64 texels, quadrant lookahead (the default); direction lookahead over
/// a 40x24 tiled texture at word 4096 with F = 8 and the slow DRAM; the cache off (every
/// request fetches every block) on one 4x4 block with F = 1; tiny pages with the shortest
/// timing (a fault on nearly every word).
fn texture_configs() -> Vec<(&'static str, TexParams)> {
    let d = TexParams::new(64, 64);
    let dram = |k: usize| control_configs()[k].1;
    vec![
        ("64x64 quadrant (default)", d),
        (
            "40x24 tiled at 4096, direction, F=8, slow DRAM",
            TexParams {
                frac_bits: 8,
                layout: Layout::Tiled,
                base: 4096,
                lookahead: Lookahead::Direction,
                dram: DramParams {
                    cols: 512,
                    rows: 512,
                    ..dram(3)
                },
                ..TexParams::new(40, 24)
            },
        ),
        (
            "4x4 cache off, F=1",
            TexParams {
                frac_bits: 1,
                cache: false,
                ..TexParams::new(4, 4)
            },
        ),
        (
            "16x8 on 4 x 8-word pages, shortest timing",
            TexParams {
                dram: dram(2),
                ..TexParams::new(16, 8)
            },
        ),
    ]
}

/// The mipmap generator: progressive 16x16 back to back; both interlaced field orders with
/// blanking and truncation; sides of 1 (vertical pairs only, horizontal pairs only); a 1x1
/// frame; 2x2 interlaced (the shift register loaded with the line just written); a 256-wide
/// frame (FIFOs of 128); a sync error mid-frame.
fn mipmap_configs() -> Vec<(String, MipmapCosim)> {
    let m = |width, height, scan, rounding, rate| {
        let mut u = MipmapCosim::new(MipmapParams {
            width,
            height,
            scan,
            rounding,
        });
        u.rate = rate;
        u
    };
    let (p, t, b) = (
        Scan::Progressive,
        Scan::InterlacedTop,
        Scan::InterlacedBottom,
    );
    let (r, tr) = (Rounding::Round, Rounding::Truncate);
    let mut v: Vec<MipmapCosim> = vec![
        m(16, 16, p, r, 8),
        m(32, 8, t, tr, 6),
        m(8, 16, b, r, 7),
        m(1, 8, p, r, 8),
        m(32, 1, p, tr, 5),
        m(1, 1, p, r, 8),
        m(2, 2, t, r, 8),
        m(256, 4, b, tr, 8),
    ];
    let mut e = m(8, 8, p, r, 8);
    e.sync_error_at = Some(100);
    v.push(e);
    v.into_iter()
        .map(|u| {
            let p = u.params;
            let err = u
                .sync_error_at
                .map_or(String::new(), |n| format!(", sof inverted at texel {n}"));
            let label = format!(
                "{}x{} {:?} {:?} {}/8 cycles{err}",
                p.width, p.height, p.scan, p.rounding, u.rate
            );
            (label, u)
        })
        .collect()
}

/// The block fetch: row-major on the default DRAM; tiled (16 x 16 blocks to a 512-word page)
/// from a base address; tiled on 1M x 16 (a 32 x 16 tile, three tiles across an odd width);
/// row-major on tiny pages.
fn fill_configs() -> Vec<(&'static str, FillCosim)> {
    let d = DramParams::default();
    let fill = |layout, blocks, base, dram| FillCosim {
        layout,
        blocks,
        base,
        dram,
    };
    vec![
        (
            "row-major 16x16 blocks",
            fill(Layout::RowMajor, (16, 16), 0, d),
        ),
        (
            "tiled 40x24 blocks from word 4096",
            fill(Layout::Tiled, (40, 24), 4096, d),
        ),
        (
            "tiled 70x20 blocks, 1M x 16",
            fill(Layout::Tiled, (70, 20), 0, DramParams::one_meg()),
        ),
        (
            "row-major 5x3 blocks, 64 x 32 words",
            fill(
                Layout::RowMajor,
                (5, 3),
                6,
                DramParams {
                    rows: 64,
                    cols: 32,
                    ..d
                },
            ),
        ),
    ]
}

/// Control unit 607 with DRAM 604: the document's 256K x 16 (30 ns page mode, 30 ns more on
/// a fault at 5 ns a cycle); 1M x 16; tiny pages (4 rows of 8 words: mostly faults) with the
/// shortest legal timing; long CAS# and RAS# times.
fn control_configs() -> Vec<(&'static str, DramParams)> {
    let d = DramParams::default();
    vec![
        ("256K x 16, 512-word pages (default)", d),
        ("1M x 16, 1024-word pages", DramParams::one_meg()),
        (
            "4 x 8 words, t_rp 1 t_rcd 1 t_cas 2 t_cp 1",
            DramParams {
                rows: 4,
                cols: 8,
                t_rp: 1,
                t_rcd: 1,
                t_cas: 2,
                t_cp: 1,
                ..d
            },
        ),
        (
            "64 x 32 words, t_rp 5 t_rcd 4 t_cas 7 t_cp 2",
            DramParams {
                rows: 64,
                cols: 32,
                t_rp: 5,
                t_rcd: 4,
                t_cas: 7,
                t_cp: 2,
                ..d
            },
        ),
    ]
}

/// The FIG. 7 pipeline: the default; trilinear over a map whose sides are not powers of two
/// (clamped, two Newton steps); Bezier with 4-bit texels, F = 12 and rounded bilinear outputs
/// (mirrored); Blinn trilinear with a constant border, the table alone and short outputs.
fn pipeline_configs() -> Vec<(&'static str, PipelineCosim)> {
    let d = BumpParams::default();
    let r = d.rsqrt;
    vec![
        ("default 16x16", PipelineCosim::new(d, 16, 16, 11)),
        (
            "trilinear 13x11 clamp 2 iterations",
            PipelineCosim::new(
                BumpParams {
                    trilinear: true,
                    border: Border::Clamp,
                    rsqrt: RsqrtParams { iterations: 2, ..r },
                    ..d
                },
                13,
                11,
                12,
            ),
        ),
        (
            "Bezier 4-bit F=12 bl.frac=10 mirror 9x5",
            PipelineCosim::new(
                BumpParams {
                    filter: Filter::Bezier,
                    height: HeightTexel::Bits4,
                    blend_bits: 12,
                    pos_frac: 12,
                    bilinear_frac: Some(10),
                    border: Border::Mirror,
                    ..d
                },
                9,
                5,
                13,
            ),
        ),
        (
            "Blinn trilinear constant 0x3c 8x8 table alone out.frac=12",
            PipelineCosim::new(
                BumpParams {
                    filter: Filter::Blinn,
                    trilinear: true,
                    border: Border::Constant(0x3c),
                    tangent_frac: 12,
                    out_frac: 12,
                    rsqrt: RsqrtParams { iterations: 0, ..r },
                    ..d
                },
                8,
                8,
                14,
            ),
        ),
    ]
}

/// Texel fetch unit 151: every border mode, power-of-two and other sides (the modulo of the
/// wrap and mirror modes), 8- and 4-bit texels, the smallest map (2 x 2) and narrow
/// coordinates (`pos_int` 4: the coordinate's whole range is near the map).
fn texel_fetch_configs() -> Vec<(&'static str, TexelFetchCosim)> {
    let d = BumpParams::default();
    let with = |border, height, pos_int| BumpParams {
        border,
        height,
        pos_int,
        ..d
    };
    vec![
        ("16x16 wrap 8-bit", TexelFetchCosim::new(d, 16, 16, 1)),
        (
            "13x7 clamp 8-bit",
            TexelFetchCosim::new(with(Border::Clamp, HeightTexel::Bits8, 16), 13, 7, 2),
        ),
        (
            "5x9 mirror 4-bit",
            TexelFetchCosim::new(with(Border::Mirror, HeightTexel::Bits4, 16), 5, 9, 3),
        ),
        (
            "2x2 constant 0xb5 8-bit sQ4 coordinates",
            TexelFetchCosim::new(with(Border::Constant(0xb5), HeightTexel::Bits8, 4), 2, 2, 4),
        ),
        (
            "12x6 wrap 4-bit sQ4 coordinates",
            TexelFetchCosim::new(with(Border::Wrap, HeightTexel::Bits4, 4), 12, 6, 5),
        ),
    ]
}

/// Normal unit 156: the default; short iterates and more output bits than the product has
/// (the result shifted left, nothing rounded) with two iterations; the widest tangents
/// (`sQ20.24`, an 89-bit sum of squares) with the table alone.
fn normal_configs() -> Vec<(&'static str, BumpParams)> {
    let d = BumpParams::default();
    vec![
        ("default (sQ16.16 in, sQ2.16 out, 1 iteration)", d),
        (
            "sQ16.8 in, sQ2.24 out, uQ2.8 -> uQ1.8, 2 iterations",
            BumpParams {
                tangent_frac: 8,
                out_frac: 24,
                rsqrt: RsqrtParams {
                    table_bits: 6,
                    iterations: 2,
                    mant_frac: 8,
                    y_frac: 8,
                },
                ..d
            },
        ),
        (
            "sQ20.24 in, table alone",
            BumpParams {
                scale_int: 12,
                tangent_frac: 24,
                rsqrt: RsqrtParams {
                    iterations: 0,
                    ..d.rsqrt
                },
                ..d
            },
        ),
    ]
}

/// Tangent unit 155: the default; Blinn with 4 bilinear fraction bits and an integer scale
/// (the tangents gain fraction bits: nothing rounded); Bezier with 4-bit texels, F = 16 and
/// rounded bilinear outputs; F = 16 exact with the widest scale and tangents (a 225-bit
/// stimulus line, 97-bit height product).
fn tangent_configs() -> Vec<(&'static str, BumpParams)> {
    let d = BumpParams::default();
    vec![
        ("default (B-spline, 8-bit, F=8)", d),
        (
            "Blinn bl.frac=4 scale uQ4.0 tan.frac=12",
            BumpParams {
                filter: Filter::Blinn,
                bilinear_frac: Some(4),
                scale_int: 4,
                scale_frac: 0,
                tangent_frac: 12,
                ..d
            },
        ),
        (
            "Bezier 4-bit F=16 bl.frac=10 scale uQ2.16 tan.frac=8",
            BumpParams {
                filter: Filter::Bezier,
                height: HeightTexel::Bits4,
                blend_bits: 16,
                pos_frac: 16,
                bilinear_frac: Some(10),
                scale_int: 2,
                scale_frac: 16,
                tangent_frac: 8,
                ..d
            },
        ),
        (
            "trilinear B-spline (default widths)",
            BumpParams {
                trilinear: true,
                ..d
            },
        ),
        (
            "trilinear Blinn 4-bit F=12 bl.frac=6 scale uQ3.5 tan.frac=10",
            BumpParams {
                trilinear: true,
                filter: Filter::Blinn,
                height: HeightTexel::Bits4,
                blend_bits: 12,
                pos_frac: 12,
                bilinear_frac: Some(6),
                scale_int: 3,
                scale_frac: 5,
                tangent_frac: 10,
                ..d
            },
        ),
        (
            "B-spline 8-bit F=16 exact scale uQ12.16 tan.frac=24",
            BumpParams {
                blend_bits: 16,
                pos_frac: 16,
                scale_int: 12,
                scale_frac: 16,
                tangent_frac: 24,
                ..d
            },
        ),
    ]
}

/// Every twin matches its model on every port of every cycle. The twins' first configurations, every unit once, in both simulators (20 k cycles in
/// Verilator, 5 k in Icarus): the quick check of `cargo test`. The full sweep is below.
#[test]
fn every_twin_matches_its_model_on_every_cycle() {
    let first = |sim: Simulator| match sim {
        Simulator::Verilator => 20_000,
        Simulator::Icarus => 5_000,
    };
    sweep(&|sim, _, first_of_unit| first_of_unit.then(|| first(sim)));
}

/// Every configuration of every twin (66: widths, modes, borders, sizes, timings), 100 k
/// cycles each in Verilator, the first configuration of each unit 20 k in Icarus. Slow:
/// `cargo test -- --ignored`, which `.ci/run` runs; `TEXRTL_COSIM_ONLY=text` narrows it to
/// configurations whose label contains `text`.
#[test]
#[ignore = "slow (about 4 minutes on 2 cores): cargo test -- --ignored, as .ci/run does"]
fn every_configuration_of_every_twin_matches_on_every_cycle() {
    let only = std::env::var("TEXRTL_COSIM_ONLY").unwrap_or_default();
    sweep(&|sim, label, first_of_unit| {
        if !label.contains(&only) {
            return None;
        }
        match sim {
            Simulator::Verilator => Some(100_000),
            Simulator::Icarus => first_of_unit.then_some(20_000),
        }
    });
}

/// Co-simulates the twins `cycles(simulator, label, first configuration of its unit)` picks,
/// for the cycles it says, two at a time; every failure is reported.
fn sweep(cycles: &(dyn Fn(Simulator, &str, bool) -> Option<usize> + Sync)) {
    let mut jobs: Vec<(Simulator, usize, usize)> = Vec::new();
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !available(sim) {
            continue;
        }
        let mut seen = Vec::new();
        for (k, (label, u)) in twins().iter().enumerate() {
            if let Some(n) = cycles(sim, label, !seen.contains(&u.name())) {
                jobs.push((sim, k, n));
            }
            seen.push(u.name());
        }
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                let units = twins();
                loop {
                    let j = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&(sim, k, n)) = jobs.get(j) else {
                        break;
                    };
                    let (label, u) = &units[k];
                    if let Err(e) = check_twin(label, u.as_ref(), sim, n) {
                        failures.lock().unwrap().push(e);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One twin in one configuration and simulator: equal on every cycle, its waveform and
/// `.gtkw` read back.
fn check_twin(label: &str, u: &dyn CosimUnit, sim: Simulator, n: usize) -> Result<(), String> {
    let safe: String = label
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let d = dir(&format!("{}-{safe}", sim.name()));
    let r = run(u, sim, &[], n, Seed(label.len() as u64), &d)
        .map_err(|e| format!("{label} in {}: {e}", sim.name()))?;
    if r.cycles != n {
        return Err(format!("{label}: {} cycles, not {n}", r.cycles));
    }
    if let Some(m) = r.mismatch {
        return Err(format!("{label} in {}: {m}", sim.name()));
    }
    let vcd = r.vcd.as_ref().ok_or("no waveform")?;
    let rb = waves::check::read_vcd(vcd)?;
    waves::check::check_gtkw(vcd, &rb)?;
    let _ = std::fs::remove_dir_all(&d);
    Ok(())
}

/// A one-bit bug: in the twin's source `.0`, `.1` replaced by `.2`.
#[derive(Clone, Copy)]
struct Bug(&'static str, &'static str, &'static str);

/// Requires the first difference of `u` with `bug` injected (its other sources kept, all
/// passed as a user passes `--rtl`) at cycle and port `want`, in every simulator installed,
/// over `n` cycles from `seed`.
fn assert_caught(u: &dyn CosimUnit, bug: Bug, n: usize, seed: Seed, want: (usize, &str)) {
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !available(sim) {
            continue;
        }
        // One folder per bug: two bugs of one unit may run at once.
        let tag = {
            use std::hash::{Hash, Hasher};
            let mut h = std::collections::hash_map::DefaultHasher::new();
            bug.1.hash(&mut h);
            h.finish() as u16
        };
        let d = dir(&format!("bug-{}-{tag:04x}-{}", u.name(), sim.name()));
        let sources: Vec<PathBuf> = u
            .rtl()
            .into_iter()
            .map(|f| match f == tb::cosim::rtl_dir().join(bug.0) {
                true => mutant(&d, bug.0, bug.1, bug.2),
                false => f,
            })
            .collect();
        let r = run(u, sim, &sources, n, seed, &d).unwrap();
        let diff = r
            .mismatch
            .unwrap_or_else(|| panic!("{}: the bug is not caught", sim.name()));
        let _ = std::fs::remove_dir_all(&d);
        assert_eq!(
            (diff.cycle, diff.port.as_str()),
            want,
            "{}: {diff}",
            sim.name()
        );
    }
}

/// The twin with `from` replaced by `to` (a one-bit bug), as a user's `--rtl` file.
fn mutant(d: &std::path::Path, file: &str, from: &str, to: &str) -> PathBuf {
    let src = std::fs::read_to_string(tb::cosim::rtl_dir().join(file)).unwrap();
    assert!(src.contains(from), "the twin has {from}");
    std::fs::create_dir_all(d).unwrap();
    let p = d.join("mutant.v");
    std::fs::write(&p, src.replacen(from, to, 1)).unwrap();
    p
}

/// The first cycle and port where the model with `alt` parameters differs from the model with
/// `base` on the harness's stimulus (what a bug equivalent to that change must report).
fn first_difference(base: BlendAdjustParams, alt: BlendAdjustParams, n: usize) -> (usize, String) {
    models_differ(&BlendAdjustCosim(base), &BlendAdjustCosim(alt), Seed(9), n)
}

/// The first cycle and port where the models of `a` and `b` differ on `a`'s stimulus.
fn models_differ(a: &dyn CosimUnit, b: &dyn CosimUnit, seed: Seed, n: usize) -> (usize, String) {
    let stim = a.stimulus(seed, n);
    let (mut ma, mut mb) = (a.model().unwrap(), b.model().unwrap());
    let (_, outs) = ma.ports();
    for (c, s) in stim.iter().enumerate() {
        let rst = c < verif::cosim::RESET_CYCLES;
        let (x, y) = (ma.cycle(rst, s), mb.cycle(rst, s));
        if c < verif::cosim::FIRST_COMPARED {
            continue;
        }
        if let Some(k) = (0..x.len()).find(|&k| x[k] != y[k]) {
            return (c, outs[k].name.clone());
        }
    }
    panic!("no difference in {n} cycles")
}

#[test]
fn injected_bugs_are_caught_with_their_cycle_and_port() {
    let sims: Vec<Simulator> = [Simulator::Verilator, Simulator::Icarus]
        .into_iter()
        .filter(|s| available(*s))
        .collect();
    for sim in sims {
        let n = 2_000;
        // A constant changed: u0 = {1'b0, u} instead of {1'b1, u} (the 1/2 of para. 0059 lost).
        let d = dir(&format!("bug-const-{}", sim.name()));
        let m = mutant(
            &d,
            "bump/blend_adjust_153.v",
            "u0_c = bypass ? {u_in, 1'b0} : {1'b1, u_in}",
            "u0_c = bypass ? {u_in, 1'b0} : {1'b0, u_in}",
        );
        let u = BlendAdjustCosim(params(8, true));
        let r = run(&u, sim, &[m], n, Seed(9), &d).unwrap();
        let diff = r.mismatch.expect("the bug is caught");
        // The first cycle after reset whose previous input was not a bypass shows it in u0.
        let stim = u.stimulus(Seed(9), n);
        let want = (verif::cosim::RESET_CYCLES..n)
            .find(|&c| stim[c - 1][1] == 0 && c > verif::cosim::RESET_CYCLES)
            .unwrap();
        assert_eq!(
            (diff.cycle, diff.port.as_str()),
            (want, "u0"),
            "{}: {diff}",
            sim.name()
        );
        let _ = std::fs::remove_dir_all(&d);
        // The register stage removed: the twin answers in the same cycle.
        let d = dir(&format!("bug-reg-{}", sim.name()));
        let m = mutant(
            &d,
            "bump/blend_adjust_153.v",
            "if (REGISTERED != 0) begin : g_reg",
            "if (0) begin : g_reg",
        );
        let r = run(&u, sim, &[m], n, Seed(9), &d).unwrap();
        let diff = r.mismatch.expect("the bug is caught");
        let want = first_difference(params(8, true), params(8, false), n);
        assert_eq!(
            (diff.cycle, diff.port.clone()),
            want,
            "{}: {diff}",
            sim.name()
        );
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// `verilator --lint-only -Wall` is clean on every twin, in every configuration the
/// co-simulation covers (its Verilog parameters as `-G` overrides).
#[test]
fn every_twin_is_lint_clean() {
    if !available(Simulator::Verilator) {
        return;
    }
    for (label, u) in twins() {
        let mut cmd = std::process::Command::new("verilator");
        cmd.args(["--lint-only", "-Wall", "--top-module", u.top()]);
        for (k, v) in u.parameters() {
            cmd.arg(format!("-G{k}={v}"));
        }
        for f in u.rtl().into_iter().chain(u.bench_rtl()) {
            cmd.arg(f);
        }
        let o = cmd.output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            o.status.success() && err.trim().is_empty(),
            "{label}: {err}"
        );
    }
}

/// Address unit 150 with its colour-mode half texel turned into a quarter (a shift constant
/// off by one): reported at the first cycle whose registered result differs, on the first
/// port that differs, as the model's own `split` predicts.
#[test]
fn address_bug_is_caught_with_its_cycle_and_port() {
    use units::bump::address_150::AddressUnit;
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !available(sim) {
            continue;
        }
        let u = AddressCosim::default();
        let n = 2_000;
        let d = dir(&format!("bug-address-{}", sim.name()));
        let m = mutant(
            &d,
            "bump/address_150.v",
            "<< (POS_FRAC - 1)",
            "<< (POS_FRAC - 2)",
        );
        let r = run(&u, sim, &[m], n, Seed(4), &d).unwrap();
        let diff = r.mismatch.expect("the bug is caught");
        let model = AddressUnit::new("a", hdl::fx::Format::signed(24, 8), 8).unwrap();
        let raw = |b: u64| ((b << 40) as i64) >> 40;
        let stim = u.stimulus(Seed(4), n);
        let want = (verif::cosim::RESET_CYCLES + 1..n)
            .find_map(|c| {
                let s = &stim[c - 1];
                let colour = s[2] == 1;
                let quarter = if colour { 1 << 6 } else { 0 };
                let (ui, ub) = model.split(raw(s[0]), colour);
                let (vj, vb) = model.split(raw(s[1]), colour);
                let (ui2, ub2) = model.split(raw(s[0]) + quarter, colour);
                let (vj2, vb2) = model.split(raw(s[1]) + quarter, colour);
                let ports = [
                    (ui != ui2, "ui"),
                    (vj != vj2, "vj"),
                    (ub != ub2, "ub"),
                    (vb != vb2, "vb"),
                ];
                ports.iter().find(|p| p.0).map(|p| (c, p.1))
            })
            .unwrap();
        assert_eq!(
            (diff.cycle, diff.port.as_str()),
            want,
            "{}: {diff}",
            sim.name()
        );
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// Replicate unit 152 with one texel scaled by 2 instead of 4: reported in cycle 1 (the first
/// compared; the unit is combinational) on the first port that carries it, red's `r00`.
#[test]
fn replicate_bug_is_caught_with_its_cycle_and_port() {
    let u = ReplicateCosim {
        texel_bits: 8,
        bezier: false,
    };
    let bug = Bug(
        "bump/replicate_152.v",
        "assign pa = xa << 2;",
        "assign pa = xa << 1;",
    );
    // Cycle 1's `a` is never 0 with this seed, so r00 differs there (checked here).
    assert_ne!(u.stimulus(Seed(6), 500)[1][0], 0);
    assert_caught(&u, bug, 500, Seed(6), (1, "r00"));
}

/// A bilinear unit that rounds half away from zero instead of half to even: caught at the
/// first cycle whose registered result has a dropped half exactly and an even quotient, on
/// port `q`, as the model's own arithmetic predicts.
#[test]
fn bilinear_rounding_bug_is_caught_with_its_cycle_and_port() {
    use units::bump::bilinear_65_68::Bilinear;
    // 4-bit texels (uQ3.3 out of 152), F = 4 (factors uQ0.5): exact fraction 13, rounded
    // to 12: a dropped half is common.
    let u = BilinearCosim {
        texel_bits: 4,
        blend_bits: 4,
        bilinear_frac: Some(12),
    };
    let n = 4_000;
    let bug = Bug(
        "bump/bilinear_65_68.v",
        "(rem == half && fl[0])",
        "(rem == half)",
    );
    let stim = u.stimulus(Seed(12), n);
    let want = (verif::cosim::RESET_CYCLES + 1..n)
        .find(|&c| {
            let v = &stim[c - 1];
            let p = [v[0], v[1], v[2], v[3]].map(|x| x as i64);
            // Exact fraction 3 + 2 * 5 = 13: one dropped bit.
            let x = Bilinear::exact(p, v[4] as i64, v[5] as i64, 5);
            x & 1 == 1 && (x >> 1) & 1 == 0
        })
        .unwrap();
    assert_caught(&u, bug, n, Seed(12), (want, "q"));
}

/// Whether rounding `x` (`sh` dropped bits, `sh > 0`) half to even and half up differ: the
/// dropped bits are exactly one half and the kept part is even.
fn tie_to_even(x: i128, sh: u32) -> bool {
    x & ((1 << sh) - 1) == 1 << (sh - 1) && (x >> sh) & 1 == 0
}

/// Tangent unit 155 with its ties rounded up instead of to even (the rounding mode swapped):
/// reported at the first cycle whose registered du, dv or height had an exact tie on an even
/// value, on the first such port, computed here from the unit's equations.
#[test]
fn tangent_rounding_bug_is_caught_with_its_cycle_and_port() {
    // 4-bit texels, F = 4, bilinear uQ3.3, scale uQ2.5, tangents .8: du, dv drop
    // 3 + 4 - 1 + 5 - 8 = 3 bits, the height 3 + 8 + 5 - 8 = 8.
    let p = BumpParams {
        height: HeightTexel::Bits4,
        blend_bits: 4,
        bilinear_frac: Some(3),
        scale_int: 2,
        scale_frac: 5,
        tangent_frac: 8,
        ..BumpParams::default()
    };
    let u = TangentCosim(p);
    let n = 2_000;
    let bug = Bug(
        "bump/tangent_155.v",
        "(rem == half && fl[0])",
        "(rem == half)",
    );
    let stim = u.stimulus(Seed(155), n);
    let want = (verif::cosim::RESET_CYCLES + 1..n)
        .find_map(|c| {
            let v: Vec<i128> = stim[c - 1].iter().map(|&x| i128::from(x)).collect();
            let [r, g, b, a, tu, tv, s] = [v[0], v[1], v[2], v[3], v[4], v[5], v[6]];
            let lerp = |x: i128, y: i128, t: i128| (x << 4) + t * (y - x);
            let du = lerp(g - r, a - b, tv) * s;
            let dv = lerp(b - r, a - g, tu) * s;
            let h = lerp(lerp(r, g, tu), lerp(b, a, tu), tv) * s;
            [("du", du, 3), ("dv", dv, 3), ("height", h, 8)]
                .into_iter()
                .find(|&(_, x, sh)| tie_to_even(x, sh))
                .map(|(port, _, _)| (c, port))
        })
        .unwrap();
    assert_caught(&u, bug, n, Seed(155), want);
}

/// The rsqrt unit of 156 with its table entries truncated instead of rounded (`(z + 1) >> 1`
/// become `z >> 1`): with the table alone (no iteration) reported at the first cycle whose
/// registered mantissa is at least 1 and indexes an entry whose doubled root `z` is odd.
#[test]
fn rsqrt_table_bug_is_caught_with_its_cycle_and_port() {
    use units::bump::rsqrt_156::RsqrtTable;
    let p = RsqrtParams {
        table_bits: 4,
        iterations: 0,
        mant_frac: 16,
        y_frac: 16,
    };
    let u = RsqrtCosim(p);
    let n = 2_000;
    let bug = Bug("bump/rsqrt_156.v", "r = (z + 1) >> 1;", "r = z >> 1;");
    let stim = u.stimulus(Seed(156), n);
    let table = RsqrtTable::new(p).unwrap();
    // z = floor(2 / sqrt(midpoint)) in units of 2^-Y, from the entry's interval.
    let z_odd = |idx: usize| {
        let lo_bits = p.table_bits - 1;
        let (hi, lo) = (idx as u32 >> lo_bits, idx as u128 & ((1 << lo_bits) - 1));
        let shift = p.mant_frac + hi - lo_bits;
        let mid2 = (((1u128 << lo_bits) | lo) << (shift + 1)) + (1u128 << shift);
        let z = ((1u128 << (2 * p.y_frac + p.mant_frac + 3)) / mid2).isqrt();
        z & 1 == 1
    };
    let want = (verif::cosim::RESET_CYCLES + 1..n)
        .find(|&c| {
            let m = stim[c - 1][0];
            m >> p.mant_frac != 0 && z_odd(table.index(m))
        })
        .unwrap();
    assert_caught(&u, bug, n, Seed(156), (want, "y"));
}

/// Normal unit 156 with its ties rounded up instead of to even in the multiply stage:
/// reported at the first cycle whose nx, ny or nz product had an exact tie on an even value
/// (first such port), found from the unit's equations with the model's own table and steps.
#[test]
fn normal_rounding_bug_is_caught_with_its_cycle_and_port() {
    use units::bump::normal_156::normalise;
    use units::bump::rsqrt_156::{rsqrt, RsqrtTable};
    // sQ.8 tangents, uQ1.8 iterates, sQ2.14 out: 8 + 8 + k - 14 = 2 + k dropped bits.
    let p = BumpParams {
        tangent_frac: 8,
        out_frac: 14,
        rsqrt: RsqrtParams {
            table_bits: 6,
            iterations: 1,
            mant_frac: 8,
            y_frac: 8,
        },
        ..BumpParams::default()
    };
    let u = NormalCosim(p);
    let n = 3_000;
    let bug = Bug(
        "bump/normal_156.v",
        "(rem == half && fl[0])",
        "(rem == half)",
    );
    let stim = u.stimulus(Seed(156), n);
    let table = RsqrtTable::new(p.rsqrt).unwrap();
    let w = p.tangent_fmt().width();
    let signed = |x: u64| ((x << (64 - w)) as i64) >> (64 - w);
    let latency = 3 + p.rsqrt.iterations as usize;
    let want = (verif::cosim::RESET_CYCLES + latency..n)
        .find_map(|c| {
            let (du, dv) = (signed(stim[c - latency][0]), signed(stim[c - latency][1]));
            let s = (du * du + dv * dv) as u128 + (1 << 16);
            let (k, mant) = normalise(s, 16, 8);
            let y = rsqrt(&table, mant) as i128;
            [("nx", -du), ("ny", -dv), ("nz", 1 << 8)]
                .into_iter()
                .find(|&(_, x)| tie_to_even(i128::from(x) * y, 2 + k))
                .map(|(port, _)| (c, port))
        })
        .unwrap();
    assert_caught(&u, bug, n, Seed(156), want);
}

/// Where Yosys is installed, every twin synthesises (`rtl/synth`, generic cells) and the
/// B-spline replicate unit is pure wiring, as para. 0056 says.
#[test]
#[ignore = "slow (about 2 minutes): cargo test -- --ignored, as .ci/run does"]
fn every_twin_synthesises_where_yosys_is_present() {
    if std::process::Command::new("yosys")
        .arg("-V")
        .output()
        .is_err()
    {
        println!("synthesis skipped: yosys not found (Debian: apt-get install yosys)");
        return;
    }
    let o = std::process::Command::new(tb::cosim::rtl_dir().join("synth"))
        .output()
        .unwrap();
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{table}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for u in tb::project::project().twins().map(|t| t.name().to_string()) {
        assert!(
            table.contains(&format!("| {u} |")),
            "{u} not synthesised: {table}"
        );
    }
    assert!(
        table.contains("| replicate_152 | 8-bit texels, B-spline (default) | 0 | 0 | 0 |"),
        "{table}"
    );
}

/// Texel fetch unit 151 whose wrap mode adds `n - 1` instead of `n` to a negative remainder
/// (a constant changed): caught at the first cycle whose registered 3x3 grid reads a
/// different texel, on the first such port (a..k), as the border arithmetic predicts.
#[test]
fn texel_fetch_wrap_bug_is_caught_with_its_cycle_and_port() {
    const NAMES: [&str; 9] = ["a", "b", "c", "d", "e", "f", "g", "h", "k"];
    let u = TexelFetchCosim::new(BumpParams::default(), 16, 16, 1);
    let bug = Bug(
        "bump/texel_fetch_151.v",
        "(rn < 0) ? rn + SN : rn",
        "(rn < 0) ? rn + SN - 1 : rn",
    );
    let (n, seed) = (2_000, Seed(15));
    let stim = u.stimulus(seed, n);
    let coord = |x: u64| ((x << 47) as i64) >> 47;
    let wrap = |i: i64, n: u32| i.rem_euclid(i64::from(n)) as u32;
    let bugged = |i: i64, n: u32| {
        let r = i % i64::from(n);
        (if r < 0 { r + i64::from(n) - 1 } else { r }) as u32
    };
    let grid = |ui: i64, vj: i64, idx: &dyn Fn(i64, u32) -> u32| -> Vec<u8> {
        (0..9)
            .map(|k| {
                let (x, y) = (ui + k % 3 - 1, vj + k / 3 - 1);
                u.map.get(idx(x, 16), idx(y, 16))
            })
            .collect()
    };
    // The grid registered at the end of cycle c - 1 shows in cycle c.
    let want = (verif::cosim::RESET_CYCLES + 1..n)
        .find_map(|c| {
            let (ui, vj) = (coord(stim[c - 1][0]), coord(stim[c - 1][1]));
            let (good, bad) = (grid(ui, vj, &wrap), grid(ui, vj, &bugged));
            (0..9).find(|&k| good[k] != bad[k]).map(|k| (c, NAMES[k]))
        })
        .expect("the stimulus reaches a negative coordinate");
    assert_caught(&u, bug, n, seed, want);
}

/// The FIG. 7 pipeline with one register stage removed from its valid delay line: `valid`
/// runs a cycle ahead of the data; caught at the first cycle where the valid input one cycle
/// later differs from the one it should show, on port `valid`.
#[test]
fn pipeline_valid_stage_bug_is_caught_with_its_cycle_and_port() {
    let u = PipelineCosim::new(BumpParams::default(), 16, 16, 11);
    let bug = Bug(
        "bump/normal_pipeline_fig7.v",
        ".DEPTH(4 + NORMAL_LATENCY)) valid_carry",
        ".DEPTH(3 + NORMAL_LATENCY)) valid_carry",
    );
    let (n, seed) = (500, Seed(16));
    let stim = u.stimulus(seed, n);
    // valid(c) is valid_in(c - depth) once that input was out of reset, else 0.
    let valid = |c: usize, depth: usize| match c.checked_sub(depth) {
        Some(i) if i >= verif::cosim::RESET_CYCLES => stim[i][0],
        _ => 0,
    };
    let latency = 4 + 3 + BumpParams::default().rsqrt.iterations as usize;
    let want = (verif::cosim::FIRST_COMPARED..n)
        .find(|&c| valid(c, latency) != valid(c, latency - 1))
        .expect("valid toggles");
    assert_caught(&u, bug, n, seed, (want, "valid"));
}

/// Control unit 607 that leaves RAS# precharge a cycle early (a constant changed): caught on
/// pin `ras_n` in the last cycle of the first precharge the model makes, and the behavioural
/// DRAM's timing check counts the short precharge (its `violations` port ends above zero,
/// while the model's DRAM, driven correctly, counts none).
#[test]
fn control_precharge_bug_is_caught_with_its_cycle_port_and_timing_check() {
    let u = ControlCosim(DramParams::default());
    let bug = Bug(
        "texmem/control_607.v",
        "PRECHARGE: if (count >= 11'(T_RP))",
        "PRECHARGE: if (count >= 11'(T_RP - 1))",
    );
    let (n, seed) = (400, Seed(17));
    let stim = u.stimulus(seed, n);
    let mut m = u.model().unwrap();
    let (_, outs) = m.ports();
    let k = outs.iter().position(|p| p.name == "ras_n").unwrap();
    let ras: Vec<u64> = (0..n)
        .map(|c| m.cycle(c < verif::cosim::RESET_CYCLES, &stim[c])[k])
        .collect();
    // RAS# falls only when a precharge ends: its last cycle is the one before.
    let want = (verif::cosim::FIRST_COMPARED..n - 1)
        .find(|&c| ras[c] == 1 && ras[c + 1] == 0)
        .expect("the stimulus opens a row");
    assert_caught(&u, bug, n, seed, (want, "ras_n"));
    // The DRAM's own check, read from the RTL's outputs.
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !available(sim) {
            continue;
        }
        let d = dir(&format!("bug-607-timing-{}", sim.name()));
        // The wrapper and the behavioural DRAM come with the unit, as for `--rtl`.
        let sources = vec![mutant(&d, bug.0, bug.1, bug.2)];
        let r = run(&u, sim, &sources, n, seed, &d).unwrap();
        assert!(r.mismatch.is_some());
        let out = std::fs::read_to_string(d.join("rtl_out.hex")).unwrap();
        let last = out
            .lines()
            .last()
            .unwrap()
            .split_whitespace()
            .last()
            .unwrap();
        let violations = u64::from_str_radix(last, 16).unwrap();
        let _ = std::fs::remove_dir_all(&d);
        assert!(
            violations > 0,
            "{}: the DRAM counted no violation",
            sim.name()
        );
    }
}

/// Cache 614 whose touch sets the `prefetched` bit instead of clearing it (a constant
/// changed): caught on port `prefetched` in the first cycle after an entry is touched without
/// being written.
#[test]
fn cache_touch_bug_is_caught_with_its_cycle_and_port() {
    let u = CacheCosim { tag_bits: 9 };
    let bug = Bug(
        "texmem/cache_614.v",
        "if (touch[k]) prefetched[k] <= 1'b0;",
        "if (touch[k]) prefetched[k] <= 1'b1;",
    );
    let (n, seed) = (300, Seed(18));
    let stim = u.stimulus(seed, n);
    // Inputs: touch, invalidate, write, write_bx, write_by, ...
    let written = |s: &[u64]| (s[2] == 1).then_some((s[3] & 1 | (s[4] & 1) << 1) as usize);
    let want = (verif::cosim::RESET_CYCLES + 1..n)
        .find(|&c| {
            let s = &stim[c - 1];
            (0..4).any(|k| s[0] >> k & 1 == 1 && written(s) != Some(k))
        })
        .expect("an entry is touched");
    assert_caught(&u, bug, n, seed, (want, "prefetched"));
}

/// The lookahead queue taking a candidate while it is being flushed (the flush dropped from
/// the take condition): caught on port `take` in the first cycle that flushes a queue the
/// fill engine could otherwise have taken from (the model, run with that cycle's flush off,
/// says when).
#[test]
fn lookahead_flush_bug_is_caught_with_its_cycle_and_port() {
    use units::texmem::control_607::LookaheadQueue;
    let u = LookaheadCosim {
        mode: Lookahead::Quadrant,
        blocks: (16, 16),
        frac_bits: 4,
    };
    let bug = Bug(
        "texmem/lookahead_queue_607.v",
        "assign take = !flush && engine_free",
        "assign take = engine_free",
    );
    let (n, seed) = (2_000, Seed(19));
    let stim = u.stimulus(seed, n);
    let uq = hdl::fx::Format::unsigned(16, 4);
    let dut = LookaheadQueue::new(Lookahead::Quadrant, (16, 16), uq, 10);
    let flushes_a_take = |d: &LookaheadQueue, s: &[u64]| {
        let mut without = d.clone();
        without.flush.set_bits(0);
        without.eval();
        s[4] == 1 && without.take.is_high()
    };
    let want = first_cycle(dut, &stim, tb::cosim::drive_lookahead, flushes_a_take)
        .expect("a flush meets a non-empty queue");
    assert_caught(&u, bug, n, seed, (want, "take"));
}

/// The first cycle from [`verif::cosim::FIRST_COMPARED`] at which `hit` holds for the model
/// `dut` driven with `stim` by `drive` (looked at with the cycle's inputs driven, before its
/// `eval`; reset as the harness applies it).
fn first_cycle<M: hdl::kernel::Module>(
    dut: M,
    stim: &[Vec<u64>],
    drive: fn(&mut M, &[u64]),
    hit: impl Fn(&M, &[u64]) -> bool,
) -> Option<usize> {
    let mut sim = hdl::kernel::Sim::new(dut);
    for (c, s) in stim.iter().enumerate() {
        sim.set_reset(c < verif::cosim::RESET_CYCLES);
        drive(&mut sim.dut, s);
        if c >= verif::cosim::FIRST_COMPARED && hit(&sim.dut, s) {
            return Some(c);
        }
        sim.eval();
        sim.tick();
    }
    None
}

/// The block fetch forgetting that a block is two words in the tiled layout (the offset inside
/// a tile not doubled): caught on port `word_addr` in the first cycle it asks for a word of a
/// block that is not the first of its tile.
#[test]
fn fill_tiled_address_bug_is_caught_with_its_cycle_and_port() {
    use units::texmem::control_607::FillEngine;
    use units::texmem::layout::BlockMap;
    let u = FillCosim {
        layout: Layout::Tiled,
        blocks: (40, 24),
        base: 4096,
        dram: DramParams::default(),
    };
    let bug = Bug(
        "texmem/fill_engine_607.v",
        "ty * AB'(TILES_X) + tx) + (inner << 1);",
        "ty * AB'(TILES_X) + tx) + inner;",
    );
    let (n, seed) = (500, Seed(20));
    let stim = u.stimulus(seed, n);
    let map = BlockMap::new(Layout::Tiled, 40, 24, 512, 4096);
    let (tw, th) = map.tile();
    let dut = FillEngine::new(map, 10, hdl::fx::Format::uint(18));
    let inside_a_tile = |d: &FillEngine, _: &[u64]| {
        let (bx, by, _) = d.block();
        d.word_request().is_some() && (by % th) * tw + bx % tw != 0
    };
    let want = first_cycle(dut, &stim, tb::cosim::drive_fill, inside_a_tile)
        .expect("a block inside a tile is fetched");
    assert_caught(&u, bug, n, seed, (want, "word_addr"));
}

/// Mipmap generator 816 whose level adders round a sum of four with +1 instead of +2 (a
/// constant changed): caught on port `l1_texel` one cycle after the first 2x2 block whose sum
/// is 2 modulo 4 is completed (its odd texel of its odd line).
#[test]
fn mipmap_rounding_bug_is_caught_with_its_cycle_and_port() {
    let (w, h) = (16usize, 16usize);
    let u = MipmapCosim::new(MipmapParams {
        width: w as u32,
        height: h as u32,
        scan: Scan::Progressive,
        rounding: Rounding::Round,
    });
    let bug = Bug(
        "mipmap/level_fig14.v",
        "(ROUND != 0) ? 10'd2 : 10'd0",
        "(ROUND != 0) ? 10'd1 : 10'd0",
    );
    let (n, seed) = (2_000, Seed(21));
    let stim = u.stimulus(seed, n);
    let mut sums = vec![0u64; (w / 2) * (h / 2)];
    let mut pos = 0usize;
    let mut want = None;
    for (c, s) in stim.iter().enumerate() {
        if s[0] == 0 {
            continue;
        }
        let (x, y) = (pos % w, pos / w % h);
        pos += 1;
        let b = (y / 2) * (w / 2) + x / 2;
        sums[b] += s[1];
        if x % 2 == 1 && y % 2 == 1 {
            if sums[b] % 4 == 2 {
                want = Some(c + 1);
                break;
            }
            sums[b] = 0;
        }
    }
    let want = want.expect("a block sums to 2 modulo 4");
    assert_caught(&u, bug, n, seed, (want, "l1_texel"));
}

/// The regression vectors' transactions, in their configurations, agree on every port of
/// every cycle in every simulator installed.
#[test]
fn regression_vectors_cosimulate_equal() {
    for sim in [Simulator::Verilator, Simulator::Icarus] {
        if !available(sim) {
            continue;
        }
        let project = tb::project::project();
        let directed = project
            .units()
            .filter_map(|u| Some((u.name(), u.directed_runs()?)));
        for (u, runs) in directed {
            for d in runs().unwrap() {
                let dir = dir(&format!("vectors-{u}-{}-{}", d.label, sim.name()));
                let r =
                    verif::cosim::run_with(d.unit.as_ref(), sim, &[], &d.stimulus, &dir).unwrap();
                let _ = std::fs::remove_dir_all(&dir);
                assert!(
                    r.mismatch.is_none(),
                    "{u} {} in {}: {}",
                    d.label,
                    sim.name(),
                    r.mismatch.unwrap()
                );
                assert_eq!(r.cycles, d.stimulus.len());
            }
        }
    }
}

/// Texture unit 602 whose bilinear interpolator 622 rounds with a quarter instead of a half
/// (a shift constant off by one): caught on port `out_rgb` in the first cycle that shows a
/// colour whose exact sums (the model's `sums` registers) round differently.
#[test]
fn texture_rounding_bug_is_caught_with_its_cycle_and_port() {
    use units::texmem::texture_unit_602::TextureUnit;
    let p = TexParams::new(64, 64);
    let u = TextureCosim(p);
    let bug = Bug(
        "texmem/bilinear_622.v",
        "SW'(1) << (2 * F - 1)",
        "SW'(1) << (2 * F - 2)",
    );
    let (n, seed) = (3_000, Seed(21));
    let stim = u.stimulus(seed, n);
    let dut = TextureUnit::new("t", p, &TextureCosim::clut(), &[]).unwrap();
    let f2 = 2 * p.frac_bits;
    let rounds_apart = |d: &TextureUnit, _: &[u64]| {
        let b = &d.bilinear;
        let round = |s: u64, half: u64| (s + half) >> f2;
        b.valid.q().is_high()
            && b.sums.iter().any(|s| {
                let s = s.q().bits();
                round(s, 1 << (f2 - 1)) != round(s, 1 << (f2 - 2))
            })
    };
    let want = first_cycle(dut, &stim, tb::cosim::drive_texture, rounds_apart)
        .expect("a colour rounds differently");
    assert_caught(&u, bug, n, seed, (want, "out_rgb"));
}

/// Texture unit 602 whose footprint forgets the clamp at the texture's right edge (x1 =
/// x0 + 1 always): caught in the first cycle stage 0 holds a request in the last column, on
/// `in_ready` when the model completes it that cycle (the twin waits for a block beyond the
/// edge), else on `need_mask` (the twin needs that block's entry too).
#[test]
fn texture_edge_clamp_bug_is_caught_with_its_cycle_and_port() {
    use units::texmem::texture_unit_602::TextureUnit;
    let p = TexParams::new(64, 64);
    let u = TextureCosim(p);
    let bug = Bug(
        "texmem/texture_unit_602.v",
        "wire [11:0] x1 = ({1'b0, x0} + 13'd1 > 13'(W - 1)) ? 12'(W - 1) : x0 + 12'd1;",
        "wire [11:0] x1 = x0 + 12'd1;",
    );
    let (n, seed) = (20_000, Seed(22));
    let stim = u.stimulus(seed, n);
    let dut = TextureUnit::new("t", p, &TextureCosim::clut(), &[]).unwrap();
    let at_edge = |d: &TextureUnit, _: &[u64]| {
        d.req_valid.q().is_high() && d.req_u.q().bits() >> p.frac_bits == u64::from(p.width - 1)
    };
    let want = first_cycle(dut.clone(), &stim, tb::cosim::drive_texture, at_edge)
        .expect("a request in the last column");
    // The model at that cycle: does it complete the request?
    let mut sim = hdl::kernel::Sim::new(dut);
    for (c, s) in stim.iter().enumerate().take(want + 1) {
        sim.set_reset(c < verif::cosim::RESET_CYCLES);
        tb::cosim::drive_texture(&mut sim.dut, s);
        sim.eval();
        if c < want {
            sim.tick();
        }
    }
    let port = if sim.dut.in_ready.is_high() {
        "in_ready"
    } else {
        "need_mask"
    };
    assert_caught(&u, bug, n, seed, (want, port));
}

/// The TEXRAM chip whose page registers 824 charge a miss no second slot: caught on port
/// `slots` in the first cycle after an access that missed an open row moved into the banks.
#[test]
fn texram_fault_slot_bug_is_caught_with_its_cycle_and_port() {
    use units::texram::texram_802::Texram802;
    let u = TexramCosim { slot_cycles: 6 };
    let bug = Bug(
        "texram/page_registers_824.v",
        "slots = slots + ((faults != 4'd0) ? 4'd2 : 4'd1);",
        "slots = slots + 4'd1;",
    );
    let (n, seed) = (3_000, Seed(23));
    let stim = u.stimulus(seed, n);
    let faulted = |d: &Texram802, _: &[u64]| d.faults.q().bits() > 0;
    let dut = u.chip().unwrap();
    let want = first_cycle(dut, &stim, tb::cosim::drive_texram, faulted).expect("a page fault");
    assert_caught(&u, bug, n, seed, (want, "slots"));
}

/// The TEXRAM chip whose banks hold an access one cycle short of its slots (SLOT_CYCLES - 1):
/// caught where the model with slots of 5 cycles first differs from the model with 6.
#[test]
fn texram_slot_length_bug_is_caught_with_its_cycle_and_port() {
    let u = TexramCosim { slot_cycles: 6 };
    let bug = Bug(
        "texram/texram_802.v",
        ".in_left(8'(cost_slots * 4'(SLOT_CYCLES)))",
        ".in_left(8'(cost_slots * 4'(SLOT_CYCLES - 1)))",
    );
    let (n, seed) = (3_000, Seed(24));
    let short = TexramCosim { slot_cycles: 5 };
    let want = models_differ(&u, &short, seed, n);
    assert_caught(&u, bug, n, seed, (want.0, want.1.as_str()));
}

/// The walker that defers a texture's read for the detail at every level, not only below
/// level 0 (`below0` lost): caught on port `acc_drf` in the first cycle the model reads
/// texture DRF 0, which links to offsets, at a lambda of 0 or more (the mutant goes on to the
/// reflectance instead).
#[test]
fn walker_deferral_bug_is_caught_with_its_cycle_and_port() {
    let u = WalkerCosim { slot_cycles: 6 };
    let bug = Bug(
        "mapchain/walker_812.v",
        "ws_deferred = below0 && d_linked(k)",
        "ws_deferred = d_linked(k)",
    );
    let (n, seed) = (3_000, Seed(25));
    let stim = u.stimulus(seed, n);
    let file = WalkerCosim::file();
    let dut = units::mapchain::walker_812::MapChain812::new(file, Default::default(), 6).unwrap();
    let mut sim = hdl::kernel::Sim::new(dut);
    let mut want = None;
    for (c, s) in stim.iter().enumerate() {
        sim.set_reset(c < verif::cosim::RESET_CYCLES);
        tb::cosim::drive_walker(&mut sim.dut, s);
        sim.eval();
        let a = &sim.dut.banks.acc;
        let texture_at_lambda_0_up = a.valid.is_high() && a.drf.bits() == 0 && a.lambda.raw() >= 0;
        if c >= verif::cosim::FIRST_COMPARED && texture_at_lambda_0_up {
            want = Some(c);
            break;
        }
        sim.tick();
    }
    let want = want.expect("a texture read at lambda >= 0");
    assert_caught(&u, bug, n, seed, (want, "acc_drf"));
}

/// The walker holding an access one cycle short of its slots (SLOT_CYCLES - 1): caught where
/// the model with slots of 5 cycles first differs from the model with 6.
#[test]
fn walker_slot_length_bug_is_caught_with_its_cycle_and_port() {
    let u = WalkerCosim { slot_cycles: 6 };
    let bug = Bug(
        "mapchain/walker_812.v",
        "{30'd0, rd_slots} * SLOT_CYCLES",
        "{30'd0, rd_slots} * (SLOT_CYCLES - 1)",
    );
    let (n, seed) = (3_000, Seed(26));
    let short = WalkerCosim { slot_cycles: 5 };
    let want = models_differ(&u, &short, seed, n);
    assert_caught(&u, bug, n, seed, (want.0, want.1.as_str()));
}
