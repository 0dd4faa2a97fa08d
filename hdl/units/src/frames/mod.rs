//! Tangent frames (003) and the per-pixel frame unit (003, 002): the per-triangle tangent
//! setup unit, and the unit that perturbs a pixel's normal in its frame (bump maps, normal
//! maps), and parallax mapping (002).
//!
//! ## Tangent frames, the per-pixel frame unit and parallax (003, 002)
//!
//! * **Tangent setup** (`hdl/units/src/frames/tangent_setup.rs`): per triangle `dP/du = (d1.y v2 - d2.y
//!   v1) / uvk`, `dP/dv = (d2.x v1 - d1.x v2) / uvk` with `uvk = d2.x d1.y - d1.x d2.y` exact and
//!   `1/uvk` by the cube-face unit's reciprocal (table + Newton: it scales both alike, so the
//!   directions are exact); UVs on a line fall back to `v1/d1.x`, `v2/d2.x`, or zero, flagged,
//!   never NaN; `t` by Gram-Schmidt through 156's rsqrt, `b = s n x t` with the **general**
//!   handedness `s = sign((n x t) . dP/dv)`: the seed's flip looks at the UV winding only and is
//!   wrong for triangles winding clockwise about n (`golden::tangents` tests both).
//!   `tangent_setup` testbench: 0.57 LSB from f64 on 3,000 random triangles (degenerate and
//!   mirrored included).
//! * **Host frames** (`tb/src/tangents.rs`, `texrtl tangents --mesh M.obj --out T.csv
//!   \[--mode max|maya|directx\]`, one row `face,corner,tx,ty,tz,bx,by,bz,nx,ny,nz,zero` per face
//!   corner): 3ds Max (face normal, the face's T and B orthonormalised), Maya (vertex normal,
//!   smoothed T and B as they are: the frame unit re-orthogonalises per pixel), DirectX (vertex
//!   normal, smoothed T orthogonalised per vertex). Vertex normals from the OBJ or summed over
//!   the smoothing group; tangents summed over faces sharing position, UV and group; polygons
//!   as fans. Tests: T.N = 0, |T| = 1, B = +-N x T, a planar mapping gives T along u, mirrored
//!   UV halves give opposite handedness (away from an unsplit seam), degenerate UVs no NaN.
//! * **Frame unit** (`frames/frame_unit.rs`): optional Gram-Schmidt, then `n' = a N + gx T + gy
//!   B` normalised through 156's rsqrt. Bumps: `a = 1`, `(gx, gy) = -grad h` (003's listing adds
//!   `+dM` and calls the sum a unit vector: both wrong, tested); normal maps: RGB8 as `c - 128`
//!   \[C\] (a flat texel is exactly N) or `2c - 255`; 002's listing reads the colour as the vector
//!   itself (tested to tilt a flat texel). `frame_unit` testbench: within the derived bound
//!   (0.59 LSB a normalisation, wider through Gram-Schmidt), measured 1.55 LSB.
//! * **Parallax** (`frames/parallax.rs`): `uv + h V.xy / V.z`, `h = height scale + bias`, V.z held
//!   to at least 1/8 \[C\], the reciprocal by table + Newton; the offset-limited `uv + h V.xy`.
//!   A cancelled height moves nothing exactly; `parallax` testbench within half an LSB plus the
//!   reciprocal's error.

pub mod frame_unit;
pub mod parallax;
pub mod tangent_setup;
