//! The seam between the line models and the linear analyses about a
//! configuration (docs/theory.md §8): the modal analysis and the line's
//! stiffness at the hang-off. A model gives its static tangent, its mass
//! (with the water's added mass) and how a vector of its unknowns moves the
//! line; the solvers in `solve::eigen` never name the model.

use crate::math::band::{BandedSystem, LinearSolveError};
use crate::math::{M3, V3};
use crate::model::RodConfig;

/// The direction a mode moves the line in, from the split of its kinetic
/// energy (docs/theory.md §8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Transverse, in the vertical plane of the line.
    InPlane,
    /// Transverse, normal to the line's plane.
    OutOfPlane,
    /// Along the line (stretching).
    Axial,
    /// Twist about the line's axis.
    Torsion,
}

impl Direction {
    /// The name the CLI and the JSON use.
    pub fn name(self) -> &'static str {
        match self {
            Direction::InPlane => "in-plane",
            Direction::OutOfPlane => "out-of-plane",
            Direction::Axial => "axial",
            Direction::Torsion => "torsion",
        }
    }

    /// Order of [`ModeMotion::fractions`].
    pub const ALL: [Direction; 4] = [Direction::InPlane, Direction::OutOfPlane, Direction::Axial, Direction::Torsion];
}

/// The motion of the line in one mode.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeMotion {
    /// Per end node: reference arc length S (m), displacement of the
    /// centreline (per unit of the mode's amplitude) and twist about the
    /// line's axis (rad per unit amplitude; 0 for the cable).
    pub nodes: Vec<(f64, V3, f64)>,
    /// Fractions of the mode's kinetic energy: in-plane transverse,
    /// out-of-plane transverse, axial, torsion (they add up to 1, except for
    /// the small share of the rotary inertia of bending).
    pub fractions: [f64; 4],
}

impl ModeMotion {
    /// The direction with the largest share of the kinetic energy.
    pub fn direction(&self) -> Direction {
        let mut best = 0;
        for k in 1..4 {
            if self.fractions[k] > self.fractions[best] {
                best = k;
            }
        }
        Direction::ALL[best]
    }
}

/// A line model linearised about a configuration: what the modal analysis
/// and the hang-off stiffness need.
pub trait Linearized {
    /// Unknowns (rows of the tangent).
    fn n_dof(&self) -> usize;
    /// A matrix with the model's band pattern.
    fn new_system(&self) -> Result<BandedSystem, LinearSolveError>;
    /// Unknowns held by the supports, sorted (the hang-off's position among them).
    fn fixed_dofs(&self) -> Vec<usize>;
    /// Rows of the hang-off's position x, y, z (spatial components), whose
    /// residuals are the reactions of the support on the line.
    fn hang_off_rows(&self) -> [usize; 3];
    /// Rows of the anchor's position x, y, z (the end at S = L), whose
    /// residuals are the reactions of the anchor on the line.
    fn anchor_rows(&self) -> [usize; 3];
    /// The static residual R(q) = f_int − f_ext at `cfg` into `r` (the loads
    /// of the static equilibrium) and its tangent ∂R/∂q into `k`.
    fn static_tangent(&self, cfg: &RodConfig, r: &mut [f64], k: &mut BandedSystem);
    /// The mass matrix at `cfg` into `m` (structural and rotary inertia, and
    /// the normal added mass of the water about the tangent at `cfg`), in the
    /// unknowns of [`Linearized::static_tangent`].
    fn mass_matrix(&self, cfg: &RodConfig, m: &mut BandedSystem);
    /// How the unknowns `phi` move the line at `cfg`; `normal` is the unit
    /// normal of the line's vertical plane (out-of-plane direction).
    fn motion(&self, cfg: &RodConfig, phi: &[f64], normal: &V3) -> ModeMotion;
    /// How the line's end at the hang-off turns with the vessel at `cfg`
    /// (docs/theory.md §8.3): pinned unless the model says otherwise.
    fn hang_off_end(&self, _cfg: &RodConfig) -> EndRotation {
        EndRotation::Pinned
    }
}

/// The end's rotational coupling to the vessel at the hang-off, for the
/// 6×6 stiffness (docs/theory.md §8.3, §15): which rows carry the end's
/// rotation (spatial components, as the vessel's small rotation δθ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndRotation {
    /// Free to turn: no end moment; the vessel's turn does not reach the line.
    Pinned,
    /// Held by the supports and turned with the vessel: δθ prescribes the
    /// rotation unknowns `rows`, whose residuals are the moment of the
    /// support on the line.
    Clamped { rows: [usize; 3] },
    /// A spring between the vessel's frame and the free rotation unknowns
    /// `rows`: its moment m on the vessel (the line's residual there has +m)
    /// changes by `k_end` θ_end + `k_vessel` δθ.
    Joint { rows: [usize; 3], k_end: M3, k_vessel: M3 },
}
