//! The line in waves (docs/theory.md §13.6): the energy balance closes with
//! the waves' work counted in `work_hydro`, for the rod and the cable, with
//! the conserving scheme (ρ∞ = 1) and the default dissipation, while the
//! line's top goes through the moving surface in every wave.

use riser::model::HangOff;
use riser::scene::Scene;
use riser::sim::Simulation;

/// The Lowe & Langley jumper (docs/cases/lowe_langley_jumper.toml) with
/// `sets` and a regular wave of `height` m, 10 s, travelling at 30°, the
/// vessel held still, started: the simulation (the waves' ramp one period).
fn jumper_in_a_wave(sets: &[String], height: f64) -> Simulation {
    let mut all = sets.to_vec();
    all.extend(
        ["wave_kind=airy", &format!("wave_height={height}"), "wave_period=10", "wave_direction=30"].map(String::from),
    );
    let all: Vec<&str> = all.iter().map(String::as_str).collect();
    let dir = env!("CARGO_MANIFEST_DIR");
    let sc = Scene::load(&format!("{dir}/docs/cases/lowe_langley_jumper.toml")).unwrap().with_overrides(&all).unwrap();
    let mut sim = Simulation::from_scene(&sc).unwrap();
    sim.start(HangOff::default());
    sim
}

/// The Lowe & Langley jumper (hang-off 5 m under the mean level) in a
/// regular 14 m, 10 s wave grown over one period: every trough uncovers its
/// top 2 m. Over 40 s (800 steps of 0.05 s) the
/// balance E − E₀ = W_top + W_hydro + W_seabed − D − A closes to the Newton
/// tolerance's share of what was exchanged.
#[test]
fn the_energy_balance_closes_in_waves_through_the_moving_surface() {
    for model in ["rod", "cable"] {
        for rho in ["1", "0.8"] {
            let sets = [format!("model={model}"), format!("rho_infinity={rho}"), "newton_tolerance=1e-10".into()];
            let mut sim = jumper_in_a_wave(&sets, 14.0);
            let motion = |_t: f64| HangOff::default();
            let e0 = sim.initial_energy;
            let (mut worst, mut exchanged, mut emerged) = (0.0f64, 0.0f64, 0usize);
            let top = sim.state.config.x[0];
            let sea = sim.sea.clone().unwrap();
            for k in 1..=800 {
                let t = k as f64 * 0.05;
                sim.advance_to(t, &motion).unwrap();
                let o = sim.outputs();
                worst = worst.max(o.energy_balance_residual(e0).abs());
                exchanged = exchanged
                    .max(o.work_top.abs() + o.work_hydro.abs() + o.dissipated_energy + o.algorithmic_dissipation);
                emerged += usize::from(sea.ramped_elevation(top.x, top.y, t) < top.z - sea.settings().surface_z);
            }
            println!(
                "{model}, rho_infinity {rho}: balance residual {worst:.3e} J of {exchanged:.3e} J exchanged; top out of the water at {emerged} of 800 steps"
            );
            assert!(emerged > 40, "the top never left the water ({emerged})");
            assert!(worst <= 1e-8 * exchanged, "{model}, {rho}: {worst} J of {exchanged} J");
        }
    }
}

/// Holding the water over a step at the predicted midpoint keeps the
/// scheme's second order (§13.6): the jumper in a regular 6 m, 10 s wave
/// grown over one period (its top stays under the troughs), rod and cable,
/// ρ∞ = 1 and 0.8: the shape at t = 12 s at steps 0.2, 0.1 and 0.05 s
/// against 0.00625 s has the observed order 2 ± 0.3, as the still-water
/// scheme (`dynamics_convergence.rs`).
#[test]
fn the_shape_in_waves_converges_at_second_order_in_the_step() {
    for model in ["rod", "cable"] {
        for rho in [1.0, 0.8] {
            let run = |dt: f64| -> Vec<riser::math::V3> {
                let sets = [
                    format!("model={model}"),
                    format!("time_step={dt}"),
                    format!("rho_infinity={rho}"),
                    "n_elements=20".into(),
                    "newton_tolerance=1e-11".into(),
                ];
                let mut sim = jumper_in_a_wave(&sets, 6.0);
                let motion = |_t: f64| HangOff::default();
                for k in 1..=(12.0 / dt).round() as usize {
                    sim.advance_to(k as f64 * dt, &motion).unwrap();
                }
                sim.outputs().shape.to_vec()
            };
            let reference = run(0.00625);
            let errors: Vec<(f64, f64)> = [0.2, 0.1, 0.05]
                .iter()
                .map(|&dt| (dt, run(dt).iter().zip(&reference).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max)))
                .collect();
            for w in errors.windows(2) {
                let order = (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln();
                println!(
                    "{model}, rho_inf {rho}, dt {} -> {}: max shape error {:.3e} -> {:.3e} m, observed order {order:.2}",
                    w[0].0, w[1].0, w[0].1, w[1].1
                );
                assert!((order - 2.0).abs() < 0.3, "{model}, rho_inf {rho}: observed order {order}");
            }
        }
    }
}
