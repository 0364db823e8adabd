//! Weather-service JSON (seed 001: a Baidu weather API response) mapped to a weather state:
//! the condition text (`result.now.text`) picks the state, the wind class (`wind_class`, a
//! Beaufort force such as "2级") sets the wind speed and `wind_dir` its direction, and the
//! place (`result.location`, by district code or name) with the local time of the reading
//! (`result.now.uptime`) sets the scene's `[sky]`, so the sun and moon are the city's.

use serde_json::Value;
use stratus_scene::Scene;

use crate::derive::Derived;
use crate::states::{self};
use crate::{WeatherError, haze};

/// Condition texts (Chinese as the service sends them, and English) and their states. The
/// first entry whose text the condition contains wins, so the specific ones come first.
const CONDITIONS: [(&str, &str); 30] = [
    ("雷", "thunderstorm"),
    ("thunder", "thunderstorm"),
    ("雪", "snow"),
    ("snow", "snow"),
    ("雨", "rain"),
    ("rain", "rain"),
    ("shower", "rain"),
    ("drizzle", "rain"),
    ("大雾", "fog"),
    ("雾", "fog"),
    ("fog", "fog"),
    ("霾", "mist"),
    ("mist", "mist"),
    ("haze", "mist"),
    ("沙", "mist"),
    ("尘", "mist"),
    ("dust", "mist"),
    ("sand", "mist"),
    ("烟", "mist"),
    ("smoke", "mist"),
    ("阴", "overcast"),
    ("overcast", "overcast"),
    ("多云", "scattered"),
    ("partly", "scattered"),
    ("cloudy", "broken"),
    ("少云", "few"),
    ("few", "few"),
    ("晴", "clear"),
    ("sunny", "clear"),
    ("clear", "clear"),
];

/// Mean wind speed (m/s) of Beaufort forces 0-12 (WMO's ranges, midpoints; force 12 its
/// lower bound).
const BEAUFORT_M_S: [f64; 13] = [
    0.1, 0.9, 2.5, 4.4, 6.7, 9.4, 12.3, 15.5, 18.9, 22.6, 26.4, 30.5, 32.7,
];

/// Compass names of wind directions (where the wind comes from), degrees.
const DIRECTIONS: [(&str, f64); 16] = [
    ("东北", 45.0),
    ("东南", 135.0),
    ("西南", 225.0),
    ("西北", 315.0),
    ("北", 0.0),
    ("东", 90.0),
    ("南", 180.0),
    ("西", 270.0),
    ("northeast", 45.0),
    ("southeast", 135.0),
    ("southwest", 225.0),
    ("northwest", 315.0),
    ("north", 0.0),
    ("east", 90.0),
    ("south", 180.0),
    ("west", 270.0),
];

/// A city the service may name: its district code (GB/T 2260, the code the service is queried
/// with), its names, and where it is (the city centre, degrees; GeoNames). The three the
/// weather system is tested with.
pub struct City {
    /// The administrative district code (`result.location.id`).
    pub code: &'static str,
    /// The names the service uses (`name`, `city`) and an English one.
    pub names: [&'static str; 3],
    /// Latitude, degrees north.
    pub latitude_deg: f64,
    /// Longitude, degrees east.
    pub longitude_deg: f64,
    /// The offset of local (civil) time from UTC, hours: China Standard Time, the one time
    /// zone of China, Urumqi included.
    pub utc_offset_h: f64,
}

/// The cities the service's `location` is matched against.
pub const CITIES: [City; 3] = [
    City {
        code: "330100",
        names: ["杭州", "杭州市", "Hangzhou"],
        latitude_deg: 30.2741,
        longitude_deg: 120.1551,
        utc_offset_h: 8.0,
    },
    City {
        code: "330200",
        names: ["宁波", "宁波市", "Ningbo"],
        latitude_deg: 29.8683,
        longitude_deg: 121.5440,
        utc_offset_h: 8.0,
    },
    City {
        code: "650100",
        names: ["乌鲁木齐", "乌鲁木齐市", "Urumqi"],
        latitude_deg: 43.8256,
        longitude_deg: 87.6168,
        utc_offset_h: 8.0,
    },
];

/// The city `location` names, by its district code first, then by its names.
fn city(location: &Value) -> Option<&'static City> {
    let text = |k: &str| location.get(k).and_then(Value::as_str);
    if let Some(id) = text("id") {
        if let Some(c) = CITIES.iter().find(|c| c.code == id) {
            return Some(c);
        }
    }
    ["name", "city"].into_iter().filter_map(text).find_map(|n| {
        CITIES
            .iter()
            .find(|c| c.names.iter().any(|m| m.eq_ignore_ascii_case(n)))
    })
}

/// `uptime` (`YYYYMMDDhhmmss`, local time at `offset_h` hours from UTC) as a UTC instant.
fn uptime_utc(uptime: &str, offset_h: f64) -> Result<stratus_astro::UtcDateTime, WeatherError> {
    let bad = |why: String| {
        json_error(format!(
            "`result.now.uptime` = {uptime:?}: {why} (expected local time as YYYYMMDDhhmmss, e.g. \"20230324202000\")"
        ))
    };
    if uptime.len() != 14 || !uptime.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad("not 14 digits".into()));
    }
    let n = |r: std::ops::Range<usize>| uptime[r].parse::<u32>().expect("digits");
    let local = stratus_astro::UtcDateTime::new(
        n(0..4) as i32,
        n(4..6),
        n(6..8),
        n(8..10),
        n(10..12),
        f64::from(n(12..14)),
    )
    .map_err(|e| bad(e.to_string()))?;
    Ok(local.plus_seconds(-offset_h * 3600.0))
}

fn field<'a>(v: &'a Value, path: &str) -> Option<&'a Value> {
    path.split('.').try_fold(v, |v, k| v.get(k))
}

fn json_error(message: String) -> WeatherError {
    WeatherError::Json(message)
}

/// The scene for a weather-service response `json` (seed 001's format), built on `base`.
pub fn scene_from_service_json(json: &str, base: &Scene) -> Result<Derived, WeatherError> {
    let v: Value = serde_json::from_str(json).map_err(|e| {
        json_error(format!(
            "not valid JSON at line {}, column {}: {e}",
            e.line(),
            e.column()
        ))
    })?;
    let now = field(&v, "result.now").ok_or_else(|| {
        json_error("no `result.now` object (expected the weather service's response)".into())
    })?;
    let text = now.get("text").and_then(Value::as_str).ok_or_else(|| {
        json_error("`result.now.text` (the condition) is missing or not a string".into())
    })?;
    let lower = text.to_lowercase();
    let (_, name) = CONDITIONS
        .iter()
        .find(|(t, _)| lower.contains(t))
        .ok_or_else(|| {
            json_error(format!(
                "`result.now.text` = {text:?}: unknown condition (known: 晴 多云 阴 雨 雪 雷阵雨 雾 霾, or sunny, cloudy, overcast, rain, snow, thunderstorm, fog, mist)"
            ))
        })?;
    let state = states::find(name)?;
    let mut scene = base.clone();
    state.params.apply(&mut scene);
    let mut notes = vec![format!(
        "state: {name} (condition {text:?}): {}",
        state.about
    )];
    if let Some(class) = now.get("wind_class") {
        let s = class
            .as_str()
            .map(str::to_owned)
            .unwrap_or_else(|| class.to_string());
        let digits: String = s.chars().filter(char::is_ascii_digit).collect();
        let force: usize = digits.parse().map_err(|_| {
            json_error(format!(
                "`result.now.wind_class` = {s:?}: expected a Beaufort force such as \"2级\""
            ))
        })?;
        let speed = BEAUFORT_M_S[force.min(12)];
        scene.clouds.wind_speed_m_s = speed;
        notes.push(format!("wind: Beaufort {force} -> {speed} m/s"));
    }
    if let Some(dir) = now.get("wind_dir").and_then(Value::as_str) {
        let lower = dir.to_lowercase();
        if let Some((_, from)) = DIRECTIONS.iter().find(|(n, _)| lower.contains(n)) {
            scene.clouds.wind_direction_deg = (from + 180.0) % 360.0;
            notes.push(format!(
                "wind from {dir} ({from} deg) -> blowing toward {} deg",
                scene.clouds.wind_direction_deg
            ));
        } else {
            notes.push(format!("wind direction {dir:?}: none recognised, kept"));
        }
    }
    // Rain, snow and a thunderstorm's rain and lightning, as a report's (the condition gives no
    // intensity: a moderate storm's rate).
    let falls = match *name {
        "rain" | "thunderstorm" => Some(stratus_scene::PrecipitationKind::Rain),
        "snow" => Some(stratus_scene::PrecipitationKind::Snow),
        _ => None,
    };
    let flashes = (*name == "thunderstorm").then_some(crate::derive::MODERATE_FLASHES_PER_MINUTE);
    crate::derive::precipitate(&mut scene, falls, flashes, &mut notes);
    haze_from_json(now, &lower, &mut scene, &mut notes)?;
    place(&v, now, &mut scene, &mut notes)?;
    Ok(Derived {
        scene,
        state,
        notes,
    })
}

/// The aerosol from the reading's visibility (`result.now.vis`, metres) or, without one, from
/// a haze, dust or smoke condition (霾, 沙, 尘, 烟).
fn haze_from_json(
    now: &Value,
    condition: &str,
    scene: &mut Scene,
    notes: &mut Vec<String>,
) -> Result<(), WeatherError> {
    let has = |words: &[&str]| words.iter().any(|w| condition.contains(w));
    let kind = if has(&["烟", "smoke"]) {
        haze::Aerosol::Smoke
    } else if has(&["沙", "尘", "dust", "sand"]) {
        haze::Aerosol::Dust
    } else if has(&[
        "雨", "雪", "雾", "rain", "snow", "drizzle", "shower", "fog", "mist",
    ]) {
        haze::Aerosol::Water
    } else {
        haze::Aerosol::Continental
    };
    let named = has(&["霾", "haze", "沙", "尘", "dust", "sand", "烟", "smoke"]);
    // A number the reading may give, within `range`, or an error naming it.
    let number = |key: &str, range: std::ops::RangeInclusive<f64>, what: &str| match now.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => v
            .as_f64()
            .filter(|x| range.contains(x))
            .map(Some)
            .ok_or_else(|| {
                json_error(format!(
                    "`result.now.{key}` = {v}: expected {what}, a number in {}..={}",
                    range.start(),
                    range.end()
                ))
            }),
    };
    let visibility = number("vis", 1.0..=1e6, "the visibility in metres")?;
    let rh = number("rh", 0.0..=100.0, "the relative humidity in percent")?.map(|p| p / 100.0);
    let pm25 = number("pm25", 0.0..=5000.0, "PM2.5 in µg/m³")?;
    let rayleigh = scene.atmosphere.air.rayleigh_scattering[1];
    let (v, why) = match (visibility, pm25) {
        // A measured visibility under 10 km says it all.
        (Some(v), _) if v < haze::CLEAR_VISIBILITY_M => (v, format!("visibility {v:.0} m")),
        // Fine particles, grown by the humidity (50% where none is given).
        (_, Some(pm)) => {
            let h = rh.unwrap_or(0.5);
            let v = haze::visibility_for_pm25(pm, h, rayleigh).max(visibility.unwrap_or(0.0));
            (
                v,
                format!(
                    "PM2.5 {pm} µg/m³ at {:.0}% humidity{} -> visibility {v:.0} m ({} m²/g dry, growth {:.2})",
                    100.0 * h,
                    if rh.is_none() {
                        " (none given: 50%)"
                    } else {
                        ""
                    },
                    haze::PM25_EFFICIENCY_M2_PER_G,
                    haze::growth(h)
                ),
            )
        }
        (None, None) if named => (
            haze::HAZE_VISIBILITY_M,
            format!(
                "condition {condition:?} without a visibility: {:.0} m",
                haze::HAZE_VISIBILITY_M
            ),
        ),
        _ => {
            // Only the humidity: the clean air's aerosol grown to it.
            if let Some(h) = rh {
                haze::humid(scene, h, notes);
            }
            return Ok(());
        }
    };
    haze::apply(scene, v, kind, &why, notes);
    Ok(())
}

/// The city and the reading's time, into the scene's `[sky]`: the sun (and moon) of that place
/// at that instant, as `stratus render --date --lat --lon` sets them.
fn place(
    v: &Value,
    now: &Value,
    scene: &mut Scene,
    notes: &mut Vec<String>,
) -> Result<(), WeatherError> {
    let Some(location) = field(v, "result.location") else {
        notes.push("no `result.location`: the sun is the base scene's".into());
        return Ok(());
    };
    let Some(city) = city(location) else {
        let known: Vec<String> = CITIES
            .iter()
            .map(|c| format!("{} ({})", c.names[0], c.code))
            .collect();
        notes.push(format!(
            "location {}: not a known city ({}): the sun is the base scene's",
            location,
            known.join(", ")
        ));
        return Ok(());
    };
    let Some(uptime) = now.get("uptime").and_then(Value::as_str) else {
        notes.push(format!(
            "place: {} ({}), but no `result.now.uptime`: without the time the sun is the base scene's",
            city.names[0], city.code
        ));
        return Ok(());
    };
    let date = uptime_utc(uptime, city.utc_offset_h)?;
    scene.sky = stratus_scene::Sky {
        date_utc: Some(date),
        latitude_deg: Some(city.latitude_deg),
        longitude_deg: Some(city.longitude_deg),
    };
    // The date and place set the sun: a direction of the base scene's would contradict it.
    scene.sun.direction = None;
    notes.push(format!(
        "place: {} ({}, {}) at {:.4} N, {:.4} E; reading at {uptime} local (UTC{:+}) = {date}",
        city.names[0],
        city.names[2],
        city.code,
        city.latitude_deg,
        city.longitude_deg,
        city.utc_offset_h
    ));
    // The debug readout the weather system keeps beside the render: the sun and moon of that
    // place and time, and the day's sunrise and sunset in local time.
    let at = stratus_astro::Place::new(city.latitude_deg, city.longitude_deg)
        .map_err(|e| json_error(format!("{}: {e}", city.names[2])))?;
    notes.push(format!(
        "at the reading: {}",
        stratus_astro::readout(at, date, city.utc_offset_h)
    ));
    let sun = stratus_astro::sun(at, date);
    if sun.elevation_deg < 0.0 && !scene.atmosphere.sky.is_physical() {
        notes.push(
            "the sun is down, but the base scene's analytic sky does not darken at night: take a physical-sky base (`--preset night`) for the night sky".into(),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEED: &str = r#"{"status": 0, "result": {"location": {"country": "中国", "province": "浙江省", "city": "杭州市", "name": "杭州", "id": "330100"}, "now": {"text": "多云", "temp": 8, "feels_like": 7, "rh": 81, "wind_class": "2级", "wind_dir": "西北风", "uptime": "20230324202000"}}, "message": "success"}"#;

    #[test]
    fn the_seed_example_maps_to_scattered_cloud_and_a_northwest_breeze() {
        let d = scene_from_service_json(SEED, &Scene::default()).unwrap();
        assert_eq!(d.state.name, "scattered");
        assert_eq!(d.scene.clouds.wind_speed_m_s, 2.5);
        assert_eq!(d.scene.clouds.wind_direction_deg, 135.0);
        d.scene.validate().unwrap();
    }

    #[test]
    fn the_seed_example_places_the_sun_over_hangzhou_at_the_reading_time() {
        let d = scene_from_service_json(SEED, &Scene::default()).unwrap();
        assert_eq!(d.scene.sky.latitude_deg, Some(30.2741));
        assert_eq!(d.scene.sky.longitude_deg, Some(120.1551));
        // 20:20 in Hangzhou (UTC+8) is 12:20 UTC.
        let expected = stratus_astro::UtcDateTime::new(2023, 3, 24, 12, 20, 0.0).unwrap();
        let off = d.scene.sky.date_utc.unwrap().seconds_since(expected);
        assert!(off.abs() < 1e-3, "{off} s from 2023-03-24T12:20:00Z");
        assert!(d.notes.iter().any(|n| n.contains("杭州")), "{:?}", d.notes);
        d.scene.validate().unwrap();
        // After dark in Hangzhou: the sun is below the horizon.
        assert!(d.scene.sun_elevation_deg() < 0.0);
    }

    #[test]
    fn cities_are_found_by_code_or_name_and_unknown_ones_keep_the_base_sun() {
        let urumqi = SEED.replace("\"id\": \"330100\"", "\"id\": \"650100\"");
        let d = scene_from_service_json(&urumqi, &Scene::default()).unwrap();
        assert_eq!(d.scene.sky.latitude_deg, Some(43.8256));
        let ningbo = SEED
            .replace("\"id\": \"330100\"", "\"id\": \"999999\"")
            .replace("杭州", "宁波");
        let d = scene_from_service_json(&ningbo, &Scene::default()).unwrap();
        assert_eq!(d.scene.sky.longitude_deg, Some(121.5440));
        let nowhere = SEED
            .replace("\"id\": \"330100\"", "\"id\": \"999999\"")
            .replace("杭州", "台州");
        let d = scene_from_service_json(&nowhere, &Scene::default()).unwrap();
        assert!(d.scene.sky.is_unset());
        assert!(
            d.notes.iter().any(|n| n.contains("not a known city")),
            "{:?}",
            d.notes
        );
    }

    #[test]
    fn the_readings_visibility_or_a_haze_condition_sets_the_aerosol() {
        let with_vis = SEED.replace("\"rh\": 81,", "\"rh\": 81, \"vis\": 4000,");
        let d = scene_from_service_json(&with_vis, &Scene::default()).unwrap();
        assert!((haze::visibility(&d.scene.atmosphere.air) - 4000.0).abs() < 1e-6);
        // 霾 (haze) without a visibility: the least haze it says there is.
        let d = scene_from_service_json(&SEED.replace("多云", "霾"), &Scene::default()).unwrap();
        assert!((haze::visibility(&d.scene.atmosphere.air) - haze::HAZE_VISIBILITY_M).abs() < 1e-6);
        // 浮尘 (floating dust): dust aerosol.
        let d = scene_from_service_json(&SEED.replace("多云", "浮尘"), &Scene::default()).unwrap();
        let air = &d.scene.atmosphere.air;
        let albedo = air.mie_scattering / (air.mie_scattering + air.mie_absorption);
        assert!((albedo - haze::Aerosol::Dust.albedo()).abs() < 1e-12);
        // A clear, humid reading: the clean air's aerosol grown by 81% humidity (2.24x), still
        // a visibility of about 120 km.
        let far = SEED.replace("\"rh\": 81,", "\"rh\": 81, \"vis\": 25000,");
        for json in [far.as_str(), SEED] {
            let d = scene_from_service_json(json, &Scene::default()).unwrap();
            let air = &d.scene.atmosphere.air;
            let grown = air.mie_scattering / stratus_scene::Air::default().mie_scattering;
            assert!((grown - haze::growth(0.81)).abs() < 1e-12, "{grown}");
            assert!((100e3..140e3).contains(&haze::visibility(air)));
            assert!(
                d.notes.iter().any(|n| n.contains("humidity 81%")),
                "{:?}",
                d.notes
            );
        }
        // PM2.5 at the reading's humidity: Koschmieder's visibility of the grown particles.
        let smog = SEED.replace("\"rh\": 81,", "\"rh\": 81, \"pm25\": 150,");
        let d = scene_from_service_json(&smog, &Scene::default()).unwrap();
        let expected = haze::visibility_for_pm25(150.0, 0.81, 13.558e-6);
        assert!((haze::visibility(&d.scene.atmosphere.air) - expected).abs() < 1e-6);
        assert!((3e3..5e3).contains(&expected), "{expected}");
        // A measured visibility wins over PM2.5.
        let both = SEED.replace("\"rh\": 81,", "\"rh\": 81, \"pm25\": 150, \"vis\": 8000,");
        let d = scene_from_service_json(&both, &Scene::default()).unwrap();
        assert!((haze::visibility(&d.scene.atmosphere.air) - 8000.0).abs() < 1e-6);
        for (bad, key) in [("\"rh\": 181", "rh"), ("\"rh\": \"wet\"", "rh")] {
            let e = scene_from_service_json(&SEED.replace("\"rh\": 81", bad), &Scene::default())
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("result.now.{key}")), "{e}");
        }
        let bad = SEED.replace("\"rh\": 81,", "\"rh\": 81, \"vis\": \"far\",");
        let e = scene_from_service_json(&bad, &Scene::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("result.now.vis"), "{e}");
    }

    #[test]
    fn a_bad_uptime_is_named() {
        for bad in ["2023032420200", "2023-03-24 20:20", "20231324202000"] {
            let e =
                scene_from_service_json(&SEED.replace("20230324202000", bad), &Scene::default())
                    .unwrap_err()
                    .to_string();
            assert!(e.contains("uptime") && e.contains(bad), "{bad}: {e}");
        }
    }

    #[test]
    fn conditions_map_to_states() {
        for (text, state) in [
            ("雷阵雨", "thunderstorm"),
            ("小雨", "rain"),
            ("雨夹雪", "snow"),
            ("阴", "overcast"),
            ("晴", "clear"),
            ("大雾", "fog"),
            ("Light Rain", "rain"),
        ] {
            let json = SEED.replace("多云", text);
            let d = scene_from_service_json(&json, &Scene::default()).unwrap();
            assert_eq!(d.state.name, state, "{text}");
        }
    }

    /// A thundershower rains with shafts and flashes at a moderate storm's rate; light snow
    /// falls as flakes without shafts; a clear sky draws neither.
    #[test]
    fn rain_snow_and_thunder_draw_their_precipitation_and_lightning() {
        let scene = |text: &str| {
            scene_from_service_json(&SEED.replace("多云", text), &Scene::default())
                .unwrap()
                .scene
        };
        let storm = scene("雷阵雨");
        assert_eq!(
            storm.precipitation.kind,
            stratus_scene::PrecipitationKind::Rain
        );
        assert!(storm.precipitation.particles > 0.0 && storm.precipitation.shafts > 0.0);
        assert_eq!(storm.lightning.flashes_per_minute, 20.0);
        let snow = scene("小雪");
        assert_eq!(
            snow.precipitation.kind,
            stratus_scene::PrecipitationKind::Snow
        );
        assert!(snow.precipitation.particles > 0.0 && snow.precipitation.shafts == 0.0);
        assert_eq!(snow.lightning.flashes_per_minute, 0.0);
        let clear = scene("晴");
        assert!(clear.precipitation.is_off() && clear.lightning.is_off());
    }

    #[test]
    fn bad_input_is_named() {
        let e = scene_from_service_json("{", &Scene::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 1"), "{e}");
        let e = scene_from_service_json(&SEED.replace("多云", "火山灰"), &Scene::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("火山灰"), "{e}");
        let e = scene_from_service_json(&SEED.replace("2级", "强"), &Scene::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("wind_class"), "{e}");
    }
}
