// @ts-check
// The demo's Web Worker: the package's own worker loop (`serve` of lanepf/worker, the one
// `TrackerWorker` talks to) with the demo's ops beside the tracker's. The tracker is the one
// `TrackerWorker.open` builds (`ctx.tracker`); the demo adds the simulator's scenes and test
// road, a second tracker to compare, the camera auto-calibrator fed every tracked frame of
// media, the top view, and per frame everything the page draws in one answer, so the page's
// main thread never waits on the filter.
// Requests are TrackerWorker's: { id, op, args } -> { id, ok, result | error, name, frame? }.
// A frame travels as `frame: { data, width, height }` with its buffer transferred; it comes
// back with the answer, or on the Error when the op throws (serve.js hands it back).
import { serve } from '../pkg/worker/serve.js';
import { version, trackerIds, trackerDefaults, trackerPreset, Calibrator, Tracker } from '../pkg/web/lanepf.js';
// The simulator is a module of its own (lanepf/sim), started with the first request.
import initSim, { scenarios, Scene, TestRoad } from '../pkg/sim/lanepf_sim.js';
import { topViewTable, topView } from './top-view.js';
import { weightsByGroup, weighing } from './particle-weights.js';

/** @typedef {import('../pkg/web/lanepf.js').EgoMotion} EgoMotion */
/** @typedef {import('../pkg/web/lanepf.js').StepOptions} StepOptions */
/** @typedef {import('../pkg/worker/serve.js').ServeContext} ServeContext */
/**
 * What the page asks for besides the estimate (main.js's `want()`).
 * @typedef {{ hypotheses?: number, layers?: boolean, top?: boolean, calibration?: boolean, belief?: boolean }} Want
 */
/**
 * A frame's size with what goes into `stepOptions`: its right image (stereo media) and the
 * car's motion, when the source has them.
 * @typedef {{ motion?: EgoMotion | null, frameRight?: Uint8Array | Uint8ClampedArray | null, width: number, height: number }} Feed
 */
/** @typedef {{ data: Uint8ClampedArray<ArrayBuffer>, width: number, height: number }} Frame */

// The simulator's module, started now so that its wasm is fetched and compiled while the main
// one is (serve() starts that with the first request); the ops that need it wait for it.
const simReady = initSim();
const sim = () => simReady;
// The open synthetic source: a simulator scene or the test road (null: none).
/** @type {Scene | TestRoad | null} */
let road = null;
// A second tracker run on the same frames, for comparison (null: none).
/** @type {Tracker | null} */
let compare = null;
// The camera auto-calibrator fed every tracked frame of a video, images or the webcam (null: none).
/** @type {Calibrator | null} */
let calibrator = null;
// The right image of the scene's current frame, for a stereo tracker.
/** @type {{ rgba: Uint8ClampedArray, width: number, height: number } | null} */
let right = null;
// The top view's lookup table for the current camera.
/** @type {ReturnType<typeof topViewTable> | null} */
let topTable = null;

/** @param {ServeContext} ctx */
function requireTracker(ctx) {
  if (!ctx.tracker) throw new Error('choose a tracker first');
  return ctx.tracker;
}

/**
 * The options of `t.step(frame, options)` / `t.beginFrame(frame, options)`: a stereo tracker
 * gets the frame's right image (stereo media) or the scene's right camera (without one its step
 * throws an Error saying that danescu-stereo needs a right image), every tracker the car's
 * motion when the source has it.
 * @param {Tracker} t
 * @param {Feed} feed
 */
function stepOptions(t, { motion, frameRight, width, height }) {
  /** @type {StepOptions} */
  const options = {};
  if (t.isStereo && frameRight) options.right = { data: frameRight, width, height };
  else if (t.isStereo && right) options.right = { data: right.rgba, width: right.width, height: right.height };
  if (motion && [motion.t_s, motion.speed_mps, motion.yaw_rate].every(Number.isFinite)) {
    options.motion = motion;
  }
  return options;
}

/**
 * The particles' weights by group (lee-cpf's stage; 0 for the others).
 * @param {Tracker} t
 */
const weightsOf = (t) => weightsByGroup(t.id, t.particles(), t.particleStride);

/**
 * What the page draws of a tracker besides its estimate, on request (`want`).
 * @param {Tracker} t
 * @param {Want} want
 */
function views(t, { hypotheses = 0, layers = false, belief = false }) {
  return {
    particles: belief ? { data: t.particles(), stride: t.particleStride } : null,
    hypotheses: hypotheses > 0 ? t.hypotheses(hypotheses) : null,
    // adachi-mmpf's belief view shows its vote histogram, one of its layers.
    layers: layers || (belief && t.id === 'adachi-mmpf') ? t.layers() : null,
  };
}

/**
 * One whole frame through the comparison tracker: its estimate, time, particles drawn, the
 * weights and belief the page shows for it and the resampling it reported.
 * @param {Uint8ClampedArray} rgba
 * @param {Feed} feed
 * @param {Want | undefined} want
 */
function stepCompare(rgba, feed, want) {
  if (!compare) return null;
  const options = stepOptions(compare, feed);
  const t0 = performance.now();
  const estimate = compare.step({ data: rgba, width: feed.width, height: feed.height }, options);
  const trackMs = performance.now() - t0;
  const groups = weightsOf(compare);
  const { hypotheses, particles, layers } = views(compare, { ...want, layers: false });
  return {
    trackerId: compare.id, estimate, trackMs, hypotheses, particles, layers,
    weighing: weighing(groups, compare.id === 'lee-cpf' ? 1 : 0),
    resamplings: compare.resamplings(),
  };
}

/**
 * Feeds a frame to the auto-calibrator (when one is open for its size): its verdict on the
 * frame, the estimate so far, and with `want.calibration` the lines it saw, for drawing.
 * @param {Uint8ClampedArray} rgba
 * @param {number} width
 * @param {number} height
 * @param {Want | undefined} want
 */
function calibrate(rgba, width, height, want) {
  if (!calibrator || calibrator.width !== width || calibrator.height !== height) return null;
  const status = calibrator.feed(rgba, width, height);
  return {
    status,
    estimate: calibrator.estimate(),
    observation: want?.calibration ? calibrator.observation() : null,
  };
}

/**
 * A result that carries the frame's pixels (and a top view and the cue layers) back,
 * transferred, not copied.
 * @param {Frame} frame
 * @param {{ top?: { rgba: Uint8ClampedArray<ArrayBuffer> } | null,
 *   layers?: import('../pkg/web/lanepf.js').Layer[] | null } & Record<string, unknown>} result
 */
function reply(frame, result) {
  /** @type {Transferable[]} */
  const transfer = [frame.data.buffer];
  if (result.top) transfer.push(result.top.rgba.buffer);
  for (const layer of result.layers ?? []) transfer.push(layer.values.buffer);
  return { result: { frame, ...result }, transfer };
}

/**
 * The top view of a frame when the page asks for it.
 * @param {Frame} frame
 * @param {Want | undefined} want
 */
const topOf = (frame, want) => (want?.top ? topView(topTable, frame.data, frame.width, frame.height) : null);

serve({
  async hello() {
    await sim();
    return { result: { version: version(), trackers: trackerIds(), scenarios: scenarios() } };
  },
  defaults({ trackerId }) {
    return { result: { paper: trackerDefaults(trackerId), realRoads: trackerPreset(trackerId, 'real-roads') } };
  },
  async openTestRoad({ camera, options }) {
    await sim();
    road?.free();
    road = null;
    road = new TestRoad(camera, options ?? {});
    return { result: { width: road.width, height: road.height } };
  },
  async openScene({ name, options }) {
    await sim();
    road?.free();
    road = null;
    const scene = new Scene(name, options ?? {});
    road = scene;
    return { result: { width: scene.width, height: scene.height, frames: scene.frames, camera: scene.camera() } };
  },
  /** The top view's lookup table for a camera (the tracker itself is `open`ed by TrackerWorker). */
  openTopView({ camera }) {
    topTable = topViewTable(camera);
    return { result: null };
  },
  /**
   * Opens the auto-calibrator for width x height frames (intrinsics: a camera of that size
   * whose focal length and lens are known, or null for the field-of-view default), or with no
   * width closes it.
   */
  openCalibrator({ width, height, intrinsics }) {
    calibrator?.free();
    calibrator = null;
    if (!width) return { result: null };
    calibrator = new Calibrator({ width, height, ...(intrinsics ? { intrinsics } : {}) });
    return { result: calibrator.options() };
  },
  /** Builds (or, with no id, drops) the comparison tracker. */
  openCompare({ trackerId, config }) {
    compare?.free();
    compare = null;
    if (trackerId) compare = new Tracker(trackerId, config);
    return { result: { trackerId: compare?.id ?? null } };
  },
  /** Renders frame `index` of the open synthetic source with its truth and ego motion. */
  renderFrame({ index }, ctx) {
    if (!road) throw new Error('no synthetic source is open');
    const t0 = performance.now();
    const rgba = road.render(index);
    const ms = performance.now() - t0;
    right = ctx.tracker?.isStereo && road instanceof Scene
      ? { rgba: road.renderRight(index), width: road.width, height: road.height }
      : null;
    const truth = road.truth(index);
    const s = truth?.state;
    const motion = s ? { t_s: s.t, speed_mps: s.speed_mps, yaw_rate: s.yaw_rate } : null;
    return {
      result: { rgba, width: road.width, height: road.height, truth, motion, ms },
      transfer: [rgba.buffer],
    };
  },
  /** Forgets any right image (a frame from a one-camera source). */
  dropRight() {
    right = null;
    return { result: null };
  },
  /**
   * One whole frame through the tracker, the comparison tracker and the calibrator: the
   * estimates and what the page draws, with the pixels back.
   */
  trackFrame({ frame, right: frameRight, motion, want }, ctx) {
    const { data: rgba, width, height } = frame;
    const calibration = calibrate(rgba, width, height, want);
    const t = ctx.tracker;
    if (!t) return reply(frame, { estimate: null, trackMs: 0, top: topOf(frame, want), calibration });
    const options = stepOptions(t, { motion, frameRight, width, height });
    const t0 = performance.now();
    const estimate = t.step({ data: rgba, width, height }, options);
    const trackMs = performance.now() - t0;
    return reply(frame, {
      estimate, trackMs, ...views(t, want ?? {}), top: topOf(frame, want), nextStep: t.nextStep ?? null,
      weighing: weighing(weightsOf(t), t.id === 'lee-cpf' ? 1 : 0),
      resamplings: t.resamplings(),
      compare: stepCompare(rgba, { motion, frameRight, width, height }, want),
      calibration,
    });
  },
  /** Starts a frame in per-step (teaching) mode; `stepStage` then runs one step per call. */
  beginStepping({ frame, right: frameRight, motion, want }, ctx) {
    const t = requireTracker(ctx);
    const { data: rgba, width, height } = frame;
    if (t.stepNames().length === 0) throw new Error(`${t.id} has no per-step mode`);
    const options = stepOptions(t, { motion, frameRight, width, height });
    const t0 = performance.now();
    t.beginFrame({ data: rgba, width, height }, options);
    const trackMs = performance.now() - t0;
    // The comparison tracker takes the whole frame at once.
    const compared = stepCompare(rgba, { motion, frameRight, width, height }, want);
    const calibration = calibrate(rgba, width, height, want);
    return reply(frame, {
      trackMs, ...views(t, want ?? {}), top: topOf(frame, want), nextStep: t.nextStep ?? null,
      compare: compared, calibration,
      weighing: weighing(weightsOf(t), t.id === 'lee-cpf' ? 1 : 0),
    });
  },
  /** Runs the next step of the frame in progress: the estimate after the last, the rest always. */
  stepStage({ frame, want }, ctx) {
    const t = requireTracker(ctx);
    const done = t.nextStep;
    // (No frame in progress: `advance` below throws, saying so.)
    const name = done === undefined ? '' : t.stepNames()[done];
    // The weights the histogram shows: lee-cpf's stage from the step's name.
    const group = t.id === 'lee-cpf' ? (/^stage 2/.test(name) ? 2 : /^stage 1/.test(name) ? 1 : 0) : 0;
    const t0 = performance.now();
    const estimate = t.advance();
    const trackMs = performance.now() - t0;
    const groups = weightsOf(t);
    return reply(frame, {
      estimate, trackMs, done, ...views(t, want ?? {}), top: topOf(frame, want), nextStep: t.nextStep ?? null,
      weighing: weighing(groups, groups.has(group) ? group : (groups.has(1) ? 1 : 0)),
      resamplings: t.resamplings(),
    });
  },
  /** The top view of a frame (after a camera change), with the pixels back. */
  topView({ frame }) {
    return reply(frame, { top: topView(topTable, frame.data, frame.width, frame.height) });
  },
  /** Both trackers forget the past (either may be missing). */
  resetTrackers(_args, ctx) {
    ctx.tracker?.reset();
    compare?.reset();
    return { result: null };
  },
});
