//! Shape functions of the paper's element (section 2.4, docs/theory.md §2):
//! cubic Hermite for the centreline r (nodal r and r'), quadratic Lagrange for
//! the directors (end nodes and a mid node), and Gauss–Legendre quadrature.
//!
//! The element parameter is ξ ∈ [0, 1]; S = S_a + ξ h with h the element's
//! reference length. Derivatives returned here are with respect to S.

/// Gauss–Legendre points on [0, 1] and weights summing to 1.
#[derive(Debug, Clone, Copy)]
pub struct Quadrature<const N: usize> {
    pub xi: [f64; N],
    pub w: [f64; N],
}

/// Four-point rule: exact for polynomials of degree 7 in ξ. The strain energy
/// density is of degree 8 (strains of degree 4); four points integrate it to
/// O(h^8), enough for every element count the project uses and cheaper than
/// five (docs/theory.md §2.3).
pub const GAUSS4: Quadrature<4> = {
    // ±sqrt(3/7 ∓ 2/7 sqrt(6/5)) on [-1, 1]
    let a = 0.339_981_043_584_856_3;
    let b = 0.861_136_311_594_052_6;
    let wa = 0.652_145_154_862_546_1;
    let wb = 0.347_854_845_137_453_9;
    Quadrature {
        xi: [0.5 * (1.0 - b), 0.5 * (1.0 - a), 0.5 * (1.0 + a), 0.5 * (1.0 + b)],
        w: [0.5 * wb, 0.5 * wa, 0.5 * wa, 0.5 * wb],
    }
};

/// Cubic Hermite functions (values) for dofs [r_a, r'_a, r_b, r'_b].
#[inline]
pub fn hermite(xi: f64, h: f64) -> [f64; 4] {
    let x2 = xi * xi;
    let x3 = x2 * xi;
    [1.0 - 3.0 * x2 + 2.0 * x3, h * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, h * (x3 - x2)]
}

/// d/dS of the cubic Hermite functions.
#[inline]
pub fn hermite_ds(xi: f64, h: f64) -> [f64; 4] {
    let x2 = xi * xi;
    [(6.0 * x2 - 6.0 * xi) / h, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / h, 3.0 * x2 - 2.0 * xi]
}

/// Quadratic Lagrange functions with nodes at ξ = 0, 1/2, 1.
#[inline]
pub fn lagrange(xi: f64) -> [f64; 3] {
    [(1.0 - xi) * (1.0 - 2.0 * xi), 4.0 * xi * (1.0 - xi), xi * (2.0 * xi - 1.0)]
}

/// d/dS of the quadratic Lagrange functions.
#[inline]
pub fn lagrange_ds(xi: f64, h: f64) -> [f64; 3] {
    [(4.0 * xi - 3.0) / h, (4.0 - 8.0 * xi) / h, (4.0 * xi - 1.0) / h]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss4_integrates_degree_7_exactly() {
        for p in 0..=7 {
            let q: f64 = (0..4).map(|i| GAUSS4.w[i] * GAUSS4.xi[i].powi(p)).sum();
            assert!((q - 1.0 / (p as f64 + 1.0)).abs() < 1e-15, "degree {p}");
        }
    }

    #[test]
    fn shape_functions_interpolate_and_differentiate() {
        let h = 1.7;
        // Hermite reproduces a cubic exactly: f(S) = 1 + 2S - S^2 + 0.5 S^3.
        let f = |s: f64| 1.0 + 2.0 * s - s * s + 0.5 * s.powi(3);
        let fp = |s: f64| 2.0 - 2.0 * s + 1.5 * s * s;
        let dofs = [f(0.0), fp(0.0), f(h), fp(h)];
        for k in 0..=10 {
            let xi = k as f64 / 10.0;
            let n = hermite(xi, h);
            let dn = hermite_ds(xi, h);
            let v: f64 = (0..4).map(|i| n[i] * dofs[i]).sum();
            let d: f64 = (0..4).map(|i| dn[i] * dofs[i]).sum();
            assert!((v - f(xi * h)).abs() < 1e-13);
            assert!((d - fp(xi * h)).abs() < 1e-13);
            // Lagrange reproduces a quadratic.
            let g = |s: f64| 3.0 - s + 0.25 * s * s;
            let gp = |s: f64| -1.0 + 0.5 * s;
            let gd = [g(0.0), g(0.5 * h), g(h)];
            let l = lagrange(xi);
            let dl = lagrange_ds(xi, h);
            let v: f64 = (0..3).map(|i| l[i] * gd[i]).sum();
            let d: f64 = (0..3).map(|i| dl[i] * gd[i]).sum();
            assert!((v - g(xi * h)).abs() < 1e-13);
            assert!((d - gp(xi * h)).abs() < 1e-13);
        }
    }
}
