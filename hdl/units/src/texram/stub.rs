//! A behavioural TEXRAM: the banks 810 as arrays, the address arithmetic of 812, the page
//! registers 824 and the interpolator 818, composed access by access. Its texels, weights,
//! result, slots and faults are those the chip is specified to give; it has no clock, no
//! video port and one configuration (luminance). It lets the footprint assembly, volume and
//! map-chain work start before the cycle-accurate chip exists, and will be held against it.

use super::address_812::Footprint;
use super::banks_810::{bank_words, locate, store_level, BANKS, ROW_WORDS};
use super::clut_814::Clut;
use super::trilinear_818::trilinear;
use super::{Border, Config, Drf, TexramAccess, TexramReply, TexramRequest, DRFS};
use crate::kernel::Module;
use crate::pages::page_registers_824::{Cost, PageRegisters824};

/// The chip's state: DRFs, bank contents, open rows and counters.
#[derive(Clone, Debug)]
pub struct TexramStub {
    drfs: [Option<Drf>; DRFS],
    banks: Vec<Vec<u8>>,
    pages: PageRegisters824,
    clut: Clut,
    slots: u64,
    accesses: u64,
    faults: u64,
    conflicts: u64,
    video_slots: u64,
}

impl Default for TexramStub {
    fn default() -> Self {
        TexramStub::new()
    }
}

/// The next level of a mipmap: each texel the rounded mean of its 2x2 (or of its pair when
/// one side is already 1), `(a + b + c + d + 2) >> 2`, as generator 816 rounds by default.
pub fn next_level(w: u32, h: u32, texels: &[u8]) -> Vec<u8> {
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let (sx, sy) = (if w > 1 { 2 } else { 1 }, if h > 1 { 2 } else { 1 });
    let mut out = Vec::with_capacity((nw * nh) as usize);
    for y in 0..nh {
        for x in 0..nw {
            let mut sum = 0u32;
            for dy in 0..sy {
                for dx in 0..sx {
                    sum += u32::from(texels[((y * sy + dy) * w + x * sx + dx) as usize]);
                }
            }
            let n = sx * sy;
            out.push(((sum + n / 2) / n) as u8);
        }
    }
    out
}

/// The row of a bank word.
fn row_of(word: u32) -> u64 {
    u64::from(word / ROW_WORDS)
}

impl TexramStub {
    /// Empty banks of the chip's size, every DRF unset, every row closed.
    pub fn new() -> TexramStub {
        TexramStub {
            drfs: [None; DRFS],
            banks: (0..BANKS)
                .map(|b| vec![0; bank_words(b) as usize])
                .collect(),
            pages: PageRegisters824::new(BANKS, 11),
            clut: Clut::identity(),
            slots: 0,
            accesses: 0,
            faults: 0,
            conflicts: 0,
            video_slots: 0,
        }
    }

    /// Writes level `k` of DRF `drf`'s map (row-major texels of the level's size).
    pub fn write_level(&mut self, drf: usize, k: u32, texels: &[u8]) -> Result<(), String> {
        let d = self.drf(drf)?;
        store_level(&mut self.banks, &d, k, texels)
    }

    /// Loads level 0 of DRF `drf`'s map and every level above it ([`next_level`]).
    pub fn load(&mut self, drf: usize, level0: &[u8]) -> Result<(), String> {
        let d = self.drf(drf)?;
        super::load_levels(&d, level0, |k, t| self.write_level(drf, k, t))
    }

    fn drf(&self, k: usize) -> Result<Drf, String> {
        self.drfs
            .get(k)
            .copied()
            .flatten()
            .ok_or_else(|| format!("drf {k}: not set"))
    }

    /// Loads the CLUT 814 (entries R, G, B, alpha from the top byte down).
    pub fn set_clut(&mut self, clut: Clut) {
        self.clut = clut;
    }

    /// Reads the eight texels of `fp` (texel (x, y) of level k stored where `place` says, in
    /// the layout of `d`): each bank one word per slot, so a bank asked for two words (the
    /// literal colour layout) takes a second round; each round one slot, two on a page fault.
    fn read(
        &mut self,
        d: &Drf,
        fp: &Footprint,
        colour: u8,
        place: impl Fn(u32, u32, u32) -> (u32, u32),
    ) -> ([u8; 8], Cost) {
        let mut texels = [colour; 8];
        let mut words: [Vec<u32>; BANKS] = Default::default();
        for (n, k) in [fp.fine, fp.coarse].into_iter().enumerate() {
            for (t, at) in fp.texels[n].iter().enumerate() {
                if let Some((x, y)) = at {
                    let (gx, gy) = place(k, *x, *y);
                    let (bank, w) = locate(d, k, gx, gy);
                    if !words[bank].contains(&w) {
                        words[bank].push(w);
                    }
                    texels[4 * n + t] = self.banks[bank][w as usize];
                }
            }
        }
        let rounds = words.iter().map(Vec::len).max().unwrap_or(0).max(1);
        if rounds > 1 {
            self.conflicts += 1;
        }
        let mut cost = Cost {
            slots: 0,
            faults: 0,
        };
        // The page registers' clock: the access's rounds within one cycle of theirs.
        self.pages.eval();
        for r in 0..rounds {
            let round = (0..BANKS).filter_map(|b| words[b].get(r).map(|&w| (b, row_of(w))));
            let c = self.pages.round(round);
            cost.slots += c.slots;
            cost.faults += c.faults;
        }
        self.pages.tick(false);
        (texels, cost)
    }

    /// The video port 808: the shift register 826 of `bank` writes its collected texels
    /// into the row holding `word` in one slot, two when the page register 824 holds another
    /// row (which the transfer then replaces: the rasterizer's next access there faults).
    /// The slots are stolen from the rasterizer and counted apart ([`TexramStub::video_slots`]).
    pub fn video_transfer(&mut self, bank: usize, word: u32) -> Cost {
        self.pages.eval();
        let cost = self.pages.round([(bank, row_of(word))]);
        self.pages.tick(false);
        self.video_slots += u64::from(cost.slots);
        self.slots += u64::from(cost.slots);
        cost
    }

    /// An access with the rasterizer's interpolated illumination `I_d` (R, G, B, alpha):
    /// the result's `rgba` after eq. 5 of the output stage 820 as the DRF's `modulate` says.
    pub fn access_lit(
        &mut self,
        req: TexramRequest,
        illumination: [u8; 4],
    ) -> Result<TexramReply, String> {
        let mut r = self.access(req)?;
        let m = self.drf(usize::from(req.drf))?.modulate;
        r.rgba = super::output_820::shade(m, illumination, r.rgba);
        Ok(r)
    }

    /// Slots the video port took.
    pub fn video_slots(&self) -> u64 {
        self.video_slots
    }

    /// Accesses that asked a bank for two words (none but in the literal colour layout).
    pub fn conflicts(&self) -> u64 {
        self.conflicts
    }

    /// Accesses so far, and the banks that missed their open row in them.
    pub fn counts(&self) -> (u64, u64) {
        (self.accesses, self.faults)
    }
}

impl TexramAccess for TexramStub {
    fn set_drf(&mut self, k: usize, drf: Drf) -> Result<(), String> {
        drf.validate()?;
        let slot = self
            .drfs
            .get_mut(k)
            .ok_or_else(|| format!("drf {k}: 0..{DRFS}"))?;
        *slot = Some(drf);
        Ok(())
    }

    fn access(&mut self, req: TexramRequest) -> Result<TexramReply, String> {
        req.validate()?;
        let d = self.drf(usize::from(req.drf))?;
        Ok(self.access_drf(d, req))
    }

    fn slots(&self) -> u64 {
        self.slots
    }

    fn load_map(&mut self, drf: &Drf, level0: &[u8]) -> Result<(), String> {
        let banks = &mut self.banks;
        super::load_levels(drf, level0, |k, t| store_level(banks, drf, k, t))
    }

    fn access_with(
        &mut self,
        drf: &Drf,
        u: i32,
        v: i32,
        lambda: i32,
    ) -> Result<TexramReply, String> {
        drf.validate()?;
        let req = TexramRequest {
            drf: super::WORKING,
            u,
            v,
            lambda,
        };
        TexramRequest { drf: 0, ..req }.validate()?;
        Ok(self.access_drf(*drf, req))
    }

    /// The page registers 824: the rows each access leaves open.
    fn visit(&self, v: &mut dyn crate::kernel::Visitor) {
        self.pages.visit(v);
    }
}

impl TexramStub {
    /// One access of `req` on the map of `d`.
    fn access_drf(&mut self, d: Drf, req: TexramRequest) -> TexramReply {
        let colour = match d.border {
            Border::Colour(c) => c,
            _ => 0,
        };
        // Planar and literal colour: each component is a map of half the DRF's size, stored
        // in a quadrant (planar) or interleaved in 2x2 cells (literal); one access each.
        let (plane, parts) = match d.config {
            Config::Luminance | Config::Index => (d, 1),
            Config::Planar | Config::Literal => (d.component_map(), 4),
        };
        let mut rgba = [0u8; 4];
        let (mut first, mut slots, mut faults) = (None, 0, 0);
        for c in 0..parts {
            let fp = Footprint::of(&plane, req.u, req.v, req.lambda);
            let place = |k: u32, x: u32, y: u32| d.config.place(&plane, c, k, x, y);
            let (texels, cost) = self.read(&d, &fp, colour, place);
            slots += cost.slots;
            faults += cost.faults;
            let value = trilinear(&texels, fp.a, fp.b, fp.f);
            match d.config {
                Config::Luminance => rgba = [value; 4],
                Config::Index => rgba = self.clut.filter(&texels, fp.a, fp.b, fp.f),
                Config::Planar | Config::Literal => rgba[c as usize] = value,
            }
            first.get_or_insert((fp, texels));
        }
        let (fp, texels) = first.expect("at least one part");
        self.slots += u64::from(slots);
        self.accesses += 1;
        self.faults += u64::from(faults);
        TexramReply {
            fine: fp.fine,
            coarse: fp.coarse,
            texels,
            a: fp.a,
            b: fp.b,
            f: fp.f,
            value: rgba[0],
            rgba,
            slots,
            faults,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chip(wl: u32, hl: u32, border: Border) -> (TexramStub, Vec<u8>) {
        let mut c = TexramStub::new();
        c.set_drf(0, Drf::new(wl, hl, border)).unwrap();
        let level0: Vec<u8> = (0..(1u32 << (wl + hl)))
            .map(|k| (k.wrapping_mul(2_654_435_761) >> 24) as u8)
            .collect();
        c.load(0, &level0).unwrap();
        (c, level0)
    }

    fn req(u: i32, v: i32, lambda: i32) -> TexramRequest {
        TexramRequest {
            drf: 0,
            u,
            v,
            lambda,
        }
    }

    #[test]
    fn level_zero_texels_come_back_where_they_were_written() {
        let (mut c, level0) = chip(5, 3, Border::Wrap);
        for y in 0..8 {
            for x in 0..32 {
                let r = c
                    .access(req((2 * x + 1) << 7, (2 * y + 1) << 7, 0))
                    .unwrap();
                assert_eq!(r.texels[0], level0[(y * 32 + x) as usize]);
                assert_eq!(r.value, r.texels[0], "at a texel centre with lambda 0");
            }
        }
    }

    #[test]
    fn integer_lambda_is_the_bilinear_of_that_level() {
        let (mut c, _) = chip(4, 4, Border::Clamp);
        for lambda in 0..=4 {
            let r = c.access(req(1000, 777, lambda << 8)).unwrap();
            assert_eq!((r.fine, r.f), (lambda as u32, 0));
            let mut fine = r.texels;
            fine[4..].copy_from_slice(&[0; 4]);
            assert_eq!(r.value, trilinear(&fine, r.a, r.b, 0));
        }
    }

    #[test]
    fn border_colour_texels_read_no_bank() {
        let (mut c, _) = chip(3, 3, Border::Colour(200));
        let r = c.access(req(-5000, -5000, 0)).unwrap();
        assert_eq!(r.texels, [200; 8]);
        assert_eq!(r.value, 200);
        assert_eq!((r.slots, r.faults), (1, 0), "nothing read, nothing missed");
    }

    #[test]
    fn slots_count_page_faults_from_the_open_rows() {
        let (mut c, _) = chip(10, 10, Border::Wrap);
        let first = c.access(req(100, 100, 0)).unwrap();
        assert_eq!(first.slots, 2, "every row starts closed");
        assert_eq!(c.access(req(356, 100, 0)).unwrap().slots, 1, "same rows");
        // 512 words per row hold one row of 2x2 groups of level 0: 32 texel rows further
        // down is another row in every bank.
        assert_eq!(c.access(req(100, 100 + (32 << 8), 0)).unwrap().slots, 2);
        assert_eq!(c.slots(), 5);
        assert_eq!(c.counts().0, 3);
    }

    #[test]
    fn bad_requests_and_unset_drfs_are_refused() {
        let (mut c, _) = chip(2, 2, Border::Wrap);
        assert!(c.access(req(1 << 20, 0, 0)).unwrap_err().contains("u raw"));
        assert!(c.access(req(0, 0, 11 << 8)).unwrap_err().contains("lambda"));
        let e = c
            .access(TexramRequest {
                drf: 3,
                ..req(0, 0, 0)
            })
            .unwrap_err();
        assert_eq!(e, "drf 3: not set");
        assert!(c.set_drf(7, Drf::new(1, 1, Border::Wrap)).is_err());
        assert!(c.set_drf(0, Drf::new(11, 1, Border::Wrap)).is_err());
        assert!(c
            .write_level(0, 3, &[0])
            .unwrap_err()
            .contains("levels 0..=2"));
    }

    #[test]
    fn the_counters_add_up_the_replies() {
        let (mut c, _) = chip(10, 10, Border::Wrap);
        let (mut slots, mut faults) = (0u64, 0u64);
        for k in 0..50 {
            let r = c
                .access(req(k * 997 % 200_000, k * 7919 % 200_000, 0))
                .unwrap();
            slots += u64::from(r.slots);
            faults += u64::from(r.faults);
        }
        assert!(faults > 0);
        assert_eq!((c.slots(), c.counts()), (slots, (50, faults)));
    }

    #[test]
    fn next_level_rounds_the_mean_of_each_block() {
        assert_eq!(next_level(2, 2, &[1, 2, 3, 5]), vec![3]);
        assert_eq!(next_level(4, 1, &[1, 2, 3, 4]), vec![2, 4]);
        assert_eq!(next_level(1, 2, &[0, 1]), vec![1]);
        assert_eq!(next_level(1, 1, &[9]), vec![9]);
    }
}
