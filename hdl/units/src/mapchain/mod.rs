//! Map linking (Schilling & Knittel section 14, Fig. 16) with the maps it links: detail maps
//! (section 9, Figs 9a/9b), reflectance maps (section 8, eq. 7) and environment maps
//! (section 7; the reflection vector and the cube face are in [`crate::envmap`]).
//!
//! * [`drf_812`](crate::mapchain::drf_812): the seven description register files of unit 812 and where maps go;
//! * [`detail_fig9`](crate::mapchain::detail_fig9): the detail path's arithmetic, units 902-914;
//! * [`program`](crate::mapchain::program): the walker's micro-program, one step per access;
//! * [`walker_812`](crate::mapchain::walker_812): the walker cycle by cycle, with the output stage 820's eqs 5-7
//!   at the chain's end;
//! * [`bank_port_810`](crate::mapchain::bank_port_810): the walker's child that holds the banks
//!   ([`crate::texram::TexramAccess`]: the stub or the chip) and makes the access the walker
//!   stages, at the clock edge, as a synchronous memory does.
//!
//! ## Map linking, detail, reflectance and environment maps (Schilling & Knittel, sections 7-9 and 14)
//!
//! A pixel's maps are linked through the seven description register files of the address and
//! control unit 812 (`hdl/units/src/mapchain/drf_812.rs`): kind (texture, u,v offset, detail,
//! reflectance, environment), the map (size, border operation and colour, eq. 5's selection and
//! `k_T`, bases), the bases of further planes (an offset DRF's v plane, an environment DRF's six
//! faces), the link, the "new coordinates before access" flag, `k_s`, the detail mode and eqs 6
//! and 7's selections. The rasterizer sends the leading DRF with each pixel; the walker
//! (`mapchain/walker_812.rs`, its micro-program `mapchain/program.rs`) follows the links, one
//! state an access, until the chain ends, then applies eqs 5-7 of the output stage 820:
//!
//! | state | what 812 does |
//! |---|---|
//! | `TEXTURE`, `REFLECTANCE` | the map at the pixel's (u, v, lambda); below level 0 with a link to offsets, the read waits for the detail |
//! | `OFFSET_U`, `OFFSET_V` | (lambda < 0 only) the two 8-bit offset maps at the pixel's level-0 texel, nearest: the tile's origin |
//! | `DETAIL` | (lambda < 0 only) the detail map at `o + frac(u) 16`, lambda `max(lambda, -4) + 4` (3 above -1) |
//! | `DETAIL_BASE` | the texel below the detail, read as a third step when -1 < lambda < 0 or the detail modulates it |
//! | `ENV_COORDS` | one cycle: eq. 4 with the perturbed normal and the cube face with s, t |
//! | `ENVIRONMENT` | the face's mipmap at `(s W, t W)`, lambda `max(lambda, 0)` |
//! | `COMBINE` / `ERROR` | the result out; `ERROR` for a chain of more than seven DRFs, a detail without offsets, an unset DRF, a reflectance lit by an environment the chain does not read |
//!
//! Every access goes through `TexramAccess::access_with`, 812's working descriptor (request
//! pointer 7, the map the walker selected: a face, an offset plane), on the stub or on the
//! cycle-accurate chip 802 (the testbench runs the longest chain on both: equal bit for bit,
//! slots and faults included). Maps are placed at row boundaries one after the other, so two
//! maps never share a DRAM row.
//!
//! Choices where the document is silent \[C\] (defaults; each a field):
//!
//! * **Detail**: each level-0 texel owns a 16 x 16 tile of a detail map of at most 256 x 256
//!   (8-bit offsets); the detail DRF's `tile:4` border wraps the bilinear pair inside the tile
//!   of the sample point at every level (`Border::Tile`, exhaustively tested: the pair stays in
//!   two banks); any other border continues into the map. u's 8 fraction bits leave the detail
//!   map 4 (a level -4 texel in 16 steps). The combination after "texture map 910 and" (the
//!   text is cut off): replace (default), multiply (`T . D`) or add-signed (`T + D - 128`), then
//!   for -1 < lambda < 0 a fade into the texel, `(X (256 - f) + T f + 128) >> 8`, `f = (lambda +
//!   1) 256`: continuous at -1 and reaching the plain texel at 0.
//! * **Environment**: lambda on the faces `max(lambda, 0)` (the document leaves it to the
//!   rasterizer); faces square, one size, at least 16 x 16 (so `s W` is exact in sQ12.8); their
//!   border clamp by default. Without `new_coords` the rasterizer's face and (u, v) are used.
//! * **Timing**: a state costs its access's slots (one, two on a page fault) times six 5 ns
//!   cycles; `ENV_COORDS` one cycle; going to the next DRF none (812 decodes it while the access
//!   runs); the next pixel is taken in the last access's last cycle, so one-access pixels come
//!   one a slot.
//!
//! Checks (`tb/tests/mapchain.rs`, the regress testbench `walker_812`: seven chain shapes on the
//! stub and the longest on the chip, coverage of shapes x lambda ranges, faces and access counts):
//! the clocked walker equals its micro-program run access by access (colour, accesses, slots,
//! faults, error), each result comes out at the cycle its slots say, and the colour is within the
//! golden model's bound (`golden/src/mapchain.rs`, from the equations: each map's value within
//! half an LSB with the chip's weight quantisation, bounds carried through eqs 5-7 and step 912
//! stage by stage, the environment's widened by the face coordinate's error times the face's
//! steepest step); measured at most 1.9 LSB. lambda >= 0 leaves the detail path unused (bit for
//! bit the plain texture's colour in one access); lambda = -4 is the integer bilinear of the
//! detail map's level 0 in the tile the offsets give; one step of lambda either side of -1
//! moves the colour at most 2 LSB; a constant reflectance k gives eq. 6 with k_s = k bit for bit;
//! a link cycle stops after seven DRFs with the flag; the walker's face is f64's unless the top
//! two components are within 2^-12. Vectors: `golden/vectors/walker_812.json`.
//!
//! Section 14's timings, from the page registers (`texrtl regress --only walker_812`; pixels along
//! a texture row, 5 ns clock, 30 ns slot):
//!
//! | chain | accesses a pixel | faulting | ns a pixel | M pixels/s | document |
//! |---|---|---|---|---|---|
//! | texture, lambda 0.5 | 1.00 | 0.00 | 30.1 | 33.2 | 33.3 M/s peak |
//! | texture + environment, lambda 0.5 | 2.00 | 2.00 | 125.0 | 8.0 | 2 accesses (16.7 M/s without faults) |
//! | texture + detail, lambda -2.5 | 4.00 | 4.00 | 240.0 | 4.17 | about 240 ns |
//! | longest chain (texture, offsets, detail, reflectance, offsets, detail, environment), lambda -2.5 | 9.00 | 9.00 | 545.0 | 1.83 | about 540 ns (about 1.8 M/s) |
//!
//! Every linked access faults because the maps lie in different rows of the same banks; the
//! document's "will most probably cause a page fault" is what the page registers give, not a
//! constant. The texture + environment chain is the document's two accesses, but with both maps
//! in one chip every access faults (125 ns, not 60): a design that keeps the environment on
//! another chip, or its faces in the texture's rows, would recover the 16.7 M.
//!
//! `texrtl mapchain --maps M.json --requests R.csv --out O.csv \[--stats S.json\] \[--vcd W.vcd\]
//! texrtl ptm fit --height H.pgm --lights L.csv --out T.ptm \[--bits 8|16\] \[--height-scale S\] \[--stats S.json\]
//! texrtl ptm eval --ptm T.ptm --queries Q.csv --out O.csv
//! texrtl tangents --mesh M.obj --out T.csv \[--mode max|maya|directx\]`:
//! M lists the DRFs and their 8-bit PGM maps (paths relative to M):
//!
//! ```json
//! { "drfs": [
//!   { "drf": 0, "kind": "texture", "maps": ["t.pgm"], "link": 1, "modulate": "illumination" },
//!   { "drf": 1, "kind": "offset", "maps": ["ou.pgm", "ov.pgm"], "link": 2 },
//!   { "drf": 2, "kind": "detail", "maps": ["d.pgm"], "detail": "multiply", "link": 6 },
//!   { "drf": 6, "kind": "environment", "k_s": 160,
//!     "maps": ["px.pgm", "nx.pgm", "py.pgm", "ny.pgm", "pz.pgm", "nz.pgm"] } ] }
//! ```
//!
//! Fields: `drf` 0..=6, `kind`, `maps` (two for offsets, six faces +x -x +y -y +z -z), `border`
//! (wrap, clamp, mirror, border:N, tile:T; default tile:4 for detail, clamp for faces, else
//! wrap), `link`, `modulate` (one, illumination, k:N), `detail` (replace, multiply, add-signed),
//! `k_s`, `base` (texture, illumination), `light` (environment, specular), `new_coords`; unknown
//! fields are refused. R has the header `drf,u,v,lambda` and any of `nx,ny,nz` (the perturbed
//! normal, |c| < 4), `vx,vy,vz` (the unit vector to the eye), `face`, `id`, `is`; O gets
//! `drf,u,v,lambda,colour,accesses,faults,error` per request; S `pixels`, `accesses`,
//! `page_faults`, `slots`, `errors`, `cycles`, `ns`, `ns_per_pixel`. One chip is one colour
//! component (configuration 4): run one maps file per component for colour.
//!
//! Not modelled: splitting a chain over several chips; video maps linked to environment maps
//! (section 14 mentions them); the frame unit of eqs 2-3 as a clocked stage (it stays a function
//! on the rasterizer's side: the walker takes the perturbed normal).

pub mod bank_port_810;
pub mod detail_fig9;
pub mod drf_812;
pub mod program;
pub mod walker_812;
