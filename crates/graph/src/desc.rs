//! The frame graph as written in `wgsl/graph.toml`: resources (format, extent, lifetime, where
//! their data comes from) and passes (compute, or raster with colour/depth targets and blend
//! state; an extent; bindings from WGSL names to resources; an optional condition).
//!
//! It is data beside the WGSL, the one description of a frame that both backends execute:
//! adding a pass or a resource touches the WGSL and this file, never backend code. What a
//! resource is used for (sampled, storage, attachment, copy) is derived from the passes, so it
//! cannot drift from them. [`GraphDesc::check`] holds it against naga's reflection; `cargo
//! xtask build-shaders` runs that check and writes the checked graph into the manifest.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A texture's dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Dimension {
    /// 1D.
    #[serde(rename = "1d")]
    D1,
    /// 2D.
    #[serde(rename = "2d")]
    D2,
    /// 3D.
    #[serde(rename = "3d")]
    D3,
    /// Cube.
    #[serde(rename = "cube")]
    Cube,
}

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
    /// The host reads this texture in its own shaders (the cloud-shadow map): it is made
    /// sampleable whatever the passes bind it as.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub host_reads: bool,
    /// Members of the uniform block a computed persistent resource is computed from: it goes
    /// stale when one of them changes (a lookup table of the air, not of the sun, is computed
    /// again only when the air changes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<String>,
    /// Inputs that may drift this far (in every component, from the values the resource was
    /// computed at) before it goes stale, by name: a table of a sun that moves a few
    /// thousandths of a degree a second need not follow every frame. Inputs not named here
    /// must stay bit for bit.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub tolerance: BTreeMap<String, f64>,
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

pub use crate::options::PLAN_OPTIONS;

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
pub const UPLOADS: [&str; 7] = [
    "frame",
    "scene.depth",
    "noise.shape",
    "noise.detail",
    "noise.weather",
    "noise.curl",
    "stars.catalogue",
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
}

/// The bytes of the uniform block that input `input` of a computed resource names: a whole
/// member (`sun_direction`) or one component of a vector member (`camera_position.y`: a sky
/// table needs the camera's altitude, not where it stands over the ground). `None` if it names
/// neither.
pub fn input_bytes(input: &str) -> Option<std::ops::Range<usize>> {
    let (name, component) = match input.split_once('.') {
        Some((m, c)) => (m, Some(c)),
        None => (input, None),
    };
    let member = stratus_scene::FrameUniforms::MEMBERS
        .iter()
        .find(|m| m.name == name)?;
    let start = member.offset;
    match component {
        None => Some(start..start + member.size),
        Some(c) => {
            let k = ["x", "y", "z"][..member.components()]
                .iter()
                .position(|n| *n == c)?;
            (member.components() > 1).then(|| start + 4 * k..start + 4 * k + 4)
        }
    }
}

/// Whether input `input` (as [`input_bytes`] names it) is made of f32 values.
pub fn input_is_float(input: &str) -> bool {
    let name = input.split_once('.').map_or(input, |(m, _)| m);
    stratus_scene::FrameUniforms::MEMBERS
        .iter()
        .any(|m| m.name == name && !m.is_unsigned())
}

/// Whether input `input` of uniform blocks `now` and `then` differs: bit for bit, or, with a
/// tolerance, by more than it in some f32 component (a NaN differs from everything).
pub fn input_differs(input: &str, tolerance: Option<f64>, now: &[u8], then: &[u8]) -> bool {
    let Some(bytes) = input_bytes(input) else {
        return false;
    };
    let (a, b) = (&now[bytes.clone()], &then[bytes]);
    match tolerance {
        None => a != b,
        Some(t) => a.chunks_exact(4).zip(b.chunks_exact(4)).any(|(a, b)| {
            let f = |c: &[u8]| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]]));
            let d = (f(a) - f(b)).abs();
            d.is_nan() || d > t
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without a tolerance an input differs in any bit; with one, when some component moved
    /// by more than it (NaN always).
    #[test]
    fn inputs_differ_bit_for_bit_or_beyond_their_tolerance() {
        let block = |sun: [f32; 3]| {
            let mut u = stratus_scene::Scene::default().uniforms();
            u.sun_direction = sun;
            u
        };
        let then = block([0.0, 0.6, 0.8]);
        let near = block([1e-4, 0.6, 0.8]);
        let far = block([0.0, 0.6, 0.8 + 3e-4]);
        let nan = block([f32::NAN, 0.6, 0.8]);
        let differs = |now: &stratus_scene::FrameUniforms, t| {
            input_differs("sun_direction", t, now.as_bytes(), then.as_bytes())
        };
        assert!(!differs(&then, None));
        assert!(differs(&near, None));
        assert!(!differs(&near, Some(1.7e-4)));
        assert!(differs(&far, Some(1.7e-4)));
        assert!(differs(&nan, Some(1.7e-4)));
        assert!(input_is_float("sun_direction") && input_is_float("camera_position.y"));
        assert!(!input_is_float("flags") && !input_is_float("no_such_member"));
    }

    /// A member names its bytes, a vector's component its 4; anything else nothing.
    #[test]
    fn inputs_name_members_or_their_components() {
        assert_eq!(input_bytes("camera_position"), Some(0..12));
        assert_eq!(input_bytes("tan_half_fov"), Some(12..16));
        assert_eq!(input_bytes("camera_position.y"), Some(4..8));
        assert_eq!(input_bytes("sun_cos_radius"), Some(76..80));
        assert_eq!(input_bytes("sun_direction.w"), None);
        assert_eq!(input_bytes("tan_half_fov.x"), None);
        assert_eq!(input_bytes("weather_offset.z"), None);
        assert_eq!(input_bytes("camera_position.fov"), None);
        assert_eq!(input_bytes("air"), None);
        assert_eq!(input_bytes("sun_direction."), None);
    }
}
