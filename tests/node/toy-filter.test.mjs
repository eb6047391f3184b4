// The first lesson's 1-D particle filter (www/toy-filter.js) without a browser: the resampler
// against its definition, ESS, the stages in order, resampling only below the threshold, the
// same run for the same seed, and the filter finding the car from a uniform start.
import test from 'node:test';
import assert from 'node:assert/strict';
import { ToyFilter, STAGES, ess, systematic, rng } from '../../www/toy-filter.js';

test('ESS is N for equal weights and 1 when one particle holds everything', () => {
  assert.equal(ess([0.25, 0.25, 0.25, 0.25]), 4);
  assert.equal(ess([1, 0, 0, 0]), 1);
  assert.ok(Math.abs(ess([0.5, 0.5, 0, 0]) - 2) < 1e-12);
});

test('systematic resampling picks each particle about N w_i times, by its cumulative weight', () => {
  const w = [0.1, 0.6, 0.0, 0.3];
  // u = 0.05: the points 0.0125, 0.2625, 0.5125, 0.7625 fall in particles 0, 1, 1, 3.
  assert.deepEqual(systematic(w, 0.05), [0, 1, 1, 3]);
  const r = rng(3);
  const n = 1000;
  const many = Array.from({ length: n }, () => r.uniform());
  const sum = many.reduce((a, v) => a + v, 0);
  const weights = many.map((v) => v / sum);
  const counts = new Array(n).fill(0);
  for (const p of systematic(weights, r.uniform())) counts[p] += 1;
  // Systematic resampling keeps every count within one of N w_i.
  counts.forEach((c, i) => assert.ok(Math.abs(c - n * weights[i]) < 1 + 1e-9, `particle ${i}: ${c} vs ${n * weights[i]}`));
});

test('the stages run in order, resampling only when ESS falls below the threshold', () => {
  const f = new ToyFilter({ seed: 2 });
  assert.equal(f.nextStage, 'predict');
  const seen = [];
  let resampled = 0;
  let skipped = 0;
  for (let k = 0; k < 3 * 30; k++) {
    const out = f.advance();
    seen.push(out.stage);
    if (out.stage === 'resample') {
      assert.equal(out.resampled, out.ess < out.threshold, JSON.stringify(out));
      if (out.resampled) {
        resampled += 1;
        assert.ok(f.w.every((w) => Math.abs(w - 1 / f.w.length) < 1e-12), 'equal weights after resampling');
        assert.equal(f.parents.length, f.x.length);
      } else {
        skipped += 1;
      }
    }
  }
  assert.deepEqual(seen.slice(0, 6), [...STAGES, ...STAGES]);
  assert.equal(f.step, 30);
  assert.ok(resampled > 0 && skipped > 0, `both happen in 30 steps: ${resampled} resampled, ${skipped} skipped`);
});

test('the same seed gives the same run; the filter finds the car from a uniform start', () => {
  const run = (seed) => {
    const f = new ToyFilter({ seed });
    for (let s = 0; s < 40; s++) f.advanceStep();
    return f;
  };
  const [a, b] = [run(5), run(5)];
  assert.deepEqual(a.x, b.x);
  assert.equal(a.car, b.car);
  assert.notDeepEqual(run(6).x, a.x);
  for (const seed of [1, 2, 3, 4, 5]) {
    const f = run(seed);
    const d = Math.abs(f.estimate() - f.car);
    const error = Math.min(d, f.options.length - d);
    assert.ok(error < 3, `seed ${seed}: estimate ${f.estimate().toFixed(2)} vs car ${f.car.toFixed(2)}`);
  }
});
