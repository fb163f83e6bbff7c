//! Conservation properties of the energy–momentum scheme (docs/theory.md §5):
//! exact energy in the Hamiltonian case, exact momenta for a free rod, the
//! discrete energy balance with drag and a moving hang-off.

use riser::loads::fluid::Fluid;
use riser::math::V3;
use riser::model::rod::RodModel;
use riser::model::sections::PerElement;
use riser::model::{DynamicOptions, HangOff, State};
use riser::scene::Scene;
use riser::sim::report::solve_scene;
use riser::solve::Integrator;

/// Catenary scene without water forces, static state, and a velocity kick.
fn hamiltonian_setup(n_el: usize, dt: f64) -> (Integrator<RodModel>, State) {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&[format!("n_elements={n_el}")]).unwrap();
    let report = solve_scene(&scene).unwrap();
    let mut model = RodModel::from_scene(&scene);
    model.fluid = PerElement::uniform(Fluid::none(), n_el);
    // energy is conserved to the Newton tolerance: ask for round-off
    let opts = DynamicOptions { time_step: dt, newton_tolerance: 1e-13, ..Default::default() };
    let integ = Integrator::new(model, opts, scene.hang_off()).unwrap();
    let mut state = State::at_rest(report.solution.config.clone(), 0.0);
    let l = scene.line.length;
    for a in 0..state.vel.len() {
        let s = integ.model.rod.s_node(a);
        let w = (std::f64::consts::PI * s / l).sin();
        let dw = std::f64::consts::PI / l * (std::f64::consts::PI * s / l).cos();
        state.vel[a] = V3::new(0.0, 0.5, 0.0) * w;
        state.slope_vel[a] = V3::new(0.0, 0.5, 0.0) * dw;
    }
    (integ, state)
}

#[test]
fn hamiltonian_energy_is_conserved_for_small_and_large_steps() {
    for &dt in &[1e-3, 0.05, 0.5] {
        let (mut integ, mut state) = hamiltonian_setup(20, dt);
        let still = |_t: f64| HangOff::default();
        let e0 = integ.model.outputs(&state).total_energy;
        let k0 = integ.model.outputs(&state).kinetic_energy;
        let mut worst: f64 = 0.0;
        let t = std::time::Instant::now();
        for _ in 0..2000 {
            integ.step(&mut state, dt, &still).unwrap();
            let o = integ.model.outputs(&state);
            worst = worst.max((o.total_energy - e0).abs());
        }
        eprintln!(
            "dt {dt}: |E - E0| max {worst:.3e} J, E0 {e0:.6e}, K0 {k0:.3e}, rel {:.3e}, iters/step {:.2}, {:?}",
            worst / e0.abs(),
            state.newton_iterations as f64 / state.steps as f64,
            t.elapsed()
        );
        // relative to |E| (datum: the hang-off; the criterion) and,
        // more demanding, to the kinetic energy of the kick, the energy that
        // actually moves around: the drift is the work of the residual left by
        // Newton (round-off of EA ε |r|/h) over the increments
        assert!(worst <= 1e-9 * e0.abs(), "energy drift {worst:e} J");
        assert!(worst <= 1e-8 * k0, "energy drift {worst:e} J vs kinetic energy {k0:e} J");
    }
}

/// A free rod in space: no gravity, no water, free ends.
fn free_rod(n_el: usize, dt: f64) -> (Integrator<RodModel>, State) {
    use riser::loads::weight::VerticalLoad;
    use riser::model::rod::{EndBc, Rod, Stiffness};
    let l = 10.0;
    let rod = Rod::new(n_el, l, Stiffness::paper(1e5, 1e2, 80.0), [EndBc::FREE, EndBc::FREE]);
    let m = 5.0;
    let vertical = VerticalLoad { uniform: 0.0, sections: vec![] };
    let model = RodModel::new(rod, m, [0.01, 0.02], vertical, Fluid::none());
    let cfg = model.rod.straight(V3::new(-4.9, -1.0, -0.5), V3::new(1.0, 0.2, 0.1), V3::z());
    // Newton to round-off: the momenta drift by h Σ x × r per step
    let opts = DynamicOptions { time_step: dt, newton_tolerance: 1e-15, ..Default::default() };
    let integ = Integrator::new(model, opts, V3::zeros()).unwrap();
    let mut state = State::at_rest(cfg, 0.0);
    let centre = state.config.x[n_el / 2];
    // slow drift: far from the origin, r' = Σ N'_k r_k loses digits (round-off ∝ |r|)
    state.set_rigid_velocity(V3::new(0.05, -0.03, 0.02), V3::new(0.3, 1.1, -0.7), centre);
    // plus a bending and stretching perturbation
    for a in 0..state.vel.len() {
        let s = integ.model.rod.s_node(a) / l;
        state.vel[a] += V3::new(0.2 * s, -0.3 * s * s, 0.4 * (1.0 - s));
    }
    (integ, state)
}

#[test]
fn free_rod_conserves_momenta_and_keeps_directors_orthonormal() {
    let (mut integ, mut state) = free_rod(8, 0.01);

    let p0 = integ.model.linear_momentum(&state);
    let l0 = integ.model.angular_momentum(&state);
    let e0 = integ.model.outputs(&state).total_energy;
    let none = |_t: f64| HangOff::default();
    let (mut dp, mut dl, mut de): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..10_000 {
        integ.step(&mut state, 0.01, &none).unwrap();
        dp = dp.max((integ.model.linear_momentum(&state) - p0).norm());
        dl = dl.max((integ.model.angular_momentum(&state) - l0).norm());

        de = de.max((integ.model.outputs(&state).total_energy - e0).abs());
    }
    let ortho = state.config.orthonormality_error();
    eprintln!(
        "free rod, 1e4 steps: |Δp|/|p| {:.2e}, |ΔL|/|L| {:.2e}, |ΔE|/E {:.2e}, |DᵀD − I| {:.2e}, iters/step {:.2}",
        dp / p0.norm(),
        dl / l0.norm(),
        de / e0.abs(),
        ortho,
        state.newton_iterations as f64 / state.steps as f64
    );
    assert!(dp <= 1e-10 * p0.norm(), "linear momentum drift {dp:e}");
    assert!(dl <= 1e-10 * l0.norm(), "angular momentum drift {dl:e}");
    assert!(de <= 1e-9 * e0.abs(), "energy drift {de:e}");
    assert!(ortho <= 1e-12, "directors not orthonormal: {ortho:e}");
}

/// Catenary scene with its current, 20 elements, heave 2.5 m / 20 s.
fn heaving_catenary(extra: &[&str]) -> (Integrator<RodModel>, State, f64) {
    let mut sets = vec!["n_elements=20".to_string()];
    sets.extend(extra.iter().map(|s| s.to_string()));
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&sets).unwrap();
    let report = solve_scene(&scene).unwrap();
    let model = RodModel::from_scene(&scene);
    let opts = DynamicOptions { time_step: 0.05, newton_tolerance: 1e-8, ..Default::default() };
    let integ = Integrator::new(model, opts, scene.hang_off()).unwrap();
    let state = State::at_rest(report.solution.config.clone(), 0.0);
    (integ, state, report.top_tension)
}

fn heave(t: f64) -> HangOff {
    let w = 2.0 * std::f64::consts::PI / 20.0;
    HangOff::translation(V3::z() * (2.5 * (w * t).sin()), V3::z() * (2.5 * w * (w * t).cos()))
}

#[test]
fn energy_balance_closes_with_drag_current_added_mass_and_moving_hang_off() {
    for extra in [&[][..], &["ca_normal=1.0", "current_direction=53"][..]] {
        let (mut integ, mut state, _) = heaving_catenary(extra);
        integ.impose_hang_off(&mut state, heave(0.0));
        let e0 = integ.model.outputs(&state).total_energy;
        let mut worst: f64 = 0.0;
        let mut exchanged: f64 = 0.0;
        for _ in 0..800 {
            integ.step(&mut state, 0.05, &heave).unwrap();
            let o = integ.model.outputs(&state);
            worst = worst.max(o.energy_balance_residual(e0).abs());
            exchanged = exchanged.max(o.work_top.abs() + o.work_hydro.abs());
        }
        let o = integ.model.outputs(&state);
        eprintln!(
            "{extra:?}: W_top {:.4e} J, W_hydro {:.4e} J, W_anchor {:.2e} J, balance residual max {worst:.3e} J \
             ({:.2e} of the energy exchanged), iters/step {:.2}",
            o.work_top,
            o.work_hydro,
            o.work_anchor,
            worst / exchanged,
            state.newton_iterations as f64 / state.steps as f64
        );
        assert!(o.work_hydro < 0.0, "the water must take energy out of a heaving line");
        assert!(worst <= 1e-6 * exchanged);
    }
}

#[test]
fn structural_damping_never_creates_energy_and_keeps_momenta() {
    // Hamiltonian setting plus Kelvin–Voigt damping: E never increases and
    // E(t) − E(0) + D(t) = 0 (D the dissipated energy)
    let (mut integ, mut state) = hamiltonian_setup(20, 0.05);
    integ.options.structural_damping = 0.01;
    let still = |_t: f64| HangOff::default();
    let mut e_prev = integ.model.outputs(&state).total_energy;
    let e0 = e_prev;
    let mut worst: f64 = 0.0;
    for _ in 0..400 {
        integ.step(&mut state, 0.05, &still).unwrap();
        let o = integ.model.outputs(&state);
        assert!(o.total_energy <= e_prev + 1e-9 * e0.abs(), "energy created: {} -> {}", e_prev, o.total_energy);
        e_prev = o.total_energy;
        worst = worst.max(o.energy_balance_residual(e0).abs());
    }
    let o = integ.model.outputs(&state);
    eprintln!("damped: dissipated {:.4e} J, balance residual {worst:.3e} J", o.dissipated_energy);
    assert!(o.dissipated_energy > 0.0);
    assert!(worst <= 1e-9 * o.dissipated_energy.max(1.0) * 1e3);
    // free rod with damping: momenta still conserved
    let (mut integ, mut state) = free_rod(8, 0.01);
    integ.options.structural_damping = 0.05;
    let p0 = integ.model.linear_momentum(&state);
    let l0 = integ.model.angular_momentum(&state);
    let none = |_t: f64| HangOff::default();
    for _ in 0..2000 {
        integ.step(&mut state, 0.01, &none).unwrap();
    }
    let dp = (integ.model.linear_momentum(&state) - p0).norm() / p0.norm();
    let dl = (integ.model.angular_momentum(&state) - l0).norm() / l0.norm();
    eprintln!(
        "damped free rod, 2000 steps: |Δp|/|p| {dp:.2e}, |ΔL|/|L| {dl:.2e}, dissipated {:.3e} J",
        state.dissipated
    );
    assert!(dp <= 1e-10 && dl <= 1e-10);
    assert!(state.dissipated > 0.0);
}

#[test]
fn free_motion_after_the_excitation_keeps_its_energy() {
    // the paper's Fig. 11: no drag, heave 2.5 m / 20 s for 15 s, then the
    // hang-off is held (at t = 15 s the heave velocity is zero)
    use riser::sim::{Heave, Simulation};
    let scene = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[
            "n_elements=20",
            "cd_normal=0",
            "cd_tangential=0",
            "newton_tolerance=1e-12",
            "rho_infinity=1",
        ])
        .unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let heave = Heave { amplitude: 2.5, period: 20.0, until: Some(15.0), ramp: 0.0 };
    let motion = move |t: f64| heave.at(t);
    sim.start(heave.at(0.0));
    let dt = 0.05;
    let mut e_hold = None;
    let mut worst: f64 = 0.0;
    let mut kinetic_max: f64 = 0.0;
    for k in 1..=800u64 {
        sim.advance_to(k as f64 * dt, &motion).unwrap();
        let o = sim.outputs();
        if k == 300 {
            e_hold = Some(o.total_energy);
        }
        if let Some(e) = e_hold {
            worst = worst.max((o.total_energy - e).abs());
            kinetic_max = kinetic_max.max(o.kinetic_energy);
        }
    }
    let e = e_hold.unwrap();
    eprintln!(
        "free motion 15–40 s: |E − E(15 s)| max {worst:.3e} J, |E| {:.4e} J ({:.2e}), kinetic energy up to {kinetic_max:.3e} J",
        e.abs(),
        worst / e.abs()
    );
    assert!(kinetic_max > 1.0, "the line must still be moving");
    assert!(worst <= 1e-8 * e.abs());
}

/// The high-frequency dissipative variant (docs/theory.md §5.10) on the
/// Hamiltonian catenary: the energy never increases, and the energy it
/// removes is `algorithmic_dissipation`: E(t) − E(0) + D_alg(t) = 0.
#[test]
fn high_frequency_dissipation_never_creates_energy_and_the_balance_closes() {
    for (dt, rho) in [(0.05, 0.5), (0.5, 0.8), (0.5, 0.1)] {
        let (mut integ, mut state) = hamiltonian_setup(20, dt);
        integ.options.rho_infinity = rho;
        let still = |_t: f64| HangOff::default();
        let o = integ.model.outputs(&state);
        let (e0, k0) = (o.total_energy, o.kinetic_energy);
        let mut e_prev = e0;
        let mut worst: f64 = 0.0;
        for _ in 0..400 {
            integ.step(&mut state, dt, &still).unwrap();
            let o = integ.model.outputs(&state);
            assert!(o.total_energy <= e_prev + 1e-9 * e0.abs(), "energy created: {e_prev} -> {}", o.total_energy);
            e_prev = o.total_energy;
            worst = worst.max(o.energy_balance_residual(e0).abs());
        }
        let o = integ.model.outputs(&state);
        eprintln!(
            "dt {dt}, rho_inf {rho}: removed {:.4e} J of K0 {k0:.4e} J, balance residual max {worst:.3e} J \
             ({:.1e} of |E0|), iters/step {:.2}",
            o.algorithmic_dissipation,
            worst / e0.abs(),
            state.newton_iterations as f64 / state.steps as f64
        );
        assert!(o.algorithmic_dissipation > 0.0);
        // the same criterion as the conserving scheme's energy (above)
        assert!(worst <= 1e-9 * e0.abs(), "balance residual {worst:e} J");
    }
}

/// The dissipative variant keeps both momenta of the free rod exactly: its
/// stress is objective, and its velocity filter has no rigid part (§5.10).
#[test]
fn high_frequency_dissipation_keeps_the_momenta_of_a_free_rod() {
    for rho in [0.5f64, 0.0] {
        // a step that leaves the axial and shear waves unresolved (ω h ≫ 1)
        let dt = 0.05;
        let (mut integ, mut state) = free_rod(8, dt);
        integ.options.rho_infinity = rho.max(1e-3);
        let p0 = integ.model.linear_momentum(&state);
        let l0 = integ.model.angular_momentum(&state);
        let none = |_t: f64| HangOff::default();
        let (mut dp, mut dl): (f64, f64) = (0.0, 0.0);
        for _ in 0..2000 {
            integ.step(&mut state, dt, &none).unwrap();
            dp = dp.max((integ.model.linear_momentum(&state) - p0).norm() / p0.norm());
            dl = dl.max((integ.model.angular_momentum(&state) - l0).norm() / l0.norm());
        }
        eprintln!(
            "free rod, rho_inf {rho}, 2000 steps: |Δp|/|p| {dp:.2e}, |ΔL|/|L| {dl:.2e}, removed {:.3e} J",
            state.algorithmic
        );
        assert!(state.algorithmic > 0.0);
        assert!(dp <= 1e-10 && dl <= 1e-10, "momentum drift {dp:e}, {dl:e}");
    }
}
