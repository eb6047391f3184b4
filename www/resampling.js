// Resampling made visible: the particles' weights as the tracker holds them, their effective
// sample size (ESS) and, for a resampling step, whether the tracker resampled and why. The ESS
// is computed from the weights `particles()` returns (the same normalised weights the tracker's
// own ESS uses: lee-cpf reports it as `lee.ess1` / `lee.ess2`, checked by the browser tests).
//
// Policies (src/filter/resample.rs): lee-cpf resamples a stage when its ESS falls below
// N_thr = ess_threshold · N (Lee, Algorithm 1); adachi-mmpf, liu-ppf and the danescu trackers
// resample on every frame whatever the ESS.

/** Effective sample size of weights: (Σw)² / Σw² (N for equal weights, 1 for one heavy). */
export function ess(weights) {
  let s = 0;
  let s2 = 0;
  for (const w of weights) {
    s += w;
    s2 += w * w;
  }
  return s2 > 0 ? (s * s) / s2 : 0;
}

/** Index of the weight in a particle's row of `particles()` (danescu: the cluster follows it). */
function weightIndex(trackerId, stride) {
  return trackerId.startsWith('danescu') ? stride - 2 : stride - 1;
}

/**
 * The weights of the particles by group: lee-cpf's stage (column 0: 1, 2, or 0 for a one-stage
 * variant), one group (0) for the others. Returns Map group -> Float64Array.
 */
export function weightsByGroup(trackerId, particles, stride) {
  const lists = new Map();
  const wi = weightIndex(trackerId, stride);
  const staged = trackerId === 'lee-cpf';
  for (let i = 0; i + stride <= particles.length; i += stride) {
    const g = staged ? particles[i] : 0;
    if (!lists.has(g)) lists.set(g, []);
    lists.get(g).push(particles[i + wi]);
  }
  return new Map([...lists].map(([g, w]) => [g, Float64Array.from(w)]));
}

/**
 * Whether step `name` of `trackerId` resamples, and how it decides: null for a step that does
 * not; { policy: 'ess', group } (lee-cpf: when the stage's ESS < N_thr) or
 * { policy: 'always', group }.
 */
export function resampleStep(trackerId, name) {
  if (!name) return null;
  if (trackerId === 'lee-cpf') {
    if (!name.includes('resample if N_eff < N_thr')) return null;
    return { policy: 'ess', group: name.startsWith('stage 2') ? 2 : name.startsWith('stage 1') ? 1 : 0 };
  }
  return /^resample/.test(name) ? { policy: 'always', group: 0 } : null;
}

/** The ESS threshold fraction of a tracker with options `options` (null: no threshold). */
export function thresholdFraction(trackerId, options) {
  return trackerId === 'lee-cpf' ? Number(options?.ess_threshold ?? 0.5) : null;
}

/**
 * What a resampling step did, from the ESS before it: { policy, ess, n, threshold, resampled }
 * (threshold in particles, null when the tracker resamples every frame).
 */
export function decide(policy, essBefore, n, fraction) {
  if (policy === 'ess') {
    const threshold = fraction * n;
    return { policy, ess: essBefore, n, threshold, resampled: essBefore < threshold };
  }
  return { policy, ess: essBefore, n, threshold: null, resampled: true };
}

/** The step text for a decision: "resampled: ESS 120 < threshold 250" or "skipped: ESS 394 > 250". */
export function resampleText(d) {
  const e = Math.round(d.ess);
  if (d.threshold === null) {
    return `resampled: every frame (ESS ${e} of ${d.n}; this tracker does not test it)`;
  }
  // Whole particles, unless that would hide which side of the threshold the ESS is on.
  const digits = Math.round(d.ess) === Math.round(d.threshold) ? 1 : 0;
  const [es, t] = [d.ess.toFixed(digits), d.threshold.toFixed(digits)];
  if (d.resampled) return `resampled: ESS ${es} < threshold ${t}`;
  return `skipped: ESS ${es} ${d.ess > d.threshold ? '>' : '≥'} ${t}`;
}
