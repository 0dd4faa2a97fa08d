//! The chain walker's micro-program (section 14): what unit 812 does after each access of a
//! pixel's chain, as a pure function of the DRF file, the pixel and the walk so far. The
//! clocked walker [`super::walker_812`] runs it one access per state; it is kept apart so
//! that the program reads as the document describes it:
//!
//! * **texture / reflectance**: read at the pixel's (u, v, lambda), unless lambda < 0 and
//!   the DRF links to offset maps: then the read waits for the detail (a third step, only if
//!   the detail needs it);
//! * **offset**: only for lambda < 0: the u and v offset maps at the pixel's level-0 texel;
//! * **detail**: only for lambda < 0: the detail map in the offsets' tile, then the waiting
//!   texel if [`needs_texel`], combined by step 912;
//! * **environment**: new coordinates first (eq. 4 and the cube face, one state), then the
//!   face's mipmap at lambda `max(lambda, 0)` \[C\]; without `new_coords` the rasterizer's face
//!   and (u, v) \[C\];
//! * then the DRF's link, or the output stage 820 (eqs 5-7) at the chain's end.
//!
//! Going to a DRF costs no cycle (812 decodes the next DRF while the last access runs); a
//! chain that visits more than seven DRFs stops with the error flag, as does a detail map
//! reached without offsets, an unset DRF or a reflectance lit by an environment the chain does
//! not read.

use super::detail_fig9::{detail_coord, detail_lambda, needs_texel, offset_point, step_912};
use super::drf_812::{DrfFile, Kind};
use crate::envmap::cube_face::{face_st, ST_FRAC};
use crate::envmap::reflect_eq4::reflect;
use crate::texram::output_820::{combine, environment, reflectance};
use crate::texram::{TexramRequest, DRFS, FRAC};

/// The walker's states; their names appear in the waveform.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum State {
    #[default]
    Idle,
    Texture,
    OffsetU,
    OffsetV,
    Detail,
    DetailBase,
    Reflectance,
    EnvCoords,
    Environment,
    Combine,
    Error,
}

/// The states' names by value.
pub const STATES: [&str; 11] = [
    "IDLE",
    "TEXTURE",
    "OFFSET_U",
    "OFFSET_V",
    "DETAIL",
    "DETAIL_BASE",
    "REFLECTANCE",
    "ENV_COORDS",
    "ENVIRONMENT",
    "COMBINE",
    "ERROR",
];

impl State {
    const ALL: [State; 11] = [
        State::Idle,
        State::Texture,
        State::OffsetU,
        State::OffsetV,
        State::Detail,
        State::DetailBase,
        State::Reflectance,
        State::EnvCoords,
        State::Environment,
        State::Combine,
        State::Error,
    ];

    pub fn from_bits(b: u64) -> State {
        State::ALL.get(b as usize).copied().unwrap_or(State::Error)
    }

    pub fn bits(self) -> u64 {
        State::ALL.iter().position(|s| *s == self).unwrap_or(0) as u64
    }

    /// A state that waits for an access to the banks.
    pub fn reads(self) -> bool {
        !matches!(
            self,
            State::Idle | State::EnvCoords | State::Combine | State::Error
        )
    }
}

/// One pixel as the rasterizer sends it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ChainRequest {
    /// The leading DRF.
    pub drf: u8,
    /// sQ12.8 and sQ5.8 raw, as a plain access.
    pub u: i32,
    pub v: i32,
    pub lambda: i32,
    /// The perturbed normal n_b (eq. 3), sQ2.14 raw, and the unit vector to the eye, sQ1.14.
    pub n: [i64; 3],
    pub eye: [i64; 3],
    /// The face (0 ..= 5) when an environment DRF has no `new_coords`.
    pub face: u8,
    /// Diffuse illumination I_d and external specular term I_s.
    pub i_d: u8,
    pub i_s: u8,
}

impl ChainRequest {
    pub fn validate(&self) -> Result<(), String> {
        TexramRequest {
            drf: self.drf,
            u: self.u,
            v: self.v,
            lambda: self.lambda,
        }
        .validate()?;
        for (name, vec, bits) in [("n", self.n, 17), ("eye", self.eye, 16)] {
            let lim = 1i64 << (bits - 1);
            if vec.iter().any(|c| !(-lim..lim).contains(c)) {
                return Err(format!("{name} {vec:?}: outside sQ{}.14", bits - 15));
            }
        }
        if self.face > 5 {
            return Err(format!("face {}: 0..=5", self.face));
        }
        Ok(())
    }
}

/// An access the walker asks the banks for: plane `plane` of DRF `drf` at raw (u, v,
/// lambda).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fetch {
    pub drf: u8,
    pub plane: u8,
    pub u: i32,
    pub v: i32,
    pub lambda: i32,
}

/// "No DRF" in the walk's DRF registers.
pub const NONE: u8 = DRFS as u8;

/// What the walker holds between states for its pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Walk {
    pub state: State,
    /// The DRF being worked on and the DRFs visited.
    pub drf: u8,
    pub steps: u8,
    /// The texture's or reflectance's read waits for the detail.
    pub deferred: bool,
    /// The detail applies to the reflectance (else the texture).
    pub to_refl: bool,
    pub tex: u8,
    pub refl: u8,
    pub env: u8,
    pub ou: u8,
    pub ov: u8,
    pub offsets: bool,
    pub detail: u8,
    /// The DRFs of the chain's texture, reflectance and environment ([`NONE`] if none).
    pub tex_drf: u8,
    pub refl_drf: u8,
    pub env_drf: u8,
    /// The environment face of eq. 4's vector and its coordinates (uQ0.12).
    pub face: u8,
    pub s: u16,
    pub t: u16,
}

impl Walk {
    /// A pixel's walk before its first DRF.
    pub fn start() -> Walk {
        Walk {
            state: State::Idle,
            drf: NONE,
            steps: 0,
            deferred: false,
            to_refl: false,
            tex: 0,
            refl: 0,
            env: 0,
            ou: 0,
            ov: 0,
            offsets: false,
            detail: 0,
            tex_drf: NONE,
            refl_drf: NONE,
            env_drf: NONE,
            face: 0,
            s: 0,
            t: 0,
        }
    }
}

/// The micro-program's context: the DRFs, the pixel and the reciprocal table of the face
/// selection.
pub struct Program<'a> {
    pub file: &'a DrfFile,
    pub px: &'a ChainRequest,
    pub tab: &'a [u64; 64],
}

impl Program<'_> {
    /// The first DRF of the pixel.
    pub fn begin(&self) -> (Walk, Option<Fetch>) {
        self.visit(Walk::start(), self.px.drf)
    }

    /// The walk after its state's access gave `value` (or after a state without access).
    pub fn advance(&self, mut w: Walk, value: u8) -> (Walk, Option<Fetch>) {
        let px = self.px;
        match w.state {
            State::Texture => w.tex = value,
            State::Reflectance => w.refl = value,
            State::OffsetU => {
                w.ou = value;
                w.state = State::OffsetV;
                let at = (offset_point(px.u), offset_point(px.v));
                return (w, Some(self.fetch(w.drf, 1, at, 0)));
            }
            State::OffsetV => {
                w.ov = value;
                w.offsets = true;
            }
            State::Detail => {
                w.detail = value;
                if w.deferred && needs_texel(self.mode(w.drf), px.lambda) {
                    w.state = State::DetailBase;
                    let k = if w.to_refl { w.refl_drf } else { w.tex_drf };
                    return (w, Some(self.fetch(k, 0, (px.u, px.v), px.lambda)));
                }
                self.apply_detail(&mut w, value, None);
            }
            State::DetailBase => {
                let d = w.detail;
                self.apply_detail(&mut w, d, Some(value));
            }
            State::EnvCoords => {
                w.state = State::Environment;
                let lg = self.file.get(w.drf).map_or(4, |d| d.map.width_log2);
                let at = |c: u16| i32::from(c) << lg >> (ST_FRAC - FRAC);
                let f = self.fetch(w.drf, w.face, (at(w.s), at(w.t)), px.lambda.max(0));
                return (w, Some(f));
            }
            State::Environment => w.env = value,
            State::Idle | State::Combine | State::Error => return (w, None),
        }
        let link = self.file.get(w.drf).and_then(|d| d.link);
        match link {
            Some(k) => self.visit(w, k),
            None => self.finish(w),
        }
    }

    fn mode(&self, k: u8) -> super::drf_812::DetailMode {
        self.file.get(k).map(|d| d.detail).unwrap_or_default()
    }

    /// Step 912 into the detail's target; the detail is used up with its offsets.
    fn apply_detail(&self, w: &mut Walk, d: u8, texel: Option<u8>) {
        let t = texel.unwrap_or(if w.to_refl { w.refl } else { w.tex });
        let x = step_912(self.mode(w.drf), self.px.lambda, d, t);
        if w.to_refl {
            w.refl = x;
        } else {
            w.tex = x;
        }
        w.offsets = false;
        w.deferred = false;
    }

    fn fetch(&self, drf: u8, plane: u8, (u, v): (i32, i32), lambda: i32) -> Fetch {
        Fetch {
            drf,
            plane,
            u,
            v,
            lambda,
        }
    }

    /// Goes to DRF `k` and on along its links until an access or the chain's end.
    fn visit(&self, mut w: Walk, mut k: u8) -> (Walk, Option<Fetch>) {
        let px = self.px;
        let below0 = px.lambda < 0;
        loop {
            w.steps += 1;
            let Some(d) = self.file.get(k).filter(|_| w.steps <= DRFS as u8) else {
                w.state = State::Error;
                return (w, None);
            };
            w.drf = k;
            let whole = (px.u, px.v);
            match d.kind {
                Kind::Texture | Kind::Reflectance => {
                    let refl = d.kind == Kind::Reflectance;
                    w.to_refl = refl;
                    *(if refl {
                        &mut w.refl_drf
                    } else {
                        &mut w.tex_drf
                    }) = k;
                    let to_offsets = d
                        .link
                        .and_then(|l| self.file.get(l))
                        .is_some_and(|l| l.kind == Kind::Offset);
                    w.deferred = below0 && to_offsets;
                    if !w.deferred {
                        w.state = if refl {
                            State::Reflectance
                        } else {
                            State::Texture
                        };
                        return (w, Some(self.fetch(k, 0, whole, px.lambda)));
                    }
                }
                Kind::Offset if below0 => {
                    w.state = State::OffsetU;
                    let at = (offset_point(px.u), offset_point(px.v));
                    return (w, Some(self.fetch(k, 0, at, 0)));
                }
                Kind::Detail if below0 => {
                    if !w.offsets {
                        w.state = State::Error;
                        return (w, None);
                    }
                    w.state = State::Detail;
                    let at = (detail_coord(w.ou, px.u), detail_coord(w.ov, px.v));
                    return (w, Some(self.fetch(k, 0, at, detail_lambda(px.lambda))));
                }
                Kind::Offset | Kind::Detail => {}
                Kind::Environment => {
                    w.env_drf = k;
                    if d.new_coords {
                        let r = reflect(px.n, px.eye);
                        let (face, s, t) = face_st(r, self.tab);
                        (w.face, w.s, w.t) = (face, s as u16, t as u16);
                        w.state = State::EnvCoords;
                        return (w, None);
                    }
                    if px.face > 5 {
                        w.state = State::Error;
                        return (w, None);
                    }
                    w.state = State::Environment;
                    return (w, Some(self.fetch(k, px.face, whole, px.lambda.max(0))));
                }
            }
            match d.link {
                Some(l) => k = l,
                None => return self.finish(w),
            }
        }
    }

    /// The chain's end: the output stage 820 next.
    fn finish(&self, mut w: Walk) -> (Walk, Option<Fetch>) {
        let lit_by_nothing = self
            .file
            .get(w.refl_drf)
            .is_some_and(|r| r.light_env && w.env_drf == NONE);
        w.state = if lit_by_nothing || w.deferred {
            State::Error
        } else {
            State::Combine
        };
        (w, None)
    }

    /// The output stage 820 on a finished walk: eq. 5, then eq. 6 or 7.
    pub fn colour(&self, w: &Walk) -> u8 {
        let px = self.px;
        let cd = match self.file.get(w.tex_drf) {
            Some(t) => combine(t.map.modulate, px.i_d, w.tex),
            None => px.i_d,
        };
        let base = |k: u8| match self.file.get(k) {
            Some(d) if !d.base_texture => px.i_d,
            _ => cd,
        };
        if let Some(r) = self.file.get(w.refl_drf) {
            let light = if r.light_env { w.env } else { px.i_s };
            return reflectance([base(w.refl_drf); 4], [w.refl; 4], [light; 4])[0];
        }
        if let Some(e) = self.file.get(w.env_drf) {
            return environment([base(w.env_drf); 4], e.k_s, [w.env; 4])[0];
        }
        cd
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every field against its format, at both sides of each limit.
    #[test]
    fn requests_are_checked_against_their_formats() {
        let ok = ChainRequest {
            drf: 6,
            u: 100,
            v: -100,
            lambda: -4 << 8,
            n: [(1 << 16) - 1, -(1 << 16), 0],
            eye: [(1 << 15) - 1, -(1 << 15), 0],
            face: 5,
            i_d: 255,
            i_s: 0,
        };
        assert!(ok.validate().is_ok());
        let bad = [
            ChainRequest { drf: 7, ..ok },
            ChainRequest {
                lambda: (10 << 8) + 1,
                ..ok
            },
            ChainRequest {
                n: [1 << 16, 0, 0],
                ..ok
            },
            ChainRequest {
                n: [0, 0, -(1 << 16) - 1],
                ..ok
            },
            ChainRequest {
                eye: [0, 1 << 15, 0],
                ..ok
            },
            ChainRequest {
                eye: [-(1 << 15) - 1, 0, 0],
                ..ok
            },
            ChainRequest { face: 6, ..ok },
        ];
        for b in bad {
            assert!(b.validate().is_err(), "{b:?}");
        }
        let e = ChainRequest {
            n: [1 << 16, 0, 0],
            ..ok
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("sQ2.14"), "{e}");
        let e = ChainRequest {
            eye: [1 << 15, 0, 0],
            ..ok
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("sQ1.14"), "{e}");
    }
}
