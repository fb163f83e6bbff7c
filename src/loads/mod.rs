//! Loads per unit length, evaluated at the same points by both line models:
//! weight and buoyancy (with buoyancy modules), current profiles, Morison drag
//! (paper eqs. 13–17), added mass and the seabed's contact; built here from
//! a scene.

pub mod current;
pub mod fluid;
pub mod morison;
pub mod seabed;
pub mod surface;
pub mod weight;

use crate::math::V3;
use crate::scene::{ProfileKind, Scene};
use current::{Current, CurrentProfile};
use fluid::Fluid;
use morison::DragCoefficients;
use seabed::Seabed;
use surface::FreeSurface;
use weight::{BuoyancySection, VerticalLoad};

/// Weight, buoyancy and buoyancy modules.
pub fn vertical_load(scene: &Scene) -> VerticalLoad {
    let mut v = VerticalLoad::new(
        scene.line.mass_per_length,
        scene.line.outer_diameter,
        scene.environment.water_density,
        scene.environment.gravity,
    );
    v.sections = scene.buoyancy.iter().map(|b| BuoyancySection { start: b.start, end: b.end, load: b.load }).collect();
    v
}

/// The seabed's contact law on the line (None: the scene has no seabed).
pub fn seabed(scene: &Scene) -> Option<Seabed> {
    scene.seabed.as_ref().map(|b| {
        Seabed::new(
            b.z,
            b.slope,
            b.stiffness,
            b.damping,
            b.friction_coefficients(),
            b.slip_velocity,
            scene.line.outer_diameter,
        )
    })
}

/// Morison drag coefficients ½ ρw D C_D.
pub fn drag_coefficients(scene: &Scene) -> DragCoefficients {
    DragCoefficients::new(
        scene.environment.water_density,
        scene.line.outer_diameter,
        scene.line.cd_normal,
        scene.line.cd_tangential,
    )
}

/// Drag (with the current) and normal added mass of the line.
pub fn fluid(scene: &Scene) -> Fluid {
    let k = drag_coefficients(scene);
    let drag = if k.is_zero() { None } else { Some((k, current(scene))) };
    let d = scene.line.outer_diameter;
    let added_mass = scene.line.ca_normal * scene.environment.water_density * std::f64::consts::PI * d * d / 4.0;
    Fluid { drag, added_mass, surface: Some(free_surface(scene)) }
}

/// The free surface as the line feels it (docs/theory.md §10): its buoyancy
/// fades over max(D/2, 5 cm) either side.
pub fn free_surface(scene: &Scene) -> FreeSurface {
    let d = scene.line.outer_diameter;
    FreeSurface {
        z: scene.environment.water_surface_z,
        half_width: (0.5 * d).max(0.05),
        buoyancy: scene.environment.water_density * scene.environment.gravity * std::f64::consts::PI * d * d / 4.0,
    }
}

/// The current profile.
pub fn current(scene: &Scene) -> Current {
    let c = &scene.current;
    let dir = V3::new(c.direction[0], c.direction[1], 0.0);
    let direction = if dir.norm() > 0.0 { dir.normalize() } else { V3::x() };
    let surface_z = scene.environment.water_surface_z;
    let profile = match c.profile {
        ProfileKind::None => CurrentProfile::None,
        ProfileKind::Uniform => CurrentProfile::Uniform { speed: c.speed.unwrap_or(0.0) },
        ProfileKind::LinearS => CurrentProfile::LinearInS {
            top: c.top.unwrap_or(0.0),
            bottom: c.bottom.unwrap_or(0.0),
            length: scene.line.length,
        },
        ProfileKind::LinearDepth => CurrentProfile::LinearInDepth {
            top: c.top.unwrap_or(0.0),
            bottom: c.bottom.unwrap_or(0.0),
            depth: c.depth.unwrap_or(1.0),
            surface_z,
        },
        ProfileKind::Table => CurrentProfile::Table {
            rows: c.table.clone().unwrap_or_default().iter().map(|r| (r[0], r[1])).collect(),
            surface_z,
        },
    };
    Current { profile, direction }
}
