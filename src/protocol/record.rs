//! What is recorded of an accepted step of a path: the solver's facts, and what the path's
//! measures ([`super::measures`]) take of the state.

use super::augmentation::AugmentedRecord;
use super::snap::SnapRecord;
use crate::fem::ellipticity::EllipticityMargins;
use crate::fem::{NewtonReport, Timings};
use serde::{Deserialize, Serialize};

/// An accepted step.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StepRecord {
    /// End-shortening reached.
    pub d: f64,
    /// Step length that reached it.
    pub step: f64,
    /// Wrinkle amplitude `A` of the converged state (by [`super::measures::SurfaceAmplitude`];
    /// this and the fields below marked so are 0 where the path takes no such measure).
    pub amplitude: f64,
    /// Strain energy of the converged state (per unit length out of plane, units mu_s H^2).
    pub strain_energy: f64,
    /// Newton iterations of the accepted attempt.
    pub iterations: usize,
    /// `|r_f|` before each iteration and at convergence.
    pub residual_history: Vec<f64>,
    /// Final residual divided by the internal-force norm.
    pub relative_residual: f64,
    /// Smallest `J` over all Gauss points.
    pub min_jacobian: f64,
    /// Negative eigenvalues of the tangent (unstable directions), when Newton reports its inertia.
    pub negative_pivots: Option<usize>,
    /// Wall time of the step, failed attempts included.
    pub seconds: f64,
    /// Wall time of the attempts discarded before this one was accepted.
    pub failed_seconds: f64,
    /// Wall times of the accepted attempt's phases.
    pub timings: Timings,
    /// Contact and stabilisation of the step, when the continuation has them.
    pub augmented: Option<AugmentedRecord>,
    /// The snap that reached this state, if it was reached by one.
    pub snap: Option<SnapRecord>,
    /// Whether this state was reached by minimising the energy from the predictor after
    /// Newton's iteration had failed (on a stable branch in contact; `iterations` are then the
    /// minimisation's steps).
    pub minimised: bool,
    /// The smallest strong-ellipticity margin of each layer over its Gauss points (by
    /// [`super::measures::Ellipticity`]).
    pub ellipticity: EllipticityMargins,
    /// The layer's growth `g` along `X` (the load under growth; 1 without growth; by
    /// [`super::measures::LayerGrowth`]).
    pub growth_layer: f64,
}

impl StepRecord {
    /// The record of a converged Newton solve, before the path's measures of the state.
    pub(super) fn new((d, step): (f64, f64), report: &NewtonReport, seconds: f64) -> Self {
        let residual = *report.residual_history.last().expect("at least the initial residual");
        StepRecord {
            d,
            step,
            amplitude: 0.0,
            strain_energy: report.energy,
            iterations: report.iterations,
            residual_history: report.residual_history.clone(),
            relative_residual: residual / report.force_norm.max(f64::MIN_POSITIVE),
            min_jacobian: report.min_jacobian,
            negative_pivots: report.negative_pivots,
            seconds,
            failed_seconds: 0.0,
            timings: report.timings,
            augmented: None,
            snap: None,
            minimised: false,
            ellipticity: EllipticityMargins {
                layer: 0.0,
                substrate: 0.0,
            },
            growth_layer: 0.0,
        }
    }
}
