//! The viewer's device, window surface, egui renderer and the clouds' renderer (the library on
//! wgpu, or the ash backend with [`stratus::Prepared`]), and the offscreen texture every frame
//! draws into.

use crate::*;

/// The renderer that draws the clouds.
pub(crate) enum Clouds {
    Wgpu(Box<stratus::Clouds>),
    /// The ash renderer, with the plan and noise the library keeps for its own (remade
    /// when the scene's plan key or noise changes).
    Ash {
        renderer: Box<dyn stratus_graph::Backend>,
        prepared: stratus::Prepared,
    },
}

pub(crate) struct Gpu {
    pub(crate) window: Arc<Window>,
    pub(crate) surface: wgpu::Surface<'static>,
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) config: wgpu::SurfaceConfiguration,
    pub(crate) offscreen: wgpu::Texture,
    pub(crate) egui_ctx: egui::Context,
    pub(crate) egui_state: egui_winit::State,
    pub(crate) egui_renderer: egui_wgpu::Renderer,
    pub(crate) clouds: Clouds,
    /// Renders stills for EXR screenshots and the work counters, on the viewer's backend.
    pub(crate) offline: Option<Box<dyn stratus_graph::Backend>>,
    pub(crate) describe: String,
    pub(crate) last_frame: Instant,
}

pub(crate) fn present_mode(vsync: Vsync, modes: &[wgpu::PresentMode]) -> wgpu::PresentMode {
    match vsync {
        Vsync::On => wgpu::PresentMode::Fifo,
        Vsync::Off => [wgpu::PresentMode::Immediate, wgpu::PresentMode::Mailbox]
            .into_iter()
            .find(|m| modes.contains(m))
            .unwrap_or(wgpu::PresentMode::Fifo),
    }
}

pub(crate) fn offscreen_texture(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    w: u32,
    h: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("view frame"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

/// RGBA8 bytes in the window's format (BGRA swaps red and blue).
pub(crate) fn to_format(rgba: &[u8], format: wgpu::TextureFormat) -> Vec<u8> {
    let mut out = rgba.to_vec();
    if format == wgpu::TextureFormat::Bgra8Unorm {
        out.chunks_exact_mut(4).for_each(|p| p.swap(0, 2));
    }
    out
}

/// Row pitch of a texture-to-buffer copy (a multiple of 256 bytes).
pub(crate) fn padded_row(width: u32) -> u32 {
    (4 * width).div_ceil(256) * 256
}

pub(crate) fn copy_to_buffer(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> wgpu::Buffer {
    let size = texture.size();
    let row = padded_row(size.width);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot"),
        size: u64::from(row) * u64::from(size.height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
    buffer
}

impl Gpu {
    pub(crate) fn resize(&mut self, size: PhysicalSize<u32>) {
        if size.width == 0 || size.height == 0 {
            return;
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&self.device, &self.config);
        self.offscreen =
            offscreen_texture(&self.device, self.config.format, size.width, size.height);
    }
}

impl App {
    pub(crate) fn create_gpu(&mut self, event_loop: &ActiveEventLoop) -> Result<Gpu> {
        let [w, h] = self.state.scene.camera.resolution;
        let window = Arc::new(
            event_loop
                .create_window(
                    Window::default_attributes()
                        .with_title(format!("Stratus: {}", self.state.name))
                        .with_inner_size(PhysicalSize::new(w, h))
                        .with_resizable(!self.options.scripted),
                )
                .context("creating the window")?,
        );
        let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(window.clone()));
        desc.backends = wgpu::Backends::VULKAN;
        desc.flags = if stratus_tool::backends::validation() {
            wgpu::InstanceFlags::VALIDATION
        } else {
            wgpu::InstanceFlags::empty()
        };
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(window.clone())
            .context("creating a Vulkan surface for the window")?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .context("no Vulkan adapter can present to this window (install mesa-vulkan-drivers for lavapipe)")?;
        let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("stratus view"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .context("creating the device")?;
        let caps = surface.get_capabilities(&adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .or_else(|| caps.formats.first().map(|f| f.remove_srgb_suffix()))
            .context("the surface offers no formats")?;
        if !caps.usages.contains(wgpu::TextureUsages::COPY_DST) {
            bail!("the window's swapchain images cannot be copied into (no COPY_DST usage)");
        }
        let present_mode = present_mode(self.options.vsync, &caps.present_modes);
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
            desired_maximum_frame_latency: 2,
        };
        surface.configure(&device, &config);
        let offscreen = offscreen_texture(&device, format, config.width, config.height);
        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(1.0),
            None,
            None,
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&device, format, egui_wgpu::RendererOptions::default());
        let info = adapter.get_info();
        let (clouds, describe) = match self.options.backend {
            ViewBackend::Wgpu => (
                Clouds::Wgpu(Box::new(
                    stratus::Clouds::new(&device, &queue, self.state.scene.clone())
                        .map_err(|e| anyhow!("{e}"))?,
                )),
                format!("wgpu (Vulkan) on {}", info.name),
            ),
            ViewBackend::Ash => {
                let renderer = open_realtime(Backend::Ash, false)?;
                let describe = format!(
                    "{}, shown through wgpu on {}",
                    renderer.describe(),
                    info.name
                );
                (
                    Clouds::Ash {
                        renderer,
                        prepared: stratus::Prepared::new(&self.state.scene)?,
                    },
                    describe,
                )
            }
        };
        Ok(Gpu {
            window,
            surface,
            device,
            queue,
            config,
            offscreen,
            egui_ctx,
            egui_state,
            egui_renderer,
            clouds,
            offline: None,
            describe: format!("{describe}, {:?}", present_mode),
            last_frame: Instant::now(),
        })
    }
}
