// End-to-end in Chromium: the demo draws what it knows honestly (issue 22, part 2). An estimate
// that is not valid is drawn faded and dashed, measured on the canvas pixels along its
// boundaries against a valid one, with a badge saying which; the colour legend shows the
// colours render.js draws with, and the canvas carries them; the ground truth's control,
// caption and legend entry exist only for the simulator's sources; the plots' caption names
// the tracker shown.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import { start, open, running, idle } from './browser.mjs';
import { readCanvas, countColour } from './pixels.mjs';

const env = await start();
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
/** render.js's colours and styles, as the page's module has them. */
const styles = (page) => page.evaluate(async () => {
  const r = await import('/render.js');
  return {
    roles: r.ROLE_COLOURS, truth: r.TRUTH_COLOUR, invalidAlpha: r.INVALID_ALPHA,
  };
});
/** Steps one frame while paused and waits for it to be drawn. */
async function stepOne(page) {
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n && window.lanepfDemo.pending === 0, before,
    { timeout: 30000 });
}
/** The shown frame's estimate, the frame's own pixels and the canvas. */
async function shown(page) {
  const { estimate, raw } = await page.evaluate(() => ({
    estimate: window.lanepfDemo.lastEstimate,
    raw: JSON.stringify(Array.from(window.lanepfDemo.lastRgba)),
  }));
  const img = await readCanvas(page);
  return { estimate, img, raw: { width: img.width, data: JSON.parse(raw) } };
}

/**
 * How a boundary is drawn: along its polyline, one sample per pixel of length, the opacity of
 * its colour over the frame beneath (the least-squares alpha of canvas = a colour + (1 - a)
 * frame), where the colour differs clearly from the frame. `coverage`: the share of samples
 * drawn on at all (a > 0.15); `alpha`: the median opacity of those.
 */
function stroke(img, raw, points, hex) {
  const colour = rgb(hex);
  const alphas = [];
  for (let k = 1; k < points.length; k++) {
    const [[x0, y0], [x1, y1]] = [points[k - 1], points[k]];
    const n = Math.ceil(Math.hypot(x1 - x0, y1 - y0));
    for (let s = 0; s < n; s++) {
      const x = Math.round(x0 + ((x1 - x0) * s) / n);
      const y = Math.round(y0 + ((y1 - y0) * s) / n);
      if (x < 2 || y < 2 || x >= img.width - 2 || y >= img.data.length / 4 / img.width - 2) continue;
      const i = 4 * (y * img.width + x);
      const under = [0, 1, 2].map((c) => raw.data[i + c]);
      const d = colour.map((v, c) => v - under[c]);
      const dd = d.reduce((a, v) => a + v * v, 0);
      if (dd < 80 * 80) continue;
      alphas.push(d.reduce((a, v, c) => a + v * (img.data[i + c] - under[c]), 0) / dd);
    }
  }
  const drawn = alphas.filter((a) => a > 0.15).sort((a, b) => a - b);
  return {
    samples: alphas.length,
    coverage: drawn.length / Math.max(1, alphas.length),
    alpha: drawn.length ? drawn[Math.floor(drawn.length / 2)] : 0,
  };
}
const egoStrokes = (s, roles) => ['ego-left', 'ego-right'].map((role) => {
  const b = s.estimate.boundaries.find((x) => x.role === role);
  assert.ok(b && b.points.length >= 2, `the estimate has its ${role} boundary`);
  return { role, ...stroke(s.img, s.raw, b.points, roles[role]) };
});
const badge = (page) => page.evaluate(() => {
  const b = document.getElementById('view-badge');
  return { visible: b.checkVisibility(), text: b.textContent, valid: b.dataset.valid };
});
const truthShown = (page) => page.evaluate(() => ({
  control: document.getElementById('show-truth').checkVisibility(),
  legend: document.querySelector('#legend [data-key="truth"]').checkVisibility(),
  caption: /ground truth/.test(document.getElementById('caption').textContent),
  plots: /ground truth/.test(document.getElementById('plots-caption').textContent),
}));

test('an estimate that is not valid is drawn faded and dashed, and the badge says "no lane"', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`);
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.frames > 10 && window.lanepfDemo.lastEstimate?.valid,
    null, { timeout: 30000 });
  const { roles, invalidAlpha } = await styles(page);
  // One frame of the scene with the estimate alone (no particles, no truth).
  await page.click('#play');
  await page.uncheck('#show-particles');
  await page.uncheck('#show-truth');
  await idle(page);
  await stepOne(page);
  const valid = await shown(page);
  assert.equal(valid.estimate.valid, true, 'adachi-mmpf is confident on the straight highway');
  assert.deepEqual(await badge(page), { visible: true, text: 'valid', valid: 'true' });
  // A blank grey picture: adachi-mmpf finds no marking and says so, but still has a guess.
  const png = await page.evaluate(async () => {
    const canvas = new OffscreenCanvas(640, 480);
    const c = canvas.getContext('2d');
    c.fillStyle = 'rgb(120, 120, 120)';
    c.fillRect(0, 0, 640, 480);
    const bytes = new Uint8Array(await (await canvas.convertToBlob({ type: 'image/png' })).arrayBuffer());
    let s = '';
    for (const b of bytes) s += String.fromCharCode(b);
    return btoa(s);
  });
  await page.setInputFiles('#file', { name: 'blank.png', mimeType: 'image/png', buffer: Buffer.from(png, 'base64') });
  await page.waitForFunction(() => /Image “blank\.png”/.test(document.getElementById('status').textContent));
  await stepOne(page);
  const invalid = await shown(page);
  assert.equal(invalid.estimate.valid, false, 'no lane on a blank picture');
  assert.deepEqual(await badge(page), { visible: true, text: 'no lane: not valid', valid: 'false' });
  await page.screenshot({ path: 'test-results/invalid-estimate.png', fullPage: true });

  const [v, n] = [egoStrokes(valid, roles), egoStrokes(invalid, roles)];
  const report = JSON.stringify({ valid: v, invalid: n });
  console.log(`boundaries drawn: ${report}`);
  for (const s of [...v, ...n]) assert.ok(s.samples >= 60, `enough of each boundary measured: ${report}`);
  for (const s of v) {
    // Solid and opaque.
    assert.ok(s.coverage > 0.9 && s.alpha > 0.85, `valid ${s.role} drawn solid and opaque: ${report}`);
  }
  for (const s of n) {
    // Drawn (not hidden), but in dashes, and faded to render.js's INVALID_ALPHA.
    assert.ok(s.coverage > 0.15 && s.coverage < 0.7, `invalid ${s.role} drawn dashed: ${report}`);
    assert.ok(Math.abs(s.alpha - invalidAlpha) < 0.12, `invalid ${s.role} faded to ${invalidAlpha}: ${report}`);
  }
  assert.deepEqual(errors, []);
  await page.close();
});

test('the legend names the colours render.js draws with, and the canvas carries them', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=test-road&tracker=adachi-mmpf`);
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.frames > 8 && window.lanepfDemo.lastEstimate?.valid,
    null, { timeout: 30000 });
  await page.click('#play');
  await page.uncheck('#show-particles');
  await idle(page);
  await stepOne(page);
  const { roles, truth, invalidAlpha } = await styles(page);
  // Each entry: its label and its sample's pixels (opaque pixels of each colour, most opaque alpha).
  const legend = await page.evaluate(() => [...document.querySelectorAll('#legend li')].map((li) => {
    const c = li.querySelector('canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = {};
    let maxAlpha = 0;
    for (let i = 0; i < d.length; i += 4) {
      maxAlpha = Math.max(maxAlpha, d[i + 3]);
      if (d[i + 3] === 255) {
        const hex = `#${[d[i], d[i + 1], d[i + 2]].map((v) => v.toString(16).padStart(2, '0')).join('')}`;
        colours[hex] = (colours[hex] ?? 0) + 1;
      }
    }
    return { key: li.dataset.key, text: li.textContent.trim(), visible: li.checkVisibility(), colours, maxAlpha };
  }));
  const entry = (key) => legend.find((e) => e.key === key);
  assert.deepEqual(legend.map((e) => e.key),
    [...Object.keys(roles), 'invalid', 'truth', 'particles']);
  for (const [role, hex] of Object.entries(roles)) {
    assert.match(entry(role).text, new RegExp(`^${role}`), `the legend names ${role}`);
    assert.ok(entry(role).colours[hex] >= 60, `${role}'s sample is ${hex}: ${JSON.stringify(entry(role).colours)}`);
  }
  assert.match(entry('truth').text, /ground truth/);
  assert.ok(entry('truth').colours[truth] >= 30, `the truth's sample is ${truth}`);
  assert.match(entry('particles').text, /particles/);
  assert.match(entry('invalid').text, /not valid.*faded.*dashed/);
  assert.ok(Math.abs(entry('invalid').maxAlpha / 255 - invalidAlpha) < 0.05,
    `the not-valid sample is faded to ${invalidAlpha} (${entry('invalid').maxAlpha})`);
  assert.ok(legend.every((e) => e.visible), 'every entry is shown for a scene with ground truth');
  // The camera view carries those colours: the truth in its own, the estimate in its roles'.
  const img = await readCanvas(page);
  assert.ok(countColour(img, rgb(truth)) > 100, `ground truth drawn in ${truth}`);
  for (const role of ['ego-left', 'ego-right']) {
    assert.ok(countColour(img, rgb(roles[role])) > 100, `${role} drawn in ${roles[role]}`);
  }
  await page.screenshot({ path: 'test-results/legend.png', fullPage: true });
  // Unticked, the truth's colour is gone from the canvas.
  await page.uncheck('#show-truth');
  await stepOne(page);
  assert.ok(countColour(await readCanvas(page), rgb(truth)) < 10, 'no truth drawn when unticked');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the ground truth control, caption and legend entry are there only for the simulator', async () => {
  // The bundled clip: a video, no ground truth.
  const { page, errors } = await open(env.browser, `${env.base}/?tracker=lee-cpf`);
  await running(page);
  assert.deepEqual(await truthShown(page), { control: false, legend: false, caption: false, plots: false });
  // A scene: all of them.
  await page.selectOption('#source', 'highway-curve');
  await page.waitForFunction(() => /highway-curve/.test(document.getElementById('status').textContent));
  assert.deepEqual(await truthShown(page), { control: true, legend: true, caption: true, plots: true });
  // Still images: none again.
  const png = await page.evaluate(async () => {
    const canvas = new OffscreenCanvas(320, 240);
    canvas.getContext('2d').fillRect(0, 0, 320, 240);
    const bytes = new Uint8Array(await (await canvas.convertToBlob({ type: 'image/png' })).arrayBuffer());
    let s = '';
    for (const b of bytes) s += String.fromCharCode(b);
    return btoa(s);
  });
  await page.setInputFiles('#file', { name: 'still.png', mimeType: 'image/png', buffer: Buffer.from(png, 'base64') });
  await page.waitForFunction(() => /Image “still\.png”/.test(document.getElementById('status').textContent));
  assert.deepEqual(await truthShown(page), { control: false, legend: false, caption: false, plots: false });
  // And the test road has it.
  await page.selectOption('#source', 'test-road');
  await page.waitForFunction(() => /Synthetic test road/.test(document.getElementById('status').textContent));
  assert.deepEqual(await truthShown(page), { control: true, legend: true, caption: true, plots: true });
  assert.deepEqual(errors, []);
  await page.close();
});

test('the plots\' caption names the tracker shown', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  const caption = () => page.textContent('#plots-caption');
  assert.match(await caption(), /^lee-cpf’s estimate \(blue\), the ground truth .* Kalman smoother \(orange\)/);
  await page.selectOption('#tracker', 'adachi-mmpf');
  await page.waitForFunction(() => /^adachi-mmpf/.test(document.getElementById('plots-caption').textContent));
  assert.match(await caption(), /^adachi-mmpf’s estimate \(blue\) and the ground truth \(grey, dashed\), over the last 300 frames\. ESS: the filter’s, the threshold N_thr the tracker reports testing it against \(yellow, dashed; none when it resamples whatever the ESS\) and a red tick on each frame it reports resampling; stepping, the frame in progress is ringed and redrawn after every stage$/);
  assert.doesNotMatch(await caption(), /lee-cpf|Kalman/);
  await page.selectOption('#tracker', 'liu-ppf');
  await page.waitForFunction(() => /^liu-ppf’s/.test(document.getElementById('plots-caption').textContent));
  await page.selectOption('#tracker', '');
  await page.waitForFunction(() => /^No tracker/.test(document.getElementById('plots-caption').textContent));
  assert.deepEqual(errors, []);
  await page.close();
});
