//! Overrides by the FMU's parameter names (docs/interface.md) (`--set name=value` on the
//! command line, parameters of the FMU).

use super::waves::{START_GAMMA, START_PERIOD, SpacingSpec, StretchingSpec, WaveKind, WavesSpec, read_table};
use super::{
    Buoyancy, DESIGN_MOTION_AMPLITUDE, DESIGN_MOTION_PERIOD, Model, NO_SEABED_Z, ProfileKind, Scene, SceneError,
    SeabedSpec, ranges,
};

/// Every parameter name that can be set, with its unit.
pub const PARAMETER_NAMES: [(&str, &str); 71] = [
    ("model", "rod | cable"),
    ("hang_off_end", "pinned | clamped | flex_joint"),
    ("flex_joint_stiffness", "N m/rad"),
    ("n_elements", "-"),
    ("time_step", "s"),
    ("newton_tolerance", "-"),
    ("static_current", "true | false"),
    ("structural_damping", "s"),
    ("rho_infinity", "-"),
    ("length", "m"),
    ("mass_per_length", "kg/m"),
    ("outer_diameter", "m"),
    ("axial_stiffness", "N"),
    ("bending_stiffness", "N m^2"),
    ("torsional_stiffness", "N m^2"),
    ("cd_normal", "-"),
    ("cd_tangential", "-"),
    ("ca_normal", "-"),
    ("rotary_inertia", "kg m"),
    ("water_density", "kg/m^3"),
    ("water_surface_z", "m"),
    ("gravity", "m/s^2"),
    ("anchor_x", "m"),
    ("anchor_y", "m"),
    ("anchor_z", "m"),
    ("current_top", "m/s"),
    ("current_bottom", "m/s"),
    ("current_direction", "deg from +x"),
    ("current_ramp", "s"),
    ("buoyancy_load", "N/m"),
    ("buoyancy_start", "m"),
    ("buoyancy_end", "m"),
    ("seabed_z", "m"),
    ("seabed_stiffness", "Pa/m"),
    ("seabed_damping", "Pa s/m"),
    ("seabed_friction", "-"),
    ("wave_kind", "none | airy | jonswap | pierson_moskowitz | table"),
    ("wave_height", "m"),
    ("wave_period", "s"),
    ("wave_direction", "deg from +x"),
    ("wave_phase", "deg"),
    ("wave_hs", "m"),
    ("wave_tp", "s"),
    ("wave_gamma", "-"),
    ("wave_components", "-"),
    ("wave_seed", "-"),
    ("wave_file", "path"),
    ("wave_stretching", "wheeler | vertical | none"),
    ("wave_spacing", "frequency | energy"),
    ("wave_ramp", "s"),
    ("water_depth", "m"),
    ("hang_off_x", "m"),
    ("hang_off_y", "m"),
    ("hang_off_z", "m"),
    ("rotation_order", "zyx | xyz"),
    ("accuracy", "-"),
    ("accuracy_motion_amplitude", "m"),
    ("accuracy_motion_period", "s"),
    ("accuracy_quantity", "top_tension | stress_range | touchdown | fatigue | all"),
    ("steel_outer_diameter", "m"),
    ("wall_thickness", "m"),
    ("youngs_modulus", "Pa"),
    ("yield_stress", "Pa"),
    ("internal_fluid_density", "kg/m^3"),
    ("internal_pressure", "Pa"),
    ("design_case_factor", "-"),
    ("tensile_strength", "Pa"),
    ("safety_class", "none | low | normal | high"),
    ("load_factor_functional", "-"),
    ("load_factor_environmental", "-"),
    ("material_resistance_factor", "-"),
];

/// The seabed the `seabed_*` parameters act on: a scene without one gets a
/// flat seabed at [`NO_SEABED_Z`] (below every line) with the default
/// contact law, so that the parameters need no order.
fn seabed(s: &mut Scene) -> &mut SeabedSpec {
    s.seabed.get_or_insert_with(|| SeabedSpec::flat(NO_SEABED_Z))
}

/// The value of a numeric parameter, checked against its range (ranges.rs).
fn number(name: &str, value: &str) -> Result<f64, SceneError> {
    let v = value
        .parse::<f64>()
        .map_err(|_| SceneError::Override { name: name.to_string(), message: format!("'{value}' is not a number") })?;
    in_range(name, v)
}

fn in_range(name: &str, v: f64) -> Result<f64, SceneError> {
    match ranges::of_parameter(name).map(|r| r.check(v)) {
        Some(Err(message)) => Err(SceneError::Override { name: name.to_string(), message }),
        _ => Ok(v),
    }
}

/// The single buoyancy section the `buoyancy_*` parameters act on (created
/// spanning the whole line with zero load if the scene has none).
fn buoyancy_section<'a>(s: &'a mut Scene, name: &str) -> Result<&'a mut Buoyancy, SceneError> {
    if s.buoyancy.len() > 1 {
        return Err(SceneError::Override {
            name: name.to_string(),
            message: format!(
                "the scene has {} buoyancy sections; buoyancy_* parameters need at most one",
                s.buoyancy.len()
            ),
        });
    }
    if s.buoyancy.is_empty() {
        s.buoyancy.push(Buoyancy { start: 0.0, end: s.line.length, load: 0.0 });
    }
    Ok(&mut s.buoyancy[0])
}

/// A uniform profile becomes linear in S when one end is set; a table cannot
/// take `current_top`/`current_bottom`.
fn current_end(s: &mut Scene, name: &str, v: f64, top: bool) -> Result<(), SceneError> {
    let c = &mut s.current;
    match c.profile {
        ProfileKind::None | ProfileKind::Uniform => {
            let u = c.speed.unwrap_or(0.0);
            c.profile = ProfileKind::LinearS;
            c.top = Some(u);
            c.bottom = Some(u);
            c.speed = None;
        }
        ProfileKind::LinearS | ProfileKind::LinearDepth => {}
        ProfileKind::Table => {
            return Err(SceneError::Override {
                name: name.to_string(),
                message: "the scene's current is a table; current_top/current_bottom apply to uniform or linear \
                          profiles"
                    .to_string(),
            });
        }
    }
    if top {
        c.top = Some(v);
    } else {
        c.bottom = Some(v);
    }
    Ok(())
}

pub(super) fn set(s: &mut Scene, name: &str, value: &str) -> Result<(), SceneError> {
    if let Some(r) = set_wave(s, name, value) {
        return r;
    }
    let num = || number(name, value);
    match name {
        "model" => {
            s.analysis.model = match value {
                "rod" => Model::Rod,
                "cable" => Model::Cable,
                _ => {
                    return Err(SceneError::Override {
                        name: name.into(),
                        message: format!("'{value}' is not a model: rod or cable"),
                    });
                }
            }
        }
        "hang_off_end" => {
            s.hang_off.end = match value {
                "pinned" => super::HangOffEnd::Pinned,
                "clamped" => super::HangOffEnd::Clamped,
                "flex_joint" => super::HangOffEnd::FlexJoint,
                _ => {
                    return Err(SceneError::Override {
                        name: name.into(),
                        message: format!("'{value}' is not an end condition: pinned, clamped or flex_joint"),
                    });
                }
            }
        }
        "flex_joint_stiffness" => {
            // a linear joint replaces a table
            s.hang_off.stiffness = Some(num()?);
            s.hang_off.table = None;
        }
        "rotation_order" => {
            s.hang_off.rotation_order = match value {
                "zyx" => super::RotationOrderSpec::Zyx,
                "xyz" => super::RotationOrderSpec::Xyz,
                _ => {
                    return Err(SceneError::Override {
                        name: name.into(),
                        message: format!(
                            "'{value}' is not a rotation order: zyx (R = Rz(yaw) Ry(pitch) Rx(roll), the marine \
                             convention) or xyz (R = Rx Ry Rz, MoorDyn's and OpenFAST's)"
                        ),
                    });
                }
            }
        }
        "hang_off_x" => s.hang_off.offset[0] = num()?,
        "hang_off_y" => s.hang_off.offset[1] = num()?,
        "hang_off_z" => s.hang_off.offset[2] = num()?,
        "n_elements" => {
            let n = value.parse::<usize>().map_err(|_| SceneError::Override {
                name: name.into(),
                message: format!("'{value}' is not a whole number of elements >= 2"),
            })?;
            in_range(name, n as f64)?;
            s.analysis.n_elements = n;
        }
        "time_step" => s.analysis.time_step = num()?,
        "newton_tolerance" => s.analysis.newton_tolerance = num()?,
        "structural_damping" => s.analysis.structural_damping = num()?,
        "rho_infinity" => s.analysis.rho_infinity = num()?,
        "accuracy" => s.analysis.accuracy = num()?,
        "accuracy_motion_amplitude" => s.analysis.accuracy_motion_amplitude = Some(num()?),
        "accuracy_motion_period" => s.analysis.accuracy_motion_period = Some(num()?),
        "accuracy_quantity" => {
            s.analysis.accuracy_quantity = super::AccuracyQuantity::parse(value)
                .map_err(|message| SceneError::Override { name: name.into(), message })?
        }
        "static_current" => {
            s.analysis.static_current = match value {
                "true" | "1" => true,
                "false" | "0" => false,
                _ => {
                    return Err(SceneError::Override {
                        name: name.into(),
                        message: format!("'{value}' is not a boolean: true or false"),
                    });
                }
            }
        }
        "length" => s.line.length = num()?,
        "mass_per_length" => s.line.mass_per_length = num()?,
        "outer_diameter" => s.line.outer_diameter = num()?,
        "axial_stiffness" => s.line.axial_stiffness = num()?,
        "bending_stiffness" => s.line.bending_stiffness = num()?,
        "torsional_stiffness" => s.line.torsional_stiffness = num()?,
        "cd_normal" => s.line.cd_normal = num()?,
        "cd_tangential" => s.line.cd_tangential = num()?,
        "ca_normal" => s.line.ca_normal = num()?,
        "rotary_inertia" => s.line.rotary_inertia = Some(num()?),
        "steel_outer_diameter" => s.line.steel_outer_diameter = Some(num()?),
        "wall_thickness" => s.line.wall_thickness = Some(num()?),
        "youngs_modulus" => s.line.youngs_modulus = Some(num()?),
        "yield_stress" => s.line.yield_stress = Some(num()?),
        "internal_fluid_density" => s.line.internal_fluid_density = Some(num()?),
        "internal_pressure" => s.line.internal_pressure = Some(num()?),
        "design_case_factor" => s.line.design_case_factor = Some(num()?),
        "tensile_strength" => s.line.tensile_strength = Some(num()?),
        "safety_class" => {
            s.line.safety_class = super::SafetyClass::parse(value)
                .map_err(|message| SceneError::Override { name: name.into(), message })?
        }
        "load_factor_functional" => s.line.load_factor_functional = Some(num()?),
        "load_factor_environmental" => s.line.load_factor_environmental = Some(num()?),
        "material_resistance_factor" => s.line.material_resistance_factor = Some(num()?),
        "water_density" => s.environment.water_density = num()?,
        "water_surface_z" => s.environment.water_surface_z = num()?,
        "gravity" => s.environment.gravity = num()?,
        "anchor_x" => s.anchor.x = num()?,
        "anchor_y" => s.anchor.y = num()?,
        "anchor_z" => s.anchor.z = num()?,
        "current_top" => current_end(s, name, num()?, true)?,
        "current_bottom" => current_end(s, name, num()?, false)?,
        "current_direction" => {
            let deg = num()?;
            s.current.direction = [deg.to_radians().cos(), deg.to_radians().sin()];
        }
        "current_ramp" => s.current.ramp = Some(num()?),
        "buoyancy_load" => buoyancy_section(s, name)?.load = num()?,
        "buoyancy_start" => buoyancy_section(s, name)?.start = num()?,
        "buoyancy_end" => buoyancy_section(s, name)?.end = num()?,
        "seabed_z" => seabed(s).z = num()?,
        "seabed_stiffness" => seabed(s).stiffness = num()?,
        "seabed_damping" => seabed(s).damping = num()?,
        "seabed_friction" => {
            let mu = num()?;
            let b = seabed(s);
            (b.friction, b.friction_axial, b.friction_lateral) = (mu, None, None);
        }
        _ => {
            return Err(SceneError::Override {
                name: name.into(),
                message: format!(
                    "unknown parameter{}; known: {}",
                    closest(name, PARAMETER_NAMES.iter().map(|p| p.0))
                        .map_or(String::new(), |c| format!(" (did you mean {c}?)")),
                    PARAMETER_NAMES.iter().map(|p| p.0).collect::<Vec<_>>().join(", ")
                ),
            });
        }
    }
    Ok(())
}

/// The scene's value of a parameter as `--set` would write it (`None` for an
/// unknown name, or where the scene has no single value: a current table's
/// ends, several buoyancy sections).
pub(super) fn get(s: &Scene, name: &str) -> Option<String> {
    if let Some(v) = get_wave(s, name) {
        return Some(v);
    }
    let num = |v: f64| Some(format!("{v}"));
    let c = &s.current;
    let end = |top: bool| match c.profile {
        ProfileKind::None => num(0.0),
        ProfileKind::Uniform => c.speed.and_then(num),
        ProfileKind::LinearS | ProfileKind::LinearDepth => (if top { c.top } else { c.bottom }).and_then(num),
        // several values: the table's shallowest and deepest rows (multi_valued)
        ProfileKind::Table => table_ends(c.table.as_deref()).and_then(|(a, b)| num(if top { a[1] } else { b[1] })),
    };
    // several sections: the first's (multi_valued)
    let section = |f: fn(&Buoyancy) -> f64| s.buoyancy.first().map_or(num(0.0), |b| num(f(b)));
    match name {
        "model" => Some(match s.analysis.model {
            Model::Rod => "rod".into(),
            Model::Cable => "cable".into(),
        }),
        "hang_off_end" => Some(s.hang_off.end.name().into()),
        // 0 where no joint is given (the FMU's start value); a table's first
        // segment's slope (multi_valued)
        "flex_joint_stiffness" => match (&s.hang_off.table, s.hang_off.stiffness) {
            (Some(t), _) => t.get(1).and_then(|r| num(r[1] / r[0])),
            (None, k) => num(k.unwrap_or(0.0)),
        },
        "rotation_order" => Some(s.hang_off.rotation_order.name().into()),
        "hang_off_x" => num(s.hang_off.offset[0]),
        "hang_off_y" => num(s.hang_off.offset[1]),
        "hang_off_z" => num(s.hang_off.offset[2]),
        "n_elements" => Some(s.analysis.n_elements.to_string()),
        "time_step" => num(s.analysis.time_step),
        "newton_tolerance" => num(s.analysis.newton_tolerance),
        "static_current" => Some(s.analysis.static_current.to_string()),
        "structural_damping" => num(s.analysis.structural_damping),
        "rho_infinity" => num(s.analysis.rho_infinity),
        "accuracy" => num(s.analysis.accuracy),
        // unset: the design motion's (the FMU's start values)
        "accuracy_motion_amplitude" => num(s.analysis.accuracy_motion_amplitude.unwrap_or(DESIGN_MOTION_AMPLITUDE)),
        "accuracy_motion_period" => num(s.analysis.accuracy_motion_period.unwrap_or(DESIGN_MOTION_PERIOD)),
        "accuracy_quantity" => Some(s.analysis.accuracy_quantity.name().into()),
        "length" => num(s.line.length),
        "mass_per_length" => num(s.line.mass_per_length),
        "outer_diameter" => num(s.line.outer_diameter),
        "axial_stiffness" => num(s.line.axial_stiffness),
        "bending_stiffness" => num(s.line.bending_stiffness),
        "torsional_stiffness" => num(s.line.torsional_stiffness),
        "cd_normal" => num(s.line.cd_normal),
        "cd_tangential" => num(s.line.cd_tangential),
        "ca_normal" => num(s.line.ca_normal),
        "rotary_inertia" => num(s.rotary_inertia()),
        // unset: the defaults (the FMU's start values; 0: none given)
        "steel_outer_diameter" => num(s.line.steel_outer_diameter.unwrap_or(s.line.outer_diameter)),
        "wall_thickness" => num(s.line.wall_thickness.unwrap_or(0.0)),
        "youngs_modulus" => num(s.line.youngs_modulus.unwrap_or(super::sections::DEFAULT_YOUNGS_MODULUS)),
        "yield_stress" => num(s.line.yield_stress.unwrap_or(0.0)),
        "internal_fluid_density" => num(s.line.internal_fluid_density.unwrap_or(0.0)),
        "internal_pressure" => num(s.line.internal_pressure.unwrap_or(0.0)),
        "design_case_factor" => num(s.line.design_case_factor.unwrap_or(1.0)),
        "tensile_strength" => num(s.line.tensile_strength.unwrap_or(0.0)),
        "safety_class" => Some(s.line.safety_class.map_or("none", |c| c.name()).into()),
        "load_factor_functional" => num(s.line.load_factor_functional.unwrap_or(super::FUNCTIONAL_LOAD_FACTOR)),
        "load_factor_environmental" => {
            num(s.line.load_factor_environmental.unwrap_or(super::ENVIRONMENTAL_LOAD_FACTOR))
        }
        "material_resistance_factor" => {
            num(s.line.material_resistance_factor.unwrap_or(super::MATERIAL_RESISTANCE_FACTOR))
        }
        "water_density" => num(s.environment.water_density),
        "water_surface_z" => num(s.environment.water_surface_z),
        "gravity" => num(s.environment.gravity),
        "anchor_x" => num(s.anchor.x),
        "anchor_y" => num(s.anchor.y),
        "anchor_z" => num(s.anchor.z),
        "current_top" => end(true),
        "current_bottom" => end(false),
        "current_direction" => num(c.direction[1].atan2(c.direction[0]).to_degrees()),
        "current_ramp" => num(c.ramp.unwrap_or(super::DEFAULT_CURRENT_RAMP)),
        "buoyancy_load" => section(|b| b.load),
        "buoyancy_start" => section(|b| b.start),
        "buoyancy_end" => section(|b| b.end),
        "seabed_z" => num(s.seabed.as_ref().map_or(NO_SEABED_Z, |b| b.z)),
        "seabed_stiffness" => num(s.seabed.as_ref().map_or(super::DEFAULT_SEABED_STIFFNESS, |b| b.stiffness)),
        "seabed_damping" => num(s.seabed.as_ref().map_or(super::DEFAULT_SEABED_DAMPING, |b| b.damping)),
        "seabed_friction" => match &s.seabed {
            None => num(0.0),
            Some(b) => {
                // axial and lateral apart: the axial (multi_valued)
                let [a, _] = b.friction_coefficients();
                num(a)
            }
        },
        _ => None,
    }
}

/// A current table's shallowest and deepest rows [depth m, speed m/s].
fn table_ends(rows: Option<&[[f64; 2]]>) -> Option<([f64; 2], [f64; 2])> {
    let rows = rows?;
    let top = rows.iter().copied().min_by(|a, b| a[0].total_cmp(&b[0]))?;
    let bottom = rows.iter().copied().max_by(|a, b| a[0].total_cmp(&b[0]))?;
    Some((top, bottom))
}

/// Where the scene holds a parameter as more than one value, what [`get`]
/// reads and what else the scene holds (None: one value). The rules
/// (docs/guide/fmu.md, "Parameters a scene holds as several values"): a
/// current table's `current_top`/`current_bottom` are its shallowest and
/// deepest rows' speeds; several buoyancy sections read as the first's
/// `buoyancy_*`; a flex joint's table reads as its first segment's slope;
/// axial and lateral seabed friction apart read as the axial coefficient.
pub(super) fn multi_valued(s: &Scene, name: &str) -> Option<String> {
    match name {
        "current_top" | "current_bottom" if s.current.profile == ProfileKind::Table => {
            let rows = s.current.table.as_deref().unwrap_or(&[]);
            let (top, bottom) = table_ends(Some(rows))?;
            let (which, row) = if name == "current_top" { ("shallowest", top) } else { ("deepest", bottom) };
            Some(format!(
                "{name} reads {} m/s: the scene's current is a table of {} rows (depth, speed); this is its {which} \
                 row's speed (at {} m)",
                row[1],
                rows.len(),
                row[0]
            ))
        }
        "buoyancy_load" | "buoyancy_start" | "buoyancy_end" if s.buoyancy.len() > 1 => {
            let b = &s.buoyancy[0];
            let value = match name {
                "buoyancy_load" => b.load,
                "buoyancy_start" => b.start,
                _ => b.end,
            };
            Some(format!(
                "{name} reads {value}: the scene has {} buoyancy sections; this is the first's (S {} to {} m, {} \
                 N/m)",
                s.buoyancy.len(),
                b.start,
                b.end,
                b.load
            ))
        }
        "flex_joint_stiffness" => {
            let t = s.hang_off.table.as_ref()?;
            let r = t.get(1)?;
            Some(format!(
                "flex_joint_stiffness reads {} N m/rad: the scene's flex joint is a table of {} rows (angle, \
                 moment); this is its first segment's slope, to {} rad",
                r[1] / r[0],
                t.len(),
                r[0]
            ))
        }
        "seabed_friction" => {
            let [a, l] = s.seabed.as_ref()?.friction_coefficients();
            (a != l).then(|| {
                format!(
                    "seabed_friction reads {a}: the scene's seabed has axial friction {a} and lateral {l}; this is \
                     the axial coefficient (setting seabed_friction makes them one)"
                )
            })
        }
        _ => None,
    }
}

fn waves(s: &mut Scene) -> &mut WavesSpec {
    s.waves.get_or_insert_with(WavesSpec::none)
}

/// Sets a wave parameter (None: `name` is not one).
fn set_wave(s: &mut Scene, name: &str, value: &str) -> Option<Result<(), SceneError>> {
    let bad = |message: String| Err(SceneError::Override { name: name.to_string(), message });
    let num = || number(name, value);
    let whole = || -> Result<u64, SceneError> {
        let n = value.parse::<i64>().map_err(|_| SceneError::Override {
            name: name.to_string(),
            message: format!("'{value}' is not a whole number"),
        })?;
        in_range(name, n as f64)?;
        Ok(n.max(0) as u64)
    };
    let r = (|| {
        match name {
            "wave_kind" => match WaveKind::parse(value) {
                Some(WaveKind::None) => s.waves = None,
                Some(k) => waves(s).kind = k,
                None => {
                    return bad(format!(
                        "'{value}' is not a kind of waves: none, airy, jonswap, pierson_moskowitz or table"
                    ));
                }
            },
            "wave_height" => waves(s).height = Some(num()?),
            "wave_period" => waves(s).period = Some(num()?),
            "wave_direction" => waves(s).direction = Some(num()?),
            "wave_phase" => waves(s).phase = Some(num()?),
            "wave_hs" => waves(s).hs = Some(num()?),
            "wave_tp" => waves(s).tp = Some(num()?),
            "wave_gamma" => waves(s).gamma = Some(num()?),
            "wave_components" => waves(s).components = Some(whole()? as usize),
            "wave_seed" => waves(s).seed = Some(whole()?),
            "wave_file" => waves(s).file = if value.is_empty() { None } else { Some(value.to_string()) },
            "wave_stretching" => match StretchingSpec::parse(value) {
                Some(k) => waves(s).stretching = Some(k),
                None => return bad(format!("'{value}' is not a stretching: wheeler, vertical or none")),
            },
            "wave_spacing" => match SpacingSpec::parse(value) {
                Some(k) => waves(s).spacing = Some(k),
                None => return bad(format!("'{value}' is not a spacing: frequency or energy")),
            },
            "wave_ramp" => waves(s).ramp = Some(num()?),
            "water_depth" => {
                let d = num()?;
                waves(s).depth = if d == 0.0 { None } else { Some(d) };
            }
            _ => return Ok(false),
        }
        Ok(true)
    })();
    match r {
        Ok(false) => None,
        Ok(true) => Some(Ok(())),
        Err(e) => Some(Err(e)),
    }
}

/// A wave parameter's value in the scene as `--set` would write it (the
/// FMU's start value where the scene has none; None: not a wave parameter).
fn get_wave(s: &Scene, name: &str) -> Option<String> {
    let w = s.waves.clone().unwrap_or_else(WavesSpec::none);
    let num = |v: f64| Some(format!("{v}"));
    match name {
        "wave_kind" => Some(w.kind.name().to_string()),
        "wave_height" => num(w.height.unwrap_or(0.0)),
        "wave_period" => num(w.period.unwrap_or(START_PERIOD)),
        "wave_direction" => num(w.direction.unwrap_or(0.0)),
        "wave_phase" => num(w.phase.unwrap_or(0.0)),
        "wave_hs" => num(w.hs.unwrap_or(0.0)),
        "wave_tp" => num(w.tp.unwrap_or(START_PERIOD)),
        "wave_gamma" => {
            num(if w.kind == WaveKind::Jonswap { w.gamma_or_default() } else { w.gamma.unwrap_or(START_GAMMA) })
        }
        "wave_components" => Some(w.components_or_default().to_string()),
        "wave_seed" => Some(w.seed.unwrap_or(0).to_string()),
        "wave_file" => Some(w.file.clone().unwrap_or_default()),
        "wave_stretching" => Some(w.stretching.unwrap_or_default().name().to_string()),
        "wave_spacing" => Some(w.spacing.unwrap_or_default().name().to_string()),
        "wave_ramp" => num(w.ramp.unwrap_or(match w.kind {
            WaveKind::Airy => w.period.unwrap_or(START_PERIOD),
            WaveKind::Jonswap | WaveKind::PiersonMoskowitz => w.tp.unwrap_or(START_PERIOD),
            WaveKind::Table => read_table(&w)
                .ok()
                .and_then(|rows| {
                    rows.iter().max_by(|a, b| a.amplitude.total_cmp(&b.amplitude)).map(|r| 1.0 / r.frequency)
                })
                .unwrap_or(START_PERIOD),
            WaveKind::None => START_PERIOD,
        })),
        "water_depth" => num(w.depth.unwrap_or(0.0)),
        _ => None,
    }
}

/// The name of `names` nearest `name` by edit distance (insertions,
/// deletions, substitutions), if within a third of its length (at least 2):
/// the suggestion for a misspelt `--set` name.
fn closest<'a>(name: &str, names: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let a: Vec<char> = name.chars().collect();
    let distance = |b: &str| {
        let b: Vec<char> = b.chars().collect();
        let mut row: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.iter().enumerate() {
            let mut diagonal = row[0];
            row[0] = i + 1;
            for (j, cb) in b.iter().enumerate() {
                let next = (diagonal + usize::from(ca != cb)).min(row[j] + 1).min(row[j + 1] + 1);
                diagonal = row[j + 1];
                row[j + 1] = next;
            }
        }
        row[b.len()]
    };
    let limit = (a.len() / 3).max(2);
    names.map(|n| (distance(n), n)).filter(|(d, _)| *d <= limit).min_by_key(|(d, _)| *d).map(|(_, n)| n)
}

#[cfg(test)]
mod suggestion_tests {
    use super::closest;

    #[test]
    fn a_misspelt_name_gets_the_nearest_known_one_and_a_stranger_none() {
        let names = ["n_elements", "time_step", "wave_hs", "wave_tp", "outer_diameter"];
        assert_eq!(closest("n_elemnts", names.into_iter()), Some("n_elements"));
        assert_eq!(closest("timestep", names.into_iter()), Some("time_step"));
        assert_eq!(closest("wave_Hs", names.into_iter()), Some("wave_hs"));
        assert_eq!(closest("outer_diamter", names.into_iter()), Some("outer_diameter"));
        assert_eq!(closest("gravity_of_mars", names.into_iter()), None);
    }
}
