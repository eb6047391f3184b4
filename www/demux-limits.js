// @ts-check
// What the demuxers accept of a container's tables and clocks, so that a small or damaged
// file cannot make them allocate gigabytes or report a frame rate of 0: at most MAX_SAMPLES
// frames (9 h at 30 fps), every frame at least one byte, all of them inside the file, a
// length of at most MAX_DURATION_S and a frame rate between MIN_FPS and MAX_FPS.

/** Most frames a video track may have. */
export const MAX_SAMPLES = 1_000_000;
/** Longest accepted video, seconds (one week). */
export const MAX_DURATION_S = 7 * 24 * 3600;
/** Slowest accepted frame rate: a frame every 100 s. */
export const MIN_FPS = 0.01;
/** Fastest accepted frame rate. */
export const MAX_FPS = 1000;

/**
 * Throws unless `count` frames are few enough.
 * @param {number} count
 * @param {string} where
 */
export function checkSampleCount(count, where) {
  if (count > MAX_SAMPLES) {
    throw new Error(`${where} declares ${count} frames, more than the ${MAX_SAMPLES} this reader accepts`);
  }
}

/**
 * Throws unless `seconds` is a length of time a video can have.
 * @param {number} seconds
 * @param {string} what
 */
export function checkDuration(seconds, what) {
  if (!(Number.isFinite(seconds) && seconds >= 0 && seconds <= MAX_DURATION_S)) {
    throw new Error(`${what} (${seconds} s) is not a video's length: it must be 0 to ${MAX_DURATION_S} s (the file is corrupt)`);
  }
}

/**
 * Throws unless `fps` (null: unknown) is a frame rate a video can have.
 * @param {number | null} fps
 * @param {string} what
 */
export function checkRate(fps, what) {
  if (fps !== null && !(fps >= MIN_FPS && fps <= MAX_FPS)) {
    throw new Error(`${what} gives a frame rate of ${fps} fps; a video's is ${MIN_FPS} to ${MAX_FPS} (the file is corrupt)`);
  }
}
