// Times every tracker in headless Chromium (the wasm package, on the page's main thread):
// renders FRAMES frames of a scenario with the package's own Scene, then steps each tracker
// over them and prints the median and 95th percentile ms/frame of Tracker.step.
// Usage (after `make pkg`): node scripts/bench-browser.mjs [FRAMES] [WIDTH] [HEIGHT] [SCENARIO]
import { start, open } from '../tests/e2e/browser.mjs';

const [frames = 60, width = 640, height = 480] = process.argv.slice(2, 5).map(Number);
const scenario = process.argv[5] ?? 'highway-curve';
const env = await start();
try {
  const { page, errors } = await open(env.browser, `${env.base}/index.html`);
  const rows = await page.evaluate(async ({ frames, width, height, scenario }) => {
    const m = await import('/pkg/web/lanepf.js');
    await m.default();
    const scene = new m.Scene(scenario, { width, height, seed: 1 });
    const images = [];
    const t0 = performance.now();
    for (let f = 0; f < frames; f++) images.push(scene.render(f).slice());
    const render = (performance.now() - t0) / frames;
    const out = [['scene render', render, render]];
    for (const id of m.trackerIds()) {
      const tracker = new m.Tracker(id, { camera: scene.camera(), seed: 1 });
      const ms = images.map((rgba) => {
        const t = performance.now();
        tracker.step(rgba, width, height);
        return performance.now() - t;
      }).slice(5).sort((a, b) => a - b);
      out.push([id, ms[Math.floor(ms.length / 2)], ms[Math.floor(ms.length * 0.95)]]);
      tracker.free();
    }
    return out;
  }, { frames, width, height, scenario });
  if (errors.length) throw new Error(errors.join('\n'));
  console.log(`${scenario} ${width}x${height}, ${frames} frames (first 5 not timed), Chromium`);
  console.log('tracker                 median ms   p95 ms');
  for (const [id, median, p95] of rows) {
    console.log(`${id.padEnd(22)} ${median.toFixed(2).padStart(10)} ${p95.toFixed(2).padStart(8)}`);
  }
} finally {
  await env.close();
}
