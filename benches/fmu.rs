//! The FMU through its C ABI (issue 28, "speed at every accuracy"): the
//! catenary with the settings (Ca 1, structural damping 2 ms, static
//! current; heave 2.5 m / 20 s grown over 20 s; 100 s), displacement input
//! only, driven as a master drives it by `benches/fmu_driver.c` (compiled here
//! with `cc`, the built `libriser.so` loaded with dlopen: fmi2SetReal(heave),
//! fmi2DoStep and fmi2GetReal(top_tension) in a loop, no interpreter), at
//! communication steps of 0.05, 0.1 and 0.2 s.
//!
//! Two tables:
//! 1. the cost of a step and of a Newton iteration at 5, 10, 20 and 60
//!    elements, in process (the CLI's loop: `Simulation::advance_to` and
//!    `Simulation::outputs` each step), with the parts one iteration is made
//!    of: a residual, a residual with its tangent, and the outputs;
//! 2. the FMU's real-time factor against its error: the top tension's
//!    minimum, mean and maximum over the steady window (40 to 100 s) at the
//!    communication points, against a converged run (120 elements, dt
//!    0.005 s, in process) read at the same times; the largest relative
//!    error of the three. Beside it the CLI (`riser run --json`,
//!    `solve_wall_time`) on the same numerics and the ratio FMU / CLI (the
//!    runs alternate; the median of the runs' ratios).
//!
//! Medians of RISER_BENCH_RUNS runs (default 5). Wall time: run it on a
//! quiet machine. Needs the release library and CLI built first:
//! `make bench-fmu` (cargo build --release --lib --bin riser, then
//! `cargo bench --bench fmu`). RISER_FMU_LIB and RISER_BIN point elsewhere;
//! RISER_BENCH_ONLY=costs or =fmu runs one table.

use riser::fmi::vars::{GUID, vr_of};
use riser::scene::Scene;
use riser::sim::{Engine, Heave, Simulation};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

mod common;
use common::*;

const SETTINGS: [&str; 3] = ["ca_normal=1", "structural_damping=0.002", "static_current=true"];
const DURATION: f64 = 100.0;
const HEAVE: Heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 20.0 };
/// The CLI's default steady window: the ramp and one period.
const WINDOW: f64 = 40.0;

fn scene(n_el: usize, dt: f64) -> Scene {
    let mut sets: Vec<String> = SETTINGS.iter().map(|s| s.to_string()).collect();
    sets.push(format!("n_elements={n_el}"));
    sets.push(format!("time_step={dt}"));
    Scene::builtin("catenary").unwrap().with_overrides(&sets).unwrap()
}

/// The top tension at every internal step of an in-process run (the CLI's
/// loop), with the solve's wall time, Newton iterations and steps.
fn in_process(n_el: usize, dt: f64) -> (Vec<(f64, f64)>, f64, u64, u64) {
    let mut sim = Simulation::from_scene(&scene(n_el, dt)).unwrap();
    let motion = move |t: f64| HEAVE.at(t);
    sim.start(HEAVE.at(0.0));
    let n = riser::sim::internal_steps(DURATION, dt).unwrap();
    let mut series = Vec::with_capacity(n as usize + 1);
    series.push((0.0, sim.outputs().top_tension));
    let t0 = Instant::now();
    for k in 1..=n {
        sim.advance_to(riser::sim::internal_step_end(0.0, DURATION, dt, k, n), &motion).unwrap();
        let o = sim.outputs();
        series.push((o.time, o.top_tension));
    }
    let wall = t0.elapsed().as_secs_f64();
    (series, wall, sim.state.newton_iterations, sim.state.steps)
}

fn costs(runs: usize) {
    println!("cost of a step and of a Newton iteration, in process (the CLI's loop), median of {runs} runs");
    println!(
        "{:>4} {:>6} {:>9} {:>9} {:>9} {:>11} {:>12} {:>13} {:>10}",
        "el.", "dt s", "solve ms", "Newton/st", "µs/step", "µs/iterat.", "residual µs", "+tangent µs", "outputs µs"
    );
    for (n_el, dt) in [(5, 0.2), (10, 0.1), (20, 0.1), (60, 0.05)] {
        let mut walls = Vec::new();
        let (mut its, mut steps) = (0, 0);
        for _ in 0..runs {
            let (_, w, i, s) = in_process(n_el, dt);
            walls.push(w);
            (its, steps) = (i, s);
        }
        let wall = median(&mut walls);
        // the parts, at the state after 30 s
        let mut sim = Simulation::from_scene(&scene(n_el, dt)).unwrap();
        let motion = move |t: f64| HEAVE.at(t);
        sim.start(HEAVE.at(0.0));
        let n = (30.0 / dt).round() as u64;
        for k in 1..=n {
            sim.advance_to(k as f64 * dt, &motion).unwrap();
        }
        let outputs = time(2000, || {
            black_box(sim.outputs());
        });
        let prev = sim.state.clone();
        let t = prev.time + dt;
        let Engine::Rod(integ) = &mut sim.integrator else { unreachable!("the catenary is a rod") };
        let predicted = integ.begin_step(&prev, dt, motion(t));
        let residual = time(2000, || {
            black_box(integ.step_residual(&prev, &predicted, dt, motion(t), false));
        });
        let tangent = time(500, || {
            black_box(integ.step_residual(&prev, &predicted, dt, motion(t), true));
        });
        println!(
            "{:>4} {:>6} {:>9.1} {:>9.2} {:>9.1} {:>11.1} {:>12.1} {:>13.1} {:>10.1}",
            n_el,
            dt,
            wall * 1e3,
            its as f64 / steps as f64,
            wall / steps as f64 * 1e6,
            wall / its as f64 * 1e6,
            residual,
            tangent,
            outputs
        );
    }
}

/// min, mean, max of the top tension at the times of `series` on the
/// communication grid of `h` in the steady window.
fn window_stats(series: &[(f64, f64)], h: f64) -> [f64; 3] {
    let on_grid = |t: f64| {
        let k = t / h;
        (k - k.round()).abs() < 1e-6
    };
    let v: Vec<f64> = series.iter().filter(|(t, _)| *t >= WINDOW - 1e-9 && on_grid(*t)).map(|p| p.1).collect();
    let min = v.iter().copied().fold(f64::INFINITY, f64::min);
    let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    [min, v.iter().sum::<f64>() / v.len() as f64, max]
}

fn rel_error(a: &[f64; 3], reference: &[f64; 3]) -> f64 {
    (0..3).map(|k| ((a[k] - reference[k]) / reference[k]).abs()).fold(0.0, f64::max)
}

fn compile_driver(root: &Path) -> PathBuf {
    let out = root.join("target").join("fmu_driver");
    let status = Command::new(std::env::var("CC").unwrap_or_else(|_| "cc".into()))
        .args(["-O2", "-o"])
        .arg(&out)
        .arg(root.join("benches").join("fmu_driver.c"))
        .args(["-ldl", "-lm"])
        .status()
        .expect("cannot run cc");
    assert!(status.success(), "cc failed on benches/fmu_driver.c");
    out
}

/// (wall s, window stats) of one run of the FMU through the C driver.
fn fmu_run(driver: &Path, lib: &Path, n_el: usize, dt: f64, h: f64) -> (f64, [f64; 3]) {
    let vr = |name: &str| vr_of(name).unwrap_or_else(|| panic!("no variable {name}"));
    let out = Command::new(driver)
        .arg(lib)
        .arg(GUID)
        .args([vr("heave"), vr("top_tension")].map(|v| v.to_string()))
        .args([h, DURATION, HEAVE.amplitude, HEAVE.period, HEAVE.ramp, WINDOW, 1.0].map(|v| format!("{v}")))
        .arg(format!("i:{}={n_el}", vr("n_elements")))
        .arg(format!("r:{}={dt}", vr("time_step")))
        .arg(format!("r:{}=1", vr("ca_normal")))
        .arg(format!("r:{}=0.002", vr("structural_damping")))
        .arg(format!("b:{}=1", vr("static_current")))
        .output()
        .expect("cannot run the driver");
    assert!(out.status.success(), "driver failed: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let mut walls = Vec::new();
    let mut stats = [0.0; 3];
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let num = |key: &str| f.iter().position(|w| *w == key).and_then(|i| f[i + 1].parse::<f64>().ok()).unwrap();
        walls.push(num("wall_s"));
        stats = [num("min"), num("mean"), num("max")];
    }
    (median(&mut walls), stats)
}

/// `solve_wall_time` of one `riser run --json` on the same numerics.
fn cli_run(bin: &Path, n_el: usize, dt: f64) -> f64 {
    let mut cmd = Command::new(bin);
    cmd.args(["run", "catenary", "--heave", "2.5,20", "--ramp", "20", "--duration", "100", "--json"]);
    for s in SETTINGS.iter().map(|s| s.to_string()).chain([format!("n_elements={n_el}"), format!("time_step={dt}")]) {
        cmd.args(["--set", &s]);
    }
    let out = cmd.output().expect("cannot run the CLI");
    assert!(out.status.success(), "CLI failed: {}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["solve_wall_time"].as_f64().unwrap()
}

fn fmu_table(runs: usize) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib =
        std::env::var("RISER_FMU_LIB").map(PathBuf::from).unwrap_or_else(|_| root.join("target/release/libriser.so"));
    let bin = std::env::var("RISER_BIN").map(PathBuf::from).unwrap_or_else(|_| root.join("target/release/riser"));
    assert!(lib.exists(), "{} not built (make bench-fmu builds it)", lib.display());
    let driver = compile_driver(&root);
    let t0 = Instant::now();
    let (reference, ..) = in_process(120, 0.005);
    println!("reference: 120 elements, dt 0.005 s, in process ({:.1} s)", t0.elapsed().as_secs_f64());
    // how converged the reference is: against 80 elements at 0.0075 s
    let (coarser, ..) = in_process(80, 0.0075);
    println!(
        "  80 elements at dt 0.0075 s differ from it by {:.1e} (window statistics every 0.15 s)",
        rel_error(&window_stats(&coarser, 0.15), &window_stats(&reference, 0.15))
    );
    println!("FMU through the C ABI (benches/fmu_driver.c), displacement only; CLI solve_wall_time; median of {runs}");
    println!(
        "{:>6} {:>4} {:>7} {:>10} {:>9} {:>10} {:>9} {:>9}",
        "comm s", "el.", "dt s", "error", "FMU s", "FMU RTF", "CLI s", "FMU/CLI"
    );
    for h in [0.05, 0.1, 0.2] {
        let reference = window_stats(&reference, h);
        for n_el in [5, 10, 20, 40, 60] {
            for dt in [h, 0.5 * h] {
                // FMU and CLI runs alternate, so that both see the same load
                let (mut fmu, mut cli, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
                let mut stats = [0.0; 3];
                for _ in 0..runs {
                    let (w, s) = fmu_run(&driver, &lib, n_el, dt, h);
                    let c = cli_run(&bin, n_el, dt);
                    (stats, fmu, cli, ratios) =
                        (s, [fmu, vec![w]].concat(), [cli, vec![c]].concat(), [ratios, vec![w / c]].concat());
                }
                let (wall, cli, ratio) = (median(&mut fmu), median(&mut cli), median(&mut ratios));
                println!(
                    "{:>6} {:>4} {:>7} {:>10.2e} {:>9.4} {:>10.0} {:>9.4} {:>9.2}",
                    h,
                    n_el,
                    dt,
                    rel_error(&stats, &reference),
                    wall,
                    DURATION / wall,
                    cli,
                    ratio
                );
            }
        }
    }
}

fn main() {
    let runs: usize = std::env::var("RISER_BENCH_RUNS").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    let only = std::env::var("RISER_BENCH_ONLY").unwrap_or_default();
    if only.is_empty() || only == "costs" {
        costs(runs);
    }
    if only.is_empty() || only == "fmu" {
        fmu_table(runs);
    }
}
