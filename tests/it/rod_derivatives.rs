//! Evidence 1 and 2 of the statics issue: the internal force is the gradient
//! of the strain energy and the tangent is the derivative of the internal
//! force (central finite differences on random configurations); the strains
//! and energy are objective and the internal force rotates with the line.

use nalgebra::{Matrix3, Vector3};
use riser::math::cayley;
use riser::model::RodConfig;
use riser::model::rod::{EndBc, Rod, Stiffness};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
    fn v3(&mut self, s: f64) -> Vector3<f64> {
        Vector3::new(self.next(), self.next(), self.next()) * s
    }
}

/// A rod with distinct stiffness per component and a curved random state.
fn random_rod_and_config(seed: u64, n_el: usize) -> (Rod, RodConfig) {
    let mut rng = Lcg(seed);
    let stiff = Stiffness { axial: 3.0e3, shear: 2.0e3, bending: [1.3e2, 0.7e2], torsion: 0.9e2 };
    let mut rod = Rod::new(n_el, 2.0, stiff, [EndBc::FREE, EndBc::FREE]);
    // a curved (non-straight) reference so that the reference strains are non-zero
    let mut reference = rod.straight(Vector3::zeros(), Vector3::new(1.0, 0.2, 0.1), Vector3::y());
    for d in reference.d.iter_mut() {
        *d = cayley(&rng.v3(0.1)) * *d;
    }
    rod.set_reference(reference.clone());
    let mut cfg = reference;
    for x in cfg.x.iter_mut() {
        *x += rng.v3(0.05);
    }
    for x in cfg.xp.iter_mut() {
        *x += rng.v3(0.1);
    }
    for d in cfg.d.iter_mut() {
        *d = cayley(&rng.v3(0.3)) * *d;
    }
    (rod, cfg)
}

fn perturbed(rod: &Rod, cfg: &RodConfig, i: usize, eps: f64) -> RodConfig {
    let mut du = vec![0.0; rod.n_dof()];
    du[i] = eps;
    let mut c = cfg.clone();
    rod.apply_increment(&mut c, &du);
    c
}

#[test]
fn internal_force_is_the_gradient_of_the_strain_energy() {
    for seed in [1, 2, 3] {
        let (rod, cfg) = random_rod_and_config(seed, 3);
        let mut r = vec![0.0; rod.n_dof()];
        rod.add_internal_force(&cfg, &mut r, None);
        let scale = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let eps = 1e-6;
        for i in 0..rod.n_dof() {
            let wp = rod.strain_energy(&perturbed(&rod, &cfg, i, eps));
            let wm = rod.strain_energy(&perturbed(&rod, &cfg, i, -eps));
            let fd = (wp - wm) / (2.0 * eps);
            // central differences: error O(eps²)·W''' plus round-off W·1e-16/eps
            assert!((fd - r[i]).abs() <= 1e-6 * scale, "seed {seed} dof {i}: analytic {} vs FD {fd}", r[i]);
        }
    }
}

#[test]
fn tangent_is_the_derivative_of_the_internal_force() {
    for seed in [4, 5] {
        let (rod, cfg) = random_rod_and_config(seed, 3);
        let n = rod.n_dof();
        let mut r = vec![0.0; n];
        let mut sys = rod.new_system().unwrap();
        rod.add_internal_force(&cfg, &mut r, Some(&mut sys));
        let scale =
            (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).fold(0.0f64, |m, (i, j)| m.max(sys.get(i, j).abs()));
        let eps = 1e-6;
        for j in 0..n {
            let mut rp = vec![0.0; n];
            let mut rm = vec![0.0; n];
            rod.add_internal_force(&perturbed(&rod, &cfg, j, eps), &mut rp, None);
            rod.add_internal_force(&perturbed(&rod, &cfg, j, -eps), &mut rm, None);
            for i in 0..n {
                let fd = (rp[i] - rm[i]) / (2.0 * eps);
                let k = sys.get(i, j);
                assert!((fd - k).abs() <= 1e-6 * scale, "seed {seed} K[{i},{j}] = {k} vs FD {fd}");
            }
        }
    }
}

#[test]
fn local_basis_tangent_at_a_twist_fixed_end_is_consistent() {
    let (mut rod, cfg) = random_rod_and_config(7, 2);
    rod.ends = [EndBc::PINNED, EndBc::PINNED_NO_TWIST];
    let n = rod.n_dof();
    let residual = |c: &RodConfig| {
        let mut r = vec![0.0; n];
        rod.add_internal_force(c, &mut r, None);
        rod.to_local_basis(c, &mut r, None);
        r
    };
    let mut r = vec![0.0; n];
    let mut sys = rod.new_system().unwrap();
    rod.add_internal_force(&cfg, &mut r, Some(&mut sys));
    rod.to_local_basis(&cfg, &mut r, Some(&mut sys));
    // the residual-only path (no strain operator formed) agrees with the
    // residual assembled with the tangent to round-off
    let r_only = residual(&cfg);
    let scale = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in r.iter().zip(&r_only) {
        assert!((a - b).abs() <= 1e-13 * scale, "{a} vs {b}");
    }
    let eps = 1e-6;
    let j0 = Rod::theta_dof(2 * rod.n_el);
    for j in j0 - 6..j0 + 3 {
        let rp = residual(&perturbed(&rod, &cfg, j, eps));
        let rm = residual(&perturbed(&rod, &cfg, j, -eps));
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * eps);
            assert!((fd - sys.get(i, j)).abs() < 1e-5 * (1.0 + fd.abs()), "K[{i},{j}] = {} vs FD {fd}", sys.get(i, j));
        }
    }
}

#[test]
fn strains_energy_and_forces_are_objective() {
    let (rod, cfg) = random_rod_and_config(9, 4);
    let q: Matrix3<f64> = cayley(&Vector3::new(0.4, -1.1, 2.0));
    let c = Vector3::new(3.0, -2.0, 7.5);
    let moved = cfg.rigidly_moved(&q, &c);
    let w0 = rod.strain_energy(&cfg);
    let w1 = rod.strain_energy(&moved);
    assert!((w0 - w1).abs() <= 1e-12 * w0, "energy {w0} vs {w1}");
    // the penalty strain γ (spatial) turns with Q; the curvatures K are invariant
    let g0 = Vector3::new(0.01, -0.02, 0.005);
    for e in 0..rod.n_el {
        for xi in [0.0, 0.3, 0.77, 1.0] {
            let a = riser::model::rod::element::strains_at(
                &riser::model::rod::element::ElemDofs::gather(&cfg, e),
                xi,
                rod.h,
                &g0,
            );
            let b = riser::model::rod::element::strains_at(
                &riser::model::rod::element::ElemDofs::gather(&moved, e),
                xi,
                rod.h,
                &g0,
            );
            let (ga, gb) = (Vector3::new(a[0], a[1], a[2]), Vector3::new(b[0], b[1], b[2]));
            assert!((q * ga - gb).norm() < 1e-13, "penalty strain: {ga} vs {gb}");
            for k in 3..6 {
                assert!((a[k] - b[k]).abs() < 1e-13, "strain {k}: {} vs {}", a[k], b[k]);
            }
        }
    }
    // every 3-component block of the reduced force (forces and moments) rotates with Q
    let n = rod.n_dof();
    let mut r0 = vec![0.0; n];
    let mut r1 = vec![0.0; n];
    rod.add_internal_force(&cfg, &mut r0, None);
    rod.add_internal_force(&moved, &mut r1, None);
    let scale = r0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for b in 0..n / 3 {
        let f0 = Vector3::new(r0[3 * b], r0[3 * b + 1], r0[3 * b + 2]);
        let f1 = Vector3::new(r1[3 * b], r1[3 * b + 1], r1[3 * b + 2]);
        assert!((q * f0 - f1).norm() <= 1e-12 * scale, "block {b}");
    }
    // and the resultant force and moment of the internal forces vanish (balance)
    let mut fsum = Vector3::zeros();
    let mut msum = Vector3::zeros();
    for a in 0..=rod.n_el {
        let i = Rod::x_dof(a);
        let f = Vector3::new(r0[i], r0[i + 1], r0[i + 2]);
        fsum += f;
        msum += cfg.x[a].cross(&f);
        let i = Rod::xp_dof(a);
        msum += cfg.xp[a].cross(&Vector3::new(r0[i], r0[i + 1], r0[i + 2]));
    }
    for j in 0..rod.n_director_nodes() {
        let i = Rod::theta_dof(j);
        msum += Vector3::new(r0[i], r0[i + 1], r0[i + 2]);
    }
    assert!(fsum.norm() <= 1e-12 * scale, "net force {fsum}");
    assert!(msum.norm() <= 1e-11 * scale, "net moment {msum}");
}
