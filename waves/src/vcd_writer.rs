//! The VCD tracer's formatter threads: the simulation hands over each cycle's changes as
//! compact records (which variable, which value) in numbered batches; each formatter thread
//! formats whole batches into VCD text, side by side, and the texts are written to the file
//! in the batches' order, so formatting and writing overlap with simulating and with each
//! other. The text is what formatting the records one after another gives (the functions
//! are tested against [`push_change`] and `push_time`, themselves against the `vcd` crate).

use crate::vcd_text::{push_change, push_real, real_of, BINARY};
use hdl::fx::Format;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::sync::mpsc::{channel, sync_channel, Receiver, Sender, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

pub(crate) type Out = vcd::Writer<BufWriter<File>>;

/// Records per batch handed to the formatters: large enough that handing over costs little
/// (a quarter of this: 14 % fewer cycles a second on replicate unit 152's VCD), small enough
/// that a batch and its text stay in the cache (four times this: 13 % fewer).
pub(crate) const BATCH: usize = 1 << 16;

/// The text a formatter starts a batch with (it grows for a larger batch); written to the
/// file at once, straight through the writer's buffer.
const CHUNK: usize = 1 << 18;

/// How one variable is written: its identifier code and width, and for a fixed-point signal
/// with a `real` companion, the companion's code and the signal's format.
pub(crate) struct Code {
    pub code: Box<[u8]>,
    pub width: u32,
    pub real: Option<(Box<[u8]>, Format)>,
}

/// What ends a change line: the code and a newline, padded to a fixed 16 bytes so that it is
/// copied in one move (a copy of the code's own length was a call to `memcpy` per change).
#[derive(Clone, Copy)]
struct Tail {
    bytes: [u8; 16],
    len: usize,
}

impl Tail {
    /// The tail of `code`, if it is short enough (up to 15 characters: 94^15 variables).
    fn of(code: &[u8]) -> Option<Tail> {
        let mut bytes = [0u8; 16];
        bytes.get_mut(..code.len())?.copy_from_slice(code);
        *bytes.get_mut(code.len())? = b'\n';
        Some(Tail {
            bytes,
            len: code.len() + 1,
        })
    }
}

/// How a variable's change is formatted, dense and read once per record: its [`Tail`] (if
/// its code is short enough) and width, and whether the line is [`Text::change`] alone (a
/// tail, no `real` companion) or takes the general path through its [`Code`].
#[derive(Clone, Copy)]
struct Line {
    tail: Option<Tail>,
    width: u32,
    alone: bool,
}

impl Line {
    fn of(c: &Code) -> Line {
        let tail = Tail::of(&c.code);
        Line {
            tail,
            width: c.width,
            alone: tail.is_some() && c.real.is_none(),
        }
    }
}

/// One step of the dump, in order: 16 bytes (what crosses between the threads is most of the
/// cost, so the record is packed: a kind and an index in one word, a value in the other).
#[derive(Clone, Copy)]
pub(crate) struct Rec {
    /// The kind in the top two bits, an index below.
    tag: u32,
    value: u64,
}

/// The records of a batch being collected: a buffer of fixed length and a cursor. A
/// `Vec::push` per record stored the length and checked the capacity each time (a third of
/// the simulation's side of a traced cycle); here the cursor stays in a register. The
/// buffer keeps its length across the threads (a formatter reads the first `n` records and
/// gives the buffer back as it is), so it is filled once.
pub(crate) struct Batch {
    recs: Vec<Rec>,
    n: usize,
}

impl Batch {
    /// An empty batch that holds `len` records.
    pub fn new(len: usize) -> Batch {
        Batch {
            recs: vec![Rec::time(0); len],
            n: 0,
        }
    }

    /// Appends `r`; panics past the length (the tracer hands a batch over once it holds
    /// [`BATCH`] records, and makes it longer by what one cycle can add).
    #[inline(always)]
    pub fn push(&mut self, r: Rec) {
        self.recs[self.n] = r;
        self.n += 1;
    }

    /// The buffer and the cursor, for a loop that keeps the cursor in a local and writes it
    /// back at its end.
    pub fn parts(&mut self) -> (&mut [Rec], &mut usize) {
        (&mut self.recs, &mut self.n)
    }

    /// How many records it holds (none before the tracer knows its signals).
    pub fn capacity(&self) -> usize {
        self.recs.len()
    }

    /// The records collected.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Forgets the records (the buffer stays).
    pub fn clear(&mut self) {
        self.n = 0;
    }

    fn recs(&self) -> &[Rec] {
        &self.recs[..self.n]
    }
}

/// The texts a [`Rec::text`] can name.
const TEXTS: [&[u8]; 2] = [b"$dumpvars\n", b"$end\n"];

impl Rec {
    const TIME: u32 = 0;
    const TEXT: u32 = 1 << 30;
    const BITS: u32 = 2 << 30;
    const REAL: u32 = 3 << 30;

    /// `#t`.
    pub fn time(t: u64) -> Rec {
        Rec {
            tag: Rec::TIME,
            value: t,
        }
    }
    /// `$dumpvars` (`end` false) or `$end`.
    pub fn text(end: bool) -> Rec {
        Rec {
            tag: Rec::TEXT | u32::from(end),
            value: 0,
        }
    }
    /// Variable `codes[i]` takes bits `v` (and its companion, if any, their real value).
    pub fn bits(i: u32, v: u64) -> Rec {
        debug_assert!(i < 1 << 30);
        Rec {
            tag: Rec::BITS | i,
            value: v,
        }
    }
    /// Real variable `codes[i]` takes `x`.
    pub fn real(i: u32, x: f64) -> Rec {
        debug_assert!(i < 1 << 30);
        Rec {
            tag: Rec::REAL | i,
            value: x.to_bits(),
        }
    }
}

/// The text being formatted: a fixed buffer and a cursor (the cursor stays in a register;
/// a `Vec` would store its length at every byte).
struct Text {
    buf: Box<[u8]>,
    pos: usize,
}

/// The longest line a change makes: `b`, 64 digits, a space and a [`Tail`]; a longer code
/// or a `real` goes through a `Vec`.
const LINE: usize = 1 + 64 + 1 + 16;

impl Text {
    fn new() -> Text {
        Text {
            buf: vec![0; CHUNK + LINE].into_boxed_slice(),
            pos: 0,
        }
    }

    /// Appends `bytes`; a record's lines may pass the chunk (a change and its `real`
    /// companion), so the buffer grows when they would pass its end, keeping a line's room
    /// for [`Text::change`].
    fn put(&mut self, bytes: &[u8]) {
        let end = self.pos + bytes.len();
        if end + LINE > self.buf.len() {
            let mut grown = vec![0; end + LINE].into_boxed_slice();
            grown[..self.pos].copy_from_slice(&self.buf[..self.pos]);
            self.buf = grown;
        }
        self.buf[self.pos..end].copy_from_slice(bytes);
        self.pos = end;
    }

    /// The [`LINE`] bytes of room at the cursor (the text grows when they would pass its
    /// end). The test and the slice's own bounds check are one compare.
    #[inline(always)]
    fn room(&mut self) -> &mut [u8; LINE] {
        if self.pos + LINE > self.buf.len() {
            self.grow();
        }
        let p = self.pos;
        (&mut self.buf[p..p + LINE]).try_into().expect("LINE")
    }

    /// A value change, as [`push_change`] writes it. The line is formatted within the
    /// [`LINE`] bytes of room at the cursor, in whole 8-byte moves: the bits shifted to the
    /// top of a word, a byte's eight digits at a time from the top; the digits past the width
    /// (of the last byte's eight) are overwritten by the space and the tail.
    #[inline(always)]
    fn change(&mut self, tail: &Tail, width: u32, bits: u64) {
        let line = self.room();
        let w = (width as usize).clamp(1, 64);
        let end = if w == 1 {
            line[0] = b'0' + (bits & 1) as u8;
            1
        } else {
            line[0] = b'b';
            let top = bits << (64 - w);
            for g in 0..w.div_ceil(8) {
                let byte = (top >> (56 - 8 * g)) & 0xff;
                line[1 + 8 * g..][..8].copy_from_slice(&BINARY[byte as usize]);
            }
            line[1 + w] = b' ';
            w + 2
        };
        line[end..end + 16].copy_from_slice(&tail.bytes);
        self.pos += end + tail.len;
    }

    /// A timestamp, as [`push_time`] writes it: `#`, the digits and a newline, within the
    /// [`LINE`] bytes of room at the cursor (at most 22 of them).
    #[inline(always)]
    fn time(&mut self, t: u64) {
        let mut digits = itoa::Buffer::new();
        let d = digits.format(t).as_bytes();
        let line = self.room();
        line[0] = b'#';
        line[1..1 + d.len()].copy_from_slice(d);
        line[1 + d.len()] = b'\n';
        self.pos += d.len() + 2;
    }

    /// Doubles the room (a batch's text is formatted whole before it is written).
    fn grow(&mut self) {
        let mut grown = vec![0; 2 * self.buf.len()].into_boxed_slice();
        grown[..self.pos].copy_from_slice(&self.buf[..self.pos]);
        self.buf = grown;
    }

    /// Appends what a `Vec` formatter wrote.
    fn with_vec(&mut self, scratch: &mut Vec<u8>, f: impl FnOnce(&mut Vec<u8>)) {
        scratch.clear();
        f(scratch);
        self.put(scratch);
    }
}

/// Formats `recs` onto the end of `text` (which grows to hold them all).
fn format(text: &mut Text, scratch: &mut Vec<u8>, codes: &[Code], lines: &[Line], recs: &[Rec]) {
    for r in recs {
        let i = (r.tag & !(3 << 30)) as usize;
        match r.tag & (3 << 30) {
            Rec::TIME => text.time(r.value),
            Rec::TEXT => text.put(TEXTS[i]),
            Rec::BITS => {
                let l = &lines[i];
                if let (true, Some(tail)) = (l.alone, &l.tail) {
                    text.change(tail, l.width, r.value);
                    continue;
                }
                let c = &codes[i];
                match &l.tail {
                    Some(tail) => text.change(tail, c.width, r.value),
                    None => text.with_vec(scratch, |b| push_change(b, &c.code, c.width, r.value)),
                }
                if let Some((code, fmt)) = &c.real {
                    text.with_vec(scratch, |b| push_real(b, code, real_of(r.value, *fmt)));
                }
            }
            _ => {
                let code = &codes[i].code;
                text.with_vec(scratch, |b| push_real(b, code, f64::from_bits(r.value)));
            }
        }
    }
}

/// The file's end of the formatters: each batch's text, written in the order the batches
/// were handed over whichever formatter finishes first; the first error stops the writing.
struct InOrder {
    out: Out,
    /// The sequence number of the next text to write.
    next: u64,
    /// Texts formatted ahead of their turn.
    early: BTreeMap<u64, Text>,
    /// Emptied texts, for the formatters to reuse.
    spare: Vec<Text>,
    error: Option<io::Error>,
}

impl InOrder {
    /// Takes batch `seq`'s text and writes every text now in turn.
    fn put(&mut self, seq: u64, text: Text) {
        self.early.insert(seq, text);
        while let Some(mut t) = self.early.remove(&self.next) {
            if self.error.is_none() {
                if let Err(e) = self.out.writer().write_all(&t.buf[..t.pos]) {
                    self.error = Some(e);
                }
            }
            t.pos = 0;
            self.spare.push(t);
            self.next += 1;
        }
    }
}

/// What the formatter threads share: the queue of numbered batches and the file's end.
struct Shared {
    batches: Mutex<Receiver<(u64, Batch)>>,
    file: Mutex<InOrder>,
    codes: Arc<[Code]>,
    lines: Vec<Line>,
}

/// One formatter thread: takes the next batch, formats it into a text of its own (outside
/// every lock, so the formatters work side by side), hands the text to the file's end in
/// its turn and the emptied batch back for reuse; until the simulation hangs up or a write
/// fails.
fn run(shared: Arc<Shared>, recycle: Sender<Batch>) {
    let mut scratch = Vec::with_capacity(64);
    loop {
        let next = shared.batches.lock().map(|q| q.recv());
        let Ok(Ok((seq, mut batch))) = next else {
            return;
        };
        let Ok(mut file) = shared.file.lock() else {
            return;
        };
        if file.error.is_some() {
            return;
        }
        let mut text = file.spare.pop().unwrap_or_else(Text::new);
        drop(file);
        format(
            &mut text,
            &mut scratch,
            &shared.codes,
            &shared.lines,
            batch.recs(),
        );
        batch.clear();
        let _ = recycle.send(batch);
        match shared.file.lock() {
            Ok(mut file) => file.put(seq, text),
            Err(_) => return,
        }
    }
}

/// The simulation's end of the formatter threads.
pub(crate) struct WriterThread {
    batches: SyncSender<(u64, Batch)>,
    seq: u64,
    recycle: Receiver<Batch>,
    shared: Arc<Shared>,
    handles: Vec<JoinHandle<()>>,
}

/// Formatter threads: as many as the machine runs at once (the simulation's thread, which
/// waits while they are behind, shares them), at most four.
fn formatters() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get().min(4))
}

impl WriterThread {
    pub fn spawn(w: Out, codes: Arc<[Code]>) -> io::Result<WriterThread> {
        let (batches, rx) = sync_channel(8);
        let (back, recycle) = channel();
        let shared = Arc::new(Shared {
            batches: Mutex::new(rx),
            file: Mutex::new(InOrder {
                out: w,
                next: 0,
                early: BTreeMap::new(),
                spare: Vec::new(),
                error: None,
            }),
            lines: codes.iter().map(Line::of).collect(),
            codes,
        });
        let mut handles = Vec::new();
        for _ in 0..formatters() {
            let (shared, back) = (Arc::clone(&shared), back.clone());
            let spawned = std::thread::Builder::new()
                .name("vcd-writer".into())
                .spawn(move || run(shared, back));
            match spawned {
                Ok(h) => handles.push(h),
                // Fewer formatters are as good as more for the text; none is an error.
                Err(e) if handles.is_empty() => return Err(e),
                Err(_) => break,
            }
        }
        Ok(WriterThread {
            batches,
            seq: 0,
            recycle,
            shared,
            handles,
        })
    }

    /// Hands over `batch` and returns an empty one, or the writer's error (the formatters
    /// have then ended: the writer comes back too).
    pub fn send(mut self, batch: Batch) -> Result<(WriterThread, Batch), (Out, io::Error)> {
        let len = batch.recs.len();
        let failed = self.shared.file.lock().map_or(true, |f| f.error.is_some());
        if failed || self.batches.send((self.seq, batch)).is_err() {
            let (w, r) = self.join();
            let e = r
                .err()
                .unwrap_or_else(|| io::Error::other("the VCD writer stopped"));
            return Err((w, e));
        }
        self.seq += 1;
        let next = self.recycle.try_recv().unwrap_or_else(|_| Batch::new(len));
        Ok((self, next))
    }

    /// Waits for everything handed over to be written; the writer comes back.
    pub fn join(self) -> (Out, io::Result<()>) {
        drop(self.batches);
        for h in self.handles {
            // `run` does not panic short of a bug; then there is no writer to give back.
            if let Err(p) = h.join() {
                std::panic::resume_unwind(p);
            }
        }
        let Ok(shared) = Arc::try_unwrap(self.shared) else {
            unreachable!("every formatter has ended");
        };
        let file = shared.file.into_inner().unwrap_or_else(|p| p.into_inner());
        let r = match file.error {
            Some(e) => Err(e),
            None => Ok(()),
        };
        (file.out, r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The writer thread's line is the same text as [`push_change`] (itself tested against
    /// the `vcd` crate) for every width, bit patterns across the byte boundaries, and codes
    /// of one to fifteen characters.
    #[test]
    fn text_change_is_push_change() {
        for code in [&b"!"[..], b"#%", b"abcdefghijklmno"] {
            let tail = Tail::of(code).expect("short code");
            for width in 1..=64u32 {
                let mask = u64::MAX >> (64 - width);
                for bits in [0, mask, 0xa5a5_5a5a_f00f_0ff0 & mask, 1u64 << (width - 1)] {
                    let mut text = Text::new();
                    text.change(&tail, width, bits);
                    let mut want = Vec::new();
                    push_change(&mut want, code, width, bits);
                    assert_eq!(
                        &text.buf[..text.pos],
                        &want[..],
                        "width {width} bits {bits:#x}"
                    );
                }
            }
        }
        assert!(
            Tail::of(b"0123456789abcdef").is_none(),
            "16 characters take the long path"
        );
    }

    /// A timestamp is [`push_time`]'s text, from one digit to twenty.
    #[test]
    fn text_time_is_push_time() {
        for t in [0, 7, 5_000, 1_234_567_890, u64::MAX] {
            let mut text = Text::new();
            text.time(t);
            let mut want = Vec::new();
            crate::vcd_text::push_time(&mut want, t);
            assert_eq!(&text.buf[..text.pos], &want[..], "t {t}");
        }
    }

    /// A record that starts just under the chunk and writes a 64-bit change and a `real`
    /// companion after it fits: the buffer grows, nothing is lost or overwritten.
    #[test]
    fn a_change_and_its_companion_fit_past_the_chunk() {
        let tail = Tail::of(b"!").unwrap();
        let mut text = Text::new();
        text.pos = CHUNK - 1;
        text.change(&tail, 64, u64::MAX);
        let real = [b'r'; 3 * LINE];
        text.put(&real);
        let mut want = Vec::new();
        push_change(&mut want, b"!", 64, u64::MAX);
        want.extend_from_slice(&real);
        assert_eq!(&text.buf[CHUNK - 1..text.pos], &want[..]);
        text.change(&tail, 64, 0);
        // The second change went into the room the growth kept: b, 64 digits, space, "!\n".
        assert_eq!(text.buf.len() - text.pos, LINE - (1 + 64 + 1 + 2));
    }
}
