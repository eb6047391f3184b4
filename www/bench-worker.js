// @ts-check
// The benchmark's worker: renders the frames of a scenario with the simulator's Scene (its own
// module, lanepf/sim), then steps
// each tracker over them as the demo does (the right frame for a stereo tracker, the car's
// motion from the ground truth for all, both in step's options; the named preset's options)
// and times each step with performance.now().
// Message in: the page's params; out: { type: 'progress' | 'version' | 'done' | 'error', ... }.
import init, { version, trackerIds, trackerPreset, Tracker } from '../pkg/web/lanepf.js';
import initSim, { Scene } from '../pkg/sim/lanepf_sim.js';

/** @typedef {import('../pkg/web/lanepf.js').StepOptions} StepOptions */
/** @typedef {import('../pkg/web/lanepf.js').EgoMotion} EgoMotion */
/**
 * The page's settings (bench.js `readParams`; names as the query string gave them: the Scene
 * and Tracker constructors refuse unknown ones).
 * @typedef {{ frames: number, width: number, height: number, scenario: import('../pkg/web/lanepf.js').ScenarioName,
 *   seed: number, warmup: number, trackers: import('../pkg/web/lanepf.js').TrackerId[] | null,
 *   preset: import('../pkg/web/lanepf.js').TrackerPreset }} BenchParams
 */

/**
 * The p-quantile of sorted numbers, as `lanepf bench` computes it (nearest rank on n - 1).
 * @param {number[]} sorted
 * @param {number} p
 */
const quantile = (sorted, p) => sorted[Math.round((sorted.length - 1) * p)];

/** @param {BenchParams} params */
async function bench({ frames, width, height, scenario, seed, warmup, trackers, preset }) {
  await Promise.all([init(), initSim()]);
  self.postMessage({ type: 'version', version: version() });
  const ids = trackers ?? trackerIds();
  const scene = new Scene(scenario, { width, height, seed });
  const camera = scene.camera();
  const left = [];
  const right = [];
  const motion = [];
  self.postMessage({ type: 'progress', text: `rendering ${frames} frames` });
  const t0 = performance.now();
  for (let f = 0; f < frames; f++) left.push(scene.render(f));
  const renderMs = (performance.now() - t0) / frames;
  for (let f = 0; f < frames; f++) {
    const s = scene.truth(f).state;
    motion.push({ t_s: s.t, speed_mps: s.speed_mps, yaw_rate: s.yaw_rate });
  }
  const rows = [];
  for (const id of ids) {
    self.postMessage({ type: 'progress', text: `running ${id}` });
    // The preset's options (the paper's are the defaults), as the demo passes them.
    const options = trackerPreset(id, preset);
    const tracker = new Tracker(id, { ...options, camera, seed });
    if (tracker.isStereo && right.length === 0) {
      for (let f = 0; f < frames; f++) right.push(scene.renderRight(f));
    }
    const ms = [];
    for (let f = 0; f < frames; f++) {
      const frame = { data: left[f], width, height };
      /** @type {StepOptions} */
      const stepOptions = { motion: motion[f] };
      if (tracker.isStereo) stepOptions.right = { data: right[f], width, height };
      const t = performance.now();
      tracker.step(frame, stepOptions);
      const dt = performance.now() - t;
      if (f >= warmup) ms.push(dt);
    }
    tracker.free();
    const mean = ms.reduce((a, b) => a + b, 0) / ms.length;
    ms.sort((a, b) => a - b);
    rows.push({ tracker: id, preset, options, width, height, frames: ms.length, median_ms: quantile(ms, 0.5),
      p95_ms: quantile(ms, 0.95), mean_ms: mean });
  }
  scene.free();
  return { version: version(), render_ms: renderMs, rows };
}

self.onmessage = ({ data }) => {
  bench(data).then(
    (result) => self.postMessage({ type: 'done', result }),
    (e) => self.postMessage({ type: 'error', error: String(e && e.message ? e.message : e) }),
  );
};
