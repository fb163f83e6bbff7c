//! Loads per unit length, evaluated at the same points by both line models:
//! weight and buoyancy (with buoyancy modules), current profiles, Morison drag
//! (paper eqs. 13–17), added mass and the seabed's contact; built here from
//! a scene.

pub mod current;
pub mod fluid;
pub mod morison;
pub mod seabed;
pub mod surface;
pub mod waves;
pub mod weight;

use crate::math::V3;
use crate::scene::sections::LineProperties;
use crate::scene::{ProfileKind, Scene};
use current::{Current, CurrentProfile};
use fluid::Fluid;
use morison::DragCoefficients;
use seabed::Seabed;
use surface::FreeSurface;
use weight::{BuoyancySection, VerticalLoad};

/// The unit tests' random numbers: a xorshift64 stream from `seed`,
/// uniform in [−1, 1).
#[cfg(test)]
pub(crate) fn uniform_stream(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// Weight, buoyancy and buoyancy modules along the line: on each piece of
/// line (its section, with its modules smeared, docs/theory.md §11)
/// q = −(m − ρw A) g, plus the scene's `[[buoyancy]]` loads.
pub fn vertical_load(scene: &Scene) -> VerticalLoad {
    let (rho, g) = (scene.environment.water_density, scene.environment.gravity);
    let q = |p: &LineProperties| -(p.mass_per_length - rho * p.displaced_area) * g;
    let pieces = scene.pieces();
    let mut v = VerticalLoad { uniform: q(&pieces[0].properties), sections: Vec::new() };
    // the other sections as their difference from the first
    for p in &pieces[1..] {
        let load = q(&p.properties) - v.uniform;
        if load != 0.0 {
            v.sections.push(BuoyancySection { start: p.start, end: p.end, load });
        }
    }
    v.sections.extend(scene.buoyancy.iter().map(|b| BuoyancySection { start: b.start, end: b.end, load: b.load }));
    v
}

/// The seabed's contact law on a piece of line of properties `p` (None:
/// the scene has no seabed): MoorDyn's kBot and cBot on its diameter.
pub fn seabed_of(scene: &Scene, p: &LineProperties) -> Option<Seabed> {
    scene.seabed.as_ref().map(|b| {
        Seabed::new(b.z, b.slope, b.stiffness, b.damping, b.friction_coefficients(), b.slip_velocity, p.diameter)
    })
}

/// Morison drag coefficients ½ ρw (C_D D) of a piece of line.
pub fn drag_coefficients_of(scene: &Scene, p: &LineProperties) -> DragCoefficients {
    let half_rho = 0.5 * scene.environment.water_density;
    DragCoefficients { normal: half_rho * p.drag_normal, tangential: half_rho * p.drag_tangential }
}

/// Drag (with the current), normal added mass and the free surface of a
/// piece of line.
pub fn fluid_of(scene: &Scene, p: &LineProperties) -> Fluid {
    let k = drag_coefficients_of(scene, p);
    let drag = if k.is_zero() { None } else { Some((k, current(scene))) };
    let added_mass = p.added_mass_area * scene.environment.water_density;
    let froude_krylov = scene.environment.water_density * p.displaced_area;
    Fluid { drag, added_mass, surface: Some(free_surface_of(scene, p)), froude_krylov }
}

/// The free surface as a piece of line feels it (docs/theory.md §10): its
/// buoyancy fades over max(D/2, 5 cm) either side.
pub fn free_surface_of(scene: &Scene, p: &LineProperties) -> FreeSurface {
    FreeSurface {
        z: scene.environment.water_surface_z,
        half_width: (0.5 * p.diameter).max(0.05),
        buoyancy: scene.environment.water_density * scene.environment.gravity * p.displaced_area,
    }
}

/// The current's growth from the run's start (t = 0; the engine moves it to
/// a run's start time): ½(1 − cos(π t/ramp)) over the scene's
/// `current.ramp` s (`current_ramp`, default [`crate::scene::DEFAULT_CURRENT_RAMP`];
/// 0: in full from t = 0, the paper's start; docs/theory.md §5.11). None
/// without a current, or with `static_current`: the static state holds the
/// current already.
pub fn current_ramp(scene: &Scene) -> waves::Ramp {
    if scene.analysis.static_current || scene.current.profile == ProfileKind::None {
        return waves::Ramp::NONE;
    }
    waves::Ramp { start: 0.0, duration: scene.current.ramp.unwrap_or(crate::scene::DEFAULT_CURRENT_RAMP) }
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
