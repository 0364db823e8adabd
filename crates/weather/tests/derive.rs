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

#[test]
fn a_reported_visibility_or_haze_group_thickens_the_air_by_koschmieder() {
    use stratus_weather::haze;
    // Haze at 3000 m: the air near the ground sees 3000 m, with continental aerosol.
    let d = derive("ZSHC 240000Z 36004MPS 3000 HZ SCT040 12/08 Q1022");
    let air = &d.scene.atmosphere.air;
    assert!((haze::visibility(air) - 3000.0).abs() < 1e-6, "{air:?}");
    let albedo = air.mie_scattering / (air.mie_scattering + air.mie_absorption);
    assert!((albedo - haze::Aerosol::Continental.albedo()).abs() < 1e-12);
    assert!(
        d.notes
            .iter()
            .any(|n| n.contains("haze: visibility 3000 m")),
        "{:?}",
        d.notes
    );
    // Smoke without a visibility: the least haze FU says there is, with sooty aerosol.
    let d = derive("KLAX 240000Z 25005KT FU SCT040 22/10 A2992");
    let air = &d.scene.atmosphere.air;
    assert!((haze::visibility(air) - haze::HAZE_VISIBILITY_M).abs() < 1e-6);
    assert!(air.mie_absorption / (air.mie_scattering + air.mie_absorption) > 0.15);
    // Rain that hides the distance: water, which hardly absorbs.
    let d = derive("KMIA 271853Z 09012KT 2SM +TSRA BKN025CB 26/24 A2992");
    let air = &d.scene.atmosphere.air;
    assert!((haze::visibility(air) - 2.0 * 1609.344).abs() < 1e-6);
    assert!(air.mie_absorption / (air.mie_scattering + air.mie_absorption) < 0.02);
    // 10 km or more, CAVOK: the clean air, its aerosol grown by the humidity of 12/08 (77%,
    // Magnus), still seeing over 100 km.
    for report in [
        "EGLL 240000Z 24010KT 9999 SCT040 12/08 Q1022",
        "EGLL 240000Z 24010KT CAVOK 12/08 Q1022",
    ] {
        let air = derive(report).scene.atmosphere.air;
        let grown = air.mie_scattering / stratus_scene::Air::default().mie_scattering;
        let rh = haze::relative_humidity(12.0, 8.0);
        assert!(
            (grown - haze::growth(rh)).abs() < 1e-12,
            "{report}: {grown}"
        );
        assert!(haze::visibility(&air) > 100e3, "{report}");
    }
    // Mist with room for its ground layer: the layer holds the visibility, not the air.
    let d = derive("EGLL 240000Z 24003KT 2000 BR BKN030 08/07 Q1022");
    assert!(d.scene.atmosphere.air.is_earth());
    assert!(d.scene.clouds.layers.iter().any(|l| l.bottom_m == 0.0));
}

#[test]
fn a_vertical_visibility_is_an_obscured_base_and_impossible_heights_are_refused() {
    // Heavy snow hides the sky from 500 ft up: the deck's base is there.
    let d = derive("CYUL 221700Z 03012KT 1/4SM +SN VV005 M05/M07 A3001");
    assert!((d.scene.atmosphere.cloud_bottom_m - 5.0 * 30.48).abs() < 1e-6);
    assert!(d.notes.iter().any(|n| n.contains("VV005")), "{:?}", d.notes);
    // The snow's 400 m is in the air, as water (ice) that hardly absorbs.
    let v = stratus_weather::haze::visibility(&d.scene.atmosphere.air);
    assert!((v - 0.25 * 1609.344).abs() < 1e-6, "{v}");
    // Fog with a vertical visibility keeps its ground layer as the obscuration.
    let d = derive("EDDF 221650Z 05003KT 0200 FG VV001 02/02 Q1025");
    assert!(d.scene.clouds.layers.iter().any(|l| l.bottom_m == 0.0));
    for (report, token) in [
        ("KJFK 221651Z 31012KT 10SM FEW700 12/M02 A3012", "FEW700"),
        ("KJFK 221651Z 31012KT 1SM FG VV800 12/M02 A3012", "VV800"),
    ] {
        let e = scene_from_metar_text(report, &Scene::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(token) && e.contains("20 km"), "{report}: {e}");
    }
}

#[test]
fn a_cumulonimbus_brings_anvils_and_a_thunderstorm_without_one_does_not() {
    // CB: anvils on; the layer is deep enough to have one (8 km) while the fair cumulus below
    // it is not, so its domes stay (density.wgsl::anvil_cover weighs the layer's depth).
    let d = derive("METAR LRTR 101600Z 11017KT 9999 TS VCSH FEW020 SCT045CB 18/09 Q1004=");
    assert_eq!(d.scene.clouds.anvil, 1.0);
    let cb = &d.scene.clouds.layers[0];
    assert!(cb.top_m - cb.bottom_m >= 6000.0, "{cb:?}");
    let main = &d.scene.atmosphere;
    assert!(main.cloud_top_m - main.cloud_bottom_m <= 4000.0);
    // Thunder heard with towering cumulus only: no anvils.
    let d = derive("METAR LRTR 101600Z 11017KT 9999 TS FEW020 SCT045TCU 18/09 Q1004=");
    assert_eq!(d.scene.clouds.anvil, 0.0);
    // The thunderstorm state has them, the others do not.
    for s in &states::STATES {
        assert_eq!(
            s.params.anvil,
            f64::from(u8::from(s.name == "thunderstorm")),
            "{}",
            s.name
        );
    }
}

#[test]
fn layer_cloud_groups_become_cellular_and_the_others_do_not() {
    // BKN015 stratocumulus (main), SCT100 altocumulus (3048 m), OVC150 altostratus (4572 m).
    let d = derive("METAR EGLL 221650Z 24010KT 9999 BKN015 SCT100 OVC150 12/08 Q1012=");
    assert_eq!(d.scene.clouds.cellular, 1.0, "stratocumulus: {:?}", d.notes);
    let [ac, altostratus] = &d.scene.clouds.layers[..] else {
        panic!("two extra layers: {:?}", d.scene.clouds.layers);
    };
    assert_eq!(ac.cellular, 1.0, "{ac:?}");
    assert_eq!(altostratus.cellular, 0.0, "{altostratus:?}");
    for kind in ["-> stratocumulus", "-> altocumulus", "-> altostratus"] {
        assert!(
            d.notes.iter().any(|n| n.contains(kind)),
            "{kind}: {:?}",
            d.notes
        );
    }
    // Fair cumulus, stratus and nimbostratus are not.
    for metar in [
        "METAR KDEN 221653Z 09008KT 10SM SCT040 20/05 A3010=",
        "METAR KSFO 221656Z 28005KT 2SM BR OVC003 12/11 A3001=",
        "METAR EDDF 221650Z 23012KT 4000 RA OVC012 08/07 Q1003=",
    ] {
        assert_eq!(derive(metar).scene.clouds.cellular, 0.0, "{metar}");
    }
}

#[test]
fn high_cloud_groups_become_cirrus_and_the_others_do_not() {
    // FEW040 cumulus (main), FEW190 altocumulus (5791 m), SCT210 cirrus (6401 m).
    let d = derive(
        "METAR CYMA 092000Z VRB02KT 20SM FEW040 FEW190 SCT210 10/01 A3002 RMK CF1AS2CC1 CF TR SLP190=",
    );
    assert_eq!(d.scene.clouds.cirrus, 0.0);
    let [alto, cirrus] = &d.scene.clouds.layers[..] else {
        panic!("two extra layers: {:?}", d.scene.clouds.layers);
    };
    assert_eq!(alto.cirrus, 0.0, "{alto:?}");
    assert_eq!(alto.cellular, 1.0, "altocumulus is cellular: {alto:?}");
    assert_eq!(cirrus.cellular, 0.0, "{cirrus:?}");
    assert_eq!(cirrus.cirrus, 1.0, "{cirrus:?}");
    // Thin ice: the cirrus density, 1500 m deep.
    assert_eq!(cirrus.density, stratus_scene::DEFAULT_CIRRUS_DENSITY);
    assert_eq!(cirrus.top_m - cirrus.bottom_m, 1500.0);
    assert!(
        d.notes.iter().any(|n| n.contains("-> cirrus")),
        "{:?}",
        d.notes
    );
    // A closed high deck is a cirrostratus veil, cirrus all the same; a report of high cloud
    // alone makes the main layer cirrus.
    let d = derive("METAR KJFK 221651Z 31012KT 10SM OVC250 12/M02 A3012=");
    assert_eq!(d.scene.clouds.cirrus, 1.0);
    assert!(
        d.notes.iter().any(|n| n.contains("-> cirrostratus")),
        "{:?}",
        d.notes
    );
}
