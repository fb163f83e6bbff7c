use riser::hydro::weight::VerticalLoad;
use riser::rod::kinematics::V3;
use riser::rod::model::{EndBc, Rod, Stiffness};
use riser::statics::*;
fn main() {
    for (ei, gj) in [(5.882e4, 9.25e6), (1e-3, 1e-3)] {
        for n in [4, 10, 20, 40, 60, 120, 240, 400] {
            let rod = Rod::new(n, 100.0, Stiffness::paper(7.96e8, ei, gj), [EndBc::PINNED, EndBc::PINNED_NO_TWIST]);
            let load = VerticalLoad::new(226.7, 0.3172, 1025.0, 9.81);
            let start = catenary_start(&rod, &load, V3::zeros(), V3::new(60.0, 0.0, -70.0));
            let loads = StaticLoads::gravity_only(load);
            let t = std::time::Instant::now();
            match solve(&rod, &loads, start, &StaticOptions::default()) {
                Ok(s) => println!(
                    "EI {ei} n {n}: top {:.3} N bottom {:.3} it {} steps {} res {:.2e} time {:?}",
                    s.reactions[0].norm(),
                    s.reactions[1].norm(),
                    s.iterations,
                    s.continuation_steps,
                    s.residual,
                    t.elapsed()
                ),
                Err(e) => println!("EI {ei} n {n}: {e}"),
            }
        }
    }
}
