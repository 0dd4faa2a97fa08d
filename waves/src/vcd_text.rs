//! The text of VCD value changes, formatted by hand (the formatting machinery of the `vcd`
//! crate was the tracer's main cost, and these are tested against it): binary digits eight at
//! a time, a change line, a real change, a timestamp. The VCD writer's threads write them, the
//! FST writer's digits for its value-change blocks too.

use hdl::fx::Format;

/// `#t` and a newline (the writer's own formatting is tested against it).
#[cfg(test)]
pub(crate) fn push_time(buf: &mut Vec<u8>, t: u64) {
    buf.push(b'#');
    buf.extend_from_slice(itoa::Buffer::new().format(t).as_bytes());
    buf.push(b'\n');
}

/// Every byte in binary digits, most significant first.
pub(crate) static BINARY: [[u8; 8]; 256] = {
    let mut t = [[b'0'; 8]; 256];
    let mut v = 0;
    while v < 256 {
        let mut k = 0;
        while k < 8 {
            if (v >> (7 - k)) & 1 == 1 {
                t[v][k] = b'1';
            }
            k += 1;
        }
        v += 1;
    }
    t
};

/// The `out.len()` low bits of `bits` as binary digits, most significant first: the bits
/// above a whole number of bytes one by one, then eight at a time.
#[inline]
pub(crate) fn binary_digits(out: &mut [u8], bits: u64) {
    let w = out.len();
    let top = w % 8;
    for (k, d) in out[..top].iter_mut().enumerate() {
        *d = b'0' + ((bits >> (w - 1 - k)) & 1) as u8;
    }
    for (j, chunk) in out[top..].chunks_exact_mut(8).enumerate() {
        chunk.copy_from_slice(&BINARY[((bits >> (8 * (w / 8 - 1 - j))) & 0xff) as usize]);
    }
}

/// The `width` low bits of `bits` as binary digits, most significant first.
#[inline]
pub(crate) fn push_binary(buf: &mut Vec<u8>, width: u32, bits: u64) {
    let mut digits = [0u8; 64];
    let d = &mut digits[..width as usize];
    binary_digits(d, bits);
    buf.extend_from_slice(d);
}

/// A value change as the `vcd` crate writes it (`1!` for a bit, `b0101 !` for a vector), but
/// formatted by hand into the cycle's buffer: the formatting machinery was the tracer's main
/// cost.
#[inline]
pub(crate) fn push_change(buf: &mut Vec<u8>, code: &[u8], width: u32, bits: u64) {
    if width == 1 {
        buf.push(b'0' + (bits & 1) as u8);
    } else {
        buf.push(b'b');
        push_binary(buf, width, bits);
        buf.push(b' ');
    }
    buf.extend_from_slice(code);
    buf.push(b'\n');
}

/// A real value change, `r<value> <code>` with the value as Rust's `Display` writes it (as the
/// `vcd` crate does).
pub(crate) fn push_real(buf: &mut Vec<u8>, code: &[u8], x: f64) {
    use std::io::Write as _;
    let _ = write!(buf, "r{x} ");
    buf.extend_from_slice(code);
    buf.push(b'\n');
}

/// A real companion's value: `bits` read in format `fmt`.
pub(crate) fn real_of(bits: u64, fmt: Format) -> f64 {
    hdl::fx::Fx::from_bits(fmt, bits as u128).to_f64()
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcd::{IdCode, Value};

    /// The hand-written change is the `vcd` crate's text for every width and for bit patterns
    /// across the byte boundaries.
    #[test]
    fn changes_are_written_as_the_vcd_crate_writes_them() {
        let id = IdCode::FIRST;
        let code = id.to_string().into_bytes();
        for width in 1..=64u32 {
            for bits in [
                0u64,
                1,
                0x5a,
                0x8000_0000_0000_0001,
                u64::MAX,
                0x0123_4567_89ab_cdef,
            ] {
                let bits = if width == 64 {
                    bits
                } else {
                    bits & ((1 << width) - 1)
                };
                let mut ours = Vec::new();
                push_change(&mut ours, &code, width, bits);
                let mut theirs = vcd::Writer::new(Vec::new());
                if width == 1 {
                    let v = if bits == 1 { Value::V1 } else { Value::V0 };
                    theirs.change_scalar(id, v).unwrap();
                } else {
                    let v = (0..width).rev().map(|k| {
                        if (bits >> k) & 1 == 1 {
                            Value::V1
                        } else {
                            Value::V0
                        }
                    });
                    theirs.change_vector(id, v).unwrap();
                }
                assert_eq!(
                    ours,
                    theirs.writer().clone(),
                    "width {width} bits {bits:#x}"
                );
            }
        }
        let mut t = Vec::new();
        push_time(&mut t, 1_234_567_890);
        assert_eq!(t, b"#1234567890\n");
    }
}
