//! The FMU's input path (docs/theory.md §7, §16.6): the hang-off's path over
//! a communication step ends on an accurate prediction of the master's motion,
//! and inside the step its acceleration follows the motion's (it erred by
//! percents before the end state's slope and curvature were made those of the
//! end values' sequence, (7.3a)). This measures both on the study's
//! design motion, the heave 2.5 m at 10 s grown over a period, given as
//! displacements at the communication points, against its closed form.

use riser::fmi::input_path::{Coupling, InputHistory, VesselInputs};
use riser::math::V3;
use riser::math::rigid::RotationOrder;
use riser::model::HangOff;
use riser::sim::vessel::Vessel;
use std::f64::consts::PI;

const A: f64 = 2.5;
const W: f64 = 2.0 * PI / 10.0;

/// The heave, its velocity and acceleration at t (the ramp ½(1 − cos πt/10)).
fn heave(t: f64) -> [f64; 3] {
    let (r, dr, ddr) = if t < 10.0 {
        let k = PI / 10.0;
        (0.5 * (1.0 - (k * t).cos()), 0.5 * k * (k * t).sin(), 0.5 * k * k * (k * t).cos())
    } else {
        (1.0, 0.0, 0.0)
    };
    let (s, c) = (W * t).sin_cos();
    [A * r * s, A * (dr * s + r * W * c), A * (ddr * s + 2.0 * dr * W * c - r * W * W * s)]
}

/// The path's largest errors over 20 to 40 s at communication step h: at the
/// steps' ends [displacement, velocity, acceleration] and inside them (7
/// points a step) [the same].
fn errors(h: f64) -> ([f64; 3], [f64; 3]) {
    let mut hist = InputHistory::new();
    hist.note_set(0);
    let vessel = Vessel { offset: V3::zeros(), order: RotationOrder::Zyx };
    let mut from = HangOff::default();
    let (mut end, mut inside) = ([0.0f64; 3], [0.0f64; 3]);
    let n = (40.0 / h).round() as usize;
    for k in 0..n {
        let t = k as f64 * h;
        let inp = VesselInputs { u: [heave(t)[0], 0.0, 0.0], ..Default::default() };
        let path = hist.plan(Coupling::Auto, &vessel, t, h, &inp, &from);
        if t >= 20.0 {
            for j in 1..=7 {
                let s = t + h * j as f64 / 7.0;
                let (p, x) = (path.at(s), heave(s));
                let e = [
                    (p.displacement.z - x[0]).abs(),
                    (p.velocity.z - x[1]).abs(),
                    (path.acceleration(s).z - x[2]).abs(),
                ];
                let slot = if j == 7 { &mut end } else { &mut inside };
                for i in 0..3 {
                    slot[i] = slot[i].max(e[i]);
                }
            }
        }
        from = path.at(t + h);
        hist.commit(t, &inp, &path);
    }
    (end, inside)
}

#[test]
fn the_path_ends_accurately_and_its_acceleration_inside_the_step_follows_the_motion() {
    let aw2 = A * W * W;
    // bounds about three times what is measured (docs/theory.md §16.6); with
    // Q's own slope and curvature (before (7.3a)) the interior erred 1.8, 5
    // and 39 % of A ω² at 0.05 to 0.2 s, and with the exactly determined
    // design of the longer steps 8.7, 15 and 68 % at 0.25, 0.3 and 0.5 s;
    // the middle steps with (7.3a) on the 12-point fit (before (7.3b)) 3.6e-4
    // and 1.1e-2 at 0.1 and 0.2 s (now 3.3e-5 and 1.2e-3)
    for (h, end_bound, inside_bound) in [
        (0.05, 2e-5, 1e-5),
        (0.1, 2e-4, 1e-4),
        (0.15, 2e-3, 1e-3),
        (0.2, 5e-3, 4e-3),
        (0.25, 1.5e-3, 1.5e-3),
        (0.3, 4e-3, 4e-3),
        (0.5, 5e-2, 6e-2),
    ] {
        let (end, inside) = errors(h);
        eprintln!(
            "h {h} s: at the steps' ends {:.2e} m, {:.2e} m/s, {:.2e} m/s²; inside {:.2e} m, {:.2e} m/s, {:.2e} m/s² \
             ({:.1e} of A ω²)",
            end[0],
            end[1],
            end[2],
            inside[0],
            inside[1],
            inside[2],
            inside[2] / aw2
        );
        // the end: the quartic's prediction, O(h⁵) in value (docs/theory.md §7)
        assert!(end[0] <= end_bound, "h {h}: end displacement error {:.2e} m", end[0]);
        // inside: the slope and curvature of the end values' sequence (7.3a)
        // make the path between successive ends follow the motion
        assert!(inside[2] <= inside_bound * aw2, "h {h}: inside acceleration error {:.2e} m/s²", inside[2]);
    }
}
