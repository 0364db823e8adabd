//! The built-in presets, embedded from `crates/scene/presets/*.toml`.

use std::sync::OnceLock;

/// Name and TOML source of every preset, in the order [`presets`] lists them.
const SOURCES: &[(&str, &str)] = &[
    ("cumulus-noon", include_str!("../presets/cumulus-noon.toml")),
    (
        "stratocumulus-overcast",
        include_str!("../presets/stratocumulus-overcast.toml"),
    ),
    ("sunset", include_str!("../presets/sunset.toml")),
    ("above-clouds", include_str!("../presets/above-clouds.toml")),
    ("inside-layer", include_str!("../presets/inside-layer.toml")),
    ("storm", include_str!("../presets/storm.toml")),
    ("dawn", include_str!("../presets/dawn.toml")),
    ("noon", include_str!("../presets/noon.toml")),
    ("dusk", include_str!("../presets/dusk.toml")),
    ("night", include_str!("../presets/night.toml")),
    ("kuwahara-day", include_str!("../presets/kuwahara-day.toml")),
    (
        "kuwahara-dusk",
        include_str!("../presets/kuwahara-dusk.toml"),
    ),
    (
        "kuwahara-night",
        include_str!("../presets/kuwahara-night.toml"),
    ),
    ("rainbow", include_str!("../presets/rainbow.toml")),
    ("lens-flare", include_str!("../presets/lens-flare.toml")),
];

/// The name of the preset that [`Scene::default`](crate::Scene::default) equals and that files
/// without `base = "..."` start from.
pub const DEFAULT_PRESET: &str = "cumulus-noon";

/// A built-in preset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PresetInfo {
    /// The name to pass to [`Scene::preset`](crate::Scene::preset) or to write in `base = "..."`.
    pub name: &'static str,
    /// One line saying what the preset shows (its TOML's top-level `description`).
    pub description: String,
    /// The preset's TOML: partial, stating only what differs from its base.
    pub source: &'static str,
}

/// Every built-in preset, the default (`cumulus-noon`) first.
pub fn presets() -> &'static [PresetInfo] {
    static PRESETS: OnceLock<Vec<PresetInfo>> = OnceLock::new();
    PRESETS.get_or_init(|| {
        SOURCES
            .iter()
            .map(|&(name, source)| PresetInfo {
                name,
                description: toml::from_str::<toml::Table>(source)
                    .ok()
                    .and_then(|t| t.get("description")?.as_str().map(str::to_owned))
                    .unwrap_or_default(),
                source,
            })
            .collect()
    })
}

/// The TOML source of the preset called `name`.
pub(crate) fn source(name: &str) -> Option<&'static str> {
    SOURCES.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// The names of all presets.
pub(crate) fn names() -> Vec<&'static str> {
    SOURCES.iter().map(|(n, _)| *n).collect()
}
