//! The assembled rod: mesh, section, end conditions, reference strains, and the
//! global internal force and tangent (docs/theory.md §2–§3).
//!
//! Global unknowns (reduced), node by node along the line:
//!   end node a:      [Δr_a (3), Δr'_a (3), θ_2a (3)]   rows 12a .. 12a+9
//!   mid node of e:   [θ_2e+1 (3)]                      rows 12e+9 .. 12e+12
//! so element e owns the contiguous rows 12e .. 12e+21 and the tangent is
//! block-banded (half-bandwidth 20).

use super::element::{self, ElMat, ElVec, ElemDofs, Factors, NDOF_EL, NGP, STRIDE, Strain};
use super::gauss::F4;
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{V3, cayley, frame_from_tangent, skew};
use crate::model::RodConfig;

/// Rotational condition at an end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RotationBc {
    /// Free to rotate.
    Free,
    /// Free to rotate except about its own axis d3 (removes the rigid twist).
    TwistFixed,
    /// No rotation.
    Clamped,
}

/// Condition at an end of the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EndBc {
    pub position_fixed: bool,
    pub rotation: RotationBc,
}

impl EndBc {
    /// Pinned: position fixed, rotation free.
    pub const PINNED: EndBc = EndBc { position_fixed: true, rotation: RotationBc::Free };
    /// Pinned with the twist about the line's axis held (the scenes' anchor).
    pub const PINNED_NO_TWIST: EndBc = EndBc { position_fixed: true, rotation: RotationBc::TwistFixed };
    /// Clamped: position and rotation fixed.
    pub const CLAMPED: EndBc = EndBc { position_fixed: true, rotation: RotationBc::Clamped };
    /// Free end.
    pub const FREE: EndBc = EndBc { position_fixed: false, rotation: RotationBc::Free };
}

/// Section stiffness of the line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stiffness {
    /// EA, N.
    pub axial: f64,
    /// Shear stiffness, N: the paper's penalty R = EA.
    pub shear: f64,
    /// EI1, EI2, N m².
    pub bending: [f64; 2],
    /// GJ, N m².
    pub torsion: f64,
}

impl Stiffness {
    /// The paper's section: shear penalty R = EA, isotropic bending.
    pub fn paper(ea: f64, ei: f64, gj: f64) -> Self {
        Stiffness { axial: ea, shear: ea, bending: [ei, ei], torsion: gj }
    }

    /// Stiffness per strain component (γ_x, γ_y, γ_z, K1, K2, K3): the
    /// paper's penalty R acts on the whole vector γ = r' − d3 (extension and
    /// shear alike), so its three entries are the penalty `shear` (= EA in the
    /// paper; `axial` is the same number and names the line's EA).
    pub fn diagonal(&self) -> [f64; 6] {
        [self.shear, self.shear, self.shear, self.bending[0], self.bending[1], self.torsion]
    }
}

/// The discrete rod (everything but the state).
#[derive(Debug, Clone)]
pub struct Rod {
    pub n_el: usize,
    /// Unstretched length, m.
    pub length: f64,
    /// Element reference length, m.
    pub h: f64,
    /// Section stiffness of the first element (of every element on a uniform line).
    pub stiffness: Stiffness,
    /// Stiffness per strain component of each element (line sections, §11).
    stiff: Vec<[f64; 6]>,
    /// Conditions at S = 0 (hang-off) and S = L (anchor).
    pub ends: [EndBc; 2],
    /// A flex joint between the vessel and the line's end at S = 0 (its
    /// rotation unknowns free; docs/theory.md §15).
    pub flex_joint: Option<super::FlexJoint>,
    /// Stress-free reference configuration.
    pub reference: RodConfig,
    /// Reference strains at the Gauss points (eq. 4).
    eps0: Vec<[Strain; NGP]>,
    /// Reference penalty coefficients g⁰ at the Gauss points (element.rs).
    g0: Vec<[V3; NGP]>,
}

impl Rod {
    /// A rod of `n_el` equal elements whose stress-free state is straight.
    pub fn new(n_el: usize, length: f64, stiffness: Stiffness, ends: [EndBc; 2]) -> Self {
        assert!(n_el >= 1);
        let h = length / n_el as f64;
        let mut rod = Rod {
            n_el,
            length,
            h,
            stiffness,
            stiff: vec![stiffness.diagonal(); n_el],
            ends,
            flex_joint: None,
            reference: RodConfig { x: vec![], xp: vec![], d: vec![] },
            eps0: vec![],
            g0: vec![],
        };
        let straight = rod.straight(V3::zeros(), V3::x(), V3::y());
        rod.set_reference(straight);
        rod
    }

    /// Sets the stress-free configuration (reference strains, eq. 4).
    pub fn set_reference(&mut self, reference: RodConfig) {
        self.g0 =
            (0..self.n_el).map(|e| element::reference_penalty(&ElemDofs::gather(&reference, e), self.h)).collect();
        self.eps0 = (0..self.n_el)
            .map(|e| {
                let mut eps = element::gauss_strains(&ElemDofs::gather(&reference, e), self.h, &self.g0[e]);
                // γ vanishes in the reference by construction of g⁰ (not only to round-off)
                for row in eps.iter_mut() {
                    row[0] = 0.0;
                    row[1] = 0.0;
                    row[2] = 0.0;
                }
                eps
            })
            .collect();
        self.reference = reference;
    }

    /// Reference penalty coefficients g⁰ of element e at its Gauss points.
    pub fn reference_penalty(&self, e: usize) -> &[V3; NGP] {
        &self.g0[e]
    }

    /// Strains of element e of `cfg` at its Gauss points.
    pub fn element_strains(&self, cfg: &RodConfig, e: usize) -> [Strain; NGP] {
        element::gauss_strains(&ElemDofs::gather(cfg, e), self.h, &self.g0[e])
    }

    /// Strains of an element's gathered dofs at its Gauss points.
    pub fn strains_of(&self, el: &ElemDofs, e: usize) -> [Strain; NGP] {
        element::gauss_strains(el, self.h, &self.g0[e])
    }

    /// Stiffness per strain component of element e.
    pub fn stiff(&self, e: usize) -> &[f64; 6] {
        &self.stiff[e]
    }

    /// Gives each element its own section stiffness (line sections, §11).
    pub fn set_element_stiffness(&mut self, per_element: &[Stiffness]) {
        assert_eq!(per_element.len(), self.n_el);
        self.stiffness = per_element[0];
        self.stiff = per_element.iter().map(Stiffness::diagonal).collect();
    }

    /// Reference strains ε⁰ at the Gauss points of element e (eq. 4).
    pub fn reference_strains(&self, e: usize) -> &[Strain; NGP] {
        &self.eps0[e]
    }

    /// Stress resultants of the midpoint scheme, C(½(ε_n + ε_{n+1}) − ε⁰)
    /// (docs/theory.md §5.2): the stress at the average strain.
    pub fn midpoint_stresses(&self, e: usize, eps_n: &[Strain; NGP], eps_1: &[Strain; NGP]) -> [Strain; NGP] {
        let (k, eps0) = (&self.stiff[e], &self.eps0[e]);
        let mut s = [[0.0; 6]; NGP];
        for g in 0..NGP {
            for c in 0..6 {
                s[g][c] = k[c] * (0.5 * (eps_n[g][c] + eps_1[g][c]) - eps0[g][c]);
            }
        }
        s
    }

    /// [`Rod::midpoint_stresses`] with strains and stresses as rows over the
    /// Gauss points (the time step's residual kernel, [`super::gauss`]).
    pub fn midpoint_stress_rows(&self, e: usize, eps_n: &[F4; 6], eps_1: &[F4; 6]) -> [F4; 6] {
        let (k, eps0) = (&self.stiff[e], &self.eps0[e]);
        let mut s = [[0.0; NGP]; 6];
        for c in 0..6 {
            for g in 0..NGP {
                s[c][g] = k[c] * (0.5 * (eps_n[c][g] + eps_1[c][g]) - eps0[g][c]);
            }
        }
        s
    }

    /// Kelvin–Voigt stresses (η/h) C (ε_{n+1} − ε_n) of the objective
    /// material strains (theory §5.9).
    pub fn damping_stresses(
        &self,
        e: usize,
        eps_n: &[Strain; NGP],
        eps_1: &[Strain; NGP],
        eta_over_h: f64,
    ) -> [Strain; NGP] {
        let k = &self.stiff[e];
        let mut s = [[0.0; 6]; NGP];
        for g in 0..NGP {
            for c in 0..6 {
                s[g][c] = k[c] * eta_over_h * (eps_1[g][c] - eps_n[g][c]);
            }
        }
        s
    }

    /// Energy dissipated over a step by the Kelvin–Voigt stress,
    /// ∫ (η/h) Δε·C Δε dS over element e, J (≥ 0).
    pub fn damping_dissipation(&self, e: usize, eps_n: &[Strain; NGP], eps_1: &[Strain; NGP], eta_over_h: f64) -> f64 {
        let mut d = 0.0;
        for g in 0..NGP {
            let mut dg = 0.0;
            for c in 0..6 {
                let de = eps_1[g][c] - eps_n[g][c];
                dg += self.stiff[e][c] * de * de;
            }
            d += crate::math::shape::GAUSS4.w[g] * self.h * eta_over_h * dg;
        }
        d
    }

    /// Number of reduced unknowns.
    pub fn n_dof(&self) -> usize {
        STRIDE * self.n_el + 9
    }

    pub fn n_director_nodes(&self) -> usize {
        2 * self.n_el + 1
    }

    /// First row of r at end node a.
    pub fn x_dof(a: usize) -> usize {
        STRIDE * a
    }

    /// First row of r' at end node a.
    pub fn xp_dof(a: usize) -> usize {
        STRIDE * a + 3
    }

    /// First row of θ at director node j.
    pub fn theta_dof(j: usize) -> usize {
        if j % 2 == 0 { 6 * j + 6 } else { 6 * j + 3 }
    }

    /// Reference arc length of end node a.
    pub fn s_node(&self, a: usize) -> f64 {
        a as f64 * self.h
    }

    /// A straight, unstretched configuration from `start` along `dir`, with d2
    /// as close as possible to `d2_hint`.
    pub fn straight(&self, start: V3, dir: V3, d2_hint: V3) -> RodConfig {
        let t = dir.normalize();
        let frame = frame_from_tangent(&t, &d2_hint);
        RodConfig {
            x: (0..=self.n_el).map(|a| start + t * self.s_node(a)).collect(),
            xp: vec![t; self.n_el + 1],
            d: vec![frame; self.n_director_nodes()],
        }
    }

    /// Stress resultants C(ε − ε⁰) at the Gauss points of element e for strains `eps`.
    pub fn stresses(&self, e: usize, eps: &[Strain; NGP]) -> [Strain; NGP] {
        let mut s = [[0.0; 6]; NGP];
        for g in 0..NGP {
            for c in 0..6 {
                s[g][c] = self.stiff[e][c] * (eps[g][c] - self.eps0[e][g][c]);
            }
        }
        s
    }

    /// Stored energy of a configuration, J.
    pub fn strain_energy(&self, cfg: &RodConfig) -> f64 {
        (0..self.n_el)
            .map(|e| {
                let eps = self.element_strains(cfg, e);
                element::energy(&eps, &self.eps0[e], &self.stiff[e], self.h)
            })
            .sum()
    }

    /// A tangent matrix with this rod's pattern.
    pub fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        BandedSystem::new(self.n_el, NDOF_EL, STRIDE)
    }

    /// Adds the static internal force ∂W/∂q (reduced) to `r` and, if given, its
    /// tangent to `sys`.
    pub fn add_internal_force(&self, cfg: &RodConfig, r: &mut [f64], mut sys: Option<&mut BandedSystem>) {
        for e in 0..self.n_el {
            let el = ElemDofs::gather(cfg, e);
            let eps = self.strains_of(&el, e);
            let s = self.stresses(e, &eps);
            let mut re = ElVec::zeros();
            let mut ke = ElMat::zeros();
            let kt = if sys.is_some() { Some(&mut ke) } else { None };
            element::internal_force(
                &el,
                &el,
                &s,
                &self.stiff[e],
                Factors::STATIC,
                self.h,
                element::Shear::Spatial(&self.g0[e]),
                &mut re,
                kt,
            );
            let off = STRIDE * e;
            for i in 0..NDOF_EL {
                r[off + i] += re[i];
            }
            if let Some(sys) = sys.as_deref_mut() {
                sys.add_block(e, |i, j| ke[(i, j)]);
            }
        }
    }

    /// Director nodes whose rotation increments are expressed in their own
    /// frame (θ = D θ_loc) so that a twist condition is a single fixed unknown.
    pub fn local_basis_nodes(&self) -> impl Iterator<Item = usize> + '_ {
        // (an iterator, not a Vec: the step's basis changes allocate nothing)
        [(0, 0), (1, 2 * self.n_el)]
            .into_iter()
            .filter(|&(end, _)| self.ends[end].rotation == RotationBc::TwistFixed)
            .map(|(_, j)| j)
    }

    /// Unknowns held at zero by the end conditions.
    pub fn fixed_dofs(&self) -> Vec<usize> {
        let mut v = Vec::new();
        for (end, bc) in self.ends.iter().enumerate() {
            let a = if end == 0 { 0 } else { self.n_el };
            let j = 2 * a;
            if bc.position_fixed {
                v.extend(Self::x_dof(a)..Self::x_dof(a) + 3);
            }
            match bc.rotation {
                RotationBc::Free => {}
                RotationBc::TwistFixed => v.push(Self::theta_dof(j) + 2),
                RotationBc::Clamped => v.extend(Self::theta_dof(j)..Self::theta_dof(j) + 3),
            }
        }
        v
    }

    /// Expresses the rotation unknowns of the local-basis nodes in their frame
    /// D: rows and columns become Dᵀ(·) and (·)D, and the change of the frame
    /// itself adds `Dᵀ [m]× D`, m the spatial residual moment (docs/theory.md §3.4).
    pub fn to_local_basis(&self, cfg: &RodConfig, r: &mut [f64], sys: Option<&mut BandedSystem>) {
        let mut sys = sys;
        for j in self.local_basis_nodes() {
            let i0 = Self::theta_dof(j);
            let d = cfg.d[j];
            let m = V3::new(r[i0], r[i0 + 1], r[i0 + 2]);
            let ml = d.transpose() * m;
            r[i0..i0 + 3].copy_from_slice(ml.as_slice());
            if let Some(sys) = sys.as_deref_mut() {
                sys.transform_dofs(i0, &d);
                let extra = d.transpose() * skew(&m) * d;
                for a in 0..3 {
                    for b in 0..3 {
                        sys.add(i0 + a, i0 + b, extra[(a, b)]);
                    }
                }
            }
        }
    }

    /// Scales a Newton increment so that no director rotates by more than
    /// `max_angle` (rad) in one iteration (the Cayley map is exact for any
    /// angle, Newton's linear model is not).
    pub fn limit_rotation_increments(&self, du: &mut [f64], max_angle: f64) {
        let mut theta_max: f64 = 0.0;
        for j in 0..self.n_director_nodes() {
            let i = Self::theta_dof(j);
            theta_max = theta_max.max(V3::new(du[i], du[i + 1], du[i + 2]).norm());
        }
        if theta_max > max_angle {
            let f = max_angle / theta_max;
            du.iter_mut().for_each(|v| *v *= f);
        }
    }

    /// The round-off of a residual evaluated at `cfg`, N: the axial force
    /// comes from r' = Σ N'_k r_k, i.e. differences of positions of size |r|
    /// over h, so no residual is more precise than R ε_mach |r|/h.
    pub fn residual_roundoff(&self, cfg: &RodConfig) -> f64 {
        let extent = cfg.x.iter().fold(0.0f64, |m, x| m.max(x.norm())).max(self.length);
        let penalty = self.stiff.iter().fold(0.0f64, |m, s| m.max(s[0]));
        penalty * f64::EPSILON * extent / self.h
    }

    /// q ← q ⊕ Δu: additive on r and r', Cayley on the directors
    /// (d_i ← cay(θ) d_i), with θ = D θ_loc at the local-basis nodes.
    pub fn apply_increment(&self, cfg: &mut RodConfig, du: &[f64]) {
        for a in 0..=self.n_el {
            let i = Self::x_dof(a);
            cfg.x[a] += V3::new(du[i], du[i + 1], du[i + 2]);
            let i = Self::xp_dof(a);
            cfg.xp[a] += V3::new(du[i], du[i + 1], du[i + 2]);
        }
        for j in 0..self.n_director_nodes() {
            let i = Self::theta_dof(j);
            let mut th = V3::new(du[i], du[i + 1], du[i + 2]);
            if self.local_basis_nodes().any(|n| n == j) {
                th = cfg.d[j] * th;
            }
            cfg.d[j] = cayley(&th) * cfg.d[j];
        }
    }

    /// Force resultant n = R γ (N, spatial) and unit tangent at ξ of element e.
    pub fn force_resultant(&self, cfg: &RodConfig, e: usize, xi: f64) -> (V3, V3) {
        let el = ElemDofs::gather(cfg, e);
        let g0 = element::reference_penalty_at(&ElemDofs::gather(&self.reference, e), xi, self.h);
        let eps = element::strains_at(&el, xi, self.h, &g0);
        let nds = crate::math::shape::hermite_ds(xi, self.h);
        let n = V3::new(eps[0], eps[1], eps[2]) * self.stiff[e][0];
        let p: V3 = (0..4).map(|k| el.c[k] * nds[k]).sum();
        (n, p.normalize())
    }

    /// Axial force n·t (N, effective tension; negative = compression) at ξ of element e.
    pub fn axial_force(&self, cfg: &RodConfig, e: usize, xi: f64) -> f64 {
        let (n, t) = self.force_resultant(cfg, e, xi);
        n.dot(&t)
    }

    /// The line at each Gauss point of `cfg`: position, effective tension and
    /// the two bending curvatures (docs/theory.md §12).
    pub fn gauss_points(&self, cfg: &crate::model::RodConfig) -> Vec<crate::model::outputs::LinePoint> {
        let rod = self;
        let mut out = Vec::with_capacity(4 * rod.n_el);
        for e in 0..rod.n_el {
            let el = ElemDofs::gather(cfg, e);
            let eps = rod.strains_of(&el, e);
            for (g, &xi) in crate::math::shape::GAUSS4.xi.iter().enumerate() {
                let (n, nds) = (crate::math::shape::hermite(xi, rod.h), crate::math::shape::hermite_ds(xi, rod.h));
                let position: V3 = (0..4).map(|k| el.c[k] * n[k]).sum();
                let tangent: V3 = (0..4).map(|k| el.c[k] * nds[k]).sum();
                let axial = V3::new(eps[g][0], eps[g][1], eps[g][2]) * rod.stiff(e)[0];
                out.push(crate::model::outputs::LinePoint {
                    element: e,
                    s: rod.s_node(e) + xi * rod.h,
                    position,
                    tension: axial.dot(&tangent.normalize()),
                    curvature: [eps[g][3], eps[g][4]],
                    twist: eps[g][5],
                });
            }
        }
        out
    }

    /// Smallest axial force at the Gauss points of all elements, N (with the
    /// stored reference coefficients; the quantity `min_tension` scans).
    pub fn min_gauss_axial_force(&self, cfg: &RodConfig) -> f64 {
        let mut m = f64::INFINITY;
        for e in 0..self.n_el {
            let el = ElemDofs::gather(cfg, e);
            let eps = self.strains_of(&el, e);
            for (g, xi) in crate::math::shape::GAUSS4.xi.iter().enumerate() {
                let nds = crate::math::shape::hermite_ds(*xi, self.h);
                let p: V3 = (0..4).map(|k| el.c[k] * nds[k]).sum();
                let n = V3::new(eps[g][0], eps[g][1], eps[g][2]) * self.stiff[e][0];
                m = m.min(n.dot(&p.normalize()));
            }
        }
        m
    }

    /// Axial force at the end nodes (averaged between the two elements at an interior node).
    pub fn nodal_axial_force(&self, cfg: &RodConfig) -> Vec<f64> {
        let mut t = vec![0.0; self.n_el + 1];
        for a in 0..=self.n_el {
            t[a] = if a == 0 {
                self.axial_force(cfg, 0, 0.0)
            } else if a == self.n_el {
                self.axial_force(cfg, self.n_el - 1, 1.0)
            } else {
                0.5 * (self.axial_force(cfg, a - 1, 1.0) + self.axial_force(cfg, a, 0.0))
            };
        }
        t
    }

    /// Centreline position at reference arc length s (Hermite interpolation).
    pub fn position_at(&self, cfg: &RodConfig, s: f64) -> V3 {
        let s = s.clamp(0.0, self.length);
        let e = ((s / self.h) as usize).min(self.n_el - 1);
        let xi = (s - e as f64 * self.h) / self.h;
        let n = crate::math::shape::hermite(xi, self.h);
        let el = ElemDofs::gather(cfg, e);
        (0..4).map(|k| el.c[k] * n[k]).sum()
    }
}
