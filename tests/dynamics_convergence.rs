//! Second-order accuracy in the time step (the midpoint scheme, and its
//! high-frequency dissipative variant, docs/theory.md §5.10), on the
//! catenary scene against a fine-step reference run.

use riser::math::V3;
use riser::scene::Scene;
use riser::sim::{Heave, Simulation};

/// Centreline at S = k L / 20 after 10 s of smoothly started heave with the current.
fn shape_after(dt: f64, rho_infinity: f64) -> Vec<V3> {
    let sets = ["n_elements=20".to_string(), format!("time_step={dt}"), format!("rho_infinity={rho_infinity}")];
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&sets).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    // smooth start: the order needs a smooth input (an abrupt start has a velocity jump)
    let heave = Heave { amplitude: 2.5, period: 10.0, until: None, ramp: 10.0 };
    let motion = move |t: f64| heave.at(t);
    sim.start(heave.at(0.0));
    let n = (10.0 / dt).round() as u64;
    for k in 1..=n {
        sim.advance_to(k as f64 * dt, &motion).unwrap();
    }
    sim.outputs().shape.to_vec()
}

#[test]
fn the_scheme_is_second_order_in_the_time_step() {
    for rho in [1.0, 0.5] {
        let reference = shape_after(0.00625, rho);
        let mut errors = Vec::new();
        for dt in [0.2, 0.1, 0.05] {
            let s = shape_after(dt, rho);
            let e = s.iter().zip(&reference).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
            errors.push((dt, e));
        }
        for w in errors.windows(2) {
            let order = (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln();
            eprintln!(
                "rho_inf {rho}, dt {} -> {}: max shape error {:.3e} -> {:.3e} m, observed order {order:.2}",
                w[0].0, w[1].0, w[0].1, w[1].1
            );
            assert!((order - 2.0).abs() < 0.3, "observed order {order}");
        }
    }
}
