//! `texrtl volume`: rays through the TEXRAM's cycle-accurate ray caster (Schilling & Knittel
//! section 13).

use super::{input, write_out, CmdError};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::runs::volume::run_volume;
use tb::volume::Ray;
use units::volume::layout::{Mode, Order, VolumeParams};

/// Rays through the TEXRAM as a ray caster (section 13, Figure 15).
#[derive(Clone, Debug, clap::Args)]
pub struct VolumeArgs {
    /// Raw 8-bit voxels, x fastest, then y, then z: exactly X*Y*Z bytes.
    #[arg(long)]
    pub volume: PathBuf,
    /// X,Y,Z: x and y even 2..=256, z 1..=256, X*Y*Z/4 words a bank at most 280,064 (the banks of level 0).
    #[arg(long)]
    pub dims: String,
    /// CSV with header x0,y0,z0,dx,dy,dz,steps: start and step in voxel units (voxel i at
    /// i; -512..512, 12 fraction bits, rounded ties to even), samples 1..=65535.
    #[arg(long)]
    pub rays: PathBuf,
    /// CSV: ray,k,x,y,z,value (and gx,gy,gz with --gradient) per sample in order.
    #[arg(long)]
    pub out: PathBuf,
    /// Gradient mode: eight accesses a sample, central differences (without the 1/2).
    #[arg(long)]
    pub gradient: bool,
    /// Word order in a bank: column (z fastest, the default) or slice.
    #[arg(long, default_value = "column")]
    pub order: String,
    /// Words of a DRAM row: a power of two, 16..=65536.
    #[arg(long, default_value_t = 512)]
    pub row_words: u32,
    /// JSON: rays, samples, accesses, slots, fault_slots, bank_misses, cycles, ns,
    /// samples_per_second.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform: stepper, page registers 824, interpolator.
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// `texrtl volume`.
pub fn run(a: &VolumeArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.stats.as_deref().map(|p| ("--stats", p)));
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--volume", a.volume.as_path()),
        ("--rays", a.rays.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(volume(a))
}

/// The volume's parameters from the options.
fn params(a: &VolumeArgs) -> Result<VolumeParams, CmdError> {
    let bad = || input(format!("--dims {}: X,Y,Z", formats::shorten(&a.dims)));
    let d: Vec<u32> = a
        .dims
        .split(',')
        .map(|s| s.trim().parse::<u32>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let [x, y, z] = d[..] else {
        return Err(bad());
    };
    let order = match a.order.as_str() {
        "column" => Order::ColumnMajor,
        "slice" => Order::SliceMajor,
        o => {
            let o = formats::shorten(o);
            return Err(input(format!("--order {o}: column or slice")));
        }
    };
    let p = VolumeParams {
        order,
        row_words: a.row_words,
        ..VolumeParams::new(x, y, z)
    };
    p.validate()
        .map_err(|e| input(format!("--dims/--row-words: {e}")))?;
    Ok(p)
}

/// Rays from the CSV, quantised and range-checked.
fn read_rays(path: &Path) -> Result<Vec<Ray>, String> {
    let t = formats::csv::read(path, &["x0,y0,z0,dx,dy,dz,steps"])?;
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let mut raw = [0i32; 6];
        for (k, x) in raw.iter_mut().enumerate() {
            let f = t.finite(r, k)?;
            let q = (f * 4096.0).round_ties_even() / 4096.0;
            if !(-512.0..512.0).contains(&q) {
                let s = formats::shorten(&r.fields[k]);
                return Err(t.error(r, format!("{} {s} outside -512..512", t.columns[k])));
            }
            *x = (q * 4096.0) as i32;
        }
        let s = t.finite(r, 6)?;
        if s.fract() != 0.0 || !(1.0..=65535.0).contains(&s) {
            let f = formats::shorten(&r.fields[6]);
            return Err(t.error(r, format!("steps {f}: a whole number 1..=65535")));
        }
        let ray = Ray {
            p: [raw[0], raw[1], raw[2]],
            d: [raw[3], raw[4], raw[5]],
            steps: s as u16,
        };
        if !units::volume::ray_caster_fig15::RayCaster::ray_fits(ray.p, ray.d, ray.steps) {
            let msg = format!(
                "steps {s}: the ray leaves the stepper's range (|x0 + steps dx| < 524288 voxels a component)"
            );
            return Err(t.error(r, msg));
        }
        v.push(ray);
    }
    Ok(v)
}

/// The command once its outputs are checked.
fn volume(a: &VolumeArgs) -> Result<String, CmdError> {
    let p = params(a)?;
    let want = p.dims.0 as u64 * p.dims.1 as u64 * p.dims.2 as u64;
    let len = std::fs::metadata(&a.volume)
        .map_err(|e| input(format!("{}: {e}", a.volume.display())))?
        .len();
    if len != want {
        return Err(input(format!(
            "{}: {len} bytes, --dims {} needs {want}",
            a.volume.display(),
            a.dims
        )));
    }
    let vox =
        std::fs::read(&a.volume).map_err(|e| input(format!("{}: {e}", a.volume.display())))?;
    let rays = read_rays(&a.rays).map_err(input)?;
    let mode = if a.gradient {
        Mode::Gradient
    } else {
        Mode::Value
    };
    let run = run_volume(p, mode, &vox, &rays, a.vcd.as_deref()).map_err(super::run_error)?;
    let mut csv = String::from("ray,k,x,y,z,value");
    csv.push_str(if a.gradient { ",gx,gy,gz\n" } else { "\n" });
    let f = |x: i64| x as f64 / 4096.0;
    for s in &run.samples {
        let _ = write!(
            csv,
            "{},{},{},{},{},{}",
            s.ray - 1,
            s.k,
            f(s.p[0]),
            f(s.p[1]),
            f(s.p[2]),
            s.value
        );
        if a.gradient {
            let g = |x: i64| x as f64 / 16.0;
            let _ = write!(csv, ",{},{},{}", g(s.g[0]), g(s.g[1]), g(s.g[2]));
        }
        csv.push('\n');
    }
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        let json = serde_json::to_vec_pretty(&run.stats).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    let st = &run.stats;
    Ok(format!(
        "{} samples of {} rays written to {}: {} accesses in {} slots, {} of them page faults, {:.2} M samples/s",
        st.samples,
        st.rays,
        a.out.display(),
        st.accesses,
        st.slots,
        st.fault_slots,
        st.samples_per_second / 1e6
    ))
}
