//! A system of lines on one vessel (issue 49, statics without free points,
//! which tests/it/system_free_points.rs tests; docs/guide/systems.md, docs/theory.md §17): the format's
//! checks, the OC3-Hywind spar's mooring against its published surge
//! stiffness, the 6×6 stiffness against central differences of the
//! system's own statics, and the command line.

use crate::common::system::{block_errors, finite_difference_stiffness, has, invalid};
use riser::scene::Scene;
use riser::scene::system::SystemScene;
use riser::sim::system::solve_system;

const OC3: &str = include_str!("../../docs/cases/oc3_hywind_mooring.toml");

fn oc3() -> SystemScene {
    SystemScene::from_toml(OC3, "oc3").expect("the OC3 scene is valid")
}

/// The published surge stiffness of the OC3-Hywind mooring (Jonkman 2010,
/// Table 5-1), N/m.
const OC3_SURGE_STIFFNESS: f64 = 41_180.0;

#[test]
fn the_oc3_mooring_has_its_published_surge_stiffness() {
    let st = solve_system(&oc3(), &[0.0; 6], true).unwrap();
    let k = st.stiffness;
    let rel = (k[(0, 0)] / OC3_SURGE_STIFFNESS - 1.0).abs();
    eprintln!("K11 {} N/m, K22 {} N/m, {rel:.2e} from 41.18 kN/m", k[(0, 0)], k[(1, 1)]);
    // 100 cable elements a line, seabed kBot 3e6 Pa/m: measured 6.2e-4 (41.155 kN/m)
    assert!(rel < 2e-3, "K11 {} N/m", k[(0, 0)]);
    assert!((k[(1, 1)] / k[(0, 0)] - 1.0).abs() < 1e-6, "the spread is symmetric: K22 = K11");
    // the neutral pose: no horizontal force, no moment
    assert!(st.force.x.abs() < 1.0 && st.force.y.abs() < 1.0, "{:?}", st.force);
    assert!(st.moment.norm() < 10.0, "{:?}", st.moment);
    for l in &st.lines {
        assert!((l.tension_to - st.lines[0].tension_to).abs() < 1e-3 * l.tension_to, "{}", l.name);
        assert!(l.touchdown_s.is_some(), "{} lies on the seabed", l.name);
    }
}

/// The composed 6×6 stiffness (each line's translation stiffness moved to
/// the reference point with the moment arm's geometric term, theory §17.3)
/// is the derivative of the system's re-solved statics: at the neutral pose
/// and at a pose with every degree of freedom displaced.
#[test]
fn the_stiffness_is_the_derivative_of_the_statics() {
    let sys = oc3();
    for pose in [[0.0; 6], [10.0, -4.0, 1.5, 0.03, -0.05, 0.2]] {
        let k = solve_system(&sys, &pose, true).unwrap().stiffness;
        let fd = finite_difference_stiffness(&pose, 1e-2, 1e-4, |p| solve_system(&sys, p, false).unwrap());
        let errs = block_errors(&k, &fd);
        eprintln!("pose {pose:?}: block errors (FF, FM, MF, MM) {errs:?}\nK {k:.6e}\nFD {fd:.6e}");
        // measured below 2e-6 (the blocks' O(h²) and the statics' 1e-10 residual)
        for e in errs {
            assert!(e < 1e-4, "{errs:?}");
        }
    }
}

#[test]
fn bad_systems_are_named() {
    // a free point's keys on a vessel point (free points: tests/it/system_free_points.rs)
    let e = invalid(&OC3.replacen("kind = \"vessel\"", "kind = \"vessel\"\nmass = 1.0", 1));
    assert!(has(&e, "point.fairlead1.mass", "only a free point"), "{e:?}");
    // an unknown point, an unknown type
    let e = invalid(&OC3.replacen("to = \"fairlead1\"", "to = \"fairlead9\"", 1));
    assert!(has(&e, "line.line1.to", "fairlead9") && has(&e, "point.fairlead1", "no line uses"), "{e:?}");
    let e = invalid(&OC3.replacen("type = \"chain\"", "type = \"wire\"", 1));
    assert!(has(&e, "line.line1.type", "wire"), "{e:?}");
    // two items of one name (a line and a point), a name that is no identifier
    let e = invalid(&OC3.replacen("name = \"line2\"", "name = \"anchor1\"", 1));
    assert!(has(&e, "line.anchor1", "unique over lines and points"), "{e:?}");
    let e = invalid(&OC3.replace("line3", "3rd-line"));
    assert!(has(&e, "line.3rd-line", "not an identifier"), "{e:?}");
    // a line between two fixed points
    let e = invalid(&OC3.replacen("from = \"anchor1\"\nto = \"fairlead1\"", "from = \"anchor1\"\nto = \"anchor2\"", 1));
    assert!(has(&e, "line.line1", "a line joins a fixed point and a vessel point"), "{e:?}");
    // the line's own checks, named as the system's
    let e = invalid(&OC3.replacen("length = 902.2", "length = 500.0", 1));
    assert!(has(&e, "line.line1", "farther than the line can reach"), "{e:?}");
    let e = invalid(&OC3.replacen("n_elements = 100", "n_elements = 0", 1));
    assert!(e.iter().any(|(f, _)| f == "line.line1.n_elements"), "{e:?}");
    let e = invalid(&OC3.replace("mass_per_length = 77.7066", "mass_per_length = -1.0"));
    assert!(e.iter().any(|(f, _)| f == "line_type.chain.mass_per_length"), "{e:?}");
    let e = invalid(&OC3.replace("newton_tolerance = 1e-8", "newton_tolerance = 1e-8\nmodel = \"rod\""));
    assert!(has(&e, "analysis.model", "line_type"), "{e:?}");
    // a single-line command given a system says so
    match Scene::from_toml(OC3, "oc3") {
        Err(e) => assert!(e.to_string().contains("this command takes a single-line scene"), "{e}"),
        Ok(_) => panic!("a system read as a single line"),
    }
}

/// The restoring force at 10 m of surge, and the fairlead tensions there
/// (MoorPy's in tests/python/test_system.py).
#[test]
fn a_surge_offset_restores() {
    let st = solve_system(&oc3(), &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0], false).unwrap();
    eprintln!("F {:?} M {:?}", st.force, st.moment);
    for l in &st.lines {
        eprintln!("{}: from {} to {}", l.name, l.tension_from, l.tension_to);
    }
    assert!(st.force.x < -3.5e5 && st.force.x > -4.2e5, "{:?}", st.force);
    assert!(st.lines[0].tension_to < st.lines[1].tension_to, "the windward line slackens");
}

#[test]
fn the_command_line_solves_a_system_at_a_pose() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases/oc3_hywind_mooring.toml");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["statics", path, "--pose", "10,0,0,0,0,0", "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let lib = solve_system(&oc3(), &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0], true).unwrap();
    assert_eq!(v["top_force"][0].as_f64().unwrap(), lib.force.x);
    assert_eq!(v["lines"].as_array().unwrap().len(), 3);
    assert_eq!(v["points"].as_array().unwrap().len(), 0);
    assert_eq!(v["stiffness"][0][0].as_f64().unwrap(), lib.stiffness[(0, 0)]);
    for key in
        ["name", "tension_from", "tension_to", "min_tension", "touchdown_s", "anchor_force", "anchor_uplift_angle"]
    {
        assert!(v["lines"][0].get(key).is_some(), "{key}");
    }
    // refused: a bad pose, --pose on a single-line scene
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["statics", path, "--pose", "1,2,3"])
        .output()
        .unwrap();
    assert!(!bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("it takes six"));
    let single = std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["statics", "catenary", "--pose", "0,0,0,0,0,0"])
        .output()
        .unwrap();
    assert!(!single.status.success() && String::from_utf8_lossy(&single.stderr).contains("only for a system"));
}
