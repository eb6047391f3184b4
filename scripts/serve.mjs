// Static server for the lanepf demo: http://127.0.0.1:PORT/ serves www/, /pkg/ serves pkg/.
// It honours HTTP Range requests (video seeking needs them; other units and multiple ranges
// get the whole file, as RFC 9110 allows), sends an ETag (size and modification time) and
// answers a matching If-None-Match with 304 (a warm reload), serves .wasm as application/wasm, binds to
// 127.0.0.1 only, answers only requests whose Host is localhost, 127.0.0.1 or [::1] with its
// port (a DNS-rebinding page names another host), refuses paths and symbolic links that lead
// outside those two folders, and sends a Content-Security-Policy, nosniff and X-Frame-Options.
// With a root folder it serves that folder alone at / instead (the npm package tests serve
// their fixture apps so).
//   node scripts/serve.mjs [--port 8080] [--root DIR]
import { createServer } from 'node:http';
import { createReadStream, promises as fs } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = resolve(fileURLToPath(new URL('..', import.meta.url)));
const demoMounts = [['/pkg/', join(repo, 'pkg')], ['/', join(repo, 'www')]];
const types = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8', '.css': 'text/css; charset=utf-8',
  '.json': 'application/json', '.wasm': 'application/wasm', '.ts': 'text/plain; charset=utf-8',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.svg': 'image/svg+xml',
  '.mp4': 'video/mp4', '.webm': 'video/webm', '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/plain; charset=utf-8',
};

// The demo's policy (index.html and bench.html carry it as a meta tag too): its own scripts
// and WebAssembly, workers, media from files and the camera, no framing.
const DEMO_CSP = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self'; "
  + "connect-src 'self'; img-src 'self' data: blob:; media-src 'self' blob: mediastream:; "
  + "style-src 'self'; object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'";
// A folder served with --root holds any app (the npm tests' import-map pages have inline
// scripts): no framing, no plugins, no <base>.
const ROOT_CSP = "object-src 'none'; base-uri 'none'; frame-ancestors 'none'";

/** Headers of every response. */
const securityHeaders = (csp) => ({
  'Content-Security-Policy': csp, 'X-Content-Type-Options': 'nosniff', 'X-Frame-Options': 'DENY',
});

/** Whether a Host header names this server: localhost, 127.0.0.1 or [::1] with its port. */
export function allowedHost(host, port) {
  if (typeof host !== 'string') return false;
  const h = host.toLowerCase();
  const names = ['localhost', '127.0.0.1', '[::1]'];
  return names.some((n) => h === `${n}:${port}` || (port === 80 && h === n));
}

/** The mounts ([URL prefix, folder] pairs) of the demo, or of `root` alone at `/`. */
function mountsFor(root) {
  return root === undefined ? demoMounts : [['/', resolve(root)]];
}

/** The mount folder holding `file` by name (`..` resolved), or null. */
function mountOf(file, mounts) {
  return mounts.map(([, dir]) => dir).find((dir) => file === dir || file.startsWith(dir + sep)) ?? null;
}

/** Maps a URL path to a file inside one of the mounts (the demo's by default), or null when it
 * escapes them. */
export function resolvePath(urlPath, mounts = demoMounts) {
  let path;
  try { path = decodeURIComponent(urlPath.split('?')[0]); } catch { return null; }
  for (const [prefix, dir] of mounts) {
    if (!path.startsWith(prefix)) continue;
    const file = normalize(join(dir, path.slice(prefix.length)));
    return mountOf(file, [[prefix, dir]]) ? file : null;
  }
  return null;
}

/** The real path of `file` (symbolic links followed) when it is inside the real path of its
 * mount folder; null when a link leads outside. Throws (ENOENT) for a missing file. */
export async function realInside(file, mounts = demoMounts) {
  const dir = mountOf(file, mounts);
  if (!dir) return null;
  const [real, realDir] = await Promise.all([fs.realpath(file), fs.realpath(dir)]);
  return real === realDir || real.startsWith(realDir + sep) ? real : null;
}

/**
 * Parses a single `bytes=a-b` range against a file size: { start, end }, or 'bad' when it
 * cannot be satisfied, or null when there is none to honour: no header, another unit than
 * bytes, several ranges or a malformed one (RFC 9110 14.2: a server may ignore Range and
 * send the whole file with 200).
 */
export function parseRange(header, size) {
  if (!header) return null;
  const m = /^bytes=(\d*)-(\d*)$/.exec(header.trim());
  if (!m || (m[1] === '' && m[2] === '')) return null;
  let start, end;
  if (m[1] === '') { start = Math.max(0, size - Number(m[2])); end = size - 1; }
  else { start = Number(m[1]); end = m[2] === '' ? size - 1 : Math.min(Number(m[2]), size - 1); }
  return start <= end && start < size ? { start, end } : 'bad';
}

async function handle(req, res, mounts, port, csp) {
  const secure = securityHeaders(csp);
  const fail = (status, text, extra = {}) => res.writeHead(status, { ...secure, ...extra }).end(text);
  if (!allowedHost(req.headers.host, port)) {
    fail(421, `this server answers only for localhost, 127.0.0.1 or [::1] on port ${port}\n`);
    return;
  }
  if (req.method !== 'GET' && req.method !== 'HEAD') {
    fail(405, 'method not allowed\n', { Allow: 'GET, HEAD' });
    return;
  }
  let file = resolvePath(req.url, mounts);
  if (!file) { fail(403, 'forbidden\n'); return; }
  let stat;
  try {
    stat = await fs.stat(file);
    if (stat.isDirectory()) { file = join(file, 'index.html'); stat = await fs.stat(file); }
    file = await realInside(file, mounts);
  } catch { fail(404, 'not found\n'); return; }
  if (!file) { fail(403, 'forbidden: a link out of the served folder\n'); return; }
  // A validator, so that a reload revalidates (304) instead of fetching every file again: the
  // browser then keeps its cached copies, and Chromium its compiled WebAssembly with them.
  const etag = `"${stat.size.toString(16)}-${Math.floor(stat.mtimeMs).toString(16)}"`;
  const headers = {
    ...secure,
    'Content-Type': types[extname(file).toLowerCase()] ?? 'application/octet-stream',
    'Accept-Ranges': 'bytes', 'Cache-Control': 'no-cache', ETag: etag,
    // Cross-origin isolation (the page loads nothing from elsewhere, so it costs nothing):
    // without it Firefox rounds performance.now() to whole milliseconds, and the demo's
    // ms/frame readings (a tracker step takes 2-40 ms) would be mostly rounding.
    'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp',
  };
  const match = req.headers['if-none-match'];
  if (match && match.split(',').some((t) => t.trim().replace(/^W\//, '') === etag)) {
    res.writeHead(304, headers).end();
    return;
  }
  const range = parseRange(req.headers.range, stat.size);
  if (range === 'bad') {
    fail(416, '', { 'Content-Range': `bytes */${stat.size}` });
    return;
  }
  const { start, end } = range ?? { start: 0, end: stat.size - 1 };
  headers['Content-Length'] = stat.size === 0 ? 0 : end - start + 1;
  if (range) headers['Content-Range'] = `bytes ${start}-${end}/${stat.size}`;
  res.writeHead(range ? 206 : 200, headers);
  if (req.method === 'HEAD' || stat.size === 0) { res.end(); return; }
  createReadStream(file, { start, end }).on('error', () => res.destroy()).pipe(res);
}

/** Starts the server on 127.0.0.1 (port 0: any free port); serves the demo (www/ and pkg/), or
 * the folder `root` alone when given. Resolves to the http.Server once listening. */
export function serve(port, root) {
  const mounts = mountsFor(root);
  const csp = root === undefined ? DEMO_CSP : ROOT_CSP;
  return new Promise((ok, fail) => {
    const server = createServer((req, res) => {
      handle(req, res, mounts, server.address().port, csp)
        .catch(() => { if (!res.headersSent) res.writeHead(500); res.end(); });
    });
    server.once('error', fail);
    server.listen(port, '127.0.0.1', () => ok(server));
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const arg = (name) => {
    const i = process.argv.indexOf(name);
    return i > 0 ? process.argv[i + 1] : undefined;
  };
  const port = Number(arg('--port') ?? process.env.PORT ?? 8080);
  const root = arg('--root');
  serve(port, root).then(
    (s) => console.log(`lanepf ${root === undefined ? 'demo' : root}: http://127.0.0.1:${s.address().port}/  (Ctrl-C stops)`),
    (e) => { console.error(`cannot listen on 127.0.0.1:${port}: ${e.message}`); process.exit(1); },
  );
}
