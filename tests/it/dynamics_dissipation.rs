//! The high-frequency dissipative variant of the scheme (docs/theory.md
//! §5.10) on its model problem and its order of accuracy:
//! its spectral radius at ω h = 100 is the asked ρ∞ (a linear oscillator).
//! Its order: `dynamics_convergence`; energy and momenta:
//! `dynamics_conservation` and `cable`.

use riser::loads::fluid::Fluid;
use riser::loads::weight::VerticalLoad;
use riser::math::V3;
use riser::model::cable::{Cable, CableModel};
use riser::model::{DynamicOptions, HangOff, State};
use riser::solve::Integrator;

/// Measured spectral radius of the scheme on a linear oscillator at ω h =
/// `omega_h`: one cable segment hanging from a fixed point under its weight
/// (tension EA(λ − 1), linear about the stretched equilibrium), its free end
/// displaced along the line. The radius is the per-step decay of the
/// oscillator's energy ½ m v² + ½ k δ², measured after the start-up steps
/// (the weights need two steps of history).
fn oscillator_radius(rho_infinity: f64, omega_h: f64) -> f64 {
    let (length, ea, m) = (10.0, 1e7, 50.0);
    let cable = Cable::new(length, 1, ea, [true, false]);
    let model = CableModel::new(cable, m, VerticalLoad { uniform: -m * 9.81, sections: vec![] }, Fluid::none());
    let load = -model.gravity_vector()[1];
    let z_eq = -length * (1.0 + load / ea);
    let (k, m_node) = (ea / length, model.mass.at(0)[1][1]);
    let omega = (k / m_node).sqrt();
    let h = omega_h / omega;
    // (a resolved step: the inertia rows' round-off, m x 2/h², limits the tolerance)
    let tolerance = if omega_h > 1.0 { 1e-12 } else { 1e-9 };
    let opts = DynamicOptions { time_step: h, newton_tolerance: tolerance, rho_infinity, ..Default::default() };
    let mut integ = Integrator::new(model, opts, V3::zeros()).unwrap();
    let amplitude = 1e-3;
    let mut state = CableModel::state_at_rest(vec![V3::zeros(), V3::new(0.0, 0.0, z_eq - amplitude)], 0.0);
    let energy = |s: &State| 0.5 * m_node * s.vel[1].norm_squared() + 0.5 * k * (s.config.x[1].z - z_eq).powi(2);
    let still = |_t: f64| HangOff::default();
    let (n0, n1) = (3, 10);
    let mut e = [0.0; 2];
    for n in 1..=n1 {
        integ.step(&mut state, h, &still).unwrap();
        if n == n0 {
            e[0] = energy(&state);
        }
    }
    e[1] = energy(&state);
    (e[1] / e[0]).powf(0.5 / (n1 - n0) as f64)
}

#[test]
fn spectral_radius_at_large_steps_is_rho_infinity() {
    for rho in [0.2, 0.5, 0.8, 0.95] {
        let r = oscillator_radius(rho, 100.0);
        eprintln!("rho_inf {rho}: measured spectral radius at ω h = 100: {r:.4}");
        assert!((r - rho).abs() <= 0.02, "rho_inf {rho}: measured {r}");
    }
    // the conserving scheme: no decay at any step
    let r = oscillator_radius(1.0, 100.0);
    assert!((r - 1.0).abs() <= 1e-9, "conserving scheme: {r}");
    // a resolved oscillation (ω h = 0.1) keeps its amplitude to O((ω h)^4) per step
    let r = oscillator_radius(0.5, 0.1);
    eprintln!("rho_inf 0.5 at ω h = 0.1: {r:.8}");
    assert!((1.0 - r).abs() <= 1e-4, "resolved mode damped: {r}");
}
