//! The dynamics of a system of lines on one vessel (issue 49; docs/theory.md
//! §17.5). With every line between a fixed point and a vessel point, the
//! lines meet only at the vessel, whose motion is prescribed (the CLI's
//! harmonics, the FMU's inputs): each line is then its own single-line run
//! ([`Simulation`] of [`SystemScene::line_scene`], its hang-off at its vessel
//! point ρ, moved by the vessel's motion as a single line's is, §14), and the
//! system's loads on the vessel are the sums of the lines' (17.11). Its energy
//! balance is the sum of the lines' (17.12).
//!
//! The lines are stepped on threads ([`SystemRun::for_each_line`]): a line's
//! arithmetic is the same on any thread and no line reads another's state,
//! so the bits are the same on any number of threads.
//!
//! Free points (joints, clump weights, buoys) are point masses coupled to
//! the ends of their lines by the same midpoint scheme (§17.7): at each
//! step, Newton on their end-of-step positions, each line attached stepped
//! with its end there and giving its end reaction and its step tangent
//! condensed on its ends ([`SystemRun::advance_to`]).

use super::Simulation;
use super::error::RiserError;
use super::system::{POINT_CONTACT_AREA, condense_in_place, condensed_stiffness6_of, solve_system};
use super::vessel::{Vessel, VesselLoads, VesselMotion};
use super::{EndStiffnessScratch, HangOffScratch};
use crate::loads::current::Current;
use crate::loads::waves::{Ramp, Sea, WaterPoint};
use crate::math::{M3, V3};
use crate::model::AnchorMotion;
use crate::model::{HangOff, Outputs, State};
use crate::scene::system::{Floater, PointKind, PointSpec, SystemScene, VesselEnd};
use crate::scene::{Model, Scene};
use std::sync::Mutex;

/// Where a line's end is held in a dynamic run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndAt {
    /// On the vessel, moved by its motion.
    Vessel,
    /// At a fixed point.
    Fixed,
    /// At the `k`-th free point of the run ([`FreePoints::points`]).
    Free(usize),
}

/// What holds a line's two ends in a run, and its frame's origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineEnds {
    /// What holds its hang-off (node 0) and its anchor (its last node).
    pub hang_off_at: EndAt,
    pub anchor_at: EndAt,
    /// Its frame's origin, global: its hang-off at rest, m.
    pub origin: V3,
}

impl LineEnds {
    /// True if its hang-off is on the vessel: its force on its hang-off is a
    /// load on the vessel (a free point's lines pull the point instead).
    pub fn on_vessel(&self) -> bool {
        self.hang_off_at == EndAt::Vessel
    }

    /// True if an end is at a free point: it steps with the points (§17.7).
    pub fn coupled(&self) -> bool {
        matches!(self.hang_off_at, EndAt::Free(_)) || matches!(self.anchor_at, EndAt::Free(_))
    }
}

/// One line of a system in a dynamic run.
pub struct LineRun {
    pub name: String,
    /// Which of its ends is on the vessel (its `from` or its `to`).
    pub vessel_end: VesselEnd,
    /// The single-line scene it is (its frame at its vessel point at rest).
    pub scene: Scene,
    pub sim: Simulation,
    /// What holds its ends, and its frame's origin.
    pub ends: LineEnds,
}

/// The hang-off motion at time s (s) of a line's vessel end, the line's
/// [`Vessel`] (its vessel point) given: the command line's harmonics
/// through [`Vessel::hang_off`], the FMU's input path at the line's offset.
pub type VesselPath<'a> = dyn Fn(&Vessel, f64) -> HangOff + Sync + 'a;

/// A trial step of a line with a free end (§17.7), in storage allocated
/// once: the line's state at the step's start and at its end, the
/// reactions of its supports on it at its hang-off and its anchor (the end
/// rows of its midpoint equations, N, in the end state), and its step
/// tangent condensed on its two ends' positions (6×6 row-major: [hang-off;
/// anchor], N/m, global), from its step tangent condensed on all its
/// prescribed unknowns (`fixed`, a rod's anchor twist among them, in the
/// basis its tangent is assembled in), whose rows and columns `at` are its
/// ends' positions.
pub struct TrialSlot {
    ends: LineEnds,
    start: State,
    state: State,
    condensed: [f64; 36],
    fixed: Vec<f64>,
    at: [usize; 6],
    result: Result<(), RiserError>,
}

impl TrialSlot {
    /// Steps `sim`'s line from the slot's start to `t` with its free ends at
    /// the points' end-of-step positions `x1` and velocities `v1` (global),
    /// its vessel end on `vessel_path`: the line's own state untouched.
    fn run(&mut self, sim: &mut Simulation, t: f64, vessel_path: &VesselPath, x1: &[V3], v1: &[V3]) {
        self.result = self.try_run(sim, t, vessel_path, x1, v1);
    }

    fn try_run(
        &mut self,
        sim: &mut Simulation,
        t: f64,
        vessel_path: &VesselPath,
        x1: &[V3],
        v1: &[V3],
    ) -> Result<(), RiserError> {
        let prev = &self.start;
        let h = t - prev.time;
        let vessel = sim.vessel;
        let origin = self.ends.origin;
        let hang_off = match self.ends.hang_off_at {
            EndAt::Free(k) => HangOff::translation(x1[k] - origin, v1[k]),
            _ => vessel_path(&vessel, t),
        };
        let anchor = match self.ends.anchor_at {
            EndAt::Free(k) => Some(AnchorMotion { position: x1[k] - origin, velocity: v1[k] }),
            _ => None,
        };
        sim.integrator.set_anchor_motion(anchor);
        let free_hang_off = matches!(self.ends.hang_off_at, EndAt::Free(_));
        let target = |s: f64| if free_hang_off { hang_off } else { vessel_path(&vessel, s) };
        self.state.clone_from(prev);
        sim.integrator.step(&mut self.state, h, &target)?;
        self.state.time = t;
        sim.integrator
            .condensed_end_tangent_into(
                prev,
                &self.state.config,
                h,
                hang_off,
                &self.at,
                &mut self.fixed,
                &mut self.condensed,
            )
            .map_err(|error| crate::model::DynamicsError::Linear { time: prev.time, step: h, error })?;
        Ok(())
    }
}

/// A system's lines as its free points' stepper reaches them: the command
/// line's [`LineRun`]s, the FMU's instance line and its others.
pub trait LineSet {
    /// Line `i`'s run.
    fn sim(&mut self, i: usize) -> &mut Simulation;

    /// Line `i`'s name.
    fn name(&self, i: usize) -> &str;

    /// `f` on every line that has a slot in `slots` (indexed as the lines)
    /// with its slot, on up to `threads` threads; here in order on this one,
    /// allocating nothing.
    fn each_slot(
        &mut self,
        slots: &mut [Option<TrialSlot>],
        threads: usize,
        f: &(dyn Fn(&mut Simulation, &mut TrialSlot) + Sync),
    ) {
        let _ = threads;
        for (i, slot) in slots.iter_mut().enumerate() {
            if let Some(slot) = slot {
                f(self.sim(i), slot);
            }
        }
    }
}

impl LineSet for Vec<LineRun> {
    fn sim(&mut self, i: usize) -> &mut Simulation {
        &mut self[i].sim
    }

    fn name(&self, i: usize) -> &str {
        &self[i].name
    }

    /// On threads, the dearest lines first.
    fn each_slot(
        &mut self,
        slots: &mut [Option<TrialSlot>],
        threads: usize,
        f: &(dyn Fn(&mut Simulation, &mut TrialSlot) + Sync),
    ) {
        let items: Vec<(usize, (&mut LineRun, &mut TrialSlot))> = self
            .iter_mut()
            .zip(slots.iter_mut())
            .enumerate()
            .filter_map(|(i, (l, s))| s.as_mut().map(|s| (i, (l, s))))
            .collect();
        on_threads(items, threads, &|(l, _)| l.cost(), &|_, (l, s)| f(&mut l.sim, s));
    }
}

impl LineRun {
    /// The tensions at the line's `from` and `to` ends of outputs `o` of its run, N.
    pub fn tensions(&self, o: &Outputs) -> (f64, f64) {
        match self.vessel_end {
            VesselEnd::From => (o.top_tension, o.bottom_tension),
            VesselEnd::To => (o.bottom_tension, o.top_tension),
        }
    }

    /// The static tensions at its `from` and `to` ends, N.
    pub fn static_tensions(&self) -> (f64, f64) {
        let s = &self.sim.statics;
        match self.vessel_end {
            VesselEnd::From => (s.top_tension, s.bottom_tension),
            VesselEnd::To => (s.bottom_tension, s.top_tension),
        }
    }

    /// Advances the line to `t` (s) with the vessel on `motion`.
    pub fn advance_to(&mut self, t: f64, motion: &(dyn Fn(f64) -> VesselMotion + Sync)) -> Result<(), RiserError> {
        let vessel = self.sim.vessel;
        let hang_off = |t: f64| -> HangOff { vessel.hang_off(&motion(t)) };
        self.sim.advance_to(t, &hang_off)
    }

    /// True if its hang-off is on the vessel ([`LineEnds::on_vessel`]).
    pub fn on_vessel(&self) -> bool {
        self.ends.on_vessel()
    }

    /// True if an end is at a free point ([`LineEnds::coupled`]).
    pub fn coupled(&self) -> bool {
        self.ends.coupled()
    }

    /// What a step of the line costs, roughly (the order the lines are handed
    /// to threads in: the dearest first): the rod's node carries six unknowns
    /// and its Gauss points the sections' work, the cable's three.
    fn cost(&self) -> usize {
        let n = self.scene.analysis.n_elements;
        match self.scene.analysis.model {
            Model::Rod => 4 * n,
            Model::Cable => n,
        }
    }
}

/// A line that failed, named.
#[derive(Debug)]
pub struct LineError {
    pub line: String,
    pub error: RiserError,
}

impl std::fmt::Display for LineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line '{}': {}", self.line, self.error)
    }
}

/// Why a step of a system failed: a line, or the free points' Newton.
#[derive(Debug)]
pub enum SystemStepError {
    Line(LineError),
    Points(PointsDiverged),
}

pub use super::error::PointsDiverged;

impl std::fmt::Display for SystemStepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SystemStepError::Line(e) => e.fmt(f),
            SystemStepError::Points(e) => e.fmt(f),
        }
    }
}

impl From<LineError> for SystemStepError {
    fn from(e: LineError) -> Self {
        SystemStepError::Line(e)
    }
}

/// Why a step of the free points failed, unnamed (a step that is split
/// again allocates nothing): line `i`'s trial, or the points' Newton from
/// `time`, point `point` the furthest from balance.
enum StepFailed {
    Line(usize, RiserError),
    Points { time: f64, residual: f64, point: usize },
}

/// The most Newton iterations on the free points' positions in a step.
pub const MAX_POINT_ITERATIONS: usize = 30;

/// The most halvings of a step of the free points and their lines (as a
/// line's own `max_halvings`, 6 by default: h/64).
pub const MAX_POINT_HALVINGS: u32 = 6;

/// A free point in a dynamic run (§17.7): a point mass with added mass,
/// weight, buoyancy, drag and the seabed's contact, at the ends of its lines.
#[derive(Debug, Clone)]
pub struct FreePointRun {
    pub name: String,
    /// Mass m and added mass m_a = C_a ρ V, kg.
    pub mass: f64,
    pub added_mass: f64,
    /// Displaced volume V, m³, and drag area C_d A, m².
    pub volume: f64,
    pub cd_area: f64,
    /// How its volume meets the surface: a point, or a cylinder of a
    /// height (§17.10).
    pub floater: Floater,
    /// Its submerged fraction over the step (§17.10: at its predicted
    /// midpoint, held over the Newton iterations; 1 for a point, whose
    /// buoyancy alone meets the surface), scaling its drag, added mass and
    /// the waves' inertia on it.
    wet: f64,
    /// Position and velocity at the run's time (global), m and m/s.
    pub position: V3,
    pub velocity: V3,
    /// Where the statics put it, m.
    pub static_position: V3,
    /// Mean velocities Δx/h of the last two steps (the predictor's), m/s.
    mean_vel: [V3; 2],
    /// Work of the water (drag, added mass) on it since the start, J.
    pub work_hydro: f64,
    /// Work of its lines on it since the start, J: the minus of the work
    /// of its ends on the lines (their `work_top` or `work_anchor`), so
    /// internal to the system.
    pub work_lines: f64,
    /// Its energy ½ m v² + U at the start, J (17.13).
    pub initial_energy: f64,
    water_density: f64,
    gravity: f64,
    surface_z: f64,
    /// The seabed: its height at x = 0, tan of its slope, the contact spring k_b A_p (N/m).
    bed: Option<(f64, f64, f64)>,
    /// The current (as its lines see it: a depth profile from the surface
    /// in the frame of the line at `current_frame_z`, `linear_s` at arc
    /// length `current_s` of that line), and its ramp from the start.
    current: Current,
    current_frame_z: f64,
    current_s: f64,
    current_ramp: Ramp,
    /// The sea (None: still water) in the frame of the line at `sea_origin`
    /// (the line's sea, its ramp from the start), and the water's motion
    /// at the step's predicted midpoint, held over the step (§13.6).
    sea: Option<Sea>,
    sea_origin: V3,
    water: WaterPoint,
}

impl FreePointRun {
    /// Potential energy U(x) = m g z + U_b(z) + U_c(x), J (17.13): weight,
    /// buoyancy below the water surface U_b = −ρ g V min(z, z_s), the
    /// seabed's contact U_c = ½ k_p ((h(x) − z)⁺)².
    pub fn potential(&self, x: V3) -> f64 {
        let ub = match self.floater.height {
            None => -self.water_density * self.gravity * self.volume * x.z.min(self.surface_z),
            // −ρ g Q(z − z_s) (17.24)
            Some(_) => -self.water_density * self.gravity * self.floater.potential(x.z - self.surface_z),
        };
        let uc = self.bed.map_or(0.0, |(z0, t, kp)| 0.5 * kp * (z0 + t * x.x - x.z).max(0.0).powi(2));
        self.mass * self.gravity * x.z + ub + uc
    }

    /// Its state as numbers (a saved FMU state): position, velocity, the
    /// predictor's two mean velocities, the water's and the lines' work
    /// on it (its energy at the start is taken again at the start).
    pub fn values(&self) -> [f64; POINT_VALUES] {
        let mut v = [0.0; POINT_VALUES];
        for (k, x) in [self.position, self.velocity, self.mean_vel[0], self.mean_vel[1]].iter().enumerate() {
            v[3 * k..3 * k + 3].copy_from_slice(x.as_slice());
        }
        v[12] = self.work_hydro;
        v[13] = self.work_lines;
        v
    }

    /// The state of [`FreePointRun::values`].
    pub fn set_values(&mut self, v: &[f64; POINT_VALUES]) {
        let at = |k: usize| V3::new(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
        (self.position, self.velocity, self.mean_vel) = (at(0), at(1), [at(2), at(3)]);
        (self.work_hydro, self.work_lines) = (v[12], v[13]);
    }

    /// −∂f/∂x of its own static load (17.4) at its position, N/m: the
    /// seabed's contact where it is in it (the weight and the buoyancy are
    /// constant below the surface, as in the statics), and a floating
    /// cylinder's waterplane stiffness ρ g A (17.23).
    pub fn load_stiffness(&self) -> M3 {
        let mut k = M3::zeros();
        if self.floater.height.is_some() {
            let (_, dv) = self.floater.displaced(self.position.z - self.surface_z);
            k[(2, 2)] = -self.water_density * self.gravity * dv;
        }
        if let Some((z0, t, kp)) = self.bed
            && z0 + t * self.position.x - self.position.z > 0.0
        {
            // f_z = k_p (h(x) − z), h(x) = z0 + tan x
            k[(2, 2)] += kp;
            k[(2, 0)] = -kp * t;
        }
        k
    }

    /// ½ m |v|² + U(x), J (the added mass's kinetic energy is the water's: §5.4).
    pub fn energy(&self) -> f64 {
        0.5 * self.mass * self.velocity.norm_squared() + self.potential(self.position)
    }

    /// E − E(0) − W_hydro − W_lines, J: the point's part of the system's
    /// energy balance (17.17).
    pub fn energy_balance_residual(&self) -> f64 {
        self.energy() - self.initial_energy - self.work_hydro - self.work_lines
    }

    /// The waves' velocity and acceleration (m/s, m/s²; ramped) at the
    /// point's midpoint predicted for the step, `x_pred` its predicted end,
    /// at `t_mid`, kept for the step's rows (as a line's Gauss points take
    /// them, §13.6: held over the Newton iterations); still water without a sea.
    /// A cylinder (§17.10) takes them at the centre of its part below the
    /// still water line, and its submerged fraction at the predicted
    /// midpoint under the waves' elevation there.
    fn freeze_water(&mut self, x_pred: V3, t_mid: f64) {
        let mut at = (self.position + x_pred) * 0.5;
        let mid = at.z;
        if let Some(h) = self.floater.height {
            let (bottom, top) = (at.z - 0.5 * h, (at.z + 0.5 * h).min(self.surface_z));
            if top > bottom {
                at.z = 0.5 * (bottom + top);
            }
        }
        self.water = match &self.sea {
            Some(sea) => sea.water(&(at - self.sea_origin), t_mid),
            None => WaterPoint::STILL,
        };
        if self.floater.height.is_some() {
            self.wet = self.floater.submerged(mid - self.surface_z - self.water.elevation);
        }
    }

    /// The point's own rows of the step (17.14) at the end-of-step position
    /// `x1` from the start of the step (`self`), step `h`, midpoint time
    /// `t_mid`: the inertia less the weight, buoyancy, contact and water, its
    /// derivative with respect to x1 (the contact's and the drag's at the
    /// midpoint: a quasi-Newton), and the water's force (drag, added mass,
    /// the waves' inertia: 17.18), N.
    fn own_rows(&self, x1: V3, h: f64, t_mid: f64) -> (V3, M3, V3) {
        let (x0, v0) = (self.position, self.velocity);
        let dx = x1 - x0;
        let v1 = dx * (2.0 / h) - v0;
        let dv = (v1 - v0) / h;
        let mut r = dv * self.mass;
        let added_mass = self.added_mass * self.wet;
        let mut k = M3::identity() * ((self.mass + added_mass) * 2.0 / (h * h));
        // weight (linear: exact)
        r.z += self.mass * self.gravity;
        // buoyancy: the discrete gradient of U_b (a step in its slope at z_s)
        let rho_g = self.water_density * self.gravity;
        // a cylinder's in waves beyond the still water's: the water's (17.25)
        let mut f_wave_buoyancy = 0.0;
        match self.floater.height {
            None => {
                let rho_g_v = rho_g * self.volume;
                let ub = |z: f64| -rho_g_v * z.min(self.surface_z);
                let fb = if (x1.z - x0.z).abs() > 0.0 && (x0.z.max(x1.z) > self.surface_z) {
                    -(ub(x1.z) - ub(x0.z)) / (x1.z - x0.z)
                } else if x0.z.max(x1.z) <= self.surface_z {
                    rho_g_v
                } else {
                    0.0
                };
                r.z -= fb;
            }
            Some(_) => {
                let (z0, z1) = (x0.z - self.surface_z, x1.z - self.surface_z);
                let eta = self.water.elevation;
                let (still, d_still) = self.floater.mean_displaced(z0, z1);
                r.z -= rho_g * still;
                if eta != 0.0 {
                    let (cut, d_cut) = self.floater.mean_displaced(z0 - eta, z1 - eta);
                    f_wave_buoyancy = rho_g * (cut - still);
                    k[(2, 2)] -= rho_g * d_cut;
                } else {
                    k[(2, 2)] -= rho_g * d_still;
                }
            }
        }
        // the seabed: U_c of the penetration p = h(x) − z, linear in x (a
        // discrete gradient in p, along ∇p = (tan, 0, −1))
        if let Some((z0, t, kp)) = self.bed {
            let p = |x: V3| z0 + t * x.x - x.z;
            let (p0, p1) = (p(x0), p(x1));
            if p0 > 0.0 || p1 > 0.0 {
                let uc = |p: f64| 0.5 * kp * p.max(0.0).powi(2);
                let slope = if (p1 - p0).abs() > 1e-12 {
                    (uc(p1) - uc(p0)) / (p1 - p0)
                } else {
                    kp * (0.5 * (p0 + p1)).max(0.0)
                };
                let grad = V3::new(t, 0.0, -1.0);
                // f_c = −slope ∇p
                r += grad * slope;
                if 0.5 * (p0 + p1) > 0.0 {
                    k += grad * grad.transpose() * (0.5 * kp);
                }
            }
        }
        // water: drag on the velocity relative to the current and the
        // waves at the midpoint, v½ = Δx/h, the added mass's inertia (§5.4)
        // and the waves' (Froude–Krylov and added mass, 17.18)
        let xm = (x0 + x1) * 0.5;
        let u = self.current.velocity(self.current_s, xm.z - self.current_frame_z).0 * self.current_ramp.at(t_mid).0
            + self.water.velocity;
        let w = u - dx / h;
        let c = 0.5 * self.water_density * self.cd_area * self.wet;
        let wn = w.norm();
        let inertia = self.water_density * self.volume * self.wet + added_mass;
        let mut f_water = w * (c * wn) + self.water.acceleration * inertia - dv * added_mass;
        if f_wave_buoyancy != 0.0 {
            f_water.z += f_wave_buoyancy;
        }
        if c > 0.0 && wn > 0.0 {
            k += (M3::identity() * wn + w * w.transpose() / wn) * (c / h);
        }
        r -= f_water;
        (r, k, f_water)
    }
}

/// A system set up for a dynamic run, every line in its static equilibrium
/// at the neutral pose (and the free points in theirs, at rest).
pub struct SystemRun {
    pub lines: Vec<LineRun>,
    /// The free points and their stepper (none: every line on its own).
    pub free: FreePoints,
    /// The run's time, s.
    pub time: f64,
}

/// The numbers of a free point's state in a saved FMU state ([`FreePointRun::values`]).
pub const POINT_VALUES: usize = 14;

/// A system's free points in a dynamic run and what steps them with their
/// lines (§17.7), its storage allocated once ([`FreePoints::advance`]
/// allocates nothing when its lines are handed to it one at a time, as the
/// FMU does).
pub struct FreePoints {
    /// The free points, in the scene's order.
    pub points: Vec<FreePointRun>,
    /// What holds each line's ends, every line of the system in its order.
    pub ends: Vec<LineEnds>,
    /// Each line with an end at a free point: its trial (None: the others).
    slots: Vec<Option<TrialSlot>>,
    /// The points' Newton (17.16): end-of-step positions x⁺ and velocities
    /// v⁺, residuals, their force scales, the water's forces, the lines'
    /// reactions, the Jacobian (3 n_p square, row-major) and the right-hand side.
    x1: Vec<V3>,
    v1: Vec<V3>,
    r: Vec<V3>,
    scale: Vec<f64>,
    f_water: Vec<V3>,
    reactions: Vec<V3>,
    jac: Vec<f64>,
    rhs: Vec<f64>,
    /// The points' states at a checkpoint ([`FreePoints::checkpoint`]).
    saved: Vec<[f64; POINT_VALUES]>,
    /// The storage of [`FreePoints::condensed_stiffness6`].
    stiffness: CondensedScratch,
    /// The points' time, s.
    pub time: f64,
    /// Newton iterations on the free points' positions since the start.
    pub point_iterations: u64,
    /// The lines' Newton iterations in the free points' trials, every trial's.
    pub trial_iterations: u64,
}

/// Each line of `sys` set up for a dynamic run ([`SystemRun::new`]): its
/// single-line run from its statics at the neutral pose (the lines' statics
/// as `riser statics SYSTEM` solves them, §17.1); with free points, the
/// system's statics (§17.4): the points in equilibrium at rest, each line
/// with a free end from its state there; and the free points.
pub fn build(sys: &SystemScene) -> Result<(Vec<LineRun>, FreePoints), String> {
    build_at(sys, &[0.0; 6])
}

/// [`build`] with the free points and their lines in the system's statics
/// with the vessel at `pose` (surge, sway, heave, roll, pitch, yaw; m, rad,
/// z-y-x), the lines between a fixed and a vessel point at the neutral
/// pose's (the caller moves them, as a single line's start is moved, §7.7).
/// Each line keeps its frame at its vessel point at rest (a line hung from
/// the vessel: its state from the pose's statics translated into that
/// frame, its hang-off then where the vessel's start puts it).
pub fn build_at(sys: &SystemScene, pose: &[f64; 6]) -> Result<(Vec<LineRun>, FreePoints), String> {
    let free: Vec<&PointSpec> = sys.points.iter().filter(|p| p.kind == PointKind::Free).collect();
    let statics = if free.is_empty() { None } else { Some(solve_system(sys, pose, false)?) };
    let at = |p: &PointSpec| match p.kind {
        PointKind::Vessel => EndAt::Vessel,
        PointKind::Fixed => EndAt::Fixed,
        PointKind::Free => EndAt::Free(free.iter().position(|f| f.name == p.name).expect("a free point")),
    };
    let mut lines = Vec::with_capacity(sys.lines.len());
    for (i, l) in sys.lines.iter().enumerate() {
        let (vessel_end, vp, ap) = sys.ends(i);
        let (hang_off_at, anchor_at) = (at(vp), at(ap));
        let coupled = matches!(hang_off_at, EndAt::Free(_)) || matches!(anchor_at, EndAt::Free(_));
        let named = |e: &dyn std::fmt::Display| format!("line '{}': {e}", l.name);
        let (scene, sim, origin) = match (&statics, coupled) {
            (Some(st), true) => {
                // its state at the free points' equilibrium, in its frame at rest
                let ls = &st.lines[i];
                let origin = if hang_off_at == EndAt::Vessel { V3::from(vp.position) } else { ls.fairlead };
                let scene = sys.line_scene_at(i, origin, ls.anchor);
                let report = translated(ls.report.clone(), ls.fairlead - origin);
                let mut sim = Simulation::from_statics(&scene, report).map_err(|e| named(&e))?;
                // a failed trial is the points' step's to split, not the line's
                sim.integrator.options_mut().max_halvings = 0;
                (scene, sim, origin)
            }
            _ => {
                // at the neutral pose the vessel point is at ρ
                let scene = sys.line_scene(i, V3::from(vp.position));
                let sim = Simulation::from_scene(&scene).map_err(|e| named(&e))?;
                (scene, sim, V3::from(vp.position))
            }
        };
        let ends = LineEnds { hang_off_at, anchor_at, origin };
        lines.push(LineRun { name: l.name.clone(), vessel_end, scene, sim, ends });
    }
    let mut points = Vec::with_capacity(free.len());
    for (k, p) in free.iter().enumerate() {
        let st = &statics.as_ref().expect("free points have statics").points[k];
        let env = &sys.environment;
        // the current as the first line at the point sees it
        let l = lines
            .iter()
            .find(|l| l.ends.hang_off_at == EndAt::Free(k) || l.ends.anchor_at == EndAt::Free(k))
            .expect("a free point has a line");
        let current_s = if l.ends.hang_off_at == EndAt::Free(k) { 0.0 } else { l.scene.line.length };
        let bed = sys.seabed.as_ref().map(|b| (b.z, b.slope.to_radians().tan(), b.stiffness * POINT_CONTACT_AREA));
        let mut point = FreePointRun {
            name: p.name.clone(),
            mass: p.mass(),
            added_mass: p.ca() * env.water_density * p.volume(),
            volume: p.volume(),
            cd_area: p.cd_area(),
            floater: p.floater(),
            wet: 1.0,
            position: st.position,
            velocity: V3::zeros(),
            static_position: st.position,
            mean_vel: [V3::zeros(); 2],
            work_hydro: 0.0,
            work_lines: 0.0,
            initial_energy: 0.0,
            water_density: env.water_density,
            gravity: env.gravity,
            surface_z: env.water_surface_z,
            bed,
            current: crate::loads::current(&l.scene),
            current_frame_z: l.ends.origin.z,
            current_s,
            current_ramp: crate::loads::current_ramp(&l.scene),
            sea: l.sim.sea.clone(),
            sea_origin: l.ends.origin,
            water: WaterPoint::STILL,
        };
        point.initial_energy = point.energy();
        points.push(point);
    }
    let ends = lines.iter().map(|l| l.ends).collect();
    let sims: Vec<&Simulation> = lines.iter().map(|l| &l.sim).collect();
    let free = FreePoints::new(points, ends, &sims);
    Ok((lines, free))
}

/// A static state `report` moved by `d` (m): its configuration's and its
/// shape's positions (the same equilibrium in a frame moved by −d).
fn translated(mut report: super::report::StaticReport, d: V3) -> super::report::StaticReport {
    report.solution.config.x.iter_mut().for_each(|x| *x += d);
    for r in &mut report.shape {
        (r.x, r.y, r.z) = (r.x + d.x, r.y + d.y, r.z + d.z);
    }
    report
}

impl SystemRun {
    /// Each line's single-line run from its statics at the neutral pose and
    /// the free points in theirs ([`build`]).
    pub fn new(sys: &SystemScene) -> Result<Self, String> {
        let (lines, free) = build(sys)?;
        Ok(SystemRun { lines, free, time: 0.0 })
    }

    /// Puts every line's hang-off on the vessel's motion `m` at t = 0 (each
    /// line's [`Simulation::start`]; a free point's lines at the point, at
    /// rest) and takes the points' energy reference there.
    pub fn start(&mut self, m: &VesselMotion) {
        self.free.start_lines(&mut self.lines, &|v: &Vessel, _| v.hang_off(m));
        self.time = self.free.time;
    }

    /// Gives free point `k` the velocity `v` (m/s) and its lines' ends with
    /// it, and takes the energy references again (a kick to start a free
    /// oscillation from; the lines' other nodes keep theirs).
    pub fn set_point_velocity(&mut self, k: usize, v: V3) {
        self.free.points[k].velocity = v;
        for l in &mut self.lines {
            let s = &mut l.sim.state;
            if l.ends.hang_off_at == EndAt::Free(k) {
                s.vel[0] = v;
                s.hang_off.velocity = v;
            }
            if l.ends.anchor_at == EndAt::Free(k) {
                let n = s.vel.len() - 1;
                s.vel[n] = v;
            }
            l.sim.initial_energy = l.sim.integrator.outputs(&l.sim.state).total_energy;
        }
        for p in &mut self.free.points {
            p.initial_energy = p.energy();
        }
    }

    /// Calls `f` on every line, on up to `threads` threads (this one among
    /// them), the dearest lines first, and gives the results in the lines'
    /// order. One thread: in order on this one, nothing spawned.
    pub fn for_each_line<R: Send>(&mut self, threads: usize, f: &(dyn Fn(&mut LineRun) -> R + Sync)) -> Vec<R> {
        let n = self.lines.len();
        let all =
            on_threads(self.lines.iter_mut().enumerate().collect(), threads, &|l: &&mut LineRun| l.cost(), &|_, l| {
                f(l)
            });
        let mut results: Vec<Option<R>> = (0..n).map(|_| None).collect();
        for (i, r) in all {
            results[i] = Some(r);
        }
        results.into_iter().map(|r| r.expect("every line is taken from the queue once")).collect()
    }

    /// Advances every line to `t` (s) with the vessel on `motion`, on up to
    /// `threads` threads; the first failed line (in the system's order)
    /// named. With free points, the points and their lines first (§17.7),
    /// then the other lines.
    pub fn advance_to(
        &mut self,
        t: f64,
        motion: &(dyn Fn(f64) -> VesselMotion + Sync),
        threads: usize,
    ) -> Result<(), SystemStepError> {
        if !self.free.points.is_empty() {
            let path = |v: &Vessel, s: f64| v.hang_off(&motion(s));
            self.free.advance(&mut self.lines, t, &path, threads)?;
        }
        let free: Vec<(usize, &mut LineRun)> =
            self.lines.iter_mut().enumerate().filter(|(_, l)| !l.coupled()).collect();
        let mut results =
            on_threads(free, threads, &|l: &&mut LineRun| l.cost(), &|_, l: &mut LineRun| l.advance_to(t, motion));
        results.sort_by_key(|(i, _)| *i);
        for (i, r) in results {
            r.map_err(|error| LineError { line: self.lines[i].name.clone(), error })?;
        }
        self.time = t;
        Ok(())
    }

    /// The lines' loads on the vessel of their outputs `outputs` (one per
    /// line, in order), summed (17.11): the force and its moment about the
    /// reference point with the lines' end moments, global and in the
    /// vessel frame. (Every line's: for a system without free points; else
    /// [`SystemRun::resultant_on_vessel`].)
    pub fn resultant(outputs: &[Outputs]) -> VesselLoads {
        let mut sum = VesselLoads {
            force: V3::zeros(),
            moment: V3::zeros(),
            force_vessel: V3::zeros(),
            moment_vessel: V3::zeros(),
        };
        for o in outputs {
            sum.force += o.top_force;
            sum.moment += o.top_moment;
            sum.force_vessel += o.vessel_force;
            sum.moment_vessel += o.vessel_moment;
        }
        sum
    }

    /// [`SystemRun::resultant`] of the lines whose hang-off is on the vessel
    /// (a line hung from a free point pulls the point, not the vessel).
    pub fn resultant_on_vessel(&self, outputs: &[Outputs]) -> VesselLoads {
        let on: Vec<Outputs> = self.lines.iter().zip(outputs).filter(|(l, _)| l.on_vessel()).map(|(_, o)| *o).collect();
        Self::resultant(&on)
    }

    /// Every line's outputs now.
    pub fn outputs(&self) -> Vec<Outputs> {
        self.lines.iter().map(|l| l.sim.outputs()).collect()
    }

    /// The system's energy balance now (17.17).
    pub fn energy_balance(&self) -> SystemBalance {
        let mut b = SystemBalance::default();
        for l in &self.lines {
            let o = l.sim.outputs();
            b.energy += o.total_energy;
            b.initial_energy += l.sim.initial_energy;
            if l.on_vessel() {
                b.work_vessel += o.work_top;
            }
            b.work_water += o.work_hydro;
            b.work_seabed += o.work_seabed;
            // a cable's anchor at a free point: its work is internal
            if !matches!(l.ends.anchor_at, EndAt::Free(_)) {
                b.work_anchor += o.work_anchor;
            }
            b.dissipated += o.dissipated_energy + o.algorithmic_dissipation;
        }
        for p in &self.free.points {
            b.energy += p.energy();
            b.initial_energy += p.initial_energy;
            b.work_water += p.work_hydro;
        }
        b.residual =
            b.energy - b.initial_energy - b.work_vessel - b.work_water - b.work_seabed - b.work_anchor + b.dissipated;
        b
    }
}

/// Why the stiffness of a system with free points could not be had at a
/// state: a line's at its ends, or the free points' (17.8), singular.
#[derive(Debug)]
pub enum StiffnessError {
    Line(LineError),
    Singular,
}

impl std::fmt::Display for StiffnessError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StiffnessError::Line(e) => e.fmt(f),
            StiffnessError::Singular => write!(
                f,
                "the free points' stiffness is singular at the state (a point its lines do not hold in some \
                 direction)"
            ),
        }
    }
}

/// What [`FreePoints::condensed_stiffness6`] keeps between calls, sized
/// when the points are set up: each line's static tangent's storage, the
/// system's stiffness over the vessel ends and the points (17.7),
/// condensed in place (17.8).
pub struct CondensedScratch {
    /// The lines (the system's indices) hung from the vessel with an end at
    /// a free point, whose hang-offs K_c couples (3 unknowns each, first).
    pub lines: Vec<usize>,
    ends: Vec<EndStiffnessScratch>,
    /// The hang-off stiffness's storage of each line without a free end
    /// ([`FreePoints::hang_off_stiffness6`]).
    hang_offs: Vec<HangOffScratch>,
    /// K over the vessel ends and the points, row-major, n × n.
    k: Vec<f64>,
}

impl CondensedScratch {
    /// Sized on the system's lines `sims` (in its order) whose ends are `ends`, with `points` free points.
    fn new(ends: &[LineEnds], points: usize, sims: &[&Simulation]) -> Self {
        let lines: Vec<usize> = (0..ends.len()).filter(|&i| ends[i].coupled() && ends[i].on_vessel()).collect();
        let n = 3 * (lines.len() + points);
        let each = ends
            .iter()
            .zip(sims)
            .map(
                |(e, sim)| {
                    if e.coupled() { EndStiffnessScratch::for_line(sim) } else { EndStiffnessScratch::default() }
                },
            )
            .collect();
        let hang_offs = ends.iter().map(|_| HangOffScratch::default()).collect();
        CondensedScratch { lines, ends: each, hang_offs, k: vec![0.0; n * n] }
    }
}

impl FreePoints {
    /// Line `i`'s (without a free end) 6×6 tangent stiffness at its
    /// hang-off, `sim` its run ([`Simulation::hang_off_stiffness6_into`],
    /// in this system's storage): allocating nothing after its first call
    /// (but for a rod with a flex joint).
    pub fn hang_off_stiffness6(&mut self, i: usize, sim: &Simulation) -> Result<crate::math::M6, RiserError> {
        sim.hang_off_stiffness6_into(&mut self.stiffness.hang_offs[i])
    }

    /// The 6×6 stiffness on the vessel's reference point of the lines at
    /// free points at the current state, the free points re-balanced
    /// (17.19): each such line's two-end static stiffness at its current
    /// configuration ([`Simulation::end_stiffness6_into`], 17.6) and each
    /// point's own load's at its current position assembled over the
    /// vessel ends and the points (17.7), the points condensed out in place
    /// (17.8), then (17.9) with the lines' arms `rotation` ρ_i and their
    /// current forces on the vessel. `line(i)` is line i of the system,
    /// named. At the statics this is `riser statics`' stiffness; during a
    /// run, the quasi-static tangent about the state: no inertia, the
    /// points balanced statically about where they are. Allocates nothing
    /// after its first call on each line (its storage).
    pub fn condensed_stiffness6<'s>(
        &mut self,
        line: &dyn Fn(usize) -> (&'s str, &'s Simulation),
        rotation: &M3,
    ) -> Result<crate::math::M6, StiffnessError> {
        let FreePoints { stiffness: w, ends, points, .. } = self;
        let nv = 3 * w.lines.len();
        let n = nv + 3 * points.len();
        w.k.iter_mut().for_each(|x| *x = 0.0);
        let lines = &w.lines;
        let dof = |i: usize, at: EndAt| match at {
            EndAt::Vessel => lines.iter().position(|&j| j == i).map(|p| 3 * p),
            EndAt::Fixed => None,
            EndAt::Free(p) => Some(nv + 3 * p),
        };
        for (i, e) in ends.iter().enumerate().filter(|(_, e)| e.coupled()) {
            let (name, sim) = line(i);
            let s6 = sim
                .end_stiffness6_into(&mut w.ends[i])
                .map_err(|error| StiffnessError::Line(LineError { line: name.to_string(), error }))?;
            // (add_line_ends' sums, in its order)
            let at = [dof(i, e.hang_off_at), dof(i, e.anchor_at)];
            for (bi, ri) in at.iter().enumerate() {
                for (bj, cj) in at.iter().enumerate() {
                    if let (Some(r), Some(c)) = (ri, cj) {
                        for (a, b) in (0..3).flat_map(|a| (0..3).map(move |b| (a, b))) {
                            w.k[(r + a) * n + c + b] += s6[(3 * bi + a, 3 * bj + b)];
                        }
                    }
                }
            }
        }
        for (p, point) in points.iter().enumerate() {
            let kp = point.load_stiffness();
            let r = nv + 3 * p;
            for (a, b) in (0..3).flat_map(|a| (0..3).map(move |b| (a, b))) {
                w.k[(r + a) * n + r + b] += kp[(a, b)];
            }
        }
        if !condense_in_place(&mut w.k, n, nv) {
            return Err(StiffnessError::Singular);
        }
        let (k, lines) = (&w.k, &w.lines);
        let arm = |i: usize| rotation * line(lines[i]).1.vessel.offset;
        let force = |i: usize| {
            let sim = line(lines[i]).1;
            sim.integrator.top_force(&sim.state)
        };
        Ok(condensed_stiffness6_of(&|r, c| k[r * n + c], lines.len(), &arm, &force))
    }

    /// The points `points` of a system whose lines' ends are `ends` and
    /// runs `sims` (in its order): each line with a free end a trial slot
    /// sized on its state and its prescribed unknowns.
    pub fn new(points: Vec<FreePointRun>, ends: Vec<LineEnds>, sims: &[&Simulation]) -> Self {
        let np = points.len();
        let slots = ends
            .iter()
            .zip(sims)
            .map(|(e, sim)| {
                e.coupled().then(|| {
                    let m = sim.integrator.fixed_unknowns();
                    TrialSlot {
                        ends: *e,
                        start: sim.state.clone(),
                        state: sim.state.clone(),
                        condensed: [0.0; 36],
                        fixed: vec![0.0; m * m],
                        at: sim.integrator.end_position_unknowns().expect("a line's ends are prescribed in a system"),
                        result: Ok(()),
                    }
                })
            })
            .collect();
        let stiffness = CondensedScratch::new(&ends, np, sims);
        FreePoints {
            points,
            ends,
            slots,
            x1: vec![V3::zeros(); np],
            v1: vec![V3::zeros(); np],
            r: vec![V3::zeros(); np],
            scale: vec![0.0; np],
            f_water: vec![V3::zeros(); np],
            reactions: vec![V3::zeros(); np],
            jac: vec![0.0; 9 * np * np],
            rhs: vec![0.0; 3 * np],
            saved: vec![[0.0; POINT_VALUES]; np],
            stiffness,
            time: 0.0,
            point_iterations: 0,
            trial_iterations: 0,
        }
    }

    /// Puts every line's hang-off on its motion at the start ([`Simulation::start`]):
    /// on the vessel at `vessel_path` at the lines' time, a free point's lines
    /// at the point, at rest; starts the points' current ramps there and
    /// takes their energy reference.
    pub fn start_lines(&mut self, lines: &mut dyn LineSet, vessel_path: &VesselPath) {
        let mut time = 0.0;
        for (i, e) in self.ends.iter().enumerate() {
            let sim = lines.sim(i);
            let h = match e.hang_off_at {
                EndAt::Free(k) => HangOff::translation(self.points[k].position - e.origin, self.points[k].velocity),
                _ => vessel_path(&sim.vessel, sim.state.time),
            };
            sim.start(h);
            if i == 0 {
                time = sim.state.time;
            }
        }
        self.time = time;
        self.set_ramps_start(time);
        for p in &mut self.points {
            p.initial_energy = p.energy();
        }
    }

    /// Starts the points' current's and waves' ramps at `start` s (a restored state's, §5.11).
    pub fn set_ramps_start(&mut self, start: f64) {
        for p in &mut self.points {
            p.current_ramp.start = start;
            if let Some(sea) = p.sea.as_mut() {
                sea.set_ramp_start(start);
            }
        }
    }

    /// Keeps the points' states ([`FreePoints::rollback`] returns to them), allocating nothing.
    pub fn checkpoint(&mut self) {
        for (s, p) in self.saved.iter_mut().zip(&self.points) {
            *s = p.values();
        }
    }

    /// Back to the points' states at the last [`FreePoints::checkpoint`], at `time` s.
    pub fn rollback(&mut self, time: f64) {
        for (s, p) in self.saved.iter().zip(self.points.iter_mut()) {
            p.set_values(s);
        }
        self.time = time;
    }

    /// The free points and their lines to `t` in one step, split in halves
    /// where it fails (a line's trial or the points' Newton), down to
    /// 1/2^`MAX_POINT_HALVINGS` of it, as a single line splits its step
    /// (§5.7); the error of the smallest sub-step if that fails too, the
    /// state kept at the last converged sub-step. The lines are `lines`
    /// (every line of the system, those without a free end untouched),
    /// their vessel ends on `vessel_path`.
    pub fn advance(
        &mut self,
        lines: &mut dyn LineSet,
        t: f64,
        vessel_path: &VesselPath,
        threads: usize,
    ) -> Result<(), SystemStepError> {
        let span = t - self.time;
        let (mut sub, mut level) = (span, 0u32);
        while self.time < t - 1e-12 * span {
            let end = if self.time + sub >= t - 1e-12 * span { t } else { self.time + sub };
            match self.step(lines, end, vessel_path, threads) {
                Ok(()) => self.time = end,
                // named only here: a step that is split allocates nothing
                Err(e) if level >= MAX_POINT_HALVINGS => return Err(self.named(lines, e)),
                Err(_) => {
                    level += 1;
                    sub *= 0.5;
                }
            }
        }
        Ok(())
    }

    /// The error of a failed step, its line or point named.
    fn named(&self, lines: &dyn LineSet, e: StepFailed) -> SystemStepError {
        match e {
            StepFailed::Line(i, error) => LineError { line: lines.name(i).to_string(), error }.into(),
            StepFailed::Points { time, residual, point } => SystemStepError::Points(PointsDiverged {
                time,
                iterations: MAX_POINT_ITERATIONS,
                residual,
                point: self.points[point].name.clone(),
            }),
        }
    }

    /// One step of the free points and their lines to `t` (§17.7): Newton
    /// on the points' end-of-step positions x⁺ (17.16), each line with an
    /// end at a point stepped from its start with its ends at x⁺ (a trial)
    /// and giving its end reactions and its condensed step tangent (17.15).
    fn step(
        &mut self,
        lines: &mut dyn LineSet,
        t: f64,
        vessel_path: &VesselPath,
        threads: usize,
    ) -> Result<(), StepFailed> {
        let t0 = self.time;
        let h = t - t0;
        let np = self.points.len();
        let mut tol = None;
        for (i, slot) in self.slots.iter_mut().enumerate() {
            if let Some(slot) = slot {
                let sim = lines.sim(i);
                tol.get_or_insert(sim.integrator.options().newton_tolerance);
                slot.start.clone_from(&sim.state);
            }
        }
        let tol = tol.unwrap_or(1e-8);
        // the predictor: the quadratic of the cable's (§5.7)
        for (x, p) in self.x1.iter_mut().zip(self.points.iter_mut()) {
            *x = p.position + (p.mean_vel[0] * 2.0 - p.mean_vel[1]) * h;
            p.freeze_water(*x, t0 + 0.5 * h);
        }
        let mut worst = (0.0, 0);
        for it in 0..=MAX_POINT_ITERATIONS {
            // v⁺ = 2 (x⁺ − x⁻)/h − v⁻ (5.1's update)
            for ((v, x), p) in self.v1.iter_mut().zip(&self.x1).zip(&self.points) {
                *v = (x - p.position) * (2.0 / h) - p.velocity;
            }
            let (x1, v1) = (&self.x1, &self.v1);
            lines.each_slot(&mut self.slots, threads, &|sim, slot| slot.run(sim, t, vessel_path, x1, v1));
            for (i, slot) in self.slots.iter_mut().enumerate() {
                if let Some(slot) = slot
                    && slot.result.is_err()
                {
                    let error = std::mem::replace(&mut slot.result, Ok(())).expect_err("a failed trial");
                    return Err(StepFailed::Line(i, error));
                }
            }
            // (17.14) + Σ P_i, and its Jacobian (17.16) with the lines' condensed tangents (17.15)
            let t_mid = t0 + 0.5 * h;
            let n3 = 3 * np;
            self.jac.iter_mut().for_each(|x| *x = 0.0);
            for (k, p) in self.points.iter().enumerate() {
                let (rk, kk, fw) = p.own_rows(self.x1[k], h, t_mid);
                self.r[k] = rk;
                self.f_water[k] = fw;
                for (a, b) in (0..3).flat_map(|a| (0..3).map(move |b| (a, b))) {
                    self.jac[(3 * k + a) * n3 + 3 * k + b] = kk[(a, b)];
                }
                self.scale[k] = p.gravity * (p.mass + p.water_density * p.volume) + fw.norm();
            }
            for tr in self.slots.iter().flatten() {
                let ends = [tr.ends.hang_off_at, tr.ends.anchor_at];
                let reaction = tr.state.mid_reaction;
                for (ea, a) in ends.iter().enumerate() {
                    let EndAt::Free(ka) = *a else { continue };
                    self.r[ka] += reaction[ea];
                    self.scale[ka] += reaction[ea].norm();
                    for (eb, b) in ends.iter().enumerate() {
                        let EndAt::Free(kb) = *b else { continue };
                        for (ra, ca) in (0..3).map(|c| (3 * ea + c, 3 * ka + c)) {
                            for (rb, cb) in (0..3).map(|c| (3 * eb + c, 3 * kb + c)) {
                                self.jac[ca * n3 + cb] += tr.condensed[ra * 6 + rb];
                            }
                        }
                    }
                }
            }
            worst = (0.0, 0);
            for k in 0..np {
                let rel = self.r[k].norm() / self.scale[k].max(f64::MIN_POSITIVE);
                if rel > worst.0 || rel.is_nan() {
                    worst = (rel, k);
                }
            }
            self.trial_iterations += self
                .slots
                .iter()
                .flatten()
                .map(|tr| tr.state.newton_iterations - tr.start.newton_iterations)
                .sum::<u64>();
            if worst.0 <= tol {
                // converged: the lines' trials and the points' step are the step
                self.reactions.iter_mut().for_each(|r| *r = V3::zeros());
                for (i, slot) in self.slots.iter_mut().enumerate() {
                    let Some(tr) = slot else { continue };
                    for (e, a) in [tr.ends.hang_off_at, tr.ends.anchor_at].iter().enumerate() {
                        if let EndAt::Free(k) = *a {
                            self.reactions[k] += tr.state.mid_reaction[e];
                        }
                    }
                    std::mem::swap(&mut lines.sim(i).state, &mut tr.state);
                }
                for (k, p) in self.points.iter_mut().enumerate() {
                    let dx = self.x1[k] - p.position;
                    // the lines pull the point by −Σ P_i; the water's work over the step (§5.4)
                    p.work_lines -= dx.dot(&self.reactions[k]);
                    p.work_hydro += dx.dot(&self.f_water[k]);
                    p.mean_vel = [dx / h, p.mean_vel[0]];
                    p.velocity = self.v1[k];
                    p.position = self.x1[k];
                }
                self.point_iterations += it as u64;
                return Ok(());
            }
            if it == MAX_POINT_ITERATIONS {
                break;
            }
            for (k, r) in self.r.iter().enumerate() {
                for c in 0..3 {
                    self.rhs[3 * k + c] = -r[c];
                }
            }
            if !solve_dense(&mut self.jac, &mut self.rhs) {
                break;
            }
            for (k, x) in self.x1.iter_mut().enumerate() {
                *x += V3::new(self.rhs[3 * k], self.rhs[3 * k + 1], self.rhs[3 * k + 2]);
            }
        }
        // the lines' own states were never touched
        for i in 0..self.ends.len() {
            lines.sim(i).integrator.set_anchor_motion(None);
        }
        Err(StepFailed::Points { time: t0, residual: worst.0, point: worst.1 })
    }
}

/// Solves A x = b in place (A n×n row-major, n = b's length; x in `b`) by
/// Gaussian elimination with partial pivoting, allocating nothing; false if
/// A is singular or the solution is not finite.
fn solve_dense(a: &mut [f64], b: &mut [f64]) -> bool {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs())).unwrap_or(c);
        if a[p * n + c] == 0.0 || !a[p * n + c].is_finite() {
            return false;
        }
        if p != c {
            for j in 0..n {
                a.swap(c * n + j, p * n + j);
            }
            b.swap(c, p);
        }
        for i in c + 1..n {
            let f = a[i * n + c] / a[c * n + c];
            if f != 0.0 {
                for j in c..n {
                    a[i * n + j] -= f * a[c * n + j];
                }
                b[i] -= f * b[c];
            }
        }
    }
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|j| a[c * n + j] * b[j]).sum();
        b[c] = (b[c] - s) / a[c * n + c];
    }
    b.iter().all(|x| x.is_finite())
}

/// The terms of a system's energy balance (17.17), J: its energy (the
/// lines' and the free points'), at the start, the work of the vessel, the
/// water, the seabed and the anchors' twist on it, what the damping
/// dissipated, and E − E0 − W + D. The works of the free points on their
/// lines and of the lines on them cancel and are in none.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SystemBalance {
    pub energy: f64,
    pub initial_energy: f64,
    pub work_vessel: f64,
    pub work_water: f64,
    pub work_seabed: f64,
    pub work_anchor: f64,
    pub dissipated: f64,
    pub residual: f64,
}

impl SystemBalance {
    /// The energy the system exchanged, J: |W_vessel| + |W_water| + |W_seabed| + |W_anchor| + D.
    pub fn exchanged(&self) -> f64 {
        self.work_vessel.abs()
            + self.work_water.abs()
            + self.work_seabed.abs()
            + self.work_anchor.abs()
            + self.dissipated
    }
}

/// `f` on each (index, item) of `items`, on up to `threads` threads (this
/// one among them), the dearest (by `cost`) first; the results with their
/// indices, in no order. One thread: in order on this one, nothing spawned.
fn on_threads<T: Send, R: Send>(
    items: Vec<(usize, T)>,
    threads: usize,
    cost: &(dyn Fn(&T) -> usize + Sync),
    f: &(dyn Fn(usize, T) -> R + Sync),
) -> Vec<(usize, R)> {
    let threads = threads.clamp(1, items.len().max(1));
    if threads == 1 {
        return items.into_iter().map(|(i, l)| (i, f(i, l))).collect();
    }
    let mut queue = items;
    queue.sort_by_key(|(i, l)| (std::cmp::Reverse(cost(l)), *i));
    let queue = Mutex::new(queue.into_iter());
    let work = || {
        let mut done = Vec::new();
        loop {
            let next = queue.lock().unwrap_or_else(|p| p.into_inner()).next();
            let Some((i, line)) = next else { break };
            done.push((i, f(i, line)));
        }
        done
    };
    std::thread::scope(|s| {
        let others: Vec<_> = (1..threads).map(|_| s.spawn(work)).collect();
        let mut all = work();
        for h in others {
            // a panic in a line's thread is this thread's (the FMU's boundary catches it)
            all.extend(h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)));
        }
        all
    })
}

/// The system's energy balance of its lines' outputs `outputs` against their
/// energies at the start `e0` (17.12): the sum of the lines' residuals, J
/// (without free points; with them, [`SystemRun::energy_balance`]).
pub fn energy_balance_residual(outputs: &[Outputs], e0: &[f64]) -> f64 {
    outputs.iter().zip(e0).map(|(o, e)| o.energy_balance_residual(*e)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The subsea buoy mooring (docs/cases) with the buoy's drag area and
    /// added mass (C_dA 7.4 m², C_a 0.5), coarsened, in a regular wave of
    /// 8 m and 15 s travelling at 30° from +x, its phase 40°, in the 200 m
    /// of the seabed, without stretching or ramp (the closed form's).
    fn buoy_in_waves() -> SystemScene {
        let text = include_str!("../../docs/cases/subsea_buoy_mooring.toml")
            .replace("n_elements = 44", "n_elements = 11")
            .replace("n_elements = 66", "n_elements = 16")
            .replace("volume = 15.0", "cd_area = 7.4\nca = 0.5\nvolume = 15.0")
            + "\n[waves]\nkind = \"airy\"\nheight = 8.0\nperiod = 15.0\ndirection = 30.0\nphase = 40.0\nramp = 0.0\n\
               stretching = \"none\"\n";
        SystemScene::from_toml(&text, "buoy_in_waves").unwrap()
    }

    /// A free point held still in an Airy wave takes the Morison force of
    /// linear theory worked by hand (17.18): with k from ω² = g k tanh kd
    /// (Newton), θ = k (x cos β + y sin β) − ω t + φ,
    /// u = a ω [cosh k(z + d) cos θ (cos β, sin β), sinh k(z + d) sin θ] / sinh kd,
    /// a_w = a ω² [cosh k(z + d) sin θ (cos β, sin β), −sinh k(z + d) cos θ] / sinh kd,
    /// f = ½ ρ C_dA |u| u + (1 + C_a) ρ V a_w: within 1e-12 of |f| at
    /// eight times over a period.
    #[test]
    fn a_point_held_still_in_an_airy_wave_takes_the_closed_form_morison_force() {
        let sys = buoy_in_waves();
        let (_, mut free) = build(&sys).unwrap();
        let p = &mut free.points[0];
        let (rho, g, d) = (1025.0, 9.80665, 200.0);
        let (a, period, beta, phi) = (4.0, 15.0, 30f64.to_radians(), 40f64.to_radians());
        let omega = 2.0 * std::f64::consts::PI / period;
        let mut k = omega * omega / g;
        for _ in 0..50 {
            let f = g * k * (k * d).tanh() - omega * omega;
            let df = g * (k * d).tanh() + g * k * d / (k * d).cosh().powi(2);
            k -= f / df;
        }
        let x = p.position;
        assert!(x.z < -50.0 && x.z > -150.0, "the buoy at {x}");
        let (cd_a, volume, ca) = (7.4, 15.0, 0.5);
        let mut worst = 0.0f64;
        for n in 0..8 {
            let t = 3.0 + n as f64 * period / 8.0;
            let theta = k * (x.x * beta.cos() + x.y * beta.sin()) - omega * t + phi;
            let (c, s) = ((k * (x.z + d)).cosh() / (k * d).sinh(), (k * (x.z + d)).sinh() / (k * d).sinh());
            let u = V3::new(beta.cos() * c * theta.cos(), beta.sin() * c * theta.cos(), s * theta.sin()) * (a * omega);
            let acc = V3::new(beta.cos() * c * theta.sin(), beta.sin() * c * theta.sin(), -s * theta.cos())
                * (a * omega * omega);
            let expected = u * (0.5 * rho * cd_a * u.norm()) + acc * ((1.0 + ca) * rho * volume);
            // held still: x⁺ = x⁻, at rest (v⁺ = v⁻ = 0)
            p.freeze_water(x, t);
            let (_, _, f) = p.own_rows(x, 0.1, t);
            let err = (f - expected).norm() / expected.norm();
            worst = worst.max(err);
            assert!(err <= 1e-12, "t = {t} s: {f} against {expected}");
        }
        eprintln!("a buoy held in an 8 m, 15 s Airy wave: the Morison force within {worst:.1e} of the closed form");
    }
}
