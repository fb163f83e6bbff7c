//! Static equilibrium (docs/theory.md §4), generic over the model's
//! [`StaticEquations`]: Newton–Raphson with the consistent tangent on
//! R(q) = 0 from the model's start, a continuation (homotopy)
//! R(q) − (1 − s) R(q₀) = 0, s: 0 → 1, when the full problem does not converge
//! from the start, and pseudo-transient continuation where that stalls.

use crate::math::band::LinearSolveError;
use crate::model::statics::{Homotopy, StaticEquations, StaticOptions, StaticSolution, StaticsError};

/// Finds the static equilibrium from `initial`: the homotopy continuation,
/// and, if it stalls (a turning point of the homotopy path), pseudo-transient
/// continuation from the same start.
pub fn solve<P: Homotopy>(p: &P, initial: P::Config, opts: &StaticOptions) -> Result<StaticSolution, StaticsError> {
    match solve_homotopy(p, initial.clone(), opts) {
        Ok(s) => Ok(s),
        Err(StaticsError::NotConverged { iterations, .. }) => {
            pseudo_transient(p, initial, opts.tolerance, iterations, 10.0)
        }
        Err(e) => Err(e),
    }
}

/// Pseudo-transient continuation (docs/theory.md §4): a sequence of
/// regularised problems R(q) + μ D (q − q_k) = 0, each started from the last,
/// with μ decreased while Newton converges easily and increased when it does
/// not; ends with Newton on R(q) = 0 alone. Robust where the homotopy path
/// turns, or from a start with no stiffness. `mu_start` in units of
/// [`StaticEquations::mu_unit`] (0: plain Newton first).
pub fn pseudo_transient<P: StaticEquations>(
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

/// The homotopy continuation R(q) − (1 − s) R(q₀) = 0, s: 0 → 1.
fn solve_homotopy<P: Homotopy>(
    prob: &P,
    initial: P::Config,
    opts: &StaticOptions,
) -> Result<StaticSolution, StaticsError> {
    let n = prob.n_dof();
    let mut sys = prob.new_system().map_err(StaticsError::Linear)?;
    let mut r = vec![0.0; n];
    let mut du = vec![0.0; n];
    let mut cfg = initial;
    prob.residual(&cfg, &mut r, None);
    // offset of the homotopy: the out-of-balance force of the start
    let r0 = r.clone();
    let internal_scale = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = prob.force_scale().max(1e-6 * internal_scale).max(f64::MIN_POSITIVE);
    // The residual cannot be evaluated more precisely than the axial force from
    // r' = (r_b − r_a)/h·…, i.e. EA·ε·|r|/h: never ask for less than 10× that.
    let floor = 10.0 * prob.residual_roundoff(&cfg) / scale;
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
            prob.apply_increment(&mut cfg, &du);
            if !P::is_finite(&cfg) {
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
    Ok(prob.solution(cfg, &r, iterations, steps, residual))
}

/// Pseudo-transient continuation from plain Newton (μ = 0 first): the
/// cable's statics, whose straight or hanging-chain start has no bending
/// stiffness to hold a homotopy path.
pub fn relax<P: StaticEquations>(p: &P, initial: P::Config, tolerance: f64) -> Result<StaticSolution, StaticsError> {
    pseudo_transient(p, initial, tolerance, 0, 0.0)
}
