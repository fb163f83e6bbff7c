//! Static equilibrium (docs/theory.md §4): Newton–Raphson with the consistent
//! tangent on f_int(q) − f_ext(q) = 0, started from an analytic elastic
//! catenary, with a continuation (homotopy) R(q) − (1 − s) R(q₀) = 0, s: 0 → 1,
//! when the full problem does not converge from the start.

pub mod catenary;
pub mod report;

use crate::hydro::current::Current;
use crate::hydro::morison::{DragCoefficients, drag};
use crate::hydro::weight::VerticalLoad;
use crate::linsolve::{BandedSystem, LinearSolveError};
use crate::rod::element::{ElemDofs, NGP};
use crate::rod::kinematics::{M3, RodConfig, V3, frame_from_tangent};
use crate::rod::model::Rod;
use crate::rod::shape::{GAUSS4, hermite, hermite_ds};
use catenary::Catenary;

/// Loads of a static problem.
#[derive(Debug, Clone)]
pub struct StaticLoads {
    /// Weight, buoyancy and buoyancy modules.
    pub vertical: VerticalLoad,
    /// Concentrated forces (N) at end nodes.
    pub point_forces: Vec<(usize, V3)>,
    /// Steady current drag (the current is included only when asked).
    pub drag: Option<(DragCoefficients, Current)>,
}

impl StaticLoads {
    pub fn gravity_only(vertical: VerticalLoad) -> Self {
        StaticLoads { vertical, point_forces: Vec::new(), drag: None }
    }
}

/// Newton settings.
#[derive(Debug, Clone, Copy)]
pub struct StaticOptions {
    /// Converged when every residual component is below `tolerance` times the
    /// load scale (moments and r'-equations measured per element length).
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Smallest continuation step before giving up.
    pub min_continuation_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions { tolerance: 1e-10, max_iterations: 40, min_continuation_step: 1.0 / 1024.0 }
    }
}

/// A converged static state.
#[derive(Debug, Clone)]
pub struct StaticSolution {
    pub config: RodConfig,
    /// Newton iterations over all continuation steps.
    pub iterations: usize,
    /// Continuation steps (1 if Newton converged from the start).
    pub continuation_steps: usize,
    /// Final relative residual.
    pub residual: f64,
    /// Force the supports exert on the line at S = 0 and S = L, N
    /// (the reactions of the discrete equations).
    pub reactions: [V3; 2],
}

/// Why a static solution could not be found.
#[derive(Debug, Clone, PartialEq)]
pub enum StaticsError {
    /// Newton did not converge even with the smallest continuation step.
    NotConverged { iterations: usize, residual: f64, continuation: f64 },
    /// The tangent is singular or not finite.
    Linear(LinearSolveError),
}

impl std::fmt::Display for StaticsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StaticsError::NotConverged { iterations, residual, continuation } => write!(
                f,
                "static equilibrium not found: Newton stopped after {iterations} iterations with relative \
                 residual {residual:.3e} at load continuation {:.1}% (the line may have no equilibrium \
                 with these ends and loads, or need more elements)",
                continuation * 100.0
            ),
            StaticsError::Linear(e) => write!(f, "static equilibrium not found: {e}"),
        }
    }
}

impl std::error::Error for StaticsError {}

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
/// (r −= f_drag) and its derivative to the tangent.
pub fn add_static_drag(
    rod: &Rod,
    cfg: &RodConfig,
    k: &DragCoefficients,
    current: &Current,
    r: &mut [f64],
    mut sys: Option<&mut BandedSystem>,
) {
    for e in 0..rod.n_el {
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
            let force = d.force * len; // per unit reference length
            // ∂F/∂x (through the depth dependence of the current) and ∂F/∂r'
            let df_dx = d.d_vrel * dvc_dz * V3::z().transpose() * len;
            let df_dp = d.d_tangent * (M3::identity() - t * t.transpose()) + d.force * t.transpose();
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
    }
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
            add_static_drag(self.rod, cfg, k, current, r, sys.as_deref_mut());
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

/// Finds the static equilibrium from `initial`: the homotopy continuation,
/// and, if it stalls (a turning point of the homotopy path), pseudo-transient
/// continuation from the same start.
pub fn solve(
    rod: &Rod,
    loads: &StaticLoads,
    initial: RodConfig,
    opts: &StaticOptions,
) -> Result<StaticSolution, StaticsError> {
    match solve_homotopy(rod, loads, initial.clone(), opts) {
        Ok(s) => Ok(s),
        Err(StaticsError::NotConverged { iterations, .. }) => {
            pseudo_transient(&StaticProblem::new(rod, loads), initial, opts.tolerance, iterations, 10.0)
        }
        Err(e) => Err(e),
    }
}

/// A static problem that pseudo-transient continuation can drive: the rod
/// ([`StaticProblem`]) and the cable ([`crate::cable::statics::CableStatics`]).
pub trait Relaxation {
    type Config: Clone;
    fn n_dof(&self) -> usize;
    fn new_system(&self) -> Result<BandedSystem, LinearSolveError>;
    /// R(q) into `r` and, if given, ∂R/∂q into `sys`.
    fn residual(&self, cfg: &Self::Config, r: &mut [f64], sys: Option<&mut BandedSystem>);
    /// Largest free residual component relative to the force scale.
    fn relative(&self, r: &[f64]) -> f64;
    /// The Newton correction du = −K⁻¹ r with the fixed unknowns held.
    fn correction(&self, sys: &mut BandedSystem, r: &mut [f64], du: &mut [f64]) -> Result<(), LinearSolveError>;
    fn apply_increment(&self, cfg: &mut Self::Config, du: &[f64]);
    fn is_finite(cfg: &Self::Config) -> bool;
    /// Weight D_i of unknown i in the regularisation μ D (q − q_k).
    fn pseudo_mass(&self, i: usize) -> f64;
    /// Unit of μ: force scale over length, N/m.
    fn mu_unit(&self) -> f64;
    /// Round-off of the relative residual at `cfg`.
    fn roundoff(&self, cfg: &Self::Config) -> f64;
    /// The converged state with its residual `r`.
    fn solution(&self, cfg: Self::Config, r: &[f64], iterations: usize, steps: usize, residual: f64) -> StaticSolution;
}

/// Pseudo-transient continuation (docs/theory.md §4): a sequence of
/// regularised problems R(q) + μ D (q − q_k) = 0, each started from the last,
/// with μ decreased while Newton converges easily and increased when it does
/// not; ends with Newton on R(q) = 0 alone. Robust where the homotopy path
/// turns, or from a start with no stiffness. `mu_start` in units of
/// [`Relaxation::mu_unit`] (0: plain Newton first).
pub fn pseudo_transient<P: Relaxation>(
    p: &P,
    initial: P::Config,
    tolerance: f64,
    prior_iterations: usize,
    mu_start: f64,
) -> Result<StaticSolution, StaticsError> {
    let n = p.n_dof();
    let mut sys = p.new_system().map_err(StaticsError::Linear)?;
    let mut r = vec![0.0; n];
    let mut du = vec![0.0; n];
    let mut acc = vec![0.0; n];
    let mut cfg = initial;
    let tolerance = tolerance.max(10.0 * p.roundoff(&cfg));
    let unit = p.mu_unit();
    let mut mu = mu_start * unit;
    let mu_max = 1e13 * unit;
    let mut iterations = prior_iterations;
    let mut steps = 0;
    let mut last_res = f64::INFINITY;
    for _ in 0..2000 {
        let saved = cfg.clone();
        acc.iter_mut().for_each(|v| *v = 0.0);
        let mut ok = false;
        let mut newton_its = 0;
        for _ in 0..12 {
            p.residual(&cfg, &mut r, Some(&mut sys));
            let res_plain = p.relative(&r);
            last_res = res_plain;
            if mu == 0.0 && res_plain <= tolerance {
                return Ok(p.solution(cfg, &r, iterations, steps, res_plain));
            }
            for i in 0..n {
                let d = p.pseudo_mass(i);
                r[i] += mu * d * acc[i];
                sys.add(i, i, mu * d);
            }
            let res = p.relative(&r);
            if !res.is_finite() {
                break;
            }
            if res <= tolerance.max(1e-8) && mu > 0.0 {
                ok = true;
                break;
            }
            iterations += 1;
            newton_its += 1;
            if p.correction(&mut sys, &mut r, &mut du).is_err() {
                break;
            }
            p.apply_increment(&mut cfg, &du);
            for i in 0..n {
                acc[i] += du[i];
            }
            if !P::is_finite(&cfg) {
                break;
            }
        }
        if ok {
            steps += 1;
            // an easy pseudo-step: lighten the regularisation; below a
            // threshold, drop it and finish with plain Newton
            mu *= if newton_its <= 3 { 0.2 } else { 0.6 };
            if mu < 1e-9 * unit {
                mu = 0.0;
            }
        } else {
            cfg = saved;
            if mu == 0.0 {
                // plain Newton failed: from the start, the full regularisation;
                // near the end of the continuation, a slight one
                mu = if steps == 0 { 10.0 * unit } else { 1e-6 * unit };
            } else {
                mu *= 4.0;
            }
            if mu > mu_max {
                break;
            }
        }
    }
    Err(StaticsError::NotConverged { iterations, residual: last_res, continuation: 1.0 })
}

impl Relaxation for StaticProblem<'_> {
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
        self.rod.residual_roundoff(cfg) / self.force_scale.max(f64::MIN_POSITIVE)
    }

    fn solution(&self, cfg: RodConfig, r: &[f64], iterations: usize, steps: usize, residual: f64) -> StaticSolution {
        StaticSolution { config: cfg, iterations, continuation_steps: steps, residual, reactions: self.reactions(r) }
    }
}

/// The homotopy continuation R(q) − (1 − s) R(q₀) = 0, s: 0 → 1.
fn solve_homotopy(
    rod: &Rod,
    loads: &StaticLoads,
    initial: RodConfig,
    opts: &StaticOptions,
) -> Result<StaticSolution, StaticsError> {
    let prob = StaticProblem::new(rod, loads);
    let n = rod.n_dof();
    let mut sys = rod.new_system().map_err(StaticsError::Linear)?;
    let mut r = vec![0.0; n];
    let mut du = vec![0.0; n];
    let mut cfg = initial;
    prob.residual(&cfg, &mut r, None);
    // offset of the homotopy: the out-of-balance force of the start
    let r0 = r.clone();
    let internal_scale = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = prob.force_scale.max(1e-6 * internal_scale).max(f64::MIN_POSITIVE);
    // The residual cannot be evaluated more precisely than the axial force from
    // r' = (r_b − r_a)/h·…, i.e. EA·ε·|r|/h: never ask for less than 10× that.
    let floor = 10.0 * rod.residual_roundoff(&cfg) / scale;
    let tolerance = opts.tolerance.max(floor);
    let mut s_done = 0.0f64;
    // far from balance (a coarse mesh on a curved start): approach in steps,
    // which keeps Newton on the branch of the start
    let res0 = prob.relative_residual(&r, scale);
    let mut ds = if res0 > 0.05 { 0.0625 } else { 1.0 };
    let mut iterations = 0;
    let mut steps = 0;
    let mut last_res = f64::INFINITY;
    while s_done < 1.0 {
        let s_try = (s_done + ds).min(1.0);
        let saved = cfg.clone();
        let offset = 1.0 - s_try;
        let mut converged = false;
        let mut best = f64::INFINITY;
        for _ in 0..opts.max_iterations {
            prob.residual(&cfg, &mut r, Some(&mut sys));
            for i in 0..n {
                r[i] -= offset * r0[i];
            }
            let res = prob.relative_residual(&r, scale);
            last_res = res;
            if res <= tolerance {
                converged = true;
                break;
            }
            if !res.is_finite() || res > 1e6 * best {
                // diverging: retry with a smaller continuation step
                break;
            }
            best = best.min(res);
            iterations += 1;
            if let Err(e) = prob.correction(&mut sys, &mut r, &mut du) {
                if matches!(e, LinearSolveError::Singular) && s_try <= s_done + opts.min_continuation_step {
                    return Err(StaticsError::Linear(e));
                }
                break;
            }
            rod.apply_increment(&mut cfg, &du);
            if !cfg.is_finite() {
                break;
            }
        }
        if converged {
            steps += 1;
            s_done = s_try;
            ds = (2.0 * ds).min(1.0);
        } else {
            cfg = saved;
            ds *= 0.5;
            if ds < opts.min_continuation_step {
                return Err(StaticsError::NotConverged { iterations, residual: last_res, continuation: s_done });
            }
        }
    }
    prob.residual(&cfg, &mut r, None);
    let residual = prob.relative_residual(&r, scale);
    let reactions = prob.reactions(&r);
    Ok(StaticSolution { config: cfg, iterations, continuation_steps: steps, residual, reactions })
}

/// A rod configuration on the analytic elastic catenary from `top` to
/// `anchor` (directors: d3 along the cable, d2 normal to its vertical plane).
/// Falls back to the straight chord when the catenary has no solution (for
/// example an anchor straight below the hang-off).
pub fn catenary_start(rod: &Rod, load: &VerticalLoad, top: V3, anchor: V3) -> RodConfig {
    let chord = anchor - top;
    let horiz = V3::new(chord.x, chord.y, 0.0);
    let span = horiz.norm();
    let eh = if span > 1e-9 * rod.length { horiz / span } else { V3::x() };
    let d2_hint = V3::z().cross(&eh);
    if let Some(cat) = Catenary::solve(rod.length, load, rod.stiffness.axial, span, chord.z) {
        let point = |s: f64| cat.at(s);
        let to3 = |h: f64, z: f64| top + eh * h + V3::z() * z;
        let tangent = |p: &catenary::CablePoint| {
            let t = p.tension();
            let stretch = 1.0 + t / rod.stiffness.axial;
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
