//! Range checks of every scene value, with the field and the allowed range in
//! each message.

use super::checker::{Checker, FieldError};
use super::{ProfileKind, Scene, ranges};

/// Largest axial strain the anchor distance may demand of the line.
pub const MAX_REACH_STRAIN: f64 = 0.05;

pub(super) fn check(s: &Scene) -> Vec<FieldError> {
    let mut c = Checker(Vec::new());
    let l = &s.line;
    let length_ok = c.range("line.length", l.length);
    c.range("line.mass_per_length", l.mass_per_length);
    c.range("line.outer_diameter", l.outer_diameter);
    c.range("line.axial_stiffness", l.axial_stiffness);
    c.range("line.bending_stiffness", l.bending_stiffness);
    c.range("line.torsional_stiffness", l.torsional_stiffness);
    c.range("line.cd_normal", l.cd_normal);
    c.range("line.cd_tangential", l.cd_tangential);
    c.range("line.ca_normal", l.ca_normal);
    if let Some(j) = l.rotary_inertia {
        c.range("line.rotary_inertia", j);
    }
    let pipe_keys = [
        ("steel_outer_diameter", l.steel_outer_diameter),
        ("wall_thickness", l.wall_thickness),
        ("youngs_modulus", l.youngs_modulus),
        ("yield_stress", l.yield_stress),
        ("internal_fluid_density", l.internal_fluid_density),
        ("internal_pressure", l.internal_pressure),
        ("design_case_factor", l.design_case_factor),
        ("tensile_strength", l.tensile_strength),
        ("load_factor_functional", l.load_factor_functional),
        ("load_factor_environmental", l.load_factor_environmental),
        ("material_resistance_factor", l.material_resistance_factor),
    ];
    let mut pipe_ok = true;
    for (k, v) in pipe_keys {
        if let Some(v) = v {
            pipe_ok &= c.range(&format!("line.{k}"), v);
        }
    }
    if pipe_ok && s.section.is_empty() {
        check_wall(&mut c, l, "line");
    }
    let env = &s.environment;
    c.range("environment.water_density", env.water_density);
    c.range("environment.gravity", env.gravity);
    c.range("environment.water_surface_z", env.water_surface_z);
    for (i, v) in s.hang_off.offset.iter().enumerate() {
        c.range(&format!("hang_off.offset[{i}]"), *v);
    }
    let a = &s.anchor;
    let ok = c.range("anchor.x", a.x) & c.range("anchor.y", a.y) & c.range("anchor.z", a.z);
    if ok && length_ok {
        let dist = (a.x * a.x + a.y * a.y + a.z * a.z).sqrt();
        let reach = l.length * (1.0 + MAX_REACH_STRAIN);
        if dist > reach {
            c.err(
                "anchor",
                format!(
                    "the anchor is {dist:.3} m from the hang-off, farther than the line can reach: \
                     at most {reach:.3} m (length {} m stretched by {}%)",
                    l.length,
                    MAX_REACH_STRAIN * 100.0
                ),
            );
        } else if dist < 1e-3 * l.length {
            c.err(
                "anchor",
                format!(
                    "the anchor is {dist:.3e} m from the hang-off: it must be at least 1e-3 of the length ({} m) \
                     away",
                    1e-3 * l.length
                ),
            );
        }
    }
    let cur = &s.current;
    match cur.profile {
        ProfileKind::None => {}
        ProfileKind::Uniform => c.speed("current.speed", cur.speed),
        ProfileKind::LinearS => {
            c.speed("current.top", cur.top);
            c.speed("current.bottom", cur.bottom);
        }
        ProfileKind::LinearDepth => {
            c.speed("current.top", cur.top);
            c.speed("current.bottom", cur.bottom);
            match cur.depth {
                None => c.err("current.depth", "missing: depth (m) where `bottom` applies".to_string()),
                Some(d) => {
                    c.range("current.depth", d);
                }
            }
        }
        ProfileKind::Table => match &cur.table {
            None => c.err("current.table", "missing: rows [depth m, speed m/s]".to_string()),
            Some(rows) if rows.is_empty() => c.err("current.table", "needs at least one row".to_string()),
            Some(rows) => {
                for (i, r) in rows.iter().enumerate() {
                    c.range(&format!("current.table[{i}].depth"), r[0]);
                    c.range(&format!("current.table[{i}].speed"), r[1]);
                    if i > 0 && r[0] <= rows[i - 1][0] {
                        c.err(&format!("current.table[{i}]"), "depths must increase from row to row".to_string());
                    }
                }
            }
        },
    }
    let [dx, dy] = cur.direction;
    if !(dx.is_finite() && dy.is_finite() && dx.abs() <= 1e6 && dy.abs() <= 1e6) || dx.hypot(dy) < 1e-6 {
        c.err(
            "current.direction",
            format!("[{dx}, {dy}] must be a horizontal vector of length between 1e-6 and 1e6 (it is normalised)"),
        );
    }
    for (i, b) in s.buoyancy.iter().enumerate() {
        let f = |k: &str| format!("buoyancy[{i}].{k}");
        let ok = c.range(&f("start"), b.start) & c.range(&f("end"), b.end);
        c.range(&f("load"), b.load);
        if ok && length_ok {
            if b.start > l.length {
                c.err(&f("start"), format!("{} m is outside the line [0, {}] m", b.start, l.length));
            }
            if b.end > l.length {
                c.err(&f("end"), format!("{} m is outside the line [0, {}] m", b.end, l.length));
            }
            if b.end <= b.start {
                c.err(&f("end"), format!("end {} m must be greater than start {} m", b.end, b.start));
            }
        }
    }
    check_sections(&mut c, s, length_ok);
    if c.0.is_empty() {
        check_lrfd(&mut c, s);
    }
    if let Some(b) = &s.seabed {
        let ok = c.range("seabed.z", b.z) & c.range("seabed.slope", b.slope);
        c.range("seabed.stiffness", b.stiffness);
        c.range("seabed.damping", b.damping);
        c.range("seabed.friction", b.friction);
        if let Some(m) = b.friction_axial {
            c.range("seabed.friction_axial", m);
        }
        if let Some(m) = b.friction_lateral {
            c.range("seabed.friction_lateral", m);
        }
        c.range("seabed.slip_velocity", b.slip_velocity);
        let anchor_ok = [a.x, a.y, a.z].iter().all(|v| v.is_finite());
        if ok && anchor_ok {
            // the hang-off is the origin: above the seabed or on it
            let under_anchor = b.height_at(a.x, a.y);
            if under_anchor > a.z + 1e-9 * a.z.abs().max(1.0) {
                c.err(
                    "seabed.z",
                    format!(
                        "the seabed is at z = {} m under the anchor ({}, {}) m, above the anchor (z = {} m): the \
                         anchor must be on the seabed or above it",
                        ranges::number(under_anchor),
                        a.x,
                        a.y,
                        a.z
                    ),
                );
            }
        }
    }
    let an = &s.analysis;
    c.range("analysis.n_elements", an.n_elements as f64);
    c.range("analysis.time_step", an.time_step);
    c.range("analysis.newton_tolerance", an.newton_tolerance);
    c.range("analysis.structural_damping", an.structural_damping);
    c.range("analysis.rho_infinity", an.rho_infinity);
    c.range("analysis.accuracy", an.accuracy);
    if let Some(a) = an.accuracy_motion_amplitude {
        c.range("analysis.accuracy_motion_amplitude", a);
    }
    if let Some(t) = an.accuracy_motion_period {
        c.range("analysis.accuracy_motion_period", t);
    }
    let end = s.hang_off.end;
    if end != super::HangOffEnd::Pinned && an.model == super::Model::Cable {
        c.err(
            "hang_off.end",
            format!(
                "'{}' needs the rod: the cable model has no rotations (its ends are pinned); use analysis.model = \
                 \"rod\" or hang_off.end = \"pinned\"",
                end.name()
            ),
        );
    }
    check_flex_joint(&mut c, s);
    c.0.extend(super::waves::check(s));
    c.0.extend(super::raos::check(s));
    c.0
}

/// A flex joint's law (docs/theory.md §15): a stiffness in its range or a
/// monotonic table from (0, 0), not both; needed when the end is a flex joint.
fn check_flex_joint(c: &mut Checker, s: &Scene) {
    let h = &s.hang_off;
    if let Some(k) = h.stiffness {
        c.range("hang_off.stiffness", k);
    }
    if let Some(rows) = &h.table
        && let Err(e) = super::check_joint_table(rows)
    {
        c.err("hang_off.table", format!("flex-joint table: {e}"));
    }
    if h.stiffness.is_some() && h.table.is_some() {
        c.err(
            "hang_off.table",
            "a flex joint takes hang_off.stiffness (linear) or hang_off.table (moment against angle), not both"
                .to_string(),
        );
    }
    if h.end == super::HangOffEnd::FlexJoint && h.stiffness.is_none() && h.table.is_none() {
        c.err(
            "hang_off.stiffness",
            "hang_off.end = \"flex_joint\" needs the joint's bending stiffness: hang_off.stiffness (N m/rad; \
             parameter flex_joint_stiffness) or hang_off.table = [[angle rad, moment N m], ...] from [0, 0]"
                .to_string(),
        );
    }
}

/// The wall of a piece of line (`[line]` or a section's, `at` naming it):
/// thinner than its radius, the steel inside the outer diameter, and a bore
/// for the contents when the line has contents (docs/theory.md §12.4).
fn check_wall(c: &mut Checker, l: &super::Line, at: &str) {
    if let Some(w) = l.wall() {
        if 2.0 * w.thickness > w.outer_diameter {
            c.err(
                &format!("{at}.wall_thickness"),
                format!(
                    "{} m is more than the radius of the steel ({} m, steel_outer_diameter / 2): the wall must leave \
                     a bore (or be a solid bar, t = D_s / 2)",
                    w.thickness,
                    w.outer_diameter / 2.0
                ),
            );
        }
        if w.outer_diameter > l.outer_diameter * (1.0 + 1e-9) {
            c.err(
                &format!("{at}.steel_outer_diameter"),
                format!(
                    "{} m is larger than the outer diameter {} m: the steel is inside the outer diameter, which \
                     includes any coating",
                    w.outer_diameter, l.outer_diameter
                ),
            );
        }
    }
    if l.has_contents() && l.bore_diameter().is_none() {
        c.err(
            &format!("{at}.wall_thickness"),
            "the contents (internal_fluid_density, internal_pressure) need the pipe's bore: give the wall \
             (wall_thickness, and steel_outer_diameter if the outer diameter includes a coating); EA, EI and the \
             outer diameter are not those of a homogeneous tube whose bore riser could take"
                .to_string(),
        );
    }
}

/// DNV-OS-F201's LRFD check (docs/theory.md §12.4): asked for by
/// `safety_class`, it needs every piece of line (`[line]`, or each section)
/// to be a tube with a yield stress and a tensile strength; a tensile
/// strength is never below the yield stress. (A tensile strength without a
/// safety class asks for no check: the statics warn of it.)
fn check_lrfd(c: &mut Checker, s: &Scene) {
    let l = &s.line;
    let pieces: Vec<(String, super::Line)> = if s.section.is_empty() {
        vec![("line".to_string(), l.clone())]
    } else {
        s.section.iter().enumerate().map(|(i, sec)| (format!("section[{i}]"), sec.bare_line(l))).collect()
    };
    for (at, p) in &pieces {
        let (fy, fu) = (p.yield_stress.filter(|v| *v > 0.0), p.tensile_strength.filter(|v| *v > 0.0));
        if let (Some(y), Some(u)) = (fy, fu)
            && u < y
        {
            c.err(
                &format!("{at}.tensile_strength"),
                format!("{u} Pa is below the yield stress {y} Pa: the tensile strength (SMTS) is the larger"),
            );
        } else if l.safety_class.is_some() && (fy.is_none() || fu.is_none()) {
            c.err(
                &format!("{at}.{}", if fy.is_none() { "yield_stress" } else { "tensile_strength" }),
                "missing: DNV-OS-F201's LRFD check (safety_class) needs the wall's yield_stress and tensile_strength"
                    .to_string(),
            );
        } else if l.safety_class.is_some() && p.bore_diameter().is_none() {
            c.err(
                &format!("{at}.wall_thickness"),
                "DNV-OS-F201's LRFD check (safety_class) needs the pipe's wall: give wall_thickness (EA, EI and the \
                 outer diameter are not those of a homogeneous tube)"
                    .to_string(),
            );
        }
    }
}

/// Line sections (docs/theory.md §11): each key in its `[line]` range, the
/// modules complete and physical, and the lengths adding up to the line's.
fn check_sections(c: &mut Checker, s: &Scene, length_ok: bool) {
    let mut total = 0.0;
    let mut lengths_ok = true;
    for (i, sec) in s.section.iter().enumerate() {
        let f = |k: &str| format!("section[{i}].{k}");
        lengths_ok &= c.range(&f("length"), sec.length);
        total += sec.length;
        let keys = [
            ("mass_per_length", sec.mass_per_length),
            ("outer_diameter", sec.outer_diameter),
            ("axial_stiffness", sec.axial_stiffness),
            ("bending_stiffness", sec.bending_stiffness),
            ("torsional_stiffness", sec.torsional_stiffness),
            ("cd_normal", sec.cd_normal),
            ("cd_tangential", sec.cd_tangential),
            ("ca_normal", sec.ca_normal),
            ("rotary_inertia", sec.rotary_inertia),
            ("steel_outer_diameter", sec.steel_outer_diameter),
            ("wall_thickness", sec.wall_thickness),
            ("youngs_modulus", sec.youngs_modulus),
            ("yield_stress", sec.yield_stress),
            ("tensile_strength", sec.tensile_strength),
        ];
        if c.optional(&keys, f, |k| format!("line.{k}")) {
            check_wall(c, &sec.bare_line(&s.line), &format!("section[{i}]"));
        }
        let sizes = [
            ("module_diameter", sec.module_diameter),
            ("module_length", sec.module_length),
            ("module_pitch", sec.module_pitch),
            ("module_mass", sec.module_mass),
        ];
        let given = sizes.iter().filter(|(_, v)| v.is_some()).count();
        let mut ok = true;
        for (k, v) in sizes
            .iter()
            .chain(&[("module_cd_normal", sec.module_cd_normal), ("module_ca_normal", sec.module_ca_normal)])
        {
            if let Some(v) = v {
                ok &= c.range(&f(k), *v);
            }
        }
        if given > 0 && given < 4 {
            let missing: Vec<&str> = sizes.iter().filter(|(_, v)| v.is_none()).map(|(k, _)| *k).collect();
            c.err(
                &f(missing[0]),
                format!(
                    "missing: buoyancy modules need module_diameter (m), module_length (m), module_pitch (m) and \
                     module_mass (kg); this section lacks {}",
                    missing.join(", ")
                ),
            );
        } else if given == 0 && (sec.module_cd_normal.is_some() || sec.module_ca_normal.is_some()) {
            let key = if sec.module_cd_normal.is_some() { "module_cd_normal" } else { "module_ca_normal" };
            c.err(
                &f(key),
                "the section has no modules: module_diameter, module_length, module_pitch and module_mass are missing"
                    .to_string(),
            );
        } else if let (Some(m), true) = (sec.modules(), ok) {
            let d = sec.outer_diameter.unwrap_or(s.line.outer_diameter);
            if m.diameter <= d {
                c.err(
                    &f("module_diameter"),
                    format!("{} m must be larger than the line's outer diameter {d} m", m.diameter),
                );
            }
            if m.length > m.pitch {
                c.err(
                    &f("module_length"),
                    format!("{} m is longer than the pitch {} m: modules cannot overlap", m.length, m.pitch),
                );
            }
            if m.pitch > sec.length {
                c.err(
                    &f("module_pitch"),
                    format!(
                        "{} m is longer than the section ({} m): the modules are smeared over their section, which \
                         must hold at least one pitch",
                        m.pitch, sec.length
                    ),
                );
            }
            let line_mass = sec.mass_per_length.unwrap_or(s.line.mass_per_length);
            let with_modules = line_mass + m.mass / m.pitch;
            let range = ranges::of_field("line.mass_per_length").expect("every checked field has a range");
            if range.check(with_modules).is_err() {
                c.err(
                    &f("module_mass"),
                    format!(
                        "the line with its modules weighs {} kg/m (module_mass / module_pitch added), outside the \
                         range of line.mass_per_length {}",
                        ranges::number(with_modules),
                        range.interval()
                    ),
                );
            }
        }
    }
    if !s.section.is_empty() && lengths_ok && length_ok {
        let l = s.line.length;
        if (total - l).abs() > 1e-9 * l {
            let last = s.section.len() - 1;
            c.err(
                &format!("section[{last}].length"),
                format!(
                    "the sections add up to {} m but line.length is {l} m: their lengths must add up to the line's",
                    ranges::number(total)
                ),
            );
        }
    }
}
