// ms/frame of one tracker's Tracker.step in the wasm package (pkg/web) under Node, without a
// browser: a quick check of WebAssembly speed while optimising (`make bench-browser` gives the
// figures in Chromium). Build the package first (`make pkg`).
//   node scripts/bench-node.mjs [TRACKER=liu-ppf] [FRAMES=60] [WIDTH=640] [HEIGHT=480] [SCENARIO=highway-curve]
import { readFileSync } from 'node:fs';

const [id = 'liu-ppf', frames = '60', width = '640', height = '480', scenario = 'highway-curve'] =
  process.argv.slice(2);
const [n, w, h] = [frames, width, height].map(Number);
const WARMUP = 5;
if (![n, w, h].every((v) => Number.isInteger(v) && v > 0) || n <= WARMUP) {
  console.error(`usage: node scripts/bench-node.mjs [TRACKER] [FRAMES > ${WARMUP}] [WIDTH] [HEIGHT] [SCENARIO]`);
  process.exit(2);
}
const pkg = new URL('../pkg/', import.meta.url);
const m = await import(new URL('web/lanepf.js', pkg));
m.initSync({ module: readFileSync(new URL('web/lanepf_bg.wasm', pkg)) });
// The frames come from the simulator's module (lanepf/sim).
const sim = await import(new URL('sim/lanepf_sim.js', pkg));
sim.initSync({ module: readFileSync(new URL('sim/lanepf_sim_bg.wasm', pkg)) });
const scene = new sim.Scene(scenario, { width: w, height: h, seed: 1 });
const rendered = Array.from({ length: n }, (_, f) => scene.render(f));
const tracker = new m.Tracker(id, { camera: scene.camera() });
const times = [];
rendered.forEach((rgba, f) => {
  const t0 = performance.now();
  tracker.step(rgba, w, h);
  if (f >= WARMUP) times.push(performance.now() - t0);
});
times.sort((a, b) => a - b);
const at = (q) => times[Math.min(times.length - 1, Math.floor(q * times.length))].toFixed(2);
console.log(`${id} ${scenario} ${w}x${h}, ${n} frames (first ${WARMUP} not timed), Node ${process.version}: `
  + `median ${at(0.5)} ms, p90 ${at(0.9)} ms`);
