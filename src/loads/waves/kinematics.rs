//! The water's velocity and acceleration of a [`Sea`] at a point (x, y, z)
//! and time t (docs/theory.md §13.2): linear (Airy) kinematics of each
//! component, evaluated at the stretched height ζ′, summed and multiplied
//! by the ramp.
//!
//! Per component, with θ = kx x + ky y − ω t + φ₀ and ζ′ the stretched height
//! above the mean level,
//!
//!   u_h = a ω C(ζ′) cos θ,   w = a ω S(ζ′) sin θ,                     (13.4)
//!   ∂u_h/∂t = a ω² C sin θ,  ∂w/∂t = −a ω² S cos θ,                   (13.5)
//!   C = cosh k(ζ′ + d) / sinh kd,  S = sinh k(ζ′ + d) / sinh kd
//!
//! (C = S = e^{kζ′} in deep water), the horizontal velocity u_h along
//! (cos β, sin β). C and S are evaluated as (e^{kζ′} ± e^{−k(ζ′+2d)})/(1 − e^{−2kd}),
//! which neither overflows nor cancels for any kd.
//!
//! Cost: two passes over the components per point (the first gives η and
//! its slope, which the stretching needs; the second the kinematics), one
//! `sin_cos` and one `exp` per component and point; with a scratch buffer
//! ([`Sea::kinematics_batch`]) the second pass reuses the first's `sin_cos`.
//! Points deeper than every component's 38 decay lengths 1/k under the
//! lowest possible trough ([`Sea::deep_cutoff`]) cost one comparison.

use super::vecmath;
use super::{DECAY_LENGTHS, LANES, Sea, SortedTerms, Stretching, Term};
use crate::math::{M3, V3};

/// The wave field at one point, ramp included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavePoint {
    /// The ramped elevation r η at the point's (x, y), m (0 where `deep`).
    pub elevation: f64,
    /// The water's velocity, m/s.
    pub velocity: V3,
    /// The water's acceleration, m/s²: r ∂u/∂t + ṙ u (local derivative of
    /// linear theory at the stretched height).
    pub acceleration: V3,
    /// ∂u/∂x (row i: velocity component, column j: coordinate), 1/s, of
    /// the velocity as returned (stretching and clamping included).
    pub gradient: M3,
    /// The point lies below [`Sea::deep_cutoff`]: the field is zero there
    /// (below 1e-16 of its surface values) and was not evaluated.
    pub deep: bool,
}

impl WavePoint {
    /// Still water.
    pub const STILL: WavePoint = WavePoint {
        elevation: 0.0,
        velocity: V3::new(0.0, 0.0, 0.0),
        acceleration: V3::new(0.0, 0.0, 0.0),
        gradient: M3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        deep: false,
    };
}

/// What the water's force on the line needs at a point (docs/theory.md
/// §13.6): the ramped elevation above the point and the water's velocity
/// and acceleration there (no gradient: the force freezes the field over a
/// step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterPoint {
    /// r η at the point's (x, y), m.
    pub elevation: f64,
    /// m/s.
    pub velocity: V3,
    /// m/s².
    pub acceleration: V3,
}

impl WaterPoint {
    /// Still water.
    pub const STILL: WaterPoint =
        WaterPoint { elevation: 0.0, velocity: V3::new(0.0, 0.0, 0.0), acceleration: V3::new(0.0, 0.0, 0.0) };
}

/// Reusable storage of [`Sea::kinematics_batch`] and [`Sea::water_batch`]:
/// a few numbers per component (allocated at the first call, reused after).
#[derive(Debug, Clone, Default)]
pub struct WaveScratch {
    sin_cos: Vec<[f64; 2]>,
    /// ω t (per call), sin θ, cos θ, e^{kζ′} (per point), sorted terms.
    wt: Vec<f64>,
    sin: Vec<f64>,
    cos: Vec<f64>,
    exp: Vec<f64>,
}

/// The components [`Sea::water`] takes at a time (a multiple of [`LANES`];
/// four buffers of this many numbers on the stack, 8 kB).
pub(crate) const CHUNK: usize = 256;

impl WaveScratch {
    fn grow(&mut self, n: usize) {
        for v in [&mut self.wt, &mut self.sin, &mut self.cos, &mut self.exp] {
            if v.len() < n {
                v.resize(n, 0.0);
            }
        }
    }
}

/// Adds a·b over slices of a multiple of [`LANES`] elements to the
/// [`LANES`] partial sums `acc` (which the compiler keeps in vector
/// registers): lane l takes elements l, l + LANES, … in order, so that the
/// sums do not depend on how the slices are cut into whole lanes.
#[inline(always)]
fn dot_into(a: &[f64], b: &[f64], acc: &mut [f64; LANES]) {
    for (a, b) in a.chunks_exact(LANES).zip(b.chunks_exact(LANES)) {
        for l in 0..LANES {
            acc[l] += a[l] * b[l];
        }
    }
}

/// Adds pass 2's velocity and acceleration terms of the sorted terms
/// `lo..lo + sin.len()` (a multiple of [`LANES`]; `sin`, `cos`, `p` theirs),
/// unramped, to the partial sums `acc`: (13.3)-(13.4) with C = S = p (deep
/// water) or C, S = c (p ± e^{−2kd}/p). Lane by lane as [`dot_into`].
#[inline(always)]
fn add_kinematics<const DEEP: bool>(
    st: &SortedTerms,
    lo: usize,
    sin: &[f64],
    cos: &[f64],
    p: &[f64],
    acc: &mut [[f64; LANES]; 6],
) {
    // whole lanes, every slice of the same length: no bounds checks in the loop
    let groups = sin.len() / LANES;
    let n = groups * LANES;
    let (sin, cos, p) = (&sin[..n], &cos[..n], &p[..n]);
    let r = lo..lo + n;
    let (awx, awy, aw) = (&st.awx[r.clone()], &st.awy[r.clone()], &st.aw[r.clone()]);
    let (aw2x, aw2y, aw2) = (&st.aw2x[r.clone()], &st.aw2y[r.clone()], &st.aw2[r.clone()]);
    let (e2kd, cf) = (&st.e2kd[r.clone()], &st.c[r]);
    for g in 0..groups {
        for l in 0..LANES {
            let i = g * LANES + l;
            let (ch, sh) = if DEEP {
                (p[i], p[i])
            } else {
                let q = e2kd[i] / p[i];
                (cf[i] * (p[i] + q), cf[i] * (p[i] - q))
            };
            let (cc, ss) = (ch * cos[i], sh * sin[i]);
            let (cs, sc) = (ch * sin[i], sh * cos[i]);
            acc[0][l] += awx[i] * cc;
            acc[1][l] += awy[i] * cc;
            acc[2][l] += aw[i] * ss;
            acc[3][l] += aw2x[i] * cs;
            acc[4][l] += aw2y[i] * cs;
            acc[5][l] -= aw2[i] * sc;
        }
    }
}

/// The phases θ = kx x + ky y − ω t + φ₀ (13.1) of the sorted terms at
/// `p` (`wt` their ω t) and their sines and cosines into `sin`, `cos`:
/// [`vecmath::sin_cos`] with θ formed in the same loop (the same bits:
/// msun's kernels if every |θ| is in their range, else std for all).
#[inline(always)]
fn phase_sin_cos(kx: &[f64], ky: &[f64], wt: &[f64], phi0: &[f64], p: &V3, sin: &mut [f64], cos: &mut [f64]) {
    let n = kx.len();
    let (ky, wt, phi0, sin, cos) = (&ky[..n], &wt[..n], &phi0[..n], &mut sin[..n], &mut cos[..n]);
    let theta = |i: usize| kx[i] * p.x + ky[i] * p.y - wt[i] + phi0[i];
    let mut ok = true;
    for i in 0..n {
        let th = theta(i);
        ok &= th.abs() <= vecmath::SIN_COS_MAX;
        (sin[i], cos[i]) = vecmath::sin_cos_reduced(th);
    }
    if !ok {
        for i in 0..n {
            (sin[i], cos[i]) = theta(i).sin_cos();
        }
    }
}

/// e^{max(kζ′, −38)} of each of the wave numbers `k` into `out` (13.4):
/// [`vecmath::exp`] with the argument formed in the same loop (the same
/// bits: msun's kernel if every argument is in its range, else std for all).
#[inline(always)]
fn decay_exp(k: &[f64], zp: f64, out: &mut [f64]) {
    let n = k.len();
    let out = &mut out[..n];
    let arg = |i: usize| (k[i] * zp).max(-DECAY_LENGTHS);
    let mut ok = true;
    for i in 0..n {
        let a = arg(i);
        ok &= a.abs() <= vecmath::EXP_MAX;
        out[i] = vecmath::exp_reduced(a);
    }
    if !ok {
        for i in 0..n {
            out[i] = arg(i).exp();
        }
    }
}

/// The sums of [`add_kinematics`]' partial sums: (velocity, acceleration).
#[inline(always)]
fn kinematics_total(acc: &[[f64; LANES]; 6]) -> (V3, V3) {
    let sum = |a: &[f64; LANES]| a.iter().sum::<f64>();
    (V3::new(sum(&acc[0]), sum(&acc[1]), sum(&acc[2])), V3::new(sum(&acc[3]), sum(&acc[4]), sum(&acc[5])))
}

impl WaveScratch {
    /// Grows the buffer to `components` entries.
    /// Grows the buffers to `components` entries and `sorted` padded ones.
    pub(crate) fn reserve(&mut self, components: usize, sorted: usize) {
        if self.sin_cos.len() < components {
            self.sin_cos.resize(components, [0.0; 2]);
        }
        self.grow(sorted);
    }
}

impl Sea {
    /// The stretched height ζ′ of a point at ζ = z − z_s under a surface at η
    /// (both ramped), with ∂ζ′/∂ζ and ∂ζ′/∂η (§13.2). A point above the
    /// surface takes the surface's kinematics (ζ clamped to η), one below
    /// the seabed the seabed's (ζ clamped to −d).
    pub fn stretch(&self, zeta: f64, eta: f64) -> (f64, f64, f64) {
        let depth = self.settings.depth;
        let (mut zc, mut dz, mut de) = if zeta > eta { (eta, 0.0, 1.0) } else { (zeta, 1.0, 0.0) };
        if let Some(d) = depth
            && zc < -d
        {
            (zc, dz, de) = (-d, 0.0, 0.0);
        }
        match self.settings.stretching {
            Stretching::None => (zc, dz, de),
            Stretching::Vertical => {
                if zc > 0.0 {
                    (0.0, 0.0, 0.0)
                } else {
                    (zc, dz, de)
                }
            }
            Stretching::Wheeler => match depth {
                None => (zc - eta, dz, de - 1.0),
                Some(d) => {
                    // a trough reaching within a tenth of the depth of the
                    // seabed is held there (linear theory has long failed)
                    let floor = -0.9 * d;
                    let (e, de_e) = if eta > floor { (eta, 1.0) } else { (floor, 0.0) };
                    let dd = d + e;
                    let zp = d * (zc - e) / dd;
                    let dzp_dzc = d / dd;
                    let dzp_de = -d * (d + zc) / (dd * dd) * de_e;
                    (zp, dzp_dzc * dz, dzp_dzc * de + dzp_de)
                }
            },
        }
    }

    /// C(ζ′) and S(ζ′) of one component (13.4).
    #[inline]
    fn depth_factors(&self, t: &Term, zp: f64) -> (f64, f64) {
        let p = (t.k * zp).exp();
        match self.settings.depth {
            None => (p, p),
            Some(d) => {
                let q = if p > 1e-150 { t.e2kd / p } else { (-t.k * (zp + 2.0 * d)).exp() };
                (t.c * (p + q), t.c * (p - q))
            }
        }
    }

    /// The wave field at `p` at time `t` (no allocation; the components'
    /// phases are computed twice: prefer [`Sea::kinematics_batch`] for many
    /// points).
    pub fn kinematics(&self, p: &V3, t: f64) -> WavePoint {
        self.evaluate(p, t, None)
    }

    /// The wave field at each of `points` at time `t` into `out` (same
    /// length): the call the force integration makes once per Newton
    /// iteration with the Gauss points of the whole line. `scratch` is
    /// grown once to the number of components and reused.
    pub fn kinematics_batch(&self, t: f64, points: &[V3], out: &mut [WavePoint], scratch: &mut WaveScratch) {
        if scratch.sin_cos.len() < self.terms.len() {
            scratch.sin_cos.resize(self.terms.len(), [0.0; 2]);
        }
        for (p, o) in points.iter().zip(out.iter_mut()) {
            *o = self.evaluate(p, t, Some(&mut scratch.sin_cos));
        }
    }

    /// The elevation, velocity and acceleration at each of `points` at time
    /// `t` into `out` (same length): what the force integration evaluates
    /// once per step at the Gauss points of the whole line. Equal to the
    /// fields of [`Sea::kinematics`] to round-off (the sums run in another
    /// order), without the gradient's work, and cheaper (docs/theory.md
    /// §13.4): the components are visited sorted by wave number, and pass 2
    /// stops at the first whose e^{kζ′} is below e^{−38} ≈ 3e-17 (C and S
    /// are then below 2e^{−38} too: ζ′ ≥ −d), the rest of them, shorter
    /// still, are smaller yet.
    pub fn water_batch(&self, t: f64, points: &[V3], out: &mut [WaterPoint], scratch: &mut WaveScratch) {
        let st = &self.sorted;
        let n = st.len;
        scratch.grow(n);
        let (r, dr) = self.settings.ramp.at(t);
        if r == 0.0 {
            out.iter_mut().for_each(|o| *o = WaterPoint::STILL);
            return;
        }
        // ω t once per call: θ below is `evaluate`'s bit for bit
        for (wt, w) in scratch.wt[..n].iter_mut().zip(&st.omega) {
            *wt = w * t;
        }
        // the loop compiled for the widest vectors the processor has (AVX2:
        // four lanes instead of two; AVX-512, pulp's `x86-v4`: eight),
        // chosen at run time by pulp, the SIMD
        // layer faer already brings (no unsafe here); the same operations in
        // the same order on every path: the same bits
        pulp::Arch::new().dispatch(WaterPoints { sea: self, r, dr, points, out, scratch });
    }

    /// The elevation, velocity and acceleration at one point at time `t`:
    /// [`Sea::water_batch`]'s per-point loop with the components taken
    /// 256 at a time through buffers on the stack (no scratch, no
    /// allocation; a sea of more than 256 components has its phases'
    /// sines and cosines evaluated again in pass 2), for the few points the
    /// outputs evaluate at a state. Bit for bit the batch's wherever every
    /// phase |θ| ≤ 8.2e5 rad (the vector sine's range, 15 days of a 10 s
    /// wave: beyond, each chunk falls back to std on its own, the batch as
    /// a whole).
    pub fn water(&self, p: &V3, t: f64) -> WaterPoint {
        let (r, dr) = self.settings.ramp.at(t);
        let zeta = p.z - self.settings.surface_z;
        if r == 0.0 || self.deep_cutoff.is_some_and(|cut| zeta < cut) {
            return WaterPoint::STILL;
        }
        pulp::Arch::new().dispatch(WaterOnePoint { sea: self, p, t, r, dr })
    }

    /// The body of [`Sea::water`] (ramp `r` > 0, rate `dr`).
    #[inline(always)]
    fn water_one_point(&self, p: &V3, t: f64, r: f64, dr: f64) -> WaterPoint {
        let st = &self.sorted;
        let n = st.len;
        let zeta = p.z - self.settings.surface_z;
        let mut wt = [0.0; CHUNK];
        let (mut sin, mut cos, mut exp) = ([0.0; CHUNK], [0.0; CHUNK], [0.0; CHUNK]);
        // sin θ and cos θ of the sorted terms lo..lo + len, as the batch forms them
        let mut phases = |lo: usize, len: usize, sin: &mut [f64; CHUNK], cos: &mut [f64; CHUNK]| {
            let r = lo..lo + len;
            for (wt, w) in wt[..len].iter_mut().zip(&st.omega[r.clone()]) {
                *wt = w * t;
            }
            let (kx, ky, phi0) = (&st.kx[r.clone()], &st.ky[r.clone()], &st.phi0[r]);
            phase_sin_cos(kx, ky, &wt[..len], phi0, p, sin, cos);
        };
        // pass 1: η (every component)
        let mut sum = [0.0; LANES];
        for lo in (0..n).step_by(CHUNK) {
            let len = CHUNK.min(n - lo);
            phases(lo, len, &mut sin, &mut cos);
            dot_into(&st.a[lo..lo + len], &cos[..len], &mut sum);
        }
        let eta = r * sum.iter().sum::<f64>();
        let (zp, _, _) = self.stretch(zeta, eta);
        // pass 2: the components whose e^{kζ′} ≥ e^{−38}, in whole lanes (as the batch)
        let active = if zp < 0.0 { st.k[..n].partition_point(|k| k * zp >= -DECAY_LENGTHS) } else { n };
        let m = active.div_ceil(LANES) * LANES;
        let mut sums = [[0.0; LANES]; 6];
        for lo in (0..m).step_by(CHUNK) {
            let len = CHUNK.min(m - lo);
            if n > CHUNK {
                phases(lo, len, &mut sin, &mut cos);
            }
            decay_exp(&st.k[lo..lo + len], zp, &mut exp);
            match self.settings.depth {
                None => add_kinematics::<true>(st, lo, &sin[..len], &cos, &exp, &mut sums),
                Some(_) => add_kinematics::<false>(st, lo, &sin[..len], &cos, &exp, &mut sums),
            }
        }
        let (vel, acc) = kinematics_total(&sums);
        WaterPoint { elevation: eta, velocity: vel * r, acceleration: acc * r + vel * dr }
    }

    /// The body of [`Sea::water_batch`] at ramp `r`, rate `dr`, with ω t in
    /// the scratch.
    #[inline(always)]
    fn water_points(&self, r: f64, dr: f64, points: &[V3], out: &mut [WaterPoint], scratch: &mut WaveScratch) {
        let st = &self.sorted;
        let n = st.len;
        let WaveScratch { wt, sin, cos, exp, .. } = scratch;
        let (wt, sin, cos, exp) = (&wt[..n], &mut sin[..n], &mut cos[..n], &mut exp[..n]);
        let (k, kx, ky, phi0) = (&st.k[..n], &st.kx[..n], &st.ky[..n], &st.phi0[..n]);
        for (p, o) in points.iter().zip(out.iter_mut()) {
            let zeta = p.z - self.settings.surface_z;
            if self.deep_cutoff.is_some_and(|cut| zeta < cut) {
                *o = WaterPoint::STILL;
                continue;
            }
            // pass 1: θ, its sine and cosine, η (every component: η is the
            // surface's, whatever the point's depth)
            phase_sin_cos(kx, ky, wt, phi0, p, sin, cos);
            let mut sum = [0.0; LANES];
            dot_into(&st.a[..n], cos, &mut sum);
            let eta = r * sum.iter().sum::<f64>();
            let (zp, _, _) = self.stretch(zeta, eta);
            // pass 2: the components whose e^{kζ′} ≥ e^{−38}, rounded up to
            // whole lanes (the few beyond are evaluated at kζ′ ≥ −38: below
            // 2e^{−38} of their surface values either way)
            let active = if zp < 0.0 { k.partition_point(|k| k * zp >= -DECAY_LENGTHS) } else { n };
            let m = active.div_ceil(LANES) * LANES;
            decay_exp(&k[..m], zp, exp);
            let mut sums = [[0.0; LANES]; 6];
            match self.settings.depth {
                None => add_kinematics::<true>(st, 0, &sin[..m], cos, exp, &mut sums),
                Some(_) => add_kinematics::<false>(st, 0, &sin[..m], cos, exp, &mut sums),
            }
            let (vel, acc) = kinematics_total(&sums);
            *o = WaterPoint { elevation: eta, velocity: vel * r, acceleration: acc * r + vel * dr };
        }
    }

    fn evaluate(&self, p: &V3, t: f64, mut cache: Option<&mut [[f64; 2]]>) -> WavePoint {
        let (r, dr) = self.settings.ramp.at(t);
        let zeta = p.z - self.settings.surface_z;
        if r == 0.0 {
            return WavePoint::STILL;
        }
        if self.deep_cutoff.is_some_and(|cut| zeta < cut) {
            return WavePoint { deep: true, ..WavePoint::STILL };
        }
        // pass 1: η and its slope
        let (mut eta, mut ex, mut ey) = (0.0, 0.0, 0.0);
        for (i, c) in self.terms.iter().enumerate() {
            let (s, co) = (c.kx * p.x + c.ky * p.y - c.omega * t + c.phi0).sin_cos();
            eta += c.a * co;
            ex -= c.a * c.kx * s;
            ey -= c.a * c.ky * s;
            if let Some(cache) = cache.as_deref_mut() {
                cache[i] = [s, co];
            }
        }
        let (eta, ex, ey) = (r * eta, r * ex, r * ey);
        let (zp, z_z, z_e) = self.stretch(zeta, eta);
        // ∂ζ′/∂x, ∂ζ′/∂y, ∂ζ′/∂z
        let dzp = [z_e * ex, z_e * ey, z_z];
        // pass 2: the kinematics at ζ′
        let mut vel = V3::zeros();
        let mut acc = V3::zeros();
        let mut grad = M3::zeros();
        for (i, c) in self.terms.iter().enumerate() {
            let (s, co) = match cache.as_deref() {
                Some(cache) => (cache[i][0], cache[i][1]),
                None => (c.kx * p.x + c.ky * p.y - c.omega * t + c.phi0).sin_cos(),
            };
            let (ch, sh) = self.depth_factors(c, zp);
            let uh = c.aw * ch * co;
            let w = c.aw * sh * s;
            let duh = c.aw2 * ch * s;
            let dw = -c.aw2 * sh * co;
            vel += V3::new(uh * c.cos_b, uh * c.sin_b, w);
            acc += V3::new(duh * c.cos_b, duh * c.sin_b, dw);
            // ∂u_h/∂x_j = a ω (k S ζ′_j cos θ − C κ_j sin θ), ∂w/∂x_j = a ω (k C ζ′_j sin θ + S κ_j cos θ)
            let (hs, hc) = (c.aw * c.k * sh * co, c.aw * ch * s);
            let (ws, wc) = (c.aw * c.k * ch * s, c.aw * sh * co);
            let duh_dx = [hs * dzp[0] - hc * c.kx, hs * dzp[1] - hc * c.ky, hs * dzp[2]];
            let dw_dx = [ws * dzp[0] + wc * c.kx, ws * dzp[1] + wc * c.ky, ws * dzp[2]];
            for j in 0..3 {
                grad[(0, j)] += c.cos_b * duh_dx[j];
                grad[(1, j)] += c.sin_b * duh_dx[j];
                grad[(2, j)] += dw_dx[j];
            }
        }
        WavePoint {
            elevation: eta,
            velocity: vel * r,
            acceleration: acc * r + vel * dr,
            gradient: grad * r,
            deep: false,
        }
    }
}

/// [`Sea::water_batch`]'s loop as pulp's operation: `with_simd` is
/// compiled inside pulp's target-feature function for each instruction set.
struct WaterPoints<'a> {
    sea: &'a Sea,
    r: f64,
    dr: f64,
    points: &'a [V3],
    out: &'a mut [WaterPoint],
    scratch: &'a mut WaveScratch,
}

impl pulp::WithSimd for WaterPoints<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        self.sea.water_points(self.r, self.dr, self.points, self.out, self.scratch);
    }
}

/// [`Sea::water`]'s body as pulp's operation (as [`WaterPoints`]).
struct WaterOnePoint<'a> {
    sea: &'a Sea,
    p: &'a V3,
    t: f64,
    r: f64,
    dr: f64,
}

impl pulp::WithSimd for WaterOnePoint<'_> {
    type Output = WaterPoint;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> WaterPoint {
        self.sea.water_one_point(self.p, self.t, self.r, self.dr)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Component, Ramp, SeaSettings};
    use super::*;

    fn sea(stretching: Stretching, depth: Option<f64>) -> Sea {
        let components = vec![
            Component { frequency: 0.1, amplitude: 2.0, phase: 0.3, direction: 0.4 },
            Component { frequency: 0.13, amplitude: 1.0, phase: 1.1, direction: -0.2 },
            Component { frequency: 0.21, amplitude: 0.4, phase: 2.0, direction: 1.0 },
        ];
        let settings = SeaSettings {
            depth,
            gravity: 9.81,
            surface_z: 10.0,
            origin: [3.0, -2.0],
            stretching,
            ramp: Ramp { start: 0.0, duration: 0.0 },
        };
        Sea::new(components, settings)
    }

    #[test]
    fn the_velocity_gradient_matches_finite_differences() {
        for stretching in [Stretching::Wheeler, Stretching::Vertical, Stretching::None] {
            for depth in [None, Some(60.0)] {
                let s = sea(stretching, depth);
                let t = 7.3;
                for p in [V3::new(5.0, 1.0, 8.0), V3::new(-20.0, 4.0, -15.0), V3::new(11.0, -3.0, 10.5)] {
                    let k = s.kinematics(&p, t);
                    let e = 1e-6;
                    for j in 0..3 {
                        let mut a = p;
                        a[j] += e;
                        let mut b = p;
                        b[j] -= e;
                        let fd = (s.kinematics(&a, t).velocity - s.kinematics(&b, t).velocity) / (2.0 * e);
                        let err = (fd - k.gradient.column(j)).norm();
                        assert!(
                            err < 1e-7,
                            "{stretching:?} {depth:?} {p:?} column {j}: {fd:?} vs {:?}",
                            k.gradient.column(j)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_batch_equals_the_single_point_evaluation_and_deep_points_are_still() {
        let s = sea(Stretching::Wheeler, None);
        let points: Vec<V3> =
            (0..50).map(|i| V3::new(i as f64 * 3.0, 0.5 * i as f64, 12.0 - 30.0 * i as f64)).collect();
        let mut out = vec![WavePoint::STILL; points.len()];
        let mut scratch = WaveScratch::default();
        s.kinematics_batch(4.0, &points, &mut out, &mut scratch);
        for (p, o) in points.iter().zip(&out) {
            assert_eq!(*o, s.kinematics(p, 4.0));
        }
        let cut = s.deep_cutoff().unwrap();
        assert!(out.iter().any(|o| o.deep));
        // just above the cutoff the field is already negligible
        let above = s.kinematics(&V3::new(0.0, 0.0, 10.0 + cut + 1e-9), 4.0);
        assert!(above.velocity.norm() < 1e-15 && !above.deep);
    }

    /// A sea of 13 components from 0.05 Hz to 1.2 Hz (k from 0.01 to
    /// 5.8 rad/m: the short ones reach the per-component cutoff 7 m down)
    /// in seven directions, given out of order of k, ramping in.
    fn broad_sea(stretching: Stretching, depth: Option<f64>) -> Sea {
        let components = (0..13)
            .map(|i| {
                let f = 0.05 + 0.0959 * ((i * 5) % 13) as f64;
                Component {
                    frequency: f,
                    amplitude: 0.6 / (1.0 + 4.0 * f),
                    phase: 0.7 * i as f64,
                    direction: -1.3 + 0.41 * (i % 7) as f64,
                }
            })
            .collect();
        let settings = SeaSettings {
            depth,
            gravity: 9.81,
            surface_z: -4.0,
            origin: [12.0, 5.0],
            stretching,
            ramp: Ramp { start: 1.0, duration: 10.0 },
        };
        Sea::new(components, settings)
    }

    #[test]
    fn the_water_batch_equals_the_kinematics_at_every_depth_to_round_off_and_the_one_point_water_bit_for_bit() {
        for stretching in [Stretching::Wheeler, Stretching::Vertical, Stretching::None] {
            for depth in [None, Some(60.0), Some(400.0)] {
                let s = broad_sea(stretching, depth);
                let (mut k_max, mut a_sum, mut aw_sum, mut aw2_sum) = (0.0f64, 0.0, 0.0, 0.0);
                for (c, k) in s.components().iter().zip(s.wave_numbers()) {
                    let w = 2.0 * std::f64::consts::PI * c.frequency;
                    k_max = k_max.max(k);
                    a_sum += c.amplitude;
                    aw_sum += c.amplitude * w;
                    aw2_sum += c.amplitude * w * w;
                }
                // the components' order is the user's, the batch's is by k
                assert!(s.wave_numbers().windows(2).any(|w| w[0] > w[1]));
                let bottom = depth.unwrap_or(5000.0);
                // from above the highest crest down to the seabed (and,
                // in deep water, below the whole-point cutoff)
                let points: Vec<V3> = (0..=120)
                    .map(|i| {
                        let zeta = 1.2 * a_sum - (i as f64 / 120.0).powi(3) * (bottom + 1.2 * a_sum);
                        V3::new(-30.0 + 7.3 * i as f64, 11.0 - 2.9 * i as f64, -4.0 + zeta)
                    })
                    .collect();
                let mut out = vec![WaterPoint::STILL; points.len()];
                let mut scratch = WaveScratch::default();
                let mut below_component_cutoff = 0;
                let mut worst = 0.0f64;
                for t in [0.5, 4.0, 11.0, 1234.5] {
                    s.water_batch(t, &points, &mut out, &mut scratch);
                    for (p, o) in points.iter().zip(&out) {
                        let k = s.kinematics(p, t);
                        let zp = s.stretch(p.z + 4.0, k.elevation).0;
                        if k_max * zp < -DECAY_LENGTHS && !k.deep {
                            below_component_cutoff += 1;
                        }
                        let what = format!("{stretching:?} {depth:?} t {t} {p:?}: {o:?} vs {k:?}");
                        worst = worst
                            .max((o.elevation - k.elevation).abs() / a_sum)
                            .max((o.velocity - k.velocity).norm() / aw_sum)
                            .max((o.acceleration - k.acceleration).norm() / (aw2_sum + aw_sum));
                        assert!((o.elevation - k.elevation).abs() <= 1e-12 * a_sum, "{what}");
                        assert!((o.velocity - k.velocity).norm() <= 1e-12 * aw_sum, "{what}");
                        assert!((o.acceleration - k.acceleration).norm() <= 1e-12 * (aw2_sum + aw_sum), "{what}");
                        if k.deep {
                            assert_eq!(*o, WaterPoint::STILL);
                        }
                        // the one-point form (the outputs'): the batch's bits
                        assert_eq!(s.water(p, t), *o, "{what}");
                    }
                }
                eprintln!("{stretching:?} {depth:?}: largest difference {worst:.1e} of the surface scale");
                assert!(below_component_cutoff > 50, "{below_component_cutoff}");
                if depth.is_none() {
                    assert!(points.iter().any(|p| p.z + 4.0 < s.deep_cutoff().unwrap()));
                }
            }
        }
    }

    /// A sea of more components than [`CHUNK`] (the one-point water takes
    /// them in three chunks and evaluates the phases again in pass 2): the
    /// same bits as the batch, at points from above the crests to below
    /// every component's cut, in deep and finite depth.
    #[test]
    fn the_one_point_water_of_a_sea_of_many_components_has_the_batchs_bits() {
        for depth in [None, Some(80.0)] {
            let components: Vec<Component> = (0..2 * CHUNK + 37)
                .map(|i| Component {
                    frequency: 0.04 + 0.0011 * ((i * 7) % 549) as f64,
                    amplitude: 0.3 / (1.0 + 10.0 * (0.0011 * i as f64)),
                    phase: 0.37 * i as f64,
                    direction: 0.2 - 0.003 * i as f64,
                })
                .collect();
            let settings = SeaSettings {
                depth,
                gravity: 9.81,
                surface_z: 2.0,
                origin: [0.0, 0.0],
                stretching: Stretching::Wheeler,
                ramp: Ramp { start: 0.0, duration: 30.0 },
            };
            let s = Sea::new(components, settings);
            let points: Vec<V3> =
                (0..60).map(|i| V3::new(4.1 * i as f64, 0.7 * i as f64, 5.0 - 1.3 * i as f64)).collect();
            let mut out = vec![WaterPoint::STILL; points.len()];
            let mut scratch = WaveScratch::default();
            for t in [17.0, 47.5] {
                s.water_batch(t, &points, &mut out, &mut scratch);
                assert!(out.iter().any(|o| o.velocity.norm() > 0.05), "{out:?}");
                for (p, o) in points.iter().zip(&out) {
                    assert_eq!(s.water(p, t), *o, "{depth:?} t {t} {p:?}");
                }
            }
        }
    }

    #[test]
    fn the_water_batch_has_the_same_bits_on_every_instruction_set() {
        let s = broad_sea(Stretching::Wheeler, Some(60.0));
        let points: Vec<V3> =
            (0..40).map(|i| V3::new(3.0 * i as f64, -1.5 * i as f64, -4.5 - 1.5 * i as f64)).collect();
        let mut a = vec![WaterPoint::STILL; points.len()];
        let mut b = a.clone();
        let mut scratch = WaveScratch::default();
        s.water_batch(13.0, &points, &mut a, &mut scratch);
        let (r, dr) = s.settings.ramp.at(13.0);
        // the portable body, with the scratch's ω t of the call above
        s.water_points(r, dr, &points, &mut b, &mut scratch);
        assert_eq!(a, b);
        // and each x86 instruction set this processor has, by name (the
        // dispatch above took the widest: AVX-512 where there is one)
        #[cfg(target_arch = "x86_64")]
        {
            let by = |vectorize: &dyn Fn(WaterPoints<'_>)| {
                let mut c = vec![WaterPoint::STILL; points.len()];
                vectorize(WaterPoints { sea: &s, r, dr, points: &points, out: &mut c, scratch: &mut scratch.clone() });
                assert_eq!(a, c);
            };
            if let Some(v3) = pulp::x86::V3::try_new() {
                by(&|op| pulp::Simd::vectorize(v3, op));
            }
            if let Some(v4) = pulp::x86::V4::try_new() {
                by(&|op| pulp::Simd::vectorize(v4, op));
            }
        }
    }
}
