// End-to-end in Chromium: the first lesson (toy.html, issue 22 part 1's first item), a 1-D
// particle filter with the demo's step controls. Stage by stage the status line tells what ran
// (a skipped resampling with its ESS and threshold), the weight histogram follows the belief
// (measured on its canvas), a resampling is animated (canvas frames differ while it runs, the
// dots end equal), the keys work, and the filter finds the car. Reached from the demo's header.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import { start, open } from './browser.mjs';
import { readCanvas } from './pixels.mjs';

const env = await start();
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

const lesson = (page) => page.evaluate(() => {
  const l = window.toyLesson;
  return {
    stages: l.stages, last: l.last, next: l.filter.nextStage, step: l.filter.step, car: l.filter.car,
    estimate: l.filter.estimate(), animating: l.animating, frames: l.animationFrames,
    weights: [Math.min(...l.filter.w), Math.max(...l.filter.w)], n: l.filter.x.length,
  };
});
/** Presses `key` and waits for `n` more stages to have run (and any animation to end). */
async function press(page, key, n = 1) {
  const before = (await lesson(page)).stages;
  await page.keyboard.press(key);
  await page.waitForFunction((k) => window.toyLesson.stages >= k && !window.toyLesson.animating, before + n);
}
/** The histogram's bars: the canvas column of the tallest bar and how many columns have one. */
async function bars(page) {
  const img = await readCanvas(page, 'toy-hist');
  const heights = [];
  for (let x = 0; x < img.width; x++) {
    let h = 0;
    for (let y = 14; y < img.height - 12; y++) {
      const i = 4 * (y * img.width + x);
      if (img.data[i] > 200 && img.data[i + 1] > 150 && img.data[i + 2] < 120) h++;
    }
    heights.push(h);
  }
  const top = Math.max(...heights);
  return { tallest: heights.indexOf(top), top, columns: heights.filter((h) => h > 0).length };
}

test('the first lesson: a particle filter on a line, stage by stage', async () => {
  const { page: demo, errors: demoErrors } = await open(env.browser, `${env.base}/`);
  // The demo links to it.
  await demo.click('#lesson-link');
  await demo.waitForURL(/toy\.html$/);
  await demo.waitForFunction(() => document.body.dataset.state === 'running');
  assert.deepEqual(demoErrors, []);
  await demo.close();

  const { page, errors } = await open(env.browser, `${env.base}/toy.html`, { viewport: { width: 1000, height: 900 } });
  await page.waitForFunction(() => document.body.dataset.state === 'running');
  assert.equal(await page.textContent('#toy-next'), 'next: predict');
  const keys = await page.textContent('.keys');
  for (const k of ['space', '.', ',']) assert.ok(keys.includes(k), keys);
  // At the start the belief is flat: bars all along the line.
  const flat = await bars(page);
  assert.ok(flat.columns > 500, `a flat histogram at the start: ${JSON.stringify(flat)}`);

  // `,`: one stage at a time.
  await press(page, ',');
  assert.match(await page.textContent('#toy-status'), /^step 1 · predict: the car drove to \d+\.\d m/);
  assert.equal((await lesson(page)).next, 'weigh');
  await press(page, ',');
  let s = await lesson(page);
  assert.match(await page.textContent('#toy-status'), /^step 1 · weigh: .* · ESS \d+ of 200$/);
  assert.ok(s.weights[1] > 2 * s.weights[0], 'weighing made the weights unequal');
  // After weighing, the histogram's tallest bar is at the reading, near the car (within 10 m,
  // the sensor's sigma being 4 m); the canvas maps 0-100 m to columns 30-770.
  const weighed = await bars(page);
  const column = (m) => 30 + (m / 100) * 740;
  assert.ok(Math.abs(weighed.tallest - column(s.car)) < 74, `tallest bar at column ${weighed.tallest}, the car at ${column(s.car).toFixed(0)}`);
  // The first weighing of a cloud spread over 100 m by a 4 m sensor leaves ESS far below N/2:
  // it resamples, animated (the canvas changes while it runs), and the weights end equal.
  const before = (await lesson(page)).stages;
  await page.keyboard.press(',');
  await page.waitForFunction((n) => window.toyLesson.stages >= n, before + 1);
  const shots = [];
  while ((await lesson(page)).animating && shots.length < 3) {
    shots.push(JSON.stringify((await readCanvas(page, 'toy-view')).data));
  }
  assert.ok(shots.length >= 2 && new Set(shots).size >= 2, `the resampling is animated (${shots.length} frames read)`);
  await page.waitForFunction(() => !window.toyLesson.animating);
  s = await lesson(page);
  assert.equal(s.last.stage, 'resample');
  assert.equal(s.last.resampled, true, JSON.stringify(s.last));
  assert.match(await page.textContent('#toy-status'), /^step 1 · resample: ESS \d+ < 100: \d+ of 200 particles were copied/);
  assert.ok(s.frames > 5, `animation frames drawn: ${s.frames}`);
  assert.ok(Math.abs(s.weights[0] - 1 / 200) < 1e-12 && Math.abs(s.weights[1] - 1 / 200) < 1e-12, 'equal weights after resampling');

  // `.`: whole steps. Once the cloud has gathered round the car, a weighing changes the
  // weights little, and the resampling is skipped, with its ESS and threshold said.
  let skipped = null;
  for (let k = 0; k < 30 && !skipped; k++) {
    const n = (await lesson(page)).stages;
    await page.keyboard.press('.');
    await page.waitForFunction((m) => window.toyLesson.stages >= m && !window.toyLesson.animating, n + 3);
    const now = await lesson(page);
    if (!now.last.resampled) skipped = now;
  }
  assert.ok(skipped, 'a step skipped its resampling within 30 steps');
  assert.match(await page.textContent('#toy-status'), /resample: skipped: ESS \d+ > 100 /);
  const marks = await page.evaluate(() => window.toyLesson.history.map((h) => h.resampled));
  assert.ok(marks.includes(true) && marks.includes(false), 'the ESS plot has steps that resampled and steps that did not');

  // Space plays; after a while the filter has found the car.
  await page.keyboard.press(' ');
  await page.waitForFunction(() => window.toyLesson.filter.step >= 25, null, { timeout: 30000 });
  await page.keyboard.press(' ');
  await page.waitForFunction(() => !window.toyLesson.animating);
  s = await lesson(page);
  const d = Math.abs(s.estimate - s.car);
  assert.ok(Math.min(d, 100 - d) < 4, `estimate ${s.estimate.toFixed(1)} m, car ${s.car.toFixed(1)} m`);
  const found = await bars(page);
  assert.ok(found.columns < 300, `the belief has narrowed: ${JSON.stringify(found)}`);
  await page.screenshot({ path: 'test-results/toy-lesson.png', fullPage: true });
  assert.deepEqual(errors, []);
  await page.close();
});
