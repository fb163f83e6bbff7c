//! A system of lines on one vessel (issue 49, docs/guide/systems.md): the
//! scene format. `[[line_type]]` (`name`, `model` = `rod` | `cable`, and the
//! keys of `[line]` but `length`), `[[point]]` (`name`, `kind` = `fixed` |
//! `vessel` | `free`, `position`; a free point's `mass`, `volume`,
//! `cd_area`, `ca`), `[[line]]` (`name`, `type`, `from`, `to`, `length`,
//! `n_elements`); `[environment]`, `[current]`, `[seabed]`, `[waves]` and
//! `[analysis]` shared. The system's frame has its origin at the vessel
//! reference point's initial position, z up: a fixed point's `position` is
//! global, a vessel point's is in the vessel frame relative to the reference
//! point, a free point's is its initial global position.
//!
//! A system is recognised by its `[[line]]` array (a single-line scene has
//! a `[line]` table and keeps its meaning). Each line is the single-line
//! [`Scene`] it is alone ([`SystemScene::line_scene`]): its frame at its
//! hang-off (its vessel point where it has one, else its free end, the
//! higher of two free ends), its other end the single line's anchor, the
//! water surface, the seabed and the waves' phase origin shifted by the
//! hang-off's global position. A line joins any two points but two fixed or
//! two vessel points.

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
    /// A joint, clump weight or buoy: a point mass in equilibrium under
    /// its lines, its weight and buoyancy and the seabed's contact.
    Free,
}

/// `[[point]]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    pub name: String,
    pub kind: PointKind,
    /// m: global for a fixed point, in the vessel frame for a vessel point,
    /// global and initial (where the statics start) for a free point.
    pub position: [f64; 3],
    /// A free point's mass, kg (default 0).
    #[serde(default)]
    pub mass: Option<f64>,
    /// A free point's displaced volume, m³ (default 0): its buoyancy ρ g V
    /// below the water surface.
    #[serde(default)]
    pub volume: Option<f64>,
    /// A free point's drag area C_d A, m² (default 0; the dynamics').
    #[serde(default)]
    pub cd_area: Option<f64>,
    /// A free point's added-mass coefficient (default 0; the dynamics'): added mass C_a ρ V.
    #[serde(default)]
    pub ca: Option<f64>,
    /// A free point's vertical extent, m (default none: a point, its
    /// buoyancy whole below the still water line and none above): a
    /// vertical cylinder of its `volume` centred on its position, of
    /// waterplane area `volume`/`height`, whose buoyancy, added mass, drag
    /// and waves' inertia go with its draft (a surface buoy; docs/theory.md
    /// §17.10).
    #[serde(default)]
    pub height: Option<f64>,
}

impl PointSpec {
    /// Mass, kg (0 unless a free point gives it).
    pub fn mass(&self) -> f64 {
        self.mass.unwrap_or(0.0)
    }

    /// Displaced volume, m³ (0 unless a free point gives it).
    pub fn volume(&self) -> f64 {
        self.volume.unwrap_or(0.0)
    }

    /// Drag area C_d A, m².
    pub fn cd_area(&self) -> f64 {
        self.cd_area.unwrap_or(0.0)
    }

    /// Added-mass coefficient.
    pub fn ca(&self) -> f64 {
        self.ca.unwrap_or(0.0)
    }

    /// Its buoyancy's shape: a point, or a vertical cylinder of height H
    /// (`height`) and waterplane area V/H.
    pub fn floater(&self) -> Floater {
        Floater { volume: self.volume(), height: self.height }
    }
}

/// A free point's buoyant volume and how it meets the water surface
/// (docs/theory.md §17.10, eqs 17.23–17.25): without a height, the whole
/// volume below the still water line and none above (a step at the
/// surface); with one, a vertical cylinder of height H centred on the
/// point, its waterplane area A = V/H, its draft
/// d(ζ) = clamp(H/2 − ζ, 0, H) for its centre ζ above the surface, its
/// displaced volume A d.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floater {
    /// V, m³.
    pub volume: f64,
    /// H, m (None: a point).
    pub height: Option<f64>,
}

impl Floater {
    /// The submerged fraction s = d/H at a centre ζ m above the surface
    /// (a point: 1 below it, 0 at and above it).
    pub fn submerged(&self, zeta: f64) -> f64 {
        match self.height {
            None => f64::from(u8::from(zeta < 0.0)),
            Some(h) => (0.5 - zeta / h).clamp(0.0, 1.0),
        }
    }

    /// The displaced volume V s (m³) at ζ and its derivative in ζ (m²:
    /// −A where the cylinder is partly submerged, else 0).
    pub fn displaced(&self, zeta: f64) -> (f64, f64) {
        match self.height {
            None => (self.volume * self.submerged(zeta), 0.0),
            Some(h) => {
                let s = self.submerged(zeta);
                let slope = if s > 0.0 && s < 1.0 { -self.volume / h } else { 0.0 };
                (self.volume * s, slope)
            }
        }
    }

    /// Q(ζ) = ∫ displaced dζ, zero clear of the water, m⁴ (17.24): the
    /// buoyancy's potential is −ρ g Q(z − z_s); Q = V ζ fully submerged
    /// (ζ ≤ −H/2), −A d²/2 partly (d the draft), 0 clear of the water; a
    /// point: V min(ζ, 0).
    pub fn potential(&self, zeta: f64) -> f64 {
        match self.height {
            None => self.volume * zeta.min(0.0),
            Some(h) => {
                let a = self.volume / h;
                let d = (0.5 * h - zeta).clamp(0.0, h);
                -0.5 * a * d * d - self.volume * (-zeta - 0.5 * h).max(0.0)
            }
        }
    }

    /// The displaced volume's mean over a step of the centre from ζ₀ to ζ₁
    /// (m³), so that ρ g times it is the discrete gradient of the
    /// buoyancy's potential, ρ g (Q(ζ₁) − Q(ζ₀))/(ζ₁ − ζ₀) (17.25): the
    /// midpoint's where both ends are on one piece of the draft (it is
    /// linear there) or the step is too short for the quotient, else the
    /// quotient; and its derivative in ζ₁ (m²). A cylinder only.
    pub fn mean_displaced(&self, zeta0: f64, zeta1: f64) -> (f64, f64) {
        let h = self.height.unwrap_or(0.0);
        let piece = |z: f64| {
            if z <= -0.5 * h {
                0
            } else if z >= 0.5 * h {
                2
            } else {
                1
            }
        };
        if piece(zeta0) == piece(zeta1) || (zeta1 - zeta0).abs() <= 1e-9 * h {
            let (v, dv) = self.displaced(0.5 * (zeta0 + zeta1));
            return (v, 0.5 * dv);
        }
        let g = (self.potential(zeta1) - self.potential(zeta0)) / (zeta1 - zeta0);
        let (v1, _) = self.displaced(zeta1);
        (g, (v1 - g) / (zeta1 - zeta0))
    }
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

/// Which end of a line is its single-line scene's hang-off
/// ([`SystemScene::ends`]): the vessel point where the line has one (so, on
/// a line between a fixed and a vessel point, the end on the vessel).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VesselEnd {
    /// `from` is the hang-off (the vessel point), `to` the anchor.
    From,
    /// `to` is the hang-off (the vessel point), `from` the anchor.
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

    /// The system with `--set name=value` of its shared numerics
    /// ([`SYSTEM_SET_KEYS`], as a single line's `--set`); a line's or a line
    /// type's key is refused, naming where it is written.
    pub fn with_overrides<S: AsRef<str>>(mut self, sets: &[S]) -> Result<SystemScene, SceneError> {
        super::apply_sets(sets, |name, value| {
            if !SYSTEM_SET_KEYS.contains(&name) {
                return Err(SceneError::Override {
                    name: name.to_string(),
                    message: format!(
                        "not for a system scene: --set takes its shared [analysis] keys ({}); a line's or a line \
                         type's key (n_elements, EA, ...) is written in the system's file",
                        SYSTEM_SET_KEYS.join(", ")
                    ),
                });
            }
            // through a line's scene: the same parsing and ranges as a single line's
            let mut scene = self.line_scene(0, V3::zeros());
            scene.set(name, value)?;
            let (model, n) = (self.analysis.model, self.analysis.n_elements);
            self.analysis = scene.analysis;
            (self.analysis.model, self.analysis.n_elements) = (model, n);
            Ok(())
        })?;
        let errs = self.check();
        if errs.is_empty() { Ok(self) } else { Err(SceneError::Invalid(errs)) }
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

    /// Which end of line `i` is its single-line scene's hang-off, its
    /// hang-off point and its anchor point (a validated system). The hang-off
    /// is the vessel point where the line has one (a line between a fixed
    /// and a vessel point: the vessel point, the fixed point its anchor);
    /// between a fixed and a free point, the free point; between two free
    /// points, the higher at their initial positions (`from` if level).
    pub fn ends(&self, i: usize) -> (VesselEnd, &PointSpec, &PointSpec) {
        let l = &self.lines[i];
        let (a, b) = (self.point(&l.from).expect("validated"), self.point(&l.to).expect("validated"));
        let from_hangs = match (a.kind, b.kind) {
            (PointKind::Vessel, _) => true,
            (_, PointKind::Vessel) => false,
            (PointKind::Free, PointKind::Fixed) => true,
            (PointKind::Fixed, PointKind::Free) => false,
            _ => a.position[2] >= b.position[2],
        };
        if from_hangs { (VesselEnd::From, a, b) } else { (VesselEnd::To, b, a) }
    }

    /// The single-line scene line `i` is with its hang-off at `fairlead`
    /// (global, m) and its anchor where the scene puts it (a fixed point's
    /// position, a free point's initial one): its frame's origin at the
    /// hang-off, the anchor, the water surface, the seabed and the waves'
    /// phase origin shifted by −`fairlead`; the hang-off's `offset` is the
    /// vessel point's vessel-frame position ρ (pinned), zero at a free point.
    pub fn line_scene(&self, i: usize, fairlead: V3) -> Scene {
        let (_, _, fp) = self.ends(i);
        self.line_scene_at(i, fairlead, V3::from(fp.position))
    }

    /// [`SystemScene::line_scene`] with its anchor end at `anchor` (global, m):
    /// a line with a free end, its ends where the system's statics put them.
    pub fn line_scene_at(&self, i: usize, fairlead: V3, anchor: V3) -> Scene {
        let l = &self.lines[i];
        let (_, vp, _) = self.ends(i);
        let t = self.line_type(&l.line_type).expect("validated");
        let mut line = t.line.clone();
        line.length = l.length;
        let a = anchor - fairlead;
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
            hang_off: super::HangOffSpec {
                offset: if vp.kind == PointKind::Vessel { vp.position } else { [0.0; 3] },
                ..Default::default()
            },
            vessel: None,
        }
    }

    /// Every problem, each naming its field: names (identifiers, unique over
    /// lines and points; line types among themselves), references, ends (not
    /// two fixed nor two vessel points a line), points no line uses, a free
    /// point's keys (and theirs refused on other points), a free point with
    /// no path through lines to a fixed or a vessel point, a free point
    /// below the seabed, and each line's own scene at the neutral pose (free
    /// points at their initial positions).
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
            let keys =
                [("mass", p.mass), ("volume", p.volume), ("cd_area", p.cd_area), ("ca", p.ca), ("height", p.height)];
            for (key, v) in keys {
                let Some(v) = v else { continue };
                if p.kind != PointKind::Free {
                    err(
                        format!("point.{}.{key}", p.name),
                        format!(
                            "only a free point has a `{key}`: point '{}' is {} (its lines' ends are held there)",
                            p.name,
                            if p.kind == PointKind::Fixed { "fixed" } else { "on the vessel" }
                        ),
                    );
                } else if !(v.is_finite() && (0.0..=MAX_POINT_VALUE).contains(&v)) {
                    err(
                        format!("point.{}.{key}", p.name),
                        format!("{v} must be finite, within [0, {MAX_POINT_VALUE:e}]"),
                    );
                } else if key == "height" && v == 0.0 {
                    err(
                        format!("point.{}.height", p.name),
                        "must be above 0 m: leave `height` out for a point whose buoyancy is whole below the \
                         surface"
                            .to_string(),
                    );
                }
            }
            let position_ok = p.position.iter().all(|v| v.is_finite() && v.abs() <= super::ranges::MAX_COORDINATE);
            if !position_ok {
                err(
                    format!("point.{}.position", p.name),
                    format!("{:?} must be finite, within ±{} m", p.position, super::ranges::MAX_COORDINATE),
                );
            }
            if p.kind == PointKind::Free && position_ok {
                if let Some(b) = &self.seabed {
                    let bed = b.height_at(p.position[0], p.position[1]);
                    if p.position[2] < bed - 1e-9 * bed.abs().max(1.0) {
                        err(
                            format!("point.{}.position", p.name),
                            format!(
                                "the free point starts below the seabed (z = {} m under it): start it on the seabed \
                                 or above",
                                super::ranges::number(bed)
                            ),
                        );
                    }
                }
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
            if kinds.len() == 2 && kinds[0] == kinds[1] && kinds[0] != PointKind::Free {
                let what = if kinds[0] == PointKind::Fixed { "two fixed points" } else { "two vessel points" };
                err(
                    format!("line.{}", l.name),
                    format!(
                        "joins point '{}' and point '{}', {what}: a line joins a fixed point and a vessel point, \
                         or either to a free point, or two free points",
                        l.from, l.to
                    ),
                );
                line_ok[i] = false;
            }
            if l.from == l.to {
                err(format!("line.{}", l.name), format!("both its ends are point '{}'", l.from));
                line_ok[i] = false;
            }
        }
        // every free point reaches a fixed or a vessel point through lines
        let held = |p: &PointSpec| p.kind != PointKind::Free;
        let mut reached: Vec<bool> = self.points.iter().map(held).collect();
        loop {
            let mut grew = false;
            for l in &self.lines {
                let (Some(a), Some(b)) = (
                    self.points.iter().position(|p| p.name == l.from),
                    self.points.iter().position(|p| p.name == l.to),
                ) else {
                    continue;
                };
                if reached[a] != reached[b] {
                    reached[a] = true;
                    reached[b] = true;
                    grew = true;
                }
            }
            if !grew {
                break;
            }
        }
        for (p, r) in self.points.iter().zip(&reached) {
            let used = self.lines.iter().any(|l| l.from == p.name || l.to == p.name);
            if !r && used {
                err(
                    format!("point.{}", p.name),
                    format!(
                        "free point '{}' has no path through lines to a fixed point or the vessel: nothing holds it",
                        p.name
                    ),
                );
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

/// The largest axial strain a line's ends may demand of it (a single line's
/// anchor distance check), for the statics of free points.
pub const MAX_REACH_STRAIN: f64 = super::validate::MAX_REACH_STRAIN;

/// The largest mass (kg), volume (m³), drag area (m²) or added-mass
/// coefficient a free point may have.
pub const MAX_POINT_VALUE: f64 = 1e9;

/// The keys `--set` takes on a system: its shared numerics (`[analysis]`).
pub const SYSTEM_SET_KEYS: [&str; 7] = [
    "time_step",
    "newton_tolerance",
    "structural_damping",
    "rho_infinity",
    "accuracy",
    "accuracy_quantity",
    "static_current",
];

/// What a command that takes only single-line scenes says of a system.
pub const NOT_YET: &str = "a system of lines ([[line]]): this command takes a single-line scene; `riser statics`, \
                           `riser run`, `riser scene`, `riser modes` and the FMU take a system (docs/guide/systems.md)";
