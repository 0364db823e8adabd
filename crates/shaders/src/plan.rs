//! The frame plan: one backend-neutral description of a frame (which variant, which passes
//! with which entry points, resources, bindings and dispatch sizes, which override values)
//! that both the wgpu and the ash backend execute step by step.
//!
//! Everything here is derived from the reflection manifest of the committed `spirv-out/`
//! (embedded at build time), so adding a pass or a binding touches the WGSL and nothing
//! backend-specific.

use std::collections::BTreeMap;

use stratus_scene::Scene;

use crate::manifest::{Manifest, ModuleManifest, ResourceInfo};

/// The module every frame runs.
pub const MODULE: &str = "clouds";

/// Passes in execution order, by entry point.
pub const PASSES: [&str; 2] = ["march", "composite"];

/// Names of the work counters, in the order of the statistics buffer (the `STAT_*` constants
/// in `wgsl/march.wgsl`).
pub const COUNTERS: [&str; 9] = [
    "pixels",
    "marched_pixels",
    "view_steps",
    "density_evaluations",
    "detail_evaluations",
    "light_samples",
    "exit_transmittance",
    "exit_missed_layer",
    "exit_ground",
];

/// A physical resource of the frame. Several WGSL bindings may name the same resource
/// (`cloud_out` in the march pass and `cloud_in` in the composite pass are one image).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Resource {
    /// The `Frame` uniform block (`FrameUniforms`).
    Frame,
    /// Shape noise, 3D RGBA8.
    Shape,
    /// Detail noise, 3D RGBA8.
    Detail,
    /// Weather map, 2D RGBA8.
    Weather,
    /// Curl noise, 2D RGBA8.
    Curl,
    /// Linear, repeating sampler for the noise textures.
    NoiseSampler,
    /// March output: radiance rgb and transmittance, RGBA32F.
    Cloud,
    /// March output: transmittance-weighted depth, R32F.
    Depth,
    /// Display image, RGBA8.
    Image,
    /// Work counters, `u32` each.
    Stats,
}

impl Resource {
    /// The physical resource a WGSL global stands for.
    pub fn for_binding(name: &str) -> Option<Self> {
        Some(match name {
            "frame" => Self::Frame,
            "shape_tex" => Self::Shape,
            "detail_tex" => Self::Detail,
            "weather_tex" => Self::Weather,
            "curl_tex" => Self::Curl,
            "noise_sampler" => Self::NoiseSampler,
            "cloud_out" | "cloud_in" => Self::Cloud,
            "depth_out" => Self::Depth,
            "image_out" => Self::Image,
            "stats" => Self::Stats,
            _ => return None,
        })
    }
}

impl Resource {
    /// The texel format of an image resource (WGSL spelling), `None` for buffers and samplers.
    pub fn texture_format(self) -> Option<&'static str> {
        match self {
            Self::Shape | Self::Detail | Self::Weather | Self::Curl | Self::Image => {
                Some("rgba8unorm")
            }
            Self::Cloud => Some("rgba32float"),
            Self::Depth => Some("r32float"),
            Self::Frame | Self::NoiseSampler | Self::Stats => None,
        }
    }

    /// Whether a sampled image of this resource may be linearly filtered (8-bit noise yes,
    /// 32-bit float no: not filterable everywhere without an extra feature).
    pub fn filterable(self) -> bool {
        self.texture_format() == Some("rgba8unorm")
    }
}

/// What a backend hands back for one frame. Both backends fill it the same way.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameOutput {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Linear in-scattered radiance (rgb) and transmittance (a), row-major, 4 floats a pixel.
    pub radiance: Vec<f32>,
    /// Transmittance-weighted depth in metres (0 where no cloud), one float a pixel.
    pub depth: Vec<f32>,
    /// The tone-mapped display image, RGBA8, row-major.
    pub image: Vec<u8>,
    /// Work counters by name ([`COUNTERS`]), when the plan gathers them.
    pub stats: Option<BTreeMap<String, u64>>,
    /// Time of every pass, in plan order.
    pub timings: Vec<PassTiming>,
    /// The device that ran the frame, in words.
    pub device: String,
}

/// The measured time of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass name.
    pub pass: String,
    /// Milliseconds.
    pub ms: f64,
    /// `gpu-timestamp` (timestamp queries) or `cpu-wall` (the pass submitted alone and waited
    /// for, where the device has no timestamp queries).
    pub source: &'static str,
}

/// Names the counters read back from the statistics buffer.
pub fn named_counters(raw: &[u32]) -> BTreeMap<String, u64> {
    COUNTERS
        .iter()
        .zip(raw)
        .map(|(n, v)| (n.to_string(), u64::from(*v)))
        .collect()
}

/// One binding of a pass: the manifest's reflection plus the physical resource.
#[derive(Clone, Debug, PartialEq)]
pub struct Binding {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// What the WGSL declares (kind, format, access, dimension).
    pub info: ResourceInfo,
    /// What is bound there.
    pub resource: Resource,
}

/// One compute pass.
#[derive(Clone, Debug, PartialEq)]
pub struct Pass {
    /// Pass name (= entry point name).
    pub name: String,
    /// The entry point.
    pub entry_point: String,
    /// Workgroup size from the manifest.
    pub workgroup_size: [u32; 3],
    /// Workgroups to dispatch.
    pub dispatch: [u32; 3],
    /// Bindings the entry point uses, by binding number.
    pub bindings: Vec<Binding>,
}

/// A whole frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// Module name.
    pub module: String,
    /// The chosen variant.
    pub variant: String,
    /// Every override constant's value in this variant (defaults filled in). wgpu is given
    /// exactly these; the ash backend loads the variant's SPIR-V, where they are baked in.
    pub overrides: BTreeMap<String, f64>,
    /// SPIR-V file of the variant in `spirv-out/`.
    pub spv_file: String,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Whether the statistics counters are gathered.
    pub stats: bool,
    /// Passes in execution order.
    pub passes: Vec<Pass>,
}

/// What a scene needs from the shader: each feature as the minimum value of its override.
#[derive(Clone, Debug, PartialEq)]
pub struct Requirements(pub BTreeMap<&'static str, f64>);

impl Requirements {
    /// The features `scene` uses (and whether the counters are wanted).
    pub fn of(scene: &Scene, stats: bool) -> Self {
        let detail = scene.clouds.detail_strength > 0.0;
        Self(BTreeMap::from([
            (
                "LIGHT_MARCH",
                f64::from(u8::from(scene.quality.light_steps > 0)),
            ),
            (
                "MAX_OCTAVES",
                f64::from(scene.lighting.multiple_scattering.octaves),
            ),
            ("DETAIL", f64::from(u8::from(detail))),
            (
                "CURL",
                f64::from(u8::from(detail && scene.clouds.curl_strength_m > 0.0)),
            ),
            ("STATS", f64::from(u8::from(stats))),
        ]))
    }
}

/// Why no plan could be made.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// The embedded manifest is missing or unreadable.
    #[error(
        "the embedded spirv-out/manifest.json is unusable ({0}); run `cargo xtask build-shaders`"
    )]
    Manifest(String),
    /// No exported variant has every feature the scene uses.
    #[error(
        "no exported shader variant has every feature this scene uses ({0}); add one to wgsl/modules.toml"
    )]
    NoVariant(String),
    /// The image size is out of range.
    #[error("image size {0}x{1}: width and height must be within [1, 16384]")]
    Size(u32, u32),
}

/// The manifest of the committed `spirv-out/`, embedded at build time.
pub fn embedded_manifest() -> Result<Manifest, PlanError> {
    Manifest::from_json(crate::EMBEDDED_MANIFEST).map_err(|e| PlanError::Manifest(e.to_string()))
}

impl FramePlan {
    /// The plan for `scene` at its resolution, from the embedded manifest.
    pub fn for_scene(scene: &Scene, stats: bool) -> Result<Self, PlanError> {
        let manifest = embedded_manifest()?;
        let [w, h] = scene.camera.resolution;
        Self::new(&manifest, &Requirements::of(scene, stats), w, h)
    }

    /// The plan for the given requirements and size.
    pub fn new(
        manifest: &Manifest,
        req: &Requirements,
        width: u32,
        height: u32,
    ) -> Result<Self, PlanError> {
        if !(1..=16384).contains(&width) || !(1..=16384).contains(&height) {
            return Err(PlanError::Size(width, height));
        }
        let module = manifest
            .module(MODULE)
            .ok_or_else(|| PlanError::Manifest(format!("no module `{MODULE}`")))?;
        let (variant, overrides) = choose_variant(module, req)?;
        let mut passes = Vec::new();
        for name in PASSES {
            let ep = module
                .entry_points
                .iter()
                .find(|e| e.name == name)
                .ok_or_else(|| PlanError::Manifest(format!("no entry point `{name}`")))?;
            let bindings = ep
                .uses
                .iter()
                .map(|&[group, binding]| {
                    let info = module
                        .resources
                        .iter()
                        .find(|r| r.group == group && r.binding == binding)
                        .ok_or_else(|| {
                            PlanError::Manifest(format!(
                                "{name} uses unknown binding {group}/{binding}"
                            ))
                        })?;
                    let resource = Resource::for_binding(&info.name).ok_or_else(|| {
                        PlanError::Manifest(format!(
                            "binding `{}` has no resource in the plan",
                            info.name
                        ))
                    })?;
                    Ok(Binding {
                        group,
                        binding,
                        info: info.clone(),
                        resource,
                    })
                })
                .collect::<Result<Vec<_>, PlanError>>()?;
            let wg = ep.workgroup_size;
            passes.push(Pass {
                name: name.to_string(),
                entry_point: name.to_string(),
                workgroup_size: wg,
                dispatch: [width.div_ceil(wg[0]), height.div_ceil(wg[1]), 1],
                bindings,
            });
        }
        Ok(Self {
            module: module.name.clone(),
            spv_file: variant.files.spv.clone(),
            variant: variant.name.clone(),
            overrides,
            width,
            height,
            stats: req.0.get("STATS").is_some_and(|&s| s > 0.0),
            passes,
        })
    }
}

/// The cheapest variant whose every override value is at least what the scene requires;
/// STATS must match exactly (the counting variant is never chosen silently, nor dropped).
/// Cost: the sum of the feature values, octaves counted as a fraction of the largest.
fn choose_variant<'m>(
    module: &'m ModuleManifest,
    req: &Requirements,
) -> Result<(&'m crate::manifest::VariantInfo, BTreeMap<String, f64>), PlanError> {
    let defaults: BTreeMap<String, f64> = module
        .overrides
        .iter()
        .filter_map(|o| Some((o.name.clone(), o.default?)))
        .collect();
    let max_of = |name: &str| {
        module
            .variants
            .iter()
            .filter_map(|v| v.overrides.get(name).or(defaults.get(name)))
            .fold(1.0f64, |a, &b| a.max(b))
    };
    let mut best: Option<(f64, &crate::manifest::VariantInfo, BTreeMap<String, f64>)> = None;
    for v in &module.variants {
        let mut values = defaults.clone();
        values.extend(v.overrides.clone());
        let covers = req.0.iter().all(|(name, &need)| {
            let have = values.get(*name).copied().unwrap_or(0.0);
            if *name == "STATS" {
                have == need
            } else {
                have >= need
            }
        });
        if !covers {
            continue;
        }
        let cost: f64 = req
            .0
            .keys()
            .filter(|n| **n != "STATS")
            .map(|n| values.get(*n).copied().unwrap_or(0.0) / max_of(n))
            .sum();
        if best.as_ref().is_none_or(|(c, _, _)| cost < *c) {
            best = Some((cost, v, values));
        }
    }
    best.map(|(_, v, values)| (v, values)).ok_or_else(|| {
        let wanted: Vec<String> = req
            .0
            .iter()
            .filter(|(_, v)| **v > 0.0)
            .map(|(k, v)| format!("{k} >= {v}"))
            .collect();
        PlanError::NoVariant(wanted.join(", "))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(light: f64, octaves: f64, detail: f64, curl: f64, stats: f64) -> Requirements {
        Requirements(BTreeMap::from([
            ("LIGHT_MARCH", light),
            ("MAX_OCTAVES", octaves),
            ("DETAIL", detail),
            ("CURL", curl),
            ("STATS", stats),
        ]))
    }

    #[test]
    fn picks_the_cheapest_variant_that_covers_the_scene() {
        let m = embedded_manifest().unwrap();
        let p = |r: &Requirements| FramePlan::new(&m, r, 64, 32).unwrap().variant;
        assert_eq!(p(&req(1.0, 2.0, 1.0, 1.0, 0.0)), "full");
        assert_eq!(p(&req(1.0, 2.0, 0.0, 0.0, 0.0)), "soft");
        assert_eq!(p(&req(0.0, 0.0, 0.0, 0.0, 0.0)), "unshadowed");
        assert_eq!(p(&req(0.0, 0.0, 0.0, 0.0, 1.0)), "unshadowed-stats");
        assert_eq!(p(&req(1.0, 2.0, 1.0, 1.0, 1.0)), "full-stats");
    }

    #[test]
    fn never_drops_a_feature() {
        let m = embedded_manifest().unwrap();
        let err = FramePlan::new(&m, &req(1.0, 99.0, 1.0, 1.0, 0.0), 64, 32).unwrap_err();
        assert!(err.to_string().contains("MAX_OCTAVES >= 99"), "{err}");
    }

    #[test]
    fn every_preset_has_a_plan_with_both_passes() {
        for p in stratus_scene::presets() {
            let scene = Scene::preset(p.name).unwrap();
            let plan = FramePlan::for_scene(&scene, false).unwrap();
            assert_eq!(plan.passes.len(), 2);
            let [w, h] = scene.camera.resolution;
            assert_eq!(plan.passes[0].dispatch, [w.div_ceil(8), h.div_ceil(8), 1]);
            // The march output is the composite input: one physical image.
            assert!(
                plan.passes[0]
                    .bindings
                    .iter()
                    .any(|b| b.resource == Resource::Cloud)
            );
            assert!(
                plan.passes[1]
                    .bindings
                    .iter()
                    .any(|b| b.resource == Resource::Cloud)
            );
        }
    }
}
