//! The configuration of a line, shared by both models: at the N+1 element end
//! nodes the centreline position r_a and slope r'_a (cubic Hermite, paper
//! §2.4), and at the 2N+1 director nodes (end nodes and element mid nodes) the
//! director frame D = [d1 d2 d3] (quadratic Lagrange); the cable uses the
//! positions only. Directors are updated by the Cayley transform of a rotation
//! vector, so D stays orthonormal to round-off.

use crate::math::{M3, V3};

/// Discrete rod configuration (positions in m, slopes dimensionless).
#[derive(Debug, PartialEq, Default)]
pub struct RodConfig {
    /// Centreline position r at the end nodes, m.
    pub x: Vec<V3>,
    /// Centreline slope r' = dr/dS at the end nodes (1 + axial strain along the tangent).
    pub xp: Vec<V3>,
    /// Director frames [d1 d2 d3] at the 2N+1 director nodes (node 2a = end node a,
    /// node 2e+1 = mid node of element e).
    pub d: Vec<M3>,
}

impl Clone for RodConfig {
    fn clone(&self) -> Self {
        RodConfig { x: self.x.clone(), xp: self.xp.clone(), d: self.d.clone() }
    }

    /// Reuses this configuration's buffers.
    fn clone_from(&mut self, o: &Self) {
        self.x.clone_from(&o.x);
        self.xp.clone_from(&o.xp);
        self.d.clone_from(&o.d);
    }
}

impl RodConfig {
    pub fn n_elements(&self) -> usize {
        self.x.len() - 1
    }

    /// Largest deviation of any director frame from orthonormality, max |DᵀD − I|.
    pub fn orthonormality_error(&self) -> f64 {
        self.d.iter().map(|d| (d.transpose() * d - M3::identity()).abs().max()).fold(0.0, f64::max)
    }

    /// Applies a superposed rigid motion x ↦ Q x + c (Q a rotation).
    pub fn rigidly_moved(&self, q: &M3, c: &V3) -> RodConfig {
        RodConfig {
            x: self.x.iter().map(|x| q * x + c).collect(),
            xp: self.xp.iter().map(|x| q * x).collect(),
            d: self.d.iter().map(|d| q * d).collect(),
        }
    }

    /// True if every number in the configuration is finite.
    pub fn is_finite(&self) -> bool {
        self.x.iter().chain(self.xp.iter()).all(|v| v.iter().all(|c| c.is_finite()))
            && self.d.iter().all(|d| d.iter().all(|c| c.is_finite()))
    }
}
