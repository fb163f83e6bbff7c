//! A system of lines on one vessel (issue 49, docs/guide/systems.md): the
//! scene format. `[[line_type]]` (`name`, `model` = `rod` | `cable`, and the
//! keys of `[line]` but `length`), `[[point]]` (`name`, `kind` = `fixed` |
//! `vessel` | `free`, `position`), `[[line]]` (`name`, `type`, `from`, `to`,
//! `length`, `n_elements`); `[environment]`, `[current]`, `[seabed]`,
//! `[waves]` and `[analysis]` shared. The system's frame has its origin at
//! the vessel reference point's initial position, z up: a fixed point's
//! `position` is global, a vessel point's is in the vessel frame relative to
//! the reference point.
//!
//! A system is recognised by its `[[line]]` array (a single-line scene has
//! a `[line]` table and keeps its meaning). Each line is the single-line
//! [`Scene`] it is alone ([`SystemScene::line_scene`]): its frame at its
//! vessel point, the anchor, the water surface, the seabed and the waves'
//! phase origin shifted by that point's global position. This increment
//! takes lines between a fixed and a vessel point; free points are refused
//! ("not yet").

use super::checker::FieldError;
use super::{Analysis, CurrentSpec, Environment, Line, Model, Scene, SceneError, SeabedSpec, in_users_terms, waves};
use crate::math::V3;
use serde::Deserialize;

/// What a point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PointKind {
    /// An anchor: `position` global.
    Fixed,
    /// A fairlead or hang-off: `position` in the vessel frame from the reference point.
    Vessel,
    /// A joint, clump weight or buoy (not yet: refused).
    Free,
}

/// `[[point]]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    pub name: String,
    pub kind: PointKind,
    /// m: global for a fixed point, in the vessel frame for a vessel point.
    pub position: [f64; 3],
}

/// `[[line]]` of a system.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SystemLine {
    pub name: String,
    /// The `[[line_type]]` it is made of.
    #[serde(rename = "type")]
    pub line_type: String,
    /// The point at its end A (arc length 0 of `from`/`to` rows).
    pub from: String,
    /// The point at its end B.
    pub to: String,
    /// Unstretched length, m.
    pub length: f64,
    pub n_elements: usize,
}

/// `[[line_type]]`: a name, the model and the keys of a single line's `[line]`.
#[derive(Debug, Clone, PartialEq)]
pub struct LineType {
    pub name: String,
    pub model: Model,
    /// The properties (its `length` is each line's).
    pub line: Line,
}

/// A system scene, parsed and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct SystemScene {
    pub name: String,
    pub description: String,
    pub line_types: Vec<LineType>,
    pub points: Vec<PointSpec>,
    pub lines: Vec<SystemLine>,
    /// Shared; `water_surface_z` (global) defaults to 0 here: the reference
    /// point at the still water line.
    pub environment: Environment,
    pub current: CurrentSpec,
    /// Shared; `z` global (the seabed's height under the reference point).
    pub seabed: Option<SeabedSpec>,
    /// Shared; the phase origin global, default the reference point.
    pub waves: Option<waves::WavesSpec>,
    /// Shared numerics (`model` is each line type's, `n_elements` each line's).
    pub analysis: Analysis,
}

/// The file as written, before the line types are read.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    name: String,
    #[serde(default)]
    description: String,
    #[serde(default)]
    line_type: Vec<toml::Table>,
    #[serde(default)]
    point: Vec<PointSpec>,
    line: Vec<SystemLine>,
    #[serde(default)]
    environment: Option<toml::Table>,
    #[serde(default)]
    current: CurrentSpec,
    #[serde(default)]
    seabed: Option<SeabedSpec>,
    #[serde(default)]
    waves: Option<waves::WavesSpec>,
    #[serde(default)]
    analysis: Option<toml::Table>,
}

/// True if `text` is a system scene: TOML whose `line` is an array (`[[line]]`).
pub fn is_system_text(text: &str) -> bool {
    text.parse::<toml::Table>().is_ok_and(|t| matches!(t.get("line"), Some(toml::Value::Array(_))))
}

/// True if `name_or_path` is a file holding a system scene (never a built-in name).
pub fn is_system_source(name_or_path: &str) -> bool {
    if super::BUILTIN.iter().any(|b| b.0 == name_or_path) {
        return false;
    }
    std::fs::read_to_string(name_or_path).is_ok_and(|t| is_system_text(&t))
}

/// True if `s` is an identifier: `[A-Za-z_][A-Za-z0-9_]*`.
pub fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic() || f == '_') && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

fn parse_error(source: &str, message: String) -> SceneError {
    SceneError::Parse { source: source.to_string(), message: in_users_terms(&message) }
}

/// Which end of a line is on the vessel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VesselEnd {
    /// `from` is the vessel point, `to` the fixed one.
    From,
    /// `to` is the vessel point, `from` the fixed one.
    To,
}

impl SystemScene {
    /// Parses and validates system TOML text; `source` names it in messages.
    pub fn from_toml(text: &str, source: &str) -> Result<SystemScene, SceneError> {
        let raw: Raw = toml::from_str(text).map_err(|e| parse_error(source, e.to_string()))?;
        let mut errs = Vec::new();
        let mut line_types = Vec::new();
        for (i, t) in raw.line_type.into_iter().enumerate() {
            let mut t = t;
            let name = match t.remove("name") {
                Some(toml::Value::String(s)) => s,
                Some(_) => return Err(parse_error(source, format!("line_type[{i}].name: expected a text"))),
                None => return Err(parse_error(source, format!("line_type[{i}]: missing field `name`"))),
            };
            let model = match t.remove("model") {
                Some(v) => v
                    .try_into::<Model>()
                    .map_err(|e| parse_error(source, format!("line_type.{name}.model: {e} (\"rod\" or \"cable\")")))?,
                None => {
                    return Err(parse_error(source, format!("line_type.{name}: missing field `model` (rod or cable)")));
                }
            };
            if t.contains_key("length") {
                errs.push(FieldError {
                    field: format!("line_type.{name}.length"),
                    message: "a line type has no length: each [[line]] gives its own `length`".to_string(),
                });
            }
            t.insert("length".to_string(), toml::Value::Float(1.0));
            let line: Line =
                toml::Value::Table(t).try_into().map_err(|e| parse_error(source, format!("line_type.{name}: {e}")))?;
            line_types.push(LineType { name, model, line });
        }
        let mut env = raw.environment.unwrap_or_default();
        env.entry("water_surface_z").or_insert(toml::Value::Float(0.0));
        let environment: Environment =
            toml::Value::Table(env).try_into().map_err(|e| parse_error(source, format!("environment: {e}")))?;
        let analysis_table = raw.analysis.unwrap_or_default();
        for (key, whose) in [("model", "each [[line_type]]'s `model`"), ("n_elements", "each [[line]]'s `n_elements`")]
        {
            if analysis_table.contains_key(key) {
                errs.push(FieldError {
                    field: format!("analysis.{key}"),
                    message: format!("not in a system's [analysis]: it is {whose}"),
                });
            }
        }
        let analysis: Analysis =
            toml::Value::Table(analysis_table).try_into().map_err(|e| parse_error(source, format!("analysis: {e}")))?;
        let sys = SystemScene {
            name: raw.name,
            description: raw.description,
            line_types,
            points: raw.point,
            lines: raw.line,
            environment,
            current: raw.current,
            seabed: raw.seabed,
            waves: raw.waves,
            analysis,
        };
        errs.extend(sys.check());
        if errs.is_empty() { Ok(sys) } else { Err(SceneError::Invalid(errs)) }
    }

    /// A system scene file.
    pub fn load(path: &str) -> Result<SystemScene, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SceneError::NotFound { name: path.to_string(), reason: e.to_string() })?;
        SystemScene::from_toml(&text, path)
    }

    /// The point named `name`.
    pub fn point(&self, name: &str) -> Option<&PointSpec> {
        self.points.iter().find(|p| p.name == name)
    }

    /// The line type named `name`.
    pub fn line_type(&self, name: &str) -> Option<&LineType> {
        self.line_types.iter().find(|t| t.name == name)
    }

    /// Which end of line `i` is on the vessel, its vessel point and its fixed point
    /// (a validated system: one of each).
    pub fn ends(&self, i: usize) -> (VesselEnd, &PointSpec, &PointSpec) {
        let l = &self.lines[i];
        let (a, b) = (self.point(&l.from).expect("validated"), self.point(&l.to).expect("validated"));
        if a.kind == PointKind::Vessel { (VesselEnd::From, a, b) } else { (VesselEnd::To, b, a) }
    }

    /// The single-line scene line `i` is with its vessel point at `fairlead`
    /// (global, m): its frame's origin there (the hang-off), the anchor, the
    /// water surface, the seabed and the waves' phase origin shifted by
    /// −`fairlead`; the hang-off's `offset` is the point's vessel-frame
    /// position ρ (pinned).
    pub fn line_scene(&self, i: usize, fairlead: V3) -> Scene {
        let l = &self.lines[i];
        let (_, vp, fp) = self.ends(i);
        let t = self.line_type(&l.line_type).expect("validated");
        let mut line = t.line.clone();
        line.length = l.length;
        let a = V3::from(fp.position) - fairlead;
        let mut environment = self.environment.clone();
        environment.water_surface_z -= fairlead.z;
        let seabed = self.seabed.as_ref().map(|b| {
            let mut b = b.clone();
            b.z = b.height_at(fairlead.x, fairlead.y) - fairlead.z;
            b
        });
        let waves = self.waves.as_ref().map(|w| {
            let mut w = w.clone();
            let [x0, y0] = w.origin.unwrap_or([0.0, 0.0]);
            w.origin = Some([x0 - fairlead.x, y0 - fairlead.y]);
            w
        });
        let mut analysis = self.analysis.clone();
        analysis.model = t.model;
        analysis.n_elements = l.n_elements;
        Scene {
            name: l.name.clone(),
            description: format!("line {} of system {} ({} to {})", l.name, self.name, l.from, l.to),
            line,
            anchor: super::Anchor { x: a.x, y: a.y, z: a.z },
            environment,
            current: self.current.clone(),
            buoyancy: Vec::new(),
            section: Vec::new(),
            seabed,
            waves,
            analysis,
            hang_off: super::HangOffSpec { offset: vp.position, ..Default::default() },
            vessel: None,
        }
    }

    /// Every problem, each naming its field: names (identifiers, unique over
    /// lines and points; line types among themselves), references, ends (one
    /// fixed and one vessel point a line), points no line uses, free points
    /// (not yet), and each line's own scene at the neutral pose.
    fn check(&self) -> Vec<FieldError> {
        let mut errs = Vec::new();
        let mut err = |field: String, message: String| errs.push(FieldError { field, message });
        if self.lines.is_empty() {
            err("line".into(), "a system needs at least one [[line]]".into());
        }
        let mut seen: Vec<(&str, &str)> = Vec::new();
        let items = self
            .points
            .iter()
            .map(|p| ("point", p.name.as_str()))
            .chain(self.lines.iter().map(|l| ("line", l.name.as_str())));
        for (what, name) in items.chain(self.line_types.iter().map(|t| ("line_type", t.name.as_str()))) {
            if !is_identifier(name) {
                err(
                    format!("{what}.{name}"),
                    format!("'{name}' is not an identifier: letters, digits and _, not starting with a digit"),
                );
            }
            let clash = |(w, n): &&(&str, &str)| *n == name && ((*w == "line_type") == (what == "line_type"));
            if let Some((w, _)) = seen.iter().find(clash) {
                let scope = if what == "line_type" { "line types" } else { "lines and points" };
                err(
                    format!("{what}.{name}"),
                    format!("the name is already that of a {w}: names are unique over {scope}"),
                );
            }
            seen.push((what, name));
        }
        for p in &self.points {
            if p.kind == PointKind::Free {
                err(
                    format!("point.{}.kind", p.name),
                    format!(
                        "point '{}' is free (a joint, clump weight or buoy): not yet supported; this version solves \
                         systems whose lines each join a fixed point and a vessel point",
                        p.name
                    ),
                );
            }
            if !p.position.iter().all(|v| v.is_finite() && v.abs() <= super::ranges::MAX_COORDINATE) {
                err(
                    format!("point.{}.position", p.name),
                    format!("{:?} must be finite, within ±{} m", p.position, super::ranges::MAX_COORDINATE),
                );
            }
            if !self.lines.iter().any(|l| l.from == p.name || l.to == p.name) {
                err(format!("point.{}", p.name), "no line uses this point".into());
            }
        }
        let mut line_ok = vec![true; self.lines.len()];
        for (i, l) in self.lines.iter().enumerate() {
            if self.line_type(&l.line_type).is_none() {
                let known: Vec<&str> = self.line_types.iter().map(|t| t.name.as_str()).collect();
                err(
                    format!("line.{}.type", l.name),
                    format!("no [[line_type]] named '{}' (there are: {})", l.line_type, known.join(", ")),
                );
                line_ok[i] = false;
            }
            let mut kinds = Vec::new();
            for (end, p) in [("from", &l.from), ("to", &l.to)] {
                match self.point(p) {
                    None => {
                        err(format!("line.{}.{end}", l.name), format!("no [[point]] named '{p}'"));
                        line_ok[i] = false;
                    }
                    Some(pt) => kinds.push(pt.kind),
                }
            }
            if kinds.len() == 2 {
                let mut k = kinds.clone();
                k.sort_by_key(|k| *k as u8);
                if k != [PointKind::Fixed, PointKind::Vessel] && !kinds.contains(&PointKind::Free) {
                    err(
                        format!("line.{}", l.name),
                        format!(
                            "joins point '{}' ({:?}) and point '{}' ({:?}): a line joins a fixed point and a vessel \
                             point in this version",
                            l.from, kinds[0], l.to, kinds[1]
                        ),
                    );
                }
                if k != [PointKind::Fixed, PointKind::Vessel] {
                    line_ok[i] = false;
                }
            }
        }
        if !errs.is_empty() {
            return errs;
        }
        // each line's own scene at the neutral pose, its fields named as the system's
        let mut shared = std::collections::BTreeSet::new();
        for (i, l) in self.lines.iter().enumerate().filter(|(i, _)| line_ok[*i]) {
            let (_, vp, fp) = self.ends(i);
            let scene = self.line_scene(i, V3::from(vp.position));
            let Err(SceneError::Invalid(es)) = scene.validate() else { continue };
            for e in es {
                let f = e.field.as_str();
                let (field, message) = if f == "line.length" || f == "analysis.n_elements" {
                    (format!("line.{}.{}", l.name, f.rsplit('.').next().unwrap_or(f)), e.message)
                } else if let Some(k) = f.strip_prefix("line.") {
                    (format!("line_type.{}.{k}", l.line_type), e.message)
                } else if f.starts_with("anchor") {
                    (
                        format!("line.{}", l.name),
                        format!("from point '{}' to point '{}': {}", vp.name, fp.name, e.message),
                    )
                } else if f.starts_with("hang_off.offset") {
                    (format!("point.{}.position", vp.name), e.message)
                } else if f == "seabed.z" && e.message.contains("anchor") {
                    (
                        format!("point.{}.position", fp.name),
                        format!("in line {}'s frame at point '{}': {}", l.name, vp.name, e.message),
                    )
                } else {
                    (e.field.clone(), e.message)
                };
                if shared.insert((field.clone(), message.clone())) {
                    errs.push(FieldError { field, message });
                }
            }
        }
        errs
    }
}

/// What a command that takes only single-line scenes says of a system.
pub const NOT_YET: &str = "a system of lines ([[line]]): this command takes a single-line scene; `riser statics`, \
                           `riser run`, `riser scene`, `riser modes` and the FMU take a system (docs/guide/systems.md)";
