//! The design numbers (issue 31, docs/theory.md §12) against closed forms:
//! the bending moment, curvature and outer-fibre stress of a clamped
//! cantilever (small load: M = P (L − s); large deflection: the elastica's
//! clamp moment P L (1 − u)), the stress of a straight tensioned line (a
//! vertical line stretched between its ends: T(s) = T_b + w (L − s)), and the
//! touchdown point and hang-off angle of the catenary with touchdown
//! (tests/it/common/reference.rs, independent of the crate); and the anchor
//! lifted off its seabed by a line too short to touch down (issue 52): its
//! uplift angle against Irvine's elastic catenary.

use crate::common;

use common::reference::{cantilever_elastica, catenary_on_seabed, elastic_catenary};
use nalgebra::Vector3;
use riser::loads::weight::VerticalLoad;
use riser::model::rod::statics::{StaticLoads, StaticProblem};
use riser::model::rod::{EndBc, Rod, Stiffness};
use riser::model::sections::PerElement;
use riser::model::statics::StaticOptions;
use riser::scene::sections::LineProperties;
use riser::scene::{Model, Scene};
use riser::sim::Simulation;
use riser::sim::design::{Design, DesignNumbers, Tube};
use riser::solve::statics::solve;

/// A steel tube: D 0.1 m, bore 0.08 m, E 200 GPa.
const E: f64 = 2.0e11;
const D: f64 = 0.1;
const BORE: f64 = 0.08;

fn tube_area() -> f64 {
    std::f64::consts::PI * (D * D - BORE * BORE) / 4.0
}

fn tube_inertia() -> f64 {
    std::f64::consts::PI * (D.powi(4) - BORE.powi(4)) / 64.0
}

fn tube_properties() -> LineProperties {
    LineProperties {
        mass_per_length: 1.0,
        displaced_area: 0.0,
        added_mass_area: 0.0,
        drag_normal: 0.0,
        drag_tangential: 0.0,
        diameter: D,
        axial_stiffness: E * tube_area(),
        bending_stiffness: E * tube_inertia(),
        torsional_stiffness: 0.8 * E * tube_inertia(),
        rotary_inertia: 0.0,
        pipe_diameter: D,
        wall: None,
        yield_stress: None,
        tensile_strength: None,
    }
}

/// A clamped–free cantilever of length `l` along x with a dead tip load `p`
/// (N, downward): its design numbers.
fn cantilever(n_el: usize, l: f64, p: f64) -> DesignNumbers {
    let props = tube_properties();
    let stiffness = Stiffness::paper(props.axial_stiffness, props.bending_stiffness, props.torsional_stiffness);
    let rod = Rod::new(n_el, l, stiffness, [EndBc::CLAMPED, EndBc::FREE]);
    let start = rod.straight(Vector3::zeros(), Vector3::x(), Vector3::y());
    let mut loads = StaticLoads::gravity_only(VerticalLoad { uniform: 0.0, sections: vec![] });
    loads.point_forces.push((n_el, Vector3::new(0.0, 0.0, -p)));
    let opts = StaticOptions { tolerance: 1e-11, ..Default::default() };
    let sol = solve(&StaticProblem::new(&rod, &loads), start, &opts).expect("cantilever converges");
    let design = Design::of_properties(PerElement::from_elements(vec![props; n_el]), Model::Rod, l, n_el);
    design.of_points(&rod.gauss_points(&sol.config), sol.config.xp[0], None, 0.0)
}

/// (12.1) recovers the tube's wall area and modulus from EA, EI and D.
#[test]
fn the_tube_of_ea_ei_and_d_is_the_steel_tube() {
    let t = Tube::of(&tube_properties()).expect("a homogeneous tube");
    println!("A {:.6e} m^2 (exact {:.6e}), E {:.6e} Pa", t.area, tube_area(), t.modulus);
    assert!((t.area - tube_area()).abs() <= 1e-12 * tube_area());
    assert!((t.modulus - E).abs() <= 1e-12 * E);
    // a flexible pipe's EI is far below a tube's: no tube, no stress
    let flexible = LineProperties { bending_stiffness: 1e-3 * E * tube_inertia(), ..tube_properties() };
    assert!(Tube::of(&flexible).is_none());
}

/// Small tip load: the moment is linear, M(s) = P (L − s), which the cubic
/// Hermite rod represents exactly; the curvature M/EI and the outer-fibre
/// stress M (D/2)/I at the largest point, within 1e-4 (the geometric
/// nonlinearity at a tip deflection of L/3e4 and the penalty's shear).
#[test]
fn cantilever_bending_moment_curvature_and_stress_match_beam_theory() {
    let (l, n) = (10.0, 16);
    let p = 1e-4 * E * tube_inertia() / (l * l);
    let d = cantilever(n, l, p);
    let s = d.max_bending_moment_s;
    let moment = p * (l - s);
    let stress = moment * 0.5 * D / tube_inertia();
    let (stress_fem, stress_s) = d.max_stress.expect("a steel tube has stresses");
    println!(
        "M {:.6e} N m at S = {s:.4} m (P (L - S) {moment:.6e}); curvature {:.6e} (M/EI {:.6e}); stress {stress_fem:.6e} Pa \
         at {stress_s:.4} m (M c / I {stress:.6e})",
        d.max_bending_moment,
        d.max_curvature,
        moment / (E * tube_inertia())
    );
    assert!(s < l / n as f64, "the largest moment is in the clamp's element, S = {s}");
    assert!((d.max_bending_moment - moment).abs() <= 1e-4 * moment);
    assert!((d.max_curvature - moment / (E * tube_inertia())).abs() <= 1e-4 * d.max_curvature);
    assert!((d.min_bend_radius * d.max_curvature - 1.0).abs() < 1e-12);
    assert_eq!(stress_s, s);
    assert!((stress_fem - stress).abs() <= 1e-4 * stress, "stress {stress_fem} vs {stress}");
}

/// Large deflection (P L²/EI = 5): the clamp moment is P times the tip's
/// horizontal distance from the clamp, P L (1 − u) with u the elastica's
/// shortening (Bisshopp & Drucker); at the first Gauss point S_g from the
/// clamp, P (L (1 − u) − S_g) (the line leaves the clamp horizontally), within
/// 2e-3 at 32 elements.
#[test]
fn elastica_clamp_moment_matches_the_closed_form() {
    let (l, n, alpha) = (10.0, 32, 5.0);
    let p = alpha * E * tube_inertia() / (l * l);
    let d = cantilever(n, l, p);
    let (_, u) = cantilever_elastica(alpha).unwrap();
    let moment = p * (l * (1.0 - u) - d.max_bending_moment_s);
    let err = (d.max_bending_moment - moment).abs() / moment;
    println!("M {:.6e} N m (closed form {moment:.6e}), error {err:.2e}", d.max_bending_moment);
    assert!(err <= 2e-3);
}

/// A vertical line stretched between its ends (hang-off above the anchor, δ
/// beyond its length): T(s) = T_b + w (L − s) with T_b = EA δ / L − w L / 2,
/// and the outer-fibre stress T_w/A at the top Gauss point, T_w = T −
/// p_e π D²/4 the true wall tension under the water's pressure
/// p_e = ρ_w g (z_s − z) (docs/theory.md §12.4), within 1e-6; the one
/// warning is the anchor's reach.
#[test]
fn straight_tensioned_line_stress_is_tension_over_wall_area() {
    let (ea, ei, dia) = (3.38e9, 2.71e7, 0.2731); // steel_catenary's pipe
    let (l, delta) = (100.0, 0.05);
    let sc = Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[
            format!("axial_stiffness={ea}"),
            format!("bending_stiffness={ei}"),
            format!("outer_diameter={dia}"),
            "anchor_x=0".to_string(),
            format!("anchor_z={}", -(l + delta)),
            "newton_tolerance=1e-10".to_string(),
        ])
        .unwrap();
    let w = -riser::loads::vertical_load(&sc).uniform;
    let sim = Simulation::from_scene(&sc).unwrap();
    let design = Design::new(&sc);
    let (d, warnings) = design.report(&sc, &sim.integrator, &sim.state);
    let (stress, s) = d.max_stress.expect("a steel tube");
    let t_b = ea * delta / l - w * l / 2.0;
    let tension = t_b + w * (l - s);
    let d_in2 = 16.0 * ei / ea - dia * dia;
    let area = std::f64::consts::PI * (dia * dia - d_in2) / 4.0;
    let env = &sc.environment;
    let p_e = env.water_density * env.gravity * (env.water_surface_z + s * (1.0 + delta / l));
    let wall_tension = tension - p_e * std::f64::consts::PI * dia * dia / 4.0;
    println!(
        "stress {stress:.6e} Pa at S = {s:.4} m, T_w/A {:.6e} Pa (T/A {:.6e}); angle {}",
        wall_tension / area,
        tension / area,
        d.hang_off_angle
    );
    assert!((stress - wall_tension / area).abs() <= 1e-6 * stress);
    assert!(d.hang_off_angle.abs() < 1e-6, "a vertical line hangs at 0 deg, got {}", d.hang_off_angle);
    assert!(d.max_curvature < 1e-9 && d.max_bending_moment < 1e-9 * ei);
    // the anchor lies beyond the unstretched length (that is how it is stretched), at a strain well below 1 %
    assert!(warnings.len() == 1 && warnings[0].contains("beyond the line's unstretched length"), "{warnings:?}");
}

/// The touchdown (S and x) and the hang-off angle of the steel catenary
/// (EI → 0, a stiff seabed) against the elastic catenary with touchdown:
/// S_td = L − L_B, x_td = (H/w) asinh(V/H) + H (L − L_B)/EA, the angle
/// atan(H/V) from the vertical; within 1 % of the lying length, 0.5 % of
/// x_td and 0.05 deg, rod and cable at 100 elements (4 m). The rod with
/// EI → 0 warns that its bending length is beyond any mesh.
#[test]
fn touchdown_and_hang_off_angle_match_the_catenary_with_touchdown() {
    for model in ["cable", "rod"] {
        let sc = Scene::builtin("steel_catenary")
            .unwrap()
            .with_overrides(&[
                format!("model={model}"),
                "bending_stiffness=1".into(),
                "torsional_stiffness=1".into(),
                "seabed_stiffness=1e9".into(),
                "n_elements=100".into(),
            ])
            .unwrap();
        let w = -riser::loads::vertical_load(&sc).uniform;
        let a = sc.anchor();
        let ea = sc.line.axial_stiffness;
        let r = catenary_on_seabed(sc.line.length, w, ea, a.x, -a.z).unwrap();
        let suspended = sc.line.length - r.lying;
        let x_td = r.h / w * (r.v_top / r.h).asinh() + r.h * suspended / ea;
        let angle = (r.h / r.v_top).atan().to_degrees();
        let sim = Simulation::from_scene(&sc).unwrap();
        let (d, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
        let (s_td, x) = (d.touchdown_s.unwrap(), d.touchdown_x.unwrap());
        println!(
            "{model}: touchdown S {s_td:.2} m ({suspended:.2}), x {x:.2} m ({x_td:.2}), angle {:.4} deg ({angle:.4})",
            d.hang_off_angle
        );
        assert!((s_td - suspended).abs() <= 0.01 * r.lying, "{model}: S_td {s_td} vs {suspended}");
        assert!((x - x_td).abs() <= 5e-3 * x_td, "{model}: x_td {x} vs {x_td}");
        assert!((d.hang_off_angle - angle).abs() <= 0.05, "{model}: angle {} vs {angle}", d.hang_off_angle);
        // EI = 1 N m^2: a bending length of millimetres that no mesh resolves, which the rod says
        match model {
            "cable" => assert!(warnings.is_empty(), "{model}: {warnings:?}"),
            _ => assert!(warnings.len() == 1 && warnings[0].contains("model=cable"), "{model}: {warnings:?}"),
        }
    }
}

/// The steel catenary at the given overrides: its scene, static outputs and warnings.
fn steel_catenary_statics(sets: &[&str]) -> (Scene, riser::model::Outputs, Vec<String>) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let sc = Scene::builtin("steel_catenary").unwrap().with_overrides(&sets).unwrap();
    let sim = Simulation::from_scene(&sc).unwrap();
    let (_, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    (sc, sim.outputs(), warnings)
}

/// Issue 52: the steel catenary (400 m in 200 m of water) with its anchor
/// moved out to 340 m, too far for the line to reach its seabed, lifts the
/// anchor. The uplift angle of the line's force on the anchor, atan2(V, H),
/// against Irvine's elastic catenary between the hang-off and the anchor
/// (12.038 deg, H 504.2 kN, V 107.5 kN): the cable within 5e-4 of it
/// (12.0367 deg at 80 elements, converging as h²: 12.0383 at 320); the rod
/// within 1 %: its EI's boundary layers at the pinned ends, √(EI/T) = 7.3 m,
/// take a share of the weight off the anchor, 11.9665 deg on 40 to 320
/// elements alike (the mesh's part is 1e-6 deg). The warning gives that
/// angle and the vertical force, to their printed digits, and the length
/// and the distance at which a uniform line reaches its seabed at its
/// anchor: checked against Irvine's catenary made inextensible (EA 1e13 N),
/// whose anchor force turns from up to down within ±0.05 m of each printed
/// number. On a seabed sloping 2 deg up towards the anchor (345 m out,
/// on it), the cable's angle from the plane is Irvine's atan2(V, H) plus
/// the slope, within 5e-4.
#[test]
fn an_anchor_lifted_off_its_seabed_warns_with_the_catenary_s_uplift_angle() {
    let (l, depth, span) = (400.0, 200.0, 340.0);
    for (model, tolerance) in [("cable", 5e-4), ("rod", 1e-2)] {
        let (sc, o, warnings) = steel_catenary_statics(&[&format!("anchor_x={span}"), &format!("model={model}")]);
        let w = -riser::loads::vertical_load(&sc).uniform;
        let r = elastic_catenary(l, w, sc.line.axial_stiffness, span, -depth).unwrap();
        let reference = r.v_bottom.atan2(r.h).to_degrees();
        let angle = riser::sim::design::anchor_uplift(&sc, o.bottom_force).unwrap();
        let f = o.bottom_force;
        println!(
            "{model}: uplift {angle:.4} deg ({reference:.4}), H {:.1} kN ({:.1}), V {:.1} kN ({:.1}); touchdown {}",
            f.x.hypot(f.y) / 1e3,
            r.h / 1e3,
            f.z / 1e3,
            r.v_bottom / 1e3,
            o.touchdown_s
        );
        assert!(o.touchdown_s >= l, "{model}: the line touches down at {}", o.touchdown_s);
        assert!((angle - reference).abs() <= tolerance * reference, "{model}: {angle} deg against {reference}");
        // the angle is atan2 of the force's components (a flat seabed)
        assert!((angle - f.z.atan2(f.x.hypot(f.y)).to_degrees()).abs() < 1e-12);
        let lifted: Vec<&String> = warnings.iter().filter(|m| m.contains("lifted off the seabed")).collect();
        assert_eq!(lifted.len(), 1, "{model}: {warnings:?}");
        let m = lifted[0];
        for part in [
            format!("pulls its anchor up at {angle:.2} deg above the seabed"),
            format!("a vertical force of {:.3} kN (of {:.3} kN)", f.z / 1e3, f.norm() / 1e3),
            "within 329.6 m of the hang-off horizontally, and one of 408.7 m at this anchor".to_string(),
            "suction or driven pile".to_string(),
        ] {
            assert!(m.contains(&part), "{model}: '{part}' not in {m}");
        }
    }
    // a seabed sloping 2 deg up towards the anchor (x = 345 m, 188.0 m down, on it), the cable: the angle
    // from its plane is Irvine's atan2(V, H) plus the slope; no bounds (a sloping seabed)
    let mut sc = Scene::builtin("steel_catenary").unwrap().with_overrides(&["model=cable".to_string()]).unwrap();
    let bed = sc.seabed.as_mut().unwrap();
    bed.slope = 2.0;
    (sc.anchor.x, sc.anchor.z) = (345.0, bed.height_at(345.0, 0.0));
    let sim = Simulation::from_scene(&sc).unwrap();
    let (_, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
    let w = -riser::loads::vertical_load(&sc).uniform;
    let r = elastic_catenary(l, w, sc.line.axial_stiffness, sc.anchor.x, sc.anchor.z).unwrap();
    let reference = r.v_bottom.atan2(r.h).to_degrees() + 2.0;
    let angle = riser::sim::design::anchor_uplift(&sc, sim.outputs().bottom_force).unwrap();
    println!("sloping seabed: uplift {angle:.4} deg ({reference:.4}); {warnings:?}");
    assert!((angle - reference).abs() <= 5e-4 * reference, "{angle} deg against {reference}");
    let m = warnings.iter().find(|m| m.contains("lifted off the seabed")).expect("warned");
    assert!(m.contains(&format!("up at {angle:.2} deg")) && !m.contains("horizontally"), "{m}");
    // the printed bounds: the inextensible catenary's anchor force turns from down to up across each
    let v_bottom = |length: f64, x: f64| elastic_catenary(length, 1e3, 1e13, x, -depth).unwrap().v_bottom;
    assert!(v_bottom(l, 329.55) < 0.0 && v_bottom(l, 329.65) > 0.0);
    assert!(v_bottom(408.75, span) < 0.0 && v_bottom(408.65, span) > 0.0);
}

/// Issue 52: what is not an anchor lifted off its seabed. The built-in
/// scenes as they are: the catenary and the lazy wave have no seabed (no
/// angle); the steel catenary's lying line pulls its anchor along the
/// seabed, pressed down by the weight of its last half element (−1.07 deg).
/// The steel catenary's anchor at 329 m, within the 329.6 m at which the
/// line reaches its seabed at the anchor: the line touches the seabed
/// nowhere (its last metres bridged by its bending stiffness) but comes down
/// onto its anchor and presses it (−0.83 deg, no warning); at 330 m it
/// lifts the anchor (0.15 deg, warned). At 340 m, an anchor 10 m above
/// the seabed is a mid-water one: no angle, no warning; 0.5 m above, it
/// sits on the seabed (within `ANCHOR_ON_SEABED`) and is lifted off it. The anchor 50 m from the hang-off
/// has 350 m of line on the seabed, pushed into compression (−66 kN) and
/// buckled up at the anchor (an uplift of 5.9 deg while the line touches
/// down): the compression warning's, not this one's.
#[test]
fn an_anchor_on_a_touching_down_line_or_in_mid_water_is_not_lifted_off() {
    for name in ["catenary", "lazy_wave", "steel_catenary"] {
        let sc = Scene::builtin(name).unwrap();
        let sim = Simulation::from_scene(&sc).unwrap();
        let (_, warnings) = Design::new(&sc).report(&sc, &sim.integrator, &sim.state);
        let uplift = riser::sim::design::anchor_uplift(&sc, sim.outputs().bottom_force);
        println!("{name}: uplift {uplift:?} deg");
        assert!(!warnings.iter().any(|m| m.contains("lifted off")), "{name}: {warnings:?}");
        match name {
            "steel_catenary" => assert!(uplift.is_some_and(|a| a < -1.0 && a > -1.1), "{uplift:?}"),
            _ => assert!(uplift.is_none(), "{name}: {uplift:?}"),
        }
    }
    let lifted = |sets: &[&str]| {
        let (sc, o, warnings) = steel_catenary_statics(sets);
        let uplift = riser::sim::design::anchor_uplift(&sc, o.bottom_force);
        let warned = warnings.iter().any(|m| m.contains("lifted off the seabed"));
        println!("{sets:?}: uplift {uplift:?} deg, touchdown {} m, warned {warned}", o.touchdown_s);
        assert_eq!(warned, riser::sim::design::anchor_lifted(&sc, &o).is_some(), "{sets:?}");
        (uplift, o.touchdown_s < sc.line.length, warned)
    };
    assert!(matches!(lifted(&["anchor_x=329"]), (Some(a), false, false) if a < 0.0));
    assert!(matches!(lifted(&["anchor_x=330"]), (Some(a), false, true) if a > 0.0 && a < 0.3));
    assert!(matches!(lifted(&["anchor_x=340", "anchor_z=-190"]), (None, false, false)));
    assert!(matches!(lifted(&["anchor_x=340", "anchor_z=-199.5"]), (Some(a), false, true) if a > 0.0));
    assert!(matches!(lifted(&["anchor_x=50"]), (Some(a), true, false) if a > 5.0));
}
