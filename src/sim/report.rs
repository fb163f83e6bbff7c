//! The static state of a scene as users read it: end forces, tension along
//! the line, the shape.

use super::error::RiserError;
use crate::loads;
use crate::math::V3;
use crate::model::cable::statics::{CableStatics, hanging_chain_start, touchdown_start};
use crate::model::cable::{Cable, CableModel};
use crate::model::rod::statics::{StaticLoads, StaticProblem, seabed_start};
use crate::model::rod::{self, Rod};
use crate::model::sections;
use crate::model::statics::{StaticOptions, StaticSolution};
use crate::scene::{Model, Scene};
use crate::solve::statics::{relax, solve};

/// One row of the static shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeRow {
    /// Reference arc length from the hang-off, m.
    pub s: f64,
    /// Position, m.
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// Axial force (effective tension), N.
    pub tension: f64,
}

/// Static equilibrium of a scene.
#[derive(Debug, Clone)]
pub struct StaticReport {
    /// |force at the hang-off|, N.
    pub top_tension: f64,
    /// |force at the anchor|, N.
    pub bottom_tension: f64,
    /// Force the line exerts on the vessel, N.
    pub top_force: V3,
    /// Force the line exerts on the anchor, N.
    pub bottom_force: V3,
    /// Smallest axial force along the line, N.
    pub min_tension: f64,
    pub iterations: usize,
    pub continuation_steps: usize,
    pub residual: f64,
    /// Rows at the element end nodes.
    pub shape: Vec<ShapeRow>,
    pub solution: StaticSolution,
}

impl StaticReport {
    /// The report of `sol` with its shape rows and smallest axial force (N).
    fn of_solution(sol: StaticSolution, shape: Vec<ShapeRow>, min_tension: f64) -> Self {
        StaticReport {
            top_tension: sol.reactions[0].norm(),
            bottom_tension: sol.reactions[1].norm(),
            top_force: -sol.reactions[0],
            bottom_force: -sol.reactions[1],
            min_tension,
            iterations: sol.iterations,
            continuation_steps: sol.continuation_steps,
            residual: sol.residual,
            shape,
            solution: sol,
        }
    }

    pub fn new(rod: &Rod, sol: StaticSolution) -> Self {
        let cfg = &sol.config;
        let tension = rod.nodal_axial_force(cfg);
        let mut shape: Vec<ShapeRow> = (0..=rod.n_el)
            .map(|a| ShapeRow { s: rod.s_node(a), x: cfg.x[a].x, y: cfg.x[a].y, z: cfg.x[a].z, tension: tension[a] })
            .collect();
        // At the ends the axial force from the element strains is the least
        // accurate value of the element (an under-resolved bending boundary
        // layer at a pinned end); the reaction of the discrete equations along
        // the line's tangent is exact there.
        let t0 = cfg.xp[0].normalize();
        let t1 = cfg.xp[rod.n_el].normalize();
        shape[0].tension = -sol.reactions[0].dot(&t0);
        shape[rod.n_el].tension = sol.reactions[1].dot(&t1);
        let interior_min = rod.min_gauss_axial_force(cfg);
        let min_tension = shape.iter().map(|r| r.tension).fold(interior_min, f64::min);
        StaticReport::of_solution(sol, shape, min_tension)
    }
}

impl StaticReport {
    /// The report of a cable's equilibrium: node rows with the mean tension
    /// of the adjacent segments, the reactions along the end segments at the ends.
    pub fn of_cable(cable: &Cable, sol: StaticSolution) -> Self {
        let x = &sol.config.x;
        let n = cable.n_el;
        let seg: Vec<f64> = (0..n).map(|e| cable.tension(x, e)).collect();
        let mut shape: Vec<ShapeRow> = (0..=n)
            .map(|a| {
                let t = if a == 0 || a == n { 0.0 } else { 0.5 * (seg[a - 1] + seg[a]) };
                ShapeRow { s: cable.s_node(a), x: x[a].x, y: x[a].y, z: x[a].z, tension: t }
            })
            .collect();
        shape[0].tension = -sol.reactions[0].dot(&(x[1] - x[0]).normalize());
        shape[n].tension = sol.reactions[1].dot(&(x[n] - x[n - 1]).normalize());
        let min_tension = shape.iter().map(|r| r.tension).chain(seg.iter().copied()).fold(f64::INFINITY, f64::min);
        StaticReport::of_solution(sol, shape, min_tension)
    }
}

/// Loads of the initial static state: gravity and buoyancy, and the current
/// when the scene's `static_current` asks for it (docs/theory.md §4).
pub fn scene_static_loads(scene: &Scene) -> StaticLoads {
    let props = sections::element_properties(scene);
    let mut loads = StaticLoads::gravity_only(loads::vertical_load(scene));
    loads.seabed = sections::seabed(scene, &props);
    loads.surface = Some(sections::free_surface(scene, &props));
    let current = loads::current(scene);
    let k = sections::drag_coefficients(scene, &props);
    if scene.analysis.static_current && !current.is_none() && !k.values().iter().all(|k| k.is_zero()) {
        loads.drag = Some((k, current));
    }
    loads
}

/// Solves the static equilibrium of a scene (with its line model).
pub fn solve_scene(scene: &Scene) -> Result<StaticReport, RiserError> {
    let rod = rod::of_scene(scene);
    let loads = scene_static_loads(scene);
    let start =
        seabed_start(&rod, &loads.vertical, scene.hang_off(), scene.anchor(), loads.seabed.as_ref().map(|b| b.first()));
    let tolerance = scene.analysis.newton_tolerance.min(1e-10);
    if scene.analysis.model == Model::Cable {
        let model = CableModel::from_scene(scene);
        let (top, anchor) = (scene.hang_off(), scene.anchor());
        let hanging = hanging_chain_start(&model, top, anchor);
        let below = |x: &Vec<V3>| model.seabed.as_ref().is_some_and(|b| x.iter().any(|p| b.penetration(p) > 0.0));
        let x0 = match hanging {
            Some(x) if !below(&x) => x,
            other => touchdown_start(&model, top, anchor).or(other).unwrap_or(start.x),
        };
        // Newton, with pseudo-transient continuation if Newton alone fails
        let sol = relax(&CableStatics::new(&model, loads.drag.is_some()), x0, tolerance)?;
        return Ok(StaticReport::of_cable(&model.cable, sol));
    }
    let opts = StaticOptions { tolerance, ..Default::default() };
    let sol = solve(&StaticProblem::new(&rod, &loads), start, &opts)?;
    Ok(StaticReport::new(&rod, sol))
}

/// The static equilibrium of a scene with its hang-off displaced by `d`
/// (m, global) from the scene's, the anchor held (the FMU's vessel inputs
/// not zero at the start, docs/theory.md §7.7): relaxed (pseudo-transient
/// continuation, then Newton) from `base`, the scene's own equilibrium,
/// shifted by d (1 − S/L) so that the start is smooth.
pub fn solve_scene_moved(scene: &Scene, base: &StaticReport, d: V3) -> Result<StaticReport, RiserError> {
    let loads = scene_static_loads(scene);
    let tolerance = scene.analysis.newton_tolerance.min(1e-10);
    let length = scene.line.length;
    let mut cfg = base.solution.config.clone();
    let fractions: Vec<f64> = base.shape.iter().map(|r| 1.0 - r.s / length).collect();
    for (x, f) in cfg.x.iter_mut().zip(&fractions) {
        *x += d * *f;
    }
    if scene.analysis.model == Model::Cable {
        let model = CableModel::from_scene(scene);
        let sol = relax(&CableStatics::new(&model, loads.drag.is_some()), cfg.x, tolerance)?;
        return Ok(StaticReport::of_cable(&model.cable, sol));
    }
    // the slope of the shift, d/dS of d (1 − S/L)
    for xp in cfg.xp.iter_mut() {
        *xp -= d / length;
    }
    let rod = rod::of_scene(scene);
    let sol = relax(&StaticProblem::new(&rod, &loads), cfg, tolerance)?;
    Ok(StaticReport::new(&rod, sol))
}

/// The relative resolution of the line's energy in the balance: a line held
/// still closes it to the round-off of summing |U| + |V| + K (a few 1e-16
/// of it, up to 1e-14 over long runs), so its residual counts against
/// `ENERGY_RESOLUTION` times that sum where less is exchanged: a still
/// line reads at most 1e-14 / 1e-8 = 1e-6, the project's closed balance
/// (`energy_balance_relative` of `riser run --json` and riser-sweep).
pub const ENERGY_RESOLUTION: f64 = 1e-8;
