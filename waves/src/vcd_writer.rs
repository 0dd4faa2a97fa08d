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

/// How a variable's change line is formatted, worked out once and read once per record (32
/// bytes, one load of half a cache line): what follows the digits, padded to a fixed 16 bytes
/// so that it is copied in one move (a copy of the code's own length was a call to `memcpy`
/// per change), and the widths the line needs, so that formatting a change computes none.
#[derive(Clone, Copy)]
#[repr(C, align(32))]
struct Line {
    /// After the digits: a space (wider than one bit), the code and a newline, zero padded;
    /// meaningful only when `short`.
    after: [u8; 16],
    /// The width, 1 to 64.
    width: u8,
    /// The shift that puts the bits at the top of a word: `64 - width`.
    shift: u8,
    /// The digits' whole bytes: `width / 8` rounded up.
    groups: u8,
    /// The line's length.
    len: u8,
    /// Whether the tail fits `after` (a code of up to 15 characters, 14 after a space:
    /// 94^14 variables).
    short: bool,
    /// Whether the change is this line alone (short, and no `real` companion); otherwise it
    /// takes the general path through its [`Code`].
    alone: bool,
}

impl Line {
    fn of(c: &Code) -> Line {
        let w = c.width.clamp(1, 64) as usize;
        let space = usize::from(w > 1);
        let tail = space + c.code.len() + 1;
        let short = tail <= 16;
        let mut after = [0u8; 16];
        if short {
            if space == 1 {
                after[0] = b' ';
            }
            after[space..tail - 1].copy_from_slice(&c.code);
            after[tail - 1] = b'\n';
        }
        let digits = if w > 1 { 1 + w } else { 1 };
        Line {
            after,
            width: w as u8,
            shift: (64 - w) as u8,
            groups: w.div_ceil(8) as u8,
            // At most 81 when short; the general path formats the others.
            len: if short { (digits + tail) as u8 } else { 0 },
            short,
            alone: short && c.real.is_none(),
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
    // A value change, the most common record, is kind 0: its tag is the variable's index.
    const BITS: u32 = 0;
    const TIME: u32 = 1 << 30;
    const TEXT: u32 = 2 << 30;
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

/// The room a change line is formatted in: `b`, 64 digits and the 16 bytes [`Line::after`]
/// them; a longer code or a `real` goes through a `Vec`.
const LINE: usize = 1 + 64 + 16;

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
    /// end).
    #[inline(always)]
    fn room(&mut self) -> &mut [u8; LINE] {
        // The cursor never passes the end: one compare tests the room and is the slice's
        // bounds check.
        if self.buf.len() - self.pos < LINE {
            self.grow();
        }
        let p = self.pos;
        (&mut self.buf[p..p + LINE]).try_into().expect("LINE")
    }

    /// A value change of a [`Line::short`] line ([`change_at`]).
    fn change(&mut self, l: &Line, bits: u64) {
        self.room();
        self.pos = change_at(&mut self.buf, self.pos, l, bits);
    }

    /// A timestamp ([`time_at`]).
    fn time(&mut self, t: u64) {
        self.room();
        self.pos = time_at(&mut self.buf, self.pos, t);
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

/// A value change of a [`Line::short`] line at `p` in `buf`, which has [`LINE`] bytes of room
/// there, as [`push_change`] writes it; the cursor after it. The line is formatted in whole
/// 8-byte moves: the bits shifted to the top of a word, a byte's eight digits at a time from
/// the top; the digits past the width (of the last byte's eight) are overwritten by what
/// follows them.
#[inline(always)]
fn change_at(buf: &mut [u8], p: usize, l: &Line, bits: u64) -> usize {
    let line: &mut [u8; LINE] = (&mut buf[p..][..LINE]).try_into().expect("LINE");
    let at = if l.width == 1 {
        line[0] = b'0' + (bits & 1) as u8;
        1
    } else {
        line[0] = b'b';
        let top = bits << l.shift;
        for g in 0..usize::from(l.groups) {
            let byte = (top >> (56 - 8 * g)) & 0xff;
            line[1 + 8 * g..][..8].copy_from_slice(&BINARY[byte as usize]);
        }
        1 + usize::from(l.width)
    };
    line[at..at + 16].copy_from_slice(&l.after);
    p + usize::from(l.len)
}

/// The decimal digits of every number below 100, two each.
static PAIRS: [[u8; 2]; 100] = {
    let mut t = [[0u8; 2]; 100];
    let mut v = 0;
    while v < 100 {
        t[v] = [b'0' + (v / 10) as u8, b'0' + (v % 10) as u8];
        v += 1;
    }
    t
};

/// A timestamp at `p` in `buf`, which has [`LINE`] bytes of room there, as [`push_time`]
/// writes it: `#`, the digits and a newline (at most 22 bytes); the cursor after it. The
/// digits are written in place, two at a time from the last: digits made elsewhere and copied
/// in whole words were read back before their narrow writes had landed (a stall for every
/// timestamp), and a copy of their own length was a call to `memcpy`.
#[inline(always)]
fn time_at(buf: &mut [u8], p: usize, t: u64) -> usize {
    let line: &mut [u8; LINE] = (&mut buf[p..][..LINE]).try_into().expect("LINE");
    let n = t.checked_ilog10().map_or(1, |l| l as usize + 1);
    let (mut v, mut k) = (t, 1 + n);
    while k >= 3 {
        k -= 2;
        line[k..k + 2].copy_from_slice(&PAIRS[(v % 100) as usize]);
        v /= 100;
    }
    if k == 2 {
        line[1] = b'0' + v as u8;
    }
    line[0] = b'#';
    line[1 + n] = b'\n';
    p + n + 2
}

/// Formats `recs` onto the end of `text` (which grows to hold them all): runs of value
/// changes and timestamps with the text's buffer and cursor in registers, and each record
/// that ends a run (another kind, or the room run short) on its own.
fn format(text: &mut Text, scratch: &mut Vec<u8>, codes: &[Code], lines: &[Line], recs: &[Rec]) {
    let mut rest = recs;
    loop {
        let done = format_lines(&mut text.buf, &mut text.pos, lines, rest);
        let Some((r, after)) = rest[done..].split_first() else {
            return;
        };
        format_record(text, scratch, codes, lines, r);
        rest = after;
    }
}

/// The value changes that are their [`Line`] alone and the timestamps from the start of
/// `recs`, while the room lasts; how many. The cursor is a local here (the text's own was
/// stored and loaded again for every record, a dependency from each line to the next).
#[inline(always)]
fn format_lines(buf: &mut [u8], pos: &mut usize, lines: &[Line], recs: &[Rec]) -> usize {
    let mut p = *pos;
    let mut n = 0;
    for r in recs {
        if buf.len() - p < LINE {
            break;
        }
        // A value change with one compare: its tag is its index.
        if r.tag < Rec::TIME {
            let l = &lines[r.tag as usize];
            if !l.alone {
                break;
            }
            p = change_at(buf, p, l, r.value);
        } else if r.tag == Rec::TIME {
            p = time_at(buf, p, r.value);
        } else {
            break;
        }
        n += 1;
    }
    *pos = p;
    n
}

/// A record that ended a run of lines, with the text grown as it needs.
fn format_record(text: &mut Text, scratch: &mut Vec<u8>, codes: &[Code], lines: &[Line], r: &Rec) {
    let i = (r.tag & !(3 << 30)) as usize;
    match r.tag & (3 << 30) {
        Rec::BITS => general_change(text, scratch, &codes[i], &lines[i], r.value),
        Rec::TIME => text.time(r.value),
        Rec::TEXT => text.put(TEXTS[i]),
        _ => {
            let code = &codes[i].code;
            text.with_vec(scratch, |b| push_real(b, code, f64::from_bits(r.value)));
        }
    }
}

/// A value change that is not its [`Line`] alone (a code too long for [`Line::after`], or a
/// `real` companion after the line), or one that found too little room.
fn general_change(text: &mut Text, scratch: &mut Vec<u8>, c: &Code, l: &Line, bits: u64) {
    if l.short {
        text.change(l, bits);
    } else {
        text.with_vec(scratch, |b| push_change(b, &c.code, c.width, bits));
    }
    if let Some((code, fmt)) = &c.real {
        text.with_vec(scratch, |b| push_real(b, code, real_of(bits, *fmt)));
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

    /// The line of `code` (no `real` companion) at `width`.
    fn line(code: &[u8], width: u32) -> Line {
        Line::of(&Code {
            code: code.into(),
            width,
            real: None,
        })
    }

    /// The writer thread's line is the same text as [`push_change`] (itself tested against
    /// the `vcd` crate) for every width, bit patterns across the byte boundaries, and codes
    /// of one to fourteen characters.
    #[test]
    fn text_change_is_push_change() {
        for code in [&b"!"[..], b"#%", b"abcdefghijklmn"] {
            for width in 1..=64u32 {
                let l = line(code, width);
                assert!(l.alone, "{code:?} at {width} bits fits");
                let mask = u64::MAX >> (64 - width);
                for bits in [0, mask, 0xa5a5_5a5a_f00f_0ff0 & mask, 1u64 << (width - 1)] {
                    let mut text = Text::new();
                    text.change(&l, bits);
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
        // Fifteen characters fit after a bit, not after a space; sixteen never.
        assert!(line(b"0123456789abcde", 1).short);
        assert!(!line(b"0123456789abcde", 2).short);
        assert!(!line(b"0123456789abcdef", 1).short);
    }

    /// A change whose code is too long for the fast line, or that has a `real` companion, is
    /// what [`push_change`] (and [`push_real`]) write.
    #[test]
    fn the_general_path_is_push_change_and_push_real() {
        let fmt = Format::signed(8, 4);
        for (code, real) in [
            (&b"0123456789abcdef"[..], false),
            (b"!", true),
            (b"0123456789abcdef", true),
        ] {
            let c = Code {
                code: code.into(),
                width: 8,
                real: real.then(|| (b"%".to_vec().into_boxed_slice(), fmt)),
            };
            let l = Line::of(&c);
            assert!(!l.alone);
            let (mut text, mut scratch) = (Text::new(), Vec::new());
            general_change(&mut text, &mut scratch, &c, &l, 0xb7);
            let mut want = Vec::new();
            push_change(&mut want, code, 8, 0xb7);
            if real {
                push_real(&mut want, b"%", real_of(0xb7, fmt));
            }
            assert_eq!(&text.buf[..text.pos], &want[..], "{code:?} real {real}");
        }
    }

    /// A batch of every kind of record, longer than a text's first chunk, formats as the
    /// records one after another do: runs of lines, the records that end them, the growth.
    #[test]
    fn a_batch_is_its_records_one_after_another() {
        let fmt = Format::unsigned(12, 4);
        let codes: Arc<[Code]> = vec![
            Code {
                code: b"!"[..].into(),
                width: 1,
                real: None,
            },
            Code {
                code: b"#%"[..].into(),
                width: 12,
                real: None,
            },
            Code {
                code: b"$"[..].into(),
                width: 12,
                real: Some((b"&".to_vec().into(), fmt)),
            },
            Code {
                code: b"0123456789abcdef"[..].into(),
                width: 64,
                real: None,
            },
        ]
        .into();
        let lines: Vec<Line> = codes.iter().map(Line::of).collect();
        let (mut recs, mut want) = (Vec::new(), Vec::new());
        recs.push(Rec::text(false));
        want.extend_from_slice(TEXTS[0]);
        for k in 0..40_000u64 {
            recs.push(Rec::time(5_000 * k));
            crate::vcd_text::push_time(&mut want, 5_000 * k);
            let i = (k % 5) as usize;
            let bits = k.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - codes[i % 4].width);
            if i == 4 {
                recs.push(Rec::real(0, 0.25 * k as f64));
                push_real(&mut want, b"!", 0.25 * k as f64);
                continue;
            }
            recs.push(Rec::bits(i as u32, bits));
            let c = &codes[i];
            push_change(&mut want, &c.code, c.width, bits);
            if let Some((code, fmt)) = &c.real {
                push_real(&mut want, code, real_of(bits, *fmt));
            }
        }
        let (mut text, mut scratch) = (Text::new(), Vec::new());
        format(&mut text, &mut scratch, &codes, &lines, &recs);
        assert!(want.len() > CHUNK, "the text grew");
        assert_eq!(&text.buf[..text.pos], &want[..]);
    }

    /// A timestamp is [`push_time`]'s text, from one digit to twenty.
    #[test]
    fn text_time_is_push_time() {
        for t in [
            0,
            7,
            10,
            99,
            100,
            5_000,
            12_345,
            1_234_567_890,
            10u64.pow(19),
            u64::MAX,
        ] {
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
        let l = line(b"!", 64);
        let mut text = Text::new();
        text.pos = CHUNK - 1;
        text.change(&l, u64::MAX);
        let real = [b'r'; 3 * LINE];
        text.put(&real);
        let mut want = Vec::new();
        push_change(&mut want, b"!", 64, u64::MAX);
        want.extend_from_slice(&real);
        assert_eq!(&text.buf[CHUNK - 1..text.pos], &want[..]);
        text.change(&l, 0);
        // The second change went into the room the growth kept: b, 64 digits, space, "!\n".
        assert_eq!(text.buf.len() - text.pos, LINE - (1 + 64 + 1 + 2));
    }
}
