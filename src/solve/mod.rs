//! The solvers, generic over the model (they never name the rod or the
//! cable): the time integrator with its Newton iteration and step control
//! ([`newton`]) and static equilibrium by continuation ([`statics`]).

pub mod eigen;
pub mod newton;
pub mod statics;

pub use newton::{Integrator, SolverLog, StepInfo};
