//! The exact first bifurcation of the discretised perfect system.
//!
//! Along the homogeneous path (eq. 4; the Q2 elements represent it exactly, so the displacement
//! is set analytically and only checked to be in equilibrium) the tangent `K_ff(d)` is positive
//! definite until its smallest eigenvalue crosses zero. Sylvester's law of inertia makes the
//! number of negative pivots of `K_ff = L D L^T` the number of negative eigenvalues; a scan in
//! `d` and a bisection on "any negative pivot" bracket the first crossing. The mode is the
//! eigenvector of the smallest eigenvalue at the stable end of the bracket, by the Lanczos
//! method on `K^-1` with the same factor; its wavenumber is the dominant cosine of its top-surface `u_y`.

use super::basic_state::homogeneous_unknowns;
use crate::error::{Error, Result};
use crate::fem::added::NoAddedEnergy;
use crate::fem::lanczos::inverse_lanczos;
use crate::fem::{Assembled, SparseLdlt, System, Tangent};
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::mesh::{Mesh, MeshSpec, Y};
use crate::protocol::Loading;

use std::f64::consts::PI;

/// Scan, bisection and inverse-iteration limits.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BifurcationSettings {
    /// Spacing of the scan in `d` from 0.
    pub scan_step: f64,
    /// Largest `d` scanned.
    pub d_end: f64,
    /// Width of the final bracket in `d`.
    pub tolerance: f64,
    /// Largest number of solves with the factor for the mode (Lanczos steps on `K^-1`).
    pub mode_solves: usize,
}

impl Default for BifurcationSettings {
    /// Scan every 0.01 up to 0.9, bracket to 1e-6, at most 50 solves for the mode.
    fn default() -> Self {
        BifurcationSettings {
            scan_step: 0.01,
            d_end: 0.9,
            tolerance: 1e-6,
            mode_solves: 50,
        }
    }
}

/// The first singular point of the homogeneous path and its mode.
#[derive(Clone, Debug)]
pub struct Bifurcation {
    /// Midpoint of the final bracket.
    pub d: f64,
    /// `(d_stable, d_unstable)`: no negative pivot at the first, some at the second.
    pub bracket: (f64, f64),
    /// Negative pivots at `d_unstable`.
    pub negative_pivots: usize,
    /// The mode, all unknowns (zero where prescribed), scaled so that the largest top-surface
    /// `|u_y|` is 1 and `u_y > 0` at the top of `X = 0`.
    pub mode: Vec<f64>,
    /// Half wavelengths of the mode across the domain.
    pub mode_number: usize,
    /// `m pi / L`.
    pub k_mode: f64,
    /// Rayleigh quotient of the mode at `d_stable` (the smallest eigenvalue there).
    pub eigenvalue: f64,
    /// Every `(d, negative pivots)` evaluated, in order.
    pub path: Vec<(f64, usize)>,
}

/// The homogeneous path of one mesh with its (reused) sparse factorisation.
struct HomogeneousPath<'a> {
    materials: &'a Bilayer,
    system: System,
    solver: Option<SparseLdlt>,
    path: Vec<(f64, usize)>,
}

impl HomogeneousPath<'_> {
    /// Number of negative pivots of `K_ff` at the homogeneous state `d` (its factor is kept).
    fn negative_pivots(&mut self, d: f64) -> Result<usize> {
        let (negative, _) = self.factorise(d)?;
        self.path.push((d, negative));
        Ok(negative)
    }

    /// Assembles and factorises `K_ff` at the homogeneous state `d`: negative pivots and `K_ff`.
    fn factorise(&mut self, d: f64) -> Result<(usize, Tangent)> {
        let bc = self.system.load_to(d)?;
        let u = homogeneous_unknowns(&self.system, self.materials, &homogeneous_state(self.materials, d)?)?;
        let assembled = self.system.assemble_for_stability(&u, &bc, &NoAddedEnergy)?;
        // The equilibrium check with the iteration's penalty: the stability penalty amplifies the
        // round-off of ln J = 0.
        let relative_residual = |a: &Assembled| a.residual_norm() / a.force_norm().max(f64::MIN_POSITIVE);
        let relative = match self.system.has_multipliers() {
            true => relative_residual(&self.system.assemble(&u, &bc, None, false)?),
            false => relative_residual(&assembled),
        };
        if relative > 1e-8 {
            return Err(Error::Solver(format!(
                "the homogeneous state at d = {d} is not a discrete equilibrium (relative residual {relative:.2e})"
            )));
        }
        let k = assembled.tangent.expect("assembled with the tangent");
        let solver = self.solver.get_or_insert_with(|| SparseLdlt::new(k.symbolic()));
        solver.factorize(k.as_ref());
        Ok((solver.negative_pivots().expect("just factorised"), k))
    }

    /// The eigenvector of the smallest eigenvalue of the current factor, by Lanczos on `K^-1`,
    /// on the free unknowns, with its Rayleigh quotient.
    fn smallest_mode(&mut self, iterations: usize, k: &Tangent) -> Result<(Vec<f64>, f64)> {
        let solver = self.solver.as_mut().expect("factorised before");
        inverse_lanczos(solver, k.as_ref(), iterations, 1e-12)
    }
}

/// Finds the first bifurcation of the perfect system of `spec` (module docs).
pub fn find_bifurcation(materials: &Bilayer, spec: MeshSpec, settings: &BifurcationSettings) -> Result<Bifurcation> {
    let mut path = HomogeneousPath {
        materials,
        system: System::new(Mesh::new(spec)?, materials)?,
        solver: None,
        path: Vec::new(),
    };
    let (stable, unstable, negative_pivots) = first_instability(|d| path.negative_pivots(d), settings)?;
    let (_, k) = path.factorise(stable)?;
    let (free_mode, eigenvalue) = path.smallest_mode(settings.mode_solves, &k)?;
    let bc = path.system.load_to(stable)?;
    let free = path.system.free_dofs(&bc)?.to_vec();
    let mut mode = vec![0.0; path.system.num_dofs()];
    for (&dof, &v) in free.iter().zip(&free_mode) {
        mode[dof] = v;
    }
    let mesh = path.system.mesh();
    scale_to_surface(mesh, &mut mode);
    let m = dominant_cosine(&top_uy(mesh, &mode), spec.length, mesh);
    Ok(Bifurcation {
        d: 0.5 * (stable + unstable),
        bracket: (stable, unstable),
        negative_pivots,
        mode,
        mode_number: m,
        k_mode: m as f64 * PI / spec.length,
        eigenvalue,
        path: path.path,
    })
}

/// The negative pivots of the stability tangent at the homogeneous states `ds` of the perfect
/// system of `spec`: past the onset, one per admissible mode whose onset lies below `d`.
pub fn homogeneous_inertia(materials: &Bilayer, spec: MeshSpec, ds: &[f64]) -> Result<Vec<usize>> {
    let mut path = HomogeneousPath {
        materials,
        system: System::new(Mesh::new(spec)?, materials)?,
        solver: None,
        path: Vec::new(),
    };
    ds.iter().map(|&d| path.negative_pivots(d)).collect()
}

/// The first `d` at which `negative_pivots(d)` is not zero, bracketed to `settings.tolerance`:
/// a scan from `scan_step` in steps of `scan_step` up to `d_end`, then bisection. Returns
/// `(d_stable, d_unstable, negative pivots at d_unstable)`.
pub(crate) fn first_instability(
    mut negative_pivots: impl FnMut(f64) -> Result<usize>,
    settings: &BifurcationSettings,
) -> Result<(f64, f64, usize)> {
    let mut stable = 0.0;
    let mut first_unstable = None;
    let mut d = settings.scan_step;
    while d <= settings.d_end + 1e-12 {
        match negative_pivots(d)? {
            0 => stable = d,
            negative => {
                first_unstable = Some((d, negative));
                break;
            }
        }
        d += settings.scan_step;
    }
    let (mut unstable, mut unstable_pivots) = first_unstable.ok_or_else(|| Error::NoRoot {
        what: "a negative pivot of the tangent on the homogeneous path".into(),
        lower: 0.0,
        upper: settings.d_end,
    })?;
    while unstable - stable > settings.tolerance {
        let middle = 0.5 * (stable + unstable);
        match negative_pivots(middle)? {
            0 => stable = middle,
            negative => (unstable, unstable_pivots) = (middle, negative),
        }
    }
    Ok((stable, unstable, unstable_pivots))
}

/// `u_y` of the top-surface nodes, sorted by `X`.
pub(crate) fn top_uy(mesh: &Mesh, u: &[f64]) -> Vec<f64> {
    mesh.top().into_iter().map(|n| u[mesh.dofs().dof(n, Y)]).collect()
}

/// Scales `u` so that the largest top-surface `|u_y|` is 1 with `u_y > 0` at `X = 0`.
fn scale_to_surface(mesh: &Mesh, u: &mut [f64]) {
    let top = top_uy(mesh, u);
    let largest = top.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let sign = if top[0] < 0.0 { -1.0 } else { 1.0 };
    if largest > 0.0 {
        u.iter_mut().for_each(|v| *v *= sign / largest);
    }
}

/// The `m >= 1` maximising `|sum_i w_i v_i cos(m pi X_i / L)|` (trapezoidal weights) over the
/// top-surface nodes.
pub(crate) fn dominant_cosine(values: &[f64], length: f64, mesh: &Mesh) -> usize {
    let xs: Vec<f64> = mesh.top().into_iter().map(|n| mesh.coordinates()[n][0]).collect();
    let last = xs.len() - 1;
    let coefficient = |m: usize| -> f64 {
        let k = m as f64 * PI / length;
        (0..=last)
            .map(|i| {
                let weight = if i == 0 || i == last { 0.5 } else { 1.0 };
                weight * values[i] * (k * xs[i]).cos()
            })
            .sum::<f64>()
            .abs()
    };
    (1..=last)
        .max_by(|&a, &b| coefficient(a).total_cmp(&coefficient(b)))
        .unwrap_or(1)
}
