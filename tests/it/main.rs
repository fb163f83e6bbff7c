//! The integration tests, one binary: each file of this folder is a module,
//! named as the file (`cargo test --profile fasttest --test it -- seabed::`
//! runs one). One test binary links once where thirty-five linked the crate
//! and its dependencies each (about a minute of a clean `make test`), and
//! its tests share the cores instead of waiting for each other's binaries.
//! `tests/no_allocation.rs` stays its own binary: it counts allocations
//! through a global allocator, which would count every other test's too.

mod common;

mod accuracy;
mod accuracy_fallback;
mod accuracy_fourth;
mod cable;
mod cli;
mod design_numbers;
mod dynamics_conservation;
mod dynamics_convergence;
mod dynamics_dissipation;
mod dynamics_frequencies;
mod dynamics_tangent;
mod error_estimate;
mod fatigue;
mod free_surface;
mod hang_off_end;
mod hang_off_stiffness;
mod hang_off_stiffness6;
mod input_path_interior;
mod layering;
mod lrfd;
mod modes;
mod monolithic_body;
mod parameter_ranges;
mod raos;
mod reference_selfcheck;
mod rod_derivatives;
mod scene_validation;
mod seabed;
mod sections;
mod stability;
mod statics_validation;
mod system;
mod system_accuracy;
mod system_dynamics;
mod system_free_dynamics;
mod system_free_points;
mod system_modes;
mod system_rod_points;
mod system_surface_buoy;
mod wall_stresses;
mod waves;
mod waves_dynamics;
mod waves_force;
