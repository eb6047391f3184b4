// End-to-end: every tracker chosen from the page tracks a simulator scene; the per-step
// (teaching) mode runs one stage per click; a run exports as JSON lines and CSV.
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { start, open } from './browser.mjs';

const env = await start();
test.after(() => env.close());

const running = (page) => page.waitForFunction(() => document.body.dataset.state === 'running',
  null, { timeout: 30000 });

test('every tracker can be chosen and tracks a synthetic scene within 0.3 m', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=`);
  await running(page);
  const ids = (await page.$$eval('#tracker option', (os) => os.map((o) => o.value))).filter(Boolean);
  assert.deepEqual(ids, ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf', 'liu-ppf',
    'liu-ppf-nokernel']);
  const report = [];
  for (const id of ids) {
    await page.click('#play'); // pause while switching
    await page.click('#restart');
    await page.selectOption('#tracker', id);
    await page.click('#play');
    await page.waitForFunction(() => window.lanepfDemo.offsetErrors.length >= 30, null, { timeout: 60000 });
    const errs = await page.evaluate(() => window.lanepfDemo.offsetErrors.slice(20, 30));
    const mean = errs.reduce((a, b) => a + b, 0) / errs.length;
    report.push(`${id} ${mean.toFixed(3)}`);
    assert.ok(mean < 0.3, `${id}: mean offset error ${mean.toFixed(3)} m over frames 20-29`);
    assert.match(await page.textContent('#timing'), /track \d+\.\d ms · offset error \d+ cm/);
  }
  console.log(`mean |offset error| frames 20-29: ${report.join(', ')}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the per-step mode runs one stage of the filter per click and redraws the cloud', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-curve&tracker=lee-cpf`);
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.results.length >= 3, null, { timeout: 30000 });
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  assert.equal(await page.isEnabled('#step-stage'), true);
  const names = await page.evaluate(async () => {
    const m = await import('/pkg/web/lanepf.js');
    await m.default();
    const scene = new m.Scene('highway-curve', { width: 320, height: 240, seed: 1 });
    const t = new m.Tracker('lee-cpf', { camera: scene.camera() });
    return t.stepNames();
  });
  assert.ok(names.length >= 4, names.join());
  const frames = await page.evaluate(() => window.lanepfDemo.results.length);
  assert.match(await page.textContent('#next-stage'), /next: start of a frame/);
  // The first click starts the frame (its cues); each next click runs one named step.
  await page.click('#step-stage');
  await page.waitForFunction(() => /next: /.test(document.getElementById('next-stage').textContent)
    && !/start of a frame/.test(document.getElementById('next-stage').textContent));
  let clouds = [];
  for (let k = 0; k < names.length; k++) {
    assert.equal(await page.textContent('#next-stage'), `next: ${names[k]}`);
    const drawn = await page.evaluate(() => window.lanepfDemo.frames);
    await page.click('#step-stage');
    await page.waitForFunction((n) => window.lanepfDemo.frames > n, drawn);
    assert.match(await page.textContent('#status'), new RegExp(`ran “${names[k].replace(/[[\]().*+?]/g, '\\$&')}”`));
    clouds.push(await page.evaluate(() => JSON.stringify(window.lanepfDemo.lastHypotheses)));
    const done = await page.evaluate(() => window.lanepfDemo.results.length);
    // The estimate (one more result) comes with the last step, not before.
    assert.equal(done, k === names.length - 1 ? frames + 1 : frames, `after step ${k}`);
  }
  assert.ok(new Set(clouds).size >= 3, 'the cloud moves between steps');
  assert.match(await page.textContent('#next-stage'), /next: start of a frame/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a run exports as JSON lines in the track format and as CSV', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`,
    { acceptDownloads: true });
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.results.length >= 6, null, { timeout: 30000 });
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0); // the frame in flight
  const n = await page.evaluate(() => window.lanepfDemo.results.length);
  const [jsonl] = await Promise.all([page.waitForEvent('download'), page.click('#export-jsonl')]);
  assert.equal(jsonl.suggestedFilename(), 'lanepf-adachi-mmpf-highway-straight.jsonl');
  const lines = readFileSync(await jsonl.path(), 'utf8').split('\n');
  assert.equal(lines.pop(), '', 'newline-terminated');
  assert.equal(lines.length, n);
  lines.forEach((line, k) => {
    const r = JSON.parse(line);
    assert.equal(r.frame, `${k}`);
    assert.equal(typeof r.valid, 'boolean');
    for (const key of ['lateral_offset_m', 'heading_rad', 'curvature_per_m', 'lane_width_m', 'ms']) {
      assert.ok(Number.isFinite(r[key]), `${key} in line ${k}`);
    }
    assert.ok(r.boundaries.some((b) => b.role === 'ego-left' && b.points.length > 5));
    assert.ok(Number.isFinite(r.state['adachi.q']));
  });
  const [csv] = await Promise.all([page.waitForEvent('download'), page.click('#export-csv')]);
  const rows = readFileSync(await csv.path(), 'utf8').trim().split('\n');
  assert.equal(rows[0], 'frame,valid,lateral_offset_m,heading_rad,curvature_per_m,lane_width_m,ms');
  assert.equal(rows.length, n + 1);
  assert.equal(Number(rows[1].split(',')[2]), JSON.parse(lines[0]).lateral_offset_m);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the teaching panel explains the tracker, its sliders rebuild it, and the seed makes runs repeat', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`);
  await running(page);
  assert.match(await page.textContent('#teach-title'), /Adachi/);
  assert.match(await page.textContent('#teach-text'), /Table 1/);
  const defaults = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#params input')]
    .map((i) => [i.name, i.type === 'checkbox' ? i.checked : Number(i.value)])));
  assert.equal(defaults.particles, 500);
  assert.equal(defaults.sigma_q_m, 0.08);
  // Fewer particles: the tracker is rebuilt, and the drawn cloud is all of its 60 particles.
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  await page.$eval('#params input[name="particles"]', (i) => {
    i.value = '60';
    i.dispatchEvent(new Event('change'));
  });
  await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.frames === 0);
  await page.click('#step');
  await page.waitForFunction(() => window.lanepfDemo.frames === 1);
  assert.equal(await page.evaluate(() => window.lanepfDemo.lastHypotheses.length), 60);

  // The same seed from the same frame gives the same run; another seed another one.
  const run = async (seed) => {
    await page.fill('#seed', `${seed}`);
    await page.$eval('#seed', (i) => i.dispatchEvent(new Event('change')));
    await page.click('#restart');
    await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.results.length === 0);
    for (let k = 0; k < 5; k++) {
      await page.click('#step');
      await page.waitForFunction((k) => window.lanepfDemo.results.length === k + 1, k);
    }
    return page.evaluate(() => window.lanepfDemo.results.map((r) => r.lateral_offset_m));
  };
  const a = await run(7);
  const b = await run(7);
  const c = await run(8);
  assert.deepEqual(a, b);
  assert.notDeepEqual(a, c);
  // Back to the paper's defaults.
  await page.click('#params-reset');
  await page.waitForFunction(() => document.querySelector('#params input[name="particles"]').value === '500');
  assert.deepEqual(errors, []);
  await page.close();
});

test('two trackers run side by side on the same frames', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  assert.equal(await page.isVisible('#view2'), false, 'no second view until asked');
  // (Both trackers are rebuilt mid-scene: each must find the lane from a cold start.)
  await page.selectOption('#compare', 'adachi-mmpf');
  await page.waitForFunction(() => window.lanepfDemo.lastCompare && window.lanepfDemo.results.length >= 20,
    null, { timeout: 30000 });
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const { main, other, truth } = await page.evaluate(() => ({
    main: window.lanepfDemo.lastEstimate, other: window.lanepfDemo.lastCompare, truth: window.lanepfDemo.lastTruth,
  }));
  assert.equal(other.trackerId, 'adachi-mmpf');
  assert.equal(main.state['lee.psi'] !== undefined, true, 'the main view is still lee-cpf');
  assert.ok(other.estimate.state['adachi.q'] !== undefined, 'the second view is adachi-mmpf');
  for (const e of [main, other.estimate]) {
    assert.ok(Math.abs(e.lateral_offset_m - truth.lateral_offset_m) < 0.3,
      `offset ${e.lateral_offset_m} vs truth ${truth.lateral_offset_m}`);
  }
  assert.equal(await page.isVisible('#view2'), true);
  assert.match(await page.textContent('#compare-caption'), /^adachi-mmpf · track \d+\.\d ms · offset error \d+ cm/);
  // The second canvas shows the frame with the ego-left colour drawn on it.
  const yellow = await page.evaluate(() => {
    const c = document.getElementById('view2');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] === 0xff && d[i + 1] === 0xd5 && d[i + 2] === 0x4f) n++;
    return n;
  });
  assert.ok(yellow > 100, `ego-left drawn on the second view (${yellow} px)`);
  await page.selectOption('#compare', '');
  await page.click('#step');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.frames >= 1);
  assert.equal(await page.isVisible('#view2'), false);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the keyboard plays, pauses and steps', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  await page.locator('body').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press(' ');
  assert.equal(await page.textContent('#play'), 'Play', 'space pauses');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const n = await page.evaluate(() => window.lanepfDemo.results.length);
  await page.keyboard.press('.');
  await page.waitForFunction((n) => window.lanepfDemo.results.length === n + 1, n);
  await page.keyboard.press(',');
  await page.waitForFunction(() => !/start of a frame/.test(document.getElementById('next-stage').textContent));
  await page.keyboard.press(' ');
  assert.equal(await page.textContent('#play'), 'Pause', 'space plays again');
  // Playing finishes the half-stepped frame first, then goes on.
  await page.waitForFunction((n) => window.lanepfDemo.results.length >= n + 4, n);
  assert.deepEqual(errors, []);
  await page.close();
});
