// @ts-check
// The first lesson's particle filter: a car on a line, a noisy position sensor, N particles.
// One step of the filter is three stages, run one at a time so each can be looked at:
//   predict:  every particle moves by the car's commanded speed plus motion noise;
//             the car itself moves (by its speed plus its own noise) and the sensor reads
//             its position plus sensor noise: z = x + N(0, sigma_z^2);
//   weigh:    w_i proportional to w_i * exp(-(z - x_i)^2 / (2 sigma_z^2)), normalised;
//             ESS = 1 / sum(w_i^2), the number of particles that effectively carry the belief;
//   resample: only when ESS < threshold * N (degeneracy: a few particles hold all the weight):
//             systematic resampling draws N particles with probability w_i, each child
//             remembers its parent (for the animation), and the weights become 1/N.
// Pure and seeded: no DOM, the same seed gives the same run (tested in Node and the browser).

/** The stages of one step, in order. */
export const STAGES = /** @type {const} */ (['predict', 'weigh', 'resample']);

/** Defaults: a 100 m line, a car at 1 m per step, a sensor good to 4 m, 200 particles. */
export const DEFAULTS = {
  particles: 200, length: 100, speed: 1, sigmaMotion: 0.5, sigmaCar: 0.3, sigmaSensor: 4,
  essThreshold: 0.5, seed: 1,
};

/**
 * A small seeded generator (mulberry32) and standard normal draws (Box-Muller).
 * @param {number} seed
 */
export function rng(seed) {
  let a = seed >>> 0;
  const uniform = () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  const normal = () => {
    const u = Math.max(uniform(), 1e-12);
    return Math.sqrt(-2 * Math.log(u)) * Math.cos(2 * Math.PI * uniform());
  };
  return { uniform, normal };
}

/**
 * Effective sample size of normalised weights: 1 / sum(w^2).
 * @param {number[]} weights
 */
export function ess(weights) {
  let s = 0;
  for (const w of weights) s += w * w;
  return s > 0 ? 1 / s : 0;
}

/**
 * Systematic resampling: one uniform draw u in [0, 1/N), then the N points u + k/N pick the
 * particles whose cumulative weight they fall in. Returns each child's parent index.
 * @param {number[]} weights
 * @param {number} u
 */
export function systematic(weights, u) {
  const n = weights.length;
  /** @type {number[]} */
  const parents = new Array(n);
  let cumulative = weights[0];
  let i = 0;
  for (let k = 0; k < n; k++) {
    const point = (u + k) / n;
    while (point > cumulative && i < n - 1) cumulative += weights[++i];
    parents[k] = i;
  }
  return parents;
}

/** What `resample` did: whether it resampled, on which ESS and threshold, and how many distinct parents. */
/** @typedef {{ resampled: boolean, ess: number, threshold: number, distinct?: number }} ResampleOutcome */
/**
 * What a stage did (`advance`).
 * @typedef {{ stage: 'predict', car: number, reading: number } | { stage: 'weigh', ess: number }
 *   | ({ stage: 'resample' } & ResampleOutcome)} StageOutcome
 */

export class ToyFilter {
  /** @param {Partial<typeof DEFAULTS>} [options] */
  constructor(options = {}) {
    this.options = { ...DEFAULTS, ...options };
    // The state; `reset` sets it.
    this.random = rng(this.options.seed);
    this.car = 0;
    /** The last sensor reading (null before the first predict). */
    /** @type {number | null} */
    this.reading = null;
    this.step = 0;
    this.next = 0;
    /** The particles' positions and weights. */
    /** @type {number[]} */
    this.x = [];
    /** @type {number[]} */
    this.w = [];
    /** The last resampling's parent of each particle, and the particles before it (null: none). */
    /** @type {number[] | null} */
    this.parents = null;
    /** @type {number[] | null} */
    this.before = null;
    /** @type {ResampleOutcome | null} */
    this.lastResample = null;
    this.reset();
  }

  /** Back to step 0: the car at 10 % of the line, the particles spread evenly over all of it. */
  reset() {
    const o = this.options;
    this.random = rng(o.seed);
    this.car = 0.1 * o.length;
    this.reading = null;
    this.step = 0;
    this.next = 0; // index into STAGES
    this.x = Array.from({ length: o.particles }, () => this.random.uniform() * o.length);
    this.w = new Array(o.particles).fill(1 / o.particles);
    this.parents = null;
    this.before = null;
    this.lastResample = null;
  }

  get nextStage() {
    return STAGES[this.next];
  }

  /**
   * Runs the next stage; returns what it did ({ stage, ... }) for the page to tell.
   * @returns {StageOutcome}
   */
  advance() {
    const stage = STAGES[this.next];
    /** @type {StageOutcome} */
    const out = stage === 'predict' ? { stage, ...this.predict() }
      : stage === 'weigh' ? { stage, ...this.weigh() } : { stage, ...this.resample() };
    this.next = (this.next + 1) % STAGES.length;
    if (this.next === 0) this.step += 1;
    return out;
  }

  /** Runs the stages left in this step (a whole step from its start). */
  advanceStep() {
    const done = [];
    do done.push(this.advance()); while (this.next !== 0);
    return done;
  }

  predict() {
    const o = this.options;
    this.parents = null;
    this.car += o.speed + o.sigmaCar * this.random.normal();
    // The line wraps: a car that drives off the end comes back at the start (and so do they).
    /** @param {number} v */
    const wrap = (v) => ((v % o.length) + o.length) % o.length;
    this.car = wrap(this.car);
    this.x = this.x.map((v) => wrap(v + o.speed + o.sigmaMotion * this.random.normal()));
    this.reading = this.car + o.sigmaSensor * this.random.normal();
    return { car: this.car, reading: this.reading };
  }

  weigh() {
    const o = this.options;
    const z = this.reading;
    if (z === null) throw new Error('weigh: no reading yet (predict comes first)');
    // Distance on the wrapped line.
    /** @param {number} v */
    const d = (v) => {
      const a = Math.abs(v - z) % o.length;
      return Math.min(a, o.length - a);
    };
    const logs = this.x.map((v, k) => Math.log(this.w[k]) - (d(v) ** 2) / (2 * o.sigmaSensor ** 2));
    const top = Math.max(...logs);
    const raw = logs.map((l) => Math.exp(l - top));
    const sum = raw.reduce((a, v) => a + v, 0);
    this.w = raw.map((v) => v / sum);
    return { ess: ess(this.w) };
  }

  /** @returns {ResampleOutcome} */
  resample() {
    const o = this.options;
    const n = this.x.length;
    const e = ess(this.w);
    const threshold = o.essThreshold * n;
    if (e >= threshold) {
      this.parents = null;
      this.lastResample = { resampled: false, ess: e, threshold };
      return this.lastResample;
    }
    const parents = systematic(this.w, this.random.uniform());
    const before = this.x;
    this.before = before;
    this.parents = parents;
    this.x = parents.map((p) => before[p]);
    this.w = new Array(n).fill(1 / n);
    this.lastResample = { resampled: true, ess: e, threshold, distinct: new Set(parents).size };
    return this.lastResample;
  }

  /** The weighted mean position (on the wrapped line, around the heaviest particle). */
  estimate() {
    const L = this.options.length;
    let best = 0;
    for (let k = 1; k < this.w.length; k++) if (this.w[k] > this.w[best]) best = k;
    const centre = this.x[best];
    let m = 0;
    this.x.forEach((v, k) => {
      let d = v - centre;
      if (d > L / 2) d -= L;
      if (d < -L / 2) d += L;
      m += this.w[k] * d;
    });
    return (((centre + m) % L) + L) % L;
  }

  /** The weights summed over `bins` equal bins of the line (the weight histogram). */
  /** @param {number} bins */
  histogram(bins) {
    const L = this.options.length;
    /** @type {number[]} */
    const h = new Array(bins).fill(0);
    this.x.forEach((v, k) => {
      h[Math.min(bins - 1, Math.floor((v / L) * bins))] += this.w[k];
    });
    return h;
  }
}
