//! Fatigue (docs/theory.md §12.5): rainflow counting of a stress history
//! (ASTM E1049-85 §5.4.4, with half cycles for the residue), the S-N curves
//! of DNV-RP-C203 (2016) by name with their thickness correction, and
//! Miner's sum of the damage; [`FatigueTracker`] counts the axial stress at
//! every point and fibre of a line over a run's steady window.

use super::design::{Design, FIBRES};
use crate::model::outputs::LinePoint;

/// Seconds in a year (365.25 days) for the damage per year (12.5.6).
pub const SECONDS_PER_YEAR: f64 = 365.25 * 86_400.0;

/// DNV-RP-C203's reference thickness t_ref for welded connections other
/// than tubular joints, m (12.5.3).
pub const REFERENCE_THICKNESS: f64 = 0.025;

/// Reversals a counter holds before its residue's stack grows (a residue
/// longer than this is a ring-down of more than half as many cycles).
const RESIDUE_CAPACITY: usize = 64;

/// An S-N curve: N = a₁ S^(−m₁) for N ≤ N_switch, N = a₂ S^(−m₂) above
/// (12.5.2), S the stress range in MPa; a single slope without a switch.
#[derive(Debug, Clone, PartialEq)]
pub struct SnCurve {
    /// The name, e.g. `D-seawater-cp`.
    pub name: String,
    pub m1: f64,
    pub log_a1: f64,
    /// The slope and intercept above the switch (the single slope's own
    /// without one).
    pub m2: f64,
    pub log_a2: f64,
    /// Cycles at the switch (None: a single slope).
    pub n_switch: Option<f64>,
    /// The thickness exponent k (12.5.3).
    pub k: f64,
}

/// One S-N class of DNV-RP-C203 (2016): (class, m₁ in air and with CP,
/// log a₁ in air, log a₁ in seawater with CP, log a₂ (m₂ = 5, both), k in
/// air and with CP, log a in free corrosion (m = 3), k in free corrosion).
type Class = (&'static str, f64, f64, f64, f64, f64, f64, f64);

/// DNV-RP-C203 (April 2016) Tables 2-1 (air), 2-2 (seawater with cathodic
/// protection) and 2-4 (free corrosion), as docs/theory.md §12.5 cites them.
const CLASSES: [Class; 14] = [
    ("B1", 4.0, 15.117, 14.917, 17.146, 0.00, 12.436, 0.00),
    ("B2", 4.0, 14.885, 14.685, 16.856, 0.00, 12.262, 0.00),
    ("C", 3.0, 12.592, 12.192, 16.320, 0.05, 12.115, 0.15),
    ("C1", 3.0, 12.449, 12.049, 16.081, 0.10, 11.972, 0.15),
    ("C2", 3.0, 12.301, 11.901, 15.835, 0.15, 11.824, 0.15),
    ("D", 3.0, 12.164, 11.764, 15.606, 0.20, 11.687, 0.20),
    ("E", 3.0, 12.010, 11.610, 15.350, 0.20, 11.533, 0.20),
    ("F", 3.0, 11.855, 11.455, 15.091, 0.25, 11.378, 0.25),
    ("F1", 3.0, 11.699, 11.299, 14.832, 0.25, 11.222, 0.25),
    ("F3", 3.0, 11.546, 11.146, 14.576, 0.25, 11.068, 0.25),
    ("G", 3.0, 11.398, 10.998, 14.330, 0.25, 10.921, 0.25),
    ("W1", 3.0, 11.261, 10.861, 14.101, 0.25, 10.784, 0.25),
    ("W2", 3.0, 11.107, 10.707, 13.845, 0.25, 10.630, 0.25),
    ("W3", 3.0, 10.970, 10.570, 13.617, 0.25, 10.493, 0.25),
];

/// The environments of the curves' names: in air (switch at 10⁷ cycles), in
/// seawater with cathodic protection (switch at 10⁶), free corrosion (one slope).
const ENVIRONMENTS: [&str; 3] = ["air", "seawater-cp", "free-corrosion"];

impl SnCurve {
    /// Every name [`SnCurve::by_name`] knows, `B1-air` … `W3-free-corrosion`.
    pub fn names() -> Vec<String> {
        ENVIRONMENTS.iter().flat_map(|env| CLASSES.iter().map(move |c| format!("{}-{env}", c.0))).collect()
    }

    /// The curve called `name` (class and environment, e.g. `D-seawater-cp`,
    /// case-insensitive), or a message listing the names.
    pub fn by_name(name: &str) -> Result<SnCurve, String> {
        let unknown = || {
            format!(
                "unknown S-N curve '{name}': DNV-RP-C203 (2016) classes B1, B2, C, C1, C2, D, E, F, F1, F3, G, W1, \
                 W2, W3, each -air, -seawater-cp (cathodic protection) or -free-corrosion: {}",
                SnCurve::names().join(", ")
            )
        };
        let (class, env) = name.split_once('-').ok_or_else(unknown)?;
        let c = CLASSES.iter().find(|c| c.0.eq_ignore_ascii_case(class)).ok_or_else(unknown)?;
        let (_, m1, air, cp, log_a2, k, free, k_free) = *c;
        let name = format!("{}-{}", c.0, env.to_ascii_lowercase());
        match env.to_ascii_lowercase().as_str() {
            "air" => Ok(SnCurve { name, m1, log_a1: air, m2: 5.0, log_a2, n_switch: Some(1e7), k }),
            "seawater-cp" => Ok(SnCurve { name, m1, log_a1: cp, m2: 5.0, log_a2, n_switch: Some(1e6), k }),
            "free-corrosion" => {
                Ok(SnCurve { name, m1: 3.0, log_a1: free, m2: 3.0, log_a2: free, n_switch: None, k: k_free })
            }
            _ => Err(unknown()),
        }
    }

    /// The stress range at the switch, MPa: S_sw = 10^((log a₁ − log N_sw)/m₁)
    /// (12.5.2); None for a single slope.
    pub fn switch_range(&self) -> Option<f64> {
        self.n_switch.map(|n| 10f64.powf((self.log_a1 - n.log10()) / self.m1))
    }

    /// Cycles to failure at the stress range `s` (MPa), N = a₁ s^(−m₁) at and
    /// above the switch's range, a₂ s^(−m₂) below (12.5.2); infinite at s = 0.
    pub fn cycles_to_failure(&self, s: f64) -> f64 {
        match self.switch_range() {
            Some(sw) if s < sw => 10f64.powf(self.log_a2 - self.m2 * s.log10()),
            _ => 10f64.powf(self.log_a1 - self.m1 * s.log10()),
        }
    }

    /// The thickness correction's factor on the stress range, (t/t_ref)^k
    /// for t > t_ref and 1 at and below it (12.5.3); `t` in m.
    pub fn thickness_factor(&self, t: f64) -> f64 {
        if t > REFERENCE_THICKNESS { (t / REFERENCE_THICKNESS).powf(self.k) } else { 1.0 }
    }
}

/// A rainflow counter of one history (ASTM E1049-85 §5.4.4), fed one sample
/// at a time: it finds the reversals (the first and last samples and every
/// change of direction; repeated values are one) and counts each range Y
/// closed by a range X ≥ Y as a cycle, or, when Y holds the history's first
/// point, as a half cycle (12.5.1); [`Rainflow::finish`] counts the residue
/// as half cycles. Its cycles are those of the whole history, in the order
/// the standard's batch procedure finds them.
#[derive(Debug, Clone)]
pub struct Rainflow {
    /// Samples fed.
    samples: usize,
    /// The candidate reversal (the latest sample that differs from the one before).
    x: f64,
    /// The direction into the candidate, x − the sample before it.
    slope: f64,
    /// The last sample fed.
    last: f64,
    /// The reversals not yet closed (the residue).
    stack: Vec<f64>,
}

impl Default for Rainflow {
    fn default() -> Self {
        Rainflow::new()
    }
}

impl Rainflow {
    pub fn new() -> Self {
        Rainflow { samples: 0, x: 0.0, slope: 0.0, last: 0.0, stack: Vec::with_capacity(RESIDUE_CAPACITY) }
    }

    /// Feeds the next sample `y`; each cycle found is given to `cycle` as
    /// (range, count 1 or ½).
    pub fn push(&mut self, y: f64, cycle: &mut impl FnMut(f64, f64)) {
        self.samples += 1;
        self.last = y;
        match self.samples {
            1 => self.reversal(y, cycle),
            2 => (self.slope, self.x) = (y - self.x_first(), y),
            _ => {
                if y == self.x {
                    return;
                }
                let slope = y - self.x;
                if self.slope * slope < 0.0 {
                    let x = self.x;
                    self.reversal(x, cycle);
                }
                (self.slope, self.x) = (slope, y);
            }
        }
    }

    /// The first sample (the bottom of the stack until it is counted).
    fn x_first(&self) -> f64 {
        self.stack.first().copied().unwrap_or(self.last)
    }

    /// Adds a reversal and counts the ranges it closes (12.5.1).
    fn reversal(&mut self, r: f64, cycle: &mut impl FnMut(f64, f64)) {
        self.stack.push(r);
        while self.stack.len() >= 3 {
            let n = self.stack.len();
            let (x1, x2, x3) = (self.stack[n - 3], self.stack[n - 2], self.stack[n - 1]);
            let (x, y) = ((x3 - x2).abs(), (x2 - x1).abs());
            if x < y {
                break;
            }
            if n == 3 {
                cycle(y, 0.5);
                self.stack.remove(0);
            } else {
                cycle(y, 1.0);
                self.stack.truncate(n - 3);
                self.stack.push(x3);
            }
        }
    }

    /// Ends the history: its last sample is a reversal (of three samples or
    /// more), and the residue's ranges are half cycles (12.5.1). The counter
    /// is then empty, ready for another history.
    pub fn finish(&mut self, cycle: &mut impl FnMut(f64, f64)) {
        if self.samples >= 3 {
            let last = self.last;
            self.reversal(last, cycle);
        }
        for w in self.stack.windows(2) {
            cycle((w[1] - w[0]).abs(), 0.5);
        }
        self.stack.clear();
        self.samples = 0;
    }
}

/// The rainflow cycles of a whole history, (range, count) in the order
/// ASTM E1049-85's procedure finds them (12.5.1).
pub fn rainflow(history: &[f64]) -> Vec<(f64, f64)> {
    let mut cycles = Vec::new();
    let mut add = |r: f64, n: f64| cycles.push((r, n));
    let mut counter = Rainflow::new();
    for &y in history {
        counter.push(y, &mut add);
    }
    counter.finish(&mut add);
    cycles
}

/// Miner's damage of `count` cycles of the stress range `range` (Pa) on
/// `curve`, the range scaled by `factor` (the SCF and the thickness
/// correction): n / N(factor · range) (12.5.4).
pub fn cycle_damage(curve: &SnCurve, range: f64, count: f64, factor: f64) -> f64 {
    count / curve.cycles_to_failure(factor * range / 1e6)
}

/// Miner's sum D = Σ nᵢ / Nᵢ of the cycles (range Pa, count) (12.5.4).
pub fn miner_sum(curve: &SnCurve, cycles: &[(f64, f64)], factor: f64) -> f64 {
    cycles.iter().map(|&(r, n)| cycle_damage(curve, r, n, factor)).sum()
}

/// What the fatigue of a window gives (12.5.5, 12.5.6): the damage per
/// year of a window of `window` s and the life in years with the design
/// fatigue factor `dff` (allowable damage 1/DFF).
pub fn damage_per_year(damage: f64, window: f64) -> f64 {
    damage * SECONDS_PER_YEAR / window
}

/// The life in years, 1 / (damage per year · DFF) (12.5.6); infinite
/// without damage.
pub fn life_years(damage_per_year: f64, dff: f64) -> f64 {
    1.0 / (damage_per_year * dff)
}

/// Fatigue's inputs: the curve, the stress concentration factor (DNV-RP-F204's
/// misalignment; 1 for none) and the design fatigue factor.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueSpec {
    pub curve: SnCurve,
    pub scf: f64,
    pub dff: f64,
}

/// (cos θ, sin θ) of the [`FIBRES`] fibres, θ = f · 2π/[`FIBRES`] from the
/// section's first director (the stress range's, §12.2).
pub fn fibre_directions() -> [(f64, f64); FIBRES] {
    std::array::from_fn(|f| {
        let theta = 2.0 * std::f64::consts::PI * f as f64 / FIBRES as f64;
        (theta.cos(), theta.sin())
    })
}

/// Miner's damage of one cycle on a curve, its constants computed once
/// (12.5.2, 12.5.4): n (f Δσ)^m / a, the branch by the switch's range;
/// integral slopes (all of DNV-RP-C203's) by multiplication.
#[derive(Debug, Clone, Copy)]
struct Miner {
    /// S_sw, MPa (0: one slope).
    switch: f64,
    m1: f64,
    inv_a1: f64,
    m2: f64,
    inv_a2: f64,
}

impl Miner {
    fn of(c: &SnCurve) -> Self {
        Miner {
            switch: c.switch_range().unwrap_or(0.0),
            m1: c.m1,
            inv_a1: 10f64.powf(-c.log_a1),
            m2: c.m2,
            inv_a2: 10f64.powf(-c.log_a2),
        }
    }

    /// The damage of `count` cycles of the range `range` (Pa) times `factor`.
    fn damage(&self, range: f64, count: f64, factor: f64) -> f64 {
        let s = factor * range / 1e6;
        let power = |m: f64| if m.fract() == 0.0 && m.abs() < 16.0 { s.powi(m as i32) } else { s.powf(m) };
        if s >= self.switch { count * power(self.m1) * self.inv_a1 } else { count * power(self.m2) * self.inv_a2 }
    }
}

/// One history being counted: its counter, damage and largest range.
#[derive(Debug, Clone)]
struct Series {
    counter: Rainflow,
    damage: f64,
    max_range: f64,
}

/// The rainflow count and Miner's damage of the axial stress (true wall
/// tension plus bending at the outer fibre, the stress range's, §12.2) at
/// every point of a line ([`crate::sim::Engine::line_points`]) and
/// [`FIBRES`] fibres, fed one state at a time over a window: memory per
/// point and fibre, not per time (a 3-hour sea state's record at every
/// point would not fit).
#[derive(Debug, Clone)]
pub struct FatigueTracker {
    spec: FatigueSpec,
    miner: Miner,
    /// Per point: arc length, m, and the factor SCF · (t/t_ref)^k on its ranges.
    points: Vec<(f64, f64)>,
    /// Per point and fibre, point-major.
    series: Vec<Series>,
    /// (cos θ, sin θ) of the fibres.
    fibres: [(f64, f64); FIBRES],
    finished: bool,
}

/// The worst point and fibre of a window's fatigue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FatigueWorst {
    /// Arc length, m.
    pub s: f64,
    /// Fibre index f (θ = f · 360°/[`FIBRES`]).
    pub fibre: usize,
    /// Its largest rainflow range, Pa (before the SCF and thickness factor).
    pub range: f64,
    /// Miner's sum over the window.
    pub damage: f64,
}

impl FatigueTracker {
    /// A tracker of `design`'s line whose states have `points` (the arc
    /// lengths and elements are read; the same points every time), or None
    /// when the line has no stresses.
    pub fn new(spec: FatigueSpec, design: &Design, points: &[LinePoint]) -> Option<Self> {
        if !design.has_stresses() {
            return None;
        }
        let points: Vec<(f64, f64)> = points
            .iter()
            .map(|p| {
                let tube = design.tube(p.element).expect("every element is a tube");
                (p.s, spec.scf * spec.curve.thickness_factor(tube.outer_radius - tube.inner_radius))
            })
            .collect();
        let series = vec![Series { counter: Rainflow::new(), damage: 0.0, max_range: 0.0 }; points.len() * FIBRES];
        Some(FatigueTracker {
            miner: Miner::of(&spec.curve),
            spec,
            points,
            series,
            fibres: fibre_directions(),
            finished: false,
        })
    }

    /// The fatigue's inputs.
    pub fn spec(&self) -> &FatigueSpec {
        &self.spec
    }

    /// Adds one state's `points` with the hang-off at `hang_off_z` (m).
    pub fn add(&mut self, design: &Design, points: &[LinePoint], hang_off_z: f64) {
        let miner = self.miner;
        for (i, p) in points.iter().enumerate() {
            let factor = self.points[i].1;
            let Some(stress) = design.fibre_stress_parts(p, hang_off_z) else { continue };
            for (f, &(c, s)) in self.fibres.iter().enumerate() {
                let sigma = stress.at(c, s);
                let one = &mut self.series[i * FIBRES + f];
                let (damage, max_range) = (&mut one.damage, &mut one.max_range);
                one.counter.push(sigma, &mut |r, n| {
                    *damage += miner.damage(r, n, factor);
                    *max_range = max_range.max(r);
                });
            }
        }
    }

    /// Counts the residues (the window's end); once.
    pub fn finish(&mut self) {
        if self.finished {
            return;
        }
        let miner = self.miner;
        for (i, one) in self.series.iter_mut().enumerate() {
            let factor = self.points[i / FIBRES].1;
            let (damage, max_range) = (&mut one.damage, &mut one.max_range);
            one.counter.finish(&mut |r, n| {
                *damage += miner.damage(r, n, factor);
                *max_range = max_range.max(r);
            });
        }
        self.finished = true;
    }

    /// Per point and fibre: (S m, fibre, damage, largest range Pa), after [`FatigueTracker::finish`].
    pub fn rows(&self) -> Vec<(f64, usize, f64, f64)> {
        self.series
            .iter()
            .enumerate()
            .map(|(i, one)| (self.points[i / FIBRES].0, i % FIBRES, one.damage, one.max_range))
            .collect()
    }

    /// The point and fibre of the largest damage (the first of equals).
    pub fn worst(&self) -> Option<FatigueWorst> {
        self.rows()
            .into_iter()
            .fold(None, |w: Option<(f64, usize, f64, f64)>, r| match w {
                Some(w) if w.2 >= r.2 => Some(w),
                _ => Some(r),
            })
            .map(|(s, fibre, damage, range)| FatigueWorst { s, fibre, range, damage })
    }
}
