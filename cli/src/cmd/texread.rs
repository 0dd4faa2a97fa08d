//! `texrtl texread`: texture requests through the cycle-accurate memory path of Figure 6.

use super::{input, write_out, CmdError};
use formats::ccc::{self, Ccc};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use tb::runs::texture::{run_texread, TexRequest};
use units::texmem::cache_614::Lookahead;
use units::texmem::layout::Layout;
use units::texmem::texture_unit_602::TexParams;

/// The `--stats` fields, shown by `texrtl texread --help` (the texture memory docs, `units::texmem`, have the same table).
pub const STATS_HELP: &str = "\
--stats JSON fields (blocks are 4x4-texel CCC blocks, two DRAM words each):
  requests                 requests accepted from the rasterizer
  interval                 cycles between requests the rasterizer offers (--interval)
  cycles                   controller cycles from the first request offered to the last result
  cycle_ns                 ns per controller cycle (5)
  ns                       cycles * cycle_ns
  pixels_per_second        requests / ns, per second
  layout                   row-major or tiled
  cache                    cache 614 on (true/false)
  lookahead                quadrant, direction or off (off whenever the cache is)
  page_words               DRAM page (row) size in words
  block_refs               blocks referenced (1, 2 or 4 per request) at each first lookup
  hits                     of those, blocks found in the cache
  hit_rate                 hits / block_refs
  misses                   block_refs - hits
  misses_cold              misses a 4-block fully-associative LRU cache would have had (never seen)
  misses_capacity          misses that cache would also have had (evicted there too)
  misses_conflict          misses that cache would not have had (held there)
  demand_fills             blocks fetched because a request needed them
  prefetch_fills           blocks fetched from the lookahead queue
  prefetch_hits            first-lookup hits on a prefetched block no request had used
  late_prefetches          first-lookup misses on the block a prefetch was fetching
  prefetch_dropped         lookahead candidates dropped because the cache held them
  stall_cycles             cycles a request waited in stage 0
  dram_reads               DRAM word reads (two per fill)
  page_hits                reads in the open DRAM row
  page_faults              reads that opened another row
  scanlines                accepted requests that are the first or flagged newline
  page_faults_per_scanline page_faults / scanlines (divided by 1 when there are none)
  violations               DRAM timing or protocol violations (0)";

/// A texture from a `.ccc` file (by its magic) or a PPM (encoded on the fly).
pub fn read_texture(path: &Path) -> Result<Ccc, String> {
    let b = formats::read_bounded(path, formats::MAX_INPUT_BYTES)?;
    if b.starts_with(ccc::MAGIC) {
        Ccc::parse(&b).map_err(|e| format!("{}: {e}", path.display()))
    } else if b.starts_with(b"P6") || b.starts_with(b"P3") {
        let img = formats::netpbm::parse_ppm(&b).map_err(|e| format!("{}: {e}", path.display()))?;
        ccc::encode(&img).map_err(|e| format!("{}: {e}", path.display()))
    } else {
        Err(format!(
            "{}: neither a .ccc file (magic TEXRTLCC) nor a PPM (P6 or P3)",
            path.display()
        ))
    }
}

/// Reads requests: header `u,v` or `u,v,newline`; `u`, `v` decimal texel coordinates, rounded
/// to the nearest multiple of `2^-frac_bits` (ties to even), inside `width x height` after
/// rounding; `newline` 0 or 1.
pub fn read_requests(path: &Path, p: &TexParams) -> Result<Vec<TexRequest>, String> {
    let t = formats::csv::read(path, &["u,v", "u,v,newline"])?;
    let one = f64::from(1u32 << p.frac_bits);
    let coord = |r: &formats::csv::Row, k: usize, size: u32| -> Result<u32, String> {
        let x = t.finite(r, k)?;
        let raw = (x * one).round_ties_even();
        if raw < 0.0 || raw >= f64::from(size) * one {
            let name = &t.columns[k];
            return Err(t.error(
                r,
                format!(
                    "{name} {} (rounded to {}) outside the texture (0 <= {name} < {size})",
                    formats::shorten(&r.fields[k]),
                    raw / one
                ),
            ));
        }
        Ok(raw as u32)
    };
    let mut v = Vec::with_capacity(t.rows.len());
    for r in &t.rows {
        let newline = match r.fields.get(2).map(String::as_str) {
            None | Some("0") => false,
            Some("1") => true,
            Some(x) => {
                let x = formats::shorten(x);
                return Err(t.error(r, format!("newline '{x}' is not 0 or 1")));
            }
        };
        v.push(TexRequest {
            u: coord(r, 0, p.width)?,
            v: coord(r, 1, p.height)?,
            newline,
        });
    }
    Ok(v)
}

/// Options of `texrtl texread`.
#[derive(Clone, Debug, clap::Args)]
pub struct TexreadArgs {
    /// The texture: a .ccc file, or a PPM (P6/P3) that is CCC-encoded first.
    #[arg(long)]
    pub texture: PathBuf,
    /// CSV with header u,v or u,v,newline: texel coordinates (texel (x, y) at integer x, y),
    /// newline 1 at a scanline change.
    #[arg(long)]
    pub requests: PathBuf,
    /// CSV u,v,r,g,b, one row per request in order (u, v as quantised).
    #[arg(long)]
    pub out: PathBuf,
    /// Disable cache 614 (every request fetches its blocks).
    #[arg(long)]
    pub no_cache: bool,
    /// Disable the lookahead prefetch (same as --lookahead off).
    #[arg(long)]
    pub no_lookahead: bool,
    /// Which neighbours to preload: quadrant (the document's: from one bit of u and of v),
    /// direction (from the motion between the scanline's last two points), off.
    #[arg(long, default_value = "quadrant")]
    pub lookahead: String,
    /// Blocks in DRAM: row-major or tiled (one page per tile).
    #[arg(long, default_value = "row-major")]
    pub layout: String,
    /// Cycles between requests the rasterizer can offer.
    #[arg(long, default_value_t = 1)]
    pub interval: u32,
    /// Fraction bits of u, v and the blend weights (1..=8).
    #[arg(long, default_value_t = 4)]
    pub frac_bits: u32,
    /// DRAM 604: 256k (256K x 16, 512-word pages) or 1m (1M x 16, 1024-word pages).
    #[arg(long, default_value = "256k")]
    pub dram: String,
    /// JSON with the counts, cycles, ns and pixels per second.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Waveform of the unit, the DRAM pins, page register, cache tags and FSMs.
    #[arg(long)]
    pub vcd: Option<PathBuf>,
}

/// `texrtl texread`: requests through the cycle-accurate unit; CSV of results, JSON stats.
pub fn run(a: &TexreadArgs) -> Result<String, CmdError> {
    let mut outs = vec![("--out", a.out.as_path())];
    outs.extend(a.stats.as_deref().map(|p| ("--stats", p)));
    outs.extend(a.vcd.as_deref().map(|p| ("--vcd", p)));
    let ins = [
        ("--texture", a.texture.as_path()),
        ("--requests", a.requests.as_path()),
    ];
    let guard = super::Outputs::check(&outs, &ins)?;
    guard.settle(texread(a))
}

/// The command once its outputs are checked.
fn texread(a: &TexreadArgs) -> Result<String, CmdError> {
    if !(1..=8).contains(&a.frac_bits) {
        return Err(input(format!("--frac-bits {}: 1..=8", a.frac_bits)));
    }
    let layout = Layout::parse(&a.layout)
        .ok_or_else(|| input(format!("--layout {}: row-major or tiled", a.layout)))?;
    let tex = read_texture(&a.texture).map_err(input)?;
    let mut p = TexParams::new(tex.width, tex.height);
    p.layout = layout;
    p.cache = !a.no_cache;
    // The scheme is checked even with --no-lookahead: a bad value is refused, not ignored.
    p.lookahead = match (a.no_lookahead, Lookahead::parse(&a.lookahead)) {
        (_, None) => {
            return Err(input(format!(
                "--lookahead {}: quadrant, direction or off",
                formats::shorten(&a.lookahead)
            )))
        }
        (true, Some(Lookahead::Direction)) => {
            return Err(input(
                "--no-lookahead with --lookahead direction: choose one".into(),
            ))
        }
        (true, _) => Lookahead::Off,
        (false, Some(l)) => l,
    };
    p.frac_bits = a.frac_bits;
    p.dram = match a.dram.as_str() {
        "256k" => units::texmem::dram_604::DramParams::default(),
        "1m" => units::texmem::dram_604::DramParams::one_meg(),
        d => return Err(input(format!("--dram {d}: 256k or 1m"))),
    };
    p.validate()
        .map_err(|e| input(format!("{}: {e}", a.texture.display())))?;
    if !(1..=1000).contains(&a.interval) {
        return Err(input(format!("--interval {}: 1..=1000 cycles", a.interval)));
    }
    let reqs = read_requests(&a.requests, &p).map_err(input)?;
    let vcd = a.vcd.clone().map(|v| (v, waves::TraceConfig::default()));
    let run = run_texread(&tex, p, &reqs, a.interval, vcd).map_err(super::run_error)?;
    if run.stats.violations != 0 {
        return Err(CmdError::Failed(format!(
            "{} DRAM timing violations",
            run.stats.violations
        )));
    }
    let one = f64::from(1u32 << p.frac_bits);
    let mut csv = String::from("u,v,r,g,b\n");
    for (r, c) in reqs.iter().zip(&run.rgb) {
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            f64::from(r.u) / one,
            f64::from(r.v) / one,
            c >> 16,
            c >> 8 & 0xff,
            c & 0xff
        );
    }
    let json =
        serde_json::to_vec_pretty(&run.stats).map_err(|e| CmdError::Failed(e.to_string()))?;
    write_out(&a.out, csv.as_bytes())?;
    if let Some(s) = &a.stats {
        write_out(s, &json)?;
    }
    let s = &run.stats;
    Ok(format!(
        "{}: {} results; {} cycles ({} ns), {:.2} M pixels/s; hit rate {:.1} %; {} DRAM reads, {} page faults",
        a.out.display(),
        run.rgb.len(),
        s.cycles,
        s.ns,
        s.pixels_per_second / 1e6,
        100.0 * s.hit_rate,
        s.dram_reads,
        s.page_faults
    ))
}
