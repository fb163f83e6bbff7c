//! `riser modes`: natural periods and mode shapes of the line about its
//! static state — the text table, the JSON object, and with `--out` the CSV
//! files and a plot of the lowest modes (modes.svg, written by hand).

use crate::svg::{Frame, escape};
use riser::math::V3;
use riser::scene::{Model, Scene};
use riser::sim::modes::{ModalReport, SceneMode, plane_normal, scene_modes};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Natural periods and mode shapes of the line about its static state (with added mass).
#[derive(clap::Args)]
pub struct ModesArgs {
    /// Built-in scene (catenary, lazy_wave, steel_catenary) or path to a scene file (TOML).
    scene: String,
    /// Override a parameter by name, e.g. --set model=cable (see `riser params`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Number of modes, lowest first.
    #[arg(long, value_name = "N", default_value_t = 10)]
    count: usize,
    /// Print one JSON object (periods, frequencies, directions, fractions, shapes).
    #[arg(long)]
    json: bool,
    /// Write modes.csv, mode_shapes.csv and modes.svg (the first six shapes) into this directory.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

/// The most modes modes.svg draws.
const PLOTTED: usize = 6;

fn model_name(model: Model) -> &'static str {
    match model {
        Model::Rod => "rod",
        Model::Cable => "cable",
    }
}

pub fn modes(args: ModesArgs) -> Result<(), String> {
    let ModesArgs { scene, set, count, json, out } = args;
    if count == 0 {
        return Err("--count must be at least 1".into());
    }
    if riser::scene::system::is_system_source(&scene) {
        if out.is_some() {
            return Err("--out: not yet for a system scene; --json has every line's periods".into());
        }
        return super::system_run::modes(&scene, &set, count, json);
    }
    let scene = super::load(&scene, &set).map_err(|e| e.to_string())?;
    let t0 = std::time::Instant::now();
    let rep = scene_modes(&scene, count).map_err(|e| e.to_string())?;
    let wall = t0.elapsed().as_secs_f64();
    let written = match &out {
        Some(dir) => write_outputs(dir, &scene, &rep).map_err(|e| format!("cannot write {}: {e}", dir.display()))?,
        None => Vec::new(),
    };
    if json {
        outln!("{}", to_json(&scene, &rep, wall));
    } else {
        print_text(&scene, &rep, wall, &written);
    }
    Ok(())
}

fn to_json(scene: &Scene, rep: &ModalReport, wall: f64) -> serde_json::Value {
    let finite = |v: f64| if v.is_finite() { serde_json::json!(v) } else { serde_json::Value::Null };
    serde_json::json!({
        "scene": scene.name,
        "model": model_name(rep.model),
        "n_elements": scene.analysis.n_elements,
        "unknowns": rep.unknowns,
        "static_current": scene.analysis.static_current,
        "periods": rep.modes.iter().map(|m| finite(m.period)).collect::<Vec<_>>(),
        "frequencies": rep.modes.iter().map(|m| m.frequency).collect::<Vec<_>>(),
        "eigenvalues": rep.modes.iter().map(|m| m.eigenvalue).collect::<Vec<_>>(),
        "eigenvalues_imag": rep.modes.iter().map(|m| m.eigenvalue_imag).collect::<Vec<_>>(),
        "directions": rep.modes.iter().map(|m| m.direction.name()).collect::<Vec<_>>(),
        "fractions": rep.modes.iter().map(|m| m.fractions.to_vec()).collect::<Vec<_>>(),
        "shapes": rep.modes.iter().map(|m| m.shape.iter().map(|r| {
            let (p, u) = (r.position, r.displacement);
            [r.s, p.x, p.y, p.z, u.x, u.y, u.z, r.twist]
        }).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "wall_time": wall,
    })
}

fn print_text(scene: &Scene, rep: &ModalReport, wall: f64, written: &[PathBuf]) {
    outln!(
        "riser modes: scene '{}' ({}, {} elements, {} free unknowns), about the static state {} the current",
        scene.name,
        model_name(rep.model),
        scene.analysis.n_elements,
        rep.unknowns,
        if scene.analysis.static_current { "with" } else { "without" }
    );
    outln!(
        "  {:>4} {:>10} {:>10}  {:<13} {:>8} {:>8} {:>8} {:>8}",
        "mode",
        "period s",
        "freq Hz",
        "direction",
        "in-pl %",
        "out-pl %",
        "axial %",
        "tors %"
    );
    for m in &rep.modes {
        let [a, b, c, d] = m.fractions.map(|v| 100.0 * v);
        let period = if m.period.is_finite() { format!("{:10.4}", m.period) } else { format!("{:>10}", "inf") };
        out!(
            "  {:>4} {period} {:>10.5}  {:<13} {a:8.2} {b:8.2} {c:8.2} {d:8.2}",
            m.number,
            m.frequency,
            m.direction.name()
        );
        if m.eigenvalue <= 0.0 {
            out!("  unstable (λ = {:.3e} 1/s²)", m.eigenvalue);
        }
        if m.eigenvalue_imag != 0.0 {
            out!("  flutter (Im λ = {:.3e} 1/s²)", m.eigenvalue_imag);
        }
        outln!();
    }
    outln!("  statics and {} modes in {:.1} ms", rep.modes.len(), wall * 1e3);
    for p in written {
        outln!("  wrote {}", p.display());
    }
}

/// modes.csv, mode_shapes.csv and modes.svg in `dir`; the paths written.
fn write_outputs(dir: &Path, scene: &Scene, rep: &ModalReport) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let table = dir.join("modes.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&table)?);
    writeln!(f, "mode,period_s,frequency_hz,direction,in_plane,out_of_plane,axial,torsion")?;
    for m in &rep.modes {
        let [a, b, c, d] = m.fractions;
        let [a, b, c, d] = [a, b, c, d].map(num);
        writeln!(f, "{},{},{},{},{a},{b},{c},{d}", m.number, num(m.period), num(m.frequency), m.direction.name())?;
    }
    f.flush()?;
    let shapes = dir.join("mode_shapes.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&shapes)?);
    writeln!(f, "mode,S,x,y,z,ux,uy,uz,twist")?;
    for m in &rep.modes {
        for r in &m.shape {
            let (p, u) = (r.position, r.displacement);
            write!(f, "{}", m.number)?;
            for v in [r.s, p.x, p.y, p.z, u.x, u.y, u.z, r.twist] {
                write!(f, ",{}", num(v))?;
            }
            writeln!(f)?;
        }
    }
    f.flush()?;
    let plot = dir.join("modes.svg");
    std::fs::write(&plot, modes_svg(scene, rep))?;
    Ok(vec![table, shapes, plot])
}

/// A number for the CSV files: exact (shortest round-trip), with an exponent
/// when plain decimals would be long (1.6e-35 rather than 0.000…016).
fn num(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-5..1e15).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// A mode's displacement against arc length, in the line's local directions.
struct Components {
    s: Vec<f64>,
    in_plane: Vec<f64>,
    out_of_plane: Vec<f64>,
    axial: Vec<f64>,
    twist: Vec<f64>,
}

/// Splits each node's displacement into axial (along the static tangent,
/// from the neighbouring nodes), out-of-plane (along the plane normal `n`)
/// and in-plane transverse (the rest, signed along n × tangent).
fn components(mode: &SceneMode, n: &V3) -> Components {
    let rows = &mode.shape;
    let last = rows.len().saturating_sub(1);
    let mut c = Components { s: vec![], in_plane: vec![], out_of_plane: vec![], axial: vec![], twist: vec![] };
    for (a, r) in rows.iter().enumerate() {
        let (prev, next) = (a.saturating_sub(1), (a + 1).min(last));
        let chord = rows[next].position - rows[prev].position;
        let t = if chord.norm() > 0.0 { chord.normalize() } else { V3::zeros() };
        let u = r.displacement;
        let (axial, out) = (u.dot(&t), u.dot(n));
        let rest = u - t * axial - n * out;
        let sign = if rest.dot(&n.cross(&t)) < 0.0 { -1.0 } else { 1.0 };
        c.s.push(r.s);
        c.axial.push(axial);
        c.out_of_plane.push(out);
        c.in_plane.push(sign * rest.norm());
        c.twist.push(r.twist);
    }
    c
}

fn panel_title(m: &SceneMode) -> String {
    if m.period.is_finite() {
        format!("mode {}: T = {:.2} s ({})", m.number, m.period, m.direction.name())
    } else {
        format!("mode {}: unstable, λ = {:.2e} 1/s² ({})", m.number, m.eigenvalue, m.direction.name())
    }
}

/// modes.svg: the first [`PLOTTED`] modes, one panel each, their
/// displacement components (m) and, for the rod, twist (rad) against S.
fn modes_svg(scene: &Scene, rep: &ModalReport) -> String {
    const IN_PLANE: &str = "#1f77b4";
    const OUT_OF_PLANE: &str = "#d62728";
    const AXIAL: &str = "#2ca02c";
    const TWIST: &str = "#9467bd";
    let (ml, mr, mt, mb) = (56.0, 14.0, 28.0, 40.0); // plot area margins inside a panel
    let head = 56.0; // figure title and legend
    let shown = &rep.modes[..rep.modes.len().min(PLOTTED)];
    let cols = match shown.len() {
        0 | 1 => 1,
        2 | 4 => 2,
        _ => 3,
    };
    let rows = shown.len().div_ceil(cols).max(1);
    // a panel; a single one as wide as two, room for the title and the legend
    let (pw, ph) = (if cols == 1 { 760.0 } else { 380.0 }, 260.0);
    let (width, height) = (pw * cols as f64, head + ph * rows as f64);
    let rod = rep.model == Model::Rod;
    let normal = plane_normal(scene.hang_off(), scene.anchor());

    let mut svg = String::new();
    let w = &mut svg;
    // writing into a String cannot fail
    let _ = writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        w,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(w, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        w,
        r#"<text x="{}" y="18" text-anchor="middle" font-size="14">{}</text>"#,
        width / 2.0,
        escape(&format!(
            "riser modes: scene '{}' ({}, {} elements), static state {} the current",
            scene.name,
            model_name(rep.model),
            scene.analysis.n_elements,
            if scene.analysis.static_current { "with" } else { "without" }
        ))
    );
    // legend
    let mut entries = vec![
        (IN_PLANE, "in-plane transverse (m)", false),
        (OUT_OF_PLANE, "out-of-plane (m)", false),
        (AXIAL, "axial (m)", false),
    ];
    if rod {
        entries.push((TWIST, "twist (rad)", true));
    }
    // about 6.5 px a character at font-size 11, a 24 px sample and gaps
    let entry_w = |label: &str| 30.0 + 6.5 * label.chars().count() as f64 + 24.0;
    let total: f64 = entries.iter().map(|(_, label, _)| entry_w(label)).sum();
    let mut x = (width - total).max(0.0) / 2.0;
    for (colour, label, dashed) in entries {
        let dash = if dashed { r#" stroke-dasharray="5,3""# } else { "" };
        let _ = writeln!(
            w,
            r#"<line x1="{x}" y1="38" x2="{}" y2="38" stroke="{colour}" stroke-width="2"{dash}/><text x="{}" y="42">{label}</text>"#,
            x + 24.0,
            x + 30.0
        );
        x += entry_w(label);
    }

    for (k, m) in shown.iter().enumerate() {
        let (ox, oy) = (pw * (k % cols) as f64, head + ph * (k / cols) as f64);
        let (x0, x1, y0, y1) = (ox + ml, ox + pw - mr, oy + mt, oy + ph - mb); // plot area, y0 at the top
        let c = components(m, &normal);
        let mut series: Vec<(&[f64], &str, bool)> =
            vec![(&c.in_plane, IN_PLANE, false), (&c.out_of_plane, OUT_OF_PLANE, false), (&c.axial, AXIAL, false)];
        if rod {
            series.push((&c.twist, TWIST, true));
        }
        let s_lo = c.s.first().copied().unwrap_or(0.0);
        let s_hi = c.s.last().copied().unwrap_or(1.0).max(s_lo + 1e-9);
        let (mut lo, mut hi) = (0.0f64, 0.0f64);
        for (v, _, _) in &series {
            for &y in v.iter().filter(|y| y.is_finite()) {
                lo = lo.min(y);
                hi = hi.max(y);
            }
        }
        if hi - lo < 1e-12 {
            (lo, hi) = (-1.0, 1.0);
        }
        let pad = 0.06 * (hi - lo);
        let (lo, hi) = (lo - pad, hi + pad);
        let px = |s: f64| x0 + (s - s_lo) / (s_hi - s_lo) * (x1 - x0);
        let py = |v: f64| y1 - (v - lo) / (hi - lo) * (y1 - y0);

        let _ = writeln!(w, "<g>");
        let _ = writeln!(
            w,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="12" font-weight="bold">{}</text>"#,
            (x0 + x1) / 2.0,
            oy + 18.0,
            escape(&panel_title(m))
        );
        // grid, ticks and their labels
        let frame = Frame { x0, x1, y0, y1 };
        frame.grid(w, (s_lo, s_hi, 5), (lo, hi, 5));
        frame.axes(w, "S (m)", if rod { "m, rad" } else { "m" }, ox + 14.0);
        for (v, colour, dashed) in series {
            let points: Vec<String> =
                c.s.iter()
                    .zip(v)
                    .filter(|(_, y)| y.is_finite())
                    .map(|(s, y)| format!("{:.2},{:.2}", px(*s), py(*y)))
                    .collect();
            let dash = if dashed { r#" stroke-dasharray="5,3""# } else { "" };
            let _ = writeln!(
                w,
                r#"<polyline fill="none" stroke="{colour}" stroke-width="1.6"{dash} points="{}"/>"#,
                points.join(" ")
            );
        }
        let _ = writeln!(w, "</g>");
    }
    let _ = writeln!(w, "</svg>");
    svg
}

#[cfg(test)]
mod tests {
    use super::{components, num, panel_title};
    use crate::svg::{tick_label, ticks};
    use riser::math::V3;
    use riser::model::linearized::Direction;
    use riser::sim::modes::{ModeRow, SceneMode};

    fn mode(eigenvalue: f64, shape: Vec<ModeRow>) -> SceneMode {
        let period = if eigenvalue > 0.0 { std::f64::consts::TAU / eigenvalue.sqrt() } else { f64::INFINITY };
        SceneMode {
            number: 2,
            period,
            frequency: if period.is_finite() { 1.0 / period } else { 0.0 },
            eigenvalue,
            eigenvalue_imag: 0.0,
            direction: Direction::InPlane,
            fractions: [1.0, 0.0, 0.0, 0.0],
            shape,
        }
    }

    #[test]
    fn titles_name_the_period_or_the_instability() {
        let w = std::f64::consts::TAU / 11.04;
        assert_eq!(panel_title(&mode(w * w, vec![])), "mode 2: T = 11.04 s (in-plane)");
        assert_eq!(panel_title(&mode(-2.5e-3, vec![])), "mode 2: unstable, λ = -2.50e-3 1/s² (in-plane)");
    }

    #[test]
    fn displacement_splits_along_tangent_normal_and_in_plane() {
        // a straight line along x in the plane y = 0 (normal ŷ); n × t = ŷ × x̂ = -ẑ
        let row = |s: f64, u: V3| ModeRow { s, position: V3::new(s, 0.0, 0.0), displacement: u, twist: 0.1 * s };
        let m =
            mode(1.0, vec![row(0.0, V3::new(0.5, 0.0, 0.0)), row(1.0, V3::new(0.2, 0.3, 0.4)), row(2.0, V3::zeros())]);
        let c = components(&m, &V3::y());
        assert_eq!(c.s, vec![0.0, 1.0, 2.0]);
        assert_eq!(c.axial, vec![0.5, 0.2, 0.0]);
        assert_eq!(c.out_of_plane, vec![0.0, 0.3, 0.0]);
        assert_eq!(c.in_plane, vec![0.0, -0.4, 0.0]);
        assert_eq!(c.twist, vec![0.0, 0.1, 0.2]);
    }

    #[test]
    fn csv_numbers_round_trip() {
        for v in [0.0, 1.0, 11.037112469503572, 1.6412417860511593e-35, -4.4e-19, 2.5e20, f64::INFINITY] {
            assert_eq!(num(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(num(1.6412417860511593e-35), "1.6412417860511593e-35");
        assert_eq!(num(0.5), "0.5");
    }

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 100.0, 5), vec![0.0, 20.0, 40.0, 60.0, 80.0, 100.0]);
        let t = ticks(-0.37, 1.06, 5);
        assert_eq!(t, vec![0.0, 0.5, 1.0]);
        assert!(t.iter().all(|v| (-0.37..=1.06).contains(v)));
        assert!(t.contains(&0.0));
        assert_eq!(tick_label(0.30000000000000004), "0.3");
        assert_eq!(tick_label(-0.0), "0");
        assert_eq!(tick_label(20.0), "20");
    }
}
