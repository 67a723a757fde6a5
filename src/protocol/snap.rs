//! Snaps: where the followed branch has no nearby equilibrium (a limit point in `d`, a trough
//! closing), the stable equilibrium at the same `d` that the structure snaps to, found by
//! minimising the total potential energy (the strain energy plus the contact terms) from the
//! last equilibrium with the boundary moved to `d` ([`crate::fem::equilibrium::minimise`]).
//! Every state so recorded is an exact equilibrium of the model and a local minimum of its
//! energy; unlike a viscously damped step ([`super::stabilisation`]), it depends neither on a
//! damping coefficient nor on the step sequence that led to it.

use super::stabilisation::StabilisationSettings;
use serde::Serialize;

/// How a path goes on where the branch it follows has no nearby equilibrium (a limit point in
/// `d`, a closing trough): one way at most.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SnapCrossing {
    /// None: the path stops where Newton's method cannot follow it.
    #[default]
    None,
    /// Viscous damping of the cut steps ([`super::stabilisation`]): the recorded states carry
    /// damping forces.
    Viscous(StabilisationSettings),
    /// Minimisation of the energy at the `d` of the failed step: every recorded state is an
    /// exact equilibrium.
    Minimised(SnapSettings),
}

impl SnapCrossing {
    /// The damping, when the crossing is viscous.
    pub fn damping(&self) -> Option<StabilisationSettings> {
        match *self {
            SnapCrossing::Viscous(settings) => Some(settings),
            _ => None,
        }
    }

    /// When a failed step is retried as a snap, when the crossing minimises.
    pub fn minimisation(&self) -> Option<SnapSettings> {
        match *self {
            SnapCrossing::Minimised(settings) => Some(settings),
            _ => None,
        }
    }
}

/// When a failed step is retried as a snap.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SnapSettings {
    /// A step at most this long (or the step control's minimum, if that is longer) that
    /// Newton's method cannot converge is retried as a snap. Short, so that a branch that goes
    /// on is followed (an unstable one too: the minimisation would leave it) and the snap
    /// happens within `below` of where the branch ends: measured on the coarse compare case
    /// (mixed element), the periodic branch ends at a fold at d = 0.240157, which steps of
    /// `3e-4` overshoot and steps down to `1e-7` resolve.
    pub below: f64,
}

impl Default for SnapSettings {
    /// Steps of at most `1e-6`.
    fn default() -> Self {
        SnapSettings { below: 1e-6 }
    }
}

/// One snap: the last equilibrium of the branch left, and the minimum reached.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct SnapRecord {
    /// End-shortening of the snap (the new state's).
    pub d: f64,
    /// End-shortening of the last equilibrium of the branch left.
    pub d_before: f64,
    /// Amplitude `A` and total energy (strain plus contact) of that equilibrium.
    pub amplitude_before: f64,
    pub energy_before: f64,
    /// Total energy of the start of the minimisation: that equilibrium with the boundary moved
    /// to `d`.
    pub energy_start: f64,
    /// Amplitude and total energy of the minimum reached.
    pub amplitude_after: f64,
    pub energy_after: f64,
    /// `energy_start - energy_after`: the minimisation never raises the energy, but with contact
    /// each is measured with its own state's multipliers, so a snap that only closes a contact
    /// pair may release a little less than nothing (within the multiplier update's change).
    pub energy_released: f64,
    /// Negative eigenvalues of the tangent at the minimum reached (none: it is stable).
    pub negative_pivots_after: Option<usize>,
    /// Steps of the minimisation (over all its passes).
    pub steps: usize,
    /// Its factorisations (shifted and unshifted tangents).
    pub factorisations: usize,
    /// Wall time of the snap.
    pub seconds: f64,
}
