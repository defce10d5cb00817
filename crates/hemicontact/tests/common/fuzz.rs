//! The harness shared by the fuzz tests (`fuzz_scenario`, `fuzz_gmsh`): panics caught with
//! their location and message (without the default hook's noise), the configuration of a
//! deterministic proptest campaign read from the environment, and small helpers of the
//! campaign statistics.
//!
//! Environment of a campaign: `HEMICONTACT_FUZZ_CASES=<u32>` (number of cases),
//! `HEMICONTACT_FUZZ_COLLECT=1` (collect every failure, one per kind, instead of stopping at
//! the first), `HEMICONTACT_FUZZ_SEED=<u64>` (explore other inputs).

use proptest::test_runner::{Config, FileFailurePersistence, RngAlgorithm, RngSeed, TestRunner};
use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::hash::{Hash, Hasher};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;
use std::time::Duration;

thread_local! {
    /// Whether panics on this thread are expected (caught by the fuzzer): then the panic
    /// hook records them silently.
    static FUZZING: Cell<bool> = const { Cell::new(false) };
    /// The location and message of the last panic on this thread.
    static LAST_PANIC: RefCell<Option<(String, String)>> = const { RefCell::new(None) };
}

/// Installs (once per process) a panic hook that records the location and message of a
/// panic raised inside [`catch_panic`] instead of printing it; other panics go to the
/// previous hook.
pub fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if FUZZING.with(Cell::get) {
                let location = info
                    .location()
                    .map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column()))
                    .unwrap_or_default();
                let payload = info.payload();
                let message = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                LAST_PANIC.with(|p| *p.borrow_mut() = Some((location, message)));
            } else {
                previous(info);
            }
        }));
    });
}

/// A panic caught by [`catch_panic`]: where it was raised (`file:line:column`) and its
/// message (empty when the hook of [`install_panic_hook`] is not installed).
#[derive(Clone, Debug, Default)]
pub struct Panic {
    /// `file:line:column` of the panic.
    pub location: String,
    /// The panic message.
    pub message: String,
}

/// Runs `f`, catching a panic and returning its location and message.
pub fn catch_panic<T>(f: impl FnOnce() -> T) -> Result<T, Panic> {
    FUZZING.with(|c| c.set(true));
    LAST_PANIC.with(|p| *p.borrow_mut() = None);
    let r = catch_unwind(AssertUnwindSafe(f));
    FUZZING.with(|c| c.set(false));
    r.map_err(|_| {
        let (location, message) = LAST_PANIC
            .with(|p| p.borrow_mut().take())
            .unwrap_or_default();
        Panic { location, message }
    })
}

/// The characters `chars` with every run of digits replaced by one `#`, so that messages
/// differing only in numbers group together.
pub fn digits_as_hash(chars: impl Iterator<Item = char>) -> String {
    let mut out = String::new();
    let mut in_digits = false;
    for c in chars {
        if c.is_ascii_digit() {
            if !in_digits {
                out.push('#');
            }
            in_digits = true;
        } else {
            out.push(c);
            in_digits = false;
        }
    }
    out
}

/// The environment variable `name` as a `u32`, or `default` when unset or not a number.
pub fn env_u32(name: &str, default: u32) -> u32 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Peak resident memory of this process in KiB (`VmHWM` of `/proc/self/status`; 0 where
/// unavailable).
pub fn peak_rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(0)
}

/// What a campaign runs: number of cases, collect mode and seed, from the environment.
pub struct Campaign {
    /// Number of generated cases (`HEMICONTACT_FUZZ_CASES`).
    pub cases: u32,
    /// Collect every failure instead of stopping at the first (`HEMICONTACT_FUZZ_COLLECT=1`).
    pub collect: bool,
    /// Seed of the generator (`HEMICONTACT_FUZZ_SEED`).
    pub seed: u64,
}

impl Campaign {
    /// The campaign of the environment, with these defaults for the number of cases and
    /// the seed (fixed: CI runs the same inputs every time).
    pub fn from_env(default_cases: u32, default_seed: u64) -> Self {
        Campaign {
            cases: env_u32("HEMICONTACT_FUZZ_CASES", default_cases),
            collect: std::env::var("HEMICONTACT_FUZZ_COLLECT").is_ok_and(|v| v == "1"),
            seed: std::env::var("HEMICONTACT_FUZZ_SEED")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(default_seed),
        }
    }

    /// A deterministic proptest runner (ChaCha from the fixed seed, no forking, no
    /// timeout) recording the seeds of failing cases in `regressions` (relative to the
    /// crate root; replayed first). `source_file` is the calling test's `file!()`.
    pub fn runner(&self, regressions: &'static str, source_file: &'static str) -> TestRunner {
        TestRunner::new(Config {
            cases: self.cases,
            failure_persistence: Some(Box::new(FileFailurePersistence::Direct(regressions))),
            source_file: Some(source_file),
            rng_algorithm: RngAlgorithm::ChaCha,
            rng_seed: RngSeed::Fixed(self.seed),
            max_shrink_iters: 4096,
            max_shrink_time: 60_000,
            max_local_rejects: 0,
            max_global_rejects: 0,
            verbose: 0,
            fork: false,
            timeout: 0,
            ..Config::default()
        })
    }
}

/// Counts of a campaign common to every fuzz test: distinct inputs (by hash), calls, and
/// the slowest case with a description `S` of its input.
#[derive(Default)]
pub struct Tally<S> {
    /// Hashes of the inputs seen.
    pub distinct: HashSet<u64>,
    /// Number of checked inputs.
    pub calls: u64,
    /// The longest check and its input.
    pub slowest: (Duration, S),
}

impl<S> Tally<S> {
    /// Records one checked input that took `elapsed`; `describe` is called only if it is
    /// the slowest so far.
    pub fn record(&mut self, input: &impl Hash, elapsed: Duration, describe: impl FnOnce() -> S) {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        input.hash(&mut h);
        self.distinct.insert(h.finish());
        self.calls += 1;
        if elapsed > self.slowest.0 {
            self.slowest = (elapsed, describe());
        }
    }
}
