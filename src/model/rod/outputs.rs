//! The rod's outputs at a state: end reactions, tensions, energies, shape.

use super::element::{self, ElVec, ElemDofs, Factors};
use super::{Rod, RodModel};
use crate::loads::fluid::{FluidFactors, FluidFields, element_fluid_force, hermite_at_gauss, water_at};
use crate::loads::{seabed, surface};
use crate::math::V3;
use crate::model::State;
use crate::model::outputs::{Outputs, SHAPE_POINTS};

impl RodModel {
    /// Force of the supports on the line at S = 0 and S = L in `state`, N:
    /// the end rows of the equations of motion at the state (internal force,
    /// weight and water at the state; inertia with the last step's acceleration).
    pub fn end_reactions(&self, s: &State) -> [V3; 2] {
        [self.end_reaction(s, 0), self.end_reaction(s, 1)]
    }

    /// The force of the support at end `end` (0: S = 0, 1: S = L) in
    /// `state`, N: one of [`RodModel::end_reactions`] (the top's alone is
    /// the FMU's per-step force: the anchor's water is not evaluated).
    pub fn end_reaction(&self, s: &State, end: usize) -> V3 {
        let rod = &self.rod;
        let n = rod.n_el;
        let (e, k) = if end == 0 { (0usize, 0usize) } else { (n - 1, 2) };
        let el = ElemDofs::gather(&s.config, e);
        let eps = rod.strains_of(&el, e);
        let st = rod.stresses(e, &eps);
        let mut re = ElVec::zeros();
        element::internal_force(
            &el,
            &el,
            &st,
            rod.stiff(e),
            Factors::STATIC,
            rod.h,
            element::Shear::Spatial(rod.reference_penalty(e)),
            &mut re,
            None,
        );
        let node = if end == 0 { 0 } else { n };
        let g = self.gravity_vector();
        let mut f = V3::new(re[12 * (k / 2)], re[12 * (k / 2) + 1], re[12 * (k / 2) + 2]);
        f -= V3::new(g[Rod::x_dof(node)], g[Rod::x_dof(node) + 1], g[Rod::x_dof(node) + 2]);
        let acc = &s.end_accel[end];
        let (mass, fluid) = (self.mass.at(e), self.fluid.at(e));
        for m in 0..4 {
            f += acc[m] * mass.centre[k][m];
        }
        // the waves at the state (§13.6)
        let shapes = hermite_at_gauss(rod.h);
        let water = self.sea.as_ref().map(|sea| {
            let points = shapes.map(|(n, _)| (0..4).map(|k| el.c[k] * n[k]).sum::<V3>());
            water_at(sea, &points, s.time)
        });
        if !fluid.is_inert_in(water.is_some()) {
            let mut ff = [V3::zeros(); 4];
            let fac = FluidFactors { position: 0.0, velocity: 0.0, acceleration: 0.0 };
            let v = s.hermite_velocity(e);
            element_fluid_force(
                fluid,
                self.current_ramp.at(s.time).0,
                FluidFields { c: &el.c, v: &v, a: acc, water: water.as_ref() },
                &shapes,
                rod.s_node(e),
                rod.h,
                fac,
                &mut ff,
                None,
            );
            f -= ff[k];
        }
        // (an element wholly below the band the surface sweeps gets
        // nothing from it: every point of the composite rule is skipped)
        let sweep = self.sea.as_ref().map_or(0.0, |s| s.max_elevation());
        if let Some(fsurf) = &fluid.surface
            && !fsurf.lowered(water.as_ref().map_or(sweep, |w| w.depression.min(sweep))).hermite_below(&el.c, rod.h)
        {
            let mut fs = [V3::zeros(); 4];
            let eta = water.as_ref().map(|w| move |xi: f64| w.elevation_at(xi));
            surface::element_static_force(
                fsurf,
                &el.c,
                |xi| crate::math::shape::hermite(xi, rod.h),
                rod.h,
                eta.as_ref().map(|f| f as &dyn Fn(f64) -> f64),
                &mut fs,
                None,
            );
            f -= fs[k];
        }
        if let Some(bed) = self.seabed.as_ref().map(|b| b.at(e)) {
            let mut fs = [V3::zeros(); 4];
            let v = s.hermite_velocity(e);
            seabed::element_state_force(bed, &el.c, &v, &hermite_at_gauss(rod.h), seabed::hermite_at, rod.h, &mut fs);
            f -= fs[k];
        }
        f
    }

    /// Effective tension (the axial force n·t, N) and curvature (|K₁, K₂|,
    /// 1/m) at every node of `cfg`: at an end the nearest Gauss point's
    /// value, inside the mean of the two nearest (one in each element).
    pub fn node_profile(&self, cfg: &crate::model::RodConfig) -> Vec<(f64, f64)> {
        let rod = &self.rod;
        let mut out = vec![(0.0, 0.0); rod.n_el + 1];
        for e in 0..rod.n_el {
            let el = ElemDofs::gather(cfg, e);
            let eps = rod.strains_of(&el, e);
            for (g, node, w) in [(0usize, e, 1.0), (3, e + 1, 1.0)] {
                let xi = crate::math::shape::GAUSS4.xi[g];
                let nds = crate::math::shape::hermite_ds(xi, rod.h);
                let p: V3 = (0..4).map(|k| el.c[k] * nds[k]).sum();
                let n = V3::new(eps[g][0], eps[g][1], eps[g][2]) * rod.stiff(e)[0];
                let tension = n.dot(&p.normalize());
                let curvature = eps[g][3].hypot(eps[g][4]);
                let both = node > 0 && node < rod.n_el;
                let f = if both { 0.5 * w } else { w };
                out[node].0 += f * tension;
                out[node].1 += f * curvature;
            }
        }
        out
    }

    /// Every output quantity of `state`.
    pub fn outputs(&self, s: &State) -> Outputs {
        let rod = &self.rod;
        let cfg = &s.config;
        let reactions = self.end_reactions(s);
        let t0 = cfg.xp[0].normalize();
        let t1 = cfg.xp[rod.n_el].normalize();
        let min_tension = (-reactions[0].dot(&t0)).min(reactions[1].dot(&t1)).min(rod.min_gauss_axial_force(cfg));
        let kinetic = self.kinetic_energy(s);
        let strain = rod.strain_energy(cfg);
        let potential = self.potential_energy(cfg);
        let mut shape = [V3::zeros(); SHAPE_POINTS];
        for (k, p) in shape.iter_mut().enumerate() {
            *p = rod.position_at(cfg, rod.length * k as f64 / (SHAPE_POINTS - 1) as f64);
        }
        let touchdown = match &self.seabed {
            Some(bed) => seabed::touchdown(bed.first(), &cfg.x, |a| rod.s_node(a), rod.length),
            None => rod.length,
        };
        let mut o =
            Outputs::of_state(s, reactions, min_tension, [kinetic, strain, potential], touchdown, cfg.xp[0], shape);
        o.hang_off_moment = self.hang_off_moment(cfg);
        if self.rod.ends[0].rotation == super::RotationBc::Clamped {
            o.end_moment = self.end_moment(s);
        }
        if let (Some(joint), Some(f)) = (&self.rod.flex_joint, self.joint_frame(&s.hang_off.rotation)) {
            // the joint's moment on the vessel, its angle and its energy,
            // counted as strain energy (§15)
            o.end_moment = joint.static_moment(&cfg.d[0], &f).0;
            o.flex_joint_angle = super::FlexJoint::angle(&cfg.d[0], &f);
            let v = joint.energy(&cfg.d[0], &f);
            o.strain_energy += v;
            o.total_energy += v;
        }
        o
    }

    /// The moment the line exerts on its support at S = 0 in `state`, global
    /// frame, N m: minus the support's reaction, the moment row of the
    /// equations of motion at the end's director node at the state (the
    /// internal moment's row; the director inertia, of the rotary inertia
    /// alone, left out), as the end forces are read (§15).
    pub fn end_moment(&self, s: &State) -> V3 {
        let rod = &self.rod;
        let el = ElemDofs::gather(&s.config, 0);
        let st = rod.stresses(0, &rod.strains_of(&el, 0));
        let mut re = ElVec::zeros();
        let shear = element::Shear::Spatial(rod.reference_penalty(0));
        element::internal_force(&el, &el, &st, rod.stiff(0), Factors::STATIC, rod.h, shear, &mut re, None);
        -V3::new(re[6], re[7], re[8])
    }

    /// The moment the line exerts on its support at S = 0, global frame, N m
    /// (15.1), from the curvature: the stress couple m = Σᵢ Cᵢ Kᵢ dᵢ with the curvatures and twist
    /// of the first element's two Gauss points nearest the end extrapolated
    /// to it, and the end's directors.
    pub fn hang_off_moment_vector(&self, cfg: &crate::model::RodConfig) -> V3 {
        let rod = &self.rod;
        let eps = rod.strains_of(&ElemDofs::gather(cfg, 0), 0);
        let xi = crate::math::shape::GAUSS4.xi;
        let w = xi[0] / (xi[1] - xi[0]);
        let c = rod.stiff(0);
        let m = V3::from_fn(|i, _| c[3 + i] * ((1.0 + w) * eps[0][3 + i] - w * eps[1][3 + i]));
        cfg.d[0] * m
    }

    /// The bending moment at S = 0, N m (15.1): the curvature vector of the
    /// first element's two Gauss points nearest the hang-off extrapolated
    /// linearly to the end, times EI.
    pub fn hang_off_moment(&self, cfg: &crate::model::RodConfig) -> f64 {
        let rod = &self.rod;
        let eps = rod.strains_of(&ElemDofs::gather(cfg, 0), 0);
        let xi = crate::math::shape::GAUSS4.xi;
        let w = xi[0] / (xi[1] - xi[0]);
        let k = |i: usize| (1.0 + w) * eps[0][i] - w * eps[1][i];
        rod.stiff(0)[3] * k(3).hypot(k(4))
    }
}
