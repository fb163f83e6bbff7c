//! `riser run SYSTEM --surge A,T --heave A,T … --duration D`: the dynamics
//! of a system of lines on one vessel under the vessel's prescribed motion
//! (issue 49, docs/guide/systems.md, docs/theory.md §17.5), the lines on
//! threads; its JSON, text summary and timeseries.csv.

use riser::math::V3;
use riser::scene::system::SystemScene;
use riser::sim::system_dynamics::{EndAt, LineRun, SystemRun};
use std::io::Write;
use std::path::Path;

/// What a line's run keeps at each output time (not the whole `Outputs`:
/// a three-hour run of many lines would hold gigabytes).
#[derive(Clone, Copy)]
struct Sample {
    t: f64,
    top_force: V3,
    top_moment: V3,
    vessel_force: V3,
    vessel_moment: V3,
    tension_from: f64,
    tension_to: f64,
    min_tension: f64,
    /// Arc length of the touchdown from the line's vessel end, m (NaN: none).
    touchdown_s: f64,
    /// The line's energy balance residual, J, and what it exchanged (|work| summed), J.
    balance: f64,
    exchanged: f64,
    /// |K| + |U| + |V|, J (the balance's resolution, as a single line's).
    held: f64,
}

fn sample(l: &LineRun, e0: f64) -> Sample {
    let o = l.sim.outputs();
    let (tension_from, tension_to) = l.tensions(&o);
    Sample {
        t: o.time,
        top_force: o.top_force,
        top_moment: o.top_moment,
        vessel_force: o.vessel_force,
        vessel_moment: o.vessel_moment,
        tension_from,
        tension_to,
        min_tension: o.min_tension,
        touchdown_s: if o.touchdown_s < l.scene.line.length { o.touchdown_s } else { f64::NAN },
        balance: o.energy_balance_residual(e0),
        // a free point's work on its line is internal to the system (§17.7)
        exchanged: if l.on_vessel() { o.work_top.abs() } else { 0.0 }
            + o.work_hydro.abs()
            + if matches!(l.ends.anchor_at, EndAt::Free(_)) { 0.0 } else { o.work_anchor.abs() }
            + o.work_seabed.abs(),
        held: o.kinetic_energy.abs() + o.strain_energy.abs() + o.potential_energy.abs(),
    }
}

/// What a free point keeps at each output time.
#[derive(Clone, Copy)]
struct PointSample {
    position: V3,
    /// Its part of the energy balance (17.17) and the water's work on it, J.
    balance: f64,
    work_hydro: f64,
}

fn point_samples(run: &SystemRun) -> Vec<PointSample> {
    run.free
        .points
        .iter()
        .map(|p| PointSample { position: p.position, balance: p.energy_balance_residual(), work_hydro: p.work_hydro })
        .collect()
}

/// `riser run` of a system file.
pub fn run(path: &str, set: &[String], args: crate::RunArgs, threads: Option<usize>) -> Result<(), String> {
    let (motions, heave_until, ramp, duration, window) =
        (args.motions, args.heave_until, args.ramp, args.duration, args.window);
    let (max_tangent_age, json, out) = (args.max_tangent_age, args.json, args.out);
    let (raos, fatigue, shape_times) = (args.raos, args.fatigue, args.shape_times);
    let estimate_error = args.estimate_error;
    if let Some(Some(q)) = estimate_error
        && q != riser::sim::error_estimate::Quantity::TopTensionMax
    {
        return Err(format!(
            "--error-quantity {}: a system's estimate is of the vessel's resultant and each line's top tension, all \
             of them (leave --error-quantity out)",
            q.name()
        ));
    }
    let not_yet = |what: &str| Err(format!("{what}: not yet for a system scene ({})", "docs/guide/systems.md"));
    if raos.is_some() {
        return not_yet("--raos (give the vessel's motion by --surge, --heave, ...)");
    }
    if fatigue.is_some() {
        return not_yet("--fatigue (run the line as a single-line scene)");
    }
    if !shape_times.is_empty() {
        return not_yet("--shape-times (timeseries.csv has every line's tensions)");
    }
    crate::check_run_times(&motions, ramp, heave_until, duration, window)?;
    let sys = SystemScene::load(path).and_then(|s| s.with_overrides(set)).map_err(|e| e.to_string())?;
    let available = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = match threads {
        Some(0) => return Err("--threads must be at least 1".to_string()),
        Some(n) => n,
        None => available,
    }
    .min(sys.lines.len());
    let period = motions.all().into_iter().flatten().map(|m| m.1).fold(0.0, f64::max);
    let ramp = ramp.unwrap_or(period);
    let axes = crate::harmonic_axes(&motions, heave_until, ramp);
    // the system's angles compose z-y-x (§17), as its lines' vessels do
    let scene0 = sys.line_scene(0, V3::zeros());
    let order = riser::sim::vessel::Vessel::of_scene(&scene0).order;
    let motion = |t: f64| crate::vessel_motion_at(&axes, None, order, t);
    // the steady window: after the motion's ramp and one period, and the sea's
    let sea = riser::loads::waves::ramp_and_period(&scene0).map_err(|e| e.to_string())?;
    let settled =
        [(period > 0.0).then_some(ramp + period), sea.map(|(r, p)| r + p)].into_iter().flatten().reduce(f64::max);
    let current_grown = riser::loads::current_ramp(&scene0).duration;
    let ((w0, w1), short) = crate::steady_window(window, settled, current_grown, duration);
    // this run as its pilots repeat it: `accuracy` measures the numerics on
    // it (docs/theory.md §16.14), --estimate-error the numerics run
    let slowest = [(period > 0.0).then_some(period), sea.map(|(_, p)| p)].into_iter().flatten().reduce(f64::max);
    let pilot_spec = riser::sim::system_accuracy::SystemRunSpec {
        motion: &motion,
        window: (w0, w1),
        period: slowest,
        irregular: riser::loads::waves::irregular(&scene0),
        max_tangent_age,
    };
    let pinned = riser::sim::accuracy::Pinned::of_names(set.iter().map(|s| s.as_str()));
    let mut said = |m: &str| eprintln!("riser: {m}");
    let (sys, choice) = riser::sim::system_accuracy::apply(sys, &pilot_spec, pinned, available, &mut said)
        .map_err(|e| e.to_string())?;
    crate::say_choice(&choice);
    let dt = sys.analysis.time_step;
    let n_steps = riser::sim::internal_steps(duration, dt).map_err(|m| format!("--duration {m}"))?;
    let wall0 = std::time::Instant::now();
    let mut run = SystemRun::new(&sys)?;
    for l in &mut run.lines {
        l.sim.integrator.options_mut().max_tangent_age = max_tangent_age;
    }
    run.start(&motion(0.0));
    let targets: Vec<f64> =
        (1..=n_steps).map(|k| riser::sim::internal_step_end(0.0, duration, dt, k, n_steps)).collect();
    let progress = std::sync::Mutex::new(crate::Progress::new(!json));
    let steps_done = std::sync::atomic::AtomicU64::new(0);
    let total = n_steps * run.lines.len() as u64;
    let solve_start = std::time::Instant::now();
    // with free points the lines at them step together, a step at a time
    // (§17.7); without, a thread runs a line through the whole run
    let mut per_point: Vec<Vec<PointSample>> = Vec::new();
    let per_line = if run.free.points.is_empty() {
        run.for_each_line(threads, &|l: &mut LineRun| {
            // the energy reference: the line's energy at the start
            let e = l.sim.initial_energy;
            let mut samples = Vec::with_capacity(targets.len() + 1);
            samples.push(sample(l, e));
            for &t in &targets {
                if let Err(err) = l.advance_to(t, &motion) {
                    return (samples, Some(format!("line '{}': {err}", l.name)));
                }
                samples.push(sample(l, e));
                let done = steps_done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                // the bar is drawn by whichever thread finds it free
                if let Ok(mut p) = progress.try_lock() {
                    p.update(done as f64 / total as f64 * duration, duration, done);
                }
            }
            (samples, None)
        })
    } else {
        let e0: Vec<f64> = run.lines.iter().map(|l| l.sim.initial_energy).collect();
        let mut samples: Vec<Vec<Sample>> = run.lines.iter().zip(&e0).map(|(l, e)| vec![sample(l, *e)]).collect();
        per_point.push(point_samples(&run));
        let mut failure = None;
        for (k, &t) in targets.iter().enumerate() {
            if let Err(err) = run.advance_to(t, &motion, threads) {
                failure = Some(err.to_string());
                break;
            }
            for ((l, e), s) in run.lines.iter().zip(&e0).zip(samples.iter_mut()) {
                s.push(sample(l, *e));
            }
            per_point.push(point_samples(&run));
            let done = (k as u64 + 1) * run.lines.len() as u64;
            if let Ok(mut p) = progress.try_lock() {
                p.update(done as f64 / total as f64 * duration, duration, done);
            }
        }
        samples.into_iter().map(|s| (s, failure.clone())).collect::<Vec<_>>()
    };
    progress.lock().unwrap_or_else(|p| p.into_inner()).finish();
    let solve_wall = solve_start.elapsed().as_secs_f64();
    // a failed line ends the system's record at its last good time
    let failure = per_line.iter().find_map(|(_, f)| f.clone());
    let n_kept = per_line.iter().map(|(s, _)| s.len()).min().unwrap_or(0);
    let series: Vec<&[Sample]> = per_line.iter().map(|(s, _)| &s[..n_kept]).collect();
    let times: Vec<f64> = series[0].iter().map(|s| s.t).collect();
    // the loads on the vessel: of the lines hung from it (§17.7)
    let sum = |f: &dyn Fn(&Sample) -> V3| -> Vec<V3> {
        (0..n_kept)
            .map(|k| {
                run.lines
                    .iter()
                    .zip(&series)
                    .filter(|(l, _)| l.on_vessel())
                    .map(|(_, s)| f(&s[k]))
                    .fold(V3::zeros(), |a, b| a + b)
            })
            .collect()
    };
    let point_sum = |k: usize, f: &dyn Fn(&PointSample) -> f64| -> f64 {
        per_point.get(k).map_or(0.0, |ps| ps.iter().map(f).sum())
    };
    let force = sum(&|s| s.top_force);
    let moment = sum(&|s| s.top_moment);
    let force_vessel = sum(&|s| s.vessel_force);
    let moment_vessel = sum(&|s| s.vessel_moment);
    let balance: Vec<f64> =
        (0..n_kept).map(|k| series.iter().map(|s| s[k].balance).sum::<f64>() + point_sum(k, &|p| p.balance)).collect();
    let exchanged = (0..n_kept)
        .map(|k| series.iter().map(|s| s[k].exchanged).sum::<f64>() + point_sum(k, &|p| p.work_hydro.abs()))
        .fold(0.0, f64::max);
    let held = (0..n_kept).map(|k| series.iter().map(|s| s[k].held).sum::<f64>()).fold(0.0, f64::max);
    let balance_max = balance.iter().map(|b| b.abs()).fold(0.0, f64::max);
    let balance_scale = exchanged.max(riser::sim::report::ENERGY_RESOLUTION * held);
    let mut warnings: Vec<String> = short.into_iter().collect();
    if let Some(sea) = run.lines[0].sim.sea.as_ref() {
        warnings.extend(riser::loads::waves::repeat_warning(sea.components(), duration));
    }
    let shortest = motions.all().into_iter().flatten().map(|m| m.1).filter(|p| *p > 0.0).reduce(f64::min);
    if let Some(p) = shortest {
        warnings.extend(riser::sim::design::steps_per_period_warning("the vessel's", p, dt));
    }
    let window_of = |v: &[(f64, f64)]| crate::window_min_mean_max(v, w0, w1);
    let of = |f: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> { (0..n_kept).map(|k| (times[k], f(k))).collect() };
    let xyz = |v: &[V3]| -> serde_json::Value {
        serde_json::json!({
            "x": window_of(&of(&|k| v[k].x)).map(finite),
            "y": window_of(&of(&|k| v[k].y)).map(finite),
            "z": window_of(&of(&|k| v[k].z)).map(finite),
        })
    };
    let in_window = |t: f64| t >= w0 - 1e-9 && t <= w1 + 1e-9;
    let mut rows = Vec::new();
    for (l, s) in run.lines.iter().zip(&series) {
        let from = window_of(&s.iter().map(|x| (x.t, x.tension_from)).collect::<Vec<_>>());
        let to = window_of(&s.iter().map(|x| (x.t, x.tension_to)).collect::<Vec<_>>());
        let min_tension = s.iter().filter(|x| in_window(x.t)).map(|x| x.min_tension).fold(f64::INFINITY, f64::min);
        let td = s
            .iter()
            .any(|x| in_window(x.t) && !x.touchdown_s.is_nan())
            .then(|| window_of(&s.iter().map(|x| (x.t, x.touchdown_s)).collect::<Vec<_>>()).map(finite));
        if min_tension < 0.0 {
            warnings.push(format!(
                "line '{}' goes into compression in the steady window: the smallest axial force is {:.3} kN",
                l.name,
                min_tension / 1e3
            ));
        }
        rows.push((l, from, to, min_tension, td));
    }
    // each free point's position over the steady window
    let point_rows: Vec<(String, V3, [[f64; 3]; 3])> = run
        .free
        .points
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let axis =
                |c: usize| window_of(&(0..n_kept).map(|k| (times[k], per_point[k][j].position[c])).collect::<Vec<_>>());
            (p.name.clone(), p.static_position, [axis(0), axis(1), axis(2)])
        })
        .collect();
    crate::warn_all(&warnings);
    let simulated = times.last().copied().unwrap_or(0.0);
    if let Some(dir) = &out {
        let loads = [&force[..], &moment[..], &force_vessel[..], &moment_vessel[..]];
        write_csv(dir, &run, &series, &per_point[..n_kept.min(per_point.len())], &times, loads, &balance, &motion)
            .map_err(|e| format!("cannot write {}: {e}", dir.display()))?;
    }
    // the error of these numerics on this run's own motion and sea (issue 51)
    let names = riser::sim::system_accuracy::line_names(&sys);
    let estimate = match estimate_error {
        Some(_) => {
            Some(riser::sim::system_accuracy::estimate_error(&sys, &pilot_spec, available).map_err(|e| e.to_string())?)
        }
        None => None,
    };
    let wall = wall0.elapsed().as_secs_f64();
    let steps: u64 = run.lines.iter().map(|l| l.sim.state.steps).sum();
    let iterations: u64 = run.lines.iter().map(|l| l.sim.state.newton_iterations).sum();
    if json {
        let lines: Vec<serde_json::Value> = rows
            .iter()
            .map(|(l, from, to, min_tension, td)| {
                serde_json::json!({
                    "name": l.name,
                    "model": if l.scene.analysis.model == riser::scene::Model::Rod { "rod" } else { "cable" },
                    "n_elements": l.scene.analysis.n_elements,
                    "static_tension_from": l.static_tensions().0,
                    "static_tension_to": l.static_tensions().1,
                    "tension_from": from.map(finite),
                    "tension_to": to.map(finite),
                    "min_tension": finite(*min_tension),
                    "touchdown_s": td,
                })
            })
            .collect();
        let v = serde_json::json!({
            "scene": sys.name,
            "system": true,
            "motion": motions.describe(),
            "time_step": dt,
            "newton_tolerance": sys.analysis.newton_tolerance,
            "duration": simulated,
            "ramp": ramp,
            "completed": failure.is_none(),
            "error": failure,
            "steady": {
                "window": [w0, w1],
                "top_force": xyz(&force),
                "top_moment": xyz(&moment),
                "vessel_force": xyz(&force_vessel),
                "vessel_moment": xyz(&moment_vessel),
                "lines": lines,
            },
            "energy_balance_residual": balance_max,
            "energy_balance_relative": if balance_scale > 0.0 { balance_max / balance_scale } else { 0.0 },
            "points": point_rows.iter().map(|(name, st, w)| serde_json::json!({
                "name": name,
                "static_position": [st.x, st.y, st.z],
                "x": w[0].map(finite),
                "y": w[1].map(finite),
                "z": w[2].map(finite),
            })).collect::<Vec<_>>(),
            "point_iterations": run.free.point_iterations,
            "trial_newton_iterations": run.free.trial_iterations,
            "threads": threads,
            "steps": steps,
            "newton_iterations": iterations,
            "wall_time": wall,
            "solve_wall_time": solve_wall,
            "real_time_factor": simulated / solve_wall.max(1e-12),
            "accuracy": crate::choice_json(&choice),
        });
        let mut v = v;
        if let (Some(e), Some(o)) = (&estimate, v.as_object_mut()) {
            o.insert("error_estimate".into(), crate::error_estimate_json(e, None, &names));
        }
        outln!("{v}");
    } else {
        let kn = |v: f64| v / 1e3;
        outln!(
            "riser run: system '{}' ({} lines, time step {} s), {}{}",
            sys.name,
            run.lines.len(),
            dt,
            motions.describe(),
            if period > 0.0 { format!(", ramped over {ramp} s") } else { String::new() }
        );
        outln!("  steady window {w0} to {w1} s (min / mean / max):");
        for (name, v) in [("force on vessel", &force), ("moment", &moment)] {
            let unit = if name == "moment" { "kN m" } else { "kN" };
            for (axis, f) in [("x", 0), ("y", 1), ("z", 2)] {
                let w = window_of(&of(&|k| v[k][f]));
                outln!("    {name:<16} {axis}  {:12.3} / {:12.3} / {:12.3} {unit}", kn(w[0]), kn(w[1]), kn(w[2]));
            }
        }
        for (l, from, to, min_tension, td) in &rows {
            let td = td
                .map(|t| format!(", touchdown {:.1} to {:.1} m", t[0].unwrap_or(f64::NAN), t[2].unwrap_or(f64::NAN)))
                .unwrap_or_default();
            outln!(
                "    line {:<12} tension from {:.3} / {:.3} / {:.3} kN, to {:.3} / {:.3} / {:.3} kN, min axial {:.3} \
                 kN{td}",
                l.name,
                kn(from[0]),
                kn(from[1]),
                kn(from[2]),
                kn(to[0]),
                kn(to[1]),
                kn(to[2]),
                kn(*min_tension)
            );
        }
        for (name, st, w) in &point_rows {
            outln!(
                "    point {name:<11} x {:.3} / {:.3} / {:.3} m, y {:.3} / {:.3} / {:.3} m, z {:.3} / {:.3} / {:.3} m \
                 (static ({:.3}, {:.3}, {:.3}) m)",
                w[0][0],
                w[0][1],
                w[0][2],
                w[1][0],
                w[1][1],
                w[1][2],
                w[2][0],
                w[2][1],
                w[2][2],
                st.x,
                st.y,
                st.z
            );
        }
        outln!("  energy balance       {:.3e} J residual of {:.3e} J exchanged (the system)", balance_max, exchanged);
        outln!(
            "  {steps} steps over {} lines on {threads} thread(s), {:.2} Newton iterations/step; {:.2} s wall, {:.0}x \
             real time",
            run.lines.len(),
            iterations as f64 / steps.max(1) as f64,
            wall,
            simulated / solve_wall.max(1e-12)
        );
        crate::choice_text(&choice);
        if let Some(e) = &estimate {
            crate::error_estimate_text(e, None, &names);
        }
        if let Some(dir) = &out {
            outln!("  wrote {}", dir.join("timeseries.csv").display());
        }
    }
    match failure {
        Some(f) => Err(format!("the run stopped at t = {simulated} s: {f}")),
        None => Ok(()),
    }
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// timeseries.csv of a system: t, the resultants (global and vessel frame),
/// the vessel's motion, the energy balance residual, and per line
/// `LINE.tension_from`, `LINE.tension_to`, `LINE.min_tension`, and per free
/// point `POINT.x`, `POINT.y`, `POINT.z`.
#[allow(clippy::too_many_arguments)]
fn write_csv(
    dir: &Path,
    run: &SystemRun,
    series: &[&[Sample]],
    points: &[Vec<PointSample>],
    times: &[f64],
    loads: [&[V3]; 4],
    balance: &[f64],
    motion: &dyn Fn(f64) -> riser::sim::vessel::VesselMotion,
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join("timeseries.csv"))?);
    write!(f, "t")?;
    for name in ["top_force", "top_moment", "vessel_force", "vessel_moment"] {
        for a in ["x", "y", "z"] {
            write!(f, ",{name}_{a}")?;
        }
    }
    write!(f, ",surge,sway,heave,roll,pitch,yaw,energy_balance_residual")?;
    for l in &run.lines {
        write!(f, ",{0}.tension_from,{0}.tension_to,{0}.min_tension", l.name)?;
    }
    for p in &run.free.points {
        write!(f, ",{0}.x,{0}.y,{0}.z", p.name)?;
    }
    writeln!(f)?;
    for (k, t) in times.iter().enumerate() {
        write!(f, "{t}")?;
        for v in loads {
            write!(f, ",{},{},{}", v[k].x, v[k].y, v[k].z)?;
        }
        let m = motion(*t);
        let d = m.displacement;
        write!(f, ",{},{},{},{},{},{}", d.x, d.y, d.z, m.angles[0], m.angles[1], m.angles[2])?;
        write!(f, ",{}", balance[k])?;
        for s in series {
            write!(f, ",{},{},{}", s[k].tension_from, s[k].tension_to, s[k].min_tension)?;
        }
        for p in points.get(k).into_iter().flatten() {
            write!(f, ",{},{},{}", p.position.x, p.position.y, p.position.z)?;
        }
        writeln!(f)?;
    }
    f.flush()
}

/// `riser model-description --scene SYSTEM.toml`: the model description of
/// the system FMU that has the file in its resources.
pub fn model_description(path: &str) -> Result<(), String> {
    if !riser::scene::system::is_system_source(path) {
        return Err(format!(
            "--scene {path}: not a system scene file ([[line]]); a single-line scene needs no FMU of its own: the \
             generic FMU takes it as its `scene` parameter"
        ));
    }
    let sys = SystemScene::load(path).map_err(|e| e.to_string())?;
    let name = std::path::Path::new(path).file_name().and_then(|n| n.to_str()).unwrap_or(path);
    out!("{}", riser::fmi::system::model_description(&sys, name)?);
    Ok(())
}

/// `riser scene SYSTEM`: the system as the models see it: its points, and
/// each line as the single-line scene it is (its frame at its vessel point,
/// docs/theory.md §17.1), with the properties along it.
pub fn print_system(path: &str, set: &[String]) -> Result<(), String> {
    let sys = SystemScene::load(path).and_then(|s| s.with_overrides(set)).map_err(|e| e.to_string())?;
    outln!("# system '{}': {} lines, {} points; {}", sys.name, sys.lines.len(), sys.points.len(), sys.description);
    outln!("# the system's frame: origin at the vessel's reference point at rest, z up");
    outln!("# {:<24} {:<8} {:>12} {:>12} {:>12}", "point", "kind", "x (m)", "y (m)", "z (m)");
    for p in &sys.points {
        let kind = format!("{:?}", p.kind).to_lowercase();
        let [x, y, z] = p.position;
        outln!("# {:<24} {:<8} {x:>12.3} {y:>12.3} {z:>12.3}", p.name, kind);
    }
    for (i, l) in sys.lines.iter().enumerate() {
        let (end, vp, _) = sys.ends(i);
        let scene = sys.line_scene(i, V3::from(vp.position));
        let end = if end == riser::scene::system::VesselEnd::From { "from" } else { "to" };
        let at = if vp.kind == riser::scene::system::PointKind::Vessel { "on the vessel" } else { "at the free point" };
        outln!();
        outln!(
            "# line '{}' ({}, {} to {}; its {end} end {at} '{}'), as the single-line scene it is (its frame's origin \
             at that point at rest; a free point at its initial position):",
            l.name,
            l.line_type,
            l.from,
            l.to,
            vp.name
        );
        crate::print_scene(scene);
    }
    Ok(())
}

/// `riser modes SYSTEM`: with the vessel held, the lines between a fixed
/// and a vessel point vibrate alone (they meet only at the vessel): their
/// modes are each line's `count` lowest; the lines joined at free points
/// vibrate together with the points (docs/theory.md §17.9): their `count`
/// lowest joined modes. All merged by period.
pub fn modes(path: &str, set: &[String], count: usize, json: bool) -> Result<(), String> {
    let sys = SystemScene::load(path).and_then(|s| s.with_overrides(set)).map_err(|e| e.to_string())?;
    let t0 = std::time::Instant::now();
    let has_free = sys.points.iter().any(|p| p.kind == riser::scene::system::PointKind::Free);
    let joined = if has_free { Some(riser::sim::system_modes::joined_modes(&sys, count)?) } else { None };
    let alone = |i: &usize| joined.as_ref().is_none_or(|j| !j.lines.contains(i));
    let mut lines = Vec::new();
    for (i, l) in sys.lines.iter().enumerate() {
        if !alone(&i) {
            continue;
        }
        let (_, vp, _) = sys.ends(i);
        let scene = sys.line_scene(i, V3::from(vp.position));
        let rep = riser::sim::modes::scene_modes(&scene, count).map_err(|e| format!("line '{}': {e}", l.name))?;
        lines.push((l.name.clone(), rep));
    }
    let wall = t0.elapsed().as_secs_f64();
    // a row: a line's own mode, or a joined one
    enum Row<'a> {
        Alone(&'a str, &'a riser::sim::modes::SceneMode),
        Joined(&'a riser::sim::system_modes::JoinedMode),
    }
    let period = |r: &Row| match r {
        Row::Alone(_, m) => m.period,
        Row::Joined(m) => m.period,
    };
    let mut merged: Vec<Row> =
        lines.iter().flat_map(|(n, r)| r.modes.iter().map(move |m| Row::Alone(n.as_str(), m))).collect();
    if let Some(j) = &joined {
        merged.extend(j.modes.iter().map(Row::Joined));
    }
    merged.sort_by(|a, b| period(b).total_cmp(&period(a)));
    // a joined mode's parts, the largest share first: (kind, name, share, direction)
    let parts = |m: &riser::sim::system_modes::JoinedMode| {
        let j = joined.as_ref().expect("a joined mode has its problem");
        let mut v: Vec<(&str, &str, f64, &str)> = m
            .lines
            .iter()
            .zip(&j.lines)
            .map(|(p, &i)| ("line", sys.lines[i].name.as_str(), p.share, p.direction))
            .chain(m.points.iter().zip(&j.point_names).map(|(p, n)| ("point", n.as_str(), p.share, p.direction)))
            .collect();
        v.sort_by(|a, b| b.2.total_cmp(&a.2));
        v
    };
    if json {
        let finite = |v: f64| v.is_finite().then_some(v);
        let mut v = serde_json::json!({
            "scene": sys.name,
            "system": true,
            "lines": lines.iter().map(|(n, r)| serde_json::json!({
                "name": n,
                "periods": r.modes.iter().map(|m| finite(m.period)).collect::<Vec<_>>(),
                "directions": r.modes.iter().map(|m| m.direction.name()).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
            "modes": merged.iter().map(|r| match r {
                Row::Alone(n, m) => serde_json::json!({
                    "line": n, "number": m.number, "period": finite(m.period), "direction": m.direction.name(),
                }),
                Row::Joined(m) => {
                    let p = parts(m);
                    serde_json::json!({
                        "joined": true,
                        "number": m.number,
                        "period": finite(m.period),
                        "frequency": m.frequency,
                        "most": p[0].1,
                        "direction": p[0].3,
                        "parts": p.iter().map(|(kind, name, share, dir)| serde_json::json!({
                            "kind": kind, "name": name, "share": share, "direction": dir,
                        })).collect::<Vec<_>>(),
                    })
                }
            }).collect::<Vec<_>>(),
            "wall_time": wall,
        });
        if let (Some(j), Some(o)) = (&joined, v.as_object_mut()) {
            o.insert(
                "joined".into(),
                serde_json::json!({
                    "lines": j.lines.iter().map(|&i| sys.lines[i].name.as_str()).collect::<Vec<_>>(),
                    "points": j.statics.points.iter().map(|p| serde_json::json!({
                        "name": p.name, "position": [p.position.x, p.position.y, p.position.z],
                    })).collect::<Vec<_>>(),
                    "unknowns": j.unknowns,
                    "asymmetry": j.asymmetry,
                    "periods": j.modes.iter().map(|m| finite(m.period)).collect::<Vec<_>>(),
                    "point_displacements": j.modes.iter().map(|m| m.point_displacements.iter()
                        .map(|d| [d.x, d.y, d.z]).collect::<Vec<_>>()).collect::<Vec<_>>(),
                }),
            );
        }
        outln!("{v}");
        return Ok(());
    }
    match &joined {
        None => outln!(
            "riser modes: system '{}' ({} lines; the vessel held, each line's {count} lowest modes, longest period \
             first)",
            sys.name,
            sys.lines.len()
        ),
        Some(j) => outln!(
            "riser modes: system '{}' ({} lines; the vessel held; line(s) {} joined at free point(s) {}: their {count} \
             lowest modes together ({} unknowns); each other line's {count} lowest; longest period first)",
            sys.name,
            sys.lines.len(),
            j.lines.iter().map(|&i| sys.lines[i].name.as_str()).collect::<Vec<_>>().join(", "),
            j.point_names.join(", "),
            j.unknowns
        ),
    }
    outln!("  {:>4} {:<24} {:>6} {:>12} {:>12}  direction", "", "line", "mode", "period (s)", "freq (Hz)");
    for (k, r) in merged.iter().enumerate() {
        match r {
            Row::Alone(n, m) => outln!(
                "  {:>4} {n:<24} {:>6} {:>12.4} {:>12.5}  {}",
                k + 1,
                m.number,
                m.period,
                m.frequency,
                m.direction.name()
            ),
            Row::Joined(m) => {
                let p = parts(m);
                let most: Vec<String> = p
                    .iter()
                    .take(3)
                    .filter(|x| x.2 >= 0.01)
                    .map(|(kind, name, share, dir)| format!("{kind} {name} {:.0}% {dir}", 100.0 * share))
                    .collect();
                outln!(
                    "  {:>4} {:<24} {:>6} {:>12.4} {:>12.5}  {}",
                    k + 1,
                    "(joined)",
                    m.number,
                    m.period,
                    m.frequency,
                    most.join(", ")
                )
            }
        }
    }
    outln!("  {:.2} s", wall);
    Ok(())
}
