//! What a finite-element run on a mesh needs in memory, estimated before anything is allocated
//! (so that a mesh far too large is refused at once, not after the machine starts swapping).
//!
//! Counts: the unknowns exactly; the stored entries of the tangent's lower triangle as 16.5 per
//! unknown (16.1 and 16.3 measured on the coarse and fine meshes); the entries of the `L D L^T`
//! factor as `5.5 n log2 n` (AMD on these structured Q2 meshes: 4.9 and 5.3 measured). Bytes:
//! three factor-sized arrays (Newton's factor, the one of an inertia counted in the background
//! ([`super::inertia`]), and the analysis with its permuted copy), the tangent with its
//! pattern and gather lists, the element matrices (171 stored values per element), a few dozen
//! vectors of unknowns and 20 MB of program; within 15 % of the peak measured on both meshes.

use crate::error::{Error, Result};
use crate::mesh::MeshSpec;
use serde::Serialize;

/// The estimate for one mesh.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MemoryEstimate {
    pub unknowns: usize,
    pub tangent_entries: f64,
    pub factor_entries: f64,
    pub bytes: f64,
}

impl MemoryEstimate {
    /// The estimate for `spec` (no allocation proportional to the mesh).
    pub fn of(spec: &MeshSpec) -> Self {
        let n = spec.num_dofs() as f64;
        let elements = (spec.nx * spec.ny()) as f64;
        let tangent_entries = 16.5 * n;
        let factor_entries = 5.5 * n * n.max(2.0).log2();
        let bytes = 24.0 * factor_entries + 40.0 * tangent_entries + 12.0 * 171.0 * elements + 400.0 * n + 20e6;
        MemoryEstimate {
            unknowns: spec.num_dofs(),
            tangent_entries,
            factor_entries,
            bytes,
        }
    }

    /// The estimate for `elements` 27-node hexahedra from their tangent's pattern and its
    /// symbolic factor (the exact counts, known before any factor is allocated; 0 entries
    /// before they are): a three-dimensional patch, whose factor's growth no fit of the plane
    /// meshes' describes. Bytes: the factor's values, its permuted copy and workspace (8 bytes
    /// each, plus a tenth), the tangent with its pattern and gather lists, each element's
    /// geometry (`dN/dX`, weights and points at 27 points: 2,295 values), a few dozen vectors
    /// of unknowns and 20 MB of program.
    pub fn of_factor(unknowns: usize, elements: usize, tangent_entries: usize, factor_entries: usize) -> Self {
        let (tangent, factor) = (tangent_entries as f64, factor_entries as f64);
        MemoryEstimate {
            unknowns,
            tangent_entries: tangent,
            factor_entries: factor,
            bytes: 8.8 * factor + 40.0 * tangent + 8.0 * 2295.0 * elements as f64 + 400.0 * unknowns as f64 + 20e6,
        }
    }

    /// Refuses (as bad input, naming both numbers) an estimate above `available` bytes.
    pub fn check(&self, available: Option<f64>) -> Result<()> {
        self.check_named(available, "mesh", "")
    }

    /// [`MemoryEstimate::check`] of what the input names `what` (`mesh`, `patch`), with a hint
    /// of what to lower.
    pub fn check_named(&self, available: Option<f64>, what: &str, hint: &str) -> Result<()> {
        match available {
            Some(available) if self.bytes > available => Err(Error::invalid(
                what,
                format!("{} unknowns (estimated {:.0} MB)", self.unknowns, self.bytes / 1e6),
                &format!(
                    "a {what} whose estimate fits in the {:.0} MB of memory available ({hint}--force runs it anyway)",
                    available / 1e6
                ),
            )),
            _ => Ok(()),
        }
    }
}

/// The memory the system can still give (`MemAvailable` of `/proc/meminfo`), if known.
pub fn available_bytes() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Hands the heap's free pages back to the system (glibc keeps blocks freed below its mmap
/// threshold in the heap: tangents, gather buffers, an old pattern): called after a pattern is
/// rebuilt and between a path and its post-processing, so that peaks do not add up.
pub fn return_free_pages() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only releases memory that no allocation owns.
    unsafe {
        libc::malloc_trim(0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_grow_with_the_mesh_and_refuse_what_does_not_fit() {
        let (coarse, fine) = (
            MemoryEstimate::of(&MeshSpec::coarse()),
            MemoryEstimate::of(&MeshSpec::fine()),
        );
        assert_eq!(coarse.unknowns, 22_110);
        // Measured peaks of whole runs: 83 MB (coarse) and 281 MB (fine).
        assert!((70e6..110e6).contains(&coarse.bytes), "{}", coarse.bytes);
        assert!((240e6..340e6).contains(&fine.bytes), "{}", fine.bytes);
        let huge = MemoryEstimate::of(&MeshSpec::new(100_000, 100_000, 100_000, 0.5, 50.0, 50.0));
        let err = huge.check(Some(24e9)).unwrap_err().to_string();
        assert!(
            err.contains("`mesh`") && err.contains("MB") && err.contains("24000 MB"),
            "{err}"
        );
        assert!(fine.check(Some(24e9)).is_ok());
        assert!(huge.check(None).is_ok(), "unknown availability is not a refusal");
    }
}
