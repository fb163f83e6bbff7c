//! The accuracy the user asks for, measured on the user's own scene (issue
//! 51; docs/theory.md §16.12). With `accuracy` ε set, riser does not predict
//! its error from a calibrated model: it measures it. Short pilot runs of the
//! scene's own motion and sea ([`super::error_estimate`]: five pilots, a
//! mesh triplet n₀, 2n₀, 4n₀ at Δt₀/4 and a step triplet Δt₀, Δt₀/2, Δt₀/4
//! at n₀) give, for each quantity the target is on, each axis' observed
//! order and error, from which the error of any mesh and step is
//!
//!   E(n, Δt) = |e_h| (n₀/n)^{p_h} + |e_t| (Δt/Δt₀)^{p_t}                      (16.17)
//!
//! e_h = q(n₀, Δt₀/4) − q*_h and e_t = q(n₀, Δt₀) − q*_t the base level's
//! errors of each axis (16.16), p_h, p_t the observed orders (16.13); the
//! bound of the two (they may cancel; the bound does not count on it), and
//! where their signs differ the larger of them (16.23, docs/theory.md
//! §16.16: their sum is no larger). The
//! choice is the cheapest (n, Δt) by the cost n/Δt (the work of a run: an
//! element-step is the unit, Newton's iterations a step about alike) with
//!
//!   E_q(n, Δt) ≤ ε |q_s| / S    for each quantity q of the target        (16.18)
//!
//! q_s the value the quantity is relative to at the round's shared pilot
//! (since docs/theory.md §16.15; the extrapolated one before) (the top
//! tension's maximum for its min, mean and max; the touchdown's largest arc
//! length for its extremes; itself otherwise), S = [`SAFETY`]. Where the
//! choice lies outside the pilots' span (coarser than n₀ or Δt₀, finer than
//! 4n₀ or Δt₀/4), (16.17) extrapolates an order beyond where it was seen: a
//! new round of pilots is run with its base at the choice, up to
//! [`MAX_ROUNDS`] rounds, so the numerics chosen are those of the last
//! round's pilots or between them; where nothing a round's pilots reach
//! meets the target, the next round is about finer numerics (twice the
//! elements, half the step, on the axes that do not converge). An axis whose triplet does not converge
//! monotonically (contact can make refinement oscillate) has no order: it is
//! said with its numbers, its finest pilot level is taken, and its error is
//! the last change, |q₂ − q₃| ([`Axis::Unconverged`]); an axis whose finer
//! two pilots agree has nothing left at or finer than 2n₀ (Δt₀/2).
//!
//! A round of `accuracy` lays its triplets through the numerics it
//! measures, its candidate (n_c, Δt_c) = (4n₀, Δt₀/4) ([`Layout::Corner`],
//! docs/theory.md §16.13, (16.19)–(16.20)): the step triplet at the
//! candidate's mesh, the mesh triplet at its step, 2.5 times the
//! candidate's work; a choice is measured only on those two lines, and a
//! level off them is the next round's candidate. The first candidate is
//! [`FIRST_CANDIDATE_COARSENING`] coarser than the scene's numerics; an
//! earlier round's pilots are reused.
//!
//! The Newton tolerance is ε² ([`newton_tolerance_for`]), the pilots' too.
//! Numerics the user set (`--set`, a master's nonzero value) are kept: their
//! axis has that one level, and the estimate says whether the target is met.

use super::error::{AccuracyError, RiserError};
use super::error_estimate::{
    Convergence, ErrorEstimate, Layout, LinePilots, Pilot, PilotRuns, Quantity, RunSpec, Triplet, estimate_on,
};
use crate::scene::{AccuracyQuantity, Scene};

/// The safety factor S of (16.18): the estimate of the pilots is within
/// 0.65–1.64 of the measured error on the cases of tests/it/error_estimate.rs.
pub const SAFETY: f64 = 1.5;
/// Rounds of pilots at most (the first about a candidate a quarter of the
/// scene's numerics): four since docs/theory.md §16.16, so that a tight
/// target climbs from the coarser first candidate as far as three rounds
/// reached from the finer one (the two chains at 1e-3: level 8, 16, 32,
/// 64 at 0.2 to 0.025 s).
pub const MAX_ROUNDS: usize = 4;
/// The most elements a choice takes (the scene's range).
pub const MAX_ELEMENTS: usize = 2000;
/// The shortest step a choice takes, s (the scene's range).
pub const MIN_STEP: f64 = 1e-4;
/// The work of a round of pilots beyond the first at most, element-steps
/// (the five pilots' elements times their steps): about 100 s of one core
/// on the catenary (4 µs an element-step). A round beyond it is not run;
/// the choice of the rounds before is kept and the output says so. The
/// first round, about the scene's numerics, always runs (it is
/// `--estimate-error`'s).
pub const MAX_ROUND_WORK: f64 = 2.5e7;
/// The first round's candidate is this much coarser than the scene's
/// numerics on each axis (a quarter of the elements, four times the step;
/// twice until docs/theory.md §16.16): the scene's defaults are finer than
/// most targets need, and the rounds after it go finer where it does not
/// meet the target (docs/theory.md §16.13, §16.16).
pub const FIRST_CANDIDATE_COARSENING: usize = 4;
/// The fewest elements a round's base takes (fewer where the candidate has
/// fewer than four times as many).
pub const MIN_BASE_ELEMENTS: usize = 2;
/// The step ladder's ratio, 2^{1/4}: steps Δt₀ 2^{−k/4}, rounded to three
/// significant digits.
const STEP_RATIO: f64 = 1.189_207_115_002_721;

/// The Newton tolerance for a target ε: ε², within [1e-10, 1e-6] (Newton's
/// share of the error a few percent of the target: docs/theory.md §16.3).
pub fn newton_tolerance_for(target: f64) -> f64 {
    target.powi(2).clamp(1e-10, 1e-6)
}

/// True where the mesh of `n` elements has a node at each end of every
/// buoyancy section and at every joint between `[[section]]`s (a section's
/// end inside an element smears its step in the load over it: the lazy
/// wave's 12 elements missed by 3.5e-2; and where the joint falls inside
/// its element changes from mesh to mesh without a trend, which makes the
/// mesh triplets of a lazy wave of sections non-monotone: docs/theory.md
/// §16.15).
pub fn nodes_on_buoyancy_ends(scene: &Scene, n: usize) -> bool {
    let l = scene.line.length;
    let joints = scene.pieces().into_iter().skip(1).map(|p| p.start);
    scene.buoyancy.iter().flat_map(|b| [b.start, b.end]).chain(joints).filter(|&e| e > 0.0 && e < l).all(|e| {
        let k = e / l * n as f64;
        (k - k.round()).abs() < 1e-6
    })
}

/// Which numerics the user set explicitly (`--set`, the FMU's master with a
/// nonzero value): they win over the choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Pinned {
    pub n_elements: bool,
    pub time_step: bool,
    pub newton_tolerance: bool,
}

impl Pinned {
    /// From the names of the parameters set (`--set name=value`: the part
    /// before `=` is taken).
    pub fn of_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Self {
        let mut p = Pinned::default();
        for n in names {
            match n.split('=').next().unwrap_or("").trim() {
                "n_elements" => p.n_elements = true,
                "time_step" => p.time_step = true,
                "newton_tolerance" => p.newton_tolerance = true,
                _ => {}
            }
        }
        p
    }
}

/// The quantities a target is on, each with the one its error is relative
/// to (16.18), on `scene` (`fatigue`: the run counts fatigue); an error
/// where the scene has none of them.
pub fn criteria(
    target: AccuracyQuantity,
    scene: &Scene,
    fatigue: bool,
) -> Result<Vec<(Quantity, Quantity)>, AccuracyError> {
    use Quantity::*;
    let top = vec![(TopTensionMax, TopTensionMax), (TopTensionMin, TopTensionMax), (TopTensionMean, TopTensionMax)];
    let touchdown = vec![(TouchdownMax, TouchdownMax), (TouchdownMin, TouchdownMax)];
    let has = |q: Quantity| q.applies(scene, fatigue);
    let one = |q: Quantity, list: Vec<(Quantity, Quantity)>| {
        if has(q) {
            return Ok(list);
        }
        let reason = match q {
            StressRange => "the line has no stresses: no wall (wall_thickness) and not a homogeneous tube",
            FatigueDamage => "fatigue is counted only by `riser run --fatigue CURVE`, on a line with stresses",
            _ => "the scene has no seabed, so no touchdown",
        };
        Err(AccuracyError::NoQuantity { quantity: target.name(), reason })
    };
    match target {
        AccuracyQuantity::TopTension => Ok(top),
        AccuracyQuantity::StressRange => one(StressRange, vec![(StressRange, StressRange)]),
        AccuracyQuantity::Touchdown => one(TouchdownMax, touchdown),
        AccuracyQuantity::Fatigue => one(FatigueDamage, vec![(FatigueDamage, FatigueDamage)]),
        AccuracyQuantity::All => {
            let mut all = top;
            if has(TouchdownMax) {
                all.extend(touchdown);
            }
            for q in [StressRange, FatigueDamage] {
                if has(q) {
                    all.push((q, q));
                }
            }
            Ok(all)
        }
    }
}

/// Below this fraction of the allowed error ε |q_s| / S, a triplet's
/// spread is the floor of the pilots (Newton's tolerance, the sampling of
/// the extremes): its pattern says nothing of an order ([`Axis::Floor`]).
pub const FLOOR_FRACTION: f64 = 0.1;

/// One axis' error model, from its triplet (16.17).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axis {
    /// |E(x)| = e₀ (x/x₀)^p, x the element length (n₀/n) or the step
    /// (Δt/Δt₀), p observed (a monotone triplet).
    Power { e0: f64, order: f64, sign: f64 },
    /// The three pilots agree within [`FLOOR_FRACTION`] of the allowed
    /// error, whatever their pattern: the error at the base level and finer
    /// is their spread, max |qᵢ − qⱼ|. A coarser level is proposed as
    /// spread (x/x₀)² (up to 2x₀) and measured by the next round's pilots,
    /// never taken on that proposal alone.
    Floor { spread: f64 },
    /// Not monotone, the spread above the floor: only the finest pilot's
    /// level (a quarter of the base) is taken, its error the last change
    /// |q₂ − q₃| (the finer two agreeing: 0 from half the base).
    Unconverged { error: f64, from: f64 },
    /// Not monotone above the floor on the round's three levels, and a
    /// fourth level run beyond the candidate on this axis (twice its
    /// elements, or half its step: [`fourth_level`]): the candidate's
    /// error from the three finest levels q_b, q_c, q_d (16.22), taken at
    /// the candidate's level only (a quarter of the base). `converges`:
    /// the change out of the candidate is smaller than the change into it
    /// (|R'| < 1); where not, the error is the larger of the two changes.
    Fourth { error: f64, ratio: Option<f64>, converges: bool, values: [f64; 4] },
}

impl Axis {
    /// The axis of triplet `t`, `allowed` the error (16.18) allows.
    pub fn of(t: &Triplet, allowed: f64) -> Axis {
        let [q1, q2, q3] = t.values;
        let spread = (q1 - q2).abs().max((q1 - q3).abs()).max((q2 - q3).abs());
        match t.class {
            Convergence::Monotone => {
                Axis::Power { e0: t.error.abs(), order: t.order.unwrap_or(f64::NAN), sign: t.error.signum() }
            }
            _ if spread <= FLOOR_FRACTION * allowed => Axis::Floor { spread },
            Convergence::Converged => Axis::Unconverged { error: 0.0, from: 0.5 },
            _ => Axis::Unconverged { error: (q2 - q3).abs(), from: 0.25 },
        }
    }

    /// The error at `ratio` = x/x₀ of the base level (None: a level the
    /// axis' model does not reach).
    pub fn error_at(&self, ratio: f64) -> Option<f64> {
        const EPS: f64 = 1e-9;
        match *self {
            Axis::Power { e0, order, .. } => Some(e0 * ratio.powf(order)),
            Axis::Floor { spread } if ratio <= 1.0 + EPS => Some(spread),
            Axis::Floor { spread } => (ratio <= 2.0 + EPS).then_some(spread * ratio * ratio),
            Axis::Unconverged { error, from } => (ratio <= from + EPS).then_some(error),
            Axis::Fourth { error, .. } => (ratio <= 0.25 + EPS).then_some(error),
        }
    }

    /// The axis does not converge: unconverged above the floor, or its
    /// fourth level's change not smaller than the change before it.
    pub fn unconverged(&self) -> bool {
        matches!(self, Axis::Unconverged { .. } | Axis::Fourth { converges: false, .. })
    }

    /// The sign of the axis' error q − q* at the levels it models: ±1,
    /// or 0 where it is not known (at the floor; not converged).
    pub fn sign(&self) -> f64 {
        match *self {
            Axis::Power { sign, .. } => sign,
            Axis::Fourth { converges: true, values, .. } if values[2] != values[3] => (values[2] - values[3]).signum(),
            _ => 0.0,
        }
    }

    /// The observed order (None: not monotone, or at the floor).
    pub fn order(&self) -> Option<f64> {
        match *self {
            Axis::Power { order, .. } => Some(order),
            _ => None,
        }
    }

    /// A coarser level is only a proposal the next round measures.
    fn proposed(&self, ratio: f64) -> bool {
        matches!(self, Axis::Floor { .. }) && ratio > 1.0 + 1e-9
    }
}

/// The candidate's error on an axis whose round's triplet q_a, q_b, q_c
/// (the candidate q_c its finest) does not converge monotonically, from a
/// fourth level q_d beyond the candidate (twice its elements, or half its
/// step) and the three finest (docs/theory.md §16.15):
///
///   R' = (q_c − q_d)/(q_b − q_c),
///   e_c = |q_c − q_d| / (1 − R')      0 ≤ R' < 1   (Richardson's)
///   e_c = |q_c − q_d|                 −1 < R' < 0  (the bound)           (16.22)
///
/// Where the errors shrink without changing sign the candidate's is that
/// of the middle level of a geometric sequence with ratio R'; where they
/// alternate and shrink, q* lies between q_c and q_d, so |q_c − q_d| bounds
/// the candidate's error, and is 1 + |R'| < 2 times it for a geometric
/// sequence (its |q_c − q_d|/(1 − R') would be the error itself, but with
/// |R'| near 1 the sequence is not known to be geometric: the jumper's
/// minimum at 0.2, 0.1, 0.05, 0.025 s alternates with R' −0.72 and that
/// estimate was 0.65 of its error). Where |R'| ≥ 1 (or q_b = q_c ≠ q_d)
/// the candidate's neighbours do not show convergence: the error is the
/// larger of the two changes about it, max(|q_b − q_c|, |q_c − q_d|), and
/// the axis is not converged.
pub fn fourth_level(values: [f64; 4]) -> Axis {
    let [_, qb, qc, qd] = values;
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (into, out) = (qb - qc, qc - qd);
    if out.abs() <= super::error_estimate::AGREE * scale {
        return Axis::Fourth { error: out.abs(), ratio: None, converges: true, values };
    }
    let ratio = (into.abs() > super::error_estimate::AGREE * scale).then(|| out / into);
    match ratio {
        Some(r) if (0.0..1.0).contains(&r) => {
            Axis::Fourth { error: out.abs() / (1.0 - r), ratio, converges: true, values }
        }
        Some(r) if r > -1.0 => Axis::Fourth { error: out.abs(), ratio, converges: true, values },
        _ => Axis::Fourth { error: into.abs().max(out.abs()), ratio, converges: false, values },
    }
}

/// One quantity's model (16.17) from a round of pilots.
#[derive(Debug, Clone, PartialEq)]
pub struct QuantityModel {
    pub quantity: Quantity,
    /// The quantity its error is relative to (16.18).
    pub relative_to: Quantity,
    /// |q_s| of `relative_to` at the round's shared pilot (its candidate).
    pub scale: f64,
    pub mesh: Axis,
    pub step: Axis,
}

impl QuantityModel {
    /// E(n, Δt) of (16.17) about the round's base (n₀, Δt₀); where the two
    /// axes' errors have opposite signs, the larger of them (16.23): their
    /// sum is no larger, and a bound that adds them counts the cancellation
    /// as error (the steel catenary's minimum, +18.6 and −12.4 N estimated,
    /// 31 N added against an error of 1.9 N).
    pub fn error(&self, base: (usize, f64), n: usize, dt: f64) -> Option<f64> {
        let (h, t) = (self.mesh.error_at(base.0 as f64 / n as f64)?, self.step.error_at(dt / base.1)?);
        // errors of opposite signs (16.23): their sum is no larger than the larger of them
        if self.mesh.sign() * self.step.sign() < 0.0 {
            return Some(h.max(t));
        }
        Some(h + t)
    }
}

/// The error of one quantity at the chosen numerics.
#[derive(Debug, Clone, PartialEq)]
pub struct Predicted {
    pub quantity: Quantity,
    pub relative_to: Quantity,
    /// E of (16.17), in the quantity's unit.
    pub error: f64,
    /// E / |q_s|.
    pub relative: f64,
    pub mesh_order: Option<f64>,
    pub step_order: Option<f64>,
}

/// What `accuracy` chose, and the measurement it chose from.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    pub target: f64,
    pub quantity: AccuracyQuantity,
    pub n_elements: usize,
    pub time_step: f64,
    pub newton_tolerance: f64,
    pub pinned: Pinned,
    /// Each quantity's estimated error at the choice.
    pub predicted: Vec<Predicted>,
    /// The rounds of pilots, the first at the scene's numerics.
    pub rounds: Vec<ErrorEstimate>,
    /// What did not converge, or where the target is not met, with numbers.
    pub notes: Vec<String>,
    /// The pilots' elapsed time, s.
    pub wall_s: f64,
    /// A system's lines' names (their quantities' labels) and its mesh in
    /// words (each line's elements at the chosen level); empty and None for one line.
    pub line_names: Vec<String>,
    pub mesh_words: Option<String>,
}

impl Choice {
    /// The largest relative error estimated at the choice.
    pub fn estimate(&self) -> f64 {
        self.predicted.iter().map(|p| p.relative).fold(0.0, f64::max)
    }

    /// The estimate meets the target.
    pub fn met(&self) -> bool {
        self.estimate() <= self.target
    }

    /// The pilots run, all rounds (those an earlier round's reused not counted).
    pub fn pilots(&self) -> usize {
        self.rounds.iter().flat_map(|r| &r.pilots).filter(|p| !p.reused).count()
    }

    /// One line: the choice, its estimate and what it cost.
    pub fn describe(&self) -> String {
        let orders: Vec<String> = self
            .predicted
            .iter()
            .filter(|p| p.quantity == p.relative_to)
            .map(|p| {
                let o = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.2}"));
                format!("{} mesh {} step {}", p.quantity.label(&self.line_names), o(p.mesh_order), o(p.step_order))
            })
            .collect();
        format!(
            "accuracy {:e} on {}: {}{}, time_step {} s{}, newton_tolerance {:e}{}; estimated error {:.2e} \
             (orders: {}); {} pilots in {} round(s), {:.1} s",
            self.target,
            self.quantity.name(),
            self.mesh_words.clone().unwrap_or_else(|| format!("n_elements {}", self.n_elements)),
            if self.pinned.n_elements { " (yours)" } else { "" },
            self.time_step,
            if self.pinned.time_step { " (yours)" } else { "" },
            self.newton_tolerance,
            if self.pinned.newton_tolerance { " (yours)" } else { "" },
            self.estimate(),
            orders.join("; "),
            self.pilots(),
            self.rounds.len(),
            self.wall_s
        )
    }

    /// The warning where the estimate at the choice is above the target.
    pub fn warning(&self) -> Option<String> {
        (!self.met()).then(|| {
            let why = if self.pinned.n_elements || self.pinned.time_step {
                "with the numerics you set"
            } else {
                "with the finest numerics the pilots reached"
            };
            format!(
                "accuracy {:e}: {why} the estimated error is {:.2e}, above the target{}",
                self.target,
                self.estimate(),
                if self.notes.is_empty() { String::new() } else { format!(" ({})", self.notes.join("; ")) }
            )
        })
    }
}

/// The models of `criteria` from a round's pilots.
fn models(
    round: &ErrorEstimate,
    criteria: &[(Quantity, Quantity)],
    target: f64,
) -> Result<Vec<QuantityModel>, AccuracyError> {
    criteria
        .iter()
        .map(|&(q, s)| {
            let e = round.of(q).ok_or_else(|| AccuracyError::NotMeasured {
                quantity: q.name().into_owned(),
                why: if round.notes.is_empty() {
                    "no value over their window".to_string()
                } else {
                    round.notes.join("; ")
                },
            })?;
            // the value at the pilot both triplets share (a round's candidate), not the
            // extrapolation: a triplet far from its asymptotic range extrapolates anywhere (the lazy
            // wave's steps of 6.4, 3.2, 1.6 s: q* −1.1e5 N of a 2.2e4 N top tension), and the
            // difference is of the order of the error itself (docs/theory.md §16.15)
            let shared = |x: &super::error_estimate::Estimate| x.step.values[2].abs();
            let scale = round.of(s).map_or(shared(e), shared);
            let allowed = target * scale / SAFETY;
            Ok(QuantityModel {
                quantity: q,
                relative_to: s,
                scale,
                mesh: Axis::of(&e.mesh, allowed),
                step: Axis::of(&e.step, allowed),
            })
        })
        .collect()
}

/// Rounds `x` to three significant digits.
fn round3(x: f64) -> f64 {
    let m = 10f64.powi(2 - x.abs().log10().floor() as i32);
    (x * m).round() / m
}

/// The candidate meshes about a base of `n0` elements (every whole number
/// from n₀/4 to 16 n₀ that `fits`: a line's with nodes on its buoyancy
/// sections' ends).
fn meshes(fits: &dyn Fn(usize) -> bool, n0: usize, pinned: bool) -> Vec<usize> {
    if pinned {
        return vec![n0];
    }
    let lo = (n0 / 4).max(2);
    let hi = (16 * n0).min(MAX_ELEMENTS);
    (lo..=hi).filter(|&n| fits(n)).collect()
}

/// The candidate steps about a base of `dt0` s (Δt₀ 2^{−k/4}, k from −8
/// to 16, three significant digits).
fn steps(dt0: f64, pinned: bool) -> Vec<f64> {
    if pinned {
        return vec![dt0];
    }
    // the pilots' own levels exact (k a multiple of 4), the others rounded
    (-8..=16)
        .map(|k: i32| if k % 4 == 0 { dt0 * 0.5f64.powi(k / 4) } else { round3(dt0 * STEP_RATIO.powi(-k)) })
        .filter(|&dt| dt >= MIN_STEP)
        .collect()
}

/// The cheapest (n, Δt) of (16.18) about `base`, or None; with
/// `proposals`, coarser levels of an axis at its floor count
/// ([`Axis::Floor`]: the next round measures them).
fn cheapest(
    models: &[QuantityModel],
    target: f64,
    (layout, base): (Layout, (usize, f64)),
    (meshes, steps): (&[usize], &[f64]),
    proposals: bool,
) -> Option<(usize, f64)> {
    let mut best: Option<(f64, usize, f64)> = None;
    for &n in meshes {
        for &dt in steps {
            if !proposals && !measured(layout, base, n, dt) {
                continue;
            }
            let cost = n as f64 / dt;
            if best.is_some_and(|b| b.0 <= cost) {
                continue;
            }
            let (rh, rt) = (base.0 as f64 / n as f64, dt / base.1);
            let ok = models.iter().all(|m| {
                (proposals || !(m.mesh.proposed(rh) || m.step.proposed(rt)))
                    && m.error(base, n, dt).is_some_and(|e| e <= target * m.scale / SAFETY)
            });
            if ok {
                best = Some((cost, n, dt));
            }
        }
    }
    best.map(|b| (b.1, b.2))
}

/// Measured by the round's pilots: within them, n₀ ≤ n ≤ 4n₀ and Δt₀/4 ≤
/// Δt ≤ Δt₀ ([`Layout::Base`]); on one of their triplets' lines, at 4n₀ or
/// at Δt₀/4, ([`Layout::Corner`]: a level off them is a proposal that a
/// round with it as its candidate measures, the mesh's and the step's
/// errors not counted on to add away from where both were run).
fn measured(layout: Layout, base: (usize, f64), n: usize, dt: f64) -> bool {
    let (mesh_in, step_in) = in_span(base, n, dt);
    match layout {
        Layout::Base => mesh_in && step_in,
        Layout::Corner => {
            let on_step_line = n == 4 * base.0;
            let on_mesh_line = (dt / (base.1 / 4.0) - 1.0).abs() < 1e-9;
            mesh_in && step_in && (on_step_line || on_mesh_line)
        }
    }
}

/// Within the round's pilots: n₀ ≤ n ≤ 4n₀ and Δt₀/4 ≤ Δt ≤ Δt₀.
fn in_span(base: (usize, f64), n: usize, dt: f64) -> (bool, bool) {
    let eps = 1e-9;
    (n >= base.0 && n <= 4 * base.0, dt <= base.1 * (1.0 + eps) && dt >= base.1 / 4.0 * (1.0 - eps))
}

/// An observed order below this, where the scheme is second order in both
/// the step (generalized-α) and the mesh, is not taken as the asymptotic
/// range: the triplet's extrapolation to the candidate is checked by a
/// fourth level where it matters (`ambiguous`).
pub const SLOW_ORDER: f64 = 1.0;

/// A step triplet's observed order above this, where generalized-α is
/// second order, is not taken as the asymptotic range either: its coarse
/// level's error is of what the finer steps have resolved (the catenary at
/// 16 elements, 0.8, 0.4, 0.2 s: order 3.9, Richardson's error at 0.2 s
/// 2 N where it is 15 N; docs/theory.md §16.16). A fourth level checks it.
pub const FAST_STEP_ORDER: f64 = 3.0;

/// Whether an axis' error at a round's candidate (a quarter of the base)
/// is ambiguous, so that a fourth level beyond the candidate decides it
/// (16.22): not monotone above the floor ([`Axis::Unconverged`] with a
/// change), or monotone with an observed order below [`SLOW_ORDER`] (on
/// the step axis, `step`, or above [`FAST_STEP_ORDER`]) and an
/// extrapolated error at the candidate above the floor ([`FLOOR_FRACTION`]
/// of `allowed`).
fn ambiguous(axis: &Axis, allowed: f64, step: bool) -> bool {
    match *axis {
        Axis::Unconverged { error, .. } => error > 0.0,
        Axis::Power { e0, order, .. } => {
            (order < SLOW_ORDER || (step && order > FAST_STEP_ORDER))
                && e0 * 0.25f64.powf(order) > FLOOR_FRACTION * allowed
        }
        _ => false,
    }
}

/// The fourth levels of a round of [`Layout::Corner`] about `candidate`
/// (n_c, Δt_c) on the axes where a quantity of the target does not
/// converge monotonically above the floor ([`Axis::Unconverged`]): the
/// mesh (2n_c, Δt_c), the step (n_c, Δt_c/2), run (or taken from `known`)
/// and added to the round's pilots; those axes' models become
/// [`Axis::Fourth`] (16.22). A fourth level run for one quantity checks
/// every other's monotone triplet on its axis: where it contradicts it
/// (the change out of the candidate not smaller than the change into it,
/// or of the other sign) that axis is [`Axis::Fourth`] too (the cable's
/// minimum tension at 0.2, 0.1, 0.05 s was monotone of order 2.2 and
/// 0.025 s moved it four times the last change: docs/theory.md §16.16).
/// Returns what it could not run.
fn fourth_levels(
    problem: &Problem,
    round: &mut ErrorEstimate,
    models: &mut [QuantityModel],
    (n, dt): (usize, f64),
    (target, tolerance): (f64, f64),
    threads: usize,
    known: &[Pilot],
) -> Vec<String> {
    let needs = |axis: fn(&QuantityModel) -> Axis, step: bool| {
        models.iter().any(|m| ambiguous(&axis(m), target * m.scale / SAFETY, step))
    };
    let mut levels = Vec::new();
    if needs(|m| m.mesh, false) && 2 * n <= MAX_ELEMENTS && (problem.fits)(2 * n) {
        levels.push((2 * n, dt));
    }
    if needs(|m| m.step, true) && dt / 2.0 >= MIN_STEP {
        levels.push((n, dt / 2.0));
    }
    if levels.is_empty() {
        return Vec::new();
    }
    let start = std::time::Instant::now();
    let plan = round.plan;
    let same = |p: &Pilot, (ne, h): (usize, f64)| p.n_elements == ne && (p.time_step / h - 1.0).abs() < 1e-12;
    let run = |l: (usize, f64)| match known.iter().find(|p| same(p, l)) {
        Some(p) => Ok(Pilot { wall_s: 0.0, reused: true, ..p.clone() }),
        None => problem.runs.run(&plan, l.0, l.1, tolerance),
    };
    let results: Vec<((usize, f64), Result<Pilot, RiserError>)> = if threads > 1 && levels.len() > 1 {
        std::thread::scope(|s| {
            let handles: Vec<_> = levels.iter().map(|&l| (l, s.spawn(move || run(l)))).collect();
            handles
                .into_iter()
                .map(|(l, h)| {
                    let r = h.join().unwrap_or_else(|_| {
                        Err(RiserError::Unsupported("an error estimate's pilot thread stopped".to_string()))
                    });
                    (l, r)
                })
                .collect()
        })
    } else {
        levels.iter().map(|&l| (l, run(l))).collect()
    };
    let mut notes = Vec::new();
    for ((ne, h), r) in results {
        let pilot = match r {
            Ok(p) => p,
            Err(e) => {
                notes.push(format!("the fourth level's pilot at {ne} elements, time_step {h} s failed ({e})"));
                continue;
            }
        };
        let mesh = ne != n;
        for m in models.iter_mut() {
            let axis = if mesh { &mut m.mesh } else { &mut m.step };
            let is_ambiguous = ambiguous(axis, target * m.scale / SAFETY, !mesh);
            let checked = matches!(axis, Axis::Power { .. });
            if !is_ambiguous && !checked {
                continue;
            }
            let (Some(slot), Some(e)) = (round.quantities.iter().position(|q| *q == m.quantity), round.of(m.quantity))
            else {
                continue;
            };
            let [qa, qb, qc] = if mesh { e.mesh.values } else { e.step.values };
            let qd = pilot.values[slot];
            if !qd.is_finite() {
                continue;
            }
            let fourth = fourth_level([qa, qb, qc, qd]);
            // a monotone triplet the fourth level (run for another quantity) contradicts: the
            // change out of the candidate not smaller than the change into it, or of the other sign
            let contradicts = match fourth {
                Axis::Fourth { converges, ratio, .. } => !converges || ratio.is_some_and(|r| r < 0.0),
                _ => false,
            };
            if is_ambiguous || contradicts {
                *axis = fourth;
            }
        }
        round.pilots.push(pilot);
    }
    round.wall_s += start.elapsed().as_secs_f64();
    notes
}

/// The base (n₀, Δt₀) of the round of [`Layout::Corner`] whose candidate,
/// its finest pilot (4n₀, Δt₀/4), is `(n, dt)` or the least finer mesh
/// whose quarter has nodes on the buoyancy sections' ends.
fn corner_base(fits: &dyn Fn(usize) -> bool, (n, dt): (usize, f64)) -> (usize, f64) {
    let lo = n.div_ceil(4).max(MIN_BASE_ELEMENTS);
    let m = (lo..=n.max(lo)).find(|&m| fits(m)).unwrap_or(lo);
    (m, dt * 4.0)
}

/// The bases the first round tries, and the layout of their pilots. With
/// neither mesh nor step set by the user: rounds of [`Layout::Corner`],
/// the first about the candidate [`FIRST_CANDIDATE_COARSENING`] coarser than
/// the scene's numerics, then (its pilots failing: a step too long for
/// Newton) the scene's own. Numerics the user set: [`Layout::Base`] about
/// them, the axis set one level.
fn first_bases(fits: &dyn Fn(usize) -> bool, (n, dt): (usize, f64), pinned: Pinned) -> (Layout, Vec<(usize, f64)>) {
    if pinned.n_elements || pinned.time_step {
        return (Layout::Base, vec![(n, dt)]);
    }
    let k = FIRST_CANDIDATE_COARSENING;
    let mut bases = vec![corner_base(fits, (n.div_ceil(k), dt * k as f64))];
    let own = corner_base(fits, (n, dt));
    if !bases.contains(&own) {
        bases.push(own);
    }
    (Layout::Corner, bases)
}

/// A choice and the round's models it was made from.
#[derive(Clone)]
struct Pick {
    numerics: (usize, f64),
    models: Vec<QuantityModel>,
    base: (usize, f64),
    /// The round's index in the rounds.
    round: usize,
}

/// The numerics of `scene` (its `accuracy` set) that meet its target on the
/// run `spec`, measured by pilots on up to `threads` threads; `progress`
/// hears of each round as it starts.
pub fn choose(
    scene: &Scene,
    spec: &RunSpec,
    pinned: Pinned,
    threads: usize,
    progress: &mut dyn FnMut(&str),
) -> Result<Choice, RiserError> {
    let fits = |n: usize| nodes_on_buoyancy_ends(scene, n);
    let problem = Problem {
        runs: &LinePilots { scene, spec },
        analysis: &scene.analysis,
        mesh: scene.analysis.n_elements,
        criteria: criteria(scene.analysis.accuracy_quantity, scene, spec.fatigue.is_some())?,
        fits: &fits,
        line_names: &[],
    };
    choose_on(&problem, pinned, threads, progress)
}

/// What [`choose_on`] measures: a scene's pilots, its numerics and the
/// quantities its target is on.
pub struct Problem<'a> {
    pub runs: &'a dyn PilotRuns,
    /// The target (`accuracy`, `accuracy_quantity`), the scene's step and
    /// Newton tolerance.
    pub analysis: &'a crate::scene::Analysis,
    /// The scene's mesh (a line's elements, a system's level).
    pub mesh: usize,
    /// The quantities the target is on, each with the one its error is relative to (16.18).
    pub criteria: Vec<(Quantity, Quantity)>,
    /// Whether a mesh may be chosen (a line's: nodes on its buoyancy sections' ends).
    pub fits: &'a dyn Fn(usize) -> bool,
    /// A system's lines' names (empty for one line).
    pub line_names: &'a [String],
}

/// [`choose`] of any scene's pilots (one line, a system: docs/theory.md §16.14).
pub fn choose_on(
    problem: &Problem,
    pinned: Pinned,
    threads: usize,
    progress: &mut dyn FnMut(&str),
) -> Result<Choice, RiserError> {
    let Problem { runs, analysis, criteria, fits, line_names, .. } = problem;
    let target = analysis.accuracy;
    let quantity = analysis.accuracy_quantity;
    let tolerance = if pinned.newton_tolerance { analysis.newton_tolerance } else { newton_tolerance_for(target) };
    let scene_numerics = (problem.mesh, analysis.time_step);
    let (layout, starts) = first_bases(fits, scene_numerics, pinned);
    let mut starts = starts.into_iter();
    let mut base = starts.next().unwrap_or(scene_numerics);
    let mut rounds: Vec<ErrorEstimate> = Vec::new();
    // each round's models (its fourth levels' in them)
    let mut round_models: Vec<Vec<QuantityModel>> = Vec::new();
    let mut notes = Vec::new();
    let start = std::time::Instant::now();
    // the finest pilot of a round about `base` (the numerics the user set kept)
    let finest = |base: (usize, f64)| {
        (if pinned.n_elements { base.0 } else { 4 * base.0 }, if pinned.time_step { base.1 } else { base.1 / 4.0 })
    };
    // the cheapest choice of all rounds that rests on measured levels
    // within its round's pilots (16.17 between them, no extrapolation)
    let mut best: Option<Pick> = None;
    let cost = |(n, dt): (usize, f64)| n as f64 / dt;
    loop {
        let duration = runs.plan().duration;
        let work: f64 = layout.levels(base.0, base.1).0.iter().map(|&(n, dt)| n as f64 * (duration / dt).ceil()).sum();
        // the numerics the round measures: its base, or its candidate (the finest pilot)
        let about = match layout {
            Layout::Base => base,
            Layout::Corner => (4 * base.0, base.1 / 4.0),
        };
        if !rounds.is_empty() && work > MAX_ROUND_WORK && best.is_some() {
            notes.push(format!(
                "round {} of pilots about {} elements at {} s ({work:.2e} element-steps) is beyond the bound of \
                 {MAX_ROUND_WORK:.1e}: the choice of the rounds before kept",
                rounds.len() + 1,
                about.0,
                about.1
            ));
            break;
        }
        progress(&format!(
            "accuracy {target:e}: round {} of pilots about {} elements, time_step {} s (5 runs of {duration:.0} s, \
             {work:.2e} element-steps)",
            rounds.len() + 1,
            about.0,
            about.1,
        ));
        let known: Vec<_> = rounds.iter().flat_map(|r| r.pilots.iter().filter(|p| !p.reused).cloned()).collect();
        let round = match estimate_on(*runs, (base.0, base.1, tolerance), threads, layout, &known) {
            Ok(r) => r,
            // a later round's pilots failed (too coarse a step): the choice so far
            Err(e) if best.is_some() => {
                notes.push(format!(
                    "round {} of pilots failed ({e}): the choice of the rounds before kept",
                    rounds.len() + 1
                ));
                break;
            }
            // the first round about a candidate coarser than the scene's
            // numerics failed: the next start
            Err(e) if rounds.is_empty() => match starts.next() {
                Some(next) => {
                    notes.push(format!(
                        "the first round of pilots about {} elements at {} s failed ({e}): started about {} \
                         elements at {} s",
                        about.0,
                        about.1,
                        4 * next.0,
                        next.1 / 4.0
                    ));
                    base = next;
                    continue;
                }
                None => return Err(e),
            },
            Err(e) => return Err(e),
        };
        let mut round = round;
        let mut models = models(&round, criteria, target)?;
        if layout == Layout::Corner {
            let candidate = (4 * base.0, base.1 / 4.0);
            notes.extend(fourth_levels(
                problem,
                &mut round,
                &mut models,
                candidate,
                (target, tolerance),
                threads,
                &known,
            ));
        }
        rounds.push(round);
        round_models.push(models.clone());
        let ladders = (&meshes(fits, base.0, pinned.n_elements)[..], &steps(base.1, pinned.time_step)[..]);
        if let Some(numerics) = cheapest(&models, target, (layout, base), ladders, false)
            && best.as_ref().is_none_or(|b| cost(numerics) < cost(b.numerics))
        {
            best = Some(Pick { numerics, models: models.clone(), base, round: rounds.len() - 1 });
        }
        // beyond the pilots: a proposal the next round measures, if it is cheaper
        let Some((n, dt)) = cheapest(&models, target, (layout, base), ladders, true) else {
            // nothing this round's pilots reach meets the target: a round about
            // finer numerics, on the axes that do not converge or whose error at the
            // finest level the round measured is above half the allowed one (both if none)
            let finest_ratio = match layout {
                Layout::Base => 1.0,
                Layout::Corner => 0.25,
            };
            let refine = |axis: fn(&QuantityModel) -> Axis| {
                models.iter().any(|m| {
                    let a = axis(m);
                    a.unconverged() || a.error_at(finest_ratio).is_none_or(|e| e > 0.5 * target * m.scale / SAFETY)
                })
            };
            let (mesh, step) = (refine(|m| m.mesh), refine(|m| m.step));
            let either = !(mesh || step);
            let next = (
                if !pinned.n_elements && (mesh || either) { 2 * base.0 } else { base.0 },
                if !pinned.time_step && (step || either) { base.1 / 2.0 } else { base.1 },
            );
            if rounds.len() >= MAX_ROUNDS || next == base || best.is_some() {
                break;
            }
            base = next;
            continue;
        };
        if rounds.len() >= MAX_ROUNDS || best.as_ref().is_some_and(|b| cost(b.numerics) <= cost((n, dt))) {
            break;
        }
        let next = match layout {
            // an axis outside the span moves there
            Layout::Base => {
                let (mesh_in, step_in) = in_span(base, n, dt);
                (if mesh_in { base.0 } else { n }, if step_in { base.1 } else { dt })
            }
            // the proposal the next round's candidate
            Layout::Corner => corner_base(fits, (n, dt)),
        };
        if next == base {
            break;
        }
        base = next;
    }
    let pick = match best {
        Some(p) => p,
        None => {
            // the target beyond what the pilots' levels reach: the last round's finest
            let round = rounds.len() - 1;
            let models = round_models[round].clone();
            notes.push(format!(
                "no mesh and step within the pilots of {} round(s) is estimated to meet the target: the finest \
                 pilot's numerics taken",
                rounds.len()
            ));
            Pick { numerics: finest(base), models, base, round }
        }
    };
    let Pick { numerics: (n, dt), models, base, round } = pick;
    let predicted = models
        .iter()
        .map(|m| {
            let error = m.error(base, n, dt).unwrap_or(f64::NAN);
            Predicted {
                quantity: m.quantity,
                relative_to: m.relative_to,
                error,
                relative: error / m.scale,
                mesh_order: m.mesh.order(),
                step_order: m.step.order(),
            }
        })
        .collect();
    // what does not converge where it decides the choice, with its numbers
    let (mesh_levels, step_levels) = match layout {
        Layout::Base => ("mesh (n, 2n, 4n elements)", "step (dt, dt/2, dt/4)"),
        Layout::Corner => ("mesh (n/4, n/2, n elements)", "step (4dt, 2dt, dt)"),
    };
    for m in &models {
        let Some(e) = rounds[round].of(m.quantity) else { continue };
        for (axis, t, what, finer) in
            [(m.mesh, &e.mesh, mesh_levels, "2n elements"), (m.step, &e.step, step_levels, "dt/2")]
        {
            let label = m.quantity.label(line_names);
            match (axis, t.note(what)) {
                (Axis::Unconverged { .. }, Some(note)) => notes.push(format!("{label}: {note}")),
                (Axis::Fourth { error, ratio, converges, values }, _) => {
                    let r = ratio.map_or("undefined".to_string(), |r| format!("{r:.3}"));
                    notes.push(format!(
                        "{label}: {what}: not monotone ({}, R = {}): {:.6e}, {:.6e}, {:.6e}; a fourth level ({finer}): \
                         {:.6e}; {}",
                        t.class.name(),
                        t.ratio.map_or("undefined".to_string(), |r| format!("{r:.3}")),
                        values[0],
                        values[1],
                        values[2],
                        values[3],
                        if converges {
                            format!("the three finest converge (R' = {r}), the candidate's error {error:.3e} (16.22)")
                        } else {
                            format!(
                                "the three finest do not converge either (R' = {r}): the larger change about the \
                                 candidate taken, {error:.3e}"
                            )
                        }
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(Choice {
        target,
        quantity,
        n_elements: n,
        time_step: dt,
        newton_tolerance: tolerance,
        pinned,
        predicted,
        rounds,
        notes,
        wall_s: start.elapsed().as_secs_f64(),
        line_names: line_names.to_vec(),
        mesh_words: None,
    })
}

/// `scene` with the numerics its `accuracy` chooses on `spec` (the scene
/// itself, None, where it has none).
pub fn apply(
    scene: Scene,
    spec: &RunSpec,
    pinned: Pinned,
    threads: usize,
    progress: &mut dyn FnMut(&str),
) -> Result<(Scene, Option<Choice>), RiserError> {
    if scene.analysis.accuracy == 0.0 {
        return Ok((scene, None));
    }
    let choice = choose(&scene, spec, pinned, threads, progress)?;
    let mut scene = scene;
    scene.analysis.n_elements = choice.n_elements;
    scene.analysis.time_step = choice.time_step;
    scene.analysis.newton_tolerance = choice.newton_tolerance;
    Ok((scene, Some(choice)))
}

/// The run the choice is made for where the motion is not known (the FMU,
/// whose master moves the vessel; `riser statics`): the design motion, a
/// heave of `accuracy_motion_amplitude` (default 2.5 m) at
/// `accuracy_motion_period` (default 10 s) grown over one period, in the
/// scene's sea and current; the window from the end of the slower of the
/// motion's ramp and period and the sea's, of three periods of the slower
/// (twenty of an irregular sea's T_p: [`super::error_estimate::pilot_periods`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignRun {
    pub heave: super::Heave,
    pub window: (f64, f64),
    pub period: f64,
    /// The scene's sea is irregular.
    pub irregular: bool,
}

impl DesignRun {
    /// [`apply`] on the design run of `scene` (the scene itself, None,
    /// where it has no `accuracy`).
    pub fn apply(
        scene: Scene,
        pinned: Pinned,
        threads: usize,
        progress: &mut dyn FnMut(&str),
    ) -> Result<(Scene, Option<Choice>), RiserError> {
        if scene.analysis.accuracy == 0.0 {
            return Ok((scene, None));
        }
        let design = DesignRun::of(&scene)?;
        let heave = design.heave;
        let motion = move |t: f64| heave.at(t);
        let spec = RunSpec {
            motion: &motion,
            window: design.window,
            period: Some(design.period),
            irregular: design.irregular,
            max_tangent_age: crate::model::DynamicOptions::default().max_tangent_age,
            fatigue: None,
        };
        apply(scene, &spec, pinned, threads, progress)
    }

    pub fn of(scene: &Scene) -> Result<DesignRun, RiserError> {
        let a = scene.analysis.accuracy_motion_amplitude.unwrap_or(crate::scene::DESIGN_MOTION_AMPLITUDE);
        let t = scene.analysis.accuracy_motion_period.unwrap_or(crate::scene::DESIGN_MOTION_PERIOD);
        let sea = crate::loads::waves::ramp_and_period(scene).map_err(|e| RiserError::Unsupported(e.to_string()))?;
        let settled = sea.map_or(2.0 * t, |(r, p)| (2.0 * t).max(r + p));
        let settled = settled.max(crate::loads::current_ramp(scene).duration);
        let period = sea.map_or(t, |(_, p)| t.max(p));
        let irregular = crate::loads::waves::irregular(scene);
        Ok(DesignRun {
            heave: super::Heave { amplitude: a, period: t, until: None, ramp: t },
            window: (settled, settled + super::error_estimate::pilot_periods(irregular) * period),
            period,
            irregular,
        })
    }
}
