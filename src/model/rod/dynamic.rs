//! The rod's dynamic model: everything about the line that does not change
//! during a run (rod, mass, weight, water), its energies and momenta.

use super::mass::ElementMass;
use super::statics::vertical_load_vector;
use super::{Rod, of_scene};
use crate::loads::seabed::{self, Seabed};
use crate::loads::weight::VerticalLoad;
use crate::loads::{self, fluid::Fluid};
use crate::math::{M3, V3};
use crate::model::{RodConfig, State};
use crate::scene::Scene;

/// Everything about the line that does not change during a run.
#[derive(Debug, Clone)]
pub struct RodModel {
    pub rod: Rod,
    /// ρ̄, kg/m.
    pub mass_per_length: f64,
    /// Element mass matrices.
    pub mass: ElementMass,
    /// Weight, buoyancy, buoyancy modules.
    pub vertical: VerticalLoad,
    /// Drag and added mass.
    pub fluid: Fluid,
    /// The seabed (None: no contact anywhere, no cost).
    pub seabed: Option<Seabed>,
    /// Consistent nodal vector of the vertical load, N (and N m on r' rows).
    f_grav: Vec<f64>,
}

impl RodModel {
    /// `rotary` = (J1, J2): rotary inertia per length of d1 and d2, kg m.
    pub fn new(rod: Rod, mass_per_length: f64, rotary: [f64; 2], vertical: VerticalLoad, fluid: Fluid) -> Self {
        let mass = ElementMass::new(mass_per_length, rotary, rod.h);
        let f_grav = vertical_load_vector(&rod, &vertical);
        RodModel { rod, mass_per_length, mass, vertical, fluid, seabed: None, f_grav }
    }

    /// The same line on a seabed.
    pub fn with_seabed(mut self, seabed: Option<Seabed>) -> Self {
        self.seabed = seabed;
        self
    }

    /// The line of a scene: its rod, section, weight, drag, current and added mass.
    pub fn from_scene(scene: &Scene) -> Self {
        let j = scene.rotary_inertia();
        RodModel::new(
            of_scene(scene),
            scene.line.mass_per_length,
            [j, j],
            loads::vertical_load(scene),
            loads::fluid(scene),
        )
        .with_seabed(loads::seabed(scene))
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
                v += seabed::element_energy(bed, &c, &shapes, self.rod.h);
            }
            if let Some(s) = &self.fluid.surface {
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
        (0..self.rod.n_el).map(|e| self.mass.kinetic_energy(&s.hermite_velocity(e), &s.director_rates(e))).sum()
    }

    /// Linear momentum, kg m/s.
    pub fn linear_momentum(&self, s: &State) -> V3 {
        (0..self.rod.n_el).map(|e| self.mass.momentum(&s.hermite_velocity(e))).sum()
    }

    /// Angular momentum about the origin, kg m²/s.
    pub fn angular_momentum(&self, s: &State) -> V3 {
        (0..self.rod.n_el)
            .map(|e| {
                let c = &s.config;
                let ce = [c.x[e], c.xp[e], c.x[e + 1], c.xp[e + 1]];
                let d = [c.d[2 * e], c.d[2 * e + 1], c.d[2 * e + 2]];
                self.mass.angular_momentum(&ce, &s.hermite_velocity(e), &d, &s.director_rates(e))
            })
            .sum()
    }

    /// Total mass, kg.
    pub fn total_mass(&self) -> f64 {
        self.mass_per_length * self.rod.length
    }
}

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
    }
}
