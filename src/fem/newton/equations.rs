//! What Newton's method solves ([`Equations`]) and minimises ([`EnergyEquations`]), and the
//! equations of a finite-element system ([`SystemEquations`]).

use crate::fem::added::AddedEnergy;
use crate::fem::assembly::{Assembled, System};
use crate::fem::boundary::Dirichlet;
use crate::fem::element::{Penalty, Registry, DOFS, GAUSS_POINTS, NODES};
#[cfg(doc)]
use crate::fem::Newton;
use crate::mesh::ElementKind;

/// What Newton's method solves: `r(u) = 0` on the free unknowns of `u`, whose prescribed unknowns
/// move to their given values. The equations give the residual and its tangent at a state; the
/// method brings the linear solve.
pub trait Equations {
    /// The prescribed unknowns and their values.
    fn prescribed(&self) -> &Dirichlet;
    /// The free unknowns, increasing (position = index in the residual).
    fn free_unknowns(&mut self) -> crate::Result<Vec<usize>>;
    /// The residual on the free unknowns (and the tangent when `with_tangent`) at the full `u`,
    /// plus `K_fc lift` when `lift` is given (one value per prescribed unknown).
    fn assemble(&mut self, u: &[f64], lift: Option<&[f64]>, with_tangent: bool) -> crate::Result<Assembled>;
    /// The factor on the convergence tolerance (a raised penalty raises the residual's
    /// round-off in proportion).
    fn tolerance_scale(&self) -> f64 {
        1.0
    }
    /// How many leading unknowns of `u` set the scale of an update (the displacements, not the
    /// multipliers that may follow them).
    fn scaled_unknowns(&self) -> usize;
    /// Where along the step from `u` to `full` the first term that the tangent at `u` lacks
    /// switches on (1: none), for the line search to start there.
    fn switch_on_fraction(&self, _u: &[f64], _full: &[f64]) -> f64 {
        1.0
    }
}

/// Equations that are the gradient of an energy (the residual's potential), which the
/// minimiser ([`Newton::minimise`]) descends.
pub trait EnergyEquations: Equations {
    /// A positive scale of each unknown's stiffness (the minimiser's shift is proportional).
    fn stiffness_scale(&self) -> crate::Result<Vec<f64>>;
    /// `assembled` (of these equations, with its tangent) with `curvature[dof]` added to the
    /// tangent's diagonal entry of every free unknown, without assembling again.
    fn with_diagonal_added(&self, assembled: &Assembled, curvature: &[f64]) -> Assembled;
}

/// The equations of a finite-element system: its strain energy plus `added`, with `bc`
/// prescribed and the multipliers' penalty multiplied by `penalty_scale`.
pub struct SystemEquations<
    'a,
    const D: usize = 2,
    const N: usize = NODES,
    const Q: usize = GAUSS_POINTS,
    const U: usize = DOFS,
> {
    pub system: &'a mut System<D, N, Q, U>,
    pub bc: &'a Dirichlet,
    pub added: &'a dyn AddedEnergy,
    pub penalty_scale: f64,
}

impl<const D: usize, const N: usize, const Q: usize, const U: usize> Equations for SystemEquations<'_, D, N, Q, U>
where
    ElementKind: Registry<D, N, Q, U>,
{
    fn prescribed(&self) -> &Dirichlet {
        self.bc
    }

    fn free_unknowns(&mut self) -> crate::Result<Vec<usize>> {
        Ok(self.system.free_dofs(self.bc)?.to_vec())
    }

    fn assemble(&mut self, u: &[f64], lift: Option<&[f64]>, with_tangent: bool) -> crate::Result<Assembled> {
        self.system.assemble_penalised(
            u,
            self.bc,
            lift,
            with_tangent,
            self.added,
            Penalty::Augmentation(self.penalty_scale),
        )
    }

    fn tolerance_scale(&self) -> f64 {
        self.penalty_scale
    }

    fn scaled_unknowns(&self) -> usize {
        self.system.mesh().num_dofs()
    }

    fn switch_on_fraction(&self, u: &[f64], full: &[f64]) -> f64 {
        self.added.switch_on_fraction(u, full)
    }
}

impl<const D: usize, const N: usize, const Q: usize, const U: usize> EnergyEquations for SystemEquations<'_, D, N, Q, U>
where
    ElementKind: Registry<D, N, Q, U>,
{
    fn stiffness_scale(&self) -> crate::Result<Vec<f64>> {
        self.system.reference_stiffness_diagonal()
    }

    fn with_diagonal_added(&self, assembled: &Assembled, curvature: &[f64]) -> Assembled {
        self.system.with_diagonal_added(assembled, curvature)
    }
}
