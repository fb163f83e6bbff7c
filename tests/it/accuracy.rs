//! `accuracy`, measured on the user's scene (issue 51, docs/theory.md
//! §16.12): with a target set, riser's pilots choose the numerics, and the
//! run at them is within the target of the converged reference of
//! `riser-tools accuracy` (committed in docs/accuracy_runs.csv with the
//! script that made it, at 0.0125 s and the study's finest meshes: finer
//! than any pilot here); the estimate it reports is within a factor 3 of
//! the error measured against that reference; the numerics the user sets
//! win; a quantity the scene does not have is refused naming why; without
//! `accuracy` nothing changes.
//!
//! The error, as in the study: `riser run SCENE --heave A,T --duration 4T`
//! (ramp one period, steady window 2T to 4T), e = max(|min − min_ref|,
//! |mean − mean_ref|, |max − max_ref|) / max_ref of the steady window's top
//! tension (accuracy_quantity = top_tension).

use std::process::Command;

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

/// The reference's steady top tension [min, mean, max] (N) of a case.
fn reference(case: &str) -> [f64; 3] {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/accuracy_runs.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        if f[col("case")] == case && f[col("kind")] == "reference" && f[col("completed")] == "True" {
            return ["tt_min", "tt_mean", "tt_max"].map(|k| f[col(k)].parse().unwrap());
        }
    }
    panic!("no reference for {case} in docs/accuracy_runs.csv: run riser-tools accuracy");
}

/// The steady window's error: the largest of the min, mean and max top
/// tension's differences from the reference's `r`, over its max.
fn rel_error(t: &[f64], r: &[f64]) -> f64 {
    (0..3).map(|k| (t[k] - r[k]).abs()).fold(0.0, f64::max) / r[2]
}

fn run_json(args: &[&str]) -> serde_json::Value {
    let out = riser(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("JSON")
}

fn steady_top_tension(v: &serde_json::Value) -> Vec<f64> {
    v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The study's case: heave `amplitude` m at `period` s for four periods.
fn case_run(scene: &str, amplitude: f64, period: f64, sets: &[&str]) -> serde_json::Value {
    let heave = format!("{amplitude},{period}");
    let duration = format!("{}", 4.0 * period);
    let mut args = vec!["run", scene, "--heave", &heave, "--duration", &duration, "--json"];
    for s in sets {
        args.extend(["--set", s]);
    }
    run_json(&args)
}

/// A target met against the reference, the estimate within a factor 3 of
/// the error measured, and the numerics run the ones reported.
/// The pilots within 20 % of a 3-hour run at the chosen numerics (issue
/// 51's aim), counted in element-steps.
fn meets(scene: &str, amplitude: f64, period: f64, target: f64) {
    let t = format!("accuracy={target}");
    let v = case_run(scene, amplitude, period, &[&t]);
    meets_run(&v, scene, target, true);
}

/// The pilots' work (element-steps, those reused counted once) over that of
/// a 3-hour run at the chosen numerics (docs/theory.md §16.13).
fn pilots_share_of_3_hours(a: &serde_json::Value) -> f64 {
    let end = a["pilot_window"][1].as_f64().unwrap();
    let pilots: f64 = a["pilots"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["reused"] == false)
        .map(|p| p["n_elements"].as_f64().unwrap() * (end / p["time_step"].as_f64().unwrap()).round())
        .sum();
    let chosen = &a["chosen"];
    pilots / (chosen["n_elements"].as_f64().unwrap() * 10800.0 / chosen["time_step"].as_f64().unwrap())
}

/// [`meets`] of the run `v` of the study's `case` (`share_checked`: the
/// pilots within 20 % of a 3-hour run at the choice).
fn meets_run(v: &serde_json::Value, case: &str, target: f64, share_checked: bool) {
    let scene = case;
    let a = &v["accuracy"];
    let measured = rel_error(&steady_top_tension(v), &reference(scene));
    let estimate = a["estimate"].as_f64().unwrap();
    assert!(measured <= target, "{scene} at {target:e}: error {measured:.3e} against the reference: {a}");
    assert!(
        estimate >= measured / 3.0,
        "{scene} at {target:e}: under-estimate {estimate:.3e}, measured {measured:.3e}"
    );
    assert_eq!(a["met"], true, "{a}");
    assert_eq!(v["n_elements"], a["chosen"]["n_elements"]);
    assert_eq!(v["time_step"], a["chosen"]["time_step"]);
    assert_eq!(v["newton_tolerance"], a["chosen"]["newton_tolerance"]);
    // the pilots are reported: five a round (an earlier round's reused
    // among them) and up to two fourth levels (docs/theory.md §16.15), each
    // with its numerics and values
    let pilots = a["pilots"].as_array().unwrap();
    let rounds = pilots.iter().map(|p| p["round"].as_u64().unwrap()).max().unwrap_or(0);
    for r in 1..=rounds {
        let k = pilots.iter().filter(|p| p["round"] == r).count();
        assert!((5..=7).contains(&k), "round {r}: {k} pilots: {a}");
    }
    assert!(pilots.iter().all(|p| p["values"]["top_tension_max"].as_f64().is_some_and(f64::is_finite)));
    // no mesh and step run twice: an earlier round's pilot is reused
    let run: Vec<(u64, u64)> = pilots
        .iter()
        .filter(|p| p["reused"] == false)
        .map(|p| (p["n_elements"].as_u64().unwrap(), p["time_step"].as_f64().unwrap().to_bits()))
        .collect();
    assert!(run.iter().enumerate().all(|(i, x)| !run[..i].contains(x)), "a pilot run twice: {a}");
    // the estimate within 3x, then the share
    assert!(estimate <= 3.0 * measured, "{scene} at {target:e}: estimate {estimate:.3e}, measured {measured:.3e}");
    let share = pilots_share_of_3_hours(a);
    assert!(!share_checked || share <= 0.2, "{scene} at {target:e}: the pilots {share:.3} of a 3-hour run: {a}");
}

/// The catenary at 1e-3: the target met, the estimate within a factor 3,
/// and the pilots within 20 % of a 3-hour run at the choice (docs/theory.md
/// §16.16: from a first candidate a quarter of the scene's numerics, 16
/// elements at 0.2 s, 7 pilots, 4.8 %; from half of them the first round
/// alone was 25 % of a 3-hour run at the 8 elements at 0.336 s it chose,
/// 29.7 % with the second).
#[test]
fn the_catenary_meets_its_target_and_its_estimate_is_within_a_factor_3() {
    meets("catenary", 2.5, 20.0, 1e-3);
}

/// The steel catenary at 1e-3: the target met, the estimate within a factor
/// 3 (docs/theory.md §16.16: at 40 elements and 0.1 s the minimum's mesh
/// and step errors had opposite signs, +18.6 and −12.4 N estimated, and
/// their added bounds made the estimate 3.5 times the error; (16.23) takes
/// the larger where the signs differ).
#[test]
fn the_steel_catenary_meets_its_target_and_its_estimate_is_within_a_factor_3() {
    meets("steel_catenary", 2.5, 15.0, 1e-3);
}

/// The study's jumper_jonswap: the jumper in a JONSWAP sea (H_s 6 m, T_p
/// 10 s, 50 components, seed 1) over 20 to 220 s. Its pilots span the
/// window's 20 T_p (docs/theory.md §16.13: over 3 T_p the estimate was
/// 0.27 times the error); the target met, the estimate within a factor 3.
/// (Its pilots are 0.18 of a 3-hour run at the choice since docs/theory.md §16.16, 16 elements at
/// 0.4 s; 0.45 before, 0.22 before the fourth level: the 220 s they run, not asserted.)
#[test]
fn in_an_irregular_sea_the_pilots_span_the_window_and_the_estimate_is_within_a_factor_3() {
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    let mut args = vec!["run", jumper, "--duration", "220", "--window", "20,220", "--json"];
    for s in ["wave_kind=jonswap", "wave_hs=6", "wave_tp=10", "wave_components=50", "wave_seed=1", "accuracy=1e-2"] {
        args.extend(["--set", s]);
    }
    let v = run_json(&args);
    assert_eq!(v["accuracy"]["pilot_window"], serde_json::json!([20.0, 220.0]), "{}", v["accuracy"]);
    meets_run(&v, "jumper_jonswap", 1e-2, false);
}

/// The numerics set by `--set` win over the choice: the mesh the user
/// gives is run, the pilots choose the step about it, and the estimate of
/// what is run is within a factor 3 of its error against the reference.
#[test]
fn the_numerics_you_set_win_and_their_error_is_estimated() {
    let v = case_run("catenary", 2.5, 20.0, &["accuracy=1e-3", "n_elements=8"]);
    let a = &v["accuracy"];
    assert_eq!(v["n_elements"], 8, "{a}");
    assert_eq!(a["set_by_user"]["n_elements"], true);
    assert_eq!(a["set_by_user"]["time_step"], false);
    // every pilot at the user's mesh or finer (the mesh triplet n, 2n, 4n)
    for p in a["pilots"].as_array().unwrap() {
        assert!([8, 16, 32].contains(&p["n_elements"].as_u64().unwrap()), "{p}");
    }
    let measured = rel_error(&steady_top_tension(&v), &reference("catenary"));
    let estimate = a["estimate"].as_f64().unwrap();
    assert!(
        estimate <= 3.0 * measured && estimate >= measured / 3.0,
        "estimate {estimate:.3e}, measured {measured:.3e}"
    );
    // the target met or not, said either way
    assert_eq!(a["met"], estimate <= 1e-3);
}

#[test]
fn without_accuracy_nothing_changes() {
    let v = case_run("catenary", 2.5, 20.0, &[]);
    assert_eq!(v["accuracy"], serde_json::Value::Null);
    assert_eq!(v["n_elements"], 60);
    assert_eq!(v["time_step"], 0.05);
}

/// A target on a quantity the scene has none of: refused before any pilot,
/// naming the quantity and why.
#[test]
fn a_quantity_the_scene_does_not_have_is_refused_naming_why() {
    for (q, why) in [
        ("touchdown", "no seabed"),
        ("stress_range", "no stresses"),
        ("fatigue", "riser run --fatigue"),
        ("bogus", "not one of top_tension, stress_range, touchdown, fatigue, all"),
    ] {
        let set = format!("accuracy_quantity={q}");
        let out = riser(&[
            "run",
            "catenary",
            "--heave",
            "2.5,20",
            "--duration",
            "80",
            "--set",
            "accuracy=1e-2",
            "--set",
            &set,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(why), "{q}: {err}");
        assert!(!err.contains("round 1 of pilots"), "{q}: refused after pilots: {err}");
    }
}

/// `riser statics` with `accuracy` chooses for the design motion (heave
/// 2.5 m at 10 s unless the scene's accuracy_motion_* say otherwise), as
/// the FMU does, and reports it.
#[test]
fn statics_chooses_for_the_design_motion_and_reports_it() {
    let v = run_json(&["statics", "catenary", "--set", "accuracy=1e-2", "--json"]);
    let a = &v["accuracy"];
    assert_eq!(v["n_elements"], a["chosen"]["n_elements"], "{a}");
    assert_eq!(a["quantity"], "top_tension");
    assert!(a["estimate"].as_f64().unwrap() <= 1e-2, "{a}");
    // the pilots' window: from two periods (the ramp and one period) for three
    assert_eq!(a["pilot_window"], serde_json::json!([20.0, 50.0]), "{a}");
}
