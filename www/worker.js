// The Web Worker that owns the WebAssembly module: it renders synthetic frames (the test road
// or a named simulator scenario) and runs the chosen tracker on them, so the page's main
// thread only draws.
// Protocol: { id, type, ...payload } (payload keys must not be `id` or `type`) -> { id, ok: true, result } | { id, ok: false, error }.
import init, { version, trackerIds, scenarios, Scene, TestRoad, Tracker } from '../pkg/web/lanepf.js';

const ready = init();
let road = null;
let tracker = null;

const handlers = {
  async hello() {
    return { version: version(), trackers: trackerIds(), scenarios: scenarios() };
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
  async openTracker({ trackerId, camera, options }) {
    tracker?.free();
    tracker = null;
    if (!trackerId) return { trackerId: null };
    tracker = new Tracker(trackerId, { ...(options ?? {}), camera });
    return { trackerId: tracker.id };
  },
  // `layers`: also return the tracker's cue pictures (Tracker.layers()) after the step.
  async renderFrame({ index, layers: withLayers = false }) {
    if (!road) throw new Error('no source is open: call openTestRoad or openScene first');
    const t0 = performance.now();
    const rgba = road.render(index);
    const ms = performance.now() - t0;
    const truth = road.truth(index);
    let estimate = null;
    let trackMs = 0;
    let layers = null;
    if (tracker) {
      // A stereo tracker gets the scene's right camera (the test road has none: its step
      // then throws an Error saying so); every tracker gets the car's motion from the truth
      // (only the Danescu trackers use it).
      if (tracker.isStereo && road.renderRight) {
        tracker.setRight(road.renderRight(index), road.width, road.height);
      }
      const s = truth?.state;
      if (s && Number.isFinite(s.t) && Number.isFinite(s.speed_mps) && Number.isFinite(s.yaw_rate)) {
        tracker.setEgoMotion({ t_s: s.t, speed_mps: s.speed_mps, yaw_rate: s.yaw_rate });
      }
      const t1 = performance.now();
      estimate = tracker.step(rgba, road.width, road.height);
      trackMs = performance.now() - t1;
      if (withLayers) layers = tracker.layers();
    }
    return {
      result: { rgba, width: road.width, height: road.height, truth, ms, estimate, trackMs, layers },
      transfer: [rgba.buffer],
    };
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
    self.postMessage({ id, ok: false, error: err?.message ?? String(err) });
  }
};
