//! A vessel's pose and the motion of a point fixed on it (the FMU's vessel coupling,
//! issue 30; docs/theory.md §14): Euler angles in the marine z-y-x order or
//! MoorDyn/OpenFAST's x-y-z order, the angular velocity in the vessel frame,
//! and the position, velocity and acceleration of an offset point
//! r = r₀ + R ρ.
//!
//! Frames: z up; for a vessel whose x points to the bow and y to port,
//! a positive roll lifts port, a positive pitch puts the bow down, a
//! positive yaw turns the bow to port (right-handed rotations about x, y, z).

use super::{M3, V3, skew};

/// The order in which the Euler angles (roll φ, pitch θ, yaw ψ) compose the
/// active rotation R that maps vessel-frame vectors to the global frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RotationOrder {
    /// R = Rz(ψ) Ry(θ) Rx(φ): the marine (and aerospace) convention.
    Zyx,
    /// R = Rx(φ) Ry(θ) Rz(ψ): MoorDyn's and OpenFAST's.
    Xyz,
}

/// Rotation by `a` rad about x.
pub fn rot_x(a: f64) -> M3 {
    let (s, c) = a.sin_cos();
    M3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Rotation by `a` rad about y.
pub fn rot_y(a: f64) -> M3 {
    let (s, c) = a.sin_cos();
    M3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// Rotation by `a` rad about z.
pub fn rot_z(a: f64) -> M3 {
    let (s, c) = a.sin_cos();
    M3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

impl RotationOrder {
    /// R of the angles [φ, θ, ψ] (rad) (14.1).
    pub fn rotation(self, angles: [f64; 3]) -> M3 {
        let [phi, theta, psi] = angles;
        match self {
            RotationOrder::Zyx => rot_z(psi) * rot_y(theta) * rot_x(phi),
            RotationOrder::Xyz => rot_x(phi) * rot_y(theta) * rot_z(psi),
        }
    }

    /// The angular velocity in the vessel frame, ω_b with Ṙ = R \[ω_b\]×, of
    /// the angle rates [φ̇, θ̇, ψ̇] at `angles` (14.2): each rate about its own
    /// axis carried into the vessel frame by the rotations that follow it.
    /// Defined at every attitude (the inverse, rates from ω_b, is singular
    /// where the middle angle is ±90°: gimbal lock).
    pub fn body_rates(self, angles: [f64; 3], rates: [f64; 3]) -> V3 {
        let [phi, theta, psi] = angles;
        let [dphi, dtheta, dpsi] = rates;
        match self {
            // R = Rz Ry Rx: ω_b = φ̇ x + Rxᵀ θ̇ y + Rxᵀ Ryᵀ ψ̇ z
            RotationOrder::Zyx => {
                V3::x() * dphi + rot_x(phi).transpose() * (V3::y() * dtheta + rot_y(theta).transpose() * V3::z() * dpsi)
            }
            // R = Rx Ry Rz: ω_b = ψ̇ z + Rzᵀ θ̇ y + Rzᵀ Ryᵀ φ̇ x
            RotationOrder::Xyz => {
                V3::z() * dpsi + rot_z(psi).transpose() * (V3::y() * dtheta + rot_y(theta).transpose() * V3::x() * dphi)
            }
        }
    }
}

/// A rigid body's motion at one instant: its reference point's position,
/// velocity and acceleration (global frame, m, m/s, m/s²), its rotation R,
/// and its angular velocity and acceleration in its own frame (rad/s, rad/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    pub position: V3,
    pub velocity: V3,
    pub acceleration: V3,
    pub rotation: M3,
    pub angular_velocity: V3,
    pub angular_acceleration: V3,
}

impl RigidMotion {
    /// The position, velocity and acceleration (global frame) of the point at
    /// `rho` in the body frame (14.3):
    ///   r = r₀ + R ρ,  v = v₀ + ω × Rρ,  a = a₀ + α × Rρ + ω × (ω × Rρ)
    /// with ω = R ω_b and α = R α_b the global angular velocity and
    /// acceleration.
    pub fn point(&self, rho: V3) -> (V3, V3, V3) {
        let arm = self.rotation * rho;
        let omega = self.rotation * self.angular_velocity;
        let alpha = self.rotation * self.angular_acceleration;
        let v = self.velocity + omega.cross(&arm);
        let a = self.acceleration + alpha.cross(&arm) + omega.cross(&omega.cross(&arm));
        (self.position + arm, v, a)
    }

    /// The moment about the reference point of a force `f` applied at the
    /// body-frame point `rho`, global frame: (R ρ) × f (14.4).
    pub fn moment_of(&self, rho: V3, f: V3) -> V3 {
        (self.rotation * rho).cross(&f)
    }
}

/// Ṙ of R = `order`.rotation(angles) with rates, by its definition R \[ω_b\]×.
pub fn rotation_rate(order: RotationOrder, angles: [f64; 3], rates: [f64; 3]) -> M3 {
    order.rotation(angles) * skew(&order.body_rates(angles, rates))
}

#[cfg(test)]
mod tests {
    use super::*;

    const ORDERS: [RotationOrder; 2] = [RotationOrder::Zyx, RotationOrder::Xyz];

    /// The signs of MoorDyn's rotation tests, in both orders (each angle alone).
    #[test]
    fn roll_lifts_port_pitch_puts_the_bow_down_yaw_turns_the_bow_to_port() {
        let a = 0.1;
        for o in ORDERS {
            let port = o.rotation([a, 0.0, 0.0]) * V3::y();
            let bow = o.rotation([0.0, a, 0.0]) * V3::x();
            let turned = o.rotation([0.0, 0.0, a]) * V3::x();
            assert!(port.z > 0.0 && bow.z < 0.0 && turned.y > 0.0, "{o:?}");
            assert!((port.z - a.sin()).abs() < 1e-15 && (bow.z + a.sin()).abs() < 1e-15);
        }
    }

    /// The orders differ when angles combine, and each R is orthonormal.
    #[test]
    fn the_two_orders_compose_differently() {
        let ang = [0.3, -0.2, 0.7];
        let (z, x) = (RotationOrder::Zyx.rotation(ang), RotationOrder::Xyz.rotation(ang));
        assert!((z - x).norm() > 0.1);
        for r in [z, x] {
            assert!((r.transpose() * r - M3::identity()).norm() < 1e-15 && (r.determinant() - 1.0).abs() < 1e-15);
        }
        // z-y-x: the columns of R are the vessel's axes; under yaw alone the bow points at (cos ψ, sin ψ, 0)
        let r = RotationOrder::Zyx.rotation([0.0, 0.0, 0.7]);
        assert!((r.column(0) - V3::new(0.7f64.cos(), 0.7f64.sin(), 0.0)).norm() < 1e-15);
    }

    /// Ṙ = R \[ω_b\]× (14.2) against central differences of R along the angles'
    /// path, both orders, at a general attitude and at pitch 90° (gimbal lock).
    #[test]
    fn body_rates_are_the_derivative_of_the_rotation() {
        let rates = [0.4, -0.3, 0.25];
        for o in ORDERS {
            for ang in [[0.3, -0.2, 0.7], [0.2, std::f64::consts::FRAC_PI_2, -0.4]] {
                let at = |t: f64| o.rotation([0, 1, 2].map(|i| ang[i] + rates[i] * t));
                let dt = 1e-5;
                let fd = (at(dt) - at(-dt)) / (2.0 * dt);
                let err = (fd - rotation_rate(o, ang, rates)).norm();
                assert!(err < 1e-9, "{o:?} {ang:?}: {err:e}");
            }
        }
    }

    /// The offset point's velocity and acceleration (14.3) against central
    /// differences of its position along a combined translation and rotation.
    #[test]
    fn offset_point_kinematics_match_finite_differences() {
        let rho = V3::new(30.0, -8.0, 5.0);
        for o in ORDERS {
            // angles and position as functions of time: a, b, c per component
            let ang = |t: f64| [0.1 * (0.5 * t).sin(), 0.05 + 0.08 * (0.3 * t).cos(), 0.2 * t];
            let dang = |t: f64| [0.05 * (0.5 * t).cos(), -0.024 * (0.3 * t).sin(), 0.2];
            let pos = |t: f64| V3::new(2.0 * (0.4 * t).sin(), t * t, -1.5 * t);
            let motion = |t: f64| {
                let h = 1e-4;
                let wb = |s: f64| o.body_rates(ang(s), dang(s));
                RigidMotion {
                    position: pos(t),
                    velocity: (pos(t + h) - pos(t - h)) / (2.0 * h),
                    acceleration: (pos(t + h) - 2.0 * pos(t) + pos(t - h)) / (h * h),
                    rotation: o.rotation(ang(t)),
                    angular_velocity: wb(t),
                    angular_acceleration: (wb(t + h) - wb(t - h)) / (2.0 * h),
                }
            };
            let t = 1.3;
            let h = 1e-3;
            let p = |s: f64| motion(s).point(rho).0;
            let (_, v, a) = motion(t).point(rho);
            let fd_v = (p(t + h) - p(t - h)) / (2.0 * h);
            let fd_a = (p(t + h) - 2.0 * p(t) + p(t - h)) / (h * h);
            assert!((v - fd_v).norm() < 1e-5 * v.norm(), "{o:?}: v {v} vs {fd_v}");
            assert!((a - fd_a).norm() < 1e-4 * a.norm(), "{o:?}: a {a} vs {fd_a}");
        }
    }

    /// M = (Rρ) × F: a vertical force at a point ahead of the reference point
    /// pitches the bow about −y (a downward pull at the bow, bow down).
    #[test]
    fn the_moment_of_a_force_at_the_offset() {
        let m = RigidMotion {
            position: V3::zeros(),
            velocity: V3::zeros(),
            acceleration: V3::zeros(),
            rotation: M3::identity(),
            angular_velocity: V3::zeros(),
            angular_acceleration: V3::zeros(),
        };
        let mom = m.moment_of(V3::new(30.0, 0.0, 0.0), V3::new(0.0, 0.0, -1e5));
        assert_eq!(mom, V3::new(0.0, 3e6, 0.0));
        // a positive moment about y is a positive pitch: bow down
        assert!((RotationOrder::Zyx.rotation([0.0, 1e-3, 0.0]) * V3::x()).z < 0.0);
    }
}
