//! The physical range of every number a scene holds, in one table shared by
//! the scene validation (scene files), the command line (`--set`) and the FMU
//! (`fmi2SetReal`/`fmi2SetInteger` of a parameter). Each bound carries its
//! reason; `riser params` prints the table and docs/interface.md lists it.
//!
//! The bounds are engineering ranges, wide enough for every line the model is
//! meant for and narrow enough that the statics and the time stepping work at
//! them in double precision (tests/it/parameter_ranges.rs runs the default scene
//! at each bound and refuses a value just outside it).

include!("range_table.rs");

impl Range {
    /// `Ok` when `v` is finite and within `[min, max]`; otherwise the message
    /// (without the field's name) giving the range and its reason.
    pub fn check(&self, v: f64) -> Result<(), String> {
        if !v.is_finite() {
            return Err(format!("{v} is not a finite number; allowed {}", self.interval()));
        }
        if v < self.min || v > self.max {
            return Err(format!("{}{} is outside {} ({})", number(v), self.suffix(), self.interval(), self.reason));
        }
        Ok(())
    }

    /// `[min, max] unit`.
    pub fn interval(&self) -> String {
        format!("[{}, {}]{}", number(self.min), number(self.max), self.suffix())
    }

    /// " unit", or nothing for a ratio.
    fn suffix(&self) -> String {
        if self.unit == "-" { String::new() } else { format!(" {}", self.unit) }
    }
}

/// A number for a message: plain between 1e-4 and 1e7, else in scientific
/// notation (never 300 digits of 1e308); exact (shortest round trip) either way.
pub fn number(v: f64) -> String {
    if v == 0.0 || (1e-4..1e7).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

/// The range of a scene field (dotted path; indices stripped: `buoyancy[2].end` → `buoyancy.end`).
pub fn of_field(field: &str) -> Option<&'static Range> {
    let mut plain = String::with_capacity(field.len());
    let mut skip = false;
    for c in field.chars() {
        match c {
            '[' => skip = true,
            ']' => skip = false,
            _ if !skip => plain.push(c),
            _ => {}
        }
    }
    RANGES.iter().find(|r| r.field == plain)
}

/// The range of an FMU / `--set` parameter.
pub fn of_parameter(name: &str) -> Option<&'static Range> {
    RANGES.iter().find(|r| r.parameter == Some(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_numeric_parameter_has_a_range_and_the_table_is_consistent() {
        for (name, _) in super::super::PARAMETER_NAMES {
            let non_numeric = [
                "model",
                "hang_off_end",
                "static_current",
                "wave_kind",
                "wave_file",
                "wave_stretching",
                "wave_spacing",
                "rotation_order",
                "accuracy_quantity",
                "safety_class",
            ];
            assert!(non_numeric.contains(&name) || of_parameter(name).is_some(), "{name} has no range");
        }
        for r in RANGES {
            assert!(r.min < r.max && r.min.is_finite() && r.max.is_finite(), "{}", r.field);
            assert!(r.check(r.min).is_ok() && r.check(r.max).is_ok());
            assert!(r.check(f64::NAN).is_err() && r.check(f64::INFINITY).is_err());
        }
        assert_eq!(of_field("buoyancy[3].end").unwrap().parameter, Some("buoyancy_end"));
        assert_eq!(of_field("current.table[0].depth").unwrap().field, "current.table.depth");
    }
}
