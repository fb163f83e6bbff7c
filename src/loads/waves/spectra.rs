//! Wave spectra and their realisation as a sum of linear components
//! (docs/theory.md §13.3): Pierson–Moskowitz and JONSWAP in frequency f (Hz),
//! deterministic amplitudes aᵢ = √(2 S(fᵢ) Δf) at the centres of
//! `components` equal bins over [f_min, f_max], phases from a seeded
//! SplitMix64 generator written out here (the same seed gives the same
//! phases on every machine: integer arithmetic and one IEEE multiplication).

use super::Component;
use std::f64::consts::PI;

/// A one-sided wave spectrum S(f), m²/Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spectrum {
    /// Pierson–Moskowitz (fully developed sea) of significant height `hs`
    /// (m) and peak period `tp` (s).
    PiersonMoskowitz { hs: f64, tp: f64 },
    /// JONSWAP: Pierson–Moskowitz times the peak enhancement γ^r, scaled so
    /// that 4√m₀ = `hs` exactly.
    Jonswap { hs: f64, tp: f64, gamma: f64 },
}

/// The peak's width σ of JONSWAP below and above the peak.
const SIGMA: [f64; 2] = [0.07, 0.09];

/// Pierson–Moskowitz in units of Hs²Tp against x = f Tp:
/// s(x) = (5/16) x⁻⁵ exp(−(5/4) x⁻⁴), whose integral over x > 0 is 1/16.
fn pm_shape(x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let x4 = x * x * x * x;
    5.0 / 16.0 / (x4 * x) * (-1.25 / x4).exp()
}

/// The exponent r(x) of JONSWAP's peak enhancement γ^r.
fn peak_exponent(x: f64) -> f64 {
    let s = if x <= 1.0 { SIGMA[0] } else { SIGMA[1] };
    (-(x - 1.0) * (x - 1.0) / (2.0 * s * s)).exp()
}

/// Composite Simpson over [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for i in 1..n {
        sum += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// The factor A_γ that scales Pierson–Moskowitz γ^r to the same m₀:
/// 1/(1 + 16 ∫ s_PM(x)(γ^{r(x)} − 1) dx). The integrand vanishes to below
/// 1e-20 outside x ∈ [0.3, 3]; it is integrated on either side of the
/// peak (where σ changes) by Simpson's rule with 4000 intervals each, to
/// about 1e-12 (DNV-RP-C205's approximation 1 − 0.287 ln γ is within 1 %).
pub fn jonswap_normalisation(gamma: f64) -> f64 {
    let lg = gamma.ln();
    let excess = |x: f64| pm_shape(x) * (peak_exponent(x) * lg).exp_m1();
    let extra = simpson(excess, 0.3, 1.0, 4000) + simpson(excess, 1.0, 3.0, 4000);
    1.0 / (1.0 + 16.0 * extra)
}

impl Spectrum {
    /// Significant wave height, m.
    pub fn hs(&self) -> f64 {
        match *self {
            Spectrum::PiersonMoskowitz { hs, .. } | Spectrum::Jonswap { hs, .. } => hs,
        }
    }

    /// Peak period, s.
    pub fn tp(&self) -> f64 {
        match *self {
            Spectrum::PiersonMoskowitz { tp, .. } | Spectrum::Jonswap { tp, .. } => tp,
        }
    }

    /// The spectral density at each of `f` (Hz), m²/Hz. The JONSWAP
    /// normalisation is computed once per call.
    pub fn densities(&self, f: &[f64]) -> Vec<f64> {
        let (hs, tp) = (self.hs(), self.tp());
        match *self {
            Spectrum::PiersonMoskowitz { .. } => f.iter().map(|&f| hs * hs * tp * pm_shape(f * tp)).collect(),
            Spectrum::Jonswap { gamma, .. } => {
                let a = jonswap_normalisation(gamma);
                f.iter().map(|&f| hs * hs * tp * a * pm_shape(f * tp) * gamma.powf(peak_exponent(f * tp))).collect()
            }
        }
    }

    /// The spectral density S(f), m²/Hz.
    pub fn density(&self, f: f64) -> f64 {
        self.densities(&[f])[0]
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014; Vigna's reference code): a 64-bit
/// state advanced by the golden-ratio increment and mixed. Small, fast,
/// and the same stream on every machine.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1): the top 53 bits, exactly.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in (0, 1].
    pub fn next_open(&mut self) -> f64 {
        ((self.next_u64() >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// How a spectrum's band is cut into bins (docs/theory.md §13.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Spacing {
    /// Equal bins, one component at each centre (13.11): the record
    /// repeats itself after 1/Δf.
    #[default]
    Frequency,
    /// Bins of equal shares of (13.11a), [`FREQUENCY_SHARE`] of the measure
    /// the band's width and the rest its energy, one component at a random
    /// frequency inside each (13.11b): no two components keep a common
    /// period, the record does not repeat itself.
    Energy,
}

/// The share of the band's width in the measure that `Spacing::Energy`
/// cuts into equal bins (13.11a): no bin is wider than 1/`FREQUENCY_SHARE`
/// times the equal bins' width, so the spectrum's tails keep components.
pub const FREQUENCY_SHARE: f64 = 0.25;

/// How a spectrum is cut into components.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discretisation {
    /// Lowest and highest frequency of the bins, Hz.
    pub f_min: f64,
    pub f_max: f64,
    /// Number of equal bins (one component each).
    pub components: usize,
    /// Seed of the phases (and of the amplitudes when random).
    pub seed: u64,
    /// Rayleigh-distributed amplitudes aᵢ √(−ln Uᵢ) instead of the
    /// deterministic aᵢ (same mean square).
    pub random_amplitudes: bool,
    /// How the band is cut into bins.
    pub spacing: Spacing,
}

/// The edges of the `d.components` bins over [f_min, f_max], Hz, and each
/// bin's energy ∫ S df, m² (`Spacing::Frequency`: S at the bin's centre
/// times its width, the midpoint rule of (13.11)).
pub fn bins(spectrum: &Spectrum, d: &Discretisation) -> (Vec<f64>, Vec<f64>) {
    let n = d.components.max(1);
    match d.spacing {
        Spacing::Frequency => {
            let df = (d.f_max - d.f_min) / n as f64;
            let edges: Vec<f64> = (0..=n).map(|i| d.f_min + i as f64 * df).collect();
            let f: Vec<f64> = (0..n).map(|i| d.f_min + (i as f64 + 0.5) * df).collect();
            (edges, spectrum.densities(&f).into_iter().map(|s| s * df).collect())
        }
        Spacing::Energy => energy_bins(spectrum, d.f_min, d.f_max, n),
    }
}

/// (13.11a): the band's cumulative energy E(f) by the trapezoidal rule on
/// max(256 n, 20000) equal cells (within 1e-7 of m₀ for JONSWAP's peak at
/// γ ≤ 7), the measure G(f) = (1 − w) E(f)/E(f_max) + w (f − f_min)/(f_max −
/// f_min) with w = [`FREQUENCY_SHARE`], strictly increasing; edge j where
/// G = j/n and its energy, both linear in the cell: the bins' energies sum
/// to E(f_max) to round-off.
fn energy_bins(spectrum: &Spectrum, f_min: f64, f_max: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let cells = (256 * n).max(20_000);
    let width = f_max - f_min;
    let f: Vec<f64> = (0..=cells).map(|k| f_min + width * k as f64 / cells as f64).collect();
    let s = spectrum.densities(&f);
    let mut e = vec![0.0; cells + 1];
    for k in 0..cells {
        e[k + 1] = e[k] + 0.5 * (s[k] + s[k + 1]) * (f[k + 1] - f[k]);
    }
    let total = e[cells];
    let w = FREQUENCY_SHARE;
    let g = |k: usize| (1.0 - w) * e[k] / total + w * k as f64 / cells as f64;
    let mut edges = vec![f_min];
    let mut energy_at = vec![0.0];
    let mut k = 0;
    for j in 1..n {
        let target = j as f64 / n as f64;
        while k + 1 < cells && g(k + 1) <= target {
            k += 1;
        }
        let (g0, g1) = (g(k), g(k + 1));
        let r = ((target - g0) / (g1 - g0)).clamp(0.0, 1.0);
        edges.push(f[k] + r * (f[k + 1] - f[k]));
        energy_at.push(e[k] + r * (e[k + 1] - e[k]));
    }
    edges.push(f_max);
    energy_at.push(total);
    let energies = energy_at.windows(2).map(|p| p[1] - p[0]).collect();
    (edges, energies)
}

/// The components of `spectrum` travelling towards `direction` (rad):
/// component i at the centre fᵢ = f_min + (i + ½) Δf of its bin, amplitude
/// √(2 S(fᵢ) Δf), phase 2π Uᵢ with Uᵢ the i-th draw of SplitMix64(seed);
/// with random amplitudes the next `components` draws Vᵢ scale them by
/// √(−ln Vᵢ) (so the phases do not depend on that choice).
///
/// `Spacing::Energy` (13.11b): the bins of (13.11a), aᵢ = √(2 Eᵢ) from each
/// bin's energy Eᵢ, and fᵢ = f_lo + Wᵢ (f_hi − f_lo) with Wᵢ the draws after
/// the phases' (and the amplitudes'): the same phases as equal bins.
pub fn realise(spectrum: &Spectrum, d: &Discretisation, direction: f64) -> Vec<Component> {
    let n = d.components.max(1);
    let mut rng = SplitMix64::new(d.seed);
    let phases: Vec<f64> = (0..n).map(|_| 2.0 * PI * rng.next_f64()).collect();
    let (f, twice_energies) = match d.spacing {
        Spacing::Frequency => {
            let df = (d.f_max - d.f_min) / n as f64;
            let f: Vec<f64> = (0..n).map(|i| d.f_min + (i as f64 + 0.5) * df).collect();
            let s = spectrum.densities(&f);
            // 2 S(fᵢ) Δf (13.11), in this order
            (f, s.iter().map(|s| 2.0 * s * df).collect::<Vec<f64>>())
        }
        Spacing::Energy => {
            let (edges, energies) = energy_bins(spectrum, d.f_min, d.f_max, n);
            (edges[..n].to_vec(), energies.iter().map(|e| 2.0 * e).collect())
        }
    };
    let scales: Vec<f64> =
        (0..n).map(|_| if d.random_amplitudes { (-rng.next_open().ln()).sqrt() } else { 1.0 }).collect();
    let frequencies: Vec<f64> = match d.spacing {
        Spacing::Frequency => f,
        // (13.11b): f holds the bins' lower edges
        Spacing::Energy => {
            let mut hi = f[1..].to_vec();
            hi.push(d.f_max);
            f.iter().zip(&hi).map(|(lo, hi)| lo + rng.next_f64() * (hi - lo)).collect()
        }
    };
    (0..n)
        .map(|i| {
            let mut amplitude = twice_energies[i].sqrt();
            if d.random_amplitudes {
                amplitude *= scales[i];
            }
            Component { frequency: frequencies[i], amplitude, phase: phases[i], direction }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_gives_the_reference_stream() {
        // the first outputs of Vigna's splitmix64.c from state 0
        let mut r = SplitMix64::new(0);
        assert_eq!(r.next_u64(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(r.next_u64(), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(r.next_u64(), 0x06c4_5d18_8009_454f);
        let mut r = SplitMix64::new(7);
        for _ in 0..1000 {
            let u = r.next_f64();
            assert!((0.0..1.0).contains(&u));
            let v = r.next_open();
            assert!(v > 0.0 && v <= 1.0);
        }
    }

    #[test]
    fn energy_bins_hold_equal_shares_the_band_s_energy_and_the_same_phases() {
        let spectrum = Spectrum::Jonswap { hs: 4.0, tp: 10.0, gamma: 3.3 };
        let (f_min, f_max) = (0.05, 0.4);
        // the band's energy by Simpson on either side of the peak (not the
        // trapezoid of (13.11a))
        let simpson_of = |a: f64, b: f64| {
            let n = 20_000;
            let f: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
            let s = spectrum.densities(&f);
            let w = |i: usize| if i == 0 || i == n { 1.0 } else { [2.0, 4.0][i % 2] };
            (0..=n).map(|i| w(i) * s[i]).sum::<f64>() * (b - a) / n as f64 / 3.0
        };
        let band = simpson_of(f_min, 0.1) + simpson_of(0.1, f_max);
        for n in [7, 100, 800] {
            let d = Discretisation {
                f_min,
                f_max,
                components: n,
                seed: 3,
                random_amplitudes: false,
                spacing: Spacing::Energy,
            };
            let (edges, energy) = bins(&spectrum, &d);
            assert_eq!((edges.len(), energy.len()), (n + 1, n));
            let total: f64 = energy.iter().sum();
            assert!((total / band - 1.0).abs() < 1e-7, "{n}: {total} against {band}");
            // (13.11a): every bin one n-th of the measure, none wider than
            // 1/w equal bins
            let w = FREQUENCY_SHARE;
            for j in 0..n {
                let width = edges[j + 1] - edges[j];
                let share = (1.0 - w) * energy[j] / total + w * width / (f_max - f_min);
                assert!((share * n as f64 - 1.0).abs() < 1e-6, "{n}, bin {j}: share {share}");
                assert!(width > 0.0 && width <= (f_max - f_min) / (w * n as f64) * (1.0 + 1e-9));
            }
            // (13.11b): one component in each bin, a = √(2E), the phases of
            // equal bins of the same seed
            let c = realise(&spectrum, &d, 0.3);
            let equal = realise(&spectrum, &Discretisation { spacing: Spacing::Frequency, ..d }, 0.3);
            for j in 0..n {
                assert!(c[j].frequency >= edges[j] && c[j].frequency < edges[j + 1]);
                assert_eq!(c[j].amplitude, (2.0 * energy[j]).sqrt());
                assert_eq!((c[j].phase, c[j].direction), (equal[j].phase, 0.3));
            }
            // Rayleigh amplitudes: the same phases and frequencies
            let r = realise(&spectrum, &Discretisation { random_amplitudes: true, ..d }, 0.3);
            assert!(r.iter().zip(&c).all(|(r, c)| r.phase == c.phase && r.frequency != 0.0));
        }
        // the peak's bins are the narrowest: more components where the energy is
        let d = Discretisation {
            f_min,
            f_max,
            components: 200,
            seed: 0,
            random_amplitudes: false,
            spacing: Spacing::Energy,
        };
        let (edges, _) = bins(&spectrum, &d);
        let at_peak = edges.windows(2).filter(|e| e[1] > 0.085 && e[0] < 0.115).count();
        assert!(at_peak > 3 * 200 * 30 / 350, "{at_peak} bins within 15 % of the peak");
    }

    #[test]
    fn the_spectra_hold_hs_squared_over_16() {
        for spec in [
            Spectrum::PiersonMoskowitz { hs: 4.0, tp: 9.0 },
            Spectrum::Jonswap { hs: 4.0, tp: 9.0, gamma: 1.0 },
            Spectrum::Jonswap { hs: 4.0, tp: 9.0, gamma: 3.3 },
            Spectrum::Jonswap { hs: 4.0, tp: 9.0, gamma: 7.0 },
        ] {
            // Simpson on either side of the peak 1/9 Hz, and the tail
            let simpson_of = |a: f64, b: f64, n: usize| {
                let f: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
                let s = spec.densities(&f);
                let w = |i: usize| {
                    if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    }
                };
                (0..=n).map(|i| w(i) * s[i]).sum::<f64>() * (b - a) / n as f64 / 3.0
            };
            let m0 =
                simpson_of(1e-3, 1.0 / 9.0, 2000) + simpson_of(1.0 / 9.0, 2.0, 20000) + simpson_of(2.0, 200.0, 20000);
            assert!((m0 / 1.0 - 1.0).abs() < 1e-6, "{spec:?}: m0 {m0}");
        }
        // γ = 1 is Pierson–Moskowitz
        let a = Spectrum::Jonswap { hs: 3.0, tp: 8.0, gamma: 1.0 }.density(0.15);
        let b = Spectrum::PiersonMoskowitz { hs: 3.0, tp: 8.0 }.density(0.15);
        assert!((a / b - 1.0).abs() < 1e-12);
        // DNV-RP-C205's approximation of the normalisation is close
        for g in [2.0, 3.3, 5.0] {
            let ours = jonswap_normalisation(g);
            assert!((ours / (1.0 - 0.287 * f64::ln(g)) - 1.0).abs() < 0.02, "{g}: {ours}");
        }
    }
}
