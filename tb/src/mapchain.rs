//! The chain walker of unit 812 (section 14, Fig. 16) with the maps it links: detail
//! (section 9), reflectance (section 8), environment (section 7) and the output stage 820.
//!
//! Each pixel is checked three ways: the clocked walker against its micro-program run access
//! by access on a second copy of the banks (colour, accesses, slots, faults, error: bit for
//! bit); its cycles against its slots; its colour against the f64 golden model of the
//! equations (`golden::mapchain`) within the bound derived there stage by stage. Chains that
//! loop are stopped after seven DRFs with the error flag.

use crate::runs::mapchain::timings;
use golden::mapchain::{GChain, GDetail, GEnv, GLayer, GMap, GPixel, Mode};
use hdl::kernel::Sim;
use units::mapchain::drf_812::{ChainDrf, DetailMode, DrfFile, Kind, Placer};
use units::mapchain::program::ChainRequest;
use units::mapchain::walker_812::{walk_pixel, ChainResult, MapChain812, Pixel, PixelField};
use units::texram::output_820::Modulate;
use units::texram::stub::{next_level, TexramStub};
use units::texram::{Border, Drf, TexramAccess};
use verif::{
    run_scored, About, Coverage, Coverpoint, Ctx, Pacing, PinMonitor, RunSpec, Scoreboard, Scored,
    Stimulus, StreamDriver, TbResult, Testbench,
};
use waves::VcdTracer;

pub const NAME: &str = "walker_812";
/// The chip's clock, 5 ns; a slot is six cycles (30 ns).
pub const CYCLE_PS: u64 = 5_000;
pub const SLOT_CYCLES: u32 = 6;

/// A DRF file and the maps it describes: each plane's access DRF and level-0 texels.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub file: DrfFile,
    pub maps: Vec<(Drf, Vec<u8>)>,
    placer: Placer,
}

impl Scene {
    pub fn new() -> Scene {
        Scene::default()
    }

    /// Adds DRF `k` of `kind` over planes of `2^wl x 2^hl` (one plane's texels each) with
    /// `border`; returns the DRF to refine.
    pub fn add(
        &mut self,
        k: usize,
        kind: Kind,
        (wl, hl): (u32, u32),
        border: Border,
        planes: Vec<Vec<u8>>,
    ) -> Result<&mut ChainDrf, String> {
        self.add_drf(k, ChainDrf::new(kind, Drf::new(wl, hl, border)), planes)
    }

    /// Adds DRF `k` as `drf` says, its planes placed after the maps before.
    pub fn add_drf(
        &mut self,
        k: usize,
        mut drf: ChainDrf,
        planes: Vec<Vec<u8>>,
    ) -> Result<&mut ChainDrf, String> {
        if planes.len() != drf.plane_count() {
            return Err(format!(
                "drf {k}: a {} map has {} planes, {} given",
                drf.kind.name(),
                drf.plane_count(),
                planes.len()
            ));
        }
        let (wl, hl) = (drf.map.width_log2, drf.map.height_log2);
        drf.validate().map_err(|e| format!("drf {k}: {e}"))?;
        let slot = self
            .file
            .drfs
            .get_mut(k)
            .ok_or_else(|| format!("drf {k}: 0..7"))?;
        for (p, texels) in planes.into_iter().enumerate() {
            let (e, o) = self.placer.place(wl, hl)?;
            if p == 0 {
                (drf.map.base_even, drf.map.base_odd) = (e, o);
            } else {
                drf.planes[p - 1] = (e, o);
            }
            self.maps.push((drf.plane(p), texels));
        }
        Ok(slot.insert(drf))
    }

    /// The scene a maps file describes.
    pub fn from_specs(specs: Vec<formats::maps_json::DrfSpec>) -> Result<Scene, String> {
        let mut s = Scene::new();
        for d in specs {
            s.add_drf(d.index, d.drf, d.planes)?;
        }
        s.file.validate()?;
        Ok(s)
    }

    /// Writes every map into `t`'s banks.
    pub fn load<T: TexramAccess>(&self, t: &mut T) -> Result<(), String> {
        self.file.validate()?;
        for (d, texels) in &self.maps {
            t.load_map(d, texels)?;
        }
        Ok(())
    }

    /// A stub with the maps loaded.
    pub fn stub(&self) -> Result<TexramStub, String> {
        let mut s = TexramStub::new();
        self.load(&mut s)?;
        Ok(s)
    }

    fn gmap(&self, d: &Drf) -> GMap {
        let texels = &self
            .maps
            .iter()
            .find(|(m, _)| (m.base_even, m.base_odd) == (d.base_even, d.base_odd))
            .expect("every plane is loaded")
            .1;
        let mut levels = vec![texels.clone()];
        for k in 0..d.max_level() {
            let (w, h) = d.level_size(k);
            let next = next_level(w, h, &levels[k as usize]);
            levels.push(next);
        }
        let border = crate::texram::golden_border(d.border);
        let (w, h) = d.level_size(0);
        GMap {
            width: w as usize,
            height: h as usize,
            levels,
            border,
        }
    }

    /// The golden model's reading of the chain from DRF `lead`: its maps and selections
    /// (`None` when it loops or is incomplete: the walker must flag it).
    pub fn golden(&self, lead: u8) -> Option<GChain> {
        let mut g = GChain {
            texture: None,
            modulate: Some(255.0),
            reflectance: None,
            env: None,
            base_texture: true,
            light_env: true,
        };
        let (mut k, mut steps, mut last) = (Some(lead), 0, None::<Kind>);
        while let Some(i) = k {
            steps += 1;
            let d = self.file.get(i).filter(|_| steps <= 7)?;
            match d.kind {
                Kind::Texture | Kind::Reflectance => {
                    let l = GLayer {
                        map: self.gmap(&d.map),
                        detail: None,
                    };
                    if d.kind == Kind::Texture {
                        g.modulate = match d.map.modulate {
                            Modulate::Illumination => None,
                            Modulate::Constant(c) => Some(f64::from(c)),
                            Modulate::One => Some(255.0),
                        };
                        g.texture = Some(l);
                    } else {
                        g.base_texture = d.base_texture;
                        g.light_env = d.light_env;
                        g.reflectance = Some(l);
                    }
                    last = Some(d.kind);
                }
                Kind::Offset => {
                    let link = self.file.get(d.link?)?;
                    let target = match last? {
                        Kind::Texture => g.texture.as_mut()?,
                        _ => g.reflectance.as_mut()?,
                    };
                    target.detail = Some(GDetail {
                        offsets: [self.gmap(&d.plane(0)), self.gmap(&d.plane(1))],
                        detail: self.gmap(&link.map),
                        tile_log2: match link.map.border {
                            Border::Tile(t) => Some(u32::from(t)),
                            _ => None,
                        },
                        mode: match link.detail {
                            DetailMode::Replace => Mode::Replace,
                            DetailMode::Multiply => Mode::Multiply,
                            DetailMode::AddSigned => Mode::AddSigned,
                        },
                    });
                }
                Kind::Detail => {}
                Kind::Environment => {
                    if g.reflectance.is_none() {
                        g.base_texture = d.base_texture;
                    }
                    g.env = Some(GEnv {
                        faces: (0..6).map(|p| self.gmap(&d.plane(p))).collect(),
                        k_s: f64::from(d.k_s),
                    });
                }
            }
            k = d.link;
        }
        Some(g)
    }
}

/// The raw request as the golden model's reals, each field scaled by its port's format.
pub fn gpixel(px: &ChainRequest) -> GPixel {
    let f = Pixel::fields();
    let raw = Pixel::of(px);
    let q = |x: &i64, f: &PixelField| *x as f64 * 2f64.powi(-f.fmt.frac());
    GPixel {
        u: q(&raw.u, &f.u),
        v: q(&raw.v, &f.v),
        lambda: q(&raw.lambda, &f.lambda),
        n: std::array::from_fn(|k| q(&raw.n[k], &f.n[k])),
        eye: std::array::from_fn(|k| q(&raw.eye[k], &f.eye[k])),
        i_d: q(&raw.i_d, &f.i_d),
        i_s: q(&raw.i_s, &f.i_s),
    }
}

/// Maps made from a seed: a smooth texture, offsets into 16 x 16 tiles, a detail map, a
/// reflectance map and six faces (each face its own ramp).
pub struct Maps {
    pub texture: Vec<u8>,
    pub offsets: [Vec<u8>; 2],
    pub detail: Vec<u8>,
    pub reflectance: Vec<u8>,
    pub faces: Vec<Vec<u8>>,
}

/// Side of the texture, offset and reflectance maps (64), of the detail map (256) and of a
/// face (32).
pub const TEX_LOG2: u32 = 6;
pub const DETAIL_LOG2: u32 = 8;
pub const FACE_LOG2: u32 = 5;

impl Maps {
    /// The maps with seeded tiles and noise.
    pub fn new(stim: &mut Stimulus) -> Maps {
        let n = 1usize << TEX_LOG2;
        let d = 1usize << DETAIL_LOG2;
        let tiles = stim.draw_n(&(0u8..16), 2 * n * n);
        let noise = stim.draw_n(&(0u8..=255), d * d);
        Maps::with(&tiles, &noise)
    }

    /// The maps from integer formulas only (for the bit-accuracy vectors).
    pub fn formula() -> Maps {
        let hash = |k: usize| (k as u32).wrapping_mul(0x9e37_79b9) >> 13;
        let n = 1usize << TEX_LOG2;
        let d = 1usize << DETAIL_LOG2;
        let tiles: Vec<u8> = (0..2 * n * n).map(|k| (hash(k) % 16) as u8).collect();
        let noise: Vec<u8> = (0..d * d).map(|k| (hash(k + 7) % 256) as u8).collect();
        Maps::with(&tiles, &noise)
    }

    /// The maps with the offsets' tiles (`2 n^2`, 0..16) and the detail's noise given.
    fn with(tiles: &[u8], noise: &[u8]) -> Maps {
        let n = 1usize << TEX_LOG2;
        let smooth = |a: usize, b: usize, x: usize, y: usize| -> u8 {
            let t = ((x * a + y * b) % 128) as i64;
            (64 + (t - 64).abs() * 2).clamp(0, 255) as u8
        };
        let texture = (0..n * n).map(|i| smooth(3, 1, i % n, i / n)).collect();
        let reflectance = (0..n * n).map(|i| smooth(1, 2, i % n, i / n)).collect();
        let offsets = [0, 1].map(|p| {
            tiles[p * n * n..(p + 1) * n * n]
                .iter()
                .map(|t| t * 16)
                .collect()
        });
        let d = 1usize << DETAIL_LOG2;
        // Detail: texels varying inside each tile (a tile's own ramp plus noise).
        let detail = (0..d * d)
            .map(|i| {
                let (x, y) = (i % d, i / d);
                let ramp = ((x % 16) * 8 + (y % 16) * 4 + (x / 16 + y / 16) * 9) % 256;
                ((ramp * 3 + usize::from(noise[i])) / 4) as u8
            })
            .collect();
        let f = 1usize << FACE_LOG2;
        let faces = (0..6)
            .map(|k| {
                (0..f * f)
                    .map(|i| smooth(k + 1, 6 - k, i % f, i / f))
                    .collect()
            })
            .collect();
        Maps {
            texture,
            offsets,
            detail,
            reflectance,
            faces,
        }
    }
}

/// The chain shapes the testbench covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A texture, eq. 5 with I_d.
    Texture,
    /// Texture -> offsets -> detail (tiles, multiply).
    Detail,
    /// The same, replace, the detail continued into the map at tile edges.
    DetailMap,
    /// Texture -> environment (eq. 6).
    Environment,
    /// Texture -> reflectance lit by I_s (eq. 7).
    Reflectance,
    /// The document's longest chain: texture -> offsets -> detail -> reflectance -> offsets
    /// -> detail -> environment (9 accesses below level 0).
    Longest,
    /// Texture -> reflectance -> texture: a cycle, stopped after seven DRFs.
    Cycle,
}

impl Shape {
    pub const ALL: [Shape; 7] = [
        Shape::Texture,
        Shape::Detail,
        Shape::DetailMap,
        Shape::Environment,
        Shape::Reflectance,
        Shape::Longest,
        Shape::Cycle,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Shape::Texture => "texture",
            Shape::Detail => "texture>offset>detail",
            Shape::DetailMap => "texture>offset>detail(map)",
            Shape::Environment => "texture>environment",
            Shape::Reflectance => "texture>reflectance",
            Shape::Longest => "longest",
            Shape::Cycle => "cycle",
        }
    }
}

/// The scene of `shape` over `m`, led by DRF 0.
pub fn scene(shape: Shape, m: &Maps) -> Result<Scene, String> {
    let mut s = Scene::new();
    let t = (TEX_LOG2, TEX_LOG2);
    let (dl, fl) = ((DETAIL_LOG2, DETAIL_LOG2), (FACE_LOG2, FACE_LOG2));
    let tex = s.add(0, Kind::Texture, t, Border::Wrap, vec![m.texture.clone()])?;
    tex.map.modulate = Modulate::Illumination;
    let detail = |s: &mut Scene, k: usize, mode: DetailMode, border: Border| {
        s.add(k, Kind::Offset, t, Border::Wrap, m.offsets.to_vec())?
            .link = Some(k as u8 + 1);
        let d = s.add(k + 1, Kind::Detail, dl, border, vec![m.detail.clone()])?;
        d.detail = mode;
        Ok::<_, String>(())
    };
    let reflectance = |s: &mut Scene, border: Border, light_env: bool| {
        s.add(3, Kind::Reflectance, t, border, vec![m.reflectance.clone()])
            .map(|r| r.light_env = light_env)
    };
    let environment = |s: &mut Scene, k_s: Option<u8>| {
        let e = s.add(6, Kind::Environment, fl, Border::Clamp, m.faces.clone())?;
        e.k_s = k_s.unwrap_or(e.k_s);
        Ok::<_, String>(())
    };
    let links: &[(usize, u8)] = match shape {
        Shape::Texture => &[],
        Shape::Detail => {
            detail(&mut s, 1, DetailMode::Multiply, Border::Tile(4))?;
            &[(0, 1)]
        }
        Shape::DetailMap => {
            detail(&mut s, 1, DetailMode::Replace, Border::Wrap)?;
            &[(0, 1)]
        }
        Shape::Environment => {
            environment(&mut s, Some(160))?;
            &[(0, 6)]
        }
        Shape::Reflectance => {
            reflectance(&mut s, Border::Mirror, false)?;
            &[(0, 3)]
        }
        Shape::Longest => {
            detail(&mut s, 1, DetailMode::AddSigned, Border::Tile(4))?;
            reflectance(&mut s, Border::Wrap, true)?;
            detail(&mut s, 4, DetailMode::Multiply, Border::Tile(4))?;
            environment(&mut s, None)?;
            &[(0, 1), (2, 3), (3, 4), (5, 6)]
        }
        Shape::Cycle => {
            reflectance(&mut s, Border::Wrap, true)?;
            &[(0, 3), (3, 0)]
        }
    };
    for &(from, to) in links {
        if let Some(d) = s.file.drfs[from].as_mut() {
            d.link = Some(to);
        }
    }
    s.file.validate()?;
    Ok(s)
}

/// A fixed-point vector (14 fraction bits) of `v` scaled to length `len`.
fn fixed(v: [f64; 3], len: f64) -> [i64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| (c / l * len * 16384.0).round() as i64)
}

/// Random pixels: u, v over the map and a texel beyond, lambda over -4 ..= 10 (half of them
/// below 0, every eighth exactly on an integer, the first six one in each unit from -4 to 2),
/// perturbed normals of length 0.7 to 1.3 facing +z, unit eye vectors facing +z, random I_d
/// and I_s; then six whose reflection points to each face in turn (at least twelve pixels,
/// so that every coverage bin is hit whatever the count).
pub fn pixels(n: usize, stim: &mut Stimulus) -> Vec<ChainRequest> {
    let mut px = random_pixels(n.max(6), stim);
    let one = 1i64 << 14;
    let (a, b) = (16220i64, 2290i64);
    // Normal, eye: w = 2 n (n . v) - v |n|^2 points to +x, -x, +y, -y, +z, -z.
    let faces = [
        ([0, 0, one], [-a, 0, b]),
        ([0, 0, one], [a, 0, b]),
        ([0, 0, one], [0, -a, b]),
        ([0, 0, one], [0, a, b]),
        ([0, 0, one], [0, 0, one]),
        ([one, 0, 0], [0, 0, one]),
    ];
    for (k, (nrm, eye)) in faces.into_iter().enumerate() {
        px.push(ChainRequest {
            n: nrm,
            eye,
            ..px[k]
        });
    }
    px
}

fn random_pixels(n: usize, stim: &mut Stimulus) -> Vec<ChainRequest> {
    let side = 256i32 << TEX_LOG2;
    (0..n)
        .map(|i| {
            // The first six cover every coverage range of lambda whatever the count.
            let lambda = match i % 8 {
                _ if i < 6 => ((i as i32 - 4) << 8) + stim.draw(&(0i32..256)),
                0 => stim.draw(&(-4i32..=10)) << 8,
                1..=4 => stim.draw(&(-1024i32..0)),
                _ => stim.draw(&(-1024i32..=2560)),
            };
            let dir = |stim: &mut Stimulus| {
                let x = stim.draw(&(-1000i32..=1000));
                let y = stim.draw(&(-1000i32..=1000));
                let z = stim.draw(&(200i32..=1000));
                [x, y, z].map(f64::from)
            };
            let len = f64::from(stim.draw(&(70i32..=130))) / 100.0;
            let n = fixed(dir(stim), len);
            let eye = fixed(dir(stim), 0.999);
            ChainRequest {
                drf: 0,
                u: stim.draw(&(-256..side + 256)),
                v: stim.draw(&(-256..side + 256)),
                lambda,
                n,
                eye,
                face: 0,
                i_d: stim.draw(&(0u8..=255)),
                i_s: stim.draw(&(0u8..=255)),
            }
        })
        .collect()
}

/// A pixel's chain result, in a cycle with `out_valid` high.
pub fn sample_chain<T: TexramAccess>(dut: &MapChain812<T>) -> Option<ChainResult> {
    dut.out_valid.q().is_high().then(|| dut.result())
}

/// The lambda range a pixel falls in (the coverage bins).
pub fn lambda_bin(lambda: i32) -> i64 {
    match lambda >> 8 {
        l if l < 0 => i64::from(l + 4),
        0 => 4,
        _ => 5,
    }
}

fn coverage_model() -> Coverage {
    let mut c = Coverage::new();
    let mut shape = Coverpoint::new("shape");
    for (i, s) in Shape::ALL.iter().enumerate() {
        shape = shape.value(s.name(), i as i64);
    }
    let shape = c.add(shape);
    let lambda = c.add(
        Coverpoint::new("lambda").values(&["-4..-3", "-3..-2", "-2..-1", "-1..0", "0..1", "1..10"]),
    );
    let mut face = Coverpoint::new("face");
    for (i, f) in units::envmap::cube_face::FACES.iter().enumerate() {
        face = face.value(f, i as i64);
    }
    c.add(face.value("none", 6));
    c.add(
        Coverpoint::new("accesses")
            .value("1", 1)
            .value("2", 2)
            .value("3", 3)
            .value("4", 4)
            .bin("5..=9", 5, 9),
    );
    c.cross("shape_x_lambda", shape, lambda);
    c
}

/// What a pixel should give: the micro-program's result on a second copy of the banks, the
/// golden colour and bound (`None`: the chain must be flagged), whether the face is
/// ambiguous, and the cycles from acceptance to the result.
#[derive(Clone, Debug)]
pub struct Expected {
    pub px: ChainRequest,
    pub reference: ChainResult,
    pub golden: Option<golden::mapchain::Bounded>,
    pub ambiguous: bool,
    pub latency: u64,
    pub face: i64,
}

/// The expectations of `px` on `scene`, in order (the banks' open rows carry over).
pub fn expectations(scene: &Scene, px: &[ChainRequest]) -> Result<Vec<Expected>, String> {
    let mut stub = scene.stub()?;
    let chain = scene.golden(0);
    let env_coords = chain.as_ref().is_some_and(|c| c.env.is_some());
    px.iter()
        .map(|q| {
            let reference = walk_pixel(&scene.file, &mut stub, q)?;
            let g = chain
                .as_ref()
                .map(|c| golden::mapchain::pixel(c, &gpixel(q)));
            let face = if env_coords {
                let p = gpixel(q);
                let w = golden::envmap::reflect(p.n, p.eye);
                i64::from(golden::envmap::face_st(w).0)
            } else {
                6
            };
            let extra = 1 + u64::from(env_coords && !reference.error);
            Ok(Expected {
                px: *q,
                reference,
                golden: g.map(|x| x.0),
                ambiguous: g.is_some_and(|x| x.1),
                latency: u64::from(reference.slots) * u64::from(SLOT_CYCLES) + extra,
                face,
            })
        })
        .collect()
}

/// One pixel's comparison.
fn compare(e: &Expected, got: &ChainResult) -> Result<(), String> {
    if *got != e.reference {
        return Err(format!("walker {got:?}, micro-program {:?}", e.reference));
    }
    match (e.golden, got.error) {
        (None, true) => Ok(()),
        (None, false) => Err("a looping chain was not flagged".into()),
        (Some(_), true) => Err("flagged a chain that ends".into()),
        (Some(_), false) if e.ambiguous => Ok(()),
        (Some(g), false) if (f64::from(got.colour) - g.x).abs() <= g.e => Ok(()),
        (Some(g), false) => Err(format!(
            "colour {} is {:.2} from the golden {:.3} (bound {:.2})",
            got.colour,
            (f64::from(got.colour) - g.x).abs(),
            g.x,
            g.e
        )),
    }
}

/// The testbench's configurations: every shape on the stub, then the longest chain on the
/// cycle-accurate chip 802.
fn config(index: usize) -> (Shape, bool) {
    Shape::ALL
        .get(index)
        .map_or((Shape::Longest, true), |s| (*s, false))
}

/// The regress testbench.
pub struct WalkerTb;

impl Testbench for WalkerTb {
    fn about(&self) -> About {
        About::new(NAME, "chain walker of 812 with detail (Fig. 9), reflectance (eq. 7) and environment maps (eqs 4, 6) (Schilling & Knittel section 14, Fig. 16)")
            .count(400, "random pixels")
            // The waveform of the longest chain on the stub: every state of the walker appears.
            .traced(5)
    }
    fn configurations(&self) -> Vec<String> {
        (0..=Shape::ALL.len())
            .map(|i| match config(i) {
                (s, false) => s.name().to_string(),
                (s, true) => format!("{} on the chip 802", s.name()),
            })
            .collect()
    }
    fn coverage(&self) -> Coverage {
        coverage_model()
    }
    fn conclude(&self, merged: &mut TbResult) {
        conclude_timings(merged);
    }
    fn run(&self, ctx: &Ctx) -> Result<TbResult, String> {
        let (shape, on_chip) = config(ctx.index);
        let mut stim = Stimulus::new(ctx.seed);
        let maps = Maps::new(&mut stim);
        let sc = scene(shape, &maps)?;
        let count = if on_chip {
            ctx.count / 4 + 1
        } else {
            ctx.count
        };
        let px = pixels(count, &mut stim);
        let want = expectations(&sc, &px)?;
        let title = format!("{NAME} {}", ctx.label);
        let mut res = if on_chip {
            let mut chip = units::texram::texram_802::Texram802::new(Default::default())?;
            sc.load_chip(&mut chip)?;
            let acc = units::texram::texram_802::Texram802Access::new(chip);
            let dut = MapChain812::new(sc.file.clone(), acc, SLOT_CYCLES)?;
            run_pixels(ctx.sim(dut, &title, CYCLE_PS, |_| ())?.0, ctx, shape, want)?
        } else {
            let dut = MapChain812::new(sc.file.clone(), sc.stub()?, SLOT_CYCLES)?;
            run_pixels(ctx.sim(dut, &title, CYCLE_PS, |_| ())?.0, ctx, shape, want)?
        };
        res.notes
            .insert(0, format!("{}: {count} pixels", ctx.label));
        Ok(res)
    }
}

impl Scene {
    /// Writes every map into the chip's banks.
    pub fn load_chip(&self, chip: &mut units::texram::texram_802::Texram802) -> Result<(), String> {
        for (d, texels) in &self.maps {
            chip.load_map(d, texels)?;
        }
        Ok(())
    }
}

/// Drives the pixels with random gaps and scores them; writes the waveform if traced.
fn run_pixels<A: TexramAccess>(
    mut sim: Sim<MapChain812<A>, VcdTracer>,
    ctx: &Ctx,
    shape: Shape,
    want: Vec<Expected>,
) -> Result<TbResult, String> {
    let mut res = TbResult::new(NAME, "");
    let mut cov = coverage_model();
    sim.reset(2);
    let mut sb: Scoreboard<Expected, ChainResult> = Scoreboard::new(compare);
    let n = want.len() as u64;
    let px: Vec<ChainRequest> = want.iter().map(|w| w.px).collect();
    let mut pending = want.into_iter();
    let mut sent = std::collections::VecDeque::new();
    let mut late = 0u64;
    let pacing = Pacing::random(200, ctx.seed.derive(9));
    let mut spec = RunSpec::new(n, 120 * n + 200).pacing(pacing);
    let si = Shape::ALL.iter().position(|s| *s == shape).unwrap_or(0) as i64;
    let (mut slots, mut faults) = (0u64, 0u64);
    let r = run_scored(
        &mut sim,
        &mut StreamDriver::new(verif::stream!(MapChain812<A>, req)),
        &mut PinMonitor::new(sample_chain),
        px,
        &mut spec,
        |_, ev| match ev {
            Scored::Sent { cycle, .. } => {
                sent.push_back(cycle);
                sb.expect(pending.next().expect("one a pixel"));
            }
            Scored::Received { cycle, txn } => {
                let at = sent.pop_front().unwrap_or(cycle);
                if let Some(e) = sb.observe(cycle, txn).expected {
                    late += u64::from(cycle - at != e.latency);
                    if let (Some(g), false) = (e.golden, txn.error || e.ambiguous) {
                        res.stats.record(f64::from(txn.colour), g.x, 1.0);
                    }
                    slots += u64::from(txn.slots);
                    faults += u64::from(txn.faults);
                    let acc = i64::from(txn.accesses);
                    cov.sample(&[si, lambda_bin(e.px.lambda), e.face, acc]);
                }
            }
        },
    );
    res.score(&sb);
    res.ran(&r);
    if late > 0 {
        res.failures.push(format!(
            "{late} pixels out at a cycle other than slots x {SLOT_CYCLES} + coordinates + 1"
        ));
    }
    if let Some(e) = sim.dut.banks.error.take() {
        res.failures
            .push(format!("the banks refused an access: {e}"));
    }
    res.notes.push(format!(
        "{}: {:.2} slots and {:.2} faulting accesses a pixel; colour within {:.2} LSB of the golden model (its derived bound per pixel)",
        ctx.label,
        slots as f64 / n.max(1) as f64,
        faults as f64 / n.max(1) as f64,
        res.stats.max_abs_lsb
    ));
    res.coverage = Some(cov);
    ctx.finish(sim, &mut res)?;
    Ok(res)
}

/// The timings as a report table, notes and (outside 10 % of the document) failures.
pub fn conclude_timings(merged: &mut TbResult) {
    let mut table = String::from(
        "| section 14 chain (pixels along a row) | accesses a pixel | faulting accesses a pixel | ns a pixel | M pixels/s | document |\n|---|---|---|---|---|---|\n",
    );
    let rows = match timings() {
        Ok(r) => r,
        Err(e) => return merged.failures.push(e),
    };
    for t in rows {
        let doc = t
            .document_ns
            .map_or("-".into(), |d| format!("about {d:.0} ns"));
        table.push_str(&format!(
            "| {} | {:.2} | {:.2} | {:.1} | {:.2} | {doc} |\n",
            t.what,
            t.accesses,
            t.faults,
            t.ns,
            1e3 / t.ns
        ));
        merged.notes.push(format!(
            "{}: {:.1} ns a pixel, {:.2} accesses of which {:.2} faulted",
            t.what, t.ns, t.accesses, t.faults
        ));
        if let Some(d) = t.document_ns.filter(|d| (t.ns / d - 1.0).abs() > 0.10) {
            merged.failures.push(format!(
                "{}: {:.1} ns a pixel, not within 10 % of the document's {d:.0}",
                t.what, t.ns
            ));
        }
    }
    merged.tables.push(table);
}
