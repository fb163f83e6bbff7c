//! The accuracy knob (issue 28, docs/theory.md §16): a run of each built-in
//! scene with `accuracy` set has a top-tension error at or below it against
//! the converged reference of `riser-tools accuracy` (committed in
//! docs/accuracy_runs.csv with the script that made it); what the error model
//! does not cover is refused naming why; the numerics set by the user win;
//! without `accuracy` nothing changes.
//!
//! The error, as in the study: `riser run SCENE --heave A,T --duration 4T`
//! (ramp one period, steady window 2T to 4T), e = max(|min − min_ref|,
//! |mean − mean_ref|, |max − max_ref|) / max_ref of the steady window's top
//! tension.

use std::process::Command;

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

/// The motion of each built-in scene's calibration case (heave amplitude m,
/// period s), as in python/riser_tools/src/riser_tools/studies/accuracy.py.
const CASES: [(&str, f64, f64); 3] = [("catenary", 2.5, 20.0), ("lazy_wave", 2.5, 30.0), ("steel_catenary", 2.5, 15.0)];
const TARGETS: [f64; 3] = [1e-2, 1e-3, 1e-4];

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

/// The steady window's error (16.1): the largest of the min, mean and max
/// top tension's differences from the reference's `r`, over its max.
fn rel_error(t: &[f64], r: &[f64]) -> f64 {
    (0..3).map(|k| (t[k] - r[k]).abs()).fold(0.0, f64::max) / r[2]
}

/// `base` with each of `sets` given as `--set NAME=VALUE`.
fn with_sets<'a>(base: &[&'a str], sets: &[&'a str]) -> Vec<&'a str> {
    let mut args = base.to_vec();
    for s in sets {
        args.extend(["--set", s]);
    }
    args
}

/// `riser` with `args`, each of `sets` given as `--set NAME=VALUE`.
fn riser_with(args: &[&str], sets: &[&str]) -> std::process::Output {
    riser(&with_sets(args, sets))
}

fn run_json(args: &[&str]) -> serde_json::Value {
    let out = riser(args);
    assert!(out.status.success(), "riser {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The steady window's top tension [min, mean, max] (N) of a successful
/// `riser run --json`.
fn steady_top_tension(out: &std::process::Output) -> Vec<f64> {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

/// Runs `scene` with each target and checks its error against the reference.
fn reaches_its_targets(scene: &str) {
    let (_, amplitude, period) = *CASES.iter().find(|c| c.0 == scene).unwrap();
    reaches(scene, scene, amplitude, period, &TARGETS);
}

/// Runs `scene` heaved by `amplitude` m at `period` s with each of `targets`
/// and checks its error (16.1) against the reference of the study's `case`.
fn reaches(case: &str, scene: &str, amplitude: f64, period: f64, targets: &[f64]) {
    let refs = reference(case);
    for &target in targets {
        let (heave, duration, acc) =
            (format!("{amplitude},{period}"), format!("{}", 4.0 * period), format!("{target}"));
        let v = run_json(&[
            "run",
            scene,
            "--heave",
            &heave,
            "--duration",
            &duration,
            "--set",
            &format!("accuracy={acc}"),
            "--json",
        ]);
        let tt: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let e = rel_error(&tt, &refs);
        // the run's numerics are the choice it reports
        let c = &v["accuracy"];
        assert_eq!(c["n_elements"], v["n_elements"], "{scene}");
        assert_eq!(c["time_step"], v["time_step"], "{scene}");
        assert_eq!(c["newton_tolerance"], v["newton_tolerance"], "{scene}");
        assert!(
            e <= target,
            "{scene}, accuracy {target:e}: error {e:.2e} with {} elements, dt {} s (predicted {})",
            v["n_elements"],
            v["time_step"],
            c["predicted_error"]
        );
    }
}

#[test]
fn every_built_in_scene_has_a_calibration_case() {
    for (name, _) in riser::scene::BUILTIN {
        assert!(CASES.iter().any(|c| c.0 == name), "built-in scene {name} has no case in tests/accuracy.rs");
    }
}

#[test]
fn catenary_reaches_each_accuracy_target() {
    reaches_its_targets("catenary");
}

#[test]
fn lazy_wave_reaches_each_accuracy_target() {
    reaches_its_targets("lazy_wave");
}

#[test]
fn steel_catenary_reaches_each_accuracy_target() {
    reaches_its_targets("steel_catenary");
}

/// Between the three targets (docs/theory.md §16.3, "Between the targets"):
/// the catenary heaved 2.5 m at 10 s, the design motion, chose 10 elements at
/// 0.02 s for 2e-4 and 0.015 s for 1.2e-4 before the mesh term of the motion
/// and reached 2.0e-4 and 1.5e-4, above the targets; the lazy wave at 30 s
/// chose 30 elements, which kink its sag bend in the statics, for 5e-4 and
/// reached 1.0e-2. Each now within its target against the study's reference
/// (docs/accuracy_runs.csv, catenary_T10 and lazy_wave).
#[test]
fn targets_between_the_three_are_reached() {
    reaches("catenary_T10", "catenary", 2.5, 10.0, &[2e-4, 1.2e-4]);
    reaches("lazy_wave", "lazy_wave", 2.5, 30.0, &[5e-4]);
}

/// The jumper heaved 2.5 m at 10 s, the design motion (docs/theory.md §16.10,
/// "The jumper at 10 s"). After the ramp the line rings at its 3.2 Hz mode,
/// with a time constant of about 6 s at any numerics, so that its default
/// window (20 to 40 s) holds what is left of it: 1.6e-4 of the top tension at
/// 160 elements and 0.00625 s. (a) That window is not the steady response at
/// 1e-4: 80 elements at 0.0125 s differ there from the study's reference of
/// the window 40 to 60 s by more than 1e-4 (2.0e-4 measured), and in that
/// window by less than 1e-5 (2.1e-6: the mesh is no part of it). (b) The
/// knob's 1e-4 run over the default window says so (its steadiness warning's
/// limit is the target). (c) In the window 40 to 60 s, where the study
/// measures this case, the knob's choices keep 1e-4, 1.2e-4 and 2e-4 against
/// the study's reference (320 elements at 0.0125 s, itself within 7.7e-6 of
/// 0.003125 s there): 2.5e-5, 3.4e-5 and 5.8e-5 measured; in the default
/// window they measured 1.45e-4 against 0.003125 s at 1e-4.
#[test]
fn the_jumper_at_10_s_rings_from_its_start_and_is_within_its_targets_past_it() {
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    let refs = reference("lowe_langley_jumper_T10");
    let e = |tt: &[f64]| rel_error(tt, &refs);
    let run = |duration: &str, window: &str, sets: &[&str]| {
        riser_with(&["run", jumper, "--heave", "2.5,10", "--duration", duration, "--window", window, "--json"], sets)
    };
    let fine = ["n_elements=80", "time_step=0.0125", "newton_tolerance=1e-10"];
    let (early, late) = std::thread::scope(|s| {
        let early = s.spawn(|| steady_top_tension(&run("40", "20,40", &fine)));
        let late = steady_top_tension(&run("60", "40,60", &fine));
        (early.join().unwrap(), late)
    });
    assert!(e(&early) > 1e-4, "the default window's ringing: {:.2e}", e(&early));
    assert!(e(&late) < 1e-5, "80 elements at 0.0125 s from 40 to 60 s: {:.2e}", e(&late));

    let out = run("40", "20,40", &["accuracy=1e-4"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("the steady window is not steady at 1e-4"), "{err}");

    for target in [1e-4, 1.2e-4, 2e-4] {
        let tt = steady_top_tension(&run("60", "40,60", &[&format!("accuracy={target}")]));
        assert!(e(&tt) <= target, "accuracy {target:e}: error {:.2e} from 40 to 60 s", e(&tt));
    }
}

/// Translations of different periods (docs/theory.md §16.10, "Translations
/// of different periods"): the jumper heaved 2 m at 10 s and surged 5 m at
/// 40 s, a wave-frequency heave with a slow surge. Taken before as one
/// harmonic of the resultant amplitude at the shortest period (5.385 m at
/// 10 s, 0.217 g), it was refused; chosen for the resultants of its
/// velocities, accelerations (0.0815 g) and jerks, it is taken, the CLI naming
/// the translations, and its 1e-3 and 1e-4 (10 elements at 0.04 s, 24 at
/// 0.02 s) keep their targets over one period of the surge after the ramp
/// and one more (80 to 120 s) against 80 elements at 0.0125 s (8.8e-6 from
/// 160 at 0.00625 s there): 6.8e-5 and 3.7e-5 measured against the finer.
#[test]
fn translations_of_different_periods_keep_their_targets() {
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    let run = |sets: &[&str]| {
        riser_with(&["run", jumper, "--heave", "2,10", "--surge", "5,40", "--duration", "120", "--json"], sets)
    };
    let (refs, coarse) = std::thread::scope(|s| {
        let refs =
            s.spawn(|| steady_top_tension(&run(&["n_elements=80", "time_step=0.0125", "newton_tolerance=1e-10"])));
        let coarse: Vec<_> = [1e-3, 1e-4].map(|t| (t, run(&[&format!("accuracy={t}")]))).into();
        (refs.join().unwrap(), coarse)
    });
    for (target, out) in coarse {
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("for translations of resultant amplitude 5.385 m, the shortest of period 10 s"), "{err}");
        let tt = steady_top_tension(&out);
        let e = rel_error(&tt, &refs);
        assert!(e <= target, "accuracy {target:e}: error {e:.2e} from 80 to 120 s");
    }
    // the one harmonic of the resultant amplitude at the shortest period: beyond the study's acceleration
    let out = riser(&["run", jumper, "--heave", "5.385,10", "--duration", "1", "--set", "accuracy=1e-3"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("= 0.2168 g"), "{err}");
}

/// A jumper heavier than the study's (docs/theory.md §16.10, "With a sag
/// bend"): at 220 kg/m for 165 (w/(m g) 0.440 for 0.254, the bound's line).
/// Heaved 2.5 m at 10 s it rings from its start as the study's does, by
/// 2.6e-4 of its top tension in the default window (20 to 40 s), where the
/// knob's 1e-4 errs 2.6e-4; past it, in the window 80 to 100 s, the knob's
/// 1e-3 and 1e-4 (12 elements at 0.05 s, 30 at 0.02 s) keep their targets
/// against 80 elements at 0.0125 s (3.0e-6 from 160 at 0.003125 s there):
/// 3.4e-5 and 7.5e-6 measured against the finer. Heaved 10 m at 27 s, the
/// motion at which 240 kg/m leaves its period, it is steady in its default
/// window (54 to 108 s; 6.3e-6 from the window 8T to 10T), where the knob's
/// 1e-3 and 1e-4 (12 elements at 0.15 s, 20 at 0.03 s) err 1.5e-4 and
/// 1.9e-5 against 160 elements at 0.003125 s, which 80 at 0.0125 s meet to
/// 1.0e-5. 180 to 200 kg/m were refused before, on probes in the default
/// window.
#[test]
fn a_heavier_jumper_keeps_its_targets_past_its_start_s_ringing() {
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    // (heave, duration, window)
    let motions = [("2.5,10", "100", "80,100"), ("10,27", "108", "54,108")];
    let run = |(heave, duration, window): (&str, &str, &str), sets: &[&str]| {
        let base = ["run", jumper, "--heave", heave, "--duration", duration, "--window", window, "--json"];
        steady_top_tension(&riser_with(&with_sets(&base, &["mass_per_length=220"]), sets))
    };
    for motion in motions {
        let (refs, coarse) = std::thread::scope(|s| {
            let refs = s.spawn(|| run(motion, &["n_elements=80", "time_step=0.0125", "newton_tolerance=1e-10"]));
            let coarse: Vec<_> = [1e-3, 1e-4].map(|t| (t, run(motion, &[&format!("accuracy={t}")]))).into();
            (refs.join().unwrap(), coarse)
        });
        for (target, tt) in coarse {
            let e = rel_error(&tt, &refs);
            assert!(e <= target, "heave {}, accuracy {target:e}: error {e:.2e} over {} s", motion.0, motion.2);
        }
    }
}

#[test]
fn the_choice_is_printed_and_explicit_numerics_win() {
    let base = ["run", "catenary", "--heave", "2.5,20", "--duration", "0.4", "--json", "--set", "accuracy=1e-3"];
    let chosen = run_json(&base);
    let n = chosen["n_elements"].as_u64().unwrap();
    let dt = chosen["time_step"].as_f64().unwrap();
    assert_eq!(chosen["accuracy"]["target"].as_f64(), Some(1e-3));
    // the target's square, at most 1e-6 (src/sim/accuracy.rs newton_tolerance_for, TOLERANCE_RANGE):
    // the ceiling from 1e-3 up, the rule below it
    assert_eq!(chosen["newton_tolerance"].as_f64(), Some(1e-6));
    let fine =
        run_json(&["run", "catenary", "--heave", "2.5,20", "--duration", "0.4", "--json", "--set", "accuracy=2e-4"]);
    let tol = fine["newton_tolerance"].as_f64().unwrap();
    assert!((tol / 4e-8 - 1.0).abs() < 1e-12, "{tol}");
    // an explicit n_elements wins; the step is still chosen
    let mut args = base.to_vec();
    args.extend(["--set", "n_elements=33"]);
    let v = run_json(&args);
    assert_eq!(v["n_elements"].as_u64(), Some(33));
    assert_eq!(v["accuracy"]["set_by_user"]["n_elements"], true);
    assert_eq!(v["accuracy"]["set_by_user"]["time_step"], false);
    // both set: both kept
    args.extend(["--set", "time_step=0.07"]);
    let v = run_json(&args);
    assert_eq!((v["n_elements"].as_u64(), v["time_step"].as_f64()), (Some(33), Some(0.07)));
    assert!(n != 33 || dt != 0.07);
    // the text summary names the choice
    let out = riser(&base[..base.len() - 3].iter().copied().chain(["--set", "accuracy=1e-3"]).collect::<Vec<_>>());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(text.contains(&format!("accuracy 1e-3: chose n_elements {n}, time_step {dt} s")), "{text}");
    // statics chooses too
    let s = run_json(&["statics", "lazy_wave", "--set", "accuracy=1e-4", "--json"]);
    assert_eq!(s["accuracy"]["n_elements"], s["n_elements"]);
}

#[test]
fn the_knob_s_newton_tolerance_moves_the_error_by_a_few_percent_of_the_target() {
    // docs/theory.md §16.8, "The Newton tolerance again": the knob's tolerance is the target's square
    // (1e-4 of the target at 1e-4, as before; 1e-3 of it at 1e-3, where it was 1e-4 of it); on the case
    // where it matters most (the lazy wave heaved at 10 s: 80 elements at 0.02 s for 1e-4, 40 at 0.05 s
    // for 1e-3) the window against the same numerics at a hundredth of that tolerance moves within a
    // tenth of the target, which the safety factor's margin (1 - 1/1.5) covers (at 1e-3 ε, 1e-7, the
    // 1e-4 choice moved 5.5e-5: why the rule is the square)
    for (target, n) in [("1e-4", 80), ("1e-3", 40)] {
        let set = format!("accuracy={target}");
        let base = ["run", "lazy_wave", "--heave", "2.5,10", "--duration", "40", "--json", "--set", &set];
        let knob = run_json(&base);
        assert_eq!(knob["n_elements"].as_u64(), Some(n));
        let eps: f64 = target.parse().unwrap();
        assert_eq!(knob["newton_tolerance"].as_f64(), Some(eps * eps));
        let tight_tol = format!("newton_tolerance={:e}", eps * eps / 100.0);
        let tight = run_json(&[&base[..], &["--set", &tight_tol]].concat());
        let (a, b) = (&knob["steady"]["top_tension"], &tight["steady"]["top_tension"]);
        let max = b[2].as_f64().unwrap();
        let moved = (0..3).map(|i| (a[i].as_f64().unwrap() - b[i].as_f64().unwrap()).abs() / max).fold(0.0, f64::max);
        eprintln!("at {target} the knob's tolerance moves the window by {moved:.1e} of its max");
        assert!(moved > 0.0, "the tolerance should change something: {moved}");
        assert!(moved <= 0.1 * eps, "{target}: {moved}");
    }
}

#[test]
fn without_accuracy_nothing_changes() {
    let a = run_json(&["run", "lazy_wave", "--heave", "2.5,30", "--duration", "1", "--json"]);
    let b = run_json(&["run", "lazy_wave", "--heave", "2.5,30", "--duration", "1", "--json", "--set", "accuracy=0"]);
    assert!(a["accuracy"].is_null() && b["accuracy"].is_null());
    for key in ["n_elements", "time_step", "newton_tolerance", "top_tension", "steps", "newton_iterations"] {
        assert_eq!(a[key], b[key], "{key}");
    }
    let scene = riser::scene::Scene::builtin("steel_catenary").unwrap();
    let (same, choice) = riser::sim::accuracy::apply(scene.clone(), None, Default::default()).unwrap();
    assert!(choice.is_none() && same == scene);
}

#[test]
fn what_the_model_does_not_cover_is_refused_naming_why() {
    let cases: [(&[&str], &str); 20] = [
        (&["--set", "model=cable"], "does not cover the cable model"),
        (&["--set", "rho_infinity=1"], "does not cover rho_infinity = 1"),
        // the catenary's low point (z = -70.4 m) is 3.2 m above a seabed at -73.6 m: a heave of 2.5 m may touch it
        (&["--set", "seabed_z=-73.6", "--heave", "2.5,20"], "may touch the seabed only during the motion"),
        (
            &["--set", "wave_kind=pierson_moskowitz", "--set", "wave_hs=4", "--set", "wave_tp=12"],
            "does not cover waves of kind",
        ),
        (
            &[
                "--set",
                "wave_kind=airy",
                "--set",
                "wave_height=2",
                "--set",
                "wave_period=12",
                "--set",
                "wave_direction=45",
            ],
            "does not cover waves travelling 45 deg from +x",
        ),
        (
            &["--set", "wave_kind=airy", "--set", "wave_height=2", "--set", "wave_period=8"],
            "period 8.000 s is shorter than the 10 s",
        ),
        (&["--set", "wave_kind=airy", "--set", "wave_height=12", "--set", "wave_period=12"], "higher than the 10 m"),
        (
            &["--set", "wave_kind=jonswap", "--set", "wave_hs=8", "--set", "wave_tp=12"],
            "Hs 8.000 m is higher than the 6 m",
        ),
        (
            &["--set", "wave_kind=airy", "--set", "wave_height=2", "--set", "wave_period=12", "--set", "accuracy=1e-4"],
            "does not cover accuracy = 1e-4 in waves",
        ),
        (&["--set", "hang_off_end=clamped"], "does not cover a clamped hang-off"),
        (&["--set", "hang_off_x=5"], "does not cover a hang-off offset"),
        // beyond the study's parameters, where a probe missed (docs/theory.md 16.10)
        (&["--set", "ca_normal=2"], "does not cover an added-mass coefficient ca_normal = 2"),
        (&["--set", "structural_damping=0.01"], "does not cover structural_damping = 0.01"),
        (&["--set", "accuracy=5e-5"], "below 1e-4"),
        (&["--heave", "1,5"], "period 5 s is shorter than the 10 s"),
        // the catenary's anchor is 92.2 m from its hang-off, its length 100 m: a 10 m heave takes it taut
        (&["--heave", "10,20"], "may take the line taut"),
        // 5 m at 10 s (sway alone): 0.201 g, twice
        // the study's largest (docs/theory.md 16.9)
        (&["--sway", "5,10"], "accelerates the hang-off by A omega^2/g = 0.2012 g, beyond the 0.101 g"),
        // heave and surge of 2.5 m at 10 s each: their resultant, 3.536 m, at 10 s is 0.1423 g (each alone
        // is the study's 0.1006)
        (
            &["--heave", "2.5,10", "--surge", "2.5,10"],
            "amplitude 3.536 m at period 10 s accelerates the hang-off by A omega^2/g = 0.1423 g",
        ),
        // the paper's abrupt start, with the current grown as the study's: the velocity jump rings the
        // axial modes (docs/theory.md 16.10; the jumper's window 40-60 s from 66.3 to 194.4 kN as refined)
        (&["--heave", "2.5,10", "--ramp", "0", "--set", "current_ramp=10"], "does not cover an abrupt start"),
        // a ramp shorter than the study's one period of the slowest motion rings them too (the jumper's
        // window 40-60 s at --ramp 2: 66.3 kN on the knob's numerics, 120.8 on 96 elements at 0.00625 s)
        (
            &["--heave", "2.5,10", "--ramp", "2"],
            "does not cover a ramp of 2 s, shorter than the slowest motion's period",
        ),
    ];
    for (extra, message) in cases {
        let mut args = vec!["run", "catenary", "--duration", "1", "--set", "accuracy=1e-3"];
        args.extend_from_slice(extra);
        let out = riser(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} ran");
        assert!(err.contains(message), "{args:?}: {err}");
    }
}

/// The still-water choices of the knob for the design motion (2.5 m at 10 s,
/// what `riser statics` and the FMU choose for), as `riser statics SCENE --set
/// accuracy=…` reports them: scene, target, n_elements, time_step,
/// newton_tolerance, predicted error. The wave terms leave them unchanged.
/// Since C_d and C_t were refitted on the points at or above the smallest
/// target with the window's time mean (docs/theory.md 16.2: 0.05 and 0.3
/// before) some are coarser: before, the catenary 30 at 0.0125 s for 1e-4,
/// the lazy wave 40 at 0.04 s and 120 at 0.0125 s, the steel catenary 30 at
/// 0.075 s and 320 at 0.0125 s, the jumper 16 at 0.04 s and 50 at 0.0125 s.
/// The steel catenary's are coarser again since the seabed contact's rule
/// splits at the crossings (docs/theory.md (9.7), C_c and C_c2 refitted):
/// 30 at 0.1 s, 120 at 0.05 s and 240 at 0.015 s before. The Newton
/// tolerance was 1e-4 of the target from 2026-11-27 (1e-5 before: 1e-8 and
/// 1e-9 at 1e-3 and 1e-4; docs/theory.md 16.3, "The Newton tolerance").
/// Since the current grows over `current_ramp` and the step term took the
/// hang-off's velocity and the order 2 (docs/theory.md §16.7) the steps at
/// 1e-3 and 1e-4 are longer:
/// before, the catenary 10 at 0.05 s and 20 at 0.015 s, the lazy wave 80 at
/// 0.0125 s, the steel catenary 80 at 0.015 s, the jumper 12 at 0.04 s and
/// 30 at 0.0125 s. Since the two mesh terms of the bend add in quadrature and
/// the touchdown's term grows with the motion (docs/theory.md §16.8) the
/// predictions moved by up to 10 % (the lazy wave's at 1e-2) and the jumper's 1e-4 is 24 elements at
/// 0.015 s (30 at 0.02 s before). The Newton tolerance is the target's
/// square since, at most 1e-6 (1e-6 at 1e-2 and 1e-3, where it was 1e-7).
/// On the seabed no element is longer than 1.2 bending lengths since
/// (docs/theory.md §16.9): the steel catenary's 1e-2 is 20 elements (10 at
/// 0.1 s, 6.5e-3 predicted, before).
const STILL_WATER_CHOICES: [(&str, f64, usize, f64, f64, f64); 12] = [
    ("catenary", 1e-2, 10, 0.1, 1e-6, 0.0009736596449860005),
    ("catenary", 1e-3, 10, 0.075, 1e-6, 0.0006019719032809062),
    ("catenary", 1e-4, 16, 0.02, 1e-8, 6.42121777230943e-05),
    ("lazy_wave", 1e-2, 20, 0.1, 1e-6, 0.0025450353044249767),
    ("lazy_wave", 1e-3, 40, 0.05, 1e-6, 0.00042121789984047816),
    ("lazy_wave", 1e-4, 80, 0.02, 1e-8, 5.9987960117259724e-05),
    ("steel_catenary", 1e-2, 20, 0.1, 1e-6, 0.0022445414625302676),
    ("steel_catenary", 1e-3, 40, 0.05, 1e-6, 0.0004888842045395281),
    ("steel_catenary", 1e-4, 80, 0.02, 1e-8, 5.1392584000594525e-05),
    ("docs/cases/lowe_langley_jumper.toml", 1e-2, 10, 0.1, 1e-6, 0.0015023657855729156),
    ("docs/cases/lowe_langley_jumper.toml", 1e-3, 12, 0.05, 1e-6, 0.0005889510897326895),
    ("docs/cases/lowe_langley_jumper.toml", 1e-4, 24, 0.015, 1e-8, 6.592488173539103e-05),
];

#[test]
fn the_still_water_choice_is_unchanged_by_the_wave_terms() {
    use riser::sim::accuracy::{Excitation, choose};
    for (scene, target, n, dt, tol, predicted) in STILL_WATER_CHOICES {
        let path = format!("{}/{scene}", env!("CARGO_MANIFEST_DIR"));
        let mut s = riser::scene::Scene::load(if scene.ends_with(".toml") { &path } else { scene }).unwrap();
        s.analysis.accuracy = target;
        for waves in [false, true] {
            // an explicit still sea (`kind = "none"`) is still water
            if waves {
                s = s.with_overrides(&["wave_kind=none"]).unwrap();
            }
            let c = choose(&s, None, Default::default()).unwrap();
            assert!(c.scales.waves.is_none());
            assert_eq!(
                (c.n_elements, c.time_step, c.newton_tolerance, c.predicted().to_bits()),
                (n, dt, tol, predicted.to_bits()),
                "{scene} at {target:e}"
            );
        }
        // a motion given: the heave's own period and amplitude, as before
        let c = choose(&s, Some(Excitation::harmonic(2.5, 10.0)), Default::default()).unwrap();
        assert_eq!((c.n_elements, c.time_step), (n, dt), "{scene} at {target:e} with heave 2.5 m / 10 s");
    }
}

/// The scenes in waves of the study (python/riser_tools/src/riser_tools/studies/accuracy.py's
/// WAVE_CASES): case, scene, heave amplitude (m, 0: none) and period s,
/// the sea's --set, duration s, steady window s.
type WaveCase = (&'static str, &'static str, f64, f64, &'static [&'static str], f64, (f64, f64));
const JONSWAP: &[&str] = &["wave_kind=jonswap", "wave_hs=6", "wave_tp=10", "wave_components=50", "wave_seed=1"];
const WAVE_CASES: [WaveCase; 2] = [
    ("catenary_jonswap_heave", "catenary", 2.5, 10.0, JONSWAP, 220.0, (20.0, 220.0)),
    (
        "jumper_airy",
        "docs/cases/lowe_langley_jumper.toml",
        0.0,
        10.0,
        &["wave_kind=airy", "wave_height=10", "wave_period=10"],
        40.0,
        (20.0, 40.0),
    ),
];

/// Runs a case in waves at each target against its reference.
fn reaches_its_targets_in_waves(case: &str, targets: &[f64]) {
    let (_, scene, amplitude, period, sea, duration, (t0, t1)) = *WAVE_CASES.iter().find(|c| c.0 == case).unwrap();
    let refs = reference(case);
    let path = format!("{}/{scene}", env!("CARGO_MANIFEST_DIR"));
    let scene = if scene.ends_with(".toml") { path.as_str() } else { scene };
    for &target in targets {
        let (duration, window, heave, acc) = (
            format!("{duration}"),
            format!("{t0},{t1}"),
            format!("{amplitude},{period}"),
            format!("accuracy={target}"),
        );
        let mut args = vec!["run", scene, "--duration", &duration, "--window", &window, "--json", "--set", &acc];
        if amplitude > 0.0 {
            args.extend(["--heave", &heave]);
        }
        for s in sea {
            args.extend(["--set", s]);
        }
        let v = run_json(&args);
        let tt: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let e = rel_error(&tt, &refs);
        let c = &v["accuracy"];
        assert!(c["wave_number"].as_f64().is_some(), "{case}: the choice has the sea's scales");
        assert_eq!(c["n_elements"], v["n_elements"], "{case}");
        assert_eq!(c["time_step"], v["time_step"], "{case}");
        assert!(
            e <= target,
            "{case}, accuracy {target:e}: error {e:.2e} with {} elements, dt {} s (predicted {})",
            v["n_elements"],
            v["time_step"],
            c["predicted_error"]
        );
    }
}

#[test]
fn a_catenary_in_an_irregular_sea_and_heave_reaches_its_targets() {
    reaches_its_targets_in_waves("catenary_jonswap_heave", &[1e-2, 1e-3]);
}

#[test]
fn the_jumper_in_a_regular_wave_reaches_its_targets() {
    reaches_its_targets_in_waves("jumper_airy", &[1e-2, 1e-3]);
}

/// The choice's `cost` of a run's `--json`.
fn cost_of(c: &serde_json::Value) -> f64 {
    riser::sim::accuracy::cost(c["n_elements"].as_u64().unwrap() as usize, c["time_step"].as_f64().unwrap())
}

/// The design motion (docs/theory.md §16.2): `riser statics` (as the FMU)
/// chooses for `accuracy_motion_amplitude` and `accuracy_motion_period`,
/// 2.5 m and 10 s unset, and reads them back; a smaller amplitude or a
/// longer period never costs more. The catenary's case moves 2.5 m at 20 s:
/// the choice for that design motion is cheaper than the default one's and
/// reaches its target against the case's reference, and a run with the heave
/// takes the design motion set over its own.
#[test]
fn the_design_motion_given_sets_the_choice() {
    let statics = |sets: &[&str]| {
        run_json(&with_sets(&["statics", "catenary", "--json", "--set", "accuracy=1e-3"], sets))["accuracy"].clone()
    };
    let motion =
        |c: &serde_json::Value| (c["motion_amplitude"].as_f64().unwrap(), c["motion_period"].as_f64().unwrap());
    let design = statics(&[]);
    assert_eq!(motion(&design), (2.5, 10.0));
    for (sets, expected) in [
        (&["accuracy_motion_amplitude=1"][..], (1.0, 10.0)),
        (&["accuracy_motion_period=20"][..], (2.5, 20.0)),
        (&["accuracy_motion_amplitude=0.5", "accuracy_motion_period=30"][..], (0.5, 30.0)),
    ] {
        let c = statics(sets);
        assert_eq!(motion(&c), expected, "{sets:?}");
        assert!(cost_of(&c) <= cost_of(&design), "{sets:?}: {c} against {design}");
    }
    let at_20 = statics(&["accuracy_motion_period=20"]);
    assert!(cost_of(&at_20) < cost_of(&design), "{at_20} against {design}");
    // the case's motion: its choice, pinned as a master would set it, reaches 1e-3
    let refs = reference("catenary");
    let error_of = |v: &serde_json::Value| {
        let tt: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        rel_error(&tt, &refs)
    };
    let (n, dt, tol) = (
        format!("n_elements={}", at_20["n_elements"]),
        format!("time_step={}", at_20["time_step"]),
        format!("newton_tolerance={}", at_20["newton_tolerance"]),
    );
    let heaved = ["run", "catenary", "--heave", "2.5,20", "--duration", "80", "--json"];
    let v = run_json(&with_sets(&heaved, &[&n, &dt, &tol]));
    assert!(error_of(&v) <= 1e-3, "the design motion's choice {at_20}: error {:.2e}", error_of(&v));
    // a run with its heave and the design period set: the design motion wins
    let v = run_json(&with_sets(&heaved, &["accuracy=1e-3", "accuracy_motion_period=10"]));
    assert_eq!(motion(&v["accuracy"]), (2.5, 10.0));
    assert_eq!((&v["n_elements"], &v["time_step"]), (&design["n_elements"], &design["time_step"]));
    assert!(error_of(&v) <= 1e-3, "error {:.2e}", error_of(&v));
}

/// `riser run` without a motion chooses for the hang-off held still: no step
/// term (docs/theory.md §16.2). With the current grown over its 10 s
/// (docs/theory.md §16.7) the window holds no jolt and the mesh terms bound
/// the still runs: the catenary at 1e-2, 1e-3 and 1e-4 reaches each against
/// the still case's reference (docs/accuracy.md, catenary_still), at 1e-2
/// for no more than the design motion's choice. The current in full from
/// t = 0 (`current_ramp = 0`) is refused, naming it, but not where it is in
/// the statics or has no speed; a design motion given is chosen for, as
/// `riser statics` chooses.
#[test]
fn a_run_without_motion_chooses_for_the_hang_off_held_still() {
    let still = ["run", "catenary", "--duration", "40", "--window", "20,40", "--json"];
    let refs = reference("catenary_still");
    for (target, set) in [(1e-2, "accuracy=1e-2"), (1e-3, "accuracy=1e-3"), (1e-4, "accuracy=1e-4")] {
        let v = run_json(&with_sets(&still, &[set]));
        let c = &v["accuracy"];
        assert_eq!(c["motion_amplitude"].as_f64(), Some(0.0));
        assert_eq!(c["predicted_time_error"].as_f64(), Some(0.0));
        if target == 1e-2 {
            let design = run_json(&["statics", "catenary", "--json", "--set", "accuracy=1e-2"])["accuracy"].clone();
            assert!(cost_of(c) <= cost_of(&design), "{c} against {design}");
        }
        let tt: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let e = rel_error(&tt, &refs);
        assert!(e <= target, "{target:e}: error {e:.2e}");
    }
    let out = riser(&with_sets(&still, &["accuracy=1e-3", "current_ramp=0"]));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("a current in full from t = 0 (current_ramp = 0"), "{err}");
    // no jolt where the current is in the statics or has no speed
    for sets in
        [&["current_ramp=0", "static_current=true"][..], &["current_ramp=0", "current_top=0", "current_bottom=0"]]
    {
        let args = with_sets(&["statics", "catenary", "--json"], &[&["accuracy=1e-2"][..], sets].concat());
        assert!(riser(&args).status.success(), "{sets:?}");
    }
    // a design motion given: chosen for it, as riser statics
    let short = ["run", "catenary", "--duration", "0.4", "--json"];
    let args = with_sets(&short, &["accuracy=1e-3", "accuracy_motion_amplitude=2.5"]);
    let v = run_json(&args);
    assert_eq!(
        (v["accuracy"]["motion_amplitude"].as_f64(), v["accuracy"]["motion_period"].as_f64()),
        (Some(2.5), Some(10.0))
    );
}

/// A line resting on its seabed held still (docs/theory.md §16.8: the
/// touchdown's term is then its still part A_s alone): the steel catenary
/// without a current, whose run is its statics, within each target of the
/// converged statics (320 elements; 10, 12 and 40 elements chosen, 1.7e-5,
/// 1.4e-4 and 1.1e-5), and without the high-frequency warning its
/// round-off once raised (src/sim/design.rs NEGLIGIBLE_DISSIPATION).
#[test]
fn a_line_resting_on_its_seabed_held_still_is_within_each_target() {
    let converged =
        run_json(&["statics", "steel_catenary", "--json", "--set", "n_elements=320"])["top_tension"].as_f64().unwrap();
    for target in ["1e-2", "1e-3", "1e-4"] {
        let args = ["run", "steel_catenary", "--duration", "20", "--json", "--set", &format!("accuracy={target}")];
        let out = riser(&args);
        assert!(out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("high-frequency oscillation"), "{target}: {err}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let tt = v["steady"]["top_tension"].as_array().unwrap();
        let e = tt.iter().map(|x| (x.as_f64().unwrap() - converged).abs()).fold(0.0, f64::max) / converged;
        assert!(e <= target.parse::<f64>().unwrap(), "{target}: error {e:.2e}");
    }
}

/// A design motion outside what the model covers, or no motion at all, is
/// refused naming the parameter (`--set`; the scene's `[analysis]` keys are
/// checked the same way).
#[test]
fn a_bad_design_motion_is_refused_naming_it() {
    for (set, message) in [
        ("accuracy_motion_amplitude=-1", "accuracy_motion_amplitude: -1 m is outside [0, 100] m"),
        ("accuracy_motion_amplitude=nan", "accuracy_motion_amplitude: NaN is not a finite number"),
        ("accuracy_motion_period=-10", "accuracy_motion_period: -10 s is outside"),
        ("accuracy_motion_amplitude=20", "amplitude 20 m (accuracy_motion_amplitude) is larger than the 10 m"),
        ("accuracy_motion_period=5", "period 5 s (accuracy_motion_period) is shorter than the 10 s"),
    ] {
        let out = riser(&["statics", "catenary", "--set", "accuracy=1e-3", "--set", set]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(message), "{set}: {err}");
    }
    let toml = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/catenary.toml"))
        .unwrap()
        .replace("[analysis]", "[analysis]\naccuracy_motion_period = -3.0");
    let dir = std::env::temp_dir().join(format!("riser-accmotion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad_motion.toml");
    std::fs::write(&path, toml).unwrap();
    let out = riser(&["statics", path.to_str().unwrap(), "--set", "accuracy=1e-3"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("analysis.accuracy_motion_period"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The knob's coverage of compression (docs/theory.md §16.9): the steel
/// catenary heaved 10 m at 20 s, within MAX_AMPLITUDE and MIN_SLACK, goes
/// into compression at its touchdown far beyond the −7.5 % of its static top
/// tension that the study's runs reached; its run at 1e-2 warns of it, and
/// the warning is true: its steady top tension misses a converged run (80
/// elements at 0.025 s, within 2.4e-4 of 160 at 0.0125 s) by more than the
/// target (3.8e-2 on its 20 elements; 0.14 on the 12 it took before the
/// seabed's element cap, MAX_TOUCHDOWN_ELEMENT). The study's own least (the lazy wave heaved at 10 s on the
/// 20 elements the knob takes for 1e-2, −1.62 kN) is not warned of; a line
/// in compression in its statics beyond it (the lazy wave with heavier
/// modules and its anchor closer, −11 %) is refused.
#[test]
fn a_line_pushed_into_compression_beyond_the_calibration_is_warned_or_refused() {
    let window = ["--duration", "80", "--window", "40,80", "--json"];
    let run = |sets: &[&str]| {
        run_json(&with_sets(&[&["run", "steel_catenary", "--heave", "10,20"][..], &window].concat(), sets))
    };
    let knob = run(&["accuracy=1e-2"]);
    let converged = run(&["n_elements=80", "time_step=0.025"]);
    let warnings = knob["steady"]["warnings"].as_array().unwrap();
    assert!(
        warnings.iter().any(|w| w.as_str().unwrap().contains("beyond the 8 % the error model was calibrated on")),
        "{warnings:?}"
    );
    let tension = |v: &serde_json::Value| -> Vec<f64> {
        v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
    };
    let (a, b) = (tension(&knob), tension(&converged));
    let e = rel_error(&a, &b);
    assert!(e > 1e-2, "the knob's run errs {e:.2e}: the warning would not be needed");

    let lazy =
        run_json(&["run", "lazy_wave", "--heave", "2.5,10", "--duration", "40", "--set", "accuracy=1e-2", "--json"]);
    assert!(lazy["steady"]["min_tension"].as_f64().unwrap() < -1.5e3, "the study's least compression");
    let warnings = lazy["steady"]["warnings"].as_array().unwrap();
    assert!(!warnings.iter().any(|w| w.as_str().unwrap().contains("calibrated on")), "{warnings:?}");

    let out = riser(&[
        "run",
        "lazy_wave",
        "--duration",
        "1",
        "--set",
        "accuracy=1e-3",
        "--set",
        "buoyancy_load=1000",
        "--set",
        "anchor_x=30",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("does not cover a line in compression"), "{err}");
}

/// The knob at 1e-2 on `riser run ARGS` with `sets` (each a `--set`), and
/// the same run with `n_elements` pinned to `coarse`, beyond a cap (whose
/// warning it checks): the knob's n_elements and both runs' errors (16.1)
/// of the steady top tension against 80 elements at 0.025 s.
fn knob_and_coarse_against_80_elements(args: &[&str], sets: &[&str], coarse: usize) -> (u64, f64, f64) {
    // the run's n_elements, steady top tension and stderr
    let run = |more: &[&str]| {
        let mut all: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        all.push("--json".into());
        for s in sets.iter().chain(more) {
            all.extend(["--set".to_string(), s.to_string()]);
        }
        let out = riser(&all.iter().map(|a| a.as_str()).collect::<Vec<_>>());
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "riser {all:?}: {err}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let t: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        (v["n_elements"].as_u64().unwrap(), t, err)
    };
    let (_, reference, _) = run(&["n_elements=80", "time_step=0.025"]);
    let error = |t: &[f64]| rel_error(t, &reference);
    let (n, knob, _) = run(&["accuracy=1e-2"]);
    let (_, pinned, err) = run(&["accuracy=1e-2", &format!("n_elements={coarse}")]);
    // the pinned mesh is beyond the cap: the knob says its prediction does not hold
    assert!(err.contains("its prediction does not hold there"), "{err}");
    (n, error(&knob), error(&pinned))
}

/// In waves no mesh coarser than h κ = 1 is taken (docs/theory.md §16.9,
/// MAX_WAVE_BEND): the lazy wave in a 6 m regular wave at 10 s at 1e-2
/// took its 10 elements (h κ = 1.64, the model's 6.5e-3) and erred 1.27e-2;
/// it takes 20 now (h κ = 0.82), within the target against 80 elements at
/// 0.025 s (within 3e-6 of 160 at 0.0125 s); the 10 elements, pinned, still
/// miss it.
#[test]
fn in_waves_the_lazy_wave_takes_no_mesh_coarser_than_the_wave_study_s() {
    let (n, knob, coarse) = knob_and_coarse_against_80_elements(
        &["run", "lazy_wave", "--duration", "40", "--window", "20,40"],
        &["wave_kind=airy", "wave_height=6", "wave_period=10"],
        10,
    );
    assert_eq!(n, 20);
    assert!(knob <= 1e-2, "{knob:.2e}");
    assert!(coarse > 1e-2, "the 10 elements reach the target: {coarse:.2e}");
}

/// On the seabed no element longer than 1.2 bending lengths, the study's
/// coarsest there (docs/theory.md §16.9, MAX_TOUCHDOWN_ELEMENT): the steel
/// catenary heaved 2.5 m at 15 s in a current of 1.0 m/s at the top to 0.3
/// m/s at the bottom, which moves its touchdown, at 1e-2: its 10 elements
/// (h/λ = 2.35), which the knob took before, err 1.9e-2; it takes 20 (1.17)
/// now, within the target against 80 elements at 0.025 s. A bending length
/// the ladder's 800 elements cannot follow so is refused, naming it.
#[test]
fn on_the_seabed_no_element_is_longer_than_the_study_s_coarsest() {
    let (n, knob, coarse) = knob_and_coarse_against_80_elements(
        &["run", "steel_catenary", "--heave", "2.5,15", "--duration", "60"],
        &["current_top=1.0", "current_bottom=0.3"],
        10,
    );
    assert_eq!(n, 20);
    assert!(knob <= 1e-2, "{knob:.2e}");
    assert!(coarse > 1e-2, "the 10 elements reach the target: {coarse:.2e}");
    // EI a ten-thousandth: λ = 0.17 m needs 1985 elements, beyond the ladder's 800: refused naming it
    let out = riser(&[
        "run",
        "steel_catenary",
        "--duration",
        "1",
        "--set",
        "bending_stiffness=2.71e3",
        "--set",
        "accuracy=1e-2",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("touchdown bending length") && err.contains("1985 elements"),
        "{err}"
    );
}

/// A uniform line is covered within the weight in water over the weight in
/// air, w/(m g), that the study's line of its kind and its probed variants
/// kept their targets at (docs/theory.md §16.10): hanging free to its anchor
/// 0.64–0.73 (the catenary 0.643), on its seabed 0.62–0.70 (the steel
/// catenary 0.630), with a sag bend below its anchor 0.15–0.441 (the jumper
/// 0.254); hanging free, up to the study's drag of its motion over its
/// weight, F_m = ½ ρ C_d D (A ω)² / w = 0.168 (the catenary heaved 2.5 m at
/// 10 s). The catenary at 140 kg/m (0.421) is refused naming its ratio, and
/// the numerics the knob took for it before (10 elements at 0.075 s,
/// tolerance 1e-6) miss 1e-3 against 80 elements at 0.025 s (2.5e-3 against
/// 160 at 0.0125 s); at 400 kg/m (0.798), beyond the heaviest probed, it is
/// refused too; at 60 kg/m it floats, and is refused as such. With C_d 1.2
/// for 0.6 (F_m 0.337), in a 0.5 m/s current (in its own 0.8 m/s the current
/// load ratio, 0.088, is refused first), it is refused naming F_m, the amplitude covered at
/// its period and the period from which its own is covered (14.08 s), which
/// separates refused and accepted. The steel catenary at 140 kg/m (0.571)
/// is refused, at its own 162.1 (0.630) taken; the jumper at 240 kg/m
/// (0.487), whose response heaved 10 m at 27 s leaves its period, refused,
/// at 220 kg/m (0.440, the heaviest probed within its targets past its
/// start's ringing; 180 kg/m was refused before those probes) taken.
#[test]
fn a_line_beyond_the_weight_in_water_or_the_motion_s_drag_of_the_study_s_is_refused() {
    let scene = |sets: &[&str], heave: &str| {
        riser_with(&["run", "catenary", "--heave", heave, "--duration", "40", "--json"], sets)
    };
    // the ratios in closed form: the catenary's water 1025 kg/m³, g 9.81 m/s², D 0.3172 m
    let (rho, d, g) = (1025.0, 0.3172, 9.81);
    let weight = |m: f64| (m - rho * std::f64::consts::PI / 4.0 * d * d) * g;
    let drag = |cd: f64, a: f64, t: f64| 0.5 * rho * cd * d * (a * 2.0 * std::f64::consts::PI / t).powi(2);
    assert!((weight(226.7) / (226.7 * g) - 0.643).abs() < 5e-4, "the study's catenary");
    assert!((drag(0.6, 2.5, 10.0) / weight(226.7) - 0.168).abs() < 5e-4, "the study's catenary");

    let out = scene(&["mass_per_length=140", "accuracy=1e-3"], "2.5,10");
    let err = String::from_utf8_lossy(&out.stderr);
    let ratio = weight(140.0) / (140.0 * g);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("lighter in water") && err.contains(&format!("is {ratio:.3} of its weight in air")), "{err}");
    let err = String::from_utf8_lossy(&scene(&["mass_per_length=400", "accuracy=1e-3"], "2.5,10").stderr).to_string();
    let ratio = weight(400.0) / (400.0 * g);
    assert!(err.contains("heavier in water") && err.contains(&format!("is {ratio:.3} of its weight in air")), "{err}");
    let err = String::from_utf8_lossy(&scene(&["mass_per_length=60", "accuracy=1e-3"], "2.5,10").stderr).to_string();
    assert!(err.contains("does not cover a line that floats"), "{err}");

    // the knob's numerics before the refusal miss 1e-3
    let tension = |out: std::process::Output| steady_top_tension(&out);
    let light = ["mass_per_length=140", "newton_tolerance=1e-6"];
    let before = tension(scene(&[light[0], light[1], "n_elements=10", "time_step=0.075"], "2.5,10"));
    let converged = tension(scene(&[light[0], "n_elements=80", "time_step=0.025"], "2.5,10"));
    let e = rel_error(&before, &converged);
    assert!(e > 1e-3, "the 10 elements at 0.075 s reach 1e-3 ({e:.2e}): the refusal would not be needed");

    // the motion's drag: C_d 1.2 doubles F_m, refused at 10 s, covered from the period named
    // (in a 0.5 m/s current: in its own 0.8 m/s, C_d 1.2 makes F_c 0.088, above the current's bound)
    let slow = ["current_top=0.5", "current_bottom=0.5"];
    let out = scene(&["cd_normal=1.2", slow[0], slow[1], "accuracy=1e-3"], "2.5,10");
    let err = String::from_utf8_lossy(&out.stderr);
    let dm = drag(1.2, 2.5, 10.0) / weight(226.7);
    let t_from = 10.0 * (dm / 0.17).sqrt();
    assert!(!out.status.success(), "{err}");
    assert!(err.contains(&format!("is {dm:.3} of the line's weight in water")), "{err}");
    assert!(err.contains(&format!("from a period of {:.2} s", (t_from * 100.0).ceil() / 100.0)), "{err}");
    let a_max = 2.5 * (0.17 / dm).sqrt();
    assert!(err.contains(&format!("up to {:.3} m", (a_max * 1e3).floor() / 1e3)), "{err}");
    let refused =
        |t: &str| !scene(&["cd_normal=1.2", slow[0], slow[1], "accuracy=1e-3"], &format!("2.5,{t}")).status.success();
    assert!(refused("14.0") && !refused("14.1"));

    // on the seabed: the steel catenary's water and diameter, 0.2731 m
    let steel = |m: &str| {
        let mass = format!("mass_per_length={m}");
        riser(&["statics", "steel_catenary", "--set", "accuracy=1e-3", "--set", &mass])
    };
    let ratio = 1.0 - rho * std::f64::consts::PI / 4.0 * 0.2731f64.powi(2) / 140.0;
    let err = String::from_utf8_lossy(&steel("140").stderr).to_string();
    assert!(
        err.contains(&format!("is {ratio:.3} of its weight in air")) && err.contains("resting on its seabed"),
        "{err}"
    );
    assert!(steel("162.1").status.success());

    // with a sag bend: the jumper made heavier, 240 kg/m for 165 (its water 1000 kg/m³, D 0.396 m)
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    let out = riser(&["statics", jumper, "--set", "accuracy=1e-4", "--set", "mass_per_length=240"]);
    let ratio = 1.0 - 1000.0 * std::f64::consts::PI / 4.0 * 0.396f64.powi(2) / 240.0;
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains("heavier in water")
            && err.contains(&format!("is {ratio:.3} of its weight in air"))
            && err.contains("with a sag bend below its anchor"),
        "{err}"
    );
    assert!(riser(&["statics", jumper, "--set", "accuracy=1e-4"]).status.success());
    assert!(riser(&["statics", jumper, "--set", "accuracy=1e-4", "--set", "mass_per_length=220"]).status.success());
}

/// No mesh whose statics kinks the line is taken (docs/theory.md §16.10,
/// MAX_STATIC_KINK): the lazy wave with modules of 540 N/m (670 in the
/// scene), heaved 2.5 m at 10 s at 1e-2, took 10 elements, whose static line
/// bends 2.55 times the converged one's largest curvature with its top
/// tension within 6e-4, and erred 4.4e-2 (against 320 elements at 0.0125 s);
/// it takes 20 now, within the target against 80 elements at 0.025 s, and
/// the 10, pinned, still miss it, and are warned of.
#[test]
fn no_mesh_whose_statics_kinks_the_line_is_taken() {
    let run = |sets: &[&str]| {
        let base =
            ["run", "lazy_wave", "--heave", "2.5,10", "--duration", "40", "--json", "--set", "buoyancy_load=540"];
        let v = run_json(&with_sets(&base, sets));
        let t: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        (v["n_elements"].as_u64().unwrap(), t)
    };
    let (_, reference) = run(&["n_elements=80", "time_step=0.025"]);
    let error = |t: &[f64]| rel_error(t, &reference);
    let (n, knob) = run(&["accuracy=1e-2"]);
    assert_eq!(n, 20);
    assert!(error(&knob) <= 1e-2, "{:.2e}", error(&knob));
    let (_, kinked) = run(&["n_elements=10", "time_step=0.1", "newton_tolerance=1e-6"]);
    assert!(error(&kinked) > 1e-2, "the 10 elements reach the target: {:.2e}", error(&kinked));
    // pinned with the knob, the kinked mesh stands and is warned of; the 20 are not
    let warned = |n: &str| {
        let out = riser(&["statics", "lazy_wave", "--set", "buoyancy_load=540", "--set", "accuracy=1e-2", "--set", n]);
        assert!(out.status.success());
        String::from_utf8_lossy(&out.stderr).contains("the n_elements you set kinks the static line")
    };
    assert!(warned("n_elements=10"));
    assert!(!warned("n_elements=20"));
}

/// A run that is its statics is covered over a wider range of the line's
/// weight in water than one in motion (docs/theory.md §16.10 "Held still",
/// STILL_WEIGHT_RATIOS): the catenary made lighter, 110 kg/m for 226.7
/// (w/(m g) 0.264, below the 0.64 of a line in motion), held still by the
/// run with its 0.8 m/s current in the statics (`static_current`), is
/// accepted at 1e-4 and within it over 20 to 40 s against 80 elements at
/// 0.05 s (within 3e-7 of 320 elements and 1e-6 of 0.0125 s). The wider range
/// is not for a current that grows in the run: in 1.2 m/s grown over 10 s
/// the line is refused, and the numerics the knob would take held still, 10
/// elements at 0.2 s, err 2.9e-3 (the growth still rings in the window; 80
/// elements within 1.2e-6 of 160 at 0.025 s); nor for a heaved run, even with
/// the motion declared 0 (`accuracy_motion_amplitude`).
#[test]
fn a_run_that_is_its_statics_is_covered_over_a_wider_weight_range() {
    let window = |sets: &[&str]| {
        let base =
            ["run", "catenary", "--duration", "40", "--window", "20,40", "--json", "--set", "mass_per_length=110"];
        let v = run_json(&with_sets(&base, sets));
        let t: Vec<f64> = v["steady"]["top_tension"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        (v["n_elements"].as_u64().unwrap(), v["time_step"].as_f64().unwrap(), t)
    };
    let error = rel_error;
    let converged = ["n_elements=80", "time_step=0.05", "newton_tolerance=1e-10"];
    // its statics: accepted and within the target
    let (_, _, reference) = window(&[&converged[..], &["static_current=true"]].concat());
    let (n, dt, knob) = window(&["static_current=true", "accuracy=1e-4"]);
    assert!(error(&knob, &reference) <= 1e-4, "{n} el. at {dt} s: {:.2e}", error(&knob, &reference));
    let refused = |extra: &[&str]| {
        let mut args =
            vec!["run", "catenary", "--duration", "1", "--set", "mass_per_length=110", "--set", "accuracy=1e-4"];
        args.extend_from_slice(extra);
        let out = riser(&args);
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(
            !out.status.success() && err.contains("is 0.264 of its weight in air, below the 0.64"),
            "{args:?}: {err}"
        );
    };
    // a current grown in the run: refused, and the coarse numerics miss
    let current = ["--set", "current_top=1.2", "--set", "current_bottom=1.2"];
    refused(&current);
    let (_, _, reference) = window(&[&converged[..], &["current_top=1.2", "current_bottom=1.2"]].concat());
    let coarse = ["n_elements=10", "time_step=0.2", "newton_tolerance=1e-8", "current_top=1.2", "current_bottom=1.2"];
    let (_, _, coarse) = window(&coarse);
    assert!(error(&coarse, &reference) > 1e-3, "{:.2e}", error(&coarse, &reference));
    // heaved, or heaved with the motion declared 0
    refused(&["--set", "static_current=true", "--heave", "2.5,10"]);
    refused(&["--set", "static_current=true", "--heave", "2.5,10", "--set", "accuracy_motion_amplitude=0"]);
}

/// A current stronger than the study's on a line of its class is refused
/// (docs/theory.md §16.10 "A stronger current", MAX_CURRENT_RATIOS): the
/// catenary heaved 2.5 m at 10 s in a uniform 1.2 m/s (its current load
/// ratio F_c 0.099, above the 0.069 of the 1.0 m/s that kept 1e-4) is
/// refused at 1e-4, and the numerics the knob took for it, 16 elements at
/// 0.02 s, miss 1e-4 against 80 elements at 0.0125 s (within 1.7e-6 of 160);
/// in 1.0 m/s it is accepted; a run that is its statics (held still, the
/// current in the statics) is accepted in 1.5 m/s. The lazy wave, whose
/// modules put it in no class, is bounded too: in a uniform 1.2 m/s (F_c
/// 0.901) heaved at 20 s it is refused at 1e-3, where the 20 elements at
/// 0.1 s it took err above 1e-2 (its coarse line pushed into compression).
/// A seabed stiffness beyond the probed 1e6 to 1e7 Pa/m is refused, and a
/// sag bend shallower than 16 % of the line's length (the jumper shortened
/// to 136 m, 11 %, missed 1e-4 by 2.75 times at 10 s; at 150 m, 16.3 %, it
/// kept it), or with less drag than the jumper's C_d 1.0 (0.8 and 0.6
/// missed 1e-4 by 1.37 and 2.7 times at 15 s).
#[test]
fn a_current_stronger_than_the_study_s_is_refused() {
    let heaved = |speed: &str, sets: &[&str]| {
        let (top, bottom) = (format!("current_top={speed}"), format!("current_bottom={speed}"));
        let base =
            ["run", "catenary", "--heave", "2.5,10", "--duration", "40", "--json", "--set", &top, "--set", &bottom];
        riser_with(&base, sets)
    };
    let top_tension = steady_top_tension;
    let refused = heaved("1.2", &["accuracy=1e-4"]);
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success() && err.contains("is 0.099 of the static top tension (F_c), above the 0.069"),
        "{err}"
    );
    let reference = top_tension(&heaved("1.2", &["n_elements=80", "time_step=0.0125", "newton_tolerance=1e-10"]));
    let before = top_tension(&heaved("1.2", &["n_elements=16", "time_step=0.02", "newton_tolerance=1e-8"]));
    let e = rel_error(&before, &reference);
    assert!(e > 1e-4, "{e:.2e}");
    assert!(heaved("1.0", &["accuracy=1e-4"]).status.success());
    // the lazy wave (modules) in a uniform 1.2 m/s heaved at 20 s: refused at 1e-3, and the 20 elements at
    // 0.1 s the knob took miss it many times over (against 40 elements at 0.025 s)
    let lazy = |sets: &[&str]| {
        let base = ["run", "lazy_wave", "--heave", "2.5,20", "--duration", "80", "--json"];
        riser_with(&with_sets(&base, &["current_top=1.2", "current_bottom=1.2"]), sets)
    };
    let refused = lazy(&["accuracy=1e-3"]);
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success() && err.contains("above the 0.626 the model covers of a line with buoyancy modules"),
        "{err}"
    );
    let reference = top_tension(&lazy(&["n_elements=40", "time_step=0.025", "newton_tolerance=1e-10"]));
    let before = top_tension(&lazy(&["n_elements=20", "time_step=0.1", "newton_tolerance=1e-6"]));
    let e = rel_error(&before, &reference);
    assert!(e > 1e-2, "{e:.2e}");
    // a shallow sag bend: the jumper shortened to 136 m (11 % sag) refused, to 150 m (16.3 %) taken
    let jumper = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/lowe_langley_jumper.toml");
    let shortened = |length: &str| {
        riser(&["run", jumper, "--heave", "2.5,10", "--duration", "1", "--set", length, "--set", "accuracy=1e-4"])
    };
    let out = shortened("length=136");
    assert!(
        !out.status.success() && String::from_utf8_lossy(&out.stderr).contains("does not cover a shallow sag bend")
    );
    assert!(shortened("length=150").status.success());
    // a sag bend with less drag than the jumper's 1.0: refused (0.8 missed 1e-4 at 15 s)
    let out = shortened("cd_normal=0.8");
    assert!(
        !out.status.success() && String::from_utf8_lossy(&out.stderr).contains("a drag coefficient cd_normal = 0.8")
    );
    // a seabed stiffer or softer than the probed: refused
    for k in ["3e5", "3e7"] {
        let out = riser(&[
            "run",
            "steel_catenary",
            "--heave",
            "2.5,10",
            "--duration",
            "1",
            "--set",
            &format!("seabed_stiffness={k}"),
            "--set",
            "accuracy=1e-4",
        ]);
        assert!(
            !out.status.success() && String::from_utf8_lossy(&out.stderr).contains("does not cover a seabed stiffness")
        );
    }
    let still = riser(&[
        "run",
        "catenary",
        "--duration",
        "1",
        "--set",
        "current_top=1.5",
        "--set",
        "current_bottom=1.5",
        "--set",
        "static_current=true",
        "--set",
        "accuracy=1e-4",
    ]);
    assert!(still.status.success(), "{}", String::from_utf8_lossy(&still.stderr));
}
