// End-to-end: videos decoded with WebCodecs in Chromium (www/webcodecs-source.js). The reader
// on its own (every frame once, in presentation order, with the container's timestamps, each
// VideoFrame closed, restart, side-by-side stereo); uploads of a VP9 WebM, an H.264 MP4 and a
// MediaRecorder recording run to their end in the demo with a progress bar; an HEVC MP4, whose
// container parses but whose codec this Chromium cannot decode, is explained.
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, rmSync, writeFileSync } from 'node:fs';
import { start, open, running, idle } from './browser.mjs';
import { makeVideos, countFrames, FRAMES, RAMP_STEP } from '../node/video-fixtures.mjs';

const env = await start();
const ramp = makeVideos(['vp9.webm', 'h264.mp4', 'h264.mkv'], { size: '320x240', ramp: true });
const other = makeVideos(['hevc.mp4'], { size: '320x240' });
const stereo = makeVideos(['vp9.webm'], { size: '640x240' });
test.after(async () => {
  await env.close();
  for (const v of [ramp, other, stereo]) rmSync(v.dir, { recursive: true, force: true });
});

const status = (page) => page.textContent('#status');

/**
 * Reads a whole video with WebCodecsVideoSource in the page, then five frames after a restart.
 * The decoders' output frames and close() calls are counted. Per frame: index, name, t, the centre pixel's grey, size, the share of the right frame's
 * bytes that differ from the left (null without one), progress.
 */
async function readInPage(page, path, options = {}) {
  return page.evaluate(async ({ b64, name, options }) => {
    const { WebCodecsVideoSource } = await import('/webcodecs-source.js');
    // Count the decoders' output frames and the close() calls on frames.
    const [Decoder, close] = [window.VideoDecoder, VideoFrame.prototype.close];
    let [outputs, closed] = [0, 0];
    window.VideoDecoder = class extends Decoder {
      constructor(init) {
        super({ ...init, output: (f) => { outputs++; init.output(f); } });
      }
    };
    VideoFrame.prototype.close = function countedClose() {
      closed++;
      return close.call(this);
    };
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const source = new WebCodecsVideoSource({ blob: new Blob([bytes]), name, ...options });
    await source.open();
    const centre = (f) => f.rgba[4 * ((f.height >> 1) * f.width + (f.width >> 1))];
    const frames = [];
    for (let f = await source.next(); f; f = await source.next()) {
      frames.push({ index: f.index, name: f.name, t: f.t, grey: centre(f), width: f.width, height: f.height,
        right: f.right ? f.right.filter((v, k) => v !== f.rgba[k]).length / f.right.length : null,
        progress: source.progress });
    }
    // Restart: from the first frame again.
    source.restart();
    const again = [];
    for (let k = 0; k < 5; k++) again.push((await source.next()).index);
    source.close();
    window.VideoDecoder = Decoder;
    VideoFrame.prototype.close = close;
    return { frames, again, label: source.label, count: source.frames, fps: source.fps, outputs, closed };
  }, { b64: readFileSync(path).toString('base64'), name: path.split('/').at(-1), options });
}

test('the WebCodecs reader gives every frame once, in presentation order, with its timestamp', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=test-road&tracker=`);
  await running(page);
  for (const name of ['vp9.webm', 'h264.mp4', 'h264.mkv']) {
    const { frames, again, label, count, fps, outputs, closed } = await readInPage(page, ramp.path(name));
    assert.ok(outputs >= FRAMES + again.length, `${name}: ${outputs} frames decoded`);
    assert.equal(closed, outputs, `${name}: every VideoFrame closed`);
    assert.equal(count, FRAMES, name);
    assert.equal(fps, 25, name);
    assert.match(label, /320x240, 1\.5 s, 37 frames at 25 frames\/s, decoded with WebCodecs/);
    assert.deepEqual(frames.map((f) => f.index), Array.from({ length: FRAMES }, (_, k) => k), `${name}: indices`);
    assert.deepEqual(frames.map((f) => f.name), frames.map((f) => `${f.index}`));
    // H.264 here has B-frames: decode order differs, the frames still come out in order.
    assert.deepEqual(frames.map((f) => Math.round(f.t * 1e6)), frames.map((f) => f.index * 40000), `${name}: timestamps`);
    // Frame k of the ramp is grey 5.82 k: each frame is the one its index says.
    const off = frames.filter((f) => Math.abs(f.grey - f.index * RAMP_STEP) > 4);
    assert.deepEqual(off.map((f) => [f.index, f.grey]), [], `${name}: pixels of the frame named`);
    assert.ok(frames.every((f) => f.width === 320 && f.height === 240 && f.right === null));
    assert.deepEqual(frames.map((f) => f.progress), frames.map((_, k) => (k + 1) / FRAMES));
    assert.deepEqual(again, [0, 1, 2, 3, 4], `${name}: restart`);
  }
  // Side-by-side stereo: each half is a frame.
  const sbs = await readInPage(page, stereo.path('vp9.webm'), { sideBySide: true });
  assert.equal(sbs.frames.length, FRAMES);
  assert.ok(sbs.frames.every((f) => f.width === 320 && f.height === 240 && f.right !== null));
  assert.ok(sbs.frames.every((f) => f.right > 0.2), 'the right half is not the left');
  assert.match(sbs.label, /640x240, .*side-by-side stereo of 320x240/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('uploaded VP9 WebM and H.264 MP4 videos run to their end with WebCodecs and a progress bar', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=adachi-mmpf`);
  await running(page);
  for (const [name, codec] of [['vp9.webm', /vp09\.00\.\d\d\.08/], ['h264.mp4', /avc1\.64001e/]]) {
    // Paused first, so the progress can be read between steps.
    if ((await page.textContent('#play')) === 'Pause') await page.click('#play');
    await idle(page);
    await page.setInputFiles('#file', ramp.path(name));
    await page.waitForFunction((name) => document.getElementById('status').textContent.includes(`Video “${name}”`),
      name, { timeout: 30000 });
    const label = await status(page);
    assert.match(label, /320x240, 1\.5 s, 37 frames at 25 frames\/s, decoded with WebCodecs/);
    assert.match(label, codec);
    for (let k = 0; k < 5; k++) await page.click('#step');
    await idle(page);
    assert.equal(await page.isVisible('#progress'), true);
    assert.equal(await page.evaluate(() => document.getElementById('progress').value), 5 / FRAMES);
    assert.equal(await page.evaluate(() => window.lanepfDemo.lastFrame.name), '4');
    await page.click('#play');
    await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 60000 });
    const { names, progress } = await page.evaluate(() => ({
      names: window.lanepfDemo.results.map((r) => r.frame), progress: document.getElementById('progress').value,
    }));
    assert.deepEqual(names, Array.from({ length: FRAMES }, (_, k) => `${k}`), `${name}: every frame once, in order`);
    assert.equal(progress, 1);
    assert.match(await status(page), /End of .* 37 frames tracked/);
    // Restart runs it again from the first frame.
    await page.click('#restart');
    await page.click('#play');
    await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 60000 });
    assert.equal(await page.evaluate(() => window.lanepfDemo.results.length), FRAMES, `${name}: after restart`);
  }
  assert.deepEqual(errors, []);
  await page.close();
});

test('a MediaRecorder recording (WebM of unknown sizes) is read with WebCodecs to its end', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=test-road&tracker=adachi-mmpf`);
  await running(page);
  // Two seconds of a moving canvas, recorded as this browser records.
  const b64 = await page.evaluate(async () => {
    const canvas = document.createElement('canvas');
    [canvas.width, canvas.height] = [320, 240];
    const ctx = canvas.getContext('2d');
    const recorder = new MediaRecorder(canvas.captureStream(25), { mimeType: 'video/webm;codecs=vp9' });
    const parts = [];
    recorder.ondataavailable = (e) => parts.push(e.data);
    const stopped = new Promise((resolve) => { recorder.onstop = resolve; });
    recorder.start(500);
    const t0 = performance.now();
    while (performance.now() - t0 < 2000) {
      const x = (performance.now() - t0) / 10;
      ctx.fillStyle = '#333';
      ctx.fillRect(0, 0, 320, 240);
      ctx.fillStyle = '#eee';
      ctx.fillRect(x, 100, 40, 40);
      await new Promise((r) => setTimeout(r, 40));
    }
    recorder.stop();
    await stopped;
    const bytes = new Uint8Array(await new Blob(parts).arrayBuffer());
    let s = '';
    for (const b of bytes) s += String.fromCharCode(b);
    return btoa(s);
  });
  const path = `${other.dir}/recording.webm`;
  writeFileSync(path, Buffer.from(b64, 'base64'));
  const frames = countFrames(path);
  assert.ok(frames > 10, `${frames} frames recorded`);
  await page.setInputFiles('#file', path);
  await page.waitForFunction(() => /Video “recording\.webm”/.test(document.getElementById('status').textContent),
    null, { timeout: 30000 });
  assert.match(await status(page), new RegExp(`${frames} frames at .* decoded with WebCodecs \\(vp09`));
  await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 60000 });
  const names = await page.evaluate(() => window.lanepfDemo.results.map((r) => r.frame));
  assert.deepEqual(names, Array.from({ length: frames }, (_, k) => `${k}`));
  assert.deepEqual(errors, []);
  await page.close();
});

test('an MP4 whose codec this Chromium cannot decode (HEVC) is explained, and the page keeps working', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  await page.setInputFiles('#file', other.path('hevc.mp4'));
  await page.waitForFunction(() => /hevc\.mp4/.test(document.getElementById('status').textContent), null, { timeout: 30000 });
  await idle(page);
  const text = await status(page);
  // WebCodecs says no; the <video> element is tried next and (in Debian's Chromium) fails too.
  assert.match(text, /[Nn]ot WebCodecs: this browser's VideoDecoder does not decode hvc1\.1\.6\.L\d+\.90/);
  if (await page.evaluate(() => document.body.dataset.state === 'error')) {
    assert.match(text, /Cannot open “hevc\.mp4”: .*Try an H\.264 MP4 or a VP9 WebM/);
    // The scene is still the source; playing goes on.
    const before = await page.evaluate(() => window.lanepfDemo.frames);
    await page.click('#play');
    await page.waitForFunction((n) => window.lanepfDemo.frames > n + 3, before);
    assert.match(await status(page), /highway-straight/);
  } else {
    assert.match(text, /by seeking a <video> element/);
  }
  assert.deepEqual(errors, []);
  await page.close();
});
