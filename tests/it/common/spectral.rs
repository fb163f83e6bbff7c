//! Frequencies of a sampled response: a Hann-windowed discrete Fourier
//! transform evaluated on a fine frequency grid (peak refined to 1e-5 Hz).

use std::f64::consts::PI;

/// |Σ w_k y_k e^{−2πi f t_k}| with a Hann window.
pub fn spectrum(y: &[f64], dt: f64, f: f64) -> f64 {
    let n = y.len();
    let mean = y.iter().sum::<f64>() / n as f64;
    let (mut re, mut im) = (0.0, 0.0);
    for (k, v) in y.iter().enumerate() {
        let w = 0.5 - 0.5 * (2.0 * PI * k as f64 / (n - 1) as f64).cos();
        let a = 2.0 * PI * f * k as f64 * dt;
        re += w * (v - mean) * a.cos();
        im -= w * (v - mean) * a.sin();
    }
    (re * re + im * im).sqrt()
}

/// Frequency of the largest spectral peak within ±15 % of `guess`, Hz.
pub fn peak_near(y: &[f64], dt: f64, guess: f64) -> f64 {
    let (mut lo, mut hi) = (0.85 * guess, 1.15 * guess);
    let mut best = guess;
    for _ in 0..4 {
        let m = 200;
        let mut top = -1.0;
        for i in 0..=m {
            let f = lo + (hi - lo) * i as f64 / m as f64;
            let s = spectrum(y, dt, f);
            if s > top {
                top = s;
                best = f;
            }
        }
        let step = (hi - lo) / m as f64;
        lo = best - 2.0 * step;
        hi = best + 2.0 * step;
    }
    best
}
