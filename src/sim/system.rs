//! The statics of a system of lines on one vessel (issue 49; docs/theory.md
//! §17): each line is solved as the single-line scene it is
//! ([`SystemScene::line_scene`], its frame at its hang-off) with the vessel
//! at a pose, and the lines' forces on the vessel, their moments about the
//! reference point and their stiffnesses are composed. Free points (joints,
//! clump weights, buoys) are put in equilibrium by Newton on their positions
//! (§17.4), each line re-solved with its ends where they are (MoorPy's
//! nested approach), the Jacobian the lines' two-end stiffnesses
//! ([`crate::solve::eigen::end_stiffness6`]); the stiffness on the vessel is then the free
//! points' condensed one (17.8, 17.9).
//!
//! Pose: [surge, sway, heave, roll, pitch, yaw] (m, rad), the reference
//! point displaced by (surge, sway, heave) from its initial position (the
//! system's origin) and the vessel turned by R of the angles in the marine
//! z-y-x order (§14, R = Rz(yaw) Ry(pitch) Rx(roll)); a vessel point at ρ is
//! at x = u + R ρ.

use super::report::{StaticReport, scene_static_loads, solve_scene};
use crate::math::rigid::RotationOrder;
use crate::math::{M3, M6, V3, skew};
use crate::model::RodConfig;
use crate::model::cable::CableModel;
use crate::model::cable::linearized::CableLinearized;
use crate::model::cable::statics::{CableStatics, touchdown_start};
use crate::model::catenary::Touchdown;
use crate::model::rod::linearized::RodLinearized;
use crate::model::rod::statics::StaticProblem;
use crate::model::rod::{self, RodModel};
use crate::model::statics::{StaticEquations, StaticSolution};
use crate::scene::system::{MAX_REACH_STRAIN, PointKind, PointSpec, SystemScene, VesselEnd};
use crate::scene::{Model, Scene};
use crate::solve::eigen::{end_stiffness6_shifted, hang_off_stiffness6};
use crate::solve::statics::relax;
use nalgebra::{DMatrix, DVector};

/// One line's static state in the system.
#[derive(Debug, Clone)]
pub struct LineStatics {
    pub name: String,
    /// The single-line scene it was solved as (its frame at its hang-off).
    pub scene: Scene,
    pub report: StaticReport,
    /// Which end is the single-line scene's hang-off (the vessel point where
    /// the line has one; [`SystemScene::ends`]).
    pub hang_off_end: VesselEnd,
    /// Which end is on the vessel, if one is.
    pub vessel_end: Option<VesselEnd>,
    /// The hang-off's global position (the vessel point's where the line has one), m.
    pub fairlead: V3,
    /// The other end's (the single line's anchor) global position, m.
    pub anchor: V3,
    /// R ρ, the vessel point from the reference point (global axes), m;
    /// zero without a vessel end.
    pub arm: V3,
    /// |force| at the line's `from` and `to` ends, N.
    pub tension_from: f64,
    pub tension_to: f64,
    /// Smallest axial force along the line, N.
    pub min_tension: f64,
    /// Arc length from the hang-off end (the vessel end where there is one)
    /// to the first seabed contact, m (None: no contact).
    pub touchdown_s: Option<f64>,
    /// Where the line has a fixed end (its anchor), the force the line
    /// exerts on it, global, N: the reaction there (with what the
    /// discretisation lumps on the end node: half an element's weight and
    /// its seabed contact). None without a fixed end.
    pub anchor_force: Option<V3>,
    /// The line's angle at its fixed end above the horizontal, deg: the
    /// rod's tangent, the cable's last segment (a chain on a penalty seabed
    /// dips by its penetration over a segment). None without a fixed end.
    pub anchor_uplift_angle: Option<f64>,
    /// The line's 3×3 stiffness at its vessel point (the translation block
    /// of `hang_off_stiffness6`, §8.3: the support's force on the line per
    /// metre of the point's displacement, the line re-solved, its other end
    /// held), N/m; zero without a vessel end or unless asked for.
    pub stiffness: M3,
}

/// A free point's static state.
#[derive(Debug, Clone)]
pub struct PointStatics {
    pub name: String,
    /// Global position, m.
    pub position: V3,
    /// Its own load: weight, buoyancy and the seabed's contact (global), N.
    pub load: V3,
    /// The net force on it (its lines' forces and its load), N: what the
    /// equilibrium leaves.
    pub residual: V3,
}

/// The system's static state at a pose.
#[derive(Debug, Clone)]
pub struct SystemStatics {
    pub pose: [f64; 6],
    pub lines: Vec<LineStatics>,
    /// The free points, in the scene's order.
    pub points: Vec<PointStatics>,
    /// Newton iterations on the free points' positions (0 without them).
    pub iterations: usize,
    /// The lines' force on the vessel, global, N.
    pub force: V3,
    /// Their moment about the reference point, global, N m.
    pub moment: V3,
    /// −∂(F, M)/∂(surge, sway, heave, δroll, δpitch, δyaw), rotations as
    /// small global rotation-vector increments about the pose (17.3), the
    /// free points re-equilibrated (17.8, 17.9): N/m, N/rad, N m/m, N m/rad. Zero
    /// unless asked for.
    pub stiffness: M6,
}

/// The rotation of a pose's angles (z-y-x).
pub fn pose_rotation(pose: &[f64; 6]) -> M3 {
    RotationOrder::Zyx.rotation([pose[3], pose[4], pose[5]])
}

/// The 6×6 stiffness on the vessel's reference point of a pinned vessel
/// point at arm a = Rρ carrying force `force` (the line's on the vessel)
/// with the line's translation stiffness `s` (17.3):
/// `K = [S, −S[a]×; [a]× S, −[F]×[a]× − [a]× S [a]×]`.
pub fn point_stiffness6(s: &M3, arm: &V3, force: &V3) -> M6 {
    let ax = skew(arm);
    let mut k = M6::zeros();
    k.fixed_view_mut::<3, 3>(0, 0).copy_from(s);
    k.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-s * ax));
    k.fixed_view_mut::<3, 3>(3, 0).copy_from(&(ax * s));
    k.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-skew(force) * ax - ax * s * ax));
    k
}

/// The translation stiffness of a line's static state at its hang-off, its
/// anchor held (§8.3).
fn line_stiffness(scene: &Scene, rep: &StaticReport) -> Result<M3, String> {
    let loads = scene_static_loads(scene);
    let cfg = &rep.solution.config;
    let s6 = match scene.analysis.model {
        Model::Cable => {
            let model = CableModel::from_scene(scene);
            hang_off_stiffness6(&CableLinearized::new(&model, loads.drag.is_some()), cfg)
        }
        Model::Rod => {
            let model = RodModel::from_scene(scene);
            hang_off_stiffness6(&RodLinearized::new(&model, &loads), cfg)
        }
    }
    .map_err(|e| format!("line '{}': its stiffness: {e}", scene.name))?;
    Ok(s6.fixed_view::<3, 3>(0, 0).into_owned())
}

/// The two-end translation stiffness of a line's static state (17.6):
/// [δR_h; δR_a] = S [δx_h; δx_a], R the supports' forces on the line at its
/// hang-off and its anchor, N/m ([`crate::solve::eigen::end_stiffness6`]).
pub fn line_end_stiffness(scene: &Scene, rep: &StaticReport) -> Result<M6, String> {
    line_end_stiffness_shifted(scene, rep, 0.0)
}

/// [`line_end_stiffness`] with the interior held by springs of `shift` N/m
/// ([`end_stiffness6_shifted`]).
fn line_end_stiffness_shifted(scene: &Scene, rep: &StaticReport, shift: f64) -> Result<M6, String> {
    let loads = scene_static_loads(scene);
    let cfg = &rep.solution.config;
    match scene.analysis.model {
        Model::Cable => {
            let model = CableModel::from_scene(scene);
            end_stiffness6_shifted(&CableLinearized::new(&model, loads.drag.is_some()), cfg, shift)
        }
        Model::Rod => {
            let model = RodModel::from_scene(scene);
            end_stiffness6_shifted(&RodLinearized::new(&model, &loads), cfg, shift)
        }
    }
    .map_err(|e| format!("line '{}': its stiffness at its ends: {e}", scene.name))
}

/// The interior springs that give a Newton direction where a line's ends
/// have no stiffness (a chain slack on the frictionless seabed, the point
/// it holds rising): this fraction of the line's axial stiffness EA/l,
/// N/m (on a chain's, 1e-6 of 7.7e7 N/m: 1 % of the 1e4 N/m that its
/// tension gives transversely).
const SLACK_SPRING: f64 = 1e-6;

/// Line `i`'s state in the system: its scene and report, its ends'
/// global positions and, with `stiffness`, its vessel point's stiffness.
fn line_statics(
    sys: &SystemScene,
    i: usize,
    scene: Scene,
    rep: StaticReport,
    ends: (V3, V3, V3),
    stiffness: Option<M3>,
) -> LineStatics {
    let l = &sys.lines[i];
    let (hang_off_end, hp, ap) = sys.ends(i);
    let (fairlead, anchor, arm) = ends;
    let (top, bottom) = (rep.top_tension, rep.bottom_tension);
    let (tension_from, tension_to) = match hang_off_end {
        VesselEnd::From => (top, bottom),
        VesselEnd::To => (bottom, top),
    };
    let loads = scene_static_loads(&scene);
    let touchdown_s = loads.seabed.as_ref().and_then(|b| {
        let nodes: Vec<V3> = rep.shape.iter().map(|s| V3::new(s.x, s.y, s.z)).collect();
        let t = crate::loads::seabed::touchdown(b.first(), &nodes, |a| rep.shape[a].s, l.length);
        (t < l.length).then_some(t)
    });
    let fixed_end = ap.kind == PointKind::Fixed;
    let anchor_uplift_angle = anchor_uplift_angle(scene.analysis.model, &rep.solution.config);
    LineStatics {
        name: l.name.clone(),
        min_tension: rep.min_tension,
        anchor_force: fixed_end.then_some(rep.bottom_force),
        anchor_uplift_angle: fixed_end.then_some(anchor_uplift_angle),
        scene,
        report: rep,
        hang_off_end,
        vessel_end: (hp.kind == PointKind::Vessel).then_some(hang_off_end),
        fairlead,
        anchor,
        arm,
        tension_from,
        tension_to,
        touchdown_s,
        stiffness: stiffness.unwrap_or_else(M3::zeros),
    }
}

/// A line's angle above the horizontal at its anchor (its last node) in
/// configuration `cfg`, deg: of its direction up the line there, the rod's
/// tangent, the cable's last chord.
pub fn anchor_uplift_angle(model: Model, cfg: &crate::model::RodConfig) -> f64 {
    let n = cfg.x.len() - 1;
    let up = match model {
        Model::Rod => -cfg.xp[n],
        Model::Cable => cfg.x[n - 1] - cfg.x[n],
    };
    up.z.atan2(up.x.hypot(up.y)).to_degrees()
}

/// Solves every line of `sys` with the vessel at `pose`, the free points
/// in equilibrium, and composes the loads on the vessel; with `stiffness`,
/// the 6×6 stiffness too. An error names the line whose statics failed,
/// or the free point that found no equilibrium.
pub fn solve_system(sys: &SystemScene, pose: &[f64; 6], stiffness: bool) -> Result<SystemStatics, String> {
    if sys.points.iter().any(|p| p.kind == PointKind::Free) {
        return solve_free_from_scene(sys, pose, stiffness);
    }
    let r = pose_rotation(pose);
    let u = V3::new(pose[0], pose[1], pose[2]);
    let mut lines = Vec::with_capacity(sys.lines.len());
    let (mut force, mut moment, mut k) = (V3::zeros(), V3::zeros(), M6::zeros());
    for (i, l) in sys.lines.iter().enumerate() {
        let (_, vp, fp) = sys.ends(i);
        let arm = r * V3::from(vp.position);
        let fairlead = u + arm;
        let scene = sys.line_scene(i, fairlead);
        scene.validate().map_err(|e| format!("line '{}' at the pose: {e}", l.name))?;
        let rep = solve_scene(&scene).map_err(|e| format!("line '{}': {e}", l.name))?;
        let s = if stiffness { line_stiffness(&scene, &rep)? } else { M3::zeros() };
        let f = rep.top_force;
        force += f;
        moment += arm.cross(&f);
        if stiffness {
            k += point_stiffness6(&s, &arm, &f);
        }
        lines.push(line_statics(sys, i, scene, rep, (fairlead, V3::from(fp.position), arm), Some(s)));
    }
    Ok(SystemStatics { pose: *pose, lines, points: Vec::new(), iterations: 0, force, moment, stiffness: k })
}

/// How a line's end is held in the statics of a system with free points.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Held {
    /// A fixed point, at its position.
    Fixed(V3),
    /// The `k`-th vessel point of the scene (its position u + R ρ).
    Vessel(usize),
    /// The `k`-th free point (unknown).
    Free(usize),
}

/// The contact area over which a free point meets the seabed, m²: its
/// vertical spring is the seabed's `stiffness` (Pa/m, per unit contact
/// area) times this (docs/theory.md §17.4).
pub const POINT_CONTACT_AREA: f64 = 1.0;

/// A free point's own load at `x` (weight, buoyancy below the water
/// surface, the seabed's contact, eq. 17.4; a point with a `height`, its
/// draft's buoyancy, 17.23) and its stiffness −∂f/∂x.
pub fn point_load(sys: &SystemScene, p: &PointSpec, x: V3) -> (V3, M3) {
    let env = &sys.environment;
    let g = env.gravity;
    let mut f = V3::new(0.0, 0.0, -p.mass() * g);
    let mut k = M3::zeros();
    match p.height {
        None => {
            if x.z < env.water_surface_z {
                f.z += env.water_density * g * p.volume();
            }
        }
        Some(_) => {
            // a cylinder at the surface (17.23): ρ g A d, its stiffness ρ g A while partly submerged
            let (v, dv) = p.floater().displaced(x.z - env.water_surface_z);
            f.z += env.water_density * g * v;
            k[(2, 2)] -= env.water_density * g * dv;
        }
    }
    if let Some(b) = &sys.seabed {
        let depth = b.height_at(x.x, x.y) - x.z;
        if depth > 0.0 {
            let kp = b.stiffness * POINT_CONTACT_AREA;
            f.z += kp * depth;
            // f_z = k_p (h(x) − z): ∂f_z/∂x = k_p tan(slope), ∂f_z/∂z = −k_p
            k[(2, 2)] += kp;
            k[(2, 0)] -= kp * b.slope.to_radians().tan();
        }
    }
    (f, k)
}

/// A line of a system with a free end, solved with its ends at `h` (the
/// hang-off) and `a` (the anchor), global.
#[derive(Debug, Clone)]
pub struct Solved {
    pub h: V3,
    pub a: V3,
    pub scene: Scene,
    pub report: StaticReport,
}

/// Plain Newton on a line's static equations from `cfg`, at most
/// `max_iterations`: None if it does not converge (the caller starts
/// elsewhere or continues), as the first stage of `relax` does but without
/// its continuation.
fn plain_newton<P: StaticEquations>(
    p: &P,
    cfg: P::Config,
    tolerance: f64,
    max_iterations: usize,
) -> Option<StaticSolution> {
    let n = p.n_dof();
    let mut cfg = cfg;
    let mut sys = p.new_system().ok()?;
    let (mut r, mut du) = (vec![0.0; n], vec![0.0; n]);
    let tolerance = tolerance.max(10.0 * p.roundoff(&cfg));
    for it in 0..=max_iterations {
        p.residual(&cfg, &mut r, Some(&mut sys));
        let res = p.relative(&r);
        if !res.is_finite() {
            return None;
        }
        if res <= tolerance {
            return Some(p.solution(cfg, &r, it, 0, res));
        }
        if it == max_iterations {
            return None;
        }
        p.correction(&mut sys, &mut r, &mut du).ok()?;
        p.apply_increment(&mut cfg, &du);
        if !P::is_finite(&cfg) {
            return None;
        }
    }
    None
}

/// Newton iterations a warm or analytic start may take before the next start is tried.
const LINE_NEWTON_ITERATIONS: usize = 15;

/// The start of a cable between `top` and `anchor` (its frame) on a seabed
/// (§17.4): every node at its material position on the continuous line
/// resting on the seabed ([`Touchdown`]), the lying ones sunk to the
/// penetration that carries the line's weight, −q/(k D); if that leaves a
/// segment slack (a chord falls short of its arc by about κ²l²/24 where the
/// strain T/EA is smaller), [`touchdown_start`]'s. (That start spreads the
/// lying nodes evenly from the last suspended one, which can leave them
/// slack, and a slack lying chain has no stiffness along the seabed: Newton
/// cannot start there.)
pub fn cable_start(model: &CableModel, top: V3, anchor: V3) -> Option<Vec<V3>> {
    let fallback = || touchdown_start(model, top, anchor);
    let c = &model.cable;
    let Some(bed) = model.seabed.as_ref() else { return fallback() };
    let chord = anchor - top;
    let horiz = V3::new(chord.x, chord.y, 0.0);
    let span = horiz.norm();
    if span <= 1e-9 * c.length {
        return fallback();
    }
    let eh = horiz / span;
    let level = bed.height_at(anchor.x, anchor.y) - top.z;
    let Some(mut td) = Touchdown::solve(c.length, &model.vertical, c.axial_stiffness, span, chord.z, level) else {
        return fallback();
    };
    // Touchdown closes on the anchor with its lying part unstretched: the
    // suspended part's span is shortened by the lying part's stretch
    // (L − L_s) H/EA, twice, so that the lying part stretched closes
    for _ in 0..2 {
        let excess = (c.length - td.suspended) * td.cat.h / c.axial_stiffness;
        let (dx, dz) = (excess * td.direction.0, excess * td.direction.1);
        let Some(t) = Touchdown::solve(c.length, &model.vertical, c.axial_stiffness, span - dx, chord.z - dz, level)
        else {
            return fallback();
        };
        td = t;
    }
    // the suspended nodes marched along the catenary at their stretched
    // lengths (as touchdown_start does), the marching's overshoot (a chord
    // falls short of its arc) spread back along them; the lying ones back
    // from the anchor at l (1 + H/EA) each, sunk by −q/(k D)
    let on_curve = |s: f64| {
        let q = td.at(s);
        top + eh * q.x + V3::z() * q.z
    };
    let mut x = vec![top];
    while x.len() <= c.n_el && c.s_node(x.len()) <= td.suspended {
        let a = x.len() - 1;
        let t = td.at(c.s_node(a) + 0.5 * c.l).tension();
        let dir = (on_curve(c.s_node(a + 1)) - x[a]).try_normalize(0.0)?;
        x.push(x[a] + dir * (c.l * (1.0 + t / c.segment_stiffness(a))));
    }
    let k = x.len() - 1;
    if k > 0 {
        let miss = on_curve(c.s_node(k)) - x[k];
        for (a, p) in x.iter_mut().enumerate() {
            *p += miss * (a as f64 / k as f64);
        }
    }
    let lying = V3::new(td.direction.0 * eh.x, td.direction.0 * eh.y, td.direction.1);
    let stretch = 1.0 + td.cat.h / c.axial_stiffness;
    for a in k + 1..=c.n_el {
        let s = c.s_node(a);
        let sink = (-model.vertical.at(s) / bed.first().stiffness).max(0.0);
        x.push(anchor - lying * ((c.length - s) * stretch) - V3::z() * sink);
    }
    x[0] = top;
    x[c.n_el] = anchor;
    // the segment at the touchdown takes up what is left: if that leaves it
    // slack, its lying end moves along the seabed to make it as stretched as
    // its neighbour, the other lying nodes spread evenly from there
    if k + 2 < c.n_el && c.stretch(&x, k) < stretch {
        let (p0, reach) = (x[k + 1], c.l * stretch);
        let w = p0 - x[k];
        let (b, cc) = (w.dot(&lying), w.norm_squared() - reach * reach);
        let first = p0 + lying * (-b + (b * b - cc).max(0.0).sqrt());
        let rest = c.n_el - (k + 1);
        for j in 0..rest {
            let s = c.s_node(k + 1 + j);
            let sink = (-model.vertical.at(s) / bed.first().stiffness).max(0.0);
            let mut p = first + (anchor - first) * (j as f64 / rest as f64);
            p.z = first.z + (anchor.z - first.z) * (j as f64 / rest as f64) - if j == 0 { 0.0 } else { sink };
            x[k + 1 + j] = p;
        }
    }
    let taut = (0..c.n_el).all(|e| c.stretch(&x, e) > 1.0);
    if taut && x.iter().all(|p| p.iter().all(|v| v.is_finite())) { Some(x) } else { fallback() }
}

/// Line `i` with its hang-off at `h` and its anchor at `a` (global). A
/// cable: plain Newton from `warm`, its last state, shifted by the ends'
/// moves interpolated along the line (as `solve_scene_moved` shifts one
/// end's), the nodes that lay on the seabed kept at their penetration; if
/// that fails, from the analytic start ([`cable_start`]), plain and then
/// with continuation; then the scene's own solve. A rod: relaxed from the
/// shifted state, else the scene's own solve. Ends beyond the line's reach
/// fail at once.
pub fn solve_line_between(sys: &SystemScene, i: usize, h: V3, a: V3, warm: Option<&Solved>) -> Result<Solved, String> {
    let l = &sys.lines[i];
    let (_, hp, ap) = sys.ends(i);
    let chord = (a - h).norm();
    if !(chord.is_finite() && chord <= l.length * (1.0 + MAX_REACH_STRAIN)) {
        return Err(format!(
            "line '{}' cannot reach from point '{}' to point '{}': they are {chord:.3} m apart, its length {} m",
            l.name, hp.name, ap.name, l.length
        ));
    }
    if chord < 1e-3 * l.length {
        return Err(format!(
            "line '{}': points '{}' and '{}' are {chord:.3e} m apart, within 1e-3 of its length",
            l.name, hp.name, ap.name
        ));
    }
    let scene = sys.line_scene_at(i, h, a);
    let failed = |e: &dyn std::fmt::Display| {
        let at = |v: V3| format!("({:.3}, {:.3}, {:.3}) m", v.x, v.y, v.z);
        format!("line '{}' from point '{}' at {} to point '{}' at {}: {e}", l.name, hp.name, at(h), ap.name, at(a))
    };
    let anchor_local = scene.anchor();
    let loads = scene_static_loads(&scene);
    let tolerance = scene.analysis.newton_tolerance.min(1e-10);
    // the last state shifted to the new ends
    let shifted = warm.map(|w| {
        let shift = (a - w.a) - (h - w.h);
        let mut cfg: RodConfig = w.report.solution.config.clone();
        let fractions: Vec<f64> = w.report.shape.iter().map(|r| r.s / l.length).collect();
        // the seabed (global) in the old frame and in the new: a node that
        // lay on it keeps its penetration, none is pushed into it
        let beds = w.scene.seabed.as_ref().zip(scene.seabed.as_ref());
        for (x, f) in cfg.x.iter_mut().zip(&fractions) {
            let old = *x;
            *x += shift * *f;
            if let Some((b_old, b_new)) = beds {
                let penetration = b_old.height_at(old.x, old.y) - old.z;
                let bed = b_new.height_at(x.x, x.y);
                x.z = if penetration > 0.0 { bed - penetration } else { x.z.max(bed) };
            }
        }
        for xp in cfg.xp.iter_mut() {
            *xp += shift / l.length;
        }
        let n = cfg.x.len() - 1;
        cfg.x[0] = V3::zeros();
        cfg.x[n] = anchor_local;
        cfg
    });
    let report = match scene.analysis.model {
        Model::Cable => {
            let model = CableModel::from_scene(&scene);
            let p = CableStatics::new(&model, loads.drag.is_some());
            let top = scene.hang_off();
            let sol =
                shifted.and_then(|cfg| plain_newton(&p, cfg.x, tolerance, LINE_NEWTON_ITERATIONS)).or_else(|| {
                    let x0 = cable_start(&model, top, anchor_local)?;
                    plain_newton(&p, x0.clone(), tolerance, LINE_NEWTON_ITERATIONS)
                        .or_else(|| relax(&p, x0, tolerance).ok())
                });
            match sol {
                Some(sol) => StaticReport::of_cable(&model.cable, sol),
                None => solve_scene(&scene).map_err(|e| failed(&e))?,
            }
        }
        Model::Rod => {
            let rod = rod::of_scene(&scene);
            let sol = shifted.and_then(|cfg| relax(&StaticProblem::new(&rod, &loads), cfg, tolerance).ok());
            match sol {
                Some(sol) => StaticReport::new(&rod, sol),
                None => solve_scene(&scene).map_err(|e| failed(&e))?,
            }
        }
    };
    Ok(Solved { h, a, scene, report })
}

/// The statics of a system with free points (§17.4).
struct FreeSystem<'a> {
    sys: &'a SystemScene,
    /// Each line's (hang-off, anchor) ends.
    held: Vec<(Held, Held)>,
    /// The free points' specs, in the scene's order.
    free: Vec<&'a PointSpec>,
    /// The vessel points' global positions and arms R ρ at the pose.
    vessel: Vec<(V3, V3)>,
}

/// The free points' residual and the assembled stiffness at a state.
struct Balance {
    /// Net force on each free point, N.
    g: Vec<V3>,
    /// Each free point's force scale: its load's and its lines' magnitudes, N.
    scale: Vec<f64>,
}

impl FreeSystem<'_> {
    fn position(&self, h: Held, x: &[V3]) -> V3 {
        match h {
            Held::Fixed(p) => p,
            Held::Vessel(k) => self.vessel[k].0,
            Held::Free(k) => x[k],
        }
    }

    fn moves(&self, i: usize) -> bool {
        let (h, a) = self.held[i];
        matches!(h, Held::Free(_)) || matches!(a, Held::Free(_))
    }

    /// Solves the lines with a free end at the free points' positions `x`,
    /// each from its last state.
    fn solve_lines(&self, x: &[V3], last: &[Option<Solved>]) -> Result<Vec<Option<Solved>>, (usize, String)> {
        let mut out = Vec::with_capacity(self.held.len());
        for (i, (h, a)) in self.held.iter().enumerate() {
            if !self.moves(i) {
                out.push(None);
                continue;
            }
            let s = solve_line_between(self.sys, i, self.position(*h, x), self.position(*a, x), last[i].as_ref())
                .map_err(|e| (i, e))?;
            out.push(Some(s));
        }
        Ok(out)
    }

    /// The net force on each free point, g_k (17.5).
    fn balance(&self, x: &[V3], solved: &[Option<Solved>]) -> Balance {
        let mut g = Vec::with_capacity(self.free.len());
        let mut scale = Vec::with_capacity(self.free.len());
        for (k, p) in self.free.iter().enumerate() {
            let (f, _) = point_load(self.sys, p, x[k]);
            g.push(f);
            let env = &self.sys.environment;
            scale.push(f.norm() + env.gravity * (p.mass() + env.water_density * p.volume()));
        }
        for (i, s) in solved.iter().enumerate() {
            let Some(s) = s else { continue };
            let (h, a) = self.held[i];
            for (end, f) in [(h, s.report.top_force), (a, s.report.bottom_force)] {
                if let Held::Free(k) = end {
                    g[k] += f;
                    scale[k] += f.norm();
                }
            }
        }
        for v in scale.iter_mut() {
            *v = v.max(1.0);
        }
        Balance { g, scale }
    }

    /// The stiffness K = −∂f/∂(positions) over the vessel points' and the
    /// free points' positions (3 each, the vessel's first), assembled from
    /// the lines' stiffnesses at their ends and the free points' own (17.7).
    fn stiffness(
        &self,
        x: &[V3],
        solved: &[Option<Solved>],
        fixed_vessel: &[Option<M3>],
    ) -> Result<DMatrix<f64>, (usize, String)> {
        let nv = self.vessel.len();
        let n = 3 * (nv + self.free.len());
        let mut k = DMatrix::<f64>::zeros(n, n);
        let dof = |h: Held| match h {
            Held::Fixed(_) => None,
            Held::Vessel(j) => Some(3 * j),
            Held::Free(j) => Some(3 * (nv + j)),
        };
        for (i, (h, a)) in self.held.iter().enumerate() {
            if let Some(s) = &solved[i] {
                // where the line's ends have no stiffness (a chain slack on the seabed), a shifted one
                let s6 = line_end_stiffness(&s.scene, &s.report)
                    .or_else(|e| {
                        let l = &s.scene;
                        let shift =
                            SLACK_SPRING * l.line.axial_stiffness * l.analysis.n_elements as f64 / l.line.length;
                        line_end_stiffness_shifted(l, &s.report, shift).map_err(|_| e)
                    })
                    .map_err(|e| (i, e))?;
                add_line_ends(&mut k, &s6, [dof(*h), dof(*a)]);
            } else if let (Some(Some(s)), Some(r)) = (fixed_vessel.get(i), dof(*h)) {
                add_block(&mut k, r, r, s);
            }
        }
        for (j, p) in self.free.iter().enumerate() {
            let (_, kp) = point_load(self.sys, p, x[j]);
            let r = 3 * (nv + j);
            add_block(&mut k, r, r, &kp);
        }
        Ok(k)
    }

    /// The names of the lines at free point `k`.
    fn lines_at(&self, k: usize) -> String {
        let names: Vec<String> = (0..self.held.len())
            .filter(|&i| self.held[i].0 == Held::Free(k) || self.held[i].1 == Held::Free(k))
            .map(|i| format!("'{}'", self.sys.lines[i].name))
            .collect();
        names.join(", ")
    }

    /// The largest step a free point takes in one Newton iteration, m: a
    /// tenth of its shortest line.
    fn max_step(&self, k: usize) -> f64 {
        (0..self.held.len())
            .filter(|&i| self.held[i].0 == Held::Free(k) || self.held[i].1 == Held::Free(k))
            .map(|i| 0.1 * self.sys.lines[i].length)
            .fold(f64::INFINITY, f64::min)
    }
}

/// The free points' Newton iterations at most.
const MAX_FREE_ITERATIONS: usize = 60;
/// Converged when each free point's net force is below this times its scale.
const FREE_TOLERANCE: f64 = 1e-8;
/// Trials of a Newton iteration's line search at most.
const LINE_SEARCH_TRIALS: usize = 20;

/// [`solve_system`] of a system with free points from `start`, a state of
/// the same system (at a nearby pose): its free points' positions and its
/// lines' shapes start the iterations (a pose sweep, finite differences).
/// Without free points, or without `start`, [`solve_system`].
pub fn solve_system_from(
    sys: &SystemScene,
    pose: &[f64; 6],
    stiffness: bool,
    start: Option<&SystemStatics>,
) -> Result<SystemStatics, String> {
    match start {
        Some(st) if sys.points.iter().any(|p| p.kind == PointKind::Free) => {
            solve_with_free_points(sys, pose, stiffness, Some(st))
        }
        _ => solve_system(sys, pose, stiffness),
    }
}

/// The free points' statics from the scene's initial positions; if that
/// fails at a pose other than the neutral, from the neutral pose's
/// equilibrium by steps along the pose (halved where a step fails).
fn solve_free_from_scene(sys: &SystemScene, pose: &[f64; 6], stiffness: bool) -> Result<SystemStatics, String> {
    let direct = solve_with_free_points(sys, pose, stiffness, None);
    if direct.is_ok() || pose.iter().all(|&p| p == 0.0) {
        return direct;
    }
    let mut state = solve_with_free_points(sys, &[0.0; 6], false, None)?;
    let (mut done, mut step): (f64, f64) = (0.0, 0.25);
    let at = |f: f64| pose.map(|p| p * f);
    while done < 1.0 {
        let next = (done + step).min(1.0);
        match solve_with_free_points(sys, &at(next), stiffness && next == 1.0, Some(&state)) {
            Ok(s) => {
                let iterations = state.iterations + s.iterations;
                state = SystemStatics { iterations, ..s };
                done = next;
            }
            Err(e) if step < 1.0 / 64.0 => {
                return Err(format!(
                    "{e} (reached from the neutral pose's equilibrium as far as {:.1}% of the pose)",
                    done * 100.0
                ));
            }
            Err(_) => step *= 0.5,
        }
    }
    Ok(state)
}

/// The statics of a system with free points (§17.4): Newton on the free
/// points' positions (17.5), every line with a free end re-solved at each
/// trial from its last state, the Jacobian the lines' two-end stiffnesses
/// assembled (17.7), the step limited to a tenth of the point's shortest
/// line and a line search on the potential energy's slope along it; then
/// the stiffness on the vessel condensed on the free points (17.8, 17.9).
fn solve_with_free_points(
    sys: &SystemScene,
    pose: &[f64; 6],
    want_stiffness: bool,
    start: Option<&SystemStatics>,
) -> Result<SystemStatics, String> {
    let r = pose_rotation(pose);
    let u = V3::new(pose[0], pose[1], pose[2]);
    let vessel_points: Vec<&PointSpec> = sys.points.iter().filter(|p| p.kind == PointKind::Vessel).collect();
    let free: Vec<&PointSpec> = sys.points.iter().filter(|p| p.kind == PointKind::Free).collect();
    let held_of = |p: &PointSpec| match p.kind {
        PointKind::Fixed => Held::Fixed(V3::from(p.position)),
        PointKind::Vessel => Held::Vessel(vessel_points.iter().position(|q| q.name == p.name).expect("a vessel point")),
        PointKind::Free => Held::Free(free.iter().position(|q| q.name == p.name).expect("a free point")),
    };
    let held: Vec<(Held, Held)> = (0..sys.lines.len())
        .map(|i| {
            let (_, h, a) = sys.ends(i);
            (held_of(h), held_of(a))
        })
        .collect();
    let vessel: Vec<(V3, V3)> = vessel_points
        .iter()
        .map(|p| {
            let arm = r * V3::from(p.position);
            (u + arm, arm)
        })
        .collect();
    let fs = FreeSystem { sys, held, free, vessel };
    // the lines between a fixed and a vessel point: as without free points
    let mut fixed_vessel: Vec<Option<(Scene, StaticReport)>> = vec![None; sys.lines.len()];
    let mut fixed_vessel_k: Vec<Option<M3>> = vec![None; sys.lines.len()];
    for (i, l) in sys.lines.iter().enumerate() {
        if fs.moves(i) {
            continue;
        }
        let scene = sys.line_scene(i, fs.position(fs.held[i].0, &[]));
        scene.validate().map_err(|e| format!("line '{}' at the pose: {e}", l.name))?;
        let rep = solve_scene(&scene).map_err(|e| format!("line '{}': {e}", l.name))?;
        if want_stiffness {
            fixed_vessel_k[i] = Some(line_stiffness(&scene, &rep)?);
        }
        fixed_vessel[i] = Some((scene, rep));
    }
    // Newton on the free points' positions
    let nf = fs.free.len();
    let (mut x, warm): (Vec<V3>, Vec<Option<Solved>>) = match start {
        Some(st) => (
            st.points.iter().map(|p| p.position).collect(),
            st.lines
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    fs.moves(i).then(|| Solved {
                        h: l.fairlead,
                        a: l.anchor,
                        scene: l.scene.clone(),
                        report: l.report.clone(),
                    })
                })
                .collect(),
        ),
        None => (fs.free.iter().map(|p| V3::from(p.position)).collect(), vec![None; sys.lines.len()]),
    };
    let mut solved = fs.solve_lines(&x, &warm).map_err(|(_, e)| {
        let whence = if start.is_some() { "where the last state left them" } else { "at their initial positions" };
        format!("the free points {whence}: {e}")
    })?;
    let mut bal = fs.balance(&x, &solved);
    let worst = |b: &Balance| {
        (0..nf).max_by(|&i, &j| (b.g[i].norm() / b.scale[i]).total_cmp(&(b.g[j].norm() / b.scale[j]))).unwrap_or(0)
    };
    let converged = |b: &Balance| b.g.iter().zip(&b.scale).all(|(g, s)| g.norm() <= FREE_TOLERANCE * s);
    let mut iterations = 0;
    // why Newton stopped, and the line that made it, if one did
    let mut failure: Option<(String, Option<usize>)> = None;
    while !converged(&bal) {
        if iterations == MAX_FREE_ITERATIONS {
            failure = Some((format!("not in equilibrium after {MAX_FREE_ITERATIONS} Newton iterations"), None));
            break;
        }
        iterations += 1;
        let k = match fs.stiffness(&x, &solved, &[]) {
            Ok(k) => k,
            Err((i, e)) => {
                failure = Some((e, Some(i)));
                break;
            }
        };
        let nv = fs.vessel.len();
        let kpp = k.view((3 * nv, 3 * nv), (3 * nf, 3 * nf)).into_owned();
        let g = DVector::from_iterator(3 * nf, bal.g.iter().flat_map(|v| [v.x, v.y, v.z]));
        // −∂g/∂x = K_pp: the step δx = K_pp⁻¹ g
        let Some(dx) = kpp.clone().lu().solve(&g).filter(|d| d.iter().all(|v| v.is_finite())) else {
            failure =
                Some(("its lines' stiffness is singular there (a point nothing holds in some direction)".into(), None));
            break;
        };
        let mut step: Vec<V3> = (0..nf).map(|k| V3::new(dx[3 * k], dx[3 * k + 1], dx[3 * k + 2])).collect();
        // s(α) = g(x + α δx)·δx = −dΠ/dα, Π the system's potential energy
        // (the lines' forces and the points' loads are its −gradient)
        let slope = |b: &Balance, step: &[V3]| b.g.iter().zip(step).map(|(g, s)| g.dot(s)).sum::<f64>();
        let s_newton = slope(&bal, &step);
        if s_newton.is_nan() || s_newton <= 0.0 {
            // K_pp not positive definite here: down the energy's gradient, g, at the stiffest line's rate
            let kmax = (0..3 * nf).map(|i| kpp[(i, i)].abs()).fold(0.0, f64::max).max(1e-300);
            step = bal.g.iter().map(|g| g / kmax).collect();
        }
        let limit = (0..nf).map(|k| step[k].norm() / fs.max_step(k)).fold(1.0, f64::max);
        step.iter_mut().for_each(|s| *s /= limit);
        let s0 = slope(&bal, &step);
        // the line search: the first α whose slope s(α) ≥ −s(0)/2 (Π then
        // fell by at least s(0) α/4 on a linear slope), by safeguarded
        // secants on s towards its root; a trial whose lines cannot be
        // solved (out of reach) halves α
        let (mut lo, mut s_lo, mut alpha) = (0.0, s0, 1.0);
        let mut accepted = false;
        let mut last_error = None;
        for _ in 0..LINE_SEARCH_TRIALS {
            let trial: Vec<V3> = x.iter().zip(&step).map(|(p, s)| p + s * alpha).collect();
            match fs.solve_lines(&trial, &solved) {
                Ok(sl) => {
                    let b = fs.balance(&trial, &sl);
                    let sa = slope(&b, &step);
                    if sa >= -0.5 * s0 || converged(&b) {
                        x = trial;
                        solved = sl;
                        bal = b;
                        accepted = true;
                        break;
                    }
                    if sa > 0.0 {
                        (lo, s_lo) = (alpha, sa);
                    }
                    let root = lo + (alpha - lo) * s_lo / (s_lo - sa);
                    alpha = root.clamp(lo + 0.1 * (alpha - lo), lo + 0.9 * (alpha - lo));
                }
                Err(e) => {
                    last_error = Some(e);
                    alpha = lo + 0.5 * (alpha - lo);
                }
            }
        }
        if !accepted {
            failure = Some(match last_error {
                Some((i, e)) => (format!("Newton's line search found no step ({e})"), Some(i)),
                None => ("Newton's line search found no step that lowers the potential energy".to_string(), None),
            });
            break;
        }
    }
    if let Some((why, line)) = failure {
        // the point: the failing line's free end, else the worst balanced
        let k = match line.map(|i| fs.held[i]) {
            Some((Held::Free(k), _)) | Some((_, Held::Free(k))) => k,
            _ => worst(&bal),
        };
        let p = fs.free[k];
        let env = &sys.environment;
        let net_up = env.gravity * (env.water_density * p.volume() - p.mass());
        let floats = if net_up > 0.0 && p.height.is_none() {
            format!(
                " It is buoyant (net {:.3} kN up): unless its lines hold it under water it rises to the surface \
                 (z = {} m), where its buoyancy, full below and none above, has no equilibrium (give it a \
                 `height` to float there: docs/guide/systems.md).",
                net_up / 1e3,
                env.water_surface_z
            )
        } else {
            String::new()
        };
        return Err(format!(
            "free point '{}' (lines {}): no static equilibrium found: {why}; at ({:.3}, {:.3}, {:.3}) m the net force \
             on it is {:.3} kN of its {:.3} kN of loads after {iterations} iterations.{floats}",
            p.name,
            fs.lines_at(k),
            x[k].x,
            x[k].y,
            x[k].z,
            bal.g[k].norm() / 1e3,
            bal.scale[k] / 1e3
        ));
    }
    // the loads on the vessel and the rows
    let (mut force, mut moment) = (V3::zeros(), V3::zeros());
    let mut on_vessel = vec![V3::zeros(); fs.vessel.len()];
    let mut lines = Vec::with_capacity(sys.lines.len());
    for i in 0..sys.lines.len() {
        let (h, a) = fs.held[i];
        let (scene, rep) = match (&solved[i], &fixed_vessel[i]) {
            (Some(s), _) => (s.scene.clone(), s.report.clone()),
            (None, Some((sc, rep))) => (sc.clone(), rep.clone()),
            (None, None) => unreachable!("every line is solved"),
        };
        let arm = match h {
            Held::Vessel(j) => {
                let (_, arm) = fs.vessel[j];
                on_vessel[j] += rep.top_force;
                force += rep.top_force;
                moment += arm.cross(&rep.top_force);
                arm
            }
            _ => V3::zeros(),
        };
        let ends = (fs.position(h, &x), fs.position(a, &x), arm);
        lines.push(line_statics(sys, i, scene, rep, ends, fixed_vessel_k[i]));
    }
    let points = (0..nf)
        .map(|k| PointStatics {
            name: fs.free[k].name.clone(),
            position: x[k],
            load: point_load(sys, fs.free[k], x[k]).0,
            residual: bal.g[k],
        })
        .collect();
    let mut stiffness = M6::zeros();
    if want_stiffness {
        let fixed_k: Vec<Option<M3>> = fixed_vessel_k.clone();
        let k = fs.stiffness(&x, &solved, &fixed_k).map_err(|(_, e)| e)?;
        let kc = condense(&k, 3 * fs.vessel.len())
            .ok_or_else(|| "the free points' stiffness is singular at the equilibrium".to_string())?;
        stiffness = condensed_stiffness6(&kc, &fs.vessel, &on_vessel);
    }
    Ok(SystemStatics { pose: *pose, lines, points, iterations, force, moment, stiffness })
}

/// Adds the 3×3 block `b` to `k` at row `r`, column `c`.
pub fn add_block(k: &mut DMatrix<f64>, r: usize, c: usize, b: &M3) {
    for i in 0..3 {
        for j in 0..3 {
            k[(r + i, c + j)] += b[(i, j)];
        }
    }
}

/// Adds a line's two-end stiffness `s6` (17.6, [hang-off; anchor]) to the
/// system's stiffness `k` (17.7) at its ends' first unknowns `ends` (None:
/// a fixed end, which drops out).
pub fn add_line_ends(k: &mut DMatrix<f64>, s6: &M6, ends: [Option<usize>; 2]) {
    for (bi, ri) in ends.iter().enumerate() {
        for (bj, cj) in ends.iter().enumerate() {
            if let (Some(r), Some(c)) = (ri, cj) {
                add_block(k, *r, *c, &s6.fixed_view::<3, 3>(3 * bi, 3 * bj).into_owned());
            }
        }
    }
}

/// The stiffness `k` over the vessel points' positions (its first `nv`
/// unknowns) and the free points' condensed on the vessel points, the free
/// points re-balanced (17.8): K_c = K_vv − K_vp K_pp⁻¹ K_pv; None if K_pp
/// is singular.
pub fn condense(k: &DMatrix<f64>, nv: usize) -> Option<DMatrix<f64>> {
    let np = k.nrows() - nv;
    let kvv = k.view((0, 0), (nv, nv));
    let kvp = k.view((0, nv), (nv, np));
    let kpv = k.view((nv, 0), (np, nv));
    let kpp = k.view((nv, nv), (np, np)).into_owned();
    let x_pv = kpp.lu().solve(&kpv.into_owned())?;
    let kc = kvv.into_owned() - kvp * x_pv;
    kc.iter().all(|v| v.is_finite()).then_some(kc)
}

/// The 6×6 stiffness on the reference point of the vessel points' condensed
/// translation stiffness `kc` (3 rows and columns a point), each point's arm
/// a_i and the lines' force on it f_i (17.9): `Σ_ij [I; [a_i]×] K_ij [I, −[a_j]×]`
/// plus each point's geometric term `−[f_i]×[a_i]×` in the moment block.
pub fn condensed_stiffness6(kc: &DMatrix<f64>, vessel: &[(V3, V3)], forces: &[V3]) -> M6 {
    condensed_stiffness6_of(&|r, c| kc[(r, c)], vessel.len(), &|i| vessel[i].1, &|i| forces[i])
}

/// [`condensed_stiffness6`] of `n` vessel points, K_c's entries `kc(row,
/// column)`, point i's arm `arm(i)` and the lines' force on it `force(i)`:
/// allocating nothing.
pub fn condensed_stiffness6_of(
    kc: &dyn Fn(usize, usize) -> f64,
    n: usize,
    arm: &dyn Fn(usize) -> V3,
    force: &dyn Fn(usize) -> V3,
) -> M6 {
    let mut k6 = M6::zeros();
    for i in 0..n {
        let ai = arm(i);
        let axi = skew(&ai);
        for j in 0..n {
            let axj = skew(&arm(j));
            let s = M3::from_fn(|r, c| kc(3 * i + r, 3 * j + c));
            let mut b = M6::zeros();
            b.fixed_view_mut::<3, 3>(0, 0).copy_from(&s);
            b.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-s * axj));
            b.fixed_view_mut::<3, 3>(3, 0).copy_from(&(axi * s));
            b.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-axi * s * axj));
            k6 += b;
        }
        let mut geo = k6.fixed_view_mut::<3, 3>(3, 3);
        geo -= skew(&force(i)) * axi;
    }
    k6
}

/// [`condense`] in place, allocating nothing: `k` (n × n row-major, the
/// vessel points' `nv` unknowns first) becomes, in its first `nv` rows'
/// first `nv` columns (read with row stride n), K_c = K_vv − K_vp K_pp⁻¹
/// K_pv (17.8), by Gaussian elimination of the points' columns with
/// partial pivoting among the points' rows; the rest is scratch. False if
/// K_pp is singular or K_c not finite.
pub fn condense_in_place(k: &mut [f64], n: usize, nv: usize) -> bool {
    for c in nv..n {
        let p = (c..n).max_by(|&i, &j| k[i * n + c].abs().total_cmp(&k[j * n + c].abs())).unwrap_or(c);
        if k[p * n + c] == 0.0 || !k[p * n + c].is_finite() {
            return false;
        }
        if p != c {
            for j in 0..n {
                k.swap(c * n + j, p * n + j);
            }
        }
        // eliminate column c from every row but the pivot's: the points' below it, and the vessel's
        for i in (0..nv).chain(c + 1..n) {
            let f = k[i * n + c] / k[c * n + c];
            if f != 0.0 {
                for j in 0..n {
                    k[i * n + j] -= f * k[c * n + j];
                }
            }
        }
    }
    (0..nv).all(|i| (0..nv).all(|j| k[i * n + j].is_finite()))
}

/// The pose turned by the small global rotation vector `dtheta` (rad) and
/// moved by `du` (m): angles of `exp([δθ]×) R` (z-y-x), for finite differences
/// of the stiffness's rotation columns.
pub fn perturbed_pose(pose: &[f64; 6], du: V3, dtheta: V3) -> [f64; 6] {
    let r = crate::math::rigid::exp_so3(&dtheta) * pose_rotation(pose);
    let [roll, pitch, yaw] = zyx_angles(&r);
    [pose[0] + du.x, pose[1] + du.y, pose[2] + du.z, roll, pitch, yaw]
}

/// The z-y-x angles [roll, pitch, yaw] of R (pitch within ±90°).
pub fn zyx_angles(r: &M3) -> [f64; 3] {
    let pitch = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    let roll = r[(2, 1)].atan2(r[(2, 2)]);
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    [roll, pitch, yaw]
}
