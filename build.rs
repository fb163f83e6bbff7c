//! Generates, from the one variable table `modelDescription/variables.csv`,
//! the FMI 2.0 `modelDescription.xml` (with quick-xml) and the Rust table of
//! value references (`$OUT_DIR/variables.rs`), so the two cannot drift apart.
//! The GUID is a hash of the table and the crate version.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use std::fmt::Write as _;
use std::path::PathBuf;

struct Var {
    name: String,
    typ: String,
    causality: String,
    variability: String,
    initial: String,
    start: String,
    unit: String,
    description: String,
}

/// (unit, [kg, m, s]) exponents of the SI base units.
const UNITS: [(&str, [i32; 3]); 16] = [
    ("m", [0, 1, 0]),
    ("Pa", [1, -1, -2]),
    ("m/s", [0, 1, -1]),
    ("m/s2", [0, 1, -2]),
    ("s", [0, 0, 1]),
    ("N", [1, 1, -2]),
    ("J", [1, 2, -2]),
    ("N/m", [1, 0, -2]),
    ("N.m2", [1, 3, -2]),
    ("N.m", [1, 2, -2]),
    ("kg/m", [1, -1, 0]),
    ("kg/m3", [1, -3, 0]),
    ("Pa/m", [1, -2, -2]),
    ("Pa.s/m", [1, -2, -1]),
    ("kg", [1, 0, 0]),
    ("kg.m2", [1, 2, 0]),
];

/// 64-bit FNV-1a with a seed.
fn fnv(data: &[u8], seed: u64) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64 ^ seed;
    for b in data {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn parse(text: &str) -> Vec<Var> {
    let mut vars = Vec::new();
    let mut header_seen = false;
    for (line_no, line) in text.lines().enumerate() {
        let line = line.trim_end();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if !header_seen {
            assert_eq!(
                line, "name;type;causality;variability;initial;start;unit;description",
                "modelDescription/variables.csv: unexpected header"
            );
            header_seen = true;
            continue;
        }
        let f: Vec<&str> = line.split(';').collect();
        assert_eq!(f.len(), 8, "modelDescription/variables.csv line {}: 8 fields expected", line_no + 1);
        vars.push(Var {
            name: f[0].to_string(),
            typ: f[1].to_string(),
            causality: f[2].to_string(),
            variability: f[3].to_string(),
            initial: f[4].to_string(),
            start: f[5].to_string(),
            unit: f[6].to_string(),
            description: f[7].to_string(),
        });
    }
    vars
}

/// The physical ranges (the same file src/scene/ranges.rs includes): the
/// parameters' and inputs' min and max in modelDescription.xml.
#[allow(dead_code)]
mod range_table {
    include!("src/scene/range_table.rs");
}

/// The `[min, max]` of a variable, formatted for the XML (integers plain).
fn variable_range(v: &Var) -> Option<(String, String)> {
    use range_table::*;
    let r = match (v.causality.as_str(), v.name.as_str()) {
        ("input", "heave" | "surge" | "sway") => &INPUT_DISPLACEMENT,
        ("input", "roll" | "pitch" | "yaw") => &INPUT_ANGLE,
        ("input", name) if name.starts_with("angular_velocity") => &INPUT_ANGULAR_VELOCITY,
        ("input", _) => &INPUT_VELOCITY,
        ("parameter", name) => RANGES.iter().find(|r| r.parameter == Some(name))?,
        _ => return None,
    };
    // the numerics' 0: the scene's, or accuracy's choice (docs/theory.md §16.12)
    if matches!(v.name.as_str(), "n_elements" | "time_step" | "newton_tolerance") {
        let f = |x: f64| if v.typ == "Integer" { format!("{}", x as i64) } else { format!("{x:e}") };
        return Some((f(0.0), f(r.max)));
    }
    let f = |x: f64| if v.typ == "Integer" { format!("{}", x as i64) } else { format!("{x:e}") };
    Some((f(r.min), f(r.max)))
}

fn main() {
    let table = "modelDescription/variables.csv";
    println!("cargo:rerun-if-changed={table}");
    println!("cargo:rerun-if-changed=src/scene/range_table.rs");
    println!("cargo:rerun-if-changed=build.rs");
    let text = std::fs::read_to_string(table).expect("read modelDescription/variables.csv");
    let vars = parse(&text);
    let version = std::env::var("CARGO_PKG_VERSION").unwrap();
    let seed_text = format!("{text}\n{version}");
    let (a, b) = (fnv(seed_text.as_bytes(), 1), fnv(seed_text.as_bytes(), 2));
    let guid = format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    );
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap());

    // ---- Rust table ----
    let mut rs = String::new();
    writeln!(rs, "/// GUID of this build's modelDescription.xml.").unwrap();
    writeln!(rs, "pub const GUID: &str = \"{guid}\";").unwrap();
    writeln!(rs, "/// Every variable, indexed by value reference.").unwrap();
    writeln!(rs, "pub const VARIABLES: &[Variable] = &[").unwrap();
    for (vr, v) in vars.iter().enumerate() {
        let kind = match v.typ.as_str() {
            "Real" => "Kind::Real",
            "Integer" => "Kind::Integer",
            "Boolean" => "Kind::Boolean",
            "String" => "Kind::String",
            t => panic!("unknown type {t}"),
        };
        let caus = match v.causality.as_str() {
            "input" => "Causality::Input",
            "output" => "Causality::Output",
            "parameter" => "Causality::Parameter",
            "calculatedParameter" => "Causality::CalculatedParameter",
            c => panic!("unknown causality {c}"),
        };
        writeln!(
            rs,
            "    Variable {{ vr: {vr}, name: {:?}, kind: {kind}, causality: {caus}, start: {:?}, unit: {:?} }},",
            v.name, v.start, v.unit
        )
        .unwrap();
    }
    writeln!(rs, "];").unwrap();
    std::fs::write(out.join("variables.rs"), rs).unwrap();

    // ---- modelDescription.xml ----
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))).unwrap();
    let mut root = BytesStart::new("fmiModelDescription");
    root.push_attribute(("fmiVersion", "2.0"));
    root.push_attribute(("modelName", "riser"));
    root.push_attribute(("guid", guid.as_str()));
    root.push_attribute((
        "description",
        "Nonlinear dynamics of a marine riser, umbilical or cable: Cosserat director rod, energy-momentum \
         conserving time stepping, Morison drag",
    ));
    root.push_attribute(("generationTool", format!("riser {version} build.rs").as_str()));
    root.push_attribute(("version", version.as_str()));
    root.push_attribute(("variableNamingConvention", "structured"));
    root.push_attribute(("numberOfEventIndicators", "0"));
    w.write_event(Event::Start(root)).unwrap();

    let mut cs = BytesStart::new("CoSimulation");
    for (k, v) in [
        ("modelIdentifier", "riser"),
        ("needsExecutionTool", "false"),
        ("canHandleVariableCommunicationStepSize", "true"),
        ("canInterpolateInputs", "true"),
        ("maxOutputDerivativeOrder", "0"),
        ("canRunAsynchronuously", "false"),
        ("canBeInstantiatedOnlyOncePerProcess", "false"),
        ("canNotUseMemoryManagementFunctions", "true"),
        ("canGetAndSetFMUstate", "true"),
        ("canSerializeFMUstate", "true"),
        ("providesDirectionalDerivative", "true"),
    ] {
        cs.push_attribute((k, v));
    }
    w.write_event(Event::Empty(cs)).unwrap();

    w.write_event(Event::Start(BytesStart::new("UnitDefinitions"))).unwrap();
    for (name, [kg, m, s]) in UNITS {
        let mut u = BytesStart::new("Unit");
        u.push_attribute(("name", name));
        w.write_event(Event::Start(u)).unwrap();
        let mut bu = BytesStart::new("BaseUnit");
        for (k, e) in [("kg", kg), ("m", m), ("s", s)] {
            if e != 0 {
                bu.push_attribute((k, e.to_string().as_str()));
            }
        }
        w.write_event(Event::Empty(bu)).unwrap();
        w.write_event(Event::End(BytesEnd::new("Unit"))).unwrap();
    }
    // angles and angular velocities: SI's rad and rad/s, and degrees for display
    for (name, s) in [("rad", 0), ("rad/s", -1)] {
        let mut u = BytesStart::new("Unit");
        u.push_attribute(("name", name));
        w.write_event(Event::Start(u)).unwrap();
        let mut bu = BytesStart::new("BaseUnit");
        if s != 0 {
            bu.push_attribute(("s", s.to_string().as_str()));
        }
        bu.push_attribute(("rad", "1"));
        w.write_event(Event::Empty(bu)).unwrap();
        w.write_event(Event::End(BytesEnd::new("Unit"))).unwrap();
    }
    // an angle: SI's rad, shown in degrees
    let mut u = BytesStart::new("Unit");
    u.push_attribute(("name", "deg"));
    w.write_event(Event::Start(u)).unwrap();
    let mut bu = BytesStart::new("BaseUnit");
    bu.push_attribute(("rad", "1"));
    bu.push_attribute(("factor", "0.017453292519943295"));
    w.write_event(Event::Empty(bu)).unwrap();
    w.write_event(Event::End(BytesEnd::new("Unit"))).unwrap();
    w.write_event(Event::End(BytesEnd::new("UnitDefinitions"))).unwrap();

    w.write_event(Event::Start(BytesStart::new("LogCategories"))).unwrap();
    for (name, desc) in [
        ("logEvents", "initialisation, parameters, state save/restore"),
        ("logStatusWarning", "warnings"),
        ("logStatusDiscard", "discarded steps (Newton failure)"),
        ("logStatusError", "errors"),
        ("logSolver", "Newton iterations and sub-steps"),
        ("logAll", "everything"),
    ] {
        let mut c = BytesStart::new("Category");
        c.push_attribute(("name", name));
        c.push_attribute(("description", desc));
        w.write_event(Event::Empty(c)).unwrap();
    }
    w.write_event(Event::End(BytesEnd::new("LogCategories"))).unwrap();

    let mut de = BytesStart::new("DefaultExperiment");
    de.push_attribute(("startTime", "0"));
    de.push_attribute(("stopTime", "100"));
    de.push_attribute(("stepSize", "0.1"));
    w.write_event(Event::Empty(de)).unwrap();

    w.write_event(Event::Start(BytesStart::new("ModelVariables"))).unwrap();
    for (vr, v) in vars.iter().enumerate() {
        let mut sv = BytesStart::new("ScalarVariable");
        sv.push_attribute(("name", v.name.as_str()));
        sv.push_attribute(("valueReference", vr.to_string().as_str()));
        sv.push_attribute(("description", v.description.as_str()));
        sv.push_attribute(("causality", v.causality.as_str()));
        sv.push_attribute(("variability", v.variability.as_str()));
        if !v.initial.is_empty() {
            sv.push_attribute(("initial", v.initial.as_str()));
        }
        w.write_event(Event::Start(sv)).unwrap();
        let mut t = BytesStart::new(v.typ.as_str());
        if !v.unit.is_empty() {
            t.push_attribute(("unit", v.unit.as_str()));
        }
        if let Some((min, max)) = variable_range(v) {
            t.push_attribute(("min", min.as_str()));
            t.push_attribute(("max", max.as_str()));
        }
        // a parameter always has a start value (an empty String's too)
        if !v.start.is_empty() || v.causality == "parameter" {
            t.push_attribute(("start", v.start.as_str()));
        }
        w.write_event(Event::Empty(t)).unwrap();
        w.write_event(Event::End(BytesEnd::new("ScalarVariable"))).unwrap();
    }
    w.write_event(Event::End(BytesEnd::new("ModelVariables"))).unwrap();

    // ModelStructure (FMI 2.0.5 §2.2.8; issue 52). <Outputs>: dependencies=""
    // ("depends on none of the Knowns"; left out, it meant "on all Knowns":
    // a direct feedthrough, an algebraic loop for any output fed back to an
    // input). No output depends on an input at a communication point: it
    // changes only in fmi2DoStep. <InitialUnknowns>: the knowns of
    // Initialization Mode are the inputs and the variables with
    // initial="exact" (the parameters), and the outputs depend on them all:
    // the statics of the parameters with the hang-off where the inputs put
    // it (docs/theory.md §7.7). fmi2GetDirectionalDerivative's stiffness of
    // the loads against the pose (a slow move, the line in equilibrium, §8.3)
    // is that derivative in Initialization Mode; between steps FMI 2.0's
    // ∂h/∂v_known is zero, as declared: the standard has no rule that the
    // dependencies list the knowns a derivative is asked for, and listing the
    // pose would declare a false feedthrough. There it is an extension, asked
    // by name.
    let outputs: Vec<usize> =
        vars.iter().enumerate().filter(|(_, v)| v.causality == "output").map(|(i, _)| i).collect();
    for &i in &outputs {
        assert_eq!(
            vars[i].initial, "calculated",
            "{}: an output is an initial unknown (initial = calculated)",
            vars[i].name
        );
    }
    let init_knowns: Vec<String> = vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == "input" || v.initial == "exact")
        .map(|(i, _)| (i + 1).to_string())
        .collect();
    let init_knowns = init_knowns.join(" ");
    w.write_event(Event::Start(BytesStart::new("ModelStructure"))).unwrap();
    w.write_event(Event::Start(BytesStart::new("Outputs"))).unwrap();
    for &i in &outputs {
        let mut u = BytesStart::new("Unknown");
        u.push_attribute(("index", (i + 1).to_string().as_str()));
        u.push_attribute(("dependencies", ""));
        w.write_event(Event::Empty(u)).unwrap();
    }
    w.write_event(Event::End(BytesEnd::new("Outputs"))).unwrap();
    // the initial unknowns: the outputs and the calculated parameters, in index order
    let initial_unknowns: Vec<usize> = vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == "output" || v.causality == "calculatedParameter")
        .map(|(i, _)| i)
        .collect();
    w.write_event(Event::Start(BytesStart::new("InitialUnknowns"))).unwrap();
    for &i in &initial_unknowns {
        let mut u = BytesStart::new("Unknown");
        u.push_attribute(("index", (i + 1).to_string().as_str()));
        u.push_attribute(("dependencies", init_knowns.as_str()));
        w.write_event(Event::Empty(u)).unwrap();
    }
    w.write_event(Event::End(BytesEnd::new("InitialUnknowns"))).unwrap();
    w.write_event(Event::End(BytesEnd::new("ModelStructure"))).unwrap();
    w.write_event(Event::End(BytesEnd::new("fmiModelDescription"))).unwrap();
    let xml = String::from_utf8(w.into_inner()).unwrap();
    std::fs::write(out.join("modelDescription.xml"), xml).unwrap();
}
