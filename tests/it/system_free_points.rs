//! Free points in the statics of a system of lines (issue 49 point 2;
//! docs/guide/systems.md, docs/theory.md §17.4): on the three cases
//! (docs/cases/{clump_weight,subsea_buoy,bridle}_mooring.toml) each free
//! point's equilibrium, summed here from its lines' end forces and its own
//! weight and buoyancy (17.5); the 6×6 condensed on the free points (17.8,
//! 17.9) against central differences of the system's own re-solved statics
//! (an independent check: no stiffness enters them); the start of a chain
//! lying on the seabed from a free point (the bridle's bug); bad systems
//! named; the dynamics refusing free points, named. MoorPy's numbers are in
//! tests/python/test_system.py.

use crate::common::system::{block_errors, finite_difference_stiffness, has, invalid};
use riser::math::V3;
use riser::model::cable::statics::touchdown_start;
use riser::scene::system::{PointKind, SystemScene, VesselEnd};
use riser::sim::system::{SystemStatics, cable_start, solve_line_between, solve_system, solve_system_from};

const CASES: [&str; 3] = ["clump_weight_mooring", "subsea_buoy_mooring", "bridle_mooring"];
const POSES: [[f64; 6]; 2] = [[0.0; 6], [8.0, 3.0, 1.0, 0.02, -0.03, 0.05]];

fn path(name: &str) -> String {
    format!("{}/docs/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

fn case(name: &str) -> SystemScene {
    SystemScene::load(&path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Each free point's net force, summed from the lines' forces on their
/// ends (the report's, at the end the point is) and its weight and
/// buoyancy from the scene (clear of the seabed, submerged: asserted).
fn net_forces(sys: &SystemScene, st: &SystemStatics) -> Vec<(String, V3, f64)> {
    let env = &sys.environment;
    let bed = sys.seabed.as_ref().map_or(f64::NEG_INFINITY, |b| b.z);
    st.points
        .iter()
        .map(|p| {
            let spec = sys.points.iter().find(|q| q.name == p.name).unwrap();
            assert_eq!(spec.kind, PointKind::Free);
            assert!(p.position.z < env.water_surface_z && p.position.z > bed + 1.0, "{} at {:?}", p.name, p.position);
            let mut f = V3::new(0.0, 0.0, env.gravity * (env.water_density * spec.volume() - spec.mass()));
            let mut scale = f.norm();
            for (l, spec_l) in st.lines.iter().zip(&sys.lines) {
                // the line's hang-off is its `from` end or its `to` end
                let (at_from, at_to) = match l.hang_off_end {
                    VesselEnd::From => (l.report.top_force, l.report.bottom_force),
                    VesselEnd::To => (l.report.bottom_force, l.report.top_force),
                };
                for (end, force) in [(&spec_l.from, at_from), (&spec_l.to, at_to)] {
                    if *end == p.name {
                        f += force;
                        scale += force.norm();
                    }
                }
            }
            (p.name.clone(), f, scale)
        })
        .collect()
}

#[test]
fn each_free_point_is_in_equilibrium() {
    for name in CASES {
        let sys = case(name);
        for pose in POSES {
            let st = solve_system(&sys, &pose, false).unwrap_or_else(|e| panic!("{name} {pose:?}: {e}"));
            assert!(!st.points.is_empty());
            for (p, f, scale) in net_forces(&sys, &st) {
                eprintln!(
                    "{name} {pose:?}: {p} net {:.3e} N of {scale:.3e} N ({} iterations)",
                    f.norm(),
                    st.iterations
                );
                // the free points' Newton stops at 1e-8 of the scale; measured at most 2.4e-10
                assert!(f.norm() <= 1e-8 * scale, "{name} {pose:?}: {p} out of balance by {f:?} N");
            }
        }
    }
}

#[test]
fn the_condensed_stiffness_is_the_derivative_of_the_statics() {
    for name in CASES {
        let sys = case(name);
        for pose in POSES {
            let st = solve_system(&sys, &pose, true).unwrap();
            let fd = finite_difference_stiffness(&pose, 1e-2, 1e-4, |p| {
                // each perturbed pose re-solved, its free points re-equilibrated from the state at `pose`
                solve_system_from(&sys, p, false, Some(&st)).unwrap()
            });
            let errs = block_errors(&st.stiffness, &fd);
            eprintln!("{name} {pose:?}: block errors (FF, FM, MF, MM) {errs:?}");
            for e in errs {
                // measured at most 3.5e-5 (the clump case's FF block, neutral pose)
                assert!(e < 1e-4, "{name} {pose:?}: {errs:?}\nK {:.6e}\nFD {fd:.6e}", st.stiffness);
            }
        }
    }
}

/// The bridle's bug: its 600 m chain, hung from the joint at its
/// equilibrium, 400 m of it lying on the seabed. The library's
/// `touchdown_start` lays the lying part unstretched (Touchdown closes on
/// the anchor with it so) and spreads it evenly after the marched
/// suspended nodes: the lying segments at zero strain or slack, no
/// stiffness along the frictionless seabed, Newton singular (the scene's
/// own solve grinds through 61 continuation steps). `cable_start` stretches
/// the lying part by H/EA and sinks it to its penetration: every segment
/// taut, and Newton converges from it alone.
#[test]
fn a_chain_lying_from_a_free_point_starts_taut() {
    let sys = case("bridle_mooring");
    let main = sys.lines.iter().position(|l| l.name == "main").unwrap();
    let (joint, anchor) = (V3::new(-31.654, 0.0, -63.315), V3::new(-600.0, 0.0, -150.0));
    let scene = sys.line_scene_at(main, joint, anchor);
    let model = riser::model::cable::CableModel::from_scene(&scene);
    let x = cable_start(&model, scene.hang_off(), scene.anchor()).expect("a start");
    let slack = |x: &[V3]| (0..model.cable.n_el).filter(|&e| model.cable.stretch(x, e) <= 1.0).count();
    assert_eq!(slack(&x), 0, "slack segments in the start");
    // the library's start, for the record (measured: 217 of 300 segments
    // slack; not asserted: the scene's own solve copes, slowly)
    if let Some(t) = touchdown_start(&model, scene.hang_off(), scene.anchor()) {
        let worst = (0..model.cable.n_el).map(|e| model.cable.stretch(&t, e) - 1.0).fold(f64::INFINITY, f64::min);
        eprintln!(
            "touchdown_start: {} of {} segments slack, the least strain {worst:.2e}",
            slack(&t),
            model.cable.n_el
        );
    }
    let solved = solve_line_between(&sys, main, joint, anchor, None).unwrap();
    eprintln!(
        "main: {} Newton iterations, {} continuation steps",
        solved.report.iterations, solved.report.continuation_steps
    );
    assert_eq!(solved.report.continuation_steps, 0);
    assert!(solved.report.iterations <= 8, "{}", solved.report.iterations);
}

#[test]
fn bad_systems_with_free_points_are_named() {
    let bridle = std::fs::read_to_string(path("bridle_mooring")).unwrap();
    // two free points joined only to each other: nothing holds them
    let island = format!(
        "{bridle}\n[[point]]\nname = \"buoy_a\"\nkind = \"free\"\nposition = [-100.0, 50.0, -80.0]\nvolume = 1.0\n\n\
         [[point]]\nname = \"buoy_b\"\nkind = \"free\"\nposition = [-100.0, 60.0, -80.0]\nmass = 100.0\n\n\
         [[line]]\nname = \"link\"\ntype = \"chain\"\nfrom = \"buoy_a\"\nto = \"buoy_b\"\nlength = 12.0\nn_elements = 4\n"
    );
    let e = invalid(&island);
    assert!(has(&e, "point.buoy_a", "no path through lines") && has(&e, "point.buoy_b", "no path"), "{e:?}");
    assert!(!e.iter().any(|(f, _)| f == "point.joint"), "the joint is held: {e:?}");
    // a free point's keys on a fixed point; a negative mass
    let e = invalid(&bridle.replacen("kind = \"fixed\"\n", "kind = \"fixed\"\nmass = 5.0\n", 1));
    assert!(has(&e, "point.anchor.mass", "only a free point"), "{e:?}");
    let e = invalid(&bridle.replace("mass = 1000.0", "mass = -1.0"));
    assert!(has(&e, "point.joint.mass", "finite"), "{e:?}");
    // a free point starting under the seabed
    let e = invalid(&bridle.replace("position = [-60.0, 0.0, -30.0]", "position = [-60.0, 0.0, -160.0]"));
    assert!(has(&e, "point.joint.position", "below the seabed"), "{e:?}");
    // a line from a point to itself; a line to an unknown point
    let e =
        invalid(&bridle.replacen("from = \"joint\"\nto = \"fairlead_port\"", "from = \"joint\"\nto = \"joint\"", 1));
    assert!(has(&e, "line.bridle_port", "both its ends are point 'joint'"), "{e:?}");
    let e = invalid(&bridle.replacen("to = \"joint\"", "to = \"jiont\"", 1));
    assert!(has(&e, "line.main.to", "jiont"), "{e:?}");
    // a point no line uses; two points of one name; a name no identifier
    let e = invalid(&format!("{bridle}\n[[point]]\nname = \"spare\"\nkind = \"free\"\nposition = [0.0, 0.0, -50.0]\n"));
    assert!(has(&e, "point.spare", "no line uses"), "{e:?}");
    let e = invalid(&bridle.replace("name = \"fairlead_starboard\"", "name = \"joint\""));
    assert!(e.iter().any(|(f, m)| f.starts_with("point.joint") && m.contains("unique")), "{e:?}");
    let e = invalid(&bridle.replace("\"joint\"", "\"the joint\""));
    assert!(has(&e, "point.the joint", "not an identifier"), "{e:?}");
}

#[test]
fn the_modes_and_the_fmu_take_free_points() {
    let bridle = path("bridle_mooring");
    let sys = case("bridle_mooring");
    // `riser run` and the FMU run them (tests/it/system_free_dynamics.rs, src/fmi/instance.rs)
    // the FMU's path: the system with the master's numerics besides its lines' scenes
    let built = riser::fmi::system::line_scenes(&sys, &[]).unwrap();
    assert_eq!(built.scenes.len(), sys.lines.len());
    assert_eq!(built.free.as_ref(), Some(&sys));
    // the command line: the modes joined at the point (docs/theory.md §17.9; their checks in
    // tests/it/system_modes.rs), the FMU's model description names the point's outputs
    let run = |args: &[&str]| std::process::Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().unwrap();
    let out = run(&["modes", bridle.as_str(), "--count", "3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("joined at free point(s) joint"), "{text}");
    let out = run(&["model-description", "--scene", bridle.as_str()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let md = String::from_utf8_lossy(&out.stdout);
    for (c, vr) in ["x", "y", "z"].iter().zip(200_000..) {
        assert!(md.contains(&format!("name=\"joint.{c}\" valueReference=\"{vr}\"")), "joint.{c}");
    }
}

#[test]
fn the_command_line_prints_the_free_points() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["statics", path("clump_weight_mooring").as_str(), "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let lib = solve_system(&case("clump_weight_mooring"), &[0.0; 6], true).unwrap();
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 1);
    assert_eq!(points[0]["name"], "clump");
    for k in 0..3 {
        assert_eq!(points[0]["position"][k].as_f64().unwrap(), lib.points[0].position[k]);
    }
    assert!(points[0].get("line_force").is_some() && points[0].get("load").is_some());
    // the anchor's line has its anchor force; the line between the clump and the fairlead none
    let lines = v["lines"].as_array().unwrap();
    assert!(lines[0].get("anchor_force").is_some() && lines[0].get("anchor_uplift_angle").is_some());
    assert!(lines[1].get("anchor_force").is_none());
    for l in lines {
        assert!(l["tension_from"].as_f64().unwrap() > 0.0 && l["tension_to"].as_f64().unwrap() > 0.0);
    }
}

/// A buoy whose lines cannot hold it under water (its chain to the anchor
/// removed) has no equilibrium: refused, named, with why; and a system with
/// no vessel point refuses a pose that would move nothing.
#[test]
fn a_system_without_equilibrium_or_vessel_is_named() {
    let buoy = std::fs::read_to_string(path("subsea_buoy_mooring")).unwrap();
    let anchor = buoy.find("[[point]]\nname = \"anchor\"").unwrap();
    let buoy_point = buoy.find("[[point]]\nname = \"buoy\"").unwrap();
    let tether = buoy.find("[[line]]\nname = \"tether\"").unwrap();
    let rope = buoy.find("[[line]]\nname = \"rope\"").unwrap();
    let rising = format!("{}{}{}", &buoy[..anchor], &buoy[buoy_point..tether], &buoy[rope..]);
    let sys = SystemScene::from_toml(&rising, "rising").unwrap_or_else(|e| panic!("{e}"));
    let e = solve_system(&sys, &[0.0; 6], false).unwrap_err();
    assert!(e.contains("free point 'buoy'") && e.contains("rises to the surface"), "{e}");
    // the clump's fairlead made a fixed point: a system on no vessel
    let fixed = std::env::temp_dir().join(format!("riser_no_vessel_{}.toml", std::process::id()));
    let text = std::fs::read_to_string(path("clump_weight_mooring")).unwrap();
    std::fs::write(&fixed, text.replace("kind = \"vessel\"", "kind = \"fixed\"")).unwrap();
    let run = |pose: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_riser"))
            .args(["statics", fixed.to_str().unwrap(), "--pose", pose])
            .output()
            .unwrap()
    };
    let (moved, neutral) = (run("5,0,0,0,0,0"), run("0,0,0,0,0,0"));
    std::fs::remove_file(&fixed).ok();
    let err = String::from_utf8_lossy(&moved.stderr);
    assert!(!moved.status.success() && err.contains("has no vessel point"), "{err}");
    assert!(neutral.status.success(), "{}", String::from_utf8_lossy(&neutral.stderr));
}
