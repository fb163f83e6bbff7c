//! DNV-OS-F201's LRFD combined-loading check (net internal overpressure,
//! docs/theory.md §12.4, (12.10)–(12.14)) against the standard's formula
//! written out here, with numbers typed in, independently of
//! src/sim/lrfd.rs: a pipe at a known moment, tension and pressure, static
//! and with an environmental part; the steel catenary with oil at 20 MPa,
//! whose largest utilisation is the one computed here from riser's own
//! tension, curvature and pressures along the line (static, and in a run
//! against its static state); the factors moving it as the formula says;
//! the FMU's outputs at the static state against `riser statics`; a line
//! without net internal overpressure reported as not checked.

use crate::common::{
    fmu_at_static_state, fmu_at_static_state_logged, oil_inside_sea_outside, pipe_properties, riser_json,
};
use nalgebra::Vector3;
use riser::model::outputs::LinePoint;
use riser::model::sections::PerElement;
use riser::scene::sections::Wall;
use riser::scene::{Model, Scene};
use riser::sim::Simulation;
use riser::sim::design::{Design, LrfdPeak};
use riser::sim::lrfd::LrfdFactors;
use std::f64::consts::PI;

/// 10¾ in X65 steel pipe, 20.6 mm wall (steel_catenary's), E 207 GPa.
const D: f64 = 0.2731;
const T2: f64 = 0.0206;
/// API 5L X65's SMYS and SMTS, Pa.
const FY: f64 = 448e6;
const FU: f64 = 531e6;
/// steel_catenary's EI, N m².
const EI: f64 = 2.71e7;

/// The standard's criterion by hand for net internal overpressure `dp`
/// (Pa), design moment `md` (N m), design effective tension `td` (N) and
/// γ_SC γ_m `gamma`: p_b(t₂) = (2/√3)(2 t₂/(D − t₂)) min(f_y, f_u/1.15);
/// q_h = (Δp/p_b) 2/√3; D/t₂ = 13.26 < 15, so β = 0.4 + q_h;
/// α_c = (1 − β) + β f_u/f_y; M_k = f_y α_c (D − t₂)² t₂;
/// T_k = f_y α_c π (D − t₂) t₂;
/// U = γ_SC γ_m [(|M_d|/M_k) √(1 − (Δp/p_b)²) + (T_d/T_k)²] + (Δp/p_b)².
fn by_hand(dp: f64, md: f64, td: f64, gamma: f64) -> f64 {
    const { assert!(D / T2 < 15.0) };
    let p_b = 2.0 / 3f64.sqrt() * (2.0 * T2 / (D - T2)) * FY.min(FU / 1.15);
    let q_h = dp / p_b * 2.0 / 3f64.sqrt();
    let beta = 0.4 + q_h;
    let alpha_c = (1.0 - beta) + beta * FU / FY;
    let m_k = FY * alpha_c * (D - T2).powi(2) * T2;
    let t_k = FY * alpha_c * PI * (D - T2) * T2;
    let pressure = dp / p_b;
    gamma * (md.abs() / m_k * (1.0 - pressure * pressure).sqrt() + (td / t_k).powi(2)) + pressure * pressure
}

/// A one-element line of the pipe, its wall and strengths given, with oil
/// (800 kg/m³ at 20 MPa at the hang-off) inside and water outside.
fn one_element(factors: LrfdFactors) -> Design {
    let wall = Wall { outer_diameter: D, thickness: T2, youngs_modulus: 2.07e11 };
    let props = pipe_properties(D, wall, [3.38e9, EI, 2.0e7], Some(FY), Some(FU));
    Design::of_properties(PerElement::from_elements(vec![props]), Model::Rod, 400.0, 1)
        .with_fluids(oil_inside_sea_outside(), 1.0)
        .with_lrfd(factors)
}

/// A point 300 m below the hang-off (at z = 0) and the still water surface.
fn point(tension: f64, curvature: [f64; 2]) -> LinePoint {
    LinePoint { element: 0, s: 300.0, position: Vector3::new(50.0, 0.0, -300.0), tension, curvature, twist: 0.0 }
}

const ULS_NORMAL: LrfdFactors = LrfdFactors { functional: 1.1, environmental: 1.3, material: 1.15, safety_class: 1.14 };

/// The pipe 300 m down (p_i = 20 MPa + 800 g 300 m, p_e = 1025 g 300 m,
/// Δp = 19.337825 MPa; p_b = 84.408 MPa, α_c = 1.12312, M_k = 660.84 kN m,
/// T_k = 8222.1 kN), normal safety class, ULS factors. Static (all of it
/// functional): T = 600 kN, κ = (0.006, −0.0053) 1/m, so M_d = 1.1 EI |κ|,
/// T_d = 1.1 T: U = 0.5217835075499444 (computed independently, typed in).
/// With an environmental part (the static state T_F = 600 kN, κ_F = (0.008,
/// 0); now T = 450 kN, κ = (0.0095, 0.001)): the moment's part adds to it,
/// M_d = |1.1 M_F + 1.3 M_E|; the tension's takes away from it, so it takes
/// 1/γ_E, T_d = 1.1 T_F + T_E/1.3 = 544.615 kN: U = 0.6249112933171593.
/// riser's within 1e-12 of the formula here, which is within 1e-12 of the
/// numbers.
#[test]
fn the_lrfd_utilisation_of_a_pipe_is_the_standard_s_formula_by_hand() {
    let design = one_element(ULS_NORMAL);
    let dp = 2e7 + 800.0 * 9.81 * 300.0 - 1025.0 * 9.81 * 300.0;
    let gamma = 1.14 * 1.15;
    // static
    let p = point(600e3, [0.006, -0.0053]);
    let hand = by_hand(dp, 1.1 * EI * 0.006f64.hypot(0.0053), 1.1 * 600e3, gamma);
    let peaks = design.stress_peaks(&[p], 0.0).unwrap();
    let u = peaks.lrfd.and_then(LrfdPeak::utilisation).unwrap();
    println!("static: U = {:.16} (by hand {hand:.16}); API {:?}", u.value, peaks.api.map(|a| a.value));
    assert!((hand / 0.5217835075499444 - 1.0).abs() < 1e-12);
    assert!((u.value / hand - 1.0).abs() < 1e-12 && u.s == 300.0);
    assert_eq!(u.check, "DNV-OS-F201 LRFD combined loading (net internal overpressure)");
    // with an environmental part
    let f = point(600e3, [0.008, 0.0]);
    let p = point(450e3, [0.0095, 0.001]);
    let (m_f, m_e) = ([EI * 0.008, 0.0], [EI * 0.0015, EI * 0.001]);
    let md = (1.1 * m_f[0] + 1.3 * m_e[0]).hypot(1.1 * m_f[1] + 1.3 * m_e[1]);
    let td = 1.1 * 600e3 + (450e3 - 600e3) / 1.3;
    let hand = by_hand(dp, md, td, gamma);
    let peaks = design.stress_peaks_over(&[p], &[f], 0.0).unwrap();
    let u = peaks.lrfd.and_then(LrfdPeak::utilisation).unwrap();
    println!("dynamic: M_d {:.3} kN m, T_d {:.3} kN: U = {:.16} (by hand {hand:.16})", md / 1e3, td / 1e3, u.value);
    assert!((hand / 0.6249112933171593 - 1.0).abs() < 1e-12);
    assert!((u.value / hand - 1.0).abs() < 1e-12);
    // the larger of the two checks is max_utilisation
    let api = peaks.api.unwrap();
    assert_eq!(peaks.utilisation.unwrap(), if api.value > u.value { api } else { u });
}

/// The factors move the utilisation as the formula says, at one point (so
/// at one pressure term P = (Δp/p_b)²): U − P scales with γ_SC (high over
/// normal 1.26/1.14, low 1.04/1.14) and with γ_m (1.0 over 1.15); all
/// functional, with no tension, U − P scales with γ_F (1.0 over 1.1).
#[test]
fn the_factors_move_the_utilisation_as_the_formula_says() {
    let dp = 2e7 + 800.0 * 9.81 * 300.0 - 1025.0 * 9.81 * 300.0;
    let p_b = 2.0 / 3f64.sqrt() * (2.0 * T2 / (D - T2)) * FY.min(FU / 1.15);
    let pressure = (dp / p_b).powi(2);
    let point = point(0.0, [0.007, 0.002]);
    let u = |f: LrfdFactors| {
        one_element(f).stress_peaks(&[point], 0.0).unwrap().lrfd.and_then(LrfdPeak::utilisation).unwrap().value
            - pressure
    };
    let normal = u(ULS_NORMAL);
    for (f, ratio) in [
        (LrfdFactors { safety_class: 1.26, ..ULS_NORMAL }, 1.26 / 1.14),
        (LrfdFactors { safety_class: 1.04, ..ULS_NORMAL }, 1.04 / 1.14),
        (LrfdFactors { material: 1.0, ..ULS_NORMAL }, 1.0 / 1.15),
        (LrfdFactors { functional: 1.0, ..ULS_NORMAL }, 1.0 / 1.1),
    ] {
        println!("{f:?}: (U - P) ratio {:.15} ({ratio:.15})", u(f) / normal);
        assert!((u(f) / normal / ratio - 1.0).abs() < 1e-12);
    }
}

/// The built-in steel catenary made of its wall with oil, 800 kg/m³ at
/// 20 MPa, X65 (SMYS 448 MPa, SMTS 531 MPa), normal safety class.
fn steel_catenary_with_oil(extra: &[&str]) -> Scene {
    let mut sets: Vec<String> = [
        "mass_per_length=128.3",
        "wall_thickness=0.0206",
        "internal_fluid_density=800",
        "internal_pressure=2e7",
        "yield_stress=448e6",
        "tensile_strength=531e6",
        "safety_class=normal",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    sets.extend(extra.iter().map(|s| s.to_string()));
    Scene::builtin("steel_catenary").unwrap().with_overrides(&sets).unwrap()
}

/// The largest utilisation along the line by hand from riser's own points
/// `points` (tension, curvature, position) and their static state's
/// `functional`, the hang-off at `top_z`, with γ_SC γ_m `gamma`: the
/// pressures (12.5), M = EI κ, each load effect factored with γ or 1/γ,
/// whichever gives the larger (12.14).
fn largest_by_hand(sc: &Scene, points: &[LinePoint], functional: &[LinePoint], top_z: f64, gamma: f64) -> (f64, f64) {
    let (rho_w, g, surface) = (sc.environment.water_density, sc.environment.gravity, sc.environment.water_surface_z);
    let factored = |f: f64, e: f64| {
        [(1.1, 1.3), (1.1, 1.0 / 1.3), (1.0 / 1.1, 1.3), (1.0 / 1.1, 1.0 / 1.3)]
            .iter()
            .map(|(a, b)| (a * f + b * e).abs())
            .fold(0.0, f64::max)
    };
    let (mut largest, mut at) = (0.0f64, 0.0);
    for (p, f) in points.iter().zip(functional) {
        let z = p.position.z;
        let p_i = 2e7 + 800.0 * g * (top_z - z);
        let p_e = if z < surface { rho_w * g * (surface - z) } else { 0.0 };
        let (m_f, m_e) = (
            [EI * f.curvature[0], EI * f.curvature[1]],
            [EI * (p.curvature[0] - f.curvature[0]), EI * (p.curvature[1] - f.curvature[1])],
        );
        // the moment is a vector: the largest |γ_F M_F + γ_E M_E| over the four
        let md = [(1.1, 1.3), (1.1, 1.0 / 1.3), (1.0 / 1.1, 1.3), (1.0 / 1.1, 1.0 / 1.3)]
            .iter()
            .map(|(a, b)| (a * m_f[0] + b * m_e[0]).hypot(a * m_f[1] + b * m_e[1]))
            .fold(0.0, f64::max);
        let u = by_hand(p_i - p_e, md, factored(f.tension, p.tension - f.tension), gamma);
        if u > largest {
            (largest, at) = (u, p.s);
        }
    }
    (largest, at)
}

/// The steel catenary with oil at 20 MPa: the largest LRFD utilisation along
/// the line equals the one computed here from riser's own effective
/// tension, curvature and position at every Gauss point, to 1e-12: in the
/// statics (all functional: 0.5603 at the sag bend, against the API check's
/// 0.902), and after 6 s of a heave of 2 m at 8 s against the run's static
/// state (the environmental part the difference).
#[test]
fn the_steel_catenary_with_oil_has_the_lrfd_utilisation_of_its_own_tension_curvature_and_pressures() {
    let sc = steel_catenary_with_oil(&[]);
    let sim = Simulation::from_scene(&sc).unwrap();
    let (d, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    println!("warnings: {warnings:?}");
    let points = sim.integrator.line_points(&sim.state);
    let top_z = sim.state.config.x[0].z;
    let (hand, at) = largest_by_hand(&sc, &points, &points, top_z, 1.14 * 1.15);
    let u = d.lrfd.and_then(LrfdPeak::utilisation).unwrap();
    let api = d.api_utilisation.unwrap();
    println!(
        "static: LRFD {:.6} at S = {:.2} m (by hand {hand:.6} at {at:.2}); API {:.4}; max_utilisation {:?}",
        u.value, u.s, api.value, d.max_utilisation
    );
    assert!((u.value / hand - 1.0).abs() < 1e-12 && u.s == at);
    assert_eq!(d.max_utilisation, Some(api));
    // heaved: against the static state
    let sc = steel_catenary_with_oil(&["n_elements=40"]);
    let mut sim = Simulation::from_scene(&sc).unwrap();
    let functional = sim.integrator.line_points(&sim.functional_state());
    let w = 2.0 * PI / 8.0;
    let motion = move |t: f64| {
        let ramp = (t / 4.0).min(1.0);
        let (z, vz) = (2.0 * ramp * (w * t).sin(), 2.0 * ramp * w * (w * t).cos());
        riser::model::HangOff::translation(Vector3::z() * z, Vector3::z() * vz)
    };
    sim.start(motion(0.0));
    for k in 1..=120 {
        sim.advance_to(0.05 * k as f64, &motion).unwrap();
    }
    let points = sim.integrator.line_points(&sim.state);
    let top_z = sim.state.config.x[0].z;
    let (hand, at) = largest_by_hand(&sc, &points, &functional, top_z, 1.14 * 1.15);
    let peaks = Design::new(&sc).stress_peaks_over(&points, &functional, top_z).unwrap();
    let u = peaks.lrfd.and_then(LrfdPeak::utilisation).unwrap();
    let (static_hand, _) = largest_by_hand(&sc, &points, &points, top_z, 1.14 * 1.15);
    println!(
        "after 6 s (hang-off at z = {top_z:.3} m): LRFD {:.6} at S = {:.2} m (by hand {hand:.6} at {at:.2}); \
         all taken as functional it would be {static_hand:.6}",
        u.value, u.s
    );
    assert!((u.value / hand - 1.0).abs() < 1e-12 && u.s == at);
    assert!((hand - static_hand).abs() > 1e-4, "the environmental part is factored apart");
}

/// The FMU's utilisations at its static state (read after initialisation,
/// before a step) equal `riser statics --json`'s, to 1e-12: the steel
/// catenary with oil at 20 MPa, high safety class; `max_utilisation` is the
/// larger of the two checks.
#[test]
fn the_fmu_s_utilisations_at_the_static_state_are_riser_statics_s() {
    use riser::fmi::vars::vr_of;
    let reals = [
        ("mass_per_length", 128.3),
        ("wall_thickness", 0.0206),
        ("internal_fluid_density", 800.0),
        ("internal_pressure", 2e7),
        ("yield_stress", 448e6),
        ("tensile_strength", 531e6),
    ];
    let mut i = fmu_at_static_state("steel_catenary", &[("safety_class", "high")], &reals);
    let mut get = |name: &str| i.get_real(vr_of(name).unwrap()).unwrap();
    let (fmu_max, fmu_api, fmu_lrfd) =
        (get("max_utilisation"), get("max_utilisation_api_rp_2rd"), get("max_utilisation_dnv_os_f201"));
    let mut args = vec!["statics", "steel_catenary", "--json", "--set", "safety_class=high"];
    let sets: Vec<String> = reals.iter().map(|(n, v)| format!("{n}={v}")).collect();
    for s in &sets {
        args.extend(["--set", s.as_str()]);
    }
    let v = riser_json(&args);
    let checks = v["utilisations"].as_array().unwrap();
    let value = |name: &str| {
        checks.iter().find(|c| c["check"].as_str().unwrap().starts_with(name)).unwrap()["value"].as_f64().unwrap()
    };
    let (cli_api, cli_lrfd) = (value("API RP 2RD"), value("DNV-OS-F201"));
    println!(
        "FMU API {fmu_api:.12}, LRFD {fmu_lrfd:.12}, max {fmu_max:.12}; riser statics {cli_api:.12}, {cli_lrfd:.12}"
    );
    assert!((fmu_api / cli_api - 1.0).abs() < 1e-12 && (fmu_lrfd / cli_lrfd - 1.0).abs() < 1e-12);
    assert_eq!(fmu_max, fmu_api.max(fmu_lrfd));
    assert_eq!(v["max_utilisation"]["value"].as_f64().unwrap(), cli_api.max(cli_lrfd));
    assert!(v["not_reported"].as_array().unwrap().is_empty());
    use riser::fmi::instance::Status;
    // the outputs are computed once per state (at the first read): heaved, they are the new
    // state's, and reading them again gives them again
    let heave = vr_of("heave").unwrap();
    for k in 0..20 {
        let t = 0.1 * k as f64;
        assert_eq!(i.set_real(heave, 0.5 * (t / 2.0).min(1.0) * (2.0 * PI / 8.0 * t).sin()), Status::Ok);
        assert_eq!(i.do_step(t, 0.1), Status::Ok);
    }
    let mut get = |name: &str| i.get_real(vr_of(name).unwrap()).unwrap();
    let (api_heaved, lrfd_heaved) = (get("max_utilisation_api_rp_2rd"), get("max_utilisation_dnv_os_f201"));
    println!("heaved 2 s: FMU API {api_heaved:.12}, LRFD {lrfd_heaved:.12}");
    assert!(api_heaved != fmu_api && lrfd_heaved != fmu_lrfd);
    assert_eq!((get("max_utilisation_api_rp_2rd"), get("max_utilisation_dnv_os_f201")), (api_heaved, lrfd_heaved));
}

/// Where the contents' pressure does not exceed the sea's (the steel
/// catenary's oil at no pressure at the hang-off: its head, 800 kg/m³,
/// below the sea's, 1025 kg/m³),
/// the criterion of net internal overpressure does not apply: riser
/// reports no LRFD utilisation and says why, in the JSON's `not_reported`
/// (the API check stays), and the FMU's log, once, its output reading 0.
#[test]
fn without_net_internal_overpressure_the_lrfd_check_is_not_reported() {
    use riser::fmi::vars::vr_of;
    let said = std::sync::Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
    let log = said.clone();
    let logger: riser::fmi::instance::Logger =
        std::sync::Arc::new(move |_, _, m: &str| log.lock().unwrap().push(m.to_string()));
    let reals = [
        ("mass_per_length", 128.3),
        ("wall_thickness", 0.0206),
        ("internal_fluid_density", 800.0),
        ("yield_stress", 448e6),
        ("tensile_strength", 531e6),
    ];
    let mut i = fmu_at_static_state_logged("steel_catenary", &[("safety_class", "normal")], &reals, Some(logger));
    for _ in 0..2 {
        assert_eq!(i.get_real(vr_of("max_utilisation_dnv_os_f201").unwrap()).unwrap(), 0.0);
    }
    let said = said.lock().unwrap();
    let n = said.iter().filter(|m| m.contains("DNV-OS-F201 LRFD combined loading not reported")).count();
    println!("FMU log: {n} message(s) of the LRFD check");
    assert_eq!(n, 1, "{said:?}");
    let mut args = vec!["statics", "steel_catenary", "--json"];
    let sets = [
        "mass_per_length=128.3",
        "wall_thickness=0.0206",
        "internal_fluid_density=800",
        "internal_pressure=0",
        "yield_stress=448e6",
        "tensile_strength=531e6",
        "safety_class=normal",
    ];
    for s in &sets {
        args.extend(["--set", s]);
    }
    let v = riser_json(&args);
    let why = v["not_reported"][0].as_str().unwrap();
    println!("{why}; max_utilisation {}", v["max_utilisation"]);
    assert!(why.contains("DNV-OS-F201") && why.contains("no net internal overpressure"), "{why}");
    assert_eq!(v["utilisations"].as_array().unwrap().len(), 1);
    assert!(v["max_utilisation"]["check"].as_str().unwrap().starts_with("API RP 2RD"));
}

/// The check's keys: a safety class without the strengths, or on a line
/// that is no tube (the catenary's flexible pipe), and a tensile strength
/// below the yield stress are refused naming the key; a tensile strength
/// without a safety class asks for no check and the statics warn of it.
#[test]
fn the_check_s_keys_are_refused_or_warned_of_when_they_ask_for_nothing_made() {
    let refused = |scene: &str, sets: &[&str], field: &str, part: &str| {
        let e = Scene::builtin(scene).unwrap().with_overrides(sets).unwrap_err().to_string();
        println!("{sets:?}: {e}");
        assert!(e.contains(field) && e.contains(part), "{e}");
    };
    refused("steel_catenary", &["safety_class=normal", "yield_stress=448e6"], "line.tensile_strength", "missing");
    refused("steel_catenary", &["safety_class=high", "tensile_strength=531e6"], "line.yield_stress", "missing");
    refused(
        "steel_catenary",
        &["yield_stress=448e6", "tensile_strength=400e6"],
        "line.tensile_strength",
        "below the yield stress",
    );
    refused(
        "catenary",
        &["safety_class=low", "yield_stress=4e8", "tensile_strength=5e8"],
        "line.wall_thickness",
        "needs the pipe's wall",
    );
    refused("steel_catenary", &["safety_class=medium"], "safety_class", "not a safety class");
    let sc = Scene::builtin("steel_catenary").unwrap().with_overrides(&["tensile_strength=531e6"]).unwrap();
    let sim = Simulation::from_scene(&sc).unwrap();
    let (d, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    println!("{warnings:?}");
    assert!(warnings.iter().any(|w| w.contains("no safety_class")));
    assert!(d.lrfd.is_none());
}
