// `lanepf/frames`: frames from what a page has (ImageData, ImageBitmap, VideoFrame, a <video>,
// a canvas, an <img>) as the RGBA bytes a tracker takes, and `FrameReader`, which reads a
// playing <video> once per presented frame (requestVideoFrameCallback).
// Plain JavaScript, no wasm: it works on the main thread and in a worker (there without <video>
// and <img>, which workers do not have).

/** An Error whose `name` is `LanepfInputError`, like the ones the wasm module throws. */
function inputError(message) {
  const e = new Error(message);
  e.name = 'LanepfInputError';
  return e;
}

const isWhole = (n) => Number.isInteger(n) && n >= 1 && n <= 16384;
const has = (name) => typeof globalThis[name] === 'function';

/** Whether `x` is an `ImageData` or a plain `{ data, width, height }` of RGBA bytes. */
function isRgbaFrame(x) {
  return x != null && typeof x === 'object'
    && (x.data instanceof Uint8ClampedArray || x.data instanceof Uint8Array)
    && Number.isInteger(x.width) && Number.isInteger(x.height);
}

/**
 * The size a drawable source shows, in pixels: [width, height], or null when `source` is not
 * one this module can draw.
 */
export function sourceSize(source) {
  if (source == null || typeof source !== 'object') return null;
  if (has('VideoFrame') && source instanceof VideoFrame) return [source.displayWidth, source.displayHeight];
  if (has('HTMLVideoElement') && source instanceof HTMLVideoElement) return [source.videoWidth, source.videoHeight];
  if (has('HTMLImageElement') && source instanceof HTMLImageElement) return [source.naturalWidth, source.naturalHeight];
  if ((has('ImageBitmap') && source instanceof ImageBitmap)
    || (has('HTMLCanvasElement') && source instanceof HTMLCanvasElement)
    || (has('OffscreenCanvas') && source instanceof OffscreenCanvas)) {
    return [source.width, source.height];
  }
  if (isRgbaFrame(source)) return [source.width, source.height];
  return null;
}

/** A 2-D canvas of `width` x `height` (an OffscreenCanvas where there is one), reused. */
class Scratch {
  constructor() { this.canvas = null; this.ctx = null; }

  context(width, height) {
    if (!this.canvas) {
      if (has('OffscreenCanvas')) this.canvas = new OffscreenCanvas(width, height);
      else if (typeof document !== 'undefined') this.canvas = document.createElement('canvas');
      else throw inputError('readFrame: this context has no canvas to draw the frame on');
      this.ctx = this.canvas.getContext('2d', { willReadFrequently: true });
    }
    if (this.canvas.width !== width) this.canvas.width = width;
    if (this.canvas.height !== height) this.canvas.height = height;
    return this.ctx;
  }
}

const shared = new Scratch();

/**
 * The RGBA pixels of `source` as an `ImageData` (of `options.width` x `options.height` when
 * given: the source is scaled to it, e.g. to the tracker's camera size; else of the source's
 * own size).
 *
 * `source`: an `ImageData` or `{ data, width, height }` (returned as it is when no other size is
 * asked for), an `ImageBitmap`, a `VideoFrame`, an `HTMLVideoElement` (its current frame), an
 * `HTMLCanvasElement` or `OffscreenCanvas`, an `HTMLImageElement`.
 *
 * Throws an Error named `LanepfInputError` for anything else, a video with no frame yet, an image
 * not yet loaded, a closed VideoFrame or a bad size.
 */
export function readFrame(source, options = {}, scratch = shared) {
  const size = sourceSize(source);
  if (!size) {
    throw inputError('readFrame: the source must be an ImageData, { data, width, height }, '
      + `ImageBitmap, VideoFrame, <video>, <canvas>, OffscreenCanvas or <img>, not ${describe(source)}`);
  }
  if (has('HTMLVideoElement') && source instanceof HTMLVideoElement && source.readyState < 2) {
    throw inputError('readFrame: the <video> has no frame yet (readyState < HAVE_CURRENT_DATA): '
      + 'wait for its loadeddata event');
  }
  const [sw, sh] = size;
  if (!isWhole(sw) || !isWhole(sh)) {
    throw inputError(`readFrame: the source is ${sw}x${sh} pixels: nothing to read `
      + '(an image not loaded yet, a closed VideoFrame?)');
  }
  const width = options.width ?? sw;
  const height = options.height ?? sh;
  if (!isWhole(width) || !isWhole(height)) {
    throw inputError(`readFrame: the size ${width}x${height} must be whole numbers from 1 to 16384`);
  }
  if (isRgbaFrame(source)) {
    if (source.data.length !== sw * sh * 4) {
      throw inputError(`readFrame: data has ${source.data.length} bytes but a ${sw}x${sh} `
        + `RGBA frame needs ${sw * sh * 4}`);
    }
    if (width === sw && height === sh) return source;
    // Scaled: staged on a canvas of its own size, then drawn at the size asked for.
    const pixels = source.data instanceof Uint8ClampedArray
      ? source.data
      : new Uint8ClampedArray(source.data.buffer, source.data.byteOffset, source.data.length);
    const stage = new Scratch().context(sw, sh);
    stage.putImageData(has('ImageData') && source instanceof ImageData ? source : new ImageData(pixels, sw, sh), 0, 0);
    const ctx = scratch.context(width, height);
    ctx.clearRect(0, 0, width, height);
    ctx.drawImage(stage.canvas, 0, 0, width, height);
    return ctx.getImageData(0, 0, width, height);
  }
  const ctx = scratch.context(width, height);
  ctx.drawImage(source, 0, 0, width, height);
  return ctx.getImageData(0, 0, width, height);
}

/** What a value is, for a message. */
function describe(x) {
  if (x === null) return 'null';
  if (typeof x !== 'object') return typeof x;
  return x.constructor?.name ? `a ${x.constructor.name}` : 'an object';
}

/**
 * Reads a playing `<video>` (or a canvas something draws into) frame by frame: `start(onFrame)`
 * calls `onFrame(frame, info)` once per frame the browser presents (requestVideoFrameCallback;
 * requestAnimationFrame where a browser or a canvas has none). A promise returned by `onFrame`
 * is awaited before the next frame is read, so a slow consumer skips frames rather than
 * queueing them. `frame` is an ImageData of the reader's size, a new one every time (its
 * buffer can be transferred). `start` returns a promise that resolves when `stop()` is called
 * or the video ends, and rejects with the first error `onFrame` or a read throws.
 */
export class FrameReader {
  /**
   * @param source an HTMLVideoElement, HTMLCanvasElement or OffscreenCanvas
   * @param options `{ width, height }`: the size to read at (default: the source's)
   */
  constructor(source, options = {}) {
    const size = sourceSize(source);
    if (!size || isRgbaFrame(source) || (has('VideoFrame') && source instanceof VideoFrame)
      || (has('ImageBitmap') && source instanceof ImageBitmap)
      || (has('HTMLImageElement') && source instanceof HTMLImageElement)) {
      throw inputError('FrameReader: the source must be a <video>, <canvas> or OffscreenCanvas, '
        + `not ${describe(source)} (use readFrame for a single image)`);
    }
    this.source = source;
    this.options = { width: options.width, height: options.height };
    this.scratch = new Scratch();
    this.frames = 0;
    this.run = null;
  }

  /** Whether frames are timed by requestVideoFrameCallback (a video in a browser with it). */
  get usesVideoFrameCallback() {
    return typeof this.source.requestVideoFrameCallback === 'function';
  }

  /** The frame showing now, as an ImageData of the reader's size. */
  read() {
    return readFrame(this.source, this.options, this.scratch);
  }

  /** Calls `onFrame(frame, { mediaTime, frames })` for every presented frame until stopped. */
  start(onFrame) {
    if (typeof onFrame !== 'function') {
      return Promise.reject(inputError('FrameReader.start: onFrame must be a function'));
    }
    this.stop();
    const run = { handle: null, done: null };
    this.run = run;
    const finished = new Promise((resolve, reject) => { run.done = { resolve, reject }; });
    const video = this.usesVideoFrameCallback;
    const end = (error) => {
      if (this.run !== run) return;
      if (error) run.done.reject(error); // before stop() resolves it
      this.stop();
    };
    const onEnded = () => end(null);
    if (video) this.source.addEventListener('ended', onEnded);
    run.cleanup = () => {
      if (video) this.source.removeEventListener('ended', onEnded);
      if (run.handle?.video !== undefined) this.source.cancelVideoFrameCallback?.(run.handle.video);
      if (run.handle?.raf !== undefined) cancelAnimationFrame(run.handle.raf);
      run.handle = null;
      run.done.resolve();
    };
    const next = () => {
      if (this.run !== run) return;
      run.handle = video
        ? { video: this.source.requestVideoFrameCallback(tick) }
        : { raf: requestAnimationFrame((now) => tick(now, null)) };
    };
    const tick = async (now, metadata) => {
      run.handle = null;
      if (this.run !== run) return;
      try {
        const frame = this.read();
        this.frames += 1;
        const mediaTime = metadata?.mediaTime ?? this.source.currentTime ?? now / 1000;
        await onFrame(frame, { mediaTime, frames: this.frames });
      } catch (e) {
        end(e);
        return;
      }
      next();
    };
    next();
    return finished;
  }

  /** Stops reading (a frame being handled finishes); the promise of `start` resolves. */
  stop() {
    const run = this.run;
    this.run = null;
    run?.cleanup();
  }
}
