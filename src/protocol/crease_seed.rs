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
use crate::fem::contact::{Contact, ContactSettings, Plane};
use crate::fem::ellipticity::{ellipticity_margins, EllipticityMargins};
use crate::fem::equilibrium::{minimise, solve_with_contact};
use crate::fem::{Dirichlet, Newton, NewtonPolicy, NewtonReport, System};
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::mesh::{Mesh, MeshSpec, X, Y};
use crate::protocol::Loading;
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

/// A fold let go: its nodes freed to frictionless contact with the plane, and the energy
/// minimised from the folded state with the model's conditions alone. The plane then pushes
/// wherever it touches, so this is an equilibrium crease (or the flat state, if it reopens).
/// Its energy need not lie below the held fold's: the contact and, in an incompressible solid,
/// the volume constraint enter through multipliers updated between minimisations, and each
/// minimisation descends only its own augmented energy.
#[derive(Clone, Debug, Serialize)]
pub struct ReleasedCrease {
    pub strain: f64,
    /// The reference length `a` that was folded before the release.
    pub fold_length: f64,
    /// `U_released - U_flat`.
    pub difference: f64,
    /// The same for the fold held on the plane (what the threshold compares).
    pub held_difference: f64,
    /// Reference length of the surface still pressed on the plane: the closed crease.
    pub closed_length: f64,
    /// Its deformed length.
    pub contact_length: f64,
    /// Whether no node touches the plane any more: the fold opened back to the flat state.
    pub reopened: bool,
    /// Surface nodes the plane presses.
    pub pressed_nodes: usize,
    /// Pressed nodes whose elastic force, computed apart from the contact, pulls them off the
    /// plane (an equilibrium crease has none).
    pub pulling_nodes: usize,
    /// Deformed depth of the closed crease below the flat surface (0 if it reopened).
    pub depth: f64,
}

/// `U_crease - U_flat` at the load's strain `strain` (the compression, or `1 - 1/g` under
/// growth) for a fold of reference length `fold_length` on a mesh of `spec` (one material,
/// shear modulus `mu`).
pub fn crease_energy(materials: &Bilayer, spec: MeshSpec, strain: f64, fold_length: f64) -> Result<CreaseEnergy> {
    fold(materials, spec, strain, fold_length)?.energy()
}

/// The fold of [`crease_energy`], released ([`ReleasedCrease`]).
pub fn released_crease(materials: &Bilayer, spec: MeshSpec, strain: f64, fold_length: f64) -> Result<ReleasedCrease> {
    fold(materials, spec, strain, fold_length)?.release()
}

/// Both: the fold held ([`crease_energy`]), then released ([`released_crease`]).
pub fn held_and_released(
    materials: &Bilayer,
    spec: MeshSpec,
    strain: f64,
    fold_length: f64,
) -> Result<(CreaseEnergy, ReleasedCrease)> {
    let folded = fold(materials, spec, strain, fold_length)?;
    let held = folded.energy()?;
    Ok((held, folded.release()?))
}

/// The folded state and what made it: the system, the model's conditions, the contact, and
/// the folded nodes held on the plane by `held`.
struct Folded {
    newton: Newton,
    system: System,
    model: Dirichlet,
    contact: Contact,
    folded: Vec<usize>,
    u: Vec<f64>,
    held: Dirichlet,
    report: NewtonReport,
    flat_energy: f64,
    mu: f64,
    strain: f64,
    fold_length: f64,
    steps: usize,
}

/// Folds the surface `0 < X <= fold_length` onto the plane at `strain`, in ramp steps.
fn fold(materials: &Bilayer, spec: MeshSpec, strain: f64, fold_length: f64) -> Result<Folded> {
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
    let (mut t, mut step, mut steps) = (0.0f64, 0.125f64, 0);
    let mut solved = None;
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
            &fold_policy(),
        ) {
            Ok(report) => {
                (t, steps) = (next, steps + 1);
                if report.iterations <= 8 {
                    step = (2.0 * step).min(0.25);
                }
                solved = Some((report, bc));
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
    let (report, held) = solved.expect("at least one step");
    Ok(Folded {
        newton,
        system,
        model,
        contact,
        folded,
        u,
        held,
        report,
        flat_energy,
        mu,
        strain,
        fold_length,
        steps,
    })
}

/// Newton's policy of the fold's steps and of the release.
fn fold_policy() -> NewtonPolicy {
    NewtonPolicy {
        max_iterations: 25,
        inertia_at_solution: false,
        ..NewtonPolicy::default()
    }
}

impl Folded {
    /// The energies of the fold held on the plane, and its shape.
    fn energy(&self) -> Result<CreaseEnergy> {
        let reactions: Vec<f64> = self
            .folded
            .iter()
            .map(|&n| {
                self.report.reactions[self
                    .held
                    .dofs()
                    .binary_search(&self.system.mesh().dofs().dof(n, X))
                    .expect("folded unknowns are prescribed")]
            })
            .collect();
        let mesh = self.system.mesh();
        let u = &self.u;
        let surface = mesh.top();
        let profile = surface
            .iter()
            .map(|&n| {
                (
                    mesh.coordinates()[n][0] + u[mesh.dofs().dof(n, X)],
                    mesh.coordinates()[n][1] + u[mesh.dofs().dof(n, Y)],
                )
            })
            .collect();
        let depth = surface_depth(mesh, u, &self.folded);
        let crease_energy = self.report.energy;
        let ellipticity = ellipticity_margins(&self.system, u)?;
        let (flat_energy, a) = (self.flat_energy, self.fold_length);
        Ok(CreaseEnergy {
            strain: self.strain,
            fold_length: a,
            flat_energy,
            crease_energy,
            difference: crease_energy - flat_energy,
            scaled_difference: (crease_energy - flat_energy) / (self.mu * a * a),
            depth,
            tensile_nodes: reactions.iter().filter(|&&r| r < 0.0).count(),
            min_jacobian: self.report.min_jacobian,
            steps: self.steps,
            ellipticity,
            surface: profile,
        })
    }
}

impl Folded {
    /// Frees the folded nodes and minimises the energy, contact with the plane as an inequality.
    fn release(mut self) -> Result<ReleasedCrease> {
        let held_difference = self.report.energy - self.flat_energy;
        minimise(
            &mut self.newton,
            (&mut self.system, &mut self.u, &self.model),
            Some(&mut self.contact),
            &NoAddedEnergy,
            &fold_policy(),
        )
        .map_err(|e| {
            Error::Solver(format!(
                "releasing the fold of a = {} at eps = {}: {e}",
                self.fold_length, self.strain
            ))
        })?;
        let u = &self.u;
        let state = self.contact.state(u);
        let pressed: Vec<usize> = self
            .contact
            .surface()
            .nodes
            .iter()
            .zip(&state.pressure)
            .filter(|(_, &p)| p > 0.0)
            .map(|(&n, _)| n)
            .collect();
        // The elastic force on each pressed node: the reaction of the strain energy alone with
        // the node held where it is.
        let mut pairs: Vec<(usize, f64)> = self
            .model
            .dofs()
            .iter()
            .copied()
            .zip(self.model.values().iter().copied())
            .collect();
        let x_of = |n: usize| self.system.mesh().dofs().dof(n, X);
        pairs.extend(pressed.iter().map(|&n| (x_of(n), u[x_of(n)])));
        let holding = Dirichlet::new(pairs)?;
        let elastic = self.system.assemble(u, &holding, None, false)?;
        let pulling = pressed
            .iter()
            .filter(|&&n| {
                elastic.reactions[holding
                    .dofs()
                    .binary_search(&self.system.mesh().dofs().dof(n, X))
                    .expect("held")]
                    < 0.0
            })
            .count();
        let energy = self.system.assemble(u, &self.model, None, false)?.energy;
        let mesh = self.system.mesh();
        Ok(ReleasedCrease {
            strain: self.strain,
            fold_length: self.fold_length,
            difference: energy - self.flat_energy,
            held_difference,
            closed_length: pressed.iter().map(|&n| mesh.coordinates()[n][0]).fold(0.0, f64::max),
            contact_length: state.contact_length,
            reopened: pressed.is_empty(),
            pressed_nodes: pressed.len(),
            pulling_nodes: pulling,
            depth: surface_depth(mesh, u, &pressed),
        })
    }
}

/// Depth of the crease: the flat surface's height (at the far end) above the lowest of `nodes`.
fn surface_depth(mesh: &Mesh, u: &[f64], nodes: &[usize]) -> f64 {
    let y = |n: usize| mesh.coordinates()[n][1] + u[mesh.dofs().dof(n, Y)];
    let far = *mesh.top().last().expect("a surface");
    match nodes.is_empty() {
        true => 0.0,
        false => nodes.iter().map(|&n| y(far) - y(n)).fold(f64::NEG_INFINITY, f64::max),
    }
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
        (system.mesh().dofs().dof(n, X), (1.0 - t) * lambda1 * x - x)
    }));
    Dirichlet::new(pairs)
}
