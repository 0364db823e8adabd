//! `[sky]`: a date and a place set the sun's direction, bad ones are named, and animation
//! moves the sun with time.

use stratus_scene::Scene;

const STOCKHOLM_EVENING: &str = r#"
[sky]
date_utc = "2026-06-21T18:30:00Z"
latitude_deg = 59.33
longitude_deg = 18.07
"#;

fn load(src: &str) -> Result<Scene, String> {
    Scene::from_toml_str(src, "test.toml").map_err(|e| e.to_string())
}

#[test]
fn a_date_and_place_set_the_sun() {
    let s = load(STOCKHOLM_EVENING).expect("loads");
    // `stratus astro` for the same date and place: elevation 8.2539, azimuth 302.9046.
    let d = s.sun_direction();
    let elevation = d[1].asin().to_degrees();
    let azimuth = d[0].atan2(d[2]).to_degrees().rem_euclid(360.0);
    assert!((elevation - 8.2539).abs() < 1e-3, "{elevation}");
    assert!((azimuth - 302.9046).abs() < 1e-3, "{azimuth}");
    assert!((s.sun_elevation_deg() - elevation).abs() < 1e-9);
    // It replaces [sun]'s angles: changing them changes nothing.
    let mut other = s.clone();
    other.sun.elevation_deg = 70.0;
    assert_eq!(other.sun_direction(), d);
    // And survives the TOML round trip.
    let again = load(&s.to_toml()).expect("round trip");
    assert_eq!(again, s);
    assert!(s.to_toml().contains("date_utc = \"2026-06-21T18:30:00Z\""));
    // A scene without [sky] writes none.
    assert!(!Scene::default().to_toml().contains("[sky]"));
}

#[test]
fn animation_moves_the_sun_with_time() {
    let s = load(STOCKHOLM_EVENING).expect("loads");
    let later = s.at_time(3600.0);
    assert_eq!(
        later.sky.date_utc.map(|d| d.to_string()).as_deref(),
        Some("2026-06-21T19:30:00Z")
    );
    // An hour later the evening sun is lower.
    assert!(later.sun_elevation_deg() < s.sun_elevation_deg() - 3.0);
}

#[test]
fn bad_skies_are_named() {
    let e =
        load("[sky]\ndate_utc = \"2026-06-21 18:30\"\nlatitude_deg = 1.0\nlongitude_deg = 2.0\n")
            .unwrap_err();
    assert!(
        e.contains("date_utc") && e.contains("does not end in `Z`"),
        "{e}"
    );
    let e = load(
        "[sky]\ndate_utc = \"2026-06-31T18:30:00Z\"\nlatitude_deg = 1.0\nlongitude_deg = 2.0\n",
    )
    .unwrap_err();
    assert!(e.contains("day 31 of 2026-06"), "{e}");
    let e = load("[sky]\ndate_utc = \"2026-06-21T18:30:00Z\"\n").unwrap_err();
    assert!(
        e.contains("give sky.latitude_deg and sky.longitude_deg too"),
        "{e}"
    );
    let e = load(&format!("{STOCKHOLM_EVENING}\n").replace("59.33", "95.0")).unwrap_err();
    assert!(e.contains("sky.latitude_deg = 95"), "{e}");
    let e = load(&format!(
        "{STOCKHOLM_EVENING}\n[sun]\ndirection = [0.0, 1.0, 0.0]\n"
    ))
    .unwrap_err();
    assert!(
        e.contains("sun.direction") && e.contains("remove one of them"),
        "{e}"
    );
}

/// `[atmosphere] sky` picks the physical sky; `[atmosphere.air]` overrides the Earth's air,
/// and bad air is named. Neither is written out while it holds its default, so scenes that do
/// not use them print as before.
#[test]
fn the_physical_sky_and_its_air_load_and_bad_air_is_named() {
    let s =
        load("[atmosphere]\nsky = \"physical\"\n[atmosphere.air]\nmie_g = 0.7\n").expect("loads");
    assert!(s.atmosphere.sky.is_physical());
    assert_eq!(s.atmosphere.air.mie_g, 0.7);
    let u = s.uniforms();
    assert_ne!(u.flags & stratus_scene::FrameUniforms::FLAG_PHYSICAL_SKY, 0);
    assert_eq!(u.mie_g, 0.7);
    assert_eq!(u.air_thickness, 100_000.0);
    let text = toml::to_string(&Scene::default()).expect("serializes");
    assert!(
        !text.contains("air") && !text.contains("physical"),
        "{text}"
    );

    let e = load("[atmosphere]\nsky = \"physicl\"\n").unwrap_err();
    assert!(e.contains("\"physical\""), "{e}");
    let e = load("[atmosphere.air]\nmie_g = 1.0\n").unwrap_err();
    assert!(e.contains("atmosphere.air.mie_g = 1"), "{e}");
    let e = load("[atmosphere.air]\nrayleigh_scattering = [1e-6, -1e-6, 0.0]\n").unwrap_err();
    assert!(
        e.contains("atmosphere.air.rayleigh_scattering") && e.contains(">= 0"),
        "{e}"
    );
}

#[test]
fn light_shafts_load_under_the_physical_sky_and_are_refused_without_it() {
    let s = load("[atmosphere]\nsky = \"physical\"\nlight_shafts = true\n").expect("loads");
    assert!(s.atmosphere.light_shafts);
    assert_ne!(
        s.uniforms().flags & stratus_scene::FrameUniforms::FLAG_LIGHT_SHAFTS,
        0
    );
    // Off by default, and then not written out.
    let plain = load("[atmosphere]\nsky = \"physical\"\n").expect("loads");
    assert!(!plain.atmosphere.light_shafts);
    assert_eq!(
        plain.uniforms().flags & stratus_scene::FrameUniforms::FLAG_LIGHT_SHAFTS,
        0
    );
    let e = load("[atmosphere]\nlight_shafts = true\n").unwrap_err();
    assert!(
        e.contains("atmosphere.light_shafts") && e.contains("sky = \"physical\""),
        "{e}"
    );
}

/// The rainbow and the post effects: they load and reach the uniforms, leave a scene without
/// them unchanged, and bad values are refused naming the field.
#[test]
fn rainbow_and_post_fields_load_and_bad_values_are_refused() {
    let s = load(
        "[atmosphere]\nsky = \"physical\"\n[rainbow]\nmoisture = 0.5\ndrop_radius_um = 20\n[post]\nkuwahara = true\nsaturation = 1.5\nlens_flare_intensity = 2.5\n[camera]\nexposure_range = [0.5, 2.0]\n",
    )
    .expect("loads");
    let u = s.uniforms();
    assert_eq!((u.rainbow_moisture, u.saturation), (0.5, 1.5));
    assert_eq!(u.lens_flare_intensity, 2.5);
    // The night sky's fields reach the uniforms; the catalogue's axes come from the date and
    // place (a unit vector each), and are 0 without them.
    let night = load(
        "[atmosphere]\nsky = \"physical\"\n[sky]\ndate_utc = \"2026-08-12T22:00:00Z\"\nlatitude_deg = 46\nlongitude_deg = 8\n[night]\nstar_intensity = 2\nstar_min_radius_px = 0.75\nstar_radius_scale = 0.5\nstar_glare_scale = 3\nmilky_way_intensity = 4\nmoon_size = 2\nmoon_msaa = true\n",
    )
    .expect("loads");
    let nu = night.uniforms();
    assert_eq!(
        (
            nu.star_intensity,
            nu.star_min_radius,
            nu.star_radius_scale,
            nu.star_glare_scale,
            nu.milky_way_intensity
        ),
        (2.0, 0.75, 0.5, 3.0, 4.0)
    );
    assert_ne!(nu.flags & stratus_scene::FrameUniforms::FLAG_MOON_MSAA, 0);
    let radius = |c: f32| f64::from(c).acos().to_degrees();
    assert!((radius(nu.moon_cos_radius) - 2.0 * 0.259).abs() < 0.01);
    for axis in [nu.celestial_x, nu.celestial_y, nu.celestial_z] {
        let n: f32 = axis.iter().map(|a| a * a).sum();
        assert!((n - 1.0).abs() < 1e-5, "{axis:?}");
    }
    assert_eq!(
        s.uniforms().celestial_z,
        [0.0; 3],
        "no date and place, no sky"
    );
    assert!((u.rainbow_drop_radius - 20e-6).abs() < 1e-12);
    assert!(u.kuwahara_radius > 0.0);
    assert_ne!(u.flags & stratus_scene::FrameUniforms::FLAG_LEE_DIAGRAM, 0);
    // Without them: nothing written out, the filter off, no table flag.
    let plain = load("[atmosphere]\nsky = \"physical\"\n").expect("loads");
    let text = plain.to_toml();
    assert!(
        !text.contains("rainbow") && !text.contains("[post]") && !text.contains("exposure_range"),
        "{text}"
    );
    let u = plain.uniforms();
    assert_eq!(
        (
            u.rainbow_moisture,
            u.kuwahara_radius,
            u.saturation,
            u.lens_flare_intensity
        ),
        (0.0, 0.0, 1.0, 0.0)
    );
    assert_eq!(u.flags & stratus_scene::FrameUniforms::FLAG_LEE_DIAGRAM, 0);
    for (text, field) in [
        ("[rainbow]\nmoisture = 1.0\n", "rainbow.moisture"),
        (
            "[atmosphere]\nsky = \"physical\"\n[rainbow]\nmoisture = -1\n",
            "rainbow.moisture",
        ),
        (
            "[atmosphere]\nsky = \"physical\"\n[rainbow]\ndrop_radius_um = 1\n",
            "rainbow.drop_radius_um",
        ),
        ("[post]\nsaturation = 9\n", "post.saturation"),
        ("[post]\nkuwahara_radius = 0\n", "post.kuwahara_radius"),
        (
            "[post]\nlens_flare_intensity = -1\n",
            "post.lens_flare_intensity",
        ),
        (
            "[post]\nlens_flare_intensity = 11\n",
            "post.lens_flare_intensity",
        ),
        ("[night]\nstar_intensity = -1\n", "night.star_intensity"),
        (
            "[night]\nstar_min_radius_px = 0.1\n",
            "night.star_min_radius_px",
        ),
        (
            "[night]\nstar_radius_scale = 5\n",
            "night.star_radius_scale",
        ),
        ("[night]\nstar_glare_scale = -2\n", "night.star_glare_scale"),
        (
            "[night]\nmilky_way_intensity = 101\n",
            "night.milky_way_intensity",
        ),
        ("[night]\nmoon_size = 0.1\n", "night.moon_size"),
        ("[night]\nmoon_msaa = 1\n", "night.moon_msaa"),
        (
            "[camera]\nexposure_range = [2.0, 1.0]\n",
            "camera.exposure_range",
        ),
        (
            "[camera]\nexposure_range = [0.0, 1.0]\n",
            "camera.exposure_range",
        ),
    ] {
        let e = load(text).unwrap_err();
        assert!(e.contains(field), "{text}: {e}");
    }
}
