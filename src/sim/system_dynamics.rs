//! The dynamics of a system of lines on one vessel (issue 49; docs/theory.md
//! §17.5). With every line between a fixed point and a vessel point, the
//! lines meet only at the vessel, whose motion is prescribed (the CLI's
//! harmonics, the FMU's inputs): each line is then its own single-line run
//! ([`Simulation`] of [`SystemScene::line_scene`], its hang-off at its vessel
//! point ρ, moved by the vessel's motion as a single line's is, §14), and the
//! system's loads on the vessel are the sums of the lines' (17.11). Its energy
//! balance is the sum of the lines' (17.12).
//!
//! The lines are stepped on threads ([`SystemRun::for_each_line`]): a line's
//! arithmetic is the same on any thread and no line reads another's state,
//! so the bits are the same on any number of threads.

use super::Simulation;
use super::error::RiserError;
use super::vessel::{VesselLoads, VesselMotion};
use crate::math::V3;
use crate::model::{HangOff, Outputs};
use crate::scene::system::{PointKind, SystemScene, VesselEnd};
use crate::scene::{Model, Scene};
use std::sync::Mutex;

/// One line of a system in a dynamic run.
pub struct LineRun {
    pub name: String,
    /// Which of its ends is on the vessel (its `from` or its `to`).
    pub vessel_end: VesselEnd,
    /// The single-line scene it is (its frame at its vessel point at rest).
    pub scene: Scene,
    pub sim: Simulation,
}

impl LineRun {
    /// The tensions at the line's `from` and `to` ends of outputs `o` of its run, N.
    pub fn tensions(&self, o: &Outputs) -> (f64, f64) {
        match self.vessel_end {
            VesselEnd::From => (o.top_tension, o.bottom_tension),
            VesselEnd::To => (o.bottom_tension, o.top_tension),
        }
    }

    /// The static tensions at its `from` and `to` ends, N.
    pub fn static_tensions(&self) -> (f64, f64) {
        let s = &self.sim.statics;
        match self.vessel_end {
            VesselEnd::From => (s.top_tension, s.bottom_tension),
            VesselEnd::To => (s.bottom_tension, s.top_tension),
        }
    }

    /// Advances the line to `t` (s) with the vessel on `motion`.
    pub fn advance_to(&mut self, t: f64, motion: &(dyn Fn(f64) -> VesselMotion + Sync)) -> Result<(), RiserError> {
        let vessel = self.sim.vessel;
        let hang_off = |t: f64| -> HangOff { vessel.hang_off(&motion(t)) };
        self.sim.advance_to(t, &hang_off)
    }

    /// What a step of the line costs, roughly (the order the lines are handed
    /// to threads in: the dearest first): the rod's node carries six unknowns
    /// and its Gauss points the sections' work, the cable's three.
    fn cost(&self) -> usize {
        let n = self.scene.analysis.n_elements;
        match self.scene.analysis.model {
            Model::Rod => 4 * n,
            Model::Cable => n,
        }
    }
}

/// A line that failed, named.
#[derive(Debug)]
pub struct LineError {
    pub line: String,
    pub error: RiserError,
}

impl std::fmt::Display for LineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line '{}': {}", self.line, self.error)
    }
}

/// A system set up for a dynamic run, every line in its static equilibrium
/// at the neutral pose.
pub struct SystemRun {
    pub lines: Vec<LineRun>,
}

/// Why a system cannot be run in this version, or None.
pub fn unsupported(sys: &SystemScene) -> Option<String> {
    let free: Vec<&str> = sys.points.iter().filter(|p| p.kind == PointKind::Free).map(|p| p.name.as_str()).collect();
    (!free.is_empty()).then(|| {
        format!(
            "free point(s) {}: the dynamics of a system with free points (joints, clump weights, buoys) is not yet \
             in this version; `riser statics` solves it (docs/guide/systems.md)",
            free.join(", ")
        )
    })
}

impl SystemRun {
    /// Each line's single-line run from its statics at the neutral pose (the
    /// lines' statics as `riser statics SYSTEM` solves them, §17.1).
    pub fn new(sys: &SystemScene) -> Result<Self, String> {
        if let Some(m) = unsupported(sys) {
            return Err(m);
        }
        let mut lines = Vec::with_capacity(sys.lines.len());
        for (i, l) in sys.lines.iter().enumerate() {
            let (vessel_end, vp, _) = sys.ends(i);
            // at the neutral pose the vessel point is at ρ
            let scene = sys.line_scene(i, V3::from(vp.position));
            let sim = Simulation::from_scene(&scene).map_err(|e| format!("line '{}': {e}", l.name))?;
            lines.push(LineRun { name: l.name.clone(), vessel_end, scene, sim });
        }
        Ok(SystemRun { lines })
    }

    /// Puts every line's hang-off on the vessel's motion `m` at t = 0 (each
    /// line's [`Simulation::start`]).
    pub fn start(&mut self, m: &VesselMotion) {
        for l in &mut self.lines {
            let h = l.sim.vessel.hang_off(m);
            l.sim.start(h);
        }
    }

    /// Calls `f` on every line, on up to `threads` threads (this one among
    /// them), the dearest lines first, and gives the results in the lines'
    /// order. One thread: in order on this one, nothing spawned.
    pub fn for_each_line<R: Send>(&mut self, threads: usize, f: &(dyn Fn(&mut LineRun) -> R + Sync)) -> Vec<R> {
        let n = self.lines.len();
        let threads = threads.clamp(1, n.max(1));
        if threads == 1 {
            return self.lines.iter_mut().map(f).collect();
        }
        let mut queue: Vec<(usize, &mut LineRun)> = self.lines.iter_mut().enumerate().collect();
        queue.sort_by_key(|(i, l)| (std::cmp::Reverse(l.cost()), *i));
        let queue = Mutex::new(queue.into_iter());
        let work = || {
            let mut done = Vec::new();
            loop {
                let next = queue.lock().unwrap_or_else(|p| p.into_inner()).next();
                let Some((i, line)) = next else { break };
                done.push((i, f(line)));
            }
            done
        };
        let mut results: Vec<Option<R>> = (0..n).map(|_| None).collect();
        std::thread::scope(|s| {
            let others: Vec<_> = (1..threads).map(|_| s.spawn(work)).collect();
            let mut all = work();
            for h in others {
                // a panic in a line's thread is this thread's (the FMU's boundary catches it)
                all.extend(h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)));
            }
            for (i, r) in all {
                results[i] = Some(r);
            }
        });
        results.into_iter().map(|r| r.expect("every line is taken from the queue once")).collect()
    }

    /// Advances every line to `t` (s) with the vessel on `motion`, on up to
    /// `threads` threads; the first failed line (in the system's order) named.
    pub fn advance_to(
        &mut self,
        t: f64,
        motion: &(dyn Fn(f64) -> VesselMotion + Sync),
        threads: usize,
    ) -> Result<(), LineError> {
        let results = self.for_each_line(threads, &|l: &mut LineRun| l.advance_to(t, motion));
        for (l, r) in self.lines.iter().zip(results) {
            r.map_err(|error| LineError { line: l.name.clone(), error })?;
        }
        Ok(())
    }

    /// The lines' loads on the vessel of their outputs `outputs` (one per
    /// line, in order), summed (17.11): the force and its moment about the
    /// reference point with the lines' end moments, global and in the
    /// vessel frame.
    pub fn resultant(outputs: &[Outputs]) -> VesselLoads {
        let mut sum = VesselLoads {
            force: V3::zeros(),
            moment: V3::zeros(),
            force_vessel: V3::zeros(),
            moment_vessel: V3::zeros(),
        };
        for o in outputs {
            sum.force += o.top_force;
            sum.moment += o.top_moment;
            sum.force_vessel += o.vessel_force;
            sum.moment_vessel += o.vessel_moment;
        }
        sum
    }

    /// Every line's outputs now.
    pub fn outputs(&self) -> Vec<Outputs> {
        self.lines.iter().map(|l| l.sim.outputs()).collect()
    }
}

/// The system's energy balance of its lines' outputs `outputs` against their
/// energies at the start `e0` (17.12): the sum of the lines' residuals, J.
pub fn energy_balance_residual(outputs: &[Outputs], e0: &[f64]) -> f64 {
    outputs.iter().zip(e0).map(|(o, e)| o.energy_balance_residual(*e)).sum()
}
