//! `accuracy` on a system of lines (issue 51 on issue 49's systems;
//! docs/theory.md §16.14): the pilots refine every line by one factor
//! (16.21) and the system's one step; the target is on the vessel's
//! resultant force and moment (each component's min, mean and max over
//! the window, relative to the largest magnitude of its resultant) and each
//! line's top tension (relative to its max). The chosen numerics meet the
//! target against a converged reference run of the same system, and the
//! estimate the choice reports is within a factor 3 of the error measured.
//!
//! The system: two of docs/cases/moored_vessel.toml's chains hanging free
//! (docs/cases/two_chains_hanging.toml: 600 m to anchors 500 m out and 200
//! m down, no seabed), the vessel surged 2 m and heaved 2 m at 10 s (the
//! CLI's ramp over one period; the window from 20 s to 50 s, three periods:
//! the pilots' own). (On moored_vessel's seabed the reference does not
//! converge at steps a test can afford: docs/theory.md §16.14.)

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::Heave;
use riser::sim::error_estimate::{PilotPlan, Quantity, Stat};
use riser::sim::system_accuracy::{self, SystemRunSpec, run_system_pilot};
use riser::sim::vessel::VesselMotion;
use std::process::Command;

/// docs/cases/two_chains_hanging.toml: two of moored_vessel's chains
/// hanging free, 30 elements at 0.05 s as written.
const HANGING: &str = include_str!("../../docs/cases/two_chains_hanging.toml");

fn free_hanging() -> String {
    HANGING.to_string()
}

const PERIOD: f64 = 10.0;
const WINDOW: (f64, f64) = (20.0, 50.0);
const SURGE: Heave = Heave { amplitude: 2.0, period: PERIOD, until: None, ramp: PERIOD };
const HEAVE: Heave = Heave { amplitude: 2.0, period: PERIOD, until: None, ramp: PERIOD };

/// `riser run --surge 2,10 --heave 2,10`'s vessel motion (ramped over one period).
fn motion(t: f64) -> VesselMotion {
    let (s, h) = (SURGE.at(t), HEAVE.at(t));
    VesselMotion {
        displacement: V3::new(s.displacement.z, 0.0, h.displacement.z),
        velocity: V3::new(s.velocity.z, 0.0, h.velocity.z),
        ..Default::default()
    }
}

fn spec() -> SystemRunSpec<'static> {
    SystemRunSpec { motion: &motion, window: WINDOW, period: Some(PERIOD), irregular: false, max_tangent_age: 20 }
}

fn plan() -> PilotPlan {
    PilotPlan::new(WINDOW, Some(PERIOD), false)
}

fn system(toml: &str, accuracy: f64) -> SystemScene {
    let mut sys = SystemScene::from_toml(toml, "two_chains").expect("valid");
    sys.analysis.accuracy = accuracy;
    sys
}

/// The quantities of `toml` at level `n`, step `dt`, Newton to 1e-10.
fn quantities_at(toml: &str, n: usize, dt: f64) -> Vec<f64> {
    run_system_pilot(&system(toml, 0.0), &spec(), &plan(), n, (dt, 1e-10)).unwrap().values
}

/// The error of the quantities `values` against `reference`, as the target
/// is on them: the largest over the criteria of |q − q_ref| / |s_ref|, and
/// the quantity it is of.
fn error_against(values: &[f64], reference: &[f64]) -> (f64, String) {
    let slots = system_accuracy::quantities(2);
    let at = |v: &[f64], q: Quantity| v[slots.iter().position(|x| *x == q).unwrap()];
    system_accuracy::criteria(riser::scene::AccuracyQuantity::TopTension, 2)
        .unwrap()
        .into_iter()
        .map(|(q, s)| ((at(values, q) - at(reference, q)).abs() / at(reference, s).abs(), q.name().into_owned()))
        .fold((0.0, String::new()), |a, b| if b.0 > a.0 { b } else { a })
}

/// What `accuracy` = `target` chose on `toml` and the error of its run
/// against the reference (level, step) `reference`, its quantities `r`.
struct Case {
    choice: riser::sim::accuracy::Choice,
    measured: f64,
    worst: String,
}

fn case(toml: &str, target: f64, reference: (usize, f64), r: &[f64]) -> Case {
    let (chosen, choice) =
        system_accuracy::apply(system(toml, target), &spec(), Default::default(), 2, &mut |m| eprintln!("{m}"))
            .unwrap();
    let c = choice.unwrap();
    eprintln!("{}", c.describe());
    // every line refined by one factor: the level's elements (16.21)
    assert!(chosen.lines.iter().all(|l| l.n_elements == c.n_elements), "{:?}", chosen.lines);
    assert_eq!((chosen.analysis.time_step, chosen.analysis.newton_tolerance), (c.time_step, c.newton_tolerance));
    // the reference finer than every pilot on both axes
    for p in c.rounds.iter().flat_map(|r| &r.pilots) {
        assert!(p.n_elements < reference.0 && p.time_step > reference.1, "pilot {} {}", p.n_elements, p.time_step);
    }
    let run = run_system_pilot(&system(toml, 0.0), &spec(), &plan(), c.n_elements, (c.time_step, c.newton_tolerance))
        .unwrap();
    let (measured, worst) = error_against(&run.values, r);
    eprintln!(
        "target {target:e}: level {}, dt {} s: measured {measured:.3e} ({worst}), estimate {:.3e}, ratio {:.2}; \
         {} pilots, {:.1} s",
        c.n_elements,
        c.time_step,
        c.estimate(),
        c.estimate() / measured,
        c.pilots(),
        c.wall_s
    );
    Case { choice: c, measured, worst }
}

/// The free-hanging reference: every line at 128 elements (4.7 m), 0.00625
/// s, Newton to 1e-10; at half its elements and twice its step its
/// quantities move by less than a tenth of the target (so the error
/// measured against it is the choice's).
const FREE_REFERENCE: (usize, f64) = (128, 0.00625);

/// The free-hanging chains at 1e-2: the estimate meets the target, the run
/// at the chosen numerics is within it of the reference, and the estimate
/// is within a factor 3 of the error measured.
#[test]
fn the_choice_meets_the_target_on_a_system_and_the_estimate_is_the_error() {
    let toml = free_hanging();
    let (n, dt) = FREE_REFERENCE;
    let r = quantities_at(&toml, n, dt);
    let (change, worst) = error_against(&quantities_at(&toml, n / 2, 2.0 * dt), &r);
    eprintln!("the reference at half its mesh and twice its step: {change:.3e} ({worst})");
    let target = 1e-2;
    assert!(change < target / 10.0, "the reference is not converged: {change:.3e} on {worst}");
    let Case { choice: c, measured, worst } = case(&toml, target, FREE_REFERENCE, &r);
    assert!(c.met(), "{}", c.describe());
    assert!(measured <= target, "measured {measured:.3e} on {worst}");
    let estimate = c.estimate();
    assert!((measured / 3.0..=3.0 * measured).contains(&estimate), "estimate {estimate:.3e}, measured {measured:.3e}");
    let share = pilots_share_of_3_hours(&system(&toml, 0.0), &c);
    eprintln!("the pilots' work: {:.2} % of a 3-hour run at the choice", 100.0 * share);
    assert!(share <= 0.2, "the pilots {share:.3} of a 3-hour run");
}

/// The pilots' work (every line's elements times the steps, those reused
/// once) over a 3-hour run's at the choice (16.19), issue 51's aim 20 %.
fn pilots_share_of_3_hours(sys: &SystemScene, c: &riser::sim::accuracy::Choice) -> f64 {
    let elements = |level: usize| system_accuracy::line_elements(sys, level).iter().sum::<usize>() as f64;
    let end = plan().duration;
    let pilots: f64 = c
        .rounds
        .iter()
        .flat_map(|r| &r.pilots)
        .filter(|p| !p.reused)
        .map(|p| elements(p.n_elements) * (end / p.time_step).round())
        .sum();
    pilots / (elements(c.n_elements) * 10800.0 / c.time_step)
}

/// 1e-3 on the free-hanging chains, against the reference at 256 elements
/// and 0.003125 s (at half its elements and twice its step it moves by
/// 1.7e-5): the numerics taken meet the target; the moment's mesh triplet
/// does not converge monotonically (16, 32, 64 elements: the moment about
/// the reference point is the difference of the two chains' vertical
/// forces at ±45 m), and the fourth level at 128 (docs/theory.md §16.15)
/// measures level 64's error: estimate 3.7e-4, met, measured 1.04e-4 (3.5
/// times; 33 before, from the last change); never below a third of it.
/// (The chains on moored_vessel's seabed are not here: their reference
/// does not converge at steps the test can afford, docs/theory.md §16.14.)
#[test]
#[ignore = "long: accuracy on a system at 1e-3"]
fn long_accuracy_on_a_system_at_1e_3() {
    let toml = free_hanging();
    let reference = (256, 0.003125);
    let r = quantities_at(&toml, reference.0, reference.1);
    let (change, worst) = error_against(&quantities_at(&toml, reference.0 / 2, 2.0 * reference.1), &r);
    eprintln!("the reference at half its mesh and twice its step: {change:.3e} ({worst})");
    let target = 1e-3;
    assert!(change < target / 10.0, "the reference moves {change:.3e} ({worst})");
    let Case { choice: c, measured, worst } = case(&toml, target, reference, &r);
    eprintln!("{}; notes: {:?}", c.describe(), c.notes);
    assert!(measured <= target, "measured {measured:.3e} on {worst}");
    assert!(c.met() && c.warning().is_none(), "{}", c.describe());
    eprintln!("the pilots' work: {:.2} % of a 3-hour run", 100.0 * pilots_share_of_3_hours(&system(&toml, 0.0), &c));
    assert!(c.estimate() >= measured / 3.0, "estimate {:.3e}, measured {measured:.3e}", c.estimate());
}

/// Each line's elements at a level keep their ratio (16.21); the levels a
/// choice takes are those where no line is rounded.
#[test]
fn lines_are_refined_by_one_factor() {
    let sys = SystemScene::from_toml(include_str!("../../docs/cases/moored_vessel.toml"), "mv").unwrap();
    assert_eq!(system_accuracy::mesh_level(&sys), 40);
    // 40 and 35 elements: whole at multiples of 8
    assert_eq!(system_accuracy::level_step(&sys), 8);
    assert_eq!(system_accuracy::line_elements(&sys, 16), vec![16, 14, 14, 14, 14]);
    assert_eq!(system_accuracy::line_elements(&sys, 40), vec![40, 35, 35, 35, 35]);
    assert_eq!(system_accuracy::line_elements(&sys, 4), vec![4, 4, 4, 4, 4]);
    // a quantity's name carries its line's
    let q = Quantity::LineTension { line: 1, stat: Stat::Max };
    assert_eq!(q.label(&system_accuracy::line_names(&sys)), "chain_bow_port.top_tension_max");
}

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

/// `riser run SYSTEM --set accuracy=...`: the choice in the JSON, the run at
/// its numerics; `--set` of a line's key refused, naming where it is
/// written; `--estimate-error` on a system.
#[test]
fn the_command_line_takes_accuracy_on_a_system() {
    let p = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/two_chains_hanging.toml");
    let base = ["run", p, "--surge", "2,10", "--heave", "2,10", "--duration", "50", "--json"];
    let out = riser(&[&base[..], &["--set", "accuracy=1e-2"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let a = &v["accuracy"];
    assert_eq!(a["met"], true, "{a}");
    let level = a["chosen"]["n_elements"].as_u64().unwrap();
    assert_eq!(v["time_step"], a["chosen"]["time_step"]);
    for l in v["steady"]["lines"].as_array().unwrap() {
        assert_eq!(l["n_elements"].as_u64().unwrap(), level, "{l}");
    }
    // the same choice as the library's on the same run (the pilots' bits do not depend on threads)
    let (_, c) =
        system_accuracy::apply(system(&free_hanging(), 1e-2), &spec(), Default::default(), 1, &mut |_| {}).unwrap();
    let c = c.unwrap();
    assert_eq!((level as usize, a["chosen"]["time_step"].as_f64().unwrap()), (c.n_elements, c.time_step));
    assert!(a["orders"]["chain_bow.top_tension_max"].is_object(), "{a}");
    assert!(a["orders"]["vessel_force_x_max"].is_object(), "{a}");
    // a line's key: refused, named
    let out = riser(&[&base[..], &["--set", "n_elements=40"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("n_elements") && err.contains("system's file"), "{err}");
    // --set time_step and --estimate-error: the five pilots about the system's numerics
    let out = riser(&[&base[..], &["--set", "time_step=0.2", "--estimate-error"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["time_step"], 0.2);
    let e = &v["error_estimate"];
    assert_eq!(e["pilots"].as_array().unwrap().len(), 5, "{e}");
    assert!(e["quantities"].as_array().unwrap().iter().any(|q| q["quantity"] == "chain_stern.top_tension_max"), "{e}");
}
