//! Helpers shared by the integration tests (each test crate uses some of them).
#![allow(dead_code)]

use fiberfold::material::Bilayer;
use fiberfold::Parameters;
use std::path::PathBuf;
use std::process::{Command, Output};

/// Layer and substrate the same neo-Hookean solid (`mu = 1`, `K = 3`, no fibres).
pub fn homogeneous_material() -> Bilayer {
    Bilayer::new(&Parameters {
        mu_l: 1.0,
        K_l: 3.0,
        mu_s: 1.0,
        K_s: 3.0,
        phi_m: 1.0,
        phi_f: 0.0,
        ..Parameters::default()
    })
}

/// An empty scratch folder name under the temporary directory, unique to this test process.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fiberfold-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Runs the `fiberfold` binary with `args`.
pub fn fiberfold<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// A small deterministic generator (xorshift), so every random test can be replayed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}
