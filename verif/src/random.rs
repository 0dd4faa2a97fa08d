//! Seeded constrained-random stimulus from proptest strategies.

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::fmt;

/// The environment variable that replays a run: `TEXRTL_SEED=0x1234abcd cargo test ...`.
pub const SEED_ENV: &str = "TEXRTL_SEED";

/// A 64-bit stimulus seed, printed in hex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Seed(pub u64);

impl fmt::Display for Seed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#018x}", self.0)
    }
}

impl Seed {
    /// Parses `0x`-prefixed hex or decimal.
    pub fn parse(s: &str) -> Result<Seed, String> {
        let t = s.trim();
        let r = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
            Some(h) => u64::from_str_radix(h, 16),
            None => t.parse(),
        };
        r.map(Seed)
            .map_err(|_| format!("'{s}' is not a seed (hex 0x... or decimal)"))
    }

    /// `TEXRTL_SEED` if set, else `default`. A malformed variable is an error, not ignored.
    pub fn from_env_or(default: Seed) -> Result<Seed, String> {
        match std::env::var(SEED_ENV) {
            Ok(v) => Seed::parse(&v).map_err(|e| format!("{SEED_ENV}: {e}")),
            Err(_) => Ok(default),
        }
    }

    /// `TEXRTL_SEED` if set, else a fresh seed from the clock and process id.
    pub fn from_env_or_fresh() -> Result<Seed, String> {
        let t = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos() as u64)
            .unwrap_or(0);
        Seed::from_env_or(Seed::fresh(t, std::process::id()))
    }

    /// The seed of a process `pid` started at `nanos`: test processes started together (one
    /// a test under nextest) differ in their id, runs of one binary in their time.
    fn fresh(nanos: u64, pid: u32) -> Seed {
        Seed(splitmix(nanos ^ u64::from(pid)))
    }

    /// A seed derived from this one for an independent stream `k` (shards, sub-benches).
    pub fn derive(self, k: u64) -> Seed {
        Seed(splitmix(
            self.0 ^ splitmix(k.wrapping_add(0x9e37_79b9_7f4a_7c15)),
        ))
    }

    /// The proptest RNG for this seed (ChaCha, identical on every platform and version).
    pub fn rng(self) -> TestRng {
        let mut bytes = [0u8; 32];
        let mut x = self.0;
        for chunk in bytes.chunks_mut(8) {
            x = splitmix(x);
            chunk.copy_from_slice(&x.to_le_bytes());
        }
        TestRng::from_seed(RngAlgorithm::ChaCha, &bytes)
    }
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A proptest runner seeded from `TEXRTL_SEED` or a fresh seed, which it prints (to stderr,
/// where `cargo test` shows it for a failing test) with the line that replays it.
pub fn seeded_runner(test: &str, cases: u32) -> TestRunner {
    let seed = Seed::from_env_or_fresh().unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{test}: stimulus seed {seed}; replay with {SEED_ENV}={seed}");
    let cfg = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(cfg, seed.rng())
}

/// `s` cut to at most 40 characters for a message.
fn formats_short(s: &str) -> String {
    if s.chars().count() <= 40 {
        s.to_string()
    } else {
        format!("{}...", s.chars().take(37).collect::<String>())
    }
}

/// One of `count` shards of a regression (`index` from 1): configurations are dealt out
/// round-robin, so the shards together run exactly what one unsharded run does, each
/// configuration with the same seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    /// This shard, from 1.
    pub index: u32,
    /// How many shards there are.
    pub count: u32,
}

impl Default for Shard {
    fn default() -> Self {
        Shard { index: 1, count: 1 }
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// Shards of a run at most (each is a machine or a CI job).
    pub const MAX_COUNT: u32 = 4096;

    /// Parses `I/N` with `1 <= I <= N <= 4096`.
    pub fn parse(s: &str) -> Result<Shard, String> {
        let s = s.trim();
        let bad = || {
            format!(
                "'{}' is not a shard I/N with 1 <= I <= N <= {}",
                formats_short(s),
                Shard::MAX_COUNT
            )
        };
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (u32, u32) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index == 0 || index > count || count > Shard::MAX_COUNT {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// Whether configuration number `c` (from 0) belongs to this shard.
    pub fn owns(&self, c: u64) -> bool {
        c % u64::from(self.count) == u64::from(self.index - 1)
    }

    /// The whole run (one shard of one).
    pub fn is_all(&self) -> bool {
        self.count == 1
    }
}

/// A [`Stimulus`] seeded from `TEXRTL_SEED` or a fresh seed, printed like [`seeded_runner`]'s.
pub fn seeded_stimulus(test: &str) -> Stimulus {
    let seed = Seed::from_env_or_fresh().unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{test}: stimulus seed {seed}; replay with {SEED_ENV}={seed}");
    Stimulus::new(seed)
}

/// Draws values from proptest strategies with a seeded RNG: the constrained-random source of
/// a testbench. The same seed gives the same values on every machine.
pub struct Stimulus {
    seed: Seed,
    runner: TestRunner,
}

impl Stimulus {
    /// A stimulus source replaying `seed`.
    pub fn new(seed: Seed) -> Stimulus {
        // No failure persistence: a stimulus source records nothing, and a union strategy
        // (`prop_oneof!`) copies the runner's configuration for each option at every draw,
        // the default's file persistence with it (9 % of replicate 152's stimulus). The
        // values drawn do not depend on it.
        let cfg = Config {
            failure_persistence: None,
            ..Config::default()
        };
        Stimulus {
            seed,
            runner: TestRunner::new_with_rng(cfg, seed.rng()),
        }
    }

    /// The seed it replays.
    pub fn seed(&self) -> Seed {
        self.seed
    }

    /// One value from `strategy`.
    pub fn draw<S: Strategy>(&mut self, strategy: &S) -> S::Value {
        strategy
            .new_tree(&mut self.runner)
            .unwrap_or_else(|e| panic!("strategy rejected every value: {e}"))
            .current()
    }

    /// `n` values from `strategy`.
    pub fn draw_n<S: Strategy>(&mut self, strategy: &S, n: usize) -> Vec<S::Value> {
        (0..n).map(|_| self.draw(strategy)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_stimulus() {
        let s = 0u32..1000;
        let a = Stimulus::new(Seed(42)).draw_n(&s, 50);
        let b = Stimulus::new(Seed(42)).draw_n(&s, 50);
        let c = Stimulus::new(Seed(43)).draw_n(&s, 50);
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!(a.iter().all(|v| *v < 1000));
    }

    #[test]
    fn shards_partition() {
        let shards: Vec<Shard> = (1..=3)
            .map(|i| Shard::parse(&format!("{i}/3")).unwrap())
            .collect();
        for c in 0..30 {
            assert_eq!(shards.iter().filter(|s| s.owns(c)).count(), 1);
        }
        for bad in ["0/2", "3/2", "1/0", "1", "a/b", "1/4097"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let most = Shard::parse("4096/4096").unwrap();
        assert!(most.owns(4095) && !most.is_all());
        assert!(Shard::parse("1/1").unwrap().is_all() && Shard::default().is_all());
        assert_eq!(Shard::parse("2/5").unwrap().to_string(), "2/5");
    }

    #[test]
    fn seeds_parse_and_print() {
        assert_eq!(Seed::parse("0x10").unwrap(), Seed(16));
        assert_eq!(Seed::parse("16").unwrap(), Seed(16));
        assert!(Seed::parse("zz").is_err());
        assert_eq!(
            Seed::parse(&Seed(0xdead).to_string()).unwrap(),
            Seed(0xdead)
        );
        assert_ne!(Seed(1).derive(0), Seed(1).derive(1));
    }

    /// The mixing function is SplitMix64 (Vigna), output for output: the published first four
    /// outputs from state 0, each the mix of the state advanced by the golden gamma. A change
    /// here would change every seed's stimulus, and no printed seed would replay.
    #[test]
    fn the_mix_is_splitmix64() {
        let gamma = 0x9e37_79b9_7f4a_7c15u64;
        let published = [
            0xe220_a839_7b1d_cdaf,
            0x6e78_9e6a_a1b9_65f4,
            0x06c4_5d18_8009_454f,
            0xf88b_b8a8_724c_81ec,
        ];
        for (k, want) in published.into_iter().enumerate() {
            assert_eq!(splitmix(gamma.wrapping_mul(k as u64)), want, "output {k}");
        }
    }

    /// Distinct seeds give distinct derived streams, and distinct stream numbers too; so do
    /// distinct processes and instants for fresh seeds.
    #[test]
    fn seeds_apart_stay_apart() {
        let distinct = |v: Vec<Seed>| {
            let n = v.len();
            n == v
                .into_iter()
                .collect::<std::collections::HashSet<_>>()
                .len()
        };
        for k in [0, 1, 5, u64::MAX] {
            assert!(
                distinct((0..256).map(|s| Seed(s).derive(k)).collect()),
                "k {k}"
            );
            assert!(
                distinct((0..256).map(|j| Seed(k).derive(j)).collect()),
                "seed {k}"
            );
        }
        for t in [0, 0xff, u64::MAX] {
            assert!(
                distinct((0..256).map(|pid| Seed::fresh(t, pid)).collect()),
                "t {t}"
            );
            assert!(
                distinct((0..256).map(|n| Seed::fresh(t ^ n, 77)).collect()),
                "t {t}"
            );
        }
    }

    /// The runner runs the cases asked for and writes no regression file on a failure.
    #[test]
    fn a_seeded_runner_runs_the_cases_asked_and_persists_nothing() {
        let mut r = seeded_runner("a_seeded_runner", 7);
        assert_eq!(r.config().cases, 7);
        assert!(r.config().failure_persistence.is_none());
        let n = std::cell::Cell::new(0);
        r.run(&(0u8..4), |_| {
            n.set(n.get() + 1);
            Ok(())
        })
        .unwrap();
        assert_eq!(n.get(), 7);
    }

    #[test]
    fn a_bad_shard_is_quoted_whole_or_cut_at_40_characters() {
        let e = Shard::parse("a/b").unwrap_err();
        assert!(e.starts_with("'a/b' is not a shard I/N"), "{e}");
        let long = format!("1/{}", "9".repeat(38));
        let e = Shard::parse(&long).unwrap_err();
        assert!(e.starts_with(&format!("'{long}' is not")), "40 kept: {e}");
        let longer = format!("{long}9");
        let e = Shard::parse(&longer).unwrap_err();
        assert!(
            e.starts_with(&format!("'{}...' is not", &longer[..37])),
            "{e}"
        );
    }
}
