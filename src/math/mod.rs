//! The bottom layer: small fixed-size algebra (vectors, rotations by the
//! Cayley transform, frames), the element shape functions and quadrature
//! ([`shape`]) and the banded linear system ([`band`]) that the line models
//! assemble into and the solvers factorise. Nothing here knows a line.

pub mod band;
pub mod rigid;
pub mod shape;

use nalgebra::{Matrix3, Matrix6, Vector3};

pub type V3 = Vector3<f64>;
pub type M3 = Matrix3<f64>;
pub type M6 = Matrix6<f64>;

/// Skew-symmetric matrix `[a]×` with `[a]× b = a × b`.
#[inline]
pub fn skew(a: &V3) -> M3 {
    M3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Cayley transform cay(θ) = (I − ½θ̂)⁻¹ (I + ½θ̂), in closed form
/// cay(θ) = I + 4/(4 + |θ|²) (θ̂ + ½ θ̂²). Exactly orthogonal for any θ.
#[inline]
pub fn cayley(theta: &V3) -> M3 {
    let t = skew(theta);
    let f = 4.0 / (4.0 + theta.norm_squared());
    M3::identity() + f * (t + 0.5 * t * t)
}

/// A frame [d1 d2 d3] with d3 = t (unit) and d2 as close as possible to `d2_hint`.
pub fn frame_from_tangent(t: &V3, d2_hint: &V3) -> M3 {
    let d3 = t.normalize();
    let mut d2 = d2_hint - d3 * d3.dot(d2_hint);
    if d2.norm() < 1e-8 {
        // hint parallel to the tangent: pick any perpendicular
        let trial = if d3.x.abs() < 0.9 { V3::x() } else { V3::y() };
        d2 = trial - d3 * d3.dot(&trial);
    }
    let d2 = d2.normalize();
    let d1 = d2.cross(&d3);
    M3::from_columns(&[d1, d2, d3])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cayley_is_orthogonal_and_first_order_exact() {
        let th = V3::new(0.3, -1.2, 2.5);
        let r = cayley(&th);
        assert!((r.transpose() * r - M3::identity()).abs().max() < 1e-15);
        assert!((r.determinant() - 1.0).abs() < 1e-14);
        // cay(εθ) = I + ε θ̂ + O(ε²)
        let eps = 1e-6;
        let d = (cayley(&(th * eps)) - M3::identity()) / eps - skew(&th);
        assert!(d.abs().max() < 1e-5);
        // Cayley of θ rotates about θ by 2 atan(|θ|/2)
        let axis = th.normalize();
        assert!((r * axis - axis).norm() < 1e-14);
        let angle = 2.0 * (th.norm() / 2.0).atan();
        assert!((((r.trace() - 1.0) / 2.0).acos() - angle).abs() < 1e-12);
    }

    #[test]
    fn frame_from_tangent_is_right_handed() {
        let f = frame_from_tangent(&V3::new(0.6, 0.0, -0.8), &V3::y());
        assert!((f.transpose() * f - M3::identity()).abs().max() < 1e-15);
        assert!((f.determinant() - 1.0).abs() < 1e-15);
        assert!((f.column(1) - V3::y()).norm() < 1e-15);
    }
}
