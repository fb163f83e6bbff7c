//! Loads from the water and gravity: current profiles, Morison drag
//! (paper eqs. 13–17), weight and buoyancy (including buoyancy modules).

pub mod current;
pub mod fluid;
pub mod morison;
pub mod weight;
