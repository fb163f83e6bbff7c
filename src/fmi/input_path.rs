//! The hang-off's path through a communication step (docs/theory.md §7).
//!
//! FMI 2.0 Co-Simulation: the inputs set before `fmi2DoStep(t, h)` are the
//! master's values **at t**. The FMU must move the hang-off over [t, t + h]
//! knowing only the inputs up to t (causal), without a lag of one step, and
//! along a smooth path: at these frequencies the line is axially stiff, so a
//! kink or a wobble of the path at the communication step's period launches
//! axial waves that ring in the tension.
//!
//! Per axis, the step's end state is predicted from the last samples the
//! master gave (k = 0 the current point, then the past ones newest first),
//! written as a polynomial Q (τ = s − t) plus an alternating nuisance,
//!
//!   u(t_k) = Q(t_k − t) + (a0 + a1 (t_k − t)/h) (−1)^k,               (7.1)
//!
//! in the least-squares sense (Q a quartic; with a2 ξ² (−1)^k too below
//! 0.075 s), with the design of [`DESIGNS`]: over 16 or 12 points on uniform
//! steps below 0.21 s, through 6 points with a0 alone above or where the steps
//! change (Q'(0), Q''(0) = the input derivatives when the master gives them),
//! and the path follows Q alone: a sequence that alternates from one
//! communication point to the next (a vessel model's round-off, the chatter of
//! a coupling loop) moves the hang-off not at all, where the interpolating
//! quartic of issue 12 multiplied it by up to 31 (docs/theory.md §7.3). The
//! path over the step is the quintic Hermite interpolant from the hang-off's
//! current position, velocity and acceleration (p, p', p'') at τ = 0 to
//! (Q, Q', Q'') at τ = h:
//!
//!   x(τ) = p H0(σ) + h p' H1(σ) + h² p'' H2(σ)
//!        + Q(h) H0(1−σ) − h Q'(h) H1(1−σ) + h² Q''(h) H2(1−σ),   σ = τ/h,  (7.2)
//!
//! with H0 = 1 − 10σ³ + 15σ⁴ − 6σ⁵, H1 = σ − 6σ³ + 8σ⁴ − 3σ⁵,
//! H2 = ½σ² − 3/2 σ³ + 3/2 σ⁴ − ½σ⁵ (value, slope, curvature 1 at σ = 0 in
//! turn, all zero at σ = 1). The path is C2 at every communication point. On
//! uniform steps the end values of successive steps are samples of one smooth
//! curve (Q(h) differs from u(t + h) by the smooth error of a fixed filter);
//! once the filters' window is known (16 points; 10 for the six-point design
//! of long steps) every design takes the end slope and curvature of that
//! curve ([`CONSISTENT`], (7.3a)) rather than Q's own, so
//! the path has no wobble at the communication step's period, at its ends or
//! inside (where a line stepped inside the communication step sees it).
//!
//! Which inputs drive an axis (`coupling_inputs`, [`Coupling`]): the
//! displacement (its samples are the u above); or the velocity alone, whose
//! samples are integrated into the displacement at each communication point
//! (the integral of the cubic through the last four velocities over the last
//! interval, fourth order, any step sizes: the position is part of the
//! history, so of the saved state); with both, the displacement drives the
//! path and the velocity gives the line its start velocity, and on uniform
//! steps of [`VELOCITY_DESIGN`] and longer the velocities join the fit
//! through their differences (an offset of the velocities from the
//! displacements' slope, which a body integrating a held force shows, is a
//! nuisance; docs/theory.md §7.4). `auto` decides per axis from which of the two
//! inputs the master has set.
//!
//! Error: Q(h) − u(t + h) = O(h^(d+1)) for Q of degree d (the quartic:
//! O(h⁵), its slope O(h⁴) and curvature O(h³)); the unit tests below measure
//! it. Fewer points (the first steps) give smaller designs.

use crate::math::rigid::{exp_so3, left_jacobian, left_jacobian_rate, log_so3};
use crate::math::{M3, V3};
use crate::model::HangOff;
use crate::sim::vessel::{Vessel, VesselMotion};
use nalgebra::{SMatrix, SVector};

/// Coefficients of the predicting polynomial (degree ≤ 4).
const POLY: usize = 5;

/// Pieces of information that predict a step's end: the polynomial's
/// coefficients and the alternating nuisance (7.1).
const CONDITIONS: usize = POLY + 1;

/// Samples of the widest least-squares design ([`DESIGNS`]).
const TAPS: usize = 16;

/// Unknowns of a least-squares design: at most five coefficients and three nuisances.
const UNKNOWNS: usize = 8;

/// Past communication points kept (one sample each beyond the current one).
const PAST: usize = TAPS - 1;

/// A design of (7.1) on displacement samples: the polynomial part of
/// `poly` coefficients (degree `poly` − 1) of the last `taps` samples
/// written, in the least-squares sense, as that polynomial plus the
/// alternating nuisances (−1)^k, τ_k (−1)^k, τ_k² (−1)^k (`alt` of them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Design {
    pub poly: usize,
    pub alt: usize,
    pub taps: usize,
}

/// The design of each communication step on uniform steps, by its size
/// (docs/theory.md §7.3; where the steps change, the last one). All fit a
/// quartic, whose error (O(h⁵)) stays too small for the line's axial
/// resonances to feed on at any step; the shorter the step, the more points
/// and nuisances smooth what alternates, where the line answers the step's
/// period most (its axial waves): 16 points and three nuisances below
/// 0.075 s, 12 and two up to 0.21 s, the exactly determined 6 and one above.
pub const DESIGNS: [(f64, Design); 3] = [
    (0.075, Design { poly: 5, alt: 3, taps: 16 }),
    (0.21, Design { poly: 5, alt: 2, taps: 12 }),
    (f64::INFINITY, Design { poly: 5, alt: 1, taps: 6 }),
];

/// The slope and curvature of each design's end state once its window of
/// uniform points is full (docs/theory.md §7.1, (7.3a)), per design: (a, d,
/// m). Not Q's own, but the filters over the last m samples that reproduce
/// the slope and curvature of the sequence
/// of end *values* for every polynomial of degree ≤ d, remove the design's
/// alternations, and of all such filters put the least energy into the band
/// θ = ωh from a π to π (the mean of |E_j(θ)|² there). The end values of
/// successive steps are samples of one smooth curve (the motion plus a
/// fixed filter's smooth error); Q's own slope and curvature, extrapolated
/// from a window of 11 or 15 steps, are not that curve's: the quintic (7.2)
/// between them made up the difference with a bump of acceleration in every
/// step, 1.8, 5 and 39 % of A ω² inside the steps at 0.05, 0.1 and 0.2 s
/// for a heave at 10 s, harmless at the step's end but not to a line
/// stepped inside the communication step (§16.6). With these the path's
/// acceleration is within 3e-6 of A ω² at 0.05 s. For the 16-point
/// design the degree and band are the highest and widest with which a
/// 2000 t vessel coupled both ways in libcosim stays as bounded as with Q's
/// own (`tests/python/test_coupling.py`). The middle steps (0.075-0.21 s)
/// take [`MIDDLE`] instead: with (7.3a) over the 12-point fit (d = 6, a =
/// 0.2) their path erred 4e-4 and 1.1e-2 of A ω² at 0.1 and 0.2 s, and
/// degree 7 there grew the vessel's loop at 0.2 s (a 1 Hz oscillation, the
/// line's axial resonance near 4 Hz aliased, to ±30 kN). The exactly
/// determined design of long steps takes degree 7 over ten samples (one
/// degree of freedom left to the band): the path's acceleration inside the
/// step within 4e-4, 1.1e-3 and 2.1e-2 of A ω² at 0.25, 0.3 and 0.5 s, where
/// Q's own erred 8.7, 15 and 68 % (sixteen samples span most of a period
/// there and fit worse). That loop is not the criterion there: at long
/// steps it grows in bands of steps with either slope and curvature (they
/// move the bands), and a body that feels the riser holds the force
/// low-passed (docs/theory.md §7.3, "Long communication steps"). Changing
/// steps keep Q's own; after a change of step the window of uniform points
/// must be full again (fifteen intervals, for every design).
pub const CONSISTENT: [Option<(f64, usize, usize)>; 3] = [Some((0.5, 7, TAPS)), None, Some((0.5, 7, 10))];

/// The index in [`DESIGNS`] of the middle steps (0.075 s to 0.21 s).
const MIDDLE_DESIGN: usize = 1;

/// The end state of the middle steps (0.075 ≤ h < 0.21 s) once sixteen
/// uniform points are known (docs/theory.md (7.3b)): (Q, h Q', h² Q'') =
/// `Σ_k MIDDLE[·][k] u_k`, k = 0 the current sample. All three rows at once,
/// under the constraints of (7.1) and (7.3a): the value exact one step ahead
/// for quartics, the slope and curvature those of the end values' sequence
/// for polynomials of degree ≤ 7, the alternations (−1)^k and ξ_k (−1)^k
/// removed from every row; of such filters the one that minimises, at 0.1,
/// 0.15 and 0.2 s, the path's acceleration error inside the steps and its
/// end value's error on a 10 s heave, its answer to a jerk (a ramp's end) at
/// the steel catenary's axial modes (2-2.6 Hz), and, weighted thirty times,
/// the catenary's measured answer to the end states at θ = ωh from 0.18 π
/// to π, where the line's axial resonance (about 4 Hz) aliases at these
/// steps and a vessel's loop grows on it (7.9). Made by
/// `riser_tools.studies.input_path_designs.middle` (docs/input_path_designs.md),
/// checked against its constraints by the unit test
/// `the_middle_design_keeps_the_constraints_of_7_1_and_7_3a`. Against the
/// 12-point least-squares quartic with the slope and curvature of (7.3a),
/// d = 6, a = 0.2 (before): the path's acceleration inside the steps within
/// 1.3e-3 of A ω² at 0.2 s (1.1e-2 before), the end value 1.0e-3 of A
/// (7.8e-4); a line stepped at 0.1 s inside 0.2 s steps steady within 0.09 kN
/// of `riser run` on the steel catenary (1.55 kN), and the 2000 t vessel's
/// loop in libcosim bounded from 0.08 to 0.2 s and stationary at 0.205 s
/// (where it grew before).
#[rustfmt::skip]
pub const MIDDLE: [[f64; TAPS]; 3] = [
    [1.106861496001382, 1.6651640963303749, -0.3218273624167458, -1.9629620499710672, -1.4277172138289116, 0.275634168118162, 1.1792344736682976, 1.355514297109703, 0.9001280385193262, -0.6458253136951477, -1.4354494684257901, -0.7683171267571192, 0.5250966982557694, 0.7955057910838239, -0.026326661773325752, -0.21471386221873046],
    [2.3144588909384294, -1.0300756103340465, -3.6566263471657665, 0.1688792777681124, 1.680815972066791, 2.319900469860554, -0.22462465792935432, -0.7588254125454363, -1.1450153961283323, -1.0637957165490888, 0.4901733306122258, 0.9989531592681684, 0.9376641449696066, -0.9234662622804455, -0.3968459373635984, 0.2884300948121796],
    [4.608822142156016, -10.085841073733139, 1.5090166570178662, 6.2703554353681685, 1.9529004217940005, 1.1271688597042497, -13.693312749195517, 6.761994702832747, 1.8439258192214363, 3.8221780961154472, -4.088027595755474, -3.546252509732071, 6.3371716844594035, -4.079097474811499, 1.529503620302269, -0.2705060357439055],
];

/// The largest degree of [`CONSISTENT`] (the size of its linear system).
const CONSISTENT_DEGREE: usize = 7;

/// The relative tolerance within which a master's steps count as one size
/// ([`InputHistory`]'s uniform steps, the designs' bounds): a master's
/// times in floating point put the length of its fixed step on either side
/// of its nominal value from one step to the next (fmpy's t_k = k h: 0.075
/// s steps of 0.07499999999999996 and 0.07500000000000007 s).
pub const STEP_TOLERANCE: f64 = 1e-6;

/// A step of h s is shorter than `bound` s by more than [`STEP_TOLERANCE`]:
/// a master's fixed step of the bound itself takes the design above it at
/// every step, not one design and the other by turns (which alternated the
/// path's end state and rang the line: the catenary's top tension 13 % high
/// at 0.21 s, 1.4 % at 0.075 s).
pub fn shorter(h: f64, bound: f64) -> bool {
    h < bound * (1.0 - STEP_TOLERANCE)
}

/// The design of a step of h s.
pub fn design(h: f64) -> Design {
    DESIGNS.iter().find(|(below, _)| shorter(h, *below)).map_or(DESIGNS[2].1, |d| d.1)
}

/// The design where the master gives both the displacement and the
/// velocity (`both`) on uniform steps of at least this many seconds
/// (docs/theory.md §7.4, (7.10)): the last five displacements and
/// velocities written, in the least-squares sense, as a quintic Q and its
/// slope plus an alternating nuisance in each, a (−1)^k and b (−1)^k, and
/// an offset c of the velocities from Q's slope. Its end state is O(h⁶) in
/// value and O(h⁴) in curvature over a span of 4h where the displacement
/// design's is O(h³) over 5h: its end values 40 and 20 times closer at 0.25
/// and 0.5 s (a 10 s wave); inside the steps the displacement design, with
/// the slope and curvature of its end values' sequence ([`CONSISTENT`]),
/// is now the closer (3.5e-5 against 3.2e-4 m/s² at 0.25 s on a 0.23 m
/// heave). Both alternations are removed; its loop gain above half the
/// Nyquist frequency is lower than the displacement design's at every step
/// it is used at. Below, the displacement designs smooth more.
///
/// The offset c: a body that integrates a force held over the step (what a
/// body FMU does with riser's output) reports velocities that differ from
/// the slope of its positions by −Ḟ h²/(12 M), smooth and, for a light
/// body at long steps, large (3e-4 m/s for the 50 t buoy at 0.5 s, whose
/// wave velocity is 0.18 m/s). Fitted as motion, the offset bends the end
/// state's slope and curvature away from its value and the path between
/// such end states bumps once a step, at 1/h and its harmonics, which rang
/// the line's axial resonance at 2/h = 4 Hz (docs/coupling.md, the buoy).
/// The velocities then inform the fit through their differences only: a
/// constant offset moves the path not at all, and on samples of one smooth
/// motion the end state's error is that without c within 1 % up to
/// θ = ωh = 1.2.
pub const VELOCITY_DESIGN: f64 = 0.21;

/// Communication points of the `both` design.
const VELOCITY_TAPS: usize = 5;

/// The `both` design's slope and curvature where the master gives the
/// vessel's mass (and for the rotation its inertias), so that the samples are
/// less the vessel's answer to riser's own load (§7.8; docs/theory.md
/// (7.10a)): (m, d), the derivatives of the least-squares polynomial of
/// degree d through the last m end values, once m + 4 uniform points are
/// known, rather than Q's own. Q's own slope and curvature are not those of
/// the end values' sequence, and the path between such end states bumps in
/// every step (5.0e-3 m/s² inside the steps on a 0.23 m heave at 10 s and
/// 0.5 s, 5.5 % of A ω²; 3.2e-4 with these rows), at 1/h = 2 Hz next to the
/// moored vessel's chains' axial mode (1.6 Hz): the system FMU one way at
/// 0.5 s missed its 0.05 s run's force by 2.7 % of its range (0.71 % with
/// these rows), coupled both ways 1.25 % (0.29 %). With the vessel's answer taken out,
/// what is extrapolated is the motion riser's load does not cause, and the
/// 2000 t vessel's loop stays bounded at every long step measured (0.21-0.6 s);
/// without it the same rows grow that loop at 0.21, 0.32-0.45 and 0.6 s
/// (the predictor's gain meets the line's aliased axial resonance), so there
/// the design keeps Q's own.
pub const VELOCITY_CONSISTENT: (usize, usize) = (10, 7);

/// Velocity samples the position of `velocity` coupling is integrated from
/// (the interpolant of degree ≤ 3 over the last interval: fourth order).
const QUADRATURE: usize = 4;

/// Numbers per past sample in [`InputHistory::to_values`]: t, u (3), v (3),
/// the rotation (9), the angular velocity inputs (3), riser's force and
/// moment on the vessel (3 + 3).
const SAMPLE_VALUES: usize = 25;

/// Numbers in [`InputHistory::to_values`].
pub const HISTORY_VALUES: usize = PAST * SAMPLE_VALUES + 14;

/// A past rotation sample farther than this from the path's start rotation
/// (rad) ends the rotation's window: the rotation vectors of the fit stay
/// well inside |φ| < π, where log is one-to-one (docs/theory.md §14.7).
const MAX_WINDOW_ROTATION: f64 = 2.0;

/// The inputs of one communication point: the vessel reference point's
/// displacement (heave, surge, sway; m) and velocity (m/s), the angles
/// [roll, pitch, yaw] (rad) and the angular velocity in the vessel frame
/// [p, q, r] (rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VesselInputs {
    pub u: [f64; 3],
    pub v: [f64; 3],
    pub angles: [f64; 3],
    pub rates: [f64; 3],
    /// Riser's force on the vessel at this point (global; heave, surge,
    /// sway: z, x, y), N: the output the master hands the vessel, which
    /// holds it over the step (§7.8).
    pub force: [f64; 3],
    /// Riser's moment on the vessel about its reference point at this point
    /// (global, x, y, z), N m: `top_moment_*`, held alike.
    pub moment: [f64; 3],
}

/// Inputs of one communication point, axes in input order (heave, surge, sway).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Displacement, m: the input, or the integral of the velocity inputs
    /// for an axis coupled by velocity.
    pub u: [f64; 3],
    /// Velocity inputs, m/s.
    pub v: [f64; 3],
    /// The vessel's rotation: R of the angle inputs, or the integral of the
    /// angular velocity inputs for a rotation coupled by velocity.
    pub rot: M3,
    /// Angular velocity inputs, vessel frame, rad/s.
    pub w: [f64; 3],
    /// Riser's force on the vessel at this point (heave, surge, sway), N.
    pub f: [f64; 3],
    /// Riser's moment on the vessel at this point (global), N m.
    pub m: [f64; 3],
}

/// Which inputs drive the hang-off (the `coupling_inputs` parameter).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Coupling {
    /// Per axis, from which inputs the master has set (never their values).
    #[default]
    Auto,
    /// The displacement inputs (the velocity ones are ignored).
    Displacement,
    /// The velocity inputs alone, integrated (the displacement ones are ignored).
    Velocity,
    /// Both: the displacement drives the path, the velocity starts the line moving.
    Both,
}

impl Coupling {
    /// The parameter's values, in this order.
    pub const NAMES: [&'static str; 4] = ["auto", "displacement", "velocity", "both"];

    /// From the parameter's value.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "auto" => Coupling::Auto,
            "displacement" => Coupling::Displacement,
            "velocity" => Coupling::Velocity,
            "both" => Coupling::Both,
            _ => return None,
        })
    }

    /// The parameter's value.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The mode of an axis whose displacement (`d`) and velocity (`v`)
    /// inputs have or have not been set: never `Auto`.
    pub fn resolve(self, d: bool, v: bool) -> Coupling {
        match self {
            Coupling::Auto => match (d, v) {
                (false, true) => Coupling::Velocity,
                (true, true) => Coupling::Both,
                _ => Coupling::Displacement,
            },
            other => other,
        }
    }
}

/// Where an axis' rates came from (for the log and the tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateSource {
    /// `fmi2SetRealInputDerivatives`.
    Derivatives,
    /// The velocity inputs (integrated: `velocity` coupling).
    Velocity,
    /// The displacement history.
    History,
    /// The displacement and velocity histories together (`both`, at the
    /// steps of [`VELOCITY_DESIGN`]).
    Both,
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

/// The path of the vessel and its hang-off over one communication step [t, t + h].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    t: f64,
    h: f64,
    /// Per axis (heave, surge, sway of the reference point, then the three
    /// components of the rotation vector φ from `rot_start`): the start
    /// (p, h p', h² p'').
    start: [[f64; 3]; 6],
    /// Per axis: the predicted end (Q(h), h Q'(h), h² Q''(h)).
    end: [[f64; 3]; 6],
    /// Per translation axis: where the rates came from.
    pub sources: [RateSource; 3],
    /// Where the rotation's rates came from (the angles' history or the
    /// angular velocity inputs).
    pub rotation_source: RateSource,
    /// Per axis: the displacement at t this path was planned from (the
    /// input, or the velocity's integral); it joins the history.
    pub u: [f64; 3],
    /// The rotation at t this path was planned from (of the angles, or the
    /// angular velocity's integral); it joins the history.
    pub rot: M3,
    /// The rotation at the step's start: R(s) = exp(φ(s)) `rot_start` (14.7).
    rot_start: M3,
    /// ρ, the hang-off in the vessel frame, m.
    offset: V3,
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

    /// The vessel's rotation and its angular velocity (global) at time s
    /// (clamped to the step): R = exp(φ) R_start, ω = J(φ) φ̇ (14.8), exact.
    pub fn rotation(&self, s: f64) -> (M3, V3) {
        let (mut phi, mut dphi) = (V3::zeros(), V3::zeros());
        for c in 0..3 {
            let x = self.axis(3 + c, s);
            phi[c] = x[0];
            dphi[c] = x[1];
        }
        (exp_so3(&phi) * self.rot_start, left_jacobian(&phi) * dphi)
    }

    /// The hang-off's motion at time s (clamped to the step): the reference
    /// point's (u, v) and the rotation composed as [`Vessel::hang_off`] does,
    /// displacement u + (R − I)ρ, velocity v + ω × Rρ, and R and ω (14.3).
    pub fn at(&self, s: f64) -> HangOff {
        let mut displacement = V3::zeros();
        let mut velocity = V3::zeros();
        for (i, &c) in COMPONENT.iter().enumerate() {
            let x = self.axis(i, s);
            displacement[c] = x[0];
            velocity[c] = x[1];
        }
        let (rotation, angular_velocity) = self.rotation(s);
        let arm = rotation * self.offset;
        HangOff {
            displacement: displacement + arm - self.offset,
            velocity: velocity + angular_velocity.cross(&arm),
            rotation,
            angular_velocity,
        }
    }

    /// The motion at time s (clamped to the step) of a point at `offset` ρ in
    /// the vessel frame other than the path's hang-off (another line's vessel
    /// point in a system, §17.6), composed as [`Path::at`] composes the
    /// hang-off's.
    pub fn at_offset(&self, s: f64, offset: V3) -> HangOff {
        Path { offset, ..*self }.at(s)
    }

    /// The vessel reference point's acceleration at time s (clamped to the step), m/s².
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

    /// The angular acceleration (global) at the step's end, rad/s²:
    /// α = J(φ) φ̈ + J̇ φ̇ (14.8), the next path's start (exact: there φ = 0).
    fn end_angular_acceleration(&self) -> [f64; 3] {
        let h = self.h;
        let phi = V3::from_fn(|c, _| self.end[3 + c][0]);
        let dphi = V3::from_fn(|c, _| self.end[3 + c][1] / h);
        let ddphi = V3::from_fn(|c, _| self.end[3 + c][2] / (h * h));
        let a = left_jacobian(&phi) * ddphi + left_jacobian_rate(&phi, &dphi) * dphi;
        [a.x, a.y, a.z]
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

/// One condition of (7.1): the `order`-th derivative of Q at τ, plus the
/// nuisance's `alternation` times a, equals `value`.
#[derive(Debug, Clone, Copy)]
struct Condition {
    tau: f64,
    order: usize,
    value: f64,
    /// (−1)^k for the k-th displacement sample, 0 for a derivative.
    alternation: f64,
}

/// The input history that plans each step's path: everything needed to
/// continue bit for bit (it is part of the saved FMU state).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InputHistory {
    /// The last communication points, newest first; `count` are valid.
    past: [Sample; PAST],
    count: usize,
    /// Per axis: the master has set the displacement input (since
    /// instantiation or reset).
    displacement_set: [bool; 3],
    /// Per axis: the master has set the velocity input.
    velocity_set: [bool; 3],
    /// Derivatives set since the last step.
    pub pending: Derivatives,
    /// The last path's acceleration at its end (the next one's start), m/s².
    end_acceleration: [f64; 3],
    /// The master has set an angle input (roll, pitch, yaw).
    rotation_set: bool,
    /// The master has set an angular velocity input.
    angular_velocity_set: bool,
    /// The last path's angular acceleration at its end (global), rad/s².
    end_angular_acceleration: [f64; 3],
    /// Per axis (heave, surge, sway): the vessel's mass with its added mass
    /// as the body that holds riser's force over each step integrates it
    /// (the `vessel_mass_*` parameters; 0: unknown), kg (§7.8). A
    /// parameter, not state: the instance sets it before each plan.
    pub mass: [f64; 3],
    /// The vessel's moments of inertia with their added inertia about its
    /// roll, pitch and yaw axes (vessel frame; the `vessel_inertia_*`
    /// parameters; 0: unknown), kg m², alike.
    pub inertia: [f64; 3],
    /// Where the vessel's answer to riser's own load is known ([`Self::mass`],
    /// [`Self::inertia`]), the `both` design of long steps takes the slope and
    /// curvature of its end values' sequence ([`VELOCITY_CONSISTENT`],
    /// (7.10a)); the instance sets it for a system of lines, which takes the
    /// vessel's answer between the points only (§7.8). A single line that
    /// also integrates that answer inside its steps (§7.10) keeps Q's own: with
    /// (7.10a) the 50 t buoy's heave at 0.5 s was 1.7 % off its monolithic
    /// reference (0.5 % with Q's own). A parameter, not state.
    pub end_value_rates: bool,
}

impl InputHistory {
    /// No history (just instantiated or reset).
    pub fn new() -> Self {
        Self::default()
    }

    /// Notes that the master set input `index` (heave, surge, sway, their
    /// velocities, roll, pitch, yaw, the angular velocities): `auto`
    /// decides from this, never from the values.
    pub fn note_set(&mut self, index: usize) {
        match index {
            0..3 => self.displacement_set[index] = true,
            3..6 => self.velocity_set[index - 3] = true,
            6..9 => self.rotation_set = true,
            9..12 => self.angular_velocity_set = true,
            _ => {}
        }
    }

    /// The mode of the rotation under `coupling` (never `Auto`): one for
    /// the three angles, which compose.
    pub fn rotation_mode(&self, coupling: Coupling) -> Coupling {
        coupling.resolve(self.rotation_set, self.angular_velocity_set)
    }

    /// The mode of each axis under `coupling` (never `Auto`).
    pub fn modes(&self, coupling: Coupling) -> [Coupling; 3] {
        std::array::from_fn(|i| coupling.resolve(self.displacement_set[i], self.velocity_set[i]))
    }

    /// The displacement of axis `i` at time t: the input, or for velocity
    /// coupling the last one plus the integral of the interpolant of the
    /// velocities (`vin` at t and the last ones) over the last interval.
    fn displacement(&self, i: usize, mode: Coupling, t: f64, u: f64, vin: f64, start: f64) -> f64 {
        if mode != Coupling::Velocity {
            return u;
        }
        if self.count == 0 {
            // the first point: where the hang-off is (its initial position)
            return start;
        }
        let (coef, n, span) = self.interpolant(t, vin, |s| s.v[i]);
        let integral: f64 = (0..n).map(|j| coef[j] / (j + 1) as f64).sum();
        self.past[0].u[i] + span * integral
    }

    /// The vessel's rotation at time t: R of the angles, or for velocity
    /// coupling the last one times exp of the fourth-order Magnus step of
    /// the interpolant of the body rates (`rates` at t and the last ones)
    /// over the last interval (14.9):
    ///   R(t) = R(t0) exp(Δ/2 (ω1 + ω2) + √3 Δ²/12 ω1 × ω2),
    /// ω1, ω2 the interpolant at the Gauss points t0 + (½ ∓ √3/6) Δ.
    fn rotation_sample(&self, mode: Coupling, vessel: &Vessel, t: f64, inp: &VesselInputs, start: &M3) -> M3 {
        if mode != Coupling::Velocity {
            return vessel.order.rotation(inp.angles);
        }
        if self.count == 0 {
            return *start;
        }
        let r3 = 3f64.sqrt();
        let mut w = [V3::zeros(); 2];
        let mut span = 0.0;
        for c in 0..3 {
            let (coef, n, sp) = self.interpolant(t, inp.rates[c], |s| s.w[c]);
            span = sp;
            for (g, x) in [0.5 - r3 / 6.0, 0.5 + r3 / 6.0].into_iter().enumerate() {
                w[g][c] = (0..n).map(|j| coef[j] * x.powi(j as i32)).sum();
            }
        }
        let phi = 0.5 * span * (w[0] + w[1]) + r3 / 12.0 * span * span * w[0].cross(&w[1]);
        self.past[0].rot * exp_so3(&phi)
    }

    /// The interpolant of degree < n ≤ 4 in s = (τ − t0)/(t − t0) through the
    /// samples `current` at t and `value` of the last ones (s = 0 at the
    /// newest past point t0): its coefficients, n and t − t0.
    fn interpolant(
        &self,
        t: f64,
        current: f64,
        value: impl Fn(&Sample) -> f64,
    ) -> (SVector<f64, QUADRATURE>, usize, f64) {
        let t0 = self.past[0].t;
        let n = (self.count + 1).min(QUADRATURE);
        // the interpolant in s = (τ − τ0)/(t − t0) through (0 at t0, ..., 1 at t)
        let span = t - t0;
        let mut a = SMatrix::<f64, QUADRATURE, QUADRATURE>::identity();
        let mut b = SVector::<f64, QUADRATURE>::zeros();
        for row in 0..n {
            let (tk, vk) = if row == 0 { (t, current) } else { (self.past[row - 1].t, value(&self.past[row - 1])) };
            let s = (tk - t0) / span;
            for j in 0..QUADRATURE {
                a[(row, j)] = if j < n { s.powi(j as i32) } else { 0.0 };
            }
            b[row] = vk;
        }
        let coef = a.lu().solve(&b).unwrap_or_else(|| {
            // distinct times make it regular; the trapezoid otherwise
            let mut c = SVector::zeros();
            c[0] = value(&self.past[0]);
            c[1] = current - value(&self.past[0]);
            c
        });
        (coef, n, span)
    }

    /// The vessel's answer to riser's own load (docs/theory.md §7.8): the
    /// motion x_r of a free body whose acceleration over the step from each
    /// of the last `known` points is `acc(k)` (k = 1 the newest past point:
    /// riser's load there less its current one, over the mass), at rest at
    /// the oldest: x_r and v_r at the points (k = 0 at t, then the past ones
    /// newest first), and its end state (x_r, h v_r, h² a_r) at t + h (the
    /// current load less itself: a_r = 0). The load the body holds over
    /// the step is known here (riser's own output at t), the body's answer
    /// to it exactly, so only the samples less x_r are extrapolated; a
    /// constant load's answer is a parabola, which every design reproduces
    /// (the reference, the current load, changes nothing but the size of
    /// the numbers).
    #[allow(clippy::type_complexity)]
    fn own_answer(
        &self,
        known: usize,
        t: f64,
        h: f64,
        acc: impl Fn(usize) -> f64,
    ) -> ([f64; TAPS], [f64; TAPS], [f64; 3]) {
        let (mut xs, mut vs) = ([0.0; TAPS], [0.0; TAPS]);
        let (mut x, mut v) = (0.0, 0.0);
        for k in (1..=known).rev() {
            let newer = if k == 1 { t } else { self.past[k - 2].t };
            let (dt, a) = (newer - self.past[k - 1].t, acc(k));
            x += v * dt + 0.5 * a * dt * dt;
            v += a * dt;
            xs[k - 1] = x;
            vs[k - 1] = v;
        }
        (xs, vs, [x + v * h, h * v, 0.0])
    }

    /// The conditions (7.1) of axis `i` at time t from the displacement `u`
    /// at t, newest first, and the source of the rates.
    fn conditions(&self, i: usize, mode: Coupling, t: f64, u: f64) -> ([Option<Condition>; CONDITIONS], RateSource) {
        let mut out = [None; CONDITIONS];
        let mut n = 0;
        let mut push = |c: Condition| {
            if n < CONDITIONS {
                out[n] = Some(c);
                n += 1;
            }
        };
        push(Condition { tau: 0.0, order: 0, value: u, alternation: 1.0 });
        let with_derivatives = mode != Coupling::Velocity;
        let first = self.pending.first[i].filter(|_| with_derivatives);
        let source = match (first, mode) {
            (Some(_), _) => RateSource::Derivatives,
            (None, Coupling::Velocity) => RateSource::Velocity,
            _ => RateSource::History,
        };
        if let Some(d) = first {
            push(Condition { tau: 0.0, order: 1, value: d, alternation: 0.0 });
        }
        if let Some(a) = self.pending.second[i].filter(|_| with_derivatives) {
            push(Condition { tau: 0.0, order: 2, value: a, alternation: 0.0 });
        }
        for (k, s) in self.past[..self.count].iter().enumerate() {
            let sign = if k % 2 == 0 { -1.0 } else { 1.0 };
            push(Condition { tau: s.t - t, order: 0, value: s.u[i], alternation: sign });
        }
        (out, source)
    }

    /// (7.1) in the least-squares sense on the samples `value(k)` (k = 0 at
    /// t, then the `known` past ones, newest first) with the design of the
    /// step h ([`design`]): (Q, h Q', h² Q'') at τ = h. With n < taps samples
    /// known (the first steps) the design shrinks: min(alt, n − 4) nuisances
    /// and min(poly, n − nuisances) coefficients.
    fn fit(&self, known: usize, t: f64, h: f64, value: impl Fn(usize) -> f64) -> [f64; 3] {
        // the smoothing designs on uniform steps (a fixed-step master); where
        // the steps change, the quartic through six points with the
        // alternation removed, whose error stays O(h⁵) at any spacing (a
        // smoothing design's larger error, smooth at uniform steps, would
        // change from step to step with the spacing and wobble the path)
        let uniform = self.uniform(known.min(TAPS - 1), t, h);
        let index = if uniform { DESIGNS.iter().position(|x| x.1 == design(h)).unwrap_or(2) } else { 2 };
        let d = DESIGNS[index].1;
        let n = (known + 1).min(d.taps);
        if index == MIDDLE_DESIGN && uniform && known + 1 >= TAPS {
            // the middle steps once sixteen uniform points are known: (7.3b)
            return std::array::from_fn(|c| (0..TAPS).map(|k| MIDDLE[c][k] * value(k)).sum());
        }
        if let Some((_, _, m)) = CONSISTENT[index].filter(|&(_, _, m)| uniform && known + 1 >= m) {
            // a fixed-step master once the filters' window is full: the end value
            // of the fit, its slope and curvature those of the end values' sequence
            // (zero weights beyond the window: only its m samples are read)
            let w = consistent_weights(index);
            return std::array::from_fn(|c| (0..m).map(|k| w[c][k] * value(k)).sum());
        }
        if uniform && n == d.taps {
            // a fixed-step master once the window is full: the fit's fixed weights
            let w = uniform_weights(index);
            return std::array::from_fn(|c| (0..n).map(|k| w[c][k] * value(k)).sum());
        }
        // the first steps: the polynomial first (up to the cubic a motion
        // starting from rest needs; a smaller one lags and then catches up
        // with a jerk the line's axial waves answer), the nuisances with the
        // samples beyond four
        let alt = d.alt.min(n.saturating_sub(4));
        let poly = d.poly.min(n - alt);
        let sigma = |k: usize| if k == 0 { 0.0 } else { (self.past[k - 1].t - t) / h };
        least_squares(poly, alt, n, sigma, value)
    }

    /// The last `back` intervals before t are all of h s (a fixed-step master).
    fn uniform(&self, back: usize, t: f64, h: f64) -> bool {
        (0..back).all(|k| {
            let newer = if k == 0 { t } else { self.past[k - 1].t };
            ((newer - self.past[k].t) / h - 1.0).abs() < STEP_TOLERANCE
        })
    }

    /// (Q, h Q', h² Q'') at the step's end by the design of
    /// [`VELOCITY_DESIGN`] from the displacements `u(k)` and the velocities
    /// `v(k)` (k = 0 at t, then the `known` past ones, newest first); None
    /// where it does not apply (a shorter step, fewer points known, steps
    /// that change). `own`: the samples are less the vessel's answer to
    /// riser's own load (§7.8) and [`InputHistory::end_value_rates`] is set:
    /// once [`VELOCITY_CONSISTENT`]'s window is known the slope and curvature
    /// are those of the end values' sequence.
    #[allow(clippy::too_many_arguments)]
    fn fit_with_velocity(
        &self,
        known: usize,
        t: f64,
        h: f64,
        own: bool,
        u: impl Fn(usize) -> f64,
        v: impl Fn(usize) -> f64,
    ) -> Option<[f64; 3]> {
        if shorter(h, VELOCITY_DESIGN) || known + 1 < VELOCITY_TAPS || !self.uniform(VELOCITY_TAPS - 1, t, h) {
            return None;
        }
        let (m, _) = VELOCITY_CONSISTENT;
        if own && known + 1 >= m + VELOCITY_TAPS - 1 && self.uniform(m + VELOCITY_TAPS - 2, t, h) {
            // the vessel's answer to riser's own load known (§7.8): the slope and
            // curvature of the end values' sequence (7.10a)
            let [wu, wv] = velocity_consistent_weights();
            return Some(std::array::from_fn(|c| (0..TAPS).map(|k| wu[c][k] * u(k) + wv[c][k] * h * v(k)).sum()));
        }
        let [wu, wv] = velocity_weights();
        Some(std::array::from_fn(|c| (0..VELOCITY_TAPS).map(|k| wu[c][k] * u(k) + wv[c][k] * h * v(k)).sum()))
    }

    /// Solves (7.1) for Q in σ = τ/h and returns (Q, h Q', h² Q'') at
    /// σ = 1: the predicted end of the step. With n conditions, Q has degree
    /// n − 2 and the nuisance takes the last unknown once two samples
    /// alternate; fewer conditions lower the degree.
    fn predict(conditions: &[Option<Condition>; CONDITIONS], h: f64) -> [f64; 3] {
        let n = conditions.iter().flatten().count();
        let samples = conditions.iter().flatten().filter(|c| c.order == 0).count();
        // unknowns: Q's coefficients 0..=degree, then a (the last column) when alternating
        let solve = |alternating: bool| {
            let used = if alternating { n } else { n.min(POLY) };
            let degree = if alternating { used - 2 } else { used - 1 };
            let mut a = SMatrix::<f64, CONDITIONS, CONDITIONS>::zeros();
            let mut b = SVector::<f64, CONDITIONS>::zeros();
            for (row, c) in conditions.iter().flatten().take(used).enumerate() {
                // d^order/dσ^order of σ^j, at σ = τ/h; the value scaled by h^order
                let sigma = c.tau / h;
                for j in c.order..=degree {
                    let falling: f64 = (0..c.order).map(|k| (j - k) as f64).product();
                    a[(row, j)] = falling * sigma.powi((j - c.order) as i32);
                }
                if alternating {
                    a[(row, CONDITIONS - 1)] = c.alternation;
                }
                b[row] = c.value * h.powi(c.order as i32);
            }
            // the rows of missing conditions pin the unused unknowns to zero
            let end = if alternating { CONDITIONS - 1 } else { CONDITIONS };
            for (row, j) in (used..CONDITIONS).zip(degree + 1..end) {
                a[(row, j)] = 1.0;
            }
            a.lu().solve(&b)
        };
        // distinct points make it regular (a quartic cannot alternate in sign
        // at six points); the plain interpolant if round-off says otherwise
        let coef = (if samples >= 2 { solve(true) } else { None }).or_else(|| solve(false)).unwrap_or_else(|| {
            let mut c = SVector::zeros();
            c[0] = conditions[0].map_or(0.0, |c| c.value);
            c
        });
        let value: f64 = (0..POLY).map(|j| coef[j]).sum();
        let slope: f64 = (1..POLY).map(|j| j as f64 * coef[j]).sum();
        let curvature: f64 = (2..POLY).map(|j| (j * (j - 1)) as f64 * coef[j]).sum();
        [value, slope, curvature]
    }

    /// The velocity the hang-off starts with at t0 (the line is at rest
    /// unless the master gives a velocity there).
    pub fn start_velocity(&self, coupling: Coupling, vin: &[f64; 3]) -> [f64; 3] {
        let modes = self.modes(coupling);
        std::array::from_fn(|i| match (self.pending.first[i], modes[i]) {
            (_, Coupling::Velocity | Coupling::Both) => vin[i],
            (Some(v), _) => v,
            _ => 0.0,
        })
    }

    /// The displacement the hang-off starts from at t0: the inputs, but
    /// for an axis driven by its velocity alone (its initial position, 0).
    pub fn start_displacement(&self, coupling: Coupling, u: &[f64; 3]) -> [f64; 3] {
        let modes = self.modes(coupling);
        std::array::from_fn(|i| if modes[i] == Coupling::Velocity { 0.0 } else { u[i] })
    }

    /// The hang-off's motion at t0 from the inputs set before
    /// fmi2ExitInitializationMode: the translations as
    /// [`InputHistory::start_displacement`] and [`InputHistory::start_velocity`],
    /// the rotation of the angles (the identity for a rotation coupled by its
    /// velocity alone), its angular velocity that of the angular velocity
    /// inputs when they drive (`velocity`, `both`), else zero; composed at
    /// the offset by [`Vessel::hang_off`].
    pub fn start(&self, coupling: Coupling, vessel: &Vessel, inp: &VesselInputs) -> HangOff {
        let u = self.start_displacement(coupling, &inp.u);
        let v = self.start_velocity(coupling, &inp.v);
        let mode = self.rotation_mode(coupling);
        let angles = if mode == Coupling::Velocity { [0.0; 3] } else { inp.angles };
        let rates = if matches!(mode, Coupling::Velocity | Coupling::Both) { inp.rates } else { [0.0; 3] };
        // input order heave, surge, sway → z, x, y
        vessel.hang_off(&VesselMotion {
            displacement: V3::new(u[1], u[2], u[0]),
            velocity: V3::new(v[1], v[2], v[0]),
            angles,
            body_rates: V3::from(rates),
        })
    }

    /// Plans the path over [t, t + h] from the hang-off's current motion
    /// `from` towards the prediction (7.1) from the inputs set for t: the
    /// reference point's translations per axis as §7 says, the rotation on
    /// rotations (§14.7): the samples R_k as rotation vectors
    /// φ_k = log(R_k R_startᵀ) from the current rotation R_start, each
    /// component through the same fit, and R(s) = exp(φ(s)) R_start.
    pub fn plan(
        &self,
        coupling: Coupling,
        vessel: &Vessel,
        t: f64,
        h: f64,
        inp: &VesselInputs,
        from: &HangOff,
    ) -> Path {
        // the reference point's motion from the hang-off's (14.3 inverted)
        let arm = from.rotation * vessel.offset;
        let ref_displacement = from.displacement - (arm - vessel.offset);
        let ref_velocity = from.velocity - from.angular_velocity.cross(&arm);
        let modes = self.modes(coupling);
        let mut sources = [RateSource::History; 3];
        let mut used = [0.0; 3];
        let mut end = [[0.0; 3]; 6];
        for (i, e) in end.iter_mut().take(3).enumerate() {
            let x = self.displacement(i, modes[i], t, inp.u[i], inp.v[i], ref_displacement[COMPONENT[i]]);
            used[i] = x;
            let (conditions, source) = self.conditions(i, modes[i], t, x);
            sources[i] = source;
            // the samples less the vessel's answer to riser's own force (§7.8), and that answer's end
            let (m, f) = (self.mass[i], inp.force[i]);
            let own = m.is_finite() && m > 0.0 && f.is_finite();
            let rates = own && self.end_value_rates;
            let (xr, vr, er) = if own {
                self.own_answer(self.count, t, h, |k| (self.past[k - 1].f[i] - f) / m)
            } else {
                ([0.0; TAPS], [0.0; TAPS], [0.0; 3])
            };
            let u_k = |k: usize| (if k == 0 { x } else { self.past[k - 1].u[i] }) - xr[k];
            let with_velocity = || {
                self.fit_with_velocity(self.count, t, h, rates, u_k, |k| {
                    (if k == 0 { inp.v[i] } else { self.past[k - 1].v[i] }) - vr[k]
                })
            };
            *e = if source == RateSource::Derivatives || conditions.iter().flatten().any(|c| c.order > 0) {
                Self::predict(&conditions, h)
            } else {
                let fitted = match (modes[i] == Coupling::Both).then(with_velocity).flatten() {
                    Some(e) => {
                        sources[i] = RateSource::Both;
                        e
                    }
                    None => self.fit(self.count, t, h, u_k),
                };
                std::array::from_fn(|c| fitted[c] + er[c])
            };
        }
        // the rotation: its samples as rotation vectors from where it is
        let mode = self.rotation_mode(coupling);
        let r_start = from.rotation;
        let rot = self.rotation_sample(mode, vessel, t, inp, &r_start);
        let relative = |r: &M3| log_so3(&(r * r_start.transpose()));
        let phi0 = relative(&rot);
        let mut phis = [V3::zeros(); PAST];
        let mut known = 0;
        for (k, s) in self.past[..self.count].iter().enumerate() {
            phis[k] = relative(&s.rot);
            if phis[k].norm() > MAX_WINDOW_ROTATION {
                break;
            }
            known = k + 1;
        }
        // with the angular velocities too (`both`): φ̇_k = J(φ_k)⁻¹ R_k ω_k (14.8)
        let mut dphis = [V3::zeros(); TAPS];
        let with_velocity = mode == Coupling::Both && known + 1 >= VELOCITY_TAPS;
        if with_velocity {
            for (k, d) in dphis.iter_mut().enumerate().take(known + 1) {
                let (phi, r, w) = if k == 0 {
                    (phi0, rot, V3::from(inp.rates))
                } else {
                    (phis[k - 1], self.past[k - 1].rot, V3::from(self.past[k - 1].w))
                };
                *d = left_jacobian(&phi).try_inverse().unwrap_or_else(M3::identity) * (r * w);
            }
        }
        // the vessel's answer to riser's own moment (§7.8): the global angular
        // acceleration R I⁻¹ Rᵀ (M_k − M(t)), R the rotation now, I the inertia
        let own_rotation =
            self.inertia.iter().all(|i| i.is_finite() && *i > 0.0) && inp.moment.iter().all(|m| m.is_finite());
        let alpha: [V3; PAST] = std::array::from_fn(|k| {
            if !own_rotation || k >= known {
                return V3::zeros();
            }
            let body = rot.transpose() * (V3::from(self.past[k].m) - V3::from(inp.moment));
            rot * V3::new(body.x / self.inertia[0], body.y / self.inertia[1], body.z / self.inertia[2])
        });
        let mut rotation_source = if mode == Coupling::Velocity { RateSource::Velocity } else { RateSource::History };
        for c in 0..3 {
            let (xr, vr, er) = if own_rotation {
                self.own_answer(known, t, h, |k| alpha[k - 1][c])
            } else {
                ([0.0; TAPS], [0.0; TAPS], [0.0; 3])
            };
            let phi = |k: usize| (if k == 0 { phi0[c] } else { phis[k - 1][c] }) - xr[k];
            let fitted = if with_velocity {
                self.fit_with_velocity(known, t, h, own_rotation && self.end_value_rates, phi, |k| dphis[k][c] - vr[k])
            } else {
                None
            };
            if fitted.is_some() {
                rotation_source = RateSource::Both;
            }
            let e = fitted.unwrap_or_else(|| self.fit(known, t, h, phi));
            end[3 + c] = std::array::from_fn(|j| e[j] + er[j]);
        }
        let mut start = [[0.0; 3]; 6];
        for (i, &c) in COMPONENT.iter().enumerate() {
            start[i] = [ref_displacement[c], h * ref_velocity[c], h * h * self.end_acceleration[i]];
        }
        for c in 0..3 {
            // at φ = 0, φ̇ = ω and φ̈ = α exactly (14.8)
            start[3 + c] = [0.0, h * from.angular_velocity[c], h * h * self.end_angular_acceleration[c]];
        }
        Path { t, h, start, end, sources, rotation_source, u: used, rot, rot_start: r_start, offset: vessel.offset }
    }

    /// Records the communication point t after a successful step along
    /// `path` from it: its inputs join the history and the pending
    /// derivatives are used up.
    pub fn commit(&mut self, t: f64, inp: &VesselInputs, path: &Path) {
        self.past.copy_within(0..PAST - 1, 1);
        self.past[0] = Sample { t, u: path.u, v: inp.v, rot: path.rot, w: inp.rates, f: inp.force, m: inp.moment };
        self.count = (self.count + 1).min(PAST);
        self.pending = Derivatives::default();
        self.end_acceleration = path.end_acceleration();
        self.end_angular_acceleration = path.end_angular_acceleration();
    }

    /// The history as numbers (for the serialized FMU state).
    pub fn to_values(&self) -> [f64; HISTORY_VALUES] {
        let mut out = [0.0; HISTORY_VALUES];
        for (k, s) in self.past.iter().enumerate() {
            let o = SAMPLE_VALUES * k;
            out[o] = s.t;
            out[o + 1..o + 4].copy_from_slice(&s.u);
            out[o + 4..o + 7].copy_from_slice(&s.v);
            out[o + 7..o + 16].copy_from_slice(s.rot.as_slice());
            out[o + 16..o + 19].copy_from_slice(&s.w);
            out[o + 19..o + 22].copy_from_slice(&s.f);
            out[o + 22..o + 25].copy_from_slice(&s.m);
        }
        let o = PAST * SAMPLE_VALUES;
        out[o] = self.count as f64;
        let mut flags = 0u32;
        for i in 0..3 {
            flags |= (self.displacement_set[i] as u32) << i;
            flags |= (self.pending.first[i].is_some() as u32) << (3 + i);
            flags |= (self.pending.second[i].is_some() as u32) << (6 + i);
            flags |= (self.velocity_set[i] as u32) << (9 + i);
            out[o + 2 + i] = self.pending.first[i].unwrap_or(0.0);
            out[o + 5 + i] = self.pending.second[i].unwrap_or(0.0);
            out[o + 8 + i] = self.end_acceleration[i];
            out[o + 11 + i] = self.end_angular_acceleration[i];
        }
        flags |= (self.rotation_set as u32) << 12;
        flags |= (self.angular_velocity_set as u32) << 13;
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
            h.past[k] = Sample {
                t: x[o],
                u: three(1),
                v: three(4),
                rot: M3::from_column_slice(&x[o + 7..o + 16]),
                w: three(16),
                f: three(19),
                m: three(22),
            };
        }
        let o = PAST * SAMPLE_VALUES;
        h.count = small_int(x[o], (PAST + 1) as f64)? as usize;
        let flags = small_int(x[o + 1], 16384.0)?;
        h.displacement_set = bits(flags);
        h.velocity_set = bits(flags >> 9);
        for i in 0..3 {
            h.pending.first[i] = (flags >> (3 + i) & 1 == 1).then_some(x[o + 2 + i]);
            h.pending.second[i] = (flags >> (6 + i) & 1 == 1).then_some(x[o + 5 + i]);
            h.end_acceleration[i] = x[o + 8 + i];
            h.end_angular_acceleration[i] = x[o + 11 + i];
        }
        h.rotation_set = flags >> 12 & 1 == 1;
        h.angular_velocity_set = flags >> 13 & 1 == 1;
        Some(h)
    }
}

/// (7.1) in the least-squares sense: `poly` coefficients and `alt`
/// alternating nuisances through the `n` samples `value(k)` at σ_k =
/// `sigma(k)` (τ/h; k = 0 the newest, at σ = 0), the minimum-norm solution
/// (unused unknowns zero); returns (Q, h Q', h² Q'') at σ = 1, the step's end.
fn least_squares(
    poly: usize,
    alt: usize,
    n: usize,
    sigma: impl Fn(usize) -> f64,
    value: impl Fn(usize) -> f64,
) -> [f64; 3] {
    // abscissa ξ = σ / s ∈ [−1, 0] on uniform steps: a well-scaled system
    let scale = ((n - 1) as f64).max(1.0);
    let mut a = SMatrix::<f64, TAPS, UNKNOWNS>::zeros();
    let mut b = SVector::<f64, TAPS>::zeros();
    for k in 0..n {
        let xi = sigma(k) / scale;
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        for j in 0..poly {
            a[(k, j)] = xi.powi(j as i32);
        }
        for m in 0..alt {
            a[(k, POLY + m)] = sign * xi.powi(m as i32);
        }
        b[k] = value(k);
    }
    let coef = a.svd(true, true).solve(&b, 1e-12).unwrap_or_else(|_| {
        let mut c = SVector::<f64, UNKNOWNS>::zeros();
        c[0] = value(0);
        c
    });
    let (mut q, mut slope, mut curvature) = (0.0, 0.0, 0.0);
    for j in 0..poly {
        let cj = coef[j] / scale.powi(j as i32);
        q += cj;
        slope += j as f64 * cj;
        curvature += (j * j.saturating_sub(1)) as f64 * cj;
    }
    [q, slope, curvature]
}

/// The weights of each design's fit on uniform steps with its window full:
/// (Q, h Q', h² Q'') = Σ_k w[·][k] u_k. The fit is linear in the samples and,
/// on uniform steps (σ_k = −k), independent of h, so a fixed-step master's
/// communication step takes a dot product instead of a singular value
/// decomposition per axis (computed once per process by the same solve).
fn uniform_weights(index: usize) -> &'static [[f64; TAPS]; 3] {
    static WEIGHTS: std::sync::OnceLock<[[[f64; TAPS]; 3]; 3]> = std::sync::OnceLock::new();
    &WEIGHTS.get_or_init(|| {
        std::array::from_fn(|di| {
            let d = DESIGNS[di].1;
            let mut w = [[0.0; TAPS]; 3];
            for k in 0..d.taps {
                let r = least_squares(d.poly, d.alt, d.taps, |j| -(j as f64), |j| if j == k { 1.0 } else { 0.0 });
                for c in 0..3 {
                    w[c][k] = r[c];
                }
            }
            w
        })
    })[index]
}

/// The weights of the design `index` once m uniform points are known
/// ([`CONSISTENT`]; zero beyond m): the value row that of the fit
/// ([`uniform_weights`]); the slope and curvature rows w (order r = 1, 2)
/// minimise wᵀ B w, B_ij = (1/(π − a)) ∫_a^π cos((i − j) θ) dθ (a = band π,
/// with 1e-9 on the diagonal), subject to, with ξ_k = −k/(m − 1),
///   Σ_k w_k ξ_k^p = Σ_k w0_k d^r/dσ^r (σ/(m − 1))^p at σ = −k,  p ≤ d
/// (for u = the polynomial, h^r times the r-th derivative of the end values'
/// sequence Σ_k w0_k u(t − k h)), and Σ_k w_k (−1)^k ξ_k^q = 0 for the
/// design's nuisances q (computed once per process, the KKT system by LU
/// with full pivoting).
fn consistent_weights(index: usize) -> &'static [[f64; TAPS]; 3] {
    const CONSTRAINTS: usize = CONSISTENT_DEGREE + 1 + 3;
    const KKT: usize = TAPS + CONSTRAINTS;
    static WEIGHTS: std::sync::OnceLock<[[[f64; TAPS]; 3]; 3]> = std::sync::OnceLock::new();
    &WEIGHTS.get_or_init(|| {
        std::array::from_fn(|di| {
            let mut w = [[0.0; TAPS]; 3];
            let Some((band, degree, taps)) = CONSISTENT[di] else { return w };
            let d = DESIGNS[di].1;
            let w0 = uniform_weights(di)[0];
            w[0] = w0;
            let scale = (taps - 1) as f64;
            let a = band * std::f64::consts::PI;
            let b = |m: usize| {
                if m == 0 { 1.0 } else { -(a * m as f64).sin() / (m as f64 * (std::f64::consts::PI - a)) }
            };
            for (order, row) in [(1usize, 1usize), (2, 2)] {
                let mut k = SMatrix::<f64, KKT, KKT>::zeros();
                let mut rhs = SVector::<f64, KKT>::zeros();
                for i in 0..TAPS {
                    for j in 0..TAPS {
                        k[(i, j)] = if i < taps && j < taps {
                            2.0 * b(i.abs_diff(j)) + if i == j { 2e-9 } else { 0.0 }
                        } else if i == j {
                            // beyond the window: w_i = 0 (no constraint row reaches it)
                            1.0
                        } else {
                            0.0
                        };
                    }
                }
                let xi = |i: usize| -(i as f64) / scale;
                let mut c = TAPS;
                for p in 0..=CONSISTENT_DEGREE {
                    if p > degree {
                        // beyond the design's degree: its multiplier is zero
                        k[(c, c)] = 1.0;
                        c += 1;
                        continue;
                    }
                    for i in 0..taps {
                        k[(c, i)] = xi(i).powi(p as i32);
                        k[(i, c)] = k[(c, i)];
                    }
                    if p >= order {
                        let falling: f64 = (0..order).map(|m| (p - m) as f64).product();
                        rhs[c] = (0..d.taps)
                            .map(|i| w0[i] * falling / scale.powi(order as i32) * xi(i).powi((p - order) as i32))
                            .sum();
                    }
                    c += 1;
                }
                for q in 0..3 {
                    if q < d.alt {
                        for i in 0..taps {
                            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                            k[(c, i)] = sign * xi(i).powi(q as i32);
                            k[(i, c)] = k[(c, i)];
                        }
                    } else {
                        // no such nuisance: its multiplier is zero
                        k[(c, c)] = 1.0;
                    }
                    c += 1;
                }
                // regular (independent constraints, a positive definite B); Q's own
                // otherwise. One step of iterative refinement: the constraints then
                // hold to round-off of the weights (an alternation of 1e-5 m moves
                // the path by 1e-18 m, not 1e-17)
                let lu = k.full_piv_lu();
                match lu.solve(&rhs) {
                    Some(x) => {
                        let x = x + lu.solve(&(rhs - k * x)).unwrap_or_default();
                        w[row].copy_from_slice(&x.as_slice()[..TAPS]);
                    }
                    None => w[row] = uniform_weights(di)[row],
                }
            }
            w
        })
    })[index]
}

/// The weights of the design of [`VELOCITY_DESIGN`] (7.10): (Q, h Q', h² Q'')
/// = Σ_k wu[·][k] u_k + wv[·][k] h v_k on uniform steps (σ_k = −k), the
/// least-squares solution of
///   Q(σ_k) + a (−1)^k = u_k,   dQ/dσ(σ_k) + b (−1)^k + c = h v_k,   k < 5,
/// for the quintic Q and the nuisances a, b, c (computed once per process;
/// Σ_k wv[·][k] = 0: an offset of the velocities is not motion).
fn velocity_weights() -> &'static [[[f64; VELOCITY_TAPS]; 3]; 2] {
    const ROWS: usize = 2 * VELOCITY_TAPS;
    const COEF: usize = 6;
    static WEIGHTS: std::sync::OnceLock<[[[f64; VELOCITY_TAPS]; 3]; 2]> = std::sync::OnceLock::new();
    WEIGHTS.get_or_init(|| {
        // unknowns: Q's coefficients, a, b, c
        let mut a = SMatrix::<f64, ROWS, { COEF + 3 }>::zeros();
        for k in 0..VELOCITY_TAPS {
            let (sigma, sign) = (-(k as f64), if k % 2 == 0 { 1.0 } else { -1.0 });
            for j in 0..COEF {
                a[(k, j)] = sigma.powi(j as i32);
                if j > 0 {
                    a[(VELOCITY_TAPS + k, j)] = j as f64 * sigma.powi(j as i32 - 1);
                }
            }
            a[(k, COEF)] = sign;
            a[(VELOCITY_TAPS + k, COEF + 1)] = sign;
            a[(VELOCITY_TAPS + k, COEF + 2)] = 1.0;
        }
        let svd = a.svd(true, true);
        let mut w = [[[0.0; VELOCITY_TAPS]; 3]; 2];
        for row in 0..ROWS {
            let coef =
                svd.solve(&SVector::<f64, ROWS>::from_fn(|r, _| (r == row) as u8 as f64), 1e-12).unwrap_or_default();
            let at_end = [
                (0..COEF).map(|j| coef[j]).sum::<f64>(),
                (1..COEF).map(|j| j as f64 * coef[j]).sum(),
                (2..COEF).map(|j| (j * (j - 1)) as f64 * coef[j]).sum(),
            ];
            for c in 0..3 {
                w[row / VELOCITY_TAPS][c][row % VELOCITY_TAPS] = at_end[c];
            }
        }
        w
    })
}

/// The slope and curvature rows of the velocity design once the vessel's
/// answer to riser's own load is known (docs/theory.md (7.10a)), for
/// [`VELOCITY_CONSISTENT`] = (m, d): h and h² times the derivatives at its
/// last point of the least-squares polynomial of degree d through the last
/// m end values e_j = Σ_k wu0_k u_{j+k} + wv0_k h v_{j+k} (j = 0 the newest,
/// at σ = 1 − j; wu0, wv0 the value rows of [`velocity_weights`]), written
/// out over the last m + 4 samples; the value row is (7.10)'s. The rows are
/// combinations of shifted value rows, so the value row's nuisances (the
/// alternations, the velocities' offset) are removed from them too
/// (computed once per process).
fn velocity_consistent_weights() -> &'static [[[f64; TAPS]; 3]; 2] {
    const M: usize = VELOCITY_CONSISTENT.0;
    const D: usize = VELOCITY_CONSISTENT.1;
    static WEIGHTS: std::sync::OnceLock<[[[f64; TAPS]; 3]; 2]> = std::sync::OnceLock::new();
    WEIGHTS.get_or_init(|| {
        let scale = (M - 1) as f64;
        // the fit in x = σ/(m − 1), the end values at σ = 1 − j
        let a = SMatrix::<f64, M, { D + 1 }>::from_fn(|j, p| ((1.0 - j as f64) / scale).powi(p as i32));
        let svd = a.svd(true, true);
        let x = 1.0 / scale;
        // c[r][j]: h^r d^r/dσ^r of the fit at σ = 1 per unit end value j
        let mut c = [[0.0; M]; 3];
        for j in 0..M {
            let coef = svd.solve(&SVector::<f64, M>::from_fn(|r, _| (r == j) as u8 as f64), 1e-14).unwrap_or_default();
            c[1][j] = (1..=D).map(|p| p as f64 * coef[p] * x.powi(p as i32 - 1)).sum::<f64>() / scale;
            c[2][j] =
                (2..=D).map(|p| (p * (p - 1)) as f64 * coef[p] * x.powi(p as i32 - 2)).sum::<f64>() / (scale * scale);
        }
        let value = velocity_weights();
        let mut w = [[[0.0; TAPS]; 3]; 2];
        for (src, dst) in value.iter().zip(w.iter_mut()) {
            dst[0][..VELOCITY_TAPS].copy_from_slice(&src[0]);
            for r in 1..3 {
                for j in 0..M {
                    for k in 0..VELOCITY_TAPS {
                        dst[r][j + k] += c[r][j] * src[0][k];
                    }
                }
            }
        }
        w
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vessel at its reference point (the translations' tests).
    const AT_REFERENCE: Vessel =
        Vessel { offset: V3::new(0.0, 0.0, 0.0), order: crate::math::rigid::RotationOrder::Zyx };

    /// Plans with the translation inputs alone.
    fn plan3(hist: &InputHistory, c: Coupling, t: f64, h: f64, u: &[f64; 3], v: &[f64; 3], at: &HangOff) -> Path {
        hist.plan(c, &AT_REFERENCE, t, h, &VesselInputs { u: *u, v: *v, ..Default::default() }, at)
    }

    fn commit3(hist: &mut InputHistory, t: f64, v: &[f64; 3], path: &Path) {
        hist.commit(t, &VesselInputs { v: *v, ..Default::default() }, path);
    }

    fn hang_off(z: f64, vz: f64) -> HangOff {
        HangOff::translation(V3::new(0.0, 0.0, z), V3::new(0.0, 0.0, vz))
    }

    /// Drives the history with heave u(t) (when given) and its velocity
    /// input `v` (when given) at communication points `times` under `auto`,
    /// returning the hang-off at each point and the paths.
    fn drive(
        times: &[f64],
        u: Option<&dyn Fn(f64) -> f64>,
        v: Option<&dyn Fn(f64) -> f64>,
    ) -> (Vec<HangOff>, Vec<Path>) {
        drive_with_mass(times, u, v, 0.0)
    }

    /// [`drive`] with the vessel's mass `mass` on every axis given (§7.8; riser's load zero).
    fn drive_with_mass(
        times: &[f64],
        u: Option<&dyn Fn(f64) -> f64>,
        v: Option<&dyn Fn(f64) -> f64>,
        mass: f64,
    ) -> (Vec<HangOff>, Vec<Path>) {
        let mut hist = InputHistory::new();
        hist.mass = [mass; 3];
        hist.end_value_rates = true;
        let pos = |t: f64| u.map_or(0.0, |u| u(t));
        let vel = |t: f64| v.map_or(0.0, |v| v(t));
        let mut at = hang_off(pos(times[0]), vel(times[0]));
        let (mut points, mut paths) = (vec![at], vec![]);
        for w in times.windows(2) {
            let (t, h) = (w[0], w[1] - w[0]);
            let (inp, vin) = ([pos(t), 0.0, 0.0], [vel(t), 0.0, 0.0]);
            if u.is_some() {
                hist.note_set(0);
            }
            if v.is_some() {
                hist.note_set(3);
            }
            let path = plan3(&hist, Coupling::Auto, t, h, &inp, &vin, &at);
            commit3(&mut hist, t, &vin, &path);
            at = path.at(t + h);
            points.push(at);
            paths.push(path);
        }
        (points, paths)
    }

    #[test]
    fn the_path_is_c2_at_communication_points_and_starts_where_the_hang_off_is() {
        let times: Vec<f64> = [0.0, 0.2, 0.5, 0.6, 1.0, 1.3, 1.4, 1.45, 1.9, 2.0, 2.3].to_vec();
        let (_, paths) = drive(&times, Some(&|t: f64| 2.5 * (0.7 * t).sin() + 0.3 * t * t), None);
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

    /// A master's fixed step of a design's bound, stepping as fmpy does to
    /// the next multiple of h (lengths on either side of h in floating
    /// point), takes one design at every step: the one above the bound.
    #[test]
    fn a_fixed_step_at_a_design_s_bound_takes_one_design() {
        for (bound, above) in [(DESIGNS[0].0, DESIGNS[1].1), (DESIGNS[1].0, DESIGNS[2].1)] {
            let steps: Vec<f64> = (0..2000).map(|k| (k + 1) as f64 * bound - k as f64 * bound).collect();
            assert!(steps.iter().any(|&h| h < bound) && steps.iter().any(|&h| h > bound), "{bound}");
            assert!(steps.iter().all(|&h| design(h) == above), "{bound}");
            assert!(steps.iter().all(|&h| !shorter(h, VELOCITY_DESIGN)) == (bound == VELOCITY_DESIGN));
        }
    }

    #[test]
    fn each_design_follows_its_polynomials_and_ignores_alternation_once_its_points_are_known() {
        // per design, steps drawn within its range of sizes: a polynomial of its degree, and the
        // same plus an alternating sequence, are followed exactly once `taps` points are known
        let mut below = 0.01;
        for (above, d) in DESIGNS {
            let top = above.min(1.0);
            let times: Vec<f64> = (0..24)
                .scan(0.0, |t, k| {
                    let x = *t;
                    *t += below + (top - below) * (0.5 + 0.45 * (1.7 * k as f64).sin());
                    Some(x)
                })
                .collect();
            assert!(times.windows(2).all(|w| design(w[1] - w[0]) == d));
            let coef = [1.0, -0.4, 0.9, -0.3, 0.05];
            let u = |t: f64| (0..d.poly).map(|j| coef[j] * t.powi(j as i32)).sum::<f64>();
            let du = |t: f64| (1..d.poly).map(|j| j as f64 * coef[j] * t.powi(j as i32 - 1)).sum::<f64>();
            let (points, _) = drive(&times, Some(&u), None);
            for k in d.taps..times.len() {
                assert!((points[k].displacement.z - u(times[k])).abs() < 1e-10, "{d:?} {k}");
                assert!((points[k].velocity.z - du(times[k])).abs() < 1e-9, "{d:?} {k}");
            }
            let index = |t: f64| times.iter().position(|&x| x == t).unwrap_or(0);
            let alt = |t: f64| u(t) + 1e-3 * if index(t) % 2 == 0 { 1.0 } else { -1.0 };
            let (noisy, _) = drive(&times, Some(&alt), None);
            for k in d.taps + 1..times.len() {
                assert!((noisy[k].displacement.z - u(times[k])).abs() < 1e-10, "{d:?} {k}");
            }
            below = above;
        }
    }

    #[test]
    fn velocity_alone_is_integrated_to_fourth_order_at_any_step_sizes() {
        // a cubic velocity is integrated exactly over an interval once four velocities are known
        let v = |t: f64| 0.3 - 0.5 * t + 0.2 * t * t - 0.04 * t.powi(3);
        let x = |t: f64| 0.3 * t - 0.25 * t * t + 0.2 / 3.0 * t.powi(3) - 0.01 * t.powi(4);
        let times = [0.0, 0.3, 0.5, 0.9, 1.0, 1.6, 1.7, 2.5];
        let (_, paths) = drive(&times, None, Some(&v));
        assert!(paths.iter().all(|p| p.sources[0] == RateSource::Velocity));
        for k in 4..paths.len() {
            let (dx, exact) = (paths[k].u[0] - paths[k - 1].u[0], x(times[k]) - x(times[k - 1]));
            assert!((dx - exact).abs() < 1e-13, "{k}: {dx} {exact}");
        }
        // and a smooth motion's position to fourth order in the step
        let err = |h: f64| {
            let w = 2.0 * std::f64::consts::PI / 20.0;
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let (_, paths) = drive(&times, None, Some(&|t: f64| 2.5 * w * (w * t).cos()));
            (1..paths.len()).map(|k| (paths[k].u[0] - 2.5 * (w * times[k]).sin()).abs()).fold(0.0, f64::max)
        };
        let order = (err(0.8) / err(0.4)).log2();
        assert!(order > 2.8, "order {order}");
    }

    #[test]
    fn the_error_at_communication_points_is_fifth_order_in_the_step() {
        // heave 2.5 sin(2πt/20): max |x − u| over 40 s at h and h/2
        let err = |h: f64| {
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let u = |t: f64| 2.5 * (2.0 * std::f64::consts::PI * t / 20.0).sin();
            let (points, _) = drive(&times, Some(&u), None);
            (10..times.len()).map(|k| (points[k].displacement.z - u(times[k])).abs()).fold(0.0, f64::max)
        };
        let (e1, e2) = (err(0.8), err(0.4));
        let order = (e1 / e2).log2();
        assert!((order - 5.0).abs() < 0.3, "{e1} {e2} order {order}");
        // closed form (docs/theory.md §7.3): the error of (7.1) on uniform
        // steps is (1 − w)⁵ (1 + 31w/32) in the shift w = e^{−iθ}, θ = ωh
        let closed = |h: f64| {
            let th = 2.0 * std::f64::consts::PI * h / 20.0;
            let r = ((1.0 + 31.0 / 32.0 * th.cos()).powi(2) + (31.0 / 32.0 * th.sin()).powi(2)).sqrt();
            2.5 * (2.0 * (th / 2.0).sin()).powi(5) * r
        };
        assert!((e2 / closed(0.4) - 1.0).abs() < 0.01, "{e2} {}", closed(0.4));
    }

    /// Heave 0.23 sin(2πt/10) at uniform steps h over 60 s, with its velocity
    /// input too when `both`, off the heave's slope by `offset` cos(2πt/10)
    /// m/s: the largest error of the hang-off at the communication points and
    /// of the path's acceleration inside the steps (after the first 10 s), and
    /// the paths.
    fn wave_errors(h: f64, both: bool, offset: f64) -> (f64, f64, Vec<Path>) {
        wave_errors_with_mass(h, both, offset, 0.0)
    }

    /// [`wave_errors`] with the vessel's mass given (§7.8).
    fn wave_errors_with_mass(h: f64, both: bool, offset: f64, mass: f64) -> (f64, f64, Vec<Path>) {
        let w = 2.0 * std::f64::consts::PI / 10.0;
        let u = |t: f64| 0.23 * (w * t).sin();
        let v = |t: f64| (0.23 * w + offset) * (w * t).cos();
        let times: Vec<f64> = (0..=(60.0 / h).round() as usize).map(|k| k as f64 * h).collect();
        let (points, paths) = drive_with_mass(&times, Some(&u), if both { Some(&v) } else { None }, mass);
        let late = (10.0 / h) as usize;
        let at = (late..times.len()).map(|k| (points[k].displacement.z - u(times[k])).abs()).fold(0.0, f64::max);
        let inside = paths[late..]
            .iter()
            .flat_map(|p| (0..=8).map(move |j| p.t + p.h * j as f64 / 8.0))
            .zip(paths[late..].iter().flat_map(|p| std::iter::repeat_n(p, 9)))
            .map(|(s, p)| (p.acceleration(s).z + w * w * u(s)).abs())
            .fold(0.0, f64::max);
        (at, inside, paths)
    }

    #[test]
    fn with_both_inputs_the_long_steps_fit_the_velocities_too_to_sixth_order() {
        // (7.10): at h ≥ 0.21 s, with the displacement and its velocity set, the
        // end state comes from five points of both; the error at the points
        // falls as h⁶ (the quintic's), 40 and 20 times below the displacement
        // design's at 0.25 and 0.5 s. Inside the steps the displacement design,
        // whose slope and curvature are those of its end values' sequence
        // (7.3a), now follows the motion better (3.5e-5 and 1.9e-3 m/s² against
        // 3.2e-4 and 5.0e-3); the velocity design keeps its own (docs/theory.md §7.4)
        let (e1, _, paths) = wave_errors(0.8, true, 0.0);
        assert!(paths[10..].iter().all(|p| p.sources[0] == RateSource::Both));
        let (e2, _, _) = wave_errors(0.4, true, 0.0);
        let order = (e1 / e2).log2();
        assert!((order - 6.0).abs() < 0.3, "{e1} {e2} order {order}");
        let aw2 = 0.23 * (2.0 * std::f64::consts::PI / 10.0f64).powi(2);
        for (h, bound) in [(0.25, 1e-2), (0.5, 0.15)] {
            let (at_with, with, _) = wave_errors(h, true, 0.0);
            let (at_without, without, _) = wave_errors(h, false, 0.0);
            eprintln!(
                "h {h}: at the points {at_with:.3e} m against {at_without:.3e}; in-step acceleration error \
                 {with:.3e} against {without:.3e} m/s²"
            );
            assert!(at_with < 0.1 * at_without, "{h}: {at_with} against {at_without}");
            assert!(with < bound * aw2, "{h}: {with}");
        }
        // below 0.21 s the displacement designs stay, velocities or not
        let (e_both, _, paths) = wave_errors(0.2, true, 0.0);
        assert!(paths.iter().all(|p| p.sources[0] == RateSource::History));
        assert_eq!(e_both, wave_errors(0.2, false, 0.0).0);
    }

    #[test]
    fn with_the_vessel_s_mass_given_the_long_steps_take_the_end_values_slope_and_curvature() {
        // (7.10a): the slope and curvature rows are h and h² times the derivatives of the end
        // values' sequence E(s) = Σ_k wu0_k u(s − k h) + wv0_k h u'(s − k h) for every polynomial
        // motion of degree ≤ 7 (h = 1, the samples at s = −k), and remove what the value row removes
        let [wu, wv] = velocity_consistent_weights();
        let [wu0, wv0] = velocity_weights();
        let (m, d) = VELOCITY_CONSISTENT;
        assert!(wu.iter().chain(wv.iter()).all(|row| row[m + VELOCITY_TAPS - 1..].iter().all(|&x| x == 0.0)));
        for p in 0..=d as i32 {
            // u = (s/8)^p and its derivatives
            let der = |s: f64, r: i32| -> f64 {
                if r > p {
                    return 0.0;
                }
                let falling: f64 = (0..r).map(|i| (p - i) as f64).product();
                falling * (s / 8.0).powi(p - r) / 8f64.powi(r)
            };
            for r in 1..3 {
                let row: f64 = (0..TAPS).map(|k| wu[r][k] * der(-(k as f64), 0) + wv[r][k] * der(-(k as f64), 1)).sum();
                let exact: f64 = (0..VELOCITY_TAPS)
                    .map(|k| wu0[0][k] * der(-(k as f64), r as i32) + wv0[0][k] * der(-(k as f64), r as i32 + 1))
                    .sum();
                assert!((row - exact).abs() < 1e-10, "degree {p}, order {r}: {row} against {exact}");
            }
        }
        for r in 0..3 {
            let alt = |w: &[f64; TAPS]| (0..TAPS).map(|k| if k % 2 == 0 { w[k] } else { -w[k] }).sum::<f64>();
            assert!(alt(&wu[r]).abs() < 1e-10 && alt(&wv[r]).abs() < 1e-10, "row {r}");
            assert!(wv[r].iter().sum::<f64>().abs() < 1e-10, "row {r}: an offset of the velocities");
        }
        // on the 0.23 m heave at 10 s: the end values unchanged, the path's acceleration inside the
        // steps (what a line stepped inside the communication step sees, at 1/h and its harmonics:
        // 2 Hz at 0.5 s, next to the moored vessel's chains' axial mode at 1.6 Hz) 61 and 16 times
        // closer at 0.25 and 0.5 s (3.2e-4 -> 5.3e-6, 5.0e-3 -> 3.2e-4 m/s²); without the mass Q's own
        for (h, gain) in [(0.25, 10.0), (0.5, 10.0)] {
            let (at_own, own, paths) = wave_errors_with_mass(h, true, 0.0, 3e6);
            let (at_q, q, _) = wave_errors(h, true, 0.0);
            eprintln!(
                "h {h}: in-step acceleration error {own:.2e} m/s² with the mass, {q:.2e} without; at the points {at_own:.2e}, {at_q:.2e} m"
            );
            assert!(paths[20..].iter().all(|p| p.sources[0] == RateSource::Both));
            assert!(own * gain < q, "{h}: {own} against {q}");
            assert!((at_own - at_q).abs() < 1e-3 * at_q, "{h}: {at_own} against {at_q}");
        }
    }

    #[test]
    fn with_both_inputs_an_offset_of_the_velocities_from_the_displacements_slope_is_not_motion() {
        // a body that integrates a force held over each step (a body FMU fed riser's force)
        // reports velocities off its positions' slope by −Ḟ h²/(12 M) (docs/theory.md §7.4)
        let w = 2.0 * std::f64::consts::PI / 10.0;
        let u = |t: f64| 0.23 * (w * t).sin() + 0.02 * (1.2 * t + 1.0).sin();
        let du = |t: f64| 0.23 * w * (w * t).cos() + 0.024 * (1.2 * t + 1.0).cos();
        for h in [0.25f64, 0.5] {
            // a constant offset moves the path not at all, at the points and between them
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let (_, clean) = drive(&times, Some(&u), Some(&du));
            let (_, off) = drive(&times, Some(&u), Some(&|t| du(t) + 3e-4));
            assert!(off[10..].iter().all(|p| p.sources[0] == RateSource::Both));
            for (a, b) in clean[1..].iter().zip(&off[1..]) {
                for j in 0..=8 {
                    let s = a.t + a.h * j as f64 / 8.0;
                    assert!((a.at(s).displacement.z - b.at(s).displacement.z).abs() < 1e-14, "{h} {s}");
                    assert!((a.acceleration(s).z - b.acceleration(s).z).abs() < 1e-12, "{h} {s}");
                }
            }
            // the 50 t buoy's (M + A = 75 t) in its 10 s wave, a force of 1.7 kN held: an offset up
            // to 3.0e-4 m/s at 0.5 s. Fitted as motion (without c) it made the path's in-step
            // acceleration error, the bump that rang the line at 2/h = 4 Hz, 21 times the clean
            // one at 0.5 s (0.106 m/s²) and 180 times at 0.25 s (0.058 m/s²), worse than the poses
            // alone were then (Q's own slope and curvature: 0.064, 0.0082 m/s²; with (7.3a) 1.9e-3
            // and 3.5e-5); with c 2.7 and 6.3 times (0.0138, 0.0020 m/s²)
            let offset = -1.7e3 * w * h * h / (12.0 * 75e3);
            let (_, clean, _) = wave_errors(h, true, 0.0);
            let (_, held, _) = wave_errors(h, true, offset);
            let (_, poses, _) = wave_errors(h, false, 0.0);
            eprintln!(
                "h {h}: in-step acceleration error {held:.3e} with the offset {offset:.2e} m/s, {clean:.3e} without, poses alone {poses:.3e} m/s²"
            );
            assert!(held < [0.003, 0.02][(h > 0.3) as usize], "{h}: {held}");
        }
    }

    #[test]
    fn with_both_inputs_alternation_in_either_moves_the_hang_off_not_at_all() {
        // the nuisances a (−1)^k and b (−1)^k of (7.10): ±1e-5 m on the
        // displacement and ±1e-4 m/s on the velocity, on a still vessel
        for h in [0.25, 0.5] {
            let times: Vec<f64> = (0..=80).map(|k| k as f64 * h).collect();
            let sign = |t: f64| if ((t / h).round() as i64) % 2 == 0 { 1.0 } else { -1.0 };
            let (points, paths) = drive(&times, Some(&|t| 1e-5 * sign(t)), Some(&|t| 1e-4 * sign(t)));
            assert!(paths[10..].iter().all(|p| p.sources[0] == RateSource::Both));
            // the first points pass the alternation (as the displacement design's do); then still
            let settled = points[12].displacement.z;
            for p in &points[12..] {
                assert!((p.displacement.z - settled).abs() < 1e-18, "{h}: {p:?}");
                assert!(p.velocity.z.abs() < 1e-16, "{h}: {p:?}");
            }
        }
    }

    #[test]
    fn each_design_s_end_slope_and_curvature_are_those_of_the_end_values_sequence() {
        // (7.3a): for a polynomial u of the design's degree sampled at σ = −k, the slope
        // and curvature rows give the derivatives of P(σ) = Σ_k w0_k u(σ − k),
        // the end values' sequence as a function of the step's start; an
        // alternation (−1)^k ξ^q of the design's nuisances gives nothing
        for (index, design) in CONSISTENT.iter().enumerate() {
            let Some((_, degree, taps)) = *design else { continue };
            let scale = (taps - 1) as f64;
            let w = consistent_weights(index);
            // nothing beyond the filters' window
            assert!(w.iter().all(|row| row[taps..].iter().all(|&x| x == 0.0)), "design {index}");
            for p in 0..=degree as i32 {
                let u = |s: f64, r: i32| {
                    let falling: f64 = (0..r).map(|m| (p - m) as f64).product();
                    if p < r { 0.0 } else { falling / scale.powi(r) * (s / scale).powi(p - r) }
                };
                for r in 1..3 {
                    let got: f64 = (0..TAPS).map(|k| w[r as usize][k] * u(-(k as f64), 0)).sum();
                    let want: f64 = (0..TAPS).map(|k| w[0][k] * u(-(k as f64), r)).sum();
                    assert!((got - want).abs() < 1e-11, "design {index}, degree {p}, order {r}: {got} {want}");
                }
            }
            for q in 0..DESIGNS[index].1.alt as i32 {
                for r in 1..3 {
                    let alt = |k: usize| if k % 2 == 0 { 1.0 } else { -1.0 } * (-(k as f64) / scale).powi(q);
                    let got: f64 = (0..TAPS).map(|k| w[r][k] * alt(k)).sum();
                    assert!(got.abs() < 1e-12, "design {index}, nuisance {q}, order {r}: {got}");
                }
            }
            // the value row is the fit's own
            assert_eq!(w[0], uniform_weights(index)[0]);
        }
    }

    #[test]
    fn the_middle_design_keeps_the_constraints_of_7_1_and_7_3a() {
        // (7.3b): the value row predicts every quartic one step ahead, the slope and
        // curvature rows are those of the end values' sequence Σ_k w0_k u(σ − k) for
        // every polynomial of degree ≤ 7, and no row answers (−1)^k or ξ_k (−1)^k
        // (ξ_k = −k/15): the table's digits hold what its design imposed
        let w = &MIDDLE;
        let scale = (TAPS - 1) as f64;
        let xi = |k: usize| -(k as f64) / scale;
        for p in 0..=4 {
            let got: f64 = (0..TAPS).map(|k| w[0][k] * xi(k).powi(p)).sum();
            assert!((got - (1.0 / scale).powi(p)).abs() < 1e-12, "value, degree {p}: {got}");
        }
        for p in 0..=7i32 {
            for r in 1..3i32 {
                let falling: f64 = (0..r).map(|m| (p - m) as f64).product();
                let got: f64 = (0..TAPS).map(|k| w[r as usize][k] * xi(k).powi(p)).sum();
                let want: f64 = if p < r {
                    0.0
                } else {
                    (0..TAPS).map(|k| w[0][k] * falling / scale.powi(r) * xi(k).powi(p - r)).sum()
                };
                assert!((got - want).abs() < 1e-12, "degree {p}, order {r}: {got} {want}");
            }
        }
        for q in 0..2 {
            for (r, row) in w.iter().enumerate() {
                let got: f64 = (0..TAPS).map(|k| row[k] * if k % 2 == 0 { 1.0 } else { -1.0 } * xi(k).powi(q)).sum();
                assert!(got.abs() < 1e-12, "nuisance {q}, row {r}: {got}");
            }
        }
        // and a fixed-step master at 0.1 s follows a quartic exactly with it once sixteen points are known
        let h = 0.1;
        let u = |t: f64| 0.3 * t - 0.02 * t * t + 1e-3 * t.powi(3) - 2e-5 * t.powi(4);
        let times: Vec<f64> = (0..=40).map(|k| k as f64 * h).collect();
        let (_, paths) = drive(&times, Some(&u), None);
        let du = |t: f64| 0.3 - 0.04 * t + 3e-3 * t * t - 8e-5 * t.powi(3);
        let ddu = |t: f64| -0.04 + 6e-3 * t - 2.4e-4 * t * t;
        for p in &paths[20..] {
            let s = p.t + h;
            let e = [p.end[0][0] - u(s), p.end[0][1] - h * du(s), p.end[0][2] - h * h * ddu(s)];
            assert!(e.iter().all(|x| x.abs() < 1e-12), "t {}: {e:?}", p.t);
        }
    }

    #[test]
    fn an_alternating_input_stops_moving_the_hang_off_once_the_nuisance_is_in_the_fit() {
        // ±1e-5 m from t = 0: the first four points are the interpolating
        // polynomials of degree 0..3 (a motion starting from rest needs them),
        // which pass the alternation multiplied by 1, 3, 7, 15; from the fifth
        // on the nuisance is in the fit and the hang-off stands still, at the
        // points and between them (docs/theory.md §7.1, §7.3)
        for h in [0.05, 0.2, 0.5] {
            let times: Vec<f64> = (0..=200).map(|k| k as f64 * h).collect();
            let alt = |t: f64| if ((t / h).round() as i64) % 2 == 0 { 1e-5 } else { -1e-5 };
            let (points, paths) = drive(&times, Some(&alt), None);
            for (k, gain) in [1.0, 3.0, 7.0, 15.0].iter().enumerate() {
                let z = points[k + 1].displacement.z.abs();
                assert!((z - gain * 1e-5).abs() < 1e-15, "{h} {k}: {z}");
            }
            for p in &points[5..] {
                assert!(p.displacement.z.abs() < 1e-18, "{h}: {p:?}");
            }
            let inside = paths[5..].iter().map(|p| p.at(p.t + 0.5 * p.h).displacement.z.abs()).fold(0.0, f64::max);
            assert!(inside < 1e-18, "{h}: {inside}");
        }
    }

    #[test]
    fn derivatives_take_precedence_over_the_history_and_the_mode_follows_what_is_set() {
        let mut hist = InputHistory::new();
        hist.note_set(0);
        let at = hang_off(0.0, 0.0);
        let path = plan3(&hist, Coupling::Auto, 0.0, 0.1, &[0.0; 3], &[0.0; 3], &at);
        commit3(&mut hist, 0.0, &[0.0; 3], &path);
        // a derivative and the history: Q(0) + a = 0.2, Q'(0) = 1.5, Q''(0) = −2, Q(−0.1) − a = 0
        hist.pending.first[0] = Some(1.5);
        hist.pending.second[0] = Some(-2.0);
        let h = 0.1;
        let path = plan3(&hist, Coupling::Auto, 0.1, h, &[0.2, 0.0, 0.0], &[0.0; 3], &at);
        assert_eq!(path.sources[0], RateSource::Derivatives);
        assert_eq!(path.sources[1], RateSource::History);
        // Q = c0 + 1.5τ − τ²: c0 + a = 0.2, c0 − 0.15 − 0.01 − a = 0
        let c0 = 0.5 * (0.2 + 0.16);
        let end = path.at(0.2).displacement.z;
        assert!((end - (c0 + 1.5 * h - h * h)).abs() < 1e-12, "{end}");
        // the velocity of sway set, its displacement not: sway is driven by velocity
        hist.note_set(5);
        assert_eq!(hist.modes(Coupling::Auto), [Coupling::Displacement, Coupling::Displacement, Coupling::Velocity]);
        hist.note_set(2);
        assert_eq!(hist.modes(Coupling::Auto)[2], Coupling::Both);
        assert_eq!(hist.modes(Coupling::Velocity), [Coupling::Velocity; 3]);
        let path = plan3(&hist, Coupling::Velocity, 0.1, h, &[0.2, 0.0, 0.0], &[0.0, 0.7, 0.0], &at);
        assert_eq!(path.sources[1], RateSource::Velocity);
        // velocity coupling: the displacement input is ignored, the derivatives too
        assert_eq!(path.u[0], 0.0);
        assert_eq!(path.sources[0], RateSource::Velocity);
        commit3(&mut hist, 0.1, &[0.0, 0.7, 0.0], &path);
        assert_eq!(hist.pending, Derivatives::default());
    }

    #[test]
    fn the_history_survives_its_numbers() {
        let mut hist = InputHistory::new();
        let at = hang_off(0.0, 0.0);
        for k in 0..7 {
            let t = 0.25 * k as f64;
            let u = [0.1 * t, 0.2 + t, 0.3 - t * t];
            hist.note_set(0);
            if k == 3 {
                hist.note_set(5);
            }
            let path = plan3(&hist, Coupling::Auto, t, 0.25, &u, &[0.0, 0.0, -1.0], &at);
            commit3(&mut hist, t, &[0.0, 0.0, -1.0], &path);
        }
        hist.pending.first[1] = Some(3.0);
        hist.pending.second[2] = Some(-4.0);
        let back = InputHistory::from_values(&hist.to_values()).unwrap();
        assert_eq!(back, hist);
        let mut bad = hist.to_values();
        bad[PAST * SAMPLE_VALUES] = 0.5;
        assert!(InputHistory::from_values(&bad).is_none());
        assert!(InputHistory::from_values(&bad[..20]).is_none());
    }

    use crate::math::rigid::RotationOrder;

    /// Drives the history with the vessel's angles `angles(t)` (when
    /// `use_angles`) and its body rates `rates(t)` (when given) under `auto`,
    /// the hang-off at `vessel`'s offset; returns the hang-off at each
    /// communication point and the paths.
    fn drive_rotation(
        times: &[f64],
        vessel: &Vessel,
        angles: &dyn Fn(f64) -> [f64; 3],
        rates: Option<&dyn Fn(f64) -> [f64; 3]>,
        use_angles: bool,
    ) -> (Vec<HangOff>, Vec<Path>) {
        let mut hist = InputHistory::new();
        let inp = |t: f64| VesselInputs {
            angles: if use_angles { angles(t) } else { [0.0; 3] },
            rates: rates.map_or([0.0; 3], |r| r(t)),
            ..Default::default()
        };
        if use_angles {
            hist.note_set(7);
        }
        if rates.is_some() {
            hist.note_set(11);
        }
        let mut at = hist.start(Coupling::Auto, vessel, &inp(times[0]));
        let (mut points, mut paths) = (vec![at], vec![]);
        for w in times.windows(2) {
            let (t, h) = (w[0], w[1] - w[0]);
            let path = hist.plan(Coupling::Auto, vessel, t, h, &inp(t), &at);
            hist.commit(t, &inp(t), &path);
            at = path.at(t + h);
            points.push(at);
            paths.push(path);
        }
        (points, paths)
    }

    /// A smooth attitude (period 20 s, angles up to 0.2 rad), its rates.
    fn attitude(t: f64) -> [f64; 3] {
        let w = 2.0 * std::f64::consts::PI / 20.0;
        [
            0.1 * (w * t).sin(),
            0.06 * (w * t + 1.0).sin() - 0.06 * 1f64.sin(),
            0.2 * (w * t + 2.0).sin() - 0.2 * 2f64.sin(),
        ]
    }

    fn attitude_rates(t: f64) -> [f64; 3] {
        let w = 2.0 * std::f64::consts::PI / 20.0;
        [0.1 * w * (w * t).cos(), 0.06 * w * (w * t + 1.0).cos(), 0.2 * w * (w * t + 2.0).cos()]
    }

    /// The angle between two rotations, rad.
    fn angle_between(a: &M3, b: &M3) -> f64 {
        log_so3(&(a * b.transpose())).norm()
    }

    #[test]
    fn the_rotation_follows_a_smooth_attitude_to_fifth_order_in_both_orders() {
        // the path's rotation at the communication points against R(a(t)):
        // the fit of §7.3 on the rotation vectors, O(h⁵) as the translations
        for order in [RotationOrder::Zyx, RotationOrder::Xyz] {
            let vessel = Vessel { offset: V3::new(30.0, -8.0, 4.0), order };
            let err = |h: f64| {
                let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
                let (points, _) = drive_rotation(&times, &vessel, &attitude, None, true);
                (10..times.len())
                    .map(|k| angle_between(&points[k].rotation, &order.rotation(attitude(times[k]))))
                    .fold(0.0, f64::max)
            };
            let (e1, e2) = (err(0.8), err(0.4));
            let rate = (e1 / e2).log2();
            assert!((rate - 5.0).abs() < 0.3, "{order:?}: {e1:e} {e2:e} order {rate}");
            // and the size of the translations' error (docs/theory.md §7.3): a
            // displacement of amplitude |a| errs by (2 sin(θ/2))⁵ |1 + 31/32 e^{−iθ}| |a|
            let th = 2.0 * std::f64::consts::PI * 0.4 / 20.0;
            let amplitude = (0.1f64.powi(2) + 0.06f64.powi(2) + 0.2f64.powi(2)).sqrt();
            let closed = (2.0 * (th / 2.0).sin()).powi(5)
                * ((1.0 + 31.0 / 32.0 * th.cos()).powi(2) + (31.0 / 32.0 * th.sin()).powi(2)).sqrt()
                * amplitude;
            assert!(e2 < 1.5 * closed, "{order:?}: {e2:e} against {closed:e}");
        }
    }

    #[test]
    fn the_rotation_s_path_inside_the_steps_follows_the_attitude_s_angular_acceleration() {
        // the rotation vectors go through the same fit, so the slope and
        // curvature of (7.3a) make the path's angular acceleration inside the
        // steps follow the attitude's: 5.3e-6, 4.1e-5 and 1.2e-3 of a ω² at
        // 0.05, 0.1 and 0.2 s (bounds about three times that; with Q's own,
        // 2.8e-3, 7.9e-3 and 6.3e-2), and with the six-point design's window
        // of ten at 0.25 and 0.5 s 4.9e-5 and 2.5e-3; the angular velocity in the global
        // frame, vee(Ṙ Rᵀ), differenced over ±1e-4 s on the path and on R(a(t))
        let order = RotationOrder::Zyx;
        let vessel = Vessel { offset: V3::new(30.0, -8.0, 4.0), order };
        let w = 2.0 * std::f64::consts::PI / 20.0;
        let aw2 = (0.1f64.powi(2) + 0.06f64.powi(2) + 0.2f64.powi(2)).sqrt() * w * w;
        let exact_rate = |t: f64| {
            let d = 1e-5;
            let (r0, r1, r2) =
                (order.rotation(attitude(t - d)), order.rotation(attitude(t)), order.rotation(attitude(t + d)));
            let k = (r2 - r0) / (2.0 * d) * r1.transpose();
            V3::new(k[(2, 1)], k[(0, 2)], k[(1, 0)])
        };
        for (h, bound) in [(0.05f64, 2e-5), (0.1, 1.5e-4), (0.2, 4e-3), (0.25, 1.5e-4), (0.5, 8e-3)] {
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let (_, paths) = drive_rotation(&times, &vessel, &attitude, None, true);
            let d = 1e-4;
            let worst = paths
                .iter()
                .filter(|p| p.t >= 20.0)
                .flat_map(|p| (1..7).map(move |j| (p, p.t + p.h * j as f64 / 7.0)))
                .map(|(p, s)| {
                    let path = (p.rotation(s + d).1 - p.rotation(s - d).1) / (2.0 * d);
                    let exact = (exact_rate(s + d) - exact_rate(s - d)) / (2.0 * d);
                    (path - exact).norm()
                })
                .fold(0.0, f64::max);
            eprintln!("h {h} s: the rotation's angular acceleration inside the steps errs {:.1e} of a ω²", worst / aw2);
            assert!(worst <= bound * aw2, "h {h}: {:.2e} of a ω²", worst / aw2);
        }
    }

    #[test]
    fn the_hang_off_moves_as_the_point_of_the_rotating_vessel() {
        // along the paths: the hang-off's velocity is the rate of its
        // displacement, Ṙ = [ω]× R, the displacement is (R − I)ρ (the
        // reference point held), and ω is continuous at communication points
        let vessel = Vessel { offset: V3::new(30.0, -8.0, 4.0), order: RotationOrder::Zyx };
        let times: Vec<f64> = [0.0, 0.2, 0.5, 0.6, 1.0, 1.3, 1.4, 1.45, 1.9, 2.0, 2.3].to_vec();
        let (_, paths) = drive_rotation(&times, &vessel, &attitude, None, true);
        for k in 0..paths.len() {
            let (t0, t1) = (times[k], times[k + 1]);
            let (e, s) = (1e-6, 0.5 * (t0 + t1));
            let (a, b, m) = (paths[k].at(s - e), paths[k].at(s + e), paths[k].at(s));
            let fd = (b.displacement - a.displacement) / (2.0 * e);
            assert!((fd - m.velocity).norm() < 1e-7, "{k}: {fd} {}", m.velocity);
            let rd = (b.rotation - a.rotation) / (2.0 * e);
            assert!((rd - crate::math::skew(&m.angular_velocity) * m.rotation).norm() < 1e-9, "{k}");
            let arm = m.rotation * vessel.offset;
            assert!((m.displacement - (arm - vessel.offset)).norm() < 1e-13, "{k}");
            if k + 1 < paths.len() {
                let (l, r) = (paths[k].at(t1), paths[k + 1].at(t1));
                assert_eq!(l.rotation, r.rotation, "{k}");
                assert!((l.angular_velocity - r.angular_velocity).norm() < 1e-15, "{k}");
                // the angular acceleration too (C2), by second-order one-sided differences
                let e = 1e-5;
                let w = |p: &Path, s: f64| p.at(s).angular_velocity;
                let left =
                    (3.0 * w(&paths[k], t1) - 4.0 * w(&paths[k], t1 - e) + w(&paths[k], t1 - 2.0 * e)) / (2.0 * e);
                let right = (-3.0 * w(&paths[k + 1], t1) + 4.0 * w(&paths[k + 1], t1 + e)
                    - w(&paths[k + 1], t1 + 2.0 * e))
                    / (2.0 * e);
                assert!((left - right).norm() < 1e-6 * left.norm().max(1.0), "{k}: {left} {right}");
            }
        }
        // held at a pose: the hang-off at (R − I)ρ, at rest
        let pose = [0.05, -0.08, 0.3];
        let times: Vec<f64> = (0..30).map(|k| k as f64 * 0.1).collect();
        let (points, _) = drive_rotation(&times, &vessel, &|_| pose, None, true);
        let r = vessel.order.rotation(pose);
        for p in &points {
            assert!((p.displacement - (r * vessel.offset - vessel.offset)).norm() < 1e-13);
            assert!(p.velocity.norm() < 1e-13 && p.angular_velocity.norm() < 1e-15);
            assert!((p.rotation - r).norm() < 1e-15);
        }
    }

    #[test]
    fn angular_velocity_alone_is_integrated_exactly_for_cubic_rates() {
        let vessel = Vessel { offset: V3::zeros(), order: RotationOrder::Zyx };
        // a constant rate about a fixed axis: exact
        let w = [0.02, -0.05, 0.1];
        let times: Vec<f64> = [0.0, 0.3, 0.5, 0.9, 1.0, 1.6, 1.7, 2.5].to_vec();
        let (_, paths) = drive_rotation(&times, &vessel, &|_| [0.0; 3], Some(&|_| w), false);
        assert!(paths.iter().all(|p| p.rotation_source == RateSource::Velocity));
        for (k, p) in paths.iter().enumerate() {
            let exact = exp_so3(&(V3::from(w) * times[k]));
            assert!(angle_between(&p.rot, &exact) < 1e-15, "{k}");
        }
        // the body rates of a smooth attitude: R(a(t)) to fourth order in the step
        let order = vessel.order;
        let rates = |t: f64| {
            let b = order.body_rates(attitude(t), attitude_rates(t));
            [b.x, b.y, b.z]
        };
        let err = |h: f64| {
            let times: Vec<f64> = (0..=(40.0 / h).round() as usize).map(|k| k as f64 * h).collect();
            let (_, paths) = drive_rotation(&times, &vessel, &attitude, Some(&rates), false);
            (1..paths.len())
                .map(|k| angle_between(&paths[k].rot, &order.rotation(attitude(times[k]))))
                .fold(0.0, f64::max)
        };
        // the integral over each interval is exact for cubic rates; over 40 s
        // the error falls as h³ (as the translations' velocity integral)
        let (e1, e2) = (err(0.8), err(0.4));
        let rate = (e1 / e2).log2();
        assert!(rate > 2.8, "{e1:e} {e2:e} order {rate}");
    }

    #[test]
    fn the_history_with_rotations_survives_its_numbers() {
        let vessel = Vessel { offset: V3::new(30.0, 0.0, -5.0), order: RotationOrder::Xyz };
        let mut hist = InputHistory::new();
        let mut at = HangOff::default();
        for k in 0..7 {
            let t = 0.25 * k as f64;
            let inp = VesselInputs {
                u: [0.1 * t, 0.2 + t, 0.3 - t * t],
                v: [0.0, 0.0, -1.0],
                angles: attitude(t),
                rates: attitude_rates(t),
                force: [-3e6 + 1e4 * t, 2e5, -4e4 * t],
                moment: [1e6, -2e7 * t, 3e5],
            };
            hist.note_set(0);
            hist.note_set(6);
            if k == 3 {
                hist.note_set(10);
            }
            let path = hist.plan(Coupling::Auto, &vessel, t, 0.25, &inp, &at);
            hist.commit(t, &inp, &path);
            at = path.at(t + 0.25);
        }
        let back = InputHistory::from_values(&hist.to_values()).unwrap();
        assert_eq!(back, hist);
        assert_eq!(back.rotation_mode(Coupling::Auto), Coupling::Both);
    }

    #[test]
    fn a_free_body_that_holds_riser_s_load_is_followed_exactly_once_its_mass_and_inertia_are_known() {
        // docs/theory.md §7.8: a body that holds riser's force and moment over
        // each step (a fixed-step master) and nothing else moves on parabolas
        // with a kink of acceleration at every point, which no extrapolation of
        // its samples follows; with its mass and inertia the path takes its
        // answer to riser's own load exactly and extrapolates the rest (here a
        // constant drift), so each step's end is where the body is then, to
        // round-off, whatever the load (here a chatter like a line's axial
        // ringing). Translations by both couplings, a yaw about the fixed z axis.
        let vessel = Vessel { offset: V3::zeros(), order: RotationOrder::Zyx };
        let (mass, inertia) = ([1.7e7, 9.0e6, 1.5e7], [5e8, 1.1e10, 9e9]);
        let load = |n: usize| {
            let x = n as f64;
            [1e5 * (7.3 * x).sin() - 2e4, 3e4 * (1.7 * x * x).cos() + 1e4, 5e4 * (2.9 * x).sin(), 4e6 * (5.1 * x).cos()]
        };
        for (h, both) in
            [(0.05, false), (0.1, false), (0.1, true), (0.2, true), (0.25, true), (0.5, false), (0.5, true)]
        {
            let mut err = [0.0f64, 0.0];
            for known in [false, true] {
                let mut hist = InputHistory::new();
                hist.mass = if known { mass } else { [0.0; 3] };
                hist.inertia = if known { inertia } else { [0.0; 3] };
                // the body: heave, surge, sway and yaw, their rates
                let (mut x, mut v) = ([0.1, -0.2, 0.3, 0.01], [0.05, 0.2, -0.1, 0.002]);
                for i in 0..3 {
                    hist.note_set(i);
                    if both {
                        hist.note_set(3 + i);
                    }
                }
                hist.note_set(8);
                let inp = |x: &[f64; 4], v: &[f64; 4], f: [f64; 4]| VesselInputs {
                    u: [x[0], x[1], x[2]],
                    v: if both { [v[0], v[1], v[2]] } else { [0.0; 3] },
                    angles: [0.0, 0.0, x[3]],
                    rates: [0.0; 3],
                    force: [f[0], f[1], f[2]],
                    moment: [0.0, 0.0, f[3]],
                };
                let mut at = hist.start(Coupling::Auto, &vessel, &inp(&x, &v, load(0)));
                for n in 0..80 {
                    let t = n as f64 * h;
                    let f = load(n);
                    let now = inp(&x, &v, f);
                    let path = hist.plan(Coupling::Auto, &vessel, t, h, &now, &at);
                    hist.commit(t, &now, &path);
                    at = path.at(t + h);
                    for j in 0..4 {
                        let a = f[j] / if j < 3 { mass[j] } else { inertia[2] };
                        x[j] += v[j] * h + 0.5 * a * h * h;
                        v[j] += a * h;
                    }
                    if n >= 20 {
                        let d = at.displacement;
                        let yaw = at.rotation[(1, 0)].atan2(at.rotation[(0, 0)]);
                        let e = [d.z - x[0], d.x - x[1], d.y - x[2], yaw - x[3]];
                        err[known as usize] = e.iter().fold(err[known as usize], |m, e| m.max(e.abs()));
                    }
                }
            }
            eprintln!(
                "h {h} s, both {both}: the path's end off the body by {:.1e} m (the inputs alone {:.1e} m)",
                err[1], err[0]
            );
            assert!(err[1] < 1e-10, "h {h} both {both}: {:e}", err[1]);
            assert!(err[0] > 1e-6, "h {h} both {both}: {:e}", err[0]);
        }
    }
}
