//! Which finite element a mesh carries, and when the displacement element locks.

use crate::error::{Error, Result};
use crate::parameters::Parameters;
use serde::{Deserialize, Serialize};

/// `K / mu` above which the displacement element locks noticeably (README: its coarse-mesh
/// bifurcation is 1.0e-3 off the linear theory at 100, 3.7e-3 at 1000, and fails from 1e5).
pub const LOCKING_RATIO: f64 = 100.0;

/// The finite element on the mesh (both interpolate displacements with Q2).
///
/// The mixed element is the more accurate at every `K / mu`, Table 1's 3 included (the
/// fine-mesh bifurcation at `beta = pi/4` within 1.2e-5 of the linear theory against 2.5e-5,
/// the Fig. 7 run's first contact 0.239 against 0.256, where refined meshes give 0.239-0.241),
/// at about 1.05 times the cost of a Newton iteration, so it is the default. The displacement
/// element, the paper's, stays available for comparison with it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ElementKind {
    /// Q2 displacements, full 3x3 integration ([`crate::fem::element`]); locks as `K / mu` grows.
    Displacement,
    /// Q2 displacements with a discontinuous linear pressure condensed per element
    /// ([`crate::fem::mixed`]); free of locking up to `K / mu = 10^6`.
    #[default]
    Mixed,
}

impl ElementKind {
    /// The element by its name, `displacement` or `mixed`.
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "displacement" => Ok(ElementKind::Displacement),
            "mixed" => Ok(ElementKind::Mixed),
            other => Err(Error::invalid("element", other, "displacement or mixed")),
        }
    }

    /// Whether this element can model the tissue: exactly incompressible tissue needs the
    /// mixed element (the displacement element cannot keep `J = 1`).
    pub fn check_for(self, incompressible: bool) -> Result<()> {
        if incompressible && self != ElementKind::Mixed {
            return Err(Error::invalid(
                "element",
                self.name(),
                "mixed when incompressible = true (the displacement element cannot keep J = 1)",
            ));
        }
        Ok(())
    }

    /// A one-line note when this element locks for `params`: the displacement element with a
    /// layer's `K / mu` above [`LOCKING_RATIO`]; it points to the mixed element.
    pub fn locking_note(self, params: &Parameters) -> Option<String> {
        let ratio = (params.K_l / params.mu_l).max(params.K_s / params.mu_s);
        (self == ElementKind::Displacement && !params.incompressible && ratio > LOCKING_RATIO).then(|| {
            format!(
                "note: K / mu = {ratio:.1e} with the displacement element, which locks above K / mu ~ {LOCKING_RATIO} \
                 (too stiff in bending; from about 1e5 its runs fail); --element mixed does not"
            )
        })
    }

    /// The element of results written before the mixed element existed (a missing field).
    pub fn of_older_files() -> Self {
        ElementKind::Displacement
    }

    /// The name [`ElementKind::from_name`] reads.
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::Displacement => "displacement",
            ElementKind::Mixed => "mixed",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_displacement_element_notes_its_locking_above_k_over_mu_100() {
        let mut params = Parameters::default();
        assert_eq!(ElementKind::Displacement.locking_note(&params), None); // K / mu = 3
        params.K_s = 1e6;
        let note = ElementKind::Displacement.locking_note(&params).unwrap();
        assert!(note.contains("1.0e6") && note.contains("--element mixed"), "{note}");
        assert_eq!(ElementKind::Mixed.locking_note(&params), None);
        params.K_s = 3.0;
        params.K_l = 101.0 * params.mu_l;
        assert!(ElementKind::Displacement.locking_note(&params).is_some());
        params.incompressible = true; // refused elsewhere, with its own message
        assert_eq!(ElementKind::Displacement.locking_note(&params), None);
    }
}
