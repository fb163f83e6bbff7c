//! The monolithic reference of two-way coupling (issue 53; docs/theory.md
//! §7.9): a heave–pitch body at the hang-off integrated inside the line's own
//! step, for riser_tools.coupling_mono (the two-way runs' reference).
//!
//!     cargo run --profile fasttest --example monolithic_body -- SCENE H DURATION \
//!         MASS INERTIA C33 C55 B33 B55 FORCE MOMENT PERIOD RAMP [NAME=VALUE...]
//!
//! SCENE a built-in scene with the overrides NAME=VALUE (`hang_off_x=30`
//! puts the hang-off 30 m forward of the body's reference point); H the
//! step, DURATION the run (s); the body's mass and pitch inertia with their
//! added mass (kg, kg m²; inertia 0: heave only), its stiffness, damping
//! and excitation amplitudes in heave and pitch, the excitation's period
//! and ramp (s). Prints CSV at every step: t, heave, pitch, their rates,
//! the top tension and force (N), the line's work on the body and the
//! energy balance of line and body (J).
use riser::scene::Scene;
use riser::sim::Simulation;
use riser::sim::monolithic::{BodyRun, HeavePitchBody};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 13 {
        eprintln!(
            "usage: monolithic_body SCENE H DURATION MASS INERTIA C33 C55 B33 B55 FORCE MOMENT PERIOD RAMP [NAME=VALUE...]"
        );
        std::process::exit(2);
    }
    let num = |s: &str| s.parse::<f64>().unwrap_or_else(|e| panic!("{s}: {e}"));
    let v: Vec<f64> = args[1..13].iter().map(|s| num(s)).collect();
    let scene = Scene::builtin(&args[0]).expect("a built-in scene").with_overrides(&args[13..]).unwrap();
    let body = HeavePitchBody {
        mass: v[2],
        inertia: v[3],
        stiffness: [v[4], v[5]],
        damping: [v[6], v[7]],
        excitation: [v[8], v[9]],
        period: v[10],
        ramp: v[11],
    };
    let (h, duration) = (v[0], v[1]);
    let mut run = BodyRun::new(Simulation::from_scene(&scene).unwrap(), body);
    println!("t,heave,pitch,heave_velocity,pitch_velocity,top_tension,top_force_x,top_force_z,work_line,balance");
    let n = (duration / h).round() as usize;
    for k in 0..=n {
        if k > 0 {
            run.step(h).unwrap_or_else(|e| panic!("step {k}: {e}"));
        }
        let o = run.sim.outputs();
        println!(
            "{},{},{},{},{},{},{},{},{},{}",
            k as f64 * h,
            run.q[0],
            run.q[1],
            run.q_dot[0],
            run.q_dot[1],
            o.top_tension,
            o.top_force.x,
            o.top_force.z,
            run.work_line,
            run.energy_balance_residual()
        );
    }
    eprintln!("{} corrections in {n} steps", run.iterations);
}
