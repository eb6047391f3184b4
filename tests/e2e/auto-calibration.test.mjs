// End-to-end: camera auto-calibration in the demo (www/auto-calibration.js, the worker's wasm
// Calibrator). A video with no camera file is made at test time: the simulator's
// highway-straight (the wasm package's Scene, in Node) seen through a camera whose pose we know,
// encoded with ffmpeg. Uploaded, it must start with the assumed camera, show the calibrator's
// progress, then hand the tracker the estimated camera (within 0.5 degrees and 10 % of the
// truth), track with it, and let a camera chosen by hand win until auto-calibration is ticked
// again.
import test from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { start, open, running } from './browser.mjs';

// 640x480 with the focal length of a 60-degree field of view (the calibrator's default guess),
// 1.4 m up, 3 degrees down, 1 degree left.
const F = 320 / Math.tan(Math.PI / 6);
const TRUTH = {
  width: 640, height: 480, fx: F, fy: F, cx: 319.5, cy: 239.5,
  height_m: 1.4, pitch_deg: 3, yaw_deg: 1,
};
const FPS = 30;

/** Renders the scenario's 300 frames through TRUTH and encodes them as VP9 WebM; returns the lane width. */
function makeVideo(path) {
  const pkg = new URL('../../pkg/sim/', import.meta.url);
  return import(new URL('lanepf_sim.js', pkg)).then((m) => {
    m.initSync({ module: readFileSync(new URL('lanepf_sim_bg.wasm', pkg)) });
    const scene = new m.Scene('highway-straight', { camera: TRUTH, seed: 1 });
    const frames = [];
    for (let f = 0; f < scene.frames; f++) frames.push(Buffer.from(scene.render(f).buffer));
    const laneWidth = scene.truth(0).lane_width_m;
    scene.free();
    const out = spawnSync('ffmpeg', ['-v', 'error', '-y', '-f', 'rawvideo', '-pix_fmt', 'rgba',
      '-s', `${TRUTH.width}x${TRUTH.height}`, '-r', `${FPS}`, '-i', '-',
      '-c:v', 'libvpx-vp9', '-deadline', 'realtime', '-cpu-used', '8', '-b:v', '3M', '-g', '30',
      '-pix_fmt', 'yuv420p', path], { input: Buffer.concat(frames), maxBuffer: 1 << 20 });
    if (out.status !== 0) throw new Error(`ffmpeg failed: ${out.stderr}`);
    return { frames: frames.length, laneWidth };
  });
}

const dir = mkdtempSync(join(tmpdir(), 'lanepf-autocal-'));
const video = join(dir, 'dashcam.webm');
const made = await makeVideo(video);
const env = await start();
test.after(async () => {
  await env.close();
  rmSync(dir, { recursive: true, force: true });
});

const autoText = (page) => page.textContent('#auto-calibration');
const errorsOf = (estimate) => ({
  pitch: Math.abs(estimate.camera.pitch_deg - TRUTH.pitch_deg),
  yaw: Math.abs(estimate.camera.yaw_deg - TRUTH.yaw_deg),
  height: Math.abs(estimate.camera.height_m / TRUTH.height_m - 1),
});

test('an uploaded video without a camera is auto-calibrated, tracked with the estimate, and a camera chosen by hand wins', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
  // A simulator scene has its own camera: no auto-calibration.
  assert.equal(await page.isVisible('#auto-calibration'), false);
  await page.setInputFiles('#file', video);
  await page.waitForFunction(() => /Video “dashcam\.webm”/.test(document.getElementById('status').textContent),
    null, { timeout: 30000 });
  assert.match(await page.textContent('#status'), /camera assumed: the Udacity clip’s, scaled, until auto-calibration measures yours/);
  assert.equal(await page.isChecked('#auto-calibrate'), true);
  // While it collects: a live status, and the tracker on the assumed (clip) camera.
  await page.waitForFunction(() => /^Auto-calibrating/.test(document.getElementById('auto-calibration').textContent),
    null, { timeout: 30000 });
  const before = await page.evaluate(() => window.lanepfDemo.camera);
  assert.notEqual(before.fx, TRUTH.fx, 'the assumed camera first');

  // Applied once confident.
  await page.waitForFunction(() => window.lanepfDemo.auto.applied, null, { timeout: 120000 });
  const applied = await page.evaluate(() => ({
    camera: window.lanepfDemo.camera, auto: window.lanepfDemo.auto.applied,
    reason: window.lanepfDemo.auto.reason, at: window.lanepfDemo.auto.appliedAt,
    confidence: window.lanepfDemo.auto.estimate.confidence, frames: window.lanepfDemo.frames,
  }));
  assert.deepEqual(applied.camera, applied.auto, 'the tracker has the estimated camera');
  assert.equal(applied.reason, 'confident');
  assert.ok(applied.confidence >= 0.8, `confidence ${applied.confidence}`);
  assert.ok(applied.at < 150, `applied at frame ${applied.at}`);
  assert.match(await autoText(page), /^Auto-calibrated: pitch -?\d+\.\d\d°, yaw -?\d+\.\d\d°, height \d+\.\d\d m, confidence 0\.\d\d, \d+ of \d+ frames\. The tracker uses/);
  // The camera panel shows it.
  assert.equal(Number(await page.inputValue('#camera-fields input[name="pitch_deg"]')),
    +applied.camera.pitch_deg.toFixed(4));

  await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 240000 });
  const end = await page.evaluate(() => ({
    estimate: window.lanepfDemo.auto.estimate, camera: window.lanepfDemo.camera,
    results: window.lanepfDemo.results,
  }));
  // The run log went on across the camera change(s): every frame once.
  assert.equal(end.results.length, made.frames);
  const e = errorsOf(end.estimate);
  console.log(`auto-calibration of the uploaded video: pitch error ${e.pitch.toFixed(3)} deg, yaw error `
    + `${e.yaw.toFixed(3)} deg, height error ${(100 * e.height).toFixed(2)} %, confidence `
    + `${end.estimate.confidence.toFixed(3)}, ${end.estimate.frames_used} of ${end.estimate.frames_seen} frames; `
    + `first applied at frame ${applied.at}`);
  assert.ok(e.pitch < 0.5 && e.yaw < 0.5 && e.height < 0.1, JSON.stringify(e));
  const a = errorsOf({ camera: end.camera });
  assert.ok(a.pitch < 0.5 && a.yaw < 0.5 && a.height < 0.1, `the camera in use: ${JSON.stringify(a)}`);
  // The tracker runs with it: the last 100 frames are valid lanes of the scene's width.
  const last = end.results.slice(-100);
  const valid = last.filter((r) => r.valid);
  assert.ok(valid.length >= 90, `${valid.length} of 100 valid`);
  const width = valid.reduce((s, r) => s + r.lane_width_m, 0) / valid.length;
  assert.ok(Math.abs(width - made.laneWidth) < 0.4, `lane width ${width} against ${made.laneWidth}`);

  // A preset applied by hand wins; the estimate is still shown, for comparison.
  await page.click('#calibration summary');
  await page.selectOption('#camera-preset', 'caltech');
  await page.click('#camera-preset-apply');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.camera.pitch_deg === 14,
    null, { timeout: 30000 });
  assert.equal(await page.isChecked('#auto-calibrate'), false);
  assert.match(await autoText(page), /^Auto-calibration \(for comparison\): pitch .*your camera is in use; tick Auto-calibrate/);
  // Ticked again: the estimate is back in use at once.
  await page.check('#auto-calibrate');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.camera.pitch_deg !== 14,
    null, { timeout: 30000 });
  const back = await page.evaluate(() => ({ camera: window.lanepfDemo.camera, estimate: window.lanepfDemo.auto.estimate }));
  assert.deepEqual(back.camera, back.estimate.camera);
  assert.match(await autoText(page), /as you ticked Auto-calibrate/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the bundled clip keeps its own camera and shows the auto estimate beside it', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?tracker=lee-cpf`);
  await page.waitForFunction(() => window.lanepfDemo.frames > 60, null, { timeout: 60000 });
  assert.equal(await page.isChecked('#auto-calibrate'), false);
  const state = await page.evaluate(() => ({
    mode: window.lanepfDemo.auto.mode, applied: window.lanepfDemo.auto.applied,
    camera: window.lanepfDemo.camera,
  }));
  assert.equal(state.mode, 'manual');
  assert.equal(state.applied, null);
  assert.equal(state.camera.fx, 578.23, 'the clip camera is in use');
  assert.match(await autoText(page), /^Auto-calibration( \(for comparison\))?: .*/);
  assert.match(await autoText(page), /clip’s own camera is in use|no straight lane markings/);
  assert.deepEqual(errors, []);
  await page.close();
});
