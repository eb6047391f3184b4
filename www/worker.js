// The Web Worker that owns the WebAssembly module: it renders synthetic frames (the test road
// or a named simulator scenario), runs the chosen tracker on frames from any source, feeds them
// to the camera auto-calibrator when one is open, and draws nothing, so the page's main thread
// never waits on the filter.
// Protocol: { id, type, ...payload } (payload keys must not be `id` or `type`) ->
// { id, ok: true, result } | { id, ok: false, error }. Frames travel as transferred buffers.
import init, {
  version, trackerIds, trackerDefaults, scenarios, Calibrator, Camera, Scene, TestRoad, Tracker,
} from '../pkg/web/lanepf.js';
import { ess, weightsByGroup, resampleStep, thresholdFraction, decide } from './resampling.js';

const ready = init();
let road = null;
let tracker = null;
// A second tracker run on the same frames, for comparison (null: none).
let compare = null;
// The camera auto-calibrator fed every tracked frame of a video, images or the webcam (null: none).
let calibrator = null;
// The right image of the scene's current frame, for a stereo tracker.
let right = null;
// Top view: road cells 0.1 m, 40 m ahead, +-8 m; LUT of camera pixel indices (-1: not seen).
const TOP = { xMin: 2, xMax: 42, yHalf: 8, cell: 0.1 };
let topLut = null;
// The open tracker's ESS threshold as a fraction of N (lee-cpf's ess_threshold; null: none).
let essFraction = null;

function buildTopLut(cameraConfig) {
  const camera = new Camera(cameraConfig);
  const rows = Math.round((TOP.xMax - TOP.xMin) / TOP.cell);
  const cols = Math.round((2 * TOP.yHalf) / TOP.cell);
  const lut = new Int32Array(rows * cols).fill(-1);
  const { width, height } = camera;
  for (let r = 0; r < rows; r++) {
    const x = TOP.xMax - (r + 0.5) * TOP.cell;
    for (let c = 0; c < cols; c++) {
      const y = TOP.yHalf - (c + 0.5) * TOP.cell;
      let uv = null;
      try {
        uv = camera.projectRoad(x, y);
      } catch {
        uv = null;
      }
      if (!uv || uv.length < 2) continue;
      const u = Math.round(uv[0]);
      const v = Math.round(uv[1]);
      if (u >= 0 && u < width && v >= 0 && v < height) lut[r * cols + c] = v * width + u;
    }
  }
  camera.free();
  return { lut, rows, cols, width, height };
}

function topView(rgba, width, height) {
  if (!topLut || topLut.width !== width || topLut.height !== height) return null;
  const { lut, rows, cols } = topLut;
  const out = new Uint8ClampedArray(rows * cols * 4);
  for (let i = 0; i < lut.length; i++) {
    const p = lut[i];
    if (p < 0) continue;
    out[4 * i] = rgba[4 * p];
    out[4 * i + 1] = rgba[4 * p + 1];
    out[4 * i + 2] = rgba[4 * p + 2];
    out[4 * i + 3] = 255;
  }
  return { rgba: out, rows, cols, ...TOP };
}

/** A tracker config from the panel's options and the page's camera; a `camera` among the
 *  options would be silently replaced, so it is refused. */
function withCamera(options, camera) {
  if (options && 'camera' in options) {
    throw Object.assign(new Error('tracker options: `camera` comes from the camera panel, not the options'), { name: 'LanepfConfigError' });
  }
  return { ...(options ?? {}), camera };
}

function requireTracker() {
  if (!tracker) throw new Error('choose a tracker first');
  return tracker;
}

function feedTracker(t, { motion, frameRight, width, height }) {
  // A stereo tracker gets the frame's right image (stereo media) or the scene's right camera;
  // without one its step throws an Error saying that danescu-stereo needs a right image.
  if (t.isStereo && frameRight) t.setRight(frameRight, width, height);
  else if (t.isStereo && right) t.setRight(right.rgba, right.width, right.height);
  if (motion && [motion.t_s, motion.speed_mps, motion.yaw_rate].every(Number.isFinite)) {
    t.setEgoMotion(motion);
  }
}

/** The particles' weights by group (lee-cpf's stage; 0 for the others). */
const weightsOf = (t) => weightsByGroup(t.id, t.particles(), t.particleStride);

/**
 * The weights the page plots after a step: those of `group` (lee-cpf's stage the step worked
 * on; the first group otherwise), the total particle count and their ESS.
 */
function weighing(groups, group = null) {
  const weights = groups.get(group) ?? groups.values().next().value ?? new Float64Array(0);
  let count = 0;
  for (const w of groups.values()) count += w.length;
  return { weights: Float32Array.from(weights), count, ess: ess(weights), group };
}

/**
 * A whole frame's resampling, for the ESS plot: lee-cpf's stage-1 ESS (measured before its
 * resampling, `lee.ess1`) against N_thr; the others resample every frame.
 */
function frameResampling(t, estimate, groups) {
  const e1 = estimate?.state?.['lee.ess1'];
  if (t.id === 'lee-cpf' && Number.isFinite(e1)) {
    const n = (groups.get(1) ?? groups.get(0) ?? new Float64Array(0)).length;
    return decide('ess', e1, n, essFraction);
  }
  const n = groups.get(0)?.length ?? 0;
  return decide('always', ess(groups.get(0) ?? []), n, null);
}

/** What the page draws besides the estimate: the particles, cues and top view on request. */
function extras(t, rgba, width, height, { hypotheses = 0, layers = false, top = false, belief = false }) {
  return {
    particles: belief ? { data: t.particles(), stride: t.particleStride } : null,
    hypotheses: hypotheses > 0 ? t.hypotheses(hypotheses) : null,
    // adachi-mmpf's belief view shows its vote histogram, one of its layers.
    layers: layers || (belief && t.id === 'adachi-mmpf') ? t.layers() : null,
    top: top ? topView(rgba, width, height) : null,
    nextStep: t.nextStep ?? null,
  };
}

/** One whole frame through the comparison tracker: its estimate, time and particles. */
function stepCompare(rgba, feed, want) {
  if (!compare) return null;
  feedTracker(compare, feed);
  const t0 = performance.now();
  const estimate = compare.step(rgba, feed.width, feed.height);
  const trackMs = performance.now() - t0;
  const hypotheses = want?.hypotheses > 0 ? compare.hypotheses(want.hypotheses) : null;
  return { trackerId: compare.id, estimate, trackMs, hypotheses };
}

/**
 * Feeds a frame to the auto-calibrator (when one is open for its size): its verdict on the
 * frame, the estimate so far, and with `want.calibration` the lines it saw, for drawing.
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

/** A result that carries the frame's pixels (and a top view) back, transferred, not copied. */
function reply(result) {
  const transfer = [result.rgba.buffer];
  if (result.top) transfer.push(result.top.rgba.buffer);
  return { result, transfer };
}

const handlers = {
  async hello() {
    return { version: version(), trackers: trackerIds(), scenarios: scenarios() };
  },
  async defaults({ trackerId }) {
    return trackerDefaults(trackerId);
  },
  async openTestRoad({ camera, options }) {
    road?.free();
    road = null;
    road = new TestRoad(camera, options ?? {});
    return { width: road.width, height: road.height };
  },
  async openScene({ name, options }) {
    road?.free();
    road = null;
    road = new Scene(name, options ?? {});
    return { width: road.width, height: road.height, frames: road.frames, camera: road.camera() };
  },
  /** Builds the tracker (null id: none) for a camera; the top view follows the camera. */
  async openTracker({ trackerId, camera, options }) {
    tracker?.free();
    tracker = null;
    topLut = buildTopLut(camera);
    if (!trackerId) return { trackerId: null, stepNames: [] };
    tracker = new Tracker(trackerId, withCamera(options, camera));
    essFraction = thresholdFraction(trackerId, { ...trackerDefaults(trackerId), ...(options ?? {}) });
    return { trackerId: tracker.id, stepNames: tracker.stepNames(), isStereo: tracker.isStereo };
  },
  /**
   * Opens the auto-calibrator for width x height frames (intrinsics: a camera of that size
   * whose focal length and lens are known, or null for the field-of-view default), or with no
   * width closes it.
   */
  async openCalibrator({ width, height, intrinsics }) {
    calibrator?.free();
    calibrator = null;
    if (!width) return null;
    calibrator = new Calibrator({ width, height, ...(intrinsics ? { intrinsics } : {}) });
    return calibrator.options();
  },
  /** Builds (or, with no id, drops) the comparison tracker for the same camera. */
  async openCompare({ trackerId, camera, options }) {
    compare?.free();
    compare = null;
    if (trackerId) compare = new Tracker(trackerId, withCamera(options, camera));
    return { trackerId: compare?.id ?? null };
  },
  /** Renders frame `index` of the open synthetic source with its truth and ego motion. */
  async renderFrame({ index }) {
    if (!road) throw new Error('no synthetic source is open');
    const t0 = performance.now();
    const rgba = road.render(index);
    const ms = performance.now() - t0;
    right = tracker?.isStereo && road.renderRight
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
  async dropRight() {
    right = null;
    return null;
  },
  /** One whole frame through the tracker; the pixels come back with the result. */
  async track({ rgba, right: frameRight, width, height, motion, want }) {
    const calibration = calibrate(rgba, width, height, want);
    if (!tracker) {
      const top = want?.top ? topView(rgba, width, height) : null;
      return reply({ rgba, estimate: null, trackMs: 0, top, calibration });
    }
    feedTracker(tracker, { motion, frameRight, width, height });
    const t0 = performance.now();
    const estimate = tracker.step(rgba, width, height);
    const trackMs = performance.now() - t0;
    const groups = weightsOf(tracker);
    return reply({
      rgba, estimate, trackMs, ...extras(tracker, rgba, width, height, want ?? {}),
      weighing: weighing(groups, tracker.id === 'lee-cpf' ? 1 : 0),
      frameResampling: frameResampling(tracker, estimate, groups),
      compare: stepCompare(rgba, { motion, frameRight, width, height }, want),
      calibration,
    });
  },
  /** Starts a frame in per-step (teaching) mode; `advance` then runs one step per call. */
  async beginFrame({ rgba, right: frameRight, width, height, motion, want }) {
    const t = requireTracker();
    if (t.stepNames().length === 0) throw new Error(`${t.id} has no per-step mode`);
    feedTracker(t, { motion, frameRight, width, height });
    t.beginFrame(rgba, width, height);
    // The comparison tracker takes the whole frame at once.
    const compared = stepCompare(rgba, { motion, frameRight, width, height }, want);
    const calibration = calibrate(rgba, width, height, want);
    const groups = weightsOf(t);
    return reply({
      rgba, ...extras(t, rgba, width, height, want ?? {}), compare: compared, calibration,
      weighing: weighing(groups, t.id === 'lee-cpf' ? 1 : 0),
    });
  },
  async advance({ rgba, width, height, want }) {
    const t = requireTracker();
    const done = t.nextStep;
    const name = t.stepNames()[done];
    // The step's group: lee-cpf's stage from the step's name.
    const group = t.id === 'lee-cpf' ? (/^stage 2/.test(name) ? 2 : /^stage 1/.test(name) ? 1 : 0) : 0;
    // A resampling step: the ESS of the weights it starts from decides (lee-cpf) or not.
    const resamples = resampleStep(t.id, name);
    const before = resamples ? weightsOf(t).get(resamples.group) : null;
    const t0 = performance.now();
    const estimate = t.advance();
    const trackMs = performance.now() - t0;
    const groups = weightsOf(t);
    const resampling = before ? decide(resamples.policy, ess(before), before.length, essFraction) : null;
    return reply({
      rgba, estimate, trackMs, done, ...extras(t, rgba, width, height, want ?? {}),
      weighing: weighing(groups, groups.has(group) ? group : (groups.has(1) ? 1 : 0)),
      resampling,
      frameResampling: estimate ? frameResampling(t, estimate, groups) : null,
    });
  },
  /** The top view of a frame (after a camera change), with the pixels back. */
  async topView({ rgba, width, height }) {
    return reply({ rgba, top: topView(rgba, width, height) });
  },
  async reset() {
    tracker?.reset();
    compare?.reset();
    return null;
  },
};

self.onmessage = async (e) => {
  const { id, type, ...payload } = e.data;
  try {
    await ready;
    const handler = handlers[type];
    if (!handler) throw new Error(`unknown request type '${type}'`);
    const out = await handler(payload);
    if (out && out.transfer) self.postMessage({ id, ok: true, result: out.result }, out.transfer);
    else self.postMessage({ id, ok: true, result: out });
  } catch (err) {
    // Hand the pixels back even on failure, so the page can still draw the frame.
    const rgba = payload?.rgba;
    const transfer = rgba?.buffer && rgba.buffer.byteLength ? [rgba.buffer] : [];
    // The error's kind (`name`, e.g. LanepfStateError) travels with its message.
    self.postMessage({ id, ok: false, error: err?.message ?? String(err), name: err?.name, rgba }, transfer);
  }
};
