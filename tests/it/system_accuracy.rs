//! `accuracy` on a system of lines (issue 51 on issue 49's systems;
//! docs/theory.md §16.14): the pilots refine every line by one factor
//! (16.21) and the system's one step; the target is on the vessel's
//! resultant force and moment (each component's min, mean and max over
//! the window, relative to the largest magnitude of its resultant) and each
//! line's top tension (relative to its max). The chosen numerics meet the
//! target against a converged reference run of the same system, and the
//! estimate the choice reports is within a factor 3 of the error measured.
//!
//! The system: a reduced copy of docs/cases/moored_vessel.toml, two of its
//! chains (700 m, OC3-Hywind's chain), fore and aft in 205 m of water, the
//! vessel surged 4 m and heaved 2 m at 10 s (the CLI's ramp over one
//! period; the window from 20 s to 50 s, three periods: the pilots' own).

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::Heave;
use riser::sim::error_estimate::{PilotPlan, Quantity, Stat};
use riser::sim::system_accuracy::{self, SystemRunSpec, run_system_pilot};
use riser::sim::vessel::VesselMotion;
use std::process::Command;

/// Two chains of moored_vessel.toml, fore and aft (bow and stern on the
/// centre line); 20 elements each, 0.1 s.
const TWO_CHAINS: &str = r#"
name = "two_chains"
description = "the vessel on two of moored_vessel's chains, fore and aft"

[[line_type]]
name = "chain"
model = "cable"
mass_per_length = 77.7066
outer_diameter = 0.09
axial_stiffness = 384.243e6
bending_stiffness = 0.0
torsional_stiffness = 0.0
cd_normal = 1.2
cd_tangential = 0.4
ca_normal = 1.0

[[point]]
name = "fairlead_bow"
kind = "vessel"
position = [45.0, 0.0, -5.0]

[[point]]
name = "fairlead_stern"
kind = "vessel"
position = [-45.0, 0.0, -5.0]

[[point]]
name = "anchor_bow"
kind = "fixed"
position = [685.0, 0.0, -205.0]

[[point]]
name = "anchor_stern"
kind = "fixed"
position = [-685.0, 0.0, -205.0]

[[line]]
name = "chain_bow"
type = "chain"
from = "fairlead_bow"
to = "anchor_bow"
length = 700.0
n_elements = 20

[[line]]
name = "chain_stern"
type = "chain"
from = "fairlead_stern"
to = "anchor_stern"
length = 700.0
n_elements = 20

[environment]
water_density = 1025.0
gravity = 9.81

[seabed]
z = -205.0
stiffness = 3.0e6
damping = 3.0e5
friction = 0.0

[analysis]
time_step = 0.1
newton_tolerance = 1e-8
"#;

const PERIOD: f64 = 10.0;
const WINDOW: (f64, f64) = (20.0, 50.0);
const SURGE: Heave = Heave { amplitude: 4.0, period: PERIOD, until: None, ramp: PERIOD };
const HEAVE: Heave = Heave { amplitude: 2.0, period: PERIOD, until: None, ramp: PERIOD };

/// `riser run --surge 4,10 --heave 2,10`'s vessel motion (ramped over one period).
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

fn system(accuracy: f64) -> SystemScene {
    let mut sys = SystemScene::from_toml(TWO_CHAINS, "two_chains").expect("valid");
    sys.analysis.accuracy = accuracy;
    sys
}

/// The reference: every line at 160 elements (4.4 m), 0.003125 s, Newton
/// to 1e-10: finer on both axes than any pilot of either target.
const REFERENCE: (usize, f64) = (160, 0.003125);

fn reference() -> &'static Vec<f64> {
    static R: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    R.get_or_init(|| {
        let plan = PilotPlan::new(WINDOW, Some(PERIOD), false);
        run_system_pilot(&system(0.0), &spec(), &plan, REFERENCE.0, (REFERENCE.1, 1e-10)).unwrap().values
    })
}

/// The error of the quantities `values` against the reference, as the
/// target is on them: the largest over the criteria of |q − q_ref| / |s_ref|.
fn measured_error(values: &[f64]) -> (f64, String) {
    let slots = system_accuracy::quantities(2);
    let at = |v: &[f64], q: Quantity| v[slots.iter().position(|x| *x == q).unwrap()];
    let r = reference();
    system_accuracy::criteria(riser::scene::AccuracyQuantity::TopTension, 2)
        .unwrap()
        .into_iter()
        .map(|(q, s)| ((at(values, q) - at(r, q)).abs() / at(r, s).abs(), q.name().into_owned()))
        .fold((0.0, String::new()), |a, b| if b.0 > a.0 { b } else { a })
}

/// At 1e-2 and 1e-3: the choice's estimate meets the target, the run at the
/// chosen numerics (every line at its level's elements, the chosen step and
/// Newton tolerance) is within the target of the reference, and the
/// estimate is within a factor 3 of that error.
#[test]
fn the_choice_meets_the_target_on_a_system_and_the_estimate_is_the_error() {
    let plan = PilotPlan::new(WINDOW, Some(PERIOD), false);
    for target in [1e-2, 1e-3] {
        let mut said = |m: &str| eprintln!("{m}");
        let (chosen, choice) =
            system_accuracy::apply(system(target), &spec(), Default::default(), 2, &mut said).unwrap();
        let c = choice.unwrap();
        eprintln!("{}", c.describe());
        for n in &c.notes {
            eprintln!("  note: {n}");
        }
        // every line refined by one factor: the level's elements (16.21)
        let level = c.n_elements;
        assert!(chosen.lines.iter().all(|l| l.n_elements == level), "{:?}", chosen.lines);
        assert_eq!((chosen.analysis.time_step, chosen.analysis.newton_tolerance), (c.time_step, c.newton_tolerance));
        // the reference finer than every pilot
        for p in c.rounds.iter().flat_map(|r| &r.pilots) {
            assert!(p.n_elements < REFERENCE.0 && p.time_step > REFERENCE.1, "pilot {} {}", p.n_elements, p.time_step);
        }
        let run = run_system_pilot(&system(0.0), &spec(), &plan, level, (c.time_step, c.newton_tolerance)).unwrap();
        let (measured, worst) = measured_error(&run.values);
        let estimate = c.estimate();
        eprintln!(
            "target {target:e}: level {level}, dt {} s: measured {measured:.3e} ({worst}), estimate {estimate:.3e}, \
             ratio {:.2}; pilots {:.1} s",
            c.time_step,
            estimate / measured,
            c.wall_s
        );
        assert!(c.met(), "{}", c.describe());
        assert!(measured <= target, "target {target:e}: measured {measured:.3e} on {worst}");
        assert!(
            (measured / 3.0..=3.0 * measured).contains(&estimate),
            "target {target:e}: estimate {estimate:.3e}, measured {measured:.3e} ({worst})"
        );
    }
}

/// The reference is converged: at half its elements and twice its step its
/// quantities move by less than a tenth of the tighter target (so an error
/// measured against it is the choice's, not the reference's).
#[test]
fn the_reference_is_converged() {
    let plan = PilotPlan::new(WINDOW, Some(PERIOD), false);
    let half = run_system_pilot(&system(0.0), &spec(), &plan, REFERENCE.0 / 2, (2.0 * REFERENCE.1, 1e-10)).unwrap();
    let (change, worst) = measured_error(&half.values);
    eprintln!("the reference at half its mesh and twice its step: {change:.3e} ({worst})");
    assert!(change < 1e-4, "{change:.3e} on {worst}");
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
    let dir = std::env::temp_dir().join(format!("riser_system_accuracy_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("two_chains.toml");
    std::fs::write(&path, TWO_CHAINS).unwrap();
    let p = path.to_str().unwrap();
    let base = ["run", p, "--surge", "4,10", "--heave", "2,10", "--duration", "50", "--json"];
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
    let (_, c) = system_accuracy::apply(system(1e-2), &spec(), Default::default(), 1, &mut |_| {}).unwrap();
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
    std::fs::remove_dir_all(&dir).ok();
}
