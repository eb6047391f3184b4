// `Tracker.resamplings()`: every tracker reports its filters' resampling decisions across the
// wasm boundary, as the filters made them (src/filter/resampling_log.rs), after each `step` and
// each `advance`. Checked against what each paper's schedule must give and against the
// tracker's own ESS in its estimate. Runs against the built package (`make pkg`).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import init, { Tracker } from '../../pkg/web/lanepf.js';
import initSim, { Scene } from '../../pkg/sim/lanepf_sim.js';

await init({ module_or_path: readFileSync(new URL('../../pkg/web/lanepf_bg.wasm', import.meta.url)) });
await initSim({ module_or_path: readFileSync(new URL('../../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });

const W = 320, H = 240;
const scene = new Scene('highway-straight', { width: W, height: H, seed: 1 });
const camera = scene.camera();
const frame = (f) => ({ data: scene.render(f), width: W, height: H });

/** Steps `tracker` through frame `f` one stage at a time: [{ name, decisions, estimate }]. */
function stepped(tracker, f) {
  tracker.beginFrame(frame(f));
  assert.deepEqual(tracker.resamplings(), [], 'beginFrame resamples nothing');
  const names = tracker.stepNames();
  const out = [];
  for (;;) {
    const name = names[tracker.nextStep];
    const estimate = tracker.advance();
    out.push({ name, decisions: tracker.resamplings(), estimate });
    if (estimate) return out;
  }
}

test('lee-cpf: each stage tests its ESS against N_thr = N/2, the ESS of its estimate', () => {
  const tracker = new Tracker('lee-cpf', { camera, particles: 400, seed: 1 });
  for (let f = 0; f < 3; f++) tracker.step(frame(f));
  const steps = stepped(tracker, 3);
  const state = steps.at(-1).estimate.state;
  const testing = steps.filter((s) => s.decisions.length);
  assert.deepEqual(testing.map((s) => s.name), [
    'stage 1: estimate, resample if N_eff < N_thr', 'stage 2: estimate, resample if N_eff < N_thr',
  ]);
  testing.forEach((s, k) => {
    assert.equal(s.decisions.length, 1);
    const [d] = s.decisions;
    assert.equal(d.rule, 'ess-below');
    assert.equal(d.threshold, d.particles / 2);
    assert.equal(d.resampled, d.ess < d.threshold);
    assert.ok(Math.abs(d.ess - state[`lee.ess${k + 1}`]) < 1e-9, `stage ${k + 1}: ${d.ess} vs ${state[`lee.ess${k + 1}`]}`);
  });
  // A whole step reports the same two, in order; a threshold option moves the threshold.
  tracker.step(frame(4));
  assert.deepEqual(tracker.resamplings().map((d) => d.rule), ['ess-below', 'ess-below']);
  const strict = new Tracker('lee-cpf', { camera, particles: 400, seed: 1, ess_threshold: 0.9 });
  strict.step(frame(0));
  strict.step(frame(1));
  const d = strict.resamplings();
  assert.ok(d.every((x) => x.threshold === 0.9 * x.particles), JSON.stringify(d));
  strict.reset();
  assert.deepEqual(strict.resamplings(), [], 'reset forgets them');
  tracker.free();
  strict.free();
});

test('adachi-mmpf: nothing to resample on the first frame, then every frame', () => {
  const tracker = new Tracker('adachi-mmpf', { camera, particles: 300, seed: 1, start_iterations: 0 });
  const first = stepped(tracker, 0);
  assert.equal(first[0].name, 'resample');
  assert.deepEqual(first[0].decisions, [], 'the first frame has no weights to resample from');
  const second = stepped(tracker, 1);
  assert.equal(second[0].decisions.length, 1);
  const [d] = second[0].decisions;
  assert.deepEqual({ rule: d.rule, threshold: d.threshold, resampled: d.resampled, particles: d.particles },
    { rule: 'always', threshold: null, resampled: true, particles: 300 });
  assert.ok(d.ess > 0 && d.ess <= 300);
  for (const s of second.slice(1)) assert.deepEqual(s.decisions, [], `${s.name} does not resample`);
  tracker.free();
});

test('liu-ppf: injection at the start of a frame, then between the partitions', () => {
  const tracker = new Tracker('liu-ppf', { camera, seed: 1 });
  tracker.step(frame(0));
  tracker.step(frame(1));
  const rules = tracker.resamplings().map((d) => d.rule);
  assert.deepEqual(rules, ['injection', 'between-stages']);
  assert.ok(tracker.resamplings().every((d) => d.resampled && d.threshold === null));
  tracker.free();
});

test('danescu-mono: injection every frame; a call that throws leaves none', () => {
  const tracker = new Tracker('danescu-mono', { camera, particles: 200, seed: 1 });
  tracker.step(frame(0));
  tracker.step(frame(1));
  assert.deepEqual(tracker.resamplings().map((d) => [d.rule, d.resampled]), [['injection', true]]);
  assert.throws(() => tracker.advance(), { name: 'LanepfStateError' });
  assert.deepEqual(tracker.resamplings(), []);
  tracker.free();
});
