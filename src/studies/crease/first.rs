//! Which instability comes first under growing compression: the wrinkle of the linear theory
//! or the crease of the energy criterion.

use serde::{Deserialize, Serialize};

/// The first instability under growing compression.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum First {
    /// `d_wrinkle <= d_crease` (or no crease pays off in the scan).
    Wrinkle,
    /// `d_crease < d_wrinkle` (or no wrinkling before the loss of ellipticity).
    Crease,
    /// Neither within the ranges searched.
    None,
    /// No crease paid off, but its search ended (a fold that snapped) below `d_wrinkle`.
    Undecided,
    /// `|d_crease - d_wrinkle|` is within the crease onset's uncertainty (`d_crease_error`):
    /// the meshes cannot tell which comes first.
    TooCloseToCall,
}

impl First {
    /// Which comes first, from the two onsets (`None`: none found) and the crease's uncertainty:
    /// too close to call where they differ by no more than it; without a crease threshold, the
    /// wrinkle if it comes before `cleared`, the lowest `d` up to which no fold paid off, else
    /// undecided.
    pub fn decide((d_wrinkle, d_crease): (Option<f64>, Option<f64>), uncertainty: f64, cleared: f64) -> First {
        match (d_wrinkle, d_crease) {
            (Some(w), Some(c)) if (c - w).abs() <= uncertainty => First::TooCloseToCall,
            (Some(w), Some(c)) if c < w => First::Crease,
            (Some(_), Some(_)) => First::Wrinkle,
            (Some(w), None) if w <= cleared => First::Wrinkle,
            (Some(_), None) => First::Undecided,
            (None, Some(_)) => First::Crease,
            (None, None) => First::None,
        }
    }
}
