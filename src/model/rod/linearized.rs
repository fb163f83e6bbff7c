//! The rod linearised about a configuration (docs/theory.md §8): the static
//! tangent of its static problem and the mass matrix in the same reduced
//! unknowns (Δr, Δr', θ), for the modal analysis and the hang-off stiffness.

use super::dofs::{C_OFF, ElMat, NGP, T_OFF};
use super::statics::{StaticLoads, StaticProblem};
use super::{Rod, RodModel};
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::shape::{GAUSS4, hermite, hermite_ds, lagrange};
use crate::math::{M3, V3, skew};
use crate::model::RodConfig;
use crate::model::linearized::{EndRotation, Linearized, ModeMotion};

/// The rod of a dynamic model with the loads of its statics.
pub struct RodLinearized<'a> {
    pub model: &'a RodModel,
    statics: StaticProblem<'a>,
}

impl<'a> RodLinearized<'a> {
    pub fn new(model: &'a RodModel, loads: &'a StaticLoads) -> Self {
        RodLinearized { model, statics: StaticProblem::new(&model.rod, loads) }
    }

    /// The rod linearised from its static problem's parts ([`StaticProblem::into_parts`]): nothing allocated.
    pub fn from_parts(model: &'a RodModel, loads: &'a StaticLoads, parts: super::statics::StaticParts) -> Self {
        RodLinearized { model, statics: StaticProblem::from_parts(&model.rod, loads, parts) }
    }

    /// Its static problem's parts, to build it again without allocating.
    pub fn into_parts(self) -> super::statics::StaticParts {
        self.statics.into_parts()
    }

    /// Spatial rotation of director node j from the unknowns (θ = D θ_loc at
    /// the nodes whose rotation is expressed in their own frame).
    fn rotation(&self, cfg: &RodConfig, phi: &[f64], j: usize, local: &[usize]) -> V3 {
        let i = Rod::theta_dof(j);
        let th = V3::new(phi[i], phi[i + 1], phi[i + 2]);
        if local.contains(&j) { cfg.d[j] * th } else { th }
    }
}

/// The element mass matrix in the reduced unknowns (eq. 8.3): the Hermite
/// mass ρ̄ ∫ N_k N_l dS of the centreline plus the added mass
/// m_a ∫ N_k N_l (I − t tᵀ) dS, and for the directors, from
/// ḋ_i = Σ_A L_A ω_A × d_iA, the rotary mass Σ_i J_i ∫ L_A L_B skew(d_iA)ᵀ skew(d_iB) dS.
pub fn element_mass(model: &RodModel, cfg: &RodConfig, e: usize) -> ElMat {
    let rod = &model.rod;
    let mut me = ElMat::zeros();
    let c = [cfg.x[e], cfg.xp[e], cfg.x[e + 1], cfg.xp[e + 1]];
    let mass = model.mass.at(e);
    for k in 0..4 {
        for l in 0..4 {
            for a in 0..3 {
                me[(C_OFF[k] + a, C_OFF[l] + a)] += mass.centre[k][l];
            }
        }
    }
    let fluid = model.fluid.at(e);
    let ma = fluid.added_mass;
    if ma > 0.0 {
        for g in 0..NGP {
            let xi = GAUSS4.xi[g];
            let n = hermite(xi, rod.h);
            let nd = hermite_ds(xi, rod.h);
            // on the submerged fraction of the line only (§10)
            let z: f64 = (0..4).map(|k| c[k].z * n[k]).sum();
            let wet = fluid.surface.as_ref().map_or(1.0, |s| s.submerged(z).0);
            let w = GAUSS4.w[g] * rod.h * ma * wet;
            let p: V3 = (0..4).map(|k| c[k] * nd[k]).sum();
            let t = p.normalize();
            let normal = M3::identity() - t * t.transpose();
            for k in 0..4 {
                for l in 0..4 {
                    let b = normal * (w * n[k] * n[l]);
                    for i in 0..3 {
                        for j in 0..3 {
                            me[(C_OFF[k] + i, C_OFF[l] + j)] += b[(i, j)];
                        }
                    }
                }
            }
        }
    }
    let d = [cfg.d[2 * e], cfg.d[2 * e + 1], cfg.d[2 * e + 2]];
    for a in 0..3 {
        for b in 0..3 {
            let mut blk = M3::zeros();
            for i in 0..2 {
                let da = skew(&d[a].column(i).into());
                let db = skew(&d[b].column(i).into());
                blk += da.transpose() * db * mass.rotary[i];
            }
            blk *= mass.director[a][b];
            for i in 0..3 {
                for j in 0..3 {
                    me[(T_OFF[a] + i, T_OFF[b] + j)] += blk[(i, j)];
                }
            }
        }
    }
    me
}

impl Linearized for RodLinearized<'_> {
    fn n_dof(&self) -> usize {
        self.model.rod.n_dof()
    }

    fn new_system(&self) -> Result<BandedSystem, LinearSolveError> {
        self.model.rod.new_system()
    }

    fn fixed_dofs(&self) -> Vec<usize> {
        let mut f = self.model.rod.fixed_dofs();
        f.sort_unstable();
        f
    }

    fn hang_off_rows(&self) -> [usize; 3] {
        let i = Rod::x_dof(0);
        [i, i + 1, i + 2]
    }

    fn anchor_rows(&self) -> [usize; 3] {
        let i = Rod::x_dof(self.model.rod.n_el);
        [i, i + 1, i + 2]
    }

    fn static_tangent(&self, cfg: &RodConfig, r: &mut [f64], k: &mut BandedSystem) {
        self.statics.residual(cfg, r, Some(k));
    }

    /// A clamp holds the end's rotation (spatial unknowns: the end is not a
    /// local-basis node); a flex joint's moment m(d, f) is objective,
    /// m(Q d, Q f) = Q m, so its derivative along the vessel frame's turn is
    /// ∂m/∂θ_f = −\[m\]× − ∂m/∂θ_d (docs/theory.md §15).
    fn hang_off_end(&self, cfg: &RodConfig) -> EndRotation {
        let rod = &self.model.rod;
        let i = Rod::theta_dof(0);
        let rows = [i, i + 1, i + 2];
        if rod.ends[0].rotation == super::RotationBc::Clamped {
            return EndRotation::Clamped { rows };
        }
        match &rod.flex_joint {
            Some(joint) if joint.frame.is_some() && rod.ends[0].rotation == super::RotationBc::Free => {
                let (m, k_end) = joint.static_moment(&cfg.d[0], &joint.frame.unwrap_or_else(M3::identity));
                EndRotation::Joint { rows, k_end, k_vessel: -skew(&m) - k_end }
            }
            _ => EndRotation::Pinned,
        }
    }

    fn mass_matrix(&self, cfg: &RodConfig, m: &mut BandedSystem) {
        m.clear();
        let rod = &self.model.rod;
        for e in 0..rod.n_el {
            let me = element_mass(self.model, cfg, e);
            m.add_block(e, |i, j| me[(i, j)]);
        }
        // the rotations of local-basis nodes are D θ_loc, as in the tangent
        for j in rod.local_basis_nodes() {
            m.transform_dofs(Rod::theta_dof(j), &cfg.d[j]);
        }
    }

    fn motion(&self, cfg: &RodConfig, phi: &[f64], normal: &V3) -> ModeMotion {
        let rod = &self.model.rod;
        let local: Vec<usize> = rod.local_basis_nodes().collect();
        let node_u = |a: usize| {
            let i = Rod::x_dof(a);
            V3::new(phi[i], phi[i + 1], phi[i + 2])
        };
        let nodes = (0..=rod.n_el)
            .map(|a| {
                let j = 2 * a;
                let twist = self.rotation(cfg, phi, j, &local).dot(&cfg.d[j].column(2));
                (rod.s_node(a), node_u(a), twist)
            })
            .collect();
        // kinetic energy split at the Gauss points (eq. 8.5)
        let mut e = [0.0; 4];
        for el in 0..rod.n_el {
            let (mass, fluid) = (self.model.mass.at(el), self.model.fluid.at(el));
            let rho = mass.mass_per_length();
            let polar = mass.rotary[0] + mass.rotary[1];
            let c = [cfg.x[el], cfg.xp[el], cfg.x[el + 1], cfg.xp[el + 1]];
            let i = [Rod::x_dof(el), Rod::xp_dof(el), Rod::x_dof(el + 1), Rod::xp_dof(el + 1)];
            let uc: [V3; 4] = std::array::from_fn(|k| V3::new(phi[i[k]], phi[i[k] + 1], phi[i[k] + 2]));
            let th: [V3; 3] = std::array::from_fn(|a| self.rotation(cfg, phi, 2 * el + a, &local));
            let d3: [V3; 3] = std::array::from_fn(|a| cfg.d[2 * el + a].column(2).into());
            for g in 0..NGP {
                let xi = GAUSS4.xi[g];
                let w = GAUSS4.w[g] * rod.h;
                let n = hermite(xi, rod.h);
                let nd = hermite_ds(xi, rod.h);
                let l = lagrange(xi);
                let t = (0..4).map(|k| c[k] * nd[k]).sum::<V3>().normalize();
                let u: V3 = (0..4).map(|k| uc[k] * n[k]).sum();
                // the added mass on the submerged fraction, as in the mass matrix
                let z: f64 = (0..4).map(|k| c[k].z * n[k]).sum();
                let ma = fluid.added_mass * fluid.surface.as_ref().map_or(1.0, |s| s.submerged(z).0);
                let ua = u.dot(&t);
                let un = u.dot(normal);
                let ui = (u - t * ua - normal * un).norm();
                let twist: f64 = (0..3).map(|a| l[a] * th[a].dot(&d3[a])).sum();
                e[0] += w * (rho + ma) * ui * ui;
                e[1] += w * (rho + ma) * un * un;
                e[2] += w * rho * ua * ua;
                e[3] += w * polar * twist * twist;
            }
        }
        let total: f64 = e.iter().sum();
        let fractions = if total > 0.0 { e.map(|v| v / total) } else { [0.0; 4] };
        ModeMotion { nodes, fractions }
    }
}
