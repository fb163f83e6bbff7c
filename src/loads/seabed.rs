//! Seabed contact (docs/theory.md §9): a plane n·x = ζ_b, a distributed
//! elastic–damped foundation against penetration and regularised Coulomb
//! friction, per unit reference length of line, in MoorDyn's convention
//! (kBot, cBot: a force per unit contact area, D the line's outer diameter):
//!
//!   penetration      δ = ζ_b − n·x                                   (9.1)
//!   elastic          V(ζ) = ½ k D δ₊²,   f_e = −∂V/∂x = k D δ₊ n     (9.2)
//!   damping          f_d = −c D min(1, δ₊/δ_d) (n·v) n                  (9.3)
//!   friction         f_f = −N (μ_a v_a a + μ_l v_l b)/√(v_a² + v_l² + v_ε²),
//!                    N = k D δ₊, v_a = a·v, v_l = b·v                  (9.4)
//!
//! with a the line's tangent projected on the plane (axial), b = n × a
//! (lateral). In a step of the midpoint scheme, at each Gauss point with
//! ζ₀ = n·x_n and ζ₁ = n·x_{n+1}:
//! - the elastic force is the discrete gradient −n (V(ζ₁) − V(ζ₀))/(ζ₁ − ζ₀)
//!   (V′ at the midpoint when ζ₁ = ζ₀), so its work over the step is exactly
//!   −ΔV: the seabed's elastic energy is conserved with the line's;     (9.5)
//! - damping and friction act with the step's mean velocity v = Δx/h, N and
//!   δ at the midpoint, and a from the line at t_n (lagged, so that the
//!   step's tangent does not depend on the slope); their work
//!   Δx·f = h v·f = −h c D (n·v)² or −h N (μ_a v_a² + μ_l v_l²)/√(…) is
//!   never positive whatever the iterate: they only dissipate.          (9.6)
//!
//! The regularisation v_ε (`slip_velocity`) replaces the Coulomb jump by a
//! smooth law: at a slip speed v the friction is μN v/√(v² + v_ε²), short of
//! μN by about v_ε²/(2v²) (0.5 % at 10 v_ε), and a line loaded below μN
//! creeps at about v_ε F/(μN) instead of sticking.
//!
//! In statics only the elastic part acts (the frictionless state: see
//! docs/theory.md §9.3).

use crate::math::shape::GAUSS4;
use crate::math::{M3, V3};

/// The penetration over which the seabed's damping is phased in, m: MoorDyn
/// switches it on at contact, a jump in the step equations that cost the
/// steel catenary (rod) 46 split steps in 2000 and 1.5 times the run time;
/// a ramp over 3 mm (a few times the default seabed's static penetration of
/// a steel riser, 1.2 mm) makes the force continuous. (Over 1 mm the ramp's
/// term cD (n·v)/(2δ_d) in the tangent reached 1e7 N/m, and finite
/// differences of the residual could no longer check it to 1e-6.)
pub const DAMPING_ONSET: f64 = 3e-3;

/// A seabed plane and its contact law.
#[derive(Debug, Clone, PartialEq)]
pub struct Seabed {
    /// Unit normal of the plane, out of the seabed (up).
    pub normal: V3,
    /// ζ_b: the plane is n·x = ζ_b, m.
    pub level: f64,
    /// k D: elastic force per unit length per metre of penetration, N/m².
    pub stiffness: f64,
    /// c D: damping force per unit length per m/s of penetration rate, N s/m².
    pub damping: f64,
    /// Friction coefficients [axial, lateral].
    pub friction: [f64; 2],
    /// Regularisation velocity v_ε of the friction, m/s.
    pub slip_velocity: f64,
}

impl Seabed {
    /// A seabed at height `z` (m) below x = 0, rising by `slope_deg` towards
    /// +x, with MoorDyn's kBot `stiffness` (Pa/m) and cBot `damping`
    /// (Pa s/m) on a line of outer diameter `diameter` (m).
    pub fn new(
        z: f64,
        slope_deg: f64,
        stiffness: f64,
        damping: f64,
        friction: [f64; 2],
        slip_velocity: f64,
        diameter: f64,
    ) -> Self {
        let a = slope_deg.to_radians();
        let normal = V3::new(-a.sin(), 0.0, a.cos());
        Seabed {
            normal,
            level: normal.dot(&V3::new(0.0, 0.0, z)),
            stiffness: stiffness * diameter,
            damping: damping * diameter,
            friction,
            slip_velocity,
        }
    }

    /// Height of the seabed under horizontal position (x, y), m.
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        (self.level - self.normal.x * x - self.normal.y * y) / self.normal.z
    }

    /// Penetration δ = ζ_b − n·x of a point (> 0 below the plane), m (9.1).
    pub fn penetration(&self, x: &V3) -> f64 {
        self.level - self.normal.dot(x)
    }

    /// Elastic energy per unit length V (9.2), J/m, at ζ = n·x.
    pub fn potential(&self, zeta: f64) -> f64 {
        let d = (self.level - zeta).max(0.0);
        0.5 * self.stiffness * d * d
    }

    /// V′(ζ) = −k D δ₊ and V″(ζ) (the static slope), N/m and N/m².
    pub fn static_slope(&self, zeta: f64) -> (f64, f64) {
        let d = self.level - zeta;
        if d > 0.0 { (-self.stiffness * d, self.stiffness) } else { (0.0, 0.0) }
    }

    /// The discrete gradient G = (V(ζ₁) − V(ζ₀))/(ζ₁ − ζ₀) and ∂G/∂ζ₁ (9.5),
    /// written without the quotient where both points are on the same side
    /// of the plane (V is quadratic there: G = V′ at the midpoint).
    pub fn discrete_slope(&self, zeta0: f64, zeta1: f64) -> (f64, f64) {
        let k = self.stiffness;
        let (d0, d1) = (self.level - zeta0, self.level - zeta1);
        if d0 >= 0.0 && d1 >= 0.0 {
            (-0.5 * k * (d0 + d1), 0.5 * k)
        } else if d0 <= 0.0 && d1 <= 0.0 {
            (0.0, 0.0)
        } else {
            // one point in contact: |ζ₁ − ζ₀| is at least its penetration
            let g = (self.potential(zeta1) - self.potential(zeta0)) / (zeta1 - zeta0);
            let (v1, _) = self.static_slope(zeta1);
            (g, (v1 - g) / (zeta1 - zeta0))
        }
    }

    /// The frame of the friction at a point with line tangent `t`: the
    /// axial direction a (t projected on the plane) and lateral b = n × a.
    pub fn friction_frame(&self, t: &V3) -> (V3, V3) {
        let n = self.normal;
        let mut a = t - n * n.dot(t);
        if a.norm() <= 1e-9 * t.norm().max(f64::MIN_POSITIVE) {
            // a line normal to the plane: any in-plane direction
            a = V3::y().cross(&n);
        }
        let a = a.normalize();
        (a, n.cross(&a))
    }

    /// Round-off of the seabed's nodal force on an element of `len` m at
    /// coordinates as large as `extent` m, N: the penetration ζ_b − n·x
    /// carries ε·extent.
    pub fn roundoff(&self, len: f64, extent: f64) -> f64 {
        self.stiffness * len * f64::EPSILON * extent
    }

    /// True if the seabed acts only elastically (no damping, no friction).
    pub fn is_conservative(&self) -> bool {
        self.damping == 0.0 && self.friction == [0.0, 0.0]
    }
}

/// The seabed's force per unit length at one point over a step, split into
/// its elastic (conservative) and dissipative parts, N/m, with their
/// derivatives with respect to the point's end-of-step position x₁, N/m².
#[derive(Debug, Clone, Copy)]
pub struct PointForce {
    pub elastic: V3,
    pub dissipative: V3,
    pub d_elastic: M3,
    pub d_dissipative: M3,
}

/// The seabed's force per unit length at a point moving from `x0` to `x1`
/// over a step of `h` s (9.5, 9.6), `t0` the line's tangent at t_n.
pub fn step_point_force(bed: &Seabed, x0: &V3, x1: &V3, t0: &V3, h: f64) -> PointForce {
    let n = bed.normal;
    let nn = n * n.transpose();
    let (z0, z1) = (n.dot(x0), n.dot(x1));
    let (g, dg) = bed.discrete_slope(z0, z1);
    let mut out =
        PointForce { elastic: -n * g, dissipative: V3::zeros(), d_elastic: -nn * dg, d_dissipative: M3::zeros() };
    let depth = bed.level - 0.5 * (z0 + z1);
    if depth <= 0.0 || bed.is_conservative() {
        return out;
    }
    let v = (x1 - x0) / h;
    // damping (9.3) at the mean velocity, phased in over the first
    // DAMPING_ONSET of penetration (continuous, so that Newton converges)
    if bed.damping > 0.0 {
        let (on, d_on) = if depth >= DAMPING_ONSET { (1.0, 0.0) } else { (depth / DAMPING_ONSET, 1.0 / DAMPING_ONSET) };
        let vn = n.dot(&v);
        out.dissipative -= n * (bed.damping * on * vn);
        // ∂(on)/∂x₁ = −(d_on/2) nᵀ
        out.d_dissipative -= nn * (bed.damping * (on / h - 0.5 * d_on * vn));
    }
    // friction (9.4): N and δ at the midpoint, the frame of t_n
    let [mu_a, mu_l] = bed.friction;
    if mu_a > 0.0 || mu_l > 0.0 {
        let normal_force = bed.stiffness * depth;
        let (a, b) = bed.friction_frame(t0);
        let (va, vl) = (a.dot(&v), b.dot(&v));
        let phi = (va * va + vl * vl + bed.slip_velocity * bed.slip_velocity).sqrt();
        let u = a * (mu_a * va) + b * (mu_l * vl);
        let f = -u * (normal_force / phi);
        out.dissipative += f;
        // ∂f/∂v = −N [ (μ_a a aᵀ + μ_l b bᵀ)/φ − u v_tᵀ/φ³ ],  ∂v/∂x₁ = I/h
        let vt = a * va + b * vl;
        let dfdv = -(a * a.transpose() * mu_a + b * b.transpose() * mu_l) * (normal_force / phi)
            + u * vt.transpose() * (normal_force / (phi * phi * phi));
        // ∂N/∂x₁ = −k D nᵀ/2
        let dn = n.transpose() * (-0.5 * bed.stiffness);
        out.d_dissipative += dfdv / h - u * dn / phi;
    }
    out
}

/// Adds the consistent nodal seabed forces of one element over a step to
/// `fe` (elastic) and `fd` (damping and friction), N, and −∂F/∂c₁ to `k`
/// (the contribution to the tangent of a residual r = … − F). The element's
/// fields are x = Σ N_j c_j with `shapes` (N, N′) at the four Gauss points;
/// `c0`, `c1` the dofs at t_n and at the trial t_{n+1}, `len` the element's
/// reference length (m), `h` the time step (s), `fac` ∂x₁/∂c₁ (1).
#[allow(clippy::too_many_arguments)]
pub fn element_step_force<const K: usize>(
    bed: &Seabed,
    c0: &[V3; K],
    c1: &[V3; K],
    shapes: &[([f64; K], [f64; K]); 4],
    len: f64,
    h: f64,
    fe: &mut [V3; K],
    fd: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    for g in 0..4 {
        let (n, nd) = &shapes[g];
        let (mut x0, mut x1, mut t0) = (V3::zeros(), V3::zeros(), V3::zeros());
        for j in 0..K {
            x0 += c0[j] * n[j];
            x1 += c1[j] * n[j];
            t0 += c0[j] * nd[j];
        }
        if bed.penetration(&x0) <= 0.0 && bed.penetration(&x1) <= 0.0 {
            continue;
        }
        let p = step_point_force(bed, &x0, &x1, &t0, h);
        let wg = GAUSS4.w[g] * len;
        for i in 0..K {
            fe[i] += p.elastic * (wg * n[i]);
            fd[i] += p.dissipative * (wg * n[i]);
        }
        if let Some(k) = k.as_deref_mut() {
            let d = p.d_elastic + p.d_dissipative;
            for i in 0..K {
                for j in 0..K {
                    k[i][j] -= d * (wg * n[i] * n[j]);
                }
            }
        }
    }
}

/// Adds the static (elastic) seabed force of one element at dofs `c` to `f`,
/// N, and −∂F/∂c to `k`.
pub fn element_static_force<const K: usize>(
    bed: &Seabed,
    c: &[V3; K],
    shapes: &[([f64; K], [f64; K]); 4],
    len: f64,
    f: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    let n_hat = bed.normal;
    for g in 0..4 {
        let (n, _) = &shapes[g];
        let mut x = V3::zeros();
        for j in 0..K {
            x += c[j] * n[j];
        }
        let (v1, v2) = bed.static_slope(n_hat.dot(&x));
        if v2 == 0.0 {
            continue;
        }
        let wg = GAUSS4.w[g] * len;
        for i in 0..K {
            f[i] -= n_hat * (v1 * wg * n[i]);
        }
        if let Some(k) = k.as_deref_mut() {
            let d = n_hat * n_hat.transpose() * v2;
            for i in 0..K {
                for j in 0..K {
                    k[i][j] += d * (wg * n[i] * n[j]);
                }
            }
        }
    }
}

/// The seabed's elastic energy of one element at dofs `c`, ∫ V dS (the same
/// quadrature as the forces), J.
pub fn element_energy<const K: usize>(bed: &Seabed, c: &[V3; K], shapes: &[([f64; K], [f64; K]); 4], len: f64) -> f64 {
    let mut e = 0.0;
    for g in 0..4 {
        let (n, _) = &shapes[g];
        let mut x = V3::zeros();
        for j in 0..K {
            x += c[j] * n[j];
        }
        e += GAUSS4.w[g] * len * bed.potential(bed.normal.dot(&x));
    }
    e
}

/// The seabed's force per unit length at a point at `x` moving with `v`,
/// `t` the line's tangent there ((9.2–9.4) at one instant), N/m.
pub fn state_point_force(bed: &Seabed, x: &V3, v: &V3, t: &V3) -> V3 {
    let n = bed.normal;
    let depth = bed.penetration(x);
    if depth <= 0.0 {
        return V3::zeros();
    }
    let normal_force = bed.stiffness * depth;
    let on = (depth / DAMPING_ONSET).min(1.0);
    let mut f = n * (normal_force - bed.damping * on * n.dot(v));
    let [mu_a, mu_l] = bed.friction;
    if mu_a > 0.0 || mu_l > 0.0 {
        let (a, b) = bed.friction_frame(t);
        let (va, vl) = (a.dot(v), b.dot(v));
        let phi = (va * va + vl * vl + bed.slip_velocity * bed.slip_velocity).sqrt();
        f -= (a * (mu_a * va) + b * (mu_l * vl)) * (normal_force / phi);
    }
    f
}

/// Adds the consistent nodal seabed force of one element at an instant
/// (dofs `c`, their rates `v`) to `f`, N.
pub fn element_state_force<const K: usize>(
    bed: &Seabed,
    c: &[V3; K],
    v: &[V3; K],
    shapes: &[([f64; K], [f64; K]); 4],
    len: f64,
    f: &mut [V3; K],
) {
    for g in 0..4 {
        let (n, nd) = &shapes[g];
        let (mut x, mut xv, mut t) = (V3::zeros(), V3::zeros(), V3::zeros());
        for j in 0..K {
            x += c[j] * n[j];
            xv += v[j] * n[j];
            t += c[j] * nd[j];
        }
        let p = state_point_force(bed, &x, &xv, &t);
        let wg = GAUSS4.w[g] * len;
        for i in 0..K {
            f[i] += p * (wg * n[i]);
        }
    }
}

/// Arc length of the first contact from the hang-off, m: the first node
/// below the plane, the crossing interpolated linearly in the penetration
/// from the node before it; `length` when no node touches. `nodes` are
/// the centreline's nodes at arc lengths `s[a]`.
pub fn touchdown(bed: &Seabed, nodes: &[V3], s: impl Fn(usize) -> f64, length: f64) -> f64 {
    let mut before = f64::NEG_INFINITY;
    for (a, x) in nodes.iter().enumerate() {
        let d = bed.penetration(x);
        if d > 0.0 {
            if a == 0 {
                return 0.0;
            }
            let w = -before / (d - before);
            return s(a - 1) + w * (s(a) - s(a - 1));
        }
        before = d;
    }
    length
}

/// True if no point of an element whose nodes are at `nodes` can touch the
/// seabed: every node more than `margin` m above the plane (the element's
/// centreline stays within `margin` of its nodes' plane heights).
pub fn clear_of(bed: &Seabed, nodes: &[V3], margin: f64) -> bool {
    nodes.iter().all(|x| bed.penetration(x) < -margin)
}

/// Shape values (N, N′) of a straight two-node segment of length `l` at the
/// four Gauss points.
pub fn linear_at_gauss(l: f64) -> [([f64; 2], [f64; 2]); 4] {
    GAUSS4.xi.map(|xi| ([1.0 - xi, xi], [-1.0 / l, 1.0 / l]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bed(slope: f64, c: f64, mu: [f64; 2]) -> Seabed {
        Seabed::new(-10.0, slope, 3e6, c, mu, 0.01, 0.3)
    }

    #[test]
    fn the_discrete_gradient_gives_the_energy_difference() {
        let b = bed(0.0, 0.0, [0.0; 2]);
        // in contact, out of contact and crossing, either way
        for (z0, z1) in [(-10.02, -10.01), (-9.0, -9.5), (-9.99, -10.03), (-10.03, -9.99), (-10.01, -10.01)] {
            let (g, _) = b.discrete_slope(z0, z1);
            if z1 != z0 {
                let de = b.potential(z1) - b.potential(z0);
                assert!((g * (z1 - z0) - de).abs() <= 1e-12 * de.abs().max(1.0), "{z0} {z1}");
            } else {
                assert_eq!(g, b.static_slope(z0).0);
            }
        }
    }

    #[test]
    fn the_point_force_derivative_matches_finite_differences() {
        // elastic (crossing and in contact), damping, friction (anisotropic), sloped
        for (slope, c, mu) in [(0.0, 0.0, [0.0, 0.0]), (5.0, 3e5, [0.0, 0.0]), (-3.0, 3e5, [0.4, 0.9])] {
            let b = bed(slope, c, mu);
            let x0 = V3::new(2.0, 0.5, b.height_at(2.0, 0.5) + 0.004);
            let t0 = V3::new(0.9, 0.3, 0.05);
            let h = 0.05;
            // midpoint 6 mm deep (full damping), 0.25 mm (in the damping's
            // onset), 1 mm above (elastic only, crossing)
            let steps =
                [V3::new(0.003, -0.002, -0.02), V3::new(0.002, 0.001, -0.0085), V3::new(-0.0004, 0.0007, -0.006)];
            for x1 in steps.map(|d| x0 + d) {
                let p = step_point_force(&b, &x0, &x1, &t0, h);
                let d = p.d_elastic + p.d_dissipative;
                for j in 0..3 {
                    let e = 1e-7;
                    let mut xp = x1;
                    xp[j] += e;
                    let mut xm = x1;
                    xm[j] -= e;
                    let (fp, fm) = (step_point_force(&b, &x0, &xp, &t0, h), step_point_force(&b, &x0, &xm, &t0, h));
                    let fd = ((fp.elastic + fp.dissipative) - (fm.elastic + fm.dissipative)) / (2.0 * e);
                    let scale = d.norm().max(1.0);
                    assert!(
                        (fd - d.column(j)).norm() <= 1e-6 * scale,
                        "slope {slope} col {j}: {fd} vs {}",
                        d.column(j)
                    );
                }
            }
        }
    }

    #[test]
    fn damping_and_friction_never_do_positive_work() {
        let b = bed(4.0, 3e5, [0.5, 1.0]);
        let t0 = V3::new(1.0, 0.2, 0.1);
        let x0 = V3::new(0.0, 0.0, b.height_at(0.0, 0.0) - 0.01);
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for _ in 0..1000 {
            let dx = V3::new(rnd(), rnd(), rnd()) * 0.05;
            let p = step_point_force(&b, &x0, &(x0 + dx), &t0, 0.05);
            assert!(p.dissipative.dot(&dx) <= 0.0);
        }
    }

    #[test]
    fn friction_saturates_at_coulomb() {
        let b = bed(0.0, 0.0, [0.5, 1.0]);
        let x0 = V3::new(0.0, 0.0, -10.01);
        let n = b.stiffness * 0.01;
        // sliding axially at 1 m/s (100 v_ε): μ_a N within v_ε²/(2v²)
        let p = step_point_force(&b, &x0, &(x0 + V3::new(0.05, 0.0, 0.0)), &V3::x(), 0.05);
        assert!((p.dissipative.x + 0.5 * n).abs() <= 0.5 * n * 0.6e-4, "{}", p.dissipative.x);
        let p = step_point_force(&b, &x0, &(x0 + V3::new(0.0, 0.05, 0.0)), &V3::x(), 0.05);
        assert!((p.dissipative.y + n).abs() <= n * 0.6e-4, "{}", p.dissipative.y);
    }
}
