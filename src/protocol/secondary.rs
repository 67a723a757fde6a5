//! Secondary bifurcations along the computed (wrinkled) path, and which branch the path took.
//!
//! The number of negative pivots of the converged tangent `K = L D L^T` is, by Sylvester's law,
//! the number of unstable directions of the state; every change of it between two accepted
//! steps brackets a bifurcation (or a limit point) of the path. Its mode is the eigenvector of
//! the eigenvalue nearest zero at the state after the change, by the Lanczos method on `K^-1`
//! with the factor. The branch is "periodic" when the troughs of the seeded mode end up equally deep,
//! "localised" when one trough is clearly the deepest, and "modulated" when several deep
//! troughs alternate with shallow ones (e.g. a period doubling).

use super::bifurcation::{dominant_cosine, top_uy};
use super::record::StepRecord;
use super::surface::surface_profile;
use crate::error::Result;
use crate::fem::added::NoAddedEnergy;
use crate::fem::lanczos::inverse_lanczos;
use crate::fem::{Dirichlet, SparseLdlt, System};
use crate::material::Bilayer;
use crate::mesh::{Mesh, Y};
use crate::protocol::Loading;
use serde::Serialize;

/// Troughs whose depths differ by more than this fraction of the deepest are clearly different.
pub const LOCALISED_SPREAD: f64 = 0.2;

/// One change of the inertia between consecutive accepted steps.
#[derive(Clone, Debug, Serialize)]
pub struct InertiaChange {
    pub d_before: f64,
    pub d_after: f64,
    pub negative_before: usize,
    pub negative_after: usize,
}

/// Every change of the number of negative pivots along `records` (steps without it are skipped).
pub fn inertia_changes(records: &[StepRecord]) -> Vec<InertiaChange> {
    let tracked: Vec<(f64, usize)> = records.iter().filter_map(|r| Some((r.d, r.negative_pivots?))).collect();
    tracked
        .windows(2)
        .filter(|w| w[0].1 != w[1].1)
        .map(|w| InertiaChange {
            d_before: w[0].0,
            d_after: w[1].0,
            negative_before: w[0].1,
            negative_after: w[1].1,
        })
        .collect()
}

/// The eigenpair of the elastic tangent at the state `u` (end-shortening `d`) whose eigenvalue
/// is nearest zero: Lanczos on `K^-1`, the mode on all unknowns (zero where prescribed) scaled to
/// a largest top-surface `|u_y|` of 1.
pub fn mode_nearest_zero(system: &mut System, u: &[f64], d: f64, iterations: usize) -> Result<(Vec<f64>, f64)> {
    let mut modes = modes_nearest_zero(system, &[(d, u)], iterations, None)?;
    Ok(modes.pop().expect("one state, one mode"))
}

/// [`mode_nearest_zero`] of each state `(d, u)`, two at a time on two threads: each factor
/// and its Lanczos iteration on a thread of its own, the factors sharing one analysis: that of
/// `analysed` (a solver and the structure id its analysis is for, e.g. the path's) where the
/// tangents have that structure, else their own.
pub fn modes_nearest_zero(
    system: &mut System,
    states: &[(f64, &[f64])],
    iterations: usize,
    mut analysed: Option<(usize, SparseLdlt)>,
) -> Result<Vec<(Vec<f64>, f64)>> {
    let mut solvers: Vec<SparseLdlt> = Vec::new();
    let mut modes = Vec::with_capacity(states.len());
    for pair in states.chunks(2) {
        let (bcs, tangents): (Vec<Dirichlet>, Vec<_>) = pair
            .iter()
            .map(|&(d, u)| {
                let bc = system.load_to(d)?;
                let assembled = system.assemble_for_stability(u, &bc, &NoAddedEnergy)?;
                let structure = assembled.structure;
                Ok((bc, (structure, assembled.tangent.expect("assembled with the tangent"))))
            })
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .unzip();
        let (structure, _) = &tangents[0];
        while solvers.len() < tangents.len() {
            let solver = match (solvers.first(), analysed.take()) {
                (Some(first), _) => first.sibling(),
                (None, Some((of, solver))) if of == *structure => solver,
                (None, _) => SparseLdlt::new(tangents[0].1.symbolic()),
            };
            solvers.push(solver);
        }
        let eigenpairs: Vec<Result<(Vec<f64>, f64)>> = std::thread::scope(|scope| {
            let running: Vec<_> = solvers
                .iter_mut()
                .zip(&tangents)
                .map(|(solver, (_, k))| {
                    scope.spawn(move || {
                        solver.factorize(k.as_ref());
                        inverse_lanczos(solver, k.as_ref(), iterations, 1e-10)
                    })
                })
                .collect();
            running
                .into_iter()
                .map(|thread| thread.join().expect("the Lanczos thread does not panic"))
                .collect()
        });
        for (bc, eigenpair) in bcs.iter().zip(eigenpairs) {
            let (x, eigenvalue) = eigenpair?;
            modes.push((scaled_mode(system, bc, &x)?, eigenvalue));
        }
    }
    Ok(modes)
}

/// The free unknowns `x` (with `bc` prescribed) as a mode on all unknowns (zero where
/// prescribed), scaled to a largest top-surface `|u_y|` of 1.
fn scaled_mode(system: &mut System, bc: &Dirichlet, x: &[f64]) -> Result<Vec<f64>> {
    let mut mode = vec![0.0; system.num_dofs()];
    for (&dof, &v) in system.free_dofs(bc)?.iter().zip(x) {
        mode[dof] = v;
    }
    let top = system.mesh().top();
    let largest = top
        .iter()
        .fold(0.0f64, |m, &n| m.max(mode[system.mesh().dofs().dof(n, Y)].abs()));
    if largest > 0.0 {
        mode.iter_mut().for_each(|v| *v /= largest);
    }
    Ok(mode)
}

/// The branch a path ended on: the depth below the highest surface point of each trough of the
/// seeded mode `A_init cos(k X)` ([`first_trough`]), and its kind.
#[derive(Clone, Debug, Serialize)]
pub struct Branch {
    pub trough_depths: Vec<f64>,
    pub kind: BranchKind,
}

/// How the troughs of the seeded mode compare ([`branch_kind`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BranchKind {
    /// Every trough as deep as the deepest, within [`LOCALISED_SPREAD`].
    Periodic,
    /// One trough deeper than all others.
    Localised,
    /// Deep troughs alternating with shallow ones.
    Modulated,
}

impl BranchKind {
    pub fn name(self) -> &'static str {
        match self {
            BranchKind::Periodic => "periodic",
            BranchKind::Localised => "localised",
            BranchKind::Modulated => "modulated",
        }
    }
}

/// Classifies the final state `u` of `mesh` seeded with `imperfection cos(k X)` (module docs).
pub fn branch(mesh: &Mesh, u: &[f64], k: f64, imperfection: f64) -> Branch {
    let reference: Vec<f64> = mesh.top().iter().map(|&n| mesh.coordinates()[n][0]).collect();
    let first = first_trough(k, imperfection);
    let trough_depths = trough_depths(&reference, &surface_profile(mesh, u), k, first, mesh.spec().length);
    Branch {
        kind: branch_kind(&trough_depths),
        trough_depths,
    }
}

/// Where the first trough of the seeded mode `imperfection cos(k X)` lies: half a wavelength
/// from `X = 0` for a positive amplitude (a crest on each symmetry plane), on `X = 0` for a
/// negative one (a trough there, and on the far plane when the domain holds whole waves).
pub fn first_trough(k: f64, imperfection: f64) -> f64 {
    match imperfection < 0.0 {
        true => 0.0,
        false => std::f64::consts::PI / k,
    }
}

/// The depth below the highest point of `profile` (deformed `(x, y)` of the surface points at
/// reference abscissae `reference`) of each trough of a mode of wavenumber `k` whose first
/// trough lies at `first` ([`first_trough`]), on `[0, length]`: the lowest point within a
/// quarter wavelength of `X = first + 2 j pi / k`.
pub fn trough_depths(reference: &[f64], profile: &[(f64, f64)], k: f64, first: f64, length: f64) -> Vec<f64> {
    let top = profile.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.1));
    let half = std::f64::consts::PI / k;
    (0..)
        .map(|j| first + (2 * j) as f64 * half)
        .take_while(|&centre| centre <= length + 1e-9)
        .map(|centre| {
            let lowest = reference
                .iter()
                .zip(profile)
                .filter(|(x, _)| (**x - centre).abs() <= 0.5 * half)
                .fold(f64::INFINITY, |m, (_, p)| m.min(p.1));
            top - lowest
        })
        .collect()
}

/// Periodic when every trough is within [`LOCALISED_SPREAD`] of the deepest, localised when
/// the deepest leads the next by more, modulated otherwise.
pub fn branch_kind(trough_depths: &[f64]) -> BranchKind {
    let mut sorted = trough_depths.to_vec();
    sorted.sort_by(|a, b| b.total_cmp(a));
    let spread = |other: f64| sorted[0] - other > LOCALISED_SPREAD * sorted[0];
    match sorted.as_slice() {
        [] | [_] => BranchKind::Periodic,
        [_, second, ..] if spread(*second) => BranchKind::Localised,
        [.., shallowest] if spread(*shallowest) => BranchKind::Modulated,
        _ => BranchKind::Periodic,
    }
}

/// The first change of the tangent's inertia along a protocol's path, and its mode.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SecondaryMode {
    /// `d` of the first state with the changed inertia.
    pub d: f64,
    /// The mode's dominant number of half wavelengths across the domain (`cos(m pi X / L)`).
    pub half_waves: usize,
}

/// The mode nearest zero of the tangent at the state `u` (end-shortening `d`) of `mesh`, and
/// its dominant number of half wavelengths across the domain.
pub fn secondary_mode(materials: &Bilayer, mesh: &Mesh, u: &[f64], d: f64) -> Result<SecondaryMode> {
    let mut system = System::new(mesh.clone(), materials)?;
    let (mode, _) = mode_nearest_zero(&mut system, u, d, 60)?;
    Ok(SecondaryMode {
        d,
        half_waves: dominant_cosine(&top_uy(mesh, &mode), mesh.spec().length, mesh),
    })
}
