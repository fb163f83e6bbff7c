//! The Newton tangent of the step equations against finite differences of
//! the residual (inertia, director inertia, discrete gradient, drag at the
//! midpoint, added mass, the twist-held anchor's step basis), in the global
//! frame and in the nodes' director frames (the corotated tangent, §5.7).

use riser::loads::waves::sea_of;
use riser::math::V3;
use riser::model::rod::RodModel;
use riser::model::{DynamicOptions, HangOff, State};
use riser::scene::Scene;
use riser::sim::report::solve_scene;
use riser::solve::Integrator;

#[test]
fn step_tangent_matches_finite_differences_of_the_residual() {
    check_tangent(0.0, false);
}

#[test]
fn step_tangent_with_structural_damping_matches_finite_differences() {
    check_tangent(0.05, false);
}

/// With the high-frequency dissipation (§5.10) active: its weights are
/// lagged (constant over a step), its stress is in the tangent.
#[test]
fn step_tangent_with_high_frequency_dissipation_matches_finite_differences() {
    check_tangent_rho(0.0, false, 0.3);
    check_tangent_rho(0.05, true, 0.6);
}

/// The corotated tangent is the derivative of the residual, both in the
/// director frames at the iterate: Fᵀ (∂r/∂u) F, probed along u = F e_j.
#[test]
fn corotated_step_tangent_matches_finite_differences_in_the_director_frames() {
    check_tangent(0.0, true);
    check_tangent(0.05, true);
}

fn check_tangent(eta: f64, corotated: bool) {
    check_tangent_rho(eta, corotated, 1.0);
}

/// The seabed (§9): some Gauss points in contact, some crossing the plane,
/// moving in and out of it and sliding (damping, friction in both
/// directions, axial and lateral coefficients different).
#[test]
fn step_tangent_with_seabed_contact_damping_and_friction_matches_finite_differences() {
    let scene = Scene::builtin("steel_catenary").unwrap().with_overrides(&["n_elements=12"]).unwrap();
    for (corotated, rho) in [(false, 1.0), (true, 0.8)] {
        check_tangent_scene(&scene, 0.0, corotated, rho);
    }
}

/// The free surface (§10) through the line: elements in the band, the
/// correction's discrete gradient, drag and added mass scaled by the
/// submerged fraction.
#[test]
fn step_tangent_through_the_free_surface_matches_finite_differences() {
    let scene = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&["n_elements=6", "ca_normal=1.0", "current_direction=40", "water_surface_z=-30"])
        .unwrap();
    check_tangent_scene(&scene, 0.0, true, 0.8);
}

/// In waves (§13.6): the drag on the velocity relative to the moving water,
/// the water's inertia (Froude–Krylov and added mass on the relative
/// acceleration) and the free surface cut at the moving elevation, with the
/// line through the surface; the waves at full height from t = 0.
#[test]
fn step_tangent_in_waves_through_the_moving_surface_matches_finite_differences() {
    let scene = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[
            "n_elements=6",
            "ca_normal=1.0",
            "current_direction=40",
            "water_surface_z=-30",
            "wave_kind=airy",
            "wave_height=8",
            "wave_period=9",
            "wave_direction=30",
            "wave_ramp=0",
        ])
        .unwrap();
    check_tangent_scene(&scene, 0.0, true, 0.8);
    check_tangent_scene(&scene, 0.0, false, 1.0);
}

/// A flex joint at the hang-off (§15) between the vessel's frame turning over
/// the step and the line's end, bent and twisted: linear (stiff enough,
/// 1e8 N m/rad, to show in its rows next to the shear penalty's) and a
/// table, in both bases.
#[test]
fn step_tangent_with_a_flex_joint_matches_finite_differences() {
    let linear = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&["n_elements=4", "hang_off_end=flex_joint", "flex_joint_stiffness=1e8"])
        .unwrap();
    let text = format!(
        "{}\n[hang_off]\nend = \"flex_joint\"\ntable = [[0.0, 0.0], [0.01, 8e5], [0.05, 1.6e6]]\n",
        linear.to_toml().split("\n[hang_off]").next().unwrap()
    );
    let table = Scene::from_toml(&text, "joint.toml").unwrap();
    assert!(table.hang_off.table.is_some());
    for corotated in [false, true] {
        check_tangent_scene(&linear, 0.0, corotated, 1.0);
        check_tangent_scene(&table, 0.0, corotated, 1.0);
    }
}

fn check_tangent_rho(eta: f64, corotated: bool, rho_infinity: f64) {
    let scene = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&["n_elements=4", "ca_normal=1.0", "current_direction=40"])
        .unwrap();
    check_tangent_scene(&scene, eta, corotated, rho_infinity);
}

fn check_tangent_scene(scene: &Scene, eta: f64, corotated: bool, rho_infinity: f64) {
    let scene = scene.clone();
    let report = solve_scene(&scene).unwrap();
    let mut model = RodModel::from_scene(&scene).with_sea(sea_of(&scene, 0.0).unwrap());
    model.set_static_frame(&report.solution.config);
    let opts =
        DynamicOptions { structural_damping: eta, corotated_tangent: corotated, rho_infinity, ..Default::default() };
    let mut integ = Integrator::new(model, opts, scene.hang_off()).unwrap();
    let mut prev = State::at_rest(report.solution.config.clone(), 0.0);
    // a moving, out-of-plane state so that every term is active
    for a in 0..prev.vel.len() {
        prev.vel[a] = V3::new(0.3, -0.4, 0.2) * (a as f64 * 0.3).sin();
        prev.slope_vel[a] = V3::new(-0.01, 0.02, 0.015) * (a as f64).cos();
        prev.mean_vel[a] = prev.vel[a];
        // a history that alternates in places: the dissipation's weights in (0, 1]
        prev.prev_mean_vel[a] = prev.vel[a] * (a as f64 * 0.9).cos();
    }
    for j in 0..prev.director_vel.len() {
        prev.director_vel[j] = prev.config.d[j] * riser::math::skew(&V3::new(0.02, -0.01, 0.03));
    }
    let h = 0.1;
    let mut target = HangOff::translation(V3::new(0.05, 0.02, 0.1), V3::new(0.3, 0.1, 0.6));
    // the vessel turned, and turning over the step (a flex joint feels it)
    prev.hang_off.rotation = riser::math::cayley(&V3::new(0.01, -0.02, 0.015));
    target.rotation = riser::math::cayley(&V3::new(0.03, 0.01, -0.02)) * prev.hang_off.rotation;
    let mut cfg = integ.begin_step(&prev, h, target);
    // move away from the predictor so the state is generic
    let n = integ.model.rod.n_dof();
    let mut bump = vec![0.0; n];
    for (i, b) in bump.iter_mut().enumerate() {
        *b = 1e-3 * ((i as f64 * 0.37).sin());
    }
    let fixed = integ.model.rod.fixed_dofs();
    for &i in &fixed {
        bump[i] = 0.0;
    }
    integ.apply_step_increment(&prev, &mut cfg, &bump);
    let twist0 = integ.workspace().twist_state();
    let r0 = integ.step_residual(&prev, &cfg, h, target, true);
    let k: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| integ.tangent_entry(i, j)).collect()).collect();
    let scale = r0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst: f64 = 0.0;
    for j in 0..n {
        if fixed.contains(&j) {
            continue;
        }
        let eps = 1e-6;
        let mut col = [vec![0.0; n], vec![0.0; n]];
        for (s, sign) in [1.0, -1.0].iter().enumerate() {
            let mut du = vec![0.0; n];
            du[j] = sign * eps;
            integ.to_spatial_basis(&cfg, &mut du);
            let mut c = cfg.clone();
            integ.workspace_mut().set_twist_state(&twist0);
            integ.apply_step_increment(&prev, &mut c, &du);
            col[s] = integ.step_residual(&prev, &c, h, target, false);
            integ.to_tangent_basis(&cfg, &mut col[s]);
        }
        integ.workspace_mut().set_twist_state(&twist0);
        for i in 0..n {
            if fixed.contains(&i) {
                continue;
            }
            let fd = (col[0][i] - col[1][i]) / (2.0 * eps);
            let err = (fd - k[i][j]).abs();
            // the row's scale: central differences of a residual of size |r| carry
            // about ε_mach |r| / eps of noise, and O(eps²) truncation
            let row_scale = k[i].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let rel = err / row_scale;
            if rel > 1e-6 {
                eprintln!("K[{i}][{j}] = {:.6e}, FD {:.6e}, row scale {row_scale:.3e}", k[i][j], fd);
            }
            worst = worst.max(rel);
        }
    }
    eprintln!("worst tangent error relative to its row {worst:.3e} (residual scale {scale:.3e})");
    assert!(worst < 1e-6);
}
