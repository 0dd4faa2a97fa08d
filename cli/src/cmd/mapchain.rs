//! `texrtl mapchain`: pixels through the chain walker of unit 812 (Schilling & Knittel
//! section 14) over linked texture, offset, detail, reflectance and environment maps.

use super::{input, write_out, CmdError};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::mapchain::Scene;
use tb::runs::mapchain::run_mapchain;
use units::mapchain::program::ChainRequest;
use units::mapchain::walker_812::{Pixel, PixelField};

/// Pixels through the map chain walker of 812 (section 14, Fig. 16).
#[derive(Clone, Debug, clap::Args)]
pub struct MapchainArgs {
    /// JSON: the DRFs and their PGM maps (see the map chain's documentation, `units::mapchain`):
    /// {"drfs": [{"drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1}, ...]}.
    #[arg(long)]
    pub maps: PathBuf,
    /// CSV with header drf,u,v,lambda and any of nx,ny,nz (the perturbed normal, |c| < 4),
    /// vx,vy,vz (unit vector to the eye, |c| < 2), face (0..=5), id, is (0..=255): u, v in
    /// level-0 texels (-4096..4096, 8 fraction bits), lambda -4..=10, vectors 14 fraction
    /// bits (rounded ties to even); defaults n = v = (0, 0, 1), face 0, id 255, is 0.
    #[arg(long)]
    pub requests: PathBuf,
    /// CSV: drf,u,v,lambda,colour,accesses,faults,error per request in order.
    #[arg(long)]
    pub out: PathBuf,
    /// JSON: pixels, accesses, page_faults, slots, errors, cycles, ns, ns_per_pixel.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform of the walker (its state by name).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// `texrtl mapchain`.
pub fn run(a: &MapchainArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.stats.as_deref().map(|p| ("--stats", p)));
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--maps", a.maps.as_path()),
        ("--requests", a.requests.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(mapchain(a, &outs))
}

/// The columns every file has; any of the pixel's other fields may follow.
const REQUIRED: [&str; 4] = ["drf", "u", "v", "lambda"];

/// The pixel of a row before its columns are read: n = v = (0, 0, 1), face 0, id 255, is 0.
fn defaults() -> Pixel<i64> {
    Pixel::of(&ChainRequest {
        n: [0, 0, 1 << 14],
        eye: [0, 0, 1 << 14],
        i_d: 255,
        ..ChainRequest::default()
    })
}

/// The values a column takes, `(low, high, closed)`: its field's format's range (closed for
/// an integer), narrowed for the DRF, lambda and the face to what the walker accepts.
fn range(f: &PixelField) -> (f64, f64, bool) {
    match f.name {
        "drf" => (0.0, 6.0, true),
        "lambda" => (-4.0, 10.0, true),
        "face" => (0.0, 5.0, true),
        _ => {
            let lsb = 2f64.powi(-f.fmt.frac());
            let (lo, hi) = (f.fmt.min_raw() as f64, f.fmt.max_raw() as f64 + 1.0);
            let closed = f.fmt.frac() == 0;
            (lo * lsb, if closed { hi - 1.0 } else { hi } * lsb, closed)
        }
    }
}

/// The header, checked: drf,u,v,lambda then optional columns, each at most once.
fn header(path: &Path, text: &str) -> Result<String, String> {
    let head = text.lines().next().unwrap_or("").trim();
    let cols: Vec<&str> = head.split(',').map(str::trim).collect();
    let fields = Pixel::fields();
    let optional: Vec<&str> = fields.each().iter().map(|f| f.name).skip(4).collect();
    let bad = || {
        format!(
            "{}:1: header '{}' is not drf,u,v,lambda followed by any of {}",
            path.display(),
            formats::shorten(head),
            optional.join(",")
        )
    };
    if cols.len() < 4 || cols[..4] != REQUIRED {
        return Err(bad());
    }
    for (k, c) in cols.iter().enumerate().skip(4) {
        if !optional.contains(c) || cols[..k].contains(c) {
            return Err(bad());
        }
    }
    Ok(cols.join(","))
}

/// `x` rounded to `frac` fraction bits (ties to even) as a raw integer if within `lo..hi`
/// (`..=hi` when `closed`); an integer column (`frac` 0) must be given as one.
fn quantise(x: f64, frac: i32, (lo, hi): (f64, f64), closed: bool) -> Option<i64> {
    let s = 2f64.powi(frac);
    let q = (x * s).round_ties_even() / s;
    let inside = q >= lo && (q < hi || closed && q == hi);
    (inside && (frac > 0 || q == x)).then_some((q * s) as i64)
}

/// The requests of `path`, every field range-checked.
fn read_requests(path: &Path) -> Result<Vec<ChainRequest>, String> {
    let text = formats::read_text_bounded(path, formats::MAX_INPUT_BYTES)?;
    let head = header(path, &text)?;
    let t = formats::csv::parse(&path.display().to_string(), &text, &[&head])?;
    let fields = Pixel::fields();
    let columns: Vec<usize> = t
        .columns
        .iter()
        .map(|c| fields.each().iter().position(|f| f.name == c))
        .collect::<Option<_>>()
        .ok_or("a column the header check let through")?;
    let mut out = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let mut px = defaults();
        for (col, &k) in columns.iter().enumerate() {
            let f = fields.each()[k];
            let (lo, hi, closed) = range(f);
            let x = t.finite(r, col)?;
            *px.each_mut()[k] = quantise(x, f.fmt.frac(), (lo, hi), closed).ok_or_else(|| {
                let v = formats::shorten(&r.fields[col]);
                let what = if f.fmt.frac() == 0 {
                    "an integer in"
                } else {
                    "in"
                };
                let end = if closed { "]" } else { ")" };
                t.error(r, format!("{} {v}: not {what} [{lo}, {hi}{end}", f.name))
            })?;
        }
        out.push(px.request());
    }
    Ok(out)
}

/// The command once its outputs are checked.
fn mapchain(a: &MapchainArgs, outs: &[(&str, &Path)]) -> Result<String, CmdError> {
    let specs = formats::maps_json::read(&a.maps).map_err(input)?;
    for (opt, o) in outs {
        let map = specs
            .iter()
            .flat_map(|s| &s.paths)
            .find(|m| super::same_file(o, m));
        if let Some(m) = map {
            return Err(input(format!(
                "{opt} {}: the same file as the map {}: choose another",
                o.display(),
                m.display()
            )));
        }
    }
    let scene =
        Scene::from_specs(specs).map_err(|e| input(format!("{}: {e}", a.maps.display())))?;
    let reqs = read_requests(&a.requests).map_err(input)?;
    let (res, st) = run_mapchain(&scene, &reqs, a.vcd.as_deref()).map_err(super::run_error)?;
    let mut csv = String::from("drf,u,v,lambda,colour,accesses,faults,error\n");
    for (q, r) in reqs.iter().zip(&res) {
        let f = |x: i32| f64::from(x) / 256.0;
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{}",
            q.drf,
            f(q.u),
            f(q.v),
            f(q.lambda),
            r.colour,
            r.accesses,
            r.faults,
            u8::from(r.error)
        );
    }
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        let json = serde_json::to_vec_pretty(&st).map_err(|e| input(e.to_string()))?;
        write_out(s, &json)?;
    }
    Ok(format!(
        "{} pixels written to {}: {} accesses, {} page faults, {} flagged chains, {:.1} ns a pixel ({:.2} M pixels/s)",
        st.pixels,
        a.out.display(),
        st.accesses,
        st.page_faults,
        st.errors,
        st.ns_per_pixel,
        1e3 / st.ns_per_pixel.max(1e-9)
    ))
}
