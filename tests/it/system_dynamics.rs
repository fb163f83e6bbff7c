//! The dynamics of a system of lines on one vessel (issue 49; docs/theory.md
//! §17.5): a one-line system is the single-line scene bit for bit; the same
//! bits on one and on two threads; the resultant moment about the
//! reference point is the lines' forces at their moving fairleads'
//! arms; the system's energy balance closes.

use riser::math::V3;
use riser::math::rigid::RotationOrder;
use riser::model::HangOff;
use riser::scene::Scene;
use riser::scene::system::SystemScene;
use riser::sim::Simulation;
use riser::sim::system_dynamics::{SystemRun, energy_balance_residual};
use riser::sim::vessel::VesselMotion;

const OC3: &str = include_str!("../../docs/cases/oc3_hywind_mooring.toml");

/// The OC3 mooring with coarser chains (`n` elements each) and step `dt`.
fn oc3(n: usize, dt: f64) -> SystemScene {
    let mut sys = SystemScene::from_toml(OC3, "oc3").expect("the OC3 scene is valid");
    for l in &mut sys.lines {
        l.n_elements = n;
    }
    sys.analysis.time_step = dt;
    sys
}

/// Surge, heave and the three rotations, each a sine (rates in the vessel
/// frame of z-y-x angles): a motion that turns the fairleads about the
/// reference point.
fn turning_motion(t: f64) -> VesselMotion {
    let w = [0.0628, 0.52, 0.3, 0.25, 0.2];
    let a = [6.0, 1.5, 0.03, 0.04, 0.05];
    let d = V3::new(a[0] * (w[0] * t).sin(), 0.0, a[1] * (w[1] * t).sin());
    let v = V3::new(a[0] * w[0] * (w[0] * t).cos(), 0.0, a[1] * w[1] * (w[1] * t).cos());
    let angles = [a[2] * (w[2] * t).sin(), a[3] * (w[3] * t).sin(), a[4] * (w[4] * t).sin()];
    let rates = [a[2] * w[2] * (w[2] * t).cos(), a[3] * w[3] * (w[3] * t).cos(), a[4] * w[4] * (w[4] * t).cos()];
    VesselMotion { displacement: d, velocity: v, angles, body_rates: RotationOrder::Zyx.body_rates(angles, rates) }
}

fn run_system(sys: &SystemScene, threads: usize, duration: f64) -> SystemRun {
    let mut run = SystemRun::new(sys).unwrap();
    run.start(&turning_motion(0.0));
    let dt = sys.analysis.time_step;
    let n = (duration / dt).round() as usize;
    for k in 1..=n {
        run.advance_to(k as f64 * dt, &turning_motion, threads).unwrap();
    }
    run
}

/// A line's arithmetic does not depend on the thread it runs on, nor on the
/// others': one and two threads give the same bits in every line's state.
#[test]
fn one_and_two_threads_give_the_same_bits() {
    let sys = oc3(20, 0.1);
    let (a, b) = (run_system(&sys, 1, 20.0), run_system(&sys, 2, 20.0));
    for (la, lb) in a.lines.iter().zip(&b.lines) {
        assert_eq!(la.sim.state, lb.sim.state, "line {}", la.name);
    }
    let (oa, ob) = (a.outputs(), b.outputs());
    let (ra, rb) = (SystemRun::resultant(&oa), SystemRun::resultant(&ob));
    assert_eq!(ra.force, rb.force);
    assert_eq!(ra.moment, rb.moment);
}

/// The resultant moment about the reference point against its definition
/// (17.11), read off the state: each line's force on the vessel at its
/// fairlead's position (the hang-off node, in the global frame) less the
/// reference point's, with the vessel turned by about 3 degrees on every
/// axis; and the vessel-frame loads are the global ones turned by Rᵀ.
#[test]
fn the_resultant_moment_is_the_forces_at_the_turning_fairleads() {
    let sys = oc3(20, 0.1);
    let run = run_system(&sys, 1, 12.0);
    let outputs = run.outputs();
    let r = SystemRun::resultant(&outputs);
    let m = turning_motion(run.lines[0].sim.state.time);
    let reference = m.displacement;
    let mut moment = V3::zeros();
    for (l, o) in run.lines.iter().zip(&outputs) {
        let (_, vp, _) = sys.ends(sys.lines.iter().position(|x| x.name == l.name).unwrap());
        // the line's frame has its origin at the fairlead at rest, ρ
        let fairlead = V3::from(vp.position) + l.sim.state.config.x[0];
        moment += (fairlead - reference).cross(&o.top_force);
    }
    let scale = r.force.norm() * 5.2 + moment.norm();
    assert!((r.moment - moment).norm() < 1e-9 * scale, "{:?} vs {:?}", r.moment, moment);
    assert!(r.moment.norm() > 1e5, "the vessel turned: a moment to compare, {:?}", r.moment);
    let rot = RotationOrder::Zyx.rotation(m.angles);
    assert!((r.force_vessel - rot.transpose() * r.force).norm() < 1e-9 * r.force.norm());
    assert!((r.moment_vessel - rot.transpose() * r.moment).norm() < 1e-9 * scale);
}

/// One energy balance for the system (17.12): the sum of its lines'
/// residuals is a small part of the energy they exchanged with the vessel,
/// the water and the seabed over a minute of turning motion (the scheme
/// conserves energy to its Newton tolerance, §5.5).
#[test]
fn the_systems_energy_balance_closes() {
    let sys = oc3(20, 0.1);
    let run = run_system(&sys, 2, 60.0);
    let outputs = run.outputs();
    let e0: Vec<f64> = run.lines.iter().map(|l| l.sim.initial_energy).collect();
    let residual = energy_balance_residual(&outputs, &e0);
    let exchanged: f64 = outputs.iter().map(|o| o.work_top.abs() + o.work_hydro.abs() + o.work_seabed.abs()).sum();
    eprintln!("residual {residual:.3e} J of {exchanged:.3e} J exchanged");
    assert!(exchanged > 1e5, "the vessel worked on the lines: {exchanged} J");
    assert!(residual.abs() < 1e-6 * exchanged, "{residual} J of {exchanged} J");
}

/// A system of one line, the built-in catenary written as a system (its
/// anchor a fixed point, its hang-off the vessel's reference point), gives
/// the single-line scene's answers bit for bit: the system layer composes
/// the line as it is alone (issue 49, evidence 4).
#[test]
fn a_one_line_system_is_the_single_line_scene_bit_for_bit() {
    let scene = Scene::builtin("catenary").unwrap();
    let a = &scene.anchor;
    let text = format!(
        "name = \"one\"\n[[line_type]]\nname = \"riser\"\nmodel = \"rod\"\nmass_per_length = 1.0\n\
         outer_diameter = 0.3\naxial_stiffness = 1e8\nbending_stiffness = 1e4\ntorsional_stiffness = 1e4\n\
         [[point]]\nname = \"anchor\"\nkind = \"fixed\"\nposition = [{}, {}, {}]\n\
         [[point]]\nname = \"hang_off\"\nkind = \"vessel\"\nposition = [0.0, 0.0, 0.0]\n\
         [[line]]\nname = \"riser\"\ntype = \"riser\"\nfrom = \"hang_off\"\nto = \"anchor\"\nlength = {}\nn_elements = {}\n",
        a.x, a.y, a.z, scene.line.length, 20
    );
    let mut sys = SystemScene::from_toml(&text, "one").unwrap();
    // the catenary's line, water, current and numerics, in the system's frame (its origin the hang-off)
    sys.line_types[0].line = scene.line.clone();
    sys.environment = scene.environment.clone();
    sys.current = scene.current.clone();
    sys.seabed = scene.seabed.clone();
    sys.waves = scene.waves.clone();
    sys.analysis = scene.analysis.clone();
    let mut single = scene.clone();
    single.analysis.n_elements = 20;
    let heave = |t: f64| VesselMotion {
        displacement: V3::z() * 2.0 * (0.6 * t).sin(),
        velocity: V3::z() * 1.2 * (0.6 * t).cos(),
        ..Default::default()
    };
    let mut run = SystemRun::new(&sys).unwrap();
    run.start(&heave(0.0));
    let mut sim = Simulation::from_scene(&single).unwrap();
    let vessel = sim.vessel;
    let hang_off = |t: f64| -> HangOff { vessel.hang_off(&heave(t)) };
    sim.start(hang_off(0.0));
    assert_eq!(run.lines[0].sim.state, sim.state, "the same static state");
    let dt = single.analysis.time_step;
    for k in 1..=100 {
        let t = k as f64 * dt;
        run.advance_to(t, &heave, 1).unwrap();
        sim.advance_to(t, &hang_off).unwrap();
    }
    assert_eq!(run.lines[0].sim.state, sim.state, "the same state after 100 steps");
    let (o, os) = (run.outputs(), sim.outputs());
    assert_eq!(SystemRun::resultant(&o).force, os.top_force);
    assert_eq!(o[0].top_tension, os.top_tension);
}
