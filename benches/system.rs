//! Lines in parallel (issue 49, evidence 5): a system of three chains and
//! one riser (docs/cases/moored_vessel.toml without its fourth chain: three
//! cables of 35 elements and a rod of 40) under surge 10 m / 100 s with heave
//! 2 m / 12 s, 120 s at 0.05 s, on 1 and on 2 threads
//! ([`SystemRun::for_each_line`], the whole run a line per thread, the
//! dearest first), interleaved; medians, the speed-up, and whether the two
//! give the same bits (they must: no line reads another's state).
//!
//! Run: `cargo bench --bench system` (RISER_BENCH_RUNS sets the runs, default 5).

use riser::math::V3;
use riser::math::rigid::RotationOrder;
use riser::scene::system::SystemScene;
use riser::sim::system_dynamics::{LineRun, SystemRun};
use riser::sim::vessel::VesselMotion;
use std::time::Instant;

mod common;
use common::median;

const SCENE: &str = include_str!("../docs/cases/moored_vessel.toml");

/// Three chains of `n_chain` elements and the riser of 40.
fn system(n_chain: usize) -> SystemScene {
    let mut sys = SystemScene::from_toml(SCENE, "moored_vessel").unwrap();
    for l in sys.lines.iter_mut().filter(|l| l.line_type == "chain") {
        l.n_elements = n_chain;
    }
    // three cables and one rod
    sys.lines.retain(|l| l.name != "chain_bow_starboard");
    sys.points.retain(|p| !p.name.ends_with("bow_starboard"));
    sys
}

fn motion(t: f64) -> VesselMotion {
    let (ws, wh) = (2.0 * std::f64::consts::PI / 100.0, 2.0 * std::f64::consts::PI / 12.0);
    let r = (t / 100.0).min(1.0);
    VesselMotion {
        displacement: V3::new(10.0 * r * (ws * t).sin(), 0.0, 2.0 * r * (wh * t).sin()),
        velocity: V3::new(10.0 * r * ws * (ws * t).cos(), 0.0, 2.0 * r * wh * (wh * t).cos()),
        angles: [0.0; 3],
        body_rates: RotationOrder::Zyx.body_rates([0.0; 3], [0.0; 3]),
    }
}

/// One run on `threads` threads: its wall time (s, the stepping only) and every line's final state's time and top force.
fn one_run(sys: &SystemScene, threads: usize) -> (f64, Vec<(f64, V3)>) {
    let mut run = SystemRun::new(sys).unwrap();
    run.start(&motion(0.0));
    let dt = sys.analysis.time_step;
    let steps = (120.0 / dt).round() as usize;
    let t0 = Instant::now();
    let done = run.for_each_line(threads, &|l: &mut LineRun| {
        for k in 1..=steps {
            l.advance_to(k as f64 * dt, &motion).unwrap();
        }
        (l.sim.state.time, l.sim.outputs().top_force)
    });
    (t0.elapsed().as_secs_f64(), done)
}

fn main() {
    let runs: usize = std::env::var("RISER_BENCH_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("surge 10 m / 100 s and heave 2 m / 12 s, 120 s at 0.05 s, {runs} runs interleaved, {cores} cores");
    // the scene's chains (35 elements: the riser is most of the work) and chains of 100 (OC3's mesh)
    for n_chain in [35, 100] {
        let sys = system(n_chain);
        println!("three chains (cable, {n_chain} elements) and a riser (rod, 40 elements):");
        let (mut one, mut two) = (Vec::new(), Vec::new());
        let mut same = true;
        for _ in 0..runs {
            let (w1, a) = one_run(&sys, 1);
            let (w2, b) = one_run(&sys, 2);
            same &= a == b;
            one.push(w1);
            two.push(w2);
        }
        let (m1, m2) = (median(&mut one), median(&mut two));
        // each line alone: the best two threads can do is the larger of the riser and the chains' sum
        let mut alone = Vec::new();
        for l in &sys.lines {
            let mut only = sys.clone();
            only.lines.retain(|x| x.name == l.name);
            only.points.retain(|p| p.name == l.from || p.name == l.to);
            let mut w: Vec<f64> = (0..runs.min(3)).map(|_| one_run(&only, 1).0).collect();
            alone.push((l.name.clone(), median(&mut w)));
        }
        let total: f64 = alone.iter().map(|a| a.1).sum();
        let riser = alone.iter().map(|a| a.1).fold(0.0, f64::max);
        let bound = total / riser.max(total - riser).max(total / 2.0);
        println!("  {:<10} {:>10} {:>9}", "threads", "wall (s)", "speed-up");
        println!("  {:<10} {:>10.3} {:>9}", 1, m1, "1.00");
        println!("  {:<10} {:>10.3} {:>9.2}   (the lines' balance allows {bound:.2})", 2, m2, m1 / m2);
        println!("  the same bits on 1 and 2 threads: {}", if same { "yes" } else { "NO" });
        for (name, w) in alone {
            println!("    line {name:<22} alone {w:8.3} s");
        }
    }
}
