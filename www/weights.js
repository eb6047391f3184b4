// @ts-check
// The weight histogram of the road trackers' particles, redrawn after every frame and every
// stage when stepping: how many particles (y) have each weight, in units of the uniform weight
// 1/N (x: 1 = an average particle), with the ESS written above. After a resampling every
// particle sits at 1; after a weighing the cloud spreads out, a few heavy ones on the right.
import { weightColour } from './render.js';

const BINS = 30;
const LEFT = 44;
const BOTTOM = 26;
const TOP = 22;

/**
 * Histogram of weights·N over [0, max(2, heaviest)]: { counts, hi }; bin k is centred on
 * k·hi/BINS, so equal weights (1) fall in the middle of a bin, not on an edge.
 * @param {ArrayLike<number> & Iterable<number>} weights
 */
export function weightHistogram(weights) {
  const n = weights.length;
  let sum = 0;
  for (const w of weights) sum += w;
  const scaled = Array.from(weights, (w) => (sum > 0 ? (w / sum) * n : 0));
  const hi = Math.max(2, ...scaled);
  const counts = new Array(BINS).fill(0);
  for (const v of scaled) counts[Math.min(BINS - 1, Math.floor((v / hi) * BINS + 0.5))] += 1;
  return { counts, hi };
}

/**
 * Draws the histogram of `weighing` ({ weights, count, ess, group }, from the worker) on
 * `canvas`, with axes and units; `label` says after which step. Returns the caption text.
 * @param {HTMLCanvasElement} canvas
 * @param {{ weights: Float32Array, count: number, ess: number, group: number | null }} weighing
 * @param {string} label
 */
export function drawWeights(canvas, weighing, label) {
  const ctx = canvas.getContext('2d');
  if (!ctx) throw new Error('the weights canvas has no 2-D context');
  const { width, height } = canvas;
  ctx.fillStyle = '#0b0e11';
  ctx.fillRect(0, 0, width, height);
  if (!weighing?.weights?.length) return 'No particles: choose a tracker.';
  const { counts, hi } = weightHistogram(weighing.weights);
  const peak = Math.max(...counts);
  const w = width - LEFT - 10;
  const h = height - TOP - BOTTOM;
  const bar = w / BINS;
  counts.forEach((c, k) => {
    if (!c) return;
    const bh = Math.max(2, (c / peak) * h);
    ctx.fillStyle = weightColour((k + 0.5) / BINS);
    ctx.fillRect(LEFT + k * bar + 1, TOP + h - bh, bar - 2, bh);
  });
  // Axes, ticks and units.
  ctx.strokeStyle = '#8a949e';
  ctx.beginPath();
  ctx.moveTo(LEFT, TOP);
  ctx.lineTo(LEFT, TOP + h);
  ctx.lineTo(LEFT + w, TOP + h);
  ctx.stroke();
  ctx.fillStyle = '#e6e9ec';
  ctx.font = '12px system-ui, sans-serif';
  ctx.fillText(String(peak), 6, TOP + 10);
  ctx.fillText('0', 30, TOP + h);
  ctx.fillText('0', LEFT + 0.5 * bar - 3, TOP + h + 14);
  /** @param {number} v */
  const at = (v) => LEFT + ((v / hi) * BINS + 0.5) * bar;
  ctx.fillText('1', at(1) - 3, TOP + h + 14);
  ctx.fillText(hi.toFixed(1), Math.min(at(hi), LEFT + w - 24), TOP + h + 14);
  ctx.fillText('weight × N (1 = uniform)', LEFT + w / 2 - 60, height - 2);
  ctx.fillText('particles', 6, TOP - 8);
  const n = weighing.weights.length;
  ctx.fillText(`ESS ${weighing.ess.toFixed(0)} of ${n}`, LEFT + w - 110, TOP - 8);
  const stage = weighing.group !== null && weighing.group > 0 ? `stage ${weighing.group}’s ` : '';
  return `Weights of ${stage}${n} particles${weighing.count > n ? ` (of ${weighing.count})` : ''} ${label}: `
    + `ESS ${weighing.ess.toFixed(1)} of ${n}.`;
}
