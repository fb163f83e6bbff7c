//! The vessel the line hangs from (docs/theory.md §14): its reference point's
//! displacement and its rotation give the hang-off's motion (the hang-off at
//! ρ in the vessel frame, r = r_ref + R ρ); the line's force and end moment
//! at the hang-off give the force and moment on the vessel about its
//! reference point, in the global and in the vessel frame.

use crate::math::rigid::RotationOrder;
use crate::math::{M3, V3};
use crate::model::HangOff;
use crate::scene::Scene;
use crate::scene::raos::RaoTable;

/// Where the hang-off sits on the vessel and how the vessel's angles compose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vessel {
    /// ρ, the hang-off in the vessel frame from the reference point, m.
    pub offset: V3,
    pub order: RotationOrder,
}

/// The vessel's motion at one instant: the reference point's displacement
/// from its initial position and its velocity (global frame, m, m/s), the
/// angles [roll, pitch, yaw] (rad) and the angular velocity in the vessel
/// frame [p, q, r] (rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VesselMotion {
    pub displacement: V3,
    pub velocity: V3,
    pub angles: [f64; 3],
    pub body_rates: V3,
}

/// The loads the line puts on the vessel (the line's side of the hang-off).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VesselLoads {
    /// The force on the vessel, global frame, N.
    pub force: V3,
    /// Its moment about the reference point plus the line's end moment, global frame, N m (14.4).
    pub moment: V3,
    /// The same two in the vessel frame.
    pub force_vessel: V3,
    pub moment_vessel: V3,
}

impl Vessel {
    /// The scene's vessel: `[hang_off] offset` and `rotation_order`.
    pub fn of_scene(scene: &Scene) -> Self {
        let [x, y, z] = scene.hang_off.offset;
        Vessel { offset: V3::new(x, y, z), order: scene.hang_off.rotation_order.order() }
    }

    /// The hang-off's motion (14.3): displacement u + (R − I) ρ (the vessel
    /// starts unrotated, the hang-off at the scene's origin), velocity
    /// v + ω × Rρ with ω = R ω_b, and the rotation R and ω for a clamped end.
    pub fn hang_off(&self, m: &VesselMotion) -> HangOff {
        let r = self.order.rotation(m.angles);
        let arm = r * self.offset;
        let omega = r * m.body_rates;
        HangOff {
            displacement: m.displacement + arm - self.offset,
            velocity: m.velocity + omega.cross(&arm),
            rotation: r,
            angular_velocity: omega,
        }
    }

    /// The loads on the vessel of the line's force `force` (on the vessel,
    /// global frame, N) and end moment `end_moment` (on the vessel, N m) at
    /// the hang-off when the vessel is rotated by `rotation`:
    /// M = (R ρ) × F + M_end (14.4).
    pub fn loads(&self, rotation: &M3, force: V3, end_moment: V3) -> VesselLoads {
        let moment = (rotation * self.offset).cross(&force) + end_moment;
        VesselLoads {
            force,
            moment,
            force_vessel: rotation.transpose() * force,
            moment_vessel: rotation.transpose() * moment,
        }
    }
}

/// One term of the vessel's motion on its RAOs: a degree of freedom moved
/// by A cos(ψ − ω t) (A = aᵢ |RAO|, ψ = the component's phase argument at
/// the reference point at t = 0 plus the RAO's phase).
#[derive(Debug, Clone, Copy, PartialEq)]
struct RaoTerm {
    dof: usize,
    amplitude: f64,
    omega: f64,
    psi: f64,
}

/// The vessel moved by the sea's own components through its RAOs
/// (docs/theory.md §14.5): degree of freedom d (surge, sway, heave of the
/// reference point, m; roll, pitch, yaw, rad) at t is
///
///   u_d(t) = r(t) Σᵢ aᵢ |RAO_d(fᵢ, βᵢ)| cos(θᵢ(t) + phase_d(fᵢ, βᵢ))     (14.6)
///
/// with θᵢ(t) = kᵢ((x_r − x₀) cos βᵢ + (y_r − y₀) sin βᵢ) − ωᵢ t + φᵢ the
/// component's phase argument of (13.1) at the reference point's mean
/// position (x_r, y_r) = −(ρ_x, ρ_y), and r(t) the waves' ramp.
#[derive(Debug, Clone, PartialEq)]
pub struct RaoMotion {
    terms: Vec<RaoTerm>,
    ramp: crate::loads::waves::Ramp,
    order: RotationOrder,
    /// The degrees of freedom the table moves.
    pub dofs: Vec<&'static str>,
}

impl RaoMotion {
    /// The motion of `vessel` in `sea` on the RAOs of `table`; an error
    /// names the component outside the table's span.
    pub fn new(vessel: &Vessel, sea: &crate::loads::waves::Sea, table: &RaoTable) -> Result<Self, String> {
        let [x0, y0] = sea.settings().origin;
        let (xr, yr) = (-vessel.offset.x, -vessel.offset.y);
        let mut terms = Vec::new();
        for (c, k) in sea.components().iter().zip(sea.wave_numbers()) {
            let omega = 2.0 * std::f64::consts::PI * c.frequency;
            let (sb, cb) = c.direction.sin_cos();
            let theta0 = k * ((xr - x0) * cb + (yr - y0) * sb) + c.phase;
            for dof in 0..6 {
                let (a, p) = table.at(dof, c.frequency, c.direction.to_degrees()).map_err(|m| {
                    format!(
                        "vessel.raos: the sea's component at {} Hz, {} deg: {m}; give RAOs over the sea's band and \
                         directions (riser waves lists them), or narrow the sea (waves.f_min, waves.f_max)",
                        c.frequency,
                        c.direction.to_degrees()
                    )
                })?;
                if a != 0.0 && c.amplitude != 0.0 {
                    terms.push(RaoTerm { dof, amplitude: c.amplitude * a, omega, psi: theta0 + p.to_radians() });
                }
            }
        }
        Ok(RaoMotion { terms, ramp: sea.settings().ramp, order: vessel.order, dofs: table.dofs() })
    }

    /// The six degrees of freedom (surge, sway, heave, m; roll, pitch, yaw,
    /// rad) and their rates at `t`, the ramp included.
    pub fn dofs_at(&self, t: f64) -> ([f64; 6], [f64; 6]) {
        let (r, dr) = self.ramp.at(t);
        let (mut u, mut v) = ([0.0; 6], [0.0; 6]);
        if r == 0.0 && dr == 0.0 {
            return (u, v);
        }
        for term in &self.terms {
            let (s, c) = (term.psi - term.omega * t).sin_cos();
            u[term.dof] += term.amplitude * c;
            v[term.dof] += term.amplitude * term.omega * s;
        }
        for d in 0..6 {
            v[d] = r * v[d] + dr * u[d];
            u[d] *= r;
        }
        (u, v)
    }

    /// The vessel's motion at `t` (the angles' rates as body rates).
    pub fn at(&self, t: f64) -> VesselMotion {
        let (u, v) = self.dofs_at(t);
        let angles = [u[3], u[4], u[5]];
        VesselMotion {
            displacement: V3::new(u[0], u[1], u[2]),
            velocity: V3::new(v[0], v[1], v[2]),
            angles,
            body_rates: self.order.body_rates(angles, [v[3], v[4], v[5]]),
        }
    }
}

/// The motion on its RAOs of the vessel of `scene` (`[vessel] raos`) in
/// `sea`: None without a table, or in still water (the vessel then does not
/// move: no waves, no wave-frequency motion); an error for a table that
/// cannot be read or a component outside its span.
pub fn rao_motion(scene: &Scene, sea: Option<&crate::loads::waves::Sea>) -> Result<Option<RaoMotion>, String> {
    let Some(path) = scene.vessel.as_ref().and_then(|v| v.raos.as_deref()) else { return Ok(None) };
    let table = crate::scene::raos::read_raos(path).map_err(|e| e.to_string())?;
    match sea {
        Some(sea) => RaoMotion::new(&Vessel::of_scene(scene), sea, &table).map(Some),
        None => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hang-off's velocity is the derivative of its displacement along a
    /// combined motion (central differences), in both orders; with ρ = 0 the
    /// hang-off moves with the reference point alone.
    #[test]
    fn the_hang_off_velocity_is_the_rate_of_its_displacement() {
        for order in [RotationOrder::Zyx, RotationOrder::Xyz] {
            let v = Vessel { offset: V3::new(30.0, -8.0, 4.0), order };
            let motion = |t: f64| {
                let angles = [0.1 * (0.7 * t).sin(), -0.05 * (0.5 * t).cos(), 0.2 * (0.3 * t).sin()];
                let rates = [0.07 * (0.7 * t).cos(), 0.025 * (0.5 * t).sin(), 0.06 * (0.3 * t).cos()];
                VesselMotion {
                    displacement: V3::new(2.0 * t.sin(), 0.5 * t, -t.cos()),
                    velocity: V3::new(2.0 * t.cos(), 0.5, t.sin()),
                    angles,
                    body_rates: order.body_rates(angles, rates),
                }
            };
            let (t, e) = (1.3, 1e-6);
            let h = v.hang_off(&motion(t));
            let fd = (v.hang_off(&motion(t + e)).displacement - v.hang_off(&motion(t - e)).displacement) / (2.0 * e);
            assert!((fd - h.velocity).norm() < 1e-8, "{order:?}: {fd:?} vs {:?}", h.velocity);
            // Ṙ = [ω]× R
            let rd = (v.hang_off(&motion(t + e)).rotation - v.hang_off(&motion(t - e)).rotation) / (2.0 * e);
            assert!((rd - crate::math::skew(&h.angular_velocity) * h.rotation).norm() < 1e-8);
            let at_ref = Vessel { offset: V3::zeros(), order }.hang_off(&motion(t));
            assert_eq!(at_ref.displacement, motion(t).displacement);
        }
    }

    /// M = (Rρ) × F + M_end, and the vessel-frame loads rotate back.
    #[test]
    fn the_moment_about_the_reference_point_is_the_arm_times_the_force() {
        let v = Vessel { offset: V3::new(30.0, 0.0, -5.0), order: RotationOrder::Zyx };
        let r = RotationOrder::Zyx.rotation([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let l = v.loads(&r, V3::new(0.0, 0.0, -1e5), V3::new(10.0, 0.0, 0.0));
        // yawed 90°: the arm (30, 0, −5) points along +y; (0, 30, −5) × (0, 0, −1e5) = (−3e6, 0, 0)
        assert!((l.moment - V3::new(-3e6 + 10.0, 0.0, 0.0)).norm() < 1e-6);
        assert!((r * l.moment_vessel - l.moment).norm() < 1e-6 && (r * l.force_vessel - l.force).norm() < 1e-9);
    }
}
