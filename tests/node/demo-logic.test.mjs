// The demo's pure logic, without a browser: lane-departure status, export formats, camera
// scaling.
import test from 'node:test';
import assert from 'node:assert/strict';
import { Departure, CAR_HALF_WIDTH_M } from '../../www/departure.js';
import { toJsonLines, toCsv, CSV_COLUMNS } from '../../www/export.js';
import { scaleCamera } from '../../www/camera-presets.js';
import { appendCapped, MAX_RESULTS } from '../../www/capped.js';

const lane = (q, psi = 0, valid = true) => ({
  valid, lateral_offset_m: q, heading_rad: psi, lane_width_m: 3.6, curvature_per_m: 0,
});

test('departure: distances to the lines from the offset and the car width', () => {
  const d = new Departure();
  const s = d.update(lane(0.3), 0, 0);
  const toLeft = 1.8 - 0.3 - CAR_HALF_WIDTH_M;
  const toRight = 1.8 + 0.3 - CAR_HALF_WIDTH_M;
  assert.match(s.text, new RegExp(`${toLeft.toFixed(2)} m to the left line, ${toRight.toFixed(2)} m to the right`));
  assert.equal(s.warn, false);
  assert.deepEqual(d.update(lane(1.0), 0.04, 0), { text: 'crossing the left line', warn: true });
  assert.equal(d.update(lane(0, 0, false), 0.08, 0), null, 'nothing for an invalid estimate');
});

test('departure: time to line crossing from the speed and heading, else from the offset rate', () => {
  const d = new Departure();
  // Lane heading +0.02 rad (lane turns left of the car): the car drifts right at v sin(psi).
  const s = d.update(lane(0, 0.02), 0, 25);
  const tlc = (1.8 - CAR_HALF_WIDTH_M) / (25 * Math.sin(0.02));
  assert.match(s.text, new RegExp(`${tlc.toFixed(1)} s to the right line`));
  assert.equal(s.warn, tlc < 1);
  // Without a speed: offset 0 -> 0.5 m left in 1 s is 0.5 m/s; 0.4 m left to go is 0.8 s.
  const e = new Departure();
  e.update(lane(0), 10, null);
  const w = e.update(lane(0.5), 11, null);
  assert.match(w.text, /0\.8 s to the left line/);
  assert.equal(w.warn, true);
});

test('export: JSON lines round-trip and CSV quotes what needs quoting', () => {
  const rows = [
    { frame: 'a,b.png', valid: true, lateral_offset_m: 0.1, heading_rad: 0, curvature_per_m: 0, lane_width_m: 3.5, ms: 2, boundaries: [] },
    { frame: '2', valid: false, lateral_offset_m: -0.2, heading_rad: 0.01, curvature_per_m: 1e-3, lane_width_m: 3.6, ms: 3, boundaries: [] },
  ];
  const lines = toJsonLines(rows).split('\n');
  assert.equal(lines.pop(), '');
  assert.deepEqual(lines.map((l) => JSON.parse(l)), rows);
  const csv = toCsv(rows).trim().split('\n');
  assert.equal(csv[0], CSV_COLUMNS.join(','));
  assert.equal(csv[1], '"a,b.png",true,0.1,0,0,3.5,2');
  assert.equal(csv[2], '2,false,-0.2,0.01,0.001,3.6,3');
});

test('camera scaling keeps the field of view and maps pixel centres', () => {
  const c = { width: 1280, height: 720, fx: 1156, fy: 1151, cx: 671.5, cy: 389.5, height_m: 1.4, pitch_deg: 0 };
  const s = scaleCamera(c, 640, 360);
  assert.equal(s.fx, 578);
  assert.equal(s.fy, 575.5);
  assert.equal(s.cx, 335.5);
  assert.equal(s.cy, 194.5);
  assert.equal(s.height_m, 1.4);
  assert.equal(Math.atan(c.width / 2 / c.fx), Math.atan(s.width / 2 / s.fx));
});

test('stereo image pairs are told from side-by-side images by their names', async () => {
  const { arePairs } = await import('../../www/media-source.js');
  assert.equal(arePairs(['a_left.png', 'a_right.png', 'b_left.png', 'b_right.png']), true);
  assert.equal(arePairs(['urban1_left.pgm', 'urban1_right.pgm']), true);
  assert.equal(arePairs(['f1_l.png', 'f1_r.png']), true);
  assert.equal(arePairs(['left.png', 'right.png']), true);
  assert.equal(arePairs(['sbs0.png', 'sbs1.png']), false, 'no camera token');
  assert.equal(arePairs(['a_left.png', 'b_right.png']), false, 'different frames');
  assert.equal(arePairs(['a_left.png']), false, 'odd count');
});

test('the run log keeps the newest frames within its cap, dropping the oldest in batches', () => {
  const list = [];
  let dropped = 0;
  for (let i = 0; i < 100; i += 1) {
    dropped += appendCapped(list, i, 36);
    // Never more than the cap plus one batch (36 / 18 = 2), never fewer than the cap once full.
    assert.ok(list.length <= 38 && list.length >= Math.min(i + 1, 36), `${i}: ${list.length}`);
    assert.equal(list[list.length - 1], i);
    assert.equal(dropped + list.length, i + 1);
  }
  assert.deepEqual(list, Array.from({ length: list.length }, (_, k) => 100 - list.length + k));
  assert.ok(MAX_RESULTS >= 10 * 60 * 30, 'ten minutes at 30 fps');
});
