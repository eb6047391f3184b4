// @ts-check
// Camera auto-calibration in the demo: the worker feeds every frame of a video, images or the
// webcam to the wasm `Calibrator`; this module decides when its estimate replaces the camera the
// tracker uses, and says what it knows. Pure logic (no DOM), tested in Node.
//
// Modes: 'auto' (the estimate is applied: once confident, or after APPLY_AFTER_FRAMES frames
// with whatever it has, then again whenever a confident estimate moves by more than MOVE_DEG
// or MOVE_HEIGHT), 'manual' (a camera the user applied, imported or saved for the source wins;
// the estimate is only shown) and 'off' (no calibrator: the simulator's sources).

/** @typedef {import('../pkg/web/lanepf.js').CameraConfig} CameraConfig */
/** @typedef {import('../pkg/web/lanepf.js').CalibrationStatus} CalibrationStatus */
/** @typedef {import('../pkg/web/lanepf.js').CalibrationEstimate} CalibrationEstimate */
/** A camera's pose: what is compared and said. */
/** @typedef {Pick<CameraConfig, 'pitch_deg' | 'yaw_deg' | 'height_m'>} Pose */
/** @typedef {'off' | 'auto' | 'manual'} Mode */
/** Why an estimate was applied. */
/** @typedef {'confident' | 'timeout' | 'moved' | 'chosen'} Reason */

/** Confidence at which the estimate is applied. */
export const APPLY_CONFIDENCE = 0.8;
/** Frames after which the estimate so far is applied even below that confidence (5 s at 30 fps). */
export const APPLY_AFTER_FRAMES = 150;
/** A confident estimate is re-applied when pitch or yaw moved by more than this, degrees ... */
export const MOVE_DEG = 0.5;
/** ... or the height by more than this share. */
export const MOVE_HEIGHT = 0.1;

/**
 * Whether `next` differs from `applied` by more than MOVE_DEG in pitch or yaw or MOVE_HEIGHT in height.
 * @param {Pose} applied
 * @param {Pose} next
 */
export function moved(applied, next) {
  return Math.abs(next.pitch_deg - applied.pitch_deg) > MOVE_DEG
    || Math.abs((next.yaw_deg ?? 0) - (applied.yaw_deg ?? 0)) > MOVE_DEG
    || Math.abs(next.height_m / applied.height_m - 1) > MOVE_HEIGHT;
}

/**
 * A camera's pose in words.
 * @param {Pose} c
 */
export function describePose(c) {
  return `pitch ${c.pitch_deg.toFixed(2)}°, yaw ${(c.yaw_deg ?? 0).toFixed(2)}°, height ${c.height_m.toFixed(2)} m`;
}

export class AutoCalibration {
  constructor() {
    /** @type {Mode} */
    this.mode = 'off';
    /** The source's own camera (the bundled clip), shown beside the estimate. */
    /** @type {Pose | null} */
    this.known = null;
    this.error = '';
    /** @type {CalibrationStatus | null} */
    this.status = null;
    /** @type {CalibrationEstimate | null} */
    this.estimate = null;
    /** The camera the tracker got from the estimate, why, and at which frame seen. */
    /** @type {Pose | null} */
    this.applied = null;
    /** @type {Reason | ''} */
    this.reason = '';
    this.appliedAt = 0;
    this.start('off');
  }

  /**
   * A new source: `mode` as above; `known`: the source has its own camera (the bundled clip),
   * shown beside the estimate; `error`: why there is no calibrator.
   * @param {Mode} mode
   * @param {{ known?: Pose | null, error?: string }} [source]
   */
  start(mode, { known = null, error = '' } = {}) {
    this.mode = mode;
    this.known = known;
    this.error = error;
    this.status = null;
    this.estimate = null;
    this.applied = null;
    this.reason = '';
    this.appliedAt = 0;
  }

  /**
   * The user's choice: 'auto' (the checkbox ticked) or 'manual' (a camera of their own).
   * @param {'auto' | 'manual'} mode
   */
  setMode(mode) {
    if (this.mode !== 'off') this.mode = mode;
  }

  /**
   * Takes the worker's `{ status, estimate }` for a frame; returns why the estimate should be
   * applied now ('confident', 'timeout', 'moved'), or null.
   * @param {{ status: CalibrationStatus, estimate: CalibrationEstimate | null } | null | undefined} calibration
   * @returns {Reason | null}
   */
  update(calibration) {
    if (!calibration) return null;
    this.status = calibration.status;
    this.estimate = calibration.estimate;
    return this.decide();
  }

  /** @returns {Reason | null} */
  decide() {
    const e = this.estimate;
    if (this.mode !== 'auto' || !e) return null;
    if (!this.applied) {
      if (e.confidence >= APPLY_CONFIDENCE) return 'confident';
      if ((this.status?.frames_seen ?? 0) >= APPLY_AFTER_FRAMES) return 'timeout';
      return null;
    }
    return e.confidence >= APPLY_CONFIDENCE && moved(this.applied, e.camera) ? 'moved' : null;
  }

  /**
   * Records that the tracker now uses `camera` (the estimate), and why.
   * @param {Pose} camera
   * @param {Reason} reason
   */
  markApplied(camera, reason) {
    this.applied = camera;
    this.reason = reason;
    this.appliedAt = this.status?.frames_seen ?? 0;
  }

  /** Whether the calibrator's lines are worth drawing: while it is still looking. */
  looking() {
    return this.mode === 'auto' && !this.applied;
  }

  /** One line about the calibration, for the page. */
  text() {
    if (this.mode === 'off') return this.error ? `Auto-calibration unavailable: ${this.error}` : '';
    const e = this.estimate;
    const seen = this.status?.frames_seen ?? 0;
    if (!e) {
      const what = seen ? `${seen} frames, no straight lane markings measured yet` : 'waiting for frames';
      return this.mode === 'auto'
        ? `Auto-calibrating the camera: ${what} (until then the tracker uses the assumed camera).`
        : `Auto-calibration: ${what}.`;
    }
    // The yaw is the boundaries' crossing until enough frames agree, then the lane's tangent.
    const summary = `${describePose(e.camera)}, confidence ${e.confidence.toFixed(2)}, `
      + `${e.frames_used} of ${e.frames_seen} frames`
      + (e.yaw_from_tangent ? ', yaw from the lane’s tangent' : '');
    if (this.mode === 'auto' && this.applied) {
      const why = {
        confident: `once confidence reached ${APPLY_CONFIDENCE}`,
        timeout: `after ${APPLY_AFTER_FRAMES} frames, below confidence ${APPLY_CONFIDENCE}`,
        moved: 'as the estimate moved',
        chosen: 'as you ticked Auto-calibrate',
        '': '',
      }[this.reason];
      return `Auto-calibrated: ${summary}. The tracker uses ${describePose(this.applied)} `
        + `since frame ${this.appliedAt} (${why}); re-applied when a confident estimate moves by `
        + `${MOVE_DEG}° or ${100 * MOVE_HEIGHT} %.`;
    }
    if (this.mode === 'auto') {
      return `Auto-calibrating: ${summary} (applied at confidence ${APPLY_CONFIDENCE} or after ${APPLY_AFTER_FRAMES} frames).`;
    }
    const own = this.known ? `the clip’s own camera is in use: ${describePose(this.known)}`
      : 'your camera is in use; tick Auto-calibrate to use this one';
    return `Auto-calibration (for comparison): ${summary}; ${own}.`;
  }
}
