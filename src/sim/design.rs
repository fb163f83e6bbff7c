//! The numbers a riser engineer reads first (docs/theory.md §12): the
//! touchdown point, the hang-off angle, the curvature and bending moment, the
//! axial strain, the outer-fibre stress and its range over a window; and the
//! warnings of a model that is implausible or under-resolved.

use super::Engine;
use super::lrfd::{LRFD_CHECK, LrfdFactors, LrfdWall};
use crate::math::V3;
use crate::model::outputs::LinePoint;
use crate::model::sections::{self, PerElement};
use crate::model::{Outputs, State};
use crate::scene::sections::LineProperties;
use crate::scene::{Model, Scene};

/// Axial strain above which riser warns: no riser, umbilical or cable
/// stretches this far elastically (steel yields near 0.2 %, a flexible pipe's
/// armour wires are designed well below that; polyester ropes are mooring
/// lines, not what riser models).
pub const STRAIN_LIMIT: f64 = 0.01;

/// Elements per bending length √(EI/T) at the touchdown below which riser
/// warns. Measured on steel_catenary (λ = 17 m) under heave 2 m / 12 s
/// against 160 elements (docs/theory.md §12.3): the steady window's smallest
/// axial force is 12 % low at 0.5 element per λ, 1.1 % at one, 0.2 % at two;
/// the stress range at the touchdown converges slowly and not monotonically
/// (−6 %, +11 %, −2.7 %, +1.1 % at 0.5, 1, 2, 4 elements per λ).
pub const ELEMENTS_PER_BENDING_LENGTH: f64 = 2.0;

/// Fibres around the circumference at which the stress range is tracked
/// (every 45°, as fatigue post-processors do).
pub const FIBRES: usize = 8;

/// The wall of a piece of line, whose stresses riser reports (12.1, 12.6):
/// the steel wall the scene gives (`wall_thickness`, docs/theory.md §12.4),
/// or else the homogeneous tube that has the line's EA, EI and pipe
/// diameter D: EA = E π (D² − d²)/4 and EI = E π (D⁴ − d⁴)/64 give
/// d² = 16 EI/EA − D² and E = EA / A.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tube {
    /// Wall area A_s, m².
    pub area: f64,
    /// Young's modulus E, Pa.
    pub modulus: f64,
    /// Outer radius of the steel r_o, m.
    pub outer_radius: f64,
    /// Inner radius r_i (the bore's), m.
    pub inner_radius: f64,
    /// Shear modulus G = GJ / J, J = π (r_o⁴ − r_i⁴)/2 the wall's polar
    /// moment, Pa (0 with GJ = 0).
    pub shear_modulus: f64,
    /// The area over which the water's pressure acts, A_e = π D²/4, D the
    /// pipe's outer diameter (its coating's, not its modules'), m²: the
    /// diameter of the buoyancy the model applies (12.6).
    pub external_area: f64,
    /// Yield stress σ_y, Pa, when the scene gives one.
    pub yield_stress: Option<f64>,
    /// Tensile strength f_u, Pa, when the scene gives one.
    pub tensile_strength: Option<f64>,
}

impl Tube {
    /// The tube of `p`: its wall when the scene gives one, else the
    /// homogeneous tube of its EA, EI and D, or None when there is none
    /// (0 ≤ d² < D² fails): a flexible pipe or an umbilical, whose layers
    /// slide and whose stresses are per layer, beyond this model.
    pub fn of(p: &LineProperties) -> Option<Tube> {
        let pi = std::f64::consts::PI;
        let d_out = p.pipe_diameter;
        let external_area = pi * d_out * d_out / 4.0;
        let (area, modulus, r_o, r_i) = match p.wall {
            Some(w) => (w.area(), w.youngs_modulus, 0.5 * w.outer_diameter, 0.5 * w.inner_diameter()),
            None => {
                let d_in2 = 16.0 * p.bending_stiffness / p.axial_stiffness - d_out * d_out; // (12.1)
                if !(d_in2 >= 0.0 && d_in2 < d_out * d_out) {
                    return None;
                }
                let area = pi * (d_out * d_out - d_in2) / 4.0;
                (area, p.axial_stiffness / area, 0.5 * d_out, 0.5 * d_in2.sqrt())
            }
        };
        let polar = pi * (r_o.powi(4) - r_i.powi(4)) / 2.0;
        Some(Tube {
            area,
            modulus,
            outer_radius: r_o,
            inner_radius: r_i,
            shear_modulus: p.torsional_stiffness / polar,
            external_area,
            yield_stress: p.yield_stress,
            tensile_strength: p.tensile_strength,
        })
    }

    /// The wall as DNV-OS-F201's LRFD check sees it: D = 2 r_o, t₂ = r_o −
    /// r_i and the strengths; None without a yield stress or a tensile
    /// strength.
    pub fn lrfd_wall(&self) -> Option<LrfdWall> {
        Some(LrfdWall {
            diameter: 2.0 * self.outer_radius,
            thickness: self.outer_radius - self.inner_radius,
            yield_strength: self.yield_stress?,
            tensile_strength: self.tensile_strength?,
        })
    }

    /// The bore's area A_i = π r_i², m².
    pub fn bore_area(&self) -> f64 {
        std::f64::consts::PI * self.inner_radius * self.inner_radius
    }

    /// The true wall tension T_w = T_eff + p_i A_i − p_e A_e, N, of the
    /// effective tension `tension` (N) under the pressures `p` (12.6).
    pub fn wall_tension(&self, tension: f64, p: Pressures) -> f64 {
        tension + p.inside * self.bore_area() - p.outside * self.external_area
    }

    /// Axial stress at the outer fibre at angle θ from the section's first
    /// axis: σ = T_w/A + E r_o (κ₁ sin θ − κ₂ cos θ), Pa (12.2), T_w the
    /// true wall tension.
    pub fn fibre_stress(&self, wall_tension: f64, curvature: [f64; 2], theta: f64) -> f64 {
        self.fibre_stress_at(wall_tension, curvature, theta.cos(), theta.sin())
    }

    /// [`Tube::fibre_stress`] at the fibre whose angle has cosine `cos` and
    /// sine `sin` (12.2).
    pub fn fibre_stress_at(&self, wall_tension: f64, curvature: [f64; 2], cos: f64, sin: f64) -> f64 {
        let bending = curvature[0] * sin - curvature[1] * cos;
        wall_tension / self.area + self.modulus * self.outer_radius * bending
    }

    /// The largest axial stress around the outer fibre: T_w/A + E r_o |κ|, Pa (12.3).
    pub fn max_stress(&self, wall_tension: f64, curvature: f64) -> f64 {
        wall_tension / self.area + self.modulus * self.outer_radius * curvature.abs()
    }

    /// Lamé's thick-walled cylinder under p_i inside and p_e outside: the
    /// hoop and radial stress at radius r, Pa (12.7),
    /// σ_θ,r = (p_i r_i² − p_e r_o²)/(r_o² − r_i²) ± (p_i − p_e) r_i² r_o² / ((r_o² − r_i²) r²).
    /// A solid bar (r_i = 0) has σ_θ = σ_r = −p_e.
    pub fn lame(&self, p: Pressures, r: f64) -> (f64, f64) {
        let (a2, b2) = (self.inner_radius * self.inner_radius, self.outer_radius * self.outer_radius);
        let mean = (p.inside * a2 - p.outside * b2) / (b2 - a2);
        if a2 == 0.0 {
            return (-p.outside, -p.outside);
        }
        let varying = (p.inside - p.outside) * a2 * b2 / ((b2 - a2) * r * r);
        (mean + varying, mean - varying)
    }

    /// The largest von Mises stress over the section (12.8): at the fibres
    /// in and against the curvature (where the axial stress is largest and
    /// smallest; σ_vm² is a convex quadratic in σ_a, so the largest around
    /// a circle is at one of them) at the inner and the outer radius, with
    /// the true wall tension `wall_tension` (N), curvature |κ| (1/m, 0 for
    /// the cable), twist κ₃ (1/m) and the pressures `p`, Pa.
    pub fn max_von_mises(&self, wall_tension: f64, curvature: f64, twist: f64, p: Pressures) -> f64 {
        let mut largest = 0.0f64;
        for r in [self.inner_radius, self.outer_radius] {
            let (hoop, radial) = self.lame(p, r);
            let shear = self.shear_modulus * twist * r;
            let bending = self.modulus * r * curvature.abs();
            for axial in [wall_tension / self.area + bending, wall_tension / self.area - bending] {
                largest = largest.max(von_mises(axial, hoop, radial, shear));
            }
        }
        largest
    }
}

/// A point's outer-fibre axial stress around its section (12.2):
/// σ(θ) = T_w/A + E r_o (κ₁ sin θ − κ₂ cos θ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FibreStress {
    /// T_w/A, Pa.
    pub axial: f64,
    /// E r_o, Pa m.
    pub stiffness: f64,
    /// (κ₁, κ₂), 1/m (0 for the cable).
    pub curvature: [f64; 2],
}

impl FibreStress {
    /// σ at the fibre whose angle has cosine `cos` and sine `sin`, Pa: the
    /// operations of [`Tube::fibre_stress_at`], bit for bit.
    pub fn at(&self, cos: f64, sin: f64) -> f64 {
        self.axial + self.stiffness * (self.curvature[0] * sin - self.curvature[1] * cos)
    }
}

/// The von Mises stress of axial, hoop and radial normal stresses and the
/// torsional shear in the section's plane, Pa (12.8):
/// σ_vm = √(½[(σ_a − σ_θ)² + (σ_θ − σ_r)² + (σ_r − σ_a)²] + 3τ²).
pub fn von_mises(axial: f64, hoop: f64, radial: f64, shear: f64) -> f64 {
    let (a, h, r) = (axial - hoop, hoop - radial, radial - axial);
    (0.5 * (a * a + h * h + r * r) + 3.0 * shear * shear).sqrt()
}

/// The pressures on the wall at one point, Pa (gauge).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pressures {
    /// The contents' p_i.
    pub inside: f64,
    /// The water's p_e.
    pub outside: f64,
}

/// The fluids inside and outside a line (12.5): the water's hydrostatic
/// pressure outside, and the contents' pressure (at the hang-off) and
/// density inside.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fluids {
    /// ρ_w, kg/m³ (0: no water).
    pub water_density: f64,
    /// g, m/s².
    pub gravity: f64,
    /// z of the still water surface, m.
    pub water_surface_z: f64,
    /// ρ_i, kg/m³.
    pub internal_density: f64,
    /// The contents' gauge pressure at the hang-off, Pa.
    pub internal_pressure: f64,
}

impl Fluids {
    /// The fluids of a scene.
    pub fn of(scene: &Scene) -> Self {
        let env = &scene.environment;
        Fluids {
            water_density: env.water_density,
            gravity: env.gravity,
            water_surface_z: env.water_surface_z,
            internal_density: scene.line.internal_fluid_density.unwrap_or(0.0),
            internal_pressure: scene.line.internal_pressure.unwrap_or(0.0),
        }
    }

    /// The pressures at height z (m) with the hang-off at `hang_off_z` (12.5):
    /// p_i = p_i,0 + ρ_i g (z_h − z); p_e = ρ_w g (z_s − z) below the still
    /// water surface z_s, 0 above it.
    pub fn pressures(&self, z: f64, hang_off_z: f64) -> Pressures {
        let inside = self.internal_pressure + self.internal_density * self.gravity * (hang_off_z - z);
        let depth = self.water_surface_z - z;
        let outside = if depth > 0.0 { self.water_density * self.gravity * depth } else { 0.0 };
        Pressures { inside, outside }
    }
}

/// API RP 2RD's basic allowable stress over the yield stress, C_a = 2/3.
pub const API_ALLOWABLE_FRACTION: f64 = 2.0 / 3.0;

/// The name of the code check riser makes (docs/theory.md §12.4).
pub const API_CHECK: &str = "API RP 2RD von Mises (sigma_vm <= C_f 2/3 sigma_y)";

/// A code check's largest utilisation along the line: its value, the check
/// ([`API_CHECK`], [`LRFD_CHECK`]) and its arc length, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Utilisation {
    pub value: f64,
    pub check: &'static str,
    pub s: f64,
}

/// The larger of two utilisations (the first of equals).
fn larger(a: Option<Utilisation>, b: Option<Utilisation>) -> Option<Utilisation> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if b.value > a.value { b } else { a }),
        (a, b) => a.or(b),
    }
}

/// DNV-OS-F201's LRFD check along a line (docs/theory.md §12.4): its
/// largest utilisation, or, where a point has no net internal overpressure
/// (p_i ≤ p_e, whose criterion riser does not implement), none: the first
/// such point's arc length, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LrfdPeak {
    Utilisation(Utilisation),
    ExternalOverpressure { s: f64 },
}

impl LrfdPeak {
    /// The larger of two (over the line, over time): none once a point had
    /// no net internal overpressure.
    pub fn max(self, other: LrfdPeak) -> LrfdPeak {
        match (self, other) {
            (LrfdPeak::Utilisation(a), LrfdPeak::Utilisation(b)) => {
                LrfdPeak::Utilisation(if b.value > a.value { b } else { a })
            }
            (LrfdPeak::ExternalOverpressure { s }, _) | (_, LrfdPeak::ExternalOverpressure { s }) => {
                LrfdPeak::ExternalOverpressure { s }
            }
        }
    }

    /// The utilisation, if reported.
    pub fn utilisation(self) -> Option<Utilisation> {
        match self {
            LrfdPeak::Utilisation(u) => Some(u),
            LrfdPeak::ExternalOverpressure { .. } => None,
        }
    }

    /// Why it is not reported, if it is not.
    pub fn not_reported(self) -> Option<String> {
        match self {
            LrfdPeak::Utilisation(_) => None,
            LrfdPeak::ExternalOverpressure { s } => Some(format!(
                "DNV-OS-F201 LRFD combined loading not reported: no net internal overpressure at S = {s:.1} m \
                 (p_i <= p_e), whose criterion (with the collapse resistance) riser does not implement"
            )),
        }
    }
}

/// The largest von Mises stress (Pa) and utilisations along a line in one
/// state, each with its arc length (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressPeaks {
    pub von_mises: (f64, f64),
    /// The larger of the checks' (`max_utilisation`); None when none is made.
    pub utilisation: Option<Utilisation>,
    /// API RP 2RD's (12.9); None when no element has a yield stress.
    pub api: Option<Utilisation>,
    /// DNV-OS-F201's LRFD check's (12.10); None when the scene asks for none.
    pub lrfd: Option<LrfdPeak>,
}

impl StressPeaks {
    /// The larger of each of two peaks (over time).
    pub fn max(self, other: StressPeaks) -> StressPeaks {
        let von_mises = if other.von_mises.0 > self.von_mises.0 { other.von_mises } else { self.von_mises };
        let lrfd = match (self.lrfd, other.lrfd) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        let api = larger(self.api, other.api);
        StressPeaks { von_mises, utilisation: larger(api, lrfd.and_then(LrfdPeak::utilisation)), api, lrfd }
    }
}

/// The design numbers of one state of the line.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignNumbers {
    /// Arc length from the hang-off to the first seabed contact, m (None: no contact).
    pub touchdown_s: Option<f64>,
    /// x of the touchdown point, m.
    pub touchdown_x: Option<f64>,
    /// Angle of the line's tangent at the hang-off from the vertical, deg.
    pub hang_off_angle: f64,
    /// Largest curvature along the line, 1/m, and its arc length, m.
    pub max_curvature: f64,
    pub max_curvature_s: f64,
    /// 1 / max_curvature, m (infinite for a straight line).
    pub min_bend_radius: f64,
    /// Largest bending moment EI |κ|, N m, and its arc length, m (0 for the cable).
    pub max_bending_moment: f64,
    pub max_bending_moment_s: f64,
    /// Largest axial strain T/EA, and its arc length, m.
    pub max_strain: f64,
    pub max_strain_s: f64,
    /// Smallest axial force, N (negative: compression), and its arc length, m.
    pub min_tension: f64,
    pub min_tension_s: f64,
    /// Largest axial stress at the outer fibre, the true wall tension's
    /// plus bending, T_w/A + E r_o |κ| (12.3, 12.6), Pa, and its arc length,
    /// m; None when the line has no wall ([`Tube::of`]).
    pub max_stress: Option<(f64, f64)>,
    /// Largest von Mises stress (12.8), Pa, and its arc length, m; None
    /// when the line has no wall.
    pub max_von_mises: Option<(f64, f64)>,
    /// Largest utilisation of the code checks ([`API_CHECK`],
    /// [`LRFD_CHECK`]: the larger) and where; None without a wall or a
    /// yield stress.
    pub max_utilisation: Option<Utilisation>,
    /// API RP 2RD's largest utilisation (12.9).
    pub api_utilisation: Option<Utilisation>,
    /// DNV-OS-F201's LRFD check (12.10), when the scene asks for it.
    pub lrfd: Option<LrfdPeak>,
}

/// What the design numbers of a scene need: each element's properties and
/// tube, once.
#[derive(Debug, Clone)]
pub struct Design {
    props: PerElement<LineProperties>,
    tubes: PerElement<Option<Tube>>,
    model: Model,
    length: f64,
    n_el: usize,
    seabed: Option<crate::scene::SeabedSpec>,
    /// The water and the contents (none: no pressure, the stresses of
    /// [`Design::of_properties`]).
    fluids: Fluids,
    /// API RP 2RD's design case factor C_f.
    case_factor: f64,
    /// DNV-OS-F201's LRFD factors, when the scene asks for the check.
    lrfd: Option<LrfdFactors>,
}

impl Design {
    pub fn new(scene: &Scene) -> Self {
        let n_el = scene.analysis.n_elements;
        let d =
            Design::of_properties(sections::element_properties(scene), scene.analysis.model, scene.line.length, n_el);
        Design {
            seabed: scene.seabed.clone(),
            fluids: Fluids::of(scene),
            case_factor: scene.line.design_case_factor.unwrap_or(1.0),
            lrfd: LrfdFactors::of(&scene.line),
            ..d
        }
    }

    /// The design numbers of a line of `n_el` elements with these properties.
    pub fn of_properties(props: PerElement<LineProperties>, model: Model, length: f64, n_el: usize) -> Self {
        let tubes = props.map(Tube::of);
        Design {
            props,
            tubes,
            model,
            length,
            n_el,
            seabed: None,
            fluids: Fluids::default(),
            case_factor: 1.0,
            lrfd: None,
        }
    }

    /// The same design with the water and contents `fluids` and API RP
    /// 2RD's design case factor C_f `case_factor` (12.5, 12.9).
    pub fn with_fluids(self, fluids: Fluids, case_factor: f64) -> Self {
        Design { fluids, case_factor, ..self }
    }

    /// The same design with DNV-OS-F201's LRFD check of `factors` (12.10).
    pub fn with_lrfd(self, factors: LrfdFactors) -> Self {
        Design { lrfd: Some(factors), ..self }
    }

    /// The tube of element `e` (None: not a homogeneous tube, or the cable's
    /// line, whose bending is not modelled: its stresses are T/A only when it
    /// is a tube).
    pub fn tube(&self, e: usize) -> Option<Tube> {
        *self.tubes.at(e)
    }

    /// True when every element is a homogeneous tube (stresses are reported).
    pub fn has_stresses(&self) -> bool {
        (0..self.n_el).all(|e| self.tube(e).is_some())
    }

    /// The outer-fibre axial stress of `p` at angle θ with the hang-off at
    /// `hang_off_z` (m), Pa (the cable: axial only).
    fn fibre_stress(&self, p: &LinePoint, theta: f64, hang_off_z: f64) -> Option<f64> {
        self.fibre_stress_cs(p, theta.cos(), theta.sin(), hang_off_z)
    }

    /// The outer-fibre axial stress of `p` at the fibre whose angle θ has
    /// cosine `cos` and sine `sin`, with the hang-off at `hang_off_z` (m),
    /// Pa: T_w/A + E r_o (κ₁ sin θ − κ₂ cos θ) (12.2, 12.6; the cable: axial
    /// only); None when `p`'s element is not a tube. The stress of the
    /// stress range and of the fatigue (§12.5).
    pub fn fibre_stress_cs(&self, p: &LinePoint, cos: f64, sin: f64, hang_off_z: f64) -> Option<f64> {
        self.fibre_stress_parts(p, hang_off_z).map(|s| s.at(cos, sin))
    }

    /// The parts of `p`'s outer-fibre axial stress that do not depend on the
    /// fibre (12.2): T_w/A, E r_o and the curvature; None when `p`'s element
    /// is not a tube.
    pub fn fibre_stress_parts(&self, p: &LinePoint, hang_off_z: f64) -> Option<FibreStress> {
        let tube = self.tube(p.element)?;
        let curvature = if self.model == Model::Rod { p.curvature } else { [0.0; 2] };
        let t_w = tube.wall_tension(p.tension, self.fluids.pressures(p.position.z, hang_off_z));
        Some(FibreStress { axial: t_w / tube.area, stiffness: tube.modulus * tube.outer_radius, curvature })
    }

    /// The largest axial stress at `p`'s outer fibre, T_w/A + E r_o |κ|, Pa.
    fn point_max_stress(&self, tube: &Tube, p: &LinePoint, hang_off_z: f64) -> f64 {
        let k = if self.model == Model::Rod { p.curvature_magnitude() } else { 0.0 };
        tube.max_stress(tube.wall_tension(p.tension, self.fluids.pressures(p.position.z, hang_off_z)), k)
    }

    /// The largest von Mises stress at `p` (12.8), Pa.
    fn point_von_mises(&self, tube: &Tube, p: &LinePoint, hang_off_z: f64) -> f64 {
        let pressures = self.fluids.pressures(p.position.z, hang_off_z);
        let (k, twist) = match self.model {
            Model::Rod => (p.curvature_magnitude(), p.twist),
            Model::Cable => (0.0, 0.0),
        };
        tube.max_von_mises(tube.wall_tension(p.tension, pressures), k, twist, pressures)
    }

    /// The largest von Mises stress and utilisations of the line whose
    /// points are `points` in a static state, its hang-off at `hang_off_z`
    /// (m): [`Design::stress_peaks_over`] with the state its own functional
    /// state.
    pub fn stress_peaks(&self, points: &[LinePoint], hang_off_z: f64) -> Option<StressPeaks> {
        self.stress_peaks_over(points, points, hang_off_z)
    }

    /// The largest von Mises stress and utilisations of the line whose
    /// points are `points`, its hang-off at `hang_off_z` (m), the static
    /// state's points `functional` (the same points: the functional load
    /// effects of DNV-OS-F201's check, the environmental ones the
    /// difference, (12.14)); None when the line has no wall (§12.4). The
    /// FMU's `max_von_mises` and `max_utilisation`, `riser run`'s over the
    /// steady window.
    pub fn stress_peaks_over(
        &self,
        points: &[LinePoint],
        functional: &[LinePoint],
        hang_off_z: f64,
    ) -> Option<StressPeaks> {
        if !self.has_stresses() {
            return None;
        }
        let mut peaks = StressPeaks { von_mises: (f64::NEG_INFINITY, 0.0), utilisation: None, api: None, lrfd: None };
        for (p, f) in points.iter().zip(functional) {
            let tube = self.tube(p.element).expect("every element is a tube");
            let vm = self.point_von_mises(&tube, p, hang_off_z);
            if vm > peaks.von_mises.0 {
                peaks.von_mises = (vm, p.s);
            }
            if let Some(sy) = tube.yield_stress {
                let value = vm / (self.case_factor * API_ALLOWABLE_FRACTION * sy);
                peaks.api = larger(peaks.api, Some(Utilisation { value, check: API_CHECK, s: p.s }));
            }
            if let Some(here) = self.point_lrfd(&tube, p, f, hang_off_z) {
                peaks.lrfd = Some(peaks.lrfd.map_or(here, |m| m.max(here)));
            }
        }
        peaks.utilisation = larger(peaks.api, peaks.lrfd.and_then(LrfdPeak::utilisation));
        peaks.von_mises.0.is_finite().then_some(peaks)
    }

    /// DNV-OS-F201's LRFD check at `p` whose static state is `f` (12.10,
    /// 12.14): the functional moment EI κ and effective tension are `f`'s,
    /// the environmental the difference, each factored; None when the scene
    /// asks for no check or `p`'s wall has no strengths.
    fn point_lrfd(&self, tube: &Tube, p: &LinePoint, f: &LinePoint, hang_off_z: f64) -> Option<LrfdPeak> {
        let (factors, wall) = (self.lrfd?, tube.lrfd_wall()?);
        let pressures = self.fluids.pressures(p.position.z, hang_off_z);
        let dp = pressures.inside - pressures.outside;
        if dp <= 0.0 {
            return Some(LrfdPeak::ExternalOverpressure { s: p.s });
        }
        let ei = match self.model {
            Model::Rod => self.props.at(p.element).bending_stiffness,
            Model::Cable => 0.0,
        };
        let m_f = [ei * f.curvature[0], ei * f.curvature[1]];
        let m_e = [ei * (p.curvature[0] - f.curvature[0]), ei * (p.curvature[1] - f.curvature[1])];
        let moment = factors.design_effect(m_f, m_e);
        let tension = factors.design_effect([f.tension], [p.tension - f.tension]);
        let value = wall.utilisation(&factors, moment, tension, dp);
        Some(LrfdPeak::Utilisation(Utilisation { value, check: LRFD_CHECK, s: p.s }))
    }

    /// The design numbers of `state`, whose `touchdown_s` output is given (m;
    /// the line's length when it touches nowhere).
    pub fn numbers(&self, engine: &Engine, state: &State, touchdown_s: f64) -> DesignNumbers {
        let hang_off_z = state.config.x[0].z;
        let touchdown = (touchdown_s < self.length).then(|| {
            let s = engine.node_arc_lengths();
            let x = &state.config.x;
            let a = s.partition_point(|&si| si <= touchdown_s).clamp(1, s.len() - 1);
            let w = (touchdown_s - s[a - 1]) / (s[a] - s[a - 1]);
            (touchdown_s, x[a - 1].x + w * (x[a].x - x[a - 1].x))
        });
        self.of_points(&engine.line_points(state), engine.hang_off_tangent(state), touchdown, hang_off_z)
    }

    /// The design numbers of a line whose points are `points`, whose tangent
    /// at the hang-off is `hang_off_tangent` and whose touchdown (S, x) is
    /// `touchdown` (m), with the hang-off at height `hang_off_z` (m; the
    /// contents' pressure is given there).
    pub fn of_points(
        &self,
        points: &[LinePoint],
        hang_off_tangent: V3,
        touchdown: Option<(f64, f64)>,
        hang_off_z: f64,
    ) -> DesignNumbers {
        let hang_off_angle = crate::model::outputs::hang_off_angle(hang_off_tangent);
        let argmax = |f: &dyn Fn(&LinePoint) -> f64| {
            points.iter().map(|p| (f(p), p.s)).fold((f64::NEG_INFINITY, 0.0), |m, v| if v.0 > m.0 { v } else { m })
        };
        let (max_curvature, max_curvature_s) = argmax(&|p| p.curvature_magnitude());
        let (max_bending_moment, max_bending_moment_s) = match self.model {
            Model::Rod => argmax(&|p| self.props.at(p.element).bending_stiffness * p.curvature_magnitude()),
            Model::Cable => (0.0, 0.0),
        };
        let (max_strain, max_strain_s) = argmax(&|p| p.tension / self.props.at(p.element).axial_stiffness);
        let (neg_min, min_tension_s) = argmax(&|p| -p.tension);
        let max_stress = self.has_stresses().then(|| {
            argmax(&|p| self.point_max_stress(&self.tube(p.element).expect("every element is a tube"), p, hang_off_z))
        });
        let peaks = self.stress_peaks(points, hang_off_z);
        DesignNumbers {
            touchdown_s: touchdown.map(|t| t.0),
            touchdown_x: touchdown.map(|t| t.1),
            hang_off_angle,
            max_curvature,
            max_curvature_s,
            min_bend_radius: 1.0 / max_curvature,
            max_bending_moment,
            max_bending_moment_s,
            max_strain,
            max_strain_s,
            min_tension: -neg_min,
            min_tension_s,
            max_stress,
            max_von_mises: peaks.map(|p| p.von_mises),
            max_utilisation: peaks.and_then(|p| p.utilisation),
            api_utilisation: peaks.and_then(|p| p.api),
            lrfd: peaks.and_then(|p| p.lrfd),
        }
    }

    /// Warnings for a state with these design numbers (docs/theory.md §12.3):
    /// strain above [`STRAIN_LIMIT`], compression, and (the rod) a mesh too
    /// coarse for the bending length √(EI/T) at the touchdown. `points` are
    /// the state's [`Engine::line_points`].
    pub fn warnings(&self, d: &DesignNumbers, points: &[LinePoint]) -> Vec<String> {
        let mut w = Vec::new();
        if d.max_strain > STRAIN_LIMIT {
            w.push(format!(
                "the axial strain reaches {:.2} % at S = {:.1} m, above the {:.0} % that no riser, umbilical or cable \
                 takes elastically: check EA, the line's length and the anchor's position",
                100.0 * d.max_strain,
                d.max_strain_s,
                100.0 * STRAIN_LIMIT
            ));
        }
        if d.min_tension < 0.0 {
            w.push(format!(
                "the line is in compression: the axial force reaches {:.3} kN at S = {:.1} m (the rod buckles there \
                 if EI cannot carry it; the cable takes no compression and goes slack)",
                d.min_tension / 1e3,
                d.min_tension_s
            ));
        }
        // the touchdown, or on a mesh too coarse for a node to reach the seabed, the line's lowest
        // point when it is within a diameter of the seabed; not the anchor's element (a taut line)
        let last = self.n_el - 1;
        let near_seabed = self.seabed.as_ref().and_then(|bed| match d.touchdown_s {
            Some(s_td) => points.iter().min_by(|a, b| (a.s - s_td).abs().total_cmp(&(b.s - s_td).abs())),
            None => {
                points.iter().filter(|p| p.element < last).min_by(|a, b| a.position.z.total_cmp(&b.position.z)).filter(
                    |p| p.position.z - bed.height_at(p.position.x, p.position.y) < self.props.at(p.element).diameter,
                )
            }
        });
        if let (Model::Rod, Some(p)) = (self.model, near_seabed.filter(|p| p.element < last))
            && p.tension > 0.0
        {
            let h = self.length / self.n_el as f64;
            let lambda = (self.props.at(p.element).bending_stiffness / p.tension).sqrt();
            if h * ELEMENTS_PER_BENDING_LENGTH > lambda {
                let n = (ELEMENTS_PER_BENDING_LENGTH * self.length / lambda).ceil();
                let fix = if n <= crate::scene::ranges::MAX_ELEMENTS {
                    format!(
                        "use at least n_elements = {n} (two elements per bending length), and check the numbers you \
                         read by doubling it: the stress range at the touchdown converges slowly"
                    )
                } else {
                    format!(
                        "no mesh of at most {} elements resolves it: a bending length this short is a boundary layer \
                         that the cable model leaves out (--set model=cable)",
                        crate::scene::ranges::MAX_ELEMENTS
                    )
                };
                w.push(format!(
                    "elements of {h:.2} m are fewer than two per bending length sqrt(EI/T) = {lambda:.3} m near \
                     the touchdown (S = {:.1} m): the curvature, bending moment and stress there are not resolved; \
                     {fix}",
                    p.s
                ));
            }
        }
        w
    }
}

impl Design {
    /// The design numbers of `state` and every warning they give, the
    /// anchor's reach included.
    pub fn report(&self, scene: &Scene, engine: &Engine, state: &State) -> (DesignNumbers, Vec<String>) {
        let outputs = engine.outputs(state);
        let numbers = self.numbers(engine, state, outputs.touchdown_s);
        let mut warnings: Vec<String> = reach_warning(scene).into_iter().collect();
        warnings.extend(anchor_lift_static_warning(scene, &outputs));
        warnings.extend(self.buoyant_warning(scene));
        warnings.extend(wall_stiffness_warnings(scene));
        warnings.extend(lrfd_warning(scene));
        warnings.extend(self.warnings(&numbers, &engine.line_points(state)));
        warnings.extend(crate::loads::waves::warnings(scene));
        if let Ok(Some((_, period))) = crate::loads::waves::ramp_and_period(scene) {
            warnings.extend(steps_per_period_warning("the sea's", period, scene.analysis.time_step));
        }
        (numbers, warnings)
    }

    /// A warning when the line as a whole floats: its buoyancy (the
    /// displaced water's weight, modules included) exceeds its weight, so
    /// that it pushes the hang-off up. A lazy wave's modules lift a part of
    /// a heavy line; a line lighter than water all along is most often a
    /// diameter or a mass given in the wrong unit.
    pub fn buoyant_warning(&self, scene: &Scene) -> Option<String> {
        let (rho, g) = (scene.environment.water_density, scene.environment.gravity);
        let h = self.length / self.n_el as f64;
        let net_up: f64 = (0..self.n_el)
            .map(|e| self.props.at(e))
            .map(|p| (rho * p.displaced_area - p.mass_per_length) * g * h)
            .sum();
        (net_up > 0.0).then(|| {
            format!(
                "the line floats: its buoyancy exceeds its weight by {:.3} kN over its {} m (weight in water {:.3} \
                 kN); it pushes the hang-off up: check the outer diameter, the mass per length and their units",
                net_up / 1e3,
                self.length,
                -net_up / 1e3
            )
        })
    }
}

/// A warning for a tensile strength given without a safety class: it asks
/// for no DNV-OS-F201 check (docs/theory.md §12.4).
pub fn lrfd_warning(scene: &Scene) -> Option<String> {
    let mut given =
        scene.line.tensile_strength.into_iter().chain(scene.section.iter().filter_map(|s| s.tensile_strength));
    (scene.line.safety_class.is_none() && given.any(|u| u > 0.0)).then(|| {
        "tensile_strength is given but no safety_class: DNV-OS-F201's LRFD combined-loading check is not made; give \
         safety_class (low, normal or high) for it"
            .to_string()
    })
}

/// The relative difference between a line's EA or EI and its wall's above
/// which riser warns (docs/theory.md §12.4).
pub const WALL_STIFFNESS_MISMATCH: f64 = 0.01;

/// Warnings for each piece of line (`[line]`, or each section) whose EA or
/// EI differs from its wall's E A_s and E I by more than
/// [`WALL_STIFFNESS_MISMATCH`]: the model bends and stretches with the
/// scene's EA and EI, the stresses are the wall's (12.6–12.8). A coating's
/// or a liner's stiffness, or a wall or modulus given wrong, shows here.
pub fn wall_stiffness_warnings(scene: &Scene) -> Vec<String> {
    let lines: Vec<(String, crate::scene::Line)> = if scene.section.is_empty() {
        vec![("[line]".to_string(), scene.line.clone())]
    } else {
        scene.section.iter().enumerate().map(|(i, s)| (format!("section {i}"), s.bare_line(&scene.line))).collect()
    };
    let mut w = Vec::new();
    for (at, l) in lines {
        let Some(wall) = l.wall() else { continue };
        let e = wall.youngs_modulus;
        for (name, given, of_wall, unit) in
            [("EA", l.axial_stiffness, e * wall.area(), "N"), ("EI", l.bending_stiffness, e * wall.inertia(), "N m^2")]
        {
            let off = given / of_wall - 1.0;
            if off.abs() > WALL_STIFFNESS_MISMATCH {
                w.push(format!(
                    "{at}: {name} {given:.4e} {unit} is {:+.1} % off the wall's E x {} = {of_wall:.4e} {unit} \
                     (E {e:.4e} Pa, steel outer diameter {} m, wall {} m): the line bends and stretches with the \
                     given {name}, the stresses are the wall's; check the wall, youngs_modulus and {name} (a \
                     coating's or a liner's stiffness is left out of the wall)",
                    100.0 * off,
                    if name == "EA" { "A_s" } else { "I" },
                    wall.outer_diameter,
                    wall.thickness
                ));
            }
        }
    }
    w
}

/// The stress peaks along the line of `sim` now ([`Design::stress_peaks_over`],
/// its static state the functional one): the FMU's `max_von_mises` and
/// utilisations. Computed when read: it builds the scene's [`Design`]; the
/// line's points only where it has stresses, the static state's only where
/// the scene asks for the LRFD check (its functional load effects).
pub fn line_stress_peaks(scene: &Scene, sim: &super::Simulation) -> Option<StressPeaks> {
    let design = Design::new(scene);
    if !design.has_stresses() {
        return None;
    }
    let points = sim.integrator.line_points(&sim.state);
    let top_z = sim.state.config.x[0].z;
    if design.lrfd.is_none() {
        return design.stress_peaks(&points, top_z);
    }
    let functional = sim.integrator.line_points(&sim.functional_state());
    design.stress_peaks_over(&points, &functional, top_z)
}

/// The FMU's output `name` of the peaks `peaks` ([`line_stress_peaks`]):
/// `max_von_mises` (Pa), `max_utilisation` (the larger of the checks),
/// `max_utilisation_api_rp_2rd`, `max_utilisation_dnv_os_f201`; 0 without a
/// wall (a flexible pipe), a utilisation 0 where its check is not made.
pub fn line_stress_output(peaks: Option<StressPeaks>, name: &str) -> f64 {
    let value = |u: Option<Utilisation>| u.map_or(0.0, |u| u.value);
    match name {
        "max_von_mises" => peaks.map_or(0.0, |p| p.von_mises.0),
        "max_utilisation_api_rp_2rd" => value(peaks.and_then(|p| p.api)),
        "max_utilisation_dnv_os_f201" => value(peaks.and_then(|p| p.lrfd).and_then(LrfdPeak::utilisation)),
        _ => value(peaks.and_then(|p| p.utilisation)),
    }
}

/// The fewest time steps a period of a motion or a sea without a warning:
/// below, the response is not resolved and the step's numerical dissipation
/// (ρ∞) damps it (the accuracy knob takes at least 75, docs/theory.md §16.2).
pub const STEPS_PER_PERIOD: f64 = 20.0;

/// A warning when `time_step` (s) takes fewer than [`STEPS_PER_PERIOD`]
/// steps a `period` (s) of `what` ("the sea's", "the heave's", …).
pub fn steps_per_period_warning(what: &str, period: f64, time_step: f64) -> Option<String> {
    let steps = period / time_step;
    (period > 0.0 && steps < STEPS_PER_PERIOD).then(|| {
        format!(
            "time_step {time_step} s takes {steps:.1} steps a period of {what} {period} s motion, fewer than \
             {STEPS_PER_PERIOD:.0}: the line's response to it is not resolved and the step's numerical damping \
             takes it down; use time_step <= {:.3} s (or set accuracy)",
            period / STEPS_PER_PERIOD
        )
    })
}

/// The relative unsteadiness of a steady window a periodic forcing of
/// `period` s leaves (docs/theory.md §12.3): the largest difference of the
/// extremes (min, max) of `samples` ((t s, y), in time order) over the
/// window's first period [t0, t0 + period] and over its last [t1 − period,
/// t1], over the largest |y| in the window. In a periodic steady state the
/// two periods' extremes agree (to the output's sampling); what is left of
/// the start (the ramp's, the current's jolt at t = 0 with `static_current`
/// false) makes the first period's differ. None when the window is shorter
/// than two periods or holds no samples.
pub fn window_drift(samples: &[(f64, f64)], window: (f64, f64), period: f64) -> Option<f64> {
    let (t0, t1) = window;
    if !(period > 0.0 && t1 - t0 >= 2.0 * period * (1.0 - 1e-9)) {
        return None;
    }
    let slack = 1e-9 * period.max(t1.abs());
    let extremes = |a: f64, b: f64| {
        samples
            .iter()
            .filter(|(t, y)| *t >= a - slack && *t <= b + slack && y.is_finite())
            .fold(None, |m: Option<(f64, f64)>, &(_, y)| Some(m.map_or((y, y), |(lo, hi)| (lo.min(y), hi.max(y)))))
    };
    let (lo1, hi1) = extremes(t0, t0 + period)?;
    let (lo2, hi2) = extremes(t1 - period, t1)?;
    let scale = samples
        .iter()
        .filter(|(t, y)| *t >= t0 - slack && *t <= t1 + slack && y.is_finite())
        .fold(0.0f64, |m, (_, y)| m.max(y.abs()));
    (scale > 0.0).then(|| (lo1 - lo2).abs().max((hi1 - hi2).abs()) / scale)
}

/// The drift above which a run warns that its steady window is not steady
/// (without `accuracy`; with it, the target): 1 % of the top tension.
pub const UNSTEADY_WINDOW: f64 = 1e-2;

/// The warning for a steady window whose first and last periods' top
/// tension extremes differ by `drift` (of [`window_drift`]) more than
/// `limit`.
pub fn unsteady_window_warning(drift: f64, limit: f64, window: (f64, f64), period: f64) -> Option<String> {
    (drift > limit).then(|| {
        let (t0, t1) = window;
        // a window as long, two periods later (the run as much longer): the
        // start's transients decay with time, not with the window's length
        let later = |t: f64| crate::scene::ranges::number(t + 2.0 * period);
        format!(
            "the steady window is not steady at {limit:e}: the top tension's extremes over its first period \
             ({t0} to {} s) and its last ({} to {t1} s) differ by {:.3} % of its max: what is left of the start's \
             transients; start the window later, e.g. --duration {} --window {},{} (docs/theory.md 12.3)",
            t0 + period,
            t1 - period,
            100.0 * drift,
            later(t1),
            later(t0),
            later(t1)
        )
    })
}

/// Whether the step's high-frequency dissipation (ρ∞ < 1) grows over three
/// successive spans: `taken` the energy it took in each (J), `flux` the
/// energy the hang-off and the water moved in each (J, the total variation
/// of `work_top` and `work_hydro`). It grows when its share of the flux
/// grows from span to span, the last's more than 1.5 times the first's, and
/// the last span's energy is above 1e-4 of `exchanged` (J, the largest
/// |`work_top`| + |`work_hydro`| so far) and above [`NEGLIGIBLE_DISSIPATION`].
/// A start's transient takes a falling share, a steady sea the same share, a
/// motion still growing (a long ramp) more energy but the same share of a
/// flux that grows with it.
pub fn dissipation_grows(taken: [f64; 3], flux: [f64; 3], exchanged: f64) -> bool {
    let share = |k: usize| if flux[k] > 0.0 { taken[k] / flux[k] } else { f64::INFINITY };
    let (s0, s1, s2) = (share(0), share(1), share(2));
    s2.is_finite()
        && s2 > 1.5 * s0
        && s2 > s1
        && s1 > s0
        && taken[2] > 1e-4 * exchanged
        && taken[2] > NEGLIGIBLE_DISSIPATION
}

/// The energy, J, below which a span's high-frequency dissipation is the
/// round-off of a line at rest, not an oscillation: the steel catenary held
/// still without a current moves 1e-3 J and its dissipation takes 1e-6 J a
/// span, whose shares of so small a flux may grow by chance (27, 32 and 44
/// over 20 s: a warning before this floor); the oscillation it guards
/// against took 40 to 138 J a span (the lazy wave at 0.00625 s, §5.10).
pub const NEGLIGIBLE_DISSIPATION: f64 = 1.0;

/// Energy in J, to three figures.
fn joules(x: f64) -> String {
    if x.abs() >= 100.0 { format!("{x:.0}") } else { format!("{x:.3}") }
}

fn growing_dissipation_message(taken: [f64; 3], flux: [f64; 3], spans: &str) -> String {
    format!(
        "a high-frequency oscillation grows through the run: the step's high-frequency dissipation \
         (rho_infinity) took {}, {} and {} J in {spans}, {:.1e}, {:.1e} and {:.1e} of the energy the hang-off and \
         the water moved; the tension's extremes may be the oscillation's, not the line's response. Give the \
         line structural damping (structural_damping=0.003, s) or set rho_infinity=1 (docs/theory.md 5.10)",
        joules(taken[0]),
        joules(taken[1]),
        joules(taken[2]),
        taken[0] / flux[0],
        taken[1] / flux[1],
        taken[2] / flux[2]
    )
}

/// The warning for a high-frequency oscillation that grows through a run
/// (`riser run`, over its steady window): [`dissipation_grows`] over the
/// samples' last three quarters, from their `times` (s, in order),
/// `algorithmic` (J, cumulative) and `work` (J, `work_top` and `work_hydro`).
/// The known case (docs/theory.md §5.10): the lazy wave heaved in its
/// current at steps of 0.00625 s and shorter with ρ∞ = 0.8 (over 60 to 120 s
/// at 0.00625 s: 40, 77 and 138 J, 3.6e-4, 7.2e-4 and 1.3e-3 of the flux),
/// where the velocity filter feeds an oscillation that ρ∞ = 1 or structural
/// damping take away. Not caught: the Lowe & Langley jumper started
/// abruptly in a 10 m wave, whose growth slows within its window (shares
/// 9.9e-3, 1.19e-2, 1.31e-2 from 20 to 50 s).
pub fn growing_dissipation_warning(times: &[f64], algorithmic: &[f64], work: &[[f64; 2]]) -> Option<String> {
    let (t0, t1) = (*times.first()?, *times.last()?);
    let n = times.len();
    if algorithmic.len() != n || work.len() != n || n < 8 || t1 <= t0 || t1.is_nan() || t0.is_nan() {
        return None;
    }
    // cumulative flux: the total variation of the two works
    let mut flux = vec![0.0; n];
    for k in 1..n {
        flux[k] = flux[k - 1] + (work[k][0] - work[k - 1][0]).abs() + (work[k][1] - work[k - 1][1]).abs();
    }
    // the last sample at or before each quarter mark
    let at = |q: f64| times.partition_point(|&x| x <= t0 + q * (t1 - t0) + 1e-9 * (t1 - t0)).max(1) - 1;
    let k = [at(0.25), at(0.5), at(0.75), n - 1];
    let span = |v: &[f64]| [v[k[1]] - v[k[0]], v[k[2]] - v[k[1]], v[k[3]] - v[k[2]]];
    let exchanged = work.iter().map(|w| w[0].abs() + w[1].abs()).fold(0.0, f64::max);
    let (taken, moved) = (span(algorithmic), span(&flux));
    dissipation_grows(taken, moved, exchanged)
        .then(|| growing_dissipation_message(taken, moved, "the run's last three quarters"))
}

/// The running form of [`growing_dissipation_warning`] for a run of no known
/// end (the FMU): the dissipation's energy and the flux over successive spans
/// of [`GrowthWatch::SPAN`] s of simulated time, their values at the marks
/// interpolated between the samples fed, [`dissipation_grows`] over the last
/// three. No allocation; `Copy`, so that it is saved and restored with the
/// state it watches.
#[derive(Debug, Clone, Copy)]
pub struct GrowthWatch {
    /// The next mark, s (infinite: the watch is off).
    next: f64,
    /// The last sample fed: t (s), dissipation and flux (J), the two works (J).
    last: Option<(f64, f64, f64, [f64; 2])>,
    /// Dissipation and flux at the last four marks, oldest first.
    marks: [(f64, f64); 4],
    count: usize,
    exchanged: f64,
}

impl GrowthWatch {
    /// The span, s of simulated time.
    pub const SPAN: f64 = 30.0;

    /// A watch from `t0` s on.
    pub fn new(t0: f64) -> Self {
        GrowthWatch { next: t0 + Self::SPAN, last: None, marks: [(0.0, 0.0); 4], count: 0, exchanged: 0.0 }
    }

    /// A watch that never speaks (after it has).
    pub fn off() -> Self {
        GrowthWatch { next: f64::INFINITY, ..Self::new(0.0) }
    }

    /// Whether it can still speak.
    pub fn is_on(&self) -> bool {
        self.next.is_finite()
    }

    /// Feeds the run at `t` s: `algorithmic` the dissipation's energy since
    /// the start (J), `work` the hang-off's and the water's work since the
    /// start (J). Returns the warning when the last three spans grow.
    pub fn feed(&mut self, t: f64, algorithmic: f64, work: [f64; 2]) -> Option<String> {
        if !self.is_on() || !t.is_finite() || !algorithmic.is_finite() || !work.iter().all(|w| w.is_finite()) {
            return None;
        }
        self.exchanged = self.exchanged.max(work[0].abs() + work[1].abs());
        let Some((t_prev, d_prev, f_prev, w_prev)) = self.last else {
            self.last = Some((t, algorithmic, 0.0, work));
            return None;
        };
        if t <= t_prev {
            return None;
        }
        let flux = f_prev + (work[0] - w_prev[0]).abs() + (work[1] - w_prev[1]).abs();
        self.last = Some((t, algorithmic, flux, work));
        let mut grows = None;
        // at most a few marks a feed: a step longer than a span interpolates them
        // (a mark within round-off of t is t's: a master's t = k h accumulates it)
        while self.next <= t + 1e-9 * Self::SPAN && self.next.is_finite() {
            let a = ((self.next - t_prev) / (t - t_prev)).min(1.0);
            let mark = (d_prev + a * (algorithmic - d_prev), f_prev + a * (flux - f_prev));
            self.marks = if self.count == 0 { [mark; 4] } else { [self.marks[1], self.marks[2], self.marks[3], mark] };
            self.count += 1;
            self.next += Self::SPAN;
            let m = self.marks;
            let taken = [m[1].0 - m[0].0, m[2].0 - m[1].0, m[3].0 - m[2].0];
            let moved = [m[1].1 - m[0].1, m[2].1 - m[1].1, m[3].1 - m[2].1];
            if self.count >= 4 && grows.is_none() && dissipation_grows(taken, moved, self.exchanged) {
                grows = Some(growing_dissipation_message(
                    taken,
                    moved,
                    &format!("the last three spans of {} s", Self::SPAN),
                ));
            }
        }
        grows
    }
}

/// The warning for an anchor beyond the line's unstretched reach from the
/// hang-off, if it is (docs/theory.md §12.3).
pub fn reach_warning(scene: &Scene) -> Option<String> {
    let span: V3 = scene.anchor() - scene.hang_off();
    let reach = scene.line.length;
    (span.norm() > reach).then(|| {
        format!(
            "the anchor is {:.2} m from the hang-off, beyond the line's unstretched length {reach} m: the line can \
             only hang straight and stretched; lengthen the line or move the anchor",
            span.norm()
        )
    })
}

/// The height above its seabed, m, square to the plane, up to which an
/// anchor sits on the seabed (an anchor higher up is a mid-water
/// termination: an arch's or a buoy's base, a tower's top, built to take the
/// line's pull in any direction, and is never warned of as lifted off). It
/// covers a line whose centreline rests on the plane (the model's contact,
/// docs/theory.md §9) against one whose bottom does, D/2 lower, and the hub
/// of a PLET or the padeye of a pile, which stand about this high.
pub const ANCHOR_ON_SEABED: f64 = 1.0;

/// The angle, deg, of the line's force on its anchor (`bottom_force`, N, as
/// [`Outputs::bottom_force`]) above the scene's seabed plane:
/// atan2(F·n, |F − (F·n) n|), n the plane's upward normal (the slope
/// turns it). Positive: the line pulls its anchor up, off the seabed;
/// negative: it presses it down (a line lying on the seabed before its
/// anchor pulls it along the plane, less the weight of the anchor's half
/// element, which the end's reaction carries). None without a seabed or for
/// an anchor more than [`ANCHOR_ON_SEABED`] above it.
pub fn anchor_uplift(scene: &Scene, bottom_force: V3) -> Option<f64> {
    let bed = scene.seabed.as_ref()?;
    let a = bed.slope.to_radians();
    let normal = V3::new(-a.sin(), 0.0, a.cos());
    let anchor = scene.anchor();
    let height = (anchor.z - bed.height_at(anchor.x, anchor.y)) * a.cos();
    if height > ANCHOR_ON_SEABED {
        return None;
    }
    let up = bottom_force.dot(&normal);
    Some(up.atan2((bottom_force - up * normal).norm()).to_degrees())
}

/// The anchor's uplift angle, deg ([`anchor_uplift`]), when the line lifts
/// its anchor off the seabed in the state whose outputs are `o`: the anchor
/// sits on the seabed, the line touches it nowhere (`o.touchdown_s` is the
/// line's length) and pulls the anchor up (an angle above 0). A line that
/// still lies on the seabed before its anchor and pulls it up there is
/// buckled on it by compression (the steel catenary's anchor 50 m from its
/// hang-off: 5.9 deg at −66 kN), which the compression warning names, with
/// the opposite cure (less line, not more).
pub fn anchor_lifted(scene: &Scene, o: &Outputs) -> Option<f64> {
    let touches = o.touchdown_s < scene.line.length;
    anchor_uplift(scene, o.bottom_force).filter(|&a| a > 0.0 && !touches)
}

/// The horizontal distance from the hang-off, m, up to which a uniform line
/// of the scene's length reaches the seabed at an anchor on it, and the
/// length, m, with which it reaches it at the scene's anchor: the
/// inextensible catenary whose lowest point is the anchor, depth h below
/// the hang-off, a = H/w: L² = h² + 2 a h, X = a acosh(1 + h/a) (the weight
/// drops out). None for a line of sections, a sloping seabed, or an anchor
/// no deeper than the hang-off.
fn touchdown_bounds(scene: &Scene) -> Option<(f64, f64)> {
    let bed = scene.seabed.as_ref()?;
    let (anchor, l) = (scene.anchor() - scene.hang_off(), scene.line.length);
    let (h, span) = (-anchor.z, anchor.x.hypot(anchor.y));
    if !scene.section.is_empty() || bed.slope != 0.0 || h <= 0.0 || l <= h {
        return None;
    }
    let reach = |a: f64| a * (1.0 + h / a).acosh();
    let a = (l * l - h * h) / (2.0 * h);
    // X(a) grows from 0 (a → 0) without bound (√(2 a h)): bisect for the span
    let (mut lo, mut hi) = (0.0, h.max(span));
    while reach(hi) < span {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if reach(mid) < span { lo = mid } else { hi = mid }
    }
    let a_here = 0.5 * (lo + hi);
    Some((reach(a), (h * h + 2.0 * a_here * h).sqrt()))
}

/// What to do about an anchor lifted off the seabed (the end of the static
/// and the run's warnings): in the statics, with the length and the anchor's
/// distance that would give the line its touchdown ([`touchdown_bounds`]); in
/// a run (`in_run`), with the margin its motion needs.
fn anchor_lift_cure(scene: &Scene, in_run: bool) -> String {
    let fix = match touchdown_bounds(scene) {
        _ if in_run => ", so that it touches down through the motion".to_string(),
        Some((x, l)) => format!(
            " (a uniform line of {} m reaches its seabed at an anchor within {x:.1} m of the hang-off \
             horizontally, and one of {l:.1} m at this anchor: the inextensible catenary in still water)",
            crate::scene::ranges::number(scene.line.length)
        ),
        None => String::new(),
    };
    format!(
        "a drag or gravity anchor, or a PLET on its mudmat, does not hold this: give the line more length or move \
         the anchor closer to the hang-off{fix}; if the anchor is meant to hold uplift (a suction or driven pile), \
         check its capacity for this force"
    )
}

/// The warning for an anchor the static state lifts off the seabed
/// ([`anchor_lifted`] of its outputs `o`), with its uplift angle and the
/// line's vertical force on it.
pub fn anchor_lift_static_warning(scene: &Scene, o: &Outputs) -> Option<String> {
    let angle = anchor_lifted(scene, o)?;
    Some(format!(
        "the anchor is lifted off the seabed: the line touches no seabed and pulls its anchor up at {angle:.2} deg \
         above the seabed, with a vertical force of {:.3} kN (of {:.3} kN); {}",
        o.bottom_force.z / 1e3,
        o.bottom_tension / 1e3,
        anchor_lift_cure(scene, false)
    ))
}

/// The warning for an anchor lifted off the seabed in a run, first at
/// `first` s, with the outputs `o` of the time of its largest uplift; None
/// when `o`'s anchor is not lifted ([`anchor_lifted`]). `riser run` gives
/// one over its run, the first time and the largest angle; the FMU calls it
/// after each communication step with `first` = `o.time` until it speaks,
/// and logs that once.
pub fn anchor_lift_warning(scene: &Scene, first: f64, o: &Outputs) -> Option<String> {
    let angle = anchor_lifted(scene, o)?;
    let when = if first < o.time {
        format!("from t = {first:.2} s: at t = {:.2} s, its largest uplift,", o.time)
    } else {
        format!("at t = {:.2} s:", o.time)
    };
    Some(format!(
        "the anchor lifts off the seabed in the run {when} the line touches no seabed and pulls its anchor up at \
         {angle:.2} deg above the seabed, with a vertical force of {:.3} kN (of {:.3} kN); {}",
        o.bottom_force.z / 1e3,
        o.bottom_tension / 1e3,
        anchor_lift_cure(scene, true)
    ))
}

/// The extremes along the line over a window: the largest and smallest axial
/// force and the largest curvature, each with its arc length (m) and time (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    /// (N, S, t)
    pub max_tension: (f64, f64, f64),
    pub min_tension: (f64, f64, f64),
    /// (1/m, S, t)
    pub max_curvature: (f64, f64, f64),
}

impl Default for Envelope {
    fn default() -> Self {
        Envelope {
            max_tension: (f64::NEG_INFINITY, 0.0, 0.0),
            min_tension: (f64::INFINITY, 0.0, 0.0),
            max_curvature: (f64::NEG_INFINITY, 0.0, 0.0),
        }
    }
}

impl Envelope {
    /// Adds the state at time `t` whose points are `points`.
    pub fn add(&mut self, t: f64, points: &[LinePoint]) {
        for p in points {
            if p.tension > self.max_tension.0 {
                self.max_tension = (p.tension, p.s, t);
            }
            if p.tension < self.min_tension.0 {
                self.min_tension = (p.tension, p.s, t);
            }
            let k = p.curvature_magnitude();
            if k > self.max_curvature.0 {
                self.max_curvature = (k, p.s, t);
            }
        }
    }

    /// Adds an end's tension (N) at arc length `s` (m), time `t` (s): the
    /// points are Gauss points, inside the elements; the largest axial force
    /// is often at the hang-off itself.
    pub fn add_end(&mut self, t: f64, tension: f64, s: f64) {
        if tension > self.max_tension.0 {
            self.max_tension = (tension, s, t);
        }
    }

    /// True once a state was added.
    pub fn is_set(&self) -> bool {
        self.max_tension.0.is_finite()
    }
}

/// The outer-fibre stress at every point and fibre over a window: its
/// smallest and largest value, for the stress range (the input of a fatigue
/// calculation; docs/theory.md §12.2).
#[derive(Debug, Clone, Default)]
pub struct StressRange {
    /// (s, per fibre (min, max)), Pa.
    points: Vec<(f64, [(f64, f64); FIBRES])>,
}

impl StressRange {
    /// Adds one state's `points` (the same points every time), its hang-off
    /// at height `hang_off_z`, m.
    pub fn add(&mut self, design: &Design, points: &[LinePoint], hang_off_z: f64) {
        if self.points.is_empty() {
            self.points = points.iter().map(|p| (p.s, [(f64::INFINITY, f64::NEG_INFINITY); FIBRES])).collect();
        }
        for (acc, p) in self.points.iter_mut().zip(points) {
            for (f, (lo, hi)) in acc.1.iter_mut().enumerate() {
                let theta = 2.0 * std::f64::consts::PI * f as f64 / FIBRES as f64;
                if let Some(sigma) = design.fibre_stress(p, theta, hang_off_z) {
                    *lo = lo.min(sigma);
                    *hi = hi.max(sigma);
                }
            }
        }
    }

    /// Per point: (S m, smallest σ, largest σ over its fibres, the largest
    /// range of one fibre), Pa: the rows of `stress_range.csv`.
    pub fn rows(&self) -> Vec<[f64; 4]> {
        self.points
            .iter()
            .map(|(s, f)| {
                let lo = f.iter().map(|x| x.0).fold(f64::INFINITY, f64::min);
                let hi = f.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
                let range = f.iter().map(|(a, b)| b - a).fold(f64::NEG_INFINITY, f64::max);
                [*s, lo, hi, range]
            })
            .collect()
    }

    /// The largest range max − min of one fibre at one point, Pa, and its
    /// arc length, m; None when nothing was added or the line has no stresses.
    pub fn largest(&self) -> Option<(f64, f64)> {
        self.points
            .iter()
            .flat_map(|(s, f)| f.iter().map(move |(lo, hi)| (hi - lo, *s)))
            .filter(|(r, _)| r.is_finite())
            .fold(None, |m: Option<(f64, f64)>, v| match m {
                Some(m) if m.0 >= v.0 => Some(m),
                _ => Some(v),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::{
        ANCHOR_ON_SEABED, GrowthWatch, anchor_uplift, growing_dissipation_warning, unsteady_window_warning,
        window_drift,
    };
    use crate::math::V3;
    use crate::scene::Scene;

    /// The uplift angle is measured from the seabed's plane, the slope
    /// included: the steel catenary's seabed tilted 10 deg (rising towards
    /// +x), its anchor on it: a force along the plane towards the hang-off
    /// (down the slope) is at 0 deg, one turned 5 deg out of it at 5 deg (and
    /// −5 deg into it), a vertical pull at 80 deg, a horizontal one towards
    /// the hang-off at +10 deg (the plane falls away under it), across the
    /// slope (y) at 0; to 1e-12 deg. An anchor up to [`ANCHOR_ON_SEABED`]
    /// above the plane (square to it) sits on it; higher, or without a
    /// seabed, there is no angle.
    #[test]
    fn the_anchor_s_uplift_is_its_force_s_angle_above_the_sloping_seabed() {
        let mut scene = Scene::builtin("steel_catenary").unwrap();
        let alpha = 10f64.to_radians();
        let bed = scene.seabed.as_mut().unwrap();
        bed.slope = 10.0;
        let on_bed = bed.height_at(scene.anchor.x, scene.anchor.y);
        scene.anchor.z = on_bed;
        // down the slope (−x and down), then turned about y by ±5 deg
        let along = V3::new(-alpha.cos(), 0.0, -alpha.sin());
        let normal = V3::new(-alpha.sin(), 0.0, alpha.cos());
        let turned = |deg: f64| 3e5 * (deg.to_radians().cos() * along + deg.to_radians().sin() * normal);
        let angle = |f: V3| anchor_uplift(&scene, f).unwrap();
        for (f, expected) in [
            (turned(0.0), 0.0),
            (turned(5.0), 5.0),
            (turned(-5.0), -5.0),
            (V3::new(0.0, 0.0, 2e5), 80.0),
            (V3::new(-2e5, 0.0, 0.0), 10.0),
            (V3::new(0.0, 2e5, 0.0), 0.0),
        ] {
            let a = angle(f);
            assert!((a - expected).abs() < 1e-12, "{f:?}: {a} deg, expected {expected}");
        }
        // heights above the plane, square to it: the vertical gap times cos(slope)
        for (up, on) in [(0.9, true), (1.1, false)] {
            scene.anchor.z = on_bed + up * ANCHOR_ON_SEABED / alpha.cos();
            assert_eq!(anchor_uplift(&scene, turned(5.0)).is_some(), on, "{up} m above");
        }
        scene.seabed = None;
        assert!(anchor_uplift(&scene, turned(5.0)).is_none());
    }

    /// (12.5) on synthetic series sampled 100 times a period of 10 s: a
    /// steady sine 100 + 10 sin(ωt) drifts 0; with 5 e^{−t/10} added, over
    /// [20, 40], the decay's fall between the periods' maxima (at 22.5 and
    /// 32.5 s) over the max, 5 (e^{−2.25} − e^{−3.25}) / (110 + 5 e^{−2.25}),
    /// to 1 % (the decay moves the maxima a little); a window shorter than two periods has none; the
    /// warning is given above its limit only.
    #[test]
    fn the_window_s_drift_is_the_first_and_last_periods_extremes_apart() {
        let w = 2.0 * std::f64::consts::PI / 10.0;
        let t: Vec<f64> = (0..=4000).map(|k| k as f64 * 0.1).collect();
        let steady: Vec<(f64, f64)> = t.iter().map(|&x| (x, 100.0 + 10.0 * (w * x).sin())).collect();
        assert!(window_drift(&steady, (20.0, 40.0), 10.0).unwrap() < 1e-12);
        let decaying: Vec<(f64, f64)> = steady.iter().map(|&(x, y)| (x, y + 5.0 * (-x / 10.0).exp())).collect();
        let d = window_drift(&decaying, (20.0, 40.0), 10.0).unwrap();
        let closed = 5.0 * ((-2.25f64).exp() - (-3.25f64).exp()) / (110.0 + 5.0 * (-2.25f64).exp());
        assert!((d / closed - 1.0).abs() < 0.01, "{d:e} against {closed:e}");
        assert!(window_drift(&decaying, (20.0, 39.0), 10.0).is_none());
        assert!(unsteady_window_warning(d, 1e-2, (20.0, 40.0), 10.0).is_none());
        let m = unsteady_window_warning(d, 1e-3, (20.0, 40.0), 10.0).unwrap();
        assert!(m.contains("20 to 30 s") && m.contains("30 to 40 s"), "{m}");
        assert!(m.contains("--duration 60 --window 40,60"), "{m}");
    }

    /// The detector on synthetic histories, a steady flux of 1 kJ/s: a
    /// dissipation growing like e^{t/30} warns; a start's transient
    /// (1 − e^{−t/5}) and a steady rate (0.5 t) do not; nor growth below 1e-4
    /// of what was exchanged; nor a dissipation that grows with a flux that
    /// grows with it (a long ramp: both like t³).
    #[test]
    fn a_growing_high_frequency_dissipation_is_warned_of() {
        let t: Vec<f64> = (0..=1200).map(|k| k as f64 * 0.1).collect();
        let of = |f: &dyn Fn(f64) -> f64| t.iter().map(|&x| f(x)).collect::<Vec<f64>>();
        let steady: Vec<[f64; 2]> = t.iter().map(|&x| [1e3 * x, 0.0]).collect();
        let growing = of(&|x| (x / 30.0).exp());
        let w = growing_dissipation_warning(&t, &growing, &steady).expect("growing");
        assert!(w.contains("structural_damping") && w.contains("rho_infinity=1"), "{w}");
        assert!(growing_dissipation_warning(&t, &of(&|x| 100.0 * (1.0 - (-x / 5.0).exp())), &steady).is_none());
        assert!(growing_dissipation_warning(&t, &of(&|x| 0.5 * x), &steady).is_none());
        let large: Vec<[f64; 2]> = t.iter().map(|&x| [1e3 * x, 1e10]).collect();
        assert!(growing_dissipation_warning(&t, &growing, &large).is_none());
        let ramp: Vec<[f64; 2]> = t.iter().map(|&x| [x * x * x, 0.0]).collect();
        assert!(growing_dissipation_warning(&t, &of(&|x| 1e-3 * x * x * x), &ramp).is_none());
        assert!(growing_dissipation_warning(&t[..3], &growing[..3], &steady[..3]).is_none());
        // a line at rest: the same growth, scaled to round-off (1e-6 J of a 1e-3 J flux), is no warning;
        // scaled to 10 J of a 1e4 J flux it is one
        let rest: Vec<[f64; 2]> = t.iter().map(|&x| [1e-5 * x, 0.0]).collect();
        assert!(growing_dissipation_warning(&t, &of(&|x| 1e-7 * (x / 30.0).exp()), &rest).is_none());
        let scaled: Vec<[f64; 2]> = t.iter().map(|&x| [1e2 * x, 0.0]).collect();
        assert!(growing_dissipation_warning(&t, &of(&|x| 0.3 * (x / 30.0).exp()), &scaled).is_some());
    }

    /// The running watch on the same histories: fed every 0.1 s it speaks
    /// on the growth three spans after the first mark (at 120 s) and only
    /// once, not on a transient, a steady rate, a growing ramp or growth
    /// below 1e-4 of what was exchanged; fed every 7 s or every 45 s (steps
    /// that do not divide its span, or longer than it) it speaks too, its
    /// marks interpolated; a copy taken before and fed again after (a
    /// restored state) speaks as the original did.
    #[test]
    fn the_running_watch_speaks_on_growth_only() {
        let run = |f: &dyn Fn(f64) -> f64, w: &dyn Fn(f64) -> [f64; 2], h: f64| {
            let mut watch = GrowthWatch::new(0.0);
            let mut said = Vec::new();
            for k in 0..=(600.0 / h) as usize {
                let t = k as f64 * h;
                if watch.feed(t, f(t), w(t)).is_some() {
                    said.push(t);
                    watch = GrowthWatch::off();
                }
            }
            said
        };
        let growth = |x: f64| (x / 30.0).exp();
        let steady = |x: f64| [1e3 * x, 0.0];
        let said = run(&growth, &steady, 0.1);
        assert_eq!(said.len(), 1);
        assert!((said[0] - 120.0).abs() < 1e-6, "{said:?}");
        assert!(run(&|x| 100.0 * (1.0 - (-x / 5.0).exp()), &steady, 0.1).is_empty());
        assert!(run(&|x| 0.5 * x, &steady, 0.1).is_empty());
        assert!(run(&|x| 1e-3 * x * x * x, &|x| [x * x * x, 0.0], 0.1).is_empty());
        assert!(run(&growth, &|x| [1e3 * x, 1e14], 0.1).is_empty());
        assert_eq!(run(&growth, &steady, 7.0), vec![126.0]);
        assert_eq!(run(&growth, &steady, 45.0).len(), 1);
        // a restored copy
        let mut a = GrowthWatch::new(0.0);
        for k in 0..=900 {
            let t = k as f64 * 0.1;
            assert!(a.feed(t, growth(t), steady(t)).is_none());
        }
        let mut b = a;
        let said_a = (901..=1300).map(|k| k as f64 * 0.1).find(|&t| a.feed(t, growth(t), steady(t)).is_some());
        let said_b = (901..=1300).map(|k| k as f64 * 0.1).find(|&t| b.feed(t, growth(t), steady(t)).is_some());
        assert_eq!(said_a, said_b);
        assert!(said_a.is_some());
        // nothing from a watch that is off, or from a non-finite time
        assert!(GrowthWatch::off().feed(1e3, 1e9, [0.0; 2]).is_none());
        assert!(GrowthWatch::new(0.0).feed(f64::INFINITY, 1.0, [0.0; 2]).is_none());
    }
}
