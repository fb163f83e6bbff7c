//! The `[vessel]` block of a scene and the vessel's RAO table
//! (docs/theory.md §14.5; docs/guide/waves.md "The vessel on its RAOs").
//!
//! `[vessel] raos = "FILE"`: a CSV of the vessel's displacement RAOs at its
//! reference point, columns `dof,frequency,direction,amplitude,phase`
//! (any order; `#` comments): dof one of surge, sway, heave, roll, pitch,
//! yaw; frequency Hz; direction deg, the waves' direction of travel in the
//! scene frame (from +x towards +y, as `[waves] direction`; the vessel's
//! axes are the scene's at rest); amplitude m/m for the translations and
//! rad/m for the rotations; phase deg, the motion's phase lag behind the
//! wave elevation at the reference point: component i moves degree of
//! freedom d by aᵢ |RAO_d(fᵢ, βᵢ)| cos(θᵢ + phase_d(fᵢ, βᵢ)), θᵢ the
//! component's phase argument of (13.1) at the reference point (the motion
//! peaks phase/ω after the crest passes it: OrcaFlex's displacement-RAO
//! convention). Each degree of freedom present is a full grid of its
//! frequencies × directions; one absent does not move.
//!
//! Interpolation ([`RaoTable::at`]): bilinear in frequency and direction,
//! the amplitude and the phase each (the phase's differences from the
//! nearest grid point's taken the short way round, within ±180°); a direction is taken modulo 360° into the
//! table's span; a frequency or direction outside the table's span is
//! refused (no extrapolation, no end values held).

use super::FieldError;
use serde::{Deserialize, Serialize};

/// A scene's `[vessel]` block.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VesselSpec {
    /// The RAO table (CSV); a relative path in a scene file is taken from
    /// the file's folder, as `waves.file` is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub raos: Option<String>,
}

/// The degrees of freedom in the order of the table's `dof` names: surge,
/// sway, heave (m), roll, pitch, yaw (rad).
pub const DOFS: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

const COLUMNS: [&str; 5] = ["dof", "frequency", "direction", "amplitude", "phase"];

/// One row of a degree of freedom: frequency, direction, amplitude, phase and its line.
type Row = (f64, f64, f64, f64, usize);

/// One degree of freedom's RAOs on its grid.
#[derive(Debug, Clone, PartialEq)]
pub struct RaoGrid {
    /// Hz, ascending.
    pub frequencies: Vec<f64>,
    /// deg, ascending.
    pub directions: Vec<f64>,
    /// |RAO| (m/m or rad/m) and phase (deg), indexed `[frequency][direction]`.
    pub amplitude: Vec<Vec<f64>>,
    pub phase: Vec<Vec<f64>>,
}

/// The vessel's RAOs, each degree of freedom's grid (None: that one does not move).
#[derive(Debug, Clone, PartialEq)]
pub struct RaoTable {
    pub grids: [Option<RaoGrid>; 6],
}

/// The place of `x` in the ascending `v`: (i, w) with x = (1 − w) v[i] + w v[i+1]
/// (w = 0 and i the only index for one value); None outside the span.
fn locate(v: &[f64], x: f64) -> Option<(usize, f64)> {
    let (lo, hi) = (v[0], v[v.len() - 1]);
    let tol = 1e-9 * lo.abs().max(hi.abs()).max(1.0);
    if x < lo - tol || x > hi + tol {
        return None;
    }
    if v.len() == 1 {
        return Some((0, 0.0));
    }
    let i = v.partition_point(|p| *p <= x).clamp(1, v.len() - 1) - 1;
    Some((i, ((x - v[i]) / (v[i + 1] - v[i])).clamp(0.0, 1.0)))
}

/// An angle difference in degrees wrapped into (−180, 180].
fn wrap180(d: f64) -> f64 {
    let r = d.rem_euclid(360.0);
    if r > 180.0 { r - 360.0 } else { r }
}

impl RaoGrid {
    /// A direction (deg) moved by whole turns into the table's span.
    fn direction_in_span(&self, beta: f64) -> f64 {
        let lo = self.directions[0];
        let b = lo + (beta - lo).rem_euclid(360.0);
        // just below a full turn above lo: lo itself
        if (b - lo - 360.0).abs() <= 1e-9 { lo } else { b }
    }

    /// |RAO| and phase (deg) at `frequency` Hz and `direction` deg, or
    /// why not (outside the span).
    pub fn at(&self, frequency: f64, direction: f64) -> Result<(f64, f64), String> {
        let span = |v: &[f64], unit: &str| {
            if v.len() == 1 {
                format!("{} {unit} only", v[0])
            } else {
                format!("{} to {} {unit}", v[0], v[v.len() - 1])
            }
        };
        let (i, u) = locate(&self.frequencies, frequency)
            .ok_or_else(|| format!("frequency {frequency} Hz outside the table's {}", span(&self.frequencies, "Hz")))?;
        let d = self.direction_in_span(direction);
        let (j, w) = locate(&self.directions, d).ok_or_else(|| {
            format!("direction {direction} deg outside the table's {} (modulo 360)", span(&self.directions, "deg"))
        })?;
        let i1 = (i + 1).min(self.frequencies.len() - 1);
        let j1 = (j + 1).min(self.directions.len() - 1);
        let corners = [(i, j, (1.0 - u) * (1.0 - w)), (i1, j, u * (1.0 - w)), (i, j1, (1.0 - u) * w), (i1, j1, u * w)];
        // the phases unwrapped about the nearest grid point's (the heaviest corner)
        let heaviest = corners.iter().fold(corners[0], |b, c| if c.2 > b.2 { *c } else { b });
        let p0 = self.phase[heaviest.0][heaviest.1];
        let (mut a, mut p) = (0.0, 0.0);
        for (fi, di, weight) in corners {
            a += weight * self.amplitude[fi][di];
            p += weight * wrap180(self.phase[fi][di] - p0);
        }
        Ok((a, p0 + p))
    }
}

impl RaoTable {
    /// The RAO of degree of freedom `dof` (0..6, [`DOFS`]) at `frequency`
    /// Hz and `direction` deg: |RAO| and phase (deg); (0, 0) for one the
    /// table does not have.
    pub fn at(&self, dof: usize, frequency: f64, direction: f64) -> Result<(f64, f64), String> {
        match &self.grids[dof] {
            None => Ok((0.0, 0.0)),
            Some(g) => g.at(frequency, direction).map_err(|m| format!("{}: {m}", DOFS[dof])),
        }
    }

    /// The degrees of freedom the table moves, by name.
    pub fn dofs(&self) -> Vec<&'static str> {
        (0..6).filter(|&d| self.grids[d].is_some()).map(|d| DOFS[d]).collect()
    }
}

/// Parses an RAO table (see the module's doc); errors name the line (1-based) and the column.
pub fn parse_raos(text: &str) -> Result<RaoTable, String> {
    let header = "dof,frequency,direction,amplitude,phase: -, Hz, deg, m/m or rad/m, deg";
    let lines = super::waves::named_rows(text, &COLUMNS, "an RAO table", header)?;
    // per dof: (frequency, direction, amplitude, phase, line)
    let mut rows: [Vec<Row>; 6] = Default::default();
    for (n, cells) in lines {
        let name = cells[0];
        let dof = DOFS.iter().position(|d| d.eq_ignore_ascii_case(name)).ok_or_else(|| {
            format!("line {n}, column 'dof': '{name}' is not one of surge, sway, heave, roll, pitch, yaw")
        })?;
        let mut v = [0.0; 4];
        for (k, col) in COLUMNS[1..].iter().enumerate() {
            let cell = cells[k + 1];
            let x: f64 = cell.parse().map_err(|_| format!("line {n}, column '{col}': '{cell}' is not a number"))?;
            if !x.is_finite() {
                return Err(format!("line {n}, column '{col}': {x} is not finite"));
            }
            v[k] = x;
        }
        let [f, d, a, p] = v;
        if f <= 0.0 {
            return Err(format!("line {n}, column 'frequency': {f} Hz must be positive"));
        }
        if a < 0.0 {
            return Err(format!("line {n}, column 'amplitude': {a} must be at least 0 (the phase carries the sign)"));
        }
        if dof >= 3 && a > 1.0 {
            return Err(format!(
                "line {n}, column 'amplitude': {name} {a} rad/m ({:.1} deg per m of wave amplitude) is implausible: \
                 the rotations' amplitudes are in rad/m; a table in deg/m converts by pi/180",
                a.to_degrees()
            ));
        }
        rows[dof].push((f, d, a, p, n));
    }
    if rows.iter().all(Vec::is_empty) {
        return Err("the table has a header but no RAOs".into());
    }
    let mut grids: [Option<RaoGrid>; 6] = Default::default();
    for (dof, r) in rows.iter().enumerate() {
        if r.is_empty() {
            continue;
        }
        let axis = |key: fn(&Row) -> f64| {
            let mut v: Vec<f64> = r.iter().map(key).collect();
            v.sort_by(f64::total_cmp);
            v.dedup();
            v
        };
        let (fs, ds) = (axis(|x| x.0), axis(|x| x.1));
        let mut amplitude = vec![vec![f64::NAN; ds.len()]; fs.len()];
        let mut phase = amplitude.clone();
        for &(f, d, a, p, n) in r {
            let i = fs.iter().position(|x| *x == f).expect("from the list");
            let j = ds.iter().position(|x| *x == d).expect("from the list");
            if !amplitude[i][j].is_nan() {
                return Err(format!("line {n}: {} at {f} Hz, {d} deg given twice", DOFS[dof]));
            }
            (amplitude[i][j], phase[i][j]) = (a, p);
        }
        for (i, row) in amplitude.iter().enumerate() {
            if let Some(j) = row.iter().position(|a| a.is_nan()) {
                return Err(format!(
                    "{} lacks the row at {} Hz, {} deg: each degree of freedom is a full grid of its {} \
                     frequencies and {} directions",
                    DOFS[dof],
                    fs[i],
                    ds[j],
                    fs.len(),
                    ds.len()
                ));
            }
        }
        if ds.len() > 1 && ds[ds.len() - 1] - ds[0] > 360.0 + 1e-9 {
            return Err(format!(
                "{}: the directions span {} to {} deg, more than a full turn",
                DOFS[dof],
                ds[0],
                ds[ds.len() - 1]
            ));
        }
        grids[dof] = Some(RaoGrid { frequencies: fs, directions: ds, amplitude, phase });
    }
    Ok(RaoTable { grids })
}

/// The RAO table of a `[vessel] raos`, read and parsed; the error names
/// `vessel.raos`, the path, the line and the column.
pub fn read_raos(path: &str) -> Result<RaoTable, FieldError> {
    let err = |message: String| FieldError { field: "vessel.raos".into(), message };
    let text = std::fs::read_to_string(path).map_err(|e| err(format!("cannot read '{path}': {e}")))?;
    parse_raos(&text).map_err(|m| err(format!("{path}: {m}")))
}

/// The checks of a `[vessel]` block: the table reads.
pub(super) fn check(s: &super::Scene) -> Vec<FieldError> {
    match s.vessel.as_ref().and_then(|v| v.raos.as_deref()) {
        Some(p) => read_raos(p).err().into_iter().collect(),
        None => Vec::new(),
    }
}

impl super::Scene {
    /// A `vessel.raos` relative to a scene file is taken from the file's folder.
    pub(super) fn resolve_raos_file(&mut self, scene_path: &std::path::Path) {
        let Some(f) = self.vessel.as_mut().and_then(|v| v.raos.as_mut()) else { return };
        let p = std::path::Path::new(f.as_str());
        if p.is_relative()
            && let Some(dir) = scene_path.parent()
        {
            *f = dir.join(p).to_string_lossy().into_owned();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_parses_interpolates_and_refuses_outside_its_span() {
        let t = "# a vessel\ndof,frequency,direction,amplitude,phase\n\
                 heave,0.05,0,1.0,0\nheave,0.15,0,0.5,90\nheave,0.05,90,0.8,170\nheave,0.15,90,0.4,-170\n\
                 pitch,0.1,0,0.02,-30\n";
        let r = parse_raos(t).unwrap();
        assert_eq!(r.dofs(), vec!["heave", "pitch"]);
        assert_eq!(r.at(2, 0.05, 0.0).unwrap(), (1.0, 0.0));
        let (a, p) = r.at(2, 0.1, 0.0).unwrap();
        assert!((a - 0.75).abs() < 1e-14 && (p - 45.0).abs() < 1e-12, "{a} {p}");
        // the phase across ±180 the short way: 170 and −170 → 180 (not 0)
        let (a, p) = r.at(2, 0.1, 90.0).unwrap();
        assert!((a - 0.6).abs() < 1e-15 && (wrap180(p - 180.0)).abs() < 1e-12, "{p}");
        // modulo 360
        assert_eq!(r.at(2, 0.05, 450.0).unwrap(), r.at(2, 0.05, 90.0).unwrap());
        assert!(r.at(2, 0.2, 0.0).unwrap_err().contains("frequency 0.2 Hz outside the table's 0.05 to 0.15 Hz"));
        assert!(r.at(2, 0.1, 100.0).unwrap_err().contains("direction 100 deg"));
        assert!(r.at(4, 0.1, 10.0).unwrap_err().contains("pitch: direction 10 deg outside the table's 0 deg only"));
        assert_eq!(r.at(0, 9.0, 9.0).unwrap(), (0.0, 0.0));
        let e = parse_raos("dof,frequency,direction,amplitude,phase\nheave,0.1,0,1,0\nheave,0.2,10,1,0\n").unwrap_err();
        assert!(e.contains("heave lacks the row"), "{e}");
        let e = parse_raos("dof,frequency,direction,amplitude,phase\nbob,0.1,0,1,0\n").unwrap_err();
        assert!(e.contains("line 2, column 'dof'"), "{e}");
        let e = parse_raos("dof,frequency,direction,amplitude,phase\nroll,0.1,0,5,0\n").unwrap_err();
        assert!(e.contains("rad/m"), "{e}");
    }
}
