//! Banks 810 and their address decoders 822: the two-level layout of Figure 2. Each level's
//! texels are spread in 2x2 groups over four banks, texel (x, y) in bank `2 (y & 1) + (x & 1)`
//! of its group; even levels use banks 0-3, odd levels banks 4-7 (the only reading that gives
//! a trilinear pair L, L+1 for every L, \[C\]). Inside a bank a level is row-major by 2x2
//! groups: word `base + offset(L) + (y >> 1) * ceil(W_L / 2) + (x >> 1)`, where `offset(L)`
//! is the words of the earlier levels of the same group.
//!
//! So the 2x2 of a level after any border operation touches each of its four banks at most
//! once (two neighbours differ in parity unless a clamp, mirror or a 1-texel level makes them
//! the same texel, which is then one read), and the two levels use different banks: one access
//! reads all eight texels. The tests prove it for every position of every level of several
//! maps under every border operation.
//!
//! Here too is an access as the banks receive it ([`AccessRegs`]: the bank words it reads,
//! where each of its texels comes from, its weights), which the address unit 812 fills and
//! passes on.

use super::output_820::Modulate;
use super::Drf;
use crate::fx::Format;
use crate::kernel::declared::Regs;
use crate::kernel::{Module, Reg, Regs, Visitor};

/// Banks on the chip.
pub const BANKS: usize = 8;
/// Words of a page (one DRAM row), \[C\].
pub const ROW_WORDS: u32 = 512;

/// Words one bank may be asked for in one access: one, but four in the literal colour layout
/// (a component's 2x2 all in one bank), read in successive rounds.
pub const ROUNDS: usize = 4;
/// Bank words need 19 bits (280,064 words in banks 0-3).
const WORD_BITS: u32 = 19;
const WORD_NAMES: [[&str; ROUNDS]; BANKS] = [
    ["word0_0", "word0_1", "word0_2", "word0_3"],
    ["word1_0", "word1_1", "word1_2", "word1_3"],
    ["word2_0", "word2_1", "word2_2", "word2_3"],
    ["word3_0", "word3_1", "word3_2", "word3_3"],
    ["word4_0", "word4_1", "word4_2", "word4_3"],
    ["word5_0", "word5_1", "word5_2", "word5_3"],
    ["word6_0", "word6_1", "word6_2", "word6_3"],
    ["word7_0", "word7_1", "word7_2", "word7_3"],
];

/// The bank words an access reads: per bank and round a word (`word[bank][round]`), and in
/// `read` (bit `4 bank + round`) which of them it reads. In the bank stage they are the
/// address decoders 822's, in their own scope.
#[derive(Clone, Debug)]
pub struct BankWords {
    scope: Option<&'static str>,
    pub read: Reg,
    pub word: [[Reg; ROUNDS]; BANKS],
}

impl BankWords {
    fn new(scope: Option<&'static str>) -> BankWords {
        BankWords {
            scope,
            read: Reg::new("read", Format::uint((BANKS * ROUNDS) as u32)),
            word: WORD_NAMES.map(|b| b.map(|n| Reg::new(n, Format::uint(WORD_BITS)))),
        }
    }

    /// Whether the access reads bank `bank` in round `round`, and the word.
    pub fn reads(&self, bank: usize, round: usize) -> Option<u64> {
        let on = self.read.q().bits() >> (bank * ROUNDS + round) & 1 == 1;
        on.then(|| self.word[bank][round].q().bits())
    }

    /// The round in which `bank` reads `word` (the next values being set): the round that
    /// already reads it, else the next free one (`read` marks the taken ones).
    pub(super) fn round_for(&mut self, bank: usize, word: u64, read: &mut u64) -> usize {
        for (r, reg) in self.word[bank].iter_mut().enumerate() {
            let at = bank * ROUNDS + r;
            if *read >> at & 1 == 0 {
                reg.set_next_bits(word);
                *read |= 1 << at;
                return r;
            }
            if reg.next_bits() == word {
                return r;
            }
        }
        unreachable!("a footprint reads at most four texels of one bank");
    }
}

impl Regs for BankWords {
    fn tick_regs(&mut self, reset: bool) {
        self.read.tick(reset);
        self.word.tick_regs(reset);
    }
    fn visit_regs(&self, v: &mut dyn Visitor) {
        if let Some(s) = self.scope {
            v.enter(s, s);
        }
        v.reg(&self.read);
        self.word.visit_regs(v);
        if self.scope.is_some() {
            v.leave();
        }
    }
}

/// One access as it goes from 812 to the banks 810: the words it reads, where each of its
/// eight texels comes from, its weights and the output stage's inputs.
#[derive(Clone, Debug, Regs)]
pub struct AccessRegs {
    pub valid: Reg,
    pub words: BankWords,
    /// Texel t's bank and round, `4 bank + round`, in bits `5t..5t+5`.
    pub src: Reg,
    /// Texel t is the border colour instead (bit t): no bank is read for it.
    pub border: Reg,
    /// a0, b0, a1, b1, f in bytes 0-4.
    pub weights: Reg,
    /// The border colour.
    pub colour: Reg,
    /// The DRF's configuration is index (CLUT 814).
    pub index: Reg,
    /// The colour component this access reads (planar, literal) and whether it is the
    /// request's last; a luminance or index access is part 0 and last.
    pub part: Reg,
    pub last: Reg,
    /// Eq. 5: the request's illumination, and the DRF's choice (0 I_d, 1 k_T, 2 one) with k_T.
    pub illum: Reg,
    pub modulate: Reg,
}

impl AccessRegs {
    /// The registers; the bank words in the scope `decoders` if given.
    pub fn new(decoders: Option<&'static str>) -> AccessRegs {
        let u = |name, bits| Reg::new(name, Format::uint(bits));
        AccessRegs {
            valid: u("valid", 1),
            words: BankWords::new(decoders),
            src: u("src", 40),
            border: u("border", 8),
            weights: u("weights", 40),
            colour: u("colour", 8),
            index: u("index", 1),
            part: u("part", 2),
            last: u("last", 1),
            illum: u("illum", 32),
            modulate: u("modulate", 10),
        }
    }

    /// At the edge every register but `valid` takes `o`'s value: the access moving on.
    pub fn take_from(&mut self, o: &AccessRegs) {
        let copy = |to: &mut Reg, from: &Reg| to.set_next_bits(from.q().bits());
        copy(&mut self.words.read, &o.words.read);
        let words = self.words.word.iter_mut().flatten();
        for (to, from) in words.zip(o.words.word.iter().flatten()) {
            copy(to, from);
        }
        copy(&mut self.src, &o.src);
        copy(&mut self.border, &o.border);
        copy(&mut self.weights, &o.weights);
        copy(&mut self.colour, &o.colour);
        copy(&mut self.index, &o.index);
        copy(&mut self.part, &o.part);
        copy(&mut self.last, &o.last);
        copy(&mut self.illum, &o.illum);
        copy(&mut self.modulate, &o.modulate);
    }

    /// Texel `t`'s bank and word, or `None` when it is the border colour.
    pub fn texel_word(&self, t: usize) -> Option<(usize, u64)> {
        if self.border.q().bits() >> t & 1 == 1 {
            return None;
        }
        let at = (self.src.q().bits() >> (5 * t) & 0x1F) as usize;
        let (bank, round) = (at / ROUNDS, at % ROUNDS);
        Some((bank, self.words.word[bank][round].q().bits()))
    }

    /// The weights `a`, `b` per level and `f`.
    pub fn weights(&self) -> ([u8; 2], [u8; 2], u8) {
        let w = self.weights.q().bits().to_le_bytes();
        ([w[0], w[2]], [w[1], w[3]], w[4])
    }

    /// Eq. 5's factor.
    pub fn modulate(&self) -> Modulate {
        let m = self.modulate.q().bits();
        match m >> 8 {
            0 => Modulate::Illumination,
            1 => Modulate::Constant(m as u8),
            _ => Modulate::One,
        }
    }
}

/// Words per bank of level `k`'s group: `ceil(W/2) * ceil(H/2)`.
fn level_words(drf: &Drf, k: u32) -> u32 {
    let (w, h) = drf.level_size(k);
    w.div_ceil(2) * h.div_ceil(2)
}

/// First word of level `k` inside its group (after the earlier levels of the same parity).
pub fn offset(drf: &Drf, k: u32) -> u32 {
    (k % 2..k).step_by(2).map(|j| level_words(drf, j)).sum()
}

/// Words the map takes in each bank of the even (`group` 0) or odd (1) levels.
pub fn group_words(drf: &Drf, group: u32) -> u32 {
    (group..=drf.max_level())
        .step_by(2)
        .map(|j| level_words(drf, j))
        .sum()
}

/// Bank and word of texel `(x, y)` of level `k`.
pub fn locate(drf: &Drf, k: u32, x: u32, y: u32) -> (usize, u32) {
    let group = k & 1;
    let bank = 4 * group + 2 * (y & 1) + (x & 1);
    let base = if group == 0 {
        drf.base_even
    } else {
        drf.base_odd
    };
    let (w, _) = drf.level_size(k);
    let word = base + offset(drf, k) + (y >> 1) * w.div_ceil(2) + (x >> 1);
    (bank as usize, word)
}

/// Writes level `k` of the map of `d` (row-major texels of the level's size) into `banks`,
/// each texel where [`locate`] says; an error names a level the map does not have or whose
/// texels do not fit.
pub fn store_level(banks: &mut [Vec<u8>], d: &Drf, k: u32, texels: &[u8]) -> Result<(), String> {
    if k > d.max_level() {
        return Err(format!(
            "level {k}: the map has levels 0..={}",
            d.max_level()
        ));
    }
    let (w, h) = d.level_size(k);
    if texels.len() != (w * h) as usize {
        return Err(format!("level {k}: {} texels for {w}x{h}", texels.len()));
    }
    for y in 0..h {
        for x in 0..w {
            let (bank, word) = locate(d, k, x, y);
            let cell = banks[bank]
                .get_mut(word as usize)
                .ok_or_else(|| format!("level {k}: word {word} beyond bank {bank}"))?;
            *cell = texels[(y * w + x) as usize];
        }
    }
    Ok(())
}

/// Words per bank for the largest map, 1024 x 1024 with its chain (derived, \[C\]): even-level
/// banks 279,621 words (bank 0; banks 1-3 one fewer), odd-level banks 69,905, each rounded up
/// to whole rows.
pub fn bank_words(bank: usize) -> u32 {
    let full = Drf::new(10, 10, super::Border::Wrap);
    group_words(&full, (bank / 4) as u32).next_multiple_of(ROW_WORDS)
}

/// The bank stage: the access being served (its bank words decoded by the address decoders
/// 822), the cycles left in its slot(s), whether it faulted, and how many video segments it
/// is when the video port has the banks. The chip drives it in its own `eval`.
#[derive(Clone, Debug, Module)]
#[module(kind = "banks_810")]
pub struct Banks810 {
    #[reg]
    pub access: AccessRegs,
    #[reg]
    pub left: Reg,
    #[reg]
    pub fault: Reg,
    /// The bank stage serves `vid_round` segments of the video port (0: a rasterizer access).
    #[reg]
    pub vid_round: Reg,
}

impl Default for Banks810 {
    fn default() -> Self {
        Banks810::new()
    }
}

impl Banks810 {
    pub fn new() -> Banks810 {
        Banks810 {
            access: AccessRegs::new(Some("address_decoders_822")),
            left: Reg::new("left", Format::uint(8)),
            fault: Reg::new("fault", Format::uint(1)),
            vid_round: Reg::new("vid_round", Format::uint(4)),
        }
    }

    /// Nothing of its own: the chip's `eval` sets its registers.
    pub fn eval(&mut self) {}

    /// The eight texels of the access served, from the banks' contents `memory` (or the
    /// border colour).
    pub fn texels(&self, memory: &[Vec<u8>]) -> [u8; 8] {
        let a = &self.access;
        std::array::from_fn(|t| match a.texel_word(t) {
            Some((bank, word)) => memory[bank][word as usize],
            None => a.colour.q().bits() as u8,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Border, Footprint};
    use super::*;
    use std::collections::HashMap;

    const MAPS: [(u32, u32); 6] = [(6, 6), (0, 5), (5, 0), (3, 1), (1, 4), (0, 0)];
    const BORDERS: [Border; 4] = [
        Border::Wrap,
        Border::Clamp,
        Border::Mirror,
        Border::Colour(9),
    ];

    #[test]
    fn every_texel_has_its_own_bank_word() {
        for (wl, hl) in MAPS {
            let drf = Drf::new(wl, hl, Border::Wrap);
            let mut seen = HashMap::new();
            for k in 0..=drf.max_level() {
                let (w, h) = drf.level_size(k);
                for y in 0..h {
                    for x in 0..w {
                        let at = locate(&drf, k, x, y);
                        assert!(at.1 < group_words(&drf, k & 1), "{wl},{hl} L{k} ({x},{y})");
                        let old = seen.insert(at, (k, x, y));
                        assert!(old.is_none(), "{at:?} holds {old:?} and {:?}", (k, x, y));
                    }
                }
            }
        }
    }

    /// The invariant of the layout: any footprint, any level, any border: per bank at most one
    /// distinct word.
    #[test]
    fn every_trilinear_footprint_is_conflict_free() {
        for (wl, hl) in MAPS {
            for border in BORDERS {
                let drf = Drf::new(wl, hl, border);
                for k in 0..=drf.max_level() {
                    let (w, h) = drf.level_size(k);
                    let lambda = (k as i32) << 8 | 0x80;
                    // Every 2x2 position at level k, inside the map and one texel beyond each
                    // edge, at the texel-centre offset that makes (i, j) the first corner.
                    for j in -2..=h as i32 + 1 {
                        for i in -2..=w as i32 + 1 {
                            let u = ((2 * i + 1) << 7) << k;
                            let v = ((2 * j + 1) << 7) << k;
                            let fp = Footprint::of(&drf, u, v, lambda);
                            assert_eq!(fp.fine, k);
                            let mut word = [None; BANKS];
                            for (n, lv) in [fp.fine, fp.coarse].into_iter().enumerate() {
                                for (x, y) in fp.texels[n].iter().flatten() {
                                    let (bank, wd) = locate(&drf, lv, *x, *y);
                                    let ok = word[bank].is_none_or(|old| old == wd);
                                    assert!(ok, "{wl},{hl} {border:?} L{k} ({i},{j}): bank {bank}");
                                    word[bank] = Some(wd);
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_largest_map_fits_the_banks() {
        assert_eq!(group_words(&Drf::new(10, 10, Border::Wrap), 0), 279_621);
        assert_eq!(group_words(&Drf::new(10, 10, Border::Wrap), 1), 69_905);
        assert_eq!(bank_words(0), 547 * 512);
        assert_eq!(bank_words(7), 137 * 512);
    }
}
