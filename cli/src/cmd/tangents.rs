//! `texrtl tangents`: a mesh's tangent frames per face corner in 003's three modes (the
//! host's side, f64; the fixed-point setup unit is verified by the `tangent_setup`
//! testbench).

use super::{input, write_out, CmdError};
use std::fmt::Write;
use std::path::PathBuf;
use tb::runs::tangents::{frames, Mode};

/// Tangent frames of a mesh, one row per face corner (003).
#[derive(Clone, Debug, clap::Args)]
pub struct TangentsArgs {
    /// Wavefront OBJ with texture coordinates on every face (v, vt, optional vn, f, s).
    #[arg(long)]
    pub mesh: PathBuf,
    /// CSV: face,corner,tx,ty,tz,bx,by,bz,nx,ny,nz,zero (faces and corners from 0).
    #[arg(long)]
    pub out: PathBuf,
    /// max (face normal, the face's T and B), maya (vertex normal, smoothed T and B as they
    /// are) or directx (vertex normal, smoothed T orthogonalised per vertex).
    #[arg(long, default_value = "max")]
    pub mode: String,
}

/// `texrtl tangents`.
pub fn run(a: &TangentsArgs) -> Result<String, CmdError> {
    let guard = super::Outputs::check(
        &[("--out", a.out.as_path())],
        &[("--mesh", a.mesh.as_path())],
    )?;
    guard.settle(tangents(a))
}

fn tangents(a: &TangentsArgs) -> Result<String, CmdError> {
    let mode = Mode::parse(&a.mode).ok_or_else(|| {
        input(format!(
            "--mode {}: max, maya or directx",
            formats::shorten(&a.mode)
        ))
    })?;
    let mesh = formats::obj::read(&a.mesh).map_err(input)?;
    let rows = frames(&mesh, mode);
    let mut csv = String::from("face,corner,tx,ty,tz,bx,by,bz,nx,ny,nz,zero\n");
    let mut zero = 0;
    for r in &rows {
        let f = &r.frame;
        let v = |x: [f64; 3]| format!("{:.6},{:.6},{:.6}", x[0], x[1], x[2]);
        zero += usize::from(f.zero);
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{}",
            r.face,
            r.corner,
            v(f.t),
            v(f.b),
            v(f.n),
            u8::from(f.zero)
        );
    }
    write_out(&a.out, csv.as_bytes())?;
    Ok(format!(
        "{} corners of {} faces written to {} ({zero} without a tangent: UVs degenerate)",
        rows.len(),
        mesh.faces.len(),
        a.out.display()
    ))
}
