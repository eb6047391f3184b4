// The package's two wasm modules (issue 21 part 5): the main one (`lanepf`, pkg/web/) has the
// trackers, the camera and the calibrator and no simulator; the simulator's (`lanepf/sim`,
// pkg/sim/) has `Scene`, `TestRoad` and `scenarios()` and no tracker. A scene's frames and
// camera go into a tracker of the other module as plain values. Runs against `make pkg`.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, statSync } from 'node:fs';
import init, * as lanepf from '../../pkg/web/lanepf.js';
import initSim, * as sim from '../../pkg/sim/lanepf_sim.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });

const SIM = ['Scene', 'TestRoad', 'scenarios'];
const MAIN = ['Camera', 'Tracker', 'Calibrator', 'trackerIds', 'trackerDefaults', 'trackerPreset'];

test('the main module exports no simulator, the simulator no tracker', () => {
  for (const name of SIM) {
    assert.equal(lanepf[name], undefined, `lanepf exports ${name}`);
    assert.equal(typeof sim[name], 'function', `lanepf/sim lacks ${name}`);
  }
  for (const name of MAIN) {
    assert.equal(typeof lanepf[name], 'function', `lanepf lacks ${name}`);
    assert.equal(sim[name], undefined, `lanepf/sim exports ${name}`);
  }
  assert.equal(sim.version(), lanepf.version());
  const dts = readFileSync(new URL('../../pkg/web/lanepf.d.ts', import.meta.url), 'utf8');
  assert.doesNotMatch(dts, /export class (Scene|TestRoad)\b|export function scenarios\b/);
  const simDts = readFileSync(new URL('../../pkg/sim/lanepf_sim.d.ts', import.meta.url), 'utf8');
  assert.match(simDts, /export class Scene\b/);
  assert.doesNotMatch(simDts, /export class (Tracker|Camera|Calibrator)\b/);
});

test('a scene of lanepf/sim feeds a tracker of lanepf', () => {
  const scene = new sim.Scene('highway-straight', { width: 160, height: 120, seed: 1 });
  const tracker = new lanepf.Tracker('lee-cpf', { camera: scene.camera(), particles: 100 });
  for (let f = 0; f < 3; f++) {
    const lane = tracker.step({ data: scene.render(f), width: scene.width, height: scene.height });
    assert.equal(typeof lane.valid, 'boolean');
  }
  assert.equal(sim.scenarios().length, 12);
  // Bad input in the simulator's module is a thrown, named Error there too.
  assert.throws(() => new sim.Scene('nope'), (e) => e.name === 'LanepfConfigError');
  tracker.free();
  scene.free();
});

test('the main module is the smaller one', () => {
  const main = statSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)).size;
  const simSize = statSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)).size;
  assert.ok(main > 0 && simSize > 0);
  assert.ok(simSize < main, `sim ${simSize} >= main ${main}`);
});
