//! A system of lines in the FMU (issue 49, docs/guide/fmu.md "A system of
//! lines", docs/theory.md §17.6): the `scene` parameter may name a system
//! file. Its first `[[line]]` is the instance's line (its single-line
//! outputs, `top_tension`, `shape[k]`, … are that line's); the others are
//! [`OtherLine`]s moved by the same vessel path at their own vessel
//! points; the loads on the vessel and the energies are the system's sums
//! (17.11, 17.12). Free points (joints, clump weights, buoys) step with the
//! lines at them by the command line's stepper ([`FreePoints`], §17.7), the
//! lines handed to it one at a time ([`FmuLines`]), allocating nothing.

use super::vars::{Kind, Variable};
use crate::model::{Outputs, State};
use crate::scene::Scene;
use crate::scene::system::{PointKind, SystemScene, VesselEnd};
use crate::sim::Simulation;
use crate::sim::system_dynamics::{FreePoints, LineSet};

/// A line of the system beyond its first, in a run.
pub struct OtherLine {
    pub name: String,
    /// Which of its ends is on the vessel.
    pub vessel_end: VesselEnd,
    pub scene: Scene,
    pub sim: Simulation,
    /// Its state at the start of the communication step in progress
    /// (allocated at initialisation, copied without allocating).
    pub step_start: State,
}

/// The parameters a master may set on a system: they apply to every line
/// (the numerics and the ramps). A line's properties, its frame (anchor,
/// hang-off, water surface, seabed height) and the sea are the system
/// file's.
pub const SYSTEM_WIDE: [&str; 6] =
    ["time_step", "newton_tolerance", "structural_damping", "rho_infinity", "static_current", "current_ramp"];

/// True if the master's value `text` for `v` is what `reading` (the
/// scene's) says: equal numbers (to 1e-12), flags or texts.
fn same_value(v: &Variable, text: &str, reading: Option<&str>) -> bool {
    let Some(r) = reading else { return false };
    match v.kind {
        Kind::Real => match (text.parse::<f64>(), r.parse::<f64>()) {
            (Ok(x), Ok(y)) => (x - y).abs() <= 1e-12 * x.abs().max(y.abs()),
            _ => false,
        },
        Kind::Integer => matches!((text.parse::<i64>(), r.parse::<i64>()), (Ok(x), Ok(y)) if x == y),
        Kind::Boolean => matches!((text.parse::<bool>(), r.parse::<bool>()), (Ok(x), Ok(y)) if x == y),
        Kind::String => text == r,
    }
}

/// Each line's single-line scene of `sys` at the neutral pose with the
/// master's parameters `sets` (variable, its value as text): those of
/// [`SYSTEM_WIDE`] applied to every line; any other must read as the
/// first line's scene reads it (a master that sets every start value of
/// the generic FMU sets the default scene's), else it is refused, named.
/// With free points, also the system with [`SYSTEM_WIDE`]'s values set
/// (its lines' scenes then come from its statics, §17.4: those here, at
/// the points' initial positions, read its parameters back).
pub fn line_scenes(sys: &SystemScene, sets: &[(&'static Variable, String)]) -> Result<LineScenes, String> {
    let wide: Vec<String> =
        sets.iter().filter(|(v, _)| SYSTEM_WIDE.contains(&v.name)).map(|(v, t)| format!("{}={t}", v.name)).collect();
    let mut scenes = Vec::with_capacity(sys.lines.len());
    for (i, l) in sys.lines.iter().enumerate() {
        let (end, vp, _) = sys.ends(i);
        let scene = sys.line_scene(i, crate::math::V3::from(vp.position));
        let scene =
            scene.with_overrides(&wide).map_err(|e| format!("invalid parameter value: line '{}': {e}", l.name))?;
        scenes.push((scene, end));
    }
    let refused: Vec<String> = sets
        .iter()
        .filter(|(v, t)| !SYSTEM_WIDE.contains(&v.name) && !same_value(v, t, scenes[0].0.parameter(v.name).as_deref()))
        .map(|(v, t)| format!("{}={t}", v.name))
        .collect();
    if !refused.is_empty() {
        return Err(format!(
            "invalid parameter value: {}: scene '{}' is a system of lines, whose lines take their properties, \
             frames and sea from its file; a master may set {} on it (they apply to every line), and any other \
             parameter only to the value its first line has",
            refused.join(", "),
            sys.name,
            SYSTEM_WIDE.join(", ")
        ));
    }
    // the first line's scene carries the master's values (the lines' scenes copy the system's)
    let set = &scenes[0].0;
    let mut system = sys.clone();
    system.analysis.time_step = set.analysis.time_step;
    system.analysis.newton_tolerance = set.analysis.newton_tolerance;
    system.analysis.structural_damping = set.analysis.structural_damping;
    system.analysis.rho_infinity = set.analysis.rho_infinity;
    system.analysis.static_current = set.analysis.static_current;
    system.current.ramp = set.current.ramp;
    // `accuracy` (docs/theory.md §16.14): the system's pilots of the design
    // motion choose every line's elements, the step and the tolerance
    let mut choice = None;
    if system.analysis.accuracy > 0.0 {
        let pinned = crate::sim::accuracy::Pinned::of_names(sets.iter().map(|(v, _)| v.name));
        let (chosen, c, said) = choose_for_design(system, &scenes[0].0, pinned)?;
        for ((scene, _), l) in scenes.iter_mut().zip(&chosen.lines) {
            scene.analysis.n_elements = l.n_elements;
            scene.analysis.time_step = chosen.analysis.time_step;
            scene.analysis.newton_tolerance = chosen.analysis.newton_tolerance;
        }
        system = chosen;
        choice = c.map(|c| (c, said));
    }
    let free = sys.points.iter().any(|p| p.kind == PointKind::Free);
    Ok(LineScenes { scenes, free: free.then_some(system), choice })
}

/// The numerics `accuracy` chooses for `sys` (the master's values set) on
/// the design motion of its first line's scene `first` (a heave of
/// `accuracy_motion_amplitude` at `accuracy_motion_period` in its sea:
/// [`crate::sim::accuracy::DesignRun`]), the pilots on the machine's
/// cores; what the rounds said, to log.
fn choose_for_design(
    sys: SystemScene,
    first: &Scene,
    pinned: crate::sim::accuracy::Pinned,
) -> Result<(SystemScene, Option<crate::sim::accuracy::Choice>, Vec<String>), String> {
    let design = crate::sim::accuracy::DesignRun::of(first).map_err(|e| e.to_string())?;
    let heave = design.heave;
    let motion = move |t: f64| {
        let h = heave.at(t);
        crate::sim::vessel::VesselMotion {
            displacement: crate::math::V3::new(0.0, 0.0, h.displacement.z),
            velocity: crate::math::V3::new(0.0, 0.0, h.velocity.z),
            ..Default::default()
        }
    };
    let spec = crate::sim::system_accuracy::SystemRunSpec {
        motion: &motion,
        window: design.window,
        period: Some(design.period),
        irregular: design.irregular,
        max_tangent_age: crate::model::DynamicOptions::default().max_tangent_age,
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut said = Vec::new();
    let (chosen, choice) =
        crate::sim::system_accuracy::apply(sys, &spec, pinned, threads, &mut |m: &str| said.push(m.to_string()))
            .map_err(|e| e.to_string())?;
    Ok((chosen, choice, said))
}

/// A system's lines as the FMU builds them ([`line_scenes`]).
pub struct LineScenes {
    /// Each line's single-line scene and which of its ends is on the vessel.
    pub scenes: Vec<(Scene, VesselEnd)>,
    /// With free points: the system with the master's numerics.
    pub free: Option<SystemScene>,
    /// With `accuracy`: the system's choice and what its rounds said.
    pub choice: Option<(crate::sim::accuracy::Choice, Vec<String>)>,
}

/// A system's lines as its free points' stepper reaches them in the FMU:
/// the instance's line (the first) and its others, one at a time.
pub struct FmuLines<'a> {
    pub first: &'a mut Simulation,
    pub first_name: &'a str,
    pub others: &'a mut [OtherLine],
}

impl LineSet for FmuLines<'_> {
    fn sim(&mut self, i: usize) -> &mut Simulation {
        if i == 0 { self.first } else { &mut self.others[i - 1].sim }
    }

    fn name(&self, i: usize) -> &str {
        if i == 0 { self.first_name } else { &self.others[i - 1].name }
    }
}

/// The outputs of a system of the first line `first`, the others `others`
/// and the free points `free`: the single-line outputs the first line's;
/// without free points, every line's loads on the vessel and energies
/// summed ([`add_line`], 17.11, 17.12); with them, the loads of the lines
/// whose hang-off is on the vessel, and the system's energies and works as
/// its balance counts them (17.17): the points' energies and the water's
/// work on them added, the works of the points on their lines (a hang-off
/// or a cable's anchor at a point) internal and left out.
pub fn system_outputs(first: &Simulation, others: &[OtherLine], free: Option<&FreePoints>) -> Outputs {
    let mut sum = first.outputs();
    let Some(free) = free else {
        for o in others {
            add_line(&mut sum, &o.sim.outputs());
        }
        return sum;
    };
    let lines = std::iter::once(sum).chain(others.iter().map(|o| o.sim.outputs()));
    let mut total = sum;
    clear_sums(&mut total);
    for (mut o, ends) in lines.zip(&free.ends) {
        if !ends.on_vessel() {
            o.top_force = crate::math::V3::zeros();
            o.top_moment = crate::math::V3::zeros();
            o.vessel_force = crate::math::V3::zeros();
            o.vessel_moment = crate::math::V3::zeros();
            o.work_top = 0.0;
        }
        if matches!(ends.anchor_at, crate::sim::system_dynamics::EndAt::Free(_)) {
            o.work_anchor = 0.0;
        }
        add_line(&mut total, &o);
    }
    for p in &free.points {
        let kinetic = 0.5 * p.mass * p.velocity.norm_squared();
        let potential = p.potential(p.position);
        total.kinetic_energy += kinetic;
        total.potential_energy += potential;
        total.total_energy += kinetic + potential;
        total.work_hydro += p.work_hydro;
    }
    total
}

/// Zeroes the quantities [`add_line`] sums.
fn clear_sums(o: &mut Outputs) {
    let zero = crate::math::V3::zeros();
    (o.top_force, o.top_moment, o.vessel_force, o.vessel_moment) = (zero, zero, zero, zero);
    (o.total_energy, o.kinetic_energy, o.strain_energy, o.potential_energy) = (0.0, 0.0, 0.0, 0.0);
    (o.work_top, o.work_hydro, o.work_anchor, o.work_seabed) = (0.0, 0.0, 0.0, 0.0);
    (o.dissipated_energy, o.algorithmic_dissipation) = (0.0, 0.0);
}

/// Adds line `other`'s loads on the vessel and its energies to the
/// system's outputs `sum` (17.11, 17.12); the single-line outputs stay the
/// first line's.
pub fn add_line(sum: &mut Outputs, other: &Outputs) {
    sum.top_force += other.top_force;
    sum.top_moment += other.top_moment;
    sum.vessel_force += other.vessel_force;
    sum.vessel_moment += other.vessel_moment;
    sum.total_energy += other.total_energy;
    sum.kinetic_energy += other.kinetic_energy;
    sum.strain_energy += other.strain_energy;
    sum.potential_energy += other.potential_energy;
    sum.work_top += other.work_top;
    sum.work_hydro += other.work_hydro;
    sum.work_anchor += other.work_anchor;
    sum.dissipated_energy += other.dissipated_energy;
    sum.algorithmic_dissipation += other.algorithmic_dissipation;
    sum.work_seabed += other.work_seabed;
}

/// The serialized state of a system: this magic, the number of blocks (u64),
/// then per line its length (u64) and its [`State::write_bytes`] block, the
/// first line's carrying the instance's numbers.
pub const SYSTEM_MAGIC: &[u8; 8] = b"RISERSY\0";

/// The framed blocks of a system's serialized state.
pub fn frame(blocks: &[Vec<u8>]) -> Vec<u8> {
    let mut out = Vec::with_capacity(16 + blocks.iter().map(|b| b.len() + 8).sum::<usize>());
    out.extend_from_slice(SYSTEM_MAGIC);
    out.extend_from_slice(&(blocks.len() as u64).to_le_bytes());
    for b in blocks {
        out.extend_from_slice(&(b.len() as u64).to_le_bytes());
        out.extend_from_slice(b);
    }
    out
}

/// The blocks of [`frame`]'s bytes, or why they are not a system's state of
/// `lines` lines.
pub fn unframe(bytes: &[u8], lines: usize) -> Result<Vec<&[u8]>, String> {
    let bad = || format!("the serialized FMU state is not that of a system of {lines} lines");
    if bytes.len() < 16 || &bytes[..8] != SYSTEM_MAGIC {
        return Err(bad());
    }
    let count = u64::from_le_bytes(bytes[8..16].try_into().map_err(|_| bad())?);
    if count != lines as u64 {
        return Err(bad());
    }
    let mut at = 16;
    let mut blocks = Vec::with_capacity(lines);
    for _ in 0..lines {
        let len = bytes
            .get(at..at + 8)
            .and_then(|b| b.try_into().ok())
            .map(u64::from_le_bytes)
            .ok_or_else(|| "the serialized FMU state is truncated".to_string())?;
        let end = usize::try_from(len).ok().and_then(|l| (at + 8).checked_add(l)).filter(|&e| e <= bytes.len());
        let Some(end) = end else { return Err("the serialized FMU state is truncated".to_string()) };
        blocks.push(&bytes[at + 8..end]);
        at = end;
    }
    if at != bytes.len() {
        return Err(bad());
    }
    Ok(blocks)
}

/// The file in a packaged system FMU's resources that names its scene (the
/// `scene` parameter's start value there): `riser-tools package-fmu --scene`.
pub const PACKAGED_SCENE: &str = "packaged_scene.txt";

/// The first value reference of a system's own outputs: line `i`'s
/// quantity `q` ([`LINE_OUTPUTS`]) is `SYSTEM_VR_BASE + LINE_OUTPUTS.len() · i + q`,
/// whatever the system (the packaged FMU's modelDescription.xml names them).
pub const SYSTEM_VR_BASE: u32 = 100_000;

/// Each line's outputs in a packaged system FMU: name suffix, unit, description.
pub const LINE_OUTPUTS: [(&str, &str, &str); 4] = [
    ("tension_from", "N", "tension at the line's `from` end"),
    ("tension_to", "N", "tension at the line's `to` end"),
    ("min_tension", "N", "smallest axial force along the line"),
    ("touchdown_s", "m", "arc length from the line's vessel end to the touchdown (its length: none)"),
];

/// Which line and quantity a system output's value reference is.
pub fn line_output(vr: u32) -> Option<(usize, usize)> {
    item_output(vr, SYSTEM_VR_BASE, POINT_VR_BASE, LINE_OUTPUTS.len())
}

/// Which item and quantity value reference `vr` is in the range [`base`,
/// `end`) of `width` quantities an item.
fn item_output(vr: u32, base: u32, end: u32, width: usize) -> Option<(usize, usize)> {
    let k = (vr < end).then(|| vr.checked_sub(base))?? as usize;
    Some((k / width, k % width))
}

/// The first value reference of a system's free points' outputs: free
/// point `k`'s (in the scene's order of its free points) coordinate `c`
/// ([`POINT_OUTPUTS`]) is `POINT_VR_BASE + POINT_OUTPUTS.len() · k + c`.
pub const POINT_VR_BASE: u32 = 200_000;

/// Each free point's outputs in a packaged system FMU: name suffix, unit, description.
pub const POINT_OUTPUTS: [(&str, &str, &str); 3] = [
    ("x", "m", "global x of the free point (the system's frame)"),
    ("y", "m", "global y of the free point"),
    ("z", "m", "global z of the free point (up)"),
];

/// Which free point and coordinate a point output's value reference is.
pub fn point_output(vr: u32) -> Option<(usize, usize)> {
    item_output(vr, POINT_VR_BASE, ANCHOR_VR_BASE, POINT_OUTPUTS.len())
}

/// The first value reference of a system's anchors' outputs: line `i`'s
/// (a line with an end at a fixed point) quantity `q` ([`ANCHOR_OUTPUTS`])
/// is `ANCHOR_VR_BASE + ANCHOR_OUTPUTS.len() · i + q`.
pub const ANCHOR_VR_BASE: u32 = 300_000;

/// Each anchor's outputs in a packaged system FMU (on its line): name suffix, unit, description.
pub const ANCHOR_OUTPUTS: [(&str, &str, &str); 2] = [
    ("anchor_force", "N", "the magnitude of its force on its anchor (a fixed point)"),
    ("anchor_uplift_angle", "deg", "its angle above the horizontal at its anchor"),
];

/// Which line and quantity an anchor output's value reference is.
pub fn anchor_output(vr: u32) -> Option<(usize, usize)> {
    item_output(vr, ANCHOR_VR_BASE, u32::MAX, ANCHOR_OUTPUTS.len())
}

/// The values of [`ANCHOR_OUTPUTS`] of a line (model `model`) at its state
/// `state` with outputs `o`: |F| (N) and the uplift angle (deg, §17.1's).
pub fn anchor_values(model: crate::scene::Model, state: &State, o: &Outputs) -> [f64; 2] {
    [o.bottom_force.norm(), crate::sim::system::anchor_uplift_angle(model, &state.config)]
}

/// The values of [`LINE_OUTPUTS`] of a line whose vessel end is `vessel_end`, of its outputs `o`.
pub fn line_values(vessel_end: VesselEnd, o: &Outputs) -> [f64; 4] {
    let (from, to) = match vessel_end {
        VesselEnd::From => (o.top_tension, o.bottom_tension),
        VesselEnd::To => (o.bottom_tension, o.top_tension),
    };
    [from, to, o.min_tension, o.touchdown_s]
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The modelDescription.xml of a system FMU (`riser model-description
/// --scene FILE`, `riser-tools package-fmu --scene`): the generic FMU's
/// variables with the `scene` parameter's start `resource` (the system file
/// in the FMU's resources), and each line's [`LINE_OUTPUTS`] as
/// `LINE.tension_from`, … (no direct feedthrough, initial values of the
/// parameters and inputs, as every output).
pub fn model_description(sys: &SystemScene, resource: &str) -> Result<String, String> {
    let md = super::vars::MODEL_DESCRIPTION;
    let scene_start = r#"<String start="catenary"/>"#;
    let at = md.find(r#"name="scene""#).ok_or("the model description has no scene parameter")?;
    let rel = md[at..].find(scene_start).ok_or("the scene parameter has no start value")?;
    let mut out = String::with_capacity(md.len() + 400 * sys.lines.len());
    out.push_str(&md[..at + rel]);
    out.push_str(&format!(r#"<String start="{}"/>"#, xml_escape(resource)));
    let rest = &md[at + rel + scene_start.len()..];
    let n_vars = md.matches("<ScalarVariable ").count();
    // the initial unknowns' dependencies of an output (top_tension's)
    let top = super::vars::vr_of("top_tension").ok_or("no top_tension")?;
    let top_index = super::vars::VARIABLES.iter().position(|v| v.vr == top).ok_or("no top_tension")? + 1;
    let initial = rest
        .split("<InitialUnknowns>")
        .nth(1)
        .and_then(|s| s.lines().find(|l| l.contains(&format!(r#"index="{top_index}""#))))
        .and_then(|l| l.split("dependencies=\"").nth(1))
        .and_then(|l| l.split('"').next())
        .ok_or("the model description has no initial unknown of top_tension")?
        .to_string();
    let (mut vars, mut outputs, mut unknowns) = (String::new(), String::new(), String::new());
    // each line's outputs, each free point's, each anchor's (names are identifiers: no escaping)
    let mut items = Vec::new();
    for (i, l) in sys.lines.iter().enumerate() {
        for (q, o) in LINE_OUTPUTS.iter().enumerate() {
            items.push((&l.name, "line", SYSTEM_VR_BASE + (LINE_OUTPUTS.len() * i + q) as u32, o));
        }
    }
    let free = sys.points.iter().filter(|p| p.kind == PointKind::Free);
    for (k, p) in free.enumerate() {
        for (c, o) in POINT_OUTPUTS.iter().enumerate() {
            items.push((&p.name, "free point", POINT_VR_BASE + (POINT_OUTPUTS.len() * k + c) as u32, o));
        }
    }
    for (i, l) in sys.lines.iter().enumerate().filter(|(i, _)| sys.ends(*i).2.kind == PointKind::Fixed) {
        for (q, o) in ANCHOR_OUTPUTS.iter().enumerate() {
            items.push((&l.name, "line", ANCHOR_VR_BASE + (ANCHOR_OUTPUTS.len() * i + q) as u32, o));
        }
    }
    for (k, (name, what_item, vr, (suffix, unit, what))) in items.into_iter().enumerate() {
        let index = n_vars + 1 + k;
        vars.push_str(&format!(
            "    <ScalarVariable name=\"{name}.{suffix}\" valueReference=\"{vr}\" description=\"{what_item} {name}: \
             {what}\" causality=\"output\" variability=\"continuous\" initial=\"calculated\">\n      <Real \
             unit=\"{unit}\"/>\n    </ScalarVariable>\n"
        ));
        outputs.push_str(&format!("      <Unknown index=\"{index}\" dependencies=\"\"/>\n"));
        unknowns.push_str(&format!("      <Unknown index=\"{index}\" dependencies=\"{initial}\"/>\n"));
    }
    let insert = |text: &str, before: &str, what: &str| -> Result<String, String> {
        let k = text.find(before).ok_or(format!("the model description has no {before}"))?;
        Ok(format!("{}{what}{}", &text[..k], &text[k..]))
    };
    let rest = insert(rest, "  </ModelVariables>", &vars)?;
    let rest = insert(&rest, "    </Outputs>", &outputs)?;
    let rest = insert(&rest, "    </InitialUnknowns>", &unknowns)?;
    out.push_str(&rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framed_blocks_read_back_and_damage_is_named() {
        let blocks = vec![vec![1u8, 2, 3], vec![], vec![9u8; 40]];
        let bytes = frame(&blocks);
        let back = unframe(&bytes, 3).unwrap();
        assert_eq!(back, blocks.iter().map(|b| b.as_slice()).collect::<Vec<_>>());
        assert!(unframe(&bytes, 2).is_err(), "another number of lines");
        assert!(unframe(&bytes[..bytes.len() - 1], 3).is_err(), "truncated");
        let mut long = bytes.clone();
        long.push(0);
        assert!(unframe(&long, 3).is_err(), "trailing bytes");
        let mut huge = bytes.clone();
        huge[16..24].copy_from_slice(&u64::MAX.to_le_bytes());
        assert!(unframe(&huge, 3).is_err(), "a length beyond the bytes");
    }
}
