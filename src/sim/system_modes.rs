//! The natural modes of a system of lines joined at free points about its
//! static state (issue 49; docs/theory.md §17.9). With the vessel held, the
//! lines between a fixed and a vessel point vibrate alone (each its own
//! [`super::modes::scene_modes`]); the lines with an end at a free point are
//! coupled through the points: their unknowns and the points' positions
//! make one generalised eigenproblem K φ = λ M φ (17.20)–(17.21), each
//! line's static tangent and mass (its end rows on the points it meets),
//! each point's load stiffness and mass with its added mass, solved dense
//! ([`lowest_modes_dense`]).

use super::report::scene_static_loads;
use super::system::{SystemStatics, point_load, solve_system};
use crate::math::V3;
use crate::math::band::BandedSystem;
use crate::model::RodConfig;
use crate::model::cable::CableModel;
use crate::model::cable::linearized::CableLinearized;
use crate::model::linearized::Linearized;
use crate::model::rod::RodModel;
use crate::model::rod::linearized::RodLinearized;
use crate::model::rod::statics::StaticLoads;
use crate::scene::Model;
use crate::scene::system::{PointKind, PointSpec, SystemScene};
use crate::solve::eigen::lowest_modes_dense;
use faer::Mat;

/// A line's or a free point's part in a joined mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Its share of the mode's kinetic energy (the shares add up to 1).
    pub share: f64,
    /// A line's: the direction with the largest share of its own kinetic
    /// energy in the mode; a point's: the global axis it moves most along
    /// (`x`, `y`, `z`).
    pub direction: &'static str,
}

/// One mode of the lines and points joined at the free points.
#[derive(Debug, Clone, PartialEq)]
pub struct JoinedMode {
    /// 1 for the lowest.
    pub number: usize,
    /// Natural period, s (∞ if the static state is unstable in this mode).
    pub period: f64,
    /// Natural frequency, Hz.
    pub frequency: f64,
    /// ω², 1/s², and its imaginary part (a flutter pair under the steady
    /// current's drag).
    pub eigenvalue: f64,
    pub eigenvalue_imag: f64,
    /// Each joined line's part (in [`JoinedModes::lines`]' order).
    pub lines: Vec<Part>,
    /// Each free point's part (the scene's order of free points).
    pub points: Vec<Part>,
    /// Each free point's displacement in the mode (global), scaled so that
    /// the largest displacement of any node or point is 1 m.
    pub point_displacements: Vec<V3>,
    /// Each free point's entries of the mass-normalised mode (as
    /// `line_vectors`), m·kg^-½.
    pub point_vectors: Vec<V3>,
    /// Each joined line's mode over its own unknowns (its frame's axes are
    /// the system's), mass-normalised over the system (φᵀ M φ = 1, kg):
    /// its end nodes' at the points they meet.
    pub line_vectors: Vec<Vec<f64>>,
}

impl JoinedMode {
    /// The line or point that moves most (the largest share of the kinetic
    /// energy): (`line` or `point`, its index among the joined lines or
    /// the free points).
    pub fn most(&self) -> (&'static str, usize) {
        let best =
            |v: &[Part]| v.iter().enumerate().max_by(|a, b| a.1.share.total_cmp(&b.1.share)).map(|(i, p)| (i, p.share));
        match (best(&self.lines), best(&self.points)) {
            (Some((i, a)), Some((_, b))) if a >= b => ("line", i),
            (_, Some((k, _))) => ("point", k),
            (Some((i, _)), None) => ("line", i),
            (None, None) => ("line", 0),
        }
    }
}

/// The joined modes and what they were solved on.
#[derive(Debug, Clone)]
pub struct JoinedModes {
    /// The lowest modes, by increasing real part of λ.
    pub modes: Vec<JoinedMode>,
    /// The joined lines (indices into the system's lines): those with an
    /// end at a free point.
    pub lines: Vec<usize>,
    /// The free points' names, in the scene's order.
    pub point_names: Vec<String>,
    /// The system's statics the modes are about (the neutral pose).
    pub statics: SystemStatics,
    /// Unknowns of the dense problem: the joined lines' free ones and 3 a point.
    pub unknowns: usize,
    /// Largest |K − Kᵀ| over the largest |K| (~1e-16 without the current).
    pub asymmetry: f64,
}

/// A joined line's linear pieces: its static tangent and mass, which of
/// its unknowns are where in the joined problem.
struct Piece {
    index: usize,
    k: BandedSystem,
    m: BandedSystem,
    /// Each of its unknowns' place in the joined problem (None: held).
    place: Vec<Option<usize>>,
    model: PieceModel,
    cfg: RodConfig,
    normal: V3,
}

/// A joined line's model: a cable, or a rod with its static loads (its end
/// at a point pinned, its twist held at its anchor end as the statics',
/// §17.4, §17.9).
enum PieceModel {
    Cable(Box<CableModel>, bool),
    Rod(Box<(RodModel, StaticLoads)>),
}

impl PieceModel {
    /// `f` on the model linearised with its static loads (`drag`: with the
    /// current's drag in the cable's static tangent; the rod's loads are its
    /// statics' and only its tangent reads them).
    fn linearized<R>(&self, drag: bool, f: impl FnOnce(&dyn Linearized) -> R) -> R {
        match self {
            PieceModel::Cable(m, with_current) => f(&CableLinearized::new(m, drag && *with_current)),
            PieceModel::Rod(rod) => f(&RodLinearized::new(&rod.0, &rod.1)),
        }
    }
}

/// The free point's mass with its added mass at `x`, C_a ρ V (isotropic,
/// as its dynamics', §17.7; a cylinder's times its submerged fraction,
/// §17.10), kg.
pub fn point_mass(sys: &SystemScene, p: &PointSpec, x: V3) -> f64 {
    let env = &sys.environment;
    let added = p.ca() * env.water_density * p.volume();
    match p.height {
        None => p.mass() + added,
        Some(_) => p.mass() + added * p.floater().submerged(x.z - env.water_surface_z),
    }
}

/// The `count` lowest modes of the lines of `sys` joined at its free points,
/// about the system's statics at the neutral pose, the vessel held
/// (docs/theory.md §17.9). An error names what failed: the statics, a line,
/// or the eigen-solution.
pub fn joined_modes(sys: &SystemScene, count: usize) -> Result<JoinedModes, String> {
    let free: Vec<&PointSpec> = sys.points.iter().filter(|p| p.kind == PointKind::Free).collect();
    if free.is_empty() {
        return Err("the system has no free point: its lines vibrate alone".to_string());
    }
    let statics = solve_system(sys, &[0.0; 6], false)?;
    let free_index = |name: &str| free.iter().position(|p| p.name == name);
    let np = free.len();
    let mut next = 3 * np;
    let mut pieces = Vec::new();
    for (i, l) in sys.lines.iter().enumerate() {
        let (_, hp, ap) = sys.ends(i);
        let (h, a) = (free_index(&hp.name), free_index(&ap.name));
        if h.is_none() && a.is_none() {
            continue;
        }
        let ls = &statics.lines[i];
        let scene = &ls.scene;
        let loads = scene_static_loads(scene);
        let model = match scene.analysis.model {
            Model::Cable => PieceModel::Cable(Box::new(CableModel::from_scene(scene)), loads.drag.is_some()),
            Model::Rod => PieceModel::Rod(Box::new((RodModel::from_scene(scene), loads))),
        };
        let cfg = ls.report.solution.config.clone();
        let named = |e: &dyn std::fmt::Display| format!("line '{}': {e}", l.name);
        let (k, m, fixed, hr, ar) = model.linearized(true, |line| {
            let n = line.n_dof();
            let mut k = line.new_system().map_err(|e| named(&e))?;
            let mut m = line.new_system().map_err(|e| named(&e))?;
            let mut r = vec![0.0; n];
            line.static_tangent(&cfg, &mut r, &mut k);
            line.mass_matrix(&cfg, &mut m);
            Ok::<_, String>((k, m, line.fixed_dofs(), line.hang_off_rows(), line.anchor_rows()))
        })?;
        let n = k.dim();
        let place = (0..n)
            .map(|d| {
                for (end, rows) in [(h, hr), (a, ar)] {
                    if let (Some(p), Some(c)) = (end, rows.iter().position(|&r| r == d)) {
                        return Some(3 * p + c);
                    }
                }
                if fixed.binary_search(&d).is_ok() {
                    None
                } else {
                    next += 1;
                    Some(next - 1)
                }
            })
            .collect();
        let normal = super::modes::plane_normal(scene.hang_off(), scene.anchor());
        pieces.push(Piece { index: i, k, m, place, model, cfg, normal });
    }
    let n = next;
    // (17.20)–(17.21): the lines' tangents and masses, their end rows on the points
    let mut k = Mat::<f64>::zeros(n, n);
    let mut m = Mat::<f64>::zeros(n, n);
    for p in &pieces {
        for (a, pa) in p.place.iter().enumerate() {
            let Some(ga) = pa else { continue };
            for (b, pb) in p.place.iter().enumerate() {
                let Some(gb) = pb else { continue };
                k[(*ga, *gb)] += p.k.get(a, b);
                m[(*ga, *gb)] += p.m.get(a, b);
            }
        }
    }
    // each point's load stiffness −∂f/∂x and its mass with its added mass
    for (j, p) in free.iter().enumerate() {
        let (_, kp) = point_load(sys, p, statics.points[j].position);
        let mp = point_mass(sys, p, statics.points[j].position);
        for a in 0..3 {
            m[(3 * j + a, 3 * j + a)] += mp;
            for b in 0..3 {
                k[(3 * j + a, 3 * j + b)] += kp[(a, b)];
            }
        }
    }
    let j_positions: Vec<V3> = statics.points.iter().map(|p| p.position).collect();
    let raw = lowest_modes_dense(&k, &m, count).map_err(|e| format!("the joined lines and points: {e}"))?;
    let modes = raw
        .modes
        .iter()
        .enumerate()
        .map(|(number, mode)| {
            let phi = &mode.vector;
            let mut line_vectors = Vec::with_capacity(pieces.len());
            let mut energies = Vec::with_capacity(pieces.len() + np);
            let mut directions = Vec::with_capacity(pieces.len());
            let mut largest = 0.0f64;
            for p in &pieces {
                let v: Vec<f64> = p.place.iter().map(|g| g.map_or(0.0, |g| phi[g])).collect();
                let mut mv = vec![0.0; v.len()];
                p.m.mul_add(&v, &mut mv);
                energies.push(v.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>());
                directions
                    .push(p.model.linearized(false, |line| line.motion(&p.cfg, &v, &p.normal).direction().name()));
                largest = largest.max(v.iter().fold(0.0, |s: f64, x| s.max(x.abs())));
                line_vectors.push(v);
            }
            let displacements: Vec<V3> = (0..np).map(|j| V3::new(phi[3 * j], phi[3 * j + 1], phi[3 * j + 2])).collect();
            let mut point_directions = Vec::with_capacity(np);
            for (j, d) in displacements.iter().enumerate() {
                energies.push(point_mass(sys, free[j], j_positions[j]) * d.norm_squared());
                largest = largest.max(d.amax());
                point_directions.push(["x", "y", "z"][d.iamax()]);
            }
            let total: f64 = energies.iter().sum();
            let share = |e: f64| if total > 0.0 { e / total } else { 0.0 };
            let scale = if largest > 0.0 { 1.0 / largest } else { 1.0 };
            JoinedMode {
                number: number + 1,
                period: mode.period(),
                frequency: mode.frequency(),
                eigenvalue: mode.eigenvalue,
                eigenvalue_imag: mode.eigenvalue_imag,
                lines: directions.iter().zip(&energies).map(|(d, e)| Part { share: share(*e), direction: d }).collect(),
                points: point_directions
                    .iter()
                    .zip(&energies[pieces.len()..])
                    .map(|(d, e)| Part { share: share(*e), direction: d })
                    .collect(),
                point_displacements: displacements.iter().map(|d| d * scale).collect(),
                point_vectors: displacements,
                line_vectors,
            }
        })
        .collect();
    Ok(JoinedModes {
        modes,
        lines: pieces.iter().map(|p| p.index).collect(),
        point_names: free.iter().map(|p| p.name.clone()).collect(),
        statics,
        unknowns: n,
        asymmetry: raw.asymmetry,
    })
}
