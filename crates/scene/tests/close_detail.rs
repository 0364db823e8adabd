//! Close-range detail: its fields are checked by name, its cost bound holds, the baselines
//! refuse it, and the uniform block carries it.

use stratus_scene::{DEFAULT_CLOSE_DETAIL_SCALE, MAX_CLOSE_STEPS, Method, Scene};

fn error(s: &Scene) -> String {
    s.validate().expect_err("should be refused").to_string()
}

fn on() -> Scene {
    let mut s = Scene::preset("inside-layer").unwrap();
    s.clouds.close_detail = 1.0;
    s
}

#[test]
fn close_detail_fields_are_checked_by_name() {
    assert!(on().validate().is_ok());
    let mut s = on();
    s.clouds.close_detail = 1.5;
    assert!(
        error(&s).contains("clouds.close_detail = 1.5"),
        "{}",
        error(&s)
    );
    let mut s = on();
    s.clouds.close_detail_scale = 1;
    let e = error(&s);
    assert!(
        e.contains("clouds.close_detail_scale = 1: must be within [2, 32]"),
        "{e}"
    );
    let mut s = on();
    s.clouds.close_detail_range_m = -5.0;
    assert!(error(&s).contains("clouds.close_detail_range_m = -5"));
    let mut s = on();
    s.quality.close_step_m = 0.0;
    assert!(error(&s).contains("quality.close_step_m = 0"));
}

/// The second erosion works where the first does: with the detail erosion off it would only
/// cost its steps, so it is refused, naming the field it needs; off, it asks nothing.
#[test]
fn close_detail_needs_the_detail_erosion() {
    let mut s = on();
    s.clouds.detail_strength = 0.0;
    let e = error(&s);
    assert!(
        e.contains("clouds.close_detail = 1: erodes the edges a second time")
            && e.contains("needs clouds.detail_strength > 0"),
        "{e}"
    );
    s.clouds.close_detail = 0.0;
    assert!(s.validate().is_ok());
}

/// More than MAX_CLOSE_STEPS steps across the range is refused, naming both fields; with close
/// detail off the same fields pass (they are not read).
#[test]
fn close_detail_steps_across_its_range_are_bounded() {
    let mut s = on();
    s.clouds.close_detail_range_m = 2000.0;
    s.quality.close_step_m = 2000.0 / f64::from(MAX_CLOSE_STEPS);
    assert!(s.validate().is_ok());
    s.quality.close_step_m = 5.0;
    let e = error(&s);
    assert!(
        e.contains(
            "quality.close_step_m = 5: takes 400 steps to cross clouds.close_detail_range_m"
        ),
        "{e}"
    );
    s.clouds.close_detail = 0.0;
    assert!(s.validate().is_ok());
}

#[test]
fn the_baselines_refuse_close_detail() {
    for method in [Method::Basic, Method::Sprites] {
        let mut s = on();
        s.quality.method = method;
        let e = error(&s);
        assert!(e.contains("close-range detail needs"), "{e}");
    }
}

/// The uniform block carries the fields; the scale is the integer the WGSL multiplies by.
#[test]
fn the_uniforms_carry_close_detail() {
    let mut s = on();
    s.clouds.close_detail = 0.75;
    s.clouds.close_detail_range_m = 800.0;
    s.quality.close_step_m = 10.0;
    let u = s.uniforms();
    assert_eq!(u.close_detail, 0.75);
    assert_eq!(u.close_detail_scale, DEFAULT_CLOSE_DETAIL_SCALE as f32);
    assert_eq!(u.close_detail_range, 800.0);
    assert_eq!(u.close_step, 10.0);
    // Off: the march and the density read nothing else.
    assert_eq!(Scene::default().uniforms().close_detail, 0.0);
}

/// A scene file sets them; a default one lists none of them (they are left out at their
/// defaults, so every other scene's file is unchanged).
#[test]
fn scene_files_set_close_detail() {
    let s = Scene::from_toml_str(
        "base = \"inside-layer\"\n[clouds]\nclose_detail = 1.0\nclose_detail_scale = 8\n[quality]\nclose_step_m = 25.0\n",
        "test.toml",
    )
    .unwrap();
    assert_eq!(s.clouds.close_detail, 1.0);
    assert_eq!(s.clouds.close_detail_scale, 8);
    assert_eq!(s.quality.close_step_m, 25.0);
    assert!(!Scene::default().to_toml().contains("close_"));
}
