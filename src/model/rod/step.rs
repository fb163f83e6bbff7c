//! The director rod's step equations (docs/theory.md §5.2–§5.6), for the
//! shared Newton iteration of [`super::newton`].
//!
//! With h the step, q½ = ½(q_n + q_{n+1}) and the new velocities
//! v_{n+1} = 2(q_{n+1} − q_n)/h − v_n, the unknown q_{n+1} solves
//!   M (v_{n+1} − v_n)/h + f_int(q_n, q_{n+1}) − f_grav − f_fluid,½ = 0      (5.3)
//! reduced at each director node by the midpoint test frames, m_A = Σ_i d_iA,½ × R_iA,
//! with f_int the discrete gradient (strain operator at q½, stress at the
//! average strain). Newton on (Δr, Δr', θ) with the consistent tangent; the
//! directors are updated by the Cayley transform.

use super::RodModel;
use crate::loads::fluid::{
    FluidFactors, FluidFields, FrozenWater, HermiteAtGauss, element_fluid_force, gauss_point_fluid_force,
    hermite_at_gauss,
};
use crate::loads::{seabed, surface};
use crate::math::band::LinearSolveError;
use crate::math::{M3, V3, cayley, skew};
use crate::model::dissipation::{self, HighFrequency, TripleLayout};
use crate::model::rod::element::{
    self, C_OFF, ElMat, ElVec, ElemDofs, Factors, NDOF_EL, NGP, STRIDE, Shear, Strain, T_OFF,
};
use crate::model::rod::gauss::{self, F4, GaussFields, GaussShapes};
use crate::model::rod::{Rod, RotationBc};
use crate::model::{DynamicOptions, HangOff, Linear, State, StepEquations, inertia_roundoff};
use crate::model::{RodConfig, extrapolation};

/// Scratch data of a rod step beyond the linear system, allocated once.
pub struct RodWorkspace {
    /// Global fluid force vector (centreline rows), N.
    fluid: Vec<f64>,
    /// The current's ramp at the step's midpoint t_n + h/2 (1: in full; §5.11).
    current_scale: f64,
    /// The waves' motion at the Gauss points, held over the step (None:
    /// still water), and the work of the moving surface on the line over
    /// the step at the last trial configuration, J (§13.6).
    water: Option<FrozenWater>,
    surface_wave_work: f64,
    /// Global force vector of the seabed's damping and friction, N (§9).
    seabed: Vec<f64>,
    /// Candidate new centreline velocities.
    vnew: Vec<V3>,
    vpnew: Vec<V3>,
    /// Shape values at the Gauss points (every element has the same length).
    shapes: GaussShapes,
    fluid_shapes: HermiteAtGauss,
    /// Strains of q_n at the Gauss points (rows over the points).
    eps_n: Vec<[F4; 6]>,
    /// Interpolated fields of q_n at the Gauss points.
    kin_n: Vec<GaussFields>,
    /// Material strains (Γ_i = d_i·r' − δ_i3, K) of q_n and of the trial
    /// q_{n+1}, for the structural damping.
    damp_n: Vec<[Strain; NGP]>,
    damp_1: Vec<[Strain; NGP]>,
    /// Reactions (force of the supports on the line) at S = 0 and S = L, N.
    reaction: [V3; 2],
    /// Inertia rows M a at the end nodes, N.
    end_inertia: [V3; 2],
    /// Hermite accelerations of the end elements.
    end_accel: [[V3; 4]; 2],
    /// Spatial reduced residual moment at the anchor (its twist reaction), N m.
    anchor_moment: V3,
    /// The same at the hang-off: the clamp's moment on the line, N m (§15).
    hang_off_moment: V3,
    /// The work of the vessel's turn on the flex joint over the step at the
    /// last trial configuration, J (15.4).
    joint_work: f64,
    /// Director nodes whose twist is held (§5.6) and the Cayley vector of
    /// their step rotation, d_{n+1} = cay(θ) d_n with θ·d3_n = 0.
    twist_nodes: Vec<usize>,
    theta_step: Vec<V3>,
    /// Whether the tangent is assembled in the nodes' director frames (§5.7).
    corotated: bool,
    /// High-frequency dissipation (§5.10): its parameters (None: ρ∞ = 1),
    /// each element's algorithmic damping factor α w_f of this step, the
    /// velocity triples' layout (nodes, then slopes), which are held,
    /// whether the line is free; triples of the new configuration, of the
    /// old and new velocities, and the filter's scratch.
    hf: Option<HighFrequency>,
    alg: Vec<f64>,
    layout: TripleLayout<4>,
    fixed_triple: Vec<bool>,
    free: bool,
    tri_c: Vec<V3>,
    tri_v0: Vec<V3>,
    tri_v: Vec<V3>,
    tri_d: Vec<V3>,
}

impl StepEquations for RodModel {
    type Workspace = RodWorkspace;

    fn workspace(&self) -> Result<(RodWorkspace, Linear), LinearSolveError> {
        let rod = &self.rod;
        let n = rod.n_dof();
        let fixed = rod.fixed_dofs();
        let np = rod.n_el + 1;
        let lin = Linear::new(rod.new_system()?, fixed.clone());
        let ws = RodWorkspace {
            fluid: vec![0.0; n],
            current_scale: 1.0,
            water: self.sea.as_ref().map(|sea| FrozenWater::new(sea, rod.n_el)),
            surface_wave_work: 0.0,
            seabed: vec![0.0; if self.seabed.is_some() { n } else { 0 }],
            vnew: vec![V3::zeros(); rod.n_el + 1],
            vpnew: vec![V3::zeros(); rod.n_el + 1],
            shapes: GaussShapes::new(rod.h),
            fluid_shapes: hermite_at_gauss(rod.h),
            eps_n: vec![[[0.0; NGP]; 6]; rod.n_el],
            kin_n: vec![GaussFields::default(); rod.n_el],
            damp_n: vec![[[0.0; 6]; NGP]; rod.n_el],
            damp_1: vec![[[0.0; 6]; NGP]; rod.n_el],
            reaction: [V3::zeros(); 2],
            end_inertia: [V3::zeros(); 2],
            end_accel: [[V3::zeros(); 4]; 2],
            anchor_moment: V3::zeros(),
            hang_off_moment: V3::zeros(),
            joint_work: 0.0,
            twist_nodes: rod.local_basis_nodes().collect(),
            theta_step: vec![V3::zeros(); rod.local_basis_nodes().count()],
            corotated: true,
            hf: None,
            alg: vec![0.0; rod.n_el],
            layout: TripleLayout {
                mass: self.mass.map(|m| m.centre),
                start: [0, np, 1, np + 1],
                n_el: rod.n_el,
                n_positions: np,
            },
            fixed_triple: (0..2 * np)
                .map(|i| {
                    let dof = if i < np { Rod::x_dof(i) } else { Rod::xp_dof(i - np) };
                    fixed.contains(&dof)
                })
                .collect(),
            free: fixed.is_empty(),
            tri_c: vec![V3::zeros(); 2 * np],
            tri_v0: vec![V3::zeros(); 2 * np],
            tri_v: vec![V3::zeros(); 2 * np],
            tri_d: vec![V3::zeros(); 2 * np],
        };
        Ok((ws, lin))
    }

    fn force_scale(&self) -> f64 {
        let weight: f64 = (0..=self.rod.n_el).map(|a| self.gravity_vector()[Rod::x_dof(a) + 2].abs()).sum();
        weight.max(self.total_mass() * 9.81)
    }

    fn hang_off_prescribed(&self) -> bool {
        self.rod.ends[0].position_fixed
    }

    fn begin(&self, ws: &mut RodWorkspace, prev: &State, options: &DynamicOptions) {
        let rod = &self.rod;
        let eta = options.structural_damping;
        ws.corotated = options.corotated_tangent;
        ws.hf = HighFrequency::new(options.rho_infinity);
        for e in 0..rod.n_el {
            let kin = &mut ws.kin_n[e];
            kin.refresh(&ws.shapes, &ElemDofs::gather(&prev.config, e));
            ws.eps_n[e] = kin.strains(Shear::Spatial(rod.reference_penalty(e)));
            if eta > 0.0 || ws.hf.is_some() {
                ws.damp_n[e] = gauss::to_points(&kin.strains(Shear::Material));
            }
        }
        // the elements' algorithmic damping α w_f, lagged (5.31)
        if let Some(hf) = ws.hf {
            let (v, u) = (&prev.mean_vel, &prev.prev_mean_vel);
            for e in 0..rod.n_el {
                ws.alg[e] = hf.alpha * dissipation::stress_weight([&v[e], &v[e + 1]], [&u[e], &u[e + 1]]);
            }
        }
    }

    /// Predictor: cubic (`order` 3) extrapolation of the centreline from the
    /// last three steps, r_{n+1} = r_n + h (3 v̄_n − 3 v̄_{n−1} + v̄_{n−2}) (v̄ the
    /// steps' mean velocities), quadratic (`order` 2, r_n + h (2 v̄_n − v̄_{n−1}))
    /// or linear (`order` 1), r_{n+1} = r_n + h v̄_n ([`crate::model::extrapolation`]);
    /// the hang-off on its path, and directors carried along with the predicted
    /// tangent (no spin about d3 at a twist-held node).
    fn predict(
        &self,
        ws: &mut RodWorkspace,
        prev: &State,
        trial: &mut State,
        h: f64,
        origin: V3,
        target: HangOff,
        order: u32,
    ) {
        let model = self;
        let (twist, theta) = (&ws.twist_nodes, &mut ws.theta_step);
        let [c1, c0, cm] = extrapolation(order);
        let rod = &model.rod;
        for a in 0..=rod.n_el {
            let fixed = (a == 0 && rod.ends[0].position_fixed) || (a == rod.n_el && rod.ends[1].position_fixed);
            if !fixed {
                trial.config.x[a] = prev.config.x[a]
                    + (prev.mean_vel[a] * c1 + prev.prev_mean_vel[a] * c0 + prev.prev2_mean_vel[a] * cm) * h;
            }
            trial.config.xp[a] = prev.config.xp[a]
                + (prev.mean_slope_vel[a] * c1 + prev.prev_mean_slope_vel[a] * c0 + prev.prev2_mean_slope_vel[a] * cm)
                    * h;
        }
        if rod.ends[0].position_fixed {
            trial.config.x[0] = origin + target.displacement;
        }
        if let (true, Some(m)) = (rod.ends[1].position_fixed, self.anchor_motion) {
            trial.config.x[rod.n_el] = m.position;
        }
        // directors: the smallest rotation that turns d3 onto the predicted
        // centreline tangent (the director rates of the scheme carry the
        // unresolved shear oscillation and predict badly at large steps)
        let last = rod.n_director_nodes() - 1;
        for j in 0..rod.n_director_nodes() {
            let d = prev.config.d[j];
            // a clamped end keeps its frame: its rotation unknowns are held at zero from here
            let end = if j == 0 {
                Some(0)
            } else if j == last {
                Some(1)
            } else {
                None
            };
            if end.is_some_and(|e| rod.ends[e].rotation == RotationBc::Clamped) {
                // the hang-off's clamp turns with the vessel: d = R(t) D_static,
                // carried from R_n to R_{n+1} (the anchor's stays)
                trial.config.d[j] = if j == 0 { target.rotation * prev.hang_off.rotation.transpose() * d } else { d };
                continue;
            }
            let a = slope_at_director_node(rod, &prev.config, j).normalize();
            let b = slope_at_director_node(rod, &trial.config, j).normalize();
            // Cayley vector of the smallest rotation a → b: 2 (a × b)/(1 + a·b)
            let theta_pred = if 1.0 + a.dot(&b) > 1e-6 { a.cross(&b) * (2.0 / (1.0 + a.dot(&b))) } else { V3::zeros() };
            if let Some(k) = twist.iter().position(|&t| t == j) {
                let d3: V3 = d.column(2).into();
                theta[k] = theta_pred - d3 * d3.dot(&theta_pred);
                trial.config.d[j] = cayley(&theta[k]) * d;
            } else {
                trial.config.d[j] = cayley(&theta_pred) * d;
            }
        }
        // the current's ramp at the midpoint, as the waves' (§5.11)
        ws.current_scale = self.current_ramp.at(prev.time + 0.5 * h).0;
        if let (Some(sea), Some(water)) = (&self.sea, ws.water.as_mut()) {
            // the waves at the predicted midpoint's Gauss points at t_n + h/2 (§13.6)
            let sh = &ws.fluid_shapes;
            for e in 0..rod.n_el {
                let (c0, c1) = (ElemDofs::gather(&prev.config, e), ElemDofs::gather(&trial.config, e));
                for g in 0..4 {
                    let n = &sh[g].0;
                    water.points[4 * e + g] = (0..4).map(|k| (c0.c[k] + c1.c[k]) * (0.5 * n[k])).sum();
                }
            }
            water.evaluate(sea, prev.time + 0.5 * h);
        }
    }

    fn residual_roundoff(&self, cfg: &RodConfig, h: f64) -> f64 {
        let extent = cfg.x.iter().fold(0.0f64, |m, x| m.max(x.norm())).max(self.rod.length);
        let inertia = inertia_roundoff(self.max_inertia_per_length(), self.rod.h, extent, h);
        let bed = self.seabed.as_ref().map_or(0.0, |b| b.roundoff(self.rod.h, extent));
        self.rod.residual_roundoff(cfg).max(inertia).max(bed)
    }

    /// The midpoint residual (5.3) at the trial configuration `cfg` and, if
    /// asked, its tangent with respect to (Δr, Δr', θ) of q_{n+1}; `eta` the
    /// Kelvin–Voigt damping time, s.
    fn assemble(
        &self,
        ws: &mut RodWorkspace,
        lin: &mut Linear,
        prev: &State,
        cfg: &RodConfig,
        h: f64,
        target: HangOff,
        eta: f64,
        tangent: bool,
    ) {
        let (model, buf, want_k) = (self, ws, tangent);
        let rod = &model.rod;
        let n_el = rod.n_el;
        lin.r.iter_mut().for_each(|v| *v = 0.0);
        buf.fluid.iter_mut().for_each(|v| *v = 0.0);
        buf.seabed.iter_mut().for_each(|v| *v = 0.0);
        if want_k {
            lin.sys.clear();
        }
        buf.end_inertia = [V3::zeros(); 2];
        // new velocities v_{n+1} = 2Δq/h − v_n; the hang-off follows its prescribed velocity
        for a in 0..=n_el {
            buf.vnew[a] = (cfg.x[a] - prev.config.x[a]) * (2.0 / h) - prev.vel[a];
            buf.vpnew[a] = (cfg.xp[a] - prev.config.xp[a]) * (2.0 / h) - prev.slope_vel[a];
        }
        if rod.ends[0].position_fixed {
            buf.vnew[0] = target.velocity;
        }
        if rod.ends[1].position_fixed {
            buf.vnew[n_el] = model.anchor_motion.map_or(V3::zeros(), |m| m.velocity);
        }
        let k_inertia = 2.0 / (h * h);
        // (multiplications by 1/h in the element loop: a division costs several)
        let inv_h = 1.0 / h;
        let fluid_active = !model.fluid.is_inert_in(buf.water.is_some());
        let fac = FluidFactors { position: 0.5, velocity: 1.0 / h, acceleration: 2.0 / (h * h) };
        // a surface that moves sweeps the band of heights z_s ± max |η|; over
        // an element it dips at most the frozen elevation's depression (13.14)
        let sweep = model.sea.as_ref().map_or(0.0, |s| s.max_elevation());
        buf.surface_wave_work = 0.0;
        let mut re = ElVec::zeros();
        let mut ke = ElMat::zeros();
        // element fluid tangent (zeroed per element only when a tangent is asked)
        let mut kf = [[M3::zeros(); 4]; 4];
        // Gauss-point fields of q_{n+1} and of q½
        let mut k1 = GaussFields::default();
        let mut km = GaussFields::default();
        for e in 0..n_el {
            re.fill(0.0);
            if want_k {
                ke.fill(0.0);
            }
            let el1 = ElemDofs::gather(cfg, e);
            let eln = ElemDofs::gather(&prev.config, e);
            let elm = ElemDofs::average(&eln, &el1);
            // internal force: discrete gradient (§5.2)
            k1.refresh(&buf.shapes, &el1);
            let shear = Shear::Spatial(rod.reference_penalty(e));
            let eps1 = k1.strains(shear);
            let s = rod.midpoint_stress_rows(e, &buf.eps_n[e], &eps1);
            // Kelvin–Voigt (η/h, §5.9) and algorithmic (α w_f, §5.10) damping
            // on the objective material strains
            let c_damp = eta / h + if buf.hf.is_some() { buf.alg[e] } else { 0.0 };
            let sd = (c_damp > 0.0).then(|| {
                let d1 = gauss::to_points(&k1.strains(Shear::Material));
                buf.damp_1[e] = d1;
                rod.damping_stresses(e, &buf.damp_n[e], &d1, c_damp)
            });
            if !want_k {
                // the fields of q½ (residual path; the tangent path forms its own),
                // the damping stress in the same pass
                km.set_average(&buf.kin_n[e], &k1);
                match &sd {
                    None => gauss::add_internal_force(&elm, &km, &s, &buf.shapes, shear, &mut re),
                    Some(sd) => {
                        let g0 = rod.reference_penalty(e);
                        gauss::add_internal_force_damped(&elm, &km, &s, g0, &gauss::to_rows(sd), &buf.shapes, &mut re)
                    }
                }
            } else {
                let (s, k) = (gauss::to_points(&s), Some(&mut ke));
                element::internal_force(&elm, &el1, &s, rod.stiff(e), Factors::MIDPOINT, rod.h, shear, &mut re, k);
                if let Some(sd) = &sd {
                    let damping = Factors { config: 0.5, stress: c_damp };
                    let (stiff, k) = (rod.stiff(e), Some(&mut ke));
                    element::internal_force(&elm, &el1, sd, stiff, damping, rod.h, Shear::Material, &mut re, k);
                }
            }
            // centreline inertia M (v_{n+1} − v_n)/h (§5.1)
            let (mass, fluid) = (model.mass.at(e), model.fluid.at(e));
            let vn = prev.hermite_velocity(e);
            let v1 = [buf.vnew[e], buf.vpnew[e], buf.vnew[e + 1], buf.vpnew[e + 1]];
            let mut acc = [V3::zeros(); 4];
            for k in 0..4 {
                acc[k] = (v1[k] - vn[k]) * inv_h;
            }
            for k in 0..4 {
                let mut f = V3::zeros();
                for m in 0..4 {
                    f += acc[m] * mass.centre[k][m];
                }
                for c in 0..3 {
                    re[C_OFF[k] + c] += f[c];
                }
                if e == 0 && k == 0 {
                    buf.end_inertia[0] += f;
                }
                if e == n_el - 1 && k == 2 {
                    buf.end_inertia[1] += f;
                }
                if want_k {
                    for m in 0..4 {
                        let v = k_inertia * mass.centre[k][m];
                        for c in 0..3 {
                            ke[(C_OFF[k] + c, C_OFF[m] + c)] += v;
                        }
                    }
                }
            }
            if e == 0 {
                buf.end_accel[0] = acc;
            }
            if e == n_el - 1 {
                buf.end_accel[1] = acc;
            }
            // water: drag at the midpoint with v½ = Δr/h, added mass with the step's acceleration (§5.4)
            let water = buf.water.as_ref().map(|w| &w.at[e]);
            if fluid_active {
                let mut ff = [V3::zeros(); 4];
                if want_k {
                    let mut vm = [V3::zeros(); 4];
                    for k in 0..4 {
                        vm[k] = (el1.c[k] - eln.c[k]) * inv_h;
                    }
                    kf = [[M3::zeros(); 4]; 4];
                    element_fluid_force(
                        fluid,
                        buf.current_scale,
                        FluidFields { c: &elm.c, v: &vm, a: &acc, water },
                        &buf.fluid_shapes,
                        rod.s_node(e),
                        rod.h,
                        fac,
                        &mut ff,
                        Some(&mut kf),
                    );
                } else {
                    // the fields at the Gauss points are those of the strains:
                    // r½, r'½ and v½ = (r_{n+1} − r_n)/h
                    let kn = &buf.kin_n[e];
                    let x: [V3; NGP] = std::array::from_fn(|g| km.position(g));
                    let p: [V3; NGP] = std::array::from_fn(|g| km.slope(g));
                    let v: [V3; NGP] = std::array::from_fn(|g| (k1.position(g) - kn.position(g)) * inv_h);
                    let (s0, sh) = (rod.s_node(e), &buf.fluid_shapes);
                    gauss_point_fluid_force(fluid, buf.current_scale, &x, &p, &v, &acc, water, sh, s0, rod.h, &mut ff);
                }
                let gdof = [Rod::x_dof(e), Rod::xp_dof(e), Rod::x_dof(e + 1), Rod::xp_dof(e + 1)];
                for k in 0..4 {
                    for c in 0..3 {
                        re[C_OFF[k] + c] -= ff[k][c];
                        buf.fluid[gdof[k] + c] += ff[k][c];
                    }
                    if want_k {
                        for m in 0..4 {
                            let mut blk = ke.fixed_view_mut::<3, 3>(C_OFF[k], C_OFF[m]);
                            blk += kf[k][m];
                        }
                    }
                }
            }
            // seabed: the discrete gradient of its elastic energy, damping and
            // friction over the step (§9, (9.5), (9.6))
            if let Some(bed) = model.seabed.as_ref().map(|b| b.at(e))
                && !seabed::clear_of(bed, &[eln.c[0], eln.c[2], el1.c[0], el1.c[2]], rod.h)
            {
                let (mut fe, mut fd) = ([V3::zeros(); 4], [V3::zeros(); 4]);
                let mut kb = [[M3::zeros(); 4]; 4];
                let k = if want_k { Some(&mut kb) } else { None };
                seabed::element_step_force(
                    bed,
                    &eln.c,
                    &el1.c,
                    &buf.fluid_shapes,
                    seabed::hermite_at,
                    rod.h,
                    h,
                    &mut fe,
                    &mut fd,
                    k,
                );
                let gdof = [Rod::x_dof(e), Rod::xp_dof(e), Rod::x_dof(e + 1), Rod::xp_dof(e + 1)];
                for k in 0..4 {
                    for c in 0..3 {
                        re[C_OFF[k] + c] -= fe[k][c] + fd[k][c];
                        buf.seabed[gdof[k] + c] += fd[k][c];
                    }
                    if want_k {
                        for m in 0..4 {
                            let mut blk = ke.fixed_view_mut::<3, 3>(C_OFF[k], C_OFF[m]);
                            blk += kb[k][m];
                        }
                    }
                }
            }
            // the free surface: the buoyancy of the emerged part taken off, as
            // the discrete gradient of its potential (§10)
            if let Some(fs) = &fluid.surface
                && let band = fs.lowered(water.map_or(sweep, |w| w.depression.min(sweep)))
                && !(band.hermite_below(&eln.c, rod.h) && band.hermite_below(&el1.c, rod.h))
            {
                let mut fsv = [V3::zeros(); 4];
                let mut kb = [[M3::zeros(); 4]; 4];
                let k = if want_k { Some(&mut kb) } else { None };
                let eta = water.map(|w| move |xi: f64| w.elevation_at(xi));
                buf.surface_wave_work += surface::element_step_force(
                    fs,
                    &eln.c,
                    &el1.c,
                    |xi| crate::math::shape::hermite(xi, rod.h),
                    rod.h,
                    eta.as_ref().map(|f| f as &dyn Fn(f64) -> f64),
                    &mut fsv,
                    k,
                );
                for k in 0..4 {
                    for c in 0..3 {
                        re[C_OFF[k] + c] -= fsv[k][c];
                    }
                    if want_k {
                        for m in 0..4 {
                            let mut blk = ke.fixed_view_mut::<3, 3>(C_OFF[k], C_OFF[m]);
                            blk += kb[k][m];
                        }
                    }
                }
            }
            // director inertia, reduced by the midpoint frames: m_A = Σ_i d_iA,½ × a_iA (§5.3)
            let ddn = prev.director_rates(e);
            // d̈ h = ḋ_{n+1} − ḋ_n = 2(d_{n+1} − d_n)/h − 2ḋ_n
            let mut ddiff = [M3::zeros(); 3];
            for b in 0..3 {
                ddiff[b] = (el1.d[b] - eln.d[b]) * (2.0 * inv_h) - ddn[b] * 2.0;
            }
            for a in 0..3 {
                let mut m = V3::zeros();
                let mut geo = M3::zeros();
                for i in 0..2 {
                    let ji = mass.rotary[i];
                    if ji == 0.0 {
                        continue;
                    }
                    let mut acc_i = V3::zeros();
                    for b in 0..3 {
                        acc_i += ddiff[b].column(i) * (mass.director[a][b] * ji * inv_h);
                    }
                    let dmid: V3 = elm.d[a].column(i).into();
                    m += dmid.cross(&acc_i);
                    if want_k {
                        let d1a: V3 = el1.d[a].column(i).into();
                        geo += skew(&acc_i) * skew(&d1a) * 0.5;
                        for b in 0..3 {
                            let d1b: V3 = el1.d[b].column(i).into();
                            let blk = skew(&dmid) * skew(&d1b) * (-k_inertia * mass.director[a][b] * ji);
                            let mut view = ke.fixed_view_mut::<3, 3>(T_OFF[a], T_OFF[b]);
                            view += blk;
                        }
                    }
                }
                for c in 0..3 {
                    re[T_OFF[a] + c] += m[c];
                }
                if want_k {
                    let mut view = ke.fixed_view_mut::<3, 3>(T_OFF[a], T_OFF[a]);
                    view += geo;
                }
            }
            let off = STRIDE * e;
            for i in 0..NDOF_EL {
                lin.r[off + i] += re[i];
            }
            if want_k && buf.corotated {
                corotate(&mut ke, &element_frames(cfg, e, &buf.twist_nodes));
            }
            if want_k {
                lin.sys.add_block(e, |i, j| ke[(i, j)]);
            }
        }
        for (ri, fi) in lin.r.iter_mut().zip(model.gravity_vector()) {
            *ri -= fi;
        }
        let i0 = Rod::x_dof(0);
        let i1 = Rod::x_dof(n_el);
        buf.reaction =
            [V3::new(lin.r[i0], lin.r[i0 + 1], lin.r[i0 + 2]), V3::new(lin.r[i1], lin.r[i1 + 1], lin.r[i1 + 2])];
        let it = Rod::theta_dof(2 * n_el);
        buf.anchor_moment = V3::new(lin.r[it], lin.r[it + 1], lin.r[it + 2]);
        let it = Rod::theta_dof(0);
        buf.hang_off_moment = V3::new(lin.r[it], lin.r[it + 1], lin.r[it + 2]);
        // the flex joint's discrete gradient at the end director node (15.4),
        // between the vessel's frames R_n D_static and R_{n+1} D_static
        if let Some(joint) = &rod.flex_joint {
            let (f0, f1) = (
                model.joint_frame(&prev.hang_off.rotation).unwrap_or_default(),
                model.joint_frame(&target.rotation).unwrap_or_default(),
            );
            let js = joint.step(&prev.config.d[0], &cfg.d[0], &f0, &f1);
            for c in 0..3 {
                lin.r[it + c] += js.moment[c];
            }
            buf.joint_work = js.vessel_work;
            if want_k {
                let k = if buf.corotated { cfg.d[0].transpose() * js.tangent * cfg.d[0] } else { js.tangent };
                for a in 0..3 {
                    for b in 0..3 {
                        lin.sys.add(it + a, it + b, k[(a, b)]);
                    }
                }
            }
        }
        // twist-held nodes: unknowns θ_loc with θ = D_n θ_loc, spatial increment
        // w = T(θ) D_n δθ_loc, T(θ) = 4/(4 + |θ|²) (I + ½θ̂) (the Cayley differential)
        for (k, &j) in buf.twist_nodes.iter().enumerate() {
            let i0 = Rod::theta_dof(j);
            let m = V3::new(lin.r[i0], lin.r[i0 + 1], lin.r[i0 + 2]);
            let th = buf.theta_step[k];
            let dn = prev.config.d[j];
            let f = 4.0 / (4.0 + th.norm_squared());
            let p = (M3::identity() + skew(&th) * 0.5) * dn * f;
            let ml = p.transpose() * m;
            lin.r[i0..i0 + 3].copy_from_slice(ml.as_slice());
            if want_k {
                lin.sys.transform_dofs(i0, &p);
                // ∂(Pᵀ m)/∂θ at fixed m, times D_n
                let tm = m + m.cross(&th) * 0.5;
                let extra = dn.transpose() * (tm * th.transpose() * (-0.5 * f * f) + skew(&m) * (0.5 * f)) * dn;
                for a in 0..3 {
                    for b in 0..3 {
                        lin.sys.add(i0 + a, i0 + b, extra[(a, b)]);
                    }
                }
            }
        }
    }

    /// Spatial components → components in the director frame of each node
    /// at `cfg` (positions and slopes of end node a in d_{2a}, the rotation
    /// of director node j in d_j; twist-held nodes keep their own basis).
    fn to_tangent_basis(&self, ws: &RodWorkspace, cfg: &RodConfig, v: &mut [f64]) {
        if ws.corotated {
            self.rotate_nodal(ws, cfg, v, true);
        }
    }

    fn to_spatial_basis(&self, ws: &RodWorkspace, cfg: &RodConfig, v: &mut [f64]) {
        if ws.corotated {
            self.rotate_nodal(ws, cfg, v, false);
        }
    }

    fn residual_norm(&self, lin: &Linear) -> f64 {
        residual_norm(&lin.r, &lin.fixed, self.rod.h)
    }

    fn apply_increment(&self, ws: &mut RodWorkspace, lin: &mut Linear, prev: &State, cfg: &mut RodConfig) {
        self.rod.limit_rotation_increments(&mut lin.du, 0.5);
        apply_increment(&self.rod, &prev.config, cfg, &lin.du, &ws.twist_nodes, &mut ws.theta_step);
    }

    /// A director may turn by at most 90° in one step: the reduced moment
    /// equations (5.3) control the step's energy error only through θ·m,
    /// |θ| = 2 tan(φ/2) for a turn φ, which is unbounded as φ → π. Newton can
    /// find such a spurious root when an abrupt motion meets a stiff line.
    fn step_is_admissible(&self, prev: &State, cfg: &RodConfig) -> bool {
        // cos φ = (tr(d_{n+1} d_nᵀ) − 1)/2 ≥ 0
        prev.config.d.iter().zip(&cfg.d).all(|(a, b)| a.component_mul(b).sum() >= 1.0)
    }

    fn finish(&self, ws: &mut RodWorkspace, state: &State, trial: &mut State, h: f64, options: &DynamicOptions) {
        let eta = options.structural_damping;
        // velocities, work and bookkeeping of the converged step (§5.5)
        let rod = &self.rod;
        let cfg0 = &state.config;
        let cfg1 = &trial.config;
        let mut w_hydro = 0.0;
        for a in 0..=rod.n_el {
            trial.vel[a] = ws.vnew[a];
            trial.slope_vel[a] = ws.vpnew[a];
            let dx = cfg1.x[a] - cfg0.x[a];
            let dp = cfg1.xp[a] - cfg0.xp[a];
            trial.prev_mean_vel[a] = state.mean_vel[a];
            trial.prev_mean_slope_vel[a] = state.mean_slope_vel[a];
            trial.prev2_mean_vel[a] = state.prev_mean_vel[a];
            trial.prev2_mean_slope_vel[a] = state.prev_mean_slope_vel[a];
            trial.mean_vel[a] = dx / h;
            trial.mean_slope_vel[a] = dp / h;
            for c in 0..3 {
                w_hydro += dx[c] * ws.fluid[Rod::x_dof(a) + c] + dp[c] * ws.fluid[Rod::xp_dof(a) + c];
            }
        }
        for j in 0..rod.n_director_nodes() {
            trial.director_vel[j] = (cfg1.d[j] - cfg0.d[j]) * (2.0 / h) - state.director_vel[j];
        }
        let dx0 = cfg1.x[0] - cfg0.x[0];
        let vbar0 = 0.5 * (state.vel[0] + trial.vel[0]);
        trial.work_top += dx0.dot(&ws.reaction[0]) + (vbar0 * h - dx0).dot(&ws.end_inertia[0]);
        if rod.ends[0].rotation == RotationBc::Clamped {
            // the clamp turning with the vessel works through its moment (θ·m, §5.5)
            trial.work_top += cayley_vector(&(cfg1.d[0] * cfg0.d[0].transpose())).dot(&ws.hang_off_moment);
        }
        if rod.flex_joint.is_some() {
            // the vessel turning the flex joint works on it (15.4)
            trial.work_top += ws.joint_work;
        }
        trial.work_hydro += w_hydro + ws.surface_wave_work;
        if !ws.seabed.is_empty() {
            let mut w = 0.0;
            for a in 0..=rod.n_el {
                let (dx, dp) = (cfg1.x[a] - cfg0.x[a], cfg1.xp[a] - cfg0.xp[a]);
                for c in 0..3 {
                    w += dx[c] * ws.seabed[Rod::x_dof(a) + c] + dp[c] * ws.seabed[Rod::xp_dof(a) + c];
                }
            }
            trial.work_seabed += w;
        }
        if eta > 0.0 {
            for e in 0..rod.n_el {
                trial.dissipated += rod.damping_dissipation(e, &ws.damp_n[e], &ws.damp_1[e], eta / h);
            }
        }
        if let (true, Some(_)) = (rod.ends[1].position_fixed, self.anchor_motion) {
            // a moving anchor's work, as the hang-off's (§5.5, §17.7)
            let n = rod.n_el;
            let dxn = cfg1.x[n] - cfg0.x[n];
            let vbar = 0.5 * (state.vel[n] + trial.vel[n]);
            trial.work_anchor += dxn.dot(&ws.reaction[1]) + (vbar * h - dxn).dot(&ws.end_inertia[1]);
        }
        if rod.ends[1].rotation == RotationBc::TwistFixed {
            let j = 2 * rod.n_el;
            trial.work_anchor += cayley_vector(&(cfg1.d[j] * cfg0.d[j].transpose())).dot(&ws.anchor_moment);
        }
        trial.end_accel = ws.end_accel;
        trial.mid_reaction = ws.reaction;
        if let Some(hf) = ws.hf {
            self.filter_velocities(ws, hf, state, trial, h);
        }
    }
}

impl RodModel {
    /// The high-frequency dissipation of a converged step (§5.10): the
    /// stress part's dissipation, the velocity filter (5.32) on the node and
    /// slope velocities (the director rates keep the midpoint rule's: the
    /// spin momentum is untouched), the filter weights of the next step.
    fn filter_velocities(&self, ws: &mut RodWorkspace, hf: HighFrequency, state: &State, trial: &mut State, h: f64) {
        let rod = &self.rod;
        for e in (0..rod.n_el).filter(|&e| ws.alg[e] > 0.0) {
            trial.algorithmic += rod.damping_dissipation(e, &ws.damp_n[e], &ws.damp_1[e], ws.alg[e]);
        }
        let np = rod.n_el + 1;
        let c1 = &trial.config;
        for a in 0..np {
            ws.tri_c[a] = c1.x[a];
            ws.tri_c[np + a] = c1.xp[a];
            ws.tri_v0[a] = state.vel[a];
            ws.tri_v0[np + a] = state.slope_vel[a];
            ws.tri_v[a] = trial.vel[a];
            ws.tri_v[np + a] = trial.slope_vel[a];
        }
        let (w, fixed, free) = (&state.hf_weight, &ws.fixed_triple, ws.free);
        trial.algorithmic +=
            ws.layout.filter(&ws.tri_c, &ws.tri_v0, &mut ws.tri_v, w, fixed, free, hf.tau, &mut ws.tri_d);
        for i in 0..2 * np {
            let acc = (ws.tri_v[i] - ws.tri_v0[i]) / h;
            trial.hf_weight[i] = dissipation::filter_weight(&acc, &state.hf_accel[i]);
            trial.hf_accel[i] = acc;
        }
        trial.vel.copy_from_slice(&ws.tri_v[..np]);
        trial.slope_vel.copy_from_slice(&ws.tri_v[np..]);
    }

    /// v ← Fᵀ v (`to_local`) or F v per nodal triple, F the director frame of
    /// the triple's node at `cfg` (see [`StepEquations::to_tangent_basis`]).
    fn rotate_nodal(&self, ws: &RodWorkspace, cfg: &RodConfig, v: &mut [f64], to_local: bool) {
        #[inline(always)]
        fn apply(v: &mut [f64], f: &M3, to_local: bool) {
            let x = V3::new(v[0], v[1], v[2]);
            let y = if to_local { f.tr_mul(&x) } else { f * x };
            v[0] = y.x;
            v[1] = y.y;
            v[2] = y.z;
        }
        for a in 0..=self.rod.n_el {
            let f = &cfg.d[2 * a];
            let (ix, ip) = (Rod::x_dof(a), Rod::xp_dof(a));
            apply(&mut v[ix..ix + 3], f, to_local);
            apply(&mut v[ip..ip + 3], f, to_local);
        }
        for (j, f) in cfg.d.iter().enumerate() {
            if !ws.twist_nodes.contains(&j) {
                let it = Rod::theta_dof(j);
                apply(&mut v[it..it + 3], f, to_local);
            }
        }
    }
}

/// Director frames of the element's seven unknown triples (in the order of
/// [`ElemDofs`]: r_a, r'_a, θ_a, θ_mid, r_b, r'_b, θ_b); identity for the
/// rotation of a twist-held node, which has a basis of its own (§5.6).
fn element_frames(cfg: &RodConfig, e: usize, twist: &[usize]) -> [M3; 7] {
    let frame = |j: usize| cfg.d[j];
    let rot = |j: usize| if twist.contains(&j) { M3::identity() } else { cfg.d[j] };
    let (a, m, b) = (2 * e, 2 * e + 1, 2 * e + 2);
    [frame(a), frame(a), rot(a), rot(m), frame(b), frame(b), rot(b)]
}

/// k ← Fᵀ k F with F = diag(frames) in 3 × 3 blocks: the element tangent
/// with respect to unknowns in the nodes' director frames (§5.7).
fn corotate(k: &mut ElMat, frames: &[M3; 7]) {
    for (bi, fi) in frames.iter().enumerate() {
        for (bj, fj) in frames.iter().enumerate() {
            let blk: M3 = k.fixed_view::<3, 3>(3 * bi, 3 * bj).into_owned();
            k.fixed_view_mut::<3, 3>(3 * bi, 3 * bj).copy_from(&(fi.transpose() * blk * fj));
        }
    }
}

/// The rod's twist-held nodes, for verification (tests probe the step
/// equations and restore the step rotations after a probe).
impl RodWorkspace {
    /// The step rotations of the twist-held nodes (to restore after a probe).
    pub fn twist_state(&self) -> Vec<V3> {
        self.theta_step.clone()
    }

    pub fn set_twist_state(&mut self, theta: &[V3]) {
        self.theta_step.copy_from_slice(theta);
    }
}

fn cayley_vector(q: &M3) -> V3 {
    let f = 2.0 / (1.0 + q.trace());
    V3::new(q[(2, 1)] - q[(1, 2)], q[(0, 2)] - q[(2, 0)], q[(1, 0)] - q[(0, 1)]) * f
}

/// q_{n+1} ← q_{n+1} ⊕ Δu: additive on r and r', Cayley on the directors
/// (d ← cay(θ) d); at a twist-held node the step's Cayley vector is updated
/// additively in the frame of d_n, θ ← θ + D_n θ_loc (θ_loc,3 = 0), and
/// d_{n+1} = cay(θ) d_n, so that θ·d3_n = 0 holds exactly (§5.6).
fn apply_increment(rod: &Rod, prev: &RodConfig, cfg: &mut RodConfig, du: &[f64], twist: &[usize], theta: &mut [V3]) {
    for a in 0..=rod.n_el {
        let i = Rod::x_dof(a);
        cfg.x[a] += V3::new(du[i], du[i + 1], du[i + 2]);
        let i = Rod::xp_dof(a);
        cfg.xp[a] += V3::new(du[i], du[i + 1], du[i + 2]);
    }
    for j in 0..rod.n_director_nodes() {
        let i = Rod::theta_dof(j);
        let th = V3::new(du[i], du[i + 1], du[i + 2]);
        if let Some(k) = twist.iter().position(|&t| t == j) {
            theta[k] += prev.d[j] * th;
            cfg.d[j] = cayley(&theta[k]) * prev.d[j];
        } else {
            cfg.d[j] = cayley(&th) * cfg.d[j];
        }
    }
}

/// Centreline slope r' at director node j (an end node, or the middle of an element).
fn slope_at_director_node(rod: &Rod, c: &RodConfig, j: usize) -> V3 {
    if j % 2 == 0 {
        c.xp[j / 2]
    } else {
        let e = j / 2;
        let nd = crate::math::shape::hermite_ds(0.5, rod.h);
        c.x[e] * nd[0] + c.xp[e] * nd[1] + c.x[e + 1] * nd[2] + c.xp[e + 1] * nd[3]
    }
}

/// Largest free residual component (moment and r'-rows per element length), N.
fn residual_norm(r: &[f64], fixed: &[usize], h: f64) -> f64 {
    // moment rows (N m) are divided by the element length; NaN anywhere gives ∞.
    // The free rows are the runs between the (sorted) fixed ones.
    let inv_h = 1.0 / h;
    let mut m: f64 = 0.0;
    let mut nan = false;
    let mut start = 0;
    for end in fixed.iter().copied().chain(std::iter::once(r.len())) {
        for (i, v) in r[start.min(end)..end].iter().enumerate() {
            let a = if (start + i) % STRIDE < 3 { v.abs() } else { v.abs() * inv_h };
            nan |= a.is_nan();
            m = m.max(a);
        }
        start = start.max(end + 1);
    }
    if nan { f64::INFINITY } else { m }
}
