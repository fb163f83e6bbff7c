//! riser: nonlinear dynamics of marine risers, umbilicals and cables, after
//! dos Santos & Rochinha, "Dynamics of marine pipelines — a nonlinear analysis"
//! (Cosserat director rod, energy–momentum conserving time stepping, Morison
//! drag), packaged as an FMI 2.0 Co-Simulation unit.
//!
//! Layout: [`rod`] (kinematics, element, strains, internal force and tangent),
//! [`hydro`] (loads from the water), [`scene`] (scene files and built-in
//! scenes), [`statics`] (static equilibrium), [`linsolve`] (global sparse LU),
//! [`error`] (the typed errors).

pub use error::RiserError;

pub mod cable;
pub mod dynamics;
pub mod error;
pub mod fmi;
pub mod hydro;
pub mod linsolve;
pub mod rod;
pub mod scene;
pub mod statics;
