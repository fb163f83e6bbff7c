//! The error of the user's own numerics, measured on the user's own scene
//! (issue 51; docs/theory.md §16.11; `riser run --estimate-error`).
//!
//! Short pilot runs of the scene's own motion and sea at three mesh levels
//! (n, 2n, 4n elements at the finest step Δt/4) and three step levels (Δt,
//! Δt/2, Δt/4 at the user's n elements; the pilot (n, Δt/4) is shared, five
//! pilots in all) give, for each quantity ([`Quantity`]), two triplets. Of
//! each triplet q₁, q₂, q₃ (coarse to fine, refinement ratio r = 2):
//!
//!   R = (q₂ − q₃)/(q₁ − q₂)                         the convergence ratio   (16.12)
//!   p = ln(1/R)/ln r                                the observed order       (16.13)
//!   q* = q₃ + (q₃ − q₂)/(r^p − 1) = q₃ + (q₃ − q₂) R/(1 − R)   Richardson   (16.14)
//!
//! classified monotone (0 < R < 1), oscillatory (R < 0) or divergent
//! (R ≥ 1; [`Convergence`]); the order is observed, never assumed. Where a
//! triplet is not monotone there is no extrapolation: its q* is the finest
//! pilot, q₃, and the estimate says so ([`Triplet::note`]). With the mesh's
//! and the step's errors additive, q(n, Δt) = q_exact + E_h(n) + E_t(Δt),
//! the step triplet's q*_t is q_exact + E_h(n), the mesh triplet's q*_h is
//! q_exact + E_t(Δt/4), so
//!
//!   q* = q*_h + q*_t − q(n, Δt/4),                                          (16.15)
//!   e = q(n, Δt) − q* = [q(n, Δt) − q*_t] + [q(n, Δt/4) − q*_h] = e_t + e_h (16.16)
//!
//! the estimate of the user's error the sum of the step's and the mesh's,
//! each from its own triplet (signed: they may cancel; the bound |e_t| +
//! |e_h| is reported with it, and Roache's GCI, that bound times a safety
//! factor F_s of 1.25 where both triplets are monotone and 3 where one is
//! not: [`GCI_SAFETY`], [`GCI_SAFETY_UNCONVERGED`]).
//!
//! The pilots are short ([`PilotPlan`]): the user's steady window cut to
//! [`PILOT_PERIODS`] periods of the slowest forcing from its start
//! ([`PILOT_PERIODS_IRREGULAR`] of an irregular sea's T_p), the run ending
//! there; the ramps and the start are the user's. The estimate is of
//! the error of the quantity over the pilots' window, which stands for the
//! user's run's (the same motion, mesh and step; a longer window's extremes
//! come from more cycles of the same response).
//!
//! The quantities ([`Quantity`]): the top tension's max, min, range and
//! time mean, the touchdown's extremes on a seabed, the largest stress
//! range on a line with stresses, and with the run's fatigue Miner's
//! damage over the window at the worst point and fibre.
//!
//! The extremes of the top tension are the peaks of the parabola through
//! the largest (smallest) sample and its neighbours ([`peak`]): a sampled
//! extreme is off the true one by up to ½|q''|(Δt/2)², a sampling error
//! that does not fall smoothly with Δt (where the peak lies between the
//! samples changes from step to step) and would hide the scheme's order.

use super::Simulation;
use super::error::RiserError;
use crate::model::HangOff;
use crate::scene::Scene;

/// Periods of the slowest forcing the pilots' window spans.
pub const PILOT_PERIODS: f64 = 3.0;
/// Peak periods T_p the pilots' window spans in an irregular sea (a
/// spectrum, a table of components): its extremes are those of the sea's
/// largest wave groups, which three periods do not hold (docs/theory.md
/// §16.13: 3 T_p under-estimated the jumper's error 0.27–0.36 times).
pub const PILOT_PERIODS_IRREGULAR: f64 = 20.0;
/// Roache's safety factor of the grid convergence index where both triplets
/// converge monotonically (three levels, the order observed).
pub const GCI_SAFETY: f64 = 1.25;
/// Roache's safety factor where a triplet does not converge monotonically.
pub const GCI_SAFETY_UNCONVERGED: f64 = 3.0;
/// Differences below this fraction of the quantity's magnitude are round-off
/// (and the Newton tolerance's): the pilots agree ([`Convergence::Converged`]).
pub const AGREE: f64 = 1e-12;

/// A quantity the estimate is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The top tension's largest value over the window, N.
    TopTensionMax,
    /// The top tension's smallest value over the window, N.
    TopTensionMin,
    /// The top tension's range over the window, max − min, N.
    TopTensionRange,
    /// The top tension's time mean over the window (trapezoid rule), N.
    TopTensionMean,
    /// The largest arc length of the touchdown over the window, m (a line on a seabed).
    TouchdownMax,
    /// The smallest arc length of the touchdown over the window, m.
    TouchdownMin,
    /// The largest outer-fibre stress range over the line and the window,
    /// Pa (a line with stresses: docs/theory.md §12.2).
    StressRange,
    /// Miner's damage over the window at the worst point and fibre (the
    /// run's fatigue, [`RunSpec::fatigue`]; docs/theory.md §12.5).
    FatigueDamage,
    /// A system's resultant force on the vessel (global frame, N): its
    /// component `axis` (0, 1, 2: x, y, z; 3: its magnitude) over the
    /// window (docs/theory.md §16.14).
    VesselForce { axis: usize, stat: Stat },
    /// A system's resultant moment on the vessel about its reference point
    /// (global frame, N m), as [`Quantity::VesselForce`].
    VesselMoment { axis: usize, stat: Stat },
    /// The top tension (at its hang-off) of a system's line `line` (its
    /// index in the system), N.
    LineTension { line: usize, stat: Stat },
}

/// A statistic of a quantity over the window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stat {
    Min,
    Mean,
    Max,
}

impl Stat {
    pub const ALL: [Stat; 3] = [Stat::Min, Stat::Mean, Stat::Max];

    pub fn name(self) -> &'static str {
        match self {
            Stat::Min => "min",
            Stat::Mean => "mean",
            Stat::Max => "max",
        }
    }

    /// Of samples `(t, y)` over `window`: the extremes' parabola peaks
    /// ([`peak`]), the trapezoid mean ([`time_mean`]).
    pub fn of(self, samples: &[(f64, f64)], window: (f64, f64)) -> f64 {
        match self {
            Stat::Min => peak(samples, window, false),
            Stat::Mean => time_mean(samples, window),
            Stat::Max => peak(samples, window, true),
        }
    }
}

impl Quantity {
    /// Every quantity, in the order of [`ErrorEstimate::estimates`].
    pub const ALL: [Quantity; 8] = [
        Quantity::TopTensionMax,
        Quantity::TopTensionMin,
        Quantity::TopTensionRange,
        Quantity::TopTensionMean,
        Quantity::TouchdownMax,
        Quantity::TouchdownMin,
        Quantity::StressRange,
        Quantity::FatigueDamage,
    ];

    /// Its name: a system's line by its index (`line2.top_tension_max`;
    /// [`Quantity::label`] names it).
    pub fn name(self) -> std::borrow::Cow<'static, str> {
        self.label(&[])
    }

    /// Its name, a system's line by its name in `lines` where it is there.
    pub fn label(self, lines: &[String]) -> std::borrow::Cow<'static, str> {
        const AXES: [&str; 4] = ["x", "y", "z", "magnitude"];
        let axis = |a: usize| AXES.get(a).copied().unwrap_or("?");
        match self {
            Quantity::VesselForce { axis: a, stat } => format!("vessel_force_{}_{}", axis(a), stat.name()).into(),
            Quantity::VesselMoment { axis: a, stat } => format!("vessel_moment_{}_{}", axis(a), stat.name()).into(),
            Quantity::LineTension { line, stat } => match lines.get(line) {
                Some(name) => format!("{name}.top_tension_{}", stat.name()).into(),
                None => format!("line{line}.top_tension_{}", stat.name()).into(),
            },
            q => q.single_name().into(),
        }
    }

    fn single_name(self) -> &'static str {
        match self {
            Quantity::TopTensionMax => "top_tension_max",
            Quantity::TopTensionMin => "top_tension_min",
            Quantity::TopTensionRange => "top_tension_range",
            Quantity::TopTensionMean => "top_tension_mean",
            Quantity::TouchdownMax => "touchdown_max",
            Quantity::TouchdownMin => "touchdown_min",
            Quantity::StressRange => "stress_range",
            Quantity::FatigueDamage => "fatigue_damage",
            _ => "",
        }
    }

    /// The quantity of a name ([`Quantity::name`]).
    pub fn parse(name: &str) -> Result<Quantity, String> {
        Quantity::ALL.into_iter().find(|q| q.name() == name).ok_or_else(|| {
            let names: Vec<&str> = Quantity::ALL.iter().map(|q| q.single_name()).collect();
            format!("unknown quantity '{name}'; one of {} or all", names.join(", "))
        })
    }

    /// Whether `scene` has the quantity: the touchdown's on a seabed, the
    /// stress range on a line with stresses, the fatigue damage on one whose
    /// run asks for fatigue (`fatigue`).
    pub fn applies(self, scene: &Scene, fatigue: bool) -> bool {
        match self {
            Quantity::TouchdownMax | Quantity::TouchdownMin => scene.seabed.is_some(),
            Quantity::StressRange => super::design::Design::new(scene).has_stresses(),
            Quantity::FatigueDamage => fatigue && super::design::Design::new(scene).has_stresses(),
            _ => true,
        }
    }

    /// Its unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::TouchdownMax | Quantity::TouchdownMin => "m",
            Quantity::StressRange => "Pa",
            Quantity::FatigueDamage => "-",
            Quantity::VesselMoment { .. } => "N m",
            _ => "N",
        }
    }

    pub fn index(self) -> usize {
        Quantity::ALL.iter().position(|q| *q == self).unwrap_or(0)
    }
}

/// How a triplet converges, by its ratio R (16.12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Convergence {
    /// 0 < R < 1: the differences shrink without changing sign.
    Monotone,
    /// R < 0: the differences change sign.
    Oscillatory,
    /// R ≥ 1 (or q₁ = q₂ ≠ q₃): the differences do not shrink.
    Divergent,
    /// The finer two agree within [`AGREE`]: nothing left to extrapolate.
    Converged,
}

impl Convergence {
    pub fn name(self) -> &'static str {
        match self {
            Convergence::Monotone => "monotone",
            Convergence::Oscillatory => "oscillatory",
            Convergence::Divergent => "divergent",
            Convergence::Converged => "converged",
        }
    }
}

/// One triplet's analysis (16.12)–(16.14).
#[derive(Debug, Clone, PartialEq)]
pub struct Triplet {
    /// The values, coarse to fine.
    pub values: [f64; 3],
    /// The refinement ratio between levels.
    pub refinement: f64,
    /// R of (16.12); None where q₁ = q₂ (within [`AGREE`]).
    pub ratio: Option<f64>,
    /// p of (16.13), only for a monotone triplet.
    pub order: Option<f64>,
    pub class: Convergence,
    /// q* of (16.14) for a monotone triplet; the finest value q₃ otherwise.
    pub extrapolated: f64,
    /// The coarsest level's error estimate, q₁ − q*.
    pub error: f64,
}

impl Triplet {
    /// Where the triplet is not monotone, what it means, with the numbers.
    pub fn note(&self, what: &str) -> Option<String> {
        let [q1, q2, q3] = self.values;
        let ratio = self.ratio.map_or("undefined (q1 = q2)".to_string(), |r| format!("{r:.3}"));
        match self.class {
            Convergence::Monotone | Convergence::Converged => None,
            c => Some(format!(
                "{what}: refinement does not converge monotonically ({}, R = {ratio}): {q1:.6e}, {q2:.6e}, \
                 {q3:.6e}; no extrapolation, the finest pilot taken, the estimate is the difference from it",
                c.name()
            )),
        }
    }
}

/// The analysis of values `q` (coarse to fine) at levels refined by `r`
/// each (16.12)–(16.14).
pub fn richardson(q: [f64; 3], r: f64) -> Triplet {
    let [q1, q2, q3] = q;
    let scale = q1.abs().max(q2.abs()).max(q3.abs());
    let (d12, d23) = (q1 - q2, q2 - q3);
    let tiny = |d: f64| d.abs() <= AGREE * scale;
    let ratio = (!tiny(d12)).then(|| d23 / d12);
    let finest =
        |class| Triplet { values: q, refinement: r, ratio, order: None, class, extrapolated: q3, error: q1 - q3 };
    if tiny(d23) {
        return finest(Convergence::Converged);
    }
    match ratio {
        Some(rr) if rr > 0.0 && rr < 1.0 => {
            let extrapolated = q3 + (q3 - q2) * rr / (1.0 - rr);
            Triplet {
                values: q,
                refinement: r,
                ratio,
                order: Some((1.0 / rr).ln() / r.ln()),
                class: Convergence::Monotone,
                extrapolated,
                error: q1 - extrapolated,
            }
        }
        Some(rr) if rr < 0.0 => finest(Convergence::Oscillatory),
        _ => finest(Convergence::Divergent),
    }
}

/// The extreme (`max`: the largest, else the smallest) of samples `(t, y)`
/// over [t0, t1]: the vertex of the parabola through the extreme sample and
/// its two neighbours, where both lie in the window and the vertex between
/// them; the sample itself otherwise (an extreme at the window's edge).
pub fn peak(samples: &[(f64, f64)], (t0, t1): (f64, f64), max: bool) -> f64 {
    let eps = 1e-9 * t1.abs().max(1.0);
    let inside: Vec<(f64, f64)> = samples.iter().copied().filter(|(t, _)| *t >= t0 - eps && *t <= t1 + eps).collect();
    let sign = if max { 1.0 } else { -1.0 };
    let Some(k) = (0..inside.len()).max_by(|&a, &b| (sign * inside[a].1).total_cmp(&(sign * inside[b].1))) else {
        return f64::NAN;
    };
    let yk = inside[k].1;
    if k == 0 || k + 1 >= inside.len() {
        return yk;
    }
    let ((ta, ya), (tb, yb), (tc, yc)) = (inside[k - 1], inside[k], inside[k + 1]);
    // divided differences of the parabola through the three points
    let f_ab = (yb - ya) / (tb - ta);
    let f_bc = (yc - yb) / (tc - tb);
    let a = (f_bc - f_ab) / (tc - ta);
    if sign * a >= 0.0 {
        return yk;
    }
    // y = yb + f_ab (t - tb) + a (t - ta)(t - tb), y' = 0 at
    let tv = 0.5 * (ta + tb) - f_ab / (2.0 * a);
    if !(tv > ta && tv < tc) {
        return yk;
    }
    let v = yb + f_ab * (tv - tb) + a * (tv - ta) * (tv - tb);
    if sign * (v - yk) >= 0.0 { v } else { yk }
}

/// The time mean of samples `(t, y)` over [t0, t1] by the trapezoid rule
/// over the samples inside (the pilots' windows start and end on every
/// level's steps).
pub fn time_mean(samples: &[(f64, f64)], (t0, t1): (f64, f64)) -> f64 {
    let eps = 1e-9 * t1.abs().max(1.0);
    let (mut integral, mut span) = (0.0, 0.0);
    for w in samples.windows(2) {
        let ((ta, ya), (tb, yb)) = (w[0], w[1]);
        if ta >= t0 - eps && tb <= t1 + eps {
            integral += 0.5 * (ya + yb) * (tb - ta);
            span += tb - ta;
        }
    }
    integral / span
}

/// The pilots' window and duration: the user's window [w0, w1] cut to
/// [w0, min(w1, w0 + k T)], T the slowest forcing's period (the motion's
/// or the sea's), k [`PILOT_PERIODS`] ([`PILOT_PERIODS_IRREGULAR`] in an
/// irregular sea); without a period the user's window as it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PilotPlan {
    pub window: (f64, f64),
    /// The pilots' simulated time, s: the window's end.
    pub duration: f64,
    /// The user's window was shortened.
    pub cut: bool,
}

impl PilotPlan {
    pub fn new(window: (f64, f64), period: Option<f64>, irregular: bool) -> PilotPlan {
        let (w0, w1) = window;
        let end = period.filter(|p| *p > 0.0).map_or(w1, |p| w1.min(w0 + pilot_periods(irregular) * p));
        PilotPlan { window: (w0, end), duration: end, cut: end < w1 }
    }
}

/// The periods of the slowest forcing the pilots' window spans:
/// [`PILOT_PERIODS`], [`PILOT_PERIODS_IRREGULAR`] in an irregular sea.
pub fn pilot_periods(irregular: bool) -> f64 {
    if irregular { PILOT_PERIODS_IRREGULAR } else { PILOT_PERIODS }
}

/// A run's motion and window, what the pilots repeat.
pub struct RunSpec<'a> {
    /// The hang-off's motion (displacement and velocity at t).
    pub motion: &'a (dyn Fn(f64) -> HangOff + Sync),
    /// The user's steady window, s.
    pub window: (f64, f64),
    /// The slowest forcing's period, s (None: none, the pilots run the window).
    pub period: Option<f64>,
    /// The sea is irregular (a spectrum, a table of components): the
    /// pilots span [`PILOT_PERIODS_IRREGULAR`] of its T_p.
    pub irregular: bool,
    /// Steps a factorised Newton tangent may be reused for (the run's).
    pub max_tangent_age: u32,
    /// The run's fatigue (its curve, SCF, DFF), for [`Quantity::FatigueDamage`].
    pub fatigue: Option<super::fatigue::FatigueSpec>,
}

/// One pilot run and its quantities.
#[derive(Debug, Clone, PartialEq)]
pub struct Pilot {
    pub n_elements: usize,
    pub time_step: f64,
    /// The quantities, in [`PilotRuns::quantities`]' order (a single
    /// line's: [`Quantity::ALL`]'s; NaN: not of this scene, or the
    /// touchdown off the seabed in the window).
    pub values: Vec<f64>,
    /// Its elapsed time, s (0 where reused).
    pub wall_s: f64,
    /// Run in an earlier round of the same choice and taken from it, not
    /// run again.
    pub reused: bool,
}

/// A scene as its pilots run it (docs/theory.md §16.14): one line on a
/// run ([`LinePilots`]) or a system of lines on the vessel's motion
/// ([`super::system_accuracy::SystemPilots`]). Its mesh is one number n:
/// a line's elements, a system's level ([`super::system_accuracy::line_elements`]).
pub trait PilotRuns: Sync {
    /// The quantities a pilot measures, in [`Pilot::values`]' order.
    fn quantities(&self) -> Vec<Quantity>;
    /// Whether the scene has `q` (`fatigue`: the run counts fatigue): only
    /// those are estimated.
    fn applies(&self, q: Quantity) -> bool;
    /// The run's window and slowest period, as the pilots cut it.
    fn plan(&self) -> PilotPlan;
    /// One pilot of `plan` at mesh `n`, step `time_step` (s) and Newton
    /// tolerance `newton_tolerance`, the rest the scene's.
    fn run(&self, plan: &PilotPlan, n: usize, time_step: f64, newton_tolerance: f64) -> Result<Pilot, RiserError>;
}

/// One line's pilots: `scene` on the run `spec` ([`run_pilot`]).
pub struct LinePilots<'a> {
    pub scene: &'a Scene,
    pub spec: &'a RunSpec<'a>,
}

impl PilotRuns for LinePilots<'_> {
    fn quantities(&self) -> Vec<Quantity> {
        Quantity::ALL.to_vec()
    }

    fn applies(&self, q: Quantity) -> bool {
        q.applies(self.scene, self.spec.fatigue.is_some())
    }

    fn plan(&self) -> PilotPlan {
        PilotPlan::new(self.spec.window, self.spec.period, self.spec.irregular)
    }

    fn run(&self, plan: &PilotPlan, n: usize, time_step: f64, newton_tolerance: f64) -> Result<Pilot, RiserError> {
        if newton_tolerance == self.scene.analysis.newton_tolerance {
            return run_pilot(self.scene, self.spec, plan, n, time_step);
        }
        let mut scene = self.scene.clone();
        scene.analysis.newton_tolerance = newton_tolerance;
        run_pilot(&scene, self.spec, plan, n, time_step)
    }
}

/// One pilot: `plan`'s run of `scene` at `n_elements` and `time_step`, the
/// rest of the numerics the scene's, and its quantities over the plan's
/// window: the top tension's at every step, the touchdown's and the stress
/// range's where the scene has them.
pub fn run_pilot(
    scene: &Scene,
    spec: &RunSpec,
    plan: &PilotPlan,
    n_elements: usize,
    time_step: f64,
) -> Result<Pilot, RiserError> {
    let start = std::time::Instant::now();
    let mut scene = scene.clone();
    scene.analysis.n_elements = n_elements;
    scene.analysis.time_step = time_step;
    let mut sim = Simulation::from_scene(&scene)?;
    sim.integrator.options_mut().max_tangent_age = spec.max_tangent_age;
    sim.start((spec.motion)(0.0));
    let n = super::internal_steps(plan.duration, time_step).map_err(RiserError::Unsupported)?;
    let design = super::design::Design::new(&scene);
    let (on_seabed, stresses) = (scene.seabed.is_some(), design.has_stresses());
    let mut fatigue = match (&spec.fatigue, stresses) {
        (Some(f), true) => {
            super::fatigue::FatigueTracker::new(f.clone(), &design, &sim.integrator.line_points(&sim.state))
        }
        _ => None,
    };
    let length = scene.line.length;
    let (w0, w1) = plan.window;
    let eps = 1e-9 * w1.abs().max(1.0);
    let mut tension = Vec::with_capacity(n as usize + 1);
    let mut touchdown = Vec::new();
    let mut stress = super::design::StressRange::default();
    let mut record = |sim: &Simulation, t: f64| {
        tension.push((t, sim.integrator.top_force(&sim.state).norm()));
        if t < w0 - eps || t > w1 + eps {
            return;
        }
        if on_seabed {
            let s = sim.integrator.outputs(&sim.state).touchdown_s;
            touchdown.push((t, if s < length { s } else { f64::NAN }));
        }
        if stresses {
            let points = sim.integrator.line_points(&sim.state);
            stress.add(&design, &points, sim.state.config.x[0].z);
            if let Some(f) = fatigue.as_mut() {
                f.add(&design, &points, sim.state.config.x[0].z);
            }
        }
    };
    record(&sim, 0.0);
    for k in 1..=n {
        let t = super::internal_step_end(0.0, plan.duration, time_step, k, n);
        sim.advance_to(t, spec.motion)?;
        record(&sim, t);
    }
    let (max, min) = (peak(&tension, plan.window, true), peak(&tension, plan.window, false));
    let mean = time_mean(&tension, plan.window);
    // the touchdown off the seabed at a step of the window: no extreme
    let lifted = touchdown.is_empty() || touchdown.iter().any(|(_, s)| s.is_nan());
    let td = |max| if lifted { f64::NAN } else { peak(&touchdown, plan.window, max) };
    let range = stress.largest().map_or(f64::NAN, |r| r.0);
    let damage = fatigue.as_mut().and_then(|f| {
        f.finish();
        f.worst()
    });
    Ok(Pilot {
        n_elements,
        time_step,
        values: vec![max, min, max - min, mean, td(true), td(false), range, damage.map_or(f64::NAN, |w| w.damage)],
        wall_s: start.elapsed().as_secs_f64(),
        reused: false,
    })
}

/// The estimate of one quantity (16.15), (16.16).
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    pub quantity: Quantity,
    /// The quantity at the user's numerics, q(n, Δt), over the pilots' window.
    pub value: f64,
    /// q* of (16.15).
    pub extrapolated: f64,
    /// e of (16.16), signed: value − extrapolated.
    pub error: f64,
    /// |e| / |q*|.
    pub relative: f64,
    /// |e_t| + |e_h|.
    pub bound: f64,
    /// The bound times the GCI's safety factor ([`GCI_SAFETY`], [`GCI_SAFETY_UNCONVERGED`]).
    pub gci: f64,
    /// Levels: elements n, 2n, 4n at Δt/4.
    pub mesh: Triplet,
    /// Levels: Δt, Δt/2, Δt/4 at n elements.
    pub step: Triplet,
    /// What is not monotone, with its numbers (empty: both triplets are).
    pub notes: Vec<String>,
}

impl Estimate {
    /// From the pilots' values: `mesh` at n, 2n, 4n (Δt/4), `step` at Δt,
    /// Δt/2, Δt/4 (n), the last of each the same pilot.
    pub fn of(quantity: Quantity, mesh: [f64; 3], step: [f64; 3]) -> Estimate {
        let (m, s) = (richardson(mesh, 2.0), richardson(step, 2.0));
        let notes = [m.note("mesh (n, 2n, 4n elements)"), s.note("step (dt, dt/2, dt/4)")];
        // the user's numerics the coarse level of the step triplet (16.16)
        let bound = m.error.abs() + s.error.abs();
        Estimate::of_triplets(quantity, (m, s), (step[0], mesh[0]), bound, notes)
    }

    /// From the pilots' values of [`Layout::Corner`]: `mesh` at n/4, n/2, n
    /// (Δt), `step` at 4Δt, 2Δt, Δt (n), the last of each the same pilot,
    /// whose error (16.15), (16.16) is the estimate's.
    pub fn of_corner(quantity: Quantity, mesh: [f64; 3], step: [f64; 3]) -> Estimate {
        let (m, s) = (richardson(mesh, 2.0), richardson(step, 2.0));
        let notes = [m.note("mesh (n/4, n/2, n elements)"), s.note("step (4dt, 2dt, dt)")];
        let value = mesh[2];
        // the candidate the fine level of both triplets
        let bound = (value - m.extrapolated).abs() + (value - s.extrapolated).abs();
        Estimate::of_triplets(quantity, (m, s), (value, value), bound, notes)
    }

    /// (16.15), (16.16) of the triplets `(mesh, step)` for the pilot `value`
    /// whose error is estimated, `shared` the pilot both triplets run.
    fn of_triplets(
        quantity: Quantity,
        (mesh, step): (Triplet, Triplet),
        (value, shared): (f64, f64),
        bound: f64,
        notes: [Option<String>; 2],
    ) -> Estimate {
        let extrapolated = mesh.extrapolated + step.extrapolated - shared;
        let error = value - extrapolated;
        let notes: Vec<String> = notes.into_iter().flatten().collect();
        let safety = if notes.is_empty() { GCI_SAFETY } else { GCI_SAFETY_UNCONVERGED };
        Estimate {
            quantity,
            value,
            extrapolated,
            error,
            relative: error.abs() / extrapolated.abs(),
            bound,
            gci: safety * bound,
            mesh,
            step,
            notes,
        }
    }

    /// One line: the estimate, the orders, what did not converge.
    pub fn summary(&self) -> String {
        self.summary_of(&[])
    }

    /// [`Estimate::summary`], a system's lines named by `lines`.
    pub fn summary_of(&self, lines: &[String]) -> String {
        let order = |t: &Triplet| match t.order {
            Some(p) => format!("order {p:.2}"),
            None => t.class.name().to_string(),
        };
        let mut s = format!(
            "error estimate of {} ({}): {:.6e} at your numerics, {:.6e} extrapolated, error {:.3e} ({:.2e} \
             relative; mesh {:.2e}, {}; step {:.2e}, {})",
            self.quantity.label(lines),
            self.quantity.unit(),
            self.value,
            self.extrapolated,
            self.error.abs(),
            self.relative,
            self.mesh.error,
            order(&self.mesh),
            self.step.error,
            order(&self.step),
        );
        for n in &self.notes {
            s.push_str("; ");
            s.push_str(n);
        }
        s
    }
}

/// The estimate of every quantity and the pilots it took.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorEstimate {
    pub plan: PilotPlan,
    /// The base's elements and step (the user's for `--estimate-error`).
    pub n_elements: usize,
    pub time_step: f64,
    /// [`Layout::levels`]' order: (n, Δt), (n, Δt/2), (n, Δt/4), (2n, Δt/4),
    /// (4n, Δt/4) about the base of [`Layout::Base`].
    pub pilots: Vec<Pilot>,
    /// The quantities of the pilots' values, in their order ([`PilotRuns::quantities`]).
    pub quantities: Vec<Quantity>,
    /// The quantities of the scene, in [`Quantity::ALL`]'s order.
    pub estimates: Vec<Estimate>,
    /// Quantities of the scene not estimated, and why.
    pub notes: Vec<String>,
    /// The pilots' wall time, s (on their threads: the elapsed time).
    pub wall_s: f64,
}

impl ErrorEstimate {
    /// The estimate of `q` (None: not of this scene, or not estimated: [`ErrorEstimate::notes`]).
    pub fn of(&self, q: Quantity) -> Option<&Estimate> {
        self.estimates.iter().find(|e| e.quantity == q)
    }
}

/// The pilots' (elements, step) of the user's `n` and `dt`, in
/// [`ErrorEstimate::pilots`]' order.
pub fn pilot_levels(n: usize, dt: f64) -> [(usize, f64); 5] {
    [(n, dt), (n, dt / 2.0), (n, dt / 4.0), (2 * n, dt / 4.0), (4 * n, dt / 4.0)]
}

/// Where a round's five pilots lie about its base (n₀, Δt₀), the coarsest
/// level of each triplet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// The triplets through the coarse corner (`--estimate-error`, the
    /// user's numerics the base): Δt₀, Δt₀/2, Δt₀/4 at n₀ and n₀, 2n₀,
    /// 4n₀ at Δt₀/4; 31 times the work of the base.
    Base,
    /// The triplets through the fine corner (4n₀, Δt₀/4), the candidate a
    /// round of `accuracy` measures (docs/theory.md §16.13): Δt₀, Δt₀/2,
    /// Δt₀/4 at 4n₀ and n₀, 2n₀, 4n₀ at Δt₀/4; 40 times the work of the
    /// base, 2.5 times the candidate's.
    Corner,
}

impl Layout {
    /// The five pilots (elements, step) about the base `n`, `dt`, and the
    /// indices of the step triplet and of the mesh triplet (coarse to fine;
    /// their finest, the shared pilot, last).
    pub fn levels(self, n: usize, dt: f64) -> ([(usize, f64); 5], [usize; 3], [usize; 3]) {
        match self {
            Layout::Base => (pilot_levels(n, dt), [0, 1, 2], [2, 3, 4]),
            Layout::Corner => (
                [(4 * n, dt), (4 * n, dt / 2.0), (4 * n, dt / 4.0), (2 * n, dt / 4.0), (n, dt / 4.0)],
                [0, 1, 2],
                [4, 3, 2],
            ),
        }
    }
}

/// The estimate of the error of `scene`'s numerics (its n_elements and
/// time_step) on the run `spec`, its pilots on up to `threads` threads.
pub fn estimate_error(scene: &Scene, spec: &RunSpec, threads: usize) -> Result<ErrorEstimate, RiserError> {
    estimate_error_laid(scene, spec, threads, Layout::Base, &[])
}

/// The pilots of `layout` about `scene`'s numerics (the base) on the run
/// `spec`, on up to `threads` threads, and the estimates of their triplets:
/// of the base's error ([`Layout::Base`]) or of the fine corner's
/// ([`Layout::Corner`]). A level among `known` (pilots of the same run and
/// numerics run before: an earlier round's) is taken from them, not run
/// again.
pub fn estimate_error_laid(
    scene: &Scene,
    spec: &RunSpec,
    threads: usize,
    layout: Layout,
    known: &[Pilot],
) -> Result<ErrorEstimate, RiserError> {
    let a = &scene.analysis;
    estimate_on(&LinePilots { scene, spec }, (a.n_elements, a.time_step, a.newton_tolerance), threads, layout, known)
}

/// [`estimate_error_laid`] of any scene's pilots `runs` about the base
/// `(n, dt, newton_tolerance)`.
pub fn estimate_on(
    runs: &dyn PilotRuns,
    (n, dt, tolerance): (usize, f64, f64),
    threads: usize,
    layout: Layout,
    known: &[Pilot],
) -> Result<ErrorEstimate, RiserError> {
    let plan = runs.plan();
    let (levels, step_at, mesh_at) = layout.levels(n, dt);
    let start = std::time::Instant::now();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let same = |p: &Pilot, (ne, h): (usize, f64)| p.n_elements == ne && (p.time_step / h - 1.0).abs() < 1e-12;
    let reused: Vec<Option<Pilot>> = levels
        .iter()
        .map(|&l| known.iter().find(|p| same(p, l)).map(|p| Pilot { wall_s: 0.0, reused: true, ..p.clone() }))
        .collect();
    // the costliest first, those not known
    let mut order: Vec<usize> = (0..levels.len()).filter(|&i| reused[i].is_none()).collect();
    order.sort_by(|&a, &b| (levels[b].0 as f64 / levels[b].1).total_cmp(&(levels[a].0 as f64 / levels[a].1)));
    let results: Vec<(usize, Result<Pilot, RiserError>)> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..threads.clamp(1, levels.len()))
            .map(|_| {
                s.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(&i) = order.get(k) else { break };
                        let (ne, h) = levels[i];
                        done.push((i, runs.run(&plan, ne, h, tolerance)));
                    }
                    done
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap_or_default()).collect()
    });
    let mut pilots: Vec<Option<Pilot>> = reused;
    for (i, r) in results {
        let (ne, h) = levels[i];
        pilots[i] = Some(r.map_err(|e| {
            RiserError::Unsupported(format!("the error estimate's pilot at {ne} elements, time_step {h} s: {e}"))
        })?);
    }
    let pilots: Vec<Pilot> = pilots
        .into_iter()
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| RiserError::Unsupported("an error estimate's pilot thread stopped".to_string()))?;
    let mut estimates = Vec::new();
    let mut notes = Vec::new();
    let quantities = runs.quantities();
    for (slot, &q) in quantities.iter().enumerate().filter(|(_, q)| runs.applies(**q)) {
        let v = |i: usize| pilots[i].values[slot];
        if (0..pilots.len()).all(|i| v(i).is_finite()) {
            let (mesh, step) = (mesh_at.map(v), step_at.map(v));
            estimates.push(match layout {
                Layout::Base => Estimate::of(q, mesh, step),
                Layout::Corner => Estimate::of_corner(q, mesh, step),
            });
        } else {
            notes.push(format!(
                "{}: not estimated, a pilot has none over the window (the line off the seabed at a step of it)",
                q.name()
            ));
        }
    }
    Ok(ErrorEstimate {
        plan,
        n_elements: n,
        time_step: dt,
        pilots,
        quantities,
        estimates,
        notes,
        wall_s: start.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_peak_of_a_sampled_parabola_is_exact() {
        let f = |t: f64| 3.0 - 2.0 * (t - 0.537).powi(2);
        let s: Vec<(f64, f64)> = (0..=20).map(|k| (k as f64 * 0.1, f(k as f64 * 0.1))).collect();
        assert!((peak(&s, (0.0, 2.0), true) - 3.0).abs() < 1e-12);
        // at the window's edge: the sample
        assert_eq!(peak(&s, (0.0, 2.0), false), f(2.0));
    }

    #[test]
    fn the_plan_cuts_the_window_to_three_periods() {
        let p = PilotPlan::new((20.0, 200.0), Some(10.0), false);
        assert_eq!((p.window, p.duration, p.cut), ((20.0, 50.0), 50.0, true));
        let p = PilotPlan::new((20.0, 40.0), Some(10.0), false);
        assert_eq!((p.window, p.duration, p.cut), ((20.0, 40.0), 40.0, false));
        // an irregular sea: twenty peak periods
        let p = PilotPlan::new((20.0, 400.0), Some(10.0), true);
        assert_eq!((p.window, p.duration, p.cut), ((20.0, 220.0), 220.0, true));
    }
}
