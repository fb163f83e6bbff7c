//! A simulation: a scene, its model, the state and the outputs, as the CLI
//! and the FMU drive it: the static state ([`report`]), the integrator with
//! the scene's settings, and hang-off motions; the typed top-level
//! [`error::RiserError`].

pub mod accuracy;
pub mod design;
pub mod error;
pub mod error_estimate;
pub mod fatigue;
pub mod lrfd;
pub mod modes;
pub mod monolithic;
pub mod report;
pub mod system;
pub mod system_accuracy;
pub mod system_dynamics;
pub mod system_modes;
pub mod vessel;

use crate::loads::waves::{Sea, sea_of};
use crate::math::{M3, M6, V3};
use crate::model::cable::CableModel;
use crate::model::cable::linearized::CableLinearized;
use crate::model::rod::RodModel;
use crate::model::rod::linearized::RodLinearized;
use crate::model::rod::statics::StaticLoads;
use crate::model::{DynamicOptions, DynamicsError, HangOff, Outputs, State};
use crate::scene::{Model, Scene, SceneError};
use crate::sim::report::{StaticReport, scene_static_loads, solve_scene};
use crate::solve::eigen::{end_stiffness6, hang_off_stiffness6};
use crate::solve::{Integrator, SolverLog, StepInfo};
use error::RiserError;
use vessel::Vessel;

/// Heave of the hang-off, U0 sin(2π t/T), held at its value after `until`
/// (the paper's runs; the free-motion run stops the excitation at 15 s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heave {
    /// Amplitude U0, m.
    pub amplitude: f64,
    /// Period T, s.
    pub period: f64,
    /// Time after which the hang-off is held still, s.
    pub until: Option<f64>,
    /// Length of a smooth start, s: the amplitude grows as ½(1 − cos(π t/ramp))
    /// (0: the paper's abrupt start, with a velocity jump at t = 0).
    pub ramp: f64,
}

impl Heave {
    /// Hang-off displacement and velocity at t.
    pub fn at(&self, t: f64) -> HangOff {
        let w = 2.0 * std::f64::consts::PI / self.period;
        let held = self.until.is_some_and(|u| t > u);
        let tt = if held { self.until.unwrap_or(t) } else { t };
        let (r, dr) = if self.ramp > 0.0 && tt < self.ramp {
            let a = std::f64::consts::PI / self.ramp;
            (0.5 * (1.0 - (a * tt).cos()), 0.5 * a * (a * tt).sin())
        } else {
            (1.0, 0.0)
        };
        let z = self.amplitude * r * (w * tt).sin();
        let vz = if held { 0.0 } else { self.amplitude * (r * w * (w * tt).cos() + dr * (w * tt).sin()) };
        HangOff::translation(V3::z() * z, V3::z() * vz)
    }
}

/// The time integrator of a scene's line model.
pub enum Engine {
    /// The Cosserat director rod.
    Rod(Box<Integrator<RodModel>>),
    /// The cable (no bending, no torsion).
    Cable(Box<Integrator<CableModel>>),
}

/// `$body` with `$i` bound to the integrator of either model.
macro_rules! with_integrator {
    ($engine:expr, $i:ident => $body:expr) => {
        match $engine {
            Engine::Rod($i) => $body,
            Engine::Cable($i) => $body,
        }
    };
}

impl Engine {
    /// The integrator of the scene's model (`analysis.model`), in the
    /// scene's waves (their ramp starting at t = 0: [`Engine::set_ramps_start`]).
    pub fn from_scene(scene: &Scene) -> Result<Self, RiserError> {
        let sea = sea_of(scene, 0.0).map_err(|e| RiserError::Scene(SceneError::Invalid(vec![e])))?;
        let options = DynamicOptions {
            time_step: scene.analysis.time_step,
            newton_tolerance: scene.analysis.newton_tolerance,
            structural_damping: scene.analysis.structural_damping,
            rho_infinity: scene.analysis.rho_infinity,
            ..Default::default()
        };
        let origin = scene.hang_off();
        let engine = match scene.analysis.model {
            Model::Rod => Integrator::new(RodModel::from_scene(scene).with_sea(sea), options, origin)
                .map(|i| Engine::Rod(i.into())),
            Model::Cable => Integrator::new(CableModel::from_scene(scene).with_sea(sea), options, origin)
                .map(|i| Engine::Cable(i.into())),
        };
        engine.map_err(|e| RiserError::Unsupported(format!("cannot set up the linear solver: {e}")))
    }

    /// Gives a flex joint its static frame, the end frame of the static
    /// configuration `cfg` (§15; nothing for other ends and the cable).
    pub fn set_static_frame(&mut self, cfg: &crate::model::RodConfig) {
        if let Engine::Rod(i) = self {
            i.model.set_static_frame(cfg);
        }
    }

    /// The sea the line is in (None: still water).
    pub fn sea(&self) -> Option<&Sea> {
        match self {
            Engine::Rod(i) => i.model.sea.as_ref(),
            Engine::Cable(i) => i.model.sea.as_ref(),
        }
    }

    /// Starts the waves' ramp and the current's at `start` s (a run's start time).
    pub fn set_ramps_start(&mut self, start: f64) {
        with_integrator!(self, i => {
            i.model.current_ramp.start = start;
            if let Some(sea) = i.model.sea.as_mut() {
                sea.set_ramp_start(start);
            }
        })
    }

    pub fn options(&self) -> &DynamicOptions {
        with_integrator!(self, i => &i.options)
    }

    pub fn options_mut(&mut self) -> &mut DynamicOptions {
        with_integrator!(self, i => &mut i.options)
    }

    /// Sets the sink of the per-iteration solver messages (None: silent).
    pub fn set_solver_log(&mut self, log: Option<SolverLog>) {
        with_integrator!(self, i => i.solver_log = log)
    }

    /// Tangents factorised so far.
    pub fn factorizations(&self) -> u64 {
        with_integrator!(self, i => i.factorizations)
    }

    /// See [`Integrator::set_work_bound`].
    pub fn set_work_bound(&mut self, bound: u64) {
        with_integrator!(self, i => i.set_work_bound(bound))
    }

    /// See [`Integrator::work`].
    pub fn work(&self) -> u64 {
        with_integrator!(self, i => i.work())
    }

    /// See [`Integrator::invalidate_tangent`].
    pub fn invalidate_tangent(&mut self) {
        with_integrator!(self, i => i.invalidate_tangent())
    }

    /// See [`Integrator::condensed_fixed_tangent`].
    pub fn condensed_fixed_tangent(
        &mut self,
        prev: &State,
        cfg: &crate::model::RodConfig,
        h: f64,
        target: HangOff,
    ) -> Result<Vec<f64>, crate::math::band::LinearSolveError> {
        with_integrator!(self, i => i.condensed_fixed_tangent(prev, cfg, h, target))
    }

    /// See [`Integrator::fixed_unknowns`].
    pub fn fixed_unknowns(&self) -> usize {
        with_integrator!(self, i => i.fixed_unknowns())
    }

    /// Where the two end nodes' positions [hang-off x, y, z, anchor x, y, z]
    /// are among the step's prescribed unknowns (sorted: the order of
    /// [`Integrator::condensed_fixed_tangent`]'s rows); None if an end's
    /// position is not prescribed.
    pub fn end_position_unknowns(&self) -> Option<[usize; 6]> {
        let (h, a) = match self {
            Engine::Rod(i) => (crate::model::rod::Rod::x_dof(0), crate::model::rod::Rod::x_dof(i.model.rod.n_el)),
            Engine::Cable(i) => (0, crate::model::cable::NODE_DOF * i.model.cable.n_el),
        };
        let fixed = with_integrator!(self, i => &i.lin.fixed);
        let mut at = [0; 6];
        for (k, dof) in (h..h + 3).chain(a..a + 3).enumerate() {
            at[k] = fixed.iter().position(|&f| f == dof)?;
        }
        Some(at)
    }

    /// The frames the step's tangent takes the end nodes' positions in at
    /// `cfg` (the rod's corotated tangent: its end nodes' director frames,
    /// §5.7), None where spatial (the cable's).
    pub fn end_frames(&self, cfg: &crate::model::RodConfig) -> [Option<crate::math::M3>; 2] {
        match self {
            Engine::Rod(i) if i.options.corotated_tangent => [Some(cfg.d[0]), Some(cfg.d[2 * i.model.rod.n_el])],
            _ => [None, None],
        }
    }

    /// The step's tangent condensed on its two ends' positions (17.15), 6×6
    /// row-major [hang-off; anchor] into `s6`, global (N/m): the tangent
    /// condensed on all its prescribed unknowns into `scratch`
    /// ([`Integrator::condensed_fixed_tangent_into`], its size the fixed
    /// unknowns' number squared), its rows and columns `at`
    /// ([`Engine::end_position_unknowns`]) taken, and the rod's turned from
    /// its end nodes' director frames, S = D_a S_loc D_bᵀ a block (§5.7).
    /// Allocates nothing.
    #[allow(clippy::too_many_arguments)]
    pub fn condensed_end_tangent_into(
        &mut self,
        prev: &State,
        cfg: &crate::model::RodConfig,
        h: f64,
        target: HangOff,
        at: &[usize; 6],
        scratch: &mut [f64],
        s6: &mut [f64; 36],
    ) -> Result<(), crate::math::band::LinearSolveError> {
        self.condensed_fixed_tangent_into(prev, cfg, h, target, scratch)?;
        let m = self.fixed_unknowns();
        let frames = self.end_frames(cfg);
        for (ea, fa) in frames.iter().enumerate() {
            for (eb, fb) in frames.iter().enumerate() {
                let local = crate::math::M3::from_fn(|r, c| scratch[at[3 * ea + r] * m + at[3 * eb + c]]);
                let block = match (fa, fb) {
                    (Some(fa), Some(fb)) => fa * local * fb.transpose(),
                    _ => local,
                };
                for (r, c) in (0..3).flat_map(|r| (0..3).map(move |c| (r, c))) {
                    s6[(3 * ea + r) * 6 + 3 * eb + c] = block[(r, c)];
                }
            }
        }
        Ok(())
    }

    /// See [`Integrator::condensed_fixed_tangent_into`].
    pub fn condensed_fixed_tangent_into(
        &mut self,
        prev: &State,
        cfg: &crate::model::RodConfig,
        h: f64,
        target: HangOff,
        s: &mut [f64],
    ) -> Result<(), crate::math::band::LinearSolveError> {
        with_integrator!(self, i => i.condensed_fixed_tangent_into(prev, cfg, h, target, s))
    }

    /// Moves the line's anchor end to `m` over the next step (None: held),
    /// pinned (a rod's twist held there as at a fixed anchor: §17.7).
    pub fn set_anchor_motion(&mut self, m: Option<crate::model::AnchorMotion>) {
        match self {
            Engine::Cable(i) => i.model.anchor_motion = m,
            Engine::Rod(i) => i.model.anchor_motion = m,
        }
    }

    /// See [`Integrator::impose_hang_off`].
    pub fn impose_hang_off(&self, state: &mut State, motion: HangOff) {
        with_integrator!(self, i => i.impose_hang_off(state, motion))
    }

    /// See [`Integrator::step`].
    pub fn step(
        &mut self,
        state: &mut State,
        h: f64,
        motion: &dyn Fn(f64) -> HangOff,
    ) -> Result<StepInfo, DynamicsError> {
        with_integrator!(self, i => i.step(state, h, motion))
    }

    /// Every output quantity of `state`.
    pub fn outputs(&self, state: &State) -> Outputs {
        match self {
            Engine::Rod(i) => i.model.outputs(state),
            Engine::Cable(i) => i.model.outputs(state),
        }
    }

    /// The force the line exerts on the vessel in `state`, N: the
    /// [`Outputs::top_force`] of [`Engine::outputs`] (minus the hang-off's
    /// reaction) without the rest of the outputs.
    pub fn top_force(&self, state: &State) -> V3 {
        -match self {
            Engine::Rod(i) => i.model.end_reaction(state, 0),
            Engine::Cable(i) => i.model.end_reaction(state, 0),
        }
    }

    /// Tension (N) and curvature (1/m) at every node of `state` (the
    /// models' `node_profile`).
    pub fn node_profile(&self, state: &State) -> Vec<(f64, f64)> {
        match self {
            Engine::Rod(i) => i.model.node_profile(&state.config),
            Engine::Cable(i) => i.model.node_profile(&state.config.x),
        }
    }

    /// The line at the points where the design numbers are read (the rod's
    /// Gauss points, the cable's nodes; docs/theory.md §12).
    pub fn line_points(&self, state: &State) -> Vec<crate::model::outputs::LinePoint> {
        match self {
            Engine::Rod(i) => i.model.rod.gauss_points(&state.config),
            Engine::Cable(i) => i.model.node_points(&state.config.x),
        }
    }

    /// Unit tangent of the line at the hang-off, pointing down the line: the
    /// rod's nodal r′; for the cable the one-sided second-order difference
    /// (−3x₀ + 4x₁ − x₂)/2 (its first chord is the tangent half a segment down).
    pub fn hang_off_tangent(&self, state: &State) -> V3 {
        let x = &state.config.x;
        match self {
            Engine::Rod(_) => state.config.xp[0].normalize(),
            Engine::Cable(_) => crate::model::outputs::first_node_tangent(x).normalize(),
        }
    }

    /// Reference arc length of every node of `state`, m.
    pub fn node_arc_lengths(&self) -> Vec<f64> {
        match self {
            Engine::Rod(i) => (0..=i.model.rod.n_el).map(|a| i.model.rod.s_node(a)).collect(),
            Engine::Cable(i) => (0..=i.model.cable.n_el).map(|a| i.model.cable.s_node(a)).collect(),
        }
    }
}

/// A scene set up for a dynamic run, starting from its static equilibrium.
/// The most internal steps one call may ask for (a communication step of
/// the FMU, a `riser run`): a million steps are 14 h of simulated time at the
/// default 0.05 s; more is a mistake in the caller's units.
pub const MAX_STEPS_PER_CALL: u64 = 1_000_000;

/// A last internal step shorter than this fraction of `time_step` is merged
/// into the one before: a span of 1.000001 steps takes one step of 1.000001
/// dt, not a step of dt and one of 1e-6 dt, whose inertia term (∝ 1/h²)
/// would magnify round-off into the reaction at the hang-off.
pub const MERGE_FRACTION: f64 = 0.01;

/// The number of internal steps of at most about `dt` that cover `span` s,
/// or an error if that is more than [`MAX_STEPS_PER_CALL`] (`span` and `dt`
/// positive and finite).
pub fn internal_steps(span: f64, dt: f64) -> Result<u64, String> {
    let n = (span / dt - MERGE_FRACTION).ceil().max(1.0);
    if n.is_nan() || n > MAX_STEPS_PER_CALL as f64 {
        return Err(format!(
            "{} s at time_step {} s takes {n:.3e} internal steps; at most {MAX_STEPS_PER_CALL} per call",
            crate::scene::ranges::number(span),
            crate::scene::ranges::number(dt)
        ));
    }
    Ok(n as u64)
}

/// The length of the internal steps the FMU takes over a communication step
/// of `span` s split into `n` ([`internal_steps`] at `time_step` `dt`):
/// `dt` itself where `n` steps of `dt` make the span (within a relative 1e-6:
/// a master's floating-point step lengths, the same bits as before), else
/// `span / n`, `n` equal steps. Multiples of `dt` and a shorter remainder
/// alternate the step's length from one internal step to the next (0.2 s at
/// the 0.119 s the `accuracy` pilots chose for the steel catenary: 0.119 s
/// and 0.081 s), and the generalized-α integrator is second order only at a
/// constant step: with the path all but exact the top tension's window then
/// erred 2.4e-3 against 5.7e-4 with two steps of 0.1 s and 3.2e-4 with the
/// motion itself at 0.119 s (`riser run`; docs/theory.md §16.6).
pub fn even_internal_step(span: f64, dt: f64, n: u64) -> f64 {
    if (span / dt - n as f64).abs() <= 1e-6 * n as f64 { dt } else { span / n as f64 }
}

/// The end time of internal step `k` of `n` from `start` over `span` s:
/// multiples of `dt`, the last one ending exactly at `start + span`.
pub fn internal_step_end(start: f64, span: f64, dt: f64, k: u64, n: u64) -> f64 {
    if k == n { start + span } else { start + k as f64 * dt }
}

pub struct Simulation {
    pub integrator: Engine,
    pub state: State,
    /// The static equilibrium the run starts from.
    pub statics: StaticReport,
    /// Total energy at t = 0, J (the reference of the energy balance).
    pub initial_energy: f64,
    /// The loads of the statics (for the stiffness at the hang-off).
    pub static_loads: StaticLoads,
    /// The scene's sea (None: still water); its ramp starts at [`Simulation::start`].
    pub sea: Option<Sea>,
    /// Where the hang-off sits on the vessel (§14).
    pub vessel: Vessel,
}

impl Simulation {
    /// Solves the scene's statics and prepares the integrator of the scene's
    /// line model with the scene's time step and Newton tolerance.
    pub fn from_scene(scene: &Scene) -> Result<Self, RiserError> {
        Simulation::from_statics(scene, solve_scene(scene)?)
    }

    /// [`Simulation::from_scene`] from a static state `statics` of the scene
    /// solved elsewhere (a system's line at its free points' equilibrium,
    /// docs/theory.md §17.4).
    pub fn from_statics(scene: &Scene, statics: StaticReport) -> Result<Self, RiserError> {
        let mut integrator = Engine::from_scene(scene)?;
        integrator.set_static_frame(&statics.solution.config);
        let sea = integrator.sea().cloned();
        let state = State::at_rest(statics.solution.config.clone(), 0.0);
        let initial_energy = integrator.outputs(&state).total_energy;
        let static_loads = scene_static_loads(scene);
        let vessel = Vessel::of_scene(scene);
        Ok(Simulation { integrator, state, statics, initial_energy, static_loads, sea, vessel })
    }

    /// Solves the statics again with the hang-off displaced by `d` (m,
    /// global; the FMU's inputs not zero at the start): the run then starts
    /// at rest in that equilibrium, not from the scene's with its hang-off
    /// node alone moved (docs/theory.md §7.7). A flex joint's static frame
    /// is that state's end frame (its spring at rest there).
    pub fn move_statics(&mut self, scene: &Scene, d: V3) -> Result<(), RiserError> {
        let statics = crate::sim::report::solve_scene_moved(scene, &self.statics, d)?;
        self.state = State::at_rest(statics.solution.config.clone(), self.state.time);
        // a flex joint's spring at rest in that state
        self.integrator.set_static_frame(&statics.solution.config);
        self.statics = statics;
        self.initial_energy = self.integrator.outputs(&self.state).total_energy;
        Ok(())
    }

    /// The static state the run starts from, at rest: the functional load
    /// effects of DNV-OS-F201's check (docs/theory.md §12.4, (12.14)).
    pub fn functional_state(&self) -> State {
        State::at_rest(self.statics.solution.config.clone(), 0.0)
    }

    /// Puts the hang-off on its motion at t = 0 and takes the energy reference there.
    pub fn start(&mut self, motion: HangOff) {
        self.set_ramps_start(self.state.time);
        self.integrator.impose_hang_off(&mut self.state, motion);
        self.initial_energy = self.integrator.outputs(&self.state).total_energy;
    }

    /// Starts the waves' and the current's ramps at `start` s (the run's
    /// start; a restored state's, docs/theory.md §5.11).
    pub fn set_ramps_start(&mut self, start: f64) {
        if let Some(sea) = self.sea.as_mut() {
            sea.set_ramp_start(start);
        }
        self.integrator.set_ramps_start(start);
    }

    /// Outputs of the current state.
    pub fn outputs(&self) -> Outputs {
        let mut o = self.integrator.outputs(&self.state);
        let loads = self.vessel.loads(&self.state.hang_off.rotation, o.top_force, o.end_moment);
        (o.top_moment, o.vessel_force, o.vessel_moment) = (loads.moment, loads.force_vessel, loads.moment_vessel);
        if let Some(sea) = &self.sea {
            let [x0, y0] = sea.settings().origin;
            o.wave_elevation = sea.ramped_elevation(x0, y0, self.state.time);
        }
        o
    }

    /// Advances to `t_target` in one internal step (split only if Newton
    /// needs it); the state's time is then exactly `t_target`.
    pub fn advance_to(&mut self, t_target: f64, motion: &dyn Fn(f64) -> HangOff) -> Result<(), RiserError> {
        let h = t_target - self.state.time;
        self.integrator.step(&mut self.state, h, motion)?;
        self.state.time = t_target;
        Ok(())
    }

    /// The line's tangent stiffness at the hang-off at the current state
    /// (docs/theory.md §8.3): the change of the force of the support on the
    /// line per metre of hang-off displacement, N/m; the force on the vessel
    /// (`top_force_*`) changes by minus this. The translation block of
    /// [`Simulation::hang_off_stiffness6`].
    pub fn hang_off_stiffness(&self) -> Result<M3, RiserError> {
        Ok(self.hang_off_stiffness6()?.fixed_view::<3, 3>(0, 0).into_owned())
    }

    /// The line's 6×6 tangent stiffness at the hang-off at the current state
    /// (docs/theory.md §8.3, eq. 8.7): [δF; δM] = S₆ [δx; δθ], the force and
    /// end moment of the support on the line against the hang-off's
    /// translation and a small rotation δθ (global) of the vessel's frame;
    /// a clamped end turns with the vessel, a flex joint holds its spring
    /// about the vessel's frame at the state; a pinned end (and the cable)
    /// has zero rotation columns and moment rows. The loads on the vessel
    /// (`top_force_*`, the end moment in `top_moment_*`) change by minus this.
    pub fn hang_off_stiffness6(&self) -> Result<M6, RiserError> {
        let cfg = &self.state.config;
        let s = match &self.integrator {
            Engine::Rod(i) => {
                // a flex joint about the vessel's frame at the state
                let turned = i.model.joint_frame(&self.state.hang_off.rotation).map(|f| {
                    let mut m = i.model.clone();
                    if let Some(j) = m.rod.flex_joint.as_mut() {
                        j.frame = Some(f);
                    }
                    m
                });
                let model = turned.as_ref().unwrap_or(&i.model);
                hang_off_stiffness6(&RodLinearized::new(model, &self.static_loads), cfg)
            }
            Engine::Cable(i) => {
                hang_off_stiffness6(&CableLinearized::new(&i.model, self.static_loads.drag.is_some()), cfg)
            }
        };
        Ok(s?)
    }

    /// The line's tangent stiffness at both its ends' positions at the
    /// current state (docs/theory.md §17.4, eq. 17.6, with the static loads
    /// as [`Simulation::hang_off_stiffness6`] takes them): [δR_h; δR_a] =
    /// S [δx_h; δx_a], the change of the supports' forces on the line at its
    /// hang-off and its anchor per metre of the ends' moves (global, N/m),
    /// the interior in equilibrium, the ends pinned.
    pub fn end_stiffness6(&self) -> Result<M6, RiserError> {
        let cfg = &self.state.config;
        let s = match &self.integrator {
            Engine::Rod(i) => end_stiffness6(&RodLinearized::new(&i.model, &self.static_loads), cfg),
            Engine::Cable(i) => end_stiffness6(&CableLinearized::new(&i.model, self.static_loads.drag.is_some()), cfg),
        };
        Ok(s?)
    }

    /// [`Simulation::hang_off_stiffness6`] in the storage `w` (sized on
    /// this line at its first call), allocating nothing after it, the same
    /// bits; a rod with a flex joint (its joint's frame turned with the
    /// vessel on a copy of its model) allocates as
    /// [`Simulation::hang_off_stiffness6`] does.
    pub fn hang_off_stiffness6_into(&self, w: &mut HangOffScratch) -> Result<M6, RiserError> {
        let cfg = &self.state.config;
        let s = match &self.integrator {
            Engine::Rod(i) if i.model.rod.flex_joint.is_some() => return self.hang_off_stiffness6(),
            Engine::Rod(i) => {
                let line = match w.parts.take() {
                    Some(LinearizedParts::Rod(p)) => RodLinearized::from_parts(&i.model, &self.static_loads, p),
                    _ => RodLinearized::new(&i.model, &self.static_loads),
                };
                let s = crate::solve::eigen::hang_off_stiffness6_in(&line, cfg, &mut w.storage);
                w.parts = Some(LinearizedParts::Rod(line.into_parts()));
                s
            }
            Engine::Cable(i) => {
                let line = match w.parts.take() {
                    Some(LinearizedParts::Cable(p)) => CableLinearized::from_parts(&i.model, p),
                    _ => CableLinearized::new(&i.model, self.static_loads.drag.is_some()),
                };
                let s = crate::solve::eigen::hang_off_stiffness6_in(&line, cfg, &mut w.storage);
                w.parts = Some(LinearizedParts::Cable(line.into_parts()));
                s
            }
        };
        Ok(s?)
    }

    /// [`Simulation::end_stiffness6`] in the storage `w` (sized on this
    /// line at its first call: a system FMU's directional derivative,
    /// docs/theory.md (17.19)), allocating nothing after it: the same
    /// numbers, the same bits.
    pub fn end_stiffness6_into(&self, w: &mut EndStiffnessScratch) -> Result<M6, RiserError> {
        let cfg = &self.state.config;
        let s = match &self.integrator {
            Engine::Rod(i) => {
                let line = match w.parts.take() {
                    Some(LinearizedParts::Rod(p)) => RodLinearized::from_parts(&i.model, &self.static_loads, p),
                    _ => RodLinearized::new(&i.model, &self.static_loads),
                };
                let s = crate::solve::eigen::end_stiffness6_shifted_in(&line, cfg, 0.0, &mut w.storage);
                w.parts = Some(LinearizedParts::Rod(line.into_parts()));
                s
            }
            Engine::Cable(i) => {
                let line = match w.parts.take() {
                    Some(LinearizedParts::Cable(p)) => CableLinearized::from_parts(&i.model, p),
                    _ => CableLinearized::new(&i.model, self.static_loads.drag.is_some()),
                };
                let s = crate::solve::eigen::end_stiffness6_shifted_in(&line, cfg, 0.0, &mut w.storage);
                w.parts = Some(LinearizedParts::Cable(line.into_parts()));
                s
            }
        };
        Ok(s?)
    }
}

/// What [`Simulation::end_stiffness6_into`] keeps between calls on one
/// line: its linearised model's owned parts and the storage of
/// [`crate::solve::eigen::end_stiffness6_shifted_in`].
#[derive(Default)]
pub struct EndStiffnessScratch {
    parts: Option<LinearizedParts>,
    storage: crate::solve::eigen::EndStiffnessStorage,
}

/// What [`Simulation::hang_off_stiffness6_into`] keeps between calls on
/// one line: its linearised model's owned parts and the storage of
/// [`crate::solve::eigen::hang_off_stiffness6_in`].
#[derive(Default)]
pub struct HangOffScratch {
    parts: Option<LinearizedParts>,
    storage: crate::solve::eigen::HangOffStorage,
}

enum LinearizedParts {
    Rod(crate::model::rod::statics::StaticParts),
    Cable(crate::model::cable::statics::CableStaticParts),
}

impl EndStiffnessScratch {
    /// The storage sized on `sim`'s line (at a system's set-up, so that
    /// its first [`Simulation::end_stiffness6_into`] allocates nothing
    /// either); empty, to be sized at the first call, if its band matrix
    /// cannot be had.
    pub fn for_line(sim: &Simulation) -> Self {
        use crate::solve::eigen::EndStiffnessStorage;
        match &sim.integrator {
            Engine::Rod(i) => {
                let line = RodLinearized::new(&i.model, &sim.static_loads);
                let storage = EndStiffnessStorage::for_line(&line).unwrap_or_default();
                EndStiffnessScratch { parts: Some(LinearizedParts::Rod(line.into_parts())), storage }
            }
            Engine::Cable(i) => {
                let line = CableLinearized::new(&i.model, sim.static_loads.drag.is_some());
                let storage = EndStiffnessStorage::for_line(&line).unwrap_or_default();
                EndStiffnessScratch { parts: Some(LinearizedParts::Cable(line.into_parts())), storage }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_communication_step_that_time_step_does_not_divide_takes_equal_internal_steps() {
        // 0.2 s at 0.119 s: two steps of 0.1 s, not 0.119 s and 0.081 s
        let n = internal_steps(0.2, 0.119).unwrap();
        assert_eq!(n, 2);
        assert!((even_internal_step(0.2, 0.119, n) - 0.1).abs() < 1e-15);
        // a multiple (as fmpy's steps give it, off by round-off): time_step itself, bit for bit
        let span = 3.0 * 0.2 - 2.0 * 0.2;
        let n = internal_steps(span, 0.05).unwrap();
        assert_eq!((n, even_internal_step(span, 0.05, n).to_bits()), (4, 0.05f64.to_bits()));
        // a remainder merged into the last step (MERGE_FRACTION) is spread over all of them
        assert!((even_internal_step(0.2005, 0.1, internal_steps(0.2005, 0.1).unwrap()) - 0.10025).abs() < 1e-15);
    }
}
