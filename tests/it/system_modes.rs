//! The modes of a system of lines joined at free points (issue 49;
//! docs/theory.md §17.9): a mass between two taut light lines against the
//! closed form of a mass on springs; a very heavy point leaves each line
//! its own modes with both ends held; the joined mode of the clump weight
//! mooring against the frequency of a free vibration of its dynamics.

use crate::common;

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::system_dynamics::SystemRun;
use riser::sim::system_modes::{JoinedModes, joined_modes};
use riser::sim::vessel::VesselMotion;

fn case(name: &str) -> SystemScene {
    let path = format!("{}/docs/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    SystemScene::load(&path).expect("the case is valid")
}

fn omega(modes: &JoinedModes, k: usize) -> f64 {
    modes.modes[k].eigenvalue.sqrt()
}

/// The scene of tests/it/system_free_dynamics.rs: a neutrally buoyant 10 t
/// point (C_a 1 on 9.756 m³: m + m_a = 2e4 kg) between two taut vertical
/// light lines (EA 1e6 N, L 10 m stretched by 0.5 %, 0.01 kg/m).
fn spring_mass() -> SystemScene {
    let text = r#"
name = "spring_mass"
[[line_type]]
name = "spring"
model = "cable"
LINE[[point]]
name = "top"
kind = "fixed"
position = [0.0, 0.0, -40.0]
[[point]]
name = "mass"
kind = "free"
position = [0.0, 0.0, -50.05]
mass = 10000.0
volume = 9.75609756097561
ca = 1.0
[[point]]
name = "bottom"
kind = "fixed"
position = [0.0, 0.0, -60.1]
[[line]]
name = "upper"
type = "spring"
from = "top"
to = "mass"
length = 10.0
n_elements = 10
[[line]]
name = "lower"
type = "spring"
from = "mass"
to = "bottom"
length = 10.0
n_elements = 10
"#;
    SystemScene::from_toml(&text.replace("LINE", common::LIGHT_ELASTIC_LINE), "spring_mass").expect("valid")
}

/// The point's three modes are a mass on springs (17.22): along the lines
/// k = 2 EA/L (each line's axial stiffness, its strain l/L − 1), across
/// them k = Σ T_i/l_i (a taut string's, T_i its mean tension, l_i its
/// stretched length), ω = sqrt(k/(m + m_a)). The lines' own mass (0.1 kg
/// each, as a spring's: a third of it at the point) lowers ω by 1.67e-6;
/// the string's tension varies along it by its weight in water (1e-4 of
/// T), which the mean takes to second order. Measured: 1.67e-6 below both,
/// the lines' mass; held to 1e-5.
#[test]
fn a_mass_between_two_taut_lines_has_the_spring_mass_frequencies() {
    let sys = spring_mass();
    let j = joined_modes(&sys, 4).expect("the joined modes");
    let m = 10000.0 + sys.environment.water_density * sys.points[1].volume();
    let st = &j.statics;
    let z = st.points[0].position.z;
    let (l_up, l_low) = (-40.0 - z, z + 60.1);
    let mean = |i: usize| 0.5 * (st.lines[i].tension_from + st.lines[i].tension_to);
    let across = ((mean(0) / l_up + mean(1) / l_low) / m).sqrt();
    let along = (2.0 * 1.0e6 / 10.0 / m).sqrt();
    for k in 0..3 {
        let md = &j.modes[k];
        eprintln!(
            "mode {}: ω {:.7} rad/s, the point {:.6} of the energy along {}",
            md.number,
            omega(&j, k),
            md.points[0].share,
            md.points[0].direction
        );
    }
    // the two across (x, y: the same ω), then along
    for k in 0..2 {
        assert_ne!(j.modes[k].points[0].direction, "z");
        let e = omega(&j, k) / across - 1.0;
        eprintln!("across: {:.7} against {across:.7} ({e:.2e})", omega(&j, k));
        assert!(e.abs() < 1e-5, "{e}");
    }
    assert_eq!(j.modes[2].points[0].direction, "z");
    let e = omega(&j, 2) / along - 1.0;
    eprintln!("along: {:.7} against {along:.7} ({e:.2e})", omega(&j, 2));
    assert!(e.abs() < 1e-5, "{e}");
    // the point carries the mode: its share of the kinetic energy near 1
    assert!(j.modes[..3].iter().all(|md| md.points[0].share > 0.999));
    // the lines' own modes (strings of 35 Hz) are far above
    assert!(j.modes[3].frequency > 10.0, "{}", j.modes[3].frequency);
}

/// A very heavy point holds the lines' ends still at their frequencies:
/// the clump weight of docs/cases/clump_weight_mooring.toml (its lines at
/// a quarter of their elements) made M = 1e8 and 1e9 kg, its volume grown
/// so that its weight in water is the clump's (the same statics). Above the
/// point's three modes (periods of minutes), the joined modes are each
/// line's own modes with both its ends held (`riser modes` of its
/// single-line scene at the statics' ends) up to the ends' coupling, which
/// falls as 1/M: measured 7.6e-5 at worst at 1e9 kg (the lines' axial
/// modes, which pull the point most), each mode's error at 1e8 kg 9.956 to
/// 10.033 times its error at 1e9 kg. Held: within 1e-4 at 1e9 kg, the ratio within
/// 2 % of 10 for every mode whose error is above 1e-9 (the limit M → ∞ is
/// the lines' own modes).
#[test]
fn a_very_heavy_point_leaves_each_line_its_own_modes() {
    let count = 8;
    let errors = |big: f64| -> Vec<f64> {
        let mut sys = case("clump_weight_mooring");
        for l in &mut sys.lines {
            l.n_elements /= 4;
        }
        let rho = sys.environment.water_density;
        let p = &mut sys.points[1];
        let net = p.mass() - rho * p.volume();
        p.mass = Some(big);
        p.volume = Some((big - net) / rho);
        p.ca = Some(0.0);
        let j = joined_modes(&sys, count + 3).expect("the joined modes");
        for md in &j.modes[..3] {
            assert!(md.points[0].share > 0.99 && md.period > 60.0, "{md:?}");
        }
        let mut own: Vec<f64> = Vec::new();
        for &i in &j.lines {
            let scene = &j.statics.lines[i].scene;
            let rep = riser::sim::modes::scene_modes(scene, count).unwrap();
            own.extend(rep.modes.iter().map(|m| m.eigenvalue));
        }
        own.sort_by(f64::total_cmp);
        own.iter()
            .take(count)
            .enumerate()
            .map(|(k, own)| {
                let joined = j.modes[3 + k].eigenvalue;
                let e = (joined / own).sqrt() - 1.0;
                eprintln!(
                    "M {big:.0e} kg, line mode {}: ω {:.6} joined, {:.6} alone ({e:.2e})",
                    k + 1,
                    joined.sqrt(),
                    own.sqrt()
                );
                e
            })
            .collect()
    };
    let (e8, e9) = (errors(1e8), errors(1e9));
    let worst = e9.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    assert!(worst < 1e-4, "{worst}");
    for (k, (a, b)) in e8.iter().zip(&e9).enumerate() {
        if b.abs() > 1e-9 {
            eprintln!("mode {}: error at 1e8 kg / at 1e9 kg = {:.4}", k + 1, a / b);
            assert!((a / b / 10.0 - 1.0).abs() < 0.02, "mode {}: {a} and {b}", k + 1);
        }
    }
}

fn still(_: f64) -> VesselMotion {
    VesselMotion::default()
}

/// The lowest joined mode of the clump weight mooring (its lines at 20 and
/// 18 elements) released in its own shape (every node and the clump given
/// 1 mm/s times the mass-normalised mode's shape, the vessel held, no
/// algorithmic dissipation: ρ∞ = 1) oscillates at the mode's frequency as
/// the midpoint rule gives it, ω_h = (2/h) atan(ω h/2) (the scheme's
/// period error, (ωh)²/12 = 1e-3 here): from the upward zero crossings of
/// the clump's displacement along its mode, over the run. The chains' drag
/// at these speeds (quadratic) is below 1e-6 of their stiffness. Measured:
/// within 1.8e-6 of ω_h (2.05e-3 below ω); held to 2e-5.
#[test]
fn the_lowest_joined_mode_is_the_free_vibration_of_the_dynamics() {
    let mut sys = case("clump_weight_mooring");
    sys.lines[0].n_elements = 20;
    sys.lines[1].n_elements = 18;
    sys.analysis.rho_infinity = 1.0;
    sys.analysis.newton_tolerance = 1e-10;
    let j = joined_modes(&sys, 3).expect("the joined modes");
    let mode = &j.modes[0];
    let w = omega(&j, 0);
    eprintln!(
        "the lowest joined mode: {:.4} s, the clump {:.3} of its energy along {}",
        mode.period, mode.points[0].share, mode.points[0].direction
    );
    let h = mode.period / 40.0;
    sys.analysis.time_step = h;
    let wh = 2.0 / h * (w * h / 2.0).atan();
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    // the mass-normalised shape, scaled to 1 mm/s at its largest
    let largest = mode.line_vectors.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let scale = 1e-3 / largest;
    for (&i, v) in j.lines.iter().zip(&mode.line_vectors) {
        let s = &mut r.lines[i].sim.state;
        for (a, vel) in s.vel.iter_mut().enumerate() {
            *vel = V3::new(v[3 * a], v[3 * a + 1], v[3 * a + 2]) * scale;
        }
    }
    let d = mode.point_displacements[0];
    let phi_p = d / d.norm();
    let v_p = mode.point_vectors[0] * scale;
    r.set_point_velocity(0, v_p);
    let x0 = r.free.points[0].static_position;
    let (mut crossings, mut last) = (Vec::new(), (0.0, 0.0));
    let n = (8.0 * mode.period / h).round() as usize;
    for k in 1..=n {
        let t = k as f64 * h;
        r.advance_to(t, &still, 1).unwrap();
        let u = (r.free.points[0].position - x0).dot(&phi_p);
        if k > 1 && last.1 < 0.0 && u >= 0.0 {
            crossings.push(last.0 + (t - last.0) * (-last.1) / (u - last.1));
        }
        last = (t, u);
    }
    let periods = crossings.len() - 1;
    let measured = 2.0 * std::f64::consts::PI * periods as f64 / (crossings[periods] - crossings[0]);
    eprintln!(
        "ω measured {measured:.6} rad/s over {periods} periods; the mode's {w:.6} ({:.2e}), the midpoint rule's \
         {wh:.6} ({:.2e})",
        measured / w - 1.0,
        measured / wh - 1.0
    );
    assert!(periods >= 6, "{periods}");
    assert!((measured / wh - 1.0).abs() < 2e-5, "{measured} against {wh}");
}
