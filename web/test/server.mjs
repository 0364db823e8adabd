// A static HTTP server for the page and a kit: `/kit/...` from the kit folder, everything else
// from web/. Used by the test runner, and by `cargo xtask web` to serve the interactive page.
//
//   node web/test/server.mjs --kit DIR [--port 8080]
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.json': 'application/json', '.wgsl': 'text/plain', '.png': 'image/png',
};

/** `--name value` pairs of a command line as an object. */
export function parseArgs(argv) {
  return Object.fromEntries(argv.reduce((acc, a, i, all) => {
    if (a.startsWith('--')) acc.push([a.slice(2), all[i + 1]]);
    return acc;
  }, []));
}

/** Serves web/ and `kit` on 127.0.0.1:`port` (0: any free port); resolves to the base URL. */
export async function serve(kit, port = 0) {
  const web = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
  const root = path.resolve(kit);
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const file = path.normalize(url.startsWith('/kit/') ? path.join(root, url.slice(5))
      : path.join(web, url === '/' ? 'index.html' : url));
    if (!file.startsWith(root) && !file.startsWith(web)) { res.writeHead(403).end(); return; }
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404).end(`${url}: not found`); return; }
      res.writeHead(200, { 'content-type': TYPES[path.extname(file)] || 'application/octet-stream' }).end(data);
    });
  });
  await new Promise((ok) => server.listen(port, '127.0.0.1', ok));
  return { server, base: `http://127.0.0.1:${server.address().port}` };
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const args = parseArgs(process.argv.slice(2));
  if (!args.kit) { console.error('usage: node web/test/server.mjs --kit DIR [--port 8080]'); process.exit(2); }
  const { base } = await serve(args.kit, Number(args.port || 8080));
  console.log(`serving the Stratus page at ${base}/ (kit: ${path.resolve(args.kit)}); Ctrl-C stops`);
}
