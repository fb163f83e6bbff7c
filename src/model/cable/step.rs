//! The cable's step equations (docs/theory.md §6.2), for the shared Newton
//! iteration: with v_{n+1} = 2(x_{n+1} − x_n)/h − v_n,
//!   M (v_{n+1} − v_n)/h + f_int(x_n, x_{n+1}) − f_grav − f_fluid,½ = 0     (6.6)
//! with f_int the discrete gradient of (6.3) along the midpoint chord, plus the
//! Kelvin–Voigt damping (6.5), and the water at the midpoint as for the rod.

use super::{CableModel, NODE_DOF};
use crate::loads::fluid::{FluidFactors, FrozenWater, segment_fluid_force, water_at};
use crate::loads::seabed::{self, linear_at_gauss};
use crate::loads::surface;
use crate::math::band::LinearSolveError;
use crate::math::{M3, V3};
use crate::model::DynamicOptions;
use crate::model::RodConfig;
use crate::model::dissipation::{self, HighFrequency, TripleLayout};
use crate::model::outputs::{Outputs, SHAPE_POINTS};
use crate::model::{HangOff, State};
use crate::model::{Linear, StepEquations, inertia_roundoff};
use nalgebra::SMatrix;

/// Scratch data of a cable step beyond the linear system, allocated once.
pub struct CableWorkspace {
    /// Global fluid force vector, N.
    fluid: Vec<f64>,
    /// The current's ramp at the step's midpoint t_n + h/2 (1: in full; §5.11).
    current_scale: f64,
    /// The waves' motion at the Gauss points, held over the step (None:
    /// still water), and the moving surface's work over the step, J (§13.6).
    water: Option<FrozenWater>,
    surface_wave_work: f64,
    /// Global force vector of the seabed's damping and friction, N (§9),
    /// and the segments' shape values at the Gauss points.
    seabed: Vec<f64>,
    seabed_shapes: [([f64; 2], [f64; 2]); 4],
    /// Candidate new node velocities, m/s.
    vnew: Vec<V3>,
    /// Stretches of x_n and of the trial x_{n+1}.
    lam_n: Vec<f64>,
    lam_1: Vec<f64>,
    /// Reactions (force of the supports on the line) at S = 0 and S = L, N.
    reaction: [V3; 2],
    /// Inertia rows M a at the end nodes, N.
    end_inertia: [V3; 2],
    /// Accelerations of the end segments' nodes [first, second, −, −], m/s².
    end_accel: [[V3; 4]; 2],
    /// High-frequency dissipation (§5.10): its parameters (None: ρ∞ = 1),
    /// each segment's algorithmic damping factor α w_f of this step, the
    /// triples' layout, which are held, whether the line is free, scratch.
    hf: Option<HighFrequency>,
    alg: Vec<f64>,
    layout: TripleLayout<2>,
    fixed_triple: Vec<bool>,
    free: bool,
    d: Vec<V3>,
}

fn node(r: &[f64], a: usize) -> V3 {
    V3::new(r[NODE_DOF * a], r[NODE_DOF * a + 1], r[NODE_DOF * a + 2])
}

impl StepEquations for CableModel {
    type Workspace = CableWorkspace;

    fn workspace(&self) -> Result<(CableWorkspace, Linear), LinearSolveError> {
        let c = &self.cable;
        let lin = Linear::new(c.new_system()?, c.fixed_dofs());
        let ws = CableWorkspace {
            fluid: vec![0.0; c.n_dof()],
            current_scale: 1.0,
            water: self.sea.as_ref().map(|sea| FrozenWater::new(sea, c.n_el)),
            surface_wave_work: 0.0,
            seabed: vec![0.0; if self.seabed.is_some() { c.n_dof() } else { 0 }],
            seabed_shapes: linear_at_gauss(c.l),
            vnew: vec![V3::zeros(); c.n_el + 1],
            lam_n: vec![1.0; c.n_el],
            lam_1: vec![1.0; c.n_el],
            reaction: [V3::zeros(); 2],
            end_inertia: [V3::zeros(); 2],
            end_accel: [[V3::zeros(); 4]; 2],
            hf: None,
            alg: vec![0.0; c.n_el],
            layout: TripleLayout { mass: self.mass.clone(), start: [0, 1], n_el: c.n_el, n_positions: c.n_el + 1 },
            fixed_triple: (0..=c.n_el)
                .map(|a| (a == 0 && c.ends_fixed[0]) || (a == c.n_el && c.ends_fixed[1]))
                .collect(),
            free: !c.ends_fixed[0] && !c.ends_fixed[1],
            d: vec![V3::zeros(); c.n_el + 1],
        };
        Ok((ws, lin))
    }

    fn force_scale(&self) -> f64 {
        let weight: f64 = self.gravity_vector().iter().map(|f| f.abs()).sum();
        weight.max(self.total_mass() * 9.81)
    }

    fn hang_off_prescribed(&self) -> bool {
        self.cable.ends_fixed[0]
    }

    fn begin(&self, ws: &mut CableWorkspace, prev: &State, options: &DynamicOptions) {
        for e in 0..self.cable.n_el {
            ws.lam_n[e] = self.cable.stretch(&prev.config.x, e);
        }
        // the segments' algorithmic damping α w_f, lagged (5.31)
        ws.hf = HighFrequency::new(options.rho_infinity);
        if let Some(hf) = ws.hf {
            let (v, u) = (&prev.mean_vel, &prev.prev_mean_vel);
            for e in 0..self.cable.n_el {
                ws.alg[e] = hf.alpha * dissipation::stress_weight([&v[e], &v[e + 1]], [&u[e], &u[e + 1]]);
            }
        }
    }

    fn predict(
        &self,
        ws: &mut CableWorkspace,
        prev: &State,
        trial: &mut State,
        h: f64,
        origin: V3,
        target: HangOff,
        order: u32,
    ) {
        // r_{n+1} = r_n + h (2 v̄_n − v̄_{n−1}) or r_n + h v̄_n (§5.7): the cable
        // keeps the quadratic (with the cubic its free-spinning test line's
        // angular momentum drifted 1.3e-10 in 1e4 steps at ρ∞ 0.5, against
        // 7.7e-11 and a bound of 1e-10: round-off, not looked into further)
        let [c1, c0, cm] = crate::model::extrapolation(order.min(2));
        // the current's ramp at the midpoint, as the waves' (§5.11)
        ws.current_scale = self.current_ramp.at(prev.time + 0.5 * h).0;
        let n = self.cable.n_el;
        for a in 0..=n {
            let fixed = (a == 0 && self.cable.ends_fixed[0]) || (a == n && self.cable.ends_fixed[1]);
            if !fixed {
                trial.config.x[a] = prev.config.x[a]
                    + (prev.mean_vel[a] * c1 + prev.prev_mean_vel[a] * c0 + prev.prev2_mean_vel[a] * cm) * h;
            }
        }
        if self.cable.ends_fixed[0] {
            trial.config.x[0] = origin + target.displacement;
        }
        if let (true, Some(m)) = (self.cable.ends_fixed[1], self.anchor_motion) {
            trial.config.x[n] = m.position;
        }
        if let (Some(sea), Some(water)) = (&self.sea, ws.water.as_mut()) {
            // the waves at the predicted midpoint's Gauss points at t_n + h/2 (§13.6)
            let (x0, x1) = (&prev.config.x, &trial.config.x);
            for e in 0..n {
                let (a, b) = ((x0[e] + x1[e]) * 0.5, (x0[e + 1] + x1[e + 1]) * 0.5);
                for g in 0..4 {
                    let xi = crate::math::shape::GAUSS4.xi[g];
                    water.points[4 * e + g] = a * (1.0 - xi) + b * xi;
                }
            }
            water.evaluate(sea, prev.time + 0.5 * h);
        }
    }

    fn residual_roundoff(&self, cfg: &RodConfig, h: f64) -> f64 {
        let extent = cfg.x.iter().fold(0.0f64, |m, x| m.max(x.norm())).max(self.cable.length);
        let inertia = inertia_roundoff(self.max_inertia_per_length(), self.cable.l, extent, h);
        let bed = self.seabed.as_ref().map_or(0.0, |b| b.roundoff(self.cable.l, extent));
        self.cable.residual_roundoff(&cfg.x).max(inertia).max(bed)
    }

    fn assemble(
        &self,
        ws: &mut CableWorkspace,
        lin: &mut Linear,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
        eta: f64,
        tangent: bool,
    ) {
        let cable = &self.cable;
        let n = cable.n_el;
        let (x0, x1) = (&prev.config.x, &cfg.x);
        lin.r.iter_mut().for_each(|v| *v = 0.0);
        ws.fluid.iter_mut().for_each(|v| *v = 0.0);
        ws.seabed.iter_mut().for_each(|v| *v = 0.0);
        if tangent {
            lin.sys.clear();
        }
        ws.end_inertia = [V3::zeros(); 2];
        for a in 0..=n {
            ws.vnew[a] = (x1[a] - x0[a]) * (2.0 / h) - prev.vel[a];
        }
        if cable.ends_fixed[0] {
            ws.vnew[0] = target.velocity;
        }
        if cable.ends_fixed[1] {
            ws.vnew[n] = self.anchor_motion.map_or(V3::zeros(), |m| m.velocity);
        }
        let k_inertia = 2.0 / (h * h);
        let fluid_active = !self.fluid.is_inert_in(ws.water.is_some());
        let fac = FluidFactors { position: 0.5, velocity: 1.0 / h, acceleration: 2.0 / (h * h) };
        // a surface that moves sweeps the band of heights z_s ± max |η|; over
        // a segment it dips at most the frozen elevation's depression (13.14)
        let sweep = self.sea.as_ref().map_or(0.0, |s| s.max_elevation());
        ws.surface_wave_work = 0.0;
        let mut ke = SMatrix::<f64, 6, 6>::zeros();
        for e in 0..n {
            let (a, b) = (e, e + 1);
            let off = NODE_DOF * e;
            // internal force: the discrete gradient along the midpoint chord (6.3), damping (6.5)
            let d0 = x0[b] - x0[a];
            let d1 = x1[b] - x1[a];
            let lam0 = ws.lam_n[e];
            let lam1 = d1.norm() / cable.l;
            let (mut g, mut dg) = cable.discrete_slope(e, lam0, lam1);
            // Kelvin–Voigt (η/h) and algorithmic (α w_f) damping of the stretch
            let c_damp = eta / h + if ws.hf.is_some() { ws.alg[e] } else { 0.0 };
            if c_damp > 0.0 {
                let (gd, dgd) = cable.damping_slope(e, lam0, lam1, c_damp);
                g += gd;
                dg += dgd;
                ws.lam_1[e] = lam1;
            }
            let (f, k) = cable.segment_force(&((d0 + d1) * 0.5), &d1, lam1, g, dg, 0.5);
            let mut fe = [-f, f];
            let mut kb = [[k, -k], [-k, k]];
            // inertia M (v_{n+1} − v_n)/h (6.4)
            let acc = [(ws.vnew[a] - prev.vel[a]) / h, (ws.vnew[b] - prev.vel[b]) / h];
            let (mass, fluid) = (self.mass.at(e), self.fluid.at(e));
            for i in 0..2 {
                let fi = acc[0] * mass[i][0] + acc[1] * mass[i][1];
                fe[i] += fi;
                for j in 0..2 {
                    kb[i][j] += M3::identity() * (k_inertia * mass[i][j]);
                }
            }
            if e == 0 {
                ws.end_inertia[0] = acc[0] * mass[0][0] + acc[1] * mass[0][1];
                ws.end_accel[0] = [acc[0], acc[1], V3::zeros(), V3::zeros()];
            }
            if e == n - 1 {
                ws.end_inertia[1] = acc[0] * mass[1][0] + acc[1] * mass[1][1];
                ws.end_accel[1] = [acc[0], acc[1], V3::zeros(), V3::zeros()];
            }
            // water at the midpoint, v½ = Δx/h, added mass with the step's acceleration (§5.4)
            let water = ws.water.as_ref().map(|w| &w.at[e]);
            if fluid_active {
                let xm = [(x0[a] + x1[a]) * 0.5, (x0[b] + x1[b]) * 0.5];
                let vm = [(x1[a] - x0[a]) / h, (x1[b] - x0[b]) / h];
                let mut ff = [V3::zeros(); 2];
                let mut kf = [[M3::zeros(); 2]; 2];
                segment_fluid_force(
                    fluid,
                    ws.current_scale,
                    &xm,
                    &vm,
                    &acc,
                    water,
                    cable.s_node(e),
                    cable.l,
                    fac,
                    &mut ff,
                    if tangent { Some(&mut kf) } else { None },
                );
                for i in 0..2 {
                    fe[i] -= ff[i];
                    for c in 0..3 {
                        ws.fluid[off + NODE_DOF * i + c] += ff[i][c];
                    }
                    for j in 0..2 {
                        kb[i][j] += kf[i][j];
                    }
                }
            }
            // seabed: the discrete gradient of its elastic energy, damping and friction (§9)
            if let Some(bed) = self.seabed.as_ref().map(|b| b.at(e))
                && !seabed::clear_of(bed, &[x0[a], x0[b], x1[a], x1[b]], 0.0)
            {
                let (mut fs, mut fd) = ([V3::zeros(); 2], [V3::zeros(); 2]);
                let mut ks = [[M3::zeros(); 2]; 2];
                let k = if tangent { Some(&mut ks) } else { None };
                let sh = &ws.seabed_shapes;
                seabed::element_step_force(
                    bed,
                    &[x0[a], x0[b]],
                    &[x1[a], x1[b]],
                    sh,
                    seabed::linear_at,
                    cable.l,
                    h,
                    &mut fs,
                    &mut fd,
                    k,
                );
                for i in 0..2 {
                    fe[i] -= fs[i] + fd[i];
                    for c in 0..3 {
                        ws.seabed[off + NODE_DOF * i + c] += fd[i][c];
                    }
                    for j in 0..2 {
                        kb[i][j] += ks[i][j];
                    }
                }
            }
            // the free surface: the emerged part's buoyancy taken off (§10)
            if let Some(fs) = &fluid.surface
                && !fs.below(&[x0[a], x0[b], x1[a], x1[b]], water.map_or(sweep, |w| w.depression.min(sweep)))
            {
                let mut fsv = [V3::zeros(); 2];
                let mut ks = [[M3::zeros(); 2]; 2];
                let k = if tangent { Some(&mut ks) } else { None };
                let eta = water.map(|w| move |xi: f64| w.elevation_at(xi));
                ws.surface_wave_work += surface::element_step_force(
                    fs,
                    &[x0[a], x0[b]],
                    &[x1[a], x1[b]],
                    surface::linear,
                    cable.l,
                    eta.as_ref().map(|f| f as &dyn Fn(f64) -> f64),
                    &mut fsv,
                    k,
                );
                for i in 0..2 {
                    fe[i] -= fsv[i];
                    for j in 0..2 {
                        kb[i][j] += ks[i][j];
                    }
                }
            }
            for i in 0..2 {
                for c in 0..3 {
                    lin.r[off + NODE_DOF * i + c] += fe[i][c];
                }
            }
            if tangent {
                for i in 0..2 {
                    for j in 0..2 {
                        ke.fixed_view_mut::<3, 3>(3 * i, 3 * j).copy_from(&kb[i][j]);
                    }
                }
                lin.sys.add_block(e, |i, j| ke[(i, j)]);
            }
        }
        for (a, f) in self.gravity_vector().iter().enumerate() {
            lin.r[NODE_DOF * a + 2] -= f;
        }
        ws.reaction = [node(&lin.r, 0), node(&lin.r, n)];
    }

    fn residual_norm(&self, lin: &Linear) -> f64 {
        // NaN anywhere gives ∞ (f64::max would skip it)
        let mut m: f64 = 0.0;
        let mut nan = false;
        let mut fi = 0;
        for (i, v) in lin.r.iter().enumerate() {
            if fi < lin.fixed.len() && lin.fixed[fi] == i {
                fi += 1;
                continue;
            }
            nan |= v.is_nan();
            m = m.max(v.abs());
        }
        if nan { f64::INFINITY } else { m }
    }

    fn apply_increment(&self, _ws: &mut CableWorkspace, lin: &mut Linear, _prev: &State, cfg: &mut RodConfig) {
        for (a, x) in cfg.x.iter_mut().enumerate() {
            *x += node(&lin.du, a);
        }
    }

    fn finish(&self, ws: &mut CableWorkspace, state: &State, trial: &mut State, h: f64, options: &DynamicOptions) {
        let eta = options.structural_damping;
        // velocities, work and bookkeeping of the converged step (§5.5)
        let (x0, x1) = (&state.config.x, &trial.config.x);
        let mut w_hydro = 0.0;
        for a in 0..=self.cable.n_el {
            let dx = x1[a] - x0[a];
            trial.vel[a] = ws.vnew[a];
            trial.prev_mean_vel[a] = state.mean_vel[a];
            trial.prev2_mean_vel[a] = state.prev_mean_vel[a];
            trial.mean_vel[a] = dx / h;
            w_hydro += dx.dot(&node(&ws.fluid, a));
        }
        let dx0 = x1[0] - x0[0];
        let vbar0 = 0.5 * (state.vel[0] + trial.vel[0]);
        trial.work_top += dx0.dot(&ws.reaction[0]) + (vbar0 * h - dx0).dot(&ws.end_inertia[0]);
        trial.work_hydro += w_hydro + ws.surface_wave_work;
        if let (true, Some(_)) = (self.cable.ends_fixed[1], self.anchor_motion) {
            // a moving anchor's work, as the hang-off's (§5.5, §17.7)
            let n = self.cable.n_el;
            let dxn = x1[n] - x0[n];
            let vbar = 0.5 * (state.vel[n] + trial.vel[n]);
            trial.work_anchor += dxn.dot(&ws.reaction[1]) + (vbar * h - dxn).dot(&ws.end_inertia[1]);
        }
        if !ws.seabed.is_empty() {
            trial.work_seabed += (0..=self.cable.n_el).map(|a| (x1[a] - x0[a]).dot(&node(&ws.seabed, a))).sum::<f64>();
        }
        if eta > 0.0 {
            for e in 0..self.cable.n_el {
                trial.dissipated += self.cable.damping_dissipation(e, ws.lam_n[e], ws.lam_1[e], eta / h);
            }
        }
        if let Some(hf) = ws.hf {
            // the stress part's dissipation (5.31), the velocity filter (5.32)
            for e in (0..self.cable.n_el).filter(|&e| ws.alg[e] > 0.0) {
                trial.algorithmic += self.cable.damping_dissipation(e, ws.lam_n[e], ws.lam_1[e], ws.alg[e]);
            }
            let (w, fixed, free) = (&state.hf_weight, &ws.fixed_triple, ws.free);
            let removed =
                ws.layout.filter(&trial.config.x, &state.vel, &mut trial.vel, w, fixed, free, hf.tau, &mut ws.d);
            trial.algorithmic += removed;
            for a in 0..=self.cable.n_el {
                let acc = (trial.vel[a] - state.vel[a]) / h;
                trial.hf_weight[a] = dissipation::filter_weight(&acc, &state.hf_accel[a]);
                trial.hf_accel[a] = acc;
            }
        }
        trial.end_accel = ws.end_accel;
        trial.mid_reaction = ws.reaction;
    }
}

impl CableModel {
    /// A cable state at rest at the node positions `x`.
    pub fn state_at_rest(x: Vec<V3>, time: f64) -> State {
        State::at_rest(RodConfig { x, xp: Vec::new(), d: Vec::new() }, time)
    }

    /// Force of the supports on the line at S = 0 and S = L in `state`, N:
    /// the end rows of the equations of motion at the state (internal force,
    /// weight and water at the state; inertia with the last step's acceleration).
    pub fn end_reactions(&self, s: &State) -> [V3; 2] {
        [self.end_reaction(s, 0), self.end_reaction(s, 1)]
    }

    /// The force of the support at end `end` (0: S = 0, 1: S = L) in
    /// `state`, N: one of [`CableModel::end_reactions`].
    pub fn end_reaction(&self, s: &State, end: usize) -> V3 {
        let c = &self.cable;
        let n = c.n_el;
        let x = &s.config.x;
        let e = if end == 0 { 0 } else { n - 1 };
        let d = x[e + 1] - x[e];
        let f_int = d / d.norm() * c.tension(x, e);
        let (row, node) = if end == 0 { (0, 0) } else { (1, n) };
        let mut f = if end == 0 { -f_int } else { f_int };
        f.z -= self.gravity_vector()[node];
        let acc = &s.end_accel[end];
        let (mass, fluid) = (self.mass.at(e), self.fluid.at(e));
        f += acc[0] * mass[row][0] + acc[1] * mass[row][1];
        // the waves at the state (§13.6)
        let water = self.sea.as_ref().map(|sea| {
            let xi = crate::math::shape::GAUSS4.xi;
            water_at(sea, &xi.map(|xi| x[e] * (1.0 - xi) + x[e + 1] * xi), s.time)
        });
        if !fluid.is_inert_in(water.is_some()) {
            let fac = FluidFactors { position: 0.0, velocity: 0.0, acceleration: 0.0 };
            let mut ff = [V3::zeros(); 2];
            segment_fluid_force(
                fluid,
                self.current_ramp.at(s.time).0,
                &[x[e], x[e + 1]],
                &[s.vel[e], s.vel[e + 1]],
                &[acc[0], acc[1]],
                water.as_ref(),
                c.s_node(e),
                c.l,
                fac,
                &mut ff,
                None,
            );
            f -= ff[row];
        }
        // (a segment wholly below the band the surface sweeps gets nothing from it)
        let sweep = self.sea.as_ref().map_or(0.0, |s| s.max_elevation());
        if let Some(fsurf) = &fluid.surface
            && !fsurf.below(&x[e..e + 2], water.as_ref().map_or(sweep, |w| w.depression.min(sweep)))
        {
            let mut fs = [V3::zeros(); 2];
            let eta = water.as_ref().map(|w| move |xi: f64| w.elevation_at(xi));
            let eta = eta.as_ref().map(|f| f as &dyn Fn(f64) -> f64);
            surface::element_static_force(fsurf, &[x[e], x[e + 1]], surface::linear, c.l, eta, &mut fs, None);
            f -= fs[row];
        }
        if let Some(bed) = self.seabed.as_ref().map(|b| b.at(e)) {
            let mut fs = [V3::zeros(); 2];
            let shapes = linear_at_gauss(c.l);
            seabed::element_state_force(
                bed,
                &[x[e], x[e + 1]],
                &[s.vel[e], s.vel[e + 1]],
                &shapes,
                seabed::linear_at,
                c.l,
                &mut fs,
            );
            f -= fs[row];
        }
        f
    }

    /// Tension (N) and curvature (1/m) at every node of the positions `x`:
    /// the mean tension of the adjacent segments (at an end, its segment's:
    /// the end's own is in the outputs' top and bottom tension); the turning
    /// angle between them over their mean length (0 at the ends).
    pub fn node_profile(&self, x: &[V3]) -> Vec<(f64, f64)> {
        let c = &self.cable;
        let n = c.n_el;
        (0..=n)
            .map(|a| {
                let seg: Vec<usize> = [a.checked_sub(1), (a < n).then_some(a)].into_iter().flatten().collect();
                let tension = seg.iter().map(|&e| c.tension(x, e)).sum::<f64>() / seg.len() as f64;
                let curvature = if seg.len() == 2 {
                    let (d0, d1) = (x[a] - x[a - 1], x[a + 1] - x[a]);
                    let angle = d0.cross(&d1).norm().atan2(d0.dot(&d1));
                    angle / (0.5 * (d0.norm() + d1.norm()))
                } else {
                    0.0
                };
                (tension, curvature)
            })
            .collect()
    }

    /// The line at each node of `x` ([`Self::node_profile`]'s tension and
    /// turning curvature, no bending moment): the design numbers' points.
    pub fn node_points(&self, x: &[V3]) -> Vec<crate::model::outputs::LinePoint> {
        let n = self.cable.n_el;
        self.node_profile(x)
            .into_iter()
            .enumerate()
            .map(|(a, (tension, k))| crate::model::outputs::LinePoint {
                element: a.min(n - 1),
                s: self.cable.s_node(a),
                position: x[a],
                tension,
                curvature: [k, 0.0],
                twist: 0.0,
            })
            .collect()
    }

    /// Every output quantity of `state` (the rod's names and meanings).
    pub fn outputs(&self, s: &State) -> Outputs {
        let c = &self.cable;
        let x = &s.config.x;
        let reactions = self.end_reactions(s);
        let t0 = (x[1] - x[0]).normalize();
        let t1 = (x[c.n_el] - x[c.n_el - 1]).normalize();
        let interior = (0..c.n_el).map(|e| c.tension(x, e)).fold(f64::INFINITY, f64::min);
        let min_tension = (-reactions[0].dot(&t0)).min(reactions[1].dot(&t1)).min(interior);
        let kinetic = self.kinetic_energy(&s.vel);
        let strain = c.strain_energy(x);
        let potential = self.potential_energy(x);
        let mut shape = [V3::zeros(); SHAPE_POINTS];
        for (k, p) in shape.iter_mut().enumerate() {
            *p = c.position_at(x, c.length * k as f64 / (SHAPE_POINTS - 1) as f64);
        }
        let touchdown = match &self.seabed {
            Some(bed) => seabed::touchdown(bed.first(), x, |a| c.s_node(a), c.length),
            None => c.length,
        };
        let tangent = crate::model::outputs::first_node_tangent(x);
        Outputs::of_state(s, reactions, min_tension, [kinetic, strain, potential], touchdown, tangent, shape)
    }
}
