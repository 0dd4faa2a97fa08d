//! texrtl's FST encoder for the tracer: bit-vector variables of 1 to 64 bits whose values come
//! as machine words, never as text.
//!
//! The file is GTKWave's FST layout, block by block: the header (fixed 329 bytes, its counts
//! and end time filled in when the file is finished), the hierarchy (LZ4), the geometry (each
//! handle's width), then one value-change block per section. A section holds the values at its
//! start (the frame, one ASCII `0`/`1`/`x` per bit), each variable's changes as its own byte
//! list (LZ4-compressed when that saves space), an offset table to those lists, and the time
//! table (zlib). A change is a LEB128 number, the count of time-table entries since the
//! variable's previous change shifted left (by 2 with the bit for a 1-bit variable, by 1 with
//! a 0 flag for a wider one), followed for a wider one by its bits packed MSB first.
//!
//! The bytes are those `fst-writer` writes for the same calls with its deduplication off; a
//! test holds the two equal. What differs is the cost: a change here is a few shifts and
//! stores, where `fst-writer` takes each value as ASCII digits and packs them bit by bit.

use std::io::{self, Seek, SeekFrom, Write};

/// Header block length, after its type byte.
const HEADER_LEN: u64 = 329;
const VERSION_LEN: usize = 128;
const DATE_LEN: usize = 119;
/// Block types.
const BLOCK_HEADER: u8 = 0;
const BLOCK_GEOMETRY: u8 = 3;
const BLOCK_HIERARCHY_LZ4: u8 = 6;
const BLOCK_VALUE_CHANGES: u8 = 8;
/// Hierarchy records.
const SCOPE: u8 = 254;
const UP_SCOPE: u8 = 255;
const SCOPE_MODULE: u8 = 0;
const VAR_WIRE: u8 = 16;
const DIR_IMPLICIT: u8 = 0;
/// A value-change list shorter than this is stored as it is.
const LZ4_MIN: usize = 32;
const ZLIB_LEVEL: u8 = 3;

/// Appends `v` as unsigned LEB128.
#[inline(always)]
fn varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push(v as u8 | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// Appends `v` as signed LEB128.
fn svarint(out: &mut Vec<u8>, mut v: i64) {
    loop {
        let byte = (v & 0x7f) as u8;
        v >>= 7;
        let last = (v == 0 && byte & 0x40 == 0) || (v == -1 && byte & 0x40 != 0);
        out.push(if last { byte } else { byte | 0x80 });
        if last {
            return;
        }
    }
}

fn c_str(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(s.as_bytes());
    out.push(0);
}

fn invalid(what: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, what)
}

/// An FST being declared: header written, scopes and variables collected.
pub(crate) struct FstHeader<W: Write + Seek> {
    out: W,
    hierarchy: Vec<u8>,
    widths: Vec<u32>,
    scopes: u64,
    depth: u32,
}

impl<W: Write + Seek> FstHeader<W> {
    /// Starts the file at `out`'s position 0: times in units of `10^timescale` s, `version`
    /// (under 128 bytes) as the writer's name.
    pub(crate) fn new(mut out: W, timescale: i8, version: &str) -> io::Result<Self> {
        if version.len() >= VERSION_LEN || version.contains('\0') {
            return Err(invalid(format!("FST version string too long: {version}")));
        }
        let mut h = Vec::with_capacity(1 + HEADER_LEN as usize);
        h.push(BLOCK_HEADER);
        h.extend_from_slice(&HEADER_LEN.to_be_bytes());
        // Start time, end time (filled in at the end).
        h.extend_from_slice(&[0; 16]);
        h.extend_from_slice(&std::f64::consts::E.to_le_bytes());
        // Writer memory, scope, variable, handle and section counts (filled in at the end).
        h.extend_from_slice(&[0; 40]);
        h.push(timescale as u8);
        h.extend_from_slice(version.as_bytes());
        h.resize(h.len() + VERSION_LEN - version.len(), 0);
        h.resize(h.len() + DATE_LEN, 0);
        // File type Verilog; time zero 0, an offset GTKWave adds to every time it shows (the
        // tracer's times are absolute, a window's too).
        h.push(0);
        h.extend_from_slice(&[0; 8]);
        out.write_all(&h)?;
        Ok(FstHeader {
            out,
            hierarchy: Vec::new(),
            widths: Vec::new(),
            scopes: 0,
            depth: 0,
        })
    }

    /// Opens a module scope.
    pub(crate) fn scope(&mut self, name: &str, component: &str) {
        self.scopes += 1;
        self.depth += 1;
        self.hierarchy.extend_from_slice(&[SCOPE, SCOPE_MODULE]);
        c_str(&mut self.hierarchy, name);
        c_str(&mut self.hierarchy, component);
    }

    /// Closes the innermost open scope.
    pub(crate) fn up_scope(&mut self) {
        debug_assert!(self.depth > 0, "no scope open");
        self.depth -= 1;
        self.hierarchy.push(UP_SCOPE);
    }

    /// Declares a wire of `width` bits (1 to 64) in the open scope; returns its handle.
    pub(crate) fn var(&mut self, name: &str, width: u32) -> io::Result<u32> {
        if !(1..=64).contains(&width) {
            return Err(invalid(format!(
                "{name}: width {width} is not 1 to 64 bits"
            )));
        }
        self.hierarchy.extend_from_slice(&[VAR_WIRE, DIR_IMPLICIT]);
        c_str(&mut self.hierarchy, name);
        varint(&mut self.hierarchy, u64::from(width));
        // Not an alias.
        varint(&mut self.hierarchy, 0);
        self.widths.push(width);
        Ok(self.widths.len() as u32 - 1)
    }

    /// Writes the hierarchy and geometry blocks; values come next.
    pub(crate) fn finish(mut self) -> io::Result<FstBody<W>> {
        debug_assert_eq!(self.depth, 0, "scopes left open");
        let packed = lz4_flex::compress(&self.hierarchy);
        let mut b = vec![BLOCK_HIERARCHY_LZ4];
        b.extend_from_slice(&(16 + packed.len() as u64).to_be_bytes());
        b.extend_from_slice(&(self.hierarchy.len() as u64).to_be_bytes());
        b.extend_from_slice(&packed);
        let mut geometry = Vec::new();
        for &w in &self.widths {
            varint(&mut geometry, u64::from(w));
        }
        b.push(BLOCK_GEOMETRY);
        b.extend_from_slice(&(24 + geometry.len() as u64).to_be_bytes());
        b.extend_from_slice(&(geometry.len() as u64).to_be_bytes());
        b.extend_from_slice(&(self.widths.len() as u64).to_be_bytes());
        b.extend_from_slice(&geometry);
        self.out.write_all(&b)?;
        // Out now, so a full disk or a bad path shows before the simulation runs.
        self.out.flush()?;
        Ok(FstBody::new(self.out, self.widths, self.scopes))
    }
}

/// An FST taking values: time steps, changes, and sections written out.
pub(crate) struct FstBody<W: Write + Seek> {
    out: W,
    widths: Vec<u32>,
    scopes: u64,
    /// Each handle's value now (`None`, shown as `x`, until it has one).
    value: Vec<Option<u64>>,
    /// Each handle's changes in this section, and the time-table index of its last one.
    lists: Vec<Vec<u8>>,
    last_index: Vec<u32>,
    list_bytes: usize,
    /// The values at this section's start, as ASCII digits (taken at its first time step).
    frame: Vec<u8>,
    time_table: Vec<u8>,
    time_index: u32,
    start: u64,
    end: u64,
    sections: u64,
}

impl<W: Write + Seek> FstBody<W> {
    fn new(out: W, widths: Vec<u32>, scopes: u64) -> Self {
        let n = widths.len();
        let bits = widths.iter().map(|&w| w as usize).sum();
        FstBody {
            out,
            widths,
            scopes,
            value: vec![None; n],
            lists: vec![Vec::new(); n],
            last_index: vec![0; n],
            list_bytes: 0,
            frame: vec![b'x'; bits],
            time_table: Vec::new(),
            time_index: 0,
            start: 0,
            end: 0,
            sections: 0,
        }
    }

    /// Moves to time `t` (not before the current one; the same time is no step).
    pub(crate) fn time(&mut self, t: u64) -> io::Result<()> {
        if t < self.end {
            return Err(invalid(format!(
                "FST time {t} is before the current time {}",
                self.end
            )));
        }
        if t == self.end {
            return Ok(());
        }
        let first = self.time_table.is_empty();
        if first {
            self.take_frame();
        } else {
            self.time_index += 1;
        }
        varint(&mut self.time_table, t - if first { 0 } else { self.end });
        self.end = t;
        Ok(())
    }

    /// Handle `h` takes `bits` (above its width ignored) at the current time.
    #[inline]
    pub(crate) fn change(&mut self, h: u32, bits: u64) {
        let h = h as usize;
        let w = self.widths[h];
        let bits = bits & (u64::MAX >> (64 - w));
        self.value[h] = Some(bits);
        if self.time_table.is_empty() {
            // Before this section's first step: the value belongs in its frame.
            return;
        }
        let delta = u64::from(self.time_index - self.last_index[h]);
        self.last_index[h] = self.time_index;
        let list = &mut self.lists[h];
        let before = list.len();
        if w == 1 {
            varint(list, delta << 2 | bits << 1);
        } else {
            varint(list, delta << 1);
            let n = w.div_ceil(8) as usize;
            let packed = bits << (8 * n as u32 - w);
            list.extend_from_slice(&packed.to_be_bytes()[8 - n..]);
        }
        self.list_bytes += list.len() - before;
    }

    /// Bytes of changes and time table held for the current section.
    pub(crate) fn size(&self) -> usize {
        self.list_bytes + self.time_table.len()
    }

    fn take_frame(&mut self) {
        let mut at = 0;
        for h in 0..self.widths.len() {
            let w = self.widths[h] as usize;
            let digits = &mut self.frame[at..at + w];
            match self.value[h] {
                Some(v) => crate::vcd_text::binary_digits(digits, v),
                None => digits.fill(b'x'),
            }
            at += w;
        }
    }

    /// Writes the current section out and starts the next at the current time.
    pub(crate) fn flush(&mut self) -> io::Result<()> {
        let block = self.section();
        self.out.write_all(&block)?;
        self.sections += 1;
        for l in &mut self.lists {
            l.clear();
        }
        self.last_index.fill(0);
        self.list_bytes = 0;
        self.time_table.clear();
        self.time_index = 0;
        self.start = self.end;
        Ok(())
    }

    /// The current section as one value-change block.
    fn section(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(self.size() + self.frame.len() + 64);
        b.push(BLOCK_VALUE_CHANGES);
        // Length and memory needed, filled in below.
        b.extend_from_slice(&[0; 8]);
        b.extend_from_slice(&self.start.to_be_bytes());
        b.extend_from_slice(&self.end.to_be_bytes());
        b.extend_from_slice(&[0; 8]);
        varint(&mut b, self.frame.len() as u64);
        varint(&mut b, self.frame.len() as u64);
        varint(&mut b, self.widths.len() as u64);
        b.extend_from_slice(&self.frame);
        let memory = self.change_lists(&mut b);
        self.time_table_into(&mut b);
        let len = b.len() as u64 - 1;
        b[1..9].copy_from_slice(&len.to_be_bytes());
        b[25..33].copy_from_slice(&memory.to_be_bytes());
        b
    }

    /// Appends each handle's change list (LZ4 where it helps) and the offset table to them;
    /// returns their total unpacked size.
    fn change_lists(&self, b: &mut Vec<u8>) -> u64 {
        varint(b, self.widths.len() as u64);
        b.push(b'4');
        let mut offsets = Vec::new();
        let mut prev = b.len() - 1;
        let mut empty = 0u64;
        let mut memory = 0;
        for list in &self.lists {
            if list.is_empty() {
                empty += 1;
                continue;
            }
            if empty > 0 {
                varint(&mut offsets, empty << 1);
                empty = 0;
            }
            let at = b.len();
            memory += list.len() as u64;
            let packed = (list.len() >= LZ4_MIN)
                .then(|| lz4_flex::compress(list))
                .filter(|p| p.len() < list.len());
            match packed {
                Some(p) => {
                    varint(b, list.len() as u64);
                    b.extend_from_slice(&p);
                }
                None => {
                    varint(b, 0);
                    b.extend_from_slice(list);
                }
            }
            svarint(&mut offsets, ((at - prev) as i64) << 1 | 1);
            prev = at;
        }
        if empty > 0 {
            varint(&mut offsets, empty << 1);
        }
        b.extend_from_slice(&offsets);
        b.extend_from_slice(&(offsets.len() as u64).to_be_bytes());
        memory
    }

    /// Appends the time table (zlib where it helps) and its sizes and entry count.
    fn time_table_into(&self, b: &mut Vec<u8>) {
        let raw = &self.time_table;
        let packed = miniz_oxide::deflate::compress_to_vec_zlib(raw, ZLIB_LEVEL);
        let stored = if packed.len() < raw.len() {
            &packed
        } else {
            raw
        };
        b.extend_from_slice(stored);
        b.extend_from_slice(&(raw.len() as u64).to_be_bytes());
        b.extend_from_slice(&(stored.len() as u64).to_be_bytes());
        let entries = if raw.is_empty() {
            0
        } else {
            u64::from(self.time_index) + 1
        };
        b.extend_from_slice(&entries.to_be_bytes());
    }

    /// Writes the last section and the header's counts and end time; returns the output.
    pub(crate) fn finish(mut self) -> io::Result<W> {
        self.flush()?;
        self.out.seek(SeekFrom::Start(17))?;
        self.out.write_all(&self.end.to_be_bytes())?;
        self.out.seek(SeekFrom::Start(41))?;
        let vars = self.widths.len() as u64;
        for n in [self.scopes, vars, vars, self.sections] {
            self.out.write_all(&n.to_be_bytes())?;
        }
        self.out.seek(SeekFrom::End(0))?;
        Ok(self.out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fst_writer::{
        FstFileType, FstHeaderWriter, FstInfo, FstScopeType, FstSignalId, FstSignalType,
        FstVarDirection, FstVarType,
    };
    use proptest::prelude::*;
    use std::io::Cursor;

    /// One call on a body: a time step, a change, or a section written out.
    #[derive(Clone, Debug)]
    enum Call {
        Time(u64),
        Change(usize, u64),
        Flush,
    }

    const VERSION: &str = "texrtl test";

    fn ours(widths: &[u32], calls: &[Call]) -> Vec<u8> {
        let mut h = FstHeader::new(Cursor::new(Vec::new()), -12, VERSION).unwrap();
        h.scope("tb", "");
        h.scope("dut", "kind");
        let ids: Vec<u32> = (0..widths.len())
            .map(|i| h.var(&format!("s{i}"), widths[i]).unwrap())
            .collect();
        h.up_scope();
        h.up_scope();
        let mut b = h.finish().unwrap();
        replay(calls, |c| match c {
            Call::Time(t) => b.time(t).unwrap(),
            Call::Change(i, v) => b.change(ids[i], v),
            Call::Flush => b.flush().unwrap(),
        });
        b.finish().unwrap().into_inner()
    }

    /// Plays `calls` to `f` with each time step's advance turned into the absolute time.
    fn replay(calls: &[Call], mut f: impl FnMut(Call)) {
        let mut t = 0;
        for c in calls {
            f(match *c {
                Call::Time(dt) => {
                    t += dt;
                    Call::Time(t)
                }
                ref other => other.clone(),
            });
        }
    }

    fn theirs(widths: &[u32], calls: &[Call]) -> Vec<u8> {
        let info = FstInfo {
            start_time: 0,
            timescale_exponent: -12,
            version: VERSION.into(),
            date: String::new(),
            file_type: FstFileType::Verilog,
        };
        let mut h = FstHeaderWriter::write_to_mem(&info).unwrap();
        let (wire, imp) = (FstVarType::Wire, FstVarDirection::Implicit);
        h.scope("tb", "", FstScopeType::Module).unwrap();
        h.scope("dut", "kind", FstScopeType::Module).unwrap();
        let ids: Vec<FstSignalId> = (0..widths.len())
            .map(|i| {
                let t = FstSignalType::bit_vec(widths[i]);
                h.var(format!("s{i}"), t, wire, imp, None).unwrap()
            })
            .collect();
        h.up_scope().unwrap();
        h.up_scope().unwrap();
        let mut b = h.finish().unwrap();
        b.set_deduplicate(false);
        let mut text = Vec::new();
        replay(calls, |c| match c {
            Call::Time(t) => b.time_change(t).unwrap(),
            Call::Change(i, v) => {
                text.clear();
                crate::vcd_text::push_binary(&mut text, widths[i], v);
                b.signal_change(ids[i], &text).unwrap();
            }
            Call::Flush => b.flush().unwrap(),
        });
        b.finish().unwrap().into_inner()
    }

    /// A run of calls as the tracer makes them: changes at time 0 first, then steps of a
    /// time advance followed by changes, and a section written out only right after a step's
    /// changes (where the tracer's writer does it).
    fn calls(n: usize) -> impl Strategy<Value = Vec<Call>> {
        let change = (0..n, any::<u64>()).prop_map(|(i, v)| Call::Change(i, v));
        let step = (
            prop_oneof![3 => 1..4u64, 1 => 100..100_000u64],
            prop::collection::vec(change.clone(), 0..6),
            prop::bool::weighted(0.1),
        );
        (
            prop::collection::vec(change, 0..6),
            prop::collection::vec(step, 0..60),
        )
            .prop_map(|(first, steps)| {
                let mut out = first;
                for (dt, changes, flush) in steps {
                    if flush {
                        out.push(Call::Flush);
                    }
                    out.push(Call::Time(dt));
                    out.extend(changes);
                }
                out
            })
    }

    fn widths_and_calls() -> impl Strategy<Value = (Vec<u32>, Vec<Call>)> {
        prop::collection::vec(prop_oneof![1 => Just(1u32), 2 => 1..=64u32], 1..12).prop_flat_map(
            |w| {
                let n = w.len();
                (Just(w), calls(n))
            },
        )
    }

    proptest! {
        /// The same calls give fst-writer's bytes exactly, bit fields and sections included.
        #[test]
        fn the_bytes_are_fst_writers((widths, calls) in widths_and_calls()) {
            prop_assert_eq!(ours(&widths, &calls), theirs(&widths, &calls));
        }
    }

    /// Long change lists are LZ4-compressed and long time tables zlib-compressed, on both
    /// sides alike; a value's bits above its width are ignored.
    #[test]
    fn compressed_lists_and_tables_are_fst_writers() {
        let widths = [1, 7, 33, 64];
        let mut calls = vec![Call::Change(0, 0), Call::Change(1, 0xff)];
        for k in 0..2000u64 {
            calls.push(Call::Time(1 + k % 3));
            calls.push(Call::Change(
                (k % 4) as usize,
                k.wrapping_mul(0x9e37_79b9_7f4a_7c15),
            ));
            if k % 700 == 699 {
                calls.push(Call::Time(5));
                calls.push(Call::Flush);
            }
        }
        assert_eq!(ours(&widths, &calls), theirs(&widths, &calls));
        // Lists either side of the size below which none is compressed (one byte a change).
        for n in [31, 32] {
            let calls: Vec<Call> = (0..n)
                .flat_map(|_| [Call::Time(1), Call::Change(0, 1)])
                .collect();
            assert_eq!(ours(&[1], &calls), theirs(&[1], &calls));
        }
    }

    #[test]
    fn leb128_at_the_edges() {
        let enc = |v: u64| {
            let mut b = Vec::new();
            varint(&mut b, v);
            b
        };
        assert_eq!(enc(0), [0]);
        assert_eq!(enc(127), [127]);
        assert_eq!(enc(128), [0x80, 1]);
        assert_eq!(enc(u64::MAX).len(), 10);
        let senc = |v: i64| {
            let mut b = Vec::new();
            svarint(&mut b, v);
            b
        };
        assert_eq!(senc(63), [63]);
        assert_eq!(senc(64), [0xc0, 0]);
        assert_eq!(senc(-64), [0x40]);
        assert_eq!(senc(-65), [0xbf, 0x7f]);
    }

    #[test]
    fn bad_declarations_are_errors() {
        let mut h = FstHeader::new(Cursor::new(Vec::new()), -12, VERSION).unwrap();
        h.scope("tb", "");
        let e = h.var("wide", 65).unwrap_err();
        assert_eq!(e.to_string(), "wide: width 65 is not 1 to 64 bits");
        assert!(h.var("none", 0).is_err());
        let long = "v".repeat(128);
        assert!(FstHeader::new(Cursor::new(Vec::new()), -12, &long).is_err());
        let mut b = FstHeader::new(Cursor::new(Vec::new()), -12, VERSION)
            .unwrap()
            .finish()
            .unwrap();
        b.time(10).unwrap();
        assert!(b.time(9).is_err());
    }
}
