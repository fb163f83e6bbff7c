//! Shared helpers for the integration tests.
//!
//! Not every test uses every helper, hence the blanket `dead_code` allowance.
#![allow(dead_code)]

pub mod reference;
pub mod spectral;
pub mod system;

use riser::math::V3;

/// A light elastic line's properties (scene TOML): EA 1e6 N, 0.01 kg/m, no
/// bending, no torsion, no drag, no added mass: a taut spring of EA/L.
pub const LIGHT_ELASTIC_LINE: &str = "mass_per_length = 0.01
outer_diameter = 0.001
axial_stiffness = 1.0e6
bending_stiffness = 0.0
torsional_stiffness = 0.0
cd_normal = 0.0
cd_tangential = 0.0
ca_normal = 0.0
";
use riser::model::cable::CableModel;
use riser::model::{DynamicOptions, HangOff, State};
use riser::scene::Scene;
use riser::solve::Integrator;

/// The cable's step tangent against central differences of the step
/// residual, from the static state of `scene` (a cable) given a moving,
/// out-of-plane velocity and a generic trial configuration, in the scene's
/// waves if it has any (at full height from t = 0 with `wave_ramp=0`): the
/// largest error relative to each row's largest entry.
pub fn cable_step_tangent_error(scene: &Scene) -> f64 {
    let rep = riser::sim::report::solve_scene(scene).unwrap();
    let model = CableModel::from_scene(scene).with_sea(riser::loads::waves::sea_of(scene, 0.0).unwrap());
    let opts = DynamicOptions { time_step: 0.05, ..Default::default() };
    let mut integ = Integrator::new(model, opts, scene.hang_off()).unwrap();
    let mut prev = State::at_rest(rep.solution.config.clone(), 0.0);
    for (a, v) in prev.vel.iter_mut().enumerate() {
        *v = V3::new(0.3, 0.2, -0.1) * (a as f64 * 0.7).sin();
    }
    let h = 0.05;
    let target = HangOff::translation(V3::new(0.05, 0.0, 0.1), V3::new(0.2, 0.0, 0.6));
    let mut cfg = integ.begin_step(&prev, h, target);
    let n_nodes = cfg.x.len();
    for (a, x) in cfg.x.iter_mut().enumerate().skip(1).take(n_nodes - 2) {
        *x += V3::new(0.01, -0.008, 0.004) * (a as f64).cos();
    }
    let n = integ.n_unknowns();
    integ.step_residual(&prev, &cfg, h, target, true);
    let k: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| integ.tangent_entry(i, j)).collect()).collect();
    let eps = 1e-7;
    let mut worst = 0.0f64;
    for j in 3..n - 3 {
        let mut col = [vec![], vec![]];
        let mut moved = [0.0; 2];
        for (s, sign) in [1.0, -1.0].into_iter().enumerate() {
            let mut du = vec![0.0; n];
            du[j] = sign * eps;
            let mut c = cfg.clone();
            integ.apply_step_increment(&prev, &mut c, &du);
            moved[s] = c.x[j / 3][j % 3];
            col[s] = integ.step_residual(&prev, &c, h, target, false);
        }
        // the step as represented: coordinates of a few hundred metres
        // quantise a 1e-7 m step by ~3e-7 of itself
        let step = moved[0] - moved[1];
        for i in 3..n - 3 {
            let fd = (col[0][i] - col[1][i]) / step;
            let row_scale = k[i].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let rel = (fd - k[i][j]).abs() / row_scale;
            if rel > 1e-6 {
                eprintln!("K[{i}][{j}] = {:.6e}, FD {fd:.6e}, row scale {row_scale:.3e}", k[i][j]);
            }
            worst = worst.max(rel);
        }
    }
    worst
}

/// A neutrally buoyant vertical line (the catenary's D with its displaced
/// mass, 81.0 kg/m) stretched 1 cm between its ends: T = EA δL/L = 79.6 kN
/// along it; EI 1e6 N m² gives a bending length λ = √(EI/T) = 3.5 m; 200
/// elements (h = λ/7); `sets` overrides on top (tests/it/hang_off_end.rs,
/// tests/it/hang_off_stiffness6.rs).
pub fn taut_vertical_line(sets: &[&str]) -> Scene {
    let mass = 1025.0 * std::f64::consts::PI * 0.3172f64.powi(2) / 4.0;
    let mut all = vec![
        format!("mass_per_length={mass}"),
        "bending_stiffness=1e6".into(),
        "anchor_x=0".into(),
        "anchor_z=-100.01".into(),
        "n_elements=200".into(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    Scene::builtin("catenary").unwrap().with_overrides(&all).unwrap()
}

/// The transverse natural frequencies (Hz, both planes, ascending) among
/// the `count` lowest modes of `scene` about its static state.
pub fn transverse_frequencies(scene: &Scene, count: usize) -> Vec<f64> {
    use riser::model::linearized::Direction;
    let report = riser::sim::modes::scene_modes(scene, count).unwrap();
    let mut f: Vec<f64> = report
        .modes
        .iter()
        .filter(|m| matches!(m.direction, Direction::InPlane | Direction::OutOfPlane))
        .map(|m| m.frequency)
        .collect();
    f.sort_by(f64::total_cmp);
    f
}

/// Asserts that the transverse frequencies `got` (two planes per
/// frequency, as [`transverse_frequencies`] gives them) match `exact` (Hz)
/// within the relative `tol`, naming `what`.
pub fn assert_plane_pairs(what: &str, got: &[f64], exact: &[f64], tol: f64) {
    assert!(got.len() >= 2 * exact.len(), "{what}: only {} transverse modes", got.len());
    for (n, e) in exact.iter().enumerate() {
        for f in &got[2 * n..2 * n + 2] {
            println!("{what} mode {}: {f:.5} Hz, closed form {e:.5} Hz ({:+.3} %)", n + 1, 100.0 * (f - e) / e);
            assert!(((f - e) / e).abs() <= tol, "{what} mode {}: {f} vs {e}", n + 1);
        }
    }
}

/// Newton with backtracking (halving the step while the off-balance grows;
/// the cable's stiff axial law makes plain Newton overshoot) from `q` for
/// R_free(q) = `target` (dead loads; zero at a static state), the supports
/// held where `q` has them, down to 1e-13 or the round-off floor. The
/// off-balance is `measure` of R − target. Returns the solution and its
/// off-balance.
pub fn solve_with_dead_loads<P: riser::model::statics::StaticEquations>(
    p: &P,
    mut q: P::Config,
    target: &[f64],
    measure: impl Fn(&[f64]) -> f64,
) -> (P::Config, f64) {
    let n = p.n_dof();
    let mut sys = p.new_system().unwrap();
    let (mut r, mut du) = (vec![0.0; n], vec![0.0; n]);
    let off_balance = |q: &P::Config, r: &mut [f64], sys: Option<&mut riser::math::band::BandedSystem>| {
        p.residual(q, r, sys);
        for (ri, ti) in r.iter_mut().zip(target) {
            *ri -= ti;
        }
        measure(r)
    };
    let mut rel = off_balance(&q, &mut r, Some(&mut sys));
    for _ in 0..60 {
        if rel < 1e-13 {
            break;
        }
        p.correction(&mut sys, &mut r, &mut du).unwrap();
        let mut step = 1.0;
        let mut trial = q.clone();
        p.apply_increment(&mut trial, &du);
        let mut trial_rel = off_balance(&trial, &mut r, None);
        while trial_rel > rel && step > 1e-6 {
            step *= 0.5;
            trial = q.clone();
            let part: Vec<f64> = du.iter().map(|v| v * step).collect();
            p.apply_increment(&mut trial, &part);
            trial_rel = off_balance(&trial, &mut r, None);
        }
        if trial_rel >= rel && rel < 1e-10 {
            break; // at the round-off floor
        }
        q = trial;
        rel = off_balance(&q, &mut r, Some(&mut sys));
    }
    (q, rel)
}

/// `riser` with these arguments (it must succeed); its stdout parsed as JSON.
pub fn riser_json(args: &[&str]) -> serde_json::Value {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// An FMU instance of the built-in `scene` with the string parameters
/// `strings` and the real ones `reals` set, through its initialisation: its
/// outputs then read the static state.
pub fn fmu_at_static_state(
    scene: &str,
    strings: &[(&str, &str)],
    reals: &[(&str, f64)],
) -> riser::fmi::instance::Instance {
    fmu_at_static_state_logged(scene, strings, reals, None)
}

/// [`fmu_at_static_state`] with logging on to `logger`, when given.
pub fn fmu_at_static_state_logged(
    scene: &str,
    strings: &[(&str, &str)],
    reals: &[(&str, f64)],
    logger: Option<riser::fmi::instance::Logger>,
) -> riser::fmi::instance::Instance {
    use riser::fmi::instance::{Instance, Status, Value};
    use riser::fmi::vars::{GUID, vr_of};
    let on = logger.is_some();
    let logger = logger.unwrap_or_else(|| std::sync::Arc::new(|_, _, _: &str| {}));
    let mut i = Instance::new("t", GUID, None, logger, on).unwrap();
    assert_eq!(i.set_param(vr_of("scene").unwrap(), Value::String(scene.into())), Status::Ok);
    for (name, v) in strings {
        assert_eq!(i.set_param(vr_of(name).unwrap(), Value::String(v.to_string())), Status::Ok, "{name}");
    }
    for (name, v) in reals {
        assert_eq!(i.set_real(vr_of(name).unwrap(), *v), Status::Ok, "{name}");
    }
    assert_eq!(i.setup_experiment(0.0), Status::Ok);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    i
}

/// The fluids of the wall tests: oil of 800 kg/m³ at 20 MPa at the hang-off
/// inside, the sea (1025 kg/m³, g 9.81 m/s², its surface at z = 0) outside.
pub fn oil_inside_sea_outside() -> riser::sim::design::Fluids {
    riser::sim::design::Fluids {
        water_density: 1025.0,
        gravity: 9.81,
        water_surface_z: 0.0,
        internal_density: 800.0,
        internal_pressure: 2e7,
    }
}

/// A bare pipe of 128.3 kg/m and outer diameter `d` (m; buoyancy's), its
/// steel `wall`, stiffnesses [EA, EI, GJ] and strengths f_y, f_u (Pa), with
/// no drag, added mass or rotary inertia.
pub fn pipe_properties(
    d: f64,
    wall: riser::scene::sections::Wall,
    [ea, ei, gj]: [f64; 3],
    yield_stress: Option<f64>,
    tensile_strength: Option<f64>,
) -> riser::scene::sections::LineProperties {
    riser::scene::sections::LineProperties {
        mass_per_length: 128.3,
        displaced_area: std::f64::consts::PI * d * d / 4.0,
        added_mass_area: 0.0,
        drag_normal: 0.0,
        drag_tangential: 0.0,
        diameter: d,
        axial_stiffness: ea,
        bending_stiffness: ei,
        torsional_stiffness: gj,
        rotary_inertia: 0.0,
        pipe_diameter: d,
        wall: Some(wall),
        yield_stress,
        tensile_strength,
    }
}
