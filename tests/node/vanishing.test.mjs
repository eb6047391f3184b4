// The calibration helper's geometry against the camera model's own projection (the wasm
// package's Camera, built by `make pkg`, run in Node).
import test from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { intersect, poseFromVanishingPoint, heightFromLaneWidth } from '../../www/vanishing.js';
import init, { Camera } from '../../pkg/web/lanepf.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });

const base = { width: 640, height: 480, fx: 309.4, fy: 344.2, cx: 317.9, cy: 256.5, height_m: 2.18 };

test('two lines meet where expected, parallel lines nowhere', () => {
  assert.deepEqual(intersect([[0, 0], [2, 2]], [[0, 2], [2, 0]]), [1, 1]);
  assert.equal(intersect([[0, 0], [1, 1]], [[0, 1], [1, 2]]), null);
});

test('pitch, yaw and height come back from the projected lane lines of a known camera', () => {
  for (const [pitch, yaw, h] of [[14, 0, 2.18], [3, 2, 1.4], [8, -3, 1.6]]) {
    const camera = new Camera({ ...base, pitch_deg: pitch, yaw_deg: yaw, height_m: h });
    // Two lane lines 3.6 m apart, seen from 8 m to 40 m.
    const line = (y) => [camera.projectRoad(8, y), camera.projectRoad(40, y)];
    const vp = intersect(line(1.8), line(-1.8));
    const pose = poseFromVanishingPoint(base, vp);
    assert.ok(Math.abs(pose.pitch_deg - pitch) < 1e-6, `pitch ${pose.pitch_deg} vs ${pitch}`);
    assert.ok(Math.abs(pose.yaw_deg - yaw) < 1e-6, `yaw ${pose.yaw_deg} vs ${yaw}`);
    if (yaw === 0) {
      const [ul, row] = camera.projectRoad(10, 1.8);
      const [ur] = camera.projectRoad(10, -1.8);
      const est = heightFromLaneWidth(base, pose.pitch_deg, row, ul, ur, 3.6);
      assert.ok(Math.abs(est - h) < 1e-6, `height ${est} vs ${h}`);
    }
    camera.free();
  }
  assert.equal(heightFromLaneWidth(base, 14, 10, 100, 200, 3.6), null, 'above the horizon');
});
