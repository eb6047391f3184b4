// @ts-check
// What the demo starts before its page modules have loaded (index.html runs this small module
// `async`, ahead of main.js and its 30-odd imports): the worker and the wasm module in it, the
// camera presets, and for the default source the bundled clip and its camera. main.js takes
// each of them from the same memoised calls (connectWorker, loadPresets, loadClipCamera) and
// the clip's bytes from prefetchVideo, so none of it waits for the page's module graph
// (`node scripts/bench-first-frame.mjs` measures the first tracked frame after navigation).
import { connectWorker } from './worker-client.js';
import { CLIP, loadClipCamera, loadPresets } from './camera-presets.js';
import { prefetchVideo } from './prefetch.js';

// Failures are main.js's to report, when it awaits the same promises.
connectWorker().then(() => performance.mark('lanepf:wasm'), () => {});
loadPresets().catch(() => {});
if ((new URLSearchParams(location.search).get('source') ?? 'clip') === 'clip') {
  loadClipCamera().catch(() => {});
  prefetchVideo(CLIP.url);
}
