//! The map chain's description for `texrtl mapchain --maps M.json`: the DRFs of unit 812 and
//! the 8-bit PGM files of their maps (paths relative to the JSON file's folder).
//!
//! ```json
//! { "drfs": [
//!   { "drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1, "modulate": "illumination" },
//!   { "drf": 1, "kind": "offset", "maps": ["ou.pgm", "ov.pgm"], "link": 2 },
//!   { "drf": 2, "kind": "detail", "maps": ["d.pgm"], "detail": "multiply", "link": 6 },
//!   { "drf": 6, "kind": "environment", "k_s": 160,
//!     "maps": ["px.pgm", "nx.pgm", "py.pgm", "ny.pgm", "pz.pgm", "nz.pgm"] }
//! ] }
//! ```
//!
//! | field | values | default |
//! |---|---|---|
//! | `drf` | 0 ..= 6 | required |
//! | `kind` | texture, offset, detail, reflectance, environment | required |
//! | `maps` | PGM paths: two for offset (u, v), six faces +x -x +y -y +z -z | required |
//! | `border` | wrap, clamp, mirror, border:N, tile:T | tile:4 for detail, clamp for faces, wrap |
//! | `link` | 0 ..= 6 | none (the chain's end) |
//! | `modulate` | one, illumination, k:N (eq. 5) | one |
//! | `detail` | replace, multiply, add-signed | replace |
//! | `k_s` | 0 ..= 255 (eq. 6) | 255 |
//! | `base` | texture, illumination (eqs 6, 7) | texture |
//! | `light` | environment, specular (eq. 7) | environment |
//! | `new_coords` | true, false (environment: eq. 4 or the rasterizer's face) | true |
//!
//! Every map's sides are powers of two up to 1024 (a detail map at most 256, faces square
//! and at least 16, all planes of a DRF one size), maxval 255.

use serde::Deserialize;
use std::path::Path;
use units::mapchain::drf_812::{ChainDrf, DetailMode, Kind};
use units::texram::output_820::Modulate;
use units::texram::{Border, Drf};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    drfs: Vec<Entry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Entry {
    drf: u8,
    kind: String,
    maps: Vec<String>,
    border: Option<String>,
    link: Option<u8>,
    modulate: Option<String>,
    detail: Option<String>,
    k_s: Option<u8>,
    base: Option<String>,
    light: Option<String>,
    new_coords: Option<bool>,
}

/// One DRF as described: its fields (bases not yet placed) and its planes' level-0 texels.
#[derive(Clone, Debug)]
pub struct DrfSpec {
    pub index: usize,
    pub drf: ChainDrf,
    pub planes: Vec<Vec<u8>>,
    /// The map files read.
    pub paths: Vec<std::path::PathBuf>,
}

fn pick<T: Copy>(what: &str, s: &str, table: &[(&str, T)]) -> Result<T, String> {
    table
        .iter()
        .find(|(n, _)| *n == s)
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
            format!("{what} '{}': {}", crate::shorten(s), names.join(", "))
        })
}

fn modulate(s: &str) -> Result<Modulate, String> {
    if let Some(k) = s.strip_prefix("k:") {
        return k
            .parse()
            .map(Modulate::Constant)
            .map_err(|_| format!("modulate '{}': k:N with N 0..=255", crate::shorten(s)));
    }
    pick(
        "modulate",
        s,
        &[
            ("one", Modulate::One),
            ("illumination", Modulate::Illumination),
        ],
    )
}

/// The map of `path`: its size as log2 and its texels.
fn map(path: &Path) -> Result<((u32, u32), Vec<u8>), String> {
    let img = crate::netpbm::read(path)?;
    let log2 = |what: &str, n: u32| {
        if n.is_power_of_two() && n <= 1024 {
            Ok(n.trailing_zeros())
        } else {
            Err(format!(
                "{}: {what} {n} is not a power of two up to 1024",
                path.display()
            ))
        }
    };
    if img.maxval != 255 {
        return Err(format!(
            "{}: maxval {}, 8-bit texels need 255",
            path.display(),
            img.maxval
        ));
    }
    Ok((
        (log2("width", img.width)?, log2("height", img.height)?),
        img.pixels,
    ))
}

/// One entry's DRF fields, its maps read (relative to `dir`).
fn entry(e: &Entry, dir: &Path) -> Result<DrfSpec, String> {
    let kinds = Kind::ALL.map(|k| (k.name(), k));
    let kind = pick("kind", &e.kind, &kinds)?;
    let default_border = match kind {
        Kind::Detail => "tile:4",
        Kind::Environment => "clamp",
        _ => "wrap",
    };
    let b = e.border.as_deref().unwrap_or(default_border);
    let border = Border::parse(b).ok_or_else(|| {
        format!(
            "border '{}': wrap, clamp, mirror, border:N or tile:T",
            crate::shorten(b)
        )
    })?;
    let mut drf = ChainDrf::new(kind, Drf::new(0, 0, border));
    if e.maps.len() != drf.plane_count() {
        return Err(format!(
            "a {} DRF names {} maps, {} given",
            kind.name(),
            drf.plane_count(),
            e.maps.len()
        ));
    }
    drf.link = e.link;
    drf.map.modulate = modulate(e.modulate.as_deref().unwrap_or("one"))?;
    let modes = [
        ("replace", DetailMode::Replace),
        ("multiply", DetailMode::Multiply),
        ("add-signed", DetailMode::AddSigned),
    ];
    drf.detail = pick("detail", e.detail.as_deref().unwrap_or("replace"), &modes)?;
    drf.k_s = e.k_s.unwrap_or(255);
    let base = e.base.as_deref().unwrap_or("texture");
    drf.base_texture = pick("base", base, &[("texture", true), ("illumination", false)])?;
    let light = e.light.as_deref().unwrap_or("environment");
    drf.light_env = pick(
        "light",
        light,
        &[("environment", true), ("specular", false)],
    )?;
    drf.new_coords = e.new_coords.unwrap_or(drf.new_coords);
    let mut planes = Vec::with_capacity(e.maps.len());
    let mut size = None;
    for m in &e.maps {
        let (s, texels) = map(&dir.join(m))?;
        if *size.get_or_insert(s) != s {
            return Err(format!("{m}: the DRF's maps differ in size"));
        }
        planes.push(texels);
    }
    let (wl, hl) = size.unwrap_or((0, 0));
    (drf.map.width_log2, drf.map.height_log2) = (wl, hl);
    drf.validate()?;
    Ok(DrfSpec {
        index: usize::from(e.drf),
        drf,
        planes,
        paths: e.maps.iter().map(|m| dir.join(m)).collect(),
    })
}

/// Reads the description at `path` and the maps it names.
pub fn read(path: &Path) -> Result<Vec<DrfSpec>, String> {
    let text = crate::read_text_bounded(path, 1 << 20)?;
    let f: File = serde_json::from_str(&text).map_err(|e| {
        // serde quotes what it refuses (a field name can hold a newline, and be long): kept on
        // one short line.
        let e = waves::output::escape_controls(&e.to_string());
        let e = waves::output::shorten_quoted(&e, '`');
        let e = waves::output::shorten_message(&e, 200);
        format!("{}: {e}", path.display())
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut seen = [false; units::texram::DRFS];
    let mut out = Vec::with_capacity(f.drfs.len().min(units::texram::DRFS));
    for e in &f.drfs {
        let at = |m: String| format!("{}: drf {}: {m}", path.display(), e.drf);
        let k = usize::from(e.drf);
        if k >= seen.len() {
            return Err(at(format!("0..{}", seen.len())));
        }
        if std::mem::replace(&mut seen[k], true) {
            return Err(at("described twice".into()));
        }
        out.push(entry(e, dir).map_err(at)?);
    }
    if out.is_empty() {
        return Err(format!("{}: no drfs", path.display()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    /// What the cargo-fuzz target found: serde quoted an unknown field holding a newline, and
    /// the message split over two lines.
    #[test]
    fn a_refused_field_with_a_newline_stays_on_one_line() {
        let d = std::env::temp_dir().join(format!("texrtl-maps-json-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("M.json");
        std::fs::write(&p, "{\"dr\\ns\":{\"drf[{rd1fsf").unwrap();
        let e = super::read(&p).unwrap_err();
        let _ = std::fs::remove_dir_all(&d);
        assert!(
            !e.contains('\n') && e.contains("unknown field `dr\\ns`"),
            "{e}"
        );
    }
}
