// Times every tracker in headless Chromium (or Firefox, or WebKit: --browser) and natively on the same synthetic sequence, and
// prints median and 95th-percentile ms/frame with the wasm/native ratio per tracker.
//
// Browser: www/bench.html (a Web Worker renders FRAMES frames of SCENARIO with seed 1, then steps
// each tracker over them, the first 5 untimed, with the right frame for danescu-stereo and the
// car's motion from the ground truth for all). Native: `lanepf bench --warmup 5 --motion`, the
// same sequence, frames and timing (release build; `cargo run` builds it when needed). The native
// bench knows only highway-curve, so for another scenario only the browser figures are printed.
//
// Usage (after `make pkg`; `make bench-browser` does both):
//   node scripts/bench-browser.mjs [FRAMES=60] [WIDTH=640] [HEIGHT=480] [SCENARIO=highway-curve] [--no-native] [--json]
//        [--browser=chromium|firefox|webkit] [--trackers=ID,ID] [--preset=paper|real-roads]
// --preset=real-roads times our options beyond the papers (what the demo runs on real footage)
// in both, instead of each paper's filter.
// --browser=firefox and --browser=webkit run the page in Debian's Firefox ESR or in WebKitGTK
// (Safari's engine) through the cross-browser suite's drivers (tests/e2e/drivers/).
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { start, open } from '../tests/e2e/browser.mjs';

const WARMUP = 5;
const USAGE = 'usage: node scripts/bench-browser.mjs [FRAMES] [WIDTH] [HEIGHT] [SCENARIO] [--no-native] [--json] [--browser=chromium|firefox|webkit] [--trackers=ID,ID] [--preset=paper|real-roads]';
const flags = process.argv.slice(2).filter((a) => a.startsWith('--'));
const positional = process.argv.slice(2).filter((a) => !a.startsWith('--'));
let browserName = 'chromium';
let trackers = null;
let preset = 'paper';
for (const f of flags) {
  const m = /^--browser=(chromium|firefox|webkit)$/.exec(f);
  const t = /^--trackers=([a-z0-9,-]+)$/.exec(f);
  const p = /^--preset=(paper|real-roads)$/.exec(f);
  if (m) browserName = m[1];
  else if (t) trackers = t[1];
  else if (p) preset = p[1];
  else if (!['--no-native', '--json'].includes(f)) {
    console.error(`unknown option ${f}; ${USAGE}`);
    process.exit(2);
  }
}
const browserLabel = { chromium: 'Chromium', firefox: 'Firefox', webkit: 'WebKit' }[browserName];
const [frames = 60, width = 640, height = 480] = positional.slice(0, 3).map(Number);
const scenario = positional[3] ?? 'highway-curve';
for (const [name, v] of [['FRAMES', frames], ['WIDTH', width], ['HEIGHT', height]]) {
  if (!Number.isInteger(v) || v <= 0) {
    console.error(`${name} must be a positive whole number, got ${v}`);
    process.exit(2);
  }
}
if (frames <= WARMUP) {
  console.error(`FRAMES must exceed the ${WARMUP} untimed frames, got ${frames}`);
  process.exit(2);
}

/** The browser figures (window.lanepfBench of www/bench.html) in Firefox or WebKit. */
async function driverBench(query) {
  const driver = await import(`../tests/e2e/drivers/${browserName}.mjs`);
  const env = await driver.launch();
  try {
    const page = await env.open(`${env.base}/bench.html?${query}`);
    await page.waitFor(() => window.lanepfBench?.done, { timeout: 30 * 60_000 });
    const bench = await page.eval(() => window.lanepfBench);
    if (bench.error) throw new Error(`bench.html: ${bench.error}`);
    const errors = await page.errors();
    if (errors.length) throw new Error(errors.join('\n'));
    const foreign = page.requests().filter((u) => !u.startsWith(env.base) && !u.startsWith('data:'));
    if (foreign.length) throw new Error(`bench.html made requests beyond its own files: ${foreign.join(', ')}`);
    return { ...bench, engine: env.version };
  } finally {
    await env.close();
  }
}

/** The browser figures: window.lanepfBench of www/bench.html. */
async function browserBench() {
  const query = new URLSearchParams({ frames, width, height, scenario, seed: 1, warmup: WARMUP, preset });
  if (trackers) query.set('trackers', trackers);
  if (browserName !== 'chromium') return driverBench(query);
  const env = await start();
  try {
    const { page, errors } = await open(env.browser, 'about:blank');
    const foreign = [];
    page.on('request', (r) => {
      if (!r.url().startsWith(env.base) && !r.url().startsWith('data:')) foreign.push(r.url());
    });
    await page.goto(`${env.base}/bench.html?${query}`);
    await page.waitForFunction(() => window.lanepfBench?.done, null, { timeout: 30 * 60_000, polling: 500 });
    const bench = await page.evaluate(() => window.lanepfBench);
    if (bench.error) throw new Error(`bench.html: ${bench.error}`);
    if (errors.length) throw new Error(errors.join('\n'));
    if (foreign.length) throw new Error(`bench.html made requests beyond its own files: ${foreign.join(', ')}`);
    return { ...bench, engine: `Chromium ${env.browser.version()}` };
  } finally {
    await env.close();
  }
}

/** The native figures from `lanepf bench`, or null when not comparable / not wanted. */
function nativeBench() {
  if (flags.includes('--no-native')) return { rows: null, note: 'native bench skipped (--no-native)' };
  if (scenario !== 'highway-curve') {
    return { rows: null, note: `no native figures: \`lanepf bench\` runs highway-curve only, not ${scenario}` };
  }
  const repo = fileURLToPath(new URL('..', import.meta.url));
  const args = ['run', '--release', '--quiet', '--bin', 'lanepf', '--', 'bench', '--frames', String(frames),
    '--warmup', String(WARMUP), '--motion', '--width', String(width), '--height', String(height), '--preset', preset,
    '--json'];
  console.error(`[bench-browser] native: cargo ${args.join(' ')}`);
  const r = spawnSync('cargo', args, { cwd: repo, encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'],
    maxBuffer: 64 << 20 });
  if (r.status !== 0) throw new Error(`the native bench failed (exit ${r.status ?? r.signal})`);
  return { rows: JSON.parse(r.stdout),
    note: `native: lanepf bench --warmup ${WARMUP} --motion --preset ${preset} (release build)` };
}

console.error(`[bench-browser] ${browserLabel}: ${scenario} ${width}x${height}, ${frames} frames, first ${WARMUP} not timed, preset ${preset}`);
const browser = await browserBench();
const native = nativeBench();
const byId = new Map((native.rows ?? []).map((r) => [r.tracker, r]));
const rows = browser.rows.map((b) => {
  const n = byId.get(b.tracker);
  return {
    tracker: b.tracker,
    wasm_median_ms: b.median_ms,
    wasm_p95_ms: b.p95_ms,
    native_median_ms: n?.median_ms ?? null,
    native_p95_ms: n?.p95_ms ?? null,
    ratio_median: n ? b.median_ms / n.median_ms : null,
  };
});

if (flags.includes('--json')) {
  console.log(JSON.stringify({ browser: browser.engine, scenario, preset, width, height, frames, warmup: WARMUP, render_ms: browser.render_ms,
    note: native.note, rows }, null, 2));
} else {
  const f = (v, w) => (v === null ? '-' : v.toFixed(2)).padStart(w);
  console.log(`${scenario} ${width}x${height}, seed 1, ${frames} frames (first ${WARMUP} not timed), preset ${preset}; `
    + `${browser.engine}${browser.version ? `, lanepf ${browser.version}` : ''}, in a Web Worker`);
  console.log(native.note);
  console.log('tracker            wasm median  wasm p95  native median  native p95  wasm/native');
  for (const r of rows) {
    console.log(`${r.tracker.padEnd(18)} ${f(r.wasm_median_ms, 11)} ${f(r.wasm_p95_ms, 9)} `
      + `${f(r.native_median_ms, 14)} ${f(r.native_p95_ms, 11)} ${f(r.ratio_median, 12)}`);
  }
  console.log(`(scene rendering in the worker: ${browser.render_ms.toFixed(2)} ms/frame, not included)`);
}
