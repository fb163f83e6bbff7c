//! Linear waves (docs/theory.md §13): a [`Sea`] of linear (Airy) components,
//! its elevation and its kinematics at any point, built from a scene's
//! `[waves]` block ([`sea_of`]).
//!
//! Convention (docs/theory.md §13; the README's `[waves]` keys): z up, the mean water level at
//! `water_surface_z`; component i of frequency fᵢ (ωᵢ = 2π fᵢ), amplitude aᵢ,
//! phase φᵢ and direction βᵢ (from +x towards +y) gives
//!
//!   η(x, y, t) = Σ aᵢ cos(kᵢ((x − x₀) cos βᵢ + (y − y₀) sin βᵢ) − ωᵢ t + φᵢ)   (13.1)
//!
//! with (x₀, y₀) the phase origin and kᵢ from the finite-depth dispersion
//! relation ([`dispersion`]). The kinematics ([`kinematics`]) are stretched
//! above the mean level and multiplied by a ramp.
//!
//! The water's force on the line (docs/theory.md §13.6, `loads::fluid`)
//! reads these kinematics once per step at the Gauss points of the whole
//! line ([`Sea::water_batch`]).

pub mod dispersion;
pub mod kinematics;
pub mod spectra;
mod vecmath;

use crate::scene::waves::{self as spec, WaveKind, WavesSpec};
use crate::scene::{FieldError, Scene};
use spectra::{Discretisation, Spectrum};
use std::f64::consts::PI;

pub use kinematics::{WaterPoint, WavePoint, WaveScratch};

/// One linear wave component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Component {
    /// Frequency f, Hz.
    pub frequency: f64,
    /// Amplitude a (half the height), m.
    pub amplitude: f64,
    /// Phase φ, rad (13.1).
    pub phase: f64,
    /// Direction of travel β, rad from +x towards +y.
    pub direction: f64,
}

/// How the kinematics above (and just below) the mean water level are taken
/// from the linear solution, which holds up to the mean level only
/// (docs/theory.md §13.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stretching {
    /// Wheeler: the water column from the seabed to the local surface η is
    /// mapped onto the column from the seabed to the mean level.
    Wheeler,
    /// The mean level's kinematics held constant above it.
    Vertical,
    /// The linear formulas evaluated as they are up to the surface.
    None,
}

/// ½(1 − cos(π (t − start)/duration)) for start < t < start + duration: 0
/// before, 1 after (duration 0: 1 always).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    /// Start of the ramp, s (the run's start).
    pub start: f64,
    /// Its length, s.
    pub duration: f64,
}

impl Ramp {
    /// No ramp: r = 1 from the start.
    pub const NONE: Ramp = Ramp { start: 0.0, duration: 0.0 };

    /// The ramp r(t) and its rate ṙ(t), 1/s.
    pub fn at(&self, t: f64) -> (f64, f64) {
        if self.duration <= 0.0 {
            return (1.0, 0.0);
        }
        let s = t - self.start;
        if s <= 0.0 {
            (0.0, 0.0)
        } else if s >= self.duration {
            (1.0, 0.0)
        } else {
            let a = PI / self.duration;
            (0.5 * (1.0 - (a * s).cos()), 0.5 * a * (a * s).sin())
        }
    }
}

/// Everything about the water a [`Sea`] needs besides its components.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeaSettings {
    /// Water depth, m (None: deep water).
    pub depth: Option<f64>,
    /// m/s².
    pub gravity: f64,
    /// The mean water level z_s, m.
    pub surface_z: f64,
    /// The phase origin (x₀, y₀), m.
    pub origin: [f64; 2],
    pub stretching: Stretching,
    pub ramp: Ramp,
}

/// What each component needs per evaluation, precomputed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Term {
    pub a: f64,
    pub k: f64,
    pub omega: f64,
    /// k cos β, k sin β, 1/m.
    pub kx: f64,
    pub ky: f64,
    pub cos_b: f64,
    pub sin_b: f64,
    /// φ − k (x₀ cos β + y₀ sin β): the phase at (0, 0).
    pub phi0: f64,
    /// a ω (m/s) and a ω² (m/s²).
    pub aw: f64,
    pub aw2: f64,
    /// e^{−2kd} and 1/(1 − e^{−2kd}) (0 and 1 in deep water).
    pub e2kd: f64,
    pub c: f64,
}

/// The terms sorted by wave number (ascending) as a struct of arrays, padded
/// with silent terms (amplitude 0) to a multiple of [`LANES`]: what
/// [`Sea::water_batch`] loops over (docs/theory.md §13.4). The velocity and
/// acceleration amplitudes are split along x and y: a ω cos β, a ω sin β,
/// a ω² cos β, a ω² sin β.
#[derive(Debug, Clone, Default)]
pub(crate) struct SortedTerms {
    pub len: usize,
    pub k: Vec<f64>,
    pub kx: Vec<f64>,
    pub ky: Vec<f64>,
    pub omega: Vec<f64>,
    pub phi0: Vec<f64>,
    pub a: Vec<f64>,
    pub aw: Vec<f64>,
    pub awx: Vec<f64>,
    pub awy: Vec<f64>,
    pub aw2: Vec<f64>,
    pub aw2x: Vec<f64>,
    pub aw2y: Vec<f64>,
    pub e2kd: Vec<f64>,
    pub c: Vec<f64>,
}

/// The width of [`SortedTerms`]' padding and of the batch's accumulators.
pub(crate) const LANES: usize = 4;

impl SortedTerms {
    fn new(terms: &[Term]) -> Self {
        let mut order: Vec<usize> = (0..terms.len()).collect();
        order.sort_by(|&i, &j| terms[i].k.total_cmp(&terms[j].k));
        let padded = terms.len().div_ceil(LANES) * LANES;
        let k_last = order.last().map_or(0.0, |&i| terms[i].k);
        let silent = Term {
            a: 0.0,
            k: k_last,
            omega: 0.0,
            kx: 0.0,
            ky: 0.0,
            cos_b: 0.0,
            sin_b: 0.0,
            phi0: 0.0,
            aw: 0.0,
            aw2: 0.0,
            e2kd: 0.0,
            c: 1.0,
        };
        let sorted: Vec<Term> =
            order.iter().map(|&i| terms[i]).chain(std::iter::repeat_n(silent, padded - terms.len())).collect();
        let col = |f: fn(&Term) -> f64| sorted.iter().map(f).collect::<Vec<f64>>();
        SortedTerms {
            len: padded,
            k: col(|t| t.k),
            kx: col(|t| t.kx),
            ky: col(|t| t.ky),
            omega: col(|t| t.omega),
            phi0: col(|t| t.phi0),
            a: col(|t| t.a),
            aw: col(|t| t.aw),
            awx: col(|t| t.aw * t.cos_b),
            awy: col(|t| t.aw * t.sin_b),
            aw2: col(|t| t.aw2),
            aw2x: col(|t| t.aw2 * t.cos_b),
            aw2y: col(|t| t.aw2 * t.sin_b),
            e2kd: col(|t| t.e2kd),
            c: col(|t| t.c),
        }
    }
}

/// Below this many decay lengths 1/k under every trough the wave field is
/// taken as zero (its size there is e^{−38} ≈ 3e-17 of the surface's).
pub(crate) const DECAY_LENGTHS: f64 = 38.0;

/// A sea: linear components and the water they travel in.
#[derive(Debug, Clone)]
pub struct Sea {
    components: Vec<Component>,
    /// In the components' order.
    pub(crate) terms: Vec<Term>,
    /// The same, sorted by k, for [`Sea::water_batch`].
    pub(crate) sorted: SortedTerms,
    pub(crate) settings: SeaSettings,
    /// Below this ζ = z − z_s every component's kinematics are below 1e-16 of
    /// their surface values and are not evaluated (None: never).
    pub(crate) deep_cutoff: Option<f64>,
}

impl Sea {
    /// The sea of `components` in the water of `settings`.
    pub fn new(components: Vec<Component>, settings: SeaSettings) -> Self {
        let g = settings.gravity;
        let [x0, y0] = settings.origin;
        let terms: Vec<Term> = components
            .iter()
            .map(|c| {
                let omega = 2.0 * PI * c.frequency;
                let k = dispersion::wave_number(omega, settings.depth, g);
                let (sin_b, cos_b) = c.direction.sin_cos();
                let (e2kd, cf) = match settings.depth {
                    Some(d) => {
                        let e = (-2.0 * k * d).exp();
                        (e, -1.0 / (-2.0 * k * d).exp_m1())
                    }
                    None => (0.0, 1.0),
                };
                Term {
                    a: c.amplitude,
                    k,
                    omega,
                    kx: k * cos_b,
                    ky: k * sin_b,
                    cos_b,
                    sin_b,
                    phi0: c.phase - k * (x0 * cos_b + y0 * sin_b),
                    aw: c.amplitude * omega,
                    aw2: c.amplitude * omega * omega,
                    e2kd,
                    c: cf,
                }
            })
            .collect();
        let amplitude_sum: f64 = components.iter().map(|c| c.amplitude.abs()).sum();
        let k_min = terms.iter().map(|t| t.k).fold(f64::INFINITY, f64::min);
        let deep_everywhere = match settings.depth {
            None => true,
            Some(d) => terms.iter().all(|t| t.k * d >= DECAY_LENGTHS) && amplitude_sum < 0.5 * d,
        };
        let deep_cutoff =
            (deep_everywhere && k_min.is_finite() && k_min > 0.0).then(|| -DECAY_LENGTHS / k_min - 2.0 * amplitude_sum);
        let sorted = SortedTerms::new(&terms);
        Sea { components, terms, sorted, settings, deep_cutoff }
    }

    /// Starts the ramp at `start` s (a run's start time).
    pub fn set_ramp_start(&mut self, start: f64) {
        self.settings.ramp.start = start;
    }

    /// The largest elevation the sea can reach anywhere, Σ |aᵢ|, m (a
    /// bound on |η|: the band of heights the moving surface sweeps).
    pub fn max_elevation(&self) -> f64 {
        self.components.iter().map(|c| c.amplitude.abs()).sum()
    }

    /// A scratch buffer sized for this sea (so that the first evaluation
    /// allocates nothing).
    pub fn scratch(&self) -> WaveScratch {
        let mut s = WaveScratch::default();
        s.reserve(self.terms.len(), self.sorted.len);
        s
    }

    /// The components as given.
    pub fn components(&self) -> &[Component] {
        &self.components
    }

    /// The wave number of each component, rad/m.
    pub fn wave_numbers(&self) -> Vec<f64> {
        self.terms.iter().map(|t| t.k).collect()
    }

    pub fn settings(&self) -> &SeaSettings {
        &self.settings
    }

    /// The depth below which the kinematics are taken as zero, as ζ = z −
    /// z_s (m; None where the long waves reach the seabed).
    pub fn deep_cutoff(&self) -> Option<f64> {
        self.deep_cutoff
    }

    /// η(x, y, t) of (13.1), m, without the ramp.
    pub fn elevation(&self, x: f64, y: f64, t: f64) -> f64 {
        self.terms.iter().map(|c| c.a * (c.kx * x + c.ky * y - c.omega * t + c.phi0).cos()).sum()
    }

    /// The elevation the line feels: r(t) η(x, y, t), m.
    pub fn ramped_elevation(&self, x: f64, y: f64, t: f64) -> f64 {
        let (r, _) = self.settings.ramp.at(t);
        if r == 0.0 { 0.0 } else { r * self.elevation(x, y, t) }
    }

    /// The zeroth spectral moment m₀ = Σ aᵢ²/2 (the variance of η), m².
    pub fn m0(&self) -> f64 {
        self.components.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum()
    }

    /// The significant wave height 4√m₀, m.
    pub fn hs(&self) -> f64 {
        4.0 * self.m0().sqrt()
    }

    /// The peak period: 1/f of the component of largest amplitude (the
    /// first of equals), s.
    pub fn peak_period(&self) -> f64 {
        peak_period(&self.components)
    }

    /// The mean zero-crossing period √(m₀/m₂), s.
    pub fn zero_crossing_period(&self) -> f64 {
        let m2: f64 = self.components.iter().map(|c| 0.5 * c.amplitude * c.amplitude * c.frequency * c.frequency).sum();
        (self.m0() / m2).sqrt()
    }
}

/// 1/f of the component of largest amplitude (the first of equals), s.
fn peak_period(components: &[Component]) -> f64 {
    let peak = components.iter().fold(None::<&Component>, |best, c| match best {
        Some(b) if b.amplitude >= c.amplitude => Some(b),
        _ => Some(c),
    });
    peak.map_or(f64::NAN, |c| 1.0 / c.frequency)
}

/// Why a scene's sea could not be built (a components file that cannot be
/// read: the scene's validation reports the same, naming the field).
pub type SeaError = FieldError;

/// The water depth the dispersion relation uses: `waves.depth` when given,
/// else the seabed's depth under the phase origin, else deep water (None).
pub fn depth_of(scene: &Scene) -> Option<f64> {
    spec::wave_depth(scene)
}

/// The components of a scene's `[waves]` block (docs/theory.md §13.3).
pub fn components_of(w: &WavesSpec) -> Result<Vec<Component>, SeaError> {
    let deg = |v: Option<f64>| v.unwrap_or(0.0).to_radians();
    Ok(match w.kind {
        WaveKind::None => Vec::new(),
        WaveKind::Airy => vec![Component {
            frequency: 1.0 / w.period.unwrap_or(f64::NAN),
            amplitude: 0.5 * w.height.unwrap_or(0.0),
            phase: deg(w.phase),
            direction: deg(w.direction),
        }],
        WaveKind::Jonswap | WaveKind::PiersonMoskowitz => {
            let (hs, tp) = (w.hs.unwrap_or(0.0), w.tp.unwrap_or(f64::NAN));
            let spectrum = match w.kind {
                WaveKind::Jonswap => Spectrum::Jonswap { hs, tp, gamma: w.gamma_or_default() },
                _ => Spectrum::PiersonMoskowitz { hs, tp },
            };
            let (f_min, f_max) = w.frequency_range();
            let d = Discretisation {
                f_min,
                f_max,
                components: w.components_or_default(),
                seed: w.seed.unwrap_or(0),
                random_amplitudes: w.random_amplitudes.unwrap_or(false),
                spacing: match w.spacing.unwrap_or_default() {
                    spec::SpacingSpec::Frequency => spectra::Spacing::Frequency,
                    spec::SpacingSpec::Energy => spectra::Spacing::Energy,
                },
            };
            spectra::realise(&spectrum, &d, deg(w.direction))
        }
        WaveKind::Table => spec::read_table(w)?
            .into_iter()
            .map(|r| Component {
                frequency: r.frequency,
                amplitude: r.amplitude,
                phase: r.phase.to_radians(),
                direction: r.direction.to_radians(),
            })
            .collect(),
    })
}

/// The scene's sea, its ramp starting at `start` s (None: no `[waves]`, or
/// `kind = "none"`: still water).
pub fn sea_of(scene: &Scene, start: f64) -> Result<Option<Sea>, SeaError> {
    let Some(w) = scene.waves.as_ref().filter(|w| w.kind != WaveKind::None) else {
        return Ok(None);
    };
    let components = components_of(w)?;
    let duration = w.ramp.unwrap_or(period_of(w, &components));
    Ok(Some(Sea::new(components, settings_of(scene, w, Ramp { start, duration }))))
}

/// The sea's period, s: a regular wave's T, a spectrum's T_p, a table's
/// peak period (that of its largest component).
fn period_of(w: &WavesSpec, components: &[Component]) -> f64 {
    match w.kind {
        WaveKind::Airy => w.period.unwrap_or(0.0),
        WaveKind::Jonswap | WaveKind::PiersonMoskowitz => w.tp.unwrap_or(0.0),
        _ => peak_period(components),
    }
}

/// The scene's sea's ramp and period, s (None: still water): the ramp
/// grows the sea from t = 0 over the first (`ramp`, default one period);
/// the period is a regular wave's T, a spectrum's T_p, a table's peak
/// period. What `riser run` waits for before its steady window.
pub fn ramp_and_period(scene: &Scene) -> Result<Option<(f64, f64)>, SeaError> {
    let Some(w) = scene.waves.as_ref().filter(|w| w.kind != WaveKind::None) else {
        return Ok(None);
    };
    let period = period_of(w, &components_of(w)?);
    Ok(Some((w.ramp.unwrap_or(period), period)))
}

/// The scene's sea is irregular: a spectrum or a table of components (the
/// pilots' window spans more of its periods: docs/theory.md §16.13).
pub fn irregular(scene: &Scene) -> bool {
    scene
        .waves
        .as_ref()
        .is_some_and(|w| matches!(w.kind, WaveKind::Jonswap | WaveKind::PiersonMoskowitz | WaveKind::Table))
}

fn settings_of(scene: &Scene, w: &WavesSpec, ramp: Ramp) -> SeaSettings {
    SeaSettings {
        depth: depth_of(scene),
        gravity: scene.environment.gravity,
        surface_z: scene.environment.water_surface_z,
        origin: w.origin.unwrap_or([0.0, 0.0]),
        stretching: match w.stretching.unwrap_or_default() {
            spec::StretchingSpec::Wheeler => Stretching::Wheeler,
            spec::StretchingSpec::Vertical => Stretching::Vertical,
            spec::StretchingSpec::None => Stretching::None,
        },
        ramp,
    }
}

/// Warnings about a scene's sea that the scene's own checks cannot give
/// (they need the wave numbers): a regular wave steeper than Miche's
/// breaking limit H/L = 0.142 tanh(kd).
/// The period after which a sea of components equally spaced in frequency,
/// Δf apart, repeats its envelope: 1/Δf, s (every component then turns by
/// the same phase, 2π f_i/Δf, f_i = f_min + (i + ½)Δf; docs/theory.md §13).
/// None for fewer than two components or frequencies not equally spaced
/// (a table's).
pub fn repeat_period(components: &[Component]) -> Option<f64> {
    let mut f: Vec<f64> = components.iter().map(|c| c.frequency).collect();
    f.sort_by(f64::total_cmp);
    f.dedup();
    if f.len() < 2 {
        return None;
    }
    let df = (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64;
    let uniform = f.windows(2).all(|w| ((w[1] - w[0]) - df).abs() <= 1e-6 * df);
    (uniform && df > 0.0).then_some(1.0 / df)
}

/// The largest envelope of the elevation's autocorrelation at lags in
/// [`from`, `to`] s (13.11c): |Σ aᵢ² e^{2πi fᵢ τ}| / Σ aᵢ², an upper bound of
/// |ρ(τ)| at a fixed point, whatever the directions; sampled every
/// 1/(8 (f_max − f_min)) of the components' range (the envelope varies on
/// the scale of 1/(f_max − f_min)). 1 at a repeat period; None for fewer
/// than two frequencies or an empty range. Returns (value, lag s).
pub fn autocorrelation_peak(components: &[Component], from: f64, to: f64) -> Option<(f64, f64)> {
    let (lo, hi) = components
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c.frequency), hi.max(c.frequency)));
    if !(hi > lo && to > from && from >= 0.0) {
        return None;
    }
    let dt = 1.0 / (8.0 * (hi - lo));
    let centre = 0.5 * (lo + hi);
    let weights: Vec<f64> = components.iter().map(|c| c.amplitude * c.amplitude).collect();
    let total: f64 = weights.iter().sum();
    let samples = ((to - from) / dt).ceil() as usize;
    let mut best = (0.0, from);
    for k in 0..=samples {
        let tau = (from + k as f64 * dt).min(to);
        let (mut re, mut im) = (0.0, 0.0);
        for (c, w) in components.iter().zip(&weights) {
            let (s, co) = (2.0 * PI * (c.frequency - centre) * tau).sin_cos();
            re += w * co;
            im += w * s;
        }
        let v = re.hypot(im) / total;
        if v > best.0 {
            best = (v, tau);
        }
    }
    Some(best)
}

/// A warning when a run of `duration` s is longer than its sea's repeat
/// period ([`repeat_period`]): it sees the same waves again, and statistics
/// over it (extremes, fatigue) are those of one period; with the
/// components that would not repeat within it, the band kept.
pub fn repeat_warning(components: &[Component], duration: f64) -> Option<String> {
    let period = repeat_period(components)?;
    if duration <= period {
        return None;
    }
    let n = components.len();
    let needed = (duration / period * n as f64).ceil() as u64;
    Some(format!(
        "the sea's {n} components, equally spaced in frequency, repeat every {period:.1} s (1/Δf): a run or record of \
         {duration} s sees the same waves {:.2} times, and its statistics (extremes, fatigue) are those of a \
         {period:.1} s record; set wave_components to at least {needed} for a sea that does not repeat within \
         the run (the same band, Δf = 1/duration)",
        duration / period
    ))
}

pub fn warnings(scene: &Scene) -> Vec<String> {
    let mut out = scene.wave_warnings();
    let Some(w) = scene.waves.as_ref().filter(|w| w.kind == WaveKind::Airy) else { return out };
    let (Some(h), Some(t)) = (w.height, w.period) else { return out };
    let d = depth_of(scene);
    let k = dispersion::wave_number(2.0 * PI / t, d, scene.environment.gravity);
    let limit = 0.142 * 2.0 * PI / k * d.map_or(1.0, |d| (k * d).tanh());
    if h > limit {
        out.push(format!(
            "waves.height {h} m exceeds the breaking limit of a {t} s wave{} (Miche: H/L = 0.142 tanh(kd), \
             H = {limit:.2} m): linear theory does not hold, the wave would break",
            d.map_or(" in deep water".to_string(), |d| format!(" in {d} m of water"))
        ));
    }
    out
}
