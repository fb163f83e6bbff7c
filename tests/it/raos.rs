//! One sea, and the vessel moving with it (issue 50; docs/theory.md §13.7,
//! §14.5; docs/guide/waves.md "One sea"): the components table `riser waves
//! --out` writes realises the same sea when a scene reads it back; the rule
//! for moving the phase origin, its sign checked; a regular wave moves the
//! hang-off of `riser run` by exactly r(t) A |RAO| cos(θ + phase) (closed
//! form, the wave number of deep water ω²/g); in a JONSWAP sea the vessel's
//! heave record has Fourier amplitudes aᵢ |RAO(fᵢ)| at the component
//! frequencies (the RAO interpolated here, independently). Run with
//! `--nocapture` to see the measured figures.

use riser::loads::waves::{Component, Sea, SeaSettings, Stretching, sea_of};
use riser::scene::Scene;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

fn riser(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_riser")).args(args).output().expect("riser runs")
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("riser-raos-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The built-in catenary's scene file with `extra` blocks appended, written as `dir/name`.
fn scene_file(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let base = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/catenary.toml")).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, format!("{base}\n{extra}\n")).unwrap();
    p
}

/// A CSV's columns by name (`#` lines skipped).
fn columns(path: &Path) -> std::collections::HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); head.len()];
    for l in lines {
        for (c, v) in cols.iter_mut().zip(l.split(',')) {
            c.push(v.parse().unwrap());
        }
    }
    head.into_iter().zip(cols).collect()
}

/// `riser waves --out` writes components.csv with the phase origin and the
/// time origin stated; a scene of kind `table` reading it (same origin, same
/// water) gives the same elevation as the scene that realised it, at points
/// 400 m apart over an hour, to 1e-9 m.
#[test]
fn the_exported_table_realises_the_same_sea() {
    let dir = temp_dir("table");
    let waves = "[waves]\nkind = \"jonswap\"\nhs = 4.0\ntp = 10.0\ndirection = 30.0\nseed = 7\ncomponents = 80\n\
                 depth = 150.0\norigin = [25.0, -15.0]";
    let source = scene_file(&dir, "source.toml", waves);
    let out = riser(&["waves", source.to_str().unwrap(), "--duration", "60", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = std::fs::read_to_string(dir.join("components.csv")).unwrap();
    let comments: Vec<&str> = table.lines().filter(|l| l.starts_with('#')).collect();
    let said = comments.join("\n");
    for needle in ["phase origin (x0, y0) = (25, -15) m", "t = 0 is the start of the run", "depth 150 m", "phase' ="] {
        assert!(said.contains(needle), "components.csv does not say '{needle}':\n{said}");
    }
    assert_eq!(table.lines().find(|l| !l.starts_with('#')).unwrap(), "frequency,amplitude,phase,direction");
    let reread = scene_file(
        &dir,
        "reread.toml",
        "[waves]\nkind = \"table\"\nfile = \"components.csv\"\ndepth = 150.0\norigin = [25.0, -15.0]",
    );
    let a = sea_of(&Scene::load(source.to_str().unwrap()).unwrap(), 0.0).unwrap().unwrap();
    let b = sea_of(&Scene::load(reread.to_str().unwrap()).unwrap(), 0.0).unwrap().unwrap();
    assert_eq!(a.components().len(), 80);
    assert_eq!(b.components().len(), 80);
    let mut worst = 0.0f64;
    for x in [-200.0, -13.0, 0.0, 25.0, 190.0] {
        for y in [-200.0, 0.0, 77.0, 200.0] {
            for k in 0..=60 {
                let t = 60.0 * k as f64;
                worst = worst.max((a.elevation(x, y, t) - b.elevation(x, y, t)).abs());
            }
        }
    }
    println!("the exported table against the realisation: largest difference {worst:.2e} m (Hs 4 m)");
    assert!(worst < 1e-9, "{worst}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Moving the phase origin from (x₀, y₀) to (x₀', y₀'): the phases become
/// φ' = φ + k((x₀' − x₀) cos β + (y₀' − y₀) sin β) and the sea is the same
/// (1e-9 m); the opposite sign is another sea (metres apart). Moving the
/// time origin to t' = t − t₀: φ' = φ − ω t₀.
#[test]
fn moving_the_phase_origin_keeps_the_sea_with_the_stated_sign() {
    let components: Vec<Component> = (0..12)
        .map(|i| Component {
            frequency: 0.06 + 0.013 * i as f64,
            amplitude: 0.3 + 0.05 * i as f64,
            phase: 0.7 * i as f64,
            direction: (20.0 + 15.0 * i as f64).to_radians(),
        })
        .collect();
    let settings = |origin: [f64; 2]| SeaSettings {
        depth: Some(120.0),
        gravity: 9.81,
        surface_z: 0.0,
        origin,
        stretching: Stretching::Wheeler,
        ramp: riser::loads::waves::Ramp::NONE,
    };
    let (o, o2) = ([10.0, -40.0], [-65.0, 30.0]);
    let a = Sea::new(components.clone(), settings(o));
    let k = a.wave_numbers();
    let moved = |sign: f64| {
        let c: Vec<Component> = components
            .iter()
            .zip(&k)
            .map(|(c, k)| Component {
                phase: c.phase + sign * k * ((o2[0] - o[0]) * c.direction.cos() + (o2[1] - o[1]) * c.direction.sin()),
                ..*c
            })
            .collect();
        Sea::new(c, settings(o2))
    };
    let (right, wrong) = (moved(1.0), moved(-1.0));
    let t0 = 37.5;
    let later = Sea::new(
        components.iter().map(|c| Component { phase: c.phase - 2.0 * PI * c.frequency * t0, ..*c }).collect(),
        settings(o),
    );
    let (mut same, mut other, mut shifted) = (0.0f64, 0.0f64, 0.0f64);
    for (x, y) in [(0.0, 0.0), (10.0, -40.0), (-65.0, 30.0), (140.0, 90.0)] {
        for i in 0..50 {
            let t = 3.7 * i as f64;
            same = same.max((a.elevation(x, y, t) - right.elevation(x, y, t)).abs());
            other = other.max((a.elevation(x, y, t) - wrong.elevation(x, y, t)).abs());
            shifted = shifted.max((a.elevation(x, y, t + t0) - later.elevation(x, y, t)).abs());
        }
    }
    println!(
        "origin moved: {same:.2e} m with the stated sign, {other:.3} m with the other; time moved {shifted:.2e} m"
    );
    assert!(same < 1e-9 && shifted < 1e-9, "{same} {shifted}");
    assert!(other > 0.5, "{other}");
}

/// θ of (13.1) at (x, y): k((x − x₀) cos β + (y − y₀) sin β) − ω t + φ.
fn theta(k: f64, omega: f64, beta: f64, phi: f64, origin: [f64; 2], p: [f64; 2], t: f64) -> f64 {
    k * ((p[0] - origin[0]) * beta.cos() + (p[1] - origin[1]) * beta.sin()) - omega * t + phi
}

/// A regular wave (H 3 m, T 10 s, 30°, phase 40°, deep water, phase origin
/// (5, 3) m) and a vessel whose hang-off is at ρ = (20, −6, 4) m from its
/// reference point, with surge, sway, heave and pitch RAOs at 0.1 Hz, 30°:
/// `riser run`'s hang-off moves by u + (R_y(pitch) − I) ρ with each degree of
/// freedom r(t) A |RAO| cos(θ + phase), θ at the reference point (−20, 6) m
/// and k = ω²/g, to 1e-9 m over the run, the ramp included; the RAO phase is
/// a lag (the motion peaks phase/ω after the crest).
#[test]
fn a_regular_wave_moves_the_hang_off_by_its_raos_exactly() {
    let dir = temp_dir("regular");
    let raos = "dof,frequency,direction,amplitude,phase\n\
                surge,0.1,30,0.7,-95\nsway,0.1,30,0.4,80\nheave,0.1,30,0.9,-20\npitch,0.1,30,0.012,110\n";
    std::fs::write(dir.join("raos.csv"), raos).unwrap();
    let scene = scene_file(
        &dir,
        "scene.toml",
        "[waves]\nkind = \"airy\"\nheight = 3.0\nperiod = 10.0\ndirection = 30.0\nphase = 40.0\nramp = 4.0\n\
         origin = [5.0, 3.0]\n\n[hang_off]\noffset = [20.0, -6.0, 4.0]\n\n[vessel]\nraos = \"raos.csv\"",
    );
    let out = riser(&["run", scene.to_str().unwrap(), "--duration", "12", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("the vessel moves on its RAOs (surge, sway, heave, pitch)"));
    let c = columns(&dir.join("timeseries.csv"));
    let (omega, g) = (2.0 * PI / 10.0, 9.81);
    let k = omega * omega / g;
    let (beta, phi) = (30f64.to_radians(), 40f64.to_radians());
    let rho = [20.0, -6.0, 4.0];
    let mut worst = 0.0f64;
    for (i, &t) in c["t"].iter().enumerate() {
        let r = if t < 4.0 { 0.5 * (1.0 - (PI * t / 4.0).cos()) } else { 1.0 };
        let th = theta(k, omega, beta, phi, [5.0, 3.0], [-rho[0], -rho[1]], t);
        let dof = |a: f64, p: f64| r * 1.5 * a * (th + p.to_radians()).cos();
        let (surge, sway, heave, pitch) = (dof(0.7, -95.0), dof(0.4, 80.0), dof(0.9, -20.0), dof(0.012, 110.0));
        // R_y(pitch) ρ − ρ
        let (sp, cp) = pitch.sin_cos();
        let hang = [surge + cp * rho[0] + sp * rho[2] - rho[0], sway, heave - sp * rho[0] + cp * rho[2] - rho[2]];
        for (name, want) in [("surge", surge), ("sway", sway), ("heave", heave), ("pitch", pitch)] {
            worst = worst.max((c[name][i] - want).abs());
        }
        for (j, name) in ["hang_off_x", "hang_off_y", "hang_off_z"].iter().enumerate() {
            worst = worst.max((c[*name][i] - hang[j]).abs());
        }
        assert_eq!(c["roll"][i], 0.0);
    }
    println!("a regular wave on RAOs: the hang-off against the closed form, largest difference {worst:.2e} m");
    assert!(worst < 1e-9, "{worst}");
    // the lag: with a heave RAO of phase 90 the heave peaks a quarter period after the crest at the reference point
    let crest = (theta(k, omega, beta, phi, [5.0, 3.0], [-rho[0], -rho[1]], 0.0) / omega).rem_euclid(10.0);
    let peak_heave = |t: f64| (theta(k, omega, beta, phi, [5.0, 3.0], [-rho[0], -rho[1]], t) + PI / 2.0).cos();
    assert!((peak_heave(crest + 2.5) - 1.0).abs() < 1e-12);
    std::fs::remove_dir_all(&dir).ok();
}

/// A table that does not cover the sea is refused, naming the component and the table's span.
#[test]
fn a_sea_outside_the_table_is_refused() {
    let dir = temp_dir("span");
    std::fs::write(
        dir.join("raos.csv"),
        "dof,frequency,direction,amplitude,phase\nheave,0.05,0,1,0\nheave,0.08,0,1,0\n",
    )
    .unwrap();
    let scene = scene_file(
        &dir,
        "scene.toml",
        "[waves]\nkind = \"airy\"\nheight = 2.0\nperiod = 10.0\n\n[vessel]\nraos = \"raos.csv\"",
    );
    let out = riser(&["run", scene.to_str().unwrap(), "--duration", "1"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("vessel.raos: the sea's component at 0.1 Hz") && err.contains("0.05 to 0.08 Hz"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A JONSWAP sea (Hs 3 m, Tp 9 s, 60 components from 0.05 to 0.35 Hz, so
/// that a record of 2/Δf = 400 s holds a whole number of each component's
/// periods; no ramp) and a heave RAO of five frequencies: the heave record
/// `riser waves --out` writes (the motion `riser run` drives) has at each
/// component frequency the Fourier amplitude aᵢ |RAO(fᵢ)| and phase
/// θᵢ(0) + phase(fᵢ) (the RAO interpolated linearly here), to 1e-9 of
/// the largest; its variance is Σ aᵢ² |RAO|² / 2, the |RAO|² S of the sea.
#[test]
fn in_a_jonswap_sea_the_heave_record_has_the_components_through_the_rao() {
    let dir = temp_dir("jonswap");
    let freq = [0.04, 0.1, 0.15, 0.25, 0.4];
    let amp = [1.0, 0.95, 0.6, 0.2, 0.05];
    let pha = [0.0, -10.0, -60.0, -150.0, 160.0];
    let mut raos = String::from("dof,frequency,direction,amplitude,phase\n");
    for i in 0..5 {
        raos += &format!("heave,{},0,{},{}\nheave,{},180,{},{}\n", freq[i], amp[i], pha[i], freq[i], amp[i], pha[i]);
    }
    std::fs::write(dir.join("raos.csv"), raos).unwrap();
    let scene = scene_file(
        &dir,
        "scene.toml",
        "[waves]\nkind = \"jonswap\"\nhs = 3.0\ntp = 9.0\ncomponents = 60\nf_min = 0.05\nf_max = 0.35\nseed = 3\n\
         ramp = 0.0\n\n[hang_off]\noffset = [15.0, 0.0, 0.0]\n\n[vessel]\nraos = \"raos.csv\"",
    );
    let out = riser(&[
        "waves",
        scene.to_str().unwrap(),
        "--duration",
        "400",
        "--step",
        "0.25",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let m = columns(&dir.join("vessel_motion.csv"));
    let (t, heave) = (&m["t"], &m["heave"]);
    assert_eq!(t.len(), 1600);
    let sea = sea_of(&Scene::load(scene.to_str().unwrap()).unwrap(), 0.0).unwrap().unwrap();
    let interp = |f: f64| {
        let i = freq.iter().rposition(|x| *x <= f).unwrap();
        let w = (f - freq[i]) / (freq[i + 1] - freq[i]);
        let mut dp = pha[i + 1] - pha[i];
        if dp > 180.0 {
            dp -= 360.0;
        } else if dp <= -180.0 {
            dp += 360.0;
        }
        ((1.0 - w) * amp[i] + w * amp[i + 1], pha[i] + w * dp)
    };
    let n = t.len() as f64;
    let (mut worst, mut largest, mut variance) = (0.0f64, 0.0f64, 0.0);
    for (c, k) in sea.components().iter().zip(sea.wave_numbers()) {
        let omega = 2.0 * PI * c.frequency;
        let (re, im) = t
            .iter()
            .zip(heave)
            .fold((0.0, 0.0), |(re, im), (t, h)| (re + h * (omega * t).cos(), im + h * (omega * t).sin()));
        // h = A cos(ψ − ω t) = A cos ψ cos ωt + A sin ψ sin ωt
        let (a_cos, a_sin) = (2.0 * re / n, 2.0 * im / n);
        let (r, p) = interp(c.frequency);
        let psi = k * (-15.0 * c.direction.cos()) + c.phase + p.to_radians();
        let want = c.amplitude * r;
        worst = worst.max((a_cos - want * psi.cos()).abs()).max((a_sin - want * psi.sin()).abs());
        largest = largest.max(want);
        variance += 0.5 * want * want;
    }
    let measured = heave.iter().map(|h| h * h).sum::<f64>() / n;
    println!(
        "JONSWAP on a heave RAO: Fourier amplitudes against a_i |RAO(f_i)|, largest difference {worst:.2e} m \
         (largest amplitude {largest:.3} m); variance {measured:.6} m^2 against sum |RAO|^2 a^2/2 = {variance:.6}"
    );
    assert!(worst < 1e-9 * largest.max(1.0), "{worst}");
    assert!((measured - variance).abs() < 1e-9 * variance);
    std::fs::remove_dir_all(&dir).ok();
}
