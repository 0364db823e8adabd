// A consumer of the Stratus engine kit on WebGPU, in plain JavaScript and nothing of Stratus's
// code: it reads only the kit (kit.json, manifest.json, the WGSL, the noise textures, a
// golden's uniform bytes and resolved frame plan) and runs the plan's passes in order. The
// browser compiles the WGSL with its own compiler (Tint in Chromium), independent of naga.

const GPU_BUFFER_USAGE = () => globalThis.GPUBufferUsage;
const GPU_TEXTURE_USAGE = () => globalThis.GPUTextureUsage;
const GPU_SHADER_STAGE = () => globalThis.GPUShaderStage;

async function fetchOk(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r;
}

/** Loads the kit at `base` (a URL folder) and opens a WebGPU device. */
export async function loadKit(base) {
  if (!navigator.gpu) throw new Error('this browser has no WebGPU (navigator.gpu)');
  const kit = await (await fetchOk(`${base}/kit.json`)).json();
  const manifest = await (await fetchOk(`${base}/manifest.json`)).json();
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error('no WebGPU adapter');
  const device = await adapter.requestDevice({
    requiredLimits: {
      maxStorageTexturesPerShaderStage: Math.min(8, adapter.limits.maxStorageTexturesPerShaderStage),
    },
  });
  const errors = [];
  device.addEventListener('uncapturederror', (e) => errors.push(e.error.message));
  return {
    base, kit, manifest, device, errors,
    adapter: adapter.info ? { vendor: adapter.info.vendor, architecture: adapter.info.architecture } : {},
    modules: new Map(), noise: new Map(),
  };
}

async function shaderModule(ctx, name) {
  if (!ctx.modules.has(name)) {
    const m = ctx.kit.modules.find((x) => x.name === name);
    if (!m) throw new Error(`the kit has no module ${name}`);
    const code = await (await fetchOk(`${ctx.base}/${m.wgsl}`)).text();
    const module = ctx.device.createShaderModule({ label: name, code });
    const info = await module.getCompilationInfo();
    const errs = info.messages.filter((x) => x.type === 'error');
    if (errs.length) {
      throw new Error(`${name}.wgsl: ${errs.map((x) => `${x.lineNum}:${x.linePos} ${x.message}`).join('; ')}`);
    }
    ctx.modules.set(name, module);
  }
  return ctx.modules.get(name);
}

async function noiseTexture(ctx, set, upload) {
  const key = `${set}/${upload}`;
  if (!ctx.noise.has(key)) {
    const entry = ctx.kit.noise.find((n) => n.key === set).textures[upload];
    const data = new Uint8Array(await (await fetchOk(`${ctx.base}/${entry.raw}`)).arrayBuffer());
    ctx.noise.set(key, { entry, data });
  }
  return ctx.noise.get(key);
}

const FLOAT32 = new Set(['rgba32float', 'r32float']);

/** The manifest's reflection of binding (group, binding) in `module`. */
function reflected(ctx, module, group, binding) {
  const m = ctx.manifest.modules.find((x) => x.name === module);
  const r = m.resources.find((x) => x.group === group && x.binding === binding);
  if (!r) throw new Error(`${module}: nothing at group ${group} binding ${binding}`);
  return r;
}

function layoutEntry(ctx, pass, b, plan, visibility) {
  const r = reflected(ctx, pass.module, b.group, b.binding);
  const res = plan.resources.find((x) => x.name === b.resource.replace('.previous', ''));
  const entry = { binding: b.binding, visibility };
  switch (r.kind) {
    case 'uniform-buffer': entry.buffer = { type: 'uniform' }; break;
    case 'storage-buffer': entry.buffer = { type: r.access === 'read' ? 'read-only-storage' : 'storage' }; break;
    case 'sampler': entry.sampler = { type: 'filtering' }; break;
    case 'sampled-texture':
      entry.texture = {
        sampleType: FLOAT32.has(res.format) ? 'unfilterable-float' : 'float',
        viewDimension: r.dimension,
      };
      break;
    case 'storage-texture':
      entry.storageTexture = {
        access: { read: 'read-only', write: 'write-only', 'read-write': 'read-write' }[r.access],
        format: r.format,
        viewDimension: r.dimension,
      };
      break;
    default: throw new Error(`${pass.name}: cannot bind ${r.name} (${r.kind})`);
  }
  return entry;
}

/**
 * Runs the first frame of `plan` with `uniforms` (`FrameUniforms`, as `uniforms.json` lays it out) and the noise set `noiseSet`, and
 * returns the display image (`image`, RGBA8) with the time the GPU work took on the CPU clock.
 * `sceneDepth` (optional) is the host's depth buffer at the plan's size, one little-endian f32
 * a pixel from the top-left (`Uint8Array`): the clouds stop at its geometry. The uniforms then
 * carry FLAG_SCENE_DEPTH and the projection's terms (`scene_depth_a`, `scene_depth_b`,
 * `scene_depth_clear`).
 */
export async function renderPlan(ctx, plan, uniforms, noiseSet, sceneDepth = null) {
  const { device } = ctx;
  const T = GPU_TEXTURE_USAGE();
  const B = GPU_BUFFER_USAGE();
  const S = GPU_SHADER_STAGE();
  const objects = new Map();
  for (const r of plan.resources) {
    if (r.kind === 'uniform') {
      const buf = device.createBuffer({ size: uniforms.byteLength, usage: B.UNIFORM | B.COPY_DST });
      device.queue.writeBuffer(buf, 0, uniforms);
      objects.set(r.name, { buffer: buf });
    } else if (r.kind === 'counters') {
      const buf = device.createBuffer({ size: Math.max(4, r.buffer_size), usage: B.STORAGE | B.COPY_DST });
      objects.set(r.name, { buffer: buf });
    } else if (r.kind === 'sampler') {
      objects.set(r.name, {
        sampler: device.createSampler({
          magFilter: r.sampler.filter, minFilter: r.sampler.filter, mipmapFilter: 'nearest',
          addressModeU: r.sampler.address, addressModeV: r.sampler.address, addressModeW: r.sampler.address,
          lodMinClamp: 0, lodMaxClamp: 32,
        }),
      });
    } else {
      let size = r.extent;
      let data = null;
      if (r.upload === 'scene.depth' && sceneDepth) {
        size = [plan.width, plan.height, 1];
        if (sceneDepth.byteLength !== size[0] * size[1] * 4) {
          throw new Error(`the scene depth has ${sceneDepth.byteLength} bytes, not 4 x ${size[0]}x${size[1]}`);
        }
        data = sceneDepth;
      } else if (r.upload === 'scene.depth') {
        // No host geometry: one texel, never read (FLAG_SCENE_DEPTH is off).
        size = [1, 1, 1];
        data = new Uint8Array(4);
      } else if (r.upload) {
        const n = await noiseTexture(ctx, noiseSet, r.upload);
        size = n.entry.size;
        data = n.data;
      }
      let usage = T.COPY_SRC | T.COPY_DST;
      if (r.usage.sampled) usage |= T.TEXTURE_BINDING;
      if (r.usage.storage) usage |= T.STORAGE_BINDING;
      if (r.usage.color) usage |= T.RENDER_ATTACHMENT;
      const make = () => device.createTexture({
        label: r.name, size: { width: size[0], height: size[1], depthOrArrayLayers: size[2] || 1 },
        dimension: r.dimension, format: r.format, usage,
      });
      const tex = make();
      if (data) {
        device.queue.writeTexture({ texture: tex }, data,
          { bytesPerRow: size[0] * 4, rowsPerImage: size[1] },
          { width: size[0], height: size[1], depthOrArrayLayers: size[2] || 1 });
      }
      // A history pair: this frame writes `name`, reads `name.previous` (the other half).
      objects.set(r.name, { texture: tex, size });
      if (r.lifetime === 'history') objects.set(`${r.name}.previous`, { texture: make(), size });
    }
  }

  const encoder = device.createCommandEncoder();
  const ran = [];
  for (const pass of plan.passes) {
    // The flags of a first frame: every computed persistent resource is `stale:` (no result
    // yet); no `history`, no `stats`, no `present` (no target of the host's).
    if (pass.when) {
      const negate = pass.when.startsWith('!');
      const flag = negate ? pass.when.slice(1) : pass.when;
      const set = flag.startsWith('stale:');
      if (set === negate) continue;
    }
    const module = await shaderModule(ctx, pass.module);
    const constants = {};
    for (const [k, v] of Object.entries(pass.overrides)) constants[k] = v;
    const compute = Boolean(pass.compute);
    const visibility = compute ? S.COMPUTE : S.VERTEX | S.FRAGMENT;
    const layout = device.createBindGroupLayout({
      label: pass.name,
      entries: pass.bindings.map((b) => layoutEntry(ctx, pass, b, plan, visibility)),
    });
    const bindGroup = device.createBindGroup({
      layout,
      entries: pass.bindings.map((b) => {
        const o = objects.get(b.resource);
        if (!o) throw new Error(`${pass.name}: no resource ${b.resource}`);
        if (o.buffer) return { binding: b.binding, resource: { buffer: o.buffer } };
        if (o.sampler) return { binding: b.binding, resource: o.sampler };
        return { binding: b.binding, resource: o.texture.createView() };
      }),
    });
    const pipelineLayout = device.createPipelineLayout({ bindGroupLayouts: [layout] });
    if (compute) {
      const pipeline = await device.createComputePipelineAsync({
        label: pass.name, layout: pipelineLayout,
        compute: { module, entryPoint: pass.compute, constants },
      });
      const cp = encoder.beginComputePass({ label: pass.name });
      cp.setPipeline(pipeline);
      cp.setBindGroup(0, bindGroup);
      cp.dispatchWorkgroups(...pass.dispatch);
      cp.end();
    } else {
      const blend = {
        replace: undefined,
        transmittance: { color: { srcFactor: 'one', dstFactor: 'src-alpha' }, alpha: { srcFactor: 'zero', dstFactor: 'one' } },
        additive: { color: { srcFactor: 'one', dstFactor: 'one' }, alpha: { srcFactor: 'one', dstFactor: 'one' } },
        over: { color: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha' }, alpha: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha' } },
      };
      const targets = pass.colors.map((c) => ({
        format: plan.resources.find((x) => x.name === c.target).format,
        blend: blend[c.blend],
      }));
      const pipeline = await device.createRenderPipelineAsync({
        label: pass.name, layout: pipelineLayout,
        vertex: { module, entryPoint: pass.vertex, constants },
        fragment: { module, entryPoint: pass.fragment, constants, targets },
        primitive: { topology: 'triangle-list' },
      });
      const rp = encoder.beginRenderPass({
        label: pass.name,
        colorAttachments: pass.colors.map((c) => ({
          view: objects.get(c.target).texture.createView(),
          loadOp: c.load === 'load' ? 'load' : 'clear', storeOp: 'store',
          clearValue: { r: 0, g: 0, b: 0, a: 0 },
        })),
      });
      rp.setViewport(0, 0, pass.extent[0], pass.extent[1], 0, 1);
      rp.setPipeline(pipeline);
      rp.setBindGroup(0, bindGroup);
      rp.draw(pass.vertices);
      rp.end();
    }
    ran.push(pass.name);
  }

  // Read back the display image.
  const image = objects.get('image');
  const [w, h] = [plan.width, plan.height];
  const bytesPerRow = Math.ceil((w * 4) / 256) * 256;
  const readback = device.createBuffer({ size: bytesPerRow * h, usage: B.COPY_DST | B.MAP_READ });
  encoder.copyTextureToBuffer({ texture: image.texture }, { buffer: readback, bytesPerRow }, { width: w, height: h });
  const t0 = performance.now();
  device.queue.submit([encoder.finish()]);
  await readback.mapAsync(GPUMapMode.READ);
  const ms = performance.now() - t0;
  const padded = new Uint8Array(readback.getMappedRange());
  const rgba = new Uint8Array(w * h * 4);
  for (let y = 0; y < h; y++) rgba.set(padded.subarray(y * bytesPerRow, y * bytesPerRow + w * 4), y * w * 4);
  readback.unmap();
  for (const o of objects.values()) (o.texture || o.buffer)?.destroy?.();
  if (ctx.errors.length) throw new Error(`WebGPU: ${ctx.errors.join('; ')}`);
  return { width: w, height: h, rgba, ms, passes: ran };
}

/** Renders golden `name` of the kit: its plan, uniform bytes and noise set. */
export async function renderGolden(ctx, name) {
  const g = ctx.kit.goldens.find((x) => x.name === name);
  if (!g) throw new Error(`the kit has no golden ${name}`);
  const plan = await (await fetchOk(`${ctx.base}/${g.plan}`)).json();
  const uniforms = new Uint8Array(await (await fetchOk(`${ctx.base}/${g.uniforms}`)).arrayBuffer());
  const depth = g.scene_depth
    ? new Uint8Array(await (await fetchOk(`${ctx.base}/${g.scene_depth}`)).arrayBuffer())
    : null;
  return renderPlan(ctx, plan, uniforms, g.noise, depth);
}
