// @ts-check
// Frame sources from media the browser decodes: a video (the bundled clip or a file of the
// user's), still images, the webcam. Each yields frames { rgba, width, height, name } in order,
// and null at the end. Frames are read from a canvas the size the tracker works at.

/** Largest frame width handed to a tracker; wider media are scaled down (aspect kept). */
export const MAX_WIDTH = 960;

/**
 * @param {number} width
 * @param {number} height
 */
function workSize(width, height) {
  if (!(width > 0 && height > 0)) throw new Error('the media reports no picture size');
  const s = Math.min(1, MAX_WIDTH / width);
  return { width: Math.round(width * s), height: Math.round(height * s) };
}

/**
 * Reads frames of width x height from images, videos or cameras. With `sideBySide`, a source
 * picture holds the left camera's frame on its left half and the right camera's on its right
 * half; `grab` then returns both.
 */
export class Grabber {
  /**
   * @param {number} width
   * @param {number} height
   * @param {boolean} [sideBySide]
   */
  constructor(width, height, sideBySide = false) {
    this.canvas = new OffscreenCanvas(sideBySide ? 2 * width : width, height);
    const ctx = this.canvas.getContext('2d', { willReadFrequently: true });
    if (!ctx) throw new Error('this browser gives no 2-D context on an OffscreenCanvas');
    this.ctx = ctx;
    this.width = width;
    this.height = height;
    this.sideBySide = sideBySide;
  }

  /** @param {CanvasImageSource} image */
  grab(image) {
    this.ctx.drawImage(image, 0, 0, this.canvas.width, this.height);
    const rgba = this.ctx.getImageData(0, 0, this.width, this.height).data;
    const right = this.sideBySide ? this.ctx.getImageData(this.width, 0, this.width, this.height).data : null;
    return { rgba, right };
  }
}

/**
 * The frame size of a picture, halved across for side-by-side stereo.
 * @param {number} width
 * @param {number} height
 * @param {boolean} sideBySide
 */
export function frameSize(width, height, sideBySide) {
  return workSize(sideBySide ? width / 2 : width, height);
}

/**
 * The label's note on the frame size the tracker gets, when it is not the picture's own.
 * @param {{ width: number, height: number }} size
 * @param {number} width
 * @param {boolean} sideBySide
 */
export function sizeNote(size, width, sideBySide) {
  if (sideBySide) return `, side-by-side stereo of ${size.width}x${size.height}`;
  return size.width !== width ? `, tracked at ${size.width}x${size.height}` : '';
}

/**
 * Waits for `ok` on `target`; rejects on `bad` or after `ms` milliseconds.
 * @param {EventTarget} target
 * @param {string} ok
 * @param {string | null} bad
 * @param {number} ms
 * @param {string} what
 * @returns {Promise<void>}
 */
function once(target, ok, bad, ms, what) {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => { done(); reject(new Error(`${what}: timed out`)); }, ms);
    const onOk = () => { done(); resolve(); };
    const onBad = () => { done(); reject(new Error(what)); };
    function done() {
      clearTimeout(timer);
      target.removeEventListener(ok, onOk);
      if (bad) target.removeEventListener(bad, onBad);
    }
    target.addEventListener(ok, onOk);
    if (bad) target.addEventListener(bad, onBad);
  });
}

/**
 * The video's frame rate, measured: play it muted at quarter speed for a few frames and take the
 * shortest interval between the media times of presented frames (requestVideoFrameCallback).
 * (At full speed a slow compositor presents only some frames: WebKit on a loaded machine
 * showed every 4th, and the rate read as 6.25 instead of 25.) Null when the browser lacks that
 * callback or the video does not play.
 */
/** @param {HTMLVideoElement} video */
async function measureFps(video) {
  if (!('requestVideoFrameCallback' in video)) return null;
  /** @type {number[]} */
  const times = [];
  /** @type {Promise<void>} */
  const measured = new Promise((resolve) => {
    /** @type {VideoFrameRequestCallback} */
    const onFrame = (_, meta) => {
      times.push(meta.mediaTime);
      if (times.length < 8) video.requestVideoFrameCallback(onFrame);
      else resolve();
    };
    video.requestVideoFrameCallback(onFrame);
  });
  try {
    video.playbackRate = 0.25;
    await video.play();
    await Promise.race([measured, new Promise((r) => setTimeout(r, 3000))]);
  } catch {
    return null;
  } finally {
    video.pause();
    video.playbackRate = 1;
  }
  let best = Infinity;
  for (let i = 1; i < times.length; i++) {
    const dt = times[i] - times[i - 1];
    if (dt > 1e-3) best = Math.min(best, dt);
  }
  // Common rates are whole or NTSC (x/1.001) numbers; keep two decimals.
  return Number.isFinite(best) ? Math.round(100 / best) / 100 : null;
}

/**
 * A MediaRecorder file reports an infinite duration until the browser has seen its end.
 * @param {HTMLVideoElement} video
 */
async function knownDuration(video) {
  if (Number.isFinite(video.duration)) return video.duration;
  const changed = once(video, 'durationchange', 'error', 10000, 'the video has no known duration');
  video.currentTime = 1e101;
  await changed;
  video.currentTime = 0;
  return video.duration;
}

/** @type {Record<number, string>} */
const MEDIA_ERRORS = {
  1: 'loading was aborted',
  2: 'a network error stopped the download',
  3: 'the file is corrupt or uses a feature this browser cannot decode',
  4: 'this browser cannot play this format',
};

/**
 * A video processed offline, frame by frame in order: seek to the next frame's time, wait for
 * it to be decoded, read it. Faster or slower than real time as the tracker allows; `fps` is
 * the stepping rate: the video's own, given or measured.
 */
export class VideoSource {
  /**
   * @param {{ url?: string, file?: File | null, name: string, fps?: number | null, camera?: import('../pkg/web/lanepf.js').CameraConfig | null,
   *   sideBySide?: boolean }} source a URL (the bundled clip) or a file of the user's
   */
  constructor({ url, file = null, name, fps = null, camera = null, sideBySide = false }) {
    this.file = file;
    this.sideBySide = sideBySide;
    // (One of the two is given.)
    this.url = url ?? URL.createObjectURL(/** @type {File} */ (file));
    this.name = name;
    this.fps = fps;
    this.camera = camera;
    this.index = 0;
    this.progress = 0;
    this.label = `Video “${name}”`;
  }

  async open() {
    const video = document.createElement('video');
    video.muted = true;
    video.playsInline = true;
    video.preload = 'auto';
    video.src = this.url;
    try {
      await once(video, 'loadeddata', 'error', 15000, 'the video did not load');
    } catch (err) {
      const why = (video.error ? MEDIA_ERRORS[video.error.code] : undefined) ?? (err instanceof Error ? err.message : String(err));
      throw new Error(`Cannot open “${this.name}”: ${why}. Try an H.264 MP4 or a VP9 WebM.`, { cause: err });
    }
    const duration = await knownDuration(video).catch(() => NaN);
    if (!(duration > 0) || !Number.isFinite(duration)) {
      throw new Error(`Cannot open “${this.name}”: it has no known duration (a live stream?).`);
    }
    // Unknown rate: measure it; failing that, read 30 frames per second (and say so).
    this.fpsNote = '';
    let fps = this.fps;
    if (!fps) {
      const measured = await measureFps(video);
      fps = measured ?? 30;
      this.fps = fps;
      this.fpsNote = measured ? ' (measured)' : ' (assumed: the browser did not report its frames)';
    }
    this.video = video;
    this.size = frameSize(video.videoWidth, video.videoHeight, this.sideBySide);
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
    this.frames = Math.max(1, Math.floor(video.duration * fps));
    this.label = `Video “${this.name}”: ${video.videoWidth}x${video.videoHeight}, `
      + `${video.duration.toFixed(1)} s, read at ${fps} frames/s${this.fpsNote}`
      + sizeNote(this.size, video.videoWidth, this.sideBySide);
  }

  restart() {
    this.index = 0;
    this.progress = 0;
  }

  async next() {
    const { video, grabber, size, fps, frames } = this;
    if (!video || !grabber || !size || !fps || frames === undefined) throw new Error(`“${this.name}” is not open`);
    if (this.index >= frames) return null;
    // The middle of frame `index`, so rounding never lands on its neighbour.
    const t = Math.min((this.index + 0.5) / fps, video.duration - 1e-3);
    if (Math.abs(video.currentTime - t) > 1e-6) {
      const seeked = once(video, 'seeked', 'error', 10000, `cannot decode “${this.name}” at ${t.toFixed(2)} s`);
      video.currentTime = t;
      await seeked;
    }
    const { rgba, right } = grabber.grab(video);
    const index = this.index++;
    this.progress = this.index / frames;
    return { rgba, right, width: size.width, height: size.height, name: `${index}`, index, t };
  }

  close() {
    this.video?.removeAttribute('src');
    this.video?.load();
    if (this.file) URL.revokeObjectURL(this.url);
  }
}

/** The name with its camera token (`left`/`right`, or `l`/`r` between separators) as `*`. */
/** @param {string} name */
const cameraless = (name) => name.replace(/left|right/i, '*').replace(/(^|[_.-])[lr](?=[_.-])/i, '$1*');

/**
 * Whether sorted `files` are left/right pairs: names that differ only in their camera token.
 * @param {string[]} names
 */
export function arePairs(names) {
  if (names.length % 2 !== 0) return false;
  for (let k = 0; k < names.length; k += 2) {
    const [a, b] = [names[k], names[k + 1]];
    if (a === b || cameraless(a) === a || cameraless(a) !== cameraless(b)) return false;
  }
  return true;
}

/**
 * Still images (one or a sequence, in file-name order), each a frame. Stereo (`stereo`):
 * images whose names pair up as left and right (`x_left`/`x_right`, `x_l`/`x_r`) are stereo
 * pairs; otherwise every image is a side-by-side picture.
 */
export class ImageSource {
  /**
   * @param {Iterable<File>} files
   * @param {{ camera?: import('../pkg/web/lanepf.js').CameraConfig | null, stereo?: boolean }} [options]
   */
  constructor(files, { camera = null, stereo = false } = {}) {
    this.files = [...files].sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));
    this.camera = camera;
    this.pairs = stereo && arePairs(this.files.map((f) => f.name));
    this.sideBySide = stereo && !this.pairs;
    this.step = this.pairs ? 2 : 1;
    this.index = 0;
    this.progress = 0;
    const n = this.files.length / this.step;
    const what = this.pairs ? 'stereo pair' : this.sideBySide ? 'side-by-side stereo image' : 'image';
    this.label = n === 1 ? `${what} “${this.files[0].name}”` : `${n} ${what}s, “${this.files[0].name}” first`;
    this.label = this.label[0].toUpperCase() + this.label.slice(1);
  }

  /** @param {File} file */
  async decode(file) {
    try {
      return await createImageBitmap(file);
    } catch {
      throw new Error(`Cannot decode “${file.name}”: not an image this browser reads (JPEG, PNG, WebP).`);
    }
  }

  async open() {
    const first = await this.decode(this.files[0]);
    this.size = frameSize(first.width, first.height, this.sideBySide);
    this.first = first;
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
  }

  restart() {
    this.index = 0;
    this.progress = 0;
  }

  /**
   * Reads image `k`, which must have the first image's size.
   * @param {number} k
   */
  async read(k) {
    const { size, grabber } = this;
    if (!size || !grabber) throw new Error('the images are not open');
    const file = this.files[k];
    const bitmap = k === 0 && this.first ? this.first : await this.decode(file);
    const expected = frameSize(bitmap.width, bitmap.height, this.sideBySide);
    if (expected.width !== size.width || expected.height !== size.height) {
      throw new Error(`“${file.name}” is ${bitmap.width}x${bitmap.height}; a sequence must keep `
        + `the size of its first image (${this.files[0].name})`);
    }
    const out = grabber.grab(bitmap);
    if (bitmap !== this.first) bitmap.close();
    return out;
  }

  async next() {
    if (this.index >= this.files.length) return null;
    const k = this.index;
    const { rgba, right } = await this.read(k);
    const { width, height } = /** @type {{ width: number, height: number }} */ (this.size);
    const frame = { rgba, right, width, height, name: this.files[k].name };
    if (this.pairs) frame.right = (await this.read(k + 1)).rgba;
    this.index += this.step;
    this.progress = this.index / this.files.length;
    return { ...frame, index: k / this.step };
  }

  close() {
    this.first?.close();
  }
}

/** The webcam, live: each frame is whatever the camera shows when the tracker is ready. */
export class WebcamSource {
  constructor(camera = null) {
    this.camera = camera;
    this.index = 0;
    this.progress = null;
    this.label = 'Webcam';
  }

  async open() {
    if (!navigator.mediaDevices?.getUserMedia) {
      throw new Error('This browser offers no camera access here (it needs https or localhost).');
    }
    try {
      this.stream = await navigator.mediaDevices.getUserMedia({
        video: { width: { ideal: 640 }, height: { ideal: 480 } }, audio: false,
      });
    } catch (err) {
      const name = err instanceof Error ? err.name : '';
      if (name === 'NotAllowedError' || name === 'SecurityError') {
        throw new Error('Camera permission was refused. Allow the camera for this page and choose Webcam again.', { cause: err });
      }
      if (name === 'NotFoundError' || name === 'OverconstrainedError') {
        throw new Error('No camera was found on this device.', { cause: err });
      }
      throw new Error(`The camera could not be started: ${err instanceof Error ? err.message : err}`, { cause: err });
    }
    const video = document.createElement('video');
    video.muted = true;
    video.playsInline = true;
    const stream = this.stream;
    video.srcObject = stream;
    await video.play();
    if (!video.videoWidth) await once(video, 'resize', null, 5000, 'the camera sent no picture');
    this.video = video;
    // (A webcam is one camera: never side by side.)
    this.size = frameSize(video.videoWidth, video.videoHeight, false);
    this.grabber = new Grabber(this.size.width, this.size.height);
    const track = stream.getVideoTracks()[0];
    this.label = `Webcam “${track?.label || 'camera'}”: ${video.videoWidth}x${video.videoHeight}`;
  }

  restart() {
    this.index = 0;
  }

  async next() {
    const { video, grabber, size } = this;
    if (!video || !grabber || !size) throw new Error('the webcam is not open');
    const { rgba } = grabber.grab(video);
    const index = this.index++;
    const t = performance.now() / 1000;
    return { rgba, width: size.width, height: size.height, name: `${index}`, index, t };
  }

  close() {
    for (const t of this.stream?.getTracks() ?? []) t.stop();
  }
}
