//! Current profiles: the horizontal water velocity as a function of the
//! reference arc length S (the paper's lazy-wave profile is linear in S) or of
//! the depth below the free surface.

use crate::math::V3;

/// Speed of the current (m/s, signed along the current direction).
#[derive(Debug, Clone, PartialEq)]
pub enum CurrentProfile {
    /// No current.
    None,
    /// The same speed everywhere.
    Uniform { speed: f64 },
    /// Linear in the reference arc length S from `top` (S = 0, hang-off) to
    /// `bottom` (S = length, anchor), as in the paper's lazy-wave case.
    LinearInS { top: f64, bottom: f64, length: f64 },
    /// Linear in depth below `surface_z` from `top` (at the surface) to `bottom`
    /// (at `depth` m below it), constant below.
    LinearInDepth { top: f64, bottom: f64, depth: f64, surface_z: f64 },
    /// Piecewise linear in depth below `surface_z`: (depth m, speed m/s) rows
    /// with increasing depth; constant beyond the first and last rows.
    Table { rows: Vec<(f64, f64)>, surface_z: f64 },
}

/// A current profile and its horizontal direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Current {
    pub profile: CurrentProfile,
    /// Unit vector of the flow direction.
    pub direction: V3,
}

impl Current {
    pub fn none() -> Self {
        Current { profile: CurrentProfile::None, direction: V3::x() }
    }

    pub fn is_none(&self) -> bool {
        matches!(self.profile, CurrentProfile::None)
    }

    /// Speed (m/s) at reference arc length `s` (m) and height `z` (m), and
    /// its derivative with respect to z (1/s).
    pub fn speed(&self, s: f64, z: f64) -> (f64, f64) {
        match &self.profile {
            CurrentProfile::None => (0.0, 0.0),
            CurrentProfile::Uniform { speed } => (*speed, 0.0),
            CurrentProfile::LinearInS { top, bottom, length } => {
                let f = (s / length).clamp(0.0, 1.0);
                (top + (bottom - top) * f, 0.0)
            }
            CurrentProfile::LinearInDepth { top, bottom, depth, surface_z } => {
                let dep = surface_z - z;
                if dep <= 0.0 {
                    (*top, 0.0)
                } else if dep >= *depth {
                    (*bottom, 0.0)
                } else {
                    let slope = (bottom - top) / depth;
                    (top + slope * dep, -slope)
                }
            }
            CurrentProfile::Table { rows, surface_z } => {
                let dep = surface_z - z;
                let first = rows[0];
                let last = rows[rows.len() - 1];
                if dep <= first.0 {
                    return (first.1, 0.0);
                }
                if dep >= last.0 {
                    return (last.1, 0.0);
                }
                for w in rows.windows(2) {
                    let (d0, v0) = w[0];
                    let (d1, v1) = w[1];
                    if dep <= d1 {
                        let slope = (v1 - v0) / (d1 - d0);
                        return (v0 + slope * (dep - d0), -slope);
                    }
                }
                (last.1, 0.0)
            }
        }
    }

    /// Velocity vector (m/s) and its z-derivative.
    pub fn velocity(&self, s: f64, z: f64) -> (V3, V3) {
        let (v, dv) = self.speed(s, z);
        (self.direction * v, self.direction * dv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_interpolate_and_differentiate() {
        let c =
            Current { profile: CurrentProfile::LinearInS { top: 0.8, bottom: 0.3, length: 100.0 }, direction: V3::x() };
        assert!((c.speed(50.0, -20.0).0 - 0.55).abs() < 1e-15);
        let c = Current {
            profile: CurrentProfile::Table { rows: vec![(0.0, 1.0), (50.0, 0.5), (100.0, 0.0)], surface_z: 10.0 },
            direction: V3::x(),
        };
        let (v, dv) = c.speed(0.0, 10.0 - 75.0);
        assert!((v - 0.25).abs() < 1e-15);
        // finite difference in z
        let e = 1e-6;
        let fd = (c.speed(0.0, -65.0 + e).0 - c.speed(0.0, -65.0 - e).0) / (2.0 * e);
        assert!((fd - dv).abs() < 1e-9);
        let c = Current {
            profile: CurrentProfile::LinearInDepth { top: 1.0, bottom: 0.2, depth: 80.0, surface_z: 10.0 },
            direction: V3::x(),
        };
        let fd = (c.speed(0.0, -30.0 + e).0 - c.speed(0.0, -30.0 - e).0) / (2.0 * e);
        assert!((fd - c.speed(0.0, -30.0).1).abs() < 1e-9);
    }
}
