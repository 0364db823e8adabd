//! A frame plan: the graph resolved for one scene and output size. Which variant of each
//! module runs (the cheapest that has every feature the scene uses), every resource with its
//! concrete size and derived usage, every pass with its workgroups or viewport and its
//! bindings. Both backends execute a plan step by step; nothing in it is backend-specific.

use std::collections::BTreeMap;

use stratus_scene::Scene;

use crate::{
    desc::{
        AddressMode, Blend, ColorDesc, Compare, DepthDesc, Filter, Lifetime, LoadOp, OutputRole,
        PREVIOUS, PassDesc, ResourceKind, TexelFormat,
    },
    manifest::{BindingKind, Dimension, ModuleManifest, ResourceInfo, VariantInfo},
    options::PlanOptions,
    program::Program,
};

/// The largest width or height of an output image: the scene's limit, the one every backend,
/// plan and the CLI check.
pub use crate::error::PlanError;
pub use stratus_scene::MAX_RESOLUTION;

/// What a resource is used for, derived from the passes that bind it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Usage {
    /// Sampled (or loaded) by a shader.
    pub sampled: bool,
    /// Bound as a storage texture or buffer.
    pub storage: bool,
    /// A raster pass's colour target.
    pub color: bool,
    /// A raster pass's depth target.
    pub depth: bool,
    /// Written by an upload from the host.
    pub upload: bool,
}

/// A sampler's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SamplerDesc {
    /// Minification and magnification filter (mipmaps: nearest; there is one level).
    pub filter: Filter,
    /// Addressing on every axis.
    pub address: AddressMode,
}

impl SamplerDesc {
    /// The LOD clamp every backend sets: [0, 32], as wgpu's defaults.
    pub const LOD_CLAMP: [f32; 2] = [0.0, 32.0];
}

/// One resource of the plan.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanResource {
    /// Name.
    pub name: String,
    /// What it is.
    pub kind: ResourceKind,
    /// Texture dimension.
    pub dimension: Dimension,
    /// Texel format of a texture.
    pub format: Option<TexelFormat>,
    /// Size of a texture; `None` for an uploaded one (the data's size).
    pub extent: Option<[u32; 3]>,
    /// How long its contents live.
    pub lifetime: Lifetime,
    /// What the passes use it for.
    pub usage: Usage,
    /// Host data it comes from.
    pub upload: Option<String>,
    /// Frame output field it is read back into.
    pub output: Option<OutputRole>,
    /// Counter names of a counters buffer.
    pub counters: Vec<String>,
    /// Sampler state.
    pub sampler: Option<SamplerDesc>,
    /// The host may supply its own texture.
    pub external: bool,
    /// Uniform members a computed persistent resource depends on (`inputs`).
    pub inputs: Vec<String>,
    /// How far some of them may drift before it goes stale (`tolerance`).
    pub tolerance: BTreeMap<String, f64>,
}

impl PlanResource {
    /// Bytes of a buffer resource (4 per counter; the uniform block's size is the host's).
    pub fn buffer_size(&self) -> u64 {
        (self.counters.len() * 4) as u64
    }

    /// Bytes of device memory the resource's textures take (both halves of a history pair);
    /// 0 for what has no extent. Read-back buffers, in host memory on a discrete GPU, are not
    /// counted.
    pub fn image_bytes(&self) -> u64 {
        let (Some([w, h, d]), Some(format)) = (self.extent, self.format) else {
            return 0;
        };
        let one = u64::from(w) * u64::from(h) * u64::from(d) * u64::from(format.texel_size());
        if self.lifetime == Lifetime::History {
            2 * one
        } else {
            one
        }
    }

    /// Whether a pass computes its contents, once and again only when they go stale: a
    /// persistent resource that is not uploaded (a LUT).
    pub fn is_computed_persistent(&self) -> bool {
        self.lifetime == Lifetime::Persistent && self.upload.is_none()
    }

    /// What a backend must agree on to keep the resource across plans: if this is equal,
    /// the existing GPU object serves the new plan.
    pub fn signature(&self) -> impl PartialEq + '_ {
        (
            self.kind,
            self.dimension,
            self.format,
            self.extent,
            self.lifetime,
            self.usage,
            self.counters.len(),
            self.sampler,
        )
    }
}

/// A frame condition: a flag that must be set (or, negated, unset) for a pass to run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Condition {
    /// The flag.
    pub flag: String,
    /// Run when the flag is *not* set.
    pub negate: bool,
}

impl Condition {
    fn parse(s: &str) -> Self {
        match s.trim().strip_prefix('!') {
            Some(f) => Self {
                flag: f.trim().into(),
                negate: true,
            },
            None => Self {
                flag: s.trim().into(),
                negate: false,
            },
        }
    }

    /// Whether the condition holds with these flags set.
    pub fn holds(&self, flags: &[&str]) -> bool {
        flags.contains(&self.flag.as_str()) != self.negate
    }
}

/// One binding of a pass: the manifest's reflection plus the resource bound there.
#[derive(Clone, Debug, PartialEq)]
pub struct Binding {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// What the WGSL declares (kind, format, access, dimension).
    pub info: ResourceInfo,
    /// Index of the resource in [`FramePlan::resources`].
    pub resource: usize,
    /// Binds last frame's half of a history resource.
    pub previous: bool,
}

/// A colour target of a raster pass, resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct ColorTarget {
    /// Index of the texture in [`FramePlan::resources`].
    pub resource: usize,
    /// Blend state.
    pub blend: Blend,
    /// Load operation.
    pub load: LoadOp,
}

/// The depth target of a raster pass, resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthTarget {
    /// Index of the texture in [`FramePlan::resources`].
    pub resource: usize,
    /// Depth test.
    pub compare: Compare,
    /// Depth writes.
    pub write: bool,
    /// Load operation.
    pub load: LoadOp,
}

/// The resource a binding binds, as the graph names it: `name`, or `name.previous` for last
/// frame's half of a history pair (a pass may bind both halves).
pub fn bound_name(plan: &FramePlan, b: &Binding) -> String {
    let name = &plan.resources[b.resource].name;
    if b.previous {
        format!("{name}{PREVIOUS}")
    } else {
        name.clone()
    }
}

/// What kind of work a pass does.
#[derive(Clone, Debug, PartialEq)]
pub enum PassKind {
    /// A compute dispatch.
    Compute {
        /// Entry point.
        entry: String,
        /// Workgroup size from the manifest.
        workgroup_size: [u32; 3],
        /// Workgroups to dispatch over the pass's extent.
        dispatch: [u32; 3],
    },
    /// A draw of `vertices` vertices with no vertex buffers, over the pass's extent.
    Raster {
        /// Vertex entry point.
        vertex: String,
        /// Fragment entry point.
        fragment: String,
        /// Vertex count.
        vertices: u32,
        /// Colour targets by `@location`.
        colors: Vec<ColorTarget>,
        /// Depth target.
        depth: Option<DepthTarget>,
    },
}

/// One pass.
#[derive(Clone, Debug, PartialEq)]
pub struct Pass {
    /// Name.
    pub name: String,
    /// WGSL module.
    pub module: String,
    /// Compute or raster.
    pub kind: PassKind,
    /// Width and height it covers.
    pub extent: [u32; 2],
    /// Runs only when this holds.
    pub when: Option<Condition>,
    /// Bindings the entry points use, by group and binding.
    pub bindings: Vec<Binding>,
}

impl Pass {
    /// The resources the pass writes (storage writes, raster targets), by index.
    pub fn writes(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .bindings
            .iter()
            .filter(|b| b.info.access.is_some_and(crate::manifest::Access::writes))
            .map(|b| b.resource)
            .collect();
        if let PassKind::Raster { colors, depth, .. } = &self.kind {
            out.extend(colors.iter().map(|c| c.resource));
            out.extend(depth.iter().map(|d| d.resource));
        }
        out
    }

    /// What names the pass's pipeline within a module variant: its name and entry points (two
    /// passes share a name under opposite plan options, with other entry points).
    pub fn pipeline_name(&self) -> String {
        match &self.kind {
            PassKind::Compute { entry, .. } => format!("{}:{entry}", self.name),
            PassKind::Raster {
                vertex, fragment, ..
            } => format!("{}:{vertex}+{fragment}", self.name),
        }
    }

    /// Whether the pass runs in a frame with these flags.
    pub fn runs(&self, flags: &[&str]) -> bool {
        self.when.as_ref().is_none_or(|c| c.holds(flags))
    }
}

/// The variant of a module a plan runs.
#[derive(Clone, Debug, PartialEq)]
pub struct ModulePlan {
    /// Variant name.
    pub variant: String,
    /// Every override value of the variant (defaults filled in): wgpu is given exactly these;
    /// the ash backend loads the variant's SPIR-V, where they are baked in.
    pub overrides: BTreeMap<String, f64>,
    /// The variant's SPIR-V file in `spirv-out/`.
    pub spv_file: String,
}

/// A whole frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// The variant the first pass's module runs (the cloud model's, in words for people).
    pub variant: String,
    /// Per module: the chosen variant.
    pub modules: BTreeMap<String, ModulePlan>,
    /// Output width.
    pub width: u32,
    /// Output height.
    pub height: u32,
    /// Whether the statistics counters are gathered.
    pub stats: bool,
    /// Every resource.
    pub resources: Vec<PlanResource>,
    /// Passes in execution order.
    pub passes: Vec<Pass>,
    /// What the plan was made from: a scene whose key differs needs another plan.
    pub key: PlanKey,
}

impl FramePlan {
    /// The resource called `name`.
    pub fn resource(&self, name: &str) -> Option<(usize, &PlanResource)> {
        self.resources
            .iter()
            .enumerate()
            .find(|(_, r)| r.name == name)
    }

    /// The names of the work counters (empty where the graph has none).
    pub fn counters(&self) -> &[String] {
        self.resources
            .iter()
            .find(|r| r.kind == ResourceKind::Counters)
            .map_or(&[], |r| &r.counters[..])
    }

    /// The workgroup size of the compute pass called `name`, where the plan holds one.
    pub fn workgroup_size(&self, name: &str) -> Option<[u32; 3]> {
        self.passes.iter().find_map(|p| match &p.kind {
            PassKind::Compute { workgroup_size, .. } if p.name == name => Some(*workgroup_size),
            _ => None,
        })
    }

    /// The paths per pixel one frame of the path tracer adds, where the plan path traces:
    /// the invocations of the `pathtrace` pass's workgroup (in `wgsl/pathtrace.wgsl` a pixel
    /// is a workgroup, `workgroup_per_texel` in the graph, one path an invocation), so the
    /// WGSL is the one place that says it.
    pub fn paths_per_frame(&self) -> Option<u32> {
        self.workgroup_size("pathtrace").map(|w| w.iter().product())
    }

    /// Whether any resource is a history pair.
    pub fn has_history(&self) -> bool {
        self.resources
            .iter()
            .any(|r| r.lifetime == Lifetime::History)
    }

    /// Whether every frame draws a raster pass (one without a `when` condition, or only a
    /// negated one such as the display image's `!hdr`, which a frame without flags runs;
    /// `present` runs only into a host's target). On lavapipe such frames' pass timestamps are late:
    /// llvmpipe bins a timestamp taken with a framebuffer bound into its tiles (backend-ash's
    /// `TIMESTAMP_STAGE`), and keeps doing so for the device's later frames, so timings of
    /// these plans are taken by the wall clock.
    pub fn rasterizes_every_frame(&self) -> bool {
        self.passes.iter().any(|p| {
            p.when.as_ref().is_none_or(|w| w.negate) && matches!(p.kind, PassKind::Raster { .. })
        })
    }
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

impl PlanOptions {
    /// Whether `pass` is in a plan made with these options.
    pub fn plans(&self, pass: &PassDesc) -> bool {
        pass.plan
            .as_deref()
            .is_none_or(|c| crate::desc::plan_condition_holds(c, &|o| self.is_set(o)))
    }
}

/// Everything a frame plan is made from besides the program: the shader features, the plan
/// options and the size. Two scenes with equal keys share one plan; a renderer compares its
/// plan's key with each new scene's ([`FramePlan::serves`]) and makes a new plan when they
/// differ.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanKey {
    /// The shader features (which variant runs).
    pub requirements: Requirements,
    /// The plan options (which passes run, at what extents).
    pub options: PlanOptions,
    /// The output size in pixels.
    pub size: [u32; 2],
}

impl PlanKey {
    /// The key of `scene`'s plan (`stats`: with the work counters).
    pub fn of(scene: &Scene, stats: bool) -> Self {
        Self {
            requirements: Requirements::of(scene, stats),
            options: PlanOptions::of(scene),
            size: scene.camera.resolution,
        }
    }
}

impl FramePlan {
    /// The plan for `scene` at its resolution, with the embedded shaders.
    pub fn for_scene(scene: &Scene, stats: bool) -> Result<Self, PlanError> {
        Self::for_key(&*Program::embedded()?, &PlanKey::of(scene, stats))
    }

    /// The plan of `program`'s graph for `key`.
    pub fn for_key(program: &Program, key: &PlanKey) -> Result<Self, PlanError> {
        let [w, h] = key.size;
        Self::with_options(program, &key.requirements, w, h, key.options)
    }

    /// Whether this plan is the one `scene` needs (same features, with or without counters
    /// as this plan; same plan options; same size): when not, a renderer must make a new one.
    pub fn serves(&self, scene: &Scene) -> bool {
        self.key == PlanKey::of(scene, self.stats)
    }

    /// The plan of `program`'s graph for the given requirements and size, default options.
    pub fn new(
        program: &Program,
        req: &Requirements,
        width: u32,
        height: u32,
    ) -> Result<Self, PlanError> {
        Self::with_options(program, req, width, height, PlanOptions::default())
    }

    /// The plan of `program`'s graph for the given requirements, size and options.
    pub fn with_options(
        program: &Program,
        req: &Requirements,
        width: u32,
        height: u32,
        options: PlanOptions,
    ) -> Result<Self, PlanError> {
        if !(1..=MAX_RESOLUTION).contains(&width) || !(1..=MAX_RESOLUTION).contains(&height) {
            return Err(PlanError::Size(width, height));
        }
        let manifest = &program.manifest;
        let graph = &program.graph;
        let bad = |m: String| PlanError::Manifest(m);
        let planned: Vec<&PassDesc> = graph.passes.iter().filter(|p| options.plans(p)).collect();
        // Resources some planned pass binds or draws into (the rest are not made), external
        // ones and the uniform block.
        let referenced = |name: &str| {
            planned.iter().any(|p| {
                p.bind
                    .values()
                    .any(|v| v.strip_suffix(PREVIOUS).unwrap_or(v) == name)
                    || p.color.iter().any(|c| c.target == name)
                    || p.depth.as_ref().is_some_and(|d| d.target == name)
            })
        };
        let graph_resources: Vec<_> = graph
            .resources
            .iter()
            .filter(|r| r.external || r.upload.as_deref() == Some("frame") || referenced(&r.name))
            .collect();
        let mut modules = BTreeMap::new();
        for pass in &planned {
            if modules.contains_key(&pass.module) {
                continue;
            }
            let module = manifest
                .module(&pass.module)
                .ok_or_else(|| bad(format!("no module `{}`", pass.module)))?;
            let (variant, overrides) = choose_variant(module, req)?;
            modules.insert(
                pass.module.clone(),
                ModulePlan {
                    variant: variant.name.clone(),
                    overrides,
                    spv_file: variant.files.spv.clone(),
                },
            );
        }
        let mut resources: Vec<PlanResource> = graph_resources
            .iter()
            .map(|r| {
                let extent = match (&r.extent, r.kind, &r.upload) {
                    (_, ResourceKind::Texture, Some(_)) => None,
                    (e, ResourceKind::Texture, None) => Some(
                        e.clone()
                            .unwrap_or_default()
                            .resolve_in(width, height, options.temporal)
                            .map_err(|e| bad(format!("resource `{}`: {e}", r.name)))?,
                    ),
                    _ => None,
                };
                Ok(PlanResource {
                    name: r.name.clone(),
                    kind: r.kind,
                    dimension: r.dimension.unwrap_or(Dimension::D2),
                    format: r.format,
                    extent,
                    lifetime: r.lifetime,
                    usage: Usage {
                        upload: r.upload.is_some() && r.kind == ResourceKind::Texture,
                        sampled: r.host_reads,
                        ..Usage::default()
                    },
                    upload: r.upload.clone(),
                    output: r.output,
                    counters: r.counters.iter().map(|c| c.name.clone()).collect(),
                    sampler: (r.kind == ResourceKind::Sampler).then(|| SamplerDesc {
                        filter: r.filter.unwrap_or_default(),
                        address: r.address.unwrap_or_default(),
                    }),
                    external: r.external,
                    inputs: r.inputs.clone(),
                    tolerance: r.tolerance.clone(),
                })
            })
            .collect::<Result<_, PlanError>>()?;
        let index = |name: &str| -> Result<usize, PlanError> {
            graph_resources
                .iter()
                .position(|r| r.name == name)
                .ok_or_else(|| bad(format!("no resource `{name}`")))
        };
        let mut passes = Vec::new();
        for pd in planned.iter().copied() {
            let module = manifest
                .module(&pd.module)
                .ok_or_else(|| bad(format!("no module `{}`", pd.module)))?;
            let [ew, eh, _] = pd
                .extent
                .resolve_in(width, height, options.temporal)
                .map_err(|e| bad(format!("pass `{}`: {e}", pd.name)))?;
            let entries: Vec<&str> = [&pd.compute, &pd.vertex, &pd.fragment]
                .into_iter()
                .flatten()
                .map(String::as_str)
                .collect();
            let mut uses = std::collections::BTreeSet::new();
            for e in &entries {
                let ep = module
                    .entry_point(e)
                    .ok_or_else(|| bad(format!("pass `{}`: no entry point `{e}`", pd.name)))?;
                uses.extend(ep.uses.iter().copied());
            }
            let mut bindings = Vec::new();
            for [group, binding] in uses {
                let info = module.resource_at(group, binding).ok_or_else(|| {
                    bad(format!(
                        "pass `{}` uses unknown binding {group}/{binding}",
                        pd.name
                    ))
                })?;
                let target = pd.bind.get(&info.name).ok_or_else(|| {
                    bad(format!("pass `{}`: `{}` is not bound", pd.name, info.name))
                })?;
                let (name, previous) = match target.strip_suffix(PREVIOUS) {
                    Some(n) => (n, true),
                    None => (target.as_str(), false),
                };
                let resource = index(name)?;
                let usage = &mut resources[resource].usage;
                match info.kind {
                    BindingKind::SampledTexture => usage.sampled = true,
                    BindingKind::StorageTexture | BindingKind::StorageBuffer => {
                        usage.storage = true
                    }
                    _ => {}
                }
                bindings.push(Binding {
                    group,
                    binding,
                    info: info.clone(),
                    resource,
                    previous,
                });
            }
            let kind = match &pd.compute {
                Some(entry) => {
                    let wg = module
                        .entry_point(entry)
                        .map(|e| e.workgroup_size)
                        .unwrap_or([1, 1, 1])
                        .map(|n| n.max(1));
                    let dispatch = if pd.workgroup_per_texel {
                        [ew, eh, 1]
                    } else {
                        [ew.div_ceil(wg[0]), eh.div_ceil(wg[1]), 1]
                    };
                    PassKind::Compute {
                        entry: entry.clone(),
                        workgroup_size: wg,
                        dispatch,
                    }
                }
                None => {
                    let colors = pd
                        .color
                        .iter()
                        .map(
                            |ColorDesc {
                                 target,
                                 blend,
                                 load,
                             }| {
                                let resource = index(target)?;
                                resources[resource].usage.color = true;
                                Ok(ColorTarget {
                                    resource,
                                    blend: *blend,
                                    load: *load,
                                })
                            },
                        )
                        .collect::<Result<_, PlanError>>()?;
                    let depth = match &pd.depth {
                        Some(DepthDesc {
                            target,
                            compare,
                            write,
                            load,
                        }) => {
                            let resource = index(target)?;
                            resources[resource].usage.depth = true;
                            Some(DepthTarget {
                                resource,
                                compare: *compare,
                                write: *write,
                                load: *load,
                            })
                        }
                        None => None,
                    };
                    PassKind::Raster {
                        vertex: pd.vertex.clone().unwrap_or_default(),
                        fragment: pd.fragment.clone().unwrap_or_default(),
                        vertices: pd.vertices,
                        colors,
                        depth,
                    }
                }
            };
            passes.push(Pass {
                name: pd.name.clone(),
                module: pd.module.clone(),
                kind,
                extent: [ew, eh],
                when: pd.when.as_deref().map(Condition::parse),
                bindings,
            });
        }
        let variant = planned
            .first()
            .and_then(|p| modules.get(&p.module))
            .map(|m| m.variant.clone())
            .unwrap_or_default();
        Ok(Self {
            variant,
            modules,
            width,
            height,
            stats: req.0.get("STATS").is_some_and(|&s| s > 0.0),
            resources,
            passes,
            key: PlanKey {
                requirements: req.clone(),
                options,
                size: [width, height],
            },
        })
    }
}

/// The cheapest variant whose every override value is at least what the scene requires
/// (requirements the module declares no override for do not apply to it); STATS must match
/// exactly (the counting variant is never chosen silently, nor dropped). Cost: the sum of the
/// feature values, each as a fraction of its largest exported value.
fn choose_variant<'m>(
    module: &'m ModuleManifest,
    req: &Requirements,
) -> Result<(&'m VariantInfo, BTreeMap<String, f64>), PlanError> {
    let defaults: BTreeMap<String, f64> = module
        .overrides
        .iter()
        .filter_map(|o| Some((o.name.clone(), o.default?)))
        .collect();
    let declared = |name: &str| module.overrides.iter().any(|o| o.name == name);
    let max_of = |name: &str| {
        module
            .variants
            .iter()
            .filter_map(|v| v.overrides.get(name).or(defaults.get(name)))
            .fold(1.0f64, |a, &b| a.max(b))
    };
    let mut best: Option<(f64, &VariantInfo, BTreeMap<String, f64>)> = None;
    for v in &module.variants {
        let mut values = defaults.clone();
        values.extend(v.overrides.clone());
        let covers = req
            .0
            .iter()
            .filter(|(n, _)| declared(n))
            .all(|(name, &need)| {
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
            .filter(|n| **n != "STATS" && declared(n))
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
            .filter(|(n, v)| **v > 0.0 && declared(n))
            .map(|(k, v)| format!("{k} >= {v}"))
            .collect();
        PlanError::NoVariant {
            module: module.name.clone(),
            wanted: wanted.join(", "),
        }
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

    fn plan(r: &Requirements) -> Result<FramePlan, PlanError> {
        FramePlan::new(&Program::embedded().unwrap(), r, 64, 32)
    }

    #[test]
    fn picks_the_cheapest_variant_that_covers_the_scene() {
        let p = |r: &Requirements| plan(r).unwrap().variant;
        assert_eq!(p(&req(1.0, 2.0, 1.0, 1.0, 0.0)), "full");
        assert_eq!(p(&req(1.0, 2.0, 0.0, 0.0, 0.0)), "soft");
        assert_eq!(p(&req(0.0, 0.0, 0.0, 0.0, 0.0)), "unshadowed");
        assert_eq!(p(&req(0.0, 0.0, 0.0, 0.0, 1.0)), "unshadowed-stats");
        assert_eq!(p(&req(1.0, 2.0, 1.0, 1.0, 1.0)), "full-stats");
    }

    #[test]
    fn never_drops_a_feature() {
        let err = plan(&req(1.0, 99.0, 1.0, 1.0, 0.0)).unwrap_err();
        assert!(err.to_string().contains("MAX_OCTAVES >= 99"), "{err}");
    }

    #[test]
    fn rejects_sizes_out_of_range() {
        let program = Program::embedded().unwrap();
        let r = req(1.0, 2.0, 1.0, 1.0, 0.0);
        for (w, h) in [(0, 16), (16, 0), (MAX_RESOLUTION + 1, 16)] {
            let err = FramePlan::new(&program, &r, w, h).unwrap_err();
            assert!(matches!(err, PlanError::Size(..)), "{err}");
        }
    }

    #[test]
    fn every_preset_plans_march_then_composite_over_one_cloud_image() {
        for p in stratus_scene::presets() {
            let scene = Scene::preset(p.name).unwrap();
            let plan = FramePlan::for_scene(&scene, false).unwrap();
            let always: Vec<&str> = plan
                .passes
                .iter()
                .filter(|p| p.runs(&[]))
                .map(|p| p.name.as_str())
                .collect();
            // Under the physical sky the cloud-shadow map after the march (its tables run
            // only when stale: when the air, the sun or the camera changed); the stylised
            // presets' filter after the composite.
            let physical = scene.atmosphere.sky.is_physical();
            let shadow: &[&str] = if physical { &["cloud-shadow"] } else { &[] };
            let styled: &[&str] = if scene.post.kuwahara {
                &["kuwahara"]
            } else {
                &[]
            };
            assert_eq!(
                always,
                [&["march"], shadow, &["composite"], styled].concat(),
                "{}",
                p.name
            );
            let [w, h] = scene.camera.resolution;
            let march = plan.passes.iter().position(|p| p.name == "march").unwrap();
            let PassKind::Compute { dispatch, .. } = &plan.passes[march].kind else {
                panic!("march is a compute pass");
            };
            assert_eq!(*dispatch, [w.div_ceil(8), h.div_ceil(8), 1]);
            // The march output is the composite input: one resource.
            let (cloud, _) = plan.resource("cloud").unwrap();
            let composite = plan
                .passes
                .iter()
                .position(|p| p.name == "composite")
                .unwrap();
            for pass in [&plan.passes[march], &plan.passes[composite]] {
                assert!(pass.bindings.iter().any(|b| b.resource == cloud));
            }
        }
    }

    #[test]
    fn usage_is_derived_from_the_passes() {
        let plan = plan(&req(1.0, 2.0, 1.0, 1.0, 0.0)).unwrap();
        let usage = |n: &str| plan.resource(n).unwrap().1.usage;
        let cloud = usage("cloud");
        assert!(cloud.storage && cloud.sampled && !cloud.color);
        let shape = usage("shape");
        assert!(shape.sampled && shape.upload && !shape.storage);
        assert!(usage("display").color);
    }

    #[test]
    fn plan_options_choose_the_passes_and_the_sparse_extent() {
        let program = Program::embedded().unwrap();
        let r = req(1.0, 2.0, 1.0, 1.0, 0.0);
        let names = |o: PlanOptions| {
            let plan = FramePlan::with_options(&program, &r, 66, 35, o).unwrap();
            let passes: Vec<(String, String)> = plan
                .passes
                .iter()
                .filter(|p| p.runs(&[]))
                .map(|p| (p.name.clone(), p.pipeline_name()))
                .collect();
            (plan, passes)
        };
        let (full, passes) = names(PlanOptions::default());
        assert_eq!(
            passes.iter().map(|p| p.1.as_str()).collect::<Vec<_>>(),
            ["march:march", "composite:composite"]
        );
        // No history and no sparse targets are made without temporal upsampling.
        assert!(!full.has_history());
        assert!(full.resource("cloud-sparse").is_none());
        for (block, extent) in [(2, [33, 18]), (4, [17, 9])] {
            let (plan, passes) = names(PlanOptions {
                temporal: block,
                ..PlanOptions::default()
            });
            assert_eq!(
                passes.iter().map(|p| p.1.as_str()).collect::<Vec<_>>(),
                [
                    "march:march_sparse",
                    "resolve:resolve",
                    "composite:composite"
                ]
            );
            assert!(plan.has_history());
            let sparse = plan.resource("cloud-sparse").unwrap().1;
            assert_eq!(sparse.extent, Some([extent[0], extent[1], 1]));
            assert_eq!(plan.passes[0].extent, extent);
        }
        let (_, passes) = names(PlanOptions {
            temporal: 4,
            checkerboard: true,
            ..PlanOptions::default()
        });
        assert_eq!(passes[0].1, "march:march_sparse_checkerboard");
        let (skip, _) = names(PlanOptions {
            empty_skip: true,
            ..PlanOptions::default()
        });
        assert_eq!(skip.passes[0].name, "occupancy");
        assert_eq!(
            skip.passes[0].when,
            Some(Condition::parse("stale:occupancy"))
        );
        // The path tracer replaces the march, keeps its means in the history pair and skips
        // empty space with the occupancy grid.
        let (pt, passes) = names(PlanOptions {
            pathtrace: true,
            empty_skip: true,
            ..PlanOptions::default()
        });
        assert_eq!(
            passes.iter().map(|p| p.1.as_str()).collect::<Vec<_>>(),
            ["pathtrace:pathtrace", "composite:composite"]
        );
        assert!(pt.has_history());
        assert_eq!(pt.passes[0].name, "occupancy");
        assert!(pt.resource("cloud-sparse").is_none());
        // Only the sprites and the rain's particles draw a raster pass every frame (present
        // and the HDR copy run on request).
        assert!(!pt.rasterizes_every_frame());
        let (sprites, _) = names(PlanOptions {
            sprites: true,
            ..PlanOptions::default()
        });
        assert!(sprites.rasterizes_every_frame());
        let (rain, _) = names(PlanOptions {
            precipitation: true,
            ..PlanOptions::default()
        });
        assert!(rain.rasterizes_every_frame());
        assert!(!names(PlanOptions::default()).0.rasterizes_every_frame());
    }

    /// A scene that asks for the path tracer plans it with empty-space skipping and none of
    /// the march's methods.
    #[test]
    fn pathtrace_scenes_plan_the_path_tracer() {
        let mut scene = Scene::default();
        scene.quality.integrator = stratus_scene::Integrator::Pathtrace;
        scene.quality.dynamic_step = true;
        let o = PlanOptions::of(&scene);
        assert!(o.pathtrace && o.empty_skip && o.temporal == 1 && !o.checkerboard);
        let plan = FramePlan::for_scene(&scene.with_size(16, 8), false).unwrap();
        assert!(plan.passes.iter().any(|p| p.name == "pathtrace"));
        assert!(!plan.passes.iter().any(|p| p.name == "march"));
    }

    #[test]
    fn conditions_negate() {
        let c = Condition::parse("!history");
        assert!(c.holds(&[]));
        assert!(!c.holds(&["history"]));
        assert!(Condition::parse("stats").holds(&["stats"]));
    }
}
