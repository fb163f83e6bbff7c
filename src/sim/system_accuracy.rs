//! `accuracy` on a system of lines (issue 51 on issue 49's systems;
//! docs/theory.md §16.14): the single line's measured choice
//! ([`super::accuracy::choose_on`]) with the system's pilots. A pilot runs
//! the whole system ([`SystemRun`]) on the vessel's motion at one mesh
//! level and the system's one time step; its mesh is a level n, every
//! line refined by the same factor (16.21, [`line_elements`]), and the
//! quantities the target is on are the vessel's resultant force and moment
//! (their components' min, mean and max over the window, each relative to
//! the largest magnitude of its resultant) and each line's top tension
//! (min, mean, max relative to that line's max).

use super::accuracy::{Choice, Pinned, Problem, choose_on};
use super::error::{AccuracyError, RiserError};
use super::error_estimate::{ErrorEstimate, Layout, Pilot, PilotPlan, PilotRuns, Quantity, Stat, estimate_on};
use super::system_dynamics::SystemRun;
use super::vessel::VesselMotion;
use crate::math::V3;
use crate::scene::AccuracyQuantity;
use crate::scene::system::SystemScene;

/// The fewest elements a line of a system takes at any level.
pub const MIN_LINE_ELEMENTS: usize = 2;

/// The system's mesh level as written: its most refined line's elements
/// (the most of any line), K of (16.21).
pub fn mesh_level(sys: &SystemScene) -> usize {
    sys.lines.iter().map(|l| l.n_elements).max().unwrap_or(0)
}

/// Each line's elements at level `n` (in the system's order):
///
///   n_i(n) = max(2, round(n n_i / K))                                       (16.21)
///
/// n_i the line's elements as written, K [`mesh_level`]: every line
/// refined by the same factor n/K, each keeping its ratio to the others, the
/// most refined line at exactly n (a line of K elements, or whose n n_i/K
/// is whole, doubles exactly with n; another within half an element).
pub fn line_elements(sys: &SystemScene, n: usize) -> Vec<usize> {
    let k = mesh_level(sys).max(1) as f64;
    sys.lines.iter().map(|l| ((n as f64 * l.n_elements as f64 / k).round() as usize).max(MIN_LINE_ELEMENTS)).collect()
}

/// The step q of the levels at which every line's n n_i/K is whole, so
/// that (16.21) rounds nothing and the pilots' levels n₀, 2n₀, 4n₀ refine
/// every line exactly twice: K / gcd(K, n_1, …, n_m). Where q is more than
/// K/4 (the levels would not reach a quarter of the mesh as written),
/// 1: any level, the lines rounded.
pub fn level_step(sys: &SystemScene) -> usize {
    fn gcd(a: usize, b: usize) -> usize {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    let k = mesh_level(sys).max(1);
    let q = k / sys.lines.iter().fold(k, |g, l| gcd(g, l.n_elements));
    if q * 4 > k { 1 } else { q }
}

/// `sys` with its lines at mesh level `n` (16.21).
pub fn at_level(sys: &SystemScene, n: usize) -> SystemScene {
    let mut s = sys.clone();
    for (l, e) in s.lines.iter_mut().zip(line_elements(sys, n)) {
        l.n_elements = e;
    }
    s
}

/// A system's run, what its pilots repeat: the vessel's motion and the
/// steady window.
pub struct SystemRunSpec<'a> {
    /// The vessel's motion at t.
    pub motion: &'a (dyn Fn(f64) -> VesselMotion + Sync),
    /// The steady window, s.
    pub window: (f64, f64),
    /// The slowest forcing's period, s (None: the pilots run the window).
    pub period: Option<f64>,
    /// The sea is irregular.
    pub irregular: bool,
    /// Steps a factorised Newton tangent may be reused for (the run's).
    pub max_tangent_age: u32,
}

/// The quantities of a system's pilot, in [`Pilot::values`]' order: the
/// resultant force's x, y, z and magnitude, each min, mean, max; the
/// moment's alike; each line's top tension min, mean, max.
pub fn quantities(lines: usize) -> Vec<Quantity> {
    let resultant = |make: fn(usize, Stat) -> Quantity| {
        (0..4).flat_map(move |axis| Stat::ALL.into_iter().map(move |stat| make(axis, stat)))
    };
    resultant(|axis, stat| Quantity::VesselForce { axis, stat })
        .chain(resultant(|axis, stat| Quantity::VesselMoment { axis, stat }))
        .chain((0..lines).flat_map(|line| Stat::ALL.into_iter().map(move |stat| Quantity::LineTension { line, stat })))
        .collect()
}

/// The quantities a system's target is on, each with the one its error is
/// relative to (16.18): the resultant's components to its largest
/// magnitude, a line's top tension to its max. `accuracy_quantity` is
/// `top_tension` (the default) or `all`: the same set.
pub fn criteria(target: AccuracyQuantity, lines: usize) -> Result<Vec<(Quantity, Quantity)>, AccuracyError> {
    if !matches!(target, AccuracyQuantity::TopTension | AccuracyQuantity::All) {
        return Err(AccuracyError::NoQuantity {
            quantity: target.name(),
            reason: "a system's target is on the vessel's resultant force and moment and each line's top tension \
                     (accuracy_quantity = top_tension or all)",
        });
    }
    let mut c = Vec::new();
    for axis in 0..3 {
        for stat in Stat::ALL {
            c.push((Quantity::VesselForce { axis, stat }, Quantity::VesselForce { axis: 3, stat: Stat::Max }));
            c.push((Quantity::VesselMoment { axis, stat }, Quantity::VesselMoment { axis: 3, stat: Stat::Max }));
        }
    }
    for line in 0..lines {
        for stat in Stat::ALL {
            c.push((Quantity::LineTension { line, stat }, Quantity::LineTension { line, stat: Stat::Max }));
        }
    }
    Ok(c)
}

/// A system's pilots: `sys` on the run `spec`.
pub struct SystemPilots<'a> {
    pub sys: &'a SystemScene,
    pub spec: &'a SystemRunSpec<'a>,
}

impl PilotRuns for SystemPilots<'_> {
    fn quantities(&self) -> Vec<Quantity> {
        quantities(self.sys.lines.len())
    }

    fn applies(&self, _: Quantity) -> bool {
        true
    }

    fn plan(&self) -> PilotPlan {
        PilotPlan::new(self.spec.window, self.spec.period, self.spec.irregular)
    }

    fn run(&self, plan: &PilotPlan, n: usize, time_step: f64, newton_tolerance: f64) -> Result<Pilot, RiserError> {
        run_system_pilot(self.sys, self.spec, plan, n, (time_step, newton_tolerance))
    }
}

/// One pilot of a system: `plan`'s run of `sys` at mesh level `n` (16.21),
/// step and Newton tolerance `(dt, tolerance)`, the lines on this thread
/// (the pilots are on threads); its quantities over the plan's window.
pub fn run_system_pilot(
    sys: &SystemScene,
    spec: &SystemRunSpec,
    plan: &PilotPlan,
    n: usize,
    (dt, tolerance): (f64, f64),
) -> Result<Pilot, RiserError> {
    let start = std::time::Instant::now();
    let mut s = at_level(sys, n);
    s.analysis.time_step = dt;
    s.analysis.newton_tolerance = tolerance;
    let mut run = SystemRun::new(&s).map_err(RiserError::Unsupported)?;
    for l in &mut run.lines {
        l.sim.integrator.options_mut().max_tangent_age = spec.max_tangent_age;
    }
    run.start(&(spec.motion)(0.0));
    let steps = super::internal_steps(plan.duration, dt).map_err(RiserError::Unsupported)?;
    let lines = run.lines.len();
    // per output time: the resultant force and moment on the vessel (the
    // lines hung from it, §17.7) and each line's top tension
    let mut force: Vec<(f64, V3)> = Vec::with_capacity(steps as usize + 1);
    let mut moment: Vec<(f64, V3)> = Vec::with_capacity(steps as usize + 1);
    let mut tension: Vec<Vec<(f64, f64)>> = vec![Vec::with_capacity(steps as usize + 1); lines];
    let mut record = |run: &SystemRun, t: f64| {
        let outputs = run.outputs();
        let loads = run.resultant_on_vessel(&outputs);
        force.push((t, loads.force));
        moment.push((t, loads.moment));
        for (series, o) in tension.iter_mut().zip(&outputs) {
            series.push((t, o.top_force.norm()));
        }
    };
    record(&run, 0.0);
    for k in 1..=steps {
        let t = super::internal_step_end(0.0, plan.duration, dt, k, steps);
        run.advance_to(t, spec.motion, 1).map_err(|e| match e {
            super::system_dynamics::SystemStepError::Line(l) => l.error,
            super::system_dynamics::SystemStepError::Points(p) => RiserError::Points(p),
        })?;
        record(&run, t);
    }
    let values = quantities(lines)
        .into_iter()
        .map(|q| {
            let of = |series: &[(f64, V3)], axis: usize, stat: Stat| {
                let v: Vec<(f64, f64)> =
                    series.iter().map(|(t, f)| (*t, if axis < 3 { f[axis] } else { f.norm() })).collect();
                stat.of(&v, plan.window)
            };
            match q {
                Quantity::VesselForce { axis, stat } => of(&force, axis, stat),
                Quantity::VesselMoment { axis, stat } => of(&moment, axis, stat),
                Quantity::LineTension { line, stat } => stat.of(&tension[line], plan.window),
                _ => f64::NAN,
            }
        })
        .collect();
    Ok(Pilot { n_elements: n, time_step: dt, values, wall_s: start.elapsed().as_secs_f64(), reused: false })
}

/// The lines' names, the labels of their quantities.
pub fn line_names(sys: &SystemScene) -> Vec<String> {
    sys.lines.iter().map(|l| l.name.clone()).collect()
}

/// The numerics of `sys` (its `accuracy` set) that meet its target on the
/// run `spec` (docs/theory.md §16.14), pilots on up to `threads` threads:
/// the system at the chosen level, step and Newton tolerance, and the
/// choice (None, `sys` as it is, without `accuracy`).
pub fn apply(
    sys: SystemScene,
    spec: &SystemRunSpec,
    pinned: Pinned,
    threads: usize,
    progress: &mut dyn FnMut(&str),
) -> Result<(SystemScene, Option<Choice>), RiserError> {
    if sys.analysis.accuracy == 0.0 {
        return Ok((sys, None));
    }
    let names = line_names(&sys);
    let step = level_step(&sys);
    let fits = |n: usize| n % step == 0;
    let problem = Problem {
        runs: &SystemPilots { sys: &sys, spec },
        analysis: &sys.analysis,
        mesh: mesh_level(&sys),
        criteria: criteria(sys.analysis.accuracy_quantity, sys.lines.len())?,
        fits: &fits,
        line_names: &names,
    };
    let mut choice = choose_on(&problem, pinned, threads, progress)?;
    let mut chosen = at_level(&sys, choice.n_elements);
    chosen.analysis.time_step = choice.time_step;
    chosen.analysis.newton_tolerance = choice.newton_tolerance;
    choice.mesh_words = Some(mesh_words(&chosen, choice.n_elements, pinned.n_elements));
    Ok((chosen, Some(choice)))
}

/// "mesh level 40 (riser 40, chain_1 35, ...)": a system's mesh in words.
pub fn mesh_words(sys: &SystemScene, level: usize, yours: bool) -> String {
    let each: Vec<String> = sys.lines.iter().map(|l| format!("{} {}", l.name, l.n_elements)).collect();
    format!("mesh level {level}{} (elements: {})", if yours { " (yours)" } else { "" }, each.join(", "))
}

/// The error of `sys`'s own numerics (its lines as written, its step) on
/// the run `spec` (`riser run SYSTEM --estimate-error`; docs/theory.md
/// §16.11): the five pilots about them, levels K, 2K, 4K and Δt, Δt/2, Δt/4.
pub fn estimate_error(sys: &SystemScene, spec: &SystemRunSpec, threads: usize) -> Result<ErrorEstimate, RiserError> {
    let a = &sys.analysis;
    estimate_on(
        &SystemPilots { sys, spec },
        (mesh_level(sys), a.time_step, a.newton_tolerance),
        threads,
        Layout::Base,
        &[],
    )
}
