//! `riser waves`: a scene's sea as riser realises it (docs/theory.md §13) —
//! the components, Hs and Tp recovered from them, and with `--out` the
//! elevation at the phase origin, its spectrum and a plot (waves.svg, written
//! by hand as modes.svg), plus the components as a table another tool (or
//! `kind = "table"`) reads.

use crate::svg::Frame;
use riser::loads::waves::spectra::{self, Discretisation, Spacing, Spectrum};
use riser::loads::waves::{Sea, sea_of};
use riser::scene::Scene;
use riser::scene::waves::{SpacingSpec, WaveKind, WavesSpec};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The sea of a scene: components, Hs and Tp, and the elevation and its spectrum.
#[derive(clap::Args)]
pub struct WavesArgs {
    /// Built-in scene or path to a scene file (TOML) with a [waves] block (or --set wave_kind=...).
    scene: String,
    /// Override a parameter by name, e.g. --set wave_hs=6 (see `riser params`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Length of the elevation record of --out, s (default 3 hours for a spectrum or a table, 20 periods for
    /// a regular wave).
    #[arg(long, value_name = "D")]
    duration: Option<f64>,
    /// Print one JSON object instead of the text summary.
    #[arg(long)]
    json: bool,
    /// Write elevation.csv, spectrum.csv, components.csv and waves.svg into this directory (and
    /// vessel_motion.csv with the vessel's RAOs).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// The vessel's RAO table (overrides the scene's [vessel] raos): --out writes
    /// vessel_motion.csv, the vessel's motion in this sea as `riser run` drives it.
    #[arg(long, value_name = "FILE")]
    raos: Option<String>,
    /// The sampling step of the records of --out, s (default a tenth of the shortest
    /// component's period, within 0.01 to 0.5 s).
    #[arg(long, value_name = "DT")]
    step: Option<f64>,
}

/// A number for the CSV files and the JSON: exact (shortest round trip).
fn num(v: f64) -> String {
    format!("{v}")
}

/// The spectrum a spectral kind describes (None for airy and table).
fn target_spectrum(w: &WavesSpec) -> Option<Spectrum> {
    let (hs, tp) = (w.hs?, w.tp?);
    match w.kind {
        WaveKind::Jonswap => Some(Spectrum::Jonswap { hs, tp, gamma: w.gamma_or_default() }),
        WaveKind::PiersonMoskowitz => Some(Spectrum::PiersonMoskowitz { hs, tp }),
        _ => None,
    }
}

/// The frequency band of each component, Hz: the spectra's equal bins;
/// otherwise halfway to the neighbouring frequencies (a single component:
/// ± half its frequency).
fn bins(w: &WavesSpec, sea: &Sea) -> Vec<(f64, f64)> {
    let c = sea.components();
    if matches!(w.kind, WaveKind::Jonswap | WaveKind::PiersonMoskowitz) {
        let (f_min, f_max) = w.frequency_range();
        if w.spacing == Some(SpacingSpec::Energy)
            && let Some(spectrum) = target_spectrum(w)
        {
            // the bins of (13.11a), as the realisation cut them
            let d = Discretisation {
                f_min,
                f_max,
                components: c.len(),
                seed: 0,
                random_amplitudes: false,
                spacing: Spacing::Energy,
            };
            let (edges, _) = spectra::bins(&spectrum, &d);
            return edges.windows(2).map(|e| (e[0], e[1])).collect();
        }
        let df = (f_max - f_min) / c.len() as f64;
        return (0..c.len()).map(|i| (f_min + i as f64 * df, f_min + (i + 1) as f64 * df)).collect();
    }
    let mut f: Vec<f64> = c.iter().map(|c| c.frequency).collect();
    f.sort_by(f64::total_cmp);
    f.dedup();
    c.iter()
        .map(|c| {
            let i = f.iter().position(|x| *x == c.frequency).unwrap_or(0);
            let lo = if i > 0 { 0.5 * (f[i - 1] + f[i]) } else { f[i] - 0.5 * f.get(1).map_or(f[i], |n| n - f[i]) };
            let hi = if i + 1 < f.len() {
                0.5 * (f[i] + f[i + 1])
            } else {
                f[i] + 0.5 * if i > 0 { f[i] - f[i - 1] } else { f[i] }
            };
            (lo.max(0.0), hi)
        })
        .collect()
}

/// The elevation record at the phase origin: times, η and the ramped η.
struct Record {
    t: Vec<f64>,
    eta: Vec<f64>,
    ramped: Vec<f64>,
    dt: f64,
}

/// The most samples an elevation record holds.
const MAX_SAMPLES: f64 = 2e6;
/// The most (DFT lines × samples) the record's spectrum may cost.
const MAX_DFT_WORK: f64 = 4e9;

/// The sampling step of the record: a tenth of the shortest component's
/// period, within [0.01, 0.5] s.
fn sample_step(sea: &Sea) -> f64 {
    let f_max = sea.components().iter().map(|c| c.frequency).fold(0.0, f64::max);
    (0.1 / f_max).clamp(0.01, 0.5)
}

fn record(sea: &Sea, duration: f64, dt: f64) -> Record {
    let n = (duration / dt).round() as usize;
    let [x0, y0] = sea.settings().origin;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
    let eta: Vec<f64> = t.iter().map(|&t| sea.elevation(x0, y0, t)).collect();
    let ramped = t.iter().zip(&eta).map(|(&t, &e)| sea.settings().ramp.at(t).0 * e).collect();
    Record { t, eta, ramped, dt }
}

/// The record's one-sided spectral density averaged over each band, m²/Hz:
/// its periodogram P_k = 2|X_k|²/N² at f_k = k/(N dt) (the power of a
/// sinusoid in line k is a²/2) summed over the lines in the band, divided
/// by the band's width. The DFT lines are evaluated directly (a rotating
/// phasor per line), only where a band needs them.
fn record_spectrum(r: &Record, bands: &[(f64, f64)]) -> Vec<f64> {
    let n = r.eta.len();
    if n < 2 {
        return vec![f64::NAN; bands.len()];
    }
    let span = n as f64 * r.dt;
    let mean = r.eta.iter().sum::<f64>() / n as f64;
    let lo = bands.iter().map(|b| b.0).fold(f64::INFINITY, f64::min);
    let hi = bands.iter().map(|b| b.1).fold(0.0, f64::max);
    let k0 = ((lo * span).ceil() as usize).max(1);
    let k1 = ((hi * span).floor() as usize).min(n / 2);
    if (k1.saturating_sub(k0) + 1) as f64 * n as f64 > MAX_DFT_WORK {
        // too long a record over too wide a band for a direct DFT: left out
        return vec![f64::NAN; bands.len()];
    }
    let mut power = Vec::with_capacity(k1.saturating_sub(k0) + 1);
    for k in k0..=k1 {
        let w = -2.0 * std::f64::consts::PI * k as f64 / n as f64;
        let (sw, cw) = w.sin_cos();
        let (mut pr, mut pi) = (1.0f64, 0.0f64);
        let (mut xr, mut xi) = (0.0, 0.0);
        for (j, e) in r.eta.iter().enumerate() {
            if j % 1024 == 0 {
                // restart the phasor exactly, so that round-off cannot accumulate
                let (s, c) = (w * j as f64).sin_cos();
                (pr, pi) = (c, s);
            }
            let v = e - mean;
            xr += v * pr;
            xi += v * pi;
            (pr, pi) = (pr * cw - pi * sw, pr * sw + pi * cw);
        }
        power.push((k as f64 / span, 2.0 * (xr * xr + xi * xi) / (n as f64 * n as f64)));
    }
    bands
        .iter()
        .map(|&(a, b)| power.iter().filter(|(f, _)| *f >= a && *f < b).map(|(_, p)| p).sum::<f64>() / (b - a))
        .collect()
}

pub fn waves(args: WavesArgs) -> Result<(), String> {
    let WavesArgs { scene, set, duration, json, out, raos, step } = args;
    let mut scene = super::load(&scene, &set).map_err(|e| e.to_string())?;
    if let Some(path) = raos {
        scene.vessel = Some(riser::scene::raos::VesselSpec { raos: Some(path) });
        scene.validate().map_err(|e| e.to_string())?;
    }
    let Some(w) = scene.waves.clone().filter(|w| w.kind != WaveKind::None) else {
        return Err(format!(
            "scene '{}' has no waves (no [waves] block, or kind none): give one, or --set wave_kind=airy \
             --set wave_height=... --set wave_period=...",
            scene.name
        ));
    };
    let sea = sea_of(&scene, 0.0).map_err(|e| e.to_string())?.expect("a kind other than none makes a sea");
    let mut warnings = riser::loads::waves::warnings(&scene);
    // a record asked for (--duration, --out) longer than the sea's repeat period
    let asked = duration.is_some() || out.is_some();
    let duration = duration.unwrap_or(match w.kind {
        WaveKind::Airy => 20.0 * w.period.unwrap_or(10.0),
        _ => 10_800.0,
    });
    if asked {
        warnings.extend(riser::loads::waves::repeat_warning(sea.components(), duration));
    }
    for m in &warnings {
        eprintln!("riser: warning: {m}");
    }
    if let Some(dt) = step
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(format!("--step must be a positive number of seconds, got {dt}"));
    }
    let dt = step.unwrap_or_else(|| sample_step(&sea));
    let longest = MAX_SAMPLES * dt;
    if !(duration.is_finite() && duration > 0.0 && duration <= longest) {
        return Err(format!(
            "--duration must be positive and at most {longest} s ({MAX_SAMPLES:e} samples of {dt} s), got {duration}"
        ));
    }
    let rao = riser::sim::vessel::rao_motion(&scene, Some(&sea))?;
    let written = match &out {
        Some(dir) => write_outputs(dir, &scene, &w, &sea, rao.as_ref(), duration, dt)
            .map_err(|e| format!("cannot write {}: {e}", dir.display()))?,
        None => Vec::new(),
    };
    if json {
        outln!("{}", to_json(&scene, &w, &sea, &warnings, &written, duration));
    } else {
        print_text(&scene, &w, &sea, &written, duration);
    }
    Ok(())
}

fn depth_text(scene: &Scene, w: &WavesSpec) -> String {
    match (riser::loads::waves::depth_of(scene), w.depth.filter(|d| *d > 0.0)) {
        (None, _) => "deep water".into(),
        (Some(d), Some(_)) => format!("depth {d} m (waves.depth)"),
        (Some(d), None) => format!("depth {d} m (the seabed's under the phase origin)"),
    }
}

/// The period after which equal bins repeat the record, s (spectra only).
fn repeat_period(w: &WavesSpec, sea: &Sea) -> Option<f64> {
    matches!(w.kind, WaveKind::Jonswap | WaveKind::PiersonMoskowitz)
        .then(|| riser::loads::waves::repeat_period(sea.components()))
        .flatten()
}

fn print_text(scene: &Scene, w: &WavesSpec, sea: &Sea, written: &[PathBuf], duration: f64) {
    let s = sea.settings();
    let what = match w.kind {
        WaveKind::Airy => format!("regular wave H {} m, T {} s", w.height.unwrap_or(0.0), w.period.unwrap_or(0.0)),
        WaveKind::Jonswap => format!(
            "JONSWAP Hs {} m, Tp {} s, gamma {:.4}{}, {} components, seed {}",
            w.hs.unwrap_or(0.0),
            w.tp.unwrap_or(0.0),
            w.gamma_or_default(),
            if w.gamma.is_none() { " (from Tp/sqrt(Hs))" } else { "" },
            sea.components().len(),
            w.seed.unwrap_or(0)
        ),
        WaveKind::PiersonMoskowitz => format!(
            "Pierson-Moskowitz Hs {} m, Tp {} s, {} components, seed {}",
            w.hs.unwrap_or(0.0),
            w.tp.unwrap_or(0.0),
            sea.components().len(),
            w.seed.unwrap_or(0)
        ),
        WaveKind::Table | WaveKind::None => {
            format!("{} components from {}", sea.components().len(), w.file.as_deref().unwrap_or("-"))
        }
    };
    outln!("riser waves: scene '{}', {what}", scene.name);
    outln!(
        "  {}, mean water level z = {} m, phase origin ({}, {}) m, {} stretching, ramp {} s",
        depth_text(scene, w),
        s.surface_z,
        s.origin[0],
        s.origin[1],
        w.stretching.unwrap_or_default().name(),
        s.ramp.duration
    );
    outln!("  eta(x, y, t) = sum a cos(k((x - x0) cos b + (y - y0) sin b) - 2 pi f t + phase)");
    outln!(
        "  {:>5} {:>12} {:>10} {:>12} {:>11} {:>12} {:>11} {:>10}",
        "i",
        "f (Hz)",
        "T (s)",
        "k (rad/m)",
        "L (m)",
        "a (m)",
        "phase deg",
        "dir deg"
    );
    for (i, (c, k)) in sea.components().iter().zip(sea.wave_numbers()).enumerate() {
        outln!(
            "  {:>5} {:>12.7} {:>10.4} {:>12.7} {:>11.3} {:>12.7} {:>11.4} {:>10.4}",
            i,
            c.frequency,
            1.0 / c.frequency,
            k,
            2.0 * std::f64::consts::PI / k,
            c.amplitude,
            c.phase.to_degrees(),
            c.direction.to_degrees()
        );
    }
    let input = |v: Option<f64>| v.map(|v| format!(" (input {v})")).unwrap_or_default();
    outln!(
        "  from the components: Hs = 4 sqrt(m0) = {:.4} m{}, Tp = {:.4} s{} (the largest component), Tz = {:.4} s, m0 = {:.5} m^2",
        sea.hs(),
        input(w.hs),
        sea.peak_period(),
        input(w.tp.or(w.period)),
        sea.zero_crossing_period(),
        sea.m0()
    );
    if let Some(t) = repeat_period(w, sea) {
        outln!("  equal bins: the record repeats itself after {t:.1} s (components / (f_max - f_min))");
    }
    if w.spacing == Some(SpacingSpec::Energy)
        && let Some((peak, lag)) = riser::loads::waves::autocorrelation_peak(sea.components(), 60.0, duration)
    {
        outln!(
            "  energy bins: no repeat period; the elevation's autocorrelation envelope from 60 s to {duration} s at \
             most {peak:.3} (lag {lag:.1} s)"
        );
    }
    for p in written {
        outln!("  wrote {}", p.display());
    }
}

fn to_json(
    scene: &Scene,
    w: &WavesSpec,
    sea: &Sea,
    warnings: &[String],
    written: &[PathBuf],
    duration: f64,
) -> serde_json::Value {
    let peak = riser::loads::waves::autocorrelation_peak(sea.components(), 60.0, duration);
    let s = sea.settings();
    let k = sea.wave_numbers();
    let comps: Vec<serde_json::Value> = sea
        .components()
        .iter()
        .zip(&k)
        .map(|(c, k)| {
            serde_json::json!({
                "frequency": c.frequency, "amplitude": c.amplitude, "phase": c.phase.to_degrees(),
                "direction": c.direction.to_degrees(), "wave_number": k,
            })
        })
        .collect();
    serde_json::json!({
        "scene": scene.name,
        "kind": w.kind.name(),
        "depth": riser::loads::waves::depth_of(scene),
        "surface_z": s.surface_z,
        "origin": s.origin,
        "stretching": w.stretching.unwrap_or_default().name(),
        "ramp": s.ramp.duration,
        "gamma": (w.kind == WaveKind::Jonswap).then(|| w.gamma_or_default()),
        "components": comps,
        "hs": sea.hs(),
        "tp": sea.peak_period(),
        "tz": sea.zero_crossing_period(),
        "m0": sea.m0(),
        "repeat_period": repeat_period(w, sea),
        "spacing": w.spacing.unwrap_or_default().name(),
        "autocorrelation_peak": peak.map(|(value, lag)| serde_json::json!({"value": value, "lag": lag, "from": 60.0, "to": duration})),
        "warnings": warnings,
        "files": written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
    })
}

fn write_outputs(
    dir: &Path,
    scene: &Scene,
    w: &WavesSpec,
    sea: &Sea,
    rao: Option<&riser::sim::vessel::RaoMotion>,
    duration: f64,
    dt: f64,
) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let rec = record(sea, duration, dt);
    let elevation = dir.join("elevation.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&elevation)?);
    writeln!(f, "t,elevation,ramped")?;
    for i in 0..rec.t.len() {
        writeln!(f, "{},{},{}", num(rec.t[i]), num(rec.eta[i]), num(rec.ramped[i]))?;
    }
    f.flush()?;
    let bands = bins(w, sea);
    let target = target_spectrum(w);
    let measured = record_spectrum(&rec, &bands);
    let spectrum = dir.join("spectrum.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&spectrum)?);
    writeln!(f, "frequency,band_low,band_high,target,components,record")?;
    let mut rows = Vec::new();
    for (i, c) in sea.components().iter().enumerate() {
        let (a, b) = bands[i];
        let s_target = target.map_or(f64::NAN, |t| t.density(c.frequency));
        let s_comp = 0.5 * c.amplitude * c.amplitude / (b - a);
        let text = |v: f64| if v.is_nan() { String::new() } else { num(v) };
        writeln!(
            f,
            "{},{},{},{},{},{}",
            num(c.frequency),
            num(a),
            num(b),
            text(s_target),
            num(s_comp),
            text(measured[i])
        )?;
        rows.push((c.frequency, s_target, s_comp, measured[i]));
    }
    f.flush()?;
    let table = dir.join("components.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&table)?);
    write_components(&mut f, scene, sea)?;
    f.flush()?;
    let mut written = vec![elevation, spectrum, table];
    if let Some(r) = rao {
        let path = dir.join("vessel_motion.csv");
        let mut f = std::io::BufWriter::new(std::fs::File::create(&path)?);
        writeln!(
            f,
            "# the vessel's motion on its RAOs ({}) in this sea, the waves' ramp included, as riser run drives it: the \
             reference point's displacement (m, m/s) and angles (rad), the angular velocity in the vessel frame \
             (rad/s): the FMU's inputs",
            r.dofs.join(", ")
        )?;
        writeln!(
            f,
            "t,surge,sway,heave,roll,pitch,yaw,surge_velocity,sway_velocity,heave_velocity,angular_velocity_x,\
             angular_velocity_y,angular_velocity_z"
        )?;
        for &t in &rec.t {
            let m = r.at(t);
            let (d, v, a, b) = (m.displacement, m.velocity, m.angles, m.body_rates);
            let row = [d.x, d.y, d.z, a[0], a[1], a[2], v.x, v.y, v.z, b.x, b.y, b.z];
            write!(f, "{}", num(t))?;
            for x in row {
                write!(f, ",{}", num(x))?;
            }
            writeln!(f)?;
        }
        f.flush()?;
        written.push(path);
    }
    let plot = dir.join("waves.svg");
    std::fs::write(&plot, svg(scene, w, sea, &rec, &rows, target))?;
    written.push(plot);
    Ok(written)
}

/// components.csv: the realised components as `kind = "table"` reads them
/// (Hz, m, deg, deg), after comment lines that state the formula, the
/// phase origin, the time origin, the water the wave numbers are of, and
/// the rules for moving the origins (docs/guide/waves.md "One sea").
fn write_components(f: &mut impl std::io::Write, scene: &Scene, sea: &Sea) -> std::io::Result<()> {
    let s = sea.settings();
    let [x0, y0] = s.origin;
    let depth = match s.depth {
        Some(d) => format!("depth {} m", num(d)),
        None => "deep water".to_string(),
    };
    writeln!(f, "# the sea of scene '{}' as riser realises it: [waves] kind = \"table\" reads it back", scene.name)?;
    writeln!(
        f,
        "# eta(x, y, t) = sum amplitude cos(k ((x - x0) cos(direction) + (y - y0) sin(direction)) - 2 pi frequency t \
         + phase); frequency Hz, amplitude m, phase deg, direction deg (of travel, from +x towards +y)"
    )?;
    writeln!(
        f,
        "# phase origin (x0, y0) = ({}, {}) m in the scene frame (the hang-off's mean position is (0, 0)): a scene \
         reading this table gives [waves] origin = [{}, {}]",
        num(x0),
        num(y0),
        num(x0),
        num(y0)
    )?;
    writeln!(
        f,
        "# t = 0 is the start of the run (riser run; the FMU's simulation time); the table holds the sea without its \
         ramp ({} s from the run's start)",
        num(s.ramp.duration)
    )?;
    writeln!(
        f,
        "# k from omega^2 = g k tanh(k d): {depth}, g = {} m/s^2 (the same water gives the same sea everywhere; \
         other water only at the phase origin)",
        num(s.gravity)
    )?;
    writeln!(
        f,
        "# another phase origin (x0', y0'): phase' = phase + k ((x0' - x0) cos(direction) + (y0' - y0) sin(direction)) \
         (rad); another time origin t' = t - t0: phase' = phase - 2 pi frequency t0 (rad)"
    )?;
    writeln!(f, "frequency,amplitude,phase,direction")?;
    for c in sea.components() {
        writeln!(
            f,
            "{},{},{},{}",
            num(c.frequency),
            num(c.amplitude),
            num(c.phase.to_degrees()),
            num(c.direction.to_degrees())
        )?;
    }
    Ok(())
}

/// Two panels: the elevation at the phase origin over the first stretch of
/// the record (the realisation and the ramped one), and the spectrum
/// (the target formula, the components' a²/(2Δf) and the record's estimate).
fn svg(
    scene: &Scene,
    w: &WavesSpec,
    sea: &Sea,
    rec: &Record,
    rows: &[(f64, f64, f64, f64)],
    target: Option<Spectrum>,
) -> String {
    let (width, panel_h, left, right) = (820.0, 240.0, 70.0, 20.0);
    let height = 2.0 * (panel_h + 60.0) + 50.0;
    let mut s = crate::svg::open(
        width,
        height,
        &format!(
            "Waves of scene '{}' ({}): Hs = 4 sqrt(m0) = {:.3} m, Tp = {:.3} s, {} components",
            scene.name,
            w.kind.name(),
            sea.hs(),
            sea.peak_period(),
            sea.components().len()
        ),
    );
    // panel 1: elevation
    let shown = (30.0 * sea.peak_period()).max(60.0).min(rec.t.last().copied().unwrap_or(0.0) + rec.dt);
    let n_shown = rec.t.iter().take_while(|t| **t <= shown).count();
    let series: [(&[f64], &str, &str); 2] = [
        (&rec.eta[..n_shown], "#1f77b4", "elevation"),
        (&rec.ramped[..n_shown], "#d62728", "ramped (as the line feels it)"),
    ];
    let y_abs = series.iter().flat_map(|(v, _, _)| v.iter()).fold(0.0f64, |m, v| m.max(v.abs())).max(1e-3);
    let lines: Vec<Curve> =
        series.iter().map(|(v, c, l)| (rec.t.iter().zip(v.iter()).map(|(t, e)| (*t, *e)).collect(), *c, *l)).collect();
    panel(
        &mut s,
        40.0,
        panel_h,
        left,
        width - right,
        (0.0, shown),
        (-y_abs, y_abs),
        "t (s)",
        "elevation at the phase origin (m)",
        &lines,
        &[],
    );
    // panel 2: spectrum
    let f_lo = rows.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let f_hi = rows.iter().map(|r| r.0).fold(0.0, f64::max);
    let (f_lo, f_hi) = if f_hi > f_lo { (0.0, f_hi * 1.05) } else { (0.0, 2.0 * f_lo.max(1e-3)) };
    let mut curves: Vec<Curve> = Vec::new();
    if let Some(t) = target {
        let f: Vec<f64> = (1..=400).map(|i| f_hi * i as f64 / 400.0).collect();
        curves.push((f.iter().copied().zip(t.densities(&f)).collect(), "#000000", "target spectrum S(f)"));
    }
    curves.push((rows.iter().map(|r| (r.0, r.3)).collect(), "#2ca02c", "the record's periodogram, per band"));
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.0, r.2)).collect();
    let s_max = curves
        .iter()
        .flat_map(|c| c.0.iter().map(|p| p.1))
        .chain(points.iter().map(|p| p.1))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        .max(1e-9);
    panel(
        &mut s,
        40.0 + panel_h + 60.0,
        panel_h,
        left,
        width - right,
        (f_lo, f_hi),
        (0.0, 1.05 * s_max),
        "f (Hz)",
        "S (m^2/Hz)",
        &curves,
        &points,
    );
    let _ = writeln!(s, "</svg>");
    s
}

/// A curve of a panel: its points, colour and legend.
type Curve<'a> = (Vec<(f64, f64)>, &'a str, &'a str);

/// One panel with polylines (and points: the components, as circles).
#[allow(clippy::too_many_arguments)]
fn panel(
    w: &mut String,
    y0: f64,
    h: f64,
    x0: f64,
    x1: f64,
    (xa, xb): (f64, f64),
    (ya, yb): (f64, f64),
    xlabel: &str,
    ylabel: &str,
    lines: &[Curve],
    points: &[(f64, f64)],
) {
    let y1 = y0 + h;
    let px = |x: f64| x0 + (x - xa) / (xb - xa) * (x1 - x0);
    let py = |y: f64| y1 - (y - ya) / (yb - ya) * (y1 - y0);
    let frame = Frame { x0, x1, y0, y1 };
    frame.grid(w, (xa, xb, 8), (ya, yb, 5));
    frame.axes(w, xlabel, ylabel, 18.0);
    for (k, (pts, colour, label)) in lines.iter().enumerate() {
        let p: Vec<String> =
            pts.iter().filter(|p| p.1.is_finite()).map(|(x, y)| format!("{:.2},{:.2}", px(*x), py(*y))).collect();
        let _ = writeln!(w, r#"<polyline fill="none" stroke="{colour}" stroke-width="1.2" points="{}"/>"#, p.join(" "));
        let ly = y0 + 14.0 + 14.0 * k as f64;
        let _ = writeln!(
            w,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="2"/><text x="{:.1}" y="{:.1}">{label}</text>"#,
            x1 - 250.0,
            ly - 4.0,
            x1 - 230.0,
            ly - 4.0,
            x1 - 225.0,
            ly
        );
    }
    if !points.is_empty() {
        for (x, y) in points {
            let _ = writeln!(w, r##"<circle cx="{:.2}" cy="{:.2}" r="2" fill="#ff7f0e"/>"##, px(*x), py(*y));
        }
        let ly = y0 + 14.0 + 14.0 * lines.len() as f64;
        let _ = writeln!(
            w,
            r##"<circle cx="{:.1}" cy="{:.1}" r="3" fill="#ff7f0e"/><text x="{:.1}" y="{:.1}">the components, a^2/(2 df)</text>"##,
            x1 - 240.0,
            ly - 4.0,
            x1 - 225.0,
            ly
        );
    }
}
