//! METAR parser: real reports from `data/metar_reports.txt`, exact decodes of representative
//! reports, and malformed input that must give errors (never panics).

use stratus_weather::metar::{
    CloudGroup, Convective, Cover, Intensity, Metar, MetarError, ObservationTime, parse,
};

const REPORTS: &str = include_str!("data/metar_reports.txt");

fn reports() -> impl Iterator<Item = &'static str> {
    REPORTS
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
}

fn ok(report: &str) -> Metar {
    parse(report).unwrap_or_else(|e| panic!("{e}\n  in {report}"))
}

fn err(report: &str) -> MetarError {
    match parse(report) {
        Ok(m) => panic!("expected an error for {report:?}, got {m:?}"),
        Err(e) => e,
    }
}

#[track_caller]
fn close(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{actual} is not within {tolerance} of {expected}"
    );
}

#[track_caller]
fn close_opt(actual: Option<f64>, expected: f64, tolerance: f64) {
    close(actual.expect("value present"), expected, tolerance);
}

fn layer(cover: Cover, feet: f64, convective: Option<Convective>) -> CloudGroup {
    CloudGroup {
        cover,
        base_m: Some(feet * 0.3048),
        convective,
    }
}

#[test]
fn every_real_report_parses_with_sane_values() {
    let mut count = 0;
    for report in reports() {
        let m = ok(report);
        count += 1;
        assert_eq!(m.station.len(), 4, "{report}");
        assert!(
            m.station.chars().all(|c| c.is_ascii_alphanumeric()),
            "{report}"
        );
        if let Some(t) = m.time {
            assert!(
                (1..=31).contains(&t.day) && t.hour < 24 && t.minute < 60,
                "{report}"
            );
        }
        if let Some(w) = m.wind {
            assert!(w.speed_m_s.is_finite() && w.speed_m_s >= 0.0, "{report}");
            assert!(
                w.gust_m_s.is_none_or(|g| g.is_finite() && g >= w.speed_m_s),
                "{report}"
            );
            assert!(
                w.direction_deg.is_none_or(|d| (0.0..=360.0).contains(&d)),
                "{report}"
            );
        }
        assert!(
            m.visibility_m.is_none_or(|v| (0.0..=60_000.0).contains(&v)),
            "{report}"
        );
        for cloud in &m.clouds {
            assert!(
                cloud.base_m.is_none_or(|b| b.is_finite() && b >= 0.0),
                "{report}"
            );
        }
        assert!(m.vertical_visibility_m.is_none_or(|v| v >= 0.0), "{report}");
        for t in [m.temperature_c, m.dewpoint_c].into_iter().flatten() {
            assert!((-90.0..=60.0).contains(&t), "{report}");
        }
        assert!(
            m.pressure_hpa.is_none_or(|p| (900.0..=1100.0).contains(&p)),
            "{report}"
        );
        for w in &m.weather {
            assert!(
                w.descriptor.is_some() || !w.phenomena.is_empty(),
                "{report}"
            );
        }
        serde_json::to_string(&m).expect("serialises");
    }
    assert!(count >= 35, "only {count} reports");
}

#[test]
fn us_report_with_gusts_miles_and_altimeter() {
    let m = ok("KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012");
    assert_eq!(m.station, "KJFK");
    assert_eq!(
        m.time,
        Some(ObservationTime {
            day: 22,
            hour: 16,
            minute: 51
        })
    );
    assert!(!m.auto && !m.cavok && !m.no_significant_cloud);
    let wind = m.wind.expect("wind");
    assert_eq!(wind.direction_deg, Some(310.0));
    close(wind.speed_m_s, 6.173, 0.001);
    close_opt(wind.gust_m_s, 10.289, 0.001);
    assert_eq!(wind.variable_from_to_deg, None);
    close_opt(m.visibility_m, 16093.44, 0.01);
    assert!(m.weather.is_empty());
    assert_eq!(m.clouds.len(), 3);
    assert_eq!(m.clouds[0].cover, Cover::Few);
    close_opt(m.clouds[0].base_m, 1371.6, 1e-6);
    assert_eq!(m.clouds[1].cover, Cover::Scattered);
    close_opt(m.clouds[1].base_m, 3657.6, 1e-6);
    assert_eq!(m.clouds[2].cover, Cover::Broken);
    close_opt(m.clouds[2].base_m, 7620.0, 1e-6);
    assert!(m.clouds.iter().all(|c| c.convective.is_none()));
    assert_eq!(m.vertical_visibility_m, None);
    assert_eq!(m.temperature_c, Some(12.0));
    assert_eq!(m.dewpoint_c, Some(-2.0));
    close_opt(m.pressure_hpa, 1019.98, 0.005);
}

#[test]
fn european_cavok_with_variable_direction() {
    let m = ok("METAR LBSF 092100Z 29006KT 260V340 CAVOK 17/10 Q1021 NOSIG=");
    assert_eq!(m.station, "LBSF");
    let wind = m.wind.expect("wind");
    assert_eq!(wind.direction_deg, Some(290.0));
    close(wind.speed_m_s, 6.0 * 0.514444, 1e-9);
    assert_eq!(wind.gust_m_s, None);
    assert_eq!(wind.variable_from_to_deg, Some((260.0, 340.0)));
    assert!(m.cavok);
    assert_eq!(m.visibility_m, Some(10_000.0));
    assert!(m.weather.is_empty() && m.clouds.is_empty());
    assert_eq!((m.temperature_c, m.dewpoint_c), (Some(17.0), Some(10.0)));
    assert_eq!(m.pressure_hpa, Some(1021.0));
}

#[test]
fn thunderstorm_with_cumulonimbus() {
    let m = ok(
        "METAR LRTR 101600Z 11017KT 9999 TS VCSH FEW020 SCT045CB 18/09 Q1004 WS RWY11 TEMPO 5000 TSRA=",
    );
    assert_eq!(m.visibility_m, Some(10_000.0));
    assert_eq!(m.weather.len(), 2);
    assert_eq!(m.weather[0].intensity, Intensity::Moderate);
    assert_eq!(m.weather[0].descriptor.as_deref(), Some("TS"));
    assert!(m.weather[0].phenomena.is_empty());
    assert!(m.weather[0].has("TS"));
    assert_eq!(m.weather[1].intensity, Intensity::InVicinity);
    assert!(m.weather[1].has("SH"));
    assert_eq!(
        m.clouds,
        vec![
            layer(Cover::Few, 2000.0, None),
            layer(Cover::Scattered, 4500.0, Some(Convective::Cumulonimbus)),
        ]
    );
    assert_eq!(m.pressure_hpa, Some(1004.0));

    // Heavy thunderstorm rain plus dust and sand storm; the TEMPO trend is not read, and the
    // first of two pressure groups wins.
    let m = ok(
        "METAR OIII 021300Z 27048G60KT 4000 +TSRA +DSSS SCT025CB SCT030 BKN070 23/11 Q1014 A2995 TEMPO FM 1300 32030G40KT 1500 SA TEMPO 1000 SA TSRA=",
    );
    assert_eq!(m.weather.len(), 2);
    assert_eq!(m.weather[0].intensity, Intensity::Heavy);
    assert_eq!(m.weather[0].descriptor.as_deref(), Some("TS"));
    assert_eq!(m.weather[0].phenomena, ["RA"]);
    assert!(m.weather[0].has("RA") && m.weather[0].has("TS") && !m.weather[0].has("SN"));
    assert_eq!(m.weather[1].phenomena, ["DS", "SS"]);
    assert_eq!(m.clouds[0].convective, Some(Convective::Cumulonimbus));
    assert_eq!(m.clouds.len(), 3);
    close_opt(m.wind.and_then(|w| w.gust_m_s), 60.0 * 0.514444, 1e-9);
    assert_eq!(m.pressure_hpa, Some(1014.0));
}

#[test]
fn fog_with_vertical_visibility() {
    let m = ok("KJMS 092242Z AUTO 14014KT 1/4SM FG VV002 00/M01 A2963 RMK AO2 T00001006");
    assert!(m.auto);
    close_opt(m.visibility_m, 402.336, 1e-6);
    assert_eq!(m.weather.len(), 1);
    assert_eq!(m.weather[0].phenomena, ["FG"]);
    assert_eq!(m.weather[0].descriptor, None);
    assert!(m.clouds.is_empty());
    close_opt(m.vertical_visibility_m, 60.96, 1e-6);
    assert_eq!(m.temperature_c, Some(0.0));
    assert!(m.temperature_c.is_some_and(|t| t.is_sign_positive()));
    assert_eq!(m.dewpoint_c, Some(-1.0));

    // Metres per second, 100 m visibility, RVR `M0200`, fog, VV001.
    let m = ok(
        "METAR USPP 100330Z 26002MPS 0100 R21/M0200 FG VV001 02/02 Q1028 R21/090060 NOSIG RMK QBB030 QFE760=",
    );
    assert_eq!(m.wind.map(|w| w.speed_m_s), Some(2.0));
    assert_eq!(m.visibility_m, Some(100.0));
    close_opt(m.vertical_visibility_m, 30.48, 1e-6);
    assert_eq!(m.pressure_hpa, Some(1028.0));

    let m = ok("KMDJ 092235Z AUTO 02018KT M1/4SM FZFG OVC003 A3002 RMK A01");
    close_opt(m.visibility_m, 402.336, 1e-6);
    assert_eq!(m.weather[0].descriptor.as_deref(), Some("FZ"));
    assert_eq!(m.weather[0].phenomena, ["FG"]);
    assert_eq!((m.temperature_c, m.dewpoint_c), (None, None));
}

#[test]
fn mixed_number_statute_miles_over_two_groups() {
    let m = ok(
        "METAR CYEG 131700Z 34010KT 1 1/2SM R30/5000VP6000FT/U R02/5000FT/N -SN SCT004 BKN007 OVC011 M01/M03 A3007 RMK SN3SF1SC3SC1 /S02/ SLP220=",
    );
    close_opt(m.visibility_m, 1.5 * 1609.344, 1e-6);
    assert_eq!(m.weather.len(), 1);
    assert_eq!(m.weather[0].intensity, Intensity::Light);
    assert_eq!(m.weather[0].phenomena, ["SN"]);
    assert_eq!(m.clouds.len(), 3);
    assert_eq!(m.clouds[2].cover, Cover::Overcast);
    assert_eq!((m.temperature_c, m.dewpoint_c), (Some(-1.0), Some(-3.0)));
    close_opt(m.pressure_hpa, 30.07 * 33.8639, 1e-9);

    let m = ok(
        "KVNY 092246Z 09005KT 1 3/4SM R16R/5000VP6000FT +RA BR FEW008 BKN018 OVC035 12/11 A2970 RMK AO2 P0023",
    );
    close_opt(m.visibility_m, 1.75 * 1609.344, 1e-6);
    assert_eq!(m.weather.len(), 2);

    // The other statute-mile forms.
    let vis =
        |group: &str| ok(&format!("KXYZ 011200Z 00000KT {group} CLR 10/05 A2992")).visibility_m;
    close_opt(vis("P6SM"), 6.0 * 1609.344, 1e-6);
    close_opt(vis("1/2SM"), 0.5 * 1609.344, 1e-6);
    close_opt(vis("M1/4SM"), 0.25 * 1609.344, 1e-6);
    close_opt(vis("2 1/4SM"), 2.25 * 1609.344, 1e-6);
    close_opt(vis("3SM"), 3.0 * 1609.344, 1e-6);
    assert_eq!(vis("9999"), Some(10_000.0));
    assert_eq!(vis("0800"), Some(800.0));
    assert_eq!(vis("4000NDV"), Some(4000.0));
    assert_eq!(vis("////"), None);
}

#[test]
fn variable_wind_and_wind_units() {
    let m = ok("METAR LSGG 092050Z VRB01KT CAVOK 19/14 Q1022 NOSIG=");
    let wind = m.wind.expect("wind");
    assert_eq!(wind.direction_deg, None);
    close(wind.speed_m_s, 0.514444, 1e-9);

    let wind = |group: &str| ok(&format!("EDDF 011200Z {group} 9999 NSC 10/05 Q1013")).wind;
    let calm = wind("00000KT").expect("calm wind");
    assert_eq!((calm.direction_deg, calm.speed_m_s), (Some(0.0), 0.0));
    close(wind("18036KMH").expect("wind").speed_m_s, 10.0, 1e-9);
    let mps = wind("24008G15MPS").expect("wind");
    assert_eq!((mps.speed_m_s, mps.gust_m_s), (8.0, Some(15.0)));
    close(
        wind("VRB03G105KT")
            .expect("wind")
            .gust_m_s
            .unwrap_or_default(),
        105.0 * 0.514444,
        1e-9,
    );
    assert_eq!(wind("/////KT"), None);
    assert_eq!(err("EDDF 011200Z 37010KT 9999").token, "37010KT");
    assert_eq!(err("EDDF 011200Z 2701KT 9999").token, "2701KT");
}

#[test]
fn runway_visual_range_and_other_skipped_groups() {
    let m = ok(
        "EGLL 011200Z 24008KT 0600 R04R/P1500N R22L/0600V1000FT/U R09L/////// FG VV002 05/05 Q1013 RERA WS R04 NOSIG",
    );
    assert_eq!(m.visibility_m, Some(600.0));
    assert_eq!(m.weather.len(), 1);
    assert!(m.weather[0].has("FG"));
    close_opt(m.vertical_visibility_m, 60.96, 1e-6);
    assert_eq!(m.pressure_hpa, Some(1013.0));

    let m = ok(
        "METAR LLBG 110620Z 19014KT 1200 R08/2000 R26/2000 R30/2000 DS VV012 12/M00 Q1010 BECMG 20020G30KT 2500 DU NSC RMK REP AT 0535Z VIS 2500M IN APCH RWY21=",
    );
    assert_eq!(m.visibility_m, Some(1200.0));
    assert!(m.weather[0].has("DS"));
    assert_eq!(m.dewpoint_c, Some(0.0));
    assert!(
        !m.no_significant_cloud,
        "NSC is in the BECMG trend, not the observation"
    );

    // Directional minimum visibility is accepted and ignored.
    let m = ok(
        "SPECI MROC 111928Z 25010KT 210V290 9999 4000N -TSRA FEW020CB FEW030 SCT100 25/23 A2997 NOSIG",
    );
    assert_eq!(m.visibility_m, Some(10_000.0));
    assert_eq!(m.weather[0].phenomena, ["RA"]);
}

#[test]
fn automatic_station_groups() {
    // Missing visibility, weather not observed, cloud cover unknown.
    let m = ok("YCBB 092100Z AUTO 09005KT //// // ////// 20/17 Q1017");
    assert!(m.auto);
    assert_eq!(m.visibility_m, None);
    assert!(m.weather.is_empty() && m.clouds.is_empty());

    let m =
        ok("METAR EGPF 092050Z AUTO 22017KT 7000 -RA FEW028/// BKN033/// //////TCU 12/09 Q1010=");
    assert_eq!(
        m.clouds,
        vec![
            layer(Cover::Few, 2800.0, None),
            layer(Cover::Broken, 3300.0, None)
        ]
    );

    let m = ok("YBAS 092100Z AUTO /////KT 9999 // NCD 27/13 Q1011 RF00.0////./");
    assert_eq!(m.wind, None);
    assert!(m.no_significant_cloud);

    let m = ok("KXYZ 011200Z AUTO 00000KT 10SM BKN/// VV/// ///// Q////");
    assert_eq!(
        m.clouds,
        vec![CloudGroup {
            cover: Cover::Broken,
            base_m: None,
            convective: None
        }]
    );
    assert_eq!(m.vertical_visibility_m, None);
    assert_eq!(
        (m.temperature_c, m.dewpoint_c, m.pressure_hpa),
        (None, None, None)
    );

    let m = ok(
        "METAR NZSP 091750Z 11009KT 9999 IC FEW015 M70/ A2823 RMK CLN AIR 10009KT ALL WNDS GRID=",
    );
    assert_eq!((m.temperature_c, m.dewpoint_c), (Some(-70.0), None));
}

#[test]
fn header_variants() {
    let m = ok(
        "METAR COR GQNO 111900Z VRB03KT 3000 TSRA FEW020 FEW030TCU FEW033CB 23/23 Q1010 TEMPO 6000 TSRA=",
    );
    assert_eq!(m.station, "GQNO");
    assert_eq!(m.clouds[1].convective, Some(Convective::ToweringCumulus));
    let m = ok("METAR KTPA 102242Z COR 08004KT 10SM TS OVC026CB 28/22 A2998 RMK AO2");
    assert_eq!(
        m.time,
        Some(ObservationTime {
            day: 10,
            hour: 22,
            minute: 42
        })
    );
    assert!(ok("SPECI KXYZ 011200Z AUTO 00000KT 10SM CLR 10/05 A2992").auto);
    assert!(ok("KXYZ 011200Z 00000KT 10SM SKC 10/05 A2992").no_significant_cloud);
    // Everything after RMK / a trend is ignored, however odd.
    let m = ok("YSCB 092130Z 07008KT 9999 SCT014 BKN022 17/13 Q1020 FM0030 07010KT 9999 SCT030");
    assert_eq!(m.clouds.len(), 2);
    assert_eq!(
        ok("KXYZ 011200Z 00000KT 10SM CLR 10/05 A2992 RMK XYZ999 $").station,
        "KXYZ"
    );
}

#[test]
fn lower_case_is_accepted_and_errors_quote_the_original_text() {
    let upper = ok("KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012");
    let lower = ok("kjfk 221651z 31012g20kt 10sm few045 sct120 bkn250 12/m02 a3012");
    assert_eq!(upper, lower);
    assert_eq!(err("kjfk 221651z 31012kt 10sm xyz999").token, "xyz999");
}

#[test]
fn unknown_group_is_named_with_its_position() {
    let report = "KJFK 221651Z 31012KT 10SM XYZ999";
    let e = err(report);
    assert_eq!(e.token, "XYZ999");
    assert_eq!(e.index, 4);
    assert_eq!(e.position, 26);
    assert_eq!(report.get(e.position..), Some("XYZ999"));
    let text = e.to_string();
    assert!(text.contains("XYZ999") && text.contains("26"), "{text}");

    // In METAR order or not at all: clouds after the temperature are an error.
    let e = err("KJFK 221651Z 31012KT 10SM 12/M02 FEW045 A3012");
    assert_eq!((e.token.as_str(), e.index, e.position), ("FEW045", 5, 33));
    // Positions count characters, not bytes.
    let e = err("KJFK 221651Z 31012KT 10SM É1");
    assert_eq!((e.token.as_str(), e.position), ("É1", 26));
}

#[test]
fn garbage_gives_errors_not_panics() {
    for (report, token, message) in [
        ("", "", "empty"),
        ("   \t\n", "", "empty"),
        ("=", "", "empty"),
        ("METAR", "", "station"),
        ("1ABC 221651Z", "1ABC", "station"),
        ("KJFKX 221651Z", "KJFKX", "station"),
        ("KJFK 321651Z 31012KT 10SM", "321651Z", "day"),
        ("KJFK 001651Z 31012KT 10SM", "001651Z", "day"),
        ("KJFK 222451Z 31012KT 10SM", "222451Z", "hour"),
        ("KJFK 221660Z 31012KT 10SM", "221660Z", "minute"),
        ("KJFK 22165AZ 31012KT", "22165AZ", "time"),
        ("METAR CYSY NIL=", "NIL", "NIL"),
        ("KJFK 221651Z NIL", "NIL", "NIL"),
        ("KJFK 221651Z 31012KT 1/0SM", "1/0SM", "statute miles"),
        ("KJFK 221651Z 31012KT 10SM WS", "WS", "wind shear"),
        ("KJFK 221651Z 31012KT 10SM ☁☁☁", "☁☁☁", "non-ASCII"),
        ("ÄÖÜ", "ÄÖÜ", "non-ASCII"),
        // METARs are ASCII throughout, remarks included.
        ("KJFK 221651Z 31012KT 10SM RMK ☁", "☁", "non-ASCII"),
        ("KJFK 221651Z 31012KT 10SM -", "-", "group"),
        ("KJFK 221651Z 31012KT 10SM +", "+", "group"),
        ("KJFK 221651Z 31012KT 10SM VC", "VC", "group"),
        ("KJFK 221651Z 31012KT 10SM M", "M", "group"),
        ("KJFK 221651Z 31012KT 10SM /", "/", "group"),
        (
            "KJFK 221651Z 31012KT 9999999999SM",
            "9999999999SM",
            "statute miles",
        ),
        ("KJFK 221651Z 31012KT 10SM Q1013 Q", "Q", "group"),
    ] {
        let e = err(report);
        assert_eq!(e.token, token, "{report:?}: {e}");
        assert!(e.message.contains(message), "{report:?}: {e}");
    }
}

#[test]
fn truncated_and_mutated_reports_never_panic() {
    // Every prefix (at character boundaries) of every real report, with and without a stray
    // non-ASCII character spliced in, must give a result rather than a panic.
    for report in reports() {
        for (at, _) in report.char_indices() {
            let prefix = report.get(..at).unwrap_or_default();
            let _ = parse(prefix);
            let _ = parse(&format!(
                "{prefix}é{}",
                report.get(at..).unwrap_or_default()
            ));
        }
    }
    // A deterministic scramble of METAR-ish fragments.
    let pieces = [
        "KJFK", "221651Z", "/", "//", "M", "P", "SM", "1", "1/", "/2SM", "KT", "G", "V", "VRB",
        "R04", "/P", "CAVOK", "FEW", "CB", "VV", "Q", "A", "-", "+", "VC", "TS", "RA", "9999",
        "NDV", "WS", "ALL", " ", " ", "RMK", "=", "é", "\u{0}", "00", "360", "361",
    ];
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    for _ in 0..20_000 {
        let mut report = String::new();
        for _ in 0..(state % 24) {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            report.push_str(pieces[(state % pieces.len() as u64) as usize]);
        }
        if let Ok(m) = parse(&report) {
            assert_eq!(m.station.len(), 4, "{report:?}");
        }
    }
}

#[test]
fn helpers_and_serialisation() {
    assert_eq!(Cover::Few.oktas(), (1, 2));
    assert_eq!(Cover::Scattered.oktas(), (3, 4));
    assert_eq!(Cover::Broken.oktas(), (5, 7));
    assert_eq!(Cover::Overcast.oktas(), (8, 8));

    let m = ok("METAR LRTR 101600Z 11017KT 9999 TS VCSH FEW020 SCT045CB 18/09 Q1004=");
    let json = serde_json::to_value(&m).expect("serialises");
    assert_eq!(json["station"], "LRTR");
    assert_eq!(json["time"]["day"], 10);
    assert_eq!(json["weather"][1]["intensity"], "InVicinity");
    assert_eq!(json["clouds"][1]["convective"], "Cumulonimbus");
    assert_eq!(json["pressure_hpa"], 1004.0);
}
