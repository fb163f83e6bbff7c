//! The linear dispersion relation ω² = g k tanh(k d) (docs/theory.md §13.1),
//! solved for the wave number k to round-off.

/// Wave number k (rad/m) of a linear wave of circular frequency `omega`
/// (rad/s) in water of depth `depth` (m; `None`: deep water, k = ω²/g)
/// under gravity `g` (m/s²).
///
/// In the dimensionless x = k d, y = ω² d / g the relation is x tanh x = y.
/// Newton's iteration on F(x) = x tanh x − y, F′ = tanh x + x (1 − tanh² x),
/// starts from Eckart's approximation x₀ = y / √tanh y (within 5 % on every
/// depth) and stops when the step is below two ulps of x: F is increasing
/// and, on the side of the root Newton lands on after its first step,
/// the iteration is monotone, so it converges to the double nearest the
/// root (or its neighbour) in 3–5 steps. Where tanh y = 1 to double
/// precision (y > 19) the water is deep at this frequency and k = ω²/g.
pub fn wave_number(omega: f64, depth: Option<f64>, g: f64) -> f64 {
    let deep = omega * omega / g;
    let Some(d) = depth else { return deep };
    let y = deep * d;
    if y > 19.0 {
        // tanh(y) = 1 - 2e-17: deep water to round-off
        return deep;
    }
    if y <= 0.0 {
        return 0.0;
    }
    let mut x = y / y.tanh().sqrt();
    for _ in 0..60 {
        let t = x.tanh();
        let f = x * t - y;
        let df = t + x * (1.0 - t * t);
        let step = f / df;
        x -= step;
        if step.abs() <= 2.0 * f64::EPSILON * x {
            break;
        }
    }
    x / d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wave_number_satisfies_the_dispersion_relation_to_round_off() {
        let g = 9.81;
        for d in [0.5, 5.0, 30.0, 100.0, 1000.0] {
            for period in [1.0, 4.0, 10.0, 20.0, 40.0] {
                let w = 2.0 * std::f64::consts::PI / period;
                let k = wave_number(w, Some(d), g);
                let lhs = g * k * (k * d).tanh();
                assert!((lhs - w * w).abs() <= 4.0 * f64::EPSILON * w * w, "d {d} T {period}: {lhs} vs {}", w * w);
            }
        }
        // deep water
        assert_eq!(wave_number(1.0, None, 9.81), 1.0 / 9.81);
        // shallow water: x tanh x = y gives x = √y (1 + y/6 + O(y²))
        let (w, d) = (0.01, 10.0);
        let y = w * w * d / 9.81;
        let k = wave_number(w, Some(d), 9.81);
        assert!((k * d / (y.sqrt() * (1.0 + y / 6.0)) - 1.0).abs() < 1e-8);
    }
}
