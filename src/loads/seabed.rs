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
//! The contact's integrands have a kink where the line crosses the plane
//! (δ₊, δ₊²), which Gauss points across it integrate to O(h²) only: as the
//! touchdown moves through an element, each point in turn takes up its share
//! of the foundation at once, and the top tension jolts (the steel catenary's
//! window extremes erred 5–9e-4 at 40 to 80 elements). Each element's rule is
//! therefore four Gauss points on every sub-interval between the points where
//! its centreline crosses the plane, in any of the configurations the step
//! evaluates (x_n, x_{n+1} and their midpoint), on which the contact is
//! either on or off: V = ½ k D δ₊² is then integrated exactly (degree 6 in ξ on a
//! cubic element), and the static force and tangent, the gradient and
//! Hessian of that exact energy, need no derivative of the crossings (the
//! integrand vanishes there); the step's tangent adds the crossings'
//! motion, since its integrands are not all polynomials.             (9.7)
//! An element clear of crossings keeps the plain four-point rule.
//!
//! The regularisation v_ε (`slip_velocity`) replaces the Coulomb jump by a
//! smooth law: at a slip speed v the friction is μN v/√(v² + v_ε²), short of
//! μN by about v_ε²/(2v²) (0.5 % at 10 v_ε), and a line loaded below μN
//! creeps at about v_ε F/(μN) instead of sticking.
//!
//! In statics only the elastic part acts (the frictionless state: see
//! docs/theory.md §9.3).

use crate::math::shape::{GAUSS4, hermite, hermite_ds};
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

/// Shape functions (N, dN/dS, d²N/dS²) of an element of length `len` (m) at
/// ξ ∈ [0, 1].
pub type ShapeAt<const K: usize> = fn(f64, f64) -> ([f64; K], [f64; K], [f64; K]);

/// [`ShapeAt`] of the rod's cubic Hermite element.
pub fn hermite_at(xi: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let dd = [(12.0 * xi - 6.0) / (h * h), (6.0 * xi - 4.0) / h, (6.0 - 12.0 * xi) / (h * h), (6.0 * xi - 2.0) / h];
    (hermite(xi, h), hermite_ds(xi, h), dd)
}

/// [`ShapeAt`] of the cable's straight two-node segment.
pub fn linear_at(xi: f64, l: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    ([1.0 - xi, xi], [-1.0 / l, 1.0 / l], [0.0; 2])
}

/// The breakpoints of an element's contact rule (9.7): 0, 1 and the points
/// where the centreline crosses the plane in up to three configurations (a
/// cubic crosses at most three times), sorted.
#[derive(Debug, Clone, Copy)]
struct Breaks {
    xi: [f64; 11],
    /// Whose crossing each break is: 0 an end or a crossing at t_n (fixed in
    /// a step), 1 at t_{n+1}, 2 at the step's midpoint.
    of: [u8; 11],
    n: usize,
}

impl Breaks {
    fn new() -> Self {
        Breaks { xi: [0.0; 11], of: [0; 11], n: 1 }
    }

    /// Adds the crossings of the configuration with dofs `c`, tagged `of`.
    fn add_crossings<const K: usize>(&mut self, bed: &Seabed, c: &[V3; K], at: ShapeAt<K>, len: f64, of: u8) {
        // the height above the plane is a cubic (or linear) in ξ: its
        // coefficients from four samples (exact), then its sign changes on
        // the pieces between its extrema
        let y: [f64; 4] = std::array::from_fn(|i| {
            let (n, _, _) = at(i as f64 / 3.0, len);
            -bed.penetration(&(0..K).fold(V3::zeros(), |x, j| x + c[j] * n[j]))
        });
        if one_side(&y) {
            return;
        }
        let p = cubic_through(&y);
        let mut ends = [0.0, 1.0, 1.0, 1.0];
        let mut m = 1;
        for r in quadratic_roots(3.0 * p[3], 2.0 * p[2], p[1]) {
            if r > 0.0 && r < 1.0 {
                ends[m] = r;
                m += 1;
            }
        }
        ends[1..m].sort_unstable_by(f64::total_cmp);
        ends[m] = 1.0;
        for w in ends[..=m].windows(2) {
            let (mut a, mut b) = (w[0], w[1]);
            let (fa, fb) = (horner(&p, a), horner(&p, b));
            if fa == 0.0 || fb == 0.0 || (fa < 0.0) == (fb < 0.0) {
                continue;
            }
            // Newton on a monotone piece, safeguarded by bisection of the
            // bracket, to well below any rule's scale
            let rising = fb > fa;
            let mut x = 0.5 * (a + b);
            for _ in 0..60 {
                let fx = horner(&p, x);
                if (fx < 0.0) == rising {
                    a = x;
                } else {
                    b = x;
                }
                let slope = (3.0 * p[3] * x + 2.0 * p[2]) * x + p[1];
                let next = x - fx / slope;
                let next = if next > a && next < b { next } else { 0.5 * (a + b) };
                let done = (next - x).abs() <= 1e-13 || b - a <= 1e-12;
                x = next;
                if done {
                    break;
                }
            }
            self.xi[self.n] = x;
            self.of[self.n] = of;
            self.n += 1;
        }
    }

    /// The sub-intervals, sorted; `None` when there is no crossing.
    fn finish(mut self) -> Option<Self> {
        if self.n == 1 {
            return None;
        }
        let mut order: [(f64, u8); 11] = [(0.0, 0); 11];
        for i in 0..self.n {
            order[i] = (self.xi[i], self.of[i]);
        }
        order[1..self.n].sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        for i in 0..self.n {
            (self.xi[i], self.of[i]) = order[i];
        }
        self.xi[self.n] = 1.0;
        self.of[self.n] = 0;
        self.n += 1;
        Some(self)
    }
}

/// True if the cubic through samples `y` at ξ = 0, ⅓, ⅔, 1 has one sign on
/// all of [0, 1]: a cheap screen. Between samples the cubic departs from the
/// samples' linear interpolant by at most max|p″|/8 (in u = 3ξ), and |p″| ≤
/// |Δ²y| + 2|Δ³y|.
fn one_side(y: &[f64; 4]) -> bool {
    let d3 = (y[3] - 3.0 * y[2] + 3.0 * y[1] - y[0]).abs();
    let d2 = (y[2] - 2.0 * y[1] + y[0]).abs().max((y[3] - 2.0 * y[2] + y[1]).abs());
    let margin = d2 + d3;
    y.iter().all(|&v| v > margin) || y.iter().all(|&v| v < -margin)
}

/// Coefficients [p0, p1, p2, p3] (in ξ) of the cubic through samples at
/// ξ = 0, ⅓, ⅔, 1 (forward differences in u = 3ξ).
fn cubic_through(y: &[f64; 4]) -> [f64; 4] {
    let d1 = y[1] - y[0];
    let d2 = y[2] - 2.0 * y[1] + y[0];
    let d3 = y[3] - 3.0 * y[2] + 3.0 * y[1] - y[0];
    // p(u) = y0 + d1 u + d2 u(u−1)/2 + d3 u(u−1)(u−2)/6
    [y[0], 3.0 * (d1 - 0.5 * d2 + d3 / 3.0), 9.0 * (0.5 * d2 - 0.5 * d3), 27.0 * d3 / 6.0]
}

fn horner(p: &[f64; 4], x: f64) -> f64 {
    ((p[3] * x + p[2]) * x + p[1]) * x + p[0]
}

/// Real roots of a x² + b x + c (a linear or constant equation when a is
/// negligible), up to two; NaN for none.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return [f64::NAN; 2];
    }
    if a.abs() <= 1e-12 * scale {
        return [if b != 0.0 { -c / b } else { f64::NAN }, f64::NAN];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [f64::NAN; 2];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 { [0.0, f64::NAN] } else { [q / a, c / q] }
}

/// Calls `point(w, &(N, N′))` at every point of an element's contact rule
/// (9.7), w its weight (m): the four Gauss points `gauss` when `breaks` is
/// `None`, else four on each sub-interval.
fn for_each_point<const K: usize>(
    breaks: Option<Breaks>,
    gauss: &[([f64; K], [f64; K]); 4],
    at: ShapeAt<K>,
    len: f64,
    mut point: impl FnMut(f64, &([f64; K], [f64; K])),
) {
    let Some(b) = breaks else {
        for g in 0..4 {
            point(GAUSS4.w[g] * len, &gauss[g]);
        }
        return;
    };
    for w in b.xi[..b.n].windows(2) {
        let span = w[1] - w[0];
        if span <= 0.0 {
            continue;
        }
        for g in 0..4 {
            let (n, nd, _) = at(w[0] + span * GAUSS4.xi[g], len);
            point(GAUSS4.w[g] * span * len, &(n, nd));
        }
    }
}

/// The contact rule's breakpoints for configurations `cs` (9.7).
fn rule_for<const K: usize>(bed: &Seabed, cs: &[&[V3; K]], at: ShapeAt<K>, len: f64) -> Option<Breaks> {
    let mut b = Breaks::new();
    for (i, c) in cs.iter().enumerate() {
        b.add_crossings(bed, c, at, len, i as u8);
    }
    b.finish()
}

/// The derivative of [`step_point_force`] along a path on which x₀, x₁ and
/// t₀ change at rates `dx0`, `dx1` and `dt0`, N/m per unit of the path's
/// parameter: what the contact rule's breakpoints (9.7) need when they move.
#[allow(clippy::too_many_arguments)]
pub fn step_point_force_along(bed: &Seabed, x0: &V3, x1: &V3, t0: &V3, dx0: &V3, dx1: &V3, dt0: &V3, h: f64) -> V3 {
    let n = bed.normal;
    let (z0, z1) = (n.dot(x0), n.dot(x1));
    let (dz0, dz1) = (n.dot(dx0), n.dot(dx1));
    // the discrete gradient G is symmetric in (ζ₀, ζ₁)
    let (_, g1) = bed.discrete_slope(z0, z1);
    let (_, g0) = bed.discrete_slope(z1, z0);
    let mut df = -n * (g0 * dz0 + g1 * dz1);
    let depth = bed.level - 0.5 * (z0 + z1);
    if depth <= 0.0 || bed.is_conservative() {
        return df;
    }
    let d_depth = -0.5 * (dz0 + dz1);
    let v = (x1 - x0) / h;
    let dv = (dx1 - dx0) / h;
    if bed.damping > 0.0 {
        let (on, d_on) = if depth >= DAMPING_ONSET { (1.0, 0.0) } else { (depth / DAMPING_ONSET, 1.0 / DAMPING_ONSET) };
        let (vn, dvn) = (n.dot(&v), n.dot(&dv));
        df -= n * (bed.damping * (d_on * d_depth * vn + on * dvn));
    }
    let [mu_a, mu_l] = bed.friction;
    if mu_a > 0.0 || mu_l > 0.0 {
        // U = μ_l P + (μ_a − μ_l) a aᵀ with P = I − n nᵀ = a aᵀ + b bᵀ, so
        // φ = √(|P v|² + v_ε²) does not depend on the frame
        let p = M3::identity() - n * n.transpose();
        let (a, _) = bed.friction_frame(t0);
        let pt = p * t0;
        let da = if pt.norm() > 1e-9 * t0.norm().max(f64::MIN_POSITIVE) {
            (M3::identity() - a * a.transpose()) * (p * dt0) / pt.norm()
        } else {
            V3::zeros()
        };
        let u = p * v * mu_l + a * ((mu_a - mu_l) * a.dot(&v));
        let du = p * dv * mu_l + (da * a.dot(&v) + a * (da.dot(&v) + a.dot(&dv))) * (mu_a - mu_l);
        let pv = p * v;
        let phi = (pv.norm_squared() + bed.slip_velocity * bed.slip_velocity).sqrt();
        let dphi = pv.dot(&dv) / phi;
        let normal_force = bed.stiffness * depth;
        let dn = bed.stiffness * d_depth;
        df -= du * (normal_force / phi) + u * (dn / phi) - u * (normal_force * dphi / (phi * phi));
    }
    df
}

/// Adds the consistent nodal seabed forces of one element over a step to
/// `fe` (elastic) and `fd` (damping and friction), N, and −∂F/∂c₁ to `k`
/// (the contribution to the tangent of a residual r = … − F). The element's
/// fields are x = Σ N_j c_j with shape functions `at` (N, N′ at ξ) and
/// `gauss` (at the four Gauss points), on the rule (9.7) of the crossings at
/// t_n, at the trial t_{n+1} and at their midpoint; `c0`, `c1` the dofs at
/// t_n and at the trial t_{n+1}, `len` the element's reference length (m),
/// `h` the time step (s). The tangent includes the motion of the crossings
/// at t_{n+1} and at the midpoint (docs/theory.md (9.8)).
#[allow(clippy::too_many_arguments)]
pub fn element_step_force<const K: usize>(
    bed: &Seabed,
    c0: &[V3; K],
    c1: &[V3; K],
    gauss: &[([f64; K], [f64; K]); 4],
    at: ShapeAt<K>,
    len: f64,
    h: f64,
    fe: &mut [V3; K],
    fd: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    let cm: [V3; K] = std::array::from_fn(|j| (c0[j] + c1[j]) * 0.5);
    let rule = rule_for(bed, &[c0, c1, &cm], at, len);
    if let (Some(b), Some(k)) = (rule, k.as_deref_mut()) {
        moving_breaks_tangent(bed, &b, c0, c1, at, len, h, k);
    }
    for_each_point(rule, gauss, at, len, |wg, (n, nd)| {
        let (mut x0, mut x1, mut t0) = (V3::zeros(), V3::zeros(), V3::zeros());
        for j in 0..K {
            x0 += c0[j] * n[j];
            x1 += c1[j] * n[j];
            t0 += c0[j] * nd[j];
        }
        if bed.penetration(&x0) <= 0.0 && bed.penetration(&x1) <= 0.0 {
            return;
        }
        let p = step_point_force(bed, &x0, &x1, &t0, h);
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
    });
}

/// The part of −∂F/∂c₁ from the rule's breakpoints that move with c₁ (the
/// crossings at t_{n+1} and at the midpoint, (9.7)): F_i = Σ over the
/// sub-intervals of the four-point sums of φ_i = f N_i, so ∂F_i/∂b is
/// len Σ_g w_g [φ_i(x_g) + (b − a) ξ_g φ_i′(x_g)] from the sub-interval
/// [a, b] ending at b, and len Σ_g w_g [−φ_i(y_g) + (c − b)(1 − ξ_g) φ_i′(y_g)]
/// from [b, c] (φ′ = dφ/dξ); and a crossing of the configuration x_s =
/// s x₁ + (1 − s) x₀, n·x_s(b) = ζ_b, moves by ∂b/∂c₁ⱼ = −s N_j(b) n/(n·x_s′(b)).
/// (With an exact rule the two sums cancel: the integrand is continuous at
/// b. The discrete gradient's quotient, the damping's onset and the
/// friction are not polynomials, so what is left is of the size of the
/// rule's error, and Newton's convergence does not need it; the tangent
/// tests do.)
#[allow(clippy::too_many_arguments)]
fn moving_breaks_tangent<const K: usize>(
    bed: &Seabed,
    b: &Breaks,
    c0: &[V3; K],
    c1: &[V3; K],
    at: ShapeAt<K>,
    len: f64,
    h: f64,
    k: &mut [[M3; K]; K],
) {
    // φ_i and φ_i′ at ξ
    let integrand = |xi: f64| -> ([V3; K], [V3; K]) {
        let (n, nd, ndd) = at(xi, len);
        let (mut x0, mut x1, mut t0, mut t1, mut k0) =
            (V3::zeros(), V3::zeros(), V3::zeros(), V3::zeros(), V3::zeros());
        for j in 0..K {
            x0 += c0[j] * n[j];
            x1 += c1[j] * n[j];
            t0 += c0[j] * nd[j];
            t1 += c1[j] * nd[j];
            k0 += c0[j] * ndd[j];
        }
        if bed.penetration(&x0) <= 0.0 && bed.penetration(&x1) <= 0.0 {
            return ([V3::zeros(); K], [V3::zeros(); K]);
        }
        let p = step_point_force(bed, &x0, &x1, &t0, h);
        let f = p.elastic + p.dissipative;
        // d/dξ = len d/dS
        let df = step_point_force_along(bed, &x0, &x1, &t0, &(t0 * len), &(t1 * len), &(k0 * len), h);
        (std::array::from_fn(|i| f * n[i]), std::array::from_fn(|i| df * n[i] + f * (nd[i] * len)))
    };
    for m in 1..b.n - 1 {
        let s = match b.of[m] {
            1 => 1.0,
            2 => 0.5,
            _ => continue,
        };
        let (a, bm, c) = (b.xi[m - 1], b.xi[m], b.xi[m + 1]);
        let mut d = [V3::zeros(); K];
        for g in 0..4 {
            let (xg, wg) = (GAUSS4.xi[g], GAUSS4.w[g] * len);
            let (phi, dphi) = integrand(a + (bm - a) * xg);
            let (psi, dpsi) = integrand(bm + (c - bm) * xg);
            for i in 0..K {
                d[i] += (phi[i] + dphi[i] * ((bm - a) * xg) - psi[i] + dpsi[i] * ((c - bm) * (1.0 - xg))) * wg;
            }
        }
        // the crossing's slope n·x_s′ (per unit ξ) and its shape values
        let (nb, ndb, _) = at(bm, len);
        let slope: f64 = (0..K).map(|j| bed.normal.dot(&((c1[j] * s + c0[j] * (1.0 - s)) * (ndb[j] * len)))).sum();
        if slope.abs() <= f64::MIN_POSITIVE {
            continue;
        }
        for i in 0..K {
            for j in 0..K {
                // −∂F_i/∂c₁ⱼ = −d_i (∂b/∂c₁ⱼ)ᵀ = d_i nᵀ s N_j(b)/slope
                k[i][j] += d[i] * bed.normal.transpose() * (s * nb[j] / slope);
            }
        }
    }
}

/// Adds the static (elastic) seabed force of one element at dofs `c` to `f`,
/// N, and −∂F/∂c to `k`, on the rule (9.7) of its crossings: exactly the
/// gradient and Hessian of [`element_energy`].
pub fn element_static_force<const K: usize>(
    bed: &Seabed,
    c: &[V3; K],
    gauss: &[([f64; K], [f64; K]); 4],
    at: ShapeAt<K>,
    len: f64,
    f: &mut [V3; K],
    mut k: Option<&mut [[M3; K]; K]>,
) {
    let n_hat = bed.normal;
    for_each_point(rule_for(bed, &[c], at, len), gauss, at, len, |wg, (n, _)| {
        let mut x = V3::zeros();
        for j in 0..K {
            x += c[j] * n[j];
        }
        let (v1, v2) = bed.static_slope(n_hat.dot(&x));
        if v2 == 0.0 {
            return;
        }
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
    });
}

/// The seabed's elastic energy of one element at dofs `c`, ∫ V dS, J: exact
/// on the rule (9.7) of its crossings.
pub fn element_energy<const K: usize>(
    bed: &Seabed,
    c: &[V3; K],
    gauss: &[([f64; K], [f64; K]); 4],
    at: ShapeAt<K>,
    len: f64,
) -> f64 {
    let mut e = 0.0;
    for_each_point(rule_for(bed, &[c], at, len), gauss, at, len, |wg, (n, _)| {
        let x = (0..K).fold(V3::zeros(), |x, j| x + c[j] * n[j]);
        e += wg * bed.potential(bed.normal.dot(&x));
    });
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
/// (dofs `c`, their rates `v`) to `f`, N, on the rule (9.7) of its crossings.
pub fn element_state_force<const K: usize>(
    bed: &Seabed,
    c: &[V3; K],
    v: &[V3; K],
    gauss: &[([f64; K], [f64; K]); 4],
    at: ShapeAt<K>,
    len: f64,
    f: &mut [V3; K],
) {
    for_each_point(rule_for(bed, &[c], at, len), gauss, at, len, |wg, (n, nd)| {
        let (mut x, mut xv, mut t) = (V3::zeros(), V3::zeros(), V3::zeros());
        for j in 0..K {
            x += c[j] * n[j];
            xv += v[j] * n[j];
            t += c[j] * nd[j];
        }
        let p = state_point_force(bed, &x, &xv, &t);
        for i in 0..K {
            f[i] += p * (wg * n[i]);
        }
    });
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

    /// A Hermite element 10 m long, bowed, crossing a flat plane at z = −10
    /// twice (sagging through it), and its dofs lowered by `dz`.
    fn bowed(dz: f64) -> [V3; 4] {
        let h = 10.0;
        // r(S) from (0, 0, −9.99) to (h, 0, −9.995) with slopes −0.004 and +0.003:
        // it dips to about 2.5 mm below the plane near the middle
        [
            V3::new(0.0, 0.0, -9.99 - dz),
            V3::new(1.0, 0.0, -0.004),
            V3::new(h, 0.0, -9.995 - dz),
            V3::new(1.0, 0.0, 0.003),
        ]
    }

    /// ∫ f over an element by 4000 sub-intervals of four Gauss points.
    fn fine<const K: usize>(at: ShapeAt<K>, len: f64, f: impl Fn(&([f64; K], [f64; K], [f64; K])) -> f64) -> f64 {
        let m = 4000;
        let mut sum = 0.0;
        for i in 0..m {
            for g in 0..4 {
                let xi = (i as f64 + GAUSS4.xi[g]) / m as f64;
                sum += GAUSS4.w[g] * len / m as f64 * f(&at(xi, len));
            }
        }
        sum
    }

    #[test]
    fn the_rule_integrates_the_energy_of_a_crossing_element_exactly() {
        // (9.7): V = ½ k D δ₊² is a polynomial of degree 6 between the
        // crossings, which four points per sub-interval integrate exactly;
        // the reference is a fine composite rule (its error O((h/4000)²))
        let b = bed(0.0, 0.0, [0.0; 2]);
        let h = 10.0;
        for dz in [0.0, 0.001, -0.001, 0.004] {
            let c = bowed(dz);
            let exact = fine(hermite_at, h, |(n, _, _)| {
                let x = (0..4).fold(V3::zeros(), |x, j| x + c[j] * n[j]);
                b.potential(b.normal.dot(&x))
            });
            let e = element_energy(&b, &c, &crate::loads::fluid::hermite_at_gauss(h), hermite_at, h);
            assert!(exact > 0.0);
            assert!((e - exact).abs() <= 1e-6 * exact, "dz {dz}: {e} against {exact}");
        }
    }

    #[test]
    fn the_force_on_a_sloping_segment_is_the_closed_form_as_it_sinks() {
        // a straight cable segment at slope t = 0.01 whose low end is d below
        // the plane: F = k D ∫ (d − t s)₊ ds = k D d²/(2t) while the crossing
        // is within it, smooth in d; four fixed points made it piecewise
        // linear, each point taking its share at once
        let b = bed(0.0, 0.0, [0.0; 2]);
        let (l, t) = (10.0, 0.01);
        for d in [0.001, 0.013, 0.0371, 0.05, 0.0999] {
            let c = [V3::new(0.0, 0.0, -10.0 - d), V3::new(l, 0.0, -10.0 - d + t * l)];
            let mut f = [V3::zeros(); 2];
            element_static_force(&b, &c, &linear_at_gauss(l), linear_at, l, &mut f, None);
            let want = b.stiffness * d * d / (2.0 * t);
            let got = f[0].z + f[1].z;
            assert!((got - want).abs() <= 1e-10 * want, "d {d}: {got} against {want}");
            // and its moment about the low end: k D ∫ s (d − t s) ds = k D d³/(6 t²)
            let m = f[1].z * l;
            let want_m = b.stiffness * d.powi(3) / (6.0 * t * t);
            assert!((m - want_m).abs() <= 1e-10 * want_m, "d {d}: moment {m} against {want_m}");
        }
    }

    #[test]
    fn the_static_force_and_tangent_are_the_energy_s_derivatives_at_a_crossing() {
        let b = bed(0.0, 0.0, [0.0; 2]);
        let (h, gauss) = (10.0, crate::loads::fluid::hermite_at_gauss(10.0));
        let c = bowed(0.0005);
        let (mut f, mut k) = ([V3::zeros(); 4], [[M3::zeros(); 4]; 4]);
        element_static_force(&b, &c, &gauss, hermite_at, h, &mut f, Some(&mut k));
        let eps = 1e-7;
        for j in 0..4 {
            for a in 0..3 {
                let (mut cp, mut cm) = (c, c);
                cp[j][a] += eps;
                cm[j][a] -= eps;
                // force: −∂E/∂c, central differences of the exact energy
                let fd = -(element_energy(&b, &cp, &gauss, hermite_at, h)
                    - element_energy(&b, &cm, &gauss, hermite_at, h))
                    / (2.0 * eps);
                assert!(
                    (f[j][a] - fd).abs() <= 1e-6 * f[0].norm().max(f[2].norm()),
                    "f[{j}][{a}] {} against {fd}",
                    f[j][a]
                );
                // tangent: −∂F/∂c
                let (mut fp, mut fm) = ([V3::zeros(); 4], [V3::zeros(); 4]);
                element_static_force(&b, &cp, &gauss, hermite_at, h, &mut fp, None);
                element_static_force(&b, &cm, &gauss, hermite_at, h, &mut fm, None);
                for i in 0..4 {
                    let col = -(fp[i] - fm[i]) / (2.0 * eps);
                    let scale = b.stiffness * h;
                    assert!((k[i][j].column(a) - col).norm() <= 1e-6 * scale, "k[{i}][{j}] column {a}");
                }
            }
        }
    }

    #[test]
    fn the_step_s_elastic_work_is_the_exact_energy_difference_across_a_crossing() {
        // (9.5) with the rule (9.7): the rule of the step has the crossings of
        // both ends, so it integrates both energies exactly, and the discrete
        // gradient's work is their difference
        let b = bed(0.0, 3e5, [0.5, 0.8]);
        let (h, gauss) = (10.0, crate::loads::fluid::hermite_at_gauss(10.0));
        for (dz0, dz1) in [(-0.002, 0.003), (0.004, -0.001), (0.0, 0.0007)] {
            let (c0, c1) = (bowed(dz0), bowed(dz1));
            let (mut fe, mut fd) = ([V3::zeros(); 4], [V3::zeros(); 4]);
            element_step_force(&b, &c0, &c1, &gauss, hermite_at, h, 0.1, &mut fe, &mut fd, None);
            let work: f64 = (0..4).map(|j| fe[j].dot(&(c1[j] - c0[j]))).sum();
            let de = element_energy(&b, &c1, &gauss, hermite_at, h) - element_energy(&b, &c0, &gauss, hermite_at, h);
            assert!((work + de).abs() <= 1e-9 * de.abs(), "{dz0} → {dz1}: work {work}, ΔE {de}");
            let dissipated: f64 = (0..4).map(|j| fd[j].dot(&(c1[j] - c0[j]))).sum();
            assert!(dissipated <= 0.0);
        }
    }

    #[test]
    fn the_crossings_are_found_where_the_cubic_changes_sign() {
        let b = bed(0.0, 0.0, [0.0; 2]);
        for dz in [0.0, 0.001, 0.0024, -0.001] {
            let c = bowed(dz);
            let z = |xi: f64| {
                let (n, _, _) = hermite_at(xi, 10.0);
                -b.penetration(&(0..4).fold(V3::zeros(), |x, j| x + c[j] * n[j]))
            };
            let mut br = Breaks::new();
            br.add_crossings(&b, &c, hermite_at, 10.0, 0);
            // every sign change of a fine sampling has a crossing within its cell
            let m = 10_000;
            let changes: Vec<f64> = (0..m)
                .filter(|&i| z(i as f64 / m as f64) * z((i + 1) as f64 / m as f64) < 0.0)
                .map(|i| i as f64 / m as f64)
                .collect();
            assert_eq!(changes.len(), br.n - 1, "dz {dz}");
            for (x, r) in changes.iter().zip(&br.xi[1..br.n]) {
                assert!(*r >= *x && *r <= x + 1.0 / m as f64, "dz {dz}: {r} outside [{x}, +1e-4]");
                assert!(z(*r).abs() < 1e-12, "dz {dz}: height {} at the crossing", z(*r));
            }
        }
    }

    #[test]
    fn the_step_tangent_with_moving_crossings_matches_finite_differences() {
        // the rule's breakpoints at t_{n+1} and at the midpoint move with c₁
        // (9.7); with damping, its onset and friction the integrands are not
        // polynomials, so the tangent needs their motion (moving_breaks_tangent)
        let b = bed(0.0, 3e5, [0.5, 0.8]);
        let (h, gauss) = (10.0, crate::loads::fluid::hermite_at_gauss(10.0));
        let mut c0 = bowed(-0.002);
        c0[0].y += 0.01;
        let mut c1 = bowed(0.003);
        c1[2].x += 0.02;
        c1[2].y -= 0.015;
        c1[3].z += 0.001;
        let dt = 0.1;
        let force = |c: &[V3; 4]| {
            let (mut fe, mut fd) = ([V3::zeros(); 4], [V3::zeros(); 4]);
            element_step_force(&b, &c0, c, &gauss, hermite_at, h, dt, &mut fe, &mut fd, None);
            std::array::from_fn::<V3, 4, _>(|i| fe[i] + fd[i])
        };
        let mut k = [[M3::zeros(); 4]; 4];
        let (mut fe, mut fd) = ([V3::zeros(); 4], [V3::zeros(); 4]);
        element_step_force(&b, &c0, &c1, &gauss, hermite_at, h, dt, &mut fe, &mut fd, Some(&mut k));
        let mut br = Breaks::new();
        br.add_crossings(&b, &c1, hermite_at, h, 1);
        assert!(br.n > 1, "the end configuration crosses the plane");
        let scale = (0..4).flat_map(|i| (0..4).map(move |j| (i, j))).fold(0.0f64, |m, (i, j)| m.max(k[i][j].norm()));
        let eps = 1e-7;
        for j in 0..4 {
            for a in 0..3 {
                let (mut cp, mut cm) = (c1, c1);
                cp[j][a] += eps;
                cm[j][a] -= eps;
                let (fp, fm) = (force(&cp), force(&cm));
                for i in 0..4 {
                    let col = -(fp[i] - fm[i]) / (2.0 * eps);
                    let err = (k[i][j].column(a) - col).norm();
                    assert!(err <= 1e-6 * scale, "k[{i}][{j}] column {a}: {:?} against {col:?}", k[i][j].column(a));
                }
            }
        }
    }
}
