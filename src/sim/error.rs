//! The crate's error type: every failure is typed; the CLI prints it and the
//! FMU turns it into an fmi2Status and a logged message.

use crate::model::DynamicsError;
use crate::model::statics::StaticsError;
use crate::scene::SceneError;
use crate::solve::eigen::EigenError;

#[derive(Debug, Clone, PartialEq)]
pub enum RiserError {
    /// A bad scene, scene file or override.
    Scene(SceneError),
    /// No static equilibrium.
    Statics(StaticsError),
    /// A dynamic run stopped (the state is kept at the last good time).
    Dynamics(DynamicsError),
    /// A modal analysis or a hang-off stiffness failed.
    Linearized(EigenError),
    /// A feature the scene asks for that this version does not provide.
    Unsupported(String),
    /// An output that is not a finite number at `time` s (the step that gave
    /// it is discarded).
    NonFinite { name: &'static str, time: f64 },
    /// `accuracy` cannot choose the numerics (docs/theory.md §16.12).
    Accuracy(AccuracyError),
    /// A system's free points did not balance their lines in a step (§17.7).
    Points(PointsDiverged),
}

impl std::fmt::Display for RiserError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RiserError::Scene(e) => e.fmt(f),
            RiserError::Statics(e) => e.fmt(f),
            RiserError::Dynamics(e) => e.fmt(f),
            RiserError::Linearized(e) => e.fmt(f),
            RiserError::Unsupported(m) => write!(f, "not supported: {m}"),
            RiserError::Accuracy(e) => e.fmt(f),
            RiserError::Points(e) => e.fmt(f),
            RiserError::NonFinite { name, time } => write!(
                f,
                "the state at t = {time:.6} s gives a non-finite {name}; the step is discarded and the state kept \
                 at its start"
            ),
        }
    }
}

impl std::error::Error for RiserError {}

impl From<SceneError> for RiserError {
    fn from(e: SceneError) -> Self {
        RiserError::Scene(e)
    }
}

impl From<StaticsError> for RiserError {
    fn from(e: StaticsError) -> Self {
        RiserError::Statics(e)
    }
}

impl From<DynamicsError> for RiserError {
    fn from(e: DynamicsError) -> Self {
        RiserError::Dynamics(e)
    }
}

impl From<EigenError> for RiserError {
    fn from(e: EigenError) -> Self {
        RiserError::Linearized(e)
    }
}

impl From<AccuracyError> for RiserError {
    fn from(e: AccuracyError) -> Self {
        RiserError::Accuracy(e)
    }
}

/// Why `accuracy` cannot choose (docs/theory.md §16.12).
#[derive(Debug, Clone, PartialEq)]
pub enum AccuracyError {
    /// The scene has none of the quantity the target is on.
    NoQuantity { quantity: &'static str, reason: &'static str },
    /// The pilots measured no value of `quantity` over their window.
    NotMeasured { quantity: String, why: String },
}

impl std::fmt::Display for AccuracyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AccuracyError::NoQuantity { quantity, reason } => {
                write!(f, "accuracy_quantity = {quantity}: {reason}")
            }
            AccuracyError::NotMeasured { quantity, why } => {
                write!(f, "accuracy: the pilots measured no {quantity} ({why})")
            }
        }
    }
}

/// The free points' positions did not balance their lines within
/// `iterations` Newton iterations; `residual` the largest point's net force
/// relative to its scale; the state kept at `time`.
#[derive(Debug, Clone, PartialEq)]
pub struct PointsDiverged {
    pub time: f64,
    pub iterations: usize,
    pub residual: f64,
    pub point: String,
}

impl std::fmt::Display for PointsDiverged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let PointsDiverged { time, iterations, residual, point } = self;
        write!(
            f,
            "time step from t = {time:.6} s failed: the free points' Newton did not converge in {iterations} \
             iterations (point '{point}' out of balance by {residual:.3e} of its force scale); the state is kept \
             at t = {time:.6} s (try a smaller time_step)"
        )
    }
}
