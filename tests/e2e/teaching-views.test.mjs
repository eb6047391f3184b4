// End-to-end in Chromium: the road trackers' teaching views (issue 22, part 1). Stepping
// lee-cpf stage by stage, the status line says what the tracker reported of its resampling
// (`Tracker.resamplings()`): skipped, with the ESS it tested (the same as the estimate's own
// `lee.ess1`) and its threshold N_thr = N/2, and links to the text on degeneracy and ESS;
// adachi-mmpf says it resampled. The weight histogram is redrawn after every stage (one bar
// after a resampling, spread after a weighing, measured on its canvas), and so are the plots
// (the frame in progress is their newest point: the canvas changes after every stage, the ESS
// strip after a weighing); the ESS plot draws lee-cpf's threshold line (adachi-mmpf has none)
// and a tick on every frame that resampled (measured on the canvas); the legend says how many
// particles are drawn of the total, and its particle sample carries the weight colours. In
// compare mode the second tracker has its own weight histogram and belief view, drawn.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { start, open, running, idle } from './browser.mjs';
import { readCanvas } from './pixels.mjs';

const env = await start();
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

const status = (page) => page.textContent('#status');

/** Runs one stage (the step-stage button) and waits for it to be drawn. */
async function stage(page) {
  await page.click('#step-stage');
  await idle(page);
}

/** Pauses a running page after `frames` frames. */
async function pauseAfter(page, frames) {
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, frames, { timeout: 60000 });
  await page.click('#play');
  await idle(page);
}

/** Columns of the weight histogram's plot area (inside its axes) that carry a bar. */
async function barColumns(page) {
  const img = await readCanvas(page, 'weights');
  const columns = new Set();
  for (let y = 24; y < img.height - 26; y++) {
    for (let x = 46; x < img.width - 10; x++) {
      const i = 4 * (y * img.width + x);
      const [r, g, b] = [img.data[i], img.data[i + 1], img.data[i + 2]];
      // The bars are in the weight ramp's saturated colours; the background and axes are grey.
      if (Math.max(r, g, b) - Math.min(r, g, b) > 40) columns.add(x);
    }
  }
  return columns.size;
}

/** A hash of canvas `id`'s pixels. */
const canvasHash = async (page, id) => createHash('sha1').update(JSON.stringify(await readCanvas(page, id))).digest('hex');

/** The pixels of the plots canvas's ESS strip (5th of 6), right of the labels, as a string. */
async function essStrip(page) {
  const img = await readCanvas(page, 'plots');
  const strip = img.height / 6;
  const rows = [];
  for (let y = Math.floor(4 * strip); y < Math.floor(5 * strip); y++) {
    rows.push(img.data.slice(4 * (y * img.width + 150), 4 * (y + 1) * img.width).join(','));
  }
  return rows.join(';');
}

/** Pixels of colour `hex` (within 30 per channel) in the plots canvas's ESS strip (5th of 6). */
async function inEssStrip(page, hex) {
  const img = await readCanvas(page, 'plots');
  const [r, g, b] = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
  const strip = img.height / 6;
  let n = 0;
  for (let y = Math.floor(4 * strip); y < Math.floor(5 * strip); y++) {
    for (let x = 150; x < img.width; x++) {
      const i = 4 * (y * img.width + x);
      if (Math.abs(img.data[i] - r) < 30 && Math.abs(img.data[i + 1] - g) < 30 && Math.abs(img.data[i + 2] - b) < 30) n++;
    }
  }
  return n;
}

const colours = (page) => page.evaluate(async () => {
  const p = await import('/plots.js');
  return { threshold: p.ESS_THRESHOLD_COLOUR, tick: p.RESAMPLED_COLOUR };
});

test('lee-cpf: the step text reports a skipped resampling with its ESS and threshold', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`,
    { viewport: { width: 1280, height: 1600 } });
  await running(page);
  await pauseAfter(page, 6);
  const { threshold } = await colours(page);
  // The ESS plot: lee-cpf's threshold line is drawn.
  const line = await inEssStrip(page, threshold);
  assert.ok(line > 100, `the threshold line is drawn in the ESS strip: ${line} pixels`);
  assert.match(await page.textContent('#plots-caption'), /threshold N_thr/);

  // Step one frame stage by stage; read the text after each resampling stage, and the plots
  // after each stage.
  const texts = [];
  const columns = [];
  let plotsBefore = await canvasHash(page, 'plots');
  let essBefore = createHash('sha1').update(await essStrip(page)).digest('hex');
  for (let k = 0; k < 9; k++) {
    await stage(page);
    const s = await page.evaluate(() => ({
      resampling: window.lanepfDemo.lastResampling, weighing: window.lanepfDemo.lastWeighing,
      live: window.lanepfDemo.plotsStage, next: document.getElementById('next-stage').textContent,
    }));
    columns.push({ label: s.weighing?.label, ess: s.weighing?.ess, bars: await barColumns(page) });
    // The plots are redrawn after every stage, the frame in progress as their newest point.
    const plotsNow = await canvasHash(page, 'plots');
    assert.notEqual(plotsNow, plotsBefore, `the plots changed after stage ${k}: ${s.weighing?.label}`);
    plotsBefore = plotsNow;
    const essNow = createHash('sha1').update(await essStrip(page)).digest('hex');
    if (k > 0 && s.live) {
      assert.equal(`after “${s.live.label}”`, s.weighing.label, 'the plots show the stage just run');
      assert.equal(s.live.ess, s.weighing.ess, 'the newest ESS point is the weights’ ESS now');
      // A weighing changes the weights: the ESS strip itself changes.
      if (/weigh/.test(s.live.label)) assert.notEqual(essNow, essBefore, `the ESS strip changed after ${s.live.label}`);
    }
    essBefore = essNow;
    if (k > 0 && s.resampling) {
      texts.push({ text: await status(page), ...s.resampling });
      // The step text links to the text on resampling.
      assert.equal(await page.isVisible('#why-link'), true, 'the link follows a resampling step');
    }
    // The histogram's caption follows each stage.
    if (k > 0) assert.match(await page.textContent('#weights-caption'), /after “/);
    if (k > 0 && (await page.textContent('#next-stage')).startsWith('next: start')) break;
  }
  console.log(`lee-cpf resampling steps: ${JSON.stringify(texts)}`);
  console.log(`weight histogram per stage: ${JSON.stringify(columns)}`);
  // Both stages' resampling steps ran; each says what it did with its numbers, N_thr = N/2.
  assert.equal(texts.length, 2, 'two resampling stages in a cascade frame');
  const own = await page.evaluate(() => window.lanepfDemo.lastEstimate.state);
  texts.forEach((t, k) => {
    assert.equal(t.rule, 'ess-below', 'lee-cpf tests its ESS');
    assert.equal(t.threshold, t.particles / 2, 'N_thr = N/2 by default');
    const m = t.text.match(/ran “stage (\d): estimate, resample if N_eff < N_thr” · (?:(skipped): ESS ([\d.]+) > ([\d.]+)|(resampled): ESS ([\d.]+) < threshold ([\d.]+))$/);
    assert.ok(m, `the step text: ${t.text}`);
    assert.equal(Number(m[1]), k + 1);
    assert.equal(m[2] === 'skipped', !t.resampled, t.text);
    assert.equal(Math.round(Number(m[3] ?? m[6])), Math.round(t.ess));
    assert.equal(Math.round(Number(m[4] ?? m[7])), Math.round(t.threshold));
    // The same ESS as the tracker's own, reported with the estimate.
    const e = own[`lee.ess${k + 1}`];
    assert.ok(Math.abs(e - t.ess) < 0.5, `stage ${k + 1}: ESS ${t.ess} from the weights, ${e} from the tracker`);
  });
  // lee-cpf's stage 2 keeps its ESS above N_thr on most frames of this road: the skipped
  // resampling is said. Which frame the pause lands on depends on the machine's load (one CI
  // run paused on a frame whose stage 2 had ESS 246), so when this frame resampled in both
  // stages the page steps on, stage by stage through at most eight more frames, to one that
  // skips, and then to the end of that frame.
  const skippedText = /· skipped: ESS \d+ > 250$/;
  let skipped = texts.some((t) => skippedText.test(t.text));
  for (let k = 0; !skipped && k < 80; k++) {
    await stage(page);
    skipped = skippedText.test(await status(page));
  }
  assert.ok(skipped, `a skipped resampling is reported: ${JSON.stringify(texts)}`);
  for (let k = 0; k < 12 && !(await page.textContent('#next-stage')).startsWith('next: start'); k++) {
    await stage(page);
  }
  // The link to the text on resampling, opened (from the last resampling step's text).
  await page.click('#step-stage'); // the next frame's start
  await idle(page);
  for (let k = 0; k < 3; k++) await stage(page);
  assert.match(await status(page), /resample if N_eff < N_thr” · /);
  await page.click('#why-link');
  assert.equal(await page.evaluate(() => document.getElementById('why-resample').open), true);
  const why = await page.textContent('#why-resample');
  for (const w of ['Degeneracy', 'ESS', '1 / Σ w']) assert.ok(why.includes(w), `the text explains ${w}`);
  // The view says how many particles it draws of the total.
  const count = await page.textContent('#view-count');
  const drawn = await page.evaluate(() => window.lanepfDemo.lastHypotheses.length);
  assert.match(count, new RegExp(` ${drawn} of 1000 drawn`), count);
  await page.screenshot({ path: 'test-results/teaching-lee.png', fullPage: true });
  assert.deepEqual(errors, []);
  await page.close();
});

test('adachi-mmpf: resampled every frame, ticks on the ESS plot, no threshold, a histogram per stage', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`,
    { viewport: { width: 1280, height: 1600 } });
  await running(page);
  await pauseAfter(page, 6);
  const { threshold, tick } = await colours(page);
  assert.equal(await inEssStrip(page, threshold), 0, 'no threshold: adachi-mmpf resamples every frame');
  const ticks = await inEssStrip(page, tick);
  assert.ok(ticks >= 6 * 6, `a tick on each frame that resampled: ${ticks} pixels`);
  // Stage 1: resample. Its weights are then all 1/N: one bar; after weighing, many.
  await stage(page); // start of the frame
  await stage(page); // resample
  assert.match(await status(page), /ran “resample” · resampled: every time, whatever the ESS \(ESS \d+ of 500\)$/);
  const reported = await page.evaluate(() => window.lanepfDemo.lastResamplings);
  assert.deepEqual(reported.map((d) => [d.rule, d.threshold, d.resampled, d.particles]), [['always', null, true, 500]]);
  const afterResample = await page.evaluate(() => window.lanepfDemo.lastWeighing);
  assert.ok(Math.abs(afterResample.ess - 500) < 1, `equal weights after resampling: ESS ${afterResample.ess}`);
  const one = await barColumns(page);
  await stage(page); // predict
  assert.equal(await page.isVisible('#why-link'), false, 'the link goes with the resampling text');
  await stage(page); // weigh
  const afterWeigh = await page.evaluate(() => window.lanepfDemo.lastWeighing);
  const many = await barColumns(page);
  console.log(`adachi-mmpf histogram columns: after resample ${one}, after weigh ${many}; ESS ${afterWeigh.ess}`);
  assert.ok(afterWeigh.ess < 400, `weighing made the weights unequal: ESS ${afterWeigh.ess}`);
  assert.ok(one > 0 && one <= 12, `one bar after resampling: ${one} columns`);
  assert.ok(many > 2 * one, `bars spread after weighing: ${many} columns`);
  // The legend's particle sample carries the weight ramp's ends: light blue-violet, heavy yellow.
  const sample = await page.evaluate(() => {
    const c = document.querySelector('#legend [data-key="particles"] canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const near = (rgb) => {
      for (let i = 0; i < d.length; i += 4) {
        if (d[i + 3] > 20 && rgb.every((v, k) => Math.abs(d[i + k] - v) < 25)) return true;
      }
      return false;
    };
    return { light: near([68, 1, 84]), heavy: near([253, 231, 37]) };
  });
  assert.deepEqual(sample, { light: true, heavy: true });
  assert.match(await page.textContent('#legend [data-key="particles"]'), /coloured by weight/);
  assert.match(await page.textContent('#view-count'), /^particles: \d+ of 500 drawn$/);
  await page.screenshot({ path: 'test-results/teaching-adachi.png', fullPage: true });
  assert.deepEqual(errors, []);
  await page.close();
});

/** Pixels of each panel of a belief canvas that are not background or axis grey. */
async function beliefInk(page, panels, id = 'belief') {
  const img = await readCanvas(page, id);
  const ph = img.height / panels;
  return Array.from({ length: panels }, (_, k) => {
    let n = 0;
    // Inside the axes (x = 46, the bottom 28 px above the panel's end), away from them.
    for (let y = Math.floor(k * ph) + 36; y < Math.floor((k + 1) * ph) - 30; y++) {
      for (let x = 49; x < img.width - 12; x++) {
        const i = 4 * (y * img.width + x);
        const [r, g, b] = [img.data[i], img.data[i + 1], img.data[i + 2]];
        if (r + g + b > 200) n++;
      }
    }
    return n;
  });
}

// Each tracker's belief view, as its paper draws it, with axes and units.
const BELIEFS = {
  'adachi-mmpf': [/^edge votes H_j over ρ/, /^lane position q by model r/],
  'liu-ppf': [/^partition 1, linear part: ρ/, /^partition 2, parabolic part: d/],
  'danescu-mono': [/^lateral offset X_CW by MBSAS cluster/],
  'lee-cpf': [/^stage 1: lane offset y₀/, /^stage 2: curvature δ/],
};
for (const [tracker, titles] of Object.entries(BELIEFS)) {
  test(`${tracker}: the belief view named in its paper`, async () => {
    const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=${tracker}`,
      { viewport: { width: 1280, height: 1600 } });
    await running(page);
    await pauseAfter(page, 4);
    const belief = await page.evaluate(() => window.lanepfDemo.lastBelief);
    assert.equal(belief.length, titles.length, JSON.stringify(belief));
    belief.forEach((b, k) => {
      assert.match(b.title, titles[k]);
      assert.ok(b.unit.length > 0 && b.items > 0, JSON.stringify(b));
    });
    assert.equal(await page.isVisible('#belief'), true);
    const caption = await page.textContent('#belief-caption');
    assert.ok(caption.startsWith(`${tracker}’s belief after the whole frame`), caption);
    const ink = await beliefInk(page, titles.length);
    for (const n of ink) assert.ok(n > 50, `every panel has bars: ${ink}`);
    if (tracker === 'adachi-mmpf') {
      const p = belief[1].probabilities;
      assert.equal(p.length, 4);
      assert.ok(Math.abs(p.reduce((a, v) => a + v, 0) - 1) < 1e-6, `P(r) sums to 1: ${p}`);
    }
    if (tracker === 'lee-cpf') {
      assert.deepEqual(belief[0].markers, ['cascade output', 'Kalman output']);
      assert.deepEqual(belief[1].markers, ['cascade output', 'Kalman output']);
      // The Kalman output's line, white, across stage 1's panel (the bars are orange).
      const img = await readCanvas(page, 'belief');
      let white = 0;
      for (let y = 40; y < img.height / 2 - 30; y++) {
        for (let x = 46; x < img.width - 12; x++) {
          const i = 4 * (y * img.width + x);
          if (img.data[i] > 235 && img.data[i + 1] > 235 && img.data[i + 2] > 235) white++;
        }
      }
      assert.ok(white > 60, `the Kalman output's line is drawn: ${white} pixels`);
    }
    await page.locator('#belief-figure').screenshot({ path: `test-results/belief-${tracker}.png` });
    assert.deepEqual(errors, []);
    await page.close();
  });
}

/** Pixels of canvas `id` inside its axes (x from 46, y from 24 to 26 px above the bottom)
 *  that are not background or axis grey. */
async function ink(page, id, top = 24, bottom = 26) {
  const img = await readCanvas(page, id);
  let n = 0;
  for (let y = top; y < img.height - bottom; y++) {
    for (let x = 46; x < img.width - 10; x++) {
      const i = 4 * (y * img.width + x);
      const [r, g, b] = [img.data[i], img.data[i + 1], img.data[i + 2]];
      if (Math.max(r, g, b) - Math.min(r, g, b) > 40) n++;
    }
  }
  return n;
}

test('compare mode: the second tracker has its own weight histogram and belief view, drawn', async () => {
  const { page, errors } = await open(env.browser,
    `${env.base}/?source=highway-straight&tracker=lee-cpf&compare=adachi-mmpf`, { viewport: { width: 1280, height: 1600 } });
  await running(page);
  await pauseAfter(page, 4);
  for (const id of ['compare-weights', 'compare-belief']) {
    assert.equal(await page.isVisible(`#${id}`), true, `#${id} is shown`);
  }
  const { weighing, belief } = await page.evaluate(() => ({
    weighing: window.lanepfDemo.lastCompareWeighing, belief: window.lanepfDemo.lastCompareBelief,
  }));
  assert.equal(weighing.n, 500, 'adachi-mmpf’s 500 particles');
  assert.ok(weighing.ess > 0 && weighing.ess <= 500, `ESS ${weighing.ess}`);
  assert.match(await page.textContent('#compare-weights-caption'), /^adachi-mmpf: Weights of 500 particles after the whole frame: ESS/);
  // adachi-mmpf's panels, not lee-cpf's (which the first belief view shows).
  assert.deepEqual(belief.map((b) => b.title.replace(/ \(.*$/, '')), ['edge votes H_j over ρ', 'lane position q by model r']);
  assert.ok(belief[1].probabilities.length === 4, JSON.stringify(belief[1]));
  const ownBelief = await page.evaluate(() => window.lanepfDemo.lastBelief.map((b) => b.title));
  assert.match(ownBelief[0], /^stage 1: lane offset y₀/);
  assert.match(await page.textContent('#compare-belief-caption'), /^adachi-mmpf’s belief after the whole frame: /);
  // Both are drawn: coloured bars inside the axes of the histogram and of each belief panel.
  const bars = await ink(page, 'compare-weights');
  assert.ok(bars > 50, `the second histogram has bars: ${bars} pixels`);
  const panels = await beliefInk(page, 2, 'compare-belief');
  for (const n of panels) assert.ok(n > 50, `every panel of the second belief view has bars: ${panels}`);
  // Stepping the first tracker, the second takes the whole frame: its figures stay drawn.
  await stage(page);
  await stage(page);
  assert.equal(await page.isVisible('#compare-belief'), true);
  assert.ok((await ink(page, 'compare-weights')) > 50);
  await page.screenshot({ path: 'test-results/teaching-compare.png', fullPage: true });
  assert.deepEqual(errors, []);
  await page.close();
});

