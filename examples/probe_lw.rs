use riser::scene::Scene;
use riser::statics::report::solve_scene;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let sets: Vec<String> = args[2..].to_vec();
    let scene = Scene::load(&args[1]).unwrap().with_overrides(&sets).unwrap();
    let (rod, rep) = solve_scene(&scene).unwrap();
    println!("top {:.1} H {:.1} it {}", rep.top_tension, rep.top_force.x, rep.iterations);
    let c = &rep.solution.config;
    for e in (0..rod.n_el).step_by(rod.n_el / 12) {
        let g: Vec<String> = riser::rod::shape::GAUSS4.xi.iter().map(|&xi| format!("{:.0}", rod.axial_force(c, e, xi))).collect();
        let mid = rod.axial_force(c, e, 0.5);
        let (n, t) = rod.force_resultant(c, e, 0.5);
        println!("e {e} S {:.1} gp {:?} mid {:.0} |n| {:.0} shear {:.0}", rod.s_node(e), g, mid, n.norm(), (n - t * n.dot(&t)).norm());
    }
}
