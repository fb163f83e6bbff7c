//! The monolithic reference of two-way coupling (issue 53; docs/theory.md
//! §7.9, `riser::sim::monolithic`): a heave–pitch body integrated inside the
//! line's own step. Checked against (a) the energy balance of line and body
//! together (7.18), and (b) the linear oscillator's frequency response when
//! the line is a light taut spring: the body on its own stiffness plus the
//! line's static stiffness at the hang-off (§8.3) through the lever.

use crate::common;

use riser::math::V3;
use riser::scene::Scene;
use riser::sim::Simulation;
use riser::sim::monolithic::{BodyRun, HeavePitchBody};
use std::f64::consts::PI;

/// A light taut vertical cable of EA 1e6 N, 10 m unstretched, stretched by
/// 0.5 % (5 kN), no drag, no current, hanging below a hang-off at the lever
/// (2, 0, 0) m of the body.
const TAUT: &str = r#"
name = "taut"
[line]
length = 10.0
LINE[anchor]
x = 0.0
y = 0.0
z = -10.05
[hang_off]
offset = [2.0, 0.0, 0.0]
[environment]
water_density = 1025.0
gravity = 9.81
water_surface_z = 10.0
[current]
profile = "uniform"
speed = 0.0
direction = [1.0, 0.0]
[analysis]
model = "cable"
n_elements = 10
time_step = 0.01
newton_tolerance = 1e-10
"#;

/// The amplitude and phase of x at ω over the samples (least squares on cos, sin).
fn harmonic(t: &[f64], x: &[f64], omega: f64) -> (f64, f64) {
    let (mut cc, mut ss, mut cs, mut xc, mut xs) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&ti, &xi) in t.iter().zip(x) {
        let (s, c) = (omega * ti).sin_cos();
        cc += c * c;
        ss += s * s;
        cs += c * s;
        xc += xi * c;
        xs += xi * s;
    }
    let det = cc * ss - cs * cs;
    let (a, b) = ((xc * ss - xs * cs) / det, (xs * cc - xc * cs) / det);
    (a.hypot(b), a.atan2(b))
}

/// Heave and pitch of the body on the light taut line in a regular
/// excitation at 0.7 of its first natural frequency, against the 2×2
/// frequency response (K + Gᵀ S G − ω² M + i ω B)⁻¹ F, S the line's static
/// stiffness at the hang-off (`hang_off_stiffness`, §8.3) and G = [e_z,
/// ∂(R_y(θ)ρ)/∂θ] at rest, window 40–60 s (the start's transient below
/// 1e-5). Measured at h = 0.01 s: heave 2.1e-4, pitch 2.6e-4 above the
/// closed form, phases within 1.4e-4 rad; at 0.005 s 5.0e-5 and 6.3e-5
/// (the midpoint rule's second order: (ωh)² = 6.9e-4 at 0.01 s, amplified
/// near resonance); held to 1e-3. The energy balance within 3e-11 of the
/// energy exchanged.
#[test]
fn a_body_on_a_light_taut_line_answers_as_the_linear_oscillator() {
    let scene = Scene::from_toml(&TAUT.replace("LINE", common::LIGHT_ELASTIC_LINE), "taut").unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let s = sim.hang_off_stiffness().unwrap();
    let rho = sim.vessel.offset;
    let (k_line, t0) = (1.0e6 / 10.0, sim.statics.top_tension);
    eprintln!(
        "line's static stiffness at the hang-off, zz: {:.6e} N/m (EA/L {k_line:.6e}); tension {t0:.1} N",
        s[(2, 2)]
    );
    assert!((s[(2, 2)] / k_line - 1.0).abs() < 1e-2, "{s}");
    let (m, i) = (1.0e4, 1.0e5);
    let (c33, c55) = (1.0e5, 1.0e6);
    // the coupled 2×2 system at rest: G = [e_z, e_y × ρ]
    let g = [V3::z(), V3::y().cross(&rho)];
    let kk = nalgebra::Matrix2::from_fn(|a, b| g[a].dot(&(s * g[b])) + if a == b { [c33, c55][a] } else { 0.0 });
    let mm = nalgebra::Matrix2::new(m, 0.0, 0.0, i);
    let w_n = (kk[(0, 0)] / m).sqrt().min((kk[(1, 1)] / i).sqrt());
    let omega = 0.7 * w_n;
    let body = HeavePitchBody {
        mass: m,
        inertia: i,
        stiffness: [c33, c55],
        damping: [2.0 * 0.1 * (kk[(0, 0)] * m).sqrt(), 2.0 * 0.1 * (kk[(1, 1)] * i).sqrt()],
        excitation: [1.0e3, 1.0e3],
        period: 2.0 * PI / omega,
        ramp: 5.0,
    };
    let bb = nalgebra::Matrix2::new(body.damping[0], 0.0, 0.0, body.damping[1]);
    // X = (K − ω²M + iωB)⁻¹ F as a real 4×4 system in (Re, Im)
    let a = kk - mm * omega * omega;
    let c = bb * omega;
    let mut big = nalgebra::Matrix4::zeros();
    big.fixed_view_mut::<2, 2>(0, 0).copy_from(&a);
    big.fixed_view_mut::<2, 2>(0, 2).copy_from(&(-c));
    big.fixed_view_mut::<2, 2>(2, 0).copy_from(&c);
    big.fixed_view_mut::<2, 2>(2, 2).copy_from(&a);
    // F sin(ωt) = Im(F e^{iωt}) → Im(X e^{iωt}) = |X| sin(ωt + arg X), X = Xr + i Xi
    let x = big.lu().solve(&nalgebra::Vector4::new(1.0e3, 1.0e3, 0.0, 0.0)).unwrap();
    let want = [(x[0].hypot(x[2]), x[2].atan2(x[0])), (x[1].hypot(x[3]), x[3].atan2(x[1]))];
    let mut run = BodyRun::new(sim, body);
    let h = 0.01;
    let (mut t, mut z, mut th) = (Vec::new(), Vec::new(), Vec::new());
    let n = (60.0 / h) as usize;
    for k in 1..=n {
        run.step(h).unwrap();
        if k as f64 * h >= 40.0 {
            t.push(k as f64 * h);
            z.push(run.q[0]);
            th.push(run.q[1]);
        }
    }
    let got = [harmonic(&t, &z, omega), harmonic(&t, &th, omega)];
    for (name, (g, w)) in ["heave", "pitch"].iter().zip(got.iter().zip(want)) {
        eprintln!(
            "{name}: amplitude {:.6e} against {:.6e} ({:.1e}), phase {:.5} against {:.5}",
            g.0,
            w.0,
            g.0 / w.0 - 1.0,
            g.1,
            w.1
        );
        assert!((g.0 / w.0 - 1.0).abs() < 1e-3, "{name}: {g:?} against {w:?}");
        assert!((g.1 - w.1).abs() < 1e-3, "{name}: {g:?} against {w:?}");
    }
    let e = run.energy_balance_residual();
    eprintln!("balance {e:.3e} J of {:.3e} J; {} corrections in {n} steps", run.exchanged(), run.iterations);
    assert!(e.abs() < 1e-6 * run.exchanged(), "{e} of {}", run.exchanged());
}

/// The 2,000 t heave–pitch vessel of issue 53 (M + A 3e6 kg, pitch inertia
/// with added inertia 7e8 kg m², hang-off 30 m forward) on the built-in
/// catenary (the rod, in its 0.8 m/s current) in a 10 s wave: the line's and
/// the body's energies balance the excitation's work, the body's damping and
/// the water's and the integrator's share on the line (7.18).
#[test]
fn the_line_and_the_body_together_balance_their_energy() {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&["hang_off_x=30".to_string()]).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let body = vessel_2000t();
    let mut run = BodyRun::new(sim, body);
    let h = 0.05;
    let mut worst: f64 = 0.0;
    for _ in 0..(30.0 / h) as usize {
        run.step(h).unwrap();
        worst = worst.max(run.energy_balance_residual().abs());
    }
    let exchanged = run.exchanged();
    eprintln!(
        "balance worst {worst:.3e} J of {exchanged:.3e} J exchanged; heave {:.4} m, pitch {:.5} rad; {} corrections",
        run.q[0], run.q[1], run.iterations
    );
    assert!(exchanged > 1e5, "{exchanged}");
    assert!(worst < 1e-6 * exchanged, "{worst} of {exchanged}");
}

/// The 2,000 t vessel of issue 53 as a heave–pitch body.
fn vessel_2000t() -> HeavePitchBody {
    HeavePitchBody {
        mass: 3.0e6,
        inertia: 7.0e8,
        stiffness: [5.0276e6, 1.18e9],
        damping: [3.883e5, 2.0 * 0.05 * (1.18e9f64 * 7.0e8).sqrt()],
        excitation: [1.1e6, 1.4e7],
        period: 10.0,
        ramp: 20.0,
    }
}
