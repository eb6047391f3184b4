// The wasm boundary (issue 19, part 2): nothing a JavaScript caller passes may kill the
// instance. Each bad argument must give a thrown Error naming it, with an error kind in
// `name`, before anything is copied into wasm memory; the object that threw stays usable and
// can be freed. Runs against the built package (`make pkg`).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import init, {
  Calibrator, Camera, Tracker, trackerDefaults, trackerIds, trackerPreset,
} from '../../pkg/web/lanepf.js';
import initSim, { Scene, TestRoad } from '../../pkg/sim/lanepf_sim.js';

const wasm = await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });
const memory = () => wasm.memory.buffer.byteLength;

const KINDS = ['LanepfConfigError', 'LanepfInputError', 'LanepfStateError'];
/** `fn` throws an Error of `kind` whose message matches `pattern`. */
function throwsKind(fn, kind, pattern) {
  assert.throws(fn, (err) => {
    assert.ok(err instanceof Error, `not an Error: ${err}`);
    assert.ok(KINDS.includes(err.name), `error.name is ${err.name}: ${err.message}`);
    if (kind) assert.equal(err.name, kind, err.message);
    if (pattern) assert.match(err.message, pattern);
    return true;
  });
}

const W = 160, H = 120;
const scene = new Scene('highway-straight', { width: W, height: H, seed: 1 });
const camera = scene.camera();
const frame = scene.render(0);

/** Objects that cannot be read safely: cyclic, very deep, throwing getters and Proxies. */
function hostile() {
  const cyclic = { ...camera }; cyclic.self = cyclic;
  let deep = {}; for (let i = 0; i < 10000; i++) deep = { a: deep };
  const getter = { ...camera }; Object.defineProperty(getter, 'fx', { enumerable: true, get() { throw new Error('boom'); } });
  const proxy = new Proxy({ ...camera }, { ownKeys() { throw new Error('trap'); } });
  const proxyGet = new Proxy({ ...camera }, { get() { throw new Error('get trap'); } });
  const bigint = { ...camera, fx: 10n };
  const noJson = { ...camera, toJSON() {} };
  const revoked = Proxy.revocable({}, {}); revoked.revoke();
  return { cyclic, deep, getter, proxy, proxyGet, bigint, noJson, revoked: revoked.proxy };
}

test('hostile config objects throw a clear Error and leave every object usable', () => {
  const tracker = new Tracker('lee-cpf', { camera, particles: 50 });
  const calibrator = new Calibrator({ width: W, height: H });
  for (const [what, bad] of Object.entries(hostile())) {
    throwsKind(() => new Tracker('lee-cpf', bad), 'LanepfConfigError');
    throwsKind(() => new Tracker('lee-cpf', { camera: bad }), 'LanepfConfigError');
    throwsKind(() => new Camera(bad), 'LanepfConfigError');
    // (A key whose toJSON gives undefined is left out, as JSON.stringify leaves it out.)
    if (what !== 'noJson') throwsKind(() => new Scene('s-curve', { camera: bad }), 'LanepfConfigError');
    throwsKind(() => new Scene('s-curve', bad), 'LanepfConfigError');
    throwsKind(() => new TestRoad(bad), 'LanepfConfigError');
    throwsKind(() => new TestRoad(camera, bad), 'LanepfConfigError');
    throwsKind(() => new Calibrator(bad), 'LanepfConfigError');
    throwsKind(() => tracker.setEgoMotion(bad), 'LanepfInputError');
    // The objects keep working.
    assert.equal(typeof tracker.step(frame, W, H).valid, 'boolean', what);
    assert.equal(typeof calibrator.feed(frame, W, H).used, 'boolean', what);
  }
  // A getter that calls back into the object it is being read for.
  const reentrant = { t_s: 0, speed_mps: 1, get yaw_rate() { tracker.step(frame, W, H); return 0; } };
  assert.throws(() => tracker.setEgoMotion(reentrant));
  tracker.setEgoMotion({ t_s: 0, speed_mps: 1, yaw_rate: 0 });
  assert.equal(typeof tracker.step(frame, W, H).valid, 'boolean');
  // A getter that frees the object: the call throws, the object is gone (wasm-bindgen's own
  // Error for any later call), the module carries on.
  const freeing = { t_s: 0, speed_mps: 1, get yaw_rate() { tracker.free(); return 0; } };
  assert.throws(() => tracker.setEgoMotion(freeing), /ego motion cannot be read/);
  assert.throws(() => tracker.step(frame, W, H), (e) => !(e instanceof WebAssembly.RuntimeError));
  const again = new Tracker('lee-cpf', { camera, particles: 50 });
  assert.equal(typeof again.step(frame, W, H).valid, 'boolean');
  again.free();
  calibrator.free();
});

test('hostile config messages say what was wrong', () => {
  const { cyclic, deep, getter } = hostile();
  throwsKind(() => new Camera(cyclic), 'LanepfConfigError', /camera.*circular|camera.*cycl/i);
  throwsKind(() => new Camera(deep), 'LanepfConfigError', /camera/);
  throwsKind(() => new Camera(getter), 'LanepfConfigError', /boom/);
  throwsKind(() => new Camera({ ...camera, fx: 10n }), 'LanepfConfigError', /fx is a BigInt/);
  throwsKind(() => new Camera({ ...camera, fx: () => 1 }), 'LanepfConfigError', /fx is a function/);
  throwsKind(() => new Camera({ ...camera, fx: NaN }), 'LanepfConfigError', /fx is NaN/);
  throwsKind(() => new Camera({ toJSON() {} }), 'LanepfConfigError', /camera gives no JSON/);
  throwsKind(() => new Camera({ toJSON() { return 5; } }), 'LanepfConfigError', /camera must be an object, but its JSON is 5/);
  throwsKind(() => new Tracker('lee-cpf', { camera: { ...camera, fy: -Infinity } }), 'LanepfConfigError', /camera\.fy is -Infinity/);
});

test('ids and names must be strings', () => {
  for (const id of [{}, 5, null, undefined, ['lee-cpf'], Symbol('x'), 'x'.repeat(1e6)]) {
    throwsKind(() => new Tracker(id, { camera }), 'LanepfConfigError', /id|tracker/);
    throwsKind(() => trackerDefaults(id), 'LanepfConfigError', /id|tracker/);
    throwsKind(() => new Scene(id), 'LanepfConfigError', /name|scenario/);
  }
  throwsKind(() => new Tracker(5, { camera }), 'LanepfConfigError', /tracker id.*string.*number/);
  assert.equal(trackerIds().length, 6);
  assert.ok(trackerDefaults('lee-cpf').particles > 0);
});

test('a preset is a tracker\'s options: paper its defaults, real-roads ours beside them', () => {
  for (const id of trackerIds()) {
    assert.deepEqual(trackerPreset(id, 'paper'), trackerDefaults(id));
    const roads = trackerPreset(id, 'real-roads');
    const changed = Object.keys(roads).filter((k) => JSON.stringify(roads[k]) !== JSON.stringify(trackerDefaults(id)[k]));
    // (liu-ppf-nokernel's real-roads is its paper's filter: it is the paper's baseline.)
    assert.equal(changed.length > 0, id !== 'liu-ppf-nokernel', `${id}: ${changed}`);
    for (const k of changed) assert.ok(['relock_share', 'curvature_prior_sd', 'adjacent_lanes', 'start_iterations', 'valid_distance_m', 'valid_support_frames', 'paired_edges', 'width_scaled_threshold', 'kalman_process_sd', 'top_view_resolved', 'side_search_share', 'reacquire_near_m', 'mode_candidates', 'width_range_m', 'snap_to_paint', 'snap_follows_bends', 'valid_needs_paint', 'valid_from_paint'].includes(k), `${id}: ${k}`);
    const tracker = new Tracker(id, { ...roads, camera, particles: 50 });
    tracker.free();
  }
  assert.equal(trackerPreset('lee-cpf', 'real-roads').curvature_prior_sd, 0.004);
  throwsKind(() => trackerPreset('lee-cpf', 'fast'), 'LanepfConfigError', /unknown preset `fast`: use one of paper, real-roads/);
  throwsKind(() => trackerPreset('lee-cpf', 5), 'LanepfConfigError', /preset/);
  throwsKind(() => trackerPreset('kalman', 'paper'), 'LanepfConfigError', /id|tracker/);
});

test('frames that are not byte arrays of the right length are refused before any copy', () => {
  const tracker = new Tracker('adachi-mmpf', { camera, particles: 50 });
  const stereo = new Tracker('danescu-stereo', { camera, particles: 50 });
  const calibrator = new Calibrator({ width: W, height: H });
  const before = memory();
  const huge = new Uint8Array(2 ** 31);
  for (const rgba of [{ length: -5 }, { length: 1e10 }, huge, [1, 2, 3], 'abc', null, undefined, 5,
    new Float32Array(W * H * 4), new Uint8Array(W * H * 4 + 1), new Uint8Array(W * H * 4).buffer]) {
    for (let i = 0; i < 3; i++) {
      throwsKind(() => tracker.step(rgba, W, H), 'LanepfInputError', /rgba|frame|buffer/);
      throwsKind(() => tracker.beginFrame(rgba, W, H), 'LanepfInputError', /rgba|frame|buffer/);
      throwsKind(() => stereo.setRight(rgba, W, H), 'LanepfInputError', /rgba|frame|buffer/);
      throwsKind(() => calibrator.feed(rgba, W, H), 'LanepfInputError', /rgba|frame|buffer/);
    }
  }
  assert.ok(memory() - before < 4 << 20, `wasm memory grew from ${before} to ${memory()}`);
  throwsKind(() => tracker.step({ length: 1e10 }, W, H), 'LanepfInputError', /rgba/);
  // A Uint8ClampedArray view into a larger buffer is read from its offset.
  const big = new Uint8ClampedArray(W * H * 4 + 8);
  big.set(frame, 8);
  const view = new Uint8ClampedArray(big.buffer, 8, W * H * 4);
  const a = new Tracker('adachi-mmpf', { camera, particles: 50 });
  const b = new Tracker('adachi-mmpf', { camera, particles: 50 });
  assert.deepEqual(a.step(view, W, H), b.step(frame, W, H));
  for (const t of [tracker, stereo, a, b]) assert.equal(typeof t.id, 'string');
  for (const t of [tracker, stereo, a, b, calibrator]) t.free();
});

test('sizes and indices must be whole numbers in range, never strings, never wrapped', () => {
  const tracker = new Tracker('adachi-mmpf', { camera, particles: 50 });
  const calibrator = new Calibrator({ width: W, height: H });
  for (const bad of [W + 0.5, 2 ** 32 + W, String(W), -1, NaN, Infinity, null, undefined, 1e300, {}, 10n]) {
    throwsKind(() => tracker.step(frame, bad, H), 'LanepfInputError', /width/);
    throwsKind(() => tracker.step(frame, W, bad), 'LanepfInputError', /height/);
    throwsKind(() => tracker.beginFrame(frame, bad, H), 'LanepfInputError', /width/);
    throwsKind(() => calibrator.feed(frame, bad, H), 'LanepfInputError', /width/);
    throwsKind(() => scene.render(bad), 'LanepfInputError', /index/);
    throwsKind(() => scene.truth(bad), 'LanepfInputError', /index/);
    if (bad !== 2 ** 32 + W) throwsKind(() => tracker.hypotheses(bad), 'LanepfInputError', /max/);
  }
  throwsKind(() => tracker.step(frame, -1, H), 'LanepfInputError', /width.*-1/);
  tracker.step(frame, W, H);
  assert.ok(tracker.hypotheses(2 ** 32).length > 0, 'hypotheses(2**32) is every particle, not 0');
  assert.equal(tracker.hypotheses(2 ** 32).length, tracker.hypotheses(50).length);
  assert.equal(tracker.hypotheses(0).length, 0);
  const road = new TestRoad(camera);
  throwsKind(() => road.render(-1), 'LanepfInputError', /index/);
  throwsKind(() => road.truth('3'), 'LanepfInputError', /index/);
  const cam = new Camera(camera);
  throwsKind(() => cam.projectRoad('10', 0), 'LanepfInputError', /x/);
  throwsKind(() => cam.roadPoint(80, null), 'LanepfInputError', /v/);
  assert.equal(cam.projectRoad(10, 0).length, 2);
  // Many points in one call: the same pixels, NaN where projectRoad throws (behind the camera).
  const many = cam.projectRoadPoints(new Float64Array([10, 0, 25.5, -3.2, -5, 1]));
  assert.deepEqual([...many.slice(0, 2)], [...cam.projectRoad(10, 0)]);
  assert.deepEqual([...many.slice(2, 4)], [...cam.projectRoad(25.5, -3.2)]);
  assert.ok(Number.isNaN(many[4]) && Number.isNaN(many[5]), `behind the camera: ${many.slice(4)}`);
  throwsKind(() => cam.projectRoad(-5, 1), 'LanepfInputError', /behind/);
  throwsKind(() => cam.projectRoadPoints(new Float64Array([1, 2, 3])), 'LanepfInputError', /pairs/);
  for (const o of [tracker, calibrator, road, cam]) o.free();
});

test('unknown keys and wrong types are errors naming the key path, everywhere', () => {
  throwsKind(() => new Scene('s-curve', { widht: 100 }), 'LanepfConfigError', /widht/);
  throwsKind(() => new Scene('s-curve', { width: 320.5 }), 'LanepfConfigError', /width/);
  throwsKind(() => new Scene('s-curve', { width: '320' }), 'LanepfConfigError', /width/);
  throwsKind(() => new Scene('s-curve', { width: -1 }), 'LanepfConfigError', /width/);
  throwsKind(() => new Scene('s-curve', { seed: null }), 'LanepfConfigError', /seed.*null/);
  throwsKind(() => new Scene('s-curve', 5), 'LanepfConfigError', /options/);
  const s = new Scene('s-curve', { width: 2 ** 5, height: 2 ** 5 });
  assert.equal(s.width, 32);
  s.free();
  const tracker = new Tracker('danescu-mono', { camera, particles: 50 });
  throwsKind(() => tracker.setEgoMotion({ t_s: 0, speed_mps: 1, yaw_rate: 0, bogus: 1 }), 'LanepfInputError', /bogus/);
  throwsKind(() => tracker.setEgoMotion({ t_s: 0, speed_mps: '1', yaw_rate: 0 }), 'LanepfInputError', /speed_mps/);
  throwsKind(() => tracker.setEgoMotion({ t_s: 0, speed_mps: NaN, yaw_rate: 0 }), 'LanepfInputError', /speed_mps/);
  throwsKind(() => tracker.setEgoMotion({ t_s: 0, speed_mps: 1 }), 'LanepfInputError', /yaw_rate/);
  tracker.setEgoMotion({ t_s: 0, speed_mps: 1, yaw_rate: 0 });
  tracker.free();
  throwsKind(() => new Tracker('lee-cpf', { camera, particles: null }), 'LanepfConfigError', /particles.*null/);
  throwsKind(() => new Tracker('lee-cpf', { camera, particles: '50' }), 'LanepfConfigError', /particles/);
  throwsKind(() => new Tracker('lee-cpf', { camera, seed: 1.5 }), 'LanepfConfigError', /seed/);
  throwsKind(() => new Tracker('lee-cpf', { camera, canny: { sigma: 1, low: 40, high: 100, camera } }),
    'LanepfConfigError', /canny.*camera/);
  throwsKind(() => new Tracker('lee-cpf', { camera, dld: { window: 3, gama: 20 } }), 'LanepfConfigError', /dld.*gama/);
  throwsKind(() => new Tracker('lee-cpf', { camera, process_sd: [1, 2, 3, 4, 5, null] }), 'LanepfConfigError', /process_sd\[5\].*null/);
  throwsKind(() => new Tracker('lee-cpf', { camera: { ...camera, pitch: 3 } }), 'LanepfConfigError', /camera.*pitch/);
  throwsKind(() => new Tracker('lee-cpf', { camera, bogus: 1 }), 'LanepfConfigError', /bogus/);
  throwsKind(() => new Tracker('lee-cpf', [camera]), 'LanepfConfigError', /config.*object/);
  throwsKind(() => new Calibrator({ width: W, height: H, hfov_deg: null }), 'LanepfConfigError', /hfov_deg.*null/);
  throwsKind(() => new TestRoad(camera, { lane_width_m: '3' }), 'LanepfConfigError', /lane_width_m/);
  throwsKind(() => new Calibrator({ width: W, height: H, stable_frames: 2 ** 32 + 5 }), 'LanepfConfigError', /stable_frames/);
  // Options left out (undefined) take their defaults.
  new Tracker('lee-cpf', { camera, particles: undefined }).free();
  new Scene('s-curve', undefined).free();
});

test('errors carry their kind in name', () => {
  throwsKind(() => new Tracker('nope', { camera }), 'LanepfConfigError', /unknown tracker/);
  const stereo = new Tracker('danescu-stereo', { camera, particles: 50 });
  throwsKind(() => stereo.step(frame, W, H), 'LanepfStateError', /needs the right image/);
  throwsKind(() => stereo.advance(), 'LanepfStateError', /no frame in progress/);
  stereo.free();
  const mono = new Tracker('lee-cpf', { camera, particles: 50 });
  throwsKind(() => mono.setRight(frame, W, H), 'LanepfStateError', /one camera/);
  throwsKind(() => mono.step(new Uint8Array(8), 1, 2), 'LanepfInputError');
  mono.free();
  const { baseline_m: _, ...mono_camera } = camera;
  throwsKind(() => new Tracker('danescu-stereo', { camera: mono_camera }), 'LanepfConfigError', /baseline_m/);
  throwsKind(() => new Camera({ ...camera, fx: -1 }), 'LanepfConfigError', /fx/);
  const cam = new Camera(camera);
  throwsKind(() => cam.roadPoint(80, 0), 'LanepfInputError', /horizon|map/);
  cam.free();
});

test('every tracker id survives the bad calls and still tracks', () => {
  for (const id of trackerIds()) {
    const t = new Tracker(id, { camera, particles: 30 });
    for (const bad of [{ length: -5 }, null, 'x']) assert.throws(() => t.step(bad, W, H));
    assert.throws(() => t.setEgoMotion({ get t_s() { throw new Error('no'); } }));
    if (t.isStereo) t.setRight(scene.renderRight(0), W, H);
    assert.equal(typeof t.step(frame, W, H).valid, 'boolean', id);
    t.free();
  }
});
