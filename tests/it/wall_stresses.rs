//! Stresses with pressure (issue 50, docs/theory.md §12.4) against closed
//! forms computed here, independently of src/sim/design.rs: the true wall
//! tension T_w = T_eff + p_i A_i − p_e A_e, Lamé's thick-walled cylinder in
//! its textbook form (σ_θ at r_i = (p_i (r_o² + r_i²) − 2 p_e r_o²)/(r_o² − r_i²),
//! σ_r = −p_i; at r_o, σ_θ = (2 p_i r_i² − p_e (r_o² + r_i²))/(r_o² − r_i²),
//! σ_r = −p_e), the torsional shear τ = GJ κ₃ r / J, and the von Mises
//! stress from the principal stresses (σ_r and the two of the axial–hoop
//! plane with its shear), not from the component formula riser uses; the API
//! RP 2RD utilisation σ_vm / (C_f 2/3 σ_y) by hand; the FMU's output at the
//! static state against `riser statics`; and a scene without the new keys,
//! whose statics and dynamics are those of the keys at their "none" values
//! and whose `max_stress` in air is the old T/A + E r |κ| to the bit.

use crate::common::{fmu_at_static_state, oil_inside_sea_outside, pipe_properties, riser_json};
use nalgebra::{Rotation3, Unit, Vector3};
use riser::model::outputs::LinePoint;
use riser::model::rod::{EndBc, Rod, Stiffness};
use riser::model::sections::PerElement;
use riser::scene::sections::Wall;
use riser::scene::{Model, Scene};
use riser::sim::Simulation;
use riser::sim::design::Design;
use std::f64::consts::PI;

/// 10¾ in X65 steel pipe, 20.6 mm wall (steel_catenary's), with a 27 mm
/// coating (D 0.3271 m) and E 207 GPa, G 79.6 GPa.
const D_STEEL: f64 = 0.2731;
const WALL: f64 = 0.0206;
const D_COATED: f64 = 0.3271;
const E: f64 = 2.07e11;
const G: f64 = 7.96e10;
/// API 5L X65's SMYS, Pa.
const SMYS: f64 = 448e6;

/// The pipe's sections by hand: (A_s, A_i, A_e, I, J, r_i, r_o).
fn sections(d_steel: f64, wall: f64, d_outer: f64) -> (f64, f64, f64, f64, f64, f64, f64) {
    let (r_o, r_i) = (d_steel / 2.0, d_steel / 2.0 - wall);
    let a_s = PI * (r_o * r_o - r_i * r_i);
    let i = PI / 4.0 * (r_o.powi(4) - r_i.powi(4));
    (a_s, PI * r_i * r_i, PI * d_outer * d_outer / 4.0, i, 2.0 * i, r_i, r_o)
}

/// Lamé's hoop and radial stress at the inner (`inner`) or outer radius,
/// the textbook forms.
fn lame(p_i: f64, p_e: f64, r_i: f64, r_o: f64, inner: bool) -> (f64, f64) {
    let (a2, b2) = (r_i * r_i, r_o * r_o);
    if inner {
        ((p_i * (b2 + a2) - 2.0 * p_e * b2) / (b2 - a2), -p_i)
    } else {
        ((2.0 * p_i * a2 - p_e * (b2 + a2)) / (b2 - a2), -p_e)
    }
}

/// Von Mises from the principal stresses: σ_r, and the axial–hoop plane's
/// (σ_a + σ_θ)/2 ± √(((σ_a − σ_θ)/2)² + τ²).
fn von_mises(axial: f64, hoop: f64, radial: f64, shear: f64) -> f64 {
    let (c, r) = (0.5 * (axial + hoop), (0.25 * (axial - hoop).powi(2) + shear * shear).sqrt());
    let (s1, s2, s3) = (c + r, c - r, radial);
    (0.5 * ((s1 - s2).powi(2) + (s2 - s3).powi(2) + (s3 - s1).powi(2))).sqrt()
}

/// The pipe at one point by hand: the true wall tension (N) from the
/// effective tension `t_eff` and the pressures, and the largest von Mises
/// stress (Pa) over the fibres in and against the curvature `k` (1/m), at
/// r_i and r_o, with the twist `twist` (1/m) and torsional stiffness `gj`.
struct Hand {
    wall_tension: f64,
    max_axial: f64,
    von_mises: f64,
}

#[allow(clippy::too_many_arguments)]
fn by_hand(t_eff: f64, k: f64, twist: f64, p_i: f64, p_e: f64, e: f64, gj: f64, d_outer: f64) -> Hand {
    let (a_s, a_i, a_e, _, j, r_i, r_o) = sections(D_STEEL, WALL, d_outer);
    let wall_tension = t_eff + p_i * a_i - p_e * a_e;
    let mut vm = 0.0f64;
    for (r, inner) in [(r_i, true), (r_o, false)] {
        let (hoop, radial) = lame(p_i, p_e, r_i, r_o, inner);
        let tau = gj * twist * r / j;
        for sign in [1.0, -1.0] {
            vm = vm.max(von_mises(wall_tension / a_s + sign * e * k * r, hoop, radial, tau));
        }
    }
    Hand { wall_tension, max_axial: wall_tension / a_s + e * k.abs() * r_o, von_mises: vm }
}

/// A straight pipe, 100 m hanging down from z = −500 m (the hang-off) in
/// water whose surface is at z = 0, stretched by ε = 2e-4 and twisted
/// uniformly by φ = 0.05 rad end to end, with oil (800 kg/m³) at 20 MPa at
/// the hang-off: each Gauss point's T_w, σ_θ, τ and σ_vm against the
/// closed forms, to 1e-12 with the rod's own tension and twist at each
/// point; the twist is φ/L to 2e-6 (the quadratic interpolation of
/// directors turning 2.5e-3 rad a half element), so that with φ/L itself
/// within 1e-8; the tension is EA ε to 1e-10. The largest von Mises stress
/// is at the top, where p_i − p_e is largest (the water, heavier than the
/// oil, gains pressure faster with depth).
#[test]
fn a_straight_pipe_with_pressure_inside_and_out_and_a_twist_has_lame_s_stresses() {
    let (l, n, strain, phi) = (100.0, 10, 2e-4, 0.05);
    let (a_s, _, _, i, j, _, _) = sections(D_STEEL, WALL, D_COATED);
    let (ea, ei, gj) = (E * a_s, E * i, G * j);
    let rod = Rod::new(n, l, Stiffness::paper(ea, ei, gj), [EndBc::CLAMPED, EndBc::PINNED_NO_TWIST]);
    let (top, down) = (Vector3::new(0.0, 0.0, -500.0), -Vector3::z());
    let mut cfg = rod.straight(top, down, Vector3::x());
    for (a, x) in cfg.x.iter_mut().enumerate() {
        *x = top + down * rod.s_node(a) * (1.0 + strain);
    }
    cfg.xp.iter_mut().for_each(|p| *p = down * (1.0 + strain));
    let axis = Unit::new_normalize(down);
    for (jn, d) in cfg.d.iter_mut().enumerate() {
        let s = jn as f64 * l / n as f64 / 2.0;
        *d = Rotation3::from_axis_angle(&axis, phi * s / l).matrix() * *d;
    }
    let wall = Wall { outer_diameter: D_STEEL, thickness: WALL, youngs_modulus: E };
    let props = pipe_properties(D_COATED, wall, [ea, ei, gj], Some(SMYS), None);
    let fluids = oil_inside_sea_outside();
    let case_factor = 1.2;
    let design = Design::of_properties(PerElement::from_elements(vec![props; n]), Model::Rod, l, n)
        .with_fluids(fluids, case_factor);
    let points = rod.gauss_points(&cfg);
    let d = design.of_points(&points, cfg.xp[0], None, top.z);
    let mut largest = (0.0f64, 0.0);
    let mut largest_axial = (f64::NEG_INFINITY, 0.0);
    for p in &points {
        assert!((p.tension / (ea * strain) - 1.0).abs() < 1e-10, "T {} vs EA eps {}", p.tension, ea * strain);
        assert!((p.twist.abs() * l / phi - 1.0).abs() < 2e-6, "twist {} vs {}", p.twist, phi / l);
        assert!(p.curvature_magnitude() < 1e-12);
        let z = top.z - p.s * (1.0 + strain);
        let (p_i, p_e) = (2e7 + 800.0 * 9.81 * (top.z - z), 1025.0 * 9.81 * (0.0 - z));
        let h = by_hand(p.tension, 0.0, p.twist, p_i, p_e, E, gj, D_COATED);
        let closed = by_hand(ea * strain, 0.0, phi / l, p_i, p_e, E, gj, D_COATED);
        assert!((h.von_mises / closed.von_mises - 1.0).abs() < 1e-8);
        if h.von_mises > largest.0 {
            largest = (h.von_mises, p.s);
        }
        if h.max_axial > largest_axial.0 {
            largest_axial = (h.max_axial, p.s);
        }
    }
    let (vm, vm_s) = d.max_von_mises.expect("a wall");
    let u = d.max_utilisation.expect("a yield stress");
    let by_hand_u = largest.0 / (case_factor * 2.0 / 3.0 * SMYS);
    let (axial, axial_s) = d.max_stress.unwrap();
    println!(
        "von Mises {vm:.6e} Pa at S = {vm_s:.4} m (by hand {:.6e} at {:.4}); utilisation {:.6} ({by_hand_u:.6}, {}); \
         axial {axial:.6e} Pa ({:.6e})",
        largest.0, largest.1, u.value, u.check, largest_axial.0
    );
    assert!((vm / largest.0 - 1.0).abs() < 1e-12 && vm_s == largest.1);
    assert!((u.value / by_hand_u - 1.0).abs() < 1e-12 && u.s == largest.1);
    assert!((axial / largest_axial.0 - 1.0).abs() < 1e-12 && axial_s == largest_axial.1);
    // the closed forms at the bottom point, as numbers
    let z = top.z - points.last().unwrap().s * (1.0 + strain);
    let (p_i, p_e) = (2e7 + 800.0 * 9.81 * (top.z - z), 1025.0 * 9.81 * -z);
    let (_, _, _, _, _, r_i, r_o) = sections(D_STEEL, WALL, D_COATED);
    let (hoop_i, _) = lame(p_i, p_e, r_i, r_o, true);
    println!(
        "bottom: p_i {:.4} MPa, p_e {:.4} MPa, hoop at r_i {:.4} MPa, tau at r_o {:.4} MPa",
        p_i / 1e6,
        p_e / 1e6,
        hoop_i / 1e6,
        G * phi / l * r_o / 1e6
    );
}

/// The built-in steel catenary made of its wall: steel 128.3 kg/m (the
/// scene's 162.1 less its oil) with oil inside, 800 kg/m³ at `pressure`.
fn steel_catenary_with_oil(pressure: f64, extra: &[&str]) -> Scene {
    let mut sets: Vec<String> =
        ["mass_per_length=128.3", "wall_thickness=0.0206", "internal_fluid_density=800", "yield_stress=448e6"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    sets.push(format!("internal_pressure={pressure}"));
    sets.extend(extra.iter().map(|s| s.to_string()));
    Scene::builtin("steel_catenary").unwrap().with_overrides(&sets).unwrap()
}

/// A vertical riser hanging in still water (the catenary scene made the
/// 10¾ in pipe, its anchor 0.05 m beyond its length straight below), with
/// oil at 20 MPa: the weight per length (m + ρ_i A_i − ρ_w A_e) g by hand
/// is the model's; T_eff(S) = T_b + w (L − S), T_b = EA δ/L − w L/2, so at
/// the top Gauss point T_w = T_eff + p_i A_i − p_e A_e, the axial stress
/// T_w/A_s, Lamé's σ_θ at r_i and the von Mises stress, all within 1e-6
/// (the stretch's share of the depth, 5e-4 of the point's, moves p_e by
/// 1e-9 of it); the largest von Mises along the line, with C_f = 1.2, its
/// API RP 2RD utilisation σ_vm / (1.2 · 2/3 · 448 MPa).
#[test]
fn a_vertical_riser_in_still_water_has_the_true_wall_tension_of_its_weight() {
    let (l, delta) = (100.0, 0.05);
    let (a_s, a_i, a_e, i, _, r_i, r_o) = sections(D_STEEL, WALL, D_STEEL);
    let sc = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[
            format!("axial_stiffness={}", E * a_s),
            format!("bending_stiffness={}", E * i),
            format!("outer_diameter={D_STEEL}"),
            "mass_per_length=128.3".to_string(),
            format!("wall_thickness={WALL}"),
            "internal_fluid_density=800".to_string(),
            "internal_pressure=2e7".to_string(),
            "yield_stress=448e6".to_string(),
            "design_case_factor=1.2".to_string(),
            "anchor_x=0".to_string(),
            format!("anchor_z={}", -(l + delta)),
            "newton_tolerance=1e-10".to_string(),
        ])
        .unwrap();
    let (rho_w, g, surface) = (sc.environment.water_density, sc.environment.gravity, sc.environment.water_surface_z);
    let w = (128.3 + 800.0 * a_i - rho_w * a_e) * g;
    let w_model = -riser::loads::vertical_load(&sc).uniform;
    assert!((w_model / w - 1.0).abs() < 1e-12, "weight {w_model} vs {w}");
    let sim = Simulation::from_scene(&sc).unwrap();
    let (d, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    println!("warnings: {warnings:?}");
    assert!(!warnings.iter().any(|m| m.contains("off the wall's")), "the wall's EA, EI are the scene's");
    let t_b = E * a_s * delta / l - w * l / 2.0;
    let points = sim.integrator.line_points(&sim.state);
    let mut largest = (0.0f64, 0.0);
    for p in &points {
        let z = -p.s * (1.0 + delta / l);
        let (p_i, p_e) = (2e7 + 800.0 * g * -z, rho_w * g * (surface - z));
        let vm = by_hand(t_b + w * (l - p.s), 0.0, 0.0, p_i, p_e, E, 0.0, D_STEEL).von_mises;
        if vm > largest.0 {
            largest = (vm, p.s);
        }
    }
    let top = points[0];
    let z = -top.s * (1.0 + delta / l);
    let (p_i, p_e) = (2e7 + 800.0 * g * -z, rho_w * g * (surface - z));
    let t_eff = t_b + w * (l - top.s);
    let t_w = t_eff + p_i * a_i - p_e * a_e;
    let (hoop, radial) = lame(p_i, p_e, r_i, r_o, true);
    let vm_top = von_mises(t_w / a_s, hoop, radial, 0.0);
    let design = Design::new(&sc);
    let top_only = design.of_points(&points[..1], sim.integrator.hang_off_tangent(&sim.state), None, 0.0);
    println!(
        "top (S = {:.4} m): T_eff {:.3} kN (model {:.3}), T_w {:.3} kN, sigma_a {:.3} MPa, hoop at r_i {:.3} MPa, \
         radial {:.3} MPa, von Mises {:.3} MPa (riser {:.3})",
        top.s,
        t_eff / 1e3,
        top.tension / 1e3,
        t_w / 1e3,
        t_w / a_s / 1e6,
        hoop / 1e6,
        radial / 1e6,
        vm_top / 1e6,
        top_only.max_von_mises.unwrap().0 / 1e6
    );
    assert!((top.tension / t_eff - 1.0).abs() < 1e-6);
    assert!((top_only.max_stress.unwrap().0 / (t_w / a_s) - 1.0).abs() < 1e-6);
    assert!((top_only.max_von_mises.unwrap().0 / vm_top - 1.0).abs() < 1e-6);
    let (vm, s) = d.max_von_mises.unwrap();
    let u = d.max_utilisation.unwrap();
    let hand_u = largest.0 / (1.2 * 2.0 / 3.0 * 448e6);
    println!(
        "largest von Mises {:.4} MPa at S = {s:.3} m (by hand {:.4} at {:.3}); utilisation {:.5} ({hand_u:.5})",
        vm / 1e6,
        largest.0 / 1e6,
        largest.1,
        u.value
    );
    assert!((vm / largest.0 - 1.0).abs() < 1e-6 && s == largest.1);
    assert!((u.value / hand_u - 1.0).abs() < 1e-6 && u.s == s);
}

/// The steel catenary with oil at 20 MPa: the largest von Mises stress
/// along the line equals the one computed here from riser's own effective
/// tension, curvature, twist and position at every Gauss point (the hand
/// formulas above), to 1e-12, in the static state (planar: no twist) and
/// after 6 s of a clamped hang-off swaying 2 m and yawing 0.05 rad at 8 s
/// (twisted); its contents make it the scene's weight again (162.09 kg/m
/// against the scene's rounded 162.1), so the statics are the scene's
/// within 2e-4; the axial stress at the touchdown with the true wall
/// tension against the effective tension's.
#[test]
fn the_steel_catenary_with_oil_has_the_von_mises_stress_of_its_own_tension_curvature_and_twist() {
    let sc = steel_catenary_with_oil(2e7, &[]);
    let sim = Simulation::from_scene(&sc).unwrap();
    let (d, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    println!("warnings: {warnings:?}");
    let points = sim.integrator.line_points(&sim.state);
    let (rho_w, g, surface) = (sc.environment.water_density, sc.environment.gravity, sc.environment.water_surface_z);
    let top_z = sim.state.config.x[0].z;
    let gj = sc.line.torsional_stiffness;
    let hand = |p: &LinePoint| {
        let z = p.position.z;
        let p_i = 2e7 + 800.0 * g * (top_z - z);
        let p_e = if z < surface { rho_w * g * (surface - z) } else { 0.0 };
        by_hand(p.tension, p.curvature_magnitude(), p.twist, p_i, p_e, E, gj, D_STEEL)
    };
    let largest = |points: &[LinePoint], top_z: f64| {
        let (mut vm, mut at) = (0.0f64, 0.0);
        for p in points {
            let z = p.position.z;
            let p_i = 2e7 + 800.0 * g * (top_z - z);
            let p_e = if z < surface { rho_w * g * (surface - z) } else { 0.0 };
            let h = by_hand(p.tension, p.curvature_magnitude(), p.twist, p_i, p_e, E, gj, D_STEEL);
            if h.von_mises > vm {
                (vm, at) = (h.von_mises, p.s);
            }
        }
        (vm, at)
    };
    let (vm, at) = largest(&points, top_z);
    let (riser_vm, riser_s) = d.max_von_mises.unwrap();
    let u = d.max_utilisation.unwrap();
    let twist = points.iter().map(|p| p.twist.abs()).fold(0.0, f64::max);
    println!(
        "max von Mises {:.4} MPa at S = {riser_s:.2} m (by hand {:.4} MPa at {at:.2}); utilisation {:.4} ({}); \
         largest twist {twist:.3e} 1/m",
        riser_vm / 1e6,
        vm / 1e6,
        u.value,
        u.check
    );
    assert!((riser_vm / vm - 1.0).abs() < 1e-12 && riser_s == at);
    assert!((u.value - vm / (2.0 / 3.0 * 448e6)).abs() < 1e-12);
    // the scene's weight: its top tension within 1e-4 of the built-in's
    let plain = Simulation::from_scene(&Scene::builtin("steel_catenary").unwrap()).unwrap();
    let (t_oil, t_plain) = (sim.outputs().top_tension, plain.outputs().top_tension);
    println!("top tension {:.3} kN with the oil inside, {:.3} kN the built-in", t_oil / 1e3, t_plain / 1e3);
    assert!((t_oil / t_plain - 1.0).abs() < 2e-4);
    // at the touchdown: the axial stress of the true wall tension against the effective tension's
    let td = d.touchdown_s.unwrap();
    let p = points.iter().min_by(|a, b| (a.s - td).abs().total_cmp(&(b.s - td).abs())).unwrap();
    let (a_s, _, _, _, _, _, _) = sections(D_STEEL, WALL, D_STEEL);
    let h = hand(p);
    println!(
        "touchdown S = {td:.1} m: T_eff {:.1} kN -> {:.2} MPa; T_w {:.1} kN -> {:.2} MPa",
        p.tension / 1e3,
        p.tension / a_s / 1e6,
        h.wall_tension / 1e3,
        h.wall_tension / a_s / 1e6
    );
    assert!(h.wall_tension > 2.0 * p.tension);
    // twisted: a clamped hang-off swaying and yawing
    let sc = steel_catenary_with_oil(2e7, &["hang_off_end=clamped", "n_elements=40"]);
    let mut sim = Simulation::from_scene(&sc).unwrap();
    let w = 2.0 * PI / 8.0;
    let motion = move |t: f64| {
        let ramp = (t / 4.0).min(1.0);
        let (y, vy) = (2.0 * ramp * (w * t).sin(), 2.0 * ramp * w * (w * t).cos());
        let (psi, dpsi) = (0.05 * ramp * (w * t).sin(), 0.05 * ramp * w * (w * t).cos());
        let mut h = riser::model::HangOff::translation(Vector3::y() * y, Vector3::y() * vy);
        h.rotation = *Rotation3::from_axis_angle(&Vector3::z_axis(), psi).matrix();
        h.angular_velocity = Vector3::z() * dpsi;
        h
    };
    sim.start(motion(0.0));
    for k in 1..=120 {
        sim.advance_to(0.05 * k as f64, &motion).unwrap();
    }
    let points = sim.integrator.line_points(&sim.state);
    let top_z = sim.state.config.x[0].z;
    let (vm, at) = largest(&points, top_z);
    let peaks = Design::new(&sc).stress_peaks(&points, top_z).unwrap();
    let twist = points.iter().map(|p| p.twist.abs()).fold(0.0, f64::max);
    println!(
        "after 6 s: max von Mises {:.4} MPa at S = {:.2} m (by hand {:.4} at {at:.2}); largest twist {twist:.3e} 1/m",
        peaks.von_mises.0 / 1e6,
        peaks.von_mises.1,
        vm / 1e6
    );
    assert!(twist > 1e-4, "twisted: {twist}");
    assert!((peaks.von_mises.0 / vm - 1.0).abs() < 1e-12 && peaks.von_mises.1 == at);
}

/// The FMU's `max_von_mises` and `max_utilisation` at its static state (read
/// after initialisation, before a step) equal `riser statics --json`'s, to
/// 1e-12: the steel catenary with oil at 20 MPa.
#[test]
fn the_fmu_s_stress_outputs_at_the_static_state_are_riser_statics_s() {
    use riser::fmi::vars::vr_of;
    let sets = [
        ("mass_per_length", 128.3),
        ("wall_thickness", 0.0206),
        ("internal_fluid_density", 800.0),
        ("internal_pressure", 2e7),
        ("yield_stress", 448e6),
    ];
    let mut i = fmu_at_static_state("steel_catenary", &[], &sets);
    let fmu_vm = i.get_real(vr_of("max_von_mises").unwrap()).unwrap();
    let fmu_u = i.get_real(vr_of("max_utilisation").unwrap()).unwrap();
    let mut args = vec!["statics".to_string(), "steel_catenary".to_string(), "--json".to_string()];
    for (name, v) in sets {
        args.extend(["--set".to_string(), format!("{name}={v}")]);
    }
    let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    let v = riser_json(&args);
    let (cli_vm, cli_u) = (v["max_von_mises"].as_f64().unwrap(), v["max_utilisation"]["value"].as_f64().unwrap());
    println!(
        "FMU {fmu_vm:.9e} Pa, {fmu_u:.9}; riser statics {cli_vm:.9e} Pa, {cli_u:.9} ({}, S = {})",
        v["max_utilisation"]["check"], v["max_von_mises_s"]
    );
    assert!((fmu_vm / cli_vm - 1.0).abs() < 1e-12 && (fmu_u / cli_u - 1.0).abs() < 1e-12);
    // the built-in scene as it is (no wall given, a homogeneous tube): a von Mises stress, no utilisation
    let mut i = fmu_at_static_state("steel_catenary", &[], &[]);
    assert!(i.get_real(vr_of("max_von_mises").unwrap()).unwrap() > 0.0);
    assert_eq!(i.get_real(vr_of("max_utilisation").unwrap()).unwrap(), 0.0);
}

/// A scene without the new keys moves as before: `riser run` of the steel
/// catenary (heave 2 m / 12 s, 30 s, 40 elements) gives the same JSON
/// numbers, bit for bit, as with every key at its "none" value (wall 0,
/// contents 0, C_f 1, yield 0, the steel diameter the outer one, no tensile
/// strength, no safety class, DNV-OS-F201's default factors); and in
/// air (water_density 0, no contents) `max_stress` is the old T/A + E r |κ|
/// of the points, to the bit.
#[test]
fn a_scene_without_the_new_keys_is_unchanged() {
    let base = ["run", "steel_catenary", "--heave", "2,12", "--duration", "30", "--json", "--set", "n_elements=40"];
    let none = [
        "wall_thickness=0",
        "internal_fluid_density=0",
        "internal_pressure=0",
        "design_case_factor=1",
        "yield_stress=0",
        "steel_outer_diameter=0.2731",
        "youngs_modulus=2.07e11",
        "tensile_strength=0",
        "safety_class=none",
        "load_factor_functional=1.1",
        "load_factor_environmental=1.3",
        "material_resistance_factor=1.15",
    ];
    let mut with_none: Vec<&str> = base.to_vec();
    for s in &none {
        with_none.extend(["--set", s]);
    }
    let (a, b) = (riser_json(&base), riser_json(&with_none));
    for key in ["top_tension", "min_tension", "energy_balance_residual", "newton_iterations", "statics"] {
        assert_eq!(a[key], b[key], "{key}");
    }
    for key in ["top_tension", "min_tension", "max_tension", "max_curvature", "stress_range", "max_von_mises"] {
        assert_eq!(a["steady"][key], b["steady"][key], "steady.{key}");
    }
    println!("top tension {} (both); steady von Mises {}", a["top_tension"], a["steady"]["max_von_mises"]);
    // in air, no contents: the old formula
    let sc = Scene::builtin("steel_catenary").unwrap().with_overrides(&["water_density=0"]).unwrap();
    let sim = Simulation::from_scene(&sc).unwrap();
    let design = Design::new(&sc);
    let d = design.numbers(&sim.integrator, &sim.state, sim.outputs().touchdown_s);
    let points = sim.integrator.line_points(&sim.state);
    let tube = design.tube(0).unwrap();
    let old = points
        .iter()
        .map(|p| (p.tension / tube.area + tube.modulus * tube.outer_radius * p.curvature_magnitude(), p.s))
        .fold((f64::NEG_INFINITY, 0.0), |m, v| if v.0 > m.0 { v } else { m });
    println!("in air: max stress {:?}, old formula {old:?}", d.max_stress);
    assert_eq!(d.max_stress, Some(old));
}

/// The wall's checks: thicker than its radius, a steel diameter beyond the
/// outer diameter, and contents without a bore (the catenary's flexible
/// pipe, no wall) are refused naming the key; a wall whose E A_s is 2 % off
/// the scene's EA is warned of in the statics with the percentage, and one
/// within 1 % is not.
#[test]
fn implausible_walls_are_refused_and_a_stiffness_off_the_wall_is_warned_of() {
    let refused = |sets: &[&str], field: &str, part: &str| {
        let e = Scene::builtin("catenary").unwrap().with_overrides(sets).unwrap_err().to_string();
        println!("{sets:?}: {e}");
        assert!(e.contains(field) && e.contains(part), "{e}");
    };
    refused(&["wall_thickness=0.09", "steel_outer_diameter=0.15"], "line.wall_thickness", "more than the radius");
    refused(&["wall_thickness=0.02", "steel_outer_diameter=0.4"], "line.steel_outer_diameter", "larger than");
    refused(&["internal_fluid_density=800"], "line.wall_thickness", "need the pipe's bore");
    refused(&["internal_pressure=1e6"], "line.wall_thickness", "need the pipe's bore");
    // the steel catenary's own EA, EI are its wall's (3.38e9 N, 2.71e7 N m^2, within 0.1 %)
    let (a_s, _, _, i, _, _, _) = sections(D_STEEL, WALL, D_STEEL);
    let warned = |ea: f64| {
        let sc = steel_catenary_with_oil(0.0, &[&format!("axial_stiffness={ea}")]);
        let sim = Simulation::from_scene(&sc).unwrap();
        let (_, w) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
        w.into_iter().filter(|m| m.contains("off the wall's")).collect::<Vec<_>>()
    };
    assert!(warned(E * a_s * 1.005).is_empty());
    let w = warned(E * a_s * 1.02);
    println!("{w:?}; EI {:.4e} (scene 2.71e7)", E * i);
    assert!(w.len() == 1 && w[0].contains("EA") && w[0].contains("+2.0 %"), "{w:?}");
}
