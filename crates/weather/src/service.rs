//! Weather-service JSON (seed 001: a Baidu weather API response) mapped to a weather state:
//! the condition text (`result.now.text`) picks the state, the wind class (`wind_class`, a
//! Beaufort force such as "2级") sets the wind speed and `wind_dir` its direction.

use serde_json::Value;
use stratus_scene::Scene;

use crate::WeatherError;
use crate::derive::Derived;
use crate::states::{self};

/// Condition texts (Chinese as the service sends them, and English) and their states. The
/// first entry whose text the condition contains wins, so the specific ones come first.
const CONDITIONS: [(&str, &str); 24] = [
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
    Ok(Derived {
        scene,
        state,
        notes,
    })
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
