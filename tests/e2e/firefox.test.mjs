// End-to-end in Firefox (Debian's firefox-esr, headless, over WebDriver BiDi; see firefox.mjs):
// the Chromium suites' checks of the paths where browsers differ, with the same thresholds and
// no page errors. The bundled clip tracked and drawn; the test road under its ground truth;
// every tracker on a synthetic scene within 0.3 m; an uploaded video read with WebCodecs
// to its end, undecodable files explained; an image sequence with an imported camera; the
// webcam (Firefox's fake camera); the calibration helper's drag; bench.html; and a clock finer
// than whole milliseconds; the keyboard (play, pause, step a frame, step a stage). Not run in
// Firefox, only in Chromium (the other suites): the per-step mode stage by stage, the
// comparison view, export (downloads), the teaching panel, stereo input and a refused camera
// permission.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startFirefox, openFirefox } from './firefox.mjs';
import { readCanvas, lum, peak, countColour, countNear } from './pixels.mjs';

const CLIP = fileURLToPath(new URL('../../www/clips/udacity-project-640x360.webm', import.meta.url));
const env = await startFirefox();
// Files handed to the page's file inputs (WebDriver BiDi sets inputs from paths on disk).
const files = mkdtempSync(join(tmpdir(), 'lanepf-firefox-'));
test.after(async () => {
  await env.close();
  rmSync(files, { recursive: true, force: true });
});
mkdirSync('test-results', { recursive: true });

const running = (page) => page.waitForFunction(() => document.body.dataset.state === 'running',
  { timeout: 30000 });
const framesAtLeast = (page, n, timeout = 30000) => page.waitForFunction(
  (n) => window.lanepfDemo.frames >= n, { timeout }, n,
);
const text = (page, selector) => page.$eval(selector, (e) => e.textContent);
const visible = (page, selector) => page.$eval(selector, (e) => e.checkVisibility());
/** Sets checkbox `selector` to `on` with a click, as a person would. */
const setChecked = async (page, selector, on) => {
  if (await page.$eval(selector, (e) => e.checked) !== on) await page.click(selector);
};

test('Firefox: the page opens on the bundled Udacity clip and draws the tracked lane on it', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/`);
  await running(page);
  assert.match(await text(page, '#version'), /^lanepf \d+\.\d+\.\d+/);
  assert.match(await text(page, '#status'), /Udacity project_video\.mp4.*640x360.*25 frames\/s/);
  await framesAtLeast(page, 40);
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.lastRgba?.length > 0);
  // (As one JSON string: see readCanvas.)
  const { estimate, rgba } = JSON.parse(await page.evaluate(() => JSON.stringify({
    estimate: window.lanepfDemo.lastEstimate, rgba: Array.from(window.lanepfDemo.lastRgba),
  })));
  assert.equal(estimate.valid, true);
  const frame = { width: 640, height: 360, data: rgba };
  // Firefox decoded the VP9 clip into real pixels: blue sky at the top of the frame.
  const sky = 4 * (20 * 640 + 320);
  assert.ok(rgba[sky + 2] > rgba[sky] + 20, 'blue sky at the top of the frame');
  // The estimated ego-left boundary lies on painted line near the car: on most rows of the
  // lower image, brighter within 4 px of it than at the lane's centre.
  const left = estimate.boundaries.find((b) => b.role === 'ego-left').points;
  const right = estimate.boundaries.find((b) => b.role === 'ego-right').points;
  const rows = left.filter(([, y]) => y > 250 && y < 340);
  assert.ok(rows.length >= 5, `${rows.length} rows of the left boundary near the car`);
  let onPaint = 0;
  for (const [x, y] of rows) {
    const xr = right.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a))[0];
    if (peak(frame, x, y, 4) > lum(frame, (x + xr) / 2, y) + 30) onPaint++;
  }
  assert.ok(onPaint / rows.length > 0.8, `left boundary on paint on ${onPaint} of ${rows.length} rows`);
  // The canvas shows it: the ego-left colour, the particles, the top view and the plots.
  const canvas = await readCanvas(page);
  assert.equal(canvas.width, 640);
  assert.ok(countColour(canvas, [0xff, 0xd5, 0x4f]) > 200, 'ego-left overlay on the canvas');
  const cloud = await page.evaluate(() => window.lanepfDemo.lastHypotheses);
  assert.ok(cloud.length > 10 && cloud.every((h) => h.boundaries.length >= 1), 'particles drawn');
  assert.equal(await visible(page, '#top'), true, 'the top view is shown');
  const plots = await readCanvas(page, 'plots');
  assert.ok(countNear(plots, [0x4f, 0xc3, 0xf7], 40) > 300, 'the plots draw the estimate over time');
  assert.match(await text(page, '#timing'), /track \d+\.\d ms/);
  await page.screenshot({ path: 'test-results/firefox-clip.png', fullPage: true });
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: the test road is drawn with markings where the ground truth says', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=test-road&tracker=`);
  await running(page);
  await framesAtLeast(page, 3);
  // Freeze the stream, hide the overlay and draw one clean frame.
  await page.click('#play');
  await setChecked(page, '#show-truth', false);
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, {}, before);
  const truth = await page.evaluate(() => window.lanepfDemo.lastTruth);
  const img = await readCanvas(page);
  assert.equal(img.width, 640);
  assert.equal(img.height, 480);
  const left = truth.boundaries.find((b) => b.role === 'ego-left');
  const right = truth.boundaries.find((b) => b.role === 'ego-right');
  assert.ok(left && right && left.points.length >= 10, 'ground truth has both ego boundaries');
  // Solid left marking bright along its near polyline, dashed right one along part of it,
  // dark asphalt between them.
  const near = (pts) => pts.filter(([, y]) => y > 200);
  const hit = (pts) => near(pts).filter(([x, y]) => peak(img, x, y, 3) > 150).length / near(pts).length;
  assert.ok(hit(left.points) > 0.9, `solid marking found on ${hit(left.points)} of the left polyline`);
  const dashed = hit(right.points);
  assert.ok(dashed > 0.05 && dashed < 0.6, `dashed marking found on ${dashed} of the right polyline`);
  for (let k = 0; k < near(left.points).length; k += 3) {
    const [xl, y] = near(left.points)[k];
    const xr = right.points.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a))[0];
    assert.ok(lum(img, (xl + xr) / 2, y) < 140, `lane centre at row ${y} is asphalt`);
  }
  // With the overlay on, the ground truth's role colours are drawn.
  await setChecked(page, '#show-truth', true);
  const n2 = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#step');
  await page.waitForFunction((n) => window.lanepfDemo.frames > n, {}, n2);
  const yellow = countColour(await readCanvas(page), [0xff, 0xd5, 0x4f]);
  assert.ok(yellow > 100, `ego-left overlay drawn (${yellow} px)`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: every tracker can be chosen and tracks a synthetic scene within 0.3 m', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=highway-straight&tracker=`);
  await running(page);
  const ids = (await page.$$eval('#tracker option', (os) => os.map((o) => o.value))).filter(Boolean);
  assert.deepEqual(ids, ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf', 'liu-ppf',
    'liu-ppf-nokernel']);
  const report = [];
  for (const id of ids) {
    await page.click('#play'); // pause while switching
    await page.click('#restart');
    await page.select('#tracker', id);
    await page.click('#play');
    await page.waitForFunction(() => window.lanepfDemo.offsetErrors.length >= 30, { timeout: 60000 });
    const errs = await page.evaluate(() => window.lanepfDemo.offsetErrors.slice(20, 30));
    const mean = errs.reduce((a, b) => a + b, 0) / errs.length;
    report.push(`${id} ${mean.toFixed(3)}`);
    assert.ok(mean < 0.3, `${id}: mean offset error ${mean.toFixed(3)} m over frames 20-29`);
    assert.match(await text(page, '#timing'), /track \d+\.\d ms · offset error \d+ cm/);
  }
  console.log(`Firefox, mean |offset error| frames 20-29: ${report.join(', ')}`);
  // Firefox rounds performance.now() to whole milliseconds unless the page is cross-origin
  // isolated (scripts/serve.mjs sends COOP/COEP); then the ms/frame readings are finer.
  const { isolated, ms } = await page.evaluate(() => ({
    isolated: window.crossOriginIsolated, ms: window.lanepfDemo.results.map((r) => r.ms),
  }));
  assert.equal(isolated, true, 'the demo page is cross-origin isolated');
  assert.ok(ms.filter((t) => !Number.isInteger(t)).length > ms.length / 2,
    `tracker times finer than whole milliseconds: ${ms.slice(0, 10).join(', ')}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: an uploaded video is read with WebCodecs to its end; an undecodable file is explained', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`);
  await running(page);
  const input = await page.$('#file');
  await input.uploadFile(CLIP);
  await page.waitForFunction(() => /Video “udacity-project-640x360\.webm”/.test(
    document.getElementById('status').textContent), { timeout: 30000 });
  // Firefox ESR has WebCodecs: frame count and rate come from the container, as in Chromium.
  assert.match(await text(page, '#status'), /300 frames at 25 frames\/s, decoded with WebCodecs/);
  await page.waitForFunction(() => window.lanepfDemo.frames > 30, { timeout: 30000 });
  const midway = await page.$eval('#progress', (e) => e.value);
  assert.ok(midway > 0.05 && midway < 0.95, `progress ${midway} while running`);
  // Every frame is read: 12 s at 25 frames/s, none skipped or repeated.
  await page.waitForFunction(() => window.lanepfDemo.ended, { timeout: 120000 });
  const names = await page.evaluate(() => window.lanepfDemo.results.map((r) => r.frame));
  assert.deepEqual(names, Array.from({ length: 300 }, (_, k) => `${k}`));
  assert.match(await text(page, '#status'), /End of .* 300 frames tracked/);

  writeFileSync(join(files, 'holiday.mp4'), 'this is a text file, not a video\n');
  await input.uploadFile(join(files, 'holiday.mp4'));
  await page.waitForFunction(() => document.body.dataset.state === 'error', { timeout: 30000 });
  assert.match(await text(page, '#status'), /Cannot open “holiday\.mp4”: .*Try an H\.264 MP4 or a VP9 WebM/);
  writeFileSync(join(files, 'broken.png'), 'nope');
  await input.uploadFile(join(files, 'broken.png'));
  await page.waitForFunction(() => /broken\.png/.test(document.getElementById('status').textContent));
  assert.match(await text(page, '#status'), /Cannot decode “broken\.png”/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: still images made in the page are tracked as a sequence with an imported camera', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=test-road&tracker=lee-cpf`);
  await running(page);
  // Eight frames of a scene as PNG files (OffscreenCanvas.convertToBlob in Firefox), and the
  // scene's camera as a camera.json.
  const { pngs, camera, truth } = await page.evaluate(async () => {
    const m = await import('/pkg/web/lanepf.js');
    await m.default();
    const scene = new m.Scene('highway-straight', { width: 640, height: 480, seed: 3 });
    const canvas = new OffscreenCanvas(640, 480);
    const pngs = [];
    for (let f = 0; f < 8; f++) {
      canvas.getContext('2d').putImageData(new ImageData(scene.render(f), 640, 480), 0, 0);
      const bytes = new Uint8Array(await (await canvas.convertToBlob({ type: 'image/png' })).arrayBuffer());
      let s = '';
      for (const b of bytes) s += String.fromCharCode(b);
      pngs.push(btoa(s));
    }
    return { pngs, camera: scene.camera(), truth: scene.truth(7).lateral_offset_m };
  });
  writeFileSync(join(files, 'sim.camera.json'), JSON.stringify(camera));
  await (await page.$('#camera-file')).uploadFile(join(files, 'sim.camera.json'));
  await page.waitForFunction(() => /Camera “sim\.camera\.json”/.test(document.getElementById('status').textContent));
  const paths = pngs.map((b64, f) => {
    const path = join(files, `frame-${f}.png`);
    writeFileSync(path, Buffer.from(b64, 'base64'));
    return path;
  });
  // Names sort numerically whatever order they come in.
  await (await page.$('#file')).uploadFile(...paths.reverse());
  await page.waitForFunction(() => window.lanepfDemo.ended, { timeout: 30000 });
  const results = await page.evaluate(() => window.lanepfDemo.results);
  assert.deepEqual(results.map((r) => r.frame), pngs.map((_, f) => `frame-${f}.png`));
  const last = results.at(-1);
  assert.ok(Math.abs(last.lateral_offset_m - truth) < 0.3,
    `offset ${last.lateral_offset_m} vs truth ${truth} after 8 images`);
  assert.match(await text(page, '#status'), /End of 8 images/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: the webcam path runs on Firefox\'s fake camera', async () => {
  // (media.navigator.streams.fake in firefox.mjs: a moving test picture, no permission prompt.)
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=webcam&tracker=lee-cpf`);
  await running(page);
  await framesAtLeast(page, 5);
  assert.match(await text(page, '#status'), /^Webcam .*: 640x480/);
  const img = await readCanvas(page);
  const values = new Set();
  for (let y = 0; y < img.height; y += 40) for (let x = 0; x < img.width; x += 40) values.add(Math.round(lum(img, x, y)));
  assert.ok(values.size > 3, 'the fake camera\'s picture is drawn');
  assert.equal(await visible(page, '#progress'), false, 'a live source has no progress bar');
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: dragging the calibration helper\'s lines gives the scene camera\'s pose', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=highway-straight&tracker=`);
  await running(page);
  await framesAtLeast(page, 2);
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const { truth, camera } = await page.evaluate(async () => {
    const m = await import('/pkg/web/lanepf.js');
    await m.default();
    const scene = new m.Scene('highway-straight', { width: 640, height: 480, seed: 1 });
    return { truth: window.lanepfDemo.lastTruth, camera: scene.camera() };
  });
  const fields = () => page.evaluate(() => Object.fromEntries(
    [...document.querySelectorAll('#camera-fields input')].map((i) => [i.name, Number(i.value)]),
  ));
  await page.click('#calibration summary');
  await setChecked(page, '#vp-helper', true);
  const at = (role, y) => {
    const pts = truth.boundaries.find((b) => b.role === role).points;
    return pts.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a));
  };
  const starts = [[0.3 * 640, 0.95 * 480], [0.46 * 640, 0.65 * 480], [0.7 * 640, 0.95 * 480], [0.54 * 640, 0.65 * 480]];
  const targets = [at('ego-left', 440), at('ego-left', 330), at('ego-right', 440), at('ego-right', 330)];
  const view = await page.$('#view');
  for (let k = 0; k < 4; k++) {
    await view.scrollIntoView();
    const box = await view.boundingBox();
    const sx = box.width / 640;
    const sy = box.height / 480;
    await page.mouse.move(box.x + starts[k][0] * sx, box.y + starts[k][1] * sy);
    await page.mouse.down();
    await page.mouse.move(box.x + targets[k][0] * sx, box.y + targets[k][1] * sy, { steps: 4 });
    await page.mouse.up();
    await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  }
  const got = await fields();
  const psiDeg = (truth.heading_rad * 180) / Math.PI;
  const pitchTruth = (truth.state['danescu.alpha'] * 180) / Math.PI;
  assert.ok(Math.abs(got.pitch_deg - pitchTruth) < 0.5, `pitch ${got.pitch_deg} vs ${pitchTruth}`);
  assert.ok(Math.abs(got.yaw_deg - (camera.yaw_deg - psiDeg)) < 0.5, `yaw ${got.yaw_deg}`);
  assert.ok(Math.abs(got.height_m / camera.height_m - 1) < 0.1, `height ${got.height_m}`);
  assert.match(await text(page, '#status'), /Camera applied: pitch/);
  // Remembered for this source (localStorage): a reload uses it.
  await page.reload();
  await running(page);
  assert.match(await text(page, '#status'), /as you calibrated it for this source/);
  assert.equal((await fields()).pitch_deg, +got.pitch_deg.toFixed(4));
  assert.deepEqual(errors, []);
  await page.close();
});

test('Firefox: bench.html times every tracker in a worker, finer than whole milliseconds', async () => {
  const { page, errors } = await openFirefox(env.browser, 'about:blank');
  const requests = [];
  page.on('request', (r) => requests.push(r.url()));
  await page.goto(`${env.base}/bench.html?frames=8&width=320&height=240`);
  await page.waitForFunction(() => window.lanepfBench?.done, { timeout: 110_000 });
  const bench = await page.evaluate(() => window.lanepfBench);
  assert.equal(bench.error, undefined, bench.error);
  const ids = ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf', 'liu-ppf', 'liu-ppf-nokernel'];
  assert.deepEqual(bench.rows.map((r) => r.tracker), ids);
  for (const r of bench.rows) {
    assert.ok(Number.isFinite(r.median_ms) && r.median_ms > 0, `${r.tracker}: median ${r.median_ms}`);
    assert.ok(Number.isFinite(r.p95_ms) && r.p95_ms >= r.median_ms, `${r.tracker}: p95 ${r.p95_ms}`);
    assert.equal(r.frames, 3, `${r.tracker}: 8 frames, the first 5 untimed`);
  }
  // Sub-millisecond trackers at this size read as 0 or 1 ms on a whole-millisecond clock.
  assert.ok(bench.rows.some((r) => !Number.isInteger(r.median_ms)),
    `medians ${bench.rows.map((r) => r.median_ms).join(', ')} are not all whole milliseconds`);
  assert.deepEqual(errors, []);
  const foreign = requests.filter((u) => !u.startsWith(env.base) && !u.startsWith('data:') && u !== 'about:blank');
  assert.ok(requests.some((u) => u.endsWith('/pkg/web/lanepf_bg.wasm')), 'requests are seen');
  assert.deepEqual(foreign, [], 'no requests beyond the page\'s own files');
  await page.close();
});

test('Firefox: the keyboard plays, pauses, steps a frame and steps a stage', async () => {
  const { page, errors } = await openFirefox(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  await page.mouse.click(5, 5);
  await page.keyboard.press(' ');
  assert.equal(await text(page, '#play'), 'Play', 'space pauses');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const n = await page.evaluate(() => window.lanepfDemo.results.length);
  await page.keyboard.press('.');
  await page.waitForFunction((n) => window.lanepfDemo.results.length === n + 1, {}, n);
  await page.keyboard.press(',');
  await page.waitForFunction(() => !/start of a frame/.test(document.getElementById('next-stage').textContent));
  await page.keyboard.press(' ');
  assert.equal(await text(page, '#play'), 'Pause', 'space plays again');
  await page.waitForFunction((n) => window.lanepfDemo.results.length >= n + 4, {}, n);
  assert.deepEqual(errors, []);
  await page.close();
});
