//! The time step shared by the line models (docs/theory.md §5.7): the
//! predictor, the modified Newton iteration on the midpoint step equations
//! with tangent reuse, and step control by halving. What a model contributes
//! (its unknowns, residual, tangent, increment and the bookkeeping of a
//! converged step) is the [`StepEquations`] trait; the director rod
//! (`model::rod::RodModel`) and the cable (`model::cable::CableModel`) implement it;
//! this module names neither.

use crate::math::V3;
use crate::math::band::LinearSolveError;
use crate::model::RodConfig;
use crate::model::{DynamicOptions, DynamicsError, HangOff, Linear, State, StepEquations};

/// Corrections a reused tangent may still need at its observed contraction
/// rate before it is renewed.
const MAX_LINEAR_ITERATIONS: f64 = 15.0;

/// A sink for solver messages.
pub type SolverLog = Box<dyn FnMut(&str) + Send>;

/// The time integrator: a line model, the options and a preallocated workspace.
pub struct Integrator<M: StepEquations> {
    pub model: M,
    pub options: DynamicOptions,
    /// Position of the hang-off at zero displacement, m.
    pub origin: V3,
    pub(crate) ws: M::Workspace,
    pub(crate) lin: Linear,
    trial: State,
    /// Force scale of the convergence test, N.
    force_scale: f64,
    /// Receives one line per Newton iteration when set (the FMU's `logSolver`).
    pub solver_log: Option<SolverLog>,
    /// Step size the factorised tangent belongs to (NaN: none).
    factor_h: f64,
    /// Steps taken since the tangent was factorised.
    factor_age: u32,
    /// Tangents factorised since construction (for benchmarks).
    pub factorizations: u64,
    /// Newton corrections since [`Integrator::set_work_bound`], converged
    /// and failed attempts alike.
    work: u64,
    /// The most corrections allowed until the next [`Integrator::set_work_bound`]
    /// (u64::MAX: no bound, the default).
    work_bound: u64,
}

/// Outcome of one successful call to [`Integrator::step`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInfo {
    /// Newton iterations used.
    pub iterations: usize,
    /// Sub-steps taken (1 if the step was not split).
    pub substeps: usize,
}

impl<M: StepEquations> Integrator<M> {
    pub fn new(model: M, options: DynamicOptions, origin: V3) -> Result<Self, LinearSolveError> {
        let (ws, lin) = model.workspace()?;
        let force_scale = model.force_scale();
        Ok(Integrator {
            model,
            options,
            origin,
            ws,
            lin,
            trial: State::default(),
            force_scale,
            solver_log: None,
            factor_h: f64::NAN,
            factor_age: 0,
            factorizations: 0,
            work: 0,
            work_bound: u64::MAX,
        })
    }

    /// The model's scratch workspace (for verification probes).
    pub fn workspace(&self) -> &M::Workspace {
        &self.ws
    }

    /// The model's scratch workspace, mutable (for verification probes).
    pub fn workspace_mut(&mut self) -> &mut M::Workspace {
        &mut self.ws
    }

    /// Bounds the Newton corrections from now on to `bound` (u64::MAX: none):
    /// a step that reaches it fails with [`DynamicsError::WorkBound`], not
    /// split further, the state at its last converged sub-step. Resets the
    /// count ([`Integrator::work`]).
    pub fn set_work_bound(&mut self, bound: u64) {
        self.work = 0;
        self.work_bound = bound;
    }

    /// Newton corrections since the last [`Integrator::set_work_bound`],
    /// those of failed attempts included.
    pub fn work(&self) -> u64 {
        self.work
    }

    /// Forgets the factorised tangent: the next step starts with a new one.
    /// Call it where results must depend on the state alone (the FMU: when
    /// a state is saved or restored).
    pub fn invalidate_tangent(&mut self) {
        self.factor_h = f64::NAN;
    }

    /// Puts the hang-off of `state` on its prescribed motion at the state's time
    /// (position and velocity), e.g. before the first step.
    pub fn impose_hang_off(&self, state: &mut State, motion: HangOff) {
        if self.model.hang_off_prescribed() {
            state.config.x[0] = self.origin + motion.displacement;
            state.vel[0] = motion.velocity;
        }
        state.hang_off = motion;
    }

    /// Advances `state` by one step `h` to the hang-off motion `motion(t)`
    /// (t absolute). A step whose Newton iteration fails is split in halves,
    /// down to h/2^max_halvings; if that fails too, `state` is left at the
    /// last converged sub-step and the error says why.
    pub fn step(
        &mut self,
        state: &mut State,
        h: f64,
        motion: &dyn Fn(f64) -> HangOff,
    ) -> Result<StepInfo, DynamicsError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(DynamicsError::BadInput(format!("time step must be positive and finite, got {h}")));
        }
        let t_end = state.time + h;
        let mut sub = h;
        let mut level = 0u32;
        let mut info = StepInfo { iterations: 0, substeps: 0 };
        let mut split = false;
        while state.time < t_end - 1e-12 * h {
            let hh = sub.min(t_end - state.time);
            let target = motion(state.time + hh);
            // the cubic predictor (which falls back to the linear one by
            // itself when it extrapolates an unresolved oscillation); halved
            // sub-steps, whose history is of another step size, the linear one
            let order = if level == 0 { self.options.predictor_order } else { 1 };
            match self.try_step(state, hh, target, order) {
                Ok(it) => {
                    info.iterations += it;
                    info.substeps += 1;
                }
                Err(e) => {
                    let last = matches!(e, DynamicsError::BadInput(_) | DynamicsError::WorkBound { .. });
                    if last || level >= self.options.max_halvings {
                        return Err(e);
                    }
                    level += 1;
                    sub *= 0.5;
                    split = true;
                }
            }
        }
        state.time = t_end;
        if split {
            state.retries += 1;
        }
        Ok(info)
    }

    /// One step of size h without splitting: on success `state` becomes the
    /// new state; on failure it is untouched.
    fn try_step(&mut self, state: &mut State, h: f64, target: HangOff, order: u32) -> Result<usize, DynamicsError> {
        let model = &self.model;
        if !(target.displacement.iter().chain(target.velocity.iter()).all(|v| v.is_finite())) {
            return Err(DynamicsError::BadInput("hang-off motion is not finite".into()));
        }
        let eta = self.options.structural_damping;
        let trial = &mut self.trial;
        trial.clone_from(state);
        model.begin(&mut self.ws, state, &self.options);
        model.predict(&mut self.ws, state, trial, h, self.origin, target, order);
        // below 10× the residual's round-off, stop when Newton stagnates
        let roundoff = model.residual_roundoff(&state.config, h);
        let asked = self.options.newton_tolerance * self.force_scale;
        let tol = asked.max(roundoff);
        // asked for round-off: iterate until the residual stops falling, so
        // that no systematic part of a linearly converging iteration is left
        let to_roundoff = asked < roundoff;
        let mut converged = false;
        let mut iterations = 0;
        let mut last = f64::INFINITY;
        let mut first = f64::INFINITY;
        let mut last_res = f64::INFINITY;
        // modified Newton: the factorised tangent is reused across iterations
        // and steps; it is refreshed when it is older than max_tangent_age
        // steps, when h changed, or when the residual contracts slowly
        let same_h = (self.factor_h - h).abs() <= 1e-9 * h; // false for NaN
        let mut refresh = !same_h || self.factor_age >= self.options.max_tangent_age;
        // whether the last Newton correction used a tangent of its own iterate
        let mut solved_fresh = false;
        // set when a fresh tangent still contracts slowly: full Newton from there
        let mut full = false;
        let mut tried_linear = false;
        let mut at_start = true;
        for it in 0..=self.options.max_iterations {
            if refresh {
                // assembling overwrites the factorised matrix
                self.factor_h = f64::NAN;
            }
            model.assemble(&mut self.ws, &mut self.lin, state, &trial.config, h, target, eta, refresh);
            let res = model.residual_norm(&self.lin);
            if let Some(log) = self.solver_log.as_mut() {
                log(&format!(
                    "t = {:.6} s, h = {h:.3e} s, Newton iteration {it}{}: residual {res:.3e} N (tolerance {tol:.3e} N)",
                    state.time,
                    if refresh { " (new tangent)" } else { "" }
                ));
            }
            last = res;
            // converged; or stagnating at round-off after a full Newton correction
            let at_tol = res <= tol && (!to_roundoff || res > 0.25 * last_res || res <= 0.1 * roundoff);
            // (never the bare prediction: an extrapolation, not a solution of
            // the step equations, whatever the tolerance; at the default one
            // the prediction is never within it)
            let corrected = iterations > 0;
            if (at_tol && corrected) || (solved_fresh && res <= 10.0 * roundoff && res > 0.25 * last_res) {
                converged = true;
                break;
            }
            if at_start && res > 0.1 * self.force_scale && order >= 2 && !tried_linear {
                // the cubic predictor extrapolated an unresolved
                // oscillation: start again from the linear one
                tried_linear = true;
                model.predict(&mut self.ws, state, trial, h, self.origin, target, 1);
                continue;
            }
            at_start = false;
            if it == self.options.max_iterations || !res.is_finite() {
                break;
            }
            if it == 0 {
                first = res;
            }
            if res > 1e8 * first {
                break;
            }
            // slow: the residual contracts by less than half per correction, or
            // at a rate that would need more than `MAX_LINEAR_ITERATIONS` more
            // corrections to reach the tolerance (a new tangent costs about
            // as much as ten residuals)
            if self.work >= self.work_bound {
                self.factor_h = f64::NAN;
                return Err(DynamicsError::WorkBound { time: state.time, iterations: self.work });
            }
            self.work += 1;
            let rate = res / last_res;
            let slow = rate > 0.5 || (rate > 0.0 && (tol / res).ln() / rate.ln() > MAX_LINEAR_ITERATIONS);
            last_res = res;
            iterations += 1;
            let lin = &mut self.lin;
            for &i in &lin.fixed {
                lin.r[i] = 0.0;
            }
            if refresh {
                for &i in &lin.fixed {
                    lin.sys.constrain(i);
                }
                if let Err(error) = lin.sys.factorize() {
                    self.factor_h = f64::NAN;
                    return Err(DynamicsError::Linear { time: state.time, step: h, error });
                }
                self.factor_h = h;
                self.factor_age = 0;
                self.factorizations += 1;
            }
            // the contraction just observed is that of the previous correction:
            // slow after a stale tangent, renew it once; slow after a fresh
            // one, the step is strongly nonlinear: full Newton from here
            let prev_fresh = solved_fresh;
            solved_fresh = refresh;
            if slow && it > 0 && prev_fresh {
                full = true;
            }
            refresh = full || (slow && it > 0);
            for (d, r) in lin.du.iter_mut().zip(&lin.r) {
                *d = -r;
            }
            model.to_tangent_basis(&self.ws, &trial.config, &mut lin.du);
            if let Err(error) = lin.sys.solve_in_place(&mut lin.du) {
                self.factor_h = f64::NAN;
                return Err(DynamicsError::Linear { time: state.time, step: h, error });
            }
            model.to_spatial_basis(&self.ws, &trial.config, &mut lin.du);
            // (a non-finite configuration shows as an infinite residual next)
            model.apply_increment(&mut self.ws, lin, state, &mut trial.config);
        }
        if !converged {
            // the next attempt (a smaller sub-step) starts from a new tangent
            self.factor_h = f64::NAN;
            return Err(DynamicsError::NotConverged {
                time: state.time,
                step: h,
                iterations,
                residual: last / self.force_scale,
            });
        }
        if !model.step_is_admissible(state, &trial.config) {
            // a spurious root of the step equations (theory §5.7): smaller steps
            self.factor_h = f64::NAN;
            return Err(DynamicsError::Inadmissible { time: state.time, step: h });
        }
        model.finish(&mut self.ws, state, trial, h, &self.options);
        if !trial.is_finite() {
            // never a state that is not a number: smaller steps, or an error
            // with the state kept
            self.factor_h = f64::NAN;
            return Err(DynamicsError::NonFinite { time: state.time, step: h });
        }
        trial.hang_off = target;
        trial.time = state.time + h;
        trial.steps += 1;
        self.factor_age += 1;
        trial.newton_iterations += iterations as u64;
        std::mem::swap(state, trial);
        Ok(iterations)
    }
}

impl<M: StepEquations> Integrator<M> {
    /// The step's tangent condensed on its fixed (prescribed) unknowns at the
    /// converged step from `prev` to `cfg` (docs/theory.md §17.7, eq. 17.15):
    /// S = K_ff − K_fi K_ii⁻¹ K_if, the change of the supports' reactions
    /// (the fixed rows of the step residual) per unit move of the prescribed
    /// unknowns, the other unknowns re-solved; row-major, in the order of
    /// the fixed unknowns (sorted), in the basis the tangent is assembled in
    /// (spatial for the cable). The fresh tangent stays factorised for the
    /// next Newton iteration of a step of `h` (the modified Newton's).
    pub fn condensed_fixed_tangent(
        &mut self,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
    ) -> Result<Vec<f64>, LinearSolveError> {
        let mut s = vec![0.0; self.lin.fixed.len().pow(2)];
        self.condensed_fixed_tangent_into(prev, cfg, h, target, &mut s)?;
        Ok(s)
    }

    /// The number of the step's prescribed (fixed) unknowns, the side of
    /// [`Integrator::condensed_fixed_tangent`]'s square.
    pub fn fixed_unknowns(&self) -> usize {
        self.lin.fixed.len()
    }

    /// [`Integrator::condensed_fixed_tangent`] into `s` (the fixed
    /// unknowns' number squared), allocating nothing once warmed up.
    pub fn condensed_fixed_tangent_into(
        &mut self,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
        s: &mut [f64],
    ) -> Result<(), LinearSolveError> {
        let eta = self.options.structural_damping;
        self.model.begin(&mut self.ws, prev, &self.options);
        self.factor_h = f64::NAN;
        self.model.assemble(&mut self.ws, &mut self.lin, prev, cfg, h, target, eta, true);
        let lin = &mut self.lin;
        lin.sys.schur_complement_into(&lin.fixed, &lin.fixed, s)?;
        self.factor_h = h;
        self.factor_age = 0;
        self.factorizations += 1;
        Ok(())
    }
}

/// Access to the step equations for verification (tests compare the tangent
/// with finite differences of the residual).
impl<M: StepEquations> Integrator<M> {
    /// Starts a step from `prev` to the hang-off motion `target`: returns the
    /// predicted configuration q_{n+1}.
    pub fn begin_step(&mut self, prev: &State, h: f64, target: HangOff) -> RodConfig {
        self.model.begin(&mut self.ws, prev, &self.options);
        let mut trial = prev.clone();
        self.model.predict(&mut self.ws, prev, &mut trial, h, self.origin, target, self.options.predictor_order);
        trial.config
    }

    /// Residual of the step equations at `cfg` (rows of fixed unknowns
    /// included); the tangent too if `want_tangent` (see [`Integrator::tangent_entry`]).
    pub fn step_residual(
        &mut self,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
        want_tangent: bool,
    ) -> Vec<f64> {
        let eta = self.options.structural_damping;
        self.model.assemble(&mut self.ws, &mut self.lin, prev, cfg, h, target, eta, want_tangent);
        self.lin.r.clone()
    }

    /// Entry (i, j) of the tangent from the last [`Integrator::step_residual`].
    pub fn tangent_entry(&self, i: usize, j: usize) -> f64 {
        self.lin.sys.get(i, j)
    }

    /// q_{n+1} ⊕ Δu, as Newton applies it.
    pub fn apply_step_increment(&mut self, prev: &State, cfg: &mut RodConfig, du: &[f64]) {
        self.lin.du.copy_from_slice(du);
        self.model.apply_increment(&mut self.ws, &mut self.lin, prev, cfg);
    }

    /// `v` (spatial components) into the basis the tangent is assembled in at `cfg`.
    pub fn to_tangent_basis(&self, cfg: &RodConfig, v: &mut [f64]) {
        self.model.to_tangent_basis(&self.ws, cfg, v);
    }

    /// The inverse of [`Integrator::to_tangent_basis`].
    pub fn to_spatial_basis(&self, cfg: &RodConfig, v: &mut [f64]) {
        self.model.to_spatial_basis(&self.ws, cfg, v);
    }

    /// Unknowns of the step equations.
    pub fn n_unknowns(&self) -> usize {
        self.lin.r.len()
    }
}
