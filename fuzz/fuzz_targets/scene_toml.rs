//! The scene loader and validator on arbitrary text: errors, never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match stratus_scene::Scene::from_toml_str(text, "fuzz.toml") {
        Ok(scene) => {
            // A loaded scene is valid: everything downstream takes it without panicking.
            let _ = scene.validate();
            let _ = scene.uniforms();
            let again = stratus_scene::Scene::from_toml_str(&scene.to_toml(), "again.toml");
            assert!(again.is_ok(), "a scene's own TOML does not load: {again:?}");
        }
        Err(e) => {
            // The error report (with line and column) renders.
            let _ = e.to_string();
        }
    }
});
