// Camera auto-calibration without a browser: the demo's policy (www/auto-calibration.js: when
// the estimate is applied, re-applied, or left for comparison) and the wasm package's
// `Calibrator` as JavaScript sees it (built by `make pkg`, run in Node): a synthetic road's
// camera recovered, and every bad input a thrown Error with a message to act on, after which
// the instance still works.
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import {
  AutoCalibration, moved, APPLY_CONFIDENCE, APPLY_AFTER_FRAMES,
} from '../../www/auto-calibration.js';
import init, { Calibrator, Tracker } from '../../pkg/web/lanepf.js';
import initSim, { Scene } from '../../pkg/sim/lanepf_sim.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });

const cam = (pitch, yaw, h) => ({ width: 640, height: 480, fx: 500, fy: 500, cx: 320, cy: 240, height_m: h, pitch_deg: pitch, yaw_deg: yaw });
const estimate = (confidence, camera = cam(3, 1, 1.4)) => ({ camera, confidence, frames_used: 40, frames_seen: 60 });
const status = (seen) => ({ frames_seen: seen, frames_used: 0, used: false });

test('policy: a camera moves by more than 0.5 degrees or 10 % of the height', () => {
  const a = cam(3, 1, 1.4);
  assert.equal(moved(a, cam(3.4, 1.4, 1.5)), false);
  assert.equal(moved(a, cam(3.6, 1, 1.4)), true);
  assert.equal(moved(a, cam(3, 0.4, 1.4)), true);
  assert.equal(moved(a, cam(3, 1, 1.55)), true);
  assert.equal(moved({ ...a, yaw_deg: undefined }, cam(3, 0.2, 1.4)), false);
});

test('policy: applied once confident or after a few seconds, re-applied when a confident estimate moves', () => {
  const auto = new AutoCalibration();
  assert.equal(auto.text(), '');
  auto.start('auto');
  assert.match(auto.text(), /waiting for frames/);
  assert.equal(auto.update({ status: status(10), estimate: null }), null);
  assert.match(auto.text(), /^Auto-calibrating the camera: 10 frames, no straight lane markings/);
  assert.equal(auto.looking(), true);
  assert.equal(auto.update({ status: status(20), estimate: estimate(0.5) }), null);
  assert.match(auto.text(), /^Auto-calibrating: pitch 3\.00°, yaw 1\.00°, height 1\.40 m, confidence 0\.50, 40 of 60 frames/);
  assert.equal(auto.update({ status: status(21), estimate: estimate(APPLY_CONFIDENCE) }), 'confident');
  auto.markApplied(auto.estimate.camera, 'confident');
  assert.equal(auto.looking(), false);
  assert.match(auto.text(), /^Auto-calibrated: pitch 3\.00°.*The tracker uses pitch 3\.00°, yaw 1\.00°, height 1\.40 m since frame 21/);
  // Small moves and unconfident large ones are not applied; a confident large one is.
  assert.equal(auto.update({ status: status(30), estimate: estimate(0.95, cam(3.3, 1.2, 1.45)) }), null);
  assert.equal(auto.update({ status: status(31), estimate: estimate(0.5, cam(4, 1, 1.4)) }), null);
  assert.equal(auto.update({ status: status(32), estimate: estimate(0.9, cam(4, 1, 1.4)) }), 'moved');
  // Once enough frames agree the yaw is the lane's tangent's, and the line says so.
  assert.doesNotMatch(auto.text(), /tangent/);
  auto.update({ status: status(33), estimate: { ...estimate(0.9, cam(4, 1, 1.4)), yaw_from_tangent: true } });
  assert.match(auto.text(), /40 of 60 frames, yaw from the lane’s tangent\./);

  const late = new AutoCalibration();
  late.start('auto');
  assert.equal(late.update({ status: status(APPLY_AFTER_FRAMES - 1), estimate: estimate(0.3) }), null);
  assert.equal(late.update({ status: status(APPLY_AFTER_FRAMES), estimate: estimate(0.3) }), 'timeout');
  late.markApplied(late.estimate.camera, 'timeout');
  assert.match(late.text(), new RegExp(`after ${APPLY_AFTER_FRAMES} frames, below confidence ${APPLY_CONFIDENCE}`));
});

test('policy: a camera of the user\'s or the clip\'s own wins; off without a calibrator', () => {
  const auto = new AutoCalibration();
  auto.start('manual', { known: cam(0, 0, 1.4) });
  assert.equal(auto.update({ status: status(400), estimate: estimate(0.99) }), null);
  assert.match(auto.text(), /^Auto-calibration \(for comparison\): pitch 3\.00°.*; the clip’s own camera is in use: pitch 0\.00°/);
  auto.setMode('auto');
  assert.equal(auto.decide(), 'confident');
  const off = new AutoCalibration();
  off.start('off', { error: 'frames of at least 32x16 pixels' });
  off.setMode('auto');
  assert.equal(off.mode, 'off');
  assert.match(off.text(), /unavailable: frames of at least 32x16/);
});

test('Calibrator in Node: the scene camera within 0.5 degrees and 10 %, accepted by a Tracker', () => {
  const f = 160 / Math.tan(Math.PI / 6);
  const truth = { width: 320, height: 240, fx: f, fy: f, cx: 159.5, cy: 119.5, height_m: 1.4, pitch_deg: 3, yaw_deg: 1 };
  const scene = new Scene('highway-straight', { camera: truth, seed: 1 });
  const calibrator = new Calibrator({ width: 320, height: 240 });
  assert.equal(calibrator.estimate(), null);
  let s = null;
  for (let k = 0; k < scene.frames; k++) s = calibrator.feed(scene.render(k), 320, 240);
  assert.deepEqual(Object.keys(s).sort(), ['ego_found', 'frames_seen', 'frames_used', 'stable', 'straight', 'used', 'vanishing_point']);
  const e = calibrator.estimate();
  assert.ok(Math.abs(e.camera.pitch_deg - 3) < 0.5, `pitch ${e.camera.pitch_deg}`);
  assert.ok(Math.abs(e.camera.yaw_deg - 1) < 0.5, `yaw ${e.camera.yaw_deg}`);
  assert.ok(Math.abs(e.camera.height_m / 1.4 - 1) < 0.1, `height ${e.camera.height_m}`);
  assert.ok(e.confidence > 0.5 && e.confidence <= 1);
  assert.equal(e.frames_seen, 300);
  assert.equal(e.intrinsics_known, false);
  assert.equal(typeof e.yaw_from_tangent, 'boolean');
  const tracker = new Tracker('lee-cpf', { camera: e.camera });
  assert.equal(typeof tracker.step(scene.render(0), 320, 240).valid, 'boolean');
  const o = calibrator.observation();
  assert.equal(o.ego.length, 2);
  assert.ok(o.lines[o.ego[0]].slope < 0 && o.lines[o.ego[1]].slope > 0, 'left leans right, right leans left');
  tracker.free();
  scene.free();
  calibrator.free();
});

test('Calibrator in Node: the yaw is the crossing\'s until tangent_yaw_after frames agree, then the tangent\'s', () => {
  const f = 160 / Math.tan(Math.PI / 6);
  const truth = { width: 320, height: 240, fx: f, fy: f, cx: 159.5, cy: 119.5, height_m: 1.4, pitch_deg: 3, yaw_deg: 1 };
  const scene = new Scene('highway-curve', { camera: truth, seed: 2 });
  const options = [0, 1, 2000].map((after) => ({ width: 320, height: 240, intrinsics: truth, tangent_yaw_after: after }));
  const calibrators = options.map((o) => new Calibrator(o));
  for (let k = 0; k < 60; k++) {
    const frame = scene.render(k);
    for (const c of calibrators) c.feed(frame, 320, 240);
  }
  const [never, first, late] = calibrators.map((c) => c.estimate());
  assert.deepEqual([never.yaw_from_tangent, first.yaw_from_tangent, late.yaw_from_tangent], [false, true, false]);
  assert.equal(late.camera.yaw_deg, never.camera.yaw_deg, 'not yet 2000 frames: the crossing\'s yaw');
  assert.notEqual(first.camera.yaw_deg, never.camera.yaw_deg);
  assert.equal(first.camera.pitch_deg, never.camera.pitch_deg, 'the pitch is the crossing\'s in both');
  for (const c of calibrators) c.free();
  scene.free();
});

test('Calibrator in Node: bad options and frames throw Errors that say what to do; the instance carries on', () => {
  const throws = (fn, re) => assert.throws(fn, (err) => err instanceof Error && re.test(err.message), String(re));
  throws(() => new Calibrator(), /calibrator options is missing: pass an object/);
  throws(() => new Calibrator('640x480'), /must be an object/);
  throws(() => new Calibrator({ width: 640 }), /missing field `height`/);
  throws(() => new Calibrator({ width: 640, height: 480, lanewidth: 3.5 }), /unknown field `lanewidth`/);
  throws(() => new Calibrator({ width: 640, height: 480, lane_width_m: NaN }), /lane_width_m is NaN/);
  throws(() => new Calibrator({ width: 640, height: 480, lane_width_m: 9 }), /lane_width_m.*2\.5 to 5/);
  throws(() => new Calibrator({ width: 640, height: 480, stable_frames: 2.5 }), /stable_frames/);
  throws(() => new Calibrator({ width: 640, height: 480, tangent_yaw: 'yes' }), /tangent_yaw/);
  throws(() => new Calibrator({ width: 640, height: 480, tangent_yaw_after: 5000 }), /tangent_yaw_after.*0 \(never\) to 2000/);
  throws(() => new Calibrator({ width: 640, height: 480, tangent_yaw_after: -1 }), /tangent_yaw_after/);
  throws(() => new Calibrator({ width: 0, height: 480 }), /0x480/);
  throws(() => new Calibrator({ width: 1e5, height: 480 }), /at most/);
  throws(() => new Calibrator({ width: 640, height: 480, intrinsics: { ...cam(3, 0, 1.4), width: 320 } }), /intrinsics are for 320x480 frames, not 640x480/);
  const c = new Calibrator({ width: 64, height: 48 });
  const frame = new Uint8ClampedArray(64 * 48 * 4).fill(90);
  throws(() => c.feed(new Uint8Array(10), 64, 48), /64x48/);
  throws(() => c.feed(frame, 128, 48), /128x48: this calibrator takes 64x48/);
  throws(() => c.feed(frame, NaN, 48), /width is NaN/);
  throws(() => c.feed(frame, 64, -48), /height is -48/);
  throws(() => c.feed([1, 2, 3], 64, 48), /Uint8Array or Uint8ClampedArray of RGBA pixels \(ImageData\.data\), not an array/);
  throws(() => c.feed(new Float32Array(64 * 48 * 4), 64, 48), /not a Float32Array/);
  throws(() => c.feed(null, 64, 48), /not null/);
  assert.equal(c.feed(frame, 64, 48).frames_seen, 1, 'the failed calls counted nothing');
  assert.deepEqual(c.options(), { lane_width_m: 3.6, hfov_deg: 60, stable_frames: 5, max_bend_px: 1.5, tangent_yaw: false, tangent_yaw_after: 100 });
  c.reset();
  assert.equal(c.feed(frame, 64, 48).frames_seen, 1);
  c.free();
});
