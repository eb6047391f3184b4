// @ts-check
// The demo page: wires a frame source, the tracking worker, the renderer and the controls.
// One frame at a time: take the next frame from the source, send its pixels to the worker
// (transferred, not copied), draw what comes back. Every action runs in one queue, so clicks
// never interleave with a frame in flight. Videos, images and the webcam are auto-calibrated
// (auto-calibration.js): the worker feeds their frames to the wasm Calibrator, and its camera
// replaces the assumed one once it is confident, unless the user chose a camera.
import { connectWorker, withCamera } from './worker-client.js';
import { SceneSource, TestRoadSource } from './source.js';
import { ImageSource, WebcamSource } from './media-source.js';
import { VideoFile } from './video-select.js';
import { CLIP, loadClipCamera, scaleCamera, readCameraFile, loadPresets } from './camera-presets.js';
import { Calibration } from './calibration.js';
import { Controls } from './controls.js';
import { drawFrame, drawTruth, drawEstimate, drawHypotheses, drawTopView, drawLayer, drawCalibrationLines } from './render.js';
import { Legend, showBadge, showCount } from './legend.js';
import { AutoCalibration } from './auto-calibration.js';
import { toJsonLines, toCsv, download } from './export.js';
import { Plots, plotsCaption } from './plots.js';
import { Departure } from './departure.js';
import { appendCapped } from './capped.js';
import { ParamsPanel } from './params-panel.js';
import { Pacer } from './pacer.js';
import { showWeighing } from './weighing-view.js';
import { resampleText, frameResampling } from './resampling.js';
import { byId, context2d } from './dom.js';

/** @typedef {import('../pkg/web/lanepf.js').LaneEstimate} LaneEstimate */
/** @typedef {import('../pkg/web/lanepf.js').CameraConfig} CameraConfig */
/** @typedef {import('../pkg/web/lanepf.js').ResampleDecision} ResampleDecision */
/** @typedef {import('../pkg/web/lanepf.js').TrackerId} TrackerId */
/** @typedef {import('../pkg/worker/index.js').TrackerWorker} TrackerWorker */
/**
 * A frame from a source: its pixels (handed to the worker and back), size, name and index, and
 * from the simulator its ground truth and the car's motion; a stereo frame's right image.
 * @typedef {{ rgba: Uint8ClampedArray<ArrayBuffer>, right?: Uint8ClampedArray<ArrayBuffer> | null, width: number,
 *   height: number, name: string, index: number, t?: number, ms?: number, truth?: LaneEstimate | null,
 *   motion?: import('../pkg/web/lanepf.js').EgoMotion | null }} Frame
 */
/**
 * A source of frames (source.js, media-source.js, webcodecs-source.js): `size` once open for
 * media (the simulator's sources have none), `progress` in [0, 1] (null: no end).
 * @typedef {{ label: string, progress?: number | null, size?: { width: number, height: number } | null,
 *   fps?: number | null, camera?: CameraConfig | null, open(): Promise<unknown>, next(): Promise<Frame | null>,
 *   restart(): void, close(): void }} Source
 */
/**
 * What the demo's worker answers for a frame (worker.js: `trackFrame`, `beginStepping`,
 * `stepStage`, `topView`): the frame's pixels back, and what the page draws.
 * @typedef {{ frame: { data: Uint8ClampedArray<ArrayBuffer>, width: number, height: number },
 *   estimate?: LaneEstimate | null, trackMs: number, done?: number, nextStep?: number | null,
 *   hypotheses?: import('../pkg/web/lanepf.js').Hypothesis[] | null, layers?: import('../pkg/web/lanepf.js').Layer[] | null,
 *   particles?: { data: Float32Array, stride: number } | null, top?: Parameters<typeof drawTopView>[1] | null,
 *   weighing?: { weights: Float32Array, count: number, ess: number, group: number | null },
 *   resamplings?: ResampleDecision[], compare?: CompareAnswer | null, calibration?: CalibrationAnswer | null }} FrameAnswer
 */
/**
 * The second tracker's whole frame (compare mode; worker.js `stepCompare`).
 * @typedef {{ trackerId: string, estimate: LaneEstimate, trackMs: number,
 *   hypotheses: import('../pkg/web/lanepf.js').Hypothesis[] | null, particles: { data: Float32Array, stride: number } | null,
 *   layers: null, weighing: NonNullable<FrameAnswer['weighing']>, resamplings: ResampleDecision[] }} CompareAnswer
 */
/**
 * The auto-calibrator's verdict on a frame and its estimate so far (worker.js `calibrate`).
 * @typedef {{ status: import('../pkg/web/lanepf.js').CalibrationStatus,
 *   estimate: import('../pkg/web/lanepf.js').CalibrationEstimate | null,
 *   observation: import('../pkg/web/lanepf.js').CalibrationObservation | null }} CalibrationAnswer
 */

/** @param {string} id */
const el = (id) => byId(id, HTMLElement);

/**
 * A point of the page's start-up on the performance timeline (`lanepf:NAME`, ms since
 * navigation), read by `scripts/bench-first-frame.mjs`.
 * @param {string} name
 * @param {Record<string, number>} [detail]
 */
const mark = (name, detail) => performance.mark(`lanepf:${name}`, { detail });

/** Particles drawn per frame (spread over the cloud). */
const DRAWN_PARTICLES = 80;

const controls = new Controls();
const ctx = context2d('view');
const topCtx = context2d('top');
const cues = context2d('cues');
const ctx2 = context2d('view2');
// The worker (a TrackerWorker of lanepf/worker, connected to the demo's worker.js), from main().
/** @type {TrackerWorker} */
let client;
const plots = new Plots(byId('plots', HTMLCanvasElement));
const legend = new Legend(el('legend'));
const departure = new Departure();
const panel = new ParamsPanel();
const auto = new AutoCalibration();
const autoText = el('auto-calibration');
const autoToggle = byId('auto-calibrate', HTMLInputElement);
const showCalibration = byId('show-calibration', HTMLInputElement);
const pacer = new Pacer();
const paceText = el('pace');
const whyLink = el('why-link');
whyLink.addEventListener('click', () => {
  byId('why-resample', HTMLDetailsElement).open = true;
});
// Read by the end-to-end tests and handy in the console (the `last*` of the frame drawn last).
/**
 * @type {{ frames: number, lastTruth: LaneEstimate | null, lastFrame: object | null, lastEstimate: LaneEstimate | null,
 *   lastLayer: object | null, lastHypotheses: object[] | null, lastRgba: Uint8ClampedArray | null, results: Record<string, unknown>[],
 *   droppedResults: number, offsetErrors: number[], ended: boolean, source: string | null, pending: number,
 *   auto: AutoCalibration, camera: CameraConfig | null, [more: string]: unknown }}
 */
const demo = (window.lanepfDemo = {
  frames: 0, lastTruth: null, lastFrame: null, lastEstimate: null, lastLayer: null,
  lastHypotheses: null, lastRgba: null, results: [], droppedResults: 0, offsetErrors: [], ended: false, source: null, pending: 0,
  auto, camera: null,
});

/**
 * @type {{ source: Source | null, sourceName: string, sourceStatus?: string, trackerId: string, compareId: string,
 *   hasTruth: boolean, camera: CameraConfig | null, importedCamera: CameraConfig | null, inFrame: Frame | null,
 *   inFrameResamplings: ResampleDecision[], inFrameMs: number, inFrameCompare?: CompareAnswer | null,
 *   lastFrame: Frame | null, lastResult: Partial<FrameAnswer> | null }}
 */
const state = {
  source: null,
  sourceName: '',
  trackerId: '',
  compareId: '',
  hasTruth: false, // the source has ground truth (the simulator's scenes and test road)
  camera: null,
  importedCamera: null,
  inFrame: null, // the frame being stepped through in per-step mode
  // Of the frame being stepped through: the resampling decisions the tracker reported so far
  // and the time its stages took so far.
  inFrameResamplings: [],
  inFrameMs: 0,
  lastFrame: null, // the frame on the canvas and what the worker said about it
  lastResult: null,
};
/** The camera panel (from main(), once the presets are loaded). */
/** @type {Calibration | null} */
let calibration = null;

// Before the WebAssembly module loads: the menus, the teaching text and the canvases as they
// will be, so nothing moves when the first frame comes (the menus list the registry's ids in
// index.html; main() checks them against the module's own list).
const params = new URLSearchParams(location.search);
const firstSource = params.get('source') ?? 'clip';
state.trackerId = params.get('tracker') ?? 'lee-cpf';
state.compareId = params.get('compare') ?? '';
controls.tracker.value = state.trackerId;
controls.compare.value = state.compareId;
// The simulator's scenes and the test road are 640x480; the bundled clip 640x360 (index.html).
if (!['clip', 'webcam', 'file'].includes(firstSource)) {
  for (const id of ['view', 'view2']) byId(id, HTMLCanvasElement).height = 480;
}
panel.show(state.trackerId, null);
showNames();
// A tracker chosen while the module loads is the one opened (main() then takes over these).
controls.onTracker = (/** @type {string} */ id) => { state.trackerId = id; };
controls.onCompare = (/** @type {string} */ id) => { state.compareId = id; };

/** Names the tracker each view shows, on the view itself. */
function showNames() {
  const name = el('view-name');
  name.textContent = state.trackerId || 'no tracker';
  name.hidden = false;
  el('compare-name').textContent = state.compareId;
}

/**
 * What to do in this page about a tracker's error, from its kind (`err.name`, see the package
 * README) and the page's own state: the page calls the trackers correctly, so a state error
 * of a stereo tracker is its missing right image, and a configuration error of one on a camera
 * without a baseline is that baseline.
 * @param {{ name?: string }} err
 */
function hint(err) {
  if (![state.trackerId, state.compareId].includes('danescu-stereo')) return '';
  if (err.name === 'LanepfStateError') {
    return ' In this page: tick Stereo and open a side-by-side video or left/right image pairs, or choose a simulator scene.';
  }
  if (err.name === 'LanepfConfigError' && !(state.camera ?? demo.camera)?.baseline_m) {
    return ' In this page: import a camera file with baseline_m, or pick a stereo preset under Camera calibration.';
  }
  return '';
}

let queue = Promise.resolve();
/** Runs `fn` after everything queued before it; errors pause the page and are shown. */
/** @param {() => void | Promise<void>} fn */
function run(fn) {
  demo.pending += 1;
  queue = queue.then(fn).catch((err) => {
    controls.setPaused(true);
    controls.say(err.message + hint(err), true);
  }).finally(() => {
    demo.pending -= 1;
  });
  return queue;
}

const want = () => ({
  hypotheses: controls.showParticles.checked ? DRAWN_PARTICLES : 0,
  layers: controls.showCues.checked,
  top: controls.showTop.checked,
  calibration: showCalibration.checked || auto.looking(),
  belief: controls.showPlots.checked,
});

/** Draws the frame and everything on it; `redraw`: the same frame again (no bookkeeping). */
/**
 * @param {Frame} frame
 * @param {Partial<FrameAnswer> | null} result
 * @param {boolean} [redraw]
 */
function draw(frame, result, redraw = false) {
  // Frames flow again after an error: back to the source's description.
  if (!redraw && document.body.dataset.state === 'error' && state.source) controls.say(state.source.label);
  state.lastFrame = frame;
  state.lastResult = result;
  drawFrame(ctx, frame.rgba, frame.width, frame.height);
  const estimate = result?.estimate ?? null;
  const hypotheses = controls.showParticles.checked ? result?.hypotheses : null;
  const truth = controls.showTruth.checked ? frame.truth : null;
  const byGroup = controls.colourGroups.checked;
  drawHypotheses(ctx, hypotheses, null, byGroup);
  // The truth over the estimate: thin dashes on a thick line where they agree.
  if (estimate) drawEstimate(ctx, estimate);
  if (truth) drawTruth(ctx, truth.boundaries);
  showBadge(el('view-badge'), estimate);
  const seen = result?.calibration?.observation;
  if (seen && (showCalibration.checked || auto.looking())) drawCalibrationLines(ctx, seen);
  calibration?.draw(ctx, estimate);
  const top = controls.showTop.checked ? result?.top : null;
  el('top-figure').hidden = !top;
  if (top) drawTopView(topCtx, top, { truth, estimate, hypotheses, byGroup });
  drawCompare(frame, result?.compare ?? null, truth, byGroup);
  const layers = controls.showCues.checked ? result?.layers : null;
  const layer = layers?.[controls.setLayers(layers)];
  el('cues-figure').hidden = !layer;
  if (layer) {
    const probabilities = estimate?.model_probabilities ?? null;
    drawLayer(cues, layer, { hypotheses: result?.hypotheses, probabilities });
    el('cues-caption').textContent = layer.name;
  }
  drawWeighing(result, estimate);
  if (redraw) return;
  Object.assign(demo, {
    lastLayer: layer ?? null,
    lastHypotheses: result?.hypotheses ?? null,
    lastEstimate: estimate,
    lastTruth: frame.truth ?? null,
    lastFrame: { index: frame.index, name: frame.name, width: frame.width, height: frame.height },
    lastRgba: frame.rgba,
    lastCompare: result?.compare ?? null,
  });
  demo.frames += 1;
  let text = `frame ${frame.name}`;
  if (frame.ms) text += ` · render ${frame.ms.toFixed(1)} ms`;
  if (estimate) {
    text += ` · track ${(result?.trackMs ?? 0).toFixed(1)} ms`;
    if (!estimate.valid) text += ' · not valid';
    if (frame.truth) {
      const err = Math.abs(estimate.lateral_offset_m - frame.truth.lateral_offset_m);
      text += ` · offset error ${(100 * err).toFixed(0)} cm`;
    }
  }
  controls.timing.textContent = text;
  controls.setProgress(state.source?.progress ?? null);
}

/**
 * The weight histograms and belief views after the frame or the step just run (the second
 * tracker's too, in compare mode), and how many particles the view draws of the tracker's
 * total (in the legend).
 */
/**
 * @param {Partial<FrameAnswer> | null} result
 * @param {LaneEstimate | null} estimate
 */
function drawWeighing(result, estimate) {
  const weighing = result?.weighing ?? null;
  const drawn = controls.showParticles.checked ? (result?.hypotheses?.length ?? 0) : 0;
  showCount(el('view-count'), drawn, weighing?.count ?? 0);
  const step = result?.done !== undefined && result?.done !== null ? controls.stepNames[result.done] : null;
  let label = step ? `after “${step}”` : 'after the whole frame';
  if (!step && !estimate && state.inFrame) label = 'at the start of the frame';
  const shown = controls.showPlots.checked;
  const own = showWeighing({ weights: 'weights', belief: 'belief' }, state.trackerId, result, estimate, label, shown);
  if (own.weighing) demo.lastWeighing = own.weighing;
  if (own.belief) demo.lastBelief = own.belief;
  // The second tracker takes whole frames, also while the first is stepped through.
  const compared = result?.compare ?? null;
  const other = showWeighing({ weights: 'compare-weights', belief: 'compare-belief', named: true },
    compared?.trackerId ?? '', compared, compared?.estimate ?? null, 'after the whole frame', shown);
  demo.lastCompareWeighing = other.weighing;
  demo.lastCompareBelief = other.belief;
}

/** The second tracker's view: the same frame with its boundaries and particles. */
/**
 * @param {Frame} frame
 * @param {CompareAnswer | null} compared
 * @param {LaneEstimate | null | undefined} truth
 * @param {boolean} byGroup
 */
function drawCompare(frame, compared, truth, byGroup) {
  el('compare-figure').hidden = !compared;
  // Side by side on a wide screen (style.css), the teaching panel then below them.
  document.body.classList.toggle('comparing', !!compared);
  if (!compared) return;
  drawFrame(ctx2, frame.rgba, frame.width, frame.height);
  drawHypotheses(ctx2, compared.hypotheses, null, byGroup);
  if (compared.estimate) drawEstimate(ctx2, compared.estimate);
  if (truth) drawTruth(ctx2, truth.boundaries);
  showBadge(el('compare-badge'), compared.estimate);
  let text = `${compared.trackerId} · track ${compared.trackMs.toFixed(1)} ms`;
  if (compared.estimate && !compared.estimate.valid) text += ' · not valid';
  if (compared.estimate && frame.truth) {
    const err = Math.abs(compared.estimate.lateral_offset_m - frame.truth.lateral_offset_m);
    text += ` · offset error ${(100 * err).toFixed(0)} cm`;
  }
  el('compare-caption').textContent = text;
}

/** A frame's end: its estimate into the plots (with the resampling `decisions` it reported), the log and the status. */
/**
 * @param {Frame} frame
 * @param {Partial<FrameAnswer> & { trackMs: number }} result
 * @param {ResampleDecision[] | undefined} decisions
 */
function record(frame, result, decisions) {
  if (!result?.estimate) return;
  plots.push(result.estimate, frame.truth, result, result.compare ?? null, frameResampling(decisions));
  el('plots-figure').hidden = !controls.showPlots.checked;
  const t = frame.motion?.t_s ?? frame.t ?? null;
  const status = departure.update(result.estimate, t, frame.motion?.speed_mps ?? null);
  controls.departure.textContent = status?.text ?? '';
  controls.departure.classList.toggle('warn', !!status?.warn);
  demo.droppedResults += appendCapped(demo.results, { ...result.estimate, frame: frame.name, ms: result.trackMs });
  if (frame.truth) {
    appendCapped(demo.offsetErrors, Math.abs(result.estimate.lateral_offset_m - frame.truth.lateral_offset_m));
  }
  controls.setExportable(true);
}

/**
 * Sends a frame's pixels to the demo's op `op` in the worker (transferred); the pixels come back
 * with the answer, or on the Error (`err.frame`).
 */
/**
 * @param {string} op
 * @param {Frame} frame
 * @param {{ motion?: Frame['motion'], right?: Frame['right'] }} [extra]
 * @returns {Promise<FrameAnswer>}
 */
async function toWorker(op, frame, extra = {}) {
  const args = { frame: { data: frame.rgba, width: frame.width, height: frame.height }, want: want(), ...extra };
  // A stereo frame's right image goes along once (it is not needed back).
  const transfer = [frame.rgba.buffer];
  if (extra.right) transfer.push(extra.right.buffer);
  try {
    const result = /** @type {FrameAnswer} */ (await client.request(op, args, transfer));
    frame.rgba = result.frame.data;
    return result;
  } catch (err) {
    // (The request's frame comes back on the Error.)
    const back = /** @type {{ frame?: FrameAnswer['frame'] }} */ (err)?.frame;
    if (back?.data) {
      frame.rgba = back.data;
      draw(frame, null);
    }
    throw err;
  }
}

/** Re-warps the frame on the canvas to the top view of the current camera. */
async function refreshTopView() {
  const frame = state.lastFrame;
  if (!frame?.rgba?.length || !controls.showTop.checked) return;
  const result = await toWorker('topView', frame);
  state.lastResult = { ...(state.lastResult ?? {}), top: result.top };
  draw(frame, state.lastResult, true);
}

/** The next frame, or null at the end of the source (which pauses the page). */
async function nextFrame() {
  const source = state.source;
  if (!source) throw new Error('no source is open');
  const frame = await source.next();
  if (!frame) {
    demo.ended = true;
    controls.setPaused(true);
    controls.setProgress(1);
    controls.say(`End of ${source.label}: ${demo.results.length} frames tracked. Restart to run it again.`);
  }
  return frame;
}

/** One whole frame (finishing a frame left half-stepped first). */
async function stepFrame() {
  if (state.inFrame) {
    await finishStepping();
    return;
  }
  const t0 = performance.now();
  const frame = await nextFrame();
  if (!frame) return;
  const t1 = performance.now();
  const result = await toWorker('trackFrame', frame, { motion: frame.motion, right: frame.right });
  const t2 = performance.now();
  record(frame, result, result.resamplings);
  draw(frame, result);
  if (demo.frames === 1 && !performance.getEntriesByName('lanepf:first-frame').length) {
    mark('first-frame', { source: t1 - t0, worker: t2 - t1, track: result.trackMs ?? NaN });
  }
  // Where a frame's time goes (ms): reading it, the worker's round trip, drawing it here.
  demo.frameMs = { source: t1 - t0, worker: t2 - t1, page: performance.now() - t2 };
  await autoCalibrate(result.calibration);
}

/**
 * Shows what the auto-calibrator knows and applies its camera when it is time.
 * @param {CalibrationAnswer | null | undefined} calibrationResult
 * @param {boolean} [canApply]
 */
async function autoCalibrate(calibrationResult, canApply = true) {
  const reason = auto.update(calibrationResult);
  if (reason && canApply) await applyAuto(reason);
  showAuto();
}

function showAuto() {
  autoText.textContent = auto.text();
  autoText.hidden = auto.mode === 'off' && !auto.error;
}

/**
 * The tracker gets the auto-calibrated camera (rebuilt with it; the run log is kept).
 * @param {import('./auto-calibration.js').Reason} reason
 */
async function applyAuto(reason) {
  if (!auto.estimate) return; // (called with an estimate to apply)
  const camera = auto.estimate.camera;
  state.camera = camera;
  demo.camera = camera;
  calibration?.show(camera, state.sourceName);
  await openTracker({ keepLog: true });
  auto.markApplied(camera, reason);
}

/** Per-step (teaching) mode: the first click starts a frame, each next click runs one step. */
async function stepStage() {
  let frame = state.inFrame;
  if (!frame) {
    frame = await nextFrame();
    if (!frame) return;
    const result = await toWorker('beginStepping', frame, { motion: frame.motion, right: frame.right });
    state.inFrame = frame;
    state.inFrameResamplings = [];
    state.inFrameMs = result.trackMs;
    state.inFrameCompare = result.compare ?? null;
    draw(frame, result);
    showStageInPlots('start of the frame: image cues', result);
    // Not in the middle of a stepped frame: the camera changes on the next whole frame.
    await autoCalibrate(result.calibration, false);
    controls.updateStageButton(result.nextStep ?? null);
    return;
  }
  const result = await toWorker('stepStage', frame);
  // The second tracker took the whole frame at its start: its views stay while this one steps.
  result.compare = state.inFrameCompare;
  const step = result.done === undefined ? '' : controls.stepNames[result.done];
  const decisions = result.resamplings ?? [];
  state.inFrameResamplings.push(...decisions);
  state.inFrameMs += result.trackMs;
  draw(frame, result);
  if (result.estimate) {
    record(frame, { ...result, trackMs: state.inFrameMs }, state.inFrameResamplings);
    demo.plotsStage = null;
    state.inFrame = null;
    controls.updateStageButton(null);
  } else {
    showStageInPlots(step, result);
    controls.updateStageButton(result.nextStep ?? null);
  }
  // What the tracker reported of its resampling in this step, with its numbers.
  const said = resampleText(decisions);
  let text = `${state.trackerId}: ran “${step}”`;
  if (said) text += ` · ${said}`;
  else if (/resampl/i.test(step)) text += ' · the tracker reported no resampling in this step';
  controls.say(text);
  whyLink.hidden = !said;
  demo.lastResampling = decisions.at(-1) ?? null;
  demo.lastResamplings = decisions;
}

/**
 * The plots follow the stages of a frame stepped through: the frame in progress is their newest
 * point (the ESS of the weights now, the time so far, the resampling reported so far).
 */
/**
 * @param {string} label
 * @param {FrameAnswer} result
 */
function showStageInPlots(label, result) {
  plots.stage({
    label, ess: result.weighing?.ess ?? null, trackMs: state.inFrameMs,
    ...frameResampling(state.inFrameResamplings),
  });
  el('plots-figure').hidden = !controls.showPlots.checked;
  demo.plotsStage = plots.live;
}

async function finishStepping() {
  while (state.inFrame) await stepStage();
}

/**
 * Builds the chosen tracker for the current camera with the panel's options and seed; with
 * `keepLog` (a camera change mid-run) the run log, plots and frame count go on.
 */
async function openTracker({ keepLog = false } = {}) {
  state.inFrame = null;
  const trackerId = state.trackerId;
  // (The worker's trackerDefaults(id) and trackerPreset(id, 'real-roads').)
  const presets = trackerId
    ? /** @type {{ paper: Record<string, unknown>, realRoads: Record<string, unknown> }} */ (await client.request('defaults', { trackerId }))
    : null;
  panel.show(trackerId, presets?.paper ?? null, presets?.realRoads ?? null);
  const options = { ...panel.changedOptions(), seed: panel.seedValue() };
  const camera = state.camera;
  if (!camera) throw new Error('No camera yet: open a source first.');
  // The top view follows the camera, the tracker or none.
  await client.request('openTopView', { camera });
  // (An id from the menu or the URL: the tracker refuses an unknown one with a LanepfConfigError.)
  if (trackerId) await client.open(/** @type {TrackerId} */ (trackerId), withCamera(options, camera));
  else await client.close();
  // The comparison tracker: the same preset (its own options in it), camera and seed.
  const compareId = trackerId ? state.compareId : '';
  const compare = compareId && panel.preset === 'real-roads'
    ? /** @type {{ realRoads: Record<string, unknown> }} */ (await client.request('defaults', { trackerId: compareId })).realRoads
    : {};
  await client.request('openCompare', {
    trackerId: compareId, config: withCamera({ ...compare, seed: options.seed }, camera),
  });
  demo.compareOptions = compare;
  controls.setStepNames(trackerId ? client.stepNames : []);
  showNames();
  el('plots-caption').textContent = plotsCaption(trackerId, state.hasTruth, plots.length,
    trackerId ? state.compareId : '');
  pacer.reset();
  demo.camera = state.camera;
  if (keepLog) return;
  Object.assign(demo, { frames: 0, lastEstimate: null, lastHypotheses: null, lastLayer: null });
  demo.results = [];
  demo.droppedResults = 0;
  demo.offsetErrors = [];
  plots.clear();
  departure.reset();
  controls.setExportable(false);
}

/** The camera for media without one: an imported file (rescaled), else the clip's, rescaled. */
/** @param {Source} source */
async function cameraFor(source) {
  if (!source.size) throw new Error(`${source.label}: no picture size`);
  const { width, height } = source.size;
  if (source.camera) return { camera: scaleCamera(source.camera, width, height), note: '' };
  if (state.importedCamera) {
    return { camera: scaleCamera(state.importedCamera, width, height), note: ' · camera: your file' };
  }
  const clip = await loadClipCamera();
  return {
    camera: scaleCamera(clip, width, height),
    note: ' · camera assumed: the Udacity clip’s, scaled, until auto-calibration measures yours (or import a camera.json)',
  };
}

/**
 * Opens the auto-calibrator for media (none for the simulator's sources). Its intrinsics: the
 * source's own camera (the bundled clip) or an imported camera file, scaled; else the
 * calibrator's field-of-view default. It applies its camera unless the user chose one.
 */
/**
 * @param {Source} source
 * @param {CameraConfig | null} userCamera
 */
async function startAuto(source, userCamera) {
  if (!source.size) {
    await client.request('openCalibrator', {});
    auto.start('off');
    return;
  }
  const { width, height } = source.size;
  const own = source.camera ? scaleCamera(source.camera, width, height) : null;
  const imported = state.importedCamera ? scaleCamera(state.importedCamera, width, height) : null;
  try {
    await client.request('openCalibrator', { width, height, intrinsics: own ?? imported });
    auto.start(own || userCamera || imported ? 'manual' : 'auto', { known: own });
  } catch (err) {
    auto.start('off', { error: err instanceof Error ? err.message : String(err) });
  }
}

/**
 * @param {Source | VideoFile} next
 * @param {string} name
 */
async function openSource(next, name) {
  // A video picks its reader as it opens: WebCodecs where it can, else seeking (video-select.js).
  if (next instanceof VideoFile) next = await next.pick();
  else await next.open();
  mark('video');
  state.source?.close();
  state.source = next;
  state.sourceName = name;
  showTruthControls(next instanceof SceneSource || next instanceof TestRoadSource);
  // Real footage starts from our real-roads options, the simulator from the paper's.
  panel.usePreset(state.hasTruth ? 'paper' : 'real-roads');
  demo.ended = false;
  demo.source = name;
  let note = '';
  if (next.size) {
    ({ camera: state.camera, note } = await cameraFor(next));
    await client.request('dropRight');
  } else {
    state.camera = next.camera ?? null;
  }
  if (!state.camera) throw new Error(`${next.label}: no camera`);
  const saved = calibration?.saved(name, state.camera.width, state.camera.height) ?? null;
  if (saved) {
    state.camera = saved;
    note = ' · camera: as you calibrated it for this source';
  }
  await startAuto(next, saved);
  mark('calibrator');
  autoToggle.checked = auto.mode === 'auto';
  autoToggle.disabled = auto.mode === 'off';
  showAuto();
  calibration?.show(state.camera, name);
  pacer.start(next.fps ?? null, { live: next instanceof WebcamSource });
  await openTracker();
  state.sourceStatus = next.label + note;
  controls.say(state.sourceStatus);
  controls.setProgress(next.progress ?? null);
}

/**
 * @param {string} value
 * @param {import('../pkg/web/lanepf.js').ScenarioInfo[]} scenarios
 */
async function sourceFor(value, scenarios) {
  if (value === 'clip') {
    return new VideoFile({ url: CLIP.url, name: CLIP.name, fps: CLIP.fps, camera: await loadClipCamera() });
  }
  if (value === 'webcam') return new WebcamSource();
  if (value === 'test-road') return new TestRoadSource(client);
  const scene = scenarios.find((s) => s.name === value);
  if (!scene) throw new Error(`unknown source ${value}`);
  return new SceneSource(client, scene.name, scene.description);
}

/** @param {File[]} files */
function filesSource(files) {
  const stereo = controls.stereo.checked;
  const videos = files.filter((f) => f.type.startsWith('video/') || /\.(mp4|webm|mov|mkv|ogv)$/i.test(f.name));
  if (videos.length > 1) throw new Error('Drop one video at a time (or a set of images).');
  if (videos.length === 1) {
    if (files.length > 1) throw new Error('Drop either one video or a set of images, not both.');
    return new VideoFile({ file: videos[0], name: videos[0].name, sideBySide: stereo });
  }
  return new ImageSource(files, { stereo });
}

/**
 * Ground truth exists for the simulator's sources only: elsewhere (the clip, your media, the
 * webcam) its control, caption and legend entry are hidden.
 */
/** @param {boolean} hasTruth */
function showTruthControls(hasTruth) {
  state.hasTruth = hasTruth;
  controls.setHasTruth(hasTruth);
  legend.update({ hasTruth, byGroup: controls.colourGroups.checked });
  el('caption').textContent = hasTruth
    ? 'Camera view: the estimate, the ground truth and the particles (colours below). Drop a video or images here.'
    : 'Camera view: the estimate and the particles (colours below). Drop a video or images here.';
}

/** The status line after the tracker changed: the source's description and the tracker. */
function sayTracking() {
  const trackers = [state.trackerId, state.compareId].filter(Boolean).join(' and ');
  controls.say(`${state.sourceStatus ?? state.source?.label ?? ''} · tracking with ${trackers || 'no tracker'}`);
}

let paceShown = 0;
/** The rate played at, and whether the tracker keeps up with the source (at most twice a second). */
function showPace(now = false) {
  const t = performance.now();
  if (!now && t - paceShown < 500) return;
  paceShown = t;
  const what = state.source instanceof SceneSource || state.source instanceof TestRoadSource ? 'the simulator'
    : state.source?.size && state.source.fps ? 'the video' : 'the source';
  paceText.textContent = controls.paused ? '' : pacer.describe(what);
  const behind = !controls.paused && pacer.behind();
  paceText.classList.toggle('warn', behind);
  paceText.dataset.behind = String(behind);
  demo.pace = { fps: pacer.fps, rate: pacer.rate(), behind, workMs: pacer.workMs() };
}

function redrawLast() {
  if (state.lastFrame?.rgba?.length) draw(state.lastFrame, state.lastResult, true);
}

async function main() {
  client = await connectWorker();
  const hello = /** @type {{ version: string, trackers: TrackerId[], scenarios: import('../pkg/web/lanepf.js').ScenarioInfo[] }} */ (
    await client.request('hello'));
  mark('hello');
  const { version, trackers, scenarios } = hello;
  const cameraPanel = new Calibration(document, byId('view', HTMLCanvasElement), await loadPresets());
  mark('presets');
  calibration = cameraPanel;
  demo.calibration = cameraPanel;
  cameraPanel.onRedraw = () => {
    if (state.lastFrame?.rgba?.length) draw(state.lastFrame, state.lastResult, true);
  };
  cameraPanel.onApply = (camera) => run(async () => {
    // A camera applied by hand wins over the auto-calibrated one.
    auto.setMode('manual');
    autoToggle.checked = false;
    showAuto();
    state.camera = camera;
    await openTracker();
    cameraPanel.save(camera);
    await refreshTopView();
    controls.say(`Camera applied: pitch ${camera.pitch_deg.toFixed(2)}°, yaw ${(camera.yaw_deg ?? 0).toFixed(2)}°, `
      + `height ${camera.height_m.toFixed(2)} m (remembered for this source).`);
  });
  controls.version.textContent = `lanepf ${version}`;
  controls.setTrackers(trackers);
  controls.setScenarios(scenarios);
  const first = firstSource;
  controls.source.value = first;
  controls.lastSource = first;
  // A source or tracker that fails to open leaves a message, not a dead page.
  await run(async () => openSource(await sourceFor(first, scenarios), first));
  mark('tracker');

  controls.onSource = (value) => run(async () => openSource(await sourceFor(value, scenarios), value));
  controls.onFiles = (files) => run(async () => {
    const name = files.length === 1 ? files[0].name : `${files.length} files`;
    await openSource(filesSource(files), name);
    controls.showSource('file:last', `Your file: ${name}`);
  });
  controls.onCameraFile = (file) => run(async () => {
    state.importedCamera = await readCameraFile(file);
    if (state.source?.size && !state.source.camera) {
      auto.setMode('manual');
      autoToggle.checked = false;
      showAuto();
      state.camera = scaleCamera(state.importedCamera, state.source.size.width, state.source.size.height);
      cameraPanel.show(state.camera, state.sourceName);
      await openTracker();
    }
    controls.say(`Camera “${file.name}” will be used for your videos, images and the webcam.`);
  });
  controls.onTracker = (id) => run(async () => {
    state.trackerId = id;
    await openTracker();
    // The status line spoke of the old tracker (a step it ran, say): back to the source's.
    sayTracking();
  });
  panel.onChange = () => run(openTracker);
  controls.onCompare = (id) => run(async () => {
    state.compareId = id;
    await openTracker();
    sayTracking();
  });
  autoToggle.addEventListener('change', () => run(async () => {
    auto.setMode(autoToggle.checked ? 'auto' : 'manual');
    // Back on: the estimate so far replaces the camera at once (if there is one yet).
    if (auto.mode === 'auto' && auto.estimate) await applyAuto('chosen');
    showAuto();
  }));
  showCalibration.addEventListener('change', redrawLast);
  controls.onStep = () => run(stepFrame);
  controls.onStepStage = () => run(stepStage);
  controls.onRestart = () => run(async () => {
    const source = state.source;
    if (!source) throw new Error('no source is open');
    source.restart();
    await client.request('resetTrackers');
    pacer.reset();
    state.inFrame = null;
    demo.results = [];
    demo.droppedResults = 0;
    demo.offsetErrors = [];
    demo.ended = false;
    plots.clear();
    departure.reset();
    controls.setExportable(false);
    controls.updateStageButton(null);
    controls.say(source.label);
  });
  controls.onExport = (format) => {
    const base = `lanepf-${state.trackerId || 'frames'}-${state.sourceName.replace(/[^\w.-]+/g, '_')}`;
    if (format === 'jsonl') download(`${base}.jsonl`, toJsonLines(demo.results), 'application/x-ndjson');
    else download(`${base}.csv`, toCsv(demo.results), 'text/csv');
    if (demo.droppedResults > 0) {
      controls.say(`The export holds the last ${demo.results.length} frames: ${demo.droppedResults} older ones `
        + 'were let go to bound the page\'s memory. Restart and export more often to keep them all.');
    }
  };
  controls.cueLayer.addEventListener('change', redrawLast);
  controls.colourGroups.addEventListener('change', () => {
    legend.update({ hasTruth: state.hasTruth, byGroup: controls.colourGroups.checked });
    redrawLast();
  });
  controls.showPlots.addEventListener('change', () => {
    el('plots-figure').hidden = !controls.showPlots.checked;
  });
  if (document.body.dataset.state !== 'error') document.body.dataset.state = 'running';

  // A frame the play loop queued behind another task (a camera change, say) is dropped if
  // that task paused the demo, e.g. with an error: the error stays on screen instead of the
  // next frame's redraw replacing it.
  // Frames start when the pacer says they are due (the source's frame rate, pacer.js), woken
  // by a timer: animation frames come late and irregularly on a busy machine, timers less so.
  const playFrame = async () => {
    if (controls.paused) return;
    const t0 = performance.now();
    pacer.begin(t0);
    await stepFrame();
    pacer.end(performance.now() - t0);
    showPace();
  };
  let playing = false;
  const tick = async () => {
    if (controls.paused) {
      if (playing) {
        // A pause is not a slow frame: the schedule starts afresh on Play.
        playing = false;
        pacer.reset();
        showPace(true);
      }
      setTimeout(tick, 30);
      return;
    }
    const wait = pacer.wait(performance.now());
    if (wait > 0) {
      setTimeout(tick, wait);
      return;
    }
    playing = true;
    await run(playFrame);
    setTimeout(tick, 0);
  };
  tick();
}

main().catch((err) => {
  document.body.dataset.state = 'error';
  controls.say(`Could not start: ${err.message}`, true);
});
