//! A rod's end at a free point (issue 49; docs/theory.md §17.7, (17.19)):
//! the point is a pinned joint (the rod's end position the point's, its
//! rotation free, no moment; a rod's twist held at its anchor end as at a
//! fixed anchor). A mass between two taut vertical rods, one hung from a
//! vessel point held still (its anchor end at the point moves with it) and
//! one hung from the point (its hang-off there): its modes are a mass on
//! springs, the across ones at the strings' stiffness T/l (a clamped end
//! would add the rods' bending); its free vibration in the dynamics keeps
//! the one energy balance and oscillates at the mode's frequency (the
//! midpoint rule's); at rest it stays at the statics.

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::system_dynamics::SystemRun;
use riser::sim::system_modes::joined_modes;
use riser::sim::vessel::VesselMotion;

/// A neutrally buoyant 1 t point (C_a 1 on 0.9756 m³: m + m_a = 2000 kg)
/// between two taut vertical rods (EA 1e6 N, EI 1e3 N m², GJ 1e3 N m²,
/// L 10 m stretched by 0.5 %, 0.01 kg/m, no drag or added mass), the upper
/// from a vessel point, undamped (ρ∞ = 1, no structural damping).
fn rod_spring_mass(extra: &str) -> SystemScene {
    let text = format!(
        r#"
name = "rod_spring_mass"
[[line_type]]
name = "rod"
model = "rod"
mass_per_length = 0.01
outer_diameter = 0.001
axial_stiffness = 1.0e6
bending_stiffness = 1.0e3
torsional_stiffness = 1.0e3
cd_normal = 0.0
cd_tangential = 0.0
ca_normal = 0.0
[[point]]
name = "top"
kind = "vessel"
position = [0.0, 0.0, -40.0]
[[point]]
name = "mass"
kind = "free"
position = [0.0, 0.0, -50.05]
mass = 1000.0
volume = 0.975609756097561
ca = 1.0
[[point]]
name = "bottom"
kind = "fixed"
position = [0.0, 0.0, -60.1]
[[line]]
name = "upper"
type = "rod"
from = "top"
to = "mass"
length = 10.0
n_elements = 8
[[line]]
name = "lower"
type = "rod"
from = "mass"
to = "bottom"
length = 10.0
n_elements = 8
[analysis]
rho_infinity = 1.0
structural_damping = 0.0
{extra}
"#
    );
    SystemScene::from_toml(&text, "rod_spring_mass").expect("a valid system")
}

fn still(_: f64) -> VesselMotion {
    VesselMotion::default()
}

/// The point's modes between the two rods (17.22): along them k = 2 EA/L,
/// across k = Σ T_i/l_i (a taut string's: pinned at the point, a rod turns
/// rigidly without bending), ω = sqrt(k/(m + m_a)). A clamped joint would
/// add at least 3 EI/l³ = 3 N/m a rod across, 0.6 % of T/l = 500 N/m (ω
/// 0.3 % higher). The rods' own mass (0.1 kg each against 2000 kg) lowers
/// ω by about 1.7e-5. Measured: see the message; held to 1e-4.
#[test]
fn a_mass_between_two_taut_rods_has_the_spring_mass_frequencies() {
    let sys = rod_spring_mass("");
    let j = joined_modes(&sys, 4).expect("the joined modes");
    let m = 1000.0 + sys.environment.water_density * sys.points[1].volume();
    let st = &j.statics;
    let z = st.points[0].position.z;
    let (l_up, l_low) = (-40.0 - z, z + 60.1);
    let mean = |i: usize| 0.5 * (st.lines[i].tension_from + st.lines[i].tension_to);
    let across = ((mean(0) / l_up + mean(1) / l_low) / m).sqrt();
    let along = (2.0 * 1.0e6 / 10.0 / m).sqrt();
    let omega = |k: usize| j.modes[k].eigenvalue.sqrt();
    for k in 0..3 {
        let md = &j.modes[k];
        eprintln!(
            "mode {}: ω {:.7} rad/s, the point {:.6} of the energy along {}",
            md.number,
            omega(k),
            md.points[0].share,
            md.points[0].direction
        );
    }
    for k in 0..2 {
        assert_ne!(j.modes[k].points[0].direction, "z");
        let e = omega(k) / across - 1.0;
        eprintln!("across: {:.7} against {across:.7} ({e:.2e})", omega(k));
        assert!(e.abs() < 1e-4, "{e}");
    }
    assert_eq!(j.modes[2].points[0].direction, "z");
    let e = omega(2) / along - 1.0;
    eprintln!("along: {:.7} against {along:.7} ({e:.2e})", omega(2));
    assert!(e.abs() < 1e-4, "{e}");
    assert!(j.modes[..3].iter().all(|md| md.points[0].share > 0.999));
}

/// The free vibration along the rods in the dynamics (the point kicked at
/// 10 cm/s, h = 5 ms, ωh = 0.05, 8 periods): ω from the upward zero crossings against
/// the joined mode's ω_m and the midpoint rule's (2/h) atan(ω_m h/2); and
/// the system's one energy balance (17.17), nothing but the point's added
/// mass exchanging energy (no drag, no damping, the vessel still).
/// Measured: see the message; held to 1e-4 of the mode and 1e-8 of the
/// kick's energy.
#[test]
fn a_mass_between_two_taut_rods_oscillates_at_its_mode_with_one_energy_balance() {
    let sys = rod_spring_mass("time_step = 0.005\nnewton_tolerance = 1e-10");
    let modes = joined_modes(&sys, 3).expect("the joined modes");
    let omega_m = modes.modes[2].eigenvalue.sqrt();
    let h = sys.analysis.time_step;
    let omega_h = 2.0 / h * (omega_m * h / 2.0).atan();
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let z0 = r.free.points[0].static_position.z;
    let v = 0.1;
    r.set_point_velocity(0, V3::new(0.0, 0.0, v));
    let kick = 0.5 * 1000.0 * v * v;
    let (mut crossings, mut last, mut worst) = (Vec::new(), (0.0, 0.0), 0.0f64);
    let n = (8.0 * 2.0 * std::f64::consts::PI / omega_m / h).round() as usize + 20;
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
    let b = r.energy_balance();
    eprintln!(
        "ω measured {measured:.6} rad/s over {periods} periods; the mode's {omega_m:.6} ({:.2e}), the midpoint \
         rule's {omega_h:.6} ({:.2e}); balance at worst {worst:.2e} of the kick's {kick} J (W_water {:.3e} J, \
         W_vessel {:.1e} J, W_anchor {:.1e} J)",
        measured / omega_m - 1.0,
        measured / omega_h - 1.0,
        b.work_water,
        b.work_vessel,
        b.work_anchor
    );
    assert!(periods >= 7, "{periods} periods");
    assert!((measured / omega_h - 1.0).abs() < 1e-6, "{measured} against the midpoint rule's {omega_h}");
    assert!(worst < 1e-8, "{worst}");
}

/// Kicked across and along at once (0.3, −0.2, 0.1 m/s), the rods bend
/// and swing about the joint: the one energy balance (17.17) holds to
/// round-off over 2 s (the rods' ends at the point turn freely, the moment
/// there zero: no work is lost at the joint). Measured: see the message;
/// held to 1e-8 of the kick's energy.
#[test]
fn rods_swinging_about_a_free_point_keep_the_energy_balance() {
    let sys = rod_spring_mass("time_step = 0.005\nnewton_tolerance = 1e-10");
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let v = V3::new(0.3, -0.2, 0.1);
    r.set_point_velocity(0, v);
    let kick = 0.5 * 1000.0 * v.norm_squared();
    let (mut worst, mut far) = (0.0f64, 0.0f64);
    let h = sys.analysis.time_step;
    for k in 1..=(2.0 / h).round() as usize {
        r.advance_to(k as f64 * h, &still, 2).unwrap();
        worst = worst.max(r.energy_balance().residual.abs() / kick);
        let p = &r.free.points[0];
        far = far.max((p.position - p.static_position).norm());
    }
    let b = r.energy_balance();
    eprintln!(
        "swinging: balance at worst {worst:.2e} of the kick's {kick:.1} J; the point {far:.3} m from its statics at \
         most; E − E0 {:.3e} J, W_water {:.3e} J, W_anchor {:.1e} J; {} point iterations",
        b.energy - b.initial_energy,
        b.work_water,
        b.work_anchor,
        r.free.point_iterations
    );
    assert!(far > 0.1, "the point moved: {far} m");
    assert!(worst < 1e-8, "{worst}");
}

fn hybrid_riser_tower() -> SystemScene {
    let path = format!("{}/docs/cases/hybrid_riser_tower.toml", env!("CARGO_MANIFEST_DIR"));
    SystemScene::load(&path).expect("the case is valid")
}

/// The hybrid riser tower (docs/cases/hybrid_riser_tower.toml: a steel
/// riser tower hung from a buoyancy can, a flexible jumper from the vessel
/// to the can, both rods pinned at the can) with the vessel still stays at
/// its statics (§17.4) for 30 s: the can within 1e-6 m of its static
/// position, each line's tension at each end within 1e-6 of its statics'.
/// Measured: see the message.
#[test]
fn a_hybrid_riser_tower_at_rest_stays_at_its_statics() {
    let sys = hybrid_riser_tower();
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let h = sys.analysis.time_step;
    let mut far = 0.0f64;
    let mut tension = 0.0f64;
    for k in 1..=(30.0 / h).round() as usize {
        r.advance_to(k as f64 * h, &still, 2).unwrap();
        let p = &r.free.points[0];
        far = far.max((p.position - p.static_position).norm());
        for (l, o) in r.lines.iter().zip(r.outputs()) {
            let (a, b) = (l.tensions(&o), l.static_tensions());
            tension = tension.max(((a.0 - b.0) / b.0).abs()).max(((a.1 - b.1) / b.1).abs());
        }
    }
    eprintln!("the tower at rest over 30 s: the can within {far:.2e} m of its statics, tensions within {tension:.2e}");
    assert!(far < 1e-6, "{far} m");
    assert!(tension < 1e-6, "{tension}");
}

/// The hybrid riser tower under surge 5 m / 40 s and heave 2 m / 10 s
/// (grown over 10 s) for 40 s: the can moves, and the system's one energy
/// balance (17.17) closes to 1e-6 of the energy exchanged (the vessel's
/// work on the jumper, the water's on the lines and the can). Measured:
/// see the message.
#[test]
fn a_hybrid_riser_tower_keeps_the_energy_balance_under_the_vessel_s_motion() {
    let sys = hybrid_riser_tower();
    let motion = |t: f64| {
        let (r, dr) = if t < 10.0 {
            let a = std::f64::consts::PI / 10.0;
            (0.5 * (1.0 - (a * t).cos()), 0.5 * a * (a * t).sin())
        } else {
            (1.0, 0.0)
        };
        let (ws, wh) = (2.0 * std::f64::consts::PI / 40.0, 2.0 * std::f64::consts::PI / 10.0);
        let (xs, vs) = (5.0 * (ws * t).sin(), 5.0 * ws * (ws * t).cos());
        let (xh, vh) = (2.0 * (wh * t).sin(), 2.0 * wh * (wh * t).cos());
        VesselMotion {
            displacement: V3::new(r * xs, 0.0, r * xh),
            velocity: V3::new(r * vs + dr * xs, 0.0, r * vh + dr * xh),
            ..Default::default()
        }
    };
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&motion(0.0));
    let h = sys.analysis.time_step;
    let (mut worst, mut far) = (0.0f64, 0.0f64);
    for k in 1..=(40.0 / h).round() as usize {
        r.advance_to(k as f64 * h, &motion, 2).unwrap();
        let b = r.energy_balance();
        worst = worst.max(b.residual.abs() / b.exchanged().max(1.0));
        let p = &r.free.points[0];
        far = far.max((p.position - p.static_position).norm());
    }
    let b = r.energy_balance();
    eprintln!(
        "the tower under surge and heave: balance at worst {worst:.2e} of the energy exchanged ({:.3e} J: W_vessel \
         {:.3e} J, W_water {:.3e} J); the can {far:.3} m from its statics at most",
        b.exchanged(),
        b.work_vessel,
        b.work_water
    );
    assert!(far > 0.05, "the can moved: {far} m");
    assert!(worst < 1e-6, "{worst}");
}

/// The step's tangent condensed on a rod's two end positions (17.15), the
/// free points' Jacobian, turned from the rod's corotated basis (its end
/// nodes' director frames, §5.7) to the global one: against central
/// differences of the ends' reactions (the end rows of the step, each step
/// converged to round-off) in the six end coordinates (±1e-4 m), on the
/// hybrid riser tower's jumper stepped 0.05 s from its statics with both
/// ends moved: within 1e-6 of the matrix's largest entry. Measured: see
/// the message.
#[test]
fn a_rod_s_condensed_end_tangent_is_the_derivative_of_its_end_reactions() {
    use riser::model::AnchorMotion;
    use riser::model::HangOff;
    use riser::sim::Simulation;
    let sys = hybrid_riser_tower();
    let statics = riser::sim::system::solve_system(&sys, &[0.0; 6], false).unwrap();
    let ls = &statics.lines[1];
    let mut sim = Simulation::from_statics(&ls.scene, ls.report.clone()).unwrap();
    sim.integrator.options_mut().newton_tolerance = 1e-14;
    let prev = sim.state.clone();
    let n = prev.config.x.len() - 1;
    let h = 0.05;
    let (dh, da) = (V3::new(0.03, 0.01, -0.02), V3::new(0.01, 0.005, 0.02));
    let at = sim.integrator.end_position_unknowns().expect("both ends prescribed");
    let m = sim.integrator.fixed_unknowns();
    assert_eq!(m, 7, "the rod's prescribed unknowns: its ends' positions and its anchor's twist");
    let mut scratch = vec![0.0; m * m];
    let mut step = |u: [V3; 2], tangent: bool| -> ([V3; 2], [f64; 36]) {
        let anchor = AnchorMotion { position: prev.config.x[n] + u[1], velocity: u[1] * (2.0 / h) };
        sim.integrator.set_anchor_motion(Some(anchor));
        let target = HangOff::translation(u[0], u[0] * (2.0 / h));
        let mut s = prev.clone();
        sim.integrator.invalidate_tangent();
        sim.integrator.step(&mut s, h, &|_| target).unwrap();
        let mut k = [0.0; 36];
        if tangent {
            sim.integrator.condensed_end_tangent_into(&prev, &s.config, h, target, &at, &mut scratch, &mut k).unwrap();
        }
        (s.mid_reaction, k)
    };
    let (_, k) = step([dh, da], true);
    let eps = 1e-4;
    let mut worst: f64 = 0.0;
    let largest = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for j in 0..6 {
        let mut e = [V3::zeros(); 2];
        e[j / 3][j % 3] = eps;
        let (p, _) = step([dh + e[0], da + e[1]], false);
        let (q, _) = step([dh - e[0], da - e[1]], false);
        for i in 0..6 {
            let fd = (p[i / 3][i % 3] - q[i / 3][i % 3]) / (2.0 * eps);
            worst = worst.max((fd - k[6 * i + j]).abs() / largest);
        }
    }
    eprintln!(
        "the rod's condensed tangent against central differences: {worst:.3e} of its largest entry {largest:.3e} N/m"
    );
    assert!(worst < 1e-6, "{worst}");
}
