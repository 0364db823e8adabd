//! Scenes derived from METAR reports: valid, with the layers and states their groups say.

use stratus_scene::Scene;
use stratus_weather::{scene_from_metar_text, states};

fn derive(report: &str) -> stratus_weather::Derived {
    let d = scene_from_metar_text(report, &Scene::default())
        .unwrap_or_else(|e| panic!("{report}: {e}"));
    d.scene
        .validate()
        .unwrap_or_else(|e| panic!("{report}: derived scene invalid: {e}"));
    d
}

#[test]
fn every_stored_report_derives_a_valid_scene() {
    let data = include_str!("data/metar_reports.txt");
    let mut n = 0;
    for line in data.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let d = derive(line);
        // Round trip: the written file loads back to the same scene.
        let back = Scene::from_toml_str(&d.to_toml(line), "derived").unwrap();
        assert_eq!(back, d.scene, "{line}");
        n += 1;
    }
    assert!(n >= 30, "only {n} reports");
}

#[test]
fn three_cloud_groups_make_three_layers() {
    let d = derive("KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012");
    let s = &d.scene;
    assert_eq!(s.clouds.layers.len(), 2);
    assert!((s.atmosphere.cloud_bottom_m - 1371.6).abs() < 0.1);
    assert!((s.clouds.layers[0].bottom_m - 3657.6).abs() < 0.1);
    assert!((s.clouds.layers[1].bottom_m - 7620.0).abs() < 0.1);
    // Coverage grows with the cover class; the high deck is thin.
    assert!(s.clouds.coverage < s.clouds.layers[0].coverage);
    assert!(s.clouds.layers[0].coverage < s.clouds.layers[1].coverage);
    assert!(s.clouds.layers[1].density < s.clouds.density);
    // From 310 degrees: blowing toward 130.
    assert_eq!(s.clouds.wind_direction_deg, 130.0);
    assert!((s.clouds.wind_speed_m_s - 6.173).abs() < 1e-3);
    assert_eq!(d.state.name, "broken");
}

#[test]
fn weather_groups_pick_states() {
    for (report, state) in [
        ("EGLL 221650Z 24010KT CAVOK 18/09 Q1020", "clear"),
        (
            "KMIA 221653Z 09015G25KT 3SM +TSRA BKN020CB OVC080 24/22 A2990",
            "thunderstorm",
        ),
        ("EDDF 221650Z 05003KT 0200 FG VV001 02/02 Q1025", "fog"),
        ("KSEA 221653Z 18008KT 4SM -RA BR OVC012 09/08 A2995", "rain"),
        ("CYUL 221700Z 03012KT 1SM -SN OVC015 M05/M07 A3001", "snow"),
    ] {
        let d = derive(report);
        assert_eq!(d.state.name, state, "{report}");
    }
    // Fog: a ground layer from the visibility, under the state's deck.
    let fog = derive("EDDF 221650Z 05003KT 0200 FG VV001 02/02 Q1025");
    let ground = fog
        .scene
        .clouds
        .layers
        .iter()
        .find(|l| l.bottom_m == 0.0)
        .unwrap();
    assert_eq!(ground.density, states::fog_density_for_visibility(200.0));
    // Rain falls from the lowest deck.
    let rain = derive("KSEA 221653Z 18008KT 4SM -RA BR OVC012 09/08 A2995");
    assert_eq!(rain.scene.clouds.precipitation, 0.4);
}

#[test]
fn malformed_reports_name_the_token() {
    let e = scene_from_metar_text("KJFK 221651Z 31012KT 10SM XYZ999", &Scene::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("XYZ999"), "{e}");
}

#[test]
fn derivation_is_deterministic() {
    let r = "KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012";
    let a = derive(r).scene.uniforms();
    let b = derive(r).scene.uniforms();
    assert_eq!(a.as_bytes(), b.as_bytes());
}

/// Found by the fuzzer: a cloud group based at the ground (SCT000) is still the main layer,
/// so the state's deck does not stay behind to overlap the report's layers.
#[test]
fn a_group_at_the_ground_is_the_main_layer() {
    let d = derive("AAAA\nSCT000\nSCT109\nSCT055\n");
    assert_eq!(d.scene.atmosphere.cloud_bottom_m, 0.0);
    assert_eq!(d.scene.clouds.layers.len(), 2);
    // Fog with four groups: the highest group gives way.
    let d = derive("EDDF 221650Z 05003KT 0200 FG FEW030 SCT050 BKN080 OVC100 02/02 Q1025");
    assert_eq!(d.scene.clouds.layers.len(), 3);
    assert_eq!(d.scene.clouds.layers[2].bottom_m, 0.0);
}
