//! Line sections and buoyancy modules (issue 17, docs/theory.md §11), rod
//! and cable: a two-section line's statics against the piecewise elastic
//! catenary (tests/it/common/reference.rs, independent of the crate); the
//! lazy wave built with physical modules against today's bare 670 N/m load
//! when the modules' drag and added mass are off; the equivalent line's
//! weight and buoyancy against the modules counted one by one; energy
//! conserved on a sectioned line; bad input.

use crate::common;

use common::reference::{joined_strings_frequencies, piecewise_catenary_sections};
use riser::scene::Scene;
use riser::sim::report::solve_scene;
use riser::sim::{Heave, Simulation};

/// A 300 m line of two sections between the origin and (200, 0, −180) m:
/// 180 m of a light, stiff pipe above 120 m of a heavy, soft one (EA ten
/// times smaller: the stretch jumps at the boundary). EI → 0 for the
/// catenary. `extra`: more TOML lines for `[analysis]`.
fn two_sections(extra: &str) -> Scene {
    let text = format!(
        r#"
name = "two_sections"
[line]
length = 300.0
mass_per_length = 100.0
outer_diameter = 0.3
axial_stiffness = 3.0e8
bending_stiffness = 1.0
torsional_stiffness = 1.0
[anchor]
x = 200.0
z = -180.0
[[section]]
length = 180.0
[[section]]
length = 120.0
mass_per_length = 250.0
outer_diameter = 0.35
axial_stiffness = 3.0e7
[analysis]
{extra}
"#
    );
    Scene::from_toml(&text, "two_sections").unwrap()
}

/// Net downward load per length of a bare section (N/m).
fn wet_weight(m: f64, d: f64) -> f64 {
    (m - 1025.0 * std::f64::consts::PI * d * d / 4.0) * 9.81
}

/// Item 5: the statics of the two-section line against the piecewise
/// catenary with the sections' own weights and EA: the hang-off's
/// horizontal and vertical force and the anchor's tension within 0.5 %
/// (the issue's catenary tolerance; measured: a few 1e-5), the boundary
/// node within 0.05 % of the line's length of the reference point, rod and
/// cable, with the boundary on a node (60 elements) and inside an element
/// (61: that element gets the mean mass and the series EA).
#[test]
fn a_two_section_line_matches_the_piecewise_catenary() {
    let r = piecewise_catenary_sections(
        &[(180.0, wet_weight(100.0, 0.3), 3.0e8), (120.0, wet_weight(250.0, 0.35), 3.0e7)],
        200.0,
        -180.0,
    )
    .unwrap();
    let at_boundary = r.shape.iter().min_by(|a, b| (a.0 - 180.0).abs().total_cmp(&(b.0 - 180.0).abs())).unwrap();
    for model in ["rod", "cable"] {
        for n in [60, 61] {
            let sc = two_sections(&format!("model = \"{model}\"\nn_elements = {n}"));
            let sim = Simulation::from_scene(&sc).unwrap();
            let o = sim.outputs();
            let (h, v) = (o.top_force.x, -o.top_force.z);
            let rel = |a: f64, b: f64| (a - b).abs() / b;
            println!(
                "{model}, {n} elements: H {h:.2} N (reference {:.2}, {:.1e}), V {v:.2} N ({:.2}, {:.1e}), bottom \
                 {:.2} N ({:.2}, {:.1e})",
                r.h,
                rel(h, r.h),
                r.v_top,
                rel(v, r.v_top),
                o.bottom_tension,
                r.bottom_tension,
                rel(o.bottom_tension, r.bottom_tension)
            );
            assert!(rel(h, r.h) <= 5e-3, "{model} {n}: H {h} vs {}", r.h);
            assert!(rel(v, r.v_top) <= 5e-3, "{model} {n}: V {v} vs {}", r.v_top);
            assert!(rel(o.bottom_tension, r.bottom_tension) <= 5e-3, "{model} {n}: bottom {}", o.bottom_tension);
            if n == 60 {
                // node 36 is at S = 180 m
                let x = solve_scene(&sc).unwrap().solution.config.x[36];
                let miss = (x.x - at_boundary.1).hypot(x.z - at_boundary.2);
                println!("  boundary node off the reference by {miss:.4} m");
                assert!(miss <= 5e-4 * 300.0, "{model}: boundary node {x:?} vs {at_boundary:?}");
            }
        }
    }
}

/// The lazy wave's modules as bodies: 1 m long, 1.0 m in diameter, every
/// 2 m on S ∈ [50, 80] m, their mass chosen so that buoyancy less weight is
/// the paper's 670 N/m.
fn lazy_wave_with_modules(module_coefficients: &str, model: &str) -> Scene {
    let lw = Scene::builtin("lazy_wave").unwrap();
    let (rho, g, d) = (lw.environment.water_density, lw.environment.gravity, lw.line.outer_diameter);
    let (dm, lm, p) = (1.0, 1.0, 2.0);
    let lift = rho * g * (lm / p) * std::f64::consts::PI * (dm * dm - d * d) / 4.0;
    let mass = (lift - 670.0) * p / g;
    let mut text = lw.to_toml();
    // no bare load: the modules make it
    let b = text.find("[[buoyancy]]").unwrap();
    let end = text[b..].find("\n\n").map_or(text.len(), |e| b + e);
    text.replace_range(b..end, "");
    text.push_str(&format!(
        "\n[[section]]\nlength = 50.0\n\n[[section]]\nlength = 30.0\nmodule_diameter = {dm}\nmodule_length = \
         {lm}\nmodule_pitch = {p}\nmodule_mass = {mass}\n{module_coefficients}\n\n[[section]]\nlength = 20.0\n"
    ));
    Scene::from_toml(&text, "lazy_wave_modules").unwrap().with_overrides(&[format!("model={model}")]).unwrap()
}

/// Item 5: with the modules' drag and added mass off, the lazy wave built
/// with physical modules has today's static state (the bare 670 N/m load),
/// also in the current (static_current: the line's own drag is kept
/// everywhere): top force and every node within 1e-6 relative (the Newton
/// tolerance), rod and cable. With the modules' drag on, the current pushes
/// the modules' section harder: the static state moves downstream.
#[test]
fn the_lazy_wave_with_modules_reproduces_the_670_n_per_m_load_case() {
    for model in ["rod", "cable"] {
        for current in [false, true] {
            let sets = [format!("model={model}"), format!("static_current={current}")];
            let today = Scene::builtin("lazy_wave").unwrap().with_overrides(&sets).unwrap();
            let mut modules = lazy_wave_with_modules("module_cd_normal = 0.0\nmodule_ca_normal = 0.0", model);
            modules.analysis.static_current = current;
            let (a, b) = (solve_scene(&today).unwrap(), solve_scene(&modules).unwrap());
            let (fa, fb) = (a.solution.reactions[0], b.solution.reactions[0]);
            let scale = fa.norm();
            let worst =
                a.solution.config.x.iter().zip(&b.solution.config.x).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
            println!(
                "{model}, current {current}: top force {fa:?} vs {fb:?} ({:.1e}); nodes within {worst:.2e} m",
                (fa - fb).norm() / scale
            );
            assert!((fa - fb).norm() <= 1e-6 * scale, "{model}: {fa:?} vs {fb:?}");
            assert!(worst <= 1e-6 * today.line.length, "{model}: nodes differ by {worst} m");
        }
        // the modules' own drag (C_d 1.2 on D_m − D) in the same current
        let mut dragged = lazy_wave_with_modules("module_ca_normal = 0.0", model);
        dragged.analysis.static_current = true;
        let mut bare = Scene::builtin("lazy_wave").unwrap().with_overrides(&[format!("model={model}")]).unwrap();
        bare.analysis.static_current = true;
        let xa = solve_scene(&bare).unwrap().solution.config.x[30].x;
        let xb = solve_scene(&dragged).unwrap().solution.config.x[30].x;
        println!("{model}: the buoyant section's middle at x = {xb:.3} m with module drag, {xa:.3} m without");
        assert!(xb > xa + 0.1, "{model}: module drag moved the line by {} m", xb - xa);
    }
}

/// The equivalent line (11.1–11.2) carries the weight and buoyancy of the
/// modules counted one by one: 15 modules on the 30 m section, each of
/// volume π (D_m² − D²) L_m / 4 and mass M_m; the total vertical load of
/// the line equals the bare line's plus theirs to round-off.
#[test]
fn the_equivalent_line_carries_the_modules_counted_one_by_one() {
    let sc = lazy_wave_with_modules("", "rod");
    let lw = Scene::builtin("lazy_wave").unwrap();
    let (rho, g, d) = (lw.environment.water_density, lw.environment.gravity, lw.line.outer_diameter);
    let m = sc.section[1].modules().unwrap();
    let count = 30.0 / m.pitch;
    let each = rho * g * std::f64::consts::PI * (m.diameter * m.diameter - d * d) / 4.0 * m.length - m.mass * g;
    let bare = -wet_weight(lw.line.mass_per_length, d) * 100.0;
    let expected = bare + count * each;
    let total = riser::loads::vertical_load(&sc).total(100.0);
    println!("vertical load {total:.3} N, bare line plus {count} modules {expected:.3} N");
    assert!((total - expected).abs() <= 1e-9 * expected.abs(), "{total} vs {expected}");
    // and the rod's and the cable's mass: line and modules
    let mass = lw.line.mass_per_length * 100.0 + count * m.mass;
    let rod = riser::model::rod::RodModel::from_scene(&sc).total_mass();
    let cable = riser::model::cable::CableModel::from_scene(&sc).total_mass();
    assert!((rod - mass).abs() <= 1e-9 * mass && (cable - mass).abs() <= 1e-9 * mass, "{rod} {cable} vs {mass}");
    // rotary inertia: the line's m D²/8 plus each module as a thick tube about a
    // transverse axis, M (D_m² + D²)/16 per module (11.5), over the 30 m section
    let model = riser::model::rod::RodModel::from_scene(&sc);
    let h = model.rod.h;
    let total: f64 = (0..model.rod.n_el).map(|e| model.mass.at(e).rotary[0] * h).sum();
    let expected =
        lw.line.mass_per_length * d * d / 8.0 * 100.0 + count * m.mass * (m.diameter * m.diameter + d * d) / 16.0;
    println!("rotary inertia {total:.4} kg m², expected {expected:.4}");
    assert!((total - expected).abs() <= 1e-9 * expected, "{total} vs {expected}");
}

/// A `[line]` key reaches every section that does not set its own, the
/// rotary inertia too (also after a `--set`), and a section's own m and D
/// give its default m D²/8; the cable's static current reaches every
/// segment that has drag, whichever the first is.
#[test]
fn line_keys_reach_the_sections_that_leave_them_out() {
    let sc = two_sections("").with_overrides(&["rotary_inertia=7.5"]).unwrap();
    let model = riser::model::rod::RodModel::from_scene(&sc);
    assert_eq!(model.mass.at(0).rotary, [7.5, 7.5]);
    assert_eq!(model.mass.at(59).rotary, [7.5, 7.5], "the heavy section (own mass and D) keeps [line]'s");
    let own = riser::model::rod::RodModel::from_scene(&two_sections(""));
    let j = 250.0 * 0.35 * 0.35 / 8.0;
    assert!((own.mass.at(59).rotary[0] - j).abs() <= 1e-12 * j, "{:?}", own.mass.at(59).rotary);
    // the current on a line whose first 20 m have no drag: rod and cable agree (within their
    // bending difference) and differ from the line without current
    let text = |model: &str, current: bool| {
        let base = two_sections(&format!("model = \"{model}\"\nstatic_current = {current}")).to_toml();
        let base = base.replacen(
            "[[section]]\nlength = 180.0",
            "[[section]]\nlength = 20.0\ncd_normal = 0.0\ncd_tangential = 0.0\n\n[[section]]\nlength = 160.0",
            1,
        );
        let base = base.replacen(
            "cd_normal = 0.0\ncd_tangential = 0.0\nca_normal",
            "cd_normal = 1.2\ncd_tangential = 0.0\nca_normal",
            1,
        );
        Scene::from_toml(&base.replacen("profile = \"none\"", "profile = \"uniform\"\nspeed = 1.5", 1), "current")
            .unwrap()
    };
    let fx = |model: &str, current: bool| solve_scene(&text(model, current)).unwrap().solution.reactions[0].x;
    let (rod, cable, still) = (fx("rod", true), fx("cable", true), fx("cable", false));
    println!(
        "horizontal force at the hang-off: rod {rod:.1} N, cable {cable:.1} N, cable without current {still:.1} N"
    );
    assert!((rod - cable).abs() <= 0.01 * rod.abs(), "rod {rod} vs cable {cable}");
    assert!((cable - still).abs() >= 0.05 * still.abs(), "the current did not reach the cable: {cable} vs {still}");
}

/// Energy on a sectioned line: with the conserving scheme and no water
/// forces, E − E₀ = W_top to the Newton tolerance while the hang-off heaves
/// the two-section line (the boundary inside an element: 61 elements), rod
/// and cable: each element's mass, weight and stiffness are its own, and
/// consistently so.
#[test]
fn a_sectioned_line_conserves_energy() {
    for model in ["rod", "cable"] {
        let sc = two_sections(&format!(
            "model = \"{model}\"\nn_elements = 61\nnewton_tolerance = 1e-11\nrho_infinity = 1.0\ntime_step = 0.02"
        ));
        let mut sim = Simulation::from_scene(&sc).unwrap();
        let heave = Heave { amplitude: 3.0, period: 6.0, until: Some(6.0), ramp: 2.0 };
        sim.start(heave.at(0.0));
        let motion = move |t: f64| heave.at(t);
        let mut out = vec![sim.outputs()];
        let mut t = 0.0;
        while t < 8.0 - 1e-9 {
            t += 0.1;
            sim.advance_to(t, &motion).unwrap();
            out.push(sim.outputs());
        }
        let e0 = out[0].total_energy;
        let exchanged = out.iter().map(|x| x.work_top.abs()).fold(0.0, f64::max);
        let worst = out.iter().map(|x| x.energy_balance_residual(e0).abs()).fold(0.0, f64::max);
        println!("{model}: balance {worst:.3e} J of {exchanged:.3e} J exchanged");
        assert!(exchanged > 1e3, "{model}: the heave did only {exchanged} J");
        assert!(worst <= 1e-7 * exchanged, "{model}: balance {worst:e}");
    }
}

/// Item 7: sections that do not add up to the line, incomplete or
/// impossible modules: each refused naming the field.
#[test]
fn bad_sections_are_refused_naming_the_field() {
    let base = two_sections("").to_toml();
    let refuse = |from: &str, to: &str, needles: &[&str]| {
        assert!(base.contains(from), "{from}");
        let e = Scene::from_toml(&base.replacen(from, to, 1), "t.toml").unwrap_err().to_string();
        for n in needles {
            assert!(e.contains(n), "'{n}' missing from: {e}");
        }
    };
    refuse("length = 120.0", "length = 100.0", &["section[1].length", "add up to 280 m", "line.length is 300"]);
    refuse("length = 120.0", "length = -1.0", &["section[1].length", "is outside"]);
    refuse("mass_per_length = 250.0", "mass_per_length = -250.0", &["section[1].mass_per_length", "is outside"]);
    let modules = "module_diameter = 1.0\nmodule_length = 1.0\nmodule_pitch = 2.0\nmodule_mass = 300.0";
    let with = |m: &str| base.replacen("length = 120.0", &format!("length = 120.0\n{m}"), 1);
    assert!(Scene::from_toml(&with(modules), "t.toml").is_ok());
    let e = Scene::from_toml(&with("module_diameter = 1.0\nmodule_length = 1.0"), "t.toml").unwrap_err().to_string();
    assert!(e.contains("section[1].module_pitch") && e.contains("module_mass"), "{e}");
    let e = Scene::from_toml(&with(&modules.replace("diameter = 1.0", "diameter = 0.2")), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_diameter") && e.contains("larger than the line"), "{e}");
    let e = Scene::from_toml(&with(&modules.replace("pitch = 2.0", "pitch = 0.5")), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_length") && e.contains("longer than the pitch"), "{e}");
    let e = Scene::from_toml(&with("module_cd_normal = 1.0"), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_cd_normal") && e.contains("no modules"), "{e}");
    let e = Scene::from_toml(&with("module_ca_normal = 1.0"), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_ca_normal") && e.contains("no modules"), "{e}");
    // a pitch longer than its section; modules too heavy for any line
    let e = Scene::from_toml(&with(&modules.replace("pitch = 2.0", "pitch = 150.0")), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_pitch") && e.contains("at least one pitch"), "{e}");
    let heavy = modules.replace("module_mass = 300.0", "module_mass = 1e5").replace("pitch = 2.0", "pitch = 1.0");
    let e = Scene::from_toml(&with(&heavy), "t").unwrap_err().to_string();
    assert!(e.contains("section[1].module_mass") && e.contains("kg/m"), "{e}");
    // a `--set length=` that breaks the sum is refused the same way
    let e = two_sections("").with_overrides(&["length=310"]).unwrap_err().to_string();
    assert!(e.contains("section[1].length") && e.contains("add up to 300 m"), "{e}");
}

/// The modes see each element's own mass: a taut vertical string of two
/// sections (60 m of 10 kg/m above 40 m of 40 kg/m, in air, tension 1 MN
/// against 2.2 kN of weight), pinned at both ends. Closed form for two
/// uniform strings joined (y and T y′ continuous): with k_i = ω √(μ_i/T) on
/// stretched lengths ℓ_i, k₁ cot(k₁ℓ₁) + k₂ cot(k₂ℓ₂) = 0. The first three
/// transverse frequencies within 0.1 %, rod and cable (the weight makes
/// the tension vary by 0.2 % along the line, the frequencies by about half
/// that at most; measured: 0.024 %).
#[test]
fn the_modes_of_a_two_section_string_match_the_closed_form() {
    let (ea, strain, l1, l2, m1, m2): (f64, f64, f64, f64, f64, f64) = (2e8, 5e-3, 60.0, 40.0, 10.0, 40.0);
    let t = ea * strain;
    let lam = 1.0 + strain;
    let exact = joined_strings_frequencies([lam * l1, lam * l2], [m1 / lam, m2 / lam], t, 3);
    for model in ["rod", "cable"] {
        let text = format!(
            r#"
name = "two_section_string"
[line]
length = 100.0
mass_per_length = {m1}
outer_diameter = 0.1
axial_stiffness = {ea}
bending_stiffness = 1e-2
torsional_stiffness = 1e6
[anchor]
x = 0.0
z = {}
[environment]
water_density = 0.0
gravity = 1.0
water_surface_z = 10.0
[[section]]
length = {l1}
[[section]]
length = {l2}
mass_per_length = {m2}
[analysis]
model = "{model}"
n_elements = 100
"#,
            -100.0 * lam
        );
        let sc = Scene::from_toml(&text, "string").unwrap();
        common::assert_plane_pairs(model, &common::transverse_frequencies(&sc, 12), &exact, 1e-3);
    }
}

/// The example scene file docs/cases/lazy_wave_modules.toml (README) is
/// the paper's lazy wave with its modules as bodies: its static state is the
/// built-in scene's (the module mass is given to 0.1 g: top force within 1e-6).
#[test]
fn the_example_lazy_wave_with_modules_has_the_papers_static_state() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let file = Scene::load(&format!("{dir}/docs/cases/lazy_wave_modules.toml")).unwrap();
    let (a, b) = (solve_scene(&Scene::builtin("lazy_wave").unwrap()).unwrap(), solve_scene(&file).unwrap());
    let (fa, fb) = (a.solution.reactions[0], b.solution.reactions[0]);
    println!("top force {fa:?} (built-in) vs {fb:?} (modules)");
    assert!((fa - fb).norm() <= 1e-6 * fa.norm(), "{fa:?} vs {fb:?}");
}

/// A joint where EA changes is reported with the rod model (its tension is
/// approximate in the two elements either side, theory §11), not with the
/// cable, nor where only the mass changes (the lazy wave's modules).
#[test]
fn a_jump_of_ea_is_reported_with_the_rod() {
    let rod = two_sections("");
    assert_eq!(rod.axial_stiffness_jumps(), vec![(180.0, 10.0)]);
    let w = rod.axial_stiffness_jump_warning().unwrap();
    assert!(w.contains("S = 180 m") && w.contains("10.000x") && w.contains("cable"), "{w}");
    assert!(two_sections("model = \"cable\"").axial_stiffness_jump_warning().is_none());
    let dir = env!("CARGO_MANIFEST_DIR");
    let modules = Scene::load(&format!("{dir}/docs/cases/lazy_wave_modules.toml")).unwrap();
    assert!(modules.axial_stiffness_jumps().is_empty());
}
