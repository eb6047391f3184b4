// @ts-check
// The camera panel: presets, editable intrinsics and pose, a helper that estimates pitch, yaw
// and height from two lane lines dragged over the frame, and per-source memory in
// localStorage. It calls `onApply(camera)` with a complete camera object.
import { intersect, poseFromVanishingPoint, heightFromLaneWidth } from './vanishing.js';
import { scaleCamera } from './camera-presets.js';
import { byId } from './dom.js';

/** @typedef {import('../pkg/web/lanepf.js').CameraConfig} CameraConfig */

export const FIELDS = /** @type {const} */ (['fx', 'fy', 'cx', 'cy', 'height_m', 'pitch_deg', 'yaw_deg', 'roll_deg']);
const STORE = 'lanepf.camera.';
const HANDLE_PX = 9;

/** @typedef {[number, number]} Point */
/** The helper's two lines, each through two handles. */
/** @typedef {[[Point, Point], [Point, Point]]} Lines */

export class Calibration {
  /**
   * @param {Document} doc
   * @param {HTMLCanvasElement} canvas the camera view (the helper's lines are dragged on it)
   * @param {Record<string, { label: string, camera: CameraConfig }>} presets
   */
  constructor(doc, canvas, presets) {
    this.doc = doc;
    this.canvas = canvas;
    this.presets = presets;
    this.panel = byId('calibration', HTMLDetailsElement, doc);
    this.form = byId('camera-fields', HTMLFormElement, doc);
    this.preset = byId('camera-preset', HTMLSelectElement, doc);
    this.helper = byId('vp-helper', HTMLInputElement, doc);
    this.laneWidth = byId('vp-lane-width', HTMLInputElement, doc);
    this.readout = byId('vp-readout', HTMLElement, doc);
    /** @type {(camera: CameraConfig) => void} */
    this.onApply = () => {};
    /** @type {() => void} */
    this.onRedraw = () => {};
    /** The camera shown (the one the tracker uses) and its source's name. */
    /** @type {CameraConfig | null} */
    this.camera = null;
    this.sourceName = '';
    /** @type {Lines | null} */
    this.lines = null;
    /** The handle being dragged: line i, point j. */
    /** @type {{ i: number, j: number } | null} */
    this.drag = null;
    for (const name of FIELDS) {
      const label = doc.createElement('label');
      const input = Object.assign(doc.createElement('input'), { type: 'number', name, step: 'any' });
      label.append(`${name} `, input);
      this.form.append(label);
    }
    for (const [key, p] of Object.entries(presets)) this.preset.add(new Option(p.label, key));
    const applyFields = () => {
      try {
        this.apply(this.read());
      } catch (err) {
        this.readout.textContent = err instanceof Error ? err.message : String(err);
      }
    };
    this.form.addEventListener('submit', (e) => {
      e.preventDefault();
      applyFields();
    });
    byId('camera-apply', HTMLButtonElement, doc).addEventListener('click', applyFields);
    byId('camera-preset-apply', HTMLButtonElement, doc).addEventListener('click', () => {
      const p = this.presets[this.preset.value];
      if (p && this.camera) this.apply(scaleCamera(p.camera, this.camera.width, this.camera.height));
    });
    this.helper.addEventListener('change', () => {
      this.lines = this.helper.checked ? this.lines : null;
      this.onRedraw();
    });
    canvas.addEventListener('pointerdown', (e) => this.pointer(e, 'down'));
    canvas.addEventListener('pointermove', (e) => this.pointer(e, 'move'));
    canvas.addEventListener('pointerup', (e) => this.pointer(e, 'up'));
  }

  /**
   * The input of camera field `name`.
   * @param {string} name
   */
  field(name) {
    const input = this.form.elements.namedItem(name);
    if (!(input instanceof HTMLInputElement)) throw new Error(`the camera panel has no field ${name}`);
    return input;
  }

  /**
   * Shows `camera` in the fields (the camera the tracker now uses).
   * @param {CameraConfig} camera
   * @param {string} sourceName
   */
  show(camera, sourceName) {
    this.camera = camera;
    this.sourceName = sourceName;
    for (const name of FIELDS) this.field(name).value = String(+(camera[name] ?? 0).toFixed(4));
    this.lines = null;
  }

  /** The camera shown with the fields' values; throws naming a field that is not a number. */
  read() {
    /** @type {Record<string, number>} */
    const values = {};
    for (const name of FIELDS) {
      const text = this.field(name).value.trim();
      const v = Number(text);
      if (text === '' || !Number.isFinite(v)) throw new Error(`Camera ${name}: “${text}” is not a number.`);
      values[name] = v;
    }
    // (The camera shown, every numeric field replaced.)
    return /** @type {CameraConfig} */ ({ ...this.camera, ...values });
  }

  /**
   * Shows `camera` and hands it on; the page saves it once a tracker accepts it.
   * @param {CameraConfig} camera
   */
  apply(camera) {
    this.show(camera, this.sourceName);
    this.onApply(camera);
  }

  /**
   * The camera saved for a source of this size, or null.
   * @param {string} sourceName
   * @param {number} width
   * @param {number} height
   * @returns {CameraConfig | null}
   */
  saved(sourceName, width, height) {
    try {
      const c = JSON.parse(localStorage.getItem(STORE + sourceName) ?? 'null');
      return c && c.width === width && c.height === height ? c : null;
    } catch {
      return null;
    }
  }

  /**
   * Remembers `camera` for the current source.
   * @param {CameraConfig} camera
   */
  save(camera) {
    try {
      localStorage.setItem(STORE + this.sourceName, JSON.stringify(camera));
    } catch {
      // Private mode or full storage: the camera still applies, it is just not remembered.
    }
  }

  active() {
    return this.helper.checked;
  }

  /**
   * Starts the two lines on the estimated ego boundaries, or on a generic lane.
   * @param {import('../pkg/web/lanepf.js').LaneEstimate | null | undefined} estimate
   * @param {number} width
   * @param {number} height
   * @returns {Lines}
   */
  startLines(estimate, width, height) {
    /** @param {string} role */
    const pick = (role) => {
      const pts = estimate?.boundaries.find((b) => b.role === role)?.points;
      return pts && pts.length >= 4 ? [pts[0], pts[Math.floor(pts.length * 0.6)]] : null;
    };
    /**
     * A copy of a line's two points.
     * @param {number[][]} l
     * @returns {[Point, Point]}
     */
    const copy = (l) => [[l[0][0], l[0][1]], [l[1][0], l[1][1]]];
    this.lines = [
      copy(pick('ego-left') ?? [[0.3 * width, 0.95 * height], [0.46 * width, 0.65 * height]]),
      copy(pick('ego-right') ?? [[0.7 * width, 0.95 * height], [0.54 * width, 0.65 * height]]),
    ];
    return this.lines;
  }

  /**
   * Draws the lines, their handles and the vanishing point on the camera view.
   * @param {CanvasRenderingContext2D} ctx
   * @param {import('../pkg/web/lanepf.js').LaneEstimate | null | undefined} estimate
   */
  draw(ctx, estimate) {
    if (!this.active()) return;
    const lines = this.lines ?? this.startLines(estimate, ctx.canvas.width, ctx.canvas.height);
    ctx.save();
    ctx.strokeStyle = '#ff5252';
    ctx.fillStyle = '#ff5252';
    ctx.lineWidth = 2;
    const vp = intersect(...lines);
    for (const [a, b] of lines) {
      ctx.beginPath();
      ctx.moveTo(a[0], a[1]);
      ctx.lineTo(...(vp ?? b));
      ctx.stroke();
      for (const p of [a, b]) {
        ctx.beginPath();
        ctx.arc(p[0], p[1], HANDLE_PX / 2 + 1, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
    if (vp) {
      ctx.beginPath();
      ctx.moveTo(0, vp[1]);
      ctx.lineTo(ctx.canvas.width, vp[1]);
      ctx.setLineDash([6, 6]);
      ctx.stroke();
    }
    ctx.restore();
    this.readout.textContent = this.describe(vp);
  }

  /** The pose the lines give, and a sentence about it. */
  estimate() {
    const lines = this.lines;
    const vp = lines && intersect(...lines);
    if (!lines || !vp || !this.camera) return null;
    const pose = poseFromVanishingPoint(this.camera, vp);
    // Height from the lines' spacing on the lowest row both reach.
    const row = Math.min(Math.max(lines[0][0][1], lines[0][1][1]),
      Math.max(lines[1][0][1], lines[1][1][1]));
    /** @param {[Point, Point]} line */
    const xOn = ([a, b]) => a[0] + ((b[0] - a[0]) * (row - a[1])) / (b[1] - a[1]);
    const h = heightFromLaneWidth(this.camera, pose.pitch_deg, row, xOn(lines[0]),
      xOn(lines[1]), Number(this.laneWidth.value));
    return { vp, ...pose, height_m: h };
  }

  /** @param {Point | null} vp */
  describe(vp) {
    const e = this.estimate();
    if (!vp || !e) return 'The two lines are parallel: drag them onto the lane markings.';
    const h = e.height_m ? `, height ${e.height_m.toFixed(2)} m` : '';
    return `vanishing point (${vp[0].toFixed(0)}, ${vp[1].toFixed(0)}): pitch ${e.pitch_deg.toFixed(2)}°, `
      + `yaw ${e.yaw_deg.toFixed(2)}°${h}`;
  }

  /**
   * Dragging a handle moves it; letting go applies the pose the lines give.
   * @param {PointerEvent} e
   * @param {'down' | 'move' | 'up'} kind
   */
  pointer(e, kind) {
    if (!this.active() || !this.lines) return;
    const r = this.canvas.getBoundingClientRect();
    /** @type {Point} */
    const p = [(e.clientX - r.left) * (this.canvas.width / r.width), (e.clientY - r.top) * (this.canvas.height / r.height)];
    if (kind === 'down') {
      /** @type {{ i: number, j: number, d: number } | null} */
      let best = null;
      this.lines.forEach((line, i) => line.forEach((q, j) => {
        const d = Math.hypot(q[0] - p[0], q[1] - p[1]);
        if (d < 3 * HANDLE_PX && (!best || d < best.d)) best = { i, j, d };
      }));
      if (best) {
        this.drag = best;
        this.canvas.setPointerCapture(e.pointerId);
        e.preventDefault();
      }
    } else if (kind === 'move' && this.drag) {
      this.lines[this.drag.i][this.drag.j] = p;
      this.onRedraw();
    } else if (kind === 'up' && this.drag) {
      this.drag = null;
      const est = this.estimate();
      if (est) {
        const lines = this.lines;
        this.apply({ ...this.read(), pitch_deg: est.pitch_deg, yaw_deg: est.yaw_deg,
          ...(est.height_m ? { height_m: est.height_m } : {}) });
        this.lines = lines;
        this.onRedraw();
      }
    }
  }
}
