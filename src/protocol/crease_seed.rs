//! A crease seeded in a homogeneously compressed solid, and its energy against the flat state
//! (Hong, Zhao & Suo 2009, Appl. Phys. Lett. 95, 111901).
//!
//! The solid is first compressed homogeneously to the end-shortening `eps` (the Q2 elements
//! represent that state exactly), or grown to `g = 1/(1 - eps)` under a growth load. Then the top-surface nodes with `0 < X <= a` are carried onto
//! the symmetry plane `x = 0` (their `u_x` ramped to `-X`, `u_y` free: frictionless), while every
//! other surface node may touch the plane but not cross it (contact, [`crate::fem::contact`]).
//! By the mirror symmetry this is a crease whose two faces are in self-contact over the
//! reference length `a` on each side. With no length scale in a half-space the energy change is
//! `U_crease - U_flat = mu a^2 f(eps)`, so its sign depends on `eps` alone (for `a` small
//! against the domain and large against the elements): it changes sign at the creasing
//! threshold, `eps_c ~ 0.35` for an incompressible neo-Hookean solid, far below Biot's 0.456.

use super::basic_state::homogeneous_unknowns;
use crate::error::{Error, Result};
use crate::fem::added::NoAddedEnergy;
use crate::fem::boundary::{dof, X};
use crate::fem::contact::{Contact, ContactSettings, Plane};
use crate::fem::ellipticity::{ellipticity_margins, EllipticityMargins};
use crate::fem::equilibrium::solve_with_contact;
use crate::fem::{Dirichlet, Newton, NewtonPolicy, System};
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::mesh::{Mesh, MeshSpec};
use serde::Serialize;

/// Smallest ramp step of the folding before giving up.
const MIN_RAMP_STEP: f64 = 1.0 / 512.0;

/// The energies of the flat and the creased state at one compression.
#[derive(Clone, Debug, Serialize)]
pub struct CreaseEnergy {
    /// End-shortening `eps` of the homogeneous compression.
    pub strain: f64,
    /// Reference length `a` of surface folded onto the plane.
    pub fold_length: f64,
    pub flat_energy: f64,
    pub crease_energy: f64,
    /// `U_crease - U_flat`.
    pub difference: f64,
    /// `(U_crease - U_flat) / (mu a^2)`: the scale-free `f(eps)`.
    pub scaled_difference: f64,
    /// Deformed depth of the crease: the lowest point of the surface on the plane, below the
    /// flat surface.
    pub depth: f64,
    /// Folded nodes that the plane pulls rather than pushes (a valid contact has none).
    pub tensile_nodes: usize,
    /// Smallest `J` at a Gauss point of the creased state.
    pub min_jacobian: f64,
    /// Ramp steps taken.
    pub steps: usize,
    /// The smallest strong-ellipticity margins over the Gauss points of the creased state.
    pub ellipticity: EllipticityMargins,
    /// The deformed top surface of the creased state, `(x, y)` from the crease outwards.
    #[serde(skip)]
    pub surface: Vec<(f64, f64)>,
}

/// `U_crease - U_flat` at the load's strain `strain` (the compression, or `1 - 1/g` under
/// growth) for a fold of reference length `fold_length` on a mesh of `spec` (one material,
/// shear modulus `mu`).
pub fn crease_energy(materials: &Bilayer, spec: MeshSpec, strain: f64, fold_length: f64) -> Result<CreaseEnergy> {
    let mesh = Mesh::new(spec)?;
    let mu = materials.layer.energy.shear_modulus();
    let state = homogeneous_state(materials, strain)?;
    let folded: Vec<usize> = mesh
        .top()
        .into_iter()
        .filter(|&n| (1e-12..=fold_length * (1.0 + 1e-9)).contains(&mesh.coordinates()[n][0]))
        .collect();
    if folded.len() < 2 {
        return Err(Error::invalid("fold length", fold_length, "at least two surface nodes"));
    }
    let mut contact = Contact::new(&mesh, vec![Plane::left(0.0)], {
        let mut settings = ContactSettings::for_mesh(&mesh, mu);
        settings.self_contact = false;
        settings
    });
    let mut system = System::new(mesh, materials)?;
    let model = system.load_to(strain)?;
    let mut u = homogeneous_unknowns(&system, materials, &state)?;
    let flat_energy = system.assemble(&u, &model, None, false)?.energy;
    let mut newton = Newton::new();
    let policy = NewtonPolicy {
        max_iterations: 25,
        inertia_at_solution: false,
        ..NewtonPolicy::default()
    };
    let (mut t, mut step, mut steps) = (0.0f64, 0.125f64, 0);
    let mut report = None;
    while t < 1.0 {
        let next = (t + step).min(1.0);
        let bc = folding_conditions(&system, &model, &folded, state.lambda1, next)?;
        match solve_with_contact(
            &mut newton,
            &mut system,
            &mut u,
            &bc,
            &mut contact,
            &NoAddedEnergy,
            &policy,
        ) {
            Ok(solved) => {
                (t, steps) = (next, steps + 1);
                if solved.iterations <= 8 {
                    step = (2.0 * step).min(0.25);
                }
                report = Some((solved, bc));
            }
            Err(_) if step > MIN_RAMP_STEP => step *= 0.5,
            Err(e) => {
                return Err(Error::Solver(format!(
                    "folding the crease at eps = {strain} stopped at {:.4} of the fold: {e}",
                    t
                )))
            }
        }
    }
    let (report, bc) = report.expect("at least one step");
    let mesh = system.mesh();
    let reactions: Vec<f64> = folded
        .iter()
        .map(|&n| {
            report.reactions[bc
                .dofs()
                .binary_search(&dof(n, X))
                .expect("folded unknowns are prescribed")]
        })
        .collect();
    let y = |n: usize| mesh.coordinates()[n][1] + u[2 * n + 1];
    let surface = mesh.top();
    let profile = surface
        .iter()
        .map(|&n| (mesh.coordinates()[n][0] + u[2 * n], y(n)))
        .collect();
    let depth = y(*surface.last().expect("a surface")) - folded.iter().map(|&n| y(n)).fold(f64::INFINITY, f64::min);
    let crease_energy = report.energy;
    let ellipticity = ellipticity_margins(&system, &u)?;
    Ok(CreaseEnergy {
        strain,
        fold_length,
        flat_energy,
        crease_energy,
        difference: crease_energy - flat_energy,
        scaled_difference: (crease_energy - flat_energy) / (mu * fold_length * fold_length),
        depth,
        tensile_nodes: reactions.iter().filter(|&&r| r < 0.0).count(),
        min_jacobian: report.min_jacobian,
        steps,
        ellipticity,
        surface: profile,
    })
}

/// The model's conditions plus the folded nodes at `x = (1 - t) lambda_1 X` (`t` from 0 to 1).
fn folding_conditions(system: &System, model: &Dirichlet, folded: &[usize], lambda1: f64, t: f64) -> Result<Dirichlet> {
    let coordinates = system.mesh().coordinates();
    let mut pairs: Vec<(usize, f64)> = model
        .dofs()
        .iter()
        .copied()
        .zip(model.values().iter().copied())
        .collect();
    pairs.extend(folded.iter().map(|&n| {
        let x = coordinates[n][0];
        (dof(n, X), (1.0 - t) * lambda1 * x - x)
    }));
    Dirichlet::new(pairs)
}
