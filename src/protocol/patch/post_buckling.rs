//! The patch's path past its bifurcation, by the strip's protocol in three dimensions: the
//! critical waves are put into the reference geometry as an imperfection
//! ([`PatchImperfection`]), the imperfect patch is solved at `d_start` from its homogeneous
//! state, and the path is followed in `d` to `d_max` by the continuation
//! ([`crate::protocol::Continuation`], adaptive steps, extrapolating predictor), each accepted
//! state reported with its wrinkle amplitude and the inertia of its tangent.
//!
//! Where the followed branch turns unstable (a negative eigenvalue of the tangent: the
//! superposed waves of a checkerboard, say, giving way to another pattern), the structure leaves
//! it: the energy is minimised at that `d` from the unstable state moved a little along its
//! unstable direction ([`Continuation::leave_unstable_state`]), and the path goes on from the
//! stable state reached.

use super::{homogeneous_patch_unknowns, nearest_singular_mode, BiaxialPatch, PatchPath};
use crate::error::{Error, Result};
use crate::fem::{Newton, NewtonPolicy, PatchSystem};
use crate::homogeneous::biaxial_state;
use crate::protocol::continuation::{Continuation, Event, Followed, StepControl};
use crate::protocol::imperfection::Imperfection;
use crate::protocol::measures::{Measure, SurfaceAmplitude};
use crate::protocol::record::StepRecord;
use crate::protocol::snap::SnapSettings;
use crate::protocol::stages::{simulation_newton, Resumption};

/// The reference-geometry imperfection `Delta Y = sum_j A_j c_j(X, Z) s_j(Y)` of a patch: one
/// wave of amplitude `A_j` per seeded wave vector `k_j = (k_x, k_z)`, `c_j = cos(k_j . X)` on
/// periodic sides and `cos(k_x X) cos(k_z Z)` on symmetry sides (the waves those sides admit),
/// each decaying into the substrate as the strip's ([`Imperfection::shape`] at `|k_j|`). Nodes
/// move vertically only.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchImperfection {
    /// The seeded waves: `(k_x, k_z)` and the amplitude `A_j`.
    pub waves: Vec<([f64; 2], f64)>,
    /// Substrate depth `D`.
    pub depth: f64,
    /// Whether the sides are symmetry planes (the waves are products of cosines).
    pub symmetric: bool,
}

impl PatchImperfection {
    /// The node displacement `[0, Delta Y, 0]` at the reference point `[X, Y, Z]`.
    pub fn displacement(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        let height = self
            .waves
            .iter()
            .map(|&([kx, kz], amplitude)| {
                let shape = Imperfection {
                    amplitude,
                    k: kx.hypot(kz),
                    depth: self.depth,
                };
                let surface = match self.symmetric {
                    true => (kx * x).cos() * (kz * z).cos(),
                    false => (kx * x + kz * z).cos(),
                };
                amplitude * surface * shape.shape(y)
            })
            .sum();
        [0.0, height, 0.0]
    }
}

/// The protocol of a patch's path.
#[derive(Clone, Copy, Debug)]
pub struct PatchProtocol {
    /// Where the path starts (below the bifurcation, where the imperfect patch is close to its
    /// homogeneous state).
    pub d_start: f64,
    /// Where it ends.
    pub d_max: f64,
    /// Adaptive steps.
    pub control: StepControl,
    /// Newton's policy of every step (the inertia of each solution is counted).
    pub newton: NewtonPolicy,
}

/// The absolute residual tolerance of a patch's Newton steps. On periodic sides the internal
/// forces cancel and no reaction sets a scale, so the strip's relative tolerance leaves only the
/// absolute one: the strip's default of 1e-12 lies at the round-off floor of a 3D patch's
/// residual (2e-12 measured on 12,382 unknowns), where its reactions (of order 1) make its own
/// effective tolerance about 1e-10.
const ABSOLUTE_TOLERANCE: f64 = 1e-10;

impl PatchProtocol {
    /// From `d_start` to `d_max` with the strip's steps and Newton's policy, but for an absolute
    /// tolerance of 1e-10 (a periodic patch's residual has no reaction to scale it by).
    pub fn new(d_start: f64, d_max: f64) -> Self {
        PatchProtocol {
            d_start,
            d_max,
            control: StepControl::default(),
            newton: NewtonPolicy {
                inertia_at_solution: true,
                absolute_tolerance: ABSOLUTE_TOLERANCE,
                ..simulation_newton()
            },
        }
    }
}

/// Most unstable branches a path leaves.
const MAX_BRANCHES_LEFT: usize = 8;

/// Inverse-Lanczos steps for an unstable direction.
const MODE_SOLVES: usize = 60;

/// The size of the move off an unstable state, relative to its wrinkle amplitude (at least
/// [`SMALLEST_MOVE`]): large enough for the minimisation to leave the saddle, small against the
/// pattern.
const MOVE_OFF: f64 = 0.1;

/// The smallest move off an unstable state, in layer thicknesses.
const SMALLEST_MOVE: f64 = 1e-3;

/// A move of the current (unstable) state along the unstable direction of its tangent, whose
/// largest nodal displacement is [`MOVE_OFF`] times the state's wrinkle amplitude.
fn unstable_perturbation(continuation: &mut Continuation<BiaxialPatch>) -> Result<Vec<f64>> {
    let u = continuation.displacement().to_vec();
    let d = continuation.d();
    let patch = continuation.system_mut();
    let size = (MOVE_OFF * patch.amplitude(&u)).max(SMALLEST_MOVE);
    let bc = patch.load_to(d)?;
    let (mode, _) = nearest_singular_mode(patch.system_mut(), &u, &bc, MODE_SOLVES)?;
    let largest = mode[..patch.displacement_unknowns()]
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    Ok(mode.into_iter().map(|v| size * v / largest).collect())
}

/// The amplitude measure of a patch's state.
impl Measure<BiaxialPatch> for SurfaceAmplitude {
    fn measure(&self, patch: &BiaxialPatch, u: &[f64], record: &mut StepRecord) -> Result<()> {
        record.amplitude = patch.amplitude(u);
        Ok(())
    }
}

impl PatchPath<'_> {
    /// Follows this path's patch with `imperfection` from `protocol.d_start` to
    /// `protocol.d_max`, reporting every accepted state (the first at `d_start`) and every cut
    /// step to `observer`. Returns the path, stopped early with why if a step failed at the
    /// smallest step.
    pub fn follow(
        self,
        imperfection: &PatchImperfection,
        protocol: &PatchProtocol,
        observer: &mut dyn FnMut(Event<'_, BiaxialPatch>) -> Result<()>,
    ) -> Result<(Continuation<BiaxialPatch>, Option<Error>)> {
        self.follow_resumable(imperfection, protocol, Resumption::default(), observer)
    }

    /// [`PatchPath::follow`], reporting its whole state as `resumption` asks, or continuing
    /// from a state it reported (the imperfect patch at `d_start` is then solved again, as the
    /// start of the predictor, but not reported).
    pub fn follow_resumable(
        self,
        imperfection: &PatchImperfection,
        protocol: &PatchProtocol,
        resumption: Resumption,
        observer: &mut dyn FnMut(Event<'_, BiaxialPatch>) -> Result<()>,
    ) -> Result<(Continuation<BiaxialPatch>, Option<Error>)> {
        let (d_start, d_max) = (protocol.d_start, protocol.d_max);
        if !(d_start.is_finite() && d_start > 0.0 && d_start < d_max) {
            return Err(Error::invalid("d-start", d_start, &format!("(0, d-max = {d_max})")));
        }
        let materials = self.materials;
        let (perfect, biaxiality, held) = self.patch.into_parts();
        let mesh = perfect.mesh().clone().perturbed(|x| imperfection.displacement(x));
        drop(perfect);
        let mut patch = BiaxialPatch::new(PatchSystem::on_patch(mesh, materials)?, biaxiality, held);
        let state = biaxial_state(materials, d_start, biaxiality * d_start)?;
        let bc = patch.load_to(d_start)?;
        let mut u = homogeneous_patch_unknowns(patch.system(), materials, &state)?;
        bc.impose(&mut u);
        let mut newton = Newton::new();
        let homogeneous = u.clone();
        let (report, _) = patch
            .correct(
                &mut newton,
                &protocol.newton,
                &mut u,
                &bc,
                None,
                (d_start, &homogeneous),
                (d_start, 0.0),
            )
            .map_err(|e| Error::Solver(format!("the imperfect patch at d_start = {d_start}: {e}")))?;
        if resumption.from.is_none() {
            let mut record = StepRecord::new((d_start, 0.0), &report, 0.0);
            SurfaceAmplitude.measure(&patch, &u, &mut record)?;
            observer(Event::Step {
                record: &record,
                system: &patch,
                u: &u,
            })?;
        }
        // The first step is predicted along the homogeneous path's du/dd (central difference).
        let h = 1e-3 * d_start;
        let homogeneous = |d: f64| -> Result<Vec<f64>> {
            homogeneous_patch_unknowns(patch.system(), materials, &biaxial_state(materials, d, biaxiality * d)?)
        };
        let (ahead, behind) = (homogeneous(d_start + h)?, homogeneous(d_start - h)?);
        let slope = ahead.iter().zip(&behind).map(|(a, b)| (a - b) / (2.0 * h)).collect();
        let measures: Vec<Box<dyn Measure<BiaxialPatch>>> = vec![Box::new(SurfaceAmplitude)];
        let mut continuation = Continuation::new((patch, newton, protocol.newton), protocol.control, d_start, u)?
            .with_first_slope(slope)
            .with_measures(measures)
            .halting_where_unstable()
            .with_snaps(SnapSettings::default());
        if let Some(interval) = resumption.checkpoints {
            interval.validate()?;
            continuation = continuation.with_checkpoints(interval);
        }
        if let Some(state) = resumption.from {
            continuation.resume(state)?;
        }
        loop {
            if let Err(stopped) = continuation.advance_to(d_max, observer) {
                return Ok((continuation, Some(stopped)));
            }
            if !continuation.is_unstable() {
                return Ok((continuation, None));
            }
            let left = continuation.unstable_states_left();
            if left == MAX_BRANCHES_LEFT {
                let d = continuation.d();
                let why = format!("the path turned unstable at d = {d:.6} after leaving {left} unstable branches");
                return Ok((continuation, Some(Error::Solver(why))));
            }
            let perturbation = unstable_perturbation(&mut continuation)?;
            if let Err(e) = continuation.leave_unstable_state(&perturbation, observer) {
                let d = continuation.d();
                let why = format!("the unstable state at d = {d:.6} could not be left for a stable one: {e}");
                return Ok((continuation, Some(Error::Solver(why))));
            }
        }
    }
}
