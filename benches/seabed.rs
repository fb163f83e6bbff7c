//! Seabed benchmark (issue 17, evidence 9): what the seabed costs.
//!
//! 1. `steel_catenary` (400 m, 80 elements, about 110 m on the seabed), rod
//!    and cable, 100 s of heave 3 m / 10 s smoothed over one period, time
//!    step 0.05 s: without friction and with the scene's (0.5 axial, 0.8
//!    lateral), and with the seabed far below the line (−20 km: the contact
//!    check alone) for the line's cost without contact.
//! 2. The catenary scene (no `[seabed]`) as `benches/dynamics.rs` runs it:
//!    compare its wall time with the same bench of a build before the seabed
//!    (docs/performance.md gives both, interleaved).
//!
//! Prints wall time (median of RISER_BENCH_RUNS runs, default 5), Newton
//! iterations per step, split steps and the real-time factor.
//! Run: `cargo bench --bench seabed`.

use riser::scene::Scene;
use riser::sim::{Heave, Simulation};
use std::time::Instant;

fn one_run(scene: &str, sets: &[&str], heave: (f64, f64)) -> (f64, f64, u64) {
    let scene = Scene::builtin(scene).unwrap().with_overrides(sets).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let h = Heave { amplitude: heave.0, period: heave.1, until: None, ramp: heave.1 };
    let motion = move |t: f64| h.at(t);
    sim.start(h.at(0.0));
    let dt = sim.integrator.options().time_step;
    let t0 = Instant::now();
    for k in 1..=(100.0 / dt).round() as u64 {
        sim.advance_to(k as f64 * dt, &motion).unwrap();
    }
    let wall = t0.elapsed().as_secs_f64();
    let st = &sim.state;
    (wall, st.newton_iterations as f64 / st.steps as f64, st.retries)
}

fn main() {
    let runs: usize = std::env::var("RISER_BENCH_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    println!("100 s simulated, dt 0.05 s, heave smoothed over its first period; median of {runs} runs");
    println!("| scene | model | seabed | wall (s) | Newton/step | split steps | RTF |");
    println!("|---|---|---|---|---|---|---|");
    type Case<'a> = (&'a str, &'a str, &'a [&'a str], (f64, f64));
    let cases: [Case; 8] = [
        ("steel_catenary", "friction 0.5 / 0.8 (the scene's)", &[], (3.0, 10.0)),
        ("steel_catenary", "no friction", &["seabed_friction=0"], (3.0, 10.0)),
        ("steel_catenary", "no damping, no friction", &["seabed_friction=0", "seabed_damping=0"], (3.0, 10.0)),
        (
            "steel_catenary",
            "20 km below (no contact)",
            &["seabed_z=-20000", "anchor_z=-200", "length=420"],
            (3.0, 10.0),
        ),
        ("catenary", "none", &[], (2.5, 20.0)),
        ("catenary", "20 km below (no contact)", &["seabed_z=-20000"], (2.5, 20.0)),
        ("catenary", "none", &["model=cable"], (2.5, 20.0)),
        ("catenary", "20 km below (no contact)", &["model=cable", "seabed_z=-20000"], (2.5, 20.0)),
    ];
    for model in ["rod", "cable"] {
        for (scene, label, sets, heave) in cases {
            let on_model = sets.iter().any(|s| s.starts_with("model="));
            if scene == "catenary" && (on_model != (model == "cable")) {
                continue;
            }
            let m = format!("model={model}");
            let mut all: Vec<&str> = vec![m.as_str()];
            all.extend(sets.iter().filter(|s| !s.starts_with("model=")));
            let mut walls = Vec::new();
            let (mut its, mut splits) = (0.0, 0);
            for _ in 0..runs {
                let (w, i, s) = one_run(scene, &all, heave);
                walls.push(w);
                its = i;
                splits = s;
            }
            walls.sort_by(f64::total_cmp);
            let w = walls[walls.len() / 2];
            println!("| {scene} | {model} | {label} | {w:.3} | {its:.2} | {splits} | {:.1} |", 100.0 / w);
        }
    }
}
