//! The METAR parser and the scene derivation on arbitrary text: errors, never panics; a
//! report that parses derives a valid scene.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match stratus_weather::metar::parse(text) {
        Ok(m) => {
            let d = stratus_weather::scene_from_metar(&m, &stratus_scene::Scene::default());
            if let Err(e) = d.scene.validate() {
                panic!("{text:?} derived an invalid scene: {e}");
            }
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
});
