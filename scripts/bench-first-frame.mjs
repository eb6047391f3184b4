// How long the demo takes from navigation to its first tracked frame on the canvas, and where
// that time goes: the page's start-up marks (`lanepf:*` in www/main.js, ms since navigation)
// for the default page (the bundled clip, lee-cpf) or the query given, in headless Chromium.
// The first load is cold (nothing cached); each further run reloads the same page in the same
// browser context (a warm cache). Prints each run and the median of the warm runs.
//
// Usage (after `make pkg`): node scripts/bench-first-frame.mjs [RUNS=6] [QUERY, e.g. tracker=liu-ppf] [--json]
import { start } from '../tests/e2e/browser.mjs';

const args = process.argv.slice(2);
const json = args.includes('--json');
const positional = args.filter((a) => !a.startsWith('--'));
const runs = Number(positional[0] ?? 6);
const query = positional[1] ?? '';
if (!Number.isInteger(runs) || runs < 2) {
  console.error('usage: node scripts/bench-first-frame.mjs [RUNS >= 2] [QUERY] [--json]');
  process.exit(2);
}
// In the order the page reaches them: boot.js has the worker's wasm ready (wasm); main.js has
// its answer (hello), the camera presets, the clip open and its first frame decoded (video),
// the auto-calibrator (calibrator), the tracker and the top view's table (tracker), then the
// first tracked frame drawn.
const MARKS = ['wasm', 'hello', 'presets', 'video', 'calibrator', 'tracker', 'first-frame'];

const env = await start();
const rows = [];
try {
  const context = await env.browser.newContext();
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  for (let run = 0; run < runs; run += 1) {
    const url = `${env.base}/index.html${query ? `?${query}` : ''}`;
    if (run === 0) await page.goto(url);
    else await page.reload();
    await page.waitForFunction(() => performance.getEntriesByName('lanepf:first-frame').length > 0
      || document.body.dataset.state === 'error', null, { timeout: 60_000 });
    const row = await page.evaluate((names) => {
      const at = Object.fromEntries(names.map((n) => {
        const [m] = performance.getEntriesByName(`lanepf:${n}`);
        return [n, m ? m.startTime : NaN];
      }));
      const [first] = /** @type {PerformanceMark[]} */ (performance.getEntriesByName('lanepf:first-frame'));
      const [nav] = /** @type {PerformanceNavigationTiming[]} */ (performance.getEntriesByType('navigation'));
      return {
        ...at, domContentLoaded: nav?.domContentLoadedEventEnd ?? NaN,
        firstSource: first?.detail?.source ?? NaN, firstWorker: first?.detail?.worker ?? NaN,
        firstTrack: first?.detail?.track ?? NaN,
        state: document.body.dataset.state,
      };
    }, MARKS);
    if (row.state === 'error') throw new Error(`the page failed to start: ${errors.join('; ')}`);
    rows.push({ run, cache: run === 0 ? 'cold' : 'warm', ...row });
  }
} finally {
  await env.close();
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const cols = ['domContentLoaded', ...MARKS, 'firstSource', 'firstWorker', 'firstTrack'];
const warm = rows.filter((r) => r.cache === 'warm');
const summary = Object.fromEntries(cols.map((c) => [c, median(warm.map((r) => r[c]))]));
if (json) {
  console.log(JSON.stringify({ query, runs: rows, warmMedian: summary }, null, 2));
} else {
  console.log(`ms since navigation (${query || 'default page: the clip, lee-cpf'}); first frame's own `
    + 'time: reading it (firstSource) and the worker\'s answer (firstWorker)');
  console.log(['run', 'cache', ...cols].map((c) => c.padStart(12)).join(''));
  for (const r of rows) {
    console.log([r.run, r.cache, ...cols.map((c) => r[c].toFixed(0))].map((v) => String(v).padStart(12)).join(''));
  }
  console.log(['median', 'warm', ...cols.map((c) => summary[c].toFixed(0))].map((v) => String(v).padStart(12)).join(''));
}
