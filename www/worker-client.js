// @ts-check
// The page's side of the demo's worker (worker.js): the package's own client, `TrackerWorker`
// of lanepf/worker, connected to the demo's worker rather than the package's. The tracker is
// opened and closed with `open` / `close`; the demo's ops (scenes, the comparison tracker,
// the calibrator, a frame through everything) are `request(op, args, transfer)`. A rejected
// request's Error keeps lanepf's kind in `name` and, when the request carried a frame, hands
// its pixels back on `err.frame`.
import { TrackerWorker } from '../pkg/worker/index.js';

/** @type {Promise<TrackerWorker> | null} */
let connecting = null;

/**
 * Starts the demo's worker and the wasm module in it (no tracker yet), once: boot.js starts it
 * while the page's other modules load, main.js takes the same worker.
 */
export function connectWorker() {
  connecting ??= TrackerWorker.connect({
    worker: new Worker(new URL('./worker.js', import.meta.url), { type: 'module' }),
  });
  return connecting;
}

/**
 * A tracker config from the panel's options and the page's camera; a `camera` among the
 * options would be silently replaced, so it is refused.
 * @param {Record<string, unknown> | null | undefined} options
 * @param {import('../pkg/web/lanepf.js').CameraConfig} camera
 * @returns {import('../pkg/web/lanepf.js').TrackerConfig}
 */
export function withCamera(options, camera) {
  if (options && 'camera' in options) {
    throw Object.assign(new Error('tracker options: `camera` comes from the camera panel, not the options'),
      { name: 'LanepfConfigError' });
  }
  return { ...(options ?? {}), camera };
}
