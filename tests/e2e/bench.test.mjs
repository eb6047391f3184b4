// End-to-end: www/bench.html runs every tracker in a Web Worker on a tiny sequence and reports a
// finite, positive median and p95 ms/frame for each id, from nothing but the server's files.
import test from 'node:test';
import assert from 'node:assert/strict';
import { start, open } from './browser.mjs';

const env = await start();
test.after(() => env.close());

test('bench.html times every tracker in a worker', { timeout: 120_000 }, async () => {
  const { page, errors } = await open(env.browser, 'about:blank');
  const requests = [];
  page.on('request', (r) => requests.push(r.url()));
  await page.goto(`${env.base}/bench.html?frames=8&width=320&height=240`);
  await page.waitForFunction(() => window.lanepfBench?.done, null, { timeout: 110_000 });
  const bench = await page.evaluate(() => window.lanepfBench);
  assert.equal(bench.error, undefined, bench.error);
  const ids = ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf', 'liu-ppf', 'liu-ppf-nokernel'];
  assert.deepEqual(bench.rows.map((r) => r.tracker), ids);
  for (const r of bench.rows) {
    assert.ok(Number.isFinite(r.median_ms) && r.median_ms > 0, `${r.tracker}: median ${r.median_ms}`);
    assert.ok(Number.isFinite(r.p95_ms) && r.p95_ms >= r.median_ms, `${r.tracker}: p95 ${r.p95_ms}`);
    assert.equal(r.frames, 3, `${r.tracker}: 8 frames, the first 5 untimed`);
    assert.deepEqual([r.width, r.height], [320, 240]);
  }
  // The table and the JSON on the page say the same.
  assert.equal(await page.locator('#table tbody tr').count(), ids.length);
  assert.deepEqual(JSON.parse(await page.textContent('#result')).rows, bench.rows);
  assert.deepEqual(errors, []);
  const foreign = requests.filter((u) => !u.startsWith(env.base) && !u.startsWith('data:'));
  assert.deepEqual(foreign, [], 'no requests beyond the page\'s own files');
});

test('bench.html reports bad parameters as an error', async () => {
  const { page } = await open(env.browser, `${env.base}/bench.html?frames=3&warmup=5`);
  await page.waitForFunction(() => window.lanepfBench?.done);
  const bench = await page.evaluate(() => window.lanepfBench);
  assert.match(bench.error, /frames=3 must exceed warmup=5/);
  assert.equal(await page.getAttribute('body', 'data-state'), 'error');
});
