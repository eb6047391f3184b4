// @ts-check
// Pitch and yaw from the vanishing point of two lane lines (the calibration helper).
//
// With no roll, the road's forward direction e_x seen by a camera of pitch p (down positive)
// and yaw y (left positive), R = Rz(y) Ry(p) as in src/camera, lands at
//   u = cx + fx tan(y) / cos(p),   v = cy - fy tan(p),
// so p = atan((cy - v) / fy) and y = atan((u - cx) cos(p) / fx). Lens distortion is ignored:
// the vanishing point of a road lies near the image centre, where distortion is smallest.

/** @typedef {[number, number]} Point */
/** @typedef {Pick<import('../pkg/web/lanepf.js').CameraConfig, 'fx' | 'fy' | 'cx' | 'cy'>} Intrinsics */

/**
 * Intersection [u, v] of the lines through a0-a1 and b0-b1, or null when they are parallel.
 * @param {[Point, Point]} a
 * @param {[Point, Point]} b
 * @returns {Point | null}
 */
export function intersect([a0, a1], [b0, b1]) {
  const [x1, y1] = a0;
  const [x2, y2] = a1;
  const [x3, y3] = b0;
  const [x4, y4] = b1;
  const den = (x1 - x2) * (y3 - y4) - (y1 - y2) * (x3 - x4);
  if (Math.abs(den) < 1e-9) return null;
  const a = x1 * y2 - y1 * x2;
  const b = x3 * y4 - y3 * x4;
  return [(a * (x3 - x4) - (x1 - x2) * b) / den, (a * (y3 - y4) - (y1 - y2) * b) / den];
}

/**
 * { pitch_deg, yaw_deg } of `camera` whose straight road vanishes at [u, v].
 * @param {Intrinsics} camera
 * @param {Point} vp
 */
export function poseFromVanishingPoint(camera, [u, v]) {
  const pitch = Math.atan((camera.cy - v) / camera.fy);
  const yaw = Math.atan(((u - camera.cx) * Math.cos(pitch)) / camera.fx);
  const deg = 180 / Math.PI;
  return { pitch_deg: pitch * deg, yaw_deg: yaw * deg };
}

/**
 * Camera height from the lane width: the two lines cross image row `row` at columns uLeft and
 * uRight, `widthM` apart on the road. With no yaw or roll, a road point at depth Z along the
 * optical axis is fx / Z pixels per metre across and fy h / (Z cos p) rows below the horizon
 * v0 = cy - fy tan(p), so h = widthM (row - v0) fx cos(p) / ((uRight - uLeft) fy).
 * Null when the row is not below the horizon or the columns are not left to right.
 * @param {Intrinsics} camera
 * @param {number} pitchDeg
 * @param {number} row
 * @param {number} uLeft
 * @param {number} uRight
 * @param {number} widthM
 */
export function heightFromLaneWidth(camera, pitchDeg, row, uLeft, uRight, widthM) {
  const p = (pitchDeg * Math.PI) / 180;
  const v0 = camera.cy - camera.fy * Math.tan(p);
  const du = uRight - uLeft;
  if (!(du > 0) || !(row > v0)) return null;
  return (widthM * (row - v0) * camera.fx * Math.cos(p)) / (du * camera.fy);
}
