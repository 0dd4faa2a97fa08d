//! `texrtl sweep normals`: error tables over bit widths, for choosing widths.

use super::widths::Widths;
use super::CmdError;
use clap::Subcommand;
use std::fmt::Write;
use tb::runs::normals::{run_normals, NormalsRun, Sample};
use units::bump::params::BumpParams;
use verif::Seed;
use waves::TraceConfig;

/// Error tables over bit widths.
#[derive(Subcommand, Debug)]
pub enum SweepCmd {
    /// Max and mean normal error against blend-factor bits and rsqrt table bits.
    Normals {
        /// Built-in height map: flat, steep, steps, noise, smooth, extremes, bumps.
        #[arg(long, default_value = "smooth")]
        map: String,
        /// Positions per configuration.
        #[arg(long, default_value_t = 2000)]
        samples: usize,
        #[arg(long, value_parser = Seed::parse, default_value = "0x5eed")]
        seed: Seed,
    },
}

/// Positions per configuration at most (35 configurations are run).
const MAX_SAMPLES: usize = 1_000_000;

/// Runs a sweep.
pub fn run(c: &SweepCmd) -> Result<String, CmdError> {
    match c {
        SweepCmd::Normals { map, samples, seed } => {
            if !(1..=MAX_SAMPLES).contains(samples) {
                return Err(CmdError::Input(format!(
                    "--samples {samples}: 1..={MAX_SAMPLES} positions"
                )));
            }
            sweep_normals(map, *samples, *seed)
        }
    }
}

/// `texrtl sweep normals`: max and mean error of the B-spline normals against golden for
/// blend-factor bits x rsqrt table bits, on the built-in noise map at random positions with 16
/// fraction bits (so the address unit's truncation to F bits is part of the error).
pub fn sweep_normals(map_name: &str, samples: usize, seed: Seed) -> Result<String, CmdError> {
    tb::maps::builtin(map_name, 16, 16, BumpParams::default().texel_fmt())
        .map_err(|e| format!("--map {}: {e}", waves::output::shorten(map_name)))?;
    let blends = [4u32, 6, 8, 10, 12, 14, 16];
    let tables = [4u32, 6, 8, 10, 12];
    let mut stim = verif::Stimulus::new(seed);
    let pts: Vec<Sample> = (0..samples)
        .map(|_| {
            let (u, v) = stim.draw(&(0u64..(16 << 16), 0u64..(16 << 16)));
            Sample {
                u: u as f64 / 65536.0,
                v: v as f64 / 65536.0,
                scale: 1.0,
                lod: 0.0,
            }
        })
        .collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "B-spline normals vs golden, {map_name} map 16x16, {samples} positions with 16 fraction bits, seed {seed}\n\
         each cell: max component error / mean component error, in units of 2^-16 (default output LSB); max angle in degrees\n"
    );
    let _ = write!(s, "{:>11}", "blend\\table");
    for t in tables {
        let _ = write!(s, " | {:>26}", format!("{t} bits"));
    }
    s.push('\n');
    for b in blends {
        let _ = write!(s, "{b:>11}");
        for t in tables {
            let w = Widths {
                blend_bits: b,
                table_bits: t,
                ..Widths::default()
            };
            let mut p = w.params()?;
            p.pos_frac = 16;
            let map = tb::maps::builtin(map_name, 16, 16, p.texel_fmt())?;
            let o = run_normals(&NormalsRun {
                name: format!("sweep F={b} T={t}"),
                params: p,
                map,
                samples: pts.clone(),
                idle_per_mille: 0,
                vcd: None,
                trace: TraceConfig::default(),
                check_accuracy: false,
                check_schedule: false,
                seed,
            })
            .map_err(CmdError::Failed)?;
            let lsb = 1.0 / 65536.0;
            let mean = o.result.stats.sum_abs_lsb / o.result.stats.count.max(1) as f64
                * (-(p.out_frac as f64)).exp2()
                / lsb;
            let _ = write!(
                s,
                " | {:>26}",
                format!(
                    "{:.1} / {:.2}, {:.4} deg",
                    o.max_component_err / lsb,
                    mean,
                    o.max_angle_deg
                )
            );
        }
        s.push('\n');
    }
    Ok(s)
}
