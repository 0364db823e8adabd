//! Helpers shared by the tests (not a test itself).

#![allow(dead_code)]

use std::collections::HashMap;

use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::Scene;

/// Noise sets by seed, generated once each (slow in debug builds).
#[derive(Default)]
pub struct NoiseCache(HashMap<u64, NoiseSet>);

impl NoiseCache {
    /// The noise set of `scene`'s seed.
    pub fn get(&mut self, scene: &Scene) -> &NoiseSet {
        let seed = scene.noise.seed;
        self.0.entry(seed).or_insert_with(|| {
            NoiseSet::generate(&NoiseConfig {
                seed,
                ..Default::default()
            })
        })
    }
}

/// The preset `name` at a small size.
pub fn small(name: &str, w: u32, h: u32) -> Scene {
    Scene::preset(name)
        .unwrap_or_else(|e| panic!("preset {name}: {e}"))
        .with_size(w, h)
}
