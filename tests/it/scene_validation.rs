//! Evidence 7 of the statics issue: bad scene files and bad overrides are
//! rejected with a message naming the field and the allowed range — one test
//! per class of bad input; never a panic.

use riser::scene::{Scene, SceneError};

fn catenary_toml() -> String {
    Scene::builtin("catenary").unwrap().to_toml()
}

fn override_err(sets: &[&str]) -> String {
    match Scene::builtin("catenary").unwrap().with_overrides(sets) {
        Ok(_) => panic!("{sets:?} was accepted"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "message does not mention '{p}':\n{msg}");
    }
}

#[test]
fn built_in_scenes_round_trip_through_toml() {
    for name in ["catenary", "lazy_wave"] {
        let s = Scene::builtin(name).unwrap();
        assert_eq!(Scene::from_toml(&s.to_toml(), name).unwrap(), s);
    }
    let s = Scene::builtin("lazy_wave").unwrap();
    assert_eq!((s.anchor.x, s.anchor.z, s.buoyancy[0].load), (50.0, -40.0, 670.0));
}

#[test]
fn missing_field_is_named() {
    let text = catenary_toml().replace("length = 100.0\n", "");
    let e = Scene::from_toml(&text, "test.toml").unwrap_err();
    assert!(matches!(e, SceneError::Parse { .. }));
    assert_mentions(&e.to_string(), &["test.toml", "length"]);
}

#[test]
fn unknown_field_is_rejected() {
    let text = catenary_toml().replace("length = 100.0\n", "length = 100.0\nlenght = 3.0\n");
    assert_mentions(&Scene::from_toml(&text, "t").unwrap_err().to_string(), &["lenght"]);
}

#[test]
fn non_finite_values_are_rejected() {
    assert_mentions(&override_err(&["axial_stiffness=inf"]), &["--set axial_stiffness", "not a finite number"]);
    assert_mentions(&override_err(&["current_top=NaN"]), &["--set current_top", "not a finite number"]);
    let text = catenary_toml().replace("gravity = 9.81", "gravity = nan");
    assert_mentions(&Scene::from_toml(&text, "t").unwrap_err().to_string(), &["environment.gravity", "finite"]);
}

#[test]
fn negative_length_mass_and_stiffness_are_rejected() {
    assert_mentions(&override_err(&["length=-100"]), &["--set length", "-100 m is outside [1, 20000] m"]);
    assert_mentions(&override_err(&["mass_per_length=0"]), &["--set mass_per_length", "0 kg/m is outside [0.01,"]);
    assert_mentions(&override_err(&["axial_stiffness=-1"]), &["--set axial_stiffness", "-1 N is outside [1000,"]);
    assert_mentions(&override_err(&["bending_stiffness=-5"]), &["--set bending_stiffness", "outside [0, 1e11]"]);
    assert_mentions(&override_err(&["cd_normal=-0.1"]), &["--set cd_normal", "-0.1 is outside [0, 5]"]);
    // every problem is listed, not only the first
    assert_mentions(&override_err(&["length=-1", "outer_diameter=-1"]), &["--set length", "--set outer_diameter"]);
}

#[test]
fn anchor_out_of_reach_is_rejected() {
    let msg = override_err(&["anchor_x=120"]);
    assert_mentions(&msg, &["anchor", "farther than the line can reach", "105.000 m"]);
    assert_mentions(&override_err(&["anchor_x=0", "anchor_z=0"]), &["anchor", "must be at least 1e-3 of the length"]);
}

#[test]
fn buoyancy_outside_the_line_is_rejected() {
    let base = Scene::builtin("lazy_wave").unwrap();
    let e = base.clone().with_overrides(&["buoyancy_end=120"]).unwrap_err().to_string();
    assert_mentions(&e, &["buoyancy[0].end", "outside the line [0, 100] m"]);
    let e = base.clone().with_overrides(&["buoyancy_start=-3"]).unwrap_err().to_string();
    assert_mentions(&e, &["--set buoyancy_start", "is outside [0, 20000] m"]);
    let e = base.with_overrides(&["buoyancy_start=70", "buoyancy_end=60"]).unwrap_err().to_string();
    assert_mentions(&e, &["buoyancy[0].end", "greater than start"]);
}

#[test]
fn fewer_than_two_elements_are_rejected() {
    assert_mentions(&override_err(&["n_elements=1"]), &["--set n_elements", "[2, 2000]"]);
    assert_mentions(&override_err(&["n_elements=-4"]), &["n_elements", "whole number"]);
}

#[test]
fn analysis_settings_out_of_range_are_rejected() {
    assert_mentions(&override_err(&["time_step=0"]), &["--set time_step", "[0.0001, 10] s"]);
    assert_mentions(&override_err(&["newton_tolerance=0.5"]), &["--set newton_tolerance", "[1e-14, 0.01]"]);
    assert_mentions(&override_err(&["model=beam"]), &["model", "rod or cable"]);
    assert_mentions(&override_err(&["static_current=maybe"]), &["static_current", "true or false"]);
}

#[test]
fn bad_overrides_are_rejected() {
    assert_mentions(&override_err(&["stifness=3"]), &["stifness", "unknown parameter", "bending_stiffness"]);
    assert_mentions(&override_err(&["length"]), &["expected name=value"]);
    assert_mentions(&override_err(&["length=abc"]), &["length", "not a number"]);
}

#[test]
fn unknown_scene_names_the_built_ins() {
    let e = Scene::load("/no/such/scene.toml").unwrap_err().to_string();
    assert_mentions(&e, &["/no/such/scene.toml", "catenary", "lazy_wave"]);
}

#[test]
fn current_overrides_follow_the_profile() {
    // a uniform current set to one speed stays uniform in effect
    let s = Scene::builtin("catenary").unwrap().with_overrides(&["current_top=0.5", "current_bottom=0.5"]).unwrap();
    let c = riser::loads::current(&s);
    assert_eq!(c.speed(0.0, 0.0).0, 0.5);
    assert_eq!(c.speed(100.0, -70.0).0, 0.5);
    // the lazy wave's profile reversed
    let s = Scene::builtin("lazy_wave").unwrap().with_overrides(&["current_top=-0.8", "current_bottom=-0.3"]).unwrap();
    assert_eq!(riser::loads::current(&s).speed(0.0, 0.0).0, -0.8);
}
