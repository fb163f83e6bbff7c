//! Implausible vessel inputs, said once each (docs/theory.md §7.5,
//! docs/guide/fmu.md): a master that feeds degrees for
//! radians, an absolute position for a displacement, or a jump, gets a
//! warning with the numbers in its log. The inputs are used as given: a
//! plausible input changes nothing, bit for bit; an implausible one is
//! still the master's (the status stays fmi2OK). Nothing here allocates
//! until it speaks.

use super::input_path::VesselInputs;
use crate::math::V3;
use crate::sim::vessel::{Vessel, VesselMotion};

/// Largest hang-off speed a vessel's motion plausibly gives, m/s (a heave
/// of 10 m at 6 s is 10.5 m/s; wave-frequency motions of ships and
/// platforms stay below 5 m/s).
pub const MAX_SPEED: f64 = 10.0;

/// Largest hang-off acceleration a vessel's motion plausibly gives, m/s²
/// (about 2 g; a heave of 10 m at 5 s is 15.8 m/s²).
pub const MAX_ACCELERATION: f64 = 20.0;

/// Largest roll or pitch of a floating vessel, deg (beyond it the vessel
/// has capsized or the angles are in degrees where radians are meant).
pub const MAX_TILT_DEG: f64 = 30.0;

/// Speed of an axis's displacement above which a velocity input held at 0
/// on that axis is said, m/s.
pub const HELD_VELOCITY_SPEED: f64 = 0.05;

/// Largest hang-off displacement in one communication step, m.
pub const MAX_JUMP: f64 = 10.0;

/// A first translation input beyond this looks like an absolute position,
/// m (the inputs are displacements from the initial, static position).
pub const ABSOLUTE_TRANSLATION: f64 = 1.0;

/// A first angle input beyond this looks like an absolute heading or an
/// angle in degrees, deg.
pub const ABSOLUTE_ANGLE_DEG: f64 = 5.0;

/// What has been said, and the last communication points' hang-off.
#[derive(Debug, Clone, Copy, Default)]
pub struct Watch {
    /// Said: absolute, roll, pitch, jump, speed, acceleration, a velocity
    /// input held at 0.
    said: [bool; 7],
    /// Whether the first communication point has been looked at.
    started: bool,
    /// The last three communication points: time (s), hang-off displacement
    /// implied by the displacement and angle inputs (m), velocity implied by
    /// the velocity inputs (m/s); the newest last.
    samples: [Option<(f64, V3, V3)>; 3],
}

const NAMES: [&str; 3] = ["heave", "surge", "sway"];
const ANGLES: [&str; 3] = ["roll", "pitch", "yaw"];

impl Watch {
    /// Forgets the communication points (a restored state: the next
    /// differences would span a jump the master made on purpose), keeping
    /// what has been said.
    pub fn forget_samples(&mut self) {
        self.samples = [None; 3];
        self.started = true;
    }

    /// Looks at the inputs `inp` set for the communication point `t` (s),
    /// against the vessel `vessel`; `both[a]` whether axis a (heave, surge,
    /// sway) is driven by its displacement and velocity inputs together;
    /// `say` receives each new warning.
    pub fn look(&mut self, t: f64, inp: &VesselInputs, vessel: &Vessel, both: [bool; 3], mut say: impl FnMut(String)) {
        if !self.started {
            self.started = true;
            self.first(t, inp, &mut say);
        }
        for (k, idx) in [(0usize, 1usize), (1, 2)] {
            let deg = inp.angles[k].to_degrees();
            if !self.said[idx] && deg.abs() > MAX_TILT_DEG {
                self.said[idx] = true;
                say(format!(
                    "{} = {} rad ({deg:.1} deg) at t = {t} s: beyond {MAX_TILT_DEG} deg, implausible for a floating \
                     vessel; the angle inputs are in radians",
                    ANGLES[k], inp.angles[k]
                ));
            }
        }
        let motion = VesselMotion {
            displacement: V3::new(inp.u[1], inp.u[2], inp.u[0]),
            velocity: V3::new(inp.v[1], inp.v[2], inp.v[0]),
            angles: inp.angles,
            body_rates: V3::new(inp.rates[0], inp.rates[1], inp.rates[2]),
        };
        let h = vessel.hang_off(&motion);
        let (p, v) = (h.displacement, h.velocity);
        match self.samples[2] {
            // a repeated communication point (a step retried after a discard): the newer sample
            Some((t2, _, _)) if t <= t2 => self.samples[2] = Some((t, p, v)),
            _ => self.samples = [self.samples[1], self.samples[2], Some((t, p, v))],
        }
        let [older, Some((t1, p1, v1)), Some((t2, p2, v2))] = self.samples else {
            self.speed(v.norm(), t, None, &mut say);
            return;
        };
        let dt = t2 - t1;
        self.held_velocity(both, inp, (t1, p1, v1), (t2, p2, v2), &mut say);
        let jump = (p2 - p1).norm();
        if !self.said[3] && jump > MAX_JUMP {
            self.said[3] = true;
            say(format!(
                "the inputs move the hang-off {jump:.2} m between t = {t1} s and {t2} s, in one communication step \
                 (more than {MAX_JUMP} m): check the units (m, rad) and that the inputs are displacements from the \
                 initial position"
            ));
        }
        self.speed((jump / dt).max(v2.norm()), t2, Some(t1), &mut say);
        if self.said[5] {
            return;
        }
        // the second divided difference of the positions; the velocity inputs' own rate
        let mut accel = (v2 - v1).norm() / dt;
        if let Some((t0, p0, _)) = older {
            let d = 2.0 * ((p2 - p1) / dt - (p1 - p0) / (t1 - t0)) / (t2 - t0);
            accel = accel.max(d.norm());
        }
        if accel > MAX_ACCELERATION {
            self.said[5] = true;
            say(format!(
                "the inputs imply a hang-off acceleration of {accel:.3e} m/s² at t = {t2} s (above \
                 {MAX_ACCELERATION} m/s², about 2 g): implausible for a vessel; check the units and the inputs' \
                 continuity"
            ));
        }
    }

    /// A velocity input the master sets but holds at 0 while its axis's
    /// displacement moves (a signal that leaves it out, or a port connected
    /// to nothing): the path fits the velocity as the hang-off's (theory
    /// §7.4), and at long steps a velocity of 0 the displacement contradicts
    /// moves the line far off (the catenary heaved 2.5 m / 10 s at 0.5 s:
    /// 325 kN).
    fn held_velocity(
        &mut self,
        both: [bool; 3],
        inp: &VesselInputs,
        (t1, p1, v1): (f64, V3, V3),
        (t2, p2, v2): (f64, V3, V3),
        say: &mut impl FnMut(String),
    ) {
        if self.said[6] {
            return;
        }
        // global x, y, z of heave, surge, sway
        for (a, c) in [(0usize, 2usize), (1, 0), (2, 1)] {
            let moving = (p2[c] - p1[c]).abs() / (t2 - t1);
            if both[a] && inp.v[a] == 0.0 && v1[c] == 0.0 && v2[c] == 0.0 && moving > HELD_VELOCITY_SPEED {
                self.said[6] = true;
                say(format!(
                    "{0}_velocity is set but held at 0 while {0} moves ({moving:.3} m/s between t = {t1} s and {t2} \
                     s): riser takes the velocity inputs as the hang-off's, and at communication steps of 0.21 s \
                     and longer a velocity the displacement contradicts moves the line far off; feed {0}_velocity \
                     the vessel's velocity, or set coupling_inputs = displacement",
                    NAMES[a]
                ));
                return;
            }
        }
    }

    fn speed(&mut self, speed: f64, t: f64, from: Option<f64>, say: &mut impl FnMut(String)) {
        if self.said[4] || speed <= MAX_SPEED {
            return;
        }
        self.said[4] = true;
        let when = match from {
            Some(t1) => format!("between t = {t1} s and {t} s"),
            None => format!("at t = {t} s"),
        };
        say(format!(
            "the inputs imply a hang-off speed of {speed:.3e} m/s {when} (above {MAX_SPEED} m/s): implausible for a \
             vessel; check the units (m, m/s, rad) and that the displacement inputs are displacements from the \
             initial position"
        ));
    }

    /// The first communication point: an input far from zero looks absolute.
    fn first(&mut self, t: f64, inp: &VesselInputs, say: &mut impl FnMut(String)) {
        let translation = (0..3).find(|&a| inp.u[a].abs() > ABSOLUTE_TRANSLATION);
        let angle = (0..3).find(|&a| inp.angles[a].to_degrees().abs() > ABSOLUTE_ANGLE_DEG);
        let what = match (translation, angle) {
            (Some(a), _) => format!("{} = {} m", NAMES[a], inp.u[a]),
            (None, Some(a)) => format!("{} = {} rad ({:.1} deg)", ANGLES[a], inp.angles[a], inp.angles[a].to_degrees()),
            (None, None) => return,
        };
        self.said[0] = true;
        say(format!(
            "{what} at the first communication point t = {t} s looks absolute: the inputs are the vessel reference \
             point's displacement and rotation from its initial position (0 at the static state), not its position \
             or heading (a first translation beyond {ABSOLUTE_TRANSLATION} m or angle beyond {ABSOLUTE_ANGLE_DEG} \
             deg is taken as given, and said)"
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rigid::RotationOrder;

    /// The messages of a watch fed `inputs(t)` at communication points
    /// 0, h, 2h, … up to `duration` s, the hang-off `offset` from the
    /// reference point.
    fn said(offset: V3, h: f64, duration: f64, inputs: impl Fn(f64) -> VesselInputs) -> Vec<String> {
        let vessel = Vessel { offset, order: RotationOrder::Zyx };
        let mut watch = Watch::default();
        let mut out = Vec::new();
        let n = (duration / h).round() as usize;
        for k in 0..=n {
            let t = k as f64 * h;
            watch.look(t, &inputs(t), &vessel, [false; 3], |m| out.push(m));
        }
        out
    }

    fn heave(z: f64) -> VesselInputs {
        VesselInputs { u: [z, 0.0, 0.0], ..Default::default() }
    }

    /// Plausible motions say nothing: a 10 m heave at 8 s (7.9 m/s,
    /// 6.2 m/s²), roll and pitch of 15 deg at 10 s with the hang-off 30 m
    /// forward, at communication steps of 0.01 to 1 s.
    #[test]
    fn plausible_motions_say_nothing() {
        let w = std::f64::consts::TAU / 8.0;
        for h in [0.01, 0.1, 0.5, 1.0] {
            let s = said(V3::zeros(), h, 40.0, |t| VesselInputs {
                u: [10.0 * (w * t).sin(), 0.0, 0.0],
                v: [10.0 * w * (w * t).cos(), 0.0, 0.0],
                ..Default::default()
            });
            assert!(s.is_empty(), "{h}: {s:?}");
            let a = 15f64.to_radians();
            let w = std::f64::consts::TAU / 10.0;
            let s = said(V3::new(30.0, 0.0, -5.0), h, 40.0, |t| VesselInputs {
                angles: [a * (w * t).sin(), a * (w * t).cos() - a, 0.0],
                ..Default::default()
            });
            assert!(s.is_empty(), "{h}: {s:?}");
        }
    }

    /// Each implausible input of issue 52, said once with its numbers.
    #[test]
    fn implausible_inputs_are_said_once_each_with_their_numbers() {
        // a pitch of 1.0 (degrees meant): 57.3 deg, said once though held
        let s = said(V3::zeros(), 0.1, 2.0, |t| VesselInputs {
            angles: [0.0, if t > 0.45 { 1.0 } else { 0.0 }, 0.0],
            ..Default::default()
        });
        assert_eq!(s.len(), 1, "{s:?}");
        assert!(s[0].contains("pitch = 1 rad (57.3 deg)") && s[0].contains("beyond 30 deg"), "{s:?}");
        // heave given as the absolute z: 5 m from the first point
        let s = said(V3::zeros(), 0.1, 1.0, |_| heave(5.0));
        assert_eq!(s.len(), 1, "{s:?}");
        assert!(s[0].contains("heave = 5 m at the first communication point t = 0 s looks absolute"), "{s:?}");
        // a yaw given as a heading: 86 deg
        let s = said(V3::zeros(), 0.1, 1.0, |_| VesselInputs { angles: [0.0, 0.0, 1.5], ..Default::default() });
        assert!(s.len() == 1 && s[0].contains("yaw = 1.5 rad (85.9 deg)") && s[0].contains("looks absolute"), "{s:?}");
        // surge 100 m after a still start: a jump of 100 m in one step, its speed and acceleration
        let s = said(V3::zeros(), 0.1, 1.0, |t| VesselInputs {
            u: [0.0, if t > 0.25 { 100.0 } else { 0.0 }, 0.0],
            ..Default::default()
        });
        assert_eq!(s.len(), 3, "{s:?}");
        assert!(s[0].contains("move the hang-off 100.00 m between t = 0.2 s and 0.30000000000000004 s"), "{s:?}");
        assert!(s[1].contains("speed of 1.000e3 m/s"), "{s:?}");
        // second divided difference over 0.1, 0.2, 0.3 s: 2 (1000 − 0) / 0.2 = 1e4 m/s²
        assert!(s[2].contains("acceleration of 1.000e4 m/s²"), "{s:?}");
        // a speed of 20 m/s alone (2 m per 0.1 s from rest, steadily): the acceleration of its start too
        let s = said(V3::zeros(), 0.1, 1.0, |t| heave(20.0 * t));
        assert!(s.iter().any(|m| m.contains("speed of 2.000e1 m/s")), "{s:?}");
        // an acceleration alone: 0.5 m in one step from rest, 5 m/s, then held
        let s = said(V3::zeros(), 0.1, 1.0, |t| heave(if t > 0.55 { 0.5 } else { 0.0 }));
        assert_eq!(s.len(), 1, "{s:?}");
        assert!(s[0].contains("acceleration of 5.000e1 m/s²"), "{s:?}");
        // the velocity inputs' own speed
        let s = said(V3::zeros(), 0.1, 1.0, |_| VesselInputs { v: [0.0, 12.0, 0.0], ..Default::default() });
        assert!(s.len() == 1 && s[0].contains("speed of 1.200e1 m/s at t = 0 s"), "{s:?}");
    }

    /// A velocity input set along with its displacement but held at 0
    /// while the displacement moves is said once, naming it; fed the
    /// motion's velocity, or not set (the displacement alone), it is not.
    #[test]
    fn a_velocity_input_held_at_zero_is_said() {
        let vessel = Vessel { offset: V3::zeros(), order: RotationOrder::Zyx };
        let w = std::f64::consts::TAU / 10.0;
        for (both, fed, expected) in [(true, false, 1), (true, true, 0), (false, false, 0)] {
            let mut watch = Watch::default();
            let mut out = Vec::new();
            for k in 0..20 {
                let t = 0.5 * k as f64;
                let inp = VesselInputs {
                    u: [2.5 * (w * t).sin(), 0.0, 0.0],
                    v: [if fed { 2.5 * w * (w * t).cos() } else { 0.0 }, 0.0, 0.0],
                    ..Default::default()
                };
                watch.look(t, &inp, &vessel, [both, false, false], |m| out.push(m));
            }
            assert_eq!(out.len(), expected, "{both} {fed}: {out:?}");
            if expected == 1 {
                assert!(
                    out[0].starts_with("heave_velocity is set but held at 0 while heave moves (1.545 m/s"),
                    "{out:?}"
                );
            }
        }
    }

    /// A communication point repeated (a step retried after a discard)
    /// replaces the sample: no spurious speed from a zero interval.
    #[test]
    fn a_retried_communication_point_is_not_a_jump() {
        let vessel = Vessel { offset: V3::zeros(), order: RotationOrder::Zyx };
        let mut watch = Watch::default();
        let mut out = Vec::new();
        for (t, z) in [(0.0, 0.0), (0.1, 0.1), (0.1, 0.1), (0.2, 0.2)] {
            watch.look(t, &heave(z), &vessel, [false; 3], |m| out.push(m));
        }
        assert!(out.is_empty(), "{out:?}");
    }
}
