//! Nonlinear plane-strain finite elements of the bilayer: Q2 elements ([`element`]), prescribed
//! displacements ([`boundary`]), assembly on the free unknowns ([`assembly`]) with energies
//! added to the elastic one ([`added`]) such as surface contact ([`contact`]), a sparse
//! `L D L^T` solver with inertia ([`linear_solver`]), Newton's method ([`newton`]) inside the
//! outer loops of multipliers and contact ([`equilibrium`]) and element-centre output fields
//! ([`fields`]).

pub mod added;
pub mod assembly;
pub mod boundary;
pub mod contact;
pub mod element;
pub mod element_kind;
pub mod ellipticity;
pub mod equilibrium;
pub mod fields;
pub mod inertia;
pub mod lanczos;
pub mod linear_solver;
pub mod load_path;
pub mod memory;
pub mod mixed;
pub mod newton;

pub use assembly::{Assembled, System, Tangent};
pub use boundary::{dof, model_conditions, Dirichlet};
pub use element_kind::{ElementKind, LOCKING_RATIO};
pub use linear_solver::{Factorisation, SparseLdlt};
pub use load_path::LoadPath;
pub use newton::{Newton, NewtonError, NewtonPolicy, NewtonReport, Precision, Reuse, Stall, Timings, Updates};
