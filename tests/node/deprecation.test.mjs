// The deprecated per-frame setters (`setRight`, `setEgoMotion`) still work and say once, in
// console.warn, what replaces them: one warning per call name for the whole module, however
// many trackers and frames use them. Its own file: the "once" is per loaded module, so no
// other test may have called them first. Runs against the built package (`make pkg`).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import init, { Tracker } from '../../pkg/web/lanepf.js';
import initSim, { Scene } from '../../pkg/sim/lanepf_sim.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });

const W = 160, H = 120;
const scene = new Scene('highway-curve', { width: W, height: H, seed: 3 });

test('setRight and setEgoMotion warn once each, naming step(frame, { right, motion })', () => {
  const warnings = [];
  const original = console.warn;
  console.warn = (...args) => warnings.push(args.join(' '));
  try {
    const trackers = [1, 2].map((seed) => new Tracker('danescu-stereo', { camera: scene.camera(), seed }));
    for (const tracker of trackers) {
      for (let f = 0; f < 3; f++) {
        const s = scene.truth(f).state;
        tracker.setRight(scene.renderRight(f), W, H);
        tracker.setEgoMotion({ t_s: s.t, speed_mps: s.speed_mps, yaw_rate: s.yaw_rate });
        assert.equal(typeof tracker.step(scene.render(f), W, H).valid, 'boolean');
      }
    }
    // A refused call warns no more than an accepted one.
    const mono = new Tracker('adachi-mmpf', { camera: scene.camera() });
    assert.throws(() => mono.setRight(scene.renderRight(0), W, H), /danescu-stereo/);
  } finally {
    console.warn = original;
  }
  assert.equal(warnings.length, 2, warnings.join('\n'));
  assert.match(warnings.find((w) => w.includes('setRight')) ?? '', /deprecated.*step\(left, \{ right \}\)/);
  assert.match(warnings.find((w) => w.includes('setEgoMotion')) ?? '', /deprecated.*step\(frame, \{ motion \}\)/);
});
