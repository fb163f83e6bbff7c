//! The Cosserat director rod of the paper: kinematics, shape functions, the
//! element (strains, energy, internal force, tangent) and the assembled model.

pub mod element;
pub mod gauss;
pub mod kinematics;
pub mod model;
pub mod shape;
