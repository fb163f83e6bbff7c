//! The rod's static equations (docs/theory.md §4): f_int(q) − f_ext(q) = 0
//! with weight, buoyancy, point forces and steady current drag, and the
//! analytic catenary start.

use super::Rod;
use super::element::{ElemDofs, NGP};
use crate::loads::current::Current;
use crate::loads::fluid::hermite_at_gauss;
use crate::loads::morison::{DragCoefficients, drag};
use crate::loads::seabed::{self, Seabed};
use crate::loads::surface::{self, FreeSurface};
use crate::loads::weight::VerticalLoad;
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::shape::{GAUSS4, hermite, hermite_ds};
use crate::math::{M3, V3, frame_from_tangent};
use crate::model::RodConfig;
use crate::model::catenary::{self, Catenary};
use crate::model::sections::PerElement;
use crate::model::statics::{Homotopy, StaticEquations, StaticSolution};

/// Loads of a static problem.
#[derive(Debug, Clone)]
pub struct StaticLoads {
    /// Weight, buoyancy and buoyancy modules.
    pub vertical: VerticalLoad,
    /// Concentrated forces (N) at end nodes.
    pub point_forces: Vec<(usize, V3)>,
    /// Steady current drag, coefficients per element (the current is
    /// included only when asked).
    pub drag: Option<(PerElement<DragCoefficients>, Current)>,
    /// The seabed's elastic support under each element (frictionless: docs/theory.md §9.3).
    pub seabed: Option<PerElement<Seabed>>,
    /// The free surface as each element feels it: the emerged part without buoyancy (§10).
    pub surface: Option<PerElement<FreeSurface>>,
}

impl StaticLoads {
    pub fn gravity_only(vertical: VerticalLoad) -> Self {
        StaticLoads { vertical, point_forces: Vec::new(), drag: None, seabed: None, surface: None }
    }
}

/// Consistent nodal loads ∫ N_k q(S) e_z dS of the vertical load (exact:
/// Gauss on each piece where q is constant).
pub fn vertical_load_vector(rod: &Rod, load: &VerticalLoad) -> Vec<f64> {
    let mut f = vec![0.0; rod.n_dof()];
    let g2 = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
    for e in 0..rod.n_el {
        let s0 = rod.s_node(e);
        let pts = load.breakpoints(s0, s0 + rod.h);
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let q = load.at(0.5 * (a + b));
            for &t in &g2 {
                let s = a + t * (b - a);
                let n = hermite((s - s0) / rod.h, rod.h);
                let wq = 0.5 * (b - a) * q;
                let dofs = [Rod::x_dof(e), Rod::xp_dof(e), Rod::x_dof(e + 1), Rod::xp_dof(e + 1)];
                for k in 0..4 {
                    f[dofs[k] + 2] += n[k] * wq;
                }
            }
        }
    }
    f
}

/// Adds the steady-current drag on a motionless line to the residual
/// (r −= f_drag) and its derivative to the tangent; with a free surface,
/// on the submerged fraction only (§10).
pub fn add_static_drag(
    rod: &Rod,
    cfg: &RodConfig,
    ks: &PerElement<DragCoefficients>,
    current: &Current,
    surfaces: Option<&PerElement<FreeSurface>>,
    r: &mut [f64],
    mut sys: Option<&mut BandedSystem>,
) {
    for e in 0..rod.n_el {
        let (k, surface) = (ks.at(e), surfaces.map(|s| s.at(e)));
        let el = ElemDofs::gather(cfg, e);
        let dofs = [Rod::x_dof(e), Rod::xp_dof(e), Rod::x_dof(e + 1), Rod::xp_dof(e + 1)];
        let mut ke = [[M3::zeros(); 4]; 4];
        for g in 0..NGP {
            let xi = GAUSS4.xi[g];
            let wg = GAUSS4.w[g] * rod.h;
            let n = hermite(xi, rod.h);
            let nd = hermite_ds(xi, rod.h);
            let x: V3 = (0..4).map(|k| el.c[k] * n[k]).sum();
            let p: V3 = (0..4).map(|k| el.c[k] * nd[k]).sum();
            let len = p.norm();
            let t = p / len;
            let s = rod.s_node(e) + xi * rod.h;
            let (vc, dvc_dz) = current.velocity(s, x.z);
            let d = drag(k, &vc, &t);
            let mut force = d.force * len; // per unit reference length
            // ∂F/∂x (through the depth dependence of the current) and ∂F/∂r'
            let mut df_dx = d.d_vrel * dvc_dz * V3::z().transpose() * len;
            let mut df_dp = d.d_tangent * (M3::identity() - t * t.transpose()) + d.force * t.transpose();
            if let Some(s) = surface {
                // only the submerged fraction feels the current (§10)
                let (sub, dsub) = s.submerged(x.z);
                df_dx = df_dx * sub + force * V3::z().transpose() * dsub;
                df_dp *= sub;
                force *= sub;
            }
            for a in 0..4 {
                for c in 0..3 {
                    r[dofs[a] + c] -= wg * n[a] * force[c];
                }
                for b in 0..4 {
                    ke[a][b] -= (df_dx * n[b] + df_dp * nd[b]) * (wg * n[a]);
                }
            }
        }
        if let Some(sys) = sys.as_deref_mut() {
            add_centreline_blocks(sys, &dofs, &ke);
        }
    }
}

/// Adds an element's 4 × 4 blocks (3 × 3 each) on its centreline unknowns
/// `dofs` (r_a, r'_a, r_b, r'_b) to the tangent.
fn add_centreline_blocks(sys: &mut BandedSystem, dofs: &[usize; 4], ke: &[[M3; 4]; 4]) {
    for a in 0..4 {
        for b in 0..4 {
            for i in 0..3 {
                for j in 0..3 {
                    sys.add(dofs[a] + i, dofs[b] + j, ke[a][b][(i, j)]);
                }
            }
        }
    }
}

/// Adds an element force `element(c, f, k)` (on the dofs c = (r_a, r'_a,
/// r_b, r'_b), adding the force to f and −∂F/∂c to k) of every element not
/// `skip`ped to the residual (r −= f) and the tangent.
fn add_element_loads(
    rod: &Rod,
    cfg: &RodConfig,
    skip: impl Fn(usize, &[V3; 4]) -> bool,
    element: impl Fn(usize, &[V3; 4], &mut [V3; 4], Option<&mut [[M3; 4]; 4]>),
    r: &mut [f64],
    mut sys: Option<&mut BandedSystem>,
) {
    for e in 0..rod.n_el {
        let c = [cfg.x[e], cfg.xp[e], cfg.x[e + 1], cfg.xp[e + 1]];
        if skip(e, &c) {
            continue;
        }
        let mut f = [V3::zeros(); 4];
        let mut ke = [[M3::zeros(); 4]; 4];
        element(e, &c, &mut f, sys.is_some().then_some(&mut ke));
        let dofs = [Rod::x_dof(e), Rod::xp_dof(e), Rod::x_dof(e + 1), Rod::xp_dof(e + 1)];
        for a in 0..4 {
            for i in 0..3 {
                r[dofs[a] + i] -= f[a][i];
            }
        }
        if let Some(sys) = sys.as_deref_mut() {
            add_centreline_blocks(sys, &dofs, &ke);
        }
    }
}

/// Adds the seabed's elastic force to the residual (r −= f) and its
/// derivative to the tangent (§9.3).
pub fn add_static_seabed(
    rod: &Rod,
    cfg: &RodConfig,
    bed: &PerElement<Seabed>,
    r: &mut [f64],
    sys: Option<&mut BandedSystem>,
) {
    let shapes = hermite_at_gauss(rod.h);
    let skip = |e: usize, c: &[V3; 4]| seabed::clear_of(bed.at(e), &[c[0], c[2]], rod.h);
    let element = |e: usize, c: &[V3; 4], f: &mut [V3; 4], k: Option<&mut [[M3; 4]; 4]>| {
        seabed::element_static_force(bed.at(e), c, &shapes, seabed::hermite_at, rod.h, f, k)
    };
    add_element_loads(rod, cfg, skip, element, r, sys);
}

/// Adds the free surface's correction (the emerged part's buoyancy taken
/// off) to the residual (r −= f) and its derivative to the tangent (§10).
pub fn add_static_surface(
    rod: &Rod,
    cfg: &RodConfig,
    s: &PerElement<FreeSurface>,
    r: &mut [f64],
    sys: Option<&mut BandedSystem>,
) {
    let skip = |e: usize, c: &[V3; 4]| s.at(e).hermite_below(c, rod.h);
    let shape = |xi| crate::math::shape::hermite(xi, rod.h);
    let element = |e: usize, c: &[V3; 4], f: &mut [V3; 4], k: Option<&mut [[M3; 4]; 4]>| {
        surface::element_static_force(s.at(e), c, shape, rod.h, None, f, k)
    };
    add_element_loads(rod, cfg, skip, element, r, sys);
}

/// What a [`StaticProblem`] owns beyond its rod and loads (its constant
/// load vector, its fixed unknowns and its force scale), kept to build it
/// again without allocating.
#[derive(Debug, Clone)]
pub struct StaticParts {
    f_const: Vec<f64>,
    fixed: Vec<usize>,
    force_scale: f64,
}

/// The static problem assembled on a rod.
pub struct StaticProblem<'a> {
    pub rod: &'a Rod,
    pub loads: &'a StaticLoads,
    f_const: Vec<f64>,
    fixed: Vec<usize>,
    /// Scale of forces for the convergence test, N.
    force_scale: f64,
}

impl<'a> StaticProblem<'a> {
    pub fn new(rod: &'a Rod, loads: &'a StaticLoads) -> Self {
        let mut f_const = vertical_load_vector(rod, &loads.vertical);
        for &(a, f) in &loads.point_forces {
            for c in 0..3 {
                f_const[Rod::x_dof(a) + c] += f[c];
            }
        }
        let mut fixed = rod.fixed_dofs();
        fixed.sort_unstable();
        let force_scale =
            (0..=rod.n_el).map(|a| (0..3).map(|c| f_const[Rod::x_dof(a) + c].abs()).sum::<f64>()).sum::<f64>();
        StaticProblem { rod, loads, f_const, fixed, force_scale }
    }

    /// The problem on `rod` and `loads` from the parts a problem on them
    /// gave back ([`StaticProblem::into_parts`]): the same problem,
    /// nothing allocated.
    pub fn from_parts(rod: &'a Rod, loads: &'a StaticLoads, parts: StaticParts) -> Self {
        let StaticParts { f_const, fixed, force_scale } = parts;
        StaticProblem { rod, loads, f_const, fixed, force_scale }
    }

    /// What the problem owns, to build it again on the same rod and loads
    /// without allocating ([`StaticProblem::from_parts`]).
    pub fn into_parts(self) -> StaticParts {
        StaticParts { f_const: self.f_const, fixed: self.fixed, force_scale: self.force_scale }
    }

    /// Residual r = f_int − f_ext (reduced, local basis at twist-held ends), and
    /// the tangent if asked. Rows of fixed unknowns are left in place.
    pub fn residual(&self, cfg: &RodConfig, r: &mut [f64], mut sys: Option<&mut BandedSystem>) {
        r.iter_mut().for_each(|v| *v = 0.0);
        if let Some(s) = sys.as_deref_mut() {
            s.clear();
        }
        self.rod.add_internal_force(cfg, r, sys.as_deref_mut());
        for (ri, fi) in r.iter_mut().zip(&self.f_const) {
            *ri -= fi;
        }
        if let Some((k, current)) = &self.loads.drag {
            add_static_drag(self.rod, cfg, k, current, self.loads.surface.as_ref(), r, sys.as_deref_mut());
        }
        if let Some(bed) = &self.loads.seabed {
            add_static_seabed(self.rod, cfg, bed, r, sys.as_deref_mut());
        }
        if let Some(s) = &self.loads.surface {
            add_static_surface(self.rod, cfg, s, r, sys.as_deref_mut());
        }
        // a flex joint against the vessel's frame it holds (§15)
        if let Some(joint) = &self.rod.flex_joint
            && let Some(f) = joint.frame
        {
            let (m, k) = joint.static_moment(&cfg.d[0], &f);
            let it = Rod::theta_dof(0);
            for a in 0..3 {
                r[it + a] += m[a];
            }
            if let Some(sys) = sys.as_deref_mut() {
                for a in 0..3 {
                    for b in 0..3 {
                        sys.add(it + a, it + b, k[(a, b)]);
                    }
                }
            }
        }
        self.rod.to_local_basis(cfg, r, sys);
    }

    /// Reactions (force of the supports on the line) from a residual.
    pub fn reactions(&self, r: &[f64]) -> [V3; 2] {
        let i0 = Rod::x_dof(0);
        let i1 = Rod::x_dof(self.rod.n_el);
        [V3::new(r[i0], r[i0 + 1], r[i0 + 2]), V3::new(r[i1], r[i1 + 1], r[i1 + 2])]
    }

    /// The Newton correction du = −K⁻¹ r with the fixed unknowns held, each
    /// director rotation limited to 0.25 rad.
    pub fn correction(&self, sys: &mut BandedSystem, r: &mut [f64], du: &mut [f64]) -> Result<(), LinearSolveError> {
        for &i in &self.fixed {
            r[i] = 0.0;
            sys.constrain(i);
        }
        sys.factorize()?;
        for (d, v) in du.iter_mut().zip(r.iter()) {
            *d = -v;
        }
        sys.solve_in_place(du)?;
        self.rod.limit_rotation_increments(du, 0.25);
        Ok(())
    }

    /// Largest free residual component relative to the load scale.
    pub fn relative_residual(&self, r: &[f64], scale: f64) -> f64 {
        let mut m: f64 = 0.0;
        let mut fi = 0;
        for (i, v) in r.iter().enumerate() {
            if fi < self.fixed.len() && self.fixed[fi] == i {
                fi += 1;
                continue;
            }
            // rows 0..3 of each 12-block are forces; the others are r'- and rotation
            // equations with units N m: measure those per element length
            let w = if i % 12 < 3 { 1.0 } else { 1.0 / self.rod.h };
            m = m.max((v * w).abs());
        }
        if m.is_nan() { f64::INFINITY } else { m / scale }
    }
}

impl StaticEquations for StaticProblem<'_> {
    type Config = RodConfig;

    fn n_dof(&self) -> usize {
        self.rod.n_dof()
    }

    fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        self.rod.new_system()
    }

    fn residual(&self, cfg: &RodConfig, r: &mut [f64], sys: Option<&mut BandedSystem>) {
        StaticProblem::residual(self, cfg, r, sys)
    }

    fn relative(&self, r: &[f64]) -> f64 {
        self.relative_residual(r, self.force_scale.max(f64::MIN_POSITIVE))
    }

    fn correction(&self, sys: &mut BandedSystem, r: &mut [f64], du: &mut [f64]) -> Result<(), LinearSolveError> {
        StaticProblem::correction(self, sys, r, du)
    }

    fn apply_increment(&self, cfg: &mut RodConfig, du: &[f64]) {
        self.rod.apply_increment(cfg, du)
    }

    fn is_finite(cfg: &RodConfig) -> bool {
        cfg.is_finite()
    }

    /// 1 on position and slope unknowns, h² on rotations.
    fn pseudo_mass(&self, i: usize) -> f64 {
        if i % 12 < 6 { 1.0 } else { self.rod.h * self.rod.h }
    }

    fn mu_unit(&self) -> f64 {
        self.force_scale.max(f64::MIN_POSITIVE) / self.rod.length
    }

    fn roundoff(&self, cfg: &RodConfig) -> f64 {
        Homotopy::residual_roundoff(self, cfg) / self.force_scale.max(f64::MIN_POSITIVE)
    }

    fn solution(&self, cfg: RodConfig, r: &[f64], iterations: usize, steps: usize, residual: f64) -> StaticSolution {
        StaticSolution { config: cfg, iterations, continuation_steps: steps, residual, reactions: self.reactions(r) }
    }
}

/// A rod configuration on the analytic elastic catenary from `top` to
/// `anchor` (directors: d3 along the cable, d2 normal to its vertical plane).
/// Falls back to the straight chord when the catenary has no solution (for
/// example an anchor straight below the hang-off).
pub fn catenary_start(rod: &Rod, load: &VerticalLoad, top: V3, anchor: V3) -> RodConfig {
    seabed_start(rod, load, top, anchor, None)
}

/// The start of the statics on a seabed (§9.3): where the hanging catenary
/// would dip below the seabed, the line resting on it from its touchdown
/// ([`catenary::Touchdown`], the seabed taken flat at its height under the
/// anchor); otherwise [`catenary_start`].
pub fn seabed_start(rod: &Rod, load: &VerticalLoad, top: V3, anchor: V3, bed: Option<&Seabed>) -> RodConfig {
    let chord = anchor - top;
    let horiz = V3::new(chord.x, chord.y, 0.0);
    let span = horiz.norm();
    let eh = if span > 1e-9 * rod.length { horiz / span } else { V3::x() };
    let d2_hint = V3::z().cross(&eh);
    let ea = rod.stiffness.axial;
    let on_curve = |point: &dyn Fn(f64) -> catenary::CablePoint| {
        let to3 = |h: f64, z: f64| top + eh * h + V3::z() * z;
        let tangent = |p: &catenary::CablePoint| {
            let t = p.tension();
            let stretch = 1.0 + t / ea;
            (eh * p.n_h + V3::z() * p.n_z) / t * stretch
        };
        let mut cfg = RodConfig { x: Vec::new(), xp: Vec::new(), d: Vec::new() };
        for a in 0..=rod.n_el {
            let p = point(rod.s_node(a));
            cfg.x.push(to3(p.x, p.z));
            cfg.xp.push(tangent(&p));
        }
        // pin the ends exactly
        cfg.x[0] = top;
        cfg.x[rod.n_el] = anchor;
        for j in 0..rod.n_director_nodes() {
            let p = point(0.5 * j as f64 * rod.h);
            cfg.d.push(frame_from_tangent(&tangent(&p), &d2_hint));
        }
        cfg
    };
    if let Some(cat) = Catenary::solve(rod.length, load, ea, span, chord.z) {
        let cfg = on_curve(&|s| cat.at(s));
        let below = |c: &RodConfig| bed.is_some_and(|b| c.x.iter().any(|x| b.penetration(x) > 0.0));
        if cfg.is_finite() && !below(&cfg) {
            return cfg;
        }
        if let Some(b) = bed {
            let level = b.height_at(anchor.x, anchor.y) - top.z;
            if let Some(td) = catenary::Touchdown::solve(rod.length, load, ea, span, chord.z, level) {
                let cfg = on_curve(&|s| td.at(s));
                if cfg.is_finite() {
                    return cfg;
                }
            }
        }
        if cfg.is_finite() {
            return cfg;
        }
    }
    let mut cfg = rod.straight(top, chord, d2_hint);
    let stretch = chord.norm() / rod.length;
    for a in 0..=rod.n_el {
        cfg.x[a] = top + chord * (a as f64 / rod.n_el as f64);
        cfg.xp[a] *= stretch;
    }
    cfg
}

impl Homotopy for StaticProblem<'_> {
    fn force_scale(&self) -> f64 {
        self.force_scale
    }

    fn relative_residual(&self, r: &[f64], scale: f64) -> f64 {
        StaticProblem::relative_residual(self, r, scale)
    }

    fn residual_roundoff(&self, cfg: &RodConfig) -> f64 {
        let extent = cfg.x.iter().fold(0.0f64, |m, x| m.max(x.norm())).max(self.rod.length);
        let bed = self.loads.seabed.as_ref().map_or(0.0, |b| b.roundoff(self.rod.h, extent));
        self.rod.residual_roundoff(cfg).max(bed)
    }
}
