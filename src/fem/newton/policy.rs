//! How one Newton solve iterates: tolerances, limits, when to give up, and which factorisations
//! it may reuse. A value passed per call; nothing a caller sets is seen by the next one.

/// Tolerances, limits and reuse rules of one Newton solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonPolicy {
    /// Largest number of Newton steps with a newly factorised tangent.
    pub max_iterations: usize,
    /// `rtol`: residual relative to the internal-force norm (keep it above the residual's round-off).
    pub residual_tolerance: f64,
    /// `atol`: absolute residual floor, for nearly unloaded states.
    pub absolute_tolerance: f64,
    /// `utol`: update relative to `1 + |u|_inf` below which the iterate no longer changes.
    pub update_tolerance: f64,
    /// Largest number of step halvings in one line search.
    pub max_backtracks: usize,
    /// Armijo constant `c` of the sufficient decrease `|r(u + alpha du)| <= (1 - c alpha) |r(u)|`.
    pub sufficient_decrease: f64,
    /// Relative residual of a linear solve above which `L B L^T` replaces `L D L^T`.
    pub solve_tolerance: f64,
    /// Whether the inertia of the tangent at the solution is counted
    /// ([`crate::fem::equilibrium`] counts it, once the outer loops have converged).
    pub inertia_at_solution: bool,
    /// Whether to factorise the tangent at the starting iterate (the predictor) and start with it.
    pub factorise_start: bool,
    /// Which held factorisations the iteration keeps using while they contract the residual.
    pub reuse: Reuse,
    /// Largest ratio `|r_(n+1)| / |r_n|` of a step with a reused factorisation for the next step to
    /// reuse it too; above it the tangent is refactorised.
    pub contraction: f64,
    /// Precision of the solves with a reused factorisation (the next residual checks the step).
    pub reused_precision: Precision,
    /// Give up when the residual stalls ([`Stall`]); `None`: never on that ground.
    pub stall: Option<Stall>,
    /// Give up when, after this many tangent steps, `|r|` has not fallen tenfold from its
    /// start, or after the first it has not halved: an iteration from a usable predictor has by
    /// then, and one that has not is stagnating on a fold (measured on the fine benchmark:
    /// every such attempt failed after three to five more steps, and the first step of the
    /// undamped ones that converged there cut `|r|` 20-90-fold). `None`: never on that ground.
    pub diverging_after: Option<usize>,
    /// For a minimisation ([`super::Newton::minimise`]): the largest nodal move from its start,
    /// beyond which it stops unfinished ([`super::NewtonReport::unfinished`]) so that the outer
    /// loops refresh what depends on the configuration (the contact pairs) before it goes on.
    /// `None`: it runs to the minimum.
    pub max_pass_move: Option<f64>,
    /// For a minimisation: the largest number of its steps in one pass, beyond which it fails
    /// as not converged.
    pub max_minimisation_steps: usize,
    /// For a minimisation: the shift `sigma` of its first step. A pass after a contact update
    /// starts from the shift the pass before ended with ([`super::NewtonReport::final_shift`]):
    /// from zero, an indefinite tangent costs a factorisation per sixteenfold raise of the
    /// shift before the first step is taken.
    pub initial_shift: f64,
    /// For a minimisation: the largest nodal move from the start of the solve, over all its
    /// passes, beyond which it fails; each pass stops (unfinished) within it. A correction of a
    /// step whose minimum lies farther than this is no correction, and is better given up at
    /// once than minimised to the end. `None`: no limit.
    pub max_move: Option<f64>,
}

/// Which factorisations a solve keeps as its iteration matrix (modified Newton).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reuse {
    /// Every step factorises the consistent tangent.
    Never,
    /// A positive definite factorisation is kept, whichever solve of the same pattern made it.
    Definite,
    /// Also an indefinite one made in this very solve (for a step on a smooth stretch of an
    /// unstable path; not near a fold, where every step needs a fresh tangent).
    AlsoIndefinite,
}

/// Precision of a solve with a reused factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// The factor rounded to single precision: half the memory traffic.
    Single,
    /// Full precision, where the tangent's conditioning leaves single precision too few digits
    /// (the incompressibility penalty of the mixed element's multipliers).
    Double,
}

/// The stall rule: give up (as not converged) when, after `steps` tangent steps, `|r|` is still
/// above both `reduction` times its start and the geometric mean of its start and the
/// tolerance. A converging iteration from a good predictor is far below by then, and a load
/// step that stalls is cheaper to cut than to grind through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stall {
    pub steps: usize,
    pub reduction: f64,
}

impl NewtonPolicy {
    /// The residual tolerance `s (rtol |f| + atol)` of a state whose internal-force norm is
    /// `force_norm`, with `s` the factor on a raised incompressibility penalty (1 otherwise).
    pub fn tolerance(&self, force_norm: f64, penalty_scale: f64) -> f64 {
        (self.residual_tolerance * force_norm + self.absolute_tolerance) * penalty_scale
    }
}

impl Default for NewtonPolicy {
    /// `rtol = 1e-10`, `atol = 1e-12`, `utol = 1e-13`, 30 steps, 12 halvings, full Newton, the
    /// inertia at the solution; a minimisation of up to 400 steps per pass.
    fn default() -> Self {
        NewtonPolicy {
            max_iterations: 30,
            residual_tolerance: 1e-10,
            absolute_tolerance: 1e-12,
            update_tolerance: 1e-13,
            max_backtracks: 12,
            sufficient_decrease: 1e-4,
            solve_tolerance: 1e-8,
            inertia_at_solution: true,
            factorise_start: false,
            reuse: Reuse::Never,
            contraction: 0.25,
            reused_precision: Precision::Single,
            stall: None,
            diverging_after: None,
            max_pass_move: None,
            max_minimisation_steps: 400,
            initial_shift: 0.0,
            max_move: None,
        }
    }
}
