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

/// A 2 x 1 map on small meshes (a few seconds a point): an isotropic soft and stiff layer.
pub fn tiny_map(out: &std::path::Path, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "map",
        "--set",
        "phi_m=1",
        "--set",
        "phi_f=0",
        "--x",
        "mu_l",
        "--x-from",
        "1.5",
        "--x-to",
        "10",
        "--x-points",
        "2",
        "--x-log",
        "--y",
        "beta",
        "--y-from",
        "0",
        "--y-to",
        "0",
        "--y-points",
        "1",
        "--waves",
        "2",
        "--elements-per-wave",
        "12",
        "--substrate-elements",
        "10",
        "--post-buckling-range",
        "0.04",
        "--fold",
        "1",
        "--crease-nx",
        "24",
        "--crease-layer-elements",
        "2",
        "--crease-substrate-elements",
        "10",
        "--out",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push(out.display().to_string());
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

/// The points of `map.json` without their wall times.
pub fn map_points(dir: &std::path::Path) -> Vec<serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("map.json")).expect("map.json");
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut points = json["points"].as_array().unwrap().clone();
    for p in &mut points {
        p.as_object_mut().unwrap().remove("seconds");
    }
    points
}
