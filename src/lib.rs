//! riser: nonlinear dynamics of marine risers, umbilicals and cables, after
//! dos Santos & Rochinha, "Dynamics of marine pipelines — a nonlinear analysis"
//! (Cosserat director rod, energy–momentum conserving time stepping, Morison
//! drag), packaged as an FMI 2.0 Co-Simulation unit.
//!
//! Layers, bottom to top; a module imports only from the layers below it
//! (checked by `tests/it/layering.rs`):
//! - [`math`]: small algebra, shape functions and quadrature, the banded system;
//! - [`scene`]: scene files, built-in scenes, overrides, validation;
//! - [`loads`]: per unit length, shared by both models: weight and buoyancy,
//!   current, Morison drag and added mass;
//! - [`model`]: the rod ([`model::rod`]) and the cable ([`model::cable`]),
//!   each whole, and the seam the solvers use ([`model::StepEquations`],
//!   [`model::statics::StaticEquations`], [`model::State`]);
//! - [`solve`]: Newton time stepping and static continuation, generic over
//!   the model;
//! - [`sim`]: a simulation (scene + model + state + outputs), the statics
//!   report, the typed top-level error;
//! - [`fmi`] and the `riser` binary on top.

pub use sim::error::RiserError;

pub mod fmi;
pub mod loads;
pub mod math;
pub mod model;
pub mod scene;
pub mod sim;
pub mod solve;
