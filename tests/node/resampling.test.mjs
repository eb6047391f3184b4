// The demo's resampling report (www/resampling.js), its particle weights (www/particle-weights.js)
// and weight histogram (www/weights.js), pure parts without a browser: ESS from weights, the
// step text and the ESS plot's marks from the decisions a tracker reports
// (`Tracker.resamplings()`), lee-cpf's stages read from `particles()` rows.
import test from 'node:test';
import assert from 'node:assert/strict';
import { decisionText, resampleText, frameResampling } from '../../www/resampling.js';
import { ess, weightsByGroup, weighing } from '../../www/particle-weights.js';
import { weightHistogram } from '../../www/weights.js';

const tested = (e, n, fraction) => ({ rule: 'ess-below', ess: e, particles: n, threshold: fraction * n, resampled: e < fraction * n });

test('ESS is N for equal weights, 1 for one heavy particle, and scale-free', () => {
  assert.equal(ess([0.25, 0.25, 0.25, 0.25]), 4);
  assert.equal(ess([1, 0, 0, 0]), 1);
  assert.ok(Math.abs(ess([2, 2, 2, 2]) - 4) < 1e-12);
  assert.ok(Math.abs(ess([0.5, 0.5, 0, 0]) - 2) < 1e-12);
  assert.equal(ess([]), 0);
});

test('the step text says what the tracker reported, with its numbers', () => {
  assert.equal(decisionText(tested(394.2, 500, 0.5)), 'skipped: ESS 394 > 250');
  assert.equal(decisionText(tested(120.4, 500, 0.5)), 'resampled: ESS 120 < threshold 250');
  // Rounding never hides the side of the threshold.
  assert.equal(decisionText(tested(249.8, 500, 0.5)), 'resampled: ESS 249.8 < threshold 250.0');
  assert.equal(decisionText(tested(250, 500, 0.5)), 'skipped: ESS 250.0 ≥ 250.0');
  // The text follows the reported decision, not a rule of its own: a tracker that reports a
  // skipped resampling below the threshold would be said so.
  assert.equal(decisionText({ ...tested(120, 500, 0.5), resampled: false }), 'skipped: ESS 120 ≥ 250');
  const always = { rule: 'always', ess: 37.6, particles: 500, threshold: null, resampled: true };
  assert.equal(decisionText(always), 'resampled: every time, whatever the ESS (ESS 38 of 500)');
  assert.equal(decisionText({ ...always, rule: 'injection' }),
    'resampled: every frame, with fresh particles injected (ESS 38 of 500)');
  assert.equal(decisionText({ ...always, rule: 'between-stages', particles: 200 }),
    'resampled between the partitions (ESS 38 of 200)');
  assert.equal(resampleText([]), null);
  assert.equal(resampleText(undefined), null);
  assert.equal(resampleText([tested(394.2, 500, 0.5)]), 'skipped: ESS 394 > 250');
  assert.equal(resampleText([always, { ...always, resampled: false, rule: 'never' }, always]),
    '3 resampling tests, 2 resampled; the last: resampled: every time, whatever the ESS (ESS 38 of 500)');
});

test('a frame is marked resampled when any decision resampled; its threshold is the first tested', () => {
  assert.deepEqual(frameResampling([]), { resampled: false, threshold: null });
  assert.deepEqual(frameResampling([tested(394, 500, 0.5), tested(100, 400, 0.5)]), { resampled: true, threshold: 250 });
  assert.deepEqual(frameResampling([tested(394, 500, 0.5)]), { resampled: false, threshold: 250 });
  assert.deepEqual(frameResampling([{ rule: 'injection', ess: 3, particles: 9, threshold: null, resampled: true }]),
    { resampled: true, threshold: null });
});

test('lee-cpf rows split by stage; danescu reads the weight before the cluster', () => {
  // lee-cpf: stage, psi, y0, w, w', c, delta, weight.
  const lee = Float32Array.from([1, 0, 0, 0, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 0, 0, 0.5, 2, 0, 0, 0, 0, 0, 0, 1]);
  const g = weightsByGroup('lee-cpf', lee, 8);
  assert.deepEqual([...g.keys()], [1, 2]);
  assert.deepEqual([...g.get(1)], [0.5, 0.5]);
  const w = weighing(g, 1);
  assert.deepEqual({ n: w.weights.length, count: w.count, ess: w.ess, group: w.group }, { n: 2, count: 3, ess: 2, group: 1 });
  // danescu: 11 parameters, the weight, the cluster.
  const row = (x, c) => [...new Array(11).fill(0), x, c];
  const d = weightsByGroup('danescu-mono', Float32Array.from([...row(0.25, 3), ...row(0.75, -1)]), 13);
  assert.deepEqual([...d.get(0)], [0.25, 0.75]);
});

test('the weight histogram puts equal weights in the bin of 1', () => {
  const { counts, hi } = weightHistogram(new Array(100).fill(0.01));
  assert.equal(hi, 2);
  assert.equal(counts.filter((c) => c > 0).length, 1);
  assert.equal(counts[15], 100);
});
