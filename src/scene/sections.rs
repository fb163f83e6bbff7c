//! Line sections and buoyancy modules (docs/theory.md §11).
//!
//! A scene's `[[section]]` blocks split the line, from the hang-off down, into
//! lengths with their own properties; a key a section leaves out is `[line]`'s.
//! A section may carry buoyancy modules: bodies of diameter D_m and length
//! L_m clamped on the line every `module_pitch` p, of mass M_m each. Like
//! OrcaFlex's "equivalent line", the modules are smeared over their section
//! (fraction φ = L_m/p of its length is module); per metre of section they add
//!   mass                 M_m / p                                   (11.1)
//!   displaced volume     φ π (D_m² − D²)/4       (buoyancy)        (11.2)
//!   added mass           φ C_a,m ρ_w π (D_m² − D²)/4               (11.3)
//!   normal drag area     φ C_d,m (D_m − D)        (× ½ ρ_w |v|v)   (11.4)
//!   rotary inertia       (M_m/p)(D_m² + D²)/16                     (11.5)
//! to the bare line's (the modules' annulus around the line and its excess
//! projected width; the line inside keeps its own coefficients, so that with
//! C_d,m = C_a,m = 0 only the modules' weight and buoyancy remain). The
//! tangential drag stays the line's; the seabed bears the equivalent diameter.

use super::{Line, Scene};
use serde::{Deserialize, Serialize};

/// A `[[section]]` block: a length of line with its own properties (absent
/// keys are the `[line]`'s) and, optionally, buoyancy modules.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Unstretched length of the section, m (the sections add up to `line.length`).
    pub length: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_per_length: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_diameter: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_stiffness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsional_stiffness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cd_normal: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cd_tangential: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ca_normal: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary_inertia: Option<f64>,
    /// Outer diameter of a buoyancy module D_m, m (> the line's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_diameter: Option<f64>,
    /// Length of one module L_m along the line, m (≤ the pitch).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_length: Option<f64>,
    /// Distance between successive modules p, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_pitch: Option<f64>,
    /// Mass of one module in air M_m, kg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_mass: Option<f64>,
    /// Normal drag coefficient of a module C_d,m (on D_m − D); default
    /// [`DEFAULT_MODULE_CD`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_cd_normal: Option<f64>,
    /// Normal added-mass coefficient of a module C_a,m; default [`DEFAULT_MODULE_CA`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub module_ca_normal: Option<f64>,
    /// The steel wall's outer diameter, m (default: `[line]`'s, else the
    /// section's `outer_diameter`), docs/theory.md §12.4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steel_outer_diameter: Option<f64>,
    /// The steel wall's thickness, m (default `[line]`'s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_thickness: Option<f64>,
    /// The wall's Young's modulus, Pa (default `[line]`'s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<f64>,
    /// The wall's yield stress, Pa (default `[line]`'s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_stress: Option<f64>,
    /// The wall's tensile strength, Pa (default `[line]`'s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensile_strength: Option<f64>,
}

/// Default normal drag coefficient of a buoyancy module: a short cylinder
/// in cross flow at the Reynolds numbers of currents (about 1 to 1.2).
pub const DEFAULT_MODULE_CD: f64 = 1.2;
/// Default normal added-mass coefficient of a buoyancy module (a cylinder's
/// potential-flow value).
pub const DEFAULT_MODULE_CA: f64 = 1.0;

/// The Young's modulus of a wall whose scene gives none, Pa: 207 GPa, the
/// value DNV-OS-F201, DNV-RP-C203 and API RP 2RD's examples take for the
/// carbon-manganese steels of risers (API 5L X52 to X80), and the one the
/// built-in `steel_catenary`'s EA and EI were made with.
pub const DEFAULT_YOUNGS_MODULUS: f64 = 2.07e11;

/// The steel wall of a piece of line (docs/theory.md §12.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// Outer diameter of the steel D_s, m.
    pub outer_diameter: f64,
    /// Thickness t, m.
    pub thickness: f64,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
}

impl Wall {
    /// The bore d_i = D_s − 2t, m.
    pub fn inner_diameter(&self) -> f64 {
        self.outer_diameter - 2.0 * self.thickness
    }

    /// The steel's area A_s = π (D_s² − d_i²)/4, m².
    pub fn area(&self) -> f64 {
        let (d, b) = (self.outer_diameter, self.inner_diameter());
        std::f64::consts::PI * (d * d - b * b) / 4.0
    }

    /// The second moment of area I = π (D_s⁴ − d_i⁴)/64, m⁴.
    pub fn inertia(&self) -> f64 {
        let (d, b) = (self.outer_diameter, self.inner_diameter());
        std::f64::consts::PI * (d.powi(4) - b.powi(4)) / 64.0
    }
}

impl Line {
    /// The steel wall, when `wall_thickness` is given (and above 0).
    pub fn wall(&self) -> Option<Wall> {
        let thickness = self.wall_thickness.filter(|t| *t > 0.0)?;
        Some(Wall {
            outer_diameter: self.steel_outer_diameter.unwrap_or(self.outer_diameter),
            thickness,
            youngs_modulus: self.youngs_modulus.unwrap_or(DEFAULT_YOUNGS_MODULUS),
        })
    }

    /// The bore's diameter d_i, m: the wall's, else that of the homogeneous
    /// tube of EA, EI and D, d² = 16 EI/EA − D² (12.1); None when neither
    /// exists (a flexible pipe without a wall given).
    pub fn bore_diameter(&self) -> Option<f64> {
        if let Some(w) = self.wall() {
            return Some(w.inner_diameter());
        }
        let d = self.outer_diameter;
        let d_in2 = 16.0 * self.bending_stiffness / self.axial_stiffness - d * d;
        (d_in2 >= 0.0 && d_in2 < d * d).then(|| d_in2.sqrt())
    }

    /// Whether the line has contents: a density or a pressure given (not 0).
    pub fn has_contents(&self) -> bool {
        self.internal_fluid_density.is_some_and(|r| r != 0.0) || self.internal_pressure.is_some_and(|p| p != 0.0)
    }
}

/// Buoyancy modules of a section (all four sizes given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modules {
    /// D_m, m.
    pub diameter: f64,
    /// L_m, m.
    pub length: f64,
    /// p, m.
    pub pitch: f64,
    /// M_m, kg.
    pub mass: f64,
    pub cd_normal: f64,
    pub ca_normal: f64,
}

/// The properties of a piece of line per metre of unstretched length, with
/// its modules smeared (11.1–11.4): what the loads and the models read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineProperties {
    /// Mass per length in air, line and modules, kg/m.
    pub mass_per_length: f64,
    /// Displaced volume per length, m² (buoyancy ρ_w g times this).
    pub displaced_area: f64,
    /// Normal added mass per length over ρ_w, m² (C_a A + modules').
    pub added_mass_area: f64,
    /// Normal drag per length over ½ ρ_w |v_n| v_n: C_dn D + modules', m.
    pub drag_normal: f64,
    /// Tangential drag per length over ½ ρ_w |v_t| v_t: C_dt D, m.
    pub drag_tangential: f64,
    /// Diameter of the equivalent line (of the displaced area), m: the
    /// seabed's contact width and the free surface's transition.
    pub diameter: f64,
    /// EA, N.
    pub axial_stiffness: f64,
    /// EI, N m².
    pub bending_stiffness: f64,
    /// GJ, N m².
    pub torsional_stiffness: f64,
    /// Rotary inertia per length, kg m.
    pub rotary_inertia: f64,
    /// Outer diameter of the pipe itself (not of its modules), m: the outer
    /// fibre of the stresses of the homogeneous tube, and the diameter over
    /// which the water's pressure acts on the pipe (docs/theory.md §12).
    pub pipe_diameter: f64,
    /// The steel wall, when the scene gives one (§12.4).
    pub wall: Option<Wall>,
    /// The wall's yield stress, Pa, when the scene gives one.
    pub yield_stress: Option<f64>,
    /// The wall's tensile strength, Pa, when the scene gives one.
    pub tensile_strength: Option<f64>,
}

/// A piece of line [start, end] (m of unstretched arc length from the hang-off).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub start: f64,
    pub end: f64,
    pub properties: LineProperties,
}

impl SectionSpec {
    /// The section's modules, if it has all four sizes.
    pub fn modules(&self) -> Option<Modules> {
        Some(Modules {
            diameter: self.module_diameter?,
            length: self.module_length?,
            pitch: self.module_pitch?,
            mass: self.module_mass?,
            cd_normal: self.module_cd_normal.unwrap_or(DEFAULT_MODULE_CD),
            ca_normal: self.module_ca_normal.unwrap_or(DEFAULT_MODULE_CA),
        })
    }

    /// The bare line of this section: `[line]` with this section's keys.
    pub fn bare_line(&self, line: &Line) -> Line {
        Line {
            length: self.length,
            mass_per_length: self.mass_per_length.unwrap_or(line.mass_per_length),
            outer_diameter: self.outer_diameter.unwrap_or(line.outer_diameter),
            axial_stiffness: self.axial_stiffness.unwrap_or(line.axial_stiffness),
            bending_stiffness: self.bending_stiffness.unwrap_or(line.bending_stiffness),
            torsional_stiffness: self.torsional_stiffness.unwrap_or(line.torsional_stiffness),
            cd_normal: self.cd_normal.unwrap_or(line.cd_normal),
            cd_tangential: self.cd_tangential.unwrap_or(line.cd_tangential),
            ca_normal: self.ca_normal.unwrap_or(line.ca_normal),
            // [line]'s if it sets one, else the default m D²/8 of the section's own m and D
            rotary_inertia: self.rotary_inertia.or(line.rotary_inertia),
            // the wall: the section's keys, else [line]'s (the steel diameter,
            // unset in both, is the section's own outer diameter)
            steel_outer_diameter: self.steel_outer_diameter.or(line.steel_outer_diameter),
            wall_thickness: self.wall_thickness.or(line.wall_thickness),
            youngs_modulus: self.youngs_modulus.or(line.youngs_modulus),
            yield_stress: self.yield_stress.or(line.yield_stress),
            tensile_strength: self.tensile_strength.or(line.tensile_strength),
            // the contents and the load case are the line's: one fluid column
            internal_fluid_density: line.internal_fluid_density,
            internal_pressure: line.internal_pressure,
            design_case_factor: line.design_case_factor,
            safety_class: line.safety_class,
            load_factor_functional: line.load_factor_functional,
            load_factor_environmental: line.load_factor_environmental,
            material_resistance_factor: line.material_resistance_factor,
        }
    }
}

/// Properties of a bare line (no modules): with contents, their mass
/// ρ_i π d_i²/4 is the line's too (docs/theory.md §12.4).
pub fn bare_properties(line: &Line) -> LineProperties {
    let d = line.outer_diameter;
    let area = std::f64::consts::PI * d * d / 4.0;
    let contents = match (line.internal_fluid_density, line.bore_diameter()) {
        (Some(rho), Some(bore)) => Some(rho * std::f64::consts::PI * bore * bore / 4.0),
        _ => None,
    };
    LineProperties {
        // (a line without contents keeps its mass exactly)
        mass_per_length: contents.map_or(line.mass_per_length, |m| line.mass_per_length + m),
        displaced_area: area,
        added_mass_area: line.ca_normal * area,
        drag_normal: line.cd_normal * d,
        drag_tangential: line.cd_tangential * d,
        diameter: d,
        axial_stiffness: line.axial_stiffness,
        bending_stiffness: line.bending_stiffness,
        torsional_stiffness: line.torsional_stiffness,
        rotary_inertia: line.rotary_inertia.unwrap_or(line.mass_per_length * d * d / 8.0),
        pipe_diameter: d,
        wall: line.wall(),
        yield_stress: line.yield_stress.filter(|y| *y > 0.0),
        tensile_strength: line.tensile_strength.filter(|u| *u > 0.0),
    }
}

/// The equivalent line of a bare line carrying modules (11.1–11.4).
pub fn with_modules(bare: LineProperties, m: &Modules) -> LineProperties {
    let d = bare.diameter;
    let phi = m.length / m.pitch;
    let annulus = std::f64::consts::PI * (m.diameter * m.diameter - d * d) / 4.0;
    let displaced_area = bare.displaced_area + phi * annulus; // (11.2)
    LineProperties {
        mass_per_length: bare.mass_per_length + m.mass / m.pitch, // (11.1)
        displaced_area,
        added_mass_area: bare.added_mass_area + phi * m.ca_normal * annulus, // (11.3)
        drag_normal: bare.drag_normal + phi * m.cd_normal * (m.diameter - d), // (11.4)
        drag_tangential: bare.drag_tangential,
        diameter: (4.0 * displaced_area / std::f64::consts::PI).sqrt(),
        // a module as a thick tube about a transverse axis of the section: (M_m/p)(D_m² + D²)/16  (11.5)
        rotary_inertia: bare.rotary_inertia + m.mass / m.pitch * (m.diameter * m.diameter + d * d) / 16.0,
        ..bare
    }
}

impl Scene {
    /// The line as pieces from the hang-off down: one piece of `[line]`
    /// without sections, else one per section (the last one ends at
    /// `line.length` exactly).
    pub fn pieces(&self) -> Vec<Piece> {
        if self.section.is_empty() {
            return vec![Piece { start: 0.0, end: self.line.length, properties: bare_properties(&self.line) }];
        }
        let mut start = 0.0;
        let n = self.section.len();
        self.section
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let bare = bare_properties(&s.bare_line(&self.line));
                let properties = match s.modules() {
                    Some(m) => with_modules(bare, &m),
                    None => bare,
                };
                let end = if i + 1 == n { self.line.length } else { start + s.length };
                let p = Piece { start, end, properties };
                start = end;
                p
            })
            .collect()
    }

    /// The joints between sections where EA changes by more than 5 %:
    /// (arc length from the hang-off, m; ratio of the larger EA to the
    /// smaller). The rod's tension in the two elements either side of such a
    /// joint is approximate (docs/theory.md §11); the cable's is not.
    pub fn axial_stiffness_jumps(&self) -> Vec<(f64, f64)> {
        self.pieces()
            .windows(2)
            .filter_map(|w| {
                let (a, b) = (w[0].properties.axial_stiffness, w[1].properties.axial_stiffness);
                let ratio = a.max(b) / a.min(b);
                (ratio > 1.05).then_some((w[0].end, ratio))
            })
            .collect()
    }

    /// The warning for [`Scene::axial_stiffness_jumps`] with the rod model, if any.
    pub fn axial_stiffness_jump_warning(&self) -> Option<String> {
        let jumps = self.axial_stiffness_jumps();
        if self.analysis.model != super::Model::Rod || jumps.is_empty() {
            return None;
        }
        let list: Vec<String> = jumps.iter().map(|(s, r)| format!("S = {s} m ({r:.3}x)")).collect();
        Some(format!(
            "EA changes between sections at {}: the rod's tension in the two elements either side of such a joint is \
             approximate (docs/theory.md section 11); the cable model is exact there",
            list.join(", ")
        ))
    }
}

/// The properties of the element [a, b] of a line made of `pieces`: the
/// length-weighted mean of the quantities per length (mass, areas, drag,
/// rotary inertia; they add along the line) and the harmonic mean of the
/// stiffnesses (compliances add in series), so that an element straddling a
/// section boundary has the mass, weight and axial compliance of what it
/// covers (docs/theory.md §11). An element inside one piece gets its values.
pub fn element_properties(pieces: &[Piece], a: f64, b: f64) -> LineProperties {
    let h = b - a;
    // (overlaps below 1e-9 of the element are round-off of a boundary on a node)
    let mut inside: Vec<(f64, &LineProperties)> = pieces
        .iter()
        .filter_map(|p| {
            let w = (p.end.min(b) - p.start.max(a)).max(0.0) / h;
            (w > 1e-9).then_some((w, &p.properties))
        })
        .collect();
    let total: f64 = inside.iter().map(|(w, _)| w).sum();
    inside.iter_mut().for_each(|(w, _)| *w /= total);
    if inside.len() == 1 {
        return *inside[0].1;
    }
    if inside.is_empty() {
        // round-off past the last piece's end
        return pieces.last().expect("a line has at least one piece").properties;
    }
    let mean = |f: fn(&LineProperties) -> f64| inside.iter().map(|(w, p)| w * f(p)).sum::<f64>();
    let harmonic = |f: fn(&LineProperties) -> f64| 1.0 / inside.iter().map(|(w, p)| w / f(p)).sum::<f64>();
    let displaced_area = mean(|p| p.displaced_area);
    // the wall of the piece that covers most of the element (the first of equals)
    let dominant = inside.iter().fold(inside[0], |m, v| if v.0 > m.0 { *v } else { m }).1;
    LineProperties {
        mass_per_length: mean(|p| p.mass_per_length),
        displaced_area,
        added_mass_area: mean(|p| p.added_mass_area),
        drag_normal: mean(|p| p.drag_normal),
        drag_tangential: mean(|p| p.drag_tangential),
        diameter: (4.0 * displaced_area / std::f64::consts::PI).sqrt(),
        axial_stiffness: harmonic(|p| p.axial_stiffness),
        bending_stiffness: harmonic(|p| p.bending_stiffness),
        torsional_stiffness: harmonic(|p| p.torsional_stiffness),
        rotary_inertia: mean(|p| p.rotary_inertia),
        pipe_diameter: mean(|p| p.pipe_diameter),
        wall: dominant.wall,
        yield_stress: dominant.yield_stress,
        tensile_strength: dominant.tensile_strength,
    }
}

/// The properties of each of `n_el` equal elements of a line of `length` m.
pub fn per_element(pieces: &[Piece], length: f64, n_el: usize) -> Vec<LineProperties> {
    let h = length / n_el as f64;
    (0..n_el).map(|e| element_properties(pieces, e as f64 * h, (e + 1) as f64 * h)).collect()
}
