//! Free points in the dynamics of a system (issue 49, point 2; docs/theory.md
//! §17.7): a clump weight at rest stays at its statics; the system's energy
//! balance closes under the vessel's motion with a clump weight and with a
//! buoy; one and two threads give the same bits; a mass between two taut
//! elastic lines oscillates at sqrt(2k/(m + m_a)).

use crate::common;

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::system_dynamics::SystemRun;
use riser::sim::vessel::VesselMotion;

fn case(name: &str) -> SystemScene {
    let path = format!("{}/docs/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    SystemScene::load(&path).expect("the case is valid")
}

/// Surge 10 m / 100 s and heave 2 m / 12 s, each grown over 20 s as
/// ½(1 − cos(π t/20)) (the CLI's harmonics with a shorter ramp).
fn surge_heave(t: f64) -> VesselMotion {
    let (r, dr) = if t < 20.0 {
        let a = std::f64::consts::PI / 20.0;
        (0.5 * (1.0 - (a * t).cos()), 0.5 * a * (a * t).sin())
    } else {
        (1.0, 0.0)
    };
    let (ws, wh) = (2.0 * std::f64::consts::PI / 100.0, 2.0 * std::f64::consts::PI / 12.0);
    let (xs, vs) = (10.0 * (ws * t).sin(), 10.0 * ws * (ws * t).cos());
    let (xh, vh) = (2.0 * (wh * t).sin(), 2.0 * wh * (wh * t).cos());
    VesselMotion {
        displacement: V3::new(r * xs, 0.0, r * xh),
        velocity: V3::new(r * vs + dr * xs, 0.0, r * vh + dr * xh),
        ..Default::default()
    }
}

fn still(_: f64) -> VesselMotion {
    VesselMotion::default()
}

/// Runs `sys` for `duration` s at its time step on `threads`, calling
/// `watch` after every step.
fn run(
    sys: &SystemScene,
    motion: &(dyn Fn(f64) -> VesselMotion + Sync),
    duration: f64,
    threads: usize,
    watch: &mut dyn FnMut(&SystemRun),
) -> SystemRun {
    let mut run = SystemRun::new(sys).unwrap();
    run.start(&motion(0.0));
    let dt = sys.analysis.time_step;
    let n = (duration / dt).round() as usize;
    for k in 1..=n {
        run.advance_to(k as f64 * dt, motion, threads).unwrap();
        watch(&run);
    }
    run
}

/// With the vessel still, the clump weight at its static equilibrium stays
/// there: over a minute it moves less than 1e-6 m, and the lines' tensions
/// stay within 1e-6 of their statics. (Measured: it does not move at all;
/// its statics leave it out of balance by less than the Newton tolerance,
/// 1e-8 of its force scale, so every step accepts x⁺ = x⁻.)
#[test]
fn a_clump_weight_at_rest_stays_at_its_statics() {
    let sys = case("clump_weight_mooring");
    let mut largest: f64 = 0.0;
    let r = run(&sys, &still, 60.0, 1, &mut |r| {
        let p = &r.free.points[0];
        largest = largest.max((p.position - p.static_position).norm());
    });
    eprintln!("the clump's largest distance from its statics over 60 s: {largest:.3e} m");
    assert!(largest < 1e-6, "{largest} m");
    let o = r.outputs();
    for (l, o) in r.lines.iter().zip(&o) {
        let s = l.sim.statics.top_tension;
        assert!((o.top_tension - s).abs() < 1e-6 * s, "line {}: {} against {s} N", l.name, o.top_tension);
    }
    assert_eq!(r.free.points.len(), 1);
}

/// One energy balance for the system (17.17): E − E0 = W_vessel + W_water +
/// W_seabed − D, the free points' work on their lines and the lines' on
/// them cancelling, over a minute of surge and heave, for the clump weight
/// and for the buoy (given a drag area and an added mass here, so that the
/// water works on it), each to 1e-6 of the energy exchanged with the
/// Newton tolerance 1e-8 (measured: at worst 2.8e-7 over the clump's run,
/// 1.8e-7 over the buoy's; 1.9e-8 and 1.1e-7 at its end: the points'
/// residual, 1e-8 of their force scale, works over each step's move).
#[test]
fn the_systems_energy_balance_closes_with_free_points() {
    for (name, cd_area, ca) in [("clump_weight_mooring", 1.4, 1.0), ("subsea_buoy_mooring", 7.4, 0.5)] {
        let mut sys = case(name);
        for p in sys.points.iter_mut().filter(|p| p.kind == riser::scene::system::PointKind::Free) {
            p.cd_area = Some(cd_area);
            p.ca = Some(ca);
        }
        let mut worst: f64 = 0.0;
        let r = run(&sys, &surge_heave, 60.0, 2, &mut |r| {
            let b = r.energy_balance();
            worst = worst.max(b.residual.abs() / b.exchanged().max(1.0));
        });
        let b = r.energy_balance();
        let p = &r.free.points[0];
        eprintln!(
            "{name}: residual {:.3e} J of {:.3e} J exchanged (worst over the run {worst:.3e} relative); W_vessel \
             {:.3e} J, W_water {:.3e} J (the point's {:.3e} J), W_seabed {:.3e} J; the point moved {:.3} m; {} point \
             iterations, {} line iterations in trials over {} steps",
            b.residual,
            b.exchanged(),
            b.work_vessel,
            b.work_water,
            p.work_hydro,
            b.work_seabed,
            (p.position - p.static_position).norm(),
            r.free.point_iterations,
            r.free.trial_iterations,
            r.lines[0].sim.state.steps
        );
        assert!(b.exchanged() > 1e4, "{name}: the vessel worked on the system: {b:?}");
        assert!(p.work_hydro.abs() > 1.0, "{name}: the water worked on the point: {} J", p.work_hydro);
        assert!(worst < 1e-6, "{name}: {worst}");
        // the sum of the lines' and the points' own balances is the system's
        let parts: f64 =
            r.outputs().iter().zip(&r.lines).map(|(o, l)| o.energy_balance_residual(l.sim.initial_energy)).sum::<f64>()
                + r.free.points.iter().map(|p| p.energy_balance_residual()).sum::<f64>();
        assert!((parts - b.residual).abs() < 1e-6 * b.exchanged(), "{parts} against {}", b.residual);
    }
}

/// A free point in waves (17.18): the subsea buoy (C_dA 7.4 m², C_a 0.5)
/// in a regular wave of 8 m and 15 s grown over a period, the vessel held:
/// the waves move the buoy and its lines, and the system's energy balance
/// (17.17) still closes, the waves' work on the point (drag on the relative
/// velocity, Froude–Krylov and added-mass inertia) in its W_water, to 1e-6
/// of the energy exchanged (measured: 2.4e-7 at worst over 45 s; the
/// buoy's range 1.24, 0.71 and 1.69 m in x, y, z).
#[test]
fn the_energy_balance_closes_with_a_buoy_in_waves() {
    let path = format!("{}/docs/cases/subsea_buoy_mooring.toml", env!("CARGO_MANIFEST_DIR"));
    let text =
        std::fs::read_to_string(path).unwrap().replace("volume = 15.0", "cd_area = 7.4\nca = 0.5\nvolume = 15.0")
            + "\n[waves]\nkind = \"airy\"\nheight = 8.0\nperiod = 15.0\ndirection = 30.0\n";
    let sys = SystemScene::from_toml(&text, "buoy_in_waves").unwrap();
    let mut worst: f64 = 0.0;
    let (mut lo, mut hi) = (V3::repeat(f64::INFINITY), V3::repeat(f64::NEG_INFINITY));
    let r = run(&sys, &still, 45.0, 2, &mut |r| {
        let b = r.energy_balance();
        worst = worst.max(b.residual.abs() / b.exchanged().max(1.0));
        let x = r.free.points[0].position;
        (lo, hi) = (lo.inf(&x), hi.sup(&x));
    });
    let b = r.energy_balance();
    let p = &r.free.points[0];
    eprintln!(
        "the buoy in an 8 m, 15 s wave: residual {:.3e} J of {:.3e} J exchanged (worst over the run {worst:.3e} \
         relative); W_water {:.3e} J (the buoy's {:.3e} J); the buoy's range {:.3} m, {:.3} m, {:.3} m",
        b.residual,
        b.exchanged(),
        b.work_water,
        p.work_hydro,
        hi.x - lo.x,
        hi.y - lo.y,
        hi.z - lo.z
    );
    assert!(hi.x - lo.x > 0.05 && hi.y - lo.y > 0.02, "the waves moved the buoy: {lo} to {hi}");
    assert!(p.work_hydro.abs() > 1.0, "the waves worked on the buoy: {} J", p.work_hydro);
    assert!(worst < 1e-6, "{worst}");
}

/// The lines at a free point are stepped on threads within each of the
/// points' Newton iterations: one and two threads give the same bits.
#[test]
fn one_and_two_threads_give_the_same_bits_with_free_points() {
    let sys = case("bridle_mooring");
    let a = run(&sys, &surge_heave, 10.0, 1, &mut |_| {});
    let b = run(&sys, &surge_heave, 10.0, 2, &mut |_| {});
    for (la, lb) in a.lines.iter().zip(&b.lines) {
        assert_eq!(la.sim.state, lb.sim.state, "line {}", la.name);
    }
    for (pa, pb) in a.free.points.iter().zip(&b.free.points) {
        assert_eq!((pa.position, pa.velocity), (pb.position, pb.velocity), "point {}", pa.name);
    }
    assert!((a.free.points[0].position - a.free.points[0].static_position).norm() > 1e-2, "the joint moved");
}

/// A neutrally buoyant mass m (with added mass m_a = C_a ρ V) between two
/// taut vertical elastic lines of EA and unstretched length L (light,
/// without drag, stretched by 0.5 %):
/// along them it is a mass on two springs k = EA/L, ω = sqrt(2k/(m + m_a)).
/// The midpoint rule's period is longer by (ωh)²/12 (tan(ω_h h/2) = ωh/2);
/// the lines' own mass (0.1 kg each against 2e4 kg) lowers ω by 2e-6.
/// Measured over 11 periods: 2.3e-5 below the closed form, 2.6e-6 below
/// the midpoint rule's ω_h; held to 5e-5 and 1e-5.
#[test]
fn a_mass_between_two_taut_lines_oscillates_at_the_closed_form() {
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
[analysis]
time_step = 0.005
newton_tolerance = 1e-10
"#;
    let text = text.replace("LINE", common::LIGHT_ELASTIC_LINE);
    let sys = SystemScene::from_toml(&text, "spring_mass").expect("a valid system");
    let (ea, l, m) = (1.0e6, 10.0, 10000.0);
    // neutrally buoyant: V = m/ρ (the lines hold it at their pretension alone)
    let m_a = 1.0 * sys.environment.water_density * sys.points[1].volume();
    let omega = (2.0 * ea / l / (m + m_a)).sqrt();
    let h = sys.analysis.time_step;
    let omega_h = 2.0 / h * (omega * h / 2.0).atan();
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    let z0 = r.free.points[0].static_position.z;
    r.set_point_velocity(0, V3::new(0.0, 0.0, 0.01));
    // upward zero crossings of z − z0, interpolated linearly
    let (mut crossings, mut last) = (Vec::new(), (0.0, 0.0));
    let n = (25.0 / h).round() as usize;
    for k in 1..=n {
        let t = k as f64 * h;
        r.advance_to(t, &still, 1).unwrap();
        let dz = r.free.points[0].position.z - z0;
        if k > 1 && last.1 < 0.0 && dz >= 0.0 {
            crossings.push(last.0 + (t - last.0) * (-last.1) / (dz - last.1));
        }
        last = (t, dz);
    }
    let periods = crossings.len() - 1;
    let period = (crossings[periods] - crossings[0]) / periods as f64;
    let measured = 2.0 * std::f64::consts::PI / period;
    eprintln!(
        "ω measured {measured:.6} rad/s over {periods} periods; closed form {omega:.6} ({:.2e}), the midpoint \
         rule's {omega_h:.6} ({:.2e})",
        measured / omega - 1.0,
        measured / omega_h - 1.0
    );
    assert!(periods >= 10, "{periods} periods");
    assert!((measured / omega - 1.0).abs() < 5e-5, "{measured} against {omega}");
    assert!((measured / omega_h - 1.0).abs() < 1e-5, "{measured} against the midpoint rule's {omega_h}");
    let b = r.energy_balance();
    assert!(b.residual.abs() < 1e-6 * b.energy.abs().max(1.0), "{b:?}");
}

/// A 10 t point hanging from a taut elastic line (EA 1e7 N, L 10 m),
/// kicked down at 1 m/s onto the seabed 5 cm under its equilibrium: its
/// contact (the seabed's stiffness over 1 m², 3e6 N/m, by the discrete
/// gradient of its energy, 17.14) throws it back, and the energy balance
/// (17.17) still closes: within 1e-9 of the kick's energy over 5 s
/// (measured: 2.7e-10, the point 3.2 cm into the seabed at its deepest).
#[test]
fn a_point_bouncing_on_the_seabed_keeps_the_energy_balance() {
    let text = r#"
name = "bounce"
[[line_type]]
name = "spring"
model = "cable"
mass_per_length = 0.01
outer_diameter = 0.001
axial_stiffness = 1.0e7
bending_stiffness = 0.0
torsional_stiffness = 0.0
[[point]]
name = "top"
kind = "fixed"
position = [0.0, 0.0, -40.0]
[[point]]
name = "mass"
kind = "free"
position = [0.0, 0.0, -50.1]
mass = 10000.0
[[line]]
name = "hanger"
type = "spring"
from = "top"
to = "mass"
length = 10.0
n_elements = 10
[seabed]
z = -50.15
[analysis]
time_step = 0.002
"#;
    let sys = SystemScene::from_toml(text, "bounce").expect("a valid system");
    let mut r = SystemRun::new(&sys).unwrap();
    r.start(&still(0.0));
    r.set_point_velocity(0, V3::new(0.0, 0.0, -1.0));
    let (mut deepest, mut worst) = (f64::INFINITY, 0.0f64);
    let h = sys.analysis.time_step;
    for k in 1..=(5.0 / h).round() as usize {
        r.advance_to(k as f64 * h, &still, 1).unwrap();
        deepest = deepest.min(r.free.points[0].position.z);
        let b = r.energy_balance();
        worst = worst.max(b.residual.abs() / (0.5 * 1e4 * 1.0));
    }
    eprintln!("deepest z {deepest:.4} m (the seabed at -50.15 m); worst balance {worst:.3e} of the kick's 5 kJ");
    assert!(deepest < -50.15 - 1e-3, "it reached the seabed: {deepest}");
    assert!(worst < 1e-9, "{worst}");
}

/// The step's tangent condensed on a cable's two ends (17.15), the free
/// points' Jacobian, against central differences of the ends' reactions
/// (the end rows of the step, each step converged to round-off) in the
/// six end coordinates (±1e-4 m), on the clump weight's upper chain
/// stepped 0.05 s from rest with both ends moved: within 1e-6 of the
/// matrix's largest entry (measured: 2.6e-7 of 2.4e6 N/m).
#[test]
fn the_condensed_end_tangent_is_the_derivative_of_the_end_reactions() {
    use riser::model::HangOff;
    use riser::model::cable::AnchorMotion;
    use riser::sim::Simulation;
    let sys = case("clump_weight_mooring");
    let statics = riser::sim::system::solve_system(&sys, &[0.0; 6], false).unwrap();
    let ls = &statics.lines[1];
    let mut sim = Simulation::from_statics(&ls.scene, ls.report.clone()).unwrap();
    sim.integrator.options_mut().newton_tolerance = 1e-14;
    let prev = sim.state.clone();
    let n = prev.config.x.len() - 1;
    let h = 0.05;
    let (dh, da) = (V3::new(0.3, 0.0, -0.2), V3::new(0.1, 0.05, 0.2));
    // both ends moved by `u` (hang-off, anchor) over the step from rest: the
    // step's end reactions, and the condensed tangent there
    let mut step = |u: [V3; 2], tangent: bool| -> ([V3; 2], Vec<f64>) {
        let anchor = AnchorMotion { position: prev.config.x[n] + u[1], velocity: u[1] * (2.0 / h) };
        sim.integrator.set_anchor_motion(Some(anchor));
        let target = HangOff::translation(u[0], u[0] * (2.0 / h));
        let mut s = prev.clone();
        sim.integrator.invalidate_tangent();
        sim.integrator.step(&mut s, h, &|_| target).unwrap();
        let k =
            if tangent { sim.integrator.condensed_fixed_tangent(&prev, &s.config, h, target).unwrap() } else { vec![] };
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
        let (m, _) = step([dh - e[0], da - e[1]], false);
        for i in 0..6 {
            let fd = (p[i / 3][i % 3] - m[i / 3][i % 3]) / (2.0 * eps);
            worst = worst.max((fd - k[6 * i + j]).abs() / largest);
        }
    }
    eprintln!("condensed tangent against central differences: {worst:.3e} of its largest entry {largest:.3e} N/m");
    assert!(worst < 1e-6, "{worst}");
}
