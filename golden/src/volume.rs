//! Volume rendering from the mathematics (Schilling & Knittel section 13), in f64: trilinear
//! interpolation of the voxels, the central-difference gradient field (without the 1/2,
//! as the chip forms it) interpolated the same way, and front-to-back compositing of
//! pre-classified RGBA samples, which the document leaves to the host.

/// A volume, x fastest; indices outside are reflected without repeating the edge voxel.
pub struct Volume<'a> {
    pub dims: (usize, usize, usize),
    pub voxels: &'a [u8],
}

fn reflect(i: i64, n: usize) -> usize {
    let n = n as i64;
    if n == 1 {
        return 0;
    }
    let p = 2 * (n - 1);
    let m = ((i % p) + p) % p;
    (if m < n { m } else { p - m }) as usize
}

impl Volume<'_> {
    pub fn voxel(&self, x: i64, y: i64, z: i64) -> f64 {
        let (nx, ny, nz) = self.dims;
        let (x, y, z) = (reflect(x, nx), reflect(y, ny), reflect(z, nz));
        f64::from(self.voxels[(z * ny + y) * nx + x])
    }

    /// `f(x+1) - f(x-1)` and the same along y and z, at a voxel.
    pub fn central(&self, x: i64, y: i64, z: i64) -> [f64; 3] {
        [
            self.voxel(x + 1, y, z) - self.voxel(x - 1, y, z),
            self.voxel(x, y + 1, z) - self.voxel(x, y - 1, z),
            self.voxel(x, y, z + 1) - self.voxel(x, y, z - 1),
        ]
    }

    /// Trilinear interpolation of `f` (a per-voxel function) at `(x, y, z)` (voxel `i` at
    /// `i`).
    pub fn trilinear<const N: usize>(
        &self,
        (x, y, z): (f64, f64, f64),
        f: impl Fn(i64, i64, i64) -> [f64; N],
    ) -> [f64; N] {
        let (i, j, k) = (x.floor(), y.floor(), z.floor());
        let (a, b, c) = (x - i, y - j, z - k);
        let mut out = [0.0; N];
        for n in 0..8 {
            let (dx, dy, dz) = (n & 1, (n >> 1) & 1, n >> 2);
            let w = if dx == 1 { a } else { 1.0 - a }
                * if dy == 1 { b } else { 1.0 - b }
                * if dz == 1 { c } else { 1.0 - c };
            let v = f(i as i64 + dx, j as i64 + dy, k as i64 + dz);
            for (o, x) in out.iter_mut().zip(v) {
                *o += w * x;
            }
        }
        out
    }

    /// The value at a point.
    pub fn value(&self, p: (f64, f64, f64)) -> f64 {
        self.trilinear(p, |x, y, z| [self.voxel(x, y, z)])[0]
    }

    /// The gradient at a point.
    pub fn gradient(&self, p: (f64, f64, f64)) -> [f64; 3] {
        self.trilinear(p, |x, y, z| self.central(x, y, z))
    }
}

/// Front-to-back compositing of one ray's RGBA samples (each 0..=1, colour not
/// premultiplied): `C += (1 - A) a c`, `A += (1 - A) a`.
pub fn composite(samples: &[[f64; 4]]) -> [f64; 4] {
    let mut acc = [0.0; 4];
    for s in samples {
        let t = (1.0 - acc[3]) * s[3];
        for c in 0..3 {
            acc[c] += t * s[c];
        }
        acc[3] += t;
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_field_interpolates_exactly() {
        let (nx, ny, nz) = (6, 4, 5);
        let v: Vec<u8> = (0..nx * ny * nz)
            .map(|n| {
                let (x, y, z) = (n % nx, n / nx % ny, n / (nx * ny));
                (3 * x + 5 * y + 7 * z + 9) as u8
            })
            .collect();
        let vol = Volume {
            dims: (nx, ny, nz),
            voxels: &v,
        };
        let p = (2.25, 1.5, 2.75);
        assert!((vol.value(p) - (3.0 * 2.25 + 5.0 * 1.5 + 7.0 * 2.75 + 9.0)).abs() < 1e-12);
        assert_eq!(vol.gradient((2.25, 1.5, 2.5)), [6.0, 10.0, 14.0]);
    }

    #[test]
    fn compositing_an_opaque_sample_hides_the_rest() {
        let c = composite(&[[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]]);
        assert_eq!(c, [1.0, 0.0, 0.0, 1.0]);
        let c = composite(&[[1.0, 1.0, 1.0, 0.5], [0.0, 0.0, 0.0, 0.5]]);
        assert_eq!(c, [0.5, 0.5, 0.5, 0.75]);
    }
}
