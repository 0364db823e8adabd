//! GPU objects of the frame graph's resources (buffers, textures and their views, samplers),
//! made when a plan needs them and kept while they serve it, the device limits a plan must
//! fit, and reading results back. ash's `resources.rs` holds the same for Vulkan.

use crate::*;

/// The GPU side of a resource of the plan.
pub(crate) struct Resource {
    /// What it was made from (kept while it serves the plan).
    pub(crate) made: Made,
    pub(crate) object: Object,
}

pub(crate) enum Object {
    Buffer(wgpu::Buffer),
    /// One texture, or two for a history pair.
    Textures(Vec<(wgpu::Texture, wgpu::TextureView)>),
    Sampler(wgpu::Sampler),
}

/// A copy recorded for readback: the resource (by index into the plan's; its readback buffer
/// goes by its name), where it goes in the output, and the row layout of a texture (padded row
/// bytes, row bytes, rows).
pub(crate) struct Copied {
    pub(crate) index: usize,
    pub(crate) readout: Readout,
    pub(crate) rows: Option<(u32, u32, u32)>,
}

pub(crate) fn extent3d([width, height, depth_or_array_layers]: [u32; 3]) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers,
    }
}

/// Maps a readback buffer, copies its data out (dropping row padding), and unmaps it.
pub(crate) fn read_buffer(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    rows: Option<(u32, u32, u32)>,
) -> Result<Vec<u8>, Error> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    poll(device)?;
    rx.recv()
        .map_err(|e| Error::Wgpu(e.to_string()))?
        // wgpu drops "device lost" errors in favour of the device-lost callback, so on an
        // application's device (whose callback is the application's) a failed map is all
        // that shows of a loss.
        .map_err(|e| {
            Error::Wgpu(format!(
                "mapping a read-back buffer failed ({e}): the device was lost, or could not create the buffer"
            ))
        })?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| Error::Wgpu(e.to_string()))?;
    // An invalid buffer (one wgpu could not create) maps as empty: say so, never index it.
    let needed = match rows {
        Some((padded, row, h)) => {
            u64::from(padded) * u64::from(h.saturating_sub(1)) + u64::from(row)
        }
        None => 0,
    };
    if (data.len() as u64) < needed {
        return Err(Error::Wgpu(format!(
            "a read-back buffer mapped {} bytes of the {needed} it should hold (the device could not create it)",
            data.len()
        )));
    }
    let out = match rows {
        Some((padded, row, h)) => (0..h)
            .flat_map(|y| {
                let start = (y * padded) as usize;
                data[start..start + row as usize].iter().copied()
            })
            .collect(),
        None => data.to_vec(),
    };
    drop(data);
    buffer.unmap();
    Ok(out)
}

impl Renderer {
    pub(crate) fn create_resource(&mut self, made: &Made) -> Result<Object, Error> {
        let r = &made.desc;
        Ok(match r.kind {
            ResourceKind::Uniform => {
                // The one uniform block, created with the renderer's first plan.
                Object::Buffer(self.uniform.clone().expect("created before resources"))
            }
            ResourceKind::Counters => {
                self.created += 1;
                Object::Buffer(self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&r.name),
                    size: r.buffer_size().max(4),
                    usage: wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_SRC
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }))
            }
            ResourceKind::Sampler => {
                self.created += 1;
                let s = r
                    .sampler
                    .ok_or_else(|| Error::Shader(format!("sampler `{}` has no state", r.name)))?;
                Object::Sampler(self.device.create_sampler(&convert::sampler(s)))
            }
            ResourceKind::Texture => {
                let size = made.size().map_err(Error::Shader)?;
                let f = r
                    .format
                    .ok_or_else(|| Error::Shader(format!("texture `{}` has no format", r.name)))?;
                let (dimension, view_dimension) = convert::dimension(r.dimension);
                let count = if r.lifetime == Lifetime::History {
                    2
                } else {
                    1
                };
                let mut list = Vec::new();
                for half in 0..count {
                    let label = if count == 2 {
                        format!("{}[{half}]", r.name)
                    } else {
                        r.name.clone()
                    };
                    let texture = self.device.create_texture(&wgpu::TextureDescriptor {
                        label: Some(&label),
                        size: extent3d(size),
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension,
                        format: convert::format(f),
                        usage: convert::texture_usage(r.usage, f),
                        view_formats: &[],
                    });
                    let view = texture.create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(view_dimension),
                        ..Default::default()
                    });
                    self.created += 2;
                    list.push((texture, view));
                }
                Object::Textures(list)
            }
        })
    }

    /// The view of a texture resource for this frame (the current half of a history pair).
    pub(crate) fn view(&self, plan: &FramePlan, index: usize) -> Result<&wgpu::TextureView, Error> {
        let r = &plan.resources[index];
        match &self.resources[&r.name].object {
            Object::Textures(t) => {
                let half = if r.lifetime == Lifetime::History {
                    history_half(self.frames.frame(), false)
                } else {
                    0
                };
                Ok(&t[half].1)
            }
            _ => Err(Error::Shader(format!("`{}` is not a texture", r.name))),
        }
    }

    pub(crate) fn readback_buffer(&mut self, name: &str, size: u64) -> wgpu::Buffer {
        if let Some(b) = self.readbacks.get(name)
            && b.size() == size
        {
            return b.clone();
        }
        let b = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.created += 1;
        self.readbacks.insert(name.into(), b.clone());
        b
    }

    /// Records the copies a frame's readback asks for into persistent readback buffers.
    pub(crate) fn copy_readbacks(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
    ) -> Result<Vec<Copied>, Error> {
        let plan = frame.plan;
        let wanted = frame.readback.targets(plan).map_err(Error::Shader)?;
        let mut out = Vec::new();
        for (i, readout) in wanted {
            let r = &plan.resources[i];
            let buffer = match &self.resources[&r.name].object {
                Object::Buffer(b) => Some(b.clone()),
                _ => None,
            };
            match &self.resources[&r.name].object {
                Object::Buffer(_) => {
                    let b = buffer.expect("a buffer");
                    let size = b.size();
                    let rb = self.readback_buffer(&r.name, size);
                    encoder.copy_buffer_to_buffer(&b, 0, &rb, 0, size);
                    out.push(Copied {
                        index: i,
                        readout,
                        rows: None,
                    });
                }
                Object::Textures(_) => {
                    let texture = self.view(plan, i)?.texture().clone();
                    let f = r
                        .format
                        .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm);
                    let [w, h, d] = self.resources[&r.name].made.size().map_err(Error::Shader)?;
                    let row = w * f.texel_size();
                    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
                        * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
                    let rb = self.readback_buffer(&r.name, u64::from(padded * h * d));
                    encoder.copy_texture_to_buffer(
                        texture.as_image_copy(),
                        wgpu::TexelCopyBufferInfo {
                            buffer: &rb,
                            layout: wgpu::TexelCopyBufferLayout {
                                offset: 0,
                                bytes_per_row: Some(padded),
                                rows_per_image: Some(h),
                            },
                        },
                        texture.size(),
                    );
                    out.push(Copied {
                        index: i,
                        readout,
                        rows: Some((padded, row, h * d)),
                    });
                }
                Object::Sampler(_) => {
                    return Err(Error::Shader(format!(
                        "readback of `{}`: a sampler holds no data",
                        r.name
                    )));
                }
            }
        }
        Ok(out)
    }

    /// Every texture of `plan` within the device's dimension limits, and every output's
    /// read-back within its buffer size limit: a clear error before anything is allocated
    /// (wgpu would otherwise hand back an invalid, empty buffer).
    pub(crate) fn check_limits(&self, plan: &FramePlan) -> Result<(), Error> {
        let limits = self.device.limits();
        let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
        for r in &plan.resources {
            let (Some([w, h, d]), Some(format)) = (r.extent, r.format) else {
                continue;
            };
            let (max, what) = if r.dimension == stratus_graph::manifest::Dimension::D3 {
                (limits.max_texture_dimension_3d, "max_texture_dimension_3d")
            } else {
                (limits.max_texture_dimension_2d, "max_texture_dimension_2d")
            };
            if w.max(h).max(d) > max {
                return Err(Error::Limit(format!(
                    "`{}` would be {w}x{h}x{d} texels; this device allows at most {max} a side ({what}): render a smaller image",
                    r.name
                )));
            }
            let bytes = u64::from(w) * u64::from(h) * u64::from(d) * u64::from(format.texel_size());
            if r.output.is_some() && bytes > limits.max_buffer_size {
                return Err(Error::Limit(format!(
                    "reading back `{}` ({w}x{h} {}) needs a {:.1} GiB buffer; this device allows at most {:.1} GiB (max_buffer_size): render a smaller image",
                    r.name,
                    format.wgsl(),
                    gib(bytes),
                    gib(limits.max_buffer_size)
                )));
            }
        }
        Ok(())
    }
}
