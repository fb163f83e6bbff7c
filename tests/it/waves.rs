//! Waves (issue 27; docs/theory.md §13): the kinematics of a regular wave
//! against the closed form of tests/it/common/reference.rs, Wheeler stretching
//! under a crest, the ramp; the spectra's realisation (Hs, Tp, seeds, the
//! variance of a long record); bad input named by its field; `riser waves`
//! and the refusal of a dynamic run with waves until the water's force with
//! waves is built. Run with `--nocapture` to see the measured figures.

use crate::common;
use common::reference;

use riser::loads::waves::{Sea, sea_of};
use riser::math::V3;
use riser::scene::Scene;
use std::f64::consts::PI;
use std::process::Command;

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

/// The built-in `base` scene with a `[waves]` block.
fn scene_with(base: &str, waves: &str) -> Result<Scene, String> {
    let text = format!("{}\n[waves]\n{waves}\n", Scene::builtin(base).unwrap().to_toml());
    Scene::from_toml(&text, "test").map_err(|e| e.to_string())
}

fn sea(base: &str, waves: &str) -> Sea {
    let s = scene_with(base, waves).unwrap();
    sea_of(&s, 0.0).unwrap().unwrap()
}

const G: f64 = 9.81;
/// The catenary's mean water level, m.
const ZS: f64 = 10.0;

// ---- (1) kinematics against the closed form ---------------------------------

#[test]
fn a_regular_wave_has_the_closed_form_kinematics_at_every_depth() {
    // T 10 s, depth 100 m, amplitude 5 m, towards 30 deg, phase 40 deg, phase origin (5, -3)
    let (a, period, d, beta, phi, origin) = (5.0, 10.0, 100.0, 30f64.to_radians(), 40f64.to_radians(), [5.0, -3.0]);
    let s = sea(
        "catenary",
        "kind = \"airy\"\nheight = 10.0\nperiod = 10.0\ndirection = 30.0\nphase = 40.0\ndepth = 100.0\n\
         stretching = \"none\"\nramp = 0.0\norigin = [5.0, -3.0]",
    );
    let omega = 2.0 * PI / period;
    let k_ref = reference::wave_number(omega, d, G);
    let k = s.wave_numbers()[0];
    println!("k = {k:.17} rad/m, the reference's bisection {k_ref:.17} (relative {:.1e})", (k - k_ref).abs() / k_ref);
    assert!((k - k_ref).abs() <= 1e-14 * k_ref);
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for &(x, y) in &[(0.0, 0.0), (37.0, -12.0), (-80.0, 55.0)] {
        for &t in &[0.0, 1.7, 4.2, 7.9, 123.4] {
            let theta = k * ((x - origin[0]) * beta.cos() + (y - origin[1]) * beta.sin()) - omega * t + phi;
            let eta = a * theta.cos();
            assert!((s.elevation(x, y, t) - eta).abs() < 1e-12);
            for zeta in [0.0, -2.0, -10.0, -30.0, -60.0, -99.9] {
                if zeta > eta {
                    continue; // in the air: linear theory holds below the surface only
                }
                let [u, w, du, dw] = reference::airy_kinematics(a, omega, k_ref, d, theta, zeta);
                let p = s.kinematics(&V3::new(x, y, ZS + zeta), t);
                let vel = V3::new(u * beta.cos(), u * beta.sin(), w);
                let acc = V3::new(du * beta.cos(), du * beta.sin(), dw);
                let err = (p.velocity - vel).amax().max((p.acceleration - acc).amax());
                worst = worst.max(err);
                checked += 1;
                assert!(
                    err < 1e-10,
                    "x {x} y {y} t {t} zeta {zeta}: {:?} {:?} vs {vel:?} {acc:?}",
                    p.velocity,
                    p.acceleration
                );
            }
        }
    }
    println!(
        "u, w, du/dt, dw/dt at {checked} points: largest difference from the closed form {worst:.2e} m/s or m/s^2"
    );
}

#[test]
fn deep_water_has_the_exponential_profile() {
    // no depth and no seabed: deep water, k = ω²/g exactly
    let s = sea("catenary", "kind = \"airy\"\nheight = 4.0\nperiod = 8.0\nstretching = \"none\"\nramp = 0.0");
    let omega = 2.0 * PI / 8.0;
    let k = omega * omega / G;
    assert_eq!(s.wave_numbers()[0], k);
    for zeta in [-2.5, -20.0, -80.0] {
        for t in [0.3, 2.9, 5.1] {
            let theta = -omega * t;
            // a depth of 5 km is deep to round-off at this k (tanh kd = 1)
            let [u, w, du, dw] = reference::airy_kinematics(2.0, omega, k, 5000.0, theta, zeta);
            let p = s.kinematics(&V3::new(0.0, 0.0, ZS + zeta), t);
            let err = (p.velocity - V3::new(u, 0.0, w)).amax().max((p.acceleration - V3::new(du, 0.0, dw)).amax());
            assert!(err < 1e-10, "{zeta} {t}: {err}");
        }
    }
}

#[test]
fn under_a_crest_wheeler_gives_the_surface_the_mean_levels_kinematics() {
    let (a, period, d) = (5.0, 10.0, 100.0);
    let omega = 2.0 * PI / period;
    let wheeler = sea("catenary", "kind = \"airy\"\nheight = 10.0\nperiod = 10.0\ndepth = 100.0\nramp = 0.0");
    let linear = sea(
        "catenary",
        "kind = \"airy\"\nheight = 10.0\nperiod = 10.0\ndepth = 100.0\nramp = 0.0\nstretching = \"none\"",
    );
    let k = reference::wave_number(omega, d, G);
    // crests at the origin at t = 0, T, 2T (phase 0); a trough at T/2
    for (t, eta) in [(0.0, a), (period, a), (2.0 * period, a), (0.5 * period, -a)] {
        let theta = -omega * t;
        let at_surface = wheeler.kinematics(&V3::new(0.0, 0.0, ZS + eta), t);
        let mean_level = linear.kinematics(&V3::new(0.0, 0.0, ZS), t);
        let [u, w, du, dw] = reference::airy_kinematics(a, omega, k, d, theta, 0.0);
        let closed = V3::new(u, 0.0, w);
        let to_closed = (at_surface.velocity - closed).amax();
        println!(
            "t = {t} s (eta = {eta} m): Wheeler at the surface u = {:.12} m/s, the closed form at the mean level {u:.12} \
             (difference {to_closed:.1e})",
            at_surface.velocity.x
        );
        assert!(to_closed < 1e-10);
        if eta > 0.0 {
            // under a crest the unstretched linear field reaches the mean level: the same value
            let diff = (at_surface.velocity - mean_level.velocity).amax();
            println!("  the unstretched linear field at the mean level differs by {diff:.1e}");
            assert!(diff < 1e-10);
        }
        assert!((at_surface.acceleration - V3::new(du, 0.0, dw)).amax() < 1e-10);
        // inside the column: the closed form at the stretched height ζ' = d (ζ − η)/(d + η)
        for zeta in [eta - 3.0, -20.0, -70.0] {
            let zp = d * (zeta - eta) / (d + eta);
            let [u, w, _, _] = reference::airy_kinematics(a, omega, k, d, theta, zp);
            let p = wheeler.kinematics(&V3::new(0.0, 0.0, ZS + zeta), t);
            assert!((p.velocity - V3::new(u, 0.0, w)).amax() < 1e-10, "zeta {zeta}");
        }
        // above the crest (in the air) the surface's kinematics, not more
        let above = wheeler.kinematics(&V3::new(0.0, 0.0, ZS + eta + 2.0), t);
        assert!((above.velocity - at_surface.velocity).amax() < 1e-12);
    }
}

#[test]
fn the_ramp_grows_the_kinematics_from_still_water() {
    let ramp = 20.0;
    let s = sea("catenary", "kind = \"airy\"\nheight = 6.0\nperiod = 10.0\ndepth = 100.0\nramp = 20.0");
    let full = sea("catenary", "kind = \"airy\"\nheight = 6.0\nperiod = 10.0\ndepth = 100.0\nramp = 0.0");
    let p = V3::new(12.0, 0.0, ZS - 40.0);
    for t in [0.0, 5.0, 13.0, 20.0, 31.0] {
        let (r, dr) = if t < ramp {
            (0.5 * (1.0 - (PI * t / ramp).cos()), 0.5 * PI / ramp * (PI * t / ramp).sin())
        } else {
            (1.0, 0.0)
        };
        let (a, b) = (s.kinematics(&p, t), full.kinematics(&p, t));
        // deep below the surface, the ramped surface's stretching is a small shift: compare at the
        // ramped stretched height through the unramped field's scaling only where r = 0 or 1
        if r == 0.0 || r == 1.0 {
            assert!((a.velocity - b.velocity * r).amax() < 1e-12, "t {t}");
            assert!((a.acceleration - (b.acceleration * r + b.velocity * dr)).amax() < 1e-12, "t {t}");
        }
        assert!((s.ramped_elevation(p.x, p.y, t) - r * full.elevation(p.x, p.y, t)).abs() < 1e-12);
    }
    // in the middle of the ramp, with the stretching off, exactly r u and r a + ṙ u
    let s = sea(
        "catenary",
        "kind = \"airy\"\nheight = 6.0\nperiod = 10.0\ndepth = 100.0\nramp = 20.0\nstretching = \"none\"",
    );
    let full = sea(
        "catenary",
        "kind = \"airy\"\nheight = 6.0\nperiod = 10.0\ndepth = 100.0\nramp = 0.0\nstretching = \"none\"",
    );
    let t = 7.0;
    let (r, dr) = (0.5 * (1.0 - (PI * t / ramp).cos()), 0.5 * PI / ramp * (PI * t / ramp).sin());
    let (a, b) = (s.kinematics(&p, t), full.kinematics(&p, t));
    assert!((a.velocity - b.velocity * r).amax() < 1e-12);
    assert!((a.acceleration - (b.acceleration * r + b.velocity * dr)).amax() < 1e-12);
}

// ---- (2) spectra -------------------------------------------------------------

fn spectrum_block(kind: &str, gamma: Option<f64>, seed: u64) -> String {
    let g = gamma.map(|g| format!("gamma = {g}\n")).unwrap_or_default();
    format!("kind = \"{kind}\"\nhs = 8.0\ntp = 12.0\n{g}seed = {seed}\ndepth = 100.0")
}

#[test]
fn the_realisations_hs_and_tp_are_the_inputs() {
    let (hs, tp) = (8.0, 12.0);
    let df = (4.0 - 0.5) / tp / 100.0;
    for (kind, gamma) in
        [("jonswap", Some(1.0)), ("jonswap", Some(3.3)), ("jonswap", Some(5.0)), ("pierson_moskowitz", None)]
    {
        let s = sea("catenary", &spectrum_block(kind, gamma, 0));
        let rel = s.hs() / hs - 1.0;
        let fp = 1.0 / s.peak_period();
        println!(
            "{kind} gamma {gamma:?}: Hs = 4 sqrt(m0) = {:.5} m ({:+.3} %), Tp = {:.4} s (peak bin {:.5} Hz, 1/Tp {:.5} Hz)",
            s.hs(),
            100.0 * rel,
            s.peak_period(),
            fp,
            1.0 / tp
        );
        assert!(rel.abs() < 0.01, "{kind} {gamma:?}: Hs {}", s.hs());
        // the peak lies in the bin of the largest component
        assert!((fp - 1.0 / tp).abs() <= 0.5 * df * (1.0 + 1e-12), "{kind} {gamma:?}: peak {fp} Hz");
        assert_eq!(s.components().len(), 100);
    }
}

#[test]
fn the_spectral_density_is_jonswaps_normalised_to_hs() {
    use riser::loads::waves::spectra::Spectrum;
    for gamma in [1.0, 3.3, 5.0] {
        let spec = Spectrum::Jonswap { hs: 8.0, tp: 12.0, gamma };
        for f in [0.05, 0.075, 0.083, 0.09, 0.12, 0.25] {
            let (ours, theirs) = (spec.density(f), reference::jonswap_density(f, 8.0, 12.0, gamma));
            assert!((ours / theirs - 1.0).abs() < 1e-7, "gamma {gamma} f {f}: {ours} vs {theirs}");
        }
    }
}

/// SplitMix64 as Vigna publishes it, written out again here.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e3779b97f4a7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

#[test]
fn the_same_seed_gives_the_same_sea_bit_for_bit_and_another_seed_another() {
    let a = sea("catenary", &spectrum_block("jonswap", Some(3.3), 7));
    let b = sea("catenary", &spectrum_block("jonswap", Some(3.3), 7));
    let c = sea("catenary", &spectrum_block("jonswap", Some(3.3), 8));
    // the phases are 2π U with U the top 53 bits of SplitMix64's draws
    let mut state = 7u64;
    for comp in a.components() {
        let u = (splitmix(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
        assert_eq!(comp.phase.to_bits(), (2.0 * PI * u).to_bits());
    }
    let mut largest: f64 = 0.0;
    for i in 0..4000 {
        let t = 0.37 * i as f64;
        let (ea, eb, ec) = (a.elevation(3.0, -1.0, t), b.elevation(3.0, -1.0, t), c.elevation(3.0, -1.0, t));
        assert_eq!(ea.to_bits(), eb.to_bits(), "t = {t}");
        largest = largest.max((ea - ec).abs());
    }
    println!("seed 7 against seed 8: the records differ by up to {largest:.3} m (Hs 8 m)");
    assert!(largest > 2.0);
}

#[test]
fn the_variance_of_a_long_record_converges_to_m0() {
    // Pierson–Moskowitz Hs 4 m, Tp 10 s in 50 components: equal bins of
    // 0.007 Hz, a record that repeats itself after 142.9 s. The sample
    // variance over N samples differs from m₀ = Σ a²/2 by the means of the
    // cross terms cos((ωᵢ ± ωⱼ) t + …) and of cos(2ωᵢ t + …), each bounded by
    // 1/(N |sin(Δω dt/2)|): the bound B below, which falls as 1/N.
    let s = sea("catenary", "kind = \"pierson_moskowitz\"\nhs = 4.0\ntp = 10.0\ncomponents = 50\nseed = 3");
    let m0 = s.m0();
    let c = s.components();
    let dt = 0.5;
    let mut previous = f64::INFINITY;
    for repeats in [2.0, 20.0, 200.0] {
        let n = (repeats * 142.857 / dt) as usize;
        let eta: Vec<f64> = (0..n).map(|i| s.elevation(0.0, 0.0, i as f64 * dt)).collect();
        let mean = eta.iter().sum::<f64>() / n as f64;
        let var = eta.iter().map(|e| (e - mean) * (e - mean)).sum::<f64>() / n as f64;
        let avg = |w: f64| 1.0 / (n as f64 * (0.5 * w * dt).sin().abs());
        let w: Vec<f64> = c.iter().map(|c| 2.0 * PI * c.frequency).collect();
        let mut bound = 0.0;
        let mut mean_bound = 0.0;
        for i in 0..c.len() {
            bound += 0.5 * c[i].amplitude * c[i].amplitude * avg(2.0 * w[i]);
            mean_bound += c[i].amplitude * avg(w[i]);
            for j in 0..c.len() {
                if i != j {
                    bound += 0.5 * c[i].amplitude * c[j].amplitude * (avg(w[i] - w[j]) + avg(w[i] + w[j]));
                }
            }
        }
        bound += mean_bound * mean_bound;
        let err = (var - m0).abs() / m0;
        println!(
            "{:>7.0} s ({repeats} repeats): sample variance {var:.6} m^2, m0 {m0:.6} m^2, relative error {err:.2e} (bound {:.2e})",
            n as f64 * dt,
            bound / m0
        );
        assert!(err <= bound / m0, "the error {err} exceeds its bound {}", bound / m0);
        assert!(err < previous);
        previous = err;
    }
    assert!(previous < 1e-3, "after 200 repeats the variance is within {previous} of m0");
}

#[test]
fn a_components_table_reproduces_a_sea() {
    // riser waves --out writes the realisation as a table; read back, the same sea
    let dir = std::env::temp_dir().join(format!("riser-waves-table-{}", std::process::id()));
    let out = riser(&[
        "waves",
        "catenary",
        "--set",
        "wave_kind=jonswap",
        "--set",
        "wave_hs=6",
        "--set",
        "wave_tp=11",
        "--set",
        "wave_seed=5",
        "--set",
        "wave_direction=20",
        "--duration",
        "600",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let hs = v["hs"].as_f64().unwrap();
    assert!((hs / 6.0 - 1.0).abs() < 0.01, "{hs}");
    assert_eq!(v["components"].as_array().unwrap().len(), 100);
    for f in ["elevation.csv", "spectrum.csv", "components.csv", "waves.svg"] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let table = dir.join("components.csv");
    let spectral = sea("catenary", "kind = \"jonswap\"\nhs = 6.0\ntp = 11.0\nseed = 5\ndirection = 20.0");
    let read = sea("catenary", &format!("kind = \"table\"\nfile = \"{}\"\nramp = 11.0", table.display()));
    for i in 0..500 {
        let t = 1.3 * i as f64;
        assert!((spectral.elevation(7.0, 2.0, t) - read.elevation(7.0, 2.0, t)).abs() < 1e-12);
    }
    // elevation.csv: the realisation at the phase origin, and ramped over Tp
    let text = std::fs::read_to_string(dir.join("elevation.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,elevation,ramped"));
    for line in lines.take(400) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(r[1], spectral.elevation(0.0, 0.0, r[0]));
        let ramp = if r[0] < 11.0 { 0.5 * (1.0 - (PI * r[0] / 11.0).cos()) } else { 1.0 };
        assert!((r[2] - ramp * r[1]).abs() < 1e-12);
    }
    // spectrum.csv: the components' a²/(2Δf) is the target at the bin centres,
    // and the record's periodogram per band is close to it near the peak
    let text = std::fs::read_to_string(dir.join("spectrum.csv")).unwrap();
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    for r in &rows {
        assert!((r[4] / r[3] - 1.0).abs() < 1e-12);
    }
    std::fs::remove_dir_all(&dir).ok();
}

// ---- (7) bad input, named by its field ---------------------------------------

fn refused(base: &str, waves: &str) -> String {
    scene_with(base, waves).expect_err("refused")
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "'{p}' missing from:\n{msg}");
    }
}

#[test]
fn bad_waves_are_refused_naming_the_field() {
    let e = refused("catenary", "kind = \"airy\"\nheight = -1.0\nperiod = 10.0");
    assert_mentions(&e, &["waves.height", "is outside [0, 40] m"]);
    let e = refused("catenary", "kind = \"airy\"\nheight = 2.0\nperiod = -10.0");
    assert_mentions(&e, &["waves.period", "is outside [1, 40] s"]);
    let e = refused("catenary", "kind = \"airy\"\nheight = 2.0");
    assert_mentions(&e, &["waves.period", "missing"]);
    let e = refused("catenary", "kind = \"jonswap\"\nhs = 12.0\ntp = 5.0");
    assert_mentions(&e, &["waves.tp", "1/15", "Tp >= 10.737 s"]);
    let e = refused("catenary", "kind = \"pierson_moskowitz\"\nhs = 2.0\ntp = 10.0\nf_min = 0.2\nf_max = 0.5");
    assert_mentions(&e, &["waves.tp", "outside the components' range"]);
    let e = refused("catenary", "kind = \"jonswap\"\nhs = 2.0\ntp = 10.0\ngamma = 0.5");
    assert_mentions(&e, &["waves.gamma", "is outside [1, 10]"]);
    let e = refused("catenary", "kind = \"stokes\"\nheight = 2.0");
    assert_mentions(&e, &["stokes", "airy"]);
    let e = refused("catenary", "kind = \"airy\"\nhieght = 2.0\nperiod = 10.0");
    assert_mentions(&e, &["hieght"]);
    // the depth: against the seabed, and deeper than the anchor without one
    let e = refused("steel_catenary", "kind = \"airy\"\nheight = 2.0\nperiod = 10.0\ndepth = 50.0");
    assert_mentions(&e, &["waves.depth", "contradicts the seabed"]);
    let e = refused("catenary", "kind = \"airy\"\nheight = 2.0\nperiod = 10.0\ndepth = 50.0");
    assert_mentions(&e, &["waves.depth", "shallower than the anchor"]);
    let e = refused("catenary", "kind = \"airy\"\nheight = 30.0\nperiod = 10.0\ndepth = 12.0\n");
    assert!(e.contains("waves.depth") || e.contains("waves.height"), "{e}");
    // the steel catenary's own seabed is the depth
    let s = scene_with("steel_catenary", "kind = \"airy\"\nheight = 2.0\nperiod = 10.0").unwrap();
    let bed = s.seabed.as_ref().unwrap().z;
    assert_eq!(riser::loads::waves::depth_of(&s), Some(s.environment.water_surface_z - bed));
    assert!(
        scene_with("steel_catenary", &format!("kind = \"airy\"\nheight = 2.0\nperiod = 10.0\ndepth = {}", 10.0 - bed))
            .is_ok()
    );
}

#[test]
fn a_bad_components_file_is_named_with_its_line_and_column() {
    let dir = std::env::temp_dir().join(format!("riser-waves-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        ("no_direction.csv", "frequency,amplitude,phase\n0.1,1,0\n", vec!["waves.file", "line 1", "'direction'"]),
        (
            "text.csv",
            "frequency,amplitude,phase,direction\n0.1,1,0,0\n0.12,1,north,0\n",
            vec!["waves.file", "line 3", "column 'phase'", "'north'"],
        ),
        ("short.csv", "frequency,amplitude,phase,direction\n0.1,1,0\n", vec!["waves.file", "line 2", "3 values"]),
    ];
    for (name, text, parts) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let e = refused("catenary", &format!("kind = \"table\"\nfile = \"{}\"", path.display()));
        assert_mentions(&e, &parts);
    }
    let e = refused("catenary", "kind = \"table\"\nfile = \"/no/such/components.csv\"");
    assert_mentions(&e, &["waves.file", "cannot read"]);
    let e = refused("catenary", "kind = \"table\"");
    assert_mentions(&e, &["waves.file", "missing"]);
    // a relative path in a scene file is the file's folder's
    std::fs::write(dir.join("sea.csv"), "frequency,amplitude,phase,direction\n0.1,1.5,30,0\n").unwrap();
    let text =
        format!("{}\n[waves]\nkind = \"table\"\nfile = \"sea.csv\"\n", Scene::builtin("catenary").unwrap().to_toml());
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    let s = Scene::load(dir.join("scene.toml").to_str().unwrap()).unwrap();
    assert_eq!(sea_of(&s, 0.0).unwrap().unwrap().components()[0].amplitude, 1.5);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_command_line_names_bad_wave_parameters() {
    let out =
        riser(&["waves", "catenary", "--set", "wave_kind=airy", "--set", "wave_height=-1", "--set", "wave_period=10"]);
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert_mentions(&e, &["--set wave_height", "is outside [0, 40] m"]);
    let out = riser(&["waves", "catenary", "--set", "wave_kind=stokes"]);
    assert_mentions(&String::from_utf8_lossy(&out.stderr), &["--set wave_kind", "'stokes' is not a kind of waves"]);
    let out = riser(&["waves", "catenary", "--set", "wave_stretching=linear"]);
    assert_mentions(&String::from_utf8_lossy(&out.stderr), &["--set wave_stretching", "wheeler, vertical or none"]);
    let out = riser(&["waves", "catenary", "--set", "wave_components=1.5"]);
    assert_mentions(&String::from_utf8_lossy(&out.stderr), &["--set wave_components", "whole number"]);
    // a wave parameter without a kind: still water, said so
    let out = riser(&["statics", "catenary", "--set", "wave_hs=3"]);
    assert!(out.status.success());
    assert_mentions(&String::from_utf8_lossy(&out.stderr), &["waves.hs given, but the waves' kind is none"]);
}

/// A run in waves through the CLI: the time series' `wave_elevation` is
/// the sea's ramped elevation at the phase origin, r(t) H/2 cos(−ωt) with
/// the ramp r of one period (13.1), to the CSV's 17 digits; the energy
/// balance closes with the waves' work in `work_hydro`.
#[test]
fn a_run_in_waves_reports_the_seas_elevation_and_closes_its_energy_balance() {
    let sets = ["--set", "wave_kind=airy", "--set", "wave_height=4", "--set", "wave_period=9"];
    let dir = std::env::temp_dir().join(format!("riser-waves-run-{}", std::process::id()));
    let mut args = vec!["run", "catenary", "--duration", "20", "--json", "--out", dir.to_str().unwrap()];
    args.extend(sets);
    let out = riser(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let (it, ie, iw, ib) = (col("t"), col("wave_elevation"), col("work_hydro"), col("total_energy"));
    let w = 2.0 * PI / 9.0;
    let (mut rows, mut moved) = (0, 0.0f64);
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let t = v[it];
        let r = if t < 9.0 { 0.5 * (1.0 - (PI * t / 9.0).cos()) } else { 1.0 };
        assert!((v[ie] - r * 2.0 * (-w * t).cos()).abs() < 1e-12, "t = {t}: {}", v[ie]);
        moved = moved.max(v[iw].abs());
        rows += 1;
        let _ = v[ib];
    }
    assert_eq!(rows, 401);
    // the waves work on the line, and the balance closes to round-off of what was exchanged
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (residual, exchanged) =
        (v["energy_balance_residual"].as_f64().unwrap(), v["energy_exchanged"].as_f64().unwrap());
    assert!(moved > 100.0, "the waves did {moved} J of work");
    assert!(residual.abs() < 1e-7 * exchanged, "{residual} J of {exchanged} J");
    let _ = std::fs::remove_dir_all(&dir);
    // still water runs as before, wave_elevation 0
    let mut args = vec!["waves", "catenary", "--json"];
    args.extend(sets);
    let out = riser(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["kind"], "airy");
    assert!((v["hs"].as_f64().unwrap() - 4.0 * (0.5f64 * 4.0).sqrt()).abs() < 1e-12);
    assert_eq!(v["tp"].as_f64().unwrap(), 9.0);
    assert_eq!(v["ramp"].as_f64().unwrap(), 9.0);
    assert!(v["depth"].is_null());
    let out = riser(&["waves", "catenary"]);
    assert!(!out.status.success());
    assert_mentions(&String::from_utf8_lossy(&out.stderr), &["has no waves"]);
}

#[test]
fn implausible_waves_warn() {
    // a 20 m, 8 s wave in deep water: L = g T²/2π = 99.9 m, Miche's limit 0.142 L = 14.19 m
    let s = scene_with("catenary", "kind = \"airy\"\nheight = 20.0\nperiod = 8.0").unwrap();
    let w = riser::loads::waves::warnings(&s);
    assert!(
        w.iter().any(|m| m.contains("waves.height") && m.contains("breaking limit") && m.contains("14.19")),
        "{w:?}"
    );
    assert!(
        riser::loads::waves::warnings(&scene_with("catenary", "kind = \"airy\"\nheight = 10.0\nperiod = 8.0").unwrap())
            .is_empty()
    );
    // keys another kind takes are named as ignored
    let s = scene_with("catenary", "kind = \"airy\"\nheight = 2.0\nperiod = 8.0\nhs = 3.0\nseed = 4").unwrap();
    let w = s.wave_warnings();
    assert!(w.len() == 1 && w[0].contains("waves.hs, waves.seed ignored") && w[0].contains("'airy'"), "{w:?}");
}

/// A sea of n components in equal bins repeats its envelope after
/// n / (f_max − f_min) = 1/Δf (issue 50: a JONSWAP sea of 100 components
/// repeats after 286 s, and a run longer than that said nothing): the
/// envelope |Σ a e^{i(2π f t + φ)}| at t and t + 1/Δf agrees to round-off;
/// a run longer than the period is warned of with the components it would
/// need, one shorter is not.
#[test]
fn a_sea_that_repeats_within_the_run_is_warned_of() {
    use riser::loads::waves::{repeat_period, repeat_warning};
    let s = sea("catenary", "kind = \"jonswap\"\nhs = 2.0\ntp = 10.0\ncomponents = 10");
    let c = s.components();
    let (lo, hi) =
        (c.iter().map(|c| c.frequency).fold(f64::MAX, f64::min), c.iter().map(|c| c.frequency).fold(0.0, f64::max));
    // bin centres: f_max − f_min = (n − 1) Δf
    let period = repeat_period(c).unwrap();
    assert!((period - 9.0 / (hi - lo)).abs() < 1e-9 * period, "{period}");
    let envelope = |t: f64| {
        let (re, im) = c.iter().fold((0.0, 0.0), |(re, im), c| {
            let th = 2.0 * PI * c.frequency * t + c.phase;
            (re + c.amplitude * th.cos(), im + c.amplitude * th.sin())
        });
        (re * re + im * im).sqrt()
    };
    for t in [0.0, 3.7, 11.2, 40.0] {
        assert!((envelope(t) - envelope(t + period)).abs() < 1e-9, "{t}");
    }
    assert!(repeat_warning(c, 0.99 * period).is_none());
    let w = repeat_warning(c, 30.0).unwrap();
    assert!(w.contains(&format!("repeat every {period:.1} s")) && w.contains("at least 11"), "{w}");
    // through `riser run`: the steady window's warnings
    let run = |duration: &str| {
        let o = riser(&[
            "run",
            "catenary",
            "--set",
            "wave_kind=jonswap",
            "--set",
            "wave_hs=2",
            "--set",
            "wave_tp=10",
            "--set",
            "wave_components=10",
            "--set",
            "n_elements=8",
            "--set",
            "time_step=0.1",
            "--duration",
            duration,
            "--json",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        j["steady"]["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|w| w.as_str().unwrap().contains("repeat every"))
            .count()
    };
    assert_eq!((run("20"), run("30")), (0, 1));
}

/// `spacing = "energy"` (docs/theory.md (13.11a-c)): a JONSWAP sea of 200
/// components has no repeat period and is not warned of; the envelope of its
/// autocorrelation (13.11c) over a 3-hour record stays far from 1 (200
/// random frequencies: its lags' sums are of ~200 unit phasors of random
/// angles, |mean| ~ 1/√200 ≈ 0.07 and its largest over the record's ~3,000
/// independent lags about 0.2; measured 0.22), where equal bins return to 1 at
/// 1/Δf (checked by `autocorrelation_peak` itself, against the repeat period);
/// the realised m₀ the band's. The envelope bounds the record's own
/// autocorrelation: |ρ(τ)| computed from a sampled record of the same
/// components never exceeds it (the test's independent sum, 20 lags).
#[test]
fn energy_bins_make_a_three_hour_sea_that_does_not_repeat() {
    use riser::loads::waves::{autocorrelation_peak, repeat_period, repeat_warning};
    let keys = "kind = \"jonswap\"\nhs = 4.0\ntp = 10.0\ncomponents = 200";
    let energy = sea("catenary", &format!("{keys}\nspacing = \"energy\""));
    let equal = sea("catenary", keys);
    let (c, e) = (energy.components(), equal.components());
    assert!(repeat_period(c).is_none() && repeat_warning(c, 10_800.0).is_none());
    let period = repeat_period(e).unwrap();
    let (at_period, _) = autocorrelation_peak(e, period, period + 1e-9).unwrap();
    assert!(at_period > 1.0 - 1e-9, "{at_period} at the period {period} s");
    // the search's samples are 1/(8 (f_max − f_min)) apart: found within one
    let (found, lag) = autocorrelation_peak(e, 60.0, 1.5 * period).unwrap();
    let dt = 1.0 / (8.0 * (e[e.len() - 1].frequency - e[0].frequency));
    assert!(found > 0.95 && (lag - period).abs() <= dt, "{found} at {lag} s (period {period} s)");
    let (peak, lag) = autocorrelation_peak(c, 60.0, 10_800.0).unwrap();
    println!(
        "energy bins, 200 components: envelope beyond 60 s at most {peak:.3} (lag {lag:.1} s); equal bins 1 at {period:.1} s"
    );
    assert!(peak < 0.3, "{peak} at {lag} s");
    // m₀ of the band: the trapezoid of (13.11a) against the midpoint rule of (13.11)
    assert!((energy.m0() / equal.m0() - 1.0).abs() < 1e-4, "{} {}", energy.m0(), equal.m0());
    // |ρ(τ)| of the components (Σ a²cos(2π f τ)/Σ a²) within the envelope
    let total: f64 = c.iter().map(|c| c.amplitude * c.amplitude).sum();
    for k in 0..20 {
        let tau = 60.0 + 537.3 * k as f64;
        let rho: f64 =
            c.iter().map(|c| c.amplitude * c.amplitude * (2.0 * PI * c.frequency * tau).cos()).sum::<f64>() / total;
        let (bound, _) = autocorrelation_peak(c, tau, tau + 1e-9).unwrap();
        assert!(rho.abs() <= bound + 1e-12, "{tau}: {rho} > {bound}");
    }
}
