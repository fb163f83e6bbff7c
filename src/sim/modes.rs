//! The natural modes of a scene's line about its static state
//! (docs/theory.md §8), as the CLI reports them: periods, the direction each
//! mode moves the line in, and its shape.

use super::error::RiserError;
use super::report::{StaticReport, scene_static_loads, solve_scene};
use crate::math::V3;
use crate::model::RodConfig;
use crate::model::cable::CableModel;
use crate::model::cable::linearized::CableLinearized;
use crate::model::linearized::{Direction, Linearized};
use crate::model::rod::RodModel;
use crate::model::rod::linearized::RodLinearized;
use crate::scene::{Model, Scene};
use crate::solve::eigen::{EigenError, Modes, lowest_modes};

/// One node of a mode shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeRow {
    /// Reference arc length from the hang-off, m.
    pub s: f64,
    /// Static position, m.
    pub position: V3,
    /// Displacement of the centreline in the mode, scaled so that the
    /// largest is 1 m (for a torsion mode: so that the largest twist is 1 rad), m.
    pub displacement: V3,
    /// Twist about the line's axis at that scale, rad (0 for the cable).
    pub twist: f64,
}

/// One natural mode of a scene's line.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneMode {
    /// 1 for the lowest.
    pub number: usize,
    /// Natural period, s (∞ if the static state is unstable in this mode).
    pub period: f64,
    /// Natural frequency, Hz.
    pub frequency: f64,
    /// ω², 1/s², and its imaginary part (non-zero only for a flutter pair
    /// under the steady current's drag).
    pub eigenvalue: f64,
    pub eigenvalue_imag: f64,
    /// The direction with the largest share of the kinetic energy.
    pub direction: Direction,
    /// Shares of the kinetic energy: in-plane, out-of-plane, axial, torsion.
    pub fractions: [f64; 4],
    pub shape: Vec<ModeRow>,
}

/// The modes of a scene.
#[derive(Debug, Clone)]
pub struct ModalReport {
    pub modes: Vec<SceneMode>,
    /// The static state the line vibrates about.
    pub statics: StaticReport,
    /// Free unknowns of the eigenproblem.
    pub unknowns: usize,
    /// Relative asymmetry of the static tangent (see [`Modes::asymmetry`]).
    pub asymmetry: f64,
    pub model: Model,
}

/// Unit normal of the vertical plane through `top` and `bottom`: the
/// out-of-plane direction of a line hanging between them (ŷ for a vertical chord).
pub fn plane_normal(top: V3, bottom: V3) -> V3 {
    let h = V3::new(bottom.x - top.x, bottom.y - top.y, 0.0);
    if h.norm() > 1e-9 * (bottom - top).norm() { V3::z().cross(&h).normalize() } else { V3::y() }
}

/// The scene's modes from the eigen-solution: directions and scaled shapes.
fn describe<L: Linearized>(line: &L, cfg: &RodConfig, modes: &Modes, normal: &V3) -> Vec<SceneMode> {
    modes
        .modes
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let motion = line.motion(cfg, &m.vector, normal);
            let direction = motion.direction();
            // scale: the largest displacement 1 m, or the largest twist 1 rad
            let (mut big, mut sign_of) = (0.0f64, 1.0);
            for (_, u, tw) in &motion.nodes {
                if direction == Direction::Torsion {
                    if tw.abs() > big {
                        big = tw.abs();
                        sign_of = tw.signum();
                    }
                } else {
                    for c in u.iter() {
                        if c.abs() > big {
                            big = c.abs();
                            sign_of = c.signum();
                        }
                    }
                }
            }
            let scale = if big > 0.0 { sign_of / big } else { 1.0 };
            let shape = motion
                .nodes
                .iter()
                .enumerate()
                .map(|(a, (s, u, tw))| ModeRow {
                    s: *s,
                    position: cfg.x[a],
                    displacement: u * scale,
                    twist: tw * scale,
                })
                .collect();
            SceneMode {
                number: k + 1,
                period: m.period(),
                frequency: m.frequency(),
                eigenvalue: m.eigenvalue,
                eigenvalue_imag: m.eigenvalue_imag,
                direction,
                fractions: motion.fractions,
                shape,
            }
        })
        .collect()
}

/// The `count` lowest natural modes of the scene's line about its static
/// state (the statics' loads: with the current when `static_current` is set),
/// with the added mass of the water.
pub fn scene_modes(scene: &Scene, count: usize) -> Result<ModalReport, RiserError> {
    if count == 0 {
        return Err(EigenError::NoModes.into());
    }
    let statics = solve_scene(scene)?;
    let loads = scene_static_loads(scene);
    let cfg = &statics.solution.config;
    let normal = plane_normal(scene.hang_off(), scene.anchor());
    let (modes, modes_raw) = match scene.analysis.model {
        Model::Rod => {
            let mut model = RodModel::from_scene(scene);
            model.set_static_frame(cfg);
            let line = RodLinearized::new(&model, &loads);
            let raw = lowest_modes(&line, cfg, count)?;
            (describe(&line, cfg, &raw, &normal), raw)
        }
        Model::Cable => {
            let model = CableModel::from_scene(scene);
            let line = CableLinearized::new(&model, loads.drag.is_some());
            let raw = lowest_modes(&line, cfg, count)?;
            (describe(&line, cfg, &raw, &normal), raw)
        }
    };
    Ok(ModalReport {
        modes,
        statics,
        unknowns: modes_raw.size,
        asymmetry: modes_raw.asymmetry,
        model: scene.analysis.model,
    })
}
