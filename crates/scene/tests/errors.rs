//! The error messages of bad scenes are part of the product: snapshot them.
//!
//! Each snapshot's description is the TOML that produced it.

use stratus_scene::{ProblemKind, Scene};

/// Loads `src` as `bad.toml`, expecting failure; snapshots the message under `name`.
fn snapshot(name: &str, src: &str) -> stratus_scene::SceneError {
    let err = Scene::from_toml_str(src, "bad.toml").expect_err("the scene should be rejected");
    insta::with_settings!({ description => src, omit_expression => true }, {
        insta::assert_snapshot!(name, err.to_string());
    });
    err
}

fn kinds(err: &stratus_scene::SceneError) -> Vec<ProblemKind> {
    err.problems().iter().map(|p| p.kind).collect()
}

#[test]
fn out_of_range_and_misspelled_field_are_both_reported() {
    let err = snapshot(
        "coverage_out_of_range_and_misspelled_field",
        "[camera]\npitch_deg = 10.0\n\n[clouds]\ncoverage = 1.7\ncovrage = 0.5\n",
    );
    assert_eq!(
        kinds(&err),
        [ProblemKind::InvalidValue, ProblemKind::UnknownField]
    );
    assert_eq!(err.problems()[1].path.as_deref(), Some("clouds.covrage"));
}

#[test]
fn syntax_error_has_line_and_column() {
    let err = snapshot(
        "syntax_error",
        "[clouds]\ncoverage = 0.5\ndensity = = 2\n\n[sun\nelevation_deg = 30\n",
    );
    assert!(kinds(&err).iter().all(|k| *k == ProblemKind::Syntax));
    let loc = err.problems()[0].location.expect("located");
    assert_eq!((loc.line, loc.column), (3, 11));
}

#[test]
fn duplicate_key_is_named() {
    snapshot(
        "duplicate_key",
        "[clouds]\ncoverage = 0.5\ncoverage = 0.6\n",
    );
}

#[test]
fn bottom_must_be_below_top() {
    snapshot(
        "cloud_bottom_not_below_top",
        "[atmosphere]\ncloud_bottom_m = 4000\ncloud_top_m = 3000\n",
    );
    // Only the top is in the file: the message is about the top.
    snapshot(
        "cloud_top_below_default_bottom",
        "[atmosphere]\ncloud_top_m = 1000\n",
    );
}

#[test]
fn nan_and_inf_are_rejected() {
    snapshot(
        "nan_and_inf",
        "[clouds]\ncoverage = nan\ndensity = inf\n\n[sun]\nilluminance = [1.0, -inf, 2.0]\n",
    );
}

#[test]
fn unknown_base_preset_suggests_nearest() {
    let err = snapshot(
        "unknown_base_preset",
        "base = \"sunsett\"\n\n[clouds]\ncoverage = 0.3\n",
    );
    assert_eq!(kinds(&err), [ProblemKind::UnknownPreset]);
}

#[test]
fn unknown_preset_by_name() {
    let err = Scene::preset("stormy").unwrap_err();
    insta::assert_snapshot!("unknown_preset_by_name", err.to_string());
}

#[test]
fn wrong_types_are_all_reported() {
    let err = snapshot(
        "wrong_types",
        concat!(
            "[clouds]\n",
            "coverage = \"lots\"\n",
            "height_model = \"parabolic\"\n",
            "\n[quality]\n",
            "light_steps = -1\n",
            "jitter = 1\n",
            "\n[camera]\n",
            "resolution = [800]\n",
            "fov_y_deg = 500\n",
        ),
    );
    // The last one is a validation error found despite the type errors before it.
    assert_eq!(
        kinds(&err),
        [
            ProblemKind::WrongType,
            ProblemKind::WrongType,
            ProblemKind::WrongType,
            ProblemKind::WrongType,
            ProblemKind::WrongType,
            ProblemKind::InvalidValue,
        ]
    );
}

#[test]
fn zero_steps() {
    snapshot(
        "zero_view_steps",
        "[quality]\nview_steps = 0\nlight_steps = 17\n",
    );
}

#[test]
fn fields_in_the_wrong_place() {
    snapshot(
        "fields_in_the_wrong_place",
        concat!(
            "coverage = 0.5\n",
            "clods = 1\n",
            "\n[quality]\n",
            "steps = 32\n",
            "\n[lighting.phase]\n",
            "model = 3\n",
        ),
    );
}

/// a > b and a > 1 are allowed (the fitted octaves have them); out-of-range constants are not.
#[test]
fn multiple_scattering_constants_are_bounded() {
    snapshot(
        "multiple_scattering_out_of_range",
        "[lighting.multiple_scattering]\na = 2.5\nb = 0.4\noctaves = 9\nbuildup_m = -1.0\n\
         side_light = 5.0\ncoverage_exponent = -1.0\nfar_chord_m = 50.0\nlimb_darkening = -0.5\n\
         forward_lobe = 1.5\nforward_lobe_g = 0.99\nvertical_anisotropy = 1.5\n\
         deck_escape = 2.5\nsteep_light = -0.1\nsteep_light_scale = 9.0\n\
         downward_dimming = 9.0\n",
    );
}

#[test]
fn validate_reports_without_location() {
    let mut scene = Scene::default();
    scene.clouds.coverage = -0.5;
    scene.sun.direction = Some([0.0; 3]);
    scene.noise.seed = u64::MAX;
    let err = scene.validate().unwrap_err();
    insta::assert_snapshot!("validate_without_file", err.to_string());
    assert!(err.problems().iter().all(|p| p.location.is_none()));
}

#[test]
fn unreadable_file_names_the_path() {
    let err = Scene::from_file("/nonexistent/scene.toml").unwrap_err();
    assert_eq!(kinds(&err), [ProblemKind::Io]);
    assert!(
        err.to_string()
            .starts_with("/nonexistent/scene.toml: cannot read the file: "),
        "{err}"
    );
}

#[test]
fn bad_animation_and_temporal_settings_are_named() {
    let err = snapshot(
        "bad_animation_and_temporal",
        "[quality]\ntemporal = \"1/8\"\n",
    );
    assert_eq!(kinds(&err), [ProblemKind::WrongType]);
    let err = snapshot(
        "checkerboard_without_temporal_and_keyframes_out_of_order",
        "[quality]\ncheckerboard = true\n\n[animation]\nduration_s = 2.0\n\n[[animation.keyframes]]\ntime_s = 1.5\n\n[[animation.keyframes]]\ntime_s = 0.5\nposition = [0.0, -5.0, 0.0]\n",
    );
    let text = err.to_string();
    assert!(text.contains("quality.checkerboard"), "{text}");
    assert!(text.contains("keyframe 1: time_s = 0.5"), "{text}");
    assert!(text.contains("keyframe 1: position"), "{text}");
}

/// The path tracer accumulates every pixel itself: temporal upsampling with it is refused,
/// and an unknown integrator is named.
#[test]
fn path_tracer_with_temporal_upsampling_is_refused() {
    let err = snapshot(
        "pathtrace_with_temporal",
        "[quality]\nintegrator = \"pathtrace\"\ntemporal = \"1/4\"\n",
    );
    assert!(err.to_string().contains("quality.temporal"), "{err}");
    let err = snapshot(
        "unknown_integrator",
        "[quality]\nintegrator = \"photon-mapping\"\n",
    );
    assert!(err.to_string().contains("quality.integrator"), "{err}");
    let ok = stratus_scene::Scene::from_toml_str(
        "[quality]\nintegrator = \"pathtrace\"\npath_orders = 1\n",
        "ok.toml",
    )
    .expect("a valid path-traced scene");
    assert_eq!(ok.quality.integrator, stratus_scene::Integrator::Pathtrace);
    assert_eq!(ok.uniforms().path_orders, 1);
}

/// A camera orientation that is not a rotation (not unit, not orthogonal, mirrored) is named.
#[test]
fn a_camera_orientation_must_be_a_rotation() {
    let err = snapshot(
        "orientation_not_unit",
        "[camera.orientation]\nforward = [0.0, 0.0, 2.0]\nright = [1.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n",
    );
    assert_eq!(
        err.problems()[0].path.as_deref(),
        Some("camera.orientation.forward")
    );
    let err = snapshot(
        "orientation_not_orthogonal",
        "[camera.orientation]\nforward = [0.0, 0.0, 1.0]\nright = [1.0, 0.0, 0.0]\nup = [0.0, 0.6, 0.8]\n",
    );
    assert!(err.to_string().contains("orthogonal to up"), "{err}");
    let err = snapshot(
        "orientation_mirrored",
        "[camera.orientation]\nforward = [0.0, 0.0, -1.0]\nright = [1.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n",
    );
    assert!(err.to_string().contains("mirrored"), "{err}");
}
