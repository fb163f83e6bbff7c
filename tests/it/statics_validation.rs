//! Evidence 3–6 of the statics issue: the rod against closed forms and
//! independent cable calculations (tests/it/common/reference.rs shares no code
//! with the crate).

use crate::common;
use common::reference::{cantilever_elastica, elastic_catenary, piecewise_catenary};
use nalgebra::Vector3;
use riser::loads::weight::VerticalLoad;
use riser::model::rod::statics::{StaticLoads, StaticProblem};
use riser::model::rod::{EndBc, Rod, Stiffness};
use riser::model::statics::StaticOptions;
use riser::scene::Scene;
use riser::sim::report::{StaticReport, solve_scene};
use riser::solve::statics::solve;

fn scene(name: &str, sets: &[&str]) -> Scene {
    Scene::builtin(name).unwrap().with_overrides(sets).unwrap()
}

fn statics(name: &str, sets: &[&str]) -> StaticReport {
    solve_scene(&scene(name, sets)).unwrap()
}

/// Clamped–free cantilever with a dead vertical tip load; returns the tip
/// displacement (m).
fn cantilever_tip(n_el: usize, ei: f64, ea: f64, load: f64) -> Vector3<f64> {
    let rod = Rod::new(n_el, 1.0, Stiffness::paper(ea, ei, ei), [EndBc::CLAMPED, EndBc::FREE]);
    let start = rod.straight(Vector3::zeros(), Vector3::x(), Vector3::y());
    let mut loads = StaticLoads::gravity_only(VerticalLoad { uniform: 0.0, sections: vec![] });
    loads.point_forces.push((n_el, Vector3::new(0.0, 0.0, -load)));
    let opts = StaticOptions { tolerance: 1e-11, ..Default::default() };
    let sol = solve(&StaticProblem::new(&rod, &loads), start, &opts).expect("cantilever converges");
    sol.config.x[n_el] - Vector3::new(1.0, 0.0, 0.0)
}

#[test]
fn cantilever_small_load_matches_pl3_over_3ei() {
    let (ei, ea, l) = (1.0e3, 1.0e9, 1.0);
    let p = 1e-4 * ei / (l * l);
    let tip = cantilever_tip(8, ei, ea, p);
    // Euler–Bernoulli plus the (here 3e-7 relative) shear compliance of the penalty R = EA
    let exact = p * l.powi(3) / (3.0 * ei) + p * l / ea;
    let err = (-tip.z - exact).abs() / exact;
    println!("cantilever: tip {:.6e} m, PL^3/3EI {:.6e} m, error {:.2e}", -tip.z, exact, err);
    assert!(err < 1e-3, "tip deflection error {err:.3e} > 0.1%");
}

#[test]
fn large_deflection_elastica_matches_bisshopp_drucker() {
    let (ei, ea) = (1.0e3, 1.0e9);
    for alpha in [1.0, 5.0] {
        let tip = cantilever_tip(16, ei, ea, alpha * ei);
        let (v, u) = cantilever_elastica(alpha).unwrap();
        let err = ((-tip.z - v).powi(2) + (-tip.x - u).powi(2)).sqrt() / v.hypot(u);
        println!(
            "elastica PL^2/EI = {alpha}: rod ({:.5}, {:.5}) reference ({v:.5}, {u:.5}) error {err:.2e}",
            -tip.z, -tip.x
        );
        assert!(err < 5e-3, "tip error {err:.3e} > 0.5% at PL^2/EI = {alpha}");
    }
}

fn catenary_w(s: &Scene) -> f64 {
    -riser::loads::vertical_load(s).uniform
}

#[test]
fn catenary_matches_the_elastic_catenary() {
    // EI, GJ negligible: bending length sqrt(EI/T) below a millimetre
    let sc = scene("catenary", &["bending_stiffness=1e-3", "torsional_stiffness=1e-3"]);
    let rep = solve_scene(&sc).unwrap();
    let r = elastic_catenary(sc.line.length, catenary_w(&sc), sc.line.axial_stiffness, 60.0, -70.0).unwrap();
    let checks = [
        ("top tension", rep.top_tension, r.top_tension),
        ("bottom tension", rep.bottom_tension, r.bottom_tension),
        ("horizontal force", rep.top_force.x, r.h),
        ("vertical force at the top", -rep.top_force.z, r.v_top),
    ];
    for (what, got, want) in checks {
        let err = (got - want).abs() / r.top_tension;
        println!("EI -> 0: {what}: rod {got:.3} N, elastic catenary {want:.3} N, error {err:.2e}");
        assert!(err < 2e-3, "{what}: {got} vs {want}");
    }
    // the vertical force at the anchor (small, the line reaches it from below)
    let err = (-rep.bottom_force.z - (-r.v_bottom)).abs() / r.top_tension;
    assert!(err < 2e-3, "anchor vertical force error {err}");

    // with the real bending stiffness: within 1%
    let rep = statics("catenary", &[]);
    let err = (rep.top_tension - r.top_tension).abs() / r.top_tension;
    println!("paper EI: top tension {:.3} N vs elastic catenary {:.3} N ({err:.2e})", rep.top_tension, r.top_tension);
    assert!(err < 1e-2);
    let err = (rep.top_force.x - r.h).abs() / r.h;
    assert!(err < 1e-2, "horizontal force {} vs {}", rep.top_force.x, r.h);
}

#[test]
fn end_reactions_balance_the_applied_load_exactly() {
    for name in ["catenary", "lazy_wave"] {
        let sc = scene(name, &[]);
        let rep = solve_scene(&sc).unwrap();
        let total = riser::loads::vertical_load(&sc).total(sc.line.length);
        // the supports carry the weight: F_top + F_bottom (on the line) + total load = 0
        let f = rep.solution.reactions[0] + rep.solution.reactions[1] + Vector3::new(0.0, 0.0, total);
        println!("{name}: reactions + load = {f:?} N (load {total:.1} N)");
        assert!(f.norm() < 1e-9 * total.abs(), "{name}: imbalance {f}");
    }
}

#[test]
fn catenary_top_tension_converges_with_the_mesh() {
    let meshes = [10usize, 20, 40, 60, 120, 240];
    let t: Vec<f64> = meshes.iter().map(|n| statics("catenary", &[&format!("n_elements={n}")]).top_tension).collect();
    let reference = t[t.len() - 1];
    let errs: Vec<f64> = t.iter().map(|v| (v - reference).abs() / reference).collect();
    for i in 0..meshes.len() - 1 {
        println!("n = {:3}: top tension {:.4} N, relative difference to n = 240: {:.2e}", meshes[i], t[i], errs[i]);
    }
    for i in 0..meshes.len() - 2 {
        let order = (errs[i] / errs[i + 1]).ln() / (meshes[i + 1] as f64 / meshes[i] as f64).ln();
        println!("observed order {} -> {}: {order:.2}", meshes[i], meshes[i + 1]);
        assert!(errs[i + 1] < errs[i], "no convergence between {} and {}", meshes[i], meshes[i + 1]);
    }
    assert!(errs[0] < 1e-4, "10 elements: {:.2e}", errs[0]);
    assert!(errs[2] < 1e-5, "40 elements: {:.2e}", errs[2]);
    // and the EI → 0 line converges to the elastic catenary itself
    let sc = scene("catenary", &[]);
    let r = elastic_catenary(100.0, catenary_w(&sc), sc.line.axial_stiffness, 60.0, -70.0).unwrap();
    let mut prev = f64::INFINITY;
    for n in [10, 20, 40] {
        let top =
            statics("catenary", &["bending_stiffness=1e-3", "torsional_stiffness=1e-3", &format!("n_elements={n}")])
                .top_tension;
        let e = (top - r.top_tension).abs() / r.top_tension;
        println!("EI -> 0, n = {n}: error to the elastic catenary {e:.2e}");
        assert!(e < prev);
        prev = e;
    }
}

fn local_extrema(rep: &StaticReport) -> (Vec<f64>, Vec<f64>) {
    let z: Vec<f64> = rep.shape.iter().map(|r| r.z).collect();
    let mut mins = Vec::new();
    let mut maxs = Vec::new();
    for i in 1..z.len() - 1 {
        if z[i] < z[i - 1] && z[i] <= z[i + 1] {
            mins.push(rep.shape[i].s);
        }
        if z[i] > z[i - 1] && z[i] >= z[i + 1] {
            maxs.push(rep.shape[i].s);
        }
    }
    (mins, maxs)
}

#[test]
fn lazy_wave_has_sag_and_hog_bends_and_matches_the_piecewise_catenary() {
    let sc = scene("lazy_wave", &[]);
    let w = -riser::loads::vertical_load(&sc).uniform;
    let segments = [(50.0, w), (30.0, w - 670.0), (20.0, w)];
    let r = piecewise_catenary(&segments, sc.line.axial_stiffness, 50.0, -40.0).unwrap();

    // the paper's line: a sag bend before the buoyant section, a hog bend over it
    let rep = statics("lazy_wave", &[]);
    let (mins, maxs) = local_extrema(&rep);
    println!("lazy wave (paper EI): sag at S = {mins:?}, hog at S = {maxs:?}, top tension {:.1} N", rep.top_tension);
    assert!(mins.iter().any(|&s| s > 30.0 && s < 50.0), "no sag bend before S = 50 m");
    assert!(maxs.iter().any(|&s| (50.0..=80.0).contains(&s)), "no hog bend over the buoyancy modules");

    // against the cable reference the bending stiffness must be small next to
    // T·R² at the bends (R ≈ H/w ≈ 3.5 m here): EI = 1e4 N m² (10 % of the
    // paper's), 120 elements
    let rep = statics("lazy_wave", &["bending_stiffness=1e4", "n_elements=120"]);
    let err = (rep.top_tension - r.top_tension).abs() / r.top_tension;
    println!(
        "lazy wave EI = 1e4: top tension {:.1} N, piecewise catenary {:.1} N, error {err:.2e}",
        rep.top_tension, r.top_tension
    );
    assert!(err < 2e-2);
    let (mins, maxs) = local_extrema(&rep);
    assert!(mins.iter().any(|&s| s > 30.0 && s < 50.0) && maxs.iter().any(|&s| (50.0..=80.0).contains(&s)));
}

#[test]
fn both_scenes_converge_from_4_to_400_elements() {
    // reference: 400 elements; coarse meshes within the stated bounds
    for (scene, coarse_tol, tol) in [("catenary", 1e-3, 2e-4), ("lazy_wave", 3e-2, 2e-3)] {
        let top = |n: usize| {
            let s = Scene::builtin(scene).unwrap().with_overrides(&[format!("n_elements={n}")]).unwrap();
            let rep = solve_scene(&s).unwrap_or_else(|e| panic!("{scene}, {n} elements: {e}"));
            rep.top_tension
        };
        let reference = top(400);
        for n in [4usize, 10, 20, 40, 60, 120, 240] {
            let t = top(n);
            let err = (t - reference).abs() / reference;
            eprintln!("{scene} {n:3} elements: top tension {t:.1} N, {err:.2e} from 400 elements");
            assert!(err <= if n == 4 { coarse_tol } else { tol }, "{scene}, {n} elements: {err:e}");
        }
    }
}
