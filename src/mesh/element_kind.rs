//! Which finite element the mesh's cells carry (the finite-element module registers what each
//! computes).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The finite element on the mesh (both interpolate displacements with Q2).
///
/// The mixed element is the more accurate at every `K / mu`, Table 1's 3 included (the
/// fine-mesh bifurcation at `beta = pi/4` within 1.2e-5 of the linear theory against 2.5e-5,
/// the Fig. 7 run's first contact 0.239 against 0.256, where refined meshes give 0.233-0.241),
/// at about 1.05 times the cost of a Newton iteration, so it is the default. The displacement
/// element, the paper's, stays available for comparison with it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum ElementKind {
    /// Q2 displacements, full 3x3 integration; locks as `K / mu` grows.
    #[value(help = "Q2 displacements, full 3x3 integration; locks as K/mu grows (usable up to K/mu ~ 100)")]
    Displacement,
    /// Q2 displacements with a discontinuous linear pressure condensed per element; free of
    /// locking up to `K / mu = 10^6`.
    #[default]
    #[value(
        help = "Q2 displacements with a discontinuous linear pressure condensed per element (Q2/P1disc): no locking up to K/mu = 10^6, same unknowns, about 5 % more time per iteration"
    )]
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
