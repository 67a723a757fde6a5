//! What the search finds for one fold length on one mesh.

use super::Criterion;
use crate::protocol::crease_seed::{CreaseEnergy, ReleasedCrease};
use serde::Serialize;

/// `d(a)` for one fold length on one mesh, with every energy evaluated on the way.
#[derive(Clone, Debug, Serialize)]
pub struct FoldThreshold {
    pub fold_length: f64,
    /// The threshold by the study's criterion (None: not within the scan).
    pub d_threshold: Option<f64>,
    /// Where the held fold's `U_crease - U_flat` changes sign (the held criterion's threshold).
    pub d_held: Option<f64>,
    /// The held fold at every `d` evaluated.
    pub evaluations: Vec<CreaseEnergy>,
    /// Why the scan ended early, if it did (e.g. the fold snapped).
    pub stopped: Option<String>,
    /// The fold at the threshold let go to contact with the plane: whether it stays closed,
    /// over what length, and with the plane pushing everywhere it touches.
    pub released: Option<ReleasedCrease>,
    /// Why the release at the threshold failed, if it did.
    pub release_error: Option<String>,
    /// Every release evaluated, by increasing `d` (the one at the threshold under the held
    /// criterion, the whole search under the released one).
    pub released_evaluations: Vec<ReleasedCrease>,
    /// Under the released criterion: whether just below the threshold the fold reopens to the
    /// flat state, so that the equilibrium crease appears already paying off (rather than
    /// passing through `U = U_flat`).
    pub appears_paying: bool,
    /// Wall time of this fold's search on this mesh (s).
    pub seconds: f64,
}

impl FoldThreshold {
    /// The entry of a fold that was not computed on a mesh of the sequence.
    pub fn not_computed(fold_length: f64) -> Self {
        FoldThreshold {
            fold_length,
            d_threshold: None,
            d_held: None,
            evaluations: Vec::new(),
            stopped: Some("not computed on this mesh".into()),
            released: None,
            release_error: None,
            released_evaluations: Vec::new(),
            appears_paying: false,
            seconds: 0.0,
        }
    }

    /// The deformed depth of the crease at the threshold: the held fold's, or the released
    /// crease's under the released criterion.
    pub fn depth_at_threshold(&self, criterion: Criterion) -> Option<f64> {
        match criterion {
            Criterion::Held => self.at_threshold().map(|e| e.depth),
            Criterion::Released => self.released.as_ref().map(|r| r.depth),
        }
    }

    /// The evaluation closest to `d`.
    pub fn nearest(&self, d: f64) -> Option<&CreaseEnergy> {
        self.evaluations
            .iter()
            .min_by(|x, y| (x.strain - d).abs().total_cmp(&(y.strain - d).abs()))
    }

    /// The evaluation at the threshold (the nearest one).
    pub fn at_threshold(&self) -> Option<&CreaseEnergy> {
        self.d_threshold.and_then(|d| self.nearest(d))
    }

    /// The largest `d` at which the fold was evaluated (the crease does not pay off below it
    /// when no threshold was found).
    pub fn cleared(&self) -> f64 {
        self.evaluations.iter().map(|e| e.strain).fold(0.0, f64::max)
    }
}
