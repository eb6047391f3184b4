// @ts-check
// The benchmark page: reads its settings from the query string, runs bench-worker.js and shows
// the ms/frame of every tracker as a table and as JSON. The result is also
// `window.lanepfBench = { done, params, rows, render_ms, version }` (or `{ done, error }`) for
// scripts/bench-browser.mjs and the end-to-end test.
import { byId } from './dom.js';

const DEFAULTS = { frames: 60, width: 640, height: 480, scenario: 'highway-curve', seed: 1, warmup: 5 };
/** The named option sets of `trackerPreset`: each paper's filter, or ours for real footage. */
const PRESETS = ['paper', 'real-roads'];

/**
 * The settings from the query string; throws an Error naming a bad value.
 * @param {string} search
 */
export function readParams(search) {
  const q = new URLSearchParams(search);
  /** @type {typeof DEFAULTS & { trackers: string[] | null, preset: string }} */
  const params = { ...DEFAULTS, trackers: null, preset: 'paper' };
  for (const key of /** @type {const} */ (['frames', 'width', 'height', 'seed', 'warmup'])) {
    if (!q.has(key)) continue;
    const n = Number(q.get(key));
    if (!Number.isInteger(n) || n < 0) throw new Error(`${key}=${q.get(key)}: a whole number is needed`);
    params[key] = n;
  }
  const scenario = q.get('scenario');
  if (scenario !== null) params.scenario = scenario;
  const trackers = q.get('trackers');
  if (trackers !== null) params.trackers = trackers.split(',').filter(Boolean);
  const preset = q.get('preset');
  if (preset !== null) {
    if (!PRESETS.includes(preset)) throw new Error(`preset=${preset}: use one of ${PRESETS.join(', ')}`);
    params.preset = preset;
  }
  if (params.frames <= params.warmup) {
    throw new Error(`frames=${params.frames} must exceed warmup=${params.warmup} (untimed frames)`);
  }
  return params;
}

const status = byId('status', HTMLElement);
const result = byId('result', HTMLElement);
/** @param {string} message */
const fail = (message) => {
  window.lanepfBench = { done: true, error: message };
  document.body.dataset.state = 'error';
  status.textContent = `error: ${message}`;
  result.textContent = JSON.stringify(window.lanepfBench, null, 2);
};

/**
 * @param {{ params: object, version: string, render_ms: number, rows: { tracker: string, preset: string,
 *   options: Record<string, unknown>, width: number,
 *   height: number, frames: number, median_ms: number, p95_ms: number, mean_ms: number }[] }} bench
 */
function show(bench) {
  const table = byId('table', HTMLTableElement);
  const body = table.tBodies[0];
  for (const r of bench.rows) {
    const tr = document.createElement('tr');
    for (const v of [r.tracker, r.median_ms.toFixed(2), r.p95_ms.toFixed(2), r.mean_ms.toFixed(2), r.frames]) {
      const td = document.createElement('td');
      td.textContent = `${v}`;
      tr.append(td);
    }
    body.append(tr);
  }
  table.hidden = false;
  result.textContent = JSON.stringify(bench, null, 2);
  status.textContent = `done (rendering: ${bench.render_ms.toFixed(2)} ms/frame, not timed in the rows)`;
  window.lanepfBench = { done: true, ...bench };
  document.body.dataset.state = 'done';
}

let params;
try {
  params = readParams(location.search);
} catch (e) {
  fail(e instanceof Error ? e.message : String(e));
}
if (params) {
  window.lanepfBench = { done: false, params };
  byId('setup', HTMLElement).textContent = `${params.scenario}, ${params.width}x${params.height}, `
    + `seed ${params.seed}: ${params.frames} frames rendered first, then every tracker stepped over `
    + `them (the first ${params.warmup} not timed), in a Web Worker, with the ${params.preset} preset.`;
  const worker = new Worker(new URL('./bench-worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = ({ data }) => {
    if (data.type === 'progress') status.textContent = data.text;
    else if (data.type === 'version') byId('version', HTMLElement).textContent = `lanepf ${data.version}`;
    else if (data.type === 'done') show({ params, ...data.result });
    else if (data.type === 'error') fail(data.error);
  };
  worker.onerror = (e) => fail(`worker failed: ${e.message ?? 'unknown error'}`);
  worker.postMessage(params);
}
