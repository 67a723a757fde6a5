//! Nonlinear finite elements of the bilayer: the element interface and its elements
//! ([`element`]), prescribed
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
pub mod ellipticity;
pub mod equilibrium;
pub mod fields;
pub mod inertia;
pub mod lanczos;
pub mod linear_solver;
pub mod memory;
pub mod newton;

pub use assembly::{Assembled, PatchSystem, StoredEntries, System, Tangent};
pub use boundary::Dirichlet;
pub use element::{ElementKind, LOCKING_RATIO};
pub use linear_solver::{Factorisation, SparseLdlt};
pub use newton::{
    EnergyEquations, Equations, Newton, NewtonError, NewtonPolicy, NewtonReport, Precision, Reuse, Stall,
    SystemEquations, Timings, Updates,
};
