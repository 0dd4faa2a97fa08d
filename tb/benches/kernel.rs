//! Speed of the RTL kernel and the fixed-point layer (criterion). Run with
//! `cargo bench -p texrtl-tb --bench kernel`; figures are recorded in the user guide (docs/guide/speed.md).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hdl::fx::{Format, Fx, Overflow, Quant};
use hdl::kernel::{Reg, Sim, Trace};
use std::hint::black_box;
use tb::maps::builtin;
use tb::mipmap::synthetic_video;
use units::bump::blend_adjust_153::{BlendAdjust, BlendAdjustParams};
use units::bump::normal_pipeline_fig7::NormalPipeline;
use units::bump::params::BumpParams;
use units::bump::replicate_152::Replicate;
use units::mipmap::{MipmapGen, MipmapParams, Rounding, Scan};
use verif::Seed;
use waves::{FstTracer, TraceConfig, VcdTracer};

const CYCLES: u64 = 4096;

fn drive<T: Trace>(sim: &mut Sim<BlendAdjust, T>) -> u64 {
    let mut acc = 0;
    for c in 0..CYCLES {
        sim.dut.i.valid_in.set_bool(true);
        sim.dut.i.u_in.set_bits(c & 0xff);
        sim.dut.i.v_in.set_bits((c * 7) & 0xff);
        sim.dut.i.bypass.set_bool(c & 0x100 != 0);
        sim.eval();
        acc += sim.dut.o.u0.bits();
        sim.tick();
    }
    acc
}

fn kernel(c: &mut Criterion) {
    let mut g = c.benchmark_group("kernel");
    g.throughput(Throughput::Elements(CYCLES));
    g.bench_function("blend_adjust_cycles_untraced", |b| {
        let mut sim =
            Sim::new(BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap());
        b.iter(|| black_box(drive(&mut sim)))
    });
    g.bench_function("blend_adjust_cycles_schedule_checked", |b| {
        let mut sim =
            Sim::new(BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap())
                .check_schedule(true);
        b.iter(|| black_box(drive(&mut sim)))
    });
    let dir = std::env::temp_dir().join(format!("texrtl-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("ba.vcd");
    g.bench_function("blend_adjust_cycles_traced_vcd", |b| {
        b.iter_batched(
            || {
                let t = VcdTracer::create(&path, "bench", TraceConfig::default()).unwrap();
                Sim::traced(
                    BlendAdjust::new("blend_adjust_153", BlendAdjustParams::default()).unwrap(),
                    t,
                )
                .unwrap()
            },
            |mut sim| {
                let a = drive(&mut sim);
                sim.finish().unwrap();
                black_box(a)
            },
            BatchSize::PerIteration,
        )
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

/// The clock edge's cost per register: 70 registers (about unit 602's count) committed as the
/// kernel commits them, a load and a store each wherever the registers lie; and, for scale, the
/// same 70 words copied from one array into another in one block.
fn edge(c: &mut Criterion) {
    const N: usize = 70;
    let mut g = c.benchmark_group("edge");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("commit_70_registers", |b| {
        let mut regs: Vec<Reg> = (0..N).map(|_| Reg::new("r", Format::uint(16))).collect();
        b.iter(|| {
            for r in regs.iter_mut() {
                r.tick(false);
            }
            black_box(&mut regs);
        })
    });
    g.bench_function("copy_70_words", |b| {
        let (mut q, d) = ([0u64; N], [1u64; N]);
        b.iter(|| {
            q.copy_from_slice(black_box(&d));
            black_box(&mut q);
        })
    });
    g.finish();
}

fn fixed_point(c: &mut Criterion) {
    let mut g = c.benchmark_group("fx");
    let src = Format::signed(24, 16);
    let dst = Format::signed(12, 6);
    let xs: Vec<Fx> = (0..1024)
        .map(|i| Fx::from_raw(src, (i * 7919 - 4_000_000) % (1 << 23)))
        .collect();
    g.throughput(Throughput::Elements(xs.len() as u64));
    g.bench_function("convert_round_half_even_saturate", |b| {
        b.iter(|| {
            let mut s = 0i128;
            for x in &xs {
                s += x
                    .convert(dst, Quant::RoundHalfEven, Overflow::Saturate)
                    .raw();
            }
            black_box(s)
        })
    });
    g.bench_function("mul_add_full_precision", |b| {
        b.iter(|| {
            let mut s = 0i128;
            for w in xs.windows(2) {
                s += (w[0] * w[1] + w[0]).raw();
            }
            black_box(s)
        })
    });
    g.finish();
}

fn pipeline<T: Trace>(sim: &mut Sim<NormalPipeline, T>) -> u64 {
    tb::runs::normals::bench_cycles(sim, CYCLES)
}

fn normal_pipeline(c: &mut Criterion) {
    let p = BumpParams::default();
    let map = builtin("noise", 16, 16, p.texel_fmt()).unwrap();
    let mut g = c.benchmark_group("normal_pipeline");
    g.throughput(Throughput::Elements(CYCLES));
    g.bench_function("cycles_untraced", |b| {
        let mut sim =
            Sim::new(NormalPipeline::new("normal_pipeline_fig7", p, map.clone(), None).unwrap());
        b.iter(|| black_box(pipeline(&mut sim)))
    });
    // Numeric tracking on: every named narrowing counts what it meets (against
    // `cycles_untraced`, tracking off, the cost of numeric coverage).
    g.bench_function("cycles_untraced_numeric_tracking", |b| {
        let mut sim =
            Sim::new(NormalPipeline::new("normal_pipeline_fig7", p, map.clone(), None).unwrap());
        hdl::fx::set_tracking(true);
        b.iter(|| black_box(pipeline(&mut sim)));
        hdl::fx::set_tracking(false);
    });
    let tri = BumpParams {
        trilinear: true,
        ..p
    };
    g.bench_function("cycles_untraced_trilinear", |b| {
        let mut sim = Sim::new(
            NormalPipeline::new(
                "normal_pipeline_fig7",
                tri,
                map.clone(),
                Some(map.downsample()),
            )
            .unwrap(),
        );
        b.iter(|| black_box(pipeline(&mut sim)))
    });
    let dir = std::env::temp_dir().join(format!("texrtl-bench-p-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("pipe.vcd");
    g.bench_function("cycles_traced_vcd", |b| {
        b.iter_batched(
            || {
                let t = VcdTracer::create(&path, "bench", TraceConfig::default()).unwrap();
                Sim::traced(
                    NormalPipeline::new("normal_pipeline_fig7", p, map.clone(), None).unwrap(),
                    t,
                )
                .unwrap()
            },
            |mut sim| {
                let a = pipeline(&mut sim);
                sim.finish().unwrap();
                black_box(a)
            },
            BatchSize::PerIteration,
        )
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

fn mipmap(c: &mut Criterion) {
    let mut g = c.benchmark_group("mipmap");
    g.sample_size(20);
    for (w, h, scan) in [
        (512u32, 512u32, Scan::InterlacedTop),
        (1024, 1024, Scan::Progressive),
    ] {
        let p = MipmapParams {
            width: w,
            height: h,
            scan,
            rounding: Rounding::Round,
        };
        let frame = synthetic_video(w, h, 1, Seed(1)).remove(0);
        g.throughput(Throughput::Elements(u64::from(w * h)));
        g.bench_function(format!("texels_{w}x{h}_{scan:?}_untraced"), |b| {
            let mut sim = Sim::new(MipmapGen::new("mipmap_gen_816", p).unwrap());
            b.iter(|| {
                for (k, &t) in frame.iter().enumerate() {
                    let d = &mut sim.dut;
                    d.valid.set_bool(true);
                    d.sof.set_bool(k == 0);
                    d.texel.set_bits(u64::from(t));
                    sim.step();
                }
                black_box(sim.dut.completed().len())
            })
        });
    }
    g.finish();
}

fn dram(c: &mut Criterion) {
    let mut g = c.benchmark_group("dram");
    let p = units::texmem::dram_604::DramParams::default();
    // A scanline-like trace: runs of 8 reads, a page change every 4.
    let trace: Vec<u64> = (0..4096u64).map(|k| (k / 4 % 512) * 512 + k % 4).collect();
    let cycles = tb::runs::dram::run_trace(p, &trace, None).unwrap().cycles;
    g.throughput(Throughput::Elements(cycles));
    g.bench_function("simulated_cycles_untraced", |b| {
        b.iter(|| black_box(tb::runs::dram::run_trace(p, &trace, None).unwrap().reads))
    });
    g.finish();
}

/// Texture unit 602 with DRAM, cache and bilinear, tracing off: simulated cycles per second
/// and texture requests per second on a scanline trace (mostly hits) and a random one (mostly
/// DRAM cycles). The texture is encoded once, outside the timing; each iteration builds the
/// unit (loading the DRAM image) and runs the trace.
fn texture(c: &mut Criterion) {
    use tb::runs::texture::run_texread;
    use tb::texture::{synthetic_texture, trace, TraceKind};
    let orig = synthetic_texture(256, 256, verif::Seed(1));
    let tex = formats::ccc::encode(&orig).unwrap();
    let p = units::texmem::texture_unit_602::TexParams::new(256, 256);
    let mut g = c.benchmark_group("texture");
    for kind in [TraceKind::Horizontal, TraceKind::Random] {
        let reqs = trace(kind, 256, 256, 4, 20_000, verif::Seed(2));
        let cycles = run_texread(&tex, p, &reqs, 1, None).unwrap().stats.cycles;
        let name = if kind == TraceKind::Random {
            "random"
        } else {
            "horizontal"
        };
        g.throughput(Throughput::Elements(cycles));
        g.bench_function(format!("{name}_simulated_cycles"), |b| {
            b.iter(|| black_box(run_texread(&tex, p, &reqs, 1, None).unwrap().stats.cycles))
        });
        g.throughput(Throughput::Elements(reqs.len() as u64));
        g.bench_function(format!("{name}_requests"), |b| {
            b.iter(|| black_box(run_texread(&tex, p, &reqs, 1, None).unwrap().stats.cycles))
        });
    }
    g.finish();
}

/// Cycles of the tracer benchmarks.
const TRACED: u64 = 20_000;

/// The replicate unit 152 with new texels every cycle (a fixed LCG): its 9 inputs and 16
/// outputs change almost every cycle, so the run measures the tracer, not the model.
fn replicate<T: Trace>(sim: &mut Sim<Replicate, T>) {
    let mut x: u64 = 1;
    for _ in 0..TRACED {
        for h in &mut sim.dut.h {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            h.set_bits(x >> 56);
        }
        sim.step();
    }
}

/// Value changes per second through each tracer alone (`companions` off, as the
/// vs-Verilator table runs them), counted by the VCD tracer.
fn tracer(c: &mut Criterion) {
    let unit = || Replicate::new("replicate_152", Format::unsigned(8, 2), false);
    let cfg = TraceConfig {
        companions: false,
        ..Default::default()
    };
    let dir = std::env::temp_dir().join(format!("texrtl-bench-t-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (vcd, fst) = (dir.join("r.vcd"), dir.join("r.fst"));
    let mut sim = Sim::traced(unit(), VcdTracer::create(&vcd, "t", cfg.clone()).unwrap()).unwrap();
    replicate(&mut sim);
    let changes = sim.trace_mut().map_or(0, |t| t.changes());
    drop(sim.finish());
    let mut g = c.benchmark_group("tracer");
    g.throughput(Throughput::Elements(changes));
    g.sample_size(20);
    g.bench_function("replicate_value_changes_vcd", |b| {
        b.iter_batched(
            || Sim::traced(unit(), VcdTracer::create(&vcd, "t", cfg.clone()).unwrap()).unwrap(),
            |mut sim| {
                replicate(&mut sim);
                sim.finish().unwrap();
            },
            BatchSize::PerIteration,
        )
    });
    g.bench_function("replicate_value_changes_fst", |b| {
        b.iter_batched(
            || Sim::traced(unit(), FstTracer::create(&fst, cfg.clone()).unwrap()).unwrap(),
            |mut sim| {
                replicate(&mut sim);
                sim.finish().unwrap();
            },
            BatchSize::PerIteration,
        )
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(
    benches,
    kernel,
    edge,
    tracer,
    fixed_point,
    normal_pipeline,
    mipmap,
    dram,
    texture
);
criterion_main!(benches);
