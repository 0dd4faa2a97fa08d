//! Fuzzing every parser of the file formats: valid PGM/PPM (ASCII and binary), `.ccc` and CSV
//! inputs with up to eight byte-level mutations ([`verif::mutate`]) must parse or give a
//! clean error, never panic, and never allocate more than the input could describe.
//!
//! The allocation bound: a parser holds at most a few machine words per input byte (a CSV
//! row is a `Vec` of `String`s, a pixel one byte, a block four bytes), so no single
//! allocation may exceed 64 bytes per input byte plus 64 KiB. A size read from a header and
//! allocated before it is checked against the input (the `P2` 65535x65535 abort found
//! once) breaks it by orders of magnitude. Seeds are printed; replay with `TEXRTL_SEED`.

use proptest::test_runner::TestCaseError;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use verif::mutate::{mutated, mutations};

/// The system allocator, recording the largest request made by a thread that asked for it.
struct Watch;

thread_local! {
    static WATCHING: Cell<bool> = const { Cell::new(false) };
    static LARGEST: Cell<usize> = const { Cell::new(0) };
    /// Mutated inputs that parsed (the fuzzing reaches past the first check).
    static ACCEPTED: Cell<usize> = const { Cell::new(0) };
}

/// Fails unless at least `min` of the cases parsed (each test runs on its own thread).
fn reached(min: usize) {
    let n = ACCEPTED.with(Cell::get);
    assert!(n >= min, "only {n} mutated inputs parsed");
}

fn note(size: usize) {
    if WATCHING.with(Cell::get) {
        LARGEST.with(|l| l.set(l.get().max(size)));
    }
}

unsafe impl GlobalAlloc for Watch {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOC: Watch = Watch;

/// Runs `parse` on `input`, watching its allocations; fails the case on a panic or an
/// allocation over the bound.
fn within_bounds<T>(
    input: &[u8],
    parse: impl FnOnce(&[u8]) -> Result<T, String>,
) -> Result<Option<T>, TestCaseError> {
    LARGEST.with(|l| l.set(0));
    WATCHING.with(|w| w.set(true));
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| parse(input)));
    WATCHING.with(|w| w.set(false));
    let largest = LARGEST.with(Cell::get);
    let bound = 64 * input.len() + (64 << 10);
    if largest > bound {
        return Err(TestCaseError::fail(format!(
            "allocated {largest} bytes for a {}-byte input",
            input.len()
        )));
    }
    match r {
        Ok(Ok(v)) => {
            ACCEPTED.with(|a| a.set(a.get() + 1));
            Ok(Some(v))
        }
        Ok(Err(msg)) => {
            if msg.is_empty() || msg.contains('\n') || msg.len() > 300 {
                return Err(TestCaseError::fail(format!("not one short line: {msg:?}")));
            }
            Ok(None)
        }
        Err(_) => Err(TestCaseError::fail("panicked")),
    }
}

fn pgm_seeds() -> Vec<Vec<u8>> {
    let px: Vec<u8> = (0..48u8).map(|k| k.wrapping_mul(29)).collect();
    let mut ascii = b"P2\n# a comment\n8 6\n255\n".to_vec();
    for p in &px {
        ascii.extend_from_slice(format!("{p} ").as_bytes());
    }
    vec![formats::netpbm::encode(8, 6, &px), ascii]
}

fn ppm_seeds() -> Vec<Vec<u8>> {
    let rgb: Vec<u8> = (0..8 * 4 * 3).map(|k| (k * 7 % 256) as u8).collect();
    let mut ascii = b"P3\n8 4\n255\n".to_vec();
    for p in &rgb {
        ascii.extend_from_slice(format!("{p}\n").as_bytes());
    }
    vec![formats::netpbm::encode_ppm(8, 4, &rgb), ascii]
}

/// Checks what a parsed image claims against what it holds.
fn image_consistent(w: u32, h: u32, len: usize, per: usize) -> Result<(), TestCaseError> {
    let want = w as usize * h as usize * per;
    if len != want {
        return Err(TestCaseError::fail(format!(
            "{w}x{h} image with {len} samples"
        )));
    }
    Ok(())
}

#[test]
fn pgm_parser_survives_mutations() {
    let seeds = pgm_seeds();
    let mut runner = verif::seeded_runner("pgm_parser_survives_mutations", 3000);
    let strat = (0..seeds.len(), mutations(8));
    runner
        .run(&strat, |(k, muts)| {
            let input = mutated(&seeds[k], &muts);
            if let Some(img) = within_bounds(&input, formats::netpbm::parse)? {
                image_consistent(img.width, img.height, img.pixels.len(), 1)?;
            }
            Ok(())
        })
        .unwrap();
    reached(30);
}

#[test]
fn ppm_parser_survives_mutations() {
    let seeds = ppm_seeds();
    let mut runner = verif::seeded_runner("ppm_parser_survives_mutations", 3000);
    let strat = (0..seeds.len(), mutations(8));
    runner
        .run(&strat, |(k, muts)| {
            let input = mutated(&seeds[k], &muts);
            if let Some(img) = within_bounds(&input, formats::netpbm::parse_ppm)? {
                image_consistent(img.width, img.height, img.pixels.len(), 3)?;
            }
            Ok(())
        })
        .unwrap();
    reached(30);
}

#[test]
fn ccc_parser_survives_mutations_and_round_trips() {
    let ppm = formats::netpbm::parse_ppm(&ppm_seeds()[0]).unwrap();
    let seed = formats::ccc::encode(&ppm).unwrap().to_bytes();
    let mut runner = verif::seeded_runner("ccc_parser_survives_mutations", 3000);
    runner
        .run(&mutations(8), |muts| {
            let input = mutated(&seed, &muts);
            if let Some(c) = within_bounds(&input, formats::ccc::Ccc::parse)? {
                // Whatever parses writes back to the same bytes and decodes.
                if c.to_bytes() != input {
                    return Err(TestCaseError::fail("does not write back the same bytes"));
                }
                image_consistent(c.width, c.height, c.decode().len(), 3)?;
            }
            Ok(())
        })
        .unwrap();
    reached(30);
}

#[test]
fn csv_parser_survives_mutations() {
    let seeds: [(&[u8], &[&str]); 3] = [
        (b"u,v\n1.5,2\n-3,4e2\n\n7,8\n", &["u,v"]),
        (b"addr\n0\n1\n600\n", &["addr"]),
        (
            b"u,v,dudx,dvdx\n1,2,0.5,0\n3,4,0,0.25\n",
            &["u,v", "u,v,dudx,dvdx"],
        ),
    ];
    let mut runner = verif::seeded_runner("csv_parser_survives_mutations", 3000);
    let strat = (0..seeds.len(), mutations(8));
    runner
        .run(&strat, |(k, muts)| {
            let (seed, headers) = seeds[k];
            let input = mutated(seed, &muts);
            let parse = |b: &[u8]| {
                let text = std::str::from_utf8(b).map_err(|e| format!("t.csv: {e}"))?;
                let t = formats::csv::parse("t.csv", text, headers)?;
                // Every field read as a finite number, as the commands read them.
                for r in &t.rows {
                    for c in 0..t.columns.len() {
                        t.finite(r, c)?;
                    }
                }
                Ok(t)
            };
            if let Some(t) = within_bounds(&input, parse)? {
                if t.rows.iter().any(|r| r.fields.len() != t.columns.len()) {
                    return Err(TestCaseError::fail("a row of the wrong width"));
                }
            }
            Ok(())
        })
        .unwrap();
    reached(30);
}

/// The allocation watch itself: a parser that allocates by a declared size is caught.
#[test]
fn the_watch_catches_an_allocation_by_declared_size() {
    let r = within_bounds(b"P2 65535 65535 255", |_| {
        Ok::<_, String>(Vec::<u8>::with_capacity(65535 * 65535))
    });
    assert!(r.is_err());
}
