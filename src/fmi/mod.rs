//! The FMI 2.0 Co-Simulation unit: the variable table ([`vars`], generated
//! from `modelDescription/variables.csv`), the safe [`instance::Instance`]
//! with the state machine, and the C ABI ([`exports`], the crate's only
//! `unsafe` code).

pub mod exports;
pub mod input_path;
pub mod instance;
pub mod plausibility;
pub mod system;
pub mod vars;
