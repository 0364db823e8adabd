//! The frame graph as written in `wgsl/graph.toml`: resources (format, extent, lifetime, where
//! their data comes from) and passes (compute, or raster with colour/depth targets and blend
//! state; an extent; bindings from WGSL names to resources; an optional condition).
//!
//! It is data beside the WGSL, the one description of a frame that both backends execute:
//! adding a pass or a resource touches the WGSL and this file, never backend code. What a
//! resource is used for (sampled, storage, attachment, copy) is derived from the passes, so it
//! cannot drift from them. [`GraphDesc::check`] holds it against naga's reflection; `cargo
//! xtask build-shaders` runs that check and writes the checked graph into the manifest.

use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use crate::manifest::{Access, BindingKind, Dimension, Manifest, ModuleManifest, Stage};

/// The whole graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphDesc {
    /// Resources, by name.
    #[serde(rename = "resource", default)]
    pub resources: Vec<ResourceDesc>,
    /// Passes in execution order.
    #[serde(rename = "pass", default)]
    pub passes: Vec<PassDesc>,
}

/// What a resource is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ResourceKind {
    /// The `FrameUniforms` block, written by the host before every frame.
    Uniform,
    /// A storage buffer of `u32` work counters, zeroed before every frame that counts.
    Counters,
    /// A texture (sampled, storage, or a raster target).
    Texture,
    /// A sampler.
    Sampler,
}

/// How long a resource's contents live.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Lifetime {
    /// Written and read within one frame.
    #[default]
    Transient,
    /// Uploaded or computed once, and again only when its inputs change.
    Persistent,
    /// A ping-pong pair: a pass writes `name` while `name.previous` is last frame's.
    History,
}

/// A texel format (WGSL spelling).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum TexelFormat {
    /// 8-bit unsigned normalised RGBA.
    #[serde(rename = "rgba8unorm")]
    Rgba8Unorm,
    /// 16-bit float RGBA.
    #[serde(rename = "rgba16float")]
    Rgba16Float,
    /// 32-bit float RGBA.
    #[serde(rename = "rgba32float")]
    Rgba32Float,
    /// 32-bit float red.
    #[serde(rename = "r32float")]
    R32Float,
    /// 32-bit float depth.
    #[serde(rename = "depth32float")]
    Depth32Float,
}

impl TexelFormat {
    /// The WGSL spelling (as the manifest writes storage formats).
    pub fn wgsl(self) -> &'static str {
        match self {
            Self::Rgba8Unorm => "rgba8unorm",
            Self::Rgba16Float => "rgba16float",
            Self::Rgba32Float => "rgba32float",
            Self::R32Float => "r32float",
            Self::Depth32Float => "depth32float",
        }
    }

    /// Bytes per texel.
    pub fn texel_size(self) -> u32 {
        match self {
            Self::Rgba8Unorm | Self::R32Float | Self::Depth32Float => 4,
            Self::Rgba16Float => 8,
            Self::Rgba32Float => 16,
        }
    }

    /// Whether a sampled texture of this format may be linearly filtered everywhere (32-bit
    /// floats need an extra feature on some devices, so they are only loaded).
    pub fn filterable(self) -> bool {
        matches!(self, Self::Rgba8Unorm | Self::Rgba16Float)
    }

    /// Whether the format is a depth format.
    pub fn is_depth(self) -> bool {
        self == Self::Depth32Float
    }
}

/// An extent as written: `"output"`, `"output/4"` (rounded up), `"output/temporal"` (divided
/// by the temporal upsampling block side, rounded up), or fixed `[w, h]` / `[w, h, d]`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ExtentDesc {
    /// `output` or `output/N`.
    Relative(String),
    /// A fixed size.
    Fixed(Vec<u32>),
}

impl Default for ExtentDesc {
    fn default() -> Self {
        Self::Relative("output".into())
    }
}

impl ExtentDesc {
    /// The size for an output of `width` x `height` without temporal upsampling, or why the
    /// extent is malformed.
    pub fn resolve(&self, width: u32, height: u32) -> Result<[u32; 3], String> {
        self.resolve_in(width, height, 1)
    }

    /// The size for an output of `width` x `height` with temporal blocks of side `block`.
    pub fn resolve_in(&self, width: u32, height: u32, block: u32) -> Result<[u32; 3], String> {
        match self {
            Self::Relative(s) => {
                let div = match s.trim().strip_prefix("output") {
                    Some("") => 1,
                    Some(rest) => rest
                        .trim()
                        .strip_prefix('/')
                        .and_then(|d| match d.trim() {
                            "temporal" => Some(block.max(1)),
                            d => d.parse::<u32>().ok(),
                        })
                        .filter(|&d| d >= 1)
                        .ok_or_else(|| {
                            format!(
                                "extent `{s}`: expected `output`, `output/N` with N >= 1 or `output/temporal`"
                            )
                        })?,
                    None => {
                        return Err(format!(
                            "extent `{s}`: expected `output`, `output/N` or [width, height]"
                        ));
                    }
                };
                Ok([width.div_ceil(div), height.div_ceil(div), 1])
            }
            Self::Fixed(v) => match v[..] {
                [w, h] if w > 0 && h > 0 => Ok([w, h, 1]),
                [w, h, d] if w > 0 && h > 0 && d > 0 => Ok([w, h, d]),
                _ => Err(format!(
                    "extent {v:?}: expected [width, height] or [width, height, depth], all >= 1"
                )),
            },
        }
    }
}

/// Which field of a frame's output a resource is read back into.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OutputRole {
    /// Linear radiance and transmittance (`FrameOutput::radiance`).
    Radiance,
    /// Transmittance-weighted depth (`FrameOutput::depth`).
    Depth,
    /// The tone-mapped display image (`FrameOutput::image`).
    Image,
}

/// Texture filtering of a sampler.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Filter {
    /// Nearest texel.
    Nearest,
    /// Linear interpolation.
    #[default]
    Linear,
}

/// Addressing outside [0, 1] of a sampler.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AddressMode {
    /// Tile.
    #[default]
    Repeat,
    /// Clamp to the edge texel.
    ClampToEdge,
}

/// A work counter: its name in the output and the WGSL constant that is its index.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterDesc {
    /// Name in statistics output.
    pub name: String,
    /// The WGSL `const` whose value is this counter's index (checked at build time).
    pub wgsl: String,
}

/// One resource.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResourceDesc {
    /// Name the passes bind it by.
    pub name: String,
    /// What it is.
    pub kind: ResourceKind,
    /// Texture dimension (default 2d).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimension: Option<Dimension>,
    /// Texel format of a texture.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<TexelFormat>,
    /// Size of a texture (default `output`; uploaded textures take the data's size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extent: Option<ExtentDesc>,
    /// How long its contents live.
    #[serde(default)]
    pub lifetime: Lifetime,
    /// Host data it is uploaded from: `noise.shape`, `noise.detail`, `noise.weather`,
    /// `noise.curl` for textures; `frame` for the uniform block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upload: Option<String>,
    /// The frame output field it is read back into, when the host asks for the output.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<OutputRole>,
    /// Counters of a `counters` buffer, in index order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub counters: Vec<CounterDesc>,
    /// Sampler filtering.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub filter: Option<Filter>,
    /// Sampler addressing.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub address: Option<AddressMode>,
    /// The host may render into its own texture here (the library's target).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub external: bool,
    /// Members of the uniform block a computed persistent resource is computed from: it goes
    /// stale when one of them changes (a lookup table of the air, not of the sun, is computed
    /// again only when the air changes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<String>,
}

/// How a raster pass blends into a colour target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Blend {
    /// Overwrite.
    #[default]
    Replace,
    /// Premultiplied radiance over what is there, seen through the source's alpha as
    /// transmittance: `dst.rgb = src.rgb + dst.rgb * src.a`, `dst.a` kept.
    Transmittance,
    /// Add.
    Additive,
    /// Premultiplied "over" (Porter-Duff), drawn back to front: `dst = src + dst * (1 -
    /// src.a)` in every channel, so alpha accumulates opacity.
    Over,
}

/// What a raster target holds when the pass begins.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadOp {
    /// Cleared: colour to zero, depth to 1.
    #[default]
    Clear,
    /// Whatever an earlier pass (or the host) left there.
    Load,
}

/// A colour target of a raster pass.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColorDesc {
    /// The texture resource drawn into.
    pub target: String,
    /// Blend state.
    #[serde(default)]
    pub blend: Blend,
    /// Load operation.
    #[serde(default)]
    pub load: LoadOp,
}

/// A depth comparison.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Compare {
    /// Always passes.
    Always,
    /// Passes when nearer.
    #[default]
    Less,
    /// Passes when nearer or equal.
    LessEqual,
    /// Passes when farther.
    Greater,
}

/// The depth target of a raster pass.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DepthDesc {
    /// The `depth32float` texture resource.
    pub target: String,
    /// Depth test.
    #[serde(default)]
    pub compare: Compare,
    /// Whether passing fragments write depth.
    #[serde(default = "yes")]
    pub write: bool,
    /// Load operation.
    #[serde(default)]
    pub load: LoadOp,
}

fn yes() -> bool {
    true
}

fn three() -> u32 {
    3
}

/// One pass.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PassDesc {
    /// Pass name (in timings and messages).
    pub name: String,
    /// The WGSL module (`wgsl/modules.toml`) its entry points are in.
    pub module: String,
    /// Compute entry point (a compute pass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compute: Option<String>,
    /// Vertex entry point (a raster pass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vertex: Option<String>,
    /// Fragment entry point (a raster pass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fragment: Option<String>,
    /// Vertices a raster pass draws (no vertex buffers: the shader makes them).
    #[serde(default = "three")]
    pub vertices: u32,
    /// What the pass covers: a compute pass dispatches over it, a raster pass's viewport.
    #[serde(default)]
    pub extent: ExtentDesc,
    /// A compute pass that dispatches one workgroup per texel of its extent (its invocations
    /// share the texel: the path tracer's paths of one pixel) rather than one invocation.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub workgroup_per_texel: bool,
    /// Runs only when this frame flag is set (`!flag`: only when it is not). Frames set
    /// `stats` when counting, `history` once last frame's history is valid, `stale:NAME` while
    /// the computed persistent resource NAME has no result (new, or invalidated by the host),
    /// `present` when the host asked for the display target; hosts may set their own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub when: Option<String>,
    /// In the plan only when this plan option holds (`!option`: only when it does not):
    /// `temporal` while temporal upsampling is on, `empty_skip` while empty-space skipping is.
    /// Unlike `when`, decided once per plan, so a
    /// resource that no planned pass binds is not made at all. Two passes may share a name
    /// when they are planned under opposite options (the march, full or sparse).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plan: Option<String>,
    /// WGSL global name -> resource name (`name.previous` for last frame's half of a history
    /// resource).
    #[serde(default)]
    pub bind: BTreeMap<String, String>,
    /// Colour targets of a raster pass, by `@location`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub color: Vec<ColorDesc>,
    /// Depth target of a raster pass.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<DepthDesc>,
}

/// Looks up the value of a WGSL `const` by module and name (build time only: it needs the
/// compiled modules).
pub type ConstantLookup<'a> = dyn Fn(&str, &str) -> Option<f64> + 'a;

/// The suffix that names last frame's half of a history resource.
pub const PREVIOUS: &str = ".previous";

/// Plan options a pass's `plan` may name.
pub const PLAN_OPTIONS: [&str; 7] = [
    "temporal",
    "empty_skip",
    "checkerboard",
    "pathtrace",
    "basic",
    "sprites",
    "physical_sky",
];

/// Whether a pass's `plan` condition (`option`, `!option`, several joined by `&`) holds when
/// `set` says which options are on.
pub fn plan_condition_holds(condition: &str, set: &dyn Fn(&str) -> bool) -> bool {
    condition.split('&').all(|term| {
        let term = term.trim();
        match term.strip_prefix('!') {
            Some(name) => !set(name.trim()),
            None => set(term),
        }
    })
}

/// Upload sources the host provides.
pub const UPLOADS: [&str; 5] = [
    "frame",
    "noise.shape",
    "noise.detail",
    "noise.weather",
    "noise.curl",
];

/// Why a graph is not usable, every problem listed.
#[derive(Debug, thiserror::Error)]
#[error("the frame graph {origin} is invalid:\n  - {}", .problems.join("\n  - "))]
pub struct GraphError {
    /// Where the graph came from (e.g. `wgsl/graph.toml`).
    pub origin: String,
    /// Every problem, each naming the pass or resource.
    pub problems: Vec<String>,
}

impl GraphDesc {
    /// Parses the TOML text of a graph file; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self, GraphError> {
        toml::from_str(text).map_err(|e| GraphError {
            origin: origin.into(),
            problems: vec![e.to_string().trim().to_string()],
        })
    }

    /// The names of the work counters (of the first counters resource), in index order.
    pub fn counter_names(&self) -> Vec<String> {
        self.resources
            .iter()
            .find(|r| r.kind == ResourceKind::Counters)
            .map(|r| r.counters.iter().map(|c| c.name.clone()).collect())
            .unwrap_or_default()
    }

    /// The resource called `name` (without a `.previous` suffix).
    pub fn resource(&self, name: &str) -> Option<&ResourceDesc> {
        self.resources.iter().find(|r| r.name == name)
    }

    /// Checks the graph against the reflection of the modules it names; `constant` looks up
    /// the value of a WGSL `const` in a module (for the counters' indices), where the caller
    /// has the compiled modules (build time); pass `None` to skip that part.
    pub fn check(
        &self,
        manifest: &Manifest,
        origin: &str,
        constant: Option<&ConstantLookup<'_>>,
    ) -> Result<(), GraphError> {
        let mut p = Vec::new();
        let mut names = BTreeSet::new();
        for r in &self.resources {
            let at = format!("resource `{}`", r.name);
            if !names.insert(r.name.as_str()) {
                p.push(format!("{at} is declared twice"));
            }
            if r.name.is_empty() || r.name.contains(PREVIOUS) {
                p.push(format!(
                    "{at}: a name may not be empty or contain `{PREVIOUS}`"
                ));
            }
            check_resource(r, &at, &mut p);
        }
        let mut pass_names = BTreeSet::new();
        for pass in &self.passes {
            let at = format!("pass `{}`", pass.name);
            if !pass_names.insert(pass.name.as_str()) {
                // Allowed for passes that no combination of plan options plans together.
                let same: Vec<&PassDesc> =
                    self.passes.iter().filter(|q| q.name == pass.name).collect();
                let together = (0..1u32 << PLAN_OPTIONS.len()).any(|bits| {
                    let set = |name: &str| {
                        PLAN_OPTIONS
                            .iter()
                            .position(|o| *o == name)
                            .is_some_and(|i| bits & (1 << i) != 0)
                    };
                    same.iter()
                        .filter(|q| {
                            q.plan
                                .as_deref()
                                .is_none_or(|c| plan_condition_holds(c, &set))
                        })
                        .count()
                        > 1
                });
                // Once per name: at its second declaration.
                if together
                    && same
                        .get(1)
                        .is_some_and(|second| std::ptr::eq(*second, pass))
                {
                    p.push(format!(
                        "{at} is declared more than once, and some plan options plan two of them (passes may share a name only under exclusive `plan` conditions)"
                    ));
                }
            }
            if let Some(condition) = &pass.plan {
                for term in condition.split('&') {
                    let name = term.trim().trim_start_matches('!').trim();
                    if !PLAN_OPTIONS.contains(&name) {
                        p.push(format!(
                            "{at}: `plan = \"{condition}\"` names `{name}`, which is no plan option (known: {})",
                            PLAN_OPTIONS.join(", ")
                        ));
                    }
                }
            }
            let Some(module) = manifest.module(&pass.module) else {
                p.push(format!(
                    "{at}: module `{}` is not in wgsl/modules.toml",
                    pass.module
                ));
                continue;
            };
            self.check_pass(pass, module, &at, &mut p);
        }
        if let Some(constant) = constant {
            for r in self.resources.iter().filter(|r| !r.counters.is_empty()) {
                let modules: BTreeSet<&str> = self
                    .passes
                    .iter()
                    .filter(|pass| pass.bind.values().any(|v| v == &r.name))
                    .map(|pass| pass.module.as_str())
                    .collect();
                for (i, c) in r.counters.iter().enumerate() {
                    for m in &modules {
                        match constant(m, &c.wgsl) {
                            Some(v) if v == i as f64 => {}
                            Some(v) => p.push(format!(
                                "resource `{}`: counter `{}` is number {i} here, but `{}` in module `{m}` is {v}",
                                r.name, c.name, c.wgsl
                            )),
                            None => p.push(format!(
                                "resource `{}`: counter `{}` names `{}`, which module `{m}` does not declare",
                                r.name, c.name, c.wgsl
                            )),
                        }
                    }
                }
            }
        }
        if p.is_empty() {
            Ok(())
        } else {
            Err(GraphError {
                origin: origin.into(),
                problems: p,
            })
        }
    }

    fn check_pass(&self, pass: &PassDesc, module: &ModuleManifest, at: &str, p: &mut Vec<String>) {
        let mut entries = Vec::new();
        let mut stage_of = |name: &Option<String>, stage: Stage, p: &mut Vec<String>| {
            if let Some(name) = name {
                match module.entry_point(name) {
                    Some(ep) if ep.stage == stage => entries.push(ep),
                    Some(ep) => p.push(format!(
                        "{at}: entry point `{name}` is a {:?} shader, not {stage:?}",
                        ep.stage
                    )),
                    None => p.push(format!(
                        "{at}: module `{}` has no entry point `{name}`",
                        module.name
                    )),
                }
            }
        };
        stage_of(&pass.compute, Stage::Compute, p);
        stage_of(&pass.vertex, Stage::Vertex, p);
        stage_of(&pass.fragment, Stage::Fragment, p);
        let raster = pass.vertex.is_some() || pass.fragment.is_some();
        match (pass.compute.is_some(), raster) {
            (true, true) => p.push(format!(
                "{at}: a pass is compute (`compute`) or raster (`vertex` + `fragment`), not both"
            )),
            (false, false) => p.push(format!(
                "{at}: names no entry point (`compute`, or `vertex` and `fragment`)"
            )),
            (false, true) if pass.vertex.is_none() || pass.fragment.is_none() => p.push(format!(
                "{at}: a raster pass needs both `vertex` and `fragment`"
            )),
            (false, true) if pass.color.is_empty() && pass.depth.is_none() => p.push(format!(
                "{at}: a raster pass needs a `color` or `depth` target"
            )),
            (true, false) if !pass.color.is_empty() || pass.depth.is_some() => {
                p.push(format!("{at}: a compute pass has no raster targets"))
            }
            _ => {}
        }
        if let Some(name) = pass
            .when
            .as_deref()
            .map(|w| w.trim().trim_start_matches('!').trim())
            .and_then(|w| w.strip_prefix("stale:"))
        {
            let computed = self
                .resource(name)
                .is_some_and(|r| r.lifetime == Lifetime::Persistent && r.upload.is_none());
            if !computed {
                p.push(format!(
                    "{at}: `when = \"stale:{name}\"` names no computed persistent resource (lifetime = \"persistent\", not uploaded)"
                ));
            }
        }
        if raster && pass.vertices == 0 {
            p.push(format!("{at}: `vertices` must be at least 1"));
        }
        if let Err(e) = pass.extent.resolve(1, 1) {
            p.push(format!("{at}: {e}"));
        }
        // Every global the entry points use must be bound, and every binding used.
        let mut used = BTreeSet::new();
        for ep in &entries {
            used.extend(ep.uses.iter().copied());
        }
        for &[group, binding] in &used {
            let Some(info) = module.resource_at(group, binding) else {
                p.push(format!(
                    "{at}: uses @group({group}) @binding({binding}), which the manifest lacks"
                ));
                continue;
            };
            match pass.bind.get(&info.name) {
                None => p.push(format!(
                    "{at}: the WGSL uses `{}` (@group({group}) @binding({binding})), which `bind` does not name",
                    info.name
                )),
                Some(target) => self.check_binding(info, target, at, p),
            }
        }
        for name in pass.bind.keys() {
            let is_used = module
                .resources
                .iter()
                .any(|r| &r.name == name && used.contains(&[r.group, r.binding]));
            if !is_used {
                p.push(format!(
                    "{at}: binds `{name}`, which its entry points do not use"
                ));
            }
        }
        for c in &pass.color {
            match self.resource(&c.target) {
                Some(r)
                    if r.kind == ResourceKind::Texture
                        && r.dimension.unwrap_or(Dimension::D2) == Dimension::D2
                        && r.format.is_some_and(|f| !f.is_depth()) => {}
                _ => p.push(format!(
                    "{at}: colour target `{}` must be a 2d texture resource of a colour format",
                    c.target
                )),
            }
        }
        if let Some(d) = &pass.depth {
            match self.resource(&d.target) {
                Some(r)
                    if r.kind == ResourceKind::Texture
                        && r.format == Some(TexelFormat::Depth32Float) => {}
                _ => p.push(format!(
                    "{at}: depth target `{}` must be a depth32float texture resource",
                    d.target
                )),
            }
        }
    }

    fn check_binding(
        &self,
        info: &crate::manifest::ResourceInfo,
        target: &str,
        at: &str,
        p: &mut Vec<String>,
    ) {
        let (name, previous) = match target.strip_suffix(PREVIOUS) {
            Some(n) => (n, true),
            None => (target, false),
        };
        let Some(r) = self.resource(name) else {
            p.push(format!(
                "{at}: binds `{}` to `{target}`, which is not a resource",
                info.name
            ));
            return;
        };
        let wrong = |what: &str| {
            format!(
                "{at}: `{}` is a {what} in the WGSL, but `{name}` is a {:?} resource",
                info.name, r.kind
            )
        };
        if previous && r.lifetime != Lifetime::History {
            p.push(format!(
                "{at}: `{target}`: only history resources have a `{PREVIOUS}` half"
            ));
        }
        match info.kind {
            BindingKind::UniformBuffer if r.kind != ResourceKind::Uniform => {
                p.push(wrong("uniform buffer"))
            }
            BindingKind::StorageBuffer if r.kind != ResourceKind::Counters => {
                p.push(wrong("storage buffer"))
            }
            BindingKind::Sampler if r.kind != ResourceKind::Sampler => p.push(wrong("sampler")),
            BindingKind::SampledTexture | BindingKind::StorageTexture => {
                if r.kind != ResourceKind::Texture {
                    p.push(wrong("texture"));
                    return;
                }
                let dim = r.dimension.unwrap_or(Dimension::D2);
                if info.dimension != Some(dim) {
                    p.push(format!(
                        "{at}: `{}` is a {:?} texture in the WGSL, `{name}` is {dim:?}",
                        info.name, info.dimension
                    ));
                }
                if info.kind == BindingKind::StorageTexture {
                    if info.format.as_deref() != r.format.map(TexelFormat::wgsl) {
                        p.push(format!(
                            "{at}: `{}` stores {:?} texels, but `{name}` is {:?}",
                            info.name, info.format, r.format
                        ));
                    }
                    if info.access.is_some_and(Access::writes) && (previous || r.upload.is_some()) {
                        p.push(format!(
                            "{at}: `{}` writes `{target}`, which only passes may read (uploaded, or last frame's)",
                            info.name
                        ));
                    }
                }
            }
            BindingKind::Other => p.push(format!(
                "{at}: `{}` has a type no backend can bind",
                info.name
            )),
            _ => {}
        }
    }
}

fn check_resource(r: &ResourceDesc, at: &str, p: &mut Vec<String>) {
    if let Some(u) = &r.upload
        && !UPLOADS.contains(&u.as_str())
    {
        p.push(format!(
            "{at}: uploads `{u}`; the host provides {UPLOADS:?}"
        ));
    }
    match r.kind {
        ResourceKind::Texture => {
            if r.format.is_none() {
                p.push(format!("{at}: a texture needs a `format`"));
            }
            if r.upload.is_some() && r.extent.is_some() {
                p.push(format!(
                    "{at}: an uploaded texture takes its data's size; drop `extent`"
                ));
            }
            if let Some(e) = &r.extent
                && let Err(e) = e.resolve(1, 1)
            {
                p.push(format!("{at}: {e}"));
            }
            if r.upload.is_some() && r.lifetime != Lifetime::Persistent {
                p.push(format!("{at}: an uploaded texture is `persistent`"));
            }
            if r.external && r.dimension.unwrap_or(Dimension::D2) != Dimension::D2 {
                p.push(format!("{at}: an external texture is 2d"));
            }
        }
        ResourceKind::Uniform if r.upload.as_deref() != Some("frame") => {
            p.push(format!("{at}: the uniform block is uploaded from `frame`"))
        }
        ResourceKind::Counters if r.counters.is_empty() => {
            p.push(format!("{at}: a counters buffer lists its `counters`"))
        }
        _ => {}
    }
    if r.kind != ResourceKind::Texture
        && (r.format.is_some() || r.extent.is_some() || r.dimension.is_some() || r.external)
    {
        p.push(format!(
            "{at}: only textures have a format, extent, dimension or external target"
        ));
    }
    if r.kind != ResourceKind::Sampler && (r.filter.is_some() || r.address.is_some()) {
        p.push(format!("{at}: only samplers have `filter` and `address`"));
    }
    if r.lifetime == Lifetime::History && r.kind != ResourceKind::Texture {
        p.push(format!("{at}: only textures can be history"));
    }
    let computed_persistent = r.lifetime == Lifetime::Persistent && r.upload.is_none();
    if !r.inputs.is_empty() && !computed_persistent {
        p.push(format!(
            "{at}: only a computed persistent resource has `inputs` (the others are made every frame or uploaded)"
        ));
    }
    for input in &r.inputs {
        if input_bytes(input).is_none() {
            p.push(format!(
                "{at}: input `{input}` is no member of the uniform block `Frame`, nor a \
                 component of one (`member.x` to `member.w`)"
            ));
        }
    }
}

/// The bytes of the uniform block that input `input` of a computed resource names: a whole
/// member (`sun_direction`) or one of its components (`camera_position.y`: a sky table needs
/// the camera's altitude, not where it stands over the ground). `None` if it names neither.
pub fn input_bytes(input: &str) -> Option<std::ops::Range<usize>> {
    let (member, component) = match input.split_once('.') {
        Some((m, c)) => (m, Some(c)),
        None => (input, None),
    };
    let i = stratus_scene::FrameUniforms::MEMBERS
        .iter()
        .position(|(m, _)| *m == member)?;
    let start = 16 * i;
    match component {
        None => Some(start..start + 16),
        Some(c) => {
            let k = ["x", "y", "z", "w"].iter().position(|n| *n == c)?;
            Some(start + 4 * k..start + 4 * k + 4)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A member names its 16 bytes, a component its 4; anything else nothing.
    #[test]
    fn inputs_name_members_or_their_components() {
        assert_eq!(input_bytes("camera_position"), Some(0..16));
        assert_eq!(input_bytes("camera_position.y"), Some(4..8));
        assert_eq!(input_bytes("sun_direction.w"), Some(76..80));
        assert_eq!(input_bytes("camera_position.fov"), None);
        assert_eq!(input_bytes("air"), None);
        assert_eq!(input_bytes("sun_direction."), None);
    }
}
