//! sin, cos and exp over slices, branch-free so that the compiler
//! vectorises them (two lanes on baseline x86-64): the inner loops of
//! [`Sea::water_batch`](super::Sea::water_batch) (docs/theory.md §13.4).
//!
//! They are FreeBSD's msun (fdlibm) algorithms, as the `libm` crate
//! carries them, without their special cases, on a bounded range of
//! arguments:
//!
//! * sin, cos: θ = n π/2 + y with n the integer nearest 2θ/π, y = (θ −
//!   n P₁) − n P₁ₜ (P₁ the first 33 bits of π/2, P₁ₜ the next 53: "good to
//!   85 bits"; n P₁ is exact and so is θ − n P₁ for |n| < 2²⁰, by Sterbenz),
//!   then msun's `__kernel_sin` and `__kernel_cos` on |y| ≲ π/4 (Remez
//!   polynomials within 2⁻⁵⁸ of sin y/y and cos y) and the quadrant n mod 4.
//!   For |θ| ≤ [`SIN_COS_MAX`] (|n| < 2¹⁹) the error of y is below 1e-19
//!   plus half an ulp of y (≤ 5.6e-17 in all) and that of each kernel below
//!   one ulp: |error| < 2e-16 (absolute; the tests find at most 1.1e-16
//!   against std over 4 million arguments). Beyond, [`sin_cos`] falls back
//!   to std.
//! * exp: x = k ln 2 + r, |r| ≤ ½ ln 2 (k ln2_hi exact), msun's rational
//!   form 1 + r + r c/(2 − c) (its polynomial within 2⁻⁵⁹), scaled by 2ᵏ:
//!   below one ulp (msun's analysis), for x in [−700, 700] (k in [−1010,
//!   1010]: no overflow, no subnormal); beyond, [`exp`] falls back to std.

/// 1.5·2⁵²: x + TO_INT − TO_INT rounds x to an integer (|x| < 2⁵¹), whose
/// low bits are then those of (x + TO_INT).to_bits().
const TO_INT: f64 = 6755399441055744.0;

const INV_PIO2: f64 = f64::from_bits(0x3FE45F30_6DC9C883); // 6.36619772367581382433e-01
const PIO2_1: f64 = f64::from_bits(0x3FF921FB_54400000); // 1.57079632673412561417e+00
const PIO2_1T: f64 = f64::from_bits(0x3DD0B461_1A626331); // 6.07710050650619224932e-11

const S1: f64 = f64::from_bits(0xBFC55555_55555549); // -1.66666666666666324348e-01
const S2: f64 = f64::from_bits(0x3F811111_1110F8A6); // 8.33333333332248946124e-03
const S3: f64 = f64::from_bits(0xBF2A01A0_19C161D5); // -1.98412698298579493134e-04
const S4: f64 = f64::from_bits(0x3EC71DE3_57B1FE7D); // 2.75573137070700676789e-06
const S5: f64 = f64::from_bits(0xBE5AE5E6_8A2B9CEB); // -2.50507602534068634195e-08
const S6: f64 = f64::from_bits(0x3DE5D93A_5ACFD57C); // 1.58969099521155010221e-10

const C1: f64 = f64::from_bits(0x3FA55555_5555554C); // 4.16666666666666019037e-02
const C2: f64 = f64::from_bits(0xBF56C16C_16C15177); // -1.38888888888741095749e-03
const C3: f64 = f64::from_bits(0x3EFA01A0_19CB1590); // 2.48015872894767294178e-05
const C4: f64 = f64::from_bits(0xBE927E4F_809C52AD); // -2.75573143513906633035e-07
const C5: f64 = f64::from_bits(0x3E21EE9E_BDB4B1C4); // 2.08757232129817482790e-09
const C6: f64 = f64::from_bits(0xBDA8FAE9_BE8838D4); // -1.13596475577881948265e-11

const LN2HI: f64 = f64::from_bits(0x3FE62E42_FEE00000); // 6.93147180369123816490e-01
const LN2LO: f64 = f64::from_bits(0x3DEA39EF_35793C76); // 1.90821492927058770002e-10
const INVLN2: f64 = f64::from_bits(0x3FF71547_652B82FE); // 1.44269504088896338700e+00
const P1: f64 = f64::from_bits(0x3FC55555_5555553E); // 1.66666666666666019037e-01
const P2: f64 = f64::from_bits(0xBF66C16C_16BEBD93); // -2.77777777770155933842e-03
const P3: f64 = f64::from_bits(0x3F11566A_AF25DE2C); // 6.61375632143793436117e-05
const P4: f64 = f64::from_bits(0xBEBBBD41_C5D26BF1); // -1.65339022054652515390e-06
const P5: f64 = f64::from_bits(0x3E663769_72BEA4D0); // 4.13813679705723846039e-08

/// The largest |θ| [`sin_cos`] reduces itself (2¹⁹ π/2 ≈ 8.2e5 rad: a
/// 10 s wave's phase after 15 days).
pub(crate) const SIN_COS_MAX: f64 = 823549.6;

/// The range of x [`exp`] evaluates itself.
pub(crate) const EXP_MAX: f64 = 700.0;

/// (sin θ, cos θ) for |θ| ≤ [`SIN_COS_MAX`] (msun's reduction and kernels).
#[inline(always)]
pub(crate) fn sin_cos_reduced(x: f64) -> (f64, f64) {
    let tmp = x * INV_PIO2 + TO_INT;
    let f_n = tmp - TO_INT;
    // n mod 4 in the low bits (TO_INT's are 0)
    let q = tmp.to_bits();
    let y = (x - f_n * PIO2_1) - f_n * PIO2_1T;
    let z = y * y;
    let w = z * z;
    let rs = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let sn = y + z * y * (S1 + z * rs);
    let rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let wc = 1.0 - hz;
    let cs = wc + (((1.0 - wc) - hz) + z * rc);
    // quadrant n mod 4 = 0: (s, c); 1: (c, −s); 2: (−s, −c); 3: (−c, s)
    let swap = (q & 1).wrapping_neg();
    let (sb, cb) = (sn.to_bits(), cs.to_bits());
    let s = (sb & !swap) | (cb & swap);
    let c = (cb & !swap) | (sb & swap);
    let s = s ^ ((q & 2) << 62);
    let c = c ^ ((q.wrapping_add(1) & 2) << 62);
    (f64::from_bits(s), f64::from_bits(c))
}

/// e^x for |x| ≤ [`EXP_MAX`] (msun's reduction and rational form).
#[inline(always)]
pub(crate) fn exp_reduced(x: f64) -> f64 {
    let tmp = x * INVLN2 + TO_INT;
    let kf = tmp - TO_INT;
    let k = tmp.to_bits().wrapping_sub(TO_INT.to_bits());
    let hi = x - kf * LN2HI;
    let lo = kf * LN2LO;
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (P1 + rr * (P2 + rr * (P3 + rr * (P4 + rr * P5))));
    let y = 1.0 + (r * c / (2.0 - c) - lo + hi);
    // 2^k (k in [−1010, 1010]: a normal number)
    let scale = f64::from_bits(k.wrapping_add(1023) << 52);
    y * scale
}

/// sin and cos of each of `theta` into `sin` and `cos` (at least as long):
/// within 2e-16 of the exact values (std's where some |θ| exceeds
/// [`SIN_COS_MAX`] or is not finite). The kernels over a slice as the
/// kinematics loop uses them (there with the phase formed in the loop,
/// `kinematics::phase_sin_cos`): what the tests check against std.
#[cfg(test)]
pub(crate) fn sin_cos(theta: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    let n = theta.len();
    let (sin, cos) = (&mut sin[..n], &mut cos[..n]);
    // one vectorised pass (NaN compares false)
    if theta.iter().fold(true, |ok, t| ok & (t.abs() <= SIN_COS_MAX)) {
        for i in 0..n {
            (sin[i], cos[i]) = sin_cos_reduced(theta[i]);
        }
    } else {
        for i in 0..n {
            (sin[i], cos[i]) = theta[i].sin_cos();
        }
    }
}

/// e^x of each of `x` into `out` (at least as long): within one ulp (std's
/// where some |x| exceeds [`EXP_MAX`] or is not finite). As [`sin_cos`],
/// the form the tests check (`kinematics::decay_exp` in the loop).
#[cfg(test)]
pub(crate) fn exp(x: &[f64], out: &mut [f64]) {
    let n = x.len();
    let out = &mut out[..n];
    if x.iter().fold(true, |ok, t| ok & (t.abs() <= EXP_MAX)) {
        for i in 0..n {
            out[i] = exp_reduced(x[i]);
        }
    } else {
        for i in 0..n {
            out[i] = x[i].exp();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SplitMix64's uniform in [0, 1).
    fn uniforms(seed: u64, n: usize) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s.wrapping_add(0x9E3779B97F4A7C15);
                let mut z = s;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
                z ^= z >> 31;
                (z >> 11) as f64 / (1u64 << 53) as f64
            })
            .collect()
    }

    #[test]
    fn sin_cos_is_within_two_ulps_of_std_over_its_range() {
        let mut args: Vec<f64> = Vec::new();
        // uniform on several scales up to the limit, and both ends
        for (i, scale) in [1.0, 10.0, 1e3, 1e5, SIN_COS_MAX].into_iter().enumerate() {
            args.extend(uniforms(i as u64, 800_000).iter().map(|u| (2.0 * u - 1.0) * scale));
        }
        // next to multiples of π/4 (quadrant boundaries and where the
        // reduction cancels)
        for m in (-2000i64..2000).chain([-524287, 524287, 1 << 18, 3 << 17, -(5 << 16)]) {
            let c = m as f64 * std::f64::consts::FRAC_PI_4;
            let mut a = c;
            for _ in 0..8 {
                args.extend([a, -a]);
                a = a.next_up();
            }
            args.extend([c.next_down(), c.next_down().next_down(), -c.next_down()]);
        }
        args.extend([0.0, -0.0, SIN_COS_MAX, -SIN_COS_MAX, 1e-300, -1e-20]);
        let (mut s, mut c) = (vec![0.0; args.len()], vec![0.0; args.len()]);
        sin_cos(&args, &mut s, &mut c);
        let mut worst = 0.0f64;
        for (i, a) in args.iter().enumerate() {
            let (es, ec) = a.sin_cos();
            worst = worst.max((s[i] - es).abs()).max((c[i] - ec).abs());
        }
        eprintln!("sin_cos: largest difference from std {worst:e} over {} arguments", args.len());
        assert!(worst < 2.3e-16, "{worst:e}");
        // beyond the range, and NaN: std's
        let big = [1.0, SIN_COS_MAX * 1.5, -3.0];
        sin_cos(&big, &mut s, &mut c);
        for (i, a) in big.iter().enumerate() {
            assert_eq!((s[i], c[i]), a.sin_cos());
        }
        sin_cos(&[f64::NAN, 1.0], &mut s, &mut c);
        assert!(s[0].is_nan() && c[0].is_nan() && s[1] == 1f64.sin());
    }

    #[test]
    fn exp_is_within_two_ulps_of_std_over_its_range() {
        let mut args: Vec<f64> = Vec::new();
        for (i, scale) in [0.5, 5.0, 40.0, EXP_MAX].into_iter().enumerate() {
            args.extend(uniforms(10 + i as u64, 500_000).iter().map(|u| (2.0 * u - 1.0) * scale));
        }
        for m in -1000i64..1000 {
            let c = (m as f64 + 0.5) * std::f64::consts::LN_2;
            args.extend([c, c.next_up(), c.next_down(), m as f64 * std::f64::consts::LN_2]);
        }
        args.extend([0.0, -0.0, EXP_MAX, -EXP_MAX, 1e-300, -1e-20, -38.0]);
        let mut out = vec![0.0; args.len()];
        exp(&args, &mut out);
        let mut worst = 0.0f64;
        for (i, a) in args.iter().enumerate() {
            let e = a.exp();
            worst = worst.max(((out[i] - e) / e).abs());
        }
        eprintln!("exp: largest relative difference from std {worst:e} over {} arguments", args.len());
        assert!(worst < 4.5e-16, "{worst:e}");
        let big = [1.0, 800.0, -750.0, f64::NEG_INFINITY];
        exp(&big, &mut out);
        for (i, a) in big.iter().enumerate() {
            assert_eq!(out[i], a.exp());
        }
    }
}
