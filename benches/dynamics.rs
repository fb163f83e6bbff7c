//! Dynamics benchmark (issue 3, evidence 7): the catenary scene, 60
//! elements, time step 0.05 s, 100 s of heave 2.5 m / 20 s with the 0.8 m/s
//! current, from the static state. Prints wall time, Newton iterations per
//! step and the real-time factor, median of several runs, for the paper's
//! abrupt start and for a one-period smooth start, at the default
//! `rho_infinity` and with the conserving scheme (`rho_infinity` = 1).
//!
//! Run: `cargo bench --bench dynamics` (RISER_BENCH_RUNS sets the run count,
//! RISER_BENCH_ONLY=smooth or =abrupt runs one start only, RISER_BENCH_RHO
//! one `rho_infinity` only).

use riser::scene::{DEFAULT_RHO_INFINITY, Scene};
use riser::sim::{Heave, Simulation};
use std::time::Instant;

mod common;
use common::*;

fn one_run(ramp: f64, rho_infinity: f64) -> (f64, f64, u64, f64) {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&[format!("rho_infinity={rho_infinity}")]).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp };
    let motion = move |t: f64| heave.at(t);
    sim.start(heave.at(0.0));
    let dt = sim.integrator.options().time_step;
    let t0 = Instant::now();
    for k in 1..=2000u64 {
        sim.advance_to(k as f64 * dt, &motion).unwrap();
    }
    let wall = t0.elapsed().as_secs_f64();
    let st = &sim.state;
    let tangents = sim.integrator.factorizations() as f64 / st.steps as f64;
    (wall, st.newton_iterations as f64 / st.steps as f64, st.retries, tangents)
}

fn main() {
    let runs: usize = std::env::var("RISER_BENCH_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    println!("catenary, 60 elements, dt 0.05 s, 100 s simulated, {runs} runs (median)");
    println!(
        "{:<28} {:>12} {:>10} {:>12} {:>13} {:>10} {:>8}",
        "start", "rho_infinity", "wall (s)", "Newton/step", "tangents/step", "RTF", "splits"
    );
    let only = std::env::var("RISER_BENCH_ONLY").unwrap_or_default();
    let starts = [("abrupt (paper)", 0.0), ("smooth over 20 s", 20.0)];
    let rhos: Vec<f64> = match std::env::var("RISER_BENCH_RHO").ok().and_then(|v| v.parse().ok()) {
        Some(r) => vec![r],
        None => vec![DEFAULT_RHO_INFINITY, 1.0],
    };
    for (rho, (name, ramp)) in rhos.into_iter().flat_map(|r| starts.map(|s| (r, s))) {
        if !name.starts_with(only.as_str()) {
            continue;
        }
        let mut walls = Vec::new();
        let mut its = 0.0;
        let mut splits = 0;
        let mut tangents = 0.0;
        for _ in 0..runs {
            let (w, i, s, t) = one_run(ramp, rho);
            walls.push(w);
            its = i;
            splits = s;
            tangents = t;
        }
        let w = median(&mut walls);
        println!(
            "{:<28} {:>12} {:>10.3} {:>12.2} {:>13.3} {:>10.1} {:>8}",
            name,
            rho,
            w,
            its,
            tangents,
            100.0 / w,
            splits
        );
    }
}
