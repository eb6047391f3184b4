// The demo's resampling report (www/resampling.js) and weight histogram (www/weights.js), pure
// parts without a browser: ESS from weights, which steps resample and how they decide, the step
// text with the numbers, lee-cpf's stages read from `particles()` rows.
import test from 'node:test';
import assert from 'node:assert/strict';
import { ess, weightsByGroup, resampleStep, thresholdFraction, decide, resampleText } from '../../www/resampling.js';
import { weightHistogram } from '../../www/weights.js';

test('ESS is N for equal weights, 1 for one heavy particle, and scale-free', () => {
  assert.equal(ess([0.25, 0.25, 0.25, 0.25]), 4);
  assert.equal(ess([1, 0, 0, 0]), 1);
  assert.ok(Math.abs(ess([2, 2, 2, 2]) - 4) < 1e-12);
  assert.ok(Math.abs(ess([0.5, 0.5, 0, 0]) - 2) < 1e-12);
  assert.equal(ess([]), 0);
});

test('which steps resample: lee-cpf by ESS per stage, the others every frame', () => {
  assert.deepEqual(resampleStep('lee-cpf', 'stage 1: estimate, resample if N_eff < N_thr'), { policy: 'ess', group: 1 });
  assert.deepEqual(resampleStep('lee-cpf', 'stage 2: estimate, resample if N_eff < N_thr'), { policy: 'ess', group: 2 });
  assert.deepEqual(resampleStep('lee-cpf', 'estimate, resample if N_eff < N_thr'), { policy: 'ess', group: 0 });
  assert.equal(resampleStep('lee-cpf', 'stage 1: weigh (DLD distance map, eqs. 27-33)'), null);
  assert.deepEqual(resampleStep('adachi-mmpf', 'resample'), { policy: 'always', group: 0 });
  assert.equal(resampleStep('adachi-mmpf', 'weigh: vote-histogram likelihood (eqs. 4-6)'), null);
  assert.equal(resampleStep('liu-ppf', 'linear part: random walk of rho, theta (eqs. 18-19)'), null);
  assert.equal(thresholdFraction('lee-cpf', { ess_threshold: 0.3 }), 0.3);
  assert.equal(thresholdFraction('adachi-mmpf', {}), null);
});

test('the step text carries the numbers the decision used', () => {
  assert.equal(resampleText(decide('ess', 394.2, 500, 0.5)), 'skipped: ESS 394 > 250');
  assert.equal(resampleText(decide('ess', 120.4, 500, 0.5)), 'resampled: ESS 120 < threshold 250');
  // Rounding never hides the side of the threshold.
  assert.equal(resampleText(decide('ess', 249.8, 500, 0.5)), 'resampled: ESS 249.8 < threshold 250.0');
  assert.equal(resampleText(decide('ess', 250, 500, 0.5)), 'skipped: ESS 250.0 ≥ 250.0');
  assert.equal(resampleText(decide('always', 37.6, 500, null)),
    'resampled: every frame (ESS 38 of 500; this tracker does not test it)');
});

test('lee-cpf rows split by stage; danescu reads the weight before the cluster', () => {
  // lee-cpf: stage, psi, y0, w, w', c, delta, weight.
  const lee = Float32Array.from([1, 0, 0, 0, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 0, 0, 0.5, 2, 0, 0, 0, 0, 0, 0, 1]);
  const g = weightsByGroup('lee-cpf', lee, 8);
  assert.deepEqual([...g.keys()], [1, 2]);
  assert.deepEqual([...g.get(1)], [0.5, 0.5]);
  // danescu: 11 parameters, the weight, the cluster.
  const row = (w, c) => [...new Array(11).fill(0), w, c];
  const d = weightsByGroup('danescu-mono', Float32Array.from([...row(0.25, 3), ...row(0.75, -1)]), 13);
  assert.deepEqual([...d.get(0)], [0.25, 0.75]);
});

test('the weight histogram puts equal weights in the bin of 1', () => {
  const { counts, hi } = weightHistogram(new Array(100).fill(0.01));
  assert.equal(hi, 2);
  assert.equal(counts.filter((c) => c > 0).length, 1);
  assert.equal(counts[15], 100);
});
