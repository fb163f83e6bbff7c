//! The flex joint at the hang-off (docs/theory.md §15): a rotational spring
//! between the vessel's frame F = R(t) D_static (f1, f2, f3 its columns) and
//! the line's end directors d1, d2, d3 at director node 0.
//!
//! Bending: the angle φ between the vessel's axis f3 and the line's d3, with
//! the invariant s = ½|d3 − f3|² = 1 − cos φ, which is quadratic in the
//! directors; the energy V(φ) = ∫₀^φ M is Ψ(s) = V(φ(s)), φ = 2 asin(√(s/2))
//! (15.2). Torsion: τ = ½(f2·d1 − f1·d2) = cos²(φ/2) sin α for a twist α
//! after the bend (zero for a pure bend), with ½ k_t τ² (15.3).
//!
//! Both invariants are quadratic in (d, f), so their increments over a step
//! are exactly their midpoint gradients times the increments; the step's
//! discrete gradient is the difference quotient of Ψ in s and k_t τ̄ for the
//! torsion (15.4), which makes its work exactly the change of V.

use crate::math::{M3, V3, skew};

/// Moment against angle of the joint's bending, piecewise linear from
/// (0, 0): a linear spring is one segment; a table's last slope continues
/// past its last angle.
#[derive(Debug, Clone, PartialEq)]
pub struct JointLaw {
    /// Start angle φ_i of each segment, rad (the first is 0).
    angle: Vec<f64>,
    /// M(φ_i), N m.
    moment: Vec<f64>,
    /// dM/dφ on segment i, N m/rad.
    slope: Vec<f64>,
    /// V(φ_i) = ∫₀^φ_i M, J.
    energy: Vec<f64>,
}

impl JointLaw {
    /// M = k φ.
    pub fn linear(k: f64) -> Self {
        JointLaw { angle: vec![0.0], moment: vec![0.0], slope: vec![k], energy: vec![0.0] }
    }

    /// Rows (φ rad, M N m) from (0, 0), angles increasing, moments
    /// non-decreasing (checked by the scene, `crate::scene::check_joint_table`).
    pub fn table(rows: &[[f64; 2]]) -> Self {
        assert!(rows.len() >= 2 && rows[0] == [0.0, 0.0], "a flex-joint table starts at (0, 0)");
        let mut law = JointLaw { angle: vec![], moment: vec![], slope: vec![], energy: vec![] };
        let mut v = 0.0;
        for w in rows.windows(2) {
            let ([a0, m0], [a1, m1]) = (w[0], w[1]);
            law.angle.push(a0);
            law.moment.push(m0);
            law.slope.push((m1 - m0) / (a1 - a0));
            law.energy.push(v);
            v += 0.5 * (m0 + m1) * (a1 - a0);
        }
        law
    }

    /// The stiffness at φ = 0, N m/rad.
    pub fn initial_stiffness(&self) -> f64 {
        self.slope[0]
    }

    fn segment(&self, phi: f64) -> usize {
        self.angle.partition_point(|&a| a <= phi).saturating_sub(1)
    }

    /// M(φ), N m.
    pub fn moment(&self, phi: f64) -> f64 {
        let i = self.segment(phi);
        self.moment[i] + self.slope[i] * (phi - self.angle[i])
    }

    /// V(φ), J.
    pub fn energy(&self, phi: f64) -> f64 {
        let i = self.segment(phi);
        let x = phi - self.angle[i];
        self.energy[i] + x * (self.moment[i] + 0.5 * self.slope[i] * x)
    }

    /// (V(b) − V(a))/(b − a) for a ≤ b, summed segment by segment (each
    /// piece the mean of M over it, exact), M(a) when a = b.
    fn mean_moment(&self, a: f64, b: f64) -> f64 {
        let (ia, ib) = (self.segment(a), self.segment(b));
        if ia == ib {
            return self.moment[ia] + self.slope[ia] * (0.5 * (a + b) - self.angle[ia]);
        }
        let mut sum = 0.0;
        let mut lo = a;
        for i in ia..=ib {
            let hi = if i == ib { b } else { self.angle[i + 1] };
            sum += (self.moment[i] + self.slope[i] * (0.5 * (lo + hi) - self.angle[i])) * (hi - lo);
            lo = hi;
        }
        sum / (b - a)
    }

    /// Ψ'(s) = M(φ)/sin φ (its limit k₀ at φ = 0).
    pub fn psi1(&self, phi: f64) -> f64 {
        let i = self.segment(phi);
        // M = k φ + c on the segment; c = 0 on the first
        let c = self.moment[i] - self.slope[i] * self.angle[i];
        self.slope[i] * over_sin(phi) + if c == 0.0 { 0.0 } else { c / phi.sin() }
    }

    /// Ψ''(s) = (M′ sin φ − M cos φ)/sin³ φ (its limit k₀/3 at φ = 0).
    pub fn psi2(&self, phi: f64) -> f64 {
        let i = self.segment(phi);
        let c = self.moment[i] - self.slope[i] * self.angle[i];
        // (sin φ − φ cos φ)/sin³ φ, by its series where it cancels
        let g = if phi < 1e-2 {
            let p2 = phi * phi;
            let sinc = 1.0 - p2 / 6.0 + p2 * p2 / 120.0;
            (1.0 / 3.0 - p2 / 30.0 + p2 * p2 / 840.0) / (sinc * sinc * sinc)
        } else {
            let s = phi.sin();
            (s - phi * phi.cos()) / (s * s * s)
        };
        self.slope[i] * g - if c == 0.0 { 0.0 } else { c * phi.cos() / phi.sin().powi(3) }
    }

    /// The difference quotient Q = (Ψ(s₁) − Ψ(s₀))/(s₁ − s₀) of a step from
    /// φ₀ to φ₁ (s = 1 − cos φ), and ∂Q/∂s₁. Written without cancellation:
    /// s₁ − s₀ = 2 sin φ̄ sin x (φ̄ the mean angle, x = ½(φ₁ − φ₀)), so
    /// Q = M̄ / sin φ̄ · x / sin x with M̄ the mean moment over [φ₀, φ₁];
    /// Ψ'(s) at φ₀ = φ₁.
    pub fn quotient(&self, phi0: f64, phi1: f64) -> (f64, f64) {
        let (a, b) = if phi0 <= phi1 { (phi0, phi1) } else { (phi1, phi0) };
        let mean = 0.5 * (a + b);
        let x = 0.5 * (b - a);
        let (ia, ib) = (self.segment(a), self.segment(b));
        // M̄ / sin φ̄: on the first segment M̄ = k₀ φ̄
        let m_over_sin =
            if ia == 0 && ib == 0 { self.slope[0] * over_sin(mean) } else { self.mean_moment(a, b) / mean.sin() };
        let q = m_over_sin * over_sin(x);
        let ds = phi0.cos() - phi1.cos();
        let dq = if ds.abs() > 1e-7 {
            // the quotient's own derivative
            (self.psi1(phi1) - q) / (2.0 * mean.sin() * (phi1 - phi0).signum() * x.sin())
        } else {
            0.5 * self.psi2(mean)
        };
        (q, dq)
    }
}

/// φ / sin φ (1 at φ = 0).
fn over_sin(phi: f64) -> f64 {
    if phi.abs() < 1e-4 { 1.0 + phi * phi / 6.0 } else { phi / phi.sin() }
}

/// The flex joint: its bending law, its torsional stiffness and the vessel
/// frame at the static state.
#[derive(Debug, Clone, PartialEq)]
pub struct FlexJoint {
    pub law: JointLaw,
    /// k_t, N m (per unit of τ, ≈ rad for small twists).
    pub torsion: f64,
    /// D_static: the line's end frame in the static state, which is the
    /// vessel's frame at R = I (None until the static state is known).
    pub frame: Option<M3>,
}

/// The joint's moment on the line's end director node over a step, its
/// derivative and the work the vessel did on the joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointStep {
    /// The reduced moment row m (added to the residual), N m.
    pub moment: V3,
    /// ∂m/∂w, w the spatial rotation increment of d_{n+1}, N m.
    pub tangent: M3,
    /// The work of the vessel's frame's turn on the joint, J: ΔV − θ·m.
    pub vessel_work: f64,
}

fn col(m: &M3, i: usize) -> V3 {
    m.column(i).into()
}

impl FlexJoint {
    /// The bending angle between d3 and f3, rad: 2 asin(|d3 − f3|/2).
    pub fn angle(d: &M3, f: &M3) -> f64 {
        2.0 * (0.5 * (col(d, 2) - col(f, 2)).norm()).min(1.0).asin()
    }

    /// τ = ½(f2·d1 − f1·d2).
    fn twist(d: &M3, f: &M3) -> f64 {
        0.5 * (col(f, 1).dot(&col(d, 0)) - col(f, 0).dot(&col(d, 1)))
    }

    /// The joint's energy with the line's end frame d and the vessel's f, J.
    pub fn energy(&self, d: &M3, f: &M3) -> f64 {
        let tau = Self::twist(d, f);
        self.law.energy(Self::angle(d, f)) + 0.5 * self.torsion * tau * tau
    }

    /// The joint's moment on the vessel at frames d, f (= the reduced
    /// moment row on the line, ∂V/∂θ), N m, and its derivative along a
    /// spatial rotation w of d:
    ///   m = Ψ'(s) f3 × d3 + k_t τ b,  b = ½(d1 × f2 − d2 × f1),
    ///   ∂m/∂w = Ψ'' a aᵀ − Ψ' \[f3\]×\[d3\]× + k_t (b bᵀ + ½ τ (\[f2\]×\[d1\]× − \[f1\]×\[d2\]×)),  a = f3 × d3.
    pub fn static_moment(&self, d: &M3, f: &M3) -> (V3, M3) {
        let phi = Self::angle(d, f);
        let (d1, d2, d3) = (col(d, 0), col(d, 1), col(d, 2));
        let (f1, f2, f3) = (col(f, 0), col(f, 1), col(f, 2));
        let a = f3.cross(&d3);
        let b = (d1.cross(&f2) - d2.cross(&f1)) * 0.5;
        let tau = Self::twist(d, f);
        let (p1, p2) = (self.law.psi1(phi), self.law.psi2(phi));
        let m = a * p1 + b * (self.torsion * tau);
        let k = a * a.transpose() * p2 - skew(&f3) * skew(&d3) * p1
            + (b * b.transpose() + (skew(&f2) * skew(&d1) - skew(&f1) * skew(&d2)) * (0.5 * tau)) * self.torsion;
        (m, k)
    }

    /// The discrete gradient over a step (15.4): d0, d1 the line's end frame
    /// at t_n, t_{n+1}; f0, f1 the vessel's.
    ///   m = Q f3½ × d3½ + k_t τ̄ c,  c = ½(d1½ × f2½ − d2½ × f1½),
    /// Q the difference quotient of Ψ, τ̄ = ½(τ_n + τ_{n+1}); so that
    /// θ·m + W_vessel = ΔV exactly, with the vessel's work
    ///   W_vessel = −Q (d3½ − f3½)·Δf3 + ½ k_t τ̄ (d1½·Δf2 − d2½·Δf1).
    pub fn step(&self, d0: &M3, d1: &M3, f0: &M3, f1: &M3) -> JointStep {
        let (dm, fm) = ((d0 + d1) * 0.5, (f0 + f1) * 0.5);
        let (df, (p0, p1)) = (f1 - f0, (Self::angle(d0, f0), Self::angle(d1, f1)));
        let (q, dq) = self.law.quotient(p0, p1);
        let (m1, m2, m3) = (col(&dm, 0), col(&dm, 1), col(&dm, 2));
        let (g1, g2, g3) = (col(&fm, 0), col(&fm, 1), col(&fm, 2));
        let (n1, n2, n3) = (col(d1, 0), col(d1, 1), col(d1, 2));
        let (h1, h2, h3) = (col(f1, 0), col(f1, 1), col(f1, 2));
        let tau = 0.5 * (Self::twist(d0, f0) + Self::twist(d1, f1));
        let bend = g3.cross(&m3);
        let c = (m1.cross(&g2) - m2.cross(&g1)) * 0.5;
        let moment = bend * q + c * (self.torsion * tau);
        // ∂s₁/∂w = f3 × d3 at t_{n+1}; ∂τ_{n+1}/∂w = ½(d1 × f2 − d2 × f1) there
        let a1 = h3.cross(&n3);
        let b1 = (n1.cross(&h2) - n2.cross(&h1)) * 0.5;
        let tangent = bend * a1.transpose() * dq - skew(&g3) * skew(&n3) * (0.5 * q)
            + (c * b1.transpose() * 0.5 + (skew(&g2) * skew(&n1) - skew(&g1) * skew(&n2)) * (0.25 * tau))
                * self.torsion;
        let vessel_work =
            -q * (m3 - g3).dot(&col(&df, 2)) + 0.5 * self.torsion * tau * (m1.dot(&col(&df, 1)) - m2.dot(&col(&df, 0)));
        JointStep { moment, tangent, vessel_work }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::cayley;

    fn laws() -> Vec<JointLaw> {
        vec![JointLaw::linear(2.5e5), JointLaw::table(&[[0.0, 0.0], [0.02, 1.2e4], [0.1, 3.0e4], [0.3, 5.0e4]])]
    }

    /// Ψ' and Ψ'' against central differences of Ψ(s) = V(φ(s)) in s, on
    /// every segment and past the table's end.
    #[test]
    fn psi_derivatives_match_finite_differences() {
        let phi_of = |s: f64| 2.0 * (0.5 * s).sqrt().asin();
        for law in laws() {
            for phi in [1e-3, 0.015, 0.05, 0.2, 0.6] {
                let s = 1.0 - f64::cos(phi);
                let e = 1e-4 * s;
                let v = |s: f64| law.energy(phi_of(s));
                let d1 = (v(s + e) - v(s - e)) / (2.0 * e);
                let e2 = 1e-3 * s;
                let d2 = (law.psi1(phi_of(s + e2)) - law.psi1(phi_of(s - e2))) / (2.0 * e2);
                assert!((d1 - law.psi1(phi)).abs() < 1e-7 * d1.abs(), "{phi}: {d1} vs {}", law.psi1(phi));
                assert!((d2 - law.psi2(phi)).abs() < 1e-5 * d2.abs(), "{phi}: {d2} vs {}", law.psi2(phi));
            }
            // the limits at φ = 0
            assert!((law.psi1(0.0) - law.initial_stiffness()).abs() < 1e-12 * law.initial_stiffness());
            assert!((law.psi2(0.0) - law.initial_stiffness() / 3.0).abs() < 1e-12 * law.initial_stiffness());
        }
    }

    /// Q (s₁ − s₀) = Ψ(s₁) − Ψ(s₀) across segments, and ∂Q/∂s₁ against
    /// central differences.
    #[test]
    fn the_quotient_is_the_exact_difference_and_its_derivative_is_right() {
        for law in laws() {
            for (p0, p1) in [(0.01, 0.012), (0.05, 0.015), (0.2, 0.25), (0.0, 0.04), (0.15, 0.15 + 1e-9)] {
                let (q, dq) = law.quotient(p0, p1);
                let ds = 2.0 * f64::sin(0.5 * (p0 + p1)) * f64::sin(0.5 * (p1 - p0));
                let dv = law.energy(p1) - law.energy(p0);
                assert!((q * ds - dv).abs() <= 1e-13 * law.energy(p0.max(p1)), "{p0} {p1}: {} vs {dv}", q * ds);
                let s1 = 1.0 - f64::cos(p1);
                let e = 1e-7 * s1;
                let phi = |s: f64| 2.0 * (0.5 * s).sqrt().asin();
                let fd = (law.quotient(p0, phi(s1 + e)).0 - law.quotient(p0, phi(s1 - e)).0) / (2.0 * e);
                assert!((fd - dq).abs() < 1e-4 * dq.abs(), "{p0} {p1}: dQ {dq} vs {fd}");
            }
        }
    }

    fn frames() -> (M3, M3, M3, M3) {
        let base = cayley(&V3::new(0.3, -0.5, 0.2));
        let f0 = base;
        let f1 = cayley(&V3::new(0.01, 0.03, -0.02)) * f0;
        let d0 = cayley(&V3::new(0.04, -0.02, 0.01)) * f0;
        let d1 = cayley(&V3::new(0.02, 0.03, -0.015)) * d0;
        (d0, d1, f0, f1)
    }

    /// θ·m + W_vessel = V₁ − V₀ over a step, and the tangents (static and
    /// step) against central differences along spatial rotations of d.
    #[test]
    fn the_step_closes_the_energy_and_the_tangents_match_finite_differences() {
        let (d0, d1, f0, f1) = frames();
        for law in laws() {
            let joint = FlexJoint { law, torsion: 3.0e5, frame: None };
            let st = joint.step(&d0, &d1, &f0, &f1);
            let q = d1 * d0.transpose();
            let theta = V3::new(q[(2, 1)] - q[(1, 2)], q[(0, 2)] - q[(2, 0)], q[(1, 0)] - q[(0, 1)])
                * (2.0 / (1.0 + q.trace()));
            let dv = joint.energy(&d1, &f1) - joint.energy(&d0, &f0);
            let balance = theta.dot(&st.moment) + st.vessel_work - dv;
            assert!(balance.abs() < 1e-12 * joint.energy(&d1, &f1), "balance {balance} of {dv}");
            let e = 1e-6;
            let (_, ks) = joint.static_moment(&d1, &f1);
            for j in 0..3 {
                let w = V3::from_fn(|i, _| if i == j { e } else { 0.0 });
                let (plus, minus) = (cayley(&w) * d1, cayley(&-w) * d1);
                let fd =
                    (joint.step(&d0, &plus, &f0, &f1).moment - joint.step(&d0, &minus, &f0, &f1).moment) / (2.0 * e);
                let err = (fd - st.tangent.column(j)).norm();
                assert!(err < 1e-6 * st.tangent.norm(), "step column {j}: {fd} vs {}", st.tangent.column(j));
                let fd = (joint.static_moment(&plus, &f1).0 - joint.static_moment(&minus, &f1).0) / (2.0 * e);
                let err = (fd - ks.column(j)).norm();
                assert!(err < 1e-6 * ks.norm(), "static column {j}: {fd} vs {}", ks.column(j));
            }
            // the static moment is ∂V/∂w
            let (m, _) = joint.static_moment(&d1, &f1);
            for j in 0..3 {
                let w = V3::from_fn(|i, _| if i == j { e } else { 0.0 });
                let fd = (joint.energy(&(cayley(&w) * d1), &f1) - joint.energy(&(cayley(&-w) * d1), &f1)) / (2.0 * e);
                assert!((fd - m[j]).abs() < 1e-6 * m.norm(), "dV/dw {j}: {fd} vs {}", m[j]);
            }
        }
    }

    /// A pure bend has no twist; a twist α about the common axis has τ = sin α.
    #[test]
    fn the_twist_measure_vanishes_for_a_bend() {
        let f = cayley(&V3::new(0.2, 0.1, -0.3));
        let bend = cayley(&(col(&f, 0) * 0.3 + col(&f, 1) * 0.4)) * f;
        assert!(FlexJoint::twist(&bend, &f).abs() < 1e-15);
        let a = 0.2f64;
        let twist = f * crate::math::rigid::rot_z(a);
        assert!((FlexJoint::twist(&twist, &f) - a.sin()).abs() < 1e-15);
        // the Cayley vector of length 0.5 turns by 2 atan(0.25)
        assert!((FlexJoint::angle(&bend, &f) - 2.0 * 0.25f64.atan()).abs() < 1e-14);
    }
}
