//! Scene files (TOML, serde): the line, its ends, the environment, the current,
//! buoyancy modules and the analysis settings, all in SI units. Built-in
//! scenes ship in `scenes/` and are compiled in. Parameters can be overridden
//! by the FMU's parameter names (docs/interface.md).

mod checker;
mod overrides;
pub mod ranges;
pub mod raos;
pub mod sections;
pub mod system;
mod validate;
pub mod waves;

pub use checker::FieldError;
pub use overrides::PARAMETER_NAMES;

use crate::math::V3;
use serde::{Deserialize, Serialize};

/// Built-in scenes: (name, TOML text).
pub const BUILTIN: [(&str, &str); 3] = [
    ("catenary", include_str!("../../scenes/catenary.toml")),
    ("lazy_wave", include_str!("../../scenes/lazy_wave.toml")),
    ("steel_catenary", include_str!("../../scenes/steel_catenary.toml")),
];

/// The default scene.
pub const DEFAULT_SCENE: &str = "catenary";

/// Line properties (paper Table 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Line {
    /// Unstretched length, m.
    pub length: f64,
    /// Mass per unit length in air, kg/m.
    pub mass_per_length: f64,
    /// Outer diameter for buoyancy and drag, m.
    pub outer_diameter: f64,
    /// EA, N (also the paper's shear penalty R).
    pub axial_stiffness: f64,
    /// EI, N m².
    pub bending_stiffness: f64,
    /// GJ, N m².
    pub torsional_stiffness: f64,
    /// Normal drag coefficient (reference length D).
    #[serde(default)]
    pub cd_normal: f64,
    /// Tangential drag coefficient (reference length D).
    #[serde(default)]
    pub cd_tangential: f64,
    /// Normal added-mass coefficient.
    #[serde(default)]
    pub ca_normal: f64,
    /// Rotary inertia per length ρI11 = ρI22, kg m; default m D²/8 (thin-walled tube).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary_inertia: Option<f64>,
    /// Outer diameter of the steel wall, m (default `outer_diameter`; less
    /// with a coating, which `outer_diameter` includes), docs/theory.md §12.4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steel_outer_diameter: Option<f64>,
    /// Thickness of the steel wall, m (unset or 0: no wall given; the
    /// stresses then come from the homogeneous tube of EA, EI and D, §12.2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_thickness: Option<f64>,
    /// Young's modulus of the wall, Pa; default [`sections::DEFAULT_YOUNGS_MODULUS`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<f64>,
    /// Yield stress of the wall (SMYS), Pa: the code check's (unset or 0: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_stress: Option<f64>,
    /// Density of the contents, kg/m³: their weight ρ_i A_i (added to the
    /// mass per length, its inertia too) and their pressure head.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub internal_fluid_density: Option<f64>,
    /// Gauge pressure of the contents at the hang-off, Pa.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub internal_pressure: Option<f64>,
    /// API RP 2RD's design case factor C_f (1.0 operating, 1.2 extreme, 1.5
    /// survival or test); default 1.0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design_case_factor: Option<f64>,
    /// Tensile strength of the wall (SMTS, the characteristic f_u), Pa:
    /// DNV-OS-F201's LRFD check's, with `yield_stress` and `safety_class`
    /// (unset or 0: none), docs/theory.md §12.4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensile_strength: Option<f64>,
    /// DNV-OS-F201's safety class, whose γ_SC the LRFD check takes (unset:
    /// no LRFD check).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub safety_class: Option<SafetyClass>,
    /// DNV-OS-F201's load effect factor on the functional load effects γ_F;
    /// default [`crate::sim::lrfd::FUNCTIONAL_LOAD_FACTOR`] (ULS).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_factor_functional: Option<f64>,
    /// DNV-OS-F201's load effect factor on the environmental load effects
    /// γ_E; default [`crate::sim::lrfd::ENVIRONMENTAL_LOAD_FACTOR`] (ULS).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_factor_environmental: Option<f64>,
    /// DNV-OS-F201's material resistance factor γ_m; default
    /// [`crate::sim::lrfd::MATERIAL_RESISTANCE_FACTOR`] (ULS and ALS).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material_resistance_factor: Option<f64>,
}

/// γ_F, the ULS load effect factor on functional load effects (DNV-OS-F201
/// Table 5-2; DNV-OS-C501 Table 8-4 for risers; Flexcom's default): the
/// default of `load_factor_functional` (the check itself: `sim::lrfd`).
pub const FUNCTIONAL_LOAD_FACTOR: f64 = 1.1;
/// γ_E, the ULS load effect factor on environmental load effects (the
/// default of `load_factor_environmental`).
pub const ENVIRONMENTAL_LOAD_FACTOR: f64 = 1.3;
/// γ_m, the material resistance factor of the ULS and the ALS (the default
/// of `material_resistance_factor`).
pub const MATERIAL_RESISTANCE_FACTOR: f64 = 1.15;

/// DNV-OS-F201's safety class: the consequence of a failure (docs/theory.md
/// §12.4), which sets the resistance factor γ_SC of the LRFD check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SafetyClass {
    Low,
    Normal,
    High,
}

impl SafetyClass {
    pub const ALL: [SafetyClass; 3] = [SafetyClass::Low, SafetyClass::Normal, SafetyClass::High];

    pub fn name(self) -> &'static str {
        match self {
            SafetyClass::Low => "low",
            SafetyClass::Normal => "normal",
            SafetyClass::High => "high",
        }
    }

    /// The class named `text`, or None for `none` (no LRFD check).
    pub fn parse(text: &str) -> Result<Option<SafetyClass>, String> {
        if text == "none" {
            return Ok(None);
        }
        SafetyClass::ALL
            .into_iter()
            .find(|c| c.name() == text)
            .map(Some)
            .ok_or_else(|| format!("'{text}' is not a safety class: low, normal, high (or none: no DNV-OS-F201 check)"))
    }
}

/// Anchor position, m (the hang-off is at the origin).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Anchor {
    pub x: f64,
    #[serde(default)]
    pub y: f64,
    pub z: f64,
}

/// Water and gravity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Environment {
    /// kg/m³.
    #[serde(default = "default_water_density")]
    pub water_density: f64,
    /// m/s².
    #[serde(default = "default_gravity")]
    pub gravity: f64,
    /// Height of the free surface, m.
    #[serde(default = "default_surface")]
    pub water_surface_z: f64,
}

fn default_water_density() -> f64 {
    1025.0
}
fn default_gravity() -> f64 {
    9.81
}
fn default_surface() -> f64 {
    10.0
}

impl Default for Environment {
    fn default() -> Self {
        Environment {
            water_density: default_water_density(),
            gravity: default_gravity(),
            water_surface_z: default_surface(),
        }
    }
}

/// Kind of current profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProfileKind {
    None,
    /// `speed` everywhere.
    Uniform,
    /// Linear in S from `top` (S = 0) to `bottom` (S = L).
    LinearS,
    /// Linear in depth from `top` (surface) to `bottom` (at `depth` m), constant below.
    LinearDepth,
    /// Piecewise linear in depth: `table` rows [depth m, speed m/s].
    Table,
}

/// Current profile as written in a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurrentSpec {
    pub profile: ProfileKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub top: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bottom: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<Vec<[f64; 2]>>,
    /// Horizontal flow direction (x, y); default +x.
    #[serde(default = "default_direction")]
    pub direction: [f64; 2],
    /// Time over which the current grows from zero at the run's start, s
    /// (unset: [`DEFAULT_CURRENT_RAMP`]; 0: in full from the start, the paper's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp: Option<f64>,
}

fn default_direction() -> [f64; 2] {
    [1.0, 0.0]
}

impl Default for CurrentSpec {
    fn default() -> Self {
        CurrentSpec {
            profile: ProfileKind::None,
            speed: None,
            top: None,
            bottom: None,
            depth: None,
            table: None,
            direction: default_direction(),
            ramp: None,
        }
    }
}

/// Buoyancy modules: `load` N/m upward on S ∈ [start, end] m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Buoyancy {
    pub start: f64,
    pub end: f64,
    pub load: f64,
}

/// The seabed (docs/theory.md §9): a plane through (0, 0, `z`) rising by
/// `slope` degrees towards +x, with MoorDyn's contact law (kBot `stiffness`,
/// cBot `damping`, per unit contact area D·dS) and regularised Coulomb friction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeabedSpec {
    /// Height of the seabed below the hang-off (at x = y = 0), m.
    pub z: f64,
    /// Slope, deg (+: the seabed rises towards +x).
    #[serde(default)]
    pub slope: f64,
    /// Penetration stiffness per unit contact area (MoorDyn's kBot), Pa/m.
    #[serde(default = "default_seabed_stiffness")]
    pub stiffness: f64,
    /// Penetration damping per unit contact area (MoorDyn's cBot), Pa s/m.
    #[serde(default = "default_seabed_damping")]
    pub damping: f64,
    /// Coulomb friction coefficient, axial and lateral (0: frictionless).
    #[serde(default)]
    pub friction: f64,
    /// Axial friction coefficient (default `friction`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_axial: Option<f64>,
    /// Lateral friction coefficient (default `friction`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_lateral: Option<f64>,
    /// Regularisation velocity of the friction v_ε, m/s: the friction
    /// reaches μN smoothly over a few v_ε of slip speed (docs/theory.md §9).
    #[serde(default = "default_slip_velocity")]
    pub slip_velocity: f64,
}

/// The time over which the current grows from zero at a run's start when
/// the scene does not say (`current_ramp`, s; docs/theory.md §5.11): long
/// against the axial and bending periods the jolt of a current in full would
/// ring, short against the windows (one period after the motion's ramp).
pub const DEFAULT_CURRENT_RAMP: f64 = 10.0;

/// MoorDyn's default kBot, Pa/m.
pub const DEFAULT_SEABED_STIFFNESS: f64 = 3.0e6;
/// MoorDyn's default cBot, Pa s/m.
pub const DEFAULT_SEABED_DAMPING: f64 = 3.0e5;
/// The default regularisation velocity of the friction, m/s.
pub const DEFAULT_SLIP_VELOCITY: f64 = 0.01;
/// The height of the seabed an FMU or `--set` reads when the scene has none,
/// m: the lowest the range allows, below every line (no contact).
pub const NO_SEABED_Z: f64 = -20_000.0;

fn default_seabed_stiffness() -> f64 {
    DEFAULT_SEABED_STIFFNESS
}
fn default_seabed_damping() -> f64 {
    DEFAULT_SEABED_DAMPING
}
fn default_slip_velocity() -> f64 {
    DEFAULT_SLIP_VELOCITY
}

impl SeabedSpec {
    /// A flat seabed at `z` with the default contact law and no friction.
    pub fn flat(z: f64) -> Self {
        SeabedSpec {
            z,
            slope: 0.0,
            stiffness: DEFAULT_SEABED_STIFFNESS,
            damping: DEFAULT_SEABED_DAMPING,
            friction: 0.0,
            friction_axial: None,
            friction_lateral: None,
            slip_velocity: DEFAULT_SLIP_VELOCITY,
        }
    }

    /// Friction coefficients [axial, lateral].
    pub fn friction_coefficients(&self) -> [f64; 2] {
        [self.friction_axial.unwrap_or(self.friction), self.friction_lateral.unwrap_or(self.friction)]
    }

    /// Height of the seabed under (x, y), m.
    pub fn height_at(&self, x: f64, _y: f64) -> f64 {
        self.z + x * self.slope.to_radians().tan()
    }
}

/// Which line model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Model {
    /// Full Cosserat director rod.
    Rod,
    /// Cable without bending and torsion (cheaper).
    Cable,
}

/// Analysis settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Analysis {
    #[serde(default = "default_model")]
    pub model: Model,
    #[serde(default = "default_elements")]
    pub n_elements: usize,
    /// Internal time step, s.
    #[serde(default = "default_time_step")]
    pub time_step: f64,
    /// Relative residual tolerance of Newton.
    #[serde(default = "default_tolerance")]
    pub newton_tolerance: f64,
    /// Include the current in the initial static equilibrium.
    #[serde(default)]
    pub static_current: bool,
    /// Stiffness-proportional (Kelvin–Voigt) structural damping time η, s:
    /// stress += η C ε̇. Damps the unresolved axial and shear waves (damping
    /// ratio η ω/2 for a mode of circular frequency ω); 0 keeps the paper's
    /// energy-conserving scheme (docs/theory.md §5.9).
    #[serde(default)]
    pub structural_damping: f64,
    /// High-frequency spectral radius ρ∞ of the time stepping, (0, 1]: 1 is
    /// the paper's energy–momentum conserving scheme; below 1 the unresolved
    /// modes (ω h ≫ 1) lose a factor ρ∞ of amplitude per step, the resolved
    /// ones are kept to second order (docs/theory.md §5.10).
    #[serde(default = "default_rho_infinity")]
    pub rho_infinity: f64,
    /// The relative error of the top tension the user accepts (issue 28,
    /// docs/theory.md §16); 0: unset, the numerics above are used as given.
    /// When set, `sim::accuracy` chooses `n_elements`, `time_step` and
    /// `newton_tolerance` (those of this block are then defaults it replaces;
    /// a `--set`/FMU value of one of them wins over its choice).
    #[serde(default, skip_serializing_if = "is_unset")]
    pub accuracy: f64,
    /// The amplitude of the hang-off motion, m, the accuracy knob chooses for
    /// (docs/theory.md §16.2): unset, `riser run` takes its own motion's (0
    /// without one) and `riser statics` and the FMU the design motion's
    /// 2.5 m; set, it wins over the run's motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy_motion_amplitude: Option<f64>,
    /// The period of the hang-off motion, s, the accuracy knob chooses for:
    /// unset, the run's motion's and otherwise the design motion's 10 s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy_motion_period: Option<f64>,
    /// What `accuracy` is on (docs/theory.md §16.12): the top tension by
    /// default.
    #[serde(default, skip_serializing_if = "AccuracyQuantity::is_default")]
    pub accuracy_quantity: AccuracyQuantity,
}

/// The quantity the `accuracy` target is on (docs/theory.md §16.12).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AccuracyQuantity {
    /// The steady window's top tension: its min, mean and max, relative to its max.
    #[default]
    TopTension,
    /// The largest outer-fibre stress range along the line.
    StressRange,
    /// The touchdown's extremes, relative to its largest arc length.
    Touchdown,
    /// Miner's damage at the worst point (`riser run --fatigue`).
    Fatigue,
    /// All of those the scene has.
    All,
}

impl AccuracyQuantity {
    pub const ALL: [AccuracyQuantity; 5] = [
        AccuracyQuantity::TopTension,
        AccuracyQuantity::StressRange,
        AccuracyQuantity::Touchdown,
        AccuracyQuantity::Fatigue,
        AccuracyQuantity::All,
    ];

    pub fn name(self) -> &'static str {
        match self {
            AccuracyQuantity::TopTension => "top_tension",
            AccuracyQuantity::StressRange => "stress_range",
            AccuracyQuantity::Touchdown => "touchdown",
            AccuracyQuantity::Fatigue => "fatigue",
            AccuracyQuantity::All => "all",
        }
    }

    pub fn parse(text: &str) -> Result<AccuracyQuantity, String> {
        AccuracyQuantity::ALL.into_iter().find(|q| q.name() == text).ok_or_else(|| {
            let names: Vec<&str> = AccuracyQuantity::ALL.iter().map(|q| q.name()).collect();
            format!("'{text}' is not one of {}", names.join(", "))
        })
    }

    fn is_default(&self) -> bool {
        *self == AccuracyQuantity::TopTension
    }
}

fn is_unset(v: &f64) -> bool {
    *v == 0.0
}

fn default_model() -> Model {
    Model::Rod
}
fn default_elements() -> usize {
    60
}
fn default_time_step() -> f64 {
    0.05
}
fn default_tolerance() -> f64 {
    1e-8
}
/// The amplitude of the design motion, m, the accuracy knob chooses for
/// where the motion is not known (`riser statics`, the FMU) and
/// `accuracy_motion_amplitude` is unset (docs/theory.md §16.2).
pub const DESIGN_MOTION_AMPLITUDE: f64 = 2.5;
/// The period of the design motion, s: the shortest the knob covers.
pub const DESIGN_MOTION_PERIOD: f64 = 10.0;
/// The default ρ∞ (docs/theory.md §5.10 says how it was chosen).
pub const DEFAULT_RHO_INFINITY: f64 = 0.8;
fn default_rho_infinity() -> f64 {
    DEFAULT_RHO_INFINITY
}

impl Default for Analysis {
    fn default() -> Self {
        Analysis {
            model: default_model(),
            n_elements: default_elements(),
            time_step: default_time_step(),
            newton_tolerance: default_tolerance(),
            static_current: false,
            structural_damping: 0.0,
            rho_infinity: default_rho_infinity(),
            accuracy: 0.0,
            accuracy_motion_amplitude: None,
            accuracy_motion_period: None,
            accuracy_quantity: AccuracyQuantity::TopTension,
        }
    }
}

/// A scene: everything needed to set up a line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub line: Line,
    pub anchor: Anchor,
    #[serde(default)]
    pub environment: Environment,
    #[serde(default)]
    pub current: CurrentSpec,
    #[serde(default)]
    pub buoyancy: Vec<Buoyancy>,
    /// Line sections from the hang-off down (`[[section]]`; none: `[line]`
    /// everywhere), docs/theory.md §11.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub section: Vec<sections::SectionSpec>,
    /// The seabed (none: the line never touches bottom, at no cost).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seabed: Option<SeabedSpec>,
    /// Waves (none: still water, at no cost), docs/theory.md §13.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub waves: Option<waves::WavesSpec>,
    #[serde(default)]
    pub analysis: Analysis,
    /// The hang-off's end condition (`[hang_off]`; default pinned).
    #[serde(default, skip_serializing_if = "HangOffSpec::is_default")]
    pub hang_off: HangOffSpec,
    /// The vessel (`[vessel]`: its RAOs, docs/theory.md §14.5; none: the
    /// vessel moves only as the CLI's options or the FMU's inputs say).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vessel: Option<raos::VesselSpec>,
}

/// How the line's end is held at the hang-off (docs/theory.md §15).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HangOffEnd {
    /// Position follows the vessel; free to rotate and twist (no moment).
    #[default]
    Pinned,
    /// Position follows the vessel; the end's orientation held at its
    /// static one (a stiff connection, the rod only).
    Clamped,
    /// Position follows the vessel; a rotational spring in bending
    /// (`[hang_off] stiffness` or `table`), torsionally stiff, between the
    /// vessel and the end (the rod only).
    FlexJoint,
}

impl HangOffEnd {
    pub fn name(self) -> &'static str {
        match self {
            HangOffEnd::Pinned => "pinned",
            HangOffEnd::Clamped => "clamped",
            HangOffEnd::FlexJoint => "flex_joint",
        }
    }
}

/// The order in which roll, pitch and yaw compose the vessel's rotation
/// (docs/theory.md §14).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RotationOrderSpec {
    /// R = Rz(yaw) Ry(pitch) Rx(roll), the marine convention.
    #[default]
    Zyx,
    /// R = Rx(roll) Ry(pitch) Rz(yaw), MoorDyn's and OpenFAST's.
    Xyz,
}

impl RotationOrderSpec {
    pub fn order(self) -> crate::math::rigid::RotationOrder {
        match self {
            RotationOrderSpec::Zyx => crate::math::rigid::RotationOrder::Zyx,
            RotationOrderSpec::Xyz => crate::math::rigid::RotationOrder::Xyz,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            RotationOrderSpec::Zyx => "zyx",
            RotationOrderSpec::Xyz => "xyz",
        }
    }
}

/// `[hang_off]`: the end condition at the hang-off and where it sits on the
/// vessel (docs/theory.md §14).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HangOffSpec {
    #[serde(default)]
    pub end: HangOffEnd,
    /// ρ, the hang-off's position in the vessel frame relative to the
    /// vessel's reference point, m (default: at the reference point).
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub offset: [f64; 3],
    /// How the vessel's roll, pitch and yaw compose its rotation.
    #[serde(default, skip_serializing_if = "is_default_order")]
    pub rotation_order: RotationOrderSpec,
    /// A flex joint's bending stiffness, N m/rad (`end = "flex_joint"`;
    /// ignored by the other ends).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// A flex joint's bending moment against its angle, rows [angle rad,
    /// moment N m] from [0, 0], as vendors give it (instead of `stiffness`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<Vec<[f64; 2]>>,
}

/// Checks a flex joint's table of [angle rad, moment N m]: at least two
/// rows, the first (0, 0), finite, angles increasing below π, moments
/// non-decreasing (a joint that softens to nothing is allowed, one that
/// pushes back less as it turns further is not).
pub fn check_joint_table(rows: &[[f64; 2]]) -> Result<(), String> {
    if rows.len() < 2 {
        return Err(format!("{} row(s): a table needs at least two rows [angle rad, moment N m]", rows.len()));
    }
    if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| !(r[0].is_finite() && r[1].is_finite())) {
        return Err(format!("row {i} [{}, {}] is not finite", r[0], r[1]));
    }
    if rows[0] != [0.0, 0.0] {
        return Err(format!(
            "starts at [{}, {}]: it must start at [0, 0] (no moment at no angle)",
            rows[0][0], rows[0][1]
        ));
    }
    for (i, w) in rows.windows(2).enumerate() {
        if w[1][0] <= w[0][0] {
            return Err(format!(
                "angles must increase: row {} ({} rad) after row {i} ({} rad)",
                i + 1,
                w[1][0],
                w[0][0]
            ));
        }
        if w[1][1] < w[0][1] {
            return Err(format!(
                "not monotonic: the moment falls from {} N m (row {i}) to {} N m (row {})",
                w[0][1],
                w[1][1],
                i + 1
            ));
        }
    }
    let last = rows[rows.len() - 1][0];
    if last >= std::f64::consts::PI {
        return Err(format!("angles are in radians, below pi: the last is {last}"));
    }
    Ok(())
}

fn is_zero3(v: &[f64; 3]) -> bool {
    *v == [0.0; 3]
}

fn is_default_order(o: &RotationOrderSpec) -> bool {
    *o == RotationOrderSpec::default()
}

impl HangOffSpec {
    fn is_default(&self) -> bool {
        *self == HangOffSpec::default()
    }
}

/// Why a scene could not be used.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneError {
    /// Neither a built-in name nor a readable file.
    NotFound { name: String, reason: String },
    /// The file is not valid TOML for a scene.
    Parse { source: String, message: String },
    /// Values out of their allowed ranges.
    Invalid(Vec<FieldError>),
    /// An override that names no parameter or has an unusable value.
    Override { name: String, message: String },
}

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SceneError::NotFound { name, reason } => write!(
                f,
                "scene '{name}' is not a built-in scene ({}) and cannot be read as a file: {reason}",
                BUILTIN.iter().map(|b| b.0).collect::<Vec<_>>().join(", ")
            ),
            SceneError::Parse { source, message } => write!(f, "scene {source}: {message}"),
            SceneError::Invalid(errs) => {
                // values given on the command line (`--set`) are named as such, not as the scene's
                if !errs.is_empty() && errs.iter().all(|e| e.field.starts_with("--set ")) {
                    write!(f, "invalid --set value:")?;
                } else {
                    write!(f, "invalid scene:")?;
                }
                for e in errs {
                    write!(f, "\n  {e}")?;
                }
                Ok(())
            }
            SceneError::Override { name, message } => write!(f, "--set {name}: {message}"),
        }
    }
}

impl std::error::Error for SceneError {}

/// A TOML/serde message with Rust's type names in the user's terms ("expected
/// usize" → "expected a whole number").
fn in_users_terms(message: &str) -> String {
    [
        ("expected usize", "expected a whole number (>= 0)"),
        ("expected u64", "expected a whole number (>= 0)"),
        ("expected u32", "expected a whole number (>= 0)"),
        ("expected i64", "expected a whole number"),
        ("expected f64", "expected a number"),
        ("expected a boolean", "expected true or false"),
        ("floating point `", "the number `"),
        ("invalid type: string", "invalid value: the text"),
        ("invalid type:", "invalid value:"),
    ]
    .iter()
    .fold(message.to_string(), |m, (rust, user)| m.replace(rust, user))
}

impl Scene {
    /// Parses and validates scene TOML text; `source` names it in messages.
    pub fn from_toml(text: &str, source: &str) -> Result<Scene, SceneError> {
        Scene::from_toml_at(text, source, None)
    }

    /// [`Scene::from_toml`] of the file at `path`: a relative `waves.file`
    /// is taken from the file's folder.
    fn from_toml_at(text: &str, source: &str, path: Option<&std::path::Path>) -> Result<Scene, SceneError> {
        if system::is_system_text(text) {
            return Err(SceneError::Parse { source: source.to_string(), message: system::NOT_YET.to_string() });
        }
        let mut scene: Scene = toml::from_str(text)
            .map_err(|e| SceneError::Parse { source: source.to_string(), message: in_users_terms(&e.to_string()) })?;
        if let Some(p) = path {
            scene.resolve_wave_file(p);
            scene.resolve_raos_file(p);
        }
        scene.validate()?;
        Ok(scene)
    }

    /// A built-in scene by name.
    pub fn builtin(name: &str) -> Option<Scene> {
        BUILTIN.iter().find(|b| b.0 == name).map(|b| Scene::from_toml(b.1, name).expect("built-in scenes are valid"))
    }

    /// A built-in scene name or the path of a scene file.
    pub fn load(name_or_path: &str) -> Result<Scene, SceneError> {
        if let Some(s) = Scene::builtin(name_or_path) {
            return Ok(s);
        }
        let text = std::fs::read_to_string(name_or_path)
            .map_err(|e| SceneError::NotFound { name: name_or_path.to_string(), reason: e.to_string() })?;
        Scene::from_toml_at(&text, name_or_path, Some(std::path::Path::new(name_or_path)))
    }

    /// Checks every value; lists all problems with the allowed ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let errs = validate::check(self);
        if errs.is_empty() { Ok(()) } else { Err(SceneError::Invalid(errs)) }
    }

    /// Applies `name=value` overrides (the FMU's parameter names), then
    /// validates; every refused override is listed (as `--set NAME`).
    pub fn with_overrides<S: AsRef<str>>(mut self, sets: &[S]) -> Result<Scene, SceneError> {
        apply_sets(sets, |name, value| self.set(name, value))?;
        self.validate()?;
        Ok(self)
    }

    /// Sets one parameter by its FMU parameter name (no validation of the whole scene).
    pub fn set(&mut self, name: &str, value: &str) -> Result<(), SceneError> {
        overrides::set(self, name, value)
    }

    /// The scene's value of a parameter (FMU / `--set` name) as text, `None`
    /// for an unknown name; where the scene holds several values, the
    /// documented one ([`Scene::parameter_note`]).
    pub fn parameter(&self, name: &str) -> Option<String> {
        overrides::get(self, name)
    }

    /// Where the scene holds parameter `name` as more than one value (a
    /// current table, several buoyancy sections, a flex joint's table,
    /// axial and lateral friction apart): what [`Scene::parameter`] reads,
    /// and what the scene holds, as a sentence for the log.
    pub fn parameter_note(&self, name: &str) -> Option<String> {
        overrides::multi_valued(self, name)
    }

    /// Anchor position, m.
    pub fn anchor(&self) -> V3 {
        V3::new(self.anchor.x, self.anchor.y, self.anchor.z)
    }

    /// Hang-off position, m (the origin).
    pub fn hang_off(&self) -> V3 {
        V3::zeros()
    }

    /// Rotary inertia per length, kg m (default m D²/8).
    pub fn rotary_inertia(&self) -> f64 {
        sections::bare_properties(&self.line).rotary_inertia
    }

    /// TOML text of the scene (after overrides).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("scene serialises")
    }
}

/// `--set name=value` overrides, each through `set` (name and value
/// trimmed); every one refused listed (as `--set NAME`, its message).
pub fn apply_sets<S: AsRef<str>>(
    sets: &[S],
    mut set: impl FnMut(&str, &str) -> Result<(), SceneError>,
) -> Result<(), SceneError> {
    let mut refused = Vec::new();
    for s in sets {
        let s = s.as_ref();
        let Some((name, value)) = s.split_once('=') else {
            refused.push(FieldError { field: format!("--set {s}"), message: "expected name=value".to_string() });
            continue;
        };
        if let Err(e) = set(name.trim(), value.trim()) {
            let message = match e {
                SceneError::Override { message, .. } => message,
                other => other.to_string(),
            };
            refused.push(FieldError { field: format!("--set {}", name.trim()), message });
        }
    }
    if refused.is_empty() { Ok(()) } else { Err(SceneError::Invalid(refused)) }
}
