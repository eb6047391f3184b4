// @ts-check
// Each tracker's belief as its paper draws it, from the particles (`particles()` rows, see
// src/wasm/tracker.rs) and the estimate: weighted histograms of the state the paper reasons
// about, one panel per partition or stage, with axes and units.
//   adachi-mmpf: the edge-vote histogram H_j over ρ (m), then the lane position q (m) stacked by
//                model r, with the model probabilities P(r);
//   lee-cpf: stage 1's y0 (m), then stage 2's curvature δ (1/km), each with the cascade's raw
//            output (orange) and the Kalman output (white) marked;
//   liu-ppf: the linear partition's ρ (px) of each boundary, then the parabolic partition's d;
//   danescu-*: the lateral offset X_CW (m), stacked by MBSAS cluster (dark grey: initialisation).
import { groupColour } from './render.js';

const DEFAULT_BINS = 40;

/**
 * One panel of a belief view: a weighted histogram of `items`, lines at `markers`, and what
 * the colours mean.
 * @typedef {{ title: string, unit: string, items: { value: number, weight: number, group: number }[],
 *   markers: { value: number, colour: string, label: string }[], probabilities?: number[] | null,
 *   colours?: string, bins?: number, range?: [number, number] }} Panel
 */

/**
 * Rows of `particles` (stride numbers each) as arrays.
 * @param {Float32Array} particles
 * @param {number} stride
 */
function rows(particles, stride) {
  /** @type {Float32Array[]} */
  const out = [];
  for (let i = 0; i + stride <= particles.length; i += stride) out.push(particles.subarray(i, i + stride));
  return out;
}

/**
 * The panels of `trackerId`'s belief: [{ title, unit, items: [{ value, weight, group }],
 * markers: [{ value, colour, label }], probabilities, colours (what the colours mean) }] (empty for an unknown layout).
 * @param {string} trackerId
 * @param {Float32Array} particles
 * @param {number} stride
 * @param {import('../pkg/web/lanepf.js').LaneEstimate | null | undefined} estimate
 * @param {import('../pkg/web/lanepf.js').Layer[] | null} [layers]
 * @returns {Panel[]}
 */
export function beliefPanels(trackerId, particles, stride, estimate, layers = null) {
  const r = rows(particles, stride);
  const st = estimate?.state ?? {};
  if (trackerId === 'adachi-mmpf') {
    const p = estimate?.model_probabilities ?? [NaN, NaN, NaN, NaN];
    // The vote histogram as the tracker binned it (its own bins, not re-binned).
    const votes = layers?.find((l) => l.kind === 'histogram');
    /** @type {Panel[]} */
    const histogram = votes ? [{
      title: `${votes.name} over ρ (Adachi Sec. 3.2, eq. 4)`, unit: 'm, ρ positive right',
      items: Array.from(votes.values, (v, k) => ({ value: votes.start + (k + 0.5) * votes.step, weight: v, group: 0 })),
      bins: votes.values.length,
      range: [votes.start, votes.start + votes.values.length * votes.step],
      markers: [],
    }] : [];
    return [...histogram, {
      title: 'lane position q by model r (Adachi Sec. 3)', unit: 'm', colours: 'colour: the model r, as the P(r) bars',
      items: r.map((x) => ({ value: x[1], weight: x[3], group: x[0] })),
      markers: [],
      probabilities: p.every(Number.isFinite) ? p : null,
    }];
  }
  if (trackerId === 'lee-cpf') {
    // The cascade's raw output and the Kalman-smoothed state, as the tracker reports them.
    const panels = [{
      title: 'stage 1: lane offset y₀ (Lee eqs. 21-33)', unit: 'm', colours: 'lines: the cascade’s raw output (orange) and the Kalman output (white)',
      items: r.filter((x) => x[0] !== 2).map((x) => ({ value: x[2], weight: x[7], group: 1 })),
      markers: [
        { value: st['lee.raw.y0'], colour: '#ff8a65', label: 'cascade output' },
        { value: st['lee.y0'], colour: '#ffffff', label: 'Kalman output' },
      ],
    }];
    const two = r.filter((x) => x[0] === 2);
    if (two.length) {
      panels.push({
        title: 'stage 2: curvature δ (far Canny edges)', unit: '1/km', colours: 'lines as above',
        items: two.map((x) => ({ value: 1000 * x[6], weight: x[7], group: 2 })),
        markers: [
          { value: 1000 * st['lee.raw.delta'], colour: '#ff8a65', label: 'cascade output' },
          { value: 1000 * st['lee.delta'], colour: '#ffffff', label: 'Kalman output' },
        ],
      });
    }
    return panels;
  }
  if (trackerId.startsWith('liu-ppf')) {
    const boundaries = Math.floor((stride - 1) / 3);
    const lin = [];
    const par = [];
    for (const x of r) {
      for (let b = 0; b < boundaries; b++) {
        lin.push({ value: x[3 * b], weight: x[stride - 1], group: b + 1 });
        par.push({ value: x[3 * b + 2], weight: x[stride - 1], group: b + 1 });
      }
    }
    return [
      { title: 'partition 1, linear part: ρ of each boundary (Liu eqs. 18-21)', unit: 'top-view px', items: lin, markers: [], colours: 'colour: which of the particle’s boundaries' },
      { title: 'partition 2, parabolic part: d of each boundary (eqs. 22-25)', unit: 'px/px, the far slope', items: par, markers: [] },
    ];
  }
  if (trackerId.startsWith('danescu')) {
    return [{
      title: 'lateral offset X_CW by MBSAS cluster (Danescu eq. 15)', unit: 'm', colours: 'colour: the cluster (dark grey: initialisation particles)',
      items: r.map((x) => ({ value: x[5], weight: x[11], group: x[12] })),
      markers: [],
    }];
  }
  return [];
}

/**
 * Draws `panels` on `canvas`, one below the other, each a weighted stacked histogram.
 * @param {HTMLCanvasElement} canvas
 * @param {Panel[]} panels
 */
export function drawBelief(canvas, panels) {
  const ctx = canvas.getContext('2d');
  if (!ctx) throw new Error('the belief canvas has no 2-D context');
  ctx.fillStyle = '#0b0e11';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.font = '12px system-ui, sans-serif';
  const ph = canvas.height / Math.max(1, panels.length);
  panels.forEach((panel, k) => drawPanel(ctx, panel, k * ph, ph, canvas.width));
}

/**
 * @param {CanvasRenderingContext2D} ctx
 * @param {Panel} panel
 * @param {number} top
 * @param {number} height
 * @param {number} width
 */
function drawPanel(ctx, panel, top, height, width) {
  const left = 46;
  const plotTop = top + 34;
  const w = width - left - 12;
  const h = height - 34 - 28;
  const items = panel.items.filter((i) => Number.isFinite(i.value) && Number.isFinite(i.weight));
  ctx.fillStyle = '#e6e9ec';
  ctx.fillText(panel.title, 6, top + 14);
  if (!items.length) return;
  const BINS = panel.bins ?? DEFAULT_BINS;
  let [lo, hi] = panel.range ?? [Math.min(...items.map((i) => i.value)), Math.max(...items.map((i) => i.value))];
  for (const m of panel.markers) {
    if (Number.isFinite(m.value)) [lo, hi] = [Math.min(lo, m.value), Math.max(hi, m.value)];
  }
  if (hi - lo < 1e-9) [lo, hi] = [lo - 0.5, hi + 0.5];
  const total = items.reduce((a, i) => a + i.weight, 0) || 1;
  const groups = [...new Set(items.map((i) => i.group))].sort((a, b) => a - b);
  const bins = groups.map(() => new Array(BINS).fill(0));
  for (const i of items) {
    const b = Math.min(BINS - 1, Math.floor(((i.value - lo) / (hi - lo)) * BINS));
    bins[groups.indexOf(i.group)][b] += i.weight / total;
  }
  const stacked = new Array(BINS).fill(0).map((_, b) => bins.reduce((a, g) => a + g[b], 0));
  const peak = Math.max(...stacked) || 1;
  const bw = w / BINS;
  for (let b = 0; b < BINS; b++) {
    let y = plotTop + h;
    groups.forEach((g, gi) => {
      const bh = (bins[gi][b] / peak) * h;
      if (bh <= 0) return;
      ctx.fillStyle = groupColour(g);
      ctx.fillRect(left + b * bw + 0.5, y - bh, Math.max(1, bw - 1), bh);
      y -= bh;
    });
  }
  /** @param {number} v */
  const x = (v) => left + ((v - lo) / (hi - lo)) * w;
  panel.markers.forEach((m, i) => {
    if (!Number.isFinite(m.value)) return;
    ctx.strokeStyle = m.colour;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(x(m.value), plotTop);
    ctx.lineTo(x(m.value), plotTop + h);
    ctx.stroke();
    ctx.lineWidth = 1;
    ctx.fillStyle = m.colour;
    ctx.fillText(m.label, width - 110, top + 14 + 13 * i);
  });
  // Axes: weight share up, the quantity across, with its unit.
  ctx.strokeStyle = '#8a949e';
  ctx.beginPath();
  ctx.moveTo(left, plotTop);
  ctx.lineTo(left, plotTop + h);
  ctx.lineTo(left + w, plotTop + h);
  ctx.stroke();
  ctx.fillStyle = '#8a949e';
  ctx.fillText(`${(100 * peak).toFixed(0)} %`, 6, plotTop + 10);
  ctx.fillText('0', 30, plotTop + h);
  ctx.fillText(lo.toPrecision(3), left, plotTop + h + 14);
  ctx.fillText(hi.toPrecision(3), left + w - 40, plotTop + h + 14);
  ctx.fillText(`${panel.unit} · bar height: share of the ${panel.bins ? 'votes' : 'weight'}`, left + w / 2 - 110, plotTop + h + 14);
  if (panel.probabilities) {
    panel.probabilities.forEach((p, k) => {
      ctx.fillStyle = groupColour(k + 1);
      ctx.fillRect(left + 8, plotTop + 4 + 14 * k, 80 * p, 9);
      ctx.fillText(`P(r=${k + 1}) ${p.toFixed(2)}`, left + 94, plotTop + 13 + 14 * k);
    });
  }
}
