//! The cheap cells of the stability matrix (docs/stability.md): each extreme
//! setting either completes with finite outputs and the energy balance
//! closed, or stops with a typed error and a finite state kept. Never a NaN,
//! a panic or a hang.

use riser::scene::Scene;
use riser::sim::{Heave, Simulation};

/// Runs `duration` s of heave from the static state; returns the outcome.
fn cell(scene: &str, sets: &[&str], heave: (f64, f64), duration: f64) -> String {
    cell_dropped(scene, sets, heave, duration, 0.0)
}

/// The same, with every free node of the line given a downward velocity of
/// `drop` m/s at t = 0 (a line slamming onto the seabed).
fn cell_dropped(scene: &str, sets: &[&str], heave: (f64, f64), duration: f64, drop: f64) -> String {
    let mut all = vec!["n_elements=20".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    let scene = Scene::builtin(scene).unwrap().with_overrides(&all).unwrap();
    run_cell(scene, heave, duration, drop)
}

/// [`cell_dropped`] on a scene as it is.
fn run_cell(scene: Scene, heave: (f64, f64), duration: f64, drop: f64) -> String {
    let mut sim = match Simulation::from_scene(&scene) {
        Ok(s) => s,
        Err(e) => {
            let msg = e.to_string();
            assert!(!msg.is_empty());
            return format!("clean error in statics: {msg}");
        }
    };
    let h = Heave { amplitude: heave.0, period: heave.1, until: None, ramp: 0.0 };
    let motion = move |t: f64| h.at(t);
    sim.start(h.at(0.0));
    if drop != 0.0 {
        let last = sim.state.vel.len() - 1;
        for v in &mut sim.state.vel[1..last] {
            *v = riser::math::V3::new(0.0, 0.0, -drop);
        }
        sim.state.mean_vel.clone_from(&sim.state.vel);
        sim.state.prev_mean_vel.clone_from(&sim.state.vel);
        sim.initial_energy = sim.outputs().total_energy;
    }
    let e0 = sim.initial_energy;
    let dt = sim.integrator.options().time_step;
    let n = (duration / dt).ceil() as u64;
    let mut worst: f64 = 0.0;
    let mut exchanged: f64 = 0.0;
    for k in 1..=n {
        let r = sim.advance_to((k as f64 * dt).min(duration), &motion);
        let o = sim.outputs();
        assert!(o.values().iter().all(|v| v.is_finite()), "non-finite output at t = {}", sim.state.time);
        assert!(sim.state.is_finite());
        if let Err(e) = r {
            let msg = e.to_string();
            assert!(msg.contains("kept"), "{msg}");
            return format!("clean stop at t = {:.3} s: {msg}", sim.state.time);
        }
        worst = worst.max(o.energy_balance_residual(e0).abs());
        exchanged = exchanged.max(o.work_top.abs() + o.work_hydro.abs() + o.work_seabed.abs());
        if k == n {
            eprintln!("  (energy balance {worst:.2e} J of {exchanged:.2e} J exchanged)");
        }
    }
    assert!(worst <= 1e-6 * exchanged.max(1.0), "energy balance {worst:e} of {exchanged:e}");
    "completes".to_string()
}

#[test]
fn extreme_time_steps() {
    for (dt, dur) in [("1", 4.0), ("1e-3", 0.2)] {
        let r = cell("catenary", &[&format!("time_step={dt}")], (2.5, 20.0), dur);
        eprintln!("dt {dt}: {r}");
    }
}

#[test]
fn extreme_meshes() {
    for (n, dur) in [("4", 2.0), ("400", 0.3)] {
        let r = cell("catenary", &[&format!("n_elements={n}")], (2.5, 20.0), dur);
        eprintln!("{n} elements: {r}");
    }
}

#[test]
fn extreme_stiffnesses() {
    for s in ["axial_stiffness=1e6", "axial_stiffness=1e11", "bending_stiffness=0", "bending_stiffness=1e7"] {
        let r = cell("catenary", &[s], (2.5, 20.0), 1.0);
        eprintln!("{s}: {r}");
    }
}

#[test]
fn violent_heave_and_strong_currents() {
    let r = cell("catenary", &[], (10.0, 3.0), 1.5);
    eprintln!("heave 10 m / 3 s: {r}");
    for c in ["-3", "3"] {
        let r = cell("catenary", &[&format!("current_top={c}"), &format!("current_bottom={c}")], (2.5, 20.0), 1.0);
        eprintln!("current {c} m/s: {r}");
    }
}

/// The seabed's cells (issue 17): the stiffest seabed (1e8 Pa/m), friction
/// 1, and the line slamming down onto it at 2 m/s, rod and cable, on the
/// steel catenary (about 110 m on the seabed) with the heave of 3 m / 10 s.
#[test]
fn seabed_extremes() {
    for model in ["rod", "cable"] {
        let m = format!("model={model}");
        for (label, sets, drop) in [
            ("stiff seabed 1e8 Pa/m", vec!["seabed_stiffness=1e8"], 0.0),
            ("friction 1", vec!["seabed_friction=1"], 0.0),
            ("slamming at 2 m/s", vec![], 2.0),
            ("stiff seabed, friction 1, slamming at 2 m/s", vec!["seabed_stiffness=1e8", "seabed_friction=1"], 2.0),
        ] {
            let mut all = vec![m.as_str()];
            all.extend(sets);
            let r = cell_dropped("steel_catenary", &all, (3.0, 10.0), 3.0, drop);
            eprintln!("{model}, {label}: {r}");
        }
    }
}

#[test]
fn lazy_wave_with_doubled_buoyancy() {
    let r = cell("lazy_wave", &["buoyancy_load=1340"], (2.5, 30.0), 1.0);
    eprintln!("lazy wave, buoyancy doubled: {r}");
}

#[test]
fn the_cable_model_at_the_extremes() {
    // slack and snap (violent heave, the tension-only law), the stiffest and
    // softest lines, the largest step, the coarsest and finest meshes, the
    // strongest currents, and the floating lazy wave
    type Cell<'a> = (&'a str, &'a [&'a str], (f64, f64), f64);
    let cells: [Cell; 9] = [
        ("catenary", &["time_step=1"], (2.5, 20.0), 4.0),
        ("catenary", &["n_elements=4"], (2.5, 20.0), 2.0),
        ("catenary", &["n_elements=400"], (2.5, 20.0), 0.5),
        ("catenary", &["axial_stiffness=1e6"], (2.5, 20.0), 1.0),
        ("catenary", &["axial_stiffness=1e11"], (2.5, 20.0), 1.0),
        ("catenary", &[], (10.0, 3.0), 3.0),
        ("catenary", &["current_top=3", "current_bottom=3"], (2.5, 20.0), 1.0),
        ("catenary", &["current_top=-3", "current_bottom=-3"], (2.5, 20.0), 1.0),
        ("lazy_wave", &["buoyancy_load=1340"], (2.5, 30.0), 1.0),
    ];
    for (scene, sets, heave, duration) in cells {
        let mut all = vec!["model=cable"];
        all.extend_from_slice(sets);
        let r = cell(scene, &all, heave, duration);
        eprintln!("cable, {scene} {sets:?}, heave {heave:?}: {r}");
    }
}

/// EA = 1e10 N with the abrupt start: at t = 7.40 s Newton once converged to
/// a spurious root of the step equations that turns directors by π (the
/// reduced moment equations then bound the energy error only through
/// θ·m, |θ| = 2 tan(φ/2) → ∞), and the energy balance broke by 1.6e7 J.
/// Such a step is now rejected and split (theory §5.7).
#[test]
fn a_spurious_root_is_rejected_and_the_balance_stays_closed() {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&["axial_stiffness=1e10"]).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let h = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 0.0 };
    let motion = move |t: f64| h.at(t);
    sim.start(h.at(0.0));
    let e0 = sim.initial_energy;
    let mut worst: f64 = 0.0;
    let mut exchanged: f64 = 0.0;
    for k in 1..=150 {
        sim.advance_to(k as f64 * 0.05, &motion).unwrap();
        let o = sim.outputs();
        worst = worst.max(o.energy_balance_residual(e0).abs());
        exchanged = exchanged.max(o.work_top.abs() + o.work_hydro.abs());
    }
    eprintln!("EA 1e10, 7.5 s: balance {worst:.2e} J of {exchanged:.2e} J, {} split steps", sim.state.retries);
    assert!(worst <= 1e-6 * exchanged, "energy balance {worst:e} of {exchanged:e}");
}

/// Storm seas (issue 27): a JONSWAP sea of Hs 15 m, Tp 13 s (grown over one
/// Tp) on the catenary and the lazy wave with the vessel still, rod and
/// cable; and the Lowe & Langley jumper, whose top (5 m under the mean
/// level) goes through the surface in every 10 s wave of 14 m. Each
/// completes with the balance closed or stops cleanly; never a NaN.
#[test]
fn storm_seas_and_a_top_through_the_surface() {
    let storm = ["wave_kind=jonswap", "wave_hs=15", "wave_tp=13", "wave_direction=20"];
    for scene in ["catenary", "lazy_wave"] {
        for model in ["rod", "cable"] {
            let m = format!("model={model}");
            let mut sets = vec![m.as_str()];
            sets.extend(storm);
            let r = cell(scene, &sets, (0.0, 13.0), 30.0);
            eprintln!("{scene}, {model}, JONSWAP Hs 15 m Tp 13 s: {r}");
        }
    }
    let dir = env!("CARGO_MANIFEST_DIR");
    for model in ["rod", "cable"] {
        let sc = Scene::load(&format!("{dir}/docs/cases/lowe_langley_jumper.toml"))
            .unwrap()
            .with_overrides(&[
                &format!("model={model}"),
                "wave_kind=airy",
                "wave_height=14",
                "wave_period=10",
                "wave_direction=45",
            ])
            .unwrap();
        let r = run_cell(sc, (0.0, 10.0), 30.0, 0.0);
        eprintln!("jumper, {model}, top through the surface (14 m, 10 s): {r}");
    }
}
