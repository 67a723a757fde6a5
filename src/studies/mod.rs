//! Studies: what each command computes and the files it writes (CSV, JSON, figures). The
//! command line and `reproduce` call these; they take a progress callback and an output folder.

pub mod bench_crease;
pub mod bench_fe;
pub mod bench_patch;
pub mod bench_stability;
pub mod bifurcation;
pub mod crease;
pub mod crease_threshold;
pub mod grid;
pub mod grid_chart;
pub mod homogeneous;
pub mod keywords;
pub mod map;
pub mod orientation;
pub mod pattern;
pub mod reproduce;
pub mod simulate;
pub mod stability;
pub mod stability_figures;

/// Called once per finished unit of work (drives a progress bar in the CLI).
pub type Tick<'a> = &'a (dyn Fn() + Sync);

/// Evenly spaced values from `from` to `to` inclusive.
pub fn linspace(from: f64, to: f64, points: usize) -> Vec<f64> {
    if points == 1 {
        return vec![from];
    }
    (0..points)
        .map(|i| from + (to - from) * i as f64 / (points - 1) as f64)
        .collect()
}

/// Validates a number of sample points.
pub fn validate_points(name: &str, points: usize, min: usize) -> crate::Result<()> {
    const MAX: usize = 1_000_000;
    if (min..=MAX).contains(&points) {
        Ok(())
    } else {
        Err(crate::Error::invalid(name, points, &format!("[{min}, {MAX}]")))
    }
}
