// End-to-end in Chromium: the demo's layout and pacing (issue 22, part 3). Measured on the page
// as a visitor gets it: bounding boxes on a phone (390x844) and a laptop (1280x800), layout
// shifts while the page loads (with the WebAssembly module held back, to see the page before
// it), the rate frames are presented at over seconds against the source's own, compare mode
// side by side and named, the status line after a tracker switch, liu-ppf-nokernel's cue.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import { start, open, running, idle } from './browser.mjs';
import { readCanvas, countNear } from './pixels.mjs';

const env = await start();
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

const PHONE = { width: 390, height: 844 };
const LAPTOP = { width: 1280, height: 800 };

/** The bounding box of `selector` in page coordinates (scrolled to the top), or null if hidden. */
const box = (page, selector) => page.evaluate((s) => {
  const el = document.querySelector(s);
  if (!el?.checkVisibility()) return null;
  const r = el.getBoundingClientRect();
  return { x: r.x + scrollX, y: r.y + scrollY, width: r.width, height: r.height, bottom: r.bottom + scrollY, right: r.right + scrollX };
}, selector);
const round = (b) => b && Object.fromEntries(Object.entries(b).map(([k, v]) => [k, Math.round(v)]));

test('the view is in the first screen on a phone and a laptop, the teaching panel near it', async () => {
  const seen = {};
  for (const viewport of [PHONE, LAPTOP]) {
    const { page, errors } = await open(env.browser, `${env.base}/`, { viewport });
    await running(page);
    await page.waitForFunction(() => window.lanepfDemo.frames > 2, null, { timeout: 30000 });
    const [view, play, teach, keys] = await Promise.all(['#view', '#play', '#teach', '#keys'].map((s) => box(page, s)));
    seen[`${viewport.width}x${viewport.height}`] = { view: round(view), play: round(play), teach: round(teach) };
    // The whole camera view, and the play button under it, without scrolling.
    assert.ok(view.y >= 0 && view.bottom <= viewport.height, `view in the first screen: ${JSON.stringify(seen)}`);
    assert.ok(view.width >= Math.min(640, viewport.width - 40), `the view uses the width: ${JSON.stringify(seen)}`);
    assert.ok(play.bottom <= viewport.height, `the play button in the first screen: ${JSON.stringify(seen)}`);
    // The teaching panel: starts in the first screen on a laptop, within two screens on a phone.
    const reach = viewport === LAPTOP ? viewport.height : 2 * viewport.height;
    assert.ok(teach && teach.y < reach, `teaching panel starts above ${reach} px: ${JSON.stringify(seen)}`);
    // The keys are on the page.
    assert.ok(keys, 'the keys are shown');
    const text = await page.textContent('#keys');
    for (const k of ['space', '.', ',']) assert.ok(text.includes(k), `key ${k} named: ${text}`);
    // The advanced inputs wait behind a disclosure.
    assert.equal(await page.isVisible('#stereo'), false, 'stereo hidden at first');
    assert.equal(await page.isVisible('#camera-file'), false, 'camera file hidden at first');
    await page.click('#advanced summary');
    assert.equal(await page.isVisible('#stereo'), true, 'stereo shown when asked');
    assert.equal(await page.isVisible('#camera-file'), true, 'camera file shown when asked');
    await page.screenshot({ path: `test-results/layout-${viewport.width}x${viewport.height}.png` });
    assert.deepEqual(errors, []);
    await page.close();
  }
  console.log(`layout: ${JSON.stringify(seen)}`);
});

test('nothing moves while the page loads, and the tracker menu works before the module', async () => {
  for (const viewport of [PHONE, LAPTOP]) {
    const page = await env.browser.newPage({ viewport });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    // The layout shifts the browser reports, from the start (buffered).
    await page.addInitScript(() => {
      window.__shifts = [];
      new PerformanceObserver((list) => {
        for (const e of list.getEntries()) {
          if (!e.hadRecentInput) window.__shifts.push({ value: e.value, at: e.startTime, nodes: e.sources.map((s) => s.node?.id || s.node?.nodeName) });
        }
      }).observe({ type: 'layout-shift', buffered: true });
    });
    // Hold the WebAssembly module back: the page as it is before the module answers.
    let release;
    const held = new Promise((r) => { release = r; });
    await page.route('**/lanepf_bg.wasm', async (route) => {
      await held;
      await route.continue();
    });
    // (The load event comes after main.js has run; the module is still held.)
    await page.goto(`${env.base}/`);
    const menu = await page.evaluate(() => {
      const t = document.getElementById('tracker');
      return { disabled: t.disabled, value: t.value, ids: [...t.options].map((o) => o.value), status: document.getElementById('status').textContent };
    });
    const ids = ['#view', '#play', '#tracker', '#status', '#teach', '#show-plots'];
    const before = await Promise.all(ids.map((s) => box(page, s)));
    release();
    await running(page);
    await page.waitForFunction(() => window.lanepfDemo.frames > 30, null, { timeout: 30000 });
    const shifts = await page.evaluate(() => window.__shifts);
    const score = shifts.reduce((a, s) => a + s.value, 0);
    console.log(`layout shift at ${viewport.width}x${viewport.height}: ${score.toFixed(4)} (${JSON.stringify(shifts)})`);
    assert.ok(score < 0.01, `cumulative layout shift ${score.toFixed(4)}: ${JSON.stringify(shifts)}`);
    const after = await Promise.all(ids.map((s) => box(page, s)));
    // Everything in the first screen stands where it stood before the module, to the pixel.
    // (Below it, on a phone, the status lines may grow and push the teaching panel down: a
    // shift nobody sees, which the browser does not count either.)
    ids.forEach((s, k) => {
      assert.ok(before[k] && after[k], `${s} shown`);
      if (before[k].y >= viewport.height) return;
      assert.ok(Math.abs(before[k].x - after[k].x) <= 1 && Math.abs(before[k].y - after[k].y) <= 1,
        `${s} moved at ${viewport.width}x${viewport.height}: ${JSON.stringify(round(before[k]))} -> ${JSON.stringify(round(after[k]))}`);
    });
    assert.equal(Math.round(after[0].height), Math.round(before[0].height), 'the view keeps its size');
    assert.match(menu.status, /Loading/, 'the module was still loading');
    assert.equal(menu.disabled, false, 'the tracker menu is enabled at load');
    assert.equal(menu.value, 'lee-cpf');
    // The menu lists what the module has (index.html's list is the registry's).
    const registry = await page.evaluate(async () => {
      const m = await import('/pkg/web/lanepf.js');
      await m.default();
      return m.trackerIds();
    });
    assert.deepEqual(menu.ids, ['', ...registry]);
    assert.deepEqual(errors, []);
    await page.close();
  }
});

/**
 * Frames presented per second over `ms` of playback, measured in the page: frames drawn and
 * the frame index they reached (a skipped frame would show as an index running ahead).
 */
const measureRate = (page, ms) => page.evaluate(async (ms) => {
  const d = window.lanepfDemo;
  const [f0, i0, t0] = [d.frames, d.lastFrame.index, performance.now()];
  await new Promise((r) => setTimeout(r, ms));
  const [f1, i1, t1] = [d.frames, d.lastFrame.index, performance.now()];
  return { fps: (1000 * (f1 - f0)) / (t1 - t0), frames: f1 - f0, indices: i1 - i0, seconds: (t1 - t0) / 1000 };
}, ms);

test('the bundled clip plays at its own 25 frames per second, with and without a tracker', async () => {
  const rates = {};
  for (const tracker of ['', 'adachi-mmpf']) {
    const { page, errors } = await open(env.browser, `${env.base}/?tracker=${tracker}`);
    await running(page);
    // Without the particle overlay: copying 80 particles' polylines out of the module and to
    // the page takes some 30-70 ms a frame on this shared 2-core machine, more than the clip's
    // 40 ms (that case, slowed down and said so, is the next test's).
    if (tracker) await page.uncheck('#show-particles');
    await page.waitForFunction(() => window.lanepfDemo.frames > 10, null, { timeout: 30000 });
    // 4 s of the 12 s clip: some 100 frames.
    const r = await measureRate(page, 4000);
    rates[tracker || 'none'] = r;
    assert.ok(Math.abs(r.fps - 25) < 2.5, `${tracker || 'no tracker'}: ${r.fps.toFixed(1)} frames/s, not 25 ± 10 %: ${JSON.stringify(rates)}`);
    const pace = await page.evaluate(() => ({ text: document.getElementById('pace').textContent, ...window.lanepfDemo.pace }));
    rates[tracker || 'none'].pace = pace;
    assert.equal(r.indices, r.frames, 'every frame presented, none skipped');
    assert.match(pace.text, /^Playing at \d+\.\d frames\/s: the video’s rate is 25$/);
    assert.equal(pace.behind, false);
    assert.deepEqual(errors, []);
    await page.close();
  }
  console.log(`playback: ${JSON.stringify(rates)}`);
});

test('a tracker that cannot keep up slows playback down, and the page says so', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?tracker=liu-ppf`);
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.frames > 3, null, { timeout: 30000 });
  // liu-ppf with 2000 particles: ten times its default, far more than a frame's 40 ms.
  await page.evaluate(() => {
    const input = document.querySelector('#params input[name="particles"]');
    input.value = '2000';
    input.dispatchEvent(new Event('change', { bubbles: true }));
  });
  // (The tracker is rebuilt: the frame count starts again and the pacer forgets its rate.)
  await page.waitForFunction(() => document.querySelector('#params input[name="particles"]').value === '2000'
    && window.lanepfDemo.pending <= 1 && window.lanepfDemo.frames < 3, null, { timeout: 30000 });
  await page.waitForFunction(() => window.lanepfDemo.frames >= 5 && window.lanepfDemo.pace?.behind === true,
    null, { timeout: 30000 });
  const r = await measureRate(page, 3000);
  const pace = await page.evaluate(() => ({ text: document.getElementById('pace').textContent, ...window.lanepfDemo.pace }));
  console.log(`slow tracker: ${JSON.stringify({ ...r, pace })}`);
  assert.ok(r.fps < 0.9 * 25, `slower than the clip: ${r.fps.toFixed(1)} frames/s`);
  assert.equal(r.indices, r.frames, 'slowed down, every frame still tracked');
  // The page says how fast it plays, within 15 % of what was measured, and why.
  const m = pace.text.match(/^Slowed down to (\d+\.\d) frames\/s, (\d\.\d\d)× the video’s 25: a frame takes (\d+) ms here, the video shows one every 40 ms/);
  assert.ok(m, `the page says it is slower: ${pace.text}`);
  assert.ok(Math.abs(Number(m[1]) - r.fps) < 0.15 * r.fps, `stated ${m[1]} vs measured ${r.fps.toFixed(1)} frames/s`);
  assert.ok(Number(m[3]) > 40, `a frame takes more than 40 ms: ${m[3]}`);
  assert.equal(await page.evaluate(() => document.getElementById('pace').classList.contains('warn')), true);
  assert.deepEqual(errors, []);
  await page.close();
});

test('compare mode: the two views side by side at 1280 px and stacked on a phone, each named, plots for both', async () => {
  for (const viewport of [LAPTOP, PHONE]) {
    const { page, errors } = await open(env.browser,
      `${env.base}/?source=highway-straight&tracker=lee-cpf&compare=adachi-mmpf`, { viewport });
    await running(page);
    await page.waitForFunction(() => window.lanepfDemo.lastCompare && window.lanepfDemo.results.length >= 10,
      null, { timeout: 30000 });
    await page.click('#play');
    await idle(page);
    const [a, b] = [await box(page, '#view'), await box(page, '#view2')];
    const where = JSON.stringify({ view: round(a), view2: round(b) });
    if (viewport === LAPTOP) {
      assert.ok(Math.abs(a.y - b.y) <= 1 && b.x >= a.right, `side by side: ${where}`);
      assert.ok(b.right <= viewport.width, `both in the screen's width: ${where}`);
      assert.ok(b.bottom <= viewport.height, `both in the first screen: ${where}`);
    } else {
      assert.ok(b.y >= a.bottom && Math.abs(a.x - b.x) <= 1, `stacked: ${where}`);
    }
    console.log(`compare at ${viewport.width}x${viewport.height}: ${where}`);
    // Each view names its tracker, on the view.
    assert.equal(await page.textContent('#view-name'), 'lee-cpf');
    assert.equal(await page.textContent('#compare-name'), 'adachi-mmpf');
    assert.equal(await page.isVisible('#view-name'), true);
    assert.equal(await page.isVisible('#compare-name'), true);
    // The plots carry both: the caption names them, the canvas has the second one's colour.
    assert.match(await page.textContent('#plots-caption'), /^lee-cpf’s estimate \(blue\), adachi-mmpf’s \(pink\)/);
    const pink = await page.evaluate(async () => (await import('/plots.js')).COMPARE_COLOUR);
    const rgb = [1, 3, 5].map((i) => parseInt(pink.slice(i, i + 2), 16));
    const n = countNear(await readCanvas(page, 'plots'), rgb, 10);
    assert.ok(n > 50, `the second tracker's lines on the plots (${n} px)`);
    await page.screenshot({ path: `test-results/compare-${viewport.width}x${viewport.height}.png` });
    assert.deepEqual(errors, []);
    await page.close();
  }
});

test('after stepping one tracker and switching, the status line no longer shows its step', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  await page.waitForFunction(() => window.lanepfDemo.frames > 2, null, { timeout: 30000 });
  await page.click('#play');
  await idle(page);
  for (let k = 0; k < 3; k++) {
    await page.click('#step-stage');
    await idle(page);
  }
  assert.match(await page.textContent('#status'), /^lee-cpf: ran “/);
  // (The switch is queued as the menu changes; idle: it has run.)
  await page.selectOption('#tracker', 'adachi-mmpf');
  await idle(page);
  const status = await page.textContent('#status');
  assert.doesNotMatch(status, /lee-cpf|ran “/, `status after the switch: ${status}`);
  assert.equal(await page.textContent('#view-name'), 'adachi-mmpf');
  assert.match(status, /highway-straight.*tracking with adachi-mmpf/);
  assert.match(await page.textContent('#next-stage'), /^next: start of a frame/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('liu-ppf-nokernel\'s cue names only what it weighs by, and is not saturated', async () => {
  const layers = {};
  for (const id of ['liu-ppf-nokernel', 'liu-ppf']) {
    const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=${id}`);
    await running(page);
    await page.check('#show-cues');
    await page.waitForFunction(() => window.lanepfDemo.lastLayer && window.lanepfDemo.frames > 5, null, { timeout: 30000 });
    await page.click('#play');
    await idle(page);
    layers[id] = await page.evaluate(() => {
      const { values, name } = window.lanepfDemo.lastLayer;
      const on = values.filter((v) => v > 0);
      const c = document.getElementById('cues');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let lit = 0;
      let white = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] + d[i + 1] + d[i + 2] > 0) lit++;
        if (d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250) white++;
      }
      return {
        name, caption: document.getElementById('cues-caption').textContent, pixels: on.length,
        atTop: on.filter((v) => v >= 0.999).length / on.length, whiteShare: white / lit,
      };
    });
    assert.deepEqual(errors, []);
    await page.close();
  }
  console.log(`cue layers: ${JSON.stringify(layers)}`);
  const [n, k] = [layers['liu-ppf-nokernel'], layers['liu-ppf']];
  assert.equal(n.caption, n.name);
  assert.doesNotMatch(n.caption, /orientation kernel weight|intensity and orientation/);
  assert.match(n.caption, /^measurement pixels: intensity kernel K_c alone/);
  assert.ok(n.pixels > 1000, 'it has measurement pixels');
  // Not saturated: most pixels below the top of the scale, few drawn white.
  assert.ok(n.atTop < 0.2, `share of nokernel's pixels at the top of the scale: ${n.atTop}`);
  assert.ok(n.whiteShare < 0.1, `share drawn white: ${n.whiteShare}`);
  // liu-ppf's own stays as it was.
  assert.equal(k.caption, 'measurement pixels: intensity and orientation kernel weight');
});
