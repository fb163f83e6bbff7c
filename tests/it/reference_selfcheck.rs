use crate::common;
use common::reference::*;

// Self-checks of the independent reference solutions in
// `tests/it/common/reference.rs` against literature values, closed forms and
// each other. Every assertion states its tolerance; run with `--nocapture`
// to see the computed values.

use std::f64::consts::PI;

/// Sea-water density [kg/m^3].
const RHO_WATER: f64 = 1025.0;
/// Gravitational acceleration [m/s^2].
const G: f64 = 9.81;

/// Submerged weight per unit length [N/m] of a pipe of mass `mass` [kg/m]
/// and outer diameter `diameter` [m].
fn submerged_weight(mass: f64, diameter: f64) -> f64 {
    (mass - RHO_WATER * PI * diameter * diameter / 4.0) * G
}

/// Relative difference `|a - b| / |b|`.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

// --- Uniform catenary test case (free-hanging steel riser) ------------------

const CAT_LENGTH: f64 = 100.0;
const CAT_EA: f64 = 7.96e8;
const CAT_SPAN: f64 = 60.0;
const CAT_DZ: f64 = -70.0;

fn cat_w() -> f64 {
    submerged_weight(226.7, 0.3172)
}

// --- Lazy-wave test case ------------------------------------------------------

const LW_EA: f64 = 4.58e8;
const LW_SPAN: f64 = 50.0;
const LW_DZ: f64 = -40.0;
/// Upward buoyancy of the modules [N/m] on s in [50, 80] m.
const LW_BUOYANCY: f64 = 670.0;

fn lazy_wave_segments() -> Vec<(f64, f64)> {
    let w = submerged_weight(138.3, 0.332);
    vec![(50.0, w), (30.0, w - LW_BUOYANCY), (20.0, w)]
}

// --- 1. Elastic catenary ------------------------------------------------------

#[test]
fn catenary_top_tension_matches_reference_case() {
    let w = cat_w();
    let f = elastic_catenary(CAT_LENGTH, w, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    println!("catenary: w = {w:.6} N/m, w*L = {:.3} N", w * CAT_LENGTH);
    println!(
        "catenary: H = {:.6} N, v_top = {:.6} N, v_bottom = {:.6} N, T_top = {:.6} N, T_bottom = {:.6} N",
        f.h, f.v_top, f.v_bottom, f.top_tension, f.bottom_tension
    );
    // Expected value of the reference case: 141.9 kN, within 0.1 kN.
    assert!((f.top_tension - 141.9e3).abs() <= 0.1e3, "top tension {}", f.top_tension);
}

#[test]
fn catenary_shape_ends_at_anchor() {
    let w = cat_w();
    let f = elastic_catenary(CAT_LENGTH, w, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    let (x0, z0) = elastic_catenary_shape(CAT_LENGTH, w, CAT_EA, &f, 0.0);
    assert_eq!((x0, z0), (0.0, 0.0));
    let (x, z) = elastic_catenary_shape(CAT_LENGTH, w, CAT_EA, &f, CAT_LENGTH);
    println!("catenary: end misfit dx = {:e} m, dz = {:e} m", x - CAT_SPAN, z - CAT_DZ);
    // The shape is integrated from the top, so this tests the solved forces.
    assert!((x - CAT_SPAN).abs() <= 1e-9, "x(L) = {x}");
    assert!((z - CAT_DZ).abs() <= 1e-9, "z(L) = {z}");
}

#[test]
fn catenary_force_balance() {
    let w = cat_w();
    let f = elastic_catenary(CAT_LENGTH, w, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    // Vertical equilibrium: vessel lifts v_top, anchor pulls down v_bottom.
    assert!(rel(f.v_top - f.v_bottom, w * CAT_LENGTH) <= 1e-12);
    assert!(rel(f.top_tension, f.h.hypot(f.v_top)) <= 1e-15);
    assert!(rel(f.bottom_tension, f.h.hypot(f.v_bottom)) <= 1e-15);
    assert!(f.h > 0.0 && f.v_top > 0.0);
    // Tension varies along the line as w times the height difference, up to
    // the O(T/EA) stretch term: T_top - T_bottom = w*70 - (vt^2 - vb^2)/(2 EA).
    let expected = w * 70.0 - (f.v_top.powi(2) - f.v_bottom.powi(2)) / (2.0 * CAT_EA);
    assert!(rel(f.top_tension - f.bottom_tension, expected) <= 1e-10);
}

#[test]
fn catenary_shape_satisfies_cable_equations() {
    // Differentiate the closed-form shape numerically and compare with the
    // extensible cable equations: |dr/ds| = 1 + T/EA, tangent along the
    // tension (h, -(v_top - w s)) / T.
    let w = cat_w();
    let f = elastic_catenary(CAT_LENGTH, w, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    let d = 1e-3;
    for i in 1..10 {
        let s = CAT_LENGTH * i as f64 / 10.0;
        let (xp, zp) = elastic_catenary_shape(CAT_LENGTH, w, CAT_EA, &f, s + d);
        let (xm, zm) = elastic_catenary_shape(CAT_LENGTH, w, CAT_EA, &f, s - d);
        let (dx, dz) = ((xp - xm) / (2.0 * d), (zp - zm) / (2.0 * d));
        let t = elastic_catenary_tension(w, &f, s);
        let stretch = 1.0 + t / CAT_EA;
        // Central-difference error ~ d^2 * curvature^2 ~ 1e-9.
        assert!((dx - stretch * f.h / t).abs() <= 1e-8, "s = {s}");
        assert!((dz + stretch * (f.v_top - w * s) / t).abs() <= 1e-8, "s = {s}");
    }
}

#[test]
fn catenary_inextensible_symmetric_limit() {
    // Classical inextensible catenary between supports at equal height:
    // L = (2H/w) sinh(w a / (2H)), v_top = -v_bottom = wL/2.
    let (length, w, span) = (100.0, 1000.0, 80.0);
    let f = elastic_catenary(length, w, 1e25, span, 0.0).unwrap();
    let l_classic = 2.0 * f.h / w * (w * span / (2.0 * f.h)).sinh();
    println!("inextensible symmetric catenary: H = {:.9} N", f.h);
    assert!(rel(l_classic, length) <= 1e-12);
    assert!(rel(f.v_top, w * length / 2.0) <= 1e-12);
    assert!(rel(-f.v_bottom, w * length / 2.0) <= 1e-12);
}

#[test]
fn catenary_taut_and_slack_extremes_converge() {
    let w = cat_w();
    // Shorter than the chord (92.2 m): the line must stretch.
    for (length, ea) in [(92.0, CAT_EA), (92.0, 1e7), (300.0, CAT_EA), (1000.0, 1e6)] {
        let f = elastic_catenary(length, w, ea, CAT_SPAN, CAT_DZ).unwrap();
        let (x, z) = elastic_catenary_shape(length, w, ea, &f, length);
        println!("catenary L = {length}, EA = {ea:e}: H = {:.6} N, T_top = {:.6} N", f.h, f.top_tension);
        assert!((x - CAT_SPAN).abs() <= 1e-9 * length && (z - CAT_DZ).abs() <= 1e-9 * length);
    }
    // Anchor above the top is fine too.
    let f = elastic_catenary(100.0, w, CAT_EA, 60.0, 50.0).unwrap();
    let (x, z) = elastic_catenary_shape(100.0, w, CAT_EA, &f, 100.0);
    assert!((x - 60.0).abs() <= 1e-9 && (z - 50.0).abs() <= 1e-9);
}

#[test]
fn catenary_rejects_bad_input() {
    assert!(elastic_catenary(0.0, 1.0, 1.0, 1.0, 0.0).is_err());
    assert!(elastic_catenary(1.0, -1.0, 1.0, 1.0, 0.0).is_err());
    assert!(elastic_catenary(1.0, 1.0, 0.0, 1.0, 0.0).is_err());
    assert!(elastic_catenary(1.0, 1.0, 1.0, 0.0, 0.0).is_err());
    assert!(elastic_catenary(1.0, 1.0, 1.0, 1.0, f64::NAN).is_err());
}

// --- 2. Piecewise catenary by shooting -----------------------------------------

#[test]
fn piecewise_single_segment_matches_closed_form() {
    let w = cat_w();
    let f = elastic_catenary(CAT_LENGTH, w, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    // One segment, and the same line cut into three pieces.
    let cases = [vec![(CAT_LENGTH, w)], vec![(20.0, w), (0.0, 5.0 * w), (45.0, w), (35.0, w)]];
    for segments in cases {
        let p = piecewise_catenary(&segments, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
        println!(
            "piecewise ({} segments): H = {:.6} N, T_top = {:.6} N (closed form {:.6} N)",
            segments.len(),
            p.h,
            p.top_tension,
            f.top_tension
        );
        // Agreement to 1e-6 relative (force magnitudes relative to T_top).
        let tol = 1e-6;
        assert!(rel(p.h, f.h) <= tol);
        assert!(rel(p.v_top, f.v_top) <= tol);
        assert!((p.v_bottom - f.v_bottom).abs() <= tol * f.top_tension);
        assert!(rel(p.top_tension, f.top_tension) <= tol);
        assert!(rel(p.bottom_tension, f.bottom_tension) <= tol);
        // Sampled shape against the closed form, to 1e-6 of the length.
        for &(s, x, z, t) in p.shape.iter().step_by(97) {
            let (xc, zc) = elastic_catenary_shape(CAT_LENGTH, w, CAT_EA, &f, s);
            assert!((x - xc).abs() <= 1e-6 * CAT_LENGTH, "s = {s}");
            assert!((z - zc).abs() <= 1e-6 * CAT_LENGTH, "s = {s}");
            assert!(rel(t, elastic_catenary_tension(w, &f, s)) <= tol, "s = {s}");
        }
    }
}

#[test]
fn lazy_wave_converges_and_has_sag_and_hog_bends() {
    let segments = lazy_wave_segments();
    let p = piecewise_catenary(&segments, LW_EA, LW_SPAN, LW_DZ).unwrap();
    let total_load: f64 = segments.iter().map(|&(l, q)| l * q).sum();
    println!("lazy wave: w = {:.6} N/m, total load = {total_load:.3} N", segments[0].1);
    println!(
        "lazy wave: H = {:.6} N, v_top = {:.6} N, v_bottom = {:.6} N, T_top = {:.6} N, T_bottom = {:.6} N",
        p.h, p.v_top, p.v_bottom, p.top_tension, p.bottom_tension
    );

    // Step-size convergence: doubling the RK4 steps changes nothing visible.
    let fine = piecewise_catenary_with_steps(&segments, LW_EA, LW_SPAN, LW_DZ, 40_000).unwrap();
    println!("lazy wave: T_top with 40000 steps = {:.9} N", fine.top_tension);
    assert!(rel(p.top_tension, fine.top_tension) <= 1e-9);
    assert!(rel(p.h, fine.h) <= 1e-9);

    // Vertical equilibrium and end point.
    assert!(rel(p.v_top - p.v_bottom, total_load) <= 1e-9);
    let &(s_end, x_end, z_end, _) = p.shape.last().unwrap();
    assert!((s_end - 100.0).abs() <= 1e-12);
    assert!((x_end - LW_SPAN).abs() <= 1e-6 && (z_end - LW_DZ).abs() <= 1e-6);

    // Sag bend (local minimum of z) before s = 50 m, hog bend (local maximum
    // of z) within the buoyant section 50..80 m.
    let z: Vec<f64> = p.shape.iter().map(|p| p.2).collect();
    let interior = 1..z.len() - 1;
    let sag: Vec<usize> = interior.clone().filter(|&i| z[i] < z[i - 1] && z[i] <= z[i + 1]).collect();
    let hog: Vec<usize> = interior.filter(|&i| z[i] > z[i - 1] && z[i] >= z[i + 1]).collect();
    let at = |i: usize| (p.shape[i].0, p.shape[i].1, p.shape[i].2);
    println!("lazy wave: sag bends (s, x, z) = {:?}", sag.iter().map(|&i| at(i)).collect::<Vec<_>>());
    println!("lazy wave: hog bends (s, x, z) = {:?}", hog.iter().map(|&i| at(i)).collect::<Vec<_>>());
    // Exactly one sag bend before the buoyant section...
    let sag_before: Vec<usize> = sag.iter().copied().filter(|&i| p.shape[i].0 < 50.0).collect();
    assert_eq!(sag_before.len(), 1);
    // ...exactly one hog bend, inside the buoyant section, above the sag...
    assert_eq!(hog.len(), 1);
    assert!((50.0..=80.0).contains(&p.shape[hog[0]].0));
    assert!(p.shape[hog[0]].2 > p.shape[sag_before[0]].2);
    // ...and (without a seabed) the 20 m heavy tail dips below the anchor
    // before rising to it (v_bottom < 0): a second local minimum after 80 m.
    assert!(sag.iter().all(|&i| p.shape[i].0 < 50.0 || p.shape[i].0 > 80.0));
    assert!(p.v_bottom < 0.0);
}

#[test]
fn piecewise_net_buoyant_line_mirrors_closed_form() {
    // A buoyant line (load -q) with the anchor 40 m below is the mirror image
    // (z -> -z) of a heavy line (load +q) with the anchor 40 m above: same H,
    // opposite vertical forces. 1e-6 relative.
    let (q, ea) = (200.0, 1e7);
    let p = piecewise_catenary(&[(100.0, -q)], ea, 50.0, -40.0).unwrap();
    let c = elastic_catenary(100.0, q, ea, 50.0, 40.0).unwrap();
    assert!(rel(p.h, c.h) <= 1e-6);
    assert!(rel(-p.v_top, c.v_top) <= 1e-6);
    assert!(rel(-p.v_bottom, c.v_bottom) <= 1e-6);
}

#[test]
fn piecewise_weightless_segment_is_straight() {
    let w = cat_w();
    let segments = [(40.0, w), (30.0, 0.0), (30.0, w)];
    let p = piecewise_catenary(&segments, CAT_EA, CAT_SPAN, CAT_DZ).unwrap();
    let pts: Vec<_> = p.shape.iter().filter(|q| (40.0..=70.0).contains(&q.0)).collect();
    let (a, b) = (pts[0], pts[pts.len() - 1]);
    for q in &pts {
        // Distance from the chord a-b.
        let cross = (b.1 - a.1) * (q.2 - a.2) - (b.2 - a.2) * (q.1 - a.1);
        assert!(cross.abs() / (b.1 - a.1).hypot(b.2 - a.2) <= 1e-10);
        assert!(rel(q.3, a.3) <= 1e-12);
    }
}

#[test]
fn piecewise_rejects_bad_input() {
    assert!(piecewise_catenary(&[], 1e8, 10.0, -10.0).is_err());
    assert!(piecewise_catenary(&[(0.0, 1.0)], 1e8, 10.0, -10.0).is_err());
    assert!(piecewise_catenary(&[(-1.0, 1.0), (20.0, 1.0)], 1e8, 10.0, -10.0).is_err());
    assert!(piecewise_catenary(&[(20.0, f64::NAN)], 1e8, 10.0, -10.0).is_err());
    assert!(piecewise_catenary(&[(20.0, 1.0)], 1e8, 0.0, -10.0).is_err());
}

// --- 3. Cantilever elastica -----------------------------------------------------

#[test]
fn elastica_matches_bisshopp_drucker() {
    // Bisshopp & Drucker (1945), Q. Appl. Math. 3: alpha = P L^2/EI = 1.
    let (v, h) = cantilever_elastica(1.0).unwrap();
    println!("elastica alpha = 1: vertical/L = {v:.12}, shortening/L = {h:.12}");
    assert!((v - 0.30172).abs() <= 2e-4);
    assert!((h - 0.05643).abs() <= 2e-4);
}

#[test]
fn elastica_matches_elliptic_integral_solution() {
    // Exact solution via the first integral theta'^2 = 2 alpha (sin phi -
    // sin theta) (phi = tip slope), evaluated by adaptive quadrature in
    // 30-digit arithmetic (mpmath); consistent with Bisshopp & Drucker's
    // tabulated values. Tolerance 1e-9 absolute.
    let cases = [
        (0.5, 0.162143575658370, 0.0159189624708375),
        (1.0, 0.301720773799814, 0.0564332362833769),
        (2.0, 0.493457480396712, 0.160641720825167),
        (3.0, 0.603253441129977, 0.254420184564187),
        (5.0, 0.713791523611913, 0.387628360724430),
        (10.0, 0.810609024880296, 0.554995597753751),
    ];
    for (alpha, v_ref, h_ref) in cases {
        let (v, h) = cantilever_elastica(alpha).unwrap();
        println!("elastica alpha = {alpha}: vertical/L = {v:.12}, shortening/L = {h:.12}");
        assert!((v - v_ref).abs() <= 1e-9, "alpha = {alpha}: v = {v}");
        assert!((h - h_ref).abs() <= 1e-9, "alpha = {alpha}: h = {h}");
    }
}

#[test]
fn elastica_small_load_is_linear() {
    // Linear beam theory: tip deflection alpha/3; shortening = (1/2) int
    // theta^2 = alpha^2/15 to leading order.
    let alpha = 1e-4;
    let (v, h) = cantilever_elastica(alpha).unwrap();
    assert!(rel(v, alpha / 3.0) <= 1e-6, "v = {v}");
    // 1 - x_tip loses ~7 digits to cancellation at this load.
    assert!(rel(h, alpha * alpha / 15.0) <= 1e-5, "h = {h}");
}

#[test]
fn elastica_large_loads_and_symmetry() {
    // Same 30-digit quadrature of the first integral as above (variable
    // pi/2 - theta for the nearly vertical tip). Above alpha = 20 the
    // reference shoots from the tip; 1e-9 absolute.
    let cases = [
        (20.0, 0.8686958982854378, 0.6838855675664751),
        (20.5, f64::NAN, f64::NAN), // just past the method switch: monotonicity only
        (50.0, 0.9171554473035874, 0.8000003960495976),
        (100.0, 0.941421350862011, 0.8585786445628821),
        (1000.0, 0.9814758063466282, 0.9552786404500042),
        (10000.0, 0.994142135623731, 0.9858578643762691),
    ];
    let mut last = (0.0, 0.0);
    for (alpha, v_ref, h_ref) in cases {
        let (v, h) = cantilever_elastica(alpha).unwrap();
        println!("elastica alpha = {alpha}: vertical/L = {v:.12}, shortening/L = {h:.12}");
        if v_ref.is_finite() {
            assert!((v - v_ref).abs() <= 1e-9, "alpha = {alpha}: v = {v}");
            assert!((h - h_ref).abs() <= 1e-9, "alpha = {alpha}: h = {h}");
        }
        // Both tend to 1 as alpha -> infinity, monotonically.
        assert!(v > last.0 && v < 1.0 && h > last.1 && h < 1.0);
        last = (v, h);
    }
    assert!(cantilever_elastica(2.0 * ELASTICA_MAX_ALPHA).is_err());
    let (v, h) = cantilever_elastica(2.0).unwrap();
    assert_eq!(cantilever_elastica(-2.0).unwrap(), (-v, h));
    assert_eq!(cantilever_elastica(0.0).unwrap(), (0.0, 0.0));
    assert!(cantilever_elastica(f64::NAN).is_err());
}

// --- 4. Bessel J0 ----------------------------------------------------------------

#[test]
fn bessel_j0_zeros_match_tables() {
    let zeros = bessel_j0_zeros(1000);
    // Abramowitz & Stegun Table 9.5 (first three to 1e-10 absolute).
    for (k, z) in [2.404825557695773, 5.520078110286311, 8.653727912911013].into_iter().enumerate() {
        println!("j0 zero {}: {:.15}", k + 1, zeros[k]);
        assert!((zeros[k] - z).abs() <= 1e-10);
    }
    // Further zeros (30-digit values from mpmath besseljzero), 1e-13 relative.
    for (k, z) in [
        (4, 11.791534439014281),
        (5, 14.930917708487787),
        (10, 30.634606468431976),
        (20, 62.048469190227166),
        (100, 313.37426607752786),
        (1000, 3140.8072952250786),
    ] {
        assert!(rel(zeros[k - 1], z) <= 1e-13, "zero {k}: {}", zeros[k - 1]);
    }
    // Strictly increasing with spacing -> pi.
    assert!(zeros.windows(2).all(|p| p[1] - p[0] > 3.0 && p[1] - p[0] < 3.2));
    assert!(((zeros[999] - zeros[998]) - PI).abs() <= 1e-5);
    assert!(bessel_j0_zeros(0).is_empty());
}

#[test]
fn bessel_j0_j1_values() {
    // 30-digit values from mpmath; tolerance 1e-14 absolute.
    for (x, j0, j1) in [
        (1.0, 0.7651976865579666, 0.4400505857449335),
        (10.0, -0.24593576445134835, 0.04347274616886144),
        (100.0, 0.019985850304223122, -0.07714535201411216),
        (1000.0, 0.024786686152420176, 0.004728311907089524),
    ] {
        let (a, b) = bessel_j0_j1(x);
        assert!((a - j0).abs() <= 1e-14, "J0({x}) = {a}");
        assert!((b - j1).abs() <= 1e-14, "J1({x}) = {b}");
        let (c, d) = bessel_j0_j1(-x);
        assert_eq!((c, d), (a, -b));
    }
    assert_eq!(bessel_j0_j1(0.0), (1.0, 0.0));
    // Small argument (power-series branch below 1e-4), 1e-15 absolute.
    let (a, b) = bessel_j0_j1(1e-4);
    assert!((a - 0.9999999975).abs() <= 1e-15 && (b - 4.99999999375e-5).abs() <= 1e-15);
    assert!(bessel_j0_j1(1e-300).0 == 1.0);
}

// --- 5. Morison's force on a fixed vertical cylinder --------------------------

/// The closed-form depth integrals of `morison_vertical_cylinder` against
/// composite Simpson quadrature (4000 intervals; error ~ (k Δz)⁴/180, below
/// 1e-12 here) of `airy_kinematics`' u and ∂u/∂t over the cylinder, the
/// force at several phases; and the first harmonic of cos θ |cos θ|, 8/(3π),
/// against a 1000-point sum over a period. Deep and finite water, a
/// cylinder from the seabed and one hanging from below the trough.
#[test]
fn morison_force_on_a_vertical_cylinder_matches_quadrature() {
    let omega = 2.0 * PI / 10.0;
    for (depth, z_bot, z_top) in [(100.0, -100.0, -2.0), (30.0, -30.0, -1.5), (500.0, -120.0, -3.0)] {
        let k = wave_number(omega, depth, G);
        let (a, d, cm, cd) = (1.2, 0.4, 1.8, 1.1);
        let f = morison_vertical_cylinder(a, omega, k, depth, d, z_bot, z_top, RHO_WATER, cm, cd);
        let area = PI * d * d / 4.0;
        for theta in [0.0, 0.4, 1.3, 2.9, 4.4, 5.8] {
            let n = 4000;
            let dz = (z_top - z_bot) / n as f64;
            let integrand = |z: f64| {
                let [u, _, du, _] = airy_kinematics(a, omega, k, depth, theta, z);
                cm * RHO_WATER * area * du + 0.5 * RHO_WATER * cd * d * u * u.abs()
            };
            let mut sum = integrand(z_bot) + integrand(z_top);
            for i in 1..n {
                sum += if i % 2 == 1 { 4.0 } else { 2.0 } * integrand(z_bot + i as f64 * dz);
            }
            let quad = sum * dz / 3.0;
            let scale = f.inertia.abs() + f.drag.abs();
            println!(
                "d {depth} m, cylinder {z_bot}..{z_top} m, theta {theta}: closed form {:.9} N, Simpson {quad:.9} N",
                f.at(theta)
            );
            assert!((f.at(theta) - quad).abs() <= 1e-10 * scale, "{depth} {theta}");
        }
    }
    let n = 1000;
    let b1: f64 = (0..n)
        .map(|i| {
            let t = 2.0 * PI * i as f64 / n as f64;
            t.cos() * t.cos().abs() * t.cos()
        })
        .sum::<f64>()
        * 2.0
        / n as f64;
    let f = MorisonAmplitudes { inertia: 0.0, drag: 1.0 };
    println!("first harmonic of cos|cos|: {b1:.12}, 8/(3 pi) = {:.12}", f.first_harmonic().1);
    assert!((b1 - f.first_harmonic().1).abs() <= 1e-6);
}
