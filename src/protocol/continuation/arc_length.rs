//! Pseudo-arc-length continuation (Keller's, as Riks's and Crisfield's methods in structural
//! mechanics): the load `d` is an unknown with the displacements, so the path is followed
//! through limit points in `d`, where displacement control must jump (a snap) and this goes
//! round the fold, along the unstable branch, with the inertia of every state counted.
//!
//! A state is `x = (u_f, d)` (the free unknowns and the load; the prescribed unknowns follow
//! `d`). Lengths are measured by `|x|^2 = (w |u_f|^2 + d^2) / 2`, with `w = 1 / |du_f/dd|^2` of
//! the first state's tangent: along a homogeneous stretch of the path a step of length `h`
//! moves `d` by `h`, as a step of displacement control does. From the converged `x_0` with unit
//! tangent `t`, a step of length `h` predicts `x_0 + h t` and corrects it by Newton's method on
//!
//! ```text
//! r(u, d) = 0,        c(u, d) = <t, x - x_0> - h = 0,
//! ```
//!
//! the bordered system solved with the factorisation of `K_ff` alone (two solves per step,
//! `K a = -r` and `K b = -dr/dd`; then `dd = -(c + <t, (a, 0)>) / <t, (b, 1)>` and
//! `du_f = a + dd b`). `dr/dd` (the prescribed unknowns and the tissues move with `d`) is a
//! central difference in `d`. The tangent at a converged state is `(K^-1 (-dr/dd), 1)`,
//! normalised and turned to continue the last one; its factorisation gives the state's inertia,
//! whose count changes by one where the path passes a limit point in `d`.
//!
//! The step control is displacement control's ([`StepControl`], on `h`). The last step lands on
//! the target `d` by displacement control from the tangent's prediction there.

use super::{Event, Followed, PathFollowing};
use crate::error::{Error, Result};
use crate::fem::{Assembled, Dirichlet, Newton, NewtonPolicy, NewtonReport, SparseLdlt, Timings, Updates};
use crate::protocol::measures::{measure_all, Measure};
use crate::protocol::record::StepRecord;
use crate::protocol::{Cut, StepControl};
use std::time::Instant;

/// Step in `d` of the central difference `dr/dd` (the residual is smooth in `d`: its error,
/// of order `1e-12` relative, only slows Newton's convergence, not where it converges).
const LOAD_DIFFERENCE: f64 = 1e-6;

/// Most states one advance records: a path that goes round a closed loop stops here.
const MAX_STATES: usize = 20_000;

/// A unit tangent of the path: along the free unknowns and along `d`.
#[derive(Clone, Debug)]
struct PathTangent {
    free: Vec<f64>,
    load: f64,
}

/// The arc-length continuation of a system `S` from a converged state.
pub struct ArcLength<S: Followed> {
    system: S,
    newton: Newton,
    policy: NewtonPolicy,
    control: StepControl,
    /// The next step's length `h`.
    step: f64,
    d: f64,
    u: Vec<f64>,
    /// The free unknowns (those not prescribed), increasing.
    free: Vec<usize>,
    /// The weight `w` of the free unknowns in the length of a step.
    weight: f64,
    /// The unit tangent at the current state (once computed).
    tangent: Option<PathTangent>,
    measures: Vec<Box<dyn Measure<S>>>,
}

impl<S: Followed> ArcLength<S> {
    /// Starts at the converged state `u` at `d`, solving with `newton` by `policy` (its
    /// tolerances and `max_iterations`); `control` sets the steps `h`.
    pub fn new(
        (mut system, newton, policy): (S, Newton, NewtonPolicy),
        control: StepControl,
        d: f64,
        u: Vec<f64>,
    ) -> Result<Self> {
        control.validate()?;
        let bc = system.load_to(d)?;
        let free = free_unknowns(&bc, u.len());
        Ok(ArcLength {
            system,
            newton,
            policy,
            step: control.initial.min(control.max),
            control,
            d,
            u,
            free,
            weight: 1.0,
            tangent: None,
            measures: Vec::new(),
        })
    }

    /// The same continuation recording `measures` of every accepted state.
    pub fn with_measures(mut self, measures: Vec<Box<dyn Measure<S>>>) -> Self {
        self.measures = measures;
        self
    }

    /// Advances until `d` reaches `target`, through any limit points on the way, reporting
    /// every accepted state and every cut; stops with [`Error::Solver`] naming `d` where a
    /// step of the minimum length fails, or where the path turns back below its start.
    fn advance(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        let start = self.d;
        if self.tangent.is_none() {
            let bc = self.system.load_to(self.d)?;
            let u = self.u.clone();
            let assembled = self.system.linearised(&u, &bc, true)?;
            let load_derivative = self.load_derivative(&u, self.d)?;
            let (tangent, _) = self.tangent_at(&assembled, load_derivative, &mut Timings::default())?;
            self.weight = 1.0 / dot(&tangent.free, &tangent.free).max(f64::MIN_POSITIVE);
            self.tangent = Some(self.normalised(tangent));
        }
        for _ in 0..MAX_STATES {
            if target - self.d <= 1e-12 {
                return Ok(());
            }
            let started = Instant::now();
            let tangent = self.tangent.clone().expect("set above");
            let last_step = tangent.load > 0.0 && self.d + self.step * tangent.load >= target;
            let attempt = match last_step {
                true => self.land_on(target, &tangent),
                false => self.attempt(self.step, &tangent),
            };
            match attempt {
                Ok((report, d, u, next)) => {
                    let mut record = StepRecord::new((d, d - self.d), &report, started.elapsed().as_secs_f64());
                    measure_all(&self.measures, &self.system, &u, &mut record)?;
                    observer(Event::Step {
                        record: &record,
                        system: &self.system,
                        u: &u,
                    })?;
                    (self.d, self.u, self.tangent) = (d, u, Some(next));
                    let c = self.control;
                    if report.tangent_steps <= c.easy_iterations {
                        self.step = (self.step * c.grow).min(c.max);
                    }
                    if self.d < start - c.max {
                        return Err(Error::Solver(format!(
                            "arc-length continuation turned back to d = {:.6}, below its start {start:.6}",
                            self.d
                        )));
                    }
                }
                Err(reason) => {
                    // The system stays at the last state's load, for what is written of it.
                    self.system.load_to(self.d)?;
                    let c = self.control;
                    if self.step <= c.min * (1.0 + 1e-9) {
                        return Err(Error::Solver(format!(
                            "arc-length continuation stopped after d = {:.6} with the minimum step {:.3e}: {reason}",
                            self.d, self.step
                        )));
                    }
                    let tried = self.d + self.step * tangent.load;
                    observer(Event::Cut(&Cut {
                        d: tried,
                        step: self.step,
                        reason: reason.to_string(),
                    }))?;
                    self.step = (self.step * c.cut).max(c.min);
                }
            }
        }
        Err(Error::Solver(format!(
            "arc-length continuation recorded {MAX_STATES} states without reaching d = {target} (at d = {:.6})",
            self.d
        )))
    }

    /// One step of length `h` along `tangent`: the converged state, its tangent, or why the
    /// correction failed.
    fn attempt(&mut self, h: f64, tangent: &PathTangent) -> Result<Corrected> {
        let (d0, u0) = (self.d, self.u.clone());
        let mut d = d0 + h * tangent.load;
        let mut u = u0.clone();
        for (&i, t) in self.free.iter().zip(&tangent.free) {
            u[i] += h * t;
        }
        let mut timings = Timings::default();
        let mut history = Vec::new();
        for iteration in 0..=self.policy.max_iterations {
            let bc = self.system.load_to(d)?;
            bc.impose(&mut u);
            let assembled = self.system.linearised(&u, &bc, true)?;
            let load_derivative = self.load_derivative(&u, d)?;
            let residual = assembled.residual_norm();
            history.push(residual);
            if residual <= self.policy.tolerance(assembled.force_norm(), 1.0) {
                let (next, pivots) = self.next_tangent(&assembled, load_derivative, tangent, &mut timings)?;
                let report = report(&assembled, history, iteration, pivots, timings);
                return Ok((report, d, u, next));
            }
            if iteration == self.policy.max_iterations {
                break;
            }
            let minus_residual = assembled.residual.iter().map(|r| -r).collect();
            let minus_derivative = load_derivative.iter().map(|r| -r).collect();
            let [a, b] = self.newton.solve_tangent(
                &assembled,
                [minus_residual, minus_derivative],
                false,
                self.policy.solve_tolerance,
                &mut timings,
            )?;
            // `<t, (v, load)>`; the constraint is linear, so after the first correction it holds
            // to round-off.
            let along = |v: &mut dyn Iterator<Item = f64>, load: f64| {
                0.5 * (self.weight * v.zip(&tangent.free).map(|(x, t)| x * t).sum::<f64>() + load * tangent.load)
            };
            let constraint = along(&mut self.free.iter().map(|&i| u[i] - u0[i]), d - d0) - h;
            let change = -(constraint + along(&mut a.iter().copied(), 0.0)) / along(&mut b.iter().copied(), 1.0);
            for ((&i, a), b) in self.free.iter().zip(&a).zip(&b) {
                u[i] += a + change * b;
            }
            d += change;
        }
        Err(Error::Solver(format!(
            "Newton's correction did not converge in {} iterations (|r| = {:.3e})",
            self.policy.max_iterations,
            history.last().copied().unwrap_or(f64::NAN)
        )))
    }

    /// The last step: displacement control at `target` from the tangent's prediction there.
    fn land_on(&mut self, target: f64, tangent: &PathTangent) -> Result<Corrected> {
        let along = (target - self.d) / tangent.load;
        let mut u = self.u.clone();
        for (&i, t) in self.free.iter().zip(&tangent.free) {
            u[i] += along * t;
        }
        let bc = self.system.load_to(target)?;
        bc.impose(&mut u);
        let policy = NewtonPolicy {
            inertia_at_solution: false,
            ..self.policy
        };
        let from = (self.d, self.u.as_slice());
        let corrected = self
            .system
            .correct(&mut self.newton, &policy, &mut u, &bc, None, from, (target, along));
        let (mut report, _) = corrected?;
        let assembled = self.system.linearised(&u, &bc, true)?;
        let load_derivative = self.load_derivative(&u, target)?;
        let (next, pivots) = self.next_tangent(&assembled, load_derivative, tangent, &mut report.timings)?;
        report.negative_pivots = pivots;
        Ok((report, target, u, next))
    }

    /// `dr/dd` at `(u, d)` by a central difference, the prescribed unknowns moved with `d`; the
    /// system is left at `d`.
    fn load_derivative(&mut self, u: &[f64], d: f64) -> Result<Vec<f64>> {
        let mut residual_at = |load: f64| -> Result<Vec<f64>> {
            let bc = self.system.load_to(load)?;
            let mut moved = u.to_vec();
            bc.impose(&mut moved);
            Ok(self.system.linearised(&moved, &bc, false)?.residual)
        };
        let ahead = residual_at(d + LOAD_DIFFERENCE)?;
        let behind = residual_at(d - LOAD_DIFFERENCE)?;
        self.system.load_to(d)?;
        Ok(ahead
            .iter()
            .zip(&behind)
            .map(|(a, b)| (a - b) / (2.0 * LOAD_DIFFERENCE))
            .collect())
    }

    /// The (unnormalised) tangent `(K^-1 (-dr/dd), 1)` at the state `assembled` is of (whose
    /// `dr/dd` is `load_derivative`), and the inertia of its `K_ff`.
    fn tangent_at(
        &mut self,
        assembled: &Assembled,
        load_derivative: Vec<f64>,
        timings: &mut Timings,
    ) -> Result<(PathTangent, Option<usize>)> {
        let minus_derivative = load_derivative.iter().map(|r| -r).collect();
        let [free] = self.newton.solve_tangent(
            assembled,
            [minus_derivative],
            false,
            self.policy.solve_tolerance,
            timings,
        )?;
        let pivots = self.newton.linear_solver().and_then(SparseLdlt::negative_pivots);
        Ok((PathTangent { free, load: 1.0 }, pivots))
    }

    /// The unit tangent at a converged state, turned to continue `previous`, and the inertia.
    fn next_tangent(
        &mut self,
        assembled: &Assembled,
        load_derivative: Vec<f64>,
        previous: &PathTangent,
        timings: &mut Timings,
    ) -> Result<(PathTangent, Option<usize>)> {
        let (next, pivots) = self.tangent_at(assembled, load_derivative, timings)?;
        let next = self.normalised(next);
        Ok(match self.inner(&next, previous) < 0.0 {
            true => (negated(next), pivots),
            false => (next, pivots),
        })
    }

    /// `<a, b> = (w a_f . b_f + a_d b_d) / 2`.
    fn inner(&self, a: &PathTangent, b: &PathTangent) -> f64 {
        0.5 * (self.weight * dot(&a.free, &b.free) + a.load * b.load)
    }

    fn normalised(&self, t: PathTangent) -> PathTangent {
        let length = self.inner(&t, &t).sqrt();
        PathTangent {
            free: t.free.iter().map(|x| x / length).collect(),
            load: t.load / length,
        }
    }
}

/// A converged step: Newton's report, the load, the unknowns and the unit tangent there.
type Corrected = (NewtonReport, f64, Vec<f64>, PathTangent);

impl<S: Followed> PathFollowing<S> for ArcLength<S> {
    fn advance_to(&mut self, target: f64, observer: &mut dyn FnMut(Event<'_, S>) -> Result<()>) -> Result<()> {
        self.advance(target, observer)
    }

    fn d(&self) -> f64 {
        self.d
    }

    fn displacement(&self) -> &[f64] {
        &self.u
    }

    fn system(&self) -> &S {
        &self.system
    }

    fn analysed_solver(&self) -> Option<(usize, SparseLdlt)> {
        self.newton.analysed_solver()
    }

    fn release_factorisation(&mut self) {
        self.newton.release_factorisation();
        crate::fem::memory::return_free_pages();
    }

    fn into_state(self: Box<Self>) -> (S, Vec<f64>) {
        (self.system, self.u)
    }
}

/// The unknowns not prescribed by `bc`, increasing.
fn free_unknowns(bc: &Dirichlet, unknowns: usize) -> Vec<usize> {
    let mut prescribed = bc.dofs().iter().peekable();
    (0..unknowns)
        .filter(|i| match prescribed.peek() {
            Some(&&p) if p == *i => {
                prescribed.next();
                false
            }
            _ => true,
        })
        .collect()
}

fn negated(t: PathTangent) -> PathTangent {
    PathTangent {
        free: t.free.iter().map(|x| -x).collect(),
        load: -t.load,
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Newton's report of a converged correction.
fn report(
    assembled: &Assembled,
    residual_history: Vec<f64>,
    iterations: usize,
    negative_pivots: Option<usize>,
    timings: Timings,
) -> NewtonReport {
    NewtonReport {
        iterations,
        tangent_steps: iterations,
        residual_history,
        force_norm: assembled.force_norm(),
        energy: assembled.energy,
        min_jacobian: assembled.min_jacobian,
        reactions: assembled.reactions.clone(),
        negative_pivots,
        start_negative_pivots: None,
        backtracks: 0,
        updates: Updates::default(),
        timings,
        unfinished: false,
        final_shift: 0.0,
    }
}
