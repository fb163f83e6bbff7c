//! The line's response at the hang-off to the C2 bumps the FMU's input path is
//! made of (docs/theory.md §7.3): for each communication step h, the change of
//! `top_force_z` at the communication points t_c + k h when the hang-off's
//! path carries one quintic Hermite bump of value, slope or curvature at t_c
//! (heave only), per unit of the bump (N/m). The coupling analysis of
//! `riser-tools coupling` reads these impulse responses (CSV on stdout):
//!
//!     cargo run --release --example hang_off_response -- SCENE T_CENTRE T_MEMORY AMPLITUDE [NAME=VALUE...] H...
//!
//! The internal step is min(0.05 s, h), as in the co-simulation studies.
use riser::math::V3;
use riser::model::HangOff;
use riser::scene::Scene;
use riser::sim::Simulation;

/// Quintic Hermite bases of docs/theory.md (7.2) at σ ∈ [0, 1] and their σ-derivatives.
fn hermite(s: f64) -> [[f64; 3]; 2] {
    let (s2, s3, s4, s5) = (s * s, s * s * s, s.powi(4), s.powi(5));
    [
        [
            1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5,
            s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5,
            0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        ],
        [
            -30.0 * s2 + 60.0 * s3 - 30.0 * s4,
            1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4,
            s - 4.5 * s2 + 6.0 * s3 - 2.5 * s4,
        ],
    ]
}

/// The bump of kind j (0 value, 1 h·slope, 2 h²·curvature) of size a centred
/// at tc on the steps [tc − h, tc] and [tc, tc + h]: (value, velocity) at t.
fn bump(j: usize, a: f64, tc: f64, h: f64, t: f64) -> (f64, f64) {
    let x = (t - tc) / h;
    if x <= -1.0 || x >= 1.0 {
        return (0.0, 0.0);
    }
    // right of the centre: H_j(σ), σ = x; left: the mirror H_j(1 − σ) with the odd one negated
    let (b, sign_v, sign_d) =
        if x >= 0.0 { (hermite(x), 1.0, 1.0) } else { (hermite(-x), if j == 1 { -1.0 } else { 1.0 }, -1.0) };
    (a * sign_v * b[0][j], a * sign_v * sign_d * b[1][j] / h)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 6 {
        eprintln!("usage: hang_off_response SCENE T_CENTRE T_MEMORY AMPLITUDE H...");
        std::process::exit(2);
    }
    let scene = Scene::builtin(&args[1]).unwrap_or_else(|| Scene::load(&args[1]).expect("scene"));
    // linearised about the line at rest in the current (its state once a run's start has died
    // out); arguments NAME=VALUE after AMPLITUDE override the scene as `--set` does
    let mut sets = vec!["static_current=true".to_string()];
    sets.extend(args[5..].iter().filter(|a| a.contains('=')).cloned());
    let scene = scene.with_overrides(&sets).expect("overrides");
    let (tc, memory, a): (f64, f64, f64) =
        (args[2].parse().unwrap(), args[3].parse().unwrap(), args[4].parse().unwrap());
    println!("h,kind,k,t,response");
    for hs in args[5..].iter().filter(|a| !a.contains('=')) {
        let h: f64 = hs.parse().unwrap();
        let mut sc = scene.clone();
        sc.analysis.time_step = h.min(0.05);
        let n = (memory / h).round() as usize;
        let run = |j: Option<usize>| -> Vec<f64> {
            let mut sim = Simulation::from_scene(&sc).expect("statics");
            sim.start(HangOff::default());
            let motion = |t: f64| {
                let (z, vz) = j.map_or((0.0, 0.0), |j| bump(j, a, tc, h, t));
                HangOff::translation(V3::new(0.0, 0.0, z), V3::new(0.0, 0.0, vz))
            };
            let dt = sc.analysis.time_step;
            let mut out = Vec::new();
            // communication steps from 0 up to tc + memory, internal steps within
            let steps = ((tc + memory) / h).round() as usize;
            let kc = (tc / h).round() as usize;
            for k in 0..steps {
                let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
                let m = riser::sim::internal_steps(h, dt).unwrap();
                for i in 1..=m {
                    sim.advance_to(riser::sim::internal_step_end(t0, h, dt, i, m), &motion).expect("step");
                }
                let _ = t1;
                if k + 1 >= kc && out.len() <= n {
                    out.push(sim.outputs().top_force.z);
                }
            }
            out
        };
        let base = run(None);
        eprintln!(
            "baseline top_force_z: first {:.6e} last {:.6e} min {:.6e} max {:.6e}",
            base[0],
            base[base.len() - 1],
            base.iter().cloned().fold(f64::INFINITY, f64::min),
            base.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        );
        for j in 0..3 {
            let r = run(Some(j));
            for (k, (x, b)) in r.iter().zip(&base).enumerate() {
                println!("{h},{j},{k},{},{:.9e}", tc + k as f64 * h, (x - b) / a);
            }
        }
        // the static stiffness S_zz at the start, for the lumped model
        let sim = Simulation::from_scene(&sc).expect("statics");
        let s = sim.hang_off_stiffness().expect("stiffness");
        // kind −1: the static stiffness S_zz (the change of the support's force per metre)
        println!("{h},-1,0,0,{:.9e}", s[(2, 2)]);
    }
}
