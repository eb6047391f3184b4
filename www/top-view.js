// @ts-check
// The top view the demo draws beside the camera view: a lookup table from road cells to camera
// pixels, built once per camera, then a plain copy of pixels per frame (in the worker).
import { Camera } from '../pkg/web/lanepf.js';

/** Road cells 0.1 m, 2 to 42 m ahead, ±8 m. */
export const TOP = { xMin: 2, xMax: 42, yHalf: 8, cell: 0.1 };

/**
 * The lookup table of a camera: camera pixel index per road cell, -1 unseen.
 * @param {import('../pkg/web/lanepf.js').CameraConfig} cameraConfig
 */
export function topViewTable(cameraConfig) {
  const camera = new Camera(cameraConfig);
  const rows = Math.round((TOP.xMax - TOP.xMin) / TOP.cell);
  const cols = Math.round((2 * TOP.yHalf) / TOP.cell);
  const lut = new Int32Array(rows * cols).fill(-1);
  const { width, height } = camera;
  // Every cell's centre, projected in one call (NaN: behind the camera).
  const xy = new Float64Array(2 * rows * cols);
  for (let r = 0; r < rows; r++) {
    const x = TOP.xMax - (r + 0.5) * TOP.cell;
    for (let c = 0; c < cols; c++) {
      xy[2 * (r * cols + c)] = x;
      xy[2 * (r * cols + c) + 1] = TOP.yHalf - (c + 0.5) * TOP.cell;
    }
  }
  const uv = camera.projectRoadPoints(xy);
  for (let i = 0; i < rows * cols; i++) {
    // (NaN fails every comparison below.)
    const u = Math.round(uv[2 * i]);
    const v = Math.round(uv[2 * i + 1]);
    if (u >= 0 && u < width && v >= 0 && v < height) lut[i] = v * width + u;
  }
  camera.free();
  return { lut, rows, cols, width, height };
}

/**
 * The top view of an RGBA frame through `table` (null when the frame's size is not its camera's).
 * @param {ReturnType<typeof topViewTable> | null} table
 * @param {Uint8Array | Uint8ClampedArray} rgba
 * @param {number} width
 * @param {number} height
 */
export function topView(table, rgba, width, height) {
  if (!table || table.width !== width || table.height !== height) return null;
  const { lut, rows, cols } = table;
  const out = new Uint8ClampedArray(rows * cols * 4);
  for (let i = 0; i < lut.length; i++) {
    const p = lut[i];
    if (p < 0) continue;
    out[4 * i] = rgba[4 * p];
    out[4 * i + 1] = rgba[4 * p + 1];
    out[4 * i + 2] = rgba[4 * p + 2];
    out[4 * i + 3] = 255;
  }
  return { rgba: out, rows, cols, ...TOP };
}
