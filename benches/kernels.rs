//! Per-call costs of the time step's kernels on the dynamics benchmark's
//! state (catenary, 60 elements, dt 0.05 s, t = 50 s of the smooth start):
//! the residual of the step equations alone, and with its tangent (each
//! including a copy of the residual vector), the band LU of that tangent and
//! a solve with it. Median
//! of several rounds of many calls; the time per step of the benchmark is
//! about 4.2 residuals, 3.2 solves and a twentieth of a tangent with its LU.
//!
//! Run: `cargo bench --bench kernels`.

use riser::scene::Scene;
use riser::sim::{Engine, Heave, Simulation};
use std::hint::black_box;
use std::time::Instant;

mod common;
use common::*;

fn main() {
    let scene = Scene::builtin("catenary").unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 20.0 };
    let motion = move |t: f64| heave.at(t);
    sim.start(heave.at(0.0));
    let dt = sim.integrator.options().time_step;
    for k in 1..=1000u64 {
        sim.advance_to(k as f64 * dt, &motion).unwrap();
    }
    let prev = sim.state.clone();
    let t = prev.time + dt;
    let Engine::Rod(integ) = &mut sim.integrator else { unreachable!("the catenary scene is a rod") };
    let predicted = integ.begin_step(&prev, dt, motion(t));
    println!(
        "catenary, 60 elements, {} unknowns, state at t = {:.0} s; median of 7 rounds",
        integ.n_unknowns(),
        prev.time
    );
    println!("{:<26} {:>12}", "kernel", "µs per call");
    for (name, tangent, calls) in [("residual", false, 4000), ("residual + tangent", true, 300)] {
        let mut rounds = Vec::new();
        for _ in 0..7 {
            let t0 = Instant::now();
            for _ in 0..calls {
                black_box(integ.step_residual(&prev, &predicted, dt, motion(t), tangent));
            }
            rounds.push(t0.elapsed().as_secs_f64() / calls as f64 * 1e6);
        }
        println!("{:<26} {:>12.1}", name, median(&mut rounds));
    }
    // the tangent of the last call into a system of its own, for the LU
    let rod = &integ.model.rod;
    let mut sys = rod.new_system().unwrap();
    let n = sys.dim();
    for i in 0..n {
        for j in 0..n {
            if sys.index(i, j).is_some() {
                sys.add(i, j, integ.tangent_entry(i, j));
            }
        }
    }
    for i in rod.fixed_dofs() {
        sys.constrain(i);
    }
    let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut rounds = Vec::new();
    for _ in 0..7 {
        let t0 = Instant::now();
        for _ in 0..300 {
            sys.factorize().unwrap();
        }
        rounds.push(t0.elapsed().as_secs_f64() / 300.0 * 1e6);
    }
    println!("{:<26} {:>12.1}", "band LU", median(&mut rounds));
    let mut rounds = Vec::new();
    let mut x = rhs.clone();
    for _ in 0..7 {
        let t0 = Instant::now();
        for _ in 0..4000 {
            x.copy_from_slice(&rhs);
            sys.solve_in_place(black_box(&mut x)).unwrap();
        }
        rounds.push(t0.elapsed().as_secs_f64() / 4000.0 * 1e6);
    }
    println!("{:<26} {:>12.1}", "solve", median(&mut rounds));
}
