//! A free point at the water surface (issue 49; docs/theory.md §17.10): a
//! vertical cylinder of the point's volume and `height` floats at the draft
//! Archimedes gives it, heaves at sqrt(k/(m + m_a)) with k its waterplane's
//! ρ g A and its line's stiffness, keeps the energy balance in still water
//! and in waves, and its tangent is the derivative of its load.

use crate::common;

use riser::math::V3;
use riser::scene::system::{Floater, SystemScene};
use riser::sim::system::{solve_system, solve_system_from};
use riser::sim::system_dynamics::SystemRun;
use riser::sim::system_modes::joined_modes;
use riser::sim::vessel::VesselMotion;

/// The line: light (0.01 kg/m), neutrally buoyant (its diameter displaces
/// 0.01 kg/m of water at 1025 kg/m³), soft (EA 1e4 N), without drag or added mass.
fn neutral_line() -> String {
    let d = (4.0 * 0.01 / (std::f64::consts::PI * 1025.0)).sqrt();
    format!(
        "mass_per_length = 0.01\nouter_diameter = {d:.17}\naxial_stiffness = 1.0e4\nbending_stiffness = \
         0.0\ntorsional_stiffness = 0.0\ncd_normal = 0.0\ncd_tangential = 0.0\nca_normal = 0.0\n"
    )
}

/// A 2.5 t buoy (4 m³ in a cylinder 4 m tall: A = 1 m²) held down by a
/// 50 m line from an anchor 52 m below the surface, straight under it.
fn buoy_text(extra: &str) -> String {
    format!(
        r#"
name = "surface_buoy"
[[line_type]]
name = "tether"
model = "cable"
{line}
[[point]]
name = "anchor"
kind = "fixed"
position = [0.0, 0.0, -52.0]
[[point]]
name = "buoy"
kind = "free"
position = [0.0, 0.0, -1.0]
mass = 2500.0
volume = 4.0
height = 4.0
ca = 1.0
{extra}
[[line]]
name = "tether"
type = "tether"
from = "buoy"
to = "anchor"
length = 50.0
n_elements = 10
[analysis]
newton_tolerance = 1e-10
"#,
        line = neutral_line()
    )
}

fn still(_: f64) -> VesselMotion {
    VesselMotion::default()
}

/// The cylinder's displaced volume, its potential and the discrete mean
/// against their definitions: d V_s/dζ and dQ/dζ = V_s by central
/// differences, the mean over a step the quotient ΔQ/Δζ, on and across
/// the draft's kinks (to round-off).
#[test]
fn a_cylinders_buoyancy_is_the_gradient_of_its_potential() {
    let f = Floater { volume: 6.0, height: Some(3.0) };
    for z in [-2.7, -1.2, -0.3, 0.4, 1.1, 2.0] {
        let e = 1e-6;
        let (v, dv) = f.displaced(z);
        let fd_q = (f.potential(z + e) - f.potential(z - e)) / (2.0 * e);
        let fd_v = (f.displaced(z + e).0 - f.displaced(z - e).0) / (2.0 * e);
        assert!((fd_q - v).abs() < 1e-8, "{z}: {fd_q} against {v}");
        assert!((fd_v - dv).abs() < 1e-8, "{z}: {fd_v} against {dv}");
        for z1 in [z + 0.05, z + 1.7, z - 2.2] {
            let (m, dm) = f.mean_displaced(z, z1);
            let q = (f.potential(z1) - f.potential(z)) / (z1 - z);
            assert!((m - q).abs() < 1e-12 * 6.0, "{z}..{z1}: {m} against {q}");
            let fd_m = (f.mean_displaced(z, z1 + e).0 - f.mean_displaced(z, z1 - e).0) / (2.0 * e);
            assert!((fd_m - dm).abs() < 1e-7, "{z}..{z1}: {fd_m} against {dm}");
        }
    }
    // fully under: the point's; clear: nothing
    assert_eq!(f.displaced(-1.6), (6.0, 0.0));
    assert_eq!(f.displaced(1.6), (0.0, 0.0));
}

/// The buoy floats where its buoyancy carries its weight and its line's
/// pull (Archimedes): ρ g A d = m g + EA (l/L − 1), d = z_s + H/2 − z, l =
/// z − z_a, solved for z (linear); its line neutrally buoyant. Measured:
/// within 1e-12 m (draft 2.4695 m of 4); held to 1e-9 m.
#[test]
fn a_surface_buoy_floats_at_archimedes_draft() {
    let sys = SystemScene::from_toml(&buoy_text(""), "surface_buoy").expect("valid");
    let st = solve_system(&sys, &[0.0; 6], true).expect("the statics");
    let (rho, g) = (sys.environment.water_density, sys.environment.gravity);
    let (a, h, m, ea, l, za) = (1.0, 4.0, 2500.0, 1.0e4, 50.0, -52.0);
    let z = (rho * g * a * (0.5 * h) - m * g + ea * za / l + ea) / (rho * g * a + ea / l);
    let got = st.points[0].position;
    eprintln!("the buoy at z = {:.12} m, Archimedes' {z:.12} m (draft {:.4} m of {h})", got.z, 0.5 * h - got.z);
    assert!((got.z - z).abs() < 1e-9, "{} against {z}", got.z);
    assert!(got.x.abs() < 1e-9 && got.y.abs() < 1e-9, "{got}");
}

/// Its heave: a mass on the waterplane's spring and its line's, ω =
/// sqrt((ρ g A + EA/L)/(m + C_a ρ A d)) (the added mass of the submerged
/// part), the joined mode (§17.9) and a free vibration of the dynamics
/// (kicked at 1 cm/s, the midpoint rule's ω_h = (2/h) atan(ωh/2), ρ∞ = 1);
/// the energy balance (17.17) closed. The line's mass (0.5 kg, a third at
/// the buoy) lowers ω by 1.7e-5. Measured: the mode 1.66e-5 below the
/// closed form and the dynamics within 9.2e-8 of the mode's ω_h, the
/// balance within 1.5e-10 of the kick's energy; held to 1e-4, 2e-6 and 1e-8.
#[test]
fn a_surface_buoy_heaves_at_its_waterplanes_frequency() {
    let mut sys = SystemScene::from_toml(&buoy_text(""), "surface_buoy").expect("valid");
    sys.analysis.rho_infinity = 1.0;
    let (rho, g) = (sys.environment.water_density, sys.environment.gravity);
    let j = joined_modes(&sys, 6).expect("the modes");
    let z = j.statics.points[0].position.z;
    let d = 2.0 - z;
    let omega = ((rho * g * 1.0 + 1.0e4 / 50.0) / (2500.0 + rho * 1.0 * d)).sqrt();
    let heave = j.modes.iter().find(|m| m.points[0].direction == "z" && m.points[0].share > 0.99).expect("heave");
    let w = heave.eigenvalue.sqrt();
    eprintln!("heave: the mode {w:.7} rad/s ({:.4} s), closed form {omega:.7} ({:.2e})", heave.period, w / omega - 1.0);
    assert!((w / omega - 1.0).abs() < 1e-4, "{w} against {omega}");
    let h = 0.02;
    sys.analysis.time_step = h;
    let wh = 2.0 / h * (w * h / 2.0).atan();
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let z0 = r.free.points[0].static_position.z;
    r.set_point_velocity(0, V3::new(0.0, 0.0, 0.01));
    let kick = 0.5 * 2500.0 * 1e-4;
    let (mut crossings, mut last, mut worst) = (Vec::new(), (0.0, 0.0), 0.0f64);
    let n = (10.0 * heave.period / h).round() as usize;
    for k in 1..=n {
        let t = k as f64 * h;
        r.advance_to(t, &still, 1).unwrap();
        let dz = r.free.points[0].position.z - z0;
        if k > 1 && last.1 < 0.0 && dz >= 0.0 {
            crossings.push(last.0 + (t - last.0) * (-last.1) / (dz - last.1));
        }
        last = (t, dz);
        worst = worst.max(r.energy_balance().residual.abs() / kick);
    }
    let periods = crossings.len() - 1;
    let measured = 2.0 * std::f64::consts::PI * periods as f64 / (crossings[periods] - crossings[0]);
    eprintln!(
        "ω measured {measured:.7} over {periods} periods; the mode's ω_h {wh:.7} ({:.2e}); the balance {worst:.2e} \
         of the kick's {kick} J",
        measured / wh - 1.0
    );
    assert!(periods >= 8);
    assert!((measured / wh - 1.0).abs() < 2e-6, "{measured} against {wh}");
    assert!(worst < 1e-8, "{worst}");
}

/// In a 2 m, 6 s Airy wave the buoy rides the waves (its draft under the
/// local elevation, its drag and added mass by its submerged fraction) and
/// the system's energy balance (17.17) closes: the waves' buoyancy beyond
/// the still water's is the water's work (17.25). Measured: within 2e-11 of
/// the energy exchanged over 24 s, the buoy heaving 2.8 m; held to 1e-8.
#[test]
fn a_surface_buoy_in_waves_keeps_the_energy_balance() {
    let text = buoy_text("cd_area = 2.0") + "[waves]\nkind = \"airy\"\nheight = 2.0\nperiod = 6.0\n";
    let mut sys = SystemScene::from_toml(&text, "surface_buoy_waves").expect("valid");
    sys.analysis.time_step = 0.05;
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let (mut lo, mut hi, mut worst) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
    for k in 1..=480 {
        r.advance_to(k as f64 * 0.05, &still, 1).unwrap();
        let b = r.energy_balance();
        worst = worst.max(b.residual.abs() / b.exchanged().max(1.0));
        let z = r.free.points[0].position.z;
        (lo, hi) = (lo.min(z), hi.max(z));
    }
    let b = r.energy_balance();
    eprintln!(
        "the buoy in a 2 m, 6 s wave: heave range {:.3} m; balance {:.3e} J of {:.3e} J exchanged (worst {worst:.2e})",
        hi - lo,
        b.residual,
        b.exchanged()
    );
    assert!(hi - lo > 1.0, "the buoy rides the waves: {lo} to {hi}");
    assert!(worst < 1e-8, "{worst}");
}

/// The statics' stiffness with a surface buoy between the vessel and an
/// anchor (docs/cases/surface_buoy_hawser.toml: a hawser from a fairlead
/// 3 m down, the tether below): the
/// condensed 6×6 (17.9), its K_pp with the buoy's waterplane (17.23),
/// against central differences of the re-solved statics (±1e-2 m, ±1e-4
/// rad). (The hawser is kept under the water: a line through the surface
/// band, ±5 cm (§10), is not linear over the differences' 1 cm.) Measured:
/// within 2.2e-7 of each block's largest entry; held to 1e-5.
#[test]
fn the_stiffness_with_a_surface_buoy_is_the_derivative_of_the_statics() {
    let path = format!("{}/docs/cases/surface_buoy_hawser.toml", env!("CARGO_MANIFEST_DIR"));
    let sys = SystemScene::load(&path).expect("valid");
    let pose = [0.0; 6];
    let st = solve_system(&sys, &pose, true).expect("statics");
    let fd = common::system::finite_difference_stiffness(&pose, 1e-2, 1e-4, |p| {
        solve_system_from(&sys, p, false, Some(&st)).unwrap()
    });
    let e = common::system::block_errors(&st.stiffness, &fd);
    let p = st.points[0].position;
    eprintln!("the buoy at ({:.3}, {:.3}, {:.3}) m; K {:.4e}, errors {e:?}", p.x, p.y, p.z, st.stiffness);
    // partly submerged: its waterplane in the stiffness
    assert!(p.z > -2.0 && p.z < 2.0, "{p}");
    assert!(e.iter().all(|v| *v < 1e-5), "{e:?}");
}
