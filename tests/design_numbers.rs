//! The design numbers (issue 31, docs/theory.md §12) against closed forms:
//! the bending moment, curvature and outer-fibre stress of a clamped
//! cantilever (small load: M = P (L − s); large deflection: the elastica's
//! clamp moment P L (1 − u)), the stress of a straight tensioned line (a
//! vertical line stretched between its ends: T(s) = T_b + w (L − s)), and the
//! touchdown point and hang-off angle of the catenary with touchdown
//! (tests/common/reference.rs, independent of the crate).

mod common;

use common::reference::{cantilever_elastica, catenary_on_seabed};
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
    design.of_points(&rod.gauss_points(&sol.config), sol.config.xp[0], None)
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
/// and the outer-fibre stress T/A at the top Gauss point, within 1e-6; the
/// one warning is the anchor's reach.
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
    println!("stress {stress:.6e} Pa at S = {s:.4} m, T/A {:.6e} Pa; angle {}", tension / area, d.hang_off_angle);
    assert!((stress - tension / area).abs() <= 1e-6 * stress);
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
