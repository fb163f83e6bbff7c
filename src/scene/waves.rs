//! The `[waves]` block of a scene (the README's `[waves]` keys under "Scenes"; docs/theory.md
//! §13): what a user writes, its checks with the field's name in every
//! message, the FMU / `--set` parameters `wave_*` and `water_depth`, and the
//! components table (CSV) of `kind = "table"`.
//!
//! The sea itself (dispersion, spectra, kinematics) is built from this in
//! `loads::waves`.

use super::checker::Checker;
use super::{FieldError, NO_SEABED_Z, Scene, SeabedSpec, ranges};
use serde::{Deserialize, Serialize};

/// Which sea.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WaveKind {
    /// Still water (the FMU's default `wave_kind`).
    None,
    /// One regular linear wave: `height`, `period`, `direction`, `phase`.
    Airy,
    /// A JONSWAP spectrum: `hs`, `tp`, `gamma`.
    Jonswap,
    /// A Pierson–Moskowitz spectrum: `hs`, `tp`.
    PiersonMoskowitz,
    /// Components read from the CSV `file`.
    Table,
}

impl WaveKind {
    pub fn name(self) -> &'static str {
        match self {
            WaveKind::None => "none",
            WaveKind::Airy => "airy",
            WaveKind::Jonswap => "jonswap",
            WaveKind::PiersonMoskowitz => "pierson_moskowitz",
            WaveKind::Table => "table",
        }
    }

    pub fn parse(text: &str) -> Option<Self> {
        [WaveKind::None, WaveKind::Airy, WaveKind::Jonswap, WaveKind::PiersonMoskowitz, WaveKind::Table]
            .into_iter()
            .find(|k| k.name() == text)
    }

    fn is_spectrum(self) -> bool {
        matches!(self, WaveKind::Jonswap | WaveKind::PiersonMoskowitz)
    }
}

/// The kinematics above the mean water level (docs/theory.md §13.2).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StretchingSpec {
    #[default]
    Wheeler,
    Vertical,
    None,
}

impl StretchingSpec {
    pub fn name(self) -> &'static str {
        match self {
            StretchingSpec::Wheeler => "wheeler",
            StretchingSpec::Vertical => "vertical",
            StretchingSpec::None => "none",
        }
    }

    pub fn parse(text: &str) -> Option<Self> {
        [StretchingSpec::Wheeler, StretchingSpec::Vertical, StretchingSpec::None].into_iter().find(|k| k.name() == text)
    }
}

/// How a spectrum's band is cut into components (docs/theory.md §13.3):
/// equal bins in frequency (13.11), or bins of equal shares of energy and
/// width with a random frequency in each (13.11a-b), a record that does not
/// repeat itself.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpacingSpec {
    #[default]
    Frequency,
    Energy,
}

impl SpacingSpec {
    pub fn name(self) -> &'static str {
        match self {
            SpacingSpec::Frequency => "frequency",
            SpacingSpec::Energy => "energy",
        }
    }

    pub fn parse(text: &str) -> Option<Self> {
        [SpacingSpec::Frequency, SpacingSpec::Energy].into_iter().find(|k| k.name() == text)
    }
}

/// A scene's `[waves]` block; absent keys take the defaults below.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WavesSpec {
    pub kind: WaveKind,
    /// Crest to trough, m (airy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// s (airy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// Direction of travel, deg from +x towards +y (airy and spectra; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<f64>,
    /// Phase φ of (13.1), deg (airy; default 0: a crest at the phase origin at t = 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<f64>,
    /// Significant wave height, m (spectra).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hs: Option<f64>,
    /// Peak period, s (spectra).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tp: Option<f64>,
    /// JONSWAP's peak enhancement (default from Tp/√Hs: [`default_gamma`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Number of components (spectra; default [`DEFAULT_COMPONENTS`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub components: Option<usize>,
    /// Frequency range of the components, Hz (default [`F_MIN_TIMES_TP`]/Tp
    /// to [`F_MAX_TIMES_TP`]/Tp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f_min: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f_max: Option<f64>,
    /// Seed of the phases (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Rayleigh-distributed amplitudes (default false: deterministic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub random_amplitudes: Option<bool>,
    /// How the band is cut into components (default `frequency`: equal bins).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<SpacingSpec>,
    /// The components' CSV (table): header `frequency,amplitude,phase,direction`
    /// (Hz, m, deg, deg). A relative path in a scene file is taken from the
    /// file's folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Default wheeler.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stretching: Option<StretchingSpec>,
    /// The time the waves grow over from still water, s (default one period,
    /// or Tp, or the period of the table's largest component).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp: Option<f64>,
    /// Water depth of the dispersion relation, m (default: the seabed's under
    /// the phase origin, else deep water). It never creates a seabed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<f64>,
    /// The phase origin (x₀, y₀), m (default (0, 0): the hang-off's mean position).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f64; 2]>,
}

/// The default number of components of a spectrum.
pub const DEFAULT_COMPONENTS: usize = 100;
/// The default frequency range of a spectrum's components, in units of the
/// peak frequency 1/Tp: [0.5, 4] holds all but 0.3 to 0.5 % of m₀ (Hs 0.16
/// to 0.25 % low) for γ from 1 to 5 (docs/theory.md §13.3).
pub const F_MIN_TIMES_TP: f64 = 0.5;
pub const F_MAX_TIMES_TP: f64 = 4.0;
/// The steepest sea a spectrum may describe: 2π Hs/(g Tp²) ≤ 1/15.
pub const MAX_SPECTRAL_STEEPNESS: f64 = 1.0 / 15.0;
/// The FMU's start values of the wave parameters (modelDescription/variables.csv),
/// which a scene without the key reads back.
pub const START_PERIOD: f64 = 10.0;
pub const START_GAMMA: f64 = 3.3;

/// JONSWAP's peak enhancement from Tp/√Hs (DNV-RP-C205): 5 below 3.6,
/// exp(5.75 − 1.15 Tp/√Hs) up to 5, 1 above (Tp in s, Hs in m).
pub fn default_gamma(hs: f64, tp: f64) -> f64 {
    let r = tp / hs.sqrt();
    if r <= 3.6 {
        5.0
    } else if r >= 5.0 {
        1.0
    } else {
        (5.75 - 1.15 * r).exp()
    }
}

impl WavesSpec {
    /// A block of kind `none` with no keys (what a `wave_*` parameter on a
    /// scene without waves starts from).
    pub fn none() -> Self {
        WavesSpec {
            kind: WaveKind::None,
            height: None,
            period: None,
            direction: None,
            phase: None,
            hs: None,
            tp: None,
            gamma: None,
            components: None,
            f_min: None,
            f_max: None,
            seed: None,
            random_amplitudes: None,
            spacing: None,
            file: None,
            stretching: None,
            ramp: None,
            depth: None,
            origin: None,
        }
    }

    /// γ as given, else [`default_gamma`].
    pub fn gamma_or_default(&self) -> f64 {
        self.gamma.unwrap_or_else(|| match (self.hs, self.tp) {
            (Some(h), Some(t)) if h > 0.0 => default_gamma(h, t),
            _ => 1.0,
        })
    }

    pub fn components_or_default(&self) -> usize {
        self.components.unwrap_or(DEFAULT_COMPONENTS)
    }

    /// [f_min, f_max] of a spectrum's components, Hz.
    pub fn frequency_range(&self) -> (f64, f64) {
        let fp = 1.0 / self.tp.unwrap_or(START_PERIOD);
        (self.f_min.unwrap_or(F_MIN_TIMES_TP * fp), self.f_max.unwrap_or(F_MAX_TIMES_TP * fp))
    }

    /// The keys given, by their scene names.
    fn given(&self) -> Vec<&'static str> {
        let keys: [(&str, bool); 18] = [
            ("height", self.height.is_some()),
            ("period", self.period.is_some()),
            ("direction", self.direction.is_some()),
            ("phase", self.phase.is_some()),
            ("hs", self.hs.is_some()),
            ("tp", self.tp.is_some()),
            ("gamma", self.gamma.is_some()),
            ("components", self.components.is_some()),
            ("f_min", self.f_min.is_some()),
            ("f_max", self.f_max.is_some()),
            ("seed", self.seed.is_some()),
            ("random_amplitudes", self.random_amplitudes.is_some()),
            ("spacing", self.spacing.is_some()),
            ("file", self.file.is_some()),
            ("stretching", self.stretching.is_some()),
            ("ramp", self.ramp.is_some()),
            ("depth", self.depth.is_some()),
            ("origin", self.origin.is_some()),
        ];
        keys.iter().filter(|k| k.1).map(|k| k.0).collect()
    }

    /// The keys `kind` takes besides the common ones (stretching, ramp,
    /// depth, origin), and which of them it needs.
    fn keys_of(kind: WaveKind) -> (&'static [&'static str], &'static [&'static str]) {
        match kind {
            WaveKind::None => (&[], &[]),
            WaveKind::Airy => (&["height", "period", "direction", "phase"], &["height", "period"]),
            WaveKind::Jonswap => (
                &[
                    "hs",
                    "tp",
                    "gamma",
                    "components",
                    "f_min",
                    "f_max",
                    "seed",
                    "random_amplitudes",
                    "spacing",
                    "direction",
                ],
                &["hs", "tp"],
            ),
            WaveKind::PiersonMoskowitz => (
                &["hs", "tp", "components", "f_min", "f_max", "seed", "random_amplitudes", "spacing", "direction"],
                &["hs", "tp"],
            ),
            WaveKind::Table => (&["file"], &["file"]),
        }
    }
}

const COMMON_KEYS: [&str; 4] = ["stretching", "ramp", "depth", "origin"];

/// The scene's seabed unless it is the placeholder the `seabed_*`
/// parameters create on a scene without one (below every line).
fn real_seabed(scene: &Scene) -> Option<&SeabedSpec> {
    scene.seabed.as_ref().filter(|b| b.z > NO_SEABED_Z)
}

/// The water depth of the dispersion relation, m: `waves.depth` when given
/// (and not 0), else the seabed's depth below the mean water level under
/// the phase origin, else deep water (None).
pub fn wave_depth(scene: &Scene) -> Option<f64> {
    let w = scene.waves.as_ref();
    if let Some(d) = w.and_then(|w| w.depth).filter(|d| *d > 0.0) {
        return Some(d);
    }
    let [x0, y0] = w.and_then(|w| w.origin).unwrap_or([0.0, 0.0]);
    real_seabed(scene).map(|b| scene.environment.water_surface_z - b.height_at(x0, y0))
}

/// One row of a components table: Hz, m, deg, deg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableRow {
    pub frequency: f64,
    pub amplitude: f64,
    pub phase: f64,
    pub direction: f64,
}

const TABLE_COLUMNS: [&str; 4] = ["frequency", "amplitude", "phase", "direction"];

/// Parses a components table: `#` comments and blank lines skipped, then
/// the header (the four columns, in any order), then one component per
/// line. Errors name the line (1-based) and the column.
pub fn parse_table(text: &str) -> Result<Vec<TableRow>, String> {
    let header = "frequency,amplitude,phase,direction: Hz, m, deg, deg";
    let lines = named_rows(text, &TABLE_COLUMNS, "a components table", header)?;
    let mut rows = Vec::new();
    for (n, cells) in lines {
        let mut v = [0.0; 4];
        for (k, name) in TABLE_COLUMNS.iter().enumerate() {
            let cell = cells[k];
            let x: f64 = cell.parse().map_err(|_| format!("line {n}, column '{name}': '{cell}' is not a number"))?;
            let r = ranges::of_field(&format!("waves.table.{name}")).expect("the table's columns have ranges");
            r.check(x).map_err(|m| format!("line {n}, column '{name}': {m}"))?;
            v[k] = x;
        }
        rows.push(TableRow { frequency: v[0], amplitude: v[1], phase: v[2], direction: v[3] });
    }
    if rows.is_empty() {
        return Err("the table has a header but no components".into());
    }
    Ok(rows)
}

/// The data rows of a CSV table with a named header (a components table,
/// an RAO table): `#` comments and blank lines skipped, then the header
/// (`names`, in any order, any case), then rows of as many cells; each row
/// with its line number (1-based) and its cells in `names`' order. Errors
/// name the line and the column; `what` names the table, `header` its
/// columns with their units.
pub(crate) fn named_rows<'a, const N: usize>(
    text: &'a str,
    names: &[&str; N],
    what: &str,
    header: &str,
) -> Result<Vec<(usize, [&'a str; N])>, String> {
    let mut columns: Option<[usize; N]> = None;
    let mut width = 0;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let Some(cols) = columns else {
            let mut cols = [usize::MAX; N];
            for (j, cell) in cells.iter().enumerate() {
                match names.iter().position(|c| c.eq_ignore_ascii_case(cell)) {
                    Some(k) if cols[k] == usize::MAX => cols[k] = j,
                    Some(_) => return Err(format!("line {n}: column '{cell}' appears twice in the header")),
                    None => {
                        return Err(format!("line {n}: '{cell}' is not a column of {what} (the header is {header})"));
                    }
                }
            }
            if let Some(k) = cols.iter().position(|c| *c == usize::MAX) {
                return Err(format!("line {n}: the header lacks the column '{}' (expected {header})", names[k]));
            }
            columns = Some(cols);
            width = cells.len();
            continue;
        };
        if cells.len() != width {
            return Err(format!("line {n}: {} values, but the header has {width} columns ({header})", cells.len()));
        }
        rows.push((n, cols.map(|c| cells[c])));
    }
    if columns.is_none() {
        return Err(format!("no header: expected the line {header}"));
    }
    Ok(rows)
}

/// The components table of a `table` block, read and parsed; the error
/// names `waves.file`, the path, the line and the column.
pub fn read_table(w: &WavesSpec) -> Result<Vec<TableRow>, FieldError> {
    let err = |message: String| FieldError { field: "waves.file".into(), message };
    let path = w.file.as_deref().ok_or_else(|| err("missing: kind = 'table' reads its components from it".into()))?;
    let text = std::fs::read_to_string(path).map_err(|e| err(format!("cannot read '{path}': {e}")))?;
    parse_table(&text).map_err(|m| err(format!("{path}: {m}")))
}

/// The checks of a `[waves]` block (scene/validate.rs adds them to its list).
pub(super) fn check(s: &Scene) -> Vec<FieldError> {
    let mut c = Checker(Vec::new());
    check_into(&mut c, s);
    c.0
}

fn check_into(c: &mut Checker, s: &Scene) {
    let Some(w) = &s.waves else { return };
    let numbers = [
        ("height", w.height),
        ("period", w.period),
        ("direction", w.direction),
        ("phase", w.phase),
        ("hs", w.hs),
        ("tp", w.tp),
        ("gamma", w.gamma),
        ("components", w.components.map(|n| n as f64)),
        ("f_min", w.f_min),
        ("f_max", w.f_max),
        ("seed", w.seed.map(|n| n as f64)),
        ("ramp", w.ramp),
        ("depth", w.depth),
    ];
    let mut ok = c.optional(&numbers, |k| format!("waves.{k}"), |k| format!("waves.{k}"));
    if let Some([x, y]) = w.origin {
        ok &= c.range_as("waves.origin", "waves.origin", x) & c.range_as("waves.origin", "waves.origin", y);
    }
    if w.kind == WaveKind::None {
        return;
    }
    let (_, needed) = WavesSpec::keys_of(w.kind);
    let given = w.given();
    for key in needed {
        if !given.contains(key) {
            let what = match *key {
                "height" => "the wave height crest to trough (m)",
                "period" => "the wave period (s)",
                "hs" => "the significant wave height (m)",
                "tp" => "the peak period (s)",
                _ => "the components' CSV file (frequency,amplitude,phase,direction)",
            };
            c.err(&format!("waves.{key}"), format!("missing: kind = '{}' needs {what}", w.kind.name()));
            ok = false;
        }
    }
    if !ok {
        return;
    }
    let g = s.environment.gravity;
    if w.kind.is_spectrum() {
        let (hs, tp) = (w.hs.unwrap_or(0.0), w.tp.unwrap_or(1.0));
        let steepness = 2.0 * std::f64::consts::PI * hs / (g * tp * tp);
        if steepness > MAX_SPECTRAL_STEEPNESS {
            let shortest = (2.0 * std::f64::consts::PI * hs / (g * MAX_SPECTRAL_STEEPNESS)).sqrt();
            c.err(
                "waves.tp",
                format!(
                    "Tp = {tp} s is too short for Hs = {hs} m: the spectral steepness 2 pi Hs/(g Tp^2) = {steepness:.4} \
                     exceeds 1/15, the steepest seas there are (they break; DNV-RP-C205's limit); the spectrum's \
                     formula needs Tp >= {shortest:.3} s"
                ),
            );
        }
        let (f_min, f_max) = w.frequency_range();
        let fp = 1.0 / tp;
        if f_min >= f_max {
            c.err("waves.f_max", format!("{f_max} Hz must be greater than f_min = {f_min} Hz"));
        } else if fp < f_min || fp > f_max {
            c.err(
                "waves.tp",
                format!(
                    "the peak frequency 1/Tp = {} Hz lies outside the components' range [f_min, f_max] = [{}, {}] Hz: \
                     the realisation would miss the peak",
                    ranges::number(fp),
                    ranges::number(f_min),
                    ranges::number(f_max)
                ),
            );
        }
    }
    if w.kind == WaveKind::Table
        && let Err(e) = read_table(w)
    {
        c.0.push(e);
    }
    check_depth(c, s, w);
}

/// `waves.depth` against the seabed and the anchor; the trough of a regular
/// wave above the seabed.
fn check_depth(c: &mut Checker, s: &Scene, w: &WavesSpec) {
    let surface = s.environment.water_surface_z;
    let [x0, y0] = w.origin.unwrap_or([0.0, 0.0]);
    let a = &s.anchor;
    if let Some(d) = w.depth.filter(|d| *d > 0.0) {
        match real_seabed(s) {
            Some(b) => {
                let under = [(x0, y0), (0.0, 0.0), (a.x, a.y)].map(|(x, y)| surface - b.height_at(x, y));
                let lo = under.iter().cloned().fold(f64::INFINITY, f64::min);
                let hi = under.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                let tol = 1e-3 * hi.abs().max(1.0);
                if d < lo - tol || d > hi + tol {
                    let span = if hi - lo <= tol {
                        format!("{} m below the mean water level", ranges::number(under[0]))
                    } else {
                        format!(
                            "from {} to {} m below the mean water level under the phase origin, the hang-off and the \
                             anchor",
                            ranges::number(lo),
                            ranges::number(hi)
                        )
                    };
                    c.err(
                        "waves.depth",
                        format!(
                            "{} m contradicts the seabed, which is {span} (seabed.z = {}, water_surface_z = {}): \
                             leave depth out to take the seabed's",
                            ranges::number(d),
                            ranges::number(b.z),
                            ranges::number(surface)
                        ),
                    );
                }
            }
            None => {
                let anchor_depth = surface - a.z;
                if d < anchor_depth - 1e-3 * anchor_depth.abs().max(1.0) {
                    c.err(
                        "waves.depth",
                        format!(
                            "{} m is shallower than the anchor, {} m below the mean water level: the line would reach \
                             below the sea floor the waves feel",
                            ranges::number(d),
                            ranges::number(anchor_depth)
                        ),
                    );
                }
            }
        }
    }
    let depth = wave_depth(s);
    if let Some(d) = depth
        && d <= 0.0
    {
        c.err(
            "seabed.z",
            format!(
                "the seabed is {} m above the mean water level under the phase origin: waves need water",
                ranges::number(-d)
            ),
        );
        return;
    }
    if let (WaveKind::Airy, Some(h), Some(d)) = (w.kind, w.height, depth)
        && 0.5 * h >= d
    {
        c.err(
            "waves.height",
            format!("{h} m: its trough, {} m deep, would reach the seabed {} m down", 0.5 * h, ranges::number(d)),
        );
    }
}

impl Scene {
    /// Keys of the `[waves]` block that do nothing: all of them when the
    /// kind is `none`, those of another kind otherwise.
    pub fn wave_warnings(&self) -> Vec<String> {
        let Some(w) = &self.waves else { return Vec::new() };
        let given = w.given();
        let (takes, _) = WavesSpec::keys_of(w.kind);
        let ignored: Vec<&str> = given
            .iter()
            .copied()
            .filter(|k| !takes.contains(k) && (w.kind == WaveKind::None || !COMMON_KEYS.contains(k)))
            .collect();
        if ignored.is_empty() {
            return Vec::new();
        }
        let list = ignored.iter().map(|k| format!("waves.{k}")).collect::<Vec<_>>().join(", ");
        vec![if w.kind == WaveKind::None {
            format!("{list} given, but the waves' kind is none: still water (set wave_kind or waves.kind)")
        } else {
            format!(
                "{list} ignored: kind = '{}' does not take {}",
                w.kind.name(),
                if ignored.len() > 1 { "them" } else { "it" }
            )
        }]
    }

    /// A `waves.file` relative to a scene file is taken from the file's folder.
    pub(super) fn resolve_wave_file(&mut self, scene_path: &std::path::Path) {
        let Some(w) = self.waves.as_mut() else { return };
        let Some(f) = w.file.as_ref() else { return };
        let p = std::path::Path::new(f);
        if p.is_relative()
            && let Some(dir) = scene_path.parent()
        {
            w.file = Some(dir.join(p).to_string_lossy().into_owned());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_parses_and_its_errors_name_the_line_and_the_column() {
        let t = "# from the vessel model\nfrequency, amplitude, phase, direction\n0.1, 1.5, 30, 0\n\n0.12,0.5,-40,15\n";
        let rows = parse_table(t).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[1], TableRow { frequency: 0.12, amplitude: 0.5, phase: -40.0, direction: 15.0 });
        // any column order
        let rows = parse_table("direction,phase,amplitude,frequency\n10,20,1,0.2\n").unwrap();
        assert_eq!(rows[0], TableRow { frequency: 0.2, amplitude: 1.0, phase: 20.0, direction: 10.0 });
        let e = parse_table("frequency,amplitude,phase,direction\n0.1,1,0,0\n0.2,abc,0,0\n").unwrap_err();
        assert!(e.contains("line 3") && e.contains("'amplitude'") && e.contains("'abc'"), "{e}");
        let e = parse_table("frequency,amplitude,phase\n0.1,1,0\n").unwrap_err();
        assert!(e.contains("line 1") && e.contains("'direction'"), "{e}");
        let e = parse_table("frequency,amplitude,phase,direction\n0.1,1,0\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("3 values"), "{e}");
        let e = parse_table("frequency,amplitude,phase,direction\n0.1,-1,0,0\n").unwrap_err();
        assert!(e.contains("line 2, column 'amplitude'") && e.contains("is outside"), "{e}");
        assert!(parse_table("frequency,amplitude,phase,direction\n").unwrap_err().contains("no components"));
        assert!(parse_table("").unwrap_err().contains("no header"));
    }

    #[test]
    fn the_default_gamma_follows_dnv() {
        assert_eq!(default_gamma(16.0, 12.0), 5.0); // Tp/√Hs = 3
        assert_eq!(default_gamma(4.0, 12.0), 1.0); // 6
        assert!((default_gamma(4.0, 8.6) - (5.75f64 - 1.15 * 4.3).exp()).abs() < 1e-15);
    }
}
