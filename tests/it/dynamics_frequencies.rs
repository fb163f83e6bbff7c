//! Natural frequencies from free vibration computed by the time integrator,
//! against closed forms: hanging chain, cantilever, taut string.
//! The frequencies are read off the response with a Hann-windowed discrete
//! Fourier transform evaluated on a fine frequency grid (peak refined to
//! 1e-5 Hz), so the resolution is far below the 0.5–1 % tolerances.

use crate::common;

use riser::loads::fluid::Fluid;
use riser::loads::weight::VerticalLoad;
use riser::math::{M3, V3};
use riser::model::RodConfig;
use riser::model::rod::RodModel;
use riser::model::rod::statics::{StaticLoads, StaticProblem};
use riser::model::rod::{EndBc, Rod, Stiffness};
use riser::model::statics::StaticOptions;
use riser::model::{DynamicOptions, HangOff, State};
use riser::solve::Integrator;
use riser::solve::statics::solve;
use std::f64::consts::PI;

/// Runs free vibration and samples the y-displacement of end node `a`.
fn record(integ: &mut Integrator<RodModel>, state: &mut State, a: usize, dt: f64, steps: usize) -> Vec<f64> {
    let still = |_t: f64| HangOff::default();
    let mut y = Vec::with_capacity(steps + 1);
    y.push(state.config.x[a].y);
    for _ in 0..steps {
        integ.step(state, dt, &still).unwrap();
        y.push(state.config.x[a].y);
    }
    y
}

fn no_gravity() -> VerticalLoad {
    VerticalLoad { uniform: 0.0, sections: vec![] }
}

// EI → 0 under tension: this is the test that exposed the zig-zag
// instability of the Σ(d_i·r' − δ_i3)² penalty (element.rs, theory §2.2).
#[test]
fn hanging_chain_first_three_frequencies() {
    // 10 m chain, 1 kg/m, EI/(m g L³) = 1e-6, nearly inextensible
    let (l, m, g) = (10.0, 1.0, 9.81);
    let n_el = 24;
    let rod = Rod::new(n_el, l, Stiffness::paper(1e7, 1e-2, 1e-2), [EndBc::PINNED_NO_TWIST, EndBc::FREE]);
    let vertical = VerticalLoad { uniform: -m * g, sections: vec![] };
    let start = rod.straight(V3::zeros(), -V3::z(), V3::y());
    let loads = StaticLoads::gravity_only(vertical.clone());
    let sol = solve(&StaticProblem::new(&rod, &loads), start, &StaticOptions::default()).unwrap();
    let model = RodModel::new(rod, m, [1e-4, 1e-4], vertical, Fluid::none());
    let dt = 0.04;
    let opts = DynamicOptions { time_step: dt, newton_tolerance: 1e-10, ..Default::default() };
    let mut integ = Integrator::new(model, opts, V3::zeros()).unwrap();
    let mut state = State::at_rest(sol.config, 0.0);
    for a in 0..=n_el {
        let s = integ.model.rod.s_node(a) / l;
        state.vel[a] = V3::y() * (0.02 * s);
        state.slope_vel[a] = V3::y() * (0.02 / l);
    }
    state.align_director_rates(&integ.model.rod);
    let y = record(&mut integ, &mut state, n_el, dt, 4000);
    let zeros = common::reference::bessel_j0_zeros(3);
    for (n, j0n) in zeros.iter().enumerate() {
        let exact = j0n / 2.0 * (g / l).sqrt() / (2.0 * PI);
        let f = common::spectral::peak_near(&y, dt, exact);
        let err = (f - exact) / exact;
        eprintln!(
            "hanging chain mode {}: {f:.5} Hz vs (j0n/2)√(g/L)/2π = {exact:.5} Hz ({:+.3} %)",
            n + 1,
            100.0 * err
        );
        assert!(err.abs() < 0.01);
    }
}

#[test]
fn cantilever_first_frequency() {
    let (l, m, ei) = (10.0, 1.0, 1e3);
    let n_el = 10;
    let rod = Rod::new(n_el, l, Stiffness::paper(1e8, ei, 1e3), [EndBc::CLAMPED, EndBc::FREE]);
    let cfg = rod.straight(V3::zeros(), V3::x(), V3::y());
    let model = RodModel::new(rod, m, [1e-6, 1e-6], no_gravity(), Fluid::none());
    let dt = 0.04;
    let opts = DynamicOptions { time_step: dt, newton_tolerance: 1e-10, ..Default::default() };
    let mut integ = Integrator::new(model, opts, V3::zeros()).unwrap();
    let mut state = State::at_rest(cfg, 0.0);
    for a in 0..=n_el {
        let s = integ.model.rod.s_node(a) / l;
        state.vel[a] = V3::y() * (0.01 * s * s);
        state.slope_vel[a] = V3::y() * (0.02 * s / l);
    }
    state.align_director_rates(&integ.model.rod);
    let y = record(&mut integ, &mut state, n_el, dt, 4000);
    let exact = 1.8751f64.powi(2) * (ei / (m * l.powi(4))).sqrt() / (2.0 * PI);
    let f = common::spectral::peak_near(&y, dt, exact);
    let err = (f - exact) / exact;
    eprintln!("cantilever: {f:.5} Hz vs 1.8751²√(EI/mL⁴)/2π = {exact:.5} Hz ({:+.3} %)", 100.0 * err);
    assert!(err.abs() < 0.01);
}

#[test]
fn taut_string_first_three_frequencies() {
    // unstretched 10 m stretched to 10.01 m: T = EA·1e-3 = 400 N; m = 1 kg/m
    let (l0, span, ea, m) = (10.0, 10.01, 4e5, 1.0);
    let n_el = 30;
    let rod = Rod::new(n_el, l0, Stiffness::paper(ea, 1e-3, 1e-3), [EndBc::PINNED_NO_TWIST, EndBc::PINNED]);
    let stretch = span / l0;
    let frame = M3::identity();
    let cfg = RodConfig {
        x: (0..=n_el).map(|a| V3::z() * (-rod.s_node(a) * stretch)).collect(),
        xp: vec![-V3::z() * stretch; n_el + 1],
        d: vec![M3::from_columns(&[V3::y(), V3::x(), -V3::z()]) * frame; 2 * n_el + 1],
    };
    let model = RodModel::new(rod, m, [1e-6, 1e-6], no_gravity(), Fluid::none());
    let dt = 0.004;
    let opts = DynamicOptions { time_step: dt, newton_tolerance: 1e-10, ..Default::default() };
    let mut integ = Integrator::new(model, opts, V3::zeros()).unwrap();
    let mut state = State::at_rest(cfg, 0.0);
    for a in 0..=n_el {
        let s = integ.model.rod.s_node(a) / l0;
        let (mut v, mut dv) = (0.0, 0.0);
        for n in 1..=3 {
            let k = n as f64 * PI;
            v += 0.01 * (k * s).sin();
            dv += 0.01 * k / l0 * (k * s).cos();
        }
        state.vel[a] = V3::y() * v;
        state.slope_vel[a] = V3::y() * dv;
    }
    let tension = ea * (stretch - 1.0);
    let rho = m / stretch; // mass per stretched length
    state.align_director_rates(&integ.model.rod);
    let y = record(&mut integ, &mut state, n_el / 5, dt, 5000);
    for n in 1..=3 {
        let exact = n as f64 / (2.0 * span) * (tension / rho).sqrt();
        let f = common::spectral::peak_near(&y, dt, exact);
        let err = (f - exact) / exact;
        eprintln!("taut string mode {n}: {f:.5} Hz vs (n/2L)√(T/ρ) = {exact:.5} Hz ({:+.3} %)", 100.0 * err);
        assert!(err.abs() < 0.005);
    }
}
