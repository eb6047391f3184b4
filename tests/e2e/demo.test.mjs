// End-to-end: the demo page loads the wasm package in a worker and draws a synthetic road with
// its ground-truth boundaries. Checked on the canvas pixels, not on the DOM.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import { start, open } from './browser.mjs';
import { readCanvas, lum, peak, countColour, xAt } from './pixels.mjs';

const env = await start();
test.after(() => env.close());

test('demo draws the synthetic road with markings where the ground truth says', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=test-road&tracker=`);
  await page.waitForFunction(() => document.body.dataset.state === 'running'
    && window.lanepfDemo.frames >= 3, null, { timeout: 30000 });
  assert.match(await page.textContent('#version'), /^lanepf \d+\.\d+\.\d+/);

  // Freeze the stream, hide the overlay and draw one clean frame.
  await page.click('#play');
  await page.uncheck('#show-truth');
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, before);
  const truth = await page.evaluate(() => window.lanepfDemo.lastTruth);
  const img = await readCanvas(page);
  assert.equal(img.width, 640);
  assert.equal(img.height, 480);

  const left = truth.boundaries.find((b) => b.role === 'ego-left');
  const right = truth.boundaries.find((b) => b.role === 'ego-right');
  assert.ok(left && right, 'ground truth has both ego boundaries');
  assert.ok(left.points.length >= 10, 'boundary polylines are sampled densely');

  // The solid left marking is bright along (nearly) all of its projected polyline, the dashed
  // right one along part of it, and the lane centre between them is dark asphalt.
  const near = (pts) => pts.filter(([, y]) => y > 200);
  const hit = (pts) => near(pts).filter(([x, y]) => peak(img, x, y, 3) > 150).length / near(pts).length;
  assert.ok(hit(left.points) > 0.9, `solid marking found on ${hit(left.points)} of the left polyline`);
  // The right marking is dashed (3 m of every 12 m): which part of it is painted depends on
  // the frame, but some dash is always near the car and it is never solid.
  const dashed = hit(right.points);
  assert.ok(dashed > 0.05 && dashed < 0.6, `dashed marking found on ${dashed} of the right polyline`);
  for (let k = 0; k < near(left.points).length; k += 3) {
    const [xl, y] = near(left.points)[k];
    const xr = right.points.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a))[0];
    assert.ok(lum(img, (xl + xr) / 2, y) < 140, `lane centre at row ${y} is asphalt`);
  }

  // With the overlay on, the role colours appear on the canvas.
  await page.check('#show-truth');
  const n2 = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, n2);
  const withOverlay = await readCanvas(page);
  const yellow = countColour(withOverlay, [0xff, 0xd5, 0x4f]);
  assert.ok(yellow > 100, `ego-left overlay drawn (${yellow} px)`);

  mkdirSync('test-results', { recursive: true });
  await page.screenshot({ path: 'test-results/demo.png' });
  assert.deepEqual(errors, []);
  await page.close();
});

test('demo switches to a simulator scenario and draws it under its ground truth', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?tracker=`);
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
  const names = await page.$$eval('#source option', (os) => os.map((o) => o.value));
  assert.ok(names.includes('highway-curve') && names.includes('urban') && names.length >= 13, names.join());

  await page.click('#play');
  await page.uncheck('#show-truth');
  await page.selectOption('#source', 'highway-curve');
  await page.waitForFunction(() => /highway-curve/.test(document.getElementById('status').textContent));
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
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
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
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
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
