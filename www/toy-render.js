// @ts-check
// Drawing the first lesson (toy.html): the line with the car, the reading and the particles;
// the weight histogram; the ESS over the steps. `t` in [0, 1] draws the resampling animation:
// each new particle slides from its parent's place to its own, the particles left without a
// child fade out.

const CAR = '#4fc3f7';
const READING = '#ff5252';
const PARTICLE = '#ffb74d';
const ESTIMATE = '#81c784';
const AXIS = '#8a949e';
/** Particles are spread over this many rows, so copies at one place do not hide each other. */
const ROWS = 12;

/** @typedef {import('./toy-filter.js').ToyFilter} ToyFilter */

/** @param {CanvasRenderingContext2D} ctx */
const clear = (ctx) => {
  ctx.fillStyle = '#0b0e11';
  ctx.fillRect(0, 0, ctx.canvas.width, ctx.canvas.height);
};

/**
 * The x axis of the line: metres to canvas pixels, with margins.
 * @param {CanvasRenderingContext2D} ctx
 * @param {number} length
 */
const axis = (ctx, length) => {
  const left = 30;
  const w = ctx.canvas.width - 2 * left;
  /** @param {number} m */
  return (m) => left + (m / length) * w;
};

/**
 * The line, its ticks every 10 m, the car, the reading (± sigma) and the estimate.
 * @param {CanvasRenderingContext2D} ctx
 * @param {ToyFilter} f
 */
function drawScene(ctx, f) {
  const { length, sigmaSensor } = f.options;
  const X = axis(ctx, length);
  const ground = ctx.canvas.height - 40;
  ctx.strokeStyle = AXIS;
  ctx.fillStyle = AXIS;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(X(0), ground);
  ctx.lineTo(X(length), ground);
  ctx.stroke();
  ctx.font = '11px system-ui, sans-serif';
  ctx.lineWidth = 1;
  for (let m = 0; m <= length; m += 10) {
    ctx.beginPath();
    ctx.moveTo(X(m), ground);
    ctx.lineTo(X(m), ground + 5);
    ctx.stroke();
    ctx.fillText(`${m} m`, X(m) - 10, ground + 17);
  }
  // The car: a box on the line.
  ctx.fillStyle = CAR;
  ctx.fillRect(X(f.car) - 9, ground - 14, 18, 12);
  // The reading with its one-sigma bracket, under the line.
  if (f.reading !== null) {
    const y = ground + 28;
    ctx.strokeStyle = READING;
    ctx.fillStyle = READING;
    ctx.beginPath();
    ctx.moveTo(X(f.reading - sigmaSensor), y);
    ctx.lineTo(X(f.reading + sigmaSensor), y);
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(X(f.reading), y - 8);
    ctx.lineTo(X(f.reading) - 5, y);
    ctx.lineTo(X(f.reading) + 5, y);
    ctx.closePath();
    ctx.fill();
  }
  const e = f.estimate();
  ctx.strokeStyle = ESTIMATE;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(X(e), 8);
  ctx.lineTo(X(e), ground);
  ctx.stroke();
}

/** A particle's dot: radius grows with its weight relative to 1/N. */
/**
 * @param {number} w
 * @param {number} n
 */
const radius = (w, n) => Math.max(1.5, Math.min(9, 2.5 * Math.sqrt(w * n)));

/**
 * The scene and the particles; with `anim` ({ t, before, weightsBefore, parents }) the
 * resampling animation at time t in [0, 1].
 * @param {CanvasRenderingContext2D} ctx
 * @param {import('./toy-filter.js').ToyFilter} f
 * @param {{ t: number, before: number[], weightsBefore: number[], parents: number[] } | null} [anim]
 */
export function drawView(ctx, f, anim = null) {
  clear(ctx);
  drawScene(ctx, f);
  const X = axis(ctx, f.options.length);
  /** @param {number} k */
  const row = (k) => ctx.canvas.height - 60 - 9 * (k % ROWS);
  const n = f.x.length;
  ctx.fillStyle = PARTICLE;
  if (anim) {
    const { t, before, weightsBefore, parents } = anim;
    const chosen = new Set(parents);
    // The old particles: the chosen ones shrink to 1/N, the others fade.
    before.forEach((x, p) => {
      ctx.globalAlpha = chosen.has(p) ? 0.35 : 0.8 * (1 - t);
      ctx.beginPath();
      ctx.arc(X(x), row(p), radius(weightsBefore[p], n) * (chosen.has(p) ? 1 : 1 - 0.5 * t), 0, 2 * Math.PI);
      ctx.fill();
    });
    // The new ones slide from their parent's row to their own.
    ctx.globalAlpha = 0.9;
    parents.forEach((p, k) => {
      const y = row(p) + (row(k) - row(p)) * t;
      ctx.beginPath();
      ctx.arc(X(before[p]), y, radius(1 / n, n), 0, 2 * Math.PI);
      ctx.fill();
    });
    ctx.globalAlpha = 1;
    return;
  }
  f.x.forEach((x, k) => {
    ctx.globalAlpha = 0.85;
    ctx.beginPath();
    ctx.arc(X(x), row(k), radius(f.w[k], n), 0, 2 * Math.PI);
    ctx.fill();
  });
  ctx.globalAlpha = 1;
}

/**
 * The weight histogram over `bins` bins, scaled to its tallest bar, the car's place marked.
 * @param {CanvasRenderingContext2D} ctx
 * @param {ToyFilter} f
 * @param {number} [bins]
 */
export function drawHistogram(ctx, f, bins = 50) {
  clear(ctx);
  const h = f.histogram(bins);
  const X = axis(ctx, f.options.length);
  const top = Math.max(...h) || 1;
  const base = ctx.canvas.height - 12;
  const barW = (X(f.options.length) - X(0)) / bins;
  ctx.fillStyle = PARTICLE;
  h.forEach((v, b) => {
    const hh = (base - 14) * (v / top);
    ctx.fillRect(X(0) + b * barW + 1, base - hh, Math.max(1, barW - 2), hh);
  });
  ctx.strokeStyle = CAR;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(X(f.car), base + 2);
  ctx.lineTo(X(f.car), base + 10);
  ctx.stroke();
  ctx.fillStyle = AXIS;
  ctx.font = '11px system-ui, sans-serif';
  ctx.fillText(`tallest bin: ${(100 * top).toFixed(0)} % of the weight`, 6, 12);
}

/**
 * ESS after each weighing (history [{ step, ess, resampled }]), the threshold dashed.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ step: number, ess: number, resampled: boolean }[]} history
 * @param {number} n particles
 * @param {number} threshold share of N
 * @param {number} [span] steps shown
 */
export function drawEss(ctx, history, n, threshold, span = 60) {
  clear(ctx);
  const base = ctx.canvas.height - 14;
  /** @param {number} v */
  const y = (v) => base - (base - 8) * (v / n);
  /** @param {number} i */
  const X = (i) => 40 + (i / (span - 1)) * (ctx.canvas.width - 50);
  const shown = history.slice(-span);
  ctx.fillStyle = AXIS;
  ctx.font = '11px system-ui, sans-serif';
  ctx.fillText(`${n}`, 4, y(n) + 4);
  ctx.fillText('0', 4, base);
  ctx.strokeStyle = AXIS;
  ctx.setLineDash([5, 4]);
  ctx.beginPath();
  ctx.moveTo(X(0), y(threshold * n));
  ctx.lineTo(X(span - 1), y(threshold * n));
  ctx.stroke();
  ctx.setLineDash([]);
  ctx.strokeStyle = PARTICLE;
  ctx.lineWidth = 2;
  ctx.beginPath();
  shown.forEach((h, i) => (i ? ctx.lineTo(X(i), y(h.ess)) : ctx.moveTo(X(i), y(h.ess))));
  ctx.stroke();
  ctx.fillStyle = READING;
  shown.forEach((h, i) => {
    if (h.resampled) ctx.fillRect(X(i) - 2, base + 4, 4, 8);
  });
}
