//! What the path to a crease adds to plain equilibrium at every step of displacement control:
//! contact of the top surface with the symmetry planes and with itself
//! ([`crate::fem::contact`]), and viscous stabilisation ([`super::stabilisation`]); with what
//! each accepted step reports about them.

use super::stabilisation::{Stabilisation, StabilisationSettings};
use crate::error::Result;
use crate::fem::added::{AddedEnergy, NoAddedEnergy, Sum};
use crate::fem::contact::{solve_with_contact, Contact, ContactSettings, Plane};
use crate::fem::inertia::BackgroundInertia;
use crate::fem::{Dirichlet, Newton, NewtonReport, System};
use crate::material::Bilayer;
use serde::Serialize;

/// Contact and stabilisation of one continuation (either may be absent).
#[derive(Debug)]
pub struct Augmentation {
    pub contact: Option<Contact>,
    pub stabilisation: Option<Stabilisation>,
    /// The inertia of states whose tangent Newton did not factorise.
    inertia: BackgroundInertia,
}

/// Largest Newton correction `|u - u_predicted|`, relative to the step `|u - u_0|`, for which the
/// inertia of the predicted state's tangent is taken for the solution's: an eigenvalue can then
/// have changed sign in between only within about this fraction of a step of a singular
/// tangent. Measured: a predictor a tenth of a step off near a limit point (mu_l = 3) had a
/// count one lower than its solution's.
const PREDICTOR_CLOSENESS: f64 = 1e-2;

/// Largest absolute difference of two states.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// Index of the right symmetry plane among the contact planes.
const RIGHT_PLANE: usize = 1;

/// What an accepted step reports about contact and stabilisation.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct AugmentedRecord {
    pub in_contact: bool,
    /// Deformed length of the closed surface (see [`crate::fem::contact::ContactState`]).
    pub contact_length: f64,
    pub contact_zones: usize,
    /// Largest penetration of the accepted state.
    pub penetration: f64,
    /// Newton solves (multiplier updates) of the accepted state.
    pub augmentations: usize,
    /// Dissipated over strain energy, accumulated along the path.
    pub stabilisation_energy_fraction: f64,
    pub dissipated_energy: f64,
    pub eta: f64,
    /// Wall time the main thread spent on the inertia of the accepted state: none where it is
    /// read from the factorisation at the predictor, otherwise the assembly of the undamped
    /// tangent (its factorisation runs in the background, see `inertia_pending`).
    pub inertia_seconds: f64,
    /// Whether the inertia is being counted in the background: the count is then
    /// [`Augmentation::next_inertia`]'s, in the order of the states.
    #[serde(skip)]
    pub inertia_pending: bool,
    /// Nominal contact pressure `(node, p)` at every top-surface node.
    #[serde(skip)]
    pub pressure: Vec<(usize, f64)>,
}

impl Augmentation {
    /// Contact with both symmetry planes and self-contact if `contact` (settings for the mesh
    /// and the stiffer tissue), and stabilisation if `stabilisation` is given.
    pub fn new(
        system: &System,
        materials: &Bilayer,
        contact: bool,
        stabilisation: Option<StabilisationSettings>,
    ) -> Result<Self> {
        let mesh = system.mesh();
        let mu = materials.layer.mu.max(materials.substrate.matrix.mu);
        let planes = vec![Plane::left(0.0), Plane::right(mesh.spec().length)];
        Ok(Augmentation {
            contact: contact.then(|| Contact::new(mesh, planes, ContactSettings::for_mesh(mesh, mu))),
            stabilisation: stabilisation
                .map(|s| Stabilisation::new(system, materials, s))
                .transpose()?,
            inertia: BackgroundInertia::default(),
        })
    }

    /// The inertia of the oldest accepted state whose count was pending (waiting for it).
    pub fn next_inertia(&mut self) -> Option<usize> {
        self.inertia.next_count()
    }

    /// Frees the background inertia's factor (after the path, before post-processing).
    pub fn release_factorisation(&mut self) {
        self.inertia.release();
    }

    /// Equilibrium at `d` (prescribed by `bc`) from the predictor `u`, stepping from the
    /// converged `(d0, u0)` with the step control at `control_step` (which decides whether the
    /// step is damped, see [`Stabilisation::damper`]); redone with a smaller `eta` while the
    /// step would exceed the dissipation budget. On failure `u` is the predictor again and
    /// nothing is booked. The inertia, when Newton's settings ask for it, is that of the
    /// undamped tangent: read from Newton's factorisation at the predictor where that tangent is
    /// the same energy's (an undamped step, no contact force at the predictor or at the
    /// solution, one Newton solve; see [`crate::fem::newton`]) and the predictor was within 1e-2
    /// (`PREDICTOR_CLOSENESS`) of a step of the solution, otherwise from one more factorisation
    /// at the solution, counted on a second thread while the next step goes on (the record is
    /// then `inertia_pending`, and [`Augmentation::next_inertia`] gives the count).
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        newton: &mut Newton,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        (d0, u0): (f64, &[f64]),
        (d, control_step): (f64, f64),
    ) -> Result<(NewtonReport, AugmentedRecord)> {
        let settings = newton.settings;
        newton.settings.inertia_at_solution = false;
        let result = self.solve_within_budget(
            newton,
            system,
            u,
            bc,
            (d0, u0),
            (d, control_step),
            settings.inertia_at_solution,
        );
        newton.settings = settings;
        result
    }

    #[allow(clippy::too_many_arguments)]
    fn solve_within_budget(
        &mut self,
        newton: &mut Newton,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        (d0, u0): (f64, &[f64]),
        (d, control_step): (f64, f64),
        wants_inertia: bool,
    ) -> Result<(NewtonReport, AugmentedRecord)> {
        let predictor = u.to_vec();
        let saved_contact = self.contact.clone();
        let length = system.mesh().spec().length;
        loop {
            let damper = match &self.stabilisation {
                Some(s) => Some(s.damper(system, (d0, u0), d, control_step)?),
                None => None,
            };
            let other: &dyn AddedEnergy = match &damper {
                Some(damper) => damper,
                None => &NoAddedEnergy,
            };
            let damped = damper.as_ref().is_some_and(|damper| damper.damps());
            let unloaded =
                |contact: &Option<Contact>, u: &[f64]| contact.as_ref().is_none_or(|c| c.loaded_pairs(u).is_empty());
            let plain = !damped && unloaded(&self.contact, u);
            newton.settings.factorise_start = plain;
            // Across a damped snap or with contact forces the residual may stagnate for a few
            // steps before it converges: there only the slower stall rule cuts the step.
            if !plain {
                newton.settings.diverging_steps = usize::MAX;
            }
            let (mut report, augmentations, loaded_at_start) = match &mut self.contact {
                Some(contact) => {
                    contact.set_plane(RIGHT_PLANE, Plane::right(length * (1.0 - d)));
                    // A new structure means a new analysis and pattern, which are large: the
                    // count in the background finishes first, freeing its factor.
                    let mut probe = contact.clone();
                    probe.search(u);
                    if !system.keeps_structure(bc, probe.groups()) {
                        self.inertia.release();
                    }
                    let solved = solve_with_contact(newton, system, u, bc, contact, other)?;
                    let mut report = solved.report;
                    report.iterations = solved.iterations;
                    report.tangent_steps = solved.tangent_steps;
                    (report, solved.augmentations, solved.loaded_at_start)
                }
                None => (newton.solve_with(system, u, bc, other)?, 1, false),
            };
            let dissipation = damper.as_ref().map_or(0.0, |damper| damper.dissipation(u));
            let mut record = AugmentedRecord {
                augmentations,
                ..AugmentedRecord::default()
            };
            let close = distance(u, &predictor) <= PREDICTOR_CLOSENESS * distance(u, u0);
            let from_start = report
                .start_negative_pivots
                .filter(|_| close && !damped && augmentations == 1 && !loaded_at_start && unloaded(&self.contact, u));
            let started = std::time::Instant::now();
            let undamped_tangent = match (wants_inertia, from_start) {
                (true, Some(count)) => {
                    report.negative_pivots = Some(count);
                    None
                }
                (true, None) => {
                    // The damper's groups with zero damping keep the pattern (and its analysis).
                    let undamped = damper.map(|damper| damper.undamped());
                    let contact: &dyn AddedEnergy = self.contact.as_ref().map_or(&NoAddedEnergy, |c| c);
                    let damping: &dyn AddedEnergy = undamped.as_ref().map_or(&NoAddedEnergy, |d| d);
                    Some(system.assemble_for_stability(u, bc, &Sum::new(vec![contact, damping]))?)
                }
                (false, _) => None,
            };
            if let Some(s) = &mut self.stabilisation {
                let Some(fraction) = s.book(dissipation, report.energy)? else {
                    u.copy_from_slice(&predictor);
                    self.contact.clone_from(&saved_contact);
                    continue;
                };
                record.stabilisation_energy_fraction = fraction;
                record.dissipated_energy = s.dissipated();
                record.eta = s.eta();
            }
            if let Some(tangent) = undamped_tangent {
                // Counted while the next step goes on, which starts from a new factorisation
                // (as it did when this count replaced Newton's held one: that of an unstable
                // state is not reused).
                self.inertia
                    .start(tangent, |structure| newton.sibling_solver(structure));
                newton.forget_factorisation();
                record.inertia_pending = true;
                record.inertia_seconds = started.elapsed().as_secs_f64();
            }
            if let Some(contact) = &self.contact {
                let state = contact.state(u);
                record.in_contact = state.in_contact;
                record.contact_length = state.contact_length;
                record.contact_zones = state.zones;
                record.penetration = state.penetration;
                record.pressure = contact.surface().nodes.iter().copied().zip(state.pressure).collect();
            }
            return Ok((report, record));
        }
    }
}
