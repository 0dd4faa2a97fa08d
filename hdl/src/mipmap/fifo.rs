//! A synchronous FIFO of declared depth that reports overflow and underflow instead of
//! wrapping: the FIFOs 1408 and 1412 of the mipmap generator (Schilling & Knittel, Figure 14).

use crate::fx::Format;
use crate::kernel::Signal;

/// What went wrong with a FIFO.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FifoError {
    /// A push into a full FIFO.
    Overflow,
    /// A pop from an empty one.
    Underflow,
}

/// A FIFO of `depth` entries of up to 16 bits, with its occupancy as a traced signal and the
/// largest occupancy seen.
#[derive(Clone, Debug)]
pub struct Fifo {
    buf: Vec<u16>,
    head: usize,
    len: usize,
    max: usize,
    /// Occupancy, traced.
    pub occupancy: Signal,
}

impl Fifo {
    /// A FIFO of `depth >= 1` entries; `name` names its occupancy signal.
    pub fn new(name: &'static str, depth: usize) -> Fifo {
        assert!(depth >= 1, "FIFO depth 0");
        let bits = usize::BITS - depth.leading_zeros();
        Fifo {
            buf: vec![0; depth],
            head: 0,
            len: 0,
            max: 0,
            occupancy: Signal::new(name, Format::uint(bits)),
        }
    }

    pub fn depth(&self) -> usize {
        self.buf.len()
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    /// Largest occupancy since construction.
    pub fn max_occupancy(&self) -> usize {
        self.max
    }

    /// The oldest entry, if any (what a pop would return).
    #[inline]
    pub fn front(&self) -> Option<u16> {
        (self.len > 0).then(|| self.buf[self.head])
    }

    /// Pushes `v`; a full FIFO refuses.
    #[inline]
    pub fn push(&mut self, v: u16) -> Result<(), FifoError> {
        let d = self.buf.len();
        if self.len == d {
            return Err(FifoError::Overflow);
        }
        let mut tail = self.head + self.len;
        if tail >= d {
            tail -= d;
        }
        self.buf[tail] = v;
        self.len += 1;
        self.max = self.max.max(self.len);
        self.occupancy.set_bits(self.len as u64);
        Ok(())
    }

    /// Pops the oldest entry; an empty FIFO refuses.
    #[inline]
    pub fn pop(&mut self) -> Result<u16, FifoError> {
        if self.len == 0 {
            return Err(FifoError::Underflow);
        }
        let v = self.buf[self.head];
        self.head += 1;
        if self.head == self.buf.len() {
            self.head = 0;
        }
        self.len -= 1;
        self.occupancy.set_bits(self.len as u64);
        Ok(v)
    }

    /// Takes every entry at once (a parallel transfer to a shift register).
    pub fn drain_all(&mut self) -> Vec<u16> {
        let mut v = Vec::with_capacity(self.len);
        while let Ok(x) = self.pop() {
            v.push(x);
        }
        v
    }

    /// Empties the FIFO (synchronous reset).
    pub fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
        self.occupancy.set_bits(0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_occupancy_and_errors() {
        let mut f = Fifo::new("occ", 3);
        assert_eq!(f.pop(), Err(FifoError::Underflow));
        for v in 1..=3 {
            f.push(v).unwrap();
        }
        assert_eq!(f.push(4), Err(FifoError::Overflow));
        assert_eq!(f.occupancy.bits(), 3);
        assert_eq!(f.pop(), Ok(1));
        f.push(5).unwrap();
        assert_eq!(f.drain_all(), vec![2, 3, 5]);
        assert_eq!(f.max_occupancy(), 3);
        assert!(f.is_empty());
    }
}
