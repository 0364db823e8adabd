// Renders every golden of a kit in headless Chromium (WebGPU: Tint compiling the WGSL,
// SwiftShader executing it) through web/stratus-kit.js, and writes each display image as
// <out>/<golden>.png plus <out>/results.json. `cargo xtask web-test` runs it and compares the
// images with the kit's goldens.
//
//   node web/test/run.mjs --kit DIR --out DIR [--screenshot FILE.png]
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { chromium } from 'playwright-core';
import { parseArgs, serve } from './server.mjs';

const args = parseArgs(process.argv.slice(2));
if (!args.kit || !args.out) {
  console.error('usage: node web/test/run.mjs --kit DIR --out DIR [--screenshot FILE.png]');
  process.exit(2);
}
const kit = path.resolve(args.kit);
fs.mkdirSync(args.out, { recursive: true });

const { server, base } = await serve(kit);

// A PNG (RGBA8, no filtering) from raw pixels.
function png(width, height, rgba) {
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc = (buf) => { let c = 0xffffffff; for (const b of buf) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8); return (c ^ 0xffffffff) >>> 0; };
  const chunk = (type, data) => {
    const head = Buffer.alloc(8); head.writeUInt32BE(data.length, 0); head.write(type, 4, 'ascii');
    const tail = Buffer.alloc(4); tail.writeUInt32BE(crc(Buffer.concat([head.subarray(4), data])), 0);
    return Buffer.concat([head, data, tail]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0); ihdr.writeUInt32BE(height, 4); ihdr[8] = 8; ihdr[9] = 6;
  const raw = Buffer.alloc((width * 4 + 1) * height);
  for (let y = 0; y < height; y++) rgba.copy(raw, y * (width * 4 + 1) + 1, y * width * 4, (y + 1) * width * 4);
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

const profile = fs.mkdtempSync(path.join(args.out, 'profile-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader',
    '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update',
    '--disable-sync'],
});
let failed = false;
try {
  const page = browser.pages()[0] || await browser.newPage();
  const logs = [];
  page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
  await page.goto(`${base}/test/harness.html`);
  await page.waitForFunction(() => window.harnessReady === true);
  const opened = await page.evaluate((b) => window.harness.open(b), `${base}/kit`);
  const results = { adapter: opened.adapter, goldens: [] };
  for (const name of opened.goldens) {
    const t0 = Date.now();
    const out = await page.evaluate((n) => window.harness.render(n), name);
    const file = path.join(args.out, `${name}.png`);
    fs.writeFileSync(file, png(out.width, out.height, Buffer.from(out.rgba, 'base64')));
    results.goldens.push({ name, image: file, frame_ms: out.ms, wall_ms: Date.now() - t0, passes: out.passes });
    console.log(`${name}: ${out.width}x${out.height}, ${out.ms.toFixed(0)} ms, passes ${out.passes.join(', ')}`);
  }
  fs.writeFileSync(path.join(args.out, 'results.json'), `${JSON.stringify(results, null, 2)}\n`);
  console.log(`adapter: ${JSON.stringify(opened.adapter)}`);
  if (args.screenshot) {
    await page.setViewportSize({ width: 900, height: 700 });
    await page.goto(`${base}/index.html?kit=/kit`);
    await page.waitForFunction(() => window.stratusViewerReady === true, null, { timeout: 120000 });
    await page.screenshot({ path: args.screenshot });
    console.log(`screenshot: ${args.screenshot}`);
  }
  const errors = logs.filter((l) => l.startsWith('error') || l.startsWith('pageerror'));
  if (errors.length) { console.error(errors.join('\n')); failed = true; }
} catch (e) {
  console.error(`web test: ${e.message}`);
  failed = true;
} finally {
  await browser.close();
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
