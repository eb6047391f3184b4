// `step(frame, { right, motion })` and `beginFrame(frame, { right, motion })` (issue 21): the
// frame as an ImageData-like `{ data, width, height }` with the right camera's frame and the
// car's motion in one call, the same as setRight + setEgoMotion + step(rgba, width, height);
// a call that throws changes nothing; estimates carry no command-line-only fields (`ms`,
// `frame`). Runs against the built package (`make pkg`).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import init, { Tracker } from '../../pkg/web/lanepf.js';
import initSim, { Scene, TestRoad } from '../../pkg/sim/lanepf_sim.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });

const W = 160, H = 120;
const scene = new Scene('highway-curve', { width: W, height: H, seed: 3 });
const camera = scene.camera();
const left = (f) => ({ data: scene.render(f), width: W, height: H });
const right = (f) => ({ data: scene.renderRight(f), width: W, height: H });
const motion = (f) => {
  const s = scene.truth(f).state;
  return { t_s: s.t, speed_mps: s.speed_mps, yaw_rate: s.yaw_rate };
};
const FRAMES = [0, 1, 2, 3, 4, 5];

/** `fn` throws an Error named `kind` whose message matches `pattern`. */
function throwsKind(fn, kind, pattern) {
  assert.throws(fn, (err) => {
    assert.ok(err instanceof Error, `not an Error: ${err}`);
    assert.equal(err.name, kind, err.message);
    assert.match(err.message, pattern);
    return true;
  });
}

test('step(frame, { right, motion }) gives what setRight + setEgoMotion + step(rgba, w, h) gives', () => {
  const config = { camera, particles: 60, seed: 2 };
  const a = new Tracker('danescu-stereo', config);
  const b = new Tracker('danescu-stereo', config);
  const still = new Tracker('danescu-stereo', config); // the same frames without the motion
  for (const f of FRAMES) {
    const one = a.step(left(f), { right: right(f), motion: motion(f) });
    b.setRight(scene.renderRight(f), W, H);
    b.setEgoMotion(motion(f));
    const old = b.step(scene.render(f), W, H);
    assert.deepEqual(one, old, `frame ${f}`);
    const noMotion = still.step(left(f), { right: right(f) });
    if (f === FRAMES.at(-1)) {
      assert.notDeepEqual(one.state, noMotion.state, 'the motion reached the tracker');
    }
  }
  // The right frame is used once: the next step without one is refused.
  throwsKind(() => a.step(left(6)), 'LanepfStateError', /right/);
  for (const t of [a, b, still]) t.free();
});

test('an ImageData-like frame and the bytes with their size give the same estimate', () => {
  for (const id of ['lee-cpf', 'adachi-mmpf', 'liu-ppf', 'danescu-mono']) {
    const a = new Tracker(id, { camera, particles: 80, seed: 1 });
    const b = new Tracker(id, { camera, particles: 80, seed: 1 });
    for (const f of [0, 1, 2]) {
      const withBytes = a.step(scene.render(f), W, H);
      // A class instance whose fields are getters, as ImageData's are.
      class Picture { constructor(p) { this.p = p; } get data() { return this.p.data; } get width() { return W; } get height() { return H; } }
      assert.deepEqual(b.step(new Picture(left(f)), {}), withBytes, `${id} frame ${f}`);
    }
    a.free(); b.free();
  }
});

test('beginFrame(frame, { right, motion }) and every advance() give what step gives', () => {
  const config = { camera, particles: 60, seed: 5 };
  const whole = new Tracker('danescu-stereo', config);
  const stepped = new Tracker('danescu-stereo', config);
  for (const f of [0, 1, 2]) {
    const expected = whole.step(left(f), { right: right(f), motion: motion(f) });
    stepped.beginFrame(left(f), { right: right(f), motion: motion(f) });
    let out = null;
    while (out === null) out = stepped.advance();
    assert.deepEqual(out, expected, `frame ${f}`);
  }
  whole.free(); stepped.free();
});

test('a step that throws leaves the tracker as it was: no motion applied, no right frame pending', () => {
  const config = { camera, particles: 60, seed: 4 };
  const tried = new Tracker('danescu-stereo', config);
  const clean = new Tracker('danescu-stereo', config);
  const leaked = new Tracker('danescu-stereo', config); // what an applied motion would give
  for (const t of [tried, clean, leaked]) t.step(left(0), { right: right(0), motion: motion(0) });
  // Frame 1's time, far faster and turning: the drift it would cause is plain in the estimate.
  const fast = { t_s: motion(1).t_s, speed_mps: 40, yaw_rate: 0.5 };
  const tiny = { data: new Uint8Array(4), width: 1, height: 1 };
  const other = new Scene('highway-curve', { width: W + 2, height: H, seed: 3 });
  const wide = { data: other.render(1), width: W + 2, height: H };
  const wideRight = { data: other.renderRight(1), width: W + 2, height: H };
  throwsKind(() => tried.step(left(1), { right: tiny, motion: fast }), 'LanepfInputError', /right is 1x1/);
  throwsKind(() => tried.step(tiny, { right: right(1), motion: fast }), 'LanepfInputError', /1x1/);
  throwsKind(() => tried.step(left(1), { right: right(1), motion: fast, extra: 1 }), 'LanepfInputError', /unknown key `extra`/);
  throwsKind(() => tried.step(left(1), { right: right(1), motion: { ...fast, speed_mps: 1e9 } }), 'LanepfInputError', /speed_mps/);
  throwsKind(() => tried.step(wide, { right: wideRight, motion: fast }), 'LanepfInputError', /camera is 160x120/);
  throwsKind(() => tried.beginFrame(wide, { right: wideRight, motion: fast }), 'LanepfInputError', /camera is 160x120/);
  other.free();
  // No right frame was left pending by the calls that failed.
  throwsKind(() => tried.step(left(1)), 'LanepfStateError', /right/);
  leaked.setEgoMotion(fast);
  const drifted = leaked.step(left(1), { right: right(1) });
  const expected = clean.step(left(1), { right: right(1) });
  assert.notDeepEqual(drifted.state, expected.state, 'the test motion would show');
  assert.deepEqual(tried.step(left(1), { right: right(1) }), expected);
  // A one-camera tracker refuses a right frame before it applies the motion.
  const mono = new Tracker('danescu-mono', config);
  const monoClean = new Tracker('danescu-mono', config);
  for (const t of [mono, monoClean]) t.step(left(0), { motion: motion(0) });
  throwsKind(() => mono.step(left(1), { right: right(1), motion: fast }), 'LanepfStateError', /one camera/);
  assert.deepEqual(mono.step(left(1)), monoClean.step(left(1)));
  for (const t of [tried, clean, leaked, mono, monoClean]) t.free();
});

test('bad frames and options are refused with the argument named', () => {
  const t = new Tracker('lee-cpf', { camera, particles: 50 });
  const bytes = scene.render(0);
  throwsKind(() => t.step(bytes), 'LanepfInputError', /bare RGBA bytes/);
  throwsKind(() => t.step(bytes, {}), 'LanepfInputError', /bare RGBA bytes/);
  throwsKind(() => t.step(left(0), bytes), 'LanepfInputError', /step options must be an object/);
  throwsKind(() => t.step(left(0), 'fast'), 'LanepfInputError', /step options must be an object/);
  throwsKind(() => t.step(left(0), { motion: null }), 'LanepfInputError', /motion is null/);
  throwsKind(() => t.step(left(0), { motion: { t_s: 0 } }), 'LanepfInputError', /motion/);
  throwsKind(() => t.step(bytes, W), 'LanepfInputError', /height must be a number/);
  throwsKind(() => t.step({ data: bytes, width: W }), 'LanepfInputError', /frame\.height/);
  throwsKind(() => t.step({ data: [1, 2, 3], width: 1, height: 1 }), 'LanepfInputError', /frame\.data/);
  throwsKind(() => t.step({ data: bytes, width: W, height: H + 1 }), 'LanepfInputError', /frame\.data has/);
  throwsKind(() => t.step(null), 'LanepfInputError', /ImageData/);
  const trap = new Proxy(left(0), { get() { throw new Error('get trap'); } });
  throwsKind(() => t.step(trap), 'LanepfInputError', /get trap/);
  const keysTrap = new Proxy({}, { ownKeys() { throw new Error('keys trap'); } });
  throwsKind(() => t.step(left(0), keysTrap), 'LanepfInputError', /keys trap/);
  // A getter that calls back into the tracker is refused rather than locking it.
  const reentrant = { get data() { t.reset(); return bytes; }, width: W, height: H };
  assert.throws(() => t.step(reentrant));
  assert.equal(t.step(left(1)).boundaries.length > 0, true, 'the tracker still works');
  t.free();
});

test('results carry no command-line-only fields; a scene truth keeps its file name', () => {
  for (const id of ['lee-cpf', 'danescu-mono']) {
    const t = new Tracker(id, { camera, particles: 50 });
    const e = t.step(left(0));
    assert.ok(!('ms' in e) && !('frame' in e), `${id}: ${Object.keys(e)}`);
    t.beginFrame(left(1));
    let out = null;
    while (out === null) out = t.advance();
    assert.ok(!('ms' in out) && !('frame' in out), `${id} advance: ${Object.keys(out)}`);
    assert.deepEqual(Object.keys(e).slice(0, 6), ['valid', 'boundaries', 'lateral_offset_m',
      'heading_rad', 'curvature_per_m', 'lane_width_m'], 'the keys keep their order');
    t.free();
  }
  const truth = scene.truth(42);
  assert.equal(truth.frame, '000042.png');
  assert.ok(!('ms' in truth));
  const road = new TestRoad(camera);
  const roadTruth = road.truth(0);
  assert.ok(!('ms' in roadTruth) && !('frame' in roadTruth), `${Object.keys(roadTruth)}`);
  road.free();
});
