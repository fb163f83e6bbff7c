//! Morison drag (paper eqs. 13–17) per unit current length of line:
//!   f = ½ ρw D [C_Dn |v_rn| v_rn + C_Dt |v_rt| v_rt],
//!   v_r = v_c − v,  v_rt = (v_r·t) t,  v_rn = v_r − v_rt,
//! with t the unit tangent of the centreline and D the outer diameter (the
//! paper uses D as reference length for both terms; MoorDyn uses πD for the
//! tangential one).

use crate::math::{M3, V3};

/// Drag coefficients premultiplied: k = ½ ρw D C_D (kg/m²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DragCoefficients {
    pub normal: f64,
    pub tangential: f64,
}

impl DragCoefficients {
    pub fn new(water_density: f64, diameter: f64, cd_normal: f64, cd_tangential: f64) -> Self {
        DragCoefficients {
            normal: 0.5 * water_density * diameter * cd_normal,
            tangential: 0.5 * water_density * diameter * cd_tangential,
        }
    }

    pub fn is_zero(&self) -> bool {
        self.normal == 0.0 && self.tangential == 0.0
    }
}

/// Drag force per unit current length (N/m) and its derivatives with respect
/// to the relative velocity v_r and to the unit tangent t.
#[derive(Debug, Clone, Copy)]
pub struct Drag {
    pub force: V3,
    pub d_vrel: M3,
    pub d_tangent: M3,
}

/// g(a) = |a| a and its derivative |a| I + a aᵀ/|a|.
#[inline]
fn abs_times(a: &V3) -> (V3, M3) {
    let n = a.norm();
    if n == 0.0 { (V3::zeros(), M3::zeros()) } else { (a * n, M3::identity() * n + a * a.transpose() / n) }
}

/// The drag force alone (no derivatives), for residual-only evaluations.
/// `t` must be a unit vector (|v_rt| is taken as |v_r·t|).
pub fn drag_force(k: &DragCoefficients, vrel: &V3, t: &V3) -> V3 {
    let vt = t.dot(vrel);
    let vrt = t * vt;
    let vrn = vrel - vrt;
    vrn * (vrn.norm() * k.normal) + vrt * (vt.abs() * k.tangential)
}

/// Morison drag for relative velocity `vrel` = v_current − v_line and unit tangent `t`.
pub fn drag(k: &DragCoefficients, vrel: &V3, t: &V3) -> Drag {
    let vt_s = t.dot(vrel);
    let vrt = t * vt_s;
    let vrn = vrel - vrt;
    let ttt = t * t.transpose();
    let dvrt_dv = ttt;
    let dvrt_dt = M3::identity() * vt_s + t * vrel.transpose();
    let (gn, dgn) = abs_times(&vrn);
    let (gt, dgt) = abs_times(&vrt);
    let force = gn * k.normal + gt * k.tangential;
    let d_vrel = dgn * (M3::identity() - dvrt_dv) * k.normal + dgt * dvrt_dv * k.tangential;
    let d_tangent = (dgt * k.tangential - dgn * k.normal) * dvrt_dt;
    Drag { force, d_vrel, d_tangent }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drag_derivatives_match_finite_differences() {
        let k = DragCoefficients::new(1025.0, 0.3, 0.6, 0.05);
        let v = V3::new(0.7, -0.2, 0.3);
        let t = V3::new(0.6, 0.1, -0.79).normalize();
        let d = drag(&k, &v, &t);
        let e = 1e-6;
        for j in 0..3 {
            let mut vp = v;
            vp[j] += e;
            let mut vm = v;
            vm[j] -= e;
            let fd = (drag(&k, &vp, &t).force - drag(&k, &vm, &t).force) / (2.0 * e);
            assert!((fd - d.d_vrel.column(j)).norm() < 1e-6 * (1.0 + fd.norm()));
            let mut tp = t;
            tp[j] += e;
            let mut tm = t;
            tm[j] -= e;
            let fd = (drag(&k, &v, &tp).force - drag(&k, &v, &tm).force) / (2.0 * e);
            assert!((fd - d.d_tangent.column(j)).norm() < 1e-6 * (1.0 + fd.norm()));
        }
        // a purely normal flow gets the normal coefficient only
        let n = V3::new(0.0, 1.0, 0.0);
        let d = drag(&k, &(n * 2.0), &V3::x());
        assert!((d.force - n * (k.normal * 4.0)).norm() < 1e-12);
        // the force-only path agrees
        assert!((drag_force(&k, &v, &t) - drag(&k, &v, &t).force).norm() < 1e-14);
        // drag opposes motion in still water: f·v ≤ 0
        let d = drag(&k, &(-v), &t);
        assert!(d.force.dot(&v) < 0.0);
    }
}
