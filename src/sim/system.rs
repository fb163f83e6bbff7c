//! The statics of a system of lines on one vessel (issue 49; docs/theory.md
//! §17): each line is solved as the single-line scene it is
//! ([`SystemScene::line_scene`], its frame at its vessel point) with the
//! vessel at a pose, and the lines' forces on the vessel, their moments about
//! the reference point and their stiffnesses are composed.
//!
//! Pose: [surge, sway, heave, roll, pitch, yaw] (m, rad), the reference
//! point displaced by (surge, sway, heave) from its initial position (the
//! system's origin) and the vessel turned by R of the angles in the marine
//! z-y-x order (§14, R = Rz(yaw) Ry(pitch) Rx(roll)); a vessel point at ρ is
//! at x = u + R ρ.

use super::report::{StaticReport, scene_static_loads, solve_scene};
use crate::math::rigid::RotationOrder;
use crate::math::{M3, M6, V3, skew};
use crate::model::cable::CableModel;
use crate::model::cable::linearized::CableLinearized;
use crate::model::rod::RodModel;
use crate::model::rod::linearized::RodLinearized;
use crate::scene::system::{SystemScene, VesselEnd};
use crate::scene::{Model, Scene};
use crate::solve::eigen::hang_off_stiffness6;

/// One line's static state in the system.
#[derive(Debug, Clone)]
pub struct LineStatics {
    pub name: String,
    /// The single-line scene it was solved as (its frame at its vessel point).
    pub scene: Scene,
    pub report: StaticReport,
    /// Which end is on the vessel.
    pub vessel_end: VesselEnd,
    /// The vessel point's global position, m.
    pub fairlead: V3,
    /// R ρ, the vessel point from the reference point (global axes), m.
    pub arm: V3,
    /// |force| at the line's `from` and `to` ends, N.
    pub tension_from: f64,
    pub tension_to: f64,
    /// Smallest axial force along the line, N.
    pub min_tension: f64,
    /// Arc length from the vessel end to the first seabed contact, m (None: no contact).
    pub touchdown_s: Option<f64>,
    /// The force the line exerts on its fixed point (anchor), global, N: the
    /// reaction there (with what the discretisation lumps on the end node:
    /// half an element's weight and its seabed contact).
    pub anchor_force: V3,
    /// The line's angle at the anchor above the horizontal, deg: the rod's
    /// tangent, the cable's last segment (a chain on a penalty seabed dips
    /// by its penetration over a segment).
    pub anchor_uplift_angle: f64,
    /// The line's 3×3 stiffness at its vessel point (the translation block
    /// of `hang_off_stiffness6`, §8.3: the support's force on the line per
    /// metre of the point's displacement, the line re-solved), N/m.
    pub stiffness: M3,
}

/// The system's static state at a pose.
#[derive(Debug, Clone)]
pub struct SystemStatics {
    pub pose: [f64; 6],
    pub lines: Vec<LineStatics>,
    /// The lines' force on the vessel, global, N.
    pub force: V3,
    /// Their moment about the reference point, global, N m.
    pub moment: V3,
    /// −∂(F, M)/∂(surge, sway, heave, δroll, δpitch, δyaw), rotations as
    /// small global rotation-vector increments about the pose (17.3): N/m,
    /// N/rad, N m/m, N m/rad. Zero unless asked for.
    pub stiffness: M6,
}

/// The rotation of a pose's angles (z-y-x).
pub fn pose_rotation(pose: &[f64; 6]) -> M3 {
    RotationOrder::Zyx.rotation([pose[3], pose[4], pose[5]])
}

/// The 6×6 stiffness on the vessel's reference point of a pinned vessel
/// point at arm a = Rρ carrying force `force` (the line's on the vessel)
/// with the line's translation stiffness `s` (17.3):
/// `K = [S, −S[a]×; [a]× S, −[F]×[a]× − [a]× S [a]×]`.
pub fn point_stiffness6(s: &M3, arm: &V3, force: &V3) -> M6 {
    let ax = skew(arm);
    let mut k = M6::zeros();
    k.fixed_view_mut::<3, 3>(0, 0).copy_from(s);
    k.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-s * ax));
    k.fixed_view_mut::<3, 3>(3, 0).copy_from(&(ax * s));
    k.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-skew(force) * ax - ax * s * ax));
    k
}

/// The translation stiffness of a line's static state (§8.3).
fn line_stiffness(scene: &Scene, rep: &StaticReport) -> Result<M3, String> {
    let loads = scene_static_loads(scene);
    let cfg = &rep.solution.config;
    let s6 = match scene.analysis.model {
        Model::Cable => {
            let model = CableModel::from_scene(scene);
            hang_off_stiffness6(&CableLinearized::new(&model, loads.drag.is_some()), cfg)
        }
        Model::Rod => {
            let model = RodModel::from_scene(scene);
            hang_off_stiffness6(&RodLinearized::new(&model, &loads), cfg)
        }
    }
    .map_err(|e| format!("line '{}': its stiffness: {e}", scene.name))?;
    Ok(s6.fixed_view::<3, 3>(0, 0).into_owned())
}

/// Solves every line of `sys` with the vessel at `pose` and composes the
/// loads on the vessel; with `stiffness`, the 6×6 stiffness too. An error
/// names the line whose statics failed.
pub fn solve_system(sys: &SystemScene, pose: &[f64; 6], stiffness: bool) -> Result<SystemStatics, String> {
    let r = pose_rotation(pose);
    let u = V3::new(pose[0], pose[1], pose[2]);
    let mut lines = Vec::with_capacity(sys.lines.len());
    let (mut force, mut moment, mut k) = (V3::zeros(), V3::zeros(), M6::zeros());
    for (i, l) in sys.lines.iter().enumerate() {
        let (vessel_end, vp, _) = sys.ends(i);
        let arm = r * V3::from(vp.position);
        let fairlead = u + arm;
        let scene = sys.line_scene(i, fairlead);
        scene.validate().map_err(|e| format!("line '{}' at the pose: {e}", l.name))?;
        let rep = solve_scene(&scene).map_err(|e| format!("line '{}': {e}", l.name))?;
        let (top, bottom) = (rep.top_tension, rep.bottom_tension);
        let (tension_from, tension_to) = match vessel_end {
            VesselEnd::From => (top, bottom),
            VesselEnd::To => (bottom, top),
        };
        let loads = scene_static_loads(&scene);
        let touchdown_s = loads.seabed.as_ref().and_then(|b| {
            let nodes: Vec<V3> = rep.shape.iter().map(|s| V3::new(s.x, s.y, s.z)).collect();
            let t = crate::loads::seabed::touchdown(b.first(), &nodes, |a| rep.shape[a].s, l.length);
            (t < l.length).then_some(t)
        });
        let fa = rep.bottom_force;
        // the line's direction at the anchor, up the line: the rod's tangent, the cable's last chord
        let cfg = &rep.solution.config;
        let n = cfg.x.len() - 1;
        let up = match scene.analysis.model {
            Model::Rod => -cfg.xp[n],
            Model::Cable => cfg.x[n - 1] - cfg.x[n],
        };
        let anchor_uplift_angle = up.z.atan2(up.x.hypot(up.y)).to_degrees();
        let s = if stiffness { line_stiffness(&scene, &rep)? } else { M3::zeros() };
        let f = rep.top_force;
        force += f;
        moment += arm.cross(&f);
        if stiffness {
            k += point_stiffness6(&s, &arm, &f);
        }
        lines.push(LineStatics {
            name: l.name.clone(),
            min_tension: rep.min_tension,
            scene,
            report: rep,
            vessel_end,
            fairlead,
            arm,
            tension_from,
            tension_to,
            touchdown_s,
            anchor_force: fa,
            anchor_uplift_angle,
            stiffness: s,
        });
    }
    Ok(SystemStatics { pose: *pose, lines, force, moment, stiffness: k })
}

/// The pose turned by the small global rotation vector `dtheta` (rad) and
/// moved by `du` (m): angles of `exp([δθ]×) R` (z-y-x), for finite differences
/// of the stiffness's rotation columns.
pub fn perturbed_pose(pose: &[f64; 6], du: V3, dtheta: V3) -> [f64; 6] {
    let r = crate::math::rigid::exp_so3(&dtheta) * pose_rotation(pose);
    let [roll, pitch, yaw] = zyx_angles(&r);
    [pose[0] + du.x, pose[1] + du.y, pose[2] + du.z, roll, pitch, yaw]
}

/// The z-y-x angles [roll, pitch, yaw] of R (pitch within ±90°).
pub fn zyx_angles(r: &M3) -> [f64; 3] {
    let pitch = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    let roll = r[(2, 1)].atan2(r[(2, 2)]);
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    [roll, pitch, yaw]
}
