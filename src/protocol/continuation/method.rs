//! The continuation methods ([`ContinuationMethod`]) and what the stages and studies ask of
//! any of them ([`PathFollowing`]).

use super::{Continuation, Event, Followed};
use crate::error::Result;
use crate::fem::SparseLdlt;
use serde::{Deserialize, Serialize};

/// How a path in `d` is followed: the continuation method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum ContinuationMethod {
    /// Displacement control in `d` ([`Continuation`]): `d` rises step by step; a limit point in
    /// `d` is crossed by the path's way across a snap.
    #[default]
    #[value(help = "displacement control: d rises step by step, a snap is crossed")]
    Displacement,
    /// Pseudo-arc length ([`super::ArcLength`]): `d` is an unknown, and the path goes round a limit
    /// point in `d`, along the unstable branch (no contact, no stabilisation).
    #[value(help = "pseudo-arc length: round the limit points in d, along unstable branches")]
    ArcLength,
}

/// A continuation method following the equilibrium path of a system `S` in `d`, for the
/// stages that drive it and the studies that read its end.
pub trait PathFollowing<S: Followed> {
    /// Follows the path until `d` reaches `target`, reporting every accepted state and every
    /// cut to `observer`; an [`crate::Error::Solver`] says where it stopped short.
    fn advance_to(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()>;
    /// The current state's load.
    fn d(&self) -> f64;
    /// The current converged unknowns.
    fn displacement(&self) -> &[f64];
    /// The system, at the current state's load.
    fn system(&self) -> &S;
    /// A solver sharing the analysis of the path's tangents, and the structure id it is for.
    fn analysed_solver(&self) -> Option<(usize, SparseLdlt)>;
    /// Frees the factorisations held between steps.
    fn release_factorisation(&mut self);
    /// The system and the current converged unknowns.
    fn into_state(self: Box<Self>) -> (S, Vec<f64>);
}

impl<S: Followed> PathFollowing<S> for Continuation<S> {
    fn advance_to(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        Continuation::advance_to(self, target, observer)
    }

    fn d(&self) -> f64 {
        Continuation::d(self)
    }

    fn displacement(&self) -> &[f64] {
        Continuation::displacement(self)
    }

    fn system(&self) -> &S {
        Continuation::system(self)
    }

    fn analysed_solver(&self) -> Option<(usize, SparseLdlt)> {
        Continuation::analysed_solver(self)
    }

    fn release_factorisation(&mut self) {
        Continuation::release_factorisation(self)
    }

    fn into_state(self: Box<Self>) -> (S, Vec<f64>) {
        Continuation::into_state(*self)
    }
}
