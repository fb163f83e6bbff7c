//! The checker the scene's validations share (scene/validate.rs, the
//! `[waves]` block's in scene/waves.rs): each problem with its field, each
//! value against its range (ranges.rs).

use super::ranges;

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

/// The problems found so far, each naming its field (the scene's checks and
/// the `[waves]` block's, scene/waves.rs).
pub(super) struct Checker(pub(super) Vec<FieldError>);

impl Checker {
    pub(super) fn err(&mut self, field: &str, message: String) {
        self.0.push(FieldError { field: field.to_string(), message });
    }
    /// The value against its field's range (ranges.rs); true if it is in it.
    pub(super) fn range(&mut self, field: &str, v: f64) -> bool {
        self.range_as(field, field, v)
    }
    /// Each key given (`Some`) against the range of `like(key)`, named
    /// `field(key)`; true if every one is inside.
    pub(super) fn optional(
        &mut self,
        keys: &[(&str, Option<f64>)],
        field: impl Fn(&str) -> String,
        like: impl Fn(&str) -> String,
    ) -> bool {
        let mut ok = true;
        for (k, v) in keys {
            if let Some(v) = v {
                ok &= self.range_as(&field(k), &like(k), *v);
            }
        }
        ok
    }
    /// The value against the range of another field (a section's keys have `[line]`'s ranges).
    pub(super) fn range_as(&mut self, field: &str, like: &str, v: f64) -> bool {
        let r = ranges::of_field(like).expect("every checked field has a range");
        match r.check(v) {
            Ok(()) => true,
            Err(m) => {
                self.err(field, m);
                false
            }
        }
    }
    pub(super) fn speed(&mut self, field: &str, v: Option<f64>) {
        match v {
            None => self.err(field, "missing: the current profile needs it (m/s)".to_string()),
            Some(v) => {
                self.range(field, v);
            }
        }
    }
}
