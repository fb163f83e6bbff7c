//! Static equilibrium of the cable (docs/theory.md §6.3): Newton on
//! f_int(x) − f_grav − f_drag(x) = 0 from the shot hanging chain (exact for
//! vertical loads), and, if that fails, the rod's pseudo-transient
//! continuation R(x) + μ (x − x_k) = 0 with μ → 0.

use super::{CableModel, NODE_DOF};
use crate::loads::fluid::{Fluid, FluidFactors, segment_fluid_force};
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{M3, V3};
use crate::model::RodConfig;
use crate::model::catenary::{Catenary, Touchdown};
use crate::model::sections::PerElement;
use crate::model::statics::{StaticEquations, StaticSolution};

/// The chord from `top` to `anchor`, its horizontal span (m) and the unit
/// horizontal direction of the vertical plane through both; None for an
/// anchor (nearly) straight below the top.
fn vertical_plane(top: V3, anchor: V3, length: f64) -> Option<(V3, f64, V3)> {
    let chord = anchor - top;
    let horiz = V3::new(chord.x, chord.y, 0.0);
    let span = horiz.norm();
    (span > 1e-9 * length).then(|| (chord, span, horiz / span))
}

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
    let (chord, span, eh) = vertical_plane(top, anchor, c.length)?;
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
            let len = c.l * (1.0 + t / c.segment_stiffness(e));
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

/// The start of the cable's statics on a seabed (§9.3), where the hanging
/// chain would dip below it: the line resting on the seabed from its
/// touchdown ([`Touchdown`], the seabed taken flat at its height under the
/// anchor). The suspended nodes are marched along the continuous curve, each
/// segment at its stretched length l(1 + T/EA) (so that none is slack), and
/// the rest spread evenly from the last of them to the anchor.
pub fn touchdown_start(model: &CableModel, top: V3, anchor: V3) -> Option<Vec<V3>> {
    let c = &model.cable;
    let bed = model.seabed.as_ref()?;
    let (chord, span, eh) = vertical_plane(top, anchor, c.length)?;
    let level = bed.height_at(anchor.x, anchor.y) - top.z;
    let td = Touchdown::solve(c.length, &model.vertical, c.axial_stiffness, span, chord.z, level)?;
    let to3 = |p: &crate::model::catenary::CablePoint| top + eh * p.x + V3::z() * p.z;
    let mut x = vec![top];
    let mut a = 0;
    while a < c.n_el && c.s_node(a + 1) <= td.suspended {
        let target = to3(&td.at(c.s_node(a + 1)));
        let t = td.at(c.s_node(a) + 0.5 * c.l).tension();
        let dir = (target - x[a]).try_normalize(0.0)?;
        x.push(x[a] + dir * (c.l * (1.0 + t / c.segment_stiffness(a))));
        a += 1;
    }
    let last = x[a];
    let rest = c.n_el - a;
    for k in 1..=rest {
        x.push(last + (anchor - last) * (k as f64 / rest as f64));
    }
    x[c.n_el] = anchor;
    x.iter().all(|p| p.iter().all(|v| v.is_finite())).then_some(x)
}

/// The static problem of a cable: internal force, the vertical load and,
/// if given, the drag of a steady current on the motionless line.
/// What a [`CableStatics`] owns beyond its model (the water's static
/// action, its force scale and its fixed unknowns), kept to build it again
/// without allocating.
#[derive(Debug, Clone)]
pub struct CableStaticParts {
    water: PerElement<Fluid>,
    scale: f64,
    fixed: Vec<usize>,
}

pub struct CableStatics<'a> {
    pub model: &'a CableModel,
    /// The water's static action on each segment (drag of the current; no added mass).
    water: PerElement<Fluid>,
    scale: f64,
    /// Fixed unknowns (the ends).
    fixed: Vec<usize>,
}

impl<'a> CableStatics<'a> {
    /// `with_current`: include the current's drag (the scene's `static_current`).
    pub fn new(model: &'a CableModel, with_current: bool) -> Self {
        let water = model.fluid.map(|f| {
            let drag = if with_current { f.drag.clone() } else { None };
            Fluid { drag, added_mass: 0.0, surface: f.surface, froude_krylov: 0.0 }
        });
        let scale = crate::model::StepEquations::force_scale(model);
        CableStatics { model, water, scale, fixed: model.cable.fixed_dofs() }
    }

    /// The statics of `model` from the parts statics of it gave back
    /// ([`CableStatics::into_parts`], with the same `with_current`):
    /// nothing allocated.
    pub fn from_parts(model: &'a CableModel, parts: CableStaticParts) -> Self {
        let CableStaticParts { water, scale, fixed } = parts;
        CableStatics { model, water, scale, fixed }
    }

    /// What the statics own, to build them again without allocating.
    pub fn into_parts(self) -> CableStaticParts {
        CableStaticParts { water: self.water, scale: self.scale, fixed: self.fixed }
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
        if let Some(beds) = &self.model.seabed {
            let shapes = crate::loads::seabed::linear_at_gauss(c.l);
            for e in 0..c.n_el {
                let bed = beds.at(e);
                if crate::loads::seabed::clear_of(bed, &x[e..e + 2], 0.0) {
                    continue;
                }
                let mut f = [V3::zeros(); 2];
                let mut k = [[M3::zeros(); 2]; 2];
                let want = sys.is_some();
                let seg = [x[e], x[e + 1]];
                crate::loads::seabed::element_static_force(
                    bed,
                    &seg,
                    &shapes,
                    crate::loads::seabed::linear_at,
                    c.l,
                    &mut f,
                    want.then_some(&mut k),
                );
                subtract_element_load(r, sys.as_deref_mut(), e, &f, &k);
            }
        }
        if self.water.values().iter().any(|f| f.surface.is_some()) {
            use crate::loads::surface::linear;
            for e in 0..c.n_el {
                let Some(fs) = &self.water.at(e).surface else { continue };
                if fs.below(&x[e..e + 2], 0.0) {
                    continue;
                }
                let mut f = [V3::zeros(); 2];
                let mut k = [[M3::zeros(); 2]; 2];
                let want = sys.is_some();
                let seg = [x[e], x[e + 1]];
                crate::loads::surface::element_static_force(
                    fs,
                    &seg,
                    linear,
                    c.l,
                    None,
                    &mut f,
                    want.then_some(&mut k),
                );
                subtract_element_load(r, sys.as_deref_mut(), e, &f, &k);
            }
        }
        if self.water.values().iter().any(|f| f.drag.is_some()) {
            let fac = FluidFactors { position: 1.0, velocity: 0.0, acceleration: 0.0 };
            let zero = [V3::zeros(); 2];
            for e in 0..c.n_el {
                if self.water.at(e).drag.is_none() {
                    continue;
                }
                let mut ff = [V3::zeros(); 2];
                let mut kf = [[M3::zeros(); 2]; 2];
                let want = sys.is_some();
                segment_fluid_force(
                    self.water.at(e),
                    1.0,
                    &[x[e], x[e + 1]],
                    &zero,
                    &zero,
                    None,
                    c.s_node(e),
                    c.l,
                    fac,
                    &mut ff,
                    if want { Some(&mut kf) } else { None },
                );
                subtract_element_load(r, sys.as_deref_mut(), e, &ff, &kf);
            }
        }
    }
}

/// Element `e`'s external nodal load `f`, N, taken off the residual R
/// (internal − external) and its stiffness `k` (that of −f, N/m) added to
/// ∂R/∂x where a tangent is asked.
fn subtract_element_load(r: &mut [f64], sys: Option<&mut BandedSystem>, e: usize, f: &[V3; 2], k: &[[M3; 2]; 2]) {
    for i in 0..2 {
        for j in 0..3 {
            r[NODE_DOF * (e + i) + j] -= f[i][j];
        }
    }
    if let Some(s) = sys {
        s.add_block(e, |i, j| k[i / 3][j / 3][(i % 3, j % 3)]);
    }
}

impl StaticEquations for CableStatics<'_> {
    type Config = Vec<V3>;

    fn n_dof(&self) -> usize {
        self.model.cable.n_dof()
    }

    fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        self.model.cable.new_system()
    }

    fn residual(&self, x: &Vec<V3>, r: &mut [f64], sys: Option<&mut BandedSystem>) {
        CableStatics::residual(self, x, r, sys)
    }

    /// Largest free residual component relative to the weight.
    fn relative(&self, r: &[f64]) -> f64 {
        let m = r.iter().enumerate().filter(|(i, _)| !self.fixed.contains(i)).fold(0.0f64, |m, (_, v)| m.max(v.abs()));
        if m.is_nan() { f64::INFINITY } else { m / self.scale }
    }

    fn correction(&self, sys: &mut BandedSystem, r: &mut [f64], du: &mut [f64]) -> Result<(), LinearSolveError> {
        for &i in &self.fixed {
            r[i] = 0.0;
            sys.constrain(i);
        }
        sys.factorize()?;
        for (d, v) in du.iter_mut().zip(r.iter()) {
            *d = -v;
        }
        sys.solve_in_place(du)
    }

    fn apply_increment(&self, x: &mut Vec<V3>, du: &[f64]) {
        for (a, p) in x.iter_mut().enumerate() {
            *p += V3::new(du[3 * a], du[3 * a + 1], du[3 * a + 2]);
        }
    }

    fn is_finite(x: &Vec<V3>) -> bool {
        x.iter().all(|p| p.iter().all(|c| c.is_finite()))
    }

    fn pseudo_mass(&self, _i: usize) -> f64 {
        1.0
    }

    fn mu_unit(&self) -> f64 {
        self.scale / self.model.cable.length
    }

    fn roundoff(&self, x: &Vec<V3>) -> f64 {
        let c = &self.model.cable;
        let extent = x.iter().fold(0.0f64, |m, p| m.max(p.norm())).max(c.length);
        let bed = self.model.seabed.as_ref().map_or(0.0, |b| b.roundoff(c.l, extent));
        c.residual_roundoff(x).max(bed) / self.scale
    }

    fn solution(&self, x: Vec<V3>, r: &[f64], iterations: usize, steps: usize, residual: f64) -> StaticSolution {
        let node = |a: usize| V3::new(r[3 * a], r[3 * a + 1], r[3 * a + 2]);
        StaticSolution {
            reactions: [node(0), node(self.model.cable.n_el)],
            config: RodConfig { x, xp: Vec::new(), d: Vec::new() },
            iterations,
            continuation_steps: steps,
            residual,
        }
    }
}
