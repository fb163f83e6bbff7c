//! Every parameter at the bounds of its physical range (src/scene/ranges.rs),
//! through the command line: at each bound the default scene (coarsened to 10
//! elements) solves its statics and runs 2 s of ramped heave with finite
//! results; just outside, `riser` refuses the value with a message naming
//! the parameter and its range. (tests/python/test_parameter_ranges.py does
//! the same through the FMU.)

use riser::scene::ranges::{self, RANGES, Range};
use std::process::Command;

fn riser(args: &[String]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

/// Other parameters a bound needs to make a line at all: the anchor within
/// reach of the shortest and the longest line, a buoyancy section to carry
/// the `buoyancy_*` bounds, a line resting on the seabed for its contact law.
fn companions(parameter: &str, value: f64) -> Vec<String> {
    let v = |s: &str| s.to_string();
    match (parameter, value) {
        ("length", l) if l < 10.0 => vec![v("anchor_x=0.6"), v("anchor_z=-0.7")],
        ("length", _) => vec![v("anchor_x=15000"), v("anchor_z=-10000")],
        ("buoyancy_load", _) => vec![v("buoyancy_start=30"), v("buoyancy_end=60")],
        ("buoyancy_start", _) => vec![v("buoyancy_end=60"), v("buoyancy_load=100")],
        ("buoyancy_end", e) if e > 1e3 => {
            vec![v("length=20000"), v("anchor_x=15000"), v("anchor_z=-10000"), v("buoyancy_load=100")]
        }
        ("buoyancy_end", _) => vec![v("buoyancy_load=100")],
        // an anchor 20 km away needs a line as long
        ("anchor_x" | "anchor_y" | "anchor_z", _) => vec![v("length=20000")],
        ("current_top" | "current_bottom", _) => vec![v("static_current=true")],
        // contents need a bore: the catenary's flexible pipe given a wall
        ("internal_fluid_density" | "internal_pressure", _) => vec![v("wall_thickness=0.02")],
        // a seabed at the hang-off's height: the line taut along it
        ("seabed_z", z) if z > -1.0 => vec![v("anchor_x=100.5"), v("anchor_z=0")],
        // the contact law's bounds on a line resting on the seabed
        ("seabed_stiffness" | "seabed_damping" | "seabed_friction", _) => {
            vec![v("anchor_x=85"), v("anchor_z=-40"), v("seabed_z=-40")]
        }
        _ => vec![],
    }
}

/// The parameters that take whole numbers (an FMI Integer).
const WHOLE: [&str; 3] = ["n_elements", "wave_components", "wave_seed"];

fn is_whole(parameter: &str) -> bool {
    WHOLE.contains(&parameter)
}

/// The bound itself for a value inside; the bound moved outwards by a
/// millionth of its size (at least 1e-6) for one outside, by one for a
/// whole number.
fn just_outside(r: &Range, upper: bool) -> f64 {
    if r.parameter.is_some_and(is_whole) {
        return if upper { r.max + 1.0 } else { r.min - 1.0 };
    }
    let step = |b: f64| b.abs().max(1.0) * 1e-6;
    if upper { r.max + step(r.max) } else { r.min - step(r.min) }
}

fn text(parameter: &str, v: f64) -> String {
    if is_whole(parameter) { format!("{}", v as i64) } else { format!("{v:e}") }
}

fn run(parameter: &str, value: f64, extra: &[String]) -> std::process::Output {
    let mut args: Vec<String> = ["run", "catenary", "--set", "n_elements=10"].iter().map(|s| s.to_string()).collect();
    // a bound at the lower end of the length needs its anchor set first
    for c in companions(parameter, value).iter().chain(extra) {
        args.extend(["--set".to_string(), c.clone()]);
    }
    args.extend(["--set".to_string(), format!("{parameter}={}", text(parameter, value))]);
    // a 2 s ramp moves the hang-off within the 2 s run (with `accuracy` set,
    // its pilots run the same 2 s: docs/theory.md §16.12)
    args.extend(["--heave", "0.5,10", "--ramp", "2", "--duration", "2", "--json"].iter().map(|s| s.to_string()));
    riser(&args)
}

/// The bound of the range runs: statics, then 2 s of dynamics, finite.
fn assert_runs(parameter: &str, value: f64, model: &str) {
    let mut extra = vec![format!("model={model}")];
    // the flex joint's stiffness acts on the rod's flex joint (the cable has none)
    if parameter == "flex_joint_stiffness" && model == "rod" {
        extra.push("hang_off_end=flex_joint".to_string());
    }
    let out = run(parameter, value, &extra);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{parameter} = {value} ({model}) at its bound does not run: {stderr}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(json["completed"], true, "{parameter} = {value} ({model}): {json}");
    for k in ["min", "mean", "max"] {
        let t = json["top_tension"][k].as_f64().unwrap_or(f64::NAN);
        assert!(t.is_finite(), "{parameter} = {value} ({model}): top tension {k} {t}");
    }
    let balance = json["energy_balance_relative"].as_f64().unwrap_or(f64::NAN);
    assert!(balance.is_finite() && balance < 1e-3, "{parameter} = {value} ({model}): energy balance {balance}");
}

/// Just outside the range: refused before any statics, naming the
/// parameter and the interval.
fn assert_refused(r: &Range, value: f64) {
    let p = r.parameter.unwrap();
    let out = run(p, value, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{p} = {value} outside its range was accepted");
    for part in [p.to_string(), r.interval(), "is outside".to_string()] {
        assert!(stderr.contains(&part), "message for {p} = {value} does not mention '{part}':\n{stderr}");
    }
}

#[test]
fn every_parameter_runs_at_its_bounds_and_is_refused_just_outside() {
    let mut checked = 0;
    for r in RANGES {
        let Some(p) = r.parameter else { continue };
        for (bound, upper) in [(r.min, false), (r.max, true)] {
            // a section cannot start at the end of the longest line nor end
            // at the hang-off: the scene's check (end > start) refuses those,
            // not the range
            if !(p == "buoyancy_start" && upper || p == "buoyancy_end" && !upper) {
                for model in ["rod", "cable"] {
                    assert_runs(p, bound, model);
                }
            }
            assert_refused(r, just_outside(r, upper));
            checked += 1;
        }
    }
    assert_eq!(checked, 2 * RANGES.iter().filter(|r| r.parameter.is_some()).count());
}

#[test]
fn not_a_number_and_infinity_are_refused_naming_the_parameter() {
    for r in RANGES {
        let Some(p) = r.parameter else { continue };
        if is_whole(p) {
            continue;
        }
        for bad in ["nan", "inf", "-inf"] {
            let args: Vec<String> =
                ["statics", "catenary", "--set", &format!("{p}={bad}")].iter().map(|s| s.to_string()).collect();
            let out = riser(&args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success() && stderr.contains(p) && stderr.contains("not a finite number"), "{stderr}");
        }
    }
}

#[test]
fn scene_files_are_checked_against_the_same_ranges() {
    // a scene file with the length and the time step out of range: both named
    // by their field in the file, with the interval of the table
    let text = riser::scene::Scene::builtin("catenary")
        .unwrap()
        .to_toml()
        .replace("length = 100.0", "length = 1e6")
        .replace("time_step = 0.05", "time_step = 1e-9");
    let e = riser::scene::Scene::from_toml(&text, "t.toml").unwrap_err().to_string();
    for part in [
        "line.length",
        &ranges::of_field("line.length").unwrap().interval(),
        "analysis.time_step",
        &ranges::of_field("analysis.time_step").unwrap().interval(),
    ] {
        assert!(e.contains(part), "'{part}' missing from:\n{e}");
    }
}
