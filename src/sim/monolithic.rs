//! The monolithic reference of two-way coupling (issue 53; docs/theory.md
//! §7.9): a rigid body in heave and pitch carrying the hang-off at its lever,
//! integrated inside riser's own implicit step, so that the body and the
//! line are one system solved with no communication step at all. A
//! reference for tests and studies of co-simulation (what a two-way run
//! should converge to), not a vessel model offered to users: the body is
//! linear (mass, inertia, hydrostatic stiffness, linear damping, a regular
//! excitation), its pitch's kinematics exact.
//!
//! The body's step is the midpoint rule of the line's (§5.2): unknowns
//! q⁺ = (z⁺, θ⁺), velocities by the same update q̇⁺ = 2(q⁺ − q⁻)/h − q̇⁻, the
//! line stepped from its start with its hang-off at the lever's end-of-step
//! position (a trial), its reaction and its step tangent condensed on the
//! hang-off (17.15) closing a Newton on q⁺ (7.17), as free points do (§17.7).
//!
//! The same step serves the FMU ([`HeldBody`], §7.10): a single line given
//! the vessel's inertias takes, inside its internal steps, the vessel's
//! answer to the line's force beyond the force the vessel holds over the
//! communication step.

use super::Simulation;
use super::error::RiserError;
use crate::math::{M3, V3};
use crate::model::{DynamicsError, HangOff, State};

/// The corner below which the held body's answer returns to 0, rad/s
/// (0.5 Hz: a tenth of the line's axial modes, five times the waves').
pub const HELD_BODY_CORNER: f64 = 2.0 * std::f64::consts::PI * 0.5;

/// The most Newton corrections of the body's unknowns in a step.
pub const MAX_BODY_ITERATIONS: usize = 30;

/// A rigid body in heave z and pitch θ about its reference point (the
/// hang-off at the lever ρ of the scene's `[hang_off] offset`), linear in its
/// own loads (docs/theory.md (7.14)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavePitchBody {
    /// Mass with added mass in heave, kg.
    pub mass: f64,
    /// Pitch inertia with added inertia, kg m² (0: no pitch, the body heaves only).
    pub inertia: f64,
    /// Hydrostatic stiffness in heave (N/m) and pitch (N m/rad).
    pub stiffness: [f64; 2],
    /// Linear damping in heave (N s/m) and pitch (N m s/rad).
    pub damping: [f64; 2],
    /// Amplitudes of the regular excitation: heave force (N), pitch moment (N m).
    pub excitation: [f64; 2],
    /// The excitation's period, s.
    pub period: f64,
    /// Its ramp, s: the amplitude grows as ½(1 − cos(π t/ramp)) (0: none).
    pub ramp: f64,
}

impl HeavePitchBody {
    /// The excitation [force, moment] at t (s): A r(t) sin(2π t/T) (7.14).
    pub fn excitation_at(&self, t: f64) -> [f64; 2] {
        let r = if self.ramp > 0.0 && t < self.ramp {
            0.5 * (1.0 - (std::f64::consts::PI * t / self.ramp).cos())
        } else {
            1.0
        };
        let s = r * (2.0 * std::f64::consts::PI * t / self.period).sin();
        [self.excitation[0] * s, self.excitation[1] * s]
    }

    /// Degrees of freedom in use: heave, and pitch if it has an inertia.
    fn dofs(&self) -> usize {
        if self.inertia > 0.0 { 2 } else { 1 }
    }
}

/// A run of a line with the body at its hang-off (§7.9).
pub struct BodyRun {
    pub sim: Simulation,
    pub body: HeavePitchBody,
    /// The body's heave (m) and pitch (rad) from rest, and their rates.
    pub q: [f64; 2],
    pub q_dot: [f64; 2],
    /// The line's generalized load on the body at rest, [N, N m]: what the
    /// body's buoyancy and trim balance, a constant heave force and pitch
    /// moment (7.14), as a vessel model balances the load it starts with
    /// (osp/vessel/Vessel6.py's `balance_initial_load`).
    pub static_load: [f64; 2],
    /// Work of the excitation on the body since the start, J.
    pub work_excitation: f64,
    /// Energy the body's damping took since the start, J (≥ 0).
    pub dissipated: f64,
    /// Work of the line on the body since the start, J: minus the hang-off's
    /// work on the line over the same steps.
    pub work_line: f64,
    /// Newton corrections of the body's unknowns over the run.
    pub iterations: u64,
}

impl BodyRun {
    /// The line at rest in its statics with the body at rest on it.
    pub fn new(mut sim: Simulation, body: HeavePitchBody) -> Self {
        sim.start(HangOff::default());
        let mut run = BodyRun {
            sim,
            body,
            q: [0.0; 2],
            q_dot: [0.0; 2],
            static_load: [0.0; 2],
            work_excitation: 0.0,
            dissipated: 0.0,
            work_line: 0.0,
            iterations: 0,
        };
        let p0 = -run.sim.outputs().top_force;
        let g = run.chord(0.0, 0.0);
        run.static_load = [g[0].dot(&p0), g[1].dot(&p0)];
        run
    }

    /// The lever's arm R_y(θ) ρ (global), m.
    fn arm(&self, theta: f64) -> V3 {
        self.sim.vessel.order.rotation([0.0, theta, 0.0]) * self.sim.vessel.offset
    }

    /// The hang-off's displacement from rest at body position q, m (7.15).
    pub fn hang_off_displacement(&self, q: [f64; 2]) -> V3 {
        V3::z() * q[0] + self.arm(q[1]) - self.sim.vessel.offset
    }

    /// The columns of the discrete derivative of the hang-off's position
    /// between pitches θ⁻ and θ⁺ (7.16): e_z, and the chord of the arm,
    /// [a(θ⁺) − a(θ⁻)]/(θ⁺ − θ⁻) (its derivative at the midpoint when the
    /// two are within 1e-9 rad), so that Δx = G Δq exactly.
    fn chord(&self, t0: f64, t1: f64) -> [V3; 2] {
        let dt = t1 - t0;
        let g = if dt.abs() > 1e-9 {
            (self.arm(t1) - self.arm(t0)) / dt
        } else {
            let tm = 0.5 * (t0 + t1);
            (self.arm(tm + 1e-6) - self.arm(tm - 1e-6)) / 2e-6
        };
        [V3::z(), g]
    }

    /// The body's energy: ½ q̇ᵀ M q̇ + ½ qᵀ C q − Q₀·q, J (the last the
    /// potential of the constant load that balances the line at rest).
    pub fn body_energy(&self) -> f64 {
        let b = &self.body;
        let kinetic = 0.5 * (b.mass * self.q_dot[0].powi(2) + b.inertia * self.q_dot[1].powi(2));
        let spring = 0.5 * (b.stiffness[0] * self.q[0].powi(2) + b.stiffness[1] * self.q[1].powi(2));
        kinetic + spring - self.static_load[0] * self.q[0] - self.static_load[1] * self.q[1]
    }

    /// The line's and the body's energy balance (7.18), J: ΔE_line + ΔE_body
    /// − the water's, the seabed's and the anchor's work on the line + the
    /// line's dissipation − the excitation's work + the body's damping. The
    /// hang-off's work is internal and cancels (`work_top` + `work_line`, to
    /// the line's end-inertia term, which the velocity update makes zero).
    pub fn energy_balance_residual(&self) -> f64 {
        let o = self.sim.outputs();
        let line = o.energy_balance_residual(self.sim.initial_energy) + o.work_top;
        line + self.body_energy() - self.work_excitation + self.dissipated
    }

    /// The energy exchanged between the line and the body so far: the sum of
    /// the magnitudes would need every step's; this is the scale of a balance,
    /// |W_exc| + D_body + |W_line|, J.
    pub fn exchanged(&self) -> f64 {
        self.work_excitation.abs() + self.dissipated + self.work_line.abs()
    }

    /// One step of h (s) of the line and the body together (7.17): Newton on
    /// q⁺ with the line stepped from its start at each trial. On failure the
    /// run is left at the step's start.
    pub fn step(&mut self, h: f64) -> Result<(), RiserError> {
        let prev: State = self.sim.state.clone();
        let (t0, b) = (prev.time, self.body);
        let n = b.dofs();
        let mass = [b.mass, b.inertia];
        let (q0, v0) = (self.q, self.q_dot);
        let x0 = self.hang_off_displacement(q0);
        let vh0 = prev.hang_off.velocity;
        let f = b.excitation_at(t0 + 0.5 * h);
        let tol = self.sim.integrator.options().newton_tolerance;
        // the predictor: the body's velocity held over the step
        let mut q1 = [q0[0] + h * v0[0], q0[1] + h * v0[1]];
        let mut worst = f64::INFINITY;
        for it in 0..=MAX_BODY_ITERATIONS {
            let x1 = self.hang_off_displacement(q1);
            // the hang-off's end velocity by the line's own update (5.1)
            let vh1 = (x1 - x0) * (2.0 / h) - vh0;
            let w1 = V3::y() * ((q1[1] - q0[1]) * (2.0 / h) - v0[1]);
            let rotation = self.sim.vessel.order.rotation([0.0, q1[1], 0.0]);
            let target = HangOff { displacement: x1, velocity: vh1, rotation, angular_velocity: w1 };
            let mut state = prev.clone();
            self.sim.integrator.step(&mut state, h, &|_| target)?;
            state.time = t0 + h;
            let p = state.mid_reaction[0];
            let g = self.chord(q0[1], q1[1]);
            // (7.17): the body's rows and their scale
            let mut r = [0.0; 2];
            let mut scale = [0.0; 2];
            for i in 0..n {
                let dq = q1[i] - q0[i];
                let v1 = dq * 2.0 / h - v0[i];
                let terms = [
                    mass[i] * (v1 - v0[i]) / h,
                    b.damping[i] * dq / h,
                    b.stiffness[i] * (q0[i] + q1[i]) * 0.5,
                    -f[i],
                    g[i].dot(&p),
                    -self.static_load[i],
                ];
                r[i] = terms.iter().sum();
                scale[i] = terms.iter().map(|x| x.abs()).sum::<f64>();
            }
            worst = (0..n).map(|i| r[i].abs() / scale[i].max(f64::MIN_POSITIVE)).fold(0.0, f64::max);
            if worst <= tol {
                for i in 0..n {
                    self.q_dot[i] = (q1[i] - q0[i]) * 2.0 / h - v0[i];
                    self.dissipated += b.damping[i] * (q1[i] - q0[i]).powi(2) / h;
                    self.work_excitation += f[i] * (q1[i] - q0[i]);
                }
                self.work_line -= (x1 - x0).dot(&p);
                self.q = q1;
                self.sim.state = state;
                self.iterations += it as u64;
                return Ok(());
            }
            if it == MAX_BODY_ITERATIONS {
                break;
            }
            // (7.17)'s Jacobian: the body's own terms and Gᵀ S G, S the line's
            // step condensed on its hang-off (17.15)
            let s = hang_off_condensed(&mut self.sim, &prev, &state, h, target)?;
            let mut jac = nalgebra::Matrix2::<f64>::identity();
            for i in 0..n {
                for j in 0..n {
                    jac[(i, j)] = g[i].dot(&(s * g[j]));
                }
                jac[(i, i)] += mass[i] * 2.0 / (h * h) + b.damping[i] / h + 0.5 * b.stiffness[i];
            }
            // the chord's turn with θ⁺ under the line's load: ½ a″(θ½)·P
            let (tm, e) = (0.5 * (q0[1] + q1[1]), 1e-4);
            let curvature = (self.arm(tm + e) - self.arm(tm) * 2.0 + self.arm(tm - e)) / (e * e);
            if n == 2 {
                jac[(1, 1)] += 0.5 * curvature.dot(&p);
            }
            let rhs = nalgebra::Vector2::new(-r[0], -r[1]);
            let Some(dq) = jac.lu().solve(&rhs) else { break };
            for (i, qi) in q1.iter_mut().enumerate().take(n) {
                *qi += dq[i];
            }
        }
        let (iterations, residual) = (MAX_BODY_ITERATIONS, worst);
        Err(RiserError::Dynamics(DynamicsError::NotConverged { time: t0, step: h, iterations, residual }))
    }
}

/// The vessel's answer to the line's force beyond the force it holds,
/// integrated inside the line's own steps (docs/theory.md §7.10; issue 53):
/// in a fixed-step master the vessel holds the load of t_n over the
/// communication step while the line's force turns within it; the FMU,
/// given the vessel's inertias (`vessel_mass_*`, `vessel_inertia_*`), moves
/// the hang-off by that rigid body's answer δq = (δu, δθ) (global
/// translation and small rotation about the reference point) to the
/// difference, M δq̈ = −Gᵀ(P − P_n), P the line's reaction at the hang-off
/// and P_n the held one, implicitly in the line's step (the monolithic step
/// of §7.9): the hang-off at the input path's position plus δu + δθ × Rρ.
/// The answer is the high-frequency one: below [`HELD_BODY_CORNER`] it
/// returns to zero (the vessel's own samples carry the slow motion).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HeldBody {
    /// Masses (surge, sway, heave; kg) and principal inertias (roll, pitch,
    /// yaw; kg m², vessel frame), with their added parts; 0: not moved.
    pub inertia: [f64; 6],
    /// δq and its rate.
    pub dq: [f64; 6],
    pub dq_dot: [f64; 6],
}

/// What [`HeldBody::step`] works in, kept by its caller between steps so
/// that the step allocates nothing once warmed up (the first step sizes it).
#[derive(Debug, Clone, Default)]
pub struct HeldScratch {
    prev: Option<State>,
    trial: Option<State>,
    condensed: Vec<f64>,
}

impl HeldBody {
    /// One step of h of the line from its state with the body's δq (7.19),
    /// about the path's `base` at the step's end, the vessel holding the
    /// reaction `held` (N). On failure the line and δq are left at the
    /// step's start.
    pub fn step(
        &mut self,
        sim: &mut Simulation,
        scratch: &mut HeldScratch,
        h: f64,
        base: HangOff,
        held: V3,
    ) -> Result<(), RiserError> {
        let HeldScratch { prev, trial, condensed } = scratch;
        let prev = prev.get_or_insert_with(|| sim.state.clone());
        prev.clone_from(&sim.state);
        let prev = &*prev;
        let t0 = prev.time;
        let r = base.rotation * sim.vessel.offset;
        let rot = base.rotation;
        // the mass matrix, global: translations, R diag(I) Rᵀ
        let mut mass = nalgebra::Matrix6::<f64>::zeros();
        for i in 0..3 {
            mass[(i, i)] = self.inertia[i];
        }
        let inertia =
            rot * M3::from_diagonal(&V3::new(self.inertia[3], self.inertia[4], self.inertia[5])) * rot.transpose();
        mass.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia);
        let active: [bool; 6] = std::array::from_fn(|i| self.inertia[i] > 0.0);
        // G = [I, −[r]×]: δx = δu + δθ × r
        let g = |i: usize| -> V3 { if i < 3 { V3::ith(i, 1.0) } else { V3::ith(i - 3, 1.0).cross(&r) } };
        let tol = sim.integrator.options().newton_tolerance;
        let (q0, v0) = (self.dq, self.dq_dot);
        let mut q1: [f64; 6] = std::array::from_fn(|i| if active[i] { q0[i] + h * v0[i] } else { 0.0 });
        let mut worst = f64::INFINITY;
        for it in 0..=MAX_BODY_ITERATIONS {
            let v1: [f64; 6] = std::array::from_fn(|i| (q1[i] - q0[i]) * (2.0 / h) - v0[i]);
            let du = V3::new(q1[0], q1[1], q1[2]);
            let dth = V3::new(q1[3], q1[4], q1[5]);
            let target = HangOff {
                displacement: base.displacement + du + dth.cross(&r),
                velocity: base.velocity + V3::new(v1[0], v1[1], v1[2]) + V3::new(v1[3], v1[4], v1[5]).cross(&r),
                rotation: crate::math::rigid::exp_so3(&dth) * rot,
                angular_velocity: base.angular_velocity + V3::new(v1[3], v1[4], v1[5]),
            };
            let state = trial.get_or_insert_with(|| prev.clone());
            state.clone_from(prev);
            sim.integrator.step(state, h, &|_| target)?;
            state.time = t0 + h;
            let p = state.mid_reaction[0];
            let acc = nalgebra::Vector6::from_fn(|i, _| (v1[i] - v0[i]) / h);
            let inert = mass * acc;
            let mut res = nalgebra::Vector6::<f64>::zeros();
            worst = 0.0;
            // the answer is the high-frequency one: δq returns to 0 below ω_c, critically damped (7.19)
            let wc = HELD_BODY_CORNER;
            let dq = nalgebra::Vector6::from_fn(|i, _| q1[i] - q0[i]);
            let qm = nalgebra::Vector6::from_fn(|i, _| 0.5 * (q0[i] + q1[i]));
            let leak = mass * (dq * (2.0 * wc / h) + qm * (wc * wc));
            for i in (0..6).filter(|&i| active[i]) {
                res[i] = inert[i] + leak[i] + g(i).dot(&(p - held));
                let scale = inert[i].abs() + g(i).dot(&p).abs() + g(i).dot(&held).abs();
                worst = f64::max(worst, res[i].abs() / scale.max(f64::MIN_POSITIVE));
            }
            if worst <= tol {
                self.dq = q1;
                self.dq_dot = v1;
                sim.state.clone_from(state);
                return Ok(());
            }
            if it == MAX_BODY_ITERATIONS {
                break;
            }
            let s = hang_off_condensed_into(sim, prev, state, h, target, condensed)?;
            let wc = HELD_BODY_CORNER;
            let mut jac = mass * (2.0 / (h * h) + 2.0 * wc / h + 0.5 * wc * wc);
            for i in 0..6 {
                for j in 0..6 {
                    jac[(i, j)] += g(i).dot(&(s * g(j)));
                }
            }
            for i in (0..6).filter(|&i| !active[i]) {
                for j in 0..6 {
                    jac[(i, j)] = 0.0;
                    jac[(j, i)] = 0.0;
                }
                jac[(i, i)] = 1.0;
            }
            // (a 6×6 on the stack: nalgebra's fixed-size LU allocates nothing)
            let Some(d) = jac.lu().solve(&(-res)) else { break };
            for (i, qi) in q1.iter_mut().enumerate() {
                *qi += d[i];
            }
        }
        let (iterations, residual) = (MAX_BODY_ITERATIONS, worst);
        Err(RiserError::Dynamics(DynamicsError::NotConverged { time: t0, step: h, iterations, residual }))
    }
}

/// [`hang_off_condensed`] with the condensed tangent in `s` (sized once).
fn hang_off_condensed_into(
    sim: &mut Simulation,
    prev: &State,
    state: &State,
    h: f64,
    target: HangOff,
    s: &mut Vec<f64>,
) -> Result<M3, RiserError> {
    let m = sim.integrator.fixed_unknowns();
    s.resize(m * m, 0.0);
    let engine = &mut sim.integrator;
    engine.condensed_fixed_tangent_into(prev, &state.config, h, target, s).map_err(|error| DynamicsError::Linear {
        time: prev.time,
        step: h,
        error,
    })?;
    let local = M3::from_fn(|i, j| s[i * m + j]);
    let rod = matches!(engine, super::Engine::Rod(_));
    Ok(if rod && engine.options().corotated_tangent {
        let d = state.config.d[0];
        d * local * d.transpose()
    } else {
        local
    })
}

/// The line's step from `prev` to `state` condensed on its hang-off's
/// translation, global, N/m: the first 3×3 block of (17.15), turned from
/// the rod's corotated basis (the hang-off node's director frame) when
/// the tangent is assembled in it.
fn hang_off_condensed(
    sim: &mut Simulation,
    prev: &State,
    state: &State,
    h: f64,
    target: HangOff,
) -> Result<M3, RiserError> {
    hang_off_condensed_into(sim, prev, state, h, target, &mut Vec::new())
}
