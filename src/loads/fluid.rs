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
//!
//! In waves (docs/theory.md §13.6) the water moves with velocity u_w and
//! acceleration a_w at each Gauss point ([`WaterAtGauss`], frozen over a
//! step): the drag acts on the relative velocity v_c + u_w − v, and the
//! accelerating water adds its inertia force
//!   f_I = ρ_w A a_w + m_a (I − t tᵀ)(a_w − a)                         (13.12)
//! (Froude–Krylov on the displaced area A in every direction, added mass
//! normal to the line: (1 + C_a) ρ_w A a_w,n normal, ρ_w A a_w,t along it);
//! every term is cut at the local surface z_s + η.

use super::current::Current;
use super::morison::{DragCoefficients, drag, drag_force};
use super::surface::FreeSurface;
use super::waves::{Sea, WaterPoint, WaveScratch};
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
    /// The Froude–Krylov mass per unit length ρ_w A (A the displaced
    /// area), kg/m: the waves' pressure gradient on the displaced water (13.12).
    pub froude_krylov: f64,
}

impl Fluid {
    pub fn none() -> Self {
        Fluid { drag: None, added_mass: 0.0, surface: None, froude_krylov: 0.0 }
    }

    /// True if still water exerts no force beyond weight and buoyancy.
    pub fn is_inert(&self) -> bool {
        self.drag.is_none() && self.added_mass == 0.0
    }

    /// True if the water exerts no force beyond weight and buoyancy, in
    /// waves (`waves`) or in still water.
    pub fn is_inert_in(&self, waves: bool) -> bool {
        self.is_inert() && !(waves && self.froude_krylov != 0.0)
    }
}

/// The water's motion at the four Gauss points of an element, held over a
/// step (docs/theory.md §13.6): velocity (m/s), acceleration (m/s²) and
/// the elevation of the surface above the point, m (all ramped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterAtGauss {
    pub velocity: [V3; 4],
    pub acceleration: [V3; 4],
    pub elevation: [f64; 4],
    /// How far the surface dips below its mean level anywhere along the
    /// element, at most, m: a bound of max(0, −η(ξ)) over ξ ∈ [0, 1] of
    /// [`WaterAtGauss::elevation_at`] ([`WaterAtGauss::depression_bound`]).
    pub depression: f64,
}

impl WaterAtGauss {
    /// Still water.
    pub const STILL: WaterAtGauss = WaterAtGauss {
        velocity: [V3::new(0.0, 0.0, 0.0); 4],
        acceleration: [V3::new(0.0, 0.0, 0.0); 4],
        elevation: [0.0; 4],
        depression: 0.0,
    };

    /// The water at the Gauss points with [`WaterAtGauss::depression`] filled.
    pub fn new(velocity: [V3; 4], acceleration: [V3; 4], elevation: [f64; 4]) -> Self {
        WaterAtGauss { velocity, acceleration, elevation, depression: Self::depression_bound(&elevation) }
    }

    /// A bound of max(0, −η(ξ)) over ξ ∈ [0, 1] for the cubic η(ξ) through
    /// the elevations `eta` at the four Gauss points (13.14): the cubic in
    /// Bernstein form on each half of the element, η = Σ b_j B_j (B_j ≥ 0,
    /// Σ B_j = 1), lies above its smallest coefficient; plus 1e-9 (1 + max |η_g|) m for the rounding of
    /// the coefficients and of the evaluation. Zero contributions of the
    /// surface cut need no evaluation below z_s − ε − this bound.
    pub fn depression_bound(eta: &[f64; 4]) -> f64 {
        let x = GAUSS4.xi;
        let (mut b, mut top) = ([0.0; 4], 0.0f64);
        for i in 0..4 {
            // the Lagrange polynomial l_i in monomial form, c0 + c1 ξ + c2 ξ² + c3 ξ³
            let mut c = [1.0, 0.0, 0.0, 0.0];
            for j in (0..4).filter(|&j| j != i) {
                let d = 1.0 / (x[i] - x[j]);
                // c ← c (ξ − x_j) d
                for m in (0..4).rev() {
                    c[m] = (if m > 0 { c[m - 1] } else { 0.0 } - x[j] * c[m]) * d;
                }
            }
            // its Bernstein coefficients
            let bi = [c[0], c[0] + c[1] / 3.0, c[0] + (2.0 * c[1] + c[2]) / 3.0, c[0] + c[1] + c[2] + c[3]];
            for j in 0..4 {
                b[j] += eta[i] * bi[j];
            }
            top = top.max(eta[i].abs());
        }
        // halved once (de Casteljau at ξ = ½): the halves' seven coefficients
        // hug the cubic four times closer
        let (b01, b12, b23) = (0.5 * (b[0] + b[1]), 0.5 * (b[1] + b[2]), 0.5 * (b[2] + b[3]));
        let (b012, b123) = (0.5 * (b01 + b12), 0.5 * (b12 + b23));
        let mid = 0.5 * (b012 + b123);
        let lowest = [b[0], b01, b012, mid, b123, b23, b[3]].iter().fold(f64::INFINITY, |m, &v| m.min(v));
        (-lowest).max(0.0) + 1e-9 * (1.0 + top)
    }

    /// The elevation at ξ ∈ [0, 1] along the element: the cubic through the
    /// four Gauss points' values (Lagrange), m.
    pub fn elevation_at(&self, xi: f64) -> f64 {
        let x = GAUSS4.xi;
        let mut eta = 0.0;
        for i in 0..4 {
            let mut l = 1.0;
            for j in 0..4 {
                if j != i {
                    l *= (xi - x[j]) / (x[i] - x[j]);
                }
            }
            eta += l * self.elevation[i];
        }
        eta
    }
}

/// The waves' motion at the Gauss points of a whole line, held over a step
/// (docs/theory.md §13.6): evaluated once per step at the step's midpoint
/// time t_n + h/2 and the predicted midpoint configuration, so that the
/// force keeps the scheme's second order and its tangent has no term of
/// the field's gradient. Allocated once.
#[derive(Debug, Clone)]
pub struct FrozenWater {
    /// The Gauss points, four per element (filled by the model), m.
    pub points: Vec<V3>,
    /// The water's motion per element (still water until evaluated).
    pub at: Vec<WaterAtGauss>,
    out: Vec<WaterPoint>,
    scratch: WaveScratch,
}

impl FrozenWater {
    /// Storage for a line of `n_el` elements in `sea`.
    pub fn new(sea: &Sea, n_el: usize) -> Self {
        FrozenWater {
            points: vec![V3::zeros(); 4 * n_el],
            at: vec![WaterAtGauss::STILL; n_el],
            out: vec![WaterPoint::STILL; 4 * n_el],
            scratch: sea.scratch(),
        }
    }

    /// Evaluates the sea at `t` s at [`FrozenWater::points`].
    pub fn evaluate(&mut self, sea: &Sea, t: f64) {
        sea.water_batch(t, &self.points, &mut self.out, &mut self.scratch);
        for (e, w) in self.at.iter_mut().enumerate() {
            for g in 0..4 {
                let p = &self.out[4 * e + g];
                w.velocity[g] = p.velocity;
                w.acceleration[g] = p.acceleration;
                w.elevation[g] = p.elevation;
            }
            w.depression = WaterAtGauss::depression_bound(&w.elevation);
        }
    }
}

/// The water's motion at the four Gauss points of an element at `points`
/// at time `t` (for outputs at a state; no scratch: a few points).
pub fn water_at(sea: &Sea, points: &[V3; 4], t: f64) -> WaterAtGauss {
    let k = points.map(|p| sea.water(&p, t));
    WaterAtGauss::new(k.map(|k| k.velocity), k.map(|k| k.acceleration), k.map(|k| k.elevation))
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
    /// The water's motion at the Gauss points (None: still water).
    pub water: Option<&'a WaterAtGauss>,
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
/// residual r = … − F) to `k`. `current_scale` multiplies the current's
/// speed (its start's ramp, docs/theory.md §5.11; 1: the current in full).
#[allow(clippy::too_many_arguments)]
pub fn element_fluid_force(
    fluid: &Fluid,
    current_scale: f64,
    fields: FluidFields<'_>,
    shapes: &HermiteAtGauss,
    s0: f64,
    h: f64,
    fac: FluidFactors,
    f: &mut [V3; 4],
    k: Option<&mut [[M3; 4]; 4]>,
) {
    let shape = |g: usize| shapes[g];
    interpolated_fluid_force(fluid, current_scale, fields.c, fields.v, fields.a, fields.water, shape, s0, h, fac, f, k);
}

/// The same for a straight two-node segment of the cable (linear
/// interpolation; `x`, `v`, `a` the nodal positions, velocities and
/// accelerations, `l` the reference length).
#[allow(clippy::too_many_arguments)]
pub fn segment_fluid_force(
    fluid: &Fluid,
    current_scale: f64,
    x: &[V3; 2],
    v: &[V3; 2],
    a: &[V3; 2],
    water: Option<&WaterAtGauss>,
    s0: f64,
    l: f64,
    fac: FluidFactors,
    f: &mut [V3; 2],
    k: Option<&mut [[M3; 2]; 2]>,
) {
    let shape = |g: usize| ([1.0 - GAUSS4.xi[g], GAUSS4.xi[g]], [-1.0 / l, 1.0 / l]);
    interpolated_fluid_force(fluid, current_scale, x, v, a, water, shape, s0, l, fac, f, k);
}

/// The fluid force alone (no derivatives) of an element from the fields at
/// its Gauss points, r = `x`, r' = `p`, velocity `v` (what the rod's residual
/// kernel has already interpolated), with the shape values `shapes` (N, N')
/// per Gauss point; `acc` the nodal accelerations (read only with added
/// mass); `water` the waves' motion (None: still water). The four points
/// are evaluated in phases so that their square roots overlap (the residual
/// is evaluated several times per step).
#[allow(clippy::too_many_arguments)]
pub fn gauss_point_fluid_force<const K: usize>(
    fluid: &Fluid,
    current_scale: f64,
    x: &[V3; 4],
    p: &[V3; 4],
    v: &[V3; 4],
    acc: &[V3; K],
    water: Option<&WaterAtGauss>,
    shapes: &[([f64; K], [f64; K]); 4],
    s0: f64,
    h: f64,
    f: &mut [V3; K],
) {
    let len: [f64; 4] = std::array::from_fn(|g| p[g].norm());
    // unit tangents (a degenerate point, |p| = 0, feels nothing)
    let t: [V3; 4] = std::array::from_fn(|g| if len[g] > 0.0 { p[g] * (1.0 / len[g]) } else { V3::zeros() });
    let mut force = [V3::zeros(); 4];
    let w = water.unwrap_or(&WaterAtGauss::STILL);
    if let Some((kd, current)) = &fluid.drag {
        for g in 0..4 {
            let vc = current.velocity(s0 + GAUSS4.xi[g] * h, x[g].z).0 * current_scale;
            force[g] = drag_force(kd, &(vc + w.velocity[g] - v[g]), &t[g]) * len[g];
        }
    }
    if fluid.added_mass > 0.0 {
        for g in 0..4 {
            let (n, _) = &shapes[g];
            let mut a = -w.acceleration[g];
            for j in 0..K {
                a += acc[j] * n[j];
            }
            // −m_a (I − t tᵀ)(a − a_w)
            force[g] -= (a - t[g] * t[g].dot(&a)) * fluid.added_mass;
        }
    }
    if water.is_some() {
        for g in 0..4 {
            // Froude–Krylov ρ_w A a_w (13.12)
            force[g] += w.acceleration[g] * fluid.froude_krylov;
        }
    }
    if let Some(s) = &fluid.surface {
        for g in 0..4 {
            force[g] *= s.submerged(x[g].z - w.elevation[g]).0;
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
    current_scale: f64,
    c: &[V3; K],
    vel: &[V3; K],
    acc: &[V3; K],
    water: Option<&WaterAtGauss>,
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
        return gauss_point_fluid_force(fluid, current_scale, &x, &p, &v, acc, water, &shapes, s0, h, f);
    }
    let w = water.unwrap_or(&WaterAtGauss::STILL);
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
            let (vc, dvc_dz) = (vc * current_scale, dvc_dz * current_scale);
            let d = drag(kd, &(vc + w.velocity[g] - v), &t);
            force += d.force * len;
            df_dx += d.d_vrel * dvc_dz * V3::z().transpose() * len;
            df_dv -= d.d_vrel * len;
            df_dp += d.d_tangent * proj + d.force * t.transpose();
        }
        if fluid.added_mass > 0.0 {
            // the acceleration relative to the water's
            let mut a = -w.acceleration[g];
            for j in 0..K {
                a += acc[j] * n[j];
            }
            let ma = fluid.added_mass;
            force -= proj * a * ma;
            df_da -= proj * ma;
            // ∂(−m_a (I − t tᵀ) a)/∂t = m_a ((t·a) I + t aᵀ), ∂t/∂p = (I − t tᵀ)/|p|
            df_dp += (M3::identity() * t.dot(&a) + t * a.transpose()) * proj * (ma / len);
        }
        if water.is_some() {
            // Froude–Krylov ρ_w A a_w (13.12), the water's motion held over the step
            force += w.acceleration[g] * fluid.froude_krylov;
        }
        if let Some(s) = &fluid.surface {
            // only the submerged fraction s(z − η) feels the water (§10, §13.6)
            let (sub, dsub) = s.submerged(x.z - w.elevation[g]);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The cubic's largest dip below the mean level, sampled at 20001 points.
    fn sampled_depression(w: &WaterAtGauss) -> f64 {
        (0..=20000).map(|i| -w.elevation_at(i as f64 / 20000.0)).fold(0.0, f64::max)
    }

    /// `depression_bound` against the interpolating cubic sampled densely:
    /// never below it (a bound, for pseudo-random elevations and for waves
    /// of every length sampled at the Gauss points), and within 1 % of the
    /// amplitude of it for waves at least ten elements long (5.6e-3 found;
    /// the band cut is then skipped nearly wherever the surface leaves it).
    #[test]
    fn the_depression_bound_bounds_the_cubic_and_is_tight_for_long_waves() {
        let mut next = crate::loads::uniform_stream(0x2545_f491_4f6c_dd1d);
        let still = WaterAtGauss::STILL;
        for _ in 0..3000 {
            let scale = 10f64.powf(3.0 * next());
            let eta = [next(), next(), next(), next()].map(|e| e * scale + 0.3 * scale);
            let w = WaterAtGauss::new(still.velocity, still.acceleration, eta);
            assert!(w.depression >= sampled_depression(&w), "{eta:?}: {} vs {}", w.depression, sampled_depression(&w));
        }
        let mut worst_gap = 0.0f64;
        for lengths in [0.5, 1.0, 2.0, 5.0, 10.0, 40.0] {
            for i in 0..200 {
                let (amplitude, phase) = (3.0, 0.0314 * i as f64);
                let eta = GAUSS4.xi.map(|x| amplitude * (2.0 * std::f64::consts::PI * x / lengths + phase).cos());
                let w = WaterAtGauss::new(still.velocity, still.acceleration, eta);
                let sampled = sampled_depression(&w);
                assert!(w.depression >= sampled, "{lengths} {phase}: {} vs {sampled}", w.depression);
                if lengths >= 10.0 {
                    worst_gap = worst_gap.max((w.depression - sampled) / amplitude);
                }
            }
        }
        eprintln!(
            "largest gap of the bound over the sampled dip, waves ≥ 10 elements: {worst_gap:.2e} of the amplitude"
        );
        assert!(worst_gap < 0.01, "{worst_gap}");
    }
}
