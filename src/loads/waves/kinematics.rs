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

use super::{Sea, Stretching, Term};
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

/// Reusable storage of [`Sea::kinematics_batch`]: one (sin θ, cos θ) per
/// component (allocated at the first call, reused after).
#[derive(Debug, Clone, Default)]
pub struct WaveScratch {
    sin_cos: Vec<[f64; 2]>,
}

impl WaveScratch {
    /// Grows the buffer to `components` entries.
    pub(crate) fn reserve(&mut self, components: usize) {
        if self.sin_cos.len() < components {
            self.sin_cos.resize(components, [0.0; 2]);
        }
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
    /// once per step at the Gauss points of the whole line (equal to the
    /// fields of [`Sea::kinematics`]).
    pub fn water_batch(&self, t: f64, points: &[V3], out: &mut [WaterPoint], scratch: &mut WaveScratch) {
        if scratch.sin_cos.len() < self.terms.len() {
            scratch.sin_cos.resize(self.terms.len(), [0.0; 2]);
        }
        for (p, o) in points.iter().zip(out.iter_mut()) {
            let k = self.evaluate(p, t, Some(&mut scratch.sin_cos));
            *o = WaterPoint { elevation: k.elevation, velocity: k.velocity, acceleration: k.acceleration };
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
}
