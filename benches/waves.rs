//! The cost of the wave kinematics (docs/theory.md §13.4) where the force
//! integration will call them: once per Newton iteration at the Gauss points
//! of the whole line (the catenary's static state, 60 elements: 240 points),
//! against one residual of the step equations in still water (the kernel a
//! Newton iteration evaluates once). A regular wave and JONSWAP seas of 50
//! and 200 components, in 100 m of water and in deep water. Median of 7
//! rounds. Two calls: `kinematics_batch` (with the velocity gradient, for a
//! tangent) and `water_batch` (elevation, velocity and acceleration: what
//! the force evaluates once per step).
//!
//! Run: `cargo bench --bench waves` (or `--profile fasttest`).

use riser::loads::waves::{WaterPoint, WavePoint, WaveScratch, sea_of};
use riser::math::V3;
use riser::scene::Scene;
use riser::sim::{Engine, Heave, Simulation};
use std::hint::black_box;
use std::time::Instant;

mod common;
use common::*;

/// The hang-off's heave in both parts: 2.5 m, 20 s, ramped in over 20 s.
const HEAVE: Heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 20.0 };

/// `sim` started from its static state and heaved by [`HEAVE`] for `steps`
/// of its own time step; that step, s.
fn heaved(sim: &mut Simulation, steps: u64) -> f64 {
    sim.start(HEAVE.at(0.0));
    let dt = sim.integrator.options().time_step;
    for k in 1..=steps {
        sim.advance_to(k as f64 * dt, &|t| HEAVE.at(t)).unwrap();
    }
    dt
}

fn main() {
    let base = Scene::builtin("catenary").unwrap();
    let mut sim = Simulation::from_scene(&base).unwrap();
    let dt = heaved(&mut sim, 200);
    let motion = |t: f64| HEAVE.at(t);
    let points: Vec<V3> = sim.integrator.line_points(&sim.state).iter().map(|p| p.position).collect();
    let prev = sim.state.clone();
    let t = prev.time + dt;
    let Engine::Rod(integ) = &mut sim.integrator else { unreachable!("the catenary scene is a rod") };
    let predicted = integ.begin_step(&prev, dt, motion(t));
    let residual = time(2000, || {
        black_box(integ.step_residual(&prev, &predicted, dt, motion(t), false));
    });
    println!("catenary, 60 elements, {} Gauss points; median of 7 rounds", points.len());
    println!("{:<44} {:>10} {:>14} {:>10} {:>14}", "", "kin. µs", "x residual", "water µs", "x residual");
    println!("{:<44} {:>10.1} {:>14.2}", "one residual of the step (still water)", residual, 1.0);
    let seas = [
        ("regular wave H 6 m T 10 s", "kind = \"airy\"\nheight = 6.0\nperiod = 10.0"),
        ("JONSWAP Hs 6 m Tp 10 s, 50 components", "kind = \"jonswap\"\nhs = 6.0\ntp = 10.0\ncomponents = 50"),
        ("JONSWAP Hs 6 m Tp 10 s, 200 components", "kind = \"jonswap\"\nhs = 6.0\ntp = 10.0\ncomponents = 200"),
    ];
    for (depth_name, depth) in [("100 m", "\ndepth = 100.0"), ("deep", "")] {
        for (name, block) in seas {
            let text = format!("{}\n[waves]\n{block}{depth}\nramp = 0.0\n", base.to_toml());
            let scene = Scene::from_toml(&text, "bench").unwrap();
            let sea = sea_of(&scene, 0.0).unwrap().unwrap();
            let mut out = vec![WavePoint::STILL; points.len()];
            let mut scratch = WaveScratch::default();
            let mut clock = 0.0;
            let calls = if sea.components().len() > 100 { 100 } else { 400 };
            let us = time(calls, || {
                clock += 0.05;
                sea.kinematics_batch(clock, &points, &mut out, &mut scratch);
                black_box(&out);
            });
            let mut water = vec![WaterPoint::STILL; points.len()];
            let water_us = time(calls, || {
                clock += 0.05;
                sea.water_batch(clock, &points, &mut water, &mut scratch);
                black_box(&water);
            });
            let deep = out.iter().filter(|p| p.deep).count();
            println!(
                "{:<44} {:>10.1} {:>14.2} {:>10.1} {:>14.2}   ({deep} points below the cutoff)",
                format!("{name}, {depth_name}"),
                us,
                us / residual,
                water_us,
                water_us / residual
            );
        }
    }
    steps_in_waves(&base);
}

/// Whole steps (issue 27): the catenary at 60 elements, dt 0.05 s, heave
/// 2.5 m / 20 s, 400 steps after 100 steps of settling, in calm water, a
/// regular wave and JONSWAP seas of 50 and 200 components (the sea's own
/// depth, the waves at full height from the start); median of 7 rounds,
/// each a fresh run, the seas taken in turn within a round (interleaved,
/// so that a machine whose load changes weighs on every sea alike); the
/// ratio to calm water, and the median of the rounds' own ratios.
fn steps_in_waves(base: &Scene) {
    let seas = [
        ("calm water", String::new()),
        ("regular wave H 6 m T 10 s", "kind = \"airy\"\nheight = 6.0\nperiod = 10.0".to_string()),
        ("JONSWAP Hs 6 m Tp 10 s, 50 components", "kind = \"jonswap\"\nhs = 6.0\ntp = 10.0\ncomponents = 50".into()),
        ("JONSWAP Hs 6 m Tp 10 s, 200 components", "kind = \"jonswap\"\nhs = 6.0\ntp = 10.0\ncomponents = 200".into()),
    ];
    let scenes: Vec<Scene> = seas
        .iter()
        .map(|(_, block)| {
            let text = if block.is_empty() {
                base.to_toml()
            } else {
                format!("{}\n[waves]\n{block}\nramp = 0.0\n", base.to_toml())
            };
            Scene::from_toml(&text, "bench").unwrap()
        })
        .collect();
    const ROUNDS: usize = 7;
    let mut us = vec![Vec::new(); seas.len()];
    let mut newton = vec![0.0; seas.len()];
    for _ in 0..ROUNDS {
        for (i, scene) in scenes.iter().enumerate() {
            let mut sim = Simulation::from_scene(scene).unwrap();
            let dt = heaved(&mut sim, 100);
            let motion = |t: f64| HEAVE.at(t);
            let it0 = sim.state.newton_iterations;
            let t0 = Instant::now();
            for k in 101..=500u64 {
                sim.advance_to(k as f64 * dt, &motion).unwrap();
            }
            us[i].push(t0.elapsed().as_secs_f64() / 400.0 * 1e6);
            newton[i] = (sim.state.newton_iterations - it0) as f64 / 400.0;
            black_box(sim.outputs());
        }
    }
    println!();
    println!("a step of the catenary, 60 elements, dt 0.05 s (median of {ROUNDS} interleaved runs of 400 steps)");
    println!("{:<44} {:>10} {:>14} {:>14} {:>12}", "", "µs/step", "x calm water", "x calm, rounds", "Newton/step");
    let calm = median(&mut us[0].clone());
    for (i, (name, _)) in seas.iter().enumerate() {
        let mut ratios: Vec<f64> = us[i].iter().zip(&us[0]).map(|(a, b)| a / b).collect();
        let m = median(&mut us[i].clone());
        println!("{name:<44} {m:>10.1} {:>14.2} {:>14.2} {:>12.2}", m / calm, median(&mut ratios), newton[i]);
    }
}
