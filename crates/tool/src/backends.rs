//! The one backend factory: every subcommand, the viewer and the lab open their renderers
//! here, and this is the one place that reads `STRATUS_VALIDATION`.

use anyhow::Result;
use clap::ValueEnum;
use stratus_backend_wgpu as backend_wgpu;
use stratus_reference::CpuBackend;

/// Which renderer runs the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The best available: wgpu on Vulkan, else wgpu on GL.
    Auto,
    /// wgpu on Vulkan.
    Wgpu,
    /// wgpu on OpenGL through EGL.
    WgpuGl,
    /// Raw Vulkan (ash), running the committed SPIR-V in spirv-out/.
    Ash,
    /// The CPU renderer with the real-time settings (the GPU's steps and jitter, in f64).
    Cpu,
    /// The CPU reference: converged quadrature, or Monte Carlo with --integrator montecarlo.
    Reference,
}

/// How to open a real-time renderer.
#[derive(Clone, Copy, Debug)]
pub struct Open {
    /// The backends' validation (wgpu's and the Vulkan layer): any message fails the frame.
    pub validation: bool,
    /// The CPU renderer's per-frame progress bar.
    pub progress: bool,
    /// Time every GPU pass by submitting it alone and waiting (the bench's wall-clock
    /// timings); GPU backends only.
    pub cpu_wall_timing: bool,
}

impl Default for Open {
    /// Validation as `STRATUS_VALIDATION` says; no progress bar, GPU timestamps.
    fn default() -> Self {
        Self {
            validation: validation(),
            progress: false,
            cpu_wall_timing: false,
        }
    }
}

/// `STRATUS_VALIDATION=1` turns on the backends' validation (wgpu's and the Vulkan layer).
pub fn validation() -> bool {
    std::env::var_os("STRATUS_VALIDATION").is_some()
}

fn wgpu(api: backend_wgpu::Api, how: &Open) -> Result<backend_wgpu::Renderer, backend_wgpu::Error> {
    let mut r = backend_wgpu::Renderer::new(backend_wgpu::Options {
        api,
        validation: how.validation,
    })?;
    r.set_cpu_wall_timing(how.cpu_wall_timing);
    Ok(r)
}

/// The CPU renderer with the GPU's real-time settings; `progress`: a progress bar per frame.
pub fn cpu_realtime(progress: bool) -> CpuBackend {
    CpuBackend {
        integrator: stratus_reference::Integrator::Quadrature(
            stratus_reference::QuadratureSettings::realtime(),
        ),
        label: "cpu (real-time settings)",
        progress,
        ..CpuBackend::default()
    }
}

/// A real-time renderer (not the reference): `auto` falls back from Vulkan to GL to the CPU,
/// saying so. `progress`: the CPU renderer's per-frame progress bar.
pub fn open_realtime(backend: Backend, progress: bool) -> Result<Box<dyn stratus_graph::Backend>> {
    open(
        backend,
        &Open {
            progress,
            ..Open::default()
        },
    )
}

/// A real-time renderer opened as `how` says (see [`open_realtime`]).
pub fn open(backend: Backend, how: &Open) -> Result<Box<dyn stratus_graph::Backend>> {
    Ok(match backend {
        Backend::Wgpu => Box::new(wgpu(backend_wgpu::Api::Vulkan, how)?),
        Backend::WgpuGl => Box::new(wgpu(backend_wgpu::Api::Gl, how)?),
        Backend::Ash => {
            let mut r = stratus_backend_ash::Renderer::new(stratus_backend_ash::Options {
                validation: how.validation,
            })?;
            r.set_cpu_wall_timing(how.cpu_wall_timing);
            Box::new(r)
        }
        Backend::Cpu => Box::new(cpu_realtime(how.progress)),
        Backend::Reference => anyhow::bail!(
            "--backend reference renders stills only; use cpu, wgpu, wgpu-gl, ash or auto"
        ),
        Backend::Auto => match wgpu(backend_wgpu::Api::Vulkan, how) {
            Ok(r) => Box::new(r),
            // Validation was asked for and cannot be had: say so, rather than render
            // unvalidated on another backend.
            Err(e @ backend_wgpu::Error::NoValidationLayer) => return Err(e.into()),
            Err(vulkan) => match wgpu(backend_wgpu::Api::Gl, how) {
                Ok(r) => {
                    eprintln!(
                        "note: no usable Vulkan device ({vulkan}); using wgpu's GL backend (install mesa-vulkan-drivers for a Vulkan device)"
                    );
                    Box::new(r)
                }
                Err(gl) => {
                    eprintln!(
                        "note: no usable Vulkan device ({vulkan}) or GL device ({gl}); rendering on the CPU (install mesa-vulkan-drivers for a Vulkan device)"
                    );
                    Box::new(cpu_realtime(how.progress))
                }
            },
        },
    })
}
