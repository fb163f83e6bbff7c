//! The error estimate of `riser run --estimate-error` (issue 51;
//! src/sim/error_estimate.rs, docs/theory.md §16.11): the pure Richardson
//! functions against closed forms, a non-monotone triplet named, and on the
//! catenary under a slow heave the observed orders and the estimates against
//! the error measured against much finer reference runs.

use riser::model::HangOff;
use riser::scene::Scene;
use riser::sim::Heave;
use riser::sim::error_estimate::{
    Convergence, ErrorEstimate, Estimate, Layout, PilotPlan, Quantity, RunSpec, estimate_error, richardson, run_pilot,
};
use std::sync::OnceLock;

/// q = q* + C h^p exactly: the order, the ratio 2^-p and q* to round-off.
#[test]
fn richardson_recovers_a_power_law_exactly() {
    for (q_star, c, p) in [(141_742.8, 350.0, 2.0), (-3.5, 0.01, 1.0), (10.0, -2.0, 3.7), (1.0, 1e-3, 0.6)] {
        let q = [1.0, 0.5, 0.25].map(|h: f64| q_star + c * h.powf(p));
        let t = richardson(q, 2.0);
        assert_eq!(t.class, Convergence::Monotone, "{q:?}");
        let order = t.order.unwrap();
        assert!((order - p).abs() < 1e-9, "p {p}: observed {order}");
        assert!((t.ratio.unwrap() - 0.5f64.powf(p)).abs() < 1e-12);
        assert!((t.extrapolated - q_star).abs() < 1e-9 * q_star.abs().max(1.0), "{} vs {q_star}", t.extrapolated);
        assert!((t.error - c).abs() < 1e-9 * c.abs().max(1.0), "the coarse level's error {} vs {c}", t.error);
    }
    // refinement ratio 3: q* + C h² at h = 1, 1/3, 1/9
    let t = richardson([1.0, 1.0 / 9.0, 1.0 / 81.0].map(|h2| 5.0 + 2.0 * h2), 3.0);
    assert!((t.order.unwrap() - 2.0).abs() < 1e-9 && (t.extrapolated - 5.0).abs() < 1e-12);
}

/// The round through its candidate (docs/theory.md §16.13, `Layout::Corner`):
/// with q = q* + a h^p + b Δt^s, the mesh triplet n/4, n/2, n at the
/// candidate's step and the step triplet 4Δt, 2Δt, Δt at its mesh give q*
/// and the candidate's own error a h_c^p + b Δt_c^s; the pilots' levels are
/// those triplets, 2.5 times the candidate's work (16.20).
#[test]
fn the_round_through_its_candidate_estimates_the_candidate_s_error() {
    let (q_star, a, p, b, s) = (100.0, 0.8, 3.0, -0.3, 2.0);
    let q = |h: f64, dt: f64| q_star + a * h.powf(p) + b * dt.powf(s);
    // the candidate at h = 0.25, Δt = 0.25 (the base at 1, 1)
    let e = Estimate::of_corner(
        Quantity::TopTensionMax,
        [q(1.0, 0.25), q(0.5, 0.25), q(0.25, 0.25)],
        [q(0.25, 1.0), q(0.25, 0.5), q(0.25, 0.25)],
    );
    let own = a * 0.25f64.powf(p) + b * 0.25f64.powf(s);
    assert!((e.extrapolated - q_star).abs() < 1e-10, "{}", e.extrapolated);
    assert!((e.value - q(0.25, 0.25)).abs() < 1e-12);
    assert!((e.error - own).abs() < 1e-10, "{} vs {own}", e.error);
    // each triplet's coarsest error, what (16.17) scales from the base
    assert!((e.mesh.error - a).abs() < 1e-10 && (e.step.error - b).abs() < 1e-10);
    let (levels, step, mesh) = Layout::Corner.levels(10, 0.4);
    assert_eq!(levels[2], (40, 0.1), "the candidate shared by both triplets");
    assert_eq!(
        (step.map(|i| levels[i]), mesh.map(|i| levels[i])),
        ([(40, 0.4), (40, 0.2), (40, 0.1)], [(10, 0.1), (20, 0.1), (40, 0.1)])
    );
    let work: f64 = levels.iter().map(|(n, dt)| *n as f64 / dt).sum();
    assert!((work / (40.0 / 0.1) - 2.5).abs() < 1e-12, "{work}");
}

/// Mesh and step additive, q = q* + a h^p + b Δt^s: (16.15) gives q*, (16.16) the user's error a + b.
#[test]
fn the_mesh_and_step_estimates_add_to_the_user_s_error() {
    let (q_star, a, p, b, s) = (100.0, 0.8, 3.0, -0.3, 2.0);
    let q = |h: f64, dt: f64| q_star + a * h.powf(p) + b * dt.powf(s);
    let e = Estimate::of(
        Quantity::TopTensionMax,
        [q(1.0, 0.25), q(0.5, 0.25), q(0.25, 0.25)],
        [q(1.0, 1.0), q(1.0, 0.5), q(1.0, 0.25)],
    );
    assert!((e.extrapolated - q_star).abs() < 1e-10, "{}", e.extrapolated);
    assert!((e.error - (a + b)).abs() < 1e-10, "{}", e.error);
    assert!((e.bound - (a.abs() + b.abs())).abs() < 1e-10);
    assert!((e.gci - 1.25 * e.bound).abs() < 1e-12);
    assert!(e.notes.is_empty());
    assert!((e.mesh.order.unwrap() - p).abs() < 1e-9 && (e.step.order.unwrap() - s).abs() < 1e-9);
}

/// Oscillatory (R < 0), divergent (R > 1, and q₁ = q₂ ≠ q₃) and agreeing
/// triplets: classified, no order, the finest taken, and said with the numbers.
#[test]
fn a_non_monotone_sequence_is_classified_and_reported() {
    let osc = richardson([100.0, 101.0, 100.5], 2.0);
    assert_eq!(osc.class, Convergence::Oscillatory);
    assert_eq!(osc.ratio, Some(-0.5));
    assert_eq!((osc.order, osc.extrapolated, osc.error), (None, 100.5, -0.5));
    let div = richardson([100.0, 101.0, 103.0], 2.0);
    assert_eq!((div.class, div.ratio, div.order, div.extrapolated), (Convergence::Divergent, Some(2.0), None, 103.0));
    let flat = richardson([100.0, 100.0, 101.0], 2.0);
    assert_eq!((flat.class, flat.ratio, flat.extrapolated), (Convergence::Divergent, None, 101.0));
    let agree = richardson([100.0, 100.5, 100.5], 2.0);
    assert_eq!(
        (agree.class, agree.order, agree.extrapolated, agree.error),
        (Convergence::Converged, None, 100.5, -0.5)
    );
    // the estimate says so, with the numbers, and takes the safety factor of the unconverged
    let e = Estimate::of(Quantity::TopTensionRange, [100.0, 101.0, 100.5], [101.0, 100.6, 100.5]);
    assert_eq!(e.notes.len(), 1, "{:?}", e.notes);
    let note = &e.notes[0];
    for want in ["mesh", "oscillatory", "R = -0.500", "1.000000e2", "1.010000e2", "1.005000e2", "finest pilot"] {
        assert!(note.contains(want), "'{want}' not in: {note}");
    }
    assert!(e.summary().contains("oscillatory"), "{}", e.summary());
    assert!((e.gci - 3.0 * e.bound).abs() < 1e-12);
}

// --- the catenary under a slow heave --------------------------------------

/// The top tension's quantities (the catenary has no seabed and no wall).
const TENSION: [Quantity; 4] =
    [Quantity::TopTensionMax, Quantity::TopTensionMin, Quantity::TopTensionRange, Quantity::TopTensionMean];

/// The user's numerics of the catenary cases: 20 elements, 0.1 s.
const N: usize = 20;
const DT: f64 = 0.1;
/// Heave 2.5 m / 10 s grown over one period; the window from 20 s (the
/// ramp and a period) to 50 s: three periods, the pilots' own.
const HEAVE: Heave = Heave { amplitude: 2.5, period: 10.0, until: None, ramp: 10.0 };
const WINDOW: (f64, f64) = (20.0, 50.0);

fn motion(t: f64) -> HangOff {
    HEAVE.at(t)
}

/// The catenary with the current in its statics (no current ramp to ring
/// the line) at the user's numerics.
fn scene() -> Scene {
    let sets = [format!("n_elements={N}"), format!("time_step={DT}"), "static_current=true".into()];
    Scene::builtin("catenary").unwrap().with_overrides(&sets).unwrap()
}

fn spec() -> RunSpec<'static> {
    RunSpec {
        motion: &motion,
        window: WINDOW,
        period: Some(HEAVE.period),
        irregular: false,
        max_tangent_age: 20,
        fatigue: None,
    }
}

fn estimate() -> &'static ErrorEstimate {
    static E: OnceLock<ErrorEstimate> = OnceLock::new();
    E.get_or_init(|| estimate_error(&scene(), &spec(), 2).unwrap())
}

/// The quantities at `n` elements and step `dt`, the pilots' window.
fn reference(n: usize, dt: f64) -> Vec<f64> {
    let plan = PilotPlan::new(WINDOW, Some(HEAVE.period), false);
    run_pilot(&scene(), &spec(), &plan, n, dt).unwrap().values
}

fn report(what: &str, q: Quantity, e: &Estimate, true_error: f64) {
    eprintln!(
        "{what} {}: values {:?}, R {:?}, order {:?}, {}; estimate {:.4e}, true {:.4e}, ratio {:.3}",
        q.name(),
        if what == "step" { e.step.values } else { e.mesh.values },
        if what == "step" { e.step.ratio } else { e.mesh.ratio },
        if what == "step" { e.step.order } else { e.mesh.order },
        if what == "step" { e.step.class.name() } else { e.mesh.class.name() },
        if what == "step" { e.step.error } else { e.mesh.error },
        true_error,
        if what == "step" { e.step.error } else { e.mesh.error } / true_error
    );
}

/// (a) The step: the top tension's time mean over whole periods, observed
/// within 2 ± 0.3 (the scheme's order; 1.79 measured); the extremes' orders
/// reported (0.80-0.82: not in their asymptotic range at these steps,
/// docs/theory.md §16.11); every quantity's Richardson estimate (its own
/// observed order) within a factor 3 of the step error measured against
/// the same mesh at Δt/64 (1.01 for the mean, 1.55-1.58 for the extremes).
#[test]
fn the_step_order_is_observed_and_the_estimate_is_the_measured_error() {
    let e = estimate();
    let fine = reference(N, DT / 64.0);
    for q in TENSION {
        let est = e.of(q).unwrap();
        let true_error = est.value - fine[q.index()];
        report("step", q, est, true_error);
        let p = est.step.order.unwrap_or(f64::NAN);
        if q == Quantity::TopTensionMean {
            assert!((p - 2.0).abs() <= 0.3, "{}: observed step order {p} ({:?})", q.name(), est.step);
        }
        assert_eq!(est.step.class, Convergence::Monotone, "{}: {:?}", q.name(), est.step);
        let r = est.step.error / true_error;
        assert!((1.0 / 3.0..=3.0).contains(&r), "{}: estimate / true {r}", q.name());
    }
}

/// (b) The mesh's observed order (whatever it is: reported) and its
/// estimate within a factor 3 of the mesh error measured against 16 n
/// elements at the same step; and the two together (16.16) against 8 n
/// elements at Δt/16.
#[test]
fn the_mesh_estimate_is_the_measured_error() {
    let e = estimate();
    let fine = reference(16 * N, DT / 4.0);
    let finest = reference(8 * N, DT / 16.0);
    for q in TENSION {
        let est = e.of(q).unwrap();
        let true_error = est.mesh.values[0] - fine[q.index()];
        report("mesh", q, est, true_error);
        let both = est.value - finest[q.index()];
        eprintln!(
            "  both {}: estimate {:.4e} (bound {:.4e}), true against 8n, dt/16 {:.4e}, ratio {:.3}",
            q.name(),
            est.error,
            est.bound,
            both,
            est.error / both
        );
        let r = est.mesh.error / true_error;
        assert!((1.0 / 3.0..=3.0).contains(&r), "{}: mesh estimate / true {r}", q.name());
        let r = est.error / both;
        assert!((1.0 / 3.0..=3.0).contains(&r), "{}: estimate / true {r}", q.name());
    }
    eprintln!("pilots: {:?}, {:.1} s wall", e.pilots, e.wall_s);
}

/// `riser run --estimate-error --json`: the estimate, its triplets and
/// pilots in `error_estimate`, the text's line naming what did not converge.
#[test]
fn the_command_line_reports_the_estimate() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "run",
            "catenary",
            "--set",
            "n_elements=8",
            "--set",
            "time_step=0.2",
            "--set",
            "static_current=true",
            "--heave",
            "2.5,10",
            "--duration",
            "30",
            "--estimate-error",
        ];
        args.extend_from_slice(extra);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_riser")).args(&args).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8(out.stdout).unwrap()
    };
    let v: serde_json::Value = serde_json::from_str(&run(&["--json"])).unwrap();
    let e = &v["error_estimate"];
    assert_eq!(e["quantity"], "top_tension_max");
    assert_eq!(e["mesh"]["levels"], serde_json::json!([8, 16, 32]));
    assert_eq!(e["step"]["levels"], serde_json::json!([0.2, 0.1, 0.05]));
    assert_eq!(e["pilot_window"], serde_json::json!([20.0, 30.0]));
    assert_eq!(e["pilots"].as_array().unwrap().len(), 5);
    assert_eq!(e["quantities"].as_array().unwrap().len(), TENSION.len());
    for k in ["value", "extrapolated", "pilots_wall_s"] {
        assert!(e[k].as_f64().is_some_and(f64::is_finite), "{k}: {e}");
    }
    let abs = e["estimate"]["absolute"].as_f64().unwrap();
    let (value, extrapolated) = (e["value"].as_f64().unwrap(), e["extrapolated"].as_f64().unwrap());
    assert!((abs - (value - extrapolated).abs()).abs() <= 1e-9 * value.abs());
    for t in ["mesh", "step"] {
        let class = e[t]["class"].as_str().unwrap();
        assert!(["monotone", "oscillatory", "divergent", "converged"].contains(&class), "{class}");
        assert_eq!(e[t]["order"].is_null(), class != "monotone", "{}", e[t]);
    }
    // a quantity the scene has not: refused before the run
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["run", "catenary", "--heave", "2.5,10", "--duration", "30", "--estimate-error"])
        .args(["--error-quantity", "stress_range"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("stress_range") && err.contains("no stresses"), "{err}");
    // a triplet not monotone is named in the notes and the text, with its numbers
    let text = run(&["--error-quantity", "all"]);
    let lines: Vec<&str> = text.lines().filter(|l| l.contains("error estimate of")).collect();
    assert_eq!(lines.len(), TENSION.len(), "{text}");
    for (q, line) in e["quantities"].as_array().unwrap().iter().zip(&lines) {
        assert_eq!(q["monotone"].as_bool().unwrap(), !line.contains("does not converge monotonically"), "{line}");
    }
}

/// Issue 51's evidence on scenes the accuracy knob refuses (a long test:
/// `cargo test --profile fasttest --test it -- error_estimate:: --ignored
/// --nocapture`): the catenary with structural damping, in a regular sea
/// travelling at 45°, and as the cable model, each at 20 elements and 0.1 s
/// heaved 2.5 m / 10 s; the estimate (16.16) of every quantity against the
/// error measured against 8 n elements at Δt/16, within a factor 3
/// (docs/guide/accuracy.md's table).
#[test]
#[ignore = "long: the evidence table of docs/guide/accuracy.md"]
fn long_the_estimate_on_scenes_the_knob_refuses() {
    let cases: [(&str, &[&str]); 3] = [
        ("structural damping 0.002 s", &["structural_damping=0.002"]),
        (
            "regular sea H 4 m, T 10 s at 45 deg",
            &["wave_kind=airy", "wave_height=4", "wave_period=10", "wave_direction=45", "wave_ramp=10"],
        ),
        ("the cable model", &["model=cable"]),
    ];
    for (name, extra) in cases {
        let mut sets = vec![format!("n_elements={N}"), format!("time_step={DT}"), "static_current=true".to_string()];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let scene = Scene::builtin("catenary").unwrap().with_overrides(&sets).unwrap();
        let sea = riser::loads::waves::ramp_and_period(&scene).unwrap();
        // the CLI's window: after the motion's ramp and a period, and the sea's
        let w0 = sea.map_or(20.0, |(r, p)| (r + p).max(20.0));
        let period = sea.map_or(HEAVE.period, |(_, p)| p.max(HEAVE.period));
        let spec = RunSpec {
            motion: &motion,
            window: (w0, w0 + 30.0),
            period: Some(period),
            irregular: false,
            max_tangent_age: 20,
            fatigue: None,
        };
        let e = estimate_error(&scene, &spec, 2).unwrap();
        let plan = PilotPlan::new(spec.window, spec.period, spec.irregular);
        let fine = run_pilot(&scene, &spec, &plan, 8 * N, DT / 16.0).unwrap().values;
        eprintln!("{name}: pilots {:.1} s wall, window {:?}", e.wall_s, plan.window);
        for q in TENSION {
            let est = e.of(q).unwrap();
            let truth = est.value - fine[q.index()];
            let order = |t: &riser::sim::error_estimate::Triplet| {
                t.order.map_or(t.class.name().to_string(), |p| format!("{p:.2}"))
            };
            eprintln!(
                "| {name} | {} | {:.1} | {} | {} | {:.3e} | {:.3e} | {:.2} |",
                q.name(),
                est.value,
                order(&est.mesh),
                order(&est.step),
                est.error,
                truth,
                est.error / truth
            );
            let r = est.error / truth;
            assert!((1.0 / 3.0..=3.0).contains(&r), "{name}, {}: estimate / true {r}", q.name());
        }
    }
}

/// The touchdown's extremes, the largest stress range and the fatigue
/// damage (DNV-RP-C203 D in seawater with cathodic protection), on the steel
/// catenary (40 elements, 0.1 s, heaved 2.5 m / 10 s, window 20–50 s; a
/// long test): every quantity's estimate (16.16) against the error measured
/// against 320 elements at Δt/16, reported; within a factor 3 asserted.
#[test]
#[ignore = "long: the steel catenary's touchdown and stress range"]
fn long_the_touchdown_and_the_stress_range_on_the_steel_catenary() {
    let n = 40;
    let sets = [format!("n_elements={n}"), format!("time_step={DT}")];
    let scene = Scene::builtin("steel_catenary").unwrap().with_overrides(&sets).unwrap();
    let curve = riser::sim::fatigue::SnCurve::by_name("D-seawater-cp").unwrap();
    let spec = RunSpec { fatigue: Some(riser::sim::fatigue::FatigueSpec { curve, scf: 1.0, dff: 1.0 }), ..spec() };
    let e = estimate_error(&scene, &spec, 2).unwrap();
    let plan = PilotPlan::new(spec.window, spec.period, spec.irregular);
    let fine = run_pilot(&scene, &spec, &plan, 8 * n, DT / 16.0).unwrap().values;
    eprintln!("steel catenary: pilots {:.1} s wall, not estimated: {:?}", e.wall_s, e.notes);
    let mut misses = Vec::new();
    for est in &e.estimates {
        let q = est.quantity;
        let truth = est.value - fine[q.index()];
        let order =
            |t: &riser::sim::error_estimate::Triplet| t.order.map_or(t.class.name().to_string(), |p| format!("{p:.2}"));
        eprintln!(
            "| steel catenary | {} ({}) | {:.6e} | {} | {} | {:.3e} | {:.3e} | {:.2} |",
            q.name(),
            q.unit(),
            est.value,
            order(&est.mesh),
            order(&est.step),
            est.error,
            truth,
            est.error / truth
        );
        eprintln!("    mesh {:?}\n    step {:?}", est.mesh.values, est.step.values);
        let r = est.error / truth;
        if !(1.0 / 3.0..=3.0).contains(&r) {
            misses.push(format!("{}: {r:.2}", q.name()));
        }
    }
    assert_eq!(e.estimates.len(), Quantity::ALL.len(), "{:?}", e.notes);
    assert!(misses.is_empty(), "estimate / true outside a factor 3: {misses:?}");
}
