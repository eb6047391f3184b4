// End-to-end: the demo's frame sources. The bundled clip's file, an uploaded video run
// to its end by seeking (without WebCodecs; webcodecs.test.mjs has the WebCodecs path),
// uploaded still images with an imported camera file, a file the browser cannot decode, and
// the webcam (Chromium's fake camera). The clip playing and stereo input are checked in every
// browser by cross-browser.test.mjs.
import test from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { start, open, running } from './browser.mjs';
import { readCanvas, lum } from './pixels.mjs';

const CLIP = fileURLToPath(new URL('../../www/clips/udacity-project-640x360.webm', import.meta.url));
const env = await start(['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream']);
test.after(() => env.close());
mkdirSync('test-results', { recursive: true });

const framesAtLeast = (page, n, timeout = 30000) => page.waitForFunction(
  (n) => window.lanepfDemo.frames >= n, n, { timeout },
);
const status = (page) => page.textContent('#status');

// The page opening on the clip and tracking it is checked in every browser by
// cross-browser.test.mjs; here, what the file itself must be.
test('the bundled clip is well under 5 MB and its licence notice lies beside it', () => {
  assert.ok(statSync(CLIP).size < 5e6, `the bundled clip is ${statSync(CLIP).size} bytes`);
  const licence = readFileSync(CLIP.replace(/udacity-project-640x360\.webm$/, 'LICENSE.udacity-project-640x360.txt'), 'utf8');
  assert.match(licence, /MIT License/);
  assert.match(licence, /Udacity/);
});

test('without WebCodecs, an uploaded video is read by seeking, frame by frame to its end with a progress bar', async () => {
  // A browser without VideoDecoder (webcodecs.test.mjs covers the WebCodecs path).
  const page = await env.browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
  await page.addInitScript(() => { delete window.VideoDecoder; });
  await page.goto(`${env.base}/?source=highway-straight&tracker=adachi-mmpf`);
  await running(page);
  await page.setInputFiles('#file', CLIP);
  await page.waitForFunction(() => /Video “udacity-project-640x360\.webm”/.test(
    document.getElementById('status').textContent), null, { timeout: 30000 });
  // The rate is measured from the video (25 frames/s), so every frame is read once.
  assert.match(await status(page), /read at 25 frames\/s \(measured\), by seeking a <video> element \(not WebCodecs: this browser has no WebCodecs VideoDecoder\)/);
  assert.match(await status(page), /camera assumed/);
  await page.waitForFunction(() => window.lanepfDemo.frames > 30, null, { timeout: 30000 });
  const midway = await page.evaluate(() => document.getElementById('progress').value);
  assert.equal(await page.isVisible('#progress'), true);
  assert.ok(midway > 0.05 && midway < 0.95, `progress ${midway} while running`);
  await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 120000 });
  const { results, progress } = await page.evaluate(() => ({
    results: window.lanepfDemo.results.length,
    progress: document.getElementById('progress').value,
  }));
  assert.equal(results, 300, '12 s at 25 frames/s');
  assert.equal(progress, 1);
  assert.match(await status(page), /End of .* 300 frames tracked/);
  assert.equal(await page.textContent('#play'), 'Play');
  assert.deepEqual(errors, []);
  await page.close();
});

test('still images with an imported camera file are tracked as a sequence', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=test-road&tracker=lee-cpf`);
  await running(page);
  // Five frames of a simulator scene as PNG files, and the scene's camera as a camera.json.
  const { pngs, camera, truth } = await page.evaluate(async () => {
    const m = await import('/pkg/sim/lanepf_sim.js');
    await m.default();
    const scene = new m.Scene('highway-straight', { width: 640, height: 480, seed: 3 });
    const canvas = new OffscreenCanvas(640, 480);
    const pngs = [];
    for (let f = 0; f < 8; f++) {
      canvas.getContext('2d').putImageData(new ImageData(scene.render(f), 640, 480), 0, 0);
      const blob = await canvas.convertToBlob({ type: 'image/png' });
      const bytes = new Uint8Array(await blob.arrayBuffer());
      let s = '';
      for (const b of bytes) s += String.fromCharCode(b);
      pngs.push(btoa(s));
    }
    return { pngs, camera: scene.camera(), truth: scene.truth(7).lateral_offset_m };
  });
  await page.setInputFiles('#camera-file', {
    name: 'sim.camera.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(camera)),
  });
  await page.waitForFunction(() => /Camera “sim\.camera\.json”/.test(document.getElementById('status').textContent));
  // Names sort numerically: frame-10 would come after frame-9.
  await page.setInputFiles('#file', pngs.map((b64, f) => ({
    name: `frame-${f}.png`, mimeType: 'image/png', buffer: Buffer.from(b64, 'base64'),
  })).reverse());
  await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 30000 });
  const { results } = await page.evaluate(() => ({ results: window.lanepfDemo.results }));
  assert.deepEqual(results.map((r) => r.frame), pngs.map((_, f) => `frame-${f}.png`));
  const last = results.at(-1);
  assert.ok(Math.abs(last.lateral_offset_m - truth) < 0.3,
    `offset ${last.lateral_offset_m} vs truth ${truth} after 8 images`);
  assert.match(await status(page), /End of 8 images/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a file the browser cannot decode gives a message and the page keeps working', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  await framesAtLeast(page, 2);
  await page.setInputFiles('#file', {
    name: 'holiday.mp4', mimeType: 'video/mp4', buffer: Buffer.from('this is a text file, not a video\n'),
  });
  await page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 30000 });
  assert.match(await status(page), /Cannot open “holiday\.mp4”: .*Try an H\.264 MP4 or a VP9 WebM/);
  // A broken image in a set is reported by name too.
  await page.setInputFiles('#file', { name: 'broken.png', mimeType: 'image/png', buffer: Buffer.from('nope') });
  await page.waitForFunction(() => /broken\.png/.test(document.getElementById('status').textContent));
  assert.match(await status(page), /Cannot decode “broken\.png”/);
  // The scene is still the source; playing goes on from where it stopped.
  const before = await page.evaluate(() => window.lanepfDemo.frames);
  await page.click('#play');
  await framesAtLeast(page, before + 5);
  assert.equal(await page.evaluate(() => document.body.dataset.state), 'running');
  assert.match(await status(page), /highway-straight/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the webcam path runs on Chromium\'s fake camera, and a refusal is explained', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=webcam&tracker=lee-cpf`);
  await running(page);
  await framesAtLeast(page, 5);
  assert.match(await status(page), /^Webcam .*: 640x480/);
  const img = await readCanvas(page);
  const values = new Set();
  for (let y = 0; y < img.height; y += 40) for (let x = 0; x < img.width; x += 40) values.add(Math.round(lum(img, x, y)));
  assert.ok(values.size > 3, 'the fake camera\'s picture is drawn');
  assert.equal(await page.isVisible('#progress'), false, 'a live source has no progress bar');
  assert.deepEqual(errors, []);
  await page.close();

  // A refusal (this browser's fake UI always grants, so the refusal is what getUserMedia
  // rejects with when a person clicks "Block").
  const denied = await env.browser.newContext();
  const p2 = await denied.newPage();
  await p2.addInitScript(() => {
    navigator.mediaDevices.getUserMedia = () => Promise.reject(new DOMException('denied', 'NotAllowedError'));
  });
  await p2.goto(`${env.base}/?source=test-road&tracker=`);
  await running(p2);
  await p2.selectOption('#source', 'webcam');
  await p2.waitForFunction(() => document.body.dataset.state === 'error');
  assert.match(await p2.textContent('#status'), /Camera permission was refused/);
  // The test road is still drawn.
  const n = await p2.evaluate(() => window.lanepfDemo.frames);
  await p2.click('#play');
  await p2.waitForFunction((n) => window.lanepfDemo.frames > n + 2, n);
  await denied.close();
});
