//! The cable model (docs/theory.md §6): a line whose bending and torsion do
//! not matter. Position-only nodes joined by straight two-node segments, an
//! elastic tension-only axial law, the same loads as the rod (weight,
//! buoyancy and modules, Morison drag, normal added mass) and the same
//! energy–momentum conserving midpoint scheme, through the shared Newton
//! iteration of [`crate::solve::newton`].
//!
//! Segment e joins nodes e and e+1, reference length l = L/N; with
//! d = x_{e+1} − x_e the stretch is λ = |d|/l and the strain energy
//!   W = ½ EA l (λ − 1)₊²                                               (6.1)
//! (a cable carries no compression). Unknowns: the node positions, three per
//! node, so the line has 3(N+1) unknowns against the rod's 15N+9.

pub mod linearized;
pub mod statics;
mod step;

pub use step::CableWorkspace;

use crate::loads::seabed::{self, Seabed};
use crate::loads::surface;
use crate::loads::weight::VerticalLoad;
use crate::loads::{self, fluid::Fluid};
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{M3, V3};
use crate::model::sections::{self, PerElement};
use crate::scene::Scene;

/// Geometry and axial stiffness of a discretised cable.
#[derive(Debug, Clone, PartialEq)]
pub struct Cable {
    /// Unstretched length L, m.
    pub length: f64,
    /// Segments N.
    pub n_el: usize,
    /// Segment reference length l = L/N, m.
    pub l: f64,
    /// EA of the first segment (of every segment on a uniform line), N.
    pub axial_stiffness: f64,
    /// EA of each segment (line sections, docs/theory.md §11), N.
    ea: Vec<f64>,
    /// Whether the position of the end at S = 0 (the hang-off) and S = L (the
    /// anchor) is prescribed.
    pub ends_fixed: [bool; 2],
}

/// Unknowns per node.
pub const NODE_DOF: usize = 3;

impl Cable {
    pub fn new(length: f64, n_el: usize, axial_stiffness: f64, ends_fixed: [bool; 2]) -> Self {
        Cable { length, n_el, l: length / n_el as f64, axial_stiffness, ea: vec![axial_stiffness; n_el], ends_fixed }
    }

    /// Gives each segment its own EA, N (line sections).
    pub fn with_segment_stiffness(mut self, ea: Vec<f64>) -> Self {
        assert_eq!(ea.len(), self.n_el);
        self.axial_stiffness = ea[0];
        self.ea = ea;
        self
    }

    /// EA of segment e, N.
    pub fn segment_stiffness(&self, e: usize) -> f64 {
        self.ea[e]
    }

    /// Reference arc length of node a, m.
    pub fn s_node(&self, a: usize) -> f64 {
        a as f64 * self.l
    }

    /// Unknowns of the line.
    pub fn n_dof(&self) -> usize {
        NODE_DOF * (self.n_el + 1)
    }

    /// The tangent's sparsity: one 6×6 block per segment, overlapping at the nodes.
    pub fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        BandedSystem::new(self.n_el, 2 * NODE_DOF, NODE_DOF)
    }

    /// Fixed unknowns (the prescribed ends).
    pub fn fixed_dofs(&self) -> Vec<usize> {
        let mut v = Vec::new();
        for (end, &fixed) in self.ends_fixed.iter().enumerate() {
            if fixed {
                let a = if end == 0 { 0 } else { self.n_el };
                v.extend(NODE_DOF * a..NODE_DOF * a + NODE_DOF);
            }
        }
        v
    }

    /// Segment stiffness k = EA l (the factor of (6.1)), N m.
    fn k(&self, e: usize) -> f64 {
        self.ea[e] * self.l
    }

    /// Stretch λ = |d|/l of segment e.
    pub fn stretch(&self, x: &[V3], e: usize) -> f64 {
        (x[e + 1] - x[e]).norm() / self.l
    }

    /// Axial force of segment e, EA (λ − 1)₊, N.
    pub fn tension(&self, x: &[V3], e: usize) -> f64 {
        self.ea[e] * (self.stretch(x, e) - 1.0).max(0.0)
    }

    /// Strain energy Σ W_e (6.1), J.
    pub fn strain_energy(&self, x: &[V3]) -> f64 {
        (0..self.n_el).map(|e| 0.5 * self.k(e) * (self.stretch(x, e) - 1.0).max(0.0).powi(2)).sum()
    }

    /// Position at arc length S (linear between nodes), m.
    pub fn position_at(&self, x: &[V3], s: f64) -> V3 {
        let s = s.clamp(0.0, self.length);
        let e = ((s / self.l) as usize).min(self.n_el - 1);
        let xi = (s - self.s_node(e)) / self.l;
        x[e] * (1.0 - xi) + x[e + 1] * xi
    }

    /// Largest relative round-off of a residual component at positions `x`, N.
    pub fn residual_roundoff(&self, x: &[V3]) -> f64 {
        let extent = x.iter().fold(0.0f64, |m, p| m.max(p.norm())).max(self.length);
        self.ea.iter().fold(0.0f64, |m, &k| m.max(k)) * f64::EPSILON * extent / self.l
    }

    /// Internal force of segment e on its end node e+1, f = 2 g d / l², and
    /// its derivative K = ∂f/∂x_{e+1} (on node e: −f, −K), for the energy
    /// slope g = ∂W/∂C (C = λ²) evaluated along `d_eval` (6.2):
    ///   K = (2/l²) [g c I + (∂g/∂λ1) d_eval ⊗ d1/(λ1 l²)],
    /// c = ∂d_eval/∂d1 (½ at the midpoint, 1 in statics), d1 the trial chord.
    fn segment_force(&self, d_eval: &V3, d1: &V3, lam1: f64, g: f64, dg: f64, c: f64) -> (V3, M3) {
        let l2 = self.l * self.l;
        let f = d_eval * (2.0 * g / l2);
        let k = (M3::identity() * (g * c) + d_eval * d1.transpose() * (dg / (lam1 * l2))) * (2.0 / l2);
        (f, k)
    }

    /// Static energy slope g = W'(C) = k (λ − 1)₊/(2λ) and dg/dλ.
    fn static_slope(&self, seg: usize, lam: f64) -> (f64, f64) {
        let (e, k) = (lam - 1.0, self.k(seg));
        if e > 0.0 { (0.5 * k * e / lam, 0.5 * k / (lam * lam)) } else { (0.0, 0.0) }
    }

    /// The discrete gradient (6.3): g = [W(λ1) − W(λ0)]/(λ1² − λ0²), so that
    /// f·(x_{n+1} − x_n) = W(λ1) − W(λ0) exactly, and ∂g/∂λ1. Written without
    /// the difference quotient where both states are taut (no cancellation).
    pub fn discrete_slope(&self, seg: usize, lam0: f64, lam1: f64) -> (f64, f64) {
        let k = self.k(seg);
        let (e0, e1) = (lam0 - 1.0, lam1 - 1.0);
        let s = lam0 + lam1;
        if e0 >= 0.0 && e1 >= 0.0 {
            (0.5 * k * (e0 + e1) / s, k / (s * s))
        } else if e0 <= 0.0 && e1 <= 0.0 {
            (0.0, 0.0)
        } else {
            // one state slack: (e1 − e0) is at least the taut state's strain
            let n = 0.5 * k * (e1.max(0.0).powi(2) - e0.max(0.0).powi(2));
            let dn = k * e1.max(0.0);
            let d = (e1 - e0) * s;
            let dd = s + (e1 - e0);
            (n / d, (dn * d - n * dd) / (d * d))
        }
    }

    /// Kelvin–Voigt damping slope (6.5): g_η = k (η/h) (λ1 − λ0)/(λ0 + λ1),
    /// dissipating k (η/h)(λ1 − λ0)² ≥ 0 over the step, and ∂g_η/∂λ1.
    pub fn damping_slope(&self, seg: usize, lam0: f64, lam1: f64, eta_over_h: f64) -> (f64, f64) {
        let s = lam0 + lam1;
        let c = self.k(seg) * eta_over_h;
        (c * (lam1 - lam0) / s, c * 2.0 * lam0 / (s * s))
    }

    /// Energy dissipated by the damping of segment e over a step, J.
    pub fn damping_dissipation(&self, seg: usize, lam0: f64, lam1: f64, eta_over_h: f64) -> f64 {
        self.k(seg) * eta_over_h * (lam1 - lam0).powi(2)
    }

    /// Adds the static internal force ∂W/∂x to `r` and its tangent to `sys`.
    pub fn add_static_internal_force(&self, x: &[V3], r: &mut [f64], mut sys: Option<&mut BandedSystem>) {
        for e in 0..self.n_el {
            let d = x[e + 1] - x[e];
            let lam = d.norm() / self.l;
            let (g, dg) = self.static_slope(e, lam);
            let (f, k) = self.segment_force(&d, &d, lam, g, dg, 1.0);
            add_segment(e, &f, &k, r, sys.as_deref_mut());
        }
    }
}

/// Adds a segment's internal force (f on node e+1, −f on node e) to `r` and
/// its derivative K (blocks [[K, −K], [−K, K]]) to `sys`.
fn add_segment(e: usize, f: &V3, k: &M3, r: &mut [f64], sys: Option<&mut BandedSystem>) {
    let (a, b) = (NODE_DOF * e, NODE_DOF * (e + 1));
    for c in 0..3 {
        r[a + c] -= f[c];
        r[b + c] += f[c];
    }
    if let Some(sys) = sys {
        sys.add_block(e, |i, j| {
            let sign = if (i < 3) == (j < 3) { 1.0 } else { -1.0 };
            sign * k[(i % 3, j % 3)]
        });
    }
}

/// Everything about a cable line that does not change during a run.
#[derive(Debug, Clone)]
pub struct CableModel {
    pub cable: Cable,
    /// Segment mass matrices (scalar factors of I3), kg: the average of the
    /// lumped and the consistent mass, ρ̄ l/12 [[5, 1], [1, 5]] (6.4), per section.
    pub mass: PerElement<[[f64; 2]; 2]>,
    pub vertical: VerticalLoad,
    /// Drag, added mass and free surface of each segment.
    pub fluid: PerElement<Fluid>,
    /// The seabed under each segment (None: no contact anywhere, no cost).
    pub seabed: Option<PerElement<Seabed>>,
    /// Nodal vertical load ∫ N_a q dS, N (z components).
    f_grav: Vec<f64>,
    /// The sea whose waves act on the line (None: still water; §13.6).
    pub sea: Option<crate::loads::waves::Sea>,
    /// The current's growth from the run's start (docs/theory.md §5.11).
    pub current_ramp: crate::loads::waves::Ramp,
    /// Where the anchor end (S = L) is at the end of the next step and its
    /// velocity there (None: held where it is, at rest). A system's free
    /// point moves it (docs/theory.md §17.7); its work is `work_anchor`.
    pub anchor_motion: Option<AnchorMotion>,
}

/// The anchor end's motion over a step (shared with the rod: a system's free point moves either).
pub use super::AnchorMotion;

/// The segment mass matrix ρ̄ l/12 [[5, 1], [1, 5]] (6.4), kg.
fn segment_mass(mass_per_length: f64, l: f64) -> [[f64; 2]; 2] {
    let m = mass_per_length * l / 12.0;
    [[5.0 * m, m], [m, 5.0 * m]]
}

impl CableModel {
    /// A uniform line of `mass_per_length` ρ̄, kg/m.
    pub fn new(cable: Cable, mass_per_length: f64, vertical: VerticalLoad, fluid: Fluid) -> Self {
        let n = cable.n_el;
        let f_grav = nodal_vertical_load(&cable, &vertical);
        let mass = PerElement::uniform(segment_mass(mass_per_length, cable.l), n);
        CableModel {
            cable,
            mass,
            vertical,
            fluid: PerElement::uniform(fluid, n),
            seabed: None,
            f_grav,
            sea: None,
            current_ramp: crate::loads::waves::Ramp::NONE,
            anchor_motion: None,
        }
    }

    /// The same line on a uniform seabed.
    pub fn with_seabed(mut self, seabed: Option<Seabed>) -> Self {
        self.seabed = seabed.map(|b| PerElement::uniform(b, self.cable.n_el));
        self
    }

    /// The same line in the waves of `sea` (None: still water).
    pub fn with_sea(mut self, sea: Option<crate::loads::waves::Sea>) -> Self {
        self.sea = sea;
        self
    }

    /// The cable of a scene: the scene's line (its sections) without its
    /// bending and torsion.
    pub fn from_scene(scene: &Scene) -> Self {
        let props = sections::element_properties(scene);
        let n = scene.analysis.n_elements;
        let cable = Cable::new(scene.line.length, n, scene.line.axial_stiffness, [true, true])
            .with_segment_stiffness((0..n).map(|e| props.at(e).axial_stiffness).collect());
        let vertical = loads::vertical_load(scene);
        let f_grav = nodal_vertical_load(&cable, &vertical);
        let mass = props.map(|p| segment_mass(p.mass_per_length, cable.l));
        let fluid = sections::fluid(scene, &props);
        let seabed = sections::seabed(scene, &props);
        let current_ramp = crate::loads::current_ramp(scene);
        CableModel { cable, mass, vertical, fluid, seabed, f_grav, sea: None, current_ramp, anchor_motion: None }
    }

    /// Largest mass per length with the added mass, kg/m.
    pub fn max_inertia_per_length(&self) -> f64 {
        let m = self.mass.values().iter().map(|m| 2.0 * (m[0][0] + m[0][1]) / self.cable.l).fold(0.0, f64::max);
        m + self.fluid.max_added_mass()
    }

    /// Nodal vertical load, N (one value per node: the z component).
    pub fn gravity_vector(&self) -> &[f64] {
        &self.f_grav
    }

    /// Potential of the vertical load, −∫ q z dS (exact for linear z), the
    /// seabed's elastic energy ∫ V dS (9.2) and the free surface's
    /// correction ∫ V_s dS (10.1), J.
    pub fn potential_energy(&self, x: &[V3]) -> f64 {
        let mut v = -x.iter().zip(&self.f_grav).map(|(p, f)| p.z * f).sum::<f64>();
        let (l, shapes) = (self.cable.l, seabed::linear_at_gauss(self.cable.l));
        if let Some(bed) = &self.seabed {
            v += (0..self.cable.n_el)
                .map(|e| seabed::element_energy(bed.at(e), &[x[e], x[e + 1]], &shapes, seabed::linear_at, l))
                .sum::<f64>();
        }
        for e in 0..self.cable.n_el {
            // a straight segment with both nodes below the band adds exactly nothing
            if let Some(s) = &self.fluid.at(e).surface
                && !s.below(&x[e..e + 2], 0.0)
            {
                v += surface::element_energy(s, &[x[e], x[e + 1]], surface::linear, l);
            }
        }
        v
    }

    /// Kinetic energy ½ vᵀ M v, J.
    pub fn kinetic_energy(&self, v: &[V3]) -> f64 {
        (0..self.cable.n_el)
            .map(|e| {
                let m = self.mass.at(e);
                let (a, b) = (v[e], v[e + 1]);
                0.5 * (m[0][0] * a.norm_squared() + 2.0 * m[0][1] * a.dot(&b) + m[1][1] * b.norm_squared())
            })
            .sum()
    }

    /// Linear momentum, kg m/s.
    pub fn linear_momentum(&self, v: &[V3]) -> V3 {
        (0..self.cable.n_el)
            .map(|e| {
                let m = self.mass.at(e);
                (v[e] + v[e + 1]) * (m[0][0] + m[0][1])
            })
            .sum()
    }

    /// Angular momentum about the origin, Σ_e Σ_kl M_kl x_k × v_l, kg m²/s.
    pub fn angular_momentum(&self, x: &[V3], v: &[V3]) -> V3 {
        (0..self.cable.n_el)
            .map(|e| {
                let m = self.mass.at(e);
                let (xa, xb, va, vb) = (x[e], x[e + 1], v[e], v[e + 1]);
                xa.cross(&(va * m[0][0] + vb * m[0][1])) + xb.cross(&(va * m[1][0] + vb * m[1][1]))
            })
            .sum()
    }

    /// Total mass, kg.
    pub fn total_mass(&self) -> f64 {
        (0..self.cable.n_el).map(|e| 2.0 * (self.mass.at(e)[0][0] + self.mass.at(e)[0][1])).sum()
    }
}

/// ∫ N_a q(S) dS at every node, with q piecewise constant (exact).
fn nodal_vertical_load(cable: &Cable, load: &VerticalLoad) -> Vec<f64> {
    let mut f = vec![0.0; cable.n_el + 1];
    for e in 0..cable.n_el {
        let s0 = cable.s_node(e);
        for w in load.breakpoints(s0, s0 + cable.l).windows(2) {
            let (a, b) = ((w[0] - s0) / cable.l, (w[1] - s0) / cable.l);
            let q = load.at(0.5 * (w[0] + w[1]));
            // ∫ ξ dS and ∫ (1 − ξ) dS over [a, b] (in ξ), times l
            let int_xi = 0.5 * (b * b - a * a) * cable.l;
            f[e] += q * ((b - a) * cable.l - int_xi);
            f[e + 1] += q * int_xi;
        }
    }
    f
}
