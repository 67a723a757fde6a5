//! The patch's path past its bifurcation, by the strip's protocol in three dimensions: the
//! critical waves are put into the reference geometry as an imperfection
//! ([`PatchImperfection`]), the imperfect patch is solved at `d_start` from its homogeneous
//! state, and the path is followed in `d` to `d_max` by the continuation
//! ([`crate::protocol::Continuation`], adaptive steps, extrapolating predictor), each accepted
//! state reported with its wrinkle amplitude and the inertia of its tangent.

use super::{homogeneous_patch_unknowns, BiaxialPatch, PatchPath};
use crate::error::{Error, Result};
use crate::fem::{Newton, NewtonPolicy, PatchSystem};
use crate::homogeneous::biaxial_state;
use crate::protocol::continuation::{Continuation, Event, Followed, StepControl};
use crate::protocol::imperfection::Imperfection;
use crate::protocol::measures::{Measure, SurfaceAmplitude};
use crate::protocol::record::StepRecord;
use crate::protocol::stages::simulation_newton;

/// The reference-geometry imperfection `Delta Y = A_init sum_j cos(k_j . X) s_j(Y)` of a
/// patch: one cosine of amplitude `A_init` per seeded wave vector `k_j = (k_x, k_z)`, each
/// decaying into the substrate as the strip's ([`Imperfection::shape`] at `|k_j|`). Nodes move
/// vertically only.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchImperfection {
    /// `A_init`, the amplitude of each seeded wave.
    pub amplitude: f64,
    /// The seeded wave vectors `(k_x, k_z)`.
    pub waves: Vec<[f64; 2]>,
    /// Substrate depth `D`.
    pub depth: f64,
}

impl PatchImperfection {
    /// The node displacement `[0, Delta Y, 0]` at the reference point `[X, Y, Z]`.
    pub fn displacement(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        let height = self
            .waves
            .iter()
            .map(|&[kx, kz]| {
                let shape = Imperfection {
                    amplitude: self.amplitude,
                    k: kx.hypot(kz),
                    depth: self.depth,
                };
                self.amplitude * (kx * x + kz * z).cos() * shape.shape(y)
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

impl PatchProtocol {
    /// From `d_start` to `d_max` with the strip's steps and Newton's policy.
    pub fn new(d_start: f64, d_max: f64) -> Self {
        PatchProtocol {
            d_start,
            d_max,
            control: StepControl::default(),
            newton: NewtonPolicy {
                inertia_at_solution: true,
                ..simulation_newton()
            },
        }
    }
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
        let mut record = StepRecord::new((d_start, 0.0), &report, 0.0);
        SurfaceAmplitude.measure(&patch, &u, &mut record)?;
        observer(Event::Step {
            record: &record,
            system: &patch,
            u: &u,
        })?;
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
            .with_measures(measures);
        let stopped = continuation.advance_to(d_max, observer).err();
        Ok((continuation, stopped))
    }
}
