//! Consistent nodal forces of the water on one element (a Hermite element of
//! the rod or a two-node segment of the cable): Morison drag (paper
//! eqs. 13–17) and normal added mass, with their derivatives with respect to
//! the element's Hermite unknowns (docs/theory.md §5.4).
//!
//! The fields are interpolated with the Hermite functions of the centreline:
//! position x(S) = Σ N_k c_k, slope p = Σ N'_k c_k, velocity v = Σ N_k v_k,
//! acceleration a = Σ N_k a_k. Per unit reference length the line feels
//!   drag          f_D = |p| · Morison(v_c(S, z) − v, t),   t = p/|p|
//!   added mass    f_A = −m_a (I − t tᵀ) a,                   m_a = C_a ρ_w π D²/4
//! (drag acts on the current length |p| dS; the added mass per reference length).
//! The consistent nodal force is F_k = ∫ N_k f dS (4-point Gauss).

use super::current::Current;
use super::morison::{DragCoefficients, drag, drag_force};
use super::surface::FreeSurface;
use crate::math::shape::{GAUSS4, hermite, hermite_ds};
use crate::math::{M3, V3};

/// Hydrodynamic description of the line.
#[derive(Debug, Clone)]
pub struct Fluid {
    /// Drag coefficients and current (None: no drag).
    pub drag: Option<(DragCoefficients, Current)>,
    /// Normal added mass per unit length m_a = C_a ρ_w π D²/4, kg/m (0: none).
    pub added_mass: f64,
    /// The free surface: drag and added mass act on the submerged fraction
    /// of the line (docs/theory.md §10; None: submerged everywhere).
    pub surface: Option<FreeSurface>,
}

impl Fluid {
    pub fn none() -> Self {
        Fluid { drag: None, added_mass: 0.0, surface: None }
    }

    /// True if the water exerts no force beyond weight and buoyancy.
    pub fn is_inert(&self) -> bool {
        self.drag.is_none() && self.added_mass == 0.0
    }
}

/// How the evaluation fields depend on the unknowns c_{n+1} of the step:
/// ∂c_eval/∂c = `position`, ∂v/∂c = `velocity`, ∂a/∂c = `acceleration`.
#[derive(Debug, Clone, Copy)]
pub struct FluidFactors {
    pub position: f64,
    pub velocity: f64,
    pub acceleration: f64,
}

/// The element's Hermite fields at which the water acts.
#[derive(Debug, Clone, Copy)]
pub struct FluidFields<'a> {
    /// Hermite position dofs [r_a, r'_a, r_b, r'_b].
    pub c: &'a [V3; 4],
    /// Hermite velocity dofs.
    pub v: &'a [V3; 4],
    /// Hermite acceleration dofs (used only with added mass).
    pub a: &'a [V3; 4],
}

/// Hermite functions and their slopes at the four Gauss points of an element
/// of length h (constant per mesh: computed once, not per element).
pub type HermiteAtGauss = [([f64; 4], [f64; 4]); 4];

/// [`HermiteAtGauss`] for an element of length `h` (m).
pub fn hermite_at_gauss(h: f64) -> HermiteAtGauss {
    GAUSS4.xi.map(|xi| (hermite(xi, h), hermite_ds(xi, h)))
}

/// Adds the consistent nodal fluid forces of a Hermite element of the rod
/// to `f` (N) and, if asked, −∂F/∂c (the contribution to the tangent of a
/// residual r = … − F) to `k`.
#[allow(clippy::too_many_arguments)]
pub fn element_fluid_force(
    fluid: &Fluid,
    fields: FluidFields<'_>,
    shapes: &HermiteAtGauss,
    s0: f64,
    h: f64,
    fac: FluidFactors,
    f: &mut [V3; 4],
    k: Option<&mut [[M3; 4]; 4]>,
) {
    let shape = |g: usize| shapes[g];
    interpolated_fluid_force(fluid, fields.c, fields.v, fields.a, shape, s0, h, fac, f, k);
}

/// The same for a straight two-node segment of the cable (linear
/// interpolation; `x`, `v`, `a` the nodal positions, velocities and
/// accelerations, `l` the reference length).
#[allow(clippy::too_many_arguments)]
pub fn segment_fluid_force(
    fluid: &Fluid,
    x: &[V3; 2],
    v: &[V3; 2],
    a: &[V3; 2],
    s0: f64,
    l: f64,
    fac: FluidFactors,
    f: &mut [V3; 2],
    k: Option<&mut [[M3; 2]; 2]>,
) {
    let shape = |g: usize| ([1.0 - GAUSS4.xi[g], GAUSS4.xi[g]], [-1.0 / l, 1.0 / l]);
    interpolated_fluid_force(fluid, x, v, a, shape, s0, l, fac, f, k);
}

/// The fluid force alone (no derivatives) of an element from the fields at
/// its Gauss points, r = `x`, r' = `p`, velocity `v` (what the rod's residual
/// kernel has already interpolated), with the shape values `shapes` (N, N')
/// per Gauss point; `acc` the nodal accelerations (read only with added
/// mass). The four points are evaluated in phases so that their square
/// roots overlap (the residual is evaluated several times per step).
#[allow(clippy::too_many_arguments)]
pub fn gauss_point_fluid_force<const K: usize>(
    fluid: &Fluid,
    x: &[V3; 4],
    p: &[V3; 4],
    v: &[V3; 4],
    acc: &[V3; K],
    shapes: &[([f64; K], [f64; K]); 4],
    s0: f64,
    h: f64,
    f: &mut [V3; K],
) {
    let len: [f64; 4] = std::array::from_fn(|g| p[g].norm());
    // unit tangents (a degenerate point, |p| = 0, feels nothing)
    let t: [V3; 4] = std::array::from_fn(|g| if len[g] > 0.0 { p[g] * (1.0 / len[g]) } else { V3::zeros() });
    let mut force = [V3::zeros(); 4];
    if let Some((kd, current)) = &fluid.drag {
        for g in 0..4 {
            let (vc, _) = current.velocity(s0 + GAUSS4.xi[g] * h, x[g].z);
            force[g] = drag_force(kd, &(vc - v[g]), &t[g]) * len[g];
        }
    }
    if fluid.added_mass > 0.0 {
        for g in 0..4 {
            let (n, _) = &shapes[g];
            let mut a = V3::zeros();
            for j in 0..K {
                a += acc[j] * n[j];
            }
            // −m_a (I − t tᵀ) a
            force[g] -= (a - t[g] * t[g].dot(&a)) * fluid.added_mass;
        }
    }
    if let Some(s) = &fluid.surface {
        for g in 0..4 {
            force[g] *= s.submerged(x[g].z).0;
        }
    }
    for g in 0..4 {
        let (n, _) = &shapes[g];
        let wg = GAUSS4.w[g] * h;
        for i in 0..K {
            f[i] += force[g] * (wg * n[i]);
        }
    }
}

/// ∫ N_k f dS over an element whose fields are interpolated by `shape(g)` =
/// (N(ξ_g), N'(ξ_g)) at Gauss point g from the dofs `c` (position), `v`, `a` (4-point Gauss).
#[allow(clippy::too_many_arguments)]
fn interpolated_fluid_force<const K: usize>(
    fluid: &Fluid,
    c: &[V3; K],
    vel: &[V3; K],
    acc: &[V3; K],
    shape: impl Fn(usize) -> ([f64; K], [f64; K]),
    s0: f64,
    h: f64,
    fac: FluidFactors,
    f: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    if k.is_none() {
        // the force alone: interpolate, then the per-point kernel
        let shapes: [([f64; K], [f64; K]); 4] = std::array::from_fn(shape);
        let (mut x, mut p, mut v) = ([V3::zeros(); 4], [V3::zeros(); 4], [V3::zeros(); 4]);
        for g in 0..4 {
            let (n, nd) = &shapes[g];
            for j in 0..K {
                x[g] += c[j] * n[j];
                p[g] += c[j] * nd[j];
                v[g] += vel[j] * n[j];
            }
        }
        return gauss_point_fluid_force(fluid, &x, &p, &v, acc, &shapes, s0, h, f);
    }
    for g in 0..4 {
        let xi = GAUSS4.xi[g];
        let wg = GAUSS4.w[g] * h;
        let (n, nd) = shape(g);
        let mut x = V3::zeros();
        let mut p = V3::zeros();
        let mut v = V3::zeros();
        for j in 0..K {
            x += c[j] * n[j];
            p += c[j] * nd[j];
            v += vel[j] * n[j];
        }
        let len = p.norm();
        if len == 0.0 {
            continue;
        }
        let t = p / len;
        let proj = M3::identity() - t * t.transpose();
        let mut force = V3::zeros();
        // derivatives of the force per reference length with respect to x, v, a, p
        let mut df_dx = M3::zeros();
        let mut df_dv = M3::zeros();
        let mut df_da = M3::zeros();
        let mut df_dp = M3::zeros();
        if let Some((kd, current)) = &fluid.drag {
            let (vc, dvc_dz) = current.velocity(s0 + xi * h, x.z);
            let d = drag(kd, &(vc - v), &t);
            force += d.force * len;
            df_dx += d.d_vrel * dvc_dz * V3::z().transpose() * len;
            df_dv -= d.d_vrel * len;
            df_dp += d.d_tangent * proj + d.force * t.transpose();
        }
        if fluid.added_mass > 0.0 {
            let mut a = V3::zeros();
            for j in 0..K {
                a += acc[j] * n[j];
            }
            let ma = fluid.added_mass;
            force -= proj * a * ma;
            df_da -= proj * ma;
            // ∂(−m_a (I − t tᵀ) a)/∂t = m_a ((t·a) I + t aᵀ), ∂t/∂p = (I − t tᵀ)/|p|
            df_dp += (M3::identity() * t.dot(&a) + t * a.transpose()) * proj * (ma / len);
        }
        if let Some(s) = &fluid.surface {
            // only the submerged fraction s(z) feels the water (§10)
            let (sub, dsub) = s.submerged(x.z);
            df_dx = df_dx * sub + force * V3::z().transpose() * dsub;
            df_dv *= sub;
            df_da *= sub;
            df_dp *= sub;
            force *= sub;
        }
        for i in 0..K {
            f[i] += force * (wg * n[i]);
        }
        if let Some(k) = k.as_deref_mut() {
            let by_value = df_dx * fac.position + df_dv * fac.velocity + df_da * fac.acceleration;
            let by_slope = df_dp * fac.position;
            for i in 0..K {
                for j in 0..K {
                    k[i][j] -= (by_value * n[j] + by_slope * nd[j]) * (wg * n[i]);
                }
            }
        }
    }
}
