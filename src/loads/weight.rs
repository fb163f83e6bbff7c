//! Weight, buoyancy of the displaced water and buoyancy modules as a
//! distributed vertical load q(S) (N/m of reference length, + = up):
//!   q(S) = −(m − ρw A) g + b(S),  A = π D²/4,
//! with b the upward load of buoyancy modules on their S-ranges. Tension
//! computed with this load is the effective tension.

/// A buoyancy section: `load` N/m upward on S ∈ [start, end] (m from the hang-off).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuoyancySection {
    pub start: f64,
    pub end: f64,
    pub load: f64,
}

/// Piecewise-constant vertical load along the line.
#[derive(Debug, Clone, PartialEq)]
pub struct VerticalLoad {
    /// Uniform part, N/m (+ = up): −(m − ρw A) g.
    pub uniform: f64,
    pub sections: Vec<BuoyancySection>,
}

impl VerticalLoad {
    pub fn new(mass_per_length: f64, outer_diameter: f64, water_density: f64, gravity: f64) -> Self {
        let area = std::f64::consts::PI * outer_diameter * outer_diameter / 4.0;
        VerticalLoad { uniform: -(mass_per_length - water_density * area) * gravity, sections: Vec::new() }
    }

    /// Load at S (N/m, + = up); at a section boundary the section counts.
    pub fn at(&self, s: f64) -> f64 {
        self.uniform + self.sections.iter().filter(|b| s >= b.start && s <= b.end).map(|b| b.load).sum::<f64>()
    }

    /// The breakpoints of q in (a, b), sorted, with a and b.
    pub fn breakpoints(&self, a: f64, b: f64) -> Vec<f64> {
        let mut p = vec![a, b];
        for sec in &self.sections {
            for x in [sec.start, sec.end] {
                if x > a && x < b {
                    p.push(x);
                }
            }
        }
        p.sort_by(f64::total_cmp);
        p.dedup();
        p
    }

    /// Total vertical load on [0, length], N.
    pub fn total(&self, length: f64) -> f64 {
        self.uniform * length
            + self.sections.iter().map(|b| b.load * (b.end.min(length) - b.start.max(0.0)).max(0.0)).sum::<f64>()
    }
}
