//! The cable linearised about a configuration (docs/theory.md §8): the
//! tangent of its static problem and its mass in the node positions.

use super::statics::CableStatics;
use super::{CableModel, NODE_DOF};
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::shape::GAUSS4;
use crate::math::{M3, V3};
use crate::model::RodConfig;
use crate::model::linearized::{Linearized, ModeMotion};

/// The cable of a dynamic model with the loads of its statics.
pub struct CableLinearized<'a> {
    pub model: &'a CableModel,
    statics: CableStatics<'a>,
}

impl<'a> CableLinearized<'a> {
    /// `with_current`: the statics include the current's drag.
    pub fn new(model: &'a CableModel, with_current: bool) -> Self {
        CableLinearized { model, statics: CableStatics::new(model, with_current) }
    }

    /// The cable linearised from its statics' parts ([`CableStatics::into_parts`]): nothing allocated.
    pub fn from_parts(model: &'a CableModel, parts: super::statics::CableStaticParts) -> Self {
        CableLinearized { model, statics: CableStatics::from_parts(model, parts) }
    }

    /// Its statics' parts, to build it again without allocating.
    pub fn into_parts(self) -> super::statics::CableStaticParts {
        self.statics.into_parts()
    }
}

impl Linearized for CableLinearized<'_> {
    fn n_dof(&self) -> usize {
        self.model.cable.n_dof()
    }

    fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        self.model.cable.new_system()
    }

    fn fixed_dofs(&self) -> Vec<usize> {
        self.model.cable.fixed_dofs()
    }

    fn hang_off_rows(&self) -> [usize; 3] {
        [0, 1, 2]
    }

    fn anchor_rows(&self) -> [usize; 3] {
        let i = NODE_DOF * self.model.cable.n_el;
        [i, i + 1, i + 2]
    }

    fn static_tangent(&self, cfg: &RodConfig, r: &mut [f64], k: &mut BandedSystem) {
        self.statics.residual(&cfg.x, r, Some(k));
    }

    /// The segment mass of the dynamics, ρ̄ l/12 [[5, 1], [1, 5]] (6.4), and
    /// the added mass m_a ∫ N_a N_b dS (I − t tᵀ) = m_a l/6 [[2, 1], [1, 2]] ⊗
    /// (I − t tᵀ) about the chord t (eq. 8.4).
    fn mass_matrix(&self, cfg: &RodConfig, m: &mut BandedSystem) {
        m.clear();
        let c = &self.model.cable;
        for e in 0..c.n_el {
            let fluid = self.model.fluid.at(e);
            // m_a ∫ s N_a N_b dS with s the submerged fraction (§10; l/6 [[2, 1], [1, 2]] under water)
            let mut added = [[0.0; 2]; 2];
            if fluid.added_mass > 0.0 {
                for g in 0..4 {
                    let xi = GAUSS4.xi[g];
                    let n = [1.0 - xi, xi];
                    let z = cfg.x[e].z * n[0] + cfg.x[e + 1].z * n[1];
                    let wet = fluid.surface.as_ref().map_or(1.0, |s| s.submerged(z).0);
                    for a in 0..2 {
                        for b in 0..2 {
                            added[a][b] += GAUSS4.w[g] * c.l * fluid.added_mass * wet * n[a] * n[b];
                        }
                    }
                }
            }
            let mass = self.model.mass.at(e);
            let t = (cfg.x[e + 1] - cfg.x[e]).normalize();
            let normal = M3::identity() - t * t.transpose();
            m.add_block(e, |i, j| {
                let (a, b) = (i / NODE_DOF, j / NODE_DOF);
                let (ii, jj) = (i % NODE_DOF, j % NODE_DOF);
                let structural = if ii == jj { mass[a][b] } else { 0.0 };
                structural + added[a][b] * normal[(ii, jj)]
            });
        }
    }

    fn motion(&self, cfg: &RodConfig, phi: &[f64], normal: &V3) -> ModeMotion {
        let c = &self.model.cable;
        let u = |a: usize| V3::new(phi[NODE_DOF * a], phi[NODE_DOF * a + 1], phi[NODE_DOF * a + 2]);
        let nodes = (0..=c.n_el).map(|a| (c.s_node(a), u(a), 0.0)).collect();
        let mut e = [0.0; 4];
        // ∫ |u|² over a segment with linear u: l/3 (|u_a|² + u_a·u_b + |u_b|²), per component
        let quad = |pa: f64, pb: f64| c.l / 3.0 * (pa * pa + pa * pb + pb * pb);
        for s in 0..c.n_el {
            let m = self.model.mass.at(s);
            let fluid = self.model.fluid.at(s);
            // the added mass on the submerged fraction (at the segment's middle)
            let wet = fluid.surface.as_ref().map_or(1.0, |f| f.submerged(0.5 * (cfg.x[s].z + cfg.x[s + 1].z)).0);
            let (rho, ma) = (2.0 * (m[0][0] + m[0][1]) / c.l, fluid.added_mass * wet);
            let t = (cfg.x[s + 1] - cfg.x[s]).normalize();
            let (ua, ub) = (u(s), u(s + 1));
            let axial = quad(ua.dot(&t), ub.dot(&t));
            let out = quad(ua.dot(normal), ub.dot(normal));
            let all = quad(ua.x, ub.x) + quad(ua.y, ub.y) + quad(ua.z, ub.z);
            e[0] += (rho + ma) * (all - axial - out).max(0.0);
            e[1] += (rho + ma) * out;
            e[2] += rho * axial;
        }
        let total: f64 = e.iter().sum();
        let fractions = if total > 0.0 { e.map(|v| v / total) } else { [0.0; 4] };
        ModeMotion { nodes, fractions }
    }
}
