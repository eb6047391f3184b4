// @ts-check
// Playback at the source's own frame rate. A frame starts when it is due: one frame interval
// (1 / the source's frames per second) after the one before, on a schedule anchored at the
// first frame, so the rate is exact on average even though a timer wakes a little late.
// When the tracker cannot keep up (a frame starts more than one interval late), the schedule
// is re-anchored there: playback slows down instead of skipping frames, so every frame is still
// tracked (a tracker's output does not depend on the machine's speed), and `describe()` says so.
// Sources without a frame rate (still images, the webcam) are not paced.

/** The rate is measured over the frames started in the last WINDOW_MS. */
const WINDOW_MS = 2000;
/** Slower than this share of the source's rate counts as not keeping up. */
const KEEP_UP = 0.9;

export class Pacer {
  constructor() {
    /** Frames per second of the source (null: not paced). */
    /** @type {number | null} */
    this.fps = null;
    this.live = false;
    /** When the next frame is due (performance.now()), null: at once. */
    /** @type {number | null} */
    this.due = null;
    /** When the frames of the last WINDOW_MS started. */
    /** @type {number[]} */
    this.starts = [];
    /** The time the last frames took from start to drawing (ms). */
    /** @type {number[]} */
    this.work = [];
    this.start(null);
  }

  /**
   * A new schedule for a source of `fps` frames per second (null: not paced, e.g. images);
   * `live`: frames come from a camera as they are taken.
   * @param {number | null | undefined} fps
   * @param {{ live?: boolean }} [options]
   */
  start(fps, { live = false } = {}) {
    this.fps = typeof fps === 'number' && Number.isFinite(fps) && fps > 0 ? fps : null;
    this.live = live;
    this.reset();
  }

  /** Forgets the schedule (after a pause or a step by hand): the next frame starts at once. */
  reset() {
    this.due = null;
    this.starts = [];
    this.work = [];
  }

  get interval() {
    return this.fps ? 1000 / this.fps : null;
  }

  /**
   * Milliseconds from `now` (performance.now()) until the next frame is due; 0: start it now.
   * @param {number} now
   */
  wait(now) {
    return !this.interval || this.due === null ? 0 : Math.max(0, this.due - now);
  }

  /**
   * A frame starts at `now`: the next one is due an interval later.
   * @param {number} now
   */
  begin(now) {
    const interval = this.interval;
    if (interval) {
      // More than one interval late: the tracker could not keep up; slow down from here.
      this.due = this.due === null || now - this.due > interval ? now + interval : this.due + interval;
    }
    this.starts.push(now);
    while (this.starts.length > 2 && now - this.starts[0] > WINDOW_MS) this.starts.shift();
  }

  /**
   * The frame started last took `ms` from its start to its drawing.
   * @param {number} ms
   */
  end(ms) {
    this.work.push(ms);
    if (this.work.length > 30) this.work.shift();
  }

  /** Frames per second started over the last two seconds; null before there are enough. */
  rate() {
    const n = this.starts.length;
    if (n < 5) return null;
    const span = this.starts[n - 1] - this.starts[0];
    return span > 0 ? (1000 * (n - 1)) / span : null;
  }

  /** The mean time the last frames took (ms), or null. (The mean: a few slow frames count.) */
  workMs() {
    if (!this.work.length) return null;
    return this.work.reduce((a, v) => a + v, 0) / this.work.length;
  }

  /** Whether playback is measurably slower than the source's rate. */
  behind() {
    const rate = this.rate();
    const n = this.starts.length;
    return !!(this.fps && rate !== null && this.starts[n - 1] - this.starts[0] >= 1000 && rate < KEEP_UP * this.fps);
  }

  /** One line for the page: the rate played at, and why it is slower than the source's. */
  describe(what = 'the source') {
    const rate = this.rate();
    const played = rate === null ? '' : `${rate.toFixed(1)} frames/s`;
    if (this.live) return played ? `Live: ${played}` : '';
    if (!this.fps || !this.interval) return played ? `Playing as fast as the tracker goes: ${played} (${what} has no frame rate)` : '';
    if (rate === null) return `Playing at ${what}’s ${this.fps} frames/s`;
    if (!this.behind()) return `Playing at ${played}: ${what}’s rate is ${this.fps}`;
    const work = this.workMs();
    const why = work === null ? '' : `: a frame takes ${work.toFixed(0)} ms here, ${what} shows one every ${this.interval.toFixed(0)} ms`;
    return `Slowed down to ${played}, ${(rate / this.fps).toFixed(2)}× ${what}’s ${this.fps}${why} (every frame is still tracked)`;
  }
}
