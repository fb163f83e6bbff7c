//! `accuracy`'s first round (docs/theory.md §16.13): its candidate is the
//! scene's numerics coarsened ([`FIRST_CANDIDATE_COARSENING`]: half the
//! elements at twice the step); where that round's pilots fail (a step too
//! long for Newton), the first round runs through the scene's own numerics and
//! says so. Measured on pilots whose quantity is an exact power law in the
//! element length and the step, q = q* + a h² + b Δt², failing at steps
//! beyond a bound: the choice is made from the scene's own round, every
//! pilot it ran within the bound, and it meets the target against q*
//! (the closed form the pilots never see).

use riser::model::DynamicsError;
use riser::scene::Scene;
use riser::sim::accuracy::{FIRST_CANDIDATE_COARSENING, Pinned, Problem, choose_on};
use riser::sim::error::RiserError;
use riser::sim::error_estimate::{Pilot, PilotPlan, PilotRuns, Quantity};
use std::sync::Mutex;

const Q_STAR: f64 = 300e3;
const A: f64 = 4e6;
const B: f64 = 2e4;

/// Pilots of q = q* + A (100/n)² + B Δt², failing above `max_step` s.
struct PowerLaw {
    max_step: f64,
    ran: Mutex<Vec<(usize, f64, bool)>>,
}

impl PowerLaw {
    fn value(n: usize, dt: f64) -> f64 {
        let h = 100.0 / n as f64;
        Q_STAR + A * 1e-4 * h * h + B * dt * dt
    }
}

impl PilotRuns for PowerLaw {
    fn quantities(&self) -> Vec<Quantity> {
        vec![Quantity::TopTensionMax]
    }

    fn applies(&self, q: Quantity) -> bool {
        q == Quantity::TopTensionMax
    }

    fn plan(&self) -> PilotPlan {
        PilotPlan::new((20.0, 40.0), Some(10.0), false)
    }

    fn run(&self, _plan: &PilotPlan, n: usize, time_step: f64, _tol: f64) -> Result<Pilot, RiserError> {
        let fails = time_step > self.max_step * (1.0 + 1e-9);
        self.ran.lock().unwrap().push((n, time_step, fails));
        if fails {
            return Err(RiserError::Dynamics(DynamicsError::NotConverged {
                time: 0.0,
                step: time_step,
                iterations: 30,
                residual: 1.0,
            }));
        }
        let values = vec![Self::value(n, time_step)];
        Ok(Pilot { n_elements: n, time_step, values, wall_s: 0.0, reused: false })
    }
}

#[test]
fn the_first_round_falls_back_to_the_scene_s_numerics_when_its_coarse_candidate_fails() {
    let scene = Scene::builtin("catenary").unwrap().with_overrides(&["accuracy=1e-3"]).unwrap();
    let (n, dt) = (scene.analysis.n_elements, scene.analysis.time_step);
    let k = FIRST_CANDIDATE_COARSENING as f64;
    // a round through its candidate (n_c, Δt_c) runs steps 4Δt_c, 2Δt_c, Δt_c
    // (16.19): about the scene's own numerics the longest is 4Δt, about the
    // coarsened candidate 4kΔt; pilots fail beyond 6Δt
    let runs = PowerLaw { max_step: dt * 6.0, ran: Mutex::new(Vec::new()) };
    let fits = |_: usize| true;
    let problem = Problem {
        runs: &runs,
        analysis: &scene.analysis,
        mesh: n,
        criteria: vec![(Quantity::TopTensionMax, Quantity::TopTensionMax)],
        fits: &fits,
        line_names: &[],
    };
    let choice = choose_on(&problem, Pinned::default(), 2, &mut |_| {}).expect("the fallback round chooses");
    let ran = runs.ran.lock().unwrap().clone();
    // the first round tried the coarsened candidate, whose long step failed
    assert!(ran.iter().any(|&(_, s, failed)| failed && (s - 4.0 * k * dt).abs() < 1e-9 * dt), "{ran:?}");
    // the note says so
    assert!(
        choice.notes.iter().any(|m| m.contains("the first round of pilots about") && m.contains("failed")),
        "{:?}",
        choice.notes
    );
    // the rounds that count ran within the bound, the first about the scene's own numerics:
    // (its step triplet's longest 4Δt, its finest pilot the scene's numerics)
    let first = &choice.rounds[0];
    let longest = first.pilots.iter().map(|p| p.time_step).fold(0.0, f64::max);
    assert!((longest - 4.0 * dt).abs() < 1e-12 * dt, "first round's longest step {longest} s, the scene's {dt} s");
    assert!(first.pilots.iter().any(|p| p.n_elements == n && (p.time_step - dt).abs() < 1e-12 * dt));
    // the choice meets the target against the closed form (16.18: relative to q*)
    let error = (PowerLaw::value(choice.n_elements, choice.time_step) - Q_STAR).abs() / Q_STAR;
    println!(
        "fell back: chose {} elements at {} s, error {error:.2e} (estimate {:.2e}), {} pilots",
        choice.n_elements,
        choice.time_step,
        choice.estimate(),
        ran.len()
    );
    assert!(error <= 1e-3, "{error}");
}
