//! DNV-OS-F201's LRFD combined-loading criterion of a pipe with net internal
//! overpressure (docs/theory.md §12.4, (12.10)–(12.14)): the design bending
//! moment, effective tension and pressure against the wall's plastic moment,
//! plastic tension and burst resistance, with the load effect factors γ_F,
//! γ_E, the material resistance factor γ_m and the safety class's γ_SC. The
//! criterion for net external overpressure (with the collapse resistance) is
//! not implemented: riser reports no LRFD utilisation there.

pub use crate::scene::{ENVIRONMENTAL_LOAD_FACTOR, FUNCTIONAL_LOAD_FACTOR, MATERIAL_RESISTANCE_FACTOR};
use crate::scene::{Line, SafetyClass};

/// The name of the check in the outputs.
pub const LRFD_CHECK: &str = "DNV-OS-F201 LRFD combined loading (net internal overpressure)";

/// γ_SC, the safety class resistance factor: 1.04 low, 1.14 normal, 1.26 high.
pub fn safety_class_factor(class: SafetyClass) -> f64 {
    match class {
        SafetyClass::Low => 1.04,
        SafetyClass::Normal => 1.14,
        SafetyClass::High => 1.26,
    }
}

/// The factors of the check: γ_F, γ_E, γ_m and γ_SC.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LrfdFactors {
    pub functional: f64,
    pub environmental: f64,
    pub material: f64,
    pub safety_class: f64,
}

impl LrfdFactors {
    /// The line's factors; None without a safety class (no LRFD check).
    pub fn of(line: &Line) -> Option<LrfdFactors> {
        Some(LrfdFactors {
            functional: line.load_factor_functional.unwrap_or(FUNCTIONAL_LOAD_FACTOR),
            environmental: line.load_factor_environmental.unwrap_or(ENVIRONMENTAL_LOAD_FACTOR),
            material: line.material_resistance_factor.unwrap_or(MATERIAL_RESISTANCE_FACTOR),
            safety_class: safety_class_factor(line.safety_class?),
        })
    }

    /// The magnitude of the design load effect of the functional part `f`
    /// and the environmental part `e` (components of one vector: the
    /// bending moment's two, N m, or the effective tension, N) (12.14):
    /// |γ_F f + γ_E e|, a factor taken as 1/γ where its part reduces the
    /// effect: the largest of the four combinations.
    pub fn design_effect<const N: usize>(&self, f: [f64; N], e: [f64; N]) -> f64 {
        let mut largest = 0.0f64;
        for gf in [self.functional, 1.0 / self.functional] {
            for ge in [self.environmental, 1.0 / self.environmental] {
                let norm2: f64 = f.iter().zip(&e).map(|(a, b)| (gf * a + ge * b).powi(2)).sum();
                largest = largest.max(norm2.sqrt());
            }
        }
        largest
    }
}

/// A wall as the check sees it: its nominal outer diameter D (m), its
/// thickness t₂ (m: the nominal less the corrosion allowance) and the
/// characteristic yield and tensile strengths f_y, f_u (Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LrfdWall {
    pub diameter: f64,
    pub thickness: f64,
    pub yield_strength: f64,
    pub tensile_strength: f64,
}

impl LrfdWall {
    /// The burst resistance p_b(t₂) = (2/√3) (2 t₂/(D − t₂)) min(f_y, f_u/1.15), Pa (12.11).
    pub fn burst_resistance(&self) -> f64 {
        let (d, t) = (self.diameter, self.thickness);
        2.0 / 3f64.sqrt() * (2.0 * t / (d - t)) * self.yield_strength.min(self.tensile_strength / 1.15)
    }

    /// The strain hardening factor α_c = (1 − β) + β f_u/f_y, with
    /// β = (0.4 + q_h) for D/t₂ < 15, (0.4 + q_h)(60 − D/t₂)/45 up to 60, 0
    /// above, and q_h = (Δp/p_b) 2/√3 for the net internal overpressure Δp
    /// (Pa, 0 without one) (12.13).
    pub fn strain_hardening(&self, dp: f64) -> f64 {
        let q_h = if dp > 0.0 { dp / self.burst_resistance() * 2.0 / 3f64.sqrt() } else { 0.0 };
        let slenderness = self.diameter / self.thickness;
        let beta = if slenderness < 15.0 {
            0.4 + q_h
        } else if slenderness <= 60.0 {
            (0.4 + q_h) * (60.0 - slenderness) / 45.0
        } else {
            0.0
        };
        (1.0 - beta) + beta * self.tensile_strength / self.yield_strength
    }

    /// The plastic bending moment M_k = f_y α_c (D − t₂)² t₂, N m, and the
    /// plastic tension T_k = f_y α_c π (D − t₂) t₂, N, at the net internal
    /// overpressure `dp` (Pa) (12.12).
    pub fn plastic_capacities(&self, dp: f64) -> (f64, f64) {
        let (d, t) = (self.diameter, self.thickness);
        let f = self.yield_strength * self.strain_hardening(dp);
        (f * (d - t) * (d - t) * t, f * std::f64::consts::PI * (d - t) * t)
    }

    /// The utilisation under the design moment `moment` (N m), effective
    /// tension `tension` (N) and net internal overpressure p_ld − p_e `dp`
    /// (Pa, > 0) (12.10):
    /// γ_SC γ_m [(|M_d|/M_k) √(1 − (Δp/p_b)²) + (T_ed/T_k)²] + (Δp/p_b)².
    /// Beyond the burst resistance (Δp > p_b) the root is taken as 0: the
    /// utilisation is then above 1 by the pressure alone.
    pub fn utilisation(&self, factors: &LrfdFactors, moment: f64, tension: f64, dp: f64) -> f64 {
        let pressure = dp / self.burst_resistance();
        let (m_k, t_k) = self.plastic_capacities(dp);
        let gamma = factors.safety_class * factors.material;
        let root = (1.0 - pressure * pressure).max(0.0).sqrt();
        gamma * (moment.abs() / m_k * root + (tension / t_k).powi(2)) + pressure * pressure
    }
}

#[cfg(test)]
mod tests {
    use super::{LrfdFactors, LrfdWall};

    /// The criterion reproduces the published numbers of a practitioner's
    /// DNV-OS-F201 WSD-versus-LRFD calculation sheet (digitalmodel's oracle
    /// tests, docs/theory.md §12.4): a 20 in pipe, t₂ = 0.82678 in, f_y =
    /// 62.4 ksi, f_u = 73.92 ksi (X65 with α_U = 0.96), 3 ksi inside, none
    /// outside, M_d = 1252.8 kips ft, no tension, γ_SC γ_m = 1.26: p_b
    /// 6.214109 ksi, α_c 1.140662, M_k 1802.77008 kips ft, T_k 3544.674857
    /// kips, utilisation 0.999883, each to the sheet's 6 to 7 figures (in
    /// its own units: the formulas are homogeneous). With γ_SC γ_m on the
    /// pressure term, the recalled alternative, it would be 1.137.
    #[test]
    fn the_criterion_reproduces_a_published_calculation_sheet() {
        let wall = LrfdWall { diameter: 20.0, thickness: 0.82678, yield_strength: 62.4, tensile_strength: 73.92 };
        let f = LrfdFactors { functional: 1.1, environmental: 1.3, material: 1.0, safety_class: 1.26 };
        let p_b = wall.burst_resistance();
        let alpha_c = wall.strain_hardening(3.0);
        let (m_k, t_k) = wall.plastic_capacities(3.0);
        let u = wall.utilisation(&f, -1252.8 * 12.0, 0.0, 3.0);
        println!("p_b {p_b:.7} ksi, alpha_c {alpha_c:.7}, M_k {:.5} kips ft, T_k {t_k:.6} kips, U {u:.7}", m_k / 12.0);
        assert!((p_b / 6.214109 - 1.0).abs() < 1e-6);
        assert!((alpha_c / 1.140662 - 1.0).abs() < 1e-6);
        assert!((m_k / 12.0 / 1802.77008 - 1.0).abs() < 1e-6);
        assert!((t_k / 3544.674857 - 1.0).abs() < 1e-6);
        assert!((u - 0.999883).abs() < 1e-6);
    }

    /// (12.14): a part that reduces the effect takes 1/γ: a moment whose
    /// environmental part opposes its functional one, tension unloaded.
    #[test]
    fn a_part_that_reduces_the_effect_takes_the_inverse_factor() {
        let f = LrfdFactors { functional: 1.1, environmental: 1.3, material: 1.15, safety_class: 1.14 };
        assert!((f.design_effect([100.0], [20.0]) - (110.0 + 26.0)).abs() < 1e-9);
        assert!((f.design_effect([100.0], [-20.0]) - (110.0 - 20.0 / 1.3)).abs() < 1e-9);
        assert!((f.design_effect([10.0], [-100.0]) - (130.0 - 10.0 / 1.1)).abs() < 1e-9);
        assert!((f.design_effect([3.0, 0.0], [0.0, 4.0]) - (3.3f64.hypot(5.2))).abs() < 1e-9);
    }
}
