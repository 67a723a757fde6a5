//! What the path to a crease adds to plain equilibrium at every step of displacement control:
//! contact of the top surface with the symmetry planes and with itself
//! ([`crate::fem::contact`]), and viscous stabilisation ([`super::stabilisation`]); with what
//! each accepted step reports about them.

use super::stabilisation::{Stabilisation, StabilisationMemory, StabilisationSettings};
use crate::error::{Error, Result};
use crate::fem::added::{AddedEnergy, NoAddedEnergy, Sum};
use crate::fem::contact::{Contact, ContactMemory, ContactSettings, Plane};
use crate::fem::equilibrium::{minimise, solve_with, solve_with_contact};
use crate::fem::inertia::BackgroundInertia;
use crate::fem::{Assembled, Dirichlet, Newton, NewtonPolicy, NewtonReport, System, Updates};
use crate::material::Bilayer;
use crate::protocol::Loading;
use serde::{Deserialize, Serialize};

/// Contact and stabilisation of one continuation (either may be absent).
#[derive(Debug)]
pub struct Augmentation {
    pub contact: Option<Contact>,
    pub stabilisation: Option<Stabilisation>,
    /// The inertia of states whose tangent Newton did not factorise.
    inertia: BackgroundInertia,
    /// The negative pivots of the last accepted state whose count is known: a predictor's count
    /// is taken for a solution's only where it is the same.
    accepted_negative_pivots: Option<usize>,
}

/// Largest Newton correction `|u - u_predicted|`, relative to the step `|u - u_0|`, for which the
/// inertia of the predicted state's tangent is taken for the solution's, when it is the last
/// accepted state's: an eigenvalue can then have changed sign in between only within about
/// this fraction of a step of a singular tangent. Measured: a predictor a tenth of a step off
/// near a limit point (mu_l = 3) had a count one lower than its solution's; one within this
/// fraction, just past a stiff layer's onset where several modes are nearly critical, had five
/// negative pivots where its solution had none (a change, now counted at the solution).
const PREDICTOR_CLOSENESS: f64 = 1e-2;

/// Largest absolute difference of two states.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// Index of the right symmetry plane among the contact planes.
const RIGHT_PLANE: usize = 1;

/// What a resumed path needs of its augmentation: the contact's pairs and multipliers, the
/// stabilisation's `eta` and dissipated energy.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AugmentationMemory {
    pub contact: Option<ContactMemory>,
    pub stabilisation: Option<StabilisationMemory>,
}

/// What an accepted step reports about contact and stabilisation.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
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
    pub inertia_pending: bool,
    /// Nominal contact pressure `(node, p)` at every top-surface node.
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
        let mu = materials
            .layer
            .energy
            .shear_modulus()
            .max(materials.substrate.energy.matrix.shear_modulus());
        let planes = vec![Plane::left(0.0), Plane::right(mesh.spec().length)];
        Ok(Augmentation {
            contact: contact.then(|| Contact::new(mesh, planes, ContactSettings::for_mesh(mesh, mu))),
            stabilisation: stabilisation
                .map(|s| Stabilisation::new(system, materials, s))
                .transpose()?,
            inertia: BackgroundInertia::default(),
            accepted_negative_pivots: None,
        })
    }

    /// What a resumed path needs of it.
    pub fn memory(&self) -> AugmentationMemory {
        AugmentationMemory {
            contact: self.contact.as_ref().map(Contact::memory),
            stabilisation: self.stabilisation.as_ref().map(Stabilisation::memory),
        }
    }

    /// Back to a state it had ([`Augmentation::memory`]) on the same mesh and settings.
    pub fn recall(&mut self, memory: AugmentationMemory) -> Result<()> {
        match (&mut self.contact, memory.contact) {
            (Some(contact), Some(memory)) => contact.recall(memory)?,
            (None, None) => {}
            _ => return Err(Error::invalid("checkpoint", "its contact", "the contact this run has")),
        }
        match (&mut self.stabilisation, memory.stabilisation) {
            (Some(stabilisation), Some(memory)) => stabilisation.recall(memory),
            (None, None) => {}
            _ => {
                return Err(Error::invalid(
                    "checkpoint",
                    "its stabilisation",
                    "the stabilisation this run has",
                ))
            }
        }
        Ok(())
    }

    /// Notes the negative pivots of the state the path accepted (`None` where not yet known:
    /// the last known count is kept, and replaced once this one is in).
    pub fn note_accepted(&mut self, negative_pivots: Option<usize>) {
        if negative_pivots.is_some() {
            self.accepted_negative_pivots = negative_pivots;
        }
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
    /// step is damped, see [`Stabilisation::damper`]) and Newton's `policy`; redone with a
    /// smaller `eta` while the step would exceed the dissipation budget. On failure `u` is the
    /// predictor again and nothing is booked. The inertia, when the policy asks for it, is that
    /// of the undamped tangent (`Augmentation::count_inertia`).
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        system: &mut System,
        u: &mut [f64],
        bc: &Dirichlet,
        (d0, u0): (f64, &[f64]),
        (d, control_step): (f64, f64),
    ) -> Result<(NewtonReport, AugmentedRecord)> {
        let predictor = u.to_vec();
        let saved_contact = self.contact.clone();
        loop {
            let damper = match &self.stabilisation {
                Some(s) => Some(s.damper(system, (d0, u0), d, control_step)?),
                None => None,
            };
            let damped = damper.as_ref().is_some_and(|damper| damper.damps());
            let plain = !damped && unloaded(&self.contact, u);
            let other: &dyn AddedEnergy = damper.as_ref().map_or(&NoAddedEnergy, |damper| damper);
            let step_policy = policy_of_step(policy, plain);
            let loaded_at_start = prepare_contact((&mut self.contact, &mut self.inertia), system, u, (bc, d));
            let solved = match &mut self.contact {
                Some(contact) => solve_with_contact(newton, system, u, bc, contact, other, &step_policy),
                None => solve_with(newton, system, u, bc, other, &step_policy),
            };
            // An undamped step the damper may carry failed: the second such failure before the
            // steps grew back is a snap, carried from here by the damper (this step again,
            // damped); the first only cuts the step.
            let may_carry = !damped && self.stabilisation.as_ref().is_some_and(|s| s.engages(control_step));
            let mut report = match solved {
                Err(e) if may_carry => {
                    if !self.stabilisation.as_mut().is_some_and(|s| s.note_undamped_failure()) {
                        return Err(e.into());
                    }
                    u.copy_from_slice(&predictor);
                    self.contact.clone_from(&saved_contact);
                    continue;
                }
                solved => solved?,
            };
            let dissipation = damper.as_ref().map_or(0.0, |damper| damper.dissipation(u));
            // The predictor's inertia is the solution's for an undamped step without contact
            // forces, solved in one pass from close by.
            let close = distance(u, &predictor) <= PREDICTOR_CLOSENESS * distance(u, u0);
            let from_start = report.start_negative_pivots.filter(|&count| {
                close
                    && Some(count) == self.accepted_negative_pivots
                    && !damped
                    && report.updates == Updates::default()
                    && !loaded_at_start
                    && unloaded(&self.contact, u)
            });
            let started = std::time::Instant::now();
            let undamped_tangent = match (policy.inertia_at_solution, from_start) {
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
            let mut record = AugmentedRecord {
                augmentations: report.updates.contact + 1,
                ..AugmentedRecord::default()
            };
            if let Some(s) = &mut self.stabilisation {
                let Some(fraction) = s.book(dissipation, report.energy)? else {
                    u.copy_from_slice(&predictor);
                    self.contact.clone_from(&saved_contact);
                    continue;
                };
                s.release(control_step);
                record.stabilisation_energy_fraction = fraction;
                record.dissipated_energy = s.dissipated();
                record.eta = s.eta();
            }
            if let Some(tangent) = undamped_tangent {
                self.count_inertia(newton, tangent, &mut record, started);
            }
            if let Some(contact) = &self.contact {
                record.record_contact(contact, u);
            }
            return Ok((report, record));
        }
    }

    /// Starts counting the inertia of the accepted state's undamped `tangent` on the second
    /// thread, while the next step goes on; that step starts from a new factorisation (as it
    /// did when this count replaced Newton's held one: that of an unstable state is not reused).
    fn count_inertia(
        &mut self,
        newton: &mut Newton,
        tangent: Assembled,
        record: &mut AugmentedRecord,
        started: std::time::Instant,
    ) {
        self.inertia
            .start(tangent, |structure| newton.sibling_solver(structure));
        newton.forget_factorisation();
        record.inertia_pending = true;
        record.inertia_seconds = started.elapsed().as_secs_f64();
    }
}

impl Augmentation {
    /// The stable equilibrium at `d` (prescribed by `bc`) reached by minimising the energy
    /// from `u` (the last equilibrium with the boundary moved to `d`; [`crate::protocol::snap`]),
    /// with contact, and its inertia. On failure `u` and the contact are as they were.
    pub fn minimise(
        &mut self,
        newton: &mut Newton,
        policy: &NewtonPolicy,
        system: &mut System,
        u: &mut [f64],
        (bc, d): (&Dirichlet, f64),
    ) -> Result<(NewtonReport, AugmentedRecord)> {
        let saved_plane = self.contact.clone();
        prepare_contact((&mut self.contact, &mut self.inertia), system, u, (bc, d));
        // Half the search distance per pass: no surface node passes unseen into a segment or
        // slides far beyond the one it was paired with.
        let policy = NewtonPolicy {
            inertia_at_solution: true,
            max_pass_move: self.contact.as_ref().map(|c| 0.5 * c.settings.search_distance),
            ..*policy
        };
        let report = match minimise(newton, (system, u, bc), self.contact.as_mut(), &NoAddedEnergy, &policy) {
            Ok(report) => report,
            Err(e) => {
                self.contact = saved_plane;
                return Err(e.into());
            }
        };
        let mut record = AugmentedRecord {
            augmentations: report.updates.contact + 1,
            ..AugmentedRecord::default()
        };
        if let Some(contact) = &self.contact {
            record.record_contact(contact, u);
        }
        Ok((report, record))
    }

    /// The total energy at `u` with `bc` prescribed: the strain energy plus the contact terms
    /// of the current pairs and multipliers.
    pub fn energy(&self, system: &mut System, u: &[f64], bc: &Dirichlet) -> Result<f64> {
        let contact: &dyn AddedEnergy = self.contact.as_ref().map_or(&NoAddedEnergy, |c| c);
        let assembled = system.assemble_with(u, bc, None, false, contact)?;
        Ok(assembled.energy + assembled.added_energy)
    }
}

/// Moves the right symmetry plane to `L (1 - d)` and, when the pairs at `u` change the
/// tangent's structure (a new analysis and pattern, which are large), lets the count in the
/// background finish first, freeing its factor. Returns whether a pair is loaded at `u` (then
/// the first tangent holds contact terms).
fn prepare_contact(
    (contact, inertia): (&mut Option<Contact>, &mut BackgroundInertia),
    system: &System,
    u: &[f64],
    (bc, d): (&Dirichlet, f64),
) -> bool {
    let Some(contact) = contact else {
        return false;
    };
    contact.set_plane(
        RIGHT_PLANE,
        Plane::right(system.load_path().right_plane(system.mesh(), d)),
    );
    let mut probe = contact.clone();
    probe.search(u);
    if !system.keeps_structure(bc, probe.groups()) {
        inertia.release();
    }
    !probe.loaded_pairs(u).is_empty()
}

/// Whether no contact pair carries force at `u`.
fn unloaded(contact: &Option<Contact>, u: &[f64]) -> bool {
    contact.as_ref().is_none_or(|c| c.loaded_pairs(u).is_empty())
}

/// Newton's `policy` for one step: a plain step (undamped, no contact forces) factorises its
/// predictor first, whose inertia may be the solution's; across a damped snap or with contact
/// forces the residual may stagnate for a few steps before it converges, so only the slower
/// stall rule cuts the step there. The inertia is the augmentation's to count, not Newton's.
fn policy_of_step(policy: &NewtonPolicy, plain: bool) -> NewtonPolicy {
    NewtonPolicy {
        inertia_at_solution: false,
        factorise_start: plain,
        diverging_after: if plain { policy.diverging_after } else { None },
        ..*policy
    }
}

impl AugmentedRecord {
    /// The contact of the accepted state `u`.
    fn record_contact(&mut self, contact: &Contact, u: &[f64]) {
        let state = contact.state(u);
        self.in_contact = state.in_contact;
        self.contact_length = state.contact_length;
        self.contact_zones = state.zones;
        self.penetration = state.penetration;
        self.pressure = contact.surface().nodes.iter().copied().zip(state.pressure).collect();
    }
}
