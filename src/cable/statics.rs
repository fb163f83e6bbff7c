//! Static equilibrium of the cable (docs/theory.md §6.3): Newton on
//! f_int(x) − f_grav − f_drag(x) = 0 from the elastic catenary, and, if that
//! fails (a slack start, buoyancy modules far from the catenary), pseudo-
//! transient continuation R(x) + μ (x − x_k) = 0 with μ → 0, as for the rod.

use super::{CableModel, NODE_DOF};
use crate::hydro::fluid::{Fluid, FluidFactors, segment_fluid_force};
use crate::linsolve::BandedSystem;
use crate::rod::kinematics::{M3, RodConfig, V3};
use crate::statics::catenary::Catenary;
use crate::statics::{StaticSolution, StaticsError};

/// The start of the cable's statics (docs/theory.md §6.3): the discrete
/// chain itself hanging under its nodal loads f_a, shot from the hang-off so
/// that it closes on the anchor. With segment 0 carrying n_0 = (H, N) in the
/// vertical plane through both ends, n_e = n_{e−1} − f_e e_z and the chords
/// d_e = l (1 + |n_e|/EA) n_e/|n_e| satisfy the static equations exactly for
/// vertical loads; Newton on (H, N) closes the chain, started from the
/// continuous elastic catenary. (Nodes placed *on* the continuous catenary
/// would not do: a chord is shorter than its arc by about κ²l²/24, which can
/// exceed the strain T/EA and leave segments slack, with no stiffness.)
/// None if the chain cannot be closed (then the caller starts elsewhere).
pub fn hanging_chain_start(model: &CableModel, top: V3, anchor: V3) -> Option<Vec<V3>> {
    let c = &model.cable;
    let chord = anchor - top;
    let horiz = V3::new(chord.x, chord.y, 0.0);
    let span = horiz.norm();
    if span <= 1e-9 * c.length {
        return None;
    }
    let eh = horiz / span;
    let cat = Catenary::solve(c.length, &model.vertical, c.axial_stiffness, span, chord.z)?;
    let f = model.gravity_vector();
    // the chain from (H, N): node positions in the plane (along eh, z)
    let chain = |u: [f64; 2]| -> Option<Vec<[f64; 2]>> {
        let mut p = vec![[0.0, 0.0]; c.n_el + 1];
        let (h, mut nz) = (u[0], u[1]);
        for e in 0..c.n_el {
            if e > 0 {
                nz -= f[e];
            }
            let t = h.hypot(nz);
            if !(t > 0.0 && t.is_finite()) {
                return None;
            }
            let len = c.l * (1.0 + t / c.axial_stiffness);
            p[e + 1] = [p[e][0] + len * h / t, p[e][1] + len * nz / t];
        }
        Some(p)
    };
    let closure = |u: [f64; 2]| chain(u).map(|p| [p[c.n_el][0] - span, p[c.n_el][1] - chord.z]);
    let mut u = [cat.h, cat.v0 - f[0]];
    let mut r = closure(u)?;
    for _ in 0..50 {
        if r[0].hypot(r[1]) <= 1e-12 * c.length {
            let p = chain(u)?;
            let mut x: Vec<V3> = p.iter().map(|q| top + eh * q[0] + V3::z() * q[1]).collect();
            x[c.n_el] = anchor;
            return Some(x);
        }
        // finite-difference Jacobian of this 2 × 2 shooting problem
        let scale = u[0].hypot(u[1]);
        let mut jac = [[0.0; 2]; 2];
        for j in 0..2 {
            let mut up = u;
            up[j] += 1e-7 * scale;
            let rp = closure(up)?;
            for i in 0..2 {
                jac[i][j] = (rp[i] - r[i]) / (1e-7 * scale);
            }
        }
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        u[0] -= (jac[1][1] * r[0] - jac[0][1] * r[1]) / det;
        u[1] -= (jac[0][0] * r[1] - jac[1][0] * r[0]) / det;
        r = closure(u)?;
    }
    None
}

/// The static problem of a cable: internal force, the vertical load and,
/// if given, the drag of a steady current on the motionless line.
pub struct CableStatics<'a> {
    pub model: &'a CableModel,
    /// The water's static action (drag of the current; no added mass).
    water: Fluid,
    scale: f64,
}

impl<'a> CableStatics<'a> {
    /// `with_current`: include the current's drag (the scene's `static_current`).
    pub fn new(model: &'a CableModel, with_current: bool) -> Self {
        let water = Fluid { drag: if with_current { model.fluid.drag.clone() } else { None }, added_mass: 0.0 };
        let scale = crate::dynamics::StepEquations::force_scale(model);
        CableStatics { model, water, scale }
    }

    /// R(x) into `r` and, if given, ∂R/∂x into `sys`.
    pub fn residual(&self, x: &[V3], r: &mut [f64], mut sys: Option<&mut BandedSystem>) {
        let c = &self.model.cable;
        r.iter_mut().for_each(|v| *v = 0.0);
        if let Some(s) = sys.as_deref_mut() {
            s.clear();
        }
        c.add_static_internal_force(x, r, sys.as_deref_mut());
        for (a, f) in self.model.gravity_vector().iter().enumerate() {
            r[NODE_DOF * a + 2] -= f;
        }
        if self.water.drag.is_some() {
            let fac = FluidFactors { position: 1.0, velocity: 0.0, acceleration: 0.0 };
            let zero = [V3::zeros(); 2];
            for e in 0..c.n_el {
                let mut ff = [V3::zeros(); 2];
                let mut kf = [[M3::zeros(); 2]; 2];
                let want = sys.is_some();
                segment_fluid_force(
                    &self.water,
                    &[x[e], x[e + 1]],
                    &zero,
                    &zero,
                    c.s_node(e),
                    c.l,
                    fac,
                    &mut ff,
                    if want { Some(&mut kf) } else { None },
                );
                for i in 0..2 {
                    for k in 0..3 {
                        r[NODE_DOF * (e + i) + k] -= ff[i][k];
                    }
                }
                if let Some(s) = sys.as_deref_mut() {
                    s.add_block(e, |i, j| kf[i / 3][j / 3][(i % 3, j % 3)]);
                }
            }
        }
    }

    /// Largest free residual component relative to the weight.
    fn relative(&self, r: &[f64], fixed: &[usize]) -> f64 {
        let m = r.iter().enumerate().filter(|(i, _)| !fixed.contains(i)).fold(0.0f64, |m, (_, v)| m.max(v.abs()));
        if m.is_nan() { f64::INFINITY } else { m / self.scale }
    }

    /// The equilibrium from `start` (node positions; the ends stay where they are).
    pub fn solve(&self, start: Vec<V3>, tolerance: f64) -> Result<StaticSolution, StaticsError> {
        let c = &self.model.cable;
        let n = c.n_dof();
        let fixed = c.fixed_dofs();
        let mut sys = c.new_system().map_err(StaticsError::Linear)?;
        let mut r = vec![0.0; n];
        let mut du = vec![0.0; n];
        let floor = 10.0 * c.residual_roundoff(&start) / self.scale;
        let tolerance = tolerance.max(floor);
        let mut x = start;
        let mut iterations = 0;
        let mut steps = 0;
        // μ = 0: plain Newton; μ > 0: a pseudo-time step x_k → x
        let mut mu = 0.0;
        let mu0 = 10.0 * self.scale / c.length;
        let mut last = f64::INFINITY;
        for _ in 0..2000 {
            let saved = x.clone();
            let mut ok = false;
            let mut its = 0;
            for _ in 0..if mu == 0.0 { 30 } else { 12 } {
                self.residual(&x, &mut r, Some(&mut sys));
                last = self.relative(&r, &fixed);
                if mu == 0.0 && last <= tolerance {
                    let node = |a: usize| V3::new(r[3 * a], r[3 * a + 1], r[3 * a + 2]);
                    return Ok(StaticSolution {
                        reactions: [node(0), node(c.n_el)],
                        config: RodConfig { x, xp: Vec::new(), d: Vec::new() },
                        iterations,
                        continuation_steps: steps,
                        residual: last,
                    });
                }
                for (i, ri) in r.iter_mut().enumerate() {
                    *ri += mu * (x[i / 3][i % 3] - saved[i / 3][i % 3]);
                    sys.add(i, i, mu);
                }
                if mu > 0.0 && self.relative(&r, &fixed) <= tolerance.max(1e-8) {
                    ok = true;
                    break;
                }
                if !last.is_finite() {
                    break;
                }
                for &i in &fixed {
                    r[i] = 0.0;
                    sys.constrain(i);
                }
                iterations += 1;
                its += 1;
                for (d, v) in du.iter_mut().zip(&r) {
                    *d = -v;
                }
                if sys.factorize().is_err() || sys.solve_in_place(&mut du).is_err() {
                    break;
                }
                for (a, p) in x.iter_mut().enumerate() {
                    *p += V3::new(du[3 * a], du[3 * a + 1], du[3 * a + 2]);
                }
            }
            if ok {
                steps += 1;
                mu *= if its <= 3 { 0.2 } else { 0.6 };
                if mu < 1e-9 * mu0 {
                    mu = 0.0;
                }
            } else {
                x = saved;
                mu = if mu == 0.0 { mu0 } else { mu * 4.0 };
                if mu > 1e12 * mu0 {
                    break;
                }
            }
        }
        Err(StaticsError::NotConverged { iterations, residual: last, continuation: 1.0 })
    }
}
