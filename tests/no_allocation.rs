//! A time step allocates nothing once the integrator is warmed up
//! (workspace preallocated at construction; the contract: nothing is allocated in
//! fmi2DoStep). Counted with a global allocator wrapper in this test binary.

use riser::scene::Scene;
use riser::sim::{Heave, Simulation};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The cases count one global number (a line's or a system's worker threads
/// count too), so they run one after the other in ONE test: with several
/// tests, libtest starts the next test's thread (which allocates) while one
/// of them is counting (5 allocations seen in `make test`, beside rustdoc).
#[test]
fn nothing_allocates_in_a_step() {
    time_steps_do_not_allocate();
    a_systems_do_step_with_free_points_does_not_allocate();
    a_systems_directional_derivative_with_free_points_does_not_allocate();
    a_do_step_with_the_vessel_s_answer_inside_does_not_allocate();
}

fn time_steps_do_not_allocate() {
    let waves = ["wave_kind=jonswap", "wave_hs=6", "wave_tp=10", "wave_components=50", "hang_off_x=20"];
    let cases = [
        ("catenary", "rod", false),
        ("catenary", "cable", false),
        ("catenary", "rod", true),
        ("catenary", "cable", true),
        // the seabed's contact with its touchdown moving through the elements:
        // the rule split at the crossings (docs/theory.md (9.7), (9.8))
        ("steel_catenary", "rod", false),
        ("steel_catenary", "cable", false),
    ];
    for (name, model, sea) in cases {
        // water, damping and a moving hang-off: every term of the step is active
        // (and waves, their kinematics, the surface cut at η: the second round)
        let m = format!("model={model}");
        let mut sets = vec![m.as_str(), "n_elements=20", "ca_normal=1", "structural_damping=0.002"];
        if sea {
            sets.extend(waves);
        }
        let scene = Scene::builtin(name).unwrap().with_overrides(&sets).unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let heave = Heave { amplitude: 2.5, period: 20.0, until: None, ramp: 0.0 };
        let motion = move |t: f64| heave.at(t);
        sim.start(heave.at(0.0));
        let dt = 0.05;
        for k in 1..=20u64 {
            sim.advance_to(k as f64 * dt, &motion).unwrap();
        }
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        for k in 21..=120u64 {
            sim.advance_to(k as f64 * dt, &motion).unwrap();
        }
        let during = ALLOCATIONS.load(Ordering::Relaxed) - before;
        let o = sim.outputs();
        eprintln!(
            "{name}, {model}{}: allocations in 100 steps: {during}; {} Newton iterations",
            if sea { " in waves" } else { "" },
            sim.state.newton_iterations
        );
        assert_eq!(during, 0, "{name}, {model}, waves {sea}");
        assert!(o.top_tension.is_finite());
    }
}

/// The allocations in steps 40 to 139 of `step` on `i`, after 40 steps of
/// warming up.
fn allocations_after_warm_up<T>(i: &mut T, step: impl Fn(&mut T, u64)) -> usize {
    for k in 0..40 {
        step(i, k);
    }
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for k in 40..140 {
        step(i, k);
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

/// fmi2DoStep of a system with a free point (the clump-weight mooring,
/// docs/cases, its chains coarsened) allocates nothing once warmed up: the
/// points' stepper and its lines' trials work in storage allocated at
/// initialisation (docs/theory.md §17.7), the vessel surging and heaving
/// through the inputs.
fn a_systems_do_step_with_free_points_does_not_allocate() {
    use riser::fmi::instance::{Instance, Status, Value};
    use riser::fmi::vars::{GUID, vr_of};
    let text = include_str!("../docs/cases/clump_weight_mooring.toml")
        .replace("n_elements = 60", "n_elements = 20")
        .replace("n_elements = 52", "n_elements = 18");
    let dir = std::env::temp_dir().join(format!("riser-no-allocation-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("clump.toml");
    std::fs::write(&path, text).unwrap();
    let mut i = Instance::new("t", GUID, None, std::sync::Arc::new(|_, _, _: &str| {}), false).unwrap();
    let scene = Value::String(path.to_string_lossy().into_owned());
    assert_eq!(i.set_param(vr_of("scene").unwrap(), scene), Status::Ok);
    i.enter_initialization_mode();
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    let (surge, heave) = (vr_of("surge").unwrap(), vr_of("heave").unwrap());
    let h = 0.05;
    let step = |i: &mut Instance, k: u64| {
        let t = k as f64 * h;
        assert_eq!(i.set_real(surge, 2.0 * (0.3 * t).sin()), Status::Ok);
        assert_eq!(i.set_real(heave, 0.5 * (0.8 * t).sin()), Status::Ok);
        assert_eq!(i.do_step(t, h), Status::Ok, "t = {t} s");
    };
    let during = allocations_after_warm_up(&mut i, step);
    eprintln!("the clump-weight system's fmi2DoStep: allocations in 100 steps: {during}");
    assert_eq!(during, 0);
    std::fs::remove_dir_all(&dir).ok();
}

/// fmi2GetDirectionalDerivative of a system with free points (the
/// clump-weight mooring, the same with a plain chain to a second fairlead,
/// and the hybrid riser tower, docs/cases: chains and rods at the points)
/// allocates nothing after initialisation, from its second call in
/// initialisation mode on (the first makes the static state) and between
/// fmi2DoSteps: each line's static tangent in storage sized when the points
/// are set up (a plain line's at its first call), the points condensed out
/// in place (docs/theory.md (17.19)).
fn a_systems_directional_derivative_with_free_points_does_not_allocate() {
    use riser::fmi::instance::{Instance, Status, Value};
    use riser::fmi::vars::{GUID, vr_of};
    let clump = include_str!("../docs/cases/clump_weight_mooring.toml")
        .replace("n_elements = 60", "n_elements = 20")
        .replace("n_elements = 52", "n_elements = 18");
    // the clump with a plain chain from a second fairlead: its hang-off stiffness too
    let mixed = clump.clone()
        + "\n[[point]]\nname = \"anchor2\"\nkind = \"fixed\"\nposition = [530.0, 0.0, -150.0]\n\
           \n[[point]]\nname = \"fairlead2\"\nkind = \"vessel\"\nposition = [5.0, 0.0, -10.0]\n\
           \n[[line]]\nname = \"plain\"\ntype = \"chain\"\nfrom = \"anchor2\"\nto = \"fairlead2\"\n\
           length = 560.0\nn_elements = 40\n";
    let tower = include_str!("../docs/cases/hybrid_riser_tower.toml").to_string();
    let dir = std::env::temp_dir().join(format!("riser-no-allocation-dd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in [("clump", clump), ("mixed", mixed), ("tower", tower)] {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        let mut i = Instance::new("t", GUID, None, std::sync::Arc::new(|_, _, _: &str| {}), false).unwrap();
        let scene = Value::String(path.to_string_lossy().into_owned());
        assert_eq!(i.set_param(vr_of("scene").unwrap(), scene), Status::Ok);
        i.enter_initialization_mode();
        let unknowns: Vec<u32> = ["top_force_x", "top_force_z", "top_moment_y", "vessel_force_x", "vessel_moment_z"]
            .iter()
            .map(|n| vr_of(n).unwrap())
            .collect();
        let knowns: Vec<u32> = ["surge", "heave", "pitch", "yaw"].iter().map(|n| vr_of(n).unwrap()).collect();
        let seed = [1.0, -0.5, 0.01, 0.02];
        let mut d = [0.0; 5];
        // the static state (the outputs' first call) made before counting
        assert_eq!(i.directional_derivative(&unknowns, &knowns, &seed, &mut d), Status::Ok);
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        assert_eq!(i.directional_derivative(&unknowns, &knowns, &seed, &mut d), Status::Ok);
        let in_initialisation = ALLOCATIONS.load(Ordering::Relaxed) - before;
        assert_eq!(i.exit_initialization_mode(), Status::Ok);
        let (surge, heave) = (vr_of("surge").unwrap(), vr_of("heave").unwrap());
        let h = 0.1;
        let step = |i: &mut Instance, k: u64| {
            let t = k as f64 * h;
            assert_eq!(i.set_real(surge, 2.0 * (0.3 * t).sin()), Status::Ok);
            assert_eq!(i.set_real(heave, 0.5 * (0.8 * t).sin()), Status::Ok);
            assert_eq!(i.do_step(t, h), Status::Ok, "{name}: t = {t} s");
            let mut d = [0.0; 5];
            assert_eq!(i.directional_derivative(&unknowns, &knowns, &seed, &mut d), Status::Ok, "{name}");
            assert!(d.iter().all(|x| x.is_finite() && *x != 0.0), "{name}: {d:?}");
        };
        let during = allocations_after_warm_up(&mut i, step);
        eprintln!(
            "the {name} system's fmi2GetDirectionalDerivative: allocations in initialisation {in_initialisation}, in \
             100 steps with a derivative each {during}"
        );
        assert_eq!(in_initialisation, 0, "{name}");
        assert_eq!(during, 0, "{name}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A single line given the vessel's inertias steps with the vessel's
/// answer inside its steps (docs/theory.md §7.10, `HeldBody`): its body
/// Newton's trial states and condensed tangent are kept by the instance,
/// so fmi2DoStep allocates nothing once warmed up.
fn a_do_step_with_the_vessel_s_answer_inside_does_not_allocate() {
    use riser::fmi::instance::{Instance, Status, Value};
    use riser::fmi::vars::{GUID, vr_of};
    let mut i = Instance::new("t", GUID, None, std::sync::Arc::new(|_, _, _: &str| {}), false).unwrap();
    assert_eq!(i.set_param(vr_of("n_elements").unwrap(), Value::Integer(10)), Status::Ok);
    assert_eq!(i.set_param(vr_of("vessel_mass_heave").unwrap(), Value::Real(2.0e6)), Status::Ok);
    i.enter_initialization_mode();
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    let (heave, heave_velocity) = (vr_of("heave").unwrap(), vr_of("heave_velocity").unwrap());
    let h = 0.1;
    let step = |i: &mut Instance, k: u64| {
        let t = k as f64 * h;
        let w = 2.0 * std::f64::consts::PI / 10.0;
        let ramp = (t / 10.0).min(1.0);
        assert_eq!(i.set_real(heave, 1.0 * ramp * (w * t).sin()), Status::Ok);
        assert_eq!(i.set_real(heave_velocity, 1.0 * ramp * w * (w * t).cos()), Status::Ok);
        assert_eq!(i.do_step(t, h), Status::Ok, "t = {t} s");
    };
    let during = allocations_after_warm_up(&mut i, step);
    eprintln!("fmi2DoStep with the vessel's answer inside (§7.10): allocations in 100 steps: {during}");
    assert_eq!(during, 0);
}
