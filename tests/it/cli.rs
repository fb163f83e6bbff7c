//! The command line as users call it: `riser statics`, `riser run` and `riser modes`: text, JSON, CSV and SVG.

use std::process::Command;

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

#[test]
fn statics_json_has_the_documented_fields_and_balances() {
    let out = riser(&["statics", "catenary", "--json", "--set", "n_elements=20"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let top = v["top_tension"].as_f64().unwrap();
    let f: Vec<f64> = v["top_force"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(f.len(), 3);
    assert!(((f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt() - top).abs() < 1e-9 * top);
    assert!(v["bottom_tension"].as_f64().unwrap() > 0.0);
    let shape = v["shape"].as_array().unwrap();
    assert_eq!(shape.len(), 21);
    let last = shape[20].as_array().unwrap();
    // the last row is the anchor: S = L, (60, 0, -70)
    let row: Vec<f64> = last.iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(row.len(), 5);
    assert!((row[0] - 100.0).abs() < 1e-12 && (row[1] - 60.0).abs() < 1e-9 && (row[3] + 70.0).abs() < 1e-9);
}

#[test]
fn statics_writes_shape_csv() {
    let dir = std::env::temp_dir().join(format!("riser-cli-{}", std::process::id()));
    let out = riser(&["statics", "lazy_wave", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(dir.join("shape.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("S,x,y,z,tension,curvature"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 61);
    // the lazy wave's sag and hog bends: curvature at the interior nodes, none at the pinned ends (EI κ = 0)
    let kmax = rows.iter().map(|r| r[5]).fold(0.0, f64::max);
    assert!(kmax > 1e-3 && rows[0][5] < 0.1 * kmax && rows[60][5] < 0.1 * kmax, "curvature {kmax}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("top tension"));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn bad_input_fails_with_a_message_and_no_panic() {
    let out = riser(&["statics", "catenary", "--set", "length=-3"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--set length") && err.contains("is outside [1, 20000] m"), "{err}");
    assert!(!err.contains("panicked"));
    let out = riser(&["statics", "no_such_scene"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a built-in scene"));
}

#[test]
fn run_json_summary_and_csv_columns() {
    let dir = std::env::temp_dir().join(format!("riser-run-{}", std::process::id()));
    let out = riser(&[
        "run",
        "catenary",
        "--set",
        "n_elements=10",
        "--heave",
        "2.5,20",
        "--ramp",
        "10",
        "--duration",
        "2",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for k in ["real_time_factor", "wall_time", "steps", "newton_iterations", "energy_balance_residual"] {
        assert!(v[k].is_number(), "missing {k}");
    }
    assert_eq!(v["steps"].as_u64().unwrap(), 40);
    let tt = &v["top_tension"];
    assert!(tt["min"].as_f64().unwrap() <= tt["mean"].as_f64().unwrap());
    assert!(tt["mean"].as_f64().unwrap() <= tt["max"].as_f64().unwrap());
    assert!(v["energy_balance_relative"].as_f64().unwrap() < 1e-6);
    let ts = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let header = ts.lines().next().unwrap();
    assert_eq!(
        header,
        "t,top_tension,top_force_x,top_force_y,top_force_z,bottom_tension,min_tension,total_energy,\
         kinetic_energy,strain_energy,potential_energy,work_top,work_hydro,dissipated_energy,algorithmic_dissipation,\
         touchdown_s,work_seabed,hang_off_angle,wave_elevation,hang_off_moment,top_moment_x,top_moment_y,top_moment_z,\
         vessel_force_x,vessel_force_y,vessel_force_z,vessel_moment_x,vessel_moment_y,vessel_moment_z,flex_joint_angle,\
         hang_off_x,hang_off_y,hang_off_z,surge,sway,heave,roll,pitch,yaw"
    );
    assert_eq!(ts.lines().count(), 42); // header + t = 0 + 40 steps
    let last_t: f64 = ts.lines().last().unwrap().split(',').next().unwrap().parse().unwrap();
    assert_eq!(last_t, 2.0);
    let shapes = std::fs::read_to_string(dir.join("shapes.csv")).unwrap();
    assert_eq!(shapes.lines().next().unwrap(), "t,S,x,y,z,tension,curvature");
    assert_eq!(shapes.lines().count(), 1 + 8 * 11);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn run_rejects_bad_arguments_with_a_message() {
    let out = riser(&["run", "catenary", "--heave", "2.5,-1", "--duration", "1"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("period"));
    let out = riser(&["run", "catenary", "--duration", "-3"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--duration"));
}

#[test]
fn modes_json_gives_the_periods_and_the_shapes() {
    let out = riser(&["modes", "catenary", "--count", "4", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["scene"], "catenary");
    assert_eq!(v["model"], "rod");
    assert!(v["unknowns"].as_u64().unwrap() > 0 && v["wall_time"].is_number());
    let numbers = |key: &str| -> Vec<f64> {
        v[key].as_array().unwrap_or_else(|| panic!("missing {key}")).iter().map(|x| x.as_f64().unwrap()).collect()
    };
    // "periods" and "shapes" are the names outside scripts rely on
    let periods = numbers("periods");
    assert_eq!(periods.len(), 4);
    assert!(periods.iter().all(|t| t.is_finite() && *t > 0.0), "{periods:?}");
    // lowest frequency first: the periods decrease; the catenary's first period (tests/it/modes.rs: 11.04 s)
    assert!(periods.windows(2).all(|w| w[0] > w[1]), "{periods:?}");
    assert!(periods[0] > 5.0 && periods[0] < 30.0);
    let freq = numbers("frequencies");
    assert!(freq.iter().zip(&periods).all(|(f, t)| (f * t - 1.0).abs() < 1e-12));
    let n_elements = v["n_elements"].as_u64().unwrap() as usize;
    let shapes = v["shapes"].as_array().unwrap();
    assert_eq!(shapes.len(), 4);
    for s in shapes {
        let rows = s.as_array().unwrap();
        assert_eq!(rows.len(), n_elements + 1);
        assert!(rows.iter().all(|r| r.as_array().unwrap().iter().filter(|x| x.is_f64() || x.is_i64()).count() == 8));
    }
    let fractions = v["fractions"].as_array().unwrap();
    assert_eq!(fractions.len(), 4);
    for f in fractions {
        let f: Vec<f64> = f.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        assert_eq!(f.len(), 4);
        assert!((f.iter().sum::<f64>() - 1.0).abs() < 0.02, "{f:?}");
    }
    let dirs: Vec<&str> = v["directions"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
    assert_eq!(dirs[0], "out-of-plane");
    assert_eq!(dirs[1], "in-plane");
}

#[test]
fn modes_text_has_the_header_and_one_row_per_mode() {
    let out = riser(&["modes", "catenary", "--set", "n_elements=20", "--count", "3"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].contains("'catenary'") && lines[0].contains("rod") && lines[0].contains("20 elements"), "{text}");
    assert!(lines[0].contains("free unknowns") && lines[0].contains("without the current"), "{text}");
    assert!(lines[1].contains("period s") && lines[1].contains("direction"), "{text}");
    for (k, dir) in [(1, "out-of-plane"), (2, "in-plane"), (3, "out-of-plane")] {
        let row: Vec<&str> = lines[1 + k].split_whitespace().collect();
        assert_eq!(row[0], k.to_string(), "{text}");
        assert!(row[1].parse::<f64>().unwrap() > 0.0);
        assert_eq!(row[3], dir, "{text}");
    }
    assert!(lines[5].contains("statics and 3 modes in"), "{text}");
    assert!(!text.contains("unstable") && !text.contains("wrote"), "{text}");
}

#[test]
fn modes_of_the_cable_write_csv_and_svg() {
    let dir = std::env::temp_dir().join(format!("riser-cli-modes-{}", std::process::id()));
    let out = riser(&["modes", "catenary", "--set", "model=cable", "--count", "3", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let modes = std::fs::read_to_string(dir.join("modes.csv")).unwrap();
    assert_eq!(modes.lines().count(), 4);
    assert!(modes.starts_with("mode,period_s,frequency_hz,direction,in_plane,out_of_plane,axial,torsion\n"));
    let first: Vec<&str> = modes.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(first.len(), 8);
    assert!(first[1].parse::<f64>().unwrap() > 5.0 && first[3] == "out-of-plane", "{modes}");
    let shapes = std::fs::read_to_string(dir.join("mode_shapes.csv")).unwrap();
    assert!(shapes.starts_with("mode,S,x,y,z,ux,uy,uz,twist\n"));
    assert_eq!(shapes.lines().count(), 1 + 3 * 61);
    assert!(shapes.lines().skip(1).all(|l| l.split(',').filter(|x| x.parse::<f64>().is_ok()).count() == 9));
    let svg = std::fs::read_to_string(dir.join("modes.svg")).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{}", &svg[..80]);
    assert!(svg.trim_end().ends_with("</svg>"));
    for k in 1..=3 {
        assert!(svg.contains(&format!("mode {k}: T = ")), "no panel for mode {k}");
    }
    assert!(!svg.contains("mode 4:"));
    // the cable has no twist: three components a panel
    assert_eq!(svg.matches("<polyline").count(), 3 * 3);
    assert!(!svg.contains("twist"));
    let text = String::from_utf8_lossy(&out.stdout);
    for f in ["modes.csv", "mode_shapes.csv", "modes.svg"] {
        assert!(text.contains(&format!("wrote {}", dir.join(f).display())), "{text}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn modes_bad_input_is_a_clear_error() {
    let out = riser(&["modes", "catenary", "--count", "0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--count must be at least 1"));
    // a line too short to reach its anchor: no static state to vibrate about
    let out = riser(&["modes", "catenary", "--set", "length=10"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("riser: error:") && err.contains("anchor"), "{err}");
    assert!(!err.contains("panicked"));
    for args in [&["modes", "no_such_scene"][..], &["modes", "catenary", "--set", "no_such_parameter=1"]] {
        let out = riser(args);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.starts_with("riser: error:") && !err.contains("panicked"), "{err}");
    }
}

#[test]
fn a_reader_that_goes_away_is_not_a_panic() {
    // `riser modes ... --json | head -c 10`: 350 kB of JSON into a pipe whose
    // reader closes after 10 bytes; the command finishes quietly
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_riser"))
        .args(["modes", "catenary", "--count", "40", "--json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("riser runs");
    let mut head = [0u8; 10];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !err.contains("panicked"), "{:?}: {err}", out.status);
    assert_eq!(&head[..2], b"{\"");
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The catenary, coarse, heaving 2.5 m / 20 s for 60 s.
const SMALL_RUN: [&str; 10] =
    ["run", "catenary", "--set", "n_elements=10", "--set", "time_step=0.1", "--heave", "2.5,20", "--duration", "60"];

/// Issue 31: the default run grows the motion over one period of the
/// slowest motion and reports the steady window from one period after the
/// ramp: the same numbers as `--ramp 20 --window 40,60`, bit for bit; the
/// whole-run extremes are kept under their old keys and enclose the window's.
#[test]
fn default_run_is_ramped_over_one_period_and_reports_its_steady_window() {
    let base = &SMALL_RUN[..];
    let default = json(&riser(&[base, &["--json", "--surge", "1,15"]].concat()));
    let explicit = json(&riser(&[base, &["--json", "--surge", "1,15", "--ramp", "20", "--window", "40,60"]].concat()));
    assert_eq!(default["ramp"].as_f64(), Some(20.0));
    assert_eq!(default["steady"], explicit["steady"]);
    let steady = &default["steady"];
    assert_eq!(steady["window"], serde_json::json!([40.0, 60.0]));
    let w: Vec<f64> = steady["top_tension"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let whole = &default["top_tension"];
    assert!(w[0] <= w[1] && w[1] <= w[2]);
    assert!(whole["min"].as_f64().unwrap() <= w[0] && w[2] <= whole["max"].as_f64().unwrap());
    assert!(steady["min_tension"].as_f64().unwrap() >= default["min_tension"].as_f64().unwrap());
    // the envelope along the line and the hang-off angle, inside what the whole run saw
    let max_t = steady["max_tension"].as_f64().unwrap();
    assert!(steady["min_tension"].as_f64().unwrap() < max_t && max_t >= w[2] - 1e-6 * w[2], "{steady}");
    let angle: Vec<f64> = steady["hang_off_angle"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert!(angle[0] <= angle[1] && angle[1] <= angle[2] && angle[0] > 0.0, "{angle:?}");
    assert!(steady["touchdown_s"].is_null() && steady["max_curvature"].as_f64().unwrap() > 0.0);
    // a flexible pipe has no stresses; nothing is implausible here
    assert!(steady["stress_range"].is_null());
    assert_eq!(steady["warnings"], serde_json::json!([]));
    let text = riser(&[&SMALL_RUN[..], &["--surge", "1,15"]].concat());
    let (stdout, stderr) = (String::from_utf8_lossy(&text.stdout), String::from_utf8_lossy(&text.stderr));
    assert!(stdout.contains("ramped over 20 s") && stdout.contains("steady window 40 to 60 s"), "{stdout}");
    assert!(stdout.contains("whole run, with the start"), "{stdout}");
    assert!(!stderr.contains("warning"), "{stderr}");
}

/// The steady window's steadiness (docs/theory.md §12.3, eq. 12.5): the
/// first and last periods' top tension extremes apart, over the max. The
/// ramp's transient dies out in the line's drag, so the catenary heaved at
/// 10 s drifts at least four times less with the window a period later and
/// is steady to 1e-5 from 40 s (measured 5.7e-5, 8.2e-6, 3.0e-6; 1.5e-4,
/// 1.1e-5, 3.8e-6 with the current in full from t = 0); the JSON's
/// drift is (12.5) of the run's own timeseries.csv; the paper's abrupt start
/// read from t = 0 is not steady (88 %) and says so; a window shorter than
/// two periods has no drift.
#[test]
fn the_window_s_drift_falls_as_the_start_dies_out() {
    let dir = std::env::temp_dir().join(format!("riser-drift-{}", std::process::id()));
    let base = ["run", "catenary", "--set", "n_elements=20", "--set", "time_step=0.05", "--heave", "2.5,10"];
    let run = |extra: &[&str]| json(&riser(&[&base[..], &["--json"], extra].concat()));
    let d = |w: &str| {
        let v = run(&["--duration", "60", "--window", w, "--out", dir.to_str().unwrap()]);
        (v["steady"]["drift"].as_f64().unwrap(), v["steady"]["warnings"].clone())
    };
    let (d20, w20) = d("20,60");
    let (d30, _) = d("30,60");
    // the last run's timeseries.csv: (12.5) over 40 to 60 s below
    let (d40, _) = d("40,60");
    assert!(d20 > 4.0 * d30 && d30 > d40 && d40 < 1e-5, "{d20:e} {d30:e} {d40:e}");
    assert!(!w20.to_string().contains("not steady"), "{w20}");
    let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let mut lines = csv.lines();
    let col = lines.next().unwrap().split(',').position(|c| c == "top_tension").unwrap();
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (f[0], f[col])
        })
        .collect();
    let over = |a: f64, b: f64| {
        let v: Vec<f64> = rows.iter().filter(|(t, _)| *t >= a - 1e-9 && *t <= b + 1e-9).map(|r| r.1).collect();
        (v.iter().cloned().fold(f64::INFINITY, f64::min), v.iter().cloned().fold(0.0, f64::max))
    };
    let ((lo1, hi1), (lo2, hi2), (_, top)) = (over(40.0, 50.0), over(50.0, 60.0), over(40.0, 60.0));
    let own = (lo1 - lo2).abs().max((hi1 - hi2).abs()) / top;
    assert!((own - d40).abs() <= 1e-12, "{own:e} against {d40:e}");
    let _ = std::fs::remove_dir_all(&dir);
    let abrupt = run(&["--duration", "40", "--ramp", "0", "--window", "0,40"]);
    assert!(abrupt["steady"]["drift"].as_f64().unwrap() > 0.5, "{}", abrupt["steady"]);
    assert!(abrupt["steady"]["warnings"].to_string().contains("the steady window is not steady at 1e-2"));
    let short = run(&["--duration", "40", "--window", "25,40"]);
    assert!(short["steady"]["drift"].is_null(), "{}", short["steady"]);
    // a motion that stops inside the window (--heave-until) has no period there
    let stops = run(&["--duration", "60", "--heave-until", "30"]);
    assert!(stops["steady"]["drift"].is_null(), "{}", stops["steady"]);
}

/// The current's start (docs/theory.md §5.11, `current_ramp`): grown over
/// 10 s it settles to the equilibrium the current in full from t = 0 and the
/// current in the statics settle to (the catenary without motion, window
/// 40 to 60 s: means within 1e-7), without the jolt: the whole run dips below
/// that equilibrium by less than a tenth of the jolt's dip (measured 63 N
/// against 1183 N); with `static_current` the ramp does nothing (bit for
/// bit), and unset it is the default 10 s (bit for bit). The cable model
/// likewise (means within 1e-6, a dip under a tenth of the jolt's).
/// `--ramp 0` puts the current in full at t = 0 unless its ramp is set, and
/// the default window waits for the current to have grown.
#[test]
fn the_current_grown_over_current_ramp_settles_where_the_others_do_without_the_jolt() {
    let base = ["run", "catenary", "--duration", "60", "--set", "n_elements=20", "--set", "time_step=0.05"];
    let run = |extra: &[&str]| json(&riser(&[&base[..], &["--json", "--window", "40,60"], extra].concat()));
    let (jolt, grown) = (run(&["--set", "current_ramp=0"]), run(&["--set", "current_ramp=10"]));
    let statics = run(&["--set", "static_current=true"]);
    let mean = |v: &serde_json::Value| v["steady"]["top_tension"][1].as_f64().unwrap();
    let settled = mean(&statics);
    for v in [&jolt, &grown] {
        assert!((mean(v) - settled).abs() < 1e-7 * settled, "{} against {settled}", mean(v));
    }
    let dip = |v: &serde_json::Value| settled - v["top_tension"]["min"].as_f64().unwrap();
    let settled_dip =
        |v: &serde_json::Value, at: &serde_json::Value| mean(at) - v["top_tension"]["min"].as_f64().unwrap();
    assert!(dip(&jolt) > 1000.0 && dip(&grown) < 0.1 * dip(&jolt), "{} {}", dip(&jolt), dip(&grown));
    assert_eq!(run(&["--set", "static_current=true", "--set", "current_ramp=10"])["steady"], statics["steady"]);
    assert_eq!(run(&[])["top_tension"], grown["top_tension"]);
    // `--ramp 0` is the paper's start, the current's too, unless its ramp is set
    let text = |extra: &[&str]| String::from_utf8_lossy(&riser(&[&base[..], extra].concat()).stdout).to_string();
    assert!(text(&["--ramp", "0"]).contains("the current acts in full from t = 0 (current_ramp = 0"));
    assert!(text(&["--ramp", "0", "--set", "current_ramp=10"]).contains("the current grows over its first 10 s"));
    // the cable model grows its current the same way: it settles where its current in the statics does
    let cable = |extra: &[&str]| run(&[&["--set", "model=cable"][..], extra].concat());
    let (c_grown, c_statics) = (cable(&[]), cable(&["--set", "static_current=true"]));
    assert!(
        (mean(&c_grown) - mean(&c_statics)).abs() < 1e-6 * mean(&c_statics),
        "{} {}",
        mean(&c_grown),
        mean(&c_statics)
    );
    assert!(settled_dip(&c_grown, &c_statics) < 0.1 * settled_dip(&cable(&["--set", "current_ramp=0"]), &c_statics));
    // the default window never starts before the current has grown: still water, 12 s, from 10 s (not 6)
    let short = json(&riser(&["run", "catenary", "--duration", "12", "--set", "n_elements=20", "--json"]));
    assert_eq!(short["steady"]["window"], serde_json::json!([10.0, 12.0]));
    let shorter = json(&riser(&["run", "catenary", "--duration", "8", "--set", "n_elements=20", "--json"]));
    assert!(shorter["steady"]["warnings"].to_string().contains("ends before the current has grown"), "{shorter}");
}

/// Issue 31: `--ramp 0` is the paper's abrupt start, the library's Heave
/// with no ramp and the current in full from t = 0 (`current_ramp = 0`,
/// theory §5.11), bit for bit (the same stepping as `riser run`).
#[test]
fn ramp_zero_is_the_papers_abrupt_start_bit_for_bit() {
    use riser::sim::{Heave, Simulation};
    let cli = json(&riser(&[&SMALL_RUN[..], &["--json", "--ramp", "0"]].concat()));
    let scene = riser::scene::Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&["n_elements=10", "time_step=0.1", "current_ramp=0"])
        .unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 0.0 };
    sim.start(heave.at(0.0));
    let n = riser::sim::internal_steps(60.0, 0.1).unwrap();
    let mut samples = vec![(sim.outputs().time, sim.outputs().top_tension)];
    for k in 1..=n {
        sim.advance_to(riser::sim::internal_step_end(0.0, 60.0, 0.1, k, n), &|t| heave.at(t)).unwrap();
        samples.push((sim.outputs().time, sim.outputs().top_tension));
    }
    let tension: Vec<f64> = samples.iter().map(|s| s.1).collect();
    let max = tension.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let min = tension.iter().cloned().fold(f64::INFINITY, f64::min);
    // the time mean, the trapezoid rule over the run
    let (mut integral, mut span) = (0.0, 0.0);
    for w in samples.windows(2) {
        integral += 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0);
        span += w[1].0 - w[0].0;
    }
    let mean = integral / span;
    assert_eq!(cli["ramp"].as_f64(), Some(0.0));
    assert_eq!(cli["top_tension"], serde_json::json!({"min": min, "mean": mean, "max": max}));
    // the velocity jump: a peak far above the static tension
    assert!(max > 2.0 * sim.statics.top_tension, "max {max}");
}

/// Issue 31: the design numbers in `riser statics --json` (README,
/// "Summaries"), and a plausible model warns of nothing.
#[test]
fn statics_json_has_the_design_numbers_and_no_warning_for_plausible_scenes() {
    for scene in ["catenary", "steel_catenary"] {
        let out = riser(&["statics", scene, "--json"]);
        let v = json(&out);
        for k in ["hang_off_angle", "max_curvature", "max_curvature_s", "min_bend_radius", "max_bending_moment"] {
            assert!(v[k].as_f64().is_some_and(|x| x > 0.0), "{scene}: {k} = {}", v[k]);
        }
        assert_eq!(v["warnings"], serde_json::json!([]), "{scene}");
        assert!(!String::from_utf8_lossy(&out.stderr).contains("warning"), "{scene}");
        let touches = scene == "steel_catenary";
        assert_eq!(v["touchdown_s"].is_number(), touches, "{scene}");
        assert_eq!(v["touchdown_x"].is_number(), touches, "{scene}");
        // the steel pipe has stresses, the flexible one (EI far below a tube's) none
        assert_eq!(v["max_stress"].is_number(), touches, "{scene}");
    }
}

/// Issue 31: each implausible model gives its warning, on stderr and in
/// the JSON's `warnings`.
#[test]
fn implausible_models_warn() {
    let cases: [(&[&str], &[&str]); 5] = [
        // the anchor beyond the line's reach: a straight, stretched line
        (
            &["statics", "catenary", "--set", "anchor_x=75"],
            &["beyond the line's unstretched length", "axial strain reaches"],
        ),
        // 40 m elements against a 17 m bending length at the touchdown
        (&["statics", "steel_catenary", "--set", "n_elements=10"], &["bending length", "n_elements = 47"]),
        // 16.7 m: fewer than two per bending length
        (&["statics", "steel_catenary", "--set", "n_elements=24"], &["bending length", "n_elements = 47"]),
        // a taut line's lowest point is its anchor, no touchdown: no mesh warning, but the reach
        (&["statics", "steel_catenary", "--set", "anchor_x=355"], &["beyond the line's unstretched length"]),
        // the abrupt start of a large heave puts the lazy wave in compression
        (
            &[
                "run",
                "lazy_wave",
                "--set",
                "n_elements=20",
                "--set",
                "time_step=0.1",
                "--heave",
                "3,12",
                "--ramp",
                "0",
                "--duration",
                "30",
            ],
            &["compression in the steady window"],
        ),
    ];
    for (args, expected) in cases {
        let out = riser(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        for e in expected {
            assert!(stderr.contains(e), "{args:?}: '{e}' not in {stderr}");
        }
        if args.contains(&"anchor_x=355") {
            assert!(!stderr.contains("bending length"), "{args:?}: {stderr}");
        }
        let v = json(&riser(&[args, &["--json"]].concat()));
        let list = if args[0] == "run" { &v["steady"]["warnings"] } else { &v["warnings"] };
        let text = list.to_string();
        assert!(expected.iter().all(|e| text.contains(e)), "{args:?}: {text}");
    }
}

/// Issue 31: messages in the user's terms (a number, a whole number), not
/// Rust's; a negative duration is refused as such, not as a flag.
#[test]
fn messages_speak_the_users_terms() {
    let dir = std::env::temp_dir().join(format!("riser-terms-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = String::from_utf8(riser(&["scene", "catenary"]).stdout).unwrap();
    for (from, to, expected) in [
        ("n_elements = 60", "n_elements = 2.5", "expected a whole number"),
        ("length = 100.0", "length = \"long\"", "expected a number"),
        ("static_current = false", "static_current = 1", "expected true or false"),
    ] {
        assert!(scene.contains(from), "{from}");
        let path = dir.join("bad.toml");
        std::fs::write(&path, scene.replace(from, to)).unwrap();
        let err = String::from_utf8_lossy(&riser(&["statics", path.to_str().unwrap()]).stderr).to_string();
        assert!(err.contains(expected), "{to}: {err}");
        assert!(!["usize", "f64", "u32", "invalid type"].iter().any(|r| err.contains(r)), "{to}: {err}");
    }
    let err = String::from_utf8_lossy(&riser(&["run", "catenary", "--duration", "-5"]).stderr).to_string();
    assert!(err.contains("--duration must be a positive number of seconds, got -5"), "{err}");
    let out = riser(&["run", "catenary", "--heave", "2.5,20", "--duration", "100", "--window", "120,200"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success() && err.contains("--window 120,200 must lie within the run, 0 to 100 s"), "{err}");
    // a negative amplitude is a number, not a flag
    let v = json(&riser(&[&SMALL_RUN[..6], &["--heave", "-2.5,20", "--duration", "1", "--json"]].concat()));
    assert_eq!(v["completed"], true);
    // riser params: the default scene's value of each parameter
    let v = json(&riser(&["params", "--json"]));
    let row = |n: &str| v.as_array().unwrap().iter().find(|r| r["name"] == n).unwrap().clone();
    assert_eq!(row("n_elements")["value"], "60");
    assert_eq!(row("model")["value"], "rod");
    let v = json(&riser(&["params", "steel_catenary", "--json"]));
    assert!(v.as_array().unwrap().iter().any(|r| r["name"] == "length" && r["value"] == "400"));
    std::fs::remove_dir_all(dir).ok();
}

/// Issue 31: the stress range of a run. A vertical steel line stretched
/// between its ends, heaved 1 cm / 10 s (quasi-static: its axial period is
/// 0.08 s): at the top Gauss point the outer-fibre stress range is the top
/// tension's range over the wall area (12.1), within 1e-3 (the inertia and
/// weight of the 0.35 m above it); the JSON's `stress_range` is the largest
/// row of stress_range.csv.
#[test]
fn the_stress_range_of_a_stretched_line_is_its_tension_range_over_the_wall() {
    let (ea, ei, d) = (3.38e9, 2.71e7, 0.2731);
    let dir = std::env::temp_dir().join(format!("riser-stress-{}", std::process::id()));
    let v = json(&riser(&[
        "run",
        "catenary",
        "--set",
        &format!("axial_stiffness={ea}"),
        "--set",
        &format!("bending_stiffness={ei}"),
        "--set",
        &format!("outer_diameter={d}"),
        "--set",
        "anchor_x=0",
        "--set",
        "anchor_z=-100.05",
        "--set",
        "n_elements=20",
        "--heave",
        "0.01,10",
        "--duration",
        "40",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]));
    let area = std::f64::consts::PI * (d * d - (16.0 * ei / ea - d * d)) / 4.0;
    let series = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let t0 = v["steady"]["window"][0].as_f64().unwrap();
    let top: Vec<f64> = series
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(2).map(|x| x.parse::<f64>().unwrap()).collect::<Vec<_>>())
        .filter(|r| r[0] >= t0 - 1e-9)
        .map(|r| r[1])
        .collect();
    let range = (top.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - top.iter().cloned().fold(f64::INFINITY, f64::min))
        / area;
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(dir.join("stress_range.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    println!("top Gauss point: {:.6e} Pa, top tension range / A {range:.6e} Pa", rows[0][3]);
    assert!((rows[0][3] - range).abs() <= 1e-3 * range);
    let largest = rows.iter().map(|r| r[3]).fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(v["steady"]["stress_range"].as_f64(), Some(largest));
    std::fs::remove_dir_all(dir).ok();
}

/// The steady window waits for the sea as for the motion (theory §12.3):
/// one period after the sea's ramp (a 12 s wave, ramped over 12 s: from
/// 24 s), the later of the two with a heave (20 s ramp and period: 40 s),
/// and in still water without motion the second half of the run; the
/// default's statistics are those of the explicit window, bit for bit.
#[test]
fn the_steady_window_waits_for_the_sea_and_in_still_water_is_the_second_half() {
    let base = ["run", "catenary", "--set", "n_elements=10", "--set", "time_step=0.1", "--duration", "60", "--json"];
    let sea = ["--set", "wave_kind=airy", "--set", "wave_height=4", "--set", "wave_period=12"];
    let window = |extra: &[&str]| json(&riser(&[&base[..], extra].concat()))["steady"].clone();
    let in_waves = window(&sea);
    assert_eq!(in_waves["window"], serde_json::json!([24.0, 60.0]));
    assert_eq!(in_waves, window(&[&sea[..], &["--window", "24,60"]].concat()));
    let with_heave = window(&[&sea[..], &["--heave", "2.5,20"]].concat());
    assert_eq!(with_heave["window"], serde_json::json!([40.0, 60.0]));
    assert_eq!(window(&[])["window"], serde_json::json!([30.0, 60.0]));
}

/// Fewer than 20 steps a period of the motion warns (theory §12.3), and
/// the response shows why: at 10 steps a period (dt 2 s, a 20 s heave) the
/// steady window's largest top tension is more than 2 % off the run at
/// 200 steps a period (3.4 % measured; 10 % with the current in full from
/// t = 0, whose jolt the 2 s step resolved worst), where 40 steps (0.5 s)
/// are within 0.2 % (0.065 %) and do not warn. A sea's period warns the same, in
/// statics too.
#[test]
fn a_time_step_of_fewer_than_twenty_a_period_warns_and_misses_the_response() {
    let run = |dt: &str| {
        let v = json(&riser(&[&SMALL_RUN[..], &["--json", "--set", &format!("time_step={dt}")]].concat()));
        let max = v["steady"]["top_tension"][2].as_f64().unwrap();
        let warned = v["steady"]["warnings"].as_array().unwrap().iter().any(|w| {
            let w = w.as_str().unwrap();
            w.contains("steps a period of the hang-off's 20 s motion") && w.contains("time_step <= 1.000 s")
        });
        (max, warned)
    };
    let (fine, coarse, long) = (run("0.1"), run("0.5"), run("2"));
    assert!(!fine.1 && !coarse.1 && long.1, "{fine:?} {coarse:?} {long:?}");
    assert!((coarse.0 - fine.0).abs() < 2e-3 * fine.0, "{coarse:?} {fine:?}");
    assert!((long.0 - fine.0).abs() > 2e-2 * fine.0, "{long:?} {fine:?}");
    let sea = ["--set", "wave_kind=airy", "--set", "wave_height=2", "--set", "wave_period=10", "--json"];
    let statics = |dt: &str| {
        json(&riser(&[&["statics", "catenary", "--set", &format!("time_step={dt}")], &sea[..]].concat()))["warnings"]
            .to_string()
    };
    assert!(statics("1").contains("steps a period of the sea's 10 s motion"), "{}", statics("1"));
    assert!(!statics("0.5").contains("steps a period"), "{}", statics("0.5"));
}

/// A line lighter than the water it displaces warns, naming by how much
/// (the catenary with its diameter given 10x: buoyancy ρ g π D²/4 L above
/// the weight m g L, to the printed digit); the lazy wave, whose modules
/// lift a part of a heavy line, does not.
#[test]
fn a_line_that_floats_warns_and_a_lazy_wave_does_not() {
    let scene = riser::scene::Scene::builtin("catenary").unwrap();
    let (l, m, d) = (scene.line.length, scene.line.mass_per_length, 10.0 * scene.line.outer_diameter);
    let env = &scene.environment;
    let up = (env.water_density * std::f64::consts::PI * d * d / 4.0 - m) * env.gravity * l;
    let v = json(&riser(&["statics", "catenary", "--json", "--set", &format!("outer_diameter={d}")]));
    let w = v["warnings"].to_string();
    assert!(w.contains(&format!("the line floats: its buoyancy exceeds its weight by {:.3} kN", up / 1e3)), "{w}");
    let lazy = json(&riser(&["statics", "lazy_wave", "--json"]))["warnings"].to_string();
    assert!(!lazy.contains("floats"), "{lazy}");
}

/// docs/theory.md §5.10: the lazy wave heaved 2.5 m / 30 s in its current,
/// in full from t = 0 (`current_ramp = 0`: the jolt seeds it), with 160
/// elements at dt 0.003125 s grows a high-frequency oscillation that the
/// velocity filter of ρ∞ = 0.8 feeds (the energy balance closed):
/// `riser run` warns over its steady window (the run's second half here),
/// naming the two remedies; with either of them, and at dt 0.0125 s, the
/// oscillation decays and there is no warning.
#[test]
fn a_growing_high_frequency_oscillation_is_warned_of() {
    let base = [
        "run",
        "lazy_wave",
        "--heave",
        "2.5,30",
        "--duration",
        "40",
        "--set",
        "n_elements=160",
        "--set",
        "current_ramp=0",
    ];
    let grows = |extra: &[&str]| {
        let out = riser(&[&base[..], extra].concat());
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        stderr.contains("a high-frequency oscillation grows through the run").then_some(stderr)
    };
    let runs: [&[&str]; 4] = [
        &["--set", "time_step=0.003125"],
        &["--set", "time_step=0.003125", "--set", "rho_infinity=1"],
        &["--set", "time_step=0.003125", "--set", "structural_damping=0.003"],
        &["--set", "time_step=0.0125"],
    ];
    // the four runs are independent: two at a time (the test machine's two cores)
    let grows = &grows;
    let (a, b) = std::thread::scope(|scope| {
        let a = scope.spawn(move || (grows(runs[0]), grows(runs[3])));
        let b = scope.spawn(move || (grows(runs[1]), grows(runs[2])));
        (a.join().unwrap(), b.join().unwrap())
    });
    let results = [a.0, b.0, b.1, a.1];
    let warned = results[0].as_ref().expect("no warning at dt 0.003125 s with rho_infinity 0.8");
    assert!(warned.contains("structural_damping") && warned.contains("rho_infinity=1"), "{warned}");
    for (extra, result) in runs.iter().zip(&results).skip(1) {
        assert!(result.is_none(), "{extra:?}");
    }
}

/// The number that follows `key` in `text` (up to a space, a comma, a colon or a parenthesis).
fn number_after(text: &str, key: &str) -> f64 {
    let rest = &text[text.find(key).unwrap_or_else(|| panic!("'{key}' not in {text}")) + key.len()..];
    let end = rest.find([' ', ',', ':', ')']).unwrap_or(rest.len());
    rest[..end].parse().unwrap_or_else(|e| panic!("'{}' after '{key}': {e}", &rest[..end]))
}

/// Issue 52: the steel catenary with its anchor at 320 m (35 m of line on
/// the seabed at rest, no warning) surged 15 m / 30 s, grown over 10 s, for
/// 30 s: as the hang-off draws away the line leaves its seabed (its
/// timeseries' `touchdown_s` = L from 16.25 to 26.2 s) and lifts its anchor.
/// `riser run` warns once, in `steady.warnings` and on stderr: from t =
/// 16.85 s, the largest uplift 5.63 deg at 21 s. Checked against the run's
/// own timeseries.csv (no touchdown at both times; the bottom tension
/// printed at the largest to 1 N, and its vertical part |F| sin(angle) to
/// the angle's printed digit) and against the statics with the anchor at
/// the farthest excursion, 335 m (5.48 deg: the motion adds 0.15 deg),
/// within 0.5 deg. The scene as it is (292 m, 120 m on the seabed), surged
/// alike, warns of no anchor.
#[test]
fn an_anchor_that_the_motion_lifts_off_its_seabed_warns_in_the_run() {
    let dir = std::env::temp_dir().join(format!("riser-anchor-lift-{}", std::process::id()));
    let run = |anchor_x: &str, out: Option<&str>| {
        let mut args = vec!["run", "steel_catenary", "--set", anchor_x, "--surge", "15,30", "--ramp", "10"];
        args.extend(["--duration", "30", "--json"]);
        args.extend(out.map(|o| ["--out", o]).into_iter().flatten());
        let out = riser(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        (json(&out), stderr)
    };
    let (v, stderr) = run("anchor_x=320", dir.to_str());
    let warnings: Vec<String> =
        v["steady"]["warnings"].as_array().unwrap().iter().map(|w| w.as_str().unwrap().to_string()).collect();
    let lifts: Vec<&String> = warnings.iter().filter(|w| w.contains("the anchor lifts off the seabed")).collect();
    assert_eq!(lifts.len(), 1, "{warnings:?}");
    assert!(!warnings.iter().any(|w| w.contains("is lifted off")), "not in the statics: {warnings:?}");
    let m = lifts[0];
    assert!(stderr.contains(m.as_str()), "{stderr}");
    assert!(m.contains("so that it touches down through the motion"), "{m}");
    let (first, t_max) = (number_after(m, "from t = "), number_after(m, ": at t = "));
    let (angle, vertical, tension) =
        (number_after(m, "up at "), number_after(m, "vertical force of "), number_after(m, "(of "));
    println!("first {first} s, largest {angle} deg at {t_max} s, {vertical} kN of {tension} kN");
    // the run's own timeseries: no touchdown at either time, the bottom tension at the largest
    let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<f64>> = csv.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    let at = |t: f64| rows.iter().find(|r| (r[0] - t).abs() < 6e-3).unwrap_or_else(|| panic!("no row at {t}"));
    let (td, bt) = (col("touchdown_s"), col("bottom_tension"));
    let off: Vec<f64> = rows.iter().filter(|r| r[td] >= 400.0).map(|r| r[0]).collect();
    println!("no touchdown from {} to {} s", off[0], off[off.len() - 1]);
    assert!(first >= off[0] && first <= t_max && t_max <= off[off.len() - 1], "{first} {t_max} {off:?}");
    assert!(at(first)[td] >= 400.0 && at(t_max)[td] >= 400.0);
    let f = at(t_max)[bt];
    assert!((tension * 1e3 - f).abs() <= 0.6, "{tension} kN against {f} N");
    let slack = f * 0.005f64.to_radians() + 1.0;
    assert!((vertical * 1e3 - f * angle.to_radians().sin()).abs() <= slack, "{vertical} kN at {angle} deg of {f} N");
    // quasi-statically: the statics with the anchor 15 m farther out
    let s = json(&riser(&["statics", "steel_catenary", "--set", "anchor_x=335", "--json"]));
    let b: Vec<f64> = s["bottom_force"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let quasi = b[2].atan2(b[0].hypot(b[1])).to_degrees();
    println!("quasi-static at 335 m: {quasi:.3} deg");
    assert!((angle - quasi).abs() < 0.5, "{angle} deg against {quasi}");
    std::fs::remove_dir_all(&dir).ok();
    // the scene's own anchor keeps its touchdown through the same motion
    let (v, stderr) = run("anchor_x=292", None);
    assert!(!v["steady"]["warnings"].to_string().contains("anchor lifts") && !stderr.contains("anchor lifts"));
}
