//! Pieces of the CLI's SVG plots (modes.svg, touchdown.svg, waves.svg): round tick
//! values, their labels, and a panel's grid.

use std::fmt::Write;

/// About `target` round tick values covering [lo, hi] (steps of 1, 2 or 5 × 10^k).
pub(crate) fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return vec![lo];
    }
    let raw = span / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0].iter().map(|k| k * mag).find(|s| span / s <= target as f64).unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).map(|v| if v.abs() < 1e-12 * step { 0.0 } else { v }).collect()
}

pub(crate) fn tick_label(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The opening of an SVG document of `width` × `height` px with its title
/// (escaped here) centred at the top.
pub(crate) fn open(width: f64, height: f64, title: &str) -> String {
    let mut w = String::new();
    let _ = writeln!(
        w,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        w,
        r#"<text x="{:.1}" y="18" text-anchor="middle" font-size="13">{}</text>"#,
        width / 2.0,
        escape(title)
    );
    w
}

/// A panel's frame in pixels: x from `x0` to `x1`, y from `y0` (top) to `y1`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Frame {
    /// The grid of a panel whose x axis spans `x` = (lo, hi, about n ticks)
    /// and y axis `y`: vertical and horizontal lines with their labels, the
    /// line at y = 0 darker.
    pub(crate) fn grid(&self, w: &mut String, x: (f64, f64, usize), y: (f64, f64, usize)) {
        let Frame { x0, x1, y0, y1 } = *self;
        for t in ticks(x.0, x.1, x.2) {
            let px = x0 + (t - x.0) / (x.1 - x.0) * (x1 - x0);
            let _ = writeln!(
                w,
                r##"<line x1="{px:.1}" y1="{y0:.1}" x2="{px:.1}" y2="{y1:.1}" stroke="#e0e0e0"/><text x="{px:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
                y1 + 14.0,
                tick_label(t)
            );
        }
        for t in ticks(y.0, y.1, y.2) {
            let py = y1 - (t - y.0) / (y.1 - y.0) * (y1 - y0);
            let stroke = if t == 0.0 { "#909090" } else { "#e0e0e0" };
            let _ = writeln!(
                w,
                r#"<line x1="{x0:.1}" y1="{py:.1}" x2="{x1:.1}" y2="{py:.1}" stroke="{stroke}"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
                x0 - 4.0,
                py + 4.0,
                tick_label(t)
            );
        }
    }

    /// The panel's border, `xlabel` under its x axis and `ylabel` turned
    /// along its y axis at x = `label_x`.
    pub(crate) fn axes(&self, w: &mut String, xlabel: &str, ylabel: &str, label_x: f64) {
        let Frame { x0, x1, y0, y1 } = *self;
        let _ = writeln!(
            w,
            r#"<rect x="{x0:.1}" y="{y0:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="black"/>"#,
            x1 - x0,
            y1 - y0
        );
        let _ = writeln!(
            w,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{xlabel}</text>"#,
            (x0 + x1) / 2.0,
            y1 + 30.0
        );
        let (lx, ly) = (label_x, (y0 + y1) / 2.0);
        let _ = writeln!(
            w,
            r#"<text x="{lx:.1}" y="{ly:.1}" text-anchor="middle" transform="rotate(-90 {lx:.1} {ly:.1})">{ylabel}</text>"#
        );
    }
}
