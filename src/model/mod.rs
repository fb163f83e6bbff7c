//! The models' layer (docs/theory.md §5, §6): what both line models share and
//! the seam the solvers use. [`rod`] and [`cable`] are each whole in their
//! folder; [`State`] is the serializable state of either (configuration,
//! velocities, work accumulators), [`StepEquations`] and
//! [`statics::StaticEquations`] the only doors the solvers go through.

pub mod cable;
pub mod catenary;
pub mod config;
pub mod dissipation;
pub mod linearized;
pub mod outputs;
pub mod rod;
pub mod sections;
pub mod serialize;
pub mod statics;

pub use config::RodConfig;
pub use outputs::Outputs;

use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{M3, V3};

/// Prescribed motion of the hang-off: displacement from its initial position
/// (m) and velocity (m/s), and the vessel's rotation since the static state
/// R (the active rotation, vessel frame to global) and angular velocity ω
/// (rad/s, global frame; docs/theory.md §14): a clamped end turns with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HangOff {
    pub displacement: V3,
    pub velocity: V3,
    pub rotation: M3,
    pub angular_velocity: V3,
}

impl Default for HangOff {
    /// At rest at the initial position, not rotated.
    fn default() -> Self {
        HangOff::translation(V3::zeros(), V3::zeros())
    }
}

impl HangOff {
    /// A translation of the hang-off without rotation.
    pub fn translation(displacement: V3, velocity: V3) -> Self {
        HangOff { displacement, velocity, rotation: M3::identity(), angular_velocity: V3::zeros() }
    }
}

/// The state of a run: everything needed to continue it (no scratch data).
#[derive(Debug, PartialEq, Default)]
pub struct State {
    /// Time, s.
    pub time: f64,
    pub config: RodConfig,
    /// ṙ at the end nodes, m/s.
    pub vel: Vec<V3>,
    /// ṙ' at the end nodes, 1/s.
    pub slope_vel: Vec<V3>,
    /// Director rates [ḋ1 ḋ2 ḋ3] at the director nodes, 1/s.
    pub director_vel: Vec<M3>,
    /// Mean velocities (r_{n} − r_{n−1})/h and (r'_{n} − r'_{n−1})/h of the
    /// last step, the predictor's velocities (free of the alternating part of
    /// unresolved stiff modes), m/s and 1/s.
    pub mean_vel: Vec<V3>,
    pub mean_slope_vel: Vec<V3>,
    /// The same of the step before and of the one before that (the
    /// predictor extrapolates cubically, §5.7).
    pub prev_mean_vel: Vec<V3>,
    pub prev_mean_slope_vel: Vec<V3>,
    pub prev2_mean_vel: Vec<V3>,
    pub prev2_mean_slope_vel: Vec<V3>,
    /// Hang-off motion at `time`.
    pub hang_off: HangOff,
    /// Work done on the line by the hang-off since t = 0, J.
    pub work_top: f64,
    /// Work done on the line by the water (drag, added mass) since t = 0, J.
    pub work_hydro: f64,
    /// Energy dissipated by structural damping since t = 0, J (≥ 0).
    pub dissipated: f64,
    /// Work of the anchor's twist reaction since t = 0, J (zero for lines
    /// moving in a vertical plane; docs/theory.md §5.5).
    pub work_anchor: f64,
    /// Energy removed by the high-frequency dissipation since t = 0, J (≥ 0; §5.10).
    pub algorithmic: f64,
    /// Work of the seabed's damping and friction on the line since t = 0, J (≤ 0; §7).
    pub work_seabed: f64,
    /// Velocity increments over the last step, (v_n − v_{n−1})/h, per velocity
    /// triple (the node velocities, then the slope velocities), m/s² and 1/s²:
    /// the history of the velocity filter's weights (§5.10).
    pub hf_accel: Vec<V3>,
    /// The velocity filter's weight of each triple for the next step (§5.10).
    pub hf_weight: Vec<f64>,
    /// Hermite acceleration dofs of the first and last element over the last
    /// step (for the end reactions), m/s².
    pub end_accel: [[V3; 4]; 2],
    /// Reactions of the supports on the line from the last step's midpoint
    /// equations (the force over the step, t_{n+½}), N.
    pub mid_reaction: [V3; 2],
    /// Internal steps taken (including sub-steps).
    pub steps: u64,
    /// Newton iterations over all steps.
    pub newton_iterations: u64,
    /// Steps that had to be split into sub-steps.
    pub retries: u64,
}

impl Clone for State {
    fn clone(&self) -> Self {
        let mut s = State::default();
        s.clone_from(self);
        s
    }

    /// Field by field, reusing this state's buffers (a time step copies the
    /// state into its trial state without allocating).
    fn clone_from(&mut self, o: &Self) {
        // destructured so that a new field cannot be forgotten
        let State {
            time,
            config,
            vel,
            slope_vel,
            director_vel,
            mean_vel,
            mean_slope_vel,
            prev_mean_vel,
            prev_mean_slope_vel,
            prev2_mean_vel,
            prev2_mean_slope_vel,
            hang_off,
            work_top,
            work_hydro,
            dissipated,
            work_anchor,
            algorithmic,
            work_seabed,
            hf_accel,
            hf_weight,
            end_accel,
            mid_reaction,
            steps,
            newton_iterations,
            retries,
        } = o;
        self.time = *time;
        self.config.clone_from(config);
        self.vel.clone_from(vel);
        self.slope_vel.clone_from(slope_vel);
        self.director_vel.clone_from(director_vel);
        self.mean_vel.clone_from(mean_vel);
        self.mean_slope_vel.clone_from(mean_slope_vel);
        self.prev_mean_vel.clone_from(prev_mean_vel);
        self.prev_mean_slope_vel.clone_from(prev_mean_slope_vel);
        self.prev2_mean_vel.clone_from(prev2_mean_vel);
        self.prev2_mean_slope_vel.clone_from(prev2_mean_slope_vel);
        self.hang_off = *hang_off;
        self.work_top = *work_top;
        self.work_hydro = *work_hydro;
        self.dissipated = *dissipated;
        self.work_anchor = *work_anchor;
        self.algorithmic = *algorithmic;
        self.work_seabed = *work_seabed;
        self.hf_accel.clone_from(hf_accel);
        self.hf_weight.clone_from(hf_weight);
        self.end_accel = *end_accel;
        self.mid_reaction = *mid_reaction;
        self.steps = *steps;
        self.newton_iterations = *newton_iterations;
        self.retries = *retries;
    }
}

impl State {
    /// A line at rest in `config` at time `time` (a cable's configuration
    /// has node positions only: no slopes, no directors).
    pub fn at_rest(config: RodConfig, time: f64) -> Self {
        let n = config.x.len();
        let np = config.xp.len();
        let nd = config.d.len();
        State {
            time,
            vel: vec![V3::zeros(); n],
            slope_vel: vec![V3::zeros(); np],
            director_vel: vec![M3::zeros(); nd],
            mean_vel: vec![V3::zeros(); n],
            mean_slope_vel: vec![V3::zeros(); np],
            prev_mean_vel: vec![V3::zeros(); n],
            prev_mean_slope_vel: vec![V3::zeros(); np],
            prev2_mean_vel: vec![V3::zeros(); n],
            prev2_mean_slope_vel: vec![V3::zeros(); np],
            hf_accel: vec![V3::zeros(); n + np],
            hf_weight: vec![0.0; n + np],
            config,
            ..Default::default()
        }
    }

    /// Hermite velocity dofs of element e.
    pub fn hermite_velocity(&self, e: usize) -> [V3; 4] {
        [self.vel[e], self.slope_vel[e], self.vel[e + 1], self.slope_vel[e + 1]]
    }

    /// Director rates at the three director nodes of element e.
    pub fn director_rates(&self, e: usize) -> [M3; 3] {
        [self.director_vel[2 * e], self.director_vel[2 * e + 1], self.director_vel[2 * e + 2]]
    }

    /// Gives the whole line the rigid velocity v + ω × (x − x0).
    pub fn set_rigid_velocity(&mut self, v: V3, omega: V3, x0: V3) {
        for a in 0..self.vel.len() {
            self.vel[a] = v + omega.cross(&(self.config.x[a] - x0));
        }
        // (a cable's state has no slopes and no directors)
        for a in 0..self.slope_vel.len() {
            self.slope_vel[a] = omega.cross(&self.config.xp[a]);
        }
        self.mean_vel.clone_from(&self.vel);
        self.mean_slope_vel.clone_from(&self.slope_vel);
        for j in 0..self.director_vel.len() {
            let d = self.config.d[j];
            self.director_vel[j] =
                M3::from_columns(&[omega.cross(&d.column(0)), omega.cross(&d.column(1)), omega.cross(&d.column(2))]);
        }
    }

    /// True if every number in the state is finite.
    pub fn is_finite(&self) -> bool {
        self.config.is_finite()
            && self.vel.iter().chain(self.slope_vel.iter()).all(|v| v.iter().all(|c| c.is_finite()))
            && self.director_vel.iter().all(|d| d.iter().all(|c| c.is_finite()))
            && self.hf_accel.iter().all(|v| v.iter().all(|c| c.is_finite()))
            && self.hf_weight.iter().all(|w| w.is_finite())
            && [
                self.time,
                self.work_top,
                self.work_hydro,
                self.work_anchor,
                self.dissipated,
                self.algorithmic,
                self.work_seabed,
            ]
            .iter()
            .all(|v| v.is_finite())
    }
}

/// Settings of the time stepping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicOptions {
    /// Internal time step, s.
    pub time_step: f64,
    /// Newton converges when the largest residual component is below this
    /// times the force scale (weight, or m L g without gravity).
    pub newton_tolerance: f64,
    /// Newton iterations before a step counts as failed.
    pub max_iterations: usize,
    /// How many times a failed step may be halved (1/2^n of `time_step`).
    pub max_halvings: u32,
    /// Kelvin–Voigt structural damping time η, s (0: energy-conserving).
    pub structural_damping: f64,
    /// High-frequency spectral radius of the scheme, (0, 1]; 1: the paper's
    /// energy–momentum conserving scheme (docs/theory.md §5.10).
    pub rho_infinity: f64,
    /// Steps a factorised tangent may be reused for (modified Newton; 0: a
    /// new tangent at every step, 1 per step and on slow convergence).
    pub max_tangent_age: u32,
    /// Express the Newton unknowns of each node in its current director
    /// frame, so that a reused tangent turns with the line (docs/theory.md
    /// §5.7); false: the global frame.
    pub corotated_tangent: bool,
    /// Order of the predictor's extrapolation of the centreline over the
    /// last steps ([`extrapolation`]): 3 cubic (the default since issue 28),
    /// 2 quadratic (the predictor before), 1 linear. The cable takes at
    /// most 2.
    pub predictor_order: u32,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        DynamicOptions {
            time_step: 0.05,
            newton_tolerance: 1e-8,
            max_iterations: 25,
            max_halvings: 6,
            structural_damping: 0.0,
            rho_infinity: 1.0,
            max_tangent_age: 20,
            corotated_tangent: true,
            predictor_order: 3,
        }
    }
}

/// Why a run stopped.
#[derive(Debug, Clone, PartialEq)]
pub enum DynamicsError {
    /// Newton did not converge even with the smallest sub-step.
    NotConverged { time: f64, step: f64, iterations: usize, residual: f64 },
    /// The tangent could not be factorised even with the smallest sub-step.
    Linear { time: f64, step: f64, error: LinearSolveError },
    /// Newton converged to a spurious root (a director turned by more than
    /// 90° in one step) even with the smallest sub-step.
    Inadmissible { time: f64, step: f64 },
    /// A bad request (non-finite input, non-positive step).
    BadInput(String),
    /// The converged step gave a state that is not finite (NaN or ±∞) even
    /// with the smallest sub-step.
    NonFinite { time: f64, step: f64 },
    /// The caller's bound on Newton iterations ([`crate::solve::newton::Integrator::set_work_bound`])
    /// was reached before the step converged (the FMU's bounded step, docs/theory.md §7.6).
    WorkBound { time: f64, iterations: u64 },
}

impl std::fmt::Display for DynamicsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DynamicsError::NotConverged { time, step, iterations, residual } => write!(
                f,
                "time step from t = {time:.6} s failed: Newton did not converge in {iterations} iterations \
                 (relative residual {residual:.3e}) even with sub-step {step:.3e} s; the state is kept at \
                 t = {time:.6} s (try a smaller time_step, more elements, or a gentler motion)"
            ),
            DynamicsError::Linear { time, step, error } => write!(
                f,
                "time step from t = {time:.6} s failed with sub-step {step:.3e} s: {error}; the state is kept \
                 at t = {time:.6} s"
            ),
            DynamicsError::NonFinite { time, step } => write!(
                f,
                "time step from t = {time:.6} s failed: even with sub-step {step:.3e} s the new state is not \
                 finite (NaN or infinite); the state is kept at t = {time:.6} s"
            ),
            DynamicsError::Inadmissible { time, step } => write!(
                f,
                "time step from t = {time:.6} s failed: even with sub-step {step:.3e} s Newton only finds a \
                 solution that turns a director by more than 90° in one step; the state is kept at \
                 t = {time:.6} s (try a smaller time_step or a gentler motion)"
            ),
            DynamicsError::BadInput(m) => write!(f, "bad input: {m}"),
            DynamicsError::WorkBound { time, iterations } => write!(
                f,
                "given up at t = {time:.6} s after {iterations} Newton iterations, the step's bound, before it \
                 converged; the state is kept at t = {time:.6} s"
            ),
        }
    }
}

impl std::error::Error for DynamicsError {}

/// The global linear system of a step, allocated once.
pub struct Linear {
    pub sys: BandedSystem,
    /// Residual of the step equations (rows of fixed unknowns included).
    pub r: Vec<f64>,
    /// Newton correction.
    pub du: Vec<f64>,
    /// Fixed unknowns, sorted.
    pub fixed: Vec<usize>,
}

impl Linear {
    pub fn new(sys: BandedSystem, mut fixed: Vec<usize>) -> Self {
        let n = sys.dim();
        fixed.sort_unstable();
        Linear { sys, r: vec![0.0; n], du: vec![0.0; n], fixed }
    }
}

/// The step equations of one line model, for the shared Newton iteration.
pub trait StepEquations {
    /// Scratch data of a step beyond the linear system, allocated once.
    type Workspace: Send;

    /// The workspace and the linear system (its pattern and fixed unknowns).
    fn workspace(&self) -> Result<(Self::Workspace, Linear), LinearSolveError>;
    /// Force scale of the convergence test (the submerged weight), N.
    fn force_scale(&self) -> f64;
    /// True if the hang-off end (S = 0) follows a prescribed motion.
    fn hang_off_prescribed(&self) -> bool;
    /// Prepares a step from `prev`: quantities of q_n the residual needs.
    fn begin(&self, ws: &mut Self::Workspace, prev: &State, options: &DynamicOptions);
    /// Predicted q_{n+1} in `trial` (`order` 3: cubic, 2: quadratic, 1:
    /// linear; [`extrapolation`]), the
    /// hang-off at `origin + target.displacement`.
    #[allow(clippy::too_many_arguments)]
    fn predict(
        &self,
        ws: &mut Self::Workspace,
        prev: &State,
        trial: &mut State,
        h: f64,
        origin: V3,
        target: HangOff,
        order: u32,
    );
    /// Round-off level of the residual at `cfg` for a step of `h` s, N: the
    /// internal forces' and the inertia's (which grows as 1/h²,
    /// [`inertia_roundoff`]).
    fn residual_roundoff(&self, cfg: &RodConfig, h: f64) -> f64;
    /// Residual of the step equations at `cfg` into `lin.r` and, if
    /// `tangent`, its derivative into `lin.sys`; `eta` the damping time, s.
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        &self,
        ws: &mut Self::Workspace,
        lin: &mut Linear,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
        eta: f64,
        tangent: bool,
    );
    /// Largest free residual component in force units, N (∞ if not finite).
    fn residual_norm(&self, lin: &Linear) -> f64;
    /// cfg ← cfg ⊕ `lin.du` (limited where the model needs it).
    fn apply_increment(&self, ws: &mut Self::Workspace, lin: &mut Linear, prev: &State, cfg: &mut RodConfig);
    /// Whether a converged step from `prev` to `cfg` is one the scheme's
    /// properties hold for (default: every converged step).
    fn step_is_admissible(&self, _prev: &State, _cfg: &RodConfig) -> bool {
        true
    }
    /// The Newton correction `v` (a right-hand side, spatial components)
    /// into the basis the tangent is assembled in at `cfg` (default: the same).
    fn to_tangent_basis(&self, _ws: &Self::Workspace, _cfg: &RodConfig, _v: &mut [f64]) {}
    /// The inverse of [`StepEquations::to_tangent_basis`]: back to spatial components.
    fn to_spatial_basis(&self, _ws: &Self::Workspace, _cfg: &RodConfig, _v: &mut [f64]) {}
    /// Velocities (with the high-frequency filter, §5.10), work and end data
    /// of the converged step into `trial`.
    fn finish(&self, ws: &mut Self::Workspace, prev: &State, trial: &mut State, h: f64, options: &DynamicOptions);
}

/// Round-off of the inertia part of a step residual, N: a node's inertial
/// force is about 2 m l (Δx − h v)/h² (m the mass per length with the added
/// mass, kg/m, l the element length, m), and Δx = x_{n+1} − x_n of
/// coordinates as large as `extent` m carries a round-off of ε·extent. It
/// exceeds the internal forces' round-off for steps below a few milliseconds.
pub fn inertia_roundoff(mass_per_length: f64, element_length: f64, extent: f64, h: f64) -> f64 {
    2.0 * mass_per_length * element_length * f64::EPSILON * extent / (h * h)
}

/// The predictor's weights of the last three steps' mean velocities
/// [v̄_n, v̄_{n−1}, v̄_{n−2}]: r_{n+1} = r_n + h Σ wᵢ v̄ᵢ, the polynomial through
/// the last `order` + 1 positions at equal steps taken on to t_{n+1}
/// (order 3: cubic, 2: quadratic, otherwise linear; §5.7).
pub fn extrapolation(order: u32) -> [f64; 3] {
    match order {
        3.. => [3.0, -3.0, 1.0],
        2 => [2.0, -1.0, 0.0],
        _ => [1.0, 0.0, 0.0],
    }
}

/// A prescribed position (m, the line's frame) and velocity (m/s) of a
/// line's anchor end (S = L) at the end of a step: a system's free point
/// moving a cable's or a rod's end (docs/theory.md §17.7, §17.11).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnchorMotion {
    pub position: V3,
    pub velocity: V3,
}
