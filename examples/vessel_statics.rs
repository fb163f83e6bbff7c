//! The rod's static state with the vessel moved and turned, for the finite
//! differences of the FMU's directional derivative with a clamped end or a
//! flex joint (tests/python/test_vessel.py): `riser statics` moves the
//! hang-off only through the anchor, which cannot turn a clamp's frame.
//!
//!     cargo run --release --example vessel_statics -- SCENE DX DY DZ R11 R12 R13 R21 R22 R23 R31 R32 R33 [NAME=VALUE...]
//!
//! From the scene's static state (the vessel unrotated), the hang-off moved
//! by (DX, DY, DZ) and the vessel's frame turned by R (row by row): a
//! clamped end's frame becomes R D_static, a flex joint holds its spring
//! against R D_static (docs/theory.md §15); the statics re-solved. Prints
//! JSON: the force of the line on the vessel (`force`, N) and its end moment
//! on the vessel (`end_moment`, N m; zero for a pinned end), global frame.
use riser::math::{M3, V3};
use riser::model::State;
use riser::model::rod::RotationBc;
use riser::model::rod::statics::StaticProblem;
use riser::model::statics::StaticOptions;
use riser::scene::Scene;
use riser::sim::report::scene_static_loads;
use riser::sim::{Engine, Simulation};
use riser::solve::statics::solve;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 13 {
        eprintln!("usage: vessel_statics SCENE DX DY DZ R11 R12 R13 R21 R22 R23 R31 R32 R33 [NAME=VALUE...]");
        std::process::exit(2);
    }
    let num = |s: &str| s.parse::<f64>().unwrap_or_else(|e| panic!("{s}: {e}"));
    let v: Vec<f64> = args[1..13].iter().map(|s| num(s)).collect();
    let disp = V3::new(v[0], v[1], v[2]);
    let r = M3::from_row_slice(&v[3..12]);
    let scene = Scene::builtin(&args[0]).expect("a built-in scene").with_overrides(&args[13..]).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let Engine::Rod(i) = &sim.integrator else { panic!("the rod only") };
    let mut model = i.model.clone();
    let mut cfg = sim.state.config.clone();
    cfg.x[0] += disp;
    match model.rod.flex_joint.as_mut() {
        Some(j) => j.frame = Some(r * j.frame.expect("the static frame is set")),
        None if model.rod.ends[0].rotation == RotationBc::Clamped => cfg.d[0] = r * cfg.d[0],
        None => {}
    }
    let loads = scene_static_loads(&scene);
    let opts = StaticOptions { tolerance: 1e-12, ..Default::default() };
    let sol = solve(&StaticProblem::new(&model.rod, &loads), cfg, &opts).unwrap();
    // at rest with R = I: the joint's frame is the one set above
    let o = model.outputs(&State::at_rest(sol.config.clone(), 0.0));
    let (f, m) = (-sol.reactions[0], o.end_moment);
    println!(
        "{{\"force\": [{:e}, {:e}, {:e}], \"end_moment\": [{:e}, {:e}, {:e}], \"residual\": {:e}}}",
        f.x, f.y, f.z, m.x, m.y, m.z, sol.residual
    );
}
