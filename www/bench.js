// The benchmark page: reads its settings from the query string, runs bench-worker.js and shows
// the ms/frame of every tracker as a table and as JSON. The result is also
// `window.lanepfBench = { done, params, rows, render_ms, version }` (or `{ done, error }`) for
// scripts/bench-browser.mjs and the end-to-end test.
const DEFAULTS = { frames: 60, width: 640, height: 480, scenario: 'highway-curve', seed: 1, warmup: 5 };

/** The settings from the query string; throws an Error naming a bad value. */
export function readParams(search) {
  const q = new URLSearchParams(search);
  const params = { ...DEFAULTS, trackers: null };
  for (const key of ['frames', 'width', 'height', 'seed', 'warmup']) {
    if (!q.has(key)) continue;
    const n = Number(q.get(key));
    if (!Number.isInteger(n) || n < 0) throw new Error(`${key}=${q.get(key)}: a whole number is needed`);
    params[key] = n;
  }
  if (q.has('scenario')) params.scenario = q.get('scenario');
  if (q.has('trackers')) params.trackers = q.get('trackers').split(',').filter(Boolean);
  if (params.frames <= params.warmup) {
    throw new Error(`frames=${params.frames} must exceed warmup=${params.warmup} (untimed frames)`);
  }
  return params;
}

const status = document.getElementById('status');
const fail = (message) => {
  window.lanepfBench = { done: true, error: message };
  document.body.dataset.state = 'error';
  status.textContent = `error: ${message}`;
  document.getElementById('result').textContent = JSON.stringify(window.lanepfBench, null, 2);
};

function show(result) {
  const body = document.querySelector('#table tbody');
  for (const r of result.rows) {
    const tr = document.createElement('tr');
    for (const v of [r.tracker, r.median_ms.toFixed(2), r.p95_ms.toFixed(2), r.mean_ms.toFixed(2), r.frames]) {
      const td = document.createElement('td');
      td.textContent = v;
      tr.append(td);
    }
    body.append(tr);
  }
  document.getElementById('table').hidden = false;
  document.getElementById('result').textContent = JSON.stringify(result, null, 2);
  status.textContent = `done (rendering: ${result.render_ms.toFixed(2)} ms/frame, not timed in the rows)`;
  window.lanepfBench = { done: true, ...result };
  document.body.dataset.state = 'done';
}

let params;
try {
  params = readParams(location.search);
} catch (e) {
  fail(e.message);
}
if (params) {
  window.lanepfBench = { done: false, params };
  document.getElementById('setup').textContent = `${params.scenario}, ${params.width}x${params.height}, `
    + `seed ${params.seed}: ${params.frames} frames rendered first, then every tracker stepped over `
    + `them (the first ${params.warmup} not timed), in a Web Worker.`;
  const worker = new Worker(new URL('./bench-worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = ({ data }) => {
    if (data.type === 'progress') status.textContent = data.text;
    else if (data.type === 'version') document.getElementById('version').textContent = `lanepf ${data.version}`;
    else if (data.type === 'done') show({ params, ...data.result });
    else if (data.type === 'error') fail(data.error);
  };
  worker.onerror = (e) => fail(`worker failed: ${e.message ?? 'unknown error'}`);
  worker.postMessage(params);
}
