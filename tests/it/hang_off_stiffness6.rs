//! The line's 6×6 stiffness at the hang-off (solve::eigen::hang_off_stiffness6,
//! docs/theory.md eq. 8.7) against central finite differences of two static
//! solutions with the hang-off moved by ±δ along x, y, z and the vessel's
//! frame turned by ±ε about x, y, z (global): for a clamped end the end's
//! frame turned with it (imposed on the held director node, as
//! tests/it/hang_off_end.rs does), for a flex joint the joint's vessel frame
//! turned. The force and the end moment of the support on the line: the
//! residual's rows at the hang-off's position and, for the clamp, at its
//! rotation; for the joint, minus the joint's moment on the vessel.

use crate::common;

use riser::math::rigid::rot_y;
use riser::math::{M3, M6, V3, cayley};
use riser::model::RodConfig;
use riser::model::rod::linearized::RodLinearized;
use riser::model::rod::statics::StaticProblem;
use riser::model::rod::{Rod, RodModel, RotationBc};
use riser::model::statics::StaticEquations;
use riser::scene::Scene;
use riser::sim::report::scene_static_loads;
use riser::sim::{Engine, Simulation};
use riser::solve::eigen::{hang_off_stiffness, hang_off_stiffness6};

/// Newton with backtracking from `q` to the round-off floor (as
/// tests/it/hang_off_stiffness.rs) of R_free(q) = `target` (the dead loads of a
/// frozen state; zero at a static state), the supports held where `q` has them;
/// converged: the free residual's largest within 1e-9 of the reaction.
fn solve_static(p: &StaticProblem, q: RodConfig, target: &[f64]) -> RodConfig {
    // the largest free residual over the hang-off's reaction (a neutrally
    // buoyant line has no weight to scale by)
    let mut fixed = p.rod.fixed_dofs();
    fixed.sort_unstable();
    let n = p.n_dof();
    let measure = |r: &[f64]| {
        let free = (0..n).filter(|i| fixed.binary_search(i).is_err()).fold(0.0f64, |a, i| a.max(r[i].abs()));
        let reaction = V3::from_fn(|c, _| r[c] + target.get(c).unwrap_or(&0.0));
        free / reaction.norm()
    };
    let (q, rel) = common::solve_with_dead_loads(p, q, target, measure);
    assert!(rel < 1e-9, "statics did not converge: {rel:.2e}");
    q
}

/// The support's force and end moment on the line at the static solution of
/// `model` from `q`.
fn support_loads(
    model: &RodModel,
    loads: &riser::model::rod::statics::StaticLoads,
    q: RodConfig,
    target: &[f64],
) -> [f64; 6] {
    let p = StaticProblem::new(&model.rod, loads);
    let q = solve_static(&p, q, target);
    let mut r = vec![0.0; p.n_dof()];
    p.residual(&q, &mut r, None);
    let it = Rod::theta_dof(0);
    let m = match &model.rod.flex_joint {
        Some(j) => -j.static_moment(&q.d[0], &j.frame.unwrap()).0,
        None if model.rod.ends[0].rotation == RotationBc::Clamped => V3::new(r[it], r[it + 1], r[it + 2]),
        None => V3::zeros(),
    };
    [r[0], r[1], r[2], m.x, m.y, m.z]
}

/// S₆ by central differences: column j = (L(+e_j) − L(−e_j)) / 2δ_j.
fn finite_difference(
    model: &RodModel,
    loads: &riser::model::rod::statics::StaticLoads,
    q: &RodConfig,
    target: &[f64],
    delta: f64,
    eps: f64,
) -> M6 {
    let mut s = M6::zeros();
    for j in 0..6 {
        let mut col = [0.0; 6];
        for sign in [1.0, -1.0] {
            let (mut qm, mut mm) = (q.clone(), model.clone());
            if j < 3 {
                let mut e = V3::zeros();
                e[j] = sign * delta;
                qm.x[0] += e;
            } else {
                let mut w = V3::zeros();
                w[j - 3] = sign * eps;
                let turn = cayley(&w);
                match mm.rod.flex_joint.as_mut() {
                    Some(joint) => joint.frame = Some(turn * joint.frame.unwrap()),
                    None => qm.d[0] = turn * qm.d[0],
                }
            }
            let l = support_loads(&mm, loads, qm, target);
            for i in 0..6 {
                col[i] += sign * l[i];
            }
        }
        let h = 2.0 * if j < 3 { delta } else { eps };
        for i in 0..6 {
            s[(i, j)] = col[i] / h;
        }
    }
    s
}

fn block(m: &M6, bi: usize, bj: usize) -> M3 {
    m.fixed_view::<3, 3>(3 * bi, 3 * bj).into_owned()
}

fn max_abs(m: &M3) -> f64 {
    m.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Each 3×3 block within `tol` of the largest of the finite differences' block.
fn compare(what: &str, s: &M6, fd: &M6, tol: f64) -> f64 {
    let mut worst = 0.0f64;
    for bi in 0..2 {
        for bj in 0..2 {
            let (a, b) = (block(s, bi, bj), block(fd, bi, bj));
            let err = max_abs(&(a - b)) / max_abs(&b);
            eprintln!("{what} block ({bi}, {bj}): max|FD| {:.4e}, max|S - FD|/max|FD| = {err:.2e}", max_abs(&b));
            assert!(max_abs(&b) > 0.0, "{what}: block ({bi}, {bj}) is zero");
            assert!(err < tol, "{what} block ({bi}, {bj}): {err:.2e}\nS = {a:.6e}FD = {b:.6e}");
            worst = worst.max(err);
        }
    }
    worst
}

fn catenary(sets: &[&str]) -> Scene {
    Scene::builtin("catenary").unwrap().with_overrides(sets).unwrap()
}

/// At the scene's static state (the Simulation's S₆, R = I) and, with
/// `turn`, at the static state with the vessel turned by `turn` rad about y
/// (the clamp's end frame or the joint's vessel frame turned, the statics
/// re-solved: a state with an end moment). `delta` the translation's step,
/// m (the rotation's 1e-4 rad): the taut line's stretch is 1 cm, and its
/// central differences' O(δ²) error is 1.05e-4 of the moment-translation
/// block at 3e-4 m, 1.2e-5 at 1e-4 m, 1.05e-6 at 3e-5 m (measured), so 3e-5 m
/// there; 1e-3 m on the catenary as tests/it/hang_off_stiffness.rs.
fn case(what: &str, scene: &Scene, turn: Option<f64>, delta: f64) -> M6 {
    let sim = Simulation::from_scene(scene).unwrap();
    let loads = scene_static_loads(scene);
    let Engine::Rod(i) = &sim.integrator else { panic!("rod") };
    let mut model = i.model.clone();
    let mut cfg = sim.state.config.clone();
    let s_sim = sim.hang_off_stiffness6().unwrap();
    assert_eq!(s_sim, hang_off_stiffness6(&RodLinearized::new(&model, &loads), &cfg).unwrap());
    // the 3×3 is the translation block
    assert_eq!(sim.hang_off_stiffness().unwrap(), block(&s_sim, 0, 0));
    let s = match turn {
        None => s_sim,
        Some(a) => {
            match model.rod.flex_joint.as_mut() {
                Some(j) => j.frame = Some(rot_y(a) * j.frame.unwrap()),
                None => cfg.d[0] = rot_y(a) * cfg.d[0],
            }
            cfg = solve_static(&StaticProblem::new(&model.rod, &loads), cfg, &[]);
            let l = support_loads(&model, &loads, cfg.clone(), &[]);
            eprintln!("{what}: end moment of the support {:.4e} N m", V3::new(l[3], l[4], l[5]).norm());
            let s = hang_off_stiffness6(&RodLinearized::new(&model, &loads), &cfg).unwrap();
            assert_eq!(block(&s, 0, 0), hang_off_stiffness(&RodLinearized::new(&model, &loads), &cfg).unwrap());
            s
        }
    };
    let fd = finite_difference(&model, &loads, &cfg, &[], delta, 1e-4);
    let worst = compare(what, &s, &fd, 1e-5);
    eprintln!("{what}: worst block {worst:.2e}");
    s
}

/// K_b = √(EI T)/(1 − λ/L) of tests/it/hang_off_end.rs (theory §15), T the
/// static top tension.
fn boundary_layer(scene: &Scene) -> f64 {
    let t = Simulation::from_scene(scene).unwrap().statics.top_tension;
    let ei = scene.line.bending_stiffness;
    (ei * t).sqrt() / (1.0 - (ei / t).sqrt() / scene.line.length)
}

const JOINT: [&str; 2] = ["hang_off_end=flex_joint", "flex_joint_stiffness=1e6"];

#[test]
fn clamped_catenary_6x6_is_the_derivative_of_the_statics() {
    let s = case("catenary, clamped", &catenary(&["hang_off_end=clamped"]), None, 1e-3);
    // at a static state of a conservative line the tangent is symmetric
    let asym = (s - s.transpose()).amax() / s.amax();
    eprintln!("asymmetry {asym:.2e}");
    assert!(asym < 1e-9, "{asym}");
}

#[test]
fn flex_joint_catenary_6x6_is_the_derivative_of_the_statics() {
    case("catenary, flex joint 1e6 N m/rad", &catenary(&JOINT), None, 1e-3);
}

#[test]
fn clamped_taut_line_6x6_is_the_derivative_of_the_statics() {
    let s = case("taut, clamped", &common::taut_vertical_line(&["hang_off_end=clamped"]), None, 3e-5);
    // the clamp's boundary layer: δM = δθ √(EI T)/(1 − λ/L) about a transverse axis
    // (measured within 3e-6, held to 5e-5 as (15.5) in tests/it/hang_off_end.rs)
    let kb = boundary_layer(&common::taut_vertical_line(&["hang_off_end=clamped"]));
    eprintln!("taut, clamped: S_yy of the rotation {:.5e} against K_b {kb:.5e}", s[(4, 4)]);
    assert!((s[(4, 4)] / kb - 1.0).abs() < 5e-5 && (s[(3, 3)] / kb - 1.0).abs() < 5e-5);
    case("taut, clamped, turned 0.01 rad", &common::taut_vertical_line(&["hang_off_end=clamped"]), Some(0.01), 3e-5);
}

#[test]
fn flex_joint_taut_line_6x6_is_the_derivative_of_the_statics() {
    let s = case("taut, flex joint 1e6 N m/rad", &common::taut_vertical_line(&JOINT), None, 3e-5);
    // the joint in series with the boundary layer (15.5)
    let kb = boundary_layer(&common::taut_vertical_line(&JOINT));
    let series = 1.0 / (1.0 / 1e6 + 1.0 / kb);
    eprintln!("taut, flex joint: S_yy of the rotation {:.5e} against 1/(1/k + 1/K_b) {series:.5e}", s[(4, 4)]);
    assert!((s[(4, 4)] / series - 1.0).abs() < 5e-5 && (s[(3, 3)] / series - 1.0).abs() < 5e-5);
    case("taut, flex joint 1e6 N m/rad, turned 0.01 rad", &common::taut_vertical_line(&JOINT), Some(0.01), 3e-5);
}

/// During a run (heave 2.5 m / 10 s, pitch 0.02 rad / 8 s, 6 s in): the
/// state frozen, the interior's out-of-balance forces held as dead loads
/// (the meaning of the stiffness at the current state, theory §8.3), the
/// clamp's frame R D_static and the joint's vessel frame R D_static turned
/// by ±1e-4 rad, the hang-off moved by ±1 mm.
fn dynamic_case(what: &str, scene: &Scene) {
    let mut sim = Simulation::from_scene(scene).unwrap();
    let (w1, w2) = (2.0 * std::f64::consts::PI / 10.0, 2.0 * std::f64::consts::PI / 8.0);
    let motion = move |t: f64| riser::model::HangOff {
        displacement: V3::new(0.0, 0.0, 2.5 * (w1 * t).sin()),
        velocity: V3::new(0.0, 0.0, 2.5 * w1 * (w1 * t).cos()),
        rotation: rot_y(0.02 * (w2 * t).sin()),
        angular_velocity: V3::new(0.0, 0.02 * w2 * (w2 * t).cos(), 0.0),
    };
    sim.start(motion(0.0));
    while sim.state.time < 6.0 - 1e-9 {
        let t = sim.state.time + 0.1;
        sim.advance_to(t, &motion).unwrap();
    }
    let s = sim.hang_off_stiffness6().unwrap();
    let loads = scene_static_loads(scene);
    let Engine::Rod(i) = &sim.integrator else { panic!("rod") };
    let mut model = i.model.clone();
    if let Some(f) = model.joint_frame(&sim.state.hang_off.rotation) {
        model.rod.flex_joint.as_mut().unwrap().frame = Some(f);
    }
    let cfg = sim.state.config.clone();
    let p = StaticProblem::new(&model.rod, &loads);
    let mut target = vec![0.0; p.n_dof()];
    p.residual(&cfg, &mut target, None);
    let out_of_balance = target.iter().skip(12).fold(0.0f64, |a, v| a.max(v.abs()));
    let m = support_loads(&model, &loads, cfg.clone(), &target);
    eprintln!(
        "{what}: out-of-balance {out_of_balance:.3e} N, end moment of the support {:.4e} N m",
        V3::new(m[3], m[4], m[5]).norm()
    );
    assert!(out_of_balance > 1.0, "the state must be off the static equilibrium");
    let fd = finite_difference(&model, &loads, &cfg, &target, 1e-3, 1e-4);
    compare(what, &s, &fd, 1e-5);
}

#[test]
fn clamped_and_flex_joint_6x6_during_a_run_are_the_frozen_state_derivatives() {
    dynamic_case("catenary, clamped, t = 6 s", &catenary(&["hang_off_end=clamped"]));
    dynamic_case("catenary, flex joint, t = 6 s", &catenary(&JOINT));
}

/// A pinned end: the rotation columns and the moment rows are zero, the
/// translation block the 3×3 stiffness.
#[test]
fn pinned_6x6_has_only_the_translation_block() {
    let sim = Simulation::from_scene(&catenary(&[])).unwrap();
    let s = sim.hang_off_stiffness6().unwrap();
    assert_eq!(block(&s, 0, 1), M3::zeros());
    assert_eq!(block(&s, 1, 0), M3::zeros());
    assert_eq!(block(&s, 1, 1), M3::zeros());
    assert_eq!(block(&s, 0, 0), sim.hang_off_stiffness().unwrap());
    assert!(max_abs(&block(&s, 0, 0)) > 0.0);
}
