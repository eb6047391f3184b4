// Drawing on the canvas: frames, lane boundaries (one colour per role) and labels.

export const ROLE_COLOURS = {
  'ego-left': '#ffd54f',
  'ego-right': '#4fc3f7',
  'left-adjacent': '#ba68c8',
  'right-adjacent': '#81c784',
};

/** Draws an RGBA frame (Uint8ClampedArray, width*height*4) scaled to the canvas. */
export function drawFrame(ctx, rgba, width, height) {
  const canvas = ctx.canvas;
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  ctx.putImageData(new ImageData(rgba, width, height), 0, 0);
}

/** Draws boundaries [{ role, points: [[x, y], ...] }] as polylines. */
export function drawBoundaries(ctx, boundaries, { dashed = false, width = 3 } = {}) {
  ctx.save();
  ctx.lineWidth = width;
  ctx.lineJoin = 'round';
  ctx.setLineDash(dashed ? [10, 8] : []);
  for (const b of boundaries) {
    if (b.points.length < 2) continue;
    ctx.strokeStyle = ROLE_COLOURS[b.role] ?? '#ffffff';
    ctx.beginPath();
    ctx.moveTo(b.points[0][0], b.points[0][1]);
    for (const [x, y] of b.points.slice(1)) ctx.lineTo(x, y);
    ctx.stroke();
  }
  ctx.restore();
}
