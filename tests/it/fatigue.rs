//! Fatigue (issue 50, docs/theory.md §12.5) against references computed
//! here: ASTM E1049-85's worked example of rainflow counting; Miner's sum of
//! n cycles of one range written out as n Δσ^m / a on each side of a
//! bilinear curve's switch and across it; DNV-RP-C203's own columns (the
//! stress range at 10⁷ cycles) against the tabulated m and log a; the
//! thickness correction; on synthetic Gaussian stress histories (sums of
//! cosines with random phases and frequencies), the narrow-band closed form
//! D = ν₀ T (2√2 σ)^m Γ(1 + m/2) / a and Dirlik's wide-band formula (written
//! out here), within the records' scatter; and `riser run --fatigue`
//! end to end, its worst damage recomputed from the stress history it wrote.
//! The rainflow counts equal the `rainflow` package's on random histories:
//! tests/python/test_fatigue.py.

use riser::sim::fatigue::{SnCurve, miner_sum, rainflow};
use std::f64::consts::PI;
use std::process::Command;

/// ASTM E1049-85, Fig. 6 (§5.4.4, rainflow counting): the history −2, 1, −3,
/// 5, −1, 3, −4, 4, −2 gives ranges 3 (½ cycle), 4 (1½), 6 (½), 8 (1), 9 (½),
/// as the standard's table of the example lists them.
#[test]
fn the_astm_e1049_worked_example() {
    let cycles = rainflow(&[-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]);
    for (range, count) in [(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)] {
        let n: f64 = cycles.iter().filter(|c| c.0 == range).map(|c| c.1).sum();
        assert_eq!(n, count, "range {range}: {cycles:?}");
    }
    let total: f64 = cycles.iter().map(|c| c.1).sum();
    assert_eq!(total, 4.0, "{cycles:?}");
}

/// n cycles of σ_m + (Δσ/2) cos(2π t/T), sampled 40 times a period from t = 0
/// to nT, in Pa.
fn cosine_history(mean: f64, range: f64, n: usize) -> Vec<f64> {
    (0..=40 * n).map(|k| mean + 0.5 * range * (2.0 * PI * k as f64 / 40.0).cos()).collect()
}

/// n Δσ^m / a by hand, Δσ in Pa, the curve's segment given.
fn by_hand(n: f64, range: f64, m: f64, log_a: f64) -> f64 {
    n * (range / 1e6).powf(m) / 10f64.powf(log_a)
}

/// A cosine stress of range Δσ, n cycles, gives D = n Δσ^m / a to 1e-12:
/// D-air, D-seawater-cp and B1-air (m₁ = 4) a part in 10⁹ above their
/// switch's range (a₁, m₁) and below it (a₂, m₂ = 5), D-free-corrosion (one
/// slope); across the switch, a history of 30 cycles above and 50 below
/// (from the same valley: the small ones close as full cycles inside the
/// large ones' half cycles) gives the sum of the two.
#[test]
fn a_cosine_stress_gives_n_cycles_damage_on_each_side_of_the_switch() {
    for name in ["D-air", "D-seawater-cp", "B1-air"] {
        let c = SnCurve::by_name(name).unwrap();
        let sw = c.switch_range().unwrap() * 1e6;
        for (range, m, log_a) in [(sw * (1.0 + 1e-9), c.m1, c.log_a1), (sw * (1.0 - 1e-9), c.m2, c.log_a2)] {
            let d = miner_sum(&c, &rainflow(&cosine_history(80e6, range, 25)), 1.0);
            let exact = by_hand(25.0, range, m, log_a);
            assert!((d / exact - 1.0).abs() < 1e-12, "{name} at {range} Pa: {d:e} against {exact:e}");
        }
        // across: 30 cycles of 1.5 S_sw from a valley at 10 MPa, then 50 of 0.6 S_sw
        let (big, small) = (1.5 * sw, 0.6 * sw);
        let mut h = vec![10e6];
        for _ in 0..30 {
            h.extend([10e6 + big, 10e6]);
        }
        for _ in 0..50 {
            h.extend([10e6 + small, 10e6]);
        }
        let d = miner_sum(&c, &rainflow(&h), 1.0);
        let exact = by_hand(30.0, big, c.m1, c.log_a1) + by_hand(50.0, small, c.m2, c.log_a2);
        assert!((d / exact - 1.0).abs() < 1e-12, "{name} across: {d:e} against {exact:e}");
    }
    let c = SnCurve::by_name("D-free-corrosion").unwrap();
    assert!(c.n_switch.is_none());
    for range in [20e6, 150e6] {
        let d = miner_sum(&c, &rainflow(&cosine_history(0.0, range, 25)), 1.0);
        let exact = by_hand(25.0, range, 3.0, 11.687);
        assert!((d / exact - 1.0).abs() < 1e-12, "free corrosion at {range}: {d:e} against {exact:e}");
    }
}

/// DNV-RP-C203 (2016) tabulates, beside m and log a, the stress range at
/// 10⁷ cycles (its "fatigue limit" column: B1 106.97 … W3 21.05 MPa, the same
/// in air and with CP): each curve's a₂ branch gives it to 0.05 % (log a to
/// three decimals, the column to two: W3's a₂ 21.057), and, in air, the a₁
/// branch too (the switch is at 10⁷);
/// the two branches meet at the switch to 0.2 % (N at S_sw from a₂ against
/// N_switch; measured at most 0.153 %, C1, D, F, F3, W1: the log a's rounded
/// to three decimals) for all 28 bilinear curves; the names are refused with the
/// list when unknown.
#[test]
fn the_curves_agree_with_the_rp_s_own_columns() {
    let limits = [
        ("B1", 106.97),
        ("B2", 93.59),
        ("C", 73.10),
        ("C1", 65.50),
        ("C2", 58.48),
        ("D", 52.63),
        ("E", 46.78),
        ("F", 41.52),
        ("F1", 36.84),
        ("F3", 32.75),
        ("G", 29.24),
        ("W1", 26.32),
        ("W2", 23.39),
        ("W3", 21.05),
    ];
    for (class, limit) in limits {
        for env in ["air", "seawater-cp"] {
            let c = SnCurve::by_name(&format!("{class}-{env}")).unwrap();
            let s2 = 10f64.powf((c.log_a2 - 7.0) / c.m2);
            assert!((s2 / limit - 1.0).abs() < 5e-4, "{class}-{env}: {s2} MPa at 1e7 against {limit}");
            if env == "air" {
                let s1 = 10f64.powf((c.log_a1 - 7.0) / c.m1);
                assert!((s1 / limit - 1.0).abs() < 5e-4, "{class}-air a1: {s1} against {limit}");
            }
            let sw = c.switch_range().unwrap();
            let n2 = 10f64.powf(c.log_a2 - c.m2 * sw.log10());
            assert!((n2 / c.n_switch.unwrap() - 1.0).abs() < 2e-3, "{class}-{env}: {n2:e} at the switch");
        }
    }
    assert_eq!(SnCurve::names().len(), 42);
    let e = SnCurve::by_name("D-sea").unwrap_err();
    assert!(e.contains("D-seawater-cp") && e.contains("W3-free-corrosion"), "{e}");
    assert_eq!(SnCurve::by_name("f1-Free-Corrosion").unwrap().name, "F1-free-corrosion");
}

/// The thickness correction (t/t_ref)^k, t_ref = 25 mm, applies only above
/// t_ref: D-air (k = 0.20) at 10, 20.6 and 25 mm gives 1, at 25.000001 mm
/// and 40 mm (t/25)^0.2 (1e-15); B1 (k = 0) never; and the damage of
/// cycles with the factor is that of the ranges times it.
#[test]
fn the_thickness_correction_is_absent_up_to_25_mm() {
    let d = SnCurve::by_name("D-air").unwrap();
    for t in [0.010, 0.0206, 0.025] {
        assert_eq!(d.thickness_factor(t), 1.0, "{t} m");
    }
    for t in [0.025000001, 0.040] {
        let exact = (t / 0.025f64).powf(0.2);
        assert!((d.thickness_factor(t) - exact).abs() < 1e-15, "{t} m");
    }
    assert_eq!(SnCurve::by_name("B1-air").unwrap().thickness_factor(0.05), 1.0);
    let f = d.thickness_factor(0.040);
    let cycles = rainflow(&cosine_history(0.0, 120e6, 10));
    let scaled: Vec<(f64, f64)> = cycles.iter().map(|&(r, n)| (r * f, n)).collect();
    let (a, b) = (miner_sum(&d, &cycles, f), miner_sum(&d, &scaled, 1.0));
    assert!((a / b - 1.0).abs() < 1e-14, "{a:e} against {b:e}");
    assert!((a / by_hand(10.0, 120e6 * f, 3.0, 12.164) - 1.0).abs() < 1e-12);
}

/// splitmix64: the tests' random numbers, uniform in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A Gaussian stress history (Pa): `n` cosines of equal amplitude (variance
/// σ² in all), frequencies uniform at random within `n` equal bins of
/// [f_lo, f_hi] Hz (so that it does not repeat), random phases; sampled every
/// `dt` s over `duration` s; with its one-sided spectral moments
/// m_j = Σ ½ A² f^j (Hz), j = 0, 1, 2, 4.
fn gaussian_history(seed: u64, sigma: f64, band: (f64, f64), n: usize, dt: f64, duration: f64) -> (Vec<f64>, [f64; 4]) {
    let mut rng = Rng(seed);
    let amp = sigma * (2.0 / n as f64).sqrt();
    let comps: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let f = band.0 + (band.1 - band.0) * (i as f64 + rng.next()) / n as f64;
            (f, 2.0 * PI * rng.next())
        })
        .collect();
    let moment = |j: i32| comps.iter().map(|(f, _)| 0.5 * amp * amp * f.powi(j)).sum::<f64>();
    let samples = (duration / dt) as usize;
    // each component's phasor e^{i(2π f t + φ)} turned by e^{i 2π f dt} a sample,
    // set afresh from cos/sin every 1000 samples against the round-off's drift
    let turn: Vec<(f64, f64)> =
        comps.iter().map(|(f, _)| ((2.0 * PI * f * dt).cos(), (2.0 * PI * f * dt).sin())).collect();
    let mut z: Vec<(f64, f64)> = vec![(0.0, 0.0); n];
    let mut h = Vec::with_capacity(samples + 1);
    for k in 0..=samples {
        if k % 1000 == 0 {
            let t = k as f64 * dt;
            for (zi, (f, phi)) in z.iter_mut().zip(&comps) {
                let a = 2.0 * PI * f * t + phi;
                *zi = (a.cos(), a.sin());
            }
        }
        h.push(amp * z.iter().map(|zi| zi.0).sum::<f64>());
        for (zi, (c, s)) in z.iter_mut().zip(&turn) {
            *zi = (zi.0 * c - zi.1 * s, zi.0 * s + zi.1 * c);
        }
    }
    (h, [moment(0), moment(1), moment(2), moment(4)])
}

/// Γ(1 + m/2) and Γ(1 + m) for m = 3: Γ(2.5) = 3√π/4, Γ(4) = 6.
const GAMMA_2_5: f64 = 1.329_340_388_179_137;
const GAMMA_4: f64 = 6.0;

/// The mean of 10 records' damage over the closed form's, and the standard
/// error of that mean (the records' standard deviation / √10).
fn mean_and_error(ratios: &[f64]) -> (f64, f64) {
    let n = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / n;
    let var = ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Narrow band: σ = 20 MPa in [0.98, 1.02] Hz (64 cosines; spectral width
/// ε = √(1 − m₂²/(m₀m₄)) ≈ 0.023), 10 records of 20,000 s sampled at 64 a
/// period, on D-free-corrosion (m = 3, log a = 11.687): the rainflow damage's
/// mean over the closed form D = ν₀ T (2√2 σ)^m Γ(1 + m/2) / a (ν₀ = √(m₂/m₀),
/// each record's own moments), within three standard errors of the records'
/// scatter (about 2 % each: the envelope is correlated over 1/(0.04 Hz) = 25 s,
/// 800 independent stretches a record) plus 2 % (the closed form counts
/// every peak a cycle of twice its height: an upper bound that rainflow
/// approaches as the band narrows; sampling lowers peaks by up to
/// 1 − cos(π/64) = 0.12 %).
#[test]
fn narrow_band_damage_is_the_rayleigh_closed_form() {
    let c = SnCurve::by_name("D-free-corrosion").unwrap();
    let (sigma, duration) = (20e6, 20_000.0);
    let ratios: Vec<f64> = (0..10)
        .map(|seed| {
            let (h, m) = gaussian_history(1000 + seed, sigma, (0.98, 1.02), 64, 1.0 / 64.0, duration);
            let d = miner_sum(&c, &rainflow(&h), 1.0);
            let nu0 = (m[2] / m[0]).sqrt();
            let closed = nu0 * duration * (2.0 * (2.0 * m[0]).sqrt() / 1e6).powi(3) * GAMMA_2_5 / 10f64.powf(11.687);
            d / closed
        })
        .collect();
    let (mean, se) = mean_and_error(&ratios);
    println!("narrow band: rainflow / closed form {mean:.4} ± {se:.4} (standard error), records {ratios:.4?}");
    assert!((mean - 1.0).abs() < 3.0 * se + 0.02, "{mean} ± {se}");
}

/// Dirlik's damage (Dirlik 1985; the form of Halfpenny's and of the
/// spectral-fatigue literature) for a single slope m = 3, spectral moments
/// m_j (Hz): x_m = (m₁/m₀)√(m₂/m₄), γ = m₂/√(m₀m₄),
/// D₁ = 2(x_m − γ²)/(1 + γ²), R = (γ − x_m − D₁²)/(1 − γ − D₁ + D₁²),
/// D₂ = (1 − γ − D₁ + D₁²)/(1 − R), D₃ = 1 − D₁ − D₂,
/// Q = 1.25(γ − D₃ − D₂R)/D₁; D = E[P] T (2√m₀)^m [D₁ Q^m Γ(1+m) +
/// (√2)^m Γ(1+m/2)(D₂ |R|^m + D₃)] / a, E[P] = √(m₄/m₂) peaks a second.
fn dirlik(m: [f64; 4], duration: f64, log_a: f64) -> f64 {
    let [m0, m1, m2, m4] = m;
    let xm = m1 / m0 * (m2 / m4).sqrt();
    let g = m2 / (m0 * m4).sqrt();
    let d1 = 2.0 * (xm - g * g) / (1.0 + g * g);
    let r = (g - xm - d1 * d1) / (1.0 - g - d1 + d1 * d1);
    let d2 = (1.0 - g - d1 + d1 * d1) / (1.0 - r);
    let d3 = 1.0 - d1 - d2;
    let q = 1.25 * (g - d3 - d2 * r) / d1;
    let peaks = (m4 / m2).sqrt();
    let scale = (2.0 * m0.sqrt() / 1e6).powi(3);
    let integral = d1 * q.powi(3) * GAMMA_4 + 2f64.sqrt().powi(3) * GAMMA_2_5 * (d2 * r.abs().powi(3) + d3);
    peaks * duration * scale * integral / 10f64.powf(log_a)
}

/// Wide band: σ = 20 MPa flat over [0.2, 1.5] Hz (200 cosines; γ = m₂/√(m₀m₄)
/// ≈ 0.77), 10 records of 2,000 s at 100 samples a second, on
/// D-free-corrosion: the rainflow damage's mean over Dirlik's, within three
/// standard errors plus 5 % (Dirlik's formula is an empirical fit to
/// rainflow on simulated histories, within a few per cent on such spectra;
/// measured 1.046 ± 0.004); the narrow-band formula, an upper bound, is 9 %
/// above rainflow here (below 0.95).
#[test]
fn wide_band_damage_is_dirlik_s() {
    let c = SnCurve::by_name("D-free-corrosion").unwrap();
    let (sigma, duration) = (20e6, 2_000.0);
    let mut nb = Vec::new();
    let ratios: Vec<f64> = (0..10)
        .map(|seed| {
            let (h, m) = gaussian_history(2000 + seed, sigma, (0.2, 1.5), 200, 0.01, duration);
            let d = miner_sum(&c, &rainflow(&h), 1.0);
            let closed = (m[2] / m[0]).sqrt() * duration * (2.0 * (2.0 * m[0]).sqrt() / 1e6).powi(3) * GAMMA_2_5
                / 10f64.powf(11.687);
            nb.push(d / closed);
            d / dirlik(m, duration, 11.687)
        })
        .collect();
    let (mean, se) = mean_and_error(&ratios);
    let (nb_mean, _) = mean_and_error(&nb);
    println!("wide band: rainflow / Dirlik {mean:.4} ± {se:.4}, rainflow / narrow band {nb_mean:.4}; {ratios:.4?}");
    assert!((mean - 1.0).abs() < 3.0 * se + 0.05, "{mean} ± {se}");
    assert!(nb_mean < 0.95, "the narrow-band bound: {nb_mean}");
}

/// `riser` with these arguments; its stdout parsed as JSON.
fn riser_json(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// `riser run steel_catenary --heave 2,12 --duration 60 --fatigue
/// D-seawater-cp` with the steel wall (20.6 mm X65): the JSON's worst damage
/// is fatigue.csv's largest, at its S and fibre; the run again with
/// --fatigue-series at that S writes the fibre's axial stress over the
/// window, whose rainflow and Miner's sum by hand (n Δσ^m / a on the JSON's
/// curve, the switch at its n_switch; t < 25 mm: no thickness correction)
/// give the same damage to 1e-12; per year over the window's length and the
/// life with the DFF as §12.5 states them; the worst point lies at the
/// touchdown (within two elements of the touchdown's excursion).
#[test]
fn the_run_s_worst_damage_is_its_stress_history_s() {
    let dir = std::env::temp_dir().join(format!("riser_fatigue_{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let base = [
        "run",
        "steel_catenary",
        "--heave",
        "2,12",
        "--duration",
        "60",
        "--fatigue",
        "D-seawater-cp",
        "--dff",
        "3",
        "--set",
        "wall_thickness=0.0206",
        "--set",
        "yield_stress=448e6",
        "--json",
        "--out",
        d,
    ];
    let first = riser_json(&base);
    let f = &first["steady"]["fatigue"];
    let worst_s = f["worst_s"].as_f64().unwrap();
    let fibre = f["worst_fibre"].as_u64().unwrap() as usize;
    let damage = f["damage"].as_f64().unwrap();
    // fatigue.csv: its largest damage is the JSON's, at its S and fibre
    let csv = std::fs::read_to_string(dir.join("fatigue.csv")).unwrap();
    let rows: Vec<Vec<f64>> =
        csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect()).collect();
    let top = rows.iter().max_by(|a, b| a[2].total_cmp(&b[2])).unwrap();
    assert_eq!((top[0], top[1] as usize, top[2]), (worst_s, fibre, damage));
    // the stress history of that point and fibre, written by the same run again
    let s_arg = worst_s.to_string();
    let mut again = base.to_vec();
    again.extend(["--fatigue-series", &s_arg]);
    let second = riser_json(&again);
    assert_eq!(second["steady"]["fatigue"], *f, "the run is deterministic");
    let series = std::fs::read_to_string(dir.join("fatigue_series.csv")).unwrap();
    let history: Vec<f64> =
        series.lines().skip(1).map(|l| l.split(',').nth(1 + fibre).unwrap().parse().unwrap()).collect();
    let curve = &f["curve"];
    let [m1, la1, m2, la2, n_sw] = ["m1", "log_a1", "m2", "log_a2", "n_switch"].map(|k| curve[k].as_f64().unwrap());
    let s_switch = 10f64.powf((la1 - n_sw.log10()) / m1);
    let by_hand: f64 = rainflow(&history)
        .iter()
        .map(|&(r, n)| {
            let s = r / 1e6;
            if s >= s_switch { n * s.powf(m1) / 10f64.powf(la1) } else { n * s.powf(m2) / 10f64.powf(la2) }
        })
        .sum();
    println!("worst S = {worst_s} m, fibre {fibre}: damage {damage:e}, by hand {by_hand:e}, {} samples", history.len());
    assert!((by_hand / damage - 1.0).abs() < 1e-12, "{by_hand:e} against {damage:e}");
    let window = f["window_length"].as_f64().unwrap();
    let w = first["steady"]["window"].as_array().unwrap();
    assert_eq!(window, w[1].as_f64().unwrap() - w[0].as_f64().unwrap());
    let per_year = damage * 365.25 * 86400.0 / window;
    assert!((f["damage_per_year"].as_f64().unwrap() / per_year - 1.0).abs() < 1e-14);
    assert!((f["life_years"].as_f64().unwrap() * per_year * 3.0 - 1.0).abs() < 1e-14);
    // at the touchdown
    let td = &first["steady"]["touchdown_s"];
    let (lo, hi) = (td[0].as_f64().unwrap(), td[2].as_f64().unwrap());
    let element = 400.0 / first["n_elements"].as_f64().unwrap();
    assert!(worst_s > lo - 2.0 * element && worst_s < hi + 2.0 * element, "worst at {worst_s}, touchdown {lo}..{hi}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A line without stresses (the catenary's flexible pipe) refuses
/// --fatigue, saying why; an unknown curve is refused with the names; --scf
/// below 1 is refused.
#[test]
fn fatigue_is_refused_where_it_has_no_meaning() {
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().unwrap();
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let e = run(&["run", "catenary", "--heave", "2,12", "--duration", "1", "--fatigue", "D-air"]);
    assert!(e.contains("no stresses") && e.contains("flexible pipe"), "{e}");
    let e = run(&["run", "steel_catenary", "--heave", "2,12", "--duration", "1", "--fatigue", "Q-air"]);
    assert!(e.contains("unknown S-N curve") && e.contains("F1-free-corrosion"), "{e}");
    let e = run(&["run", "steel_catenary", "--duration", "1", "--fatigue", "D-air", "--scf", "0.9"]);
    assert!(e.contains("--scf"), "{e}");
}
