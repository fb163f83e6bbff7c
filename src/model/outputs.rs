//! The quantities a run reports at each output time, with the interface's names (docs/interface.md)
//! (docs/theory.md §5.6).

use super::State;
use crate::math::V3;

/// Points of the `shape[k]` output: S = k L / 20, k = 0..=20.
pub const SHAPE_POINTS: usize = 21;

/// The line at one of the points where the design numbers are read
/// (docs/theory.md §12): the rod's Gauss points, the cable's nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinePoint {
    /// Element the point lies in.
    pub element: usize,
    /// Unstretched arc length from the hang-off, m.
    pub s: f64,
    /// Position, m.
    pub position: V3,
    /// Axial force (effective tension), N.
    pub tension: f64,
    /// Bending curvature about the section's two axes (the rod's director
    /// frame), 1/m. The cable's turning curvature is in `[0]`: it carries no
    /// bending moment.
    pub curvature: [f64; 2],
    /// Twist κ₃ about the tangent (the rod's torsional strain), 1/m; 0 for
    /// the cable, which has no torsion.
    pub twist: f64,
}

impl LinePoint {
    /// |curvature|, 1/m.
    pub fn curvature_magnitude(&self) -> f64 {
        self.curvature[0].hypot(self.curvature[1])
    }
}

/// Output quantities at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outputs {
    /// s.
    pub time: f64,
    /// |force at the hang-off|, N (effective tension).
    pub top_tension: f64,
    /// Force the line exerts on the vessel, N.
    pub top_force: V3,
    /// |force at the anchor|, N.
    pub bottom_tension: f64,
    /// Force the line exerts on the anchor, N.
    pub bottom_force: V3,
    /// Smallest axial force along the line (Gauss points and ends), N.
    pub min_tension: f64,
    /// kinetic + strain + potential, J.
    pub total_energy: f64,
    pub kinetic_energy: f64,
    pub strain_energy: f64,
    /// Potential of gravity and buoyancy, −∫ q z dS (z from the origin),
    /// and the seabed's elastic energy, J.
    pub potential_energy: f64,
    /// Work of the hang-off on the line since t = 0, J.
    pub work_top: f64,
    /// Work of the water on the line since t = 0, J.
    pub work_hydro: f64,
    /// Work of the anchor's twist reaction since t = 0, J (not an FMU output).
    pub work_anchor: f64,
    /// Energy dissipated by structural damping since t = 0, J (≥ 0; 0 without damping).
    pub dissipated_energy: f64,
    /// Energy removed by the scheme's high-frequency dissipation since t = 0,
    /// J (≥ 0; 0 with ρ∞ = 1).
    pub algorithmic_dissipation: f64,
    /// Work of the seabed's damping and friction on the line since t = 0, J (≤ 0).
    pub work_seabed: f64,
    /// Arc length from the hang-off to the first seabed contact, m (the
    /// line's length when it touches nowhere).
    pub touchdown_s: f64,
    /// Angle of the line's tangent at the hang-off from the downward
    /// vertical, deg (docs/theory.md §12.1).
    pub hang_off_angle: f64,
    /// The water's elevation at the phase origin as the line feels it (the
    /// ramp included), m: 0 in still water (docs/theory.md §13). Set by the
    /// simulation, which knows the sea.
    pub wave_elevation: f64,
    /// Bending moment at the hang-off, N m: EI |κ| extrapolated to S = 0
    /// from the first element's two nearest Gauss points (0 for a pinned end
    /// to the discretisation's accuracy, and for the cable; §15).
    pub hang_off_moment: f64,
    /// The moment the line exerts on the vessel at the hang-off, global
    /// frame, N m (a clamped end; 0 for a pinned one; §15). Not an FMU output
    /// itself: it enters `top_moment`.
    pub end_moment: V3,
    /// The line's force and end moment on the vessel as moments about the
    /// vessel's reference point, global frame, N m (§14, (14.4)); and force
    /// and moment in the vessel frame. Set by the simulation, which knows
    /// the vessel (at a vessel's reference point = the hang-off, unrotated:
    /// the end moment, and the force itself).
    pub top_moment: V3,
    pub vessel_force: V3,
    pub vessel_moment: V3,
    /// Rotation of the line's end relative to the vessel since the static
    /// state, rad (a flex joint's angle; 0 for pinned and clamped ends).
    pub flex_joint_angle: f64,
    /// Centreline at S = k L / 20, m.
    pub shape: [V3; SHAPE_POINTS],
}

impl Outputs {
    /// Names of the scalar outputs, in the order of [`Outputs::values`].
    pub const NAMES: [&'static str; 29] = [
        "top_tension",
        "top_force_x",
        "top_force_y",
        "top_force_z",
        "bottom_tension",
        "min_tension",
        "total_energy",
        "kinetic_energy",
        "strain_energy",
        "potential_energy",
        "work_top",
        "work_hydro",
        "dissipated_energy",
        "algorithmic_dissipation",
        "touchdown_s",
        "work_seabed",
        "hang_off_angle",
        "wave_elevation",
        "hang_off_moment",
        "top_moment_x",
        "top_moment_y",
        "top_moment_z",
        "vessel_force_x",
        "vessel_force_y",
        "vessel_force_z",
        "vessel_moment_x",
        "vessel_moment_y",
        "vessel_moment_z",
        "flex_joint_angle",
    ];

    /// Scalar outputs in the order of [`Outputs::NAMES`].
    pub fn values(&self) -> [f64; 29] {
        [
            self.top_tension,
            self.top_force.x,
            self.top_force.y,
            self.top_force.z,
            self.bottom_tension,
            self.min_tension,
            self.total_energy,
            self.kinetic_energy,
            self.strain_energy,
            self.potential_energy,
            self.work_top,
            self.work_hydro,
            self.dissipated_energy,
            self.algorithmic_dissipation,
            self.touchdown_s,
            self.work_seabed,
            self.hang_off_angle,
            self.wave_elevation,
            self.hang_off_moment,
            self.top_moment.x,
            self.top_moment.y,
            self.top_moment.z,
            self.vessel_force.x,
            self.vessel_force.y,
            self.vessel_force.z,
            self.vessel_moment.x,
            self.vessel_moment.y,
            self.vessel_moment.z,
            self.flex_joint_angle,
        ]
    }

    /// The name of the first output that is not a finite number (NaN, ±∞),
    /// if any: the scalar outputs, then the shape points (`shape[k]`).
    pub fn first_non_finite(&self) -> Option<&'static str> {
        if let Some(i) = self.values().iter().position(|v| !v.is_finite()) {
            return Some(Self::NAMES[i]);
        }
        if !self.work_anchor.is_finite() {
            return Some("work_anchor");
        }
        if self.shape.iter().any(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite())) {
            return Some("shape");
        }
        None
    }

    /// E(t) − E(0) − W_top − W_hydro − W_anchor − W_seabed + D + D_alg: zero
    /// to the Newton tolerance (§5.5, §5.9, §5.10, §9), J.
    pub fn energy_balance_residual(&self, e0: f64) -> f64 {
        self.total_energy - e0 - self.work_top - self.work_hydro - self.work_anchor - self.work_seabed
            + self.dissipated_energy
            + self.algorithmic_dissipation
    }
}

impl Outputs {
    /// The outputs of state `s` from its end `reactions` (force of the supports
    /// on the line, N), smallest axial force (N), energies [kinetic, strain,
    /// potential] (J), the touchdown's arc length (m) and shape points; the
    /// work terms are the state's.
    pub fn of_state(
        s: &State,
        reactions: [V3; 2],
        min_tension: f64,
        energy: [f64; 3],
        touchdown_s: f64,
        hang_off_tangent: V3,
        shape: [V3; SHAPE_POINTS],
    ) -> Self {
        let [kinetic, strain, potential] = energy;
        Outputs {
            time: s.time,
            top_tension: reactions[0].norm(),
            top_force: -reactions[0],
            bottom_tension: reactions[1].norm(),
            bottom_force: -reactions[1],
            min_tension,
            total_energy: kinetic + strain + potential,
            kinetic_energy: kinetic,
            strain_energy: strain,
            potential_energy: potential,
            work_top: s.work_top,
            work_hydro: s.work_hydro,
            work_anchor: s.work_anchor,
            dissipated_energy: s.dissipated,
            algorithmic_dissipation: s.algorithmic,
            work_seabed: s.work_seabed,
            touchdown_s,
            hang_off_angle: hang_off_angle(hang_off_tangent),
            wave_elevation: 0.0,
            hang_off_moment: 0.0,
            end_moment: V3::zeros(),
            top_moment: V3::zeros(),
            vessel_force: -reactions[0],
            vessel_moment: V3::zeros(),
            flex_joint_angle: 0.0,
            shape,
        }
    }
}

/// The angle of `tangent` (pointing down the line) from the downward
/// vertical, deg (§12.1).
pub fn hang_off_angle(tangent: V3) -> f64 {
    (-tangent.z / tangent.norm()).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The tangent of a line of nodes `x` at its first node, second order: the
/// one-sided difference (−3x₀ + 4x₁ − x₂)/2 (the first chord alone is the
/// tangent half a segment down; §12.1).
pub fn first_node_tangent(x: &[V3]) -> V3 {
    match x.len() {
        0 | 1 => V3::z() * -1.0,
        2 => x[1] - x[0],
        _ => 4.0 * x[1] - 3.0 * x[0] - x[2],
    }
}
