//! `riser` — the engine of the FMU on the command line.
//!
//! `riser statics SCENE [--set name=value]... [--json] [--out DIR]`
//! `riser run SCENE [--set name=value]... [--heave A,T] [--surge A,T] [--sway A,T] [--heave-until T] --duration D [--out DIR] [--json]`
//! `riser modes SCENE [--set name=value]... [--count N] [--json] [--out DIR]` — natural periods and
//! mode shapes about the static state (modes.rs: text, JSON, modes.csv, mode_shapes.csv, modes.svg)
//! `riser waves SCENE [--set name=value]... [--duration D] [--out DIR] [--json]` — the scene's sea
//! (waves.rs: components, Hs and Tp; elevation.csv, spectrum.csv, components.csv, waves.svg)
//! `riser params`, `riser model-description`, `riser scene SCENE [--set name=value]...`

/// `println!` for the command's output on stdout, which a closed pipe
/// (`riser statics catenary --json | head -c 100`) silences instead of
/// panicking: the command goes on (and writes its files), only the printing
/// stops.
macro_rules! outln {
    () => {
        $crate::emit(format_args!("\n"))
    };
    ($($t:tt)*) => {
        $crate::emit(format_args!("{}\n", format_args!($($t)*)))
    };
}

/// `print!` on stdout as [`outln!`].
macro_rules! out {
    ($($t:tt)*) => {
        $crate::emit(format_args!($($t)*))
    };
}

mod modes;
mod svg;
mod system;
mod system_run;
mod touchdown;
mod waves;

/// Writes to stdout; a reader that has gone away (broken pipe) is not an
/// error of the command, any other failure is reported once on stderr.
fn emit(args: std::fmt::Arguments) {
    use std::sync::atomic::{AtomicBool, Ordering};
    static SILENT: AtomicBool = AtomicBool::new(false);
    if SILENT.load(Ordering::Relaxed) {
        return;
    }
    if let Err(e) = std::io::stdout().lock().write_fmt(args) {
        SILENT.store(true, Ordering::Relaxed);
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("riser: cannot write to stdout: {e}");
        }
    }
}

use clap::{Parser, Subcommand};
use riser::scene::{PARAMETER_NAMES, Scene};
use riser::sim::report::{StaticReport, solve_scene};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "riser", version, about = "Nonlinear statics and dynamics of marine risers (Cosserat rod)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Static equilibrium under gravity and buoyancy (and the current if the scene's static_current is true).
    Statics {
        /// Built-in scene (catenary, lazy_wave, steel_catenary) or path to a scene file (TOML).
        scene: String,
        /// Override a parameter by name, e.g. --set n_elements=120 (see `riser params`).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Print one JSON object instead of the text summary.
        #[arg(long)]
        json: bool,
        /// Write shape.csv (S, x, y, z, tension) into this directory.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// A system scene's vessel pose: surge,sway,heave (m),roll,pitch,yaw (rad) (docs/guide/systems.md).
        #[arg(long, value_name = "POSE", allow_hyphen_values = true)]
        pose: Option<String>,
    },
    /// Dynamic run from the static state with the vessel moving A sin(2πt/T) (heave, surge, sway, roll, pitch, yaw).
    Run(Box<RunCli>),
    /// Natural periods and mode shapes of the line about its static state (with added mass).
    Modes(modes::ModesArgs),
    /// The scene's sea as riser realises it: components, Hs and Tp, and with --out the elevation, its
    /// spectrum and a plot.
    Waves(waves::WavesArgs),
    /// List the parameters accepted by --set (the FMU's parameters) with their units and allowed ranges.
    Params {
        /// The scene whose values are shown (the defaults of a run of it).
        #[arg(default_value = "catenary")]
        scene: String,
        /// Print a JSON array of {name, value, field, unit, min, max, reason} (min/max absent for non-numbers).
        #[arg(long)]
        json: bool,
    },
    /// Print the FMU's modelDescription.xml (generated from modelDescription/variables.csv).
    ModelDescription {
        /// A system scene file: the model description of a system FMU with it in its resources
        /// (its `scene` parameter's start value the file's name; each line's outputs
        /// LINE.tension_from, LINE.tension_to, LINE.min_tension, LINE.touchdown_s, each free
        /// point's POINT.x, POINT.y, POINT.z, each line's at a fixed point LINE.anchor_force,
        /// LINE.anchor_uplift_angle).
        #[arg(long, value_name = "FILE")]
        scene: Option<String>,
    },
    /// The rainflow cycles (ASTM E1049-85) of a history, one number a line in FILE, as a JSON
    /// array of [range, count] in the order the procedure finds them (the tests' hook).
    #[command(hide = true)]
    Rainflow { file: PathBuf },
    /// Print a scene file (built-in or path, after --set overrides) as TOML.
    Scene {
        scene: String,
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
    },
}

/// `riser params`: every `--set` name with its value in `scene` (the
/// default when not set), its unit, range and the range's reason.
fn params(scene: &str, json: bool) -> Result<(), String> {
    use riser::scene::ranges;
    let sc = load(scene, &[] as &[String]).map_err(|e| e.to_string())?;
    // a number to 10 significant digits (a derived default such as m D²/8 prints its round-off otherwise)
    let value = |name: &str| match sc.parameter(name) {
        Some(text) => match text.parse::<f64>() {
            Ok(v) if v.is_finite() && v != 0.0 => ranges::number(format!("{v:.9e}").parse().unwrap_or(v)),
            _ => text,
        },
        None => "-".to_string(),
    };
    let rows: Vec<serde_json::Value> = PARAMETER_NAMES
        .iter()
        .map(|(name, unit)| match ranges::of_parameter(name) {
            Some(r) => serde_json::json!({
                "name": name, "value": value(name), "field": r.field, "unit": r.unit, "min": r.min, "max": r.max,
                "reason": r.reason,
            }),
            None => serde_json::json!({ "name": name, "value": value(name), "unit": unit }),
        })
        .collect();
    if json {
        outln!("{}", serde_json::Value::Array(rows));
        return Ok(());
    }
    outln!("parameters of --set and the FMU, with their values in scene '{}' (the default when not set):", sc.name);
    for (name, unit) in PARAMETER_NAMES {
        match ranges::of_parameter(name) {
            Some(r) => outln!("{name:20} {:>14} {:34} {}", value(name), r.interval(), r.reason),
            None => outln!("{name:20} {:>14} {unit}", value(name)),
        }
    }
    Ok(())
}

/// `riser scene`: the scene as TOML, then, as TOML comments, the line the
/// models see: each piece's properties with its modules smeared (theory §11),
/// and the end conditions.
fn print_scene(scene: Scene) {
    out!("{}", scene.to_toml());
    outln!();
    outln!("# The line as the models see it (docs/theory.md section 11: buoyancy modules smeared over their section):");
    outln!(
        "# {:>9} {:>9} {:>10} {:>11} {:>11} {:>10} {:>10} {:>11} {:>11}",
        "from (m)",
        "to (m)",
        "mass kg/m",
        "displ. m^2",
        "added m^2",
        "Cd D (m)",
        "D_eq (m)",
        "EA (N)",
        "EI (N m^2)"
    );
    for p in scene.pieces() {
        let q = &p.properties;
        outln!(
            "# {:>9.2} {:>9.2} {:>10.3} {:>11.5} {:>11.5} {:>10.4} {:>10.4} {:>11.4e} {:>11.4e}",
            p.start,
            p.end,
            q.mass_per_length,
            q.displaced_area,
            q.added_mass_area,
            q.drag_normal,
            q.diameter,
            q.axial_stiffness,
            q.bending_stiffness
        );
    }
    outln!(
        "# Ends: the hang-off is pinned (position follows the vessel, free to rotate and to twist); the anchor is \
         pinned (fixed, free to rotate, its twist about the line's axis held)."
    );
}

/// The arguments of `riser run`.
#[derive(clap::Args)]
struct RunCli {
    /// Built-in scene (catenary, lazy_wave, steel_catenary) or path to a scene file (TOML).
    scene: String,
    /// Override a parameter by name, e.g. --set time_step=0.1, or --set accuracy=1e-3 for riser to
    /// choose the elements, time step and tolerance (see `riser params`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Heave amplitude (m) and period (s) of the hang-off, e.g. --heave 2.5,20.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    heave: Option<(f64, f64)>,
    /// Surge (along x) amplitude (m) and period (s) of the hang-off; adds to the other motions.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    surge: Option<(f64, f64)>,
    /// Sway (along y) amplitude (m) and period (s) of the hang-off; adds to the other motions.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    sway: Option<(f64, f64)>,
    /// Roll amplitude (rad) and period (s) of the vessel about its reference point (the
    /// hang-off at [hang_off] offset, `--set hang_off_x=…`); adds to the other motions.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    roll: Option<(f64, f64)>,
    /// Pitch amplitude (rad) and period (s) of the vessel; adds to the other motions.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    pitch: Option<(f64, f64)>,
    /// Yaw amplitude (rad) and period (s) of the vessel; adds to the other motions.
    #[arg(long, value_name = "AMPLITUDE,PERIOD", value_parser = parse_pair, allow_hyphen_values = true)]
    yaw: Option<(f64, f64)>,
    /// The vessel's RAO table (CSV: dof,frequency,direction,amplitude,phase; overrides the
    /// scene's [vessel] raos): the vessel moves by the sea's own components through it, in
    /// phase with the waves on the line (docs/guide/waves.md); adds to the other motions.
    #[arg(long, value_name = "FILE")]
    raos: Option<String>,
    /// Hold the hang-off still after this time (s).
    #[arg(long, value_name = "T")]
    heave_until: Option<f64>,
    /// Grow the amplitudes smoothly over this time (s), ½(1 − cos(πt/ramp)); default one period
    /// of the slowest motion. --ramp 0 is the paper's abrupt start (a velocity jump at t = 0), the
    /// current in full from t = 0 too unless current_ramp is set (default: it grows over 10 s).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    ramp: Option<f64>,
    /// Simulated time, s.
    #[arg(long, value_name = "D", allow_negative_numbers = true)]
    duration: f64,
    /// The steady window of the statistics, s (default: to the end of the run from one
    /// period of the slowest motion after its ramp and one period of the sea after the
    /// sea's ramp, whichever is later; in still water without motion, the second half).
    #[arg(long, value_name = "T0,T1", value_parser = parse_window)]
    window: Option<(f64, f64)>,
    /// Times (s) at which shapes.csv records the shape; default: 8 over the last (longest) period.
    #[arg(long, value_name = "T1,T2,...", value_delimiter = ',')]
    shape_times: Vec<f64>,
    /// Steps a factorised Newton tangent may be reused for (0: a new one every step).
    #[arg(long, value_name = "STEPS", default_value_t = 20)]
    max_tangent_age: u32,
    /// A system of lines ([[line]]): step its lines on this many threads (default: the
    /// machine's cores, at most one a line); the answers are the same bits on any number.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Print one JSON summary instead of the text summary.
    #[arg(long)]
    json: bool,
    /// Write timeseries.csv and shapes.csv into this directory (with stress_range.csv for a
    /// steel tube, touchdown.svg on a seabed, fatigue.csv with --fatigue).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Fatigue over the steady window: rainflow (ASTM E1049-85) of the axial stress at every
    /// point of the line and 8 fibres of the steel's outer surface, Miner's damage on this
    /// DNV-RP-C203 S-N curve (e.g. D-seawater-cp, F1-free-corrosion, C-air), the damage per
    /// year and the life (docs/theory.md 12.5).
    #[arg(long, value_name = "CURVE")]
    fatigue: Option<String>,
    /// Stress concentration factor on the fatigue's stress ranges (DNV-RP-F204's misalignment
    /// of girth welds), at least 1.
    #[arg(long, value_name = "X", requires = "fatigue", default_value_t = 1.0)]
    scf: f64,
    /// Design fatigue factor: the life is 1 / (damage per year x DFF), the allowable damage
    /// 1/DFF (at least 1).
    #[arg(long, value_name = "Y", requires = "fatigue", default_value_t = 1.0)]
    dff: f64,
    /// With --fatigue and --out: write fatigue_series.csv, the axial stress at the 8 fibres of
    /// the point of the line nearest arc length S (m) at every output time of the steady window.
    #[arg(long, value_name = "S", requires = "fatigue")]
    fatigue_series: Option<f64>,
    /// Measure the error of this run's numerics on its own motion and sea (issue 51,
    /// docs/guide/accuracy.md): five short pilots (three periods of the slowest forcing, twenty of an
    /// irregular sea's peak period) at
    /// n, 2n, 4n elements and dt, dt/2, dt/4, the observed orders and Richardson's
    /// extrapolation; adds error_estimate to --json and a line to the text.
    #[arg(long)]
    estimate_error: bool,
    /// The quantity --estimate-error reports first: top_tension_max (default),
    /// top_tension_min, top_tension_range, top_tension_mean, touchdown_max, touchdown_min (on a
    /// seabed), stress_range (a line with stresses), fatigue_damage (with --fatigue), or all (every one is in the JSON).
    #[arg(long, value_name = "NAME", requires = "estimate_error", default_value = "top_tension_max")]
    error_quantity: String,
}

/// The vessel's harmonic motions asked for: (amplitude m or rad, period s) each.
struct Motions {
    heave: Option<(f64, f64)>,
    surge: Option<(f64, f64)>,
    sway: Option<(f64, f64)>,
    roll: Option<(f64, f64)>,
    pitch: Option<(f64, f64)>,
    yaw: Option<(f64, f64)>,
}

impl Motions {
    /// "heave 2.5 m / 20 s, roll 0.1 rad / 12 s ..." or "the hang-off held still".
    fn describe(&self) -> String {
        let parts: Vec<String> = [
            ("heave", self.heave, "m"),
            ("surge", self.surge, "m"),
            ("sway", self.sway, "m"),
            ("roll", self.roll, "rad"),
            ("pitch", self.pitch, "rad"),
            ("yaw", self.yaw, "rad"),
        ]
        .into_iter()
        .filter_map(|(name, m, unit)| m.map(|(a, t)| format!("{name} {a} {unit} / {t} s")))
        .collect();
        if parts.is_empty() { "the hang-off held still".to_string() } else { parts.join(", ") }
    }

    fn all(&self) -> [Option<(f64, f64)>; 6] {
        [self.heave, self.surge, self.sway, self.roll, self.pitch, self.yaw]
    }
}

fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 2 {
        return Err(format!("expected AMPLITUDE,PERIOD, got '{s}'"));
    }
    let a: f64 = parts[0].trim().parse().map_err(|_| format!("'{}' is not a number", parts[0]))?;
    let t: f64 = parts[1].trim().parse().map_err(|_| format!("'{}' is not a number", parts[1]))?;
    if !(t.is_finite() && t > 0.0) {
        return Err(format!("the period must be positive and finite, got {t} s"));
    }
    riser::scene::ranges::INPUT_DISPLACEMENT.check(a).map_err(|m| format!("amplitude {m}"))?;
    Ok((a, t))
}

fn parse_window(s: &str) -> Result<(f64, f64), String> {
    let parts: Vec<&str> = s.split(',').collect();
    let number = |p: &str| p.trim().parse::<f64>().map_err(|_| format!("'{}' is not a number", p.trim()));
    match parts.as_slice() {
        [a, b] => {
            let (t0, t1) = (number(a)?, number(b)?);
            if !(t0.is_finite() && t1.is_finite() && t0 >= 0.0 && t1 > t0) {
                return Err(format!("the window must be 0 <= T0 < T1, got {t0},{t1} s"));
            }
            Ok((t0, t1))
        }
        _ => Err(format!("expected T0,T1 (s), got '{s}'")),
    }
}

/// The scene with the numerics its `accuracy` chooses (docs/theory.md
/// §16.12: pilots of the run `spec`, the scene's own motion and sea; None:
/// the design motion, as the FMU chooses, for `riser statics`), the
/// numerics given by `--set` kept; the rounds of pilots and the choice are
/// printed on stderr.
fn choose_numerics(
    scene: Scene,
    set: &[String],
    spec: Option<&riser::sim::error_estimate::RunSpec>,
) -> Result<(Scene, Option<riser::sim::accuracy::Choice>), String> {
    use riser::sim::accuracy;
    let pinned = accuracy::Pinned::of_names(set.iter().map(|s| s.as_str()));
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut progress = |m: &str| eprintln!("riser: {m}");
    let (scene, choice) = match spec {
        Some(spec) => accuracy::apply(scene, spec, pinned, threads, &mut progress),
        None => accuracy::DesignRun::apply(scene, pinned, threads, &mut progress),
    }
    .map_err(|e| e.to_string())?;
    say_choice(&choice);
    Ok((scene, choice))
}

/// The choice of `accuracy` on stderr: what was chosen, its notes and the
/// warning where its estimate misses the target.
fn say_choice(choice: &Option<riser::sim::accuracy::Choice>) {
    if let Some(c) = choice {
        eprintln!("riser: {}", c.describe());
        for n in &c.notes {
            eprintln!("riser: note: {n}");
        }
        if let Some(w) = c.warning() {
            eprintln!("riser: warning: {w}");
        }
    }
}

/// The choice of `accuracy` under the JSON key `accuracy` (null when unset):
/// target, quantity, estimate, orders, chosen, set_by_user, pilots (every
/// round's), notes.
fn choice_json(choice: &Option<riser::sim::accuracy::Choice>) -> serde_json::Value {
    let Some(c) = choice else { return serde_json::Value::Null };
    let finite = |v: f64| if v.is_finite() { Some(v) } else { None };
    let orders: serde_json::Map<String, serde_json::Value> = c
        .predicted
        .iter()
        .map(|p| {
            (
                p.quantity.label(&c.line_names).into_owned(),
                serde_json::json!({
                    "mesh": p.mesh_order, "step": p.step_order, "error": finite(p.error),
                    "relative": finite(p.relative), "relative_to": p.relative_to.label(&c.line_names),
                }),
            )
        })
        .collect();
    let pilots: Vec<serde_json::Value> = c
        .rounds
        .iter()
        .enumerate()
        .flat_map(|(r, round)| {
            round.pilots.iter().map(move |p| {
                let values: serde_json::Map<String, serde_json::Value> = round
                    .quantities
                    .iter()
                    .zip(&p.values)
                    .filter(|(_, v)| v.is_finite())
                    .map(|(q, v)| (q.label(&c.line_names).into_owned(), (*v).into()))
                    .collect();
                serde_json::json!({
                    "round": r + 1, "n_elements": p.n_elements, "time_step": p.time_step,
                    "values": values, "wall_s": p.wall_s, "reused": p.reused,
                })
            })
        })
        .collect();
    serde_json::json!({
        "target": c.target,
        "quantity": c.quantity.name(),
        "estimate": finite(c.estimate()),
        "met": c.met(),
        "orders": orders,
        "chosen": {
            "n_elements": c.n_elements,
            "time_step": c.time_step,
            "newton_tolerance": c.newton_tolerance,
        },
        "set_by_user": {
            "n_elements": c.pinned.n_elements,
            "time_step": c.pinned.time_step,
            "newton_tolerance": c.pinned.newton_tolerance,
        },
        "pilots": pilots,
        "pilot_window": [c.rounds.last().map(|r| r.plan.window.0), c.rounds.last().map(|r| r.plan.window.1)],
        "notes": c.notes,
        "wall_s": c.wall_s,
    })
}

/// The choice of `accuracy` as a line of the text summary.
fn choice_text(choice: &Option<riser::sim::accuracy::Choice>) {
    if let Some(c) = choice {
        outln!("  {}", c.describe());
    }
}

fn load(scene: &str, set: &[String]) -> Result<Scene, riser::RiserError> {
    let scene = Scene::load(scene)?.with_overrides(set)?;
    if let Some(w) = scene.axial_stiffness_jump_warning() {
        eprintln!("riser: warning: {w}");
    }
    Ok(scene)
}

/// shape.csv: the static state's nodes with their tension (N) and curvature (1/m).
fn write_shape_csv(dir: &Path, scene: &Scene, report: &StaticReport) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("shape.csv");
    let cfg = &report.solution.config;
    let profile = match scene.analysis.model {
        riser::scene::Model::Rod => riser::model::rod::RodModel::from_scene(scene).node_profile(cfg),
        riser::scene::Model::Cable => riser::model::cable::CableModel::from_scene(scene).node_profile(&cfg.x),
    };
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path)?);
    writeln!(f, "S,x,y,z,tension,curvature")?;
    for (k, r) in report.shape.iter().enumerate() {
        let curvature = profile.get(k).map_or(0.0, |p| p.1);
        writeln!(f, "{},{},{},{},{},{}", r.s, r.x, r.y, r.z, r.tension, curvature)?;
    }
    f.flush()?;
    Ok(path)
}

/// The design numbers of the static state and their warnings (docs/theory.md §12).
fn static_design(
    scene: &Scene,
    rep: &StaticReport,
) -> Result<(riser::sim::design::DesignNumbers, Vec<String>), String> {
    let mut engine = riser::sim::Engine::from_scene(scene).map_err(|e| e.to_string())?;
    engine.set_static_frame(&rep.solution.config);
    let state = riser::model::State::at_rest(rep.solution.config.clone(), 0.0);
    Ok(riser::sim::design::Design::new(scene).report(scene, &engine, &state))
}

/// The design numbers under the JSON keys the README documents for `riser statics --json`.
fn design_json(d: &riser::sim::design::DesignNumbers) -> serde_json::Value {
    serde_json::json!({
        "touchdown_s": d.touchdown_s,
        "touchdown_x": d.touchdown_x,
        "hang_off_angle": d.hang_off_angle,
        "max_curvature": d.max_curvature,
        "max_curvature_s": d.max_curvature_s,
        "min_bend_radius": if d.min_bend_radius.is_finite() { Some(d.min_bend_radius) } else { None },
        "max_bending_moment": d.max_bending_moment,
        "max_bending_moment_s": d.max_bending_moment_s,
        "max_strain": d.max_strain,
        "max_strain_s": d.max_strain_s,
        "min_tension_s": d.min_tension_s,
        "max_stress": d.max_stress.map(|m| m.0),
        "max_stress_s": d.max_stress.map(|m| m.1),
        "max_von_mises": d.max_von_mises.map(|m| m.0),
        "max_von_mises_s": d.max_von_mises.map(|m| m.1),
        "max_utilisation": utilisation_json(d.max_utilisation),
        "utilisations": utilisations_json(d.api_utilisation, d.lrfd),
        "not_reported": not_reported_json(d.lrfd),
    })
}

/// Each code check's largest utilisation, [{value, check, s}]: API RP 2RD's
/// with a yield stress, DNV-OS-F201's LRFD check's when the scene asks for
/// it and it is made.
fn utilisations_json(
    api: Option<riser::sim::design::Utilisation>,
    lrfd: Option<riser::sim::design::LrfdPeak>,
) -> serde_json::Value {
    let checks = [api, lrfd.and_then(|l| l.utilisation())];
    serde_json::Value::Array(checks.into_iter().map(utilisation_json).filter(|v| !v.is_null()).collect())
}

/// The checks the scene asks for that are not made, each with why.
fn not_reported_json(lrfd: Option<riser::sim::design::LrfdPeak>) -> serde_json::Value {
    serde_json::json!(lrfd.and_then(|l| l.not_reported()).into_iter().collect::<Vec<_>>())
}

/// The text lines of DNV-OS-F201's LRFD check, when the scene asks for it:
/// each check's utilisation, or why the LRFD one is not made.
fn lrfd_text(indent: &str, api: Option<riser::sim::design::Utilisation>, lrfd: Option<riser::sim::design::LrfdPeak>) {
    let Some(lrfd) = lrfd else { return };
    for u in [api, lrfd.utilisation()].into_iter().flatten() {
        outln!("{indent}{:.3} at S = {:.1} m ({})", u.value, u.s, u.check);
    }
    if let Some(why) = lrfd.not_reported() {
        outln!("{indent}{why}");
    }
}

/// A code check's utilisation as JSON: {value, check, s}, or null.
fn utilisation_json(u: Option<riser::sim::design::Utilisation>) -> serde_json::Value {
    match u {
        Some(u) => serde_json::json!({"value": u.value, "check": u.check, "s": u.s}),
        None => serde_json::Value::Null,
    }
}

/// The design numbers as lines of the text summary.
fn design_text(d: &riser::sim::design::DesignNumbers) {
    match (d.touchdown_s, d.touchdown_x) {
        (Some(s), Some(x)) => outln!("  touchdown       S = {s:.2} m, x = {x:.2} m"),
        _ => outln!("  touchdown       none (the line touches no seabed)"),
    }
    outln!("  hang-off angle  {:10.3} deg from the vertical", d.hang_off_angle);
    outln!(
        "  max curvature   {:10.5} 1/m at S = {:.1} m (min bend radius {:.2} m)",
        d.max_curvature,
        d.max_curvature_s,
        d.min_bend_radius
    );
    outln!("  max bending moment {:7.3} kN m at S = {:.1} m", d.max_bending_moment / 1e3, d.max_bending_moment_s);
    outln!("  max axial strain {:9.4} % at S = {:.1} m", 100.0 * d.max_strain, d.max_strain_s);
    match d.max_stress {
        Some((v, s)) => {
            outln!("  max stress      {:10.3} MPa at S = {s:.1} m (outer fibre, true wall tension + bending)", v / 1e6)
        }
        None => outln!(
            "  max stress      n/a (no wall given, and EA, EI and D are not those of a homogeneous tube: a flexible \
             pipe, whose stresses are per layer)"
        ),
    }
    if let Some((v, s)) = d.max_von_mises {
        outln!("  max von Mises   {:10.3} MPa at S = {s:.1} m (with pressure, hoop and torsion)", v / 1e6);
    }
    match d.max_utilisation {
        Some(u) => outln!("  max utilisation {:10.3} at S = {:.1} m ({})", u.value, u.s, u.check),
        None if d.max_von_mises.is_some() => outln!("  max utilisation n/a (no yield_stress given)"),
        None => {}
    }
    lrfd_text("    check              ", d.api_utilisation, d.lrfd);
}

fn warn_all(warnings: &[String]) {
    for w in warnings {
        eprintln!("riser: warning: {w}");
    }
}

fn statics(scene: &str, set: &[String], json: bool, out: Option<PathBuf>) -> Result<(), String> {
    let scene = load(scene, set).map_err(|e| e.to_string())?;
    let (scene, choice) = choose_numerics(scene, set, None)?;
    let t0 = std::time::Instant::now();
    let rep = solve_scene(&scene).map_err(|e| e.to_string())?;
    let wall = t0.elapsed().as_secs_f64();
    let (design, warnings) = static_design(&scene, &rep)?;
    warn_all(&warnings);
    let csv = match &out {
        Some(dir) => {
            Some(write_shape_csv(dir, &scene, &rep).map_err(|e| format!("cannot write {}: {e}", dir.display()))?)
        }
        None => None,
    };
    if json {
        let mut v = serde_json::json!({
            "scene": scene.name,
            "n_elements": scene.analysis.n_elements,
            "time_step": scene.analysis.time_step,
            "newton_tolerance": scene.analysis.newton_tolerance,
            "accuracy": choice_json(&choice),
            "top_tension": rep.top_tension,
            "bottom_tension": rep.bottom_tension,
            "top_force": [rep.top_force.x, rep.top_force.y, rep.top_force.z],
            "bottom_force": [rep.bottom_force.x, rep.bottom_force.y, rep.bottom_force.z],
            "min_tension": rep.min_tension,
            "iterations": rep.iterations,
            "continuation_steps": rep.continuation_steps,
            "residual": rep.residual,
            "wall_time": wall,
            "shape": rep.shape.iter().map(|r| [r.s, r.x, r.y, r.z, r.tension]).collect::<Vec<_>>(),
            "warnings": warnings,
        });
        if let (Some(o), serde_json::Value::Object(d)) = (v.as_object_mut(), design_json(&design)) {
            o.extend(d);
        }
        outln!("{v}");
    } else {
        let kn = |v: f64| v / 1e3;
        let line = match scene.section.len() {
            0 => format!("EA {:.4e} N, EI {:.4e} N m^2", scene.line.axial_stiffness, scene.line.bending_stiffness),
            n => format!("{n} sections"),
        };
        outln!("riser statics: scene '{}' ({} elements, {line})", scene.name, scene.analysis.n_elements);
        choice_text(&choice);
        outln!(
            "  Newton: {} iterations, {} continuation step(s), relative residual {:.2e}, {:.1} ms",
            rep.iterations,
            rep.continuation_steps,
            rep.residual,
            wall * 1e3
        );
        outln!("  top tension     {:10.3} kN", kn(rep.top_tension));
        outln!(
            "  force on vessel ({:.3}, {:.3}, {:.3}) kN",
            kn(rep.top_force.x),
            kn(rep.top_force.y),
            kn(rep.top_force.z)
        );
        outln!("  bottom tension  {:10.3} kN", kn(rep.bottom_tension));
        outln!("  min tension     {:10.3} kN at S = {:.1} m", kn(rep.min_tension), design.min_tension_s);
        let low = rep.shape.iter().fold(f64::INFINITY, |m, r| m.min(r.z));
        outln!("  lowest point    {:10.3} m", low);
        design_text(&design);
        if !warnings.is_empty() {
            outln!("  {} warning(s) (on stderr)", warnings.len());
        }
        if let Some(p) = csv {
            outln!("  wrote {}", p.display());
        }
    }
    Ok(())
}

/// A progress line on stderr for runs longer than a second (terminal only).
struct Progress {
    start: std::time::Instant,
    last: f64,
    enabled: bool,
    shown: bool,
}

impl Progress {
    fn new(enabled: bool) -> Self {
        use std::io::IsTerminal;
        Progress {
            start: std::time::Instant::now(),
            last: 0.0,
            enabled: enabled && std::io::stderr().is_terminal(),
            shown: false,
        }
    }

    fn update(&mut self, t: f64, duration: f64, steps: u64) {
        let wall = self.start.elapsed().as_secs_f64();
        if !self.enabled || wall < 1.0 || wall - self.last < 0.2 {
            return;
        }
        self.last = wall;
        self.shown = true;
        let frac = (t / duration).clamp(0.0, 1.0);
        let filled = (frac * 30.0) as usize;
        eprint!(
            "\r[{}{}] {:5.1}%  t = {:.1}/{:.1} s  {} steps  {:.0}x real time ",
            "#".repeat(filled),
            ".".repeat(30 - filled),
            100.0 * frac,
            t,
            duration,
            steps,
            t / wall
        );
    }

    fn finish(&self) {
        if self.shown {
            eprint!("\r{}\r", " ".repeat(90));
        }
    }
}

/// What `riser run` is asked for, beyond the scene.
struct RunArgs {
    motions: Motions,
    /// --raos: the RAO table, over the scene's [vessel] raos.
    raos: Option<String>,
    heave_until: Option<f64>,
    /// None: one period of the slowest motion.
    ramp: Option<f64>,
    duration: f64,
    window: Option<(f64, f64)>,
    shape_times: Vec<f64>,
    max_tangent_age: u32,
    json: bool,
    out: Option<PathBuf>,
    /// The fatigue asked for (--fatigue, --scf, --dff).
    fatigue: Option<riser::sim::fatigue::FatigueSpec>,
    /// --fatigue-series: the arc length of the point whose stresses are written, m.
    fatigue_series: Option<f64>,
    /// --estimate-error: the quantity reported first (None: all), or no estimate.
    estimate_error: Option<Option<riser::sim::error_estimate::Quantity>>,
}

/// The fatigue asked for on the command line: the curve by name, the SCF
/// and the DFF, each checked.
fn fatigue_spec(curve: Option<String>, scf: f64, dff: f64) -> Result<Option<riser::sim::fatigue::FatigueSpec>, String> {
    let Some(name) = curve else { return Ok(None) };
    let curve = riser::sim::fatigue::SnCurve::by_name(&name).map_err(|m| format!("--fatigue: {m}"))?;
    if !(scf.is_finite() && scf >= 1.0) {
        return Err(format!("--scf must be a stress concentration factor of at least 1, got {scf}"));
    }
    if !(dff.is_finite() && dff >= 1.0) {
        return Err(format!("--dff must be a design fatigue factor of at least 1 (1: none), got {dff}"));
    }
    Ok(Some(riser::sim::fatigue::FatigueSpec { curve, scf, dff }))
}

/// `riser rainflow FILE`: the cycles of the history in FILE (one number a line).
fn rainflow_command(file: &Path) -> Result<(), String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let history = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(|l| l.parse::<f64>().map_err(|_| format!("{}: '{l}' is not a number", file.display())))
        .collect::<Result<Vec<f64>, String>>()?;
    let cycles: Vec<[f64; 2]> = riser::sim::fatigue::rainflow(&history).into_iter().map(|(r, n)| [r, n]).collect();
    outln!("{}", serde_json::json!(cycles));
    Ok(())
}

/// The stresses of one point's fibres over the steady window
/// (--fatigue-series): the point's index and (t, σ per fibre) rows, Pa.
struct FatigueRecord {
    point: usize,
    rows: Vec<(f64, [f64; riser::sim::design::FIBRES])>,
}

/// Adds the state at time `t` whose points are `points` to the fatigue and
/// its record, the hang-off at `top_z`.
fn fatigue_add(
    fatigue: &mut Option<riser::sim::fatigue::FatigueTracker>,
    record: &mut Option<FatigueRecord>,
    design: &riser::sim::design::Design,
    points: &[riser::model::outputs::LinePoint],
    top_z: f64,
    t: f64,
) {
    if let Some(f) = fatigue.as_mut() {
        f.add(design, points, top_z);
    }
    if let Some(r) = record.as_mut() {
        let dirs = riser::sim::fatigue::fibre_directions();
        let p = &points[r.point];
        r.rows.push((t, dirs.map(|(c, s)| design.fibre_stress_cs(p, c, s, top_z).unwrap_or(0.0))));
    }
}

/// The JSON of `--estimate-error` (issue 51): the `headline` quantity's
/// estimate (None: top_tension_max first), every quantity's in `quantities`,
/// the pilots.
fn error_estimate_json(
    e: &riser::sim::error_estimate::ErrorEstimate,
    headline: Option<riser::sim::error_estimate::Quantity>,
    lines: &[String],
) -> serde_json::Value {
    use riser::sim::error_estimate::{Estimate, Quantity, Triplet};
    let finite = |v: f64| v.is_finite().then_some(v);
    let triplet = |t: &Triplet, levels: serde_json::Value, fixed: (&str, serde_json::Value)| {
        let mut v = serde_json::json!({
            "levels": levels,
            "values": t.values,
            "order": t.order.and_then(finite),
            "ratio": t.ratio.and_then(finite),
            "class": t.class.name(),
            "extrapolated": t.extrapolated,
            "error": t.error,
        });
        if let Some(o) = v.as_object_mut() {
            o.insert(fixed.0.into(), fixed.1);
        }
        v
    };
    let (n, dt) = (e.n_elements, e.time_step);
    let one = |q: &Estimate| {
        serde_json::json!({
            "quantity": q.quantity.label(lines),
            "value": q.value,
            "extrapolated": q.extrapolated,
            "estimate": {
                "absolute": q.error.abs(),
                "signed": q.error,
                "relative": finite(q.relative),
                "bound": q.bound,
                "gci": q.gci,
                "gci_safety_factor": if q.notes.is_empty() {
                    riser::sim::error_estimate::GCI_SAFETY
                } else {
                    riser::sim::error_estimate::GCI_SAFETY_UNCONVERGED
                },
            },
            "mesh": triplet(&q.mesh, serde_json::json!([n, 2 * n, 4 * n]), ("time_step", (dt / 4.0).into())),
            "step": triplet(&q.step, serde_json::json!([dt, dt / 2.0, dt / 4.0]), ("n_elements", n.into())),
            "monotone": q.notes.is_empty(),
            "notes": q.notes,
        })
    };
    // the headline checked applicable before the run; not estimated: the quantity and why
    let asked = headline.unwrap_or_else(|| e.estimates.first().map_or(Quantity::TopTensionMax, |x| x.quantity));
    let mut v = match e.of(asked) {
        Some(first) => one(first),
        None => serde_json::json!({"quantity": asked.name(), "value": null, "estimate": null}),
    };
    if let Some(o) = v.as_object_mut() {
        o.insert("not_estimated".into(), e.notes.clone().into());
        o.insert("quantities".into(), e.estimates.iter().map(one).collect::<Vec<_>>().into());
        o.insert("pilot_window".into(), serde_json::json!([e.plan.window.0, e.plan.window.1]));
        o.insert("pilot_duration".into(), e.plan.duration.into());
        o.insert(
            "pilots".into(),
            e.pilots
                .iter()
                .map(|p| {
                    let mut values = serde_json::Map::new();
                    for (q, v) in e.quantities.iter().zip(&p.values) {
                        values.insert(q.label(lines).into(), finite(*v).into());
                    }
                    serde_json::json!({"n_elements": p.n_elements, "time_step": p.time_step, "values": values, "wall_s": p.wall_s})
                })
                .collect::<Vec<_>>()
                .into(),
        );
        o.insert("pilots_wall_s".into(), e.wall_s.into());
    }
    v
}

/// The text of `--estimate-error`: a line per quantity asked for (None: all).
fn error_estimate_text(
    e: &riser::sim::error_estimate::ErrorEstimate,
    headline: Option<riser::sim::error_estimate::Quantity>,
    lines: &[String],
) {
    let (w0, w1) = e.plan.window;
    outln!(
        "  error estimate: 5 pilots at {n}, {}, {} elements and time steps {dt}, {}, {} s over {w0} to {w1} s{}",
        2 * e.n_elements,
        4 * e.n_elements,
        e.time_step / 2.0,
        e.time_step / 4.0,
        if e.plan.cut { " (the window cut to 3 periods)" } else { "" },
        n = e.n_elements,
        dt = e.time_step,
    );
    for q in &e.estimates {
        if headline.is_none_or(|h| h == q.quantity) {
            outln!("    {}", q.summary_of(lines));
        }
    }
    for n in &e.notes {
        outln!("    {n}");
    }
}

/// The steady window [t0, t1] of a run (s) and, when the run is too short
/// for one, a warning: the default starts `settled` s after t = 0, one
/// period of the slowest motion after its ramp and one period of the sea
/// after the sea's (the start's transients have died out by then with the
/// default ρ∞ = 0.8: docs/figures/abrupt_vs_smooth.png); without motion
/// or sea (`None`: still water, the line moves only as the current grows)
/// the second half of the run. Never before the current has grown
/// (`current_grown` s, its ramp's end; 0 with the current in the statics or
/// none, docs/theory.md §5.11).
fn steady_window(
    asked: Option<(f64, f64)>,
    settled: Option<f64>,
    current_grown: f64,
    duration: f64,
) -> ((f64, f64), Option<String>) {
    if let Some(w) = asked {
        return (w, None);
    }
    let Some(t0) = settled else {
        if current_grown >= duration {
            return (
                (0.5 * duration, duration),
                Some(format!(
                    "the run ({duration} s) ends before the current has grown (current_ramp = {current_grown} s): \
                     the statistics of its second half are of the current's start; run longer or give --window"
                )),
            );
        }
        return ((current_grown.max(0.5 * duration), duration), None);
    };
    let t0 = t0.max(current_grown);
    if t0 < duration {
        ((t0, duration), None)
    } else {
        (
            (0.5 * duration, duration),
            Some(format!(
                "the run ({duration} s) is shorter than the ramp and one period, or the current's growth ({t0} s): \
                 the statistics of its second half are not of a steady state; run longer or give --window"
            )),
        )
    }
}

/// The min, time mean and max of `(t, y)` samples in time order (a window of
/// the run's output series). The mean is the trapezoid rule's ∫ y dt over the
/// samples' span: the arithmetic mean of the samples with both ends included
/// carries an O(Δt) bias, (y_end − ȳ) Δt / W over a window W, as large as the
/// integrator's own error at 1e-4 (docs/accuracy.md, "The references' floor").
/// A NaN `y` is a gap: the intervals at either side of it do not count (the
/// touchdown point while the line is off the seabed). With no interval left,
/// the mean is the samples' (one sample: itself).
fn min_mean_max(v: impl Iterator<Item = (f64, f64)> + Clone) -> [f64; 3] {
    let present = v.clone().filter(|(_, y)| !y.is_nan());
    let n = present.clone().count();
    if n == 0 {
        return [f64::NAN; 3];
    }
    let min = present.clone().map(|(_, y)| y).fold(f64::INFINITY, f64::min);
    let max = present.clone().map(|(_, y)| y).fold(f64::NEG_INFINITY, f64::max);
    let (mut integral, mut span) = (0.0, 0.0);
    let mut prev: Option<(f64, f64)> = None;
    for (t, y) in v {
        if let Some((t0, y0)) = prev
            && !(y.is_nan() || y0.is_nan())
        {
            integral += 0.5 * (y0 + y) * (t - t0);
            span += t - t0;
        }
        prev = Some((t, y));
    }
    let mean = if span > 0.0 { integral / span } else { present.map(|(_, y)| y).sum::<f64>() / n as f64 };
    [min, mean, max]
}

/// Min, time mean and max of a series over the window [t0, t1] (s): the
/// extremes of the samples in it, the mean of the piecewise-linear
/// interpolant over exactly [t0, t1] (its ends interpolated between the
/// samples either side, where the step does not fall on them; before, the
/// trapezoid rule over the samples inside only, a window short by up to a
/// step at each end: the steel catenary heaved at 10 s, window 20 to 40 s,
/// dt 0.015 s, its first sample at 20.01 s, had its mean 27.6 N, 7.6e-5 of
/// the maximum, off). A NaN is a gap, as in [`min_mean_max`]; with no
/// interval inside, the samples' mean.
fn window_min_mean_max(v: &[(f64, f64)], t0: f64, t1: f64) -> [f64; 3] {
    let inside = || v.iter().copied().filter(|(t, _)| *t >= t0 - 1e-9 && *t <= t1 + 1e-9);
    let [min, sampled_mean, max] = min_mean_max(inside());
    let (mut integral, mut span) = (0.0, 0.0);
    for w in v.windows(2) {
        let ((ta, ya), (tb, yb)) = (w[0], w[1]);
        let (a, b) = (ta.max(t0), tb.min(t1));
        if b <= a || tb <= ta || ya.is_nan() || yb.is_nan() {
            continue;
        }
        let at = |t: f64| ya + (yb - ya) * (t - ta) / (tb - ta);
        integral += 0.5 * (at(a) + at(b)) * (b - a);
        span += b - a;
    }
    [min, if span > 0.0 { integral / span } else { sampled_mean }, max]
}

/// The checks of `riser run`'s times and motions that need no scene:
/// duration, ramp, --heave-until, the window within the run, and angles in
/// radians below π/2.
fn check_run_times(
    motions: &Motions,
    ramp: Option<f64>,
    heave_until: Option<f64>,
    duration: f64,
    window: Option<(f64, f64)>,
) -> Result<(), String> {
    if !(duration.is_finite() && duration > 0.0) {
        return Err(format!("--duration must be a positive number of seconds, got {duration}"));
    }
    if let Some(r) = ramp
        && !(r.is_finite() && r >= 0.0)
    {
        return Err(format!("--ramp must be zero (the paper's abrupt start) or positive, got {r}"));
    }
    if let Some(u) = heave_until
        && !u.is_finite()
    {
        return Err(format!("--heave-until must be finite, got {u}"));
    }
    if let Some((t0, t1)) = window
        && t1 > duration * (1.0 + 1e-12)
    {
        return Err(format!("--window {t0},{t1} must lie within the run, 0 to {duration} s (--duration)"));
    }
    if let Some(name) = [("roll", motions.roll), ("pitch", motions.pitch), ("yaw", motions.yaw)]
        .into_iter()
        .find_map(|(name, m)| m.filter(|(a, _)| a.abs() >= 0.5 * std::f64::consts::PI).map(|_| name))
    {
        return Err(format!(
            "--{name}: an amplitude of 90 degrees (π/2 rad) or more; the angles are in radians (0.1 rad = 5.7 deg)"
        ));
    }
    Ok(())
}

/// Each harmonic motion asked for as a ramped sine about its axis: (axis,
/// its sine), axes 0-5 heave, surge, sway of the reference point, roll,
/// pitch, yaw (`Motions::all`'s order).
fn harmonic_axes(motions: &Motions, until: Option<f64>, ramp: f64) -> Vec<(usize, riser::sim::Heave)> {
    motions
        .all()
        .into_iter()
        .enumerate()
        .filter_map(|(i, m)| m.map(|(amplitude, period)| (i, riser::sim::Heave { amplitude, period, until, ramp })))
        .collect()
}

/// The vessel's motion at `t` (s): the harmonics `axes` summed, plus the
/// motion on its RAOs; the body rates of the angles' rates in `order` (§14).
fn vessel_motion_at(
    axes: &[(usize, riser::sim::Heave)],
    rao: Option<&riser::sim::vessel::RaoMotion>,
    order: riser::math::rigid::RotationOrder,
    t: f64,
) -> riser::sim::vessel::VesselMotion {
    let mut m = riser::sim::vessel::VesselMotion::default();
    let mut rates = [0.0; 3];
    for (i, h) in axes {
        let one = h.at(t);
        let (u, v) = (one.displacement.z, one.velocity.z);
        match i {
            0 => (m.displacement.z, m.velocity.z) = (u, v),
            1 => (m.displacement.x, m.velocity.x) = (u, v),
            2 => (m.displacement.y, m.velocity.y) = (u, v),
            k => (m.angles[k - 3], rates[k - 3]) = (u, v),
        }
    }
    if let Some(r) = rao {
        let (u, v) = r.dofs_at(t);
        m.displacement += riser::math::V3::new(u[0], u[1], u[2]);
        m.velocity += riser::math::V3::new(v[0], v[1], v[2]);
        for k in 0..3 {
            m.angles[k] += u[3 + k];
            rates[k] += v[3 + k];
        }
    }
    m.body_rates = order.body_rates(m.angles, rates);
    m
}

fn run(scene: &str, set: &[String], args: RunArgs) -> Result<(), String> {
    use riser::model::Outputs;
    use riser::sim::Simulation;
    let RunArgs {
        motions,
        raos,
        heave_until,
        ramp,
        duration,
        window,
        shape_times,
        max_tangent_age,
        json,
        out,
        fatigue: fatigue_asked,
        fatigue_series,
        estimate_error,
    } = args;
    check_run_times(&motions, ramp, heave_until, duration, window)?;
    let mut scene = load(scene, set).map_err(|e| e.to_string())?;
    if let Some(path) = raos {
        scene.vessel = Some(riser::scene::raos::VesselSpec { raos: Some(path) });
        scene.validate().map_err(|e| e.to_string())?;
    }
    // `--ramp 0` is the paper's abrupt start: the current too, unless the
    // scene or --set give its ramp (theory §5.11)
    if ramp == Some(0.0) && scene.current.ramp.is_none() {
        scene.current.ramp = Some(0.0);
    }
    let period = motions.all().into_iter().flatten().map(|m| m.1).fold(0.0, f64::max);
    let ramp = ramp.unwrap_or(period);
    // each motion a ramped sine about its axis (heave, surge, sway of the
    // reference point; roll, pitch, yaw), summed; the hang-off follows the
    // vessel at its offset (theory §14)
    let axes = harmonic_axes(&motions, heave_until, ramp);
    let vessel = riser::sim::vessel::Vessel::of_scene(&scene);
    // the vessel on its RAOs in the sea's own components (theory §14.5)
    let sea0 = riser::loads::waves::sea_of(&scene, 0.0).map_err(|e| e.to_string())?;
    let rao = riser::sim::vessel::rao_motion(&scene, sea0.as_ref())?;
    let mut rao_warnings = Vec::new();
    if scene.vessel.as_ref().is_some_and(|v| v.raos.is_some()) && sea0.is_none() {
        rao_warnings.push(
            "vessel.raos given, but the scene has no waves: the vessel does not move on its RAOs in still water"
                .to_string(),
        );
    }
    let vessel_motion = |t: f64| vessel_motion_at(&axes, rao.as_ref(), vessel.order, t);
    let motion_fn = |t: f64| vessel.hang_off(&vessel_motion(t));
    // the steady window waits for the slower of the motion and the sea
    let sea = riser::loads::waves::ramp_and_period(&scene).map_err(|e| e.to_string())?;
    let settled =
        [(period > 0.0).then_some(ramp + period), sea.map(|(r, p)| r + p)].into_iter().flatten().reduce(f64::max);
    // the current's growth (none without a current or with it in the statics)
    let current_grown = riser::loads::current_ramp(&scene).duration;
    let ((w0, w1), short) = steady_window(window, settled, current_grown, duration);
    let slowest = [(period > 0.0).then_some(period), sea.map(|(_, p)| p)].into_iter().flatten().reduce(f64::max);
    // this run as its pilots repeat it: `accuracy` measures the numerics on
    // it (§16.12), --estimate-error the numerics run (§16.11)
    let pilot_spec = riser::sim::error_estimate::RunSpec {
        motion: &motion_fn,
        window: (w0, w1),
        period: slowest,
        irregular: riser::loads::waves::irregular(&scene),
        max_tangent_age,
        fatigue: fatigue_asked.clone(),
    };
    let (scene, choice) = choose_numerics(scene, set, Some(&pilot_spec))?;
    if let Some(Some(q)) = estimate_error
        && !q.applies(&scene, fatigue_asked.is_some())
    {
        use riser::sim::error_estimate::Quantity;
        return Err(format!(
            "--error-quantity {}: this run has none ({})",
            q.name(),
            match q {
                Quantity::StressRange => "no stresses: no wall and not a homogeneous tube",
                Quantity::FatigueDamage => "give --fatigue CURVE, on a line with stresses",
                _ => "no seabed, no touchdown",
            }
        ));
    }
    // refused before the statics: a duration of more steps than a call may take
    riser::sim::internal_steps(duration, scene.analysis.time_step).map_err(|m| format!("--duration {m}"))?;
    if fatigue_asked.is_some() && !riser::sim::design::Design::new(&scene).has_stresses() {
        return Err(
            "--fatigue: this line has no stresses: it has no wall (wall_thickness) and is not the homogeneous \
                    tube of its EA, EI and outer diameter (a flexible pipe, whose stresses are per layer: armour \
                    wires, pressure sheath), so there is no axial stress to count; give a steel pipe its wall \
                    (--set wall_thickness=...)"
                .to_string(),
        );
    }
    let wall0 = std::time::Instant::now();
    let mut sim = Simulation::from_scene(&scene).map_err(|e| e.to_string())?;
    sim.integrator.options_mut().max_tangent_age = max_tangent_age;
    // what timeseries.csv adds: the hang-off's displacement and the vessel's six degrees of freedom
    let motion_row = |t: f64, h: &riser::model::HangOff| {
        let m = vessel_motion(t);
        let d = m.displacement;
        [h.displacement.x, h.displacement.y, h.displacement.z, d.x, d.y, d.z, m.angles[0], m.angles[1], m.angles[2]]
    };
    sim.start(motion_fn(0.0));
    let e0 = sim.initial_energy;
    let design = riser::sim::design::Design::new(&scene);
    let (static_design, mut warnings) = design.report(&scene, &sim.integrator, &sim.state);
    warnings.extend(rao_warnings);
    warnings.extend(short);
    // a sea that repeats within the run (docs/theory.md §13)
    if let Some(sea) = sim.sea.as_ref() {
        warnings.extend(riser::loads::waves::repeat_warning(sea.components(), duration));
    }
    // a step too long for the shortest motion (the sea's: Design::report)
    let shortest = motions.all().into_iter().flatten().map(|m| m.1).filter(|p| *p > 0.0).reduce(f64::min);
    if let Some(p) = shortest {
        warnings.extend(riser::sim::design::steps_per_period_warning("the hang-off's", p, scene.analysis.time_step));
    }
    let mut stress = riser::sim::design::StressRange::default();
    let mut peaks: Option<riser::sim::design::StressPeaks> = None;
    let mut envelope = riser::sim::design::Envelope::default();
    let track_stress = design.has_stresses();
    // the static state's points: the functional load effects of DNV-OS-F201's check (§12.4)
    let functional = sim.integrator.line_points(&sim.functional_state());
    let mut shape_times = shape_times;
    if shape_times.is_empty() {
        let t0 = if period > 0.0 && duration >= period { duration - period } else { 0.0 };
        let span = duration - t0;
        shape_times = (0..8).map(|k| t0 + span * (k as f64 + 1.0) / 8.0).collect();
    }
    shape_times.sort_by(f64::total_cmp);
    let mut series: Vec<Outputs> = vec![sim.outputs()];
    let mut motion_rows = vec![motion_row(sim.state.time, &sim.state.hang_off)];
    let mut shapes: Vec<(f64, Vec<[f64; 6]>)> = Vec::new();
    let mut next_shape = 0;
    let arc = sim.integrator.node_arc_lengths();
    let record_shape = |sim: &Simulation| {
        let x = &sim.state.config.x;
        let profile = sim.integrator.node_profile(&sim.state);
        arc.iter().zip(x).zip(profile).map(|((s, p), (t, k))| [*s, p.x, p.y, p.z, t, k]).collect::<Vec<_>>()
    };
    while next_shape < shape_times.len() && shape_times[next_shape] <= 0.0 {
        shapes.push((0.0, record_shape(&sim)));
        next_shape += 1;
    }
    let in_window = |t: f64| t >= w0 - 1e-9 && t <= w1 + 1e-9;
    // the fatigue's counters and the record of one point, allocated here, not in the steps
    let dt = sim.integrator.options().time_step;
    let n_steps = riser::sim::internal_steps(duration, dt).map_err(|m| format!("--duration {m}"))?;
    let (mut fatigue, mut fatigue_record) = match fatigue_asked.clone() {
        Some(spec) => {
            let points = sim.integrator.line_points(&sim.state);
            let record = fatigue_series.map(|s| {
                let nearest =
                    (0..points.len()).min_by(|&a, &b| (points[a].s - s).abs().total_cmp(&(points[b].s - s).abs()));
                FatigueRecord { point: nearest.unwrap_or(0), rows: Vec::with_capacity(n_steps as usize + 1) }
            });
            (riser::sim::fatigue::FatigueTracker::new(spec, &design, &points), record)
        }
        None => (None, None),
    };
    let length = scene.line.length;
    let ends = |e: &mut riser::sim::design::Envelope, o: &Outputs| {
        e.add_end(o.time, o.top_tension, 0.0);
        e.add_end(o.time, o.bottom_tension, length);
    };
    if in_window(0.0) {
        let points = sim.integrator.line_points(&sim.state);
        envelope.add(0.0, &points);
        ends(&mut envelope, &series[0]);
        if track_stress {
            let top_z = sim.state.config.x[0].z;
            stress.add(&design, &points, top_z);
            peaks = design.stress_peaks_over(&points, &functional, top_z);
            fatigue_add(&mut fatigue, &mut fatigue_record, &design, &points, top_z, 0.0);
        }
    }
    let solve_start = std::time::Instant::now();
    let mut progress = Progress::new(!json);
    let mut failure = None;
    for k in 1..=n_steps {
        let target = riser::sim::internal_step_end(0.0, duration, dt, k, n_steps);
        if let Err(e) = sim.advance_to(target, &motion_fn) {
            failure = Some(e.to_string());
            break;
        }
        let o = sim.outputs();
        series.push(o);
        motion_rows.push(motion_row(sim.state.time, &sim.state.hang_off));
        if in_window(o.time) {
            let points = sim.integrator.line_points(&sim.state);
            envelope.add(o.time, &points);
            ends(&mut envelope, &o);
            if track_stress {
                let top_z = sim.state.config.x[0].z;
                stress.add(&design, &points, top_z);
                if let Some(now) = design.stress_peaks_over(&points, &functional, top_z) {
                    peaks = Some(peaks.map_or(now, |p| p.max(now)));
                }
                fatigue_add(&mut fatigue, &mut fatigue_record, &design, &points, top_z, o.time);
            }
        }
        while next_shape < shape_times.len() && shape_times[next_shape] <= sim.state.time + 0.5 * dt {
            shapes.push((sim.state.time, record_shape(&sim)));
            next_shape += 1;
        }
        progress.update(sim.state.time, duration, sim.state.steps);
    }
    progress.finish();
    let solve_wall = solve_start.elapsed().as_secs_f64();
    // the fatigue: the residues counted, the worst point and fibre, per year over the window read
    if let Some(f) = fatigue.as_mut() {
        f.finish();
    }
    let window_read = w1.min(sim.state.time) - w0;
    let fatigue_worst = fatigue.as_ref().and_then(|f| f.worst());
    let wall = wall0.elapsed().as_secs_f64();
    let [t_min, t_mean, t_max] = min_mean_max(series.iter().map(|o| (o.time, o.top_tension)));
    let steady: Vec<&Outputs> = series.iter().filter(|o| in_window(o.time)).collect();
    let over_window = |f: &dyn Fn(&Outputs) -> f64| {
        let v: Vec<(f64, f64)> = series.iter().map(|o| (o.time, f(o))).collect();
        window_min_mean_max(&v, w0, w1)
    };
    let steady_tension = over_window(&|o| o.top_tension);
    let steady_min_tension = steady.iter().map(|o| o.min_tension).fold(f64::INFINITY, f64::min);
    let whole_min_tension = series.iter().map(|o| o.min_tension).fold(f64::INFINITY, f64::min);
    let stress_range = stress.largest();
    let angle = over_window(&|o| o.hang_off_angle);
    // off the seabed: a gap in the touchdown's statistics
    let touchdown = |o: &Outputs| if o.touchdown_s < length { o.touchdown_s } else { f64::NAN };
    let td_range = steady.iter().any(|o| !touchdown(o).is_nan()).then(|| over_window(&touchdown));
    if steady_min_tension < 0.0 {
        warnings.push(format!(
            "the line goes into compression in the steady window: the smallest axial force is {:.3} kN",
            steady_min_tension / 1e3
        ));
    } else if whole_min_tension < 0.0 {
        warnings.push(format!(
            "the line goes into compression during the start ({:.3} kN), not in the steady window",
            whole_min_tension / 1e3
        ));
    }
    // the anchor lifted off its seabed: the first time, and the largest uplift (the whole run)
    let lifted = |o: &&Outputs| riser::sim::design::anchor_lifted(&scene, o);
    if let Some(first) = series.iter().find(|o| lifted(o).is_some()) {
        let largest = series.iter().filter_map(|o| lifted(&o).map(|a| (o, a))).max_by(|a, b| a.1.total_cmp(&b.1));
        warnings.extend(largest.and_then(|(o, _)| riser::sim::design::anchor_lift_warning(&scene, first.time, o)));
    }
    // the window's steadiness: a motion of one period in still water
    let periods: Vec<f64> = motions.all().into_iter().flatten().map(|m| m.1).collect();
    // (a motion that stops in the window, --heave-until, has none)
    let forcing_period = match (periods.first(), sea) {
        (Some(&p), None)
            if periods.iter().all(|q| (q - p).abs() <= 1e-9 * p) && heave_until.is_none_or(|u| u >= w1) =>
        {
            Some(p)
        }
        _ => None,
    };
    let tension: Vec<(f64, f64)> = series.iter().map(|o| (o.time, o.top_tension)).collect();
    let drift = forcing_period.and_then(|p| riser::sim::design::window_drift(&tension, (w0, w1), p));
    if let (Some(d), Some(p)) = (drift, forcing_period) {
        let limit = choice.as_ref().map_or(riser::sim::design::UNSTEADY_WINDOW, |c| c.target);
        warnings.extend(riser::sim::design::unsteady_window_warning(d, limit, (w0, w1), p));
    }
    // the energy exchanged with the line (hang-off, water, anchor, seabed) and
    // the magnitude of what E sums: the relative balance's scale, which a
    // line held still has too (docs/theory.md §5.5; riser-sweep's the same)
    let exchanged = series
        .iter()
        .map(|o| o.work_top.abs() + o.work_hydro.abs() + o.work_anchor.abs() + o.work_seabed.abs())
        .fold(0.0, f64::max);
    let held = series
        .iter()
        .map(|o| o.kinetic_energy.abs() + o.strain_energy.abs() + o.potential_energy.abs())
        .fold(0.0, f64::max);
    let balance_scale = exchanged.max(riser::sim::report::ENERGY_RESOLUTION * held);
    // over the steady window: a motion still growing (the ramps) takes a
    // growing share where the line snatches as it grows
    let times: Vec<f64> = steady.iter().map(|o| o.time).collect();
    let algorithmic: Vec<f64> = steady.iter().map(|o| o.algorithmic_dissipation).collect();
    let work: Vec<[f64; 2]> = steady.iter().map(|o| [o.work_top, o.work_hydro]).collect();
    warnings.extend(riser::sim::design::growing_dissipation_warning(&times, &algorithmic, &work));
    warn_all(&warnings);
    let balance = series.iter().map(|o| o.energy_balance_residual(e0).abs()).fold(0.0, f64::max);
    let st = &sim.state;
    let simulated = st.time;
    // the error of these numerics on this run's own motion and sea (issue 51)
    let estimate = match estimate_error {
        Some(headline) => {
            let spec = &pilot_spec;
            let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
            let e = riser::sim::error_estimate::estimate_error(&scene, spec, threads).map_err(|e| e.to_string())?;
            Some((e, headline))
        }
        None => None,
    };
    if let Some(dir) = &out {
        write_run_csv(dir, &series, &motion_rows, &shapes)
            .map_err(|e| format!("cannot write {}: {e}", dir.display()))?;
        let stress_csv = dir.join("stress_range.csv");
        match stress_range {
            Some(_) => write_stress_csv(&stress_csv, &stress.rows())
                .map_err(|e| format!("cannot write {}: {e}", stress_csv.display()))?,
            // not last run's table of another scene
            None => _ = std::fs::remove_file(&stress_csv),
        }
        let fatigue_csv = dir.join("fatigue.csv");
        match &fatigue {
            Some(f) => write_fatigue_csv(&fatigue_csv, f, window_read)
                .map_err(|e| format!("cannot write {}: {e}", fatigue_csv.display()))?,
            None => _ = std::fs::remove_file(&fatigue_csv),
        }
        let series_csv = dir.join("fatigue_series.csv");
        match &fatigue_record {
            Some(r) => write_fatigue_series(&series_csv, r)
                .map_err(|e| format!("cannot write {}: {e}", series_csv.display()))?,
            None => _ = std::fs::remove_file(&series_csv),
        }
        let td: Vec<f64> = series.iter().map(|o| o.touchdown_s).collect();
        let bed = scene.seabed.as_ref().map(|b| b.height_at(scene.anchor.x, scene.anchor.y));
        let path = dir.join("touchdown.svg");
        match touchdown::svg(&shapes, &td, scene.line.length, bed) {
            Some(plot) => std::fs::write(&path, plot).map_err(|e| format!("cannot write {}: {e}", path.display()))?,
            // not last run's plot of another scene
            None => _ = std::fs::remove_file(&path),
        }
    }
    let finite = |v: f64| if v.is_finite() { Some(v) } else { None };
    if json {
        let mut statics = design_json(&static_design);
        if let Some(o) = statics.as_object_mut() {
            o.insert("top_tension".into(), sim.statics.top_tension.into());
        }
        let v = serde_json::json!({
            "scene": scene.name,
            "n_elements": scene.analysis.n_elements,
            "time_step": dt,
            "newton_tolerance": scene.analysis.newton_tolerance,
            "accuracy": choice_json(&choice),
            "duration": simulated,
            "ramp": ramp,
            "completed": failure.is_none(),
            "error": failure,
            "static_top_tension": sim.statics.top_tension,
            "top_tension": {"min": t_min, "mean": t_mean, "max": t_max},
            "min_tension": whole_min_tension,
            "steady": {
                "window": [w0, w1],
                "top_tension": steady_tension.map(finite),
                "min_tension": finite(steady_min_tension),
                "stress_range": stress_range.map(|r| r.0),
                "stress_range_s": stress_range.map(|r| r.1),
                "max_von_mises": peaks.map(|p| p.von_mises.0),
                "max_von_mises_s": peaks.map(|p| p.von_mises.1),
                "max_utilisation": utilisation_json(peaks.and_then(|p| p.utilisation)),
                "utilisations": utilisations_json(peaks.and_then(|p| p.api), peaks.and_then(|p| p.lrfd)),
                "not_reported": not_reported_json(peaks.and_then(|p| p.lrfd)),
                "fatigue": fatigue.as_ref().map(|f| fatigue_json(f, fatigue_worst, window_read)),
                "min_tension_s": envelope.is_set().then_some(envelope.min_tension.1),
                "max_tension": envelope.is_set().then_some(envelope.max_tension.0),
                "max_tension_s": envelope.is_set().then_some(envelope.max_tension.1),
                "max_curvature": envelope.is_set().then_some(envelope.max_curvature.0),
                "max_curvature_s": envelope.is_set().then_some(envelope.max_curvature.1),
                "hang_off_angle": angle.map(finite),
                "touchdown_s": td_range.map(|t| t.map(finite)),
                "drift": drift,
                "warnings": warnings,
            },
            "statics": statics,
            "energy_balance_residual": balance,
            "energy_exchanged": exchanged,
            "dissipated_energy": series.last().map(|o| o.dissipated_energy).unwrap_or(0.0),
            "structural_damping": scene.analysis.structural_damping,
            "rho_infinity": scene.analysis.rho_infinity,
            "algorithmic_dissipation": series.last().map(|o| o.algorithmic_dissipation).unwrap_or(0.0),
            "energy_balance_relative": if balance_scale > 0.0 { balance / balance_scale } else { 0.0 },
            "steps": st.steps,
            "newton_iterations": st.newton_iterations,
            "iterations_per_step": st.newton_iterations as f64 / (st.steps.max(1)) as f64,
            "retries": st.retries,
            "wall_time": wall,
            "solve_wall_time": solve_wall,
            "real_time_factor": simulated / solve_wall.max(1e-12),
        });
        let mut v = v;
        if let (Some((e, headline)), Some(o)) = (&estimate, v.as_object_mut()) {
            o.insert("error_estimate".into(), error_estimate_json(e, *headline, &[]));
        }
        outln!("{v}");
    } else {
        let kn = |v: f64| v / 1e3;
        let start = match ramp {
            0.0 => ", abrupt start (the paper's: --ramp 0)".to_string(),
            r => format!(", ramped over {r} s"),
        };
        outln!(
            "riser run: scene '{}' ({} elements, time step {} s), {}{}{}",
            scene.name,
            scene.analysis.n_elements,
            dt,
            match (&rao, motions.all().iter().any(Option::is_some)) {
                (Some(_), false) => "the vessel on its RAOs".to_string(),
                _ => motions.describe(),
            },
            heave_until.map(|u| format!(" until {u} s")).unwrap_or_default(),
            if period > 0.0 { start } else { String::new() }
        );
        choice_text(&choice);
        if let Some(r) = &rao {
            outln!(
                "  the vessel moves on its RAOs ({}) in the sea's own components, the waves' ramp included{}",
                r.dofs.join(", "),
                if motions.all().iter().any(Option::is_some) { ", plus the motions above" } else { "" }
            );
        }
        if !riser::loads::current(&scene).is_none() && !scene.analysis.static_current {
            let grows = match riser::loads::current_ramp(&scene).duration {
                0.0 => "acts in full from t = 0 (current_ramp = 0, the paper's)".to_string(),
                r => format!("grows over its first {r} s (current_ramp)"),
            };
            outln!(
                "  the current {grows}; the static state is without it (static_current = false): the mean tension \
                 moves by the current's drag"
            );
        }
        outln!("  static top tension   {:10.3} kN", kn(sim.statics.top_tension));
        let d = &static_design;
        let touchdown = d.touchdown_s.map(|s| format!(", touchdown at S = {s:.1} m")).unwrap_or_default();
        outln!(
            "  static state: hang-off angle {:.2} deg{touchdown}, min bend radius {:.2} m at S = {:.1} m",
            d.hang_off_angle,
            d.min_bend_radius,
            d.max_curvature_s
        );
        outln!("  steady window {w0} to {w1} s:");
        outln!(
            "    top tension min/mean/max {:.3} / {:.3} / {:.3} kN",
            kn(steady_tension[0]),
            kn(steady_tension[1]),
            kn(steady_tension[2])
        );
        if let Some(d) = drift {
            outln!(
                "    steadiness               first and last periods' top tension extremes {:.4} % apart",
                100.0 * d
            );
        }
        outln!("    hang-off angle           {:.2} / {:.2} / {:.2} deg", angle[0], angle[1], angle[2]);
        if envelope.is_set() {
            let e = &envelope;
            outln!(
                "    axial force along the line {:.3} kN (S = {:.1} m) to {:.3} kN (S = {:.1} m)",
                kn(e.min_tension.0),
                e.min_tension.1,
                kn(e.max_tension.0),
                e.max_tension.1
            );
            outln!(
                "    min bend radius          {:.2} m at S = {:.1} m (t = {:.1} s)",
                1.0 / e.max_curvature.0,
                e.max_curvature.1,
                e.max_curvature.2
            );
        }
        if let Some(td) = td_range {
            outln!("    touchdown S min/mean/max {:.2} / {:.2} / {:.2} m", td[0], td[1], td[2]);
        }
        match stress_range {
            Some((r, s)) => outln!("    stress range             {:.3} MPa at S = {s:.1} m (outer fibre)", r / 1e6),
            None => outln!("    stress range             n/a (no wall and not a homogeneous tube: a flexible pipe)"),
        }
        if let Some(p) = peaks {
            outln!("    max von Mises            {:.3} MPa at S = {:.1} m", p.von_mises.0 / 1e6, p.von_mises.1);
            if let Some(u) = p.utilisation {
                outln!("    max utilisation          {:.3} at S = {:.1} m ({})", u.value, u.s, u.check);
            }
            lrfd_text("      check                  ", p.api, p.lrfd);
        }
        if let (Some(f), Some(w)) = (&fatigue, fatigue_worst) {
            let spec = f.spec();
            let per_year = riser::sim::fatigue::damage_per_year(w.damage, window_read);
            outln!(
                "    fatigue ({}, SCF {}, DFF {}) damage {:.3e} over the window, {} a year, life {} years at S = \
                 {:.1} m, fibre {} ({} deg); its largest range {:.3} MPa",
                spec.curve.name,
                spec.scf,
                spec.dff,
                w.damage,
                readable(per_year),
                readable(riser::sim::fatigue::life_years(per_year, spec.dff)),
                w.s,
                w.fibre,
                w.fibre * 360 / riser::sim::design::FIBRES,
                w.range / 1e6
            );
        }
        outln!(
            "  whole run, with the start: top tension min/mean/max {:.3} / {:.3} / {:.3} kN, min axial force {:.3} kN",
            kn(t_min),
            kn(t_mean),
            kn(t_max),
            kn(whole_min_tension)
        );
        outln!("  energy balance       {:.3e} J residual of {:.3e} J exchanged", balance, exchanged);
        if let Some((e, headline)) = &estimate {
            error_estimate_text(e, *headline, &[]);
        }
        outln!(
            "  {} steps, {:.2} Newton iterations/step, {} split steps; {:.2} s wall, {:.0}x real time",
            st.steps,
            st.newton_iterations as f64 / (st.steps.max(1)) as f64,
            st.retries,
            solve_wall,
            simulated / solve_wall.max(1e-12)
        );
        if !warnings.is_empty() {
            outln!("  {} warning(s) (on stderr)", warnings.len());
        }
        if let Some(dir) = &out {
            let stress = match (stress_range.is_some(), fatigue.is_some(), fatigue_record.is_some()) {
                (true, true, true) => ", stress_range.csv, fatigue.csv, fatigue_series.csv",
                (true, true, false) => ", stress_range.csv, fatigue.csv",
                (true, false, _) => ", stress_range.csv",
                _ => "",
            };
            let plot = if dir.join("touchdown.svg").exists() { " and touchdown.svg" } else { "" };
            outln!("  wrote {}/timeseries.csv, shapes.csv{stress}{plot}", dir.display());
        }
    }
    match failure {
        Some(msg) => Err(format!("run stopped at t = {simulated:.6} s: {msg}")),
        None => Ok(()),
    }
}

/// A number to four significant digits, in exponent form outside 1e-3 to 1e5.
fn readable(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-3..1e5).contains(&v.abs()) {
        riser::scene::ranges::number(format!("{v:.4e}").parse().unwrap_or(v))
    } else {
        format!("{v:.3e}")
    }
}

/// `steady.fatigue` of `riser run --json` (docs/theory.md §12.5).
fn fatigue_json(
    f: &riser::sim::fatigue::FatigueTracker,
    worst: Option<riser::sim::fatigue::FatigueWorst>,
    window: f64,
) -> serde_json::Value {
    use riser::sim::fatigue::{REFERENCE_THICKNESS, damage_per_year, life_years};
    let spec = f.spec();
    let c = &spec.curve;
    let per_year = worst.map(|w| damage_per_year(w.damage, window));
    serde_json::json!({
        "curve": {
            "name": c.name, "m1": c.m1, "log_a1": c.log_a1, "m2": c.m2, "log_a2": c.log_a2,
            "n_switch": c.n_switch, "k": c.k, "t_ref": REFERENCE_THICKNESS,
        },
        "scf": spec.scf,
        "dff": spec.dff,
        "window_length": window,
        "worst_s": worst.map(|w| w.s),
        "worst_fibre": worst.map(|w| w.fibre),
        "worst_fibre_angle": worst.map(|w| 360.0 * w.fibre as f64 / riser::sim::design::FIBRES as f64),
        "worst_range": worst.map(|w| w.range),
        "damage": worst.map(|w| w.damage),
        "damage_per_year": per_year,
        "life_years": per_year.map(|d| life_years(d, spec.dff)).filter(|l| l.is_finite()),
    })
}

/// fatigue.csv: per point of the line and fibre, the damage over the
/// steady window, the life in years (with the DFF; `inf` without damage),
/// the damage per year and the largest rainflow range, Pa.
fn write_fatigue_csv(path: &Path, f: &riser::sim::fatigue::FatigueTracker, window: f64) -> std::io::Result<()> {
    use riser::sim::fatigue::{damage_per_year, life_years};
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "S,fibre,damage,life,damage_per_year,max_range")?;
    for (s, fibre, damage, range) in f.rows() {
        let per_year = damage_per_year(damage, window);
        let life = life_years(per_year, f.spec().dff);
        writeln!(out, "{s},{fibre},{damage:e},{life:e},{per_year:e},{range}")?;
    }
    out.flush()
}

/// fatigue_series.csv: t and the axial stress at the 8 fibres of one point, Pa.
fn write_fatigue_series(path: &Path, r: &FatigueRecord) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(out, "t")?;
    for f in 0..riser::sim::design::FIBRES {
        write!(out, ",fibre{f}")?;
    }
    writeln!(out)?;
    for (t, sigma) in &r.rows {
        write!(out, "{t}")?;
        for v in sigma {
            write!(out, ",{v}")?;
        }
        writeln!(out)?;
    }
    out.flush()
}

/// stress_range.csv: per point of the line, the outer-fibre stress's extremes
/// over its 8 fibres and the largest range of one fibre over the steady window.
fn write_stress_csv(path: &Path, rows: &[[f64; 4]]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "S,stress_min,stress_max,stress_range")?;
    for r in rows {
        writeln!(f, "{},{},{},{}", r[0], r[1], r[2], r[3])?;
    }
    f.flush()
}

/// The columns timeseries.csv adds after the outputs: the hang-off's
/// displacement from its mean position (m) and the vessel's motion that
/// moves it (the reference point's surge, sway, heave, m; roll, pitch, yaw, rad).
const MOTION_COLUMNS: [&str; 9] =
    ["hang_off_x", "hang_off_y", "hang_off_z", "surge", "sway", "heave", "roll", "pitch", "yaw"];

fn write_run_csv(
    dir: &Path,
    series: &[riser::model::Outputs],
    motion: &[[f64; 9]],
    shapes: &[(f64, Vec<[f64; 6]>)],
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join("timeseries.csv"))?);
    write!(f, "t")?;
    for n in riser::model::Outputs::NAMES.iter().chain(&MOTION_COLUMNS) {
        write!(f, ",{n}")?;
    }
    writeln!(f)?;
    for (o, m) in series.iter().zip(motion) {
        write!(f, "{}", o.time)?;
        for v in o.values().iter().chain(m) {
            write!(f, ",{v}")?;
        }
        writeln!(f)?;
    }
    f.flush()?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join("shapes.csv"))?);
    writeln!(f, "t,S,x,y,z,tension,curvature")?;
    for (t, rows) in shapes {
        for r in rows {
            writeln!(f, "{t},{},{},{},{},{},{}", r[0], r[1], r[2], r[3], r[4], r[5])?;
        }
    }
    f.flush()
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Statics { scene, set, json, out, pose } => {
            if riser::scene::system::is_system_source(&scene) {
                system::statics(&scene, &set, json, out.is_some(), pose.as_deref())
            } else if pose.is_some() {
                Err("--pose: only for a system scene in this version (docs/guide/systems.md)".to_string())
            } else {
                statics(&scene, &set, json, out)
            }
        }
        Command::Run(r) => {
            let RunCli {
                scene,
                set,
                heave,
                surge,
                sway,
                roll,
                pitch,
                yaw,
                raos,
                heave_until,
                ramp,
                duration,
                window,
                shape_times,
                max_tangent_age,
                threads,
                json,
                out,
                fatigue,
                scf,
                dff,
                fatigue_series,
                estimate_error,
                error_quantity,
            } = *r;
            let motions = Motions { heave, surge, sway, roll, pitch, yaw };
            let is_system = riser::scene::system::is_system_source(&scene);
            let quantity = match error_quantity.as_str() {
                "all" => Ok(None),
                name => riser::sim::error_estimate::Quantity::parse(name).map(Some),
            };
            match (fatigue_spec(fatigue, scf, dff), quantity) {
                (_, Err(m)) => Err(format!("--error-quantity: {m}")),
                (Ok(_), _) if threads.is_some() && !is_system => {
                    Err("--threads: only for a system of lines ([[line]]); a single line runs on one".to_string())
                }
                (Ok(fatigue), Ok(quantity)) => {
                    let args = RunArgs {
                        motions,
                        raos,
                        heave_until,
                        ramp,
                        duration,
                        window,
                        shape_times,
                        max_tangent_age,
                        json,
                        out,
                        fatigue,
                        fatigue_series,
                        estimate_error: estimate_error.then_some(quantity),
                    };
                    if is_system { system_run::run(&scene, &set, args, threads) } else { run(&scene, &set, args) }
                }
                (Err(m), _) => Err(m),
            }
        }
        Command::Rainflow { file } => rainflow_command(&file),
        Command::Modes(args) => modes::modes(args),
        Command::Waves(args) => waves::waves(args),
        Command::ModelDescription { scene: None } => {
            out!("{}", riser::fmi::vars::MODEL_DESCRIPTION);
            Ok(())
        }
        Command::ModelDescription { scene: Some(path) } => system_run::model_description(&path),
        Command::Params { scene, json } => params(&scene, json),
        Command::Scene { scene, set } if riser::scene::system::is_system_source(&scene) => {
            system_run::print_system(&scene, &set)
        }
        Command::Scene { scene, set } => load(&scene, &set).map(print_scene).map_err(|e| e.to_string()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("riser: error: {msg}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::min_mean_max;

    /// The window's mean is the time mean: on y = a + b cos(ω t) sampled over
    /// two whole periods it is a (the trapezoid rule is exact for a periodic
    /// trigonometric polynomial over its period, to rounding), where the
    /// samples' arithmetic mean with both ends is off by (y_end − a) Δt / W.
    #[test]
    fn the_mean_is_the_time_mean_not_the_samples() {
        let (a, b, period, dt): (f64, f64, f64, f64) = (140e3, 4e3, 20.0, 0.1);
        let n = (2.0 * period / dt).round() as usize;
        let w = 2.0 * std::f64::consts::PI / period;
        let samples: Vec<(f64, f64)> = (0..=n).map(|k| k as f64 * dt).map(|t| (t, a + b * (w * t).cos())).collect();
        let [min, mean, max] = min_mean_max(samples.iter().copied());
        assert!((mean - a).abs() <= 1e-9 * a, "time mean {mean} against {a}");
        assert_eq!((min, max), (a - b, a + b));
        let arithmetic = samples.iter().map(|s| s.1).sum::<f64>() / samples.len() as f64;
        // n + 1 samples, n of them a whole number of periods (sum n a), the
        // last one more at the peak: a + b / (n + 1) ≈ a + b Δt / W
        let bias = b / (n + 1) as f64;
        assert!(((arithmetic - a) - bias).abs() <= 1e-6 * bias, "{arithmetic}: the bias this replaces");
    }

    /// The window's mean is over exactly [t0, t1]: on y = a + b cos(ω t)
    /// sampled at a step that falls on neither end of a two-period window,
    /// the interpolant's mean is a to O(Δt²) (the trapezoid rule's), where
    /// the samples inside alone, short by up to a step at each end, are off
    /// by O(b Δt / W).
    #[test]
    fn the_window_s_mean_is_over_exactly_the_window() {
        use super::window_min_mean_max;
        let (a, b, period, dt): (f64, f64, f64, f64) = (140e3, 4e3, 20.0, 0.03);
        let w = 2.0 * std::f64::consts::PI / period;
        let v: Vec<(f64, f64)> = (0..=3000).map(|k| k as f64 * dt).map(|t| (t, a + b * (w * t + 0.7).sin())).collect();
        let (t0, t1) = (20.0, 60.0);
        let [_, mean, _] = window_min_mean_max(&v, t0, t1);
        // the trapezoid rule's error on a sine: b (ω Δt)²/12 at most
        let bound = b * (w * dt).powi(2) / 12.0;
        assert!((mean - a).abs() <= bound, "window mean {mean} against {a} (bound {bound:.2e})");
        let inside: Vec<(f64, f64)> = v.iter().copied().filter(|(t, _)| *t >= t0 && *t <= t1).collect();
        let [_, short, _] = min_mean_max(inside.iter().copied());
        assert!((short - a).abs() > 20.0 * bound, "the window short by a step: {short}");
        // where the samples fall on both ends, the same as before
        let on: Vec<(f64, f64)> = (0..=400).map(|k| k as f64 * 0.1).map(|t| (t, a + b * (w * t).cos())).collect();
        let inside: Vec<(f64, f64)> = on.iter().copied().filter(|(t, _)| *t >= 10.0 - 1e-9).collect();
        let [_, m0, _] = window_min_mean_max(&on, 10.0, 40.0);
        let [_, m1, _] = min_mean_max(inside.iter().copied());
        assert!((m0 - m1).abs() <= 1e-9 * a, "{m0} against {m1}");
    }

    /// A NaN is a gap: the intervals next to it do not count. A linear ramp
    /// with a gap in the middle: each piece's time mean, weighted by its span.
    #[test]
    fn a_gap_leaves_its_intervals_out() {
        let nan = f64::NAN;
        let s = [(0.0, 0.0), (1.0, 1.0), (2.0, nan), (3.0, 3.0), (4.0, 4.0), (5.0, 5.0)];
        let [min, mean, max] = min_mean_max(s.iter().copied());
        // [0, 1]: mean 0.5, span 1; [3, 5]: mean 4, span 2
        assert_eq!((min, max), (0.0, 5.0));
        assert!((mean - (0.5 + 4.0 * 2.0) / 3.0).abs() < 1e-15, "{mean}");
        // one sample: itself; none: NaN
        assert_eq!(min_mean_max([(1.0, 7.0)].into_iter()), [7.0; 3]);
        assert!(min_mean_max([(1.0, nan)].into_iter()).iter().all(|x| x.is_nan()));
    }
}
