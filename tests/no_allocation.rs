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

#[test]
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
