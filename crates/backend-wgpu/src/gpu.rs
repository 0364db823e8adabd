//! The device: opened by the renderer (an instance with or without validation, the best
//! adapter for the API) or taken from an application, its uncaptured errors and loss, waiting
//! for it, and the timestamp queries. ash's `gpu.rs` holds the same for Vulkan.

use crate::*;

/// Timestamp queries and the buffers their results travel through.
pub(crate) struct Queries {
    pub(crate) set: wgpu::QuerySet,
    pub(crate) resolve: wgpu::Buffer,
    pub(crate) read: wgpu::Buffer,
    pub(crate) count: u32,
}

pub(crate) fn class_of(t: wgpu::DeviceType) -> DeviceClass {
    match t {
        wgpu::DeviceType::DiscreteGpu => DeviceClass::Discrete,
        wgpu::DeviceType::IntegratedGpu => DeviceClass::Integrated,
        wgpu::DeviceType::VirtualGpu => DeviceClass::Virtual,
        wgpu::DeviceType::Other => DeviceClass::Other,
        wgpu::DeviceType::Cpu => DeviceClass::Cpu,
    }
}

/// Waits for the device. wgpu 30's `Device::poll` panics on any error but a timeout (a real
/// device loss among them, after the lost callback has run), so the panic is caught and
/// turned into an error; the caller then finds the loss the callback recorded.
pub(crate) fn poll(device: &wgpu::Device) -> Result<(), Error> {
    let waited = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        device.poll(wgpu::PollType::wait_indefinitely())
    }));
    match waited {
        Ok(Ok(_)) => Ok(()),
        Ok(Err(e)) => Err(Error::Wgpu(e.to_string())),
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("no message");
            Err(Error::Wgpu(format!(
                "waiting for the device failed ({what}): the device was lost"
            )))
        }
    }
}

/// Whether the Vulkan loader lists the Khronos validation layer (the check backend-ash makes
/// before asking for it). Without a loader this says yes, so that the missing loader is what
/// the caller hears about (wgpu then finds no Vulkan adapter).
pub(crate) fn validation_layer_installed() -> bool {
    // SAFETY: loads the system's Vulkan loader as any Vulkan use does; the entry is dropped at
    // the end of this function and nothing created from it outlives it.
    let Ok(entry) = (unsafe { ash::Entry::load() }) else {
        return true;
    };
    // SAFETY: a global command of a loaded entry, with no handles involved.
    let layers = unsafe { entry.enumerate_instance_layer_properties() }.unwrap_or_default();
    layers.iter().any(|l| {
        l.layer_name_as_c_str()
            .is_ok_and(|n| n == c"VK_LAYER_KHRONOS_validation")
    })
}

pub(crate) fn describe(info: &wgpu::AdapterInfo) -> String {
    describe_device(
        &info.name,
        &format!("{:?}", info.backend),
        class_of(info.device_type),
    )
}

impl Renderer {
    /// Picks an adapter for `options.api` (a real GPU before a CPU driver), creates a device of
    /// its own, and runs the embedded shaders.
    pub fn new(options: Options) -> Result<Self, Error> {
        let program = Program::embedded().map_err(|e| Error::Shader(e.to_string()))?;
        Self::with_program(options, program)
    }

    /// As [`Renderer::new`], running `program` (a test's own graph and shaders).
    pub fn with_program(options: Options, program: Arc<Program>) -> Result<Self, Error> {
        let backends = match options.api {
            Api::Vulkan => wgpu::Backends::VULKAN,
            Api::Gl => wgpu::Backends::GL,
        };
        // wgpu goes on without the layer when it is missing; a caller who asked for
        // validation is told instead, as backend-ash tells it.
        if options.validation && options.api == Api::Vulkan && !validation_layer_installed() {
            return Err(Error::NoValidationLayer);
        }
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends;
        desc.flags = if options.validation {
            wgpu::InstanceFlags::VALIDATION
        } else {
            wgpu::InstanceFlags::empty()
        };
        let instance = wgpu::Instance::new(desc);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(backends));
        let classes: Vec<DeviceClass> = adapters
            .iter()
            .map(|a| class_of(a.get_info().device_type))
            .collect();
        let adapter = best_device(&classes)
            .map(|i| adapters.swap_remove(i))
            .ok_or(Error::NoAdapter {
                api: options.api,
                hint: match options.api {
                    Api::Vulkan => {
                        " (install a Vulkan driver: `apt-get install mesa-vulkan-drivers libvulkan1` gives lavapipe)"
                    }
                    Api::Gl => {
                        " (install EGL and a GL driver: `apt-get install libegl1 libgl1-mesa-dri`)"
                    }
                },
            })?;
        let info = adapter.get_info();
        // Every frame is compute passes: a device without them (NVIDIA's EGL gives wgpu a GL
        // context without compute shaders) is refused here, by name, so that `auto` moves on.
        if !adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        {
            return Err(Error::NoCompute {
                adapter: describe(&info),
            });
        }
        let mut required_features = wgpu::Features::empty();
        if adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            required_features |= wgpu::Features::TIMESTAMP_QUERY;
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("stratus"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| Error::Device {
            adapter: describe(&info),
            message: e.to_string(),
        })?;
        if options.api == Api::Gl {
            probe_gl_compute(&device, &info)?;
        }
        let errors = Arc::new(Mutex::new(Vec::new()));
        let sink = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            sink.lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(e.to_string());
        }));
        let lost = Arc::new(Mutex::new(None));
        let lost_sink = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            // wgpu gives no message for a destroyed device: the reason alone then.
            *lost_sink.lock().unwrap_or_else(|e| e.into_inner()) = Some(if message.is_empty() {
                format!("{reason:?}")
            } else {
                format!("{reason:?}: {message}")
            });
        });
        let mut renderer = Self::build(device, queue, describe(&info), program);
        renderer.errors = Some(errors);
        renderer.lost = lost;
        renderer.validation = options.validation;
        renderer.check_errors()?;
        Ok(renderer)
    }

    /// A renderer on an application's device and queue (the application keeps them, its own
    /// error handler and its device-lost callback: a lost device then shows as a failed
    /// read-back that says the device may be lost). Passes are timed where the device has
    /// `TIMESTAMP_QUERY`.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        program: Arc<Program>,
    ) -> Result<Self, Error> {
        Ok(Self::build(
            device,
            queue,
            "the application's wgpu device".into(),
            program,
        ))
    }

    pub(crate) fn build(
        device: wgpu::Device,
        queue: wgpu::Queue,
        description: String,
        program: Arc<Program>,
    ) -> Self {
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self {
            device,
            queue,
            description,
            timestamps,
            program,
            modules: HashMap::new(),
            pipelines: HashMap::new(),
            resources: HashMap::new(),
            plan: None,
            groups: Vec::new(),
            keys: Vec::new(),
            uniform: None,
            noise: None,
            scene_depth: None,
            bound: HashMap::new(),
            bound_changed: false,
            frames: FrameState::default(),
            queries: None,
            readbacks: HashMap::new(),
            errors: None,
            lost: Arc::new(Mutex::new(None)),
            validation: false,
            created: 0,
        }
    }

    /// The device the renderer runs on (its own, or the application's).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The adapter in words, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter(&self) -> String {
        self.description.clone()
    }

    /// Whether passes are timed with GPU timestamp queries (else by CPU wall time).
    pub fn has_timestamps(&self) -> bool {
        self.timestamps
    }

    pub(crate) fn check_errors(&self) -> Result<(), Error> {
        self.check_lost()?;
        let Some(errors) = &self.errors else {
            return Ok(());
        };
        let errors = std::mem::take(&mut *errors.lock().unwrap_or_else(|e| e.into_inner()));
        if errors.is_empty() {
            Ok(())
        } else {
            Err(self.classify(errors.join("\n")))
        }
    }

    /// [`Error::DeviceLost`] once the device is lost.
    pub(crate) fn check_lost(&self) -> Result<(), Error> {
        match &*self.lost.lock().unwrap_or_else(|e| e.into_inner()) {
            Some(reason) => Err(Error::DeviceLost {
                adapter: self.description.clone(),
                reason: reason.clone(),
            }),
            None => Ok(()),
        }
    }

    /// A wgpu error message as an [`Error`]: the device's loss once our callback has seen it
    /// (wgpu reports a loss through the callback alone, never through its errors), else the
    /// message.
    pub(crate) fn classify(&self, message: String) -> Error {
        if let Err(lost) = self.check_lost() {
            return lost;
        }
        Error::Wgpu(message)
    }

    pub(crate) fn wait(&self) -> Result<(), Error> {
        poll(&self.device)?;
        self.check_lost()
    }

    pub(crate) fn ensure_queries(&mut self, count: u32) {
        if !self.timestamps || count == 0 || self.queries.as_ref().is_some_and(|q| q.count >= count)
        {
            return;
        }
        let size = u64::from(count) * 8;
        let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass times"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let resolve = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.created += 3;
        self.queries = Some(Queries {
            set,
            resolve,
            read,
            count,
        });
    }

    pub(crate) fn resolve_queries(&self, encoder: &mut wgpu::CommandEncoder, passes: u32) {
        if let Some(q) = &self.queries
            && passes > 0
        {
            let n = 2 * passes;
            encoder.resolve_query_set(&q.set, 0..n, &q.resolve, 0);
            encoder.copy_buffer_to_buffer(&q.resolve, 0, &q.read, 0, u64::from(n) * 8);
        }
    }
}

/// Builds a one-line compute pipeline on a GL device and refuses the device if that fails. A
/// GL adapter may report compute shaders while wgpu's GL backend translates WGSL for a GLSL
/// version without them (NVIDIA's EGL: "The selected version doesn't support
/// Features(COMPUTE_SHADER)"): every Stratus pipeline would then fail, so the device is
/// refused at creation, by name, and `auto` moves on to the CPU.
fn probe_gl_compute(device: &wgpu::Device, info: &wgpu::AdapterInfo) -> Result<(), Error> {
    // A failed translation is an internal error in wgpu (and is logged at error level).
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("stratus gl compute probe"),
        source: wgpu::ShaderSource::Wgsl(
            "@group(0) @binding(0) var<storage, read_write> v: array<u32>;\n\
             @compute @workgroup_size(1) fn probe() { v[0] = 1u; }"
                .into(),
        ),
    });
    let _pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("stratus gl compute probe"),
        layout: None,
        module: &module,
        entry_point: Some("probe"),
        compilation_options: Default::default(),
        cache: None,
    });
    let failed = pollster::block_on(validation.pop());
    let failed = failed.or(pollster::block_on(internal.pop()));
    match failed {
        None => Ok(()),
        Some(e) => {
            // wgpu's message nests its causes over several lines; the last is the reason.
            let text = e.to_string();
            // wgpu-core words a failed translation "Internal error: <reason>": the reason is
            // the driver's, not a fault of wgpu's, so the prefix is not shown.
            let reason = text
                .lines()
                .map(str::trim)
                .rfind(|l| !l.is_empty())
                .unwrap_or("unknown");
            let reason = reason
                .strip_prefix("Internal error:")
                .map_or(reason, str::trim)
                .to_string();
            Err(Error::NoCompute {
                adapter: format!(
                    "{} (a one-line compute pipeline failed: {reason})",
                    describe(info)
                ),
            })
        }
    }
}
