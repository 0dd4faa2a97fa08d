//! `texrtl tangents`: the host's per-corner tangent frames of a mesh in the seed's three modes
//! (003), in `f64`: the tool chain's side of what the tangent setup unit computes in hardware.
//!
//! Host \[C\]: a polygon's dP/du, dP/dv are the mean of its fan triangles'; its normal the
//! normalised sum of their cross products. Vertex normals: the OBJ's where given, else the
//! sum of the face normals (area-weighted) over the faces sharing the position and the
//! smoothing group (group 0: the face's own). Smoothed tangents: the sum of the faces' unit
//! dP/du (and dP/dv) over faces sharing position, texture coordinate and group.

use formats::obj::Mesh;
use golden::tangents::{add, cross, face_tangent, normalize, orthonormal, scale, Frame};
use std::collections::HashMap;

/// The seed's three ways of making a corner's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The face normal, the face's T and B orthonormalised.
    Max,
    /// The vertex normal, the smoothed T and B as they are (normalised, not orthogonal).
    Maya,
    /// The vertex normal, the smoothed T orthogonalised per vertex, B = s n x t.
    DirectX,
}

impl Mode {
    pub fn parse(s: &str) -> Option<Mode> {
        match s {
            "max" => Some(Mode::Max),
            "maya" => Some(Mode::Maya),
            "directx" => Some(Mode::DirectX),
            _ => None,
        }
    }
}

/// A polygon's tangents and normal.
struct FaceGeom {
    dpdu: [f64; 3],
    dpdv: [f64; 3],
    /// Unnormalised (twice the area).
    area_n: [f64; 3],
}

fn face_geom(m: &Mesh, f: &formats::obj::Face) -> FaceGeom {
    let c = &f.corners;
    let mut g = FaceGeom {
        dpdu: [0.0; 3],
        dpdv: [0.0; 3],
        area_n: [0.0; 3],
    };
    for k in 1..c.len() - 1 {
        let tri = [c[0], c[k], c[k + 1]];
        let p = tri.map(|x| m.positions[x.p]);
        let uv = tri.map(|x| m.uvs[x.t]);
        let ft = face_tangent(p, uv);
        g.dpdu = add(g.dpdu, ft.dpdu);
        g.dpdv = add(g.dpdv, ft.dpdv);
        let e = cross(
            golden::tangents::sub(p[1], p[0]),
            golden::tangents::sub(p[2], p[0]),
        );
        g.area_n = add(g.area_n, e);
    }
    let k = 1.0 / (c.len() - 2) as f64;
    (g.dpdu, g.dpdv) = (scale(g.dpdu, k), scale(g.dpdv, k));
    g
}

/// Summed unit dP/du and dP/dv at a (position, texture coordinate, group).
type Pair = ([f64; 3], [f64; 3]);

/// One row of the output: face, corner and its frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerFrame {
    pub face: usize,
    pub corner: usize,
    pub frame: Frame,
}

/// Every corner's frame of `m` in `mode`.
pub fn frames(m: &Mesh, mode: Mode) -> Vec<CornerFrame> {
    let geom: Vec<FaceGeom> = m.faces.iter().map(|f| face_geom(m, f)).collect();
    let mut vn: HashMap<(usize, u32), [f64; 3]> = HashMap::new();
    let mut vt: HashMap<(usize, usize, u32), Pair> = HashMap::new();
    for (f, g) in m.faces.iter().zip(&geom) {
        for c in &f.corners {
            if f.smoothing != 0 {
                let e = vn.entry((c.p, f.smoothing)).or_insert([0.0; 3]);
                *e = add(*e, g.area_n);
            }
            let e = vt
                .entry((c.p, c.t, f.smoothing))
                .or_insert(([0.0; 3], [0.0; 3]));
            *e = (add(e.0, normalize(g.dpdu).0), add(e.1, normalize(g.dpdv).0));
        }
    }
    let mut out = Vec::new();
    for (fi, (f, g)) in m.faces.iter().zip(&geom).enumerate() {
        let face_n = normalize(g.area_n).0;
        for (ci, c) in f.corners.iter().enumerate() {
            let vertex_n = match (c.n, f.smoothing) {
                (Some(k), _) => normalize(m.normals[k]).0,
                (None, 0) => face_n,
                (None, s) => normalize(vn[&(c.p, s)]).0,
            };
            let (t, b) = vt[&(c.p, c.t, f.smoothing)];
            let frame = match mode {
                Mode::Max => orthonormal(face_n, g.dpdu, g.dpdv),
                Mode::DirectX => orthonormal(vertex_n, t, b),
                Mode::Maya => {
                    let (tn, ok) = normalize(t);
                    Frame {
                        t: tn,
                        b: normalize(b).0,
                        n: vertex_n,
                        zero: !ok,
                    }
                }
            };
            out.push(CornerFrame {
                face: fi,
                corner: ci,
                frame,
            });
        }
    }
    out
}
