//! `riser statics SYSTEM [--pose surge,sway,heave,roll,pitch,yaw]`: the
//! statics of a system of lines on one vessel (issue 49,
//! docs/guide/systems.md), its JSON and text summary.

use riser::scene::system::{SystemScene, VesselEnd};
use riser::sim::system::{SystemStatics, solve_system};

/// `--pose`'s six numbers (m, rad); none: the neutral pose.
pub fn parse_pose(pose: Option<&str>) -> Result<[f64; 6], String> {
    let Some(text) = pose else { return Ok([0.0; 6]) };
    let v: Vec<f64> = text
        .split(',')
        .map(|t| t.trim().parse::<f64>().map_err(|_| format!("--pose: '{}' is not a number", t.trim())))
        .collect::<Result<_, _>>()?;
    let Ok(p) = <[f64; 6]>::try_from(v.as_slice()) else {
        return Err(format!("--pose: {} number(s); it takes six: surge,sway,heave (m),roll,pitch,yaw (rad)", v.len()));
    };
    if let Some(x) = p.iter().find(|x| !x.is_finite()) {
        return Err(format!("--pose: {x} is not finite"));
    }
    if let Some(a) = p[3..].iter().find(|a| a.abs() >= std::f64::consts::FRAC_PI_2) {
        return Err(format!("--pose: an angle of {a} rad: the angles are radians, below pi/2"));
    }
    Ok(p)
}

fn v3(v: &riser::math::V3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The JSON of `riser statics SYSTEM --json` (docs/guide/systems.md).
pub fn system_json(sys: &SystemScene, st: &SystemStatics, wall: f64) -> serde_json::Value {
    let lines: Vec<serde_json::Value> = st
        .lines
        .iter()
        .map(|l| {
            let end = |e: VesselEnd| if e == VesselEnd::From { "from" } else { "to" };
            let mut row = serde_json::json!({
                "name": l.name,
                "tension_from": l.tension_from,
                "tension_to": l.tension_to,
                "min_tension": l.min_tension,
                "touchdown_s": l.touchdown_s,
                "hang_off_end": end(l.hang_off_end),
                "iterations": l.report.iterations,
                "residual": l.report.residual,
            });
            if let Some(o) = row.as_object_mut() {
                // a fixed end's load; the vessel point's position where the line has one
                if let (Some(f), Some(a)) = (l.anchor_force, l.anchor_uplift_angle) {
                    o.insert("anchor_force".into(), v3(&f).into());
                    o.insert("anchor_uplift_angle".into(), a.into());
                }
                o.insert("fairlead".into(), l.vessel_end.map(|_| v3(&l.fairlead)).into());
                o.insert("vessel_end".into(), l.vessel_end.map(end).into());
            }
            row
        })
        .collect();
    let points: Vec<serde_json::Value> = st
        .points
        .iter()
        .map(|p| {
            serde_json::json!({
                "name": p.name,
                "position": v3(&p.position),
                "load": v3(&p.load),
                "line_force": v3(&(p.residual - p.load)),
                "residual": p.residual.norm(),
            })
        })
        .collect();
    let k: Vec<Vec<f64>> = (0..6).map(|i| (0..6).map(|j| st.stiffness[(i, j)]).collect()).collect();
    serde_json::json!({
        "scene": sys.name,
        "system": true,
        "pose": st.pose,
        "top_force": v3(&st.force),
        "top_moment": v3(&st.moment),
        "lines": lines,
        "points": points,
        "point_iterations": st.iterations,
        "stiffness": k,
        "wall_time": wall,
    })
}

/// `riser statics` of a system file.
pub fn statics(path: &str, set: &[String], json: bool, out: bool, pose: Option<&str>) -> Result<(), String> {
    if out {
        return Err("--out: not yet for a system scene; --json has every line's numbers".to_string());
    }
    let sys = SystemScene::load(path).and_then(|s| s.with_overrides(set)).map_err(|e| e.to_string())?;
    let pose = parse_pose(pose)?;
    let on_vessel = sys.points.iter().any(|p| p.kind == riser::scene::system::PointKind::Vessel);
    if !on_vessel && pose.iter().any(|&v| v != 0.0) {
        return Err(format!(
            "--pose: system '{}' has no vessel point (its lines join fixed and free points): nothing moves with \
             the vessel's pose",
            sys.name
        ));
    }
    let t0 = std::time::Instant::now();
    let st = solve_system(&sys, &pose, true)?;
    let wall = t0.elapsed().as_secs_f64();
    if json {
        outln!("{}", system_json(&sys, &st, wall));
        return Ok(());
    }
    let kn = |v: f64| v / 1e3;
    outln!("riser statics: system '{}' ({} lines)", sys.name, sys.lines.len());
    let iterations = st.lines.iter().map(|l| l.report.iterations).max().unwrap_or(0);
    let residual = st.lines.iter().map(|l| l.report.residual).fold(0.0, f64::max);
    outln!(
        "  Newton: at most {iterations} iterations a line, relative residual at most {residual:.2e}, {:.1} ms",
        wall * 1e3
    );
    outln!(
        "  pose            surge {} m, sway {} m, heave {} m, roll {} rad, pitch {} rad, yaw {} rad",
        pose[0],
        pose[1],
        pose[2],
        pose[3],
        pose[4],
        pose[5]
    );
    let (f, m) = (st.force, st.moment);
    outln!("  force on vessel ({:.3}, {:.3}, {:.3}) kN", kn(f.x), kn(f.y), kn(f.z));
    outln!("  moment          ({:.3}, {:.3}, {:.3}) kN m about the reference point", kn(m.x), kn(m.y), kn(m.z));
    for l in &st.lines {
        let td = l.touchdown_s.map_or("none".to_string(), |s| format!("{s:.2} m"));
        let uplift = l.anchor_uplift_angle.map_or(String::new(), |a| format!(", anchor uplift {a:.2} deg"));
        outln!(
            "  line {:<10} tension from {:.3} kN, to {:.3} kN, min {:.3} kN, touchdown {td}{uplift}",
            l.name,
            kn(l.tension_from),
            kn(l.tension_to),
            kn(l.min_tension),
        );
    }
    if !st.points.is_empty() {
        outln!("  free points in equilibrium after {} Newton iterations:", st.iterations);
    }
    for p in &st.points {
        outln!(
            "  point {:<9} at ({:.3}, {:.3}, {:.3}) m, its own load ({:.3}, {:.3}, {:.3}) kN, out of balance {:.2e} N",
            p.name,
            p.position.x,
            p.position.y,
            p.position.z,
            kn(p.load.x),
            kn(p.load.y),
            kn(p.load.z),
            p.residual.norm()
        );
    }
    let k = &st.stiffness;
    outln!(
        "  stiffness       surge {:.3} kN/m, sway {:.3} kN/m, heave {:.3} kN/m, roll {:.4e} N m/rad, pitch {:.4e} N \
         m/rad, yaw {:.4e} N m/rad (diagonal; --json for the 6x6)",
        kn(k[(0, 0)]),
        kn(k[(1, 1)]),
        kn(k[(2, 2)]),
        k[(3, 3)],
        k[(4, 4)],
        k[(5, 5)]
    );
    Ok(())
}
