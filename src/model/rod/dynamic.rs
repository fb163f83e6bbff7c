//! The rod's dynamic model: everything about the line that does not change
//! during a run (rod, mass, weight, water), its energies and momenta.

use super::mass::ElementMass;
use super::statics::vertical_load_vector;
use super::{Rod, of_properties};
use crate::loads::seabed::{self, Seabed};
use crate::loads::waves::{Ramp, Sea};
use crate::loads::weight::VerticalLoad;
use crate::loads::{self, fluid::Fluid};
use crate::math::{M3, V3};
use crate::model::sections::{self, PerElement};
use crate::model::{RodConfig, State};
use crate::scene::Scene;

/// Everything about the line that does not change during a run.
#[derive(Debug, Clone)]
pub struct RodModel {
    pub rod: Rod,
    /// Element mass matrices (per section, §11).
    pub mass: PerElement<ElementMass>,
    /// Weight, buoyancy, buoyancy modules.
    pub vertical: VerticalLoad,
    /// Drag, added mass and free surface of each element.
    pub fluid: PerElement<Fluid>,
    /// The seabed under each element (None: no contact anywhere, no cost).
    pub seabed: Option<PerElement<Seabed>>,
    /// Consistent nodal vector of the vertical load, N (and N m on r' rows).
    f_grav: Vec<f64>,
    /// The sea whose waves act on the line (None: still water; §13.6).
    pub sea: Option<Sea>,
    /// The current's growth from the run's start (duration 0: in full from
    /// the start, the paper's; docs/theory.md §5.11).
    pub current_ramp: Ramp,
    /// Where the anchor end (S = L) is at the end of the next step and its
    /// velocity there (None: held where it is, at rest). A system's free
    /// point moves it, the end pinned, its twist held as at a fixed anchor
    /// (docs/theory.md §17.7); its work is `work_anchor`.
    pub anchor_motion: Option<crate::model::AnchorMotion>,
}

impl RodModel {
    /// A uniform line: `mass_per_length` ρ̄ (kg/m), `rotary` = (J1, J2) the
    /// rotary inertia per length of d1 and d2, kg m.
    pub fn new(rod: Rod, mass_per_length: f64, rotary: [f64; 2], vertical: VerticalLoad, fluid: Fluid) -> Self {
        let n = rod.n_el;
        let mass = PerElement::uniform(ElementMass::new(mass_per_length, rotary, rod.h), n);
        let f_grav = vertical_load_vector(&rod, &vertical);
        RodModel {
            rod,
            mass,
            vertical,
            fluid: PerElement::uniform(fluid, n),
            seabed: None,
            f_grav,
            sea: None,
            current_ramp: Ramp::NONE,
            anchor_motion: None,
        }
    }

    /// The same line on a uniform seabed.
    pub fn with_seabed(mut self, seabed: Option<Seabed>) -> Self {
        self.seabed = seabed.map(|b| PerElement::uniform(b, self.rod.n_el));
        self
    }

    /// The same line in the waves of `sea` (None: still water).
    pub fn with_sea(mut self, sea: Option<Sea>) -> Self {
        self.sea = sea;
        self
    }

    /// The line of a scene: its rod, sections, weight, drag, current and added mass.
    pub fn from_scene(scene: &Scene) -> Self {
        let props = sections::element_properties(scene);
        let mut rod = of_properties(scene, &props);
        // the static state is the pinned line's; a clamp holds the end at that orientation
        match scene.hang_off.end {
            crate::scene::HangOffEnd::Pinned => {}
            crate::scene::HangOffEnd::Clamped => rod.ends[0] = super::EndBc::CLAMPED,
            crate::scene::HangOffEnd::FlexJoint => rod.flex_joint = Some(flex_joint_of_scene(scene, &rod)),
        }
        let h = rod.h;
        let mass = props.map(|p| ElementMass::new(p.mass_per_length, [p.rotary_inertia; 2], h));
        let vertical = loads::vertical_load(scene);
        let f_grav = vertical_load_vector(&rod, &vertical);
        let fluid = sections::fluid(scene, &props);
        let seabed = sections::seabed(scene, &props);
        let current_ramp = loads::current_ramp(scene);
        RodModel { rod, mass, vertical, fluid, seabed, f_grav, sea: None, current_ramp, anchor_motion: None }
    }

    /// Sets the flex joint's static frame D_static (the line's end frame in
    /// the static state, `cfg.d[0]`): the vessel's frame is R(t) D_static.
    /// Nothing without a flex joint.
    pub fn set_static_frame(&mut self, cfg: &RodConfig) {
        if let Some(j) = self.rod.flex_joint.as_mut() {
            j.frame = Some(cfg.d[0]);
        }
    }

    /// The vessel's frame at the flex joint for the vessel's rotation R,
    /// R D_static (None: no flex joint).
    ///
    /// # Panics
    /// With a flex joint whose static frame was never set ([`RodModel::set_static_frame`]).
    pub fn joint_frame(&self, rotation: &M3) -> Option<M3> {
        self.rod
            .flex_joint
            .as_ref()
            .map(|j| rotation * j.frame.expect("the flex joint's static frame is set (RodModel::set_static_frame)"))
    }

    /// Largest mass per length with the added mass, kg/m.
    pub fn max_inertia_per_length(&self) -> f64 {
        self.mass.values().iter().map(|m| m.mass_per_length()).fold(0.0, f64::max) + self.fluid.max_added_mass()
    }

    /// Consistent nodal vertical load vector.
    pub fn gravity_vector(&self) -> &[f64] {
        &self.f_grav
    }

    /// Potential of the vertical load, −∫ q(S) z(S) dS (z from the origin),
    /// the seabed's elastic energy ∫ V dS (9.2) and the free surface's
    /// correction ∫ V_s dS (10.1), J.
    pub fn potential_energy(&self, cfg: &RodConfig) -> f64 {
        let mut v = 0.0;
        for a in 0..=self.rod.n_el {
            v -= self.f_grav[Rod::x_dof(a) + 2] * cfg.x[a].z + self.f_grav[Rod::xp_dof(a) + 2] * cfg.xp[a].z;
        }
        let shapes = crate::loads::fluid::hermite_at_gauss(self.rod.h);
        for e in 0..self.rod.n_el {
            let c = [cfg.x[e], cfg.xp[e], cfg.x[e + 1], cfg.xp[e + 1]];
            if let Some(bed) = &self.seabed {
                v += seabed::element_energy(bed.at(e), &c, &shapes, seabed::hermite_at, self.rod.h);
            }
            // an element whose centreline lies wholly below the band adds
            // exactly nothing (V_s = 0 there): its composite rule skipped
            if let Some(s) = &self.fluid.at(e).surface
                && !s.hermite_below(&c, self.rod.h)
            {
                v += crate::loads::surface::element_energy(
                    s,
                    &c,
                    |xi| crate::math::shape::hermite(xi, self.rod.h),
                    self.rod.h,
                );
            }
        }
        v
    }

    /// Kinetic energy, J.
    pub fn kinetic_energy(&self, s: &State) -> f64 {
        (0..self.rod.n_el).map(|e| self.mass.at(e).kinetic_energy(&s.hermite_velocity(e), &s.director_rates(e))).sum()
    }

    /// Linear momentum, kg m/s.
    pub fn linear_momentum(&self, s: &State) -> V3 {
        (0..self.rod.n_el).map(|e| self.mass.at(e).momentum(&s.hermite_velocity(e))).sum()
    }

    /// Angular momentum about the origin, kg m²/s.
    pub fn angular_momentum(&self, s: &State) -> V3 {
        (0..self.rod.n_el)
            .map(|e| {
                let c = &s.config;
                let ce = [c.x[e], c.xp[e], c.x[e + 1], c.xp[e + 1]];
                let d = [c.d[2 * e], c.d[2 * e + 1], c.d[2 * e + 2]];
                self.mass.at(e).angular_momentum(&ce, &s.hermite_velocity(e), &d, &s.director_rates(e))
            })
            .sum()
    }

    /// Total mass, kg.
    pub fn total_mass(&self) -> f64 {
        (0..self.rod.n_el).map(|e| self.mass.at(e).mass_per_length() * self.rod.h).sum()
    }
}

/// The scene's flex joint (§15): its law (linear or tabulated); torsion
/// held by k_t = 100 GJ/h of the first element (the joint twists a
/// hundredth of what that element does under the same torque), its static
/// frame set once the statics is known.
pub fn flex_joint_of_scene(scene: &Scene, rod: &Rod) -> super::FlexJoint {
    let law = match (&scene.hang_off.table, scene.hang_off.stiffness) {
        (Some(rows), _) => super::JointLaw::table(rows),
        (None, k) => super::JointLaw::linear(k.unwrap_or(0.0)),
    };
    super::FlexJoint { law, torsion: TORSION_FACTOR * rod.stiff(0)[5] / rod.h, frame: None }
}

/// k_t / (GJ/h) of the flex joint's torsion (§15).
pub const TORSION_FACTOR: f64 = 100.0;

impl State {
    /// Director rates that follow the centreline: ḋ_i = ω × d_i with
    /// ω = t × ṫ the rotation rate of the tangent t = r'/|r'| (no spin), at
    /// every director node; and the predictor's velocities set to the current
    /// ones. For initial velocity fields given on the centreline only.
    pub fn align_director_rates(&mut self, rod: &Rod) {
        let nd = crate::math::shape::hermite_ds(0.5, rod.h);
        for j in 0..self.director_vel.len() {
            let (p, pd) = if j % 2 == 0 {
                (self.config.xp[j / 2], self.slope_vel[j / 2])
            } else {
                let e = j / 2;
                let c = &self.config;
                (
                    c.x[e] * nd[0] + c.xp[e] * nd[1] + c.x[e + 1] * nd[2] + c.xp[e + 1] * nd[3],
                    self.vel[e] * nd[0]
                        + self.slope_vel[e] * nd[1]
                        + self.vel[e + 1] * nd[2]
                        + self.slope_vel[e + 1] * nd[3],
                )
            };
            let len = p.norm();
            let t = p / len;
            let tdot = (pd - t * t.dot(&pd)) / len;
            let omega = t.cross(&tdot);
            let d = self.config.d[j];
            self.director_vel[j] =
                M3::from_columns(&[omega.cross(&d.column(0)), omega.cross(&d.column(1)), omega.cross(&d.column(2))]);
        }
        self.mean_vel.clone_from(&self.vel);
        self.mean_slope_vel.clone_from(&self.slope_vel);
        self.prev_mean_vel.clone_from(&self.vel);
        self.prev_mean_slope_vel.clone_from(&self.slope_vel);
        self.prev2_mean_vel.clone_from(&self.vel);
        self.prev2_mean_slope_vel.clone_from(&self.slope_vel);
    }
}
