//! The element's unknowns and their layout (shared by the element, the
//! Gauss-point kernels and the assembly):
//!   [r_a (3), r'_a (3), θ_a (3), θ_mid (3), r_b (3), r'_b (3), θ_b (3)]
//! so that element e owns the contiguous global rows 12e .. 12e+21.

use crate::math::{M3, V3};
use crate::model::RodConfig;
use nalgebra::{SMatrix, SVector};

/// Unknowns per element (reduced: rotations instead of director components).
pub const NDOF_EL: usize = 21;
/// Gauss points per element.
pub const NGP: usize = 4;
/// Global stride between consecutive elements.
pub const STRIDE: usize = 12;

pub type ElVec = SVector<f64, NDOF_EL>;
pub type ElMat = SMatrix<f64, NDOF_EL, NDOF_EL>;
/// Strain vector (γ_x, γ_y, γ_z, K1, K2, K3): spatial penalty strain, then
/// bending and twist.
pub type Strain = [f64; 6];

/// Local offsets of the Hermite dofs [r_a, r'_a, r_b, r'_b].
pub const C_OFF: [usize; 4] = [0, 3, 12, 15];
/// Local offsets of the director-node rotations [θ_a, θ_mid, θ_b].
pub const T_OFF: [usize; 3] = [6, 9, 18];

/// Which shear/extension measure the first three strain rows carry.
#[derive(Debug, Clone, Copy)]
pub enum Shear<'a> {
    /// The paper's spatial penalty strain γ = r' − d3 − Σ g⁰_i d_i, with the
    /// reference coefficients g⁰ at the Gauss points (the stored energy).
    Spatial(&'a [V3; NGP]),
    /// Material components Γ_i = d_i·r' − δ_i3 (quadratic and invariant under
    /// rigid motions): used for the objective structural damping (theory §5.9).
    Material,
}

/// Cyclic index triples (i, j, k).
pub const CYC: [(usize, usize, usize); 3] = [(0, 1, 2), (1, 2, 0), (2, 0, 1)];

/// The element's nodal values gathered from a configuration.
#[derive(Debug, Clone, Copy)]
pub struct ElemDofs {
    /// Hermite dofs [r_a, r'_a, r_b, r'_b].
    pub c: [V3; 4],
    /// Director frames at [start, mid, end].
    pub d: [M3; 3],
}

impl ElemDofs {
    pub fn gather(cfg: &RodConfig, e: usize) -> Self {
        ElemDofs {
            c: [cfg.x[e], cfg.xp[e], cfg.x[e + 1], cfg.xp[e + 1]],
            d: [cfg.d[2 * e], cfg.d[2 * e + 1], cfg.d[2 * e + 2]],
        }
    }

    /// Component-wise average ½(a + b): the midpoint configuration q_{n+½}.
    pub fn average(a: &Self, b: &Self) -> Self {
        let mut m = *a;
        for k in 0..4 {
            m.c[k] = 0.5 * (a.c[k] + b.c[k]);
        }
        for k in 0..3 {
            m.d[k] = 0.5 * (a.d[k] + b.d[k]);
        }
        m
    }
}
