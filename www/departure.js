// @ts-check
// Lane-departure status: how far the car's sides are from the ego lane's boundaries and the
// time to line crossing (TLC) at the current lateral speed.
//
// The car is CAR_HALF_WIDTH_M either side of the camera. Lateral speed (positive left) is
// -v sin(psi) from the car's speed v and the lane's heading psi when the speed is known, else
// the rate of change of the estimated offset between frames.

export const CAR_HALF_WIDTH_M = 0.9;
/** Below this TLC (s) the status warns. */
export const WARN_TLC_S = 1.0;

export class Departure {
  constructor() {
    /** The last valid estimate's offset and time (null: none). */
    /** @type {{ q: number, t: number | null } | null} */
    this.previous = null;
  }

  reset() {
    this.previous = null;
  }

  /**
   * `estimate`: a valid estimate; `t`: the frame's time in seconds; `speed`: m/s or null.
   * Returns { text, warn } or null when there is nothing to say.
   * @param {import('../pkg/web/lanepf.js').LaneEstimate | null | undefined} estimate
   * @param {number | null} t
   * @param {number | null} speed
   */
  update(estimate, t, speed) {
    if (!estimate?.valid || !(estimate.lane_width_m > 0)) {
      this.previous = null;
      return null;
    }
    const q = estimate.lateral_offset_m;
    const half = estimate.lane_width_m / 2;
    const toLeft = half - q - CAR_HALF_WIDTH_M;
    const toRight = half + q - CAR_HALF_WIDTH_M;
    let lateral = null;
    const prev = this.previous;
    if (typeof speed === 'number' && Number.isFinite(speed)) lateral = -speed * Math.sin(estimate.heading_rad);
    else if (prev && typeof t === 'number' && Number.isFinite(t) && prev.t !== null && t > prev.t) {
      lateral = (q - prev.q) / (t - prev.t);
    }
    this.previous = { q, t };
    if (toLeft < 0 || toRight < 0) {
      return { text: `crossing the ${toLeft < 0 ? 'left' : 'right'} line`, warn: true };
    }
    const side = lateral !== null && lateral > 0 ? 'left' : 'right';
    const distance = side === 'left' ? toLeft : toRight;
    const tlc = lateral && Math.abs(lateral) > 1e-3 ? distance / Math.abs(lateral) : Infinity;
    const text = `in lane · ${toLeft.toFixed(2)} m to the left line, ${toRight.toFixed(2)} m to the right`
      + (Number.isFinite(tlc) && tlc < 10 ? ` · ${tlc.toFixed(1)} s to the ${side} line` : '');
    return { text, warn: tlc < WARN_TLC_S };
  }
}
