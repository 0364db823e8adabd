// The interactive page: a golden scene of the kit, re-rendered as the controls change. The
// camera and the sun are members of the uniform block (uniforms.json); everything else comes
// from the golden's bytes unchanged.
import { loadKit, renderPlan } from './stratus-kit.js';

const KIT = new URLSearchParams(location.search).get('kit') || './kit';
const $ = (id) => document.getElementById(id);
const status = (s) => { $('status').textContent = s; };

// Members of the uniform block by name: byte offset (uniforms.json).
function member(layout, name) {
  const m = layout.members.find((x) => x.name === name);
  if (!m) throw new Error(`uniforms.json has no member ${name}`);
  return m.offset;
}

// The plan at another image size: output-sized resources and passes follow it (a golden's plan
// is resolved at the golden's size), as do the image size and aspect in the uniform block.
function resize(plan, width, height) {
  const out = JSON.parse(JSON.stringify(plan));
  const same = (e) => e && e[0] === plan.width && e[1] === plan.height;
  for (const r of out.resources) if (same(r.extent)) r.extent = [width, height, r.extent[2] || 1];
  for (const p of out.passes) {
    if (!same(p.extent)) continue;
    p.extent = [width, height];
    if (p.dispatch) p.dispatch = [Math.ceil(width / p.workgroup_size[0]), Math.ceil(height / p.workgroup_size[1]), 1];
  }
  out.width = width;
  out.height = height;
  return out;
}

// The camera basis and sun direction as Stratus derives them from yaw, pitch and elevation
// (x east, y up, z north; forward = (sin yaw cos pitch, sin pitch, cos yaw cos pitch)).
function edit(bytes, layout, { yaw, pitch, sun, sunAzimuth, width, height }) {
  const out = new Uint8Array(bytes);
  const f = new Float32Array(out.buffer);
  const u = new Uint32Array(out.buffer);
  const size = member(layout, 'size') / 4;
  u[size] = width;
  u[size + 1] = height;
  f[member(layout, 'aspect') / 4] = width / height;
  const set = (name, v) => { const o = member(layout, name) / 4; f[o] = v[0]; f[o + 1] = v[1]; f[o + 2] = v[2]; };
  const r = Math.PI / 180;
  const [sy, cy, sp, cp] = [Math.sin(yaw * r), Math.cos(yaw * r), Math.sin(pitch * r), Math.cos(pitch * r)];
  set('camera_forward', [sy * cp, sp, cy * cp]);
  set('camera_right', [cy, 0, -sy]);
  set('camera_up', [-sp * sy, cp, -sp * cy]);
  const [se, ce, sa, ca] = [Math.sin(sun * r), Math.cos(sun * r), Math.sin(sunAzimuth * r), Math.cos(sunAzimuth * r)];
  set('sun_direction', [sa * ce, se, ca * ce]);
  return out;
}

// A tower in front of the camera and into its clouds, as the host's depth buffer: a box 600 m
// square from the ground to 500 m above the cloud base, 5 km ahead along the camera's heading
// (the kit's `*-tower` golden draws the same one). Reversed Z, infinite far plane, 0.1 m near
// plane: depth = 0.1 / distance along the view axis, 0 where the ray misses. The display image
// shows the tower as a flat grey surface; a host composites the clouds over its own shading.
const TOWER_TERMS = [0, 0.1];
function tower(uniformBytes, layout, width, height) {
  const f = new Float32Array(uniformBytes.buffer);
  const v = (name) => { const o = member(layout, name) / 4; return [f[o], f[o + 1], f[o + 2]]; };
  const fwd = v('camera_forward');
  const right = v('camera_right');
  const up = v('camera_up');
  const alt = v('camera_position')[1];
  const tan = f[member(layout, 'tan_half_fov') / 4];
  const aspect = width / height;
  const hn = Math.hypot(fwd[0], fwd[2]) || 1e-9;
  const centre = [5000 * fwd[0] / hn, 5000 * fwd[2] / hn];
  const lo = [centre[0] - 300, -alt, centre[1] - 300];
  const hi = [centre[0] + 300, f[member(layout, 'cloud_bottom') / 4] + 500 - alt, centre[1] + 300];
  const depth = new Float32Array(width * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const sx = ((x + 0.5) / width * 2 - 1) * tan * aspect;
      const sy = (1 - (y + 0.5) / height * 2) * tan;
      const d = [0, 1, 2].map((k) => fwd[k] + sx * right[k] + sy * up[k]);
      let near = 0;
      let far = Infinity;
      for (let k = 0; k < 3; k++) {
        if (Math.abs(d[k]) < 1e-12) { if (lo[k] > 0 || hi[k] < 0) far = -1; continue; }
        const a = lo[k] / d[k];
        const b = hi[k] / d[k];
        near = Math.max(near, Math.min(a, b));
        far = Math.min(far, Math.max(a, b));
      }
      depth[y * width + x] = near <= far && near > 0 ? TOWER_TERMS[1] / near - TOWER_TERMS[0] : 0;
    }
  }
  const u32 = new Uint32Array(uniformBytes.buffer);
  u32[member(layout, 'flags') / 4] |= 128; // FLAG_SCENE_DEPTH
  f[member(layout, 'scene_depth_a') / 4] = TOWER_TERMS[0];
  f[member(layout, 'scene_depth_b') / 4] = TOWER_TERMS[1];
  f[member(layout, 'scene_depth_clear') / 4] = 0;
  return new Uint8Array(depth.buffer);
}

async function main() {
  const ctx = await loadKit(KIT);
  const layout = await (await fetch(`${KIT}/uniforms.json`)).json();
  const select = $('preset');
  for (const g of ctx.kit.goldens) select.add(new Option(g.name, g.name));
  let golden = null;
  let busy = false;
  let again = false;
  async function load() {
    const g = ctx.kit.goldens.find((x) => x.name === select.value);
    $('tower').checked = Boolean(g.scene_depth);
    const plan = await (await fetch(`${KIT}/${g.plan}`)).json();
    const bytes = new Uint8Array(await (await fetch(`${KIT}/${g.uniforms}`)).arrayBuffer());
    const f = new Float32Array(bytes.buffer);
    const fw = member(layout, 'camera_forward') / 4;
    const sd = member(layout, 'sun_direction') / 4;
    const deg = 180 / Math.PI;
    $('yaw').value = Math.round(Math.atan2(f[fw], f[fw + 2]) * deg);
    $('pitch').value = Math.round(Math.asin(f[fw + 1]) * deg);
    $('sun').value = Math.round(Math.asin(f[sd + 1]) * deg);
    golden = { g, plan, bytes, sunAzimuth: Math.atan2(f[sd], f[sd + 2]) * deg };
  }
  async function draw() {
    if (busy) { again = true; return; }
    busy = true;
    try {
      const [width, height] = $('size').value.split('x').map(Number);
      const u = edit(golden.bytes, layout, {
        yaw: +$('yaw').value, pitch: +$('pitch').value, sun: +$('sun').value, sunAzimuth: golden.sunAzimuth, width, height,
      });
      // A tower golden's bytes carry FLAG_SCENE_DEPTH: off with the tower.
      new Uint32Array(u.buffer)[member(layout, 'flags') / 4] &= ~128;
      const depth = $('tower').checked ? tower(u, layout, width, height) : null;
      const out = await renderPlan(ctx, resize(golden.plan, width, height), u, golden.g.noise, depth);
      const canvas = $('view');
      canvas.width = out.width; canvas.height = out.height;
      canvas.style.width = `${Math.max(out.width, 480)}px`;
      canvas.getContext('2d').putImageData(new ImageData(new Uint8ClampedArray(out.rgba.buffer), out.width, out.height), 0, 0);
      status(`${golden.g.name}: ${out.width}x${out.height}, frame ${out.ms.toFixed(1)} ms (submit to read-back), passes ${out.passes.join(', ')}\nadapter: ${ctx.adapter.vendor || '?'} ${ctx.adapter.architecture || ''}`);
    } catch (e) {
      status(`error: ${e.message}`);
    }
    busy = false;
    if (again) { again = false; draw(); }
  }
  select.onchange = async () => { await load(); draw(); };
  for (const id of ['yaw', 'pitch', 'sun']) $(id).oninput = draw;
  $('size').onchange = draw;
  $('tower').onchange = draw;
  await load();
  await draw();
  window.stratusViewerReady = true;
}

main().catch((e) => status(`error: ${e.message}`));
