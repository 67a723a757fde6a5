//! Loading protocols of the finite-element model and what is read off them: the paper's three
//! stages ([`stages`]) with adaptive displacement control ([`continuation`]), the seeded
//! imperfection and admissible wavenumbers ([`imperfection`]), the top surface and its
//! amplitude ([`surface`]), onset estimates from `A(d)` ([`onset`]), and the exact bifurcation
//! of the discretised perfect system from the inertia of its tangent ([`bifurcation`]). Past the
//! onset, the path to a crease adds contact to every step ([`augmentation`]), crosses snaps by
//! minimising the energy ([`snap`]) or, as an option, by viscous stabilisation
//! ([`stabilisation`]), and tracks secondary bifurcations ([`secondary`]); a
//! crease seeded in a homogeneous half-space gives the creasing threshold ([`crease_seed`]).

pub mod augmentation;
pub mod basic_state;
pub mod bifurcation;
pub mod continuation;
pub mod crease_seed;
pub mod imperfection;
pub mod load_path;
pub mod measures;
pub mod onset;
pub mod patch;
mod predictor;
pub mod record;
pub mod secondary;
pub mod snap;
pub mod stabilisation;
pub mod stages;
pub mod surface;

pub use augmentation::{Augmentation, AugmentedRecord};
pub use bifurcation::{find_bifurcation, Bifurcation, BifurcationSettings};
pub use continuation::{
    ArcLength, CheckpointInterval, Continuation, ContinuationMethod, Cut, Event, PathFollowing, PathState, StepControl,
};
pub use imperfection::{mode_number, wavenumber_of_waves, Imperfection};
pub use load_path::{model_conditions, LoadPath, Loading};
pub use measures::{bilayer_measures, Measure};
pub use onset::OnsetEstimates;
pub use record::StepRecord;
pub use snap::{SnapCrossing, SnapRecord, SnapSettings};
pub use stabilisation::{Stabilisation, StabilisationSettings};
pub use stages::{Outcome, Protocol, STAGE_ONE_COMPRESSION};
pub use surface::{amplitude, surface_profile};
