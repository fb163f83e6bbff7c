//! `touchdown.svg` of `riser run --out` on a line that touches the seabed
//! (written by hand, as modes.svg): the touchdown zone at the shape times —
//! elevation, effective tension and curvature against the arc length S,
//! over the range the touchdown moved through and 40 m either side.

use crate::svg::Frame;
use std::fmt::Write;

/// One recorded shape: its time (s) and rows [S, x, y, z, tension, curvature].
pub type Shape = (f64, Vec<[f64; 6]>);

/// The plot, or None when the line never touched the seabed (`touchdown`:
/// the run's touchdown_s series, `length` the line's length, m).
pub fn svg(shapes: &[Shape], touchdown: &[f64], length: f64, seabed_z: Option<f64>) -> Option<String> {
    let seabed_z = seabed_z?;
    let touching: Vec<f64> = touchdown.iter().copied().filter(|s| *s < length).collect();
    if touching.is_empty() || shapes.is_empty() {
        return None;
    }
    let lo = touching.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = touching.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let (s_lo, s_hi) = ((lo - 40.0).max(0.0), (hi + 40.0).min(length));
    let (width, panel_h, left) = (760.0, 180.0, 70.0);
    let height = 3.0 * (panel_h + 50.0) + 40.0;
    let mut w = crate::svg::open(
        width,
        height,
        &format!(
            "Touchdown zone: touchdown_s from {lo:.1} to {hi:.1} m; {} shapes (light to dark: earlier to later)",
            shapes.len()
        ),
    );
    let panels: [(&str, usize, f64); 3] = [("z (m)", 3, 1.0), ("tension (kN)", 4, 1e-3), ("curvature (1/m)", 5, 1.0)];
    for (p, (label, col, scale)) in panels.iter().enumerate() {
        let y0 = 30.0 + p as f64 * (panel_h + 50.0);
        let (x0, x1, y1) = (left, width - 20.0, y0 + panel_h);
        let rows = |sh: &Shape| {
            sh.1.iter().filter(|r| r[0] >= s_lo && r[0] <= s_hi).map(|r| (r[0], r[*col] * scale)).collect::<Vec<_>>()
        };
        let values: Vec<f64> = shapes.iter().flat_map(|sh| rows(sh).into_iter().map(|r| r.1)).collect();
        let mut v_lo = values.iter().cloned().fold(f64::INFINITY, f64::min);
        let mut v_hi = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        if *col == 3 {
            v_lo = v_lo.min(seabed_z);
        }
        if v_hi - v_lo <= 1e-12 * v_hi.abs().max(1.0) {
            (v_lo, v_hi) = (v_lo - 1.0, v_hi + 1.0);
        }
        let px = |s: f64| x0 + (s - s_lo) / (s_hi - s_lo) * (x1 - x0);
        let py = |v: f64| y1 - (v - v_lo) / (v_hi - v_lo) * (y1 - y0);
        let frame = Frame { x0, x1, y0, y1 };
        frame.grid(&mut w, (s_lo, s_hi, 6), (v_lo, v_hi, 4));
        if *col == 3 {
            let y = py(seabed_z);
            let _ = writeln!(
                w,
                r##"<line x1="{x0:.1}" y1="{y:.1}" x2="{x1:.1}" y2="{y:.1}" stroke="#8b5a2b" stroke-width="2"/><text x="{:.1}" y="{:.1}" fill="#8b5a2b">seabed (under the anchor)</text>"##,
                x0 + 6.0,
                y - 4.0
            );
        }
        frame.axes(&mut w, "S (m)", label, 18.0);
        for (k, sh) in shapes.iter().enumerate() {
            let shade = 200.0 - 170.0 * k as f64 / (shapes.len().max(2) - 1) as f64;
            let points: Vec<String> = rows(sh).iter().map(|(s, v)| format!("{:.2},{:.2}", px(*s), py(*v))).collect();
            let _ = writeln!(
                w,
                r#"<polyline fill="none" stroke="rgb({0:.0},{0:.0},255)" stroke-width="1.4" points="{1}"><title>t = {2} s</title></polyline>"#,
                shade,
                points.join(" "),
                sh.0
            );
        }
    }
    let _ = writeln!(w, "</svg>");
    Some(w)
}

#[cfg(test)]
mod tests {
    use super::svg;

    #[test]
    fn a_line_that_never_touches_has_no_plot_and_one_that_does_has_three_panels() {
        let shape =
            (1.0, (0..=10).map(|a| [a as f64 * 10.0, a as f64 * 9.0, 0.0, -(a as f64) * 5.0, 1e5, 1e-3]).collect());
        assert!(svg(std::slice::from_ref(&shape), &[100.0], 100.0, Some(-50.0)).is_none());
        assert!(svg(std::slice::from_ref(&shape), &[80.0], 100.0, None).is_none());
        let s = svg(&[shape], &[80.0, 85.0], 100.0, Some(-50.0)).unwrap();
        assert_eq!(s.matches("<polyline").count(), 3);
        assert!(s.contains("seabed") && s.ends_with("</svg>\n"));
    }
}
