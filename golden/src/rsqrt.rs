//! The error bound of a table-plus-Newton-Raphson inverse square root (normal unit 156 of
//! US 2004/0207631), derived from the mathematics, for checking the hardware exhaustively.
//!
//! Input `m` in [1, 4), output `y ~ 1/sqrt(m)` with `Y` fraction bits. The table is indexed
//! by one bit telling [1,2) from [2,4) and the next `T - 1` mantissa bits, so an interval is
//! `2^-(T-1)` wide in [1,2) (twice that in [2,4), where the function is flatter); its entry is
//! `1/sqrt` of the midpoint, rounded to Y bits. With relative slope `|d ln y / dm| = 1/(2m)`
//! at most 1/2, the entry's relative error is at most `2^-(T-1) / 2 * 1/2 = 2^-(T+1)` plus the
//! entry's rounding (half an ULP). One step `y' = y (3 - m y^2) / 2` maps a relative error `e`
//! to at most `1.5 e^2 + 0.5 e^3`, plus the rounding of `m y^2` to Y+2 bits (half an ULP of
//! that, times `y / 2 <= 1/2`) and of `y'` (half an ULP). Since `y <= 1`, relative error times
//! `2^Y` bounds the error in ULPs.

/// The bound in ULPs of `2^-y_frac` for `table_bits` index bits and `iterations` steps.
pub fn error_bound_ulps(table_bits: u32, iterations: u32, y_frac: u32) -> f64 {
    let ulp = (-(y_frac as f64)).exp2();
    let mut e = (-(table_bits as f64 + 1.0)).exp2() + 0.5 * ulp;
    for _ in 0..iterations {
        e = 1.5 * e * e + 0.5 * e * e * e + 0.25 * ulp * 0.5 + 0.5 * ulp;
    }
    e / ulp
}

#[cfg(test)]
mod tests {
    #[test]
    fn bound_shrinks_with_table_and_iterations() {
        use super::error_bound_ulps as b;
        assert!(b(8, 1, 24) < b(6, 1, 24));
        assert!(b(8, 2, 24) < b(8, 1, 24));
        assert!((b(10, 0, 16) - (2f64.powi(-11) * 65536.0 + 0.5)).abs() < 1e-9);
    }
}
