//! Independent reference solutions for checking the finite-element rod model.
//!
//! Everything here is plain `std` Rust and deliberately shares no code with
//! the `riser` crate, so that agreement between the two is meaningful.
//!
//! Units are SI throughout (m, N, N/m, rad).
//!
//! Conventions for the cable solutions ([`elastic_catenary`],
//! [`piecewise_catenary`]):
//!
//! * the top end (vessel, hang-off point) is at the origin;
//! * `x` is horizontal, positive from the top towards the anchor;
//! * `z` is vertical, positive **upward**, so the anchor usually has `z < 0`;
//! * `s` is the *unstretched* arc length measured from the top (`0..=length`);
//! * loads are given per unit unstretched length, positive **downward**.
//!
//! Sign conventions of the returned end forces (all cases: line in tension):
//!
//! * `h`: horizontal component of the line tension (constant along the line
//!   because there is no horizontal load), always `> 0`;
//! * `v_top`: vertical component of the tension at the top; positive when
//!   the line pulls the vessel **down**, i.e. it is the upward force the
//!   vessel must supply;
//! * `v_bottom`: vertical component of the tension at the anchor; positive
//!   when the line pulls the anchor **up**, i.e. it is the downward force the
//!   anchor must supply. Negative means the line arrives at the anchor from
//!   below (it sags below the anchor; there is no seabed in these models).
//!
//! With these conventions, vertical equilibrium of the whole line reads
//! `v_top - v_bottom = total downward load` (`w * length` for a uniform line).

use std::f64::consts::PI;

// ---------------------------------------------------------------------------
// Shared numerical helpers
// ---------------------------------------------------------------------------

/// Returns an error unless `value` is finite and strictly positive.
fn require_positive(name: &str, value: f64) -> Result<(), String> {
    if value.is_finite() && value > 0.0 { Ok(()) } else { Err(format!("{name} must be finite and > 0, got {value}")) }
}

/// Returns an error unless `value` is finite.
fn require_finite(name: &str, value: f64) -> Result<(), String> {
    if value.is_finite() { Ok(()) } else { Err(format!("{name} must be finite, got {value}")) }
}

/// Euclidean norm of a 2-vector.
fn norm2(r: [f64; 2]) -> f64 {
    r[0].hypot(r[1])
}

/// Solves the 2x2 system `J du = -r`; `None` if singular or not finite.
fn newton_step_2x2(j: [[f64; 2]; 2], r: [f64; 2]) -> Option<[f64; 2]> {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let du = [(-r[0] * j[1][1] + r[1] * j[0][1]) / det, (-r[1] * j[0][0] + r[0] * j[1][0]) / det];
    (du[0].is_finite() && du[1].is_finite()).then_some(du)
}

/// Settings for [`newton_2d`].
struct NewtonSettings {
    /// Converged when the Newton step, relative to the size of the unknowns
    /// (infinity norm), is below this.
    step_tol: f64,
    /// ...and the residual norm is below this (guards against stopping on a
    /// spuriously tiny step far from the root).
    residual_tol: f64,
    /// Maximum number of Newton iterations.
    max_iter: usize,
}

/// Damped Newton iteration for two equations in two unknowns.
///
/// * `residual(u)` returns the residual, or `None` where it cannot be
///   evaluated (treated like an infinitely bad point by the line search);
/// * `jacobian(u, r)` returns `d residual / d u` at `u` (with `r` the residual
///   already computed there), or `None` on failure;
/// * `admissible(u)` restricts the iterates (e.g. positive horizontal force).
///
/// Each full Newton step is halved until the residual norm decreases (or is
/// already at the round-off floor `residual_tol`).
fn newton_2d(
    residual: impl Fn([f64; 2]) -> Option<[f64; 2]>,
    jacobian: impl Fn([f64; 2], [f64; 2]) -> Option<[[f64; 2]; 2]>,
    admissible: impl Fn([f64; 2]) -> bool,
    start: [f64; 2],
    settings: &NewtonSettings,
) -> Result<[f64; 2], String> {
    let mut u = start;
    if !admissible(u) {
        return Err(format!("Newton start {u:?} is not admissible"));
    }
    let mut r = residual(u).ok_or_else(|| format!("residual undefined at start {u:?}"))?;
    for _ in 0..settings.max_iter {
        let rn = norm2(r);
        let j = jacobian(u, r).ok_or_else(|| format!("Jacobian undefined at {u:?}"))?;
        let du = newton_step_2x2(j, r).ok_or_else(|| format!("singular Jacobian at {u:?}"))?;
        let size = u[0].abs().max(u[1].abs()).max(f64::MIN_POSITIVE);
        let rel_step = du[0].abs().max(du[1].abs()) / size;
        if rel_step <= settings.step_tol && rn <= settings.residual_tol {
            let un = [u[0] + du[0], u[1] + du[1]];
            return Ok(if admissible(un) { un } else { u });
        }
        // Backtracking line search on the residual norm.
        let mut t = 1.0;
        let mut accepted = None;
        while t > 1e-12 {
            let un = [u[0] + t * du[0], u[1] + t * du[1]];
            if admissible(un) {
                if let Some(rn_new) = residual(un) {
                    let n = norm2(rn_new);
                    if n.is_finite() && (n < rn || n <= settings.residual_tol) {
                        accepted = Some((un, rn_new));
                        break;
                    }
                }
            }
            t *= 0.5;
        }
        match accepted {
            Some((un, rn_new)) => {
                u = un;
                r = rn_new;
            }
            // No decrease possible: fine if we are already at round-off level.
            None if rn <= settings.residual_tol => return Ok(u),
            None => return Err(format!("line search failed at {u:?} (residual {rn:e})")),
        }
    }
    Err(format!(
        "Newton did not converge in {} iterations (last iterate {u:?}, residual {:e})",
        settings.max_iter,
        norm2(r)
    ))
}

// ---------------------------------------------------------------------------
// 1. Extensible elastic catenary (Irvine), closed form
// ---------------------------------------------------------------------------

/// End forces of a suspended cable; see the module docs for the signs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatenaryForces {
    /// Horizontal component of the tension [N], constant along the line, > 0.
    pub h: f64,
    /// Vertical tension component at the top [N]; positive = line pulls the
    /// vessel down (the upward force the vessel must supply).
    pub v_top: f64,
    /// Vertical tension component at the anchor [N]; positive = line pulls
    /// the anchor up (the downward force the anchor must supply).
    pub v_bottom: f64,
    /// Tension magnitude at the top [N].
    pub top_tension: f64,
    /// Tension magnitude at the anchor [N].
    pub bottom_tension: f64,
}

/// Peyrot & Goulois (1979) starting values for a uniform catenary.
///
/// `w` [N/m] > 0 downward, `span` [m] > 0 horizontal, `rise` [m] = height of
/// the top above the anchor. Returns `(h, v_top)` [N].
fn peyrot_goulois_start(length: f64, w: f64, span: f64, rise: f64) -> (f64, f64) {
    let chord = span.hypot(rise);
    let lambda =
        if length <= chord { 0.2 } else { (3.0 * ((length * length - rise * rise) / (span * span) - 1.0)).sqrt() };
    let h = (w * span / (2.0 * lambda)).abs();
    let v_top = 0.5 * w * (rise / lambda.tanh() + length);
    (h, v_top)
}

/// Closed-form end-to-end projections of a uniform elastic catenary and their
/// derivatives, written from the anchor end (Irvine 1981, eqs. 2.18/2.19).
///
/// Unknowns are `h` and `va` (= `v_bottom`); `vt = va + w length` (= `v_top`).
/// Returns `([span, rise], d[span, rise]/d[h, va])` where `span` is the
/// horizontal distance and `rise` the height of the top above the anchor.
fn irvine_projections(length: f64, w: f64, ea: f64, h: f64, va: f64) -> ([f64; 2], [[f64; 2]; 2]) {
    let vt = va + w * length;
    let ta = h.hypot(va);
    let tt = h.hypot(vt);
    let dasinh = (vt / h).asinh() - (va / h).asinh();
    let span = h * length / ea + h / w * dasinh;
    let rise = (tt - ta) / w + (vt * vt - va * va) / (2.0 * w * ea);
    let jac = [
        [length / ea + dasinh / w - (vt / tt - va / ta) / w, h / w * (1.0 / tt - 1.0 / ta)],
        [h / w * (1.0 / tt - 1.0 / ta), (vt / tt - va / ta) / w + length / ea],
    ];
    ([span, rise], jac)
}

/// Irvine's extensible elastic catenary between a top point and an anchor,
/// without seabed contact, solved for its end forces.
///
/// * `length` [m]: unstretched length of the line, > 0;
/// * `w` [N/m]: submerged weight per unit unstretched length, > 0 (downward);
/// * `ea` [N]: axial stiffness, > 0;
/// * `span_h` [m]: horizontal distance from the top to the anchor, > 0;
/// * `dz` [m]: anchor height minus top height (e.g. `-70.0`), any sign.
///
/// The two unknowns (`h`, `v_bottom`) are found by damped Newton with the
/// analytic Jacobian from a Peyrot–Goulois start, converged to a relative
/// step of 1e-13. Sign conventions: see the module docs.
pub fn elastic_catenary(length: f64, w: f64, ea: f64, span_h: f64, dz: f64) -> Result<CatenaryForces, String> {
    require_positive("length", length)?;
    require_positive("w", w)?;
    require_positive("ea", ea)?;
    require_positive("span_h", span_h)?;
    require_finite("dz", dz)?;
    let rise = -dz;
    let (h0, vt0) = peyrot_goulois_start(length, w, span_h, rise);
    let target = [span_h, rise];
    let scale = length.max(span_h).max(rise.abs());
    let residual = |u: [f64; 2]| {
        let (p, _) = irvine_projections(length, w, ea, u[0], u[1]);
        let r = [p[0] - target[0], p[1] - target[1]];
        (r[0].is_finite() && r[1].is_finite()).then_some(r)
    };
    let jacobian = |u: [f64; 2], _r: [f64; 2]| {
        let (_, j) = irvine_projections(length, w, ea, u[0], u[1]);
        j.iter().flatten().all(|v| v.is_finite()).then_some(j)
    };
    let settings = NewtonSettings { step_tol: 1e-13, residual_tol: 1e-11 * scale, max_iter: 200 };
    let u = newton_2d(residual, jacobian, |u| u[0] > 0.0, [h0, vt0 - w * length], &settings)
        .map_err(|e| format!("elastic_catenary: {e}"))?;
    let (h, v_bottom) = (u[0], u[1]);
    let v_top = v_bottom + w * length;
    Ok(CatenaryForces { h, v_top, v_bottom, top_tension: h.hypot(v_top), bottom_tension: h.hypot(v_bottom) })
}

/// An elastic catenary whose lower part rests on a flat, frictionless,
/// rigid seabed (MoorPy's `catenary()` with `CB = 0`): the fairlead forces
/// and the length on the seabed.
#[derive(Debug, Clone, Copy)]
pub struct SeabedCatenary {
    /// Horizontal force, N (uniform along the line without friction).
    pub h: f64,
    /// Vertical force at the fairlead, N (= w times the suspended length).
    pub v_top: f64,
    /// Unstretched length resting on the seabed, m.
    pub lying: f64,
}

/// The elastic catenary with a length on the seabed (Irvine's equations with
/// the touchdown where the suspended part's tangent is horizontal; the
/// lying part straight under the tension H):
///
///   L_B = L − V/w
///   X   = L_B + (H/w) asinh(V/H) + H L/EA
///   Z   = (H/w) (√(1 + (V/H)²) − 1) + V²/(2 EA w)
///
/// * `length` [m], `w` [N/m] submerged weight, `ea` [N];
/// * `span_h` [m]: horizontal distance from the fairlead to the anchor;
/// * `depth` [m]: height of the fairlead above the seabed (the anchor is on it).
///
/// Solved by nested bisection: V from Z for a given H (Z grows with V), then
/// H from X (X grows with H at the touchdown solution), each to the
/// resolution of the double. Err when no part of the line would rest on the
/// seabed (V ≥ w L) or the line cannot reach.
pub fn catenary_on_seabed(length: f64, w: f64, ea: f64, span_h: f64, depth: f64) -> Result<SeabedCatenary, String> {
    require_positive("length", length)?;
    require_positive("w", w)?;
    require_positive("ea", ea)?;
    require_positive("span_h", span_h)?;
    require_positive("depth", depth)?;
    let z_of = |h: f64, v: f64| h / w * ((1.0 + (v / h).powi(2)).sqrt() - 1.0) + v * v / (2.0 * ea * w);
    let v_of = |h: f64| {
        let (mut lo, mut hi) = (0.0, w * length);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if z_of(h, mid) < depth { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let x_of = |h: f64| {
        let v = v_of(h);
        length - v / w + h / w * (v / h).asinh() + h * length / ea
    };
    let (mut lo, mut hi) = (1e-9 * w * length, 1e3 * w * length);
    if x_of(lo) > span_h || x_of(hi) < span_h {
        return Err(format!("catenary_on_seabed: no touchdown solution for span {span_h} m"));
    }
    for _ in 0..300 {
        let mid = (lo * hi).sqrt();
        if x_of(mid) < span_h { lo = mid } else { hi = mid }
    }
    let h = (lo * hi).sqrt();
    let v = v_of(h);
    if v >= w * length * (1.0 - 1e-12) {
        return Err("catenary_on_seabed: the whole line is suspended".to_string());
    }
    Ok(SeabedCatenary { h, v_top: v, lying: length - v / w })
}

/// Position `(x, z)` [m] of the elastic catenary at unstretched arc length `s`
/// [m] from the top (closed form, Irvine), for the end forces `forces`
/// returned by [`elastic_catenary`] with the same `length`, `w` [N/m] and
/// `ea` [N].
///
/// The curve is integrated from the top (at the origin), so `s = length`
/// reproduces the anchor position only to the accuracy of `forces`: this is
/// a genuine check of the solution. `s` outside `0..=length` extrapolates the
/// same analytic curve.
pub fn elastic_catenary_shape(length: f64, w: f64, ea: f64, forces: &CatenaryForces, s: f64) -> (f64, f64) {
    let _ = length; // the shape from the top does not depend on the length
    let h = forces.h;
    let vt = forces.v_top;
    // Vertical tension component at s (positive = line descends towards the
    // anchor at s).
    let vs = vt - w * s;
    let x = h * s / ea + h / w * ((vt / h).asinh() - (vs / h).asinh());
    let z = -((vt * s - 0.5 * w * s * s) / ea + (h.hypot(vt) - h.hypot(vs)) / w);
    (x, z)
}

/// Tension magnitude [N] of the elastic catenary at unstretched arc length
/// `s` [m] from the top, for the end forces `forces` and weight `w` [N/m].
pub fn elastic_catenary_tension(w: f64, forces: &CatenaryForces, s: f64) -> f64 {
    forces.h.hypot(forces.v_top - w * s)
}

// ---------------------------------------------------------------------------
// 2. Multi-segment extensible cable by ODE shooting
// ---------------------------------------------------------------------------

/// Solution of [`piecewise_catenary`]; force signs as in [`CatenaryForces`].
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseCatenary {
    /// Horizontal tension [N], > 0.
    pub h: f64,
    /// Vertical tension component at the top [N] (positive = pulls vessel down).
    pub v_top: f64,
    /// Vertical tension component at the anchor [N] (positive = pulls anchor up).
    pub v_bottom: f64,
    /// Tension magnitude at the top [N].
    pub top_tension: f64,
    /// Tension magnitude at the anchor [N].
    pub bottom_tension: f64,
    /// Shape at every integration node, from top to anchor:
    /// `(s [m] unstretched arc length from the top, x [m], z [m], tension [N])`.
    pub shape: Vec<(f64, f64, f64, f64)>,
}

/// Number of RK4 steps used by [`piecewise_catenary`] over the whole line.
pub const PIECEWISE_STEPS: usize = 20_000;

/// Result of one integration of the cable equations from the top.
struct CableShot {
    /// Anchor-end state `[x, z, tx, tz]`.
    end: [f64; 4],
    /// Samples `(s, x, z, tension)` if requested.
    samples: Vec<(f64, f64, f64, f64)>,
}

/// Integrates the extensible cable equilibrium equations from the top with
/// classical RK4, splitting the steps at segment boundaries.
///
/// State `y = [x, z, tx, tz]` where `(tx, tz)` is the force exerted by the
/// part of the line beyond `s` on the part before it (it points along the
/// tangent towards the anchor). With `q` the downward load per unstretched
/// length and `t = |(tx, tz)|`:
///
/// `x' = (1 + t/EA) tx/t`, `z' = (1 + t/EA) tz/t`, `tx' = 0`, `tz' = q`.
///
/// Start: `y(0) = [0, 0, h, -v_top]`. Returns `None` if the tension vanishes
/// (the model has no compression) or anything becomes non-finite.
fn integrate_cable(
    segments: &[(f64, f64)],
    eas: &[f64],
    h: f64,
    v_top: f64,
    total_steps: usize,
    record: bool,
) -> Option<CableShot> {
    let total_length: f64 = segments.iter().map(|seg| seg.0).sum();
    let rhs = |y: [f64; 4], q: f64, ea: f64| -> Option<[f64; 4]> {
        let t = y[2].hypot(y[3]);
        if t <= 0.0 || !t.is_finite() {
            return None;
        }
        let stretch = 1.0 + t / ea;
        Some([stretch * y[2] / t, stretch * y[3] / t, 0.0, q])
    };
    let mut y = [0.0, 0.0, h, -v_top];
    let mut s0 = 0.0;
    let mut samples = Vec::new();
    if record {
        samples.reserve(total_steps + 16 * segments.len() + 1);
        samples.push((0.0, y[0], y[1], y[2].hypot(y[3])));
    }
    for (&(len, q), &ea) in segments.iter().zip(eas) {
        if len == 0.0 {
            continue;
        }
        let n = ((total_steps as f64 * len / total_length).ceil() as usize).max(16);
        let ds = len / n as f64;
        for k in 0..n {
            let k1 = rhs(y, q, ea)?;
            let k2 = rhs(add_scaled(y, 0.5 * ds, k1), q, ea)?;
            let k3 = rhs(add_scaled(y, 0.5 * ds, k2), q, ea)?;
            let k4 = rhs(add_scaled(y, ds, k3), q, ea)?;
            for i in 0..4 {
                y[i] += ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            if !y.iter().all(|v| v.is_finite()) {
                return None;
            }
            if record {
                // Arc length from the node count, to avoid accumulating ds.
                let s = s0 + len * (k + 1) as f64 / n as f64;
                samples.push((s, y[0], y[1], y[2].hypot(y[3])));
            }
        }
        s0 += len;
    }
    Some(CableShot { end: y, samples })
}

/// `y + a * k` for 4-vectors.
fn add_scaled(y: [f64; 4], a: f64, k: [f64; 4]) -> [f64; 4] {
    [y[0] + a * k[0], y[1] + a * k[1], y[2] + a * k[2], y[3] + a * k[3]]
}

/// Extensible cable made of consecutive uniform segments, between a top point
/// at the origin and an anchor, without seabed, solved by ODE shooting.
///
/// * `segments`: from the top, `(unstretched length [m] >= 0, net downward
///   load per unstretched length [N/m])`; loads may be negative (buoyant) or
///   zero. At least one segment must have positive length.
/// * `ea` [N]: axial stiffness (same for all segments), > 0;
/// * `span_h` [m]: horizontal distance from the top to the anchor, > 0;
/// * `dz` [m]: anchor height minus top height (e.g. `-40.0`).
///
/// Method (independent of [`elastic_catenary`]): RK4 integration of the
/// equilibrium ODEs (see `integrate_cable`) with [`PIECEWISE_STEPS`] steps
/// over the line, split at the segment boundaries, and Newton shooting with a
/// central-difference Jacobian on the two unknown top force components
/// `(h, v_top)` so that the integrated end point hits the anchor. If Newton
/// fails from the Peyrot–Goulois start of the equivalent uniform line, the
/// loads are morphed from that uniform line to the actual ones in steps
/// (continuation). The line must be in tension everywhere.
pub fn piecewise_catenary(segments: &[(f64, f64)], ea: f64, span_h: f64, dz: f64) -> Result<PiecewiseCatenary, String> {
    piecewise_catenary_with_steps(segments, ea, span_h, dz, PIECEWISE_STEPS)
}

/// [`piecewise_catenary`] with an explicit total number of RK4 steps
/// `total_steps` (>= 1; each non-empty segment gets at least 16 steps), for
/// step-size convergence studies.
pub fn piecewise_catenary_with_steps(
    segments: &[(f64, f64)],
    ea: f64,
    span_h: f64,
    dz: f64,
    total_steps: usize,
) -> Result<PiecewiseCatenary, String> {
    piecewise_catenary_general(segments, &vec![ea; segments.len()], span_h, dz, total_steps)
}

/// [`piecewise_catenary`] for segments with their own axial stiffness:
/// `sections` from the top, `(unstretched length [m], net downward load
/// [N/m], EA [N])` (a line of several sections: the tension is continuous
/// across a boundary, the stretch jumps with EA).
pub fn piecewise_catenary_sections(
    sections: &[(f64, f64, f64)],
    span_h: f64,
    dz: f64,
) -> Result<PiecewiseCatenary, String> {
    let segments: Vec<(f64, f64)> = sections.iter().map(|s| (s.0, s.1)).collect();
    let eas: Vec<f64> = sections.iter().map(|s| s.2).collect();
    piecewise_catenary_general(&segments, &eas, span_h, dz, PIECEWISE_STEPS)
}

fn piecewise_catenary_general(
    segments: &[(f64, f64)],
    eas: &[f64],
    span_h: f64,
    dz: f64,
    total_steps: usize,
) -> Result<PiecewiseCatenary, String> {
    for &ea in eas {
        require_positive("ea", ea)?;
    }
    let ea = eas.iter().sum::<f64>() / eas.len().max(1) as f64;
    require_positive("span_h", span_h)?;
    require_finite("dz", dz)?;
    if total_steps == 0 {
        return Err("total_steps must be >= 1".into());
    }
    for (i, &(len, q)) in segments.iter().enumerate() {
        if !(len.is_finite() && len >= 0.0) {
            return Err(format!("segment {i}: length must be finite and >= 0, got {len}"));
        }
        require_finite(&format!("segment {i}: load"), q)?;
    }
    let length: f64 = segments.iter().map(|seg| seg.0).sum();
    require_positive("total segment length", length)?;
    let total_load: f64 = segments.iter().map(|&(len, q)| len * q).sum();
    let rise = -dz;

    // Start from the equivalent uniform line. A net-buoyant line is the
    // mirror image (z -> -z) of a heavy one; a weightless one gets a small
    // nominal load just to produce a start.
    let max_q = segments.iter().map(|seg| seg.1.abs()).fold(0.0, f64::max);
    let w_mean = total_load / length;
    let w_start = w_mean.abs().max(1e-3 * max_q).max(1e-9 * ea / length);
    let start = if w_mean >= 0.0 {
        let (h0, vt0) = peyrot_goulois_start(length, w_start, span_h, rise);
        [h0, vt0]
    } else {
        let (h0, vt0) = peyrot_goulois_start(length, w_start, span_h, -rise);
        [h0, -vt0]
    };

    let solve = |segs: &[(f64, f64)], start: [f64; 2]| -> Result<[f64; 2], String> {
        shoot_cable(segs, eas, span_h, dz, total_steps, start)
    };
    let u = match solve(segments, start) {
        Ok(u) => u,
        Err(direct_err) => {
            // Continuation from the uniform line (same total load) to the
            // actual load distribution.
            let mut result = Err(direct_err);
            for n_sub in [8usize, 64] {
                let mut u = start;
                let mut ok = true;
                for k in 0..=n_sub {
                    let t = k as f64 / n_sub as f64;
                    let segs: Vec<(f64, f64)> =
                        segments.iter().map(|&(len, q)| (len, (1.0 - t) * w_mean + t * q)).collect();
                    match solve(&segs, u) {
                        Ok(v) => u = v,
                        Err(e) => {
                            result = Err(format!("continuation ({n_sub} steps) failed: {e}"));
                            ok = false;
                            break;
                        }
                    }
                }
                if ok {
                    result = Ok(u);
                    break;
                }
            }
            result.map_err(|e| format!("piecewise_catenary: {e}"))?
        }
    };

    let (h, v_top) = (u[0], u[1]);
    let shot = integrate_cable(segments, eas, h, v_top, total_steps, true)
        .ok_or("piecewise_catenary: final integration failed")?;
    let v_bottom = -shot.end[3];
    Ok(PiecewiseCatenary {
        h,
        v_top,
        v_bottom,
        top_tension: h.hypot(v_top),
        bottom_tension: h.hypot(v_bottom),
        shape: shot.samples,
    })
}

/// Newton shooting on `(h, v_top)` for [`piecewise_catenary_with_steps`].
fn shoot_cable(
    segments: &[(f64, f64)],
    eas: &[f64],
    span_h: f64,
    dz: f64,
    total_steps: usize,
    start: [f64; 2],
) -> Result<[f64; 2], String> {
    let length: f64 = segments.iter().map(|seg| seg.0).sum();
    let scale = length.max(span_h).max(dz.abs());
    let residual = |u: [f64; 2]| -> Option<[f64; 2]> {
        let shot = integrate_cable(segments, eas, u[0], u[1], total_steps, false)?;
        Some([shot.end[0] - span_h, shot.end[1] - dz])
    };
    // Central differences with a step proportional to the force level.
    let jacobian = |u: [f64; 2], _r: [f64; 2]| -> Option<[[f64; 2]; 2]> {
        let d = 1e-6 * u[0].abs().max(u[1].abs());
        let mut j = [[0.0; 2]; 2];
        for col in 0..2 {
            let mut up = u;
            let mut um = u;
            up[col] += d;
            um[col] -= d;
            if up[0] <= 0.0 || um[0] <= 0.0 {
                return None;
            }
            let rp = residual(up)?;
            let rm = residual(um)?;
            for row in 0..2 {
                j[row][col] = (rp[row] - rm[row]) / (2.0 * d);
            }
        }
        Some(j)
    };
    let settings = NewtonSettings { step_tol: 1e-11, residual_tol: 1e-9 * scale, max_iter: 100 };
    newton_2d(residual, jacobian, |u| u[0] > 0.0, start, &settings)
}

// ---------------------------------------------------------------------------
// 3. Large-deflection cantilever (Euler elastica) with a dead tip load
// ---------------------------------------------------------------------------

/// RK4 state of the cantilever shooting: an angle variable, its derivative,
/// the two tip coordinates and the sensitivities of the first two to the
/// shooting unknown (see [`shoot_elastica`] and [`shoot_elastica_from_tip`]).
type ElasticaState = [f64; 6];

/// One classical RK4 step of length `ds` of y' = rhs(y).
fn rk4_step(rhs: &impl Fn(&ElasticaState) -> ElasticaState, y: &mut ElasticaState, ds: f64) {
    let k1 = rhs(y);
    let k2 = rhs(&std::array::from_fn(|i| y[i] + 0.5 * ds * k1[i]));
    let k3 = rhs(&std::array::from_fn(|i| y[i] + 0.5 * ds * k2[i]));
    let k4 = rhs(&std::array::from_fn(|i| y[i] + ds * k3[i]));
    for i in 0..6 {
        y[i] += ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

/// Integrates the normalized elastica from the clamp with RK4 in `n` steps,
/// for initial curvature `kappa0 = theta'(0)`: state
/// `[theta, theta', x, y, dtheta/dkappa0, dtheta'/dkappa0]`. Returns the tip
/// state and
/// whether the physical-branch conditions held along the way
/// (`0 <= theta < pi/2`, `theta' >= 0` up to round-off).
fn shoot_elastica(alpha: f64, kappa0: f64, n: usize) -> (ElasticaState, bool) {
    let rhs = |y: &ElasticaState| -> ElasticaState {
        let (sin, cos) = y[0].sin_cos();
        [y[1], -alpha * cos, cos, sin, y[5], alpha * sin * y[4]]
    };
    let ds = 1.0 / n as f64;
    let mut y: ElasticaState = [0.0, kappa0, 0.0, 0.0, 0.0, 1.0];
    let tol = 1e-9 * kappa0.abs().max(1e-300);
    let mut physical = true;
    for _ in 0..n {
        rk4_step(&rhs, &mut y, ds);
        // For very large alpha the tip slope approaches pi/2 exponentially
        // closely, so allow round-off-level overshoot there.
        if !(y[0] > -tol && y[0] < 0.5 * PI + 1e-8 && y[1] > -tol) {
            physical = false;
        }
    }
    (y, physical)
}

/// Newton on `kappa0` for `theta'(1) = 0` with the exact (variational)
/// derivative, starting from `guess`, with step halving if `|theta'(1)|`
/// does not decrease.
fn solve_elastica_kappa(alpha: f64, guess: f64, n: usize) -> Result<f64, String> {
    let mut k = guess;
    let (mut y, _) = shoot_elastica(alpha, k, n);
    for _ in 0..100 {
        let f = y[1];
        let df = y[5];
        if df == 0.0 || !df.is_finite() || !f.is_finite() {
            return Err(format!("elastica: bad sensitivity at kappa0 = {k}"));
        }
        let dk = -f / df;
        if dk.abs() <= 1e-14 * k.abs() {
            return Ok(k + dk);
        }
        let mut t = 1.0;
        loop {
            let kn = k + t * dk;
            let (yn, _) = shoot_elastica(alpha, kn, n);
            if yn[1].abs() < f.abs() || f.abs() <= 1e-15 * alpha {
                k = kn;
                y = yn;
                break;
            }
            t *= 0.5;
            if t < 1e-10 {
                // At the round-off floor the residual cannot decrease.
                return if f.abs() <= 1e-12 * alpha.max(1.0) {
                    Ok(k)
                } else {
                    Err(format!("elastica: line search failed at kappa0 = {k}"))
                };
            }
        }
    }
    Err(format!("elastica: Newton did not converge for alpha = {alpha}"))
}

/// Loads above this use shooting from the tip ([`elastica_from_tip`]); at or
/// below it, shooting from the clamp ([`solve_elastica_kappa`]).
const ELASTICA_TIP_SHOOTING_ABOVE: f64 = 20.0;

/// Largest load parameter accepted by [`cantilever_elastica`]: beyond it the
/// tip's angular distance to vertical, about `exp(-sqrt(alpha))`, underflows.
pub const ELASTICA_MAX_ALPHA: f64 = 1e5;

/// Large-deflection cantilever (inextensible, unshearable Euler elastica),
/// clamped horizontally at `s = 0`, with a vertical dead load `P` at the tip
/// `s = L`.
///
/// * `alpha` [-]: load parameter `P L^2 / EI`, `|alpha| <=`
///   [`ELASTICA_MAX_ALPHA`]; negative values (upward load) are handled by
///   symmetry.
///
/// Returns `(vertical tip deflection / L, horizontal tip shortening / L)`,
/// the deflection being positive in the direction of the load.
///
/// Method: shooting for `theta'' = -alpha cos(theta)` in normalized arc
/// length with `theta(0) = 0`, `theta'(1) = 0` (theta = slope angle towards
/// the load), RK4 with `4000 + 400 sqrt(alpha)` steps, integrating
/// `x' = cos(theta)`, `y' = sin(theta)` along; Newton uses the variational
/// equation for the exact derivative. Up to `alpha = 20` the unknown is
/// `theta'(0)` (integration from the clamp, continuation in `alpha` from the
/// linear solution). Beyond, shooting from the clamp becomes hopelessly
/// ill-conditioned (sensitivity ~ `exp(sqrt(alpha))`, already ~1e9 at
/// `alpha = 500`) because the tip slope approaches vertical exponentially;
/// there the unknown is `ln(pi/2 - theta(1))` and the integration runs from
/// the tip to the clamp (see [`elastica_from_tip`]). Only the physical,
/// monotone branch (`0 <= theta <= pi/2`) is accepted.
pub fn cantilever_elastica(alpha: f64) -> Result<(f64, f64), String> {
    require_finite("alpha", alpha)?;
    if alpha < 0.0 {
        let (v, h) = cantilever_elastica(-alpha)?;
        return Ok((-v, h));
    }
    if alpha == 0.0 {
        return Ok((0.0, 0.0));
    }
    if alpha > ELASTICA_MAX_ALPHA {
        return Err(format!("elastica: alpha = {alpha} exceeds the supported {ELASTICA_MAX_ALPHA}"));
    }
    let n = 4000 + (400.0 * alpha.sqrt()).ceil() as usize;
    if alpha > ELASTICA_TIP_SHOOTING_ABOVE {
        return elastica_from_tip(alpha, n);
    }
    // Continuation: alpha_k grows geometrically; the next guess extrapolates
    // kappa0 ~ alpha^p in log-log (p = 1 in the linear regime, smaller for
    // large loads).
    let mut a = alpha.min(0.5);
    let mut prev: Option<(f64, f64)> = None; // (alpha, kappa0)
    let mut exponent = 1.0;
    let kappa0 = loop {
        let guess = match prev {
            None => a,
            Some((ap, kp)) => kp * (a / ap).powf(exponent),
        };
        let k = solve_elastica_kappa(a, guess, n)?;
        if a >= alpha {
            break k;
        }
        if let Some((ap, kp)) = prev {
            exponent = ((k / kp).ln() / (a / ap).ln()).clamp(0.5, 1.0);
        }
        prev = Some((a, k));
        a = (1.5 * a).min(alpha);
    };
    let (y, physical) = shoot_elastica(alpha, kappa0, n);
    if !physical {
        return Err(format!("elastica: non-physical branch for alpha = {alpha}"));
    }
    Ok((y[3], 1.0 - y[2]))
}

/// Integrates the elastica from the tip to the clamp for a given tip angle.
///
/// Variable `u = pi/2 - theta` (keeps full relative precision when the tip
/// is nearly vertical) and `sigma = 1 - s`: `u_sigma_sigma = alpha sin(u)`,
/// `u(0) = u_tip = exp(ell)`, `u_sigma(0) = 0`. State
/// `[u, u_sigma, x, y, du/d ell, d u_sigma/d ell]` where `x`, `y` accumulate
/// the tip coordinates `int sin(u)`, `int cos(u)`. Returns the state at the
/// clamp (`sigma = 1`), or `None` once `u` exceeds 3 (< pi): the tip angle is
/// then far too small (the curve would loop), and beyond `pi` the residual
/// would oscillate wildly instead of staying positive.
fn shoot_elastica_from_tip(alpha: f64, ell: f64, n: usize) -> Option<ElasticaState> {
    let rhs = |y: &ElasticaState| -> ElasticaState {
        let (sin, cos) = y[0].sin_cos();
        [y[1], alpha * sin, sin, cos, y[5], alpha * cos * y[4]]
    };
    let ds = 1.0 / n as f64;
    let u_tip = ell.exp();
    let mut y: ElasticaState = [u_tip, 0.0, 0.0, 0.0, u_tip, 0.0];
    for _ in 0..n {
        rk4_step(&rhs, &mut y, ds);
        if y[0].is_nan() || y[0] > 3.0 {
            return None;
        }
    }
    Some(y)
}

/// Shooting from the tip for large `alpha`: finds `ell = ln(pi/2 - theta(1))`
/// such that `theta(0) = 0`, i.e. `u(sigma = 1) = pi/2`, by Newton with the
/// variational derivative, safeguarded by bisection on a sign-changing
/// bracket (`u_tip = pi/2` overshoots; `u_tip = exp(-sqrt(alpha) - 60)`
/// undershoots since `u <= u_tip cosh(sqrt(alpha) sigma)`). Returns the
/// normalized `(deflection, shortening)`.
fn elastica_from_tip(alpha: f64, n: usize) -> Result<(f64, f64), String> {
    // Residual u(1) - pi/2 (+infinity on overshoot, see
    // shoot_elastica_from_tip) and the final state.
    let g = |ell: f64| match shoot_elastica_from_tip(alpha, ell, n) {
        Some(y) => (y[0] - 0.5 * PI, Some(y)),
        None => (f64::INFINITY, None),
    };
    let (mut lo, mut hi) = (-alpha.sqrt() - 60.0, (0.5 * PI).ln());
    let (g_lo, _) = g(lo);
    let (g_hi, _) = g(hi);
    if !(g_lo < 0.0 && g_hi > 0.0) {
        return Err(format!("elastica: no bracket from the tip for alpha = {alpha}"));
    }
    let tip = |y: ElasticaState| (y[3], 1.0 - y[2]);
    let mut ell = 0.5 * (lo + hi);
    for _ in 0..300 {
        let (r, y) = g(ell);
        if r == 0.0 {
            if let Some(y) = y {
                return Ok(tip(y));
            }
        }
        if r < 0.0 {
            lo = ell;
        } else {
            hi = ell;
        }
        // Newton step if it stays inside the bracket, else bisection.
        let next = match y {
            Some(y) if y[4] > 0.0 && lo < ell - r / y[4] && ell - r / y[4] < hi => ell - r / y[4],
            _ => 0.5 * (lo + hi),
        };
        let converged = (next - ell).abs() <= 1e-15 * ell.abs().max(1.0) || hi - lo <= 1e-15 * ell.abs().max(1.0);
        ell = next;
        if converged {
            if let (_, Some(y)) = g(ell) {
                return Ok(tip(y));
            }
        }
    }
    Err(format!("elastica: tip shooting did not converge for alpha = {alpha}"))
}

// ---------------------------------------------------------------------------
// 4. Zeros of the Bessel function J0
// ---------------------------------------------------------------------------

/// Bessel functions `(J0(x), J1(x))` for any finite real `x`.
///
/// Miller's backward recurrence `J_{k-1} = (2k/x) J_k - J_{k+1}` started well
/// above the turning point (order `x + 10 x^(1/3) + 30`), normalized with
/// `J0 + 2 (J2 + J4 + ...) = 1`; power series for `|x| < 1e-4`. Absolute
/// accuracy about 1e-15 for moderate `x`, degrading slowly (roughly like
/// `sqrt(x)` ulps) for large `x`. Non-finite `x` gives NaNs.
pub fn bessel_j0_j1(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let ax = x.abs();
    if ax < 1e-4 {
        // Power series; truncation error below 1e-26. (The recurrence would
        // overflow for tiny x.)
        let x2 = x * x;
        return (1.0 - x2 / 4.0 * (1.0 - x2 / 16.0), x / 2.0 * (1.0 - x2 / 8.0));
    }
    let start = (ax + 10.0 * ax.cbrt() + 30.0).ceil() as usize;
    let start = start + start % 2; // even
    let mut j_next = 0.0; // J_{k+1}
    let mut j = 1e-30; // J_k, arbitrary small seed
    let mut even_sum = 0.0; // 2 * (J_2 + J_4 + ...)
    let mut j1 = 0.0;
    for k in (1..=start).rev() {
        let j_prev = 2.0 * k as f64 / ax * j - j_next; // J_{k-1}
        j_next = j;
        j = j_prev;
        let order = k - 1;
        if order == 1 {
            j1 = j;
        } else if order >= 2 && order % 2 == 0 {
            even_sum += 2.0 * j;
        }
        // Rescale to avoid overflow far above the turning point.
        if j.abs() > 1e250 {
            j *= 1e-250;
            j_next *= 1e-250;
            even_sum *= 1e-250;
            j1 *= 1e-250;
        }
    }
    let norm = j + even_sum;
    let j0 = j / norm;
    let j1 = j1 / norm;
    // J0 is even, J1 is odd.
    (j0, if x < 0.0 { -j1 } else { j1 })
}

/// First `n` positive zeros of the Bessel function `J0`, in increasing order.
///
/// Starts from McMahon's asymptotic expansion (Abramowitz & Stegun 9.5.12)
/// and polishes each zero with Newton on `J0` (`J0' = -J1`) evaluated by
/// [`bessel_j0_j1`], to a relative step of about 1 ulp. (Newton from
/// McMahon's guess is always within the basin; the iteration count is capped
/// regardless, so this cannot loop or panic.)
pub fn bessel_j0_zeros(n: usize) -> Vec<f64> {
    (1..=n)
        .map(|k| {
            let beta = (k as f64 - 0.25) * PI;
            let b8 = 8.0 * beta;
            let mut x = beta + 1.0 / b8 - 124.0 / (3.0 * b8.powi(3)) + 120_928.0 / (15.0 * b8.powi(5));
            for _ in 0..50 {
                let (j0, j1) = bessel_j0_j1(x);
                let dx = j0 / j1;
                x += dx;
                if dx.abs() <= 4.0 * f64::EPSILON * x {
                    break;
                }
            }
            x
        })
        .collect()
}

/// The lowest `count` natural frequencies (Hz) of two uniform taut strings
/// joined end to end and pinned at both far ends: lengths `ell` (m, as
/// stretched), masses per length `mu` (kg/m of that length), tension `t`
/// (N). With k_i = ω √(μ_i/T), y and T y′ continuous at the joint give
/// k₁ cos(k₁ℓ₁) sin(k₂ℓ₂) + k₂ cos(k₂ℓ₂) sin(k₁ℓ₁) = 0 (the cot form times
/// the sines, free of poles), whose roots are found by scanning ω in steps
/// of 1e-3 rad/s and bisection.
pub fn joined_strings_frequencies(ell: [f64; 2], mu: [f64; 2], t: f64, count: usize) -> Vec<f64> {
    let g = |w: f64| {
        let (k1, k2) = (w * (mu[0] / t).sqrt(), w * (mu[1] / t).sqrt());
        k1 * (k1 * ell[0]).cos() * (k2 * ell[1]).sin() + k2 * (k2 * ell[1]).cos() * (k1 * ell[0]).sin()
    };
    let mut out = vec![];
    let (mut w, dw) = (1e-3, 1e-3);
    while out.len() < count {
        if g(w) * g(w + dw) < 0.0 {
            let (mut a, mut b) = (w, w + dw);
            for _ in 0..100 {
                let c = 0.5 * (a + b);
                if g(a) * g(c) <= 0.0 { b = c } else { a = c }
            }
            out.push(0.5 * (a + b) / (2.0 * std::f64::consts::PI));
        }
        w += dw;
    }
    out
}

// ---------------------------------------------------------------------------
// Linear (Airy) waves
// ---------------------------------------------------------------------------

/// Wave number k (rad/m) of the finite-depth dispersion relation
/// ω² = g k tanh(k d), by bisection on k between the deep-water value ω²/g
/// (tanh ≤ 1 makes the root at least that) and the shallow-water bound
/// ω/√(g d) + ω²/g, halving until the bracket stops shrinking (about 60
/// halvings: the root to the last bit). No Newton, no Eckart start: another
/// route than the crate's.
pub fn wave_number(omega: f64, depth: f64, g: f64) -> f64 {
    let f = |k: f64| g * k * (k * depth).tanh() - omega * omega;
    let (mut lo, mut hi) = (omega * omega / g, omega / (g * depth).sqrt() + omega * omega / g);
    assert!(f(lo) <= 0.0 && f(hi) >= 0.0, "the bracket holds the root");
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return if f(hi).abs() < f(lo).abs() { hi } else { lo };
        }
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

/// The linear (Airy) wave of amplitude `a` (m), circular frequency
/// `omega`, wave number `k`, in depth `depth`, travelling along +x', at
/// the phase θ = k x' − ω t + φ and the height `zeta` (m, above the mean
/// level, −d ≤ ζ ≤ 0 where linear theory holds): (horizontal velocity u,
/// vertical velocity w, ∂u/∂t, ∂w/∂t), from the velocity potential
/// Φ = (a g/ω) cosh k(ζ + d)/cosh kd sin θ (u = ∂Φ/∂x', w = ∂Φ/∂ζ), written
/// with cosh and sinh directly (the crate uses exponentials), g from the
/// dispersion relation g = ω²/(k tanh kd).
pub fn airy_kinematics(a: f64, omega: f64, k: f64, depth: f64, theta: f64, zeta: f64) -> [f64; 4] {
    let g = omega * omega / (k * (k * depth).tanh());
    let amp = a * g / omega; // Φ's amplitude a g/ω
    let c = (k * (zeta + depth)).cosh() / (k * depth).cosh();
    let s = (k * (zeta + depth)).sinh() / (k * depth).cosh();
    // Φ = amp c sin θ: u = ∂Φ/∂x' = amp k c cos θ, w = ∂Φ/∂ζ = amp k s sin θ
    let u = amp * k * c * theta.cos();
    let w = amp * k * s * theta.sin();
    // ∂θ/∂t = −ω
    let du = amp * k * c * omega * theta.sin();
    let dw = -amp * k * s * omega * theta.cos();
    [u, w, du, dw]
}

/// The amplitudes of the horizontal Morison force on a fixed vertical
/// cylinder in a regular linear wave, [`morison_vertical_cylinder`]: the
/// force (N, along the wave's direction) at the phase θ is
///
///   F(θ) = F_I sin θ + F_D cos θ |cos θ|
///
/// (θ = k x' − ω t + φ at the cylinder's axis, so that η = a cos θ there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MorisonAmplitudes {
    /// F_I, N: amplitude of the inertia force C_M ρ A ∫ ∂u/∂t dz.
    pub inertia: f64,
    /// F_D, N: amplitude of the drag force ½ ρ C_D D ∫ u|u| dz.
    pub drag: f64,
}

impl MorisonAmplitudes {
    /// The force at the phase θ, N: F_I sin θ + F_D cos θ |cos θ|.
    pub fn at(&self, theta: f64) -> f64 {
        self.inertia * theta.sin() + self.drag * theta.cos() * theta.cos().abs()
    }

    /// The force's first harmonic in θ, (A₁, B₁) with F ≈ A₁ sin θ + B₁ cos θ
    /// plus higher odd harmonics, N: A₁ = F_I and B₁ = 8/(3π) F_D, from the
    /// Fourier series
    ///
    ///   cos θ |cos θ| = (8/3π) cos θ + (8/15π) cos 3θ − (8/105π) cos 5θ + …
    ///
    /// ((1/π) ∫ cos θ |cos θ| cos θ dθ over a period is (2/π) ∫ cos³ θ dθ
    /// over (−π/2, π/2), that is (2/π)(4/3)).
    pub fn first_harmonic(&self) -> (f64, f64) {
        (self.inertia, 8.0 / (3.0 * PI) * self.drag)
    }
}

/// Morison's horizontal force on a fixed, rigid vertical cylinder of
/// diameter `diameter` (m) from the height `z_bot` to `z_top` (m above the
/// mean level, −d ≤ z_bot < z_top ≤ 0: the whole length below the trough,
/// where linear theory holds without stretching) in the linear wave of
/// amplitude `a` (m), circular frequency `omega`, wave number `k` and depth
/// `depth` d (m) of [`airy_kinematics`], water density `rho` (kg/m³),
/// inertia coefficient `cm` (C_M = 1 + C_a) and drag coefficient `cd`.
///
/// With g = ω²/(k tanh kd) from the dispersion relation, the horizontal
/// velocity and acceleration on the axis are (s = z + d)
///
///   u = a ω cosh(k s)/sinh(kd) cos θ,   ∂u/∂t = a ω² cosh(k s)/sinh(kd) sin θ
///
/// (the potential's a g k/(ω cosh kd) is a ω/sinh kd, since g k tanh kd =
/// ω²), all at one phase θ along the axis, so that u|u| = U(z)² cos θ |cos θ|
/// and the depth integrals separate from time. With A = π D²/4,
///
///   F_I = C_M ρ A a ω² ∫ cosh(k s) ds / sinh kd
///       = C_M ρ A a ω² [sinh(k s_t) − sinh(k s_b)] / (k sinh kd),
///   F_D = ½ ρ C_D D (a ω/sinh kd)² ∫ cosh²(k s) ds
///       = ½ ρ C_D D (a ω/sinh kd)² [s/2 + sinh(2 k s)/(4k)] from s_b to s_t,
///
/// s_b = z_bot + d, s_t = z_top + d (∫ cosh² = ∫ (1 + cosh 2ks)/2). The
/// forces per unit length integrated are Morison's for a fixed cylinder:
/// C_M ρ A ∂u/∂t (Froude–Krylov ρ A ∂u/∂t plus added mass C_a ρ A ∂u/∂t)
/// and ½ ρ C_D D u|u|; the convective acceleration and the vertical
/// velocity (along the axis) do not enter at first order.
#[allow(clippy::too_many_arguments)]
pub fn morison_vertical_cylinder(
    a: f64,
    omega: f64,
    k: f64,
    depth: f64,
    diameter: f64,
    z_bot: f64,
    z_top: f64,
    rho: f64,
    cm: f64,
    cd: f64,
) -> MorisonAmplitudes {
    assert!(-depth <= z_bot && z_bot < z_top && z_top <= 0.0, "the cylinder is in the water column");
    let (sb, st) = (z_bot + depth, z_top + depth);
    let skd = (k * depth).sinh();
    let area = PI * diameter * diameter / 4.0;
    let int_cosh = ((k * st).sinh() - (k * sb).sinh()) / k;
    let int_cosh2 = |s: f64| s / 2.0 + (2.0 * k * s).sinh() / (4.0 * k);
    let inertia = cm * rho * area * a * omega * omega * int_cosh / skd;
    let drag = 0.5 * rho * cd * diameter * (a * omega / skd).powi(2) * (int_cosh2(st) - int_cosh2(sb));
    MorisonAmplitudes { inertia, drag }
}

/// JONSWAP's spectral density (m²/Hz) at f (Hz) for Hs, Tp, γ, with the
/// constant α fixed by its own integral: S = α f⁻⁵ exp(−1.25 (f_p/f)⁴) γ^r,
/// r = exp(−(f − f_p)²/(2 σ² f_p²)), σ = 0.07 below the peak and 0.09 above,
/// α such that ∫ S df = Hs²/16, the integral by the trapezoidal rule in
/// ln f on 400 000 points over [f_p/20, 2000 f_p] (the tails beyond hold
/// below 1e-13 of m₀: the f⁻⁵ tail above 2000 f_p is 5/4 · 2000⁻⁴ of it).
pub fn jonswap_density(f: f64, hs: f64, tp: f64, gamma: f64) -> f64 {
    let fp = 1.0 / tp;
    let shape = |f: f64| {
        let sigma = if f <= fp { 0.07 } else { 0.09 };
        let r = (-(f - fp) * (f - fp) / (2.0 * sigma * sigma * fp * fp)).exp();
        f.powi(-5) * (-1.25 * (fp / f).powi(4)).exp() * gamma.powf(r)
    };
    let n = 400_000;
    let (u0, u1) = ((fp / 20.0).ln(), (2000.0 * fp).ln());
    let h = (u1 - u0) / n as f64;
    let mut integral = 0.0;
    for i in 0..=n {
        let u = u0 + i as f64 * h;
        let w = if i == 0 || i == n { 0.5 } else { 1.0 };
        integral += w * shape(u.exp()) * u.exp();
    }
    integral *= h;
    hs * hs / 16.0 / integral * shape(f)
}
