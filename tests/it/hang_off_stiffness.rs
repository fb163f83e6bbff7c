//! The line's stiffness at the hang-off (solve::eigen::hang_off_stiffness,
//! the FMU's directional derivative) against finite differences of the
//! nonlinear equations:
//! - at the static state: two static solutions with the hang-off moved by ±δ;
//! - during a dynamic run: the state frozen, the out-of-balance forces of the
//!   interior (inertia, drag) held as dead loads, the hang-off moved by ±δ and
//!   the static equations re-solved — the meaning of "the tangent stiffness
//!   at the current state" (docs/theory.md §8.3).

use crate::common;

use riser::math::{M3, V3};
use riser::model::RodConfig;
use riser::model::cable::linearized::CableLinearized;
use riser::model::cable::statics::CableStatics;
use riser::model::rod::linearized::RodLinearized;
use riser::model::rod::statics::StaticProblem;
use riser::model::statics::StaticEquations;
use riser::scene::Scene;
use riser::sim::report::scene_static_loads;
use riser::sim::{Engine, Simulation};
use riser::solve::eigen::hang_off_stiffness;

/// Solves R_free(q) = `target` (the supports held where `q` has them) by
/// Newton with backtracking from `q` (the cable's stiff axial law makes plain
/// Newton overshoot); the support reaction at the hang-off, N.
fn reaction_with_dead_loads<P: StaticEquations>(p: &P, q: P::Config, target: &[f64]) -> V3 {
    let (q, _) = common::solve_with_dead_loads(p, q, target, |r| p.relative(r));
    let mut r = vec![0.0; p.n_dof()];
    p.residual(&q, &mut r, None);
    V3::new(r[0], r[1], r[2])
}

/// S by central differences: column j = (R(+δ e_j) − R(−δ e_j)) / 2δ.
fn finite_difference<P: StaticEquations>(
    p: &P,
    q: &P::Config,
    target: &[f64],
    move_top: impl Fn(&mut P::Config, V3),
    delta: f64,
) -> M3 {
    let mut s = M3::zeros();
    for j in 0..3 {
        let mut e = V3::zeros();
        e[j] = delta;
        let (mut qp, mut qm) = (q.clone(), q.clone());
        move_top(&mut qp, e);
        move_top(&mut qm, -e);
        let col = (reaction_with_dead_loads(p, qp, target) - reaction_with_dead_loads(p, qm, target)) / (2.0 * delta);
        s.set_column(j, &col);
    }
    s
}

fn max_abs(m: &M3) -> f64 {
    m.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

fn compare(what: &str, s: &M3, fd: &M3, tol: f64) {
    let err = max_abs(&(s - fd)) / max_abs(fd);
    eprintln!("{what}: S = {s:.6e}FD = {fd:.6e}max|S − FD|/max|FD| = {err:.2e}");
    assert!(err < tol, "{what}: relative difference {err:.2e}");
}

fn shift_rod(q: &mut RodConfig, e: V3) {
    q.x[0] += e;
}

/// The cable's hang-off is its first node.
fn shift_cable() -> impl Fn(&mut Vec<V3>, V3) {
    |q, e| q[0] += e
}

/// At the static state (target residual 0 on the free unknowns).
fn static_case(scene_name: &str, model: &str) -> M3 {
    static_case_with(scene_name, model, &[])
}

fn static_case_with(scene_name: &str, model: &str, sets: &[&str]) -> M3 {
    let mut all = vec![format!("model={model}")];
    all.extend(sets.iter().map(|s| s.to_string()));
    let scene = Scene::builtin(scene_name).unwrap().with_overrides(&all).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let loads = scene_static_loads(&scene);
    let cfg = &sim.state.config;
    let s = sim.hang_off_stiffness().unwrap();
    let what = format!("{scene_name} ({model}) {sets:?}, statics");
    let delta = 1e-3;
    match &sim.integrator {
        Engine::Rod(i) => {
            let p = StaticProblem::new(&i.model.rod, &loads);
            let zero = vec![0.0; p.n_dof()];
            let fd = finite_difference(&p, cfg, &zero, shift_rod, delta);
            assert_eq!(s, hang_off_stiffness(&RodLinearized::new(&i.model, &loads), cfg).unwrap());
            compare(&what, &s, &fd, 1e-5);
        }
        Engine::Cable(i) => {
            let p = CableStatics::new(&i.model, false);
            let zero = vec![0.0; p.n_dof()];
            let fd = finite_difference(&p, &cfg.x, &zero, shift_cable(), delta);
            assert_eq!(s, hang_off_stiffness(&CableLinearized::new(&i.model, false), cfg).unwrap());
            compare(&what, &s, &fd, 1e-5);
        }
    }
    s
}

#[test]
fn catenary_rod_static_stiffness_is_the_derivative_of_the_static_top_force() {
    static_case("catenary", "rod");
}

/// A flex joint (§15) resists the end's turn as the hang-off moves: its
/// tangent in the statics' is in the stiffness, which then differs from
/// the pinned line's (by 1.2 % at 1e6 N m/rad, 17 kN m/deg). Measured:
/// within 8.3e-9 of the finite differences (held to 1e-5).
#[test]
fn catenary_rod_static_stiffness_with_a_flex_joint_is_the_derivative_of_the_static_top_force() {
    let joint = static_case_with("catenary", "rod", &["hang_off_end=flex_joint", "flex_joint_stiffness=1e6"]);
    let pinned = static_case("catenary", "rod");
    let change = max_abs(&(joint - pinned)) / max_abs(&pinned);
    eprintln!("the flex joint changes the stiffness by {change:.2e} of the pinned line's");
    assert!(change > 1e-3, "{change}");
}

#[test]
fn catenary_cable_static_stiffness_is_the_derivative_of_the_static_top_force() {
    static_case("catenary", "cable");
}

#[test]
fn lazy_wave_rod_static_stiffness_is_the_derivative_of_the_static_top_force() {
    static_case("lazy_wave", "rod");
}

#[test]
fn lazy_wave_cable_static_stiffness_is_the_derivative_of_the_static_top_force() {
    static_case("lazy_wave", "cable");
}

/// During a heave run: the interior's out-of-balance forces at the frozen
/// state are the dead loads of the re-solve.
fn dynamic_case(model: &str) {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&[format!("model={model}")]).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let heave = riser::sim::Heave { amplitude: 2.5, period: 10.0, until: None, ramp: 0.0 };
    let motion = move |t: f64| heave.at(t);
    sim.start(motion(0.0));
    while sim.state.time < 6.0 - 1e-9 {
        let t = sim.state.time + 0.1;
        sim.advance_to(t, &motion).unwrap();
    }
    let loads = scene_static_loads(&scene);
    let cfg = sim.state.config.clone();
    let s = sim.hang_off_stiffness().unwrap();
    let what = format!("catenary ({model}) at t = {:.1} s of a heave run", sim.state.time);
    match &sim.integrator {
        Engine::Rod(i) => {
            let p = StaticProblem::new(&i.model.rod, &loads);
            let mut target = vec![0.0; p.n_dof()];
            p.residual(&cfg, &mut target, None);
            let out_of_balance = target.iter().skip(12).fold(0.0f64, |a, v| a.max(v.abs()));
            eprintln!("out-of-balance force of the interior: {out_of_balance:.3e} N");
            assert!(out_of_balance > 1.0, "the state must be off the static equilibrium");
            let fd = finite_difference(&p, &cfg, &target, shift_rod, 1e-3);
            compare(&what, &s, &fd, 1e-5);
        }
        Engine::Cable(i) => {
            let p = CableStatics::new(&i.model, false);
            let mut target = vec![0.0; p.n_dof()];
            p.residual(&cfg.x, &mut target, None);
            let fd = finite_difference(&p, &cfg.x, &target, shift_cable(), 1e-3);
            compare(&what, &s, &fd, 1e-5);
        }
    }
}

#[test]
fn rod_stiffness_during_a_run_is_the_frozen_state_derivative() {
    dynamic_case("rod");
}

#[test]
fn cable_stiffness_during_a_run_is_the_frozen_state_derivative() {
    dynamic_case("cable");
}
