//! Range checks of every scene value, with the field and the allowed range in
//! each message.

use super::{Model, ProfileKind, Scene};

/// One bad value.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Dotted path in the scene file, e.g. `line.length`.
    pub field: String,
    pub message: String,
}

impl std::fmt::Display for FieldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

/// Largest axial strain the anchor distance may demand of the line.
pub const MAX_REACH_STRAIN: f64 = 0.05;
/// Largest number of elements.
pub const MAX_ELEMENTS: usize = 5000;
/// Largest current speed accepted, m/s.
pub const MAX_CURRENT: f64 = 10.0;

struct Checker(Vec<FieldError>);

impl Checker {
    fn err(&mut self, field: &str, message: String) {
        self.0.push(FieldError { field: field.to_string(), message });
    }
    fn finite(&mut self, field: &str, v: f64, unit: &str) -> bool {
        if v.is_finite() {
            true
        } else {
            self.err(field, format!("{v} is not a finite number (unit {unit})"));
            false
        }
    }
    fn positive(&mut self, field: &str, v: f64, unit: &str) {
        if self.finite(field, v, unit) && v <= 0.0 {
            self.err(field, format!("{v} {unit} must be > 0"));
        }
    }
    fn non_negative(&mut self, field: &str, v: f64, unit: &str) {
        if self.finite(field, v, unit) && v < 0.0 {
            self.err(field, format!("{v} {unit} must be >= 0"));
        }
    }
    fn speed(&mut self, field: &str, v: Option<f64>) {
        match v {
            None => self.err(field, "missing: the current profile needs it (m/s)".to_string()),
            Some(v) => {
                if self.finite(field, v, "m/s") && v.abs() > MAX_CURRENT {
                    self.err(field, format!("{v} m/s is outside [-{MAX_CURRENT}, {MAX_CURRENT}] m/s"));
                }
            }
        }
    }
}

pub(super) fn check(s: &Scene) -> Vec<FieldError> {
    let mut c = Checker(Vec::new());
    let l = &s.line;
    c.positive("line.length", l.length, "m");
    c.positive("line.mass_per_length", l.mass_per_length, "kg/m");
    c.positive("line.outer_diameter", l.outer_diameter, "m");
    c.positive("line.axial_stiffness", l.axial_stiffness, "N");
    c.non_negative("line.bending_stiffness", l.bending_stiffness, "N m^2");
    c.non_negative("line.torsional_stiffness", l.torsional_stiffness, "N m^2");
    c.non_negative("line.cd_normal", l.cd_normal, "(-)");
    c.non_negative("line.cd_tangential", l.cd_tangential, "(-)");
    c.non_negative("line.ca_normal", l.ca_normal, "(-)");
    if let Some(j) = l.rotary_inertia {
        c.non_negative("line.rotary_inertia", j, "kg m");
    }
    let env = &s.environment;
    c.non_negative("environment.water_density", env.water_density, "kg/m^3");
    c.non_negative("environment.gravity", env.gravity, "m/s^2");
    c.finite("environment.water_surface_z", env.water_surface_z, "m");
    let a = &s.anchor;
    let ok = c.finite("anchor.x", a.x, "m") & c.finite("anchor.y", a.y, "m") & c.finite("anchor.z", a.z, "m");
    if ok && l.length.is_finite() && l.length > 0.0 {
        let dist = (a.x * a.x + a.y * a.y + a.z * a.z).sqrt();
        let reach = l.length * (1.0 + MAX_REACH_STRAIN);
        if dist > reach {
            c.err(
                "anchor",
                format!(
                    "the anchor is {dist:.3} m from the hang-off, farther than the line can reach: \
                     at most {reach:.3} m (length {} m stretched by {}%)",
                    l.length,
                    MAX_REACH_STRAIN * 100.0
                ),
            );
        } else if dist < 1e-6 * l.length {
            c.err("anchor", "the anchor coincides with the hang-off (distance must be > 0 m)".to_string());
        }
    }
    let cur = &s.current;
    match cur.profile {
        ProfileKind::None => {}
        ProfileKind::Uniform => c.speed("current.speed", cur.speed),
        ProfileKind::LinearS => {
            c.speed("current.top", cur.top);
            c.speed("current.bottom", cur.bottom);
        }
        ProfileKind::LinearDepth => {
            c.speed("current.top", cur.top);
            c.speed("current.bottom", cur.bottom);
            match cur.depth {
                None => c.err("current.depth", "missing: depth (m) where `bottom` applies".to_string()),
                Some(d) => c.positive("current.depth", d, "m"),
            }
        }
        ProfileKind::Table => match &cur.table {
            None => c.err("current.table", "missing: rows [depth m, speed m/s]".to_string()),
            Some(rows) if rows.is_empty() => c.err("current.table", "needs at least one row".to_string()),
            Some(rows) => {
                for (i, r) in rows.iter().enumerate() {
                    let f = format!("current.table[{i}]");
                    if c.finite(&f, r[0], "m") && r[0] < 0.0 {
                        c.err(&f, format!("depth {} m must be >= 0", r[0]));
                    }
                    c.speed(&f, Some(r[1]));
                    if i > 0 && r[0] <= rows[i - 1][0] {
                        c.err(&f, "depths must increase from row to row".to_string());
                    }
                }
            }
        },
    }
    let [dx, dy] = cur.direction;
    if !(dx.is_finite() && dy.is_finite()) || dx.hypot(dy) == 0.0 {
        c.err("current.direction", format!("[{dx}, {dy}] must be a non-zero horizontal vector"));
    }
    for (i, b) in s.buoyancy.iter().enumerate() {
        let f = |k: &str| format!("buoyancy[{i}].{k}");
        let ok = c.finite(&f("start"), b.start, "m") & c.finite(&f("end"), b.end, "m");
        c.finite(&f("load"), b.load, "N/m");
        if ok && l.length.is_finite() {
            if b.start < 0.0 || b.start > l.length {
                c.err(&f("start"), format!("{} m is outside the line [0, {}] m", b.start, l.length));
            }
            if b.end < 0.0 || b.end > l.length {
                c.err(&f("end"), format!("{} m is outside the line [0, {}] m", b.end, l.length));
            }
            if b.end <= b.start {
                c.err(&f("end"), format!("end {} m must be greater than start {} m", b.end, b.start));
            }
        }
    }
    let an = &s.analysis;
    if an.n_elements < 2 || an.n_elements > MAX_ELEMENTS {
        c.err("analysis.n_elements", format!("{} must be in [2, {MAX_ELEMENTS}]", an.n_elements));
    }
    if c.finite("analysis.time_step", an.time_step, "s") && !(an.time_step > 0.0 && an.time_step <= 100.0) {
        c.err("analysis.time_step", format!("{} s must be in (0, 100] s", an.time_step));
    }
    if c.finite("analysis.newton_tolerance", an.newton_tolerance, "(-)")
        && !(an.newton_tolerance > 0.0 && an.newton_tolerance <= 1e-2)
    {
        c.err("analysis.newton_tolerance", format!("{} must be in (0, 1e-2]", an.newton_tolerance));
    }
    if c.finite("analysis.structural_damping", an.structural_damping, "s")
        && !(an.structural_damping >= 0.0 && an.structural_damping <= 10.0)
    {
        c.err("analysis.structural_damping", format!("{} s must be in [0, 10] s", an.structural_damping));
    }
    if c.finite("analysis.rho_infinity", an.rho_infinity, "(-)") && !(an.rho_infinity > 0.0 && an.rho_infinity <= 1.0) {
        c.err("analysis.rho_infinity", format!("{} must be in (0, 1]", an.rho_infinity));
    }
    let _ = Model::Rod;
    c.0
}
