// The Web Worker that owns the WebAssembly module: it renders synthetic frames (the test road
// or a named simulator scenario) and (as the
// trackers land) runs them, so the page's main thread only draws.
// Protocol: { id, type, ...payload } -> { id, ok: true, result } | { id, ok: false, error }.
import init, { version, trackerIds, scenarios, Scene, TestRoad } from '../pkg/web/lanepf.js';

const ready = init();
let road = null;

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
  async renderFrame({ index }) {
    if (!road) throw new Error('no source is open: call openTestRoad or openScene first');
    const t0 = performance.now();
    const rgba = road.render(index);
    const ms = performance.now() - t0;
    const truth = road.truth(index);
    return { result: { rgba, width: road.width, height: road.height, truth, ms }, transfer: [rgba.buffer] };
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
