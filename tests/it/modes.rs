//! Natural modes (solve::eigen::lowest_modes) against closed forms: the taut
//! string, the hanging chain and the cantilever, rod and cable; the mass
//! matrix against the kinetic energy; mesh convergence.

use crate::common;

use riser::loads::fluid::Fluid;
use riser::loads::weight::VerticalLoad;
use riser::math::{M3, V3, skew};
use riser::model::cable::linearized::CableLinearized;
use riser::model::cable::{Cable, CableModel};
use riser::model::linearized::{Direction, Linearized};
use riser::model::rod::linearized::RodLinearized;
use riser::model::rod::statics::{StaticLoads, StaticProblem};
use riser::model::rod::{EndBc, Rod, RodModel, Stiffness};
use riser::model::statics::StaticOptions;
use riser::model::{RodConfig, State};
use riser::solve::eigen::{Modes, lowest_modes};
use riser::solve::statics::solve;
use std::f64::consts::PI;

fn no_gravity() -> VerticalLoad {
    VerticalLoad { uniform: 0.0, sections: vec![] }
}

/// Frequencies (Hz) of the modes moving the line mostly in `dir`.
fn frequencies_in<L: Linearized>(line: &L, cfg: &RodConfig, modes: &Modes, dir: Direction, normal: V3) -> Vec<f64> {
    modes
        .modes
        .iter()
        .filter(|m| line.motion(cfg, &m.vector, &normal).direction() == dir)
        .map(|m| m.frequency())
        .collect()
}

fn check(what: &str, got: &[f64], exact: &[f64], tol: f64) {
    assert!(got.len() >= exact.len(), "{what}: only {} modes found", got.len());
    for (n, (f, e)) in got.iter().zip(exact).enumerate() {
        let err = (f - e) / e;
        eprintln!("{what} mode {}: {f:.6} Hz vs closed form {e:.6} Hz ({:+.4} %)", n + 1, 100.0 * err);
        assert!(err.abs() < tol, "{what} mode {}: {f} Hz vs {e} Hz", n + 1);
    }
}

/// A straight vertical rod from the origin down, stretched by `stretch`.
fn vertical(rod: &Rod, stretch: f64) -> RodConfig {
    let n_el = rod.n_el;
    RodConfig {
        x: (0..=n_el).map(|a| V3::z() * (-rod.s_node(a) * stretch)).collect(),
        xp: vec![-V3::z() * stretch; n_el + 1],
        d: vec![M3::from_columns(&[V3::y(), V3::x(), -V3::z()]); 2 * n_el + 1],
    }
}

// Taut string with a little bending stiffness, pinned at both ends:
// ω_n² = [T (nπ/ℓ)² + EI (nπ/ℓ)⁴] / μ, ℓ the stretched length, μ = m/λ.
#[test]
fn taut_string_rod_first_three_transverse_frequencies() {
    let (l0, stretch, ea, ei, m) = (10.0, 1.01, 1e6, 1.0, 1.0);
    let rod = Rod::new(40, l0, Stiffness::paper(ea, ei, 1.0), [EndBc::PINNED_NO_TWIST, EndBc::PINNED]);
    let cfg = vertical(&rod, stretch);
    let model = RodModel::new(rod, m, [1e-6, 1e-6], no_gravity(), Fluid::none());
    let loads = StaticLoads::gravity_only(no_gravity());
    let line = RodLinearized::new(&model, &loads);
    let modes = lowest_modes(&line, &cfg, 12).unwrap();
    let (t, span, mu) = (ea * (stretch - 1.0), l0 * stretch, m / stretch);
    let exact: Vec<f64> = (1..=3)
        .map(|n| {
            let k = n as f64 * PI / span;
            ((t * k * k + ei * k.powi(4)) / mu).sqrt() / (2.0 * PI)
        })
        .collect();
    // a vertical line: ŷ is its "out-of-plane" direction, x̂ the in-plane one; the two are degenerate
    let fy = frequencies_in(&line, &cfg, &modes, Direction::OutOfPlane, V3::y());
    let fx = frequencies_in(&line, &cfg, &modes, Direction::InPlane, V3::y());
    check("taut string (rod, y)", &fy, &exact, 0.005);
    check("taut string (rod, x)", &fx, &exact, 0.005);
}

#[test]
fn taut_string_cable_first_three_transverse_frequencies() {
    let (l0, stretch, ea, m) = (10.0, 1.01, 1e6, 1.0);
    let n_el = 60;
    let cable = Cable::new(l0, n_el, ea, [true, true]);
    let model = CableModel::new(cable, m, no_gravity(), Fluid::none());
    let cfg = RodConfig {
        x: (0..=n_el).map(|a| V3::z() * (-(a as f64) * l0 / n_el as f64 * stretch)).collect(),
        xp: vec![],
        d: vec![],
    };
    let line = CableLinearized::new(&model, false);
    let modes = lowest_modes(&line, &cfg, 12).unwrap();
    let (t, span, mu) = (ea * (stretch - 1.0), l0 * stretch, m / stretch);
    // the discrete string of N segments with the cable's mass ρ̄ l/12 [[5, 1], [1, 5]]:
    // ω² = (T/(μ ℓ_e²)) 2(1 − cos θ) / ((5 + cos θ)/6), θ = nπ/N — within 0.1 % of the
    // continuous string for n ≤ 3 at N = 60; the test holds the continuous one to 0.5 %.
    let exact: Vec<f64> = (1..=3).map(|n| n as f64 / (2.0 * span) * (t / mu).sqrt()).collect();
    let fy = frequencies_in(&line, &cfg, &modes, Direction::OutOfPlane, V3::y());
    check("taut string (cable)", &fy, &exact, 0.005);
}

// Hanging chain, free at the bottom: ω_n = (j_{0,n}/2) √(g/L).
#[test]
fn hanging_chain_rod_first_three_frequencies() {
    let (l, m, g) = (10.0, 1.0, 9.81);
    let rod = Rod::new(40, l, Stiffness::paper(1e7, 1e-3, 1e-3), [EndBc::PINNED_NO_TWIST, EndBc::FREE]);
    let vertical_load = VerticalLoad { uniform: -m * g, sections: vec![] };
    let loads = StaticLoads::gravity_only(vertical_load.clone());
    let start = rod.straight(V3::zeros(), -V3::z(), V3::y());
    let sol = solve(&StaticProblem::new(&rod, &loads), start, &StaticOptions::default()).unwrap();
    let model = RodModel::new(rod, m, [1e-6, 1e-6], vertical_load, Fluid::none());
    let line = RodLinearized::new(&model, &loads);
    let modes = lowest_modes(&line, &sol.config, 10).unwrap();
    let exact: Vec<f64> =
        common::reference::bessel_j0_zeros(3).iter().map(|j| j / 2.0 * (g / l).sqrt() / (2.0 * PI)).collect();
    let fy = frequencies_in(&line, &sol.config, &modes, Direction::OutOfPlane, V3::y());
    check("hanging chain (rod)", &fy, &exact, 0.005);
}

#[test]
fn hanging_chain_cable_first_three_frequencies() {
    let (l, m, g) = (10.0, 1.0, 9.81);
    let n_el = 80;
    let cable = Cable::new(l, n_el, 1e7, [true, false]);
    let model = CableModel::new(cable, m, VerticalLoad { uniform: -m * g, sections: vec![] }, Fluid::none());
    // static state: the tension m g (L − S) stretches each segment
    let mut x = vec![V3::zeros(); n_el + 1];
    for a in 0..n_el {
        let s_mid = (a as f64 + 0.5) * l / n_el as f64;
        let stretch = 1.0 + m * g * (l - s_mid) / 1e7;
        x[a + 1] = x[a] - V3::z() * (l / n_el as f64 * stretch);
    }
    let cfg = RodConfig { x, xp: vec![], d: vec![] };
    let line = CableLinearized::new(&model, false);
    let modes = lowest_modes(&line, &cfg, 10).unwrap();
    let exact: Vec<f64> =
        common::reference::bessel_j0_zeros(3).iter().map(|j| j / 2.0 * (g / l).sqrt() / (2.0 * PI)).collect();
    let fy = frequencies_in(&line, &cfg, &modes, Direction::OutOfPlane, V3::y());
    check("hanging chain (cable)", &fy, &exact, 0.005);
}

// Cantilever (Euler–Bernoulli): ω_n = (β_n L)² √(EI/(m L⁴)), (βL)² = 3.5160, 22.0345.
#[test]
fn cantilever_first_two_bending_frequencies() {
    let (l, m, ei) = (10.0, 1.0, 1e3);
    let rod = Rod::new(20, l, Stiffness::paper(1e9, ei, 1e3), [EndBc::CLAMPED, EndBc::FREE]);
    let cfg = rod.straight(V3::zeros(), V3::x(), V3::y());
    let model = RodModel::new(rod, m, [1e-8, 1e-8], no_gravity(), Fluid::none());
    let loads = StaticLoads::gravity_only(no_gravity());
    let line = RodLinearized::new(&model, &loads);
    let modes = lowest_modes(&line, &cfg, 8).unwrap();
    let exact: Vec<f64> = [3.5160, 22.0345].iter().map(|b| b * (ei / (m * l.powi(4))).sqrt() / (2.0 * PI)).collect();
    // the line along x̂: ẑ × x̂ = ŷ is the out-of-plane direction
    let fy = frequencies_in(&line, &cfg, &modes, Direction::OutOfPlane, V3::y());
    check("cantilever (y)", &fy, &exact, 0.005);
    let fz = frequencies_in(&line, &cfg, &modes, Direction::InPlane, V3::y());
    check("cantilever (z)", &fz, &exact, 0.005);
}

// The mass matrix is the kinetic energy's: ½ φᵀ M φ = T(velocities φ), with
// the director rates ḋ_i = θ × d_i, checked against the model's own energy.
#[test]
fn rod_mass_matrix_is_the_kinetic_energy() {
    let rod = Rod::new(6, 12.0, Stiffness::paper(1e6, 1e3, 5e2), [EndBc::PINNED, EndBc::PINNED_NO_TWIST]);
    let loads = StaticLoads::gravity_only(VerticalLoad { uniform: -100.0, sections: vec![] });
    let start = riser::model::rod::statics::catenary_start(&rod, &loads.vertical, V3::zeros(), V3::new(8.0, 1.0, -6.0));
    let fluid = Fluid::none();
    let model = RodModel::new(rod, 30.0, [0.02, 0.03], loads.vertical.clone(), fluid);
    let line = RodLinearized::new(&model, &loads);
    let mut m = line.new_system().unwrap();
    line.mass_matrix(&start, &mut m);
    let n = line.n_dof();
    let local: Vec<usize> = model.rod.local_basis_nodes().collect();
    let mut seed = 7u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let phi: Vec<f64> = (0..n).map(|_| rnd()).collect();
    let mut mphi = vec![0.0; n];
    m.mul_add(&phi, &mut mphi);
    let quad: f64 = phi.iter().zip(&mphi).map(|(a, b)| a * b).sum();
    let mut s = State::at_rest(start.clone(), 0.0);
    for a in 0..=model.rod.n_el {
        let (i, ip) = (Rod::x_dof(a), Rod::xp_dof(a));
        s.vel[a] = V3::new(phi[i], phi[i + 1], phi[i + 2]);
        s.slope_vel[a] = V3::new(phi[ip], phi[ip + 1], phi[ip + 2]);
    }
    for j in 0..model.rod.n_director_nodes() {
        let i = Rod::theta_dof(j);
        let mut th = V3::new(phi[i], phi[i + 1], phi[i + 2]);
        if local.contains(&j) {
            th = start.d[j] * th;
        }
        s.director_vel[j] = skew(&th) * start.d[j];
    }
    let t = model.kinetic_energy(&s);
    eprintln!("½ φᵀMφ = {:.15e}, T = {t:.15e}", 0.5 * quad);
    assert!((0.5 * quad - t).abs() <= 1e-13 * t);
}

// Every mode returned solves K φ = λ M φ and is mass-normalised (the catenary
// scene: the rod's spectrum spans many decades, the test of the shift-invert).
#[test]
fn catenary_modes_solve_the_eigenproblem() {
    let scene = riser::scene::Scene::builtin("catenary").unwrap();
    let statics = riser::sim::report::solve_scene(&scene).unwrap();
    let loads = riser::sim::report::scene_static_loads(&scene);
    let model = RodModel::from_scene(&scene);
    let line = RodLinearized::new(&model, &loads);
    let cfg = &statics.solution.config;
    let modes = lowest_modes(&line, cfg, 12).unwrap();
    let n = line.n_dof();
    let (mut k, mut m) = (line.new_system().unwrap(), line.new_system().unwrap());
    let mut r = vec![0.0; n];
    line.static_tangent(cfg, &mut r, &mut k);
    line.mass_matrix(cfg, &mut m);
    let fixed = line.fixed_dofs();
    eprintln!("{} free unknowns, asymmetry {:.1e}", modes.size, modes.asymmetry);
    for md in &modes.modes {
        let (mut kp, mut mp) = (vec![0.0; n], vec![0.0; n]);
        k.mul_add(&md.vector, &mut kp);
        m.mul_add(&md.vector, &mut mp);
        let scale = kp.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let res = (0..n)
            .filter(|i| fixed.binary_search(i).is_err())
            .map(|i| (kp[i] - md.eigenvalue * mp[i]).abs())
            .fold(0.0, f64::max);
        let norm: f64 = md.vector.iter().zip(&mp).map(|(a, b)| a * b).sum();
        eprintln!("T = {:8.4} s: |Kφ − λMφ|/|Kφ| = {:.1e}, φᵀMφ = {norm:.12}", md.period(), res / scale);
        assert!(res <= 1e-8 * scale);
        assert!((norm - 1.0).abs() < 1e-12);
    }
}

/// The `k` lowest modes of `line` about `cfg`, M φ of each (the modal
/// coordinate of a displacement u is (Mφ)ᵀu) and the number of unknowns.
fn modes_and_mass_products<L: Linearized>(line: &L, cfg: &RodConfig, k: usize) -> (Modes, Vec<Vec<f64>>, usize) {
    let modes = lowest_modes(line, cfg, k).unwrap();
    let mut m = line.new_system().unwrap();
    line.mass_matrix(cfg, &mut m);
    let mphi = modes
        .modes
        .iter()
        .map(|md| {
            let mut v = vec![0.0; line.n_dof()];
            m.mul_add(&md.vector, &mut v);
            v
        })
        .collect();
    (modes, mphi, line.n_dof())
}

/// Free vibration of a scene's line started with the velocity field of its
/// first `k` modes (no drag, the conserving scheme): the frequencies of the
/// modal responses against the modal analysis.
fn modes_against_free_vibration(model_name: &str, k: usize, dt: f64, duration: f64) {
    use riser::model::HangOff;
    use riser::sim::{Engine, Simulation};
    let scene = riser::scene::Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[
            format!("model={model_name}"),
            "cd_normal=0".into(),
            "cd_tangential=0".into(),
            "rho_infinity=1".into(),
            format!("time_step={dt}"),
            "newton_tolerance=1e-10".into(),
        ])
        .unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let cfg = sim.state.config.clone();
    let loads = riser::sim::report::scene_static_loads(&scene);
    // the modes, and M φ of each (the modal coordinate of a displacement u is (Mφ)ᵀu)
    let (modes, mphi, n_dof) = match &sim.integrator {
        Engine::Rod(i) => modes_and_mass_products(&RodLinearized::new(&i.model, &loads), &cfg, k),
        Engine::Cable(i) => modes_and_mass_products(&CableLinearized::new(&i.model, false), &cfg, k),
    };
    let rod = matches!(sim.integrator, Engine::Rod(_));
    let stride = if rod { 12 } else { 3 };
    let n_nodes = cfg.x.len();
    // initial velocity: Σ_k v0 φ_k, each mode with a peak velocity of ~1 cm/s
    let mut q0 = vec![0.0; n_dof];
    for md in &modes.modes {
        let big = md.vector.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (q, v) in q0.iter_mut().zip(&md.vector) {
            *q += 0.01 * v / big;
        }
    }
    let s = &mut sim.state;
    for a in 0..n_nodes {
        let i = stride * a;
        s.vel[a] = V3::new(q0[i], q0[i + 1], q0[i + 2]);
        if rod {
            s.slope_vel[a] = V3::new(q0[i + 3], q0[i + 4], q0[i + 5]);
        }
    }
    if rod {
        if let Engine::Rod(i) = &sim.integrator {
            let local: Vec<usize> = i.model.rod.local_basis_nodes().collect();
            for j in 0..s.director_vel.len() {
                let t = Rod::theta_dof(j);
                let mut th = V3::new(q0[t], q0[t + 1], q0[t + 2]);
                if local.contains(&j) {
                    th = cfg.d[j] * th;
                }
                s.director_vel[j] = skew(&th) * cfg.d[j];
            }
        }
    }
    s.mean_vel.clone_from(&s.vel);
    s.prev_mean_vel.clone_from(&s.vel);
    s.mean_slope_vel.clone_from(&s.slope_vel);
    s.prev_mean_slope_vel.clone_from(&s.slope_vel);
    // modal coordinates from the node translations (and slopes)
    let coords = |st: &State| -> Vec<f64> {
        mphi.iter()
            .map(|mp| {
                let mut y = 0.0;
                for a in 0..n_nodes {
                    let i = stride * a;
                    let u = st.config.x[a] - cfg.x[a];
                    y += mp[i] * u.x + mp[i + 1] * u.y + mp[i + 2] * u.z;
                    if rod {
                        let up = st.config.xp[a] - cfg.xp[a];
                        y += mp[i + 3] * up.x + mp[i + 4] * up.y + mp[i + 5] * up.z;
                    }
                }
                y
            })
            .collect()
    };
    let steps = (duration / dt).round() as usize;
    let mut series = vec![Vec::with_capacity(steps + 1); modes.modes.len()];
    let still = |_t: f64| HangOff::default();
    for step in 0..=steps {
        if step > 0 {
            sim.integrator.step(&mut sim.state, dt, &still).unwrap();
        }
        for (y, c) in series.iter_mut().zip(coords(&sim.state)) {
            y.push(c);
        }
    }
    for (md, y) in modes.modes.iter().zip(&series) {
        let f = common::spectral::peak_near(y, dt, md.frequency());
        let err = (f - md.frequency()) / md.frequency();
        eprintln!(
            "catenary ({model_name}): modal T = {:.4} s, free vibration T = {:.4} s ({:+.3} %)",
            md.period(),
            1.0 / f,
            100.0 * err
        );
        assert!(err.abs() < 0.01);
    }
}

#[test]
fn catenary_rod_modes_match_free_vibration() {
    modes_against_free_vibration("rod", 4, 0.05, 300.0);
}

#[test]
fn catenary_cable_modes_match_free_vibration() {
    modes_against_free_vibration("cable", 4, 0.05, 300.0);
}

/// Periods of the first `k` modes of the catenary scene with `n` elements.
fn catenary_periods(model: &str, n: usize, k: usize) -> Vec<f64> {
    let scene = riser::scene::Scene::builtin("catenary")
        .unwrap()
        .with_overrides(&[format!("model={model}"), format!("n_elements={n}")])
        .unwrap();
    riser::sim::modes::scene_modes(&scene, k).unwrap().modes.iter().map(|m| m.period).collect()
}

/// Mesh convergence of the catenary's first six periods, 10–80 elements,
/// against 160 elements: the error falls at the order the elements promise.
fn mesh_convergence(model: &str, min_order: f64, max_error_80: f64) {
    let k = 6;
    let reference = catenary_periods(model, 160, k);
    let meshes = [10, 20, 40, 80];
    let errors: Vec<Vec<f64>> = meshes
        .iter()
        .map(|&n| catenary_periods(model, n, k).iter().zip(&reference).map(|(t, r)| ((t - r) / r).abs()).collect())
        .collect();
    eprintln!("catenary ({model}): relative period error against 160 elements (observed order)");
    for m in 0..k {
        let mut line = format!("  mode {} (T = {:.4} s):", m + 1, reference[m]);
        for (i, &n) in meshes.iter().enumerate() {
            line += &format!(" {n} el {:.2e}", errors[i][m]);
            if i > 0 {
                line += &format!(" ({:.1})", (errors[i - 1][m] / errors[i][m]).log2());
            }
        }
        eprintln!("{line}");
    }
    for m in 0..k {
        assert!(errors[3][m] < max_error_80, "mode {}: {:.2e} at 80 elements", m + 1, errors[3][m]);
        // the mean order from 20 to 80 elements (one step may be off where
        // the error changes sign or is still pre-asymptotic)
        let order = (errors[1][m] / errors[3][m]).log2() / 2.0;
        assert!(order > min_order, "mode {}: order {order:.2}", m + 1);
    }
}

#[test]
fn catenary_rod_modes_converge_with_the_mesh() {
    mesh_convergence("rod", 3.5, 1e-6);
}

#[test]
fn catenary_cable_modes_converge_with_the_mesh() {
    mesh_convergence("cable", 1.8, 1e-3);
}
