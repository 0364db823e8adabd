//! The execution paths and the renderers behind them, each created once per test binary.

use std::{collections::HashMap, path::PathBuf, sync::Arc};

use stratus_backend_ash as ash_backend;
use stratus_backend_wgpu as wgpu_backend;
use stratus_graph::{FrameInput, FrameOutput, FramePlan, plan::PassKind};
use stratus_noise::NoiseSet;
use stratus_scene::Scene;

use crate::spirv::{self, Lang};

/// An execution path. The labels are the ones the issue fixes for tables and test names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Path {
    /// 1. wgpu on Vulkan, from the WGSL (wgpu's own naga translation).
    WgpuVulkan,
    /// 2. ash, from the committed `spirv-out/<module>.<variant>.spv`.
    AshSpv,
    /// 3. wgpu on GL (naga's GLSL inside wgpu, Mesa's GLSL compiler).
    WgpuGl,
    /// 4. ash, from naga's GLSL (translated at test time) compiled by glslangValidator.
    AshGlsl,
    /// 5. ash, from naga's HLSL (translated at test time) compiled by glslang's HLSL front end.
    AshHlsl,
    /// 6. The CPU reference (quadrature at the scene's real-time settings).
    Cpu,
    /// 7. The engine kit in headless Chromium (Tint compiling the WGSL, SwiftShader running
    ///    it, web/stratus-kit.js running the plan): `cargo xtask web-test` renders, the suite
    ///    reads its images.
    WebTint,
    /// naga's MSL: pinned by a snapshot, not executed (no Metal runtime here).
    Msl,
}

impl Path {
    /// Every path, in table order.
    pub const ALL: [Path; 8] = [
        Path::WgpuVulkan,
        Path::AshSpv,
        Path::WgpuGl,
        Path::AshGlsl,
        Path::AshHlsl,
        Path::Cpu,
        Path::WebTint,
        Path::Msl,
    ];

    /// The label in tables and test names.
    pub fn label(self) -> &'static str {
        match self {
            Path::WgpuVulkan => "wgpu-vulkan",
            Path::AshSpv => "ash-spv",
            Path::WgpuGl => "wgpu-gl",
            Path::AshGlsl => "ash-glsl",
            Path::AshHlsl => "ash-hlsl",
            Path::Cpu => "cpu",
            Path::WebTint => "web-tint",
            Path::Msl => "msl",
        }
    }

    /// What runs, in words.
    pub fn about(self) -> &'static str {
        match self {
            Path::WgpuVulkan => "wgpu on Vulkan, from the WGSL (wgpu's own naga translation)",
            Path::AshSpv => "ash, from the committed spirv-out/<module>.<variant>.spv",
            Path::WgpuGl => "wgpu on GL (naga's GLSL inside wgpu, Mesa's GLSL compiler)",
            Path::AshGlsl => {
                "ash, naga's GLSL (translated at test time) compiled by glslangValidator -V"
            }
            Path::AshHlsl => {
                "ash, naga's HLSL (translated at test time) compiled by glslangValidator -D -V -e <entry> (HLSL front end), legalized by spirv-opt --legalize-hlsl"
            }
            Path::Cpu => "the CPU reference, quadrature at the scene's real-time settings",
            Path::WebTint => {
                "the engine kit in headless Chromium: Tint compiles the WGSL, SwiftShader runs it, web/stratus-kit.js runs the plan (`cargo xtask web-test`, which `cargo xtask ci` runs before the suite; display image only, the kit's presets)"
            }
            Path::Msl => "naga's MSL: pinned by a snapshot, not executed (no Metal runtime here)",
        }
    }
}

/// Messages wgpu logged since the last call (the shared recorder: the Vulkan validation
/// layer's messages about wgpu's calls arrive this way); any of them fails the path that
/// caused it.
fn logged() -> Vec<String> {
    stratus_test_support::take_wgpu_log()
}

fn init_logging() {
    stratus_test_support::record_wgpu_log();
}

/// Fails with what wgpu logged, if anything.
fn check_log(what: &str) -> Result<(), String> {
    let msgs = logged();
    if msgs.is_empty() {
        Ok(())
    } else {
        Err(format!("{what}: validation messages:\n{}", msgs.join("\n")))
    }
}

/// Why a wgpu renderer could not be created.
enum WgpuFailure {
    /// The device has no compute shaders: on a device of another class the path is not
    /// executed (see [`Renderers::unsupported`]).
    NoCompute(String),
    Other(String),
}

impl From<WgpuFailure> for String {
    fn from(f: WgpuFailure) -> String {
        match f {
            WgpuFailure::NoCompute(e) | WgpuFailure::Other(e) => e,
        }
    }
}

fn wgpu_renderer(api: wgpu_backend::Api) -> Result<wgpu_backend::Renderer, WgpuFailure> {
    let r = wgpu_backend::Renderer::new(wgpu_backend::Options {
        api,
        validation: true,
    })
    .map_err(|e| match e {
        wgpu_backend::Error::NoCompute { .. } => {
            // The backend's compute probe failing logs wgpu's translation error: that is the
            // refusal itself, not a message about another path.
            let _ = logged();
            WgpuFailure::NoCompute(e.to_string())
        }
        e => WgpuFailure::Other(e.to_string()),
    })?;
    check_log(&format!("creating the wgpu {api:?} renderer")).map_err(WgpuFailure::Other)?;
    Ok(r)
}

/// A frame, and the passes that did not run from the path's own shaders.
pub struct Rendered {
    pub frame: FrameOutput,
    /// `(pass, why)` for every pass that ran from the committed SPIR-V instead, because the
    /// device cannot bind what the path's module declares.
    pub substituted: Vec<(String, String)>,
}

/// The supplied modules of a variant: glslang's output, with the passes the device cannot
/// bind replaced by the committed SPIR-V's.
struct Prepared {
    shaders: ash_backend::Shaders,
    substituted: Vec<(String, String)>,
}

/// The renderers, each created once, and the glslang output per variant.
pub struct Renderers {
    wgpu_vulkan: Result<wgpu_backend::Renderer, String>,
    wgpu_gl: Result<wgpu_backend::Renderer, String>,
    /// wgpu found a GL device without compute shaders (NVIDIA's EGL): a capability every
    /// frame needs, which the golden device has.
    gl_without_compute: bool,
    /// The device class (set once wgpu-vulkan's device is known).
    pub class: crate::report::DeviceClass,
    ash: Result<ash_backend::Renderer, String>,
    cpu: stratus_reference::CpuBackend,
    compiled: HashMap<(String, String, Lang), Result<Prepared, String>>,
    scratch: PathBuf,
}

impl Renderers {
    /// Creates every renderer, all with validation on. `scratch` receives glslang's output.
    pub fn new(scratch: PathBuf) -> Self {
        init_logging();
        let (wgpu_gl, gl_without_compute) = match wgpu_renderer(wgpu_backend::Api::Gl) {
            Err(WgpuFailure::NoCompute(e)) => (Err(e), true),
            other => (other.map_err(String::from), false),
        };
        Self {
            wgpu_vulkan: wgpu_renderer(wgpu_backend::Api::Vulkan).map_err(String::from),
            wgpu_gl,
            gl_without_compute,
            class: crate::report::DeviceClass::Golden,
            ash: ash_backend::Renderer::new(ash_backend::Options { validation: true })
                .map_err(|e| e.to_string()),
            cpu: stratus_reference::CpuBackend::default(),
            compiled: HashMap::new(),
            scratch,
        }
    }

    /// Why `path` is not executed on this device, if it is not: on a device of another class,
    /// wgpu-gl where the GL device has no compute shaders (NVIDIA's EGL). On the golden
    /// device that is a failure like any other.
    pub fn unsupported(&self, path: Path) -> Option<&'static str> {
        (path == Path::WgpuGl
            && self.gl_without_compute
            && self.class == crate::report::DeviceClass::Other)
            .then_some("the GL device has no compute shaders (wgpu refuses it by name)")
    }

    /// The device of each GPU path, in words.
    pub fn devices(&self) -> Vec<(Path, String)> {
        let d = |r: &Result<String, String>| match r {
            Ok(s) => s.clone(),
            Err(e) => format!("unavailable: {e}"),
        };
        vec![
            (
                Path::WgpuVulkan,
                d(&self
                    .wgpu_vulkan
                    .as_ref()
                    .map(|r| r.adapter())
                    .map_err(Clone::clone)),
            ),
            (
                Path::WgpuGl,
                d(&self
                    .wgpu_gl
                    .as_ref()
                    .map(|r| r.adapter())
                    .map_err(Clone::clone)),
            ),
            (
                Path::AshSpv,
                d(&self.ash.as_ref().map(|r| r.adapter()).map_err(Clone::clone)),
            ),
        ]
    }

    /// Renders `scene` on `path` (with the statistics variant if `stats`; the CPU always
    /// counts). Any validation message is an error.
    pub fn render(
        &mut self,
        path: Path,
        scene: &Scene,
        noise: &Arc<NoiseSet>,
        stats: bool,
    ) -> Result<Rendered, String> {
        self.render_frame(path, scene, noise, stats, false, &[])
    }

    /// [`Renderers::render`] with every computed persistent resource (the air's tables)
    /// computed again, so that every pass of the plan runs in this frame: the ash/wgpu time
    /// ratio then has a pair for each pass in every round.
    pub fn render_every_pass(
        &mut self,
        path: Path,
        scene: &Scene,
        noise: &Arc<NoiseSet>,
    ) -> Result<Rendered, String> {
        let plan = FramePlan::for_scene(scene, false).map_err(|e| e.to_string())?;
        let computed: Vec<&str> = plan
            .resources
            .iter()
            .filter(|r| r.is_computed_persistent())
            .map(|r| r.name.as_str())
            .collect();
        self.render_frame(path, scene, noise, false, false, &computed)
    }

    /// [`Renderers::render`] as a frame of a sequence: `cut` starts the history over (the
    /// first frame of a path's sequence), otherwise the renderer reprojects last frame's.
    /// `invalidate` names computed persistent resources to compute again in this frame.
    pub fn render_frame(
        &mut self,
        path: Path,
        scene: &Scene,
        noise: &Arc<NoiseSet>,
        stats: bool,
        cut: bool,
        invalidate: &[&str],
    ) -> Result<Rendered, String> {
        let plan = FramePlan::for_scene(scene, stats).map_err(|e| e.to_string())?;
        let mut frame = FrameInput::new(&plan, scene, noise).with_invalidated(invalidate);
        if cut {
            frame = frame.with_cut();
        }
        let whole = |frame| Rendered {
            frame,
            substituted: Vec::new(),
        };
        match path {
            Path::WgpuVulkan | Path::WgpuGl => {
                let r = if path == Path::WgpuVulkan {
                    &mut self.wgpu_vulkan
                } else {
                    &mut self.wgpu_gl
                };
                let r = r.as_mut().map_err(|e| e.clone())?;
                let out = r.render(&frame).map_err(|e| e.to_string());
                check_log(path.label())?;
                out.map(whole)
            }
            Path::AshSpv => {
                let r = self.ash.as_mut().map_err(|e| e.clone())?;
                r.render(&frame).map(whole).map_err(|e| e.to_string())
            }
            Path::AshGlsl | Path::AshHlsl => {
                let lang = if path == Path::AshGlsl {
                    Lang::Glsl
                } else {
                    Lang::Hlsl
                };
                let r = self.ash.as_mut().map_err(|e| e.clone())?;
                // A variant's shaders per list of entry points: temporal plans and the
                // baselines run other entry points, some under the same pass names.
                let passes: Vec<String> = plan
                    .passes
                    .iter()
                    .map(|p| match &p.kind {
                        PassKind::Compute { entry, .. } => format!("{}:{entry}", p.name),
                        _ => p.name.clone(),
                    })
                    .collect();
                let key = (plan.variant.clone(), passes.join(","), lang);
                if !self.compiled.contains_key(&key) {
                    let prepared = spirv::compile(&plan, lang, &self.scratch)
                        .and_then(|list| prepare(r, &frame, lang, list));
                    self.compiled.insert(key.clone(), prepared);
                }
                let p = self.compiled[&key].as_ref().map_err(|e| e.clone())?;
                let frame = r
                    .render_with(&frame, &p.shaders)
                    .map_err(|e| e.to_string())?;
                Ok(Rendered {
                    frame,
                    substituted: p.substituted.clone(),
                })
            }
            // The CPU renderer at the real-time settings, keeping temporal history as the GPU
            // renderers do.
            Path::Cpu => {
                use stratus_graph::Backend as _;
                self.cpu
                    .render(&frame)
                    .map(whole)
                    .map_err(|e| e.to_string())
            }
            Path::Msl => Err("MSL is not executed here (no Metal runtime)".into()),
            Path::WebTint => Err("web-tint renders in the browser (`cargo xtask web-test`)".into()),
        }
    }

    /// Tears the renderers down; returns what validation reported while doing so (leaks).
    pub fn finish(self) -> Vec<String> {
        let mut problems = Vec::new();
        if let Ok(ash) = self.ash {
            if let Err(e) = ash.finish() {
                problems.push(format!("ash teardown: {e}"));
            }
        }
        drop(self.wgpu_vulkan);
        drop(self.wgpu_gl);
        problems.extend(logged());
        problems
    }
}

/// The only passes a path may run from the committed SPIR-V instead of its own module, each with
/// the reason the backend must give and why that is the translator's doing, not Stratus's.
/// Any other `Unsupported` pass fails the path: a silent substitution would let a path pass
/// without running the shaders it claims to test.
pub const DECLARED_SUBSTITUTIONS: &[(Lang, &str, &str, &str)] = &[
    (
        Lang::Hlsl,
        "march",
        "maxPerStageDescriptorSamplers",
        "naga's HLSL declares its sampler heap as arrays of 2048 samplers, more than lavapipe's 32 a stage; a device with a larger limit runs the pass from the HLSL",
    ),
    (
        Lang::Hlsl,
        "cloud-shadow",
        "maxPerStageDescriptorSamplers",
        "as `march`: the sampler heap of naga's HLSL",
    ),
    (
        Lang::Hlsl,
        "host-shadow",
        "maxPerStageDescriptorSamplers",
        "as `march`: the sampler heap of naga's HLSL",
    ),
    (
        Lang::Hlsl,
        "resolve",
        "maxPerStageDescriptorSamplers",
        "as `march`: the sampler heap of naga's HLSL",
    ),
    (
        Lang::Hlsl,
        "composite",
        "maxPerStageDescriptorSamplers",
        "as `march`: the sampler heap of naga's HLSL (the physical sky's composite samples the weather map for the rainbow's rain)",
    ),
    (
        Lang::Hlsl,
        "hdr-composite",
        "maxPerStageDescriptorSamplers",
        "as `composite`",
    ),
    (
        Lang::Hlsl,
        "sprite-build",
        "maxPerStageDescriptorSamplers",
        "as `march`: the sampler heap of naga's HLSL",
    ),
];

/// Whether `pass` may run from the committed SPIR-V on the `lang` path for the backend's
/// `reason`: only as [`DECLARED_SUBSTITUTIONS`] lists (that pass, that path, that reason).
fn may_substitute(lang: Lang, pass: &str, reason: &str) -> Result<(), String> {
    if DECLARED_SUBSTITUTIONS
        .iter()
        .any(|(l, p, why, _)| *l == lang && *p == pass && reason.contains(why))
    {
        Ok(())
    } else {
        Err(format!(
            "pass `{pass}` cannot run from the {lang:?} module ({reason}), and that is not a declared substitution (DECLARED_SUBSTITUTIONS in tests/tests/conformance/paths.rs)"
        ))
    }
}

/// Only the declared substitutions pass: another pass, another path or another reason fails
/// the path.
#[test]
fn an_undeclared_substitution_fails_the_path() {
    let sampler_limit = "binding needs 2048 samplers: maxPerStageDescriptorSamplers is 32";
    assert!(may_substitute(Lang::Hlsl, "march", sampler_limit).is_ok());
    let undeclared = may_substitute(Lang::Hlsl, "pathtrace", sampler_limit).unwrap_err();
    assert!(undeclared.contains("`pathtrace`") && undeclared.contains("not a declared"));
    assert!(may_substitute(Lang::Glsl, "march", sampler_limit).is_err());
    assert!(may_substitute(Lang::Hlsl, "march", "out of device memory").is_err());
}

/// Renders once to find the passes whose module the device cannot bind (the backend says so
/// with `Error::Unsupported` before creating anything), and runs those from the committed
/// SPIR-V instead, so that the rest of the path's shaders still run; only the substitutions
/// [`DECLARED_SUBSTITUTIONS`] lists are allowed.
fn prepare(
    r: &mut ash_backend::Renderer,
    frame: &FrameInput<'_>,
    lang: Lang,
    mut list: Vec<ash_backend::PassShader>,
) -> Result<Prepared, String> {
    let plan = frame.plan;
    let mut substituted: Vec<(String, String)> = Vec::new();
    loop {
        let shaders = ash_backend::Shaders::PerPass(list.clone());
        match r.render_with(frame, &shaders) {
            Ok(_) => {
                return Ok(Prepared {
                    shaders,
                    substituted,
                });
            }
            Err(ash_backend::Error::Unsupported { pass, reason, .. })
                if !substituted.iter().any(|(p, _)| *p == pass) =>
            {
                may_substitute(lang, &pass, &reason)?;
                // The supplied list holds the compute passes, in plan order.
                let computes: Vec<_> = plan
                    .passes
                    .iter()
                    .filter(|p| matches!(p.kind, PassKind::Compute { .. }))
                    .collect();
                let i = computes
                    .iter()
                    .position(|p| p.name == pass)
                    .ok_or_else(|| format!("the backend named an unknown pass {pass}"))?;
                list[i] = spirv::committed(plan, computes[i])?;
                substituted.push((pass, reason));
            }
            Err(e) => return Err(e.to_string()),
        }
    }
}
