// @ts-check
// Live plots of the estimate over the last frames: one strip per quantity, the estimate as a
// line, the second tracker's (compare mode) in pink, the ground truth (when the source has one)
// dashed, lee-cpf's raw particle-filter output before its Kalman smoother in orange, the latest
// values written beside. While a frame is stepped through stage by stage, its ESS and time so
// far are the newest point (ringed), redrawn after every stage. The ESS strip's threshold line
// and resampling ticks are what the tracker reported (`Tracker.resamplings()`).

const RAD_TO_DEG = 180 / Math.PI;

/** @typedef {import('../pkg/web/lanepf.js').LaneEstimate} LaneEstimate */
/**
 * A quantity plotted: its value `of` an estimate (or the truth) and the frame's result, lee-cpf's
 * `raw` value before its Kalman smoother, `truth: false` when the truth has none.
 * @typedef {{ name: string, unit: string, of: (e: LaneEstimate, r?: { trackMs?: number } | null) => number | undefined,
 *   raw?: (e: LaneEstimate) => number, truth?: false }} Series
 */
/**
 * The frame in progress, stepped through stage by stage (see `Plots.stage`).
 * @typedef {{ label?: string, ess?: number | null, trackMs?: number, resampled?: boolean, threshold?: number | null }} Live
 */

/**
 * `v` when it is a finite number, else null (a gap in the plot).
 * @param {unknown} v
 * @returns {number | null}
 */
const finite = (v) => (typeof v === 'number' && Number.isFinite(v) ? v : null);

/** The quantities plotted: name, unit, value of an estimate (or truth), and of a result. */
/** @type {Series[]} */
export const SERIES = [
  // lee-cpf: the raw cascade filter's output next to the Kalman-smoothed one.
  { name: 'lateral offset', unit: 'm', of: (e) => e.lateral_offset_m, raw: (e) => -e.state?.['lee.raw.y0'] },
  { name: 'heading', unit: 'deg', of: (e) => e.heading_rad * RAD_TO_DEG, raw: (e) => e.state?.['lee.raw.psi'] * RAD_TO_DEG },
  { name: 'curvature', unit: '1/km', of: (e) => e.curvature_per_m * 1000 },
  { name: 'lane width', unit: 'm', of: (e) => e.lane_width_m },
  { name: 'ESS', unit: 'particles', of: (e) => e.ess, truth: false },
  { name: 'time', unit: 'ms/frame', of: (e, r) => r?.trackMs, truth: false },
];

/** The ESS threshold line's colour and the resampled-frame ticks' colour. */
export const ESS_THRESHOLD_COLOUR = '#ffd54f';
export const RESAMPLED_COLOUR = '#ef5350';

/** The ring round the point of the frame being stepped through, and its label. */
export const LIVE_COLOUR = '#ffffff';

/** The second tracker's colour in the plots. */
export const COMPARE_COLOUR = '#f48fb1';

/**
 * The plots' caption: whose estimate is plotted (`trackerId`, '' for none), the second
 * tracker's (`compareId`, '' for none), the ground truth only for a source that has one,
 * lee-cpf's raw filter only for lee-cpf.
 * @param {string} trackerId
 * @param {boolean} hasTruth
 * @param {number} [length]
 * @param {string} [compareId]
 */
export function plotsCaption(trackerId, hasTruth, length = 300, compareId = '') {
  if (!trackerId) return 'No tracker: nothing to plot (choose one under Tracker)';
  const parts = [`${trackerId}’s estimate (blue)`];
  if (compareId) parts.push(`${compareId}’s (pink)`);
  if (hasTruth) parts.push('the ground truth (grey, dashed)');
  if (trackerId === 'lee-cpf') parts.push('its raw filter before the Kalman smoother (orange)');
  const list = parts.length > 1 ? `${parts.slice(0, -1).join(', ')} and ${parts.at(-1)}` : parts[0];
  const which = trackerId === 'lee-cpf' ? 'stage 1’s before it resamples' : 'the filter’s';
  const ess = `ESS: ${which}, the threshold N_thr the tracker reports testing it against (yellow, dashed; `
    + 'none when it resamples whatever the ESS) and a red tick on each frame it reports resampling; '
    + 'stepping, the frame in progress is ringed and redrawn after every stage';
  return `${list}, over the last ${length} frames. ${ess}`;
}

export class Plots {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {number} [length] frames shown
   */
  constructor(canvas, length = 300) {
    this.canvas = canvas;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('the plots canvas has no 2-D context');
    this.ctx = ctx;
    this.length = length;
    /** @type {Live | null} */
    this.live = null;
    /** @type {(number | null)[]} */
    this.threshold = [];
    /** @type {boolean[]} */
    this.resampled = [];
    // Per series: the estimate's values, the truth's, lee-cpf's raw ones, the second tracker's.
    /** @type {(number | null)[][]} */
    this.points = [];
    /** @type {(number | null)[][]} */
    this.truth = [];
    /** @type {(number | null)[][]} */
    this.raw = [];
    /** @type {(number | null)[][]} */
    this.other = [];
    this.clear();
  }

  clear() {
    // The frame being stepped through, stage by stage (null: none): see `stage`.
    this.live = null;
    // The ESS strip's threshold (particles, null: none) and whether each frame resampled.
    this.threshold = [];
    this.resampled = [];
    this.points = SERIES.map(() => []);
    this.truth = SERIES.map(() => []);
    this.raw = SERIES.map(() => []);
    this.other = SERIES.map(() => []);
    this.draw();
  }

  /**
   * Adds a frame's estimate (and truth, when known; `compare`, the second tracker's
   * { estimate, trackMs }, in compare mode; `resampling`, what the tracker reported of the
   * frame's resampling: { resampled, threshold }, resampling.js's `frameResampling`). Ends the
   * frame in progress, if one was being stepped through.
   * @param {LaneEstimate | null} estimate
   * @param {LaneEstimate | null | undefined} truth
   * @param {{ trackMs?: number } | null} result
   * @param {{ estimate: LaneEstimate | null, trackMs?: number } | null} [compare]
   * @param {{ resampled: boolean, threshold: number | null } | null} [resampling]
   */
  push(estimate, truth, result, compare = null, resampling = null) {
    this.live = null;
    const r = resampling;
    this.threshold.push(finite(r?.threshold));
    this.resampled.push(!!r?.resampled);
    if (this.threshold.length > this.length) {
      this.threshold.shift();
      this.resampled.shift();
    }
    SERIES.forEach((s, k) => {
      const v = estimate ? s.of(estimate, result) : null;
      const t = truth && s.truth !== false ? s.of(truth) : null;
      const raw = estimate && s.raw ? s.raw(estimate) : null;
      const o = compare?.estimate ? s.of(compare.estimate, compare) : null;
      this.points[k].push(finite(v));
      this.truth[k].push(finite(t));
      this.raw[k].push(finite(raw));
      this.other[k].push(finite(o));
      if (this.points[k].length > this.length) {
        for (const series of [this.points, this.truth, this.raw, this.other]) series[k].shift();
      }
    });
    this.draw();
  }

  /**
   * The frame in progress after a stage, drawn as the newest point until the frame ends
   * (`push`): `{ label, ess, trackMs, resampled, threshold }`: the step just run, the ESS of
   * the weights now, the frame's time so far, whether the tracker reported a resampling in the
   * frame so far and the threshold it tested. The other quantities are known at the frame's end.
   * @param {Live} live
   */
  stage(live) {
    this.live = live;
    this.draw();
  }

  /**
   * Series `k` with the frame in progress (if any) as its newest point, at most `length`.
   * @template T
   * @param {T[]} series
   * @param {T} value
   * @returns {T[]}
   */
  withLive(series, value) {
    if (!this.live) return series;
    return [...series, value].slice(-this.length);
  }

  draw() {
    const { ctx, canvas } = this;
    const live = this.live;
    /** @param {Series} s */
    const liveValue = (s) => (!live ? null : s.name === 'ESS' ? live.ess : s.name === 'time' ? live.trackMs : null);
    const threshold = this.withLive(this.threshold, finite(live?.threshold));
    const resampled = this.withLive(this.resampled, !!live?.resampled);
    const strip = canvas.height / SERIES.length;
    const left = 150;
    const w = canvas.width - left - 8;
    ctx.fillStyle = '#0b0e11';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.font = '12px system-ui, sans-serif';
    SERIES.forEach((s, k) => {
      const top = k * strip;
      const ess = s.name === 'ESS';
      const v = liveValue(s);
      const points = this.withLive(this.points[k], finite(v));
      const [truth, raw, other] = [this.truth[k], this.raw[k], this.other[k]].map((series) => this.withLive(series, null));
      const values = [...points, ...truth, ...raw, ...other,
        ...(ess ? threshold : [])].filter((x) => x !== null);
      let lo = Math.min(...values);
      let hi = Math.max(...values);
      if (!values.length) [lo, hi] = [0, 1];
      if (hi - lo < 1e-9) [lo, hi] = [lo - 0.5, hi + 0.5];
      const pad = 0.1 * (hi - lo);
      // Counts and times never go below zero: no padding under a zero floor.
      [lo, hi] = [lo >= 0 && lo - pad < 0 ? 0 : lo - pad, hi + pad];
      /** @param {number} v */
      const y = (v) => top + strip - 4 - ((v - lo) / (hi - lo)) * (strip - 8);
      /** @param {number} i */
      const x = (i) => left + (i / Math.max(1, this.length - 1)) * w;
      ctx.strokeStyle = '#222a31';
      ctx.beginPath();
      ctx.moveTo(0, top + strip - 0.5);
      ctx.lineTo(canvas.width, top + strip - 0.5);
      ctx.stroke();
      /**
       * @param {(number | null)[]} series
       * @param {string} colour
       * @param {number[]} dash
       */
      const line = (series, colour, dash) => {
        ctx.strokeStyle = colour;
        ctx.setLineDash(dash);
        ctx.beginPath();
        let pen = false;
        series.forEach((v, i) => {
          if (v === null) {
            pen = false;
            return;
          }
          if (pen) ctx.lineTo(x(i), y(v));
          else ctx.moveTo(x(i), y(v));
          pen = true;
        });
        ctx.stroke();
        ctx.setLineDash([]);
      };
      line(truth, '#8a949e', [4, 3]);
      line(raw, '#ff8a65', []);
      line(other, COMPARE_COLOUR, []);
      line(points, '#4fc3f7', []);
      // The frame in progress: its point ringed, so that each stage's change shows.
      const newest = points.at(-1);
      if (live && newest !== null && newest !== undefined) {
        ctx.strokeStyle = LIVE_COLOUR;
        ctx.beginPath();
        ctx.arc(x(points.length - 1), y(newest), 4, 0, 2 * Math.PI);
        ctx.stroke();
      }
      if (ess) {
        // The threshold N_thr (lee-cpf), dashed yellow, and a tick under every frame that
        // resampled.
        // The threshold now in force is drawn across the whole strip (2 px, so it shows
        // from the first frame), its value written at the right.
        const now = threshold.filter((t) => t !== null).at(-1);
        if (now !== undefined) {
          ctx.save();
          ctx.strokeStyle = ESS_THRESHOLD_COLOUR;
          ctx.lineWidth = 2;
          ctx.setLineDash([6, 4]);
          ctx.beginPath();
          ctx.moveTo(left, Math.round(y(now)));
          ctx.lineTo(canvas.width - 60, Math.round(y(now)));
          ctx.stroke();
          ctx.restore();
          ctx.fillStyle = ESS_THRESHOLD_COLOUR;
          ctx.fillText(`N_thr ${now.toFixed(0)}`, canvas.width - 56, Math.round(y(now)) + 4);
        }
        line(threshold, ESS_THRESHOLD_COLOUR, [6, 4]);
        ctx.fillStyle = RESAMPLED_COLOUR;
        resampled.forEach((done, i) => {
          if (done) ctx.fillRect(Math.round(x(i)) - 1, top + strip - 7, 2, 6);
        });
      }
      /** @param {(number | null)[]} series */
      const latest = (series) => {
        const last = series.filter((v) => v !== null).at(-1);
        return last === undefined ? '–' : last.toFixed(Math.abs(last) < 10 ? 3 : 1);
      };
      ctx.fillStyle = '#e6e9ec';
      ctx.fillText(`${s.name} (${s.unit})`, 6, top + 16);
      ctx.fillStyle = '#4fc3f7';
      ctx.fillText(latest(points), 6, top + 32);
      if (this.other[k].some((v) => v !== null)) {
        ctx.fillStyle = COMPARE_COLOUR;
        ctx.fillText(latest(this.other[k]), 72, top + 32);
      }
      ctx.fillStyle = '#8a949e';
      ctx.fillText(`${hi.toPrecision(3)} … ${lo.toPrecision(3)}`, 6, top + 48);
    });
    if (live) {
      // Which stage the newest point is after, at the top right.
      ctx.fillStyle = LIVE_COLOUR;
      const text = `frame in progress: after “${live.label}”`;
      ctx.fillText(text, canvas.width - 8 - ctx.measureText(text).width, 14);
    }
  }
}
