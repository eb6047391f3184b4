// @ts-check
// The particles' weights as the tracker holds them, read from `particles()` rows (the layout
// each tracker documents in src/wasm/tracker.rs), and their effective sample size: what the
// weight histogram draws. The ESS here is measured from the weights, for the histogram's
// label; whether a tracker resampled, and on which ESS, is what the tracker reports
// (`Tracker.resamplings()`, see resampling.js).

/**
 * Effective sample size of weights: (Σw)² / Σw² (N for equal weights, 1 for one heavy).
 * @param {Iterable<number>} weights
 */
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
/**
 * @param {string} trackerId
 * @param {number} stride
 */
function weightIndex(trackerId, stride) {
  return trackerId.startsWith('danescu') ? stride - 2 : stride - 1;
}

/**
 * The weights of the particles by group: lee-cpf's stage (column 0: 1, 2, or 0 for a one-stage
 * variant), one group (0) for the others. Returns Map group -> Float64Array.
 * @param {string} trackerId
 * @param {ArrayLike<number>} particles `particles()`: `stride` numbers per particle
 * @param {number} stride
 * @returns {Map<number, Float64Array>}
 */
export function weightsByGroup(trackerId, particles, stride) {
  /** @type {Map<number, number[]>} */
  const lists = new Map();
  const wi = weightIndex(trackerId, stride);
  const staged = trackerId === 'lee-cpf';
  for (let i = 0; i + stride <= particles.length; i += stride) {
    const g = staged ? particles[i] : 0;
    let list = lists.get(g);
    if (!list) lists.set(g, (list = []));
    list.push(particles[i + wi]);
  }
  return new Map([...lists].map(([g, w]) => [g, Float64Array.from(w)]));
}

/**
 * What the weight histogram draws: the weights of `group` (the first group when it has none),
 * the total particle count over the groups and their ESS.
 * @param {Map<number, Float64Array>} groups
 * @param {number | null} [group]
 */
export function weighing(groups, group = null) {
  const weights = (group === null ? undefined : groups.get(group)) ?? groups.values().next().value ?? new Float64Array(0);
  let count = 0;
  for (const w of groups.values()) count += w.length;
  return { weights: Float32Array.from(weights), count, ess: ess(weights), group };
}
