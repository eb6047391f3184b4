// @ts-check
// Drawing on the canvas: frames, lane boundaries (one colour per role), the particle cloud,
// the top view and the trackers' cue layers. How things look is decided here, once, and the
// legend (legend.js) draws its samples with these same functions:
//   a valid estimate:      solid, opaque, in its role's colour;
//   an estimate that is not valid: the same colour faded to INVALID_ALPHA and dashed
//                          (INVALID_DASH), thinner, so it never passes for a confident one;
//   the ground truth:      dashed (TRUTH_DASH) in TRUTH_COLOUR, whatever the role, thin and
//                          over the estimate (dashes on a thick line where they agree);
//   particles:             thin lines, opacity by weight, in their role's (or group's) colour.

/** @typedef {import('../pkg/web/lanepf.js').Boundary} Boundary */
/** @typedef {import('../pkg/web/lanepf.js').Delimiter} Delimiter */
/** @typedef {import('../pkg/web/lanepf.js').Hypothesis} Hypothesis */
/** @typedef {import('../pkg/web/lanepf.js').LaneEstimate} LaneEstimate */
/** @typedef {import('../pkg/web/lanepf.js').Layer} Layer */
/** @typedef {import('../pkg/web/lanepf.js').CalibrationObservation} CalibrationObservation */
/** A point on the canvas or the road: [x, y]. */
/** @typedef {[number, number]} Point */
/** Road point [x ahead, y left] -> canvas point, for the top view. */
/** @typedef {(p: Point) => Point} RoadMap */
/** A boundary drawn as a polyline: its role and canvas points. */
/** @typedef {{ role: string, points: Point[] }} Polyline */

/** @type {Record<string, string>} */
export const ROLE_COLOURS = {
  'ego-left': '#ffd54f',
  'ego-right': '#4fc3f7',
  'left-adjacent': '#ba68c8',
  'right-adjacent': '#81c784',
};

/** The ground truth's colour and dash pattern (one colour for every role). */
export const TRUTH_COLOUR = '#ff1744';
export const TRUTH_DASH = [10, 8];
/** An estimate that is not valid: its opacity and dash pattern. */
export const INVALID_ALPHA = 0.4;
export const INVALID_DASH = [8, 8];

/**
 * Draws an RGBA frame (Uint8ClampedArray, width*height*4) scaled to the canvas.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Uint8ClampedArray<ArrayBuffer>} rgba
 * @param {number} width
 * @param {number} height
 */
export function drawFrame(ctx, rgba, width, height) {
  const canvas = ctx.canvas;
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  ctx.putImageData(new ImageData(rgba, width, height), 0, 0);
}

/**
 * Draws boundaries [{ role, points: [[x, y], ...] }] as polylines in their role's colour (or
 * `colour` for all), with the dash pattern `dash` (none: solid) and opacity `alpha`.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Polyline[]} boundaries
 * @param {{ dash?: number[], width?: number, colour?: string | null, alpha?: number }} [style]
 */
export function drawBoundaries(ctx, boundaries, { dash = [], width = 3, colour = null, alpha = 1 } = {}) {
  ctx.save();
  ctx.lineWidth = width;
  ctx.lineJoin = 'round';
  ctx.globalAlpha = alpha;
  ctx.setLineDash(dash);
  for (const b of boundaries) {
    if (b.points.length < 2) continue;
    ctx.strokeStyle = colour ?? ROLE_COLOURS[b.role] ?? '#ffffff';
    ctx.beginPath();
    ctx.moveTo(b.points[0][0], b.points[0][1]);
    for (const [x, y] of b.points.slice(1)) ctx.lineTo(x, y);
    ctx.stroke();
  }
  ctx.restore();
}

/**
 * Draws the ground truth's boundaries: dashed, in TRUTH_COLOUR.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Polyline[]} boundaries
 * @param {number} [width]
 */
export function drawTruth(ctx, boundaries, width = 2) {
  drawBoundaries(ctx, boundaries, { dash: TRUTH_DASH, width, colour: TRUTH_COLOUR });
}

/**
 * Draws an estimate (`LaneEstimate`): its boundaries, and for a tracker with marking widths
 * (danescu-*) the markings' bands under thin centre lines. A valid estimate solid and opaque;
 * one that is not valid faded (INVALID_ALPHA) and dashed (INVALID_DASH). Image polylines, or
 * the road polylines through `map` (road point -> canvas point) for the top view.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Pick<LaneEstimate, 'valid' | 'boundaries' | 'delimiters'>} estimate
 * @param {RoadMap | null} [map]
 */
export function drawEstimate(ctx, estimate, map = null) {
  const banded = (estimate.delimiters?.length ?? 0) > 0;
  const boundaries = map
    ? estimate.boundaries.map((b) => ({ ...b, points: (b.road_points ?? []).map(map) }))
    : estimate.boundaries;
  // Thinner on the top view, whose canvas is small; thin centre lines over marking bands.
  const width = map ? (banded ? 1 : 3) : (banded ? 2 : 4);
  const alpha = estimate.valid ? 1 : INVALID_ALPHA;
  drawDelimiters(ctx, estimate.delimiters, map, alpha);
  drawBoundaries(ctx, boundaries, { width, alpha, dash: estimate.valid ? [] : INVALID_DASH });
}

/**
 * Draws the markings of a tracker that models their widths (`LaneEstimate.delimiters`,
 * danescu-*): each boundary's marking as a translucent band of its role's colour between the
 * marking's inner and outer edge, the edges as thin lines. Image polylines, or the road
 * polylines through `map` (road point -> canvas point) for the top view; `alpha` fades it all
 * (an estimate that is not valid).
 * @param {CanvasRenderingContext2D} ctx
 * @param {Delimiter[] | undefined} delimiters
 * @param {RoadMap | null} [map]
 * @param {number} [alpha]
 */
export function drawDelimiters(ctx, delimiters, map = null, alpha = 1) {
  if (!delimiters?.length) return;
  /** @param {Delimiter} d */
  const pts = (d) => (map ? (d.road_points ?? []).map(map) : d.points);
  ctx.save();
  for (const role of new Set(delimiters.map((d) => d.role))) {
    const inner = delimiters.find((d) => d.role === role && d.side === 'inner');
    const outer = delimiters.find((d) => d.role === role && d.side === 'outer');
    if (!inner || !outer) continue;
    const [a, b] = [pts(inner), pts(outer)];
    if (a.length < 2 || b.length < 2) continue;
    const colour = ROLE_COLOURS[role] ?? '#ffffff';
    // The band: along the inner edge, back along the outer one.
    ctx.beginPath();
    ctx.moveTo(a[0][0], a[0][1]);
    for (let k = 1; k < a.length; k++) ctx.lineTo(a[k][0], a[k][1]);
    for (let k = b.length - 1; k >= 0; k--) ctx.lineTo(b[k][0], b[k][1]);
    ctx.closePath();
    ctx.globalAlpha = 0.35 * alpha;
    ctx.fillStyle = colour;
    ctx.fill();
    ctx.globalAlpha = 0.9 * alpha;
    ctx.strokeStyle = colour;
    ctx.lineWidth = 1;
    for (const line of [a, b]) {
      ctx.beginPath();
      ctx.moveTo(line[0][0], line[0][1]);
      for (const [x, y] of line.slice(1)) ctx.lineTo(x, y);
      ctx.stroke();
    }
  }
  ctx.restore();
}

/** Colours of particle groups (Adachi's models, Lee's stages, Danescu's clusters; -1 grey). */
export const GROUP_COLOURS = ['#e0e0e0', '#ff8a65', '#4dd0e1', '#aed581', '#f06292', '#ffd54f', '#9575cd'];
/** @param {number} g */
export const groupColour = (g) => (g < 0 ? '#757575' : GROUP_COLOURS[g % GROUP_COLOURS.length]);

/**
 * Colour of a particle of weight `v` relative to the heaviest drawn (0..1): dark blue for the
 * lightest, through teal and green, to yellow for the heaviest (a viridis-like ramp).
 * @param {number} v
 */
export function weightColour(v) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const x = Math.min(1, Math.max(0, Number.isFinite(v) ? v : 0)) * (stops.length - 1);
  const k = Math.min(stops.length - 2, Math.floor(x));
  const f = x - k;
  const c = stops[k].map((a, i) => Math.round(a + f * (stops[k + 1][i] - a)));
  return `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
}

/**
 * Draws the particle cloud (Tracker.hypotheses()): each particle's boundaries as a thin line
 * coloured by its weight relative to the heaviest drawn (weightColour), or by its group with
 * `byGroup`, and more opaque when heavier: image polylines, or the road polylines through `map`
 * (road point -> canvas point) when it is given.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Hypothesis[] | null | undefined} hypotheses
 * @param {RoadMap | null} [map]
 * @param {boolean} [byGroup]
 */
export function drawHypotheses(ctx, hypotheses, map = null, byGroup = false) {
  if (!hypotheses?.length) return;
  const top = hypotheses.reduce((a, h) => Math.max(a, h.weight), 0) || 1;
  ctx.save();
  ctx.lineWidth = 1;
  for (const h of hypotheses) {
    ctx.globalAlpha = 0.25 + 0.6 * (h.weight / top);
    for (const b of h.boundaries) {
      const pts = map ? (b.road_points ?? []).map(map) : b.points;
      if (pts.length < 2) continue;
      ctx.strokeStyle = byGroup ? groupColour(h.group) : weightColour(h.weight / top);
      ctx.beginPath();
      ctx.moveTo(pts[0][0], pts[0][1]);
      for (const [x, y] of pts.slice(1)) ctx.lineTo(x, y);
      ctx.stroke();
    }
  }
  ctx.restore();
}

/**
 * Draws the top view (the worker's inverse perspective mapping of the frame: rows far to near,
 * columns left to right) with boundaries and particles on it from their road points.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ rgba: Uint8ClampedArray<ArrayBuffer>, rows: number, cols: number, yHalf: number, xMax: number, cell: number }} top
 *   the worker's top view (top-view.js)
 * @param {{ truth?: LaneEstimate | null, estimate?: LaneEstimate | null, hypotheses?: Hypothesis[] | null,
 *   byGroup?: boolean }} [overlays]
 */
export function drawTopView(ctx, top, { truth = null, estimate = null, hypotheses = null, byGroup = false } = {}) {
  const canvas = ctx.canvas;
  if (canvas.width !== top.cols || canvas.height !== top.rows) {
    canvas.width = top.cols;
    canvas.height = top.rows;
  }
  ctx.putImageData(new ImageData(top.rgba, top.cols, top.rows), 0, 0);
  // Road point [x ahead, y left] -> canvas [column, row].
  /** @type {RoadMap} */
  const map = ([x, y]) => [(top.yHalf - y) / top.cell, (top.xMax - x) / top.cell];
  /** @param {Boundary[]} boundaries */
  const asImage = (boundaries) => boundaries.map((b) => ({ ...b, points: (b.road_points ?? []).map(map) }));
  drawHypotheses(ctx, hypotheses, map, byGroup);
  if (estimate) drawEstimate(ctx, estimate, map);
  if (truth) drawTruth(ctx, asImage(truth.boundaries));
}

/**
 * Heat colour of a value in [0, 1]: red grows linearly, then yellow and white show the top.
 * @param {number} v
 */
function heat(v) {
  const t = Math.min(1, Math.max(0, v));
  return [255 * t, 255 * t * t, 255 * t * t * t];
}

/**
 * Draws one of a tracker's cue layers (Tracker.layers()): a `grid` on the road plane as a heat
 * map, far at the top and left on the left as seen from the car, or a `histogram` over a road
 * axis as bars, with the particles' boundaries as ticks and the groups' probabilities over a
 * lateral axis. Values are scaled by the layer's largest.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Layer} layer
 * @param {{ hypotheses?: Hypothesis[] | null, probabilities?: number[] | null }} [marks]
 */
export function drawLayer(ctx, layer, { hypotheses = null, probabilities = null } = {}) {
  const canvas = ctx.canvas;
  // A grid on the road and a plane (e.g. Danescu's lateral density image) are both heat maps
  // with row 0 at the bottom.
  if (layer.kind === 'grid' || layer.kind === 'plane') {
    const { width, height, values } = layer;
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const max = values.reduce((a, v) => Math.max(a, v), 0) || 1;
    const img = new ImageData(width, height);
    for (let r = 0; r < height; r++) {
      // Row 0 (nearest the car, or lowest) is drawn at the bottom.
      const out = (height - 1 - r) * width;
      for (let c = 0; c < width; c++) {
        const [red, green, blue] = heat(values[r * width + c] / max);
        const i = 4 * (out + c);
        img.data[i] = red;
        img.data[i + 1] = green;
        img.data[i + 2] = blue;
        img.data[i + 3] = 255;
      }
    }
    ctx.putImageData(img, 0, 0);
    return;
  }
  const { values } = layer;
  if (canvas.width !== 640 || canvas.height !== 200) {
    canvas.width = 640;
    canvas.height = 200;
  }
  ctx.fillStyle = '#000';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const max = values.reduce((a, v) => Math.max(a, v), 0) || 1;
  const w = canvas.width / Math.max(1, values.length);
  ctx.fillStyle = '#ffb74d';
  values.forEach((v, k) => {
    const h = (canvas.height - 10) * (v / max);
    ctx.fillRect(k * w, canvas.height - h, Math.max(1, w), h);
  });
  // On a lateral axis (rho, positive right), the particles' boundaries as ticks above the
  // bars, coloured by group, and the groups' probabilities (Adachi's P(r)).
  if (hypotheses?.length && /^rho/.test(layer.axis ?? '')) {
    const top = hypotheses.reduce((a, h) => Math.max(a, h.weight), 0) || 1;
    for (const h of hypotheses) {
      ctx.strokeStyle = groupColour(h.group);
      ctx.globalAlpha = 0.2 + 0.8 * (h.weight / top);
      for (const b of h.boundaries) {
        const y = b.road_points?.[Math.floor(b.road_points.length / 2)]?.[1];
        if (y === undefined || !Number.isFinite(y)) continue;
        const x = ((-y - layer.start) / layer.step) * w;
        ctx.beginPath();
        ctx.moveTo(x, 2);
        ctx.lineTo(x, 2 + 30 * (h.weight / top));
        ctx.stroke();
      }
    }
    ctx.globalAlpha = 1;
  }
  if (probabilities?.length) {
    ctx.font = '12px system-ui, sans-serif';
    probabilities.forEach((p, k) => {
      ctx.fillStyle = groupColour(k + 1);
      ctx.fillRect(8, 44 + 16 * k, 120 * p, 10);
      ctx.fillText(`P(r=${k + 1}) ${p.toFixed(2)}`, 134, 53 + 16 * k);
    });
  }
}

/**
 * Draws what the auto-calibrator saw in the last frame (`Calibrator.observation()`): the lines
 * through marking pixels (thin), the two ego boundaries it measures from (thick, up to where
 * they meet), the vanishing point and the horizon through it. Undistorted pixels: with a
 * distorting lens the lines sit slightly off the markings near the image edges.
 * @param {CanvasRenderingContext2D} ctx
 * @param {CalibrationObservation} observation
 */
export function drawCalibrationLines(ctx, observation) {
  const { lines, ego, vanishing_point: vp } = observation;
  /**
   * @param {import('../pkg/web/lanepf.js').CalibrationLine} l
   * @param {number} y
   */
  const x = (l, y) => l.x_ref + l.slope * (y - l.y_ref);
  ctx.save();
  ctx.strokeStyle = 'rgba(255, 152, 0, 0.6)';
  ctx.lineWidth = 1;
  lines.forEach((l, i) => {
    if (ego?.includes(i)) return;
    ctx.beginPath();
    ctx.moveTo(x(l, l.y_bottom), l.y_bottom);
    ctx.lineTo(x(l, l.y_top), l.y_top);
    ctx.stroke();
  });
  ctx.strokeStyle = '#ff9800';
  ctx.lineWidth = 3;
  for (const i of ego ?? []) {
    const l = lines[i];
    const top = vp ? vp[1] : l.y_top;
    ctx.beginPath();
    ctx.moveTo(x(l, l.y_bottom), l.y_bottom);
    ctx.lineTo(x(l, top), top);
    ctx.stroke();
  }
  if (vp) {
    ctx.lineWidth = 1;
    ctx.setLineDash([4, 6]);
    ctx.beginPath();
    ctx.moveTo(0, vp[1]);
    ctx.lineTo(ctx.canvas.width, vp[1]);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(vp[0], vp[1], 6, 0, 2 * Math.PI);
    ctx.stroke();
  }
  ctx.restore();
}
