//! Cost of the modal analysis (`riser modes`, solve::eigen::lowest_modes) and
//! of the hang-off stiffness (the FMU's directional derivative) against the
//! mesh, on the catenary scene, rod and cable: wall time of the statics, of
//! the eigen-solution (shift-inverted, dense) and of one stiffness
//! evaluation. Median of `RISER_BENCH_RUNS` runs (default 3).
//!
//! Run: `cargo bench --bench modes` (`RISER_BENCH_ELEMENTS=60,400` to choose the meshes).

use riser::scene::Scene;
use riser::sim::Simulation;
use riser::sim::modes::scene_modes;
use std::time::Instant;

mod common;
use common::*;

fn main() {
    let runs: usize = std::env::var("RISER_BENCH_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(3);
    let meshes: Vec<usize> = std::env::var("RISER_BENCH_ELEMENTS")
        .ok()
        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![10, 20, 40, 60, 80, 160, 400]);
    println!("catenary scene, 10 lowest modes; median of {runs} run(s), wall time");
    println!(
        "{:<6} {:>9} {:>10} {:>12} {:>12} {:>14} {:>12}",
        "model", "elements", "unknowns", "statics ms", "modes ms", "stiffness ms", "T1 s"
    );
    for model in ["rod", "cable"] {
        for &n in &meshes {
            let scene = Scene::builtin("catenary")
                .unwrap()
                .with_overrides(&[format!("model={model}"), format!("n_elements={n}")])
                .unwrap();
            let (mut t_statics, mut t_modes, mut t_stiff) = (Vec::new(), Vec::new(), Vec::new());
            let mut unknowns = 0;
            let mut t1 = 0.0;
            for _ in 0..runs {
                let t0 = Instant::now();
                let sim = Simulation::from_scene(&scene).unwrap();
                t_statics.push(t0.elapsed().as_secs_f64() * 1e3);
                let t0 = Instant::now();
                let rep = scene_modes(&scene, 10).unwrap();
                // scene_modes solves the statics again: take them out
                t_modes.push(t0.elapsed().as_secs_f64() * 1e3);
                unknowns = rep.unknowns;
                t1 = rep.modes[0].period;
                let t0 = Instant::now();
                std::hint::black_box(sim.hang_off_stiffness().unwrap());
                t_stiff.push(t0.elapsed().as_secs_f64() * 1e3);
            }
            let ts = median(&mut t_statics);
            let tm = median(&mut t_modes) - ts;
            println!(
                "{:<6} {:>9} {:>10} {:>12.1} {:>12.1} {:>14.2} {:>12.5}",
                model,
                n,
                unknowns,
                ts,
                tm.max(0.0),
                median(&mut t_stiff),
                t1
            );
        }
    }
}
