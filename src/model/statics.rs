//! The seam between the models' static equations and the static solvers:
//! settings, the solution, the errors, and the [`StaticEquations`] trait.

use crate::math::V3;
use crate::math::band::{BandedSystem, LinearSolveError};
use crate::model::RodConfig;

/// Newton settings.
#[derive(Debug, Clone, Copy)]
pub struct StaticOptions {
    /// Converged when every residual component is below `tolerance` times the
    /// load scale (moments and r'-equations measured per element length).
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Smallest continuation step before giving up.
    pub min_continuation_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions { tolerance: 1e-10, max_iterations: 40, min_continuation_step: 1.0 / 1024.0 }
    }
}

/// A converged static state.
#[derive(Debug, Clone)]
pub struct StaticSolution {
    pub config: RodConfig,
    /// Newton iterations over all continuation steps.
    pub iterations: usize,
    /// Continuation steps (1 if Newton converged from the start).
    pub continuation_steps: usize,
    /// Final relative residual.
    pub residual: f64,
    /// Force the supports exert on the line at S = 0 and S = L, N
    /// (the reactions of the discrete equations).
    pub reactions: [V3; 2],
}

/// Why a static solution could not be found.
#[derive(Debug, Clone, PartialEq)]
pub enum StaticsError {
    /// Newton did not converge even with the smallest continuation step.
    NotConverged { iterations: usize, residual: f64, continuation: f64 },
    /// The tangent is singular or not finite.
    Linear(LinearSolveError),
}

impl std::fmt::Display for StaticsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StaticsError::NotConverged { iterations, residual, continuation } => write!(
                f,
                "static equilibrium not found: Newton stopped after {iterations} iterations with relative \
                 residual {residual:.3e} at load continuation {:.1}% (the line may have no equilibrium \
                 with these ends and loads, or need more elements)",
                continuation * 100.0
            ),
            StaticsError::Linear(e) => write!(f, "static equilibrium not found: {e}"),
        }
    }
}

impl std::error::Error for StaticsError {}

/// A static problem that pseudo-transient continuation can drive: the rod
/// (`model::rod::statics::StaticProblem`) and the cable
/// (`model::cable::statics::CableStatics`).
pub trait StaticEquations {
    type Config: Clone;
    fn n_dof(&self) -> usize;
    fn new_system(&self) -> Result<BandedSystem, LinearSolveError>;
    /// R(q) into `r` and, if given, ∂R/∂q into `sys`.
    fn residual(&self, cfg: &Self::Config, r: &mut [f64], sys: Option<&mut BandedSystem>);
    /// Largest free residual component relative to the force scale.
    fn relative(&self, r: &[f64]) -> f64;
    /// The Newton correction du = −K⁻¹ r with the fixed unknowns held.
    fn correction(&self, sys: &mut BandedSystem, r: &mut [f64], du: &mut [f64]) -> Result<(), LinearSolveError>;
    fn apply_increment(&self, cfg: &mut Self::Config, du: &[f64]);
    fn is_finite(cfg: &Self::Config) -> bool;
    /// Weight D_i of unknown i in the regularisation μ D (q − q_k).
    fn pseudo_mass(&self, i: usize) -> f64;
    /// Unit of μ: force scale over length, N/m.
    fn mu_unit(&self) -> f64;
    /// Round-off of the relative residual at `cfg`.
    fn roundoff(&self, cfg: &Self::Config) -> f64;
    /// The converged state with its residual `r`.
    fn solution(&self, cfg: Self::Config, r: &[f64], iterations: usize, steps: usize, residual: f64) -> StaticSolution;
}

/// Static equations that the homotopy continuation can also drive (the rod).
pub trait Homotopy: StaticEquations {
    /// Scale of forces for the convergence test, N.
    fn force_scale(&self) -> f64;
    /// Largest free residual component relative to `scale`.
    fn relative_residual(&self, r: &[f64], scale: f64) -> f64;
    /// Round-off of the residual at `cfg`, N.
    fn residual_roundoff(&self, cfg: &Self::Config) -> f64;
}
