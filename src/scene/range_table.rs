// The table of physical ranges: data only, no imports, so that build.rs
// includes the same file to write the bounds into modelDescription.xml as
// the variables' min and max (src/scene/ranges.rs explains the table).

/// The closed interval `[min, max]` a scene value must lie in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Dotted path in the scene file, e.g. `line.length`.
    pub field: &'static str,
    /// The FMU parameter and `--set` name, if the value has one.
    pub parameter: Option<&'static str>,
    /// SI unit ("-" for a ratio).
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
    /// Why these bounds.
    pub reason: &'static str,
}

/// Largest |coordinate| of the anchor, the free surface and the hang-off's
/// displacement, m.
pub const MAX_COORDINATE: f64 = 20_000.0;
/// Largest |component| of the hang-off's offset from the vessel's reference point, m.
pub const MAX_HANG_OFF_OFFSET: f64 = 500.0;
/// Largest current speed, m/s.
pub const MAX_CURRENT: f64 = 10.0;
/// Largest number of elements.
pub const MAX_ELEMENTS: f64 = 2000.0;

const LENGTH_REASON: &str = "from a 1 m jumper to the longest umbilicals and moorings (about 20 km)";
const COORD_REASON: &str = "20 km either way: the longest line's reach; vertically, deeper than any ocean";
const OFFSET_REASON: &str =
    "on the hull: the largest vessels are about 460 m long; farther is not a point on a vessel";
const CURRENT_REASON: &str = "the strongest tidal streams reach about 5 m/s";

/// Every range. Scene fields without a parameter name (`current.speed`,
/// `current.depth`, the table's rows, `buoyancy[i].*`) are checked with the
/// entry of their field.
pub const RANGES: &[Range] = &[
    Range {
        field: "line.length",
        parameter: Some("length"),
        unit: "m",
        min: 1.0,
        max: 20_000.0,
        reason: LENGTH_REASON,
    },
    Range {
        field: "line.mass_per_length",
        parameter: Some("mass_per_length"),
        unit: "kg/m",
        min: 0.01,
        max: 1e5,
        reason: "from an optical fibre cable (about 0.1 kg/m) to a hundred times the heaviest chains and \
                 steel pipes (about 1 t/m)",
    },
    Range {
        field: "line.outer_diameter",
        parameter: Some("outer_diameter"),
        unit: "m",
        min: 0.001,
        max: 5.0,
        reason: "Morison's slender-body loads need a diameter small against the length and the waves; the \
                 largest buoyancy-clad risers are about 2 m",
    },
    Range {
        field: "line.axial_stiffness",
        parameter: Some("axial_stiffness"),
        unit: "N",
        min: 1e3,
        max: 1e12,
        reason: "from a thin fibre rope to thirty times a 1 m steel pipe (3e10 N)",
    },
    Range {
        field: "line.bending_stiffness",
        parameter: Some("bending_stiffness"),
        unit: "N m^2",
        min: 0.0,
        max: 1e11,
        reason: "0 for a cable-like rod up to thirty times a 1 m steel pipe (3.5e9 N m^2)",
    },
    Range {
        field: "line.torsional_stiffness",
        parameter: Some("torsional_stiffness"),
        unit: "N m^2",
        min: 0.0,
        max: 1e11,
        reason: "0 up to thirty times a 1 m steel pipe (2.7e9 N m^2)",
    },
    Range {
        field: "line.cd_normal",
        parameter: Some("cd_normal"),
        unit: "-",
        min: 0.0,
        max: 5.0,
        reason: "measured cylinder drag is 0.5-1.2, up to about 2.5 with vortex-induced vibration or strakes",
    },
    Range {
        field: "line.cd_tangential",
        parameter: Some("cd_tangential"),
        unit: "-",
        min: 0.0,
        max: 5.0,
        reason: "skin friction coefficients are 0.01-0.1 on diameter D; bounded like the normal one",
    },
    Range {
        field: "line.ca_normal",
        parameter: Some("ca_normal"),
        unit: "-",
        min: 0.0,
        max: 5.0,
        reason: "a cylinder's potential-flow added mass is 1, near a wall or with modules up to about 2",
    },
    Range {
        field: "line.rotary_inertia",
        parameter: Some("rotary_inertia"),
        unit: "kg m",
        min: 0.0,
        max: 1e5,
        reason: "the default m D^2/8 of a 2 m riser of 2 t/m is 1000 kg m; a hundred times that",
    },
    Range {
        field: "line.steel_outer_diameter",
        parameter: Some("steel_outer_diameter"),
        unit: "m",
        min: 0.001,
        max: 5.0,
        reason: "as the outer diameter: the steel wall is inside it (a coating between)",
    },
    Range {
        field: "line.wall_thickness",
        parameter: Some("wall_thickness"),
        unit: "m",
        min: 0.0,
        max: 0.1,
        reason: "0: no wall given; the thickest riser walls (high-pressure, high-temperature pipe) are about 50 mm",
    },
    Range {
        field: "line.youngs_modulus",
        parameter: Some("youngs_modulus"),
        unit: "Pa",
        min: 1e9,
        max: 5e11,
        reason: "from a polymer pipe's few GPa through titanium (110 GPa) and steel (207 GPa) to about twice steel's",
    },
    Range {
        field: "line.yield_stress",
        parameter: Some("yield_stress"),
        unit: "Pa",
        min: 0.0,
        max: 2e9,
        reason: "0: none given (no code check); line pipe steels run from X42 (290 MPa) to X120 (830 MPa)",
    },
    Range {
        field: "line.internal_fluid_density",
        parameter: Some("internal_fluid_density"),
        unit: "kg/m^3",
        min: 0.0,
        max: 3000.0,
        reason: "from gas through oil and water to drilling muds and brines (up to about 2300 kg/m^3)",
    },
    Range {
        field: "line.internal_pressure",
        parameter: Some("internal_pressure"),
        unit: "Pa",
        min: -101_325.0,
        max: 2e8,
        reason: "gauge pressure: down to a full vacuum; the highest-rated risers take 20 ksi (138 MPa)",
    },
    Range {
        field: "line.design_case_factor",
        parameter: Some("design_case_factor"),
        unit: "-",
        min: 1.0,
        max: 1.5,
        reason: "API RP 2RD's design case factor C_f: 1.0 operating, 1.2 extreme, 1.5 survival or test",
    },
    Range {
        field: "line.tensile_strength",
        parameter: Some("tensile_strength"),
        unit: "Pa",
        min: 0.0,
        max: 2.5e9,
        reason: "0: none given (no DNV-OS-F201 check); line pipe steels run from X42 (414 MPa) to X120 (931 MPa)",
    },
    Range {
        field: "line.load_factor_functional",
        parameter: Some("load_factor_functional"),
        unit: "-",
        min: 1.0,
        max: 2.0,
        reason: "DNV-OS-F201's gamma_F: 1.1 in the ULS, 1.0 in the ALS (a part that reduces the effect takes 1/gamma_F)",
    },
    Range {
        field: "line.load_factor_environmental",
        parameter: Some("load_factor_environmental"),
        unit: "-",
        min: 1.0,
        max: 2.0,
        reason: "DNV-OS-F201's gamma_E: 1.3 in the ULS, 1.0 in the ALS (a part that reduces the effect takes 1/gamma_E)",
    },
    Range {
        field: "line.material_resistance_factor",
        parameter: Some("material_resistance_factor"),
        unit: "-",
        min: 1.0,
        max: 1.5,
        reason: "DNV-OS-F201's gamma_m: 1.15 in the ULS and the ALS, 1.0 in the SLS",
    },
    Range {
        field: "section.length",
        parameter: None,
        unit: "m",
        min: 0.01,
        max: 20_000.0,
        reason: "a section at least a centimetre long (a bend stiffener, a clamp) up to the longest line",
    },
    Range {
        field: "section.module_diameter",
        parameter: None,
        unit: "m",
        min: 0.01,
        max: 5.0,
        reason: "larger than the line it clads; distributed buoyancy modules are about 1-2.5 m",
    },
    Range {
        field: "section.module_length",
        parameter: None,
        unit: "m",
        min: 0.01,
        max: 100.0,
        reason: "a module is typically 1-3 m long; at most its pitch",
    },
    Range {
        field: "section.module_pitch",
        parameter: None,
        unit: "m",
        min: 0.01,
        max: 1000.0,
        reason: "modules every few metres; smeared over the section, so a pitch much longer than the \
                 elements makes the equivalent line a poor model (docs/theory.md 11)",
    },
    Range {
        field: "section.module_mass",
        parameter: None,
        unit: "kg",
        min: 0.0,
        max: 1e5,
        reason: "a syntactic-foam module of 2 m by 2 m is about 3 t; thirty times that",
    },
    Range {
        field: "section.module_cd_normal",
        parameter: None,
        unit: "-",
        min: 0.0,
        max: 10.0,
        reason: "bluff bodies in cross flow are about 1-2; 0 switches the modules' drag off",
    },
    Range {
        field: "section.module_ca_normal",
        parameter: None,
        unit: "-",
        min: 0.0,
        max: 5.0,
        reason: "a cylinder's potential-flow value is 1; 0 switches the modules' added mass off",
    },
    Range {
        field: "environment.water_density",
        parameter: Some("water_density"),
        unit: "kg/m^3",
        min: 0.0,
        max: 2000.0,
        reason: "0 for a line in air, sea water 1025, up to drilling mud",
    },
    Range {
        field: "environment.gravity",
        parameter: Some("gravity"),
        unit: "m/s^2",
        min: 1.0,
        max: 30.0,
        reason: "the statics need a distributed load to define the hanging shape; Earth's 9.81 with room \
                 for test values",
    },
    Range {
        field: "environment.water_surface_z",
        parameter: Some("water_surface_z"),
        unit: "m",
        min: -MAX_COORDINATE,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "hang_off.offset",
        parameter: Some("hang_off_x"),
        unit: "m",
        min: -MAX_HANG_OFF_OFFSET,
        max: MAX_HANG_OFF_OFFSET,
        reason: OFFSET_REASON,
    },
    Range {
        field: "hang_off.offset",
        parameter: Some("hang_off_y"),
        unit: "m",
        min: -MAX_HANG_OFF_OFFSET,
        max: MAX_HANG_OFF_OFFSET,
        reason: OFFSET_REASON,
    },
    Range {
        field: "hang_off.offset",
        parameter: Some("hang_off_z"),
        unit: "m",
        min: -MAX_HANG_OFF_OFFSET,
        max: MAX_HANG_OFF_OFFSET,
        reason: OFFSET_REASON,
    },
    Range {
        field: "hang_off.stiffness",
        parameter: Some("flex_joint_stiffness"),
        unit: "N m/rad",
        min: 0.0,
        max: 1e9,
        reason: "0 (a pinned end) up to far beyond a flex joint's tens of kN m per degree (1.7e6 N m/rad at \
                 30 kN m/deg), where the joint is a clamp for any line",
    },
    Range {
        field: "anchor.x",
        parameter: Some("anchor_x"),
        unit: "m",
        min: -MAX_COORDINATE,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "anchor.y",
        parameter: Some("anchor_y"),
        unit: "m",
        min: -MAX_COORDINATE,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "anchor.z",
        parameter: Some("anchor_z"),
        unit: "m",
        min: -MAX_COORDINATE,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "current.speed",
        parameter: None,
        unit: "m/s",
        min: -MAX_CURRENT,
        max: MAX_CURRENT,
        reason: CURRENT_REASON,
    },
    Range {
        field: "current.top",
        parameter: Some("current_top"),
        unit: "m/s",
        min: -MAX_CURRENT,
        max: MAX_CURRENT,
        reason: CURRENT_REASON,
    },
    Range {
        field: "current.bottom",
        parameter: Some("current_bottom"),
        unit: "m/s",
        min: -MAX_CURRENT,
        max: MAX_CURRENT,
        reason: CURRENT_REASON,
    },
    Range { field: "current.depth", parameter: None, unit: "m", min: 0.01, max: MAX_COORDINATE, reason: COORD_REASON },
    Range {
        field: "current.table.depth",
        parameter: None,
        unit: "m",
        min: 0.0,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "current.table.speed",
        parameter: None,
        unit: "m/s",
        min: -MAX_CURRENT,
        max: MAX_CURRENT,
        reason: CURRENT_REASON,
    },
    Range {
        field: "current.direction",
        parameter: Some("current_direction"),
        unit: "deg",
        min: -360.0,
        max: 360.0,
        reason: "one turn either way from +x",
    },
    Range {
        field: "current.ramp",
        parameter: Some("current_ramp"),
        unit: "s",
        min: 0.0,
        max: 3600.0,
        reason: "the current grows from zero over this time from the run's start; 0 sets it in full at once (the \
                 paper's), an hour is longer than any start needs",
    },
    Range {
        field: "buoyancy.load",
        parameter: Some("buoyancy_load"),
        unit: "N/m",
        min: -1e5,
        max: 1e5,
        reason: "net upward load of the modules (negative: ballast); 1e5 N/m exceeds the buoyancy of a \
                 continuous string of 3 m modules (71 kN/m)",
    },
    Range {
        field: "buoyancy.start",
        parameter: Some("buoyancy_start"),
        unit: "m",
        min: 0.0,
        max: 20_000.0,
        reason: "arc length from the hang-off; within the line (checked against its length too)",
    },
    Range {
        field: "buoyancy.end",
        parameter: Some("buoyancy_end"),
        unit: "m",
        min: 0.0,
        max: 20_000.0,
        reason: "arc length from the hang-off; within the line (checked against its length too)",
    },
    Range {
        field: "seabed.z",
        parameter: Some("seabed_z"),
        unit: "m",
        min: -MAX_COORDINATE,
        max: 0.0,
        reason: "below the hang-off (the origin) and within the deepest ocean; it must not be above the anchor \
                 either (checked against it)",
    },
    Range {
        field: "seabed.slope",
        parameter: None,
        unit: "deg",
        min: -45.0,
        max: 45.0,
        reason: "continental slopes are a few degrees and canyon walls about 30; steeper is a wall, not a seabed",
    },
    Range {
        field: "seabed.stiffness",
        parameter: Some("seabed_stiffness"),
        unit: "Pa/m",
        min: 1e4,
        max: 1e10,
        reason: "from very soft clay (about 1e4 to 1e5 Pa/m) to rock (above 1e8); MoorDyn's default is 3e6",
    },
    Range {
        field: "seabed.damping",
        parameter: Some("seabed_damping"),
        unit: "Pa s/m",
        min: 0.0,
        max: 1e9,
        reason: "0 (none) to far above the critical damping of any line on any soil; MoorDyn's default is 3e5",
    },
    Range {
        field: "seabed.friction",
        parameter: Some("seabed_friction"),
        unit: "-",
        min: 0.0,
        max: 2.0,
        reason: "Coulomb coefficients of pipes and cables on soils and rock are 0.1 to 1.5",
    },
    Range {
        field: "seabed.friction_axial",
        parameter: None,
        unit: "-",
        min: 0.0,
        max: 2.0,
        reason: "Coulomb coefficients of pipes and cables on soils and rock are 0.1 to 1.5",
    },
    Range {
        field: "seabed.friction_lateral",
        parameter: None,
        unit: "-",
        min: 0.0,
        max: 2.0,
        reason: "Coulomb coefficients of pipes and cables on soils and rock are 0.1 to 1.5",
    },
    Range {
        field: "seabed.slip_velocity",
        parameter: None,
        unit: "m/s",
        min: 1e-4,
        max: 1.0,
        reason: "the regularisation of the friction: small against the line's slip speeds, large enough for \
                 Newton (docs/theory.md §9)",
    },
    Range {
        field: "waves.height",
        parameter: Some("wave_height"),
        unit: "m",
        min: 0.0,
        max: 40.0,
        reason: "crest to trough of a regular wave; the highest waves measured are about 30 m",
    },
    Range {
        field: "waves.period",
        parameter: Some("wave_period"),
        unit: "s",
        min: 1.0,
        max: 40.0,
        reason: "from 1 s wind ripples to the longest ocean swell (about 30 s)",
    },
    Range {
        field: "waves.direction",
        parameter: Some("wave_direction"),
        unit: "deg",
        min: -360.0,
        max: 360.0,
        reason: "direction of travel, one turn either way from +x towards +y",
    },
    Range {
        field: "waves.phase",
        parameter: Some("wave_phase"),
        unit: "deg",
        min: -360.0,
        max: 360.0,
        reason: "one turn either way",
    },
    Range {
        field: "waves.hs",
        parameter: Some("wave_hs"),
        unit: "m",
        min: 0.0,
        max: 25.0,
        reason: "significant wave height; the largest measured in storms are about 20 m",
    },
    Range {
        field: "waves.tp",
        parameter: Some("wave_tp"),
        unit: "s",
        min: 1.0,
        max: 40.0,
        reason: "peak period, from short wind seas to the longest ocean swell (about 30 s)",
    },
    Range {
        field: "waves.gamma",
        parameter: Some("wave_gamma"),
        unit: "-",
        min: 1.0,
        max: 10.0,
        reason: "JONSWAP's peak enhancement: measured 1 to 7 (mean 3.3); 1 is Pierson-Moskowitz",
    },
    Range {
        field: "waves.components",
        parameter: Some("wave_components"),
        unit: "-",
        min: 1.0,
        max: 10_000.0,
        reason: "the kinematics cost components x points per evaluation; 10000 components repeat only after \
                 hours",
    },
    Range {
        field: "waves.seed",
        parameter: Some("wave_seed"),
        unit: "-",
        min: 0.0,
        max: 2_147_483_647.0,
        reason: "any seed an FMI Integer holds",
    },
    Range {
        field: "waves.ramp",
        parameter: Some("wave_ramp"),
        unit: "s",
        min: 0.0,
        max: 3600.0,
        reason: "the waves grow from still water over this time; 0 starts them at full height, an hour is \
                 longer than any start needs",
    },
    Range {
        field: "waves.depth",
        parameter: Some("water_depth"),
        unit: "m",
        min: 0.0,
        max: MAX_COORDINATE,
        reason: "0: the seabed's depth, else deep water; within the deepest ocean",
    },
    Range {
        field: "waves.f_min",
        parameter: None,
        unit: "Hz",
        min: 0.001,
        max: 10.0,
        reason: "from 1000 s long waves to 0.1 s ripples",
    },
    Range {
        field: "waves.f_max",
        parameter: None,
        unit: "Hz",
        min: 0.001,
        max: 10.0,
        reason: "from 1000 s long waves to 0.1 s ripples",
    },
    Range {
        field: "waves.origin",
        parameter: None,
        unit: "m",
        min: -MAX_COORDINATE,
        max: MAX_COORDINATE,
        reason: COORD_REASON,
    },
    Range {
        field: "waves.table.frequency",
        parameter: None,
        unit: "Hz",
        min: 0.001,
        max: 10.0,
        reason: "from 1000 s long waves to 0.1 s ripples",
    },
    Range {
        field: "waves.table.amplitude",
        parameter: None,
        unit: "m",
        min: 0.0,
        max: 20.0,
        reason: "half the height of the highest waves measured",
    },
    Range {
        field: "waves.table.phase",
        parameter: None,
        unit: "deg",
        min: -360.0,
        max: 360.0,
        reason: "one turn either way",
    },
    Range {
        field: "waves.table.direction",
        parameter: None,
        unit: "deg",
        min: -360.0,
        max: 360.0,
        reason: "direction of travel, one turn either way from +x towards +y",
    },
    Range {
        field: "analysis.n_elements",
        parameter: Some("n_elements"),
        unit: "-",
        min: 2.0,
        max: MAX_ELEMENTS,
        reason: "two elements are the fewest that bend; the modes and the statics converge long before 2000 \
                 (docs/performance.md), which cost seconds per simulated second",
    },
    Range {
        field: "analysis.time_step",
        parameter: Some("time_step"),
        unit: "s",
        min: 1e-4,
        max: 10.0,
        reason: "0.1 ms resolves the axial waves of short elements; a step above 10 s is longer than sea \
                 waves and resolves nothing",
    },
    Range {
        field: "analysis.newton_tolerance",
        parameter: Some("newton_tolerance"),
        unit: "-",
        min: 1e-14,
        max: 1e-2,
        reason: "relative to the line's weight; below round-off Newton iterates until the residual stops \
                 falling; above 1 % the run is not an equilibrium",
    },
    Range {
        field: "analysis.structural_damping",
        parameter: Some("structural_damping"),
        unit: "s",
        min: 0.0,
        max: 10.0,
        reason: "damping time eta: 10 s critically damps every mode above 0.03 Hz",
    },
    Range {
        field: "analysis.rho_infinity",
        parameter: Some("rho_infinity"),
        unit: "-",
        min: 0.01,
        max: 1.0,
        reason: "the spectral radius at infinite frequency: 1 conserves energy, smaller values damp the \
                 unresolved modes faster (theory 5.10)",
    },
    Range {
        field: "analysis.accuracy",
        parameter: Some("accuracy"),
        unit: "-",
        min: 0.0,
        max: 0.1,
        reason: "relative error accepted in accuracy_quantity (0: unset, the numerics as given); riser measures \
                 it by pilot runs (theory 16.12); above 10 % a run says nothing",
    },
    Range {
        field: "analysis.accuracy_motion_amplitude",
        parameter: Some("accuracy_motion_amplitude"),
        unit: "m",
        min: 0.0,
        max: 100.0,
        reason: "the heave of the design motion the accuracy pilots run where the motion is not known (the FMU, \
                 riser statics; theory 16.12)",
    },
    Range {
        field: "analysis.accuracy_motion_period",
        parameter: Some("accuracy_motion_period"),
        unit: "s",
        min: 0.1,
        max: 1000.0,
        reason: "the period of the design motion's heave (theory 16.12)",
    },
];

/// The hang-off inputs of the FMU (m and m/s): checked when a master sets them.
pub const INPUT_DISPLACEMENT: Range = Range {
    field: "hang-off displacement",
    parameter: None,
    unit: "m",
    min: -MAX_COORDINATE,
    max: MAX_COORDINATE,
    reason: COORD_REASON,
};
/// The hang-off velocity inputs of the FMU, m/s.
pub const INPUT_VELOCITY: Range = Range {
    field: "hang-off velocity",
    parameter: None,
    unit: "m/s",
    min: -100.0,
    max: 100.0,
    reason: "ten times the fastest vessel motion",
};

/// The vessel's angle inputs of the FMU (roll, pitch, yaw), rad: any angle
/// gives a rotation; the bound keeps sin and cos of it exact to 1e-14.
pub const INPUT_ANGLE: Range = Range {
    field: "vessel angle",
    parameter: None,
    unit: "rad",
    min: -100.0,
    max: 100.0,
    reason: "16 turns: the rotation is periodic, and beyond, the angle's round-off grows past 1e-14 rad",
};

/// The vessel's angular velocity inputs of the FMU (vessel frame), rad/s.
pub const INPUT_ANGULAR_VELOCITY: Range = Range {
    field: "vessel angular velocity",
    parameter: None,
    unit: "rad/s",
    min: -10.0,
    max: 10.0,
    reason: "fifty times a vessel's fastest roll rate",
};

/// The hang-off accelerations a master may give as input derivatives, m/s².
pub const INPUT_ACCELERATION: Range = Range {
    field: "hang-off acceleration",
    parameter: None,
    unit: "m/s^2",
    min: -1000.0,
    max: 1000.0,
    reason: "a hundred times gravity",
};
