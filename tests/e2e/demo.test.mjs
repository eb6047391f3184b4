// End-to-end in Chromium only: a simulator scenario chosen from the page drawn under its ground
// truth, adachi-mmpf's lanes on the truth, liu-ppf's cue view, danescu-mono's marking bands,
// and an export's real download.
// Checked on the canvas pixels, not on the DOM. (The checks every browser runs, Chromium
// included, are in cross-browser.test.mjs.)
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync } from 'node:fs';
import { start, open, running } from './browser.mjs';
import { readCanvas, peak, xAt } from './pixels.mjs';

const env = await start();
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

test('demo switches to a simulator scenario and draws it under its ground truth', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?tracker=`);
  await running(page);
  const names = await page.$$eval('#source option', (os) => os.map((o) => o.value));
  assert.ok(names.includes('highway-curve') && names.includes('urban') && names.length >= 13, names.join());

  await page.click('#play');
  // (The clip has no ground truth, so no control for it until the scene is open.)
  await page.selectOption('#source', 'highway-curve');
  await page.waitForFunction(() => /highway-curve/.test(document.getElementById('status').textContent));
  await page.uncheck('#show-truth');
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, before);
  const truth = await page.evaluate(() => window.lanepfDemo.lastTruth);
  const img = await readCanvas(page);
  // Three lanes with the car in the middle: four boundaries, and the outer (solid) left edge
  // of the road is bright along its near part.
  assert.deepEqual(truth.boundaries.map((b) => b.role).sort(),
    ['ego-left', 'ego-right', 'left-adjacent', 'right-adjacent']);
  const edge = truth.boundaries.find((b) => b.role === 'left-adjacent').points.filter(([, y]) => y > 260);
  assert.ok(edge.length >= 5, 'the road edge is visible near the car');
  const bright = edge.filter(([x, y]) => peak(img, x, y, 2) > 150).length / edge.length;
  assert.ok(bright > 0.9, `solid road edge found on ${bright} of its polyline`);
  // Sky at the top is blue, not grey or black.
  const top = 4 * (10 * img.width + 320);
  assert.ok(img.data[top + 2] > img.data[top] + 30, 'blue sky');
  assert.deepEqual(errors, []);
  await page.close();
});

test('demo runs the adachi-mmpf tracker in the worker and draws its lanes on the truth', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/`);
  await running(page);
  await page.click('#play');
  await page.selectOption('#source', 'highway-straight');
  await page.waitForFunction(() => /highway-straight/.test(document.getElementById('status').textContent));
  await page.selectOption('#tracker', 'adachi-mmpf');
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.lastEstimate && window.lanepfDemo.frames > 10,
    null, { timeout: 30000 });
  await page.click('#play');
  const { truth, estimate } = await page.evaluate(() => ({
    truth: window.lanepfDemo.lastTruth, estimate: window.lanepfDemo.lastEstimate,
  }));
  assert.equal(estimate.valid, true);
  // The estimated ego-left boundary lies on the true one: mean |dx| over shared rows < 20 px.
  const est = estimate.boundaries.find((b) => b.role === 'ego-left').points;
  const tru = truth.boundaries.find((b) => b.role === 'ego-left').points;
  const diffs = est.map(([, y]) => [xAt(est, y), xAt(tru, y)]).filter(([a, b]) => a !== null && b !== null)
    .map(([a, b]) => Math.abs(a - b));
  assert.ok(diffs.length > 10, `${diffs.length} shared rows`);
  const mean = diffs.reduce((a, b) => a + b, 0) / diffs.length;
  assert.ok(mean < 20, `ego-left estimate ${mean.toFixed(1)} px from the truth`);
  assert.match(await page.textContent('#timing'), /track \d+\.\d ms · offset error \d+ cm/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('demo runs liu-ppf and shows its measurement pixels as the tracker cue view', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/`);
  await running(page);
  await page.click('#play');
  await page.selectOption('#source', 'highway-straight');
  await page.waitForFunction(() => /highway-straight/.test(document.getElementById('status').textContent));
  await page.selectOption('#tracker', 'liu-ppf');
  assert.equal(await page.isVisible('#cues'), false, 'no cue view before it is asked for');
  await page.check('#show-cues');
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.lastLayer && window.lanepfDemo.frames > 8,
    null, { timeout: 30000 });
  await page.click('#play');
  const layer = await page.evaluate(() => window.lanepfDemo.lastLayer);
  assert.equal(layer.kind, 'grid');
  assert.match(await page.textContent('#cues-caption'), /measurement pixels/);
  assert.equal(await page.isVisible('#cues'), true);
  // The cue canvas is the top view: the markings are bright columns near the car, at the
  // true boundaries' lateral positions (y = y0 - (c + 1/2) cell).
  const cue = await page.evaluate(() => {
    const c = document.getElementById('cues');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height);
    return { width: d.width, height: d.height, data: Array.from(d.data) };
  });
  assert.equal(cue.width, layer.width);
  const truth = await page.evaluate(() => window.lanepfDemo.lastTruth);
  const ego = truth.boundaries.find((b) => b.role === 'ego-left');
  // Over 1-13 m from the near edge of the view (a dashed line has a dash in any 12 m): the
  // brightest pixel within 3 columns of the line, and the brightest 0.8-1.2 m inside the lane.
  let best = 0;
  let background = 0;
  for (let x = layer.x0 + 1; x < layer.x0 + 13; x += layer.cell) {
    const near = ego.road_points.reduce((a, p) => (Math.abs(p[0] - x) < Math.abs(a[0] - x) ? p : a));
    const col = Math.floor((layer.y0 - near[1]) / layer.cell);
    const row = cue.height - 1 - Math.floor((x - layer.x0) / layer.cell);
    const red = (c) => cue.data[4 * (row * cue.width + c)];
    for (let c = col - 3; c <= col + 3; c++) best = Math.max(best, red(c));
    for (let c = col + 8; c < col + 12; c++) background = Math.max(background, red(c));
  }
  assert.ok(best > 150 && best > background + 50, `marking ${best} vs asphalt ${background}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('demo draws danescu-mono\'s markings as bands between their inner and outer edges', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=danescu-mono`);
  await page.waitForFunction(() => document.body.dataset.state === 'running'
    && window.lanepfDemo.lastEstimate?.valid && window.lanepfDemo.frames > 20, null, { timeout: 60000 });
  // Freeze, hide the particles and the truth, and draw one frame with the estimate alone.
  await page.click('#play');
  await page.uncheck('#show-particles');
  await page.uncheck('#show-truth');
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, before, { timeout: 30000 });
  const { estimate, raw } = await page.evaluate(() => ({
    estimate: window.lanepfDemo.lastEstimate,
    raw: JSON.stringify(Array.from(window.lanepfDemo.lastRgba)),
  }));
  const frame = { width: 640, data: JSON.parse(raw) };
  const img = await readCanvas(page);
  const px = (im, x, y) => Array.from(im.data.slice(4 * (y * im.width + x), 4 * (y * im.width + x) + 3));
  const yellow = [0xff, 0xd5, 0x4f];
  const edges = (side) => estimate.delimiters.find((d) => d.role === 'ego-left' && d.side === side).points;
  const [inner, outer] = [edges('inner'), edges('outer')];
  // Rows where the left marking is at least 16 px wide: a quarter of the way in from each edge
  // (clear of the 1 px edge lines and the 2 px centre line, some 1.5 and 3 px across on a
  // marking slanted at 45 degrees) the frame is tinted 35 % towards the role colour; 3 px
  // beyond both edges it is untouched.
  let rows = 0;
  for (let y = 300; y < 480; y += 6) {
    const [a, b] = [xAt(inner, y), xAt(outer, y)];
    if (a === null || b === null || Math.abs(a - b) < 16) continue;
    rows += 1;
    const s = Math.sign(a - b);
    for (const x of [b + (a - b) / 4, a - (a - b) / 4].map(Math.round)) {
      const [got, under] = [px(img, x, y), px(frame, x, y)];
      got.forEach((v, k) => assert.ok(Math.abs(v - (0.35 * yellow[k] + 0.65 * under[k])) <= 3,
        `row ${y}, x ${x}: ${got} is not ${under} tinted towards the ego-left colour`));
    }
    for (const x of [Math.round(b - 3 * s), Math.round(a + 3 * s)]) {
      assert.deepEqual(px(img, x, y), px(frame, x, y), `row ${y}, x ${x} outside the marking is drawn on`);
    }
  }
  assert.ok(rows >= 5, `the left marking is at least 16 px wide on ${rows} sampled rows`);
  await page.check('#show-particles');
  await page.screenshot({ path: 'test-results/danescu-markings.png' });
  assert.deepEqual(errors, []);
  await page.close();
});

test('the export buttons download the run as files', async () => {
  // (What the files hold is checked in every browser by cross-browser.test.mjs, on the Blob the
  // page hands over; here, that Chromium saves exactly that text under the right name.)
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`,
    { acceptDownloads: true });
  await page.waitForFunction(() => document.body.dataset.state === 'running'
    && window.lanepfDemo.results.length >= 6, null, { timeout: 30000 });
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0); // the frame in flight
  const expected = await page.evaluate(async () => {
    const m = await import('/export.js');
    return { jsonl: m.toJsonLines(window.lanepfDemo.results), csv: m.toCsv(window.lanepfDemo.results) };
  });
  assert.ok(expected.jsonl.split('\n').length > 6, 'a run of several frames');
  for (const [button, name, text] of [
    ['#export-jsonl', 'lanepf-adachi-mmpf-highway-straight.jsonl', expected.jsonl],
    ['#export-csv', 'lanepf-adachi-mmpf-highway-straight.csv', expected.csv],
  ]) {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    assert.equal(download.suggestedFilename(), name);
    assert.equal(readFileSync(await download.path(), 'utf8'), text);
  }
  assert.deepEqual(errors, []);
  await page.close();
});
