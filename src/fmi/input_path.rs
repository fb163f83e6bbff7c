//! The hang-off's path through a communication step (docs/theory.md §7).
//!
//! FMI 2.0 Co-Simulation: the inputs set before `fmi2DoStep(t, h)` are the
//! master's values **at t**. The FMU must move the hang-off over [t, t + h]
//! knowing only the inputs up to t (causal), without a lag of one step, and
//! along a smooth path: at these frequencies the line is axially stiff, so a
//! kink or a wobble of the path at the communication step's period launches
//! axial waves that ring in the tension.
//!
//! Per axis, the step's end state is predicted from the latest five pieces of
//! information the master gave, the polynomial P of degree ≤ 4 (τ = s − t)
//!
//!   P(0) = u(t),  then P'(0), P''(0) if given, then the past communication
//!   points t_k < t, newest first: P(t_k − t) = u(t_k)  (or P'(t_k − t) =
//!   v(t_k) when the velocity input is connected),                         (7.1)
//!
//! and the path over the step is the quintic Hermite interpolant from the
//! hang-off's current position, velocity and acceleration (p, p', p'') at
//! τ = 0 to (P, P', P'') at τ = h:
//!
//!   x(τ) = p H0(σ) + h p' H1(σ) + h² p'' H2(σ)
//!        + P(h) H0(1−σ) − h P'(h) H1(1−σ) + h² P''(h) H2(1−σ),   σ = τ/h,  (7.2)
//!
//! with H0 = 1 − 10σ³ + 15σ⁴ − 6σ⁵, H1 = σ − 6σ³ + 8σ⁴ − 3σ⁵,
//! H2 = ½σ² − 3/2 σ³ + 3/2 σ⁴ − ½σ⁵ (value, slope, curvature 1 at σ = 0 in
//! turn, all zero at σ = 1). The path is C2 at every communication point, and
//! since the end states of successive steps are samples of one smooth curve
//! (P(h) differs from u(t + h) by a smooth O(h⁵) error), the path has no
//! wobble at the communication step's period beyond that order.
//!
//! Sources, per axis, in order of precedence for P'(0) and P''(0):
//! 1. input derivatives (`fmi2SetRealInputDerivatives`, orders 1 and 2) set
//!    for this step;
//! 2. the velocity input, once it has been non-zero (a velocity input left
//!    at 0 means "follow the displacement"); then the past conditions are the
//!    past velocities (while connected);
//! 3. the displacement history alone.
//!
//! Error: from the displacement history with five points known,
//! P(h) − u(t + h) = O(h⁵) (the error of a quartic extrapolation), its slope
//! O(h⁴) and curvature O(h³), so the hang-off is within O(h⁵) of the input at
//! every communication point; the unit tests below measure it. Fewer points
//! (the first four steps) give lower degrees. The price of the high degree is
//! that a jump in the input (not a physical motion) overshoots for four steps.

use crate::math::V3;
use crate::model::HangOff;
use nalgebra::{SMatrix, SVector};

/// Pieces of information that predict a step's end (the degree of (7.1) + 1).
const CONDITIONS: usize = 5;

/// Past communication points kept (one piece each beyond the current one).
const PAST: usize = CONDITIONS - 1;

/// Numbers per past sample in [`InputHistory::to_values`].
const SAMPLE_VALUES: usize = 8;

/// Numbers in [`InputHistory::to_values`].
pub const HISTORY_VALUES: usize = PAST * SAMPLE_VALUES + 11;

/// Inputs of one communication point, axes in input order (heave, surge, sway).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Displacement inputs, m.
    pub u: [f64; 3],
    /// Velocity inputs, m/s.
    pub v: [f64; 3],
    /// Per axis: the velocity input was connected at that point.
    pub connected: [bool; 3],
}

/// Where an axis' rates came from (for the log and the tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateSource {
    /// `fmi2SetRealInputDerivatives`.
    Derivatives,
    /// The velocity input.
    Velocity,
    /// The displacement history.
    History,
}

/// The quintic Hermite bases of (7.2) at σ and their first and second
/// derivatives in σ: `[[H0, H1, H2], [H0', H1', H2'], [H0'', H1'', H2'']]`.
fn hermite(sigma: f64) -> [[f64; 3]; 3] {
    let (s2, s3) = (sigma * sigma, sigma * sigma * sigma);
    let (s4, s5) = (s2 * s2, s2 * s3);
    [
        [
            1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5,
            sigma - 6.0 * s3 + 8.0 * s4 - 3.0 * s5,
            0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        ],
        [
            -30.0 * s2 + 60.0 * s3 - 30.0 * s4,
            1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4,
            sigma - 4.5 * s2 + 6.0 * s3 - 2.5 * s4,
        ],
        [
            -60.0 * sigma + 180.0 * s2 - 120.0 * s3,
            -36.0 * sigma + 96.0 * s2 - 60.0 * s3,
            1.0 - 9.0 * sigma + 18.0 * s2 - 10.0 * s3,
        ],
    ]
}

/// The hang-off's path over one communication step [t, t + h].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    t: f64,
    h: f64,
    /// Per axis (heave, surge, sway): the start (p, h p', h² p'').
    start: [[f64; 3]; 3],
    /// Per axis: the predicted end (P(h), h P'(h), h² P''(h)).
    end: [[f64; 3]; 3],
    /// Per axis: where P'(0) came from.
    pub sources: [RateSource; 3],
}

/// heave → z, surge → x, sway → y: the component of V3 for each input axis.
const COMPONENT: [usize; 3] = [2, 0, 1];

impl Path {
    /// The path of axis `i` and its first two derivatives in τ at time s
    /// (clamped to the step), by (7.2).
    fn axis(&self, i: usize, s: f64) -> [f64; 3] {
        let sigma = ((s - self.t) / self.h).clamp(0.0, 1.0);
        let (a, b) = (hermite(sigma), hermite(1.0 - sigma));
        let (p, e) = (&self.start[i], &self.end[i]);
        // the end's bases are mirrored: H(1 − σ), with the odd one (H1) negated
        let sign = [1.0, -1.0, 1.0];
        std::array::from_fn(|d| {
            let mirror = if d == 1 { -1.0 } else { 1.0 };
            let x: f64 = (0..3).map(|k| p[k] * a[d][k] + mirror * sign[k] * e[k] * b[d][k]).sum();
            x / self.h.powi(d as i32)
        })
    }

    /// Hang-off displacement and velocity at time s (clamped to the step).
    pub fn at(&self, s: f64) -> HangOff {
        let mut displacement = V3::zeros();
        let mut velocity = V3::zeros();
        for (i, &c) in COMPONENT.iter().enumerate() {
            let x = self.axis(i, s);
            displacement[c] = x[0];
            velocity[c] = x[1];
        }
        HangOff { displacement, velocity }
    }

    /// Hang-off acceleration at time s (clamped to the step), m/s².
    pub fn acceleration(&self, s: f64) -> V3 {
        let mut a = V3::zeros();
        for (i, &c) in COMPONENT.iter().enumerate() {
            a[c] = self.axis(i, s)[2];
        }
        a
    }

    /// The path's acceleration at the step's end, per input axis, m/s².
    fn end_acceleration(&self) -> [f64; 3] {
        std::array::from_fn(|i| self.end[i][2] / (self.h * self.h))
    }
}

/// Input derivatives set for the coming step (`fmi2SetRealInputDerivatives`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Derivatives {
    /// d/dt of heave, surge, sway (m/s), if set.
    pub first: [Option<f64>; 3],
    /// d²/dt² of heave, surge, sway (m/s²), if set; or d/dt of the velocity inputs.
    pub second: [Option<f64>; 3],
}

/// One condition of (7.1): the `order`-th derivative of P at τ equals `value`.
#[derive(Debug, Clone, Copy)]
struct Condition {
    tau: f64,
    order: usize,
    value: f64,
}

/// The input history that plans each step's path: everything needed to
/// continue bit for bit (it is part of the saved FMU state).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InputHistory {
    /// The last communication points, newest first; `count` are valid.
    past: [Sample; PAST],
    count: usize,
    /// Per axis: the velocity input has been non-zero (it is connected).
    velocity_connected: [bool; 3],
    /// Derivatives set since the last step.
    pub pending: Derivatives,
    /// The last path's acceleration at its end (the next one's start), m/s².
    end_acceleration: [f64; 3],
}

impl InputHistory {
    /// No history (just instantiated or reset).
    pub fn new() -> Self {
        Self::default()
    }

    /// Notes a velocity input's value: a non-zero value connects it.
    pub fn note_velocity(&mut self, axis: usize, value: f64) {
        if value != 0.0 {
            self.velocity_connected[axis] = true;
        }
    }

    /// The conditions (7.1) of axis `i` at time t, newest first, and the
    /// source of the slope.
    fn conditions(&self, i: usize, t: f64, u: f64, vin: f64) -> ([Option<Condition>; CONDITIONS], RateSource) {
        let mut out = [None; CONDITIONS];
        let mut n = 0;
        let mut push = |c: Condition| {
            if n < CONDITIONS {
                out[n] = Some(c);
                n += 1;
            }
        };
        push(Condition { tau: 0.0, order: 0, value: u });
        let source = if self.pending.first[i].is_some() {
            RateSource::Derivatives
        } else if self.velocity_connected[i] {
            RateSource::Velocity
        } else {
            RateSource::History
        };
        match source {
            RateSource::Derivatives => push(Condition { tau: 0.0, order: 1, value: self.pending.first[i].unwrap() }),
            RateSource::Velocity => push(Condition { tau: 0.0, order: 1, value: vin }),
            RateSource::History => {}
        }
        if let Some(a) = self.pending.second[i] {
            push(Condition { tau: 0.0, order: 2, value: a });
        }
        for s in &self.past[..self.count] {
            match source {
                RateSource::Velocity if s.connected[i] => push(Condition { tau: s.t - t, order: 1, value: s.v[i] }),
                // the velocities are contiguous: stop at the first point without one
                RateSource::Velocity => break,
                _ => push(Condition { tau: s.t - t, order: 0, value: s.u[i] }),
            }
        }
        (out, source)
    }

    /// Solves (7.1) for P in σ = τ/h and returns (P, h P', h² P'') at σ = 1:
    /// the predicted end of the step. Missing conditions lower the degree.
    fn predict(conditions: &[Option<Condition>; CONDITIONS], h: f64) -> [f64; 3] {
        let mut a = SMatrix::<f64, CONDITIONS, CONDITIONS>::zeros();
        let mut b = SVector::<f64, CONDITIONS>::zeros();
        for (row, c) in conditions.iter().enumerate() {
            match c {
                Some(c) => {
                    // d^order/dσ^order of σ^j, at σ = τ/h; the value scaled by h^order
                    let sigma = c.tau / h;
                    for j in c.order..CONDITIONS {
                        let falling: f64 = (0..c.order).map(|k| (j - k) as f64).product();
                        a[(row, j)] = falling * sigma.powi((j - c.order) as i32);
                    }
                    b[row] = c.value * h.powi(c.order as i32);
                }
                // fewer conditions: the highest coefficients are zero
                None => a[(row, row)] = 1.0,
            }
        }
        // distinct points and consecutive orders at τ = 0: A is regular
        let coef = a.lu().solve(&b).unwrap_or_else(|| {
            let mut c = SVector::zeros();
            c[0] = conditions[0].map_or(0.0, |c| c.value);
            c
        });
        let value = coef.sum();
        let slope: f64 = (1..CONDITIONS).map(|j| j as f64 * coef[j]).sum();
        let curvature: f64 = (2..CONDITIONS).map(|j| (j * (j - 1)) as f64 * coef[j]).sum();
        [value, slope, curvature]
    }

    /// The velocity the hang-off starts with at t0 (the line is at rest
    /// unless the master gives a velocity there).
    pub fn start_velocity(&self, vin: &[f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| match self.pending.first[i] {
            Some(v) => v,
            None if self.velocity_connected[i] => vin[i],
            None => 0.0,
        })
    }

    /// Plans the path over [t, t + h] from the hang-off's current motion
    /// `from` towards the prediction (7.1) from the inputs set for t.
    pub fn plan(&self, t: f64, h: f64, u: &[f64; 3], vin: &[f64; 3], from: &HangOff) -> Path {
        let mut sources = [RateSource::History; 3];
        let end = std::array::from_fn(|i| {
            let (conditions, source) = self.conditions(i, t, u[i], vin[i]);
            sources[i] = source;
            Self::predict(&conditions, h)
        });
        let start = std::array::from_fn(|i| {
            let c = COMPONENT[i];
            [from.displacement[c], h * from.velocity[c], h * h * self.end_acceleration[i]]
        });
        Path { t, h, start, end, sources }
    }

    /// Records the communication point t after a successful step along
    /// `path` from it: its inputs join the history and the pending
    /// derivatives are used up.
    pub fn commit(&mut self, t: f64, u: &[f64; 3], vin: &[f64; 3], path: &Path) {
        self.past.copy_within(0..PAST - 1, 1);
        self.past[0] = Sample { t, u: *u, v: *vin, connected: self.velocity_connected };
        self.count = (self.count + 1).min(PAST);
        self.pending = Derivatives::default();
        self.end_acceleration = path.end_acceleration();
    }

    /// The history as numbers (for the serialized FMU state).
    pub fn to_values(&self) -> [f64; HISTORY_VALUES] {
        let mut out = [0.0; HISTORY_VALUES];
        for (k, s) in self.past.iter().enumerate() {
            let o = SAMPLE_VALUES * k;
            out[o] = s.t;
            out[o + 1..o + 4].copy_from_slice(&s.u);
            out[o + 4..o + 7].copy_from_slice(&s.v);
            out[o + 7] = (0..3).map(|i| (s.connected[i] as u32) << i).sum::<u32>() as f64;
        }
        let o = PAST * SAMPLE_VALUES;
        out[o] = self.count as f64;
        let mut flags = 0u32;
        for i in 0..3 {
            flags |= (self.velocity_connected[i] as u32) << i;
            flags |= (self.pending.first[i].is_some() as u32) << (3 + i);
            flags |= (self.pending.second[i].is_some() as u32) << (6 + i);
            out[o + 2 + i] = self.pending.first[i].unwrap_or(0.0);
            out[o + 5 + i] = self.pending.second[i].unwrap_or(0.0);
            out[o + 8 + i] = self.end_acceleration[i];
        }
        out[o + 1] = flags as f64;
        out
    }

    /// The inverse of [`InputHistory::to_values`]; None if the numbers are
    /// not a history this version writes.
    pub fn from_values(x: &[f64]) -> Option<Self> {
        if x.len() != HISTORY_VALUES || x.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let small_int = |v: f64, below: f64| (v >= 0.0 && v < below && v.fract() == 0.0).then_some(v as u32);
        let bits = |m: u32| -> [bool; 3] { std::array::from_fn(|i| m >> i & 1 == 1) };
        let mut h = InputHistory::default();
        for k in 0..PAST {
            let o = SAMPLE_VALUES * k;
            let three = |j: usize| [x[o + j], x[o + j + 1], x[o + j + 2]];
            let mask = small_int(x[o + 7], 8.0)?;
            h.past[k] = Sample { t: x[o], u: three(1), v: three(4), connected: bits(mask) };
        }
        let o = PAST * SAMPLE_VALUES;
        h.count = small_int(x[o], (PAST + 1) as f64)? as usize;
        let flags = small_int(x[o + 1], 512.0)?;
        h.velocity_connected = bits(flags);
        for i in 0..3 {
            h.pending.first[i] = (flags >> (3 + i) & 1 == 1).then_some(x[o + 2 + i]);
            h.pending.second[i] = (flags >> (6 + i) & 1 == 1).then_some(x[o + 5 + i]);
            h.end_acceleration[i] = x[o + 8 + i];
        }
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hang_off(z: f64, vz: f64) -> HangOff {
        HangOff { displacement: V3::new(0.0, 0.0, z), velocity: V3::new(0.0, 0.0, vz) }
    }

    /// Drives the history with heave u(t) (and its velocity input `v`, when
    /// given) at communication points `times`, returning the hang-off at each
    /// point and the paths.
    fn drive(times: &[f64], u: impl Fn(f64) -> f64, v: Option<&dyn Fn(f64) -> f64>) -> (Vec<HangOff>, Vec<Path>) {
        let mut hist = InputHistory::new();
        let vel = |t: f64| v.map_or(0.0, |v| v(t));
        let mut at = hang_off(u(times[0]), vel(times[0]));
        let (mut points, mut paths) = (vec![at], vec![]);
        for w in times.windows(2) {
            let (t, h) = (w[0], w[1] - w[0]);
            let (inp, vin) = ([u(t), 0.0, 0.0], [vel(t), 0.0, 0.0]);
            hist.note_velocity(0, vin[0]);
            let path = hist.plan(t, h, &inp, &vin, &at);
            hist.commit(t, &inp, &vin, &path);
            at = path.at(t + h);
            points.push(at);
            paths.push(path);
        }
        (points, paths)
    }

    #[test]
    fn the_path_is_c2_at_communication_points_and_starts_where_the_hang_off_is() {
        let times: Vec<f64> = [0.0, 0.2, 0.5, 0.6, 1.0, 1.3, 1.4, 1.45, 1.9].to_vec();
        let (_, paths) = drive(&times, |t| 2.5 * (0.7 * t).sin() + 0.3 * t * t, None);
        for k in 0..paths.len() - 1 {
            let t = times[k + 1];
            let (a, b) = (paths[k].at(t), paths[k + 1].at(t));
            assert_eq!(a.displacement.z, b.displacement.z);
            assert!((a.velocity.z - b.velocity.z).abs() <= 1e-14, "{k}: {a:?} {b:?}");
            let (left, right) = (paths[k].acceleration(t).z, paths[k + 1].acceleration(t).z);
            assert!((left - right).abs() <= 1e-12 * left.abs().max(1.0), "{k}: {left} {right}");
            // the velocity and acceleration are the derivatives of the path
            let (e, s) = (1e-6, t - 0.5 * (t - times[k]));
            let fd = (paths[k].at(s + e).displacement.z - paths[k].at(s - e).displacement.z) / (2.0 * e);
            assert!((fd - paths[k].at(s).velocity.z).abs() < 1e-7, "{k}");
            let fd = (paths[k].at(s + e).velocity.z - paths[k].at(s - e).velocity.z) / (2.0 * e);
            assert!((fd - paths[k].acceleration(s).z).abs() < 1e-6, "{k}");
        }
    }

    #[test]
    fn a_quartic_input_is_followed_exactly_once_five_points_are_known() {
        let u = |t: f64| 1.0 - 0.4 * t + 0.9 * t * t - 0.3 * t.powi(3) + 0.05 * t.powi(4);
        let du = |t: f64| -0.4 + 1.8 * t - 0.9 * t * t + 0.2 * t.powi(3);
        let times = [0.0, 0.3, 0.5, 0.9, 1.0, 1.6, 1.7, 2.5];
        let (points, _) = drive(&times, u, None);
        for k in 5..times.len() {
            assert!((points[k].displacement.z - u(times[k])).abs() < 1e-11, "{k}");
            assert!((points[k].velocity.z - du(times[k])).abs() < 1e-10, "{k}");
        }
        // from the velocity inputs: the value now and the last four velocities
        let (points, _) = drive(&times, u, Some(&du));
        for k in 4..times.len() {
            assert!((points[k].displacement.z - u(times[k])).abs() < 1e-11, "{k}");
            assert!((points[k].velocity.z - du(times[k])).abs() < 1e-10, "{k}");
        }
    }

    #[test]
    fn the_error_at_communication_points_is_fifth_order_in_the_step() {
        // heave 2.5 sin(2πt/20): max |x − u| over 40 s at h and h/2
        let err = |h: f64| {
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let u = |t: f64| 2.5 * (2.0 * std::f64::consts::PI * t / 20.0).sin();
            let (points, _) = drive(&times, u, None);
            (10..times.len()).map(|k| (points[k].displacement.z - u(times[k])).abs()).fold(0.0, f64::max)
        };
        let (e1, e2) = (err(0.8), err(0.4));
        let order = (e1 / e2).log2();
        assert!((order - 5.0).abs() < 0.3, "{e1} {e2} order {order}");
        // closed form: the error of the quartic extrapolation is the fifth
        // backward difference, 2.5 (2 sin(θ/2))⁵ at most, θ = ωh
        let closed = |h: f64| 2.5 * (2.0 * (std::f64::consts::PI * h / 20.0).sin()).powi(5);
        assert!((e2 / closed(0.4) - 1.0).abs() < 0.01, "{e2} {}", closed(0.4));
    }

    #[test]
    fn derivatives_and_velocity_inputs_take_precedence_over_the_history() {
        let mut hist = InputHistory::new();
        let at = hang_off(0.0, 0.0);
        let path = hist.plan(0.0, 0.1, &[0.0; 3], &[0.0; 3], &at);
        hist.commit(0.0, &[0.0; 3], &[0.0; 3], &path);
        // a derivative and the history: P(0) = 0.2, P'(0) = 1.5, P''(0) = −2, P(−0.1) = 0
        hist.pending.first[0] = Some(1.5);
        hist.pending.second[0] = Some(-2.0);
        let h = 0.1;
        let path = hist.plan(0.1, h, &[0.2, 0.0, 0.0], &[0.0; 3], &at);
        assert_eq!(path.sources[0], RateSource::Derivatives);
        assert_eq!(path.sources[1], RateSource::History);
        // the cubic through those conditions, at τ = h
        let c3 = (0.0 - (0.2 - 1.5 * 0.1 - 1.0 * 0.01)) / -0.001;
        let end = path.at(0.2).displacement.z;
        assert!((end - (0.2 + 1.5 * h - h * h + c3 * h * h * h)).abs() < 1e-12, "{end}");
        hist.note_velocity(1, 0.7);
        let path = hist.plan(0.1, h, &[0.2, 0.0, 0.0], &[0.0, 0.7, 0.0], &at);
        assert_eq!(path.sources[1], RateSource::Velocity);
        hist.commit(0.1, &[0.2, 0.0, 0.0], &[0.0, 0.7, 0.0], &path);
        assert_eq!(hist.pending, Derivatives::default());
    }

    #[test]
    fn the_history_survives_its_numbers() {
        let mut hist = InputHistory::new();
        let at = hang_off(0.0, 0.0);
        for k in 0..6 {
            let t = 0.25 * k as f64;
            let u = [0.1 * t, 0.2 + t, 0.3 - t * t];
            if k == 3 {
                hist.note_velocity(2, -1.0);
            }
            let path = hist.plan(t, 0.25, &u, &[0.0, 0.0, -1.0], &at);
            hist.commit(t, &u, &[0.0, 0.0, -1.0], &path);
        }
        hist.pending.first[1] = Some(3.0);
        hist.pending.second[2] = Some(-4.0);
        let back = InputHistory::from_values(&hist.to_values()).unwrap();
        assert_eq!(back, hist);
        let mut bad = hist.to_values();
        bad[7] = 0.5;
        assert!(InputHistory::from_values(&bad).is_none());
        assert!(InputHistory::from_values(&bad[..20]).is_none());
    }
}
