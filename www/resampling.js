// @ts-check
// Resampling made visible, from what the tracker reports: each filter's decision as it made it
// (`Tracker.resamplings()`: the rule, the ESS it tested, the threshold, whether it resampled;
// src/filter/resampling_log.rs). Nothing here knows a tracker's rules: the step text and the
// ESS plot's marks say what the tracker did.

/** @typedef {import('../pkg/web/lanepf.js').ResampleDecision} ResampleDecision */

/**
 * Whole particles, unless that would hide which side of the threshold the ESS is on.
 * @param {number} ess
 * @param {number} threshold
 */
function pair(ess, threshold) {
  const digits = Math.round(ess) === Math.round(threshold) ? 1 : 0;
  return [ess.toFixed(digits), threshold.toFixed(digits)];
}

/**
 * The text of one decision: "skipped: ESS 394 > 250", "resampled: ESS 120 < threshold 250", ...
 * @param {ResampleDecision} d
 */
export function decisionText(d) {
  const of = `ESS ${Math.round(d.ess)} of ${d.particles}`;
  switch (d.rule) {
    case 'ess-below': {
      const threshold = d.threshold ?? NaN; // (a number for this rule, says the .d.ts)
      const [es, t] = pair(d.ess, threshold);
      if (d.resampled) return `resampled: ESS ${es} < threshold ${t}`;
      return `skipped: ESS ${es} ${d.ess > threshold ? '>' : '≥'} ${t}`;
    }
    case 'always':
      return `resampled: every time, whatever the ESS (${of})`;
    case 'injection':
      return `resampled: every frame, with fresh particles injected (${of})`;
    case 'between-stages':
      return `resampled between the partitions (${of})`;
    case 'never':
      return `not resampled: this filter never resamples (${of})`;
    default:
      return `${d.resampled ? 'resampled' : 'not resampled'} (${of})`;
  }
}

/**
 * The step text for the decisions one step reported (null for none): one decision's text, or
 * for a step of many (a first frame's start-up rounds) how many resampled and the last one's.
 * @param {ResampleDecision[] | null | undefined} decisions
 */
export function resampleText(decisions) {
  if (!decisions?.length) return null;
  if (decisions.length === 1) return decisionText(decisions[0]);
  const done = decisions.filter((d) => d.resampled).length;
  return `${decisions.length} resampling tests, ${done} resampled; the last: ${decisionText(decisions[decisions.length - 1])}`;
}

/**
 * A frame's resampling for the ESS plot, from every decision reported in it: whether any filter
 * resampled, and the threshold of the frame's first ESS test (null when none tested the ESS;
 * lee-cpf's stage 1 tests first).
 * @param {ResampleDecision[] | null | undefined} decisions
 */
export function frameResampling(decisions) {
  const tested = (decisions ?? []).find((d) => d.rule === 'ess-below');
  return { resampled: (decisions ?? []).some((d) => d.resampled), threshold: tested?.threshold ?? null };
}
